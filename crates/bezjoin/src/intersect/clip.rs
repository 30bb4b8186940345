//! The fast path of [`super::intersect`]: fat-line Bezier clipping
//! (Sederberg and Nishita, *Curve intersection using Bezier clipping*,
//! CAD 22(9), 1990) on planar polynomial and rational pieces, with fixed-capacity stack
//! buffers (no heap), followed by the same chord seeds and Newton polishing
//! as the subdivision (module documentation, steps 2 and 3).
//!
//! # Clipping
//! Let `L` be the line through the end points of a piece `B` (unit normal
//! `n`, `L = {x : n.x + c = 0}`) and `[dmin, dmax]` the range of the signed
//! distances `n.B_j + c` of B's control points, 0 included: by the convex
//! hull property B lies in that *fat line*. A point of `A` within the
//! tolerance `tol` of B therefore has distance in `[dmin - tol, dmax + tol]`
//! from `L`. The distance of `A(s)` from `L` is a polynomial with Bernstein
//! coefficients `e_i = n.A_i + c`, so its graph lies in the convex hull of
//! the points `(i / n, e_i)`; the parameters where that hull meets the band
//! are an interval `[s0, s1]` outside which no point of `A` is within `tol`
//! of `B`. `A` is cut to it (de Casteljau, from the span's own poles each
//! time), then `B` against the fat line of the new `A`, and so on. Only
//! parameters that provably hold no meeting point are discarded, so every
//! crossing the subdivision would find is kept. When a round keeps more than
//! 80 % of both parameter ranges, the larger piece is halved (two crossings,
//! or a tangency). At a transversal crossing the ranges shrink
//! quadratically.
//!
//! A rational piece (weights positive) lies in the convex hull of its
//! Cartesian control points too, so its fat line is read from them; its
//! signed distance from a line is `sum B_i w_i e_i / sum B_i w_i`, so the
//! band is met where the polynomials with coefficients `w_i (e_i - lo)`
//! and `w_i (e_i - hi)` are `>= 0` and `<= 0` respectively, and the kept
//! interval is the intersection of their hulls' extents there
//! ([`clip_rational`]). A pair with a rational piece is clipped with both
//! pieces in homogeneous form (de Casteljau on `(w x, w y, w)`).
//!
//! # Leaves and hard cases
//! When both pieces are flat (the subdivision's criterion), the crossing of
//! their chords seeds Newton on the whole curves (`Search::polish`). The
//! fast path gives up, and the caller runs the subdivision from scratch
//! instead (so its results there are the subdivision's, bit for bit), on
//! anything it cannot settle by the arguments above alone: a dimension
//! other than 2, a weight that is not positive and finite, degree 0 or above [`MAX_DEGREE`], an
//! overlap, chords that are nearly parallel, a hit whose tangents make an
//! angle with sine at most `SURELY_TRANSVERSAL_SINE` (a tangency or
//! near-tangency), a polished hit outside its leaf's parameter box, or more
//! than [`MAX_PAIRS`] pairs, [`STACK`] pending pairs, `max_box_pairs` or
//! `max_depth`.

use super::track::{Piece, is_flat};
use super::{Candidate, RELATIVE_CHORD_FLATNESS, SURELY_TRANSVERSAL_SINE, Search, chord_crossing};
use std::cmp::Ordering;

/// Highest degree the fast path takes (its buffers hold `MAX_DEGREE + 1`
/// control points).
pub(super) const MAX_DEGREE: usize = 15;
/// Pending piece pairs per span pair (halves waiting to be clipped).
const STACK: usize = 32;
/// Clipping rounds (over all span pairs) before the fast path gives up.
const MAX_PAIRS: usize = 512;
/// A round that keeps more than this share of both ranges halves a piece.
const SPLIT_RATIO: f64 = 0.8;

/// Capacity (control points) of the buffers for pieces up to degree 3,
/// the common case: a quarter of the general buffers, so a piece is copied
/// and scanned in 64 bytes rather than 256.
const SMALL: usize = 4;
/// Capacity of the general buffers (`MAX_DEGREE + 1` control points).
const LARGE: usize = MAX_DEGREE + 1;

/// A planar polynomial Bezier piece of degree `n < N`, its control points
/// `[x, y]` in a buffer of capacity `N` ([`SMALL`] or [`LARGE`]; the
/// arithmetic does not depend on `N`).
#[derive(Clone, Copy)]
struct Poly<const N: usize> {
    n: usize,
    points: [[f64; 2]; N],
}

impl<const N: usize> Poly<N> {
    fn from_piece(piece: &Piece) -> Option<Poly<N>> {
        let n = piece.degree();
        if piece.is_rational() || n == 0 || n >= N {
            return None;
        }
        let mut points = [[0.0; 2]; N];
        for (point, row) in points
            .iter_mut()
            .zip(piece.points().chunks_exact(2))
            .take(n + 1)
        {
            point.copy_from_slice(row);
        }
        Some(Poly { n, points })
    }

    fn x(&self, i: usize) -> f64 {
        self.points[i][0]
    }

    fn y(&self, i: usize) -> f64 {
        self.points[i][1]
    }

    fn point(&self, i: usize) -> &[f64] {
        &self.points[i]
    }

    fn used(&self) -> &[f64] {
        self.points[..=self.n].as_flattened()
    }

    /// `self` becomes the piece on `[0, t]` (de Casteljau in place: after
    /// step `r`, point `i >= r` holds level `r`'s point `i - r`, so point
    /// `r` is final; the same operations as the textbook triangle).
    fn keep_left(&mut self, t: f64) {
        match self.n.min(N - 1) {
            3 => self.keep_left_n(3, t),
            n => self.keep_left_n(n, t),
        }
    }

    /// [`Self::keep_left`] of degree `n` (inlined: a constant `n`, the
    /// cubic's, unrolls it).
    #[inline(always)]
    fn keep_left_n(&mut self, n: usize, t: f64) {
        keep_left_rows(&mut self.points, n, t);
    }

    /// `self` becomes the piece on `[s, 1]` (de Casteljau in place: after
    /// step `r`, point `n - r` is final).
    fn keep_right(&mut self, s: f64) {
        match self.n.min(N - 1) {
            3 => self.keep_right_n(3, s),
            n => self.keep_right_n(n, s),
        }
    }

    /// [`Self::keep_right`] of degree `n` (see [`Self::keep_left_n`]).
    #[inline(always)]
    fn keep_right_n(&mut self, n: usize, s: f64) {
        keep_right_rows(&mut self.points, n, s);
    }

    /// The piece on `[s, t]`, `0 <= s < t <= 1`.
    fn segment(&self, s: f64, t: f64) -> Poly<N> {
        let mut out = *self;
        if t < 1.0 {
            out.keep_left(t);
        }
        if s > 0.0 {
            out.keep_right(s / t);
        }
        out
    }

