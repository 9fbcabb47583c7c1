//! What `flexwing flutter` prints: the tables, or one JSON document (`--json`). Every number is
//! finite: a non-finite value (none is expected) becomes `-` in the tables and `null` in JSON.

use std::fmt::Write as _;
use std::path::PathBuf;

use flexwing::analysis::aero::flutter::{FlutterRun, Stability};
use flexwing::solve::aeroelastic::{Crossing, CrossingKind, DivergenceBasis};
use serde::Serialize;

use super::Outcome;
use crate::output::short;

const MISSING: &str = "-";

/// `Some(v)` for a finite `v`.
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// `v` with `decimals` decimals, or `-`.
fn fixed(v: Option<f64>, decimals: usize) -> String {
    v.and_then(finite)
        .map_or_else(|| MISSING.into(), |v| format!("{v:.decimals$}"))
}

/// The flutter speed cell: the speed, `unstable at start`, or `none` (no onset in the sweep).
fn flutter_cell(s: Option<&Stability>) -> (String, String) {
    match s {
        None => (MISSING.into(), MISSING.into()),
        Some(s) if s.flutter.is_none() && !s.unstable_at_start.is_empty() => {
            ("unstable at start".into(), MISSING.into())
        }
        Some(s) => match s.flutter {
            Some(c) => (fixed(Some(c.speed), 5), fixed(Some(c.frequency), 5)),
            None => ("none".into(), MISSING.into()),
        },
    }
}

/// `onset` or `offset`.
pub fn kind_name(c: &Crossing) -> &'static str {
    match c.kind {
        CrossingKind::Onset => "onset",
        CrossingKind::Offset => "offset",
    }
}

