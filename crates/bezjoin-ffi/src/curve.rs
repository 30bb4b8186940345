//! Curve handles: create, inspect, evaluate, and the exact operations.
//!
//! Every function here takes Bezier and NURBS handles (`nurbs.rs` makes the
//! latter). A Bezier handle keeps its exact behaviour; a NURBS handle works
//! in its own parameters, on its domain `[first, last]`.

use bezjoin_core::{BezierCurve, BezjoinError, Curve, MAX_DEGREE, NurbsCurve};

use crate::guard::{guard, guard_release};
use crate::handles::{BzjCurve, HandleOut, require_all};
use crate::pointers::{curve_ref, input_slice, output_slice, require_out};
use crate::status::{BzjStatus, FfiError};

/// Create a Bezier curve of degree `degree` in dimension `dim` from
/// `points_len == (degree + 1) * dim` row-major coordinates.
///
/// @return BZJ_ERR_NULL_POINTER if `points` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `dim == 0`, `degree` is above the
///         maximum degree 4096, `(degree + 1) * dim` overflows `size_t`, or
///         `points_len` is wrong (all checked before `points` is read);
///         BZJ_ERR_NON_FINITE if a coordinate is NaN or infinite.
///         On any error `*out` is set to NULL.
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
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        if points.is_null() {
            return Err(FfiError::NullPointer("points".into()));
        }
        // Check the length from the numbers alone before touching memory.
        BezierCurve::check_shape(dim, degree, points_len)?;
        // SAFETY: caller promises `points_len` readable doubles.
        let pts = unsafe { input_slice(points, points_len, "points") }?;
        out.write(BezierCurve::new(dim, degree, pts.to_vec())?);
        Ok(())
    })
}

/// Release a curve handle. NULL is accepted and ignored. The calling
/// thread's last error message is left unchanged.
///
/// # Safety
/// `curve` is NULL or a handle from this library not yet released.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_free(curve: *mut BzjCurve) {
    if curve.is_null() {
        return;
    }
    guard_release(|| {
        // SAFETY: a live handle made by `Box::into_raw`, released once.
        drop(unsafe { Box::from_raw(curve) });
    });
}

/// The degree of `c` (Bezier or NURBS).
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

/// The dimension of `c` (Bezier or NURBS).
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

/// Copy the `(degree + 1) * dim` row-major control points of `c` into `out`;
/// for a NURBS handle its `pole_count * dim` poles (Cartesian, not
/// multiplied by the weights; `bzj_curve_pole_count`, `bzj_curve_weights`).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `out_len` is larger than any array can be;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len` is below the number of
///         coordinates (nothing written).
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

/// Value and derivatives `0..=max_order` of `c` at `t`, written row-major:
/// row `k` (`dim` doubles) is the k-th derivative; `(max_order + 1) * dim`
/// doubles. Any `max_order` (above the degree a polynomial's derivatives
/// are 0). A Bezier handle takes any finite `t` (outside `[0, 1]` the
/// polynomial is continued). A NURBS handle takes `t` in its domain
/// `[first, last]` only; at an interior knot the derivatives are those of
/// the span on the right of `t`, at `last` those of the last span.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `t` is NaN or infinite, or (NURBS) a derivative
///         overflows `double` (extreme knot spacing; the message names its order);
///         BZJ_ERR_INVALID_ARGUMENT if `t` is outside a NURBS handle's
///         domain, `(max_order + 1) * dim` overflows `size_t` or `out_len`
///         is larger than any array can be;
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
    guard(move || {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        if !t.is_finite() {
            return Err(non_finite_t(t));
        }
        let needed = derivative_rows_len(max_order, curve.dim())?;
        match curve {
            Curve::Bezier(c) => {
                // SAFETY: caller contract.
                let buf = unsafe { output_slice(out, out_len, needed, "out") }?;
                if max_order == 0 {
                    c.eval_into(t, buf);
                } else {
                    c.eval_derivatives_into(t, max_order, buf);
                }
            }
            Curve::Nurbs(n) => {
                // The parameter's error before the buffer's.
                let (first, last) = n.domain();
                if !(first..=last).contains(&t) {
                    n.check_parameter("t", t)?;
                }
                // SAFETY: caller contract.
                let buf = unsafe { output_slice(out, out_len, needed, "out") }?;
                // The value in dimension 2 or 3 (`buf` holds `dim` values
                // at order 0) straight into the caller's buffer; the rest
                // through a scratch block.
                if max_order == 0
                    && let Ok(point) = <&mut [f64; 3]>::try_from(&mut *buf)
                {
                    *point = n.point_checked::<3>(|| "t".into(), t)?;
                } else if max_order == 0
                    && let Ok(point) = <&mut [f64; 2]>::try_from(&mut *buf)
                {
                    *point = n.point_checked::<2>(|| "t".into(), t)?;
                } else {
                    eval_nurbs(n, t, max_order, buf)?;
                }
            }
        }
        Ok(())
    })
}