    /// [`is_flat`] for a planar piece, on squared distances (no square
    /// roots): the control points' distances from the chord (from its
    /// nearer end beyond its ends) within `max(absolute, relative_chord *
    /// chord)`. Squares that are not normal numbers (overflow, underflow,
    /// a degenerate chord) take the general [`is_flat`].
    fn is_flat(&self, absolute: f64, relative_chord: f64) -> bool {
        match self.n.min(N - 1) {
            3 => self.is_flat_n(3, absolute, relative_chord),
            n => self.is_flat_n(n, absolute, relative_chord),
        }
    }

    /// [`Self::is_flat`] of degree `n` (see [`Self::keep_left_n`]).
    #[inline(always)]
    fn is_flat_n(&self, n: usize, absolute: f64, relative_chord: f64) -> bool {
        let (ax, ay) = (self.x(0), self.y(0));
        let (dx, dy) = (self.x(n) - ax, self.y(n) - ay);
        let len2 = dx * dx + dy * dy;
        if !len2.is_normal() {
            return is_flat(self.used(), n, 2, absolute, relative_chord);
        }
        let bound = absolute.max(relative_chord * len2.sqrt());
        let bound2 = bound * bound;
        for i in 1..n {
            let (rx, ry) = (self.x(i) - ax, self.y(i) - ay);
            let s = (rx * dx + ry * dy) / len2;
            let (px, py) = (rx - s * dx, ry - s * dy);
            let beyond = if s < 0.0 {
                -s
            } else if s > 1.0 {
                s - 1.0
            } else {
                0.0
            };
            let dev2 = px * px + py * py + beyond * beyond * len2;
            if !dev2.is_finite() {
                return is_flat(self.used(), n, 2, absolute, relative_chord);
            }
            if dev2 > bound2 {
                return false;
            }
        }
        true
    }

    /// Bounding box of the control points: `(min x, min y, max x, max y)`
    /// (by comparisons: a NaN coordinate leaves the box as `f64::min` and
    /// `f64::max` would, ignored).
    fn bounds(&self) -> [f64; 4] {
        match self.n.min(N - 1) {
            3 => self.bounds_n(3),
            n => self.bounds_n(n),
        }
    }

    /// [`Self::bounds`] of degree `n` (see [`Self::keep_left_n`]).
    #[inline(always)]
    fn bounds_n(&self, n: usize) -> [f64; 4] {
        let mut b = [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        for p in &self.points[..=n] {
            let (x, y) = (p[0], p[1]);
            if x < b[0] {
                b[0] = x;
            }
            if y < b[1] {
                b[1] = y;
            }
            if x > b[2] {
                b[2] = x;
            }
            if y > b[3] {
                b[3] = y;
            }
        }
        b
    }

    fn diagonal(&self) -> f64 {
        let b = self.bounds();
        (b[2] - b[0]).hypot(b[3] - b[1])
    }
}

/// The rows `p[0..=n]` (`K` coordinates each: Cartesian, or homogeneous)
/// become the piece on `[0, t]`, de Casteljau in place: after step `r`,
/// row `i >= r` holds level `r`'s point `i - r`, so row `r` is final.
#[inline(always)]
fn keep_left_rows<const K: usize>(p: &mut [[f64; K]], n: usize, t: f64) {
    for r in 1..=n {
        for i in (r..=n).rev() {
            let prev = p[i - 1];
            for (x, y) in p[i].iter_mut().zip(prev) {
                *x = y + t * (*x - y);
            }
        }
    }
}

/// The rows `p[0..=n]` become the piece on `[s, 1]`, de Casteljau in place
/// (after step `r`, row `n - r` is final).
#[inline(always)]
fn keep_right_rows<const K: usize>(p: &mut [[f64; K]], n: usize, s: f64) {
    for r in 1..=n {
        for i in 0..=n - r {
            let next = p[i + 1];
            for (x, y) in p[i].iter_mut().zip(next) {
                *x += s * (y - *x);
            }
        }
    }
}

/// A planar rational Bezier piece of degree `n < N`: its homogeneous
/// control points `(w x, w y, w)` (weights positive) and their Cartesian
/// projections `(x, y)` as a [`Poly`], on which the box, the flatness and
/// the chord are read (a rational piece with positive weights lies in the
/// convex hull of its Cartesian control points, and passes through the
/// first and the last).
#[derive(Clone, Copy)]
struct RationalPoly<const N: usize> {
    homogeneous: [[f64; 3]; N],
    projected: Poly<N>,
}

impl<const N: usize> RationalPoly<N> {
    /// A rational piece, or a polynomial one with unit weights (a pair with
    /// one rational piece is clipped in this form on both sides).
    #[inline(always)]
    fn from_piece(piece: &Piece) -> Option<RationalPoly<N>> {
        let n = piece.degree();
        if n == 0 || n >= N || piece.dim() != 2 {
            return None;
        }
        // Cubics with the degree as a constant: the same rows and checks.
        match n {
            3 => Self::from_piece_n(piece, 3),
            n => Self::from_piece_n(piece, n),
        }
    }

    /// [`Self::from_piece`] of degree `n` (`0 < n < N`, the plane).
    #[inline(always)]
    fn from_piece_n(piece: &Piece, n: usize) -> Option<RationalPoly<N>> {
        let mut homogeneous = [[0.0; 3]; N];
        match piece.homogeneous() {
            Some(rows) => {
                let rows = &rows[..3 * (n + 1)];
                for (h, row) in homogeneous.iter_mut().zip(rows.chunks_exact(3)) {
                    if !(row[2] > 0.0 && row[2].is_finite()) {
                        return None;
                    }
                    *h = [row[0], row[1], row[2]];
                }
            }
            None => {
                let rows = &piece.points()[..2 * (n + 1)];
                for (h, row) in homogeneous.iter_mut().zip(rows.chunks_exact(2)) {
                    *h = [row[0], row[1], 1.0];
                }
            }
        }
        let mut projected = Poly {
            n,
            points: [[0.0; 2]; N],
        };
        // The projections as the piece's own (`x / w`, the subdivision's).
        for (p, h) in projected.points.iter_mut().zip(&homogeneous).take(n + 1) {
            *p = [h[0] / h[2], h[1] / h[2]];
        }
        Some(RationalPoly {
            homogeneous,
            projected,
        })
    }

    /// The piece on `[s, t]`, `0 <= s < t <= 1`: de Casteljau on the
    /// homogeneous points (as [`Poly::segment`] on the Cartesian ones),
    /// then projected. Inlined into the clipping loop, which keeps the
    /// result (a copy of about 170 bytes otherwise).
    #[inline(always)]
    fn segment(&self, s: f64, t: f64) -> RationalPoly<N> {
        // Cubics with the degree as a constant: the same operations.
        match self.projected.n {
            3 => self.segment_n(3, s, t),
            n => self.segment_n(n, s, t),
        }
    }

