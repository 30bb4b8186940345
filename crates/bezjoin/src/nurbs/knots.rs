//! Knot insertion (The NURBS Book A5.1, one knot at a time as Boehm's
//! rule), knot removal (the inverse of one insertion, checked), and what
//! is built on them: split, trim, clamping and reversal. All work on the
//! homogeneous poles `(w P, w)`, so rational curves are exact too.

use super::{NurbsCurve, unit_weights_dropped};
use crate::basis::{KnotSide, find_span};
use crate::error::{BezjoinError, Result, check_finite_scalar};

/// Values of the window of [`NurbsCurve::clamped_trim_windowed`]: `2 p + 1`
/// rows of `dim + 1` values.
const TRIM_ROWS: usize = 64;
/// Knots of that window: `3 p + 1`.
const TRIM_KNOTS: usize = 32;

impl NurbsCurve {
    /// Multiplicity of the value `u` in the knot vector.
    pub fn multiplicity(&self, u: f64) -> usize {
        self.knots.iter().filter(|&&k| k == u).count()
    }

    /// The same curve with the knot `u` inserted `times` more times
    /// (A5.1): same shape, same parameters, `times` more poles. The
    /// multiplicity after insertion may not exceed the degree (the end
    /// values of the knot vector: degree + 1), and `u` must lie in the
    /// domain.
    pub fn insert_knot(&self, u: f64, times: usize) -> Result<NurbsCurve> {
        self.check_parameter("u", u)?;
        let (first, last) = self.domain();
        let limit = if u == first || u == last {
            self.degree + 1
        } else {
            self.degree
        };
        let now = self.multiplicity(u);
        if now.saturating_add(times) > limit {
            return Err(BezjoinError::invalid(
                "times",
                format!(
                    "inserting {u} {times} times makes its multiplicity {} > {limit}",
                    now.saturating_add(times)
                ),
            ));
        }
        let mut h = self.homogeneous_points();
        let mut knots = self.knots.clone();
        for _ in 0..times {
            insert_once(self.dim + 1, self.degree, &mut knots, &mut h, u);
        }
        Ok(NurbsCurve::from_homogeneous(
            self.dim,
            self.degree,
            &h,
            knots,
            self.weights.is_some(),
        ))
    }

    /// Cut at `u` in the closed domain: the homogeneous poles and knots
    /// with `u` inserted up to multiplicity `degree` at least, and the
    /// index of the first occurrence of `u` and its multiplicity.
    fn cut(&self, u: f64) -> (Vec<f64>, Vec<f64>, usize, usize) {
        let p = self.degree;
        let mut h = self.homogeneous_points();
        let mut knots = self.knots.clone();
        let now = self.multiplicity(u);
        for _ in now..p {
            insert_once(self.dim + 1, p, &mut knots, &mut h, u);
        }
        let j = knots.partition_point(|&k| k < u);
        let m = knots[j..].iter().take_while(|&&k| k == u).count();
        (h, knots, j, m)
    }

    /// The part on `[first, u]` from a cut (see [`cut`](Self::cut)).
    fn left_of_cut(&self, h: &[f64], knots: &[f64], j: usize, u: f64) -> NurbsCurve {
        let hd = self.dim + 1;
        let p = self.degree;
        let mut k = knots[..j].to_vec();
        k.extend(std::iter::repeat_n(u, p + 1));
        NurbsCurve::from_homogeneous(self.dim, p, &h[..j * hd], k, self.weights.is_some())
    }

    /// The part on `[u, last]` from a cut.
    fn right_of_cut(&self, h: &[f64], knots: &[f64], j: usize, m: usize, u: f64) -> NurbsCurve {
        let hd = self.dim + 1;
        let p = self.degree;
        let start = j + m - p - 1;
        let mut k = vec![u; p + 1];
        k.extend_from_slice(&knots[j + m..]);
        NurbsCurve::from_homogeneous(self.dim, p, &h[start * hd..], k, self.weights.is_some())
    }

    /// The two pieces `[first, u]` and `[u, last]` (`first < u < last`),
    /// each clamped at `u`, with the original parameters; exact (knot
    /// insertion, no approximation).
    pub fn split_at(&self, u: f64) -> Result<(NurbsCurve, NurbsCurve)> {
        check_finite_scalar("u", u)?;
        let (first, last) = self.domain();
        if u <= first || u >= last {
            return Err(BezjoinError::out_of_range(
                "u",
                u,
                format!("({first}, {last})"),
            ));
        }
        let (h, knots, j, m) = self.cut(u);
        Ok((
            self.left_of_cut(&h, &knots, j, u),
            self.right_of_cut(&h, &knots, j, m, u),
        ))
    }

