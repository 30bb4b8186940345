//! Symmetric ends for the fair search: where the blend problem is its own
//! mirror image, the fair blend is chosen among the symmetric blends.
//!
//! A problem is symmetric under a linear isometry `L` of vectors with
//! `L L = I` (the reflection across the plane that bisects the chord
//! `Q(v0) - P(u0)`, or the point reflection through the chord's midpoint,
//! `L = -I`) when `Q`'s end is `P`'s end carried by `L` and traversed the
//! other way: the arc-length derivatives `d^j Q / ds^j` at `v0` are
//! `(-1)^j L d^j P / ds^j` at `u0`, `j = 1..k`. The corner of two lines cut
//! at equal distances from their vertex (every fillet by radius of two
//! lines) is symmetric under the reflection, the step between two parallel
//! lines under the point reflection. A symmetric blend, `R(t) = m + L (R(1 -
//! t) - m)` (`m` the midpoint), has `R^(j)(1) = (-1)^j L R^(j)(0)`: given
//! `P`'s shape values `beta_p`, with targets `T_j = sum_i B_(j,i)(beta_p)
//! P^(i)(u0)`, `Q`'s are the solution of
//!
//! ```text
//! sum_(i=1..j) B_(j,i)(beta_q) Q^(i)(v0) = (-1)^j L T_j,   j = 1..k,
//! ```
//!
//! triangular in `beta_q` (`B_(j,1) = beta_j`, and `B_(j,i)` for `i >= 2`
//! holds `beta_1..beta_(j-1)` only): `beta_(q,j)` is the component along
//! `Q'(v0)` of the right-hand side less the known terms. On a symmetric
//! problem that right-hand side lies along `Q'(v0)` for every `beta_p`, and
//! the blend of `(beta_p, beta_q)` is symmetric (up to rounding).
//!
//! Why (user testing, session 44): the fair search's simplex starts with a
//! step in each shape value. On a symmetric problem a step at `P`'s end and
//! the same step at `Q`'s end give mirror-image blends of equal energy, a
//! tie that rounding breaks: the G3 fillet of radius 9 in a corner of two
//! lines came out lopsided by 1.6 (18 % of the radius) and another blend
//! came out when the corner moved by 0.001. Searching `P`'s values alone,
//! with `Q`'s their mirror, removes the tie and halves the search.

use crate::connect::Problem;

use super::{MAX_GEOMETRIC_ORDER, partial_bell_small};

/// The largest part of a right-hand side of the mirror equations, relative
/// to the size of its terms, that may lie off `Q'(v0)` for a problem to
/// count as symmetric: far above rounding (`1e-16` times the terms' growth
/// with the coordinates), far below any asymmetry that shows (`1e-9` of a
/// part 1000 across is a micrometre).
pub const SYMMETRY_TOLERANCE: f64 = 1e-9;

/// The tolerance of [`EndSymmetry::of`] is at least this many roundings of
/// the ends' largest coordinate, relative to the chord.
pub const SYMMETRY_ROUNDING: f64 = 256.0;

/// The shape values' ratios `gamma_j = beta_j / beta_1` of the test that
/// decides symmetry ([`EndSymmetry::of`]): arbitrary, non-zero, so that
/// every term of the mirror equations is exercised.
const TEST_GAMMAS: [f64; MAX_GEOMETRIC_ORDER - 1] = [0.37, -0.23, 0.19, -0.13, 0.11];

/// The isometry of vectors that carries `P`'s end to `Q`'s.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// Across the plane through the chord's midpoint perpendicular to it.
    Reflection,
    /// Through the chord's midpoint (`v -> -v`).
    PointReflection,
}

