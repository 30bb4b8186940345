//! The rows of stage 1: the continuity conditions (3), fix ends and keep
//! points as linear conditions on the perturbations, and the bookkeeping of
//! dependent rows (consistent, contradictory or undecided).

use std::cell::OnceCell;

use nalgebra::{DMatrix, DVector};

use crate::basis::{bezier_basis_derivatives, binomial};
use crate::error::{BezjoinError, Result};

use super::columns::{Columns, OwnedColumns};
use super::stage_one::{CONTRADICTION_MARGIN, PieceInput};

pub(super) struct Row {
    /// Over all unknowns, unit 2-norm.
    pub(super) coefficients: DVector<f64>,
    /// Right-hand side for the perturbation (one value per coordinate).
    pub(super) rhs: DVector<f64>,
    pub(super) label: String,
}

pub(super) fn normalised(mut row: Row) -> Row {
    let norm = row.coefficients.norm();
    if norm > 0.0 {
        row.coefficients /= norm;
        row.rhs /= norm;
    }
    row
}

/// The rows of a stage-1 problem: the continuity conditions (3) and the
/// fix-ends and keep-point constraints, all on the perturbations `e` of all
/// control points (`(count (m + 1)) x dim`, piece after piece).
pub(super) struct Problem<'p, 'a> {
    pub(super) pieces: &'p [PieceInput<'a>],
    pub(super) points_per_piece: usize,
    pub(super) unknowns: usize,
    pub(super) dim: usize,
    /// The input control points, stacked (`unknowns x dim`, [`Problem::x0`]).
    x0: OwnedColumns,
    /// Coordinate scale of the input.
    pub(super) scale: f64,
    /// Size of the input: the largest range of one coordinate over all
    /// control points (at least the smallest positive double). A
    /// translation of the data leaves it unchanged, so the tolerance of the
    /// dependent conditions (`CONSISTENCY_TOLERANCE` times it) does too;
    /// the coordinate scale would grow with the distance from the origin and
    /// let a contradiction pass as rounding.
    pub(super) extent: f64,
    /// The piece lengths `h_j` (the continuity rows' weights).
    lengths: &'p [f64],
    /// The continuity rows as [`Row`]s, built on first use (the KKT
    /// reference and fallback; the orthogonal path needs none and checks
    /// (3) by [`Problem::continuity_residual`]).
    continuity: OnceCell<Vec<Row>>,
    fix_ends: bool,
    /// The number of constraint rows ([`Problem::constraints`]).
    constraint_count: usize,
    /// The constraint rows with their labels, built on first use (the
    /// closed form of fixed ends on two pieces needs none).
    constraints: OnceCell<Vec<Row>>,
}

