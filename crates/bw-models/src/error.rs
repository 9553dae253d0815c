//! Everything that can go wrong when building or simulating a model.

/// Everything that can go wrong when building or simulating a model.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A model parameter is outside its admissible set.
    #[error("parameter `{name}` = {} is not admissible: {allowed}", Shown(*.value))]
    InvalidParameter {
        /// Parameter name as in the paper (`"kappa"`, `"B_b"`, ...).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The admissible range.
        allowed: &'static str,
    },
    /// A simulation setting is out of range.
    #[error("setting `{name}` = {} is not admissible: {allowed}", Shown(*.value))]
    InvalidSetting {
        /// Setting name as in [`Settings`](crate::Settings).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// The admissible range.
        allowed: &'static str,
    },
    /// Parameters of one model were given to the other.
    #[error("parameters of the {found} model given where the {expected} model was expected")]
    WrongModel {
        /// The model expected.
        expected: &'static str,
        /// The model the parameters belong to.
        found: &'static str,
    },
    /// A piecewise-linear input table is malformed.
    #[error("input table point {index}: {reason}")]
    InvalidTable {
        /// Index of the offending point.
        index: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// A method was asked for a model or parameters it does not cover.
    #[error("not applicable: {reason}")]
    NotApplicable {
        /// What the method covers, or why it gave up.
        reason: &'static str,
    },
    /// A body, pair or wall of a chain is not admissible ([`crate::chain::Chain::new`]).
    #[error("{part}: `{name}` = {} is not admissible: {allowed}", Shown(*.value))]
    InvalidChain {
        /// Which body, pair or wall.
        part: ChainPart,
        /// The quantity (`"mass"`, `"gap"`, `"laws"`, ...).
        name: &'static str,
        /// The rejected value (a count for `"bodies"` and `"laws"`).
        value: f64,
        /// What is admissible.
        allowed: &'static str,
    },
    /// A body's material or geometry is not admissible ([`crate::materials::MaterialPair`]).
    #[error("{}: `{name}` = {} is not admissible: {allowed}", body_name(*.body), Shown(*.value))]
    InvalidMaterial {
        /// The body: 1 or 2, 0 for the pair.
        body: u8,
        /// The quantity (`"poisson"`, `"youngs_modulus"`, ...).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What is admissible, and the likely unit of a slip.
        allowed: &'static str,
    },
    /// A name that is not one of those known: a contact law, or a parameter of one.
    #[error("{}", unknown_name(law, name, problem))]
    UnknownName {
        /// The law whose parameter is named, or `""` where the law itself is.
        law: &'static str,
        /// The name given.
        name: Box<str>,
        /// What is wrong with it (`"is not one of its parameters"`, `"is missing"`).
        problem: &'static str,
    },
    /// The integration failed.
    #[error("simulation failed: {0}")]
    Solver(#[from] bwc_events::Error),
}

/// The part of a chain an error is about ([`ModelError::InvalidChain`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum ChainPart {
    /// The chain as a whole.
    Chain,
    /// Moving body `i`, counted from the left (walls not counted).
    Body(u32),
    /// Pair `j`, counted from the left (a left wall's pair first).
    Pair(u32),
    /// The wall on the left.
    LeftWall,
    /// The wall on the right.
    RightWall,
}

impl std::fmt::Display for ChainPart {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ChainPart::Chain => write!(f, "chain"),
            ChainPart::Body(i) => write!(f, "chain body {i}"),
            ChainPart::Pair(j) => write!(f, "chain pair {j}"),
            ChainPart::LeftWall => write!(f, "chain left wall"),
            ChainPart::RightWall => write!(f, "chain right wall"),
        }
    }
}

/// A rejected value as a message shows it: in full where short, else with an exponent
/// (`4e-306`, not 306 zeros; `1e308`, not 309 digits).
struct Shown(f64);

impl std::fmt::Display for Shown {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-5..1e16).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// The message of [`ModelError::UnknownName`], with the names that are admissible.
fn unknown_name(law: &str, name: &str, problem: &str) -> String {
    match crate::ELEMENT_LAWS.iter().find(|s| s.name == law) {
        Some(spec) => format!(
            "law \"{law}\": parameter `{name}` {problem}: {}",
            spec.param_list()
        ),
        None => {
            let laws: Vec<&str> = crate::ELEMENT_LAWS.iter().map(|s| s.name).collect();
            format!("contact law `{name}` {problem}: {}", laws.join(", "))
        }
    }
}

fn body_name(body: u8) -> String {
    match body {
        0 => "the pair of bodies".to_string(),
        i => format!("body {i}"),
    }
}
