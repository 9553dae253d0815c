//! Contact elements behind handles: create, advance, read, reset, free.

use crate::law::law;
use crate::registry::{dead, Kind, Registry};
use crate::status::{guard, invalid, out, BwcStatus, Failure};
use bw_models::sequence::Policy;
use bw_models::{AnyContactElement, ElementSettings, ElementStep, Penetration};
use std::ffi::{c_char, CStr};
use std::sync::{Mutex, RwLock};

/// A contact element's handle: 0 is never one, and no law handle has the same value.
pub type BwcContact = u64;

/// `policy`: each new contact starts from the law at rest.
pub const BWC_POLICY_RESET: u32 = 0;
/// `policy`: each new contact starts from the state of the last separation.
pub const BWC_POLICY_CARRY: u32 = 1;

/// How an element integrates; [`bwc_element_settings_default`] gives the defaults.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcElementSettings {
    /// Relative tolerance of the element's internal steps, in [1e-14, 1e-2].
    pub rtol: f64,
    /// Absolute tolerance of the law's displacements (m), > 0.
    pub atol: f64,
    /// `BWC_POLICY_RESET` or `BWC_POLICY_CARRY`.
    pub policy: u32,
}

/// What one host step gave.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcStep {
    /// The force at the step's end (N, positive pushing the bodies apart; 0 once separated).
    pub force: f64,
    /// `∫ F dt` over the step (N s).
    pub impulse: f64,
    /// `∫ -F u dt` over the step (J): the work the bodies did on the contact.
    pub work: f64,
    /// Where the contact ended in the step (s from its start); NaN if it did not.
    pub separated_at: f64,
    /// Where a contact began in the step (s from its start; penetration input only); NaN if
    /// none did.
    pub began_at: f64,
}

/// An element's scalars: what [`bwc_contact_info`] gives.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BwcContactInfo {
    /// The force at the end of the last step (N).
    pub force: f64,
    /// The work the bodies did on the contact so far (J).
    pub absorbed: f64,
    /// The energy dissipated so far (J): absorbed less what the law's springs hold.
    pub dissipated: f64,
    /// The penetration (m) at which the next contact begins (penetration input).
    pub onset_depth: f64,
    /// Contacts that have ended.
    pub contacts: u64,
    /// 1 while a contact is under way, else 0.
    pub in_contact: i32,
}

static CONTACTS: RwLock<Registry<Mutex<AnyContactElement>>> =
    RwLock::new(Registry::new(Kind::Contact));

/// Runs `f` on the element of a live handle, holding only that element's lock.
fn with<T>(handle: BwcContact, f: impl FnOnce(&mut AnyContactElement) -> T) -> Result<T, Failure> {
    let contacts = CONTACTS.read().unwrap_or_else(|e| e.into_inner());
    let cell = contacts
        .get(handle)
        .ok_or_else(|| dead("contact", handle, Kind::Contact))?;
    let mut element = cell.lock().unwrap_or_else(|e| e.into_inner());
    Ok(f(&mut element))
}

/// Keeps `element` behind a new handle.
fn keep(element: AnyContactElement) -> Result<BwcContact, Failure> {
    let mut contacts = CONTACTS.write().unwrap_or_else(|e| e.into_inner());
    contacts
        .insert(Mutex::new(element))
        .ok_or_else(|| Failure::new(BwcStatus::Failed, "no handles left: free some contacts"))
}

/// The default settings: `rtol` 1e-10, `atol` 1e-16 m, `BWC_POLICY_RESET`.
#[no_mangle]
pub extern "C" fn bwc_element_settings_default() -> BwcElementSettings {
    let d = ElementSettings::default();
    BwcElementSettings {
        rtol: d.rtol,
        atol: d.atol,
        policy: BWC_POLICY_RESET,
    }
}

