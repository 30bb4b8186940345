//! G^k connect (docs/mathematics.md#geometric-continuity): the partial Bell
//! polynomials against Stirling numbers; the beta-constraints against an
//! independent composition of Taylor series; G1-G3 judged by unit tangent,
//! curvature vector and its arc-length derivative on both sides (never by
//! raw parametric derivatives); C^k as the case `beta_j = 0`; fair shapes
//! no worse than their neighbours and loop-free on a long-edge corner.

mod common;

use bezjoin_core::{
    BezierCurve, BezjoinError, ConnectOptions, CurveJet, GEOMETRIC_CONDITION_LIMIT,
    GeometricOptions, IntersectOptions, KnotSide, MAX_LENGTH_RATIO, NurbsCurve, connect,
    connect_geometric, connect_geometric_curve, curvature_variation, fairness_report, intersect,
    partial_bell,
};
use common::Random;

/// `T`, the curvature vector `K = (r'' |r'|^2 - (r'.r'') r') / |r'|^4` and
/// `dK/ds`, from the parametric derivatives `r', r'', r'''` (rows 1..3 of a
/// jet): quantities of the point set, the same for every regular
/// parametrisation.
fn invariants(jet: &[f64], d: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let a = &jet[d..2 * d];
    let b = &jet[2 * d..3 * d];
    let c = &jet[3 * d..4 * d];
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let s2 = dot(a, a);
    let m = dot(a, b);
    let dm = dot(b, b) + dot(a, c);
    let speed = s2.sqrt();
    let t: Vec<f64> = a.iter().map(|x| x / speed).collect();
    let k: Vec<f64> = (0..d).map(|i| (b[i] * s2 - m * a[i]) / (s2 * s2)).collect();
    // d/dt of (b s2 - m a) / s2^2
    let dk_dt: Vec<f64> = (0..d)
        .map(|i| {
            let num = b[i] * s2 - m * a[i];
            let dnum = c[i] * s2 + b[i] * 2.0 * m - dm * a[i] - m * b[i];
            dnum / (s2 * s2) - num * 4.0 * m / (s2 * s2 * s2)
        })
        .collect();
    let dk_ds = dk_dt.iter().map(|x| x / speed).collect();
    (t, k, dk_ds)
}

fn gap(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt()
}

