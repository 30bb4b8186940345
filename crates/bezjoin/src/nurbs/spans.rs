//! Decomposition into Bezier spans (The NURBS Book A5.6, as repeated knot
//! insertion) and degree elevation (the spans elevated, then the knots the
//! elevated curve does not need removed, each removal checked).

use super::{NurbsCurve, unit_weights_dropped};
use crate::basis::{KnotSide, find_span};
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

/// Relative size (to the largest homogeneous coordinate) above which a
/// knot removal that should be exact is refused as ill-conditioned.
const REMOVAL_TOLERANCE: f64 = 1e-10;

impl NurbsCurve {
    /// The distinct knot values inside the open domain, with their
    /// multiplicities.
    pub fn interior_knots(&self) -> (Vec<f64>, Vec<usize>) {
        let (first, last) = self.domain();
        let (k, m) = self.knots_with_multiplicities();
        k.into_iter()
            .zip(m)
            .filter(|(u, _)| *u > first && *u < last)
            .unzip()
    }

    /// Number of non-empty knot spans in the domain.
    pub fn span_count(&self) -> usize {
        self.interior_knots().0.len() + 1
    }

    /// The curve as its Bezier spans, in order: one-span curves of the same
    /// degree on `[u_i, u_(i+1)]` (the distinct knots of the domain), with
    /// the original parameters; rational spans stay rational. Exact.
    pub fn bezier_spans(&self) -> Vec<NurbsCurve> {
        let poles = self.span_poles();
        let rational = self.weights.is_some();
        (0..poles.count())
            .map(|i| {
                let (lo, hi) = poles.domain(i);
                let rows = poles.rows(i);
                if rational {
                    let mut span =
                        NurbsCurve::from_homogeneous(self.dim, self.degree, rows, Vec::new(), true);
                    let mut k = vec![lo; self.degree + 1];
                    k.extend(std::iter::repeat_n(hi, self.degree + 1));
                    span.knots = k;
                    span.weights = unit_weights_dropped(span.weights.take());
                    span
                } else {
                    NurbsCurve::from_span_parts(self.dim, self.degree, rows.to_vec(), None, lo, hi)
                }
            })
            .collect()
    }

    /// The Bezier poles of every span in one buffer ([`SpanPoles`]): the
    /// clamped curve's homogeneous poles (`(w P, w)`; for a curve without
    /// weights its Cartesian poles) with every interior knot raised to
    /// multiplicity `p` by single insertions in increasing order (Boehm,
    /// A5.1: `Q_i = a_i R_i + (1 - a_i) R_(i-1)`), in place in one buffer
    /// reserved for the result. These are the operations of
    /// [`bezier_spans`](Self::bezier_spans) before this buffer existed
    /// (one `insert_once` per insertion on homogeneous rows), so the rows
    /// are the same bits: without weights the weight coordinate stays
    /// exactly 1 (`a + fl(1 - a) = 1` for `a` in `[0, 1]`: exact for
    /// `a >= 1/2`, else `fl(1 - a)` is within `2^-54` of `1 - a` and the
    /// sum rounds to 1), so `1 * x` and the division by it are exact and
    /// the Cartesian coordinates see the same operations.
    ///
    /// Built on first use and kept beside the curve (with the span table of
    /// the evaluation, in the curve's `SpanCache`: empty in a clone, never
    /// compared), so an intersection, the arc-length inversions and the
    /// trims of one curve decompose it once.
    pub(crate) fn span_poles(&self) -> &SpanPoles {
        self.span_cache
            .1
            .get_or_init(|| Box::new(self.build_span_poles()))
    }

