//! Householder QR of the orthogonal stage 1's least-squares matrix on flat
//! column-major buffers, with the reflectors kept: `Q^T` and `Q` are
//! applied from them, the thin `Q` is formed from them only when the error
//! estimate needs its entries, and the triangular solves with `T` and
//! `T^T` run in place. One factor per solve, no temporaries per product.
//!
//! The factor is the textbook one (Golub & Van Loan, Algorithm 5.2.1):
//! column `k` is reflected onto `alpha_k e_k` with `alpha_k = -sign(a_kk)
//! ||a_k..||`, the reflector `v_k = a_k.. - alpha_k e_1` is stored in place
//! below and on the diagonal, `H_k = I - beta_k v_k v_k^T` with `beta_k =
//! 1 / (||a_k..|| (||a_k..|| + |a_kk|))`, and `A = Q T`, `Q = H_0 H_1 ...`,
//! `T` upper triangular with diagonal `alpha`. Only the signs of `T`'s rows
//! (and `Q`'s columns) may differ from another Householder QR; every
//! quantity the merge uses (`T^-1 Q^T`, `Q Q^T`, the least-squares
//! solution, Frobenius norms) is independent of them.

/// `$call` with the consts `$r`, `$c` bound to the factor's `(rows, cols)`
/// when it is one of the merge's small sizes (two pieces of degree `m`,
/// rows `2 (m + 1)`; `m - 1` free columns with fixed ends, `m = 2..=5`, and
/// `m + 1` without, `m = 1..=3`), else to `(0, 0)` (sizes read at run
/// time, [`Factor::sizes`]): loops of known length, the same operations.
macro_rules! with_small_sizes {
    ($rows:expr, $cols:expr, |$r:ident, $c:ident| $call:expr) => {
        match ($rows, $cols) {
            (6, 1) => {
                const $r: usize = 6;
                const $c: usize = 1;
                $call
            }
            (8, 2) => {
                const $r: usize = 8;
                const $c: usize = 2;
                $call
            }
            (10, 3) => {
                const $r: usize = 10;
                const $c: usize = 3;
                $call
            }
            (12, 4) => {
                const $r: usize = 12;
                const $c: usize = 4;
                $call
            }
            (4, 2) => {
                const $r: usize = 4;
                const $c: usize = 2;
                $call
            }
            (6, 3) => {
                const $r: usize = 6;
                const $c: usize = 3;
                $call
            }
            (8, 4) => {
                const $r: usize = 8;
                const $c: usize = 4;
                $call
            }
            _ => {
                const $r: usize = 0;
                const $c: usize = 0;
                $call
            }
        }
    };
}
pub(super) use with_small_sizes;

/// `A = Q T` of a `rows x cols` matrix (`rows >= cols`), reflectors kept,
/// in the caller's buffer ([`Factor::packed_len`] entries).
#[derive(Clone, Copy)]
pub(super) struct Factor<'p> {
    rows: usize,
    cols: usize,
    /// Column-major `rows x cols`: `v_k` in column `k` from row `k` down,
    /// `T`'s strict upper part above the diagonal; then `T`'s diagonal
    /// `alpha_k` (`cols`), then `beta_k` (`cols`).
    packed: &'p [f64],
}

/// `sum_i a_i b_i` over the common length, in four interleaved partial
/// sums (so that the compiler can keep them in vector registers), added
/// pairwise at the end.
#[inline]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    let n = a.len().min(b.len());
    let (a, b) = (&a[..n], &b[..n]);
    let (mut s0, mut s1, mut s2, mut s3) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        let x: &[f64; 4] = x.try_into().expect("4 entries");
        let y: &[f64; 4] = y.try_into().expect("4 entries");
        s0 += x[0] * y[0];
        s1 += x[1] * y[1];
        s2 += x[2] * y[2];
        s3 += x[3] * y[3];
    }
    ((s0 + s2) + (s1 + s3)) + tail
}

/// `x -= beta (v^T x) v`.
#[inline]
fn reflect(v: &[f64], x: &mut [f64], beta: f64) {
    let s = beta * dot(v, x);
    for (xi, vi) in x.iter_mut().zip(v) {
        *xi -= s * vi;
    }
}

impl<'p> Factor<'p> {
    /// The entries of a factor's buffer for a `rows x cols` matrix.
    pub(super) fn packed_len(rows: usize, cols: usize) -> usize {
        rows * cols + 2 * cols
    }

