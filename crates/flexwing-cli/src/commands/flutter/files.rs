//! The result files of `flexwing flutter`, each written atomically; `status.txt` last. Numbers
//! that are not finite (none is expected) are written as empty fields.

use std::path::{Path, PathBuf};

use flexwing::analysis::aero::flutter::{FlutterRun, Stability};
use serde::Serialize;

use super::report::{finite, kind_name};
use super::Outcome;
use crate::output;
use crate::plot::{self, LinePlot, ModelShapes, Panel, Series, ShapePlot};

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    divergence_speed_m_s: Option<f64>,
    /// False: the divergence speed lies beyond the sweep (not reached by it).
    divergence_within_sweep: Option<bool>,
    flutter_speed_m_s: Option<f64>,
    flutter_frequency_rad_s: Option<f64>,
    unstable_at_start: usize,
    pk_flutter_speed_m_s: Option<f64>,
    pk_flutter_frequency_rad_s: Option<f64>,
    wall_time_s: Option<f64>,
    status: &'static str,
}

#[derive(Serialize)]
struct CrossingRow {
    model: String,
    method: &'static str,
    kind: &'static str,
    speed_m_s: Option<f64>,
    frequency_rad_s: Option<f64>,
    branch: usize,
    wet_mode: usize,
}

#[derive(Serialize)]
struct VgRow {
    model: String,
    method: &'static str,
    branch: usize,
    wet_mode: usize,
    speed_m_s: Option<f64>,
    real_1_s: Option<f64>,
    omega_rad_s: Option<f64>,
    damping_ratio: Option<f64>,
}

#[derive(Serialize)]
struct EquilibriumRow {
    model: String,
    speed_m_s: Option<f64>,
    dynamic_pressure_pa: Option<f64>,
    tip_x_m: Option<f64>,
    tip_y_m: Option<f64>,
    tip_twist_rad: Option<f64>,
    lift_n: Option<f64>,
    root_bending_moment_n_m: Option<f64>,
    divergence_pressure_pa: Option<f64>,
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

/// The eigen-analyses of a run: its own aerodynamics, then the p-k check.
fn methods(r: &FlutterRun) -> impl Iterator<Item = (&'static str, &Stability)> {
    std::iter::once(("eigenvalues", &r.stability)).chain(r.pk.as_ref().map(|p| ("p-k", p)))
}

/// Every result file a run may write (besides `status.txt`): removed before a run, so that a
/// folder holds one run's files only.
pub const FILES: &[&str] = &[
    "flutter_summary.csv",
    "flutter_crossings.csv",
    "flutter_vg.csv",
    "flutter_equilibria.csv",
    "flutter_nodes.csv",
    "flutter_vg.svg",
    "flutter_vg.png",
    "flutter_shapes.svg",
    "flutter_shapes.png",
];

/// Write every result file into `dir`; returns the paths in the order written.
pub fn write_files(dir: &Path, outcome: &Outcome, with_plot: bool) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let runs = outcome.runs();
    let mut files = Vec::new();

    let summary = dir.join("flutter_summary.csv");
    output::write_csv(
        &summary,
        runs.iter().map(|r| {
            let f = r.stability.flutter;
            let pk = r.pk.as_ref().and_then(|p| p.flutter);
            SummaryRow {
                model: r.kind.label(),
                dofs: r.dofs,
                divergence_speed_m_s: r.divergence.as_ref().and_then(|d| finite(d.speed)),
                divergence_within_sweep: r.divergence.as_ref().map(|d| d.within_sweep),
                flutter_speed_m_s: f.and_then(|c| finite(c.speed)),
                flutter_frequency_rad_s: f.and_then(|c| finite(c.frequency)),
                unstable_at_start: r.stability.unstable_at_start.len(),
                pk_flutter_speed_m_s: pk.and_then(|c| finite(c.speed)),
                pk_flutter_frequency_rad_s: pk.and_then(|c| finite(c.frequency)),
                wall_time_s: finite(r.wall_time_s),
                status: crate::commands::run_word(&r.status),
            }
        }),
    )?;
    files.push(summary);

    let crossings = dir.join("flutter_crossings.csv");
    output::write_csv(
        &crossings,
        runs.iter().flat_map(|r| {
            methods(r).flat_map(move |(method, s)| {
                s.crossings.iter().map(move |c| CrossingRow {
                    model: r.kind.label(),
                    method,
                    kind: kind_name(c),
                    speed_m_s: finite(c.speed),
                    frequency_rad_s: finite(c.frequency),
                    branch: c.branch,
                    wet_mode: s.branches[c.branch].mode,
                })
            })
        }),
    )?;
    files.push(crossings);

