//! Feasibility classification of `merge` when "keep P" or "keep Q" makes the
//! problem badly conditioned (mathematics.md, section 3).
//!
//! Keep P with the continuity conditions (3) is never contradictory: `Q^` is
//! fully determined by `P`, it is `P` on `[1, 1 + (1 - mu) / mu]` (so `R` is
//! `P` on `[0, 1 / mu]`); keep Q likewise (`P^` is `Q` on
//! `[-mu / (1 - mu), 0]`). The smaller the kept piece, the further the
//! extrapolation. Asserted over `mu` in `[0.02, 0.98]` and degrees 1..12:
//!
//! * a feasible system is never called `Inconsistent`: it is answered, or
//!   refused as `IllConditioned` with an estimate above the limit;
//! * every answer is within its own error estimate of the exact answer (an
//!   exact-rational extrapolation, BigInt de Casteljau), relative to the
//!   coordinate scale of input and result, and within the requested accuracy;
//! * contradictory combinations (keep P and keep Q of unrelated curves; keep
//!   P with fix ends or a point on Q; keep Q with fix ends or a point on P)
//!   are `Inconsistent` at every `mu` and degree, naming the constraint;
//! * the same combinations on the two pieces of one curve (dependent but
//!   consistent) are never `Inconsistent`, and are answered where the
//!   problem is well conditioned.
//!
//! `cargo test -p bezjoin-core --test merge_conditioning -- --nocapture`
//! prints the counts quoted in docs/accuracy.md (Merge section).

mod common;
use bezjoin_core::BezierCurve;
use bezjoin_core::BezjoinError;
use bezjoin_core::{
    Breakpoints, CONSISTENCY_TOLERANCE, ChainMergeOptions, DEFAULT_MERGE_ACCURACY, KeepPoint,
    Merge, MergeOptions, merge, merge_chain,
};
use common::{Random, bezier_basis_derivatives, control_matrix};
use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

type Q = BigRational;

/// Split parameters swept, `(0.02 .. 0.98)`, including the reported 0.08 and
/// 0.057, their mirror images, and the dyadic `2^-k`, `1 - 2^-k`.
const MUS: [f64; 27] = [
    0.02, 0.03, 0.04, 0.057, 0.0625, 0.08, 0.1, 0.125, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.6, 0.7,
    0.75, 0.8, 0.85, 0.875, 0.9, 0.92, 0.9375, 0.943, 0.96, 0.97, 0.98,
];

/// A curve with small integer coordinates: split at `2^-k` (k <= 4) up to
/// degree 12, its pieces are exact in doubles, so the kept piece's extension
/// is exactly that curve and as small as the data: the case where
/// extrapolation loses the most.
fn integer_curve(rng: &mut Random, dim: usize, degree: usize) -> BezierCurve {
    let pts = (0..(degree + 1) * dim)
        .map(|_| (rng.next() * 17.0).floor() - 8.0)
        .collect();
    BezierCurve::new(dim, degree, pts).unwrap()
}

/// Whether `mu` is `2^-k` or `1 - 2^-k` with `k <= 4`.
fn dyadic(mu: f64) -> bool {
    (1..=4).any(|k| {
        let d = 0.5f64.powi(k);
        mu == d || mu == 1.0 - d
    })
}

/// The a-priori bound on the relative rounding of the kept piece's
/// compensated extension: `2 eps + 2 (3 n eps)^2 (2/m - 1)^n`, `m` the kept
/// piece's share of `[0, 1]`.
fn a_priori_bound(degree: usize, m: f64) -> f64 {
    let gamma = 3.0 * degree as f64 * f64::EPSILON;
    2.0 * f64::EPSILON + 2.0 * gamma * gamma * (2.0 / m - 1.0).powi(degree as i32)
}

fn exact(x: f64) -> Q {
    Q::from_float(x).expect("finite")
}