fn size(a: &[f64]) -> f64 {
    a.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The largest relative mismatch of the G^order invariants (1: T, 2: K,
/// 3: dK/ds) between two jets.
fn geometric_mismatch(left: &[f64], right: &[f64], d: usize, order: usize) -> f64 {
    let (t1, k1, dk1) = invariants(left, d);
    let (t2, k2, dk2) = invariants(right, d);
    let mut worst = gap(&t1, &t2);
    if order >= 2 {
        worst = worst.max(gap(&k1, &k2) / size(&k1).max(size(&k2)).max(1e-3));
    }
    if order >= 3 {
        worst = worst.max(gap(&dk1, &dk2) / size(&dk1).max(size(&dk2)).max(1e-3));
    }
    worst
}

/// The larger G^k mismatch ([`geometric_mismatch`]) of the blend's two ends
/// against `P` at `u0` and `Q` at `v0`.
fn ends_mismatch(
    (p, u0): (&BezierCurve, f64),
    (q, v0): (&BezierCurve, f64),
    blend: &BezierCurve,
    k: usize,
) -> f64 {
    let d = p.dim();
    geometric_mismatch(
        &p.eval_derivatives(u0, 3),
        &blend.eval_derivatives(0.0, 3),
        d,
        k,
    )
    .max(geometric_mismatch(
        &q.eval_derivatives(v0, 3),
        &blend.eval_derivatives(1.0, 3),
        d,
        k,
    ))
}

#[test]
fn partial_bell_polynomials_give_stirling_numbers() {
    // B_(n,k)(1, 1, ...) = S(n, k), the Stirling numbers of the second kind
    let b = partial_bell(&[1.0; 6], 6);
    let stirling = [
        (1, 1, 1.0),
        (4, 2, 7.0),
        (5, 2, 15.0),
        (5, 3, 25.0),
        (6, 3, 90.0),
        (6, 4, 65.0),
        (6, 6, 1.0),
    ];
    for (n, k, s) in stirling {
        assert_eq!(b[(n, k)], s, "S({n}, {k})");
    }
    // B_(n,1) = x_n, B_(n,n) = x_1^n, and B_(4,2) = 4 x1 x3 + 3 x2^2
    let x = [2.0, -3.0, 5.0, 7.0];
    let b = partial_bell(&x, 4);
    assert_eq!(b[(4, 1)], 7.0);
    assert_eq!(b[(4, 4)], 16.0);
    assert_eq!(b[(4, 2)], 4.0 * 2.0 * 5.0 + 3.0 * 9.0);
}

/// Taylor coefficients of `P(phi(t))` at `t = 0`, `phi(t) = u0 + sum beta_j
/// t^j / j!`, from `P`'s Taylor coefficients at `u0` by series
/// composition (powers of `phi - u0` by repeated multiplication): an
/// evaluation of Faa di Bruno's formula that shares nothing with the Bell
/// recurrence. Returns derivatives `0..=order` row-major.
fn composed_derivatives(p_jet: &[f64], shape: &[f64], d: usize, order: usize) -> Vec<f64> {
    let factorial = |n: usize| (1..=n).map(|i| i as f64).product::<f64>();
    // h = phi - u0 as a series: h_j = beta_j / j!
    let mut h = vec![0.0; order + 1];
    for (j, b) in shape.iter().enumerate().take(order) {
        h[j + 1] = b / factorial(j + 1);
    }
    let mut out = vec![0.0; (order + 1) * d];
    let mut power = vec![0.0; order + 1];
    power[0] = 1.0; // h^0
    for i in 0..=order {
        // add P^(i)/i! * h^i
        for j in 0..=order {
            for c in 0..d {
                out[j * d + c] += p_jet[i * d + c] / factorial(i) * power[j];
            }
        }
        let mut next = vec![0.0; order + 1];
        for a in 0..=order {
            for b in 0..=order - a {
                next[a + b] += power[a] * h[b];
            }
        }
        power = next;
    }
    for j in 0..=order {
        for c in 0..d {
            out[j * d + c] *= factorial(j);
        }
    }
    out
}

/// `k` random shape values: `beta_1` in [0.3, 2], the others in [-1, 1].
fn random_shape(rng: &mut Random, k: usize) -> Vec<f64> {
    (0..k)
        .map(|j| {
            if j == 0 {
                rng.range(0.3, 2.0)
            } else {
                rng.range(-1.0, 1.0)
            }
        })
        .collect()
}

/// Given shapes: the blend's parametric derivatives are exactly the
/// beta-constraints (against the series composition), and it meets P and Q
/// with G^k judged by T, K, dK/ds.
#[test]
fn given_shapes_satisfy_the_beta_constraints_and_meet_with_gk() {
    let mut rng = Random(31);
    for case in 0..30 {
        let d = 2 + case % 2;
        let (kp, kq) = (1 + case % 4, 1 + (case / 2) % 4);
        let p = rng.curve(d, 3 + case % 3, 2.0);
        let q = rng.curve(d, 4, 2.0);
        let (u0, v0) = (rng.range(0.3, 0.9), rng.range(0.1, 0.7));
        let (ps, qs) = (random_shape(&mut rng, kp), random_shape(&mut rng, kq));
        let options = GeometricOptions::new(kp, kq).with_shapes(ps.clone(), qs.clone());
        let g = connect_geometric(&p, u0, &q, v0, &options).unwrap();
        assert_eq!(g.p_shape, ps);
        let r = &g.curve;
        // beta-constraints at t = 0 against the composition of P's series
        let want = composed_derivatives(&p.eval_derivatives(u0, kp), &ps, d, kp);
        let got = r.eval_derivatives(0.0, kp);
        for j in 0..=kp {
            let (w, g_) = (&want[j * d..(j + 1) * d], &got[j * d..(j + 1) * d]);
            assert!(
                gap(w, g_) <= 1e-9 * (1.0 + size(w)),
                "case {case} P order {j}"
            );
        }
        // at t = 1: R(t) = Q(phi_q(t)) with phi_q^(j)(1) = beta_qj; with s = t - 1
        let want = composed_derivatives(&q.eval_derivatives(v0, kq), &qs, d, kq);
        let got = r.eval_derivatives(1.0, kq);
        for j in 0..=kq {
            let (w, g_) = (&want[j * d..(j + 1) * d], &got[j * d..(j + 1) * d]);
            assert!(
                gap(w, g_) <= 1e-9 * (1.0 + size(w)),
                "case {case} Q order {j}"
            );
        }
        // the geometric judge, both ends
        let order_p = kp.min(3);
        let left = p.eval_derivatives(u0, 3);
        let start = r.eval_derivatives(0.0, 3);
        let m = geometric_mismatch(&left, &start, d, order_p);
        assert!(m <= 1e-8, "case {case}: G{order_p} at P, mismatch {m:e}");
        let right = q.eval_derivatives(v0, 3);
        let end = r.eval_derivatives(1.0, 3);
        let order_q = kq.min(3);
        let m = geometric_mismatch(&right, &end, d, order_q);
        assert!(m <= 1e-8, "case {case}: G{order_q} at Q, mismatch {m:e}");
        // and the judge can fail: one order more than asked is not met
        if kp < 3 {
            assert!(
                geometric_mismatch(&left, &start, d, kp + 1) > 1e-6,
                "case {case}: G{} at P by accident",
                kp + 1
            );
        }
    }
}

/// `beta_j = 0` for `j >= 2` is connect's C^k with the scales `beta_1`.
#[test]
fn zero_higher_shapes_are_the_ck_connect() {
    let mut rng = Random(4);
    for case in 0..10 {
        let p = rng.curve(2, 4, 1.0);
        let q = rng.curve(2, 3, 1.0);
        let (a, b) = (rng.range(0.5, 2.0), rng.range(0.5, 2.0));
        let k = 1 + case % 3;
        let mut ps = vec![0.0; k];
        let mut qs = vec![0.0; k];
        ps[0] = a;
        qs[0] = b;
        let g = connect_geometric(
            &p,
            0.6,
            &q,
            0.3,
            &GeometricOptions::new(k, k).with_shapes(ps, qs),
        )
        .unwrap();
        let c = connect(
            &p,
            0.6,
            &q,
            0.3,
            &ConnectOptions::new(k, k).with_scales(a, b),
        )
        .unwrap();
        let worst = g
            .curve
            .points()
            .iter()
            .zip(c.curve.points())
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(worst <= 1e-12, "case {case}: {worst:e}");
    }
}

/// Two edges of a corner, 40 and 20 long, rounded with setback 2 (the
/// issue's example: connect with scale 1 loops there): the fair G2 blend is
/// loop-free, close to the length of the circular arc, with one curvature
/// maximum; no nearby shape values give a lower energy.
#[test]
fn fair_g2_blend_of_a_long_edge_corner_does_not_loop() {
    let long = BezierCurve::new(2, 1, vec![-40.0, 0.0, 0.0, 0.0]).unwrap();
    let short = BezierCurve::new(2, 1, vec![0.0, 0.0, 0.0, 20.0]).unwrap();
    let (u0, v0) = (38.0 / 40.0, 2.0 / 20.0);
    let g = connect_geometric(&long, u0, &short, v0, &GeometricOptions::new(2, 2)).unwrap();
    let r = &g.curve;
    // loop-free: the blend's two halves meet only at their shared point
    let (first, second) = r.split_at(0.5).unwrap();
    let hits = intersect(&first, &second, &IntersectOptions::default()).unwrap();
    assert!(
        hits.iter().all(|h| h.u > 1.0 - 1e-6 && h.v < 1e-6),
        "self-intersection: {hits:?}"
    );
    let length = r.arc_length(0.0, 1.0, 1e-10).unwrap();
    assert!(length < 2.0 * 4.0, "blend length {length}");
    assert_eq!(g.report.curvature_extrema, 1, "{:?}", g.report);
    assert!(g.report.curvature_min >= -1e-9 || g.report.curvature_max <= 1e-9);
    // the chosen shapes are a local minimum of the energy
    let energy_at = |ps: Vec<f64>, qs: Vec<f64>| {
        connect_geometric(
            &long,
            u0,
            &short,
            v0,
            &GeometricOptions::new(2, 2).with_shapes(ps, qs),
        )
        .map(|c| curvature_variation(&c.curve))
        .unwrap_or(f64::INFINITY)
    };
    let best = energy_at(g.p_shape.clone(), g.q_shape.clone());
    assert!((best - g.report.energy).abs() <= 1e-12 * best.max(1.0));
    let mut rng = Random(9);
    for _ in 0..20 {
        let jitter = |s: &[f64], rng: &mut Random| -> Vec<f64> {
            vec![
                s[0] * (1.0 + rng.range(-0.05, 0.05)),
                s[1] + rng.range(-0.05, 0.05) * s[0],
            ]
        };
        let (ps, qs) = (jitter(&g.p_shape, &mut rng), jitter(&g.q_shape, &mut rng));
        assert!(energy_at(ps, qs) >= best * (1.0 - 1e-6));
    }
    // the report is what the curve shows
    let report = fairness_report(r);
    assert_eq!(report, g.report);
}

/// NURBS inputs: P's jet from the left of a knot, Q's from the right; the
/// fair G3 blend of a circle arc and a line meets both with G3.
#[test]
fn nurbs_inputs_meet_with_g3() {
    let arc =
        bezjoin_core::ellipse_arc(2, &[0.0, 0.0], &[1.0, 0.0], &[0.0, 1.0], 1.0, 1.0, 0.0, 1.5)
            .unwrap();
    let line = NurbsCurve::new(
        2,
        1,
        vec![2.0, 1.5, 3.0, 3.0],
        None,
        vec![0.0, 0.0, 1.0, 1.0],
    )
    .unwrap();
    let g = connect_geometric(&arc, 1.5, &line, 0.0, &GeometricOptions::new(3, 3)).unwrap();
    let d = 2;
    let (left, _) = arc.jet(1.5, 3, KnotSide::Left);
    let left: Vec<f64> = left.transpose().as_slice().to_vec();
    let start = g.curve.eval_derivatives(0.0, 3);
    assert!(geometric_mismatch(&left, &start, d, 3) <= 1e-8);
    // the arc's curvature is 1 at the join, the line's 0
    let (_, k, _) = invariants(&start, d);
    assert!((size(&k) - 1.0).abs() <= 1e-8);
    let end = g.curve.eval_derivatives(1.0, 3);
    let (_, k, _) = invariants(&end, d);
    assert!(size(&k) <= 1e-8);
}

#[test]
fn shape_values_are_checked_by_name() {
    let p = BezierCurve::new(2, 2, vec![0.0, 0.0, 1.0, 1.0, 2.0, 0.0]).unwrap();
    let q = BezierCurve::new(2, 2, vec![3.0, 0.0, 4.0, 1.0, 5.0, 0.0]).unwrap();
    let bad = GeometricOptions::new(2, 2).with_shapes(vec![-1.0, 0.0], vec![1.0, 0.0]);
    match connect_geometric(&p, 1.0, &q, 0.0, &bad) {
        Err(BezjoinError::InvalidArgument { name, .. }) => assert_eq!(name, "p_shape[0]"),
        other => panic!("{other:?}"),
    }
    let short = GeometricOptions::new(2, 2).with_shapes(vec![1.0, 0.0], vec![1.0]);
    match connect_geometric(&p, 1.0, &q, 0.0, &short) {
        Err(BezjoinError::LengthMismatch { name, .. }) => assert_eq!(name, "q_shape"),
        other => panic!("{other:?}"),
    }
    let nan = GeometricOptions::new(1, 1).with_shapes(vec![f64::NAN], vec![1.0]);
    assert!(connect_geometric(&p, 1.0, &q, 0.0, &nan).is_err());
}

/// G^k needs a regular point: where the input's tangent is zero (repeated
/// end poles) every shape value gives `R'(0) = beta_1 P'(u0) = 0`, a blend
/// whose curvature is undefined there, so the call is IllConditioned naming
/// the curve and the parameter, with searched and with given shapes, on the
/// end path (given shapes, no constraints) and on the general one; G^0 at
/// that end, or the zero tangent away from the join, is answered.
#[test]
fn a_zero_tangent_at_the_join_is_refused_by_name() {
    // P'(1) = 3 (P3 - P2) = 0; Q'(0) = 3 (Q1 - Q0) = 0.
    let p = BezierCurve::new(2, 3, vec![0.0, 0.0, 1.0, 1.0, 2.0, 0.0, 2.0, 0.0]).unwrap();
    let q = BezierCurve::new(2, 3, vec![5.0, 3.0, 5.0, 3.0, 7.0, 2.5, 8.0, 1.0]).unwrap();
    let regular = BezierCurve::new(2, 2, vec![5.0, 3.0, 6.0, 3.0, 7.0, 2.0]).unwrap();
    let refused = |result: bezjoin_core::Result<bezjoin_core::GeometricConnection>,
                   needle: &str| {
        match result {
            Err(BezjoinError::IllConditioned { what, .. }) => {
                assert!(what.contains(needle), "{what}")
            }
            other => panic!("{needle}: {other:?}"),
        }
    };
    for order in [1, 2, 3] {
        let searched = GeometricOptions::new(order, order);
        let shapes = vec![1.0; order];
        let given = GeometricOptions::new(order, order).with_shapes(shapes.clone(), shapes.clone());
        let mut constrained = given.clone();
        constrained
            .constraints
            .push(bezjoin_core::PointConstraint::new(0.5, 0, vec![4.0, 2.0]));
        for options in [&searched, &given, &constrained] {
            refused(
                connect_geometric(&p, 1.0, &regular, 0.0, options),
                "tangent of p at u0 = 1 is zero",
            );
            refused(
                connect_geometric(&regular, 1.0, &q, 0.0, options),
                "tangent of q at v0 = 0 is zero",
            );
        }
        // G^0 at the singular end needs no tangent; away from the join the
        // zero tangent does not matter.
        assert!(
            connect_geometric(&p, 1.0, &regular, 0.0, &GeometricOptions::new(0, order)).is_ok()
        );
        assert!(connect_geometric(&p, 0.5, &regular, 0.0, &searched).is_ok());
    }
}

/// The fairness energy's quadrature (4 panels of 8-point Gauss-Legendre)
/// against a fine composite Simpson rule of the same integrand built from
/// the judge's invariants: the two agree to 1e-6 relative on a fair blend
/// and on random quintics without near-cusps.
#[test]
fn fairness_energy_quadrature_is_accurate() {
    let mut rng = Random(77);
    let long = BezierCurve::new(2, 1, vec![-40.0, 0.0, 0.0, 0.0]).unwrap();
    let short = BezierCurve::new(2, 1, vec![0.0, 0.0, 0.0, 20.0]).unwrap();
    let fair = connect_geometric(&long, 0.95, &short, 0.1, &GeometricOptions::new(2, 2))
        .unwrap()
        .curve;
    let mut curves = vec![fair];
    // random quintics whose speed stays above a fifth of its largest value
    // (no near-cusp: there a curvature peak is too sharp for any fixed rule)
    while curves.len() < 6 {
        let c = rng.curve(2, 5, 1.0);
        let speeds: Vec<f64> = (0..=200)
            .map(|i| size(&c.eval_derivatives(i as f64 / 200.0, 1)[2..4]))
            .collect();
        let (lo, hi) = speeds
            .iter()
            .fold((f64::INFINITY, 0.0f64), |(a, b), &s| (a.min(s), b.max(s)));
        if lo > 0.2 * hi {
            curves.push(c);
        }
    }
    for (k, c) in curves.iter().enumerate() {
        let m = 20000;
        let (mut variation, mut length) = (0.0, 0.0);
        for i in 0..=m {
            let t = i as f64 / m as f64;
            let w = if i == 0 || i == m {
                1.0
            } else if i % 2 == 1 {
                4.0
            } else {
                2.0
            } / (3.0 * m as f64);
            let jet = c.eval_derivatives(t, 3);
            let speed = size(&jet[2..4]);
            let (_, kappa_vector, dk) = invariants(&jet, 2);
            // in the plane, |d(kappa N)/ds|^2 = (dkappa/ds)^2 + kappa^4
            let dkappa2 = dk.iter().map(|x| x * x).sum::<f64>() - size(&kappa_vector).powi(4);
            variation += w * dkappa2 * speed;
            length += w * speed;
        }
        let reference = variation * length.powi(3);
        let ours = curvature_variation(c);
        assert!(
            (ours - reference).abs() <= 1e-6 * reference.abs().max(1e-12),
            "curve {k}: {ours} vs {reference}"
        );
    }
}

/// The table "G^k connect: beta-constraint residual versus order" of
/// docs/accuracy.md: for orders `k = 1..=6` at both ends and input degrees
/// 3, 7 and 12 (40 random cases each, 2D and 3D, random shapes with
/// `beta_1` in [0.3, 2] and the others in [-1, 1]), the largest relative
/// residual of the blend's derivatives `0..=k` against the beta-constraints
/// (evaluated independently by series composition), and for fair shapes
/// the largest G^min(k, 3) mismatch of T, K, dK/ds. Run with
/// `cargo test -p bezjoin-core --test geometric -- --ignored --nocapture`.
#[test]
#[ignore = "prints the G^k accuracy table for docs/accuracy.md"]
fn print_gk_accuracy_table() {
    let mut rng = Random(2026);
    println!(
        "| k | input degree | blend degree | beta-constraint residual (given shapes) | G^min(k,3) mismatch (fair shapes) |"
    );
    println!("|---|---|---|---|---|");
    for k in 1..=6 {
        for degree in [3usize, 7, 12] {
            let (mut worst_beta, mut worst_fair) = (0.0f64, 0.0f64);
            let mut blend_degree = 0;
            for case in 0..40 {
                let d = 2 + case % 2;
                let p = rng.curve(d, degree, 2.0);
                let q = rng.curve(d, degree, 2.0);
                let (u0, v0) = (rng.range(0.3, 0.9), rng.range(0.1, 0.7));
                let (ps, qs) = (random_shape(&mut rng, k), random_shape(&mut rng, k));
                let options = GeometricOptions::new(k, k).with_shapes(ps.clone(), qs.clone());
                let Ok(g) = connect_geometric(&p, u0, &q, v0, &options) else {
                    continue;
                };
                blend_degree = g.curve.degree();
                for (curve, at, t, s) in [(&p, u0, 0.0, &ps), (&q, v0, 1.0, &qs)] {
                    let want = composed_derivatives(&curve.eval_derivatives(at, k), s, d, k);
                    let got = g.curve.eval_derivatives(t, k);
                    for j in 0..=k {
                        let (w, x) = (&want[j * d..(j + 1) * d], &got[j * d..(j + 1) * d]);
                        worst_beta = worst_beta.max(gap(w, x) / (1.0 + size(w)));
                    }
                }
                if let Ok(fair) = connect_geometric(&p, u0, &q, v0, &GeometricOptions::new(k, k)) {
                    let o = k.min(3);
                    let m0 = geometric_mismatch(
                        &p.eval_derivatives(u0, 3),
                        &fair.curve.eval_derivatives(0.0, 3),
                        d,
                        o,
                    );
                    let m1 = geometric_mismatch(
                        &q.eval_derivatives(v0, 3),
                        &fair.curve.eval_derivatives(1.0, 3),
                        d,
                        o,
                    );
                    worst_fair = worst_fair.max(m0).max(m1);
                }
            }
            println!("| {k} | {degree} | {blend_degree} | {worst_beta:.1e} | {worst_fair:.1e} |");
        }
    }
}

/// The fair shapes of generic inputs do not depend on where the inputs
/// sit: 40 random 3D pairs (a cubic, and a quartic three units away), G2
/// and G3, each under three rigid motions (a rotation about the z axis and
/// a shift of up to 1e3 in every coordinate), 240 blends: the blend of the
/// moved inputs is the moved blend to 1e-6 of its size (measured: 5.1e-12
/// at worst). The search's path is set by comparisons of energies that
/// differ by far more than the rounding the motion changes.
///
/// Not covered, and documented (docs/reliability.md, decision 2): inputs
/// whose energy is flat along a shape value, such as a corner of two lines,
/// where the comparisons are near-ties and the capped search stops at
/// different points (a G3 corner with r = 100 moved by 333 mm: 9.9 mm).
/// A search run to convergence (docs/performance.md, session 39) fixes that
/// corner but fails this test on 8 to 17 of the 240 blends: the energy has
/// flat valleys with several local minima.
#[test]
fn the_fair_blend_of_generic_inputs_moves_with_them() {
    // xorshift, so that the cases are those measured.
    let mut state = 2024u64;
    let mut range = |lo: f64, hi: f64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        lo + (hi - lo) * ((state >> 11) as f64 / (1u64 << 53) as f64)
    };
    let mut worst = 0.0f64;
    for case in 0..40 {
        let p: Vec<f64> = (0..12).map(|_| range(-1.0, 1.0)).collect();
        let q: Vec<f64> = (0..15)
            .map(|i| range(-1.0, 1.0) + if i % 3 == 0 { 3.0 } else { 0.0 })
            .collect();
        let (u0, v0) = (range(0.5, 0.9), range(0.1, 0.5));
        for order in [2, 3] {
            let options = GeometricOptions::new(order, order);
            let (pc, qc) = (
                BezierCurve::new(3, 3, p.clone()).unwrap(),
                BezierCurve::new(3, 4, q.clone()).unwrap(),
            );
            let base = connect_geometric(&pc, u0, &qc, v0, &options).unwrap();
            let size = base
                .curve
                .points()
                .iter()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            for _ in 0..3 {
                let angle = range(-3.0, 3.0);
                let shift = [range(-1e3, 1e3), range(-1e3, 1e3), range(-1e3, 1e3)];
                let (c, s) = (angle.cos(), angle.sin());
                let moved = |v: &[f64]| -> Vec<f64> {
                    v.chunks(3)
                        .flat_map(|x| {
                            [
                                c * x[0] - s * x[1] + shift[0],
                                s * x[0] + c * x[1] + shift[1],
                                x[2] + shift[2],
                            ]
                        })
                        .collect()
                };
                let g = connect_geometric(
                    &BezierCurve::new(3, 3, moved(&p)).unwrap(),
                    u0,
                    &BezierCurve::new(3, 4, moved(&q)).unwrap(),
                    v0,
                    &options,
                )
                .unwrap();
                let gap = g
                    .curve
                    .points()
                    .iter()
                    .zip(moved(base.curve.points()))
                    .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
                    / size;
                worst = worst.max(gap);
                assert!(
                    gap <= 1e-6,
                    "case {case} G{order}, turned {angle}, shifted {shift:?}: the blend moved by \
                     {gap:e} of its size"
                );
            }
        }
    }
    assert!(worst > 0.0, "every motion changed the rounding somewhere");
}

/// Fair shape values between coincident ends are refused by name: the blend
/// is a loop, whose scale-free energy falls as it grows, and the search ran
/// away (user testing, session 40: a G0/G2 blend from a corner back to it
/// had coordinates of 1.35e68 on a part 10 across and reported energy 0; G1
/// stopped at the edge of its range with a loop to 343). Ends 1e-12 apart
/// (of a coordinate scale 10) are the same; with both shapes given the loop
/// is the caller's choice and is answered; ends apart give a blend within
/// the size of the part.
#[test]
fn fair_shapes_between_coincident_ends_are_refused_by_name() {
    let along = BezierCurve::new(2, 1, vec![0.0, 0.0, 10.0, 0.0]).unwrap();
    let up = BezierCurve::new(2, 1, vec![10.0, 0.0, 10.0, 10.0]).unwrap();
    let nearly = BezierCurve::new(2, 1, vec![10.0, 1e-11, 10.0, 10.0]).unwrap();
    for q in [&up, &nearly] {
        for (kp, kq) in [(0, 2), (1, 1), (2, 2), (3, 3)] {
            let options = GeometricOptions::new(kp, kq);
            match connect_geometric(&along, 1.0, q, 0.0, &options) {
                Err(BezjoinError::InvalidArgument { name, reason }) => {
                    assert_eq!(name, "v0", "{reason}");
                    assert!(reason.contains("coincident"), "{reason}");
                }
                Ok(g) => panic!("G{kp}/G{kq}: answered {:?}", g.curve.points()),
                Err(other) => panic!("G{kp}/G{kq}: {other}"),
            }
        }
        // One end given, the other searched: still refused.
        let mut one = GeometricOptions::new(2, 2);
        one.p_shape = Some(vec![1.0, 0.0]);
        assert!(matches!(
            connect_geometric(&along, 1.0, q, 0.0, &one),
            Err(BezjoinError::InvalidArgument { .. })
        ));
        let given = GeometricOptions::new(2, 2).with_shapes(vec![1.0, 0.0], vec![1.0, 0.0]);
        let g = connect_geometric(&along, 1.0, q, 0.0, &given).unwrap();
        assert!(g.curve.points().iter().all(|v| v.abs() <= 20.0));
    }
    // Ends apart by a thousandth of the part: a blend, no larger than it.
    let apart = BezierCurve::new(2, 1, vec![10.0, 0.01, 10.0, 10.0]).unwrap();
    for (kp, kq) in [(0, 2), (1, 1), (2, 2), (3, 3)] {
        let g = connect_geometric(&along, 1.0, &apart, 0.0, &GeometricOptions::new(kp, kq));
        let g = g.unwrap_or_else(|e| panic!("G{kp}/G{kq}: {e}"));
        let largest = g.curve.points().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(largest <= 20.0, "G{kp}/G{kq}: coordinates up to {largest}");
    }
}

/// Where the ends face away from each other every G^k blend loops, and the
/// scale-free fairness energy falls as the loop grows: the search ran to
/// blends 1e3-1e6 times the gap (user testing, session 40: 8,261 mm on a
/// 7.07 mm gap between two 40 mm lines; 63 of 400 random pairs above 100
/// times). The fair blend is now at most `MAX_LENGTH_RATIO` chords long
/// (its length by the search's rule; checked here to 2 % by arc length) and
/// still meets P and Q with G^k; ordinary ends are not affected (a U-turn
/// stays near 2 chords).
#[test]
fn a_fair_blend_between_ends_facing_away_is_at_most_ten_chords_long() {
    let line = |a: [f64; 2], b: [f64; 2]| BezierCurve::new(2, 1, vec![a[0], a[1], b[0], b[1]]);
    let p = line([0.0, 0.0], [40.0, 0.0]).unwrap();
    let cases = [
        (line([40.0, 2.0], [0.0, 2.0]).unwrap(), 3.0), // a U-turn: no loop needed
        (line([38.0, 5.0], [38.0, 40.0]).unwrap(), MAX_LENGTH_RATIO), // Q starts behind P's end
        (line([45.0, 5.0], [45.0, -30.0]).unwrap(), MAX_LENGTH_RATIO), // Q heads back down
    ];
    let mut rng = Random(40);
    let mut random = Vec::new();
    for _ in 0..60 {
        let mut points = |offset: f64| -> Vec<f64> {
            (0..8)
                .map(|i| rng.range(-1.5, 1.5) + if i % 2 == 0 { offset } else { 0.0 })
                .collect()
        };
        let (a, b) = (points(0.0), points(3.0));
        random.push((
            BezierCurve::new(2, 3, a).unwrap(),
            rng.range(0.3, 1.0),
            BezierCurve::new(2, 3, b).unwrap(),
            rng.range(0.0, 0.7),
        ));
    }
    let all = cases
        .iter()
        .map(|(q, limit)| (&p, 1.0, q, 0.0, *limit))
        .chain(
            random
                .iter()
                .map(|(p, u0, q, v0)| (p, *u0, q, *v0, MAX_LENGTH_RATIO)),
        );
    for (case, (p, u0, q, v0, limit)) in all.enumerate() {
        for k in 1..=3 {
            let g = match connect_geometric(p, u0, q, v0, &GeometricOptions::new(k, k)) {
                Ok(g) => g,
                Err(e) => panic!("case {case} G{k}: {e}"),
            };
            let chord = gap(&p.eval(u0), &q.eval(v0));
            let length = g.curve.arc_length(0.0, 1.0, 1e-9).unwrap();
            assert!(
                length <= 1.02 * limit * chord,
                "case {case} G{k}: length {length} for the chord {chord}"
            );
            let d = p.dim();
            let r0 = g.curve.eval_derivatives(0.0, 3);
            let r1 = g.curve.eval_derivatives(1.0, 3);
            let mismatch = geometric_mismatch(&p.eval_derivatives(u0, 3), &r0, d, k)
                .max(geometric_mismatch(&q.eval_derivatives(v0, 3), &r1, d, k));
            assert!(
                mismatch <= 1e-6,
                "case {case} G{k}: G^k mismatch {mismatch}"
            );
        }
    }
}

#[test]
fn fair_blends_of_nearly_stationary_ends_are_answered_in_size() {
    // Reliability R1: P ends at (6 + eps, 1), Q starts at (10 - eps, -1), each
    // with its end poles eps apart (|P'| = |Q'| = 3 eps). The search's grid
    // was centred on beta_1 = chord / |P'| per end (3e3 chords for eps =
    // 1e-3), where every trial blend is over ten chords long, and G^2 was
    // refused for every eps up to 1e-3. With the ends' speeds raised to
    // their floor (BALANCED_SPEED_FLOOR) the fair blends are answered, at
    // most ten chords long, and meet both ends with G^k.
    // Below eps = 1e-6 the ends' tangents are not known to
    // GEOMETRIC_CONDITION_LIMIT and the blend is refused
    // (`a_numerically_stationary_end_is_refused_and_every_answer_meets_gk`).
    for eps in [1e-6, 1e-5, 1e-4, 1e-3] {
        let p = BezierCurve::from_rows(&[[0.0, 0.0], [3.0, 0.0], [6.0, 1.0], [6.0 + eps, 1.0]])
            .unwrap();
        let q =
            BezierCurve::from_rows(&[[10.0 - eps, -1.0], [10.0, -1.0], [10.0, 3.0], [11.0, 8.0]])
                .unwrap();
        for k in [2, 3] {
            let g = connect_geometric(&p, 1.0, &q, 0.0, &GeometricOptions::new(k, k))
                .unwrap_or_else(|e| panic!("eps {eps:e}, G{k}: {e}"));
            let chord = gap(&p.eval(1.0), &q.eval(0.0));
            let length = g.curve.arc_length(0.0, 1.0, 1e-9).unwrap();
            assert!(
                length <= 1.02 * MAX_LENGTH_RATIO * chord,
                "eps {eps:e}, G{k}: length {length} for the chord {chord}"
            );
            {
                let mismatch = ends_mismatch((&p, 1.0), (&q, 0.0), &g.curve, k);
                assert!(mismatch <= 1e-6, "eps {eps:e}, G{k}: mismatch {mismatch:e}");
            }
        }
    }
}

#[test]
fn a_numerically_stationary_end_is_refused_and_every_answer_meets_gk() {
    // User testing, session 42: an end whose last two poles are eps apart
    // was answered for every eps > 0, with the tangent off by 8 degrees and
    // the curvature by 92 % at eps = 3e-15, 1.7e-5 at 1e-12; and next to an
    // interior cusp (u0 = 0.5 + 1e-10 on a cubic with a cusp at 0.5) the
    // curvature was off by 100 %. The invariants are now known to
    // GEOMETRIC_CONDITION_LIMIT or the blend is refused (IllConditioned,
    // naming the end); every answer meets G^k, judged here from the
    // inputs' own jets. Both paths: 2D with given shapes (the end path) and
    // fair shapes (the general path), and 5D (always the general path).
    let q2 =
        BezierCurve::from_rows(&[[9.0, 1.0], [10.0, -1.0], [12.0, -1.0], [13.0, 1.0]]).unwrap();
    let (mut answered, mut refused) = (0, 0);
    let mut check = |p: &BezierCurve, u0: f64, q: &BezierCurve, k: usize, shapes: bool| {
        let mut options = GeometricOptions::new(k, k);
        if shapes {
            options = options.with_shapes(
                vec![1.0, 0.3, -0.2][..k].to_vec(),
                vec![1.0, 0.1, 0.4][..k].to_vec(),
            );
        }
        match connect_geometric_curve(p, u0, q, 0.0, &options) {
            Ok(g) => {
                let mismatch = ends_mismatch((p, u0), (q, 0.0), &g.curve, k);
                assert!(
                    mismatch <= GEOMETRIC_CONDITION_LIMIT,
                    "u0 {u0}, G{k}: mismatch {mismatch:e}"
                );
                answered += 1;
                None
            }
            Err(BezjoinError::IllConditioned {
                what,
                estimate,
                limit,
            }) => {
                assert_eq!(limit, GEOMETRIC_CONDITION_LIMIT, "{what}");
                assert!(estimate > limit && what.contains("p at u0"), "{what}");
                refused += 1;
                Some(estimate)
            }
            Err(e) => panic!("u0 {u0}, G{k}: {e}"),
        }
    };
    for eps in [3e-15, 1e-12, 1e-9, 1e-6, 1e-3] {
        let p = BezierCurve::from_rows(&[
            [0.0, 0.0],
            [2.0, 3.0],
            [5.0, 3.0],
            [5.0 + eps, 3.0 - 0.3 * eps],
        ])
        .unwrap();
        let lift = |c: &BezierCurve| {
            let points: Vec<f64> = c
                .points()
                .chunks(2)
                .flat_map(|xy| [xy[0], xy[1], 0.5 * xy[0], -xy[1], 1.0])
                .collect();
            BezierCurve::new(5, c.degree(), points).unwrap()
        };
        for k in [2, 3] {
            for shapes in [true, false] {
                let estimate = check(&p, 1.0, &q2, k, shapes);
                // The fixed arrays (2D, shapes given) and the general path agree.
                let lifted = check(&lift(&p), 1.0, &lift(&q2), k, shapes);
                assert_eq!(estimate.is_some(), lifted.is_some(), "eps {eps:e} G{k}");
                if eps <= 1e-9 {
                    assert!(estimate.is_some(), "eps {eps:e} G{k} was answered");
                }
            }
        }
    }
    // Next to an interior cusp: P' and P'' nearly parallel, the curvature a
    // small difference of large numbers.
    let cusp = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [1.0, 0.0]]).unwrap();
    let q = BezierCurve::from_rows(&[[3.0, 0.0], [4.0, 1.0], [5.0, 0.0]]).unwrap();
    for offset in [1e-10, 1e-8, 1e-6, 1e-4, 1e-2] {
        let estimate = check(&cusp, 0.5 + offset, &q, 2, false);
        if offset <= 1e-8 {
            assert!(estimate.is_some(), "cusp + {offset:e} was answered");
        }
    }
    assert!(
        answered >= 10 && refused >= 10,
        "{answered} answered, {refused} refused"
    );
}

