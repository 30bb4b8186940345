//! The orthogonal path of stage 1 (no piece kept): the merged curve `R`
//! itself is the unknown, the continuity conditions (3) are eliminated by
//! construction, and the metric is minimised by Householder QR of a
//! well-scaled sample matrix; no KKT system, no Gram matrix.
//!
//! With `R`'s control points `r` (`(m + 1) x dim`) the pieces are `S_j r`
//! (`S_j` the exact restriction of `R` to `[t_j, t_{j+1}]`), so every `r`
//! satisfies (3) and the feasible set of (3) is exactly `{S r}` (`S` the
//! stacked `S_j`, full column rank): a basis of the null space of the
//! continuity rows without forming them. The metric is a least-squares
//! norm `||M r - b||^2`:
//!
//! * discrete: `M = S`, `b` the input control points;
//! * integral: the rows of `M` are `sqrt(w_k) B^m(t_j + h_j u_k)` (Bernstein
//!   values of `R` at the Gauss-Legendre nodes `u_k` of each piece, `m + 1`
//!   nodes: exact for the degree-`2m` integrand), `b` the rows
//!   `sqrt(w_k) C_j(u_k)`. This is `W^(1/2) B S` in exact arithmetic: the
//!   Gram matrix `B^T W B` is never formed, so its condition (`1e16` near
//!   degree 25) is never squared into the answer.
//!
//! Fix ends and keep points are rows on the pieces, `G x = G x0`, hence on
//! `r`: `(G S) r = G x0`. They are orthonormalised (Gram-Schmidt, two
//! passes, dependent rows set aside to be checked at the answer), a
//! particular solution `r_p` and an orthonormal null-space basis `Z` of the
//! kept rows follow, and the reduced problem `min ||M Z y - (b - M r_p)||`
//! is solved by QR. The pieces are then `R` split at the breakpoints by de
//! Casteljau (convex combinations), and `R` is stage 2's answer directly.
//!
//! **Error estimate** (first order, a posteriori: measured on the answer's
//! own factor and residual, componentwise). With `A = M Z = Q T`, the
//! pieces move by `S Z delta_y`, and a perturbation `delta_A`, `delta_t`
//! of the sample matrix and the target moves `y` by `A^+ (delta_t -
//! delta_A y) + (A^T A)^-1 delta_A^T res`. Every entry of `A` and `t`
//! carries a relative rounding of at most `gamma`, so, entry by entry,
//!
//! ```text
//! |delta x| <= gamma (|K1| (|t| + |A| |y|) + |K2| |A|^T |res|),
//! K1 = S Z A^+ = S Z T^-1 Q^T,  K2 = S Z T^-1 T^-T
//! ```
//!
//! for every coordinate (the rounding of the entries; the same with `Z`
//! in place of `S Z` bounds `R`'s own control points, and the estimate is
//! the larger). The solve is refined twice in working precision (the
//! correction from the residual through the same factor, which makes it
//! componentwise backward stable); the last correction, mapped, times
//! [`REFINEMENT_MARGIN`] is the a-posteriori part for the solve's own
//! rounding; and, for the pieces, the same first-order bound with norms
//! for the QR's normwise backward error ([`QR_MARGIN`] `eps sqrt(rows
//! cols) ||A||_F`), which the refinement does not remove entirely. Plus
//! the kept rows' own rounding magnified by
//! their condition, plus the de Casteljau rounding of the pieces. `K1`,
//! `K2` map straight to the pieces' control points, and the absolute
//! values keep the structure of the Bernstein sample matrices (totally
//! positive: a relative change of their entries moves the answer far less
//! than their condition number says), so the bound follows the pieces'
//! actual sensitivity; measured against an exact rational reference in
//! test `merge_exact`.

use std::sync::OnceLock;

use nalgebra::{DMatrix, DMatrixView, DVector};

use crate::basis::binomial;
use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

use super::MergeMetric;
use super::columns::{Columns, Parts, ZeroBuffer, nalgebra_dot_sized};
use super::lsq::{self, Factor};
use super::rows::{Problem, Row, check_dependent_rows, extend_orthonormal};
use super::stage_one::{CONSISTENCY_TOLERANCE, RANK_TOLERANCE};
use super::stage_two::restriction_matrix;

/// The rounding `gamma` of the first-order estimate is this times
/// `(m + 2) eps` relative per entry of the sample matrix and the target
/// (measured margin: test `merge_exact`, degrees 1..30, every case
/// bounded).
pub const ESTIMATE_MARGIN: f64 = 4.0;

/// Weight of `R`'s own control-point bound in the estimate. The curve `R`
/// is its pieces (the promise is about them), but its control points are
/// less well determined than theirs; their componentwise bound overstates
/// their true error 200..350x (test `merge_accuracy`, degrees 20..30,
/// merge back of a split curve), so it enters with this measured weight
/// (a margin of about 4 left there): a guard against returning control
/// points of `R` far off while the pieces are fine, not a proven bound.
pub const MERGED_WEIGHT: f64 = 1.0 / 64.0;

/// The normwise backward error of the Householder QR solve in the
/// estimate of the pieces: this times `eps sqrt(rows columns)` times
/// `||A||_F` (measured margin: test `merge_exact`).
pub const QR_MARGIN: f64 = 4.0;

/// Refinement steps of the least-squares solve (working precision).
pub const REFINEMENT_STEPS: usize = 2;

/// The last refinement correction, mapped to the pieces or `R`, times this
/// is the estimate's part for the solve's own rounding.
pub const REFINEMENT_MARGIN: f64 = 8.0;

/// What a solve of the orthogonal path returns.
pub(super) struct Orthogonal {
    /// `R`'s control points, `(m + 1) x dim`.
    pub(super) merged: DMatrix<f64>,
    /// The pieces `R|[t_j, t_{j+1}]`, stacked, `(count (m + 1)) x dim`.
    pub(super) x: DMatrix<f64>,
    /// Relative error estimate of the pieces (0 for a trial).
    pub(super) estimate: f64,
    /// `||M r - b||^2`, the metric measured at the answer.
    pub(super) metric_value: f64,
    /// `d metric / d mu` (two pieces, rows independent of `mu`), by the
    /// envelope theorem: the derivative of `||M(mu) r - b||^2` at the
    /// optimal, fixed `r`.
    pub(super) slope: Option<f64>,
    /// `x` is `R` split at `mu` by the de Casteljau steps of
    /// [`BezierCurve::split_unchecked`] (two pieces, the double solve), so
    /// stage 2's split of `R` gives it back bit for bit.
    pub(super) split_of_merged: bool,
    /// `lsq::amax(x)` against the problem's scale, the larger, when it was
    /// computed (the full check of the double solve's `x`): the result
    /// scale stage 1 measures its residuals against.
    pub(super) result_scale: Option<f64>,
}

/// Gauss-Legendre nodes and weights on `[0, 1]` (`count` nodes, exact for
/// polynomials of degree `2 count - 1`): Newton's method on the Legendre
/// polynomial from the asymptotic guesses, to full precision.
pub(crate) fn gauss_legendre_unit(count: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; count];
    let mut weights = vec![0.0; count];
    let n = count as f64;
    for i in 0..count.div_ceil(2) {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            // Legendre recurrence: p = P_count(x), derivative = P'_count(x).
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=count {
                let k = k as f64;
                let p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            let p = if count == 0 { 1.0 } else { p1 };
            let p_prev = if count == 1 { 1.0 } else { p0 };
            derivative = n * (x * p - p_prev) / (x * x - 1.0);
            let step = p / derivative;
            x -= step;
            if step.abs() <= 1e-16 * x.abs().max(1e-300) {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
        // x runs from near +1 down; map [-1, 1] to [0, 1].
        nodes[count - 1 - i] = 0.5 * (1.0 + x);
        nodes[i] = 0.5 * (1.0 - x);
        weights[count - 1 - i] = 0.5 * w;
        weights[i] = 0.5 * w;
    }
    (nodes, weights)
}

/// Node counts whose Gauss-Legendre rule (double here, double-double in
/// module `refine`) is computed once and kept ([`stored_per_count`]).
pub(super) const STORED_RULES: usize = 64;

/// `make(count)`, computed once and kept in `slots[count]`; counts past
/// the slots are computed on each call (the same values either way).
pub(super) fn stored_per_count<T: Clone>(
    slots: &'static [OnceLock<T>],
    count: usize,
    make: impl FnOnce(usize) -> T,
) -> std::borrow::Cow<'static, T> {
    match slots.get(count) {
        Some(slot) => std::borrow::Cow::Borrowed(slot.get_or_init(|| make(count))),
        None => std::borrow::Cow::Owned(make(count)),
    }
}

/// [`gauss_legendre_unit`]`(count)`, computed once per count up to
/// [`STORED_RULES`].
fn gauss_legendre_stored(count: usize) -> std::borrow::Cow<'static, (Vec<f64>, Vec<f64>)> {
    static RULES: [OnceLock<(Vec<f64>, Vec<f64>)>; STORED_RULES + 1] =
        [const { OnceLock::new() }; STORED_RULES + 1];
    stored_per_count(&RULES, count, gauss_legendre_unit)
}

/// All Bernstein values `B_i^m(t)`, `i = 0..m`, into `out` (product form
/// with exact binomials).
fn bernstein_row(m: usize, t: f64, out: &mut [f64]) {
    let s = 1.0 - t;
    // out[i] = C(m,i) t^i, then times s^(m-i) from the right.
    let mut tp = 1.0;
    for (i, o) in out.iter_mut().enumerate().take(m + 1) {
        *o = binomial(m, i) * tp;
        tp *= t;
    }
    let mut sp = 1.0;
    for i in (0..=m).rev() {
        out[i] *= sp;
        sp *= s;
    }
}

/// [`restrictions_into`] as a new matrix (the tests' form).
#[cfg(test)]
fn restrictions(m: usize, breakpoints: &[f64]) -> DMatrix<f64> {
    let mut s = DMatrix::zeros((breakpoints.len() - 1) * (m + 1), m + 1);
    restrictions_into(m, breakpoints, s.as_mut_slice());
    s
}

/// The stacked restriction matrices `[S_0; S_1; ...]` (`R`'s control
/// points to the pieces') into the column-major `data` (`count (m + 1) x
/// (m + 1)`, all zero). Two pieces: from the Bernstein triangle at `mu`,
/// `S_L[i][k] = B_k^i(mu)`, `S_R[i][k] = B_(k-i)^(m-i)(mu)`; more: segment
/// of every unit vector.
fn restrictions_into(m: usize, breakpoints: &[f64], data: &mut [f64]) {
    if breakpoints.len() != 3 {
        data.copy_from_slice(restriction_matrix(m, breakpoints).as_slice());
        return;
    }
    let mu = breakpoints[1];
    match m + 1 {
        2 => restrictions_two::<2>(m, mu, data),
        3 => restrictions_two::<3>(m, mu, data),
        4 => restrictions_two::<4>(m, mu, data),
        5 => restrictions_two::<5>(m, mu, data),
        6 => restrictions_two::<6>(m, mu, data),
        7 => restrictions_two::<7>(m, mu, data),
        8 => restrictions_two::<8>(m, mu, data),
        _ => restrictions_two::<0>(m, mu, data),
    }
}

/// [`restrictions_into`] for two pieces split at `mu`, with `P = m + 1`
/// points known at compile time (`0`: not): the same operations in the
/// same order.
#[inline(always)]
fn restrictions_two<const P: usize>(m: usize, mu: f64, data: &mut [f64]) {
    let points = if P == 0 { m + 1 } else { P };
    let m = points - 1;
    let rows = 2 * points;
    let data = &mut data[..rows * points];
    // The triangle `B_k^i(mu)` is S_L itself: built in place in the top
    // block (column-major, entry (i, k) at `k rows + i`), no other storage.
    data[0] = 1.0;
    for i in 1..points {
        for k in 0..=i {
            let from_same = if k < i {
                (1.0 - mu) * data[k * rows + i - 1]
            } else {
                0.0
            };
            let from_below = if k > 0 {
                mu * data[(k - 1) * rows + i - 1]
            } else {
                0.0
            };
            data[k * rows + i] = from_same + from_below;
        }
    }
    // S_R[i][k] = B_(k-i)^(m-i)(mu), from the top block's row m - i.
    for i in 0..points {
        for k in i..points {
            data[k * rows + points + i] = data[(k - i) * rows + m - i];
        }
    }
}

/// Whether `a * b` (`a` `rows x inner`, `b` `inner x cols`) is one that
/// nalgebra hands to `matrixmultiply` (its `gemm` does for dynamic
/// matrices with every dimension above 5), whose kernels sum in another
/// order: [`product_into`] then defers to nalgebra.
fn blocked_product(rows: usize, inner: usize, cols: usize) -> bool {
    rows > 5 && cols > 5 && inner > 5
}

