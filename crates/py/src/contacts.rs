//! `bwc.Contacts`: many contact elements of one law, advanced together in parallel.

use crate::contact::{element, failed_step, policy_name, Contact};
use crate::BwcError;
use bw_models::{AnyContactElement, ElementStep, ModelError, Penetration};
use numpy::ndarray::Array2;
use numpy::{
    AllowTypeChange, IntoPyArray, PyArray1, PyArray2, PyArrayLikeDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

// Taken at any dimension so that a 2-D array is an error naming its argument and shape, not
// the extraction's own message.
type Floats<'py> = PyArrayLikeDyn<'py, f64, AllowTypeChange>;
type Indices<'py> = PyArrayLikeDyn<'py, i64, AllowTypeChange>;

/// The error for argument `name` given an array of more than one dimension.
fn one_dimensional(name: &str, shape: &[usize]) -> PyResult<()> {
    if shape.len() <= 1 {
        return Ok(());
    }
    let dims: Vec<String> = shape.iter().map(usize::to_string).collect();
    Err(BwcError::new_err(format!(
        "{name}: an array of shape ({}): give a 1-D array, one value per contact advanced",
        dims.join(", ")
    )))
}

/// Many contact elements of one law, advanced together in parallel (the GIL released).
///
/// For hosts that step thousands of contacts: each call takes arrays, one value per contact
/// advanced (all of them, or those ``index`` names), and returns a dict of arrays. A call
/// is all or nothing: on an error no contact is advanced. Results do not depend on the
/// number of threads.
///
/// Parameters
/// ----------
/// model, params, policy, rtol, atol
///     As :class:`Contact`.
/// count : int
///     The number of contacts, >= 1, all out of contact and at rest.
///
/// Attributes
/// ----------
/// force, absorbed, dissipated, onset_depth : numpy.ndarray
///     Per contact, as :class:`Contact`'s.
/// in_contact : numpy.ndarray of bool
/// contacts : numpy.ndarray of uint64
/// state : numpy.ndarray
///     The laws' states (m), one row per contact.
/// model, policy : str
/// mass : float or None
///
/// Examples
/// --------
/// >>> import numpy as np, bwc
/// >>> law = {"k": 117080063.0, "c": 5854003.0, "n": 1.1, "p": 1.7, "alpha": 0.1,
/// ...        "beta": 981.05, "gamma": -961.4, "A": 0.925}
/// >>> many = bwc.Contacts("shccm", law, 1000)
/// >>> u = -np.linspace(1.0, 3.0, 1000)          # approach speeds, m/s
/// >>> out = many.advance(1e-5, u, u)
/// >>> bool(np.all(np.diff(out["force"]) > 0))   # faster, deeper, harder
/// True
/// >>> out = many.advance(1e-5, u[:2], u[:2], index=[0, 1])   # only the first two
/// >>> [int(n) for n in many.state.shape]
/// [1000, 2]
#[pyclass(module = "bwc")]
#[derive(Debug, Clone)]
pub struct Contacts {
    elements: Vec<AnyContactElement>,
    mass: Option<f64>,
}

/// An array argument as numpy gives it, else a [`BwcError`] naming it (not numpy's own
/// ValueError for, say, a string among the numbers).
fn array_of<'py, T>(
    name: &str,
    value: &Bound<'py, PyAny>,
    what: &str,
) -> PyResult<PyArrayLikeDyn<'py, T, AllowTypeChange>>
where
    T: numpy::Element + 'py,
    Vec<T>: FromPyObject<'py>,
{
    value.extract().map_err(|e: PyErr| {
        let why = e.value(value.py()).to_string();
        BwcError::new_err(format!("{name}: {why}: give {what}"))
    })
}

