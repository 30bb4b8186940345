//! Curvature of a blend, its variation energy, and the search for fair
//! shape parameters (docs/mathematics.md#geometric-continuity).

use crate::basis::bezier_basis_derivatives;
use crate::bezier::BezierCurve;
use crate::connect::Problem;
use crate::error::{BezjoinError, Result};

use super::solve_with_shapes;

/// Panels of the composite 8-point Gauss-Legendre rule of
/// [`curvature_variation`] and of the reported energy: 64 panels agree with
/// a 20 000-interval Simpson rule to 1e-6 relative on blends whose speed
/// stays above a fifth of its largest value (test
/// `fairness_energy_quadrature_is_accurate`); near a cusp the curvature
/// peak is too sharp for any fixed rule and the energy is a lower estimate.
pub const ENERGY_PANELS: usize = 64;

/// Panels of the rule the fair search ranks its trial blends with: 4
/// panels resolve the smooth blends near the optimum; on a blend with a
/// near-cusp they can be off by a factor ten, but such a blend's energy is
/// then still orders of magnitude above the optimum's.
const SEARCH_PANELS: usize = 4;

/// Evenly spaced samples of the curvature behind the report's range and
/// extrema count.
pub const CURVATURE_SAMPLES: usize = 512;

/// Grid points over the common `ln beta_1` before Nelder-Mead.
const GRID_POINTS: usize = 13;

/// Decades of `beta_1` searched on either side of the natural scale.
const GRID_DECADES: f64 = 2.0;

/// Largest number of energy evaluations of the Nelder-Mead search.
const MAX_EVALUATIONS: usize = 120;

/// Nelder-Mead stops when the simplex's energies agree to this relative
/// spread.
const RELATIVE_SPREAD: f64 = 1e-5;

const GL_NODES: [f64; 4] = [
    0.183_434_642_495_649_8,
    0.525_532_409_916_329,
    0.796_666_477_413_626_7,
    0.960_289_856_497_536_3,
];
const GL_WEIGHTS: [f64; 4] = [
    0.362_683_783_378_362,
    0.313_706_645_877_887_3,
    0.222_381_034_453_374_5,
    0.101_228_536_290_376_3,
];

/// What a blend's curvature looks like.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FairnessReport {
    /// `L^3 int (d kappa / ds)^2 ds`, the minimised fairness energy
    /// ([`curvature_variation`]; scale-free).
    pub energy: f64,
    /// Smallest curvature over the blend (sampled; signed in 2D).
    pub curvature_min: f64,
    /// Largest curvature over the blend (sampled; signed in 2D).
    pub curvature_max: f64,
    /// Interior local extrema of the curvature along the blend (sampled).
    pub curvature_extrema: usize,
}

/// Curvature and its parameter derivative at `t`: signed in 2D,
/// `kappa = (x' y'' - y' x'') / |r'|^3`; in other dimensions
/// `kappa = sqrt(|r'|^2 |r''|^2 - (r'.r'')^2) / |r'|^3 >= 0`. Returns
/// `(kappa, dkappa/dt, |r'|)`; `|r'| = 0` (a cusp) gives infinities.
fn curvature_at(curve: &BezierCurve, t: f64, jet: &mut [f64]) -> (f64, f64, f64) {
    let d = curve.dim();
    curve.eval_derivatives_into(t, 3, jet);
    kappa_from(&jet[d..2 * d], &jet[2 * d..3 * d], &jet[3 * d..4 * d])
}

