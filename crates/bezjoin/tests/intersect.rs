//! Curve-curve intersection: cases whose answer is known by construction,
//! the hard cases (ends, tangency, degenerate control points, overlaps, 3D),
//! and random curves against a fine polyline.

mod common;
use bezjoin_core::BezierCurve;
use bezjoin_core::{IntersectOptions, IntersectionKind, intersect};
use common::distance;

fn curve(rows: &[&[f64]]) -> BezierCurve {
    BezierCurve::from_rows(rows).unwrap()
}

fn hits(p: &BezierCurve, q: &BezierCurve) -> Vec<bezjoin_core::Intersection> {
    intersect(p, q, &IntersectOptions::default()).unwrap()
}

/// A tiny deterministic generator (no dependency; reproducible failures).
struct Lcg(u64);
impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((self.0 >> 11) as f64) / ((1u64 << 53) as f64)
    }
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

#[test]
fn line_line_through_a_chosen_point() {
    let mut rng = Lcg(7);
    for _ in 0..200 {
        let x = [rng.range(-5.0, 5.0), rng.range(-5.0, 5.0)];
        let (s, t) = (rng.range(0.05, 0.95), rng.range(0.05, 0.95));
        let a = rng.range(0.0, std::f64::consts::TAU);
        let b = a + rng.range(0.2, 2.9);
        let (la, lb) = (rng.range(0.5, 3.0), rng.range(0.5, 3.0));
        let p = curve(&[
            &[x[0] - s * la * a.cos(), x[1] - s * la * a.sin()],
            &[
                x[0] + (1.0 - s) * la * a.cos(),
                x[1] + (1.0 - s) * la * a.sin(),
            ],
        ]);
        let q = curve(&[
            &[x[0] - t * lb * b.cos(), x[1] - t * lb * b.sin()],
            &[
                x[0] + (1.0 - t) * lb * b.cos(),
                x[1] + (1.0 - t) * lb * b.sin(),
            ],
        ]);
        let h = hits(&p, &q);
        assert_eq!(h.len(), 1);
        assert_eq!(h[0].kind, IntersectionKind::Crossing);
        assert!((h[0].u - s).abs() < 1e-13, "{} vs {s}", h[0].u);
        assert!((h[0].v - t).abs() < 1e-13, "{} vs {t}", h[0].v);
        assert!(distance(&h[0].point, &x) < 1e-13);
    }
}

#[test]
fn line_cubic_with_known_parameter() {
    // Q is the graph of a cubic over x = 3v (x linear in v), so the vertical
    // line x = 3 v0 meets it exactly once, at v = v0.
    let mut rng = Lcg(11);
    for _ in 0..100 {
        let ys: Vec<f64> = (0..4).map(|_| rng.range(-2.0, 2.0)).collect();
        let q = curve(&[&[0.0, ys[0]], &[1.0, ys[1]], &[2.0, ys[2]], &[3.0, ys[3]]]);
        let v0 = rng.range(0.01, 0.99);
        let y = q.eval(v0)[1];
        let s = rng.range(0.1, 0.9);
        let p = curve(&[&[3.0 * v0, y - 5.0 * s], &[3.0 * v0, y + 5.0 * (1.0 - s)]]);
        let h = hits(&p, &q);
        assert_eq!(h.len(), 1, "{h:?}");
        assert_eq!(h[0].kind, IntersectionKind::Crossing);
        assert!((h[0].v - v0).abs() < 1e-13, "{} vs {v0}", h[0].v);
        assert!((h[0].u - s).abs() < 1e-13, "{} vs {s}", h[0].u);
    }
}

/// Cubic of the form `a + b t + c t^2 + d t^3` as Bernstein coefficients.
fn power_to_bernstein(c: [f64; 4]) -> [f64; 4] {
    [
        c[0],
        c[0] + c[1] / 3.0,
        c[0] + 2.0 * c[1] / 3.0 + c[2] / 3.0,
        c[0] + c[1] + c[2] + c[3],
    ]
}

