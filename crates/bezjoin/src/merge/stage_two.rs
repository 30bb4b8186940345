//! Stage 2: the single curve `R` from the stage-1 pieces, checked by
//! restricting it back to every piece, and the measured deviation.

use std::sync::OnceLock;

use nalgebra::DMatrix;

use crate::bezier::BezierCurve;
use crate::error::{BezjoinError, Result};

use super::stage_one::DEVIATION_SAMPLES;

/// Stage 2: the single curve `R` from the pieces, extrapolated from the
/// piece that reaches `[0, 1]` with the shortest extrapolation (for two
/// pieces the longer one: the error factor `(2/mu - 1)^m` is smallest
/// there), then checked: `R` restricted to every `[t_j, t_{j+1}]` must
/// give back that piece. Returns `R`, the largest control-point
/// difference of that check relative to the coordinate scale, and the
/// restrictions of `R` to the pieces' intervals (for [`max_deviation`]).
///
/// When stage 1 found `R` itself (`found`, the orthogonal path), `R` is
/// taken as it is and only checked.
pub(crate) fn stage_two(
    pieces: &[DMatrix<f64>],
    breakpoints: &[f64],
    accuracy: f64,
    found: Option<&DMatrix<f64>>,
    split_of_merged: bool,
) -> Result<(BezierCurve, f64, Vec<BezierCurve>)> {
    let merged = match found {
        Some(r) => BezierCurve::from_matrix(r)?,
        None => extrapolate(pieces, breakpoints)?,
    };
    if found.is_some() && split_of_merged && pieces.len() == 2 {
        // The pieces are R's split at mu by the operations of the split
        // below (stage 1 computed them so): the restrictions are the pieces
        // themselves and the check's difference is exactly zero (test
        // `split_of_merged_is_the_stage_two_split_to_the_bit`).
        let restrictions = pieces
            .iter()
            .map(BezierCurve::from_matrix)
            .collect::<Result<Vec<_>>>()?;
        return Ok((merged, 0.0, restrictions));
    }
    check_restrictions(merged, pieces, breakpoints, accuracy)
}

/// `R` extrapolated from the piece with the shortest extrapolation, refined.
fn extrapolate(pieces: &[DMatrix<f64>], breakpoints: &[f64]) -> Result<BezierCurve> {
    let lengths: Vec<f64> = breakpoints.windows(2).map(|w| w[1] - w[0]).collect();
    // Extrapolating piece j to [0, 1] runs de Casteljau steps at parameters
    // down to -t_j / h_j and up to 1 + (1 - t_{j+1}) / h_j; each step at a
    // distance s outside [0, 1] multiplies rounding errors by up to 1 + 2s.
    // Take the piece with the shortest reach (for two pieces: the longer).
    let reach = |j: usize| breakpoints[j].max(1.0 - breakpoints[j + 1]) / lengths[j];
    let longest = (0..lengths.len())
        .min_by(|&a, &b| reach(a).total_cmp(&reach(b)))
        .unwrap_or(0);
    let piece = BezierCurve::from_matrix(&pieces[longest])?;
    let h = lengths[longest];
    let start = -breakpoints[longest] / h;
    let end = (1.0 - breakpoints[longest]) / h;
    let mut merged = piece.segment(start, end)?;
    // Refinement: the extrapolation amplifies rounding by up to (2/h - 1)^m;
    // two steps of least-squares correction against ALL pieces (the stacked
    // restriction matrices [S_0; S_1; ...] are well conditioned together,
    // unlike any one of them) remove most of it.
    refine(&mut merged, pieces, breakpoints);
    Ok(merged)
}

/// `R` restricted to every piece's interval against the piece.
pub(super) fn check_restrictions(
    merged: BezierCurve,
    pieces: &[DMatrix<f64>],
    breakpoints: &[f64],
    accuracy: f64,
) -> Result<(BezierCurve, f64, Vec<BezierCurve>)> {
    let scale = pieces
        .iter()
        // As nalgebra's `amax` but 0 for an all-NaN piece: the same after
        // the fold from 0 by `f64::max`.
        .map(|p| super::lsq::amax(p.as_slice()))
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut worst = 0.0f64;
    let mut restrictions = Vec::with_capacity(pieces.len());
    // Two pieces: both restrictions are the edges of one triangle at mu.
    let mut both = None;
    if let &[a, mu, b] = breakpoints
        && a == 0.0
        && b == 1.0
    {
        let (left, right) = merged.split_unchecked(mu);
        if left
            .points()
            .iter()
            .chain(right.points())
            .all(|v| v.is_finite())
        {
            both = Some([left, right]);
        }
    }
    let mut both = both.map(|pair| pair.into_iter());
    for (j, p) in pieces.iter().enumerate() {
        // segment (blossoms) is a second computation of what stage 1's
        // de Casteljau split gave.
        let back = match both.as_mut().and_then(Iterator::next) {
            Some(back) => back,
            None => restriction(&merged, breakpoints[j], breakpoints[j + 1])?,
        };
        // max |back_ic - p_ic| as nalgebra's `amax` of the difference
        // matrix (first entry's magnitude, then f64::max), without forming
        // it: `back` is row-major, `p` column-major.
        let d = back.dim();
        let (rows, data) = (p.nrows(), p.as_slice());
        let mut diff = f64::NAN;
        for (i, point) in back.points().chunks_exact(d).enumerate() {
            for (c, &v) in point.iter().enumerate() {
                let gap = (v - data[c * rows + i]).abs();
                diff = if i == 0 && c == 0 { gap } else { diff.max(gap) };
            }
        }
        worst = worst.max(diff / scale);
        restrictions.push(back);
    }
    if worst.is_nan() || worst > accuracy {
        return Err(BezjoinError::IllConditioned {
            what: format!(
                "merge stage 2 (R of degree {} restricted to the pieces does not give them back)",
                merged.degree()
            ),
            estimate: worst,
            limit: accuracy,
        });
    }
    Ok((merged, worst, restrictions))
}