    fn build_span_poles(&self) -> SpanPoles {
        let p = self.degree;
        let (first, last) = self.domain();
        let n = self.point_count();
        let clamped = self.knots[..=p].iter().all(|&k| k == first)
            && self.knots[n..].iter().all(|&k| k == last);
        // The largest absolute value of the rows before any insertion (of
        // this curve's, not the clamped copy's: clamping is insertions too).
        let scale = self.row_scale();
        if !clamped {
            let mut poles = self.clamped().build_span_poles();
            poles.scale = poles.scale.max(scale);
            // The clamping's own insertions (not tracked): the a priori
            // bound of `spans_jet_into`, `4 (p + 1)^2 u S` per coordinate.
            let q = (p + 1) as f64;
            let clamping = 4.0 * q * q * (f64::EPSILON / 2.0) * poles.scale * poles.h as f64;
            for [_, error] in &mut poles.span_sizes {
                *error += clamping;
            }
            return poles;
        }
        let rational = self.weights.is_some();
        let h = if rational { self.dim + 1 } else { self.dim };
        // Distinct interior knots and the insertions they need: those of
        // `interior_knots` (strictly inside the domain), as the old
        // `bezier_spans` took them. (Reading every run of equal knots
        // instead broke on a knot vector that steps back by an ulp next to
        // an end, which the `nurbs` fuzz target produced: more breaks than
        // rows, an out-of-range slice.)
        let (interior, multiplicities) = self.interior_knots();
        let mut breaks = Vec::with_capacity(interior.len() + 2);
        breaks.push(first);
        breaks.extend_from_slice(&interior);
        breaks.push(last);
        let insertions: usize = multiplicities.iter().map(|&m| p.saturating_sub(m)).sum();
        let count = n + insertions;
        let mut rows = Vec::with_capacity(count * h);
        if rational {
            let mut row = [0.0f64; 17];
            for i in 0..n {
                if h <= row.len() {
                    self.homogeneous_point(i, &mut row[..h]);
                    rows.extend_from_slice(&row[..h]);
                } else {
                    let mut row = vec![0.0; h];
                    self.homogeneous_point(i, &mut row);
                    rows.extend_from_slice(&row);
                }
            }
        } else {
            rows.extend_from_slice(&self.points);
        }
        // With weights, a bound per row on its rounding (1-norm): the
        // products `w_i x_i` (`u |w_i x_i|` per coordinate), then the
        // insertions' (`insert_in_place_tracked`).
        let unit = f64::EPSILON / 2.0;
        let mut row_errors: Vec<f64> = if rational {
            rows.chunks_exact(h)
                .map(|row| unit * abs_sum(&row[..h - 1]))
                .collect()
        } else {
            Vec::new()
        };
        if insertions > 0 {
            let mut knots = Vec::with_capacity(self.knots.len() + insertions);
            knots.extend_from_slice(&self.knots);
            for &u in &breaks[1..breaks.len() - 1] {
                let m = knots.iter().filter(|&&k| k == u).count();
                let times = p.saturating_sub(m);
                if rational {
                    insert_in_place_tracked(h, p, &mut knots, &mut rows, &mut row_errors, u, times);
                } else {
                    insert_in_place(h, p, &mut knots, &mut rows, u, times);
                }
            }
        }
        let beziers = if rational {
            Vec::new()
        } else {
            (0..breaks.len() - 1)
                .map(|i| {
                    BezierCurve::from_parts(
                        self.dim,
                        p,
                        rows[i * p * h..(i * p + p + 1) * h].to_vec(),
                    )
                })
                .collect()
        };
        let span_sizes = span_sizes(&rows, &row_errors, h, p);
        SpanPoles {
            breaks,
            rows,
            h,
            degree: p,
            scale,
            span_sizes,
            beziers,
            rational_cuts: std::sync::OnceLock::new(),
            homogeneous: std::sync::OnceLock::new(),
            projected: std::sync::OnceLock::new(),
        }
    }

    /// [`SpanPoles::scale`] of this curve: the largest absolute pole
    /// coordinate, with weights also `|w_i x_i|` (as rounded) and `w_i`.
    fn row_scale(&self) -> f64 {
        let largest = match &self.weights {
            None => self.points.iter().fold(0.0f64, |m, v| m.max(v.abs())),
            Some(weights) => {
                self.points
                    .chunks_exact(self.dim)
                    .zip(weights)
                    .fold(0.0f64, |m, (row, &w)| {
                        row.iter()
                            .fold(m.max(w.abs()), |m, &x| m.max((w * x).abs()))
                    })
            }
        };
        largest.max(f64::MIN_POSITIVE)
    }

