//! Splines whose defining points lie on the curve (mathematics.md, section 4;
//! Kovtun, seed 004): cubic Lagrange-form segments joined C^1 by a local
//! recurrence ([`bzj_lagrange_spline`], the published contract), and the
//! degree 4/5, C^2/C^3, backward and mirrored variants
//! ([`bzj_lagrange_spline_degree`]). The math and its error-growth facts are
//! documented in `bezjoin_core::lagrange`.

use bezjoin_core::BezierCurve;
use bezjoin_core::BezjoinError;
use bezjoin_core::{BuildDirection, DerivedPoints, LagrangeOptions, lagrange_spline};

use crate::guard::guard;
use crate::handles::{BzjCurve, HandleArray, ShortArray};
use crate::pointers::input_slice;
use crate::status::{BzjStatus, FfiError, FfiResult};

/// Flag for [`bzj_lagrange_spline_degree`]: build from the last segment
/// backwards (the last segment's inner points are all given).
pub const BZJ_LAGRANGE_BACKWARD: u32 = 1;
/// Flag for [`bzj_lagrange_spline_degree`]: derive the inner points farthest
/// from the join instead of the nearest (the mirrored variant; errors grow
/// by a factor `degree - 1` or more per node: short chains only).
pub const BZJ_LAGRANGE_MIRRORED: u32 = 2;

/// `a * b` for a length, or INVALID_ARGUMENT naming `name`.
fn length(name: &str, factors: &[usize]) -> FfiResult<usize> {
    factors
        .iter()
        .try_fold(1usize, |acc, &f| acc.checked_mul(f))
        .ok_or_else(|| FfiError::Core(BezjoinError::invalid(name, "length overflows size_t")))
}

/// The caller's `out_segments`, not yet written: BUFFER_TOO_SMALL writes
/// nothing, so the slots are cleared only once their room is checked.
///
/// # Safety
/// `out_segments` is NULL or points to `segment_capacity` writable handle
/// pointers.
unsafe fn segments_array(out_segments: *mut *mut BzjCurve, segment_capacity: usize) -> HandleArray {
    // SAFETY: forwarded.
    unsafe {
        HandleArray::untouched(
            out_segments,
            segment_capacity,
            "out_segments",
            ShortArray::Handles,
        )
    }
}

/// The shared body: checks the handle array, builds, writes the handles only
/// when everything succeeded (so an error leaks nothing).
///
/// # Safety
/// As for the public functions.
#[allow(clippy::too_many_arguments)]
unsafe fn build_into(
    dim: usize,
    node_count: usize,
    nodes: *const f64,
    params: *const f64,
    start_inner: (*const f64, &str),
    free_inner: (*const f64, &str),
    options: &LagrangeOptions,
    out_segments: HandleArray,
) -> FfiResult {
    let out = out_segments.require()?;
    if node_count < 2 {
        return Err(BezjoinError::invalid(
            "node_count",
            format!("at least 2 nodes are needed, got {node_count}"),
        )
        .into());
    }
    let segment_count = node_count - 1;
    out.check_room(segment_count)?;
    out.clear_first(segment_count);
    options.validate()?;
    // dim == 0 makes every length 0 (nothing is read); the core refuses it.
    let node_len = length("nodes", &[node_count, dim])?;
    let start_len = length(start_inner.1, &[options.degree - 1, dim])?;
    let free_len = length(
        free_inner.1,
        &[node_count - 2, options.free_points_per_segment(), dim],
    )?;
    // SAFETY: caller contract: each array holds the documented number of doubles.
    let nodes = unsafe { input_slice(nodes, node_len, "nodes") }?;
    // SAFETY: as above.
    let start = unsafe { input_slice(start_inner.0, start_len, start_inner.1) }?;
    // SAFETY: as above.
    let free = unsafe { input_slice(free_inner.0, free_len, free_inner.1) }?;
    let params = if params.is_null() {
        None
    } else {
        // SAFETY: non-null, the caller promises `node_count` doubles.
        Some(unsafe { input_slice(params, node_count, "params") }?)
    };
    let spline = lagrange_spline(dim, nodes, params, start, free, options).map_err(|e| {
        // name the arrays as the C caller knows them
        FfiError::Core(rename(e, start_inner.1, free_inner.1))
    })?;
    let segments: Vec<BezierCurve> = spline.into_segments();
    out.write(segments);
    Ok(())
}

/// Core errors name `start_inner` / `free_inner`; the C functions call them
/// `first_inner` / `second_inner` (contract) or the same (new function).
fn rename(error: BezjoinError, start: &str, free: &str) -> BezjoinError {
    let fix = |name: String| match name.as_str() {
        "start_inner" => start.to_string(),
        "free_inner" => free.to_string(),
        _ => name,
    };
    match error {
        BezjoinError::LengthMismatch {
            name,
            expected,
            actual,
        } => BezjoinError::LengthMismatch {
            name: fix(name),
            expected,
            actual,
        },
        BezjoinError::NonFinite { name, index, value } => BezjoinError::NonFinite {
            name: fix(name),
            index,
            value,
        },
        other => other,
    }
}