impl<'p, 'a> Problem<'p, 'a> {
    pub(super) fn new(pieces: &'p [PieceInput<'a>], lengths: &'p [f64], fix_ends: bool) -> Self {
        let count = pieces.len();
        let m = pieces[0].curve.degree();
        let dim = pieces[0].curve.dim();
        let points_per_piece = m + 1;
        let unknowns = count * points_per_piece;
        let constraint_count = 2 * usize::from(fix_ends)
            + pieces
                .iter()
                .flat_map(|p| p.points.iter().map(|(_, kp)| kp.max_order + 1))
                .sum::<usize>();
        // Built in place (no copy of the stack-held x0 when returned), x0
        // and the scale filled in below.
        let mut problem = Self {
            pieces,
            points_per_piece,
            unknowns,
            dim,
            x0: OwnedColumns::zeros(unknowns, dim),
            scale: 0.0,
            extent: 0.0,
            lengths,
            continuity: OnceCell::new(),
            fix_ends,
            constraint_count,
            constraints: OnceCell::new(),
        };
        let rows = problem.x0.as_mut_slice();
        for (j, p) in pieces.iter().enumerate() {
            // Column-major x0 from the row-major control points.
            for (i, point) in p.curve.points().chunks_exact(dim).enumerate() {
                for (c, &v) in point.iter().enumerate() {
                    rows[c * unknowns + j * points_per_piece + i] = v;
                }
            }
        }
        // As nalgebra's `amax` (which differs only for an all-NaN x0, and
        // then gives NaN, which `max` passes over as well).
        problem.scale = super::lsq::amax(problem.x0.columns().as_slice()).max(f64::MIN_POSITIVE);
        problem.extent = coordinate_extent([(problem.x0.columns().as_slice(), unknowns)], dim);
        problem
    }

    /// The input control points of every piece, stacked (`unknowns x
    /// dim`, piece after piece).
    pub(super) fn x0(&self) -> Columns<'_> {
        self.x0.columns()
    }

    /// The number of constraint rows, without building them.
    pub(super) fn constraint_count(&self) -> usize {
        self.constraint_count
    }

    /// The constraint rows (fix ends, then the keep points piece after
    /// piece), in a fixed order; right-hand sides are exactly zero (the
    /// constrained quantities keep their values). "Keep piece j unchanged"
    /// is not among them: see `solve_stage_one`.
    pub(super) fn constraints(&self) -> &[Row] {
        self.constraints.get_or_init(|| {
            let pieces = self.pieces;
            let count = pieces.len();
            let (unknowns, dim) = (self.unknowns, self.dim);
            let points_per_piece = self.points_per_piece;
            let m = points_per_piece - 1;
            let mut constraints = Vec::with_capacity(self.constraint_count);
            let unit = |index: usize| {
                let mut a = DVector::zeros(unknowns);
                a[index] = 1.0;
                a
            };
            if self.fix_ends {
                constraints.push(Row {
                    coefficients: unit(0),
                    rhs: DVector::zeros(dim),
                    label: format!("fix ends (first point of {})", pieces[0].name),
                });
                constraints.push(Row {
                    coefficients: unit(unknowns - 1),
                    rhs: DVector::zeros(dim),
                    label: format!("fix ends (last point of {})", pieces[count - 1].name),
                });
            }
            for (j, p) in pieces.iter().enumerate() {
                for &(k, kp) in &p.points {
                    let d = bezier_basis_derivatives(m, kp.param, kp.max_order);
                    for s in 0..=kp.max_order {
                        let mut a = DVector::zeros(unknowns);
                        for i in 0..=m {
                            a[j * points_per_piece + i] = d[(s, i)];
                        }
                        constraints.push(normalised(Row {
                            coefficients: a,
                            rhs: DVector::zeros(dim),
                            label: format!(
                                "{}[{k}] (derivative {s} of {} at {})",
                                p.points_name, p.name, kp.param
                            ),
                        }));
                    }
                }
            }
            debug_assert_eq!(constraints.len(), self.constraint_count);
            constraints
        })
    }

    /// The continuity rows (3), unit length, join after join, order `r =
    /// 0..m` ([`continuity_row`]); independent by construction (row `r` of
    /// join `j` brings in control point `r` of piece `j + 1` for the first
    /// time).
    pub(super) fn continuity(&self) -> &[Row] {
        self.continuity.get_or_init(|| {
            let points = self.points_per_piece;
            let m = points - 1;
            let count = self.pieces.len();
            let mut rows = Vec::with_capacity((count - 1) * points);
            let (mut left, mut right) = (vec![0.0; points], vec![0.0; points]);
            for j in 0..count - 1 {
                for r in 0..=m {
                    continuity_row(
                        m,
                        r,
                        self.lengths[j],
                        self.lengths[j + 1],
                        &mut left,
                        &mut right,
                    );
                    let mut a = DVector::zeros(self.unknowns);
                    a.rows_mut(j * points, points).copy_from_slice(&left);
                    a.rows_mut((j + 1) * points, points).copy_from_slice(&right);
                    rows.push(Row {
                        coefficients: a,
                        rhs: DVector::zeros(self.dim),
                        label: format!(
                            "continuity of order {r} between {} and {}",
                            self.pieces[j].name,
                            self.pieces[j + 1].name
                        ),
                    });
                }
            }
            rows
        })
    }

    /// `max_(j, r, c) |a_(j,r) . x_c|` (NaN terms passed over): the residual of the continuity
    /// rows (3) ([`continuity_row`], unit length) at the stacked control
    /// points `x` of all pieces, every coordinate. Only the `r + 1`
    /// nonzero entries of each half of a row are visited: `O(m^2 dim)` per
    /// join, no row is stored.
    pub(super) fn continuity_residual(&self, x: &DMatrix<f64>) -> f64 {
        let points = self.points_per_piece;
        // The two halves of a row: on the stack up to degree 15, then 63
        // (zeroing the larger buffer costs more than the rows at low
        // degree).
        // Constant-size rows and sums up to degree 7 (the same values in
        // the same order).
        match points {
            2 => return self.continuity_residual_sized::<2>(x),
            3 => return self.continuity_residual_sized::<3>(x),
            4 => return self.continuity_residual_sized::<4>(x),
            5 => return self.continuity_residual_sized::<5>(x),
            6 => return self.continuity_residual_sized::<6>(x),
            7 => return self.continuity_residual_sized::<7>(x),
            8 => return self.continuity_residual_sized::<8>(x),
            _ => {}
        }
        if points <= 16 {
            let [mut left, mut right] = [[0.0f64; 16]; 2];
            self.continuity_residual_in(x, &mut left[..points], &mut right[..points])
        } else if points <= 64 {
            let [mut left, mut right] = [[0.0f64; 64]; 2];
            self.continuity_residual_in(x, &mut left[..points], &mut right[..points])
        } else {
            let (mut left, mut right) = (vec![0.0; points], vec![0.0; points]);
            self.continuity_residual_in(x, &mut left, &mut right)
        }
    }

    /// [`Problem::continuity_residual`] for `P` points per piece (`P <=
    /// SMALL_ROWS`): the rows by [`continuity_row_small`], the sums over
    /// fixed-size halves in the same order.
    fn continuity_residual_sized<const P: usize>(&self, x: &DMatrix<f64>) -> f64 {
        let m = P - 1;
        let rows = x.nrows();
        let mut worst = 0.0f64;
        let mut left = [0.0f64; P];
        let mut right = [0.0f64; P];
        for j in 0..self.pieces.len() - 1 {
            for r in 0..=m {
                continuity_row_small(
                    m,
                    r,
                    self.lengths[j],
                    self.lengths[j + 1],
                    &mut left,
                    &mut right,
                );
                for column in x.as_slice().chunks_exact(rows).take(self.dim) {
                    let here: &[f64; P] = column[j * P..(j + 1) * P].try_into().expect("P points");
                    let next: &[f64; P] = column[(j + 1) * P..(j + 2) * P]
                        .try_into()
                        .expect("P points");
                    let mut sum = 0.0;
                    for i in m - r..P {
                        sum += left[i] * here[i];
                    }
                    for i in 0..=r {
                        sum += right[i] * next[i];
                    }
                    worst = super::lsq::raise(worst, sum.abs());
                }
            }
        }
        worst
    }

    /// [`Problem::continuity_residual`] with the row halves' storage.
    fn continuity_residual_in(&self, x: &DMatrix<f64>, left: &mut [f64], right: &mut [f64]) -> f64 {
        let points = self.points_per_piece;
        let m = points - 1;
        let rows = x.nrows();
        let mut worst = 0.0f64;
        for j in 0..self.pieces.len() - 1 {
            for r in 0..=m {
                continuity_row_nonzero(m, r, self.lengths[j], self.lengths[j + 1], left, right);
                for column in x.as_slice().chunks_exact(rows).take(self.dim) {
                    let here = &column[j * points..(j + 1) * points];
                    let next = &column[(j + 1) * points..(j + 2) * points];
                    let mut sum = 0.0;
                    for (a, v) in left[m - r..].iter().zip(&here[m - r..]) {
                        sum += a * v;
                    }
                    for (a, v) in right[..=r].iter().zip(&next[..=r]) {
                        sum += a * v;
                    }
                    // f64::max (`raise`) passes over a NaN, as the row-wise amax did
                    // (non-finite pieces are refused later, as such).
                    worst = super::lsq::raise(worst, sum.abs());
                }
            }
        }
        worst
    }

    /// Conditions given beyond continuity (a kept piece counts `m + 1`).
    pub(super) fn given(&self) -> usize {
        self.pieces.iter().filter(|p| p.keep).count() * self.points_per_piece
            + self.constraint_count
    }

    /// The `Inconsistent` error for the dependent constraint `row`, missed
    /// by `residual`; `before` names the conditions it depends on.
    pub(super) fn contradiction(
        &self,
        row: &Row,
        residual: f64,
        scale: f64,
        before: &[String],
        independent: usize,
    ) -> BezjoinError {
        BezjoinError::Inconsistent {
            reason: format!(
                "{} contradicts the continuity conditions and the constraints before it{} \
                 (it depends linearly on them but would need a change of {residual:e}, \
                 coordinate scale {scale:e}); {}",
                row.label,
                if before.is_empty() {
                    String::new()
                } else {
                    format!(" ({})", summarise(before))
                },
                self.counts(independent)
            ),
        }
    }

    pub(super) fn counts(&self, independent: usize) -> String {
        format!(
            "beyond continuity at most {} independent conditions fit per coordinate, {} were \
             given, {independent} independent",
            self.points_per_piece,
            self.given()
        )
    }
}

