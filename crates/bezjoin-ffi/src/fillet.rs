//! Curve intersection and corner rounding (mathematics.md, section 2):
//! `bzj_intersect`, `bzj_fillet` of the contract, and the additions
//! `bzj_intersect_detailed`, `bzj_intersect_options_default`,
//! `bzj_fillet_auto_scale`, `bzj_fillet_deviation`, `bzj_fillet_chain` and
//! `bzj_fillet_vertex`. Every function takes Bezier and NURBS handles
//! (mathematics.md, section 6).

use bezjoin_core::BezjoinError;
use bezjoin_core::{
    ChainFilletOptions, Curve, DeviationFilletOptions, Fillet, FilletOptions, ShapeScale, fillet,
    fillet_chain, fillet_vertex, fillet_within_deviation,
};
use bezjoin_core::{IntersectOptions, Intersection, IntersectionKind, intersect};

use crate::guard::guard;
// The entry point these docs link to (rustdoc only; the header's text is unchanged).
#[cfg(doc)]
use crate::connect::bzj_connect_balanced_scale;
use crate::handles::{
    BzjCurve, CheckedOut, HandleArray, HandleOut, HandleSlots, ShortArray, require_all,
};
use crate::pointers::{
    curve_ref, input_ref, input_slice, output_slice, require_out, write_optional, write_scales,
};
use crate::status::{BzjStatus, FfiError, FfiResult};

/// Options of `bzj_fillet` (contract layout; every field is read).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjFilletOptions {
    /// Arc length along P back from the crossing, > 0.
    pub p_setback: f64,
    /// Arc length along Q on from the crossing, > 0.
    pub q_setback: f64,
    /// kp: the blend's continuity order at P (any order, as for connect).
    pub p_order: usize,
    /// kq: the blend's continuity order at Q (any order).
    pub q_order: usize,
    /// alpha > 0; 1.0 = the paper.
    pub p_scale: f64,
    /// beta > 0; 1.0 = the paper.
    pub q_scale: f64,
}

impl BzjFilletOptions {
    fn to_core(self) -> FilletOptions {
        FilletOptions::new(self.p_setback, self.q_setback, self.p_order, self.q_order)
            .with_scales(self.p_scale, self.q_scale)
    }
}

/// What an intersection hit is.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(non_camel_case_types)]
pub enum BzjIntersectionKind {
    /// The curves cross (2D: P passes from one side of Q to the other).
    BZJ_INTERSECTION_CROSSING = 0,
    /// The curves meet tangentially without crossing.
    BZJ_INTERSECTION_TOUCHING = 1,
    /// The curves coincide for u in [u, u_end], v from v to v_end.
    BZJ_INTERSECTION_OVERLAP = 2,
}

/// One hit of `bzj_intersect_detailed`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjIntersection {
    /// Parameter on P (for an overlap, its start).
    pub u: f64,
    /// Parameter on Q (for an overlap, of the point P(u)).
    pub v: f64,
    /// Overlap: end parameter on P (> u). Otherwise equal to u.
    pub u_end: f64,
    /// Overlap: parameter on Q of P(u_end) (below v when the curves run in
    /// opposite directions). Otherwise equal to v.
    pub v_end: f64,
    /// |P(u) - Q(v)|, at most the distance tolerance.
    pub distance: f64,
    /// Crossing, touching or overlap.
    pub kind: BzjIntersectionKind,
}

/// Tolerances and work bounds of the intersection search; fill with
/// `bzj_intersect_options_default` and change what you need.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjIntersectOptions {
    /// Curves meet where |P(u) - Q(v)| <= this times the largest absolute
    /// control-point coordinate of either curve; in (0, 1). Default 1e-9.
    pub relative_distance_tolerance: f64,
    /// Sine of the tangent angle below which a hit at an end point (or in 3D)
    /// is touching rather than crossing; in [0, 1). Default 1e-6.
    pub tangent_tolerance: f64,
    /// Largest number of subdivision levels. Default 60.
    pub max_depth: usize,
    /// Largest number of bounding-box pairs examined (>= 1); exceeding it is
    /// BZJ_ERR_ILL_CONDITIONED. Default 200000.
    pub max_box_pairs: usize,
    /// Largest number of hits; exceeding it is BZJ_ERR_ILL_CONDITIONED.
    /// Default 10000.
    pub max_hits: usize,
}

impl From<&IntersectOptions> for BzjIntersectOptions {
    fn from(o: &IntersectOptions) -> Self {
        Self {
            relative_distance_tolerance: o.relative_distance_tolerance,
            tangent_tolerance: o.tangent_tolerance,
            max_depth: o.max_depth,
            max_box_pairs: o.max_box_pairs,
            max_hits: o.max_hits,
        }
    }
}

