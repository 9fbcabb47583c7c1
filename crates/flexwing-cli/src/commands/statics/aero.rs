//! `flexwing static` on a case with `[aero]`: static aeroelastic equilibria (steady strip theory)
//! at `aero.flight.speed` or along `[aero.sweep]`, for the full and reduced models of `[static]`
//! (`flexwing::analysis::aero::statics`), and the divergence speed where the sweep finds it.
//!
//! Files: `static_aero.csv` (one row per model and speed), `static_nodes.csv`,
//! `static_summary.csv`, `status.txt`; with `--plot` `static_shapes.svg/.png`. Non-finite numbers
//! (none expected) are written as empty fields (CSV) or `null` (JSON).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexwing::analysis::aero::statics::{self, AeroStaticOutcome, AeroStaticRun};
use flexwing::Error;
use serde::Serialize;

use super::StaticArgs;
use crate::commands::flutter::aero_line;
use crate::commands::{default_out_dir, model_line, status_text, Failure, Incomplete};
use crate::output::{self, short};
use crate::plot::{self, ModelShapes, ShapePlot};
use flexwing_case::Case;

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

#[derive(Serialize)]
struct PointRow {
    model: String,
    speed_m_s: Option<f64>,
    dynamic_pressure_pa: Option<f64>,
    tip_x_m: Option<f64>,
    tip_y_m: Option<f64>,
    tip_twist_rad: Option<f64>,
    lift_n: Option<f64>,
    root_bending_moment_n_m: Option<f64>,
    divergence_pressure_pa: Option<f64>,
    tip_difference_m: Option<f64>,
    iterations: usize,
}

#[derive(Serialize)]
struct NodeRow {
    model: String,
    speed_m_s: Option<f64>,
    node: usize,
    x_m: Option<f64>,
    y_m: Option<f64>,
    twist_rad: Option<f64>,
}

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    wall_time_s: Option<f64>,
    divergence_speed_m_s: Option<f64>,
    /// False: the divergence speed lies beyond the sweep (not reached by it).
    divergence_within_sweep: Option<bool>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonReport<'a> {
    case: &'a str,
    title: Option<&'a str>,
    model: &'a str,
    aerodynamics: &'a str,
    models: Vec<JsonModel>,
    files: Vec<String>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonModel {
    summary: SummaryRow,
    points: Vec<PointRow>,
}

fn point_rows(r: &AeroStaticRun) -> impl Iterator<Item = PointRow> + '_ {
    r.points.iter().map(|p| {
        let (x, y, twist) = p.tip();
        PointRow {
            model: r.kind.label(),
            speed_m_s: finite(p.speed),
            dynamic_pressure_pa: finite(p.dynamic_pressure),
            tip_x_m: finite(x),
            tip_y_m: finite(y),
            tip_twist_rad: finite(twist),
            lift_n: finite(p.lift),
            root_bending_moment_n_m: finite(p.root_bending_moment),
            divergence_pressure_pa: p.divergence_pressure.and_then(finite),
            tip_difference_m: p.tip_difference.and_then(finite),
            iterations: p.stats.iterations,
        }
    })
}

fn summary(r: &AeroStaticRun, incomplete: &[Incomplete]) -> SummaryRow {
    let label = r.kind.label();
    SummaryRow {
        error: incomplete
            .iter()
            .find(|i| i.what == label)
            .map(|i| i.message.clone()),
        model: label,
        dofs: r.dofs,
        wall_time_s: finite(r.wall_time_s),
        divergence_speed_m_s: r.divergence.as_ref().and_then(|d| finite(d.speed)),
        divergence_within_sweep: r.divergence.as_ref().map(|d| d.within_sweep),
        status: crate::commands::run_word(&r.status),
    }
}

/// Every result file a run may write (besides `status.txt`): removed before a run, so that a
/// folder holds one run's files only.
pub const FILES: &[&str] = &[
    "static_aero.csv",
    "static_nodes.csv",
    "static_summary.csv",
    "static_shapes.svg",
    "static_shapes.png",
];

/// Run the static aeroelastic analysis of the case.
pub fn run(args: &StaticArgs, case: &Case) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let plan = case.aero_static_plan().map_err(Failure::input)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    crate::output::prepare_dir(&dir, FILES, true).map_err(Failure::Run)?;
    // Ctrl-C and `kill` stop the sweep before its next speed, as for structural sweeps.
    crate::commands::interrupt::catch_interrupts(true);
    let result =
        statics::run(&plan, &mut crate::commands::interrupt::Cancel).map_err(|e| match e {
            Error::Input(e) => Failure::input(format!("{name}: {e}")),
            e => Failure::run(format!("{name}: {e}")),
        })?;
    let incomplete: Vec<Incomplete> = result
        .runs
        .iter()
        .filter_map(|r| crate::commands::status_entry(&r.kind.label(), &r.status, None, &[]))
        .collect();
    let model = model_line(&plan.model);
    let aero = aero_line(plan.aero.aerodynamics, plan.aero.density);
    let written = write_files(
        &dir,
        &result,
        &incomplete,
        case,
        &name,
        plan.model.beam().length(),
        args.plot,
    )
    .map_err(Failure::Run)?;
    let status = crate::commands::overall_word(&incomplete);
    let error = crate::commands::error_text(&incomplete);
    let text = if args.json {
        let doc = JsonReport {
            case: &name,
            title: case.title.as_deref(),
            model: &model,
            aerodynamics: &aero,
            models: result
                .runs
                .iter()
                .map(|r| JsonModel {
                    summary: summary(r, &incomplete),
                    points: point_rows(r).collect(),
                })
                .collect(),
            files: written.iter().map(|f| f.display().to_string()).collect(),
            status,
            error,
        };
        let mut t = serde_json::to_string_pretty(&doc).unwrap_or_default();
        t.push('\n');
        t
    } else {
        tables(case, &model, &aero, &result, &incomplete, &written)
    };
    let printed = crate::commands::print_stdout(&text, args.json);
    if let Some(first) = incomplete.first() {
        return Err(Failure::run(format!(
            "{name}: {}: {} (see status.txt)",
            first.what, first.message
        )));
    }
    printed
}

