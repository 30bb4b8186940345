//! Approximate merging of consecutive Bezier curves into one curve
//! (docs/mathematics.md#merge).
//!
//! After Ganchuk, Krivosheev, Mavrin, Ryzhov, "Approximation of conjugation
//! of Bezier curves with preservation of smoothness order and additional
//! restrictions", Bulletin of SUSU, Construction and Architecture, 2024,
//! 24(1) 59-69, which builds on Hu, Tong, Ju, Sun, "Approximate merging of a
//! pair of Bezier curves", Computer-Aided Design 33 (2001).
//!
//! # The method
//!
//! Given `P` and `Q` of degree `n` (a lower degree is elevated first,
//! exactly), [`merge`] finds the smallest changes `eps`, `delta` of their
//! control points such that `P^ = P + eps` and `Q^ = Q + delta` are the two
//! pieces of ONE Bezier curve `R` of degree `n` split at `mu in (0, 1)`:
//! `P^(u) = R(mu u)`, `Q^(v) = R(mu + (1 - mu) v)`.
//!
//! **Stage 1** minimises the chosen [`MergeMetric`] subject to the
//! continuity conditions
//!
//! ```text
//! (1 - mu)^r P^^(r)(1) = mu^r Q^^(r)(0),   r = 0..n                 (3)
//! ```
//!
//! and the caller's constraints. The `mu` factors fix a gap in the paper,
//! whose equations omit them and are right only for `mu = 1/2`. The
//! solver does not write (3) as rows: `R` itself is the unknown and the
//! pieces are its exact restrictions, so (3) holds by construction; the
//! metric becomes a least-squares norm of a sample matrix (the Bernstein
//! values of `R` at Gauss-Legendre nodes for the integral metric, never the
//! ill-conditioned Gram matrix), the other constraints are eliminated by
//! an orthonormal null-space basis, and the reduced problem is solved by
//! Householder QR, for all coordinates at once (module `orthogonal`). The
//! paper's Lagrange-multiplier (KKT) formulation is kept as the tests'
//! reference.
//!
//! **Stage 2**: stage 1 found `R` directly (the spec's "or solve for `R`
//! directly") and the pieces are `R` split at `mu` by de Casteljau. With a
//! kept piece, `R = segment(P^, 0, 1/mu)`, or `segment(Q^, -mu/(1-mu), 1)`
//! when `mu < 1/2` (extrapolate from the longer piece: the rounding error
//! grows like `(2/mu - 1)^n`), refined by two least-squares correction
//! steps against both pieces at once. `R` restricted to `[0, mu]` and
//! `[mu, 1]` by a second algorithm (blossoms) must give back `P^` and `Q^`;
//! that check is part of every merge.
//!
//! # Guarantees and checks
//!
//! * The stage-1 solve is checked: its first-order componentwise error
//!   estimate of the pieces (module `orthogonal`; measured >= the true
//!   error against an exact rational reference, test `merge_exact`) and
//!   the residual of (3) must stay below `accuracy` (default
//!   [`DEFAULT_MERGE_ACCURACY`]), otherwise the answer is `IllConditioned`
//!   with the estimate. Estimates and checks are relative to the larger of
//!   the input's and the result's coordinate scale (keep P with a small `mu`
//!   makes `Q^` far larger than `P` and `Q`).
//! * `R` restricted to each piece's interval reproduces the stage-1 pieces to
//!   `accuracy` relative to the coordinate scale, otherwise `IllConditioned`.
//! * Constraints: rows are scaled to unit length and tested against the
//!   continuity rows and the constraints before them (QR / Gram-Schmidt; a
//!   remainder at the rounding level, [`RANK_TOLERANCE`] `sqrt(N)`, means
//!   linearly dependent; any larger remainder keeps the row and its
//!   ill-conditioning goes into the estimate). A dependent row that the
//!   solution satisfies (to [`CONSISTENCY_TOLERANCE`] times the size of the
//!   input, the largest range of one coordinate: unchanged by a
//!   translation) is *redundant but consistent* and accepted
//!   (for example three points with first derivatives on a cubic `P`); one
//!   that it misses by more than [`CONTRADICTION_MARGIN`] times what the
//!   rounding explains (`sqrt(N)` times the error estimate, plus the rows'
//!   own rounding) is *contradictory*, an [`BezjoinError::Inconsistent`]
//!   error naming it; in between, `IllConditioned`. Beyond continuity, at
//!   most `n + 1` independent conditions per coordinate fit.
//! * Keep P / keep Q (a kept curve of a chain): nothing is minimised, since
//!   (3) makes the pieces one curve `R` and a kept piece fixes `R` (its
//!   extension). The other pieces are computed directly from the kept one
//!   (the one with the shortest extrapolation if several are kept) by
//!   compensated de Casteljau (error-free transformations, double-double
//!   parameters), with the bound `2 eps |x| + 2 (3 n eps)^2 |blossom|` per
//!   control point as the error estimate: a few ulps even for a small kept
//!   piece (plain arithmetic would lose `(2/mu - 1)^n` ulps). The kept curve
//!   is returned bit for bit. Every other condition (another kept curve,
//!   fix ends, keep points) is then dependent and checked as above, what
//!   rounding explains being that bound plus the data's own half-ulp
//!   rounding magnified by the extension, `eps |blossom|`: keep P with fix
//!   ends on unrelated curves is `Inconsistent`, on the two pieces of one
//!   curve it is answered (or `IllConditioned` when the extension magnifies
//!   the pieces' rounding beyond the tolerance).
//! * Every merge reports `mu`, the metric value and the largest distance
//!   between `R` and "P then Q" ([`DEVIATION_SAMPLES`] + 1 samples on each
//!   piece, `R(mu u)` against `P(u)`, `R(mu + (1-mu) v)` against `Q(v)`).
//!
//! # Beyond the paper
//!
//! * the `mu` minimising the metric ([`Breakpoints::Optimal`]);
//! * a merged degree `m > n` ([`MergeOptions::degree`]): `P` and `Q` are
//!   elevated to `m` (exact) and the degree-`m` problem is solved;
//! * [`merge_chain`]: `N >= 2` consecutive curves into one, see there.

mod bspline;
mod bspline_slope;
mod columns;
mod kept;
mod kkt;
mod lsq;
mod orthogonal;
mod refine;
mod rows;
mod stage_one;
mod stage_two;
mod trial;

use crate::bezier::{BezierCurve, check_degree_supported};
use crate::error::{
    BezjoinError, Result, check_closed_range, check_finite_scalar, check_open_range, check_positive,
};
use crate::minimize::{Minimum, minimize_on_grid_then_brent, minimize_with_slope};

pub use bspline::{
    BSplineChainMerge, BSplineMerge, CurveChainMerge, CurveMerge, MAX_MERGE_POLES,
    merge_bspline_chain, merge_bsplines, merge_bsplines_metric_at, merge_curve_chain, merge_curves,
};

pub use stage_one::{
    CONSISTENCY_TOLERANCE, CONTRADICTION_MARGIN, DEVIATION_SAMPLES, RANK_TOLERANCE,
};
use stage_one::{PieceInput, StageOne, StageOneCheck, solve_stage_one, solve_stage_one_slope};
use stage_two::{max_deviation, stage_two};

