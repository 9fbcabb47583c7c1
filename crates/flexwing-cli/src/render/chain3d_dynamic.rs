//! `flexwing dynamic` on the 3-D chain: `dynamic_tip.csv` (the tip `x, y, z`, the tip
//! section's rotation vector and the energies at every output time), the node file
//! (`dynamic_nodes.csv` or `.npz`: node `x, y, z` and section rotations at the node file's
//! times), `dynamic_summary.csv` (the planar run's columns), a plot of the tip in time, the
//! side-by-side table, and a JSON document that is the library's serialized outcome.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::chain3d::{
    Chain3dPlan, Dynamic3d, Dynamic3dOutcome, Dynamic3dRun, Snapshot3d,
};
use flexwing::analysis::Status;
use flexwing_case::OutputFormatSpec;
use flexwing_io::nodes::{self, NodeHistory};
use serde::Serialize;

use super::dynamic::{self, NodeOutput, SummaryRow};
use super::{table, Context};
use crate::output::{self, short};
use crate::plot::{write_lines, LinePlot, Panel, Series};

/// Every file a 3-D dynamic run may write.
pub const FILES: &[&str] = &[
    "dynamic_tip.csv",
    "dynamic_nodes.csv",
    "dynamic_nodes.npz",
    "dynamic_summary.csv",
    "dynamic_tip.svg",
    "dynamic_tip.png",
];

#[derive(Serialize)]
#[allow(non_snake_case)]
struct TipRow<'a> {
    model: &'a str,
    t_s: f64,
    tip_x_m: f64,
    tip_y_m: f64,
    tip_z_m: f64,
    tip_rx_rad: f64,
    tip_ry_rad: f64,
    tip_rz_rad: f64,
    kinetic_J: f64,
    strain_J: f64,
    total_J: f64,
    work_J: f64,
    dissipated_J: f64,
    energy_balance_error: f64,
}

#[derive(Serialize)]
struct NodeRow<'a> {
    model: &'a str,
    t_s: f64,
    node: usize,
    span_m: f64,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    rx_rad: Option<f64>,
    ry_rad: Option<f64>,
    rz_rad: Option<f64>,
}

/// Wall time of `run` over that of the first model.
fn ratio_to_first(o: &Dynamic3dOutcome, run: &Dynamic3dRun) -> Option<f64> {
    let first = o.runs.first()?;
    (first.wall_time_s > 0.0).then(|| run.wall_time_s / first.wall_time_s)
}

pub fn files(
    ctx: &Context,
    d: &Dynamic3d,
    o: &Dynamic3dOutcome,
    dir: &Path,
    plot: bool,
) -> Result<Vec<PathBuf>> {
    let tip = dir.join("dynamic_tip.csv");
    output::write_csv(
        &tip,
        o.runs.iter().flat_map(|r| {
            (0..r.t.len()).map(move |k| TipRow {
                model: &r.label,
                t_s: r.t[k],
                tip_x_m: r.tip_x[k],
                tip_y_m: r.tip_y[k],
                tip_z_m: r.tip_z[k],
                tip_rx_rad: r.tip_rotation[k][0],
                tip_ry_rad: r.tip_rotation[k][1],
                tip_rz_rad: r.tip_rotation[k][2],
                kinetic_J: r.kinetic[k],
                strain_J: r.strain[k],
                total_J: r.total[k],
                work_J: r.work[k],
                dissipated_J: r.dissipated[k],
                energy_balance_error: r.balance_error[k],
            })
        }),
    )?;
    let nodes = write_nodes(ctx, d, o, dir)?;
    let summary = dir.join("dynamic_summary.csv");
    output::write_csv(
        &summary,
        o.runs.iter().map(|r| {
            let mut row = SummaryRow::new(
                r.label.clone(),
                r.dofs,
                r.integrator,
                &r.stats,
                r.wall_time_s,
                r.energy_audit.as_ref(),
                &r.status,
            );
            row.ratio_to_first = Some(ratio_to_first(o, r));
            row.max_tip_difference_m = r.max_tip_difference;
            row
        }),
    )?;
    let mut files = vec![tip, nodes, summary];
    if plot {
        files.extend(tip_plot(ctx, o, dir)?);
    }
    Ok(files)
}

