//! The tip-history figure of `flexwing dynamic`: tip `y`, tip `x` (and the tip twist with torsion)
//! against time, one panel each, every model in every panel (the first solid, the others dashed).

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{
    finite_points, legend, lines, mesh, titled, write_figure, DrawResult, Figure, COLOURS,
};

/// Height of one panel (px).
const PANEL_HEIGHT: u32 = 380;
/// Height of one legend entry (px), for the headroom left above the curves.
const LEGEND_ROW: f64 = 26.0;

pub use flexwing_paper::figure::{HistoryFigure as HistoryPlot, TipSeries as HistorySeries};

/// Write `dynamic_tip.svg` and `dynamic_tip.png` into `dir`; returns the paths written.
pub fn write_tip_history(dir: &Path, plot: &HistoryPlot) -> Result<Vec<PathBuf>> {
    write_history(dir, "dynamic_tip", plot)
}

/// Write `<stem>.svg` and `<stem>.png` into `dir`; returns the paths written.
pub fn write_history(dir: &Path, stem: &str, plot: &HistoryPlot) -> Result<Vec<PathBuf>> {
    write_figure(dir, stem, plot)
}

/// Number of panels: tip y, tip x, and the twist with torsion.
fn panels(plot: &HistoryPlot) -> u32 {
    if plot.has_torsion {
        3
    } else {
        2
    }
}

impl Figure for HistoryPlot {
    fn size(&self) -> (u32, u32) {
        (1200, 60 + panels(self) * PANEL_HEIGHT)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let body = titled(root, &self.title)?;
        let panels = body.split_evenly((panels(self) as usize, 1));
        panel(&panels[0], self, "tip y (m)", |s| &s.y, true)?;
        panel(&panels[1], self, "tip x (m)", |s| &s.x, false)?;
        if self.has_torsion {
            panel(&panels[2], self, "tip twist (rad)", |s| &s.twist, false)?;
        }
        root.present()
    }
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    plot: &HistoryPlot,
    y_label: &str,
    values: impl Fn(&HistorySeries) -> &Vec<f64>,
    legend_entries: bool,
) -> DrawResult<DB> {
    let rows = if legend_entries { plot.series.len() } else { 0 };
    let (lo, hi) = y_range(
        plot.series.iter().flat_map(|s| values(s).iter().copied()),
        rows,
        area.dim_in_pixel().1,
    );
    let t_end = plot.end_time;
    let mut chart = ChartBuilder::on(area)
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(95)
        .build_cartesian_2d(0.0..t_end, lo..hi)?;
    mesh(&mut chart, ("t (s)", y_label), (t_end, hi - lo), (240, 215))?;
    for (k, s) in plot.series.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let style = colour.stroke_width(if s.dashed { 2 } else { 3 });
        let points = finite_points(s.t.iter().copied().zip(values(s).iter().copied()));
        let label = legend_entries.then(|| s.label.clone());
        lines(&mut chart, vec![points], style, s.dashed, label)?;
    }
    if legend_entries {
        legend(&mut chart, SeriesLabelPosition::UpperRight, 10, 17)?;
    }
    Ok(())
}

/// Axis range around the data, with headroom above it for `rows` legend entries in a panel of
/// `height` pixels.
fn y_range(values: impl Iterator<Item = f64>, rows: usize, height: u32) -> (f64, f64) {
    let (mut lo, mut hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let mut span = hi - lo;
    if span <= 1e-12 * hi.abs().max(lo.abs()).max(f64::MIN_POSITIVE) {
        // A constant history: centre it in a band of ±5 % of its value (or ±1).
        let half = if hi == 0.0 { 1.0 } else { 0.05 * hi.abs() };
        lo -= half;
        hi += half;
        span = hi - lo;
    }
    let plot_px = f64::from(height.saturating_sub(80).max(100));
    let legend_px = if rows == 0 {
        0.0
    } else {
        20.0 + LEGEND_ROW * rows as f64
    };
    // The data take what the legend leaves, at least half the height.
    let data_fraction = ((plot_px - legend_px) / plot_px).clamp(0.5, 0.92);
    let total = span / data_fraction;
    lo -= 0.04 * span;
    (lo, lo + total + 0.04 * span)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn range_contains_the_data_and_leaves_room_for_the_legend() {
        let (lo, hi) = y_range([-0.5, 0.5].into_iter(), 3, 380);
        assert!(lo < -0.5 && hi > 0.5);
        assert!(hi - 0.5 > 0.2, "no headroom: {hi}");
        let (lo, hi) = y_range([2.0, 2.0].into_iter(), 0, 380);
        assert!(lo < 2.0 && hi > 2.0);
        assert_eq!(y_range(std::iter::empty(), 1, 380), (-1.0, 1.0));
    }
}
