//! Deformed shapes `y(x)` on axes of equal scale: the figure of `flexwing static` (every sweep
//! point, one colour per model, the full model solid and reduced models dashed) and the snapshots
//! of `flexwing dynamic` (one shape per output time, coloured from dark to light along a gradient).

use std::path::{Path, PathBuf};

use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

use super::{legend, lines, mesh, titled, write_figure, DrawResult, Figure, COLOURS};

/// Canvas width (px).
const WIDTH: u32 = 1200;
/// Space around the plotting area: chart margin, axis label areas and title (px).
const MARGIN: u32 = 20;
const X_LABEL_AREA: u32 = 55;
const Y_LABEL_AREA: u32 = 90;
const TITLE_AREA: u32 = 45;
/// Height of one legend entry (px).
const LEGEND_ROW: f64 = 28.0;

pub use flexwing_paper::figure::{ModelShapes, ShapesFigure as ShapePlot};

/// Write `<stem>.svg` and `<stem>.png` into `dir`; returns the paths written.
pub fn write_shapes(dir: &Path, stem: &str, plot: &ShapePlot) -> Result<Vec<PathBuf>> {
    write_figure(dir, stem, plot)
}

/// Axis ranges of the chart (m).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frame {
    x: (f64, f64),
    y: (f64, f64),
}

/// The geometry of a shape plot.
trait Layout {
    fn bounds(&self) -> Frame;
    fn legend_px(&self) -> f64;
    fn frame(&self, size: (u32, u32)) -> Frame;
}

impl Layout for ShapePlot {
    /// Bounding box of the data and the undeformed beam, with a 4 % margin.
    fn bounds(&self) -> Frame {
        let mut x = (0.0_f64, self.length);
        let mut y = (0.0_f64, 0.0_f64);
        for (px, py) in self
            .models
            .iter()
            .flat_map(|m| m.shapes.iter().flatten())
            .filter(|(a, b)| a.is_finite() && b.is_finite())
        {
            x = (x.0.min(*px), x.1.max(*px));
            y = (y.0.min(*py), y.1.max(*py));
        }
        let pad = 0.04 * (x.1 - x.0).max(y.1 - y.0).max(f64::MIN_POSITIVE);
        Frame {
            x: (x.0 - pad, x.1 + pad),
            y: (y.0 - pad, y.1 + pad),
        }
    }

    fn legend_px(&self) -> f64 {
        let entries = self.models.iter().filter(|m| !m.label.is_empty()).count();
        20.0 + LEGEND_ROW * (entries + 1) as f64
    }

    /// Equal-scale ranges for a plotting area of `(width, height)` pixels.
    fn frame(&self, (width, height): (u32, u32)) -> Frame {
        let b = self.bounds();
        let (w, h) = (f64::from(width.max(1)), f64::from(height.max(1)));
        let free = (h - self.legend_px()).max(h / 3.0);
        let (dx, dy) = (b.x.1 - b.x.0, b.y.1 - b.y.0);
        let per_px = (dx / w).max(dy / free);
        let x_slack = w * per_px - dx;
        let y_slack = free * per_px - dy;
        let y0 = b.y.0 - 0.5 * y_slack;
        Frame {
            x: (b.x.0 - 0.5 * x_slack, b.x.1 + 0.5 * x_slack),
            y: (y0, y0 + h * per_px),
        }
    }
}