/// [`bzj_curve_eval`] of a NURBS handle into `buf` (its checked length),
/// all but the value in dimension 2 or 3: computed into a scratch block (on
/// the stack up to 16 doubles) and checked before anything is written. Out
/// of line: the block would otherwise give the Bezier path's frame its
/// size.
#[inline(never)]
fn eval_nurbs(
    n: &NurbsCurve,
    t: f64,
    max_order: usize,
    buf: &mut [f64],
) -> Result<(), BezjoinError> {
    let needed = buf.len();
    let mut stack = [0.0f64; 16];
    let mut heap = Vec::new();
    let block: &mut [f64] = if needed <= stack.len() {
        &mut stack[..needed]
    } else {
        heap.resize(needed, 0.0);
        &mut heap
    };
    n.eval_derivatives_checked_into(|| "t".into(), t, max_order, block)?;
    buf.copy_from_slice(block);
    Ok(())
}

/// The same curve written with degree `new_degree >= degree` (exact). A
/// NURBS handle gives a NURBS handle on the same domain: every span is
/// raised, the multiplicity of each interior knot grows by
/// `new_degree - degree` (so the continuity there is kept), the ends are
/// clamped; rational curves stay rational.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `new_degree` is below the degree or
///         above the maximum degree 4096;
///         BZJ_ERR_ILL_CONDITIONED (NURBS) if removing a knot the raised
///         spans do not need, exact in exact arithmetic, leaves an error
///         above 1e-10 of the largest homogeneous coordinate.
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
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = out.require()?;
        match curve {
            Curve::Bezier(b) => out.write(b.elevate_degree(new_degree)?),
            Curve::Nurbs(n) => {
                // Before the core builds a knot vector of that size.
                if new_degree > MAX_DEGREE {
                    return Err(BezjoinError::invalid(
                        "new_degree",
                        format!("{new_degree} is above the supported maximum degree {MAX_DEGREE}"),
                    )
                    .into());
                }
                out.write(n.elevate_degree(new_degree)?);
            }
        }
        Ok(())
    })
}

/// Split `c` at `t in [0, 1]` into the pieces on `[0, t]` and `[t, 1]`,
/// each reparametrised to `[0, 1]` (de Casteljau, exact). A NURBS handle is
/// split at `t` strictly inside its domain `(first, last)` into two NURBS
/// handles on `[first, t]` and `[t, last]` that keep the original
/// parameters (knot insertion, exact; each piece clamped at `t`).
///
/// @return BZJ_ERR_NULL_POINTER if a pointer is NULL;
///         BZJ_ERR_NON_FINITE if `t` is NaN or infinite;
///         BZJ_ERR_INVALID_ARGUMENT if `t` is outside `[0, 1]` (Bezier) or
///         outside the open domain `(first, last)` (NURBS).
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
    let outs = unsafe {
        [
            HandleOut::cleared(left, "left"),
            HandleOut::cleared(right, "right"),
        ]
    };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let [left, right] = require_all(outs)?;
        match curve {
            Curve::Bezier(c) => {
                let (a, b) = c.split_at(t)?;
                left.write(a);
                right.write(b);
            }
            Curve::Nurbs(n) => {
                check_nurbs_split(n, t)?;
                let (a, b) = n.split_at(t)?;
                left.write(a);
                right.write(b);
            }
        }
        Ok(())
    })
}