/// The node file (`[output] format`) at the node file's output times.
fn write_nodes<'a>(
    ctx: &Context,
    d: &Dynamic3d,
    o: &'a Dynamic3dOutcome,
    dir: &Path,
) -> Result<PathBuf> {
    let output = &ctx.case.output;
    let written = dynamic::node_indices(output, d.output_times.len());
    let kept = |r: &'a Dynamic3dRun| -> Vec<&'a Snapshot3d> {
        r.snapshots
            .iter()
            .filter(|s| written.binary_search(&s.index).is_ok())
            .collect()
    };
    match output.format() {
        OutputFormatSpec::Csv => {
            let path = dir.join("dynamic_nodes.csv");
            let rows = o.runs.iter().flat_map(|r| {
                kept(r).into_iter().flat_map(move |s| {
                    let sh = &s.shape;
                    (0..sh.position.len()).map(move |k| {
                        let rot = k.checked_sub(1).map(|e| sh.rotation[e]);
                        NodeRow {
                            model: &r.label,
                            t_s: s.t,
                            node: k,
                            span_m: sh.span[k],
                            x_m: sh.position[k][0],
                            y_m: sh.position[k][1],
                            z_m: sh.position[k][2],
                            rx_rad: rot.map(|v| v[0]),
                            ry_rad: rot.map(|v| v[1]),
                            rz_rad: rot.map(|v| v[2]),
                        }
                    })
                })
            });
            output::write_csv(&path, rows)?;
            Ok(path)
        }
        OutputFormatSpec::Npz => {
            let path = dir.join("dynamic_nodes.npz");
            let histories: Vec<NodeHistory> = o
                .runs
                .iter()
                .map(|r| {
                    let shots = kept(r);
                    let n = shots.first().map_or(0, |s| s.shape.position.len());
                    let mut values = Vec::with_capacity(shots.len() * n * 6);
                    for s in &shots {
                        for k in 0..n {
                            let rot = k
                                .checked_sub(1)
                                .map_or([f64::NAN; 3], |e| s.shape.rotation[e]);
                            values.extend(s.shape.position[k]);
                            values.extend(rot);
                        }
                    }
                    NodeHistory {
                        label: r.label.clone(),
                        t: shots.iter().map(|s| s.t).collect(),
                        index: shots.iter().map(|s| s.index as i64).collect(),
                        nodes: n,
                        values,
                    }
                })
                .collect();
            let vars = nodes::variables(&nodes::SPATIAL, &histories);
            flexwing_io::atomic::write_with(&path, |f| flexwing_io::npz::write(f, &vars))?;
            Ok(path)
        }
    }
}

fn legend(run: &Dynamic3dRun) -> String {
    match (&run.status, run.t.last()) {
        (Status::Complete, _) => run.label.clone(),
        (Status::Suspect(_), _) => format!("{}: suspect (energy balance)", run.label),
        (_, Some(t)) => format!("{}: stopped at t = {} s", run.label, short(*t)),
        (_, None) => format!("{}: failed", run.label),
    }
}

/// The tip's `x`, `y`, `z` in time, one line per model.
fn tip_plot(ctx: &Context, o: &Dynamic3dOutcome, dir: &Path) -> Result<Vec<PathBuf>> {
    let panel = |axis: &str, f: fn(&Dynamic3dRun) -> &[f64]| Panel {
        x_label: "t (s)".into(),
        y_label: format!("tip {axis} (m)"),
        series: o
            .runs
            .iter()
            .enumerate()
            .map(|(k, r)| Series {
                label: legend(r),
                dashed: k > 0,
                colour: Some(k),
                points: r.t.iter().copied().zip(f(r).iter().copied()).collect(),
            })
            .collect(),
    };
    let plot = LinePlot {
        title: format!("Tip history of the 3-D chain: {}", ctx.what()),
        panels: vec![
            panel("x", |r| &r.tip_x),
            panel("y", |r| &r.tip_y),
            panel("z", |r| &r.tip_z),
        ],
    };
    write_lines(dir, "dynamic_tip", &plot)
}

