//! `ShapeScale::Balanced`: the automatic scale with both ends of the blend
//! at one speed. Its defining properties: the blend does not depend on how
//! fast either input runs in its own parameter (a linear reparametrisation
//! of P or Q gives the same blend), both ends of the blend run at the same
//! speed, and that speed minimises the fairness energy among all speeds in
//! the search range.

mod common;

use bezjoin_core::{
    AUTO_SCALE_SEARCH_DECADES, BezierCurve, BezjoinError, ChainFilletOptions, ConnectOptions,
    Connection, DeviationFilletOptions, FilletOptions, NurbsCurve, ShapeScale,
    UNKINKED_POLYGON_CHORDS, connect, fairness_energy, fillet_chain, fillet_vertex,
    fillet_within_deviation,
};
use common::{Random, distance, speed_and_floor};

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The largest control-point difference of `a` and `b`, relative to the
/// larger control-point size of the two.
fn relative_difference(a: &BezierCurve, b: &BezierCurve) -> f64 {
    assert_eq!(a.points().len(), b.points().len());
    let size = a
        .coordinate_scale()
        .max(b.coordinate_scale())
        .max(f64::MIN_POSITIVE);
    a.points()
        .iter()
        .zip(b.points())
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / size
}

/// Random pairs: (P, u0, Q, v0, kp, kq), 2D and 3D, degrees 2 to 5, the
/// curves apart so that the gap is not tiny.
fn pairs(count: usize) -> Vec<(BezierCurve, f64, BezierCurve, f64, usize, usize)> {
    let mut random = Random(0xba1a_11ce);
    (0..count)
        .map(|_| {
            let dim = 2 + random.below(2);
            let (np, nq) = (2 + random.below(4), 2 + random.below(4));
            let p = random.curve(dim, np, 1.0);
            let mut q = random.curve(dim, nq, 1.0);
            let shift = random.range(1.0, 3.0);
            let q_points: Vec<f64> = q
                .points()
                .iter()
                .enumerate()
                .map(|(i, v)| if i % dim == 0 { v + shift } else { *v })
                .collect();
            q = BezierCurve::new(dim, q.degree(), q_points).unwrap();
            let kp = 1 + random.below(3);
            let kq = 1 + random.below(3);
            (p, random.range(0.3, 0.9), q, random.range(0.1, 0.7), kp, kq)
        })
        .collect()
}

/// `bezier` as a NURBS curve on `[0, length]`: the same points, a linear
/// reparametrisation (speed divided by `length`).
fn on_domain(bezier: &BezierCurve, length: f64) -> NurbsCurve {
    NurbsCurve::from_bezier(bezier)
        .reparametrized(0.0, length)
        .unwrap()
}

#[test]
fn the_balanced_blend_does_not_depend_on_the_inputs_parametrisation() {
    let mut auto_moved = 0;
    let mut compared = 0;
    for (i, (p, u0, q, v0, kp, kq)) in pairs(40).into_iter().enumerate() {
        let options = ConnectOptions::new(kp, kq);
        let Ok(reference) = connect(&p, u0, &q, v0, &options.clone().with_balanced_scale()) else {
            continue;
        };
        let auto = connect(&p, u0, &q, v0, &options.clone().with_auto_scale()).unwrap();
        for (cp, cq) in [(1e-3, 1.0), (1.0, 250.0), (40.0, 0.02)] {
            let (pn, qn) = (on_domain(&p, cp), on_domain(&q, cq));
            let balanced = connect(
                &pn,
                u0 * cp,
                &qn,
                v0 * cq,
                &options.clone().with_balanced_scale(),
            )
            .unwrap_or_else(|e| panic!("pair {i}, lengths {cp}, {cq}: {e}"));
            let difference = relative_difference(&balanced.curve, &reference.curve);
            assert!(
                difference < 1e-9,
                "pair {i}, lengths {cp}, {cq}: the balanced blend moved by {difference:e}"
            );
            // The scales absorb the reparametrisation: alpha |P'(u0)| is the speed.
            assert!((balanced.p_scale / cp - reference.p_scale).abs() <= 1e-9 * reference.p_scale);
            compared += 1;
            let moved = connect(
                &pn,
                u0 * cp,
                &qn,
                v0 * cq,
                &options.clone().with_auto_scale(),
            )
            .map(|c| relative_difference(&c.curve, &auto.curve))
            .unwrap_or(f64::INFINITY);
            if moved > 1e-3 {
                auto_moved += 1;
            }
        }
    }
    assert!(compared >= 100, "only {compared} comparisons");
    // The property is not a tautology: the one-s automatic scale moves.
    assert!(
        auto_moved * 2 > compared,
        "Auto moved in {auto_moved} of {compared}"
    );
}