/// `R` on `[a, b]`: control point `i` is the blossom `R[a^(n-i), b^i]`, as
/// [`BezierCurve::segment`] computes it (`i` de Casteljau steps at `b`,
/// then `n - i` at `a`). On an end piece (`a = 0` or `b = 1`) the steps at
/// `0` and `1` only select points (`1 p + 0 q = p`, `0 p + 1 q = q`
/// exactly for finite values), so the blossoms are the edges of one de
/// Casteljau triangle at the other end, the same values in `O(n^2)`
/// instead of `O(n^3)`; a non-finite result is recomputed by `segment`
/// for its error.
fn restriction(merged: &BezierCurve, a: f64, b: f64) -> Result<BezierCurve> {
    let back = if a == 0.0 {
        merged.split_unchecked(b).0
    } else if b == 1.0 {
        merged.split_unchecked(a).1
    } else {
        return merged.segment(a, b);
    };
    if back.points().iter().all(|v| v.is_finite()) {
        Ok(back)
    } else {
        merged.segment(a, b)
    }
}

/// Restriction matrices: row block `j` maps `R`'s control points to those of
/// `R` on `[t_j, t_{j+1}]` (exact segments of the unit coefficient vectors).
///
/// All unit vectors at once, as one curve of dimension `degree + 1` whose
/// control point `k` is `e_k` (de Casteljau works coordinate by
/// coordinate, so column `k` is the segment of `e_k` alone, the same
/// values), restricted by [`restriction`]: `O(n^3)` for the end pieces
/// instead of `O(n^4)` for `n + 1` separate blossomed segments.
pub(super) fn restriction_matrix(degree: usize, breakpoints: &[f64]) -> DMatrix<f64> {
    let count = breakpoints.len() - 1;
    let points = degree + 1;
    let mut identity = vec![0.0; points * points];
    for k in 0..points {
        identity[k * points + k] = 1.0;
    }
    let basis_curve = BezierCurve::from_parts(points, degree, identity);
    let mut s = DMatrix::zeros(count * points, points);
    for j in 0..count {
        let (a, b) = (breakpoints[j], breakpoints[j + 1]);
        let seg = if a == 0.0 {
            basis_curve.split_unchecked(b).0
        } else if b == 1.0 {
            basis_curve.split_unchecked(a).1
        } else {
            basis_curve.segment_unchecked(a, b)
        };
        for i in 0..points {
            for (k, &v) in seg.point(i).iter().enumerate() {
                s[(j * points + i, k)] = v;
            }
        }
    }
    s
}

pub(super) fn refine(merged: &mut BezierCurve, pieces: &[DMatrix<f64>], breakpoints: &[f64]) {
    let degree = merged.degree();
    let points = degree + 1;
    let s = restriction_matrix(degree, breakpoints);
    let mut target = DMatrix::zeros(s.nrows(), merged.dim());
    for (j, p) in pieces.iter().enumerate() {
        target.rows_mut(j * points, points).copy_from(p);
    }
    let qr = s.clone().qr();
    let (q, r) = (qr.q(), qr.r());
    let mut current = merged.control_matrix();
    for _ in 0..2 {
        let residual = &target - &s * &current;
        let Some(correction) = r.solve_upper_triangular(&(q.transpose() * residual)) else {
            return;
        };
        if correction.iter().any(|v| !v.is_finite()) {
            return;
        }
        current += correction;
    }
    if let Ok(better) = BezierCurve::from_matrix(&current) {
        *merged = better;
    }
}