impl From<&BzjIntersectOptions> for IntersectOptions {
    fn from(o: &BzjIntersectOptions) -> Self {
        Self {
            relative_distance_tolerance: o.relative_distance_tolerance,
            tangent_tolerance: o.tangent_tolerance,
            max_depth: o.max_depth,
            max_box_pairs: o.max_box_pairs,
            max_hits: o.max_hits,
        }
    }
}

impl From<&Intersection> for BzjIntersection {
    fn from(h: &Intersection) -> Self {
        let (kind, u_end, v_end) = match h.kind {
            IntersectionKind::Crossing => {
                (BzjIntersectionKind::BZJ_INTERSECTION_CROSSING, h.u, h.v)
            }
            IntersectionKind::Touching => {
                (BzjIntersectionKind::BZJ_INTERSECTION_TOUCHING, h.u, h.v)
            }
            IntersectionKind::Overlap { u_range, v_range } => (
                BzjIntersectionKind::BZJ_INTERSECTION_OVERLAP,
                u_range.1,
                v_range.1,
            ),
        };
        Self {
            u: h.u,
            v: h.v,
            u_end,
            v_end,
            distance: h.distance,
            kind,
        }
    }
}

/// Options of `bzj_fillet_deviation`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjDeviationFilletOptions {
    /// eps > 0: the largest distance allowed between the corner point X
    /// (the crossing) and the blend R, min over t of |R(t) - X|; the
    /// result's distance is in [eps (1 - 1e-9), eps (1 - 2.5e-10)], never
    /// above eps.
    pub max_deviation: f64,
    /// dq / dp > 0; 1.0 = symmetric rounding.
    pub setback_ratio: f64,
    /// kp: the blend's continuity order at P (any order, as for connect).
    pub p_order: usize,
    /// kq: the blend's continuity order at Q (any order).
    pub q_order: usize,
    /// alpha > 0; 1.0 = the paper.
    pub p_scale: f64,
    /// beta > 0; 1.0 = the paper.
    pub q_scale: f64,
}

/// What `bzj_fillet_deviation` chose and achieved.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjDeviationFilletReport {
    /// The setback dp found (arc length along P back from the crossing).
    pub p_setback: f64,
    /// dq = setback_ratio * dp.
    pub q_setback: f64,
    /// The achieved deviation min over t of |R(t) - X|: at most
    /// max_deviation (1 - 2.5e-10) and at least max_deviation (1 - 1e-9).
    pub deviation: f64,
    /// Where P was cut.
    pub u0: f64,
    /// Where Q was cut.
    pub v0: f64,
}

/// Same-dimension check with the C argument names.
fn same_dimension(p: &Curve, q: &Curve) -> FfiResult {
    if p.dim() != q.dim() {
        return Err(BezjoinError::DimensionMismatch {
            name: "q".into(),
            expected: p.dim(),
            actual: q.dim(),
        }
        .into());
    }
    Ok(())
}

/// All places where `p` and `q` meet, ordered by u: crossings, touching
/// points, and each overlap by its start pair. Writes the first
/// `min(capacity, total)` pairs `(u, v)` into `out` (`2 * capacity` doubles)
/// and the total found into `count`. `capacity == 0` with `out == NULL` is a
/// valid "count only" query. Default tolerances (relative distance 1e-9);
/// use `bzj_intersect_detailed` for the kind of each hit and other
/// tolerances. Bezier and NURBS handles: `u` and `v` are in each curve's
/// domain (`[0, 1]` for a Bezier curve).
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q` or `count` is NULL, or `out` is
///         NULL while `capacity > 0`;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_INVALID_ARGUMENT for curves of dimension 1;
///         BZJ_ERR_ILL_CONDITIONED if the curves run within the tolerance
///         of each other without coinciding and the work bound is reached.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `out` is NULL or points to
/// `2 * capacity` writable doubles; `count` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_intersect(
    p: *const BzjCurve,
    q: *const BzjCurve,
    out: *mut f64,
    capacity: usize,
    count: *mut usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let count = require_out(count, "count")?;
        if capacity > 0 && out.is_null() {
            return Err(FfiError::NullPointer("out".into()));
        }
        let doubles = capacity
            .checked_mul(2)
            .ok_or_else(|| BezjoinError::invalid("capacity", format!("{capacity} is too large")))?;
        same_dimension(p, q)?;
        let hits = intersect(p, q, &IntersectOptions::default())?;
        let written = hits.len().min(capacity);
        if written > 0 {
            // SAFETY: non-null (checked) with `2 * capacity >= 2 * written` writable doubles.
            let buf = unsafe { std::slice::from_raw_parts_mut(out, doubles) };
            for (i, h) in hits.iter().take(written).enumerate() {
                buf[2 * i] = h.u;
                buf[2 * i + 1] = h.v;
            }
        }
        // SAFETY: checked non-null.
        unsafe { count.write(hits.len()) };
        Ok(())
    })
}

/// Fill `out` with the default intersection options.
///
/// @return BZJ_ERR_NULL_POINTER if `out` is NULL.
///
/// # Safety
/// `out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_intersect_options_default(out: *mut BzjIntersectOptions) -> BzjStatus {
    guard(|| {
        let out = require_out(out, "out")?;
        // SAFETY: checked non-null.
        unsafe { out.write(BzjIntersectOptions::from(&IntersectOptions::default())) };
        Ok(())
    })
}