#[test]
fn both_ends_of_the_balanced_blend_run_at_one_speed() {
    // The blend leaves each end at sigma |X'| / speed(X), speed(X) = max(|X'|,
    // the floor terms): at one speed sigma where no floor applies.
    let mut floored = 0;
    let mut compared = 0;
    for (i, (p, u0, q, v0, kp, kq)) in pairs(40).into_iter().enumerate() {
        let options = ConnectOptions::new(kp, kq).with_balanced_scale();
        let Ok(c) = connect(&p, u0, &q, v0, &options) else {
            continue;
        };
        let start = norm(&c.curve.derivative_at(0.0, 1));
        let end = norm(&c.curve.derivative_at(1.0, 1));
        let chord = distance(&p.eval(u0), &q.eval(v0));
        let (p_speed, p_floor) = speed_and_floor(&p, u0, kp, chord);
        let (q_speed, q_floor) = speed_and_floor(&q, v0, kq, chord);
        // alpha = sigma / max(|P'|, floor), beta = sigma / max(|Q'|, floor).
        let sigma = c.p_scale * p_speed.max(p_floor);
        assert!(
            (c.q_scale * q_speed.max(q_floor) - sigma).abs() <= 1e-12 * sigma,
            "pair {i}: the scales are not one sigma"
        );
        assert!(
            (start - c.p_scale * p_speed).abs() <= 1e-9 * start,
            "pair {i}"
        );
        assert!((end - c.q_scale * q_speed).abs() <= 1e-9 * end, "pair {i}");
        if p_floor <= p_speed && q_floor <= q_speed {
            assert!(
                (start - end).abs() <= 1e-9 * start.max(end),
                "pair {i}: |R'(0)| = {start}, |R'(1)| = {end}"
            );
            compared += 1;
        } else {
            floored += 1;
        }
    }
    // Random cubics with chords of 1 to 3: the floor is the exception.
    assert!(
        compared >= 30 && floored <= 5,
        "{compared} compared, {floored} floored"
    );
}

#[test]
fn an_end_that_turns_within_the_floor_keeps_the_blend_in_size() {
    // User testing, session 41: P ends at (6 + eps, 1) with its last two poles
    // eps apart (|P'(1)| = 3 eps, a near-stationary end), Q runs up x = 10.
    // Without the floor alpha = sigma / (3 eps) made control points of 1.2e26
    // (eps = 1e-15) to 164 (eps = 1e-3) on a shape 10 wide. The blend now stays
    // within a few times the shape, continuous at both ends, and the same when
    // P is reparametrised (also for eps = 0, an exactly stationary end).
    let q = BezierCurve::from_rows(&[[10.0, -2.0], [10.0, 3.0], [10.0, 8.0]]).unwrap();
    for eps in [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3] {
        let p = BezierCurve::from_rows(&[[0.0, 0.0], [3.0, 0.0], [6.0, 1.0], [6.0 + eps, 1.0]])
            .unwrap();
        let options = ConnectOptions::new(2, 2).with_balanced_scale();
        let c = connect(&p, 1.0, &q, 0.2, &options).unwrap();
        let size = c.curve.coordinate_scale();
        assert!(size < 30.0, "eps {eps:e}: control points up to {size}");
        let slow = on_domain(&p, 1e-3);
        let moved = connect(&slow, 1e-3, &q, 0.2, &options).unwrap();
        let difference = relative_difference(&moved.curve, &c.curve);
        assert!(
            difference < 1e-9,
            "eps {eps:e}: reparametrised, moved by {difference:e}"
        );
        // Both ends nearly stationary (review, session 41: the search was
        // centred on the chord over the raw speeds, 1e9 chords for eps =
        // 1e-9, and gave control points of 2.4e14).
        let q_slow =
            BezierCurve::from_rows(&[[10.0 - eps, -1.0], [10.0, -1.0], [10.0, 3.0], [11.0, 8.0]])
                .unwrap();
        let both = connect(&p, 1.0, &q_slow, 0.0, &options).unwrap();
        let size = both.curve.coordinate_scale();
        assert!(
            size < 30.0,
            "eps {eps:e}, both ends: control points up to {size}"
        );
    }
}