/// The curve `s -> c(a + (b - a) s)` for any finite `a`, `b` (extrapolation
/// and `a > b` allowed; `a == b` gives a constant curve). For a NURBS
/// handle: the piece on `[a, b]`, `first <= a < b <= last`, as a NURBS
/// handle with the original parameters (its domain is `[a, b]`; exact, by
/// knot insertion; clamped at both ends).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `a` or `b` is NaN or infinite;
///         BZJ_ERR_INVALID_ARGUMENT if `a` or `b` lies so far outside
///         `[0, 1]` that the segment's control points overflow (Bezier), or
///         `a` or `b` is outside the domain or `a >= b` (NURBS).
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
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = out.require()?;
        match curve {
            Curve::Bezier(c) => out.write(c.segment(a, b)?),
            Curve::Nurbs(n) => out.write(n.segment(a, b)?),
        }
        Ok(())
    })
}

/// The curve traversed backwards, `s -> c(1 - s)`; for a NURBS handle
/// `u -> c(first + last - u)` on the same domain (a NURBS handle).
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
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = out.require()?;
        match curve {
            Curve::Bezier(c) => out.write(c.reverse()),
            Curve::Nurbs(n) => out.write(n.reverse()),
        }
        Ok(())
    })
}

/// Signed arc length of `c` from parameter `a` to `b` (negative when
/// `b < a`). A Bezier handle takes any finite `a`, `b` and is integrated by
/// adaptive Gauss-Legendre quadrature to an absolute accuracy of
/// `1e-13 * max(1, control polygon length)`, or `16 * DBL_EPSILON` times
/// the length where that is larger (the rounding level, e.g. long
/// extrapolated ranges); the range is cut at cusps first, so the accuracy
/// holds across them. A NURBS handle takes `a`, `b` in its domain and is
/// integrated span by span to `1e-13 * max(1, length of the polygon of
/// poles)`: polynomial spans as Bezier curves (above), rational spans by
/// adaptive Gauss-Kronrod on the speed.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_NON_FINITE if `a` or `b` is NaN or infinite, or (after
///         those) the control polygon's length overflows `double` (finite
///         points more than `DBL_MAX` apart: the accuracy above is relative
///         to it; the message names "the control polygon length of the
///         curve");
///         BZJ_ERR_INVALID_ARGUMENT if the length overflows the double range
///         (e.g. `a = -1e200, b = 1e200`; the message names `a, b`), or `a`
///         or `b` is outside a NURBS handle's domain (named);
///         BZJ_ERR_ILL_CONDITIONED if the adaptive rule spends its work
///         budget (Bezier: about 10^6 speed evaluations, 40 bisections; a
///         rational span: 2^18 speed evaluations) without reaching the
///         accuracy above; the message carries the estimated relative error.
///         On any error `*out` is left unchanged.
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

