//! Bad input through the C ABI: a status, a message naming the argument, its value and what
//! is admissible, and nothing changed.

use bwc::*;
use std::ffi::CStr;
use std::ptr::{null, null_mut};

fn message() -> String {
    // SAFETY: the library's last error is a NUL-terminated string.
    unsafe { CStr::from_ptr(bwc_last_error()) }
        .to_str()
        .unwrap()
        .to_owned()
}

fn expect(status: BwcStatus, want: BwcStatus, words: &[&str]) {
    assert_eq!(status, want, "{}", message());
    let m = message();
    for w in words {
        assert!(m.contains(w), "{w:?} not in {m:?}");
    }
}

/// Table 4's BWSHCCM.
pub(crate) fn shccm() -> BwcLawParams {
    let l = bw_models::published::CROSS_BWSHCCM;
    BwcLawParams {
        model: BWC_MODEL_SHCCM,
        k: l.k,
        c: l.c,
        n: l.n,
        p: l.p,
        alpha: l.alpha,
        beta: l.beta,
        gamma: l.gamma,
        a: l.a,
    }
}

/// A step to write into.
fn zero_step() -> BwcStep {
    BwcStep {
        force: 0.0,
        impulse: 0.0,
        work: 0.0,
        separated_at: 0.0,
        began_at: 0.0,
    }
}

fn info(contact: BwcContact) -> [f64; 5] {
    let mut i = BwcContactInfo {
        force: 0.0,
        absorbed: 0.0,
        dissipated: 0.0,
        onset_depth: 0.0,
        contacts: 0,
        in_contact: 0,
    };
    // SAFETY: `i` is writable.
    assert_eq!(unsafe { bwc_contact_info(contact, &mut i) }, BwcStatus::Ok);
    [
        i.force,
        i.absorbed,
        i.dissipated,
        i.onset_depth,
        f64::from(i.in_contact),
    ]
}

#[test]
fn bad_laws_are_named() {
    let mut law = 0;
    let mut bad = shccm();
    bad.k = -1.0;
    // SAFETY: valid pointers or NULL, as each call's contract allows.
    unsafe {
        expect(
            bwc_law_new(&bad, &mut law),
            BwcStatus::InvalidArgument,
            &["bwc_law_new", "`k` = -1", "k > 0"],
        );
        bad = shccm();
        bad.model = 7;
        expect(
            bwc_law_new(&bad, &mut law),
            BwcStatus::InvalidArgument,
            &["`model` = 7", "BWC_MODEL_MCM (1)"],
        );
        expect(
            bwc_law_new(null(), &mut law),
            BwcStatus::NullPointer,
            &["`params` is NULL"],
        );
        expect(
            bwc_law_new(&shccm(), null_mut()),
            BwcStatus::NullPointer,
            &["`out` is NULL"],
        );
        let base = BwcBaseParams {
            model: BWC_MODEL_MCM,
            b_b: 1.0,
            gamma_b: 2.0,
            kappa: 0.5,
            sigma_b: 1.0,
            n: 1.0,
            p: 1.5,
            u_b: 1.0,
            t_b: 1.0,
        };
        expect(
            bwc_law_from_base(&base, &mut law, null_mut()),
            BwcStatus::InvalidArgument,
            &["`Gamma_b` = 2"],
        );
    }
    assert_eq!(law, 0, "no law was made");
}

#[test]
fn bad_impacts_are_named() {
    let mut law = 0;
    let mut out = BwcImpact {
        e: 0.0,
        t_s: 0.0,
        separated: 0,
    };
    // SAFETY: valid pointers or NULL, as each call's contract allows.
    unsafe {
        assert_eq!(bwc_law_new(&shccm(), &mut law), BwcStatus::Ok);
        expect(
            bwc_impact(law, -0.145, 2.0, 0.0, &mut out),
            BwcStatus::InvalidArgument,
            &["bwc_impact", "`m` = -0.145", "m > 0 (kg)"],
        );
        expect(
            bwc_impact(law, 0.145, f64::NAN, 0.0, &mut out),
            BwcStatus::InvalidArgument,
            &["`v0` = NaN"],
        );
        expect(
            bwc_impact(law, 0.145, 2.0, 0.0, null_mut()),
            BwcStatus::NullPointer,
            &["`out`"],
        );
        assert_eq!(bwc_impact(law, 0.145, 2.0, 0.0, &mut out), BwcStatus::Ok);
        assert!(out.separated == 1 && out.e > 0.5 && out.e < 1.0 && out.t_s > 0.0);
        assert_eq!(bwc_law_free(law), BwcStatus::Ok);
        expect(
            bwc_impact(law, 0.145, 2.0, 0.0, &mut out),
            BwcStatus::InvalidHandle,
            &["`law`", "not a live handle"],
        );
        expect(
            bwc_law_free(law),
            BwcStatus::InvalidHandle,
            &["bwc_law_free"],
        );
    }
    assert_eq!(bwc_law_free(0), BwcStatus::Ok);
}

