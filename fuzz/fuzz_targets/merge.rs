//! `bzj_merge` and `bzj_merge_to_degree` on fuzzed curve pairs (also of
//! different dimensions) with fuzzed options written the way a C host
//! writes them: the enum fields as arbitrary `int32_t`, the bools as
//! arbitrary bytes, `mu` any double, up to 4 keep points per curve with
//! fuzzed parameters and orders, optional outputs NULL or not.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

/// `BzjMergeOptions` as raw C data (any bit pattern in the enum and bool fields).
#[repr(C)]
struct RawMergeOptions {
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
const _: () = assert!(size_of::<RawMergeOptions>() == size_of::<BzjMergeOptions>());
const _: () = assert!(align_of::<RawMergeOptions>() == align_of::<BzjMergeOptions>());

fn small_int(input: &mut Input) -> i32 {
    match input.byte() % 8 {
        0 => i32::from_le_bytes([input.byte(), input.byte(), input.byte(), input.byte()]),
        _ => i32::from(input.byte() % 5),
    }
}

fn flag(input: &mut Input) -> u8 {
    match input.byte() % 8 {
        0 => input.byte(),
        b => b % 2,
    }
}

fn keep_points(input: &mut Input) -> Vec<BzjKeepPoint> {
    (0..input.below(5))
        .map(|_| BzjKeepPoint {
            param: input.parameter(),
            max_order: input.size(MAX_DEGREE + 2),
        })
        .collect()
}

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let p_points = keep_points(&mut input);
    let q_points = keep_points(&mut input);
    let options = RawMergeOptions {
        metric: small_int(&mut input),
        split: small_int(&mut input),
        mu: if input.byte().is_multiple_of(2) {
            input.parameter()
        } else {
            input.double()
        },
        keep_p: flag(&mut input),
        keep_q: flag(&mut input),
        fix_ends: flag(&mut input),
        p_points: if p_points.is_empty() {
            null()
        } else {
            p_points.as_ptr()
        },
        p_point_count: p_points.len(),
        q_points: if q_points.is_empty() {
            null()
        } else {
            q_points.as_ptr()
        },
        q_point_count: q_points.len(),
    };
    let options_ptr = (&raw const options).cast::<BzjMergeOptions>();
    let want_hats = input.byte().is_multiple_of(2);
    let want_report = input.byte().is_multiple_of(2);
    let to_degree = input.byte().is_multiple_of(3);
    let degree = input.below(MAX_DEGREE + 1);

    let (mut merged, mut p_hat, mut q_hat) = (null_mut(), null_mut(), null_mut());
    let mut report = BzjMergeReport {
        mu: f64::NAN,
        metric_value: f64::NAN,
        max_deviation: f64::NAN,
    };
    let hat = |h: &mut *mut BzjCurve| if want_hats { h as *mut _ } else { null_mut() };
    let report_ptr = if want_report {
        &raw mut report
    } else {
        null_mut()
    };
    // SAFETY: live handles; options readable with its arrays holding their
    // counts; every out-pointer valid or NULL.
    let status = unsafe {
        if to_degree {
            bzj_merge_to_degree(
                p,
                q,
                options_ptr,
                degree,
                &mut merged,
                hat(&mut p_hat),
                hat(&mut q_hat),
                report_ptr,
            )
        } else {
            bzj_merge(
                p,
                q,
                options_ptr,
                &mut merged,
                hat(&mut p_hat),
                hat(&mut q_hat),
                report_ptr,
            )
        }
    };
    let call = if to_degree {
        "bzj_merge_to_degree"
    } else {
        "bzj_merge"
    };
    check_and_free(status, merged, call);
    if want_hats {
        check_and_free(status, p_hat, call);
        check_and_free(status, q_hat, call);
    }
    if status == BzjStatus::BZJ_OK && want_report {
        assert!(
            report.mu > 0.0 && report.mu < 1.0,
            "{call}: report.mu = {}",
            report.mu
        );
        assert!(
            report.metric_value >= 0.0,
            "{call}: metric_value = {}",
            report.metric_value
        );
        assert!(
            report.max_deviation >= 0.0,
            "{call}: max_deviation = {}",
            report.max_deviation
        );
    }
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
