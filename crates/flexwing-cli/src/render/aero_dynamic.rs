//! `flexwing dynamic` on a case with `[aero]`: the aeroelastic response of every model (a gust,
//! changes of speed or root angle); `dynamic_aero.csv` (tip, twist, root bending moment, lift,
//! speed, energies, the work of the loads, the dissipated energy, the energy balance per output
//! time), `dynamic_hinges.csv` (each control surface's hinge moment per output time, with
//! `[[aero.surfaces]]`), `dynamic_nodes.csv` or `.npz` (as `flexwing dynamic`'s),
//! `dynamic_summary.csv` and the tip-history plot. Non-finite numbers (none expected) are
//! written as empty fields (CSV) or `null` (JSON).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::response::{
    AeroDynamicOutcome, AeroDynamicPlan, AeroDynamicRun, AeroSample,
};
use flexwing::analysis::dynamics::EnergyAudit;
use serde::Serialize;

use super::dynamic::{history, write_nodes, NodeOutput, SummaryRow, Tip};
use super::{finite, Context};
use crate::output;
use crate::plot::{self, HistoryPlot};

pub const FILES: &[&str] = &[
    "dynamic_aero.csv",
    "dynamic_hinges.csv",
    "dynamic_nodes.csv",
    "dynamic_nodes.npz",
    "dynamic_summary.csv",
    "dynamic_tip.svg",
    "dynamic_tip.png",
];

const MISSING: &str = "-";

impl Tip for AeroSample {
    fn tip(&self) -> (f64, f64, f64, f64) {
        (self.t, self.tip_x, self.tip_y, self.tip_twist)
    }
}

#[derive(Serialize)]
struct SampleRow {
    model: String,
    t_s: Option<f64>,
    tip_x_m: Option<f64>,
    tip_y_m: Option<f64>,
    tip_twist_rad: Option<f64>,
    root_bending_moment_n_m: Option<f64>,
    lift_n: Option<f64>,
    speed_m_s: Option<f64>,
    kinetic_j: Option<f64>,
    strain_j: Option<f64>,
    work_j: Option<f64>,
    dissipated_j: Option<f64>,
    energy_balance_error: Option<f64>,
}

fn samples(r: &AeroDynamicRun) -> impl Iterator<Item = SampleRow> + '_ {
    r.samples.iter().map(|s| SampleRow {
        model: r.kind.label(),
        t_s: finite(s.t),
        tip_x_m: finite(s.tip_x),
        tip_y_m: finite(s.tip_y),
        tip_twist_rad: finite(s.tip_twist),
        root_bending_moment_n_m: finite(s.root_bending_moment),
        lift_n: finite(s.lift),
        speed_m_s: finite(s.speed),
        kinetic_j: finite(s.kinetic),
        strain_j: finite(s.strain),
        work_j: finite(s.work),
        dissipated_j: finite(s.dissipated),
        energy_balance_error: finite(s.balance_error),
    })
}

/// A row of `dynamic_hinges.csv` (written when the wing has control surfaces): the hinge moment
/// of one surface at one output time.
#[derive(Serialize)]
struct HingeRow {
    model: String,
    t_s: Option<f64>,
    surface: String,
    hinge_moment_n_m: Option<f64>,
}

/// The hinge rows of `r`, for the surfaces of `plan`.
fn hinge_rows<'a>(
    plan: &'a AeroDynamicPlan,
    r: &'a AeroDynamicRun,
) -> impl Iterator<Item = HingeRow> + 'a {
    r.samples
        .iter()
        .zip(&r.hinge_moments)
        .flat_map(move |(s, row)| {
            plan.aero
                .section
                .surfaces
                .iter()
                .zip(row)
                .map(move |(sf, &h)| HingeRow {
                    model: r.kind.label(),
                    t_s: finite(s.t),
                    surface: sf.name.clone(),
                    hinge_moment_n_m: finite(h),
                })
        })
}

fn summary(ctx: &Context, r: &AeroDynamicRun) -> SummaryRow {
    let label = r.kind.label();
    let mut row = SummaryRow::new(
        label.clone(),
        r.dofs,
        r.integrator,
        &r.stats,
        r.wall_time_s,
        r.energy_audit.as_ref(),
        &r.status,
    );
    row.aero_states = Some(r.aero_states);
    row.max_tip_difference_m = r.max_tip_difference.and_then(finite);
    row.error = Some(ctx.message_of(&label));
    row
}

pub fn files(
    ctx: &Context,
    plan: &AeroDynamicPlan,
    outcome: &AeroDynamicOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let runs = &outcome.runs;
    let tip = dir.join("dynamic_aero.csv");
    output::write_csv(&tip, runs.iter().flat_map(samples))?;
    let nodes = write_nodes(
        &ctx.case.output,
        plan.structure.output_times.len(),
        runs.iter()
            .map(|r| (r.kind.label(), r.snapshots.as_slice())),
        dir,
    )?;
    let sum = dir.join("dynamic_summary.csv");
    output::write_csv(&sum, runs.iter().map(|r| summary(ctx, r)))?;
    let mut files = vec![tip, nodes, sum];
    if !plan.aero.section.surfaces.is_empty() {
        let hinges = dir.join("dynamic_hinges.csv");
        output::write_csv(&hinges, runs.iter().flat_map(|r| hinge_rows(plan, r)))?;
        files.push(hinges);
    }
    if with_plot {
        let s = &plan.structure;
        let plot = HistoryPlot {
            title: format!("Aeroelastic response: {}", ctx.what()),
            end_time: s.end_time,
            has_torsion: s.model.has_torsion(),
            series: runs
                .iter()
                .map(|r| {
                    let label = format!("{} ({} dofs)", r.kind.label(), r.dofs);
                    history(label, r.kind.modes().is_some(), &r.samples)
                })
                .collect(),
        };
        files.extend(plot::write_tip_history(dir, &plot)?);
    }
    Ok(files)
}