/// A symmetry of a blend problem's two ends ([`EndSymmetry::of`]).
#[derive(Debug, Clone)]
pub(super) struct EndSymmetry {
    kind: Kind,
    /// The unit chord `(Q(v0) - P(u0)) / |Q(v0) - P(u0)|`.
    axis: Vec<f64>,
    /// `Q'(v0)` and `|Q'(v0)|^2`, the same for every shape value.
    q1: Vec<f64>,
    q1_square: f64,
    /// The target and right-hand side of one row of the mirror equations
    /// (`2 dim`): [`solve`](Self::solve) runs in every trial of the fair
    /// search, and allocates nothing.
    scratch: std::cell::RefCell<Vec<f64>>,
}

impl EndSymmetry {
    /// The symmetry of `problem`'s ends, if any: orders equal and at least
    /// 1, no interior constraints, ends apart, and the mirror equations for
    /// the test shape values (`beta_1 = beta1`, `gamma_j` from
    /// [`TEST_GAMMAS`]) solved with every right-hand side within
    /// [`SYMMETRY_TOLERANCE`] (or [`SYMMETRY_ROUNDING`] roundings of the
    /// ends' largest coordinate over the chord, if larger) of `Q'(v0)` and
    /// a positive `beta_(q,1)`. The reflection is tried first.
    pub(super) fn of(problem: &Problem, beta1: f64) -> Option<Self> {
        let k = problem.p_order;
        if k == 0 || k != problem.q_order || !problem.constraints.is_empty() {
            return None;
        }
        let chord = problem.q_derivatives.row(0) - problem.p_derivatives.row(0);
        let length = chord.norm();
        if !(length > 0.0 && length.is_finite() && beta1 > 0.0 && beta1.is_finite()) {
            return None;
        }
        let axis: Vec<f64> = chord.iter().map(|c| c / length).collect();
        let q1: Vec<f64> = problem.q_derivatives.row(1).iter().copied().collect();
        let q1_square: f64 = q1.iter().map(|v| v * v).sum();
        if !(q1_square > 0.0 && q1_square.is_finite()) {
            return None;
        }
        // The ends' own rounding far from the origin: a symmetric problem
        // whose coordinates are 1e7 and whose chord is 2 is symmetric to
        // about 1e-9 only (review, session 44: 19 of 58 such problems were
        // recognised at 1e7, 60 of 60 at the origin).
        let largest = problem.ends_coordinate();
        let tolerance = SYMMETRY_TOLERANCE.max(SYMMETRY_ROUNDING * f64::EPSILON * largest / length);
        let mut test = [0.0; MAX_GEOMETRIC_ORDER];
        test[0] = beta1;
        for (value, gamma) in test[1..k].iter_mut().zip(TEST_GAMMAS) {
            *value = gamma * beta1;
        }
        let mut mirrored = [0.0; MAX_GEOMETRIC_ORDER];
        [Kind::Reflection, Kind::PointReflection]
            .into_iter()
            .map(|kind| Self {
                kind,
                axis: axis.clone(),
                q1: q1.clone(),
                q1_square,
                scratch: std::cell::RefCell::new(vec![0.0; 2 * problem.dim]),
            })
            .find(|symmetry| {
                symmetry
                    .solve(problem, &test[..k], &mut mirrored[..k])
                    .is_some_and(|off| off <= tolerance)
            })
    }

    /// `Q`'s shape values for `P`'s `p_shape` (the mirror equations), into
    /// `q_shape`; `false` where they have no solution (`beta_(q,1)` not
    /// positive, a value not finite).
    pub(super) fn mirror_shape(
        &self,
        problem: &Problem,
        p_shape: &[f64],
        q_shape: &mut [f64],
    ) -> bool {
        self.solve(problem, p_shape, q_shape).is_some()
    }

    /// `v` carried by the isometry, into `out`.
    fn apply(&self, v: &[f64], out: &mut [f64]) {
        match self.kind {
            Kind::Reflection => {
                let along: f64 = v.iter().zip(&self.axis).map(|(a, b)| a * b).sum();
                for ((o, x), a) in out.iter_mut().zip(v).zip(&self.axis) {
                    *o = x - 2.0 * along * a;
                }
            }
            Kind::PointReflection => {
                for (o, x) in out.iter_mut().zip(v) {
                    *o = -x;
                }
            }
        }
    }

