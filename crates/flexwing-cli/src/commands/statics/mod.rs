//! `flexwing static`: non-linear static equilibria of the full model and of reduced models,
//! at one load level or over a load sweep continued from point to point.
//!
//! A model whose sweep stops early does not stop the run: the other models are solved, every
//! file is written with the points that converged, `status.txt` says what stopped where, and the
//! command exits with status 1.

mod files;
pub(crate) mod report;

use std::io::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use flexwing::model::{AppliedLoads, FullModel, Load, StructuralModel};
use flexwing::solve::{sweep_static, Modes, StaticOptions, StaticSolution, StaticStats};
use flexwing::SolveError;

use super::{clean, default_out_dir, model_line, Failure};
use crate::case::{case_field, Case, StaticPlan, Sweep};

/// Options of `flexwing static`.
#[derive(Debug, Args)]
pub struct StaticArgs {
    /// Case file (TOML) with [[loads]] and optionally [static]; see docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write static_shapes.svg and static_shapes.png (deformed shapes of every point).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the tables.
    #[arg(long)]
    pub json: bool,
}

/// The equilibria of one model over the sweep.
#[derive(Debug, Clone)]
pub struct ModelRun {
    /// `full`, `reduced-r2`, `reduced-modes-1-2-4`.
    pub label: String,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// Retained modes (1-based) of a reduced model; `None` for the full model.
    pub modes: Option<Vec<usize>>,
    /// Wall time of the solve over all points (s).
    pub wall_time_s: f64,
    /// The converged points, in sweep order from the first.
    pub points: Vec<PointResult>,
    /// Why the sweep stopped early, one line.
    pub error: Option<String>,
}

/// One equilibrium, as nodal quantities of the full model.
#[derive(Debug, Clone)]
pub struct PointResult {
    /// Scale of the swept load (1 without a sweep).
    pub scale: f64,
    /// Scales of all loads.
    pub scales: Vec<f64>,
    /// Node positions `x_0 … x_n` (m).
    pub x: Vec<f64>,
    /// Node positions `y_0 … y_n` (m).
    pub y: Vec<f64>,
    /// Twist at each node (rad): that of the element inboard of it, 0 at the clamp.
    pub twist: Vec<f64>,
    /// Joint rotations of the full model at the equilibrium (rad).
    pub q: Vec<f64>,
    /// Solver counters of this point.
    pub stats: StaticStats,
    /// Distance of the tip from the full model's tip at the same point (m); reduced models only.
    pub tip_difference: Option<f64>,
}

impl PointResult {
    /// Tip position and twist `(x, y, twist)`.
    pub fn tip(&self) -> (f64, f64, f64) {
        let n = self.x.len() - 1;
        (self.x[n], self.y[n], self.twist[n])
    }
}

/// A mode about the full model's final equilibrium.
#[derive(Debug, Clone, Copy)]
pub struct LoadedMode {
    /// Mode number, 1-based.
    pub mode: usize,
    /// Circular frequency about the loaded equilibrium (rad/s).
    pub omega: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Circular frequency of the same-numbered mode about the undeformed state (rad/s).
    pub unloaded_omega: f64,
}

pub use super::Incomplete;

/// Everything the reports and files need.
#[derive(Debug)]
pub struct Outcome {
    /// Path of the case file as given.
    pub case_name: String,
    /// The case's title.
    pub title: Option<String>,
    /// One line describing the full model.
    pub model_line: String,
    /// Number of elements.
    pub n_elements: usize,
    /// Whether the model has torsion.
    pub has_torsion: bool,
    /// One line per load.
    pub loads: Vec<String>,
    /// The sweep, if any.
    pub sweep: Option<Sweep>,
    /// Scale of the swept load at each point (`[1]` without a sweep).
    pub scales: Vec<f64>,
    /// The solved models, the full model first.
    pub runs: Vec<ModelRun>,
    /// Loaded modes, if asked for and computed.
    pub loaded_modes: Option<Vec<LoadedMode>>,
    /// What did not complete.
    pub incomplete: Vec<Incomplete>,
}

impl Outcome {
    /// The full model's run, if it was solved.
    pub fn full(&self) -> Option<&ModelRun> {
        self.runs.iter().find(|r| r.modes.is_none())
    }

