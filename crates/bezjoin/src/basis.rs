//! B-spline basis functions and all their derivatives in one call.
//!
//! This is algorithm A2.3 of Piegl & Tiller, *The NURBS Book* (2nd ed.,
//! p. 72), for a general non-decreasing knot vector. A Bezier curve of degree
//! `n` is the special case of the clamped knot vector `0^(n+1) 1^(n+1)`
//! ([`bezier_basis_derivatives`]); the papers behind bezjoin insist on this
//! form (docs/mathematics.md#bezier-basics), and every solver takes its derivative
//! rows from here.
//!
//! Guarantee: for a parameter inside the knot span the returned row `k` holds
//! the exact (up to rounding) k-th derivatives of the `p + 1` non-zero basis
//! functions of that span. Outside the knot range the polynomial pieces of the
//! first/last span are continued (extrapolation), which is what
//! `segment(a, b)` with `b > 1` needs.

use nalgebra::DMatrix;

/// Which span to use when the parameter sits exactly on an interior knot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KnotSide {
    /// The span that ends at the knot: derivatives from the left.
    Left,
    /// The span that starts at the knot: derivatives from the right (the usual choice).
    Right,
}

/// Index `i` of the knot span `[knots[i], knots[i+1])` holding `t`
/// (The NURBS Book, A2.1), for a curve of degree `degree`.
///
/// Parameters before the first or after the last span are assigned to that
/// span (extrapolation). With [`KnotSide::Left`] a parameter on an interior
/// knot belongs to the span that ends there.
///
/// # Panics
/// If `knots.len() < 2 * degree + 2` (not a valid clamped knot vector).
pub(crate) fn find_span(knots: &[f64], degree: usize, t: f64, side: KnotSide) -> usize {
    assert!(
        knots.len() >= 2 * degree + 2,
        "knot vector too short for degree {degree}"
    );
    let p = degree;
    let last = knots.len() - p - 2; // index of the last control point
    // Candidate spans are p..=last; with non-decreasing knots the search below
    // always lands on a span of non-zero length unless t lies outside.
    let spans = &knots[p..=last + 1];
    // The domain [knots[p], knots[last + 1]]; with an unclamped knot vector
    // its end values may repeat inside `spans`, and a span of zero length
    // must never be chosen.
    let (start, end) = (knots[p], knots[last + 1]);
    match side {
        KnotSide::Right => {
            // largest i with knots[i] <= t, among spans that start before the end
            let count = spans[..=last - p].partition_point(|&k| k <= t && k < end);
            if count == 0 { p } else { p + count - 1 }
        }
        KnotSide::Left => {
            // smallest i with knots[i + 1] >= t, among spans that end after the start
            let count = spans[1..].partition_point(|&k| k < t || k <= start);
            (p + count).min(last)
        }
    }
}

/// The non-zero basis functions of degree `degree` on span `span` and their
/// derivatives up to `max_order`, at `t` (The NURBS Book, A2.3).
///
/// Returns a `(max_order + 1) x (degree + 1)` matrix: entry `(k, j)` is the
/// k-th derivative of `N_(span - degree + j)` at `t`. Orders above `degree`
/// give zero rows.
pub(crate) fn basis_derivatives(
    knots: &[f64],
    degree: usize,
    span: usize,
    t: f64,
    max_order: usize,
) -> DMatrix<f64> {
    let p = degree;
    let n = max_order.min(p);
    let mut rows = vec![0.0; (n + 1) * (p + 1)];
    let mut work = vec![0.0; basis_work_len(p)];
    basis_derivatives_into(knots, p, span, t, n, &mut rows, &mut work);
    let mut ders = DMatrix::<f64>::zeros(max_order + 1, p + 1);
    for k in 0..=n {
        for j in 0..=p {
            ders[(k, j)] = rows[k * (p + 1) + j];
        }
    }
    ders
}

/// Length of the work buffer [`basis_derivatives_into`] needs for degree `p`.
pub(crate) const fn basis_work_len(p: usize) -> usize {
    (p + 1) * (p + 1) + 4 * (p + 1)
}

/// A2.3 into caller buffers, without allocation: `ders` receives
/// `(n + 1) x (p + 1)` values row-major (`n <= p`; row `k` holds the k-th
/// derivatives of `N_(span - p + j)`, `j = 0..=p`, at `t`), `work` holds at
/// least [`basis_work_len`]`(p)` values. The same arithmetic, in the same
/// order, as [`basis_derivatives`] (which calls it).
pub(crate) fn basis_derivatives_into(
    knots: &[f64],
    p: usize,
    span: usize,
    t: f64,
    n: usize,
    ders: &mut [f64],
    work: &mut [f64],
) {
    debug_assert!(n <= p && ders.len() >= (n + 1) * (p + 1));
    let m = p + 1;
    // ndu (m x m, row-major): lower triangle knot differences (then their
    // reciprocals), upper triangle basis functions.
    let (ndu, rest) = work.split_at_mut(m * m);
    let (left, rest) = rest.split_at_mut(m);
    let (right, rest) = rest.split_at_mut(m);
    let (a0, a1) = rest.split_at_mut(m);
    ndu[0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j * m + r] = right[r + 1] + left[j - r];
            let temp = ndu[r * m + j - 1] / ndu[j * m + r];
            ndu[r * m + j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j * m + j] = saved;
    }
    for j in 0..=p {
        ders[j] = ndu[j * m + p];
    }
    if n == 0 {
        return;
    }
    // Reciprocals of the knot differences (lower triangle of ndu), so that
    // the O(p^2 n) loop below multiplies instead of dividing.
    for j in 1..=p {
        for r in 0..j {
            ndu[j * m + r] = 1.0 / ndu[j * m + r];
        }
    }
    // Derivatives (Eq. 2.9), two alternating rows of coefficients.
    let a: [&mut [f64]; 2] = [a0, &mut a1[..m]];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=n {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2][0] = a[s1][0] * ndu[(pk + 1) * m + rk as usize];
                d = a[s2][0] * ndu[rk as usize * m + pk];
            }
            let j1: usize = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2: usize = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) * ndu[(pk + 1) * m + idx];
                d += a[s2][j] * ndu[idx * m + pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] * ndu[(pk + 1) * m + r];
                d += a[s2][k] * ndu[r * m + pk];
            }
            ders[k * m + r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for k in 1..=n {
        for j in 0..=p {
            ders[k * m + j] *= factor;
        }
        factor *= (p - k) as f64;
    }
}

