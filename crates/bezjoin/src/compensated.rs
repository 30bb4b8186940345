//! Compensated arithmetic: double-double numbers (error-free transforms
//! TwoSum and TwoProduct) and the compensated de Casteljau blossom used
//! where plain rounding would lose `(2/mu - 1)^n` units in the last place
//! (the kept-piece path of [`crate::merge()`]).

use nalgebra::DMatrix;

/// A double-double number `hi + lo` (`|lo| <= ulp(hi) / 2`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DoubleDouble {
    pub(crate) hi: f64,
    pub(crate) lo: f64,
}

/// `a + b = s + e` exactly (Knuth's TwoSum).
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a b = p + e` exactly (fused multiply-add).
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// `(t - origin) / (end - origin)` to about `eps^2` relative: the
/// differences are exact double-doubles, the quotient is corrected once.
pub(crate) fn relative_parameter(t: f64, origin: f64, end: f64) -> DoubleDouble {
    let (nh, nl) = two_sum(t, -origin);
    let (dh, dl) = two_sum(end, -origin);
    let q = nh / dh;
    // remainder = (nh + nl) - q (dh + dl), the first product exactly.
    let (ph, pl) = two_product(q, dh);
    let remainder = ((nh - ph) - pl) + nl - q * dl;
    let (hi, lo) = two_sum(q, remainder / dh);
    DoubleDouble { hi, lo }
}

/// The control points of the curve with control points `points` (rows) on
/// `[a, b]` of its parameter, each the blossom `(a^(n-i), b^i)`, by
/// compensated de Casteljau (Graillat, Langlois, Louvet, "Algorithms for
/// accurate, validated and fast polynomial evaluation", 2009: every step's
/// rounding is captured exactly by TwoSum / TwoProduct and carried in a
/// second recurrence, as are the low parts of `a`, `b` and `1 - t`), with a
/// bound on each result's error: `2 eps |value| + 2 (3 n eps)^2 |blossom|`,
/// where `|blossom|` is the same recurrence on `|p|` with weights
/// `|1 - t|`, `|t|` (twice the published `eps |value| + 2 gamma_3n^2
/// |blossom|` for the low parts of the parameters). Far outside `[0, 1]`
/// the weights sum to `(|1 - a| + |a|)^(n-i) (|1 - b| + |b|)^i`, the
/// `(2/mu - 1)^n` of the spec: plain de Casteljau loses that many units in
/// the last place, the compensated one only its square times `eps^2`, so
/// the answer stays accurate to a few ulps until that product reaches the
/// accuracy. Also returns `|blossom|` (`eps |blossom|` bounds how far half
/// an ulp of rounding in the data moves the result).
pub(crate) fn blossom_segment(
    points: &DMatrix<f64>,
    a: DoubleDouble,
    b: DoubleDouble,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let n = points.nrows() - 1;
    let dim = points.ncols();
    let gamma = 3.0 * n as f64 * f64::EPSILON;
    let mut out = DMatrix::zeros(n + 1, dim);
    let mut bound = DMatrix::zeros(n + 1, dim);
    let mut blossom_abs = DMatrix::zeros(n + 1, dim);
    // One de Casteljau step at t on the first `len` entries of (value,
    // error, absolute) recurrences.
    let step = |value: &mut DMatrix<f64>,
                error: &mut DMatrix<f64>,
                absolute: &mut DMatrix<f64>,
                len: usize,
                t: DoubleDouble| {
        let (sh, sl) = two_sum(1.0, -t.hi);
        let sl = sl - t.lo;
        for j in 0..len - 1 {
            for c in 0..dim {
                let (p, q) = (value[(j, c)], value[(j + 1, c)]);
                let (p1, pi1) = two_product(sh, p);
                let (p2, pi2) = two_product(t.hi, q);
                let (sum, sigma) = two_sum(p1, p2);
                value[(j, c)] = sum;
                error[(j, c)] = sh * error[(j, c)]
                    + t.hi * error[(j + 1, c)]
                    + (pi1 + pi2 + sigma + sl * p + t.lo * q);
                absolute[(j, c)] = sh.abs() * absolute[(j, c)] + t.hi.abs() * absolute[(j + 1, c)];
            }
        }
    };
    // `level` holds the blossom values (b^i, ...) after i steps at b.
    let mut level = points.clone();
    let mut level_error = DMatrix::zeros(n + 1, dim);
    let mut level_abs = points.abs();
    for i in 0..=n {
        let len = n + 1 - i;
        let mut value = level.rows(0, len).into_owned();
        let mut error = level_error.rows(0, len).into_owned();
        let mut absolute = level_abs.rows(0, len).into_owned();
        for done in 0..len - 1 {
            step(&mut value, &mut error, &mut absolute, len - done, a);
        }
        for c in 0..dim {
            let result = value[(0, c)] + error[(0, c)];
            out[(i, c)] = result;
            bound[(i, c)] =
                2.0 * f64::EPSILON * result.abs() + 2.0 * gamma * gamma * absolute[(0, c)];
            blossom_abs[(i, c)] = absolute[(0, c)];
        }
        if i < n {
            step(&mut level, &mut level_error, &mut level_abs, len, b);
        }
    }
    (out, bound, blossom_abs)
}
