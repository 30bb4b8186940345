//! A fixed amount of merge work for instruction counts (callgrind), the
//! same pairs as `benches/merge.rs`: `MERGE_CASE="degree,metric,split"`
//! (metric `discrete` / `integral`, split `given` (mu = 0.4) / `optimal`),
//! `MERGE_REPEATS` merges. `MERGE_PAIR=back` merges the two pieces of one
//! curve split at 0.4 instead (a pair every degree answers: the default
//! pair is refused at degree 31, so it counts only the refusal).
//! `MERGE_PAIR=demo` merges the C++ demo's row "merge two cubics,
//! discrete, mu = 1/2" (`cpp-demo/demo.cpp`, `check_merge`): its two 3D
//! cubics, fix ends, `mu = 1/2` (the degree and split of `MERGE_CASE`
//! ignored, its metric used).
//! `MERGE_KIND=bspline` merges the same pair as one-span B-splines with
//! `merge_bsplines` (the B-spline / Bezier ratio of issue 20).
//! `MERGE_POINTS=file` reads the pair from a file instead (two lines of
//! planar control points `x0 y0 x1 y1 ...`, the degree of `MERGE_CASE` then
//! ignored: e.g. the random pairs of `bindings/python/bench/degree_growth.py`),
//! and `MERGE_MU` replaces the given `mu = 0.4`. Run the difference of two repeat counts under
//! `valgrind --tool=callgrind` for the per-merge count:
//! `MERGE_CASE=15,discrete,given MERGE_REPEATS=10 cargo test --release -p
//! bezjoin-core --test merge_instructions -- --ignored`.

use bezjoin_core::{
    BezierCurve, Breakpoints, MergeMetric, MergeOptions, NurbsCurve, merge, merge_bsplines,
};

fn pair(degree: usize) -> (BezierCurve, BezierCurve) {
    let make = |offset: usize, shift: f64| {
        let pts: Vec<f64> = (0..(degree + 1) * 2)
            .map(|i| ((i * 7919 + offset) % 97) as f64 / 9.7 + if i % 2 == 0 { shift } else { 0.0 })
            .collect();
        BezierCurve::new(2, degree, pts).unwrap()
    };
    (make(0, 0.0), make(31, 10.0))
}

#[test]
#[ignore]
fn merge_work() {
    let Ok(case) = std::env::var("MERGE_CASE") else {
        return;
    };
    let repeats: usize = std::env::var("MERGE_REPEATS")
        .ok()
        .and_then(|r| r.parse().ok())
        .unwrap_or(1);
    let parts: Vec<&str> = case.split(',').collect();
    let degree: usize = parts[0].parse().unwrap();
    let metric = match parts[1] {
        "integral" => MergeMetric::Integral,
        _ => MergeMetric::Discrete,
    };
    let given: f64 = std::env::var("MERGE_MU")
        .ok()
        .and_then(|m| m.parse().ok())
        .unwrap_or(0.4);
    let split = match parts[2] {
        "optimal" => Breakpoints::Optimal,
        _ => Breakpoints::Given(vec![given]),
    };
    let from_file = std::env::var("MERGE_POINTS")
        .ok()
        .filter(|path| !path.is_empty())
        .map(|path| {
            let text = std::fs::read_to_string(path).unwrap();
            let curves: Vec<BezierCurve> = text
                .lines()
                .take(2)
                .map(|line| {
                    let values: Vec<f64> = line
                        .split_whitespace()
                        .map(|v| v.parse().unwrap())
                        .collect();
                    BezierCurve::new(2, values.len() / 2 - 1, values).unwrap()
                })
                .collect();
            (curves[0].clone(), curves[1].clone())
        });
    let demo = std::env::var("MERGE_PAIR").is_ok_and(|v| v == "demo");
    let degree = if demo {
        3
    } else {
        from_file.as_ref().map_or(degree, |(p, _)| p.degree())
    };
    let (p, q) = if demo {
        let p = [0.0, 0.0, 0.0, 0.4, 0.5, 0.1, 0.9, 0.7, 0.2, 1.4, 0.75, 0.2];
        let q = [1.4, 0.75, 0.2, 1.9, 0.8, 0.2, 2.4, 0.5, 0.1, 2.8, 0.0, 0.0];
        (
            BezierCurve::new(3, 3, p.to_vec()).unwrap(),
            BezierCurve::new(3, 3, q.to_vec()).unwrap(),
        )
    } else if let Some(pair) = from_file {
        pair
    } else if std::env::var("MERGE_PAIR").is_ok_and(|v| v == "back") {
        let (whole, _) = pair(degree);
        whole.split_at(0.4).unwrap()
    } else {
        pair(degree)
    };
    let options = if demo {
        MergeOptions {
            fix_ends: true,
            ..MergeOptions::default()
                .with_metric(metric)
                .with_split(Breakpoints::Uniform)
        }
    } else {
        MergeOptions::default()
            .with_metric(metric)
            .with_split(split)
    };
    let one_span = |c: &BezierCurve| {
        let knots = [vec![0.0; degree + 1], vec![1.0; degree + 1]].concat();
        NurbsCurve::new(c.dim(), degree, c.points().to_vec(), None, knots).unwrap()
    };
    let bspline = std::env::var("MERGE_KIND").is_ok_and(|v| v == "bspline");
    let (ps, qs) = (one_span(&p), one_span(&q));
    let mut answered = 0;
    let mut refusal = None;
    for _ in 0..repeats {
        let outcome = if bspline {
            std::hint::black_box(merge_bsplines(&ps, &qs, &options)).map(|_| ())
        } else {
            std::hint::black_box(merge(&p, &q, &options)).map(|_| ())
        };
        match outcome {
            Ok(()) => answered += 1,
            Err(e) => refusal = Some(e),
        }
    }
    println!("{case}: {answered}/{repeats} answered");
    if let Some(e) = refusal {
        println!("refused: {e}");
    }
}
