//! Writing the SVG document: background, combs (under everything), control
//! polygons, curves, markers, legend and caption, in that order.

use std::fmt::Write as _;

use super::comb::{COMB_SPIKES, COMB_TIP_SAMPLES, Combs};
use super::layout::{DRAWING_WIDTH, LINE_HEIGHT, Layout, MARGIN};
use super::{Figure, MarkerKind, Role, escape, legend_curves, legend_marker_kinds, marker_xy};

/// The SVG document of `figure`, laid out by `layout`; `curve_points` are
/// the sampled curves.
pub(super) fn svg(
    figure: &Figure,
    curve_points: &[Vec<[f64; 2]>],
    combs: &Combs,
    layout: &Layout,
) -> String {
    let mut s = String::new();
    header(&mut s, figure, layout);
    comb_group(&mut s, figure, combs, layout);
    polygon_group(&mut s, figure, layout);
    curve_group(&mut s, figure, curve_points, layout);
    marker_group(&mut s, figure, layout);
    super::plot::plot_group(&mut s, &figure.plots, layout.drawing_height);
    let y = legend_group(&mut s, figure, layout);
    caption_group(&mut s, figure, layout, y + 8.0);
    s.push_str("</svg>\n");
    s
}

/// XML declaration, `<svg>` start tag, title, background and drawing frame.
fn header(s: &mut String, figure: &Figure, layout: &Layout) {
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.0}\" height=\"{h:.0}\" viewBox=\"0 0 {w:.0} {h:.0}\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\" font-size=\"13\">",
        w = DRAWING_WIDTH,
        h = layout.total_height
    );
    let _ = writeln!(s, "<title>{}</title>", escape(&figure.title));
    let _ = writeln!(
        s,
        "<rect x=\"0\" y=\"0\" width=\"{:.0}\" height=\"{:.0}\" fill=\"white\"/>",
        DRAWING_WIDTH, layout.total_height
    );
    let _ = writeln!(
        s,
        "<rect x=\"0.5\" y=\"0.5\" width=\"{:.0}\" height=\"{:.1}\" fill=\"none\" stroke=\"#e0e0e0\"/>",
        DRAWING_WIDTH - 1.0,
        layout.drawing_height - 1.0
    );
}

/// The combs: spikes, then the tip line, per curve that has one.
fn comb_group(s: &mut String, figure: &Figure, combs: &Combs, layout: &Layout) {
    let _ = writeln!(s, "<g id=\"combs\" fill=\"none\">");
    for ((item, comb), tip) in figure.curves.iter().zip(&combs.samples).zip(&combs.tips) {
        let (Some(samples), Some(tip)) = (comb, tip) else {
            continue;
        };
        let step = (COMB_TIP_SAMPLES / COMB_SPIKES).max(1);
        let mut d = String::new();
        for i in (0..samples.len()).step_by(step) {
            let (a, b) = (layout.map(samples[i].0), layout.map(tip[i]));
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
            polyline(tip, layout),
            item.role.comb()
        );
    }
    let _ = writeln!(s, "</g>");
}

/// The control polygons (dashed) with their control points as squares.
fn polygon_group(s: &mut String, figure: &Figure, layout: &Layout) {
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
            polyline(&poly, layout),
            item.role.stroke()
        );
        for &p in &poly {
            let (x, y) = layout.map(p);
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
}

/// The curves, each with its label as a tooltip.
fn curve_group(s: &mut String, figure: &Figure, curve_points: &[Vec<[f64; 2]>], layout: &Layout) {
    let _ = writeln!(
        s,
        "<g id=\"curves\" fill=\"none\" stroke-linecap=\"round\" stroke-linejoin=\"round\">"
    );
    for (item, pts) in figure.curves.iter().zip(curve_points) {
        let width = if item.role == Role::Result { 2.6 } else { 2.0 };
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" stroke=\"{}\" stroke-width=\"{width}\"{}><title>{}</title></polyline>",
            polyline(pts, layout),
            item.role.stroke(),
            item.role.dash(),
            escape(&item.label)
        );
    }
    let _ = writeln!(s, "</g>");
}