/// Largest distance between `R` and the original pieces, each compared in
/// its own parameter: `R(t_j + h_j u)` against `C_j(u)` at
/// [`DEVIATION_SAMPLES`]` + 1` evenly spaced `u`.
///
/// `restrictions[j]` is `R` on `[t_j, t_{j+1}]` (from [`stage_two`], by
/// blossoming: `restrictions[j](u) = R(t_j + h_j u)` exactly in exact
/// arithmetic). The difference `R(t_j + h_j u) - C_j(u)` is then one Bezier
/// curve of the working degree, `restrictions[j]` minus `C_j` elevated to
/// it (convex combinations, exact in exact arithmetic), evaluated once per
/// sample instead of evaluating `R` and `C_j` separately: as
/// `sum_i B_i^n(u) D_i` with the Bernstein values at the samples read from
/// a table computed once per degree (up to [`DEVIATION_TABLE_DEGREE`]; by
/// the Bernstein-Horner scheme of [`BezierCurve::eval_into`] above). Both
/// are stable: the table's entries carry `(n + 1) eps` relative, the sum of
/// nonnegative weights another `(n + 1) eps` of `max |D_i|`, so this is the
/// same sampled quantity, changed by rounding only (a few `n eps` of the
/// coordinate scale; tests/merge_accuracy.rs compares it with the
/// two-evaluation form).
///
/// The differences are taken of the halved points (exact, a power of two)
/// and the distance doubled at the end, so that points near the top of the
/// `f64` range do not overflow a difference whose value is in range.
///
/// Errors: none in practice (the working degree is at least every input's,
/// so the elevation cannot fail); its error is passed on.
pub(crate) fn max_deviation(
    restrictions: &[BezierCurve],
    originals: &[&BezierCurve],
) -> Result<f64> {
    let Some(first) = restrictions.first() else {
        return Ok(0.0);
    };
    let (n, d) = (first.degree(), first.dim());
    let len = (n + 1) * d;
    // Half the difference curve of each piece in turn (on the stack for
    // small pieces), its samples noted before the next piece's.
    let mut on_stack = [0.0f64; HALF_ON_STACK];
    let mut on_heap = Vec::new();
    let table = deviation_table(n);
    let mut worst = Worst::default();
    for (back, c) in restrictions.iter().zip(originals) {
        let half: &mut [f64] = if len <= HALF_ON_STACK {
            &mut on_stack[..len]
        } else {
            on_heap.resize(len, 0.0);
            &mut on_heap
        };
        // C_j at the working degree (n >= its degree: working_degree checks
        // it).
        let elevated;
        let c_points = if c.degree() == n {
            c.points()
        } else {
            elevated = c.elevate_degree(n)?;
            elevated.points()
        };
        for ((h, r), c) in half.iter_mut().zip(back.points()).zip(c_points) {
            *h = 0.5 * r - 0.5 * c;
        }
        note_half(n, d, table, half, &mut worst);
    }
    let worst = worst.value();
    Ok(2.0 * worst)
}

/// The largest number of coordinates of [`max_deviation`]'s half
/// difference of one piece kept on the stack (degree 7 in space).
const HALF_ON_STACK: usize = 24;

/// The samples of one (half) difference curve `half` (degree `n`,
/// dimension `d`) noted in `worst`: from the deviation table (`table`,
/// coefficient by coefficient, a few contiguous samples at a time; each
/// sample's sum still taken in the order `i = 0..n`), else one Horner
/// evaluation per sample above the tabulated degrees.
fn note_half(n: usize, d: usize, table: Option<&[f64]>, half: &[f64], worst: &mut Worst) {
    let Some(table) = table else {
        let mut value = vec![0.0; d];
        for s in 0..=DEVIATION_SAMPLES {
            let u = s as f64 / DEVIATION_SAMPLES as f64;
            crate::bezier::bernstein_horner_any(half, n, d, u, 1.0, &mut value);
            worst.note(&value);
        }
        return;
    };
    match d {
        2 => {
            if !deviation_screened::<2>(n, table, half, worst) {
                deviation_fixed::<2>(table, half, worst);
            }
        }
        3 => {
            if !deviation_screened::<3>(n, table, half, worst) {
                deviation_fixed::<3>(table, half, worst);
            }
        }
        _ => {
            let mut value = vec![0.0; d];
            for s in 0..=DEVIATION_SAMPLES {
                value.fill(0.0);
                for (i, p) in half.chunks_exact(d).enumerate() {
                    let b = table[i * TABLE_ROW + s];
                    for (o, x) in value.iter_mut().zip(p) {
                        *o += b * x;
                    }
                }
                worst.note(&value);
            }
        }
    }
}

/// Degrees up to which [`max_deviation`] reads the Bernstein values at its
/// samples from a table computed once per degree ([`TABLE_ROW`]` (n + 1)`
/// values, 70 kB at degree 32); above, it evaluates by Horner.
pub const DEVIATION_TABLE_DEGREE: usize = 32;

/// Samples per piece of [`max_deviation`].
const SAMPLES: usize = DEVIATION_SAMPLES + 1;

/// Samples evaluated together by [`deviation_fixed`] (their partial sums
/// stay in registers while the coefficients are visited).
const LANES: usize = 4;

/// Length of one coefficient's row of the deviation table: the samples,
/// padded with zeros to a multiple of [`LANES`] (a padded sample's value
/// is exactly zero, which changes no maximum).
const TABLE_ROW: usize = SAMPLES.div_ceil(LANES) * LANES;

/// `B_i^n(s / DEVIATION_SAMPLES)`, coefficient-major (entry `i TABLE_ROW +
/// s`, `i = 0..=n`, `s = 0..=DEVIATION_SAMPLES`, zero for `s` above), by
/// the product form `C(n,i) u^i (1 - u)^(n-i)` with exact binomials and
/// exact `u`, `1 - u` (relative error at most `(n + 1) eps` per entry);
/// `None` above [`DEVIATION_TABLE_DEGREE`].
fn deviation_table(n: usize) -> Option<&'static [f64]> {
    static TABLES: [OnceLock<Vec<f64>>; DEVIATION_TABLE_DEGREE + 1] =
        [const { OnceLock::new() }; DEVIATION_TABLE_DEGREE + 1];
    let slot = TABLES.get(n)?;
    Some(slot.get_or_init(|| {
        let mut table = vec![0.0; TABLE_ROW * (n + 1)];
        for i in 0..=n {
            for s in 0..SAMPLES {
                let u = s as f64 / DEVIATION_SAMPLES as f64;
                let v = 1.0 - u;
                let mut b = crate::basis::binomial(n, i);
                for _ in 0..i {
                    b *= u;
                }
                for _ in i..n {
                    b *= v;
                }
                table[i * TABLE_ROW + s] = b;
            }
        }
        table
    }))
}

