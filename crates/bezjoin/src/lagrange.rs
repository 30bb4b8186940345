//! Splines whose defining points lie ON the curve: polynomial segments in
//! Lagrange form, joined with C^1 (or C^2, C^3) continuity by a local
//! recurrence, returned as exact Bezier pieces or one B-spline.
//!
//! After A.M. Kovtun, *"Spline of third degree with control points incident
//! to the curve"* (seed 004, restated in mathematics.md, section 4). The paper
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
//! # Error growth (measured)
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
//! Measured over 20 uniform nodes: a unit change of one inner point of the
//! first segment changes the derived points of the last segment (18 steps
//! later) by at most, building forwards (test
//! `perturbation_growth_over_twenty_nodes` in `tests/lagrange.rs` asserts
//! these to 1 %):
//!
//! | degree, continuity | NextToJoin | FarFromJoin |
//! |--------------------|------------|-------------|
//! | 3, C1              | 7.63e-6 (= 2^-17) | 2.62e5 (= 2^18) |
//! | 4, C1              | 7.74e-9    | 3.87e8      |
//! | 5, C1              | 5.82e-11   | 6.87e10     |
//! | 4, C2              | 1.11e9     | 1.58e26     |
//! | 5, C2              | 1.93e7     | 1.41e35     |
//! | 5, C3              | 1.12e20    | 7.85e44     |
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

use nalgebra::DMatrix;

use crate::basis::binomial;
use crate::bezier::{BezierCurve, distance, norm};
use crate::bspline::BSplineCurve;
use crate::error::{BezjoinError, Result, check_finite};

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

/// The Lagrange basis of degree `n` on `u = j / n`: derivatives at `u = 0`
/// and `u = 1`, and the exact map to Bezier control points.
struct LagrangeBasis {
    degree: usize,
    /// `at_start[m][j] = L_j^(m)(0)`.
    at_start: Vec<Vec<f64>>,
    /// `at_end[m][j] = L_j^(m)(1)`.
    at_end: Vec<Vec<f64>>,
    /// `to_bezier[(i, j)]`: weight of `y_j` in Bezier point `b_i`.
    to_bezier: DMatrix<f64>,
}

impl LagrangeBasis {
    fn new(n: usize) -> Self {
        // power coefficients in u of every L_j: power[j][k]
        let mut power = vec![vec![0.0; n + 1]; n + 1];
        for (j, row) in power.iter_mut().enumerate() {
            // integer polynomial prod_(l != j) (s - l), lowest power first
            let mut poly = vec![1.0f64];
            let mut denominator = 1.0f64;
            for l in 0..=n {
                if l == j {
                    continue;
                }
                let mut next = vec![0.0; poly.len() + 1];
                for (p, &c) in poly.iter().enumerate() {
                    next[p + 1] += c;
                    next[p] -= c * l as f64;
                }
                poly = next;
                denominator *= j as f64 - l as f64;
            }
            for (k, value) in row.iter_mut().enumerate() {
                *value = poly[k] * (n as f64).powi(k as i32) / denominator;
            }
        }
        let factorial = |m: usize| (1..=m).map(|v| v as f64).product::<f64>();
        let at_start: Vec<Vec<f64>> = (0..=n)
            .map(|m| (0..=n).map(|j| factorial(m) * power[j][m]).collect())
            .collect();
        let at_end: Vec<Vec<f64>> = (0..=n)
            .map(|m| {
                let sign = if m % 2 == 0 { 1.0 } else { -1.0 };
                (0..=n).map(|j| sign * at_start[m][n - j]).collect()
            })
            .collect();
        let mut to_bezier = DMatrix::zeros(n + 1, n + 1);
        for i in 0..=n {
            for j in 0..=n {
                to_bezier[(i, j)] = (0..=i)
                    .map(|k| binomial(i, k) / binomial(n, k) * power[j][k])
                    .sum();
            }
        }
        Self {
            degree: n,
            at_start,
            at_end,
            to_bezier,
        }
    }

