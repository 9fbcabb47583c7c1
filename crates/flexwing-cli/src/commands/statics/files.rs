//! The result files of `flexwing static`, each written atomically; `status.txt` last.

use std::path::{Path, PathBuf};

use flexwing::model::FullModel;
use serde::Serialize;

use flexwing::analysis::statics::StaticRun;

use super::Outcome;
use crate::output;
use crate::plot::{self, ModelShapes, ShapePlot};
use flexwing_case::Case;

#[derive(Serialize)]
struct TipRow {
    model: String,
    point: usize,
    scale: f64,
    tip_x_m: f64,
    tip_y_m: f64,
    tip_twist_rad: f64,
    load_steps: usize,
    iterations: usize,
    residual_norm: f64,
}

#[derive(Serialize)]
struct NodeRow {
    model: String,
    point: usize,
    scale: f64,
    node: usize,
    x_m: f64,
    y_m: f64,
    twist_rad: f64,
}

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    wall_time_s: f64,
    ratio_to_full: Option<f64>,
    max_tip_difference_m: Option<f64>,
}

#[derive(Serialize)]
struct FrequencyRow {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
}

/// Every file a run may write into its folder (removed before a new run).
pub const FILES: &[&str] = &[
    "static_tip.csv",
    "static_nodes.csv",
    "static_summary.csv",
    "loaded_frequencies.csv",
    "static_shapes.svg",
    "static_shapes.png",
    "status.txt",
];

/// Write every result file into `dir`; returns the paths in the order written.
pub fn write_files(
    dir: &Path,
    outcome: &Outcome,
    full: &FullModel,
    case: &Case,
    with_plot: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let runs = outcome.runs();
    let mut files = Vec::new();

    let tip = dir.join("static_tip.csv");
    output::write_csv(
        &tip,
        runs.iter().flat_map(|r| {
            r.points.iter().enumerate().map(move |(k, p)| {
                let (x, y, twist) = p.tip();
                TipRow {
                    model: r.kind.label(),
                    point: k + 1,
                    scale: p.scale,
                    tip_x_m: x,
                    tip_y_m: y,
                    tip_twist_rad: twist,
                    load_steps: p.stats.load_steps,
                    iterations: p.stats.iterations,
                    residual_norm: p.stats.residual_norm,
                }
            })
        }),
    )?;
    files.push(tip);

    let nodes = dir.join("static_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| {
            r.points.iter().enumerate().flat_map(move |(k, p)| {
                (0..p.shape.x.len()).map(move |i| NodeRow {
                    model: r.kind.label(),
                    point: k + 1,
                    scale: p.scale,
                    node: i,
                    x_m: p.shape.x[i],
                    y_m: p.shape.y[i],
                    twist_rad: p.shape.twist[i],
                })
            })
        }),
    )?;
    files.push(nodes);

    let summary = dir.join("static_summary.csv");
    output::write_csv(
        &summary,
        runs.iter().map(|r| SummaryRow {
            model: r.kind.label(),
            dofs: r.dofs,
            wall_time_s: r.wall_time_s,
            ratio_to_full: outcome.result.ratio_to_full(r),
            max_tip_difference_m: r.max_tip_difference(),
        }),
    )?;
    files.push(summary);

    if let Some(modes) = outcome.loaded_modes() {
        let path = dir.join("loaded_frequencies.csv");
        output::write_csv(
            &path,
            modes.iter().map(|m| FrequencyRow {
                mode: m.mode,
                omega_rad_s: m.omega,
                frequency_hz: m.frequency_hz,
            }),
        )?;
        files.push(path);
    }

    if with_plot {
        files.extend(plot::write_shapes(
            dir,
            "static_shapes",
            &shape_plot(outcome, full, case),
        )?);
    }

    let status = dir.join("status.txt");
    output::write_bytes(
        &status,
        crate::commands::status_text(&outcome.incomplete).as_bytes(),
    )?;
    files.push(status);
    Ok(files)
}

fn shape_plot(outcome: &Outcome, full: &FullModel, case: &Case) -> ShapePlot {
    let name = Path::new(&outcome.case_name)
        .file_name()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    let what = case.title.as_deref().unwrap_or(&name);
    let points = match &outcome.sweep {
        Some(s) => format!(
            ", {} scale {} to {} ({} points)",
            s.name,
            super::report::short(s.scales[0]),
            super::report::short(s.scales[s.scales.len() - 1]),
            s.scales.len()
        ),
        None => String::new(),
    };
    ShapePlot {
        title: format!("Static deformed shapes: {what}{points}"),
        length: full.beam().length(),
        models: outcome
            .runs()
            .iter()
            .map(|r| ModelShapes {
                label: legend(r),
                dashed: r.kind.modes().is_some(),
                shapes: r
                    .points
                    .iter()
                    .map(|p| {
                        let s = &p.shape;
                        s.x.iter().copied().zip(s.y.iter().copied()).collect()
                    })
                    .collect(),
            })
            .collect(),
        gradient: false,
    }
}

fn legend(run: &StaticRun) -> String {
    let label = run.kind.label();
    let kind = if run.kind.modes().is_some() {
        format!("{label} (dashed, {} dofs)", run.dofs)
    } else {
        format!("{label} ({} dofs)", run.dofs)
    };
    if !run.status.is_complete() {
        format!("{kind}: stopped after {} points", run.points.len())
    } else {
        kind
    }
}