/// The continuity row of order `r` between a piece of length `left` and
/// the next of length `right` (eq. (3) scaled by the longer length to the
/// power `r`), on the two pieces' control points, unit 2-norm, into
/// `on_left` and `on_right` (`m + 1` each). In closed form: with `B^(r)`
/// the `r`-th derivatives of the degree-`m` Bernstein basis,
/// `B_i^(r)(1) = m!/(m-r)! (-1)^(m-i) C(r, m-i)` and `B_i^(r)(0) = m!/(m-r)!
/// (-1)^(r-i) C(r, i)`, so the row is `(wl B^(r)(1), -wr B^(r)(0))` with
/// `wl = (right / longer)^r`, `wr = (left / longer)^r`; the common factor
/// `m!/(m-r)!` cancels in the normalisation and the norm is `sqrt((wl^2 +
/// wr^2) C(2r, r))` (`sum_k C(r,k)^2 = C(2r, r)`).
pub(super) fn continuity_row(
    m: usize,
    r: usize,
    left: f64,
    right: f64,
    on_left: &mut [f64],
    on_right: &mut [f64],
) {
    on_left.fill(0.0);
    on_right.fill(0.0);
    continuity_row_nonzero(m, r, left, right, on_left, on_right);
}

/// The two sides' weights of continuity row `r` with the interval lengths
/// `left`, `right` and `central = C(2r, r)`: `(right / longer)^r` and
/// `(left / longer)^r` divided by the row's norm factor
/// `sqrt((wl^2 + wr^2) C(2r, r))`. Shared by [`continuity_row_nonzero`]
/// and [`continuity_row_small`], so both form them with the same operations.
#[inline(always)]
fn row_weights(r: usize, left: f64, right: f64, central: f64) -> (f64, f64) {
    let longer = left.max(right);
    let wl = (right / longer).powi(r as i32);
    let wr = (left / longer).powi(r as i32);
    let norm = ((wl * wl + wr * wr) * central).sqrt();
    (wl / norm, wr / norm)
}

