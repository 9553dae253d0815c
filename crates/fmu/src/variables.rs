//! The FMU's variables: names, value references and roles, as `modelDescription.xml` lists
//! them (a test holds the two together).

use bw_models::ELEMENT_LAWS;
use std::sync::LazyLock;

/// A variable's type in FMI terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Type {
    /// fmi2Real.
    Real,
    /// fmi2Integer.
    Integer,
    /// fmi2Boolean.
    Boolean,
}

/// One scalar variable.
#[derive(Debug, Clone, Copy)]
pub struct Variable {
    /// Its name in `modelDescription.xml`.
    pub name: &'static str,
    /// Its value reference.
    pub vr: u32,
    /// Its type.
    pub kind: Type,
    /// `parameter`, `input` or `output`.
    pub causality: &'static str,
    /// What it is, with its unit and admissible values.
    pub description: &'static str,
}

const fn var(
    name: &'static str,
    vr: u32,
    kind: Type,
    causality: &'static str,
    description: &'static str,
) -> Variable {
    Variable {
        name,
        vr,
        kind,
        causality,
        description,
    }
}

/// The law's real parameters, in the order of [`crate::instance::Params::reals`].
pub const REAL_PARAMETERS: [&str; 10] = [
    "k", "c", "n", "p", "alpha", "beta", "gamma", "A", "rtol", "atol",
];

/// Every variable of the FMU.
pub const VARIABLES: [Variable; 20] = [
    var("k", 1, Type::Real, "parameter", "stiffness k (kg m^(1-p) s^-2), > 0"),
    var("c", 2, Type::Real, "parameter", "damping c: kg m^-p s^-1 (SHCCM, >= 0) or kg s^-1 (MCM, > 0)"),
    var("n", 3, Type::Real, "parameter", "Bouc-Wen exponent n >= 1"),
    var("p", 4, Type::Real, "parameter", "force exponent p >= 1"),
    var("alpha", 5, Type::Real, "parameter", "share of the elastic element, in (0, 1)"),
    var("beta", 6, Type::Real, "parameter", "Bouc-Wen beta (m^-n), >= 0"),
    var("gamma", 7, Type::Real, "parameter", "Bouc-Wen gamma (m^-n), in [-beta, beta]"),
    var("A", 8, Type::Real, "parameter", "Bouc-Wen A > 0"),
    var("rtol", 9, Type::Real, "parameter", "relative tolerance of the element's steps, in [1e-14, 1e-2]"),
    var("atol", 10, Type::Real, "parameter", "absolute tolerance of the law's states (m), > 0"),
    var("model", 20, Type::Integer, "parameter", "0: BWSHCCM (states x, z), 1: BWMCM (states r, y, z), 2: Hunt-Crossley, 3: Kelvin-Voigt, 4: Thornton, 5: Jackson-Green (from 2 on, the parameters named <law>.<parameter>)"),
    var("policy", 21, Type::Integer, "parameter", "what a new contact starts from: 0 the law at rest, 1 the state of the last separation"),
    var("delta", 30, Type::Real, "input", "penetration (m), positive while the bodies overlap"),
    var("delta_dot", 31, Type::Real, "input", "rate of the penetration (m/s), positive while the bodies approach; its derivative (order 1) is the relative acceleration"),
    var("force", 40, Type::Real, "output", "contact force at the end of the last step (N), positive pushing the bodies apart"),
    var("impulse", 41, Type::Real, "output", "impulse of the force over the last step (N s)"),
    var("dissipated", 42, Type::Real, "output", "energy dissipated in the contact so far (J)"),
    var("absorbed", 43, Type::Real, "output", "work the bodies did on the contact so far (J)"),
    var("in_contact", 50, Type::Boolean, "output", "whether a contact is under way"),
    var("contacts", 51, Type::Integer, "output", "contacts that have ended"),
];

/// A real parameter of one of the element laws beyond the two Bouc-Wen laws (which take the
/// parameters of [`VARIABLES`]): law `i` of [`ELEMENT_LAWS`] (`model = i`) has its `j`-th
/// parameter at value reference `100 + 10 i + j`, named `<law>.<parameter>` with the law's
/// name in snake case (`thornton.delta_y`).
#[derive(Debug, Clone, Copy)]
pub struct LawVariable {
    /// The FMU variable.
    pub variable: Variable,
    /// The law's index in [`ELEMENT_LAWS`]: the `model` that selects it.
    pub law: usize,
    /// The parameter's name in the law's spec.
    pub param: &'static str,
    /// Its start value (the spec's).
    pub start: f64,
}

/// The models whose parameters are [`VARIABLES`]' `k` to `A`.
pub const BOUC_WEN_MODELS: usize = 2;

/// Every [`LawVariable`], law by law in the order of [`ELEMENT_LAWS`].
pub fn law_variables() -> &'static [LawVariable] {
    static ALL: LazyLock<Vec<LawVariable>> = LazyLock::new(|| {
        let mut all = Vec::new();
        for (i, spec) in ELEMENT_LAWS.iter().enumerate().skip(BOUC_WEN_MODELS) {
            for (j, p) in spec.params.iter().enumerate() {
                // Built once per process; the names and descriptions live as long as the
                // library, as the constant ones do.
                let name = format!("{}.{}", spec.name.replace('-', "_"), p.name);
                let description = format!(
                    "{} (model = {i}): {} ({}), {}",
                    spec.title, p.name, p.unit, p.allowed
                );
                all.push(LawVariable {
                    variable: var(
                        Box::leak(name.into_boxed_str()),
                        100 + 10 * i as u32 + j as u32,
                        Type::Real,
                        "parameter",
                        Box::leak(description.into_boxed_str()),
                    ),
                    law: i,
                    param: p.name,
                    start: p.start,
                });
            }
        }
        all
    });
    &ALL
}

/// The variable of a value reference and type.
pub fn find(vr: u32, kind: Type) -> Option<&'static Variable> {
    VARIABLES
        .iter()
        .chain(law_variables().iter().map(|l| &l.variable))
        .find(|v| v.vr == vr && v.kind == kind)
}
