//! NURBS curves (mathematics.md, section 6; `bezjoin_core::NurbsCurve`):
//! making them, reading their knots, weights and domain, converting between
//! the two kinds of handle, exact conic arcs.
//!
//! The functions of `curve.rs` take NURBS handles too; the rules are stated
//! there, at each function.

use bezjoin_core::{BezjoinError, Curve, NurbsCurve, ellipse_arc};

use crate::guard::guard;
use crate::handles::{BzjCurve, HandleArray, HandleOut, ShortArray};
use crate::pointers::{curve_ref, input_slice, output_slice, require_out};
use crate::status::{BzjStatus, FfiError, FfiResult};

/// Create a NURBS curve of degree `degree >= 1` in dimension `dim` from
/// `poles_len == pole_count * dim` row-major pole coordinates (Cartesian,
/// not multiplied by the weights), `weights_len == pole_count` weights
/// `> 0` (or `weights_len == 0` for a polynomial B-spline: `weights` is
/// then not read and may be NULL), and the flat knot vector of
/// `knots_len == pole_count + degree + 1` non-decreasing values: interior
/// multiplicity `<= degree`, end multiplicity `<= degree + 1`, a non-empty
/// domain `[knots[degree], knots[pole_count]]`. At least `degree + 1`
/// poles. Weights that are all equal give a curve that is not rational
/// (`bzj_curve_is_rational`). Every length is checked from the numbers
/// before any array is read.
///
/// @return BZJ_ERR_NULL_POINTER if `out`, `poles` or `knots` is NULL, or
///         `weights` is NULL while `weights_len > 0`;
///         BZJ_ERR_INVALID_ARGUMENT if `dim == 0`, `degree == 0` or above the
///         maximum degree 4096, `poles_len` is not a multiple of `dim` or
///         gives fewer than `degree + 1` poles, `weights_len` is neither 0
///         nor the pole count, `knots_len` is not `pole_count + degree + 1`,
///         a length is larger than any array can be, a weight is `<= 0` or
///         below the smallest normal double 2.2e-308 (its reciprocal
///         overflows), or a weight times the largest pole coordinate
///         overflows (named, `weights[i]`), or the knots decrease, have a
///         multiplicity above the limits, an empty domain, an interval too
///         short to invert, or a span (or domain-end sum) that overflows
///         (the message names `knots` and says which);
///         BZJ_ERR_NON_FINITE if a pole coordinate, weight or knot is NaN or
///         infinite (named with its index).
///         On any error `*out` is set to NULL.
///
/// # Safety
/// `poles` points to `poles_len` readable doubles, `weights` to
/// `weights_len`, `knots` to `knots_len`; `out` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_nurbs_new(
    dim: usize,
    degree: usize,
    poles: *const f64,
    poles_len: usize,
    weights: *const f64,
    weights_len: usize,
    knots: *const f64,
    knots_len: usize,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: `out` is null or writable (caller contract).
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        if poles.is_null() {
            return Err(FfiError::NullPointer("poles".into()));
        }
        if knots.is_null() {
            return Err(FfiError::NullPointer("knots".into()));
        }
        if weights_len > 0 && weights.is_null() {
            return Err(FfiError::NullPointer("weights".into()));
        }
        // The lengths from the numbers alone, before touching memory.
        NurbsCurve::check_shape(dim, degree, poles_len, weights_len, knots_len)?;
        // SAFETY: caller promises `poles_len` readable doubles.
        let poles = unsafe { input_slice(poles, poles_len, "poles") }?;
        // SAFETY: caller promises `weights_len` readable doubles (none read when 0).
        let weights = unsafe { input_slice(weights, weights_len, "weights") }?;
        // SAFETY: caller promises `knots_len` readable doubles.
        let knots = unsafe { input_slice(knots, knots_len, "knots") }?;
        let weights = (weights_len > 0).then(|| weights.to_vec());
        out.write(NurbsCurve::new(
            dim,
            degree,
            poles.to_vec(),
            weights,
            knots.to_vec(),
        )?);
        Ok(())
    })
}

/// Write one value through a required out-pointer after reading the curve.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
unsafe fn inspect<T>(
    c: *const BzjCurve,
    out: *mut T,
    value: impl FnOnce(&Curve) -> T,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = require_out(out, "out")?;
        // SAFETY: checked non-null, writable by the caller contract.
        unsafe { out.write(value(curve)) };
        Ok(())
    })
}

/// Whether `c` is a NURBS handle (`false`: a Bezier handle).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_is_nurbs(c: *const BzjCurve, out: *mut bool) -> BzjStatus {
    // SAFETY: forwarded.
    unsafe { inspect(c, out, |curve| matches!(curve, Curve::Nurbs(_))) }
}

