//! [`bzj_connect`] and [`bzj_connect_auto_scale`] of two Bezier curves given
//! by their control points, the connecting curve's control points written to
//! a caller buffer: one call, no handles (issue 19: a blend from a binding
//! such as Python's ctypes costs a few calls across the ABI instead of nine).
//! The curves, the solve and its checks are exactly those of `bzj_curve_new`
//! followed by `bzj_connect` (`bzj_connect_auto_scale`) and
//! `bzj_curve_points`, so the control points are the same, bit for bit.

use bezjoin_core::{
    BezierCurve, BezjoinError, ConnectOptions, ShapeScale, check_connect_degree, connect,
    connect_curve,
};

use crate::guard::guard;
use crate::pointers::{input_slice, output_slice, write_optional};
use crate::status::{BzjStatus, FfiError, FfiResult};
// The entry points these docs link to (rustdoc only; the header's text is unchanged).
#[cfg(doc)]
use crate::connect::{bzj_connect, bzj_connect_auto_scale};

/// The Bezier curve of dimension `dim` whose control points are the `len`
/// doubles at `points` (row-major, `len / dim` points); errors name the
/// arguments `{side}_points` and `{side}_len`.
///
/// # Safety
/// `points` is NULL or points to `len` readable doubles.
unsafe fn bezier_from_points(
    dim: usize,
    points: *const f64,
    len: usize,
    side: &str,
) -> FfiResult<BezierCurve> {
    let name = format!("{side}_points");
    if points.is_null() {
        return Err(FfiError::NullPointer(name));
    }
    if len == 0 || len % dim != 0 {
        return Err(BezjoinError::invalid(
            format!("{side}_len"),
            format!("{len} is not a positive multiple of dim = {dim}"),
        )
        .into());
    }
    // SAFETY: caller promises `len` readable doubles.
    let values = unsafe { input_slice(points, len, &name) }?;
    BezierCurve::new(dim, len / dim - 1, values.to_vec()).map_err(|error| match error {
        // The core names its array "points": say which of the two it is.
        BezjoinError::NonFinite { index, value, .. } => {
            BezjoinError::NonFinite { name, index, value }.into()
        }
        other => other.into(),
    })
}

/// The common part of the two entry points: sizes checked in the order the
/// documentation lists (dimension, degree, output room, inputs), then the
/// connection, its control points written to `out_points`. Returns the scale
/// used (`alpha = beta` for the automatic scale).
///
/// # Safety
/// As [`bzj_connect_points`].
#[allow(clippy::too_many_arguments)]
unsafe fn connect_points(
    dim: usize,
    p_points: *const f64,
    p_len: usize,
    u0: f64,
    q_points: *const f64,
    q_len: usize,
    v0: f64,
    options: ConnectOptions,
    out_points: *mut f64,
    out_len: usize,
) -> FfiResult<f64> {
    if dim == 0 {
        return Err(BezjoinError::invalid("dim", "must be at least 1").into());
    }
    let degree = check_connect_degree(options.p_order, options.q_order, [])?;
    // degree <= 31, so no overflow for any representable output length.
    let needed = (degree + 1)
        .checked_mul(dim)
        .ok_or_else(|| BezjoinError::invalid("dim", format!("{dim} is too large")))?;
    // SAFETY: caller promises `out_len` writable doubles.
    let out = unsafe { output_slice(out_points, out_len, needed, "out_points") }?;
    // SAFETY: caller contract for both arrays.
    let p = unsafe { bezier_from_points(dim, p_points, p_len, "p") }?;
    // SAFETY: as above.
    let q = unsafe { bezier_from_points(dim, q_points, q_len, "q") }?;
    if let ShapeScale::Given { p: p_scale, .. } = options.scale {
        // bzj_connect's path (the curve alone, the same points).
        out.copy_from_slice(connect_curve(&p, u0, &q, v0, &options)?.points());
        return Ok(p_scale);
    }
    let connection = connect(&p, u0, &q, v0, &options)?;
    out.copy_from_slice(connection.curve.points());
    Ok(connection.p_scale)
}

