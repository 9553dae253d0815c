//! What a collision model is ([`CollisionModel`]): a right-hand side with the outputs the
//! impact analysis needs.

use super::form::NdForm;
use bwc_ode::{Matrix, State, System};

/// A collision model: a right-hand side with the outputs the impact analysis needs.
pub trait CollisionModel<const N: usize>: System<N> {
    /// State at the instant of impact: all displacements zero, relative velocity `-v0`.
    fn initial_state(&self) -> State<N>;
    /// Contact force `F` (positive pushes the bodies apart).
    fn force(&self, y: &State<N>) -> f64;
    /// Relative displacement `x` (`x < 0` is compression).
    fn displacement(&self, y: &State<N>) -> f64;
    /// Relative velocity `v`.
    fn velocity(&self, y: &State<N>) -> f64;
    /// The external input at `t`.
    fn input(&self, t: f64) -> f64;
    /// A time from which the input is constant (model time units; `-inf` for a constant
    /// input), if any (see [`Input::constant_after`](crate::input::Input::constant_after)).
    fn input_constant_after(&self) -> Option<f64>;
    /// The model's nondimensional form, through which a CoR evaluation takes the crate's fast
    /// paths (the Taylor series, the phase path and the double-double path): `None` (the
    /// default) for a model without one, which keeps the Runge-Kutta path. Only the crate's
    /// models can make an [`NdForm`]; a model of one's own keeps the default.
    #[doc(hidden)]
    fn nondimensional_form(&self) -> Option<NdForm<'_, N>> {
        None
    }
    /// Whether the input is constant at all times.
    fn input_is_constant(&self) -> bool {
        self.input_constant_after() == Some(f64::NEG_INFINITY)
    }
    /// Impact speed `v0` (1 for nondimensional models), so that `e = v(t_s) / v0`.
    fn impact_speed(&self) -> f64;
    /// Natural magnitude of each state component (ones for nondimensional models; the scales
    /// of Table 1 for SI models): absolute tolerances are multiplied by these.
    fn state_scale(&self) -> State<N>;
    /// Natural time scale (1 for nondimensional models, `T_c` in seconds for SI models).
    fn time_scale(&self) -> f64;
    /// Functions whose zeros are the non-smooth points of the right-hand side: the velocity
    /// across the hysteretic element (`|v|` or `|ẏ|`) and `z`, in natural (nondimensional)
    /// units so that they compare with the absolute tolerance.
    fn kinks(&self, t: f64, y: &State<N>) -> [f64; 2];
    /// How long (model time) the state `y`, moving with derivative `f`, stays clear of a point
    /// where the right-hand side is not analytic (the base of a term `c |s|^q` reaching 0), to
    /// first order, while that term matters at tolerance `rtol`; `+inf` where none does (the
    /// default). The Runge-Kutta path with [`Settings::stop_at_kinks`](crate::Settings::stop_at_kinks) keeps its steps to half
    /// of it: an embedded error estimate assumes the solution analytic over a few step lengths
    /// and passes steps that end close to such a point with errors of a hundred tolerances
    /// (STABILITY.md, "Stops at the non-smooth points"). The NDBWSHCCM and the BWSHCCM say it for `X` and `Z`; the
    /// MCMs keep the default (measured: it moved a flat separation of the NDBWMCM by up to 1e-9
    /// at rtol 1e-9).
    fn clearance(&self, y: &State<N>, f: &State<N>, rtol: f64) -> f64 {
        let _ = (y, f, rtol);
        f64::INFINITY
    }
    /// The Jacobian `∂f/∂y` for implicit methods. Analytic for the nondimensional models; by
    /// default forward differences with steps `√ε max(|y_i|, scale_i)` (relative accuracy about
    /// `1e-8`, enough for the step-size control of RODAS4, which then behaves like a method
    /// of lower order on the affected steps).
    fn jacobian(&self, t: f64, y: &State<N>) -> Matrix<N> {
        let f0 = self.rhs(t, y);
        let scale = self.state_scale();
        let mut j = Matrix::<N>::zeros();
        for c in 0..N {
            let d = f64::EPSILON.sqrt() * y[c].abs().max(scale[c]);
            let mut yc = *y;
            yc[c] += d;
            j.set_column(c, &((self.rhs(t, &yc) - f0) / (yc[c] - y[c])));
        }
        j
    }
}

/// Whether every component of `f` is below `10 atol` in natural units (state scale per time
/// scale): the state is at rest.
pub(crate) fn at_rest<M: CollisionModel<N>, const N: usize>(
    model: &M,
    f: &State<N>,
    atol: f64,
) -> bool {
    let scale = model.state_scale() / model.time_scale();
    f.iter()
        .zip(scale.iter())
        .all(|(d, s)| d.abs() <= 10.0 * atol * s)
}

/// The [`CollisionModel`] methods of a nondimensional model with `N` states: impact speed,
/// state scales and time scale all 1.
macro_rules! nondimensional_scales {
    ($n:literal) => {
        fn impact_speed(&self) -> f64 {
            1.0
        }
        fn state_scale(&self) -> State<$n> {
            State::<$n>::repeat(1.0)
        }
        fn time_scale(&self) -> f64 {
            1.0
        }
    };
}
pub(crate) use nondimensional_scales;

/// The [`CollisionModel`] input methods of a model whose `input` field is an
/// [`Input`](crate::input::Input).
macro_rules! input_of_field {
    () => {
        fn input(&self, t: f64) -> f64 {
            self.input.at(t)
        }
        fn input_constant_after(&self) -> Option<f64> {
            self.input.constant_after()
        }
    };
}
pub(crate) use input_of_field;

/// The [`CollisionModel`] input methods of an unforced model: `u = 0` at all times.
macro_rules! unforced {
    () => {
        fn input(&self, _t: f64) -> f64 {
            0.0
        }
        fn input_constant_after(&self) -> Option<f64> {
            Some(f64::NEG_INFINITY)
        }
    };
}
pub(crate) use unforced;