    /// The factor of `a` (column-major `rows x cols`) in `packed`
    /// ([`Factor::packed_len`] entries, any contents); `None` when a column
    /// is (numerically) zero below the diagonal or not finite, i.e. `T`
    /// would have a zero or non-finite pivot.
    pub(super) fn new(a: &[f64], rows: usize, cols: usize, packed: &'p mut [f64]) -> Option<Self> {
        debug_assert!(rows >= cols && a.len() == rows * cols);
        let size = rows * cols;
        assert_eq!(packed.len(), Self::packed_len(rows, cols));
        // T's diagonal and the betas are written column by column below.
        packed[..size].copy_from_slice(a);
        let (matrix, rest) = packed.split_at_mut(size);
        let (diagonal, beta) = rest.split_at_mut(cols);
        for k in 0..cols {
            let packed = &mut *matrix;
            let column = &packed[k * rows..(k + 1) * rows];
            let norm = dot(&column[k..], &column[k..]).sqrt();
            if !(norm > 0.0 && norm.is_finite()) {
                return None;
            }
            let akk = column[k];
            let alpha = if akk > 0.0 { -norm } else { norm };
            packed[k * rows + k] = akk - alpha;
            beta[k] = 1.0 / (norm * (norm + akk.abs()));
            diagonal[k] = alpha;
            let (before, after) = packed.split_at_mut((k + 1) * rows);
            let v = &before[k * rows + k..(k + 1) * rows];
            for j in 0..cols - k - 1 {
                reflect(v, &mut after[j * rows + k..(j + 1) * rows], beta[k]);
            }
        }
        Some(Self { rows, cols, packed })
    }

    pub(super) fn rows(&self) -> usize {
        self.rows
    }

    pub(super) fn cols(&self) -> usize {
        self.cols
    }

    /// `T[i][j]`, `i <= j`.
    #[cfg(test)]
    fn t(&self, i: usize, j: usize) -> f64 {
        if i == j {
            self.diagonal()[i]
        } else {
            self.packed[j * self.rows + i]
        }
    }

    /// `x <- Q^T x` (one column of length `rows`).
    #[cfg(test)]
    pub(super) fn apply_qt(&self, x: &mut [f64]) {
        self.apply_qt_sized::<0, 0>(x);
    }

    /// `(rows, cols)`: `(R, C)` when `R > 0` (sizes known at compile
    /// time), else the factor's own.
    #[inline(always)]
    pub(super) fn sizes<const R: usize, const C: usize>(&self) -> (usize, usize) {
        if R == 0 {
            (self.rows, self.cols)
        } else {
            debug_assert_eq!((R, C), (self.rows, self.cols));
            (R, C)
        }
    }

    /// `Self::apply_qt` (test-only) with the sizes of [`Self::sizes`].
    #[inline(always)]
    fn apply_qt_sized<const R: usize, const C: usize>(&self, x: &mut [f64]) {
        let (rows, cols) = self.sizes::<R, C>();
        let beta = &self.packed[rows * cols + cols..];
        for k in 0..cols {
            reflect(
                &self.packed[k * rows + k..(k + 1) * rows],
                &mut x[k..],
                beta[k],
            );
        }
    }

    /// `T`'s column `j` above the diagonal (`j` entries).
    pub(super) fn t_column(&self, j: usize) -> &[f64] {
        &self.packed[j * self.rows..j * self.rows + j]
    }

    /// `T`'s diagonal.
    pub(super) fn diagonal(&self) -> &[f64] {
        let size = self.rows * self.cols;
        &self.packed[size..size + self.cols]
    }

    /// `y <- T^-1 y` (the first `cols` entries), column by column.
    #[cfg(test)]
    pub(super) fn solve_t(&self, y: &mut [f64]) {
        let mut work = y[..self.cols].to_vec();
        self.solve_leading_t_into::<0, 0>(&mut work, &mut y[..self.cols]);
    }

    /// `||T^-1||_F`: column `k` of `T^-1` from `e_k` on the leading
    /// `(k + 1) x (k + 1)` block (`T^-1` is upper triangular), column by
    /// column as [`Self::solve_leading_t_into`].
    pub(super) fn inverse_frobenius(&self) -> f64 {
        let mut total = 0.0;
        let mut e = vec![0.0; self.cols];
        let mut column = vec![0.0; self.cols];
        for k in 0..self.cols {
            let e = &mut e[..=k];
            e.fill(0.0);
            e[k] = 1.0;
            let column = &mut column[..=k];
            self.solve_leading_t_into::<0, 0>(e, column);
            total += column.iter().map(|v| v * v).sum::<f64>();
        }
        total.sqrt()
    }