#[test]
fn a_blend_whose_poles_cannot_hold_its_curvature_is_refused() {
    // User testing, session 42: the same cubics as B-splines on [0, D]. With
    // D = 1e6 and shape values [1, 0.5] the blend's first control-point steps
    // are 5e-7 on coordinates of 3, and its stored poles cannot hold the
    // curvature: answered with the curvature at q off by 1.4e-3. The
    // estimate now counts the stored blend's own rounding: refused; every
    // answer meets G^2 to the limit, judged from the inputs' own jets.
    let p_poles = [0.0, 0.0, 1.0, 0.8, 2.2, 1.1, 3.0, 0.9];
    let q_poles = [4.0, 0.2, 4.8, -0.6, 5.5, -1.7, 7.0, -2.0];
    for domain in [1.0, 1e3, 1e6] {
        let knots = |d: f64| vec![0.0, 0.0, 0.0, 0.0, d, d, d, d];
        let p = NurbsCurve::new(2, 3, p_poles.to_vec(), None, knots(domain)).unwrap();
        let q = NurbsCurve::new(2, 3, q_poles.to_vec(), None, knots(domain)).unwrap();
        let options = GeometricOptions::new(2, 2).with_shapes(vec![1.0, 0.5], vec![1.0, 0.5]);
        match connect_geometric_curve(&p, domain, &q, 0.0, &options) {
            Ok(g) => {
                let left = p
                    .jet(domain, 3, KnotSide::Left)
                    .0
                    .transpose()
                    .as_slice()
                    .to_vec();
                let right = q
                    .jet(0.0, 3, KnotSide::Right)
                    .0
                    .transpose()
                    .as_slice()
                    .to_vec();
                let mismatch =
                    geometric_mismatch(&left, &g.curve.eval_derivatives(0.0, 3), 2, 2).max(
                        geometric_mismatch(&right, &g.curve.eval_derivatives(1.0, 3), 2, 2),
                    );
                assert!(
                    mismatch <= GEOMETRIC_CONDITION_LIMIT,
                    "domain {domain:e}: mismatch {mismatch:e}"
                );
                assert!(domain < 1e6, "domain {domain:e} was answered");
            }
            Err(BezjoinError::IllConditioned {
                estimate, limit, ..
            }) => {
                assert!(estimate > limit && domain > 1.0, "domain {domain:e}");
            }
            Err(e) => panic!("domain {domain:e}: {e}"),
        }
    }
}

