//! Merge of polynomial B-splines (docs/mathematics.md section 6, "Merge of
//! B-splines"): the seed's method carried over to B-splines, as the merge
//! paper's conclusion says it can be ("without significant changes").
//!
//! # The method
//!
//! Curves `C_0..C_{N-1}` (for [`merge_bsplines`] `P` and `Q`), polynomial
//! B-splines of one degree `p` (a lower degree is elevated first, exactly;
//! unclamped knot vectors are clamped first, same shape), and breakpoints
//! `0 = t_0 < t_1 < ... < t_N = 1` (for two curves `t_1 = mu`). The merged
//! curve `R` is the B-spline of degree `p` on `[0, 1]` whose interior knots
//! are those of `C_j` mapped affinely into `(t_j, t_{j+1})` (multiplicities
//! kept), with **no knot at any `t_j`**: one polynomial piece spans each
//! join, the paper's `C^n` there (indeed `C^infinity`). `R` has
//! `sum_j n_j - (N - 1)(p + 1)` poles (`nP + nQ - p - 1` for two curves).
//!
//! The unknowns are `R`'s poles `r`. The piece `C^_j = R|[t_j, t_{j+1}]`,
//! written on `C_j`'s own knots and parameters, has poles `A_j r`: the
//! restriction matrix `A_j` is knot insertion of `t_j` and `t_{j+1}` (to
//! multiplicity `p`), exact and linear in `r`. Stage 1 minimises
//!
//! ```text
//! sum_j (A_j r - c_j)^T W_j (A_j r - c_j)
//! ```
//!
//! (`c_j` the poles of `C_j`, summed over the coordinates) with `W_j = I`
//! for [`MergeMetric::Discrete`] (the sum of squared pole changes) or the
//! Gram matrix of `C_j`'s B-spline basis divided by its domain's length
//! for [`MergeMetric::Integral`] (`int |C^_j - C_j|^2 du / (b_j - a_j)`,
//! each curve in its own parameter, equal weights: for Bezier curves
//! exactly section 3's metric). The Gram matrix is exact: each span's
//! basis is written in Bernstein form (Bezier decomposition of the basis
//! itself) and the Bernstein Gram matrix is used, no quadrature. The
//! constraints are linear in `r`: fix ends (`R`'s first and last pole),
//! keep `C_j` (`A_j r = c_j`), keep points with derivatives
//! (`C^_j^(s)(u_k) = C_j^(s)(u_k)`, `u_k` in `C_j`'s domain). Stage 1 is
//! one KKT system for all coordinates, its rows orthonormalised first.
//!
//! Since the stacked `A_j` have full column rank (a spline is fixed by its
//! restrictions), the metric is positive definite in `r` and the problem
//! has one solution whenever the constraints are consistent. For Bezier
//! curves (one span each) it is section 3's problem with `R`'s control
//! points as the unknowns: the second, independent formulation that the
//! Bezier [`merge`](super::merge) is tested against, so both must agree.
//!
//! # Guarantees and checks
//!
//! * The KKT solve's error estimate (condition times backward error) must
//!   stay below `accuracy`, else `IllConditioned` with the estimate.
//! * Constraints that depend linearly on those before them are checked at
//!   the solution: consistent (accepted), contradictory
//!   (`Inconsistent`, naming the constraint) or, in between,
//!   `IllConditioned`, with the Bezier merge's tolerances.
//! * `R` restricted to every `[t_j, t_{j+1}]` by knot insertion (a second
//!   computation of the pieces) must give back `A_j r` to `accuracy`
//!   relative to the coordinate scale, else `IllConditioned`.
//! * A kept curve is returned bit for bit as its piece (after clamping and
//!   elevation, which are exact).
//! * The optimal `mu` ([`Breakpoints::Optimal`]) is searched as the Bezier
//!   merge searches it: without kept curves and keep points on the metric
//!   and its closed-form slope (envelope theorem with the motion of `R`'s
//!   knots, module `bspline_slope`), the trials solved lean (no condition
//!   estimate), the winner solved with every check; a refused winner
//!   repeats the slope search with every check at every trial, a failed
//!   lean trial hands over to the value search (every trial fully
//!   checked), which also serves kept curves and keep points. The answer
//!   is always a fully checked solve.
//! * The restriction matrices of a pair come from Boehm's insertion of `mu`
//!   on the `p + 1` poles it changes (`O(p^3)`); the split check above
//!   recomputes the pieces from `R` by the library's knot insertion.
//! * The report's `max_deviation` is measured: [`DEVIATION_SAMPLES`]` + 1`
//!   evenly spaced parameters of each input curve, `R` at the mapped
//!   parameter against the input (clamped and elevated: the same curve),
//!   as one difference B-spline on the input's knots (`R` restricted minus
//!   the input, pole by pole), evaluated through its Bezier spans.

use nalgebra::{DMatrix, DVector};

use crate::basis::{KnotSide, basis_derivatives, find_span};
use crate::bezier::{BezierCurve, MAX_DEGREE};
use crate::curve::Curve;
use crate::error::{BezjoinError, Result, check_positive};
use crate::linalg::solve_checked;
use crate::minimize::minimize_with_slope;
use crate::nurbs::NurbsCurve;

use super::bspline_slope::{knot_rates, pair_split};

use super::rows::{
    Dependent, Row, WorstUndecided, classify, extend_orthonormal, normalised, summarise,
};
use super::stage_one::{
    CONSISTENCY_TOLERANCE, DEVIATION_SAMPLES, RANK_TOLERANCE, bernstein_gram_matrix,
};
use super::{
    Breakpoints, ChainMergeOptions, ChainMergeReport, KeepPoint, MU_SEARCH_MAX_STEPS,
    MU_SEARCH_MIN, MU_SEARCH_SAMPLES, MU_SEARCH_SLOPE_SAMPLES, MU_SEARCH_TOLERANCE, MergeMetric,
    MergeOptions, MergeReport, chain_breakpoints, chain_keep_points, extend_into_tail, optimal_mu,
    polygon_breakpoints, polygon_split,
};

/// The result of [`merge_bsplines`].
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineMerge {
    /// The single B-spline `R` on `[0, 1]`: `P`'s interior knots mapped
    /// into `(0, mu)`, `Q`'s into `(mu, 1)`, none at `mu`.
    pub merged: NurbsCurve,
    /// `P^ = R|[0, mu]` on `P`'s own knots and parameters.
    pub p_hat: NurbsCurve,
    /// `Q^ = R|[mu, 1]` on `Q`'s own knots and parameters.
    pub q_hat: NurbsCurve,
    /// Split parameter, metric value, measured deviation and checks.
    pub report: MergeReport,
}

/// The result of [`merge_bspline_chain`].
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineChainMerge {
    /// The single B-spline `R` on `[0, 1]`.
    pub merged: NurbsCurve,
    /// `C^_j = R|[t_j, t_{j+1}]`, each on `C_j`'s own knots and parameters.
    pub pieces: Vec<NurbsCurve>,
    /// Breakpoints, metric value, measured deviation and checks.
    pub report: ChainMergeReport,
}