/// [`curvature_at`] from the first three derivatives `a`, `b`, `c`.
fn kappa_from(a: &[f64], b: &[f64], c: &[f64]) -> (f64, f64, f64) {
    let d = a.len();
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let s2 = dot(a, a);
    let speed = s2.sqrt();
    if speed == 0.0 || !speed.is_finite() {
        return (f64::INFINITY, f64::INFINITY, 0.0);
    }
    let ab = dot(a, b);
    if d == 2 {
        let kappa = (a[0] * b[1] - a[1] * b[0]) / (speed * s2);
        let dkappa = (a[0] * c[1] - a[1] * c[0]) / (speed * s2) - 3.0 * kappa * ab / s2;
        return (kappa, dkappa, speed);
    }
    let gram = (s2 * dot(b, b) - ab * ab).max(0.0);
    let kappa = gram.sqrt() / (speed * s2);
    // d(gram)/dt = 2 |a|^2 (b.c) - 2 (a.b) (a.c)
    let dgram = 2.0 * s2 * dot(b, c) - 2.0 * ab * dot(a, c);
    let first = if gram > 0.0 {
        dgram / (2.0 * gram.sqrt() * speed * s2)
    } else {
        0.0
    };
    (kappa, first - 3.0 * kappa * ab / s2, speed)
}

/// The quadrature of [`curvature_variation`] for one degree: the nodes'
/// weights and the Bernstein derivative rows (orders 1..3) at every node,
/// computed once, so each energy costs three small products per node (the
/// fair search evaluates hundreds of blends of one degree).
pub(super) struct EnergyRule {
    degree: usize,
    weights: Vec<f64>,
    /// Per node, `3 (n + 1)` values: the first, second and third
    /// derivatives of the Bernstein basis there.
    rows: Vec<f64>,
}

impl EnergyRule {
    pub(super) fn new(degree: usize, panels: usize) -> Self {
        let h = 1.0 / panels as f64;
        let n1 = degree + 1;
        let mut weights = Vec::new();
        let mut rows = Vec::new();
        for panel in 0..panels {
            let mid = (panel as f64 + 0.5) * h;
            for (node, weight) in GL_NODES.iter().zip(GL_WEIGHTS) {
                for t in [mid - 0.5 * h * node, mid + 0.5 * h * node] {
                    let basis = bezier_basis_derivatives(degree, t, 3);
                    weights.push(weight * 0.5 * h);
                    for k in 1..=3 {
                        for i in 0..n1 {
                            rows.push(basis[(k, i)]);
                        }
                    }
                }
            }
        }
        Self {
            degree,
            weights,
            rows,
        }
    }

    /// `L^3 int (d kappa/ds)^2 ds` of `curve` (of this rule's degree).
    pub(super) fn energy(&self, curve: &BezierCurve) -> f64 {
        debug_assert_eq!(curve.degree(), self.degree);
        let d = curve.dim();
        let n1 = self.degree + 1;
        let points = curve.points();
        let mut jet = vec![0.0; 3 * d];
        let (mut variation, mut length) = (0.0, 0.0);
        for (node, weight) in self.weights.iter().enumerate() {
            let rows = &self.rows[node * 3 * n1..(node + 1) * 3 * n1];
            jet.fill(0.0);
            for k in 0..3 {
                let row = &rows[k * n1..(k + 1) * n1];
                let out = &mut jet[k * d..(k + 1) * d];
                for (i, &b) in row.iter().enumerate() {
                    for (o, x) in out.iter_mut().zip(&points[i * d..(i + 1) * d]) {
                        *o += b * x;
                    }
                }
            }
            let (_, dkappa, speed) = kappa_from(&jet[..d], &jet[d..2 * d], &jet[2 * d..]);
            variation += weight * dkappa * dkappa / speed;
            length += weight * speed;
        }
        let total = variation * length.powi(3);
        if total.is_nan() { f64::INFINITY } else { total }
    }
}

/// The fairness energy `L^3 int (d kappa / ds)^2 ds` of a blend of length
/// `L`: the curvature variation made scale-free (a blend twice the size has
/// the same energy). Without the factor the energy of far-reaching blends
/// tends to zero (their curvature does), and minimising it runs away to
/// huge loops. `int (d kappa/ds)^2 ds = int (dkappa/dt)^2 / |r'| dt` and
/// `L = int |r'| dt` over `[0, 1]` by composite 8-point Gauss-Legendre on
/// [`ENERGY_PANELS`] panels; infinite when the speed vanishes at a node (a
/// cusp).
pub fn curvature_variation(curve: &BezierCurve) -> f64 {
    EnergyRule::new(curve.degree(), ENERGY_PANELS).energy(curve)
}

