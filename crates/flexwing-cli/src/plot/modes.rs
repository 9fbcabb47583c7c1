//! The figure of `flexwing modes`: mode shapes against the span, and the twist with torsion.

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{mesh, titled, write_figure, DrawResult, Figure, COLOURS, FONT};
use crate::output;
use flexwing::analysis::modes::ModeResult;

/// Most modes drawn in one figure.
pub const MAX_PLOTTED_MODES: usize = 6;

/// What the figure shows.
pub struct ModePlot<'a> {
    /// Figure title.
    pub title: String,
    /// Span (m).
    pub length: f64,
    /// Whether to draw the twist panel.
    pub has_torsion: bool,
    /// The modes to draw (at most [`MAX_PLOTTED_MODES`] are used).
    pub modes: &'a [ModeResult],
}

/// Write `mode_shapes.svg` and `mode_shapes.png` into `dir`; returns the paths written.
pub fn write_mode_shapes(dir: &Path, plot: &ModePlot) -> Result<Vec<PathBuf>> {
    write_figure(dir, "mode_shapes", plot)
}

impl Figure for ModePlot<'_> {
    fn size(&self) -> (u32, u32) {
        (1200, if self.has_torsion { 1000 } else { 560 })
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let plot = self;
        let body = titled(root, &plot.title)?;
        let modes = &plot.modes[..plot.modes.len().min(MAX_PLOTTED_MODES)];
        if plot.has_torsion {
            let (top, bottom) = body.split_vertically(body.dim_in_pixel().1 / 2);
            panel(
                &top,
                plot.length,
                modes,
                "vertical displacement dy (m)",
                |m| &m.shape.dy,
            )?;
            panel(&bottom, plot.length, modes, "twist (rad)", |m| {
                &m.shape.twist
            })?;
        } else {
            panel(
                &body,
                plot.length,
                modes,
                "vertical displacement dy (m)",
                |m| &m.shape.dy,
            )?;
        }
        root.present()
    }
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    length: f64,
    modes: &[ModeResult],
    y_label: &str,
    values: impl Fn(&ModeResult) -> &Vec<f64>,
) -> DrawResult<DB> {
    let (lo, hi) = y_range(modes.iter().flat_map(|m| values(m).iter().copied()));
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..length, lo..hi)?;
    mesh(
        &mut chart,
        ("x (m)", y_label),
        (length, hi - lo),
        (235, 205),
    )?;
    // The zero line, for reading signs.
    chart.draw_series(LineSeries::new(
        [(0.0, 0.0), (length, 0.0)],
        BLACK.mix(0.5).stroke_width(1),
    ))?;
    for (k, m) in modes.iter().enumerate() {
        let colour = COLOURS[k % COLOURS.len()];
        let points = m.shape.x.iter().copied().zip(values(m).iter().copied());
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(3)))?
            .label(format!(
                "mode {}: {} Hz",
                m.mode,
                output::significant(m.frequency_hz, 4)
            ))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 24, y)], colour.stroke_width(3)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .margin(12)
        .label_font((FONT, 18))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.6))
        .draw()
}

/// Axis range around the data, with room above for the legend.
fn y_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = values
        .filter(|v| v.is_finite())
        .fold((0.0_f64, 0.0_f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
    let span = hi - lo;
    if span <= f64::MIN_POSITIVE {
        return (-1.0, 1.0);
    }
    lo -= 0.08 * span;
    hi += 0.45 * span;
    (lo, hi)
}
