//! Laws from materials through the C ABI: the table by name, and a pair's law as the Rust
//! library derives it, NaN where a quantity does not exist; bad bodies named.

use bw_models::materials::{material, Body, MaterialPair};
use bwc::*;
use std::ffi::{CStr, CString};

fn message() -> String {
    // SAFETY: the library's last error is a NUL-terminated string.
    unsafe { CStr::from_ptr(bwc_last_error()) }
        .to_str()
        .unwrap()
        .to_owned()
}

fn named(name: &str) -> BwcMaterial {
    let name = CString::new(name).unwrap();
    let mut m = BwcMaterial {
        youngs_modulus: 0.0,
        poisson: 0.0,
        density: 0.0,
        yield_strength: 0.0,
    };
    // SAFETY: live pointers.
    assert_eq!(
        unsafe { bwc_material(name.as_ptr(), &mut m) },
        BwcStatus::Ok,
        "{}",
        message()
    );
    m
}

fn pair(a: &BwcBody, b: &BwcBody) -> Result<BwcMaterialPair, (BwcStatus, String)> {
    let mut out = BwcMaterialPair {
        e_star: 0.0,
        r_star: 0.0,
        m_star: 0.0,
        k: 0.0,
        p_y: 0.0,
        yields_first: 9,
        delta_y: 0.0,
        force_y: 0.0,
        a_y: 0.0,
        v_y: 0.0,
        t_b: 0.0,
    };
    // SAFETY: live pointers.
    match unsafe { bwc_materials(a, b, &mut out) } {
        BwcStatus::Ok => Ok(out),
        s => Err((s, message())),
    }
}

#[test]
fn a_pairs_law_is_the_librarys() {
    let sphere = BwcBody {
        material: named("alumina"),
        radius: 2.5e-3,
        mass: f64::NAN,
        yield_pressure: f64::NAN,
    };
    assert!(
        sphere.material.yield_strength.is_nan(),
        "alumina is elastic"
    );
    let plate = BwcBody {
        material: named("aluminium-6061-t6"),
        radius: f64::INFINITY,
        mass: f64::NAN,
        yield_pressure: f64::NAN,
    };
    let got = pair(&sphere, &plate).unwrap();
    let want = MaterialPair::new(
        &Body::sphere(material("alumina").unwrap().material, 2.5e-3),
        &Body::flat(material("aluminium-6061-t6").unwrap().material),
    )
    .unwrap();
    assert_eq!(
        (got.k, got.e_star, got.m_star),
        (want.k, want.e_star, want.m_star)
    );
    assert_eq!((Some(got.delta_y), Some(got.v_y)), (want.delta_y, want.v_y));
    assert_eq!(got.yields_first, 2);
    // Two elastic bodies: no yield, NaN for its quantities.
    let glass = BwcBody {
        material: named("glass-soda-lime"),
        ..sphere
    };
    let elastic = pair(
        &glass,
        &BwcBody {
            material: named("glass-soda-lime"),
            ..plate
        },
    )
    .unwrap();
    assert_eq!(elastic.yields_first, 0);
    assert!(elastic.p_y.is_nan() && elastic.delta_y.is_nan() && elastic.v_y.is_nan());
}

#[test]
fn bad_bodies_and_names_are_said() {
    let name = CString::new("unobtainium").unwrap();
    let mut m = named("ptfe");
    // SAFETY: live pointers.
    let status = unsafe { bwc_material(name.as_ptr(), &mut m) };
    assert!(
        status == BwcStatus::InvalidArgument && message().contains("alumina"),
        "{}",
        message()
    );
    let mut soft = named("ptfe");
    soft.youngs_modulus = 0.5; // GPa, not Pa
    let body = BwcBody {
        material: soft,
        radius: 1e-3,
        mass: f64::NAN,
        yield_pressure: f64::NAN,
    };
    let flat = BwcBody {
        material: named("ptfe"),
        radius: f64::INFINITY,
        ..body
    };
    let (s, m) = pair(&body, &flat).unwrap_err();
    assert!(
        s == BwcStatus::InvalidArgument && m.contains("body 1") && m.contains("GPa"),
        "{m}"
    );
    let (s, m) = pair(&flat, &flat).unwrap_err();
    assert!(
        s == BwcStatus::InvalidArgument && m.contains("two flats"),
        "{m}"
    );
}
