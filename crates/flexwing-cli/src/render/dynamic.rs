//! `flexwing dynamic`: the integrator's work and the tips of every model side by side;
//! `dynamic_tip.csv`, `dynamic_nodes.csv`, `dynamic_summary.csv`, the tip-history and snapshot
//! plots; its JSON carries each model's histories, counters and energy audit.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::dynamics::{
    gyroscopic_name, Comparison, DynamicOutcome, DynamicPlan, DynamicRun, EnergyAudit, Initial,
    Sample, Snapshot,
};
use flexwing::analysis::Status;
use flexwing::solve::integrate::{IntegratorStats, Method};
use flexwing::solve::{Damping, Gyroscopic, TimeFunction};
use flexwing_case::{OutputFormatSpec, OutputSpec};
use flexwing_io::nodes::{self, NodeHistory};
use serde::Serialize;

use super::{polyline, table, Context, Fields};
use crate::output::{self, short};
use crate::plot::{self, HistoryPlot, HistorySeries, ModelShapes, ShapePlot};

pub const FILES: &[&str] = &[
    "dynamic_tip.csv",
    "dynamic_nodes.csv",
    "dynamic_nodes.npz",
    "dynamic_summary.csv",
    "dynamic_tip.svg",
    "dynamic_tip.png",
    "dynamic_snapshots.svg",
    "dynamic_snapshots.png",
];

/// Number of intervals between the snapshots of the snapshot plot (so 11 shapes).
pub const PLOT_SNAPSHOT_INTERVALS: usize = 10;

const MISSING: &str = "-";

/// Indices of the output times written to the node file (`[output] node_times`): all of them
/// up to its value, else every k-th from the first (`flexwing_case::thinned_indices`).
pub fn node_indices(output: &OutputSpec, n: usize) -> Vec<usize> {
    flexwing_case::thinned_indices(n, output.max_node_times())
}

/// What the node file holds: its format and which output times (the summary and the JSON say
/// when it was thinned).
#[derive(Serialize)]
pub struct NodeOutput {
    /// `csv` or `npz`.
    pub format: &'static str,
    /// Output times written per model.
    pub times: usize,
    /// Output times of the run.
    pub of: usize,
    /// Every `every`-th output time is written (1: all of them).
    pub every: usize,
}

impl NodeOutput {
    pub fn of(output: &OutputSpec, n: usize) -> Self {
        let written = node_indices(output, n);
        Self {
            format: output.format().name(),
            times: written.len(),
            of: n,
            every: written.get(1).copied().unwrap_or(1),
        }
    }

    /// The summary's line.
    pub fn line(&self) -> String {
        let file = format!("dynamic_nodes.{}", self.format);
        if self.every <= 1 {
            format!("node output: {file}, every output time ({})", self.of)
        } else {
            format!(
                "node output: {file}, every {}th of {} output times ({} written; [output] \
                 node_times = \"all\" or --node-times all writes every one)",
                self.every, self.of, self.times
            )
        }
    }
}

/// The node histories of `runs` at the output times `written`, for `.npz`.
pub fn node_histories<'a>(
    runs: impl Iterator<Item = (String, &'a [Snapshot])>,
    written: &[usize],
) -> Vec<NodeHistory> {
    runs.map(|(label, shots)| {
        let kept: Vec<&Snapshot> = shots
            .iter()
            .filter(|s| written.binary_search(&s.index).is_ok())
            .collect();
        let nodes = kept.first().map_or(0, |s| s.shape.x.len());
        let mut values = Vec::with_capacity(kept.len() * nodes * 3);
        for s in &kept {
            for i in 0..nodes {
                values.extend([s.shape.x[i], s.shape.y[i], s.shape.twist[i]]);
            }
        }
        NodeHistory {
            label,
            t: kept.iter().map(|s| s.t).collect(),
            index: kept.iter().map(|s| s.index as i64).collect(),
            nodes,
            values,
        }
    })
    .collect()
}