/// Merge two polynomial B-splines `P` and `Q` into one B-spline `R`, C^p
/// across the join with no knot there (docs/mathematics.md section 6,
/// "Merge of B-splines"; the module documentation states the method).
///
/// Every option of [`merge`](super::merge) applies: both metrics, every
/// split ([`Breakpoints::Optimal`] searches `mu` as there), keep `P` / `Q`,
/// fix ends, keep points (`param` in the curve's own domain, orders up to
/// the working degree) and `degree` (elevates both curves).
///
/// Guarantee: `P^`, `Q^` are `R`'s pieces at `mu`, satisfy the constraints
/// and minimise the metric among all such pairs (checked as the module
/// says). Two Bezier curves (as one-span B-splines) give section 3's answer.
///
/// Errors: a rational curve (InvalidArgument naming `p` or `q`); the
/// errors of [`merge`](super::merge) otherwise, and InvalidArgument for
/// `mu` when an interior knot of `P` or `Q`, mapped, would round onto the
/// join or an end.
pub fn merge_bsplines(
    p: &NurbsCurve,
    q: &NurbsCurve,
    options: &MergeOptions,
) -> Result<BSplineMerge> {
    let problem = pair_problem(p, q, options)?;
    let given = |mu: f64| problem.solve(&[0.0, mu, 1.0]).map(|solved| (mu, solved));
    let (mu, solved) = match &options.split {
        Breakpoints::Given(inner) => {
            let &[mu] = inner.as_slice() else {
                return Err(BezjoinError::LengthMismatch {
                    name: "mu".into(),
                    expected: 1,
                    actual: inner.len(),
                });
            };
            super::check_split(mu)?;
            given(mu)?
        }
        Breakpoints::Uniform => given(0.5)?,
        Breakpoints::PolygonLength => {
            given(polygon_breakpoints(&[p.polygon_length(), q.polygon_length()], &["P", "Q"])?[1])?
        }
        Breakpoints::Optimal => problem.optimal()?,
    };
    let mut pieces = solved.pieces.into_iter();
    let p_hat = pieces.next().expect("two pieces");
    let q_hat = pieces.next().expect("two pieces");
    Ok(BSplineMerge {
        merged: solved.merged,
        p_hat,
        q_hat,
        report: MergeReport {
            mu,
            metric_value: solved.metric_value,
            max_deviation: solved.max_deviation,
            solve_error_estimate: solved.error_estimate,
            split_check_error: solved.split_check_error,
        },
    })
}

/// The metric value of the stage-1 optimum of [`merge_bsplines`] at a given
/// `mu` (the function [`Breakpoints::Optimal`] minimises); `options.split`
/// is ignored.
pub fn merge_bsplines_metric_at(
    p: &NurbsCurve,
    q: &NurbsCurve,
    options: &MergeOptions,
    mu: f64,
) -> Result<f64> {
    super::check_split(mu)?;
    let problem = pair_problem(p, q, options)?;
    Ok(problem
        .stage_one(&[0.0, mu, 1.0], Check::Full)?
        .metric_value)
}

/// The validated problem of a pair merge (names `p`, `q`, `p_points`,
/// `q_points` in errors).
fn pair_problem<'a>(
    p: &'a NurbsCurve,
    q: &'a NurbsCurve,
    options: &'a MergeOptions,
) -> Result<SplineProblem<'a>> {
    SplineProblem::new(
        &[p, q],
        &["p".into(), "q".into()],
        &[options.keep_p, options.keep_q],
        vec![
            ("p_points", options.p_points.iter().enumerate().collect()),
            ("q_points", options.q_points.iter().enumerate().collect()),
        ],
        Settings {
            metric: options.metric,
            fix_ends: options.fix_ends,
            degree: options.degree,
            accuracy: options.accuracy,
        },
    )
}

/// Merge `N >= 2` consecutive polynomial B-splines into one B-spline `R`,
/// `C_j` becoming `R` on `[t_j, t_{j+1}]` with its interior knots mapped
/// there and no knot at any `t_j` (the module documentation states the
/// method). The options are [`merge_chain`](super::merge_chain)'s: keep
/// points name their curve and take `param` in that curve's domain;
/// [`Breakpoints::Optimal`] is refused.
///
/// Errors: a rational curve (InvalidArgument naming `curves[j]`); the
/// errors of [`merge_chain`](super::merge_chain) otherwise.
pub fn merge_bspline_chain(
    curves: &[NurbsCurve],
    options: &ChainMergeOptions,
) -> Result<BSplineChainMerge> {
    let count = curves.len();
    if count < 2 {
        return Err(BezjoinError::invalid(
            "curves",
            format!("{count} curves given, at least 2 are needed"),
        ));
    }
    if !options.keep.is_empty() && options.keep.len() != count {
        return Err(BezjoinError::LengthMismatch {
            name: "keep".into(),
            expected: count,
            actual: options.keep.len(),
        });
    }
    let refs: Vec<&NurbsCurve> = curves.iter().collect();
    let names: Vec<String> = (0..count).map(|j| format!("curves[{j}]")).collect();
    let keep: Vec<bool> = (0..count)
        .map(|j| options.keep.get(j).copied().unwrap_or(false))
        .collect();
    let points = chain_keep_points(options, count)?
        .into_iter()
        .map(|p| ("keep_points", p))
        .collect();
    let problem = SplineProblem::new(
        &refs,
        &names,
        &keep,
        points,
        Settings {
            metric: options.metric,
            fix_ends: options.fix_ends,
            degree: options.degree,
            accuracy: options.accuracy,
        },
    )?;
    let lengths: Vec<f64> = curves.iter().map(NurbsCurve::polygon_length).collect();
    let name_refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let breakpoints = chain_breakpoints(&options.breakpoints, &lengths, &name_refs)?;
    let solved = problem.solve(&breakpoints)?;
    Ok(BSplineChainMerge {
        merged: solved.merged,
        pieces: solved.pieces,
        report: ChainMergeReport {
            breakpoints,
            metric_value: solved.metric_value,
            max_deviation: solved.max_deviation,
            solve_error_estimate: solved.error_estimate,
            split_check_error: solved.split_check_error,
        },
    })
}

/// The options every B-spline merge shares.
struct Settings {
    metric: MergeMetric,
    fix_ends: bool,
    degree: Option<usize>,
    accuracy: f64,
}

/// One input curve at the working degree, clamped, with its constraints.
struct Piece<'a> {
    /// Clamped and elevated: same shape and parameters as `original`.
    curve: NurbsCurve,
    /// `P`, `Q` or `curves[j]`.
    label: String,
    keep: bool,
    /// Keep points with their index in the caller's array and its name.
    points_name: &'static str,
    points: Vec<(usize, &'a KeepPoint)>,
    /// Poles, `n_j x dim`.
    poles: DMatrix<f64>,
    /// `W_j` of the metric; `None` for the identity ([`MergeMetric::Discrete`]).
    weight: Option<DMatrix<f64>>,
}

impl Piece<'_> {
    /// `W_j m`.
    fn weighted<S>(
        &self,
        m: &nalgebra::Matrix<f64, nalgebra::Dyn, nalgebra::Dyn, S>,
    ) -> DMatrix<f64>
    where
        S: nalgebra::Storage<f64, nalgebra::Dyn, nalgebra::Dyn>,
    {
        match &self.weight {
            Some(w) => w * m,
            None => m.clone_owned(),
        }
    }
}