    /// The Bezier curve of a clamped one-span polynomial curve, read from
    /// its poles (no knot work): the curve is this Bezier curve in the
    /// local parameter `t = (u - first) / (last - first)`. `None` for
    /// several spans, unclamped ends or unequal weights.
    pub(crate) fn one_span_bezier(&self) -> Option<BezierCurve> {
        if !self.is_bezier_span() || self.is_rational() {
            return None;
        }
        Some(BezierCurve::from_parts(
            self.dim,
            self.degree,
            self.points.clone(),
        ))
    }

    /// The parameter `a + (b - a) t` of the domain `[a, b]` for the local
    /// parameter `t` of [`one_span_bezier`](Self::one_span_bezier): the
    /// ends exact (`t <= 0` gives `a`, `t >= 1` gives `b`), clamped to the
    /// domain in between.
    pub(crate) fn domain_parameter(&self, t: f64) -> f64 {
        let (a, b) = self.domain();
        if t <= 0.0 {
            a
        } else if t >= 1.0 {
            b
        } else {
            (a + (b - a) * t).clamp(a, b)
        }
    }

    /// The curve as a Bezier curve on `[0, 1]` when it is one polynomial
    /// span (clamped, weights all equal); `None` otherwise.
    pub fn to_bezier(&self) -> Option<BezierCurve> {
        if self.span_count() != 1 || self.is_rational() {
            return None;
        }
        let c = self.clamped();
        BezierCurve::new(c.dim, c.degree, c.points.clone()).ok()
    }

    /// The same curve with degree `new_degree >= degree`: every span
    /// elevated, every knot's multiplicity raised by `new_degree - degree`
    /// (so the continuity at each knot is kept), ends clamped; exact.
    ///
    /// Errors: `new_degree` below the degree or above
    /// [`MAX_DEGREE`](crate::MAX_DEGREE); `IllConditioned` if a knot
    /// removal that is exact in exact arithmetic leaves an error above
    /// `1e-10` of the largest homogeneous coordinate.
    pub fn elevate_degree(&self, new_degree: usize) -> Result<NurbsCurve> {
        let p = self.degree;
        if new_degree < p {
            return Err(BezjoinError::invalid(
                "new_degree",
                format!(
                    "{new_degree} is below the curve's degree {p}; degree reduction is not exact"
                ),
            ));
        }
        if new_degree == p {
            return Ok(self.clone());
        }
        if new_degree > crate::bezier::MAX_DEGREE {
            return Err(BezjoinError::invalid(
                "new_degree",
                format!(
                    "{new_degree} is above the supported maximum {}",
                    crate::bezier::MAX_DEGREE
                ),
            ));
        }
        let q = new_degree;
        let hd = self.dim + 1;
        let spans = self.bezier_spans();
        let (breaks, mults) = self.interior_knots();
        let mut h: Vec<f64> = Vec::new();
        let (first, last) = self.domain();
        let mut knots = vec![first; q + 1];
        for (i, span) in spans.iter().enumerate() {
            let raised = BezierCurve::new(hd, p, span.homogeneous_points())?.elevate_degree(q)?;
            let skip = if i == 0 { 0 } else { hd };
            h.extend_from_slice(&raised.points()[skip..]);
            if i + 1 < spans.len() {
                knots.extend(std::iter::repeat_n(breaks[i], q));
            }
        }
        knots.extend(std::iter::repeat_n(last, q + 1));
        let scale = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let mut curve =
            NurbsCurve::from_homogeneous(self.dim, q, &h, knots, self.weights.is_some());
        for (&u, &m) in breaks.iter().zip(&mults) {
            for _ in m..p {
                let (reduced, error) = curve.remove_knot_once(u);
                if error.is_nan() || error > REMOVAL_TOLERANCE * scale {
                    return Err(BezjoinError::IllConditioned {
                        what: format!("degree elevation: removing the knot {u}"),
                        estimate: error / scale,
                        limit: REMOVAL_TOLERANCE,
                    });
                }
                curve = reduced;
            }
        }
        curve.weights = unit_weights_dropped(curve.weights.take());
        Ok(curve)
    }
}

