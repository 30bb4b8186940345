//! Merging two curves: two curves of degree 3, 7, 15 and 31, both metrics,
//! a given mu against the optimal mu (a refused merge is timed as well: the
//! bench measures the work either way); two 4-span cubic B-splines the same
//! way (issue 17's goal: at most 4x the Bezier cubics with the paper's
//! integral metric).
use std::hint::black_box;

use bezjoin_core::BezierCurve;
use bezjoin_core::{Breakpoints, MergeMetric, MergeOptions, NurbsCurve, merge, merge_bsplines};
use criterion::{Criterion, criterion_group, criterion_main};

fn pair(degree: usize) -> (BezierCurve, BezierCurve) {
    let make = |offset: usize, shift: f64| {
        let pts: Vec<f64> = (0..(degree + 1) * 2)
            .map(|i| ((i * 7919 + offset) % 97) as f64 / 9.7 + if i % 2 == 0 { shift } else { 0.0 })
            .collect();
        BezierCurve::new(2, degree, pts).unwrap()
    };
    (make(0, 0.0), make(31, 10.0))
}

fn bench_merge(c: &mut Criterion) {
    for degree in [3, 7, 15, 31] {
        let (p, q) = pair(degree);
        for (metric, metric_name) in [
            (MergeMetric::Discrete, "discrete"),
            (MergeMetric::Integral, "integral"),
        ] {
            for (split, split_name) in [
                (Breakpoints::Given(vec![0.4]), "given_mu"),
                (Breakpoints::Optimal, "optimal_mu"),
            ] {
                let options = MergeOptions::default()
                    .with_metric(metric)
                    .with_split(split);
                c.bench_function(
                    &format!("merge/deg{degree}/{metric_name}/{split_name}"),
                    |b| b.iter(|| merge(black_box(&p), black_box(&q), &options).is_ok()),
                );
            }
        }
    }
}

/// Two clamped cubic B-splines of 4 spans (7 poles each), the second
/// starting where the first ends.
fn spline_pair() -> (NurbsCurve, NurbsCurve) {
    let make = |offset: usize, shift: f64| {
        let pts: Vec<f64> = (0..14)
            .map(|i| ((i * 7919 + offset) % 97) as f64 / 9.7 + if i % 2 == 0 { shift } else { 0.0 })
            .collect();
        let knots = vec![0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.7, 1.0, 1.0, 1.0, 1.0];
        NurbsCurve::new(2, 3, pts, None, knots).unwrap()
    };
    (make(0, 0.0), make(31, 10.0))
}

fn bench_merge_bsplines(c: &mut Criterion) {
    let (p, q) = spline_pair();
    for (metric, metric_name) in [
        (MergeMetric::Discrete, "discrete"),
        (MergeMetric::Integral, "integral"),
    ] {
        for (split, split_name) in [
            (Breakpoints::Given(vec![0.4]), "given_mu"),
            (Breakpoints::Optimal, "optimal_mu"),
        ] {
            let options = MergeOptions::default()
                .with_metric(metric)
                .with_split(split);
            c.bench_function(
                &format!("merge_bspline/4span_cubic/{metric_name}/{split_name}"),
                |b| b.iter(|| merge_bsplines(black_box(&p), black_box(&q), &options).unwrap()),
            );
        }
    }
}

criterion_group!(benches, bench_merge, bench_merge_bsplines);
criterion_main!(benches);
