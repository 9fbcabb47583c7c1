//! What `flexwing dynamic` prints: the side-by-side table, or one JSON document (`--json`).

use std::fmt::Write as _;
use std::path::PathBuf;

use flexwing::analysis::dynamics::{DynamicPlan, DynamicRun, EnergyAudit, Initial, Sample};
use flexwing::analysis::Stop;
use flexwing::solve::integrate::Method;
use flexwing::solve::{Damping, Gyroscopic, TimeFunction};
use serde::Serialize;

use super::Outcome;
use crate::commands::statics::report::{describe_load, short};
use flexwing_case::Case;

const MISSING: &str = "-";

/// The case-file spelling of a gyroscopic option.
pub fn gyroscopic_name(g: Gyroscopic) -> &'static str {
    match g {
        Gyroscopic::Exact => "exact",
        Gyroscopic::FiniteDifference { .. } => "finite-difference",
        Gyroscopic::Neglected => "neglected",
    }
}

/// A time function as a factor, e.g. `× sin(20 t)`; empty for a constant.
pub fn describe_time(f: &TimeFunction) -> String {
    match f {
        TimeFunction::Constant => String::new(),
        TimeFunction::Sine { omega, phase } => {
            if *phase == 0.0 {
                format!(" × sin({} t)", short(*omega))
            } else {
                format!(" × sin({} t + {})", short(*omega), short(*phase))
            }
        }
        TimeFunction::Step { time } => format!(" × step from 0 to 1 at t = {} s", short(*time)),
        TimeFunction::Ramp { start, end } => format!(
            " × ramp from 0 at t = {} s to 1 at t = {} s",
            short(*start),
            short(*end)
        ),
        TimeFunction::Table { t, .. } => format!(
            " × table of {} points over [{}, {}] s",
            t.len(),
            short(t[0]),
            short(t[t.len() - 1])
        ),
    }
}

/// One line per load: name, load, time history, and whether it acts during the motion.
pub fn describe_loads(case: &Case, plan: &DynamicPlan) -> Vec<String> {
    let initial = match &plan.initial {
        Initial::Static { loads } => loads.clone(),
        _ => Vec::new(),
    };
    plan.loads
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let name = case.loads[i]
                .name
                .clone()
                .unwrap_or_else(|| format!("loads[{i}]"));
            let when = match &plan.time[i] {
                Some(f) => describe_time(f),
                None if initial.contains(&i) => {
                    " (inactive: only for the initial static deflection)".into()
                }
                None => " (inactive: not used)".into(),
            };
            format!("{name}: {}{when}", describe_load(l))
        })
        .collect()
}

/// One line describing the initial state; `names` are those of the loads of a static one.
pub fn describe_initial(initial: &Initial, names: &[String]) -> String {
    match initial {
        Initial::Static { .. } => format!(
            "each model's static equilibrium under {}, released at rest",
            names.join(", ")
        ),
        Initial::Given { .. } => "the given q and qdot (reduced models: their projections \
             η = Φᵀ M(0) q, η̇ = Φᵀ M(0) q̇)"
            .into(),
        Initial::Rest => "at rest, undeformed".into(),
    }
}

fn damping_line(damping: &Damping) -> String {
    match damping {
        Damping::None => "none".into(),
        Damping::Rayleigh { alpha, beta } => {
            format!("Rayleigh, C = {} M(0) + {} K", short(*alpha), short(*beta))
        }
        Damping::Modal { ratios } => {
            let r: Vec<String> = ratios.iter().map(|&z| short(z)).collect();
            format!("modal, ratios {} of modes 1 to {}", r.join(", "), r.len())
        }
    }
}

fn last(run: &DynamicRun) -> Option<&Sample> {
    run.samples.last()
}

/// `complete`, `suspect`, `incomplete` or `interrupted`.
pub fn status(run: &DynamicRun) -> &'static str {
    match run.status.stop() {
        Some(Stop::Interrupted { .. }) => "interrupted",
        _ => run.status.word(),
    }
}