    /// [`Self::segment`] of degree `n` (`self.projected.n`).
    #[inline(always)]
    fn segment_n(&self, n: usize, s: f64, t: f64) -> RationalPoly<N> {
        if t >= 1.0 && s <= 0.0 {
            // Nothing cut (the whole piece, as a clipping pair starts):
            // the rows and their projections are `self`'s, computed by the
            // same divisions.
            return *self;
        }
        let mut h = self.homogeneous;
        if t < 1.0 {
            keep_left_rows(&mut h, n, t);
        }
        if s > 0.0 {
            keep_right_rows(&mut h, n, s / t);
        }
        let mut projected = self.projected;
        for (p, row) in projected.points.iter_mut().zip(&h).take(n + 1) {
            *p = [row[0] / row[2], row[1] / row[2]];
        }
        RationalPoly {
            homogeneous: h,
            projected,
        }
    }
}

/// What [`Search::clip_spans`] needs of a piece: the polynomial [`Poly`]
/// and the rational [`RationalPoly`].
trait Clippable<const N: usize>: Copy {
    /// The piece in this form (`None`: not one the clipping takes).
    fn from_piece(piece: &Piece) -> Option<Self>;
    /// The Cartesian control points (box, flatness, chord).
    fn cartesian(&self) -> &Poly<N>;
    fn segment(&self, s: f64, t: f64) -> Self;
    /// The parameter interval outside which no point of `self` is within
    /// `margin` of `other` ([`clip`]).
    fn clip_against(&self, other: &Self, margin: f64) -> Option<(f64, f64)>;
}

impl<const N: usize> Clippable<N> for Poly<N> {
    fn from_piece(piece: &Piece) -> Option<Self> {
        Poly::from_piece(piece)
    }
    fn cartesian(&self) -> &Poly<N> {
        self
    }
    fn segment(&self, s: f64, t: f64) -> Self {
        Poly::segment(self, s, t)
    }
    fn clip_against(&self, other: &Self, margin: f64) -> Option<(f64, f64)> {
        clip(self, other, margin)
    }
}

impl<const N: usize> Clippable<N> for RationalPoly<N> {
    #[inline(always)]
    fn from_piece(piece: &Piece) -> Option<Self> {
        RationalPoly::from_piece(piece)
    }
    fn cartesian(&self) -> &Poly<N> {
        &self.projected
    }
    #[inline(always)]
    fn segment(&self, s: f64, t: f64) -> Self {
        RationalPoly::segment(self, s, t)
    }
    fn clip_against(&self, other: &Self, margin: f64) -> Option<(f64, f64)> {
        clip_rational(self, other, margin)
    }
}

/// [`clip`] for rational pieces. `other` lies in its fat line (the convex
/// hull of its Cartesian control points, weights positive). The signed
/// distance of `a(s)` from the line is `d(s) = sum B_i(s) w_i e_i / w(s)`
/// (`e_i` the distances of `a`'s Cartesian control points, `w(s) > 0`), so
/// `lo <= d(s) <= hi` exactly where the polynomials with Bernstein
/// coefficients `w_i (e_i - lo)` and `w_i (e_i - hi)` are `>= 0` and `<=
/// 0`: the interval is the intersection of the `t`-extents of their
/// hulls within those half-planes. `Some((0, 1))` (nothing cut) when a
/// coefficient is not finite.
fn clip_rational<const N: usize>(
    a: &RationalPoly<N>,
    b: &RationalPoly<N>,
    margin: f64,
) -> Option<(f64, f64)> {
    // Cubics with the degrees as constants (unrolled): the same operations.
    match (a.projected.n.min(N - 1), b.projected.n.min(N - 1)) {
        (3, 3) => clip_rational_n(a, 3, b, 3, margin),
        (n, m) => clip_rational_n(a, n, b, m, margin),
    }
}

/// [`clip_rational`] for `a` of degree `n` and `b` of degree `m`.
#[inline(always)]
fn clip_rational_n<const N: usize>(
    a: &RationalPoly<N>,
    n: usize,
    b: &RationalPoly<N>,
    m: usize,
    margin: f64,
) -> Option<(f64, f64)> {
    let mut e = [0.0; N];
    let Some((lo, hi)) = distances(&a.projected, n, &b.projected, m, margin, &mut e) else {
        return Some((0.0, 1.0));
    };
    let (mut above, mut below) = ([0.0; N], [0.0; N]);
    for i in 0..=n {
        let w = a.homogeneous[i][2];
        above[i] = w * (e[i] - lo);
        below[i] = w * (e[i] - hi);
        if !(above[i].is_finite() && below[i].is_finite()) {
            return Some((0.0, 1.0));
        }
    }
    let (s0, s1) = hull_extent(&above[..=n], 0.0, f64::INFINITY)?;
    let (r0, r1) = hull_extent(&below[..=n], f64::NEG_INFINITY, 0.0)?;
    let (t0, t1) = (s0.max(r0), s1.min(r1));
    if t0 > t1 {
        return None;
    }
    let slack = 8.0 * f64::EPSILON * (n + 1) as f64;
    Some(((t0 - slack).max(0.0), (t1 + slack).min(1.0)))
}

fn boxes_meet<const N: usize>(a: &Poly<N>, b: &Poly<N>, margin: f64) -> bool {
    let (p, q) = (a.bounds(), b.bounds());
    p[0] <= q[2] + margin && q[0] <= p[2] + margin && p[1] <= q[3] + margin && q[1] <= p[3] + margin
}

/// The parameter interval of `a` (in `[0, 1]`) outside which no point of
/// `a` is within `margin` of `b` (module documentation), `None` when there
/// is none; `Some((0, 1))` when `b`'s chord is degenerate (no line to clip
/// against).
fn clip<const N: usize>(a: &Poly<N>, b: &Poly<N>, margin: f64) -> Option<(f64, f64)> {
    match (a.n.min(N - 1), b.n.min(N - 1)) {
        (3, 3) => clip_n(a, 3, b, 3, margin),
        (n, m) => clip_n(a, n, b, m, margin),
    }
}

/// The fat line of `b` (degree `m`) and the signed distances from its
/// line of `a`'s control points (degree `n`) into `e`, scaled alike: the
/// band `(lo, hi)` of [`clip`] (the fat line widened by `margin`). `None`
/// when `b`'s chord is degenerate (no line to clip against).
#[inline(always)]
fn distances<const N: usize>(
    a: &Poly<N>,
    n: usize,
    b: &Poly<N>,
    m: usize,
    margin: f64,
    e: &mut [f64; N],
) -> Option<(f64, f64)> {
    let (dx, dy) = (b.x(m) - b.x(0), b.y(m) - b.y(0));
    // The normal `(-dy, dx)` is first taken unnormalised: every signed
    // distance and the margin are scaled by `len` alike (one square root,
    // no divisions). Should a product overflow, the unit normal is taken.
    let len2 = dx * dx + dy * dy;
    let len = if len2.is_normal() {
        len2.sqrt()
    } else {
        dx.hypot(dy)
    };
    if !(len > 0.0 && len.is_finite()) {
        return None;
    }
    let mut scale = 1.0;
    // At most two passes: unnormalised, then (a product overflowed) with
    // the unit normal. A flag, not `scale != 1.0`: when `len == 1` the unit
    // normal is the first one, and the test never ended (fuzz finding F11).
    let mut unit = false;
    let (lo, hi) = loop {
        let (nx, ny) = (-dy * scale, dx * scale);
        let c = -(nx * b.x(0) + ny * b.y(0));
        let (mut dmin, mut dmax) = (0.0f64, 0.0f64);
        for j in 1..m {
            let d = nx * b.x(j) + ny * b.y(j) + c;
            dmin = dmin.min(d);
            dmax = dmax.max(d);
        }
        let widened = margin * len * scale;
        let (lo, hi) = (dmin - widened, dmax + widened);
        let mut finite = lo.is_finite() && hi.is_finite();
        for (e, p) in e.iter_mut().zip(&a.points).take(n + 1) {
            *e = nx * p[0] + ny * p[1] + c;
            finite &= e.is_finite();
        }
        if finite || unit {
            break (lo, hi);
        }
        unit = true;
        scale = 1.0 / len;
    };
    Some((lo, hi))
}

/// [`clip`] for `a` of degree `n` and `b` of degree `m` (inlined: the
/// cubics' constant degrees unroll it).
#[inline(always)]
fn clip_n<const N: usize>(
    a: &Poly<N>,
    n: usize,
    b: &Poly<N>,
    m: usize,
    margin: f64,
) -> Option<(f64, f64)> {
    let mut e = [0.0; N];
    let Some((lo, hi)) = distances(a, n, b, m, margin, &mut e) else {
        return Some((0.0, 1.0));
    };
    let (t0, t1) = hull_extent(&e[..=n], lo, hi)?;
    // A margin for the rounding of the crossings above.
    let slack = 8.0 * f64::EPSILON * (n + 1) as f64;
    Some(((t0 - slack).max(0.0), (t1 + slack).min(1.0)))
}

/// The `t`-extent of `hull({(i / n, e_i)})` (`n + 1 = e.len()` values)
/// within the band `lo <= y <= hi` (either end may be infinite), `None`
/// when the hull misses the band: its extreme points are control points
/// inside the band or crossings of the band's edges by segments between
/// two control points (every hull edge is one, and every such segment lies
/// in the hull).
#[inline(always)]
fn hull_extent(e: &[f64], lo: f64, hi: f64) -> Option<(f64, f64)> {
    let n = e.len() - 1;
    let (mut t0, mut t1) = (f64::INFINITY, f64::NEG_INFINITY);
    // (Comparisons rather than `min`/`max`: a NaN `t` is skipped either way.)
    let mut take = |t: f64| {
        if t < t0 {
            t0 = t;
        }
        if t > t1 {
            t1 = t;
        }
    };
    // The abscissae `i / n`, each divided once.
    let nf = n as f64;
    let mut ts = [0.0; LARGE];
    for (i, t) in ts.iter_mut().enumerate().take(n + 1) {
        *t = i as f64 / nf;
    }
    for i in 0..=n {
        let (ti, ei) = (ts[i], e[i]);
        if ei >= lo && ei <= hi {
            take(ti);
        }
        for j in i + 1..=n {
            let (tj, ej) = (ts[j], e[j]);
            if (ei - lo) * (ej - lo) < 0.0 {
                let w = (lo - ei) / (ej - ei);
                take(ti + w * (tj - ti));
            }
            if (ei - hi) * (ej - hi) < 0.0 {
                let w = (hi - ei) / (ej - ei);
                take(ti + w * (tj - ti));
            }
        }
    }
    if t0 > t1 || t0.is_nan() || t1.is_nan() {
        return None;
    }
    Some((t0, t1))
}

/// A pending pair: parameter ranges `[s0, s1]` on the P span and
/// `[t0, t1]` on the Q span (span-local, in `[0, 1]`) and the depth.
#[derive(Clone, Copy)]
struct Pending {
    s: (f64, f64),
    t: (f64, f64),
    depth: usize,
}

impl Search<'_> {
    /// The fast path: every crossing of the curves into the candidates, or
    /// `false` (candidates cleared) when the caller must run the
    /// subdivision (module documentation of this file).
    pub(super) fn clip_search(&mut self) -> bool {
        let done = self.pair.p.dim() == 2 && self.overlaps.is_empty() && self.clip_all();
        if !done {
            self.candidates.clear();
        }
        done
    }