/// Validated curves and settings: what a solve at any breakpoints needs.
struct SplineProblem<'a> {
    pieces: Vec<Piece<'a>>,
    degree: usize,
    dim: usize,
    fix_ends: bool,
    accuracy: f64,
    /// Largest absolute pole coordinate of the inputs.
    scale: f64,
    /// Largest range of one pole coordinate over the inputs: the size the
    /// tolerance of dependent conditions is relative to (unchanged by a
    /// translation, unlike `scale`; as the Bezier merge's
    /// `Problem::extent`).
    extent: f64,
    /// For two pieces, `d tau / d mu` of every knot of `R`
    /// ([`knot_rates`]), for the slope of the metric.
    rates: Option<Vec<f64>>,
}

/// How much a stage-1 solve checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Check {
    /// Every check, the KKT solve's condition estimate included: every
    /// answer a caller receives.
    Full,
    /// A trial of the optimal-`mu` search on slopes: the KKT system is
    /// solved by LU with one refinement step and no condition estimate
    /// (error estimate 0, no refusal for conditioning), and the slope
    /// `d metric / d mu` is computed. The winner is solved again with
    /// `Full`; if that, or any trial, fails, the value search with `Full`
    /// at every trial decides ([`SplineProblem::optimal`]).
    Trial,
}

impl Check {
    /// The KKT solve's condition estimate and the refusal on it.
    fn is_full(self) -> bool {
        self == Check::Full
    }

    /// `d metric / d mu` wanted (when the slope search applies).
    fn wants_slope(self) -> bool {
        self == Check::Trial
    }
}

/// Stage 1 at given breakpoints.
struct StageOne {
    knots: Vec<f64>,
    /// `R`'s poles, `n_R x dim`.
    poles: DMatrix<f64>,
    /// `A_j r` for every piece.
    pieces: Vec<DMatrix<f64>>,
    metric_value: f64,
    error_estimate: f64,
    /// `d metric / d mu` (trials of the slope search only).
    slope: Option<f64>,
}

/// A finished merge.
struct Solved {
    merged: NurbsCurve,
    pieces: Vec<NurbsCurve>,
    metric_value: f64,
    max_deviation: f64,
    error_estimate: f64,
    split_check_error: f64,
}

/// The curve whose poles are the unit vectors of dimension `n` on `knots`:
/// any knot operation on it gives the matrix of that operation on the poles
/// of every curve with these knots.
fn identity_curve(degree: usize, knots: &[f64]) -> Result<NurbsCurve> {
    let n = knots.len() - degree - 1;
    NurbsCurve::new(
        n,
        degree,
        DMatrix::<f64>::identity(n, n).as_slice().to_vec(),
        None,
        knots.to_vec(),
    )
}

/// The poles of a curve as an `n x dim` matrix.
fn pole_matrix(c: &NurbsCurve) -> DMatrix<f64> {
    DMatrix::from_row_slice(c.point_count(), c.dim(), c.points())
}

/// `W_j` of [`MergeMetric::Integral`]: `int N_i N_k du / (b - a)` over the
/// clamped curve's domain, exact (Bernstein form of every span).
fn normalised_gram(curve: &NurbsCurve) -> Result<DMatrix<f64>> {
    let p = curve.degree();
    let n = curve.point_count();
    let (a, b) = curve.domain();
    let bernstein = bernstein_gram_matrix(p);
    let mut gram = DMatrix::zeros(n, n);
    for span in identity_curve(p, curve.knots())?.bezier_spans() {
        let (s0, s1) = span.domain();
        // Row i of the span's poles is Bernstein coefficient i of every
        // basis function: S (p+1 x n).
        let s = pole_matrix(&span);
        gram += (s.transpose() * &bernstein * &s) * ((s1 - s0) / (b - a));
    }
    Ok(gram)
}

/// Most poles (after clamping and elevation, all curves together) a merge
/// of B-splines takes: as many as two Bezier curves of degree
/// [`MAX_DEGREE`]. Its systems are dense over all poles, so a larger
/// problem would ask for memory by the square of the count (two curves of
/// 1e5 poles: an 80 GB Gram matrix, an abort of the host) and time by the
/// cube (measured: 2 x 1000 poles 2.6 s, 2 x 3000 poles 66 s and 1.5 GB).
pub const MAX_MERGE_POLES: usize = 2 * (MAX_DEGREE + 1);

impl<'a> SplineProblem<'a> {
    /// Validates the curves (polynomial, one dimension), the keep points
    /// and the settings; clamps and elevates.
    fn new(
        curves: &[&'a NurbsCurve],
        names: &[String],
        keep: &[bool],
        points: Vec<(&'static str, Vec<(usize, &'a KeepPoint)>)>,
        settings: Settings,
    ) -> Result<Self> {
        check_positive("accuracy", settings.accuracy)?;
        let dim = curves[0].dim();
        for (j, c) in curves.iter().enumerate() {
            if c.dim() != dim {
                return Err(BezjoinError::DimensionMismatch {
                    name: names[j].clone(),
                    expected: dim,
                    actual: c.dim(),
                });
            }
            if c.is_rational() {
                return Err(BezjoinError::invalid(
                    names[j].clone(),
                    "the curve is rational (its weights differ): a merge of B-splines takes \
                     polynomial B-splines, since R restricted to a piece is polynomial",
                ));
            }
        }
        let highest = curves.iter().map(|c| c.degree()).max().unwrap_or(0);
        let degree = super::checked_working_degree(highest, settings.degree)?;
        let mut pieces = Vec::with_capacity(curves.len());
        let mut total_poles = 0usize;
        for (j, ((c, (points_name, points)), &keep)) in
            curves.iter().zip(points).zip(keep).enumerate()
        {
            for &(k, kp) in &points {
                c.check_parameter(&format!("{points_name}[{k}].param"), kp.param)?;
                if kp.max_order > degree {
                    return Err(BezjoinError::OrderAboveDegree {
                        name: format!("{points_name}[{k}].max_order"),
                        order: kp.max_order,
                        degree,
                        curve: names[j].clone(),
                    });
                }
            }
            let curve = c.clamped().elevate_degree(degree)?;
            total_poles += curve.point_count();
            if total_poles > MAX_MERGE_POLES {
                return Err(BezjoinError::invalid(
                    names[j].clone(),
                    format!(
                        "the curves to merge have more than {MAX_MERGE_POLES} poles at degree \
                         {degree} ({total_poles} up to this one), as many as two Bezier curves of \
                         the largest degree {MAX_DEGREE}: the merge solves dense systems over all \
                         poles (memory grows with their square, time with their cube)"
                    ),
                ));
            }
            let weight = match settings.metric {
                MergeMetric::Discrete => None,
                MergeMetric::Integral => Some(normalised_gram(&curve)?),
            };
            pieces.push(Piece {
                poles: pole_matrix(&curve),
                curve,
                label: match names[j].as_str() {
                    "p" => "P".into(),
                    "q" => "Q".into(),
                    other => other.into(),
                },
                keep,
                points_name,
                points,
                weight,
            });
        }
        let scale = pieces
            .iter()
            .map(|p| p.poles.amax())
            .fold(f64::MIN_POSITIVE, f64::max);
        let extent = super::rows::coordinate_extent(
            pieces.iter().map(|p| (p.poles.as_slice(), p.poles.nrows())),
            dim,
        );
        let rates = match pieces.as_slice() {
            [first, second] => Some(knot_rates(degree, &first.curve, &second.curve)),
            _ => None,
        };
        Ok(Self {
            pieces,
            degree,
            dim,
            fix_ends: settings.fix_ends,
            accuracy: settings.accuracy,
            scale,
            extent,
            rates,
        })
    }