/// The extreme of `f` over the samples, with its time.
fn peak(r: &AeroDynamicRun, f: impl Fn(&AeroSample) -> f64) -> String {
    r.samples
        .iter()
        .map(|s| (f(s), s.t))
        .filter(|(v, _)| v.is_finite())
        .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
        .map_or_else(
            || MISSING.into(),
            |(v, t)| format!("{v:.6} at t = {t:.4} s"),
        )
}

pub fn text(ctx: &Context, s: &mut String, plan: &AeroDynamicPlan, outcome: &AeroDynamicOutcome) {
    let times = plan.structure.output_times.len();
    let _ = writeln!(s, "{}", NodeOutput::of(&ctx.case.output, times).line());
    let _ = writeln!(s);
    let w = super::label_width(outcome.runs.iter().map(|r| &r.kind));
    // The columns after the model's label and their widths; the status last.
    const WIDTHS: [usize; 11] = [5, 11, 17, 6, 8, 5, 14, 13, 12, 12, 12];
    let line = |s: &mut String, label: &str, cells: [String; 11], status: &str| {
        let mut l = format!("{label:<w$}");
        for (c, width) in cells.iter().zip(WIDTHS) {
            let _ = write!(l, "  {c:>width$}");
        }
        let _ = writeln!(s, "{l}  {status}");
    };
    let heads = [
        "dofs",
        "aero states",
        "integrator",
        "steps",
        "rejected",
        "LU",
        "wall time (ms)",
        "ratio to 1st",
        "max Δtip (m)",
        "energy error",
        "energy limit",
    ];
    line(s, "model", heads.map(String::from), "status");
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| MISSING.into(), f);
    for r in &outcome.runs {
        let audit = r.energy_audit.as_ref();
        let cells = [
            r.dofs.to_string(),
            r.aero_states.to_string(),
            r.integrator.name().into(),
            r.stats.steps.to_string(),
            r.stats.rejected_steps.to_string(),
            r.stats.factorizations.to_string(),
            format!("{:.3}", 1e3 * r.wall_time_s),
            opt(outcome.ratio_to_first(r), &|v| format!("{v:.3}")),
            opt(r.max_tip_difference, &|v| format!("{v:.2e}")),
            opt(audit.map(|e| e.max_error), &|v| format!("{v:.2e}")),
            opt(audit.and_then(|e| e.limit), &|v| format!("{v:.1e}")),
        ];
        line(s, &r.kind.label(), cells, r.status.word());
    }
    let _ = writeln!(s);
    for r in &outcome.runs {
        let _ = writeln!(s, "{}:", r.kind.label());
        type Of = fn(&AeroSample) -> f64;
        let rows: [(&str, Of); 4] = [
            ("largest |tip y| (m):                ", |x| x.tip_y),
            ("largest |tip twist| (rad):          ", |x| x.tip_twist),
            ("largest |root bending moment| (N·m): ", |x| {
                x.root_bending_moment
            }),
            ("largest |lift| (N):                 ", |x| x.lift),
        ];
        for (what, f) in rows {
            let _ = writeln!(s, "  {what}{}", peak(r, f));
        }
    }
}

#[derive(Serialize)]
pub struct Json {
    model: String,
    aerodynamics: String,
    node_output: NodeOutput,
    /// The gust's penetration (`uniform`, `kussner`), absent without a gust.
    #[serde(skip_serializing_if = "Option::is_none")]
    penetration: Option<&'static str>,
    models: Vec<JsonModel>,
}

#[derive(Serialize)]
struct JsonModel {
    summary: SummaryRow,
    energy_audit: Option<EnergyAudit>,
    samples: Vec<SampleRow>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    hinge_moments: Vec<HingeRow>,
}

pub fn json(ctx: &Context, plan: &AeroDynamicPlan, outcome: &AeroDynamicOutcome) -> Json {
    Json {
        model: super::model_line(&plan.structure.model),
        aerodynamics: super::aero_line(plan.aero.aerodynamics, plan.aero.density),
        node_output: NodeOutput::of(&ctx.case.output, plan.structure.output_times.len()),
        penetration: plan.flight.gust.as_ref().map(|g| g.penetration.name()),
        models: outcome
            .runs
            .iter()
            .map(|r| JsonModel {
                summary: summary(ctx, r),
                energy_audit: r.energy_audit,
                samples: samples(r).collect(),
                hinge_moments: hinge_rows(plan, r).collect(),
            })
            .collect(),
    }
}
