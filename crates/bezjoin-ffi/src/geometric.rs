//! Geometric continuity G^k with fair shape parameters (mathematics.md
//! section 7; the contract's section "Geometric continuity").

use bezjoin_core::{
    BezjoinError, FairnessReport, GeometricOptions, MAX_GEOMETRIC_ORDER, connect_geometric,
    fillet_radius,
};

use crate::guard::guard;
use crate::handles::{BzjCurve, HandleOut, require_all};
use crate::pointers::{curve_ref, input_ref, input_slice, output_slice, write_optional};
use crate::status::BzjStatus;

/// Options of [`bzj_connect_geometric`] (layout fixed by the contract).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjGeometricOptions {
    /// G^kp at P(u0).
    pub p_order: usize,
    /// G^kq at Q(v0).
    pub q_order: usize,
    /// `kp` values beta_1..beta_kp, beta_1 > 0; NULL: chosen for fairness.
    pub p_shape: *const f64,
    /// `kq` values, the same at Q; NULL: chosen for fairness.
    pub q_shape: *const f64,
}

/// What a G^k blend's curvature looks like (layout fixed by the contract).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct BzjFairnessReport {
    /// The minimised fairness energy of the blend, `L^3 integral (d kappa /
    /// ds)^2 ds` (L its length: scale-free).
    pub energy: f64,
    /// Smallest curvature over the blend (signed in 2D; 513 samples).
    pub curvature_min: f64,
    /// Largest curvature over the blend.
    pub curvature_max: f64,
    /// Interior local extrema of the curvature along the blend.
    pub curvature_extrema: usize,
}

impl From<FairnessReport> for BzjFairnessReport {
    fn from(r: FairnessReport) -> Self {
        Self {
            energy: r.energy,
            curvature_min: r.curvature_min,
            curvature_max: r.curvature_max,
            curvature_extrema: r.curvature_extrema,
        }
    }
}

/// The Bezier curve `R` connecting `p` at `u0` to `q` at `v0` with
/// geometric continuity G^kp and G^kq: after a regular reparametrisation
/// with shape parameters beta_1 > 0, beta_2, ... per end, C^k (the
/// beta-constraints `R^(j)(0) = sum_i P^(i)(u0) B_(j,i)(beta)`, `B_(j,i)`
/// the partial Bell polynomials; the same at `t = 1` with Q). The degree of
/// `out` is `kp + kq + 1`. With `options->p_shape` / `q_shape` NULL the
/// shape values of that end are chosen by minimising the blend's fairness
/// energy `L^3 integral (d kappa / ds)^2 ds` (deterministic search); they
/// are written to `p_shape_out` (kp doubles) and `q_shape_out` (kq
/// doubles) when those are not NULL, and the blend's energy, curvature
/// range and number of curvature extrema to `report` when it is not NULL.
/// `p`, `q`: Bezier or NURBS handles (P's derivatives from the left of a
/// knot, Q's from the right). Guarantee: the beta-constraints of the
/// returned shape values hold to a relative residual of 1e-8, as for
/// [`crate::bzj_connect`], or the call fails with BZJ_ERR_ILL_CONDITIONED.
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q`, `options` or `out` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if an order is above 6, `u0`/`v0` is
///         outside its curve's domain, or a given beta_1 is not > 0
///         (`options.p_shape[0]` named);
///         BZJ_ERR_NON_FINITE if a parameter or shape value is NaN/infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if `p` and `q` differ in dimension;
///         BZJ_ERR_ILL_CONDITIONED if the result cannot be trusted to 1e-8
///         or no shape values give a blend with defined curvature.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` NULL or readable, its
/// non-NULL shape arrays holding `p_order` / `q_order` doubles; `out` NULL or
/// writable; `p_shape_out`, `q_shape_out` NULL or writable for `p_order` /
/// `q_order` doubles; `report` NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_connect_geometric(
    p: *const BzjCurve,
    u0: f64,
    q: *const BzjCurve,
    v0: f64,
    options: *const BzjGeometricOptions,
    out: *mut *mut BzjCurve,
    p_shape_out: *mut f64,
    q_shape_out: *mut f64,
    report: *mut BzjFairnessReport,
) -> BzjStatus {
    // SAFETY: `out` is null or writable (caller contract).
    let out = unsafe { HandleOut::cleared(out, "out") };
    guard(|| {
        let out = out.require()?;
        // SAFETY: caller contract for every pointer.
        let (p, q, o) = unsafe {
            (
                curve_ref(p, "p")?,
                curve_ref(q, "q")?,
                input_ref(options, "options")?,
            )
        };
        // The orders bound the shape arrays' lengths: checked before reading.
        for (name, order) in [
            ("options.p_order", o.p_order),
            ("options.q_order", o.q_order),
        ] {
            if order > MAX_GEOMETRIC_ORDER {
                return Err(BezjoinError::invalid(
                    name,
                    format!("{order} is above the largest geometric order {MAX_GEOMETRIC_ORDER}"),
                )
                .into());
            }
        }
        let read = |ptr: *const f64,
                    order: usize,
                    name: &str|
         -> crate::status::FfiResult<Option<Vec<f64>>> {
            if ptr.is_null() {
                return Ok(None);
            }
            // SAFETY: caller promises `order` readable doubles.
            Ok(Some(unsafe { input_slice(ptr, order, name) }?.to_vec()))
        };
        let options = GeometricOptions {
            p_order: o.p_order,
            q_order: o.q_order,
            p_shape: read(o.p_shape, o.p_order, "options.p_shape")?,
            q_shape: read(o.q_shape, o.q_order, "options.q_shape")?,
            constraints: Vec::new(),
        };
        let g = connect_geometric(p, u0, q, v0, &options).map_err(|e| match e {
            BezjoinError::InvalidArgument { name, reason }
                if name.starts_with("p_shape") || name.starts_with("q_shape") =>
            {
                BezjoinError::InvalidArgument {
                    name: format!("options.{name}"),
                    reason,
                }
            }
            other => other,
        })?;
        for (ptr, values, name) in [
            (p_shape_out, &g.p_shape, "p_shape_out"),
            (q_shape_out, &g.q_shape, "q_shape_out"),
        ] {
            if !ptr.is_null() && !values.is_empty() {
                // SAFETY: caller promises `order` writable doubles.
                unsafe { output_slice(ptr, values.len(), values.len(), name) }?
                    .copy_from_slice(values);
            }
        }
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, g.report.into()) };
        out.write(g.curve);
        Ok(())
    })
}

