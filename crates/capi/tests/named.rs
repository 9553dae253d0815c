//! Contact elements by the law's name through the C ABI: the same element as the one from a
//! law handle, every registered law, and what is wrong with a name said.

use bw_models::{ElementSettings, ELEMENT_LAWS};
use bwc::*;
use std::ffi::{CStr, CString};
use std::ptr::{null, null_mut};

fn message() -> String {
    // SAFETY: the library's last error is a NUL-terminated string.
    unsafe { CStr::from_ptr(bwc_last_error()) }
        .to_str()
        .unwrap()
        .to_owned()
}

/// A contact of `law` with `params`, or the status and message.
fn named(law: &str, params: &[(&str, f64)]) -> Result<BwcContact, (BwcStatus, String)> {
    let law = CString::new(law).unwrap();
    let names: Vec<CString> = params
        .iter()
        .map(|(n, _)| CString::new(*n).unwrap())
        .collect();
    let pointers: Vec<*const std::ffi::c_char> = names.iter().map(|n| n.as_ptr()).collect();
    let values: Vec<f64> = params.iter().map(|(_, v)| *v).collect();
    let mut out = 0;
    // SAFETY: every pointer is live for the call, with `params.len()` elements.
    let status = unsafe {
        bwc_contact_new_named(
            law.as_ptr(),
            pointers.as_ptr(),
            values.as_ptr(),
            params.len(),
            null(),
            &mut out,
        )
    };
    match status {
        BwcStatus::Ok => Ok(out),
        s => Err((s, message())),
    }
}

fn force_after(contact: BwcContact, steps: usize) -> f64 {
    let mut step = BwcStep {
        force: 0.0,
        impulse: 0.0,
        work: 0.0,
        separated_at: 0.0,
        began_at: 0.0,
    };
    for _ in 0..steps {
        // SAFETY: `step` is writable.
        assert_eq!(
            unsafe { bwc_contact_advance(contact, 1e-6, -1.0, -1.0, &mut step) },
            BwcStatus::Ok,
            "{}",
            message()
        );
    }
    step.force
}

/// Table 4's BWSHCCM by name steps as the same law from a law handle, bit for bit.
#[test]
fn a_law_by_name_is_the_law_from_its_handle() {
    let l = bw_models::published::CROSS_BWSHCCM;
    let params = super::errors::shccm();
    let (mut law, mut by_handle) = (0, 0);
    // SAFETY: live pointers.
    unsafe {
        assert_eq!(bwc_law_new(&params, &mut law), BwcStatus::Ok);
        assert_eq!(bwc_contact_new(law, null(), &mut by_handle), BwcStatus::Ok);
    }
    let values = [
        ("k", l.k),
        ("c", l.c),
        ("n", l.n),
        ("p", l.p),
        ("alpha", l.alpha),
        ("beta", l.beta),
        ("gamma", l.gamma),
        ("A", l.a),
    ];
    let by_name = named("shccm", &values).unwrap();
    let (a, b) = (force_after(by_handle, 100), force_after(by_name, 100));
    assert!(a > 0.0 && a == b, "{a} vs {b}");
    for c in [by_handle, by_name] {
        assert_eq!(bwc_contact_free(c), BwcStatus::Ok);
    }
    assert_eq!(bwc_law_free(law), BwcStatus::Ok);
}

/// Every law of the registry builds by name from its start values; its state has the spec's length and its force
/// is the Rust element's.
#[test]
fn every_registered_law_builds_by_name() {
    for spec in ELEMENT_LAWS {
        let params: Vec<(&str, f64)> = spec.params.iter().map(|p| (p.name, p.start)).collect();
        let contact = named(spec.name, &params).unwrap_or_else(|e| panic!("{}: {e:?}", spec.name));
        let force = force_after(contact, 20);
        let mut rust =
            bw_models::AnyContactElement::of_law(spec.name, &params, ElementSettings::default())
                .unwrap();
        for _ in 0..20 {
            rust.advance(1e-6, -1.0, -1.0).unwrap();
        }
        assert_eq!(force, rust.force(), "{}", spec.name);
        let (mut state, mut len) = ([0.0; 3], 0);
        // SAFETY: room for 3 doubles and a writable length.
        let status = unsafe { bwc_contact_state(contact, state.as_mut_ptr(), 3, &mut len) };
        assert_eq!(
            (status, len),
            (BwcStatus::Ok, spec.states.len()),
            "{}",
            spec.name
        );
        assert_eq!(bwc_contact_free(contact), BwcStatus::Ok);
    }
}

#[test]
fn what_is_wrong_with_a_name_is_said() {
    let invalid = BwcStatus::InvalidArgument;
    let (s, m) = named("hertz", &[]).unwrap_err();
    assert!(
        s == invalid && m.contains("`hertz`") && m.contains("thornton"),
        "{m}"
    );
    let (s, m) = named("kelvin-voigt", &[("k", 1e5)]).unwrap_err();
    assert!(
        s == invalid && m.contains("`c` is missing") && m.contains("k, c"),
        "{m}"
    );
    let (s, m) = named("kelvin-voigt", &[("k", 1e5), ("c", -1.0)]).unwrap_err();
    assert!(s == invalid && m.contains("c >= 0 (N s/m)"), "{m}");
    let (s, m) = named("thornton", &[("k", 1e5), ("delta_y", 1e-6), ("R", 1.0)]).unwrap_err();
    assert!(
        s == invalid && m.contains("`R` is not one of its parameters"),
        "{m}"
    );
    let mut out = 0;
    // SAFETY: NULL pointers, which the function refuses.
    let status = unsafe { bwc_contact_new_named(null(), null(), null(), 0, null(), &mut out) };
    assert!(
        status == BwcStatus::NullPointer && message().contains("`law`"),
        "{}",
        message()
    );
    let law = CString::new("kelvin-voigt").unwrap();
    // SAFETY: NULL arrays with a count, which the function refuses.
    let status =
        unsafe { bwc_contact_new_named(law.as_ptr(), null(), null(), 2, null(), &mut out) };
    assert!(
        status == BwcStatus::NullPointer && message().contains("`names`"),
        "{}",
        message()
    );
    // SAFETY: a NULL `out`, which the function refuses.
    let status =
        unsafe { bwc_contact_new_named(law.as_ptr(), null(), null(), 0, null(), null_mut()) };
    assert_eq!(status, BwcStatus::NullPointer);
}
