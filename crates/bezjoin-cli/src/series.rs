//! Truncated power series: what the tool's own geometric checks are built
//! from, independently of the library's Bell polynomials.
//!
//! A series is its coefficients `a[0] + a[1] h + a[2] h^2 + ...`; every
//! operation keeps the terms up to `h^n`. A vector series is stored row by
//! row (`dim` values per coefficient). Two uses:
//!
//! - the derivatives of a curve with respect to arc length
//!   ([`arc_length_derivatives`]): `s(h) = int |r'|`, inverted to `h(s)`,
//!   composed into `r(t + h(s))`; two curves meet with G^k exactly when
//!   these agree for orders `0..=k` (the unit tangent, the curvature vector,
//!   its arc-length derivative, ...);
//! - the targets of the beta-constraints ([`reparametrised_derivatives`]):
//!   `R(t) = P(phi(t))` with `phi^(j) = beta_j`, by composing the series.

/// Taylor coefficients `d_j / j!` of derivative rows `d_j` (`dim` values
/// each, rows `0..=n`).
pub fn taylor(derivatives: &[f64], dim: usize) -> Vec<f64> {
    by_factorials(derivatives, dim, |x, f| x / f)
}

/// Derivative rows `j! c_j` of Taylor coefficient rows `c_j`.
pub fn untaylor(coefficients: &[f64], dim: usize) -> Vec<f64> {
    by_factorials(coefficients, dim, |x, f| x * f)
}

/// Row `j` (`dim` values) of `rows` combined with `j!` by `op`.
fn by_factorials(rows: &[f64], dim: usize, op: impl Fn(f64, f64) -> f64) -> Vec<f64> {
    let mut factorial = 1.0;
    let mut out = Vec::with_capacity(rows.len());
    for (j, row) in rows.chunks(dim).enumerate() {
        if j > 0 {
            factorial *= j as f64;
        }
        out.extend(row.iter().map(|&x| op(x, factorial)));
    }
    out
}

/// `a b` up to `h^n`.
pub fn mul(a: &[f64], b: &[f64], n: usize) -> Vec<f64> {
    let mut out = vec![0.0; n + 1];
    for (i, x) in a.iter().enumerate().take(n + 1) {
        for (j, y) in b.iter().enumerate().take(n + 1 - i) {
            out[i + j] += x * y;
        }
    }
    out
}

/// `sqrt(a)` up to `h^n`, for `a[0] > 0`.
pub fn sqrt(a: &[f64], n: usize) -> Vec<f64> {
    let mut out = vec![0.0; n + 1];
    out[0] = a[0].sqrt();
    for m in 1..=n {
        let cross: f64 = (1..m).map(|i| out[i] * out[m - i]).sum();
        out[m] = (a.get(m).copied().unwrap_or(0.0) - cross) / (2.0 * out[0]);
    }
    out
}

/// The inverse series `g` of `h` (`h[0] = 0`, `h[1] != 0`): `h(g(s)) = s`
/// up to `s^n`, by the fixed point `g = (s - sum_(m>=2) h_m g^m) / h_1`,
/// each round fixing one more order.
pub fn invert(h: &[f64], n: usize) -> Vec<f64> {
    let mut g = vec![0.0; n + 1];
    if n == 0 {
        return g;
    }
    g[1] = 1.0 / h[1];
    for _ in 1..n {
        let mut power = g.clone();
        let mut higher = vec![0.0; n + 1];
        for hm in h.iter().take(n + 1).skip(2) {
            power = mul(&power, &g, n);
            for (acc, p) in higher.iter_mut().zip(&power) {
                *acc += hm * p;
            }
        }
        for k in 1..=n {
            g[k] = ((k == 1) as u8 as f64 - higher[k]) / h[1];
        }
    }
    g
}

/// The vector series `sum_j c_j g^j` (rows `c_j`, `dim` values each) up to
/// `s^n`, for a scalar series `g` with `g[0] = 0`.
pub fn compose(c: &[f64], dim: usize, g: &[f64], n: usize) -> Vec<f64> {
    let mut out = vec![0.0; (n + 1) * dim];
    let mut power = vec![0.0; n + 1];
    power[0] = 1.0;
    for row in c.chunks(dim).take(n + 1) {
        for (k, p) in power.iter().enumerate() {
            for (o, x) in out[k * dim..(k + 1) * dim].iter_mut().zip(row) {
                *o += p * x;
            }
        }
        power = mul(&power, g, n);
    }
    out
}