#[test]
fn bad_steps_leave_the_contact_unchanged() {
    let (mut law, mut contact) = (0, 0);
    let mut step = zero_step();
    // SAFETY: valid pointers or NULL, as each call's contract allows.
    unsafe {
        assert_eq!(bwc_law_new(&shccm(), &mut law), BwcStatus::Ok);
        let mut settings = bwc_element_settings_default();
        settings.policy = 2;
        expect(
            bwc_contact_new(law, &settings, &mut contact),
            BwcStatus::InvalidArgument,
            &["`settings.policy` = 2"],
        );
        settings = bwc_element_settings_default();
        settings.rtol = 1.0;
        expect(
            bwc_contact_new(law, &settings, &mut contact),
            BwcStatus::InvalidArgument,
            &["`rtol` = 1"],
        );
        assert_eq!(bwc_contact_new(law, null(), &mut contact), BwcStatus::Ok);
        // The law may go: the element keeps its own.
        assert_eq!(bwc_law_free(law), BwcStatus::Ok);
        assert_eq!(
            bwc_contact_advance(contact, 1e-5, -2.0, -1.9, &mut step),
            BwcStatus::Ok
        );
        let before = info(contact);
        expect(
            bwc_contact_advance(contact, 0.0, -2.0, -2.0, &mut step),
            BwcStatus::InvalidArgument,
            &["`dt` = 0", "dt > 0 (s)"],
        );
        expect(
            bwc_contact_advance(contact, 1e-5, f64::NAN, -2.0, &mut step),
            BwcStatus::InvalidArgument,
            &["`u_start` = NaN"],
        );
        expect(
            bwc_contact_advance_penetration(contact, 1e-5, f64::NAN, 1.0, 0.0, 1.0, &mut step),
            BwcStatus::InvalidArgument,
            &["`depth_start` = NaN", "finite penetration"],
        );
        expect(
            bwc_contact_advance_penetration(contact, 1e-5, 0.0, 1.0, 0.0, f64::INFINITY, &mut step),
            BwcStatus::InvalidArgument,
            &["`rate_end` = inf"],
        );
        assert_eq!(info(contact), before);
        let mut state = [0.0; 3];
        let mut len = 0;
        expect(
            bwc_contact_state(contact, state.as_mut_ptr(), 1, &mut len),
            BwcStatus::InvalidArgument,
            &["`capacity` = 1"],
        );
        assert_eq!(len, 2);
        assert_eq!(
            bwc_contact_state(contact, state.as_mut_ptr(), 3, &mut len),
            BwcStatus::Ok
        );
        assert!(state[0] < 0.0, "compressed: {state:?}");
        expect(
            bwc_contact_state(contact, null_mut(), 3, &mut len),
            BwcStatus::NullPointer,
            &["`out`"],
        );
        // Copies: a scratch element tries a step, the original is untouched.
        let mut scratch = 0;
        assert_eq!(bwc_contact_clone(contact, &mut scratch), BwcStatus::Ok);
        assert_eq!(
            bwc_contact_advance(scratch, 1e-5, -1.9, -1.8, &mut step),
            BwcStatus::Ok
        );
        assert_eq!(info(contact), before);
        assert_eq!(bwc_contact_copy(contact, scratch), BwcStatus::Ok);
        assert_eq!(info(scratch), before);
        assert_eq!(bwc_contact_free(scratch), BwcStatus::Ok);
        expect(
            bwc_contact_copy(contact, scratch),
            BwcStatus::InvalidHandle,
            &["`to`"],
        );
        assert_eq!(bwc_contact_reset(contact), BwcStatus::Ok);
        assert_eq!(info(contact), [0.0; 5]);
        assert_eq!(bwc_contact_free(contact), BwcStatus::Ok);
        expect(
            bwc_contact_advance(contact, 1e-5, -2.0, -2.0, &mut step),
            BwcStatus::InvalidHandle,
            &["bwc_contact_advance", "`contact`", "freed"],
        );
        expect(
            bwc_contact_reset(12345),
            BwcStatus::InvalidHandle,
            &["`contact` = 0x3039"],
        );
    }
}

/// A law's handle where a contact's is expected (and the reverse) is an error naming both
/// kinds, even where the two hold the same slot: nothing is advanced or freed.
#[test]
fn a_handle_of_the_wrong_kind_is_an_error() {
    let mut law = 0;
    let mut contact = 0;
    let mut step = zero_step();
    // SAFETY: every pointer is to a live local.
    unsafe {
        assert_eq!(bwc_law_new(&shccm(), &mut law), BwcStatus::Ok);
        assert_eq!(bwc_contact_new(law, null(), &mut contact), BwcStatus::Ok);
        expect(
            bwc_contact_advance(law, 1e-5, -2.0, -2.0, &mut step),
            BwcStatus::InvalidHandle,
            &["`contact`", "is a law handle, not a contact handle"],
        );
        assert_eq!(info(contact), [0.0; 5]);
        let mut other = 0;
        expect(
            bwc_contact_new(contact, null(), &mut other),
            BwcStatus::InvalidHandle,
            &["`law`", "is a contact handle, not a law handle"],
        );
        expect(
            bwc_law_free(contact),
            BwcStatus::InvalidHandle,
            &["a contact handle"],
        );
        expect(
            bwc_contact_free(law),
            BwcStatus::InvalidHandle,
            &["a law handle"],
        );
        assert_eq!(bwc_contact_free(contact), BwcStatus::Ok);
        assert_eq!(bwc_law_free(law), BwcStatus::Ok);
    }
}
