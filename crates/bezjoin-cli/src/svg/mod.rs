//! SVG pictures with control polygons and curvature combs, written by hand.
//!
//! What a picture shows: every curve, its control polygon (dashed, with the
//! control points as small squares), and its **curvature comb** — spikes
//! perpendicular to the curve, of length proportional to the signed
//! curvature `k = (x'y'' - y'x'') / |r'|^3`, drawn on the side away from the
//! centre of curvature, with their tips joined. One comb scale is used for
//! every curve of a picture, so a comb that runs on smoothly across a join
//! point shows curvature continuity (G2/C2), a step in the comb shows a
//! curvature jump, and a kink in the tip line shows a jump of the curvature's
//! derivative.
//!
//! Curves are drawn through samples of their points and first two
//! derivatives, so every kind is drawn the same way: Bezier curves, NURBS
//! curves (polynomial or rational, sampled span by span with both sides of
//! every interior knot, so a curvature step at a knot shows where it is)
//! and circular arcs. The curvature comes from the first and second
//! derivatives alone.
//!
//! Coordinates: the model's `y` axis points up (the SVG's is flipped).
//! Curves of dimension 3 or more are drawn in top view (the `x`-`y`
//! projection) and their combs show the curvature of that projection; a
//! curve of dimension 1 is drawn as the graph `(t, x(t))`.

use bezjoin_core::{BezierCurve, CurveRef, KnotSide, NurbsCurve};

mod bounds;
mod comb;
mod layout;
mod output;
mod plot;

/// The drawable geometry of one curve.
#[derive(Debug, Clone)]
pub enum Shape {
    /// A Bezier curve of any degree and dimension.
    Bezier(BezierCurve),
    /// A NURBS curve of any degree and dimension, on its domain.
    Nurbs(NurbsCurve),
    /// A circular arc in the x-y plane: `center + radius (cos a, sin a)`,
    /// `a = start_angle + sweep * t`, `t in [0, 1]`.
    Arc {
        /// Centre of the circle.
        center: [f64; 2],
        /// Radius, > 0.
        radius: f64,
        /// Angle of the start point, radians.
        start_angle: f64,
        /// Signed angle swept (positive = counter-clockwise).
        sweep: f64,
    },
}

impl Shape {
    /// A curve of either kind.
    pub fn curve<'a>(curve: impl Into<CurveRef<'a>>) -> Self {
        match curve.into() {
            CurveRef::Bezier(c) => Shape::Bezier(c.clone()),
            CurveRef::Nurbs(c) => Shape::Nurbs(c.clone()),
        }
    }

    /// Projected point, first and second derivative at `t` in `[0, 1]`
    /// (a NURBS curve's domain mapped onto `[0, 1]`; at an interior knot its
    /// derivatives are those from the right).
    pub fn jet(&self, t: f64) -> [[f64; 2]; 3] {
        match self {
            Shape::Bezier(c) => projected(&c.eval_derivatives(t, 2), c.dim(), t),
            Shape::Nurbs(c) => {
                let (a, b) = c.domain();
                let u = a + t * (b - a);
                let d = c.eval_derivatives_side(u, 2, KnotSide::Right);
                let [p, d1, d2] = projected(&d, c.dim(), u);
                let s = b - a;
                [p, [d1[0] * s, d1[1] * s], [d2[0] * s * s, d2[1] * s * s]]
            }
            Shape::Arc {
                center,
                radius,
                start_angle,
                sweep,
            } => {
                let a = start_angle + sweep * t;
                let (s, c) = a.sin_cos();
                [
                    [center[0] + radius * c, center[1] + radius * s],
                    [-radius * sweep * s, radius * sweep * c],
                    [-radius * sweep * sweep * c, -radius * sweep * sweep * s],
                ]
            }
        }
    }

    /// Samples for drawing: `count + 1` jets ([`Shape::jet`]) at equally
    /// spaced `t` for a Bezier curve or an arc; for a NURBS curve about as
    /// many, spread over the knot spans by their parameter lengths (at
    /// least 2 per span), each span from its first parameter (derivatives
    /// from the right) to its last (from the left), so both sides of every
    /// interior knot are drawn.
    pub fn sample_jets(&self, count: usize) -> Vec<[[f64; 2]; 3]> {
        let Shape::Nurbs(c) = self else {
            return (0..=count)
                .map(|i| self.jet(i as f64 / count as f64))
                .collect();
        };
        let (a, b) = c.domain();
        let (inner, _) = c.interior_knots();
        let mut breaks = vec![a];
        breaks.extend(inner);
        breaks.push(b);
        let mut out = Vec::with_capacity(count + 2 * breaks.len());
        for w in breaks.windows(2) {
            let (lo, hi) = (w[0], w[1]);
            let n = ((count as f64 * (hi - lo) / (b - a)).round() as usize).max(1);
            for i in 0..=n {
                let u = lo + (hi - lo) * i as f64 / n as f64;
                let side = if i == n {
                    KnotSide::Left
                } else {
                    KnotSide::Right
                };
                let d = c.eval_derivatives_side(u, 2, side);
                let [p, d1, d2] = projected(&d, c.dim(), u);
                let s = b - a;
                out.push([p, [d1[0] * s, d1[1] * s], [d2[0] * s * s, d2[1] * s * s]]);
            }
        }
        out
    }

    /// Projected control polygon (empty for an arc).
    fn polygon(&self) -> Vec<[f64; 2]> {
        match self {
            Shape::Nurbs(c) => (0..c.point_count())
                .map(|i| {
                    let p = c.point(i);
                    if c.dim() == 1 {
                        // Greville abscissa: where the pole acts most.
                        let k = c.knots();
                        let p_deg = c.degree();
                        [
                            k[i + 1..=i + p_deg].iter().sum::<f64>() / p_deg as f64,
                            p[0],
                        ]
                    } else {
                        [p[0], p[1]]
                    }
                })
                .collect(),
            Shape::Bezier(c) => (0..c.point_count())
                .map(|i| {
                    let p = c.point(i);
                    if c.dim() == 1 {
                        [i as f64 / c.degree().max(1) as f64, p[0]]
                    } else {
                        [p[0], p[1]]
                    }
                })
                .collect(),
            Shape::Arc { .. } => Vec::new(),
        }
    }

    fn dim(&self) -> usize {
        match self {
            Shape::Bezier(c) => c.dim(),
            Shape::Nurbs(c) => c.dim(),
            Shape::Arc { .. } => 2,
        }
    }
}

