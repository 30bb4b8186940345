//! Geometric continuity G^k with fair shape parameters (mathematics.md
//! section 7; the contract's section "Geometric continuity").

use bezjoin_core::{
    BezjoinError, FairnessReport, GeometricOptions, MAX_GEOMETRIC_ORDER, RadiusFillet,
    connect_geometric_curve, fairness_report, fillet_radius, fillet_radius_chain,
};

use crate::fillet::{ChainCall, chain_call, chain_pieces_out, fillet_outputs};
use crate::guard::guard;
use crate::handles::{BzjCurve, CheckedOut, HandleOut, require_all};
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
/// energy `L^3 integral (d kappa / ds)^2 ds` among blends at most 10 times
/// the chord `|q(v0) - p(u0)|` long (deterministic search: where the ends
/// face away from each other every blend loops, and the energy would grow
/// the loop without end); they
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
///         outside its curve's domain, a given beta_1 is not > 0
///         (`options.p_shape[0]` named), or shape values are to be chosen
///         for fairness while `q(v0)` is within 1e-9 of the coordinate scale
///         of `p(u0)` (`v0` named: a blend between coincident points is a
///         loop, which has no fairest size; give both shapes);
///         BZJ_ERR_NON_FINITE if a parameter or shape value is NaN/infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if `p` and `q` differ in dimension;
///         BZJ_ERR_ILL_CONDITIONED if the result cannot be trusted to 1e-8
///         or no shape values give a blend with defined curvature and at
///         most 10 chords long (so
///         always when `p`'s tangent at `u0` or `q`'s at `v0` is zero at an
///         end of order >= 1: G^k needs a regular point; the message names
///         the curve and the parameter), or if an end's tangent and
///         curvature are not known to 1e-6 of themselves (an end within a
///         few thousand roundings of stationary, next to a cusp, or whose
///         blend's stored poles cannot hold its curvature; the
///         message names the end and gives the estimate; docs/mathematics.md,
///         "Numerically stationary ends").
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
        // The fairness report costs far more than a solve with given
        // shapes: formed only when asked for.
        let g = connect_geometric_curve(p, u0, q, v0, &options).map_err(|e| match e {
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
        if !report.is_null() {
            // SAFETY: writable (caller contract).
            unsafe { write_optional(report, fairness_report(&g.curve).into()) };
        }
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
///         BZJ_ERR_INVALID_ARGUMENT if `radius` is not > 0 or at most 1e-9 of
///         the curves' coordinate size, `order` is 0 or above 6, or the arc
///         of that radius does not fit on the curves (`radius` named), or
///         its touching point leaves at most 1e-9 of P's or Q's length (`p`
///         or `q` named);
///         BZJ_ERR_NON_FINITE if `radius` is NaN or infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if the dimensions differ;
///         BZJ_ERR_NO_INTERSECTION if there is no corner (no shared vertex and
///         no crossing, or parallel tangents there);
///         BZJ_ERR_ILL_CONDITIONED if the touching points or the blend cannot
///         be trusted, or the blend is not sized like the arc: it strays more
///         than `radius` from it, or its curvature exceeds 4 times the larger
///         of `1/radius` and its end curvatures (a second crossing near the
///         corner, or a turn of more than 180 degrees).
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
    let write_report = |f: &RadiusFillet| {
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, f.report.into()) };
        Ok(())
    };
    // SAFETY: caller contract.
    unsafe {
        fillet_radius_with(
            p,
            q,
            radius,
            order,
            [p_trimmed, blend, q_trimmed],
            write_report,
        )
    }
}

/// What a fillet by radius reports besides its pieces (a new struct of
/// this library, not in the contract's list; the layout is fixed from its
/// first release).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct BzjRadiusFilletReport {
    /// Energy, curvature range and extrema of the blend (as
    /// [`bzj_fillet_radius`] reports them).
    pub fairness: BzjFairnessReport,
    /// Largest distance of the blend from the circle of the G1 arc of the
    /// same radius in the same corner (sampled at 257 parameters).
    pub arc_deviation: f64,
    /// The arc's touching point on P: where P is cut.
    pub u0: f64,
    /// The arc's touching point on Q: where Q is cut.
    pub v0: f64,
}

/// [`bzj_fillet_radius`] with more of what it found: `report` (may be
/// NULL) receives the fairness report, the blend's largest distance from
/// the arc's circle and the touching points; `arc_centre` (may be NULL)
/// receives the arc's centre, as many doubles as the curves' dimension.
/// Outputs, guarantee and statuses as [`bzj_fillet_radius`].
///
/// # Safety
/// As [`bzj_fillet_radius`]; `report` is NULL or writable; `arc_centre` is
/// NULL or points to dimension-many writable doubles.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_radius_detailed(
    p: *const BzjCurve,
    q: *const BzjCurve,
    radius: f64,
    order: usize,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    report: *mut BzjRadiusFilletReport,
    arc_centre: *mut f64,
) -> BzjStatus {
    let write_report = |f: &RadiusFillet| {
        if !arc_centre.is_null() {
            let dim = f.arc_centre.len();
            // SAFETY: the caller promises dimension-many doubles.
            unsafe { output_slice(arc_centre, dim, dim, "arc_centre") }?
                .copy_from_slice(&f.arc_centre);
        }
        let summary = BzjRadiusFilletReport {
            fairness: f.report.into(),
            arc_deviation: f.arc_deviation,
            u0: f.u0,
            v0: f.v0,
        };
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, summary) };
        Ok(())
    };
    // SAFETY: caller contract.
    unsafe {
        fillet_radius_with(
            p,
            q,
            radius,
            order,
            [p_trimmed, blend, q_trimmed],
            write_report,
        )
    }
}

