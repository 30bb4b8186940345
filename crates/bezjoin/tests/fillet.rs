//! Corner rounding: the defining properties (C^k chain in the B-spline
//! sense, setback arc lengths, mirror symmetry), the deviation bound, chains
//! (sequential and parallel identical) and every error path.

mod common;
use bezjoin_core::{BSplineCurve, join_jumps, relative_jump};
use bezjoin_core::{BezierCurve, BezjoinError, KnotSide};
use bezjoin_core::{
    ChainFilletOptions, DeviationFilletOptions, FilletOptions, distance_to_curve, fillet,
    fillet_at, fillet_chain, fillet_within_deviation,
};
use bezjoin_core::{IntersectOptions, IntersectionKind, intersect};
use common::{distance, norm};

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

fn curve(rows: &[&[f64]]) -> BezierCurve {
    BezierCurve::from_rows(rows).unwrap()
}

/// A random cubic through `x` at parameter `t`, heading in direction `angle`.
fn cubic_through(rng: &mut Lcg, x: [f64; 2], t: f64, angle: f64) -> BezierCurve {
    // A gently curved cubic along the direction, then shifted so that C(t) = x.
    let (c, s) = (angle.cos(), angle.sin());
    let bend = [rng.range(-0.3, 0.3), rng.range(-0.3, 0.3)];
    let local = [
        [0.0, 0.0],
        [1.0, bend[0]],
        [2.0, bend[1]],
        [3.0, rng.range(-0.2, 0.2)],
    ];
    let rows: Vec<Vec<f64>> = local
        .iter()
        .map(|p| vec![c * p[0] - s * p[1], s * p[0] + c * p[1]])
        .collect();
    let raw = BezierCurve::from_rows(&rows).unwrap();
    let at = raw.eval(t);
    let shifted: Vec<Vec<f64>> = rows
        .iter()
        .map(|p| vec![p[0] + x[0] - at[0], p[1] + x[1] - at[1]])
        .collect();
    BezierCurve::from_rows(&shifted).unwrap()
}

/// Derivatives `0..=k` from both sides of the knot at `t` agree to `tol` relative.
fn assert_continuous(spline: &BSplineCurve, t: f64, k: usize, tol: f64, what: &str) {
    let left = spline.eval_derivatives_side(t, k, KnotSide::Left);
    let right = spline.eval_derivatives_side(t, k, KnotSide::Right);
    let dim = spline.dim();
    for order in 0..=k {
        let a: Vec<f64> = left[order * dim..(order + 1) * dim].to_vec();
        let b: Vec<f64> = right[order * dim..(order + 1) * dim].to_vec();
        let jump = relative_jump(&a, &b);
        assert!(
            jump <= tol,
            "{what}: derivative {order} jumps by {jump:e} at t = {t}: {a:?} vs {b:?}"
        );
    }
}

#[test]
fn three_pieces_form_a_ck_bspline_and_setbacks_hold() {
    let mut rng = Lcg(31);
    let mut done = 0;
    for case in 0..30 {
        let x = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let a = rng.range(0.0, std::f64::consts::TAU);
        let (tp, tq, b) = (
            rng.range(0.4, 0.7),
            rng.range(0.3, 0.6),
            a + rng.range(0.5, 2.6),
        );
        let p = cubic_through(&mut rng, x, tp, a);
        let q = cubic_through(&mut rng, x, tq, b);
        let kp = 1 + (rng.next() * 3.0) as usize;
        let kq = 1 + (rng.next() * 3.0) as usize;
        let (dp, dq) = (rng.range(0.1, 0.6), rng.range(0.1, 0.6));
        let (alpha, beta) = (rng.range(0.5, 2.0), rng.range(0.5, 2.0));
        let options = FilletOptions::new(dp, dq, kp, kq).with_scales(alpha, beta);
        let f = match fillet(&p, &q, &options) {
            Ok(f) => f,
            Err(e) => panic!("case {case}: {e}"),
        };
        let (us, vs) = (f.crossing.u, f.crossing.v);
        assert!(distance(&p.eval(us), &q.eval(vs)) < 1e-14);
        // It is the first crossing.
        let hits = intersect(&p, &q, &IntersectOptions::default()).unwrap();
        let first = hits
            .iter()
            .find(|h| h.kind == IntersectionKind::Crossing)
            .unwrap();
        assert_eq!(first.u, us);
        // Setback arc lengths, measured independently.
        let lp = p.arc_length(f.u0, us, 1e-14).unwrap();
        let lq = q.arc_length(vs, f.v0, 1e-14).unwrap();
        assert!((lp - dp).abs() <= 1e-9 * dp, "case {case}: {lp} vs {dp}");
        assert!((lq - dq).abs() <= 1e-9 * dq, "case {case}: {lq} vs {dq}");
        // The trimmed pieces are the original curves on [0, u0] and [v0, 1].
        for i in 0..=10 {
            let s = i as f64 / 10.0;
            assert!(distance(&f.p_trimmed.eval(s), &p.eval(f.u0 * s)) < 1e-13);
            let v = f.v0 + (1.0 - f.v0) * s;
            assert!(distance(&f.q_trimmed.eval(s), &q.eval(v)) < 1e-13);
        }
        // C^k in the B-spline sense of mathematics.md: knot intervals
        // (u0, alpha, (1 - v0) alpha / beta), derivatives from both sides.
        assert_eq!(f.blend.degree(), kp + kq + 1);
        let intervals = [f.u0, alpha, (1.0 - f.v0) * alpha / beta];
        let spline = BSplineCurve::from_bezier_chain(
            &[
                f.p_trimmed.as_bezier().unwrap().clone(),
                f.blend.clone(),
                f.q_trimmed.as_bezier().unwrap().clone(),
            ],
            &intervals,
        )
        .unwrap();
        assert_continuous(&spline, intervals[0], kp, 1e-9, "P|R join");
        assert_continuous(&spline, intervals[0] + intervals[1], kq, 1e-9, "R|Q join");
        // Not more than promised in general: the next derivative jumps at
        // one of the joins for these random data (guards the test itself).
        let jp = join_jumps(
            f.p_trimmed.as_bezier().unwrap(),
            intervals[0],
            &f.blend,
            intervals[1],
            kp + 1,
        );
        let jq = join_jumps(
            &f.blend,
            intervals[1],
            f.q_trimmed.as_bezier().unwrap(),
            intervals[2],
            kq + 1,
        );
        assert!(jp[kp + 1] > 1e-6 || jq[kq + 1] > 1e-6, "case {case}");
        done += 1;
    }
    assert_eq!(done, 30);
}