/// Like `bzj_intersect`, with the kind of each hit (crossing, touching,
/// overlap with its range) and explicit tolerances: `options` may be NULL for
/// the defaults. Writes the first `min(capacity, total)` hits into `out` and
/// the total into `count`; `capacity == 0` with `out == NULL` counts only.
/// Bezier and NURBS handles; parameters in each curve's domain.
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q` or `count` is NULL, or `out` is
///         NULL while `capacity > 0`;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_INVALID_ARGUMENT for curves of dimension 1, an option out
///         of its range (named in the message);
///         BZJ_ERR_NON_FINITE if a tolerance is NaN or infinite;
///         BZJ_ERR_ILL_CONDITIONED if a work bound is reached.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable; `out`
/// is NULL or points to `capacity` writable `BzjIntersection`; `count` is
/// NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_intersect_detailed(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjIntersectOptions,
    out: *mut BzjIntersection,
    capacity: usize,
    count: *mut usize,
) -> BzjStatus {
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let count = require_out(count, "count")?;
        if capacity > 0 && out.is_null() {
            return Err(FfiError::NullPointer("out".into()));
        }
        same_dimension(p, q)?;
        // SAFETY: caller contract (NULL or readable).
        let options = match unsafe { options.as_ref() } {
            Some(o) => IntersectOptions::from(o),
            None => IntersectOptions::default(),
        };
        let hits = intersect(p, q, &options)?;
        let written = hits.len().min(capacity);
        for (i, h) in hits.iter().take(written).enumerate() {
            // SAFETY: `out` is non-null with `capacity > i` writable elements.
            unsafe { out.add(i).write(BzjIntersection::from(h)) };
        }
        // SAFETY: checked non-null.
        unsafe { count.write(hits.len()) };
        Ok(())
    })
}

/// Round the corner between `p` and `q` at their first crossing (smallest u
/// on P; touching points and overlaps are skipped): keeps P on `[a, u0]` and
/// Q on `[v0, b]` (`a` the start of P's domain, `b` the end of Q's: 0 and 1
/// for Bezier curves), where the arc length of P from u0 to the crossing is
/// `p_setback` and that of Q from the crossing to v0 is `q_setback`, and joins
/// them with the C^k curve of `bzj_connect` (degree `p_order + q_order + 1`;
/// orders may exceed the degrees). The three curves form a C^k B-spline with
/// knot intervals `(u0 - a, p_scale, (b - v0) p_scale / q_scale)`. Other
/// corners of the crossing: pass `bzj_curve_reverse` of P and/or Q.
///
/// NURBS handles: `p_trimmed` and `q_trimmed` are NURBS handles with the
/// input's parameters (domains `[a, u0]` and `[v0, b]`, cut by knot
/// insertion, exact); Bezier inputs give Bezier pieces on `[0, 1]`. The
/// blend is always a Bezier handle. A corner at a shared vertex (P ends
/// where Q starts, as in a wire) is `bzj_fillet_vertex`.
///
/// @return BZJ_ERR_NULL_POINTER if a pointer is NULL;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_NON_FINITE if an option is NaN or infinite;
///         BZJ_ERR_INVALID_ARGUMENT if a setback or scale is not positive, a
///         setback is at most 1e-9 of the curves' coordinate size (the cut
///         could not be told from the corner), or
///         a setback is not shorter than the part of the curve before / after
///         the crossing by more than the larger of twice its length
///         accuracy (`2 relative_length_accuracy setback`) and 1e-9 of the
///         curve's length (a longer one would keep a sliver of the curve);
///         BZJ_ERR_NO_INTERSECTION if the curves do not cross or only touch;
///         BZJ_ERR_ILL_CONDITIONED if the connection cannot be trusted.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable; the
/// three out-pointers are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_fillet(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, None, None, [p_trimmed, blend, q_trimmed]) }
}

/// [`bzj_fillet`] with `alpha = beta = s` chosen automatically, as
/// `bzj_connect_auto_scale` chooses it: `s` minimises the blend's fairness
/// energy `integral_0^1 |R''(t)|^2 dt` over two decades either side of
/// `s0 = |Q(v0) - P(u0)| / mean(|P'(u0)|, |Q'(v0)|)` (each speed raised to
/// its floor where the end turns within 1 % of the chord,
/// docs/mathematics.md). `options->p_scale`
/// and `options->q_scale` are ignored (not read for validity). The chosen
/// `s` is written to `scale_out` when it is not NULL. With the paper's
/// scale 1 a blend whose ends move fast against the setback puts its inner
/// control points past the corner and can loop; this variant avoids that.
/// Same guarantee as [`bzj_fillet`], with knot intervals
/// `(u0 - a, s, b - v0)`.
///
/// @return the statuses of [`bzj_fillet`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet`]; `scale_out` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_fillet_auto_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    scale_out: *mut f64,
) -> BzjStatus {
    let chosen = Some((ShapeScale::Auto, [scale_out, std::ptr::null_mut()]));
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, None, chosen, [p_trimmed, blend, q_trimmed]) }
}