/// The connection with the balanced scales of speed `sigma`:
/// `sigma / max(|X'|, floor)` at each end.
fn at_speed(
    (p, u0, q, v0): (&BezierCurve, f64, &BezierCurve, f64),
    options: &ConnectOptions,
    sigma: f64,
) -> Option<Connection> {
    let chord = distance(&p.eval(u0), &q.eval(v0));
    let (p_speed, p_floor) = speed_and_floor(p, u0, options.p_order, chord);
    let (q_speed, q_floor) = speed_and_floor(q, v0, options.q_order, chord);
    let alpha = sigma / p_speed.max(p_floor);
    let beta = sigma / q_speed.max(q_floor);
    connect(p, u0, q, v0, &options.clone().with_scales(alpha, beta)).ok()
}

#[test]
fn the_balanced_speed_minimises_the_fairness_energy_over_the_range() {
    let half_width = AUTO_SCALE_SEARCH_DECADES * std::f64::consts::LN_10;
    let mut checked = 0;
    for (i, (p, u0, q, v0, kp, kq)) in pairs(24).into_iter().enumerate() {
        let options = ConnectOptions::new(kp, kq);
        let Ok(c) = connect(&p, u0, &q, v0, &options.clone().with_balanced_scale()) else {
            continue;
        };
        let best = fairness_energy(&c.curve);
        // The search range: two decades either side of the chord.
        let chord = norm(
            &(0..p.dim())
                .map(|k| q.eval(v0)[k] - p.eval(u0)[k])
                .collect::<Vec<_>>(),
        );
        let scan: Vec<(f64, f64)> = (0..=400)
            .filter_map(|j| {
                let sigma = (chord.ln() - half_width + 2.0 * half_width * j as f64 / 400.0).exp();
                let other = at_speed((&p, u0, &q, v0), &options, sigma)?;
                Some((sigma, fairness_energy(&other.curve)))
            })
            .collect();
        // Where the energy is least at the range's lower end (ends facing
        // away: the blend would turn in kinks) and no speed floor applies,
        // the speed is the chord's, or the largest below it whose control
        // polygon is at most UNKINKED_POLYGON_CHORDS chords (session 44).
        let lowest = scan.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
        let floored = [(&p, u0, kp), (&q, v0, kq)].iter().any(|&(x, at, order)| {
            let (speed, floor) = speed_and_floor(x, at, order, chord);
            order > 0 && floor > speed
        });
        if scan.first().is_some_and(|x| x.1 <= lowest) && !floored {
            let polygon = c.curve.polygon_length();
            assert!(
                polygon <= UNKINKED_POLYGON_CHORDS * chord * (1.0 + 1e-9),
                "pair {i}"
            );
            checked += 1;
            continue;
        }
        for (sigma, energy) in scan {
            assert!(
                best <= energy * (1.0 + 1e-9) + 1e-12,
                "pair {i}: sigma {sigma} gives {energy}, the balanced blend {best}"
            );
        }
        checked += 1;
    }
    assert!(checked >= 20, "only {checked} pairs answered");
}

/// Two lines at a right angle meeting at the origin: P along x from
/// `(-p_length, 0)`, Q along y to `(0, q_length)`, each a degree-1 Bezier
/// (speed = its length).
fn corner(p_length: f64, q_length: f64) -> (BezierCurve, BezierCurve) {
    (
        BezierCurve::from_rows(&[[-p_length, 0.0], [0.0, 0.0]]).unwrap(),
        BezierCurve::from_rows(&[[0.0, 0.0], [0.0, q_length]]).unwrap(),
    )
}

#[test]
fn a_corner_of_unequal_lines_gets_the_blend_of_equal_ones() {
    // Setback 1 on lines 1000 and 10 long cuts at the same points as on
    // lines 10 and 10; only the speeds differ.
    for (kp, kq) in [(1, 1), (2, 2), (3, 2)] {
        let options = FilletOptions::new(1.0, 1.0, kp, kq);
        let (p, q) = corner(10.0, 10.0);
        let equal = fillet_vertex(&p, &q, &options.clone().with_balanced_scale(), 0.0).unwrap();
        let (p, q) = corner(1000.0, 10.0);
        let unequal = fillet_vertex(&p, &q, &options.clone().with_balanced_scale(), 0.0).unwrap();
        let difference = relative_difference(&equal.blend, &unequal.blend);
        assert!(difference < 1e-9, "orders {kp}/{kq}: {difference:e}");
        // The one-s automatic scale does not have this property.
        let auto = fillet_vertex(&p, &q, &options.clone().with_auto_scale(), 0.0).unwrap();
        assert!(relative_difference(&equal.blend, &auto.blend) > 1e-2);
    }
}

