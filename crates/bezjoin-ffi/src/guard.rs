//! The boundary: status codes, the per-thread last error, the panic guard
//! and the pointer helpers every entry point uses.

use std::cell::RefCell;
use std::ffi::{CString, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

use bezjoin_core::{BezierCurve, BezjoinError};

/// Status returned by every fallible function. Values are fixed by the contract.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(non_camel_case_types)]
pub enum BzjStatus {
    /// Success.
    BZJ_OK = 0,
    /// A required pointer was null.
    BZJ_ERR_NULL_POINTER = 1,
    /// A value out of its domain (degree, order, dim, parameter range, setback...).
    BZJ_ERR_INVALID_ARGUMENT = 2,
    /// NaN or infinity in the input.
    BZJ_ERR_NON_FINITE = 3,
    /// Curves or data of different dimensions.
    BZJ_ERR_DIMENSION_MISMATCH = 4,
    /// Caller's buffer shorter than needed.
    BZJ_ERR_BUFFER_TOO_SMALL = 5,
    /// Constraints contradict each other or are too many (no solution).
    BZJ_ERR_INCONSISTENT = 6,
    /// The linear system is singular.
    BZJ_ERR_SINGULAR = 7,
    /// The answer cannot be trusted to the promised accuracy.
    BZJ_ERR_ILL_CONDITIONED = 8,
    /// Curves to be filleted do not cross (or only touch).
    BZJ_ERR_NO_INTERSECTION = 9,
    /// A bug: an internal panic caught at the boundary.
    BZJ_ERR_INTERNAL = 99,
}

/// Opaque, immutable Bezier curve handle (degree `n >= 0`, dimension `dim >= 1`).
pub struct BzjCurve {
    pub(crate) curve: BezierCurve,
}

/// An error at the boundary: one of the core library's, or one that only
/// the C side can make.
#[derive(Debug)]
pub(crate) enum FfiError {
    Core(BezjoinError),
    NullPointer(String),
    BufferTooSmall {
        name: String,
        needed: usize,
        given: usize,
    },
    /// A caller's array of handle slots shorter than needed.
    HandleArrayTooSmall {
        name: String,
        needed: usize,
        given: usize,
    },
}

impl From<BezjoinError> for FfiError {
    fn from(e: BezjoinError) -> Self {
        FfiError::Core(e)
    }
}

impl FfiError {
    pub(crate) fn status(&self) -> BzjStatus {
        use BzjStatus::*;
        match self {
            FfiError::NullPointer(_) => BZJ_ERR_NULL_POINTER,
            FfiError::BufferTooSmall { .. } | FfiError::HandleArrayTooSmall { .. } => {
                BZJ_ERR_BUFFER_TOO_SMALL
            }
            FfiError::Core(e) => match e {
                BezjoinError::ParameterOutOfRange { .. }
                | BezjoinError::OrderAboveDegree { .. }
                | BezjoinError::LengthMismatch { .. }
                | BezjoinError::InvalidArgument { .. } => BZJ_ERR_INVALID_ARGUMENT,
                BezjoinError::NonFinite { .. } | BezjoinError::NonFiniteScalar { .. } => {
                    BZJ_ERR_NON_FINITE
                }
                BezjoinError::DimensionMismatch { .. } => BZJ_ERR_DIMENSION_MISMATCH,
                BezjoinError::Inconsistent { .. } => BZJ_ERR_INCONSISTENT,
                BezjoinError::Singular { .. } => BZJ_ERR_SINGULAR,
                BezjoinError::IllConditioned { .. } => BZJ_ERR_ILL_CONDITIONED,
                BezjoinError::NoIntersection { .. } => BZJ_ERR_NO_INTERSECTION,
            },
        }
    }

    pub(crate) fn message(&self) -> String {
        match self {
            FfiError::Core(e) => e.to_string(),
            FfiError::NullPointer(name) => format!("{name} is a null pointer"),
            FfiError::BufferTooSmall {
                name,
                needed,
                given,
            } => {
                format!("{name} holds {given} doubles, {needed} are needed")
            }
            FfiError::HandleArrayTooSmall {
                name,
                needed,
                given,
            } => {
                format!("{name} has room for {given} handles, {needed} are needed")
            }
        }
    }
}

pub(crate) type FfiResult<T = ()> = Result<T, FfiError>;

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_last_error(message: &str) {
    LAST_ERROR.with(|e| {
        // A success after a success: nothing to store (no allocation on the
        // hot path of evaluation calls).
        if message.is_empty() && e.borrow().as_bytes().is_empty() {
            return;
        }
        *e.borrow_mut() = CString::new(message.replace('\0', " ")).unwrap_or_default();
    });
}

/// Run one entry point's body: a panic becomes `BZJ_ERR_INTERNAL`, an error
/// its status with the message stored for [`bzj_last_error`].
pub(crate) fn guard(body: impl FnOnce() -> FfiResult) -> BzjStatus {
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(Ok(())) => {
            set_last_error("");
            BzjStatus::BZJ_OK
        }
        Ok(Err(e)) => {
            set_last_error(&e.message());
            e.status()
        }
        Err(panic) => {
            let what = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            set_last_error(&format!(
                "internal error (a bug in bezjoin, please report): {what}"
            ));
            BzjStatus::BZJ_ERR_INTERNAL
        }
    }
}