/// [`bzj_fillet`] with the blend leaving both curves at one speed `sigma`:
/// `alpha = sigma / |P'(u0)|`, `beta = sigma / |Q'(v0)|`, `sigma` chosen as
/// [`bzj_fillet_auto_scale`] chooses `s` (least fairness energy
/// `integral_0^1 |R''(t)|^2 dt`, two decades either side of the chord
/// `|Q(v0) - P(u0)|`). The blend then does not depend on how fast either
/// curve runs in its own parameter (a line given on `[0, 1]` or on
/// `[0, length]`), which the one `s` of [`bzj_fillet_auto_scale`] does not:
/// there a corner of lines 1000 and 10 long (setback 1) peaks at curvature
/// 1.29e4 where lines 10 and 10 peak at 1.33. Near-stationary ends as in
/// [`bzj_connect_balanced_scale`]. `options->p_scale` and
/// `options->q_scale` are ignored (not read for validity); `alpha`, `beta`
/// are written to `p_scale_out`, `q_scale_out` when not NULL. Same
/// guarantee as [`bzj_fillet`].
///
/// @return the statuses of [`bzj_fillet`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet`]; `p_scale_out`, `q_scale_out` are NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_balanced_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    p_scale_out: *mut f64,
    q_scale_out: *mut f64,
) -> BzjStatus {
    let chosen = Some((ShapeScale::Balanced, [p_scale_out, q_scale_out]));
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, None, chosen, [p_trimmed, blend, q_trimmed]) }
}

/// The three handle outputs of a fillet, cleared.
///
/// # Safety
/// Each is NULL or writable.
pub(crate) unsafe fn fillet_outputs(
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
) -> [HandleOut; 3] {
    // SAFETY: forwarded.
    unsafe {
        [
            HandleOut::cleared(p_trimmed, "p_trimmed"),
            HandleOut::cleared(blend, "blend"),
            HandleOut::cleared(q_trimmed, "q_trimmed"),
        ]
    }
}

/// One corner rounded: at the first crossing (`gap` None, `bzj_fillet`) or
/// at the shared vertex within `gap` (`bzj_fillet_vertex`), with the
/// options' scales (`chosen` None) or the scale the library chooses, its
/// `alpha`, `beta` written through the two pointers ([`write_scales`]).
///
/// # Safety
/// As [`bzj_fillet_vertex_balanced_scale`].
unsafe fn corner_fillet(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    gap: Option<f64>,
    chosen: Option<(ShapeScale, [*mut f64; 2])>,
    [p_trimmed, blend, q_trimmed]: [*mut *mut BzjCurve; 3],
) -> BzjStatus {
    // SAFETY: caller contract.
    let outs = unsafe { fillet_outputs(p_trimmed, blend, q_trimmed) };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        // SAFETY: caller contract.
        let options = unsafe { input_ref(options, "options") }?;
        let outs = require_all(outs)?;
        let mut core_options = options.to_core();
        if let Some((scale, _)) = chosen {
            core_options.scale = scale;
        }
        let result = match gap {
            Some(gap) => fillet_vertex(p, q, &core_options, gap)?,
            None => fillet(p, q, &core_options)?,
        };
        if let Some((_, scales_out)) = chosen {
            // SAFETY: NULL or writable by the caller contract.
            unsafe { write_scales(scales_out, (result.p_scale, result.q_scale)) };
        }
        write_fillet(outs, result);
        Ok(())
    })
}

/// The three pieces of a fillet into the caller's (checked) slots.
fn write_fillet([p_out, blend_out, q_out]: [CheckedOut; 3], result: Fillet) {
    p_out.write(result.p_trimmed);
    blend_out.write(result.blend);
    q_out.write(result.q_trimmed);
}