/// [`bzj_connect`] of the Bezier curves `P` and `Q` given by their control
/// points, without handles: `R` from `P(u0)` to `Q(v0)` with
/// `R^(k)(0) = p_scale^k P^(k)(u0)` (k = 0..p_order) and
/// `R^(k)(1) = q_scale^k Q^(k)(v0)` (k = 0..q_order), of degree
/// `p_order + q_order + 1`; its `(p_order + q_order + 2) * dim` control
/// points (row-major) are written to `out_points`. `P` has the
/// `p_len / dim` control points `p_points` (degree `p_len / dim - 1`), `Q`
/// likewise. The result is the one of `bzj_curve_new` for both curves,
/// `bzj_connect` with these orders and scales and no interior constraints,
/// and `bzj_curve_points`, bit for bit, with the same guarantee (every
/// condition to a relative residual of 1e-8, or BZJ_ERR_ILL_CONDITIONED).
///
/// @return BZJ_ERR_NULL_POINTER if `p_points`, `q_points` or `out_points`
///         is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `dim` is 0, `p_len` or `q_len` is not a
///         positive multiple of `dim`, `u0` or `v0` is outside [0, 1], a
///         scale is not > 0;
///         BZJ_ERR_BUFFER_TOO_SMALL if `out_len < (p_order + q_order + 2) * dim`;
///         BZJ_ERR_NON_FINITE if a coordinate, `u0`, `v0` or a scale is NaN
///         or infinite;
///         BZJ_ERR_ILL_CONDITIONED as `bzj_connect` (the degree
///         `p_order + q_order + 1` above 31 is refused before anything is read).
///         On an error `out_points` is left unchanged.
///
/// # Safety
/// `p_points` is NULL or points to `p_len` readable doubles, `q_points` to
/// `q_len`; `out_points` is NULL or points to `out_len` writable doubles.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_connect_points(
    dim: usize,
    p_points: *const f64,
    p_len: usize,
    u0: f64,
    q_points: *const f64,
    q_len: usize,
    v0: f64,
    p_order: usize,
    q_order: usize,
    p_scale: f64,
    q_scale: f64,
    out_points: *mut f64,
    out_len: usize,
) -> BzjStatus {
    guard(|| {
        let options = ConnectOptions::new(p_order, q_order).with_scales(p_scale, q_scale);
        // SAFETY: caller contract for every pointer.
        unsafe {
            connect_points(
                dim, p_points, p_len, u0, q_points, q_len, v0, options, out_points, out_len,
            )
        }?;
        Ok(())
    })
}

