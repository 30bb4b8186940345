//! G^k connect (mathematics.md, geometric continuity) next to its C^k
//! counterpart (issue 20: G^k within 2x of C^k), on the C++ demo's curves
//! (P a cubic, Q a quartic, 3D, `u0 = 0.6`, `v0 = 0.3`):
//!
//! - `geometric_vs_connect/g<k>/{given,ck}`: G^k with given shape values
//!   `(1, 0.3, 0.6, 0.9, 1.2, 1.5)` (their first `k`) at both ends, against
//!   C^k with scales 1, for every geometric order 1 to 6;
//! - `geometric_fair_vs_auto/g<k>/{fair,ck_auto}`: G^k with fair shape
//!   values (the search) against C^k with the automatic scale, for 2 and 3.
use std::hint::black_box;

use bezjoin_core::{
    BezierCurve, ConnectOptions, GeometricOptions, MAX_GEOMETRIC_ORDER, connect,
    connect_geometric_curve,
};
use criterion::{Criterion, criterion_group, criterion_main};

fn demo_curves() -> (BezierCurve, BezierCurve) {
    let p = BezierCurve::new(
        3,
        3,
        vec![
            0.1, -0.5, 0.3, 0.7, 0.2, -0.4, -0.3, 0.9, 0.5, 0.8, -0.6, 0.2,
        ],
    )
    .unwrap();
    let q = BezierCurve::new(
        3,
        4,
        vec![
            2.6, 0.1, -0.2, 3.1, -0.7, 0.4, 2.2, 0.5, 0.9, 3.4, 0.3, -0.8, 2.9, -0.2, 0.6,
        ],
    )
    .unwrap();
    (p, q)
}

fn bench_given_shapes(c: &mut Criterion) {
    let (p, q) = demo_curves();
    for k in 1..=MAX_GEOMETRIC_ORDER {
        let shape: Vec<f64> = [1.0, 0.3, 0.6, 0.9, 1.2, 1.5][..k].to_vec();
        let geometric = GeometricOptions::new(k, k).with_shapes(shape.clone(), shape);
        let plain = ConnectOptions::new(k, k);
        c.bench_function(&format!("geometric_vs_connect/g{k}/given"), |b| {
            b.iter(|| {
                connect_geometric_curve(
                    black_box(&p),
                    black_box(0.6),
                    black_box(&q),
                    black_box(0.3),
                    &geometric,
                )
                .unwrap()
            })
        });
        c.bench_function(&format!("geometric_vs_connect/g{k}/ck"), |b| {
            b.iter(|| {
                connect(
                    black_box(&p),
                    black_box(0.6),
                    black_box(&q),
                    black_box(0.3),
                    &plain,
                )
                .unwrap()
            })
        });
    }
}

fn bench_fair_shapes(c: &mut Criterion) {
    let (p, q) = demo_curves();
    for k in [2, 3] {
        let fair = GeometricOptions::new(k, k);
        let auto = ConnectOptions::new(k, k).with_auto_scale();
        c.bench_function(&format!("geometric_fair_vs_auto/g{k}/fair"), |b| {
            b.iter(|| {
                connect_geometric_curve(black_box(&p), 0.6, black_box(&q), 0.3, &fair).unwrap()
            })
        });
        c.bench_function(&format!("geometric_fair_vs_auto/g{k}/ck_auto"), |b| {
            b.iter(|| connect(black_box(&p), 0.6, black_box(&q), 0.3, &auto).unwrap())
        });
    }
}

criterion_group!(benches, bench_given_shapes, bench_fair_shapes);
criterion_main!(benches);
