//! Curvature combs: samples of every curve's signed curvature, the one comb
//! scale of a picture, and the spike tips.

use super::{Figure, Shape, signed_curvature};

/// Samples per comb (the tip line's resolution).
pub(super) const COMB_TIP_SAMPLES: usize = 240;
/// Spikes drawn per comb.
pub(super) const COMB_SPIKES: usize = 60;
/// Longest spike, as a fraction of the drawing's larger side.
const COMB_LENGTH_FRACTION: f64 = 0.12;

/// Comb samples of one curve: (point on the curve, unit normal, signed curvature).
pub(super) type CombSamples = Vec<([f64; 2], [f64; 2], f64)>;

/// The combs of a picture, one entry per curve (`None` for a curve drawn
/// without comb).
pub(super) struct Combs {
    /// Samples along each curve.
    pub(super) samples: Vec<Option<CombSamples>>,
    /// Tip of the spike at each sample.
    pub(super) tips: Vec<Option<Vec<[f64; 2]>>>,
    /// Spike length per unit of curvature, the same for every curve.
    pub(super) scale: f64,
    /// Some spikes were shortened to the clip curvature.
    pub(super) clipped: bool,
}

impl Combs {
    /// Sample the combs of `figure` and scale them for a drawing whose
    /// larger side is `size` (model units).
    pub(super) fn new(figure: &Figure, size: f64) -> Self {
        let samples: Vec<Option<CombSamples>> = figure
            .curves
            .iter()
            .map(|item| {
                item.comb
                    .then(|| comb_samples(&item.shape, COMB_TIP_SAMPLES))
            })
            .collect();
        let (scale, clip) = comb_scale(&samples, size);
        let mut clipped = false;
        let tips = samples
            .iter()
            .map(|c| {
                c.as_ref().map(|samples| {
                    samples
                        .iter()
                        .map(|&(p, n, k)| {
                            let kk = if k.abs() > clip {
                                clipped = true;
                                clip * k.signum()
                            } else {
                                k
                            };
                            // Spike on the side away from the centre of curvature.
                            let len = -kk * scale;
                            [p[0] + n[0] * len, p[1] + n[1] * len]
                        })
                        .collect()
                })
            })
            .collect();
        Combs {
            samples,
            tips,
            scale,
            clipped,
        }
    }

    /// Every spike tip of every comb.
    pub(super) fn tips(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.tips.iter().flatten().flatten().copied()
    }
}

/// Comb samples of one curve: (point, unit normal pointing away from the
/// centre of curvature when k > 0 is left, signed curvature).
fn comb_samples(shape: &Shape, count: usize) -> CombSamples {
    shape
        .sample_jets(count)
        .into_iter()
        .map(|[p, d1, d2]| {
            let speed = d1[0].hypot(d1[1]);
            let left = if speed > 0.0 {
                [-d1[1] / speed, d1[0] / speed]
            } else {
                [0.0, 0.0]
            };
            (p, left, signed_curvature(d1, d2))
        })
        .collect()
}

/// One comb scale for the whole picture, and the curvature magnitude the
/// spikes are clipped at: the largest |k| (ignoring isolated extreme values
/// above 4x the 95th percentile, whose spikes are clipped and said so) maps
/// to `COMB_LENGTH_FRACTION` of `size`. Scale 0 when no curve bends.
fn comb_scale(combs: &[Option<CombSamples>], size: f64) -> (f64, f64) {
    let mut magnitudes: Vec<f64> = combs
        .iter()
        .flatten()
        .flat_map(|c| c.iter().map(|s| s.2.abs()))
        .filter(|k| k.is_finite())
        .collect();
    magnitudes.sort_by(f64::total_cmp);
    let max = magnitudes.last().copied().unwrap_or(0.0);
    if max == 0.0 {
        return (0.0, f64::INFINITY);
    }
    let p95 = magnitudes[(magnitudes.len() - 1) * 95 / 100];
    let reference = if max > 4.0 * p95 && p95 > 0.0 {
        4.0 * p95
    } else {
        max
    };
    (COMB_LENGTH_FRACTION * size / reference, reference)
}