/// Run the body of a function that cannot fail and returns nothing (the
/// release functions) inside the one catch_unwind: the last error is left
/// as it was, so `bzj_curve_free(tmp)` between a failed call and
/// `bzj_last_error()` does not erase the message. A panic (a bug) still
/// replaces it.
pub(crate) fn guard_release(body: impl FnOnce()) {
    if catch_unwind(AssertUnwindSafe(body)).is_err() {
        set_last_error("internal error (a bug in bezjoin, please report): panic while releasing");
    }
}

/// The caller's curve behind `ptr`, or NULL_POINTER naming `name`.
///
/// # Safety
/// `ptr` is null or a live handle from this library.
pub(crate) unsafe fn curve_ref<'a>(ptr: *const BzjCurve, name: &str) -> FfiResult<&'a BezierCurve> {
    // SAFETY: the caller promises a live handle or null.
    unsafe { ptr.as_ref() }
        .map(|h| &h.curve)
        .ok_or_else(|| FfiError::NullPointer(name.into()))
}

/// The caller's array of `len` doubles; a null pointer is accepted only when `len == 0`.
///
/// # Safety
/// `ptr` is null or points to `len` readable doubles.
pub(crate) unsafe fn input_slice<'a, T>(
    ptr: *const T,
    len: usize,
    name: &str,
) -> FfiResult<&'a [T]> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(FfiError::NullPointer(name.into()));
    }
    check_possible_length::<T>(len, name)?;
    // SAFETY: non-null and the caller promises `len` readable elements.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// The caller's output buffer, checked against the length needed.
///
/// # Safety
/// `ptr` is null or points to `given` writable doubles.
pub(crate) unsafe fn output_slice<'a>(
    ptr: *mut f64,
    given: usize,
    needed: usize,
    name: &str,
) -> FfiResult<&'a mut [f64]> {
    if ptr.is_null() {
        return Err(FfiError::NullPointer(name.into()));
    }
    check_possible_length::<f64>(given, name)?;
    if given < needed {
        return Err(FfiError::BufferTooSmall {
            name: name.into(),
            needed,
            given,
        });
    }
    // SAFETY: non-null and the caller promises `given >= needed` writable doubles.
    Ok(unsafe { std::slice::from_raw_parts_mut(ptr, needed) })
}