/// The Bezier poles of a curve's spans ([`NurbsCurve::span_poles`]): span
/// `i` on `[breaks[i], breaks[i + 1]]` has the `p + 1` rows starting at row
/// `i p` (neighbouring spans share their end row), each of `h` values
/// (`dim + 1` homogeneous for a curve with weights, else `dim`).
#[derive(Debug, Clone)]
pub(crate) struct SpanPoles {
    pub(crate) breaks: Vec<f64>,
    pub(crate) rows: Vec<f64>,
    pub(crate) h: usize,
    pub(crate) degree: usize,
    /// The largest absolute value of the curve's own rows (its poles, or
    /// with weights its homogeneous poles `(w x, w)` as rounded), at least
    /// `f64::MIN_POSITIVE`: every row of every insertion is a convex
    /// combination of them, so no larger (the scale of the insertions'
    /// rounding). Without weights, [`NurbsCurve::coordinate_scale`].
    pub(crate) scale: f64,
    /// For a curve with weights, per span the largest 1-norm of its rows
    /// and the largest bound on their rounding (the 1-norm of a row's
    /// difference from the exact decomposition of the exact data, tracked
    /// through the insertions: [`insert_in_place_tracked`]); empty without
    /// weights.
    pub(crate) span_sizes: Vec<[f64; 2]>,
    /// For a curve without weights, span `i` as the Bezier curve of its
    /// rows (in `t = (u - breaks[i]) / (breaks[i + 1] - breaks[i])`);
    /// empty for a curve with weights.
    pub(crate) beziers: Vec<BezierCurve>,
    /// For a curve with weights, the arc-length quadrature's cuts of every
    /// span (module `length`), computed on first use.
    pub(crate) rational_cuts: std::sync::OnceLock<Vec<super::length::RationalSpanSpeed>>,
    /// For a curve with weights, span `i` as the Bezier curve of its
    /// homogeneous rows (dimension `dim + 1`), built on first use (the
    /// intersection's pieces).
    homogeneous: std::sync::OnceLock<Vec<BezierCurve>>,
    /// For a curve with weights, the Cartesian poles `x = (w x) / w` of
    /// every span's rows, spans one after the other, built on first use
    /// (the intersection's pieces and their boxes).
    projected: std::sync::OnceLock<Vec<f64>>,
}

impl SpanPoles {
    /// Span `i` as the Bezier curve of its rows: for a curve without
    /// weights its Bezier curve ([`SpanPoles::beziers`]), with weights its
    /// homogeneous curve (dimension `dim + 1`).
    pub(crate) fn span_curve(&self, i: usize) -> &BezierCurve {
        if !self.beziers.is_empty() {
            return &self.beziers[i];
        }
        let all = self.homogeneous.get_or_init(|| {
            (0..self.count())
                .map(|k| BezierCurve::from_parts(self.h, self.degree, self.rows(k).to_vec()))
                .collect()
        });
        &all[i]
    }

    /// For a curve with weights, the Cartesian poles of span `i` (`p + 1`
    /// rows of `h - 1` values, each `(w x) / w` of its homogeneous row).
    pub(crate) fn projected(&self, i: usize) -> &[f64] {
        let (p, d) = (self.degree, self.h - 1);
        let all = self.projected.get_or_init(|| {
            (0..self.count())
                .flat_map(|k| {
                    self.rows(k)
                        .chunks_exact(d + 1)
                        .flat_map(move |row| row[..d].iter().map(move |x| x / row[d]))
                })
                .collect()
        });
        &all[i * (p + 1) * d..(i + 1) * (p + 1) * d]
    }

    /// Number of spans.
    pub(crate) fn count(&self) -> usize {
        self.breaks.len() - 1
    }

