//! Exact conic arcs as rational quadratic NURBS (The NURBS Book A7.1).

use super::NurbsCurve;
use crate::error::{BezjoinError, Result, check_finite, check_finite_scalar, check_positive};

/// How far from unit length and from orthogonal the axes of
/// [`ellipse_arc`] may be (absolute, on unit vectors).
pub const AXIS_TOLERANCE: f64 = 1e-9;

/// The elliptic arc `c + rx cos(a) X + ry sin(a) Y`, `a` from `a0` to `a1`,
/// as a rational quadratic NURBS in dimension 2 or 3 (A7.1, mapped by the
/// affine map that takes the unit circle to the ellipse, which keeps the
/// weights).
///
/// The arc is cut into `ceil((a1 - a0) / 90 deg)` pieces of equal angle
/// `da`; each is one rational quadratic span with end weights 1 and middle
/// weight `cos(da / 2)`, so the curve is exactly the ellipse. The domain is
/// `[a0, a1]` and the knots sit at the pieces' angles, where the curve
/// passes through the ellipse point of that angle; between knots the
/// parameter is not the angle (no rational parametrization of a conic is).
///
/// Requirements: `dim` 2 or 3; `centre`, `x_axis`, `y_axis` of `dim`
/// values; the axes unit and orthogonal within [`AXIS_TOLERANCE`]; radii
/// `> 0`; `a0 < a1 <= a0 + 2 pi`. A full turn gives a closed curve (first
/// pole = last pole). A circle is the case `x_radius = y_radius`.
#[allow(clippy::too_many_arguments)]
pub fn ellipse_arc(
    dim: usize,
    centre: &[f64],
    x_axis: &[f64],
    y_axis: &[f64],
    x_radius: f64,
    y_radius: f64,
    a0: f64,
    a1: f64,
) -> Result<NurbsCurve> {
    if dim != 2 && dim != 3 {
        return Err(BezjoinError::invalid(
            "dim",
            format!("{dim}: conic arcs are built in dimension 2 or 3"),
        ));
    }
    for (name, v) in [("centre", centre), ("x_axis", x_axis), ("y_axis", y_axis)] {
        if v.len() != dim {
            return Err(BezjoinError::LengthMismatch {
                name: name.into(),
                expected: dim,
                actual: v.len(),
            });
        }
        check_finite(name, v)?;
    }
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    for (name, v) in [("x_axis", x_axis), ("y_axis", y_axis)] {
        let n = dot(v, v).sqrt();
        if (n - 1.0).abs() > AXIS_TOLERANCE {
            return Err(BezjoinError::invalid(
                name,
                format!("has length {n}; a unit vector is needed"),
            ));
        }
    }
    let cos = dot(x_axis, y_axis);
    if cos.abs() > AXIS_TOLERANCE {
        return Err(BezjoinError::invalid(
            "y_axis",
            format!("is not orthogonal to x_axis (cosine {cos:e})"),
        ));
    }
    check_positive("x_radius", x_radius)?;
    check_positive("y_radius", y_radius)?;
    check_finite_scalar("a0", a0)?;
    check_finite_scalar("a1", a1)?;
    let turn = 2.0 * std::f64::consts::PI;
    let sweep = a1 - a0;
    // `a1 - a0` carries the rounding of `a0 + 2 pi` when the caller made
    // `a1` that way: a full turn is accepted to 4 ulp of the angles.
    let slack = 4.0 * f64::EPSILON * a0.abs().max(a1.abs()).max(turn);
    if sweep.is_nan() || sweep <= 0.0 || sweep > turn + slack {
        return Err(BezjoinError::out_of_range(
            "a1",
            a1,
            format!("(a0, a0 + 2 pi] = ({a0}, {})", a0 + turn),
        ));
    }
    let full_turn = sweep >= turn - slack;
    let sweep = sweep.min(turn);
    let pieces = (sweep / (0.5 * std::f64::consts::PI) - 1e-12)
        .ceil()
        .max(1.0) as usize;
    let da = sweep / pieces as f64;
    let w_mid = (0.5 * da).cos();
    let at = |angle: f64, stretch: f64| -> Vec<f64> {
        let (s, c) = angle.sin_cos();
        (0..dim)
            .map(|i| centre[i] + stretch * (x_radius * c * x_axis[i] + y_radius * s * y_axis[i]))
            .collect()
    };
    let mut poles = Vec::with_capacity((2 * pieces + 1) * dim);
    let mut weights = Vec::with_capacity(2 * pieces + 1);
    let mut knots = vec![a0; 3];
    for i in 0..pieces {
        let start = a0 + i as f64 * da;
        poles.extend(at(start, 1.0));
        weights.push(1.0);
        poles.extend(at(start + 0.5 * da, 1.0 / w_mid));
        weights.push(w_mid);
        if i + 1 < pieces {
            knots.extend([start + da; 2]);
        }
    }
    // The last pole at the exact end angle (a full turn: the first pole).
    if full_turn {
        poles.extend(at(a0, 1.0));
    } else {
        poles.extend(at(a1, 1.0));
    }
    weights.push(1.0);
    knots.extend([a1; 3]);
    NurbsCurve::new(dim, 2, poles, Some(weights), knots)
}
