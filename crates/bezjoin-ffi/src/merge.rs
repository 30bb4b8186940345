//! Merge two (or `N`) consecutive curves into one (mathematics.md, section 3).
//!
//! The option structs come from C and contain C enums and `bool`s: they are
//! declared here exactly as the contract shows (so the header is right) but
//! read through private mirrors with `i32` / `u8` fields, whose values are
//! validated, so a bad enum or bool value is `BZJ_ERR_INVALID_ARGUMENT`,
//! never undefined behaviour.

use std::mem::{align_of, offset_of, size_of};

use bezjoin_core::BezjoinError;
use bezjoin_core::{
    Breakpoints, ChainKeepPoint, ChainMergeOptions, Curve, CurveMerge, KeepPoint, MergeMetric,
    MergeOptions, merge_curve_chain, merge_curves,
};

use crate::guard::guard;
use crate::handles::{BzjCurve, CheckedOut, HandleArray, HandleOut, ShortArray};
use crate::pointers::{curve_ref, input_ref, input_slice, output_slice, write_optional};
use crate::status::{BzjStatus, FfiError, FfiResult};

/// What stage 1 minimises.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(non_camel_case_types)]
pub enum BzjMetric {
    /// Sum of squared control-point changes.
    BZJ_METRIC_DISCRETE = 0,
    /// Integral of the squared change of each curve over its own parameter
    /// (the paper's eq. 12, exact Bernstein Gram matrix).
    BZJ_METRIC_L2 = 1,
}

/// How the split parameter `mu` is chosen.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(non_camel_case_types)]
pub enum BzjSplit {
    /// Use `options.mu`.
    BZJ_SPLIT_GIVEN = 0,
    /// `mu = 1/2` (the paper's examples).
    BZJ_SPLIT_HALF = 1,
    /// Proportional to the control-polygon lengths.
    BZJ_SPLIT_POLYGON = 2,
    /// The `mu` minimising the metric over `[0.001, 0.999]` (33 samples,
    /// then Brent's method around the best).
    BZJ_SPLIT_OPTIMAL = 3,
}

/// A point kept with its derivatives `0..=max_order`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjKeepPoint {
    /// `u_k` on P or `v_k` on Q, in `[0, 1]`.
    pub param: f64,
    /// Derivatives `0..=max_order` kept (at most the degree of the merge).
    pub max_order: usize,
}

/// Options of [`bzj_merge`] (layout fixed by the contract).
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjMergeOptions {
    /// The metric minimised.
    pub metric: BzjMetric,
    /// How `mu` is chosen.
    pub split: BzjSplit,
    /// Used when `split == BZJ_SPLIT_GIVEN`, in `(0, 1)`; ignored otherwise.
    pub mu: f64,
    /// P unchanged.
    pub keep_p: bool,
    /// Q unchanged.
    pub keep_q: bool,
    /// First point of P and last point of Q unchanged.
    pub fix_ends: bool,
    /// Points of P kept (may be NULL if the count is 0).
    pub p_points: *const BzjKeepPoint,
    /// Number of `p_points`.
    pub p_point_count: usize,
    /// Points of Q kept (may be NULL if the count is 0).
    pub q_points: *const BzjKeepPoint,
    /// Number of `q_points`.
    pub q_point_count: usize,
}

/// What [`bzj_merge`] reports (layout fixed by the contract).
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct BzjMergeReport {
    /// Split parameter used.
    pub mu: f64,
    /// Value of the minimised metric.
    pub metric_value: f64,
    /// Max distance between R and P-then-Q (R(mu u) against P(u),
    /// R(mu + (1-mu) v) against Q(v), 257 samples each).
    pub max_deviation: f64,
}

/// The C layout of [`BzjMergeOptions`] with plain integers for the enums
/// and bools.
#[repr(C)]
struct MergeOptionsMirror {
    metric: i32,
    split: i32,
    mu: f64,
    keep_p: u8,
    keep_q: u8,
    fix_ends: u8,
    p_points: *const BzjKeepPoint,
    p_point_count: usize,
    q_points: *const BzjKeepPoint,
    q_point_count: usize,
}

