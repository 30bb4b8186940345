//! `bzj_intersect` on fuzzed curve pairs with output capacities 0..8: the
//! pairs written are `min(count, capacity)`, each `(u, v)` in [0, 1] and
//! ordered by `u`; nothing is written past `2 * capacity` doubles.
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::null_mut;

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let capacity = input.below(9);
    let mut out = vec![f64::NAN; 2 * capacity + 2];
    let mut count = usize::MAX;
    let out_ptr = if capacity == 0 && input.byte() % 2 == 0 {
        null_mut()
    } else {
        out.as_mut_ptr()
    };
    // SAFETY: live handles; `out` holds 2 * capacity (+2 guard) doubles.
    let status = unsafe { bzj_intersect(p, q, out_ptr, capacity, &mut count) };
    check(status, "bzj_intersect");
    if status == BzjStatus::BZJ_OK {
        let written = count.min(capacity);
        let mut previous = f64::NEG_INFINITY;
        for pair in out[..2 * written].chunks(2) {
            assert!(
                (0.0..=1.0).contains(&pair[0]) && (0.0..=1.0).contains(&pair[1]),
                "{pair:?}"
            );
            assert!(pair[0] >= previous, "crossings not ordered by u: {out:?}");
            previous = pair[0];
        }
    }
    assert!(
        out[2 * capacity..].iter().all(|x| x.is_nan()),
        "bzj_intersect wrote past capacity"
    );
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