/// The values of samples `s0 .. s0 + LANES` of the (half) difference curve
/// `half` of dimension `D`, `acc[c][k]` the coordinate `c` of sample
/// `s0 + k`: each sum from `0.0` in the order `i = 0..n` (the one body of
/// [`deviation_fixed`] and [`exact_squares`]).
// The lanes are read across the coordinate rows (`acc[c][k]`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn lane_values<const D: usize>(table: &[f64], half: &[f64], s0: usize) -> [[f64; LANES]; D] {
    let mut acc = [[0.0f64; LANES]; D];
    for (row, p) in table.chunks_exact(TABLE_ROW).zip(half.chunks_exact(D)) {
        let b: &[f64; LANES] = row[s0..s0 + LANES].try_into().expect("LANES entries");
        for c in 0..D {
            let x = p[c];
            for k in 0..LANES {
                acc[c][k] += b[k] * x;
            }
        }
    }
    acc
}

/// The sample values of one (half) difference curve of dimension `D`,
/// `sum_i B_i(u_s) half_i` for every sample `s` (each sum from `0.0` in
/// the order `i = 0..n`), noted in `worst`. [`LANES`] samples at a time,
/// their sums kept in registers over all coefficients (no array of all
/// sample values).
// The lanes are read across the coordinate rows (`acc[c][k]`).
#[allow(clippy::needless_range_loop)]
fn deviation_fixed<const D: usize>(table: &[f64], half: &[f64], worst: &mut Worst) {
    let values = |s0: usize| lane_values::<D>(table, half, s0);
    // The largest square (a plain compare) and the sum of all squares. A
    // NaN or infinite square makes the sum non-finite; a subnormal or
    // underflowed square (its value below sqrt(MIN_POSITIVE), so it
    // matters only when every square is that small) shows as a largest
    // square below 2 MIN_POSITIVE. Either sends the piece through
    // `Worst::note` sample by sample, whose norm does not square (before,
    // squares that underflowed to zero were passed over, so a piece of
    // such tiny differences reported 0); otherwise the largest square is
    // exactly what `note` would keep.
    let mut largest = 0.0f64;
    let mut total = 0.0f64;
    for s0 in (0..TABLE_ROW).step_by(LANES) {
        let acc = values(s0);
        for k in 0..LANES {
            let mut square = 0.0;
            for c in 0..D {
                square += acc[c][k] * acc[c][k];
            }
            if square > largest {
                largest = square;
            }
            total += square;
        }
    }
    let other = !total.is_finite() || largest < 2.0 * f64::MIN_POSITIVE;
    if other {
        for s0 in (0..TABLE_ROW).step_by(LANES) {
            let acc = values(s0);
            for k in 0..LANES {
                let value: [f64; D] = std::array::from_fn(|c| acc[c][k]);
                worst.note(&value);
            }
        }
    } else {
        worst.square = worst.square.max(largest);
    }
}

/// Degrees up to which [`deviation_screened`] runs (above, the
/// subdivisions of its degree-`2n` polynomial cost more than
/// [`deviation_fixed`]'s sums).
const SCREENED_DEGREE: usize = 5;

/// Halvings from `[0, 1]` to one sample spacing: `2^SAMPLE_LEVELS =
/// DEVIATION_SAMPLES`, so every sample is an end of a dyadic interval.
const SAMPLE_LEVELS: u32 = DEVIATION_SAMPLES.trailing_zeros();
const _: () = assert!(1 << SAMPLE_LEVELS == DEVIATION_SAMPLES);

/// The level at which [`deviation_screened`] stops halving and evaluates
/// a span's samples exactly (as [`deviation_fixed`] does): spans of
/// [`EXACT_WIDTH`] sample spacings.
const EXACT_LEVEL: u32 = 5;

/// Sample spacings of one span at [`EXACT_LEVEL`] (a multiple of
/// [`LANES`]).
const EXACT_WIDTH: usize = 1 << (SAMPLE_LEVELS - EXACT_LEVEL);
const _: () = assert!(EXACT_WIDTH % LANES == 0 && EXACT_LEVEL <= SAMPLE_LEVELS);

/// The squares of samples `first .. first + EXACT_WIDTH` as
/// [`deviation_fixed`] computes them ([`LANES`] at a time: each sample's
/// sums from `0.0` in the order `i = 0..n`, then the square summed over
/// the coordinates in order). `first` is a multiple of [`LANES`].
// The lanes are read across the coordinate rows (`acc[c][k]`).
#[allow(clippy::needless_range_loop)]
#[inline]
fn exact_squares<const D: usize>(table: &[f64], half: &[f64], first: usize) -> [f64; EXACT_WIDTH] {
    let mut squares = [0.0f64; EXACT_WIDTH];
    for (g, out) in squares.chunks_exact_mut(LANES).enumerate() {
        let acc = lane_values::<D>(table, half, first + g * LANES);
        for k in 0..LANES {
            let mut square = 0.0;
            for c in 0..D {
                square += acc[c][k] * acc[c][k];
            }
            out[k] = square;
        }
    }
    squares
}