#[test]
fn the_fair_blend_of_a_long_knot_range_is_the_blend_of_the_unit_range() {
    // Review, session 42: before the fair search the condition check took
    // beta_1 = 1, so the same cubics as B-splines on [0, 1e9] (|P'| 1e9
    // times smaller) were refused, where the search's beta_1 makes up for
    // the parametrisation. The fair blend does not depend on it.
    let p_poles = [0.0, 0.0, 1.0, 0.8, 2.2, 1.1, 3.0, 0.9];
    let q_poles = [4.0, 0.2, 4.8, -0.6, 5.5, -1.7, 7.0, -2.0];
    let knots = |d: f64| vec![0.0, 0.0, 0.0, 0.0, d, d, d, d];
    for k in [2, 3] {
        let blend = |domain: f64| {
            let p = NurbsCurve::new(2, 3, p_poles.to_vec(), None, knots(domain)).unwrap();
            let q = NurbsCurve::new(2, 3, q_poles.to_vec(), None, knots(domain)).unwrap();
            connect_geometric_curve(&p, domain, &q, 0.0, &GeometricOptions::new(k, k))
                .unwrap_or_else(|e| panic!("G{k} on [0, {domain:e}]: {e}"))
                .curve
        };
        let unit = blend(1.0);
        for domain in [1e6, 1e9, 1e12] {
            let other = blend(domain);
            let gap = unit
                .points()
                .iter()
                .zip(other.points())
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(
                gap <= 1e-9 * unit.coordinate_scale(),
                "G{k} on [0, {domain:e}]: {gap:e}"
            );
        }
    }
}

