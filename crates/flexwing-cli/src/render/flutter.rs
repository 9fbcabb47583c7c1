//! `flexwing flutter`: the divergence and flutter speeds of every model, every crossing of the
//! imaginary axis, the notes; `flutter_summary.csv`, `flutter_crossings.csv`, `flutter_vg.csv`,
//! `flutter_equilibria.csv`, `flutter_nodes.csv`, the V-g and shape plots. Every number is
//! finite: a non-finite value (none is expected) becomes `-` in the tables, an empty CSV field
//! and `null` in JSON.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::flutter::{FlutterOutcome, FlutterPlan, FlutterRun, Stability};
use flexwing::solve::aeroelastic::{Crossing, CrossingKind};
use serde::Serialize;

use super::aero_static::{node_rows, point_rows};
use super::{equilibria_shapes, finite, Context, Fields};
use crate::output::{self, short};
use crate::plot::{self, LinePlot, Panel, Series, ShapePlot};

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

const MISSING: &str = "-";

/// The eigen-analyses of a run: its own aerodynamics, then the p-k check.
fn methods(r: &FlutterRun) -> impl Iterator<Item = (&'static str, &Stability)> {
    std::iter::once(("eigenvalues", &r.stability)).chain(r.pk.as_ref().map(|p| ("p-k", p)))
}

/// `onset` or `offset`.
fn kind_name(c: &Crossing) -> &'static str {
    match c.kind {
        CrossingKind::Onset => "onset",
        CrossingKind::Offset => "offset",
    }
}

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
struct JsonCrossing {
    kind: &'static str,
    speed_m_s: Option<f64>,
    frequency_rad_s: Option<f64>,
    branch: usize,
    mode: usize,
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

fn crossing(s: &Stability, c: &Crossing) -> JsonCrossing {
    JsonCrossing {
        kind: kind_name(c),
        speed_m_s: finite(c.speed),
        frequency_rad_s: finite(c.frequency),
        branch: c.branch,
        mode: s.branches[c.branch].mode,
    }
}

pub fn files(
    ctx: &Context,
    plan: &FlutterPlan,
    outcome: &FlutterOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let runs = &outcome.runs;
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
                status: r.status.word(),
            }
        }),
    )?;
    let crossings = dir.join("flutter_crossings.csv");
    output::write_csv(
        &crossings,
        runs.iter().flat_map(|r| {
            methods(r).flat_map(move |(method, s)| {
                s.crossings.iter().map(move |c| {
                    let c = crossing(s, c);
                    CrossingRow {
                        model: r.kind.label(),
                        method,
                        kind: c.kind,
                        speed_m_s: c.speed_m_s,
                        frequency_rad_s: c.frequency_rad_s,
                        branch: c.branch,
                        wet_mode: c.mode,
                    }
                })
            })
        }),
    )?;
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
    let equilibria = dir.join("flutter_equilibria.csv");
    output::write_csv(
        &equilibria,
        runs.iter()
            .flat_map(|r| point_rows(&r.kind, &r.equilibria, false)),
    )?;
    let nodes = dir.join("flutter_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| node_rows(&r.kind, &r.equilibria)),
    )?;
    let mut files = vec![summary, crossings, vg, equilibria, nodes];
    if with_plot {
        let what = ctx.what();
        files.extend(plot::write_lines(
            dir,
            "flutter_vg",
            &vg_plot(outcome, &what),
        )?);
        let sp = plan.speeds();
        let shapes = ShapePlot {
            title: format!(
                "Static aeroelastic equilibria: {what}, U = {} to {} m/s",
                short(sp[0]),
                short(sp[sp.len() - 1])
            ),
            length: plan.model.beam().length(),
            models: runs
                .iter()
                .map(|r| {
                    let label = format!("{} ({} dofs)", r.kind.label(), r.dofs);
                    equilibria_shapes(label, r.kind.modes().is_some(), &r.equilibria)
                })
                .collect(),
            gradient: false,
        };
        files.extend(plot::write_shapes(dir, "flutter_shapes", &shapes)?);
    }
    Ok(files)
}

