//! `modelDescription.xml` declares what the binary implements: the same guid, the same
//! variables (name, value reference, type, causality) in the same order, and the parameters'
//! start values are the instance's defaults.

use bwc_contact::{Instance, Type, GUID, VARIABLES};

/// The value of `attribute="..."` in `tag`.
fn attribute<'a>(tag: &'a str, attribute: &str) -> Option<&'a str> {
    let start = tag.find(&format!(" {attribute}=\""))? + attribute.len() + 3;
    let len = tag[start..].find('"')?;
    Some(&tag[start..start + len])
}

#[test]
fn the_model_description_declares_the_binary() {
    let xml = include_str!("../modelDescription.xml");
    let root = &xml[xml.find("<fmiModelDescription").unwrap()..];
    assert_eq!(attribute(root, "guid"), Some(GUID));
    let declared: Vec<&str> = xml.split("<ScalarVariable").skip(1).collect();
    assert_eq!(declared.len(), VARIABLES.len());
    let fresh = Instance::new();
    for (text, v) in declared.iter().zip(VARIABLES) {
        let head = &text[..text.find('>').unwrap()];
        assert_eq!(attribute(head, "name"), Some(v.name));
        assert_eq!(
            attribute(head, "valueReference"),
            Some(v.vr.to_string().as_str())
        );
        assert_eq!(
            attribute(head, "causality"),
            Some(v.causality),
            "{}",
            v.name
        );
        let body = &text[text.find('>').unwrap() + 1..];
        let kind = match v.kind {
            Type::Real => "<Real",
            Type::Integer => "<Integer",
            Type::Boolean => "<Boolean",
        };
        assert!(body.trim_start().starts_with(kind), "{}: {body}", v.name);
        if v.causality == "parameter" {
            let start: f64 = attribute(body, "start").unwrap().parse().unwrap();
            let default = match v.kind {
                Type::Real => fresh.get_real(v.vr).unwrap(),
                _ => f64::from(fresh.get_integer(v.vr).unwrap()),
            };
            assert_eq!(start, default, "{}", v.name);
        }
    }
}