fn settings(s: &BwcElementSettings) -> Result<ElementSettings, Failure> {
    let mut out = ElementSettings::default();
    out.rtol = s.rtol;
    out.atol = s.atol;
    out.policy = match s.policy {
        BWC_POLICY_RESET => Policy::Reset,
        BWC_POLICY_CARRY => Policy::Carry,
        p => {
            return Err(invalid(
                "settings.policy",
                f64::from(p),
                "BWC_POLICY_RESET (0) or BWC_POLICY_CARRY (1)",
            ))
        }
    };
    Ok(out)
}

/// Creates a contact element of `law`, out of contact and at rest. `settings` may be NULL
/// for the defaults.
///
/// # Safety
/// `settings` points to a `BwcElementSettings` or is NULL; `out` points to a writable
/// `BwcContact` (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_new(
    law: crate::BwcLaw,
    settings: *const BwcElementSettings,
    out: *mut BwcContact,
) -> BwcStatus {
    guard("bwc_contact_new", || {
        // SAFETY: the caller's contract; NULL is checked (and allowed for `settings`).
        let (given, out) = unsafe { (settings.as_ref(), self::out(out, "out")?) };
        let settings = match given {
            Some(s) => self::settings(s)?,
            None => ElementSettings::default(),
        };
        let params = self::law(law)?;
        let element = AnyContactElement::new(&params, settings)?;
        *out = keep(element)?;
        Ok(())
    })
}

/// Creates a contact element of the law named `law` (NUL-terminated UTF-8: `"shccm"`,
/// `"mcm"` or another of the element laws, `"thornton"` for one; the guide's reference of
/// contact laws lists them with their parameters and units), whose `count` parameters are named
/// `names[i]` with the SI values `values[i]`, out of contact and at rest. `settings` may be
/// NULL for the defaults. An unknown law or parameter name, a missing parameter or an
/// inadmissible value is `BWC_STATUS_INVALID_ARGUMENT`, and the last error names it and lists
/// what is admissible.
///
/// # Safety
/// `law` is a NUL-terminated string; `names` and `values` point to `count` elements each
/// (they may be NULL when `count` is 0), each name NUL-terminated; `settings` points to a
/// `BwcElementSettings` or is NULL; `out` points to a writable `BwcContact`.
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_new_named(
    law: *const c_char,
    names: *const *const c_char,
    values: *const f64,
    count: usize,
    settings: *const BwcElementSettings,
    out: *mut BwcContact,
) -> BwcStatus {
    guard("bwc_contact_new_named", || {
        // SAFETY: the caller's contract; NULL is checked (and allowed for `settings`).
        let (given, out) = unsafe { (settings.as_ref(), self::out(out, "out")?) };
        let settings = match given {
            Some(s) => self::settings(s)?,
            None => ElementSettings::default(),
        };
        // SAFETY: the caller's contract.
        let law = unsafe { text(law, "law")? };
        // SAFETY: the caller's contract.
        let params = unsafe { named_values(names, values, count)? };
        let element = AnyContactElement::of_law(law, &params, settings)?;
        *out = keep(element)?;
        Ok(())
    })
}

/// A NUL-terminated UTF-8 argument as text.
///
/// # Safety
/// A non-NULL `ptr` is NUL-terminated.
pub(crate) unsafe fn text<'a>(ptr: *const c_char, name: &str) -> Result<&'a str, Failure> {
    if ptr.is_null() {
        return Err(Failure::new(
            BwcStatus::NullPointer,
            format!("argument `{name}` is NULL: pass a NUL-terminated string"),
        ));
    }
    // SAFETY: the caller's contract.
    unsafe { CStr::from_ptr(ptr) }.to_str().map_err(|_| {
        Failure::new(
            BwcStatus::InvalidArgument,
            format!("argument `{name}` is not UTF-8 text"),
        )
    })
}

