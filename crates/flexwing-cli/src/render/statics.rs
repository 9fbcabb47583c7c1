//! `flexwing static`: the equilibria of every model side by side over the sweep points, a
//! summary, the loaded modes; `static_tip.csv`, `static_nodes.csv`, `static_summary.csv`,
//! `loaded_frequencies.csv` and the shape plot.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::statics::{LoadedMode, StaticOutcome, StaticPlan, StaticPoint, StaticRun};
use flexwing::solve::StaticStats;
use serde::Serialize;

use super::table::{self, Column, Group};
use super::{polyline, Context, Fields};
use crate::output::{self, short};
use crate::plot::{self, ModelShapes, ShapePlot};

pub const FILES: &[&str] = &[
    "static_tip.csv",
    "static_nodes.csv",
    "static_summary.csv",
    "loaded_frequencies.csv",
    "static_shapes.svg",
    "static_shapes.png",
];

const MISSING: &str = "-";

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

impl FrequencyRow {
    fn of(m: &LoadedMode) -> Self {
        Self {
            mode: m.mode,
            omega_rad_s: m.omega,
            frequency_hz: m.frequency_hz,
        }
    }
}

/// The swept load's name and its scales, if the plan sweeps.
fn sweep(plan: &StaticPlan) -> Option<(String, &[f64])> {
    let s = plan.sweep.as_ref()?;
    Some((plan.load_name(s.load), &s.scales))
}

/// The points of a run, numbered from 1.
fn points(r: &StaticRun) -> impl Iterator<Item = (usize, &StaticPoint)> {
    r.points.iter().enumerate().map(|(k, p)| (k + 1, p))
}

pub fn files(
    ctx: &Context,
    plan: &StaticPlan,
    outcome: &StaticOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let runs = &outcome.runs;
    let tip = dir.join("static_tip.csv");
    output::write_csv(
        &tip,
        runs.iter().flat_map(|r| {
            points(r).map(|(point, p)| {
                let (x, y, twist) = p.tip();
                TipRow {
                    model: r.kind.label(),
                    point,
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
    let nodes = dir.join("static_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| {
            points(r).flat_map(move |(point, p)| {
                let s = &p.shape;
                (0..s.x.len()).map(move |i| NodeRow {
                    model: r.kind.label(),
                    point,
                    scale: p.scale,
                    node: i,
                    x_m: s.x[i],
                    y_m: s.y[i],
                    twist_rad: s.twist[i],
                })
            })
        }),
    )?;
    let summary = dir.join("static_summary.csv");
    output::write_csv(
        &summary,
        runs.iter().map(|r| SummaryRow {
            model: r.kind.label(),
            dofs: r.dofs,
            wall_time_s: r.wall_time_s,
            ratio_to_full: outcome.ratio_to_full(r),
            max_tip_difference_m: r.max_tip_difference(),
        }),
    )?;
    let mut files = vec![tip, nodes, summary];
    if let Some(Ok(modes)) = &outcome.loaded_modes {
        let path = dir.join("loaded_frequencies.csv");
        output::write_csv(&path, modes.iter().map(FrequencyRow::of))?;
        files.push(path);
    }
    if with_plot {
        let points = match sweep(plan) {
            Some((name, s)) => format!(
                ", {name} scale {} to {} ({} points)",
                short(s[0]),
                short(s[s.len() - 1]),
                s.len()
            ),
            None => String::new(),
        };
        let plot = ShapePlot {
            title: format!("Static deformed shapes: {}{points}", ctx.what()),
            length: plan.model.beam().length(),
            models: runs.iter().map(shapes).collect(),
            gradient: false,
        };
        files.extend(plot::write_shapes(dir, "static_shapes", &plot)?);
    }
    Ok(files)
}

fn shapes(run: &StaticRun) -> ModelShapes {
    let (label, dashed) = (run.kind.label(), run.kind.modes().is_some());
    let mut legend = if dashed {
        format!("{label} (dashed, {} dofs)", run.dofs)
    } else {
        format!("{label} ({} dofs)", run.dofs)
    };
    if !run.status.is_complete() {
        let _ = write!(legend, ": stopped after {} points", run.points.len());
    }
    ModelShapes {
        label: legend,
        dashed,
        shapes: run.points.iter().map(|p| polyline(&p.shape)).collect(),
    }
}

fn model_group(has_torsion: bool, run: &StaticRun, rows: usize) -> Group {
    let column = |header, width, f: &dyn Fn(&StaticPoint) -> Option<String>| Column {
        header,
        width,
        cells: (0..rows)
            .map(|k| {
                run.points
                    .get(k)
                    .and_then(f)
                    .unwrap_or_else(|| MISSING.into())
            })
            .collect(),
    };
    let mut columns = vec![
        column("tip x (m)", 10, &|p| Some(format!("{:.6}", p.tip().0))),
        column("tip y (m)", 10, &|p| Some(format!("{:.6}", p.tip().1))),
    ];
    if has_torsion {
        columns.push(column("twist (rad)", 11, &|p| {
            Some(format!("{:.6}", p.tip().2))
        }));
    }
    columns.push(column("iter", 4, &|p| Some(p.stats.iterations.to_string())));
    if run.kind.modes().is_some() {
        columns.push(column("Δtip (m)", 8, &|p| {
            p.tip_difference.map(|d| format!("{d:.2e}"))
        }));
    }
    Group {
        title: run.kind.label(),
        columns,
    }
}

pub fn text(s: &mut String, plan: &StaticPlan, outcome: &StaticOutcome) {
    for (i, l) in plan.loads.iter().enumerate() {
        let _ = writeln!(s, "load {}: {}", plan.load_name(i), l);
    }
    let scales = plan.point_scales();
    let rows = scales.len();
    let mut groups = Vec::new();
    match sweep(plan) {
        Some((name, sw)) => {
            let _ = writeln!(
                s,
                "sweep: scale of {name} from {} to {} in {rows} points, the other loads at scale 1",
                short(sw[0]),
                short(sw[rows - 1]),
            );
            groups.push(Group {
                title: String::new(),
                columns: vec![
                    Column {
                        header: "point",
                        width: 5,
                        cells: (1..=rows).map(|k| k.to_string()).collect(),
                    },
                    Column {
                        header: "scale",
                        width: 9,
                        cells: scales.iter().map(|&v| short(v)).collect(),
                    },
                ],
            });
        }
        None => {
            let _ = writeln!(s, "every load at scale 1");
        }
    }
    let _ = writeln!(s);
    let torsion = plan.model.has_torsion();
    groups.extend(outcome.runs.iter().map(|r| model_group(torsion, r, rows)));
    s.push_str(&table::groups(&groups, rows));

    let _ = writeln!(s);
    let w = super::label_width(outcome.runs.iter().map(|r| &r.kind));
    let _ = writeln!(
        s,
        "{:<w$}  {:>5}  {:>14}  {:>13}  {:>12}",
        "model", "dofs", "wall time (ms)", "ratio to full", "max Δtip (m)"
    );
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| MISSING.into(), f);
    for r in &outcome.runs {
        let _ = writeln!(
            s,
            "{:<w$}  {:>5}  {:>14.3}  {:>13}  {:>12}",
            r.kind.label(),
            r.dofs,
            1e3 * r.wall_time_s,
            opt(outcome.ratio_to_full(r), &|v| format!("{v:.3}")),
            opt(r.max_tip_difference(), &|v| format!("{v:.2e}")),
        );
    }
    if let Some(Ok(modes)) = &outcome.loaded_modes {
        let at = match sweep(plan) {
            Some((name, sw)) => format!(" (point {rows}, {name} scale {})", short(sw[rows - 1])),
            None => String::new(),
        };
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "loaded modes about the full model's last equilibrium{at}:"
        );
        let _ = writeln!(
            s,
            "{:>4}  {:>13}  {:>12}  {:>19}",
            "mode", "ω (rad/s)", "f (Hz)", "unloaded ω (rad/s)"
        );
        for m in modes {
            let _ = writeln!(
                s,
                "{:>4}  {:>13.4}  {:>12.4}  {:>19.4}",
                m.mode, m.omega, m.frequency_hz, m.unloaded_omega
            );
        }
    }
}

#[derive(Serialize)]
pub struct Json<'a> {
    n_elements: usize,
    has_torsion: bool,
    sweep: Option<JsonSweep<'a>>,
    models: Vec<JsonModel<'a>>,
    loaded_modes: Option<Vec<FrequencyRow>>,
}

#[derive(Serialize)]
struct JsonSweep<'a> {
    load: String,
    scales: &'a [f64],
}