const _: () = {
    assert!(size_of::<MergeOptionsMirror>() == size_of::<BzjMergeOptions>());
    assert!(align_of::<MergeOptionsMirror>() == align_of::<BzjMergeOptions>());
    assert!(size_of::<BzjMetric>() == size_of::<i32>());
    assert!(size_of::<BzjSplit>() == size_of::<i32>());
    assert!(size_of::<bool>() == size_of::<u8>());
    assert!(offset_of!(MergeOptionsMirror, split) == offset_of!(BzjMergeOptions, split));
    assert!(offset_of!(MergeOptionsMirror, mu) == offset_of!(BzjMergeOptions, mu));
    assert!(offset_of!(MergeOptionsMirror, keep_p) == offset_of!(BzjMergeOptions, keep_p));
    assert!(offset_of!(MergeOptionsMirror, keep_q) == offset_of!(BzjMergeOptions, keep_q));
    assert!(offset_of!(MergeOptionsMirror, fix_ends) == offset_of!(BzjMergeOptions, fix_ends));
    assert!(offset_of!(MergeOptionsMirror, p_points) == offset_of!(BzjMergeOptions, p_points));
    assert!(
        offset_of!(MergeOptionsMirror, q_point_count) == offset_of!(BzjMergeOptions, q_point_count)
    );
};

fn metric_from(value: i32, name: &str) -> FfiResult<MergeMetric> {
    match value {
        0 => Ok(MergeMetric::Discrete),
        1 => Ok(MergeMetric::Integral),
        _ => Err(BezjoinError::invalid(
            name,
            format!("{value} is not a BzjMetric (BZJ_METRIC_DISCRETE = 0, BZJ_METRIC_L2 = 1)"),
        )
        .into()),
    }
}

#[inline]
fn bool_from(value: u8, name: &str) -> FfiResult<bool> {
    match value {
        0 => Ok(false),
        1 => Ok(true),
        _ => Err(BezjoinError::invalid(name, format!("{value} is not a bool (0 or 1)")).into()),
    }
}

fn keep_points(points: &[BzjKeepPoint]) -> Vec<KeepPoint> {
    points
        .iter()
        .map(|k| KeepPoint {
            param: k.param,
            max_order: k.max_order,
        })
        .collect()
}

/// Read and validate the caller's options.
///
/// # Safety
/// `options` is null or points to a readable `BzjMergeOptions` whose point
/// arrays hold their counts.
unsafe fn read_options(options: *const BzjMergeOptions) -> FfiResult<MergeOptions> {
    // SAFETY: same layout (asserted above); null or readable (caller contract).
    let o = unsafe { input_ref(options.cast::<MergeOptionsMirror>(), "options") }?;
    let metric = metric_from(o.metric, "options.metric")?;
    let split = match o.split {
        0 => Breakpoints::Given(vec![o.mu]),
        1 => Breakpoints::Uniform,
        2 => Breakpoints::PolygonLength,
        3 => Breakpoints::Optimal,
        v => {
            return Err(BezjoinError::invalid(
                "options.split",
                format!("{v} is not a BzjSplit (0..3)"),
            )
            .into());
        }
    };
    // No points (`input_slice` gives none for a zero count, whatever the
    // pointer) without the call.
    let p_points = match o.p_point_count {
        0 => &[],
        // SAFETY: caller promises the counts.
        count => unsafe { input_slice(o.p_points, count, "options.p_points") }?,
    };
    let q_points = match o.q_point_count {
        0 => &[],
        // SAFETY: caller promises the counts.
        count => unsafe { input_slice(o.q_points, count, "options.q_points") }?,
    };
    Ok(MergeOptions {
        metric,
        split,
        keep_p: bool_from(o.keep_p, "options.keep_p")?,
        keep_q: bool_from(o.keep_q, "options.keep_q")?,
        fix_ends: bool_from(o.fix_ends, "options.fix_ends")?,
        p_points: keep_points(p_points),
        q_points: keep_points(q_points),
        degree: None,
        accuracy: bezjoin_core::DEFAULT_MERGE_ACCURACY,
    })
}