/// The body of `bzj_fillet_radius` and `bzj_fillet_radius_detailed`: the
/// fillet into the three handle slots, after `report` wrote what else the
/// caller asked for.
///
/// # Safety
/// `p`, `q` are NULL or live handles; each slot is NULL or writable.
unsafe fn fillet_radius_with(
    p: *const BzjCurve,
    q: *const BzjCurve,
    radius: f64,
    order: usize,
    [p_trimmed, blend, q_trimmed]: [*mut *mut BzjCurve; 3],
    report: impl FnOnce(&RadiusFillet) -> crate::status::FfiResult<()>,
) -> BzjStatus {
    // SAFETY: each is null or writable (caller contract).
    let outs = unsafe { fillet_outputs(p_trimmed, blend, q_trimmed) };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let outs = require_all(outs)?;
        let f = fillet_radius(p, q, radius, order)?;
        report(&f)?;
        write_radius_fillet(outs, f);
        Ok(())
    })
}

/// Round every corner of a chain of curves (a wire) by radius, each as
/// [`bzj_fillet_radius`] rounds one: corner i between `curves[i]` and
/// `curves[i + 1]` (and, when `closed == 1`, between the last curve and the
/// first) is their shared vertex when one ends where the next starts
/// (within 1e-9 of their coordinate size), else their crossing nearest the
/// shared end (as [`crate::fillet::bzj_fillet_chain`] chooses it); it is
/// rounded like the G1 arc of radius `radius` with a G^`order` blend of
/// fair shape values. Pieces, `count`, `capacity` and the "count only"
/// query as `bzj_fillet_chain` (trimmed curve 0, blend 0, trimmed curve 1,
/// ...: `2 * curve_count - 1` handles open, `2 * curve_count` closed).
/// `reports` (may be NULL) receives one [`BzjRadiusFilletReport`] per
/// corner: `curve_count - 1` open, `curve_count` closed (not written by a
/// "count only" query or on error).
///
/// @return BZJ_ERR_NULL_POINTER if `curves`, one of its handles or `count`
///         is NULL, or `out_pieces` is NULL while `capacity > 0`;
///         BZJ_ERR_BUFFER_TOO_SMALL if `0 < capacity <` the number needed;
///         BZJ_ERR_INVALID_ARGUMENT if `closed` is not 0 or 1, fewer than 2
///         curves are given, `radius` is not > 0, `order` is 0 or above 6,
///         the arc does not fit a corner ("corner i radius"), or the arcs
///         at the two ends of a curve overlap or leave at most 1e-9 of its
///         length (naming `curves[i]`);
///         BZJ_ERR_NON_FINITE if `radius` is NaN or infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_NO_INTERSECTION if a corner has no vertex or crossing, or
///         its tangents are parallel (the message names the corner);
///         BZJ_ERR_ILL_CONDITIONED if a corner's touching points or blend
///         cannot be trusted.
///
/// # Safety
/// `curves` is NULL or points to `curve_count` readable handle pointers
/// (each NULL or live); `out_pieces` is NULL or points to `capacity`
/// writable handle pointers; `count` is NULL or writable; `reports` is
/// NULL or points to the corner count of writable reports.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_radius_chain(
    curves: *const *const BzjCurve,
    curve_count: usize,
    radius: f64,
    order: usize,
    closed: i32,
    out_pieces: *mut *mut BzjCurve,
    capacity: usize,
    count: *mut usize,
    reports: *mut BzjRadiusFilletReport,
) -> BzjStatus {
    // SAFETY: caller promises NULL or `capacity` writable handle pointers.
    let pieces = unsafe { chain_pieces_out(out_pieces, capacity) };
    guard(|| {
        // SAFETY: caller contract (`curves`, `count`).
        let call = unsafe { chain_call(curves, curve_count, closed, count, pieces, || Ok(())) }?;
        let Some(ChainCall {
            curves,
            closed,
            pieces,
            ..
        }) = call
        else {
            return Ok(());
        };
        let rounded = fillet_radius_chain(&curves, radius, order, closed)?;
        if !reports.is_null() {
            let n = rounded.corners.len();
            // SAFETY: the caller promises the corner count of reports.
            let out = unsafe { std::slice::from_raw_parts_mut(reports, n) };
            for (slot, c) in out.iter_mut().zip(&rounded.corners) {
                *slot = BzjRadiusFilletReport {
                    fairness: c.report.into(),
                    arc_deviation: c.arc_deviation,
                    u0: c.u0,
                    v0: c.v0,
                };
            }
        }
        pieces.write(rounded.pieces);
        Ok(())
    })
}

/// The three pieces of a fillet by radius into the caller's slots.
fn write_radius_fillet([p_out, blend_out, q_out]: [CheckedOut; 3], f: RadiusFillet) {
    p_out.write(f.p_trimmed);
    blend_out.write(f.blend);
    q_out.write(f.q_trimmed);
}