fn tables(
    case: &Case,
    model: &str,
    aero: &str,
    result: &AeroStaticOutcome,
    incomplete: &[Incomplete],
    files: &[PathBuf],
) -> String {
    let mut s = String::new();
    if let Some(t) = &case.title {
        let _ = writeln!(s, "{t}");
    }
    let _ = writeln!(s, "{model}");
    let _ = writeln!(s, "{aero}");
    let _ = writeln!(s, "static aeroelastic equilibria (steady strip theory)");
    for r in &result.runs {
        let _ = writeln!(s);
        let _ = writeln!(s, "{} ({} dofs):", r.kind.label(), r.dofs);
        let _ = writeln!(
            s,
            "{:>10}  {:>11}  {:>11}  {:>12}  {:>10}  {:>12}  {:>4}",
            "U (m/s)", "tip x (m)", "tip y (m)", "twist (rad)", "lift (N)", "root M (N·m)", "iter"
        );
        for p in &r.points {
            let (x, y, twist) = p.tip();
            let _ = writeln!(
                s,
                "{:>10}  {x:>11.6}  {y:>11.6}  {twist:>12.6}  {:>10.4}  {:>12.4}  {:>4}",
                short(p.speed),
                p.lift,
                p.root_bending_moment,
                p.stats.iterations
            );
        }
        match &r.divergence {
            Some(d) if d.within_sweep => {
                let _ = writeln!(s, "divergence speed: {:.5} m/s", d.speed);
            }
            Some(d) => {
                let _ = writeln!(
                    s,
                    "divergence speed: {:.5} m/s, beyond the sweep and not reached by it: the \
                     linear divergence speed of the undeformed wing, which stayed undeformed at \
                     every speed of the sweep",
                    d.speed
                );
            }
            None => {
                let _ = writeln!(s, "divergence speed: not reached");
            }
        }
        let _ = writeln!(s, "wall time: {:.3} ms", 1e3 * r.wall_time_s);
    }
    let _ = writeln!(s);
    if incomplete.is_empty() {
        let _ = writeln!(s, "status: complete");
    }
    for i in incomplete {
        let _ = writeln!(s, "status: {}: {}: {}", i.word, i.what, i.message);
    }
    for f in files {
        let _ = writeln!(s, "wrote {}", f.display());
    }
    s
}

fn write_files(
    dir: &Path,
    result: &AeroStaticOutcome,
    incomplete: &[Incomplete],
    case: &Case,
    name: &str,
    length: f64,
    with_plot: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let mut files = Vec::new();
    let points = dir.join("static_aero.csv");
    output::write_csv(&points, result.runs.iter().flat_map(point_rows))?;
    files.push(points);
    let nodes = dir.join("static_nodes.csv");
    output::write_csv(
        &nodes,
        result.runs.iter().flat_map(|r| {
            r.points.iter().flat_map(move |p| {
                (0..p.shape.x.len()).map(move |i| NodeRow {
                    model: r.kind.label(),
                    speed_m_s: finite(p.speed),
                    node: i,
                    x_m: finite(p.shape.x[i]),
                    y_m: finite(p.shape.y[i]),
                    twist_rad: finite(p.shape.twist[i]),
                })
            })
        }),
    )?;
    files.push(nodes);
    let sum = dir.join("static_summary.csv");
    output::write_csv(&sum, result.runs.iter().map(|r| summary(r, incomplete)))?;
    files.push(sum);
    if with_plot {
        let what = case.title.clone().unwrap_or_else(|| name.to_string());
        let plot = ShapePlot {
            title: format!("Static aeroelastic equilibria: {what}"),
            length,
            models: result
                .runs
                .iter()
                .map(|r| ModelShapes {
                    label: format!("{} ({} dofs)", r.kind.label(), r.dofs),
                    dashed: r.kind.modes().is_some(),
                    shapes: r
                        .points
                        .iter()
                        .map(|p| {
                            p.shape
                                .x
                                .iter()
                                .copied()
                                .zip(p.shape.y.iter().copied())
                                .collect()
                        })
                        .collect(),
                })
                .collect(),
            gradient: false,
        };
        files.extend(plot::write_shapes(dir, "static_shapes", &plot)?);
    }
    let status = dir.join("status.txt");
    output::write_bytes(&status, status_text(incomplete).as_bytes())?;
    files.push(status);
    Ok(files)
}