    fn bezier_points(&self, dim: usize, on_curve: &[f64]) -> Vec<f64> {
        let n = self.degree;
        let mut out = vec![0.0; (n + 1) * dim];
        for i in 0..=n {
            for j in 0..=n {
                let w = self.to_bezier[(i, j)];
                for c in 0..dim {
                    out[i * dim + c] += w * on_curve[j * dim + c];
                }
            }
        }
        // the end points are the nodes themselves: keep them bit-exact so
        // consecutive segments share their join exactly
        out[..dim].copy_from_slice(&on_curve[..dim]);
        out[n * dim..].copy_from_slice(&on_curve[n * dim..]);
        out
    }
}

/// The exact Bezier form of the degree-`n` polynomial through the `n + 1`
/// points `on_curve` (row-major, `dim` each) at `u = j / n`, `n >= 1`.
///
/// Errors: `dim == 0`, fewer than 2 points or a length that is not a
/// multiple of `dim` (InvalidArgument), NaN/infinity (NonFinite).
pub fn bezier_from_lagrange_points(dim: usize, on_curve: &[f64]) -> Result<BezierCurve> {
    if dim == 0 {
        return Err(BezjoinError::invalid("dim", "must be at least 1"));
    }
    if on_curve.len() % dim != 0 || on_curve.len() < 2 * dim {
        return Err(BezjoinError::invalid(
            "on_curve",
            format!(
                "{} values do not make at least 2 points of dimension {dim}",
                on_curve.len()
            ),
        ));
    }
    check_finite("on_curve", on_curve)?;
    let n = on_curve.len() / dim - 1;
    let basis = LagrangeBasis::new(n);
    BezierCurve::new(dim, n, basis.bezier_points(dim, on_curve))
}

/// The `n + 1` points of `curve` at `u = j / n` (row-major): its Lagrange
/// form, the inverse of [`bezier_from_lagrange_points`].
pub fn lagrange_points_of_bezier(curve: &BezierCurve) -> Vec<f64> {
    let n = curve.degree();
    let dim = curve.dim();
    let mut out = vec![0.0; (n + 1) * dim];
    for j in 0..=n {
        let u = if n == 0 { 0.0 } else { j as f64 / n as f64 };
        curve.eval_into(u, &mut out[j * dim..(j + 1) * dim]);
    }
    out
}

/// Global parameters: checked `params`, or chord length from 0.
pub fn chord_length_params(dim: usize, nodes: &[f64]) -> Result<Vec<f64>> {
    let count = nodes.len() / dim.max(1);
    let mut x = vec![0.0; count];
    for i in 1..count {
        let chord = distance(
            &nodes[(i - 1) * dim..i * dim],
            &nodes[i * dim..(i + 1) * dim],
        );
        if chord == 0.0 {
            return Err(BezjoinError::invalid(
                "nodes",
                format!(
                    "nodes {} and {i} coincide; chord-length parameters need distinct \
                     consecutive nodes (give params instead)",
                    i - 1
                ),
            ));
        }
        x[i] = x[i - 1] + chord;
    }
    if !x.last().copied().unwrap_or(0.0).is_finite() {
        return Err(BezjoinError::invalid("nodes", "the chord length overflows"));
    }
    Ok(x)
}

/// A spline of Lagrange-form segments: the on-curve points, their exact
/// Bezier pieces and the construction's own error report.
#[derive(Debug, Clone, PartialEq)]
pub struct LagrangeSpline {
    dim: usize,
    degree: usize,
    continuity: usize,
    accuracy: f64,
    params: Vec<f64>,
    on_curve: Vec<Vec<f64>>,
    segments: Vec<BezierCurve>,
    error_growth: f64,
    error_estimate: f64,
    continuity_residual: f64,
}