/// An upper estimate of one character's advance at font size 12 (px).
const LABEL_CHAR_WIDTH: f64 = 7.2;

/// The markers with their labels.
fn marker_group(s: &mut String, figure: &Figure, layout: &Layout) {
    let _ = writeln!(s, "<g id=\"markers\">");
    for m in &figure.markers {
        let (x, y) = layout.map(marker_xy(m));
        if m.kind == MarkerKind::Label {
            let _ = writeln!(
                s,
                "<text x=\"{x:.2}\" y=\"{y:.2}\" fill=\"#222\" font-size=\"13\" font-weight=\"bold\">{}</text>",
                escape(&m.label)
            );
            continue;
        }
        s.push_str(&marker_svg(m.kind, x, y));
        if !m.label.is_empty() {
            // Right of the marker, or left of it (anchored at its end) when
            // the label would run past the drawing's right edge.
            let (lx, anchor) =
                if x + 8.0 + LABEL_CHAR_WIDTH * m.label.chars().count() as f64 > DRAWING_WIDTH {
                    (x - 8.0, " text-anchor=\"end\"")
                } else {
                    (x + 8.0, "")
                };
            let _ = writeln!(
                s,
                "<text x=\"{lx:.2}\" y=\"{:.2}\" fill=\"#333\" font-size=\"12\"{anchor}>{}</text>",
                y - 8.0,
                escape(&m.label)
            );
        }
    }
    let _ = writeln!(s, "</g>");
}

/// The legend below the drawing: one row per curve, then one per kind of
/// marker. Returns the baseline after its last row.
fn legend_group(s: &mut String, figure: &Figure, layout: &Layout) -> f64 {
    let mut y = layout.drawing_height + layout.plots_height + LINE_HEIGHT;
    let _ = writeln!(s, "<g id=\"legend\">");
    for item in legend_curves(figure) {
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
    for kind in legend_marker_kinds(figure) {
        s.push_str(&marker_svg(kind, MARGIN + 15.0, y - 4.0));
        let text = match kind {
            MarkerKind::Join => "join point",
            MarkerKind::Crossing => "crossing of the given curves",
            MarkerKind::Constraint => "prescribed point",
            MarkerKind::Centre => "centre of the circular arc",
            MarkerKind::Label => "",
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
    y
}

/// The bold title and the caption lines, the first baseline at `y`.
fn caption_group(s: &mut String, figure: &Figure, layout: &Layout, mut y: f64) {
    let _ = writeln!(s, "<g id=\"caption\">");
    let _ = writeln!(
        s,
        "<text x=\"{MARGIN:.1}\" y=\"{y:.1}\" font-weight=\"bold\" font-size=\"14\">{}</text>",
        escape(&figure.title)
    );
    for line in &layout.caption {
        y += LINE_HEIGHT;
        let _ = writeln!(
            s,
            "<text x=\"{MARGIN:.1}\" y=\"{y:.1}\" fill=\"#222\">{}</text>",
            escape(line)
        );
    }
    let _ = writeln!(s, "</g>");
}

/// The symbol of a marker of `kind` centred at (`x`, `y`), SVG coordinates.
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
        MarkerKind::Centre => format!(
            "<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"3.5\" fill=\"none\" stroke=\"#7d3c98\" stroke-width=\"1.4\"/>\n<path d=\"M{:.2} {y:.2}L{:.2} {y:.2}M{x:.2} {:.2}L{x:.2} {:.2}\" stroke=\"#7d3c98\" stroke-width=\"1.4\"/>\n",
            x - 7.0,
            x + 7.0,
            y - 7.0,
            y + 7.0
        ),
        MarkerKind::Label => String::new(),
    }
}

/// The `points` attribute of a polyline through the model points `points`;
/// points that map to non-finite coordinates are left out.
fn polyline(points: &[[f64; 2]], layout: &Layout) -> String {
    let mut out = String::with_capacity(points.len() * 16);
    for &p in points {
        let (x, y) = layout.map(p);
        if x.is_finite() && y.is_finite() {
            let _ = write!(out, "{x:.2},{y:.2} ");
        }
    }
    out.pop();
    out
}
