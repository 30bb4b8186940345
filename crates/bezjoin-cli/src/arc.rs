//! The plain circular-arc fillet, drawn next to bezjoin's rounding for
//! comparison.
//!
//! What it is: the circle that is tangent to `P` at the same start point
//! `P(u0)` as bezjoin's blend (so both roundings leave `P` at the same
//! place) and tangent to `Q` at some point `Q(v)`; the arc between the two
//! tangent points is the classic G1 fillet. It is exact up to the Newton
//! tolerance: the unknowns are the radius `r` and the parameter `v`, solved
//! from `P(u0) + s r nP = Q(v) + s r nQ(v)` (`nP`, `nQ` the left unit
//! normals, `s = +1` when the path turns left at the crossing, `-1` when it
//! turns right), starting from the straight-line estimate
//! `r = d / tan(delta/2)` (`d` the setback, `delta` the turning angle at the
//! crossing). The arc meets both curves with the same tangent (G1) but its
//! curvature `1/r` differs from theirs: the combs show the jump.

use bezjoin_core::{CurveRef, KnotSide};

use crate::check::derivatives;
use crate::svg::Shape;

/// A solved circular fillet.
#[derive(Debug, Clone)]
pub struct CircularFillet {
    /// The arc.
    pub shape: Shape,
    /// Its radius.
    pub radius: f64,
    /// Start point (on P, parameter `u0`).
    pub start: [f64; 2],
    /// End point (on Q, parameter `v`).
    pub end: [f64; 2],
    /// Parameter of the tangent point on Q.
    pub v: f64,
    /// Distance between the two descriptions of the centre after Newton.
    pub residual: f64,
}

/// Newton iterations allowed.
const MAX_ITERATIONS: usize = 60;

/// Point, first and second derivative of a plane curve at `t`, from `side`
/// at a knot of a NURBS curve.
fn jet(curve: CurveRef, t: f64, side: KnotSide) -> [[f64; 2]; 3] {
    let d = derivatives(curve, t, 2, side);
    let dim = curve.dim();
    [
        [d[0], d[1]],
        [d[dim], d[dim + 1]],
        [d[2 * dim], d[2 * dim + 1]],
    ]
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = v[0].hypot(v[1]);
    [v[0] / n, v[1] / n]
}

fn left(v: [f64; 2]) -> [f64; 2] {
    [-v[1], v[0]]
}

/// The circular fillet tangent to `p` at `p(u0)` and to `q` somewhere after
/// the crossing `q(v_cross)`, for the corner turning at the crossing
/// `(u_cross, v_cross)`; `v_guess` is where to start looking on `q`
/// (bezjoin's own `v0` is a good guess). `p`, `q`: Bezier or NURBS plane
/// curves, parameters in their domains (P's derivatives from the left of a
/// knot, Q's from the right). `None` if the curves are not planar, the
/// corner is degenerate, or Newton does not converge to `1e-10` of the
/// picture's size inside `q`'s parameter range.
pub fn circular_fillet<'a, 'b>(
    p: impl Into<CurveRef<'a>>,
    u0: f64,
    q: impl Into<CurveRef<'b>>,
    u_cross: f64,
    v_cross: f64,
    v_guess: f64,
) -> Option<CircularFillet> {
    let (p, q) = (p.into(), q.into());
    if p.dim() != 2 || q.dim() != 2 {
        return None;
    }
    let tp = unit(jet(p, u_cross, KnotSide::Left)[1]);
    let tq = unit(jet(q, v_cross, KnotSide::Right)[1]);
    let cross = tp[0] * tq[1] - tp[1] * tq[0];
    let dot = tp[0] * tq[0] + tp[1] * tq[1];
    let turning = cross.atan2(dot).abs();
    if !(1e-6..std::f64::consts::PI - 1e-6).contains(&turning) {
        return None;
    }
    let side = cross.signum();
    let [start, d1p, _] = jet(p, u0, KnotSide::Left);
    let n_p = left(unit(d1p));
    let setback = p
        .arc_length(u0, u_cross, p.default_length_accuracy())
        .ok()?;
    let q_last = q.domain().1;
    let mut radius = setback / (turning / 2.0).tan();
    let mut v = v_guess;
    let size = p.coordinate_scale().max(q.coordinate_scale());
    let mut residual = f64::INFINITY;
    for _ in 0..MAX_ITERATIONS {
        let [qv, d1, d2] = jet(q, v, KnotSide::Right);
        let speed = d1[0].hypot(d1[1]);
        let t = [d1[0] / speed, d1[1] / speed];
        let n_q = left(t);
        // F = start + s r nP - Q(v) - s r nQ(v)
        let f = [
            start[0] + side * radius * (n_p[0] - n_q[0]) - qv[0],
            start[1] + side * radius * (n_p[1] - n_q[1]) - qv[1],
        ];
        residual = f[0].hypot(f[1]);
        if residual <= 1e-10 * size {
            break;
        }
        // dT/dv = (Q'' - T (T.Q'')) / |Q'|, dN/dv = left(dT/dv).
        let along = t[0] * d2[0] + t[1] * d2[1];
        let dt = [
            (d2[0] - t[0] * along) / speed,
            (d2[1] - t[1] * along) / speed,
        ];
        let dn = left(dt);
        let jv = [
            -d1[0] - side * radius * dn[0],
            -d1[1] - side * radius * dn[1],
        ];
        let jr = [side * (n_p[0] - n_q[0]), side * (n_p[1] - n_q[1])];
        let det = jv[0] * jr[1] - jv[1] * jr[0];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let delta_v = (f[0] * jr[1] - f[1] * jr[0]) / det;
        let delta_r = (jv[0] * f[1] - jv[1] * f[0]) / det;
        v = (v - delta_v).clamp(v_cross, q_last);
        radius -= delta_r;
        if !(radius > 0.0 && radius.is_finite()) {
            return None;
        }
    }
    if residual > 1e-10 * size {
        return None;
    }
    let center = [
        start[0] + side * radius * n_p[0],
        start[1] + side * radius * n_p[1],
    ];
    let end_point = q.eval(v);
    let a0 = (start[1] - center[1]).atan2(start[0] - center[0]);
    let a1 = (end_point[1] - center[1]).atan2(end_point[0] - center[0]);
    let full = 2.0 * std::f64::consts::PI;
    let sweep = if side > 0.0 {
        (a1 - a0).rem_euclid(full)
    } else {
        -(a0 - a1).rem_euclid(full)
    };
    Some(CircularFillet {
        shape: Shape::Arc {
            center,
            radius,
            start_angle: a0,
            sweep,
        },
        radius,
        start,
        end: [end_point[0], end_point[1]],
        v,
        residual,
    })
}

