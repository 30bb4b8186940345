//! The screen of the curve-only connect ([`super::connect_curve`], the path
//! of `bzj_connect`): for given scales, no interior constraints, in the
//! plane and in space, each end in one pass with its number of rows a
//! constant (orders up to 7): the jet ([`CurveJet::jet_screen_into`]), the
//! targets `s^k X^(k)`, the substitution and a residual screen that costs
//! no square root and no division but the targets' by the diagonal
//! entries ([`super::ends::divided_target`])
//! (mathematics.md, "The curve alone").
//!
//! The control points are those of the full path ([`super::ends`]) bit for
//! bit: the same jets, the same products by the scale, the same
//! substitution (per coordinate the same operations in the same order; the
//! coordinates are independent, so the loop over them may come first).
//! Where a row does not pass the screen, the caller runs the full check,
//! which answers or refuses with its own estimate.
//!
//! **Why a row that passes passes the full check.** The full check accepts
//! row `k` when `(|D_k R - T_k| + gamma sum_s |b_s| |R_s| + e_k) /
//! max(|T_k|, S ||D_k||_1) <= 1e-8` (Euclidean norms; `S` the data scale:
//! the curves' coordinate scales and every row's `|T_j| / ||D_j||_1`). The
//! screen's terms are never below the numerator's and never above the
//! denominator's:
//! - `|x|_1 >= |x|` for the residual and the target's norm in `e_k`;
//! - `||D_k||_1 max_(s<=k) |R_s|_1 >= sum_s |b_s| |R_s|`;
//! - the jets' rounding bounded a priori ([`CurveJet::jet_screen_into`]);
//! - `|T_k|_inf <= |T_k|` in the denominator;
//! - the data scale from the coordinate scales and the end's own rows
//!   only, a lower bound of `S` up to rounding (the other end's rows can
//!   only raise `S`; `|T_j|_inf` times the rounded reciprocal of
//!   `||D_j||_1` can exceed `|T_j| / ||D_j||_1` by an ulp or two where
//!   `T_j` has one non-zero coordinate).
//!
//! All of this holds to first order; the slack [`SCREEN_SLACK`] of the
//! limit covers the rest inside [`SCREEN_RANGE`]. That range bounds the
//! magnitudes from above, so no square the full check forms overflows.
//! From below it bounds only the data scale: a target, residual or
//! coordinate may still be far below `1e-154`, where its square is not a
//! normal number and the full check's Euclidean norm of it can be off by
//! far more than the slack. Such a quantity is at most about `1e-154`
//! while every denominator is at least `S' ||D_k||_1 >= 1e-140`, so it is
//! within about `1e-14` of the limit's scale either way.
//!
//! A point that is not finite fails its own row: it enters that row's
//! residual `D_k R - T_k`, which is then infinite or NaN, and neither
//! passes `<=` against a finite denominator. The denominators are finite
//! because the range checks (`data_scale <= high`, `|T_k|_inf <= high`)
//! are in the same conjunction as the comparison: the two must stay
//! together (`inf <= inf` would pass).

use super::ends::divided_target;
use super::{
    CONNECT_RESIDUAL_LIMIT, END_BAND_NORM_RECIPROCALS, END_BAND_NORMS, FALLING_FACTORIALS,
    MAX_CONNECT_DEGREE, SIGNED_BINOMIALS, power, unit_roundoff,
};
use crate::basis::KnotSide;
use crate::bezier::BezierCurve;
use crate::curve::CurveJet;

/// The part of [`CONNECT_RESIDUAL_LIMIT`] the screen keeps in reserve:
/// inside [`SCREEN_RANGE`] its bounds are at least the full check's to
/// first order (within a few `n u` relatively, far below this), so a
/// problem that passes the screen passes the full check.
const SCREEN_SLACK: f64 = 1e-6;

