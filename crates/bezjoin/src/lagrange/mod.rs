//! Splines whose defining points lie ON the curve: polynomial segments in
//! Lagrange form, joined with C^1 (or C^2, C^3) continuity by a local
//! recurrence, returned as exact Bezier pieces or one B-spline.
//!
//! After A.M. Kovtun, *"Spline of third degree with control points incident
//! to the curve"* (seed 004, stated in docs/mathematics.md#lagrange-form-splines). The paper
//! treats graphs `y(x)`; here every coordinate of a parametric curve is one
//! such graph over a global parameter `x` (given, or chord length).
//!
//! # The segment
//! A segment of degree `n` (3, 4 or 5) spans `[x_i, x_(i+1)]`,
//! `h_i = x_(i+1) - x_i`, `u = (x - x_i) / h_i`, and is the Lagrange
//! interpolant of `n + 1` points `y_0 .. y_n` on the curve at `u = j / n`:
//! `y_0` and `y_n` are the nodes, `y_1 .. y_(n-1)` the *inner points*. For the
//! cubic of the paper, the end derivatives are
//!
//! ```text
//! dy/du(0) = -5.5 y0 + 9 y1 - 4.5 y2 +     y3
//! dy/du(1) =     -y0 + 4.5 y1 - 9 y2 + 5.5 y3
//! ```
//!
//! and in general `d^m y/du^m (0) = sum_j L_j^(m)(0) y_j` with the Lagrange
//! basis `L_j`, `L_j^(m)(1) = (-1)^m L_(n-j)^(m)(0)`. The coefficients are
//! computed from the integer polynomials `prod_(l != j) (s - l)`, `s = n u`,
//! so they are exact rationals rounded once.
//!
//! Conversion to Bezier form is exact: with the power coefficients `a_k` of
//! the segment, `b_i = sum_(k <= i) C(i, k) / C(n, k) a_k`, i.e.
//! `b = M^-1 y` with `M_ji = B_i^n(j / n)` ([`bezier_from_lagrange_points`]);
//! the way back is evaluation at `u = j / n` ([`lagrange_points_of_bezier`]).
//!
//! # The recurrence (C^k at every node, in the global parameter)
//! At the node shared by segments `i - 1` and `i`, C^k means for `m = 1..=k`
//!
//! ```text
//! (1 / h_(i-1)^m) sum_j L_j^(m)(1) y_j^(i-1) = (1 / h_i^m) sum_j L_j^(m)(0) y_j^(i)
//! ```
//!
//! The user gives every node, all `n - 1` inner points of the *starting*
//! segment, and `n - 1 - k` *free* inner points of every other segment; the
//! other `k` inner points (the *derived* ones) follow from these `k` linear
//! equations, segment after segment. For the cubic with C^1, building
//! forwards and deriving the point at `u = 1/3` ([`DerivedPoints::NextToJoin`],
//! the paper's choice and the C function `bzj_lagrange_spline`):
//!
//! ```text
//! y1^(i) = ( (h_i / h_(i-1)) (-y0 + 4.5 y1 - 9 y2 + 5.5 y3)^(i-1)
//!            + 5.5 y0^(i) + 4.5 y2^(i) - y3^(i) ) / 9
//! ```
//!
//! The mirrored variant ([`DerivedPoints::FarFromJoin`]) takes the point at
//! `u = 1/3` from the user and derives the one at `u = 2/3`:
//!
//! ```text
//! y2^(i) = ( -5.5 y0^(i) + 9 y1^(i) + y3^(i)
//!            - (h_i / h_(i-1)) (-y0 + 4.5 y1 - 9 y2 + 5.5 y3)^(i-1) ) / 4.5
//! ```
//!
//! Building backwards ([`BuildDirection::Backward`]) starts from the last
//! segment and matches, at each node, the right-hand derivatives; there
//! `NextToJoin` derives the points nearest the segment's END (for the cubic
//! the user gives `u = 1/3` and `u = 2/3` follows), which is the forward
//! scheme read in reverse.
//!
//! For degree 4 and 5 (beyond the paper, which names them as future work)
//! the same equations hold with `n + 1` points at `u = j / n`: continuity
//! `k` may be 1 ..= `n - 2`, so that every later segment keeps at least one
//! free inner point. With `NextToJoin`, building forwards, the derived points
//! are `u = 1/n .. k/n` (for degree 5 with C^2: `u = 1/5, 2/5` follow, the
//! user gives `u = 3/5, 4/5`); with `FarFromJoin` they are
//! `u = (n-k)/n .. (n-1)/n`. Building backwards the roles of the two ends
//! swap. `k = n - 1` (no free point: the spline is fixed by the first
//! segment) is refused; so is any placement whose `k x k` system is singular.
//!
//! # Error growth
//! The recurrence is linear: a change `delta` of a derived point of one
//! segment reaches the next segment multiplied by the transfer matrix of the
//! `k x k` system (times `(h_i / h_(i-1))^m` in the equation of order `m`).
//! With uniform parameters its spectral radius, per node, is:
//!
//! | degree, continuity | NextToJoin (stable choice) | FarFromJoin (mirrored) |
//! |--------------------|----------------------------|------------------------|
//! | 3, C1              | 1/2 (= 4.5 / 9)            | 2 (= 9 / 4.5)          |
//! | 4, C1              | 1/3                        | 3                      |
//! | 5, C1              | 1/4                        | 4                      |
//! | 4, C2              | 3.08                       | 27.7                   |
//! | 5, C2              | 2.39                       | 86.1                   |
//! | 5, C3              | 12.1                       | 291                    |
//!
//! (C1 factors exact: `1/(n-1)` and `n-1`; the others from the eigenvalues of
//! the transfer matrix. Of all `C(n-1, k)` choices of derived points,
//! NextToJoin has the smallest factor in every case; the other choices are
//! not offered.) So only C^1 built the stable way damps errors. **Every C^2
//! and C^3 recurrence amplifies them**, like the classical C^2 cubic spline
//! marched from one end: such a spline has no local construction that is
//! stable, and these modes are for short chains, as is the mirrored variant.
//!
//! How far a change travels over 20 uniform nodes, measured, is in
//! `docs/accuracy.md` (Lagrange spline).
//!
//! The construction estimates the rounding error this carries and refuses
//! a result whose estimate exceeds the requested accuracy as
//! [`BezjoinError::IllConditioned`]: with the default accuracy 1e-9 and
//! uniform parameters the longest accepted chains are 21 segments for the
//! mirrored cubic, 12 for degree 4 with C^2, 15 for degree 5 with C^2 and 6
//! for degree 5 with C^3 (test `longest_accepted_chains_match_the_documentation`);
//! C^1 built the stable way is accepted at any length.
//!
//! # Guarantees and checks
//! [`lagrange_spline`] verifies its own result: every node and every given
//! inner point lies on its Bezier segment, and the derivative jumps at every
//! node (orders `1..=k`, global parameter) are at most `accuracy` relative to
//! the derivative sizes; it also estimates the rounding error carried by the
//! recurrence, `eps * (1 + sum_s G_s)` with `G_s` the factor by which a change
//! of the starting segment reaches segment `s` ([`LagrangeSpline::error_growth`]).
//! Any of these above `accuracy` ([`DEFAULT_LAGRANGE_ACCURACY`] by default)
//! is `IllConditioned`, never a silent answer.