impl Figure for ShapePlot {
    /// The height follows the aspect ratio of the data, within 500 to 1100 px.
    fn size(&self) -> (u32, u32) {
        let b = self.bounds();
        let plot_w = f64::from(WIDTH - 2 * MARGIN - Y_LABEL_AREA);
        let aspect = (b.y.1 - b.y.0) / (b.x.1 - b.x.0);
        let plot_h = plot_w * aspect + self.legend_px();
        let overhead = f64::from(2 * MARGIN + X_LABEL_AREA + TITLE_AREA);
        let height = (plot_h + overhead).clamp(500.0, 1100.0);
        (WIDTH, height.round() as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let body = titled(root, &self.title)?;
        // A first chart only to learn the plotting area's size; nothing is drawn on it.
        let probe = ChartBuilder::on(&body)
            .margin(MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA)
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?;
        let frame = self.frame(probe.plotting_area().dim_in_pixel());
        drop(probe);

        let mut chart = ChartBuilder::on(&body)
            .margin(MARGIN)
            .x_label_area_size(X_LABEL_AREA)
            .y_label_area_size(Y_LABEL_AREA)
            .build_cartesian_2d(frame.x.0..frame.x.1, frame.y.0..frame.y.1)?;
        let spans = (frame.x.1 - frame.x.0, frame.y.1 - frame.y.0);
        mesh(&mut chart, ("x (m)", "y (m)"), spans, (240, 215))?;

        let grey = RGBColor(150, 150, 150);
        chart
            .draw_series(LineSeries::new(
                [(0.0, 0.0), (self.length, 0.0)],
                grey.stroke_width(4),
            ))?
            .label("undeformed")
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 30, y)], grey.stroke_width(4)));

        for (k, model) in self.models.iter().enumerate() {
            let colour = if self.gradient {
                gradient(k as f64 / (self.models.len().max(2) - 1) as f64)
            } else {
                COLOURS[k % COLOURS.len()]
            };
            let style = colour.stroke_width(2);
            let label = model.label.clone();
            // The tips, so the end points can be told apart where curves overlap.
            chart.draw_series(
                model
                    .shapes
                    .iter()
                    .filter_map(|s| s.last())
                    .map(|&p| Circle::new(p, 3, colour.filled())),
            )?;
            let shapes = model.shapes.clone();
            lines(&mut chart, shapes, style, model.dashed, Some(label))?;
        }
        legend(&mut chart, SeriesLabelPosition::UpperLeft, 12, 18)?;
        root.present()
    }
}

/// Anchors of the gradient: the viridis colour map (dark blue, teal, green, yellow).
const GRADIENT: [(f64, f64, f64); 5] = [
    (68.0, 1.0, 84.0),
    (59.0, 82.0, 139.0),
    (33.0, 145.0, 140.0),
    (94.0, 201.0, 98.0),
    (253.0, 231.0, 37.0),
];

/// The colour at `s` in `[0, 1]` along [`GRADIENT`], stopping short of its palest end so that
/// every line stays visible on white.
fn gradient(s: f64) -> RGBColor {
    let s = 0.9 * s.clamp(0.0, 1.0) * (GRADIENT.len() - 1) as f64;
    let k = (s.floor() as usize).min(GRADIENT.len() - 2);
    let w = s - k as f64;
    let (a, b) = (GRADIENT[k], GRADIENT[k + 1]);
    let mix = |p: f64, q: f64| (p + w * (q - p)).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plot(shape: Vec<(f64, f64)>) -> ShapePlot {
        ShapePlot {
            title: String::new(),
            length: 1.0,
            models: vec![ModelShapes {
                label: "full".into(),
                dashed: false,
                shapes: vec![shape],
            }],
            gradient: false,
        }
    }

    #[test]
    fn frame_has_equal_scales_and_contains_the_data() {
        let p = plot(vec![(0.0, 0.0), (0.5, -0.3), (0.8, -0.6)]);
        let px = (900, 500);
        let f = p.frame(px);
        let sx = (f.x.1 - f.x.0) / 900.0;
        let sy = (f.y.1 - f.y.0) / 500.0;
        assert!((sx / sy - 1.0).abs() < 1e-12, "{sx} vs {sy}");
        assert!(f.x.0 < 0.0 && f.x.1 > 1.0);
        assert!(f.y.0 < -0.6 && f.y.1 > 0.0);
    }

    #[test]
    fn gradient_runs_from_dark_to_light() {
        assert_eq!(gradient(0.0), RGBColor(68, 1, 84));
        let light = gradient(1.0);
        assert!(light.1 > 150 && light.1 < 231, "{light:?}");
    }
}