/// Whether `c` is rational: a NURBS handle whose weights are not all equal
/// (equal weights cancel). `false` for every Bezier handle.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_is_rational(c: *const BzjCurve, out: *mut bool) -> BzjStatus {
    // SAFETY: forwarded.
    unsafe { inspect(c, out, Curve::is_rational) }
}

/// The number of poles of `c` (`degree + 1` control points for a Bezier
/// handle): `bzj_curve_points` writes `pole_count * dim` doubles,
/// `bzj_curve_weights` `pole_count`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_pole_count(c: *const BzjCurve, out: *mut usize) -> BzjStatus {
    // SAFETY: forwarded.
    unsafe { inspect(c, out, Curve::point_count) }
}

/// The flat knot vector of `c` (`pole_count + degree + 1` values; a Bezier
/// handle: 0 and 1, each `degree + 1` times). The number of knots is
/// written into `count` whenever `c` and `count` are valid, even when the
/// call then fails. `out == NULL` with `out_len == 0` is a size query:
/// only `count` is written, and the call succeeds. Otherwise `out` receives
/// the knots.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `count` is NULL, or `out` is NULL
///         while `out_len > 0`;
///         BZJ_ERR_INVALID_ARGUMENT if `out_len` is larger than any array can be;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len` is below the number of
///         knots (nothing written into `out`; `count` holds the number).
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or points to `out_len`
/// writable doubles; `count` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_knots(
    c: *const BzjCurve,
    out: *mut f64,
    out_len: usize,
    count: *mut usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let count = require_out(count, "count")?;
        let needed = knot_count(curve);
        // SAFETY: checked non-null.
        unsafe { count.write(needed) };
        if out.is_null() && out_len == 0 {
            return Ok(());
        }
        // SAFETY: caller contract.
        let buf = unsafe { output_slice(out, out_len, needed, "out") }?;
        match curve {
            Curve::Bezier(b) => {
                let half = b.degree() + 1;
                buf[..half].fill(0.0);
                buf[half..].fill(1.0);
            }
            Curve::Nurbs(n) => buf.copy_from_slice(n.knots()),
        }
        Ok(())
    })
}

/// `pole_count + degree + 1`.
fn knot_count(curve: &Curve) -> usize {
    match curve {
        Curve::Bezier(b) => 2 * (b.degree() + 1),
        Curve::Nurbs(n) => n.knots().len(),
    }
}