/// Round the corner at the vertex where `p` ends and `q` starts (a wire's
/// or a sketch's vertex), whatever other crossings P and Q have (for those,
/// `bzj_fillet` keeps its first-crossing rule): P's last point and Q's first
/// point must lie within `gap >= 0` (absolute) of each other (sketch
/// solvers leave 1e-7 and more). Setbacks are arc lengths measured back
/// from P's end and on from Q's start. Outputs and guarantee as
/// `bzj_fillet` (with the vertex as the crossing: `u*` = the end of P's
/// domain, `v*` = the start of Q's), for Bezier and NURBS handles.
///
/// @return BZJ_ERR_NULL_POINTER if a pointer is NULL;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_NON_FINITE if an option or `gap` is NaN or infinite;
///         BZJ_ERR_INVALID_ARGUMENT if a setback or scale is not positive,
///         `gap` is negative, a setback is at most 1e-9 of the curves'
///         coordinate size, or a setback is not shorter than the curve by
///         more than the larger of twice its length accuracy and 1e-9 of the
///         curve's length;
///         BZJ_ERR_NO_INTERSECTION if P's end and Q's start are more than
///         `gap` apart (the message gives the distance), or if the path
///         doubles back at the vertex (Q leaves along P's arrival direction
///         reversed, the sine of the tangents' angle at most 1e-6, the
///         default tangent tolerance of `BzjIntersectOptions`): a cusp, no
///         corner to round;
///         BZJ_ERR_ILL_CONDITIONED if the connection cannot be trusted.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable; the
/// three out-pointers are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_fillet_vertex(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    gap: f64,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
) -> BzjStatus {
    let outs = [p_trimmed, blend, q_trimmed];
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, Some(gap), None, outs) }
}

/// [`bzj_fillet_vertex`] with `alpha = beta = s` chosen automatically as
/// [`bzj_fillet_auto_scale`] chooses it (`options->p_scale` and
/// `options->q_scale` are ignored, not read for validity); the chosen `s`
/// is written to `scale_out` when it is not NULL. The default for a user
/// who gives no scales: the paper's scale 1 can loop when the setbacks are
/// short against the curves' parametric speed (a 40 mm and a 20 mm line
/// with setback 2 give a self-intersecting blend 13.6 mm long).
///
/// @return the statuses of [`bzj_fillet_vertex`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet_vertex`]; `scale_out` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_vertex_auto_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    gap: f64,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    scale_out: *mut f64,
) -> BzjStatus {
    let outs = [p_trimmed, blend, q_trimmed];
    // SAFETY: caller contract.
    let chosen = Some((ShapeScale::Auto, [scale_out, std::ptr::null_mut()]));
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, Some(gap), chosen, outs) }
}

/// [`bzj_fillet_vertex`] with the blend leaving both curves at one speed, as
/// [`bzj_fillet_balanced_scale`] chooses it (`options->p_scale` and
/// `options->q_scale` are ignored, not read for validity); `alpha`, `beta`
/// are written to `p_scale_out`, `q_scale_out` when not NULL. The default
/// to prefer for a CAD corner: the blend depends on the corner's geometry
/// and the setbacks only, not on the lengths or parametrisations of the
/// edges (with [`bzj_fillet_vertex_auto_scale`] a corner of lines 1000 and
/// 10 long gets a near-kink at the short edge's end).
///
/// @return the statuses of [`bzj_fillet_vertex`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet_vertex`]; `p_scale_out`, `q_scale_out` are NULL or
/// writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_vertex_balanced_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjFilletOptions,
    gap: f64,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    p_scale_out: *mut f64,
    q_scale_out: *mut f64,
) -> BzjStatus {
    let outs = [p_trimmed, blend, q_trimmed];
    let chosen = Some((ShapeScale::Balanced, [p_scale_out, q_scale_out]));
    // SAFETY: caller contract.
    unsafe { corner_fillet(p, q, options, Some(gap), chosen, outs) }
}

/// Round the corner at the first crossing so that the blend passes within
/// `max_deviation` of the corner point X (the crossing), using nearly all of
/// it: `max_deviation (1 - 1e-9) <= min over t of |R(t) - X| <=
/// max_deviation (1 - 2.5e-10)`, a strict bound (a blend above
/// `max_deviation` is never returned; the margin covers the rounding of the
/// computed distance), with setbacks `dp` and `dq = setback_ratio * dp`
/// found by a bracketing search (1.0 = symmetric). Outputs as
/// `bzj_fillet` (Bezier and NURBS handles; NURBS pieces keep their
/// parameters); `report` (may be NULL) receives the setbacks, the deviation
/// achieved and the cut parameters.
///
/// @return BZJ_ERR_NULL_POINTER if a required pointer is NULL;
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_NON_FINITE if an option is NaN or infinite;
///         BZJ_ERR_INVALID_ARGUMENT if `max_deviation`, `setback_ratio` or a
///         scale is not positive, or the deviation cannot be reached even
///         with the longest setbacks the curves allow (the message gives the
///         largest possible);
///         BZJ_ERR_NO_INTERSECTION if the curves do not cross or only touch;
///         BZJ_ERR_ILL_CONDITIONED if the connection cannot be trusted or no
///         setback the search tries gives a deviation in that window.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable; the
/// out-pointers and `report` are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_fillet_deviation(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjDeviationFilletOptions,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    report: *mut BzjDeviationFilletReport,
) -> BzjStatus {
    // SAFETY: caller contract (`scale_out` NULL is allowed).
    unsafe {
        fillet_deviation_with_scale(
            p,
            q,
            options,
            false,
            p_trimmed,
            blend,
            q_trimmed,
            report,
            std::ptr::null_mut(),
        )
    }
}

