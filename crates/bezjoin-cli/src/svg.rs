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
//! Coordinates: the model's `y` axis points up (the SVG's is flipped).
//! Curves of dimension 3 or more are drawn in top view (the `x`-`y`
//! projection) and their combs show the curvature of that projection; a
//! curve of dimension 1 is drawn as the graph `(t, x(t))`.

use std::fmt::Write as _;

use bezjoin_core::BezierCurve;

/// The drawable geometry of one curve.
#[derive(Debug, Clone)]
pub enum Shape {
    /// A Bezier curve of any degree and dimension.
    Bezier(BezierCurve),
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
    /// Projected point, first and second derivative at `t`.
    pub fn jet(&self, t: f64) -> [[f64; 2]; 3] {
        match self {
            Shape::Bezier(c) => {
                let d = c.eval_derivatives(t, 2);
                if c.dim() == 1 {
                    [[t, d[(0, 0)]], [1.0, d[(1, 0)]], [0.0, d[(2, 0)]]]
                } else {
                    [
                        [d[(0, 0)], d[(0, 1)]],
                        [d[(1, 0)], d[(1, 1)]],
                        [d[(2, 0)], d[(2, 1)]],
                    ]
                }
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

    /// Projected control polygon (empty for an arc).
    fn polygon(&self) -> Vec<[f64; 2]> {
        match self {
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
            Shape::Arc { .. } => 2,
        }
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
        CurveItem {
            shape: Shape::Bezier(curve.clone()),
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

const CURVE_SAMPLES: usize = 240;
const COMB_SPIKES: usize = 60;
const COMB_TIP_SAMPLES: usize = 240;
/// Longest spike, as a fraction of the drawing's larger side.
const COMB_LENGTH_FRACTION: f64 = 0.12;
const DRAWING_WIDTH: f64 = 820.0;
const MARGIN: f64 = 24.0;
const LINE_HEIGHT: f64 = 18.0;

struct Bounds {
    min: [f64; 2],
    max: [f64; 2],
}

/// Comb samples of one curve: (point on the curve, unit normal, signed curvature).
type CombSamples = Vec<([f64; 2], [f64; 2], f64)>;

impl Bounds {
    fn empty() -> Self {
        Bounds {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        }
    }

    fn add(&mut self, p: [f64; 2]) {
        if p[0].is_finite() && p[1].is_finite() {
            for ((lo, hi), v) in self.min.iter_mut().zip(self.max.iter_mut()).zip(p) {
                *lo = lo.min(v);
                *hi = hi.max(v);
            }
        }
    }

    fn size(&self) -> f64 {
        (self.max[0] - self.min[0]).max(self.max[1] - self.min[1])
    }
}

/// Comb samples of one curve: (point, unit normal pointing away from the
/// centre of curvature when k > 0 is left, signed curvature).
fn comb_samples(shape: &Shape, count: usize) -> CombSamples {
    (0..=count)
        .map(|i| {
            let t = i as f64 / count as f64;
            let [p, d1, d2] = shape.jet(t);
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

fn render(figure: &Figure) -> String {
    // 1. Model-space bounds of curves, polygons and markers.
    let mut bounds = Bounds::empty();
    let mut curve_points: Vec<Vec<[f64; 2]>> = Vec::new();
    for item in &figure.curves {
        let pts: Vec<[f64; 2]> = (0..=CURVE_SAMPLES)
            .map(|i| item.shape.jet(i as f64 / CURVE_SAMPLES as f64)[0])
            .collect();
        pts.iter().for_each(|&p| bounds.add(p));
        if item.polygon {
            item.shape.polygon().into_iter().for_each(|p| bounds.add(p));
        }
        curve_points.push(pts);
    }
    for m in &figure.markers {
        bounds.add(marker_xy(m));
    }
    if !bounds.min[0].is_finite() {
        bounds.add([0.0, 0.0]);
        bounds.add([1.0, 1.0]);
    }
    let size = bounds.size().max(1e-12);

    // 2. One comb scale for the whole picture: the largest |k| (ignoring
    //    isolated extreme values above 4x the 95th percentile, whose spikes
    //    are clipped and said so) maps to COMB_LENGTH_FRACTION of the size.
    let combs: Vec<Option<CombSamples>> = figure
        .curves
        .iter()
        .map(|item| {
            item.comb
                .then(|| comb_samples(&item.shape, COMB_TIP_SAMPLES))
        })
        .collect();
    let mut magnitudes: Vec<f64> = combs
        .iter()
        .flatten()
        .flat_map(|c| c.iter().map(|s| s.2.abs()))
        .filter(|k| k.is_finite())
        .collect();
    magnitudes.sort_by(f64::total_cmp);
    let (comb_scale, clip) = if magnitudes.is_empty() || *magnitudes.last().unwrap() == 0.0 {
        (0.0, f64::INFINITY)
    } else {
        let max = *magnitudes.last().unwrap();
        let p95 = magnitudes[(magnitudes.len() - 1) * 95 / 100];
        let reference = if max > 4.0 * p95 && p95 > 0.0 {
            4.0 * p95
        } else {
            max
        };
        (COMB_LENGTH_FRACTION * size / reference, reference)
    };
    let mut clipped = false;
    let tips: Vec<Option<Vec<[f64; 2]>>> = combs
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
                        let len = -kk * comb_scale;
                        [p[0] + n[0] * len, p[1] + n[1] * len]
                    })
                    .collect()
            })
        })
        .collect();
    tips.iter().flatten().flatten().for_each(|&p| bounds.add(p));

    // 3. Model -> SVG coordinates, y flipped.
    let width_model = (bounds.max[0] - bounds.min[0]).max(1e-12 * size);
    let height_model = (bounds.max[1] - bounds.min[1]).max(1e-12 * size);
    let inner_width = DRAWING_WIDTH - 2.0 * MARGIN;
    let mut scale = inner_width / width_model;
    let max_inner_height = 560.0;
    if height_model * scale > max_inner_height {
        scale = max_inner_height / height_model;
    }
    let inner_height = (height_model * scale).max(120.0);
    let x_offset = MARGIN + (inner_width - width_model * scale) / 2.0;
    let y_offset = MARGIN + (inner_height - height_model * scale) / 2.0;
    let map = |p: [f64; 2]| -> (f64, f64) {
        (
            x_offset + (p[0] - bounds.min[0]) * scale,
            y_offset + (bounds.max[1] - p[1]) * scale,
        )
    };

    let projected = figure.curves.iter().any(|c| c.shape.dim() >= 3);
    let graph = figure.curves.iter().any(|c| c.shape.dim() == 1);
    let mut caption = figure.caption.clone();
    if projected {
        caption.push(
            "3D curves shown in top view (x-y projection); combs show the curvature of the projection."
                .into(),
        );
    }
    if graph {
        caption.push("1D curves shown as graphs (t, x(t)).".into());
    }
    if clipped {
        caption.push("Some comb spikes are clipped (very high curvature there).".into());
    }
    caption.push(format!(
        "Curvature combs: spike length = {:.3e} x curvature (same scale for every curve); y points up.",
        comb_scale
    ));

    let legend_rows = figure.curves.len()
        + figure
            .markers
            .iter()
            .map(|m| m.kind)
            .fold(Vec::new(), |mut v, k| {
                if !v.contains(&k) {
                    v.push(k);
                }
                v
            })
            .len();
    let drawing_height = inner_height + 2.0 * MARGIN;
    let legend_height = LINE_HEIGHT * legend_rows as f64 + 8.0;
    let caption_height = LINE_HEIGHT * (caption.len() + 1) as f64 + 12.0;
    let total_height = drawing_height + legend_height + caption_height;

    let mut s = String::new();
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.0} {h:.0}\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"13\">",
        w = DRAWING_WIDTH,
        h = total_height
    );
    let _ = writeln!(s, "<title>{}</title>", escape(&figure.title));
    let _ = writeln!(
        s,
        "<rect x=\"0\" y=\"0\" width=\"{:.0}\" height=\"{:.0}\" fill=\"white\"/>",
        DRAWING_WIDTH, total_height
    );
    let _ = writeln!(
        s,
        "<rect x=\"0.5\" y=\"0.5\" width=\"{:.0}\" height=\"{:.1}\" fill=\"none\" stroke=\"#e0e0e0\"/>",
        DRAWING_WIDTH - 1.0,
        drawing_height - 1.0
    );

    // Combs (under everything): spikes, then the tip line.
    let _ = writeln!(s, "<g id=\"combs\" fill=\"none\">");
    for ((item, comb), tip) in figure.curves.iter().zip(&combs).zip(&tips) {
        let (Some(samples), Some(tip)) = (comb, tip) else {
            continue;
        };
        let step = (COMB_TIP_SAMPLES / COMB_SPIKES).max(1);
        let mut d = String::new();
        for i in (0..samples.len()).step_by(step) {
            let (a, b) = (map(samples[i].0), map(tip[i]));
            let _ = write!(d, "M{:.2} {:.2}L{:.2} {:.2}", a.0, a.1, b.0, b.1);
        }
        let _ = writeln!(
            s,
            "<path d=\"{d}\" stroke=\"{}\" stroke-width=\"0.8\"/>",
            item.role.comb()
        );
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" stroke=\"{}\" stroke-width=\"1.4\"/>",
            polyline(tip, map),
            item.role.comb()
        );
    }
    let _ = writeln!(s, "</g>");

