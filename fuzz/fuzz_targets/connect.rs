//! `bzj_connect` and `bzj_connect_auto_scale` on fuzzed curve pairs (also of
//! different dimensions) with fuzzed parameters `u0`, `v0`, orders (also
//! `SIZE_MAX`), scales (any double) and up to 3 interior point constraints
//! (any `t`, orders <= 4, values of exactly `(K + 1) * dim` doubles, so an
//! over-read is caught by AddressSanitizer); then `bzj_connect_geometric`
//! with fuzzed orders and shape values given or left fair.
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
    // G^k with fuzzed orders (any size_t: above 6 is refused before the
    // shape arrays are read) and shapes given (any doubles) or left fair.
    let orders = [input.size(8), input.size(8)];
    let shapes: Vec<Vec<f64>> = orders
        .iter()
        .map(|&k| (0..k.min(6)).map(|_| input.double()).collect())
        .collect();
    let given = input.byte();
    let shape_ptr = |j: usize| {
        if given & (1 << j) != 0 && shapes[j].len() == orders[j] {
            shapes[j].as_ptr()
        } else {
            null()
        }
    };
    let geometric = BzjGeometricOptions {
        p_order: orders[0],
        q_order: orders[1],
        p_shape: shape_ptr(0),
        q_shape: shape_ptr(1),
    };
    let (mut p_out, mut q_out) = ([f64::NAN; 6], [f64::NAN; 6]);
    let mut report = BzjFairnessReport::default();
    let mut out = null_mut();
    // SAFETY: live handles; shape arrays hold their orders (NULL otherwise);
    // the shape outputs hold 6 >= any accepted order.
    let status = unsafe {
        bzj_connect_geometric(
            p,
            u0,
            q,
            v0,
            &geometric,
            &mut out,
            p_out.as_mut_ptr(),
            q_out.as_mut_ptr(),
            &mut report,
        )
    };
    check_and_free(status, out, "bzj_connect_geometric");
    if status == BzjStatus::BZJ_OK {
        for (values, &k) in [&p_out, &q_out].iter().zip(&orders) {
            assert!(k == 0 || values[0] > 0.0, "bzj_connect_geometric: beta_1 = {}", values[0]);
        }
    }
    // SAFETY: live handles, released once.
    unsafe {
        bzj_curve_free(p);
        bzj_curve_free(q);
    }
});