/// The magnitudes the screen accepts: the data scale (at least the curves'
/// coordinate scale) between the two, the targets' largest coordinates and
/// `||D_k||_1 max_s |R_s|_1` at most the second. The full check squares
/// coordinates before its square roots: above about `1e154` a square
/// overflows (the check then refuses with an infinite estimate), and below
/// about `1e-154` a square loses digits or vanishes (a Euclidean norm then
/// comes out below the largest coordinate, so a denominator shrinks).
/// The upper end keeps every square finite; the lower end keeps every
/// denominator at least `1e-140`, far above any quantity whose square is
/// not normal (module documentation). Outside it the full check answers.
const SCREEN_RANGE: (f64, f64) = (1e-140, 1e140);

/// The most rows of one end: `R` has at most `MAX_CONNECT_DEGREE + 1`
/// points.
const MAX_ROWS: usize = MAX_CONNECT_DEGREE + 1;

/// The screen of [`super::connect_curve`] (`args`: `(u0, v0, kp, kq, alpha,
/// beta)`, validated; dimensions equal): `Some(R)` when every condition
/// row passes it, `None` when one does not or the problem is outside its
/// range (dimension other than 2 and 3, degree `kp + kq + 1` above
/// [`MAX_CONNECT_DEGREE`]).
pub(super) fn connect_ends_screened<P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    q: &Q,
    args: (f64, f64, usize, usize, f64, f64),
) -> Option<BezierCurve> {
    let (_, _, kp, kq, _, _) = args;
    if kp + kq + 1 > MAX_CONNECT_DEGREE {
        return None;
    }
    match p.dim() {
        2 => screen_in::<2, P, Q>(p, q, args),
        3 => screen_in::<3, P, Q>(p, q, args),
        _ => None,
    }
}

/// [`connect_ends_screened`] in dimension `D`: both ends into one block of
/// `R`'s coordinates, P's rows `0..=kp` first.
fn screen_in<const D: usize, P: CurveJet + ?Sized, Q: CurveJet + ?Sized>(
    p: &P,
    q: &Q,
    (u0, v0, kp, kq, alpha, beta): (f64, f64, usize, usize, f64, f64),
) -> Option<BezierCurve> {
    let n = kp + kq + 1;
    let (p_scale, q_scale) = (p.coordinate_scale(), q.coordinate_scale());
    let coordinate_scale = p_scale.max(q_scale);
    let (low, high) = SCREEN_RANGE;
    if !(coordinate_scale >= low && coordinate_scale <= high) {
        return None;
    }
    // `resize` after `with_capacity`: malloc and a short fill (`vec![0.0;
    // len]` takes calloc's slower path).
    let mut points = Vec::with_capacity((n + 1) * D);
    points.resize((n + 1) * D, 0.0f64);
    let (p_points, q_points) = points.split_at_mut((kp + 1) * D);
    let p_end = End {
        n,
        at: u0,
        side: KnotSide::Left,
        jet_scale: p_scale,
        scale: alpha,
        data_scale: coordinate_scale,
    };
    let q_end = End {
        at: v0,
        side: KnotSide::Right,
        jet_scale: q_scale,
        scale: beta,
        ..p_end
    };
    let pass = screen_end_by_rows::<D, false, P>(p, kp + 1, &p_end, p_points)
        && screen_end_by_rows::<D, true, Q>(q, kq + 1, &q_end, q_points);
    pass.then(|| BezierCurve::from_parts(D, n, points))
}

/// The larger of `m` and `v` by one comparison (`m` when `v` is NaN):
/// the maxima of the screen without `f64::max`'s NaN handling. A NaN
/// target or point still fails the screen: it makes its row's residual
/// NaN, which fails `<=`; an infinite one makes a magnitude exceed
/// [`SCREEN_RANGE`].
#[inline(always)]
fn larger(m: f64, v: f64) -> f64 {
    if v > m { v } else { m }
}

/// What one end's screen needs besides its curve.
#[derive(Clone, Copy)]
struct End {
    /// The degree of `R`.
    n: usize,
    /// The parameter of the end (`u0` or `v0`) and the side of a knot the
    /// jet is taken from.
    at: f64,
    side: KnotSide,
    /// The curve's coordinate scale (the a priori bounds of its jet).
    jet_scale: f64,
    /// `alpha` or `beta`.
    scale: f64,
    /// The larger of the two curves' coordinate scales.
    data_scale: f64,
}

