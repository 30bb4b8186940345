//! `bzj_curve_segment` with arbitrary (also reversed, equal, far
//! extrapolated, non-finite) end parameters.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::null_mut;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some(c) = curve(&mut input) else { return };
    for _ in 0..4 {
        let a = input.parameter();
        let b = input.parameter();
        let mut out = null_mut();
        // SAFETY: live handle, writable out-pointer.
        let status = unsafe { bzj_curve_segment(c, a, b, &mut out) };
        check_and_free(status, out, "bzj_curve_segment");
    }
    // SAFETY: live handle, released once.
    unsafe { bzj_curve_free(c) };
});