    fn clip_all(&mut self) -> bool {
        let mut rounds = 0usize;
        for i in 0..self.p_pieces.len() {
            for j in 0..self.q_pieces.len() {
                // The pieces are read (copied into the clipping buffers)
                // before the search borrows `self` mutably.
                let (a, b) = (&self.p_pieces[i], &self.q_pieces[j]);
                if !super::track::boxes_meet(a, b, self.tolerance) {
                    continue;
                }
                let (u_span, v_span) = ((a.lo, a.hi), (b.lo, b.hi));
                let small = a.degree() < SMALL && b.degree() < SMALL;
                // A pair with a rational piece: both in homogeneous form (a
                // polynomial one with unit weights).
                let clipped = match (a.is_rational() || b.is_rational(), small) {
                    (true, true) => self.clip_pair::<SMALL, RationalPoly<SMALL>>(
                        i,
                        j,
                        u_span,
                        v_span,
                        &mut rounds,
                    ),
                    (true, false) => self.clip_pair::<LARGE, RationalPoly<LARGE>>(
                        i,
                        j,
                        u_span,
                        v_span,
                        &mut rounds,
                    ),
                    (false, true) => {
                        self.clip_pair::<SMALL, Poly<SMALL>>(i, j, u_span, v_span, &mut rounds)
                    }
                    (false, false) => {
                        self.clip_pair::<LARGE, Poly<LARGE>>(i, j, u_span, v_span, &mut rounds)
                    }
                };
                if !clipped {
                    return false;
                }
            }
        }
        true
    }

    /// [`Self::clip_spans`] on P's piece `i` and Q's piece `j` in the form
    /// `P` (copied into its buffers first); `false` (give up) when either
    /// is not one that form takes.
    fn clip_pair<const N: usize, P: Clippable<N>>(
        &mut self,
        i: usize,
        j: usize,
        u_span: (f64, f64),
        v_span: (f64, f64),
        rounds: &mut usize,
    ) -> bool {
        match (
            P::from_piece(&self.p_pieces[i]),
            P::from_piece(&self.q_pieces[j]),
        ) {
            (Some(pa), Some(pb)) => self.clip_spans(&pa, u_span, &pb, v_span, rounds),
            _ => false,
        }
    }

