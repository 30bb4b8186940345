//! `bzj_merge_chain` on fuzzed chains of up to 16 curves (one dimension, or
//! mixed) with the options written the way a C host writes them: the enum
//! fields as arbitrary `int32_t`, the bools as arbitrary bytes, breakpoints
//! (increasing or any doubles, any count), a merged degree (also `SIZE_MAX`),
//! keep flags and up to 4 keep points (any curve index, parameter, order).
//! Counts lie downwards (shorter than the array) or are impossible (more than
//! `isize::MAX` bytes, which must be refused before anything is read); the
//! curve array, one of its handles, `options` and `merged` may be NULL
//! (`BZJ_ERR_NULL_POINTER`). The optional outputs (`pieces`,
//! `breakpoints_out`, `report`) are NULL or buffers with guard entries past
//! the declared length: on success `merged` and the first `curve_count`
//! pieces are live (and of the working degree), the breakpoints run from 0 to
//! 1 strictly increasing; after a failure nothing is written but NULLs.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

/// `BzjChainMergeOptions` as raw C data (any bit pattern in the enum and bool fields).
#[repr(C)]
struct RawChainOptions {
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
const _: () = assert!(size_of::<RawChainOptions>() == size_of::<BzjChainMergeOptions>());
const _: () = assert!(align_of::<RawChainOptions>() == align_of::<BzjChainMergeOptions>());

/// An enum value: mostly `0..=valid` (one past the last valid value), sometimes any `int32_t`.
fn enum_value(input: &mut Input, valid: u8) -> i32 {
    match input.byte() % 8 {
        0 => i32::from_le_bytes([input.byte(), input.byte(), input.byte(), input.byte()]),
        _ => i32::from(input.byte() % (valid + 2)),
    }
}

/// A C bool: mostly 0 or 1, sometimes any byte.
fn flag(input: &mut Input) -> u8 {
    match input.byte() % 8 {
        0 => input.byte(),
        b => b % 2,
    }
}

/// A declared count for an array of `len`: mostly `len`, sometimes less,
/// sometimes impossible.
fn declared(input: &mut Input, len: usize) -> usize {
    match input.byte() % 16 {
        0 => input.impossible_count(),
        1 | 2 => input.below(len + 1),
        _ => len,
    }
}

fn ptr_or_null<T>(v: &[T]) -> *const T {
    if v.is_empty() { null() } else { v.as_ptr() }
}

/// `count` interior breakpoints: mostly strictly increasing in (0, 1),
/// sometimes with one arbitrary double.
fn breakpoints(input: &mut Input, count: usize) -> Vec<f64> {
    let weights: Vec<f64> = (0..=count).map(|_| 1.0 + input.ordinary().abs()).collect();
    let total: f64 = weights.iter().sum();
    let mut sum = 0.0;
    let mut inner: Vec<f64> = weights[..count]
        .iter()
        .map(|w| {
            sum += w;
            sum / total
        })
        .collect();
    if !inner.is_empty() && input.byte().is_multiple_of(4) {
        let i = input.below(inner.len());
        inner[i] = input.double();
    }
    inner
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let n = input.below(MAX_CHAIN + 1);
    let one_dim = !input.byte().is_multiple_of(8);
    let dim = 1 + input.below(MAX_DIM);
    let mut handles = Vec::with_capacity(n);
    for _ in 0..n {
        let d = if one_dim {
            dim
        } else {
            1 + input.below(MAX_DIM)
        };
        if let Some(c) = curve_in(&mut input, d, MAX_DEGREE) {
            handles.push(c);
        }
    }
    let n = handles.len();
    let (curves, null_entry) = handle_array(&mut input, &handles);
    let curves_null = input.byte().is_multiple_of(32);
    let curve_count = if curves_null {
        input.size(MAX_CHAIN)
    } else {
        declared(&mut input, n)
    };
    let impossible_curves = curve_count > n;

    // Options.
    let metric = enum_value(&mut input, 1);
    let split = enum_value(&mut input, 2);
    let inner = if input.byte().is_multiple_of(8) {
        let len = input.below(n + 2);
        breakpoints(&mut input, len)
    } else {
        breakpoints(&mut input, n.saturating_sub(1))
    };
    let breakpoint_count = declared(&mut input, inner.len());
    let degree = if input.byte().is_multiple_of(4) {
        input.size(MAX_DEGREE)
    } else {
        0
    };
    let fix_ends = flag(&mut input);
    let keep: Vec<u8> = if input.byte().is_multiple_of(4) {
        (0..n).map(|_| flag(&mut input)).collect()
    } else {
        Vec::new()
    };
    let keep_points: Vec<BzjChainKeepPoint> = (0..input.below(5))
        .map(|_| BzjChainKeepPoint {
            curve: if input.byte().is_multiple_of(8) {
                input.size(MAX_CHAIN)
            } else {
                input.below(n.max(1))
            },
            param: input.parameter(),
            max_order: input.size(MAX_DEGREE + 2),
        })
        .collect();
    let keep_point_count = declared(&mut input, keep_points.len());
    let options = RawChainOptions {
        metric,
        split,
        breakpoints: if input.byte().is_multiple_of(16) {
            null()
        } else {
            ptr_or_null(&inner)
        },
        breakpoint_count,
        degree,
        fix_ends,
        // `keep` holds `n >= curve_count` flags whenever it is read (an
        // impossible `curve_count` is refused before).
        keep: ptr_or_null(&keep),
        keep_points: ptr_or_null(&keep_points),
        keep_point_count,
    };
    let options_null = input.byte().is_multiple_of(32);
    let options_ptr = if options_null {
        null()
    } else {
        (&raw const options).cast::<BzjChainMergeOptions>()
    };

    // Outputs.
    let merged_null = input.byte().is_multiple_of(32);
    let pieces_len = input.below(n + 3);
    let mut pieces = vec![sentinel(); pieces_len];
    let (pieces_ptr, piece_capacity) = if input.byte().is_multiple_of(3) {
        (null_mut(), input.size(MAX_CHAIN + 2))
    } else {
        let declared = if input.byte().is_multiple_of(4) {
            input.below(pieces_len + 1)
        } else {
            pieces_len
        };
        (pieces.as_mut_ptr(), declared)
    };
    let bp_len = input.below(n + 3);
    let mut bp = vec![f64::NAN; bp_len + 2];
    let (bp_ptr, breakpoints_len) = if input.byte().is_multiple_of(3) {
        (null_mut(), input.size(MAX_CHAIN + 2))
    } else {
        let declared = match input.byte() % 8 {
            0 => input.impossible_count(),
            1 => input.below(bp_len + 1),
            _ => bp_len,
        };
        (bp.as_mut_ptr(), declared)
    };
    let want_report = input.byte().is_multiple_of(2);
    let mut report = BzjChainMergeReport {
        metric_value: f64::NAN,
        max_deviation: f64::NAN,
    };

    let mut merged = sentinel();
    // SAFETY: `curves` holds `n` entries (a larger count is impossible and
    // refused before reading); the options' arrays hold at least their
    // declared counts (or the count is impossible); `pieces` holds
    // `pieces_len >= piece_capacity` slots, `bp` `bp_len + 2` doubles (more
    // than a possible `breakpoints_len`); every other pointer valid or NULL.
    let status = unsafe {
        bzj_merge_chain(
            if curves_null { null() } else { curves.as_ptr() },
            curve_count,
            options_ptr,
            if merged_null { null_mut() } else { &mut merged },
            pieces_ptr,
            piece_capacity,
            bp_ptr,
            breakpoints_len,
            if want_report {
                &raw mut report
            } else {
                null_mut()
            },
        )
    };
    let call = "bzj_merge_chain";
    check(status, call);

    // NULL where a value is required, in the order the contract checks.
    if merged_null || curves_null {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL merged/curves"
        );
    } else if impossible_curves {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_INVALID_ARGUMENT,
            "{call}: curve_count = {curve_count} with {n} curves"
        );
    } else if null_entry.is_some_and(|i| i < curve_count) || options_null {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL handle/options"
        );
    }
    if bp_ptr.is_null() {
        // Nothing to check.
    } else if breakpoints_len > bp_len {
        assert_ne!(
            status,
            BzjStatus::BZJ_OK,
            "{call}: breakpoints_len = {breakpoints_len}"
        );
    }

    if merged_null {
        assert_eq!(merged, sentinel(), "{call} wrote through a NULL merged");
    } else if status == BzjStatus::BZJ_OK {
        // The merged degree is the highest degree of the curves or the one asked for.
        let highest = handles[..curve_count]
            .iter()
            .map(|&h| {
                let mut d = 0;
                // SAFETY: live handle, writable out-pointer.
                unsafe { bzj_curve_degree(h, &mut d) };
                d
            })
            .max()
            .unwrap_or(0);
        let mut got = 0;
        // SAFETY: a live handle the library just returned.
        unsafe { bzj_curve_degree(merged, &mut got) };
        let expected = if degree == 0 { highest } else { degree };
        assert_eq!(got, expected, "{call}: merged degree");
        check_and_free(status, merged, call);
    } else {
        assert!(merged.is_null(), "{call}: merged not NULL after {status:?}");
    }

    let written = if status == BzjStatus::BZJ_OK {
        curve_count
    } else {
        0
    };
    if pieces_ptr.is_null() {
        assert!(pieces.iter().all(|&s| s == sentinel()));
    } else {
        check_handle_slots(status, &pieces, written, piece_capacity, call);
    }

    if status == BzjStatus::BZJ_OK && !bp_ptr.is_null() {
        let t = &bp[..curve_count + 1];
        assert!(
            t[0] == 0.0 && t[curve_count] == 1.0,
            "{call}: breakpoints {t:?}"
        );
        assert!(
            t.windows(2).all(|w| w[0] < w[1]),
            "{call}: breakpoints not increasing {t:?}"
        );
        assert!(
            bp[curve_count + 1..].iter().all(|x| x.is_nan()),
            "{call} wrote past curve_count + 1 breakpoints"
        );
    } else {
        assert!(
            bp.iter().all(|x| x.is_nan()),
            "{call} wrote breakpoints after {status:?}"
        );
    }
    if status == BzjStatus::BZJ_OK && want_report {
        assert!(
            report.metric_value >= 0.0 && report.max_deviation >= 0.0,
            "{call}: report {report:?}"
        );
    } else {
        assert!(report.metric_value.is_nan() && report.max_deviation.is_nan());
    }
    free_all(&handles);
});
