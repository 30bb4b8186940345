//! The spline: building it node by node, checking it, and its B-spline form.

use crate::bezier::{BezierCurve, blossom, distance, norm};
use crate::error::{BezjoinError, Result, check_finite};
use crate::nurbs::BSplineCurve;

use super::basis::LagrangeBasis;
use super::recurrence::Recurrence;
use super::{BuildDirection, LagrangeOptions};

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
        let mut work = Vec::new();
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
                let args = window.iter().map(|&t| (t - x0) / (x1 - x0));
                points.extend_from_slice(blossom(piece.points(), d, args, &mut work));
            }
        }
        let spline = BSplineCurve::new(d, n, points, None, knots)?;
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
                worst = worst.max(distance(&value, &self.on_curve[s][j * d..(j + 1) * d]));
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
/// # use bezjoin_core::{lagrange_spline, LagrangeOptions};
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

/// The largest coordinate difference between the control points of two
/// adjacent segments and the node they share (`left`'s last point).
fn extent(left: &BezierCurve, right: &BezierCurve) -> f64 {
    let d = left.dim();
    let points = left.points();
    let node = &points[points.len() - d..];
    points
        .chunks_exact(d)
        .chain(right.points().chunks_exact(d))
        .flat_map(|point| point.iter().zip(node).map(|(x, y)| (x - y).abs()))
        .fold(0.0, f64::max)
}

/// The construction's self-check: on-curve points on their Bezier segments
/// and derivative jumps at the nodes; returns the largest continuity residual.
pub(super) fn check_spline(spline: &LagrangeSpline, accuracy: f64) -> Result<f64> {
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
        // The pieces' extent around their shared node, not their distance from
        // the origin: the floor of a derivative's size must not grow when the
        // spline is moved (user testing, session 40: an arc of radius 1e-3
        // moved to 1e6 had C1 jumps of 7.7e-5 of its derivatives, accepted
        // against a floor of the coordinates).
        let local_scale = extent(left, right);
        for m in 1..=k {
            let row = m * d..(m + 1) * d;
            let a: Vec<f64> = l[row.clone()]
                .iter()
                .map(|v| v / hl.powi(m as i32))
                .collect();
            let b: Vec<f64> = r[row].iter().map(|v| v / hr.powi(m as i32)).collect();
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