/// The square of sample `s` as [`deviation_fixed`] computes it (its lane).
#[allow(clippy::needless_range_loop)]
#[inline]
fn exact_square<const D: usize>(table: &[f64], half: &[f64], s: usize) -> f64 {
    let mut acc = [0.0f64; D];
    for (row, p) in table.chunks_exact(TABLE_ROW).zip(half.chunks_exact(D)) {
        let b = row[s];
        for c in 0..D {
            acc[c] += b * p[c];
        }
    }
    let mut square = 0.0;
    for c in 0..D {
        square += acc[c] * acc[c];
    }
    square
}

/// Halvings [`deviation_screened`] may run before it declines (a curve
/// whose distance is nearly the same at many samples).
const SCREEN_BUDGET: usize = 96;

/// `C(n,i) C(n,j) / C(2n,i+j)`, entry `i (n + 1) + j`: the product of two
/// degree-`n` Bernstein polynomials in the degree-`2n` basis, `B_i^n B_j^n =
/// w_ij B_(i+j)^(2n)`; exact binomials.
fn product_weights(n: usize) -> Option<&'static [f64]> {
    static WEIGHTS: [OnceLock<Vec<f64>>; SCREENED_DEGREE + 1] =
        [const { OnceLock::new() }; SCREENED_DEGREE + 1];
    let slot = WEIGHTS.get(n)?;
    Some(slot.get_or_init(|| {
        use crate::basis::binomial;
        let mut w = vec![0.0; (n + 1) * (n + 1)];
        for i in 0..=n {
            for j in 0..=n {
                w[i * (n + 1) + j] = binomial(n, i) * binomial(n, j) / binomial(2 * n, i + j);
            }
        }
        w
    }))
}

/// One dyadic interval of the squared-norm polynomial: its Bernstein
/// coefficients there, its level (`0` is `[0, 1]`) and first sample.
#[derive(Clone, Copy)]
struct Span<const K: usize> {
    coefficients: [f64; K],
    /// The largest coefficient (an upper bound of the polynomial here).
    upper: f64,
    level: u32,
    first: usize,
}

/// `maxsd`: the larger of two finite values.
#[inline(always)]
fn larger(a: f64, b: f64) -> f64 {
    if a > b { a } else { b }
}

impl<const K: usize> Span<K> {
    fn new(coefficients: [f64; K], level: u32, first: usize) -> Self {
        let mut upper = coefficients[0];
        for &v in &coefficients[1..] {
            upper = larger(v, upper);
        }
        Self {
            coefficients,
            upper,
            level,
            first,
        }
    }
}

/// [`deviation_fixed`]'s result, bit for bit, from far fewer operations:
/// the squared norm `|D(u)|^2` of the (half) difference curve is one
/// scalar polynomial of degree `2n`, with Bernstein coefficients `E_k =
/// sum_(i+j=k) w_ij D_i . D_j` ([`product_weights`]). Branch and bound on
/// it locates the samples that can hold the largest square: an interval's
/// coefficients bound the polynomial there from above (convex hull), its
/// end coefficients are its values at the ends, and halving an interval
/// (de Casteljau at `1/2`) down to [`EXACT_WIDTH`] sample spacings
/// ([`EXACT_LEVEL`]) puts a sample at every end; an interval whose largest
/// coefficient is below the best known value by more than the rounding
/// bound `T` is dropped. The samples of every interval that reaches
/// [`EXACT_LEVEL`] are evaluated as [`deviation_fixed`] evaluates them (the
/// same sums in the same order; its last sample only if its value, the last
/// coefficient, is not below `best - T`), and the largest of those squares
/// is [`deviation_fixed`]'s largest square: the sample of that square is
/// among them, and every square evaluated is one of [`deviation_fixed`]'s.
/// The best known value is the largest of the halving midpoints' values and
/// of the squares evaluated (both within the rounding below of the exact
/// `|D(u_s)|^2`).
///
/// Why the same: with `K = max_i |D_i|^2` (so `|E_k| <= K`, the weights of
/// one `k` summing to 1), the computed coefficients are within `(n + D +
/// 4) eps K` of the exact ones, each halving adds `2n eps K` at most, so
/// every computed bound and value is within `(17n + D + 4) eps K` of the
/// exact one; [`deviation_fixed`]'s squares are within `(4n + D + 5) eps
/// K` of `|D(u_s)|^2`. The sample of the largest square therefore survives
/// every comparison with the margin `(42n + 4D + 18) eps K` (a best value
/// from an evaluated square is closer: its error is the smaller); `T` is
/// four times that (plus `1e-300` for subnormal products). Declines
/// (returns `false`, nothing noted) at degree 0 and above
/// [`SCREENED_DEGREE`], after [`SCREEN_BUDGET`] halvings, and when
/// `K` is not finite, above `f64::MAX / 1024` (so [`deviation_fixed`]'s
/// sum of squares is finite) or below `2^-900` (subnormal rounding), or
/// the best value is within `T + 4 MIN_POSITIVE` of zero: whenever
/// [`deviation_fixed`] might take its non-squaring path.
// The lanes are read across the coordinate rows (`acc[c]`).
#[allow(clippy::needless_range_loop)]
fn deviation_screened<const D: usize>(
    n: usize,
    table: &[f64],
    half: &[f64],
    worst: &mut Worst,
) -> bool {
    // One instance per degree `2n = K - 1` (fixed-size loops).
    match n {
        1 => screen::<D, 3>(table, half, worst),
        2 => screen::<D, 5>(table, half, worst),
        3 => screen::<D, 7>(table, half, worst),
        4 => screen::<D, 9>(table, half, worst),
        5 => screen::<D, 11>(table, half, worst),
        _ => false,
    }
}