/// The handle outputs of a two-curve merge, cleared: `merged` (required),
/// `p_hat` and `q_hat` (optional).
///
/// # Safety
/// Each is NULL or writable.
unsafe fn merge_outputs(
    merged: *mut *mut BzjCurve,
    p_hat: *mut *mut BzjCurve,
    q_hat: *mut *mut BzjCurve,
) -> [HandleOut; 3] {
    // SAFETY: forwarded.
    unsafe {
        [
            HandleOut::cleared(merged, "merged"),
            HandleOut::cleared(p_hat, "p_hat"),
            HandleOut::cleared(q_hat, "q_hat"),
        ]
    }
}

/// Write the results of a two-curve merge: the optional outputs the
/// caller gave, then `merged`.
///
/// # Safety
/// `report` is null or writable.
unsafe fn write_merge(
    result: CurveMerge,
    merged: CheckedOut,
    p_hat: HandleOut,
    q_hat: HandleOut,
    report: *mut BzjMergeReport,
) {
    let r = result.report;
    let summary = BzjMergeReport {
        mu: r.mu,
        metric_value: r.metric_value,
        max_deviation: r.max_deviation,
    };
    // SAFETY: caller contract.
    unsafe { write_optional(report, summary) };
    if let Some(out) = p_hat.given() {
        out.write(result.p_hat);
    }
    if let Some(out) = q_hat.given() {
        out.write(result.q_hat);
    }
    merged.write(result.merged);
}

/// Merge `p` and `q` into one Bezier curve `merged` (mathematics.md,
/// section 3; Ganchuk, Krivosheev, Mavrin, Ryzhov 2024 with the mu-scaled
/// continuity conditions): the smallest change (in `options.metric`) of
/// their control points, under the constraints of `options`, that makes
/// them the pieces `p_hat`, `q_hat` of one curve split at `mu`. A lower
/// degree is elevated first; the merged degree is the higher one.
/// `p_hat`, `q_hat` and `report` may be NULL when not wanted.
///
/// NURBS handles (mathematics.md section 6, "Merge of B-splines"): two
/// polynomial B-splines (a Bezier handle counts as a one-span B-spline
/// when the other is a NURBS handle) are merged into a NURBS `merged` on
/// [0, 1] whose interior knots are p's mapped into (0, mu) and q's into
/// (mu, 1), with no knot at mu (one polynomial piece spans the join);
/// `p_hat` and `q_hat` are NURBS handles on p's and q's own knots and
/// parameters. Keep-point parameters are in each curve's domain. Two
/// Bezier handles give the Bezier result as before.
///
/// Guarantee: the KKT solve's error estimate and the check "merged split at
/// mu gives p_hat, q_hat" are both within 1e-8 relative, or the call fails
/// with BZJ_ERR_ILL_CONDITIONED.
///
/// @return BZJ_ERR_NULL_POINTER if `p`, `q`, `options` or `merged` is NULL,
///         or a point array is NULL with a non-zero count;
///         BZJ_ERR_INVALID_ARGUMENT if `mu` (with BZJ_SPLIT_GIVEN) is outside
///         (0, 1), a keep-point parameter is outside the curve's domain
///         ([0, 1] for a Bezier), an order is above the degree, an enum or
///         bool field holds an invalid value, a control polygon has zero
///         length or is too short next to the other for BZJ_SPLIT_POLYGON,
///         `p` or `q` is a rational NURBS handle (the message names it), or
///         B-spline inputs have more than 8194 poles together (after
///         elevation to the common degree; the merge's systems are dense);
///         BZJ_ERR_NON_FINITE if `mu` or a keep-point parameter is NaN/infinite;
///         BZJ_ERR_DIMENSION_MISMATCH if `p` and `q` differ in dimension;
///         BZJ_ERR_INCONSISTENT if the constraints contradict each other or are
///         too many (the message names the first offending one);
///         BZJ_ERR_SINGULAR / BZJ_ERR_ILL_CONDITIONED if the solve cannot be trusted.
///
/// # Safety
/// `p`, `q` are NULL or live handles; `options` is NULL or readable with its
/// point arrays holding their counts; `merged`, `p_hat`, `q_hat`, `report`
/// are NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_merge(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjMergeOptions,
    merged: *mut *mut BzjCurve,
    p_hat: *mut *mut BzjCurve,
    q_hat: *mut *mut BzjCurve,
    report: *mut BzjMergeReport,
) -> BzjStatus {
    // SAFETY: each is null or writable (caller contract).
    let [merged, p_hat, q_hat] = unsafe { merge_outputs(merged, p_hat, q_hat) };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let merged = merged.require()?;
        // SAFETY: caller contract.
        let options = unsafe { read_options(options) }?;
        let result = merge_curves(p, q, &options)?;
        // SAFETY: `report` null or writable (caller contract).
        unsafe { write_merge(result, merged, p_hat, q_hat, report) };
        Ok(())
    })
}