    // Control polygons.
    let _ = writeln!(
        s,
        "<g id=\"polygons\" fill=\"none\" stroke-width=\"0.9\" stroke-dasharray=\"4 3\" opacity=\"0.75\">"
    );
    for item in figure.curves.iter().filter(|c| c.polygon) {
        let poly = item.shape.polygon();
        if poly.is_empty() {
            continue;
        }
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" stroke=\"{}\"/>",
            polyline(&poly, map),
            item.role.stroke()
        );
        for &p in &poly {
            let (x, y) = map(p);
            let _ = writeln!(
                s,
                "<rect x=\"{:.2}\" y=\"{:.2}\" width=\"5\" height=\"5\" fill=\"white\" stroke=\"{}\" stroke-dasharray=\"none\"/>",
                x - 2.5,
                y - 2.5,
                item.role.stroke()
            );
        }
    }
    let _ = writeln!(s, "</g>");

    // Curves.
    let _ = writeln!(
        s,
        "<g id=\"curves\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">"
    );
    for (item, pts) in figure.curves.iter().zip(&curve_points) {
        let width = if item.role == Role::Result { 2.6 } else { 2.0 };
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" stroke=\"{}\" stroke-width=\"{width}\"{}><title>{}</title></polyline>",
            polyline(pts, map),
            item.role.stroke(),
            item.role.dash(),
            escape(&item.label)
        );
    }
    let _ = writeln!(s, "</g>");

    // Markers.
    let _ = writeln!(s, "<g id=\"markers\">");
    for m in &figure.markers {
        let (x, y) = map(marker_xy(m));
        s.push_str(&marker_svg(m.kind, x, y));
        if !m.label.is_empty() {
            let _ = writeln!(
                s,
                "<text x=\"{:.2}\" y=\"{:.2}\" fill=\"#333\" font-size=\"12\">{}</text>",
                x + 8.0,
                y - 8.0,
                escape(&m.label)
            );
        }
    }
    let _ = writeln!(s, "</g>");

    // Legend.
    let mut y = drawing_height + LINE_HEIGHT;
    let _ = writeln!(s, "<g id=\"legend\">");
    for item in &figure.curves {
        let _ = writeln!(
            s,
            "<line x1=\"{:.1}\" y1=\"{:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"{}\" stroke-width=\"2.4\"{}/>",
            MARGIN,
            y - 4.0,
            MARGIN + 30.0,
            y - 4.0,
            item.role.stroke(),
            item.role.dash()
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\">{}</text>",
            MARGIN + 40.0,
            y,
            escape(&item.label)
        );
        y += LINE_HEIGHT;
    }
    let mut kinds_done = Vec::new();
    for m in &figure.markers {
        if kinds_done.contains(&m.kind) {
            continue;
        }
        kinds_done.push(m.kind);
        s.push_str(&marker_svg(m.kind, MARGIN + 15.0, y - 4.0));
        let text = match m.kind {
            MarkerKind::Join => "join point",
            MarkerKind::Crossing => "crossing of the given curves",
            MarkerKind::Constraint => "prescribed point",
        };
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\">{}</text>",
            MARGIN + 40.0,
            y,
            text
        );
        y += LINE_HEIGHT;
    }
    let _ = writeln!(s, "</g>");

    // Caption.
    y += 8.0;
    let _ = writeln!(s, "<g id=\"caption\">");
    let _ = writeln!(
        s,
        "<text x=\"{MARGIN:.1}\" y=\"{y:.1}\" font-weight=\"bold\" font-size=\"14\">{}</text>",
        escape(&figure.title)
    );
    for line in &caption {
        y += LINE_HEIGHT;
        let _ = writeln!(
            s,
            "<text x=\"{MARGIN:.1}\" y=\"{y:.1}\" fill=\"#222\">{}</text>",
            escape(line)
        );
    }
    let _ = writeln!(s, "</g>");
    s.push_str("</svg>\n");
    s
}