/// A spline of cubic segments, each given by four points ON it at local
/// parameters `u = 0, 1/3, 2/3, 1`, joined C^1 in a global parameter
/// (Kovtun's construction, mathematics.md section 4), written as
/// `node_count - 1` cubic Bezier handles.
///
/// * `nodes`: `node_count * dim` doubles; `params`: `node_count` strictly
///   increasing global parameters, or NULL for chord length;
/// * `first_inner`: `2 * dim` doubles, the points at `u = 1/3, 2/3` of
///   segment 0;
/// * `second_inner`: `(node_count - 2) * dim` doubles, the point at
///   `u = 2/3` of each later segment (may be NULL when `node_count == 2`);
///   the point at `u = 1/3` follows from C^1 (errors halve per node);
/// * `out_segments`: caller array of `segment_capacity >= node_count - 1`
///   handles; on success entry `i` is segment `i` (release each with
///   `bzj_curve_free`).
///
/// @return BZJ_ERR_NULL_POINTER if `out_segments`, `nodes`, `first_inner`,
///         or (with `node_count > 2`) `second_inner` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `dim == 0`, `node_count < 2`, `params`
///         is not strictly increasing, consecutive nodes coincide with chord
///         length (NULL `params`);
///         BZJ_ERR_NON_FINITE if any value is NaN or infinite;
///         BZJ_ERR_BUFFER_TOO_SMALL if `segment_capacity < node_count - 1`
///         (nothing is written);
///         BZJ_ERR_ILL_CONDITIONED if the result fails its own checks.
///         On every error the first `node_count - 1` entries of `out_segments`
///         are NULL when `segment_capacity` holds them (a shorter array is
///         not written, whatever the error) and nothing is leaked.
///
/// # Safety
/// Every non-NULL pointer points to the number of doubles stated above;
/// `out_segments` points to `segment_capacity` writable handle pointers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn bzj_lagrange_spline(
    dim: usize,
    node_count: usize,
    nodes: *const f64,
    params: *const f64,
    first_inner: *const f64,
    second_inner: *const f64,
    out_segments: *mut *mut BzjCurve,
    segment_capacity: usize,
) -> BzjStatus {
    // SAFETY: caller contract.
    let out_segments = unsafe { segments_array(out_segments, segment_capacity) };
    guard(|| {
        // SAFETY: forwarded caller contract.
        unsafe {
            build_into(
                dim,
                node_count,
                nodes,
                params,
                (first_inner, "first_inner"),
                (second_inner, "second_inner"),
                &LagrangeOptions::default(),
                out_segments,
            )
        }
    })
}