#[test]
fn cubic_cubic_with_three_chosen_crossings() {
    // P = (3t, yp(t)), Q = (3s, yq(s)): they meet where yp(t) = yq(t), and
    // yp - yq = k (t - r1)(t - r2)(t - r3) has the chosen roots.
    let mut rng = Lcg(13);
    for _ in 0..100 {
        let mut r = [rng.next(), rng.next(), rng.next()];
        r.sort_by(f64::total_cmp);
        r = [0.05 + 0.9 * r[0], 0.05 + 0.9 * r[1], 0.05 + 0.9 * r[2]];
        if r[1] - r[0] < 0.02 || r[2] - r[1] < 0.02 {
            continue;
        }
        let k = rng.range(2.0, 10.0) * if rng.next() < 0.5 { -1.0 } else { 1.0 };
        let diff = [
            -k * r[0] * r[1] * r[2],
            k * (r[0] * r[1] + r[0] * r[2] + r[1] * r[2]),
            -k * (r[0] + r[1] + r[2]),
            k,
        ];
        let base = [
            rng.range(-1.0, 1.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
            rng.range(-3.0, 3.0),
        ];
        let yq = power_to_bernstein(base);
        let yp = power_to_bernstein([
            base[0] + diff[0],
            base[1] + diff[1],
            base[2] + diff[2],
            base[3] + diff[3],
        ]);
        let p = curve(&[&[0.0, yp[0]], &[1.0, yp[1]], &[2.0, yp[2]], &[3.0, yp[3]]]);
        let q = curve(&[&[0.0, yq[0]], &[1.0, yq[1]], &[2.0, yq[2]], &[3.0, yq[3]]]);
        let h = hits(&p, &q);
        assert_eq!(h.len(), 3, "roots {r:?}: {h:?}");
        for (hit, root) in h.iter().zip(r) {
            assert_eq!(hit.kind, IntersectionKind::Crossing);
            assert!((hit.u - root).abs() < 1e-12, "{} vs {root}", hit.u);
            assert!((hit.v - root).abs() < 1e-12, "{} vs {root}", hit.v);
        }
    }
}

#[test]
fn crossings_at_and_near_end_points() {
    // A T-junction: P ends exactly on Q.
    let q = curve(&[&[0.0, 0.0], &[1.0, 1.0], &[2.0, -1.0], &[3.0, 0.0]]);
    let v0 = 0.3;
    let x = q.eval(v0);
    let p = curve(&[
        &[x[0] - 1.0, x[1] + 2.0],
        &[x[0] + 0.2, x[1] + 1.0],
        &[x[0], x[1]],
    ]);
    let h = hits(&p, &q);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!(h[0].u, 1.0);
    assert!((h[0].v - v0).abs() < 1e-14);
    assert_eq!(h[0].kind, IntersectionKind::Crossing);
    // A corner of a chain: P(1) = Q(0).
    let q2 = curve(&[
        &[x[0], x[1]],
        &[x[0] + 1.0, x[1] + 0.5],
        &[x[0] + 2.0, x[1] - 1.0],
    ]);
    let h = hits(&p, &q2);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!((h[0].u, h[0].v), (1.0, 0.0));
    assert_eq!(h[0].kind, IntersectionKind::Crossing);
    // P extended past Q (still crossing), shortened by less than the
    // tolerance (meets within it) and by more (no intersection).
    for (shift, expect) in [(1e-10, 1usize), (-1e-10, 1), (1e-6, 1), (-1e-6, 0)] {
        // P extended or shortened along its end tangent direction.
        let end = p.segment(0.0, 1.0 + shift).unwrap();
        let h = hits(&end, &q);
        assert_eq!(h.len(), expect, "shift {shift}: {h:?}");
        if expect == 0 {
            continue;
        }
        // The constructed answer. Extended: end(u) = P(u (1 + shift)) is
        // X = P(1) = Q(v0) at u = 1 / (1 + shift), v = v0. Shortened within
        // the tolerance: the closest approach, u = 1 (the end of the
        // shortened P) and v the foot of end(1) on Q, found here by Newton
        // on Q'(v) . (Q(v) - end(1)) = 0 from v0.
        let (u_expected, v_expected) = if shift > 0.0 {
            (1.0 / (1.0 + shift), v0)
        } else {
            let y = end.eval(1.0);
            let mut v = v0;
            for _ in 0..20 {
                let (qv, d1, d2) = (q.eval(v), q.derivative_at(v, 1), q.derivative_at(v, 2));
                let r: Vec<f64> = (0..2).map(|c| qv[c] - y[c]).collect();
                let f = d1[0] * r[0] + d1[1] * r[1];
                let df = d2[0] * r[0] + d2[1] * r[1] + d1[0] * d1[0] + d1[1] * d1[1];
                v -= f / df;
            }
            (1.0, v)
        };
        assert_eq!(
            h[0].kind,
            IntersectionKind::Crossing,
            "shift {shift}: {h:?}"
        );
        assert!(
            (h[0].u - u_expected).abs() <= 1e-12,
            "shift {shift}: u = {} vs {u_expected}",
            h[0].u
        );
        assert!(
            (h[0].v - v_expected).abs() <= 1e-12,
            "shift {shift}: v = {} vs {v_expected}",
            h[0].v
        );
        // The shortened case is a real test of the foot: v moved from v0.
        if shift < 0.0 {
            assert!((v_expected - v0).abs() > 1e-12, "{v_expected} vs {v0}");
        }
    }
}

#[test]
fn tangent_touching_and_nearly_tangent_crossings() {
    // Parabola y = x^2 on [-1, 1].
    let parabola = curve(&[&[-1.0, 1.0], &[0.0, -1.0], &[1.0, 1.0]]);
    let axis = curve(&[&[-1.0, 0.0], &[1.0, 0.0]]);
    let h = hits(&parabola, &axis);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!(h[0].kind, IntersectionKind::Touching);
    assert!((h[0].u - 0.5).abs() < 1e-7);
    // y = delta: crossings at x = -+ sqrt(delta), u = (1 -+ sqrt(delta)) / 2.
    for delta in [1e-2, 1e-4, 1e-6, 1e-8] {
        let line = curve(&[&[-1.0, delta], &[1.0, delta]]);
        let h = hits(&parabola, &line);
        assert_eq!(h.len(), 2, "delta {delta}: {h:?}");
        let r = delta.sqrt();
        assert!((h[0].u - 0.5 * (1.0 - r)).abs() < 1e-12, "{delta}: {h:?}");
        assert!((h[1].u - 0.5 * (1.0 + r)).abs() < 1e-12, "{delta}: {h:?}");
        for hit in &h {
            assert_eq!(hit.kind, IntersectionKind::Crossing, "{delta}: {hit:?}");
        }
        let below = curve(&[&[-1.0, -delta], &[1.0, -delta]]);
        assert!(hits(&parabola, &below).is_empty());
    }
    // Two cubics tangent at an interior point (same value and tangent,
    // different curvature): touching.
    let a = curve(&[&[0.0, 0.0], &[1.0, 1.0], &[2.0, 1.0], &[3.0, 0.0]]);
    let t = 0.5;
    let x = a.eval(t);
    let d = a.derivative_at(t, 1);
    let b = curve(&[
        &[x[0] - d[0] * 0.2, x[1] - d[1] * 0.2 + 0.5],
        &[x[0] - d[0] * 0.1, x[1] - d[1] * 0.1 - 1.0 / 6.0],
        &[x[0] + d[0] * 0.1, x[1] + d[1] * 0.1 - 1.0 / 6.0],
        &[x[0] + d[0] * 0.2, x[1] + d[1] * 0.2 + 0.5],
    ]);
    let h = hits(&a, &b);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!(h[0].kind, IntersectionKind::Touching);
    assert!((h[0].u - t).abs() < 1e-6);
}

#[test]
fn degenerate_repeated_control_points() {
    // Repeated first and last points: zero speed at both ends.
    let p = curve(&[&[0.0, 0.0], &[0.0, 0.0], &[2.0, 2.0], &[2.0, 2.0]]);
    let q = curve(&[&[0.0, 2.0], &[0.0, 2.0], &[2.0, 0.0], &[2.0, 0.0]]);
    let h = hits(&p, &q);
    assert_eq!(h.len(), 1, "{h:?}");
    assert!((h[0].u - 0.5).abs() < 1e-13 && (h[0].v - 0.5).abs() < 1e-13);
    assert_eq!(h[0].kind, IntersectionKind::Crossing);
    // Crossing exactly at the zero-speed end of P.
    let r = curve(&[&[-1.0, 1.0], &[1.0, -1.0]]);
    let h = hits(&p, &r);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!(h[0].u, 0.0);
    assert!((h[0].v - 0.5).abs() < 1e-13);
    // A degree-0 curve (a point) on a line, and off it.
    let point = curve(&[&[0.5, 0.5]]);
    let diagonal = curve(&[&[0.0, 0.0], &[1.0, 1.0]]);
    let h = hits(&point, &diagonal);
    assert_eq!(h.len(), 1, "{h:?}");
    assert!((h[0].v - 0.5).abs() < 1e-15);
    let off = curve(&[&[0.5, 0.6]]);
    assert!(hits(&off, &diagonal).is_empty());
}

#[test]
fn collinear_and_coincident_pieces_are_overlaps() {
    let a = curve(&[&[0.0, 0.0], &[2.0, 2.0]]);
    let b = curve(&[&[1.0, 1.0], &[3.0, 3.0]]);
    let h = hits(&a, &b);
    assert_eq!(h.len(), 1, "{h:?}");
    match h[0].kind {
        IntersectionKind::Overlap { u_range, v_range } => {
            assert!((u_range.0 - 0.5).abs() < 1e-14 && (u_range.1 - 1.0).abs() < 1e-14);
            assert!((v_range.0).abs() < 1e-14 && (v_range.1 - 0.5).abs() < 1e-14);
        }
        other => panic!("{other:?}"),
    }
    // A cubic and a reversed piece of itself.
    let c = curve(&[&[0.0, 0.0], &[1.0, 2.0], &[3.0, 3.0], &[4.0, 0.0]]);
    let piece = c.segment(0.7, 0.2).unwrap();
    let h = hits(&c, &piece);
    assert_eq!(h.len(), 1, "{h:?}");
    match h[0].kind {
        IntersectionKind::Overlap { u_range, v_range } => {
            assert!((u_range.0 - 0.2).abs() < 1e-9 && (u_range.1 - 0.7).abs() < 1e-9);
            assert!((v_range.0 - 1.0).abs() < 1e-9 && v_range.1.abs() < 1e-9);
        }
        other => panic!("{other:?}"),
    }
    // Identical curves, and a curve against its own degree elevation.
    let h = hits(&c, &c.elevate_degree(6).unwrap());
    assert_eq!(h.len(), 1);
    assert!(matches!(h[0].kind, IntersectionKind::Overlap { .. }));
    // Collinear but disjoint: nothing.
    let far = curve(&[&[2.5, 2.5], &[3.0, 3.0]]);
    assert!(hits(&a, &far).is_empty());
}

#[test]
fn three_d_meets_only_within_tolerance() {
    let x = [0.3, -0.2, 1.1];
    let p = curve(&[&[x[0] - 1.0, x[1], x[2]], &[x[0] + 1.0, x[1], x[2]]]);
    let q = curve(&[
        &[x[0] - 0.3, x[1] - 1.0, x[2] - 0.5],
        &[x[0] + 0.3, x[1], x[2]],
        &[x[0] - 0.3, x[1] + 1.0, x[2] + 0.5],
    ]);
    // Q passes through X at v = 1/2 (symmetric control points).
    let h = hits(&p, &q);
    assert_eq!(h.len(), 1, "{h:?}");
    assert_eq!(h[0].kind, IntersectionKind::Crossing);
    assert!((h[0].u - 0.5).abs() < 1e-14 && (h[0].v - 0.5).abs() < 1e-14);
    // Lift Q off P by 1e-6 along the common normal of the tangents at X,
    // (1, 0, 0) x (0, 1, 0.5): skew, no intersection.
    let n = [0.0, -0.5 / 1.25f64.sqrt(), 1.0 / 1.25f64.sqrt()];
    let lift = |r: [f64; 3]| [r[0] + 1e-6 * n[0], r[1] + 1e-6 * n[1], r[2] + 1e-6 * n[2]];
    let lifted = curve(&[
        &lift([x[0] - 0.3, x[1] - 1.0, x[2] - 0.5]),
        &lift([x[0] + 0.3, x[1], x[2]]),
        &lift([x[0] - 0.3, x[1] + 1.0, x[2] + 0.5]),
    ]);
    assert!(hits(&p, &lifted).is_empty());
    // Within a looser tolerance they meet (closest approach 1e-6).
    let loose = IntersectOptions {
        relative_distance_tolerance: 1e-5,
        ..IntersectOptions::default()
    };
    let h = intersect(&p, &lifted, &loose).unwrap();
    assert_eq!(h.len(), 1);
    assert!((h[0].distance - 1e-6).abs() < 1e-12, "{h:?}");
}

/// Crossings of two fine polylines: parameters `(u, v)` of every pair of
/// crossing segments.
fn polyline_crossings(p: &BezierCurve, q: &BezierCurve, n: usize) -> Vec<(f64, f64)> {
    let pp: Vec<Vec<f64>> = (0..=n).map(|i| p.eval(i as f64 / n as f64)).collect();
    let qq: Vec<Vec<f64>> = (0..=n).map(|i| q.eval(i as f64 / n as f64)).collect();
    let mut out = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let (a, b, c, d) = (&pp[i], &pp[i + 1], &qq[j], &qq[j + 1]);
            let orient = |o: &[f64], x: &[f64], y: &[f64]| {
                (x[0] - o[0]) * (y[1] - o[1]) - (x[1] - o[1]) * (y[0] - o[0])
            };
            let (o1, o2) = (orient(a, b, c), orient(a, b, d));
            let (o3, o4) = (orient(c, d, a), orient(c, d, b));
            if o1 * o2 < 0.0 && o3 * o4 < 0.0 {
                let s = o3 / (o3 - o4);
                let t = o1 / (o1 - o2);
                out.push(((i as f64 + s) / n as f64, (j as f64 + t) / n as f64));
            }
        }
    }
    out
}

