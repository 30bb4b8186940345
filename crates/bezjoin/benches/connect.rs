//! Connect (mathematics.md, section 1): cubic to cubic with C3 at both ends
//! (degree 7), in 2D and 3D, with and without one K = 2 interior constraint
//! (degree 10), structured solve versus the dense reference solve.
use std::hint::black_box;

use bezjoin_core::BezierCurve;
use bezjoin_core::{ConnectOptions, PointConstraint, connect, connect_dense_reference};
use criterion::{Criterion, criterion_group, criterion_main};

fn cubic(dim: usize, offset: f64) -> BezierCurve {
    let pts: Vec<f64> = (0..4 * dim)
        .map(|i| offset + ((i * 7919) % 97) as f64 / 9.7)
        .collect();
    BezierCurve::new(dim, 3, pts).unwrap()
}

fn bench_connect(c: &mut Criterion) {
    for dim in [2, 3] {
        let p = cubic(dim, 0.0);
        let q = cubic(dim, 20.0);
        let plain = ConnectOptions::new(3, 3);
        let base = connect(&p, 1.0, &q, 0.0, &plain).unwrap();
        let values = base
            .curve
            .eval_derivatives(0.5, 2)
            .iter()
            .map(|v| v * 1.05)
            .collect();
        let constrained = plain
            .clone()
            .with_constraint(PointConstraint::new(0.5, 2, values));
        let auto = plain.clone().with_auto_scale();
        c.bench_function(&format!("connect_auto_scale/c3/{dim}d"), |b| {
            b.iter(|| connect(black_box(&p), 1.0, black_box(&q), 0.0, &auto).unwrap())
        });
        for (label, options) in [("c3", &plain), ("c3_k2", &constrained)] {
            c.bench_function(&format!("connect_structured/{label}/{dim}d"), |b| {
                b.iter(|| connect(black_box(&p), 1.0, black_box(&q), 0.0, options).unwrap())
            });
            c.bench_function(&format!("connect_dense/{label}/{dim}d"), |b| {
                b.iter(|| {
                    connect_dense_reference(black_box(&p), 1.0, black_box(&q), 0.0, options)
                        .unwrap()
                })
            });
        }
    }
}

criterion_group!(benches, bench_connect);
criterion_main!(benches);