/// `L^3 int (d kappa/ds)^2 ds` of the 2D cubic `b` by composite Simpson
/// on a grid of `coarse` intervals, with `fine` intervals in
/// `[centre - half, centre + half]`: the cubic's derivatives in closed form
/// (a quadratic hodograph, a linear second derivative), independent of the
/// library's quadrature.
fn cubic_energy_by_simpson(
    b: [[f64; 2]; 4],
    (centre, half): (f64, f64),
    coarse: usize,
    fine: usize,
) -> f64 {
    let d1: Vec<[f64; 2]> = (0..3)
        .map(|i| [3.0 * (b[i + 1][0] - b[i][0]), 3.0 * (b[i + 1][1] - b[i][1])])
        .collect();
    let d2: Vec<[f64; 2]> = (0..2)
        .map(|i| {
            [
                2.0 * (d1[i + 1][0] - d1[i][0]),
                2.0 * (d1[i + 1][1] - d1[i][1]),
            ]
        })
        .collect();
    let d3 = [d2[1][0] - d2[0][0], d2[1][1] - d2[0][1]];
    // (int (dkappa/dt)^2 / |r'| dt, int |r'| dt) integrands at t.
    let at = |t: f64| {
        let s = 1.0 - t;
        let a: Vec<f64> = (0..2)
            .map(|c| s * s * d1[0][c] + 2.0 * s * t * d1[1][c] + t * t * d1[2][c])
            .collect();
        let bb: Vec<f64> = (0..2).map(|c| s * d2[0][c] + t * d2[1][c]).collect();
        let s2 = a[0] * a[0] + a[1] * a[1];
        let speed = s2.sqrt();
        let cross = a[0] * bb[1] - a[1] * bb[0];
        let cross_dot = a[0] * d3[1] - a[1] * d3[0];
        let ab = a[0] * bb[0] + a[1] * bb[1];
        let dkappa = cross_dot / (speed * s2) - 3.0 * cross * ab / (speed * s2 * s2);
        (dkappa * dkappa / speed, speed)
    };
    let mut sums = (0.0, 0.0);
    let mut simpson = |lo: f64, hi: f64, n: usize| {
        let h = (hi - lo) / n as f64;
        for i in 0..n {
            let (x0, x1, x2) = (
                at(lo + i as f64 * h),
                at(lo + (i as f64 + 0.5) * h),
                at(lo + (i + 1) as f64 * h),
            );
            sums.0 += h / 6.0 * (x0.0 + 4.0 * x1.0 + x2.0);
            sums.1 += h / 6.0 * (x0.1 + 4.0 * x1.1 + x2.1);
        }
    };
    let (lo, hi) = (centre - half, centre + half);
    simpson(0.0, lo, coarse);
    simpson(lo, hi, fine);
    simpson(hi, 1.0, coarse);
    sums.0 * sums.1.powi(3)
}