#[test]
fn an_end_of_order_zero_takes_the_other_ends_speed() {
    let (p, q) = corner(1000.0, 10.0);
    let options = ConnectOptions::new(0, 2).with_balanced_scale();
    let c = connect(&p, 0.5, &q, 0.5, &options).unwrap();
    let q_speed = norm(&q.derivative_at(0.5, 1));
    assert!((c.p_scale - c.q_scale).abs() <= 1e-15 * c.q_scale);
    assert!((c.q_scale * q_speed - norm(&c.curve.derivative_at(1.0, 1))).abs() < 1e-9);
}

#[test]
fn the_deviation_fillet_refuses_the_balanced_scale_naming_it() {
    let (p, q) = corner(10.0, 10.0);
    let mut options = DeviationFilletOptions::new(0.1, 2);
    options.shape.scale = ShapeScale::Balanced;
    match fillet_within_deviation(&p, &q, &options) {
        Err(BezjoinError::InvalidArgument { name, .. }) => assert_eq!(name, "scale"),
        other => panic!("expected InvalidArgument(scale), got {other:?}"),
    }
}

#[test]
fn a_chain_takes_the_balanced_scale_at_every_corner() {
    // A closed 1000 x 10 rectangle: every corner's blend is the 10 x 10
    // square's blend at that corner, and each corner's scales are those of
    // the corner rounded alone.
    let rectangle = |w: f64, h: f64| {
        let c = [[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]];
        (0..4)
            .map(|i| BezierCurve::from_rows(&[c[i], c[(i + 1) % 4]]).unwrap())
            .collect::<Vec<_>>()
    };
    let options =
        ChainFilletOptions::closed(FilletOptions::new(1.0, 1.0, 2, 2).with_balanced_scale());
    let square = fillet_chain(&rectangle(10.0, 10.0), &options).unwrap();
    let long_sides = rectangle(1000.0, 10.0);
    let long = fillet_chain(&long_sides, &options).unwrap();
    for i in 0..4 {
        let corner = long_sides[(i + 1) % 4].point(0);
        let square_corner = rectangle(10.0, 10.0)[(i + 1) % 4].point(0).to_vec();
        let (a, b) = (&long.pieces[2 * i + 1], &square.pieces[2 * i + 1]);
        let (Some(a), Some(b)) = (a.as_bezier(), b.as_bezier()) else {
            panic!("corner {i}: the blends are Bezier curves");
        };
        for k in 0..=a.degree() {
            for c in 0..2 {
                let moved = (a.point(k)[c] - corner[c]) - (b.point(k)[c] - square_corner[c]);
                assert!(moved.abs() <= 1e-9, "corner {i}, point {k}: {moved:e}");
            }
        }
        let alone = fillet_vertex(
            &long_sides[i],
            &long_sides[(i + 1) % 4],
            &FilletOptions::new(1.0, 1.0, 2, 2).with_balanced_scale(),
            0.0,
        )
        .unwrap();
        assert_eq!(long.corners[i].scales, (alone.p_scale, alone.q_scale));
    }
}

#[test]
fn equal_speeds_give_the_automatic_scales_answer_bit_for_bit() {
    // Lines 10 and 10 (one speed at the cut) and an end of order 0: the
    // balanced blend is the automatic one, the same bits; lines 1000 and 10
    // are not (the property has a contrast).
    let options = FilletOptions::new(1.0, 1.0, 2, 2);
    let (p, q) = corner(10.0, 10.0);
    let balanced = fillet_vertex(&p, &q, &options.clone().with_balanced_scale(), 0.0).unwrap();
    let auto = fillet_vertex(&p, &q, &options.clone().with_auto_scale(), 0.0).unwrap();
    assert_eq!(balanced.blend.points(), auto.blend.points());
    let (long, _) = corner(1000.0, 10.0);
    let order_zero = ConnectOptions::new(0, 2);
    let balanced = connect(
        &long,
        0.5,
        &q,
        0.5,
        &order_zero.clone().with_balanced_scale(),
    )
    .unwrap();
    let auto = connect(&long, 0.5, &q, 0.5, &order_zero.with_auto_scale()).unwrap();
    assert_eq!(balanced.curve.points(), auto.curve.points());
    let balanced = fillet_vertex(&long, &q, &options.clone().with_balanced_scale(), 0.0).unwrap();
    let auto = fillet_vertex(&long, &q, &options.with_auto_scale(), 0.0).unwrap();
    assert_ne!(balanced.blend.points(), auto.blend.points());
}