/// The clamped Bezier knot vector `0^(n+1) 1^(n+1)`.
pub(crate) fn bezier_knots(degree: usize) -> Vec<f64> {
    let mut knots = vec![0.0; degree + 1];
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    knots
}

/// `D(t)`: the Bernstein basis of degree `degree` and its derivatives up to
/// `max_order` at `t`, through A2.3 on the knots `0^(n+1) 1^(n+1)`.
///
/// Row `k` holds the k-th derivatives of `B_0^n .. B_n^n`; `D(0)` is lower
/// triangular and `D(1)` anti-triangular (docs/mathematics.md#bezier-basics). Any
/// finite `t` is accepted (the polynomials are continued outside `[0, 1]`).
pub(crate) fn bezier_basis_derivatives(degree: usize, t: f64, max_order: usize) -> DMatrix<f64> {
    if degree == 0 {
        let mut d = DMatrix::zeros(max_order + 1, 1);
        d[(0, 0)] = 1.0;
        return d;
    }
    let knots = bezier_knots(degree);
    basis_derivatives(&knots, degree, degree, t, max_order)
}

/// Binomial coefficient `C(n, k)` as `f64` (exact while it is below 2^53).
pub(crate) fn binomial(n: usize, k: usize) -> f64 {
    if k > n {
        return 0.0;
    }
    let k = k.min(n - k);
    let mut c = 1.0f64;
    for i in 0..k {
        c = c * (n - i) as f64 / (i + 1) as f64;
    }
    c.round()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bernstein(n: usize, i: usize, t: f64) -> f64 {
        binomial(n, i) * t.powi(i as i32) * (1.0 - t).powi((n - i) as i32)
    }

    #[test]
    fn bezier_basis_is_bernstein_and_sums_to_one() {
        for n in 0..12 {
            for s in 0..=20 {
                let t = s as f64 / 20.0;
                let d = bezier_basis_derivatives(n, t, 0);
                let sum: f64 = d.row(0).iter().sum();
                assert!((sum - 1.0).abs() < 1e-14);
                for i in 0..=n {
                    assert!(
                        (d[(0, i)] - bernstein(n, i, t)).abs() < 1e-14,
                        "n={n} i={i} t={t}"
                    );
                }
            }
        }
    }

    #[test]
    fn d0_lower_triangular_and_d1_anti_triangular() {
        let n = 7;
        let d0 = bezier_basis_derivatives(n, 0.0, n);
        let d1 = bezier_basis_derivatives(n, 1.0, n);
        for k in 0..=n {
            for i in 0..=n {
                if i > k {
                    assert_eq!(d0[(k, i)], 0.0);
                }
                if i < n - k {
                    assert_eq!(d1[(k, i)], 0.0);
                } else {
                    assert_ne!(d1[(k, i)], 0.0);
                }
            }
        }
    }

    #[test]
    fn find_span_on_interior_knots_respects_side() {
        let knots = [0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0];
        assert_eq!(find_span(&knots, 2, 0.5, KnotSide::Right), 4);
        assert_eq!(find_span(&knots, 2, 0.5, KnotSide::Left), 2);
        assert_eq!(find_span(&knots, 2, 0.25, KnotSide::Right), 2);
        assert_eq!(find_span(&knots, 2, 0.75, KnotSide::Left), 4);
        assert_eq!(find_span(&knots, 2, 1.0, KnotSide::Right), 4);
        assert_eq!(find_span(&knots, 2, 0.0, KnotSide::Left), 2);
        assert_eq!(find_span(&knots, 2, -1.0, KnotSide::Right), 2);
        assert_eq!(find_span(&knots, 2, 2.0, KnotSide::Left), 4);
    }

    #[test]
    fn general_knot_basis_partition_of_unity_and_derivative_sums_vanish() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.2, 0.5, 0.5, 0.9, 1.0, 1.0, 1.0, 1.0];
        let p = 3;
        for s in 0..=50 {
            let t = s as f64 / 50.0;
            let span = find_span(&knots, p, t, KnotSide::Right);
            let d = basis_derivatives(&knots, p, span, t, 4);
            let sum0: f64 = d.row(0).iter().sum();
            assert!((sum0 - 1.0).abs() < 1e-13, "t={t}");
            for k in 1..=4 {
                let sk: f64 = d.row(k).iter().sum();
                assert!(sk.abs() < 1e-9, "k={k} t={t} sum={sk}");
            }
        }
    }
}
