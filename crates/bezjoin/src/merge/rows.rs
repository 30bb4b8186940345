//! The rows of stage 1: the continuity conditions (3), fix ends and keep
//! points as linear conditions on the perturbations, and the bookkeeping of
//! dependent rows (consistent, contradictory or undecided).

use nalgebra::{DMatrix, DVector};

use crate::basis::bezier_basis_derivatives;
use crate::error::{BezjoinError, Result};

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
    pub(super) x0: DMatrix<f64>,
    /// Coordinate scale of the input.
    pub(super) scale: f64,
    pub(super) continuity: Vec<Row>,
    pub(super) constraints: Vec<Row>,
}

impl<'p, 'a> Problem<'p, 'a> {
    pub(super) fn new(pieces: &'p [PieceInput<'a>], lengths: &[f64], fix_ends: bool) -> Self {
        let count = pieces.len();
        let m = pieces[0].curve.degree();
        let dim = pieces[0].curve.dim();
        let points_per_piece = m + 1;
        let unknowns = count * points_per_piece;
        let mut x0 = DMatrix::zeros(unknowns, dim);
        for (j, p) in pieces.iter().enumerate() {
            x0.rows_mut(j * points_per_piece, points_per_piece)
                .copy_from(&p.curve.control_matrix());
        }
        let scale = x0.amax().max(f64::MIN_POSITIVE);

        // Continuity rows (3): independent by construction (row r of join j
        // brings in control point r of piece j + 1 for the first time).
        let at_one = bezier_basis_derivatives(m, 1.0, m);
        let at_zero = bezier_basis_derivatives(m, 0.0, m);
        let mut continuity = Vec::new();
        for j in 0..count - 1 {
            let (left, right) = (lengths[j], lengths[j + 1]);
            let longer = left.max(right);
            for r in 0..=m {
                let mut a = DVector::zeros(unknowns);
                let wl = (right / longer).powi(r as i32);
                let wr = (left / longer).powi(r as i32);
                for i in 0..=m {
                    a[j * points_per_piece + i] = wl * at_one[(r, i)];
                    a[(j + 1) * points_per_piece + i] = -wr * at_zero[(r, i)];
                }
                continuity.push(normalised(Row {
                    coefficients: a,
                    rhs: DVector::zeros(dim),
                    label: format!(
                        "continuity of order {r} between {} and {}",
                        pieces[j].name,
                        pieces[j + 1].name
                    ),
                }));
            }
        }

        // Constraint rows, in a fixed order; right-hand sides are exactly
        // zero (the constrained quantities keep their values). "Keep piece j
        // unchanged" is not among them: see `solve_stage_one`.
        let mut constraints = Vec::new();
        let unit = |index: usize| {
            let mut a = DVector::zeros(unknowns);
            a[index] = 1.0;
            a
        };
        if fix_ends {
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
        Self {
            pieces,
            points_per_piece,
            unknowns,
            dim,
            x0,
            scale,
            continuity,
            constraints,
        }
    }

    /// Conditions given beyond continuity (a kept piece counts `m + 1`).
    pub(super) fn given(&self) -> usize {
        self.pieces.iter().filter(|p| p.keep).count() * self.points_per_piece
            + self.constraints.len()
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