/// The default `accuracy` of a merge: the largest accepted relative error
/// estimate of the stage-1 solve and of the stage-2 check.
pub const DEFAULT_MERGE_ACCURACY: f64 = 1e-8;

/// The optimal split parameter is searched in `[MU_SEARCH_MIN, 1 - MU_SEARCH_MIN]`.
pub const MU_SEARCH_MIN: f64 = 1e-3;

/// Number of evenly spaced samples of the metric that bracket the optimal
/// `mu` before the refinement by Brent's method.
pub const MU_SEARCH_SAMPLES: usize = 32;

/// Evenly spaced samples of the metric and its slope that start the
/// derivative-based search of the optimal `mu` (no kept curve, no keep
/// points) at degree 0; one more per degree, at most
/// [`MU_SEARCH_SAMPLES`] + 1 (the metric's features narrow like `1 / n`).
/// Every interval whose cubic Hermite model has a minimum (or whose values
/// contradict its slopes) is searched.
pub const MU_SEARCH_SLOPE_SAMPLES: usize = 9;

/// The refinement (Brent's method) stops when the bracket around the best
/// `mu` is about this wide.
pub const MU_SEARCH_TOLERANCE: f64 = 1e-10;

/// At most this many refinement evaluations after the grid.
pub const MU_SEARCH_MAX_STEPS: usize = 100;

/// Samples of the metric, evenly spaced in `ln mu` (or `ln (1 - mu)`),
/// over a tail of the optimal `mu`'s range below [`MU_SEARCH_MIN`] (at
/// most `[MIN_SPLIT, MU_SEARCH_MIN]`, three decades), searched where the
/// main search's minimum lies in its outermost grid interval and one
/// curve is far shorter than the other ([`extend_into_tail`]).
pub const MU_TAIL_SAMPLES: usize = 10;

/// The tail of the optimal `mu`'s search reaches this factor closer to the
/// end than the split proportional to the control-polygon lengths
/// ([`extend_into_tail`]).
pub const MU_TAIL_REACH: f64 = 10.0;

/// The tail search's refinement stops at a bracket about this wide in
/// `ln mu` (`ln (1 - mu)`): a relative step of 1e-6 in the distance to
/// the end of the range.
pub const MU_TAIL_TOLERANCE: f64 = 1e-6;

/// What stage 1 minimises.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum MergeMetric {
    /// Sum of the squared changes of the control points,
    /// `sum_i |eps_i|^2 + |delta_i|^2`.
    #[default]
    Discrete,
    /// The paper's eq. (12): `int_0^1 |P^(u) - P(u)|^2 du + int_0^1 |Q^(v) -
    /// Q(v)|^2 dv`, each curve in its own parameter, equal weights, with the
    /// exact Bernstein Gram matrix (`G_ij = C(n,i) C(n,j) / ((2n+1) C(2n,i+j))`).
    Integral,
}

/// Keep the point and its derivatives `0..=max_order` of a curve at `param`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeepPoint {
    /// `u_k` on `P` or `v_k` on `Q`, in `[0, 1]`.
    pub param: f64,
    /// Derivatives `0..=max_order` are kept (at most the working degree).
    pub max_order: usize,
}

/// Options of [`merge`].
#[derive(Debug, Clone, PartialEq)]
pub struct MergeOptions {
    /// The metric minimised in stage 1.
    pub metric: MergeMetric,
    /// How `mu` is chosen.
    pub split: Breakpoints,
    /// `P` unchanged (`eps = 0`).
    pub keep_p: bool,
    /// `Q` unchanged (`delta = 0`).
    pub keep_q: bool,
    /// First point of `P` and last point of `Q` unchanged.
    pub fix_ends: bool,
    /// Points of `P` kept with derivatives.
    pub p_points: Vec<KeepPoint>,
    /// Points of `Q` kept with derivatives.
    pub q_points: Vec<KeepPoint>,
    /// Degree of `R`; `None` is the larger of the two degrees. A larger
    /// value elevates both curves to it first.
    pub degree: Option<usize>,
    /// Largest accepted relative error estimate ([`DEFAULT_MERGE_ACCURACY`]).
    pub accuracy: f64,
}

impl Default for MergeOptions {
    fn default() -> Self {
        Self {
            metric: MergeMetric::Discrete,
            split: Breakpoints::Uniform,
            keep_p: false,
            keep_q: false,
            fix_ends: false,
            p_points: Vec::new(),
            q_points: Vec::new(),
            degree: None,
            accuracy: DEFAULT_MERGE_ACCURACY,
        }
    }
}

impl MergeOptions {
    /// These options with another metric.
    pub fn with_metric(mut self, metric: MergeMetric) -> Self {
        self.metric = metric;
        self
    }

    /// These options with another split choice.
    pub fn with_split(mut self, split: Breakpoints) -> Self {
        self.split = split;
        self
    }
}

/// What every merge reports.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MergeReport {
    /// Split parameter used.
    pub mu: f64,
    /// Value of the minimised metric.
    pub metric_value: f64,
    /// Largest distance between `R` and "P then Q" (sampled, see the module).
    pub max_deviation: f64,
    /// Relative error estimate of the stage-1 KKT solve.
    pub solve_error_estimate: f64,
    /// Largest control-point difference between `R` split at `mu` and
    /// `P^`, `Q^`, relative to the coordinate scale.
    pub split_check_error: f64,
}

/// The result of [`merge`].
#[derive(Debug, Clone, PartialEq)]
pub struct Merge {
    /// The single curve `R`.
    pub merged: BezierCurve,
    /// `P^ = P + eps`, the piece of `R` on `[0, mu]`.
    pub p_hat: BezierCurve,
    /// `Q^ = Q + delta`, the piece of `R` on `[mu, 1]`.
    pub q_hat: BezierCurve,
    /// Split parameter, metric value, deviation and checks.
    pub report: MergeReport,
}

/// The smallest piece a given split `mu` may leave, as a part of the
/// merged curve's parameter range: the continuity conditions at the join
/// scale like `mu^-n`, and below this a merge was answered with a wrong
/// curve (`mu = 1e-6 .. 1e-100`: 3.18 mm off on 20 mm B-splines) or a NaN
/// length (`1e-200`), user testing, session 39. The FreeCAD form's limit.
pub const MIN_SPLIT: f64 = 1e-6;

/// `mu` in `(0, 1)` (ParameterOutOfRange, as before), then in
/// `[MIN_SPLIT, 1 - MIN_SPLIT]` (ParameterOutOfRange naming that range).
pub(crate) fn check_split(mu: f64) -> Result<()> {
    check_open_range("mu", mu, 0.0, 1.0)?;
    check_closed_range("mu", mu, MIN_SPLIT, 1.0 - MIN_SPLIT)
}

