//! The one error type of the library.
//!
//! Every variant carries the offending values so that a message can name the
//! bad argument (`"u0 = 1.5 is outside [0, 1]"`). The C ABI maps the variants
//! onto its status codes with an exhaustive `match`, so the enum is
//! deliberately not `#[non_exhaustive]`: a new variant must be given a status
//! code before the FFI crate compiles again.

/// Result alias used throughout the crate.
pub type Result<T, E = BezjoinError> = std::result::Result<T, E>;

/// Everything that can go wrong in a bezjoin operation.
///
/// # Status codes of the C ABI
///
/// Every variant maps onto exactly one status code of the C contract
/// (`include/bezjoin.h`); several variants share a code (the message
/// from `bzj_last_error()` tells them apart). The mapping is the exhaustive
/// `match` in `FfiError::status` (crate `bezjoin-ffi`, `guard.rs`), and a unit
/// test there checks this table variant by variant:
///
/// | Variant                | Status                       | Value |
/// |------------------------|------------------------------|-------|
/// | [`ParameterOutOfRange`](Self::ParameterOutOfRange) | `BZJ_ERR_INVALID_ARGUMENT`   | 2 |
/// | [`OrderAboveDegree`](Self::OrderAboveDegree)       | `BZJ_ERR_INVALID_ARGUMENT`   | 2 |
/// | [`LengthMismatch`](Self::LengthMismatch)           | `BZJ_ERR_INVALID_ARGUMENT`   | 2 |
/// | [`InvalidArgument`](Self::InvalidArgument)         | `BZJ_ERR_INVALID_ARGUMENT`   | 2 |
/// | [`NonFinite`](Self::NonFinite)                     | `BZJ_ERR_NON_FINITE`         | 3 |
/// | [`NonFiniteScalar`](Self::NonFiniteScalar)         | `BZJ_ERR_NON_FINITE`         | 3 |
/// | [`DimensionMismatch`](Self::DimensionMismatch)     | `BZJ_ERR_DIMENSION_MISMATCH` | 4 |
/// | [`Inconsistent`](Self::Inconsistent)               | `BZJ_ERR_INCONSISTENT`       | 6 |
/// | [`Singular`](Self::Singular)                       | `BZJ_ERR_SINGULAR`           | 7 |
/// | [`IllConditioned`](Self::IllConditioned)           | `BZJ_ERR_ILL_CONDITIONED`    | 8 |
/// | [`NoIntersection`](Self::NoIntersection)           | `BZJ_ERR_NO_INTERSECTION`    | 9 |
///
/// The remaining codes come from the boundary alone: `BZJ_ERR_NULL_POINTER`
/// (1, a NULL pointer), `BZJ_ERR_BUFFER_TOO_SMALL` (5, a caller's array too
/// short) and `BZJ_ERR_INTERNAL` (99, a caught panic); no core error maps
/// to them, and `BZJ_OK` (0) is success.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BezjoinError {
    /// A scalar parameter lies outside its domain.
    ///
    /// ```
    /// # use bezjoin_core::BezierCurve;
    /// let line = BezierCurve::new(2, 1, vec![0.0, 0.0, 1.0, 0.0]).unwrap();
    /// let err = line.split_at(1.5).unwrap_err();
    /// assert_eq!(err.to_string(), "t = 1.5 is outside [0, 1]");
    /// ```
    #[error("{name} = {} is outside {range}", Compact(*.value))]
    ParameterOutOfRange {
        /// Name of the argument as the caller knows it.
        name: String,
        /// The value given.
        value: f64,
        /// The allowed range, written as in mathematics (`[0, 1]`, `(0, 1)`, `> 0`).
        range: String,
    },

    /// A continuity or derivative order above what the curve's degree allows.
    #[error("{name} = {order} is above the degree {degree} of {curve}")]
    OrderAboveDegree {
        /// Name of the order argument.
        name: String,
        /// The order given.
        order: usize,
        /// The degree it may not exceed.
        degree: usize,
        /// Which curve.
        curve: String,
    },

    /// An array whose length does not fit the degree, dimension or count.
    #[error("{name} has {actual} values, expected {expected}")]
    LengthMismatch {
        /// Name of the array.
        name: String,
        /// Length needed.
        expected: usize,
        /// Length given.
        actual: usize,
    },

    /// Any other value outside its domain; the reason says which and why.
    #[error("{name}: {reason}")]
    InvalidArgument {
        /// Name of the argument.
        name: String,
        /// What is wrong with it.
        reason: String,
    },

    /// NaN or infinity in the input.
    ///
    /// ```
    /// # use bezjoin_core::BezierCurve;
    /// let err = BezierCurve::new(1, 1, vec![0.0, f64::NAN]).unwrap_err();
    /// assert_eq!(err.to_string(), "points[1] = NaN is not finite");
    /// ```
    #[error("{name}[{index}] = {value} is not finite")]
    NonFinite {
        /// Name of the array or argument.
        name: String,
        /// Position of the first non-finite value (0 for a scalar).
        index: usize,
        /// The value found.
        value: f64,
    },

    /// A scalar argument that is NaN or infinite (no index in the message).
    ///
    /// ```
    /// # use bezjoin_core::BezierCurve;
    /// let line = BezierCurve::new(1, 1, vec![0.0, 1.0]).unwrap();
    /// let err = line.segment(0.0, f64::INFINITY).unwrap_err();
    /// assert_eq!(err.to_string(), "b = inf is not finite");
    /// ```
    #[error("{name} = {value} is not finite")]
    NonFiniteScalar {
        /// Name of the argument.
        name: String,
        /// The value found.
        value: f64,
    },

    /// Two curves or data sets of different dimensions.
    #[error("{name} has dimension {actual}, expected {expected}")]
    DimensionMismatch {
        /// Which input.
        name: String,
        /// Dimension of the reference input.
        expected: usize,
        /// Dimension found.
        actual: usize,
    },

    /// The constraints contradict each other or are too many.
    #[error("inconsistent constraints: {reason}")]
    Inconsistent {
        /// Which constraints and why.
        reason: String,
    },

    /// A linear system that has no unique solution.
    #[error("singular system in {what}")]
    Singular {
        /// Which system.
        what: String,
    },

    /// The answer cannot be trusted to the promised accuracy.
    #[error("{what}: estimated relative error {estimate:e} exceeds the promised {limit:e}")]
    IllConditioned {
        /// Which computation.
        what: String,
        /// The error estimate (relative).
        estimate: f64,
        /// The accuracy the library promises.
        limit: f64,
    },

    /// Curves that should cross do not (or only touch).
    #[error("no intersection: {reason}")]
    NoIntersection {
        /// What was found instead.
        reason: String,
    },
}

