//! Evaluation with all derivatives, degrees 3, 7, 15, in 2D and 3D.
use std::hint::black_box;

use bezjoin_core::BezierCurve;
use criterion::{Criterion, criterion_group, criterion_main};

fn curve(degree: usize, dim: usize) -> BezierCurve {
    let pts: Vec<f64> = (0..(degree + 1) * dim)
        .map(|i| ((i * 7919) % 97) as f64 / 9.7)
        .collect();
    BezierCurve::new(dim, degree, pts).unwrap()
}

fn bench_eval(c: &mut Criterion) {
    for dim in [2, 3] {
        for degree in [3, 7, 15] {
            let cv = curve(degree, dim);
            let mut value = vec![0.0; dim];
            c.bench_function(&format!("eval_value/deg{degree}/{dim}d"), |b| {
                b.iter(|| cv.eval_into(black_box(0.37), &mut value))
            });
            let mut all = vec![0.0; (degree + 1) * dim];
            c.bench_function(&format!("eval_all_derivatives/deg{degree}/{dim}d"), |b| {
                b.iter(|| cv.eval_derivatives_into(black_box(0.37), degree, &mut all))
            });
            c.bench_function(
                &format!("eval_all_derivatives_a23_basis/deg{degree}/{dim}d"),
                |b| b.iter(|| cv.eval_derivatives_basis(black_box(0.37), degree, &mut all)),
            );
        }
    }
}

criterion_group!(benches, bench_eval);
criterion_main!(benches);