    /// Whether [`Breakpoints::Optimal`] searches on slopes: two pieces and
    /// constraint rows that do not depend on `mu` (no kept curve, no keep
    /// points), so that the envelope theorem gives the slope
    /// (module `bspline_slope`).
    fn slope_search_applies(&self) -> bool {
        self.rates.is_some() && self.pieces.iter().all(|p| !p.keep && p.points.is_empty())
    }

    /// The optimal `mu` and the fully checked merge there, the Bezier
    /// merge's search carried over (`PairProblem::optimal_mu`). Where the
    /// slope search applies: [`minimize_with_slope`] on lean trials
    /// ([`Check::Trial`]) over `[MU_SEARCH_MIN, 1 - MU_SEARCH_MIN]`,
    /// [`MU_SEARCH_SLOPE_SAMPLES`] plus one sample per pole of `R` beyond
    /// the first (for Bezier inputs the Bezier search's count), at most
    /// [`MU_SEARCH_SAMPLES`] + 1, then the winner solved with every check.
    /// When that check refuses the winner or a lean trial fails, and
    /// always where the slope search does not apply: the value search
    /// ([`optimal_mu`], every trial fully checked, refused trials counting
    /// as infinitely bad), whose answer is then exactly the one before the
    /// slope search existed. (The slope search with every check at every
    /// trial, the Bezier merge's fallback, was measured: at degree 31,
    /// where the KKT estimate refuses the metric's own minimum, it needs
    /// three times the trials of the value search.)
    fn optimal(&self) -> Result<(f64, Solved)> {
        // (Nested, not a let chain: the crate's rust-version is 1.85.)
        if self.slope_search_applies() {
            if let Ok(mu) = self.optimal_mu_on_slopes() {
                match self.solve(&[0.0, mu, 1.0]) {
                    Err(BezjoinError::IllConditioned { .. }) => {}
                    solved => return Ok((mu, solved?)),
                }
            }
        }
        let mu = self.optimal_mu_on_values()?;
        Ok((mu, self.solve(&[0.0, mu, 1.0])?))
    }

    /// The slope search of [`Self::optimal`] on lean trials; the first
    /// failed trial's error when any failed (the value search takes over).
    fn optimal_mu_on_slopes(&self) -> Result<f64> {
        let poles = self.merged_pole_count();
        let samples = (MU_SEARCH_SLOPE_SAMPLES + poles - 1).min(MU_SEARCH_SAMPLES + 1);
        let mut first_error = None;
        let minimum = minimize_with_slope(
            |mu| match self.stage_one(&[0.0, mu, 1.0], Check::Trial) {
                Ok(StageOne {
                    metric_value,
                    slope: Some(slope),
                    ..
                }) => Some((metric_value, slope)),
                Ok(_) => None,
                Err(e) => {
                    first_error.get_or_insert(e);
                    None
                }
            },
            MU_SEARCH_MIN,
            1.0 - MU_SEARCH_MIN,
            samples,
            MU_SEARCH_TOLERANCE,
            MU_SEARCH_MAX_STEPS,
        );
        let no_value = || BezjoinError::NonFiniteScalar {
            name: "merge metric at every sampled mu".into(),
            value: f64::INFINITY,
        };
        match (minimum, first_error) {
            (_, Some(e)) => Err(e),
            (Some(m), None) => Ok(extend_into_tail(m, samples, self.polygon_mu(), |mu| {
                self.stage_one(&[0.0, mu, 1.0], Check::Trial)
                    .map_or(f64::INFINITY, |s| s.metric_value)
            })
            .x),
            (None, None) => Err(no_value()),
        }
    }

    /// The value search: every trial fully checked.
    fn optimal_mu_on_values(&self) -> Result<f64> {
        optimal_mu(self.polygon_mu(), |mu| {
            self.stage_one(&[0.0, mu, 1.0], Check::Full)
                .map(|s| s.metric_value)
        })
    }

    /// The split proportional to the two curves' control-polygon lengths:
    /// where the tail of the optimal `mu`'s search may reach
    /// ([`extend_into_tail`]).
    fn polygon_mu(&self) -> f64 {
        polygon_split(
            self.pieces[0].curve.polygon_length(),
            self.pieces[1].curve.polygon_length(),
        )
    }

    /// The number of poles of `R`: `sum_j n_j - (N - 1)(p + 1)`.
    fn merged_pole_count(&self) -> usize {
        let total: usize = self.pieces.iter().map(|p| p.curve.point_count()).sum();
        total - (self.pieces.len() - 1) * (self.degree + 1)
    }

    /// `R`'s knot vector for the breakpoints: every piece's interior knots
    /// mapped into its interval, none at a breakpoint.
    fn merged_knots(&self, breakpoints: &[f64]) -> Result<Vec<f64>> {
        let p = self.degree;
        let mut knots = vec![0.0; p + 1];
        for (j, piece) in self.pieces.iter().enumerate() {
            let (t0, t1) = (breakpoints[j], breakpoints[j + 1]);
            let (a, b) = piece.curve.domain();
            let n = piece.curve.point_count();
            for &k in &piece.curve.knots()[p + 1..n] {
                let mapped = t0 + (t1 - t0) * ((k - a) / (b - a));
                if !(mapped > t0 && mapped < t1) {
                    return Err(BezjoinError::invalid(
                        if self.pieces.len() == 2 {
                            "mu"
                        } else {
                            "breakpoints"
                        },
                        format!(
                            "the interior knot {k} of {} maps to {mapped}, which rounds onto \
                             the end of its interval [{t0}, {t1}] of R",
                            piece.label
                        ),
                    ));
                }
                knots.push(mapped);
            }
        }
        knots.extend(std::iter::repeat_n(1.0, p + 1));
        Ok(knots)
    }

