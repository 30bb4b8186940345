//! Page layout: where the drawing goes (model to SVG coordinates, `y`
//! flipped), the caption lines, and the heights of the drawing, legend and
//! caption.

use super::bounds::Bounds;
use super::comb::Combs;
use super::plot::PLOT_ROW_HEIGHT;
use super::{Figure, legend_curves, legend_marker_kinds};

/// Width of the whole picture, pixels.
pub(super) const DRAWING_WIDTH: f64 = 820.0;
/// Space around the drawing, pixels.
pub(super) const MARGIN: f64 = 24.0;
/// Height of one legend or caption line, pixels.
pub(super) const LINE_HEIGHT: f64 = 18.0;
/// Tallest drawing inside the margins, pixels.
const MAX_INNER_HEIGHT: f64 = 560.0;
/// Shortest drawing inside the margins, pixels.
const MIN_INNER_HEIGHT: f64 = 120.0;

/// Where everything goes on the page.
pub(super) struct Layout {
    /// Pixels per model unit.
    scale: f64,
    /// Left edge of the model bounds on the page.
    x_offset: f64,
    /// Top edge of the model bounds on the page.
    y_offset: f64,
    /// Smallest model `x`.
    min_x: f64,
    /// Largest model `y`.
    max_y: f64,
    /// Height of the drawing with its margins (the plots start below).
    pub(super) drawing_height: f64,
    /// Height of the row of plots (0 without plots; the legend starts below).
    pub(super) plots_height: f64,
    /// Height of the whole picture.
    pub(super) total_height: f64,
    /// Caption lines below the title: the figure's, then the notes on
    /// projection, clipping and the comb scale.
    pub(super) caption: Vec<String>,
}

impl Layout {
    /// Lay out `figure` whose model `bounds` (comb tips included) have the
    /// larger side `size` measured before the comb tips were added.
    pub(super) fn new(figure: &Figure, bounds: &Bounds, size: f64, combs: &Combs) -> Self {
        let width_model = (bounds.max[0] - bounds.min[0]).max(1e-12 * size);
        let height_model = (bounds.max[1] - bounds.min[1]).max(1e-12 * size);
        let inner_width = DRAWING_WIDTH - 2.0 * MARGIN;
        let mut scale = inner_width / width_model;
        if height_model * scale > MAX_INNER_HEIGHT {
            scale = MAX_INNER_HEIGHT / height_model;
        }
        let inner_height = (height_model * scale).max(MIN_INNER_HEIGHT);
        let x_offset = MARGIN + (inner_width - width_model * scale) / 2.0;
        let y_offset = MARGIN + (inner_height - height_model * scale) / 2.0;

        let caption = caption_lines(figure, combs);
        let drawing_height = inner_height + 2.0 * MARGIN;
        let plots_height = if figure.plots.is_empty() {
            0.0
        } else {
            PLOT_ROW_HEIGHT
        };
        let legend_height = LINE_HEIGHT * legend_rows(figure) as f64 + 8.0;
        let caption_height = LINE_HEIGHT * (caption.len() + 1) as f64 + 12.0;
        Layout {
            scale,
            x_offset,
            y_offset,
            min_x: bounds.min[0],
            max_y: bounds.max[1],
            drawing_height,
            plots_height,
            total_height: drawing_height + plots_height + legend_height + caption_height,
            caption,
        }
    }

    /// Model point to SVG coordinates (y flipped).
    pub(super) fn map(&self, p: [f64; 2]) -> (f64, f64) {
        (
            self.x_offset + (p[0] - self.min_x) * self.scale,
            self.y_offset + (self.max_y - p[1]) * self.scale,
        )
    }
}

/// The figure's caption lines followed by the picture's own notes.
fn caption_lines(figure: &Figure, combs: &Combs) -> Vec<String> {
    let largest_dim = figure.curves.iter().map(|c| c.shape.dim()).max();
    let graph = figure.curves.iter().any(|c| c.shape.dim() == 1);
    let mut caption = figure.caption.clone();
    if let Some(dim) = largest_dim.filter(|d| *d >= 3) {
        caption.push(format!(
            "{dim}D curves shown in top view (x-y projection); combs show the curvature of the projection."
        ));
    }
    if graph {
        caption.push("1D curves shown as graphs (t, x(t)).".into());
    }
    if combs.clipped {
        caption.push("Some comb spikes are clipped (very high curvature there).".into());
    }
    caption.push(format!(
        "Curvature combs: spike length = {:.3e} x curvature (same scale for every curve); y points up.",
        combs.scale
    ));
    caption
}

/// Legend rows: one per listed curve and one per kind of marker.
fn legend_rows(figure: &Figure) -> usize {
    legend_curves(figure).len() + legend_marker_kinds(figure).len()
}