/// Control points of `c` on `[a, b]`, exactly: point `i` is the blossom
/// `c(a^(n-i), b^i)`, by de Casteljau in integers over a common denominator.
fn exact_segment(c: &BezierCurve, a: &Q, b: &Q) -> Vec<Vec<Q>> {
    let n = c.degree();
    let d = c.dim();
    let values: Vec<Q> = c.points().iter().map(|&v| exact(v)).collect();
    let mut denominator = BigInt::one();
    for v in &values {
        // Denominators of doubles are powers of two: the largest divides all.
        if v.denom() > &denominator {
            denominator = v.denom().clone();
        }
    }
    let integers: Vec<BigInt> = values
        .iter()
        .map(|v| (v * Q::from_integer(denominator.clone())).to_integer())
        .collect();
    (0..=n)
        .map(|i| {
            let mut points: Vec<Vec<BigInt>> = (0..=n)
                .map(|j| integers[j * d..(j + 1) * d].to_vec())
                .collect();
            let mut scale = denominator.clone();
            for step in 0..n {
                let t = if step < i { b } else { a };
                let (u, w) = (t.numer(), t.denom());
                let stay = w - u;
                for j in 0..points.len() - 1 {
                    let next: Vec<BigInt> = points[j]
                        .iter()
                        .zip(&points[j + 1])
                        .map(|(p, q)| &stay * p + u * q)
                        .collect();
                    points[j] = next;
                }
                points.pop();
                scale *= w;
            }
            points[0]
                .iter()
                .map(|v| Q::new(v.clone(), scale.clone()))
                .collect()
        })
        .collect()
}

fn difference(c: &BezierCurve, reference: &[Vec<Q>]) -> f64 {
    let mut worst = 0.0f64;
    for (i, row) in reference.iter().enumerate() {
        for (k, v) in row.iter().enumerate() {
            let d = (exact(c.point(i)[k]) - v).abs();
            worst = worst.max(d.to_f64().unwrap_or(f64::INFINITY));
        }
    }
    worst
}