/// [`continuity_row`]'s nonzero entries only (`on_left[m - r..]`,
/// `on_right[..=r]`), the others left as they are: for
/// [`Problem::continuity_residual`], which reads no other.
fn continuity_row_nonzero(
    m: usize,
    r: usize,
    left: f64,
    right: f64,
    on_left: &mut [f64],
    on_right: &mut [f64],
) {
    let (wl, wr) = row_weights(r, left, right, binomial(2 * r, r));
    // C(r, k) by the exact integer recurrence C(r, k+1) = C(r, k) (r - k) /
    // (k + 1) (exact in f64 while below 2^53, as `binomial`). Up to
    // INTEGER_ORDERS in integers (every product below 2^53, so the same
    // values as the rounded f64 recurrence, without a rounding call).
    const INTEGER_ORDERS: usize = 50;
    let mut c = 1.0f64;
    let mut exact = 1u64;
    for k in 0..=r {
        if k > 0 {
            if r <= INTEGER_ORDERS {
                exact = exact * (r + 1 - k) as u64 / k as u64;
                c = exact as f64;
            } else {
                c = (c * (r + 1 - k) as f64 / k as f64).round();
            }
        }
        // Left: i = m - k, sign (-1)^k; right: i = k, sign (-1)^(r-k).
        on_left[m - k] = if k % 2 == 0 { wl * c } else { -wl * c };
        on_right[k] = if (r - k) % 2 == 0 { -wr * c } else { wr * c };
    }
}