/// Merge `P` and `Q` into one Bezier curve `R` (docs/mathematics.md#merge;
/// Ganchuk et al. 2024 with the `mu`-scaled continuity conditions).
///
/// Guarantee: `P^`, `Q^` are the pieces of `R` at `mu` (checked to
/// `options.accuracy`), satisfy the constraints, and minimise the metric
/// among all such pairs; see the module documentation for the checks.
///
/// ```
/// # use bezjoin_core::{BezierCurve, Breakpoints, MergeOptions, merge};
/// let r = BezierCurve::from_rows(&[[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]]).unwrap();
/// let (p, q) = r.split_at(0.3).unwrap();
/// let options = MergeOptions::default().with_split(Breakpoints::Optimal);
/// let result = merge(&p, &q, &options).unwrap();
/// assert!((result.report.mu - 0.3).abs() < 1e-6);
/// assert!(result.report.max_deviation < 1e-9);
/// ```
///
/// Errors: dimensions differ (DimensionMismatch); `mu` outside `(0, 1)` or
/// `[MIN_SPLIT, 1 - MIN_SPLIT]`,
/// a keep-point parameter outside `[0, 1]` (ParameterOutOfRange); an order
/// above the working degree (OrderAboveDegree); a degree below the curves'
/// or, for [`Breakpoints::PolygonLength`], a control polygon of zero
/// length or too short next to the total for a non-empty interval
/// (InvalidArgument); NaN/infinity (NonFinite); too many or contradictory
/// constraints (Inconsistent, naming the constraint); an untrustworthy
/// solve (IllConditioned, with the estimate).
pub fn merge(p: &BezierCurve, q: &BezierCurve, options: &MergeOptions) -> Result<Merge> {
    let problem = PairProblem::new(p, q, options)?;
    let (mu, stage_one) = match &options.split {
        Breakpoints::Given(inner) => {
            let &[mu] = inner.as_slice() else {
                return Err(BezjoinError::LengthMismatch {
                    name: "mu".into(),
                    expected: 1,
                    actual: inner.len(),
                });
            };
            check_split(mu)?;
            (mu, problem.solve_given(mu)?)
        }
        Breakpoints::Uniform => (0.5, problem.solve_given(0.5)?),
        Breakpoints::PolygonLength => {
            let mu =
                polygon_breakpoints(&[p.polygon_length(), q.polygon_length()], &["P", "Q"])?[1];
            (mu, problem.solve_given(mu)?)
        }
        Breakpoints::Optimal => {
            let mu = problem.optimal_mu(StageOneCheck::Trial)?;
            match problem.solve(mu, StageOneCheck::Full) {
                // The quick search's winner failed the full check: search
                // again with the full check at every trial.
                Err(BezjoinError::IllConditioned { .. }) => {
                    let mu = problem.optimal_mu(StageOneCheck::Full)?;
                    (mu, problem.solve(mu, StageOneCheck::Full)?)
                }
                stage_one => (mu, stage_one?),
            }
        }
    };
    let breakpoints = [0.0, mu, 1.0];
    let (metric_value, solve_error_estimate) = (stage_one.metric_value, stage_one.error_estimate);
    let (merged, split_check_error, [p_hat, q_hat], max_deviation) =
        match stage_one.into_split_curves() {
            // Stage 1's pieces are R's split at mu: stage 2's restrictions are
            // those very curves and its check's difference is exactly zero (the
            // shortcut of `stage_two`, here without the pieces' matrices). P^
            // and Q^ are those curves; their construction cannot fail
            // (`StageOne::into_split_curves`).
            Ok((merged, hats)) => {
                let max_deviation = max_deviation(&hats, &[p, q])?;
                (merged, 0.0, hats, max_deviation)
            }
            Err(stage_one) => {
                let pieces = stage_one.pieces();
                let (merged, split_check_error, restrictions) = stage_two(
                    &pieces,
                    &breakpoints,
                    options.accuracy,
                    stage_one.merged.as_ref(),
                    stage_one.split_of_merged,
                )?;
                let max_deviation = max_deviation(&restrictions, &[p, q])?;
                // P^ and Q^ are stage 1's pieces.
                let mut hats = pieces.iter().map(BezierCurve::from_matrix);
                let p_hat = hats.next().expect("two pieces")?;
                let q_hat = hats.next().expect("two pieces")?;
                (merged, split_check_error, [p_hat, q_hat], max_deviation)
            }
        };
    Ok(Merge {
        merged,
        p_hat,
        q_hat,
        report: MergeReport {
            mu,
            metric_value,
            max_deviation,
            solve_error_estimate,
            split_check_error,
        },
    })
}

/// The metric value of the stage-1 optimum at a given `mu` (no stage 2),
/// the function [`Breakpoints::Optimal`] minimises. `options.split` is
/// ignored.
pub fn merge_metric_at(
    p: &BezierCurve,
    q: &BezierCurve,
    options: &MergeOptions,
    mu: f64,
) -> Result<f64> {
    let problem = PairProblem::new(p, q, options)?;
    check_split(mu)?;
    problem.solve_given(mu).map(|s| s.metric_value)
}

/// Two curves at the working degree with their constraints: what stage 1
/// needs for any `mu`.
struct PairProblem<'a> {
    /// `P` and `Q` (on the stack: a merge's one allocation fewer).
    pieces: [PieceInput<'a>; 2],
    metric: MergeMetric,
    fix_ends: bool,
    accuracy: f64,
}

impl<'a> PairProblem<'a> {
    /// Validates the pair and the options other than the split.
    fn new(p: &'a BezierCurve, q: &'a BezierCurve, options: &'a MergeOptions) -> Result<Self> {
        if q.dim() != p.dim() {
            return Err(BezjoinError::DimensionMismatch {
                name: "q".into(),
                expected: p.dim(),
                actual: q.dim(),
            });
        }
        check_positive("accuracy", options.accuracy)?;
        let degree = working_degree(&[p, q], options.degree)?;
        let pieces = [
            piece_input(
                p,
                "P",
                "p_points",
                options.keep_p,
                options.p_points.iter().enumerate().collect(),
                degree,
            )?,
            piece_input(
                q,
                "Q",
                "q_points",
                options.keep_q,
                options.q_points.iter().enumerate().collect(),
                degree,
            )?,
        ];
        Ok(Self {
            pieces,
            metric: options.metric,
            fix_ends: options.fix_ends,
            accuracy: options.accuracy,
        })
    }

    /// The split proportional to the control-polygon lengths of the two
    /// pieces (as worked on), `L_P / (L_P + L_Q)`: where the tail of the
    /// optimal `mu`'s search may reach ([`extend_into_tail`]).
    fn polygon_mu(&self) -> f64 {
        polygon_split(
            self.pieces[0].curve.polygon_length(),
            self.pieces[1].curve.polygon_length(),
        )
    }

    /// The fully checked solve at a given `mu`, without the slope (which
    /// only the search of the optimal `mu` reads).
    fn solve_given(&self, mu: f64) -> Result<StageOne> {
        solve_stage_one_slope(
            &self.pieces,
            &[0.0, mu, 1.0],
            self.metric,
            self.fix_ends,
            self.accuracy,
            StageOneCheck::Full,
            false,
        )
    }

    fn solve(&self, mu: f64, check: StageOneCheck) -> Result<StageOne> {
        solve_stage_one(
            &self.pieces,
            &[0.0, mu, 1.0],
            self.metric,
            self.fix_ends,
            self.accuracy,
            check,
        )
    }