impl LagrangeSpline {
    /// Dimension.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Degree of every segment.
    pub fn degree(&self) -> usize {
        self.degree
    }
    /// Continuity order at every node.
    pub fn continuity(&self) -> usize {
        self.continuity
    }
    /// Global parameters of the nodes, strictly increasing.
    pub fn params(&self) -> &[f64] {
        &self.params
    }
    /// `h_i = x_(i+1) - x_i` of every segment.
    pub fn intervals(&self) -> Vec<f64> {
        self.params.windows(2).map(|w| w[1] - w[0]).collect()
    }
    /// Number of segments (`node_count - 1`).
    pub fn segment_count(&self) -> usize {
        self.segments.len()
    }
    /// The `degree + 1` points (row-major) of segment `i` at `u = j / n`,
    /// given and derived alike.
    pub fn on_curve_points(&self, i: usize) -> &[f64] {
        &self.on_curve[i]
    }
    /// The Bezier pieces, segment `i` over local `u in [0, 1]`.
    pub fn segments(&self) -> &[BezierCurve] {
        &self.segments
    }
    /// The Bezier pieces, by value.
    pub fn into_segments(self) -> Vec<BezierCurve> {
        self.segments
    }
    /// Largest factor by which a change of the starting segment's inner
    /// points reaches the derived points of any later segment (infinity-norm
    /// of the linear map); 0 for a single segment.
    pub fn error_growth(&self) -> f64 {
        self.error_growth
    }
    /// Estimated relative rounding error of the derived points,
    /// `eps * (1 + sum over segments of the growth factor)`.
    pub fn relative_error_estimate(&self) -> f64 {
        self.error_estimate
    }
    /// Largest relative derivative jump (orders `1..=continuity`, global
    /// parameter) over all nodes, as checked by the construction.
    pub fn max_continuity_residual(&self) -> f64 {
        self.continuity_residual
    }

    /// The inputs (`start_inner`, `free_inner`) that rebuild this spline with
    /// `options` (degree and continuity must be this spline's): the starting
    /// segment's inner points and, for every other segment in increasing
    /// order, its free inner points. Used to check that forward, backward and
    /// mirrored constructions describe the same splines.
    pub fn construction_data(&self, options: &LagrangeOptions) -> Result<(Vec<f64>, Vec<f64>)> {
        options.validate()?;
        if options.degree != self.degree || options.continuity > self.continuity {
            return Err(BezjoinError::invalid(
                "options",
                format!(
                    "degree {} / C{} cannot describe a degree {} C{} spline",
                    options.degree, options.continuity, self.degree, self.continuity
                ),
            ));
        }
        let d = self.dim;
        let n = self.degree;
        let start = match options.direction {
            BuildDirection::Forward => 0,
            BuildDirection::Backward => self.segments.len() - 1,
        };
        let start_inner = self.on_curve[start][d..n * d].to_vec();
        let free = options.free_indices();
        let mut free_inner = Vec::new();
        for (s, points) in self.on_curve.iter().enumerate() {
            if s == start {
                continue;
            }
            for &j in &free {
                free_inner.extend_from_slice(&points[j * d..(j + 1) * d]);
            }
        }
        Ok((start_inner, free_inner))
    }

    /// The spline as one clamped B-spline of degree `n` over the global
    /// parameters, every interior knot of multiplicity `n - k` (for the
    /// cubic C^1: 2). Built directly: a control point whose knot window lies
    /// inside one segment is that segment's Bezier point; the `k` points
    /// around each node that the higher continuity makes redundant are
    /// dropped (for C^1 the node itself, which lies on the segment between
    /// its neighbours in the ratio `h_(i-1) : h_i`), and for `k >= 2` the
    /// `k - 1` new points are blossom values of the adjacent segment.
    ///
    /// Checked: the B-spline passes through every on-curve point of every
    /// segment, which makes each of its pieces the segment's polynomial
    /// (degree `n` through `n + 1` points); a miss beyond the spline's
    /// accuracy is IllConditioned. Distinct knots and multiplicities, as
    /// OpenCASCADE takes them: [`BSplineCurve::knots_with_multiplicities`].
    pub fn to_bspline(&self) -> Result<BSplineCurve> {
        let n = self.degree;
        let k = self.continuity;
        let d = self.dim;
        let count = self.params.len();
        let mut knots = vec![self.params[0]; n + 1];
        for &x in &self.params[1..count - 1] {
            knots.extend(std::iter::repeat_n(x, n - k));
        }
        knots.extend(std::iter::repeat_n(self.params[count - 1], n + 1));
        let point_count = knots.len() - n - 1;
        let mut points = Vec::with_capacity(point_count * d);
        for j in 0..point_count {
            let window = &knots[j + 1..=j + n];
            // a non-empty span [knots[r], knots[r+1]] with j <= r <= j + n,
            // preferably one whose closed interval holds the whole window
            let spans: Vec<usize> = (j.max(n)..=(j + n).min(knots.len() - n - 2))
                .filter(|&r| knots[r] < knots[r + 1])
                .collect();
            let r = spans
                .iter()
                .copied()
                .find(|&r| window.iter().all(|&t| t == knots[r] || t == knots[r + 1]))
                .unwrap_or(spans[0]);
            let s = self.params.partition_point(|&x| x <= knots[r]) - 1;
            let (x0, x1) = (self.params[s], self.params[s + 1]);
            let piece = &self.segments[s];
            if window.iter().all(|&t| t == x0 || t == x1) {
                let index = window.iter().filter(|&&t| t == x1).count();
                points.extend_from_slice(piece.point(index));
            } else {
                let args: Vec<f64> = window.iter().map(|&t| (t - x0) / (x1 - x0)).collect();
                points.extend(blossom(piece, &args));
            }
        }
        let spline = BSplineCurve::new(d, n, knots, points)?;
        // self-check: the B-spline interpolates every on-curve point
        let scale = self.coordinate_scale();
        let mut worst = 0.0f64;
        for s in 0..self.segments.len() {
            let (x0, x1) = (self.params[s], self.params[s + 1]);
            for j in 0..=n {
                let x = x0 + (x1 - x0) * j as f64 / n as f64;
                let side = if j == n {
                    crate::basis::KnotSide::Left
                } else {
                    crate::basis::KnotSide::Right
                };
                let value = spline.eval_derivatives_side(x, 0, side);
                let row: Vec<f64> = value.row(0).iter().copied().collect();
                worst = worst.max(distance(&row, &self.on_curve[s][j * d..(j + 1) * d]));
            }
        }
        let relative = worst / scale;
        if relative > self.accuracy {
            return Err(BezjoinError::IllConditioned {
                what: "Lagrange spline as one B-spline (interpolation of its on-curve points)"
                    .into(),
                estimate: relative,
                limit: self.accuracy,
            });
        }
        Ok(spline)
    }