    /// The same curve with both ends clamped (end knots of multiplicity
    /// degree + 1, the first and last poles on the curve): same shape,
    /// same domain. A clamped curve comes back unchanged.
    pub fn clamped(&self) -> NurbsCurve {
        let (first, last) = self.domain();
        let p = self.degree;
        let mut curve = self.clone();
        if curve.knots[..=p].iter().any(|&k| k != first) {
            let (h, knots, j, m) = curve.cut(first);
            curve = curve.right_of_cut(&h, &knots, j, m, first);
        }
        let n = curve.point_count();
        if curve.knots[n..].iter().any(|&k| k != last) {
            let (h, knots, j, _) = curve.cut(last);
            curve = curve.left_of_cut(&h, &knots, j, last);
        }
        curve
    }

    /// The piece on `[a, b]` (`first <= a < b <= last`) with the original
    /// parameters, clamped at both ends; exact.
    pub fn segment(&self, a: f64, b: f64) -> Result<NurbsCurve> {
        self.check_parameter("a", a)?;
        self.check_parameter("b", b)?;
        if a >= b {
            return Err(BezjoinError::invalid(
                "b",
                format!("{b} must be greater than a = {a}"),
            ));
        }
        let (first, last) = self.domain();
        let mut curve = self.clamped();
        if a > first {
            curve = curve.split_at(a)?.1;
        }
        if b < last {
            curve = curve.split_at(b)?.0;
        }
        Ok(curve)
    }

    /// [`segment`](Self::segment)`(first, u)` (`left`) or `(u, last)` of a
    /// clamped one-span polynomial curve without weights, by one de
    /// Casteljau pass at `t = (u - first) / (last - first)` on the poles
    /// ([`crate::fillet::bezier_trim`], the Bezier fillet's trim; exact in
    /// exact arithmetic, as the knot insertions are). `None` for other
    /// curves, `u` not strictly inside the domain or a non-finite result.
    pub(crate) fn one_span_trim(&self, u: f64, left: bool) -> Option<NurbsCurve> {
        if self.weights.is_some() {
            return None;
        }
        let bezier = self.one_span_bezier()?;
        let (a, b) = self.domain();
        if !(u > a && u < b) {
            return None;
        }
        let t = (u - a) / (b - a);
        let piece = crate::fillet::bezier_trim(&bezier, t, left)?;
        let (lo, hi) = if left { (a, u) } else { (u, b) };
        Some(NurbsCurve::from_span_parts(
            self.dim,
            self.degree,
            piece.points().to_vec(),
            None,
            lo,
            hi,
        ))
    }

    /// [`segment`](Self::segment)`(first, u)` (`left`) or `(u, last)` of a
    /// clamped curve, `u` strictly inside the domain: the knot `u` inserted
    /// up to multiplicity `p` in one buffer (the operations of `segment`'s
    /// `cut`: on the homogeneous poles with weights, then the Cartesian
    /// poles and weights as `from_homogeneous` gives them; without weights
    /// on the Cartesian poles, since the weight coordinate of the
    /// homogeneous rows stays exactly 1, see [`NurbsCurve::span_poles`], so
    /// the poles are the same bits either way), then the rows and knots of
    /// the side asked for. `None` for other curves or parameters.
    pub(crate) fn clamped_trim(&self, u: f64, left: bool) -> Option<NurbsCurve> {
        self.clamped_trim_windowed(u, left)
            .or_else(|| self.clamped_trim_by_insertion(u, left))
    }