#[derive(Serialize)]
struct JsonModel<'a> {
    label: String,
    dofs: usize,
    modes: Option<Vec<usize>>,
    wall_time_s: f64,
    ratio_to_full: Option<f64>,
    max_tip_difference_m: Option<f64>,
    status: &'static str,
    error: Option<String>,
    points: Vec<JsonPoint<'a>>,
}

#[derive(Serialize)]
struct JsonPoint<'a> {
    point: usize,
    scale: f64,
    scales: &'a [f64],
    tip: Fields<f64>,
    tip_difference_m: Option<f64>,
    nodes: Fields<&'a [f64]>,
    stats: &'a StaticStats,
}

pub fn json<'a>(ctx: &Context, plan: &'a StaticPlan, outcome: &'a StaticOutcome) -> Json<'a> {
    let point = |(k, p): (usize, &'a StaticPoint)| {
        let (x, y, twist) = p.tip();
        JsonPoint {
            point: k + 1,
            scale: p.scale,
            scales: &p.scales,
            tip: Fields(vec![("x_m", x), ("y_m", y), ("twist_rad", twist)]),
            tip_difference_m: p.tip_difference,
            nodes: Fields(vec![
                ("x_m", &p.shape.x),
                ("y_m", &p.shape.y),
                ("twist_rad", &p.shape.twist),
            ]),
            stats: &p.stats,
        }
    };
    Json {
        n_elements: plan.model.n_elements(),
        has_torsion: plan.model.has_torsion(),
        sweep: sweep(plan).map(|(load, scales)| JsonSweep { load, scales }),
        models: outcome
            .runs
            .iter()
            .map(|r| JsonModel {
                label: r.kind.label(),
                dofs: r.dofs,
                modes: r.kind.modes(),
                wall_time_s: r.wall_time_s,
                ratio_to_full: outcome.ratio_to_full(r),
                max_tip_difference_m: r.max_tip_difference(),
                status: r.status.word(),
                error: ctx.message_of(&r.kind.label()),
                points: r.points.iter().enumerate().map(point).collect(),
            })
            .collect(),
        loaded_modes: match &outcome.loaded_modes {
            Some(Ok(modes)) => Some(modes.iter().map(FrequencyRow::of).collect()),
            _ => None,
        },
    }
}