#[test]
fn the_reported_energy_counts_a_near_cusp_between_the_nodes() {
    // Session 43: a blend whose speed dips to near zero between the
    // quadrature's nodes had its curvature peak missed by the rule, and its
    // energy was reported (and ranked by the fair search) 1e5 to 1e24 times
    // too small. The cubic (0, 0), (1, 1), (delta, 1), (1, 0) has speed
    // 0.75 delta at t = 1/2 (a cusp for delta = 0), a panel boundary of
    // the 64-panel rule: the reported energy must match an independent
    // Simpson rule fine enough to resolve the dip (width about delta / 8).
    for delta in [1e-2, 1e-3, 1e-4] {
        let b = [[0.0, 0.0], [1.0, 1.0], [delta, 1.0], [1.0, 0.0]];
        let curve = BezierCurve::from_rows(&b).unwrap();
        let reference = cubic_energy_by_simpson(b, (0.5, 0.02), 4000, 400_000);
        let reported = curvature_variation(&curve);
        assert!(
            (reported / reference - 1.0).abs() <= 0.02,
            "delta {delta:e}: reported {reported:e}, Simpson {reference:e}"
        );
        assert_eq!(fairness_report(&curve).energy, reported);
    }
}

#[test]
fn a_fair_blend_from_an_end_with_a_short_last_leg_stays_near_the_gap() {
    // Reliability D1 (session 42), its cause found in session 43: P's last
    // leg is 1 % of the gap and turns P by 70 degrees, so every G^2 blend
    // starts with P's radius of about 1e-3 of the gap. The fair search
    // ranked its trials on 4 panels, blind to near-cusps between the nodes,
    // and returned blends 8.6 to 10 gaps long that doubled back over P
    // (their energy 1e5 to 1e14 times the short blend's). With the search's
    // winner re-ranked with its speed dips refined (and the search run again
    // when that ranking was fooled) the blend stays within twice the gap,
    // has no near-cusp, and meets both ends with G^k.
    let q = BezierCurve::from_rows(&[[1.0, 0.0], [2.0, 0.5], [3.0, -1.0], [4.0, 0.0]]).unwrap();
    for eps in [0.01, 0.005, 0.002] {
        let p = BezierCurve::from_rows(&[
            [-4.0, -1.0],
            [-3.0, 1.0],
            [-1.0, 0.3],
            [-1.0, 0.3 - 2.0 * eps],
        ])
        .unwrap();
        for k in [2, 3] {
            let g = connect_geometric(&p, 1.0, &q, 0.0, &GeometricOptions::new(k, k))
                .unwrap_or_else(|e| panic!("eps {eps}, G{k}: {e}"));
            let chord = gap(&p.eval(1.0), &q.eval(0.0));
            let length = g.curve.arc_length(0.0, 1.0, 1e-9).unwrap();
            assert!(
                length <= 2.0 * chord,
                "eps {eps}, G{k}: length {length} for the chord {chord}"
            );
            let speeds: Vec<f64> = (0..=20_000)
                .map(|i| size(&g.curve.derivative_at(i as f64 / 20_000.0, 1)))
                .collect();
            let slowest = speeds.iter().copied().fold(f64::INFINITY, f64::min);
            let mean = speeds.iter().sum::<f64>() / speeds.len() as f64;
            assert!(
                slowest >= 1e-3 * mean,
                "eps {eps}, G{k}: speed dips to {slowest:e} (mean {mean:e})"
            );
            let mismatch = ends_mismatch((&p, 1.0), (&q, 0.0), &g.curve, k);
            assert!(mismatch <= 1e-6, "eps {eps}, G{k}: mismatch {mismatch:e}");
        }
    }
}