    /// The domain of span `i`.
    pub(crate) fn domain(&self, i: usize) -> (f64, f64) {
        (self.breaks[i], self.breaks[i + 1])
    }

    /// The span that holds `u`: `breaks[i] <= u < breaks[i + 1]` from the
    /// right, `breaks[i] < u <= breaks[i + 1]` from the left, clamped to the
    /// first and last span at (and beyond) the domain's ends.
    pub(crate) fn span_at(&self, u: f64, side: crate::basis::KnotSide) -> usize {
        use crate::basis::KnotSide;
        let count = self.count();
        let above = self.breaks[1..count].partition_point(|&b| match side {
            KnotSide::Right => b <= u,
            KnotSide::Left => b < u,
        });
        above.min(count - 1)
    }

    /// The `p + 1` rows of span `i`.
    pub(crate) fn rows(&self, i: usize) -> &[f64] {
        let (p, h) = (self.degree, self.h);
        &self.rows[i * p * h..(i * p + p + 1) * h]
    }
}

/// The sum of the absolute values (the 1-norm of a row).
pub(crate) fn abs_sum(row: &[f64]) -> f64 {
    row.iter().fold(0.0f64, |s, x| s + x.abs())
}

/// [`SpanPoles::span_sizes`] of the rows (`h` values each, spans of `p + 1`
/// rows sharing their ends) and their errors; empty without errors.
fn span_sizes(rows: &[f64], row_errors: &[f64], h: usize, p: usize) -> Vec<[f64; 2]> {
    if row_errors.is_empty() || p == 0 {
        return Vec::new();
    }
    let count = (row_errors.len() - 1) / p;
    (0..count)
        .map(|i| {
            let window = i * p..=i * p + p;
            let size = rows[i * p * h..(i * p + p + 1) * h]
                .chunks_exact(h)
                .map(abs_sum)
                .fold(0.0f64, f64::max);
            let error = row_errors[window].iter().fold(0.0f64, |m, &e| m.max(e));
            [size, error]
        })
        .collect()
}

/// `times` insertions of `u` into the rows `h` (`hd` values each) on
/// `knots`, in place: each the operations of [`super::knots::insert_once`]
/// (`k` the span of `u` from the right; rows `k + 1 - p ..= k` become
/// `a_i R_i + (1 - a_i) R_(i-1)`, the rows from `k` on move up one),
/// computed from the highest new row down so that each reads rows not yet
/// written.
pub(super) fn insert_in_place(
    hd: usize,
    p: usize,
    knots: &mut Vec<f64>,
    h: &mut Vec<f64>,
    u: f64,
    times: usize,
) {
    // The plane and space (with or without the weight) with the row length
    // as a constant: the same operations.
    match hd {
        2 => insert_sized(2, p, knots, h, None, u, times),
        3 => insert_sized(3, p, knots, h, None, u, times),
        4 => insert_sized(4, p, knots, h, None, u, times),
        _ => insert_sized(hd, p, knots, h, None, u, times),
    }
}

/// [`insert_in_place`] (the same operations on the rows, so the same bits)
/// that also carries `errors`, one value per row: a bound on the 1-norm of
/// the difference between the computed row and the row that exact
/// insertions of the exact data would give (the errors of the rows before
/// the first insertion are the caller's). A new row `a R_i + (1 - a)
/// R_(i-1)` gets `a e_i + (1 - a) e_(i-1) + 8 u max(|R_i|_1, |R_(i-1)|_1)`:
/// the computed `a` is within `3 u a` of the exact ratio (a difference, a
/// difference, a quotient), `fl(1 - a)` within `3 u a + u (1 - a)` of
/// `1 - a`, and the two products and the sum add `u (a |x| + (1 - a) |y|)
/// + u |new|` per coordinate: `u (5 a |x| + 3 |y|)` in all, at most `8 u`
/// times the larger row's 1-norm (to first order, `a` in `[0, 1]`).
pub(super) fn insert_in_place_tracked(
    hd: usize,
    p: usize,
    knots: &mut Vec<f64>,
    h: &mut Vec<f64>,
    errors: &mut Vec<f64>,
    u: f64,
    times: usize,
) {
    match hd {
        2 => insert_sized(2, p, knots, h, Some(errors), u, times),
        3 => insert_sized(3, p, knots, h, Some(errors), u, times),
        4 => insert_sized(4, p, knots, h, Some(errors), u, times),
        _ => insert_sized(hd, p, knots, h, Some(errors), u, times),
    }
}

