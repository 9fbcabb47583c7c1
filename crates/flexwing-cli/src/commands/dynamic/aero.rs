//! `flexwing dynamic` on a case with `[aero]`: the aeroelastic response to a gust and to changes of
//! speed or root angle (`flexwing::analysis::aero::response`), for the full and reduced models of
//! `[dynamic]`, from the static aeroelastic equilibrium of the initial flight (or at rest).
//!
//! Files: `dynamic_aero.csv` (one row per model and output time: tip, twist, root bending moment,
//! lift, speed, energies, the work of the loads and the dissipated energy, the energy balance),
//! `dynamic_summary.csv` (with the energy audit's largest error and limit), `status.txt`; with
//! `--plot` `dynamic_tip.svg/.png`. A run whose energy balance exceeds its limit is `suspect`, one
//! whose energy runs away is stopped (docs/model-choices.md, "Energy audit"): both exit 1.
//! Non-finite numbers (none expected) are written as empty fields (CSV) or `null` (JSON).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use flexwing::analysis::aero::response::{self, AeroDynamicOutcome, AeroDynamicRun};
use flexwing::analysis::Stop;
use flexwing::Error;
use serde::Serialize;

use super::DynamicArgs;
use crate::commands::flutter::aero_line;
use crate::commands::{
    default_out_dir, model_line, status_entry, status_text, Failure, Incomplete,
};
use crate::output;
use crate::plot::{self, HistoryPlot, HistorySeries};
use flexwing_case::Case;

fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
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

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    aero_states: usize,
    integrator: &'static str,
    steps: usize,
    rejected_steps: usize,
    newton_failures: usize,
    rhs_evaluations: usize,
    jacobian_evaluations: usize,
    factorizations: usize,
    wall_time_s: Option<f64>,
    max_tip_difference_m: Option<f64>,
    energy_balance_max_error: Option<f64>,
    energy_balance_max_error_t_s: Option<f64>,
    energy_balance_limit: Option<f64>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonReport<'a> {
    case: &'a str,
    title: Option<&'a str>,
    model: &'a str,
    aerodynamics: &'a str,
    models: Vec<JsonModel>,
    files: Vec<String>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonModel {
    summary: SummaryRow,
    energy_audit: Option<flexwing::analysis::dynamics::EnergyAudit>,
    samples: Vec<SampleRow>,
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

fn summary(r: &AeroDynamicRun, incomplete: &[Incomplete]) -> SummaryRow {
    let label = r.kind.label();
    let st = &r.stats;
    SummaryRow {
        error: incomplete
            .iter()
            .find(|i| i.what == label)
            .map(|i| i.message.clone()),
        model: label,
        dofs: r.dofs,
        aero_states: r.aero_states,
        integrator: r.integrator.name(),
        steps: st.steps,
        rejected_steps: st.rejected_steps,
        newton_failures: st.newton_failures,
        rhs_evaluations: st.rhs_evaluations,
        jacobian_evaluations: st.jacobian_evaluations,
        factorizations: st.factorizations,
        wall_time_s: finite(r.wall_time_s),
        max_tip_difference_m: r.max_tip_difference.and_then(finite),
        energy_balance_max_error: r.energy_audit.as_ref().and_then(|e| finite(e.max_error)),
        energy_balance_max_error_t_s: r
            .energy_audit
            .as_ref()
            .and_then(|e| finite(e.max_error_time)),
        energy_balance_limit: r.energy_audit.as_ref().and_then(|e| e.limit),
        status: status_word(r),
    }
}

/// `complete`, `suspect`, `incomplete` or `interrupted`.
fn status_word(r: &AeroDynamicRun) -> &'static str {
    match r.status.stop() {
        Some(Stop::Interrupted { .. }) => "interrupted",
        _ => r.status.word(),
    }
}

/// Every result file a run may write (besides `status.txt`): removed before a run, so that a
/// folder holds one run's files only.
pub const FILES: &[&str] = &[
    "dynamic_aero.csv",
    "dynamic_summary.csv",
    "dynamic_tip.svg",
    "dynamic_tip.png",
];

/// Run the aeroelastic response of the case.
pub fn run(args: &DynamicArgs, case: &Case) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let plan = case.aero_dynamic_plan().map_err(Failure::input)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    crate::output::prepare_dir(&dir, FILES, true).map_err(Failure::Run)?;
    // Ctrl-C and `kill` stop the run after the current step, as for structural runs.
    crate::commands::interrupt::catch_interrupts(false);
    let result =
        response::run(&plan, &mut crate::commands::interrupt::Cancel).map_err(|e| match e {
            Error::Input(e) => Failure::input(format!("{name}: {e}")),
            e => Failure::run(format!("{name}: {e}")),
        })?;
    let incomplete: Vec<Incomplete> = result
        .runs
        .iter()
        .filter_map(|r| status_entry(&r.kind.label(), &r.status, None, &[]))
        .collect();
    let s = &plan.structure;
    let model = model_line(&s.model);
    let aero = aero_line(plan.aero.aerodynamics, plan.aero.density);
    let title = case.title.clone().unwrap_or_else(|| name.clone());
    let written = write_files(
        &dir,
        &result,
        &incomplete,
        &title,
        s.end_time,
        s.model.has_torsion(),
        args.plot,
    )
    .map_err(Failure::Run)?;
    let status = crate::commands::overall_word(&incomplete);
    let error = crate::commands::error_text(&incomplete);
    let text = if args.json {
        let doc = JsonReport {
            case: &name,
            title: case.title.as_deref(),
            model: &model,
            aerodynamics: &aero,
            models: result
                .runs
                .iter()
                .map(|r| JsonModel {
                    summary: summary(r, &incomplete),
                    energy_audit: r.energy_audit,
                    samples: samples(r).collect(),
                })
                .collect(),
            files: written.iter().map(|f| f.display().to_string()).collect(),
            status,
            error,
        };
        let mut t = serde_json::to_string_pretty(&doc).unwrap_or_default();
        t.push('\n');
        t
    } else {
        tables(case, &model, &aero, &result, &incomplete, &written)
    };
    let printed = crate::commands::print_stdout(&text, args.json);
    if let Some(first) = incomplete.first() {
        return Err(Failure::run(format!(
            "{name}: {}: {}: {} (see status.txt)",
            first.what, first.word, first.message
        )));
    }
    printed
}