    fn coordinate_scale(&self) -> f64 {
        self.segments
            .iter()
            .map(BezierCurve::coordinate_scale)
            .fold(f64::MIN_POSITIVE, f64::max)
    }
}

/// The blossom (polar form) of `curve` at `args` (`degree` values): de
/// Casteljau with a different parameter at every level.
fn blossom(curve: &BezierCurve, args: &[f64]) -> Vec<f64> {
    let n = curve.degree();
    let d = curve.dim();
    let mut work = curve.points().to_vec();
    for (level, &t) in args.iter().enumerate() {
        for i in 0..n - level {
            for c in 0..d {
                work[i * d + c] = (1.0 - t) * work[i * d + c] + t * work[(i + 1) * d + c];
            }
        }
    }
    work[..d].to_vec()
}

/// The recurrence's fixed data: build order, derived/free indices and the
/// inverse of its `k x k` system.
struct Recurrence<'a> {
    basis: &'a LagrangeBasis,
    continuity: usize,
    forward: bool,
    derived: Vec<usize>,
    inverse: DMatrix<f64>,
}

impl<'a> Recurrence<'a> {
    fn new(basis: &'a LagrangeBasis, options: &LagrangeOptions) -> Result<Self> {
        let k = options.continuity;
        let forward = options.direction == BuildDirection::Forward;
        let derived = options.derived_indices();
        let own = if forward {
            &basis.at_start
        } else {
            &basis.at_end
        };
        let system = DMatrix::from_fn(k, k, |m, q| own[m + 1][derived[q]]);
        let inverse = system.clone().try_inverse().ok_or_else(|| {
            BezjoinError::invalid(
                "continuity",
                format!(
                    "C{k} cannot be reached by deriving inner points {derived:?} of degree {} \
                     segments (singular system)",
                    options.degree
                ),
            )
        })?;
        let condition =
            crate::linalg::norm_1(&system) * crate::linalg::norm_1(&inverse) * f64::EPSILON;
        if condition > 1e-8 {
            return Err(BezjoinError::invalid(
                "continuity",
                format!(
                    "C{k} by deriving inner points {derived:?} of degree {} segments is nearly \
                     singular (relative condition {condition:e})",
                    options.degree
                ),
            ));
        }
        Ok(Self {
            basis,
            continuity: k,
            forward,
            derived,
            inverse,
        })
    }

    /// Segment indices in build order.
    fn order(&self, segment_count: usize) -> Vec<usize> {
        if self.forward {
            (0..segment_count).collect()
        } else {
            (0..segment_count).rev().collect()
        }
    }

