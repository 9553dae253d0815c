//! One FMU instance: its parameters, its phase in the FMI 2.0 state machine, the contact
//! element and its inputs and outputs. Everything here is plain Rust; `fmi2` wraps it for C.

use crate::variables::{find, law_variables, Type, Variable, BOUC_WEN_MODELS, REAL_PARAMETERS};
use bw_models::sequence::Policy;
use bw_models::{
    AnyContactElement, ElementSettings, ModelError, ModelKind, Penetration, Physical,
    PhysicalParams, ELEMENT_LAWS,
};

/// Where an instance is in FMI 2.0's Co-Simulation state machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// After fmi2Instantiate: parameters may be set.
    Instantiated,
    /// Between fmi2EnterInitializationMode and fmi2ExitInitializationMode.
    Initialization,
    /// Stepping: fmi2DoStep.
    Stepping,
    /// After fmi2Terminate.
    Terminated,
}

/// The parameters: the Bouc-Wen law's reals ([`REAL_PARAMETERS`]), the other laws'
/// ([`law_variables`]), the model and the policy.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// `k, c, n, p, alpha, beta, gamma, A, rtol, atol`.
    pub reals: [f64; 10],
    /// The other laws' parameters, in the order of [`law_variables`].
    pub laws: Vec<f64>,
    /// The law's index in [`ELEMENT_LAWS`]: 0 SHCCM, 1 MCM, then the other laws.
    pub model: i32,
    /// 0: reset, 1: carry.
    pub policy: i32,
}

impl Default for Params {
    /// The BWSHCCM of the paper's Table 4 (Cross's baseball), `rtol` 1e-10, `atol` 1e-16 m,
    /// reset: the start values of `modelDescription.xml`.
    fn default() -> Self {
        let l = bw_models::published::CROSS_BWSHCCM;
        Self {
            reals: [
                l.k, l.c, l.n, l.p, l.alpha, l.beta, l.gamma, l.a, 1e-10, 1e-16,
            ],
            laws: law_variables().iter().map(|l| l.start).collect(),
            model: 0,
            policy: 0,
        }
    }
}

/// What changes while stepping: what fmi2GetFMUstate saves.
#[derive(Debug, Clone)]
pub struct Dynamic {
    element: Option<AnyContactElement>,
    delta: f64,
    delta_dot: f64,
    /// The relative acceleration over the next step (m/s², the derivative of `delta_dot`),
    /// 0 unless fmi2SetRealInputDerivatives gave it.
    accel: f64,
    impulse: f64,
    time: f64,
}

/// One instance.
#[derive(Debug, Clone)]
pub struct Instance {
    params: Params,
    phase: Phase,
    dynamic: Dynamic,
}

impl Default for Instance {
    fn default() -> Self {
        Self::new()
    }
}

impl Instance {
    /// A fresh instance with the default parameters.
    pub fn new() -> Self {
        Self {
            params: Params::default(),
            phase: Phase::Instantiated,
            dynamic: Dynamic {
                element: None,
                delta: 0.0,
                delta_dot: 0.0,
                accel: 0.0,
                impulse: 0.0,
                time: 0.0,
            },
        }
    }

    /// The phase.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// The time of the last communication point (s).
    pub fn time(&self) -> f64 {
        self.dynamic.time
    }

    /// fmi2SetupExperiment: the start time.
    pub fn setup(&mut self, start: f64) -> Result<(), String> {
        self.expect(&[Phase::Instantiated], "fmi2SetupExperiment")?;
        if !start.is_finite() {
            return Err(format!("startTime = {start} is not finite"));
        }
        self.dynamic.time = start;
        Ok(())
    }

    /// fmi2EnterInitializationMode.
    pub fn enter_initialization(&mut self) -> Result<(), String> {
        self.expect(&[Phase::Instantiated], "fmi2EnterInitializationMode")?;
        self.phase = Phase::Initialization;
        Ok(())
    }

    /// fmi2ExitInitializationMode: the law from the parameters, checked.
    pub fn exit_initialization(&mut self) -> Result<(), String> {
        self.expect(&[Phase::Initialization], "fmi2ExitInitializationMode")?;
        self.dynamic.element = Some(element(&self.params)?);
        self.phase = Phase::Stepping;
        Ok(())
    }

    /// fmi2Terminate.
    pub fn terminate(&mut self) -> Result<(), String> {
        self.expect(&[Phase::Stepping], "fmi2Terminate")?;
        self.phase = Phase::Terminated;
        Ok(())
    }

    /// fmi2Reset: as instantiated, with the default parameters.
    pub fn reset(&mut self) {
        *self = Self::new();
    }

    fn expect(&self, phases: &[Phase], what: &str) -> Result<(), String> {
        if phases.contains(&self.phase) {
            Ok(())
        } else {
            Err(format!("{what} is not allowed in phase {:?}", self.phase))
        }
    }

