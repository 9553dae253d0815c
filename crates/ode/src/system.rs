//! What the solvers integrate: a right-hand side `y' = f(t, y)` on stack-allocated states.

/// A state of `N` components on the stack.
pub type State<const N: usize> = nalgebra::SVector<f64, N>;

/// A right-hand side `y' = f(t, y)` (non-autonomous in general).
///
/// Implemented for closures `Fn(f64, &State<N>) -> State<N>` and for references to systems.
pub trait System<const N: usize> {
    /// The derivative `f(t, y)`.
    fn rhs(&self, t: f64, y: &State<N>) -> State<N>;
}

impl<const N: usize, F: Fn(f64, &State<N>) -> State<N>> System<N> for F {
    #[inline]
    fn rhs(&self, t: f64, y: &State<N>) -> State<N> {
        self(t, y)
    }
}
