//! Event location against closed forms.
#![allow(clippy::excessive_precision)] // reference values keep their published digits

use bwc_events::{
    class, Condition, Crossing, Direction, Locator, NoSwitches, Outcome, Step, SwitchAt, Values,
};
use bwc_ode::{Integrator, Options, State, DOP853, VERN7, VERN9};

/// Separation `F <= 0 <= v` for a two-state oscillator `x' = v, v' = F(x)`.
struct Separation<G>(G);

impl<G: Fn(f64) -> f64> Condition<2> for Separation<G> {
    fn count(&self) -> usize {
        2
    }
    fn values(&self, _t: f64, y: &State<2>) -> Values {
        [(self.0)(y[0]), y[1], 0.0, 0.0]
    }
    fn holds(&self, _start: &Values, g: &Values) -> bool {
        g[0] <= 0.0 && g[1] >= 0.0
    }
}

/// Exact separation times of s'' = -s^p, s(0) = 0, s'(0) = 1: by the first integral
/// s'^2/2 + s^(p+1)/(p+1) = 1/2, T_s = 2/(p+1) s_max B(1/(p+1), 1/2) with
/// s_max = ((p+1)/2)^(1/(p+1)) (Beta function values from mpmath at 30 digits).
const ELASTIC: [(f64, f64); 5] = [
    (1.0, std::f64::consts::PI),
    (1.5, 3.2180654597190430845),
    (2.0, 3.2101956532389271625),
    (3.0, 3.1181694995108224606),
    (5.0, 2.9166563142603385794),
];

fn power_force(p: f64) -> impl Fn(f64) -> f64 + Copy {
    move |x: f64| -x.abs().powf(p - 1.0) * x
}

/// Separation of the elastic oscillator: (T_s, v(T_s), RHS evaluations, events, instant of the
/// switch at v = 0 if one was requested).
fn elastic_separation(
    tab: &'static bwc_ode::Tableau,
    p: f64,
    rtol: f64,
    switch_at_v0: bool,
) -> (f64, f64, u64, u64, Option<f64>) {
    let force = power_force(p);
    let f = move |_t: f64, y: &State<2>| State::<2>::new(y[1], force(y[0]));
    let mut it = Integrator::new(
        f,
        tab,
        0.0,
        State::<2>::new(0.0, -1.0),
        Options::new(rtol, rtol * 1e-2),
    )
    .unwrap();
    let switches = SwitchAt(move |_t: f64, y: &State<2>| [if switch_at_v0 { y[1] } else { 1.0 }]);
    let mut loc = Locator::new(Separation(force), switches);
    let mut switched = None;
    loop {
        match loc.step(&mut it, 10.0).unwrap() {
            Step::Event { t, y } => {
                return (t, y[1], it.stats().rhs_evals, it.stats().events, switched)
            }
            Step::Switched { t, .. } => switched = Some(t),
            Step::Continued => assert!(it.t() < 10.0, "no separation"),
        }
    }
}

/// The force vanishes like (T_s - T)^p at separation; T_s must still come out to 1e-12 and the
/// rebound velocity to 1 (elastic: e = 1).
#[test]
fn elastic_limit_separation_time_to_1e12() {
    for (p, ts_exact) in ELASTIC {
        for tab in [&DOP853, &VERN7, &VERN9] {
            for switch in [false, true] {
                let (ts, v, evals, events, switched) = elastic_separation(tab, p, 1e-13, switch);
                // v = 0 is both a switching point and a boundary of the separation condition:
                // the switch must still fire, at maximum compression T_s / 2, then separation.
                assert_eq!(events, if switch { 2 } else { 1 }, "{} p = {p}", tab.name);
                if switch {
                    let t = switched.expect("switch at v = 0 fired");
                    assert!(
                        (t - ts_exact / 2.0).abs() < 1e-12,
                        "{} p = {p}: switch at {t}",
                        tab.name
                    );
                }
                let rel = (ts - ts_exact).abs() / ts_exact;
                assert!(
                    rel < 1e-12,
                    "{} p = {p} switch {switch}: T_s = {ts} vs {ts_exact} ({rel:e})",
                    tab.name
                );
                assert!((v - 1.0).abs() < 1e-11, "{} p = {p}: e = {v}", tab.name);
                assert!(evals < 20_000, "{evals}");
            }
        }
    }
}

