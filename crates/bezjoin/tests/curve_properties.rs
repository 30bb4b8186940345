//! Properties of the Bezier core (issue 2, item 7): every exact operation
//! is checked against an independent way of computing the same thing.

use bezjoin_core::BezierCurve;
use bezjoin_core::basis::{bezier_basis_derivatives, binomial};
use bezjoin_core::bezier::distance;
use proptest::prelude::*;

/// A random curve of degree 0..=max_degree in dimension 1..=4 with
/// coordinates in [-10, 10].
fn curve(max_degree: usize) -> impl Strategy<Value = BezierCurve> {
    (0..=max_degree, 1usize..=4).prop_flat_map(|(n, d)| {
        prop::collection::vec(-10.0f64..10.0, (n + 1) * d)
            .prop_map(move |pts| BezierCurve::new(d, n, pts).unwrap())
    })
}

/// `|a - b| <= tol * max(1, scale)`.
fn close(a: &[f64], b: &[f64], tol: f64, scale: f64) -> bool {
    distance(a, b) <= tol * scale.max(1.0)
}

/// k-th derivative by the Bernstein closed form
/// `n!/(n-k)! sum_i (Delta^k P)_i B_i^(n-k)(t)`, independent of A2.3.
fn derivative_closed_form(c: &BezierCurve, t: f64, k: usize) -> Vec<f64> {
    let n = c.degree();
    let d = c.dim();
    if k > n {
        return vec![0.0; d];
    }
    let mut diffs: Vec<Vec<f64>> = (0..=n).map(|i| c.point(i).to_vec()).collect();
    for _ in 0..k {
        diffs = diffs
            .windows(2)
            .map(|w| w[1].iter().zip(&w[0]).map(|(b, a)| b - a).collect())
            .collect();
    }
    let falling: f64 = (0..k).map(|j| (n - j) as f64).product();
    let m = n - k;
    let mut out = vec![0.0; d];
    for (i, p) in diffs.iter().enumerate() {
        let b = binomial(m, i) * t.powi(i as i32) * (1.0 - t).powi((m - i) as i32);
        for c in 0..d {
            out[c] += falling * b * p[c];
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn fast_evaluation_matches_de_casteljau(c in curve(20), t in -0.5f64..1.5) {
        let s = c.coordinate_scale() * 2f64.powi(c.degree() as i32);
        prop_assert!(close(&c.eval(t), &c.eval_de_casteljau(t), 1e-13, s * (1.0 + t.abs()).powi(c.degree() as i32)));
    }

    #[test]
    fn elevation_leaves_the_curve_unchanged(c in curve(12), extra in 0usize..10) {
        let e = c.elevate_degree(c.degree() + extra).unwrap();
        prop_assert_eq!(e.degree(), c.degree() + extra);
        for i in 0..=32 {
            let t = i as f64 / 32.0;
            prop_assert!(close(&e.eval(t), &c.eval(t), 1e-13, c.coordinate_scale()));
        }
        // End points are kept exactly.
        prop_assert_eq!(e.point(0), c.point(0));
        prop_assert_eq!(e.point(e.degree()), c.point(c.degree()));
    }

    #[test]
    fn split_pieces_reproduce_the_curve(c in curve(15), t in 0.0f64..=1.0) {
        let (l, r) = c.split_at(t).unwrap();
        for i in 0..=20 {
            let s = i as f64 / 20.0;
            prop_assert!(close(&l.eval(s), &c.eval(t * s), 1e-13, c.coordinate_scale()));
            prop_assert!(close(&r.eval(s), &c.eval(t + (1.0 - t) * s), 1e-13, c.coordinate_scale()));
        }
        prop_assert_eq!(l.point(l.degree()), r.point(0));
    }

    #[test]
    fn segment_zero_one_is_the_identity(c in curve(15)) {
        let s = c.segment(0.0, 1.0).unwrap();
        for i in 0..=c.degree() {
            prop_assert!(close(s.point(i), c.point(i), 1e-15, c.coordinate_scale()));
        }
    }

    #[test]
    fn segments_compose(c in curve(10), a in -0.5f64..1.5, b in -0.5f64..1.5, u in 0.0f64..1.0, v in 0.0f64..1.0) {
        let once = c.segment(a, b).unwrap().segment(u, v).unwrap();
        let direct = c.segment(a + (b - a) * u, a + (b - a) * v).unwrap();
        let growth = 2.5f64.powi(c.degree() as i32);
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            prop_assert!(close(&once.eval(s), &direct.eval(s), 1e-12, c.coordinate_scale() * growth));
            prop_assert!(close(&direct.eval(s), &c.eval(a + (b - a) * (u + (v - u) * s)), 1e-12, c.coordinate_scale() * growth));
        }
    }

    #[test]
    fn reverse_twice_is_identity_and_equals_segment_one_zero(c in curve(12)) {
        prop_assert_eq!(c.reverse().reverse(), c.clone());
        let r = c.segment(1.0, 0.0).unwrap();
        for i in 0..=c.degree() {
            prop_assert!(close(r.point(i), c.reverse().point(i), 1e-14, c.coordinate_scale()));
        }
    }

    #[test]
    fn derivatives_match_closed_form_and_finite_differences(c in curve(12), t in 0.05f64..0.95) {
        let n = c.degree();
        let all = c.eval_derivatives(t, n + 1);
        for k in 0..=n + 1 {
            let ours: Vec<f64> = all.row(k).iter().copied().collect();
            let closed = derivative_closed_form(&c, t, k);
            let size = (0..k).map(|j| (n.saturating_sub(j)).max(1) as f64).product::<f64>() * 2f64.powi(k as i32);
            prop_assert!(close(&ours, &closed, 1e-11, c.coordinate_scale() * size), "k={} {:?} vs {:?}", k, ours, closed);
        }
        // The A2.3 basis path (what the solvers use) agrees with both.
        let mut basis_path = vec![0.0; (n + 2) * c.dim()];
        c.eval_derivatives_basis(t, n + 1, &mut basis_path);
        for k in 0..=n + 1 {
            let closed = derivative_closed_form(&c, t, k);
            let size = (0..k).map(|j| (n.saturating_sub(j)).max(1) as f64).product::<f64>() * 2f64.powi(k as i32);
            let row = &basis_path[k * c.dim()..(k + 1) * c.dim()];
            prop_assert!(close(row, &closed, 1e-11, c.coordinate_scale() * size), "A2.3 path, k={}", k);
        }
        // Central differences of order k-1 give order k to O(h^2).
        if n >= 1 {
            let h = 1e-5;
            let lo = c.derivative_at(t - h, 0);
            let hi = c.derivative_at(t + h, 0);
            let fd: Vec<f64> = hi.iter().zip(&lo).map(|(a, b)| (a - b) / (2.0 * h)).collect();
            let d1: Vec<f64> = all.row(1).iter().copied().collect();
            prop_assert!(close(&fd, &d1, 1e-5, c.coordinate_scale() * (n * n * n) as f64));
        }
    }

    #[test]
    fn basis_sums_to_one_and_is_bernstein(n in 0usize..25, t in -0.2f64..1.2) {
        let d = bezier_basis_derivatives(n, t, n);
        let sum: f64 = d.row(0).iter().sum();
        prop_assert!((sum - 1.0).abs() < 1e-12 * 2f64.powi(n as i32) * (1.0 + t.abs()).powi(n as i32));
        for k in 1..=n {
            // Derivatives of a partition of unity sum to zero; the terms are of
            // size n!/(n-k)! 2^n (1+|t|)^n, so that sets the rounding scale.
            let sk: f64 = d.row(k).iter().sum();
            let falling: f64 = (0..k).map(|j| (n - j) as f64).product();
            let scale = falling * 2f64.powi(n as i32) * (1.0 + t.abs()).powi(n as i32);
            prop_assert!(sk.abs() < 1e-13 * scale, "k={} sum={}", k, sk);
        }
        if (0.0..=1.0).contains(&t) {
            for i in 0..=n {
                let b = binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32);
                prop_assert!((d[(0, i)] - b).abs() < 1e-14 * binomial(n, i).max(1.0), "n={} i={}", n, i);
            }
        }
    }

    #[test]
    fn straight_line_length_is_exact(
        x0 in -10.0f64..10.0, y0 in -10.0f64..10.0, dx in -10.0f64..10.0, dy in -10.0f64..10.0,
        inner in prop::collection::vec(0.0f64..1.0, 0..6),
    ) {
        // Control points on one segment, in increasing order along it:
        // monotone parametrisation, so the length is the chord.
        let mut s = inner.clone();
        s.sort_by(f64::total_cmp);
        let mut rows = vec![[x0, y0]];
        rows.extend(s.iter().map(|&f| [x0 + f * dx, y0 + f * dy]));
        rows.push([x0 + dx, y0 + dy]);
        let c = BezierCurve::from_rows(&rows).unwrap();
        let chord = (dx * dx + dy * dy).sqrt();
        let len = c.arc_length(0.0, 1.0, 1e-13).unwrap();
        prop_assert!((len - chord).abs() <= 1e-12 * chord.max(1.0), "{} vs {}", len, chord);
    }

    #[test]
    fn length_inverse_round_trips(c in curve(8), a in 0.0f64..1.0, b in 0.0f64..1.0) {
        prop_assume!(c.degree() >= 1 && c.polygon_length() > 1e-3);
        let len = c.arc_length(a, b, 1e-13).unwrap();
        let back = c.param_at_length(a, len, 1e-12).unwrap();
        let again = c.arc_length(a, back, 1e-13).unwrap();
        prop_assert!((again - len).abs() <= 1e-11 * c.polygon_length().max(1.0), "{} vs {}", again, len);
    }
}

#[test]
fn semicubical_parabola_length_matches_closed_form() {
    // (t^2, t^3): zero speed at t = 0 (repeated control points).
    let c =
        BezierCurve::from_rows(&[[0.0, 0.0], [0.0, 0.0], [1.0 / 3.0, 0.0], [1.0, 1.0]]).unwrap();
    let exact = (13f64.powf(1.5) - 8.0) / 27.0;
    let len = c.arc_length(0.0, 1.0, 1e-14).unwrap();
    assert!((len - exact).abs() < 1e-13, "{len} vs {exact}");
}

#[test]
fn arc_length_errors_name_the_argument() {
    let c = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 0.0]]).unwrap();
    assert_eq!(
        c.arc_length(f64::NAN, 1.0, 1e-9).unwrap_err().to_string(),
        "a[0] = NaN is not finite"
    );
    assert!(
        c.arc_length(0.0, 1.0, 0.0)
            .unwrap_err()
            .to_string()
            .contains("accuracy")
    );
    assert!(
        c.param_at_length(0.5, 0.75, 1e-12)
            .unwrap_err()
            .to_string()
            .contains("longer than the arc length 0.5")
    );
}