    /// The mirror equations solved for `q_shape`; returns the largest part
    /// of a right-hand side off `Q'(v0)` relative to its terms' size, or
    /// `None` where there is no solution.
    fn solve(&self, problem: &Problem, p_shape: &[f64], q_shape: &mut [f64]) -> Option<f64> {
        let k = p_shape.len();
        let (p, q) = (&problem.p_derivatives, &problem.q_derivatives);
        let (q1, q1_square) = (&self.q1, self.q1_square);
        let p_bell = partial_bell_small(p_shape, k);
        let mut scratch = self.scratch.borrow_mut();
        let (target, rhs) = scratch.split_at_mut(problem.dim);
        let mut worst = 0.0f64;
        q_shape.fill(0.0);
        for j in 1..=k {
            target.fill(0.0);
            for i in 1..=j {
                for (c, t) in target.iter_mut().enumerate() {
                    *t += p_bell[j][i] * p[(i, c)];
                }
            }
            self.apply(target, rhs);
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            let mut size = 0.0;
            for v in rhs.iter_mut() {
                *v *= sign;
                size += *v * *v;
            }
            let mut size = size.sqrt();
            // `q_shape[j - 1..]` is still zero: the table's columns `i >= 2`
            // of row `j` are the known terms.
            let q_bell = partial_bell_small(q_shape, k);
            for i in 2..=j {
                let mut term = 0.0;
                for (c, v) in rhs.iter_mut().enumerate() {
                    let x = q_bell[j][i] * q[(i, c)];
                    *v -= x;
                    term += x * x;
                }
                size += term.sqrt();
            }
            let beta = rhs.iter().zip(q1).map(|(a, b)| a * b).sum::<f64>() / q1_square;
            let off: f64 = rhs
                .iter()
                .zip(q1)
                .map(|(a, b)| (a - beta * b) * (a - beta * b))
                .sum::<f64>()
                .sqrt();
            if !beta.is_finite() || (j == 1 && beta <= 0.0) {
                return None;
            }
            if size > 0.0 {
                worst = worst.max(off / size);
            }
            q_shape[j - 1] = beta;
        }
        Some(worst)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bezier::BezierCurve;
    use crate::connect::{ConnectOptions, prepare};

    fn problem(p: &[f64], u0: f64, q: &[f64], v0: f64, dim: usize, k: usize) -> Problem {
        let p = BezierCurve::new(dim, p.len() / dim - 1, p.to_vec()).unwrap();
        let q = BezierCurve::new(dim, q.len() / dim - 1, q.to_vec()).unwrap();
        prepare(&p, u0, &q, v0, &ConnectOptions::new(k, k)).unwrap()
    }

    fn kind(problem: &Problem) -> Option<Kind> {
        EndSymmetry::of(problem, 1.0).map(|s| s.kind)
    }

    /// Which problems are symmetric, and under what: the corner of two lines
    /// of different lengths cut at equal distances from the vertex (a
    /// reflection; lines of any speed), the same cut unequally (none), two
    /// parallel lines stepped (a point reflection), a cubic and its own
    /// mirror image in 3D (a reflection), an arc-like cubic next to a line
    /// (none), and the mirrored cubic with one pole moved by 1e-6 (none).
    /// Orders 1 to 4.
    #[test]
    fn symmetric_problems_are_recognised_and_others_are_not() {
        for k in 1..=4 {
            // Lines (-80, 0) -> (0, 0) and (0, 0) -> 45 (cos 73, sin 73),
            // cut 6 from the vertex on each.
            let (c, s) = (73f64.to_radians().cos(), 73f64.to_radians().sin());
            let corner = |cut_q: f64| {
                problem(
                    &[-80.0, 0.0, 0.0, 0.0],
                    1.0 - 6.0 / 80.0,
                    &[0.0, 0.0, 45.0 * c, 45.0 * s],
                    cut_q / 45.0,
                    2,
                    k,
                )
            };
            assert_eq!(kind(&corner(6.0)), Some(Kind::Reflection), "G{k}");
            assert_eq!(kind(&corner(6.5)), None, "G{k}");
            let step = problem(
                &[-10.0, 0.0, 0.0, 0.0],
                1.0,
                &[3.0, 2.0, 13.0, 2.0],
                0.0,
                2,
                k,
            );
            assert_eq!(kind(&step), Some(Kind::PointReflection), "G{k}");
            // A 3D cubic and its mirror image across the plane x = 2,
            // traversed the other way.
            let p = [-1.0, 0.3, 0.2, 0.0, 1.0, -0.4, 1.0, 1.3, 0.5, 1.5, 1.1, 0.9];
            let mirrored = |p: &[f64]| -> Vec<f64> {
                let mut out = Vec::new();
                for point in p.chunks(3).rev() {
                    out.extend([4.0 - point[0], point[1], point[2]]);
                }
                out
            };
            let q = mirrored(&p);
            assert_eq!(
                kind(&problem(&p, 0.8, &q, 0.2, 3, k)),
                Some(Kind::Reflection),
                "G{k}"
            );
            let mut moved = q.clone();
            moved[4] += 1e-6;
            assert_eq!(kind(&problem(&p, 0.8, &moved, 0.2, 3, k)), None, "G{k}");
            let arc = [0.0, 0.0, 1.0, 0.0, 2.0, 0.5, 2.5, 1.5];
            let line = [2.5, 1.5, 3.0, 2.5];
            assert_eq!(kind(&problem(&arc, 0.9, &line, 0.1, 2, k)), None, "G{k}");
        }
    }

    /// On a symmetric problem the mirror of any shape values gives
    /// symmetric targets: `R^(j)(1) = (-1)^j L R^(j)(0)` to rounding, for
    /// random shape values of both signs.
    #[test]
    fn mirrored_shapes_give_mirrored_targets() {
        let p = [-1.0, 0.3, 0.2, 0.0, 1.0, -0.4, 1.0, 1.3, 0.5, 1.5, 1.1, 0.9];
        let q: Vec<f64> = p
            .chunks(3)
            .rev()
            .flat_map(|x| [4.0 - x[0], x[1], x[2]])
            .collect();
        let mut values = crate::test_values::Values(44);
        for k in 1..=MAX_GEOMETRIC_ORDER {
            let problem = problem(&p, 0.8, &q, 0.2, 3, k);
            let symmetry = EndSymmetry::of(&problem, 1.0).expect("symmetric");
            for _ in 0..20 {
                let mut shape = vec![0.0; k];
                shape[0] = 0.1 + values.unit();
                for value in &mut shape[1..] {
                    *value = 2.0 * values.signed();
                }
                let mut mirrored = vec![0.0; k];
                assert!(symmetry.mirror_shape(&problem, &shape, &mut mirrored));
                let p_bell = partial_bell_small(&shape, k);
                let q_bell = partial_bell_small(&mirrored, k);
                for j in 1..=k {
                    let (mut at_p, mut at_q) = ([0.0; 3], [0.0; 3]);
                    for i in 1..=j {
                        for c in 0..3 {
                            at_p[c] += p_bell[j][i] * problem.p_derivatives[(i, c)];
                            at_q[c] += q_bell[j][i] * problem.q_derivatives[(i, c)];
                        }
                    }
                    let mut expected = [0.0; 3];
                    symmetry.apply(&at_p, &mut expected);
                    let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
                    let size = at_p.iter().map(|v| v * v).sum::<f64>().sqrt();
                    for c in 0..3 {
                        let gap = (sign * expected[c] - at_q[c]).abs();
                        assert!(gap <= 1e-12 * size.max(1.0), "G{k} order {j}: {gap:e}");
                    }
                }
            }
        }
    }
}
