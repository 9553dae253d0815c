//! `bwc.Contact` and `bwc.Contacts`: the contact element for Python hosts, one at a time or
//! many at once (in parallel, with the GIL released).

use crate::BwcError;
use bw_models::sequence::Policy;
use bw_models::{
    law_spec, AnyContactElement, BaseMap, BaseParams, ElementSettings, ElementStep, LawSpec,
    ModelKind, Penetration, Physical, PhysicalParams, ELEMENT_LAWS,
};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

const BASE: [&str; 8] = ["B_b", "Gamma_b", "kappa", "sigma_b", "n", "p", "U_b", "T_b"];

/// The SI parameters of a Bouc-Wen law, as its registry spec names them: `k, c, n, p, alpha,
/// beta, gamma, A`.
fn physical_names() -> Vec<&'static str> {
    let spec = &<bw_models::Bwshccl as bw_models::NamedLaw<2>>::SPEC;
    spec.params.iter().map(|p| p.name).collect()
}

/// The Bouc-Wen law of `kind` from a dict of SI parameters (`k, c, n, p, alpha, beta, gamma, A`; an
/// `m` is not the law's and is left alone) or of base parameters (`B_b, Gamma_b, kappa,
/// sigma_b, n, p, U_b, T_b`, with `A = 1`), and the mass the base parameters imply.
fn law(kind: ModelKind, params: &Bound<'_, PyAny>) -> PyResult<(PhysicalParams, Option<f64>)> {
    let (base, v) = values(params)?;
    let bad = |e: bw_models::ModelError| BwcError::new_err(format!("params: {e}"));
    if base {
        let [b_b, gamma_b, kappa, sigma_b, n, p, u_b, t_b] = v;
        let b = BaseParams {
            b_b,
            gamma_b,
            kappa,
            sigma_b,
            n,
            p,
            u_b,
            t_b,
        };
        let (law, m) = BaseMap::new(kind, b)
            .and_then(|m| m.physical())
            .map_err(bad)?;
        Ok((law, Some(m)))
    } else {
        let [k, c, n, p, alpha, beta, gamma, a] = v;
        let l = Physical {
            k,
            c,
            n,
            p,
            alpha,
            beta,
            gamma,
            a,
        };
        Ok((PhysicalParams::new(kind, l).map_err(bad)?, None))
    }
}

/// The registered laws' names, quoted, for messages: `"shccm", "mcm", ... or "thornton"`.
fn law_names() -> String {
    let quoted: Vec<String> = ELEMENT_LAWS
        .iter()
        .map(|s| format!("\"{}\"", s.name))
        .collect();
    match quoted.split_last() {
        Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
        None => String::new(),
    }
}

/// The law a `model` argument names: one of [`ELEMENT_LAWS`].
fn law_name(model: &Bound<'_, PyAny>) -> PyResult<String> {
    match word(model, "model")? {
        Some(name) if law_spec(&name).is_ok() => Ok(name),
        Some(name) => Err(BwcError::new_err(format!(
            "model: \"{name}\" is not a model: {}",
            law_names()
        ))),
        None => Err(BwcError::new_err(format!(
            "model = {} is not a model: the string {}",
            shown(model),
            law_names()
        ))),
    }
}

/// The element of a law other than the Bouc-Wen ones from a dict of its parameters, each
/// key checked against its spec.
fn named_element(
    spec: &LawSpec,
    params: &Bound<'_, PyAny>,
    settings: ElementSettings,
) -> PyResult<AnyContactElement> {
    let dict = params.downcast::<PyDict>().map_err(|_| {
        BwcError::new_err(format!(
            "params = {} is not admissible: a dict of the law's parameters ({})",
            shown(params),
            spec.param_list()
        ))
    })?;
    let mut named: Vec<(String, f64)> = Vec::new();
    for (key, value) in dict.iter() {
        let Some(key) = word(&key, "params")? else {
            return Err(BwcError::new_err(format!(
                "params: the key {} is not a parameter of the law: {}",
                shown(&key),
                spec.param_list()
            )));
        };
        let value = value
            .extract()
            .map_err(|_| BwcError::new_err(format!("params[\"{key}\"]: not a number")))?;
        named.push((key, value));
    }
    let pairs: Vec<(&str, f64)> = named.iter().map(|(k, v)| (k.as_str(), *v)).collect();
    AnyContactElement::of_law(spec.name, &pairs, settings)
        .map_err(|e| BwcError::new_err(format!("params: {e}")))
}

