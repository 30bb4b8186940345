//! Curve handles: create, inspect, evaluate, and the exact operations.

use bezjoin_core::BezierCurve;
use bezjoin_core::error::{BezjoinError, check_finite_scalar};

use crate::guard::{
    BzjCurve, BzjStatus, FfiError, clear_handle, curve_ref, guard, input_slice, output_slice,
    require_out, write_handle,
};

/// Create a Bezier curve of degree `degree` in dimension `dim` from
/// `points_len == (degree + 1) * dim` row-major coordinates.
///
/// @return BZJ_ERR_NULL_POINTER if `points` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `dim == 0` or `points_len` is wrong;
///         BZJ_ERR_NON_FINITE if a coordinate is NaN or infinite.
///
/// # Safety
/// `points` points to `points_len` readable doubles; `out` is writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_new(
    dim: usize,
    degree: usize,
    points: *const f64,
    points_len: usize,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: `out` is null or writable (caller contract).
    unsafe { clear_handle(out) };
    guard(|| {
        let out = require_out(out, "out")?;
        if points.is_null() {
            return Err(FfiError::NullPointer("points".into()));
        }
        // SAFETY: caller promises `points_len` readable doubles.
        let pts = unsafe { input_slice(points, points_len, "points") }?;
        let curve = BezierCurve::new(dim, degree, pts.to_vec())?;
        // SAFETY: `out` checked non-null above.
        unsafe { write_handle(out, curve) };
        Ok(())
    })
}

/// Release a curve handle. NULL is accepted and ignored.
///
/// # Safety
/// `curve` is NULL or a handle from this library not yet released.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_free(curve: *mut BzjCurve) {
    if curve.is_null() {
        return;
    }
    let _ = guard(|| {
        // SAFETY: a live handle made by `Box::into_raw`, released once.
        drop(unsafe { Box::from_raw(curve) });
        Ok(())
    });
}

/// The degree of `c`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_degree(c: *const BzjCurve, out: *mut usize) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        // SAFETY: checked non-null.
        unsafe { out.write(curve.degree()) };
        Ok(())
    })
}

/// The dimension of `c`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_dim(c: *const BzjCurve, out: *mut usize) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        // SAFETY: checked non-null.
        unsafe { out.write(curve.dim()) };
        Ok(())
    })
}

/// Copy the `(degree + 1) * dim` row-major control points of `c` into `out`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len < (degree + 1) * dim` (nothing written).
///
/// # Safety
/// `c` is NULL or a live handle; `out` points to `out_len` writable doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_points(
    c: *const BzjCurve,
    out: *mut f64,
    out_len: usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        // SAFETY: caller contract.
        let buf = unsafe { output_slice(out, out_len, curve.points().len(), "out") }?;
        buf.copy_from_slice(curve.points());
        Ok(())
    })
}

/// Value and derivatives `0..=max_order` of `c` at `t` (any finite `t`;
/// outside `[0, 1]` the polynomial is continued), written row-major: row `k`
/// (`dim` doubles) is the k-th derivative; `(max_order + 1) * dim` doubles.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `t` is NaN or infinite;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len` is short (nothing written).
///
/// # Safety
/// `c` is NULL or a live handle; `out` points to `out_len` writable doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_eval(
    c: *const BzjCurve,
    t: f64,
    max_order: usize,
    out: *mut f64,
    out_len: usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        check_finite_scalar("t", t)?;
        let needed = max_order
            .checked_add(1)
            .and_then(|k| k.checked_mul(curve.dim()))
            .ok_or_else(|| {
                BezjoinError::invalid("max_order", format!("{max_order} is too large"))
            })?;
        // SAFETY: caller contract.
        let buf = unsafe { output_slice(out, out_len, needed, "out") }?;
        if max_order == 0 {
            curve.eval_into(t, buf);
        } else {
            curve.eval_derivatives_into(t, max_order, buf);
        }
        Ok(())
    })
}

/// The same curve written with degree `new_degree >= degree` (exact).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `new_degree` is below the degree.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_elevate(
    c: *const BzjCurve,
    new_degree: usize,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe { clear_handle(out) };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        let elevated = curve.elevate_degree(new_degree)?;
        // SAFETY: checked non-null.
        unsafe { write_handle(out, elevated) };
        Ok(())
    })
}

/// Split `c` at `t in [0, 1]` into the pieces on `[0, t]` and `[t, 1]`,
/// each reparametrised to `[0, 1]` (de Casteljau, exact).
///
/// @return BZJ_ERR_NULL_POINTER if a pointer is NULL;
///         BZJ_ERR_NON_FINITE / BZJ_ERR_INVALID_ARGUMENT for a bad `t`.
///
/// # Safety
/// `c` is NULL or a live handle; `left`, `right` are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_split(
    c: *const BzjCurve,
    t: f64,
    left: *mut *mut BzjCurve,
    right: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe {
        clear_handle(left);
        clear_handle(right);
    }
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let left = require_out(left, "left")?;
        let right = require_out(right, "right")?;
        let (a, b) = curve.split_at(t)?;
        // SAFETY: both checked non-null.
        unsafe {
            write_handle(left, a);
            write_handle(right, b);
        }
        Ok(())
    })
}

/// The curve `s -> c(a + (b - a) s)` for any finite `a`, `b` (extrapolation
/// and `a > b` allowed; `a == b` gives a constant curve).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `a` or `b` is NaN or infinite.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_segment(
    c: *const BzjCurve,
    a: f64,
    b: f64,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe { clear_handle(out) };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        let seg = curve.segment(a, b)?;
        // SAFETY: checked non-null.
        unsafe { write_handle(out, seg) };
        Ok(())
    })
}

/// The curve traversed backwards, `s -> c(1 - s)`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_reverse(
    c: *const BzjCurve,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe { clear_handle(out) };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        // SAFETY: checked non-null.
        unsafe { write_handle(out, curve.reverse()) };
        Ok(())
    })
}

/// Signed arc length of `c` from parameter `a` to `b` (any finite values),
/// by adaptive Gauss-Legendre quadrature to an absolute accuracy of
/// `1e-13 * max(1, control polygon length)`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `a` or `b` is NaN or infinite.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_length(
    c: *const BzjCurve,
    a: f64,
    b: f64,
    out: *mut f64,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        let len = curve.arc_length_default(a, b)?;
        // SAFETY: checked non-null.
        unsafe { out.write(len) };
        Ok(())
    })
}
