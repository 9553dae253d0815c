//! Status codes, the last error's message, and the guard every exported function runs in.

use std::cell::RefCell;
use std::ffi::{c_char, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

/// What a call did. Every function but the getters of constants returns one; after any
/// status but `BWC_STATUS_OK`, [`bwc_last_error`] says why and what would help.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BwcStatus {
    /// Done.
    Ok = 0,
    /// A pointer argument was NULL where a value is required.
    NullPointer = 1,
    /// An argument or parameter is outside its admissible set; nothing changed.
    InvalidArgument = 2,
    /// A handle is not live (freed, or never returned by a `_new` function), or of the wrong
    /// kind (a law's where a contact's is expected, or the reverse).
    InvalidHandle = 3,
    /// The computation failed (its integration did not converge); nothing changed.
    Failed = 4,
    /// A bug in bwc: it was caught at the boundary. Please report it with the message.
    Internal = 5,
}

/// Why a call failed: its status and the message for [`bwc_last_error`].
#[derive(Debug)]
pub(crate) struct Failure {
    pub(crate) status: BwcStatus,
    pub(crate) message: String,
}

impl Failure {
    pub(crate) fn new(status: BwcStatus, message: impl Into<String>) -> Self {
        Self {
            status,
            message: message.into(),
        }
    }
}

impl From<bw_models::ModelError> for Failure {
    fn from(e: bw_models::ModelError) -> Self {
        use bw_models::ModelError as M;
        let status = match e {
            M::Solver(_) | M::NotApplicable { .. } => BwcStatus::Failed,
            _ => BwcStatus::InvalidArgument,
        };
        // What a host can change, by the integration's failure.
        let hint = match bw_models::Remedy::of(&e) {
            Some(bw_models::Remedy::CheckVelocities) => {
                "; the state overflowed: check the velocities (`u_start`, `u_end`, or the \
                 penetration rates, m/s) and the law's parameters"
            }
            Some(bw_models::Remedy::ShorterStep) => {
                "; take a shorter host step `dt`, or loosen `rtol` in the element's settings"
            }
            Some(bw_models::Remedy::LooserTolerances) => {
                "; take a shorter host step `dt`, loosen `rtol` and `atol` in the element's \
                 settings, or check the velocities and the law's parameters (a very stiff or \
                 large-exponent law)"
            }
            _ => "",
        };
        Self::new(status, format!("{e}{hint}"))
    }
}

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

/// Runs `body` as the exported `function`: a failure or a panic becomes a status and the
/// thread's last error message; nothing unwinds into the caller.
pub(crate) fn guard(function: &str, body: impl FnOnce() -> Result<(), Failure>) -> BwcStatus {
    let failure = match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => return BwcStatus::Ok,
        Ok(Err(failure)) => failure,
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            Failure::new(
                BwcStatus::Internal,
                format!("internal error (a bug): {what}"),
            )
        }
    };
    let text = format!("{function}: {}", failure.message).replace('\0', " ");
    LAST_ERROR.with(|last| *last.borrow_mut() = CString::new(text).unwrap_or_default());
    failure.status
}

/// The message of the last failed call on this thread (UTF-8, NUL-terminated): the function,
/// the argument or parameter, its value and what is admissible. Empty before any failure.
/// The pointer stays valid until the next failing call on the same thread; copy the text to
/// keep it.
#[no_mangle]
pub extern "C" fn bwc_last_error() -> *const c_char {
    LAST_ERROR.with(|last| last.borrow().as_ptr())
}

/// The pointer as a reference, or the failure naming the NULL argument.
///
/// # Safety
/// A non-NULL `ptr` points to a valid, aligned `T`.
pub(crate) unsafe fn arg<'a, T>(ptr: *const T, name: &str) -> Result<&'a T, Failure> {
    // SAFETY: the caller's contract.
    unsafe { ptr.as_ref() }.ok_or_else(|| null(name))
}

/// The pointer as a mutable reference, or the failure naming the NULL argument.
///
/// # Safety
/// A non-NULL `ptr` points to a valid, aligned, writable `T`.
pub(crate) unsafe fn out<'a, T>(ptr: *mut T, name: &str) -> Result<&'a mut T, Failure> {
    // SAFETY: the caller's contract.
    unsafe { ptr.as_mut() }.ok_or_else(|| null(name))
}

fn null(name: &str) -> Failure {
    Failure::new(
        BwcStatus::NullPointer,
        format!("argument `{name}` is NULL: pass a pointer to a value"),
    )
}

/// The failure of an argument outside its admissible set.
pub(crate) fn invalid(name: &str, value: f64, allowed: &str) -> Failure {
    Failure::new(
        BwcStatus::InvalidArgument,
        format!("argument `{name}` = {value} is not admissible: {allowed}"),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::ffi::CStr;

    /// A panic inside becomes `BWC_STATUS_INTERNAL` with its message; nothing unwinds.
    #[test]
    fn a_panic_stops_at_the_boundary() {
        let status = guard("bwc_test", || panic!("the sky fell"));
        assert_eq!(status, BwcStatus::Internal);
        // SAFETY: the last error is a NUL-terminated string.
        let m = unsafe { CStr::from_ptr(bwc_last_error()) }
            .to_str()
            .unwrap();
        assert_eq!(m, "bwc_test: internal error (a bug): the sky fell");
        assert_eq!(guard("bwc_test", || Ok(())), BwcStatus::Ok);
    }
}
