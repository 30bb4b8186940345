//! Connect two curves with C^k continuity and interior constraints
//! (mathematics.md, section 1; `bezjoin_core::connect`).

use bezjoin_core::{BezjoinError, Curve};
use bezjoin_core::{
    ConnectOptions, PointConstraint, ShapeScale, check_connect_degree, connect, connect_curve,
};

use crate::guard::guard;
use crate::handles::{BzjCurve, HandleOut};
use crate::pointers::{curve_ref, input_ref, input_slice, write_scales};
use crate::status::{BzjStatus, FfiError, FfiResult};

/// An interior constraint: `R^(k)(t) = values[k*dim .. (k+1)*dim]`, `k = 0..=max_order`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjPointConstraint {
    /// Parameter on the connecting curve, in (0,1).
    pub t: f64,
    /// K: derivatives 0..K are prescribed.
    pub max_order: usize,
    /// (K+1)*dim doubles, row k = R^(k)(t).
    pub values: *const f64,
}

/// Options of [`bzj_connect`] (layout fixed by the contract).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjConnectOptions {
    /// kp: derivatives 0..kp of P are matched (any order; above P's degree
    /// they are those of P's polynomial or rational form).
    pub p_order: usize,
    /// kq: derivatives 0..kq of Q are matched (any order).
    pub q_order: usize,
    /// alpha > 0; 1.0 = the paper.
    pub p_scale: f64,
    /// beta > 0; 1.0 = the paper.
    pub q_scale: f64,
    /// May be NULL if constraint_count = 0.
    pub constraints: *const BzjPointConstraint,
    /// Number of entries in `constraints`.
    pub constraint_count: usize,
}

/// Read the C options into the core's options; `dim` is the dimension of P
/// (the length of each derivative row).
///
/// # Safety
/// `options` is valid for reads, its arrays as the contract describes.
unsafe fn read_options(options: &BzjConnectOptions, dim: usize) -> FfiResult<ConnectOptions> {
    let mut out = ConnectOptions::new(options.p_order, options.q_order)
        .with_scales(options.p_scale, options.q_scale);
    if options.constraint_count == 0 {
        check_connect_degree(options.p_order, options.q_order, [])?;
    } else {
        // SAFETY: as this function's.
        out.constraints = unsafe { read_constraints(options, dim) }?;
    }
    Ok(out)
}

/// The interior constraints of [`read_options`] (`constraint_count > 0`),
/// the degree checked before any values array is read.
///
/// # Safety
/// As [`read_options`].
#[cold]
unsafe fn read_constraints(
    options: &BzjConnectOptions,
    dim: usize,
) -> FfiResult<Vec<PointConstraint>> {
    // SAFETY: caller promises `constraint_count` readable constraints.
    let constraints = unsafe {
        input_slice(
            options.constraints,
            options.constraint_count,
            "options.constraints",
        )
    }?;
    // Refuse an impossible degree before reading any values array.
    check_connect_degree(
        options.p_order,
        options.q_order,
        constraints.iter().map(|c| c.max_order),
    )?;
    let mut out = Vec::with_capacity(constraints.len());
    for (j, c) in constraints.iter().enumerate() {
        let rows = c.max_order + 1;
        let name = format!("options.constraints[{j}].values");
        // Bounded by MAX_CONNECT_DEGREE above, so no overflow.
        let len = rows * dim;
        if c.values.is_null() {
            return Err(FfiError::NullPointer(name));
        }
        // SAFETY: caller promises (max_order + 1) * dim readable doubles.
        let values = unsafe { input_slice(c.values, len, &name) }?;
        out.push(PointConstraint::new(c.t, c.max_order, values.to_vec()));
    }
    Ok(out)
}