/// Mirror in the y axis.
fn mirror(x: &[f64]) -> Vec<f64> {
    vec![-x[0], x[1]]
}

#[test]
fn mirror_symmetric_input_gives_a_mirror_symmetric_blend() {
    // P rises to the right and crosses the y axis once, at X; Q is P
    // mirrored and reversed, so Q(v) = M(P(1 - v)) crosses P at X and the
    // path "P up to X, then Q" is symmetric about the axis.
    let p = curve(&[&[-2.0, -1.0], &[-0.8, -0.2], &[0.7, 0.4], &[1.5, 1.5]]);
    let rows: Vec<Vec<f64>> = (0..=3).rev().map(|i| mirror(p.point(i))).collect();
    let q = BezierCurve::from_rows(&rows).unwrap();
    for order in 1..=3 {
        for setback in [0.1, 0.5, 1.0] {
            let f = fillet(&p, &q, &FilletOptions::symmetric(setback, order)).unwrap();
            assert!(f.crossing.point[0].abs() < 1e-14);
            assert!((f.v0 - (1.0 - f.u0)).abs() < 1e-10, "{} {}", f.u0, f.v0);
            for i in 0..=20 {
                let t = i as f64 / 20.0;
                let a = mirror(&f.blend.eval(t));
                let b = f.blend.eval(1.0 - t);
                assert!(
                    distance(&a, &b) < 1e-10,
                    "order {order}, setback {setback}, t = {t}: {a:?} vs {b:?}"
                );
            }
            // The blend is not trivially symmetric: it is curved.
            let (b0, b1) = (f.blend.eval(0.0), f.blend.eval(1.0));
            let chord_mid = [0.5 * (b0[0] + b1[0]), 0.5 * (b0[1] + b1[1])];
            assert!(distance(&f.blend.eval(0.5), &chord_mid) > 1e-3);
        }
    }
}

#[test]
fn errors_name_what_is_wrong() {
    let p = curve(&[&[-1.0, 0.0], &[0.0, 0.5], &[1.0, 0.0]]);
    let q = curve(&[&[0.0, -1.0], &[0.1, 0.0], &[0.0, 1.0]]);
    let ok = FilletOptions::symmetric(0.2, 1);
    fillet(&p, &q, &ok).unwrap();
    // No crossing.
    let far = curve(&[&[5.0, -1.0], &[5.0, 1.0]]);
    let e = fillet(&p, &far, &ok).unwrap_err();
    assert!(matches!(e, BezjoinError::NoIntersection { .. }), "{e}");
    assert!(e.to_string().contains("do not cross"), "{e}");
    // Only touching: the tangent line at the apex of the parabola.
    let tangent = curve(&[&[-1.0, 0.25], &[1.0, 0.25]]);
    let e = fillet(&p, &tangent, &FilletOptions::symmetric(0.2, 1)).unwrap_err();
    assert!(matches!(e, BezjoinError::NoIntersection { .. }), "{e}");
    assert!(e.to_string().contains("only touch"), "{e}");
    // Setback longer than the part before / after the crossing.
    let e = fillet(&p, &q, &FilletOptions::new(5.0, 0.2, 2, 2)).unwrap_err();
    assert!(
        e.to_string().starts_with("p_setback: 5 is not shorter"),
        "{e}"
    );
    let e = fillet(&p, &q, &FilletOptions::new(0.2, 5.0, 2, 2)).unwrap_err();
    assert!(
        e.to_string().starts_with("q_setback: 5 is not shorter"),
        "{e}"
    );
    // Orders above the degree are allowed (as for connect): the blend's
    // derivatives above P's degree vanish at the join, like P's.
    let f = fillet(&p, &q, &FilletOptions::new(0.2, 0.2, 3, 1)).unwrap();
    let jet = f.blend.eval_derivatives(0.0, 3);
    assert!(jet[6..8].iter().all(|x| x.abs() < 1e-9), "{jet:?}");
    // Non-finite and non-positive input.
    let e = fillet(&p, &q, &FilletOptions::new(f64::NAN, 0.2, 1, 1)).unwrap_err();
    assert!(matches!(e, BezjoinError::NonFiniteScalar { .. }), "{e}");
    assert!(e.to_string().contains("p_setback"), "{e}");
    let e = fillet(&p, &q, &FilletOptions::new(0.2, f64::INFINITY, 1, 1)).unwrap_err();
    assert!(e.to_string().contains("q_setback"), "{e}");
    let e = fillet(&p, &q, &FilletOptions::new(0.0, 0.2, 1, 1)).unwrap_err();
    assert_eq!(e.to_string(), "p_setback = 0 is outside > 0");
    let e = fillet(&p, &q, &ok.clone().with_scales(f64::NAN, 1.0)).unwrap_err();
    assert!(e.to_string().contains("p_scale"), "{e}");
    // Dimensions.
    let q3 = curve(&[&[0.0, 0.0, 0.0], &[1.0, 1.0, 1.0]]);
    let e = fillet(&p, &q3, &ok).unwrap_err();
    assert!(matches!(e, BezjoinError::DimensionMismatch { .. }), "{e}");
}