fn marker_xy(m: &Marker) -> [f64; 2] {
    [
        m.at.first().copied().unwrap_or(0.0),
        m.at.get(1).copied().unwrap_or(0.0),
    ]
}

fn marker_svg(kind: MarkerKind, x: f64, y: f64) -> String {
    match kind {
        MarkerKind::Join => format!(
            "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"5\" fill=\"white\" stroke=\"black\" stroke-width=\"1.6\"/>\n"
        ),
        MarkerKind::Crossing => format!(
            "<path d=\"M{:.2} {:.2}L{:.2} {:.2}M{:.2} {:.2}L{:.2} {:.2}\" stroke=\"black\" stroke-width=\"2\"/>\n",
            x - 5.0,
            y - 5.0,
            x + 5.0,
            y + 5.0,
            x - 5.0,
            y + 5.0,
            x + 5.0,
            y - 5.0
        ),
        MarkerKind::Constraint => format!(
            "<path d=\"M{x:.2} {:.2}L{:.2} {y:.2}L{x:.2} {:.2}L{:.2} {y:.2}Z\" fill=\"#ffd23f\" stroke=\"black\" stroke-width=\"1.2\"/>\n",
            y - 6.0,
            x + 6.0,
            y + 6.0,
            x - 6.0
        ),
    }
}

fn polyline(points: &[[f64; 2]], map: impl Fn([f64; 2]) -> (f64, f64)) -> String {
    let mut out = String::with_capacity(points.len() * 16);
    for &p in points {
        let (x, y) = map(p);
        if x.is_finite() && y.is_finite() {
            let _ = write!(out, "{x:.2},{y:.2} ");
        }
    }
    out.pop();
    out
}

#[cfg(test)]
mod tests {
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