/// Values and derivatives `0..=max_order` of `c` at the `n` parameters
/// `ts` in one call (a host tessellating a curve for display), written
/// parameter-major: `out[(i * (max_order + 1) + k) * dim + c]` is
/// coordinate `c` of the k-th derivative at `ts[i]`;
/// `n * (max_order + 1) * dim` doubles. Block `i` is exactly what
/// `bzj_curve_eval(c, ts[i], max_order, ...)` writes (for a NURBS handle
/// every `ts[i]` must lie in its domain). Every parameter is checked before
/// anything is written. `n == 0` writes nothing (`ts` and `out` may then be
/// NULL).
///
/// @return BZJ_ERR_NULL_POINTER if `c`, or `ts` or `out` with `n > 0`, is NULL;
///         BZJ_ERR_NON_FINITE if some `ts[i]` is NaN or infinite (named), or
///         (NURBS) a derivative overflows `double` (the message names
///         `ts[i]` and the order; the blocks are evaluated in order straight
///         into `out`, so those before block `i` are written);
///         BZJ_ERR_INVALID_ARGUMENT if some `ts[i]` is outside a NURBS
///         handle's domain (named), `n * (max_order + 1) * dim` overflows
///         `size_t`, or `n` or `out_len` is larger than any array can be;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len` is short (nothing written).
///
/// # Safety
/// `c` is NULL or a live handle; `ts` points to `n` readable doubles; `out`
/// points to `out_len` writable doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_eval_many(
    c: *const BzjCurve,
    ts: *const f64,
    n: usize,
    max_order: usize,
    out: *mut f64,
    out_len: usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        // SAFETY: caller contract.
        let ts = unsafe { input_slice(ts, n, "ts") }?;
        if let Some(i) = ts.iter().position(|t| !t.is_finite()) {
            return Err(BezjoinError::NonFinite {
                name: "ts".into(),
                index: i,
                value: ts[i],
            }
            .into());
        }
        let block = derivative_rows_len(max_order, curve.dim())?;
        let needed = block.checked_mul(n).ok_or_else(|| {
            BezjoinError::invalid(
                "n, max_order",
                format!(
                    "n * (max_order + 1) * dim = {n} * ({max_order} + 1) * {} overflows",
                    curve.dim()
                ),
            )
        })?;
        if n == 0 {
            return Ok(());
        }
        if let Curve::Nurbs(nurbs) = curve {
            let (first, last) = nurbs.domain();
            if let Some(i) = ts.iter().position(|&t| t < first || t > last) {
                nurbs.check_parameter(&format!("ts[{i}]"), ts[i])?;
            }
        }
        // SAFETY: caller contract.
        let buf = unsafe { output_slice(out, out_len, needed, "out") }?;
        // Every argument is checked: evaluate straight into the caller's
        // buffer, one block per parameter.
        let blocks = ts.iter().zip(buf.chunks_exact_mut(block));
        match curve {
            Curve::Bezier(c) if max_order == 0 => c.eval_many_into(ts, buf),
            Curve::Bezier(c) => {
                for (&t, rows) in blocks {
                    c.eval_derivatives_into(t, max_order, rows);
                }
            }
            Curve::Nurbs(nurbs) => {
                for (i, (&t, rows)) in blocks.enumerate() {
                    nurbs.eval_derivatives_checked_into(
                        || format!("ts[{i}]"),
                        t,
                        max_order,
                        rows,
                    )?;
                }
            }
        }
        Ok(())
    })
}

/// A NURBS curve is split at `t` strictly inside its domain; the errors
/// name `t`, the argument of `bzj_curve_split`.
fn check_nurbs_split(curve: &NurbsCurve, t: f64) -> Result<(), BezjoinError> {
    if !t.is_finite() {
        return Err(BezjoinError::NonFiniteScalar {
            name: "t".into(),
            value: t,
        });
    }
    let (first, last) = curve.domain();
    if t <= first || t >= last {
        return Err(BezjoinError::out_of_range(
            "t",
            t,
            format!("({first}, {last})"),
        ));
    }
    Ok(())
}

/// NON_FINITE naming the parameter `t` (cold and out of line: the
/// evaluation's hot path builds no error).
#[cold]
#[inline(never)]
fn non_finite_t(t: f64) -> FfiError {
    BezjoinError::NonFiniteScalar {
        name: "t".into(),
        value: t,
    }
    .into()
}

