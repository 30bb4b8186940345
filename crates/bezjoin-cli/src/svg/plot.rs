//! The row of graphs below the drawing ([`super::Plot`]): each in its own
//! box with axes, "nice" ticks, a zero line, dashed vertical marks and its
//! series clipped to the box.

use std::fmt::Write as _;

use super::layout::{DRAWING_WIDTH, MARGIN};
use super::{Plot, escape};

/// Height of the row of plots, pixels (boxes, titles and axis labels).
pub(super) const PLOT_ROW_HEIGHT: f64 = 210.0;
/// Gap between two plots, pixels.
const PLOT_GAP: f64 = 18.0;
/// Room left of a plot box for the vertical tick labels, pixels.
const LEFT_ROOM: f64 = 56.0;
/// Room above a plot box for its title, pixels.
const TOP_ROOM: f64 = 24.0;
/// Room below a plot box for the horizontal tick labels and axis name.
const BOTTOM_ROOM: f64 = 38.0;

/// Tick values: multiples of a step of 1, 2 or 5 times a power of ten
/// giving the number of intervals nearest `count` over `[lo, hi]`, and the
/// step.
fn ticks(lo: f64, hi: f64, count: usize) -> (Vec<f64>, f64) {
    let span = hi - lo;
    if !(span > 0.0 && span.is_finite()) {
        return (vec![lo], 1.0);
    }
    let raw = span / count as f64;
    let power = 10f64.powf(raw.log10().floor());
    let intervals = |step: f64| span / step;
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * power)
        .min_by(|a, b| {
            (intervals(*a) - count as f64)
                .abs()
                .total_cmp(&(intervals(*b) - count as f64).abs())
        })
        .unwrap_or(power);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let values = (first..=last)
        .map(|i| {
            let v = i as f64 * step;
            if v.abs() < 1e-12 * step { 0.0 } else { v }
        })
        .collect();
    (values, step)
}

/// A tick label with as many decimals as the step needs.
fn tick_label(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// The plots of a figure side by side, their row starting at `top`.
pub(super) fn plot_group(s: &mut String, plots: &[Plot], top: f64) {
    if plots.is_empty() {
        return;
    }
    let n = plots.len() as f64;
    let width = (DRAWING_WIDTH - 2.0 * MARGIN - (n - 1.0) * PLOT_GAP) / n;
    let _ = writeln!(s, "<g id=\"plots\" font-size=\"11\">");
    for (i, plot) in plots.iter().enumerate() {
        let left = MARGIN + i as f64 * (width + PLOT_GAP);
        one_plot(s, plot, i, left, top, width);
    }
    let _ = writeln!(s, "</g>");
}

fn one_plot(s: &mut String, plot: &Plot, index: usize, left: f64, top: f64, width: f64) {
    let x0 = left + LEFT_ROOM;
    let w = width - LEFT_ROOM;
    let y0 = top + TOP_ROOM;
    let h = PLOT_ROW_HEIGHT - TOP_ROOM - BOTTOM_ROOM;
    let [xa, xb] = plot.x_bounds();
    let [ya, yb] = plot.y_bounds();
    let map = |p: [f64; 2]| -> (f64, f64) {
        (
            x0 + (p[0] - xa) / (xb - xa) * w,
            y0 + (yb - p[1]) / (yb - ya) * h,
        )
    };
    let _ = writeln!(
        s,
        "<text x=\"{left:.1}\" y=\"{:.1}\" font-size=\"12\" font-weight=\"bold\">{}</text>",
        top + 14.0,
        escape(&plot.title)
    );
    let _ = writeln!(
        s,
        "<rect x=\"{x0:.1}\" y=\"{y0:.1}\" width=\"{w:.1}\" height=\"{h:.1}\" fill=\"#fcfcfc\" stroke=\"#bbbbbb\"/>"
    );
    // Ticks and grid.
    let (y_ticks, y_step) = ticks(ya, yb, 4);
    for v in y_ticks {
        let (_, y) = map([xa, v]);
        let stroke = if v == 0.0 { "#888888" } else { "#e6e6e6" };
        let _ = writeln!(
            s,
            "<line x1=\"{x0:.1}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"{stroke}\" stroke-width=\"0.8\"/>",
            x0 + w
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\" fill=\"#444\">{}</text>",
            x0 - 4.0,
            y + 4.0,
            tick_label(v, y_step)
        );
    }
    let (x_ticks, x_step) = ticks(xa, xb, 4);
    for v in x_ticks {
        let (x, _) = map([v, ya]);
        let _ = writeln!(
            s,
            "<line x1=\"{x:.1}\" y1=\"{:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#888888\" stroke-width=\"0.8\"/>",
            y0 + h,
            y0 + h + 4.0
        );
        let _ = writeln!(
            s,
            "<text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\" fill=\"#444\">{}</text>",
            y0 + h + 15.0,
            tick_label(v, x_step)
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\" fill=\"#222\">{}</text>",
        x0 + w / 2.0,
        y0 + h + 30.0,
        escape(&plot.x_label)
    );
    let (yx, yy) = (left + 10.0, y0 + h / 2.0);
    let _ = writeln!(
        s,
        "<text x=\"{yx:.1}\" y=\"{yy:.1}\" text-anchor=\"middle\" transform=\"rotate(-90 {yx:.1} {yy:.1})\" fill=\"#222\">{}</text>",
        escape(&plot.y_label)
    );
    for &m in &plot.x_marks {
        let (x, _) = map([m, ya]);
        let _ = writeln!(
            s,
            "<line x1=\"{x:.1}\" y1=\"{y0:.1}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#555555\" stroke-width=\"0.8\" stroke-dasharray=\"3 3\"/>",
            y0 + h
        );
    }
    // The series, clipped to the box.
    let _ = writeln!(
        s,
        "<clipPath id=\"plot-clip-{index}\"><rect x=\"{x0:.1}\" y=\"{y0:.1}\" width=\"{w:.1}\" height=\"{h:.1}\"/></clipPath>"
    );
    let _ = writeln!(
        s,
        "<g clip-path=\"url(#plot-clip-{index})\" fill=\"none\" stroke-linejoin=\"round\">"
    );
    for series in &plot.series {
        let mut points = String::new();
        for &p in &series.points {
            let (x, y) = map(p);
            if x.is_finite() && y.is_finite() {
                let _ = write!(points, "{x:.2},{y:.2} ");
            }
        }
        points.pop();
        let _ = writeln!(
            s,
            "<polyline points=\"{points}\" stroke=\"{}\" stroke-width=\"1.8\"{}><title>{}</title></polyline>",
            series.role.stroke(),
            series.role.dash(),
            escape(&series.label)
        );
    }
    let _ = writeln!(s, "</g>");
}

#[cfg(test)]
mod plot_tests {
    use super::*;

    #[test]
    fn ticks_are_round_and_inside() {
        let (t, step) = ticks(-0.07, 0.93, 4);
        assert_eq!(step, 0.2);
        assert_eq!(t.len(), 5);
        assert!(t.contains(&0.0));
        assert!(t.iter().all(|v| (-0.07..=0.93).contains(v)));
        assert_eq!(tick_label(0.4, step), "0.4");
        assert_eq!(tick_label(10.0, 5.0), "10");
    }
}
