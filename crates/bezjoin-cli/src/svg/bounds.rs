//! Model-space bounds of a picture: the sampled curves, their control
//! polygons and the markers (the comb tips are added once the comb scale is
//! known).

use super::{Figure, marker_xy};

/// Points sampled along each curve to draw it.
const CURVE_SAMPLES: usize = 240;

/// An axis-aligned box in model coordinates.
pub(super) struct Bounds {
    pub(super) min: [f64; 2],
    pub(super) max: [f64; 2],
}

impl Bounds {
    fn empty() -> Self {
        Bounds {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        }
    }

    /// Grow to contain `p`; points with a non-finite coordinate are ignored.
    pub(super) fn add(&mut self, p: [f64; 2]) {
        if p[0].is_finite() && p[1].is_finite() {
            for ((lo, hi), v) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
                *lo = lo.min(v);
                *hi = hi.max(v);
            }
        }
    }

    /// The larger side.
    pub(super) fn size(&self) -> f64 {
        (self.max[0] - self.min[0]).max(self.max[1] - self.min[1])
    }
}

/// Every curve of `figure` sampled at about `CURVE_SAMPLES + 1` parameters
/// ([`super::Shape::sample_jets`]), projected to the picture's plane.
pub(super) fn sample_curves(figure: &Figure) -> Vec<Vec<[f64; 2]>> {
    figure
        .curves
        .iter()
        .map(|item| {
            item.shape
                .sample_jets(CURVE_SAMPLES)
                .into_iter()
                .map(|[p, _, _]| p)
                .collect()
        })
        .collect()
}

/// Bounds of the sampled curves, the control polygons that are drawn and
/// the markers; the unit square when there is nothing to bound.
pub(super) fn model_bounds(figure: &Figure, curve_points: &[Vec<[f64; 2]>]) -> Bounds {
    let mut bounds = Bounds::empty();
    for (item, pts) in figure.curves.iter().zip(curve_points) {
        pts.iter().for_each(|&p| bounds.add(p));
        if item.polygon {
            item.shape.polygon().into_iter().for_each(|p| bounds.add(p));
        }
    }
    for m in &figure.markers {
        bounds.add(marker_xy(m));
    }
    if !bounds.min[0].is_finite() {
        bounds.add([0.0, 0.0]);
        bounds.add([1.0, 1.0]);
    }
    bounds
}