/// `a * b` into the column-major `out` (`rows x cols`), the same values as
/// nalgebra's `a * b` bit for bit: its `gemm` on small matrices is column
/// axpys, entry `(i, j)` being `a[i][0] b[0][j]` and then
/// `a[i][k] b[k][j] + sum` for `k = 1..` in order (no fused multiply-add; an empty inner
/// dimension gives `0`), done here the same way on slices;
/// `matrixmultiply`'s case is nalgebra's own product. No temporary but in
/// that case. `abs`: of `|a| |b|` (entries' absolute values, exact), as
/// nalgebra's `a.abs() * b.abs()`.
fn product_into<'a, 'b>(
    a: impl Into<Columns<'a>>,
    b: impl Into<Columns<'b>>,
    abs: bool,
    out: &mut [f64],
) {
    let (a, b) = (a.into(), b.into());
    let (rows, inner, cols) = (a.nrows(), a.ncols(), b.ncols());
    debug_assert!(inner == b.nrows() && out.len() == rows * cols);
    if blocked_product(rows, inner, cols) {
        let (a, b) = (a.view(), b.view());
        let product = if abs { a.abs() * b.abs() } else { a * b };
        out.copy_from_slice(product.as_slice());
        return;
    }
    if inner == 0 || rows == 0 {
        out.fill(0.0);
        return;
    }
    product_columns(a, b.as_slice(), abs, out);
}

/// `out = a b` for the columns of `b` (`a.ncols()` entries each, at least
/// one; `out` column-major with `a.nrows()` rows), each as nalgebra's
/// small `gemm` (see [`product_into`]): `a[:, 0] b_0`, then `a[:, k] b_k +
/// out` in order; with `abs`, of `|a|` and `|b|`. The merge's small row
/// counts as constants ([`product_columns_sized`]), chosen once for all
/// columns.
#[inline(always)]
fn product_columns<'a>(a: impl Into<Columns<'a>>, b: &[f64], abs: bool, out: &mut [f64]) {
    let a = a.into();
    let rows = a.nrows();
    debug_assert_eq!(out.len() * a.ncols(), b.len() * rows);
    let a = a.as_slice();
    match rows {
        4 => product_columns_sized::<4>(a, rows, b, abs, out),
        6 => product_columns_sized::<6>(a, rows, b, abs, out),
        8 => product_columns_sized::<8>(a, rows, b, abs, out),
        10 => product_columns_sized::<10>(a, rows, b, abs, out),
        12 => product_columns_sized::<12>(a, rows, b, abs, out),
        _ => product_columns_sized::<0>(a, rows, b, abs, out),
    }
}

/// [`product_columns`] with `N` rows known at compile time (`N = 0`:
/// `rows`): per entry the same operations in the same order.
#[inline(always)]
fn product_columns_sized<const N: usize>(
    a: &[f64],
    rows: usize,
    b: &[f64],
    abs: bool,
    out: &mut [f64],
) {
    let rows = if N == 0 { rows } else { N };
    // At least 1 for the chunks (no inner entries: no columns of `b`).
    let inner = (a.len() / rows).max(1);
    let value = |x: f64| if abs { x.abs() } else { x };
    for (bj, out) in b.chunks_exact(inner).zip(out.chunks_exact_mut(rows)) {
        let out = &mut out[..rows];
        for (k, (ak, &bk)) in a.chunks_exact(rows).zip(bj).enumerate() {
            let ak = &ak[..rows];
            let bk = value(bk);
            if k == 0 {
                out.iter_mut()
                    .zip(ak)
                    .for_each(|(o, &x)| *o = value(x) * bk);
            } else {
                out.iter_mut()
                    .zip(ak)
                    .for_each(|(o, &x)| *o += value(x) * bk);
            }
        }
    }
}

/// nalgebra's `dot` of two dynamic columns bit for bit, of `|a|` and
/// `|b|` ([`nalgebra_dot_sized`]).
#[inline(always)]
fn nalgebra_dot_abs(a: &[f64], b: &[f64]) -> f64 {
    nalgebra_dot_sized::<0, true>(a, b)
}

/// [`nalgebra_dot_abs`] with the length `N` known at compile time (`0`:
/// `a.len()`): the same operations in the same order.
#[inline(always)]
fn nalgebra_dot_abs_sized<const N: usize>(a: &[f64], b: &[f64]) -> f64 {
    nalgebra_dot_sized::<N, true>(a, b)
}

/// [`abs_tr_mul_into`] into a new matrix (the tests' form).
#[cfg(test)]
fn abs_tr_mul(a: &DMatrix<f64>, b: &DMatrix<f64>) -> DMatrix<f64> {
    let rows = a.nrows();
    debug_assert_eq!(rows, b.nrows());
    let mut out = DMatrix::zeros(a.ncols(), b.ncols());
    abs_tr_mul_into(a.into(), b.into(), out.as_mut_slice());
    out
}

/// `a.abs().tr_mul(&b.abs())` bit for bit (nalgebra's: entry `(i, j)` the
/// `dot` of column `i` of `|a|` and column `j` of `|b|`,
/// [`nalgebra_dot_abs`]), into the column-major `out` (`a.ncols() x
/// b.ncols()`), without the matrices `|a|` and `|b|`.
fn abs_tr_mul_into(a: Columns<'_>, b: Columns<'_>, out: &mut [f64]) {
    let rows = a.nrows();
    debug_assert_eq!(out.len(), a.ncols() * b.ncols());
    if rows == 0 {
        out.fill(0.0);
        return;
    }
    for (bj, oj) in b
        .as_slice()
        .chunks_exact(rows)
        .zip(out.chunks_exact_mut(a.ncols().max(1)))
    {
        for (ai, o) in a.as_slice().chunks_exact(rows).zip(oj.iter_mut()) {
            // The merge's small row counts as constants.
            *o = match rows {
                4 => nalgebra_dot_abs_sized::<4>(ai, bj),
                6 => nalgebra_dot_abs_sized::<6>(ai, bj),
                8 => nalgebra_dot_abs_sized::<8>(ai, bj),
                10 => nalgebra_dot_abs_sized::<10>(ai, bj),
                12 => nalgebra_dot_abs_sized::<12>(ai, bj),
                _ => nalgebra_dot_abs(ai, bj),
            };
        }
    }
}

/// [`abs_into`] as a new matrix (the tests' form).
#[cfg(test)]
fn abs_of(m: &DMatrix<f64>) -> DMatrix<f64> {
    let mut out = m.clone();
    abs_into(m.into(), out.as_mut_slice());
    out
}

/// `m.abs()` (nalgebra's, entry by entry) into the column-major `out`.
fn abs_into(m: Columns<'_>, out: &mut [f64]) {
    for (o, v) in out.iter_mut().zip(m.as_slice()) {
        *o = v.abs();
    }
}

/// [`combined_product`]`(c, m, p, Minus)` (`abs`: `PlusAbs`) for the fixed
/// ends' particular solution `p`, whose rows `1..k` (`k = p.nrows() - 1`)
/// are exactly `+0` and `m`'s entries finite and `>= +0` (Bernstein
/// values), from the two nonzero rows alone: entry `(i, c)` of the product
/// is `a + (+0) + ... + (+0) + b` with `a = m[i][0] p[0][c]`, `b = m[i][k]
/// p[k][c]` (the products by the zero rows are exactly `+0`), i.e. `(a +
/// 0) + b` when there is a zero row (`a + 0` is `a`, but `+0` for `a =
/// -0`) and `a + b` otherwise: the same values.
#[cfg(test)]
fn ends_product(c: &DMatrix<f64>, m: &DMatrix<f64>, p: &DMatrix<f64>, abs: bool) -> DMatrix<f64> {
    let mut out = DMatrix::zeros(c.nrows(), c.ncols());
    ends_product_into(c.into(), false, m.into(), p.into(), abs, out.as_mut_slice());
    out
}

/// `ends_product` (test-only) into the column-major `out` (`c`'s shape), with `c`
/// replaced by `|c|` when `c_abs` (entry by entry, exact: the same values
/// as passing `abs_of(c)`, one matrix fewer).
fn ends_product_into(
    c: Columns<'_>,
    c_abs: bool,
    m: Columns<'_>,
    p: Columns<'_>,
    abs: bool,
    out: &mut [f64],
) {
    let rows = m.nrows();
    let k = p.nrows() - 1;
    debug_assert!(k >= 1 && m.ncols() == k + 1 && c.shape() == (rows, p.ncols()));
    let (first, last) = (
        &m.as_slice()[..rows],
        &m.as_slice()[k * rows..(k + 1) * rows],
    );
    for (col, ((oc, cc), pc)) in out
        .chunks_exact_mut(rows)
        .zip(c.as_slice().chunks_exact(rows))
        .zip(p.as_slice().chunks_exact(k + 1))
        .enumerate()
    {
        debug_assert!(pc[1..k].iter().all(|v| v.to_bits() == 0), "column {col}");
        let (p0, pk) = if abs {
            (pc[0].abs(), pc[k].abs())
        } else {
            (pc[0], pc[k])
        };
        for (((o, &x), &f), &l) in oc.iter_mut().zip(cc).zip(first).zip(last) {
            let x = if c_abs { x.abs() } else { x };
            let (f, l) = if abs { (f.abs(), l.abs()) } else { (f, l) };
            let a = f * p0;
            let sum = if k >= 2 {
                (a + 0.0) + l * pk
            } else {
                a + l * pk
            };
            *o = if abs { x + sum } else { x - sum };
        }
    }
}

/// How [`combined_product`] joins `c` and the product.
#[derive(Clone, Copy)]
enum Combine {
    /// `c + a b`.
    Plus,
    /// `c + |a| |b|`.
    PlusAbs,
    /// `c - a b`.
    Minus,
}

/// `c + a b`, `c + |a| |b|` or `c - a b` (`c` as `a b` is `rows x
/// cols`): the product as nalgebra's ([`product_into`]), then joined with
/// `c` entry by entry, the same values as nalgebra's `c + a * b` (and the
/// others) with one matrix allocated.
fn combined_product<'c, 'a, 'b>(
    c: impl Into<Columns<'c>>,
    a: impl Into<Columns<'a>>,
    b: impl Into<Columns<'b>>,
    how: Combine,
) -> DMatrix<f64> {
    let c = c.into();
    let mut out = DMatrix::zeros(c.nrows(), c.ncols());
    combined_product_into(c, a.into(), b.into(), how, out.as_mut_slice());
    out
}

/// [`combined_product`] into the column-major `out` (`c`'s shape).
fn combined_product_into(
    c: Columns<'_>,
    a: Columns<'_>,
    b: Columns<'_>,
    how: Combine,
    out: &mut [f64],
) {
    product_into(a, b, matches!(how, Combine::PlusAbs), out);
    let joined = out.iter_mut().zip(c.as_slice());
    match how {
        Combine::Plus | Combine::PlusAbs => joined.for_each(|(o, &x)| *o += x),
        Combine::Minus => joined.for_each(|(o, &x)| *o = x - *o),
    }
}

/// [`integral_samples`]' `(M, b, what b's rounding is relative to)`.
type IntegralSamples = (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>);

/// The integral metric's sample matrix `M` and target `b` (see the
/// module), and what the target's rounding is relative to; `None` for the
/// discrete metric, whose `M` and `b` are `S` and `x0` themselves and whose
/// target's rounding is relative to `|b|` (taken where it is used).
fn integral_samples(
    problem: &Problem<'_, '_>,
    breakpoints: &[f64],
    metric: MergeMetric,
) -> Option<IntegralSamples> {
    match metric {
        MergeMetric::Discrete => None,
        MergeMetric::Integral => {
            let points = problem.points_per_piece;
            let m = points - 1;
            let count = problem.pieces.len();
            let dim = problem.dim;
            let rule = gauss_legendre_stored(points);
            let (nodes, weights) = (&rule.0, &rule.1);
            let mut samples = DMatrix::zeros(count * points, points);
            let mut target = DMatrix::zeros(count * points, dim);
            // sqrt(w_k) sum_i B_i(u_k) |P_i|: the size the target's
            // rounding is relative to (the values may cancel).
            let mut target_abs = DMatrix::zeros(count * points, dim);
            let mut own = vec![0.0; points];
            let mut row = vec![0.0; points];
            let mut value = vec![0.0; dim];
            for (j, piece) in problem.pieces.iter().enumerate() {
                let (t0, t1) = (breakpoints[j], breakpoints[j + 1]);
                for (k, (&u, &w)) in nodes.iter().zip(weights.iter()).enumerate() {
                    let root = w.sqrt();
                    bernstein_row(m, t0 + (t1 - t0) * u, &mut row);
                    for i in 0..points {
                        samples[(j * points + k, i)] = root * row[i];
                    }
                    piece.curve.eval_into(u, &mut value);
                    bernstein_row(m, u, &mut own);
                    for c in 0..dim {
                        target[(j * points + k, c)] = root * value[c];
                        target_abs[(j * points + k, c)] = root
                            * (0..points)
                                .map(|i| own[i] * piece.curve.point(i)[c].abs())
                                .sum::<f64>();
                    }
                }
            }
            Some((samples, target, target_abs))
        }
    }
}

