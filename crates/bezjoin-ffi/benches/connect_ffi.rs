//! `bzj_connect` through the C ABI: cubic to cubic with C3 at both ends
//! (degree 7), 2D and 3D, with and without one K = 2 constraint; the handle
//! is created and freed in each iteration, as a C caller would.
use std::hint::black_box;

use bezjoin::{BzjConnectOptions, BzjPointConstraint, BzjStatus, bzj_connect};
use bezjoin::{bzj_curve_eval, bzj_curve_free, bzj_curve_new};
use criterion::{Criterion, criterion_group, criterion_main};

fn bench_connect_ffi(c: &mut Criterion) {
    for dim in [2usize, 3] {
        // The handle type is not re-exported; let inference name it.
        let cubic = |dim: usize, offset: f64| {
            let pts: Vec<f64> = (0..4 * dim)
                .map(|i| offset + ((i * 7919) % 97) as f64 / 9.7)
                .collect();
            let mut c = std::ptr::null_mut();
            let s = unsafe { bzj_curve_new(dim, 3, pts.as_ptr(), pts.len(), &mut c) };
            assert_eq!(s, BzjStatus::BZJ_OK);
            c
        };
        let p = cubic(dim, 0.0);
        let q = cubic(dim, 20.0);
        let mut plain = BzjConnectOptions {
            p_order: 3,
            q_order: 3,
            p_scale: 1.0,
            q_scale: 1.0,
            constraints: std::ptr::null(),
            constraint_count: 0,
        };
        // Constraint data: the unconstrained curve's value and derivatives
        // at t = 1/2, moved by 5%.
        let mut base = std::ptr::null_mut();
        assert_eq!(
            unsafe { bzj_connect(p, 1.0, q, 0.0, &plain, &mut base) },
            BzjStatus::BZJ_OK
        );
        let mut values = vec![0.0; 3 * dim];
        assert_eq!(
            unsafe { bzj_curve_eval(base, 0.5, 2, values.as_mut_ptr(), values.len()) },
            BzjStatus::BZJ_OK
        );
        unsafe { bzj_curve_free(base) };
        values.iter_mut().for_each(|v| *v *= 1.05);
        let constraint = BzjPointConstraint {
            t: 0.5,
            max_order: 2,
            values: values.as_ptr(),
        };
        for (label, with_constraint) in [("c3", false), ("c3_k2", true)] {
            if with_constraint {
                plain.constraints = &constraint;
                plain.constraint_count = 1;
            }
            c.bench_function(&format!("bzj_connect/{label}/{dim}d"), |b| {
                b.iter(|| {
                    let mut out = std::ptr::null_mut();
                    let s = unsafe { bzj_connect(black_box(p), 1.0, q, 0.0, &plain, &mut out) };
                    assert_eq!(s, BzjStatus::BZJ_OK);
                    unsafe { bzj_curve_free(out) };
                })
            });
        }
        unsafe {
            bzj_curve_free(p);
            bzj_curve_free(q);
        }
    }
}

criterion_group!(benches, bench_connect_ffi);
criterion_main!(benches);