/// [`bzj_connect_points`] with `p_scale = q_scale = s` chosen as
/// [`bzj_connect_auto_scale`] chooses it (least fairness energy
/// `integral_0^1 |R''(t)|^2 dt`); `s` is written to `scale_out` when it is
/// not NULL. The control points are those of `bzj_connect_auto_scale` on
/// the same curves, bit for bit.
///
/// @return the statuses of [`bzj_connect_points`] (no scale is read);
///         `scale_out` is left unchanged on an error.
///
/// # Safety
/// As [`bzj_connect_points`]; `scale_out` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_connect_points_auto_scale(
    dim: usize,
    p_points: *const f64,
    p_len: usize,
    u0: f64,
    q_points: *const f64,
    q_len: usize,
    v0: f64,
    p_order: usize,
    q_order: usize,
    out_points: *mut f64,
    out_len: usize,
    scale_out: *mut f64,
) -> BzjStatus {
    guard(|| {
        let options = ConnectOptions::new(p_order, q_order).with_auto_scale();
        // SAFETY: caller contract for every pointer.
        let scale = unsafe {
            connect_points(
                dim, p_points, p_len, u0, q_points, q_len, v0, options, out_points, out_len,
            )
        }?;
        // SAFETY: NULL or writable by the caller contract.
        unsafe { write_optional(scale_out, scale) };
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::connect::{BzjConnectOptions, bzj_connect, bzj_connect_auto_scale};
    use crate::curve::{bzj_curve_free, bzj_curve_new, bzj_curve_points};
    use crate::handles::BzjCurve;

    const P: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 1.0, 0.2, 2.0, 1.0, 0.1, 3.0, 0.0, 0.0];
    const Q: [f64; 9] = [4.0, 0.5, 0.0, 5.0, 0.0, 0.3, 7.0, 0.0, 0.0];

    fn handle(points: &[f64]) -> *mut BzjCurve {
        let mut c = std::ptr::null_mut();
        // SAFETY: a valid array and out-pointer.
        let s = unsafe {
            bzj_curve_new(
                3,
                points.len() / 3 - 1,
                points.as_ptr(),
                points.len(),
                &mut c,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_OK);
        c
    }

    /// The points of `bzj_connect` (`auto`: `bzj_connect_auto_scale`) on handles.
    fn through_handles(auto: bool, scales: (f64, f64)) -> (Vec<f64>, f64) {
        let (p, q) = (handle(&P), handle(&Q));
        let options = BzjConnectOptions {
            p_order: 3,
            q_order: 2,
            p_scale: scales.0,
            q_scale: scales.1,
            constraints: std::ptr::null(),
            constraint_count: 0,
        };
        let mut r = std::ptr::null_mut();
        let mut scale = f64::NAN;
        // SAFETY: live handles, valid options and out-pointers.
        let s = unsafe {
            if auto {
                bzj_connect_auto_scale(p, 0.9, q, 0.1, &options, &mut r, &mut scale)
            } else {
                bzj_connect(p, 0.9, q, 0.1, &options, &mut r)
            }
        };
        assert_eq!(s, BzjStatus::BZJ_OK);
        let mut points = vec![0.0; 7 * 3];
        // SAFETY: a live handle and a buffer of its size.
        assert_eq!(
            unsafe { bzj_curve_points(r, points.as_mut_ptr(), points.len()) },
            BzjStatus::BZJ_OK
        );
        // SAFETY: live handles, released once.
        unsafe {
            bzj_curve_free(p);
            bzj_curve_free(q);
            bzj_curve_free(r);
        }
        (points, scale)
    }

    #[test]
    fn the_same_points_as_the_handles_bit_for_bit() {
        let mut out = vec![f64::NAN; 7 * 3];
        // SAFETY: valid arrays.
        let s = unsafe {
            bzj_connect_points(
                3,
                P.as_ptr(),
                12,
                0.9,
                Q.as_ptr(),
                9,
                0.1,
                3,
                2,
                0.8,
                1.3,
                out.as_mut_ptr(),
                out.len(),
            )
        };
        assert_eq!(s, BzjStatus::BZJ_OK);
        assert_eq!(out, through_handles(false, (0.8, 1.3)).0);
        let mut scale = f64::NAN;
        // SAFETY: valid arrays.
        let s = unsafe {
            bzj_connect_points_auto_scale(
                3,
                P.as_ptr(),
                12,
                0.9,
                Q.as_ptr(),
                9,
                0.1,
                3,
                2,
                out.as_mut_ptr(),
                out.len(),
                &mut scale,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_OK);
        let (want, want_scale) = through_handles(true, (1.0, 1.0));
        assert_eq!(out, want);
        assert_eq!(scale.to_bits(), want_scale.to_bits());
    }

    #[test]
    fn errors_name_the_argument_and_leave_the_output_alone() {
        let mut out = [7.0; 21];
        let null = std::ptr::null();
        let p = P.as_ptr();
        let q = Q.as_ptr();
        #[allow(clippy::type_complexity)]
        let cases: [(
            usize,
            *const f64,
            usize,
            f64,
            usize,
            usize,
            f64,
            BzjStatus,
            &str,
        ); 8] = [
            (
                0,
                p,
                12,
                0.9,
                3,
                21,
                1.0,
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
                "dim",
            ),
            (
                3,
                null,
                12,
                0.9,
                3,
                21,
                1.0,
                BzjStatus::BZJ_ERR_NULL_POINTER,
                "p_points",
            ),
            (
                3,
                p,
                11,
                0.9,
                3,
                21,
                1.0,
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
                "p_len",
            ),
            (
                3,
                p,
                0,
                0.9,
                3,
                21,
                1.0,
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
                "p_len",
            ),
            (
                3,
                p,
                12,
                0.9,
                3,
                20,
                1.0,
                BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL,
                "out_points",
            ),
            (
                3,
                p,
                12,
                1.5,
                3,
                21,
                1.0,
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
                "u0",
            ),
            (
                3,
                p,
                12,
                0.9,
                3,
                21,
                0.0,
                BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
                "scale",
            ),
            (
                3,
                p,
                12,
                0.9,
                30,
                21,
                1.0,
                BzjStatus::BZJ_ERR_ILL_CONDITIONED,
                "degree",
            ),
        ];
        for (dim, p_points, p_len, u0, p_order, out_len, scale, want, name) in cases {
            // SAFETY: the arrays hold at least the lengths given.
            let s = unsafe {
                bzj_connect_points(
                    dim,
                    p_points,
                    p_len,
                    u0,
                    q,
                    9,
                    0.1,
                    p_order,
                    2,
                    scale,
                    scale,
                    out.as_mut_ptr(),
                    out_len,
                )
            };
            let message = crate::guard::last_error();
            assert_eq!(s, want, "{name}: {message}");
            assert!(message.contains(name), "{name}: {message}");
            assert!(out.iter().all(|&x| x == 7.0));
        }
    }
}