    /// The constraint rows on `R`'s poles (unit length, unnormalised
    /// right-hand sides scaled alike), in the order fix ends, kept curves,
    /// keep points.
    fn rows(&self, restrictions: &[DMatrix<f64>], unknowns: usize) -> Result<Vec<Row>> {
        let d = self.dim;
        let mut rows = Vec::new();
        let last_piece = self.pieces.len() - 1;
        if self.fix_ends {
            let first = &self.pieces[0];
            let last = &self.pieces[last_piece];
            let mut row = DVector::zeros(unknowns);
            row[0] = 1.0;
            rows.push(Row {
                coefficients: row,
                rhs: first.poles.row(0).transpose(),
                label: format!("fix ends (first point of {})", first.label),
            });
            let mut row = DVector::zeros(unknowns);
            row[unknowns - 1] = 1.0;
            rows.push(Row {
                coefficients: row,
                rhs: last.poles.row(last.poles.nrows() - 1).transpose(),
                label: format!("fix ends (last point of {})", last.label),
            });
        }
        for (piece, a) in self.pieces.iter().zip(restrictions) {
            if piece.keep {
                for i in 0..a.nrows() {
                    rows.push(normalised(Row {
                        coefficients: a.row(i).transpose(),
                        rhs: piece.poles.row(i).transpose(),
                        label: format!("keep {} (pole {i})", piece.label),
                    }));
                }
            }
        }
        let p = self.degree;
        for (piece, a) in self.pieces.iter().zip(restrictions) {
            let knots = piece.curve.knots();
            for &(k, kp) in &piece.points {
                let span = find_span(knots, p, kp.param, KnotSide::Right);
                let basis = basis_derivatives(knots, p, span, kp.param, kp.max_order);
                let values = piece.curve.eval_derivatives(kp.param, kp.max_order);
                for s in 0..=kp.max_order {
                    let mut coefficients = DVector::zeros(unknowns);
                    for jb in 0..=p {
                        let weight = basis[(s, jb)];
                        if weight != 0.0 {
                            coefficients.axpy(weight, &a.row(span - p + jb).transpose(), 1.0);
                        }
                    }
                    rows.push(normalised(Row {
                        coefficients,
                        rhs: DVector::from_column_slice(&values[s * d..(s + 1) * d]),
                        label: format!(
                            "{}[{k}] (derivative {s} of {} at {})",
                            piece.points_name, piece.label, kp.param
                        ),
                    }));
                }
            }
        }
        Ok(rows)
    }

    /// Stage 1: `R`'s poles minimising the metric under the constraints,
    /// checked.
    fn stage_one(&self, breakpoints: &[f64], check: Check) -> Result<StageOne> {
        let p = self.degree;
        let d = self.dim;
        let knots = self.merged_knots(breakpoints)?;
        let unknowns = knots.len() - p - 1;
        // The restriction matrices A_j: for two pieces from the local
        // split block (Boehm's insertion of mu, module `bspline_slope`),
        // for chains by knot insertion on the curve whose poles are the
        // unit vectors.
        let split = if self.pieces.len() == 2 {
            let span = self.pieces[0].poles.nrows() - 1;
            let rates = match check.wants_slope() && self.slope_search_applies() {
                true => self.rates.as_deref(),
                false => None,
            };
            Some(pair_split(p, &knots, rates, breakpoints[1], span))
        } else {
            None
        };
        // Each A_j as (first column, its columns from there on): A_j is
        // zero outside the poles of R that its interval sees.
        let compact: Vec<(usize, DMatrix<f64>)> = match &split {
            Some(split) => split.restrictions(p, unknowns).into(),
            None => {
                let identity = identity_curve(p, &knots)?;
                let mut restrictions = Vec::with_capacity(self.pieces.len());
                for j in 0..self.pieces.len() {
                    let segment = identity.segment(breakpoints[j], breakpoints[j + 1])?;
                    let a = pole_matrix(&segment);
                    let (first, width) = nonzero_columns(&a);
                    restrictions.push((first, a.columns(first, width).into_owned()));
                }
                restrictions
            }
        };
        // The full-width A_j, which only the rows of kept curves and keep
        // points read.
        let restrictions: Vec<DMatrix<f64>> =
            if self.pieces.iter().any(|p| p.keep || !p.points.is_empty()) {
                compact
                    .iter()
                    .map(|(first, a)| {
                        let mut full = DMatrix::zeros(a.nrows(), unknowns);
                        full.columns_mut(*first, a.ncols()).copy_from(a);
                        full
                    })
                    .collect()
            } else {
                Vec::new()
            };
        let mut hessian = DMatrix::zeros(unknowns, unknowns);
        let mut gradient = DMatrix::zeros(unknowns, d);
        for (piece, (first, a)) in self.pieces.iter().zip(&compact) {
            debug_assert_eq!(a.nrows(), piece.poles.nrows());
            let (first, width) = (*first, a.ncols());
            let wa = piece.weighted(a);
            let mut block = hessian.view_mut((first, first), (width, width));
            block += a.transpose() * &wa;
            let mut rows = gradient.rows_mut(first, width);
            rows += wa.transpose() * &piece.poles;
        }
        // Entries of order one for the solve (the solution is unchanged).
        let norm = hessian.amax();
        hessian /= norm;
        gradient /= norm;

        let (poles, estimate) = if check == Check::Trial && self.slope_search_applies() {
            (self.lean_poles(&hessian, &gradient)?, 0.0)
        } else {
            // Orthonormal basis of the constraint rows (two Gram-Schmidt
            // passes); a row with a remainder at the rounding level depends on
            // those before it and is checked at the solution instead.
            let rank_tolerance = RANK_TOLERANCE * (unknowns as f64).sqrt();
            let mut basis: Vec<(DVector<f64>, DVector<f64>)> = Vec::new();
            let rows = self.rows(&restrictions, unknowns)?;
            let (kept, dependent) = extend_orthonormal(&mut basis, &rows, rank_tolerance, unknowns);
            let independent: Vec<&str> = kept.iter().map(|r| r.label.as_str()).collect();
            let size = unknowns + basis.len();
            let mut kkt = DMatrix::zeros(size, size);
            let mut rhs = DMatrix::zeros(size, d);
            kkt.view_mut((0, 0), (unknowns, unknowns))
                .copy_from(&hessian);
            rhs.rows_mut(0, unknowns).copy_from(&gradient);
            for (k, (coefficients, row_rhs)) in basis.iter().enumerate() {
                for i in 0..unknowns {
                    kkt[(unknowns + k, i)] = coefficients[i];
                    kkt[(i, unknowns + k)] = coefficients[i];
                }
                rhs.row_mut(unknowns + k).copy_from(&row_rhs.transpose());
            }
            let what = "the B-spline merge KKT system";
            let (solution, estimate) = if check.is_full() {
                let solution = solve_checked(&kkt, &rhs, what)?;
                let estimate = solution.error_estimate();
                (Some(solution), estimate)
            } else {
                (None, 0.0)
            };
            let poles = match &solution {
                Some(solution) => solution.x.rows(0, unknowns).into_owned(),
                None => solve_lean(&kkt, &rhs, what)?.rows(0, unknowns).into_owned(),
            };

            let result_scale = poles.amax().max(self.scale);
            let tolerance = CONSISTENCY_TOLERANCE.max(self.accuracy) * self.extent;
            let root = (unknowns as f64).sqrt();
            let explained = root * (estimate + unknowns as f64 * f64::EPSILON) * result_scale;
            let mut undecided = WorstUndecided::default();
            for row in &dependent {
                let residual = (poles.transpose() * &row.coefficients - &row.rhs).amax();
                match classify(residual, tolerance, explained) {
                    Dependent::Contradictory => {
                        return Err(BezjoinError::Inconsistent {
                            reason: format!(
                                "{} contradicts the constraints before it{} (it depends linearly \
                                 on them but would need a change of {residual:e}, coordinate \
                                 scale {result_scale:e}); R has {unknowns} poles per coordinate \
                                 (knots of degree {p}), {} independent conditions were given",
                                row.label,
                                if independent.is_empty() {
                                    String::new()
                                } else {
                                    format!(" ({})", summarise(&independent))
                                },
                                basis.len()
                            ),
                        });
                    }
                    Dependent::Undecided => undecided.note(residual, &row.label),
                    Dependent::Consistent => {}
                }
            }
            if let Some(solution) = &solution
                && estimate > self.accuracy
            {
                return Err(BezjoinError::IllConditioned {
                    what: format!(
                        "B-spline merge stage 1 (KKT system of size {size}, condition estimate {:e})",
                        solution.condition
                    ),
                    estimate,
                    limit: self.accuracy,
                });
            }
            undecided.into_result(result_scale, self.accuracy)?;
            (poles, estimate)
        };

        let mut metric_value = 0.0;
        let mut pieces = Vec::with_capacity(self.pieces.len());
        let mut weighted_changes = Vec::with_capacity(self.pieces.len());
        for (piece, (first, a)) in self.pieces.iter().zip(&compact) {
            let hat = a * poles.rows(*first, a.ncols());
            let change = &hat - &piece.poles;
            let weighted = piece.weighted(&change);
            metric_value += change.dot(&weighted);
            weighted_changes.push(weighted);
            pieces.push(hat);
        }
        // The envelope theorem's slope (module `bspline_slope`):
        // 2 sum_j (A_j r - c_j)^T W_j (dA_j/dmu) r.
        let slope = match &split {
            Some(split) if check.wants_slope() && self.slope_search_applies() => {
                let (left, right) = split.piece_rates(p, &poles);
                Some(2.0 * (weighted_changes[0].dot(&left) + weighted_changes[1].dot(&right)))
            }
            _ => None,
        };
        Ok(StageOne {
            knots,
            poles,
            pieces,
            metric_value,
            error_estimate: estimate,
            slope,
        })
    }