/// [`bzj_fillet_deviation`] with `alpha = beta = s` chosen automatically
/// at every setback the search tries, as [`bzj_fillet_auto_scale`] chooses
/// it (`options->p_scale` and `options->q_scale` are ignored, not read for
/// validity); the `s` of the returned blend is written to `scale_out` when
/// it is not NULL. The same deviation guarantee. With the paper's scale 1
/// the blend of two long edges loops and reaches the deviation only with
/// long setbacks (lines 60 and 40 long crossing at right angles, deviation
/// 0.1: setbacks 6.2); with the automatic scale the setbacks stay near the
/// arc's (0.27 there).
///
/// @return the statuses of [`bzj_fillet_deviation`] (except for the
///         scales).
///
/// # Safety
/// As [`bzj_fillet_deviation`]; `scale_out` is NULL or writable.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_deviation_auto_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjDeviationFilletOptions,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    report: *mut BzjDeviationFilletReport,
    scale_out: *mut f64,
) -> BzjStatus {
    // SAFETY: caller contract.
    unsafe {
        fillet_deviation_with_scale(
            p, q, options, true, p_trimmed, blend, q_trimmed, report, scale_out,
        )
    }
}

/// The body of `bzj_fillet_deviation` and `bzj_fillet_deviation_auto_scale`.
///
/// # Safety
/// As [`bzj_fillet_deviation_auto_scale`].
#[allow(clippy::too_many_arguments)]
unsafe fn fillet_deviation_with_scale(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjDeviationFilletOptions,
    auto_scale: bool,
    p_trimmed: *mut *mut BzjCurve,
    blend: *mut *mut BzjCurve,
    q_trimmed: *mut *mut BzjCurve,
    report: *mut BzjDeviationFilletReport,
    scale_out: *mut f64,
) -> BzjStatus {
    // SAFETY: caller contract.
    let outs = unsafe { fillet_outputs(p_trimmed, blend, q_trimmed) };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        // SAFETY: caller contract.
        let o = unsafe { input_ref(options, "options") }?;
        let [p_out, blend_out, q_out] = require_all(outs)?;
        let mut core =
            DeviationFilletOptions::new(o.max_deviation, 0).with_setback_ratio(o.setback_ratio);
        core.shape =
            FilletOptions::new(1.0, 1.0, o.p_order, o.q_order).with_scales(o.p_scale, o.q_scale);
        if auto_scale {
            core.shape.scale = ShapeScale::Auto;
        }
        let r = fillet_within_deviation(p, q, &core)?;
        let summary = BzjDeviationFilletReport {
            p_setback: r.p_setback,
            q_setback: r.q_setback,
            deviation: r.deviation,
            u0: r.fillet.u0,
            v0: r.fillet.v0,
        };
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, summary) };
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(scale_out, r.fillet.p_scale) };
        write_fillet([p_out, blend_out, q_out], r.fillet);
        Ok(())
    })
}

/// Round every corner of a chain of curves in one call. Corner i lies
/// between `curves[i]` and `curves[i + 1]` (and, when `closed == 1`, between
/// the last curve and the first); its crossing is the one nearest the shared
/// end (smallest `(last - u) / |P's domain| + (v - first) / |Q's domain|`,
/// i.e. `(1 - u) + v` for Bezier curves), rounded as `bzj_fillet` with
/// `options`. Bezier and NURBS handles: trimmed pieces keep their kind and
/// parameters; blends are Bezier handles.
/// Long chains (more than 64 corners) are computed in parallel; the result is
/// identical either way.
///
/// Output, in path order: trimmed curve 0, blend 0, trimmed curve 1, ...:
/// `2 * curve_count - 1` handles for an open chain, `2 * curve_count` for a
/// closed one (ending with the blend back to the start). The number needed
/// is written into `count`; `capacity == 0` with `out_pieces == NULL` is a
/// valid "count only" query (nothing is computed, but the arguments are
/// checked as below up to the count: NULL handles, `closed`, fewer than 2
/// curves). Release every handle with `bzj_curve_free`.
///
/// @return BZJ_ERR_NULL_POINTER if `curves`, one of its handles, `options`
///         or `count` is NULL, or `out_pieces` is NULL while `capacity > 0`;
///         BZJ_ERR_BUFFER_TOO_SMALL if `0 < capacity <` the number needed
///         (no handles are written);
///         BZJ_ERR_INVALID_ARGUMENT if `closed` is not 0 or 1, fewer than 2
///         curves are given, an option is out of range, a setback is too long
///         at a corner ("corner i ..."), or two cuts pass each other on a
///         curve or leave at most 1e-9 of its length (naming `curves[i]`);
///         BZJ_ERR_DIMENSION_MISMATCH if the curves' dimensions differ;
///         BZJ_ERR_NON_FINITE if an option is NaN or infinite;
///         BZJ_ERR_NO_INTERSECTION if consecutive curves do not cross or meet
///         tangentially (a smooth joint; the message names the corner);
///         BZJ_ERR_ILL_CONDITIONED if a connection cannot be trusted.
///
/// # Safety
/// `curves` is NULL or points to `curve_count` readable handle pointers (each
/// NULL or live); `options` is NULL or readable; `out_pieces` is NULL or
/// points to `capacity` writable handle pointers; `count` is NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_fillet_chain(
    curves: *const *const BzjCurve,
    curve_count: usize,
    options: *const BzjFilletOptions,
    closed: i32,
    out_pieces: *mut *mut BzjCurve,
    capacity: usize,
    count: *mut usize,
) -> BzjStatus {
    let (pieces, chosen) = ((out_pieces, capacity, count), None);
    // SAFETY: caller contract.
    unsafe { fillet_chain_with_scale(curves, curve_count, options, closed, pieces, chosen) }
}