/// No event at the initial instant although F(0) = 0: the force leaves zero, it does not cross.
#[test]
fn no_spurious_event_at_impact() {
    let force = power_force(1.5);
    let f = move |_t: f64, y: &State<2>| State::<2>::new(y[1], force(y[0]));
    let mut it = Integrator::new(
        f,
        &DOP853,
        0.0,
        State::<2>::new(0.0, -1.0),
        Options::new(1e-10, 1e-12),
    )
    .unwrap();
    let mut loc = Locator::new(Separation(force), NoSwitches);
    let first = loc.step(&mut it, 10.0).unwrap();
    assert_eq!(first, Step::Continued);
    match loc.run(&mut it, 10.0).unwrap() {
        Outcome::Event { t, .. } => assert!(t > 3.0),
        Outcome::Horizon { .. } => panic!("no separation"),
    }
}

/// y' = |cos t| has a kink at t = π/2; exact y = sin t before, 2 - sin t after. With a switching
/// function cos t the solver stops at π/2 to the last bits and keeps its full order.
#[test]
fn switching_point_is_hit_exactly_and_restores_accuracy() {
    let f = |t: f64, _y: &State<1>| State::<1>::new(t.cos().abs());
    let exact = |t: f64| {
        if t <= std::f64::consts::FRAC_PI_2 {
            t.sin()
        } else {
            2.0 - t.sin()
        }
    };
    let t_end = 3.0;
    for tab in bwc_ode::METHODS {
        let opts = Options::new(1e-12, 1e-14);
        let mut it = Integrator::new(f, tab, 0.0, State::<1>::new(0.0), opts).unwrap();
        let mut loc = Locator::new(
            Crossing::new(|_t: f64, _y: &State<1>| 1.0, Direction::Down),
            SwitchAt(|t: f64, _y: &State<1>| [t.cos()]),
        );
        let mut switched_at = None;
        while it.t() < t_end {
            if let Step::Switched { t, .. } = loc.step(&mut it, t_end).unwrap() {
                switched_at = Some(t);
            }
        }
        let ts = switched_at.expect("switch located");
        assert!(
            (ts - std::f64::consts::FRAC_PI_2).abs() < 4e-16,
            "{}: {ts}",
            tab.name
        );
        let with = (it.y()[0] - exact(t_end)).abs();
        let stats_with = it.stats();

        let mut plain = Integrator::new(f, tab, 0.0, State::<1>::new(0.0), opts).unwrap();
        plain.integrate_to(t_end).unwrap();
        let without = (plain.y()[0] - exact(t_end)).abs();
        assert!(with < 1e-12, "{}: error with switching {with:e}", tab.name);
        // Stopping at the kink costs one retaken step but buys accuracy per RHS evaluation.
        assert!(
            with * 10.0 <= without.max(1e-13),
            "{}: {with:e} vs {without:e}",
            tab.name
        );
        assert!(
            stats_with.rhs_evals <= plain.stats().rhs_evals + 20,
            "{}: {stats_with:?}",
            tab.name
        );
        assert_eq!(stats_with.events, 1);
    }
}

