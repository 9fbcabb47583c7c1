//! What `flexwing static` prints: the tables, or one JSON document (`--json`).

use std::fmt::Write as _;
use std::path::PathBuf;

use flexwing::beam::Profile;
use flexwing::model::{DistributedForce, Force, Load};
use serde::Serialize;

use flexwing::analysis::statics::{StaticPoint, StaticRun};

use super::Outcome;
pub use crate::output::short;

/// One line describing a load.
pub fn describe_load(load: &Load) -> String {
    let profile = |p: &Profile| match p {
        Profile::Uniform(v) => short(*v),
        Profile::Table { .. } => "table".into(),
    };
    match load {
        Load::PointForce { span, force } => match force {
            Force::Dead { fx, fy } => format!(
                "dead point force (fx, fy) = ({}, {}) N at span {} m",
                short(*fx),
                short(*fy),
                short(*span)
            ),
            Force::Follower { tangential, normal } => format!(
                "follower point force (tangential, normal) = ({}, {}) N at span {} m",
                short(*tangential),
                short(*normal),
                short(*span)
            ),
        },
        Load::Moment { span, value } => {
            format!("moment {} N·m at span {} m", short(*value), short(*span))
        }
        Load::Torque { span, value } => {
            format!("torque {} N·m at span {} m", short(*value), short(*span))
        }
        Load::Distributed(DistributedForce::Dead { fx, fy }) => format!(
            "dead distributed force (fx, fy) = ({}, {}) N/m",
            profile(fx),
            profile(fy)
        ),
        Load::Distributed(DistributedForce::Follower { tangential, normal }) => format!(
            "follower distributed force (tangential, normal) = ({}, {}) N/m",
            profile(tangential),
            profile(normal)
        ),
        Load::Gravity { g } => format!("gravity, g = {} m/s² along -y", short(*g)),
    }
}

/// A column of the side-by-side table.
struct Column {
    header: &'static str,
    width: usize,
    cells: Vec<String>,
}

/// Columns under a common title.
struct Group {
    title: String,
    columns: Vec<Column>,
}

const MISSING: &str = "-";

fn render(groups: &[Group], rows: usize) -> String {
    let group_width =
        |g: &Group| g.columns.iter().map(|c| c.width).sum::<usize>() + 2 * (g.columns.len() - 1);
    let mut lines = [String::new(), String::new(), String::new()];
    for (k, g) in groups.iter().enumerate() {
        let sep = if k == 0 { "" } else { "   " };
        let w = group_width(g);
        let _ = write!(lines[0], "{sep}{:^w$}", g.title);
        let rule = if g.title.is_empty() {
            " ".repeat(w)
        } else {
            "─".repeat(w)
        };
        let _ = write!(lines[1], "{sep}{rule}");
        let headers: Vec<String> = g
            .columns
            .iter()
            .map(|c| format!("{:>w$}", c.header, w = c.width))
            .collect();
        let _ = write!(lines[2], "{sep}{}", headers.join("  "));
    }
    let mut s = String::new();
    for l in &lines {
        let _ = writeln!(s, "{}", l.trim_end());
    }
    for row in 0..rows {
        let mut line = String::new();
        for (k, g) in groups.iter().enumerate() {
            let sep = if k == 0 { "" } else { "   " };
            let cells: Vec<String> = g
                .columns
                .iter()
                .map(|c| format!("{:>w$}", c.cells[row], w = c.width))
                .collect();
            let _ = write!(line, "{sep}{}", cells.join("  "));
        }
        let _ = writeln!(s, "{}", line.trim_end());
    }
    s
}

