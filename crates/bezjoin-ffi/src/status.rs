//! Status codes: the C enum [`BzjStatus`], the boundary's error type
//! [`FfiError`] with its exhaustive mapping to a status, and the status
//! names of [`bzj_status_name`].

use std::ffi::c_char;

use bezjoin_core::BezjoinError;

use crate::guard::no_unwind;

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
    /// `BZJ_ERR_INTERNAL` (99) is not an error value: [`guard`](crate::guard::guard) returns it
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
mod status_mapping_tests {
    use std::ffi::CStr;

    use super::*;
    use crate::guard::{bzj_last_error, guard};

    fn text(p: *const c_char) -> String {
        assert!(!p.is_null());
        // SAFETY: the library's strings are NUL-terminated and live long enough.
        unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_owned()
    }

    fn last_error() -> String {
        text(bzj_last_error())
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
    fn status_names_are_static_strings() {
        for (value, name) in [
            (0, "BZJ_OK"),
            (99, "BZJ_ERR_INTERNAL"),
            (10, "BZJ_UNKNOWN_STATUS"),
            (-1, "BZJ_UNKNOWN_STATUS"),
            (i32::MIN, "BZJ_UNKNOWN_STATUS"),
        ] {
            assert_eq!(text(bzj_status_name(value)), name);
        }
    }
}