/// `d/d mu` of the samples `M(mu) r` at fixed `r`, two pieces: discrete,
/// the control points of `u R'(mu u)` and `(1 - v) R'(mu + (1 - mu) v)`;
/// integral, `sqrt(w_k)` times those functions at the nodes.
fn sample_slopes(
    merged: &DMatrix<f64>,
    breakpoints: &[f64],
    metric: MergeMetric,
) -> Result<DMatrix<f64>> {
    let points = merged.nrows();
    let m = points - 1;
    let dim = merged.ncols();
    let mu = breakpoints[1];
    let mut out = DMatrix::zeros(2 * points, dim);
    if m == 0 {
        return Ok(out);
    }
    let hodograph = BezierCurve::from_matrix(merged)?.hodograph();
    match metric {
        MergeMetric::Discrete => {
            let (left, right) = hodograph.split_unchecked(mu);
            let scale = 1.0 / m as f64;
            for i in 1..=m {
                let d = left.point(i - 1);
                for c in 0..dim {
                    out[(i, c)] = i as f64 * scale * d[c];
                }
            }
            for i in 0..m {
                let e = right.point(i);
                for c in 0..dim {
                    out[(points + i, c)] = (m - i) as f64 * scale * e[c];
                }
            }
        }
        MergeMetric::Integral => {
            let rule = gauss_legendre_stored(points);
            let (nodes, weights) = (&rule.0, &rule.1);
            let mut value = vec![0.0; dim];
            for (k, (&u, &w)) in nodes.iter().zip(weights.iter()).enumerate() {
                let root = w.sqrt();
                hodograph.eval_into(mu * u, &mut value);
                for c in 0..dim {
                    out[(k, c)] = root * u * value[c];
                }
                hodograph.eval_into(mu + (1.0 - mu) * u, &mut value);
                for c in 0..dim {
                    out[(points + k, c)] = root * (1.0 - u) * value[c];
                }
            }
        }
    }
    Ok(out)
}

/// Orthonormal completion of the orthonormal rows `basis` (length `n`):
/// `n - basis.len()` columns orthogonal to them and to each other (greedy
/// Gram-Schmidt on the unit vectors, largest remainder first).
fn null_space(basis: &[(DVector<f64>, DVector<f64>)], n: usize) -> DMatrix<f64> {
    let mut vectors: Vec<DVector<f64>> = basis.iter().map(|(b, _)| b.clone()).collect();
    let mut columns = Vec::with_capacity(n - basis.len());
    while vectors.len() < n {
        let mut best: Option<DVector<f64>> = None;
        let mut best_norm = -1.0;
        for k in 0..n {
            let mut v = DVector::zeros(n);
            v[k] = 1.0;
            for _ in 0..2 {
                for b in &vectors {
                    let dot = b.dot(&v);
                    v.axpy(-dot, b, 1.0);
                }
            }
            let norm = v.norm();
            if norm > best_norm {
                best_norm = norm;
                best = Some(v);
            }
        }
        let v = best.expect("n > 0") / best_norm;
        vectors.push(v.clone());
        columns.push(v);
    }
    if columns.is_empty() {
        return DMatrix::zeros(n, 0);
    }
    DMatrix::from_columns(&columns)
}

/// The constraint rows on `r`: `(G S) r = G x0 + rhs`, scaled to unit
/// length.
fn constraint_rows_on_r<'s>(problem: &Problem<'_, '_>, s: impl Into<Columns<'s>>) -> Vec<Row> {
    let s = s.into().view();
    let x0 = problem.x0().view();
    problem
        .constraints()
        .iter()
        .map(|row| {
            let coefficients = s.tr_mul(&row.coefficients);
            let rhs = x0.tr_mul(&row.coefficients) + &row.rhs;
            let norm = coefficients.norm();
            if norm > 0.0 {
                Row {
                    coefficients: coefficients / norm,
                    rhs: rhs / norm,
                    label: row.label.clone(),
                }
            } else {
                Row {
                    coefficients,
                    rhs,
                    label: row.label.clone(),
                }
            }
        })
        .collect()
}

/// The feasible set `{r_p + Z y}` of the constraint rows on `r`, its
/// matrices in parts of the solve's buffer.
struct Feasible<'r, 'a> {
    /// Rows kept (independent) and dependent (checked at the answer).
    kept: Vec<&'r Row>,
    dependent: Vec<&'r Row>,
    /// The particular solution `r_p` (`(m + 1) x dim`).
    particular: Columns<'a>,
    /// The orthonormal null-space basis `Z` (`None`: no kept rows).
    free: usize,
    z: Option<Columns<'a>>,
    /// `Z` is `e_1, ..., e_(m-1)` (the fixed ends' closed form): `M Z` is
    /// columns `1..m` of `M`, and `Z`'s zero rows `0` and `m` carry nothing
    /// into `R`'s guard.
    selection: bool,
    /// The number of kept rows and their condition number (`None`: none).
    kept_condition: Option<(usize, f64)>,
}

impl<'r, 'a> Feasible<'r, 'a> {
    /// Any rows: Gram-Schmidt (two passes), the particular solution from
    /// the orthonormal rows, the greedy null-space completion, the kept
    /// rows' condition from their singular values.
    fn general(
        rows_r: &'r [Row],
        problem: &Problem<'_, '_>,
        points: usize,
        parts: &mut Parts<'a>,
    ) -> Self {
        let mut basis: Vec<(DVector<f64>, DVector<f64>)> = Vec::new();
        let rank_tolerance = RANK_TOLERANCE * (problem.unknowns as f64).sqrt();
        let (kept, dependent) = extend_orthonormal(&mut basis, rows_r, rank_tolerance, points);
        let mut particular = DMatrix::zeros(points, problem.dim);
        for (b, rhs) in &basis {
            particular.ger(1.0, b, rhs, 1.0);
        }
        let particular = parts.matrix(points, problem.dim, |p| {
            p.copy_from_slice(particular.as_slice())
        });
        let z = (!basis.is_empty()).then(|| {
            let z = null_space(&basis, points);
            parts.matrix(points, z.ncols(), |p| p.copy_from_slice(z.as_slice()))
        });
        let kept_condition = (!kept.is_empty()).then(|| {
            let g = DMatrix::from_fn(kept.len(), points, |k, i| kept[k].coefficients[i]);
            let singular = g.singular_values();
            (
                kept.len(),
                singular.max() / singular.min().max(f64::MIN_POSITIVE),
            )
        });
        Self {
            kept,
            dependent,
            particular,
            free: points - basis.len(),
            z,
            selection: false,
            kept_condition,
        }
    }

    /// Two pieces whose only constraints are the fixed ends (degree `m >=
    /// 1`): the rows on `r` are exactly `e_0` and `e_m` (the first row of
    /// `S_L` and the last of `S_R` are unit rows), with right-hand sides
    /// `P_0` and `Q_m`, so Gram-Schmidt keeps both unchanged, the
    /// particular solution is `r_0 = P_0`, `r_m = Q_m` (zero elsewhere),
    /// the greedy null-space completion is `e_1, ..., e_(m-1)` in that
    /// order (every other unit vector has remainder 1, the first wins), and
    /// the kept rows are orthonormal (condition 1): what [`Feasible::general`]
    /// computes, in closed form, without building the rows.
    fn fixed_ends(x0: Columns<'_>, dim: usize, m: usize, parts: &mut Parts<'a>) -> Self {
        let points = m + 1;
        let particular = parts.matrix(points, dim, |p| {
            for (column, from) in p
                .chunks_exact_mut(points)
                .zip(x0.as_slice().chunks_exact(2 * points))
            {
                column[0] = from[0];
                column[m] = from[2 * points - 1];
            }
        });
        let z = parts.matrix(points, m - 1, |z| {
            z.iter_mut()
                .skip(1)
                .step_by(points + 1)
                .for_each(|e| *e = 1.0);
        });
        Self {
            kept: Vec::new(),
            dependent: Vec::new(),
            particular,
            free: m - 1,
            z: Some(z),
            selection: true,
            kept_condition: Some((2, 1.0)),
        }
    }
}