#[test]
fn deviation_bound_holds_and_is_monotone_for_short_setbacks() {
    let mut rng = Lcg(77);
    for case in 0..4 {
        let x = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let a = rng.range(0.0, std::f64::consts::TAU);
        let p = cubic_through(&mut rng, x, 0.6, a);
        let b = a + rng.range(0.6, 2.5);
        let q = cubic_through(&mut rng, x, 0.4, b);
        let order = 1 + case % 3;
        // Monotone for setbacks short against the curves (about 3 long):
        // a sweep up to 0.4. (Longer ones can turn; the search copes.)
        let mut last = 0.0;
        for i in 1..=8 {
            let dp = 0.05 * i as f64;
            let f = fillet(&p, &q, &FilletOptions::symmetric(dp, order)).unwrap();
            let (_, dev) = distance_to_curve(&f.blend, &f.crossing.point);
            assert!(
                dev > last,
                "case {case}: deviation {dev} after {last} at dp = {dp}"
            );
            last = dev;
        }
        for ratio in [1.0, 0.5, 2.0] {
            let eps = rng.range(0.01, 0.1);
            let options = DeviationFilletOptions::new(eps, order).with_setback_ratio(ratio);
            let r = fillet_within_deviation(&p, &q, &options).unwrap();
            // A strict bound: within eps, and within 1e-9 relative of it.
            assert!(
                r.deviation <= eps && r.deviation >= eps * (1.0 - 1e-9),
                "{} vs {eps}",
                r.deviation
            );
            // Independently: sampling of the blend comes no closer than
            // eps (1 - 1e-9) to the corner, and within eps of it near the
            // reported parameter (a sampled distance is never below the
            // true minimum, so this bounds the true deviation by eps).
            let x = &r.fillet.crossing.point;
            let blend = &r.fillet.blend;
            let closest = (0..=2000)
                .map(|i| distance(&blend.eval(i as f64 / 2000.0), x))
                .fold(f64::INFINITY, f64::min);
            assert!(closest >= eps * (1.0 - 1e-9), "{closest} < {eps}");
            let t = r.deviation_parameter;
            let local = (0..=2000)
                .map(|i| distance(&blend.eval(t + 1e-4 * (i as f64 / 1000.0 - 1.0)), x))
                .fold(f64::INFINITY, f64::min);
            assert!(local <= eps, "{local} vs {eps}");
            // The setbacks have the requested ratio and hold as arc lengths.
            assert!((r.q_setback - ratio * r.p_setback).abs() <= 1e-15 * r.q_setback);
            let f = &r.fillet;
            let lp = p.arc_length(f.u0, f.crossing.u, 1e-14).unwrap();
            let lq = q.arc_length(f.crossing.v, f.v0, 1e-14).unwrap();
            assert!((lp - r.p_setback).abs() <= 1e-9 * r.p_setback);
            assert!((lq - r.q_setback).abs() <= 1e-9 * r.q_setback);
        }
    }
}

/// The bound is one-sided on many corners, scales and ratios: never above
/// eps, and never more than 1e-9 relative below it.
#[test]
fn deviation_never_exceeds_the_bound() {
    let mut rng = Lcg(2024);
    let mut worst_below = 0.0f64;
    let mut done = 0;
    for case in 0..24 {
        let x = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let a = rng.range(0.0, std::f64::consts::TAU);
        let (tp, tq, b) = (
            rng.range(0.5, 0.7),
            rng.range(0.3, 0.5),
            a + rng.range(0.6, 2.5),
        );
        let p = cubic_through(&mut rng, x, tp, a);
        let q = cubic_through(&mut rng, x, tq, b);
        let eps = rng.range(0.005, 0.1);
        let ratio = rng.range(0.5, 2.0);
        let s = rng.range(0.5, 1.5);
        let mut options = DeviationFilletOptions::new(eps, 1 + case % 3).with_setback_ratio(ratio);
        options.shape = options.shape.with_scales(s, s);
        let r = match fillet_within_deviation(&p, &q, &options) {
            Ok(r) => r,
            // A bound beyond reach of these curves (a random shallow corner).
            Err(e) if e.to_string().contains("cannot be reached") => continue,
            Err(e) => panic!("case {case}: {e}"),
        };
        done += 1;
        assert!(
            r.deviation <= eps,
            "case {case}: {} above {eps}",
            r.deviation
        );
        let below = (eps - r.deviation) / eps;
        assert!(below <= 1e-9, "case {case}: {below:e} below");
        // The reported deviation is the blend's distance from the corner.
        let (_, d) = distance_to_curve(&r.fillet.blend, &r.fillet.crossing.point);
        assert_eq!(d, r.deviation, "case {case}");
        worst_below = worst_below.max(below);
    }
    assert!(done >= 20, "only {done} of 24 cases reachable");
    eprintln!("{done} cases; largest relative gap below eps: {worst_below:e}");
}

