//! Measures the accuracy of the exact curve operations against degree and
//! prints the markdown table of docs/accuracy.md ("Curves").
//!
//! `cargo run --release -p bezjoin-core --example accuracy_curves`
//!
//! For each degree, 200 random 3D curves with coordinates in [-1, 1]; errors
//! are the largest distance at 101 parameters, relative to the largest
//! control-point coordinate. References: de Casteljau evaluation of the
//! original curve (the most stable evaluation there is).

use bezjoin_core::BezierCurve;

/// A small deterministic generator (xorshift), so the table is reproducible.
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

fn main() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    println!(
        "| degree | eval (Horner) | elevate to 2n | split at 0.3 | segment [0.2, 0.7] | extrapolate segment [0, 2] (on [0, 1]) | length vs Richardson-extrapolated polyline |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|");
    for n in [1usize, 2, 3, 5, 7, 10, 15, 20, 25, 30] {
        let mut worst = [0.0f64; 6];
        for _ in 0..200 {
            let pts: Vec<f64> = (0..(n + 1) * 3).map(|_| rng.next()).collect();
            let c = BezierCurve::new(3, n, pts).unwrap();
            let scale = c.coordinate_scale();
            let e = c.elevate_degree(2 * n).unwrap();
            let (l, r) = c.split_at(0.3).unwrap();
            let s = c.segment(0.2, 0.7).unwrap();
            let x = c.segment(0.0, 2.0).unwrap();
            for i in 0..=100 {
                let t = i as f64 / 100.0;
                let reference = c.eval_de_casteljau(t);
                let err = |v: &[f64], w: &[f64]| distance(v, w) / scale;
                worst[0] = worst[0].max(err(&c.eval(t), &reference));
                worst[1] = worst[1].max(err(&e.eval(t), &reference));
                let piece = if t <= 0.3 {
                    l.eval(t / 0.3)
                } else {
                    r.eval((t - 0.3) / 0.7)
                };
                worst[2] = worst[2].max(err(&piece, &reference));
                worst[3] = worst[3].max(err(&s.eval(t), &c.eval_de_casteljau(0.2 + 0.5 * t)));
                worst[4] = worst[4].max(err(&x.eval(t / 2.0), &reference));
            }
            // Length: inscribed polylines converge as L - c2 h^2 - c4 h^4 ...;
            // two Richardson steps on 2048/4096/8192 pieces remove both terms.
            let len = c.arc_length_default(0.0, 1.0).unwrap();
            let poly = |m: usize| -> f64 {
                let pts: Vec<Vec<f64>> = (0..=m)
                    .map(|i| c.eval_de_casteljau(i as f64 / m as f64))
                    .collect();
                pts.windows(2).map(|w| distance(&w[0], &w[1])).sum()
            };
            let (a, b, d) = (poly(2048), poly(4096), poly(8192));
            let r1 = (4.0 * b - a) / 3.0;
            let r2 = (4.0 * d - b) / 3.0;
            let reference = (16.0 * r2 - r1) / 15.0;
            worst[5] = worst[5].max((len - reference).abs() / len.max(1e-300));
        }
        println!(
            "| {n} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.1e} | {:.1e} |",
            worst[0], worst[1], worst[2], worst[3], worst[4], worst[5]
        );
    }
}

/// Euclidean distance between two points of equal dimension.
fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}