/// Stage 1 by the orthogonal path. `full`: every check and the error
/// estimate (every answer a caller receives); otherwise a trial of the
/// `mu` search (value and slope only, no refusal for conditioning).
/// `want_slope`: two pieces and rows independent of `mu` (no keep points).
pub(super) fn orthogonal_solution(
    problem: &Problem<'_, '_>,
    breakpoints: &[f64],
    metric: MergeMetric,
    accuracy: f64,
    full: bool,
    want_slope: bool,
) -> Result<Orthogonal> {
    let points = problem.points_per_piece;
    let m = points - 1;
    let count = problem.pieces.len();
    let dim = problem.dim;
    let x0 = problem.x0();
    // The samples' rows (both metrics: `points` per piece).
    let rows = count * points;
    // The intermediate matrices in parts of two buffers, on the stack for
    // small degrees (each below the size where glibc's `memset` switches
    // to `rep stosb`): `S`, `r_p` and `Z`, then, once the number of free
    // columns is known, the solve's (`solve_buffer_len`).
    let mut problem_buffer = ZeroBuffer::<PROBLEM_ON_STACK>::new();
    let mut parts = problem_buffer.parts(rows * points + points * dim + points * points);
    let s = parts.matrix(rows, points, |s| restrictions_into(m, breakpoints, s));
    // `||S||_F`, and `||M||_F`, which is the same for the discrete metric
    // (`M = S`), computed once.
    let s_norm = std::cell::OnceCell::new();
    let s_norm = || *s_norm.get_or_init(|| s.norm());
    let integral = integral_samples(problem, breakpoints, metric);
    let (samples, target, target_abs): (Columns<'_>, Columns<'_>, Option<Columns<'_>>) =
        match &integral {
            Some((samples, target, target_abs)) => {
                (samples.into(), target.into(), Some(target_abs.into()))
            }
            None => (s, x0, None),
        };
    let samples_norm = || match &integral {
        Some(_) => samples.norm(),
        None => s_norm(),
    };

    let ends_only = count == 2
        && m >= 1
        && problem.constraint_count() == 2
        && problem.pieces.iter().all(|p| p.points.is_empty());
    let rows_r: Vec<Row>;
    let feasible = if ends_only {
        rows_r = Vec::new();
        Feasible::fixed_ends(x0, dim, m, &mut parts)
    } else {
        rows_r = constraint_rows_on_r(problem, s);
        Feasible::general(&rows_r, problem, points, &mut parts)
    };
    let Feasible {
        kept,
        dependent,
        particular,
        z,
        free,
        selection,
        kept_condition,
    } = feasible;
    let kept_count = kept_condition.map_or(0, |(count, _)| count);
    let mut solve_buffer = ZeroBuffer::<SOLVE_ON_STACK>::new();
    let mut parts = solve_buffer.parts(solve_buffer_len(rows, free, dim));
    // The fixed ends' products with the particular solution from its two
    // nonzero rows (`ends_product`), where nalgebra's product is the
    // column axpys (not `matrixmultiply`'s blocked sums).
    let ends_products = selection && !blocked_product(rows, points, dim);
    // Without kept rows the particular solution is zero: no products.
    let reduced_target = if z.is_none() {
        target
    } else {
        parts.matrix(rows, dim, |out| {
            if ends_products {
                ends_product_into(target, false, samples, particular, false, out);
            } else {
                combined_product_into(target, samples, particular, Combine::Minus, out);
            }
        })
    };
    let merged;
    let mut factor = None;
    if free == 0 {
        merged = particular.to_matrix();
    } else {
        let a = match z {
            // M Z for Z = (e_1 .. e_(m-1)): every entry of the product is
            // `M[i][k] 0 + ... + M[i][j+1] 1 + ... + 0` with the products
            // by 0 exactly +0 (M's entries are Bernstein values, finite,
            // >= +0) and the sums exact in any order (also
            // `matrixmultiply`'s), i.e. `M[i][j+1]` itself: the columns,
            // read in place.
            Some(_) if selection => {
                Columns::new(&samples.as_slice()[rows..rows * (1 + free)], rows, free)
            }
            Some(z) => parts.matrix(rows, z.ncols(), |a| product_into(samples, z, false, a)),
            None => samples,
        };
        // Householder QR with the reflectors kept (module `lsq`): Q^T is
        // applied from them, no Q is formed for the solve.
        let packed = parts.take(Factor::packed_len(rows, free));
        let Some(qr) = Factor::new(a.as_slice(), rows, free, packed) else {
            return Err(ill_conditioned_factor(accuracy));
        };
        // The solves' scratch, the refinement steps, the remainder. The
        // steps go to two buffers in turn, so the last finite one is still
        // in its buffer after a step that is not (the last correction,
        // no copy); zeros until written.
        let work = parts.take(rows);
        let steps = [parts.take(free * dim), parts.take(free * dim)];
        let mut last_step = None;
        let remainder = parts.take(rows * dim);
        let y = parts.take(free * dim);
        qr.least_squares(reduced_target.as_slice(), y, work);
        // Two steps of refinement in working precision (the correction
        // from the residual through the same factor): they make the answer
        // componentwise backward stable, and the last correction measures
        // what the solve's rounding leaves (the estimate's a-posteriori
        // part).
        for taken in 0..REFINEMENT_STEPS {
            // remainder = t - A y as nalgebra's `gemm(-1, A, y, 1)` on a
            // copy of t: per column, `(-a_k) y_k + r` for k = 0.. in order,
            // the first from t itself (`matrixmultiply`'s case by nalgebra
            // itself).
            if blocked_product(rows, free, dim) {
                let mut r = reduced_target.to_matrix();
                r.gemm(-1.0, &a.view(), &Columns::new(y, free, dim).view(), 1.0);
                remainder.copy_from_slice(r.as_slice());
            } else {
                let (t, a) = (reduced_target.as_slice(), a.as_slice());
                match rows {
                    4 => remainder_sized::<4>(remainder, t, a, y, rows, free),
                    6 => remainder_sized::<6>(remainder, t, a, y, rows, free),
                    8 => remainder_sized::<8>(remainder, t, a, y, rows, free),
                    10 => remainder_sized::<10>(remainder, t, a, y, rows, free),
                    12 => remainder_sized::<12>(remainder, t, a, y, rows, free),
                    _ => remainder_sized::<0>(remainder, t, a, y, rows, free),
                }
            }
            let step = &mut *steps[taken % 2];
            qr.least_squares(remainder, step, work);
            if !lsq::all_finite(step) {
                break;
            }
            for (e, &d) in y.iter_mut().zip(step.iter()) {
                *e += d;
            }
            last_step = Some(taken % 2);
        }
        // The last finite step, or zeros (the second buffer, never written,
        // when the first step is not finite or none is taken).
        let [first_step, second_step] = steps;
        let correction: &[f64] = match last_step {
            Some(0) => first_step,
            Some(_) | None => second_step,
        };
        let y = Columns::new(y, free, dim);
        merged = match z {
            Some(z) => combined_product(particular, z, y, Combine::Plus),
            None => y.to_matrix(),
        };
        // `A` itself where its absolute values are needed: every use takes
        // them (`abs_tr_mul`, `PlusAbs`) or is a norm.
        factor = Some((qr, y, a, correction));
    }
    let residual = parts.matrix(rows, dim, |out| {
        combined_product_into(target, samples, (&merged).into(), Combine::Minus, out)
    });
    let metric_value = residual.norm_squared();

    // The pieces: R split at the breakpoints (de Casteljau). `R` as a
    // curve only for more than two pieces; for two, its construction is
    // run only where it fails (a non-finite or too high `R`), for its error.
    let curve = if count == 2 {
        if !lsq::all_finite(merged.as_slice()) || m > crate::bezier::MAX_DEGREE {
            BezierCurve::from_matrix(&merged)?;
        }
        None
    } else {
        Some(BezierCurve::from_matrix(&merged)?)
    };
    let mut x = DMatrix::zeros(count * points, problem.dim);
    if count == 2 {
        // `curve.split_unchecked(mu)` coordinate by coordinate, in place in
        // x's columns (the same de Casteljau steps, `(1 - t) a + t b`): the
        // right half's storage is the triangle's working row, whose entry
        // `m - level` is final after `level` steps.
        let t = breakpoints[1];
        for (c, column) in x.as_mut_slice().chunks_exact_mut(2 * points).enumerate() {
            let from = merged.column(c);
            match points {
                2 => split_column_sized::<2>(column, from.as_slice(), t),
                3 => split_column_sized::<3>(column, from.as_slice(), t),
                4 => split_column_sized::<4>(column, from.as_slice(), t),
                5 => split_column_sized::<5>(column, from.as_slice(), t),
                6 => split_column_sized::<6>(column, from.as_slice(), t),
                7 => split_column_sized::<7>(column, from.as_slice(), t),
                8 => split_column_sized::<8>(column, from.as_slice(), t),
                _ => split_column(column, from.as_slice(), t),
            }
        }
    } else {
        let curve = curve.expect("built for more than two pieces");
        for j in 0..count {
            let piece = curve.segment_unchecked(breakpoints[j], breakpoints[j + 1]);
            x.rows_mut(j * points, points)
                .copy_from(&piece.control_matrix());
        }
    }

    let slope = if want_slope && count == 2 {
        let derivative = sample_slopes(&merged, breakpoints, metric)?;
        Some(-2.0 * residual.view().dot(&derivative))
    } else {
        None
    };
    if !full {
        return Ok(Orthogonal {
            merged,
            x,
            estimate: 0.0,
            metric_value,
            slope,
            split_of_merged: count == 2,
            result_scale: None,
        });
    }

    // First-order error estimate of the pieces (see the module).
    // The scale from `lsq::amax` (NaN entries passed over), the estimate
    // from nalgebra's `amax` of x, which is the same value unless x holds
    // a NaN (then read from the slice by `nalgebra_amax`).
    let x_amax = lsq::amax(x.as_slice());
    let x_amax_nalgebra = if x.as_slice().iter().fold(false, |nan, v| nan | v.is_nan()) {
        lsq::nalgebra_amax(x.as_slice())
    } else {
        x_amax
    };
    let result_scale = x_amax.max(problem.scale);
    let eps = f64::EPSILON;
    let mut estimate = (m as f64 + 2.0) * eps * x_amax_nalgebra / result_scale;
    let mut reduced_gain = 0.0;
    // Either metric beyond the double solve's reach: refined in
    // double-double (module `refine`), with its own a-posteriori estimate.
    let refinable = count == 2 && dependent.is_empty();
    let refined = || {
        super::refine::refine_least_squares(
            problem,
            breakpoints[1],
            problem.constraint_count() > 0,
            metric,
            merged.iter().all(|v| v.is_finite()).then_some(&merged),
        )
        .filter(|r| r.estimate <= accuracy)
        .map(|r| Orthogonal {
            merged: r.merged,
            x: r.x,
            estimate: r.estimate,
            metric_value: r.metric_value,
            slope,
            split_of_merged: false,
            result_scale: None,
        })
    };
    let mut refinement_tried = false;
    if let (true, MergeMetric::Discrete, true, Some((qr, y, a, _))) =
        (refinable, metric, m >= REFUSAL_FLOOR_DEGREE, &factor)
    {
        // The estimate below is at least `estimate` plus this floor of its
        // normwise QR term (see `refusal_floor`): when the floor alone
        // exceeds `accuracy` the double answer is refused whatever the
        // rest adds, so the refinement is tried first and the bound is
        // computed only if the refinement does not answer (same answers,
        // same errors).
        let floor = refusal_floor(
            qr,
            *a,
            *y,
            reduced_target,
            residual,
            (accuracy - estimate) * result_scale,
        );
        if estimate + floor / result_scale > accuracy && !skip_refusal_floor() {
            #[cfg(test)]
            FLOOR_TAKEN.with(|t| t.set(t.get() + 1));
            refinement_tried = true;
            if let Some(answer) = refined() {
                return Ok(answer);
            }
        }
    }
    if let Some((qr, y, a, correction)) = &factor {
        // The discrete metric samples the pieces themselves (M = S), so
        // the pieces' map S Z is A = Q T and K0 = S Z T^-1 is the thin Q
        // (no triangular solve); otherwise K0 is solved for.
        let pieces_map = match (metric, &z) {
            (MergeMetric::Discrete, _) => None,
            (MergeMetric::Integral, Some(z)) => Some(s.view() * z.view()),
            (MergeMetric::Integral, None) => Some(s.to_matrix()),
        };

        // The pieces (through S Z) and R itself (through Z): R's control
        // points are less well determined than the pieces' (S has small
        // singular values at high degree), and R is an answer too.
        // `|M| |r_p|`: both products take the entries' absolute values
        // themselves (`abs`, `PlusAbs`), so `r_p` is passed as it is.
        let target_size = match (z, target_abs) {
            (None, Some(t)) => t,
            (None, None) => parts.matrix(rows, dim, |out| abs_into(target, out)),
            (Some(_), t) if ends_products => parts.matrix(rows, dim, |out| {
                ends_product_into(
                    t.unwrap_or(target),
                    t.is_none(),
                    samples,
                    particular,
                    true,
                    out,
                )
            }),
            (Some(_), t) => {
                let t = t.unwrap_or_else(|| parts.matrix(rows, dim, |out| abs_into(target, out)));
                parts.matrix(rows, dim, |out| {
                    combined_product_into(t, samples, particular, Combine::PlusAbs, out)
                })
            }
        };
        let shared = Shared::new(
            *qr,
            *y,
            *a,
            reduced_target,
            target_size,
            residual,
            metric_value.sqrt(),
            m,
            correction,
            parts.take(Shared::values_len(rows, free, dim)),
        );
        let mut scratch = Scratch::default();
        let (pieces_bound, pieces_gain, pieces_k2t) = first_order_bound(
            &shared,
            pieces_map
                .as_ref()
                .map_or(Map::Factor, |map| Map::Of(map.into())),
            true,
            &mut scratch,
        )
        .ok_or_else(|| ill_conditioned_factor(accuracy))?;
        let merged_bound = match (pieces_k2t, &z) {
            // Discrete metric, no kept rows: R's map is the identity and
            // its K1 = T^-1 Q^T is the pieces' K2^T, already solved (and
            // its absolute values taken).
            (true, None) => values_bound_transposed(
                &shared,
                scratch.k2(qr.rows(), qr.cols()),
                REFINEMENT_MARGIN * shared.correction().amax(),
            ),
            _ => {
                let zr = match &z {
                    // Z = (e_1 .. e_(m-1)): its rows 1..m are the identity
                    // and give the same rows of K0 = Z T^-1, K1 = K0 Q^T
                    // and Z c (row by row the same operations); its zero
                    // rows 0 and m give zero rows there (+-0, or NaN
                    // against an infinite |t|), which no maximum of
                    // absolute values (>= 0, NaN passed over) takes: the
                    // same bound from the identity of the free columns.
                    Some(_) if selection => Map::Identity(free),
                    Some(z) => Map::Of(*z),
                    None => Map::Identity(points),
                };
                first_order_bound(&shared, zr, false, &mut scratch)
                    .ok_or_else(|| ill_conditioned_factor(accuracy))?
                    .0
            }
        };
        estimate += pieces_bound.max(MERGED_WEIGHT * merged_bound) / result_scale;
        // ||S Z A^+||_F ||M||_F: how much a move of the particular solution
        // (the kept rows' rounding, below) reaches the pieces through the
        // least-squares problem.
        reduced_gain = pieces_gain * samples_norm();
    }
    if let Some((_, condition)) = kept_condition {
        // The kept rows carry their entries' rounding: the feasible set
        // moves by up to cond(rows) eps relative, which the pieces feel
        // through S directly and through the reduced least-squares problem
        // (the optimum moves along with the particular solution).
        estimate += ESTIMATE_MARGIN
            * eps
            * condition
            * (s_norm() + reduced_gain)
            * Columns::from(&merged).norm()
            / result_scale;
    }

    // Dependent rows, checked at the answer (as the KKT path).
    let e = if dependent.is_empty() {
        DMatrix::zeros(0, 0)
    } else {
        &x - x0.view()
    };
    let tolerance = CONSISTENCY_TOLERANCE.max(accuracy) * problem.extent;
    let unknowns = problem.unknowns;
    let root = (unknowns as f64).sqrt();
    let explained = root * (estimate + unknowns as f64 * eps) * result_scale;
    // rows_r is problem.constraints row for row, in order.
    let rows = dependent.iter().map(|row_r| {
        let index = rows_r
            .iter()
            .position(|r| std::ptr::eq(r, *row_r))
            .expect("a row of rows_r");
        &problem.constraints()[index]
    });
    let undecided = check_dependent_rows(
        problem,
        rows,
        &kept,
        &e,
        (tolerance, explained, result_scale),
    )?;
    if (estimate.is_nan() || estimate > accuracy) && refinable && !refinement_tried {
        if let Some(answer) = refined() {
            return Ok(answer);
        }
    }
    if estimate.is_nan() || estimate > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 1 (least squares for R of degree {m}, {} conditions kept, \
                 first-order error estimate of the pieces)",
                kept_count
            ),
            estimate,
            limit: accuracy,
        });
    }
    undecided.into_result(result_scale, accuracy)?;
    Ok(Orthogonal {
        merged,
        x,
        estimate,
        metric_value,
        slope,
        split_of_merged: count == 2,
        result_scale: Some(result_scale),
    })
}

/// `remainder = t - A y` (column-major, `rows` rows; `A` with `free`
/// columns) as nalgebra's `gemm(-1, A, y, 1)` on a copy of `t`: per
/// column, `(-a_k) y_k + r` for `k = 0..` in order, the first from `t`
/// itself; `R` rows known at compile time (`0`: `rows`).
#[inline(always)]
fn remainder_sized<const R: usize>(
    remainder: &mut [f64],
    t: &[f64],
    a: &[f64],
    y: &[f64],
    rows: usize,
    free: usize,
) {
    let rows = if R == 0 { rows } else { R };
    for ((r, t), yc) in remainder
        .chunks_exact_mut(rows)
        .zip(t.chunks_exact(rows))
        .zip(y.chunks_exact(free))
    {
        let (r, t) = (&mut r[..rows], &t[..rows]);
        let mut columns = a.chunks_exact(rows).zip(yc);
        if let Some((a0, &y0)) = columns.next() {
            for ((e, &x), &from) in r.iter_mut().zip(&a0[..rows]).zip(t) {
                *e = from + -x * y0;
            }
        }
        for (ak, &yk) in columns {
            for (e, &x) in r.iter_mut().zip(&ak[..rows]) {
                *e += -x * yk;
            }
        }
    }
}