mod basis;
mod recurrence;
mod spline;

use crate::error::{BezjoinError, Result};

pub use basis::{bezier_from_lagrange_points, lagrange_points_of_bezier};
pub use spline::{LagrangeSpline, chord_length_params, lagrange_spline};

/// Default relative accuracy promised by [`lagrange_spline`]: the limit for
/// the continuity residuals and the recurrence's rounding-error estimate.
pub const DEFAULT_LAGRANGE_ACCURACY: f64 = 1e-9;

/// Which end the recurrence starts from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BuildDirection {
    /// Start with segment 0 (all its inner points given), go to the last.
    #[default]
    Forward,
    /// Start with the last segment (all its inner points given), go to the first.
    Backward,
}

/// Which inner points of each later segment follow from continuity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DerivedPoints {
    /// The `k` inner points nearest the node shared with the segment built
    /// before (for the cubic built forwards: `u = 1/3`). Errors decay
    /// (factor 1/2 per node for the cubic): the stable choice.
    #[default]
    NextToJoin,
    /// The `k` inner points farthest from that node (for the cubic built
    /// forwards: `u = 2/3`, the user gives `u = 1/3`). Errors grow (factor 2
    /// per node for the cubic, much more for higher degree): short chains only.
    FarFromJoin,
}

/// How to build a Lagrange-form spline; `Default` is the paper's cubic C^1
/// forward construction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LagrangeOptions {
    /// Degree of every segment: 3, 4 or 5.
    pub degree: usize,
    /// Continuity order at every node, `1 ..= degree - 2`.
    pub continuity: usize,
    /// Which end the recurrence starts from.
    pub direction: BuildDirection,
    /// Which inner points follow from continuity.
    pub derived: DerivedPoints,
    /// Relative accuracy the result must meet (see the module doc).
    pub accuracy: f64,
}

