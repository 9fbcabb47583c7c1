//! `flexwing gust`: a discrete gust family (CS 25.341(a)) on every model — `gust_family.csv`
//! (per model and gust gradient distance `H`: the design velocity, the largest and smallest
//! change of each output from the equilibrium with their times, the run's steps, wall time and
//! status), `gust_family_critical.csv` (per model and output: the critical `H`, its peak and
//! time), the text summary and the JSON document; with `--plot` `gust_family.svg/.png`, the
//! peaks against `H`, one panel per output. Non-finite numbers are empty fields (CSV) or `null`
//! (JSON).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::gust_family::{
    GustFamilyOutcome, GustFamilyPlan, GustMember, Peak, FOOT, OUTPUTS, OUTPUT_UNITS,
};
use serde::Serialize;

use super::{finite, Context};
use crate::output;
use crate::plot::{write_lines, LinePlot, Panel, Series};

pub const FILES: &[&str] = &[
    "gust_family.csv",
    "gust_family_critical.csv",
    "gust_family.svg",
    "gust_family.png",
];

/// The outputs a model of `plan` has: all of [`OUTPUTS`], the twist and torque only with
/// torsion (their indices).
fn outputs(plan: &GustFamilyPlan) -> Vec<usize> {
    let torsion = plan.response.structure.model.has_torsion();
    (0..OUTPUTS.len())
        .filter(|&k| torsion || !matches!(OUTPUTS[k], "tip_twist" | "root_torque"))
        .collect()
}

/// The peak columns of one output: `{name}_max`, `_max_time_s`, `_min`, `_min_time_s`.
#[derive(Serialize)]
struct PeakCells {
    max: Option<f64>,
    max_time_s: Option<f64>,
    min: Option<f64>,
    min_time_s: Option<f64>,
}

impl From<&Peak> for PeakCells {
    fn from(p: &Peak) -> Self {
        Self {
            max: finite(p.max),
            max_time_s: finite(p.max_time),
            min: finite(p.min),
            min_time_s: finite(p.min_time),
        }
    }
}

#[derive(Serialize)]
struct MemberRow {
    model: String,
    gradient_m: f64,
    gradient_ft: f64,
    design_velocity_m_s: f64,
    tip_y_max_m: Option<f64>,
    tip_y_max_time_s: Option<f64>,
    tip_y_min_m: Option<f64>,
    tip_y_min_time_s: Option<f64>,
    tip_twist_max_rad: Option<f64>,
    tip_twist_max_time_s: Option<f64>,
    tip_twist_min_rad: Option<f64>,
    tip_twist_min_time_s: Option<f64>,
    root_bending_moment_max_n_m: Option<f64>,
    root_bending_moment_max_time_s: Option<f64>,
    root_bending_moment_min_n_m: Option<f64>,
    root_bending_moment_min_time_s: Option<f64>,
    root_torque_max_n_m: Option<f64>,
    root_torque_max_time_s: Option<f64>,
    root_torque_min_n_m: Option<f64>,
    root_torque_min_time_s: Option<f64>,
    lift_max_n: Option<f64>,
    lift_max_time_s: Option<f64>,
    lift_min_n: Option<f64>,
    lift_min_time_s: Option<f64>,
    steps: usize,
    wall_time_s: f64,
    status: &'static str,
}

fn member_row(m: &GustMember, model: usize) -> MemberRow {
    let r = &m.runs[model];
    let [y, tw, bm, tq, l] = r.peaks.each_ref().map(PeakCells::from);
    MemberRow {
        model: r.kind.label(),
        gradient_m: m.gradient,
        gradient_ft: m.gradient / FOOT,
        design_velocity_m_s: m.design_velocity,
        tip_y_max_m: y.max,
        tip_y_max_time_s: y.max_time_s,
        tip_y_min_m: y.min,
        tip_y_min_time_s: y.min_time_s,
        tip_twist_max_rad: tw.max,
        tip_twist_max_time_s: tw.max_time_s,
        tip_twist_min_rad: tw.min,
        tip_twist_min_time_s: tw.min_time_s,
        root_bending_moment_max_n_m: bm.max,
        root_bending_moment_max_time_s: bm.max_time_s,
        root_bending_moment_min_n_m: bm.min,
        root_bending_moment_min_time_s: bm.min_time_s,
        root_torque_max_n_m: tq.max,
        root_torque_max_time_s: tq.max_time_s,
        root_torque_min_n_m: tq.min,
        root_torque_min_time_s: tq.min_time_s,
        lift_max_n: l.max,
        lift_max_time_s: l.max_time_s,
        lift_min_n: l.min,
        lift_min_time_s: l.min_time_s,
        steps: r.steps,
        wall_time_s: r.wall_time_s,
        status: r.status.word(),
    }
}