    /// [`clamped_trim`](Self::clamped_trim) with the insertions on a window
    /// of `p + 1` rows on the stack: the insertions of `u` read only the
    /// original rows `first - p ..= first` (`first` the span of `u` from the
    /// right; every later row only moves) and the knots `first - p ..=
    /// first + p` with the inserted `u`s, so the same loop on those rows
    /// and knots gives the same bits; the rows outside the window are the
    /// curve's own (with weights through `(w x) / w`, as the full path
    /// gives them). `None` (the full path answers) when `u` already has
    /// multiplicity `p` or more, the curve is not clamped, `u` is not
    /// strictly inside, or the window does not fit its buffers.
    pub(crate) fn clamped_trim_windowed(&self, u: f64, left: bool) -> Option<NurbsCurve> {
        let p = self.degree;
        let (first_u, last_u) = self.domain();
        let n = self.point_count();
        if !(u > first_u && u < last_u) || p == 0 {
            return None;
        }
        let clamped = self.knots[..=p].iter().all(|&k| k == first_u)
            && self.knots[n..].iter().all(|&k| k == last_u);
        let now = self.multiplicity(u);
        if !clamped || now >= p {
            return None;
        }
        let times = p - now;
        let hd = self.dim + usize::from(self.weights.is_some());
        if (2 * p + 1) * hd > TRIM_ROWS || 3 * p + 1 > TRIM_KNOTS {
            return None;
        }
        let first = find_span(&self.knots, p, u, KnotSide::Right);
        // Cubics in the plane and in space, with and without weights, with
        // the sizes as constants: the same operations.
        // Buffers of exactly `(2p + 1) hd` rows' values and `3p + 1` knots
        // for those (less to zero).
        Some(match (p, hd) {
            (3, 2) => self.trim_window::<14, 10>(3, 2, u, left, first, times),
            (3, 3) => self.trim_window::<21, 10>(3, 3, u, left, first, times),
            (3, 4) => self.trim_window::<28, 10>(3, 4, u, left, first, times),
            _ => self.trim_window::<TRIM_ROWS, TRIM_KNOTS>(p, hd, u, left, first, times),
        })
    }

    /// The body of [`clamped_trim_windowed`](Self::clamped_trim_windowed):
    /// degree `p`, rows of `hd` values, `first` the span of `u` from the
    /// right, `times` insertions; the buffers of `R` row values and `K`
    /// knots fit (`(2p + 1) hd <= R`, `3p + 1 <= K`).
    #[inline(always)]
    fn trim_window<const R: usize, const K: usize>(
        &self,
        p: usize,
        hd: usize,
        u: f64,
        left: bool,
        first: usize,
        times: usize,
    ) -> NurbsCurve {
        let rational = self.weights.is_some();
        let (dim, n) = (self.dim, self.point_count());
        let lo = first - p;
        // The window: rows `lo ..= first` (homogeneous with weights) and
        // knots `lo ..= first + p`, local indices from `lo`.
        let mut h = [0.0f64; R];
        for (r, row) in h[..(p + 1) * hd].chunks_exact_mut(hd).enumerate() {
            let x = self.point(lo + r);
            match &self.weights {
                // `homogeneous_point`'s operations.
                Some(weights) => {
                    let w = weights[lo + r];
                    for (o, x) in row.iter_mut().zip(x) {
                        *o = w * x;
                    }
                    row[dim] = w;
                }
                None => row.copy_from_slice(x),
            }
        }
        let mut kn = [0.0f64; K];
        kn[..2 * p + 1].copy_from_slice(&self.knots[lo..=first + p]);
        let mut kn_len = 2 * p + 1;
        // `insert_in_place`'s loop with `first` at local `p`.
        for r in 0..times {
            let k = p + r;
            h.copy_within(k * hd..(k + 1) * hd, (k + 1) * hd);
            for i in ((k + 1 - p)..=k).rev() {
                let a = (u - kn[i]) / (kn[i + p] - kn[i]);
                for c in 0..hd {
                    h[i * hd + c] = a * h[i * hd + c] + (1.0 - a) * h[(i - 1) * hd + c];
                }
            }
            kn.copy_within(k + 1..kn_len, k + 2);
            kn[k + 1] = u;
            kn_len += 1;
        }
        // After the insertions `u` has multiplicity `p`: its first copy at
        // `j` (global), the left piece's rows `..j`, the right piece's from
        // `j - 1`.
        let j = lo + kn[..kn_len].partition_point(|&k| k < u);
        let window_rows = p + 1 + times;
        let (orig_rows, win_rows, tail_rows) = if left {
            (0..lo, 0..j - lo, first + 1..first + 1)
        } else {
            (first + 1..first + 1, j - 1 - lo..window_rows, first + 1..n)
        };
        let count = orig_rows.len() + win_rows.len() + tail_rows.len();
        let mut points = Vec::with_capacity(count * dim);
        let mut weights = Vec::with_capacity(if rational { count } else { 0 });
        let own = |i: usize, points: &mut Vec<f64>, weights: &mut Vec<f64>| {
            let x = self.point(i);
            if rational {
                let w = self.weight(i);
                points.extend(x.iter().map(|x| (w * x) / w));
                weights.push(w);
            } else {
                points.extend_from_slice(x);
            }
        };
        for i in orig_rows {
            own(i, &mut points, &mut weights);
        }
        for row in h[win_rows.start * hd..win_rows.end * hd].chunks_exact(hd) {
            if rational {
                let w = row[dim];
                points.extend(row[..dim].iter().map(|x| x / w));
                weights.push(w);
            } else {
                points.extend_from_slice(row);
            }
        }
        for i in tail_rows {
            own(i, &mut points, &mut weights);
        }
        let knots = if left {
            let mut k = Vec::with_capacity(j + p + 1);
            k.extend_from_slice(&self.knots[..j]);
            k.extend(std::iter::repeat_n(u, p + 1));
            k
        } else {
            let mut k = Vec::with_capacity(p + 1 + self.knots.len() - (first + 1));
            k.extend(std::iter::repeat_n(u, p + 1));
            k.extend_from_slice(&self.knots[first + 1..]);
            k
        };
        NurbsCurve {
            degree: p,
            dim,
            knots,
            points,
            weights: rational.then_some(weights),
            span_cache: Default::default(),
        }
    }