/// Point, first and second derivative (rows of `d`, `dim` values each)
/// projected to the picture's plane: the `x`-`y` plane, or the graph
/// `(t, x(t))` of a curve of dimension 1 (`t` its parameter).
fn projected(d: &[f64], dim: usize, t: f64) -> [[f64; 2]; 3] {
    if dim == 1 {
        [[t, d[0]], [1.0, d[1]], [0.0, d[2]]]
    } else {
        [
            [d[0], d[1]],
            [d[dim], d[dim + 1]],
            [d[2 * dim], d[2 * dim + 1]],
        ]
    }
}

/// Signed curvature of a plane curve from its first two derivatives.
pub fn signed_curvature(d1: [f64; 2], d2: [f64; 2]) -> f64 {
    let speed = d1[0].hypot(d1[1]);
    if speed == 0.0 {
        return 0.0;
    }
    (d1[0] * d2[1] - d1[1] * d2[0]) / (speed * speed * speed)
}

/// What a curve is in the picture; decides its colour and style.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// A given curve.
    Input,
    /// The computed curve.
    Result,
    /// A given curve after the operation changed it (merge's P^, Q^).
    Modified,
    /// A comparison curve (the circular-arc fillet).
    Reference,
    /// A part of a given curve that the result no longer uses.
    Discarded,
}

impl Role {
    fn stroke(self) -> &'static str {
        match self {
            Role::Input => "#1f5fa8",
            Role::Result => "#d1420f",
            Role::Modified => "#1b8a4a",
            Role::Reference => "#7d3c98",
            Role::Discarded => "#a8a8a8",
        }
    }

    fn comb(self) -> &'static str {
        match self {
            Role::Input => "#8fb3de",
            Role::Result => "#f2a27f",
            Role::Modified => "#8fd1aa",
            Role::Reference => "#c7a3d6",
            Role::Discarded => "#dddddd",
        }
    }

    fn dash(self) -> &'static str {
        match self {
            Role::Discarded => " stroke-dasharray=\"6 4\"",
            Role::Reference => " stroke-dasharray=\"10 3\"",
            _ => "",
        }
    }
}

/// One curve of a picture.
#[derive(Debug, Clone)]
pub struct CurveItem {
    /// Its geometry.
    pub shape: Shape,
    /// Its colour and style.
    pub role: Role,
    /// Legend text.
    pub label: String,
    /// Draw the control polygon.
    pub polygon: bool,
    /// Draw the curvature comb.
    pub comb: bool,
}

impl CurveItem {
    /// A Bezier curve with polygon and comb.
    pub fn bezier(curve: &BezierCurve, role: Role, label: impl Into<String>) -> Self {
        Self::new(curve, role, label)
    }

