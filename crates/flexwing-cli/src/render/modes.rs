//! `flexwing modes`: the frequency table, `frequencies.csv`, `mode_shapes.csv` and the mode-shape
//! plot; its JSON carries each mode with its shape.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::modes::{ModesOutcome, ModesPlan};
use serde::Serialize;

use super::{Context, Fields};
use crate::output;
use crate::plot::{self, ModePlot};

pub const FILES: &[&str] = &[
    "frequencies.csv",
    "mode_shapes.csv",
    "mode_shapes.svg",
    "mode_shapes.png",
];

#[derive(Serialize)]
struct FrequencyRow {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
    bending_energy_fraction: f64,
}

#[derive(Serialize)]
struct ShapeRow {
    mode: usize,
    node: usize,
    x_m: f64,
    dx_m: f64,
    dy_m: f64,
    twist_rad: f64,
}

pub fn files(
    ctx: &Context,
    plan: &ModesPlan,
    outcome: &ModesOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let modes = &outcome.modes;
    let frequencies = dir.join("frequencies.csv");
    output::write_csv(
        &frequencies,
        modes.iter().map(|r| FrequencyRow {
            mode: r.mode,
            omega_rad_s: r.omega,
            frequency_hz: r.frequency_hz,
            bending_energy_fraction: r.bending_energy_fraction,
        }),
    )?;
    let shapes = dir.join("mode_shapes.csv");
    output::write_csv(
        &shapes,
        modes.iter().flat_map(|r| {
            let s = &r.shape;
            (0..s.x.len()).map(move |i| ShapeRow {
                mode: r.mode,
                node: i,
                x_m: s.x[i],
                dx_m: s.dx[i],
                dy_m: s.dy[i],
                twist_rad: s.twist[i],
            })
        }),
    )?;
    let mut files = vec![frequencies, shapes];
    if with_plot {
        let plot = ModePlot {
            title: format!("Mode shapes (mass-normalized): {}", ctx.what()),
            length: plan.model.beam().length(),
            has_torsion: plan.model.has_torsion(),
            modes,
        };
        files.extend(plot::write_mode_shapes(dir, &plot)?);
    }
    Ok(files)
}

/// `bending` (≥ 90 % of the strain energy in bending), `torsion` (≤ 10 %) or `coupled`.
fn mode_type(bending_fraction: f64) -> &'static str {
    if bending_fraction >= 0.9 {
        "bending"
    } else if bending_fraction <= 0.1 {
        "torsion"
    } else {
        "coupled"
    }
}

pub fn text(s: &mut String, outcome: &ModesOutcome) {
    let _ = writeln!(
        s,
        "{:>4}  {:>13}  {:>12}  {:>13}  type",
        "mode", "ω (rad/s)", "f (Hz)", "bending share"
    );
    for r in &outcome.modes {
        let b = r.bending_energy_fraction;
        let _ = writeln!(
            s,
            "{:>4}  {:>13.4}  {:>12.4}  {b:>13.4}  {}",
            r.mode,
            r.omega,
            r.frequency_hz,
            mode_type(b)
        );
    }
}

#[derive(Serialize)]
pub struct Json<'a> {
    n_elements: usize,
    n_dofs: usize,
    has_torsion: bool,
    calibration: &'static str,
    modes: Vec<JsonMode<'a>>,
}

#[derive(Serialize)]
struct JsonMode<'a> {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
    bending_energy_fraction: f64,
    shape: Fields<&'a [f64]>,
}

pub fn json<'a>(plan: &'a ModesPlan, outcome: &'a ModesOutcome) -> Json<'a> {
    let model = &plan.model;
    Json {
        n_elements: model.n_elements(),
        n_dofs: model.n_dofs(),
        has_torsion: model.has_torsion(),
        calibration: model.beam().calibration().name(),
        modes: outcome
            .modes
            .iter()
            .map(|r| JsonMode {
                mode: r.mode,
                omega_rad_s: r.omega,
                frequency_hz: r.frequency_hz,
                bending_energy_fraction: r.bending_energy_fraction,
                shape: Fields(vec![
                    ("x_m", &r.shape.x),
                    ("dx_m", &r.shape.dx),
                    ("dy_m", &r.shape.dy),
                    ("twist_rad", &r.shape.twist),
                ]),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mode_types() {
        assert_eq!(mode_type(0.95), "bending");
        assert_eq!(mode_type(0.5), "coupled");
        assert_eq!(mode_type(0.02), "torsion");
    }
}
