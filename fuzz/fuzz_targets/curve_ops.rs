//! The other curve operations on fuzzed curves: split, elevate (to degree
//! <= 40), reverse, points with short buffers, and NULL out-pointers.
//! (Arc length has its own target, `curve_length`.)
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some(c) = curve(&mut input) else { return };
    for _ in 0..6 {
        // SAFETY (whole block): `c` is live, out-pointers are valid or NULL.
        unsafe {
            match input.byte() % 5 {
                0 => {
                    let (mut l, mut r) = (null_mut(), null_mut());
                    let status = bzj_curve_split(c, input.parameter(), &mut l, &mut r);
                    check_and_free(status, l, "bzj_curve_split");
                    check_and_free(status, r, "bzj_curve_split");
                }
                1 => {
                    let mut out = null_mut();
                    let status = bzj_curve_elevate(c, input.below(MAX_DEGREE + 1), &mut out);
                    check_and_free(status, out, "bzj_curve_elevate");
                }
                2 => {
                    let mut out = null_mut();
                    check_and_free(bzj_curve_reverse(c, &mut out), out, "bzj_curve_reverse");
                }
                3 => {
                    let len = input.below((MAX_DEGREE + 2) * MAX_DIM);
                    let mut buf = vec![0.0; len];
                    check(
                        bzj_curve_points(c, buf.as_mut_ptr(), len),
                        "bzj_curve_points",
                    );
                }
                _ => {
                    // NULL where a value is required: BZJ_ERR_NULL_POINTER.
                    let s = bzj_curve_segment(c, 0.0, 1.0, null_mut());
                    assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
                    let mut out = null_mut();
                    let s = bzj_curve_reverse(null(), &mut out);
                    assert_eq!(s, BzjStatus::BZJ_ERR_NULL_POINTER);
                    assert!(out.is_null());
                }
            }
        }
    }
    // SAFETY: live handle, released once.
    unsafe { bzj_curve_free(c) };
});