    /// A curve of either kind (Bezier or NURBS) with polygon and comb
    /// (neither for a discarded curve).
    pub fn new<'a>(curve: impl Into<CurveRef<'a>>, role: Role, label: impl Into<String>) -> Self {
        CurveItem {
            shape: Shape::curve(curve),
            role,
            label: label.into(),
            polygon: role != Role::Discarded,
            comb: role != Role::Discarded,
        }
    }

    /// Same item without control polygon.
    pub fn without_polygon(mut self) -> Self {
        self.polygon = false;
        self
    }
}

/// Kinds of marked points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MarkerKind {
    /// Where two curves of the result meet.
    Join,
    /// A crossing of the given curves.
    Crossing,
    /// A prescribed point (constraint, kept point, on-curve point).
    Constraint,
    /// The centre of a circle (the circular-arc fillet's).
    Centre,
    /// No symbol: the label alone, in bold at the point (a panel's title);
    /// not listed in the legend.
    Label,
}

/// A marked point.
#[derive(Debug, Clone)]
pub struct Marker {
    /// Position (first two coordinates are used).
    pub at: Vec<f64>,
    /// Kind.
    pub kind: MarkerKind,
    /// Short text next to it (may be empty).
    pub label: String,
}

impl Marker {
    /// A marker of `kind` at `at`.
    pub fn new(kind: MarkerKind, at: &[f64], label: impl Into<String>) -> Self {
        Marker {
            at: at.to_vec(),
            kind,
            label: label.into(),
        }
    }
}

/// A whole picture.
#[derive(Debug, Clone, Default)]
pub struct Figure {
    /// Bold first caption line.
    pub title: String,
    /// Further caption lines (degree, continuity orders, report).
    pub caption: Vec<String>,
    /// Curves, drawn in order.
    pub curves: Vec<CurveItem>,
    /// Marked points.
    pub markers: Vec<Marker>,
    /// Graphs drawn in one row below the drawing (curvature along arc
    /// length), left to right.
    pub plots: Vec<Plot>,
}

/// A graph below the drawing, e.g. the curvature `kappa` against arc length
/// `s`: axes with ticks, a zero line, dashed vertical lines at `x_marks`
/// (join points, where a jump of the curvature shows as a step) and the
/// series, each in its role's colour and style.
#[derive(Debug, Clone, Default)]
pub struct Plot {
    /// Title above the graph.
    pub title: String,
    /// Name of the horizontal axis.
    pub x_label: String,
    /// Name of the vertical axis.
    pub y_label: String,
    /// The lines drawn.
    pub series: Vec<PlotSeries>,
    /// Vertical dashed lines at these abscissae.
    pub x_marks: Vec<f64>,
    /// Range of the vertical axis; `None`: the data's, with 0 included.
    /// Values outside are clipped (several plots can share one range).
    pub y_range: Option<[f64; 2]>,
}

/// One line of a [`Plot`].
#[derive(Debug, Clone)]
pub struct PlotSeries {
    /// Colour and style.
    pub role: Role,
    /// What it is (the line's tooltip).
    pub label: String,
    /// `(x, y)` points, joined in order.
    pub points: Vec<[f64; 2]>,
}

impl Plot {
    /// The range of the vertical axis: `y_range`, or the data's with 0
    /// included, widened by 6 % (a flat line gets a unit range).
    pub fn y_bounds(&self) -> [f64; 2] {
        if let Some(r) = self.y_range {
            return r;
        }
        let (lo, hi) = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p[1]))
            .filter(|y| y.is_finite())
            .fold((0.0f64, 0.0f64), |(lo, hi), y| (lo.min(y), hi.max(y)));
        let pad = 0.06 * (hi - lo);
        if pad > 0.0 {
            [lo - pad, hi + pad]
        } else {
            [lo - 1.0, hi + 1.0]
        }
    }

    /// The range of the horizontal axis (of the data; `[0, 1]` when empty).
    pub fn x_bounds(&self) -> [f64; 2] {
        let (lo, hi) = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p[0]))
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                (lo.min(x), hi.max(x))
            });
        if lo < hi { [lo, hi] } else { [0.0, 1.0] }
    }
}

impl Figure {
    /// An empty figure titled `title`.
    pub fn new(title: impl Into<String>) -> Self {
        Figure {
            title: title.into(),
            ..Default::default()
        }
    }

    /// Add a curve.
    pub fn curve(&mut self, item: CurveItem) -> &mut Self {
        self.curves.push(item);
        self
    }

    /// Add a marker.
    pub fn marker(&mut self, marker: Marker) -> &mut Self {
        self.markers.push(marker);
        self
    }

