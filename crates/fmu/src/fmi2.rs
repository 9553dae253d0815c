//! The FMI 2.0 Co-Simulation functions, exported by their standard names. Each checks its
//! pointers, runs the instance's method, catches any panic, and reports a failure through the
//! importer's logger with status fmi2Error.

use crate::instance::{Dynamic, Instance};
use crate::GUID;
use std::ffi::{c_char, c_int, c_uint, c_void, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

type Status = c_int;
const OK: Status = 0;
const DISCARD: Status = 2;
const ERROR: Status = 3;

/// fmi2CallbackLogger: `(environment, instanceName, status, category, message, ...)`, the
/// message a printf format.
type Logger =
    unsafe extern "C" fn(*mut c_void, *const c_char, Status, *const c_char, *const c_char, ...);

/// fmi2CallbackFunctions.
#[repr(C)]
pub struct CallbackFunctions {
    logger: Option<Logger>,
    allocate_memory: Option<unsafe extern "C" fn(usize, usize) -> *mut c_void>,
    free_memory: Option<unsafe extern "C" fn(*mut c_void)>,
    step_finished: Option<unsafe extern "C" fn(*mut c_void, Status)>,
    component_environment: *mut c_void,
}

/// What an fmi2Component points to.
struct Component {
    instance: Instance,
    name: CString,
    logger: Option<Logger>,
    environment: *mut c_void,
}

impl Component {
    /// Sends `message` to the importer's logger (a format without arguments: `%` doubled).
    fn log(&self, status: Status, message: &str) {
        log(self.logger, self.environment, &self.name, status, message);
    }
}

fn log(logger: Option<Logger>, env: *mut c_void, name: &CStr, status: Status, message: &str) {
    let Some(logger) = logger else { return };
    let text = CString::new(message.replace('%', "%%").replace('\0', " ")).unwrap_or_default();
    let category = if status == OK {
        c"logAll"
    } else {
        c"logStatusError"
    };
    // SAFETY: the importer's logger, called as fmi2CallbackLogger with a format that
    // takes no arguments.
    unsafe { logger(env, name.as_ptr(), status, category.as_ptr(), text.as_ptr()) };
}

/// Runs `body` on the component `c` as `function`: NULL, errors and panics become fmi2Error
/// (logged where the component has a logger).
fn call(
    c: *mut c_void,
    function: &str,
    body: impl FnOnce(&mut Component) -> Result<Status, String>,
) -> Status {
    // SAFETY: a non-NULL component came from fmi2Instantiate (the importer's contract).
    let Some(component) = (unsafe { c.cast::<Component>().as_mut() }) else {
        return ERROR;
    };
    let result = catch_unwind(AssertUnwindSafe(|| body(component)))
        .unwrap_or_else(|_| Err("internal error (a bug in bwc); please report it".into()));
    match result {
        Ok(status) => status,
        Err(message) => {
            component.log(ERROR, &format!("{function}: {message}"));
            ERROR
        }
    }
}

/// `n` values at `ptr`, or the error naming the NULL argument.
///
/// # Safety
/// A non-NULL `ptr` points to `n` values.
unsafe fn slice<'a, T>(ptr: *const T, n: usize, name: &str) -> Result<&'a [T], String> {
    if n == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(format!("argument `{name}` is NULL for {n} values"));
    }
    // SAFETY: the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(ptr, n) })
}

/// # Safety
/// A non-NULL `ptr` points to `n` writable values.
unsafe fn slice_mut<'a, T>(ptr: *mut T, n: usize, name: &str) -> Result<&'a mut [T], String> {
    if n == 0 {
        return Ok(&mut []);
    }
    if ptr.is_null() {
        return Err(format!("argument `{name}` is NULL for {n} values"));
    }
    // SAFETY: the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, n) })
}

/// "default": the standard's types.
#[no_mangle]
pub extern "C" fn fmi2GetTypesPlatform() -> *const c_char {
    c"default".as_ptr()
}

/// "2.0".
#[no_mangle]
pub extern "C" fn fmi2GetVersion() -> *const c_char {
    c"2.0".as_ptr()
}

/// Logging is always on for errors; nothing else is logged.
#[no_mangle]
pub extern "C" fn fmi2SetDebugLogging(
    c: *mut c_void,
    _logging_on: c_int,
    _n_categories: usize,
    _categories: *const *const c_char,
) -> Status {
    call(c, "fmi2SetDebugLogging", |_| Ok(OK))
}