#[test]
fn random_curves_against_dense_polylines() {
    let mut rng = Lcg(2024);
    let n = 400;
    let mut checked = 0;
    for case in 0..120 {
        let dp = 1 + (rng.next() * 5.0) as usize;
        let dq = 1 + (rng.next() * 5.0) as usize;
        let rows = |rng: &mut Lcg, d: usize| -> Vec<Vec<f64>> {
            (0..=d)
                .map(|_| vec![rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)])
                .collect()
        };
        let p = BezierCurve::from_rows(&rows(&mut rng, dp)).unwrap();
        let q = BezierCurve::from_rows(&rows(&mut rng, dq)).unwrap();
        let h = hits(&p, &q);
        let crossings: Vec<_> = h
            .iter()
            .filter(|x| x.kind == IntersectionKind::Crossing)
            .collect();
        for x in &h {
            assert!(x.distance <= 1e-9, "case {case}: {x:?}");
        }
        // Skip the rare cases where a hit is nearly tangent or near an end
        // (the polyline cannot judge them); they are covered above.
        let delicate = h.iter().any(|x| {
            let a = p.derivative_at(x.u, 1);
            let b = q.derivative_at(x.v, 1);
            let cross = (a[0] * b[1] - a[1] * b[0]).abs();
            cross < 0.05 * common::norm(&a) * common::norm(&b)
                || !(0.01..=0.99).contains(&x.u)
                || !(0.01..=0.99).contains(&x.v)
        });
        let poly = polyline_crossings(&p, &q, n);
        let poly_delicate = poly
            .iter()
            .any(|&(u, v)| !(0.01..=0.99).contains(&u) || !(0.01..=0.99).contains(&v));
        if delicate || poly_delicate {
            continue;
        }
        checked += 1;
        assert_eq!(
            crossings.len(),
            poly.len(),
            "case {case}: {h:?} vs {poly:?}"
        );
        for &(u, v) in &poly {
            assert!(
                crossings
                    .iter()
                    .any(|x| (x.u - u).abs() < 2e-3 && (x.v - v).abs() < 2e-3),
                "case {case}: polyline crossing ({u}, {v}) not found in {h:?}"
            );
        }
    }
    assert!(checked > 80, "only {checked} cases checked");
}