    /// `complete` or `incomplete`.
    pub fn status(&self) -> &'static str {
        if self.incomplete.is_empty() {
            "complete"
        } else {
            "incomplete"
        }
    }

    /// `LABEL: MESSAGE` of everything incomplete, joined by `; `; `None` when complete.
    pub fn error(&self) -> Option<String> {
        (!self.incomplete.is_empty()).then(|| {
            self.incomplete
                .iter()
                .map(|i| format!("{}: {}", i.what, i.message))
                .collect::<Vec<_>>()
                .join("; ")
        })
    }

    /// Wall time of `run` over that of the full model.
    pub fn ratio_to_full(&self, run: &ModelRun) -> Option<f64> {
        let full = self.full()?;
        (full.wall_time_s > 0.0).then(|| run.wall_time_s / full.wall_time_s)
    }

    /// Largest tip difference from the full model over the points both solved.
    pub fn max_tip_difference(run: &ModelRun) -> Option<f64> {
        run.points
            .iter()
            .filter_map(|p| p.tip_difference)
            .reduce(f64::max)
    }
}

/// Run the command.
pub fn run(args: &StaticArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let input = |e: flexwing::InputError| Failure::input(format!("{name}: {e}"));
    let case = Case::load(&args.case).map_err(Failure::input)?;
    let full = FullModel::new(case.to_beam().map_err(input)?);
    let loads = case.to_loads(full.beam()).map_err(input)?;
    let applied = full
        .apply(&loads, "loads")
        .map_err(|e| input(case_field(e)))?;
    let plan = case.static_plan(full.n_dofs(), &loads).map_err(input)?;

    let unloaded = if plan.reduced.is_empty() && plan.modes.is_none() {
        None
    } else {
        Some(Modes::undeformed(&full).map_err(|e| {
            Failure::run(format!(
                "{name}: modal analysis about the undeformed state failed: {e}"
            ))
        })?)
    };
    let reduced = match &unloaded {
        None => Vec::new(),
        Some(modes) => plan
            .reduced
            .iter()
            .map(|r| r.build(&full, modes).map(|m| (r.label.clone(), m)))
            .collect::<Result<Vec<_>, _>>()
            .map_err(input)?,
    };

    let solver = Solver {
        full: &full,
        applied: &applied,
        points: plan.points(loads.len()),
        scales: plan.point_scales(),
        sweep: plan.sweep.as_ref(),
        options: &plan.options,
    };
    let mut runs = Vec::new();
    if plan.full {
        runs.push(solver.run("full".into(), &full, None));
    }
    for (label, model) in &reduced {
        let modes = model.mode_indices().iter().map(|k| k + 1).collect();
        runs.push(solver.run(label.clone(), model, Some(modes)));
    }
    compare_tips(&mut runs);

    let mut incomplete: Vec<Incomplete> = runs
        .iter()
        .filter_map(|r| {
            r.error.as_ref().map(|e| Incomplete {
                what: r.label.clone(),
                message: e.clone(),
            })
        })
        .collect();
    let loaded_modes = match (&plan.modes, &unloaded) {
        (Some(count), Some(unloaded)) => {
            loaded_modes(&full, &applied, &plan, &runs, *count, unloaded).unwrap_or_else(|e| {
                incomplete.push(e);
                None
            })
        }
        _ => None,
    };

    let outcome = Outcome {
        case_name: name.clone(),
        title: case.title.clone(),
        model_line: model_line(&full),
        n_elements: full.n_elements(),
        has_torsion: full.has_torsion(),
        loads: describe_loads(&case, &loads),
        sweep: plan.sweep.clone(),
        scales: plan.point_scales(),
        runs,
        loaded_modes,
        incomplete,
    };

    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    let written =
        files::write_files(&dir, &outcome, &full, &case, args.plot).map_err(Failure::Run)?;
    let text = if args.json {
        report::json(&outcome, &written)
    } else {
        report::tables(&outcome, &written)
    };
    let mut stdout = std::io::stdout().lock();
    let printed = stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| Failure::run(format!("cannot write to standard output: {e}")));
    if let Some(first) = outcome.incomplete.first() {
        let others: Vec<&str> = outcome.incomplete[1..]
            .iter()
            .map(|i| i.what.as_str())
            .collect();
        let also = if others.is_empty() {
            String::new()
        } else {
            format!(" (also incomplete: {}; see status.txt)", others.join(", "))
        };
        return Err(Failure::run(format!(
            "{name}: {}: {}{also}",
            first.what, first.message
        )));
    }
    printed
}

/// What every model's sweep shares.
struct Solver<'a> {
    full: &'a FullModel,
    applied: &'a AppliedLoads,
    points: Vec<Vec<f64>>,
    scales: Vec<f64>,
    sweep: Option<&'a Sweep>,
    options: &'a StaticOptions,
}

