//! A small sample of the stress sweep (the full one runs by hand: see STABILITY.md).

use bwc_benches::stress::{sample, sweep, Class};

/// Every case ends in a known class: separated with finite T_s and 0 <= e (<= 1 + 1e-9 without
/// input), no separation, or a classified solver failure; never energy created, never an
/// unclassified error; sampling is deterministic.
#[test]
fn stress_sample_is_classified() {
    let outcomes = sweep(7, 300);
    assert_eq!(outcomes.len(), 300);
    let mut separated = 0;
    for o in &outcomes {
        match &o.class {
            Class::EnergyCreated(e) => panic!("energy created: e = {e} for {:?}", o.case),
            Class::Other(m) => panic!("unclassified failure {m} for {:?}", o.case),
            Class::Separated => separated += 1,
            _ => {}
        }
    }
    assert!(separated > 200, "{separated} of 300 separated");
    assert_eq!(sample(7, 42), sample(7, 42));
    assert_ne!(sample(7, 42), sample(7, 43));
}