/// Orders up to which [`continuity_row_small`] reads its binomials from
/// tables.
const SMALL_ROWS: usize = 16;

/// `C(r, k)` for `r, k < SMALL_ROWS` (exact integers).
const PASCAL: [[f64; SMALL_ROWS]; SMALL_ROWS] = crate::basis::pascal_square();

/// `C(2r, r)` for `r < SMALL_ROWS` (exact integers).
const CENTRAL: [f64; SMALL_ROWS] = {
    let mut table = [0.0; SMALL_ROWS];
    let mut r = 0;
    while r < SMALL_ROWS {
        let mut c = 1u64;
        let mut i = 0;
        while i < r {
            c = c * (2 * r - i) as u64 / (i + 1) as u64;
            i += 1;
        }
        table[r] = c as f64;
        r += 1;
    }
    table
};

/// [`continuity_row_nonzero`] for `r < SMALL_ROWS`, the binomials `C(2r,
/// r)` and `C(r, k)` read from [`CENTRAL`] and [`PASCAL`] (the same exact
/// integers as `binomial` and the integer recurrence give): the same
/// entries.
#[inline]
fn continuity_row_small(
    m: usize,
    r: usize,
    left: f64,
    right: f64,
    on_left: &mut [f64],
    on_right: &mut [f64],
) {
    let (wl, wr) = row_weights(r, left, right, CENTRAL[r]);
    for (k, &c) in PASCAL[r][..=r].iter().enumerate() {
        on_left[m - k] = if k % 2 == 0 { wl * c } else { -wl * c };
        on_right[k] = if (r - k) % 2 == 0 { -wr * c } else { wr * c };
    }
}

/// The largest range `max - min` of one coordinate over blocks of
/// column-major points (each `(entries, rows)`: `rows` points a column,
/// `dim` columns), at least the smallest positive double (NaN entries are
/// passed over, as by `f64::max`). The Bezier merge has one block (its
/// stacked `x0`), the B-spline merge one per piece.
pub(super) fn coordinate_extent<'c>(
    blocks: impl IntoIterator<Item = (&'c [f64], usize)>,
    dim: usize,
) -> f64 {
    let mut ranges = vec![(f64::INFINITY, f64::NEG_INFINITY); dim];
    for (entries, rows) in blocks {
        for (column, (low, high)) in entries.chunks_exact(rows.max(1)).zip(&mut ranges) {
            for &v in column {
                (*low, *high) = (low.min(v), high.max(v));
            }
        }
    }
    ranges
        .iter()
        .map(|(low, high)| high - low)
        .fold(f64::MIN_POSITIVE, f64::max)
}

/// How a dependent condition stands, given its residual at the solution,
/// the tolerance, and what rounding explains.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Dependent {
    Consistent,
    Contradictory,
    /// Missed by more than the tolerance but within what rounding explains.
    Undecided,
}

pub(super) fn classify(residual: f64, tolerance: f64, explained: f64) -> Dependent {
    if residual.is_nan() || residual > tolerance.max(CONTRADICTION_MARGIN * explained) {
        Dependent::Contradictory
    } else if residual > tolerance {
        Dependent::Undecided
    } else {
        Dependent::Consistent
    }
}

/// The dependent condition with the largest residual among those that are
/// undecided (missed by more than the tolerance, within what rounding
/// explains): reported as `IllConditioned` once every condition was checked
/// and none contradicted.
#[derive(Default)]
pub(super) struct WorstUndecided(Option<(f64, String)>);

