//! Plots (SVG and PNG) with plotters: mode shapes (`modes.rs`), deformed shapes (`shapes.rs`,
//! static equilibria and dynamic snapshots) and tip time histories (`history.rs`).
//!
//! Text is drawn with DejaVu Sans compiled into the binary (the `dejavu` crate, registered with
//! plotters' `ab_glyph` font table under the family name `sans-serif`), so the PNG renders the same
//! on a machine with no fonts installed. The SVG keeps its text as `<text>` elements in the
//! `sans-serif` family, which every SVG viewer can render.

mod history;
mod lines;
mod modes;
mod shapes;

pub use history::{write_history, write_tip_history, HistoryPlot, HistorySeries};
pub use lines::{write_lines, LinePlot, Panel, Series};
pub use modes::{write_mode_shapes, ModePlot};
pub use shapes::{write_shapes, ModelShapes, ShapePlot};

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::{anyhow, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::output;

/// Font family name under which the bundled font is registered.
const FONT: &str = "sans-serif";

/// Line colours of successive modes or models (colour-blind-friendly "tab10" hues).
const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure that can be drawn on any plotters backend.
trait Figure {
    /// Canvas size in pixels.
    fn size(&self) -> (u32, u32);
    /// Draw the whole figure on `root`.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// Write `<stem>.svg` and `<stem>.png` into `dir`, each atomically; returns the paths written.
fn write_figure(dir: &Path, stem: &str, figure: &impl Figure) -> Result<Vec<PathBuf>> {
    register_bundled_font()?;
    let size = figure.size();

    let svg_path = dir.join(format!("{stem}.svg"));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        figure
            .draw(&root)
            .map_err(|e| anyhow!("cannot draw {}: {e}", svg_path.display()))?;
    }
    output::write_bytes(&svg_path, svg.as_bytes())?;

    let png_path = dir.join(format!("{stem}.png"));
    output::write_atomic(&png_path, |tmp| {
        let root = BitMapBackend::new(tmp, size).into_drawing_area();
        figure.draw(&root).map_err(|e| anyhow!("{e}"))
    })?;
    Ok(vec![svg_path, png_path])
}

fn register_bundled_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        register_font(FONT, FontStyle::Normal, dejavu::sans::regular()).is_ok()
            && register_font(FONT, FontStyle::Bold, dejavu::sans::bold()).is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the bundled DejaVu Sans font could not be loaded"))
    }
}

/// Fill `root` white and draw `title` at the largest size (≤ 26) that fits the width; returns
/// the area below the title.
fn titled<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
) -> Result<DrawingArea<DB, Shift>, DrawingAreaErrorKind<DB::ErrorType>> {
    root.fill(&WHITE)?;
    let width = root.dim_in_pixel().0;
    let mut size = 26;
    while size > 12
        && root
            .estimate_text_size(title, &(FONT, size).into_text_style(root))?
            .0
            + 40
            > width
    {
        size -= 1;
    }
    root.titled(title, (FONT, size))
}

/// Tick labels for an axis spanning `range`: enough decimals for steps of about `range / 10`,
/// and no "-0.0".
fn tick_format(range: f64) -> impl Fn(&f64) -> String {
    let decimals = if range > 0.0 && range.is_finite() {
        (1 - range.log10().floor() as i32).max(0) as usize
    } else {
        1
    };
    move |v: &f64| {
        let v = if v.abs() < 1e-9 * range { 0.0 } else { *v };
        format!("{v:.decimals$}")
    }
}

/// A chart of `f64` against `f64`.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The grid, the tick labels (for axes spanning `spans`) and the axis names of `chart`, the
/// grid lines in the greys `(light, bold)`.
fn mesh<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    (x_desc, y_desc): (&str, &str),
    spans: (f64, f64),
    (light, bold): (u8, u8),
) -> DrawResult<DB> {
    let (x_format, y_format) = (tick_format(spans.0), tick_format(spans.1));
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .label_style((FONT, 18))
        .axis_desc_style((FONT, 20))
        .light_line_style(RGBColor(light, light, light))
        .bold_line_style(RGBColor(bold, bold, bold))
        .draw()
}

/// Draw the polylines `lines` in `style`, dashed or solid, with a legend entry `label` (none
/// when `None` or empty).
fn lines<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    lines: Vec<Vec<(f64, f64)>>,
    style: ShapeStyle,
    dashed: bool,
    label: Option<String>,
) -> DrawResult<DB> {
    let label = label.filter(|l| !l.is_empty());
    if dashed {
        let drawn = chart.draw_series(
            lines
                .into_iter()
                .map(|l| DashedPathElement::new(l, 9, 6, style)),
        )?;
        if let Some(label) = label {
            drawn.label(label).legend(move |(x, y)| {
                DashedPathElement::new(vec![(x, y), (x + 30, y)], 9, 6, style)
            });
        }
    } else {
        let drawn = chart.draw_series(lines.into_iter().map(|l| PathElement::new(l, style)))?;
        if let Some(label) = label {
            drawn
                .label(label)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 30, y)], style));
        }
    }
    Ok(())
}

/// The legend box of `chart` at `position`, with `margin` and labels of `size` px.
fn legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    position: SeriesLabelPosition,
    margin: u32,
    size: u32,
) -> DrawResult<DB> {
    chart
        .configure_series_labels()
        .position(position)
        .legend_area_size(42)
        .margin(margin)
        .label_font((FONT, size))
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.6))
        .draw()
}

/// The finite points of `points`.
fn finite_points(points: impl IntoIterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    points
        .into_iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_have_no_negative_zero() {
        let f = tick_format(1.6);
        assert_eq!(f(&-1e-17), "0.0");
        assert_eq!(f(&0.4), "0.4");
        assert_eq!(tick_format(16.0)(&2.0), "2");
    }
}