/// Whether a `params` dict holds base parameters, and its eight values in the order of
/// [`BASE`] or [`physical_names`]; every key checked, every value a number.
fn values(params: &Bound<'_, PyAny>) -> PyResult<(bool, [f64; 8])> {
    let params = params.downcast::<PyDict>().map_err(|_| {
        BwcError::new_err(format!(
            "params = {} is not admissible: a dict of the law's parameters ({}; or {})",
            shown(params),
            physical_names().join(", "),
            BASE.join(", ")
        ))
    })?;
    let base = params.contains("B_b")? || params.contains("sigma_b")?;
    let physical = physical_names();
    let names: &[&str] = if base { &BASE } else { &physical };
    for key in params.keys() {
        let Some(key) = word(&key, "params")? else {
            return Err(BwcError::new_err(format!(
                "params: the key {} is not a parameter of the law: {}",
                shown(&key),
                names.join(", ")
            )));
        };
        // An SI dict may carry the bodies' `m` (a scene's `[physical]` does); the law has none.
        let known = names.contains(&key.as_str()) || (key == "m" && !base);
        if !known {
            return Err(BwcError::new_err(format!(
                "params[\"{key}\"]: not a parameter of the law: {}",
                names.join(", ")
            )));
        }
    }
    let mut v = [0.0; 8];
    for (slot, name) in v.iter_mut().zip(names) {
        let value = params.get_item(name)?.ok_or_else(|| {
            BwcError::new_err(format!(
                "params[\"{name}\"] is missing: the law needs {}",
                names.join(", ")
            ))
        })?;
        *slot = value
            .extract()
            .map_err(|_| BwcError::new_err(format!("params[\"{name}\"]: not a number")))?;
    }
    Ok((base, v))
}

fn settings(policy: &Bound<'_, PyAny>, rtol: f64, atol: f64) -> PyResult<ElementSettings> {
    let mut s = ElementSettings::default();
    s.rtol = rtol;
    s.atol = atol;
    s.policy = match word(policy, "policy")?.as_deref() {
        Some("reset") => Policy::Reset,
        Some("carry") => Policy::Carry,
        Some(other) => {
            return Err(BwcError::new_err(format!(
                "policy: \"{other}\" is not a policy: \"reset\" or \"carry\""
            )))
        }
        None => {
            return Err(BwcError::new_err(format!(
                "policy = {} is not a policy: the string \"reset\" or \"carry\"",
                shown(policy)
            )))
        }
    };
    Ok(s)
}

/// `value` as a Rust string if it is a Python `str` (`None` if it is not); an error naming
/// `name` only for a string Python cannot give as UTF-8 (lone surrogates).
fn word(value: &Bound<'_, PyAny>, name: &str) -> PyResult<Option<String>> {
    let Ok(s) = value.downcast::<PyString>() else {
        return Ok(None);
    };
    s.to_cow()
        .map(|t| Some(t.into_owned()))
        .map_err(|_| BwcError::new_err(format!("{name}: a string that is not valid UTF-8")))
}

/// A failed step's error with what the caller can change, in the arguments' names.
pub(crate) fn failed_step(e: &bw_models::ModelError) -> String {
    use bw_models::Remedy;
    let hint = match Remedy::of(e) {
        Some(Remedy::CheckVelocities) => {
            "; the state overflowed: check the velocities (or penetration rates, m/s) and the \
             law's parameters"
        }
        Some(Remedy::ShorterStep) => "; take a shorter step dt, or a looser rtol",
        Some(Remedy::LooserTolerances) => {
            "; take a shorter step dt, a looser rtol and atol, or check the velocities and the \
             law's parameters (a very stiff or large-exponent law)"
        }
        _ => "",
    };
    format!("{e}{hint}")
}

/// A value as an error message shows it: its repr, cut to 60 characters.
fn shown(value: &Bound<'_, PyAny>) -> String {
    let repr = value
        .repr()
        .map_or_else(|_| "<unprintable>".to_owned(), |r| r.to_string());
    match repr.char_indices().nth(60) {
        Some((i, _)) => format!("{}...", &repr[..i]),
        None => repr,
    }
}