/// The `pole_count` weights of `c` into `out`; all 1 when `c` is not
/// rational (a Bezier handle, a polynomial B-spline, or weights that are
/// all equal, which cancel: the curve is the same).
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `out_len` is larger than any array can be;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len < pole_count` (nothing written).
///
/// # Safety
/// `c` is NULL or a live handle; `out` points to `out_len` writable doubles.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_weights(
    c: *const BzjCurve,
    out: *mut f64,
    out_len: usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        // SAFETY: caller contract.
        let buf = unsafe { output_slice(out, out_len, curve.point_count(), "out") }?;
        match curve {
            Curve::Nurbs(n) if n.is_rational() => {
                for (i, w) in buf.iter_mut().enumerate() {
                    *w = n.weight(i);
                }
            }
            _ => buf.fill(1.0),
        }
        Ok(())
    })
}

/// The parameter domain of `c`: `[0, 1]` for a Bezier handle,
/// `[knots[degree], knots[pole_count]]` for a NURBS handle. Both values
/// are written on success only.
///
/// @return BZJ_ERR_NULL_POINTER if `c`, `first` or `last` is NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `first` and `last` are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_domain(
    c: *const BzjCurve,
    first: *mut f64,
    last: *mut f64,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let first = require_out(first, "first")?;
        let last = require_out(last, "last")?;
        let (a, b) = curve.domain();
        // SAFETY: both checked non-null, writable by the caller contract.
        unsafe {
            first.write(a);
            last.write(b);
        }
        Ok(())
    })
}

/// The same curve as a NURBS handle: a Bezier handle becomes a one-span
/// polynomial NURBS on `[0, 1]` (knots 0 and 1, each `degree + 1` times; a
/// degree-0 curve, a point, is raised to degree 1, as a NURBS curve has
/// degree `>= 1`); a NURBS handle is copied.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `out` is NULL.
///         On any error `*out` is set to NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_to_nurbs(
    c: *const BzjCurve,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let out = out.require()?;
        out.write(curve.to_nurbs());
        Ok(())
    })
}

/// The Bezier spans of `c`, in order, exactly (knot insertion): span `i`
/// covers `[k_i, k_(i+1)]`, the distinct knots of the domain in order.
/// A polynomial span comes back as a Bezier handle (that span
/// reparametrised to `[0, 1]`: `s -> c(k_i + (k_(i+1) - k_i) s)`); a
/// rational span as a one-span NURBS handle keeping the original parameters
/// (its domain is `[k_i, k_(i+1)]`). A Bezier handle gives one span, a copy
/// of itself. The number of spans is written into `count` whenever `c` and
/// `count` are valid, even when the call then fails. `out == NULL` with
/// `capacity == 0` is a size query: only `count` is written, and the call
/// succeeds. Otherwise the first `count` slots of `out` receive new
/// handles, each released with `bzj_curve_free`.
///
/// @return BZJ_ERR_NULL_POINTER if `c` or `count` is NULL, or `out` is NULL
///         while `capacity > 0`;
///         BZJ_ERR_BUFFER_TOO_SMALL if `capacity` is below the number of
///         spans (no handle is written; `count` holds the number).
///         On any error the `capacity` slots of `out` are set to NULL.
///
/// # Safety
/// `c` is NULL or a live handle; `out` is NULL or points to `capacity`
/// writable handle slots; `count` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_curve_bezier_spans(
    c: *const BzjCurve,
    out: *mut *mut BzjCurve,
    capacity: usize,
    count: *mut usize,
) -> BzjStatus {
    // SAFETY: caller promises NULL or `capacity` writable handle slots.
    let slots = unsafe { HandleArray::cleared(out, capacity, "out", ShortArray::Handles) };
    guard(|| {
        // SAFETY: caller contract.
        let curve = unsafe { curve_ref(c, "c") }?;
        let count = require_out(count, "count")?;
        let needed = match curve {
            Curve::Bezier(_) => 1,
            Curve::Nurbs(n) => n.span_count(),
        };
        // SAFETY: checked non-null.
        unsafe { count.write(needed) };
        if slots.is_null() && capacity == 0 {
            return Ok(());
        }
        let slots = slots.require()?;
        slots.check_room(needed)?;
        let spans = spans_of(curve);
        debug_assert_eq!(spans.len(), needed);
        slots.write(spans);
        Ok(())
    })
}

/// The spans as curves of the kind `bzj_curve_bezier_spans` promises.
fn spans_of(curve: &Curve) -> Vec<Curve> {
    match curve {
        Curve::Bezier(b) => vec![Curve::Bezier(b.clone())],
        Curve::Nurbs(n) => n
            .bezier_spans()
            .into_iter()
            .map(|span| match span.to_bezier() {
                Some(bezier) => Curve::Bezier(bezier),
                None => Curve::Nurbs(span),
            })
            .collect(),
    }
}

/// The elliptic arc `centre + x_radius cos(a) x_axis + y_radius sin(a)
/// y_axis`, `a` from `a0` to `a1` (radians), as an exact rational quadratic
/// NURBS handle in dimension 2 or 3 (a circle: `x_radius == y_radius`).
/// `centre`, `x_axis` and `y_axis` hold `dim` doubles each; the axes are
/// unit vectors and orthogonal, within 1e-9. `a0 < a1 <= a0 + 2 pi` (a
/// full turn gives a closed curve). The arc is cut into `ceil((a1 - a0) /
/// (pi/2))` spans of equal angle; the domain is `[a0, a1]` and the knots
/// sit at the spans' angles, where the curve passes through the ellipse
/// point of that angle (between knots the parameter is not the angle).
///
/// @return BZJ_ERR_NULL_POINTER if `centre`, `x_axis`, `y_axis` or `out`
///         is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `dim` is not 2 or 3 (checked before
///         the arrays are read), an axis is not of unit length, the axes are
///         not orthogonal, a radius is not `> 0`, or `a1` is not in
///         `(a0, a0 + 2 pi]`;
///         BZJ_ERR_NON_FINITE if a coordinate, radius or angle is NaN or
///         infinite (named).
///         On any error `*out` is set to NULL.
///
/// # Safety
/// `centre`, `x_axis`, `y_axis` are NULL or point to `dim` readable doubles
/// each; `out` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_nurbs_ellipse_arc(
    dim: usize,
    centre: *const f64,
    x_axis: *const f64,
    y_axis: *const f64,
    x_radius: f64,
    y_radius: f64,
    a0: f64,
    a1: f64,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        // SAFETY: caller contract (each NULL or `dim` readable doubles).
        let (centre, x_axis, y_axis) = unsafe {
            (
                vector_input(centre, dim, "centre")?,
                vector_input(x_axis, dim, "x_axis")?,
                vector_input(y_axis, dim, "y_axis")?,
            )
        };
        if dim != 2 && dim != 3 {
            return Err(BezjoinError::invalid(
                "dim",
                format!("{dim}: conic arcs are built in dimension 2 or 3"),
            )
            .into());
        }
        out.write(ellipse_arc(
            dim, centre, x_axis, y_axis, x_radius, y_radius, a0, a1,
        )?);
        Ok(())
    })
}