/// Write the node file of `runs` (CSV or `.npz`, `[output] format`) into `dir`.
pub fn write_nodes<'a>(
    output: &OutputSpec,
    n_times: usize,
    runs: impl Iterator<Item = (String, &'a [Snapshot])> + Clone,
    dir: &Path,
) -> Result<PathBuf> {
    let written = node_indices(output, n_times);
    match output.format() {
        OutputFormatSpec::Csv => {
            let path = dir.join("dynamic_nodes.csv");
            output::write_csv(
                &path,
                runs.flat_map(|(label, shots)| {
                    let written = &written;
                    shots
                        .iter()
                        .filter(move |s| written.binary_search(&s.index).is_ok())
                        .flat_map(move |s| {
                            let label = label.clone();
                            (0..s.shape.x.len()).map(move |i| NodeRow {
                                model: label.clone(),
                                t_s: s.t,
                                node: i,
                                x_m: s.shape.x[i],
                                y_m: s.shape.y[i],
                                twist_rad: s.shape.twist[i],
                            })
                        })
                }),
            )?;
            Ok(path)
        }
        OutputFormatSpec::Npz => {
            let path = dir.join("dynamic_nodes.npz");
            let vars = nodes::variables(&nodes::PLANAR, &node_histories(runs, &written));
            flexwing_io::atomic::write_with(&path, |f| flexwing_io::npz::write(f, &vars))?;
            Ok(path)
        }
    }
}

