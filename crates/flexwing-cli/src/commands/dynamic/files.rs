//! The result files of `flexwing dynamic`, each written atomically; `status.txt` last.

use std::path::{Path, PathBuf};

use serde::Serialize;

use flexwing::analysis::dynamics::DynamicRun;
use flexwing::analysis::Status;

use super::Outcome;
use crate::commands::statics::report::short;
use crate::output;
use crate::plot::{self, HistoryPlot, HistorySeries, ModelShapes, ShapePlot};
use flexwing_case::Case;

#[derive(Serialize)]
#[allow(non_snake_case)]
struct TipRow {
    model: String,
    t_s: f64,
    tip_x_m: f64,
    tip_y_m: f64,
    tip_twist_rad: f64,
    kinetic_J: f64,
    strain_J: f64,
    total_J: f64,
    work_J: f64,
    dissipated_J: f64,
    energy_balance_error: f64,
}

#[derive(Serialize)]
struct NodeRow {
    model: String,
    t_s: f64,
    node: usize,
    x_m: f64,
    y_m: f64,
    twist_rad: f64,
}

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    integrator: &'static str,
    steps: usize,
    rejected_steps: usize,
    newton_failures: usize,
    rhs_evaluations: usize,
    jacobian_evaluations: usize,
    factorizations: usize,
    wall_time_s: f64,
    ratio_to_first: Option<f64>,
    max_tip_difference_m: Option<f64>,
    max_relative_error_tip_x: Option<f64>,
    max_relative_error_tip_y: Option<f64>,
    energy_balance_max_error: Option<f64>,
    energy_balance_max_error_t_s: Option<f64>,
    energy_balance_limit: Option<f64>,
    status: &'static str,
}

/// Every file a run may write into its folder (removed before a new run).
pub const FILES: &[&str] = &[
    "dynamic_tip.csv",
    "dynamic_nodes.csv",
    "dynamic_summary.csv",
    "dynamic_tip.svg",
    "dynamic_tip.png",
    "dynamic_snapshots.svg",
    "dynamic_snapshots.png",
    "status.txt",
];

