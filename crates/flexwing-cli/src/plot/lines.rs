//! A general figure of stacked panels of line series (x against y), for the reproduction's
//! figures that are not beam shapes or tip histories (relative errors against time).

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;

use super::{tick_format, titled, write_figure, DrawResult, Figure, COLOURS, FONT};

/// Height of one panel (px).
const PANEL_HEIGHT: u32 = 380;

/// Stacked panels sharing a title.
pub struct LinePlot {
    /// Figure title.
    pub title: String,
    /// Panels, top to bottom.
    pub panels: Vec<Panel>,
}

/// One panel.
pub struct Panel {
    /// Horizontal axis label.
    pub x_label: String,
    /// Vertical axis label.
    pub y_label: String,
    /// The series, drawn in order.
    pub series: Vec<Series>,
}

/// One line.
pub struct Series {
    /// Legend text.
    pub label: String,
    /// Dashed or solid.
    pub dashed: bool,
    /// Index into the line colours; `None`: the series' position in its panel.
    pub colour: Option<usize>,
    /// Points; non-finite ones are skipped.
    pub points: Vec<(f64, f64)>,
}

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
    let x_format = tick_format(x1 - x0);
    let y_format = tick_format(top - y0);
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(95)
        .build_cartesian_2d(x0..x1, y0..top)?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .label_style((FONT, 18))
        .axis_desc_style((FONT, 20))
        .light_line_style(RGBColor(240, 240, 240))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()?;
    for (k, s) in panel.series.iter().enumerate() {
        let style = COLOURS[s.colour.unwrap_or(k) % COLOURS.len()].stroke_width(if s.dashed {
            2
        } else {
            3
        });
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect();
        let label = s.label.clone();
        if s.dashed {
            chart
                .draw_series(std::iter::once(DashedPathElement::new(pts, 9, 6, style)))?
                .label(label)
                .legend(move |(x, y)| {
                    DashedPathElement::new(vec![(x, y), (x + 30, y)], 9, 6, style)
                });
        } else {
            chart
                .draw_series(LineSeries::new(pts, style))?
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 30, y)], style));
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .legend_area_size(42)
        .margin(10)
        .label_font((FONT, 17))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.6))
        .draw()?;
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
