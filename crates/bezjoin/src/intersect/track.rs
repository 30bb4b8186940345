//! The two curves of an intersection search as the search sees them: a
//! [`Track`] evaluates a Bezier or NURBS curve (and its tangent) on its
//! domain and cuts it into [`Piece`]s, Bezier spans whose control points
//! bound them. A rational span is kept in homogeneous form `(w P, w)`:
//! de Casteljau halves it exactly there, and with positive weights the
//! span lies in the convex hull of its Cartesian poles `P`, so the boxes
//! of the projected poles bound it as for a polynomial piece.

use std::borrow::Cow;

use crate::bezier::{BezierCurve, distance, scaled_norm};
use crate::curve::CurveRef;
use crate::nurbs::NurbsCurve;

/// One curve of the pair.
pub(super) enum Track<'a> {
    /// A Bezier curve with its hodograph.
    Bezier {
        curve: &'a BezierCurve,
        hodograph: Cow<'a, BezierCurve>,
    },
    /// A NURBS curve (evaluated by A2.3/A4.2).
    Nurbs(&'a NurbsCurve),
}

impl<'a> Track<'a> {
    pub(super) fn new(curve: CurveRef<'a>) -> Self {
        match curve {
            CurveRef::Bezier(curve) => Track::Bezier {
                curve,
                hodograph: Cow::Owned(curve.hodograph()),
            },
            CurveRef::Nurbs(n) => Track::Nurbs(n),
        }
    }

    /// A Bezier curve with its hodograph already at hand.
    pub(crate) fn bezier(curve: &'a BezierCurve, hodograph: &'a BezierCurve) -> Self {
        Track::Bezier {
            curve,
            hodograph: Cow::Borrowed(hodograph),
        }
    }

    pub(super) fn dim(&self) -> usize {
        match self {
            Track::Bezier { curve, .. } => curve.dim(),
            Track::Nurbs(n) => n.dim(),
        }
    }

    pub(super) fn degree(&self) -> usize {
        match self {
            Track::Bezier { curve, .. } => curve.degree(),
            Track::Nurbs(n) => n.degree(),
        }
    }

    pub(super) fn domain(&self) -> (f64, f64) {
        match self {
            Track::Bezier { .. } => (0.0, 1.0),
            Track::Nurbs(n) => n.domain(),
        }
    }

    pub(super) fn coordinate_scale(&self) -> f64 {
        match self {
            Track::Bezier { curve, .. } => curve.coordinate_scale(),
            Track::Nurbs(n) => n.coordinate_scale(),
        }
    }

    pub(super) fn eval_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier { curve, .. } => curve.eval_into(u, out),
            Track::Nurbs(n) => n.point_and_tangent(u, out, None),
        }
    }

    /// [`Self::eval_into`] at a parameter of [`Self::breaks`]: a Bezier
    /// curve's ends are its first and last control points, exactly (no
    /// evaluation).
    pub(super) fn break_point_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier { curve, .. } if u == 0.0 => out.copy_from_slice(curve.point(0)),
            Track::Bezier { curve, .. } if u == 1.0 => {
                out.copy_from_slice(curve.point(curve.degree()))
            }
            _ => self.eval_into(u, out),
        }
    }

    pub(super) fn eval(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        self.eval_into(u, &mut out);
        out
    }

    /// The first derivative at `u` into `out`.
    pub(super) fn tangent_into(&self, u: f64, out: &mut [f64]) {
        match self {
            Track::Bezier { hodograph, .. } => hodograph.eval_into(u, out),
            Track::Nurbs(n) => {
                let mut point = [0.0f64; 16];
                let mut heap = Vec::new();
                let point: &mut [f64] = if n.dim() <= point.len() {
                    &mut point[..n.dim()]
                } else {
                    heap.resize(n.dim(), 0.0);
                    &mut heap
                };
                n.point_and_tangent(u, point, Some(out));
            }
        }
    }

    pub(super) fn tangent(&self, u: f64) -> Vec<f64> {
        let mut out = vec![0.0; self.dim()];
        self.tangent_into(u, &mut out);
        out
    }

    /// The parameters where pieces meet: the domain's ends and, for a
    /// NURBS curve, its interior knots (where two polynomial pieces can
    /// start or stop coinciding).
    pub(super) fn breaks(&self) -> Cow<'static, [f64]> {
        match self {
            // A Bezier curve's domain is [0, 1]: nothing to allocate.
            Track::Bezier { .. } => Cow::Borrowed(&[0.0, 1.0]),
            Track::Nurbs(n) => {
                let (a, b) = n.domain();
                let knots = n.interior_knots().0;
                let mut out = Vec::with_capacity(knots.len() + 2);
                out.push(a);
                out.extend(knots);
                out.push(b);
                Cow::Owned(out)
            }
        }
    }

    /// Number of Bezier spans.
    pub(super) fn span_count(&self) -> usize {
        match self {
            Track::Bezier { .. } => 1,
            Track::Nurbs(n) => n.span_count(),
        }
    }

    /// The curve as Bezier pieces over its domain (a Bezier curve's one
    /// piece borrows the curve: no copy).
    pub(super) fn pieces(&self) -> Vec<Piece<'a>> {
        match self {
            Track::Bezier { curve, .. } => {
                vec![Piece::new(Cow::Borrowed(*curve), false, 0.0, 1.0)]
            }
            Track::Nurbs(n) => n
                .bezier_spans()
                .into_iter()
                .map(|span| {
                    let (lo, hi) = span.domain();
                    if span.weights().is_some() {
                        let h = span.homogeneous_points();
                        let curve = BezierCurve::new(span.dim() + 1, span.degree(), h)
                            .expect("a span's homogeneous poles are a valid Bezier curve");
                        Piece::new(Cow::Owned(curve), true, lo, hi)
                    } else {
                        let curve =
                            BezierCurve::new(span.dim(), span.degree(), span.points().to_vec())
                                .expect("a span's poles are a valid Bezier curve");
                        Piece::new(Cow::Owned(curve), false, lo, hi)
                    }
                })
                .collect(),
        }
    }
}