/// Write every result file into `dir`; returns the paths in the order written.
pub fn write_files(
    dir: &Path,
    outcome: &Outcome,
    case: &Case,
    with_plot: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let runs = outcome.runs();
    let mut files = Vec::new();

    let tip = dir.join("dynamic_tip.csv");
    output::write_csv(
        &tip,
        runs.iter().flat_map(|r| {
            r.samples.iter().map(move |p| TipRow {
                model: r.kind.label(),
                t_s: p.t,
                tip_x_m: p.tip_x,
                tip_y_m: p.tip_y,
                tip_twist_rad: p.tip_twist,
                kinetic_J: p.kinetic,
                strain_J: p.strain,
                total_J: p.total(),
                work_J: p.work,
                dissipated_J: p.dissipated,
                energy_balance_error: p.balance_error,
            })
        }),
    )?;
    files.push(tip);

    let nodes = dir.join("dynamic_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| {
            r.snapshots
                .iter()
                .filter(|s| outcome.node_indices.binary_search(&s.index).is_ok())
                .flat_map(move |s| {
                    (0..s.shape.x.len()).map(move |i| NodeRow {
                        model: r.kind.label(),
                        t_s: s.t,
                        node: i,
                        x_m: s.shape.x[i],
                        y_m: s.shape.y[i],
                        twist_rad: s.shape.twist[i],
                    })
                })
        }),
    )?;
    files.push(nodes);

    let summary = dir.join("dynamic_summary.csv");
    output::write_csv(
        &summary,
        runs.iter().map(|r| SummaryRow {
            model: r.kind.label(),
            dofs: r.dofs,
            integrator: r.integrator.name(),
            steps: r.stats.steps,
            rejected_steps: r.stats.rejected_steps,
            newton_failures: r.stats.newton_failures,
            rhs_evaluations: r.stats.rhs_evaluations,
            jacobian_evaluations: r.stats.jacobian_evaluations,
            factorizations: r.stats.factorizations,
            wall_time_s: r.wall_time_s,
            ratio_to_first: outcome.result.ratio_to_first(r),
            max_tip_difference_m: r.comparison.map(|c| c.max_tip_difference),
            max_relative_error_tip_x: r.comparison.and_then(|c| c.relative_x),
            max_relative_error_tip_y: r.comparison.and_then(|c| c.relative_y),
            energy_balance_max_error: r.energy_audit.as_ref().map(|e| e.max_error),
            energy_balance_max_error_t_s: r.energy_audit.as_ref().map(|e| e.max_error_time),
            energy_balance_limit: r.energy_audit.as_ref().and_then(|e| e.limit),
            status: super::report::status(r),
        }),
    )?;
    files.push(summary);

    if with_plot {
        let what = case_title(outcome, case);
        files.extend(plot::write_tip_history(dir, &history_plot(outcome, &what))?);
        files.extend(plot::write_shapes(
            dir,
            "dynamic_snapshots",
            &snapshot_plot(outcome, &what),
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

fn case_title(outcome: &Outcome, case: &Case) -> String {
    let name = Path::new(&outcome.case_name)
        .file_name()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    case.title.clone().unwrap_or(name)
}

fn legend(run: &DynamicRun, first: bool) -> String {
    let dofs = match run.dofs {
        1 => "1 dof".to_string(),
        n => format!("{n} dofs"),
    };
    let label = run.kind.label();
    let kind = if first {
        format!("{label} ({dofs})")
    } else {
        format!("{label} (dashed, {dofs})")
    };
    match (&run.status, run.samples.last()) {
        (Status::Complete, _) => kind,
        (Status::Suspect(_), _) => format!("{kind}: suspect (energy balance)"),
        (_, Some(s)) => format!("{kind}: stopped at t = {} s", short(s.t)),
        (_, None) => format!("{kind}: failed"),
    }
}

fn history_plot(outcome: &Outcome, what: &str) -> HistoryPlot {
    HistoryPlot {
        title: format!("Tip history: {what}"),
        end_time: outcome.end_time,
        has_torsion: outcome.has_torsion,
        series: outcome
            .runs()
            .iter()
            .enumerate()
            .map(|(k, r)| HistorySeries {
                label: legend(r, k == 0),
                dashed: k > 0,
                t: r.samples.iter().map(|p| p.t).collect(),
                x: r.samples.iter().map(|p| p.tip_x).collect(),
                y: r.samples.iter().map(|p| p.tip_y).collect(),
                twist: r.samples.iter().map(|p| p.tip_twist).collect(),
            })
            .collect(),
    }
}

/// The first model's deformed shapes at the plot's output times, coloured from dark (early) to
/// light (late); the legend names the first and the last.
fn snapshot_plot(outcome: &Outcome, what: &str) -> ShapePlot {
    let first = outcome.runs().first();
    let snapshots: Vec<_> = first
        .iter()
        .flat_map(|r| r.snapshots.iter())
        .filter(|s| outcome.plot_indices.binary_search(&s.index).is_ok())
        .collect();
    let label = first.map_or_else(String::new, |r| format!(" of the {} model", r.kind.label()));
    let count = snapshots.len();
    ShapePlot {
        title: format!("Deformed shapes{label}, dark to light in time: {what}"),
        length: outcome.length,
        models: snapshots
            .iter()
            .enumerate()
            .map(|(k, s)| ModelShapes {
                label: if k == 0 || k + 1 == count {
                    format!("t = {} s", short(s.t))
                } else if k == 1 {
                    format!("… {} snapshots between …", count - 2)
                } else {
                    String::new()
                },
                dashed: false,
                shapes: vec![s
                    .shape
                    .x
                    .iter()
                    .copied()
                    .zip(s.shape.y.iter().copied())
                    .collect()],
            })
            .collect(),
        gradient: true,
    }
}