/// A G^`order` fillet sized like the G1 arc of radius `radius` in the same
/// corner: at the shared vertex when P's last point is Q's first point
/// (within 1e-9 of the curves' coordinate size), else at the first
/// crossing. The arc's touching points (where the offset curves at
/// distance `radius` on the inner side meet: for lines the tangent length
/// `radius tan(theta/2)`) are where P and Q are cut; `p_trimmed` and
/// `q_trimmed` keep their kinds and parameters; `blend` is the G^order
/// Bezier curve between the cuts with fair shape values (as
/// [`bzj_connect_geometric`] with NULL shapes). `report` (may be NULL)
/// receives the blend's energy, curvature range and number of curvature
/// extrema (one maximum for a corner between lines).
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q` or an output handle pointer is
///         NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `radius` is not > 0, `order` is 0 or
///         above 6, or the arc of that radius does not fit on the curves
///         (`radius` named);
///         BZJ_ERR_NON_FINITE if `radius` is NaN or infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if the dimensions differ;
///         BZJ_ERR_NO_INTERSECTION if there is no corner (no shared vertex and
///         no crossing, or parallel tangents there);
///         BZJ_ERR_ILL_CONDITIONED if the touching points or the blend cannot
///         be trusted.
///
/// # Safety
/// `p`, `q` are NULL or live handles; the three handle pointers are NULL or
/// writable; `report` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_radius(
    p: *const BzjCurve,
    q: *const BzjCurve,
    radius: f64,
    order: usize,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    report: *mut BzjFairnessReport,
) -> BzjStatus {
    // SAFETY: each is null or writable (caller contract).
    let outs = unsafe {
        [
            HandleOut::cleared(p_trimmed, "p_trimmed"),
            HandleOut::cleared(blend, "blend"),
            HandleOut::cleared(q_trimmed, "q_trimmed"),
        ]
    };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let [p_out, blend_out, q_out] = require_all(outs)?;
        let f = fillet_radius(p, q, radius, order)?;
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, f.report.into()) };
        p_out.write(f.p_trimmed);
        blend_out.write(f.blend);
        q_out.write(f.q_trimmed);
        Ok(())
    })
}
