//! `bzj_curve_new` with arbitrary dim, degree, length and coordinates
//! (including sizes that overflow `(degree + 1) * dim`).
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::null_mut;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let dim = input.size(MAX_DIM + 1);
    let degree = input.size(MAX_DEGREE + 1);
    let len = input.below(4 * (MAX_DEGREE + 2) * MAX_DIM);
    let points: Vec<f64> = (0..len).map(|_| input.coordinate()).collect();
    // The declared length may be shorter than the buffer, never longer.
    let declared = if input.byte().is_multiple_of(4) {
        input.below(len + 1)
    } else {
        len
    };
    let mut out = null_mut();
    // SAFETY: `points` holds at least `declared` doubles.
    let status = unsafe { bzj_curve_new(dim, degree, points.as_ptr(), declared, &mut out) };
    check_and_free(status, out, "bzj_curve_new");
    // A NULL points pointer with any length.
    let mut out = null_mut();
    // SAFETY: a NULL pointer is a documented error.
    let status = unsafe { bzj_curve_new(dim, degree, std::ptr::null(), declared, &mut out) };
    check_and_free(status, out, "bzj_curve_new(NULL)");
});
