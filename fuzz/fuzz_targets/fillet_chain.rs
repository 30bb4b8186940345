//! `bzj_fillet_chain`, `bzj_fillet_chain_auto_scale` and
//! `bzj_fillet_radius_chain` (radius and order from the fuzzed options) on
//! fuzzed chains of up to 16 curves (one dimension, or
//! mixed; each curve either fuzzed freely or a segment overshooting a fuzzed
//! polygon's vertices, so that consecutive curves cross near their shared
//! end) with fuzzed setbacks (any double), orders (also `SIZE_MAX`), scales
//! and `closed` (any `int32_t`). The curve count lies downwards or is
//! impossible (more than `isize::MAX` bytes, refused before reading);
//! `curves`, one of its handles, `options`, `count` or `out_pieces` may be
//! NULL (`BZJ_ERR_NULL_POINTER`), the capacity any size with a NULL
//! `out_pieces` (0 is the count-only query) and at most the array otherwise.
//! On success the first `count` slots hold live handles, `count` is
//! `2 n - 1` (open) or `2 n` (closed); the other declared slots are NULL
//! (all of them after a failure) and nothing past the declared capacity is
//! written.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

/// A segment from `a` to `b` (overshooting both by `1/8` of its length),
/// with `degree - 1` fuzzed interior points near the line.
fn overshooting(input: &mut Input, a: &[f64], b: &[f64], degree: usize) -> Option<*mut BzjCurve> {
    let dim = a.len();
    let mut points = Vec::with_capacity((degree + 1) * dim);
    for i in 0..=degree {
        let s = -0.125 + 1.25 * i as f64 / degree as f64;
        let bend = if i == 0 || i == degree {
            0.0
        } else {
            input.ordinary() / 20.0
        };
        points.extend((0..dim).map(|k| a[k] + s * (b[k] - a[k]) + bend));
    }
    let mut out = null_mut();
    // SAFETY: `points` holds `points.len()` doubles; `out` is writable.
    let status = unsafe { bzj_curve_new(dim, degree, points.as_ptr(), points.len(), &mut out) };
    check(status, "bzj_curve_new");
    (status == BzjStatus::BZJ_OK).then_some(out)
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let n = input.below(MAX_CHAIN + 1);
    let one_dim = !input.byte().is_multiple_of(8);
    let dim = 1 + input.below(MAX_DIM);
    let vertices: Vec<Vec<f64>> = (0..=n)
        .map(|_| (0..dim).map(|_| input.coordinate()).collect())
        .collect();
    let mut handles = Vec::with_capacity(n);
    for i in 0..n {
        let c = if one_dim && !input.byte().is_multiple_of(4) {
            let degree = 1 + input.below(6);
            // A closed chain wants the last segment to return to the start.
            let end = if i + 1 == n {
                &vertices[0]
            } else {
                &vertices[i + 1]
            };
            let end = if input.byte().is_multiple_of(2) {
                &vertices[i + 1]
            } else {
                end
            };
            overshooting(&mut input, &vertices[i], end, degree)
        } else {
            let d = if one_dim {
                dim
            } else {
                1 + input.below(MAX_DIM)
            };
            curve_in(&mut input, d, MAX_DEGREE)
        };
        handles.extend(c);
    }
    let n = handles.len();
    let (curves, null_entry) = handle_array(&mut input, &handles);
    let curves_null = input.byte().is_multiple_of(32);
    let curve_count = match input.byte() % 16 {
        _ if curves_null => input.size(MAX_CHAIN),
        0 => input.impossible_count(),
        1 | 2 => input.below(n + 1),
        _ => n,
    };
    let options = fillet_options(&mut input);
    let options_null = input.byte().is_multiple_of(32);
    let closed = match input.byte() % 8 {
        0 => i32::from_le_bytes([input.byte(), input.byte(), input.byte(), input.byte()]),
        b => i32::from(b % 2),
    };
    let closed_valid = closed == 0 || closed == 1;
    let pieces_len = input.below(2 * n + 3);
    let mut pieces = vec![sentinel(); pieces_len];
    let (pieces_ptr, capacity) = match input.byte() % 8 {
        // The count-only query, or a NULL array with any capacity.
        0 => (null_mut(), 0),
        1 => (null_mut(), input.size(2 * MAX_CHAIN + 2)),
        2 => (pieces.as_mut_ptr(), input.below(pieces_len + 1)),
        _ => (pieces.as_mut_ptr(), pieces_len),
    };
    let count_null = input.byte().is_multiple_of(32);
    let mut count = usize::MAX;
    // Read last, so that inputs written for `bzj_fillet_chain` alone still
    // decode as before (an exhausted input reads 0: that function).
    let variant = match input.byte() % 8 {
        5 => Variant::AutoScale,
        6 | 7 => Variant::Radius,
        _ => Variant::Setbacks,
    };
    let extras_null = input.byte().is_multiple_of(4);
    // Corner outputs: one per corner at most (`n` for a closed chain).
    let mut scales = vec![f64::NAN; n];
    let mut reports = vec![BzjRadiusFilletReport::default(); n];
    let scales_ptr = if extras_null {
        null_mut()
    } else {
        scales.as_mut_ptr()
    };
    let reports_ptr = if extras_null {
        null_mut()
    } else {
        reports.as_mut_ptr()
    };
    let options_null = options_null && variant != Variant::Radius;

    // SAFETY: `curves` holds `n` entries (a larger count is impossible and
    // refused before reading); options readable or NULL; `pieces` holds
    // `pieces_len >= capacity` slots (or the pointer is NULL); `count`
    // writable or NULL.
    let curves_ptr = if curves_null { null() } else { curves.as_ptr() };
    let options_ptr = if options_null {
        null()
    } else {
        &raw const options
    };
    let count_ptr = if count_null {
        null_mut()
    } else {
        &raw mut count
    };
    // SAFETY: as above; `scales` and `reports` hold `n` entries, at least
    // the corner count of any chain that reaches them.
    let (status, call) = unsafe {
        match variant {
            Variant::Setbacks => (
                bzj_fillet_chain(
                    curves_ptr,
                    curve_count,
                    options_ptr,
                    closed,
                    pieces_ptr,
                    capacity,
                    count_ptr,
                ),
                "bzj_fillet_chain",
            ),
            Variant::AutoScale => (
                bzj_fillet_chain_auto_scale(
                    curves_ptr,
                    curve_count,
                    options_ptr,
                    closed,
                    pieces_ptr,
                    capacity,
                    count_ptr,
                    scales_ptr,
                ),
                "bzj_fillet_chain_auto_scale",
            ),
            Variant::Radius => (
                bzj_fillet_radius_chain(
                    curves_ptr,
                    curve_count,
                    options.p_setback,
                    options.p_order,
                    closed,
                    pieces_ptr,
                    capacity,
                    count_ptr,
                    reports_ptr,
                ),
                "bzj_fillet_radius_chain",
            ),
        }
    };
    check(status, call);

    // The contract's checks, in order.
    // (Saturating: `curve_count` may be impossible.)
    let needed = match closed {
        1 => curve_count.saturating_mul(2),
        _ => curve_count.saturating_mul(2).saturating_sub(1),
    };
    let count_only = pieces_ptr.is_null() && capacity == 0;
    if count_null || curves_null || options_null {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL argument"
        );
    } else if !closed_valid || curve_count > n {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
            "{call}: closed = {closed}, curve_count = {curve_count} of {n}"
        );
    } else if null_entry.is_some_and(|i| i < curve_count) {
        // Refused before the count, also in a count-only query.
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL handle"
        );
    } else if curve_count < 2 {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
            "{call}: fewer than 2 curves"
        );
    } else {
        assert_eq!(count, needed, "{call}: count");
        if count_only {
            assert_eq!(status, BzjStatus::BZJ_OK, "{call}: count-only query");
        } else if pieces_ptr.is_null() {
            assert_eq!(
                status,
                BzjStatus::BZJ_ERR_NULL_POINTER,
                "{call}: NULL array"
            );
        } else if capacity < needed {
            assert_eq!(
                status,
                BzjStatus::BZJ_ERR_BUFFER_TOO_SMALL,
                "{call}: capacity"
            );
        }
    }
    if count_null
        || curves_null
        || options_null
        || !closed_valid
        || curve_count > n
        || null_entry.is_some_and(|i| i < curve_count)
        || curve_count < 2
    {
        assert_eq!(count, usize::MAX, "{call} wrote count before refusing");
    }
    if pieces_ptr.is_null() {
        assert!(pieces.iter().all(|&s| s == sentinel()));
    } else {
        let written = if status == BzjStatus::BZJ_OK {
            needed
        } else {
            0
        };
        check_handle_slots(status, &pieces, written, capacity, call);
    }
    // Corner outputs: written on success only, one per corner, finite.
    let corners = if closed == 1 {
        curve_count
    } else {
        curve_count.saturating_sub(1)
    };
    if !extras_null {
        for i in 0..n {
            let written = status == BzjStatus::BZJ_OK && !count_only && i < corners;
            match variant {
                Variant::AutoScale if written => {
                    assert!(
                        scales[i] > 0.0 && scales[i].is_finite(),
                        "{call}: scale {i} = {}",
                        scales[i]
                    );
                }
                Variant::AutoScale => assert!(scales[i].is_nan(), "{call}: scale {i} written"),
                Variant::Radius if written => {
                    let r = &reports[i];
                    assert!(
                        r.arc_deviation >= 0.0 && r.u0.is_finite() && r.v0.is_finite(),
                        "{call}: report {i} = {r:?}"
                    );
                }
                Variant::Radius => {
                    assert!(
                        reports[i].u0 == 0.0 && reports[i].arc_deviation == 0.0,
                        "{call}: report {i} written"
                    );
                }
                Variant::Setbacks => {}
            }
        }
    }
    free_all(&handles);
});

/// Which chain function the input calls.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Variant {
    /// `bzj_fillet_chain`.
    Setbacks,
    /// `bzj_fillet_chain_auto_scale`.
    AutoScale,
    /// `bzj_fillet_radius_chain` (radius = the fuzzed `p_setback`, order =
    /// the fuzzed `p_order`).
    Radius,
}