/// One coordinate of `R` (`from`, its `n + 1` control values) split at
/// `t` by de Casteljau (`(1 - t) a + t b`, as `split_unchecked`) into
/// `column`: the left half's `n + 1` values, then the right half's. The
/// right half's storage is the triangle's working row, whose entry `n -
/// level` is final after `level` steps.
fn split_column(column: &mut [f64], from: &[f64], t: f64) {
    let points = from.len();
    let m = points - 1;
    let (left, right) = column.split_at_mut(points);
    right.copy_from_slice(from);
    left[0] = right[0];
    for (level, out) in left.iter_mut().enumerate().skip(1) {
        for i in 0..=m - level {
            right[i] = (1.0 - t) * right[i] + t * right[i + 1];
        }
        *out = right[0];
    }
}

/// [`split_column`] for `P` control values (the same operations in the
/// same order, the loops of a known length).
// `level` indexes the left half and bounds the step's row.
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn split_column_sized<const P: usize>(column: &mut [f64], from: &[f64], t: f64) {
    let (left, right) = column.split_at_mut(P);
    let left: &mut [f64; P] = left.try_into().expect("P values");
    let right: &mut [f64; P] = right.try_into().expect("P values");
    right.copy_from_slice(&from[..P]);
    left[0] = right[0];
    for level in 1..P {
        for i in 0..P - level {
            right[i] = (1.0 - t) * right[i] + t * right[i + 1];
        }
        left[level] = right[0];
    }
}

/// From this degree on the discrete metric's solve first checks the
/// refusal floor ([`refusal_floor`]); below it the double estimate
/// refuses only at extreme `mu`, and the floor would cost more than it
/// saves (the answers are the same either way).
pub const REFUSAL_FLOOR_DEGREE: usize = 16;

/// A floor of the normwise QR term of [`first_order_bound`] for the
/// pieces of the discrete metric (`K0` the thin `Q`, `K2 = Q T^-T`):
/// `QR_MARGIN eps sqrt(rows free) (||Q||_F (||t|| + ||A||_F ||y||) +
/// ||T^-1||_F ||A||_F ||res||)`, halved for rounding: `||Q||_F =
/// sqrt(free)` and `||Q T^-T||_F = ||T^-1||_F` for orthonormal columns,
/// which the computed `Q` and `K2` have to about `free eps` relative, and
/// `||T^-1||_F` is solved here on the leading blocks of `T`. Every other
/// term of that bound is non-negative, so the estimate is at least this
/// divided by the result scale (test `refusal_floor_changes_no_answer`).
/// The residual part (`free` triangular solves) is computed only when the
/// first part does not already reach `needed`.
fn refusal_floor(
    qr: &Factor<'_>,
    a: Columns<'_>,
    y: Columns<'_>,
    target: Columns<'_>,
    residual: Columns<'_>,
    needed: f64,
) -> f64 {
    let (rows, free) = (a.nrows(), a.ncols());
    let factor = 0.5 * QR_MARGIN * f64::EPSILON * ((rows * free) as f64).sqrt();
    let a_norm = a.norm();
    let values = factor * (free as f64).sqrt() * (target.norm() + a_norm * y.norm());
    if values > needed {
        return values;
    }
    values + factor * qr.inverse_frobenius() * a_norm * residual.norm()
}

#[cfg(not(test))]
fn skip_refusal_floor() -> bool {
    false
}

#[cfg(test)]
thread_local! {
    /// Tests: compute the full estimate even when the refusal floor
    /// exceeds the accuracy (the answers must not change).
    static SKIP_REFUSAL_FLOOR: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
thread_local! {
    /// Tests: how many solves took the refusal floor's early refinement.
    static FLOOR_TAKEN: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

#[cfg(test)]
fn skip_refusal_floor() -> bool {
    SKIP_REFUSAL_FLOOR.with(|s| s.get())
}

/// What the first-order bound needs of the least-squares solve, on flat
/// column-major buffers.
struct Shared<'s> {
    /// `A = Q T` (reflectors kept), `T` upper triangular (`free x free`).
    qr: Factor<'s>,
    /// One buffer ([`Shared::values_len`]): the thin `Q` (`rows x free`,
    /// formed once from the reflectors), then `through_values` (`rows x
    /// dim`), then `through_residual` (`free x dim`), each column-major.
    values: &'s [f64],
    y: Columns<'s>,
    /// `A` (`rows x free`): only its absolute values (`|A|` in the
    /// products) and its norm are read.
    a: Columns<'s>,
    target: Columns<'s>,
    /// The residual's norm (`|A|^T |res|` is in `values`).
    residual_norm: f64,
    m: usize,
    /// The last refinement correction of `y` (`free x dim`,
    /// column-major).
    correction: &'s [f64],
}

impl<'s> Shared<'s> {
    /// The entries of the buffer of a `rows x free` factor with `dim`
    /// coordinates.
    fn values_len(rows: usize, free: usize, dim: usize) -> usize {
        rows * free + rows * dim + free * dim
    }

    /// `values`: [`Shared::values_len`] entries, all zero; `residual_norm`:
    /// `residual.norm()` (the root of the metric value, already summed).
    #[allow(clippy::too_many_arguments)]
    fn new(
        qr: Factor<'s>,
        y: Columns<'s>,
        a: Columns<'s>,
        target: Columns<'s>,
        target_size: Columns<'_>,
        residual: Columns<'_>,
        residual_norm: f64,
        m: usize,
        correction: &'s [f64],
        values: &'s mut [f64],
    ) -> Self {
        let (rows, free, dim) = (qr.rows(), qr.cols(), y.ncols());
        debug_assert_eq!(correction.len(), free * dim);
        debug_assert!(target_size.shape() == (rows, dim) && residual.shape() == (rows, dim));
        let (q, rest) = values.split_at_mut(rows * free);
        let (through_values, through_residual) = rest.split_at_mut(rows * dim);
        qr.thin_q_into(q);
        combined_product_into(target_size, a, y, Combine::PlusAbs, through_values);
        abs_tr_mul_into(a, residual, through_residual);
        Self {
            qr,
            values,
            y,
            a,
            target,
            residual_norm,
            m,
            correction,
        }
    }

    /// The last refinement correction as a `free x dim` matrix (a view of
    /// the same column-major values).
    fn correction(&self) -> DMatrixView<'s, f64> {
        DMatrixView::from_slice(self.correction, self.qr.cols(), self.y.ncols())
    }

    /// The thin `Q`, column-major `rows x free`.
    fn q(&self) -> &[f64] {
        &self.values[..self.qr.rows() * self.qr.cols()]
    }

    /// Per coordinate `c`: `|t_c| + |A| |y_c|`, where `|t_c|` is what the
    /// reduced target's rounding is relative to (`|b|` as evaluated, `sum
    /// |B| |P|`, plus `|M| |r_p|`); column-major `rows x dim`.
    fn through_values(&self) -> &[f64] {
        let (rows, free, dim) = (self.qr.rows(), self.qr.cols(), self.y.ncols());
        &self.values[rows * free..rows * free + rows * dim]
    }

    /// Per coordinate: `|A|^T |res_c|`, column-major `free x dim`.
    fn through_residual(&self) -> &[f64] {
        let (rows, free, dim) = (self.qr.rows(), self.qr.cols(), self.y.ncols());
        &self.values[rows * free + rows * dim..]
    }
}

/// Entries of the first buffer of [`orthogonal_solution`] (`S`, `r_p`,
/// `Z`) kept on the stack (two pieces of degree 3 in space: `60`).
const PROBLEM_ON_STACK: usize = 64;

/// Entries of the solve's buffer of [`orthogonal_solution`] kept on the
/// stack (two pieces of degree 3 in space with fixed ends:
/// [`solve_buffer_len`]` = 228`).
const SOLVE_ON_STACK: usize = 240;

/// The entries [`orthogonal_solution`] takes from its solve's buffer at
/// most, for `rows` samples, `free` free columns and `dim` coordinates.
fn solve_buffer_len(rows: usize, free: usize, dim: usize) -> usize {
    // The reduced target, A = M Z, the factor; the solves' scratch, the
    // two steps, the remainder and y.
    let solve = rows * dim
        + rows * free
        + Factor::packed_len(rows, free)
        + rows
        + 3 * free * dim
        + rows * dim;
    // The residual, the target's size (and its absolute values), `Shared`.
    let bound = 3 * rows * dim + Shared::values_len(rows, free, dim);
    solve + bound
}

/// The buffer of [`first_order_bound`], kept between its calls for the
/// pieces and for `R` (the same values, one allocation); after a call for
/// the pieces of the discrete metric it holds `|K2|` ([`Scratch::k2`]).
///
/// Up to [`SCRATCH_ON_STACK`] entries it lives on the stack (`small`,
/// zeros at first, as a new `Vec` resized with zeros); beyond, in `large`,
/// which starts as a copy of `small` and grows with zeros: every call sees
/// the same contents as with one `Vec` grown to the largest need so far.
struct Scratch {
    small: [f64; SCRATCH_ON_STACK],
    large: Vec<f64>,
}

/// Entries of [`Scratch`] kept on the stack (the buffer of two pieces of
/// degree 5 in the discrete metric: `2 + 12 + 144 + 48 = 206`).
const SCRATCH_ON_STACK: usize = 224;

impl Default for Scratch {
    fn default() -> Self {
        Self {
            small: [0.0; SCRATCH_ON_STACK],
            large: Vec::new(),
        }
    }
}

impl Scratch {
    /// The buffer with at least `need` entries.
    fn buffer_mut(&mut self, need: usize) -> &mut [f64] {
        if self.large.is_empty() && need <= SCRATCH_ON_STACK {
            return &mut self.small;
        }
        if self.large.is_empty() {
            self.large.extend_from_slice(&self.small);
        }
        if self.large.len() < need {
            self.large.resize(need, 0.0);
        }
        &mut self.large
    }

    fn buffer(&self) -> &[f64] {
        if self.large.is_empty() {
            &self.small
        } else {
            &self.large
        }
    }

    /// `|K2|` (column-major `rows x free`) of the last call of
    /// [`first_order_bound`] without a map.
    fn k2(&self, rows: usize, free: usize) -> &[f64] {
        let start = free + rows + rows * rows;
        &self.buffer()[start..start + rows * free]
    }
}

/// `max_c amax(K v_c)` for a column-major `out x inner` matrix `k` and the
/// columns `v_c` of `v` (`inner x dim`); `O`, `I`: `out` and `inner` known
/// at compile time (`0`: not).
#[inline(always)]
fn largest_product<const O: usize, const I: usize>(
    k: &[f64],
    out: usize,
    v: &[f64],
    v_rows: usize,
    acc: &mut [f64],
) -> f64 {
    let mut worst = 0.0f64;
    debug_assert_eq!(acc.len(), out);
    let general_inner = |out: usize| (k.len() / out.max(1)).min(v_rows);
    debug_assert!(O == 0 || O == out);
    debug_assert!(I == 0 || I == general_inner(out));
    let out = if O != 0 { O } else { out };
    let inner = if I != 0 { I } else { general_inner(out) };
    let acc = &mut acc[..out];
    let k = &k[..out * inner];
    for column in v.chunks_exact(v_rows.max(1)) {
        if out < SHORT_COLUMNS {
            // Few outputs: entry by entry along K's rows (the same sums in
            // the same order, `0 + k_o0 v_0 + k_o1 v_1 + ...`), rather than
            // many short column updates.
            for (o, a) in acc.iter_mut().enumerate() {
                let mut sum = 0.0;
                for (i, &x) in column[..inner].iter().enumerate() {
                    sum += k[i * out + o] * x;
                }
                *a = sum;
            }
        } else {
            columns_times(acc, k, column, Start::Set);
        }
        worst = lsq::raise(worst, lsq::amax(acc));
    }
    worst
}

/// Where [`columns_times`] starts.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Start {
    /// `acc` set from the first column's product (no zero fill first): the
    /// values of summing into zeros (`0 + e x` is `e x`) but for the sign
    /// of an entry whose every term is a zero, which the largest absolute
    /// value that is read of it ([`lsq::amax`]) does not see.
    Set,
    /// Added to `acc` as it is.
    Add,
}

/// `acc (+)= sum_k K[:, k] x_k`, `k` in order, column update by column
/// update (`K` column-major with `acc.len()` rows; as many columns as both
/// `K` and `x` have).
#[inline(always)]
fn columns_times(acc: &mut [f64], k: &[f64], x: &[f64], start: Start) {
    let mut columns = k.chunks_exact(acc.len()).zip(x);
    if start == Start::Set {
        match columns.next() {
            Some((kc, &x)) => acc.iter_mut().zip(kc).for_each(|(a, &e)| *a = e * x),
            None => acc.fill(0.0),
        }
    }
    for (kc, &x) in columns {
        for (a, &e) in acc.iter_mut().zip(kc) {
            *a += e * x;
        }
    }
}