/// A piece `curve = original|[lo, hi]` (homogeneous when `rational`) with
/// its Cartesian control points and their bounding box; a whole Bezier
/// curve is borrowed, a span or a half owned.
#[derive(Clone)]
pub(super) struct Piece<'a> {
    curve: Cow<'a, BezierCurve>,
    /// Cartesian control points of a rational piece, row-major (a
    /// polynomial piece's are the curve's own: no copy).
    projected: Option<Vec<f64>>,
    dim: usize,
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// The bounding box of the Cartesian control points: `dim` minima,
    /// then `dim` maxima (inline up to dimension [`INLINE_BOUNDS_DIM`],
    /// else one allocation).
    bounds: Bounds,
}

/// Dimensions up to which a piece's box is kept inline.
const INLINE_BOUNDS_DIM: usize = 4;

/// A piece's box: `dim` minima then `dim` maxima.
#[derive(Clone)]
enum Bounds {
    Inline([f64; 2 * INLINE_BOUNDS_DIM]),
    Heap(Vec<f64>),
}

impl Bounds {
    fn as_slice(&self) -> &[f64] {
        match self {
            Bounds::Inline(b) => b,
            Bounds::Heap(b) => b,
        }
    }

    fn as_mut_slice(&mut self) -> &mut [f64] {
        match self {
            Bounds::Inline(b) => b,
            Bounds::Heap(b) => b,
        }
    }
}

impl<'a> Piece<'a> {
    fn new(curve: Cow<'a, BezierCurve>, rational: bool, lo: f64, hi: f64) -> Self {
        let dim = if rational {
            curve.dim() - 1
        } else {
            curve.dim()
        };
        let projected: Option<Vec<f64>> = rational.then(|| {
            curve
                .points()
                .chunks_exact(dim + 1)
                .flat_map(|row| row[..dim].iter().map(move |x| x / row[dim]))
                .collect()
        });
        let mut bounds = if dim <= INLINE_BOUNDS_DIM {
            Bounds::Inline([0.0; 2 * INLINE_BOUNDS_DIM])
        } else {
            Bounds::Heap(vec![0.0; 2 * dim])
        };
        let b = bounds.as_mut_slice();
        b[..dim].fill(f64::INFINITY);
        b[dim..2 * dim].fill(f64::NEG_INFINITY);
        for row in projected
            .as_deref()
            .unwrap_or(curve.points())
            .chunks_exact(dim)
        {
            // Comparisons (a NaN is skipped, as by `f64::min` / `max`).
            for (c, &x) in row.iter().enumerate() {
                if x < b[c] {
                    b[c] = x;
                }
                if x > b[dim + c] {
                    b[dim + c] = x;
                }
            }
        }
        Self {
            curve,
            projected,
            dim,
            lo,
            hi,
            bounds,
        }
    }

    /// Lower corner of the bounding box.
    pub(super) fn min(&self) -> &[f64] {
        &self.bounds.as_slice()[..self.dim]
    }

    /// Upper corner of the bounding box.
    pub(super) fn max(&self) -> &[f64] {
        &self.bounds.as_slice()[self.dim..2 * self.dim]
    }

    pub(super) fn degree(&self) -> usize {
        self.curve.degree()
    }

