//! Intersection and corner rounding: one cubic-cubic intersection, one
//! cubic-cubic C3 fillet (blend degree 7), the fair G2 fillet by radius of
//! the same corner, one deviation-bound fillet, the intersection and the
//! C3 fillet of the same cubics as two-span NURBS (polynomial and
//! rational), and a chain of 100 000 corners on 1 and 2 threads (local
//! rayon pools).
use std::hint::black_box;

use bezjoin_core::{BezierCurve, NurbsCurve};
use bezjoin_core::{
    ChainFilletOptions, DeviationFilletOptions, FilletOptions, fillet, fillet_chain, fillet_radius,
    fillet_within_deviation,
};
use bezjoin_core::{IntersectOptions, intersect};
use criterion::{Criterion, criterion_group, criterion_main};

fn cubic(rows: [[f64; 2]; 4]) -> BezierCurve {
    BezierCurve::from_rows(&rows).unwrap()
}

/// A zigzag of `n` cubics meeting end to end at sharp corners.
fn zigzag(n: usize) -> Vec<BezierCurve> {
    (0..n)
        .map(|i| {
            let x = i as f64 * 1.5;
            let (y0, y1) = if i % 2 == 0 { (0.0, 1.0) } else { (1.0, 0.0) };
            let bulge = 0.1 * ((i * 7919 % 13) as f64 / 13.0 - 0.5);
            cubic([
                [x, y0],
                [x + 0.5, y0 + (y1 - y0) / 3.0 + bulge],
                [x + 1.0, y0 + 2.0 * (y1 - y0) / 3.0 - bulge],
                [x + 1.5, y1],
            ])
        })
        .collect()
}

/// `curve` as a clamped cubic NURBS with `weights` (none: polynomial),
/// cut into two spans at `u = 1/2` by knot insertion (the same curve).
fn two_spans(curve: &BezierCurve, weights: Option<Vec<f64>>) -> NurbsCurve {
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    NurbsCurve::new(2, 3, curve.points().to_vec(), weights, knots)
        .unwrap()
        .insert_knot(0.5, 1)
        .unwrap()
}

fn bench_fillet(c: &mut Criterion) {
    let p = cubic([[-1.0, -1.0], [-0.3, 0.2], [0.4, 0.5], [1.2, 0.3]]);
    let q = cubic([[0.5, -1.2], [0.1, -0.2], [-0.1, 0.6], [0.3, 1.4]]);
    c.bench_function("intersect/cubic_cubic", |b| {
        b.iter(|| intersect(black_box(&p), black_box(&q), &IntersectOptions::default()).unwrap())
    });
    // Issue 20: two crossings, a tangency (a cubic touching a straight
    // cubic at its lowest point), and a degree-7 pair crossing once.
    let arch = cubic([[0.0, 0.0], [0.3, 1.0], [0.7, 1.0], [1.0, 0.0]]);
    let level = cubic([[-0.1, 0.3], [0.33, 0.35], [0.67, 0.35], [1.1, 0.3]]);
    c.bench_function("intersect/cubic_cubic_two_crossings", |b| {
        b.iter(|| {
            intersect(
                black_box(&arch),
                black_box(&level),
                &IntersectOptions::default(),
            )
            .unwrap()
        })
    });
    let cup = cubic([
        [0.0, 1.0],
        [1.0 / 3.0, -1.0 / 3.0],
        [2.0 / 3.0, -1.0 / 3.0],
        [1.0, 1.0],
    ]);
    let floor = cubic([[0.0, 0.0], [1.0 / 3.0, 0.0], [2.0 / 3.0, 0.0], [1.0, 0.0]]);
    c.bench_function("intersect/cubic_cubic_tangency", |b| {
        b.iter(|| {
            intersect(
                black_box(&cup),
                black_box(&floor),
                &IntersectOptions::default(),
            )
            .unwrap()
        })
    });
    let p7 = BezierCurve::from_rows(&[
        [-1.0, -1.0],
        [-0.7, -0.2],
        [-0.4, 0.4],
        [-0.1, 0.1],
        [0.2, 0.6],
        [0.5, 0.2],
        [0.8, 0.7],
        [1.2, 0.3],
    ])
    .unwrap();
    let q7 = BezierCurve::from_rows(&[
        [0.5, -1.2],
        [0.2, -0.8],
        [0.4, -0.3],
        [0.0, 0.0],
        [0.2, 0.4],
        [-0.2, 0.7],
        [0.1, 1.0],
        [0.3, 1.4],
    ])
    .unwrap();
    c.bench_function("intersect/degree7_degree7", |b| {
        b.iter(|| intersect(black_box(&p7), black_box(&q7), &IntersectOptions::default()).unwrap())
    });
    let options = FilletOptions::symmetric(0.3, 3);
    c.bench_function("fillet/cubic_cubic_c3", |b| {
        b.iter(|| fillet(black_box(&p), black_box(&q), &options).unwrap())
    });
    // Issue 20: NURBS within 2x their Bezier counterparts. The same two
    // cubics as two-span NURBS, polynomial and rational (the C demo
    // driver's pair, weights inside (0.8, 1.3)).
    let (pn, qn) = (two_spans(&p, None), two_spans(&q, None));
    let (pw, qw) = (
        two_spans(&p, Some(vec![1.0, 1.3, 0.8, 1.0])),
        two_spans(&q, Some(vec![1.0, 0.9, 1.25, 1.0])),
    );
    c.bench_function("intersect/nurbs_two_span_rational", |b| {
        b.iter(|| intersect(black_box(&pw), black_box(&qw), &IntersectOptions::default()).unwrap())
    });
    c.bench_function("fillet/nurbs_two_span_c3", |b| {
        b.iter(|| fillet(black_box(&pn), black_box(&qn), &options).unwrap())
    });
    c.bench_function("fillet/nurbs_two_span_rational_c3", |b| {
        b.iter(|| fillet(black_box(&pw), black_box(&qw), &options).unwrap())
    });
    let deviation = DeviationFilletOptions::new(0.05, 3);
    // Issue 18's goal: a fair G2 fillet of two cubics at most 10x the C^k
    // fillet with given scales above.
    c.bench_function("fillet_radius/cubic_cubic_g2", |b| {
        b.iter(|| fillet_radius(black_box(&p), black_box(&q), 0.3, 2).unwrap())
    });
    c.bench_function("fillet/cubic_cubic_c3_within_deviation", |b| {
        b.iter(|| fillet_within_deviation(black_box(&p), black_box(&q), &deviation).unwrap())
    });
}

fn bench_chain(c: &mut Criterion) {
    let curves = zigzag(100_001);
    let options = ChainFilletOptions::open(FilletOptions::symmetric(0.25, 2));
    let mut group = c.benchmark_group("fillet_chain_100000_corners_c2");
    group.sample_size(10);
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        group.bench_function(format!("{threads}_threads"), |b| {
            b.iter(|| pool.install(|| fillet_chain(black_box(&curves), &options).unwrap()))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_fillet, bench_chain);
criterion_main!(benches);
