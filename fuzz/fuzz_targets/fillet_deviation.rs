//! `bzj_fillet_deviation` on fuzzed curve pairs with fuzzed deviation bounds
//! and setback ratios (ordinary positive values or any double), orders (also
//! `SIZE_MAX`) and scales; sometimes `p`, `q`, `options` or one out-pointer
//! NULL (`BZJ_ERR_NULL_POINTER`), `report` NULL or not. On success the three
//! handles are live and the report holds positive setbacks with
//! `q_setback = setback_ratio * p_setback`, a deviation within 1e-9 relative
//! of `max_deviation`, and cut parameters inside (0, 1); after a failure the
//! handles are NULL and the report is not written.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let options = BzjDeviationFilletOptions {
        max_deviation: if input.byte().is_multiple_of(4) {
            input.double()
        } else {
            input.ordinary().abs() / 50.0
        },
        setback_ratio: match input.byte() % 4 {
            0 => input.double(),
            1 => input.ordinary().abs() / 20.0,
            _ => 1.0,
        },
        p_order: input.size(6),
        q_order: input.size(6),
        p_scale: if input.byte().is_multiple_of(4) {
            input.double()
        } else {
            1.0
        },
        q_scale: if input.byte().is_multiple_of(4) {
            input.double()
        } else {
            1.0
        },
    };
    let drop_one = input.byte() % 16;
    let want_report = input.byte().is_multiple_of(2);
    let blank = BzjDeviationFilletReport {
        p_setback: f64::NAN,
        q_setback: f64::NAN,
        deviation: f64::NAN,
        u0: f64::NAN,
        v0: f64::NAN,
    };
    let mut report = blank;
    let (mut a, mut b, mut c) = (null_mut(), null_mut(), null_mut());
    let pa: *mut *mut BzjCurve = if drop_one == 4 { null_mut() } else { &mut a };
    let pb: *mut *mut BzjCurve = if drop_one == 5 { null_mut() } else { &mut b };
    let pc: *mut *mut BzjCurve = if drop_one == 6 { null_mut() } else { &mut c };
    // SAFETY: handles live or NULL, options readable or NULL, out-pointers
    // and report valid or NULL.
    let status = unsafe {
        bzj_fillet_deviation(
            if drop_one == 1 { null() } else { p },
            if drop_one == 2 { null() } else { q },
            if drop_one == 3 { null() } else { &options },
            pa,
            pb,
            pc,
            if want_report {
                &raw mut report
            } else {
                null_mut()
            },
        )
    };
    let call = "bzj_fillet_deviation";
    if (1..=6).contains(&drop_one) {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "{call}: NULL argument"
        );
    }
    check_and_free(status, a, call);
    check_and_free(status, b, call);
    check_and_free(status, c, call);
    if status == BzjStatus::BZJ_OK && want_report {
        let r = report;
        let eps = options.max_deviation;
        assert!(r.p_setback > 0.0 && r.q_setback > 0.0, "{call}: {r:?}");
        assert_eq!(
            r.q_setback,
            options.setback_ratio * r.p_setback,
            "{call}: {r:?}"
        );
        assert!(
            (r.deviation - eps).abs() / eps <= 1e-9,
            "{call}: deviation {} for max_deviation {eps}: {r:?}",
            r.deviation
        );
        assert!(
            r.u0 > 0.0 && r.u0 < 1.0 && r.v0 > 0.0 && r.v0 < 1.0,
            "{call}: {r:?}"
        );
    } else {
        let r = report;
        assert!(
            r.p_setback.is_nan()
                && r.q_setback.is_nan()
                && r.deviation.is_nan()
                && r.u0.is_nan()
                && r.v0.is_nan(),
            "{call} wrote the report after {status:?}: {r:?}"
        );
    }
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