    /// Add a graph below the drawing.
    pub fn plot(&mut self, plot: Plot) -> &mut Self {
        self.plots.push(plot);
        self
    }

    /// Add a caption line.
    pub fn line(&mut self, text: impl Into<String>) -> &mut Self {
        self.caption.push(text.into());
        self
    }

    /// The picture as an SVG document.
    pub fn to_svg(&self) -> String {
        render(self)
    }
}

/// Escape text for XML content and attribute values.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        match ch {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c => out.push(c),
        }
    }
    out
}

/// Draw `figure`: model bounds of everything but the combs, the comb scale
/// and comb tips (which widen the bounds), the page layout, then the SVG.
fn render(figure: &Figure) -> String {
    let curve_points = bounds::sample_curves(figure);
    let mut bounds = bounds::model_bounds(figure, &curve_points);
    let size = bounds.size().max(1e-12);
    let combs = comb::Combs::new(figure, size);
    combs.tips().for_each(|p| bounds.add(p));
    let layout = layout::Layout::new(figure, &bounds, size, &combs);
    output::svg(figure, &curve_points, &combs, &layout)
}

/// The curves listed in the legend: each (role, label) once, in the order
/// drawn; curves without a label are not listed.
fn legend_curves(figure: &Figure) -> Vec<&CurveItem> {
    let mut out: Vec<&CurveItem> = Vec::new();
    for item in &figure.curves {
        if !item.label.is_empty()
            && !out
                .iter()
                .any(|o| o.role == item.role && o.label == item.label)
        {
            out.push(item);
        }
    }
    out
}

/// The kinds of markers listed in the legend, in the order first used
/// (labels are not listed).
fn legend_marker_kinds(figure: &Figure) -> Vec<MarkerKind> {
    let mut kinds = Vec::new();
    for m in &figure.markers {
        if m.kind != MarkerKind::Label && !kinds.contains(&m.kind) {
            kinds.push(m.kind);
        }
    }
    kinds
}

/// Where a marker is drawn: its first two coordinates (0 where missing).
fn marker_xy(m: &Marker) -> [f64; 2] {
    [
        m.at.first().copied().unwrap_or(0.0),
        m.at.get(1).copied().unwrap_or(0.0),
    ]
}

#[cfg(test)]
mod curvature_escape_and_layout_tests {
    use super::*;

    #[test]
    fn curvature_of_a_circle_is_one_over_radius_with_sign() {
        let ccw = Shape::Arc {
            center: [1.0, 2.0],
            radius: 3.0,
            start_angle: 0.3,
            sweep: 1.0,
        };
        let [_, d1, d2] = ccw.jet(0.4);
        assert!((signed_curvature(d1, d2) - 1.0 / 3.0).abs() < 1e-14);
        let cw = Shape::Arc {
            center: [1.0, 2.0],
            radius: 3.0,
            start_angle: 0.3,
            sweep: -1.0,
        };
        let [_, d1, d2] = cw.jet(0.4);
        assert!((signed_curvature(d1, d2) + 1.0 / 3.0).abs() < 1e-14);
    }

    #[test]
    fn parabola_curvature_matches_formula() {
        // y = x^2 as a quadratic Bezier on x in [-1, 1]: k(x) = 2 / (1 + 4x^2)^1.5.
        let c = BezierCurve::from_rows(&[[-1.0, 1.0], [0.0, -1.0], [1.0, 1.0]]).unwrap();
        let shape = Shape::Bezier(c);
        for i in 0..=10 {
            let t = i as f64 / 10.0;
            let [p, d1, d2] = shape.jet(t);
            let x = p[0];
            let expected = 2.0 / (1.0 + 4.0 * x * x).powf(1.5);
            assert!((signed_curvature(d1, d2) - expected).abs() < 1e-12);
        }
    }

    #[test]
    fn escape_handles_markup() {
        assert_eq!(escape("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }

    #[test]
    fn flipped_y_puts_higher_points_nearer_the_top() {
        let mut f = Figure::new("t");
        f.marker(Marker::new(MarkerKind::Join, &[0.0, 0.0], "low"));
        f.marker(Marker::new(MarkerKind::Join, &[0.0, 10.0], "high"));
        let svg = f.to_svg();
        let y_of = |label: &str| -> f64 {
            let end = svg.find(&format!(">{label}</text>")).unwrap();
            let start = svg[..end].rfind("y=\"").unwrap() + 3;
            svg[start..].split('"').next().unwrap().parse().unwrap()
        };
        assert!(y_of("high") < y_of("low"));
    }
}