#[test]
fn bad_input_is_named() {
    let p = curve(&[&[0.0, 0.0], &[1.0, 1.0]]);
    let q3 = curve(&[&[0.0, 0.0, 0.0], &[1.0, 1.0, 1.0]]);
    let e = intersect(&p, &q3, &IntersectOptions::default()).unwrap_err();
    assert!(e.to_string().contains("q has dimension 3"), "{e}");
    let bad = IntersectOptions {
        relative_distance_tolerance: f64::NAN,
        ..IntersectOptions::default()
    };
    let e = intersect(&p, &p, &bad).unwrap_err();
    assert!(e.to_string().contains("relative_distance_tolerance"), "{e}");
    let line1 = curve(&[&[0.0], &[1.0]]);
    assert!(intersect(&line1, &line1, &IntersectOptions::default()).is_err());
}

#[test]
fn work_is_bounded() {
    // Two curves within the tolerance of each other along a stretch without
    // coinciding: a tiny budget gives IllConditioned, never a hang.
    let a = curve(&[&[0.0, 0.0], &[1.0, 1.0], &[2.0, -1.0], &[3.0, 0.0]]);
    let b = curve(&[
        &[0.0, 1e-8],
        &[1.0, 1.0 + 1e-8],
        &[2.0, -1.0 + 1e-8],
        &[3.0, 1e-8],
    ]);
    let tight = IntersectOptions {
        max_box_pairs: 50,
        ..IntersectOptions::default()
    };
    let r = intersect(&a, &b, &tight);
    assert!(
        matches!(r, Err(bezjoin_core::BezjoinError::IllConditioned { .. })),
        "{r:?}"
    );
    // With the default budget: 1e-8 apart is more than the tolerance
    // (3e-9 here), so they do not meet.
    assert!(hits(&a, &b).is_empty());
    // A shift of 1e-12 is within it: one overlap.
    let c = curve(&[&[0.0, 1e-12], &[1.0, 1.0], &[2.0, -1.0], &[3.0, 0.0]]);
    let h = hits(&a, &c);
    assert_eq!(h.len(), 1, "{h:?}");
    assert!(
        matches!(h[0].kind, IntersectionKind::Overlap { .. }),
        "{h:?}"
    );
}

