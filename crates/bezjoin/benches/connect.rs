//! Connect (mathematics.md, section 1): cubic to cubic with C3 at both ends
//! (degree 7), in 2D and 3D, with and without one K = 2 interior constraint
//! (degree 10), structured solve versus the dense reference solve.
//!
//! `connect_vs_jets/<case>/{connect,connect_curve,jets}` (issue 20): a connect
//! (with its estimate, and the curve alone as `bzj_connect` takes it) next to
//! the evaluation of the two input jets it needs (`P^(k)(u0)`, k <= kp, and
//! `Q^(k)(v0)`, k <= kq, by `eval_derivatives_into` into stack buffers), the
//! physical limit of the operation; the goal is connect <= 2x jets. Cases:
//! cubic + cubic C3 in 2D (at the ends `u0 = 1, v0 = 0` and at the C++
//! demo's interior parameters `u0 = 0.6, v0 = 0.3`) and 3D, cubic + quartic
//! C3/C4 in 3D (the demo's case), each without and with one interior point
//! (position and tangent at `t = 0.4`, as the demo).
//!
//! `connect_nurbs_inputs/{bezier,two_spans,two_spans_rational}` (issue 20:
//! NURBS inputs within 2x their Bezier counterparts): `connect_curve` C3/C4
//! of the C++ demo's cubic and quartic in 3D at `u0 = 0.6`, `v0 = 0.3`, as
//! Bezier curves, as two-span NURBS curves (the knot 0.5 inserted: the same
//! geometry) and as rational copies of those spans (the demo's weights).
use std::hint::black_box;

use bezjoin_core::{BezierCurve, NurbsCurve};
use bezjoin_core::{
    ConnectOptions, PointConstraint, connect, connect_curve, connect_dense_reference,
};
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
        let balanced = plain.clone().with_balanced_scale();
        c.bench_function(&format!("connect_balanced_scale/c3/{dim}d"), |b| {
            b.iter(|| connect(black_box(&p), 1.0, black_box(&q), 0.0, &balanced).unwrap())
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

fn curve(dim: usize, degree: usize, offset: f64) -> BezierCurve {
    let pts: Vec<f64> = (0..(degree + 1) * dim)
        .map(|i| offset + ((i * 7919) % 97) as f64 / 9.7)
        .collect();
    BezierCurve::new(dim, degree, pts).unwrap()
}

fn bench_connect_vs_jets(c: &mut Criterion) {
    // (label, dim, degree of Q, kp, kq, u0, v0)
    let cases = [
        ("cubic_cubic_c3_2d_ends", 2, 3, 3, 3, 1.0, 0.0),
        ("cubic_cubic_c3_2d", 2, 3, 3, 3, 0.6, 0.3),
        ("cubic_cubic_c3_3d", 3, 3, 3, 3, 0.6, 0.3),
        ("cubic_quartic_c3c4_3d", 3, 4, 3, 4, 0.6, 0.3),
    ];
    for (label, dim, q_degree, kp, kq, u0, v0) in cases {
        let p = curve(dim, 3, 0.0);
        let q = curve(dim, q_degree, 20.0);
        let plain = ConnectOptions::new(kp, kq);
        let base = connect(&p, u0, &q, v0, &plain).unwrap();
        let values = base
            .curve
            .eval_derivatives(0.4, 1)
            .iter()
            .map(|v| v * 1.05)
            .collect();
        let point = plain
            .clone()
            .with_constraint(PointConstraint::new(0.4, 1, values));
        for (suffix, options) in [("", &plain), ("_point", &point)] {
            c.bench_function(&format!("connect_vs_jets/{label}{suffix}/connect"), |b| {
                b.iter(|| {
                    connect(
                        black_box(&p),
                        black_box(u0),
                        black_box(&q),
                        black_box(v0),
                        options,
                    )
                    .unwrap()
                })
            });
            c.bench_function(
                &format!("connect_vs_jets/{label}{suffix}/connect_curve"),
                |b| {
                    b.iter(|| {
                        connect_curve(
                            black_box(&p),
                            black_box(u0),
                            black_box(&q),
                            black_box(v0),
                            options,
                        )
                        .unwrap()
                    })
                },
            );
            c.bench_function(&format!("connect_vs_jets/{label}{suffix}/jets"), |b| {
                let mut pj = [0.0f64; 16];
                let mut qj = [0.0f64; 16];
                b.iter(|| {
                    black_box(&p).eval_derivatives_into(
                        black_box(u0),
                        kp,
                        &mut pj[..(kp + 1) * dim],
                    );
                    black_box(&q).eval_derivatives_into(
                        black_box(v0),
                        kq,
                        &mut qj[..(kq + 1) * dim],
                    );
                    black_box((&mut pj, &mut qj));
                })
            });
        }
    }
}

fn bench_connect_nurbs_inputs(c: &mut Criterion) {
    let p = BezierCurve::new(
        3,
        3,
        vec![0.1, 0.2, 0.3, 1.0, 1.5, -0.2, 2.0, -0.7, 0.4, 3.1, 0.2, 0.1],
    )
    .unwrap();
    let q = BezierCurve::new(
        3,
        4,
        vec![
            5.5, 0.3, 0.2, 6.1, 1.2, -0.4, 7.0, -0.5, 0.6, 7.8, 0.9, 0.0, 8.9, 0.1, 0.3,
        ],
    )
    .unwrap();
    let two_spans = |b: &BezierCurve| NurbsCurve::from_bezier(b).insert_knot(0.5, 1).unwrap();
    let weighted = |n: &NurbsCurve, weights: &[f64]| {
        NurbsCurve::new(
            n.dim(),
            n.degree(),
            n.points().to_vec(),
            Some(weights.to_vec()),
            n.knots().to_vec(),
        )
        .unwrap()
    };
    let (p_spans, q_spans) = (two_spans(&p), two_spans(&q));
    let p_rational = weighted(&p_spans, &[1.0, 0.7, 1.3, 0.9, 1.0]);
    let q_rational = weighted(&q_spans, &[1.0, 1.2, 0.8, 1.1, 0.7, 1.0]);
    let options = ConnectOptions::new(3, 4);
    let (u0, v0) = (0.6, 0.3);
    c.bench_function("connect_nurbs_inputs/bezier", |b| {
        b.iter(|| connect_curve(black_box(&p), u0, black_box(&q), v0, &options).unwrap())
    });
    c.bench_function("connect_nurbs_inputs/two_spans", |b| {
        b.iter(|| {
            connect_curve(black_box(&p_spans), u0, black_box(&q_spans), v0, &options).unwrap()
        })
    });
    c.bench_function("connect_nurbs_inputs/two_spans_rational", |b| {
        b.iter(|| {
            connect_curve(
                black_box(&p_rational),
                u0,
                black_box(&q_rational),
                v0,
                &options,
            )
            .unwrap()
        })
    });
}

criterion_group!(
    benches,
    bench_connect,
    bench_connect_vs_jets,
    bench_connect_nurbs_inputs
);
criterion_main!(benches);