/// The deviation search keeps its two arc-length inversions across its
/// trial setbacks; the corner it returns is the one `fillet_at` builds from
/// scratch with the setbacks it found, bit for bit. Cubic corners and a
/// degree-45 curve against its rotation (many speed minima), for ordinary
/// and tiny bounds.
#[test]
fn deviation_search_returns_the_fillet_of_its_setbacks() {
    let mut rng = Lcg(4242);
    let mut corners = Vec::new();
    for _ in 0..3 {
        let x = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
        let a = rng.range(0.0, std::f64::consts::TAU);
        let p = cubic_through(&mut rng, x, 0.6, a);
        let b = a + rng.range(0.6, 2.5);
        let q = cubic_through(&mut rng, x, 0.4, b);
        corners.push((p, q));
    }
    let rows: Vec<Vec<f64>> = (0..=45)
        .map(|_| vec![rng.range(-10.0, 10.0), rng.range(-10.0, 10.0)])
        .collect();
    let wiggly = BezierCurve::from_rows(&rows).unwrap();
    let centre = wiggly.eval(0.5);
    let rotated: Vec<Vec<f64>> = rows
        .iter()
        .map(|r| {
            vec![
                centre[0] - (r[1] - centre[1]),
                centre[1] + (r[0] - centre[0]),
            ]
        })
        .collect();
    corners.push((wiggly, BezierCurve::from_rows(&rotated).unwrap()));
    let mut found = 0;
    for (case, (p, q)) in corners.iter().enumerate() {
        for eps in [0.05, 1e-3, 1e-7] {
            for order in [0, 2] {
                let options = DeviationFilletOptions::new(eps, order).with_setback_ratio(0.8);
                let Ok(r) = fillet_within_deviation(p, q, &options) else {
                    continue;
                };
                found += 1;
                let mut shape = options.shape.clone();
                shape.p_setback = r.p_setback;
                shape.q_setback = r.q_setback;
                let fresh = fillet_at(p, q, &r.fillet.crossing, &shape).unwrap();
                assert_eq!(fresh, r.fillet, "case {case}, eps {eps}, order {order}");
            }
        }
    }
    eprintln!("{found} of 24 corners rounded");
    assert!(found >= 18, "only {found} corners rounded");
}

#[test]
fn deviation_for_two_lines_matches_geometry() {
    // Two lines at right angles with a symmetric C1 cubic blend: by symmetry
    // the closest point is R(1/2), on the bisector; the search must land on it.
    let p = curve(&[&[-2.0, 0.0], &[2.0, 0.0]]);
    let q = curve(&[&[0.0, -2.0], &[0.0, 2.0]]);
    let r = fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(0.3, 1)).unwrap();
    assert!((r.deviation_parameter - 0.5).abs() < 1e-6);
    let mid = r.fillet.blend.eval(0.5);
    assert!((mid[0] + mid[1]).abs() < 1e-12, "{mid:?}");
    let d = distance(&mid, &[0.0, 0.0]);
    assert!((0.3 * (1.0 - 1e-9)..=0.3).contains(&d), "{d}");
    // Unreachable bound.
    let e = fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(50.0, 1)).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("max_deviation: 50 cannot be reached"),
        "{e}"
    );
    let e = fillet_within_deviation(&p, &q, &DeviationFilletOptions::new(-1.0, 1)).unwrap_err();
    assert!(e.to_string().contains("max_deviation"), "{e}");
    let e = fillet_within_deviation(
        &p,
        &q,
        &DeviationFilletOptions::new(0.1, 1).with_setback_ratio(f64::NAN),
    )
    .unwrap_err();
    assert!(e.to_string().contains("setback_ratio"), "{e}");
}

/// A zigzag of cubics meeting end to end with sharp corners.
fn zigzag(rng: &mut Lcg, n: usize, closed: bool) -> Vec<BezierCurve> {
    let mut nodes: Vec<[f64; 2]> = (0..=n)
        .map(|i| {
            [
                i as f64 * 1.5 + rng.range(-0.2, 0.2),
                if i % 2 == 0 { 0.0 } else { 1.0 } + rng.range(-0.2, 0.2),
            ]
        })
        .collect();
    if closed {
        // Close over a polygon instead: points on a circle.
        nodes = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                let r = 3.0 + rng.range(-0.3, 0.3);
                [r * a.cos(), r * a.sin()]
            })
            .collect();
        nodes.push(nodes[0]);
    }
    (0..n)
        .map(|i| {
            let (a, b) = (nodes[i], nodes[i + 1]);
            let d = [b[0] - a[0], b[1] - a[1]];
            let normal = [-d[1], d[0]];
            let (s1, s2) = (rng.range(-0.15, 0.15), rng.range(-0.15, 0.15));
            curve(&[
                &a,
                &[
                    a[0] + d[0] / 3.0 + s1 * normal[0],
                    a[1] + d[1] / 3.0 + s1 * normal[1],
                ],
                &[
                    a[0] + 2.0 * d[0] / 3.0 + s2 * normal[0],
                    a[1] + 2.0 * d[1] / 3.0 + s2 * normal[1],
                ],
                &b,
            ])
        })
        .collect()
}