/// `2^-900`: below it, [`deviation_screened`]'s squares may round as
/// subnormals (exact: a power of two, as `2f64.powi(-900)`).
const SUBNORMAL_ROUNDING: f64 = f64::from_bits((1023 - 900) << 52);

/// [`deviation_screened`] for the degree `2n = K - 1`.
#[allow(clippy::needless_range_loop)]
fn screen<const D: usize, const K: usize>(table: &[f64], half: &[f64], worst: &mut Worst) -> bool {
    let n = (K - 1) / 2;
    let Some(weights) = product_weights(n) else {
        return false;
    };
    let points = n + 1;
    let degree = 2 * n;
    let largest_coefficient = half
        .chunks_exact(D)
        .map(|p| p.iter().map(|x| x * x).sum::<f64>())
        .fold(0.0f64, |m, v| if v > m { v } else { m });
    if !(largest_coefficient.is_finite()
        && (SUBNORMAL_ROUNDING..=f64::MAX / 1024.0).contains(&largest_coefficient))
    {
        return false;
    }
    let mut square_coefficients = [0.0f64; K];
    for (i, pi) in half.chunks_exact(D).enumerate() {
        for (j, pj) in half.chunks_exact(D).enumerate() {
            let mut dot = 0.0;
            for c in 0..D {
                dot += pi[c] * pj[c];
            }
            square_coefficients[i + j] += weights[i * points + j] * dot;
        }
    }
    let whole = Span::new(square_coefficients, 0, 0);
    let eps = f64::EPSILON;
    let bound = 4.0 * (42 * n + 4 * D + 18) as f64 * eps * largest_coefficient + 1e-300;
    let mut best = larger(whole.coefficients[0], whole.coefficients[degree]);
    // The largest square of the samples evaluated exactly so far (as
    // `deviation_fixed` evaluates them), over the spans that reach
    // [`EXACT_LEVEL`].
    let mut largest = 0.0f64;
    // Depth first, the half with the larger bound first: the span being
    // searched is `span`, the halves set aside wait on the stack (at most
    // one per level). A half is dropped when set aside if its bound is
    // already below `best - bound` (`best` only grows, so it would be
    // dropped when taken up again).
    let mut stack = [whole; EXACT_LEVEL as usize + 1];
    let mut depth = 0;
    let mut span = whole;
    let mut halvings = 0;
    loop {
        let dropped = span.upper < best - bound;
        if !dropped {
            if span.level == EXACT_LEVEL {
                // Its samples `first .. first + EXACT_WIDTH` exactly,
                // [`LANES`] at a time (`first` is a multiple of
                // `EXACT_WIDTH`, itself a multiple of `LANES`), and its
                // last sample `first + EXACT_WIDTH` alone, unless its
                // polynomial value (the last coefficient) already rules it
                // out.
                let squares = exact_squares::<D>(table, half, span.first);
                let mut here = squares[0];
                for &square in &squares[1..] {
                    here = larger(square, here);
                }
                if span.coefficients[degree] >= best - bound {
                    here = larger(
                        exact_square::<D>(table, half, span.first + EXACT_WIDTH),
                        here,
                    );
                }
                largest = larger(here, largest);
                best = larger(here, best);
            } else {
                halvings += 1;
                if halvings > SCREEN_BUDGET {
                    return false;
                }
                // de Casteljau at 1/2: the left half's coefficients are the
                // triangle's first entries, the right half's its last.
                let mut c = span.coefficients;
                let mut l = span.coefficients;
                for r in 1..K {
                    for k in 0..K - r {
                        c[k] = 0.5 * (c[k] + c[k + 1]);
                    }
                    l[r] = c[0];
                }
                best = larger(c[0], best);
                let level = span.level + 1;
                let left = Span::new(l, level, span.first);
                let right = Span::new(c, level, span.first + (1 << (SAMPLE_LEVELS - level)));
                // The half with the larger bound is searched first.
                let (first, second) = if left.upper > right.upper {
                    (left, right)
                } else {
                    (right, left)
                };
                let dropped = second.upper < best - bound;
                if !dropped {
                    stack[depth] = second;
                    depth += 1;
                }
                span = first;
                continue;
            }
        }
        if depth == 0 {
            break;
        }
        depth -= 1;
        span = stack[depth];
    }
    if !(best.is_finite() && best - bound >= 4.0 * f64::MIN_POSITIVE) {
        return false;
    }
    worst.square = worst.square.max(largest);
    true
}

/// The largest Euclidean norm among the sampled values: the largest
/// square while squares are normal (one square root at the end), the
/// overflow-safe [`crate::bezier::norm`] otherwise.
#[derive(Default)]
struct Worst {
    square: f64,
    other: f64,
}