    /// Clipping on one pair of spans (`pa` on `[u_lo, u_hi]` of P, `pb` on
    /// `[v_lo, v_hi]` of Q); `false` to give up.
    fn clip_spans<const N: usize, P: Clippable<N>>(
        &mut self,
        pa: &P,
        u_span: (f64, f64),
        pb: &P,
        v_span: (f64, f64),
        rounds: &mut usize,
    ) -> bool {
        let margin = self.tolerance;
        let budget = MAX_PAIRS.min(self.options.max_box_pairs);
        let mut stack = [Pending {
            s: (0.0, 1.0),
            t: (0.0, 1.0),
            depth: 0,
        }; STACK];
        let mut pending = 1usize;
        while pending > 0 {
            pending -= 1;
            let Pending {
                mut s,
                mut t,
                mut depth,
            } = stack[pending];
            // The pieces on the current ranges, each cut from its span.
            let mut a = pa.segment(s.0, s.1);
            let mut b = pb.segment(t.0, t.1);
            loop {
                *rounds += 1;
                if *rounds > budget || depth > self.options.max_depth {
                    return false;
                }
                if !boxes_meet(a.cartesian(), b.cartesian(), margin) {
                    break;
                }
                let flat_a = a
                    .cartesian()
                    .is_flat(self.flatness, RELATIVE_CHORD_FLATNESS);
                let flat_b = flat_a
                    && b.cartesian()
                        .is_flat(self.flatness, RELATIVE_CHORD_FLATNESS);
                if flat_a && flat_b {
                    let to_u = |x: f64| u_span.0 + x * (u_span.1 - u_span.0);
                    let to_v = |x: f64| v_span.0 + x * (v_span.1 - v_span.0);
                    let u_box = (to_u(s.0), to_u(s.1));
                    let v_box = (to_v(t.0), to_v(t.1));
                    if !self.clip_leaf(a.cartesian(), u_box, b.cartesian(), v_box) {
                        return false;
                    }
                    break;
                }
                // A against B's fat line, then B against the new A's.
                let Some((c0, c1)) = a.clip_against(&b, margin) else {
                    break;
                };
                let new_s = (s.0 + c0 * (s.1 - s.0), s.0 + c1 * (s.1 - s.0));
                if new_s.0.partial_cmp(&new_s.1) != Some(Ordering::Less) {
                    // A range shrunk to a point: no room for the pieces.
                    return false;
                }
                if (c0, c1) != (0.0, 1.0) {
                    a = pa.segment(new_s.0, new_s.1);
                }
                let Some((d0, d1)) = b.clip_against(&a, margin) else {
                    break;
                };
                let new_t = (t.0 + d0 * (t.1 - t.0), t.0 + d1 * (t.1 - t.0));
                if new_t.0.partial_cmp(&new_t.1) != Some(Ordering::Less) {
                    return false;
                }
                if (d0, d1) != (0.0, 1.0) {
                    b = pb.segment(new_t.0, new_t.1);
                }
                let kept_a = (new_s.1 - new_s.0) / (s.1 - s.0);
                let kept_b = (new_t.1 - new_t.0) / (t.1 - t.0);
                s = new_s;
                t = new_t;
                if kept_a > SPLIT_RATIO && kept_b > SPLIT_RATIO {
                    // Halve the larger piece: the half with smaller
                    // parameters is clipped on, the other waits.
                    if pending == STACK {
                        return false;
                    }
                    depth += 1;
                    if a.cartesian().diagonal() >= b.cartesian().diagonal() {
                        let mid = 0.5 * (s.0 + s.1);
                        stack[pending] = Pending {
                            s: (mid, s.1),
                            t,
                            depth,
                        };
                        s = (s.0, mid);
                        a = pa.segment(s.0, s.1);
                    } else {
                        let mid = 0.5 * (t.0 + t.1);
                        stack[pending] = Pending {
                            s,
                            t: (mid, t.1),
                            depth,
                        };
                        t = (t.0, mid);
                        b = pb.segment(t.0, t.1);
                    }
                    pending += 1;
                }
            }
        }
        true
    }