/// Below this many rows, [`largest_product`] and `|K1|` of
/// [`first_order_bound`] go entry by entry instead of by column updates
/// (the same operations in the same order per entry).
const SHORT_COLUMNS: usize = 4;

/// `max_c amax(K^T v_c)` for a column-major `inner x out` matrix `k`
/// (`out` columns of length `inner`) and the columns `v_c` of `v`.
fn largest_transposed_product(k: &[f64], inner: usize, v: &[f64], v_rows: usize) -> f64 {
    let mut worst = 0.0f64;
    for column in v.chunks_exact(v_rows.max(1)) {
        for kc in k.chunks_exact(inner) {
            worst = lsq::raise(worst, lsq::dot(kc, column).abs());
        }
    }
    worst
}

/// `K T^-T` in place for a column-major `out x free` matrix `k`
/// (column operations, from the last column); `free = F` and `out = O`
/// known at compile time when not `0`.
#[inline(always)]
fn times_t_inverse_transposed<const F: usize, const O: usize>(
    qr: &Factor,
    k: &mut [f64],
    out: usize,
) {
    let free = if F != 0 { F } else { qr.cols() };
    debug_assert!(free == qr.cols() && (O == 0 || O == out));
    let out = if O != 0 { O } else { out };
    for c in (0..free).rev() {
        // K[:, c] = (K[:, c] - sum_(j > c) T[c][j] K[:, j]) / T[c][c].
        let (head, tail) = k.split_at_mut((c + 1) * out);
        let column = &mut head[c * out..(c + 1) * out];
        for j in c + 1..free {
            let t = qr.t_column(j)[c];
            for (e, &x) in column
                .iter_mut()
                .zip(&tail[(j - c - 1) * out..(j - c) * out])
            {
                *e -= t * x;
            }
        }
        let d = qr.diagonal()[c];
        column.iter_mut().for_each(|e| *e /= d);
    }
}

/// The map of [`first_order_bound`].
#[derive(Clone, Copy)]
enum Map<'m> {
    /// The pieces of the discrete metric: `S Z = A` itself (`K0` the thin
    /// `Q`).
    Factor,
    /// A matrix (`S Z` of the integral metric, `Z`).
    Of(Columns<'m>),
    /// The identity of this size (`R`'s guard through the free columns),
    /// the same values as [`Map::Of`] an identity matrix without it.
    Identity(usize),
}

/// The first-order bound (module documentation) of the largest change of
/// `map y` (`map` = `S Z` for the pieces, `Z` for `R`; `None`: the pieces
/// of the discrete metric, whose map `S Z` is `A` itself, so that `K0 =
/// map T^-1` is the thin `Q` of the factor), absolute, and
/// `||K0||_F = ||map A^+||_F`; for `None` also `K2 = Q T^-T`
/// (column-major `rows x free`), whose transpose `T^-1 Q^T` is `A^+`,
/// i.e. `R`'s `K1` when `Z = I`.
///
/// All by column operations on column-major buffers: `K0 = map T^-1`,
/// `K1 = K0 Q^T` (outer products of columns), `K2 = K0 T^-T`.
fn first_order_bound(
    shared: &Shared<'_>,
    map: Map<'_>,
    with_normwise: bool,
    scratch: &mut Scratch,
) -> Option<(f64, f64, bool)> {
    // The merge's small sizes as constants (`lsq::with_small_sizes`), as
    // `lsq::Factor::least_squares`: the same operations in the same order.
    // The map's rows too: `rows` for the thin Q, `free` for the identity.
    lsq::with_small_sizes!(shared.qr.rows(), shared.qr.cols(), |R, F| {
        match map {
            Map::Factor => first_order_bound_sized::<R, F, R>(shared, map, with_normwise, scratch),
            Map::Identity(_) => {
                first_order_bound_sized::<R, F, F>(shared, map, with_normwise, scratch)
            }
            Map::Of(_) => first_order_bound_sized::<R, F, 0>(shared, map, with_normwise, scratch),
        }
    })
}

/// [`first_order_bound`] with `rows = R`, `free = F` and the map's rows
/// `O` known at compile time (`0`: read from the factor / the map).
#[inline(always)]
fn first_order_bound_sized<const R: usize, const F: usize, const O: usize>(
    shared: &Shared<'_>,
    map: Map<'_>,
    with_normwise: bool,
    scratch: &mut Scratch,
) -> Option<(f64, f64, bool)> {
    let qr = shared.qr;
    let (rows, free) = qr.sizes::<R, F>();
    let q = shared.q();
    let dim = shared.y.ncols();
    let eps = f64::EPSILON;
    // Componentwise (Skeel-style): every entry of A and of the target
    // carries a relative rounding of at most gamma.
    let gamma = ESTIMATE_MARGIN * (shared.m as f64 + 2.0) * eps;
    let out = match map {
        _ if O != 0 => O,
        Map::Factor => rows,
        Map::Of(map) => map.nrows(),
        Map::Identity(n) => n,
    };
    debug_assert!(match map {
        Map::Factor => out == rows,
        Map::Of(map) => out == map.nrows(),
        Map::Identity(n) => out == n,
    });
    // One buffer: w (free), acc (max(rows, out)), |K1| (out x rows), K0
    // and then K2 (out x free).
    let acc_len = rows.max(out);
    let need = free + acc_len + out * rows + out * free;
    let (w, rest) = scratch.buffer_mut(need).split_at_mut(free);
    let (acc, rest) = rest.split_at_mut(acc_len);
    let (k1, rest) = rest.split_at_mut(out * rows);
    let k0 = &mut rest[..out * free];
    // K0 (out x free) and the last correction mapped, max |map c|.
    let mapped_correction = match map {
        Map::Factor => {
            // map = A = Q T: map c = Q (T c). K0 = Q.
            let acc = &mut acc[..rows];
            let mut worst = 0.0f64;
            for c in 0..dim {
                w.copy_from_slice(&shared.correction[c * free..(c + 1) * free]);
                qr.mul_t_sized::<R, F>(w);
                columns_times(acc, q, w, Start::Set);
                worst = lsq::raise(worst, lsq::amax(acc));
            }
            k0.copy_from_slice(q);
            worst
        }
        Map::Of(_) | Map::Identity(_) => {
            // K0 = map T^-1: K0[:, k] = (map[:, k] - sum_(j < k) T[j][k]
            // K0[:, j]) / T[k][k].
            match map {
                Map::Of(map) => k0.copy_from_slice(map.as_slice()),
                _ => {
                    k0.fill(0.0);
                    k0.iter_mut().step_by(out + 1).for_each(|e| *e = 1.0);
                }
            }
            for k in 0..free {
                let (done, rest) = k0.split_at_mut(k * out);
                let column = &mut rest[..out];
                for (j, &t) in qr.t_column(k).iter().enumerate() {
                    for (e, &x) in column.iter_mut().zip(&done[j * out..(j + 1) * out]) {
                        *e -= t * x;
                    }
                }
                let d = qr.diagonal()[k];
                column.iter_mut().for_each(|e| *e /= d);
            }
            // max |map c| as nalgebra's `amax` of the product (its
            // entries are finite: a finite map, a finite correction), the
            // product column by column in `acc` as nalgebra's.
            let mut worst = 0.0f64;
            match map {
                Map::Identity(n) => {
                    // `I c` as nalgebra's product (also `matrixmultiply`'s)
                    // is `c` entry by entry up to the sign of a zero (the
                    // products by 0 and 1 exact, the sums with zeros
                    // exact), so its largest absolute value is `c`'s.
                    debug_assert_eq!(n, free);
                    for column in shared.correction.chunks_exact(free) {
                        worst = lsq::raise(worst, lsq::amax(column));
                    }
                }
                Map::Of(map) if blocked_product(out, free, dim) => {
                    worst = (map.view() * shared.correction()).amax();
                }
                Map::Of(map) => {
                    let acc = &mut acc[..out];
                    for c in 0..dim {
                        product_columns(
                            map,
                            &shared.correction[c * free..(c + 1) * free],
                            false,
                            acc,
                        );
                        worst = lsq::raise(worst, lsq::amax(acc));
                    }
                }
                Map::Factor => unreachable!("the thin Q's case above"),
            }
            worst
        }
    };
    let acc = &mut acc[..out];
    // |K1| = |K0 Q^T| (out x rows): column i is sum_k Q[i][k] K0[:, k].
    // For the thin Q (K0 = Q) it is symmetric: the entries on and below
    // the diagonal are summed, those above copied from them.
    let symmetric = matches!(map, Map::Factor);
    if !symmetric && out < SHORT_COLUMNS {
        // Entry by entry: `K0[o][0] Q[i][0] + K0[o][1] Q[i][1] + ...` in
        // that order, as the column updates below.
        for (i, column) in k1.chunks_exact_mut(out).enumerate() {
            for (o, e) in column.iter_mut().enumerate() {
                let mut sum = k0[o] * q[i];
                for k in 1..free {
                    sum += k0[k * out + o] * q[k * rows + i];
                }
                *e = sum;
            }
        }
    } else {
        for (i, column) in k1.chunks_exact_mut(out).enumerate() {
            let from = if symmetric { i } else { 0 };
            let q0 = q[i];
            let column = &mut column[from..];
            for (e, &x) in column.iter_mut().zip(&k0[from..out]) {
                *e = x * q0;
            }
            for k in 1..free {
                let qik = q[k * rows + i];
                for (e, &x) in column.iter_mut().zip(&k0[k * out + from..(k + 1) * out]) {
                    *e += x * qik;
                }
            }
        }
    }
    if symmetric {
        for i in 0..rows {
            for o in 0..i {
                k1[i * out + o] = k1[o * out + i];
            }
        }
    }
    k1.iter_mut().for_each(|v| *v = v.abs());
    let k0_norm = lsq::norm(k0);
    // What the solve's own rounding leaves after refinement: the last
    // correction mapped, with a margin (a-posteriori).
    let measured = REFINEMENT_MARGIN * mapped_correction;
    if !with_normwise {
        // R's guard: the values term only (what the measured weight was
        // calibrated on, merge back with zero residual); no K2.
        let bound = values_bound::<O, R>(shared, k1, measured, acc);
        return Some((bound, k0_norm, false));
    }
    // K2 = K0 T^-T (out x free), in K0's place.
    let k2 = k0;
    times_t_inverse_transposed::<F, O>(&qr, k2, out);
    // Householder QR's own backward error is normwise (column by column),
    // not componentwise, and refinement in working precision does not
    // remove all of it (measured: test merge_exact, degree 20, mu ~0.1,
    // integral metric): its first-order effect with Frobenius norms.
    let a_norm = shared.a.norm();
    let normwise = QR_MARGIN
        * eps
        * ((rows * free) as f64).sqrt()
        * (k0_norm * (shared.target.norm() + a_norm * shared.y.norm())
            + lsq::norm(k2) * a_norm * shared.residual_norm);
    k2.iter_mut().for_each(|v| *v = v.abs());
    let mut worst = 0.0f64;
    for c in 0..dim {
        let tv = &shared.through_values()[c * rows..(c + 1) * rows];
        columns_times(acc, k1, tv, Start::Set);
        let tr = &shared.through_residual()[c * free..(c + 1) * free];
        columns_times(acc, k2, tr, Start::Add);
        worst = lsq::raise(worst, gamma * lsq::amax(acc));
    }
    Some((worst + measured + normwise, k0_norm, symmetric))
}

/// The values term of [`first_order_bound`] alone, `max_c gamma |K1|
/// (|t_c| + |A| |y_c|)`, plus the `measured` refinement term: `R`'s guard,
/// from `|K1|` (`|map A^+|`, absolute values taken; column-major, `rows`
/// columns).
/// `O`, `R`: `|K1|`'s rows and columns known at compile time (`0`: not).
#[inline(always)]
fn values_bound<const O: usize, const R: usize>(
    shared: &Shared<'_>,
    k1: &[f64],
    measured: f64,
    acc: &mut [f64],
) -> f64 {
    let gamma = ESTIMATE_MARGIN * (shared.m as f64 + 2.0) * f64::EPSILON;
    let out = k1.len() / shared.qr.rows();
    gamma * largest_product::<O, R>(k1, out, shared.through_values(), shared.qr.rows(), acc)
        + measured
}

/// [`values_bound`] with `|K1|` given by its transpose (column-major
/// `rows x out`): `R`'s guard from the pieces' `|K2| = |A^+|^T`.
fn values_bound_transposed(shared: &Shared<'_>, k1t: &[f64], measured: f64) -> f64 {
    let gamma = ESTIMATE_MARGIN * (shared.m as f64 + 2.0) * f64::EPSILON;
    gamma
        * largest_transposed_product(
            k1t,
            shared.qr.rows(),
            shared.through_values(),
            shared.qr.rows(),
        )
        + measured
}

fn ill_conditioned_factor(accuracy: f64) -> BezjoinError {
    BezjoinError::IllConditioned {
        what: "merge stage 1 (the least-squares factor is singular or overflows)".into(),
        estimate: f64::INFINITY,
        limit: accuracy,
    }
}