    /// Fill in the derived points of every segment after the first in build
    /// order; `on_curve[s]` holds `(n + 1) * dim` values with the nodes, the
    /// starting segment's inner points and the free points already set.
    fn fill_derived(&self, dim: usize, intervals: &[f64], on_curve: &mut [Vec<f64>]) {
        let k = self.continuity;
        let (own, neighbour) = if self.forward {
            (&self.basis.at_start, &self.basis.at_end)
        } else {
            (&self.basis.at_end, &self.basis.at_start)
        };
        let order = self.order(on_curve.len());
        let n = self.basis.degree;
        let mut rhs = DMatrix::zeros(k, 1);
        for pair in order.windows(2) {
            let (p, s) = (pair[0], pair[1]);
            let ratio = intervals[s] / intervals[p];
            for c in 0..dim {
                for m in 1..=k {
                    let neighbour_derivative: f64 = (0..=n)
                        .map(|j| neighbour[m][j] * on_curve[p][j * dim + c])
                        .sum();
                    let known: f64 = (0..=n)
                        .filter(|j| !self.derived.contains(j))
                        .map(|j| own[m][j] * on_curve[s][j * dim + c])
                        .sum();
                    rhs[(m - 1, 0)] = neighbour_derivative * ratio.powi(m as i32) - known;
                }
                let solution = &self.inverse * &rhs;
                for (q, &j) in self.derived.iter().enumerate() {
                    on_curve[s][j * dim + c] = solution[(q, 0)];
                }
            }
        }
    }

    /// Growth factor per segment: infinity-norm of the map from the starting
    /// segment's inner points to the segment's derived points.
    fn growth(&self, intervals: &[f64]) -> Vec<f64> {
        let n = self.basis.degree;
        let count = intervals.len();
        let start = self.order(count)[0];
        let mut row_sums = vec![vec![0.0; self.derived.len()]; count];
        for unit in 1..n {
            let mut data = vec![vec![0.0; n + 1]; count];
            data[start][unit] = 1.0;
            self.fill_derived(1, intervals, &mut data);
            for s in 0..count {
                if s == start {
                    continue;
                }
                for (q, &j) in self.derived.iter().enumerate() {
                    row_sums[s][q] += data[s][j].abs();
                }
            }
        }
        row_sums
            .iter()
            .map(|r| r.iter().copied().fold(0.0, f64::max))
            .collect()
    }
}