    /// The poles of a lean trial ([`Check::Trial`], only where the slope
    /// search applies): the only constraints are fix ends, unit rows on
    /// `R`'s first and last pole, so those poles are set and eliminated;
    /// the Hessian of the others is symmetric positive definite (the
    /// stacked `A_j` have full column rank), solved by Cholesky with one
    /// refinement step. The same minimiser as the KKT system of
    /// [`Check::Full`]; `Singular` when the factorisation fails or the
    /// solution is not finite (the trial fails, the value search decides).
    fn lean_poles(&self, hessian: &DMatrix<f64>, gradient: &DMatrix<f64>) -> Result<DMatrix<f64>> {
        let n = hessian.nrows();
        let mut poles = DMatrix::zeros(n, self.dim);
        let (first, count) = if self.fix_ends {
            let last = &self.pieces[self.pieces.len() - 1].poles;
            poles.row_mut(0).copy_from(&self.pieces[0].poles.row(0));
            poles.row_mut(n - 1).copy_from(&last.row(last.nrows() - 1));
            (1, n.saturating_sub(2))
        } else {
            (0, n)
        };
        if count == 0 {
            return Ok(poles);
        }
        let h = hessian.view((first, first), (count, count)).into_owned();
        let mut rhs = gradient.rows(first, count).into_owned();
        if self.fix_ends {
            rhs -= hessian.view((first, 0), (count, 1)) * poles.row(0);
            rhs -= hessian.view((first, n - 1), (count, 1)) * poles.row(n - 1);
        }
        let singular = || BezjoinError::Singular {
            what: "the B-spline merge normal equations (lean trial)".into(),
        };
        let factor = h.clone().cholesky().ok_or_else(singular)?;
        let mut x = factor.solve(&rhs);
        let step = factor.solve(&(&rhs - &h * &x));
        if step.iter().all(|v| v.is_finite()) {
            x += step;
        }
        if x.iter().any(|v| !v.is_finite()) {
            return Err(singular());
        }
        poles.rows_mut(first, count).copy_from(&x);
        Ok(poles)
    }

    /// Stage 1, then `R` and its pieces as curves, the split check and the
    /// measured deviation.
    fn solve(&self, breakpoints: &[f64]) -> Result<Solved> {
        let one = self.stage_one(breakpoints, Check::Full)?;
        let (p, d) = (self.degree, self.dim);
        let merged = NurbsCurve::new(d, p, row_major(&one.poles), None, one.knots.clone())?;
        let result_scale = one.poles.amax().max(self.scale);
        let mut split_check_error = 0.0f64;
        let mut pieces = Vec::with_capacity(self.pieces.len());
        let mut halves = Vec::with_capacity(self.pieces.len());
        for (j, (piece, hat)) in self.pieces.iter().zip(&one.pieces).enumerate() {
            let restricted = pole_matrix(&merged.segment(breakpoints[j], breakpoints[j + 1])?);
            let difference = (&restricted - hat).amax() / result_scale;
            split_check_error = split_check_error.max(difference);
            // Half of (R restricted) - C_j, pole by pole (halved exactly,
            // so that poles near the top of the f64 range do not overflow).
            halves.push(restricted * 0.5 - pole_matrix(&piece.curve) * 0.5);
            pieces.push(if piece.keep {
                piece.curve.clone()
            } else {
                NurbsCurve::new(d, p, row_major(hat), None, piece.curve.knots().to_vec())?
            });
        }
        if split_check_error > self.accuracy || split_check_error.is_nan() {
            return Err(BezjoinError::IllConditioned {
                what: "B-spline merge (R restricted to the pieces' intervals against the \
                       stage-1 pieces)"
                    .into(),
                estimate: split_check_error,
                limit: self.accuracy,
            });
        }
        // R(t_j + h_j f) - C_j(a + (b - a) f) is one B-spline on C_j's
        // knots (R restricted, written on the affine image of C_j's knots
        // by knot insertion, minus C_j, pole by pole): evaluated once per
        // sample instead of R and C_j separately, the same sampled
        // quantity up to rounding (tests/merge_bspline.rs compares it with
        // the two-evaluation form). Sampled span by span (each span once
        // converted to Bezier form): the samples increase, so the span
        // cursor only moves on.
        let mut max_deviation = 0.0f64;
        let mut value = vec![0.0; d];
        for (piece, half) in self.pieces.iter().zip(&halves) {
            let (a, b) = piece.curve.domain();
            let knots = piece.curve.knots().to_vec();
            let difference = NurbsCurve::new(d, p, row_major(half), None, knots)?;
            let mut spans = SpanWalker::new(&difference)?;
            for s in 0..=DEVIATION_SAMPLES {
                let f = s as f64 / DEVIATION_SAMPLES as f64;
                let u = if s == DEVIATION_SAMPLES {
                    b
                } else {
                    a + (b - a) * f
                };
                spans.eval_into(u, &mut value);
                max_deviation = max_deviation.max(crate::bezier::norm(&value));
            }
        }
        let max_deviation = 2.0 * max_deviation;
        Ok(Solved {
            merged,
            pieces,
            metric_value: one.metric_value,
            max_deviation,
            error_estimate: one.error_estimate,
            split_check_error,
        })
    }
}

/// The first column of `a` with a non-zero entry and the number of columns
/// up to its last one (`(0, 0)` for a zero matrix).
fn nonzero_columns(a: &DMatrix<f64>) -> (usize, usize) {
    let used = |c: &usize| a.column(*c).iter().any(|&v| v != 0.0);
    let Some(first) = (0..a.ncols()).find(used) else {
        return (0, 0);
    };
    let last = (0..a.ncols()).rev().find(used).expect("a used column");
    (first, last + 1 - first)
}