/// A length no array can have (more than `isize::MAX` bytes) is a caller
/// error, reported before any slice is made (making one would be UB).
fn check_possible_length<T>(len: usize, name: &str) -> FfiResult {
    let largest = isize::MAX as usize / std::mem::size_of::<T>().max(1);
    if len > largest {
        return Err(FfiError::Core(BezjoinError::invalid(
            format!("length of {name}"),
            format!("{len} is larger than any array can be"),
        )));
    }
    Ok(())
}

/// A required pointer to one value to read.
///
/// # Safety
/// `ptr` is null or valid for reads.
pub(crate) unsafe fn input_ref<'a, T>(ptr: *const T, name: &str) -> FfiResult<&'a T> {
    // SAFETY: the caller promises null or a valid pointer.
    unsafe { ptr.as_ref() }.ok_or_else(|| FfiError::NullPointer(name.into()))
}

/// A required out-pointer for one value.
pub(crate) fn require_out<T>(ptr: *mut T, name: &str) -> FfiResult<*mut T> {
    if ptr.is_null() {
        Err(FfiError::NullPointer(name.into()))
    } else {
        Ok(ptr)
    }
}

/// Set a handle out-pointer to NULL (if the out-pointer itself is non-null).
///
/// # Safety
/// `out` is null or valid for writes.
pub(crate) unsafe fn clear_handle(out: *mut *mut BzjCurve) {
    if !out.is_null() {
        // SAFETY: non-null, the caller promises it is writable.
        unsafe { out.write(std::ptr::null_mut()) };
    }
}

/// Move a curve into a new handle.
pub(crate) fn new_handle(curve: BezierCurve) -> *mut BzjCurve {
    Box::into_raw(Box::new(BzjCurve { curve }))
}

/// Write a new handle through an out-pointer already checked non-null.
///
/// # Safety
/// `out` is valid for writes.
pub(crate) unsafe fn write_handle(out: *mut *mut BzjCurve, curve: BezierCurve) {
    // SAFETY: the caller checked `out` and promises it is writable.
    unsafe { out.write(new_handle(curve)) };
}

static VERSION: &str = concat!(env!("CARGO_PKG_VERSION"), "\0");

/// The library version, `"MAJOR.MINOR.PATCH"` (a static string).
#[unsafe(no_mangle)]
pub extern "C" fn bzj_version() -> *const c_char {
    VERSION.as_ptr().cast()
}

/// The message of the calling thread's last failed call (empty after a
/// success). Valid until this thread's next bezjoin call; never NULL.
#[unsafe(no_mangle)]
pub extern "C" fn bzj_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// The name of a status code as a static string (`"BZJ_ERR_SINGULAR"`),
/// `"BZJ_UNKNOWN_STATUS"` for a value that is not one.
#[unsafe(no_mangle)]
pub extern "C" fn bzj_status_name(status: i32) -> *const c_char {
    let name: &'static str = match status {
        0 => "BZJ_OK\0",
        1 => "BZJ_ERR_NULL_POINTER\0",
        2 => "BZJ_ERR_INVALID_ARGUMENT\0",
        3 => "BZJ_ERR_NON_FINITE\0",
        4 => "BZJ_ERR_DIMENSION_MISMATCH\0",
        5 => "BZJ_ERR_BUFFER_TOO_SMALL\0",
        6 => "BZJ_ERR_INCONSISTENT\0",
        7 => "BZJ_ERR_SINGULAR\0",
        8 => "BZJ_ERR_ILL_CONDITIONED\0",
        9 => "BZJ_ERR_NO_INTERSECTION\0",
        99 => "BZJ_ERR_INTERNAL\0",
        _ => "BZJ_UNKNOWN_STATUS\0",
    };
    name.as_ptr().cast()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panic_becomes_internal_with_message() {
        let s = guard(|| panic!("boom"));
        assert_eq!(s, BzjStatus::BZJ_ERR_INTERNAL);
        let msg = unsafe { std::ffi::CStr::from_ptr(bzj_last_error()) }
            .to_str()
            .unwrap()
            .to_owned();
        assert!(msg.contains("boom"), "{msg}");
    }
}
