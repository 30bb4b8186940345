//! `bzj_fillet` and `bzj_fillet_auto_scale` on fuzzed curve pairs with
//! fuzzed setbacks (any double), orders (also `SIZE_MAX`) and scales;
//! sometimes one out-pointer NULL; then `bzj_fillet_radius` on the same
//! pair with any radius and order.
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
    // SAFETY: live handles, writable out-pointers.
    let status =
        unsafe { bzj_fillet_radius(p, q, radius, order, &mut a, &mut b, &mut c, report_ptr) };
    check_and_free(status, a, "bzj_fillet_radius");
    check_and_free(status, b, "bzj_fillet_radius");
    check_and_free(status, c, "bzj_fillet_radius");
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