/// A new instance (Co-Simulation only), or NULL with the reason logged.
///
/// # Safety
/// The arguments as FMI 2.0 defines them.
#[no_mangle]
pub unsafe extern "C" fn fmi2Instantiate(
    instance_name: *const c_char,
    fmu_type: c_int,
    guid: *const c_char,
    _resource_location: *const c_char,
    functions: *const CallbackFunctions,
    _visible: c_int,
    _logging_on: c_int,
) -> *mut c_void {
    catch_unwind(|| {
        // SAFETY: the importer's contract: NULL or valid.
        let functions = unsafe { functions.as_ref() };
        let name = if instance_name.is_null() {
            c"bwc_contact".to_owned()
        } else {
            // SAFETY: a NUL-terminated string (the importer's contract).
            unsafe { CStr::from_ptr(instance_name) }.to_owned()
        };
        let (logger, env) = functions.map_or((None, std::ptr::null_mut()), |f| {
            (f.logger, f.component_environment)
        });
        let fail = |message: &str| {
            log(
                logger,
                env,
                &name,
                ERROR,
                &format!("fmi2Instantiate: {message}"),
            );
            std::ptr::null_mut()
        };
        if functions.is_none() {
            return fail("argument `functions` is NULL");
        }
        if fmu_type != 1 {
            return fail(&format!(
                "fmuType = {fmu_type}: this FMU is for Co-Simulation (fmi2CoSimulation = 1) only"
            ));
        }
        // SAFETY: NULL or a NUL-terminated string (the importer's contract).
        let given = (!guid.is_null()).then(|| unsafe { CStr::from_ptr(guid) });
        if given.and_then(|g| g.to_str().ok()) != Some(GUID) {
            return fail(&format!(
                "fmuGUID {given:?} is not this FMU's {GUID}: the modelDescription.xml and the \
                 binary come from different builds"
            ));
        }
        let component = Component {
            instance: Instance::new(),
            name,
            logger,
            environment: env,
        };
        Box::into_raw(Box::new(component)).cast::<c_void>()
    })
    .unwrap_or(std::ptr::null_mut())
}

/// Frees an instance (NULL does nothing).
///
/// # Safety
/// `c` came from fmi2Instantiate and is not used again.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeInstance(c: *mut c_void) {
    if !c.is_null() {
        // SAFETY: the importer's contract.
        drop(unsafe { Box::from_raw(c.cast::<Component>()) });
    }
}

/// The start time; the tolerance is the `rtol` parameter's, the stop time is not needed.
#[no_mangle]
pub extern "C" fn fmi2SetupExperiment(
    c: *mut c_void,
    _tolerance_defined: c_int,
    _tolerance: f64,
    start_time: f64,
    _stop_time_defined: c_int,
    _stop_time: f64,
) -> Status {
    call(c, "fmi2SetupExperiment", |s| {
        s.instance.setup(start_time).map(|()| OK)
    })
}

/// Enters initialization mode.
#[no_mangle]
pub extern "C" fn fmi2EnterInitializationMode(c: *mut c_void) -> Status {
    call(c, "fmi2EnterInitializationMode", |s| {
        s.instance.enter_initialization().map(|()| OK)
    })
}

/// Builds the law from the parameters (an inadmissible one is named) and starts stepping.
#[no_mangle]
pub extern "C" fn fmi2ExitInitializationMode(c: *mut c_void) -> Status {
    call(c, "fmi2ExitInitializationMode", |s| {
        s.instance.exit_initialization().map(|()| OK)
    })
}

/// Ends the simulation.
#[no_mangle]
pub extern "C" fn fmi2Terminate(c: *mut c_void) -> Status {
    call(c, "fmi2Terminate", |s| s.instance.terminate().map(|()| OK))
}

/// Back to the state after fmi2Instantiate.
#[no_mangle]
pub extern "C" fn fmi2Reset(c: *mut c_void) -> Status {
    call(c, "fmi2Reset", |s| {
        s.instance.reset();
        Ok(OK)
    })
}

/// Reads Real variables.
///
/// # Safety
/// `vr` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetReal(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut f64,
) -> Status {
    call(c, "fmi2GetReal", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            *v = s.instance.get_real(*r)?;
        }
        Ok(OK)
    })
}

/// Reads Integer variables.
///
/// # Safety
/// `vr` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetInteger(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut c_int,
) -> Status {
    call(c, "fmi2GetInteger", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            *v = s.instance.get_integer(*r)?;
        }
        Ok(OK)
    })
}

/// Reads Boolean variables.
///
/// # Safety
/// `vr` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBoolean(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *mut c_int,
) -> Status {
    call(c, "fmi2GetBoolean", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice_mut(value, nvr, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            *v = c_int::from(s.instance.get_boolean(*r)?);
        }
        Ok(OK)
    })
}

/// The FMU has no String variables.
#[no_mangle]
pub extern "C" fn fmi2GetString(
    c: *mut c_void,
    _vr: *const c_uint,
    nvr: usize,
    _value: *mut *const c_char,
) -> Status {
    call(c, "fmi2GetString", |_| no_strings(nvr))
}