#[cfg(test)]
mod circular_fillet_tests {
    use super::*;
    use crate::svg::signed_curvature;
    use bezjoin_core::BezierCurve;

    #[test]
    fn fillet_of_a_right_angle_between_lines_is_the_textbook_one() {
        // P along +x through the origin, Q along +y: left turn of 90 degrees.
        let p = BezierCurve::from_rows(&[[-4.0, 0.0], [4.0, 0.0]]).unwrap();
        let q = BezierCurve::from_rows(&[[0.0, -4.0], [0.0, 4.0]]).unwrap();
        // Setback 1 on P: u0 = 3/8 (P(u0) = (-1, 0)); radius must be 1, centre (-1, 1).
        let arc = circular_fillet(&p, 0.375, &q, 0.5, 0.5, 0.6).unwrap();
        assert!((arc.radius - 1.0).abs() < 1e-9, "{}", arc.radius);
        assert!((arc.v - 0.625).abs() < 1e-9);
        let Shape::Arc { center, sweep, .. } = arc.shape else {
            unreachable!()
        };
        assert!((center[0] + 1.0).abs() < 1e-9 && (center[1] - 1.0).abs() < 1e-9);
        assert!((sweep - std::f64::consts::FRAC_PI_2).abs() < 1e-9);
    }

    #[test]
    fn fillet_between_cubics_is_tangent_at_both_ends() {
        let p = BezierCurve::from_rows(&[[0.0, 0.0], [3.0, 1.0], [6.0, 0.5], [10.0, 3.0]]).unwrap();
        let q = BezierCurve::from_rows(&[[6.0, -3.0], [6.5, 0.0], [5.0, 4.0], [7.0, 8.0]]).unwrap();
        // Find the crossing by brute force (independent of the library).
        let mut best = (f64::INFINITY, 0.0, 0.0);
        for i in 0..=400 {
            for j in 0..=400 {
                let (u, v) = (i as f64 / 400.0, j as f64 / 400.0);
                let d = crate::check::distance(&p.eval(u), &q.eval(v));
                if d < best.0 {
                    best = (d, u, v);
                }
            }
        }
        let (_, uc, vc) = best;
        let arc = circular_fillet(&p, uc - 0.15, &q, uc, vc, vc + 0.15).unwrap();
        let [a0, d0, dd0] = arc.shape.jet(0.0);
        let [a1, d1, _] = arc.shape.jet(1.0);
        let tp = p.derivative_at(uc - 0.15, 1);
        let tq = q.derivative_at(arc.v, 1);
        let sin = |a: [f64; 2], b: &[f64]| {
            (a[0] * b[1] - a[1] * b[0]) / (a[0].hypot(a[1]) * b[0].hypot(b[1]))
        };
        let cos = |a: [f64; 2], b: &[f64]| {
            (a[0] * b[0] + a[1] * b[1]) / (a[0].hypot(a[1]) * b[0].hypot(b[1]))
        };
        assert!(sin(d0, &tp).abs() < 1e-8 && cos(d0, &tp) > 0.0);
        assert!(sin(d1, &tq).abs() < 1e-8 && cos(d1, &tq) > 0.0);
        assert!(crate::check::distance(&a0, &p.eval(uc - 0.15)) < 1e-9);
        assert!(crate::check::distance(&a1, &q.eval(arc.v)) < 1e-9);
        assert!((signed_curvature(d0, dd0).abs() - 1.0 / arc.radius).abs() < 1e-9);
    }
}