    /// `x <- T x` (the first `cols` entries).
    #[cfg(test)]
    pub(super) fn mul_t(&self, x: &mut [f64]) {
        self.mul_t_sized::<0, 0>(x);
    }

    /// `Self::mul_t` (test-only) with the sizes of [`Self::sizes`]: row `i` is
    /// `T[i][i] x_i + T[i][i+1] x_(i+1) + ...` in that order.
    #[inline(always)]
    pub(super) fn mul_t_sized<const R: usize, const C: usize>(&self, x: &mut [f64]) {
        let (rows, cols) = self.sizes::<R, C>();
        let diagonal = &self.packed[rows * cols..rows * cols + cols];
        let x = &mut x[..cols];
        for i in 0..cols {
            let mut sum = diagonal[i] * x[i];
            for (j, &xj) in x.iter().enumerate().skip(i + 1) {
                sum += self.packed[j * rows + i] * xj;
            }
            x[i] = sum;
        }
    }

    /// The least-squares solution of `min ||A y - b||` for every column of
    /// `b` (column-major `rows x dim`) into `y` (`cols x dim`), with
    /// `work` (`rows`) as scratch.
    pub(super) fn least_squares(&self, b: &[f64], y: &mut [f64], work: &mut [f64]) {
        with_small_sizes!(self.rows, self.cols, |R, C| self
            .least_squares_sized::<R, C>(b, y, work))
    }

    /// [`Self::least_squares`] with the sizes of [`Self::sizes`]:
    /// [`Self::apply_qt_sized`] then [`Self::solve_leading_t_into`] per column, inlined; the
    /// solve writes each solved entry straight to `y`.
    ///
    /// (Not a copy of the solved entries from `work` afterwards: that copy
    /// read, as one wide load, entries the solve had just stored one by one,
    /// a store-forwarding stall that cost 45 % of this function's time
    /// whenever the compiler vectorised the copy, issue 20, session 49.)
    #[inline(always)]
    fn least_squares_sized<const R: usize, const C: usize>(
        &self,
        b: &[f64],
        y: &mut [f64],
        work: &mut [f64],
    ) {
        let (rows, cols) = self.sizes::<R, C>();
        for (column, out) in b.chunks_exact(rows).zip(y.chunks_exact_mut(cols)) {
            let work = &mut work[..rows];
            work.copy_from_slice(column);
            self.apply_qt_sized::<R, C>(work);
            self.solve_leading_t_into::<R, C>(&mut work[..cols], out);
        }
    }

    /// `T_k^-1 y` on the leading `k x k` block of `T`, `k = y.len() <=
    /// cols`, column by column from the last (the sizes of [`Self::sizes`]),
    /// each solved entry written to `out` (`k` entries); `y` is scratch.
    #[inline(always)]
    fn solve_leading_t_into<const R: usize, const C: usize>(&self, y: &mut [f64], out: &mut [f64]) {
        let (rows, cols) = self.sizes::<R, C>();
        let diagonal = &self.packed[rows * cols..rows * cols + cols];
        let out = &mut out[..y.len()];
        for j in (0..y.len()).rev() {
            let yj = y[j] / diagonal[j];
            out[j] = yj;
            for (yi, &t) in y[..j].iter_mut().zip(&self.packed[j * rows..j * rows + j]) {
                *yi -= t * yj;
            }
        }
    }

    /// The thin `Q` (column-major `rows x cols`), from the reflectors
    /// ([`Factor::thin_q_into`] into a new vector).
    #[cfg(test)]
    pub(super) fn thin_q(&self) -> Vec<f64> {
        let mut q = vec![0.0; self.rows * self.cols];
        self.thin_q_into(&mut q);
        q
    }

    /// The thin `Q` (column-major `rows x cols`), from the reflectors, into
    /// `q` (`rows x cols` entries, all zero).
    pub(super) fn thin_q_into(&self, q: &mut [f64]) {
        with_small_sizes!(self.rows, self.cols, |R, C| self
            .thin_q_into_sized::<R, C>(q))
    }

    /// [`Self::thin_q_into`] with the sizes of [`Self::sizes`].
    #[inline(always)]
    fn thin_q_into_sized<const R: usize, const C: usize>(&self, q: &mut [f64]) {
        let (rows, cols) = self.sizes::<R, C>();
        debug_assert!(q.len() == rows * cols && q.iter().all(|&v| v == 0.0));
        let beta = &self.packed[rows * cols + cols..];
        for (k, column) in q[..rows * cols].chunks_exact_mut(rows).enumerate() {
            column[k] = 1.0;
            // Q e_k = H_0 ... H_(cols-1) e_k: H_j for j > k acts on rows
            // j.. only, where e_k is zero, so H_k is the first to apply.
            for j in (0..=k).rev() {
                let reflector = &self.packed[j * rows + j..(j + 1) * rows];
                reflect(reflector, &mut column[j..], beta[j]);
            }
        }
    }
}