    /// [`clamped_trim`](Self::clamped_trim) by insertions on all rows (the
    /// general path, and the reference of the windowed one in tests).
    pub(crate) fn clamped_trim_by_insertion(&self, u: f64, left: bool) -> Option<NurbsCurve> {
        let p = self.degree;
        let (first, last) = self.domain();
        let n = self.point_count();
        let clamped = self.knots[..=p].iter().all(|&k| k == first)
            && self.knots[n..].iter().all(|&k| k == last);
        if !(clamped && u > first && u < last) {
            return None;
        }
        let rational = self.weights.is_some();
        let d = if rational { self.dim + 1 } else { self.dim };
        let now = self.multiplicity(u);
        let insertions = p.saturating_sub(now);
        let mut h = Vec::with_capacity((n + insertions) * d);
        if rational {
            h.resize(n * d, 0.0);
            for (i, row) in h.chunks_exact_mut(d).enumerate() {
                self.homogeneous_point(i, row);
            }
        } else {
            h.extend_from_slice(&self.points);
        }
        let mut knots = Vec::with_capacity(self.knots.len() + insertions);
        knots.extend_from_slice(&self.knots);
        super::spans::insert_in_place(d, p, &mut knots, &mut h, u, insertions);
        let j = knots.partition_point(|&k| k < u);
        let m = knots[j..].iter().take_while(|&&k| k == u).count();
        let (points, knots) = if left {
            h.truncate(j * d);
            knots.truncate(j);
            knots.extend(std::iter::repeat_n(u, p + 1));
            (h, knots)
        } else {
            let start = j + m - p - 1;
            h.drain(..start * d);
            let mut k = Vec::with_capacity(p + 1 + knots.len() - (j + m));
            k.extend(std::iter::repeat_n(u, p + 1));
            k.extend_from_slice(&knots[j + m..]);
            (h, k)
        };
        if rational {
            return Some(NurbsCurve::from_homogeneous(
                self.dim, p, &points, knots, true,
            ));
        }
        Some(NurbsCurve {
            degree: p,
            dim: d,
            knots,
            points,
            weights: None,
            span_cache: Default::default(),
        })
    }