/// An input array's values, checked to have one per advanced contact.
fn values(name: &str, value: &Bound<'_, PyAny>, expected: usize) -> PyResult<Vec<f64>> {
    let array: Floats<'_> = array_of(name, value, "numbers, one per contact advanced")?;
    one_dimensional(name, array.shape())?;
    let values: Vec<f64> = array.as_array().iter().copied().collect();
    if values.len() != expected {
        return Err(BwcError::new_err(format!(
            "{name}: {} values for {expected} contacts: give one per contact advanced",
            values.len()
        )));
    }
    Ok(values)
}

impl Contacts {
    /// The contacts `index` names (all, in order, without one), checked: in range and each
    /// once.
    fn selected(&self, index: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<usize>> {
        let n = self.elements.len();
        let Some(index) = index else {
            return Ok((0..n).collect());
        };
        let index: Indices<'_> = array_of("index", index, "integers, the contacts to advance")?;
        one_dimensional("index", index.shape())?;
        let mut seen = vec![false; n];
        let mut out = Vec::with_capacity(index.as_array().len());
        for (k, &i) in index.as_array().iter().enumerate() {
            let bad = |why: String| BwcError::new_err(format!("index[{k}] = {i}: {why}"));
            let at = usize::try_from(i)
                .ok()
                .filter(|&u| u < n)
                .ok_or_else(|| bad(format!("not a contact: 0 <= index < {n}")))?;
            if std::mem::replace(&mut seen[at], true) {
                return Err(bad("named twice: advance each contact once per step".into()));
            }
            out.push(at);
        }
        Ok(out)
    }

    /// Advances the contacts `chosen` by `step(element, k)` (k: the position in `chosen`) in
    /// parallel without the GIL; all or nothing.
    fn advance_with<'py>(
        &mut self,
        py: Python<'py>,
        what: &str,
        chosen: &[usize],
        step: impl Fn(&mut AnyContactElement, usize) -> Result<ElementStep, ModelError> + Sync,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mut work: Vec<AnyContactElement> =
            chosen.iter().map(|&i| self.elements[i].clone()).collect();
        let results: Vec<Result<ElementStep, ModelError>> = py.allow_threads(|| {
            work.par_iter_mut()
                .enumerate()
                .map(|(k, e)| step(e, k))
                .collect()
        });
        let mut steps = Vec::with_capacity(results.len());
        for (k, r) in results.into_iter().enumerate() {
            steps.push(r.map_err(|e| {
                BwcError::new_err(format!(
                    "{what}: contact {} (the {k}-th advanced): {}; no contact was advanced",
                    chosen[k],
                    failed_step(&e)
                ))
            })?);
        }
        for (&i, e) in chosen.iter().zip(work) {
            self.elements[i] = e;
        }
        step_arrays(py, &steps)
    }

    fn column<'py, T: numpy::Element>(
        &self,
        py: Python<'py>,
        f: impl Fn(&AnyContactElement) -> T,
    ) -> Bound<'py, PyArray1<T>> {
        self.elements
            .iter()
            .map(f)
            .collect::<Vec<T>>()
            .into_pyarray(py)
    }
}

/// The steps as a dict of arrays: force, impulse, work, separated_at, began_at (NaN where
/// none).
fn step_arrays<'py>(py: Python<'py>, steps: &[ElementStep]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let col = |f: &dyn Fn(&ElementStep) -> f64| steps.iter().map(f).collect::<Vec<f64>>();
    out.set_item("force", col(&|s| s.force).into_pyarray(py))?;
    out.set_item("impulse", col(&|s| s.impulse).into_pyarray(py))?;
    out.set_item("work", col(&|s| s.work).into_pyarray(py))?;
    let nan = f64::NAN;
    out.set_item(
        "separated_at",
        col(&|s| s.separated_at.unwrap_or(nan)).into_pyarray(py),
    )?;
    out.set_item(
        "began_at",
        col(&|s| s.began_at.unwrap_or(nan)).into_pyarray(py),
    )?;
    Ok(out)
}

