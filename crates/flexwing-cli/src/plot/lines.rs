//! A general figure of stacked panels of line series (x against y), for the reproduction's
//! figures that are not beam shapes or tip histories (relative errors against time).

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    finite_points, legend, lines, mesh, titled, write_figure, DrawResult, Figure, COLOURS,
};

/// Height of one panel (px).
const PANEL_HEIGHT: u32 = 380;

pub use flexwing_paper::figure::{LinesFigure as LinePlot, Panel, Series};

/// Write `<stem>.svg` and `<stem>.png` into `dir`; returns the paths written.
pub fn write_lines(dir: &Path, stem: &str, plot: &LinePlot) -> Result<Vec<PathBuf>> {
    write_figure(dir, stem, plot)
}

impl Figure for LinePlot {
    fn size(&self) -> (u32, u32) {
        (1200, 60 + self.panels.len().max(1) as u32 * PANEL_HEIGHT)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let body = titled(root, &self.title)?;
        let areas = body.split_evenly((self.panels.len().max(1), 1));
        for (panel, area) in self.panels.iter().zip(&areas) {
            draw_panel(area, panel)?;
        }
        root.present()
    }
}

fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        (0.0, 1.0)
    } else if hi - lo <= 1e-12 * hi.abs().max(lo.abs()).max(1e-300) {
        (lo - 0.5 * lo.abs().max(1.0), hi + 0.5 * hi.abs().max(1.0))
    } else {
        (lo, hi)
    }
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> DrawResult<DB> {
    let points = || panel.series.iter().flat_map(|s| s.points.iter());
    let (x0, x1) = range(points().map(|p| p.0));
    let (y0, y1) = range(points().map(|p| p.1));
    // Headroom above the data for the legend.
    let rows = panel.series.len() as f64;
    let top = y1 + (y1 - y0) * (0.12 + 0.08 * rows);
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(95)
        .build_cartesian_2d(x0..x1, y0..top)?;
    let axes = (panel.x_label.as_str(), panel.y_label.as_str());
    mesh(&mut chart, axes, (x1 - x0, top - y0), (240, 215))?;
    for (k, s) in panel.series.iter().enumerate() {
        let colour = COLOURS[s.colour.unwrap_or(k) % COLOURS.len()];
        let style = colour.stroke_width(if s.dashed { 2 } else { 3 });
        let points = finite_points(s.points.iter().copied());
        lines(
            &mut chart,
            vec![points],
            style,
            s.dashed,
            Some(s.label.clone()),
        )?;
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight, 10, 17)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_are_never_empty() {
        assert_eq!(range([1.0, 3.0].into_iter()), (1.0, 3.0));
        let (lo, hi) = range([2.0, 2.0].into_iter());
        assert!(lo < 2.0 && hi > 2.0);
        assert_eq!(range([f64::NAN].into_iter()), (0.0, 1.0));
    }
}