fn no_strings(n: usize) -> Result<Status, String> {
    if n == 0 {
        Ok(OK)
    } else {
        Err("the FMU has no String variables".into())
    }
}

/// Sets Real parameters (before initialization) and inputs.
///
/// # Safety
/// `vr` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetReal(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *const f64,
) -> Status {
    call(c, "fmi2SetReal", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice(value, nvr, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            s.instance.set_real(*r, *v)?;
        }
        Ok(OK)
    })
}

/// Sets Integer parameters (before initialization).
///
/// # Safety
/// `vr` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetInteger(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    value: *const c_int,
) -> Status {
    call(c, "fmi2SetInteger", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, value) = unsafe { (slice(vr, nvr, "vr")?, slice(value, nvr, "value")?) };
        for (r, v) in vr.iter().zip(value) {
            s.instance.set_integer(*r, *v)?;
        }
        Ok(OK)
    })
}

/// The FMU has no settable Boolean variables.
#[no_mangle]
pub extern "C" fn fmi2SetBoolean(
    c: *mut c_void,
    _vr: *const c_uint,
    nvr: usize,
    _value: *const c_int,
) -> Status {
    call(c, "fmi2SetBoolean", |_| {
        if nvr == 0 {
            Ok(OK)
        } else {
            Err("the FMU's only Boolean, `in_contact`, is an output".into())
        }
    })
}

/// The FMU has no String variables.
#[no_mangle]
pub extern "C" fn fmi2SetString(
    c: *mut c_void,
    _vr: *const c_uint,
    nvr: usize,
    _value: *const *const c_char,
) -> Status {
    call(c, "fmi2SetString", |_| no_strings(nvr))
}

/// Saves the state (element, inputs, time) for a later fmi2SetFMUstate: a master that tries
/// a step and takes it again.
///
/// # Safety
/// `state` points to a writable fmi2FMUstate (NULL, or one this function gave).
#[no_mangle]
pub unsafe extern "C" fn fmi2GetFMUstate(c: *mut c_void, state: *mut *mut c_void) -> Status {
    call(c, "fmi2GetFMUstate", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let slot = unsafe { state.as_mut() }.ok_or("argument `FMUstate` is NULL")?;
        let snapshot = s.instance.snapshot();
        // SAFETY: a non-NULL state came from this function.
        match unsafe { slot.cast::<Dynamic>().as_mut() } {
            Some(existing) => *existing = snapshot,
            None => *slot = Box::into_raw(Box::new(snapshot)).cast(),
        }
        Ok(OK)
    })
}

/// Restores a state saved by fmi2GetFMUstate.
///
/// # Safety
/// `state` came from fmi2GetFMUstate and was not freed.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetFMUstate(c: *mut c_void, state: *mut c_void) -> Status {
    call(c, "fmi2SetFMUstate", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let saved =
            unsafe { state.cast::<Dynamic>().as_ref() }.ok_or("argument `FMUstate` is NULL")?;
        s.instance.restore(saved);
        Ok(OK)
    })
}

/// Frees a saved state and sets it to NULL.
///
/// # Safety
/// `state` points to NULL or to a state from fmi2GetFMUstate.
#[no_mangle]
pub unsafe extern "C" fn fmi2FreeFMUstate(c: *mut c_void, state: *mut *mut c_void) -> Status {
    call(c, "fmi2FreeFMUstate", |_| {
        // SAFETY: the importer's contract; NULL is checked.
        if let Some(slot) = unsafe { state.as_mut() } {
            if !slot.is_null() {
                // SAFETY: the state came from fmi2GetFMUstate.
                drop(unsafe { Box::from_raw(slot.cast::<Dynamic>()) });
                *slot = std::ptr::null_mut();
            }
        }
        Ok(OK)
    })
}

/// Not supported (canSerializeFMUstate = false).
#[no_mangle]
pub extern "C" fn fmi2SerializedFMUstateSize(
    c: *mut c_void,
    _state: *mut c_void,
    _size: *mut usize,
) -> Status {
    call(
        c,
        "fmi2SerializedFMUstateSize",
        |_| Err(NO_SERIALIZE.into()),
    )
}

/// Not supported (canSerializeFMUstate = false).
#[no_mangle]
pub extern "C" fn fmi2SerializeFMUstate(
    c: *mut c_void,
    _state: *mut c_void,
    _bytes: *mut c_char,
    _size: usize,
) -> Status {
    call(c, "fmi2SerializeFMUstate", |_| Err(NO_SERIALIZE.into()))
}

/// Not supported (canSerializeFMUstate = false).
#[no_mangle]
pub extern "C" fn fmi2DeSerializeFMUstate(
    c: *mut c_void,
    _bytes: *const c_char,
    _size: usize,
    _state: *mut *mut c_void,
) -> Status {
    call(c, "fmi2DeSerializeFMUstate", |_| Err(NO_SERIALIZE.into()))
}

