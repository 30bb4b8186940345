//! Curvature along arc length, `kappa(s)`, of a path of pieces (the kept
//! part of P, a rounding, the kept part of Q) for the pictures' graphs
//! ([`crate::svg::Plot`]) and for the curvature jumps at their joins.
//!
//! Every piece is sampled through [`Shape::sample_jets`] (the same samples
//! the drawing uses; in the x-y plane), its signed curvature
//! `(x' y'' - y' x'') / |r'|^3` taken from the first and second
//! derivatives, and `s` summed along the sampled points (chord lengths of
//! [`PIECE_SAMPLES`] steps per piece: for the graphs, not for reports).

use crate::svg::{Plot, PlotSeries, Role, Shape, signed_curvature};

/// Sampling steps per piece of a path.
pub const PIECE_SAMPLES: usize = 400;

/// One piece of a path.
#[derive(Debug, Clone)]
pub struct PathPiece {
    /// Its geometry.
    pub shape: Shape,
    /// Colour and style of its line in the graph.
    pub role: Role,
    /// What it is.
    pub label: String,
}

impl PathPiece {
    /// A piece of `shape` drawn in `role`.
    pub fn new(shape: Shape, role: Role, label: impl Into<String>) -> Self {
        PathPiece {
            shape,
            role,
            label: label.into(),
        }
    }
}

/// `kappa(s)` of a path: per piece its `(s, kappa)` samples, `s` running on
/// from one piece to the next (0 at the start of the first piece).
#[derive(Debug, Clone)]
pub struct CurvatureProfile {
    /// Samples per piece.
    pub pieces: Vec<Vec<[f64; 2]>>,
    /// Roles and labels of the pieces.
    pub styles: Vec<(Role, String)>,
}

impl CurvatureProfile {
    /// Sample `pieces` in order.
    pub fn new(pieces: &[PathPiece]) -> Self {
        let mut s = 0.0;
        let mut out = Vec::with_capacity(pieces.len());
        for piece in pieces {
            let jets = piece.shape.sample_jets(PIECE_SAMPLES);
            let mut samples = Vec::with_capacity(jets.len());
            let mut previous: Option<[f64; 2]> = None;
            for [p, d1, d2] in jets {
                if let Some(q) = previous {
                    s += (p[0] - q[0]).hypot(p[1] - q[1]);
                }
                previous = Some(p);
                samples.push([s, signed_curvature(d1, d2)]);
            }
            out.push(samples);
        }
        CurvatureProfile {
            pieces: out,
            styles: pieces.iter().map(|p| (p.role, p.label.clone())).collect(),
        }
    }

    /// Where the pieces meet (values of `s`).
    pub fn joins(&self) -> Vec<f64> {
        self.pieces
            .iter()
            .take(self.pieces.len().saturating_sub(1))
            .filter_map(|p| p.last().map(|x| x[0]))
            .collect()
    }

    /// `kappa` after minus `kappa` before each join.
    pub fn jumps(&self) -> Vec<f64> {
        self.pieces
            .windows(2)
            .map(|w| match (w[0].last(), w[1].first()) {
                (Some(a), Some(b)) => b[1] - a[1],
                _ => f64::NAN,
            })
            .collect()
    }

    /// Smallest and largest `kappa` over the pieces numbered `range`.
    pub fn range_of(&self, pieces: std::ops::Range<usize>) -> [f64; 2] {
        self.pieces[pieces]
            .iter()
            .flatten()
            .map(|x| x[1])
            .filter(|k| k.is_finite())
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], k| {
                [lo.min(k), hi.max(k)]
            })
    }

    /// The graph of `kappa` against `s`, dashed lines at the joins.
    pub fn plot(&self, title: impl Into<String>) -> Plot {
        Plot {
            title: title.into(),
            x_label: "arc length s".into(),
            y_label: "curvature kappa".into(),
            series: self
                .pieces
                .iter()
                .zip(&self.styles)
                .map(|(points, (role, label))| PlotSeries {
                    role: *role,
                    label: label.clone(),
                    points: points.clone(),
                })
                .collect(),
            x_marks: self.joins(),
            y_range: None,
        }
    }
}

#[cfg(test)]
mod curvature_profile_tests {
    use super::*;
    use bezjoin_core::BezierCurve;

    #[test]
    fn a_line_then_a_quarter_circle_jumps_by_one_over_the_radius() {
        let line = BezierCurve::from_rows(&[[-3.0, 0.0], [0.0, 0.0]]).unwrap();
        let arc = Shape::Arc {
            center: [0.0, 2.0],
            radius: 2.0,
            start_angle: -std::f64::consts::FRAC_PI_2,
            sweep: std::f64::consts::FRAC_PI_2,
        };
        let profile = CurvatureProfile::new(&[
            PathPiece::new(Shape::Bezier(line), Role::Input, "line"),
            PathPiece::new(arc, Role::Reference, "arc"),
        ]);
        let joins = profile.joins();
        assert_eq!(joins.len(), 1);
        assert!((joins[0] - 3.0).abs() < 1e-12);
        assert!((profile.jumps()[0] - 0.5).abs() < 1e-12);
        let end = profile.pieces[1].last().unwrap()[0];
        assert!((end - 3.0 - std::f64::consts::PI).abs() < 1e-4, "{end}");
        let [lo, hi] = profile.range_of(0..2);
        assert!(lo == 0.0 && (hi - 0.5).abs() < 1e-12, "{lo} {hi}");
    }
}