/// The KKT solve of a trial ([`Check::Trial`]): LU with one step of
/// iterative refinement, no condition estimate; `Singular` when a pivot
/// vanishes or the solution is not finite.
fn solve_lean(kkt: &DMatrix<f64>, rhs: &DMatrix<f64>, what: &str) -> Result<DMatrix<f64>> {
    let singular = || BezjoinError::Singular { what: what.into() };
    let lu = kkt.clone().lu();
    let mut x = lu.solve(rhs).ok_or_else(singular)?;
    if let Some(step) = lu.solve(&(rhs - kkt * &x))
        && step.iter().all(|v| v.is_finite())
    {
        x += step;
    }
    if x.iter().any(|v| !v.is_finite()) {
        return Err(singular());
    }
    Ok(x)
}

/// Evaluation of a polynomial B-spline at increasing parameters through
/// its Bezier spans (converted once), the span found by walking forward.
struct SpanWalker {
    /// Span `k` covers `[breaks[k], breaks[k + 1]]`.
    breaks: Vec<f64>,
    spans: Vec<BezierCurve>,
    cursor: usize,
}

impl SpanWalker {
    fn new(curve: &NurbsCurve) -> Result<Self> {
        let pieces = curve.bezier_spans();
        let mut breaks = Vec::with_capacity(pieces.len() + 1);
        let mut spans = Vec::with_capacity(pieces.len());
        for piece in &pieces {
            let (s0, s1) = piece.domain();
            if breaks.is_empty() {
                breaks.push(s0);
            }
            breaks.push(s1);
            spans.push(BezierCurve::new(
                piece.dim(),
                piece.degree(),
                piece.points().to_vec(),
            )?);
        }
        Ok(Self {
            breaks,
            spans,
            cursor: 0,
        })
    }

    /// The point at `u` (not below the previous call's `u`).
    fn eval_into(&mut self, u: f64, out: &mut [f64]) {
        while self.cursor + 1 < self.spans.len() && u > self.breaks[self.cursor + 1] {
            self.cursor += 1;
        }
        let (s0, s1) = (self.breaks[self.cursor], self.breaks[self.cursor + 1]);
        self.spans[self.cursor].eval_into(((u - s0) / (s1 - s0)).clamp(0.0, 1.0), out);
    }
}

/// The rows of `m` one after the other.
fn row_major(m: &DMatrix<f64>) -> Vec<f64> {
    m.transpose().as_slice().to_vec()
}

/// The result of [`merge_curves`]: Bezier curves when both inputs were
/// Bezier curves, B-splines otherwise.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveMerge {
    /// The single curve `R`.
    pub merged: Curve,
    /// `P^`, the piece of `R` on `[0, mu]` in `P`'s parameters.
    pub p_hat: Curve,
    /// `Q^`, the piece of `R` on `[mu, 1]` in `Q`'s parameters.
    pub q_hat: Curve,
    /// Split parameter, metric value, measured deviation and checks.
    pub report: MergeReport,
}

/// The result of [`merge_curve_chain`].
#[derive(Debug, Clone, PartialEq)]
pub struct CurveChainMerge {
    /// The single curve `R`.
    pub merged: Curve,
    /// `C^_j`, the piece of `R` on `[t_j, t_{j+1}]` in `C_j`'s parameters.
    pub pieces: Vec<Curve>,
    /// Breakpoints, metric value, measured deviation and checks.
    pub report: ChainMergeReport,
}

/// Merge any two curves: two Bezier curves by [`merge`](super::merge)
/// (section 3, a Bezier `R`), anything else by [`merge_bsplines`] (Bezier
/// inputs taken as one-span B-splines; a rational input is refused).
pub fn merge_curves(p: &Curve, q: &Curve, options: &MergeOptions) -> Result<CurveMerge> {
    if let (Curve::Bezier(p), Curve::Bezier(q)) = (p, q) {
        let m = super::merge(p, q, options)?;
        return Ok(CurveMerge {
            merged: m.merged.into(),
            p_hat: m.p_hat.into(),
            q_hat: m.q_hat.into(),
            report: m.report,
        });
    }
    let m = merge_bsplines(&p.to_nurbs(), &q.to_nurbs(), options)?;
    Ok(CurveMerge {
        merged: m.merged.into(),
        p_hat: m.p_hat.into(),
        q_hat: m.q_hat.into(),
        report: m.report,
    })
}

/// Merge a chain of any curves: all Bezier by
/// [`merge_chain`](super::merge_chain), otherwise by
/// [`merge_bspline_chain`].
pub fn merge_curve_chain(curves: &[Curve], options: &ChainMergeOptions) -> Result<CurveChainMerge> {
    let beziers: Option<Vec<BezierCurve>> = curves
        .iter()
        .map(|c| match c {
            Curve::Bezier(b) => Some(b.clone()),
            Curve::Nurbs(_) => None,
        })
        .collect();
    if let Some(beziers) = beziers {
        let m = super::merge_chain(&beziers, options)?;
        return Ok(CurveChainMerge {
            merged: m.merged.into(),
            pieces: m.pieces.into_iter().map(Curve::from).collect(),
            report: m.report,
        });
    }
    let nurbs: Vec<NurbsCurve> = curves.iter().map(Curve::to_nurbs).collect();
    let m = merge_bspline_chain(&nurbs, options)?;
    Ok(CurveChainMerge {
        merged: m.merged.into(),
        pieces: m.pieces.into_iter().map(Curve::from).collect(),
        report: m.report,
    })
}

#[cfg(test)]
mod slope_tests {
    use super::*;

    /// Uniform in `[0, 1)` (LCG, deterministic).
    fn uniform(state: &mut u64) -> f64 {
        *state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (*state >> 11) as f64 / (1u64 << 53) as f64
    }

    /// A clamped 2D B-spline of degree `p` with `spans` spans of random
    /// lengths on a random domain, an interior knot doubled now and then.
    fn bspline(state: &mut u64, p: usize, spans: usize) -> NurbsCurve {
        let a = uniform(state) * 4.0 - 2.0;
        let mut knots = vec![a; p + 1];
        let mut x = a;
        for _ in 1..spans {
            x += 0.2 + uniform(state);
            let m = if p > 1 && uniform(state) < 0.3 { 2 } else { 1 };
            knots.extend(std::iter::repeat_n(x, m));
        }
        x += 0.2 + uniform(state);
        knots.extend(std::iter::repeat_n(x, p + 1));
        let n = knots.len() - p - 1;
        let poles = (0..2 * n).map(|_| uniform(state) * 4.0 - 2.0).collect();
        NurbsCurve::new(2, p, poles, None, knots).unwrap()
    }