/// Build a spline of Lagrange-form segments through `nodes`.
///
/// * `nodes`: `node_count * dim` row-major values, `node_count >= 2`;
/// * `params`: `node_count` strictly increasing global parameters, or `None`
///   for chord length (then consecutive nodes must differ);
/// * `start_inner`: the `degree - 1` inner points (`u = 1/n .. (n-1)/n`) of
///   the starting segment (segment 0 forwards, the last one backwards),
///   `(degree - 1) * dim` values;
/// * `free_inner`: for every other segment in increasing segment order its
///   `degree - 1 - continuity` free inner points in increasing `u`
///   ([`LagrangeOptions::free_indices`]), `(node_count - 2) *
///   (degree - 1 - continuity) * dim` values.
///
/// The defaults of [`LagrangeOptions`] are the paper's construction: cubic,
/// C^1, forwards, `free_inner` = the `u = 2/3` point of every later segment.
///
/// Errors: `dim == 0`, fewer than 2 nodes, `nodes` not a multiple of `dim`,
/// degree not 3..=5, continuity not in `1..=degree-2`, coincident
/// consecutive nodes with chord length (InvalidArgument); `params` not
/// strictly increasing (ParameterOutOfRange naming the entry); wrong array
/// lengths (LengthMismatch); NaN/infinity (NonFinite); a result that fails
/// its own checks (IllConditioned, see the module doc).
///
/// ```
/// # use bezjoin_core::lagrange::{lagrange_spline, LagrangeOptions};
/// // three nodes of the unit parabola y = x^2 with uniform parameters
/// let nodes = [0.0, 0.0, 1.0, 1.0, 2.0, 4.0];
/// let start = [1.0 / 3.0, 1.0 / 9.0, 2.0 / 3.0, 4.0 / 9.0];
/// let free = [5.0 / 3.0, 25.0 / 9.0]; // u = 2/3 of the second segment
/// let spline = lagrange_spline(2, &nodes, Some(&[0.0, 1.0, 2.0]), &start, &free,
///                              &LagrangeOptions::default()).unwrap();
/// // the derived point u = 1/3 of segment 1 is on the parabola too
/// let p = &spline.on_curve_points(1)[2..4];
/// assert!((p[0] - 4.0 / 3.0).abs() < 1e-14 && (p[1] - 16.0 / 9.0).abs() < 1e-14);
/// ```
pub fn lagrange_spline(
    dim: usize,
    nodes: &[f64],
    params: Option<&[f64]>,
    start_inner: &[f64],
    free_inner: &[f64],
    options: &LagrangeOptions,
) -> Result<LagrangeSpline> {
    options.validate()?;
    if dim == 0 {
        return Err(BezjoinError::invalid("dim", "must be at least 1"));
    }
    if nodes.len() % dim != 0 {
        return Err(BezjoinError::invalid(
            "nodes",
            format!(
                "{} values are not a whole number of points of dimension {dim}",
                nodes.len()
            ),
        ));
    }
    let count = nodes.len() / dim;
    if count < 2 {
        return Err(BezjoinError::invalid(
            "nodes",
            format!("at least 2 nodes are needed, got {count}"),
        ));
    }
    check_finite("nodes", nodes)?;
    let n = options.degree;
    let k = options.continuity;
    let expected_start = (n - 1) * dim;
    if start_inner.len() != expected_start {
        return Err(BezjoinError::LengthMismatch {
            name: "start_inner".into(),
            expected: expected_start,
            actual: start_inner.len(),
        });
    }
    let expected_free = (count - 2) * (n - 1 - k) * dim;
    if free_inner.len() != expected_free {
        return Err(BezjoinError::LengthMismatch {
            name: "free_inner".into(),
            expected: expected_free,
            actual: free_inner.len(),
        });
    }
    check_finite("start_inner", start_inner)?;
    check_finite("free_inner", free_inner)?;
    let x = match params {
        Some(p) => {
            if p.len() != count {
                return Err(BezjoinError::LengthMismatch {
                    name: "params".into(),
                    expected: count,
                    actual: p.len(),
                });
            }
            check_finite("params", p)?;
            if let Some(i) = p.windows(2).position(|w| w[1] <= w[0]) {
                return Err(BezjoinError::out_of_range(
                    format!("params[{}]", i + 1),
                    p[i + 1],
                    format!(
                        "(params[{i}], inf) = ({}, inf): the parameters must increase strictly",
                        p[i]
                    ),
                ));
            }
            p.to_vec()
        }
        None => chord_length_params(dim, nodes)?,
    };
    let intervals: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    if let Some(i) = intervals.iter().position(|h| !(h.is_finite() && *h > 0.0)) {
        return Err(BezjoinError::invalid(
            "params",
            format!(
                "interval {i} = {} is not a positive finite length",
                intervals[i]
            ),
        ));
    }

    let basis = LagrangeBasis::new(n);
    let recurrence = Recurrence::new(&basis, options)?;
    let segment_count = count - 1;
    let start = recurrence.order(segment_count)[0];
    let free = options.free_indices();
    let free_per_segment = free.len() * dim;
    let mut on_curve = vec![vec![0.0; (n + 1) * dim]; segment_count];
    let mut free_cursor = 0;
    for (s, points) in on_curve.iter_mut().enumerate() {
        points[..dim].copy_from_slice(&nodes[s * dim..(s + 1) * dim]);
        points[n * dim..].copy_from_slice(&nodes[(s + 1) * dim..(s + 2) * dim]);
        if s == start {
            points[dim..n * dim].copy_from_slice(start_inner);
        } else {
            let given = &free_inner[free_cursor..free_cursor + free_per_segment];
            for (q, &j) in free.iter().enumerate() {
                points[j * dim..(j + 1) * dim].copy_from_slice(&given[q * dim..(q + 1) * dim]);
            }
            free_cursor += free_per_segment;
        }
    }
    recurrence.fill_derived(dim, &intervals, &mut on_curve);

    let growth = recurrence.growth(&intervals);
    let error_growth = growth.iter().copied().fold(0.0, f64::max);
    let error_estimate = f64::EPSILON * (1.0 + growth.iter().sum::<f64>());
    if !error_estimate.is_finite() || error_estimate > options.accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "Lagrange spline recurrence over {segment_count} segments (growth factor \
                 {error_growth:e})"
            ),
            estimate: error_estimate,
            limit: options.accuracy,
        });
    }
    if let Some((s, _)) = on_curve
        .iter()
        .enumerate()
        .find(|(_, p)| p.iter().any(|v| !v.is_finite()))
    {
        return Err(BezjoinError::IllConditioned {
            what: format!("Lagrange spline recurrence: segment {s} overflows"),
            estimate: f64::INFINITY,
            limit: options.accuracy,
        });
    }

    let segments: Vec<BezierCurve> = on_curve
        .iter()
        .map(|points| BezierCurve::new(dim, n, basis.bezier_points(dim, points)))
        .collect::<Result<_>>()?;

    let mut spline = LagrangeSpline {
        dim,
        degree: n,
        continuity: k,
        accuracy: options.accuracy,
        params: x,
        on_curve,
        segments,
        error_growth,
        error_estimate,
        continuity_residual: 0.0,
    };
    spline.continuity_residual = check_spline(&spline, options.accuracy)?;
    Ok(spline)
}