fn member_rows(outcome: &GustFamilyOutcome) -> impl Iterator<Item = MemberRow> + '_ {
    let models = outcome.members.first().map_or(0, |m| m.runs.len());
    (0..models).flat_map(move |k| outcome.members.iter().map(move |m| member_row(m, k)))
}

/// The critical gust of one output of one model.
#[derive(Serialize)]
struct CriticalRow {
    model: String,
    output: &'static str,
    unit: &'static str,
    /// `None` if no run of the model completed.
    gradient_m: Option<f64>,
    gradient_ft: Option<f64>,
    design_velocity_m_s: Option<f64>,
    /// The change of the larger magnitude, signed.
    peak: Option<f64>,
    time_s: Option<f64>,
}

fn critical_rows<'a>(
    plan: &GustFamilyPlan,
    outcome: &'a GustFamilyOutcome,
) -> impl Iterator<Item = CriticalRow> + 'a {
    let shown = outputs(plan);
    outcome
        .statuses()
        .into_iter()
        .enumerate()
        .flat_map(move |(k, (kind, _))| {
            let label = kind.label();
            shown.clone().into_iter().map(move |j| {
                let c = outcome.critical(k, j);
                let extreme = c.map(|m| m.runs[k].peaks[j].extreme());
                CriticalRow {
                    model: label.clone(),
                    output: OUTPUTS[j],
                    unit: OUTPUT_UNITS[j],
                    gradient_m: c.map(|m| m.gradient),
                    gradient_ft: c.map(|m| m.gradient / FOOT),
                    design_velocity_m_s: c.map(|m| m.design_velocity),
                    peak: extreme.and_then(|e| finite(e.0)),
                    time_s: extreme.and_then(|e| finite(e.1)),
                }
            })
        })
}

pub fn files(
    ctx: &Context,
    plan: &GustFamilyPlan,
    outcome: &GustFamilyOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let members = dir.join("gust_family.csv");
    output::write_csv(&members, member_rows(outcome))?;
    let critical = dir.join("gust_family_critical.csv");
    output::write_csv(&critical, critical_rows(plan, outcome))?;
    let mut files = vec![members, critical];
    if with_plot {
        files.extend(write_lines(
            dir,
            "gust_family",
            &peak_plot(ctx, plan, outcome),
        )?);
    }
    Ok(files)
}

/// One panel per output: each model's largest (solid) and smallest (dashed) change against `H`.
fn peak_plot(ctx: &Context, plan: &GustFamilyPlan, outcome: &GustFamilyOutcome) -> LinePlot {
    let models = outcome.statuses();
    let panel = |j: usize| Panel {
        x_label: "gust gradient distance H (m)".into(),
        y_label: format!("peak change of {} ({})", OUTPUTS[j], OUTPUT_UNITS[j]),
        series: models
            .iter()
            .enumerate()
            .flat_map(|(k, (kind, _))| {
                let line = |min: bool| Series {
                    label: format!("{} {}", kind.label(), if min { "min" } else { "max" }),
                    dashed: min,
                    colour: Some(k),
                    points: outcome
                        .members
                        .iter()
                        .map(|m| {
                            let p = &m.runs[k].peaks[j];
                            (m.gradient, if min { p.min } else { p.max })
                        })
                        .collect(),
                };
                [line(false), line(true)]
            })
            .collect(),
    };
    LinePlot {
        title: format!("Discrete gusts (CS 25.341(a)): {}", ctx.what()),
        panels: outputs(plan).into_iter().map(panel).collect(),
    }
}

/// The line saying what the family is.
fn family_line(plan: &GustFamilyPlan, outcome: &GustFamilyOutcome) -> String {
    let h = |m: Option<&GustMember>| m.map_or(f64::NAN, |m| m.gradient);
    format!(
        "gust family: {} 1−cos gusts, H = {:.3} to {:.3} m, U_ref = {} m/s, F_g = {}, from t = {} s, \
         {} penetration",
        outcome.members.len(),
        h(outcome.members.first()),
        h(outcome.members.last()),
        plan.reference_velocity,
        plan.alleviation,
        plan.start,
        plan.penetration.name(),
    )
}