#[test]
fn chains_open_and_closed_are_ck_at_every_join() {
    let mut rng = Lcg(5);
    for closed in [false, true] {
        let curves = zigzag(&mut rng, 9, closed);
        let k = 2;
        let (alpha, beta) = (1.3, 0.8);
        let corner = FilletOptions::symmetric(0.3, k).with_scales(alpha, beta);
        let options = if closed {
            ChainFilletOptions::closed(corner)
        } else {
            ChainFilletOptions::open(corner)
        };
        let r = fillet_chain(&curves, &options).unwrap();
        let n = curves.len();
        assert_eq!(r.pieces.len(), if closed { 2 * n } else { 2 * n - 1 });
        assert_eq!(r.corners.len(), if closed { n } else { n - 1 });
        // Parameter length of each trimmed curve.
        let kept = |i: usize| -> f64 {
            let start = if i > 0 {
                r.corners[i - 1].v0
            } else if closed {
                r.corners[n - 1].v0
            } else {
                0.0
            };
            let end = if i < r.corners.len() {
                r.corners[i].u0
            } else {
                1.0
            };
            end - start
        };
        for (i, c) in r.corners.iter().enumerate() {
            assert_eq!((c.crossing.u, c.crossing.v), (1.0, 0.0), "corner {i}");
            let trim = r.pieces[2 * i].as_bezier().unwrap();
            let blend = r.pieces[2 * i + 1].as_bezier().unwrap();
            let next = r.pieces[(2 * i + 2) % r.pieces.len()].as_bezier().unwrap();
            let next_kept = kept((i + 1) % n);
            let jl = join_jumps(trim, kept(i), blend, alpha, k);
            let jr = join_jumps(blend, alpha, next, next_kept * alpha / beta, k);
            for order in 0..=k {
                assert!(jl[order] <= 1e-9, "corner {i} left, order {order}: {jl:?}");
                assert!(jr[order] <= 1e-9, "corner {i} right, order {order}: {jr:?}");
            }
            // Setbacks as arc lengths from the shared end.
            let lp = curves[i].arc_length(c.u0, 1.0, 1e-14).unwrap();
            let lq = curves[(i + 1) % n].arc_length(0.0, c.v0, 1e-14).unwrap();
            assert!((lp - 0.3).abs() <= 1e-9 * 0.3 && (lq - 0.3).abs() <= 1e-9 * 0.3);
        }
    }
}

#[test]
fn parallel_and_sequential_chains_are_identical() {
    let mut rng = Lcg(99);
    let curves = zigzag(&mut rng, 100, false);
    let corner = FilletOptions::symmetric(0.25, 3);
    let sequential = ChainFilletOptions {
        parallel_threshold: usize::MAX,
        ..ChainFilletOptions::open(corner.clone())
    };
    let parallel = ChainFilletOptions {
        parallel_threshold: 0,
        ..ChainFilletOptions::open(corner)
    };
    let a = fillet_chain(&curves, &sequential).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let b = pool.install(|| fillet_chain(&curves, &parallel)).unwrap();
    assert_eq!(a, b);
    // The first failing corner is the one reported, either way.
    let mut broken = curves.clone();
    broken[40] = curve(&[&[100.0, 100.0], &[101.0, 100.0]])
        .elevate_degree(3)
        .unwrap();
    broken[90] = curve(&[&[200.0, 100.0], &[201.0, 100.0]])
        .elevate_degree(3)
        .unwrap();
    let ea = fillet_chain(&broken, &sequential).unwrap_err();
    let eb = pool
        .install(|| fillet_chain(&broken, &parallel))
        .unwrap_err();
    assert_eq!(ea, eb);
    assert!(ea.to_string().contains("corner 39"), "{ea}");
}

#[test]
fn chain_errors() {
    let mut rng = Lcg(3);
    let curves = zigzag(&mut rng, 3, false);
    let options = ChainFilletOptions::open(FilletOptions::symmetric(0.3, 1));
    let e = fillet_chain(&curves[..1], &options).unwrap_err();
    assert!(e.to_string().contains("at least 2 curves"), "{e}");
    // Setbacks so long that the cuts on the middle curve pass each other.
    let long = ChainFilletOptions::open(FilletOptions::symmetric(1.0, 1));
    let e = fillet_chain(&curves, &long).unwrap_err();
    assert!(e.to_string().contains("curves[1]"), "{e}");
    // A smooth (tangent-continuous) joint is not a corner.
    let a = curve(&[&[0.0, 0.0], &[1.0, 0.0], &[2.0, 0.0]]);
    let b = curve(&[&[2.0, 0.0], &[3.0, 0.0], &[4.0, 1.0]]);
    let e = fillet_chain(&[a, b], &options).unwrap_err();
    assert!(matches!(e, BezjoinError::NoIntersection { .. }), "{e}");
    assert!(e.to_string().contains("corner 0"), "{e}");
    assert!(e.to_string().contains("tangentially"), "{e}");
}

#[test]
fn three_d_corner_is_ck() {
    // Two space cubics through X = (0.2, -0.1, 0.5) at u = 0.6 and v = 0.3
    // (each shifted so), crossing at an angle.
    let x = [0.2, -0.1, 0.5];
    let shift_through = |rows: [[f64; 3]; 4], t: f64| -> BezierCurve {
        let raw = BezierCurve::from_rows(&rows).unwrap();
        let at = raw.eval(t);
        let moved: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| (0..3).map(|c| r[c] + x[c] - at[c]).collect())
            .collect();
        BezierCurve::from_rows(&moved).unwrap()
    };
    let p = shift_through(
        [
            [0.0, 0.0, 0.0],
            [1.0, 0.3, 0.2],
            [2.0, -0.2, 0.5],
            [3.0, 0.1, 0.4],
        ],
        0.6,
    );
    let q = shift_through(
        [
            [0.0, 0.0, 0.0],
            [0.2, 1.0, 0.4],
            [-0.1, 2.0, 0.1],
            [0.3, 3.0, 0.6],
        ],
        0.3,
    );
    let f = fillet(&p, &q, &FilletOptions::new(0.4, 0.7, 3, 2)).unwrap();
    assert!((f.crossing.u - 0.6).abs() < 1e-12 && (f.crossing.v - 0.3).abs() < 1e-12);
    let spline = f.to_bspline().unwrap();
    let [a, b, _] = f.knot_intervals();
    assert_continuous(&spline, a, 3, 1e-9, "3D P|R");
    assert_continuous(&spline, a + b, 2, 1e-9, "3D R|Q");
    let lp = p.arc_length(f.u0, 0.6, 1e-14).unwrap();
    assert!((lp - 0.4).abs() <= 1e-9 * 0.4);
}

