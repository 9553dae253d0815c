//! `modelDescription.xml` declares what the binary implements: the same guid, the same
//! variables (name, value reference, type, causality) in the same order, and the parameters'
//! start values are the instance's defaults.

use bwc_contact::{law_variables, Instance, Type, GUID, VARIABLES};
use std::path::Path;

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
    let all: Vec<_> = VARIABLES
        .iter()
        .chain(law_variables().iter().map(|l| &l.variable))
        .collect();
    assert_eq!(declared.len(), all.len());
    let fresh = Instance::new();
    for (text, &v) in declared.iter().zip(&all) {
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

const BEGIN: &str = "    <!-- law variables:";
const END: &str = "    <!-- end of law variables -->";

/// The `modelDescription.xml` entries of the element laws' parameters, as the registry gives
/// them.
fn law_entries() -> String {
    let escape = |s: &str| {
        s.replace('&', "&amp;")
            .replace('<', "&lt;")
            .replace('>', "&gt;")
            .replace('"', "&quot;")
    };
    let mut out = String::from(
        "    <!-- law variables: generated from bw_models::ELEMENT_LAWS by \
         crates/fmu/tests/description.rs, which rewrites them when BWC_WRITE_MODEL_DESCRIPTION \
         is set -->\n",
    );
    for (i, l) in law_variables().iter().enumerate() {
        let v = &l.variable;
        out += &format!(
            "    <!-- {index} -->\n    <ScalarVariable name=\"{name}\" valueReference=\"{vr}\" \
             causality=\"parameter\" variability=\"fixed\" initial=\"exact\"\n      \
             description=\"{description}\">\n      <Real start=\"{start:?}\"/>\n    \
             </ScalarVariable>\n",
            index = VARIABLES.len() + i + 1,
            name = v.name,
            vr = v.vr,
            description = escape(v.description),
            start = l.start,
        );
    }
    out + END
}

/// The law variables' entries are the registry's (an XML comment holds no double hyphen, so
/// the command to rewrite them is in the failure's message, not in the file): a new element law in `bw_models` is
/// declared here by regenerating them.
#[test]
fn the_law_variables_are_the_registrys() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("modelDescription.xml");
    let xml = std::fs::read_to_string(&path).unwrap();
    let (begin, end) = (xml.find(BEGIN).unwrap(), xml.find(END).unwrap());
    let made = law_entries();
    if std::env::var_os("BWC_WRITE_MODEL_DESCRIPTION").is_some() {
        let fresh = format!("{}{made}{}", &xml[..begin], &xml[end + END.len()..]);
        std::fs::write(&path, fresh).unwrap();
        return;
    }
    assert!(
        xml[begin..end + END.len()] == made,
        "{} is stale: rewrite its law variables with `BWC_WRITE_MODEL_DESCRIPTION=1 cargo test \
         -p bwc-fmu --test description` and commit it",
        path.display()
    );
    let model = VARIABLES.iter().find(|v| v.name == "model").unwrap();
    for (i, spec) in bw_models::ELEMENT_LAWS.iter().enumerate().skip(2) {
        let named = format!("{i}: {}", spec.title);
        assert!(
            model.description.contains(&named),
            "{named}: {}",
            model.description
        );
    }
}
