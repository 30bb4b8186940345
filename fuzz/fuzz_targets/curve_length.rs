//! `bzj_curve_length` on fuzzed curves and parameter ranges. A successful
//! length must be finite and carry the sign of `b - a`.
//! Open finding (docs/reliability.md): ordinary inputs can make the adaptive
//! quadrature run for minutes; scripts/fuzz-short.sh skips this target until
//! that is fixed (reproducer in C: fuzz/regressions/length_hang.c).
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some(c) = curve(&mut input) else { return };
    for _ in 0..3 {
        let (a, b) = (input.parameter(), input.parameter());
        let mut length = f64::NAN;
        // SAFETY: live handle, writable out-pointer.
        let status = unsafe { bzj_curve_length(c, a, b, &mut length) };
        check(status, "bzj_curve_length");
        if status == BzjStatus::BZJ_OK {
            assert!(length.is_finite(), "length {length} on [{a}, {b}]");
            assert!(
                length * (b - a) >= 0.0,
                "length {length} has the wrong sign on [{a}, {b}]"
            );
        }
    }
    // SAFETY: live handle, released once.
    unsafe { bzj_curve_free(c) };
});