/// `count` (name, value) pairs from two C arrays.
///
/// # Safety
/// With `count > 0`, `names` and `values` point to `count` elements each, every name
/// NUL-terminated or NULL.
unsafe fn named_values<'a>(
    names: *const *const c_char,
    values: *const f64,
    count: usize,
) -> Result<Vec<(&'a str, f64)>, Failure> {
    if count == 0 {
        return Ok(Vec::new());
    }
    if names.is_null() || values.is_null() {
        let which = if names.is_null() { "names" } else { "values" };
        return Err(Failure::new(
            BwcStatus::NullPointer,
            format!("argument `{which}` is NULL with count = {count}: pass {count} elements"),
        ));
    }
    // SAFETY: the caller's contract: `count` elements each.
    let (names, values) = unsafe {
        (
            std::slice::from_raw_parts(names, count),
            std::slice::from_raw_parts(values, count),
        )
    };
    names
        .iter()
        .zip(values)
        .enumerate()
        // SAFETY: the caller's contract.
        .map(|(i, (&n, &v))| Ok((unsafe { text(n, &format!("names[{i}]"))? }, v)))
        .collect()
}

/// Frees a contact element. Freeing 0 does nothing; a freed handle is an error ever after.
#[no_mangle]
pub extern "C" fn bwc_contact_free(contact: BwcContact) -> BwcStatus {
    guard("bwc_contact_free", || {
        if contact == 0 {
            return Ok(());
        }
        let mut contacts = CONTACTS.write().unwrap_or_else(|e| e.into_inner());
        contacts
            .remove(contact)
            .map(drop)
            .ok_or_else(|| dead("contact", contact, Kind::Contact))
    })
}

fn c_step(s: ElementStep) -> BwcStep {
    BwcStep {
        force: s.force,
        impulse: s.impulse,
        work: s.work,
        separated_at: s.separated_at.unwrap_or(f64::NAN),
        began_at: s.began_at.unwrap_or(f64::NAN),
    }
}

/// Advances the element over a host step of `dt` (s) in which the relative velocity goes
/// linearly from `u_start` to `u_end` (m/s, negative while the bodies approach). Call it
/// while the bodies touch: the step starts a contact if none is under way. `out` may be NULL.
/// On failure nothing changed.
///
/// # Safety
/// `out` points to a writable `BwcStep` or is NULL.
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_advance(
    contact: BwcContact,
    dt: f64,
    u_start: f64,
    u_end: f64,
    out: *mut BwcStep,
) -> BwcStatus {
    guard("bwc_contact_advance", || {
        let step = with(contact, |el| el.advance(dt, u_start, u_end))??;
        // SAFETY: the caller's contract; NULL is allowed.
        if let Some(out) = unsafe { out.as_mut() } {
            *out = c_step(step);
        }
        Ok(())
    })
}

/// Advances the element over a host step of `dt` (s) from the penetration `depth_start`
/// (m, positive while the bodies overlap) and its rate `rate_start` (m/s, positive while
/// they approach) to `depth_end`, `rate_end`. The element finds each contact's onset (where
/// the penetration rises through the onset depth) and separation inside the step. `out` may
/// be NULL. On failure nothing changed.
///
/// # Safety
/// `out` points to a writable `BwcStep` or is NULL.
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_advance_penetration(
    contact: BwcContact,
    dt: f64,
    depth_start: f64,
    rate_start: f64,
    depth_end: f64,
    rate_end: f64,
    out: *mut BwcStep,
) -> BwcStatus {
    guard("bwc_contact_advance_penetration", || {
        let start = Penetration {
            depth: depth_start,
            rate: rate_start,
        };
        let end = Penetration {
            depth: depth_end,
            rate: rate_end,
        };
        let step = with(contact, |el| el.advance_penetration(dt, start, end))??;
        // SAFETY: the caller's contract; NULL is allowed.
        if let Some(out) = unsafe { out.as_mut() } {
            *out = c_step(step);
        }
        Ok(())
    })
}

/// The element's force, energies, onset depth and counts.
///
/// # Safety
/// `out` points to a writable `BwcContactInfo` (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_info(
    contact: BwcContact,
    out: *mut BwcContactInfo,
) -> BwcStatus {
    guard("bwc_contact_info", || {
        // SAFETY: the caller's contract; NULL is checked.
        let out = unsafe { self::out(out, "out")? };
        *out = with(contact, |el| BwcContactInfo {
            force: el.force(),
            absorbed: el.absorbed(),
            dissipated: el.dissipated(),
            onset_depth: el.onset_depth(),
            contacts: el.contacts(),
            in_contact: i32::from(el.in_contact()),
        })?;
        Ok(())
    })
}