/// The text report.
pub fn tables(outcome: &Outcome, files: &[PathBuf]) -> String {
    let plan_lines = &outcome.settings;
    let mut s = String::new();
    if let Some(title) = &outcome.title {
        let _ = writeln!(s, "{title}");
    }
    let _ = writeln!(s, "{}", outcome.model_line);
    for l in &outcome.loads {
        let _ = writeln!(s, "load {l}");
    }
    let _ = writeln!(s, "initial state: {}", outcome.initial);
    let times = &outcome.output_times;
    let _ = writeln!(
        s,
        "time: 0 to {} s, {} output times from {} to {} s",
        short(outcome.end_time),
        times.len(),
        short(times[0]),
        short(times[times.len() - 1])
    );
    let _ = writeln!(s, "damping: {}", plan_lines.damping);
    let _ = writeln!(s, "tolerances: {}", plan_lines.tolerances);
    let _ = writeln!(s);

    type Cell<'a> = Box<dyn Fn(&DynamicRun) -> String + 'a>;
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| MISSING.into(), f);
    let mut rows: Vec<(&str, Cell)> = vec![
        ("dofs", Box::new(|r| r.dofs.to_string())),
        ("integrator", Box::new(|r| r.integrator.name().into())),
        (
            "gyroscopic term",
            Box::new(|r| gyroscopic_name(r.gyroscopic).into()),
        ),
        ("steps", Box::new(|r| r.stats.steps.to_string())),
        (
            "rejected steps",
            Box::new(|r| r.stats.rejected_steps.to_string()),
        ),
        (
            "  of which Newton failed",
            Box::new(|r| r.stats.newton_failures.to_string()),
        ),
        (
            "RHS evaluations",
            Box::new(|r| r.stats.rhs_evaluations.to_string()),
        ),
        (
            "Jacobian evaluations",
            Box::new(|r| r.stats.jacobian_evaluations.to_string()),
        ),
        (
            "factorizations",
            Box::new(|r| r.stats.factorizations.to_string()),
        ),
        (
            "wall time (ms)",
            Box::new(|r| format!("{:.3}", 1e3 * r.wall_time_s)),
        ),
        (
            "ratio to first",
            Box::new(|r| opt(outcome.result.ratio_to_first(r), &|v| format!("{v:.3}"))),
        ),
        (
            "t reached (s)",
            Box::new(|r| opt(last(r).map(|p| p.t), &|v| short(v))),
        ),
        (
            "tip x at t reached (m)",
            Box::new(|r| opt(last(r).map(|p| p.tip_x), &|v| format!("{v:.6}"))),
        ),
        (
            "tip y at t reached (m)",
            Box::new(|r| opt(last(r).map(|p| p.tip_y), &|v| format!("{v:.6}"))),
        ),
    ];
    if outcome.has_torsion {
        rows.push((
            "tip twist at t reached (rad)",
            Box::new(|r| opt(last(r).map(|p| p.tip_twist), &|v| format!("{v:.6}"))),
        ));
    }
    rows.extend::<[(&str, Cell); 6]>([
        (
            "max Δtip from first (m)",
            Box::new(|r| {
                opt(r.comparison.map(|c| c.max_tip_difference), &|v| {
                    format!("{v:.2e}")
                })
            }),
        ),
        (
            "max |Δx| / max |x₁ − L|",
            Box::new(|r| {
                opt(r.comparison.and_then(|c| c.relative_x), &|v| {
                    format!("{v:.2e}")
                })
            }),
        ),
        (
            "max |Δy| / max |y₁|",
            Box::new(|r| {
                opt(r.comparison.and_then(|c| c.relative_y), &|v| {
                    format!("{v:.2e}")
                })
            }),
        ),
        (
            "energy balance error",
            Box::new(|r| {
                opt(r.energy_audit.as_ref().map(|e| e.max_error), &|v| {
                    format!("{v:.2e}")
                })
            }),
        ),
        (
            "energy balance limit",
            Box::new(|r| match r.energy_audit.as_ref().map(|e| e.limit) {
                Some(Some(l)) => format!("{l:.1e}"),
                // The simplified model has no balance: its error is the energy it creates.
                Some(None) => "none".into(),
                None => MISSING.into(),
            }),
        ),
        ("status", Box::new(|r| status(r).into())),
    ]);

    let runs = outcome.runs();
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|(_, f)| runs.iter().map(f).collect())
        .collect();
    let head = rows
        .iter()
        .map(|(h, _)| h.chars().count())
        .max()
        .unwrap_or(0);
    let widths: Vec<usize> = runs
        .iter()
        .enumerate()
        .map(|(k, r)| {
            cells
                .iter()
                .map(|row| row[k].chars().count())
                .chain([r.kind.label().chars().count(), 8])
                .max()
                .unwrap_or(8)
        })
        .collect();
    let mut line = format!("{:head$}", "");
    for (r, w) in runs.iter().zip(&widths) {
        let _ = write!(line, "  {:>w$}", r.kind.label());
    }
    let _ = writeln!(s, "{}", line.trim_end());
    for ((h, _), row) in rows.iter().zip(&cells) {
        let pad = head - h.chars().count();
        let mut line = format!("{h}{}", " ".repeat(pad));
        for (c, w) in row.iter().zip(&widths) {
            let _ = write!(line, "  {c:>w$}");
        }
        let _ = writeln!(s, "{}", line.trim_end());
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

/// Lines of the text report that describe the plan's settings.
#[derive(Debug)]
pub struct PlanLines {
    /// The damping.
    pub damping: String,
    /// Tolerances and integrator options.
    pub tolerances: String,
}

impl PlanLines {
    /// The lines for `plan`.
    pub fn of(plan: &DynamicPlan) -> Self {
        let st = &plan.settings;
        let mut tolerances = format!(
            "rtol {}, atol {} rad on the coordinates",
            short(st.rtol),
            short(st.atol)
        );
        if plan.integrator == Method::Bdf {
            let _ = write!(tolerances, ", BDF maximum order {}", st.max_order);
        }
        if let Some(h) = st.step {
            let _ = write!(tolerances, ", midpoint fixed step {} s", short(h));
        }
        if let Some(h) = st.max_step {
            let _ = write!(tolerances, ", steps at most {} s", short(h));
        }
        let uses_gyroscopic =
            plan.full || !plan.reduced.is_empty() || !plan.reduced_modes.is_empty();
        if let (true, Gyroscopic::FiniteDifference { step }) = (uses_gyroscopic, plan.gyroscopic) {
            let _ = write!(tolerances, ", finite-difference γ step {}", short(step));
        }
        Self {
            damping: damping_line(&plan.damping),
            tolerances,
        }
    }
}

#[derive(Serialize)]
struct JsonReport<'a> {
    case: &'a str,
    title: Option<&'a str>,
    n_elements: usize,
    has_torsion: bool,
    end_time_s: f64,
    models: Vec<JsonModel<'a>>,
    files: Vec<String>,
    status: &'static str,
    error: Option<String>,
}