/// [`insert_in_place`] and [`insert_in_place_tracked`], inlined so that a
/// constant `hd` unrolls it.
#[inline(always)]
fn insert_sized(
    hd: usize,
    p: usize,
    knots: &mut Vec<f64>,
    h: &mut Vec<f64>,
    mut errors: Option<&mut Vec<f64>>,
    u: f64,
    times: usize,
) {
    if times == 0 {
        return;
    }
    let unit = f64::EPSILON / 2.0;
    let first = find_span(knots, p, u, KnotSide::Right);
    for r in 0..times {
        // After `r` insertions `u` occupies `first + 1 ..= first + r`, so
        // the span of `u` from the right is `first + r`: what `find_span`
        // would return.
        let k = first + r;
        let n = h.len() / hd;
        h.resize((n + 1) * hd, 0.0);
        h.copy_within(k * hd..n * hd, (k + 1) * hd);
        if let Some(errors) = errors.as_deref_mut() {
            errors.insert(k, errors[k]);
        }
        for i in ((k + 1 - p)..=k).rev() {
            let a = (u - knots[i]) / (knots[i + p] - knots[i]);
            if let Some(errors) = errors.as_deref_mut() {
                let larger =
                    abs_sum(&h[i * hd..(i + 1) * hd]).max(abs_sum(&h[(i - 1) * hd..i * hd]));
                errors[i] = a * errors[i] + (1.0 - a) * errors[i - 1] + 8.0 * unit * larger;
            }
            for c in 0..hd {
                h[i * hd + c] = a * h[i * hd + c] + (1.0 - a) * h[(i - 1) * hd + c];
            }
        }
        knots.insert(k + 1, u);
    }
}

#[cfg(test)]
mod tests {
    use super::super::knots::insert_once;
    use super::NurbsCurve;

    use crate::test_values::unit_generator as generator;

    /// A random curve of `degree` with `count` poles in `dim` on `[a, a +
    /// h]`: interior knots random (some repeated), ends clamped or (when
    /// `free`) not, weights when `rational`.
    fn random_curve(
        next: &mut impl FnMut() -> f64,
        dim: usize,
        degree: usize,
        count: usize,
        free: bool,
        rational: bool,
    ) -> NurbsCurve {
        let (a, h) = (10.0 * next() - 5.0, 0.1 + 5.0 * next());
        let mut inner: Vec<f64> = (0..count - degree - 1).map(|_| next()).collect();
        inner.sort_by(f64::total_cmp);
        if degree >= 2 && inner.len() >= 2 && next() < 0.3 {
            inner[1] = inner[0];
        }
        let mut knots: Vec<f64> = if free {
            (0..=degree).map(|i| -0.1 * (degree - i) as f64).collect()
        } else {
            vec![0.0; degree + 1]
        };
        knots.extend(inner);
        if free {
            knots.extend((0..=degree).map(|i| 1.0 + 0.1 * i as f64));
        } else {
            knots.extend(std::iter::repeat_n(1.0, degree + 1));
        }
        let knots = knots.iter().map(|k| a + h * k).collect();
        let poles = (0..count * dim).map(|_| 4.0 * next() - 2.0).collect();
        let weights = rational.then(|| (0..count).map(|_| 0.3 + 2.0 * next()).collect());
        NurbsCurve::new(dim, degree, poles, weights, knots).expect("a valid curve")
    }

