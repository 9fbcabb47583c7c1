//! `flexwing modes`: natural frequencies and mode shapes about the undeformed state.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;
use flexwing::analysis::modes::{self, ModeResult, ModesPlan};
use flexwing::analysis::NoProgress;
use flexwing::model::FullModel;
use serde::Serialize;

use super::{calibration_name, default_out_dir, model_line, Failure};
use crate::output;
use crate::plot::{self, ModePlot};
use flexwing_case::Case;

/// Options of `flexwing modes`.
#[derive(Debug, Args)]
pub struct ModesArgs {
    /// Case file (TOML); see docs/case-file.md for the keys.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Number of modes to report, 1 to n_dofs; overrides `[modes] count` of the case
    /// [default: min(10, n_dofs)].
    #[arg(long, short = 'n', value_name = "N")]
    pub count: Option<usize>,

    /// Also write mode_shapes.svg and mode_shapes.png (the first min(count, 6) modes).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the table.
    #[arg(long)]
    pub json: bool,
}

/// Run the command.
pub fn run(args: &ModesArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let case = Case::load(&args.case).map_err(Failure::input)?;
    // `--count` wins over `[modes] count`.
    let plan = match args.count {
        Some(n) => ModesPlan::new(case.model().map_err(Failure::input)?, Some(n), "--count")
            .map_err(|e| Failure::input(format!("{name}: {e}")))?,
        None => case.modes_plan().map_err(Failure::input)?,
    };
    let model = &plan.model;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    let previous = [
        "frequencies.csv",
        "mode_shapes.csv",
        "mode_shapes.svg",
        "mode_shapes.png",
    ];
    crate::output::prepare_dir(&dir, &previous, false).map_err(Failure::Run)?;
    let results = modes::run(&plan, &mut NoProgress)
        .map_err(|e| Failure::run(format!("{name}: modal analysis failed: {e}")))?
        .modes;

    let files =
        write_files(&dir, &case, &args.case, model, &results, args.plot).map_err(Failure::Run)?;

    let text = if args.json {
        json_report(&name, &case, model, &results, &files)
    } else {
        table_report(&case, model, &results, &files)
    };
    super::print_stdout(&text, args.json)
}

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

fn write_files(
    dir: &Path,
    case: &Case,
    case_path: &Path,
    model: &FullModel,
    results: &[ModeResult],
    with_plot: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let frequencies = dir.join("frequencies.csv");
    output::write_csv(
        &frequencies,
        results.iter().map(|r| FrequencyRow {
            mode: r.mode,
            omega_rad_s: r.omega,
            frequency_hz: r.frequency_hz,
            bending_energy_fraction: r.bending_energy_fraction,
        }),
    )?;
    let shapes = dir.join("mode_shapes.csv");
    output::write_csv(
        &shapes,
        results.iter().flat_map(|r| {
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
        let name = case_path
            .file_name()
            .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
        let title = match &case.title {
            Some(t) => format!("Mode shapes (mass-normalized): {t}"),
            None => format!("Mode shapes (mass-normalized): {name}"),
        };
        files.extend(plot::write_mode_shapes(
            dir,
            &ModePlot {
                title,
                length: model.beam().length(),
                has_torsion: model.has_torsion(),
                modes: results,
            },
        )?);
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

fn table_report(
    case: &Case,
    model: &FullModel,
    results: &[ModeResult],
    files: &[PathBuf],
) -> String {
    let mut s = String::new();
    if let Some(title) = &case.title {
        let _ = writeln!(s, "{title}");
    }
    let _ = writeln!(s, "{}", model_line(model));
    let _ = writeln!(
        s,
        "{:>4}  {:>13}  {:>12}  {:>13}  type",
        "mode", "ω (rad/s)", "f (Hz)", "bending share"
    );
    for r in results {
        let _ = writeln!(
            s,
            "{:>4}  {:>13.4}  {:>12.4}  {:>13.4}  {}",
            r.mode,
            r.omega,
            r.frequency_hz,
            r.bending_energy_fraction,
            mode_type(r.bending_energy_fraction)
        );
    }
    let _ = writeln!(s);
    for f in files {
        let _ = writeln!(s, "wrote {}", f.display());
    }
    s
}

#[derive(Serialize)]
struct JsonReport<'a> {
    case: &'a str,
    title: Option<&'a str>,
    n_elements: usize,
    n_dofs: usize,
    has_torsion: bool,
    calibration: &'static str,
    modes: Vec<JsonMode<'a>>,
    files: Vec<String>,
    /// Always `"complete"`: a modal analysis that fails prints the error document instead.
    status: &'static str,
}

#[derive(Serialize)]
struct JsonMode<'a> {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
    bending_energy_fraction: f64,
    shape: JsonShape<'a>,
}

#[derive(Serialize)]
struct JsonShape<'a> {
    x_m: &'a [f64],
    dx_m: &'a [f64],
    dy_m: &'a [f64],
    twist_rad: &'a [f64],
}

fn json_report(
    name: &str,
    case: &Case,
    model: &FullModel,
    results: &[ModeResult],
    files: &[PathBuf],
) -> String {
    let report = JsonReport {
        case: name,
        title: case.title.as_deref(),
        n_elements: model.n_elements(),
        n_dofs: model.n_dofs(),
        has_torsion: model.has_torsion(),
        calibration: calibration_name(model.beam().calibration()),
        modes: results
            .iter()
            .map(|r| JsonMode {
                mode: r.mode,
                omega_rad_s: r.omega,
                frequency_hz: r.frequency_hz,
                bending_energy_fraction: r.bending_energy_fraction,
                shape: JsonShape {
                    x_m: &r.shape.x,
                    dx_m: &r.shape.dx,
                    dy_m: &r.shape.dy,
                    twist_rad: &r.shape.twist,
                },
            })
            .collect(),
        files: files.iter().map(|f| f.display().to_string()).collect(),
        status: "complete",
    };
    // Serializing plain structs of numbers and strings cannot fail.
    let mut text = serde_json::to_string_pretty(&report).unwrap_or_default();
    text.push('\n');
    text
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