    /// The search of [`Breakpoints::Optimal`], each trial solved with
    /// `check`: on the metric and its slope (closed form) when the
    /// conditions do not depend on `mu` (no kept curve, no keep points),
    /// on the metric alone otherwise.
    fn optimal_mu(&self, check: StageOneCheck) -> Result<f64> {
        let with_slope = self.pieces.iter().all(|p| !p.keep && p.points.is_empty());
        if !with_slope {
            return optimal_mu(self.polygon_mu(), |mu| {
                self.solve(mu, check).map(|s| s.metric_value)
            });
        }
        let mut first_error = None;
        let mut without_slope = false;
        // The quick search's trials: the lean solver (value and slope only,
        // everything independent of mu prepared once); the fully checked
        // search, and any mu the lean solver cannot factor, go through
        // stage 1.
        let mut lean = match check {
            StageOneCheck::Trial => {
                trial::TrialSolver::new(&self.pieces, self.metric, self.fix_ends)
            }
            StageOneCheck::Full => None,
        };
        let samples =
            (MU_SEARCH_SLOPE_SAMPLES + self.pieces[0].curve.degree()).min(MU_SEARCH_SAMPLES + 1);
        let minimum = minimize_with_slope(
            |mu| {
                if let Some(found) = lean.as_mut().and_then(|t| t.evaluate(mu)) {
                    return Some(found);
                }
                match self.solve(mu, check) {
                    Ok(s) => {
                        without_slope |= s.slope.is_none();
                        Some((s.metric_value, s.slope.unwrap_or(f64::NAN)))
                    }
                    Err(e) => {
                        first_error.get_or_insert(e);
                        None
                    }
                }
            },
            MU_SEARCH_MIN,
            1.0 - MU_SEARCH_MIN,
            samples,
            MU_SEARCH_TOLERANCE,
            MU_SEARCH_MAX_STEPS,
        );
        if without_slope {
            // Some trials were answered by the KKT fallback of stage 1,
            // which has no slope: the search on the values alone.
            return optimal_mu(self.polygon_mu(), |mu| {
                self.solve(mu, check).map(|s| s.metric_value)
            });
        }
        match (minimum, first_error) {
            (Some(m), _) => Ok(extend_into_tail(m, samples, self.polygon_mu(), |mu| {
                match lean.as_mut().and_then(|t| t.evaluate(mu)) {
                    Some((value, _)) => value,
                    None => self
                        .solve(mu, check)
                        .map_or(f64::INFINITY, |s| s.metric_value),
                }
            })
            .x),
            (None, Some(e)) => Err(e),
            (None, None) => Err(BezjoinError::NonFiniteScalar {
                name: "merge metric at every sampled mu".into(),
                value: f64::INFINITY,
            }),
        }
    }
}

/// How the breakpoints `0 = t_0 < t_1 < ... < t_N = 1` of a merge of `N`
/// curves are chosen: curve `j` becomes `R` on `[t_j, t_{j+1}]`. For two
/// curves ([`merge`]) `t_1` is the split parameter `mu`. One type for
/// [`merge`] ([`MergeOptions::split`], default [`Breakpoints::Uniform`],
/// `mu = 1/2` as in the paper's examples) and [`merge_chain`]
/// ([`ChainMergeOptions::breakpoints`], default
/// [`Breakpoints::PolygonLength`]).
#[derive(Debug, Clone, PartialEq)]
pub enum Breakpoints {
    /// The caller's interior breakpoints `0 < t_1 < ... < t_{N-1} < 1`
    /// (for [`merge`], the one value `mu`, named `mu` in errors).
    Given(Vec<f64>),
    /// `t_j = j / N` (`mu = 1/2`).
    Uniform,
    /// Proportional to the control-polygon lengths (for two curves
    /// `mu = L_P / (L_P + L_Q)`, the paper's suggestion).
    PolygonLength,
    /// For [`merge`] only: the `mu` minimising the metric. Without kept
    /// curves and keep points, the metric and its slope `d metric / d mu`
    /// (closed form, by the envelope theorem: the derivative of the
    /// least-squares norm at the optimal, fixed `R`) are sampled at
    /// `MU_SEARCH_SLOPE_SAMPLES` + degree evenly spaced values (at most
    /// [`MU_SEARCH_SAMPLES`] + 1) and every interval whose cubic Hermite
    /// model may hold a minimum is searched on the slope (safeguarded cubic
    /// interpolation, [`MU_SEARCH_TOLERANCE`]); the trials skip the error
    /// estimate, the winner is solved with every check. Otherwise the
    /// metric is sampled at [`MU_SEARCH_SAMPLES`] + 1 evenly spaced values in
    /// `[MU_SEARCH_MIN, 1 - MU_SEARCH_MIN]`, the best sample and its
    /// neighbours bracket Brent's method (parabolic interpolation
    /// safeguarded by golden section) that stops at a bracket of about
    /// [`MU_SEARCH_TOLERANCE`] (or after [`MU_SEARCH_MAX_STEPS`] steps).
    /// This finds the global minimum when the metric has one minimum per
    /// sampling interval; values of `mu` where stage 1 fails count as
    /// infinitely bad. [`merge_chain`] refuses it (InvalidArgument).
    Optimal,
}

/// A keep-point on one curve of a chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainKeepPoint {
    /// Index of the curve in the chain.
    pub curve: usize,
    /// Parameter and derivative order on that curve.
    pub point: KeepPoint,
}

/// Options of [`merge_chain`].
#[derive(Debug, Clone, PartialEq)]
pub struct ChainMergeOptions {
    /// The metric, summed over the pieces.
    pub metric: MergeMetric,
    /// How the breakpoints are chosen.
    pub breakpoints: Breakpoints,
    /// Curves kept unchanged: empty (none), or one flag per curve.
    pub keep: Vec<bool>,
    /// First point of the first curve and last point of the last unchanged.
    pub fix_ends: bool,
    /// Points kept with derivatives.
    pub keep_points: Vec<ChainKeepPoint>,
    /// Degree of `R`; `None` is the largest degree of the curves.
    pub degree: Option<usize>,
    /// Largest accepted relative error estimate ([`DEFAULT_MERGE_ACCURACY`]).
    pub accuracy: f64,
}

impl Default for ChainMergeOptions {
    fn default() -> Self {
        Self {
            metric: MergeMetric::Discrete,
            breakpoints: Breakpoints::PolygonLength,
            keep: Vec::new(),
            fix_ends: false,
            keep_points: Vec::new(),
            degree: None,
            accuracy: DEFAULT_MERGE_ACCURACY,
        }
    }
}

/// What a chain merge reports.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainMergeReport {
    /// `0 = t_0 < t_1 < ... < t_N = 1`: curve `j` became `R` on `[t_j, t_{j+1}]`.
    pub breakpoints: Vec<f64>,
    /// Sum of the metrics of all pieces.
    pub metric_value: f64,
    /// Largest distance between `R(t_j + (t_{j+1} - t_j) u)` and `C_j(u)`, sampled.
    pub max_deviation: f64,
    /// Relative error estimate of the stage-1 KKT solve.
    pub solve_error_estimate: f64,
    /// Largest control-point difference between `R` restricted to the
    /// pieces' intervals and the pieces, relative to the coordinate scale.
    pub split_check_error: f64,
}