/// The extreme of `f` over the samples, with its time.
fn peak(r: &AeroDynamicRun, f: impl Fn(&response::AeroSample) -> f64) -> String {
    r.samples
        .iter()
        .map(|s| (f(s), s.t))
        .filter(|(v, _)| v.is_finite())
        .max_by(|a, b| a.0.abs().total_cmp(&b.0.abs()))
        .map_or_else(|| "-".into(), |(v, t)| format!("{v:.6} at t = {t:.4} s"))
}

fn tables(
    case: &Case,
    model: &str,
    aero: &str,
    result: &AeroDynamicOutcome,
    incomplete: &[Incomplete],
    files: &[PathBuf],
) -> String {
    let mut s = String::new();
    if let Some(t) = &case.title {
        let _ = writeln!(s, "{t}");
    }
    let _ = writeln!(s, "{model}");
    let _ = writeln!(s, "{aero}");
    let _ = writeln!(s);
    let w = result
        .runs
        .iter()
        .map(|r| r.kind.label().chars().count())
        .max()
        .unwrap_or(0)
        .max(10);
    let _ = writeln!(
        s,
        "{:<w$}  {:>5}  {:>11}  {:>17}  {:>6}  {:>8}  {:>5}  {:>14}  {:>13}  {:>12}  {:>12}  {:>12}  status",
        "model",
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
    );
    for r in &result.runs {
        let ratio = result
            .ratio_to_first(r)
            .map_or_else(|| "-".into(), |v| format!("{v:.3}"));
        let diff = r
            .max_tip_difference
            .map_or_else(|| "-".into(), |v| format!("{v:.2e}"));
        let energy = r
            .energy_audit
            .as_ref()
            .map_or_else(|| "-".into(), |e| format!("{:.2e}", e.max_error));
        let limit = r
            .energy_audit
            .as_ref()
            .and_then(|e| e.limit)
            .map_or_else(|| "-".into(), |l| format!("{l:.1e}"));
        let _ = writeln!(
            s,
            "{:<w$}  {:>5}  {:>11}  {:>17}  {:>6}  {:>8}  {:>5}  {:>14.3}  {:>13}  {:>12}  {:>12}  {:>12}  {}",
            r.kind.label(),
            r.dofs,
            r.aero_states,
            r.integrator.name(),
            r.stats.steps,
            r.stats.rejected_steps,
            r.stats.factorizations,
            1e3 * r.wall_time_s,
            ratio,
            diff,
            energy,
            limit,
            status_word(r)
        );
    }
    let _ = writeln!(s);
    for r in &result.runs {
        let _ = writeln!(s, "{}:", r.kind.label());
        let _ = writeln!(
            s,
            "  largest |tip y| (m):                {}",
            peak(r, |x| x.tip_y)
        );
        let _ = writeln!(
            s,
            "  largest |tip twist| (rad):          {}",
            peak(r, |x| x.tip_twist)
        );
        let _ = writeln!(
            s,
            "  largest |root bending moment| (N·m): {}",
            peak(r, |x| x.root_bending_moment)
        );
        let _ = writeln!(
            s,
            "  largest |lift| (N):                 {}",
            peak(r, |x| x.lift)
        );
    }
    let _ = writeln!(s);
    if incomplete.is_empty() {
        let _ = writeln!(s, "status: complete");
    }
    for i in incomplete {
        let _ = writeln!(s, "status: {}: {}: {}", i.word, i.what, i.message);
    }
    for f in files {
        let _ = writeln!(s, "wrote {}", f.display());
    }
    s
}

fn write_files(
    dir: &Path,
    result: &AeroDynamicOutcome,
    incomplete: &[Incomplete],
    title: &str,
    end_time: f64,
    has_torsion: bool,
    with_plot: bool,
) -> anyhow::Result<Vec<PathBuf>> {
    output::create_dir(dir)?;
    let mut files = Vec::new();
    let tip = dir.join("dynamic_aero.csv");
    output::write_csv(&tip, result.runs.iter().flat_map(samples))?;
    files.push(tip);
    let sum = dir.join("dynamic_summary.csv");
    output::write_csv(&sum, result.runs.iter().map(|r| summary(r, incomplete)))?;
    files.push(sum);
    if with_plot {
        let plot = HistoryPlot {
            title: format!("Aeroelastic response: {title}"),
            end_time,
            has_torsion,
            series: result
                .runs
                .iter()
                .map(|r| HistorySeries {
                    label: format!("{} ({} dofs)", r.kind.label(), r.dofs),
                    dashed: r.kind.modes().is_some(),
                    t: r.samples.iter().map(|s| s.t).collect(),
                    x: r.samples.iter().map(|s| s.tip_x).collect(),
                    y: r.samples.iter().map(|s| s.tip_y).collect(),
                    twist: r.samples.iter().map(|s| s.tip_twist).collect(),
                })
                .collect(),
        };
        files.extend(plot::write_tip_history(dir, &plot)?);
    }
    let status = dir.join("status.txt");
    output::write_bytes(&status, status_text(incomplete).as_bytes())?;
    files.push(status);
    Ok(files)
}