/// A fair blend between ends that are each other's image under a point
/// reflection (two parallel lines stepped, in 3D, the second line twice as
/// fast) is point-symmetric: `R_i + R_(n-i) = P(u0) + Q(v0)` to 1e-9 of the
/// chord, at G1 to G4 (session 44: the search takes P's shape values alone
/// and Q's their mirror, module `geometric::symmetry`).
#[test]
fn a_fair_blend_between_point_symmetric_ends_is_point_symmetric() {
    let p = BezierCurve::new(3, 1, vec![-10.0, 0.0, 1.0, 0.0, 0.0, 1.0]).unwrap();
    let q = BezierCurve::new(3, 1, vec![3.0, 2.0, 2.5, 23.0, 2.0, 2.5]).unwrap();
    for k in 1..=4 {
        let g = connect_geometric_curve(&p, 1.0, &q, 0.0, &GeometricOptions::new(k, k))
            .unwrap_or_else(|e| panic!("G{k}: {e}"));
        let n = g.curve.degree();
        let chord = common::distance(g.curve.point(0), g.curve.point(n));
        for i in 0..=n {
            let (a, b) = (g.curve.point(i), g.curve.point(n - i));
            for c in 0..3 {
                let sum = a[c] + b[c];
                let ends = [0.0 + 3.0, 0.0 + 2.0, 1.0 + 2.5][c];
                assert!(
                    (sum - ends).abs() <= 1e-9 * chord,
                    "G{k} pole {i}: {sum} vs {ends}"
                );
            }
        }
    }
}