    /// The leaf of a flat pair `a` (parameters `u_box` on P) and `b`
    /// (`v_box` on Q): the seed at the crossing of the chords, polished on
    /// the whole curves, into the candidates when within the tolerance;
    /// `false` (give up) for nearly parallel chords, a polished hit outside
    /// the leaf's box, or a hit that is not surely transversal.
    fn clip_leaf<const N: usize>(
        &mut self,
        a: &Poly<N>,
        u_box: (f64, f64),
        b: &Poly<N>,
        v_box: (f64, f64),
    ) -> bool {
        let Some((s, t)) = chord_crossing(a.point(0), a.point(a.n), b.point(0), b.point(b.n))
        else {
            return false;
        };
        if self.known_in(u_box.0, u_box.1, v_box.0, v_box.1) {
            return true;
        }
        let u = u_box.0 + s * (u_box.1 - u_box.0);
        let v = v_box.0 + t * (v_box.1 - v_box.0);
        let mut tangents = [0.0; 4];
        let (u, v, d, known) = self.pair.polish_with_tangents(u, v, &mut tangents);
        if d > self.tolerance {
            return true;
        }
        // The hit must be this leaf's (a crossing elsewhere means Newton
        // wandered: the leaf's own crossing is not certain).
        let room_u = 0.01 * (u_box.1 - u_box.0) + 1e-9 * self.units.0;
        let room_v = 0.01 * (v_box.1 - v_box.0) + 1e-9 * self.units.1;
        if u < u_box.0 - room_u
            || u > u_box.1 + room_u
            || v < v_box.0 - room_v
            || v > v_box.1 + room_v
        {
            return false;
        }
        if !known {
            let (ta, tb) = tangents.split_at_mut(2);
            self.pair.p.tangent_into(u, ta);
            self.pair.q.tangent_into(v, tb);
        }
        let (ta, tb) = (&tangents[..2], &tangents[2..]);
        let cross = ta[0] * tb[1] - ta[1] * tb[0];
        let sizes = ta[0].hypot(ta[1]) * tb[0].hypot(tb[1]);
        if cross.abs().partial_cmp(&(SURELY_TRANSVERSAL_SINE * sizes)) != Some(Ordering::Greater) {
            return false;
        }
        self.candidates.push(Candidate {
            u,
            v,
            distance: d,
            tangents: Some(tangents),
        });
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::{
        IntersectOptions, Intersection, IntersectionKind, intersect, intersect_by_clipping,
        intersect_by_subdivision,
    };
    use crate::bezier::BezierCurve;
    use crate::curve::CurveRef;
    use crate::nurbs::NurbsCurve;

    /// Fuzz finding F11: a chord of length exactly 1 whose signed
    /// distances overflow. The retry with the unit normal was decided by
    /// `scale != 1.0`, which stays false when `len == 1`, so the loop never
    /// ended; now two passes at most, and the clip answers (on a thread
    /// with a deadline, so that a return of the hang fails instead of
    /// hanging the test run).
    #[test]
    fn clip_with_a_unit_chord_and_overflowing_distances_ends() {
        let (sender, receiver) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            let b = super::Poly::<{ super::SMALL }> {
                n: 2,
                points: [[0.0, -1.7e308], [0.5, 1.0e308], [1.0, -1.7e308], [0.0, 0.0]],
            };
            let a = super::Poly::<{ super::SMALL }> {
                n: 2,
                points: [[0.0, 1.7e308], [0.5, 0.0], [1.0, 1.7e308], [0.0, 0.0]],
            };
            // The chord of b: (1, 0), length 1 exactly; a's distances from
            // it, 1.7e308 + 1.7e308, overflow in both passes.
            sender.send(super::clip(&a, &b, 1e-9)).unwrap();
        });
        let result = receiver
            .recv_timeout(std::time::Duration::from_secs(20))
            .expect("clip ended within 20 s");
        // No claim about the clipped range of such a pair; it must answer.
        let _ = result;
    }

    /// Fixed-seed linear congruential generator (Knuth's MMIX constants).
    struct Lcg(u64);

    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            lo + (hi - lo) * self.next()
        }
    }

    fn random_bezier(rng: &mut Lcg, degree: usize) -> BezierCurve {
        let points: Vec<f64> = (0..2 * (degree + 1))
            .map(|_| rng.range(-1.0, 1.0))
            .collect();
        BezierCurve::new(2, degree, points).unwrap()
    }

    /// A cubic B-spline with `poles` poles on uniform interior knots,
    /// rational with weights in `[0.5, 2]` when asked.
    fn random_nurbs(rng: &mut Lcg, poles: usize, rational: bool) -> NurbsCurve {
        let degree = 3;
        let points: Vec<f64> = (0..2 * poles).map(|_| rng.range(-1.0, 1.0)).collect();
        let weights = rational.then(|| (0..poles).map(|_| rng.range(0.5, 2.0)).collect());
        let spans = poles - degree;
        let mut knots = vec![0.0; degree + 1];
        knots.extend((1..spans).map(|k| k as f64 / spans as f64));
        knots.extend(vec![1.0; degree + 1]);
        NurbsCurve::new(2, degree, points, weights, knots).unwrap()
    }

    /// `fast` and `reference` report the same hits: same kinds, parameters
    /// within `1e-9` of the domains (Newton-polished crossings agree to
    /// rounding; the tolerance covers both polishings' stopping points),
    /// distances within the tolerance.
    fn assert_same(fast: &[Intersection], reference: &[Intersection], what: &str) {
        assert_eq!(
            fast.len(),
            reference.len(),
            "{what}: {fast:?} vs {reference:?}"
        );
        for (a, b) in fast.iter().zip(reference) {
            assert_eq!(a.kind, b.kind, "{what}: {a:?} vs {b:?}");
            assert!((a.u - b.u).abs() <= 1e-9, "{what}: {a:?} vs {b:?}");
            assert!((a.v - b.v).abs() <= 1e-9, "{what}: {a:?} vs {b:?}");
        }
    }

    fn compare<'a>(p: impl Into<CurveRef<'a>>, q: impl Into<CurveRef<'a>>, what: &str) -> bool {
        let (p, q) = (p.into(), q.into());
        let options = IntersectOptions::default();
        let reference = intersect_by_subdivision(p, q, &options).unwrap();
        let full = intersect(p, q, &options).unwrap();
        assert_same(&full, &reference, what);
        match intersect_by_clipping(p, q, &options) {
            Some(fast) => {
                let fast = fast.unwrap();
                assert_same(&fast, &reference, what);
                assert!(
                    fast.iter().all(|h| h.kind == IntersectionKind::Crossing),
                    "{what}: the fast path reports crossings only: {fast:?}"
                );
                true
            }
            None => {
                // Given up: `intersect` is the subdivision's answer, bit for bit.
                assert_eq!(full, reference, "{what}");
                false
            }
        }
    }

    #[test]
    fn clipping_finds_the_subdivisions_crossings_on_random_pairs() {
        let mut rng = Lcg(20);
        let (mut fast, mut crossings) = (0, 0);
        for case in 0..400 {
            let dp = 1 + (rng.next() * 8.0) as usize;
            let dq = 1 + (rng.next() * 8.0) as usize;
            let p = random_bezier(&mut rng, dp);
            let q = random_bezier(&mut rng, dq);
            if compare(&p, &q, &format!("case {case}, degrees {dp}, {dq}")) {
                fast += 1;
                crossings += intersect(&p, &q, &IntersectOptions::default())
                    .unwrap()
                    .len();
            }
        }
        // The fast path takes most pairs, and many of them cross.
        assert!(
            fast > 300 && crossings > 400,
            "fast {fast}, crossings {crossings}"
        );
    }

    #[test]
    fn clipping_at_high_degree_and_on_nurbs_spans() {
        let mut rng = Lcg(2020);
        let mut fast = 0;
        for case in 0..40 {
            let d = 9 + case % 7;
            let p = random_bezier(&mut rng, d);
            let q = random_bezier(&mut rng, 3);
            fast += usize::from(compare(&p, &q, &format!("degree {d}, case {case}")));
        }
        assert!(fast > 20, "fast {fast}");
        // Above MAX_DEGREE: always the subdivision.
        let p = random_bezier(&mut rng, super::MAX_DEGREE + 1);
        let q = random_bezier(&mut rng, 2);
        assert!(!compare(&p, &q, "degree 16"));
        let mut fast = 0;
        let (mut rational_fast, mut rational_crossings) = (0, 0);
        for case in 0..60 {
            let p = random_nurbs(&mut rng, 4 + case % 4, false);
            let q = random_bezier(&mut rng, 3);
            fast += usize::from(compare(&p, &q, &format!("B-spline, case {case}")));
            let r = random_nurbs(&mut rng, 5, false);
            compare(&p, &r, &format!("two B-splines, case {case}"));
            // Rational spans, against a Bezier curve and against another
            // rational curve: clipped in homogeneous form, the same hits
            // as the subdivision's.
            let w = random_nurbs(&mut rng, 5, true);
            let x = random_nurbs(&mut rng, 4 + case % 3, true);
            for (what, hit) in [
                (
                    "rational",
                    compare(&w, &q, &format!("rational, case {case}")),
                ),
                (
                    "two rational",
                    compare(&w, &x, &format!("two rational, case {case}")),
                ),
            ] {
                if hit {
                    rational_fast += 1;
                    let other: CurveRef = if what == "rational" {
                        (&q).into()
                    } else {
                        (&x).into()
                    };
                    rational_crossings += intersect(&w, other, &IntersectOptions::default())
                        .unwrap()
                        .len();
                }
            }
        }
        assert!(fast > 30, "fast {fast}");
        assert!(
            rational_fast > 100 && rational_crossings > 120,
            "rational: fast {rational_fast}, crossings {rational_crossings}"
        );
    }

    /// The rational clip never cuts away a parameter whose point is within
    /// the margin of the other piece (the defining property of the clip):
    /// on fixed-seed random rational cubic pairs, dense samples of `a`
    /// outside the returned interval are all farther than the margin from
    /// dense samples of `b`, taken as the distance to `b`'s sampled polygon
    /// (a lower bound on the true distance up to the sampling error, kept
    /// below the margin's tenth by the sample count).
    #[test]
    fn rational_clip_keeps_every_point_near_the_other_piece() {
        use super::{RationalPoly, SMALL, clip_rational};
        let mut rng = Lcg(31);
        let eval = |p: &RationalPoly<SMALL>, t: f64| -> [f64; 2] {
            let mut h = p.homogeneous;
            for r in 1..=3 {
                for i in 0..=3 - r {
                    let next = h[i + 1];
                    for (x, y) in h[i].iter_mut().zip(next) {
                        *x = (1.0 - t) * *x + t * y;
                    }
                }
            }
            [h[0][0] / h[0][2], h[0][1] / h[0][2]]
        };
        let mut cut = 0;
        for case in 0..300 {
            let mut piece = || {
                let mut homogeneous = [[0.0; 3]; SMALL];
                for h in homogeneous.iter_mut() {
                    let w = rng.range(0.3, 3.0);
                    *h = [w * rng.range(-1.0, 1.0), w * rng.range(-1.0, 1.0), w];
                }
                let mut projected = super::Poly {
                    n: 3,
                    points: [[0.0; 2]; SMALL],
                };
                for (p, h) in projected.points.iter_mut().zip(&homogeneous) {
                    *p = [h[0] / h[2], h[1] / h[2]];
                }
                RationalPoly {
                    homogeneous,
                    projected,
                }
            };
            let (a, b) = (piece(), piece());
            let margin = rng.range(0.0, 0.05);
            let samples = 400;
            let bs: Vec<[f64; 2]> = (0..=samples)
                .map(|k| eval(&b, k as f64 / samples as f64))
                .collect();
            let near = |x: [f64; 2]| {
                bs.windows(2).any(|w| {
                    let (p, q) = (w[0], w[1]);
                    let (dx, dy) = (q[0] - p[0], q[1] - p[1]);
                    let len2 = dx * dx + dy * dy;
                    let s = if len2 > 0.0 {
                        (((x[0] - p[0]) * dx + (x[1] - p[1]) * dy) / len2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let (ex, ey) = (p[0] + s * dx - x[0], p[1] + s * dy - x[1]);
                    (ex * ex + ey * ey).sqrt() <= margin
                })
            };
            let kept = clip_rational(&a, &b, margin);
            if kept != Some((0.0, 1.0)) {
                cut += 1;
            }
            for k in 0..=samples {
                let t = k as f64 / samples as f64;
                let inside = kept.is_some_and(|(lo, hi)| t >= lo && t <= hi);
                if !inside && near(eval(&a, t)) {
                    panic!("case {case}: t = {t} is within {margin} of b, clipped to {kept:?}");
                }
            }
        }
        assert!(cut > 100, "cut {cut}");
    }

    #[test]
    fn hard_cases_are_left_to_the_subdivision() {
        let curve = |rows: &[[f64; 2]]| BezierCurve::from_rows(rows).unwrap();
        // A tangency: a cubic touching a straight cubic at its lowest point.
        let cup = curve(&[
            [0.0, 1.0],
            [1.0 / 3.0, -1.0 / 3.0],
            [2.0 / 3.0, -1.0 / 3.0],
            [1.0, 1.0],
        ]);
        let floor = curve(&[[0.0, 0.0], [1.0 / 3.0, 0.0], [2.0 / 3.0, 0.0], [1.0, 0.0]]);
        assert!(!compare(&cup, &floor, "tangency"));
        let h = intersect(&cup, &floor, &IntersectOptions::default()).unwrap();
        assert_eq!(h.len(), 1);
        assert_eq!(h[0].kind, IntersectionKind::Touching);
        // An overlap: a line and a part of it.
        let line = curve(&[[0.0, 0.0], [2.0, 1.0]]);
        let part = curve(&[[0.5, 0.25], [1.0, 0.5], [1.5, 0.75]]);
        assert!(!compare(&line, &part, "overlap"));
        // 3D: the subdivision.
        let a = BezierCurve::from_rows(&[[0.0, 0.0, 0.0], [1.0, 1.0, 0.0]]).unwrap();
        let b = BezierCurve::from_rows(&[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]).unwrap();
        assert!(!compare(&a, &b, "3D"));
        // A transversal crossing is the fast path's.
        let c = curve(&[[0.0, 1.0], [1.0, 0.0]]);
        assert!(compare(&line, &c, "lines"));
    }

    /// The cubic steps with the degree as a constant (`keep_left`,
    /// `keep_right`, `is_flat`, `bounds`, `clip` on degree 3) are the
    /// general loops run with the degree unknown at compile time, to the
    /// bit; and the planar polish with the dimension as a constant is the
    /// general one with the dimension unknown (same parameters, distance,
    /// flag and tangents), on fixed-seed random cubics.
    #[test]
    fn constant_size_paths_are_the_general_ones_to_the_bit() {
        use super::super::CurvePair;
        use super::super::track::Track;
        use super::{Poly, SMALL, clip, clip_n};
        use std::hint::black_box;
        let bits = |p: &Poly<SMALL>| -> Vec<u64> {
            p.points.iter().flatten().map(|x| x.to_bits()).collect()
        };
        let pair_bits = |r: Option<(f64, f64)>| r.map(|(a, b)| (a.to_bits(), b.to_bits()));
        let mut rng = Lcg(27);
        let (mut flat, mut curved, mut clipped) = (0, 0, 0);
        for case in 0..400 {
            let mut poly = || {
                let mut points = [[0.0; 2]; SMALL];
                for p in points.iter_mut() {
                    *p = [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)];
                }
                Poly::<SMALL> { n: 3, points }
            };
            let (a, b) = (poly(), poly());
            // A near-straight copy of `b`, so that `is_flat` answers both ways.
            let mut c = b;
            for (i, p) in c.points.iter_mut().enumerate() {
                let w = i as f64 / 3.0;
                p[0] = b.points[0][0] + w * (b.points[3][0] - b.points[0][0]) + 1e-3 * p[0];
                p[1] = b.points[0][1] + w * (b.points[3][1] - b.points[0][1]) + 1e-3 * p[1];
            }
            let three = black_box(3);
            let (s, t) = (rng.range(0.0, 0.5), rng.range(0.5, 1.0));
            for p in [a, b, c] {
                let (mut x, mut y) = (p, p);
                x.keep_left(t);
                y.keep_left_n(three, t);
                assert_eq!(bits(&x), bits(&y), "case {case}: keep_left");
                let (mut x, mut y) = (p, p);
                x.keep_right(s);
                y.keep_right_n(three, s);
                assert_eq!(bits(&x), bits(&y), "case {case}: keep_right");
                let absolute = rng.range(0.0, 2e-3);
                let f = p.is_flat(absolute, 1e-2);
                assert_eq!(
                    f,
                    p.is_flat_n(three, absolute, 1e-2),
                    "case {case}: is_flat"
                );
                if f {
                    flat += 1
                } else {
                    curved += 1
                }
                let (x, y) = (p.bounds(), p.bounds_n(three));
                assert_eq!(
                    x.map(f64::to_bits),
                    y.map(f64::to_bits),
                    "case {case}: bounds"
                );
            }
            for (p, q) in [(&a, &b), (&b, &a), (&a, &c), (&c, &a)] {
                let margin = rng.range(0.0, 1e-2);
                let x = clip(p, q, margin);
                assert_eq!(
                    pair_bits(x),
                    pair_bits(clip_n(p, three, q, three, margin)),
                    "case {case}: clip"
                );
                if x.is_some_and(|(lo, hi)| lo > 0.0 || hi < 1.0) {
                    clipped += 1;
                }
            }
            let (pc, qc) = (random_bezier(&mut rng, 3), random_bezier(&mut rng, 3));
            let curves = CurvePair {
                p: Track::new(CurveRef::from(&pc)),
                q: Track::new(CurveRef::from(&qc)),
            };
            let (u, v) = (rng.next(), rng.next());
            let (mut ta, mut tb) = ([0.0; 4], [0.0; 4]);
            let x = curves.polish_with_tangents(u, v, &mut ta);
            let y = curves.polish_sized(black_box(2), u, v, &mut tb);
            assert_eq!(
                (x.0.to_bits(), x.1.to_bits(), x.2.to_bits(), x.3),
                (y.0.to_bits(), y.1.to_bits(), y.2.to_bits(), y.3),
                "case {case}: polish"
            );
            assert_eq!(
                ta.map(f64::to_bits),
                tb.map(f64::to_bits),
                "case {case}: tangents"
            );
        }
        assert!(
            flat > 100 && curved > 100 && clipped > 100,
            "{flat} {curved} {clipped}"
        );
    }

    /// The rational cubics' constant-degree paths (`RationalPoly::segment`,
    /// `clip_rational` and `RationalPoly::from_piece` on degree 3) are the
    /// same bodies run with the degree unknown at compile time, to the bit
    /// (homogeneous rows, projections, clipped intervals), on fixed-seed
    /// random rational cubics with weights in `[0.3, 3]` (and, for
    /// `from_piece`, the spans of two-span rational NURBS cubics and
    /// Bezier cubics' pieces).
    #[test]
    fn rational_constant_degree_paths_are_the_general_ones_to_the_bit() {
        use super::{Poly, RationalPoly, SMALL, clip_rational, clip_rational_n};
        use std::hint::black_box;
        let bits = |p: &RationalPoly<SMALL>| -> Vec<u64> {
            let h = p.homogeneous.iter().flatten();
            h.chain(p.projected.points.iter().flatten())
                .map(|x| x.to_bits())
                .collect()
        };
        let pair_bits = |r: Option<(f64, f64)>| r.map(|(a, b)| (a.to_bits(), b.to_bits()));
        let mut rng = Lcg(41);
        let mut clipped = 0;
        for case in 0..400 {
            let mut poly = |scale: f64| {
                let mut homogeneous = [[0.0; 3]; SMALL];
                let mut projected = Poly::<SMALL> {
                    n: 3,
                    points: [[0.0; 2]; SMALL],
                };
                for (h, p) in homogeneous.iter_mut().zip(&mut projected.points).take(4) {
                    let w = rng.range(0.3, 3.0);
                    let (x, y) = (scale * rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
                    *h = [w * x, w * y, w];
                    *p = [h[0] / h[2], h[1] / h[2]];
                }
                RationalPoly {
                    homogeneous,
                    projected,
                }
            };
            let (a, b) = (poly(1.0), poly(1.0));
            // A flat one (small extent across), so that clips cut.
            let c = poly(0.05);
            let three = black_box(3);
            for p in [a, b, c] {
                let (s, t) = (rng.range(0.0, 0.5), rng.range(0.5, 1.0));
                for (s, t) in [(s, t), (0.0, t), (s, 1.0)] {
                    assert_eq!(
                        bits(&p.segment(s, t)),
                        bits(&p.segment_n(three, s, t)),
                        "case {case}: segment {s} {t}"
                    );
                }
            }
            for (p, q) in [(&a, &b), (&b, &a), (&a, &c), (&c, &a), (&b, &c)] {
                let margin = rng.range(0.0, 1e-2);
                let x = clip_rational(p, q, margin);
                assert_eq!(
                    pair_bits(x),
                    pair_bits(clip_rational_n(p, three, q, three, margin)),
                    "case {case}: clip"
                );
                if x.is_some_and(|(lo, hi)| lo > 0.0 || hi < 1.0) {
                    clipped += 1;
                }
            }
        }
        assert!(clipped > 100, "{clipped}");
        // `from_piece` of cubic pieces (rational spans of two-span NURBS
        // cubics, and a Bezier cubic's piece) with the degree constant is
        // the body with the degree unknown.
        let mut built = 0;
        for case in 0..100 {
            let poles: Vec<f64> = (0..8).map(|_| rng.range(-1.0, 1.0)).collect();
            let weights: Vec<f64> = (0..4).map(|_| rng.range(0.3, 3.0)).collect();
            let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
            let curve = crate::NurbsCurve::new(2, 3, poles.clone(), Some(weights), knots)
                .unwrap()
                .insert_knot(rng.range(0.2, 0.8), 1)
                .unwrap();
            let bezier = crate::BezierCurve::new(2, 3, poles).unwrap();
            for track in [
                super::super::track::Track::new(CurveRef::from(&curve)),
                super::super::track::Track::new(CurveRef::from(&bezier)),
            ] {
                for piece in track.pieces().iter() {
                    let x = RationalPoly::<SMALL>::from_piece(piece).unwrap();
                    let y = RationalPoly::<SMALL>::from_piece_n(piece, three_constant()).unwrap();
                    assert_eq!(bits(&x), bits(&y), "case {case}: from_piece");
                    built += 1;
                }
            }
        }
        assert_eq!(built, 300);
    }

    /// 3, unknown at compile time.
    fn three_constant() -> usize {
        std::hint::black_box(3)
    }
}