/// `max |x_i|` (NaN passed over, as nalgebra's `amax`): the fold from `0`
/// by `f64::max`, as [`raise`] (one compare per entry).
#[inline]
pub(super) fn amax(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |m, v| raise(m, v.abs()))
}

/// Whether every entry is finite: the same answer as `iter().all(..)`,
/// without its early exit (every entry read; a loop the compiler can
/// widen, cheaper on the merge's short, finite slices).
#[inline]
pub(super) fn all_finite(x: &[f64]) -> bool {
    x.iter().fold(true, |finite, v| finite & v.is_finite())
}

/// `m.max(a)` for a largest value so far `m` that is not NaN and a
/// candidate `a` that is not `-0` (an absolute value, or a product of
/// them), as `a > m` keeps `a`, else `m` (one `maxsd`): the same value
/// (a NaN `a` compares false and is passed over, as `f64::max` passes it
/// over; equal values are the same bits, `+0` against `+0`).
#[inline(always)]
pub(super) fn raise(m: f64, a: f64) -> f64 {
    if a > m { a } else { m }
}

/// nalgebra's `amax` of a matrix with these entries, bit for bit: `|x_0|`
/// (`0` for no entries), then simba's `simd_max` (`m >= a` keeps `m`, else
/// `a`: a NaN entry replaces the maximum so far) with every further
/// `|x_i|` in order, read from the slice. Without NaN entries it is
/// [`amax`].
pub(super) fn nalgebra_amax(x: &[f64]) -> f64 {
    let mut entries = x.iter();
    let first = entries.next().map_or(0.0, |v| v.abs());
    entries.fold(first, |m, v| {
        let a = v.abs();
        if m >= a { m } else { a }
    })
}