/// [`bzj_merge`] with a merged curve of degree `degree`, at least the higher
/// of the two curves' degrees: both are elevated to `degree` (exactly) and
/// the degree-`degree` problem is solved; keep-point orders may go up to
/// `degree`. A higher degree gives more freedom, so a smaller change.
///
/// @return as [`bzj_merge`]; BZJ_ERR_INVALID_ARGUMENT also if `degree` is
///         below a curve's degree.
///
/// # Safety
/// As [`bzj_merge`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_merge_to_degree(
    p: *const BzjCurve,
    q: *const BzjCurve,
    options: *const BzjMergeOptions,
    degree: usize,
    merged: *mut *mut BzjCurve,
    p_hat: *mut *mut BzjCurve,
    q_hat: *mut *mut BzjCurve,
    report: *mut BzjMergeReport,
) -> BzjStatus {
    // SAFETY: each is null or writable (caller contract).
    let [merged, p_hat, q_hat] = unsafe { merge_outputs(merged, p_hat, q_hat) };
    guard(|| {
        // SAFETY: caller contract.
        let (p, q) = unsafe { (curve_ref(p, "p")?, curve_ref(q, "q")?) };
        let merged = merged.require()?;
        // SAFETY: caller contract.
        let mut options = unsafe { read_options(options) }?;
        options.degree = Some(degree);
        let result = merge_curves(p, q, &options)?;
        // SAFETY: `report` null or writable (caller contract).
        unsafe { write_merge(result, merged, p_hat, q_hat, report) };
        Ok(())
    })
}

/// How the breakpoints of [`bzj_merge_chain`] are chosen.
#[repr(i32)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[allow(non_camel_case_types)]
pub enum BzjChainSplit {
    /// Use `options.breakpoints` (`curve_count - 1` interior values,
    /// strictly increasing in (0, 1), every piece at least 1e-6 of the
    /// range).
    BZJ_CHAIN_SPLIT_GIVEN = 0,
    /// `t_j = j / N`.
    BZJ_CHAIN_SPLIT_UNIFORM = 1,
    /// Proportional to the control-polygon lengths.
    BZJ_CHAIN_SPLIT_POLYGON = 2,
}

/// A point kept with derivatives on one curve of a chain.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjChainKeepPoint {
    /// Index of the curve in the chain.
    pub curve: usize,
    /// Parameter on that curve, in [0, 1].
    pub param: f64,
    /// Derivatives `0..=max_order` kept.
    pub max_order: usize,
}

/// Options of [`bzj_merge_chain`].
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct BzjChainMergeOptions {
    /// The metric, summed over the pieces.
    pub metric: BzjMetric,
    /// How the breakpoints are chosen.
    pub split: BzjChainSplit,
    /// `curve_count - 1` interior breakpoints for BZJ_CHAIN_SPLIT_GIVEN
    /// (may be NULL otherwise).
    pub breakpoints: *const f64,
    /// Number of `breakpoints`.
    pub breakpoint_count: usize,
    /// Degree of the merged curve; 0 means the highest degree of the curves.
    pub degree: usize,
    /// First point of the first curve and last point of the last unchanged.
    pub fix_ends: bool,
    /// `curve_count` flags "keep this curve unchanged", or NULL for none.
    pub keep: *const bool,
    /// Points kept with derivatives (may be NULL if the count is 0).
    pub keep_points: *const BzjChainKeepPoint,
    /// Number of `keep_points`.
    pub keep_point_count: usize,
}

