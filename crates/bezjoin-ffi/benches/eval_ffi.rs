//! Evaluation through the C ABI (issue 20): `bzj_curve_eval` of the value
//! (order 0) at degrees 3 and 7 in 3D and of value + 2 derivatives at
//! degree 3; `bzj_curve_eval_many` of 1000 parameters (order 0 and order 1,
//! degree 3, 3D; throughput in points); the same curve as a NURBS handle
//! (`bzj_curve_to_nurbs`) for both entry points. The C++ demo's reference
//! is OCCT's `Geom_BezierCurve::D0`: 70.2 ns at degree 3, 249 ns at 7.
use std::hint::black_box;

use bezjoin::{
    BzjStatus, bzj_curve_eval, bzj_curve_eval_many, bzj_curve_free, bzj_curve_new,
    bzj_curve_to_nurbs,
};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};

fn bench_eval_ffi(c: &mut Criterion) {
    let dim = 3usize;
    let new_curve = |degree: usize| {
        let pts: Vec<f64> = (0..(degree + 1) * dim)
            .map(|i| ((i * 7919) % 97) as f64 / 9.7)
            .collect();
        let mut h = std::ptr::null_mut();
        let s = unsafe { bzj_curve_new(dim, degree, pts.as_ptr(), pts.len(), &mut h) };
        assert_eq!(s, BzjStatus::BZJ_OK);
        h
    };
    for degree in [3usize, 7] {
        let h = new_curve(degree);
        let mut nurbs = std::ptr::null_mut();
        assert_eq!(
            unsafe { bzj_curve_to_nurbs(h, &mut nurbs) },
            BzjStatus::BZJ_OK
        );
        for (kind, handle) in [("bezier", h), ("nurbs", nurbs)] {
            let mut out = [0.0f64; 3];
            c.bench_function(
                &format!("bzj_curve_eval/{kind}/deg{degree}/3d/value"),
                |b| {
                    b.iter(|| {
                        let s = unsafe {
                            bzj_curve_eval(
                                black_box(handle),
                                black_box(0.37),
                                0,
                                out.as_mut_ptr(),
                                3,
                            )
                        };
                        black_box((s, &mut out));
                    })
                },
            );
            if degree == 3 {
                let mut out = [0.0f64; 9];
                c.bench_function(
                    &format!("bzj_curve_eval/{kind}/deg{degree}/3d/order2"),
                    |b| {
                        b.iter(|| {
                            let s = unsafe {
                                bzj_curve_eval(
                                    black_box(handle),
                                    black_box(0.37),
                                    2,
                                    out.as_mut_ptr(),
                                    9,
                                )
                            };
                            black_box((s, &mut out));
                        })
                    },
                );
                let count = 1000usize;
                let ts: Vec<f64> = (0..count).map(|i| i as f64 / (count - 1) as f64).collect();
                let mut group = c.benchmark_group(format!("bzj_curve_eval_many/{kind}"));
                group.throughput(Throughput::Elements(count as u64));
                for order in [0usize, 1] {
                    let mut all = vec![0.0f64; count * (order + 1) * dim];
                    group.bench_function(format!("deg{degree}/3d/order{order}/1000"), |b| {
                        b.iter(|| {
                            let s = unsafe {
                                bzj_curve_eval_many(
                                    black_box(handle),
                                    ts.as_ptr(),
                                    count,
                                    order,
                                    all.as_mut_ptr(),
                                    all.len(),
                                )
                            };
                            assert_eq!(s, BzjStatus::BZJ_OK);
                            black_box(&mut all);
                        })
                    });
                }
                group.finish();
            }
        }
        unsafe {
            bzj_curve_free(h);
            bzj_curve_free(nurbs);
        }
    }
}

criterion_group!(benches, bench_eval_ffi);
criterion_main!(benches);
