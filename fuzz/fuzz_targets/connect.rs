//! `bzj_connect` and `bzj_connect_auto_scale` on fuzzed curve pairs (also of
//! different dimensions) with fuzzed parameters `u0`, `v0`, orders (also
//! `SIZE_MAX`), scales (any double) and up to 3 interior point constraints
//! (any `t`, orders <= 4, values of exactly `(K + 1) * dim` doubles, so an
//! over-read is caught by AddressSanitizer).
#![no_main]

use bezjoin_fuzz::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

fuzz_target!(|data: &[u8]| {
    let mut input = Input::new(data);
    let Some((p, q)) = curve_pair(&mut input) else {
        return;
    };
    let mut dim = 0usize;
    // SAFETY: live handle, writable out-pointer.
    unsafe { bzj_curve_dim(p, &mut dim) };
    let count = input.below(4);
    let values: Vec<Vec<f64>> = (0..count)
        .map(|_| {
            let order = input.below(5);
            (0..(order + 1) * dim).map(|_| input.coordinate()).collect()
        })
        .collect();
    let constraints: Vec<BzjPointConstraint> = values
        .iter()
        .map(|v| BzjPointConstraint {
            t: input.parameter(),
            max_order: v.len() / dim - 1,
            values: v.as_ptr(),
        })
        .collect();
    let options = BzjConnectOptions {
        p_order: input.size(8),
        q_order: input.size(8),
        p_scale: if input.byte() % 4 == 0 {
            input.double()
        } else {
            1.0
        },
        q_scale: if input.byte() % 4 == 0 {
            input.double()
        } else {
            1.0
        },
        constraints: if constraints.is_empty() {
            null()
        } else {
            constraints.as_ptr()
        },
        constraint_count: constraints.len(),
    };
    let (u0, v0) = (input.parameter(), input.parameter());
    let mut out = null_mut();
    // SAFETY: live handles, readable options with arrays holding their counts.
    let status = unsafe {
        if input.byte() % 4 == 0 {
            let mut scale = f64::NAN;
            bzj_connect_auto_scale(p, u0, q, v0, &options, &mut out, &mut scale)
        } else {
            bzj_connect(p, u0, q, v0, &options, &mut out)
        }
    };
    check_and_free(status, out, "bzj_connect");
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