#[repr(C)]
struct ChainOptionsMirror {
    metric: i32,
    split: i32,
    breakpoints: *const f64,
    breakpoint_count: usize,
    degree: usize,
    fix_ends: u8,
    keep: *const u8,
    keep_points: *const BzjChainKeepPoint,
    keep_point_count: usize,
}

const _: () = {
    assert!(size_of::<ChainOptionsMirror>() == size_of::<BzjChainMergeOptions>());
    assert!(align_of::<ChainOptionsMirror>() == align_of::<BzjChainMergeOptions>());
    assert!(size_of::<BzjChainSplit>() == size_of::<i32>());
    assert!(offset_of!(ChainOptionsMirror, split) == offset_of!(BzjChainMergeOptions, split));
    assert!(offset_of!(ChainOptionsMirror, fix_ends) == offset_of!(BzjChainMergeOptions, fix_ends));
    assert!(offset_of!(ChainOptionsMirror, keep) == offset_of!(BzjChainMergeOptions, keep));
    assert!(
        offset_of!(ChainOptionsMirror, keep_point_count)
            == offset_of!(BzjChainMergeOptions, keep_point_count)
    );
};

/// What [`bzj_merge_chain`] reports.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct BzjChainMergeReport {
    /// Sum of the pieces' metrics.
    pub metric_value: f64,
    /// Max distance between the merged curve on `[t_j, t_{j+1}]` and curve
    /// `j`, each in its own parameter (257 samples per curve).
    pub max_deviation: f64,
}