pub fn text(ctx: &Context, s: &mut String, plan: &GustFamilyPlan, outcome: &GustFamilyOutcome) {
    let _ = writeln!(s, "{}", family_line(plan, outcome));
    let _ = writeln!(s);
    let w = super::label_width(outcome.statuses().into_iter().map(|(k, _)| k));
    let _ = writeln!(
        s,
        "{:<w$}  {:>20}  {:>10}  {:>10}  {:>14}  {:>10}",
        "model", "output", "critical H", "U_ds", "peak", "at t"
    );
    let _ = writeln!(
        s,
        "{:<w$}  {:>20}  {:>10}  {:>10}  {:>14}  {:>10}",
        "", "", "(m)", "(m/s)", "", "(s)"
    );
    for row in critical_rows(plan, outcome) {
        let cell = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| "-".into(), f);
        let _ = writeln!(
            s,
            "{:<w$}  {:>20}  {:>10}  {:>10}  {:>14}  {:>10}",
            row.model,
            row.output,
            cell(row.gradient_m, &|v| format!("{v:.3}")),
            cell(row.design_velocity_m_s, &|v| format!("{v:.4}")),
            cell(row.peak, &|v| format!("{v:+.5e} {}", row.unit)),
            cell(row.time_s, &|v| format!("{v:.4}")),
        );
    }
    let _ = writeln!(s);
    for (k, (kind, _)) in outcome.statuses().into_iter().enumerate() {
        let steps: usize = outcome.members.iter().map(|m| m.runs[k].steps).sum();
        let _ = writeln!(
            s,
            "{}: {} runs, {steps} steps, {:.3} s of integration",
            kind.label(),
            outcome.members.len(),
            outcome.wall_time_s(k),
        );
        if let Some(message) = ctx.message_of(&kind.label()) {
            let _ = writeln!(s, "  {message}");
        }
    }
}

#[derive(Serialize)]
pub struct Json {
    model: String,
    aerodynamics: String,
    family: JsonFamily,
    models: Vec<JsonModel>,
}

#[derive(Serialize)]
struct JsonFamily {
    reference_velocity_m_s: f64,
    alleviation: f64,
    start_s: f64,
    penetration: &'static str,
    outputs: Vec<JsonOutput>,
}

#[derive(Serialize)]
struct JsonOutput {
    name: &'static str,
    unit: &'static str,
}

#[derive(Serialize)]
struct JsonModel {
    model: String,
    status: &'static str,
    error: Option<String>,
    wall_time_s: f64,
    members: Vec<MemberRow>,
    critical: Vec<CriticalRow>,
}

pub fn json(ctx: &Context, plan: &GustFamilyPlan, outcome: &GustFamilyOutcome) -> Json {
    let critical: Vec<CriticalRow> = critical_rows(plan, outcome).collect();
    let mut critical = critical.into_iter().peekable();
    Json {
        model: super::model_line(&plan.response.structure.model),
        aerodynamics: super::aero_line(plan.response.aero.aerodynamics, plan.response.aero.density),
        family: JsonFamily {
            reference_velocity_m_s: plan.reference_velocity,
            alleviation: plan.alleviation,
            start_s: plan.start,
            penetration: plan.penetration.name(),
            outputs: outputs(plan)
                .into_iter()
                .map(|j| JsonOutput {
                    name: OUTPUTS[j],
                    unit: OUTPUT_UNITS[j],
                })
                .collect(),
        },
        models: outcome
            .statuses()
            .into_iter()
            .enumerate()
            .map(|(k, (kind, status))| {
                let label = kind.label();
                let mut own = Vec::new();
                while let Some(c) = critical.next_if(|c| c.model == label) {
                    own.push(c);
                }
                JsonModel {
                    status: status.word(),
                    error: ctx.message_of(&label),
                    wall_time_s: outcome.wall_time_s(k),
                    members: outcome.members.iter().map(|m| member_row(m, k)).collect(),
                    critical: own,
                    model: label,
                }
            })
            .collect(),
    }
}