    /// Cartesian control point `i`.
    pub(super) fn point(&self, i: usize) -> &[f64] {
        let points = self.projected.as_deref().unwrap_or(self.curve.points());
        &points[i * self.dim..(i + 1) * self.dim]
    }

    pub(super) fn split(&self) -> (Piece<'a>, Piece<'a>) {
        let (a, b) = self.curve.split_unchecked(0.5);
        let mid = 0.5 * (self.lo + self.hi);
        (
            Piece::new(Cow::Owned(a), self.projected.is_some(), self.lo, mid),
            Piece::new(Cow::Owned(b), self.projected.is_some(), mid, self.hi),
        )
    }

    /// Flat enough to seed Newton from the chord: control points within
    /// `max(absolute, relative_chord * chord)` of the chord.
    pub(super) fn is_flat(&self, absolute: f64, relative_chord: f64) -> bool {
        is_flat(
            self.points(),
            self.degree(),
            self.dim,
            absolute,
            relative_chord,
        )
    }

    pub(super) fn contains(&self, x: &[f64], margin: f64) -> bool {
        let (min, max) = (self.min(), self.max());
        (0..x.len()).all(|c| x[c] >= min[c] - margin && x[c] <= max[c] + margin)
    }

    /// Distance from `x` to the box (0 inside): no point of the piece is
    /// closer to `x`.
    pub(super) fn box_distance(&self, x: &[f64]) -> f64 {
        let gaps = || {
            x.iter()
                .zip(self.min().iter().zip(self.max()))
                .map(|(x, (lo, hi))| (lo - x).max(x - hi).max(0.0))
        };
        // `norm` of the gaps, without a temporary vector
        let square = gaps().map(|g| g * g).sum::<f64>();
        if square.is_normal() {
            square.sqrt()
        } else {
            scaled_norm(gaps())
        }
    }

    pub(super) fn diagonal(&self) -> f64 {
        distance(self.min(), self.max())
    }

    /// Whether the piece is a span of a rational curve.
    pub(super) fn is_rational(&self) -> bool {
        self.projected.is_some()
    }

    /// The Cartesian control points, row-major.
    pub(super) fn points(&self) -> &[f64] {
        self.projected.as_deref().unwrap_or(self.curve.points())
    }
}

/// [`Piece::is_flat`] for the degree-`n` polygon `points` (row-major,
/// `dim` coordinates).
pub(super) fn is_flat(
    points: &[f64],
    n: usize,
    dim: usize,
    absolute: f64,
    relative_chord: f64,
) -> bool {
    let chord = distance(&points[..dim], &points[n * dim..(n + 1) * dim]);
    deviation_from_chord(points, n, dim) <= absolute.max(relative_chord * chord)
}

/// Largest distance of a control point of the degree-`n` polygon `points`
/// (row-major, `dim` coordinates) from its chord (from the first point when
/// the chord is degenerate); points beyond the chord's ends count their
/// distance from the nearer end.
fn deviation_from_chord(points: &[f64], n: usize, dim: usize) -> f64 {
    let point = |i: usize| &points[i * dim..(i + 1) * dim];
    let a = point(0);
    let b = point(n);
    let len2: f64 = b.iter().zip(a).map(|(x, y)| (x - y) * (x - y)).sum();
    let mut worst = 0.0f64;
    for i in 1..n {
        let p = point(i);
        // |p - a|^2 and (p - a).(b - a), without temporaries
        let (rel2, along) = p
            .iter()
            .zip(a)
            .zip(b)
            .fold((0.0, 0.0), |(r, s), ((x, y), z)| {
                let rel = x - y;
                (r + rel * rel, s + rel * (z - y))
            });
        let dev = if len2 > 0.0 {
            let s = along / len2;
            let perp: f64 = p
                .iter()
                .zip(a)
                .zip(b)
                .map(|((x, y), z)| {
                    let d = (x - y) - s * (z - y);
                    d * d
                })
                .sum::<f64>();
            // Points beyond the chord's ends also count as deviation.
            let beyond = if s < 0.0 {
                -s
            } else if s > 1.0 {
                s - 1.0
            } else {
                0.0
            };
            (perp + beyond * beyond * len2).sqrt()
        } else {
            rel2.sqrt()
        };
        worst = worst.max(dev);
    }
    worst
}

pub(super) fn boxes_meet(a: &Piece, b: &Piece, margin: f64) -> bool {
    let (a_min, a_max, b_min, b_max) = (a.min(), a.max(), b.min(), b.max());
    (0..a_min.len()).all(|c| a_min[c] <= b_max[c] + margin && b_min[c] <= a_max[c] + margin)
}