/// [`bzj_fillet_chain`] with `alpha = beta = s` chosen automatically at
/// every corner as [`bzj_fillet_auto_scale`] chooses it (`options->p_scale`
/// and `options->q_scale` are ignored, not read for validity). When
/// `scales_out` is not NULL it receives the corner count of doubles (`s` of
/// corner i at index i): `curve_count - 1` for an open chain,
/// `curve_count` for a closed one; it is not written by a "count only"
/// query or on error.
///
/// @return the statuses of [`bzj_fillet_chain`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet_chain`]; `scales_out` is NULL or points to the corner
/// count of writable doubles.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_chain_auto_scale(
    curves: *const *const BzjCurve,
    curve_count: usize,
    options: *const BzjFilletOptions,
    closed: i32,
    out_pieces: *mut *mut BzjCurve,
    capacity: usize,
    count: *mut usize,
    scales_out: *mut f64,
) -> BzjStatus {
    let pieces = (out_pieces, capacity, count);
    let chosen = Some((ShapeScale::Auto, scales_out));
    // SAFETY: caller contract.
    unsafe { fillet_chain_with_scale(curves, curve_count, options, closed, pieces, chosen) }
}

/// [`bzj_fillet_chain`] with every corner's blend leaving both its curves at
/// one speed, as [`bzj_fillet_balanced_scale`] chooses it (`options->p_scale`
/// and `options->q_scale` are ignored, not read for validity): the blends
/// do not depend on how fast the curves run in their own parameters (a
/// 1000 x 10 rectangle of lines gets the corners of a 10 x 10 square, where
/// [`bzj_fillet_chain_auto_scale`]'s one `s` a corner gives near-kinks).
/// When `scales_out` is not NULL it receives twice the corner count of
/// doubles, `alpha` and `beta` of corner i at indices `2 i` and `2 i + 1`
/// (the corner count: `curve_count - 1` for an open chain, `curve_count`
/// for a closed one); it is not written by a "count only" query or on error.
///
/// @return the statuses of [`bzj_fillet_chain`] (except for the scales).
///
/// # Safety
/// As [`bzj_fillet_chain`]; `scales_out` is NULL or points to twice the
/// corner count of writable doubles.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_fillet_chain_balanced_scale(
    curves: *const *const BzjCurve,
    curve_count: usize,
    options: *const BzjFilletOptions,
    closed: i32,
    out_pieces: *mut *mut BzjCurve,
    capacity: usize,
    count: *mut usize,
    scales_out: *mut f64,
) -> BzjStatus {
    let pieces = (out_pieces, capacity, count);
    let chosen = Some((ShapeScale::Balanced, scales_out));
    // SAFETY: caller contract.
    unsafe { fillet_chain_with_scale(curves, curve_count, options, closed, pieces, chosen) }
}