#[derive(Serialize)]
struct JsonModel<'a> {
    label: String,
    dofs: usize,
    modes: Option<Vec<usize>>,
    integrator: &'static str,
    gyroscopic: &'static str,
    stats: JsonStats,
    wall_time_s: f64,
    ratio_to_first: Option<f64>,
    max_tip_difference_m: Option<f64>,
    max_relative_error: Option<JsonRelative>,
    status: &'static str,
    error: Option<&'a str>,
    t_s: Vec<f64>,
    tip: JsonTip,
    energy: JsonEnergy,
    energy_audit: Option<EnergyAudit>,
}

#[derive(Serialize)]
struct JsonStats {
    steps: usize,
    rejected_steps: usize,
    newton_failures: usize,
    rhs_evaluations: usize,
    jacobian_evaluations: usize,
    factorizations: usize,
    newton_iterations: usize,
}

#[derive(Serialize)]
struct JsonRelative {
    tip_x: Option<f64>,
    tip_y: Option<f64>,
}

#[derive(Serialize)]
struct JsonTip {
    x_m: Vec<f64>,
    y_m: Vec<f64>,
    twist_rad: Vec<f64>,
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct JsonEnergy {
    kinetic_J: Vec<f64>,
    strain_J: Vec<f64>,
    total_J: Vec<f64>,
    work_J: Vec<f64>,
    dissipated_J: Vec<f64>,
    balance_error: Vec<f64>,
}

fn json_model<'a>(outcome: &'a Outcome, r: &'a DynamicRun) -> JsonModel<'a> {
    let column = |f: fn(&Sample) -> f64| r.samples.iter().map(f).collect::<Vec<f64>>();
    let st = &r.stats;
    JsonModel {
        label: r.kind.label(),
        dofs: r.dofs,
        modes: r.kind.modes(),
        integrator: r.integrator.name(),
        gyroscopic: gyroscopic_name(r.gyroscopic),
        stats: JsonStats {
            steps: st.steps,
            rejected_steps: st.rejected_steps,
            newton_failures: st.newton_failures,
            rhs_evaluations: st.rhs_evaluations,
            jacobian_evaluations: st.jacobian_evaluations,
            factorizations: st.factorizations,
            newton_iterations: st.newton_iterations,
        },
        wall_time_s: r.wall_time_s,
        ratio_to_first: outcome.result.ratio_to_first(r),
        max_tip_difference_m: r.comparison.map(|c| c.max_tip_difference),
        max_relative_error: r.comparison.map(|c| JsonRelative {
            tip_x: c.relative_x,
            tip_y: c.relative_y,
        }),
        status: status(r),
        error: outcome.message_of(r),
        t_s: column(|p| p.t),
        tip: JsonTip {
            x_m: column(|p| p.tip_x),
            y_m: column(|p| p.tip_y),
            twist_rad: column(|p| p.tip_twist),
        },
        energy: JsonEnergy {
            kinetic_J: column(|p| p.kinetic),
            strain_J: column(|p| p.strain),
            total_J: column(Sample::total),
            work_J: column(|p| p.work),
            dissipated_J: column(|p| p.dissipated),
            balance_error: column(|p| p.balance_error),
        },
        energy_audit: r.energy_audit,
    }
}

/// The JSON document of `--json`.
pub fn json(outcome: &Outcome, files: &[PathBuf]) -> String {
    let report = JsonReport {
        case: &outcome.case_name,
        title: outcome.title.as_deref(),
        n_elements: outcome.n_elements,
        has_torsion: outcome.has_torsion,
        end_time_s: outcome.end_time,
        models: outcome
            .runs()
            .iter()
            .map(|r| json_model(outcome, r))
            .collect(),
        files: files.iter().map(|f| f.display().to_string()).collect(),
        status: outcome.status(),
        error: outcome.error(),
    };
    // Serializing plain structs of numbers and strings cannot fail; a non-finite number (a state
    // that blew up) becomes null.
    let mut text = serde_json::to_string_pretty(&report).unwrap_or_default();
    text.push('\n');
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_functions_read_as_factors() {
        assert_eq!(describe_time(&TimeFunction::Constant), "");
        assert_eq!(
            describe_time(&TimeFunction::Sine {
                omega: 20.0,
                phase: 0.0
            }),
            " × sin(20 t)"
        );
        assert_eq!(
            describe_time(&TimeFunction::Ramp {
                start: 0.0,
                end: 0.2
            }),
            " × ramp from 0 at t = 0 s to 1 at t = 0.2 s"
        );
    }
}