/// The result of [`merge_chain`].
#[derive(Debug, Clone, PartialEq)]
pub struct ChainMerge {
    /// The single curve `R`.
    pub merged: BezierCurve,
    /// The changed curves `C^_j`, each `R` on `[t_j, t_{j+1}]`.
    pub pieces: Vec<BezierCurve>,
    /// Breakpoints, metric value, deviation and checks.
    pub report: ChainMergeReport,
}

/// **[beyond the paper]** Merge `N >= 2` consecutive curves `C_0..C_{N-1}`
/// into one Bezier curve `R` of degree `m` (the largest degree, or
/// `options.degree`; lower degrees are elevated exactly).
///
/// With breakpoints `0 = t_0 < t_1 < ... < t_N = 1` and `h_j = t_{j+1} -
/// t_j`, curve `j` is to become `C^_j(u) = R(t_j + h_j u)`. The pieces are
/// one polynomial exactly when at every join
/// `h_{j+1}^r C^_j^(r)(1) = h_j^r C^_{j+1}^(r)(0)`, `r = 0..m` (eq. (3) with
/// `mu = h_j / (h_j + h_{j+1})`, scaled). Stage 1 minimises the SUM of the
/// pieces' metrics under these conditions and the constraints (one KKT
/// system); stage 2 extrapolates `R` from the piece with the shortest extrapolation
/// (for two pieces the longer one) and checks it
/// against every piece. With `N = 2` this is exactly [`merge`].
///
/// The breakpoints are given, uniform or proportional to the control-polygon
/// lengths; an optimal choice (an `(N-1)`-dimensional search) is not offered.
///
/// Errors: as [`merge`]; fewer than two curves, `keep` of the wrong length,
/// breakpoints not strictly increasing inside `(0, 1)`, leaving a piece
/// shorter than [`MIN_SPLIT`] of the range, or of the wrong count
/// (InvalidArgument / ParameterOutOfRange / LengthMismatch).
pub fn merge_chain(curves: &[BezierCurve], options: &ChainMergeOptions) -> Result<ChainMerge> {
    let count = curves.len();
    if count < 2 {
        return Err(BezjoinError::invalid(
            "curves",
            format!("{count} curves given, at least 2 are needed"),
        ));
    }
    for (j, c) in curves.iter().enumerate().skip(1) {
        if c.dim() != curves[0].dim() {
            return Err(BezjoinError::DimensionMismatch {
                name: format!("curves[{j}]"),
                expected: curves[0].dim(),
                actual: c.dim(),
            });
        }
    }
    check_positive("accuracy", options.accuracy)?;
    if !options.keep.is_empty() && options.keep.len() != count {
        return Err(BezjoinError::LengthMismatch {
            name: "keep".into(),
            expected: count,
            actual: options.keep.len(),
        });
    }
    let refs: Vec<&BezierCurve> = curves.iter().collect();
    let degree = working_degree(&refs, options.degree)?;
    let names: Vec<String> = (0..count).map(|j| format!("curves[{j}]")).collect();
    let per_curve = chain_keep_points(options, count)?;
    let mut pieces = Vec::with_capacity(count);
    for (j, c) in curves.iter().enumerate() {
        let keep = options.keep.get(j).copied().unwrap_or(false);
        pieces.push(piece_input(
            c,
            &names[j],
            "keep_points",
            keep,
            per_curve[j].clone(),
            degree,
        )?);
    }
    let lengths: Vec<f64> = curves.iter().map(BezierCurve::polygon_length).collect();
    let name_refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let breakpoints = chain_breakpoints(&options.breakpoints, &lengths, &name_refs)?;
    let stage_one = solve_stage_one(
        &pieces,
        &breakpoints,
        options.metric,
        options.fix_ends,
        options.accuracy,
        StageOneCheck::Full,
    )?;
    let stage_one_pieces = stage_one.pieces();
    let (merged, split_check_error, restrictions) = stage_two(
        &stage_one_pieces,
        &breakpoints,
        options.accuracy,
        stage_one.merged.as_ref(),
        stage_one.split_of_merged,
    )?;
    let max_deviation = max_deviation(&restrictions, &refs)?;
    let pieces = stage_one_pieces
        .iter()
        .map(BezierCurve::from_matrix)
        .collect::<Result<Vec<_>>>()?;
    Ok(ChainMerge {
        merged,
        pieces,
        report: ChainMergeReport {
            breakpoints,
            metric_value: stage_one.metric_value,
            max_deviation,
            solve_error_estimate: stage_one.error_estimate,
            split_check_error,
        },
    })
}

/// The breakpoints `0 = t_0 < ... < t_N = 1` of a chain merge of curves
/// with these control-polygon lengths: the caller's (validated), uniform
/// or proportional to the lengths, every piece at least [`MIN_SPLIT`]
/// ([`check_pieces`]); [`Breakpoints::Optimal`] is refused.
fn chain_breakpoints(
    breakpoints: &Breakpoints,
    lengths: &[f64],
    names: &[&str],
) -> Result<Vec<f64>> {
    let count = lengths.len();
    let all = match breakpoints {
        Breakpoints::Given(inner) => {
            if inner.len() != count - 1 {
                return Err(BezjoinError::LengthMismatch {
                    name: "breakpoints".into(),
                    expected: count - 1,
                    actual: inner.len(),
                });
            }
            let mut all = vec![0.0];
            for (k, &t) in inner.iter().enumerate() {
                let name = format!("breakpoints[{k}]");
                check_open_range(&name, t, 0.0, 1.0)?;
                if t <= *all.last().expect("non-empty") {
                    return Err(BezjoinError::invalid(
                        name,
                        format!("{t} is not above the breakpoint before it"),
                    ));
                }
                all.push(t);
            }
            all.push(1.0);
            all
        }
        Breakpoints::Uniform => (0..=count).map(|j| j as f64 / count as f64).collect(),
        Breakpoints::Optimal => {
            return Err(BezjoinError::invalid(
                "breakpoints",
                "Optimal is searched for two curves only (merge); give the breakpoints, \
                 Uniform or PolygonLength",
            ));
        }
        Breakpoints::PolygonLength => polygon_breakpoints(lengths, names)?,
    };
    check_pieces(&all, breakpoints, names)?;
    Ok(all)
}

/// Every piece `[t_j, t_(j+1)]` of `all` (`0 = t_0 < ... < t_N = 1`) spans
/// at least [`MIN_SPLIT`] of the range, the rule of a given `mu` for each
/// join of a chain: the join conditions scale like `h_j^-n` (user testing,
/// session 39: a pair split at `mu = 1e-6 .. 1e-100` was answered with a
/// curve 3.18 mm off). A given breakpoint is named (the first one that
/// ends a short piece, or the last one before a short final piece);
/// breakpoints proportional to polygon lengths name the short curve.
fn check_pieces(all: &[f64], breakpoints: &Breakpoints, names: &[&str]) -> Result<()> {
    let Some(j) = (0..all.len() - 1).find(|&j| all[j + 1] - all[j] < MIN_SPLIT) else {
        return Ok(());
    };
    let (from, to) = (all[j], all[j + 1]);
    let part = format!(
        "leaves {} the piece [{from}, {to}], {:e} of the merged curve's range, below the \
         smallest piece {MIN_SPLIT:e}",
        names[j],
        to - from
    );
    Err(match breakpoints {
        Breakpoints::Given(_) => {
            // Breakpoint k is all[k + 1]; the last piece ends at 1.
            let k = if j + 1 < all.len() - 1 { j } else { j - 1 };
            BezjoinError::invalid(
                format!("breakpoints[{k}]"),
                format!("{} {part}", all[k + 1]),
            )
        }
        _ => BezjoinError::invalid(
            "breakpoints",
            format!("the split proportional to polygon lengths {part}; give the split explicitly"),
        ),
    })
}