/// The derivatives `d^j r / ds^j`, `j = 0..=n`, with respect to arc length
/// (row 0 the point, row 1 the unit tangent, row 2 the curvature vector,
/// ...) from the parametric derivative rows `r^(0..=n)` at one parameter;
/// `None` where the speed `|r'|` is zero or not finite.
pub fn arc_length_derivatives(derivatives: &[f64], dim: usize, n: usize) -> Option<Vec<f64>> {
    let c = taylor(&derivatives[..(n + 1) * dim], dim);
    if n == 0 {
        return Some(c);
    }
    // r'(t + h) = sum_m (m + 1) c_(m+1) h^m; its squared length; the speed.
    let w: Vec<Vec<f64>> = (0..n)
        .map(|m| {
            c[(m + 1) * dim..(m + 2) * dim]
                .iter()
                .map(|x| (m + 1) as f64 * x)
                .collect()
        })
        .collect();
    let squared: Vec<f64> = (0..n)
        .map(|m| {
            (0..=m)
                .map(|a| w[a].iter().zip(&w[m - a]).map(|(x, y)| x * y).sum::<f64>())
                .sum()
        })
        .collect();
    if !(squared[0] > 0.0 && squared[0].is_finite()) {
        return None;
    }
    let speed = sqrt(&squared, n - 1);
    // s(h) = int_0^h speed.
    let mut s = vec![0.0; n + 1];
    for m in 0..n {
        s[m + 1] = speed[m] / (m + 1) as f64;
    }
    let h = invert(&s, n);
    let out = untaylor(&compose(&c, dim, &h, n), dim);
    out.iter().all(|x| x.is_finite()).then_some(out)
}

/// The derivatives `R^(0..=n)` at `t0` of `R(t) = C(phi(t))` with
/// `phi(t0) = u0`, `phi^(j)(t0) = beta_j` (`beta[j - 1]`, `j = 1..=n`),
/// from `C`'s derivative rows `C^(0..=n)` at `u0`: the beta-constraints'
/// targets (Faa di Bruno's formula, by composing series).
pub fn reparametrised_derivatives(derivatives: &[f64], dim: usize, beta: &[f64]) -> Vec<f64> {
    let n = beta.len();
    let c = taylor(&derivatives[..(n + 1) * dim], dim);
    let mut g = vec![0.0; n + 1];
    let mut factorial = 1.0;
    for (j, b) in beta.iter().enumerate() {
        factorial *= (j + 1) as f64;
        g[j + 1] = b / factorial;
    }
    untaylor(&compose(&c, dim, &g, n), dim)
}

#[cfg(test)]
mod series_tests {
    use super::*;

    #[test]
    fn arc_length_derivatives_of_a_circle_are_the_frenet_ones() {
        // r(t) = (R cos(w t), R sin(w t)) at t = 0.3: unit tangent, curvature
        // vector -n / R pointing at the centre, its derivative -T / R^2.
        let (radius, w, t) = (2.5_f64, 1.7_f64, 0.3_f64);
        let a = w * t;
        let mut d = Vec::new();
        for k in 0..4 {
            let f = w.powi(k) * radius;
            let phase = a + k as f64 * std::f64::consts::FRAC_PI_2;
            d.extend([f * phase.cos(), f * phase.sin()]);
        }
        let s = arc_length_derivatives(&d, 2, 3).unwrap();
        let tangent = [-a.sin(), a.cos()];
        let inward = [-a.cos(), -a.sin()];
        for c in 0..2 {
            assert!((s[2 + c] - tangent[c]).abs() < 1e-12);
            assert!((s[4 + c] - inward[c] / radius).abs() < 1e-12);
            assert!((s[6 + c] + tangent[c] / (radius * radius)).abs() < 1e-12);
        }
    }

    #[test]
    fn reparametrisation_is_faa_di_bruno() {
        // C(u) = (u^3, u^2) at u0 = 0.5, beta = (2, 3, -1):
        // R' = b1 C', R'' = b1^2 C'' + b2 C', R''' = b1^3 C''' + 3 b1 b2 C'' + b3 C'.
        let u: f64 = 0.5;
        let d = [
            u.powi(3),
            u * u,
            3.0 * u * u,
            2.0 * u,
            6.0 * u,
            2.0,
            6.0,
            0.0,
        ];
        let (b1, b2, b3) = (2.0, 3.0, -1.0);
        let r = reparametrised_derivatives(&d, 2, &[b1, b2, b3]);
        for c in 0..2 {
            let (d1, d2, d3) = (d[2 + c], d[4 + c], d[6 + c]);
            assert!((r[2 + c] - b1 * d1).abs() < 1e-12);
            assert!((r[4 + c] - (b1 * b1 * d2 + b2 * d1)).abs() < 1e-12);
            assert!((r[6 + c] - (b1 * b1 * b1 * d3 + 3.0 * b1 * b2 * d2 + b3 * d1)).abs() < 1e-12);
        }
    }
}