impl BezjoinError {
    /// `ParameterOutOfRange` with owned strings.
    pub fn out_of_range(name: impl Into<String>, value: f64, range: impl Into<String>) -> Self {
        Self::ParameterOutOfRange {
            name: name.into(),
            value,
            range: range.into(),
        }
    }

    /// `InvalidArgument` with owned strings.
    pub fn invalid(name: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::InvalidArgument {
            name: name.into(),
            reason: reason.into(),
        }
    }
}

/// Check that every value of `values` is finite; name the first one that is not.
pub(crate) fn check_finite(name: &str, values: &[f64]) -> Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        None => Ok(()),
        Some(index) => Err(BezjoinError::NonFinite {
            name: name.into(),
            index,
            value: values[index],
        }),
    }
}

/// Check a scalar is finite.
pub(crate) fn check_finite_scalar(name: &str, value: f64) -> Result<()> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(non_finite_scalar(name, value))
    }
}

/// The error of [`check_finite_scalar`], out of the callers' hot paths
/// (the checks themselves are inlined: a comparison and a branch).
#[cold]
#[inline(never)]
fn non_finite_scalar(name: &str, value: f64) -> BezjoinError {
    BezjoinError::NonFiniteScalar {
        name: name.into(),
        value,
    }
}

/// The error of a range check, out of the callers' hot paths.
#[cold]
#[inline(never)]
fn outside_range(name: &str, value: f64, range: std::fmt::Arguments<'_>) -> BezjoinError {
    BezjoinError::out_of_range(name, value, range.to_string())
}

/// Check `value` is finite and in the closed interval `[lo, hi]`.
pub(crate) fn check_closed_range(name: &str, value: f64, lo: f64, hi: f64) -> Result<()> {
    check_finite_scalar(name, value)?;
    if value < lo || value > hi {
        return Err(outside_range(name, value, format_args!("[{lo}, {hi}]")));
    }
    Ok(())
}

/// Check `value` is finite and in the open interval `(lo, hi)`.
pub(crate) fn check_open_range(name: &str, value: f64, lo: f64, hi: f64) -> Result<()> {
    check_finite_scalar(name, value)?;
    if value <= lo || value >= hi {
        return Err(outside_range(name, value, format_args!("({lo}, {hi})")));
    }
    Ok(())
}

/// Check `value` is finite and strictly positive.
pub(crate) fn check_positive(name: &str, value: f64) -> Result<()> {
    check_finite_scalar(name, value)?;
    if value <= 0.0 {
        return Err(outside_range(name, value, format_args!("> 0")));
    }
    Ok(())
}

/// A number for a message: as Rust writes it (the shortest string that
/// reads back to the same double) between 1e-5 and 1e16, where that is a
/// plain decimal, and in exponent form outside, where the plain decimal of
/// a value like 1e-300 runs to hundreds of digits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Compact(pub f64);

impl std::fmt::Display for Compact {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let magnitude = self.0.abs();
        if magnitude == 0.0 || !magnitude.is_finite() || (1e-5..1e16).contains(&magnitude) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Out-of-range values read back exactly and stay short at every
    /// magnitude: plain decimals in the middle, exponent form at the ends
    /// (a tiny or huge parameter used to print as hundreds of digits).
    #[test]
    fn out_of_range_messages_are_short_and_exact_at_every_magnitude() {
        for value in [
            -1e-300,
            5e-324,
            1e-6,
            2.5e-5,
            0.0,
            -0.0,
            1.5,
            123_456.789,
            9.9e15,
            1e16,
            -3.7e200,
            f64::MAX,
        ] {
            let message = BezjoinError::out_of_range("ts[0]", value, "[0, 1]").to_string();
            let written = message
                .strip_prefix("ts[0] = ")
                .and_then(|rest| rest.strip_suffix(" is outside [0, 1]"))
                .unwrap_or_else(|| panic!("{message}"));
            assert!(written.len() <= 24, "{value:e}: {message}");
            assert_eq!(
                written.parse::<f64>().map(f64::to_bits),
                Ok(value.to_bits()),
                "{message}"
            );
        }
        assert_eq!(
            BezjoinError::out_of_range("t", 1.5, "[0, 1]").to_string(),
            "t = 1.5 is outside [0, 1]"
        );
        assert_eq!(
            BezjoinError::out_of_range("ts[0]", -1e-300, "[0, 1]").to_string(),
            "ts[0] = -1e-300 is outside [0, 1]"
        );
    }
}
