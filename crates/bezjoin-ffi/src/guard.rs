//! The boundary: status codes, the per-thread last error, the panic guard
//! and the pointer helpers every entry point uses.

use std::cell::RefCell;
use std::ffi::{CStr, CString, c_char};
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
    /// The status code of this error: exactly one per variant, several
    /// variants sharing a code (the message tells them apart). The `match`
    /// is exhaustive without a wildcard, so a new core variant does not
    /// compile until it is given a code here (and in the table of
    /// [`BezjoinError`] and the test `every_error_variant_has_its_one_status`).
    ///
    /// | Error                                   | Status                       |
    /// |-----------------------------------------|------------------------------|
    /// | `NullPointer`                           | `BZJ_ERR_NULL_POINTER` (1)       |
    /// | `BufferTooSmall`, `HandleArrayTooSmall` | `BZJ_ERR_BUFFER_TOO_SMALL` (5)   |
    /// | `Core(ParameterOutOfRange)`             | `BZJ_ERR_INVALID_ARGUMENT` (2)   |
    /// | `Core(OrderAboveDegree)`                | `BZJ_ERR_INVALID_ARGUMENT` (2)   |
    /// | `Core(LengthMismatch)`                  | `BZJ_ERR_INVALID_ARGUMENT` (2)   |
    /// | `Core(InvalidArgument)`                 | `BZJ_ERR_INVALID_ARGUMENT` (2)   |
    /// | `Core(NonFinite)`                       | `BZJ_ERR_NON_FINITE` (3)         |
    /// | `Core(NonFiniteScalar)`                 | `BZJ_ERR_NON_FINITE` (3)         |
    /// | `Core(DimensionMismatch)`               | `BZJ_ERR_DIMENSION_MISMATCH` (4) |
    /// | `Core(Inconsistent)`                    | `BZJ_ERR_INCONSISTENT` (6)       |
    /// | `Core(Singular)`                        | `BZJ_ERR_SINGULAR` (7)           |
    /// | `Core(IllConditioned)`                  | `BZJ_ERR_ILL_CONDITIONED` (8)    |
    /// | `Core(NoIntersection)`                  | `BZJ_ERR_NO_INTERSECTION` (9)    |
    ///
    /// `BZJ_ERR_INTERNAL` (99) is not an error value: [`guard`] returns it
    /// for a caught panic.
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

/// Returned by [`bzj_last_error`] when the thread's message cannot be read
/// (its thread-local storage already destroyed, during thread exit).
static NO_MESSAGE: &CStr = c"";

/// Store the calling thread's message. Never panics: while the thread-local
/// is being destroyed (a call from another thread-local's destructor at
/// thread exit) the message is dropped, and the status still returned.
fn set_last_error(message: &str) {
    let _ = LAST_ERROR.try_with(|e| {
        // A success after a success: nothing to store (no allocation on the
        // hot path of evaluation calls).
        if message.is_empty() && e.try_borrow().is_ok_and(|m| m.as_bytes().is_empty()) {
            return;
        }
        let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
        if let Ok(mut slot) = e.try_borrow_mut() {
            *slot = text;
        }
    });
}

/// Run the body of an entry point that cannot report a status (it returns
/// a pointer) inside catch_unwind: a panic, which the body is written never
/// to raise, gives `fallback` instead of unwinding into C.
fn no_unwind<T>(fallback: T, body: impl FnOnce() -> T) -> T {
    catch_unwind(AssertUnwindSafe(body)).unwrap_or(fallback)
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
    // Cannot panic (a static's address); inside `no_unwind` all the same, so
    // that every extern "C" body runs under catch_unwind without exception.
    let version: *const c_char = VERSION.as_ptr().cast();
    no_unwind(version, || version)
}

/// The message of the calling thread's last failed call (empty after a
/// success). Valid until this thread's next bezjoin call; never NULL (an
/// empty static string when called during thread exit, after the thread's
/// message storage is gone).
#[unsafe(no_mangle)]
pub extern "C" fn bzj_last_error() -> *const c_char {
    no_unwind(NO_MESSAGE.as_ptr(), || {
        LAST_ERROR
            .try_with(|e| e.try_borrow().map_or(NO_MESSAGE.as_ptr(), |m| m.as_ptr()))
            .unwrap_or(NO_MESSAGE.as_ptr())
    })
}

/// The name of a status code as a static string (`"BZJ_ERR_SINGULAR"`),
/// `"BZJ_UNKNOWN_STATUS"` for a value that is not one.
#[unsafe(no_mangle)]
pub extern "C" fn bzj_status_name(status: i32) -> *const c_char {
    no_unwind(c"BZJ_UNKNOWN_STATUS".as_ptr(), || status_name(status))
}