fn largest(reference: &[Vec<Q>]) -> f64 {
    reference
        .iter()
        .flatten()
        .map(|v| v.abs().to_f64().unwrap_or(f64::INFINITY))
        .fold(0.0, f64::max)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kept {
    P,
    Q,
}

/// The exact changed piece (`Q^` for keep P, `P^` for keep Q) and `R`:
/// `R(t) = P(t / mu)` (keep P), `R(t) = Q((t - mu) / (1 - mu))` (keep Q),
/// for the double `mu` taken exactly.
fn exact_answer(
    kept: Kept,
    p: &BezierCurve,
    q: &BezierCurve,
    mu: f64,
) -> (Vec<Vec<Q>>, Vec<Vec<Q>>) {
    let (h0, h1) = (exact(mu), Q::one() - exact(mu));
    match kept {
        Kept::P => (
            exact_segment(p, &Q::one(), &(Q::one() / &h0)),
            exact_segment(p, &Q::zero(), &(Q::one() / &h0)),
        ),
        Kept::Q => (
            exact_segment(q, &(-&h0 / &h1), &Q::zero()),
            exact_segment(q, &(-&h0 / &h1), &Q::one()),
        ),
    }
}

fn keep_options(kept: Kept, mu: f64, accuracy: f64) -> MergeOptions {
    MergeOptions {
        keep_p: kept == Kept::P,
        keep_q: kept == Kept::Q,
        split: Breakpoints::Given(vec![mu]),
        accuracy,
        ..MergeOptions::default()
    }
}

/// What one keep-P / keep-Q case did.
struct Outcome {
    /// At the default accuracy.
    answered: bool,
    /// With accuracy 1 (every estimate accepted): true error / estimate.
    ratio: f64,
    /// With accuracy 1: the true error (relative to the coordinate scale).
    error: f64,
}

/// Checks one case; panics on any violated property.
fn check_keep(kept: Kept, p: &BezierCurve, q: &BezierCurve, mu: f64, what: &str) -> Outcome {
    let (changed, r_exact) = exact_answer(kept, p, q, mu);
    let input_scale = p.coordinate_scale().max(q.coordinate_scale());
    let scale = input_scale.max(largest(&changed));
    fn unchanged<'m>(
        kept: Kept,
        m: &'m Merge,
        p: &'m BezierCurve,
        q: &'m BezierCurve,
    ) -> (&'m BezierCurve, &'m BezierCurve, &'m BezierCurve) {
        match kept {
            Kept::P => (&m.p_hat, p, &m.q_hat),
            Kept::Q => (&m.q_hat, q, &m.p_hat),
        }
    }
    // Every estimate accepted: the estimate must bound the true error.
    let (mut ratio, mut true_error) = (f64::NAN, f64::NAN);
    match merge(p, q, &keep_options(kept, mu, 1.0)) {
        Ok(m) => {
            let (same, original, other) = unchanged(kept, &m, p, q);
            assert_eq!(same, original, "{what}: the kept curve changed");
            let error = difference(other, &changed) / scale;
            let estimate = m.report.solve_error_estimate;
            assert!(
                error <= estimate,
                "{what}: true error {error:e} above the estimate {estimate:e}"
            );
            ratio = error / estimate;
            true_error = error;
        }
        Err(BezjoinError::IllConditioned {
            estimate, limit, ..
        }) => assert!(
            estimate > limit,
            "{what}: refused with {estimate:e} <= {limit:e}"
        ),
        Err(e) => panic!("{what}: feasible system refused with {e}"),
    }
    // The default accuracy: answered within it, or refused with the estimate.
    let answered = match merge(p, q, &keep_options(kept, mu, DEFAULT_MERGE_ACCURACY)) {
        Ok(m) => {
            let (same, original, other) = unchanged(kept, &m, p, q);
            assert_eq!(same, original, "{what}: the kept curve changed");
            let error = difference(other, &changed) / scale;
            assert!(
                error <= DEFAULT_MERGE_ACCURACY
                    && m.report.solve_error_estimate <= DEFAULT_MERGE_ACCURACY,
                "{what}: error {error:e}, estimate {:e}",
                m.report.solve_error_estimate
            );
            assert!(
                m.report.split_check_error <= DEFAULT_MERGE_ACCURACY,
                "{what}"
            );
            let r_error = difference(&m.merged, &r_exact) / scale.max(largest(&r_exact));
            assert!(
                r_error <= 10.0 * DEFAULT_MERGE_ACCURACY,
                "{what}: R off the exact extrapolation by {r_error:e}"
            );
            true
        }
        Err(BezjoinError::IllConditioned {
            estimate, limit, ..
        }) => {
            assert!(
                estimate > limit,
                "{what}: refused with {estimate:e} <= {limit:e}"
            );
            false
        }
        Err(e) => panic!("{what}: feasible system refused with {e}"),
    };
    Outcome {
        answered,
        ratio,
        error: true_error,
    }
}