/// V-g (damping ratio) and V-ω panels: one series per branch, the full model's (or the first
/// model's) solid, the p-k check's dashed.
fn vg_plot(outcome: &FlutterOutcome, what: &str) -> LinePlot {
    let (mut damping, mut frequency) = (Vec::new(), Vec::new());
    let run = outcome.runs.first();
    for (method, s) in run.into_iter().flat_map(methods) {
        for (k, b) in s.branches.iter().enumerate() {
            let zeta = b.damping_ratios();
            let n = b.real.len().min(s.speeds.len());
            let series = |values: &[f64]| Series {
                label: format!("mode {} ({method})", b.mode),
                dashed: method == "p-k",
                colour: Some(k),
                points: (0..n).map(|i| (s.speeds[i], values[i])).collect(),
            };
            damping.push(series(&zeta));
            frequency.push(series(&b.imag));
        }
    }
    let model = run.map_or_else(String::new, |r| r.kind.label());
    let panel = |y_label: &str, series| Panel {
        x_label: "free-stream speed U (m/s)".into(),
        y_label: y_label.into(),
        series,
    };
    LinePlot {
        title: format!("V-g and V-ω: {what}, {model} model"),
        panels: vec![
            panel("damping ratio ζ = −Re s/|s|", damping),
            panel("frequency ω = Im s (rad/s)", frequency),
        ],
    }
}

/// `v` with `decimals` decimals, or `-`.
fn fixed(v: f64, decimals: usize) -> String {
    finite(v).map_or_else(|| MISSING.into(), |v| format!("{v:.decimals$}"))
}

/// The flutter speed cell: the speed, `unstable at start`, or `none` (no onset in the sweep).
fn flutter_cell(s: Option<&Stability>) -> (String, String) {
    match s {
        None => (MISSING.into(), MISSING.into()),
        Some(s) if s.flutter.is_none() && !s.unstable_at_start.is_empty() => {
            ("unstable at start".into(), MISSING.into())
        }
        Some(s) => match s.flutter {
            Some(c) => (fixed(c.speed, 5), fixed(c.frequency, 5)),
            None => ("none".into(), MISSING.into()),
        },
    }
}

pub fn text(s: &mut String, ctx: &Context, plan: &FlutterPlan, outcome: &FlutterOutcome) {
    let sp = plan.speeds();
    let (first, last) = (short(sp[0]), short(sp[sp.len() - 1]));
    let _ = writeln!(s, "speeds: {first} to {last} m/s ({} points)", sp.len());
    let _ = writeln!(s);
    let runs = &outcome.runs;
    let w = super::label_width(runs.iter().map(|r| &r.kind));
    let with_pk = runs.iter().any(|r| r.pk.is_some());
    let _ = write!(
        s,
        "{:<w$}  {:>5}  {:>16}  {:>17}  {:>13}",
        "model", "dofs", "divergence (m/s)", "flutter (m/s)", "ω_f (rad/s)"
    );
    if with_pk {
        let _ = write!(s, "  {:>17}  {:>13}", "p-k flutter (m/s)", "p-k ω (rad/s)");
    }
    let _ = writeln!(s, "  {:>14}", "wall time (ms)");
    for r in runs {
        let (u, omega) = flutter_cell(Some(&r.stability));
        let divergence = r.divergence.as_ref().map_or_else(
            || "none".into(),
            |d| {
                format!(
                    "{}{}",
                    fixed(d.speed, 5),
                    if d.within_sweep { "" } else { "*" }
                )
            },
        );
        let label = r.kind.label();
        let _ = write!(
            s,
            "{label:<w$}  {:>5}  {divergence:>16}  {u:>17}  {omega:>13}",
            r.dofs
        );
        if with_pk {
            let (u, omega) = flutter_cell(r.pk.as_ref());
            let _ = write!(s, "  {u:>17}  {omega:>13}");
        }
        let _ = writeln!(s, "  {:>14.3}", 1e3 * r.wall_time_s);
    }
    if runs
        .iter()
        .any(|r| r.divergence.is_some_and(|d| !d.within_sweep))
    {
        let _ = writeln!(
            s,
            "* beyond the sweep ({first} to {last} m/s), not reached by it: the linear divergence \
             speed of the undeformed wing, which stayed undeformed at every speed of the sweep",
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "crossings of the imaginary axis (onset: a branch becomes unstable; offset: stable again):"
    );
    let mut any = false;
    for r in runs {
        for (method, st) in methods(r) {
            for c in &st.crossings {
                any = true;
                let b = &st.branches[c.branch];
                let _ = writeln!(
                    s,
                    "  {} ({method}): {:<6} U = {} m/s, ω = {} rad/s, branch of wet mode {} ({} \
                     rad/s at U = 0)",
                    r.kind.label(),
                    kind_name(c),
                    fixed(c.speed, 5),
                    fixed(c.frequency, 5),
                    b.mode,
                    fixed(b.wet_frequency, 3),
                );
            }
        }
    }
    if !any {
        let _ = writeln!(s, "  none in the sweep");
    }
    for note in &ctx.notes {
        let _ = writeln!(s, "note: {note}");
    }
}

#[derive(Serialize)]
pub struct Json<'a> {
    model: String,
    aerodynamics: String,
    speeds_m_s: Vec<Option<f64>>,
    models: Vec<JsonModel>,
    notes: &'a [String],
}

