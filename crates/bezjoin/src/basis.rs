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
    let mut ders = DMatrix::<f64>::zeros(max_order + 1, degree + 1);
    let mut scratch = vec![0.0; basis_scratch_len(degree)];
    // Column-major: entry (k, j) at k + j (max_order + 1).
    basis_derivatives_into(
        |i| knots[i],
        degree,
        span,
        t,
        max_order,
        BasisLayout {
            order_stride: 1,
            index_stride: max_order + 1,
        },
        ders.as_mut_slice(),
        &mut scratch,
    );
    ders
}

/// Where [`basis_derivatives_into`] writes entry `(k, j)` (derivative order
/// `k`, basis function `j`): at `k * order_stride + j * index_stride`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BasisLayout {
    pub(crate) order_stride: usize,
    pub(crate) index_stride: usize,
}

impl BasisLayout {
    /// Row-major `(max_order + 1) x (degree + 1)`: row `k` is contiguous.
    pub(crate) fn row_major(degree: usize) -> Self {
        Self {
            order_stride: degree + 1,
            index_stride: 1,
        }
    }
}

/// The scratch doubles [`basis_derivatives_into`] needs at degree `degree`:
/// `(p + 1)^2 + 4 (p + 1)`.
pub(crate) const fn basis_scratch_len(degree: usize) -> usize {
    (degree + 1) * (degree + 5)
}

/// A2.3 ([`basis_derivatives`]) into caller storage, without allocating:
/// knot `i` is `knot(i)`, the entries go to `ders` as `layout` says (rows
/// above `degree` are set to zero), `scratch` holds at least
/// [`basis_scratch_len`]`(degree)` doubles. The same operations in the same
/// order as ever, so the same values bit for bit whatever the storage.
#[allow(clippy::too_many_arguments)]
pub(crate) fn basis_derivatives_into(
    knot: impl Fn(usize) -> f64,
    degree: usize,
    span: usize,
    t: f64,
    max_order: usize,
    layout: BasisLayout,
    ders: &mut [f64],
    scratch: &mut [f64],
) {
    basis_derivatives_inline(knot, degree, span, t, max_order, layout, ders, scratch);
}

/// The body of [`basis_derivatives_into`], inlined into callers that know
/// the degree at compile time (the NURBS jets of small fixed degrees), so
/// that its loops are unrolled there: the same operations in the same order.
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub(crate) fn basis_derivatives_inline(
    knot: impl Fn(usize) -> f64,
    degree: usize,
    span: usize,
    t: f64,
    max_order: usize,
    layout: BasisLayout,
    ders: &mut [f64],
    scratch: &mut [f64],
) {
    let p = degree;
    let p1 = p + 1;
    let n = max_order.min(p);
    let at = |k: usize, j: usize| k * layout.order_stride + j * layout.index_stride;
    // ndu: lower triangle knot differences (then their reciprocals), upper
    // triangle basis functions; entry (j, r) at j * (p + 1) + r. Every entry
    // read below is written first.
    let (ndu, rest) = scratch[..basis_scratch_len(p)].split_at_mut(p1 * p1);
    let (left, rest) = rest.split_at_mut(p1);
    let (right, a) = rest.split_at_mut(p1);
    ndu[0] = 1.0;
    for j in 1..=p {
        left[j] = t - knot(span + 1 - j);
        right[j] = knot(span + j) - t;
        let mut saved = 0.0;
        for r in 0..j {
            ndu[j * p1 + r] = right[r + 1] + left[j - r];
            let temp = ndu[r * p1 + j - 1] / ndu[j * p1 + r];
            ndu[r * p1 + j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j * p1 + j] = saved;
    }
    for j in 0..=p {
        ders[at(0, j)] = ndu[j * p1 + p];
    }
    for k in n + 1..=max_order {
        for j in 0..=p {
            ders[at(k, j)] = 0.0;
        }
    }
    // Reciprocals of the knot differences (lower triangle of ndu), so that
    // the O(p^2 n) loop below multiplies instead of dividing.
    for j in 1..=p {
        for r in 0..j {
            ndu[j * p1 + r] = 1.0 / ndu[j * p1 + r];
        }
    }
    // Derivatives (Eq. 2.9), two alternating rows of coefficients (row s at
    // a[s * (p + 1)..]).
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, p1);
        a[0] = 1.0;
        for k in 1..=n {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                a[s2] = a[s1] * ndu[(pk + 1) * p1 + rk as usize];
                d = a[s2] * ndu[rk as usize * p1 + pk];
            }
            let j1: usize = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2: usize = if (r as isize - 1) <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2 + j] = (a[s1 + j] - a[s1 + j - 1]) * ndu[(pk + 1) * p1 + idx];
                d += a[s2 + j] * ndu[idx * p1 + pk];
            }
            if r <= pk {
                a[s2 + k] = -a[s1 + k - 1] * ndu[(pk + 1) * p1 + r];
                d += a[s2 + k] * ndu[r * p1 + pk];
            }
            ders[at(k, r)] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for k in 1..=n {
        for j in 0..=p {
            ders[at(k, j)] *= factor;
        }
        factor *= (p - k) as f64;
    }
}

/// `D(t)`: the Bernstein basis of degree `degree` and its derivatives up to
/// `max_order` at `t`, through A2.3 on the knots `0^(n+1) 1^(n+1)`.
///
/// Row `k` holds the k-th derivatives of `B_0^n .. B_n^n`; `D(0)` is lower
/// triangular and `D(1)` anti-triangular (docs/mathematics.md#bezier-basics). Any
/// finite `t` is accepted (the polynomials are continued outside `[0, 1]`).
pub(crate) fn bezier_basis_derivatives(degree: usize, t: f64, max_order: usize) -> DMatrix<f64> {
    let mut d = DMatrix::zeros(max_order + 1, degree + 1);
    let mut scratch = vec![0.0; basis_scratch_len(degree)];
    let layout = BasisLayout {
        order_stride: 1,
        index_stride: max_order + 1,
    };
    bezier_basis_derivatives_into(degree, t, max_order, layout, d.as_mut_slice(), &mut scratch);
    d
}

/// [`bezier_basis_derivatives`] into caller storage (as
/// [`basis_derivatives_into`]; `ders` entirely written), without
/// allocating: A2.3 on the knots `0^(n+1) 1^(n+1)`, read as `knot(i) = 0`
/// for `i <= n` and 1 above, with no knot vector built.
pub(crate) fn bezier_basis_derivatives_into(
    degree: usize,
    t: f64,
    max_order: usize,
    layout: BasisLayout,
    ders: &mut [f64],
    scratch: &mut [f64],
) {
    if degree == 0 {
        for k in 0..=max_order {
            ders[k * layout.order_stride] = if k == 0 { 1.0 } else { 0.0 };
        }
        return;
    }
    let knot = |i: usize| if i <= degree { 0.0 } else { 1.0 };
    basis_derivatives_into(knot, degree, degree, t, max_order, layout, ders, scratch);
}

/// Pascal's triangle as a square table: `C(r, k)` at `[r][k]` for
/// `r, k < N`, zero for `k > r` (exact integers for the sizes used, far
/// below `2^53`).
pub(crate) const fn pascal_square<const N: usize>() -> [[f64; N]; N] {
    let mut table = [[0.0; N]; N];
    let mut r = 0;
    while r < N {
        let mut c = 1u64;
        let mut k = 0;
        while k <= r {
            table[r][k] = c as f64;
            c = c * (r - k) as u64 / (k + 1) as u64;
            k += 1;
        }
        r += 1;
    }
    table
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