/// The tables of the text report.
pub fn tables(outcome: &Outcome, files: &[PathBuf]) -> String {
    let mut s = String::new();
    if let Some(title) = &outcome.title {
        let _ = writeln!(s, "{title}");
    }
    let _ = writeln!(s, "{}", outcome.model_line);
    let _ = writeln!(s, "{}", outcome.aero_line);
    let sp = &outcome.speeds;
    let _ = writeln!(
        s,
        "speeds: {} to {} m/s ({} points)",
        short(sp[0]),
        short(sp[sp.len() - 1]),
        sp.len()
    );
    let _ = writeln!(s);
    let runs = outcome.runs();
    let w = runs
        .iter()
        .map(|r| r.kind.label().chars().count())
        .max()
        .unwrap_or(0)
        .max(10);
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
        let _ = write!(
            s,
            "{:<w$}  {:>5}  {:>16}  {:>17}  {:>13}",
            r.kind.label(),
            r.dofs,
            r.divergence.as_ref().map_or_else(
                || "none".into(),
                |d| format!(
                    "{}{}",
                    fixed(Some(d.speed), 5),
                    if d.within_sweep { "" } else { "*" }
                )
            ),
            u,
            omega
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
            "* beyond the sweep ({} to {} m/s), not reached by it: the linear divergence speed of \
             the undeformed wing, which stayed undeformed at every speed of the sweep",
            short(sp[0]),
            short(sp[sp.len() - 1])
        );
    }
    let _ = writeln!(s);
    let _ = writeln!(
        s,
        "crossings of the imaginary axis (onset: a branch becomes unstable; offset: stable again):"
    );
    let mut any = false;
    for r in runs {
        for (method, st) in
            std::iter::once(("eigenvalues", &r.stability)).chain(r.pk.as_ref().map(|p| ("p-k", p)))
        {
            for c in &st.crossings {
                any = true;
                let b = &st.branches[c.branch];
                let _ = writeln!(
                    s,
                    "  {} ({method}): {:<6} U = {} m/s, ω = {} rad/s, branch of wet mode {} ({} rad/s at U = 0)",
                    r.kind.label(),
                    kind_name(c),
                    fixed(Some(c.speed), 5),
                    fixed(Some(c.frequency), 5),
                    b.mode,
                    fixed(Some(b.wet_frequency), 3),
                );
            }
        }
    }
    if !any {
        let _ = writeln!(s, "  none in the sweep");
    }
    for n in &outcome.notes {
        let _ = writeln!(s, "note: {n}");
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
    model: &'a str,
    aerodynamics: &'a str,
    speeds_m_s: Vec<Option<f64>>,
    models: Vec<JsonModel<'a>>,
    notes: &'a [String],
    files: Vec<String>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonModel<'a> {
    label: String,
    dofs: usize,
    modes: Option<Vec<usize>>,
    wall_time_s: Option<f64>,
    divergence: Option<JsonDivergence>,
    eigenvalues: JsonStability,
    pk: Option<JsonStability>,
    equilibria: Vec<JsonEquilibrium>,
    equilibria_complete: bool,
    status: &'static str,
    error: Option<&'a str>,
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
struct JsonCrossing {
    kind: &'static str,
    speed_m_s: Option<f64>,
    frequency_rad_s: Option<f64>,
    branch: usize,
    mode: usize,
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

#[derive(Serialize)]
struct JsonEquilibrium {
    speed_m_s: Option<f64>,
    tip_y_m: Option<f64>,
    tip_twist_rad: Option<f64>,
    lift_n: Option<f64>,
    root_bending_moment_n_m: Option<f64>,
}

fn all(v: &[f64]) -> Vec<Option<f64>> {
    v.iter().copied().map(finite).collect()
}

fn json_crossing(s: &Stability, c: &Crossing) -> JsonCrossing {
    JsonCrossing {
        kind: kind_name(c),
        speed_m_s: finite(c.speed),
        frequency_rad_s: finite(c.frequency),
        branch: c.branch,
        mode: s.branches[c.branch].mode,
    }
}

fn json_stability(s: &Stability) -> JsonStability {
    JsonStability {
        flutter: s.flutter.as_ref().map(|c| json_crossing(s, c)),
        unstable_at_start: s.unstable_at_start.clone(),
        crossings: s.crossings.iter().map(|c| json_crossing(s, c)).collect(),
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

fn json_model<'a>(outcome: &'a Outcome, r: &FlutterRun) -> JsonModel<'a> {
    JsonModel {
        label: r.kind.label(),
        dofs: r.dofs,
        modes: r.kind.modes(),
        wall_time_s: finite(r.wall_time_s),
        divergence: r.divergence.as_ref().map(|d| JsonDivergence {
            speed_m_s: finite(d.speed),
            dynamic_pressure_pa: finite(d.dynamic_pressure),
            basis: match d.basis {
                DivergenceBasis::Bracketed => "bracketed",
                DivergenceBasis::Undeformed => "undeformed",
            },
            within_sweep: d.within_sweep,
        }),
        eigenvalues: json_stability(&r.stability),
        pk: r.pk.as_ref().map(json_stability),
        equilibria: r
            .equilibria
            .iter()
            .map(|p| {
                let (_, y, twist) = p.tip();
                JsonEquilibrium {
                    speed_m_s: finite(p.speed),
                    tip_y_m: finite(y),
                    tip_twist_rad: finite(twist),
                    lift_n: finite(p.lift),
                    root_bending_moment_n_m: finite(p.root_bending_moment),
                }
            })
            .collect(),
        equilibria_complete: r.equilibria_status.is_complete(),
        status: crate::commands::run_word(&r.status),
        error: outcome.message_of(r),
    }
}

/// The JSON document of `--json`.
pub fn json(outcome: &Outcome, files: &[PathBuf]) -> String {
    let report = JsonReport {
        case: &outcome.case_name,
        title: outcome.title.as_deref(),
        model: &outcome.model_line,
        aerodynamics: &outcome.aero_line,
        speeds_m_s: all(&outcome.speeds),
        models: outcome
            .runs()
            .iter()
            .map(|r| json_model(outcome, r))
            .collect(),
        notes: &outcome.notes,
        files: files.iter().map(|f| f.display().to_string()).collect(),
        status: outcome.status(),
        error: outcome.error(),
    };
    // Plain structs of strings, integers and finite-or-null numbers: serializing cannot fail.
    let mut text = serde_json::to_string_pretty(&report).unwrap_or_default();
    text.push('\n');
    text
}