pub fn text(ctx: &Context, s: &mut String, d: &Dynamic3d, o: &Dynamic3dOutcome) {
    let name = |i: usize| {
        d.load_names
            .get(i)
            .cloned()
            .unwrap_or_else(|| format!("loads[{i}]"))
    };
    for i in 0..d.loads.len() {
        let when = dynamic::load_when(&d.time, &d.initial, i);
        let when = if when.is_empty() {
            " (constant)".to_string()
        } else {
            when
        };
        let _ = writeln!(s, "load {}{when}", name(i));
    }
    dynamic::run_lines(s, &d.initial, &name, d.end_time, &d.output_times);
    let _ = writeln!(s, "damping: {}", dynamic::damping_line(&d.damping));
    let uses_gyroscopic = d.full || !d.reduced.is_empty() || !d.reduced_modes.is_empty();
    let tolerances =
        dynamic::tolerances_line(d.integrator, &d.settings, d.gyroscopic, uses_gyroscopic);
    let _ = writeln!(s, "tolerances: {tolerances}");
    let times = d.output_times.len();
    let _ = writeln!(s, "{}", NodeOutput::of(&ctx.case.output, times).line());
    let _ = writeln!(s);
    let runs = &o.runs;
    let cells = |f: &dyn Fn(&Dynamic3dRun) -> String| runs.iter().map(f).collect::<Vec<_>>();
    let last = |r: &Dynamic3dRun, v: &dyn Fn(&Dynamic3dRun) -> &[f64]| {
        v(r).last().map_or("-".to_string(), |x| format!("{x:.6}"))
    };
    let e2 = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.2e}"));
    let rows = vec![
        ("dofs", cells(&|r| r.dofs.to_string())),
        ("integrator", cells(&|r| r.integrator.name().into())),
        ("gyroscopic term", cells(&|r| r.gyroscopic.into())),
        ("steps", cells(&|r| r.stats.steps.to_string())),
        (
            "rejected steps",
            cells(&|r| r.stats.rejected_steps.to_string()),
        ),
        (
            "  of which Newton failed",
            cells(&|r| r.stats.newton_failures.to_string()),
        ),
        (
            "RHS evaluations",
            cells(&|r| r.stats.rhs_evaluations.to_string()),
        ),
        (
            "wall time (ms)",
            cells(&|r| format!("{:.3}", 1e3 * r.wall_time_s)),
        ),
        ("t reached (s)", cells(&|r| last(r, &|r| &r.t))),
        ("tip x at t reached (m)", cells(&|r| last(r, &|r| &r.tip_x))),
        ("tip y at t reached (m)", cells(&|r| last(r, &|r| &r.tip_y))),
        ("tip z at t reached (m)", cells(&|r| last(r, &|r| &r.tip_z))),
        (
            "max Δtip from first (m)",
            cells(&|r| e2(r.max_tip_difference)),
        ),
        (
            "energy balance error",
            cells(&|r| e2(r.energy_audit.map(|e| e.max_error))),
        ),
        (
            "energy balance limit",
            cells(&|r| match r.energy_audit.map(|e| e.limit) {
                Some(Some(l)) => format!("{l:.1e}"),
                Some(None) => "none".into(),
                None => "-".into(),
            }),
        ),
        ("status", cells(&|r| r.status.word().into())),
    ];
    let labels: Vec<String> = runs.iter().map(|r| r.label.clone()).collect();
    s.push_str(&table::rows(&labels, &rows));
}

/// The node file's description in the JSON document of a 3-D dynamic run.
pub fn node_output(ctx: &Context, plan: &Chain3dPlan) -> Option<NodeOutput> {
    match &plan.analysis {
        flexwing::analysis::chain3d::Analysis3d::Dynamic(d) => {
            Some(NodeOutput::of(&ctx.case.output, d.output_times.len()))
        }
        _ => None,
    }
}