impl WorstUndecided {
    pub(super) fn note(&mut self, residual: f64, label: &str) {
        if self.0.as_ref().is_none_or(|(r, _)| residual > *r) {
            self.0 = Some((residual, label.to_owned()));
        }
    }

    pub(super) fn into_result(self, scale: f64, accuracy: f64) -> Result<()> {
        match self.0 {
            None => Ok(()),
            Some((residual, label)) => Err(BezjoinError::IllConditioned {
                what: format!(
                    "merge stage 1 ({label} depends linearly on the conditions before it and \
                     is missed by {residual:e}, within what the rounding explains: consistent \
                     or contradictory cannot be told)"
                ),
                estimate: residual / scale,
                limit: accuracy,
            }),
        }
    }
}

/// The dependent conditions `rows` at the answer (`e`, the unknowns): each
/// is [`classify`]'d by its residual `|e^T a - b|_max`; the first
/// contradictory one is the `Inconsistent` error naming the `kept` rows it
/// depends on; otherwise the worst undecided one, to be reported once the
/// caller's own checks are done. One check for both stage-1 formulations.
pub(super) fn check_dependent_rows<'r>(
    problem: &Problem<'_, '_>,
    rows: impl IntoIterator<Item = &'r Row>,
    kept: &[&Row],
    e: &DMatrix<f64>,
    (tolerance, explained, result_scale): (f64, f64, f64),
) -> Result<WorstUndecided> {
    let mut undecided = WorstUndecided::default();
    for row in rows {
        let residual = (e.transpose() * &row.coefficients - &row.rhs).amax();
        match classify(residual, tolerance, explained) {
            Dependent::Contradictory => {
                let before: Vec<String> = kept.iter().map(|r| r.label.clone()).collect();
                return Err(problem.contradiction(
                    row,
                    residual,
                    result_scale,
                    &before,
                    kept.len(),
                ));
            }
            Dependent::Undecided => undecided.note(residual, &row.label),
            Dependent::Consistent => {}
        }
    }
    Ok(undecided)
}

pub(super) fn summarise<S: AsRef<str>>(labels: &[S]) -> String {
    const SHOWN: usize = 4;
    let shown: Vec<&str> = labels.iter().take(SHOWN).map(AsRef::as_ref).collect();
    if labels.len() <= SHOWN {
        shown.join("; ")
    } else {
        format!("{}; and {} more", shown.join("; "), labels.len() - SHOWN)
    }
}