/// The most contacts one [`Contacts`] holds: about 50 GB of elements.
const MAX_CONTACTS: usize = 100_000_000;

/// The `count` argument: an integer in `1..=MAX_CONTACTS`, else a [`BwcError`] naming it (not
/// Python's OverflowError for a negative one, nor a panic for a huge one).
fn contact_count(count: &Bound<'_, PyAny>) -> PyResult<usize> {
    let refused = |shown: String| {
        BwcError::new_err(format!(
            "count = {shown} is not admissible: an integer, 1 <= count <= {MAX_CONTACTS}"
        ))
    };
    if count.is_instance_of::<pyo3::types::PyBool>() {
        return Err(refused(count.repr()?.to_string()));
    }
    match count.extract::<i128>() {
        Ok(c) if (1..=MAX_CONTACTS as i128).contains(&c) => Ok(c as usize),
        Ok(c) => Err(refused(c.to_string())),
        Err(_) => Err(refused(count.repr()?.to_string())),
    }
}

#[pymethods]
impl Contacts {
    #[new]
    #[pyo3(signature = (model, params, count, *, policy=None, rtol=1e-10, atol=1e-16))]
    fn new(
        model: &Bound<'_, PyAny>,
        params: &Bound<'_, PyAny>,
        count: &Bound<'_, PyAny>,
        policy: Option<&Bound<'_, PyAny>>,
        rtol: f64,
        atol: f64,
    ) -> PyResult<Self> {
        let count = contact_count(count)?;
        let reset = pyo3::types::PyString::new(model.py(), "reset");
        let policy = policy.unwrap_or(reset.as_any());
        let (one, mass) = element(model, params, policy, rtol, atol)?;
        let mut elements = Vec::new();
        elements.try_reserve_exact(count).map_err(|_| {
            BwcError::new_err(format!(
                "count = {count}: no memory for so many contacts; a smaller count, or several \
                 Contacts, would fit"
            ))
        })?;
        elements.resize(count, one);
        Ok(Self { elements, mass })
    }