/// Fast lines, short setback: with the paper's scale 1 the blend's inner
/// control points pass the corner (the blend loops); the automatic scale
/// keeps the blend inside the corner, is C^k in the B-spline sense with the
/// knot intervals of the chosen scale, and is a minimum of the fairness
/// energy over the scale.
#[test]
fn auto_scale_keeps_a_fast_corner_inside_and_minimises_the_energy() {
    use bezjoin_core::fairness_energy;
    // P runs along y = 0 to the corner X = (0, 0) and beyond, Q along x = 0
    // upwards; both with speed 8 (parameter length 1, 8 units long), written
    // as cubics so that C^3 can be asked.
    let p = curve(&[&[-4.0, 0.0], &[4.0, 0.0]])
        .elevate_degree(3)
        .unwrap();
    let q = curve(&[&[0.0, -4.0], &[0.0, 4.0]])
        .elevate_degree(3)
        .unwrap();
    let order = 3;
    let paper = fillet(&p, &q, &FilletOptions::symmetric(0.5, order)).unwrap();
    // Scale 1: R'(0) = P'(u0) = (8, 0), so R_1 = R_0 + (8/7, 0) is past x = 0.
    assert!(paper.blend.point(1)[0] > 0.0, "{:?}", paper.blend.point(1));
    let options = FilletOptions::symmetric(0.5, order).with_auto_scale();
    let auto = fillet(&p, &q, &options).unwrap();
    let s = auto.p_scale;
    assert_eq!(auto.q_scale, s);
    assert!(s > 0.0 && s < 1.0, "s = {s}");
    // Inside the corner: every control point of the blend in the quadrant
    // x <= 0, y >= 0 (the blend lies in their convex hull).
    for i in 0..=auto.blend.degree() {
        let b = auto.blend.point(i);
        assert!(b[0] <= 1e-15 && b[1] >= -1e-15, "control point {i}: {b:?}");
    }
    // Same setbacks and cut points as the paper's scale; C^3 at both joins.
    assert_eq!((auto.u0, auto.v0), (paper.u0, paper.v0));
    let intervals = [auto.u0, s, 1.0 - auto.v0];
    let spline = BSplineCurve::from_bezier_chain(
        &[
            auto.p_trimmed.as_bezier().unwrap().clone(),
            auto.blend.clone(),
            auto.q_trimmed.as_bezier().unwrap().clone(),
        ],
        &intervals,
    )
    .unwrap();
    // Lines have zero second and third derivatives, so each jump is taken
    // relative to the largest derivative at the join, not to itself.
    for t in [intervals[0], intervals[0] + s] {
        let left = spline.eval_derivatives_side(t, order, KnotSide::Left);
        let right = spline.eval_derivatives_side(t, order, KnotSide::Right);
        let dim = spline.dim();
        let row = |d: &[f64], k: usize| d[k * dim..(k + 1) * dim].to_vec();
        let size = (0..=order)
            .map(|k| norm(&row(&left, k)).max(norm(&row(&right, k))))
            .fold(0.0, f64::max);
        for k in 0..=order {
            let jump = distance(&row(&left, k), &row(&right, k));
            assert!(
                jump <= 1e-9 * size,
                "t = {t}: derivative {k} jumps by {jump:e} (size {size:e})"
            );
        }
    }
    // A minimum of the energy over the scale (fixed-scale fillets nearby).
    let energy = fairness_energy(&auto.blend);
    for factor in [0.9, 0.99, 1.01, 1.1] {
        let other = fillet(
            &p,
            &q,
            &FilletOptions::symmetric(0.5, order).with_scales(s * factor, s * factor),
        )
        .unwrap();
        assert!(
            fairness_energy(&other.blend) >= energy * (1.0 - 1e-12),
            "factor {factor}: {} < {energy}",
            fairness_energy(&other.blend)
        );
    }
    // Scales given before switching to the automatic scale are replaced,
    // not validated.
    let ignored = options
        .clone()
        .with_scales(-1.0, f64::NAN)
        .with_auto_scale();
    assert_eq!(fillet(&p, &q, &ignored).unwrap(), auto);
}

/// Space curves meet only within the distance tolerance (closest
/// approach): a skew pair has no corner to round.
#[test]
fn skew_three_d_curves_have_no_corner() {
    // P along x through X; Q a parabola through X at v = 1/2 with tangent
    // (0, 1, 0.5). Lifted along the common normal of the two tangents at X
    // by `lift`, Q passes P at exactly that distance.
    let x = [0.3, -0.2, 1.1];
    let p = curve(&[&[x[0] - 1.0, x[1], x[2]], &[x[0] + 1.0, x[1], x[2]]]);
    let n = [0.0, -0.5 / 1.25f64.sqrt(), 1.0 / 1.25f64.sqrt()];
    let q_lifted = |lift: f64| {
        let at = |r: [f64; 3]| -> Vec<f64> { (0..3).map(|c| r[c] + lift * n[c]).collect() };
        BezierCurve::from_rows(&[
            at([x[0] - 0.3, x[1] - 1.0, x[2] - 0.5]),
            at([x[0] + 0.3, x[1], x[2]]),
            at([x[0] - 0.3, x[1] + 1.0, x[2] + 0.5]),
        ])
        .unwrap()
    };
    let options = FilletOptions::new(0.3, 0.3, 1, 1);
    // Meeting: rounded (guards the construction).
    let f = fillet(&p, &q_lifted(0.0), &options).unwrap();
    assert!((f.crossing.u - 0.5).abs() < 1e-12 && (f.crossing.v - 0.5).abs() < 1e-12);
    // Skew by 1e-6 (the default tolerance is 1e-9 times the coordinate
    // scale 1.6): NoIntersection.
    let skew = q_lifted(1e-6);
    let e = fillet(&p, &skew, &options).unwrap_err();
    assert!(matches!(e, BezjoinError::NoIntersection { .. }), "{e}");
    assert!(e.to_string().contains("do not cross"), "{e}");
    // The deviation mode refuses it the same way.
    let e = fillet_within_deviation(&p, &skew, &DeviationFilletOptions::new(0.05, 1)).unwrap_err();
    assert!(matches!(e, BezjoinError::NoIntersection { .. }), "{e}");
    // Within a looser tolerance they meet and the corner is rounded.
    let mut loose = options.clone();
    loose.intersect.relative_distance_tolerance = 1e-5;
    let f = fillet(&p, &skew, &loose).unwrap();
    assert!(
        (f.crossing.distance - 1e-6).abs() < 1e-12,
        "{:?}",
        f.crossing
    );
}