/// The report of a blend: [`curvature_variation`], and the curvature's
/// range and interior local extrema over [`CURVATURE_SAMPLES`]` + 1` evenly
/// spaced parameters (changes below `1e-9` of the range are not counted).
pub fn fairness_report(curve: &BezierCurve) -> FairnessReport {
    let mut jet = vec![0.0; 4 * curve.dim()];
    let kappas: Vec<f64> = (0..=CURVATURE_SAMPLES)
        .map(|i| curvature_at(curve, i as f64 / CURVATURE_SAMPLES as f64, &mut jet).0)
        .collect();
    let min = kappas.iter().copied().fold(f64::INFINITY, f64::min);
    let max = kappas.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let noise = 1e-9 * (max - min).abs().max(max.abs());
    let mut extrema = 0;
    let mut direction = 0i8;
    for w in kappas.windows(2) {
        let step = w[1] - w[0];
        let now = if step > noise {
            1
        } else if step < -noise {
            -1
        } else {
            0
        };
        if now != 0 {
            if direction != 0 && now != direction {
                extrema += 1;
            }
            direction = now;
        }
    }
    FairnessReport {
        energy: curvature_variation(curve),
        curvature_min: min,
        curvature_max: max,
        curvature_extrema: extrema,
    }
}

/// Shape values from search coordinates: per end `ln beta_1` then
/// `gamma_j = beta_j / beta_1`.
fn shapes_from(
    x: &[f64],
    p_order: usize,
    fixed_p: Option<&[f64]>,
    fixed_q: Option<&[f64]>,
    q_order: usize,
) -> (Vec<f64>, Vec<f64>) {
    let mut at = 0;
    let mut end = |order: usize, fixed: Option<&[f64]>| -> Vec<f64> {
        if let Some(f) = fixed {
            return f.to_vec();
        }
        if order == 0 {
            return Vec::new();
        }
        let beta1 = x[at].exp();
        let mut shape = vec![beta1];
        for j in 1..order {
            shape.push(x[at + j] * beta1);
        }
        at += order;
        shape
    };
    let p = end(p_order, fixed_p);
    let q = end(q_order, fixed_q);
    (p, q)
}

/// The fair shape values (module documentation of `geometric`).
pub(super) fn fair_shapes(
    problem: &Problem,
    fixed_p: Option<&[f64]>,
    fixed_q: Option<&[f64]>,
    natural: f64,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let (kp, kq) = (problem.p_order, problem.q_order);
    let free_p = if fixed_p.is_some() { 0 } else { kp };
    let free_q = if fixed_q.is_some() { 0 } else { kq };
    let rule = EnergyRule::new(problem.degree, SEARCH_PANELS);
    let energy = |x: &[f64]| -> f64 {
        let (ps, qs) = shapes_from(x, kp, fixed_p, fixed_q, kq);
        match solve_with_shapes(problem, &ps, &qs) {
            Ok(c) => rule.energy(&c.curve),
            Err(_) => f64::INFINITY,
        }
    };
    let dims = free_p + free_q;
    if dims == 0 {
        return Ok(shapes_from(&[], kp, fixed_p, fixed_q, kq));
    }
    // Grid over a common ln beta_1 (gammas zero).
    let start_of = |log_beta: f64| {
        let mut x = vec![0.0; dims];
        if free_p > 0 {
            x[0] = log_beta;
        }
        if free_q > 0 {
            x[free_p] = log_beta;
        }
        x
    };
    let center = natural.ln();
    let half = GRID_DECADES * std::f64::consts::LN_10;
    let mut best: Option<(f64, Vec<f64>)> = None;
    for i in 0..GRID_POINTS {
        let log_beta = center - half + 2.0 * half * i as f64 / (GRID_POINTS - 1) as f64;
        let x = start_of(log_beta);
        let e = energy(&x);
        if e.is_finite() && best.as_ref().is_none_or(|(b, _)| e < *b) {
            best = Some((e, x));
        }
    }
    let Some((_, start)) = best else {
        return Err(BezjoinError::IllConditioned {
            what: "G^k connect: no shape value on the search grid gives a blend with \
                   defined curvature (every trial failed or has a cusp)"
                .into(),
            estimate: f64::INFINITY,
            limit: crate::CONNECT_RESIDUAL_LIMIT,
        });
    };
    let x = nelder_mead(energy, &start, 0.5, MAX_EVALUATIONS, RELATIVE_SPREAD);
    Ok(shapes_from(&x, kp, fixed_p, fixed_q, kq))
}