    /// fmi2SetReal of one variable.
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), String> {
        let v = variable(vr, Type::Real)?;
        match v.causality {
            "parameter" => {
                self.settable(v)?;
                *self.params.real(v.vr)? = value;
                Ok(())
            }
            "input" => {
                if !value.is_finite() {
                    return Err(format!(
                        "input `{}` = {value} is not admissible: a finite number",
                        v.name
                    ));
                }
                match v.name {
                    "delta" => self.dynamic.delta = value,
                    _ => self.dynamic.delta_dot = value,
                }
                Ok(())
            }
            _ => Err(format!("`{}` is an output: it cannot be set", v.name)),
        }
    }

    /// fmi2SetInteger of one variable.
    pub fn set_integer(&mut self, vr: u32, value: i32) -> Result<(), String> {
        let v = variable(vr, Type::Integer)?;
        if v.causality != "parameter" {
            return Err(format!("`{}` is an output: it cannot be set", v.name));
        }
        self.settable(v)?;
        let top = if v.name == "model" {
            ELEMENT_LAWS.len() as i32 - 1
        } else {
            1
        };
        if !(0..=top).contains(&value) {
            return Err(format!(
                "parameter `{}` = {value} is not admissible: {}",
                v.name, v.description
            ));
        }
        match v.name {
            "model" => self.params.model = value,
            _ => self.params.policy = value,
        }
        Ok(())
    }

    fn settable(&self, v: &Variable) -> Result<(), String> {
        self.expect(&[Phase::Instantiated, Phase::Initialization], "")
            .map_err(|_| {
                format!(
                    "parameter `{}` is fixed once initialized: set it before \
                     fmi2ExitInitializationMode (or after fmi2Reset)",
                    v.name
                )
            })
    }

    /// fmi2GetReal of one variable.
    pub fn get_real(&self, vr: u32) -> Result<f64, String> {
        let v = variable(vr, Type::Real)?;
        let d = &self.dynamic;
        let e = d.element.as_ref();
        Ok(match v.name {
            "delta" => d.delta,
            "delta_dot" => d.delta_dot,
            "force" => e.map_or(0.0, |e| e.force()),
            "impulse" => d.impulse,
            "dissipated" => e.map_or(0.0, |e| e.dissipated()),
            "absorbed" => e.map_or(0.0, |e| e.absorbed()),
            _ => match real_slot(v.vr)? {
                (false, i) => self.params.reals[i],
                (true, i) => self.params.laws[i],
            },
        })
    }

    /// fmi2GetInteger of one variable.
    pub fn get_integer(&self, vr: u32) -> Result<i32, String> {
        let v = variable(vr, Type::Integer)?;
        let e = self.dynamic.element.as_ref();
        Ok(match v.name {
            "model" => self.params.model,
            "policy" => self.params.policy,
            _ => e.map_or(0, |e| i32::try_from(e.contacts()).unwrap_or(i32::MAX)),
        })
    }

    /// fmi2GetBoolean of one variable.
    pub fn get_boolean(&self, vr: u32) -> Result<bool, String> {
        variable(vr, Type::Boolean)?;
        Ok(self
            .dynamic
            .element
            .as_ref()
            .is_some_and(|e| e.in_contact()))
    }

    /// fmi2SetRealInputDerivatives of one input: order 1 of `delta_dot` (or order 2 of
    /// `delta`) is the relative acceleration over the next step; order 1 of `delta` must be
    /// `delta_dot`'s value and is taken as it.
    pub fn set_input_derivative(&mut self, vr: u32, order: i32, value: f64) -> Result<(), String> {
        let v = variable(vr, Type::Real)?;
        if v.causality != "input" {
            return Err(format!("`{}` is not an input", v.name));
        }
        if !value.is_finite() {
            return Err(format!(
                "the derivative of order {order} of `{}` = {value} is not admissible: a finite \
                 number",
                v.name
            ));
        }
        match (v.name, order) {
            ("delta_dot", 1) | ("delta", 2) => self.dynamic.accel = value,
            ("delta", 1) => self.dynamic.delta_dot = value,
            _ => {
                return Err(format!(
                    "derivative of order {order} of `{}`: the FMU takes order 1 of `delta_dot` \
                     (or 1 and 2 of `delta`)",
                    v.name
                ))
            }
        }
        Ok(())
    }

    /// fmi2DoStep from `t` over `h`: the penetration from its value and rate (and the
    /// acceleration, where given) at `t`, quadratic over the step.
    pub fn do_step(&mut self, t: f64, h: f64) -> Result<(), String> {
        self.expect(&[Phase::Stepping], "fmi2DoStep")?;
        if !(h > 0.0 && h.is_finite()) {
            return Err(format!(
                "communicationStepSize = {} is not admissible: > 0 (s), finite",
                number(h)
            ));
        }
        let d = &mut self.dynamic;
        if (t - d.time).abs() > 1e-9 * d.time.abs().max(h) {
            return Err(format!(
                "currentCommunicationPoint = {} is not the FMU's time {}: step on from the last \
                 step's end (or restore an FMU state)",
                number(t),
                number(d.time)
            ));
        }
        let start = Penetration {
            depth: d.delta,
            rate: d.delta_dot,
        };
        let end = Penetration {
            depth: d.delta + h * (d.delta_dot + 0.5 * h * d.accel),
            rate: d.delta_dot + h * d.accel,
        };
        let element = d.element.as_mut().ok_or("the FMU is not initialized")?;
        let step = element
            .advance_penetration(h, start, end)
            .map_err(|e| step_failure(&e, h))?;
        d.impulse = step.impulse;
        d.time = t + h;
        d.accel = 0.0;
        Ok(())
    }

    /// What fmi2GetFMUstate saves.
    pub fn snapshot(&self) -> Dynamic {
        self.dynamic.clone()
    }

    /// fmi2SetFMUstate: back to a saved state.
    pub fn restore(&mut self, saved: &Dynamic) {
        self.dynamic = saved.clone();
    }
}