/// A kink that depends on the state: a spring stiffer in extension, y'' = -y - 3 max(y, 0), from
/// y = 0, y' = -1. Half periods of pi (y < 0) and pi/2 (y > 0) alternate, so at t = 5 pi (after
/// three full periods and half a soft one) y = -1, y' = 0 exactly, with six kinks on the way.
/// Steps aimed at the kinks after a rejected straddling trial reach each with a few rejections
/// (the controller alone shrinks the step about ten times first) and restore full accuracy.
#[test]
fn rejected_steps_are_aimed_at_kinks() {
    let f = |_t: f64, y: &State<2>| State::<2>::new(y[1], -y[0] - 3.0 * y[0].max(0.0));
    let t_end = 5.0 * std::f64::consts::PI;
    let (y0, exact) = (State::<2>::new(0.0, -1.0), State::<2>::new(-1.0, 0.0));
    for tab in bwc_ode::METHODS {
        let opts = Options::new(1e-12, 1e-14);
        let mut it = Integrator::new(f, tab, 0.0, y0, opts).unwrap();
        let mut loc = Locator::new(
            Crossing::new(|_t: f64, _y: &State<2>| 1.0, Direction::Down),
            SwitchAt(|_t: f64, y: &State<2>| [y[0]]),
        );
        let mut kinks = Vec::new();
        while it.t() < t_end {
            if let Step::Switched { t, .. } = loc.step(&mut it, t_end).unwrap() {
                kinks.push(t / std::f64::consts::PI);
            }
        }
        let mut plain = Integrator::new(f, tab, 0.0, y0, opts).unwrap();
        plain.integrate_to(t_end).unwrap();
        let (with, without) = ((it.y() - exact).amax(), (plain.y() - exact).amax());
        let (s, p) = (it.stats(), plain.stats());
        let name = tab.name;
        for (got, want) in kinks.iter().zip([1.0, 1.5, 2.5, 3.0, 4.0, 4.5]) {
            assert!(
                (got - want).abs() < 1e-11,
                "{name}: kink at {got} pi, not {want} pi"
            );
        }
        assert_eq!(kinks.len(), 6, "{name}: {kinks:?}");
        // At most four rejected trials per kink, at most half of the plain run's.
        assert!(
            s.rejected <= 24 && 2 * s.rejected <= p.rejected,
            "{name}: {s:?} vs {p:?}"
        );
        assert!(s.rhs_evals < p.rhs_evals, "{name}: {s:?} vs {p:?}");
        // DOP853's global error at rtol 1e-12 over 18 steps of 0.18 is ~2e-10 (its error
        // estimate is optimistic on this problem); the others are at 1e-12 to 1e-13.
        assert!(with < 1e-9, "{name}: error {with:e} (plain {without:e})");
    }
}

/// A crossing in the wrong direction is not an event; `Either` takes the first one.
#[test]
fn crossing_directions() {
    // y = sin t: first zero crossing downwards at π, upwards at 2π.
    let f = |t: f64, _y: &State<1>| State::<1>::new(t.cos());
    for (dir, expected) in [
        (Direction::Down, std::f64::consts::PI),
        (Direction::Up, 2.0 * std::f64::consts::PI),
        (Direction::Either, std::f64::consts::PI),
    ] {
        let mut it = Integrator::new(
            f,
            &DOP853,
            0.0,
            State::<1>::new(0.0),
            Options::new(1e-12, 1e-14),
        )
        .unwrap();
        // Start just after 0 so that y is positive at the start.
        it.integrate_to(0.1).unwrap();
        let cond = Crossing::new(|_t: f64, y: &State<1>| y[0], dir);
        match Locator::new(cond, NoSwitches).run(&mut it, 10.0).unwrap() {
            Outcome::Event { t, y } => {
                assert!((t - expected).abs() < 1e-11, "{dir:?}: {t}");
                assert!(class(y[0]) <= 0 || dir == Direction::Up);
            }
            Outcome::Horizon { .. } => panic!("{dir:?}: no event"),
        }
    }
}

/// A boundary function that leaves its class and comes back inside one step: the ends of the
/// step agree, the event in between must still be found (here one step spans the whole run).
#[test]
fn a_crossing_and_back_inside_one_step_is_found() {
    // y = t; g = (y - a)(y - b) is negative on (a, b) only.
    for (a, b) in [(0.3, 0.6), (0.05, 0.12), (0.81, 0.9)] {
        let f = |_t: f64, _y: &State<1>| State::<1>::new(1.0);
        let options = Options::new(1e-10, 1e-12).with_h0(1.0);
        let mut it = Integrator::new(f, &DOP853, 0.0, State::<1>::new(0.0), options).unwrap();
        let g = move |_t: f64, y: &State<1>| (y[0] - a) * (y[0] - b);
        let mut locator = Locator::new(Crossing::new(g, Direction::Down), NoSwitches);
        match locator.run(&mut it, 1.0).unwrap() {
            Outcome::Event { t, .. } => assert!((t - a).abs() < 1e-14, "({a}, {b}): {t}"),
            Outcome::Horizon { .. } => panic!("({a}, {b}): the dip was missed"),
        }
        assert_eq!(it.stats().accepted, 1, "one step to the event (retaken)");
    }
}

/// `y <= 0 <= y'` on the harmonic oscillator `y'' = -y`, `y(0) = 0`, `y'(0) = 1`
/// (`y = sin t`): it first holds at `3π/2` and holds until `2π`; again from `3π/2 + 2π`.
struct Rebound;

impl Condition<2> for Rebound {
    fn count(&self) -> usize {
        2
    }
    fn values(&self, _t: f64, y: &State<2>) -> Values {
        [y[0], y[1], 0.0, 0.0]
    }
    fn holds(&self, _start: &Values, g: &Values) -> bool {
        g[0] <= 0.0 && g[1] >= 0.0
    }
}