/// Indices of about [`PLOT_SNAPSHOT_INTERVALS`] + 1 evenly spaced output times, first and last
/// included.
pub fn plot_indices(n: usize) -> Vec<usize> {
    if n <= PLOT_SNAPSHOT_INTERVALS + 1 {
        return (0..n).collect();
    }
    let mut v: Vec<usize> = (0..=PLOT_SNAPSHOT_INTERVALS)
        .map(|j| ((j * (n - 1)) as f64 / PLOT_SNAPSHOT_INTERVALS as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

#[derive(Serialize)]
#[allow(non_snake_case)]
struct TipRow {
    model: String,
    t_s: f64,
    tip_x_m: f64,
    tip_y_m: f64,
    tip_twist_rad: f64,
    kinetic_J: f64,
    strain_J: f64,
    total_J: f64,
    work_J: f64,
    dissipated_J: f64,
    energy_balance_error: f64,
}

#[derive(Serialize)]
struct NodeRow {
    model: String,
    t_s: f64,
    node: usize,
    x_m: f64,
    y_m: f64,
    twist_rad: f64,
}

/// A row of `dynamic_summary.csv` (structural and aeroelastic: `aero_states` and `error` are
/// the aeroelastic one's, the comparison columns the structural one's).
#[derive(Serialize)]
pub struct SummaryRow {
    pub model: String,
    pub dofs: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub aero_states: Option<usize>,
    pub integrator: &'static str,
    pub steps: usize,
    pub rejected_steps: usize,
    pub newton_failures: usize,
    pub rhs_evaluations: usize,
    pub jacobian_evaluations: usize,
    pub factorizations: usize,
    pub wall_time_s: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ratio_to_first: Option<Option<f64>>,
    pub max_tip_difference_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_relative_error_tip_x: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_relative_error_tip_y: Option<Option<f64>>,
    pub energy_balance_max_error: Option<f64>,
    pub energy_balance_max_error_t_s: Option<f64>,
    pub energy_balance_limit: Option<f64>,
    pub status: &'static str,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<Option<String>>,
}

impl SummaryRow {
    /// The columns every dynamic summary shares.
    pub fn new(
        label: String,
        dofs: usize,
        integrator: Method,
        stats: &IntegratorStats,
        wall_time_s: f64,
        audit: Option<&EnergyAudit>,
        status: &Status,
    ) -> Self {
        let finite = super::finite;
        Self {
            model: label,
            dofs,
            aero_states: None,
            integrator: integrator.name(),
            steps: stats.steps,
            rejected_steps: stats.rejected_steps,
            newton_failures: stats.newton_failures,
            rhs_evaluations: stats.rhs_evaluations,
            jacobian_evaluations: stats.jacobian_evaluations,
            factorizations: stats.factorizations,
            wall_time_s: finite(wall_time_s),
            ratio_to_first: None,
            max_tip_difference_m: None,
            max_relative_error_tip_x: None,
            max_relative_error_tip_y: None,
            energy_balance_max_error: audit.and_then(|e| finite(e.max_error)),
            energy_balance_max_error_t_s: audit.and_then(|e| finite(e.max_error_time)),
            energy_balance_limit: audit.and_then(|e| e.limit),
            status: status.word(),
            error: None,
        }
    }
}

pub fn files(
    ctx: &Context,
    plan: &DynamicPlan,
    outcome: &DynamicOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let runs = &outcome.runs;
    let tip = dir.join("dynamic_tip.csv");
    output::write_csv(
        &tip,
        runs.iter().flat_map(|r| {
            r.samples.iter().map(move |p| TipRow {
                model: r.kind.label(),
                t_s: p.t,
                tip_x_m: p.tip_x,
                tip_y_m: p.tip_y,
                tip_twist_rad: p.tip_twist,
                kinetic_J: p.kinetic,
                strain_J: p.strain,
                total_J: p.total(),
                work_J: p.work,
                dissipated_J: p.dissipated,
                energy_balance_error: p.balance_error,
            })
        }),
    )?;
    let nodes = write_nodes(
        &ctx.case.output,
        plan.output_times.len(),
        runs.iter()
            .map(|r| (r.kind.label(), r.snapshots.as_slice())),
        dir,
    )?;
    let summary = dir.join("dynamic_summary.csv");
    output::write_csv(
        &summary,
        runs.iter().map(|r| {
            let mut row = SummaryRow::new(
                r.kind.label(),
                r.dofs,
                r.integrator,
                &r.stats,
                r.wall_time_s,
                r.energy_audit.as_ref(),
                &r.status,
            );
            row.ratio_to_first = Some(outcome.ratio_to_first(r));
            row.max_tip_difference_m = r.comparison.map(|c| c.max_tip_difference);
            row.max_relative_error_tip_x = Some(r.comparison.and_then(|c| c.relative_x));
            row.max_relative_error_tip_y = Some(r.comparison.and_then(|c| c.relative_y));
            row
        }),
    )?;
    let mut files = vec![tip, nodes, summary];
    if with_plot {
        let what = ctx.what();
        let history = HistoryPlot {
            title: format!("Tip history: {what}"),
            end_time: plan.end_time,
            has_torsion: plan.model.has_torsion(),
            series: runs
                .iter()
                .enumerate()
                .map(|(k, r)| history(legend(r, k == 0), k > 0, &r.samples))
                .collect(),
        };
        files.extend(plot::write_tip_history(dir, &history)?);
        let shown = plot_indices(plan.output_times.len());
        files.extend(plot::write_shapes(
            dir,
            "dynamic_snapshots",
            &snapshot_plot(plan, runs.first(), &shown, &what),
        )?);
    }
    Ok(files)
}

/// The tip history of one model's samples for the history plot.
pub fn history(label: String, dashed: bool, samples: &[impl Tip]) -> HistorySeries {
    HistorySeries {
        label,
        dashed,
        t: samples.iter().map(|s| s.tip().0).collect(),
        x: samples.iter().map(|s| s.tip().1).collect(),
        y: samples.iter().map(|s| s.tip().2).collect(),
        twist: samples.iter().map(|s| s.tip().3).collect(),
    }
}

/// A sample with a time and a tip: `(t, x, y, twist)`.
pub trait Tip {
    fn tip(&self) -> (f64, f64, f64, f64);
}

impl Tip for Sample {
    fn tip(&self) -> (f64, f64, f64, f64) {
        (self.t, self.tip_x, self.tip_y, self.tip_twist)
    }
}

fn legend(run: &DynamicRun, first: bool) -> String {
    let dofs = match run.dofs {
        1 => "1 dof".to_string(),
        n => format!("{n} dofs"),
    };
    let label = run.kind.label();
    let kind = if first {
        format!("{label} ({dofs})")
    } else {
        format!("{label} (dashed, {dofs})")
    };
    match (&run.status, run.samples.last()) {
        (Status::Complete, _) => kind,
        (Status::Suspect(_), _) => format!("{kind}: suspect (energy balance)"),
        (_, Some(s)) => format!("{kind}: stopped at t = {} s", short(s.t)),
        (_, None) => format!("{kind}: failed"),
    }
}

/// The first model's deformed shapes at the plot's output times, coloured from dark (early) to
/// light (late); the legend names the first and the last.
fn snapshot_plot(
    plan: &DynamicPlan,
    first: Option<&DynamicRun>,
    shown: &[usize],
    what: &str,
) -> ShapePlot {
    let snapshots: Vec<_> = first
        .iter()
        .flat_map(|r| r.snapshots.iter())
        .filter(|s| shown.binary_search(&s.index).is_ok())
        .collect();
    let label = first.map_or_else(String::new, |r| format!(" of the {} model", r.kind.label()));
    let count = snapshots.len();
    ShapePlot {
        title: format!("Deformed shapes{label}, dark to light in time: {what}"),
        length: plan.model.beam().length(),
        models: snapshots
            .iter()
            .enumerate()
            .map(|(k, s)| ModelShapes {
                label: if k == 0 || k + 1 == count {
                    format!("t = {} s", short(s.t))
                } else if k == 1 {
                    format!("… {} snapshots between …", count - 2)
                } else {
                    String::new()
                },
                dashed: false,
                shapes: vec![polyline(&s.shape)],
            })
            .collect(),
        gradient: true,
    }
}

/// A time function as a factor, e.g. `× sin(20 t)`; empty for a constant.
pub fn describe_time(f: &TimeFunction) -> String {
    match f {
        TimeFunction::Constant => String::new(),
        TimeFunction::Sine { omega, phase } if *phase == 0.0 => {
            format!(" × sin({} t)", short(*omega))
        }
        TimeFunction::Sine { omega, phase } => {
            format!(" × sin({} t + {})", short(*omega), short(*phase))
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

pub fn damping_line(damping: &Damping) -> String {
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

/// The integrator's tolerances and options; `uses_gyroscopic`: a model of the run gets the
/// gyroscopic term (its finite-difference step is then shown).
pub fn tolerances_line(
    integrator: Method,
    st: &flexwing::solve::integrate::IntegratorSettings,
    gyroscopic: Gyroscopic,
    uses_gyroscopic: bool,
) -> String {
    let mut s = format!(
        "rtol {}, atol {} rad on the coordinates",
        short(st.rtol),
        short(st.atol)
    );
    if integrator == Method::Bdf {
        let _ = write!(s, ", BDF maximum order {}", st.max_order);
    }
    if let Some(h) = st.step {
        let _ = write!(s, ", midpoint fixed step {} s", short(h));
    }
    if let Some(h) = st.max_step {
        let _ = write!(s, ", steps at most {} s", short(h));
    }
    if let (true, Gyroscopic::FiniteDifference { step }) = (uses_gyroscopic, gyroscopic) {
        let _ = write!(s, ", finite-difference γ step {}", short(step));
    }
    s
}

/// The lines of the initial state, the simulated time and the node file.
pub fn run_lines(
    s: &mut String,
    initial: &Initial,
    load_name: &dyn Fn(usize) -> String,
    end_time: f64,
    times: &[f64],
) {
    let initial = match initial {
        Initial::Static { loads } => {
            let names: Vec<String> = loads.iter().map(|&i| load_name(i)).collect();
            format!(
                "each model's static equilibrium under {}, released at rest",
                names.join(", ")
            )
        }
        Initial::Given { .. } => "the given q and qdot (reduced models: their projections \
             η = Φᵀ M(0) q, η̇ = Φᵀ M(0) q̇)"
            .into(),
        Initial::Rest => "at rest, undeformed".into(),
    };
    let _ = writeln!(s, "initial state: {initial}");
    let _ = writeln!(
        s,
        "time: 0 to {} s, {} output times from {} to {} s",
        short(end_time),
        times.len(),
        short(times[0]),
        short(times[times.len() - 1])
    );
}

/// When load `i` acts: its time history as a factor, or why it is inactive.
pub fn load_when(time: &[Option<TimeFunction>], initial: &Initial, i: usize) -> String {
    let of_initial = matches!(initial, Initial::Static { loads } if loads.contains(&i));
    match &time[i] {
        Some(f) => describe_time(f),
        None if of_initial => " (inactive: only for the initial static deflection)".into(),
        None => " (inactive: not used)".into(),
    }
}

pub fn text(ctx: &Context, s: &mut String, plan: &DynamicPlan, outcome: &DynamicOutcome) {
    for (i, l) in plan.loads.iter().enumerate() {
        let when = load_when(&plan.time, &plan.initial, i);
        let _ = writeln!(s, "load {}: {}{when}", plan.load_name(i), l);
    }
    run_lines(
        s,
        &plan.initial,
        &|i| plan.load_name(i),
        plan.end_time,
        &plan.output_times,
    );
    let times = &plan.output_times;
    let _ = writeln!(s, "damping: {}", damping_line(&plan.damping));
    let uses_gyroscopic = plan.full || !plan.reduced.is_empty() || !plan.reduced_modes.is_empty();
    let tolerances = tolerances_line(
        plan.integrator,
        &plan.settings,
        plan.gyroscopic,
        uses_gyroscopic,
    );
    let _ = writeln!(s, "tolerances: {tolerances}");
    let _ = writeln!(
        s,
        "{}",
        NodeOutput::of(&ctx.case.output, times.len()).line()
    );
    let _ = writeln!(s);
    s.push_str(&table::rows(
        &outcome
            .runs
            .iter()
            .map(|r| r.kind.label())
            .collect::<Vec<_>>(),
        &rows(plan.model.has_torsion(), outcome),
    ));
}

/// The rows of the side-by-side table: one cell per model.
fn rows(has_torsion: bool, outcome: &DynamicOutcome) -> Vec<(&'static str, Vec<String>)> {
    let runs = &outcome.runs;
    let cells = |f: &dyn Fn(&DynamicRun) -> String| runs.iter().map(f).collect::<Vec<_>>();
    let opt = |v: Option<f64>, f: &dyn Fn(f64) -> String| v.map_or_else(|| MISSING.into(), f);
    let last = |r: &DynamicRun| r.samples.last().copied();
    let (e2, f6) = (|v: f64| format!("{v:.2e}"), |v: f64| format!("{v:.6}"));
    let count = |f: fn(&IntegratorStats) -> usize| cells(&|r| f(&r.stats).to_string());
    let mut rows = vec![
        ("dofs", cells(&|r| r.dofs.to_string())),
        ("integrator", cells(&|r| r.integrator.name().into())),
        (
            "gyroscopic term",
            cells(&|r| gyroscopic_name(r.gyroscopic).into()),
        ),
        ("steps", count(|s| s.steps)),
        ("rejected steps", count(|s| s.rejected_steps)),
        ("  of which Newton failed", count(|s| s.newton_failures)),
        ("RHS evaluations", count(|s| s.rhs_evaluations)),
        ("Jacobian evaluations", count(|s| s.jacobian_evaluations)),
        ("factorizations", count(|s| s.factorizations)),
        (
            "wall time (ms)",
            cells(&|r| format!("{:.3}", 1e3 * r.wall_time_s)),
        ),
        (
            "ratio to first",
            cells(&|r| opt(outcome.ratio_to_first(r), &|v| format!("{v:.3}"))),
        ),
        (
            "t reached (s)",
            cells(&|r| opt(last(r).map(|p| p.t), &short)),
        ),
        (
            "tip x at t reached (m)",
            cells(&|r| opt(last(r).map(|p| p.tip_x), &f6)),
        ),
        (
            "tip y at t reached (m)",
            cells(&|r| opt(last(r).map(|p| p.tip_y), &f6)),
        ),
    ];
    if has_torsion {
        let twist = cells(&|r| opt(last(r).map(|p| p.tip_twist), &f6));
        rows.push(("tip twist at t reached (rad)", twist));
    }
    let comparison = |f: &dyn Fn(&Comparison) -> Option<f64>| {
        cells(&|r| opt(r.comparison.as_ref().and_then(f), &e2))
    };
    rows.extend([
        (
            "max Δtip from first (m)",
            comparison(&|c| Some(c.max_tip_difference)),
        ),
        ("max |Δx| / max |x₁ − L|", comparison(&|c| c.relative_x)),
        ("max |Δy| / max |y₁|", comparison(&|c| c.relative_y)),
        (
            "energy balance error",
            cells(&|r| opt(r.energy_audit.map(|e| e.max_error), &e2)),
        ),
        (
            "energy balance limit",
            cells(&|r| match r.energy_audit.map(|e| e.limit) {
                Some(Some(l)) => format!("{l:.1e}"),
                // The simplified model has no balance: its error is the energy it creates.
                Some(None) => "none".into(),
                None => MISSING.into(),
            }),
        ),
        ("status", cells(&|r| r.status.word().into())),
    ]);
    rows
}

#[derive(Serialize)]
pub struct Json<'a> {
    n_elements: usize,
    has_torsion: bool,
    end_time_s: f64,
    node_output: NodeOutput,
    models: Vec<JsonModel<'a>>,
}

#[derive(Serialize)]
struct JsonModel<'a> {
    label: String,
    dofs: usize,
    modes: Option<Vec<usize>>,
    integrator: &'static str,
    gyroscopic: &'static str,
    stats: &'a IntegratorStats,
    wall_time_s: f64,
    ratio_to_first: Option<f64>,
    max_tip_difference_m: Option<f64>,
    max_relative_error: Option<Fields<Option<f64>>>,
    status: &'static str,
    error: Option<String>,
    t_s: Vec<f64>,
    tip: Fields<Vec<f64>>,
    energy: Fields<Vec<f64>>,
    energy_audit: Option<EnergyAudit>,
}

pub fn json<'a>(ctx: &Context, plan: &DynamicPlan, outcome: &'a DynamicOutcome) -> Json<'a> {
    let model = |r: &'a DynamicRun| {
        let column = |f: fn(&Sample) -> f64| r.samples.iter().map(f).collect::<Vec<f64>>();
        JsonModel {
            label: r.kind.label(),
            dofs: r.dofs,
            modes: r.kind.modes(),
            integrator: r.integrator.name(),
            gyroscopic: gyroscopic_name(r.gyroscopic),
            stats: &r.stats,
            wall_time_s: r.wall_time_s,
            ratio_to_first: outcome.ratio_to_first(r),
            max_tip_difference_m: r.comparison.map(|c| c.max_tip_difference),
            max_relative_error: r
                .comparison
                .map(|c| Fields(vec![("tip_x", c.relative_x), ("tip_y", c.relative_y)])),
            status: r.status.word(),
            error: ctx.message_of(&r.kind.label()),
            t_s: column(|p| p.t),
            tip: Fields(vec![
                ("x_m", column(|p| p.tip_x)),
                ("y_m", column(|p| p.tip_y)),
                ("twist_rad", column(|p| p.tip_twist)),
            ]),
            energy: Fields(vec![
                ("kinetic_J", column(|p| p.kinetic)),
                ("strain_J", column(|p| p.strain)),
                ("total_J", column(Sample::total)),
                ("work_J", column(|p| p.work)),
                ("dissipated_J", column(|p| p.dissipated)),
                ("balance_error", column(|p| p.balance_error)),
            ]),
            energy_audit: r.energy_audit,
        }
    };
    Json {
        n_elements: plan.model.n_elements(),
        has_torsion: plan.model.has_torsion(),
        end_time_s: plan.end_time,
        node_output: NodeOutput::of(&ctx.case.output, plan.output_times.len()),
        models: outcome.runs.iter().map(model).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_snapshots_are_capped() {
        let o = OutputSpec::default();
        let max = OutputSpec::DEFAULT_NODE_TIMES;
        assert_eq!(node_indices(&o, 5), [0, 1, 2, 3, 4]);
        assert_eq!(node_indices(&o, 201).len(), 201);
        let v = node_indices(&o, 202);
        assert_eq!(v[1], 2);
        assert!(v.len() <= max);
        let v = node_indices(&o, 100_000);
        assert!(v.len() <= max && v.len() > 190, "{}", v.len());
        let all = OutputSpec {
            node_times: Some(flexwing_case::NodeTimesSpec::All),
            ..OutputSpec::default()
        };
        assert_eq!(node_indices(&all, 100_000).len(), 100_000);
        let line = NodeOutput::of(&o, 2001).line();
        assert!(
            line.contains("every 10th of 2001 output times (201 written"),
            "{line}"
        );
    }

    #[test]
    fn plot_snapshots_are_evenly_spaced() {
        assert_eq!(plot_indices(3), [0, 1, 2]);
        let v = plot_indices(201);
        assert_eq!(v.len(), 11);
        assert_eq!(v[1], 20);
        assert_eq!(v[10], 200);
    }

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