/// The contact element of `model` and `params` with `policy` and tolerances, and the mass the
/// parameters imply (base parameters); every argument of the wrong type or value is an error
/// naming it.
pub(crate) fn element(
    model: &Bound<'_, PyAny>,
    params: &Bound<'_, PyAny>,
    policy: &Bound<'_, PyAny>,
    rtol: f64,
    atol: f64,
) -> PyResult<(AnyContactElement, Option<f64>)> {
    let name = law_name(model)?;
    let settings = settings(policy, rtol, atol)?;
    let Some(kind) = ModelKind::parse(&name) else {
        let spec = law_spec(&name).map_err(|e| BwcError::new_err(format!("model: {e}")))?;
        return Ok((named_element(spec, params, settings)?, None));
    };
    let (law, mass) = law(kind, params)?;
    let element =
        AnyContactElement::new(&law, settings).map_err(|e| BwcError::new_err(e.to_string()))?;
    Ok((element, mass))
}

pub(crate) fn policy_name(e: &AnyContactElement) -> &'static str {
    match e.settings().policy {
        Policy::Reset => "reset",
        Policy::Carry => "carry",
    }
}

/// What one host step of a :class:`Contact` gave.
///
/// Attributes
/// ----------
/// force : float
///     The force at the step's end (N, positive pushing the bodies apart; 0 once separated).
/// impulse : float
///     The impulse of the force over the step (N s): what the host's momentum balance needs.
/// work : float
///     The work the bodies did on the contact over the step (J).
/// separated_at : float or None
///     Where the contact ended in the step (s from its start).
/// began_at : float or None
///     Where a contact began in the step (s from its start; penetration input only).
#[pyclass(module = "bwc", frozen, get_all)]
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// The force at the step's end (N, positive pushing the bodies apart; 0 once separated).
    force: f64,
    /// The impulse of the force over the step (N s).
    impulse: f64,
    /// The work the bodies did on the contact over the step (J).
    work: f64,
    /// Where the contact ended in the step (s from its start), or None.
    separated_at: Option<f64>,
    /// Where a contact began in the step (s from its start; penetration input), or None.
    began_at: Option<f64>,
}

#[pymethods]
impl Step {
    fn __repr__(&self) -> String {
        let opt = |v: Option<f64>| v.map_or("None".into(), py_float);
        format!(
            "Step(force={}, impulse={}, work={}, separated_at={}, began_at={})",
            py_float(self.force),
            py_float(self.impulse),
            py_float(self.work),
            opt(self.separated_at),
            opt(self.began_at)
        )
    }
}