#[test]
fn events_are_reported_once_when_continuing_past_them() {
    let f = |_t: f64, y: &State<2>| State::<2>::new(y[1], -y[0]);
    let start = State::<2>::new(0.0, 1.0);
    let opts = Options::new(1e-12, 1e-14);
    let tau = 2.0 * std::f64::consts::PI;
    // The same locator, stepping on after each event.
    let mut it = Integrator::new(f, &DOP853, 0.0, start, opts).unwrap();
    let mut locator = Locator::new(Rebound, NoSwitches);
    let mut times = Vec::new();
    while it.t() < 3.0 * tau {
        if let Step::Event { t, .. } = locator.step(&mut it, 3.0 * tau).unwrap() {
            times.push(t);
        }
    }
    assert_eq!(times.len(), 3, "{times:?}");
    for (k, t) in times.iter().enumerate() {
        let exact = 0.75 * tau + k as f64 * tau;
        assert!((t - exact).abs() < 1e-9, "{t} vs {exact}");
    }
    // A new locator restarted at the event state: told so, it waits for the next one.
    let mut it = Integrator::new(f, &DOP853, 0.0, start, opts).unwrap();
    let Outcome::Event { t, y } = Locator::new(Rebound, NoSwitches).run(&mut it, tau).unwrap()
    else {
        panic!("no event");
    };
    let mut again = Integrator::new(f, &DOP853, t, y, opts).unwrap();
    let next = Locator::new(Rebound, NoSwitches)
        .after_event()
        .run(&mut again, 3.0 * tau)
        .unwrap();
    let Outcome::Event { t: t2, .. } = next else {
        panic!("no second event");
    };
    assert!((t2 - (t + tau)).abs() < 1e-9, "{t2}");
    // A crossing is an instant: continuing past one needs nothing (sin t crosses 0 upwards at
    // 2π and 4π; not at 0, where it starts).
    let mut it = Integrator::new(f, &DOP853, 0.0, start, opts).unwrap();
    let mut up = Locator::new(
        Crossing::new(|_t: f64, y: &State<2>| y[0], Direction::Up),
        NoSwitches,
    );
    let mut ups = Vec::new();
    while let Outcome::Event { t, .. } = up.run(&mut it, 2.5 * tau).unwrap() {
        ups.push(t);
    }
    assert_eq!(ups.len(), 2, "{ups:?}");
    assert!((ups[0] - tau).abs() < 1e-9 && (ups[1] - 2.0 * tau).abs() < 1e-9);
}

/// A shallow, brief excursion: `y = (sin t, cos t)` and the event where `sin t` rises through
/// `1 - δ` (δ = 1e-6), which it leaves again 2.8e-3 later, inside one step of a few tenths.
/// The cubic model from the step's ends misses the peak by about `h^4 / 384` (1e-5 here), more
/// than the excursion; the model's extremum comes within its margin of the boundary and the
/// dense output's extremum, found near it, shows the crossing. Exact: `t* = asin(1 - δ)`.
#[test]
fn a_shallow_excursion_inside_one_step_is_found() {
    let delta: f64 = 1e-6;
    let t_star = (1.0 - delta).asin();
    let f = |_t: f64, y: &State<2>| State::<2>::new(y[1], -y[0]);
    let rise = Crossing::new(
        move |_t: f64, y: &State<2>| y[0] - (1.0 - delta),
        Direction::Up,
    );
    // (At rtol 1e-6 the excursion is no deeper than the step's own error.)
    for rtol in [1e-8, 1e-9, 1e-10, 1e-11, 1e-12] {
        let y0 = State::<2>::new(0.0, 1.0);
        let mut it = Integrator::new(f, &DOP853, 0.0, y0, Options::new(rtol, rtol)).unwrap();
        let outcome = Locator::new(rise, NoSwitches).run(&mut it, 3.0).unwrap();
        let Outcome::Event { t, .. } = outcome else {
            panic!("rtol {rtol:e}: the excursion was missed: {outcome:?}");
        };
        // The root's conditioning: a state error ε moves it by ε / √(2δ) = 700 ε.
        assert!(
            (t - t_star).abs() < 1e4 * rtol,
            "rtol {rtol:e}: t = {t}, t* = {t_star}"
        );
    }
}