/// The reported cases: random curves, keep P at degree 9, mu 0.08 and at
/// degree 10, mu 0.057 (and keep Q at 1 - mu) were called Inconsistent
/// ("keep P unchanged (control point 9) contradicts ..."). They are well
/// conditioned relative to the result (`Q^` is large, and so is its
/// rounding budget) and must be answered.
#[test]
fn reported_small_mu_cases_are_answered() {
    let mut rng = Random(0x5eed_0001);
    for (degree, mu) in [(9, 0.08), (10, 0.057)] {
        for _ in 0..3 {
            let p = rng.curve(2, degree, 2.0);
            let q = rng.curve(2, degree, 2.0);
            for (kept, m) in [(Kept::P, mu), (Kept::Q, 1.0 - mu)] {
                let what = format!("degree {degree} {kept:?} mu {m}");
                let outcome = check_keep(kept, &p, &q, m, &what);
                assert!(outcome.answered, "{what}: refused");
            }
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Data {
    /// Unrelated random curves: the extension grows like its bound.
    Random,
    /// The kept piece cut (in doubles) from a random curve.
    Piece,
    /// The kept piece cut exactly from an integer curve at a dyadic `mu`.
    ExactPiece,
}

/// Keep P / keep Q over the whole sweep, on random curves and on a kept
/// piece cut from a longer curve (whose extension is as small as the data,
/// so the rounding relative to it grows like `(2/m - 1)^n` in plain
/// arithmetic).
#[test]
fn keep_one_curve_is_never_inconsistent_and_answers_hold_their_estimate() {
    let mut rng = Random(0x0dd_ba11);
    let (mut answered, mut refused, mut worst_ratio, mut worst_error) = (0, 0, 0.0f64, 0.0f64);
    for degree in 1..=12 {
        for &mu in &MUS {
            for kept in [Kept::P, Kept::Q] {
                for data in [Data::Random, Data::Piece, Data::ExactPiece] {
                    if data == Data::ExactPiece && !dyadic(mu) {
                        continue;
                    }
                    let dim = 1 + (rng.next() * 3.0) as usize;
                    let (mut p, mut q) = (rng.curve(dim, degree, 2.0), rng.curve(dim, degree, 2.0));
                    let whole = match data {
                        Data::Random => None,
                        Data::Piece => Some(rng.curve(dim, degree, 2.0)),
                        Data::ExactPiece => Some(integer_curve(&mut rng, dim, degree)),
                    };
                    if let Some(whole) = &whole {
                        let (a, b) = whole.split_at(mu).unwrap();
                        match kept {
                            Kept::P => p = a,
                            Kept::Q => q = b,
                        }
                    }
                    let what = format!("degree {degree} {kept:?} mu {mu} {data:?}");
                    let outcome = check_keep(kept, &p, &q, mu, &what);
                    if outcome.answered {
                        answered += 1;
                    } else {
                        refused += 1;
                    }
                    if outcome.ratio.is_finite() {
                        worst_ratio = worst_ratio.max(outcome.ratio);
                        worst_error = worst_error.max(outcome.error);
                    }
                    // Where the a-priori bound allows it, the answer is given.
                    let m = if kept == Kept::P { mu } else { 1.0 - mu };
                    let bound = a_priori_bound(degree, m);
                    if bound <= 1e-9 {
                        assert!(
                            outcome.answered,
                            "{what}: refused (a-priori bound {bound:e})"
                        );
                    }
                }
            }
        }
    }
    eprintln!(
        "keep P / keep Q sweep: {answered} answered, {refused} refused as IllConditioned, \
         0 Inconsistent; largest true error {worst_error:.1e}, largest true error / estimate \
         {worst_ratio:.2e}"
    );
}

fn expect_inconsistent(result: Result<Merge, BezjoinError>, needle: &str, what: &str) {
    match result {
        Err(BezjoinError::Inconsistent { reason }) => {
            assert!(
                reason.contains(needle),
                "{what}: {reason:?} lacks {needle:?}"
            )
        }
        other => panic!("{what}: expected Inconsistent, got {:?}", other.err()),
    }
}

/// The contradictory combinations stay contradictory at every mu and degree.
#[test]
fn contradictory_combinations_are_inconsistent_over_the_sweep() {
    let mut rng = Random(0xbad_c0de);
    let point = KeepPoint {
        param: 0.5,
        max_order: 0,
    };
    for degree in 1..=12 {
        for &mu in &MUS {
            let p = rng.curve(2, degree, 2.0);
            let q = rng.curve(2, degree, 2.0);
            let base = MergeOptions {
                split: Breakpoints::Given(vec![mu]),
                ..MergeOptions::default()
            };
            let cases = [
                (
                    MergeOptions {
                        keep_p: true,
                        keep_q: true,
                        ..base.clone()
                    },
                    "keep Q unchanged",
                ),
                (
                    MergeOptions {
                        keep_p: true,
                        fix_ends: true,
                        ..base.clone()
                    },
                    "fix ends (last point of Q)",
                ),
                (
                    MergeOptions {
                        keep_q: true,
                        fix_ends: true,
                        ..base.clone()
                    },
                    "fix ends (first point of P)",
                ),
                (
                    MergeOptions {
                        keep_p: true,
                        q_points: vec![point],
                        ..base.clone()
                    },
                    "q_points[0]",
                ),
                (
                    MergeOptions {
                        keep_q: true,
                        p_points: vec![point],
                        ..base.clone()
                    },
                    "p_points[0]",
                ),
            ];
            for (o, needle) in cases {
                let what = format!("degree {degree} mu {mu} {needle}");
                expect_inconsistent(merge(&p, &q, &o), needle, &what);
            }
        }
    }
}

/// The same combinations on the two pieces of one curve are dependent but
/// consistent: never Inconsistent; answered (with that curve) wherever the
/// extrapolation loses little, refused as IllConditioned otherwise.
#[test]
fn consistent_dependent_combinations_are_never_inconsistent() {
    let mut rng = Random(0xc0ffee);
    let (mut answered, mut refused) = (0, 0);
    for degree in 1..=12 {
        for &mu in &MUS {
            let curve = rng.curve(2, degree, 2.0);
            let (p, q) = curve.split_at(mu).unwrap();
            let base = MergeOptions {
                split: Breakpoints::Given(vec![mu]),
                ..MergeOptions::default()
            };
            let on_q = KeepPoint {
                param: 0.5,
                max_order: degree / 2,
            };
            let cases = [
                ("keep P and Q", None, {
                    MergeOptions {
                        keep_p: true,
                        keep_q: true,
                        ..base.clone()
                    }
                }),
                ("keep P, fix ends", Some(mu), {
                    MergeOptions {
                        keep_p: true,
                        fix_ends: true,
                        ..base.clone()
                    }
                }),
                ("keep Q, fix ends", Some(1.0 - mu), {
                    MergeOptions {
                        keep_q: true,
                        fix_ends: true,
                        ..base.clone()
                    }
                }),
                ("keep P, point on Q", Some(mu), {
                    MergeOptions {
                        keep_p: true,
                        q_points: vec![on_q],
                        ..base.clone()
                    }
                }),
            ];
            for (name, extrapolated, o) in cases {
                let what = format!("degree {degree} mu {mu} {name}");
                match merge(&p, &q, &o) {
                    Ok(m) => {
                        answered += 1;
                        let scale = curve.coordinate_scale().max(m.merged.coordinate_scale());
                        if o.keep_p {
                            assert_eq!(m.p_hat, p, "{what}: P changed");
                        }
                        if o.keep_q {
                            assert_eq!(m.q_hat, q, "{what}: Q changed");
                        }
                        // The constraints hold (unit rows, consistency tolerance).
                        let tolerance = 2.0 * CONSISTENCY_TOLERANCE * scale;
                        if o.fix_ends {
                            let first = (m.p_hat.point(0)[0] - p.point(0)[0])
                                .abs()
                                .max((m.p_hat.point(0)[1] - p.point(0)[1]).abs());
                            let last = (m.q_hat.point(degree)[0] - q.point(degree)[0])
                                .abs()
                                .max((m.q_hat.point(degree)[1] - q.point(degree)[1]).abs());
                            assert!(first.max(last) <= tolerance, "{what}: ends moved");
                        }
                        for kp in &o.q_points {
                            let d = bezier_basis_derivatives(degree, kp.param, kp.max_order);
                            let change = &d * (control_matrix(&m.q_hat) - control_matrix(&q));
                            for s in 0..=kp.max_order {
                                let norm = d.row(s).norm();
                                let moved = change.row(s).amax();
                                assert!(
                                    moved <= tolerance * norm,
                                    "{what}: derivative {s} at {} moved by {moved:e}",
                                    kp.param
                                );
                            }
                        }
                        // R is the curve up to the kept piece's own rounding
                        // (half an ulp) magnified by its extension.
                        let share = extrapolated.unwrap_or(mu.max(1.0 - mu));
                        let magnified =
                            (2.0 / share - 1.0).powi(degree as i32) * f64::EPSILON * scale;
                        let error = (control_matrix(&m.merged) - control_matrix(&curve)).amax();
                        assert!(
                            error <= 10.0 * DEFAULT_MERGE_ACCURACY * scale + magnified,
                            "{what}: R off the curve by {error:e}"
                        );
                    }
                    Err(BezjoinError::IllConditioned {
                        estimate, limit, ..
                    }) => {
                        refused += 1;
                        assert!(estimate > limit, "{what}");
                        // Refused only where the kept piece's extrapolation
                        // loses accuracy (both kept: nothing is extrapolated).
                        let m = extrapolated.unwrap_or_else(|| panic!("{what}: refused"));
                        let loss = (2.0 / m - 1.0).powi(degree as i32) * f64::EPSILON;
                        assert!(loss > 1e-11, "{what}: refused (loss bound {loss:e})");
                    }
                    Err(e) => panic!("{what}: consistent system refused with {e}"),
                }
            }
        }
    }
    eprintln!("pieces of one curve: {answered} answered, {refused} refused as IllConditioned");
}

/// Chains: a free curve between two kept ones is determined by the first
/// (its extrapolation), so the second contradicts it unless all three are
/// pieces of one curve.
#[test]
fn chain_with_kept_curves_on_both_sides_of_a_free_one() {
    let mut rng = Random(0xc4a1);
    for degree in [2, 5, 8] {
        let curve = rng.curve(2, degree, 2.0);
        let pieces: Vec<BezierCurve> = [(0.0, 0.25), (0.25, 0.75), (0.75, 1.0)]
            .iter()
            .map(|&(a, b)| curve.segment(a, b).unwrap())
            .collect();
        let o = ChainMergeOptions {
            keep: vec![true, false, true],
            breakpoints: Breakpoints::Given(vec![0.25, 0.75]),
            ..ChainMergeOptions::default()
        };
        let m = merge_chain(&pieces, &o).unwrap();
        let error = (control_matrix(&m.merged) - control_matrix(&curve)).amax();
        assert!(
            error <= 1e-9 * curve.coordinate_scale(),
            "degree {degree}: {error:e}"
        );
        let unrelated: Vec<BezierCurve> = (0..3).map(|_| rng.curve(2, degree, 2.0)).collect();
        match merge_chain(&unrelated, &o) {
            Err(BezjoinError::Inconsistent { reason }) => {
                assert!(reason.contains("keep curves[2] unchanged"), "{reason}")
            }
            other => panic!(
                "degree {degree}: expected Inconsistent, got {:?}",
                other.err()
            ),
        }
    }
}

/// An accuracy the extension cannot meet is refused as IllConditioned with
/// an estimate above it and at least the true error (never Inconsistent):
/// exact pieces at `mu = 1/16`, degree 12, kept piece extended 16-fold.
#[test]
fn keep_refusals_carry_an_estimate_above_the_true_error() {
    let mut rng = Random(0x7e57);
    for kept in [Kept::P, Kept::Q] {
        let mu = if kept == Kept::P { 0.0625 } else { 0.9375 };
        let whole = integer_curve(&mut rng, 2, 12);
        let (p, q) = whole.split_at(mu).unwrap();
        let what = format!("{kept:?} mu {mu}");
        let answer = merge(&p, &q, &keep_options(kept, mu, 1.0)).unwrap();
        // The pieces are exact, so the answer is `whole` on the other side.
        let other = if kept == Kept::P {
            &answer.q_hat
        } else {
            &answer.p_hat
        };
        let exact_other = if kept == Kept::P { &q } else { &p };
        let scale = whole.coordinate_scale();
        let error = (control_matrix(other) - control_matrix(exact_other)).amax() / scale;
        let estimate = answer.report.solve_error_estimate;
        assert!(
            error <= estimate && estimate > 1e-14,
            "{what}: {error:e} / {estimate:e}"
        );
        let limit = estimate / 2.0;
        match merge(&p, &q, &keep_options(kept, mu, limit)) {
            Err(BezjoinError::IllConditioned {
                estimate: refused, ..
            }) => assert!(refused > limit && refused >= error, "{what}: {refused:e}"),
            other => panic!("{what}: expected IllConditioned, got {:?}", other.err()),
        }
    }
}