/// An error of the intersection search at a chain corner names the corner,
/// as the other corner errors do.
#[test]
fn chain_intersection_errors_name_the_corner() {
    // Corner 0: two lines at a right angle, one hit. Corner 1: the line
    // x = 2 and a parabola that leaves its top end and crosses it again at
    // t = 2/3 (x(t) = 2 + 4t - 6t^2): two hits.
    let curves = [
        curve(&[&[0.0, 0.0], &[2.0, 0.0]]),
        curve(&[&[2.0, 0.0], &[2.0, 2.0]]),
        curve(&[&[2.0, 2.0], &[4.0, 1.0], &[0.0, 1.0]]),
    ];
    let mut corner = FilletOptions::symmetric(0.2, 1);
    let options = ChainFilletOptions::open(corner.clone());
    let r = fillet_chain(&curves, &options).unwrap();
    assert_eq!(
        (r.corners[1].crossing.u, r.corners[1].crossing.v),
        (1.0, 0.0)
    );
    // At most one hit per pair: corner 1's search exceeds the bound.
    corner.intersect.max_hits = 1;
    let limited = ChainFilletOptions::open(corner.clone());
    let e = fillet_chain(&curves, &limited).unwrap_err();
    assert!(matches!(e, BezjoinError::IllConditioned { .. }), "{e}");
    assert!(
        e.to_string()
            .starts_with("corner 1: curve intersection: more than max_hits = 1"),
        "{e}"
    );
    // The same in parallel (the first failing corner in chain order).
    let parallel = ChainFilletOptions {
        parallel_threshold: 0,
        ..limited
    };
    assert_eq!(fillet_chain(&curves, &parallel).unwrap_err(), e);
    // One box pair is enough for corner 0 (two flat lines are a leaf at
    // once) but not for the parabola of corner 1: corner 1 is named.
    corner.intersect.max_hits = 10_000;
    corner.intersect.max_box_pairs = 1;
    let e = fillet_chain(&curves, &ChainFilletOptions::open(corner)).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("corner 1: curve intersection: more than max_box_pairs = 1"),
        "{e}"
    );
}

fn whole_length(c: &bezjoin_core::Curve) -> f64 {
    let (a, b) = c.domain();
    c.arc_length_default(a, b).unwrap()
}

/// A setback as long as its curve (within the setback's accuracy) is
/// refused by name whatever the rounding: it used to be accepted with a
/// kept piece 1.8e-15 long at one end (an edge no CAD kernel takes) and
/// refused at the other with "10 is not shorter than the arc length
/// 10.000000000000002". The rule is the chains' and the radius fillets'
/// (user testing, session 39): a setback 1e-10 shorter, which kept 8e-10 of
/// an 8-long curve, is refused too; one 1e-8 shorter is answered and keeps
/// that much of the curve.
#[test]
fn a_setback_as_long_as_its_curve_is_refused_not_left_as_a_sliver() {
    let bent_p = BezierCurve::new(2, 2, vec![0.0, 0.0, 5.0, 0.0, 10.0, 0.0]).unwrap();
    let bent_q = BezierCurve::new(2, 2, vec![10.0, 0.0, 10.0, 4.0, 10.0, 8.0]).unwrap();
    let line_p = BezierCurve::new(2, 1, vec![0.0, 0.0, 10.0, 0.0]).unwrap();
    let line_q = BezierCurve::new(2, 1, vec![10.0, 0.0, 10.0, 8.0]).unwrap();
    for (p, q) in [(&bent_p, &bent_q), (&line_p, &line_q), (&bent_p, &line_q)] {
        for (dp, dq, name) in [(10.0, 1.0, "p_setback"), (1.0, 8.0, "q_setback")] {
            for order in [1, 2] {
                let options = FilletOptions::new(dp, dq, order, order);
                match bezjoin_core::fillet_vertex(p, q, &options, 0.0) {
                    Err(BezjoinError::InvalidArgument { name: got, reason }) => {
                        assert_eq!(got, name, "{reason}");
                        assert!(reason.contains("by more than"), "{reason}");
                    }
                    Ok(f) => panic!(
                        "{name}: answered, kept pieces of length {} and {}",
                        whole_length(&f.p_trimmed),
                        whole_length(&f.q_trimmed)
                    ),
                    Err(other) => panic!("{name}: {other}"),
                }
            }
        }
        let options = FilletOptions::new(1.0, 8.0 * (1.0 - 1e-10), 2, 2);
        match bezjoin_core::fillet_vertex(p, q, &options, 0.0) {
            Err(BezjoinError::InvalidArgument { name, reason }) => {
                assert_eq!(name, "q_setback", "{reason}");
                assert!(reason.contains("1e-9 of Q's length"), "{reason}");
            }
            other => panic!("{other:?}"),
        }
        let options = FilletOptions::new(1.0, 8.0 * (1.0 - 1e-8), 2, 2);
        let f = bezjoin_core::fillet_vertex(p, q, &options, 0.0).unwrap();
        let kept = whole_length(&f.q_trimmed);
        assert!((kept - 8e-8).abs() <= 1e-11, "kept {kept}");
    }
}