/// The Bezier curve `R` connecting `p` at `u0` to `q` at `v0` with
/// `R^(k)(0) = alpha^k P^(k)(u0)` (k = 0..kp), `R^(k)(1) = beta^k Q^(k)(v0)`
/// (k = 0..kq) and the interior constraints `R^(k)(t_j) = values_j[k]`
/// (Krivosheev, Mavrin, Starkova 2025, Theorems 1 and 2). The degree of
/// `out` is `kp + kq + 1 + sum(K_j + 1)`. Guarantee: every condition holds
/// to a relative residual of 1e-8 (definition in the Rust documentation of
/// `bezjoin_core::connect`), or the call fails with BZJ_ERR_ILL_CONDITIONED.
///
/// `p` and `q` may each be a Bezier or a NURBS handle: `u0` lies in P's
/// domain and `v0` in Q's (`[0, 1]` for a Bezier, `bzj_curve_domain`); the
/// orders `kp`, `kq` may exceed the degrees (a polynomial's higher
/// derivatives are 0, a rational curve's are not). At a knot of a NURBS
/// curve P's derivatives are taken from the left of `u0` (the side P
/// arrives from) and Q's from the right of `v0` (the side Q leaves to). The
/// result is always a Bezier handle.
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q`, `options`, `out`, a
///         non-empty `options->constraints` or a constraint's `values` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `u0` is outside P's domain or `v0`
///         outside Q's, a scale is not > 0, a constraint's `t` is outside
///         (0,1) or repeated;
///         BZJ_ERR_NON_FINITE if `u0`, `v0`, a scale, a `t` or a value is NaN or infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if `p` and `q` have different dimensions;
///         BZJ_ERR_SINGULAR if the interior system is numerically singular;
///         BZJ_ERR_ILL_CONDITIONED if the result cannot be trusted to 1e-8
///         (the message carries the finite estimate, "estimated relative
///         error E exceeds the promised 1e-8") or its degree is above 31
///         (refused before solving: the message names the degree and the
///         estimate is inf, as no answer exists to check).
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable, with
/// `constraint_count` readable constraints each holding
/// `(max_order + 1) * dim` readable doubles; `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_connect(
    p: *const BzjCurve,
    u0: f64,
    q: *const BzjCurve,
    v0: f64,
    options: *const BzjConnectOptions,
    out: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: `out` is null or writable (caller contract).
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        // SAFETY: caller contract for every pointer.
        let (p, q, options) = unsafe { read_inputs(p, q, options) }?;
        out.write(connect_curve(p, u0, q, v0, &options)?);
        Ok(())
    })
}

/// [`bzj_connect`] with `alpha = beta = s` chosen automatically to minimise
/// the fairness energy `integral_0^1 |R''(t)|^2 dt` (exact, Bernstein Gram
/// matrix) by a bounded search over two decades either side of
/// `s0 = |Q(v0) - P(u0)| / mean(|P'(u0)|, |Q'(v0)|)` (each speed raised to
/// its floor where the end turns within 1 % of the chord,
/// docs/mathematics.md); `options->p_scale` and `options->q_scale` are
/// ignored. The chosen `s` is written to `scale_out`
/// when it is not NULL. Same guarantee as [`bzj_connect`].
///
/// @return the statuses of [`bzj_connect`] (except for the scales, which are
///         not read); BZJ_ERR_INVALID_ARGUMENT naming `v0` when `Q(v0)` is
///         within 1e-9 of the ends' largest coordinate from `P(u0)` and an
///         order is at least 1 (the scale is sized by that gap; between
///         coincident points every blend is a loop).
///
/// # Safety
/// As [`bzj_connect`]; `scale_out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_connect_auto_scale(
    p: *const BzjCurve,
    u0: f64,
    q: *const BzjCurve,
    v0: f64,
    options: *const BzjConnectOptions,
    out: *mut *mut BzjCurve,
    scale_out: *mut f64,
) -> BzjStatus {
    let scales = [scale_out, std::ptr::null_mut()];
    // SAFETY: caller contract.
    unsafe { connect_chosen_scale(p, u0, q, v0, options, out, ShapeScale::Auto, scales) }
}

