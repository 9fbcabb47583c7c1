//! Plots of mode shapes (SVG and PNG) with plotters.
//!
//! Text is drawn with DejaVu Sans compiled into the binary (the `dejavu` crate, registered with
//! plotters' `ab_glyph` font table under the family name `sans-serif`), so the PNG renders the same
//! on a machine with no fonts installed. The SVG keeps its text as `<text>` elements in the
//! `sans-serif` family, which every SVG viewer can render.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use anyhow::{anyhow, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

use crate::commands::modes::ModeResult;
use crate::output;

/// Font family name under which the bundled font is registered.
const FONT: &str = "sans-serif";

/// Line colours of successive modes (colour-blind-friendly "tab10" hues).
const COLOURS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

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
    register_bundled_font()?;
    let size = (1200, if plot.has_torsion { 1000 } else { 560 });

    let svg_path = dir.join("mode_shapes.svg");
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        draw(&root, plot).map_err(|e| anyhow!("cannot draw {}: {e}", svg_path.display()))?;
    }
    output::write_bytes(&svg_path, svg.as_bytes())?;

    let png_path = dir.join("mode_shapes.png");
    output::write_atomic(&png_path, |tmp| {
        let root = BitMapBackend::new(tmp, size).into_drawing_area();
        draw(&root, plot).map_err(|e| anyhow!("{e}"))
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

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, plot: &ModePlot) -> DrawResult<DB> {
    root.fill(&WHITE)?;
    // The largest title size that fits the width.
    let width = root.dim_in_pixel().0;
    let mut size = 26;
    while size > 12
        && root
            .estimate_text_size(&plot.title, &(FONT, size).into_text_style(root))?
            .0
            + 40
            > width
    {
        size -= 1;
    }
    let body = root.titled(&plot.title, (FONT, size))?;
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

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    length: f64,
    modes: &[ModeResult],
    y_label: &str,
    values: impl Fn(&ModeResult) -> &Vec<f64>,
) -> DrawResult<DB> {
    let (lo, hi) = y_range(modes.iter().flat_map(|m| values(m).iter().copied()));
    let x_format = tick_format(length);
    let y_format = tick_format(hi - lo);
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .x_label_area_size(55)
        .y_label_area_size(90)
        .build_cartesian_2d(0.0..length, lo..hi)?;
    chart
        .configure_mesh()
        .x_desc("x (m)")
        .y_desc(y_label)
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .label_style((FONT, 18))
        .axis_desc_style((FONT, 20))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()?;
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