#[test]
fn work_bounds_up_to_usize_max_are_accepted() {
    // Fuzz finding F5 (docs/reliability.md): the candidate-merging threshold
    // `4 * max_hits + 64` overflowed for max_hits > usize::MAX / 4 (a panic,
    // i.e. BZJ_ERR_INTERNAL, with overflow checks; a threshold of 60 without).
    let p = curve(&[&[0.0, 0.0], &[2.0, 2.0]]);
    let q = curve(&[&[0.0, 2.0], &[1.0, 0.0], &[2.0, 0.0]]);
    let expected = hits(&p, &q);
    assert_eq!(expected.len(), 1);
    for big in [usize::MAX / 4 + 1, usize::MAX / 2 + 1, usize::MAX] {
        let options = IntersectOptions {
            max_depth: big,
            max_box_pairs: big,
            max_hits: big,
            ..IntersectOptions::default()
        };
        let h = intersect(&p, &q, &options).unwrap();
        assert_eq!(h, expected, "bounds {big}");
    }
}

/// Found by the fuzzer (`intersect_detailed`): a control point of 3e105
/// overflows the arithmetic of the search; the answer was a "crossing" with
/// `u = NaN` and distance NaN. Every coordinate of Q is at y >= 67 and P
/// stays at y <= 0, so there is no hit at all.
#[test]
fn overflowing_coordinates_give_no_nan_hit() {
    let p = BezierCurve::new(2, 1, vec![-1e2, 0.0, 0.0, -7.7349853515625e1]).unwrap();
    let mut q_points = vec![-3.1299510524152305e105, 6.70562744140625e1];
    q_points.extend([
        6.70562744140625e1,
        6.70562744140625e1,
        6.70562744140625e1,
        6.70562744140625e1,
        6.70562744140625e1,
        7.33062744140625e1,
        6.70562744140625e1,
        6.7071533203125e1,
        7.0977783203125e1,
        6.70562744140625e1,
        6.70562744140625e1,
        6.70562744140625e1,
    ]);
    let q = BezierCurve::new(2, 6, q_points).unwrap();
    let found = intersect(&p, &q, &IntersectOptions::default()).unwrap();
    assert!(found.is_empty(), "{found:?}");
}