/// [`bzj_connect`] with the blend leaving both curves at one speed `sigma`:
/// `alpha = sigma / |P'(u0)|`, `beta = sigma / |Q'(v0)|`, `sigma` chosen as
/// [`bzj_connect_auto_scale`] chooses `s` (least fairness energy
/// `integral_0^1 |R''(t)|^2 dt` over two decades either side of the chord
/// `|Q(v0) - P(u0)|`). `alpha^k P^(k)(u0)` is the jet of P reparametrised to
/// unit speed at `u0`, so the result does not depend on how fast either
/// curve runs in its own parameter: a line given on `[0, 1]` or on
/// `[0, length]` gives the same blend (with [`bzj_connect_auto_scale`]'s
/// one `s` it does not, and a fast curve next to a slow one gets a
/// near-kink at the slow end). An end that turns or accelerates on a scale
/// below 1 % of the chord is balanced at a higher speed than its `|P'|`
/// (`BALANCED_SPEED_FLOOR`, docs/mathematics.md), which keeps the blend in
/// size where an end is nearly stationary. Where the two speeds agree to
/// 1e-9, or an end has none (order 0, or derivatives that all vanish), the
/// answer is [`bzj_connect_auto_scale`]'s, the same bits. `options->p_scale` and
/// `options->q_scale` are ignored; `alpha` and `beta` are written to
/// `p_scale_out`, `q_scale_out` when not NULL. Same guarantee as
/// [`bzj_connect`].
///
/// @return the statuses of [`bzj_connect`] (except for the scales, which are
///         not read); BZJ_ERR_INVALID_ARGUMENT naming `v0` when `Q(v0)` is
///         within 1e-9 of the ends' largest coordinate from `P(u0)` and an
///         order is at least 1 (the scale is sized by that gap; between
///         coincident points every blend is a loop).
///
/// # Safety
/// As [`bzj_connect`]; `p_scale_out`, `q_scale_out` are NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_connect_balanced_scale(
    p: *const BzjCurve,
    u0: f64,
    q: *const BzjCurve,
    v0: f64,
    options: *const BzjConnectOptions,
    out: *mut *mut BzjCurve,
    p_scale_out: *mut f64,
    q_scale_out: *mut f64,
) -> BzjStatus {
    let scales = [p_scale_out, q_scale_out];
    let balanced = ShapeScale::Balanced;
    // SAFETY: caller contract.
    unsafe { connect_chosen_scale(p, u0, q, v0, options, out, balanced, scales) }
}

/// The body of [`bzj_connect_auto_scale`] and [`bzj_connect_balanced_scale`]:
/// [`bzj_connect`] with the scale `scale` chosen by the library, `alpha` and
/// `beta` written to `scales_out[0]`, `scales_out[1]` where not NULL.
///
/// # Safety
/// As [`bzj_connect`]; each of `scales_out` is NULL or writable.
#[allow(clippy::too_many_arguments)]
unsafe fn connect_chosen_scale(
    p: *const BzjCurve,
    u0: f64,
    q: *const BzjCurve,
    v0: f64,
    options: *const BzjConnectOptions,
    out: *mut *mut BzjCurve,
    scale: ShapeScale,
    scales_out: [*mut f64; 2],
) -> BzjStatus {
    // SAFETY: `out` is null or writable (caller contract).
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        // SAFETY: caller contract for every pointer.
        let (p, q, mut options) = unsafe { read_inputs(p, q, options) }?;
        options.scale = scale;
        let connection = connect(p, u0, q, v0, &options)?;
        let scales = (connection.p_scale, connection.q_scale);
        // SAFETY: NULL or writable by the caller contract.
        unsafe { write_scales(scales_out, scales) };
        out.write(connection.curve);
        Ok(())
    })
}