/// A path that doubles back at the vertex (a line and the same line run
/// back) has no corner, only a cusp: refused by name, as the chains and the
/// radius fillet refuse it, instead of a blend that runs out along the line
/// and back. A sharp but real corner (179 degrees of turn) and a smooth joint
/// (collinear lines, smoothed by a C^k blend) are still answered.
#[test]
fn a_path_that_doubles_back_at_the_vertex_is_refused() {
    let out = BezierCurve::new(2, 1, vec![0.0, 0.0, 10.0, 0.0]).unwrap();
    let back = BezierCurve::new(2, 1, vec![10.0, 0.0, 0.0, 0.0]).unwrap();
    let options = FilletOptions::new(1.0, 1.0, 2, 2);
    for (p, q) in [(&out, &back), (&back, &out)] {
        match bezjoin_core::fillet_vertex(p, q, &options, 0.0) {
            Err(BezjoinError::NoIntersection { reason }) => {
                assert!(reason.contains("double back"), "{reason}")
            }
            other => panic!("{other:?}"),
        }
    }
    // 179 degrees of turn: a real (very sharp) corner.
    let angle = 179.0f64.to_radians();
    let sharp = BezierCurve::new(
        2,
        1,
        vec![10.0, 0.0, 10.0 + 10.0 * angle.cos(), 10.0 * angle.sin()],
    )
    .unwrap();
    let f = bezjoin_core::fillet_vertex(&out, &sharp, &options, 0.0).unwrap();
    assert_eq!(f.blend.degree(), 5);
    let ahead = BezierCurve::new(2, 1, vec![10.0, 0.0, 20.0, 0.0]).unwrap();
    assert!(bezjoin_core::fillet_vertex(&out, &ahead, &options, 0.0).is_ok());
}

/// A huge setback is named in a short message, as a huge radius is: the
/// setback and the arc length it exceeds read in exponent form (1e300 used
/// to print as its 301 digits), for a vertex fillet, a crossing and a
/// chain, and for the Q end.
#[test]
fn a_huge_setback_is_named_in_a_short_message() {
    let along = BezierCurve::new(2, 1, vec![0.0, 0.0, 40.0, 0.0]).unwrap();
    let up = BezierCurve::new(2, 1, vec![40.0, 0.0, 40.0, 30.0]).unwrap();
    let through = BezierCurve::new(2, 1, vec![40.0, -10.0, 40.0, 30.0]).unwrap();
    let check = |result: Result<(), BezjoinError>, named: &str| match result {
        Err(BezjoinError::InvalidArgument { name, reason }) => {
            assert_eq!(name, named, "{reason}");
            assert!(reason.contains("1e300") && reason.len() < 200, "{reason}");
        }
        other => panic!("{other:?}"),
    };
    for (p_setback, q_setback, named) in [(1e300, 1.0, "p_setback"), (1.0, 1e300, "q_setback")] {
        let options = FilletOptions::new(p_setback, q_setback, 2, 2);
        check(
            bezjoin_core::fillet_vertex(&along, &up, &options, 0.0).map(|_| ()),
            named,
        );
        check(
            bezjoin_core::fillet(&along, &through, &options).map(|_| ()),
            named,
        );
        let chain = ChainFilletOptions::open(options.clone());
        let got = bezjoin_core::fillet_chain(&[along.clone(), up.clone()], &chain).map(|_| ());
        match got {
            Err(BezjoinError::InvalidArgument { reason, .. }) => {
                assert!(reason.contains("1e300") && reason.len() < 300, "{reason}")
            }
            other => panic!("{other:?}"),
        }
    }
}

/// A setback at most 1e-9 of the curves' coordinate size is refused by name,
/// as such a radius is: a setback of 1e-300 was answered with a blend 4e-15
/// long (user testing, session 40), an edge no CAD kernel takes. For the
/// vertex fillet, at a crossing and along a chain, at either end; twice that
/// is answered.
#[test]
fn a_setback_too_small_to_tell_from_the_corner_is_refused_by_name() {
    let along = BezierCurve::new(2, 1, vec![0.0, 0.0, 10.0, 0.0]).unwrap();
    let up = BezierCurve::new(2, 1, vec![10.0, 0.0, 10.0, 10.0]).unwrap();
    let through = BezierCurve::new(2, 1, vec![5.0, -5.0, 5.0, 5.0]).unwrap();
    for tiny in [1e-300, 1e-9 * 10.0] {
        for (p_setback, q_setback, named) in [(tiny, 1.0, "p_setback"), (1.0, tiny, "q_setback")] {
            let options = FilletOptions::new(p_setback, q_setback, 2, 2);
            let chain = ChainFilletOptions::open(options.clone());
            let results = [
                bezjoin_core::fillet_vertex(&along, &up, &options, 0.0).map(|_| ()),
                bezjoin_core::fillet(&along, &through, &options).map(|_| ()),
                bezjoin_core::fillet_chain(&[along.clone(), up.clone()], &chain).map(|_| ()),
            ];
            for result in results {
                match result {
                    Err(BezjoinError::InvalidArgument { name, reason }) => {
                        assert_eq!(name, named, "{reason}");
                        assert!(
                            reason.contains("could not be told from the corner"),
                            "{reason}"
                        );
                    }
                    other => panic!("{tiny:e} as {named}: {other:?}"),
                }
            }
        }
    }
    let options = FilletOptions::new(2e-8, 2e-8, 2, 2);
    let f = bezjoin_core::fillet_vertex(&along, &up, &options, 0.0).unwrap();
    assert_eq!(f.blend.degree(), 5);
}