    /// `point_and_tangent_by_spans` (de Casteljau on the kept Bezier rows,
    /// the polish's evaluation) is `point_and_tangent` (de Boor on the
    /// poles) up to rounding for rational quadratics and cubics in the
    /// plane and in space, at random parameters, at every interior knot
    /// (from the right: the tangent jumps at a double knot of a quadratic)
    /// and at both ends; every other curve goes to `point_and_tangent`
    /// itself, the same bits.
    #[test]
    fn span_row_evaluation_is_de_boor_up_to_rounding() {
        let mut next = generator(47);
        let (mut by_rows, mut same) = (0, 0);
        for case in 0..400 {
            let degree = 1 + case % 4;
            let dim = 2 + (case / 4) % 2;
            let count = degree + 1 + (case / 8) % 5;
            let rational = case % 5 != 0;
            let c = random_curve(&mut next, dim, degree, count, case % 7 == 3, rational);
            let (a, b) = c.domain();
            let mut us: Vec<f64> = (0..6).map(|_| a + (b - a) * next()).collect();
            us.extend(c.knots.iter().copied().filter(|&k| k > a && k < b));
            us.extend([a, b]);
            for u in us {
                let (mut p0, mut t0) = (vec![0.0; dim], vec![0.0; dim]);
                let (mut p1, mut t1) = (vec![0.0; dim], vec![0.0; dim]);
                c.point_and_tangent(u, &mut p0, Some(&mut t0));
                c.point_and_tangent_by_spans(u, &mut p1, &mut t1);
                if !(rational && (degree == 2 || degree == 3)) {
                    assert_eq!((&p1, &t1), (&p0, &t0), "case {case} u {u}");
                    same += 1;
                    continue;
                }
                let speed = t0.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                for (x, y) in p1.iter().zip(&p0) {
                    assert!(
                        (x - y).abs() <= 1e-13 * (1.0 + y.abs()),
                        "case {case} u {u}"
                    );
                }
                for (x, y) in t1.iter().zip(&t0) {
                    assert!((x - y).abs() <= 1e-12 * (1.0 + speed), "case {case} u {u}");
                }
                by_rows += 1;
            }
        }
        assert!(by_rows > 1000 && same > 500, "{by_rows} {same}");
    }

    /// The span decomposition's rows are the bits of the repeated
    /// `insert_once` on the clamped curve's homogeneous poles (the
    /// decomposition before the in-place buffer), and `bezier_spans` gives
    /// each span's poles and weights from them: polynomial and rational
    /// curves, clamped and free ends, repeated knots, degrees 1 to 5.
    #[test]
    fn span_poles_are_the_repeated_insertions_bit_for_bit() {
        let mut next = generator(5);
        for case in 0..300 {
            let degree = 1 + case % 5;
            let dim = 2 + case % 2;
            let count = degree + 1 + (case / 5) % 6;
            let rational = case % 3 == 0;
            let c = random_curve(&mut next, dim, degree, count, case % 7 == 1, rational);
            let clamped = c.clamped();
            let hd = dim + 1;
            let mut h = clamped.homogeneous_points();
            let mut knots = clamped.knots.clone();
            let (breaks, mults) = clamped.interior_knots();
            for (&u, &m) in breaks.iter().zip(&mults) {
                for _ in m..degree {
                    insert_once(hd, degree, &mut knots, &mut h, u);
                }
            }
            let poles = c.span_poles();
            assert_eq!(poles.count(), breaks.len() + 1, "case {case}");
            assert_eq!(&poles.breaks[1..poles.count()], &breaks[..], "case {case}");
            let rows = poles.rows.len() / poles.h;
            assert_eq!(rows, h.len() / hd, "case {case}");
            for i in 0..rows {
                let reference = &h[i * hd..(i + 1) * hd];
                let got = &poles.rows[i * poles.h..(i + 1) * poles.h];
                if rational {
                    assert_eq!(got, reference, "case {case} row {i}");
                } else {
                    // The weight coordinate stayed exactly 1.
                    assert_eq!(reference[dim], 1.0, "case {case} row {i}");
                    assert_eq!(got, &reference[..dim], "case {case} row {i}");
                }
            }
            for (i, span) in c.bezier_spans().iter().enumerate() {
                assert_eq!(span.domain(), poles.domain(i), "case {case}");
                if !rational {
                    assert_eq!(span.points(), poles.beziers[i].points(), "case {case}");
                }
            }
        }
    }