    let vg = dir.join("flutter_vg.csv");
    output::write_csv(
        &vg,
        runs.iter().flat_map(|r| {
            methods(r).flat_map(move |(method, s)| {
                s.branches.iter().enumerate().flat_map(move |(k, b)| {
                    let zeta = b.damping_ratios();
                    (0..b.real.len().min(s.speeds.len())).map(move |i| VgRow {
                        model: r.kind.label(),
                        method,
                        branch: k,
                        wet_mode: b.mode,
                        speed_m_s: finite(s.speeds[i]),
                        real_1_s: finite(b.real[i]),
                        omega_rad_s: finite(b.imag[i]),
                        damping_ratio: finite(zeta[i]),
                    })
                })
            })
        }),
    )?;
    files.push(vg);

    let equilibria = dir.join("flutter_equilibria.csv");
    output::write_csv(
        &equilibria,
        runs.iter().flat_map(|r| {
            r.equilibria.iter().map(move |p| {
                let (x, y, twist) = p.tip();
                EquilibriumRow {
                    model: r.kind.label(),
                    speed_m_s: finite(p.speed),
                    dynamic_pressure_pa: finite(p.dynamic_pressure),
                    tip_x_m: finite(x),
                    tip_y_m: finite(y),
                    tip_twist_rad: finite(twist),
                    lift_n: finite(p.lift),
                    root_bending_moment_n_m: finite(p.root_bending_moment),
                    divergence_pressure_pa: p.divergence_pressure.and_then(finite),
                }
            })
        }),
    )?;
    files.push(equilibria);

    let nodes = dir.join("flutter_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| {
            r.equilibria.iter().flat_map(move |p| {
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

    if with_plot {
        files.extend(plot::write_lines(dir, "flutter_vg", &vg_plot(outcome))?);
        files.extend(plot::write_shapes(
            dir,
            "flutter_shapes",
            &shape_plot(outcome),
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

fn what(outcome: &Outcome) -> String {
    let name = Path::new(&outcome.case_name)
        .file_name()
        .map_or_else(String::new, |s| s.to_string_lossy().into_owned());
    outcome.title.clone().unwrap_or(name)
}

/// V-g (damping ratio) and V-ω panels: one series per branch, the full model's (or the first
/// model's) solid, the p-k check's dashed.
fn vg_plot(outcome: &Outcome) -> LinePlot {
    let mut damping = Vec::new();
    let mut frequency = Vec::new();
    let run = outcome.runs().first();
    for (method, s) in run.into_iter().flat_map(methods) {
        for (k, b) in s.branches.iter().enumerate() {
            let label = format!("mode {} ({method})", b.mode);
            let zeta = b.damping_ratios();
            let n = b.real.len().min(s.speeds.len());
            damping.push(Series {
                label: label.clone(),
                dashed: method == "p-k",
                colour: Some(k),
                points: (0..n).map(|i| (s.speeds[i], zeta[i])).collect(),
            });
            frequency.push(Series {
                label,
                dashed: method == "p-k",
                colour: Some(k),
                points: (0..n).map(|i| (s.speeds[i], b.imag[i])).collect(),
            });
        }
    }
    let model = run.map_or_else(String::new, |r| r.kind.label());
    LinePlot {
        title: format!("V-g and V-ω: {}, {model} model", what(outcome)),
        panels: vec![
            Panel {
                x_label: "free-stream speed U (m/s)".into(),
                y_label: "damping ratio ζ = −Re s/|s|".into(),
                series: damping,
            },
            Panel {
                x_label: "free-stream speed U (m/s)".into(),
                y_label: "frequency ω = Im s (rad/s)".into(),
                series: frequency,
            },
        ],
    }
}

/// The static equilibria along the speeds, one curve per speed reached, per model.
fn shape_plot(outcome: &Outcome) -> ShapePlot {
    let sp = &outcome.speeds;
    ShapePlot {
        title: format!(
            "Static aeroelastic equilibria: {}, U = {} to {} m/s",
            what(outcome),
            output::short(sp[0]),
            output::short(sp[sp.len() - 1])
        ),
        length: outcome.length,
        models: outcome
            .runs()
            .iter()
            .map(|r| ModelShapes {
                label: format!("{} ({} dofs)", r.kind.label(), r.dofs),
                dashed: r.kind.modes().is_some(),
                shapes: r
                    .equilibria
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