    /// The same point set traversed backwards on the same domain:
    /// `R(u) = C(first + last - u)`. The knots are `first + last - k`,
    /// except that a knot equal to `first` or `last` becomes exactly `last`
    /// or `first` (the rounded mirror can land an ulp off, which split one
    /// multiple end knot into knots an ulp apart and made the knot vector
    /// step back; fuzz finding F12, docs/reliability.md), and the mirrored
    /// knots of the domain stay inside it; so the knot vector stays
    /// non-decreasing (the mirror is monotone, and so is rounding).
    pub fn reverse(&self) -> NurbsCurve {
        let (first, last) = self.domain();
        let d = self.dim;
        let knots: Vec<f64> = self
            .knots
            .iter()
            .rev()
            .map(|&k| {
                if k == first {
                    last
                } else if k == last {
                    first
                } else if k > first && k < last {
                    ((first + last) - k).clamp(first, last)
                } else {
                    (first + last) - k
                }
            })
            .collect();
        let mut points = Vec::with_capacity(self.points.len());
        for row in self.points.chunks_exact(d).rev() {
            points.extend_from_slice(row);
        }
        let weights = self
            .weights
            .as_ref()
            .map(|w| w.iter().rev().copied().collect());
        let mut r = NurbsCurve {
            degree: self.degree,
            dim: d,
            knots,
            points,
            weights,
            span_cache: Default::default(),
        };
        // The knots outside the domain stay outside it.
        let p = self.degree;
        let n = r.point_count();
        r.knots[p] = first;
        r.knots[n] = last;
        for i in 0..p {
            r.knots[i] = r.knots[i].min(first);
        }
        for i in n + 1..r.knots.len() {
            r.knots[i] = r.knots[i].max(last);
        }
        r
    }

    /// The curve with the interior knot `u` removed `times` times, when the
    /// curve is smooth enough there for that to be exact: each removal's
    /// error (the largest homogeneous pole distance between the curve and
    /// the result with `u` inserted back) must stay within `tolerance`
    /// (absolute); otherwise `InvalidArgument` on `u` with the error.
    pub fn remove_knot(&self, u: f64, times: usize, tolerance: f64) -> Result<NurbsCurve> {
        self.check_parameter("u", u)?;
        let (first, last) = self.domain();
        let now = self.multiplicity(u);
        if u == first || u == last || now < times {
            return Err(BezjoinError::invalid(
                "u",
                format!("{u} is not an interior knot of multiplicity >= {times} (it has {now})"),
            ));
        }
        let mut curve = self.clone();
        for i in 0..times {
            let (reduced, error) = curve.remove_knot_once(u);
            if error.is_nan() || error > tolerance {
                return Err(BezjoinError::invalid(
                    "u",
                    format!(
                        "removal {} of {times} of the knot {u} would move the curve by {error:e} \
                         (tolerance {tolerance:e})",
                        i + 1
                    ),
                ));
            }
            curve = reduced;
        }
        Ok(curve)
    }

    /// `self` followed by `next`, as one curve: `self` must end where
    /// `next` starts, in parameter (`last == next.first`) and in space
    /// (within `1e-12` of the coordinate scale), both clamped there, with
    /// one degree and dimension. The join knot gets multiplicity `degree`
    /// (the curve is C^0 there); [`remove_knot`](Self::remove_knot) makes
    /// it smoother where the pieces allow. `next`'s weights are scaled so
    /// that the two weights at the join agree (which does not change
    /// `next`). The inverse of [`split_at`](Self::split_at).
    pub fn join(&self, next: &NurbsCurve) -> Result<NurbsCurve> {
        if next.dim != self.dim {
            return Err(BezjoinError::DimensionMismatch {
                name: "next".into(),
                expected: self.dim,
                actual: next.dim,
            });
        }
        if next.degree != self.degree {
            return Err(BezjoinError::invalid(
                "next",
                format!(
                    "has degree {}, the curve {}; elevate the lower one first",
                    next.degree, self.degree
                ),
            ));
        }
        let p = self.degree;
        let (_, u) = self.domain();
        let (start, _) = next.domain();
        if start != u {
            return Err(BezjoinError::invalid(
                "next",
                format!("starts at parameter {start}, the curve ends at {u}"),
            ));
        }
        let a = self.clamped();
        let b = next.clamped();
        let n = a.point_count();
        let scale = a.coordinate_scale().max(b.coordinate_scale());
        let gap = crate::bezier::distance(a.point(n - 1), b.point(0));
        if gap.is_nan() || gap > 1e-12 * scale {
            return Err(BezjoinError::invalid(
                "next",
                format!("starts {gap:e} away from the end of the curve"),
            ));
        }
        let hd = self.dim + 1;
        let mut h = a.homogeneous_points();
        let ratio = a.weight(n - 1) / b.weight(0);
        let hb = b.homogeneous_points();
        h.extend(hb[hd..].iter().map(|x| x * ratio));
        let mut knots = a.knots[..n].to_vec();
        knots.extend(std::iter::repeat_n(u, p));
        knots.extend_from_slice(&b.knots[p + 1..]);
        let rational = a.weights.is_some() || b.weights.is_some();
        let mut joined = NurbsCurve::from_homogeneous(self.dim, p, &h, knots, rational);
        joined.weights = unit_weights_dropped(joined.weights.take());
        Ok(joined)
    }