fn model_group(outcome: &Outcome, run: &StaticRun, rows: usize) -> Group {
    let cell = |k: usize, f: &dyn Fn(&StaticPoint) -> Option<String>| -> String {
        run.points
            .get(k)
            .and_then(f)
            .unwrap_or_else(|| MISSING.into())
    };
    let column = |header, width, f: &dyn Fn(&StaticPoint) -> Option<String>| Column {
        header,
        width,
        cells: (0..rows).map(|k| cell(k, f)).collect(),
    };
    let mut columns = vec![
        column("tip x (m)", 10, &|p| Some(format!("{:.6}", p.tip().0))),
        column("tip y (m)", 10, &|p| Some(format!("{:.6}", p.tip().1))),
    ];
    if outcome.has_torsion {
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

/// The tables of the text report.
pub fn tables(outcome: &Outcome, files: &[PathBuf]) -> String {
    let mut s = String::new();
    if let Some(title) = &outcome.title {
        let _ = writeln!(s, "{title}");
    }
    let _ = writeln!(s, "{}", outcome.model_line);
    for l in &outcome.loads {
        let _ = writeln!(s, "load {l}");
    }
    let rows = outcome.scales.len();
    let mut groups = Vec::new();
    match &outcome.sweep {
        Some(sweep) => {
            let _ = writeln!(
                s,
                "sweep: scale of {} from {} to {} in {} points, the other loads at scale 1",
                sweep.name,
                short(sweep.scales[0]),
                short(sweep.scales[rows - 1]),
                rows
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
                        cells: outcome.scales.iter().map(|&v| short(v)).collect(),
                    },
                ],
            });
        }
        None => {
            let _ = writeln!(s, "every load at scale 1");
        }
    }
    let _ = writeln!(s);
    groups.extend(outcome.runs().iter().map(|r| model_group(outcome, r, rows)));
    s.push_str(&render(&groups, rows));

    let _ = writeln!(s);
    let w = outcome
        .runs()
        .iter()
        .map(|r| r.kind.label().chars().count())
        .max()
        .unwrap_or(0)
        .max(10);
    let _ = writeln!(
        s,
        "{:<w$}  {:>5}  {:>14}  {:>13}  {:>12}",
        "model", "dofs", "wall time (ms)", "ratio to full", "max Δtip (m)"
    );
    for r in outcome.runs() {
        let ratio = outcome
            .result
            .ratio_to_full(r)
            .map_or_else(|| MISSING.into(), |v| format!("{v:.3}"));
        let diff = r
            .max_tip_difference()
            .map_or_else(|| MISSING.into(), |v| format!("{v:.2e}"));
        let _ = writeln!(
            s,
            "{:<w$}  {:>5}  {:>14.3}  {:>13}  {:>12}",
            r.kind.label(),
            r.dofs,
            1e3 * r.wall_time_s,
            ratio,
            diff
        );
    }

    if let Some(modes) = outcome.loaded_modes() {
        let at = match &outcome.sweep {
            Some(sw) => format!(
                " (point {rows}, {} scale {})",
                sw.name,
                short(sw.scales[rows - 1])
            ),
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

    let _ = writeln!(s);
    if outcome.incomplete.is_empty() {
        let _ = writeln!(s, "status: complete");
    }
    for i in &outcome.incomplete {
        let _ = writeln!(s, "status: {}: {}: {}", i.word, i.what, i.message);
    }
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
    has_torsion: bool,
    sweep: Option<JsonSweep<'a>>,
    models: Vec<JsonModel<'a>>,
    loaded_modes: Option<Vec<JsonMode>>,
    files: Vec<String>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonSweep<'a> {
    load: &'a str,
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
    error: Option<&'a str>,
    points: Vec<JsonPoint<'a>>,
}

#[derive(Serialize)]
struct JsonPoint<'a> {
    point: usize,
    scale: f64,
    scales: &'a [f64],
    tip: JsonTip,
    tip_difference_m: Option<f64>,
    nodes: JsonNodes<'a>,
    stats: JsonStats,
}

#[derive(Serialize)]
struct JsonTip {
    x_m: f64,
    y_m: f64,
    twist_rad: f64,
}

#[derive(Serialize)]
struct JsonNodes<'a> {
    x_m: &'a [f64],
    y_m: &'a [f64],
    twist_rad: &'a [f64],
}

#[derive(Serialize)]
struct JsonStats {
    load_steps: usize,
    rejected_steps: usize,
    iterations: usize,
    residual_evaluations: usize,
    factorizations: usize,
    residual_norm: f64,
}

#[derive(Serialize)]
struct JsonMode {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
}

/// The JSON document of `--json`.
pub fn json(outcome: &Outcome, files: &[PathBuf]) -> String {
    let report = JsonReport {
        case: &outcome.case_name,
        title: outcome.title.as_deref(),
        n_elements: outcome.n_elements,
        has_torsion: outcome.has_torsion,
        sweep: outcome.sweep.as_ref().map(|s| JsonSweep {
            load: &s.name,
            scales: &s.scales,
        }),
        models: outcome
            .runs()
            .iter()
            .map(|r| JsonModel {
                label: r.kind.label(),
                dofs: r.dofs,
                modes: r.kind.modes(),
                wall_time_s: r.wall_time_s,
                ratio_to_full: outcome.result.ratio_to_full(r),
                max_tip_difference_m: r.max_tip_difference(),
                status: crate::commands::run_word(&r.status),
                error: outcome.message_of(r),
                points: r.points.iter().enumerate().map(json_point).collect(),
            })
            .collect(),
        loaded_modes: outcome.loaded_modes().map(|modes| {
            modes
                .iter()
                .map(|m| JsonMode {
                    mode: m.mode,
                    omega_rad_s: m.omega,
                    frequency_hz: m.frequency_hz,
                })
                .collect()
        }),
        files: files.iter().map(|f| f.display().to_string()).collect(),
        status: outcome.status(),
        error: outcome.error(),
    };
    // Serializing plain structs of numbers and strings cannot fail; a non-finite residual norm
    // becomes null.
    let mut text = serde_json::to_string_pretty(&report).unwrap_or_default();
    text.push('\n');
    text
}

fn json_point((k, p): (usize, &StaticPoint)) -> JsonPoint<'_> {
    let (x, y, twist) = p.tip();
    let st = &p.stats;
    JsonPoint {
        point: k + 1,
        scale: p.scale,
        scales: &p.scales,
        tip: JsonTip {
            x_m: x,
            y_m: y,
            twist_rad: twist,
        },
        tip_difference_m: p.tip_difference,
        nodes: JsonNodes {
            x_m: &p.shape.x,
            y_m: &p.shape.y,
            twist_rad: &p.shape.twist,
        },
        stats: JsonStats {
            load_steps: st.load_steps,
            rejected_steps: st.rejected_steps,
            iterations: st.iterations,
            residual_evaluations: st.residual_evaluations,
            factorizations: st.factorizations,
            residual_norm: st.residual_norm,
        },
    }
}