impl Worst {
    #[inline]
    fn note(&mut self, value: &[f64]) {
        let square = value.iter().map(|x| x * x).sum::<f64>();
        if square.is_normal() {
            self.square = self.square.max(square);
        } else {
            self.other = self.other.max(crate::bezier::norm(value));
        }
    }

    fn value(&self) -> f64 {
        self.square.sqrt().max(self.other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve(state: &mut u64, dim: usize, degree: usize) -> BezierCurve {
        let points = (0..(degree + 1) * dim)
            .map(|_| {
                *state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                (*state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
            })
            .collect();
        BezierCurve::new(dim, degree, points).unwrap()
    }

    /// The restriction matrix applied to `R` against `R`'s blossomed
    /// segments (`BezierCurve::segment`) on every piece: end pieces (two
    /// pieces) and middle pieces (chains of three and four).
    #[test]
    fn restriction_matrix_gives_the_blossomed_segments() {
        let mut state = 11;
        for degree in [1, 2, 3, 6, 15, 31] {
            let r = curve(&mut state, 1, degree);
            for breakpoints in [
                vec![0.0, 0.4, 1.0],
                vec![0.0, 0.1, 0.75, 1.0],
                vec![0.0, 0.3, 0.5, 0.6, 1.0],
            ] {
                let s = restriction_matrix(degree, &breakpoints);
                let mapped = &s * DMatrix::from_column_slice(degree + 1, 1, r.points());
                for j in 0..breakpoints.len() - 1 {
                    let segment = r.segment(breakpoints[j], breakpoints[j + 1]).unwrap();
                    for i in 0..=degree {
                        let gap = (mapped[(j * (degree + 1) + i, 0)] - segment.points()[i]).abs();
                        assert!(
                            gap <= 1e-12,
                            "degree {degree} {breakpoints:?} piece {j} point {i}: gap {gap:e}"
                        );
                    }
                }
            }
        }
    }

    /// The screen's subnormal threshold is `2^-900` as `powi` computes it.
    #[test]
    fn subnormal_rounding_is_two_to_the_minus_900() {
        assert_eq!(SUBNORMAL_ROUNDING.to_bits(), 2f64.powi(-900).to_bits());
    }

    /// `max_deviation` (difference curves, tabulated basis, the unrolled
    /// dimensions 2 and 3, the general path, Horner above the table)
    /// against the two-evaluation definition `max_s |R(t_j + h_j u_s) -
    /// C_j(u_s)|`, within `16 (n + 1) eps` of the largest coordinate.
    #[test]
    fn max_deviation_is_the_two_evaluation_maximum() {
        let mut state = 5;
        for dim in [1, 2, 3, 4] {
            for degree in [
                1,
                3,
                8,
                20,
                DEVIATION_TABLE_DEGREE,
                DEVIATION_TABLE_DEGREE + 3,
            ] {
                let r = curve(&mut state, dim, degree);
                let breakpoints = [0.0, 0.35, 1.0];
                let restrictions: Vec<BezierCurve> = (0..2)
                    .map(|j| r.segment(breakpoints[j], breakpoints[j + 1]).unwrap())
                    .collect();
                // Originals: the pieces moved, one of lower degree.
                let p = curve(&mut state, dim, degree);
                let q = curve(&mut state, dim, degree.saturating_sub(1).max(1));
                let ours = max_deviation(&restrictions, &[&p, &q]).unwrap();
                let mut reference = 0.0f64;
                let (mut a, mut b) = (vec![0.0; dim], vec![0.0; dim]);
                for (j, c) in [&p, &q].into_iter().enumerate() {
                    let (t0, t1) = (breakpoints[j], breakpoints[j + 1]);
                    for s in 0..=DEVIATION_SAMPLES {
                        let u = s as f64 / DEVIATION_SAMPLES as f64;
                        r.eval_into(t0 + (t1 - t0) * u, &mut a);
                        c.eval_into(u, &mut b);
                        let d = a
                            .iter()
                            .zip(&b)
                            .map(|(x, y)| (x - y) * (x - y))
                            .sum::<f64>();
                        reference = reference.max(d.sqrt());
                    }
                }
                let scale = [&r, &p, &q]
                    .iter()
                    .map(|c| c.points().iter().fold(0.0f64, |m, v| m.max(v.abs())))
                    .fold(0.0f64, f64::max);
                let bound = 16.0 * (degree + 1) as f64 * f64::EPSILON * scale;
                assert!(
                    (ours - reference).abs() <= bound,
                    "dim {dim} degree {degree}: {ours:e} vs {reference:e} (bound {bound:e})"
                );
            }
        }
    }

    /// The screened maximum (squared-norm polynomial, then the samples near
    /// its top evaluated as `deviation_fixed` evaluates them) is
    /// `deviation_fixed`'s largest square bit for bit: random difference
    /// curves, near-constant ones (every sample ties up to rounding), tiny
    /// ones and ones at the edges of the accepted range, every screened
    /// degree, dimensions 2 and 3.
    /// The largest squares of `deviation_screened` and `deviation_fixed`
    /// on the difference curve `half` (degree `n`, dimension 2 or 3), or
    /// `None` when the screened search declines.
    fn screened_and_fixed(n: usize, dim: usize, half: &[f64]) -> Option<(f64, f64)> {
        fn both<const D: usize>(n: usize, half: &[f64]) -> Option<(f64, f64)> {
            let table = deviation_table(n).unwrap();
            let mut screened = Worst::default();
            if !deviation_screened::<D>(n, table, half, &mut screened) {
                return None;
            }
            let mut fixed = Worst::default();
            deviation_fixed::<D>(table, half, &mut fixed);
            assert_eq!(fixed.other, 0.0);
            Some((screened.square, fixed.square))
        }
        match dim {
            2 => both::<2>(n, half),
            3 => both::<3>(n, half),
            _ => unreachable!("dimension {dim}"),
        }
    }

    #[test]
    fn screened_deviation_is_the_fixed_one_bit_for_bit() {
        let mut state = 41;
        let mut screened_count = 0;
        for n in 0..=SCREENED_DEGREE {
            for dim in [2, 3] {
                for kind in 0..5 {
                    let c = curve(&mut state, dim, n);
                    let half: Vec<f64> = match kind {
                        0 => c.points().to_vec(),
                        // Every coefficient the same point: |D| constant.
                        1 => c.points()[..dim].repeat(n + 1),
                        // The same plus a perturbation at the rounding level.
                        2 => c.points()[..dim]
                            .repeat(n + 1)
                            .iter()
                            .zip(c.points())
                            .map(|(a, b)| a + 1e-15 * b)
                            .collect(),
                        3 => c.points().iter().map(|v| v * 1e-250).collect(),
                        _ => c.points().iter().map(|v| v * 1e150).collect(),
                    };
                    let result = screened_and_fixed(n, dim, &half);
                    if let Some((screened, fixed)) = result {
                        screened_count += 1;
                        assert_eq!(
                            screened.to_bits(),
                            fixed.to_bits(),
                            "degree {n} dim {dim} kind {kind}: {screened:e} vs {fixed:e}"
                        );
                    }
                }
            }
        }
        // Everything but the tiny kind (below 2^-900) is screened.
        assert!(
            screened_count >= 2 * 2 * SCREENED_DEGREE,
            "{screened_count}"
        );
    }

    /// The exact evaluation at [`EXACT_LEVEL`] (every sample of a span that
    /// reaches it, its last one unless ruled out by its value) gives
    /// `deviation_fixed`'s largest square bit for bit on many random
    /// difference curves: ones whose largest distance lies anywhere,
    /// including at span ends and near ties between two humps.
    #[test]
    fn screened_exact_spans_are_the_fixed_one_bit_for_bit() {
        let mut state = 7;
        let mut screened_count = 0;
        for case in 0..6000 {
            let n = 1 + case % SCREENED_DEGREE;
            let dim = 2 + (case / SCREENED_DEGREE) % 2;
            let c = curve(&mut state, dim, n);
            let half: Vec<f64> = if case % 3 == 0 {
                // Symmetric control polygons: two equal humps, the
                // largest distance decided by rounding.
                let p = c.points();
                (0..=n)
                    .flat_map(|i| {
                        let j = i.min(n - i);
                        p[j * dim..(j + 1) * dim].to_vec()
                    })
                    .collect()
            } else {
                c.points().to_vec()
            };
            let result = screened_and_fixed(n, dim, &half);
            if let Some((screened, fixed)) = result {
                screened_count += 1;
                assert_eq!(
                    screened.to_bits(),
                    fixed.to_bits(),
                    "case {case} degree {n} dim {dim}: {screened:e} vs {fixed:e}"
                );
            }
        }
        assert!(screened_count >= 5000, "{screened_count}");
    }

    /// Differences so small that their squares are subnormal or zero, and
    /// so large that they overflow: the sampled maximum is still the
    /// largest distance (computed without squaring), in the unrolled
    /// dimensions 2 and 3 and the general path, against the
    /// two-evaluation definition with an overflow-safe norm.
    #[test]
    fn max_deviation_survives_tiny_and_huge_differences() {
        let mut state = 23;
        for scale in [1e-170, 1e-158, 1e-152, 1e150, 1e160] {
            for dim in [2, 3, 4] {
                let degree = 3;
                let unit = curve(&mut state, dim, degree);
                let r = BezierCurve::new(
                    dim,
                    degree,
                    unit.points().iter().map(|v| v * scale).collect(),
                )
                .unwrap();
                let breakpoints = [0.0, 0.5, 1.0];
                let restrictions: Vec<BezierCurve> = (0..2)
                    .map(|j| r.segment(breakpoints[j], breakpoints[j + 1]).unwrap())
                    .collect();
                let zero = BezierCurve::new(dim, degree, vec![0.0; (degree + 1) * dim]).unwrap();
                let ours = max_deviation(&restrictions, &[&zero, &zero]).unwrap();
                let mut reference = 0.0f64;
                let mut a = vec![0.0; dim];
                for back in &restrictions {
                    for s in 0..=DEVIATION_SAMPLES {
                        back.eval_into(s as f64 / DEVIATION_SAMPLES as f64, &mut a);
                        reference = reference.max(crate::bezier::norm(&a));
                    }
                }
                assert!(
                    reference > 0.0 && (ours - reference).abs() <= 1e-12 * reference,
                    "scale {scale:e} dim {dim}: {ours:e} vs {reference:e}"
                );
            }
        }
    }
}