    /// The closed-form slope (envelope theorem with the knot motion,
    /// module `bspline_slope`) against a central difference of the metric:
    /// one-span and multi-span inputs of different span counts, both
    /// metrics, with and without fix ends.
    #[test]
    fn slope_is_the_derivative_of_the_metric() {
        let mut state = 11;
        for degree in [1, 2, 3, 7, 15] {
            for (p_spans, q_spans) in [(1, 1), (3, 1), (2, 4)] {
                let (p, q) = (
                    bspline(&mut state, degree, p_spans),
                    bspline(&mut state, degree, q_spans),
                );
                for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                    for fix_ends in [false, true] {
                        let options = MergeOptions {
                            metric,
                            fix_ends,
                            ..MergeOptions::default()
                        };
                        let problem = pair_problem(&p, &q, &options).unwrap();
                        assert!(problem.slope_search_applies());
                        let at =
                            |mu: f64| problem.stage_one(&[0.0, mu, 1.0], Check::Trial).unwrap();
                        for mu in [0.1, 0.37, 0.5, 0.8] {
                            let h = 1e-5;
                            let difference =
                                (at(mu + h).metric_value - at(mu - h).metric_value) / (2.0 * h);
                            let slope = at(mu).slope.unwrap();
                            assert!(
                                (slope - difference).abs() <= 1e-5 * (1.0 + difference.abs()),
                                "degree {degree} spans {p_spans}/{q_spans} {metric:?} fix ends \
                                 {fix_ends} mu {mu}: slope {slope} vs {difference}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// The restriction matrices from the local split block against knot
    /// insertion on the curve whose poles are the unit vectors (the
    /// library's `segment`, an independent computation).
    #[test]
    fn split_block_restrictions_are_the_segments() {
        let mut state = 7;
        for degree in [1, 2, 3, 6, 11] {
            for (p_spans, q_spans) in [(1, 1), (4, 2), (1, 3)] {
                let (p, q) = (
                    bspline(&mut state, degree, p_spans),
                    bspline(&mut state, degree, q_spans),
                );
                let options = MergeOptions::default();
                let problem = pair_problem(&p, &q, &options).unwrap();
                for mu in [0.05, 0.3, 0.5, 0.93] {
                    let breakpoints = [0.0, mu, 1.0];
                    let knots = problem.merged_knots(&breakpoints).unwrap();
                    let unknowns = knots.len() - degree - 1;
                    let span = problem.pieces[0].poles.nrows() - 1;
                    let split = pair_split(degree, &knots, None, mu, span);
                    let identity = identity_curve(degree, &knots).unwrap();
                    for (j, (first, compact)) in
                        split.restrictions(degree, unknowns).iter().enumerate()
                    {
                        let mut a = DMatrix::zeros(compact.nrows(), unknowns);
                        a.columns_mut(*first, compact.ncols()).copy_from(compact);
                        let segment = identity.segment(breakpoints[j], breakpoints[j + 1]);
                        let reference = pole_matrix(&segment.unwrap());
                        assert_eq!(a.shape(), reference.shape());
                        let gap = (a - &reference).amax();
                        assert!(
                            gap <= 1e-13,
                            "degree {degree} spans {p_spans}/{q_spans} mu {mu} piece {j}: {gap:e}"
                        );
                    }
                }
            }
        }
    }

    /// The lean search can pick a `mu` whose full check fails; the merge
    /// must then return the value search's answer (every trial fully
    /// checked; the answer before the slope search existed), never the
    /// lean one. Each pair is merged with
    /// the default accuracy (the lean winner kept) and with an accuracy
    /// just below the error estimate at the lean winner (refused there, so
    /// the fallback runs and answers where the estimate is smaller).
    #[test]
    fn optimal_mu_falls_back_to_the_value_search() {
        let mut state = 5;
        let (mut fallbacks, mut quick_kept) = (0, 0);
        for (degree, spans) in [(3, 1), (6, 2), (9, 1), (4, 3)] {
            for metric in [MergeMetric::Discrete, MergeMetric::Integral] {
                let (p, q) = (
                    bspline(&mut state, degree, spans),
                    bspline(&mut state, degree, spans),
                );
                let loose = MergeOptions::default()
                    .with_metric(metric)
                    .with_split(Breakpoints::Optimal);
                let problem = pair_problem(&p, &q, &loose).unwrap();
                let quick = problem.optimal_mu_on_slopes().unwrap();
                let at_quick = problem
                    .stage_one(&[0.0, quick, 1.0], Check::Full)
                    .unwrap()
                    .error_estimate;
                for accuracy in [loose.accuracy, 0.9 * at_quick] {
                    let options = MergeOptions {
                        accuracy,
                        ..loose.clone()
                    };
                    let problem = pair_problem(&p, &q, &options).unwrap();
                    assert_eq!(problem.optimal_mu_on_slopes(), Ok(quick));
                    let result = merge_bsplines(&p, &q, &options);
                    match problem.solve(&[0.0, quick, 1.0]) {
                        Ok(full) => {
                            quick_kept += 1;
                            let m = result.unwrap();
                            assert_eq!(m.report.mu, quick);
                            assert_eq!(m.report.metric_value, full.metric_value);
                        }
                        Err(BezjoinError::IllConditioned { .. }) => {
                            let checked = problem.optimal_mu_on_values();
                            let (Ok(m), Ok(mu)) = (result, checked) else {
                                continue;
                            };
                            fallbacks += 1;
                            assert_eq!(m.report.mu, mu);
                            assert_ne!(m.report.mu, quick);
                            assert!(m.report.solve_error_estimate <= accuracy);
                            assert!(problem.solve(&[0.0, mu, 1.0]).is_ok());
                        }
                        Err(e) => panic!("unexpected {e}"),
                    }
                }
            }
        }
        eprintln!("{fallbacks} answered fallbacks, {quick_kept} quick answers kept");
        assert!(
            fallbacks > 0 && quick_kept > 0,
            "{fallbacks} answered fallbacks, {quick_kept} quick answers kept: the test no \
             longer covers both paths"
        );
    }

    /// A lean trial (fix ends eliminated, Cholesky) gives the fully
    /// checked KKT solve's poles and metric (the same minimiser), and only
    /// trials carry a slope.
    #[test]
    fn lean_trials_give_the_checked_metric() {
        let mut state = 29;
        for degree in [2, 5, 9] {
            let (p, q) = (
                bspline(&mut state, degree, 2),
                bspline(&mut state, degree, 3),
            );
            for (metric, fix_ends) in [
                (MergeMetric::Discrete, false),
                (MergeMetric::Discrete, true),
                (MergeMetric::Integral, false),
                (MergeMetric::Integral, true),
            ] {
                let options = MergeOptions {
                    metric,
                    fix_ends,
                    ..MergeOptions::default()
                };
                let problem = pair_problem(&p, &q, &options).unwrap();
                for mu in [0.2, 0.6] {
                    let lean = problem.stage_one(&[0.0, mu, 1.0], Check::Trial).unwrap();
                    let full = problem.stage_one(&[0.0, mu, 1.0], Check::Full).unwrap();
                    assert!(full.slope.is_none() && lean.slope.is_some());
                    let gap = (lean.metric_value - full.metric_value).abs();
                    assert!(gap <= 1e-12 * full.metric_value.max(1.0), "gap {gap:e}");
                    let scale = full.poles.amax().max(1.0);
                    let pole_gap = (&lean.poles - &full.poles).amax();
                    assert!(
                        pole_gap <= 1e-9 * scale,
                        "degree {degree} {metric:?} fix ends {fix_ends} mu {mu}: poles {pole_gap:e}"
                    );
                }
            }
        }
    }
}