#[cfg(test)]
mod tests {
    use super::super::stage_one::PieceInput;
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// Two random planar pieces `P`, `Q` of `degree`, nothing kept.
    fn random_pieces(state: &mut u64, degree: usize) -> Vec<PieceInput<'static>> {
        ["P", "Q"]
            .iter()
            .map(|name| PieceInput {
                curve: std::borrow::Cow::Owned(curve(state, degree)),
                name,
                points_name: "points",
                keep: false,
                points: Vec::new(),
            })
            .collect()
    }

    /// The refusal floor (`refusal_floor`) changes no answer: with and
    /// without it, the same result bit for bit (R, the pieces, the
    /// estimate and the metric) or the same error, for random pairs at high
    /// degrees, with and without fixed ends, and the floor is taken in a
    /// good share of them (the double solve refuses there).
    #[test]
    fn refusal_floor_changes_no_answer() {
        let mut state = 29;
        let mut cases = 0;
        for degree in [16, 24, 31] {
            for fix_ends in [false, true] {
                for mu in [0.3, 0.5, 0.71] {
                    let pieces = random_pieces(&mut state, degree);
                    let lengths = [mu, 1.0 - mu];
                    let problem = Problem::new(&pieces, &lengths, fix_ends);
                    let solve = |skip: bool| {
                        SKIP_REFUSAL_FLOOR.with(|s| s.set(skip));
                        let out = orthogonal_solution(
                            &problem,
                            &[0.0, mu, 1.0],
                            MergeMetric::Discrete,
                            1e-8,
                            true,
                            true,
                        );
                        SKIP_REFUSAL_FLOOR.with(|s| s.set(false));
                        out
                    };
                    let taken = FLOOR_TAKEN.with(|t| t.get());
                    let with_floor = solve(false);
                    if FLOOR_TAKEN.with(|t| t.get()) > taken {
                        cases += 1;
                    }
                    let without = solve(true);
                    let context = format!("degree {degree} mu {mu} fix ends {fix_ends}");
                    match (with_floor, without) {
                        (Ok(a), Ok(b)) => {
                            assert_eq!(a.merged, b.merged, "{context}");
                            assert_eq!(a.x, b.x, "{context}");
                            assert_eq!(a.estimate.to_bits(), b.estimate.to_bits(), "{context}");
                            assert_eq!(
                                a.metric_value.to_bits(),
                                b.metric_value.to_bits(),
                                "{context}"
                            );
                        }
                        (Err(a), Err(b)) => assert_eq!(a, b, "{context}"),
                        (a, b) => panic!(
                            "{context}: with the floor {:?}, without {:?}",
                            a.map(|o| o.estimate),
                            b.map(|o| o.estimate)
                        ),
                    }
                }
            }
        }
        assert!(cases >= 4, "the floor was taken in {cases} of 18 cases");
    }

    /// The closed-form feasible set of fixed ends on two pieces is what
    /// the general construction (rows on `r`, Gram-Schmidt, greedy null
    /// space, singular values) gives for the same rows: the same
    /// particular solution and null-space basis bit for bit, both rows
    /// kept, none dependent, the same condition, at every degree and `mu`.
    #[test]
    fn fixed_ends_feasible_set_is_the_general_one() {
        let mut state = 17;
        for degree in [1, 2, 3, 4, 7, 15, 24, 31] {
            let pieces = random_pieces(&mut state, degree);
            for mu in [1e-3, 0.3, 0.5, 0.77] {
                let lengths = [mu, 1.0 - mu];
                let problem = Problem::new(&pieces, &lengths, true);
                let s = restrictions(degree, &[0.0, mu, 1.0]);
                let rows_r = constraint_rows_on_r(&problem, &s);
                let len = (degree + 1) * (problem.dim + degree + 1);
                let (mut general_buffer, mut closed_buffer) = (vec![0.0; len], vec![0.0; len]);
                let general = Feasible::general(
                    &rows_r,
                    &problem,
                    degree + 1,
                    &mut Parts::new(&mut general_buffer),
                );
                let closed = Feasible::fixed_ends(
                    problem.x0(),
                    problem.dim,
                    degree,
                    &mut Parts::new(&mut closed_buffer),
                );
                let context = format!("degree {degree} mu {mu}");
                assert_eq!(general.kept.len(), 2, "{context}");
                assert!(general.dependent.is_empty(), "{context}");
                assert_eq!(closed.free, general.free, "{context}");
                assert_eq!(
                    closed.particular.to_matrix(),
                    general.particular.to_matrix(),
                    "{context}"
                );
                assert_eq!(
                    closed.z.map(Columns::to_matrix),
                    general.z.map(Columns::to_matrix),
                    "{context}"
                );
                let (count, condition) = general.kept_condition.unwrap();
                assert_eq!(Some((count, condition)), closed.kept_condition, "{context}");
            }
        }
    }

    /// Random inputs of a first-order bound (`rows x free` system, `dim`
    /// right-hand sides), drawn in this order: `A`, `y`, the target, its
    /// size (absolute values), the residual, the correction.
    struct BoundInputs {
        a: DMatrix<f64>,
        y: DMatrix<f64>,
        target: DMatrix<f64>,
        target_size: DMatrix<f64>,
        residual: DMatrix<f64>,
        correction: DMatrix<f64>,
    }

    impl BoundInputs {
        /// `Shared` of these inputs with `a` (`A` or `|A|`), the ends'
        /// count `ends` and the correction `correction`; the factor of the
        /// inputs' `A` and the shared values in `buffer`.
        fn shared<'s>(
            &'s self,
            a: &'s DMatrix<f64>,
            ends: usize,
            correction: &'s DMatrix<f64>,
            buffer: &'s mut Vec<f64>,
        ) -> Shared<'s> {
            let (rows, free, dim) = (self.a.nrows(), self.a.ncols(), self.y.ncols());
            let packed_len = Factor::packed_len(rows, free);
            buffer.resize(packed_len + Shared::values_len(rows, free, dim), 0.0);
            let (packed, values) = buffer.split_at_mut(packed_len);
            Shared::new(
                Factor::new(self.a.as_slice(), rows, free, packed).unwrap(),
                (&self.y).into(),
                a.into(),
                (&self.target).into(),
                (&self.target_size).into(),
                (&self.residual).into(),
                self.residual.norm(),
                ends,
                correction.as_slice(),
                values,
            )
        }
    }

    fn bound_inputs(
        values: &mut crate::test_values::Values,
        rows: usize,
        free: usize,
        dim: usize,
    ) -> BoundInputs {
        let a = random_matrix(values, rows, free);
        BoundInputs {
            y: random_matrix(values, free, dim),
            target: random_matrix(values, rows, dim),
            target_size: random_matrix(values, rows, dim).abs(),
            residual: random_matrix(values, rows, dim),
            correction: random_matrix(values, free, dim),
            a,
        }
    }

    fn random_matrix(
        values: &mut crate::test_values::Values,
        rows: usize,
        cols: usize,
    ) -> DMatrix<f64> {
        DMatrix::from_fn(rows, cols, |_, _| {
            // Signed values, some exact zeros of either sign.
            let v = values.signed();
            if v.abs() < 0.05 { 0.0 * v.signum() } else { v }
        })
    }

    fn same_bits(a: &DMatrix<f64>, b: &DMatrix<f64>) -> bool {
        a.shape() == b.shape()
            && a.iter()
                .zip(b.iter())
                .all(|(x, y)| x.to_bits() == y.to_bits())
    }

    /// `Scratch` holds what one `Vec` grown with zeros to the largest need
    /// so far would hold: zeros at first, earlier writes kept when a later
    /// need crosses from the stack to the heap, and zeros in the growth;
    /// `k2` reads the buffer in use.
    #[test]
    fn scratch_is_a_vec_grown_with_zeros() {
        let mut scratch = Scratch::default();
        let mut reference: Vec<f64> = Vec::new();
        let mut next = 1.0;
        for need in [
            5,
            40,
            SCRATCH_ON_STACK,
            3,
            SCRATCH_ON_STACK + 1,
            10,
            700,
            20,
        ] {
            if reference.len() < need {
                reference.resize(need, 0.0);
            }
            let buffer = scratch.buffer_mut(need);
            assert!(buffer.len() >= need);
            assert_eq!(
                buffer[..reference.len().min(buffer.len())],
                reference[..reference.len().min(buffer.len())],
                "need {need}"
            );
            // Write part of the need, as a call does.
            for (b, r) in buffer[..need / 2].iter_mut().zip(&mut reference) {
                *b = next;
                *r = next;
                next += 1.0;
            }
            let (rows, free) = (2, 1);
            let start = free + rows + rows * rows;
            if reference.len() >= start + rows * free {
                assert_eq!(
                    scratch.k2(rows, free),
                    &reference[start..start + rows * free]
                );
            }
        }
    }

    /// The slice products replace nalgebra's operators bit for bit: `a *
    /// b`, `|a| |b|`, `c + a b`, `c - a b`, `c + |a| |b|`, `a^T |b|`,
    /// `|m|`, on shapes below and above nalgebra's `matrixmultiply`
    /// threshold, an empty inner dimension, and entries of both signs
    /// with signed zeros.
    #[test]
    fn products_are_nalgebras_bit_for_bit() {
        let mut values = crate::test_values::Values(41);
        for (rows, inner, cols) in [
            (8, 4, 3),
            (8, 2, 3),
            (4, 2, 3),
            (1, 1, 1),
            (2, 0, 2),
            (64, 31, 2),
            (7, 6, 6),
            (9, 8, 7),
            (12, 3, 9),
            (6, 3, 2),
            (10, 4, 3),
            (16, 5, 3),
            (6, 1, 1),
        ] {
            let context = format!("{rows} x {inner} x {cols}");
            let a = random_matrix(&mut values, rows, inner);
            let b = random_matrix(&mut values, inner, cols);
            let c = random_matrix(&mut values, rows, cols);
            let mut out = vec![0.0; rows * cols];
            product_into(&a, &b, false, &mut out);
            assert!(
                same_bits(&DMatrix::from_vec(rows, cols, out.clone()), &(&a * &b)),
                "{context}"
            );
            product_into(&a, &b, true, &mut out);
            assert!(
                same_bits(&DMatrix::from_vec(rows, cols, out), &(a.abs() * b.abs())),
                "{context}"
            );
            assert!(
                same_bits(
                    &combined_product(&c, &a, &b, Combine::Plus),
                    &(&c + &a * &b)
                ),
                "{context}"
            );
            assert!(
                same_bits(
                    &combined_product(&c, &a, &b, Combine::Minus),
                    &(&c - &a * &b)
                ),
                "{context}"
            );
            assert!(
                same_bits(
                    &combined_product(&c, &a, &b, Combine::PlusAbs),
                    &(&c + a.abs() * b.abs())
                ),
                "{context}"
            );
            assert!(same_bits(&abs_of(&a), &a.abs()), "{context}");
            let d = random_matrix(&mut values, rows, cols);
            assert!(
                same_bits(&abs_tr_mul(&c, &d), &c.abs().tr_mul(&d.abs())),
                "{context}"
            );
        }
    }

    /// The fixed ends' products from the particular solution's two nonzero
    /// rows are nalgebra's `c - M p` and `c + |M| |p|` bit for bit, with
    /// zero entries of `M` and negative end values (signed-zero products,
    /// `-0 + 0 = +0`).
    #[test]
    fn ends_products_are_nalgebras_bit_for_bit() {
        let mut values = crate::test_values::Values(43);
        for (rows, m, dim) in [(4, 1, 2), (6, 2, 3), (8, 3, 3), (12, 5, 2), (64, 31, 3)] {
            let samples =
                random_matrix(&mut values, rows, m + 1).map(|v| if v < 0.0 { 0.0 } else { v });
            let mut p = DMatrix::zeros(m + 1, dim);
            for c in 0..dim {
                p[(0, c)] = values.signed();
                p[(m, c)] = -values.unit();
            }
            let c = random_matrix(&mut values, rows, dim);
            let context = format!("{rows} x {m} x {dim}");
            assert!(
                same_bits(
                    &ends_product(&c, &samples, &p, false),
                    &(&c - &samples * &p)
                ),
                "{context}"
            );
            assert!(
                same_bits(
                    &ends_product(&c, &samples, &p, true),
                    &(&c + samples.abs() * p.abs())
                ),
                "{context}"
            );
        }
    }

    /// The restriction matrices of two pieces are the Bernstein triangle
    /// at `mu` (`S_L[i][k] = B_k^i(mu)`, `S_R[i][k] = B_(k-i)^(m-i)(mu)`):
    /// bit for bit the triangle's recurrence, run separately here.
    #[test]
    fn restrictions_are_the_bernstein_triangle() {
        for m in [0, 1, 2, 3, 7, 16, 31] {
            for mu in [1e-3, 0.3, 0.5, 0.77] {
                let points = m + 1;
                let mut triangle = vec![vec![0.0; points]; points];
                triangle[0][0] = 1.0;
                for i in 1..points {
                    for k in 0..=i {
                        let same = if k < i {
                            (1.0 - mu) * triangle[i - 1][k]
                        } else {
                            0.0
                        };
                        let below = if k > 0 {
                            mu * triangle[i - 1][k - 1]
                        } else {
                            0.0
                        };
                        triangle[i][k] = same + below;
                    }
                }
                let s = restrictions(m, &[0.0, mu, 1.0]);
                for i in 0..points {
                    for k in 0..points {
                        let left = if k <= i { triangle[i][k] } else { 0.0 };
                        let right = if k >= i { triangle[m - i][k - i] } else { 0.0 };
                        assert_eq!(s[(i, k)].to_bits(), left.to_bits(), "m {m} mu {mu}");
                        assert_eq!(
                            s[(points + i, k)].to_bits(),
                            right.to_bits(),
                            "m {m} mu {mu}"
                        );
                    }
                }
            }
        }
    }

    /// The constant-size remainders `t - A y` are the general one bit for
    /// bit (random signed entries with zeros of both signs; the row counts
    /// of the dispatch, 1..3 free columns and coordinates).
    #[test]
    fn constant_size_remainders_are_the_general_one() {
        let mut values = crate::test_values::Values(53);
        for rows in [4, 6, 8, 10, 12] {
            for free in 1..=3 {
                for dim in 1..=3 {
                    let t = random_matrix(&mut values, rows, dim);
                    let a = random_matrix(&mut values, rows, free);
                    let y = random_matrix(&mut values, free, dim);
                    let (t, a, y) = (t.as_slice(), a.as_slice(), y.as_slice());
                    let (mut general, mut sized) = (vec![0.0; rows * dim], vec![0.0; rows * dim]);
                    remainder_sized::<0>(&mut general, t, a, y, rows, free);
                    match rows {
                        4 => remainder_sized::<4>(&mut sized, t, a, y, rows, free),
                        6 => remainder_sized::<6>(&mut sized, t, a, y, rows, free),
                        8 => remainder_sized::<8>(&mut sized, t, a, y, rows, free),
                        10 => remainder_sized::<10>(&mut sized, t, a, y, rows, free),
                        _ => remainder_sized::<12>(&mut sized, t, a, y, rows, free),
                    }
                    let bits = crate::test_values::bits;
                    assert_eq!(bits(&general), bits(&sized), "{rows} x {free}, dim {dim}");
                }
            }
        }
    }

    /// The constant-size restriction matrices of two pieces are the
    /// general one bit for bit (random `mu`, 2..8 points).
    #[test]
    fn constant_size_restrictions_are_the_general_one() {
        let mut values = crate::test_values::Values(43);
        for points in 2..=8 {
            for _ in 0..100 {
                let mu = values.unit();
                let len = 2 * points * points;
                let (mut general, mut sized) = (vec![0.0; len], vec![0.0; len]);
                restrictions_two::<0>(points - 1, mu, &mut general);
                restrictions_into(points - 1, &[0.0, mu, 1.0], &mut sized);
                let bits = crate::test_values::bits;
                assert_eq!(bits(&general), bits(&sized), "{points} points, mu = {mu}");
            }
        }
    }

    /// The constant-size splits of a column are the general one bit for
    /// bit, and both are `split_unchecked`'s halves: random values, random
    /// `t` in `[0, 1)`.
    #[test]
    fn constant_size_split_columns_are_the_general_one() {
        let mut values = crate::test_values::Values(41);
        for points in 2..=8 {
            for _ in 0..200 {
                let from: Vec<f64> = (0..points).map(|_| values.signed() * 1e3).collect();
                let t = values.unit();
                let mut general = vec![0.0; 2 * points];
                let mut sized = vec![0.0; 2 * points];
                split_column(&mut general, &from, t);
                match points {
                    2 => split_column_sized::<2>(&mut sized, &from, t),
                    3 => split_column_sized::<3>(&mut sized, &from, t),
                    4 => split_column_sized::<4>(&mut sized, &from, t),
                    5 => split_column_sized::<5>(&mut sized, &from, t),
                    6 => split_column_sized::<6>(&mut sized, &from, t),
                    7 => split_column_sized::<7>(&mut sized, &from, t),
                    _ => split_column_sized::<8>(&mut sized, &from, t),
                }
                let bits = crate::test_values::bits;
                assert_eq!(bits(&general), bits(&sized), "{points} points, t = {t}");
                // And the curve's own split, point by point.
                let curve = BezierCurve::new(1, points - 1, from.clone()).expect("a curve");
                let (l, r) = curve.split_unchecked(t);
                let expected: Vec<f64> = l.points().iter().chain(r.points()).copied().collect();
                assert_eq!(bits(&general), bits(&expected), "{points} points, t = {t}");
            }
        }
    }

    /// The constant-size product columns are the general one bit for bit
    /// (the same sums in the same order), with and without `abs`.
    #[test]
    fn constant_size_product_columns_are_the_general_one() {
        let mut values = crate::test_values::Values(43);
        for rows in [4, 6, 8, 10, 12] {
            for inner in [1, 2, 3, 5, 9] {
                let a = random_matrix(&mut values, rows, inner);
                let b = random_matrix(&mut values, inner, 1);
                for abs in [false, true] {
                    let (mut sized, mut general) = (vec![0.0; rows], vec![0.0; rows]);
                    product_columns(&a, b.as_slice(), abs, &mut sized);
                    product_columns_sized::<0>(a.as_slice(), rows, b.as_slice(), abs, &mut general);
                    let bits = crate::test_values::bits;
                    assert_eq!(bits(&sized), bits(&general), "{rows} x {inner} {abs}");
                }
            }
        }
    }

    /// The first-order bound with the sizes as constants (rows, free
    /// columns and the map's rows) is the general one bit for bit, for the
    /// thin Q, an identity and a matrix map, with and without the normwise
    /// part.
    #[test]
    fn constant_size_first_order_bound_is_the_general_one() {
        let mut values = crate::test_values::Values(13);
        for (rows, free) in [
            (6, 1),
            (8, 2),
            (10, 3),
            (12, 4),
            (4, 2),
            (6, 3),
            (8, 4),
            (7, 3),
        ] {
            for dim in [1, 3, 7] {
                let inputs = bound_inputs(&mut values, rows, free, dim);
                let correction = inputs.correction.clone() * 1e-17;
                let mut buffer = Vec::new();
                let shared = inputs.shared(&inputs.a, rows / 2, &correction, &mut buffer);
                let map = random_matrix(&mut values, rows + 1, free);
                for normwise in [false, true] {
                    for which in [Map::Factor, Map::Identity(free), Map::Of((&map).into())] {
                        let mut scratch = Scratch::default();
                        let sized = first_order_bound(&shared, which, normwise, &mut scratch);
                        let mut scratch = Scratch::default();
                        let general = first_order_bound_sized::<0, 0, 0>(
                            &shared,
                            which,
                            normwise,
                            &mut scratch,
                        );
                        let bits = |b: Option<(f64, f64, bool)>| {
                            b.map(|(x, y, z)| (x.to_bits(), y.to_bits(), z))
                        };
                        assert_eq!(bits(sized), bits(general), "{rows} x {free}, {dim}");
                        assert!(sized.is_some_and(|b| b.0 > 0.0));
                    }
                }
            }
        }
    }

    /// `Shared`'s correction (a slice of the solves' buffer) is the
    /// `free x dim` matrix it was built from, bit for bit and in shape, and
    /// a map's product with its view is the product with that matrix bit
    /// for bit, also where nalgebra takes `matrixmultiply` (the blocked
    /// sizes, `blocked_product`) and with exact zeros of either sign.
    #[test]
    fn shared_correction_is_the_matrix_it_was_given() {
        let mut values = crate::test_values::Values(23);
        let bits = |m: &DMatrix<f64>| {
            let mut b: Vec<u64> = m.iter().map(|x| x.to_bits()).collect();
            b.extend([m.nrows() as u64, m.ncols() as u64]);
            b
        };
        for (rows, free, dim, out) in [
            (8, 2, 3, 5),
            (12, 4, 1, 3),
            (14, 7, 6, 9),
            (20, 9, 7, 16),
            (30, 6, 13, 8),
        ] {
            let inputs = bound_inputs(&mut values, rows, free, dim);
            let mut buffer = Vec::new();
            let shared = inputs.shared(&inputs.a, rows / 2, &inputs.correction, &mut buffer);
            assert_eq!(
                bits(&shared.correction().into_owned()),
                bits(&inputs.correction)
            );
            let map = random_matrix(&mut values, out, free);
            assert_eq!(
                bits(&(&map * shared.correction())),
                bits(&(&map * &inputs.correction)),
                "{rows} x {free} x {dim}, map {out} rows"
            );
            assert_eq!(
                (&map * shared.correction()).amax().to_bits(),
                (&map * &inputs.correction).amax().to_bits()
            );
        }
    }

    /// `Shared`'s one buffer holds the thin `Q`, `|t| + |A| |y|` and `|A|^T
    /// |res|` as the separate matrices did, bit for bit.
    #[test]
    fn shared_buffer_holds_the_three_matrices() {
        let mut values = crate::test_values::Values(19);
        for (rows, free, dim) in [(8, 2, 3), (6, 1, 2), (12, 4, 1), (9, 5, 7)] {
            let inputs = bound_inputs(&mut values, rows, free, dim);
            let mut buffer = Vec::new();
            let shared = inputs.shared(&inputs.a, rows / 2, &inputs.correction, &mut buffer);
            let bits = crate::test_values::bits;
            assert_eq!(bits(shared.q()), bits(&shared.qr.thin_q()));
            let through_values =
                combined_product(&inputs.target_size, &inputs.a, &inputs.y, Combine::PlusAbs);
            assert_eq!(
                bits(shared.through_values()),
                bits(through_values.as_slice())
            );
            let through_residual = abs_tr_mul(&inputs.a, &inputs.residual);
            assert_eq!(
                bits(shared.through_residual()),
                bits(through_residual.as_slice())
            );
        }
    }

    /// `Map::Identity` (no matrix) gives what an identity matrix gives,
    /// bit for bit, for `R`'s guard and with the normwise part, on both
    /// sides of nalgebra's `matrixmultiply` threshold, with zero and
    /// negative corrections.
    #[test]
    fn identity_map_is_the_identity_matrix_to_the_bit() {
        let mut values = crate::test_values::Values(11);
        for (free, dim) in [(1, 1), (2, 3), (3, 2), (6, 7), (9, 3), (7, 6)] {
            let rows = 2 * free + 2;
            let inputs = bound_inputs(&mut values, rows, free, dim);
            let mut correction = inputs.correction.clone() * 1e-17;
            correction[(0, 0)] = 0.0;
            correction[(free - 1, dim - 1)] = -0.0;
            let mut buffer = Vec::new();
            let shared = inputs.shared(&inputs.a, 2 * free, &correction, &mut buffer);
            let identity = DMatrix::identity(free, free);
            let mut scratch = Scratch::default();
            for normwise in [false, true] {
                let matrix =
                    first_order_bound(&shared, Map::Of((&identity).into()), normwise, &mut scratch)
                        .unwrap();
                let map = first_order_bound(&shared, Map::Identity(free), normwise, &mut scratch)
                    .unwrap();
                assert_eq!(
                    matrix.0.to_bits(),
                    map.0.to_bits(),
                    "{free} {dim} {normwise}"
                );
                assert_eq!(
                    matrix.1.to_bits(),
                    map.1.to_bits(),
                    "{free} {dim} {normwise}"
                );
                assert_eq!(matrix.2, map.2);
                assert!(map.0 > 0.0);
            }
        }
    }

    /// `R`'s guard through the fixed ends' `Z = (e_1 .. e_(m-1))` is the
    /// guard through the identity of the free columns (what the closed
    /// form passes), bit for bit: the zero rows of `Z` add nothing.
    #[test]
    fn selection_guard_is_the_identity_guard() {
        let mut values = crate::test_values::Values(7);
        for m in [2, 3, 5, 9, 20] {
            let (rows, free, dim) = (2 * (m + 1), m - 1, 2);
            let inputs = bound_inputs(&mut values, rows, free, dim);
            let a_abs = inputs.a.abs();
            let correction = inputs.correction.clone() * 1e-17;
            let mut buffer = Vec::new();
            let shared = inputs.shared(&a_abs, m, &correction, &mut buffer);
            let z = DMatrix::from_fn(m + 1, free, |i, k| if i == k + 1 { 1.0 } else { 0.0 });
            let mut scratch = Scratch::default();
            let through_z =
                first_order_bound(&shared, Map::Of((&z).into()), false, &mut scratch).unwrap();
            let identity = DMatrix::identity(free, free);
            let through_i =
                first_order_bound(&shared, Map::Of((&identity).into()), false, &mut scratch)
                    .unwrap();
            let through_map =
                first_order_bound(&shared, Map::Identity(free), false, &mut scratch).unwrap();
            assert_eq!(through_z.0.to_bits(), through_i.0.to_bits(), "m {m}");
            assert_eq!(through_map.0.to_bits(), through_i.0.to_bits(), "m {m}");
            assert_eq!(through_map.1.to_bits(), through_i.1.to_bits(), "m {m}");
            assert!(through_z.0 > 0.0, "m {m}");
        }
    }
}