    /// Remove one occurrence of the interior knot `u` (the inverse of one
    /// insertion). Returns the curve and the removal error: the largest
    /// distance, in homogeneous coordinates, between the poles of the
    /// given curve and those of the result with `u` inserted back. Exact
    /// removal (the curve is `C^(p-m+1)` at `u` for multiplicity `m`) has
    /// an error at the rounding level of the poles.
    pub(crate) fn remove_knot_once(&self, u: f64) -> (NurbsCurve, f64) {
        let hd = self.dim + 1;
        let p = self.degree;
        let h = self.homogeneous_points();
        // The curve without u: knots U' and unknown poles Q (one fewer).
        let r = self
            .knots
            .iter()
            .rposition(|&k| k == u)
            .expect("u is a knot");
        let mut reduced = self.knots.clone();
        reduced.remove(r);
        let s_reduced = self.multiplicity(u) - 1;
        // Span of u in U' (from the right): U'_k <= u < U'_(k+1).
        let k = find_span(&reduced, p, u, KnotSide::Right);
        let count = self.point_count() - 1;
        let mut q = vec![0.0; count * hd];
        // Unchanged: Q_i = P_i for i <= k - p; Q_(i-1) = P_i for i >= k - s' + 1.
        for i in 0..=k - p {
            q[i * hd..(i + 1) * hd].copy_from_slice(&h[i * hd..(i + 1) * hd]);
        }
        for i in (k - s_reduced + 1)..=count {
            q[(i - 1) * hd..i * hd].copy_from_slice(&h[i * hd..(i + 1) * hd]);
        }
        // Unknowns Q_lo..=Q_hi; equations P_i = a_i Q_i + (1 - a_i) Q_(i-1)
        // for i = lo..=hi + 1, one more than unknowns: forward from the
        // left up to the middle, backward from the right, the last
        // equation is the check.
        let lo = k - p + 1;
        let hi = k - s_reduced - 1; // may be lo - 1: no unknowns
        let alpha = |i: usize| (u - reduced[i]) / (reduced[i + p] - reduced[i]);
        let mid = (lo + hi).div_ceil(2); // forward fills lo..mid (exclusive)
        for i in lo..mid {
            let a = alpha(i);
            for c in 0..hd {
                q[i * hd + c] = (h[i * hd + c] - (1.0 - a) * q[(i - 1) * hd + c]) / a;
            }
        }
        let mut i = hi + 1;
        while i > mid {
            let a = alpha(i);
            for c in 0..hd {
                q[(i - 1) * hd + c] = (h[i * hd + c] - a * q[i * hd + c]) / (1.0 - a);
            }
            i -= 1;
        }
        // The equation left over: i = mid.
        let a = alpha(mid);
        let mut error = 0.0f64;
        for c in 0..hd {
            let back = a * q[mid * hd + c] + (1.0 - a) * q[(mid - 1) * hd + c];
            error = error.max((back - h[mid * hd + c]).abs());
        }
        (
            NurbsCurve::from_homogeneous(self.dim, p, &q, reduced, self.weights.is_some()),
            error,
        )
    }
}

/// One insertion of `u` (Boehm; A5.1 with r = 1) into homogeneous poles
/// `h` (`hd` values each) on `knots`, in place.
pub(crate) fn insert_once(hd: usize, p: usize, knots: &mut Vec<f64>, h: &mut Vec<f64>, u: f64) {
    let k = find_span(knots, p, u, KnotSide::Right);
    let n = h.len() / hd;
    let mut out = Vec::with_capacity((n + 1) * hd);
    out.extend_from_slice(&h[..(k + 1 - p) * hd]);
    for i in (k + 1 - p)..=k {
        let a = (u - knots[i]) / (knots[i + p] - knots[i]);
        for c in 0..hd {
            out.push(a * h[i * hd + c] + (1.0 - a) * h[(i - 1) * hd + c]);
        }
    }
    out.extend_from_slice(&h[k * hd..]);
    *h = out;
    knots.insert(k + 1, u);
}