/// Extend the orthonormal `basis` (rows with their right-hand sides) by
/// `rows` in order, two Gram-Schmidt passes each: a row whose remainder is
/// above `rank_tolerance` (and while the basis does not span all
/// `unknowns`) joins it; the others depend on those before them and are
/// returned second, to be checked at the solution. Returns (independent,
/// dependent).
pub(super) fn extend_orthonormal<'r>(
    basis: &mut Vec<(DVector<f64>, DVector<f64>)>,
    rows: impl IntoIterator<Item = &'r Row>,
    rank_tolerance: f64,
    unknowns: usize,
) -> (Vec<&'r Row>, Vec<&'r Row>) {
    let (mut kept, mut dependent) = (Vec::new(), Vec::new());
    for row in rows {
        if basis.len() >= unknowns {
            // The basis spans every direction: the row depends on it.
            dependent.push(row);
            continue;
        }
        let mut v = row.coefficients.clone();
        let mut rhs = row.rhs.clone();
        for _ in 0..2 {
            for (b, b_rhs) in basis.iter() {
                let dot = b.dot(&v);
                v.axpy(-dot, b, 1.0);
                rhs.axpy(-dot, b_rhs, 1.0);
            }
        }
        let remainder = v.norm();
        if remainder > rank_tolerance {
            basis.push((v / remainder, rhs / remainder));
            kept.push(row);
        } else {
            dependent.push(row);
        }
    }
    (kept, dependent)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BezierCurve;

    /// The closed-form continuity row against the definition: the `r`-th
    /// derivatives of the Bernstein basis at 1 and 0 (general basis code),
    /// weighted by the lengths and normalised.
    #[test]
    fn continuity_row_is_the_normalised_derivative_condition() {
        for m in [0, 1, 2, 3, 7, 15, 24] {
            let at_one = bezier_basis_derivatives(m, 1.0, m);
            let at_zero = bezier_basis_derivatives(m, 0.0, m);
            for (left, right) in [(0.5, 0.5), (0.3, 0.7), (0.9, 0.1), (0.01, 0.99)] {
                let longer = f64::max(left, right);
                let (mut on_left, mut on_right) = (vec![0.0; m + 1], vec![0.0; m + 1]);
                for r in 0..=m {
                    continuity_row(m, r, left, right, &mut on_left, &mut on_right);
                    let wl = (right / longer).powi(r as i32);
                    let wr = (left / longer).powi(r as i32);
                    let reference: Vec<f64> = (0..=m)
                        .map(|i| wl * at_one[(r, i)])
                        .chain((0..=m).map(|i| -wr * at_zero[(r, i)]))
                        .collect();
                    let norm = reference.iter().map(|v| v * v).sum::<f64>().sqrt();
                    for (k, (ours, exact)) in
                        on_left.iter().chain(&on_right).zip(&reference).enumerate()
                    {
                        let exact = exact / norm;
                        assert!(
                            (ours - exact).abs() <= 1e-13,
                            "m {m} r {r} lengths ({left}, {right}) entry {k}: {ours} vs {exact}"
                        );
                    }
                }
            }
        }
    }

    /// The table-driven rows are [`continuity_row_nonzero`]'s to the bit
    /// (every order below [`SMALL_ROWS`], random lengths), and the
    /// constant-size residual is the general one to the bit (degrees 1..7,
    /// two and three pieces, dimensions 1..4, values of mixed signs and
    /// scales).
    #[test]
    fn small_continuity_rows_and_residual_are_the_general_ones_to_the_bit() {
        let mut state = 99u64;
        let mut next = || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for m in 0..SMALL_ROWS {
            for _ in 0..20 {
                let (left, right) = (next(), next());
                for r in 0..=m {
                    let ([mut a, mut b], [mut c, mut d]) =
                        ([[7.0; SMALL_ROWS]; 2], [[7.0; SMALL_ROWS]; 2]);
                    continuity_row_nonzero(m, r, left, right, &mut a[..=m], &mut b[..=m]);
                    continuity_row_small(m, r, left, right, &mut c[..=m], &mut d[..=m]);
                    assert_eq!(a.map(f64::to_bits), c.map(f64::to_bits), "m {m} r {r}");
                    assert_eq!(b.map(f64::to_bits), d.map(f64::to_bits), "m {m} r {r}");
                }
            }
        }
        for case in 0..600 {
            let m = 1 + case % 7;
            let count = 2 + case % 2;
            let dim = 1 + case % 4;
            let scale = [1.0, 1e-3, 1e4][case % 3];
            let curves: Vec<BezierCurve> = (0..count)
                .map(|_| {
                    let points = (0..(m + 1) * dim)
                        .map(|_| (next() * 2.0 - 1.0) * scale)
                        .collect();
                    BezierCurve::new(dim, m, points).unwrap()
                })
                .collect();
            let pieces: Vec<PieceInput<'_>> = curves
                .iter()
                .map(|c| PieceInput {
                    curve: std::borrow::Cow::Borrowed(c),
                    name: "P",
                    points_name: "p_points",
                    keep: false,
                    points: Vec::new(),
                })
                .collect();
            let lengths: Vec<f64> = (0..count).map(|_| 0.05 + next()).collect();
            let problem = Problem::new(&pieces, &lengths, false);
            // x: the pieces' points, near-continuous, plus noise.
            let x = DMatrix::from_fn(count * (m + 1), dim, |_, _| (next() - 0.5) * scale);
            let sized = problem.continuity_residual(&x);
            let [mut left, mut right] = [[0.0f64; SMALL_ROWS]; 2];
            let general = problem.continuity_residual_in(&x, &mut left[..=m], &mut right[..=m]);
            assert_eq!(sized.to_bits(), general.to_bits(), "case {case}");
        }
    }
}
