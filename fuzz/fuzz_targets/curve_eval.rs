//! `bzj_curve_eval` at arbitrary parameters, derivative orders and buffer
//! lengths; the written values must be deterministic. `bzj_curve_eval_many`
//! on the same parameters: each block must be exactly what `bzj_curve_eval`
//! writes, and nothing is written after a failure.
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
    let n = input.below(6);
    let ts: Vec<f64> = (0..n).map(|_| input.parameter()).collect();
    let order = input.size(MAX_DEGREE + 3);
    let len = input.below(((MAX_DEGREE + 4) * MAX_DIM * 6).max(1));
    let mut many = vec![-7.25; len];
    // SAFETY: `ts` holds `n` doubles, `many` holds `len`; `c` is live.
    let status = unsafe { bzj_curve_eval_many(c, ts.as_ptr(), n, order, many.as_mut_ptr(), len) };
    check(status, "bzj_curve_eval_many");
    if status == BzjStatus::BZJ_OK && n > 0 {
        let mut dim = 0;
        // SAFETY: live handle, valid out-pointer.
        assert_eq!(unsafe { bzj_curve_dim(c, &mut dim) }, BzjStatus::BZJ_OK);
        let block_len = (order + 1) * dim;
        assert!(n * block_len <= len, "bzj_curve_eval_many accepted a short buffer");
        for (i, &t) in ts.iter().enumerate() {
            let mut one = vec![f64::NAN; block_len];
            // SAFETY: `one` holds `block_len` doubles.
            let status = unsafe { bzj_curve_eval(c, t, order, one.as_mut_ptr(), block_len) };
            assert_eq!(status, BzjStatus::BZJ_OK, "eval refused what eval_many took");
            let got = &many[i * block_len..(i + 1) * block_len];
            let same = got.iter().zip(&one).all(|(a, b)| a.to_bits() == b.to_bits());
            assert!(same, "bzj_curve_eval_many block {i} differs from bzj_curve_eval");
        }
    } else if status != BzjStatus::BZJ_OK {
        assert!(
            many.iter().all(|v| *v == -7.25),
            "bzj_curve_eval_many wrote after a failure"
        );
    }
    // SAFETY: live handle, released once.
    unsafe { bzj_curve_free(c) };
});