/// The keep points of a chain merge grouped by curve, each with its index
/// in `options.keep_points`; a curve index out of range is refused.
fn chain_keep_points(
    options: &ChainMergeOptions,
    count: usize,
) -> Result<Vec<Vec<(usize, &KeepPoint)>>> {
    let mut per_curve: Vec<Vec<(usize, &KeepPoint)>> = vec![Vec::new(); count];
    for (k, kp) in options.keep_points.iter().enumerate() {
        if kp.curve >= count {
            return Err(BezjoinError::invalid(
                format!("keep_points[{k}].curve"),
                format!("{} is not below the curve count {count}", kp.curve),
            ));
        }
        per_curve[kp.curve].push((k, &kp.point));
    }
    Ok(per_curve)
}

fn working_degree(curves: &[&BezierCurve], requested: Option<usize>) -> Result<usize> {
    checked_working_degree(
        curves.iter().map(|c| c.degree()).max().unwrap_or(0),
        requested,
    )
}

/// The merge's working degree: the `requested` one (the caller's `degree`)
/// or else `highest`, the highest degree of the curves to merge. A requested
/// degree below `highest` or above [`crate::MAX_DEGREE`] is InvalidArgument naming
/// `degree` (the latter used to be named `new_degree`, after the elevation
/// that refused it: user testing, session 40).
pub(super) fn checked_working_degree(highest: usize, requested: Option<usize>) -> Result<usize> {
    if let Some(m) = requested {
        check_degree_supported("degree", m)?;
    }
    match requested {
        None => Ok(highest),
        Some(m) if m >= highest => Ok(m),
        Some(m) => Err(BezjoinError::invalid(
            "degree",
            format!("{m} is below the highest degree {highest} of the curves to merge"),
        )),
    }
}

fn piece_input<'a>(
    curve: &'a BezierCurve,
    name: &'a str,
    points_name: &'a str,
    keep: bool,
    points: Vec<(usize, &'a KeepPoint)>,
    degree: usize,
) -> Result<PieceInput<'a>> {
    for &(k, kp) in &points {
        check_closed_range(&format!("{points_name}[{k}].param"), kp.param, 0.0, 1.0)?;
        if kp.max_order > degree {
            return Err(BezjoinError::OrderAboveDegree {
                name: format!("{points_name}[{k}].max_order"),
                order: kp.max_order,
                degree,
                curve: name.into(),
            });
        }
    }
    // At the working degree already: borrowed, not copied.
    let curve = if curve.degree() == degree {
        std::borrow::Cow::Borrowed(curve)
    } else {
        std::borrow::Cow::Owned(curve.elevate_degree(degree)?)
    };
    Ok(PieceInput {
        curve,
        name,
        points_name,
        keep,
        points,
    })
}

/// Breakpoints proportional to the control-polygon lengths.
fn polygon_breakpoints(lengths: &[f64], names: &[&str]) -> Result<Vec<f64>> {
    for (j, &l) in lengths.iter().enumerate() {
        check_finite_scalar("control polygon length", l)?;
        if l <= 0.0 {
            return Err(BezjoinError::invalid(
                "split",
                format!(
                    "the control polygon of {} has zero length, so a split proportional to \
                     polygon lengths would give it an empty interval",
                    names[j]
                ),
            ));
        }
    }
    let total: f64 = lengths.iter().sum();
    check_finite_scalar("sum of the control polygon lengths", total)?;
    let mut breakpoints = vec![0.0];
    let mut running = 0.0;
    for l in &lengths[..lengths.len() - 1] {
        running += l;
        breakpoints.push(running / total);
    }
    breakpoints.push(1.0);
    // A polygon far shorter than the total (below its rounding unit) gets
    // an interval that rounds to nothing: refuse rather than solve on an
    // empty piece.
    if let Some(j) = (0..lengths.len()).find(|&j| breakpoints[j + 1] <= breakpoints[j]) {
        return Err(BezjoinError::invalid(
            "split",
            format!(
                "the control polygon of {} (length {:e}) is too short next to the total \
                 length {:e} for a split proportional to polygon lengths: its interval \
                 rounds to nothing in double precision; give the split explicitly or use \
                 a uniform one",
                names[j], lengths[j], total
            ),
        ));
    }
    Ok(breakpoints)
}

/// Minimise `metric(mu)` over `[MU_SEARCH_MIN, 1 - MU_SEARCH_MIN]`: sampling
/// brackets the best sample, Brent's method refines it
/// ([`crate::minimize`]). When no sample can be solved, the first sample's
/// error is returned.
fn optimal_mu(polygon_mu: f64, mut metric: impl FnMut(f64) -> Result<f64>) -> Result<f64> {
    let mut first_error = None;
    let minimum = minimize_on_grid_then_brent(
        |mu| match metric(mu) {
            Ok(v) => v,
            Err(e) => {
                first_error.get_or_insert(e);
                f64::INFINITY
            }
        },
        MU_SEARCH_MIN,
        1.0 - MU_SEARCH_MIN,
        MU_SEARCH_SAMPLES + 1,
        MU_SEARCH_TOLERANCE,
        MU_SEARCH_MAX_STEPS,
    );
    match (minimum, first_error) {
        (Some(m), _) => Ok(
            extend_into_tail(m, MU_SEARCH_SAMPLES + 1, polygon_mu, |mu| {
                metric(mu).unwrap_or(f64::INFINITY)
            })
            .x,
        ),
        (None, Some(e)) => Err(e),
        // Every sample returned a non-finite value without an error: the
        // metric overflows everywhere.
        (None, None) => Err(BezjoinError::NonFiniteScalar {
            name: "merge metric at every sampled mu".into(),
            value: f64::INFINITY,
        }),
    }
}

/// `a / (a + b)` for the control-polygon lengths `a`, `b` of two curves
/// (NaN where it is not a number in `[0, 1]`): a hint for the tail of the
/// optimal `mu`'s search, so a zero length gives 0 or 1 here where
/// [`polygon_breakpoints`] (the split a caller asks for) refuses it.
pub(super) fn polygon_split(a: f64, b: f64) -> f64 {
    let mu = a / (a + b);
    if (0.0..=1.0).contains(&mu) {
        mu
    } else {
        f64::NAN
    }
}