/// **Beyond the paper**: merge `curve_count >= 2` consecutive curves into
/// one Bezier curve. With breakpoints `0 = t_0 < ... < t_N = 1`, curve `j`
/// is changed as little as possible (sum of the metrics) into the piece of
/// `merged` on `[t_j, t_{j+1}]`; the pieces are one curve exactly when
/// `h_{j+1}^r C_j^(r)(1) = h_j^r C_{j+1}^(r)(0)` at every join (`h_j` the
/// interval lengths). With two curves this is [`bzj_merge`]. If any curve
/// is a NURBS handle, all are merged as polynomial B-splines into a NURBS
/// `merged` (each curve's interior knots mapped into its interval, none at
/// a breakpoint) and the pieces are NURBS handles on the curves' own knots.
///
/// Outputs: `merged` (required); `pieces` (NULL, or an array of
/// `piece_capacity >= curve_count` handles receiving the changed curves);
/// `breakpoints_out` (NULL, or `breakpoints_len >= curve_count + 1`
/// doubles receiving `t_0..t_N`); `report` (NULL or written).
///
/// @return BZJ_ERR_NULL_POINTER if `curves`, one of the handles, `options`
///         or `merged` is NULL, or an array is NULL with a non-zero count;
///         BZJ_ERR_BUFFER_TOO_SMALL if `piece_capacity < curve_count` or
///         `breakpoints_len < curve_count + 1` (their pointers non-NULL);
///         BZJ_ERR_INVALID_ARGUMENT if `curve_count < 2`, breakpoints are not
///         strictly increasing in (0, 1), leave a piece shorter than 1e-6
///         of the range (`MIN_SPLIT`) or are not `curve_count - 1` of them,
///         a keep point names a curve that does not exist, its parameter is
///         outside that curve's domain or its order above the degree,
///         `degree` is below a curve's degree, an enum/bool field is
///         invalid, or a curve is a rational NURBS handle;
///         BZJ_ERR_NON_FINITE, BZJ_ERR_DIMENSION_MISMATCH, BZJ_ERR_INCONSISTENT,
///         BZJ_ERR_SINGULAR, BZJ_ERR_ILL_CONDITIONED as for [`bzj_merge`].
///
/// # Safety
/// `curves` is NULL or points to `curve_count` handles (NULL or live);
/// `options` NULL or readable with its arrays holding their counts (`keep`:
/// `curve_count` bools); `merged` NULL or writable; `pieces` NULL or
/// `piece_capacity` writable handle slots; `breakpoints_out` NULL or
/// `breakpoints_len` writable doubles; `report` NULL or writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_merge_chain(
    curves: *const *const BzjCurve,
    curve_count: usize,
    options: *const BzjChainMergeOptions,
    merged: *mut *mut BzjCurve,
    pieces: *mut *mut BzjCurve,
    piece_capacity: usize,
    breakpoints_out: *mut f64,
    breakpoints_len: usize,
    report: *mut BzjChainMergeReport,
) -> BzjStatus {
    // SAFETY: caller contract: `merged` null or writable, `pieces` null or
    // `piece_capacity` writable slots.
    let (merged, pieces) = unsafe {
        (
            HandleOut::cleared(merged, "merged"),
            HandleArray::cleared(
                pieces,
                piece_capacity,
                "pieces",
                ShortArray::AsDoubles("pieces"),
            ),
        )
    };
    guard(|| {
        let merged = merged.require()?;
        if curves.is_null() {
            return Err(FfiError::NullPointer("curves".into()));
        }
        // SAFETY: caller promises `curve_count` handle pointers.
        let handles = unsafe { input_slice(curves, curve_count, "curves") }?;
        let mut owned: Vec<Curve> = Vec::with_capacity(handles.len());
        for (j, &h) in handles.iter().enumerate() {
            // SAFETY: each is null or a live handle.
            owned.push(unsafe { curve_ref(h, &format!("curves[{j}]")) }?.clone());
        }
        // SAFETY: same layout (asserted); null or readable.
        let o = unsafe { input_ref(options.cast::<ChainOptionsMirror>(), "options") }?;
        let metric = metric_from(o.metric, "options.metric")?;
        let breakpoints = match o.split {
            0 => {
                // SAFETY: caller promises the count.
                let b = unsafe {
                    input_slice(o.breakpoints, o.breakpoint_count, "options.breakpoints")
                }?;
                Breakpoints::Given(b.to_vec())
            }
            1 => Breakpoints::Uniform,
            2 => Breakpoints::PolygonLength,
            v => {
                return Err(BezjoinError::invalid(
                    "options.split",
                    format!("{v} is not a BzjChainSplit (0..2)"),
                )
                .into());
            }
        };
        let keep = if o.keep.is_null() {
            Vec::new()
        } else {
            // SAFETY: caller promises `curve_count` bools.
            let flags = unsafe { input_slice(o.keep, curve_count, "options.keep") }?;
            flags
                .iter()
                .enumerate()
                .map(|(j, &v)| bool_from(v, &format!("options.keep[{j}]")))
                .collect::<FfiResult<Vec<bool>>>()?
        };
        // SAFETY: caller promises the count.
        let points =
            unsafe { input_slice(o.keep_points, o.keep_point_count, "options.keep_points") }?;
        let options = ChainMergeOptions {
            metric,
            breakpoints,
            keep,
            fix_ends: bool_from(o.fix_ends, "options.fix_ends")?,
            keep_points: points
                .iter()
                .map(|k| ChainKeepPoint {
                    curve: k.curve,
                    point: KeepPoint {
                        param: k.param,
                        max_order: k.max_order,
                    },
                })
                .collect(),
            degree: if o.degree == 0 { None } else { Some(o.degree) },
            accuracy: bezjoin_core::DEFAULT_MERGE_ACCURACY,
        };
        // Check the output buffers before computing anything.
        let pieces = pieces.given();
        if let Some(pieces) = &pieces {
            pieces.check_room(curve_count)?;
        }
        let breakpoint_buffer = if breakpoints_out.is_null() {
            None
        } else {
            // SAFETY: caller promises `breakpoints_len` writable doubles.
            Some(unsafe {
                output_slice(
                    breakpoints_out,
                    breakpoints_len,
                    curve_count + 1,
                    "breakpoints_out",
                )
            }?)
        };
        let result = merge_curve_chain(&owned, &options)?;
        if let Some(buffer) = breakpoint_buffer {
            buffer.copy_from_slice(&result.report.breakpoints);
        }
        let summary = BzjChainMergeReport {
            metric_value: result.report.metric_value,
            max_deviation: result.report.max_deviation,
        };
        // SAFETY: NULL or writable (caller contract).
        unsafe { write_optional(report, summary) };
        if let Some(pieces) = pieces {
            pieces.write(result.pieces);
        }
        merged.write(result.merged);
        Ok(())
    })
}