impl Default for LagrangeOptions {
    fn default() -> Self {
        Self {
            degree: 3,
            continuity: 1,
            direction: BuildDirection::Forward,
            derived: DerivedPoints::NextToJoin,
            accuracy: DEFAULT_LAGRANGE_ACCURACY,
        }
    }
}

impl LagrangeOptions {
    /// Segments of degree `degree` (3, 4 or 5).
    pub fn with_degree(mut self, degree: usize) -> Self {
        self.degree = degree;
        self
    }
    /// C^`continuity` at every node.
    pub fn with_continuity(mut self, continuity: usize) -> Self {
        self.continuity = continuity;
        self
    }
    /// Build from the given end.
    pub fn with_direction(mut self, direction: BuildDirection) -> Self {
        self.direction = direction;
        self
    }
    /// Choose which inner points are derived.
    pub fn with_derived(mut self, derived: DerivedPoints) -> Self {
        self.derived = derived;
        self
    }
    /// Relative accuracy to meet.
    pub fn with_accuracy(mut self, accuracy: f64) -> Self {
        self.accuracy = accuracy;
        self
    }

    /// Number of free inner points the user gives for every segment other
    /// than the starting one: `degree - 1 - continuity`.
    pub fn free_points_per_segment(&self) -> usize {
        self.degree - 1 - self.continuity
    }

    /// Inner-point indices (`j` of `u = j / n`) of a later segment that are
    /// derived from continuity, increasing.
    pub fn derived_indices(&self) -> Vec<usize> {
        let (n, k) = (self.degree, self.continuity);
        let near_start = matches!(
            (self.direction, self.derived),
            (BuildDirection::Forward, DerivedPoints::NextToJoin)
                | (BuildDirection::Backward, DerivedPoints::FarFromJoin)
        );
        if near_start {
            (1..=k).collect()
        } else {
            (n - k..n).collect()
        }
    }

    /// Inner-point indices of a later segment the user gives, increasing.
    pub fn free_indices(&self) -> Vec<usize> {
        let derived = self.derived_indices();
        (1..self.degree).filter(|j| !derived.contains(j)).collect()
    }

    /// Check degree (3..=5), continuity (1..=degree-2) and accuracy (> 0).
    pub fn validate(&self) -> Result<()> {
        if !(3..=5).contains(&self.degree) {
            return Err(BezjoinError::invalid(
                "degree",
                format!("{} is not one of 3, 4, 5", self.degree),
            ));
        }
        if self.continuity == 0 || self.continuity + 2 > self.degree {
            return Err(BezjoinError::invalid(
                "continuity",
                format!(
                    "C{} is not achievable with degree {} segments: continuity must be 1 ..= {} \
                     (degree - 2) so that every later segment keeps a free inner point",
                    self.continuity,
                    self.degree,
                    self.degree - 2
                ),
            ));
        }
        if !(self.accuracy.is_finite() && self.accuracy > 0.0) {
            return Err(BezjoinError::out_of_range("accuracy", self.accuracy, "> 0"));
        }
        Ok(())
    }
}

#[cfg(test)]
mod options_tests {
    use super::*;

    #[test]
    fn derived_indices_cover_the_four_placements() {
        let o = LagrangeOptions::default().with_degree(5).with_continuity(2);
        assert_eq!(o.derived_indices(), vec![1, 2]);
        assert_eq!(o.free_indices(), vec![3, 4]);
        let m = o.with_derived(DerivedPoints::FarFromJoin);
        assert_eq!(m.derived_indices(), vec![3, 4]);
        let b = o.with_direction(BuildDirection::Backward);
        assert_eq!(b.derived_indices(), vec![3, 4]);
        assert_eq!(
            b.with_derived(DerivedPoints::FarFromJoin).derived_indices(),
            vec![1, 2]
        );
    }
}
