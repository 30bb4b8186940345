//! Evaluation with all derivatives, degrees 3, 7, 15, in 2D and 3D; arc
//! length and its inverse. Inputs and outputs pass through
//! `std::hint::black_box`, so the work cannot be hoisted out of the loop or
//! dropped as dead.
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
                b.iter(|| {
                    black_box(&cv).eval_into(black_box(0.37), &mut value);
                    black_box(&mut value);
                })
            });
            let mut all = vec![0.0; (degree + 1) * dim];
            c.bench_function(&format!("eval_all_derivatives/deg{degree}/{dim}d"), |b| {
                b.iter(|| {
                    black_box(&cv).eval_derivatives_into(black_box(0.37), degree, &mut all);
                    black_box(&mut all);
                })
            });
            c.bench_function(
                &format!("eval_all_derivatives_a23_basis/deg{degree}/{dim}d"),
                |b| {
                    b.iter(|| {
                        black_box(&cv).eval_derivatives_basis(black_box(0.37), degree, &mut all);
                        black_box(&mut all);
                    })
                },
            );
        }
    }
}

fn bench_arc_length(c: &mut Criterion) {
    let cubic = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 3.0], [4.0, 0.0]]).unwrap();
    let accuracy = cubic.default_length_accuracy();
    c.bench_function("arc_length/cubic_2d_default_accuracy", |b| {
        b.iter(|| black_box(black_box(&cubic).arc_length(black_box(0.0), black_box(1.0), accuracy)))
    });
    let total = cubic.arc_length(0.0, 1.0, accuracy).unwrap();
    c.bench_function("param_at_length/cubic_2d_forward_0.3_total", |b| {
        b.iter(|| {
            black_box(black_box(&cubic).param_at_length(
                black_box(0.1),
                black_box(0.3 * total),
                accuracy,
            ))
        })
    });
    c.bench_function("param_at_length/cubic_2d_backward_0.3_total", |b| {
        b.iter(|| {
            black_box(black_box(&cubic).param_at_length(
                black_box(0.9),
                black_box(-0.3 * total),
                accuracy,
            ))
        })
    });
    // A cusp: the hodograph passes through zero at t = 1/2.
    let cusp = BezierCurve::from_rows(&[[0.0, 0.0], [2.0, 1.0], [0.0, 1.0], [2.0, 0.0]]).unwrap();
    let accuracy = cusp.default_length_accuracy();
    let total = cusp.arc_length(0.0, 1.0, accuracy).unwrap();
    c.bench_function("param_at_length/cusp_2d_across_cusp", |b| {
        b.iter(|| {
            black_box(black_box(&cusp).param_at_length(
                black_box(0.0),
                black_box(0.7 * total),
                accuracy,
            ))
        })
    });
}

criterion_group!(benches, bench_eval, bench_arc_length);
criterion_main!(benches);