/// The generalisation of [`bzj_lagrange_spline`]: segments of degree
/// `degree` (3, 4 or 5) through points ON them at `u = j / degree`, joined
/// C^`continuity` (`1 ..= degree - 2`) at every node.
///
/// * `flags`: 0, or a combination of [`BZJ_LAGRANGE_BACKWARD`] (start from
///   the last segment) and [`BZJ_LAGRANGE_MIRRORED`] (derive the inner points
///   farthest from the join; errors grow fast: short chains only);
/// * `start_inner`: `(degree - 1) * dim` doubles, all inner points
///   (`u = 1/n .. (n-1)/n`) of the starting segment (segment 0, or the last
///   with BACKWARD);
/// * `free_inner`: `(node_count - 2) * (degree - 1 - continuity) * dim`
///   doubles: for every other segment in increasing segment order its free
///   inner points in increasing `u`. Without flags the derived points are
///   `u = 1/n .. continuity/n` and the free ones the rest (e.g. degree 5,
///   C^2: give `u = 3/5, 4/5`); MIRRORED or BACKWARD alone swaps the two
///   ends, both together restore it. May be NULL when its length is 0.
/// * `out_segments` as for [`bzj_lagrange_spline`].
///
/// `degree = 3, continuity = 1, flags = 0` is exactly `bzj_lagrange_spline`.
/// Every C^2 and C^3 recurrence amplifies errors from node to node (factor
/// about 2.4 to 12 per node, documented in the Rust crate); results whose
/// estimated error exceeds 1e-9 are refused with BZJ_ERR_ILL_CONDITIONED.
///
/// @return BZJ_ERR_NULL_POINTER if `out_segments`, `nodes`, `start_inner` or
///         a non-empty `free_inner` is NULL;
///         BZJ_ERR_INVALID_ARGUMENT if `degree` is not 3, 4 or 5,
///         `continuity` is not in `1 ..= degree - 2`, `flags` has unknown
///         bits, `dim == 0`, `node_count < 2`, `params` is not strictly
///         increasing, or consecutive nodes coincide with chord length;
///         BZJ_ERR_NON_FINITE if any value is NaN or infinite;
///         BZJ_ERR_BUFFER_TOO_SMALL if `segment_capacity < node_count - 1`
///         (nothing is written);
///         BZJ_ERR_ILL_CONDITIONED if the recurrence amplifies rounding
///         beyond 1e-9 or the result fails its own checks.
///         On every error the first `node_count - 1` entries of `out_segments`
///         are NULL when `segment_capacity` holds them (a shorter array is
///         not written, whatever the error) and nothing is leaked.
///
/// # Safety
/// Every non-NULL pointer points to the number of doubles stated above;
/// `out_segments` points to `segment_capacity` writable handle pointers.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn bzj_lagrange_spline_degree(
    dim: usize,
    degree: usize,
    continuity: usize,
    flags: u32,
    node_count: usize,
    nodes: *const f64,
    params: *const f64,
    start_inner: *const f64,
    free_inner: *const f64,
    out_segments: *mut *mut BzjCurve,
    segment_capacity: usize,
) -> BzjStatus {
    // SAFETY: caller contract.
    let out_segments = unsafe { segments_array(out_segments, segment_capacity) };
    guard(|| {
        let known = BZJ_LAGRANGE_BACKWARD | BZJ_LAGRANGE_MIRRORED;
        if flags & !known != 0 {
            // validate the handle array first so the error contract holds
            if let Some(out) = out_segments.given() {
                if node_count >= 2 && out.has_room(node_count - 1) {
                    out.clear_first(node_count - 1);
                }
            }
            return Err(BezjoinError::invalid(
                "flags",
                format!(
                    "{flags:#x} has bits other than BZJ_LAGRANGE_BACKWARD | BZJ_LAGRANGE_MIRRORED"
                ),
            )
            .into());
        }
        let options = LagrangeOptions::default()
            .with_degree(degree)
            .with_continuity(continuity)
            .with_direction(if flags & BZJ_LAGRANGE_BACKWARD != 0 {
                BuildDirection::Backward
            } else {
                BuildDirection::Forward
            })
            .with_derived(if flags & BZJ_LAGRANGE_MIRRORED != 0 {
                DerivedPoints::FarFromJoin
            } else {
                DerivedPoints::NextToJoin
            });
        // SAFETY: forwarded caller contract.
        unsafe {
            build_into(
                dim,
                node_count,
                nodes,
                params,
                (start_inner, "start_inner"),
                (free_inner, "free_inner"),
                &options,
                out_segments,
            )
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bzj_curve_free;
    use bezjoin_core::lagrange_spline;

    #[test]
    fn contract_function_equals_the_core_default() {
        let nodes = [0.0, 0.0, 1.0, 0.5, 2.0, 0.0, 3.0, 1.0];
        let first = [0.3, 0.2, 0.7, 0.4];
        let second = [1.7, 0.3, 2.6, 0.5];
        let mut out = [std::ptr::null_mut(); 4];
        let s = unsafe {
            bzj_lagrange_spline(
                2,
                4,
                nodes.as_ptr(),
                std::ptr::null(),
                first.as_ptr(),
                second.as_ptr(),
                out.as_mut_ptr(),
                4,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_OK);
        let core = lagrange_spline(
            2,
            &nodes,
            None,
            &first,
            &second,
            &LagrangeOptions::default(),
        )
        .unwrap();
        for (i, seg) in core.segments().iter().enumerate() {
            let h = unsafe { &*out[i] };
            assert_eq!(h.curve.points(), seg.points());
        }
        assert!(out[3].is_null());
        for h in out {
            unsafe { bzj_curve_free(h) };
        }
    }

    #[test]
    fn buffer_too_small_writes_nothing_and_errors_clear_handles() {
        let nodes = [0.0, 1.0, 2.0];
        let first = [0.3, 0.6];
        let second = [1.6];
        let marker = 0x10 as *mut BzjCurve;
        let mut out = [marker; 2];
        let s = unsafe {
            bzj_lagrange_spline(
                1,
                3,
                nodes.as_ptr(),
                std::ptr::null(),
                first.as_ptr(),
                second.as_ptr(),
                out.as_mut_ptr(),
                1,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL);
        assert_eq!(out, [marker; 2]);
        let bad = [0.3, f64::NAN];
        let s = unsafe {
            bzj_lagrange_spline(
                1,
                3,
                nodes.as_ptr(),
                std::ptr::null(),
                bad.as_ptr(),
                second.as_ptr(),
                out.as_mut_ptr(),
                2,
            )
        };
        assert_eq!(s, BzjStatus::BZJ_ERR_NON_FINITE);
        assert!(out.iter().all(|p| p.is_null()));
        let msg = unsafe { std::ffi::CStr::from_ptr(crate::bzj_last_error()) };
        assert_eq!(msg.to_str().unwrap(), "first_inner[1] = NaN is not finite");
    }
}