/// [`screen_end`] with the number of rows a constant up to 8 (orders up
/// to 7: every loop's bounds constants), a run-time count in arrays of
/// [`MAX_ROWS`] above.
fn screen_end_by_rows<const D: usize, const AT_ONE: bool, C: CurveJet + ?Sized>(
    curve: &C,
    rows: usize,
    end: &End,
    out: &mut [f64],
) -> bool {
    match rows {
        1 => screen_end::<D, AT_ONE, 1, C>(1, curve, end, out),
        2 => screen_end::<D, AT_ONE, 2, C>(2, curve, end, out),
        3 => screen_end::<D, AT_ONE, 3, C>(3, curve, end, out),
        4 => screen_end::<D, AT_ONE, 4, C>(4, curve, end, out),
        5 => screen_end::<D, AT_ONE, 5, C>(5, curve, end, out),
        6 => screen_end::<D, AT_ONE, 6, C>(6, curve, end, out),
        7 => screen_end::<D, AT_ONE, 7, C>(7, curve, end, out),
        8 => screen_end::<D, AT_ONE, 8, C>(8, curve, end, out),
        rows if rows <= MAX_ROWS => screen_end_many::<D, AT_ONE, C>(rows, curve, end, out),
        _ => false,
    }
}

/// [`screen_end`] for more than 8 rows, in a function of its own: its
/// arrays of [`MAX_ROWS`] rows stay out of the stack frame of the common
/// counts.
#[inline(never)]
fn screen_end_many<const D: usize, const AT_ONE: bool, C: CurveJet + ?Sized>(
    rows: usize,
    curve: &C,
    end: &End,
    out: &mut [f64],
) -> bool {
    screen_end::<D, AT_ONE, MAX_ROWS, C>(rows, curve, end, out)
}