    /// `clamped_trim` is `segment` bit for bit (knots, poles and weights),
    /// left and right, with and without weights, at random parameters and
    /// at existing knots of every multiplicity; `None` for free ends.
    #[test]
    fn clamped_trims_are_the_segments_bit_for_bit() {
        let mut next = generator(9);
        let mut rational_trims = 0;
        for case in 0..300 {
            let degree = 1 + case % 5;
            let dim = 2 + case % 2;
            let count = degree + 1 + (case / 5) % 6;
            let free = case % 11 == 3;
            let rational = case % 3 == 1;
            let c = random_curve(&mut next, dim, degree, count, free, rational);
            let (a, b) = c.domain();
            let mut us: Vec<f64> = (0..4).map(|_| a + (b - a) * next()).collect();
            us.extend(c.knots.iter().copied().filter(|&k| k > a && k < b));
            for u in us {
                for left in [true, false] {
                    let trim = c.clamped_trim(u, left);
                    if free {
                        assert!(trim.is_none(), "case {case}");
                        continue;
                    }
                    let segment = if left {
                        c.segment(a, u).unwrap()
                    } else {
                        c.segment(u, b).unwrap()
                    };
                    let trim = trim.unwrap();
                    assert_eq!(trim.knots, segment.knots, "case {case} u {u} left {left}");
                    assert_eq!(trim.points, segment.points, "case {case} u {u} left {left}");
                    assert_eq!(trim.weights, segment.weights, "case {case}");
                    rational_trims += usize::from(rational);
                }
            }
        }
        assert!(rational_trims > 300, "{rational_trims}");
    }

    /// The windowed trim (insertions on `p + 1` rows on the stack) is the
    /// insertion on all rows bit for bit, left and right, with and without
    /// weights, at random parameters and at knots of multiplicity below the
    /// degree; the trimmed curve evaluates as the curve on the kept range.
    #[test]
    fn windowed_trims_are_the_full_insertions_bit_for_bit() {
        let mut next = generator(31);
        let (mut windowed, mut rational_windowed) = (0, 0);
        for case in 0..400 {
            let degree = 1 + case % 5;
            let dim = 2 + case % 2;
            let count = degree + 1 + (case / 5) % 7;
            let rational = case % 2 == 1;
            let c = random_curve(&mut next, dim, degree, count, false, rational);
            let (a, b) = c.domain();
            let mut us: Vec<f64> = (0..4).map(|_| a + (b - a) * next()).collect();
            us.extend(c.knots.iter().copied().filter(|&k| k > a && k < b));
            for u in us {
                for left in [true, false] {
                    let full = c.clamped_trim_by_insertion(u, left).unwrap();
                    let Some(fast) = c.clamped_trim_windowed(u, left) else {
                        assert!(c.multiplicity(u) >= degree, "case {case} u {u}");
                        continue;
                    };
                    assert_eq!(fast.knots, full.knots, "case {case} u {u} left {left}");
                    assert_eq!(fast.points, full.points, "case {case} u {u} left {left}");
                    assert_eq!(fast.weights, full.weights, "case {case} u {u} left {left}");
                    let (lo, hi) = fast.domain();
                    assert_eq!((lo, hi), if left { (a, u) } else { (u, b) });
                    for s in 0..=8 {
                        let t = lo + (hi - lo) * s as f64 / 8.0;
                        let (x, y) = (fast.eval(t), c.eval(t));
                        for (x, y) in x.iter().zip(&y) {
                            assert!((x - y).abs() <= 1e-12 * (1.0 + y.abs()), "case {case}");
                        }
                    }
                    windowed += 1;
                    rational_windowed += usize::from(rational);
                }
            }
        }
        assert!(
            windowed > 2000 && rational_windowed > 1000,
            "{windowed} {rational_windowed}"
        );
    }
}