impl Solver<'_> {
    /// Sweep `model`, timing the solve alone.
    fn run<M: StructuralModel>(
        &self,
        label: String,
        model: &M,
        modes: Option<Vec<usize>>,
    ) -> ModelRun {
        let start = Instant::now();
        let result = sweep_static(model, self.applied, &self.points, self.options);
        let wall_time_s = start.elapsed().as_secs_f64();
        let (solutions, error) = match result {
            Ok(s) => (s, None),
            Err(e) => {
                let message = match self.sweep {
                    Some(s) => {
                        // The solver's load factor runs from the previous point (rest before the
                        // first) to the failed one; say which scale it reached.
                        let target = s.scales[e.point];
                        let reached = match &e.error {
                            SolveError::StaticDiverged { load_factor, .. } => {
                                let previous = e.point.checked_sub(1).map_or(0.0, |p| s.scales[p]);
                                format!(
                                    ", converged up to scale {}",
                                    report::short(previous + load_factor * (target - previous))
                                )
                            }
                            _ => String::new(),
                        };
                        format!(
                            "stopped at sweep point {} of {} ({} scale {}{reached}): {}",
                            e.point + 1,
                            self.points.len(),
                            s.name,
                            report::short(target),
                            e.error
                        )
                    }
                    None => e.error.to_string(),
                };
                (e.completed, Some(message))
            }
        };
        ModelRun {
            label,
            dofs: model.n_dofs(),
            modes,
            wall_time_s,
            points: solutions
                .iter()
                .zip(&self.scales)
                .map(|(s, &scale)| self.point(s, scale))
                .collect(),
            error,
        }
    }

    fn point(&self, sol: &StaticSolution, scale: f64) -> PointResult {
        let full = self.full;
        let kin = full.kinematics(&sol.q);
        let nodes = full.node_positions(&kin);
        let twist = (0..nodes.len())
            .map(|k| {
                if k == 0 || !full.has_torsion() {
                    0.0
                } else {
                    clean(kin.psi[k - 1])
                }
            })
            .collect();
        PointResult {
            scale,
            scales: sol.scales.clone(),
            x: nodes.iter().map(|p| clean(p[0])).collect(),
            y: nodes.iter().map(|p| clean(p[1])).collect(),
            twist,
            q: sol.q.clone(),
            stats: sol.stats,
            tip_difference: None,
        }
    }
}

/// Fill in each reduced model's tip distance from the full model, point by point.
fn compare_tips(runs: &mut [ModelRun]) {
    let Some(full) = runs.iter().position(|r| r.modes.is_none()) else {
        return;
    };
    let tips: Vec<(f64, f64, f64)> = runs[full].points.iter().map(PointResult::tip).collect();
    for run in runs.iter_mut().filter(|r| r.modes.is_some()) {
        for (p, reference) in run.points.iter_mut().zip(&tips) {
            let (x, y, _) = p.tip();
            p.tip_difference = Some((x - reference.0).hypot(y - reference.1));
        }
    }
}

/// Modes about the full model's equilibrium at the last point; `Ok(None)` if the full model did
/// not reach it (that is already reported as incomplete).
fn loaded_modes(
    full: &FullModel,
    applied: &AppliedLoads,
    plan: &StaticPlan,
    runs: &[ModelRun],
    count: usize,
    unloaded: &Modes,
) -> Result<Option<Vec<LoadedMode>>, Incomplete> {
    let Some(run) = runs.iter().find(|r| r.modes.is_none()) else {
        return Ok(None);
    };
    let n_points = plan.point_scales().len();
    if run.points.len() < n_points {
        return Ok(None);
    }
    let last = &run.points[n_points - 1];
    let modes = Modes::loaded(full, &last.q, applied, &last.scales).map_err(|e| Incomplete {
        what: "loaded modes".into(),
        message: e.to_string(),
    })?;
    Ok(Some(
        (0..count.min(modes.n_modes()))
            .map(|k| LoadedMode {
                mode: k + 1,
                omega: modes.omega()[k],
                frequency_hz: modes.omega()[k] / (2.0 * std::f64::consts::PI),
                unloaded_omega: unloaded.omega()[k],
            })
            .collect(),
    ))
}

/// One line per load, for the table report.
fn describe_loads(case: &Case, loads: &[Load]) -> Vec<String> {
    loads
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let name = case.loads[i]
                .name
                .clone()
                .unwrap_or_else(|| format!("loads[{i}]"));
            format!("{name}: {}", report::describe_load(l))
        })
        .collect()
}