/// The two curves and the options, with the dimension checked before any
/// constraint values are read.
///
/// # Safety
/// As [`bzj_connect`].
unsafe fn read_inputs<'a>(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjConnectOptions,
) -> FfiResult<(&'a Curve, &'a Curve, ConnectOptions)> {
    // SAFETY: caller contract.
    let p = unsafe { curve_ref(p, "p") }?;
    // SAFETY: caller contract.
    let q = unsafe { curve_ref(q, "q") }?;
    // SAFETY: caller contract.
    let options = unsafe { input_ref(options, "options") }?;
    if p.dim() != q.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        }
        .into());
    }
    // SAFETY: caller contract.
    let options = unsafe { read_options(options, p.dim()) }?;
    Ok((p, q, options))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::{bzj_curve_eval, bzj_curve_free, bzj_curve_new};

    fn make(dim: usize, points: &[f64]) -> *mut BzjCurve {
        let mut c = std::ptr::null_mut();
        let degree = points.len() / dim - 1;
        let s = unsafe { bzj_curve_new(dim, degree, points.as_ptr(), points.len(), &mut c) };
        assert_eq!(s, BzjStatus::BZJ_OK);
        c
    }

    fn eval(c: *const BzjCurve, t: f64, order: usize, dim: usize) -> Vec<f64> {
        let mut out = vec![0.0; (order + 1) * dim];
        let s = unsafe { bzj_curve_eval(c, t, order, out.as_mut_ptr(), out.len()) };
        assert_eq!(s, BzjStatus::BZJ_OK);
        out
    }

    #[test]
    fn connects_with_a_constraint_and_reports_errors() {
        let p = make(2, &[0.0, 0.0, 1.0, 2.0, 2.0, 2.0, 3.0, 0.0]);
        let q = make(2, &[6.0, 0.0, 7.0, -2.0, 8.0, -2.0, 9.0, 0.0]);
        let values = [4.5, 0.5, 3.0, 0.0];
        let constraint = BzjPointConstraint {
            t: 0.5,
            max_order: 1,
            values: values.as_ptr(),
        };
        let options = BzjConnectOptions {
            p_order: 2,
            q_order: 3,
            p_scale: 1.5,
            q_scale: 0.5,
            constraints: &constraint,
            constraint_count: 1,
        };
        let mut r = std::ptr::null_mut();
        let s = unsafe { bzj_connect(p, 0.7, q, 0.2, &options, &mut r) };
        assert_eq!(s, BzjStatus::BZJ_OK);
        let mut degree = 0;
        unsafe { crate::curve::bzj_curve_degree(r, &mut degree) };
        assert_eq!(degree, 2 + 3 + 1 + 2);
        let rp = eval(r, 0.0, 2, 2);
        let pp = eval(p, 0.7, 2, 2);
        for k in 0..=2 {
            for c in 0..2 {
                let want = pp[k * 2 + c] * 1.5f64.powi(k as i32);
                assert!((rp[k * 2 + c] - want).abs() < 1e-9 * (1.0 + want.abs()));
            }
        }
        let rt = eval(r, 0.5, 1, 2);
        for i in 0..4 {
            assert!((rt[i] - values[i]).abs() < 1e-9);
        }
        // Errors.
        let mut bad = std::ptr::null_mut();
        assert_eq!(
            unsafe { bzj_connect(p, 1.5, q, 0.2, &options, &mut bad) },
            BzjStatus::BZJ_ERR_INVALID_ARGUMENT
        );
        assert!(bad.is_null());
        assert_eq!(
            unsafe { bzj_connect(std::ptr::null(), 0.5, q, 0.2, &options, &mut bad) },
            BzjStatus::BZJ_ERR_NULL_POINTER
        );
        let null_values = BzjPointConstraint {
            values: std::ptr::null(),
            ..constraint
        };
        let o = BzjConnectOptions {
            constraints: &null_values,
            ..options
        };
        assert_eq!(
            unsafe { bzj_connect(p, 0.5, q, 0.2, &o, &mut bad) },
            BzjStatus::BZJ_ERR_NULL_POINTER
        );
        let huge = BzjPointConstraint {
            max_order: usize::MAX,
            ..constraint
        };
        let o = BzjConnectOptions {
            constraints: &huge,
            ..options
        };
        assert_eq!(
            unsafe { bzj_connect(p, 0.5, q, 0.2, &o, &mut bad) },
            BzjStatus::BZJ_ERR_ILL_CONDITIONED
        );
        // `r` still holds the first result: release it before reusing `r`.
        unsafe { bzj_curve_free(r) };
        r = std::ptr::null_mut();
        let mut scale = 0.0;
        assert_eq!(
            unsafe { bzj_connect_auto_scale(p, 1.0, q, 0.0, &options, &mut r, &mut scale) },
            BzjStatus::BZJ_OK
        );
        assert!(scale > 0.0);
        assert!(!r.is_null());
        unsafe {
            bzj_curve_free(r);
            bzj_curve_free(p);
            bzj_curve_free(q);
        }
    }
}