/// The body of `bzj_fillet_chain` and its automatic and balanced variants;
/// `(out_pieces, capacity, count)` as they take them; `chosen`: the options'
/// scales (None) or the scale the library chooses at every corner and the
/// caller's array for it (NULL: not written): corner i's `s` at index i
/// (automatic), its `alpha`, `beta` at `2 i`, `2 i + 1` (balanced).
///
/// # Safety
/// As [`bzj_fillet_chain_balanced_scale`].
unsafe fn fillet_chain_with_scale(
    curves: *const *const BzjCurve,
    curve_count: usize,
    options: *const BzjFilletOptions,
    closed: i32,
    (out_pieces, capacity, count): (*mut *mut BzjCurve, usize, *mut usize),
    chosen: Option<(ShapeScale, *mut f64)>,
) -> BzjStatus {
    // SAFETY: caller promises NULL or `capacity` writable handle pointers.
    let pieces = unsafe { chain_pieces_out(out_pieces, capacity) };
    guard(|| {
        // SAFETY: caller contract (`curves`, `count`, `options`).
        let call = unsafe {
            chain_call(curves, curve_count, closed, count, pieces, || {
                input_ref(options, "options").copied()
            })
        }?;
        let Some(ChainCall {
            curves: owned,
            closed,
            options,
            pieces,
        }) = call
        else {
            return Ok(());
        };
        let mut core = ChainFilletOptions::open(options.to_core());
        core.closed = closed;
        let (scale, scales_out) = chosen.unwrap_or((core.fillet.scale, std::ptr::null_mut()));
        core.fillet.scale = scale;
        let rounded = fillet_chain(&owned, &core)?;
        if !scales_out.is_null() {
            // One `s` a corner (alpha = beta), or both scales.
            let per_corner = if scale == ShapeScale::Balanced { 2 } else { 1 };
            let scales: Vec<f64> = (rounded.corners.iter())
                .flat_map(|c| [c.scales.0, c.scales.1].into_iter().take(per_corner))
                .collect();
            // SAFETY: caller promises room for the corner count of doubles
            // (twice that for the balanced scales).
            unsafe { output_slice(scales_out, scales.len(), scales.len(), "scales_out") }?
                .copy_from_slice(&scales);
        }
        pieces.write(rounded.pieces);
        Ok(())
    })
}

/// The pieces array of a chain call, cleared.
///
/// # Safety
/// `out_pieces` is NULL or points to `capacity` writable handle pointers.
pub(crate) unsafe fn chain_pieces_out(
    out_pieces: *mut *mut BzjCurve,
    capacity: usize,
) -> HandleArray {
    // SAFETY: forwarded.
    unsafe {
        HandleArray::cleared(
            out_pieces,
            capacity,
            "out_pieces",
            ShortArray::AsDoubles("out_pieces (handles)"),
        )
    }
}

/// The checked arguments of a chain call (`bzj_fillet_chain` and its
/// variants).
pub(crate) struct ChainCall<T> {
    /// The curves, copied.
    pub(crate) curves: Vec<Curve>,
    /// `closed == 1`.
    pub(crate) closed: bool,
    /// What the call reads besides (its options).
    pub(crate) options: T,
    /// Room for every piece, checked.
    pub(crate) pieces: HandleSlots,
}

/// Check a chain call's arguments in the documented order (`count`,
/// `curves`, the options read by `read_options`, `closed`, NULL handles,
/// fewer than 2 curves), write the number of pieces into `count`, and
/// return `None` for a "count only" query (`capacity == 0` with NULL
/// `out_pieces`), else the call with room checked for every piece.
///
/// # Safety
/// `curves` is NULL or points to `curve_count` readable handle pointers
/// (each NULL or live); `count` is NULL or writable.
pub(crate) unsafe fn chain_call<T>(
    curves: *const *const BzjCurve,
    curve_count: usize,
    closed: i32,
    count: *mut usize,
    pieces: HandleArray,
    read_options: impl FnOnce() -> FfiResult<T>,
) -> FfiResult<Option<ChainCall<T>>> {
    let count = require_out(count, "count")?;
    if curves.is_null() {
        return Err(FfiError::NullPointer("curves".into()));
    }
    let options = read_options()?;
    let closed = match closed {
        0 => false,
        1 => true,
        other => {
            return Err(BezjoinError::invalid(
                "closed",
                format!("{other} is neither 0 (open) nor 1 (closed)"),
            )
            .into());
        }
    };
    // SAFETY: caller promises `curve_count` readable pointers.
    let handles = unsafe { input_slice(curves, curve_count, "curves") }?;
    // Checked before the count, so that a "count only" query already
    // refuses what the real call would refuse without computing.
    if let Some(i) = handles.iter().position(|h| h.is_null()) {
        return Err(FfiError::NullPointer(format!("curves[{i}]")));
    }
    if curve_count < 2 {
        return Err(BezjoinError::invalid(
            "curves",
            format!("a chain needs at least 2 curves, {curve_count} given"),
        )
        .into());
    }
    let mut chain_curves = Vec::with_capacity(curve_count);
    for (i, &h) in handles.iter().enumerate() {
        // SAFETY: each is a live handle (non-null, checked; caller contract).
        chain_curves.push(unsafe { curve_ref(h, &format!("curves[{i}]")) }?);
    }
    let needed = if closed {
        curve_count.saturating_mul(2)
    } else {
        curve_count.saturating_mul(2).saturating_sub(1)
    };
    // SAFETY: checked non-null.
    unsafe { count.write(needed) };
    if pieces.is_null() && pieces.capacity() == 0 {
        return Ok(None);
    }
    let pieces = pieces.require()?;
    pieces.check_room(needed)?;
    Ok(Some(ChainCall {
        curves: chain_curves.into_iter().cloned().collect(),
        closed,
        options,
        pieces,
    }))
}