fn variable(vr: u32, kind: Type) -> Result<&'static Variable, String> {
    find(vr, kind).ok_or_else(|| format!("no {kind:?} variable has value reference {vr}"))
}

impl Params {
    /// The real parameter at value reference `vr`.
    fn real(&mut self, vr: u32) -> Result<&mut f64, String> {
        Ok(match real_slot(vr)? {
            (false, i) => &mut self.reals[i],
            (true, i) => &mut self.laws[i],
        })
    }

    fn settings(&self) -> ElementSettings {
        let mut settings = ElementSettings::default();
        settings.rtol = self.reals[8];
        settings.atol = self.reals[9];
        settings.policy = if self.policy == 1 {
            Policy::Carry
        } else {
            Policy::Reset
        };
        settings
    }
}

/// Where the real parameter at `vr` is: in [`Params::laws`] (`true`) or [`Params::reals`],
/// at which index.
fn real_slot(vr: u32) -> Result<(bool, usize), String> {
    let v = find(vr, Type::Real).map_or("", |v| v.name);
    if let Some(i) = REAL_PARAMETERS.iter().position(|n| *n == v) {
        return Ok((false, i));
    }
    law_variables()
        .iter()
        .position(|l| l.variable.vr == vr)
        .map(|i| (true, i))
        .ok_or_else(|| format!("no real parameter has value reference {vr}"))
}

/// The element the parameters describe; an error names the parameter.
fn element(p: &Params) -> Result<AnyContactElement, String> {
    let model = usize::try_from(p.model).unwrap_or(0);
    if model >= BOUC_WEN_MODELS {
        return named_element(p, model);
    }
    let [k, c, n, pp, alpha, beta, gamma, a, ..] = p.reals;
    let kind = if model == 1 {
        ModelKind::Mcm
    } else {
        ModelKind::Shccm
    };
    let law = Physical {
        k,
        c,
        n,
        p: pp,
        alpha,
        beta,
        gamma,
        a,
    };
    let params = PhysicalParams::new(kind, law).map_err(|e| e.to_string())?;
    AnyContactElement::new(&params, p.settings()).map_err(|e| e.to_string())
}

/// The element of a law beyond the Bouc-Wen ones, from its `<law>.<parameter>` variables; an
/// error names the variable.
fn named_element(p: &Params, model: usize) -> Result<AnyContactElement, String> {
    let mine: Vec<_> = law_variables()
        .iter()
        .zip(&p.laws)
        .filter(|(l, _)| l.law == model)
        .collect();
    let values: Vec<(&str, f64)> = mine.iter().map(|(l, v)| (l.param, **v)).collect();
    AnyContactElement::of_law(ELEMENT_LAWS[model].name, &values, p.settings()).map_err(
        |e| match e {
            ModelError::InvalidParameter {
                name,
                value,
                allowed,
            } => {
                let variable = mine
                    .iter()
                    .find(|(l, _)| l.param == name)
                    .map_or(name, |(l, _)| l.variable.name);
                format!("parameter `{variable}` = {value} is not admissible: {allowed}")
            }
            e => e.to_string(),
        },
    )
}

/// A failed step's message in the FMU's names: the step is `communicationStepSize`, the
/// motion `delta` and `delta_dot`, the tolerances the parameters `rtol` and `atol`.
fn step_failure(e: &bw_models::ModelError, h: f64) -> String {
    use bw_models::{ModelError, Remedy};
    if let ModelError::InvalidSetting {
        name: "dt",
        allowed,
        ..
    } = e
    {
        return format!(
            "communicationStepSize = {} is not admissible: {allowed}",
            number(h)
        );
    }
    let hint = match Remedy::of(e) {
        Some(Remedy::CheckVelocities) => {
            "; the state overflowed: check the inputs `delta`, `delta_dot` (and its derivative) \
             and the law's parameters"
        }
        Some(Remedy::ShorterStep) => {
            "; take a shorter communicationStepSize, or loosen the parameter `rtol`"
        }
        Some(Remedy::LooserTolerances) => {
            "; take a shorter communicationStepSize, loosen the parameters `rtol` and `atol`, or \
             check the inputs and the law's parameters (a very stiff or large-exponent law)"
        }
        _ => "",
    };
    format!("{e}{hint}")
}

/// A number as a message shows it: in full where short, else with an exponent (`4e-306`, not
/// 306 zeros).
fn number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
