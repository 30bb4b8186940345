//! NURBS evaluation beside the Bezier evaluation of the same degree (issue 20:
//! NURBS inputs stay within 2x their Bezier counterparts): a rational quintic
//! of 3 spans in 3D and a polynomial cubic of 4 spans, value and derivatives
//! 0..=3, against a Bezier curve of the same degree and dimension; rows
//! `nurbs_eval/*` take the basis route (`eval_derivatives`, A2.3), rows
//! `nurbs_eval_checked/*` the route of `bzj_curve_eval`
//! (`eval_derivatives_checked_into`, through the Bezier spans), and rows
//! `nurbs_one_span/*` a Bezier curve as a one-span NURBS (what a host's
//! `bzj_curve_to_nurbs` gives) beside the Bezier curve. Inputs and outputs
//! pass through `std::hint::black_box`.
use std::hint::black_box;

use bezjoin_core::{BezierCurve, NurbsCurve};
use criterion::{Criterion, criterion_group, criterion_main};

fn poles(count: usize, dim: usize) -> Vec<f64> {
    (0..count * dim)
        .map(|i| ((i * 7919) % 97) as f64 / 9.7)
        .collect()
}

/// Clamped knots with `spans` uniform spans of a degree-`p` curve.
fn knots(p: usize, spans: usize) -> Vec<f64> {
    let mut k = vec![0.0; p + 1];
    k.extend((1..spans).map(|i| i as f64 / spans as f64));
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

fn bench_nurbs_eval(c: &mut Criterion) {
    let cases: [(&str, usize, usize, bool); 2] = [
        ("rational_deg5_3spans", 5, 3, true),
        ("polynomial_deg3_4spans", 3, 4, false),
    ];
    for (name, p, spans, rational) in cases {
        let dim = 3;
        let count = p + spans;
        let weights = rational.then(|| (0..count).map(|i| 1.0 + 0.25 * (i % 3) as f64).collect());
        let nurbs = NurbsCurve::new(dim, p, poles(count, dim), weights, knots(p, spans)).unwrap();
        let bezier = BezierCurve::new(dim, p, poles(p + 1, dim)).unwrap();
        for order in [0usize, 3] {
            c.bench_function(&format!("nurbs_eval/{name}/order{order}"), |b| {
                b.iter(|| black_box(black_box(&nurbs).eval_derivatives(black_box(0.37), order)))
            });
            let mut rows = vec![0.0; (order + 1) * dim];
            c.bench_function(&format!("nurbs_eval_checked/{name}/order{order}"), |b| {
                b.iter(|| {
                    black_box(&nurbs)
                        .eval_derivatives_checked_into(
                            || "u".into(),
                            black_box(0.37),
                            order,
                            &mut rows,
                        )
                        .unwrap();
                    black_box(&mut rows);
                })
            });
            let mut out = vec![0.0; (order + 1) * dim];
            c.bench_function(&format!("bezier_eval/deg{p}_3d/order{order}"), |b| {
                b.iter(|| {
                    black_box(&bezier).eval_derivatives_into(black_box(0.37), order, &mut out);
                    black_box(&mut out);
                })
            });
        }
    }
}

fn bench_one_span(c: &mut Criterion) {
    for p in [3usize, 7] {
        let dim = 3;
        let bezier = BezierCurve::new(dim, p, poles(p + 1, dim)).unwrap();
        let nurbs = NurbsCurve::from_bezier(&bezier);
        for order in [0usize, 3] {
            let mut out = vec![0.0; (order + 1) * dim];
            c.bench_function(&format!("nurbs_one_span/deg{p}_3d/order{order}"), |b| {
                b.iter(|| {
                    black_box(&nurbs)
                        .eval_derivatives_checked_into(
                            || "u".into(),
                            black_box(0.37),
                            order,
                            &mut out,
                        )
                        .unwrap();
                    black_box(&mut out);
                })
            });
            c.bench_function(
                &format!("nurbs_one_span/bezier_deg{p}_3d/order{order}"),
                |b| {
                    b.iter(|| {
                        if order == 0 {
                            black_box(&bezier).eval_into(black_box(0.37), &mut out);
                        } else {
                            black_box(&bezier).eval_derivatives_into(
                                black_box(0.37),
                                order,
                                &mut out,
                            );
                        }
                        black_box(&mut out);
                    })
                },
            );
        }
    }
}

criterion_group!(benches, bench_nurbs_eval, bench_one_span);
criterion_main!(benches);