/// A required input vector of `dim` doubles, NOT read yet: the pointer is
/// checked here, the slice made only for `dim` 2 or 3 (empty otherwise, for
/// the caller to refuse `dim` before anything is read).
///
/// # Safety
/// `ptr` is NULL or points to `dim` readable doubles.
unsafe fn vector_input<'a>(ptr: *const f64, dim: usize, name: &str) -> FfiResult<&'a [f64]> {
    if ptr.is_null() {
        return Err(FfiError::NullPointer(name.into()));
    }
    if dim != 2 && dim != 3 {
        return Ok(&[]);
    }
    // SAFETY: non-null, `dim` readable doubles by the caller contract.
    unsafe { input_slice(ptr, dim, name) }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{bzj_curve_eval, bzj_curve_free};
    use crate::guard::last_error;

    #[test]
    fn impossible_lengths_are_refused_before_reading() {
        let poles = [0.0, 1.0];
        let knots = [0.0, 0.0, 1.0, 1.0];
        let mut out = std::ptr::dangling_mut();
        // SAFETY: the library must not read past the arrays.
        let s = unsafe {
            bzj_nurbs_new(
                1,
                1,
                poles.as_ptr(),
                usize::MAX,
                std::ptr::null(),
                0,
                knots.as_ptr(),
                4,
                &mut out,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT, "{}", last_error());
        assert!(last_error().starts_with("poles: "), "{}", last_error());
        assert!(out.is_null());
        // SAFETY: as above; knots_len matches the pole count but no array has it.
        let s = unsafe {
            bzj_nurbs_new(
                1,
                1,
                poles.as_ptr(),
                usize::MAX / 4,
                std::ptr::null(),
                0,
                knots.as_ptr(),
                usize::MAX / 4 + 2,
                &mut out,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_ERR_INVALID_ARGUMENT, "{}", last_error());
        assert!(
            last_error().starts_with("poles: ")
                && last_error().contains("more than any array of doubles holds"),
            "{}",
            last_error()
        );
    }

    #[test]
    fn circle_arc_evaluates_on_the_circle() {
        let centre = [1.0, -2.0];
        let (x, y) = ([1.0, 0.0], [0.0, 1.0]);
        let mut c = std::ptr::null_mut();
        // SAFETY: valid arrays of 2 doubles, writable out.
        let s = unsafe {
            bzj_nurbs_ellipse_arc(
                2,
                centre.as_ptr(),
                x.as_ptr(),
                y.as_ptr(),
                3.0,
                3.0,
                0.3,
                5.0,
                &mut c,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_OK, "{}", last_error());
        let mut p = [0.0; 2];
        for i in 0..=50 {
            let t = 0.3 + 4.7 * f64::from(i) / 50.0;
            // SAFETY: live handle, 2 writable doubles.
            let s = unsafe { bzj_curve_eval(c, t, 0, p.as_mut_ptr(), 2) };
            assert_eq!(s, BzjStatus::BZJ_OK, "{}", last_error());
            let r = (p[0] - 1.0).hypot(p[1] + 2.0);
            assert!((r - 3.0).abs() < 1e-14 * 3.0, "r = {r} at {t}");
        }
        let mut spans = [std::ptr::null_mut(); 4];
        let mut count = 0;
        // SAFETY: live handle, 4 writable slots.
        let s = unsafe { bzj_curve_bezier_spans(c, spans.as_mut_ptr(), 2, &mut count) };
        assert_eq!(s, BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL);
        // ceil(4.7 / (pi / 2)) = 3 spans.
        assert_eq!(count, 3);
        assert!(spans.iter().all(|h| h.is_null()));
        // SAFETY: live handles, released once.
        unsafe {
            assert_eq!(
                bzj_curve_bezier_spans(c, spans.as_mut_ptr(), 4, &mut count),
                BzjStatus::BZJ_OK
            );
            assert_eq!(count, 3);
            assert!(spans[..3].iter().all(|h| !h.is_null()));
            assert!(spans[3].is_null());
            for h in spans {
                bzj_curve_free(h);
            }
            bzj_curve_free(c);
        }
    }
}