/// One end of the screen, `rows <= CAP` condition rows (`CAP` the size of
/// the arrays; with `rows == CAP` every loop has constant bounds: the
/// inner loops run over all `CAP` slots with a test instead of a bound that
/// depends on the row): P's (`AT_ONE = false`,
/// rows of `D(0)`, unknown `R_k`, known `R_0..R_(k-1)`) or Q's (rows of
/// `D(1)`, unknown `R_(n-k)`, known `R_(n-k+1)..R_n`), the band
/// `b_s = n!/(n-k)! (-1)^(k-s) C(k, s)` from the tables.
///
/// 1. The jet `X^(0..rows)` and its a priori bounds `err_k`.
/// 2. The targets `T_k = s^k X^(k)` (the factor by repeated products, none
///    for `s = 1`), `e_k = s^k err_k + (k + 1) u |T_k|_1`, `|T_k|_inf`, the
///    end's data scale `max(S_0, |T_k|_inf / ||D_k||_1)`.
/// 3. Row by row: the unknown by substitution on the row divided by its
///    diagonal entry, as the full path's, and the row product `D_k R`
///    (each accumulator in the full path's order: at the P end the known
///    points first, at the Q end the new one first), and `|D_k R - T_k|_1`
///    summed over the coordinates in order.
/// 4. Row `k` passes when `|D_k R - T_k|_1 + gamma ||D_k||_1 max_(s<=k)
///    |R_s|_1 + e_k <= (1 - SCREEN_SLACK) 1e-8 max(|T_k|_inf, S ||D_k||_1)`
///    and the magnitudes are inside [`SCREEN_RANGE`].
///
/// `out` receives the end's points in `R`'s order: `R_0..R_(rows-1)` (P)
/// or `R_(n+1-rows)..R_n` (Q), `D` coordinates each.
#[inline(always)]
fn screen_end<const D: usize, const AT_ONE: bool, const CAP: usize, C: CurveJet + ?Sized>(
    rows: usize,
    curve: &C,
    end: &End,
    out: &mut [f64],
) -> bool {
    let n = end.n;
    let mut targets = [[0.0f64; D]; CAP];
    let mut errors = [0.0f64; CAP];
    curve.jet_screen_into(
        end.at,
        rows - 1,
        end.side,
        end.jet_scale,
        targets[..rows].as_flattened_mut(),
        &mut errors[..rows],
    );
    let reciprocals = &END_BAND_NORM_RECIPROCALS[n];
    let band_norms = &END_BAND_NORMS[n];
    let falling = &FALLING_FACTORIALS[n];
    // `s = 1` (the paper's scale): the products are exact and skipped.
    if end.scale != 1.0 {
        let mut factor = 1.0f64;
        for k in 0..rows {
            for v in targets[k].iter_mut() {
                *v *= factor;
            }
            errors[k] *= power(end.scale, k);
            factor *= end.scale;
        }
    }
    let mut largest = [0.0f64; CAP];
    let mut data_scale = end.data_scale;
    for k in 0..rows {
        let mut size = 0.0f64;
        for v in targets[k] {
            size += v.abs();
            largest[k] = larger(largest[k], v.abs());
        }
        errors[k] += (k + 1) as f64 * unit_roundoff() * size;
        data_scale = larger(data_scale, largest[k] * reciprocals[k]);
    }
    // Row by row, all coordinates side by side: the substitution and
    // `|D_k R - T_k|_1`, `|R_k|_1`.
    let mut solved = [[0.0f64; D]; CAP];
    let mut differences = [0.0f64; CAP];
    let mut sizes = [0.0f64; CAP];
    for k in 0..rows {
        let f = falling[k];
        let signed = &SIGNED_BINOMIALS[k];
        let target = targets[k];
        let mut value = [0.0f64; D];
        let x = if AT_ONE {
            // `solved[j]` is `R_(n-j)`: band slot `s` of row `k` is
            // `solved[k - s]`.
            let new_band = f * signed[0];
            let mut x = divided_target(target, new_band);
            for s in 1..CAP {
                if s <= k {
                    let ratio = signed[s] * signed[0];
                    for c in 0..D {
                        x[c] -= ratio * solved[k - s][c];
                    }
                }
            }
            for c in 0..D {
                value[c] += new_band * x[c];
            }
            for s in 1..CAP {
                if s <= k {
                    let b = f * signed[s];
                    for c in 0..D {
                        value[c] += b * solved[k - s][c];
                    }
                }
            }
            x
        } else {
            let new_band = f * signed[k];
            let mut x = divided_target(target, new_band);
            for s in 0..CAP {
                if s < k {
                    let ratio = signed[s] * signed[k];
                    let b = f * signed[s];
                    for c in 0..D {
                        x[c] -= ratio * solved[s][c];
                        value[c] += b * solved[s][c];
                    }
                }
            }
            for c in 0..D {
                value[c] += new_band * x[c];
            }
            x
        };
        for c in 0..D {
            differences[k] += (value[c] - target[c]).abs();
            sizes[k] += x[c].abs();
        }
        solved[k] = x;
    }
    let limit = (1.0 - SCREEN_SLACK) * CONNECT_RESIDUAL_LIMIT;
    let (_, high) = SCREEN_RANGE;
    let gamma = 2.0 * (2 * n + 4) as f64 * unit_roundoff();
    let mut pass = data_scale <= high;
    let mut running = 0.0f64;
    for k in 0..rows {
        // `sum_s |b_s| |R_s|_1 <= ||D_k||_1 max_(s<=k) |R_s|_1`.
        running = larger(running, sizes[k]);
        let row_product = band_norms[k] * running;
        let numerator = differences[k] + gamma * row_product + errors[k];
        let denominator = larger(largest[k], data_scale * band_norms[k]);
        pass &= (numerator <= limit * denominator) & (largest[k] <= high) & (row_product <= high);
    }
    for (k, point) in solved[..rows].iter().enumerate() {
        let slot = if AT_ONE { rows - 1 - k } else { k };
        out[slot * D..(slot + 1) * D].copy_from_slice(point);
    }
    pass
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::connect::{ConnectOptions, connect};

    /// Every count of rows the screen has its own code for (1 to 8 at each
    /// end) and the shared code above (9 and 10), in the plane and in
    /// space, with the paper's scale and others, and P also as a NURBS
    /// curve (its own jets): the screen passes well-conditioned problems
    /// and gives `connect`'s points bit for bit, which the full check
    /// accepts.
    #[test]
    fn every_row_count_gives_the_full_paths_points() {
        let mut values = crate::test_values::Values(4701);
        let (mut passed, mut cases) = (0, 0);
        for dim in [2, 3] {
            for kp in 0..10 {
                for kq in 0..10 {
                    let mut curve = |degree: usize, shift: f64| {
                        let points = (0..(degree + 1) * dim)
                            .map(|_| shift + 4.0 * values.signed())
                            .collect();
                        BezierCurve::new(dim, degree, points).unwrap()
                    };
                    // Degrees at, below and above the orders.
                    let (p, q) = (curve((kp + kq) % 8 + 1, 0.0), curve((kp * kq) % 7 + 1, 9.0));
                    let (u0, v0) = (0.2 + 0.6 * values.unit(), 0.2 + 0.6 * values.unit());
                    let scale = [1.0, 0.5, 2.0][(kp + kq) % 3];
                    let options = ConnectOptions::new(kp, kq).with_scales(scale, 1.0 / scale);
                    let full = connect(&p, u0, &q, v0, &options).unwrap();
                    let nurbs = crate::NurbsCurve::from_bezier(&p);
                    let args = (u0, v0, kp, kq, scale, 1.0 / scale);
                    let label = format!("dim {dim}, orders {kp}/{kq}, scale {scale}");
                    for screened in [
                        connect_ends_screened(&p, &q, args),
                        connect_ends_screened(&nurbs, &q, args),
                    ] {
                        cases += 1;
                        if let Some(r) = screened {
                            passed += 1;
                            assert_eq!(r.points(), full.curve.points(), "{label}");
                            assert_eq!((r.dim(), r.degree()), (dim, kp + kq + 1), "{label}");
                        }
                    }
                    assert!(full.error_estimate <= CONNECT_RESIDUAL_LIMIT, "{label}");
                }
            }
        }
        // None of these goes to the full check (the screen is not a path
        // that falls back on ordinary problems).
        assert_eq!(passed, cases, "{passed} of {cases} passed");
    }

    /// More than 16 rows at one end and the largest result degree (31):
    /// the shared code's arrays of 32 rows. Where the screen passes, its
    /// points are `connect`'s bit for bit and `connect` accepts them.
    #[test]
    fn the_largest_row_counts_give_the_full_paths_points() {
        let mut values = crate::test_values::Values(4703);
        let (mut passed, mut cases) = (0, 0);
        for dim in [2, 3] {
            for (kp, kq) in [
                (30, 0),
                (0, 30),
                (15, 15),
                (20, 10),
                (10, 20),
                (16, 14),
                (17, 3),
            ] {
                for degrees in [(3, 4), (12, 9), (24, 26)] {
                    let mut curve = |degree: usize, shift: f64| {
                        let points = (0..(degree + 1) * dim)
                            .map(|_| shift + 4.0 * values.signed())
                            .collect();
                        BezierCurve::new(dim, degree, points).unwrap()
                    };
                    let (p, q) = (curve(degrees.0, 0.0), curve(degrees.1, 9.0));
                    let (u0, v0) = (0.2 + 0.6 * values.unit(), 0.2 + 0.6 * values.unit());
                    let options = ConnectOptions::new(kp, kq).with_scales(0.25, 0.25);
                    let full = connect(&p, u0, &q, v0, &options);
                    let label = format!("dim {dim}, orders {kp}/{kq}, degrees {degrees:?}");
                    cases += 1;
                    if let Some(r) = connect_ends_screened(&p, &q, (u0, v0, kp, kq, 0.25, 0.25)) {
                        passed += 1;
                        let full = full.unwrap_or_else(|e| {
                            panic!("{label}: screen passed, check refused: {e}")
                        });
                        assert_eq!(r.points(), full.curve.points(), "{label}");
                        assert!(full.error_estimate <= CONNECT_RESIDUAL_LIMIT, "{label}");
                    }
                }
            }
        }
        assert_eq!(passed, cases, "{passed} of {cases} passed");
    }
}
