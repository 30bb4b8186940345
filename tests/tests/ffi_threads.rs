//! Handles are read from several threads at once; last-error messages stay
//! with the thread that caused them (c-api.md, Conventions).

use std::ffi::CStr;

use bezjoin::{
    BzjCurve, BzjStatus, bzj_curve_eval, bzj_curve_free, bzj_curve_new, bzj_curve_split,
    bzj_last_error,
};

struct Shared(*mut BzjCurve);
// SAFETY: BzjCurve is immutable; the contract allows concurrent reads.
unsafe impl Sync for Shared {}
unsafe impl Send for Shared {}

fn last_error() -> String {
    unsafe { CStr::from_ptr(bzj_last_error()) }
        .to_str()
        .unwrap()
        .to_owned()
}

#[test]
fn shared_handle_gives_identical_results_on_every_thread() {
    let pts = [0.0, 0.0, 1.0, 3.0, 2.0, -1.0, 4.0, 2.0, 5.0, 0.0];
    let mut c = std::ptr::null_mut();
    assert_eq!(
        unsafe { bzj_curve_new(2, 4, pts.as_ptr(), pts.len(), &mut c) },
        BzjStatus::BZJ_OK
    );
    let shared = Shared(c);
    let run = |shared: &Shared| -> Vec<u64> {
        (0..2000)
            .map(|i| {
                let t = i as f64 / 1999.0;
                let mut out = [0.0; 10];
                assert_eq!(
                    unsafe { bzj_curve_eval(shared.0, t, 4, out.as_mut_ptr(), 10) },
                    BzjStatus::BZJ_OK
                );
                out.iter().fold(0u64, |h, v| h.rotate_left(5) ^ v.to_bits())
            })
            .collect()
    };
    let single = run(&shared);
    let results: Vec<Vec<u64>> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..8).map(|_| s.spawn(|| run(&shared))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for r in results {
        assert_eq!(r, single, "a thread saw different bits");
    }
    unsafe { bzj_curve_free(c) };
}

#[test]
fn last_error_is_per_thread() {
    let pts = [0.0, 0.0, 1.0, 1.0];
    let mut c = std::ptr::null_mut();
    assert_eq!(
        unsafe { bzj_curve_new(2, 1, pts.as_ptr(), 4, &mut c) },
        BzjStatus::BZJ_OK
    );
    let shared = Shared(c);
    std::thread::scope(|s| {
        for k in 0..6 {
            let shared = &shared;
            s.spawn(move || {
                let t = 2.0 + k as f64; // a different bad parameter per thread
                for _ in 0..200 {
                    let (mut l, mut r) = (std::ptr::null_mut(), std::ptr::null_mut());
                    let status = unsafe { bzj_curve_split(shared.0, t, &mut l, &mut r) };
                    assert_eq!(status, BzjStatus::BZJ_ERR_INVALID_ARGUMENT);
                    assert!(l.is_null() && r.is_null());
                    assert_eq!(last_error(), format!("t = {t} is outside [0, 1]"));
                }
            });
        }
    });
    unsafe { bzj_curve_free(c) };
}
