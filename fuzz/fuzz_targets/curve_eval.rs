//! `bzj_curve_eval` at arbitrary parameters, derivative orders and buffer
//! lengths; the written values must be deterministic.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some(c) = curve(&mut input) else { return };
    for _ in 0..4 {
        let t = input.parameter();
        let order = input.size(MAX_DEGREE + 3);
        let len = input.below(((MAX_DEGREE + 4) * MAX_DIM).max(1));
        let mut buf = vec![f64::NAN; len];
        // SAFETY: `buf` holds `len` doubles; `c` is live.
        let status = unsafe { bzj_curve_eval(c, t, order, buf.as_mut_ptr(), len) };
        check(status, "bzj_curve_eval");
        if status == BzjStatus::BZJ_OK {
            let mut again = vec![f64::NAN; len];
            // SAFETY: as above.
            let status = unsafe { bzj_curve_eval(c, t, order, again.as_mut_ptr(), len) };
            assert_eq!(status, BzjStatus::BZJ_OK);
            let same = buf
                .iter()
                .zip(&again)
                .all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "bzj_curve_eval is not deterministic at t = {t}");
        }
    }
    // SAFETY: live handle, released once.
    unsafe { bzj_curve_free(c) };
});