/// The optimal `mu`'s search beyond `[MU_SEARCH_MIN, 1 - MU_SEARCH_MIN]`.
/// `found` is the main search's minimum on its grid of `grid_points`
/// evenly spaced samples; `polygon_mu` is the split proportional to the
/// control-polygon lengths, `L_P / (L_P + L_Q)`. Where `found` lies in the
/// grid's outermost interval at one end and `polygon_mu` lies within
/// `MU_TAIL_REACH * MU_SEARCH_MIN` of that end, one curve is far shorter
/// than the other and the minimum may lie closer to the end: a curve 1000
/// long merged with one 0.01 long has its minimum near `mu = 1 - 1e-5`,
/// and `mu = 0.999` changes the curves by a metric 64,000 times larger
/// (user testing, session 44). There `metric` is minimised again over the
/// tail from [`MU_SEARCH_MIN`] to `d = max(MIN_SPLIT, polygon's distance
/// to the end / MU_TAIL_REACH)` (`[d, MU_SEARCH_MIN]` or `[1 - MU_SEARCH_MIN,
/// 1 - d]`), on `ln mu` (`ln (1 - mu)`): [`MU_TAIL_SAMPLES`] samples, then
/// Brent's method to [`MU_TAIL_TOLERANCE`]. The tail reaches a decade past
/// the polygon split and no further: between curves of like lengths the
/// metric can keep falling towards `MIN_SPLIT` (one curve squeezed into a
/// millionth of `R`'s range), which is no merge a user asks for. Returns
/// the better of the two minima (`found` on a tie, and wherever no tail is
/// searched: the same answer as before). Non-finite values count as
/// infinitely bad.
pub(super) fn extend_into_tail(
    found: Minimum,
    grid_points: usize,
    polygon_mu: f64,
    mut metric: impl FnMut(f64) -> f64,
) -> Minimum {
    let (lo, hi) = (MU_SEARCH_MIN, 1.0 - MU_SEARCH_MIN);
    let step = (hi - lo) / (grid_points - 1) as f64;
    let toward_one = if found.x < lo + step {
        false
    } else if found.x > hi - step {
        true
    } else {
        return found;
    };
    let polygon_distance = if toward_one {
        1.0 - polygon_mu
    } else {
        polygon_mu
    };
    // (A NaN polygon split searches no tail; `f64::max` would drop it.)
    if polygon_distance.is_nan() {
        return found;
    }
    let reach = (polygon_distance / MU_TAIL_REACH).max(MIN_SPLIT);
    if reach >= MU_SEARCH_MIN {
        return found;
    }
    let mu_at = |s: f64| {
        let distance = s.exp();
        let mu = if toward_one { 1.0 - distance } else { distance };
        mu.clamp(MIN_SPLIT, 1.0 - MIN_SPLIT)
    };
    let tail = minimize_on_grid_then_brent(
        |s| metric(mu_at(s)),
        reach.ln(),
        MU_SEARCH_MIN.ln(),
        MU_TAIL_SAMPLES,
        MU_TAIL_TOLERANCE,
        MU_SEARCH_MAX_STEPS,
    );
    match tail {
        Some(t) if t.value < found.value => Minimum {
            x: mu_at(t.x),
            value: t.value,
            evaluations: found.evaluations + t.evaluations,
        },
        _ => found,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// The quick search (trials without the rounding term of the estimate)
    /// can pick a `mu` whose full check fails; `merge` must then fall back to
    /// the fully checked search and return its answer, never the quick one.
    /// Degrees 12..20 with the integral metric and tight accuracies give
    /// both situations.
    #[test]
    fn optimal_mu_falls_back_to_the_fully_checked_search() {
        let mut state = 5;
        let (mut fallbacks, mut quick_kept) = (0, 0);
        // The last two: accuracies below what even the double-double
        // refinement of the integral metric (module `refine`) reaches there,
        // so that fallbacks still occur now that it answers the first three.
        for (degree, accuracy) in [
            (12, 1e-6),
            (14, 1e-11),
            (20, 1e-9),
            (14, 1e-14),
            (20, 1e-13),
        ] {
            for _ in 0..3 {
                let (p, q) = (curve(&mut state, degree), curve(&mut state, degree));
                // Tight accuracies, so that the full check refuses some mu.
                let options = MergeOptions {
                    accuracy,
                    ..MergeOptions::default()
                        .with_metric(MergeMetric::Integral)
                        .with_split(Breakpoints::Optimal)
                };
                let problem = PairProblem::new(&p, &q, &options).unwrap();
                let Ok(quick) = problem.optimal_mu(StageOneCheck::Trial) else {
                    continue;
                };
                let result = merge(&p, &q, &options);
                match problem.solve(quick, StageOneCheck::Full) {
                    Ok(full) => {
                        quick_kept += 1;
                        let m = result.unwrap();
                        assert_eq!(m.report.mu, quick);
                        assert_eq!(m.report.metric_value, full.metric_value);
                    }
                    Err(BezjoinError::IllConditioned { .. }) => {
                        fallbacks += 1;
                        let checked = problem.optimal_mu(StageOneCheck::Full);
                        match (result, checked) {
                            (Ok(m), Ok(mu)) => {
                                assert_eq!(m.report.mu, mu);
                                assert_ne!(m.report.mu, quick);
                                // The answer passed every check at its mu.
                                assert!(problem.solve(mu, StageOneCheck::Full).is_ok());
                            }
                            (Err(e), Err(f)) => assert_eq!(e, f),
                            (r, c) => panic!("merge {r:?} vs fully checked search {c:?}"),
                        }
                    }
                    Err(e) => panic!("unexpected {e}"),
                }
            }
        }
        eprintln!("{fallbacks} fallbacks, {quick_kept} quick answers kept");
        assert!(
            fallbacks > 0 && quick_kept > 0,
            "{fallbacks} fallbacks, {quick_kept} quick answers kept: the test no longer covers both paths"
        );
    }
}

#[cfg(test)]
mod split_tests {
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// The options of case `case` of the stage-1 tests: the discrete
    /// metric for even cases, the integral one for odd; the ends fixed
    /// unless `case` is a multiple of 3.
    fn case_options(case: usize) -> MergeOptions {
        let metric = if case % 2 == 0 {
            MergeMetric::Discrete
        } else {
            MergeMetric::Integral
        };
        let mut options = MergeOptions::default().with_metric(metric);
        options.fix_ends = case % 3 != 0;
        options
    }

    /// Where stage 1 reports its pieces as `R`'s split
    /// (`split_of_merged`), they are `R.split_unchecked(mu)` bit for bit,
    /// and stage 2's full check on them (the restrictions recomputed and
    /// compared) finds exactly zero: what `stage_two` returns without
    /// recomputing. Both metrics, with and without fixed ends, degrees 1
    /// to 9, random `mu`; most stage-1 answers take that path.
    #[test]
    fn split_of_merged_is_the_stage_two_split_to_the_bit() {
        let mut state = 0x5eed_5911_u64;
        let mut next = crate::test_values::unit_generator(91);
        let (mut taken, mut solved) = (0, 0);
        let bits = |c: &BezierCurve| c.points().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        for case in 0..240 {
            let degree = 1 + case % 9;
            let (p, q) = (
                curve(&mut state, degree),
                curve(&mut state, 1 + (case / 9) % 9),
            );
            let options = case_options(case);
            let problem = PairProblem::new(&p, &q, &options).unwrap();
            let mu = 0.05 + 0.9 * next();
            let Ok(stage_one) = problem.solve_given(mu) else {
                continue;
            };
            solved += 1;
            // The pieces as curves without their matrices: the same bits.
            for (j, piece) in stage_one.pieces().iter().enumerate() {
                let curve = stage_one.piece_curve(j).unwrap();
                assert_eq!(
                    bits(&curve),
                    bits(&BezierCurve::from_matrix(piece).unwrap()),
                    "case {case}"
                );
            }
            if !stage_one.split_of_merged {
                continue;
            }
            taken += 1;
            let merged = BezierCurve::from_matrix(stage_one.merged.as_ref().unwrap()).unwrap();
            let (left, right) = merged.split_unchecked(mu);
            for (piece, split) in stage_one.pieces().iter().zip([&left, &right]) {
                let hat = BezierCurve::from_matrix(piece).unwrap();
                assert_eq!(bits(&hat), bits(split), "case {case}");
            }
            let (_, worst, restrictions) = super::stage_two::check_restrictions(
                merged,
                &stage_one.pieces(),
                &[0.0, mu, 1.0],
                options.accuracy,
            )
            .unwrap();
            assert_eq!(worst, 0.0, "case {case}");
            assert_eq!(bits(&restrictions[0]), bits(&left), "case {case}");
        }
        assert!(
            taken > solved * 3 / 4 && solved > 200,
            "{taken} of {solved}"
        );
    }

    /// `StageOne::into_split_curves` (no validation) gives the curves of the
    /// validated constructors bit for bit where the pieces are `R`'s split,
    /// and nothing elsewhere: random pairs in dimensions 1 to 4, degrees 1
    /// to 9 (P and Q of different degrees too), both metrics, with and
    /// without fixed ends, coordinate scales 1e-3 to 1e4, random `mu`.
    #[test]
    fn split_curves_are_the_checked_ones_to_the_bit() {
        let mut values = crate::test_values::Values(0x5b1_17c0);
        let bits = |c: &BezierCurve| {
            let mut b: Vec<u64> = c.points().iter().map(|v| v.to_bits()).collect();
            b.extend([c.dim() as u64, c.degree() as u64]);
            b
        };
        let (mut split, mut other, mut found_unsplit) = (0, 0, 0);
        for case in 0..600 {
            let dim = 1 + case % 4;
            let scale = [1.0, 1e-3, 10.0, 1e4][(case / 4) % 4];
            let mut random_curve = |degree: usize| {
                let points = (0..(degree + 1) * dim)
                    .map(|_| scale * values.signed())
                    .collect();
                BezierCurve::new(dim, degree, points).unwrap()
            };
            // Every tenth case of degree 14 to 21: some of these take the
            // refined solve (`R` found, the pieces not its split).
            let (p_degree, q_degree) = if case % 10 == 9 {
                (14 + case % 8, 14 + (case / 10) % 8)
            } else {
                (1 + case % 9, 1 + (case / 9) % 9)
            };
            let p = random_curve(p_degree);
            let q = random_curve(q_degree);
            let options = case_options(case);
            let problem = PairProblem::new(&p, &q, &options).unwrap();
            let mu = 0.05 + 0.9 * values.unit();
            let Ok(stage_one) = problem.solve_given(mu) else {
                continue;
            };
            let split_of_merged = stage_one.split_of_merged;
            let checked = (
                stage_one
                    .merged
                    .as_ref()
                    .map(|r| BezierCurve::from_matrix(r).unwrap()),
                stage_one
                    .pieces()
                    .iter()
                    .map(|piece| BezierCurve::from_matrix(piece).unwrap())
                    .collect::<Vec<_>>(),
            );
            match stage_one.into_split_curves() {
                Ok((merged, hats)) => {
                    split += 1;
                    assert!(split_of_merged, "case {case}");
                    assert_eq!(bits(&merged), bits(&checked.0.unwrap()), "case {case}");
                    for (j, hat) in hats.iter().enumerate() {
                        assert_eq!(bits(hat), bits(&checked.1[j]), "case {case}, piece {j}");
                    }
                }
                Err(stage_one) => {
                    other += 1;
                    assert!(
                        !stage_one.split_of_merged || stage_one.merged.is_none(),
                        "case {case}"
                    );
                    found_unsplit += usize::from(stage_one.merged.is_some());
                }
            }
        }
        assert!(
            split > 400 && found_unsplit > 0,
            "{split} split, {other} other ({found_unsplit} with R)"
        );
    }
}

#[cfg(test)]
mod slope_tests {
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// The closed-form slope (envelope theorem) against a central
    /// difference of the metric, both metrics, with and without fix ends.
    #[test]
    fn slope_is_the_derivative_of_the_metric() {
        let mut state = 3;
        for degree in [1, 3, 7, 15] {
            let (p, q) = (curve(&mut state, degree), curve(&mut state, degree));
            for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                for fix_ends in [false, true] {
                    let options = MergeOptions {
                        metric,
                        fix_ends,
                        ..MergeOptions::default()
                    };
                    let problem = PairProblem::new(&p, &q, &options).unwrap();
                    for mu in [0.1, 0.37, 0.5, 0.8] {
                        let h = 1e-5;
                        let at = |mu| problem.solve(mu, StageOneCheck::Trial).unwrap();
                        let difference =
                            (at(mu + h).metric_value - at(mu - h).metric_value) / (2.0 * h);
                        let slope = at(mu).slope.unwrap();
                        assert!(
                            (slope - difference).abs() <= 1e-5 * (1.0 + difference.abs()),
                            "degree {degree} {metric:?} fix ends {fix_ends} mu {mu}: slope {slope} vs {difference}"
                        );
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod reference_tests {
    use super::rows::Problem;
    use super::*;

    use crate::test_values::planar_curve as curve;

    /// The orthogonal stage 1 against the paper's Lagrange-multiplier (KKT)
    /// formulation on the pieces, kept as the reference: same pieces.
    #[test]
    fn orthogonal_stage_one_agrees_with_the_kkt_formulation() {
        let mut state = 9;
        for degree in 1..=10 {
            let (p, q) = (curve(&mut state, degree), curve(&mut state, degree));
            for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                for fix_ends in [false, true] {
                    let options = MergeOptions {
                        metric,
                        fix_ends,
                        p_points: if degree >= 3 {
                            vec![KeepPoint {
                                param: 0.4,
                                max_order: 1,
                            }]
                        } else {
                            Vec::new()
                        },
                        ..MergeOptions::default()
                    };
                    let pair = PairProblem::new(&p, &q, &options).unwrap();
                    for mu in [0.2, 0.5, 0.7] {
                        let ours = pair.solve(mu, StageOneCheck::Full).unwrap();
                        let lengths = [mu, 1.0 - mu];
                        let problem = Problem::new(&pair.pieces, &lengths, fix_ends);
                        let (x, _) =
                            kkt::kkt_solution(&problem, metric, 1.0, StageOneCheck::Full).unwrap();
                        let scale = x.amax().max(1.0);
                        for (j, piece) in ours.pieces().iter().enumerate() {
                            let reference = x.rows(j * (degree + 1), degree + 1);
                            let gap = (piece - reference).amax() / scale;
                            assert!(
                                gap < 1e-9,
                                "degree {degree} {metric:?} fix ends {fix_ends} mu {mu}: gap {gap:e}"
                            );
                        }
                    }
                }
            }
        }
    }
}
