//! The local recurrence that derives each segment's inner points from its
//! neighbour's, for C^k at every node.

use nalgebra::DMatrix;

use crate::error::{BezjoinError, Result};

use super::basis::LagrangeBasis;
use super::{BuildDirection, LagrangeOptions};

/// The recurrence's fixed data: build order, derived/free indices and the
/// inverse of its `k x k` system.
pub(super) struct Recurrence<'a> {
    pub(super) basis: &'a LagrangeBasis,
    pub(super) continuity: usize,
    pub(super) forward: bool,
    pub(super) derived: Vec<usize>,
    pub(super) inverse: DMatrix<f64>,
}

impl<'a> Recurrence<'a> {
    pub(super) fn new(basis: &'a LagrangeBasis, options: &LagrangeOptions) -> Result<Self> {
        let k = options.continuity;
        let forward = options.direction == BuildDirection::Forward;
        let derived = options.derived_indices();
        let own = if forward {
            &basis.at_start
        } else {
            &basis.at_end
        };
        let system = DMatrix::from_fn(k, k, |m, q| own[m + 1][derived[q]]);
        let inverse = system.clone().try_inverse().ok_or_else(|| {
            BezjoinError::invalid(
                "continuity",
                format!(
                    "C{k} cannot be reached by deriving inner points {derived:?} of degree {} \
                     segments (singular system)",
                    options.degree
                ),
            )
        })?;
        let condition =
            crate::linalg::norm_1(&system) * crate::linalg::norm_1(&inverse) * f64::EPSILON;
        if condition > 1e-8 {
            return Err(BezjoinError::invalid(
                "continuity",
                format!(
                    "C{k} by deriving inner points {derived:?} of degree {} segments is nearly \
                     singular (relative condition {condition:e})",
                    options.degree
                ),
            ));
        }
        Ok(Self {
            basis,
            continuity: k,
            forward,
            derived,
            inverse,
        })
    }

    /// Segment indices in build order.
    pub(super) fn order(&self, segment_count: usize) -> Vec<usize> {
        if self.forward {
            (0..segment_count).collect()
        } else {
            (0..segment_count).rev().collect()
        }
    }

    /// Fill in the derived points of every segment after the first in build
    /// order; `on_curve[s]` holds `(n + 1) * dim` values with the nodes, the
    /// starting segment's inner points and the free points already set.
    pub(super) fn fill_derived(&self, dim: usize, intervals: &[f64], on_curve: &mut [Vec<f64>]) {
        let k = self.continuity;
        let (own, neighbour) = if self.forward {
            (&self.basis.at_start, &self.basis.at_end)
        } else {
            (&self.basis.at_end, &self.basis.at_start)
        };
        let order = self.order(on_curve.len());
        let n = self.basis.degree;
        let mut rhs = DMatrix::zeros(k, 1);
        for pair in order.windows(2) {
            let (p, s) = (pair[0], pair[1]);
            let ratio = intervals[s] / intervals[p];
            for c in 0..dim {
                for m in 1..=k {
                    let neighbour_derivative: f64 = (0..=n)
                        .map(|j| neighbour[m][j] * on_curve[p][j * dim + c])
                        .sum();
                    let known: f64 = (0..=n)
                        .filter(|j| !self.derived.contains(j))
                        .map(|j| own[m][j] * on_curve[s][j * dim + c])
                        .sum();
                    rhs[(m - 1, 0)] = neighbour_derivative * ratio.powi(m as i32) - known;
                }
                let solution = &self.inverse * &rhs;
                for (q, &j) in self.derived.iter().enumerate() {
                    on_curve[s][j * dim + c] = solution[(q, 0)];
                }
            }
        }
    }

    /// Growth factor per segment: infinity-norm of the map from the starting
    /// segment's inner points to the segment's derived points.
    pub(super) fn growth(&self, intervals: &[f64]) -> Vec<f64> {
        let n = self.basis.degree;
        let count = intervals.len();
        let start = self.order(count)[0];
        let mut row_sums = vec![vec![0.0; self.derived.len()]; count];
        for unit in 1..n {
            let mut data = vec![vec![0.0; n + 1]; count];
            data[start][unit] = 1.0;
            self.fill_derived(1, intervals, &mut data);
            for s in 0..count {
                if s == start {
                    continue;
                }
                for (q, &j) in self.derived.iter().enumerate() {
                    row_sums[s][q] += data[s][j].abs();
                }
            }
        }
        row_sums
            .iter()
            .map(|r| r.iter().copied().fold(0.0, f64::max))
            .collect()
    }
}
