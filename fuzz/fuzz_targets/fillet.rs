//! `bzj_fillet` and `bzj_fillet_auto_scale` on fuzzed curve pairs with
//! fuzzed setbacks (any double), orders (also `SIZE_MAX`) and scales;
//! sometimes one out-pointer NULL; then `bzj_fillet_radius` or
//! `bzj_fillet_radius_detailed` on the same pair with any radius and order.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::null_mut;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let options = fillet_options(&mut input);
    let drop_one = input.byte() % 16;
    let (mut a, mut b, mut c) = (null_mut(), null_mut(), null_mut());
    let pa: *mut *mut BzjCurve = if drop_one == 1 { null_mut() } else { &mut a };
    let pb: *mut *mut BzjCurve = if drop_one == 2 { null_mut() } else { &mut b };
    let pc: *mut *mut BzjCurve = if drop_one == 3 { null_mut() } else { &mut c };
    // Sometimes the automatic scale (the given scales are then ignored),
    // with or without somewhere to write the chosen scale.
    let auto = input.byte() % 4;
    let mut scale = f64::NAN;
    // SAFETY: live handles, readable options, out-pointers valid or NULL.
    let status = unsafe {
        match auto {
            0 => bzj_fillet_auto_scale(p, q, &options, pa, pb, pc, &mut scale),
            1 => bzj_fillet_auto_scale(p, q, &options, pa, pb, pc, null_mut()),
            _ => bzj_fillet(p, q, &options, pa, pb, pc),
        }
    };
    if auto == 0 && status == BzjStatus::BZJ_OK {
        assert!(
            scale.is_finite() && scale > 0.0,
            "bzj_fillet_auto_scale reported the scale {scale}"
        );
    }
    if (1..=3).contains(&drop_one) {
        assert_eq!(
            status,
            BzjStatus::BZJ_ERR_NULL_POINTER,
            "bzj_fillet with a NULL out-pointer"
        );
    }
    check_and_free(status, a, "bzj_fillet");
    check_and_free(status, b, "bzj_fillet");
    check_and_free(status, c, "bzj_fillet");
    // The fillet by radius: any radius (the setback's bits), any order.
    let radius = options.p_setback;
    let order = input.size(8);
    let (mut a, mut b, mut c) = (null_mut(), null_mut(), null_mut());
    let mut report = BzjFairnessReport::default();
    let report_ptr: *mut BzjFairnessReport = if input.byte() % 2 == 0 {
        &mut report
    } else {
        null_mut()
    };
    // Read last (an exhausted input reads 0: bzj_fillet_radius, as before).
    let detailed = input.byte() % 2 == 1;
    let mut detailed_report = BzjRadiusFilletReport::default();
    let mut centre = [f64::NAN; MAX_DIM + 1];
    // SAFETY: live handles, writable out-pointers; `centre` holds more
    // doubles than any fuzzed curve's dimension.
    let (status, call) = unsafe {
        if detailed {
            (
                bzj_fillet_radius_detailed(
                    p,
                    q,
                    radius,
                    order,
                    &mut a,
                    &mut b,
                    &mut c,
                    &mut detailed_report,
                    centre.as_mut_ptr(),
                ),
                "bzj_fillet_radius_detailed",
            )
        } else {
            (
                bzj_fillet_radius(p, q, radius, order, &mut a, &mut b, &mut c, report_ptr),
                "bzj_fillet_radius",
            )
        }
    };
    if detailed && status == BzjStatus::BZJ_OK {
        let r = detailed_report;
        assert!(
            r.arc_deviation >= 0.0 && r.arc_deviation.is_finite(),
            "{call}: arc deviation {}",
            r.arc_deviation
        );
        let mut dim = 0usize;
        // SAFETY: live handle, writable out-pointer.
        check(unsafe { bzj_curve_dim(p, &mut dim) }, "bzj_curve_dim");
        assert!(
            centre[..dim].iter().all(|x| x.is_finite()),
            "{call}: centre {centre:?}"
        );
        assert!(centre[dim].is_nan(), "{call} wrote past the dimension");
    }
    check_and_free(status, a, call);
    check_and_free(status, b, call);
    check_and_free(status, c, call);
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