const NO_SERIALIZE: &str = "states are not serialized (canSerializeFMUstate = false): use \
                            fmi2GetFMUstate and fmi2SetFMUstate";

/// Not supported (providesDirectionalDerivative = false).
#[no_mangle]
pub extern "C" fn fmi2GetDirectionalDerivative(
    c: *mut c_void,
    _unknown: *const c_uint,
    _n_unknown: usize,
    _known: *const c_uint,
    _n_known: usize,
    _dv_known: *const f64,
    _dv_unknown: *mut f64,
) -> Status {
    call(c, "fmi2GetDirectionalDerivative", |_| {
        Err("no directional derivatives (providesDirectionalDerivative = false)".into())
    })
}

/// The inputs' derivatives over the next step: order 1 of `delta_dot` is the relative
/// acceleration (m/s²), making the penetration quadratic over the step.
///
/// # Safety
/// `vr`, `order` and `value` point to `nvr` values.
#[no_mangle]
pub unsafe extern "C" fn fmi2SetRealInputDerivatives(
    c: *mut c_void,
    vr: *const c_uint,
    nvr: usize,
    order: *const c_int,
    value: *const f64,
) -> Status {
    call(c, "fmi2SetRealInputDerivatives", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let (vr, order, value) = unsafe {
            (
                slice(vr, nvr, "vr")?,
                slice(order, nvr, "order")?,
                slice(value, nvr, "value")?,
            )
        };
        for ((r, o), v) in vr.iter().zip(order).zip(value) {
            s.instance.set_input_derivative(*r, *o, *v)?;
        }
        Ok(OK)
    })
}

/// Not supported (maxOutputDerivativeOrder = 0).
#[no_mangle]
pub extern "C" fn fmi2GetRealOutputDerivatives(
    c: *mut c_void,
    _vr: *const c_uint,
    _nvr: usize,
    _order: *const c_int,
    _value: *mut f64,
) -> Status {
    call(c, "fmi2GetRealOutputDerivatives", |_| {
        Err("no output derivatives (maxOutputDerivativeOrder = 0)".into())
    })
}

/// Advances the contact from `t` over `h` (s).
#[no_mangle]
pub extern "C" fn fmi2DoStep(c: *mut c_void, t: f64, h: f64, _no_set_prior: c_int) -> Status {
    call(c, "fmi2DoStep", |s| s.instance.do_step(t, h).map(|()| OK))
}

/// Steps are never asynchronous: nothing to cancel.
#[no_mangle]
pub extern "C" fn fmi2CancelStep(c: *mut c_void) -> Status {
    call(c, "fmi2CancelStep", |_| {
        Err("steps are never pending: nothing to cancel".into())
    })
}

/// Steps are never asynchronous: no status to give.
#[no_mangle]
pub extern "C" fn fmi2GetStatus(c: *mut c_void, _kind: c_int, _value: *mut Status) -> Status {
    call(c, "fmi2GetStatus", |_| Ok(DISCARD))
}

/// fmi2LastSuccessfulTime: the time of the last step's end.
///
/// # Safety
/// `value` points to a writable double.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetRealStatus(c: *mut c_void, kind: c_int, value: *mut f64) -> Status {
    call(c, "fmi2GetRealStatus", |s| {
        // SAFETY: the importer's contract; NULL is checked.
        let value = unsafe { value.as_mut() }.ok_or("argument `value` is NULL")?;
        if kind != 2 {
            return Ok(DISCARD);
        }
        *value = s.instance.time();
        Ok(OK)
    })
}

/// No Integer status.
#[no_mangle]
pub extern "C" fn fmi2GetIntegerStatus(c: *mut c_void, _kind: c_int, _value: *mut c_int) -> Status {
    call(c, "fmi2GetIntegerStatus", |_| Ok(DISCARD))
}

/// fmi2Terminated: never asked to stop early.
///
/// # Safety
/// `value` points to a writable fmi2Boolean.
#[no_mangle]
pub unsafe extern "C" fn fmi2GetBooleanStatus(
    c: *mut c_void,
    kind: c_int,
    value: *mut c_int,
) -> Status {
    call(c, "fmi2GetBooleanStatus", |_| {
        // SAFETY: the importer's contract; NULL is checked.
        let value = unsafe { value.as_mut() }.ok_or("argument `value` is NULL")?;
        if kind != 3 {
            return Ok(DISCARD);
        }
        *value = 0;
        Ok(OK)
    })
}

/// No String status.
#[no_mangle]
pub extern "C" fn fmi2GetStringStatus(
    c: *mut c_void,
    _kind: c_int,
    _value: *mut *const c_char,
) -> Status {
    call(c, "fmi2GetStringStatus", |_| Ok(DISCARD))
}