/// The force at the end of the last step (N).
///
/// # Safety
/// `out` points to a writable double (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_force(contact: BwcContact, out: *mut f64) -> BwcStatus {
    guard("bwc_contact_force", || {
        // SAFETY: the caller's contract; NULL is checked.
        let out = unsafe { self::out(out, "out")? };
        *out = with(contact, |el| el.force())?;
        Ok(())
    })
}

/// The energy dissipated in the contact so far (J).
///
/// # Safety
/// `out` points to a writable double (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_dissipated(contact: BwcContact, out: *mut f64) -> BwcStatus {
    guard("bwc_contact_dissipated", || {
        // SAFETY: the caller's contract; NULL is checked.
        let out = unsafe { self::out(out, "out")? };
        *out = with(contact, |el| el.dissipated())?;
        Ok(())
    })
}

/// The law's state (m): `x, z` (SHCCM), `r, y, z` (MCM), or as the reference of contact laws
/// names it for the others (Thornton's `x, x_m`), written to `out` (room for `capacity` values); `len` receives their
/// number (1 to 3). A `capacity` below it is an
/// error that writes nothing but `len`.
///
/// # Safety
/// `out` points to `capacity` writable doubles; `len` to a writable size_t (neither NULL).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_state(
    contact: BwcContact,
    out: *mut f64,
    capacity: usize,
    len: *mut usize,
) -> BwcStatus {
    guard("bwc_contact_state", || {
        // SAFETY: the caller's contract; NULL is checked.
        let len = unsafe { self::out(len, "len")? };
        if out.is_null() {
            return Err(Failure::new(
                BwcStatus::NullPointer,
                "argument `out` is NULL: pass room for 3 doubles",
            ));
        }
        let (values, n) = with(contact, |el| {
            let mut v = [0.0; 3];
            let s = el.state();
            v[..s.len()].copy_from_slice(s);
            (v, s.len())
        })?;
        *len = n;
        if capacity < n {
            return Err(invalid(
                "capacity",
                capacity as f64,
                "room for the law's states: 1 to 3 (3 always suffices)",
            ));
        }
        // SAFETY: `out` has room for `capacity >= n` doubles (the caller's contract).
        unsafe { std::slice::from_raw_parts_mut(out, n) }.copy_from_slice(&values[..n]);
        Ok(())
    })
}

/// Back to the law at rest, out of contact, with nothing absorbed and the onset depth 0.
#[no_mangle]
pub extern "C" fn bwc_contact_reset(contact: BwcContact) -> BwcStatus {
    guard("bwc_contact_reset", || with(contact, |el| el.reset()))
}

/// Creates a new element with the state of `from` (law, settings, state, energies, counts):
/// for hosts that try a step before taking it.
///
/// # Safety
/// `out` points to a writable `BwcContact` (NULL is an error).
#[no_mangle]
pub unsafe extern "C" fn bwc_contact_clone(from: BwcContact, out: *mut BwcContact) -> BwcStatus {
    guard("bwc_contact_clone", || {
        // SAFETY: the caller's contract; NULL is checked.
        let out = unsafe { self::out(out, "out")? };
        let element = with(from, |e| e.clone()).map_err(|_| dead("from", from, Kind::Contact))?;
        *out = keep(element)?;
        Ok(())
    })
}

/// Makes `to` a copy of `from` (law, settings, state, energies, counts), both live: a host
/// that tries a step on a scratch element copies the real one into it first.
#[no_mangle]
pub extern "C" fn bwc_contact_copy(from: BwcContact, to: BwcContact) -> BwcStatus {
    guard("bwc_contact_copy", || {
        let element = with(from, |e| e.clone()).map_err(|_| dead("from", from, Kind::Contact))?;
        with(to, |e| *e = element).map_err(|_| dead("to", to, Kind::Contact))
    })
}