fn status_name(status: i32) -> *const c_char {
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

    fn text(p: *const c_char) -> String {
        assert!(!p.is_null());
        // SAFETY: the library's strings are NUL-terminated and live long enough.
        unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_owned()
    }

    fn last_error() -> String {
        text(bzj_last_error())
    }

    #[test]
    fn panic_becomes_internal_with_message() {
        let s = guard(|| panic!("boom"));
        assert_eq!(s, BzjStatus::BZJ_ERR_INTERNAL);
        let msg = last_error();
        assert!(msg.contains("boom"), "{msg}");
    }

    /// Which variant an error is. No wildcard: a new variant of either enum
    /// stops this test compiling until the table below gives it a status.
    fn variant(e: &FfiError) -> &'static str {
        use BezjoinError as E;
        match e {
            FfiError::NullPointer(_) => "NullPointer",
            FfiError::BufferTooSmall { .. } => "BufferTooSmall",
            FfiError::HandleArrayTooSmall { .. } => "HandleArrayTooSmall",
            FfiError::Core(core) => match core {
                E::ParameterOutOfRange { .. } => "ParameterOutOfRange",
                E::OrderAboveDegree { .. } => "OrderAboveDegree",
                E::LengthMismatch { .. } => "LengthMismatch",
                E::InvalidArgument { .. } => "InvalidArgument",
                E::NonFinite { .. } => "NonFinite",
                E::NonFiniteScalar { .. } => "NonFiniteScalar",
                E::DimensionMismatch { .. } => "DimensionMismatch",
                E::Inconsistent { .. } => "Inconsistent",
                E::Singular { .. } => "Singular",
                E::IllConditioned { .. } => "IllConditioned",
                E::NoIntersection { .. } => "NoIntersection",
            },
        }
    }

    /// The documented mapping (the tables at `BezjoinError` and
    /// `FfiError::status`), with the values and names the C contract fixes:
    /// each variant exactly once, each with exactly one status; through the
    /// guard the status and the variant's own message reach the caller.
    #[test]
    fn every_error_variant_has_its_one_status() {
        use BezjoinError as E;
        use BzjStatus::*;
        let core = |e: E| FfiError::Core(e);
        let table: Vec<(FfiError, BzjStatus, i32, &str)> = vec![
            (
                FfiError::NullPointer("points".into()),
                BZJ_ERR_NULL_POINTER,
                1,
                "BZJ_ERR_NULL_POINTER",
            ),
            (
                FfiError::BufferTooSmall {
                    name: "out".into(),
                    needed: 8,
                    given: 7,
                },
                BZJ_ERR_BUFFER_TOO_SMALL,
                5,
                "BZJ_ERR_BUFFER_TOO_SMALL",
            ),
            (
                FfiError::HandleArrayTooSmall {
                    name: "out".into(),
                    needed: 3,
                    given: 2,
                },
                BZJ_ERR_BUFFER_TOO_SMALL,
                5,
                "BZJ_ERR_BUFFER_TOO_SMALL",
            ),
            (
                core(E::out_of_range("u0", 1.5, "[0, 1]")),
                BZJ_ERR_INVALID_ARGUMENT,
                2,
                "BZJ_ERR_INVALID_ARGUMENT",
            ),
            (
                core(E::OrderAboveDegree {
                    name: "kp".into(),
                    order: 4,
                    degree: 3,
                    curve: "P".into(),
                }),
                BZJ_ERR_INVALID_ARGUMENT,
                2,
                "BZJ_ERR_INVALID_ARGUMENT",
            ),
            (
                core(E::LengthMismatch {
                    name: "points".into(),
                    expected: 8,
                    actual: 7,
                }),
                BZJ_ERR_INVALID_ARGUMENT,
                2,
                "BZJ_ERR_INVALID_ARGUMENT",
            ),
            (
                core(E::invalid("dim", "must be at least 1")),
                BZJ_ERR_INVALID_ARGUMENT,
                2,
                "BZJ_ERR_INVALID_ARGUMENT",
            ),
            (
                core(E::NonFinite {
                    name: "points".into(),
                    index: 2,
                    value: f64::NAN,
                }),
                BZJ_ERR_NON_FINITE,
                3,
                "BZJ_ERR_NON_FINITE",
            ),
            (
                core(E::NonFiniteScalar {
                    name: "t".into(),
                    value: f64::INFINITY,
                }),
                BZJ_ERR_NON_FINITE,
                3,
                "BZJ_ERR_NON_FINITE",
            ),
            (
                core(E::DimensionMismatch {
                    name: "q".into(),
                    expected: 2,
                    actual: 3,
                }),
                BZJ_ERR_DIMENSION_MISMATCH,
                4,
                "BZJ_ERR_DIMENSION_MISMATCH",
            ),
            (
                core(E::Inconsistent {
                    reason: "keep P and keep Q".into(),
                }),
                BZJ_ERR_INCONSISTENT,
                6,
                "BZJ_ERR_INCONSISTENT",
            ),
            (
                core(E::Singular {
                    what: "the middle block".into(),
                }),
                BZJ_ERR_SINGULAR,
                7,
                "BZJ_ERR_SINGULAR",
            ),
            (
                core(E::IllConditioned {
                    what: "connect".into(),
                    estimate: 1e-6,
                    limit: 1e-8,
                }),
                BZJ_ERR_ILL_CONDITIONED,
                8,
                "BZJ_ERR_ILL_CONDITIONED",
            ),
            (
                core(E::NoIntersection {
                    reason: "the curves only touch".into(),
                }),
                BZJ_ERR_NO_INTERSECTION,
                9,
                "BZJ_ERR_NO_INTERSECTION",
            ),
        ];
        let mut seen = std::collections::BTreeMap::new();
        for (error, status, value, name) in &table {
            *seen.entry(variant(error)).or_insert(0) += 1;
            assert_eq!(error.status(), *status, "{error:?}");
            assert_eq!(*status as i32, *value, "{name}");
            assert_eq!(text(bzj_status_name(*value)), *name);
            let message = error.message();
            assert!(!message.is_empty(), "{error:?}");
            let returned = guard(|| {
                Err(match error {
                    FfiError::Core(e) => FfiError::Core(e.clone()),
                    FfiError::NullPointer(n) => FfiError::NullPointer(n.clone()),
                    FfiError::BufferTooSmall {
                        name,
                        needed,
                        given,
                    } => FfiError::BufferTooSmall {
                        name: name.clone(),
                        needed: *needed,
                        given: *given,
                    },
                    FfiError::HandleArrayTooSmall {
                        name,
                        needed,
                        given,
                    } => FfiError::HandleArrayTooSmall {
                        name: name.clone(),
                        needed: *needed,
                        given: *given,
                    },
                })
            });
            assert_eq!(returned, *status, "{error:?}");
            assert_eq!(last_error(), message);
            if let FfiError::Core(e) = error {
                assert_eq!(message, e.to_string());
            }
        }
        // 3 boundary variants + 11 core variants, each exactly once.
        assert_eq!(seen.len(), 14, "{seen:?}");
        assert!(seen.values().all(|&k| k == 1), "{seen:?}");
        // No error value maps to success or to the panic code.
        assert!(
            table
                .iter()
                .all(|(e, ..)| !matches!(e.status(), BZJ_OK | BZJ_ERR_INTERNAL))
        );
        assert_eq!(guard(|| Ok(())), BZJ_OK);
        assert_eq!(last_error(), "");
    }

    #[test]
    fn status_names_and_version_are_static_strings() {
        for (value, name) in [
            (0, "BZJ_OK"),
            (99, "BZJ_ERR_INTERNAL"),
            (10, "BZJ_UNKNOWN_STATUS"),
            (-1, "BZJ_UNKNOWN_STATUS"),
            (i32::MIN, "BZJ_UNKNOWN_STATUS"),
        ] {
            assert_eq!(text(bzj_status_name(value)), name);
        }
        assert_eq!(text(bzj_version()), env!("CARGO_PKG_VERSION"));
        assert_eq!(bzj_version(), bzj_version());
    }

    /// Calls made from another thread-local's destructor at thread exit,
    /// after `LAST_ERROR` is gone: `bzj_last_error` returns an empty string
    /// (with `LocalKey::with` it panicked, and a panic there aborts the
    /// process), an entry point still returns its status.
    #[test]
    fn last_error_during_thread_exit_is_empty_not_a_panic() {
        use std::sync::Mutex;
        static SEEN: Mutex<Vec<(bool, String, BzjStatus, String)>> = Mutex::new(Vec::new());

        struct CallsAtExit;
        impl Drop for CallsAtExit {
            fn drop(&mut self) {
                let gone = LAST_ERROR.try_with(|_| ()).is_err();
                let before = text(bzj_last_error());
                let status = guard(|| Err(FfiError::NullPointer("late".into())));
                let after = text(bzj_last_error());
                SEEN.lock().unwrap().push((gone, before, status, after));
            }
        }
        thread_local! {
            static AT_EXIT: CallsAtExit = const { CallsAtExit };
        }

        std::thread::spawn(|| {
            // Registered first, so destroyed after LAST_ERROR (destructors
            // run in reverse order of registration on this platform).
            AT_EXIT.with(|_| ());
            let s = guard(|| Err(FfiError::NullPointer("early".into())));
            assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
            assert_eq!(last_error(), "early is a null pointer");
        })
        .join()
        .expect("the thread exits cleanly");

        let seen = SEEN.lock().unwrap();
        assert_eq!(seen.len(), 1);
        let (gone, before, status, after) = &seen[0];
        assert_eq!(*status, BzjStatus::BZJ_ERR_NULL_POINTER);
        if *gone {
            assert_eq!(before, "");
            assert_eq!(after, "");
        } else {
            // Another destructor order: the storage is still there.
            assert_eq!(before, "early is a null pointer");
            assert_eq!(after, "late is a null pointer");
        }
    }
}