/// The construction's self-check: on-curve points on their Bezier segments
/// and derivative jumps at the nodes; returns the largest continuity residual.
fn check_spline(spline: &LagrangeSpline, accuracy: f64) -> Result<f64> {
    let d = spline.dim;
    let n = spline.degree;
    let k = spline.continuity;
    let scale = spline.coordinate_scale();
    let mut worst_point = 0.0f64;
    let mut value = vec![0.0; d];
    for (s, piece) in spline.segments.iter().enumerate() {
        for j in 0..=n {
            piece.eval_into(j as f64 / n as f64, &mut value);
            worst_point =
                worst_point.max(distance(&value, &spline.on_curve[s][j * d..(j + 1) * d]));
        }
    }
    if worst_point / scale > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: "Lagrange spline: on-curve points off their Bezier segments".into(),
            estimate: worst_point / scale,
            limit: accuracy,
        });
    }
    let intervals = spline.intervals();
    let mut worst_jump = 0.0f64;
    for s in 1..spline.segments.len() {
        let (left, right) = (&spline.segments[s - 1], &spline.segments[s]);
        let (hl, hr) = (intervals[s - 1], intervals[s]);
        let l = left.eval_derivatives(1.0, k);
        let r = right.eval_derivatives(0.0, k);
        let local_scale = left.coordinate_scale().max(right.coordinate_scale());
        for m in 1..=k {
            let a: Vec<f64> = l.row(m).iter().map(|v| v / hl.powi(m as i32)).collect();
            let b: Vec<f64> = r.row(m).iter().map(|v| v / hr.powi(m as i32)).collect();
            // the size a derivative of this order can have on these pieces
            let falling: f64 = (n - m + 1..=n).map(|v| v as f64).product();
            let size = norm(&a)
                .max(norm(&b))
                .max(falling * local_scale / hl.max(hr).powi(m as i32));
            worst_jump = worst_jump.max(distance(&a, &b) / size);
        }
    }
    if worst_jump > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!("Lagrange spline: C{k} residual at the nodes"),
            estimate: worst_jump,
            limit: accuracy,
        });
    }
    Ok(worst_jump)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubic_end_derivatives_are_the_papers() {
        let b = LagrangeBasis::new(3);
        assert_eq!(b.at_start[1], vec![-5.5, 9.0, -4.5, 1.0]);
        assert_eq!(b.at_end[1], vec![-1.0, 4.5, -9.0, 5.5]);
    }

    #[test]
    fn lagrange_basis_reproduces_polynomials() {
        // y = u^n sampled at j/n: Bezier of u^n is (0, ..., 0, 1)
        for n in 1..=5 {
            let pts: Vec<f64> = (0..=n)
                .map(|j| (j as f64 / n as f64).powi(n as i32))
                .collect();
            let c = bezier_from_lagrange_points(1, &pts).unwrap();
            for i in 0..n {
                assert!(c.point(i)[0].abs() < 1e-14, "n={n} b{i}={}", c.point(i)[0]);
            }
            assert_eq!(c.point(n)[0], 1.0);
        }
    }

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