/// `(max_order + 1) * dim`, the doubles of one value-and-derivatives block
/// (`bzj_curve_eval`, each parameter of `bzj_curve_eval_many`), or
/// INVALID_ARGUMENT naming `max_order` when it overflows.
fn derivative_rows_len(max_order: usize, dim: usize) -> Result<usize, BezjoinError> {
    max_order
        .checked_add(1)
        .and_then(|k| k.checked_mul(dim))
        .ok_or_else(|| BezjoinError::invalid("max_order", format!("{max_order} is too large")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::guard::last_error;

    fn line() -> *mut BzjCurve {
        let pts = [0.0, 0.0, 1.0, 2.0];
        let mut c = std::ptr::null_mut();
        // SAFETY: valid buffers.
        let s = unsafe { bzj_curve_new(2, 1, pts.as_ptr(), pts.len(), &mut c) };
        assert_eq!(s, BzjStatus::BZJ_OK);
        c
    }

    #[test]
    fn elevate_to_an_impossible_degree_is_an_error_not_a_panic() {
        let c = line();
        for new_degree in [usize::MAX, usize::MAX / 2, 1usize << 50] {
            let mut out = std::ptr::dangling_mut();
            // SAFETY: live handle, writable out.
            let s = unsafe { bzj_curve_elevate(c, new_degree, &mut out) };
            assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT, "{}", last_error());
            assert!(out.is_null());
            assert!(last_error().contains("new_degree"), "{}", last_error());
        }
        // SAFETY: live handle.
        unsafe { bzj_curve_free(c) };
    }

    #[test]
    fn wrong_points_len_is_rejected_before_reading_points() {
        let pts = [0.0, 0.0, 1.0, 2.0];
        let mut c = std::ptr::dangling_mut();
        // A length that no array can have: must be rejected from the
        // numbers alone, never turned into a slice.
        // SAFETY: the library must not read past the 4 doubles.
        let s = unsafe { bzj_curve_new(2, 1, pts.as_ptr(), usize::MAX, &mut c) };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
        assert!(c.is_null());
        assert!(last_error().contains("points"), "{}", last_error());
        // SAFETY: as above.
        let s = unsafe { bzj_curve_new(2, usize::MAX, pts.as_ptr(), 4, &mut c) };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
        assert!(last_error().contains("degree"), "{}", last_error());
        // A degree above the cap with the length that degree would need:
        // refused by the cap before the 8,194 doubles are read (the copy
        // used to come first and read past the 4 given; user testing,
        // session 39).
        // `points` is a page that may not be read: reading it would kill
        // this test process.
        // SAFETY: an anonymous private mapping of one page, unmapped below.
        let page = unsafe {
            libc::mmap(
                std::ptr::null_mut(),
                4096,
                libc::PROT_NONE,
                libc::MAP_PRIVATE | libc::MAP_ANONYMOUS,
                -1,
                0,
            )
        };
        assert_ne!(page, libc::MAP_FAILED);
        // SAFETY: the library must refuse from the numbers alone.
        let s = unsafe { bzj_curve_new(2, 4097, page.cast(), 2 * 4098, &mut c) };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
        assert!(c.is_null());
        assert!(
            last_error().contains("degree: 4097 is above"),
            "{}",
            last_error()
        );
        // SAFETY: the mapping made above.
        assert_eq!(unsafe { libc::munmap(page, 4096) }, 0);
    }

    #[test]
    fn impossible_out_len_is_rejected_not_sliced() {
        let c = line();
        let mut buf = [0.0f64; 4];
        // out_len larger than any array can be (more than isize::MAX bytes).
        // SAFETY: the library must not write past the 4 doubles.
        let s = unsafe { bzj_curve_eval(c, 0.5, usize::MAX / 16, buf.as_mut_ptr(), usize::MAX) };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT, "{}", last_error());
        assert!(last_error().contains("length of out"), "{}", last_error());
        // SAFETY: as above.
        let s = unsafe { bzj_curve_points(c, buf.as_mut_ptr(), usize::MAX) };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT, "{}", last_error());
        // SAFETY: live handle.
        unsafe { bzj_curve_free(c) };
    }

    #[test]
    fn non_finite_scalar_message_names_the_argument_without_index() {
        let c = line();
        let mut buf = [0.0f64; 2];
        // SAFETY: live handle, 2 writable doubles.
        let s = unsafe { bzj_curve_eval(c, f64::NAN, 0, buf.as_mut_ptr(), 2) };
        assert_eq!(s, BzjStatus::BZJ_ERR_NON_FINITE);
        assert_eq!(last_error(), "t = NaN is not finite");
        // SAFETY: live handle.
        unsafe { bzj_curve_free(c) };
    }

    /// `eval_many` blocks are `bzj_curve_eval`'s bits (Bezier handles of
    /// dimensions 1 to 4, the unrolled and the general paths, and the
    /// same curves as NURBS handles), and a success after a failure
    /// empties the last error, a success after a success keeps it empty.
    #[test]
    fn eval_many_blocks_are_eval_bits_and_success_clears_the_message() {
        use crate::nurbs::bzj_curve_to_nurbs;
        for dim in 1..=4usize {
            for degree in [0usize, 1, 3, 7, 9, 20] {
                let pts: Vec<f64> = (0..(degree + 1) * dim)
                    .map(|i| ((i * 7919) % 97) as f64 / 9.7 - 5.0)
                    .collect();
                let mut bezier = std::ptr::null_mut();
                // SAFETY: valid buffers.
                let s = unsafe { bzj_curve_new(dim, degree, pts.as_ptr(), pts.len(), &mut bezier) };
                assert_eq!(s, BzjStatus::BZJ_OK);
                let mut nurbs = std::ptr::null_mut();
                // SAFETY: live handle, writable out.
                assert_eq!(
                    unsafe { bzj_curve_to_nurbs(bezier, &mut nurbs) },
                    BzjStatus::BZJ_OK
                );
                let ts: Vec<f64> = (0..50).map(|i| i as f64 / 49.0).collect();
                for handle in [bezier, nurbs] {
                    for max_order in [0usize, 2] {
                        let block = (max_order + 1) * dim;
                        let mut many = vec![0.0; ts.len() * block];
                        // SAFETY: live handle, buffers of the lengths given.
                        let s = unsafe {
                            bzj_curve_eval_many(
                                handle,
                                ts.as_ptr(),
                                ts.len(),
                                max_order,
                                many.as_mut_ptr(),
                                many.len(),
                            )
                        };
                        assert_eq!(s, BzjStatus::BZJ_OK, "{}", last_error());
                        for (i, &t) in ts.iter().enumerate() {
                            let mut one = vec![0.0; block];
                            // SAFETY: as above.
                            let s = unsafe {
                                bzj_curve_eval(handle, t, max_order, one.as_mut_ptr(), block)
                            };
                            assert_eq!(s, BzjStatus::BZJ_OK);
                            let got = &many[i * block..(i + 1) * block];
                            assert!(
                                got.iter()
                                    .zip(&one)
                                    .all(|(a, b)| a.to_bits() == b.to_bits()),
                                "dim {dim}, degree {degree}, order {max_order}, t {t}"
                            );
                        }
                    }
                }
                let mut v = vec![0.0; dim];
                // SAFETY: live handle, `dim` writable doubles.
                let s = unsafe { bzj_curve_eval(nurbs, 2.0, 0, v.as_mut_ptr(), dim) };
                assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
                assert!(last_error().contains("t = 2"), "{}", last_error());
                for _ in 0..2 {
                    // SAFETY: as above.
                    let s = unsafe { bzj_curve_eval(nurbs, 0.5, 0, v.as_mut_ptr(), dim) };
                    assert_eq!(s, BzjStatus::BZJ_OK);
                    assert_eq!(last_error(), "");
                }
                // SAFETY: live handles, released once.
                unsafe {
                    bzj_curve_free(bezier);
                    bzj_curve_free(nurbs);
                }
            }
        }
    }

    /// The value of a NURBS handle of dimension 2 or 3 (its own path)
    /// reports errors in the order of every other evaluation: the
    /// parameter (not finite, then outside the domain) before the buffer,
    /// a NULL buffer before its length; a short buffer is not written.
    /// The values are those of the core's checked evaluation, bit for bit.
    #[test]
    fn nurbs_value_errors_come_in_the_general_order() {
        use crate::nurbs::bzj_curve_to_nurbs;
        for dim in [2usize, 3] {
            let pts: Vec<f64> = (0..4 * dim).map(|i| (i * i) as f64 / 7.0 - 1.0).collect();
            let mut bezier = std::ptr::null_mut();
            let mut nurbs = std::ptr::null_mut();
            // SAFETY: valid buffers, writable outs.
            unsafe {
                assert_eq!(
                    bzj_curve_new(dim, 3, pts.as_ptr(), pts.len(), &mut bezier),
                    BzjStatus::BZJ_OK
                );
                assert_eq!(bzj_curve_to_nurbs(bezier, &mut nurbs), BzjStatus::BZJ_OK);
            }
            let mut v = [7.0f64; 3];
            // SAFETY (every call below): a live handle; `out` is NULL or
            // `v`'s 3 writable doubles (a fresh pointer each call), and the
            // library writes no further than that whatever `len` says.
            let eval = |t: f64, out: *mut f64, len: usize| unsafe {
                bzj_curve_eval(nurbs, t, 0, out, len)
            };
            let null = std::ptr::null_mut();
            assert_eq!(
                eval(f64::NAN, v.as_mut_ptr(), 1),
                BzjStatus::BZJ_ERR_NON_FINITE
            );
            assert_eq!(last_error(), "t = NaN is not finite");
            assert_eq!(
                eval(1.5, v.as_mut_ptr(), 1),
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT
            );
            assert!(last_error().contains("t = 1.5"), "{}", last_error());
            assert_eq!(eval(-0.25, null, 0), BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
            assert!(last_error().contains("t = -0.25"), "{}", last_error());
            assert_eq!(eval(0.5, null, 0), BzjStatus::BZJ_ERR_NULL_POINTER);
            assert!(last_error().contains("out"), "{}", last_error());
            assert_eq!(eval(0.5, null, dim), BzjStatus::BZJ_ERR_NULL_POINTER);
            assert_eq!(
                eval(0.5, v.as_mut_ptr(), usize::MAX),
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT
            );
            assert!(last_error().contains("length of out"), "{}", last_error());
            assert_eq!(
                eval(0.5, v.as_mut_ptr(), dim - 1),
                BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL
            );
            assert!(last_error().contains("out"), "{}", last_error());
            assert_eq!(v, [7.0; 3], "a short buffer is not written");
            // SAFETY: a live handle.
            let curve = unsafe { curve_ref(nurbs, "c") }.unwrap();
            let Curve::Nurbs(core) = curve else {
                panic!("a NURBS handle")
            };
            for t in [0.0, 0.3, 0.5, 0.9, 1.0] {
                assert_eq!(eval(t, v.as_mut_ptr(), 3), BzjStatus::BZJ_OK);
                let mut expected = vec![0.0; dim];
                core.eval_derivatives_checked_into(|| "t".into(), t, 0, &mut expected)
                    .unwrap();
                assert!(
                    expected
                        .iter()
                        .zip(&v)
                        .all(|(a, b)| a.to_bits() == b.to_bits()),
                    "dim {dim}, t {t}: {v:?} vs {expected:?}"
                );
            }
            // SAFETY: live handles, released once.
            unsafe {
                bzj_curve_free(bezier);
                bzj_curve_free(nurbs);
            }
        }
    }

    #[test]
    fn free_keeps_the_last_error() {
        let c = line();
        let mut out = std::ptr::null_mut();
        // SAFETY: live handle, writable out.
        let s = unsafe { bzj_curve_split(c, 2.0, &mut out, std::ptr::null_mut()) };
        assert_ne!(s, BzjStatus::BZJ_OK);
        let before = last_error();
        assert!(!before.is_empty());
        // SAFETY: live handle; NULL is accepted.
        unsafe {
            bzj_curve_free(c);
            bzj_curve_free(std::ptr::null_mut());
        }
        assert_eq!(last_error(), before);
    }
}