/// The Frobenius (2-) norm `sqrt(sum x_i^2)`.
pub(super) fn norm(x: &[f64]) -> f64 {
    dot(x, x).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// [`amax`] is the fold from `0` by `f64::max` bit for bit, and
    /// [`raise`] is `f64::max` on every step of it: random entries with
    /// signed zeros, infinities, NaNs and subnormals.
    #[test]
    fn amax_is_the_max_fold_to_the_bit() {
        let mut values = crate::test_values::Values(36);
        for len in 0..40 {
            for round in 0..40 {
                let x: Vec<f64> = (0..len).map(|_| values.hostile(round)).collect();
                let fold = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert_eq!(amax(&x).to_bits(), fold.to_bits(), "{x:?}");
                // `raise` against `f64::max` from every partial maximum.
                let mut m = 0.0f64;
                for v in &x {
                    assert_eq!(raise(m, v.abs()).to_bits(), m.max(v.abs()).to_bits());
                    m = m.max(v.abs());
                }
            }
        }
    }

    /// [`all_finite`] is `iter().all(is_finite)`: random entries with
    /// NaNs and infinities anywhere, and none.
    #[test]
    fn all_finite_is_all() {
        let mut values = crate::test_values::Values(37);
        for len in 0..30 {
            for _ in 0..40 {
                let x: Vec<f64> = (0..len)
                    .map(|_| match (values.unit() * 40.0) as u32 {
                        0 => f64::NAN,
                        1 => f64::INFINITY,
                        2 => f64::NEG_INFINITY,
                        _ => values.signed(),
                    })
                    .collect();
                assert_eq!(all_finite(&x), x.iter().all(|v| v.is_finite()), "{x:?}");
            }
        }
    }

    /// [`nalgebra_amax`] is nalgebra's `amax` bit for bit, and so is
    /// [`amax`] without NaN entries: random entries with signed zeros,
    /// infinities, NaNs (also first, also all NaN) and subnormals, and no
    /// entries.
    #[test]
    fn slice_amax_is_nalgebras_to_the_bit() {
        let mut values = crate::test_values::Values(35);
        for len in 0..40 {
            for round in 0..30 {
                let m = DMatrix::from_fn(len, 1, |_, _| values.hostile(round));
                assert_eq!(
                    nalgebra_amax(m.as_slice()).to_bits(),
                    m.amax().to_bits(),
                    "{len} entries, round {round}"
                );
                let nan = m.iter().any(|v| v.is_nan());
                if !nan {
                    assert_eq!(
                        amax(m.as_slice()).to_bits(),
                        m.amax().to_bits(),
                        "{len} entries, round {round}"
                    );
                }
            }
        }
    }

    fn matrix(state: &mut u64, rows: usize, cols: usize) -> DMatrix<f64> {
        DMatrix::from_fn(rows, cols, |_, _| {
            *state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (*state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
    }

    /// The defining properties of the factor: `Q T = A`, `Q^T Q = I`,
    /// `T` upper triangular; `Q^T`, `T`, `T^-1` applied from it
    /// are those matrices; the least-squares solution satisfies the normal
    /// equations `A^T (A y - b) = 0`.
    #[test]
    fn factor_is_a_qr_and_its_applications_are_the_matrices() {
        let mut state = 7;
        for (rows, cols) in [(1, 1), (4, 2), (8, 4), (8, 2), (32, 16), (20, 20), (64, 31)] {
            let a = matrix(&mut state, rows, cols);
            let mut packed = vec![0.0; Factor::packed_len(rows, cols)];
            let f = Factor::new(a.as_slice(), rows, cols, &mut packed).unwrap();
            let q = DMatrix::from_column_slice(rows, cols, &f.thin_q());
            let t = DMatrix::from_fn(cols, cols, |i, j| if i <= j { f.t(i, j) } else { 0.0 });
            let tol = 64.0 * (rows as f64) * f64::EPSILON;
            assert!((&q * &t - &a).amax() <= tol, "{rows}x{cols}: QT != A");
            assert!(
                (q.transpose() * &q - DMatrix::identity(cols, cols)).amax() <= tol,
                "{rows}x{cols}: Q not orthonormal"
            );
            let x = matrix(&mut state, rows, 1);
            let mut qt = x.as_slice().to_vec();
            f.apply_qt(&mut qt);
            let head = DMatrix::from_column_slice(cols, 1, &qt[..cols]);
            assert!(
                (head - q.transpose() * &x).amax() <= tol,
                "{rows}x{cols}: Q^T x"
            );
            let mut y = x.as_slice()[..cols].to_vec();
            f.solve_t(&mut y);
            let yv = DMatrix::from_column_slice(cols, 1, &y);
            let xv = DMatrix::from_column_slice(cols, 1, &x.as_slice()[..cols]);
            let scale = 1.0 + yv.amax() * t.amax();
            assert!(
                (&t * &yv - &xv).amax() <= tol * scale,
                "{rows}x{cols}: T^-1"
            );
            let mut w = xv.as_slice().to_vec();
            f.mul_t(&mut w);
            assert!((DMatrix::from_column_slice(cols, 1, &w) - &t * &xv).amax() <= tol * t.amax());
            let mut ls = vec![0.0; cols];
            let mut work = vec![0.0; rows];
            f.least_squares(x.as_slice(), &mut ls, &mut work);
            let ls = DMatrix::from_column_slice(cols, 1, &ls);
            let normal = a.transpose() * (&a * &ls - &x);
            let scale = 1.0 + ls.amax() * a.amax() * (rows as f64);
            assert!(
                normal.amax() <= tol * scale,
                "{rows}x{cols}: normal equations"
            );
        }
        // A zero column has no factor.
        let mut packed = [0.0; 8];
        assert!(Factor::new(&[1.0, 2.0, 0.0, 0.0], 2, 2, &mut packed).is_none());
    }

    /// The least-squares solve with the sizes as constants (every size of
    /// the dispatch) is the general loop run with the sizes unknown at
    /// compile time, to the bit, on random matrices and right-hand sides.
    #[test]
    fn constant_size_solves_are_the_general_one_to_the_bit() {
        use std::hint::black_box;
        let mut state = 11;
        for (rows, cols) in [
            (6, 1),
            (8, 2),
            (10, 3),
            (12, 4),
            (4, 2),
            (6, 3),
            (8, 4),
            (9, 2),
        ] {
            for _ in 0..20 {
                let a = matrix(&mut state, rows, cols);
                let b = matrix(&mut state, rows, 3);
                let mut packed = vec![0.0; Factor::packed_len(rows, cols)];
                let f = Factor::new(a.as_slice(), rows, cols, &mut packed).unwrap();
                let (mut fast, mut general) = (vec![0.0; cols * 3], vec![0.0; cols * 3]);
                let mut work = vec![0.0; rows];
                f.least_squares(b.as_slice(), &mut fast, &mut work);
                black_box(&f).least_squares_sized::<0, 0>(b.as_slice(), &mut general, &mut work);
                let bits = crate::test_values::bits;
                assert_eq!(bits(&fast), bits(&general), "{rows}x{cols}");
            }
        }
    }
}