#[derive(Serialize)]
struct JsonModel {
    label: String,
    dofs: usize,
    modes: Option<Vec<usize>>,
    wall_time_s: Option<f64>,
    divergence: Option<JsonDivergence>,
    eigenvalues: JsonStability,
    pk: Option<JsonStability>,
    equilibria: Vec<Fields<Option<f64>>>,
    equilibria_complete: bool,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonDivergence {
    speed_m_s: Option<f64>,
    dynamic_pressure_pa: Option<f64>,
    /// "bracketed" (between two speeds of the sweep) or "undeformed" (the linear divergence
    /// pressure of the undeformed wing).
    basis: &'static str,
    /// False: beyond the speeds of the sweep, not reached by it.
    within_sweep: bool,
}

#[derive(Serialize)]
struct JsonStability {
    flutter: Option<JsonCrossing>,
    unstable_at_start: Vec<usize>,
    crossings: Vec<JsonCrossing>,
    speeds_m_s: Vec<Option<f64>>,
    branches: Vec<JsonBranch>,
    wall_time_s: Option<f64>,
}

#[derive(Serialize)]
struct JsonBranch {
    mode: usize,
    wet_frequency_rad_s: Option<f64>,
    real_1_s: Vec<Option<f64>>,
    omega_rad_s: Vec<Option<f64>>,
    damping_ratio: Vec<Option<f64>>,
    uncertain: bool,
}

fn all(v: &[f64]) -> Vec<Option<f64>> {
    v.iter().copied().map(finite).collect()
}

fn json_stability(s: &Stability) -> JsonStability {
    JsonStability {
        flutter: s.flutter.as_ref().map(|c| crossing(s, c)),
        unstable_at_start: s.unstable_at_start.clone(),
        crossings: s.crossings.iter().map(|c| crossing(s, c)).collect(),
        speeds_m_s: all(&s.speeds),
        branches: s
            .branches
            .iter()
            .map(|b| JsonBranch {
                mode: b.mode,
                wet_frequency_rad_s: finite(b.wet_frequency),
                real_1_s: all(&b.real),
                omega_rad_s: all(&b.imag),
                damping_ratio: all(&b.damping_ratios()),
                uncertain: b.uncertain,
            })
            .collect(),
        wall_time_s: finite(s.wall_time_s),
    }
}

fn json_model(ctx: &Context, r: &FlutterRun) -> JsonModel {
    JsonModel {
        label: r.kind.label(),
        dofs: r.dofs,
        modes: r.kind.modes(),
        wall_time_s: finite(r.wall_time_s),
        divergence: r.divergence.as_ref().map(|d| JsonDivergence {
            speed_m_s: finite(d.speed),
            dynamic_pressure_pa: finite(d.dynamic_pressure),
            basis: flexwing::analysis::aero::basis_name(d.basis),
            within_sweep: d.within_sweep,
        }),
        eigenvalues: json_stability(&r.stability),
        pk: r.pk.as_ref().map(json_stability),
        equilibria: r
            .equilibria
            .iter()
            .map(|p| {
                let (_, y, twist) = p.tip();
                Fields(vec![
                    ("speed_m_s", finite(p.speed)),
                    ("tip_y_m", finite(y)),
                    ("tip_twist_rad", finite(twist)),
                    ("lift_n", finite(p.lift)),
                    ("root_bending_moment_n_m", finite(p.root_bending_moment)),
                ])
            })
            .collect(),
        equilibria_complete: r.equilibria_status.is_complete(),
        status: r.status.word(),
        error: ctx.message_of(&r.kind.label()),
    }
}

pub fn json<'a>(ctx: &'a Context, plan: &FlutterPlan, outcome: &FlutterOutcome) -> Json<'a> {
    Json {
        model: super::model_line(&plan.model),
        aerodynamics: super::aero_line(plan.aero.aerodynamics, plan.aero.density),
        speeds_m_s: all(plan.speeds()),
        models: outcome.runs.iter().map(|r| json_model(ctx, r)).collect(),
        notes: &ctx.notes,
    }
}