/// Minimise `f` from `start` by the Nelder-Mead simplex method (standard
/// coefficients 1, 2, 1/2, 1/2; initial simplex `start + step e_i`), until
/// the simplex's values agree to `relative_spread` or `max_evaluations` are
/// spent. Deterministic. Non-finite values count as worse than any finite.
pub(crate) fn nelder_mead(
    mut f: impl FnMut(&[f64]) -> f64,
    start: &[f64],
    step: f64,
    max_evaluations: usize,
    relative_spread: f64,
) -> Vec<f64> {
    let n = start.len();
    let value = |f: &mut dyn FnMut(&[f64]) -> f64, x: &[f64]| {
        let v = f(x);
        if v.is_finite() { v } else { f64::INFINITY }
    };
    let mut simplex: Vec<(f64, Vec<f64>)> = Vec::with_capacity(n + 1);
    simplex.push((value(&mut f, start), start.to_vec()));
    for i in 0..n {
        let mut x = start.to_vec();
        x[i] += step;
        simplex.push((value(&mut f, &x), x));
    }
    let mut evaluations = n + 1;
    while evaluations < max_evaluations {
        simplex.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (best, worst) = (simplex[0].0, simplex[n].0);
        if best.is_finite()
            && worst.is_finite()
            && (worst - best) <= relative_spread * best.abs().max(f64::MIN_POSITIVE)
        {
            break;
        }
        let centroid: Vec<f64> = (0..n)
            .map(|c| simplex[..n].iter().map(|(_, x)| x[c]).sum::<f64>() / n as f64)
            .collect();
        let along = |scale: f64, worst: &[f64]| -> Vec<f64> {
            centroid
                .iter()
                .zip(worst)
                .map(|(c, w)| c + scale * (c - w))
                .collect()
        };
        let worst_x = simplex[n].1.clone();
        let reflected = along(1.0, &worst_x);
        let fr = value(&mut f, &reflected);
        evaluations += 1;
        if fr < simplex[0].0 {
            let expanded = along(2.0, &worst_x);
            let fe = value(&mut f, &expanded);
            evaluations += 1;
            simplex[n] = if fe < fr {
                (fe, expanded)
            } else {
                (fr, reflected)
            };
        } else if fr < simplex[n - 1].0 {
            simplex[n] = (fr, reflected);
        } else {
            let contracted = if fr < simplex[n].0 {
                along(0.5, &worst_x)
            } else {
                along(-0.5, &worst_x)
            };
            let fc = value(&mut f, &contracted);
            evaluations += 1;
            if fc < simplex[n].0.min(fr) {
                simplex[n] = (fc, contracted);
            } else {
                // Shrink towards the best point.
                let best_x = simplex[0].1.clone();
                for entry in simplex.iter_mut().skip(1) {
                    let x: Vec<f64> = best_x
                        .iter()
                        .zip(&entry.1)
                        .map(|(b, y)| b + 0.5 * (y - b))
                        .collect();
                    *entry = (value(&mut f, &x), x);
                    evaluations += 1;
                }
            }
        }
    }
    simplex.sort_by(|a, b| a.0.total_cmp(&b.0));
    simplex.swap_remove(0).1
}