/// A float as Python writes it in a repr, to 6 significant digits: `0.0`, `1.5`, `0.0025`,
/// `1.23457e-07`.
pub(crate) fn py_float(x: f64) -> String {
    if x == 0.0 {
        return "0.0".into();
    }
    if !x.is_finite() {
        return if x.is_nan() {
            "nan"
        } else if x > 0.0 {
            "inf"
        } else {
            "-inf"
        }
        .into();
    }
    let magnitude = x.abs();
    if (1e-4..1e6).contains(&magnitude) {
        let digits = (5 - magnitude.log10().floor() as i32).max(0) as usize;
        let text = format!("{x:.digits$}");
        let text = if text.contains('.') {
            text.trim_end_matches('0').to_string()
        } else {
            text
        };
        if text.ends_with('.') {
            format!("{text}0")
        } else {
            text
        }
    } else {
        let text = format!("{x:.5e}");
        let (mantissa, exponent) = text.split_once('e').unwrap_or((&text, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        let exponent: i32 = exponent.parse().unwrap_or(0);
        format!(
            "{mantissa}e{}{:02}",
            if exponent < 0 { '-' } else { '+' },
            exponent.abs()
        )
    }
}

impl From<ElementStep> for Step {
    fn from(s: ElementStep) -> Self {
        Self {
            force: s.force,
            impulse: s.impulse,
            work: s.work,
            separated_at: s.separated_at,
            began_at: s.began_at,
        }
    }
}

/// A contact element: one contact's law and state, carried between a host simulator's steps.
///
/// Per step the host gives the time step and the relative motion; the element integrates the
/// law's stiff internal states over the step to ``rtol`` (its own steps, stopping at the
/// law's kinks), finds the separation ``F <= 0 <= u`` inside it and returns the force at the
/// step's end, its impulse and its work. SI units; ``F > 0`` pushes the bodies apart, the
/// relative velocity ``u < 0`` while they approach, the penetration is positive while they
/// overlap.
///
/// Parameters
/// ----------
/// model : str
///     ``"shccm"`` or ``"mcm"``, the Bouc-Wen-Simon-Hunt-Crossley or the Bouc-Wen-Maxwell
///     law, or another of the element laws (``"thornton"``, ``"hunt-crossley"``, ...: the
///     guide's reference of contact laws lists them with their parameters).
/// params : dict
///     For the Bouc-Wen laws, SI parameters ``k, c, n, p, alpha, beta, gamma, A`` (an ``m``
///     may be there and is not used: the law has no mass), or base parameters ``B_b,
///     Gamma_b, kappa, sigma_b, n, p, U_b, T_b`` (the law with ``A = 1``; :attr:`mass` is
///     then ``T_b / U_b``). For the others, their SI parameters by name (Thornton's ``k``,
///     N/m^(3/2), and ``delta_y``, m).
/// policy : {"reset", "carry"}
///     What a new contact starts from: the law at rest, or the state of the last separation.
/// rtol, atol : float
///     Tolerances of the internal steps: relative, and absolute of the law's states (m).
///
/// Attributes
/// ----------
/// force : float
///     The force at the end of the last step (N).
/// state : numpy.ndarray
///     The law's states (m): ``x, z`` or ``r, y, z`` (Bouc-Wen), as the reference names them
///     for the other laws (Thornton's ``x, x_m``: ``x_m`` the deepest ``x`` so far).
/// absorbed, dissipated : float
///     The work done on the contact so far, and the part of it not held by the law's springs
///     (J).
/// in_contact : bool
///     Whether a contact is under way.
/// contacts : int
///     Contacts that have ended.
/// onset_depth : float
///     The penetration (m) at which the next contact begins (penetration input): 0, then the
///     penetration at the last separation.
/// model, policy : str
/// mass : float or None
///     The mass base parameters were taken with (kg).
///
/// Raises
/// ------
/// BwcError
///     A parameter or setting outside its admissible set, named with its value.
///
/// See Also
/// --------
/// Contacts : many contacts of one law, advanced together.
///
/// Examples
/// --------
/// >>> import bwc
/// >>> law = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1,
/// ...        "beta": 981.05, "gamma": -961.4, "A": 0.925}
/// >>> contact = bwc.Contact("shccm", law)
/// >>> step = contact.advance(1e-5, -2.0, -2.0)   # 10 us of an approach at 2 m/s
/// >>> bool(step.force > 0), step.separated_at, contact.in_contact
/// (True, None, True)
/// >>> round(float(contact.state[0]) * 1e6, 9)    # x = u dt, in um
/// -20.0
#[pyclass(module = "bwc")]
#[derive(Debug, Clone)]
pub struct Contact {
    element: AnyContactElement,
    mass: Option<f64>,
}

impl Contact {
    pub(crate) fn of(element: AnyContactElement, mass: Option<f64>) -> Self {
        Self { element, mass }
    }
}

#[pymethods]
impl Contact {
    #[new]
    #[pyo3(signature = (model, params, *, policy=None, rtol=1e-10, atol=1e-16))]
    fn new(
        model: &Bound<'_, PyAny>,
        params: &Bound<'_, PyAny>,
        policy: Option<&Bound<'_, PyAny>>,
        rtol: f64,
        atol: f64,
    ) -> PyResult<Self> {
        let reset = PyString::new(model.py(), "reset");
        let policy = policy.unwrap_or(reset.as_any());
        let (element, mass) = element(model, params, policy, rtol, atol)?;
        Ok(Self { element, mass })
    }

    /// Advances the element over a host step with the relative velocity.
    ///
    /// Call it while the bodies touch: a step starts a contact if none is under way. After a
    /// separation inside the step the force is 0 for the rest of it.
    ///
    /// Parameters
    /// ----------
    /// dt : float
    ///     The step (s), > 0.
    /// u_start, u_end : float
    ///     The relative velocity (m/s, negative while the bodies approach) at the step's start
    ///     and end, taken as linear in between.
    ///
    /// Returns
    /// -------
    /// Step
    ///
    /// Raises
    /// ------
    /// BwcError
    ///     A bad argument (named) or a failed integration; the element is unchanged.
    fn advance(&mut self, py: Python<'_>, dt: f64, u_start: f64, u_end: f64) -> PyResult<Step> {
        let e = &mut self.element;
        py.allow_threads(|| e.advance(dt, u_start, u_end))
            .map(Step::from)
            .map_err(|e| BwcError::new_err(format!("advance: {}", failed_step(&e))))
    }

    /// Advances the element over a host step with the penetration.
    ///
    /// The penetration is the cubic Hermite interpolant of its values and rates at the ends.
    /// Out of contact, a contact begins where the penetration rises through
    /// :attr:`onset_depth`; it ends at ``F <= 0 <= u``. A step may hold several.
    ///
    /// Parameters
    /// ----------
    /// dt : float
    ///     The step (s), > 0.
    /// depth_start, rate_start : float
    ///     The penetration (m, positive while the bodies overlap) and its rate (m/s, positive
    ///     while they approach) at the step's start.
    /// depth_end, rate_end : float
    ///     The same at the step's end.
    ///
    /// Returns
    /// -------
    /// Step
    ///
    /// Raises
    /// ------
    /// BwcError
    ///     A bad argument (named) or a failed integration; the element is unchanged.
    fn advance_penetration(
        &mut self,
        py: Python<'_>,
        dt: f64,
        depth_start: f64,
        rate_start: f64,
        depth_end: f64,
        rate_end: f64,
    ) -> PyResult<Step> {
        let (a, b) = ends(depth_start, rate_start, depth_end, rate_end);
        let e = &mut self.element;
        py.allow_threads(|| e.advance_penetration(dt, a, b))
            .map(Step::from)
            .map_err(|e| BwcError::new_err(format!("advance_penetration: {}", failed_step(&e))))
    }

    /// Back to the law at rest, out of contact, nothing absorbed.
    fn reset(&mut self) {
        self.element.reset();
    }

    /// An independent copy (to try a step before taking it).
    fn copy(&self) -> Self {
        self.clone()
    }

    fn __copy__(&self) -> Self {
        self.clone()
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> Self {
        self.clone()
    }

    /// The force at the end of the last step (N).
    #[getter]
    fn force(&self) -> f64 {
        self.element.force()
    }

    /// The law's state (m) as a new array: x, z (SHCCM) or r, y, z (MCM).
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, self.element.state())
    }

    /// The work the bodies did on the contact so far (J).
    #[getter]
    fn absorbed(&self) -> f64 {
        self.element.absorbed()
    }

    /// The energy dissipated so far (J).
    #[getter]
    fn dissipated(&self) -> f64 {
        self.element.dissipated()
    }

    /// Whether a contact is under way.
    #[getter]
    fn in_contact(&self) -> bool {
        self.element.in_contact()
    }

    /// Contacts that have ended.
    #[getter]
    fn contacts(&self) -> u64 {
        self.element.contacts()
    }

    /// The penetration (m) at which the next contact begins (penetration input).
    #[getter]
    fn onset_depth(&self) -> f64 {
        self.element.onset_depth()
    }

    /// "shccm" or "mcm".
    #[getter]
    fn model(&self) -> &'static str {
        self.element.spec().name
    }

    /// "reset" or "carry".
    #[getter]
    fn policy(&self) -> &'static str {
        policy_name(&self.element)
    }

    /// The mass (kg) base parameters were taken with (`T_b / U_b`); None for SI parameters.
    #[getter]
    fn mass(&self) -> Option<f64> {
        self.mass
    }

    fn __repr__(&self) -> String {
        format!(
            "Contact(model='{}', policy='{}', in_contact={}, force={}, dissipated={}, \
             contacts={})",
            self.model(),
            self.policy(),
            if self.in_contact() { "True" } else { "False" },
            py_float(self.force()),
            py_float(self.dissipated()),
            self.contacts()
        )
    }
}

fn ends(d0: f64, r0: f64, d1: f64, r1: f64) -> (Penetration, Penetration) {
    (
        Penetration {
            depth: d0,
            rate: r0,
        },
        Penetration {
            depth: d1,
            rate: r1,
        },
    )
}