    /// Advances the contacts over a host step with their relative velocities.
    ///
    /// Parameters
    /// ----------
    /// dt : float
    ///     The step (s), > 0, the same for all.
    /// u_start, u_end : array_like
    ///     The relative velocities (m/s) at the step's start and end, one per contact advanced.
    /// index : array_like of int, optional
    ///     The contacts to advance, each once; all of them without it.
    ///
    /// Returns
    /// -------
    /// dict
    ///     Arrays ``force``, ``impulse``, ``work``, ``separated_at`` and ``began_at`` (NaN
    ///     where none), one value per contact advanced, as :class:`Step`'s.
    ///
    /// Raises
    /// ------
    /// BwcError
    ///     A bad argument or index (named), or a contact whose step failed (named); no
    ///     contact was advanced.
    #[pyo3(signature = (dt, u_start, u_end, index=None))]
    fn advance<'py>(
        &mut self,
        py: Python<'py>,
        dt: f64,
        u_start: &Bound<'py, PyAny>,
        u_end: &Bound<'py, PyAny>,
        index: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let chosen = self.selected(index)?;
        let a = values("u_start", u_start, chosen.len())?;
        let b = values("u_end", u_end, chosen.len())?;
        self.advance_with(py, "advance", &chosen, |e, k| e.advance(dt, a[k], b[k]))
    }

    /// Advances the contacts over a host step with their penetrations.
    ///
    /// Parameters
    /// ----------
    /// dt : float
    ///     The step (s), > 0, the same for all.
    /// depth_start, rate_start, depth_end, rate_end : array_like
    ///     Penetrations (m) and their rates (m/s) at the step's ends, one per contact advanced
    ///     (see :meth:`Contact.advance_penetration`).
    /// index : array_like of int, optional
    ///     The contacts to advance, each once; all of them without it.
    ///
    /// Returns
    /// -------
    /// dict
    ///     As :meth:`advance`.
    ///
    /// Raises
    /// ------
    /// BwcError
    ///     As :meth:`advance`.
    #[pyo3(signature = (dt, depth_start, rate_start, depth_end, rate_end, index=None))]
    #[allow(clippy::too_many_arguments)]
    fn advance_penetration<'py>(
        &mut self,
        py: Python<'py>,
        dt: f64,
        depth_start: &Bound<'py, PyAny>,
        rate_start: &Bound<'py, PyAny>,
        depth_end: &Bound<'py, PyAny>,
        rate_end: &Bound<'py, PyAny>,
        index: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let chosen = self.selected(index)?;
        let n = chosen.len();
        let d0 = values("depth_start", depth_start, n)?;
        let r0 = values("rate_start", rate_start, n)?;
        let d1 = values("depth_end", depth_end, n)?;
        let r1 = values("rate_end", rate_end, n)?;
        self.advance_with(py, "advance_penetration", &chosen, |e, k| {
            let a = Penetration {
                depth: d0[k],
                rate: r0[k],
            };
            let b = Penetration {
                depth: d1[k],
                rate: r1[k],
            };
            e.advance_penetration(dt, a, b)
        })
    }

    /// Resets the contacts (all, or those `index` names) to the law at rest.
    #[pyo3(signature = (index=None))]
    fn reset(&mut self, index: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        for i in self.selected(index)? {
            self.elements[i].reset();
        }
        Ok(())
    }

    /// A copy of contact `i` as a `Contact`.
    fn contact(&self, i: i64) -> PyResult<Contact> {
        let n = self.elements.len();
        let at = usize::try_from(i)
            .ok()
            .filter(|&u| u < n)
            .ok_or_else(|| BwcError::new_err(format!("i = {i}: not a contact: 0 <= i < {n}")))?;
        Ok(Contact::of(self.elements[at].clone(), self.mass))
    }

    fn __len__(&self) -> usize {
        self.elements.len()
    }

    /// The forces at the end of the last step (N).
    #[getter]
    fn force<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.column(py, |e| e.force())
    }

    /// The work the bodies did on each contact so far (J).
    #[getter]
    fn absorbed<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.column(py, |e| e.absorbed())
    }

    /// The energy dissipated in each contact so far (J).
    #[getter]
    fn dissipated<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.column(py, |e| e.dissipated())
    }

    /// Whether each contact is under way.
    #[getter]
    fn in_contact<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<bool>> {
        self.column(py, |e| e.in_contact())
    }

    /// Contacts that have ended, per element.
    #[getter]
    fn contacts<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        self.column(py, |e| e.contacts())
    }

    /// The onset depths (m).
    #[getter]
    fn onset_depth<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.column(py, |e| e.onset_depth())
    }

    /// The laws' states (m), one row per contact, named as `Contact.state`.
    #[getter]
    fn state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let width = self.elements[0].state().len();
        let flat: Vec<f64> = self
            .elements
            .iter()
            .flat_map(|e| e.state().to_vec())
            .collect();
        Array2::from_shape_vec((self.elements.len(), width), flat)
            .expect("one row per contact")
            .into_pyarray(py)
    }

    /// "shccm" or "mcm".
    #[getter]
    fn model(&self) -> &'static str {
        self.elements[0].spec().name
    }

    /// "reset" or "carry".
    #[getter]
    fn policy(&self) -> &'static str {
        policy_name(&self.elements[0])
    }

    /// The mass (kg) base parameters were taken with; None for SI parameters.
    #[getter]
    fn mass(&self) -> Option<f64> {
        self.mass
    }

    fn __repr__(&self) -> String {
        let active = self.elements.iter().filter(|e| e.in_contact()).count();
        format!(
            "Contacts(model='{}', policy='{}', count={}, in_contact={active})",
            self.model(),
            self.policy(),
            self.elements.len()
        )
    }
}
