//! `flexwing dynamic`: time histories of the full model, the simplified model (gyroscopic term
//! neglected) and reduced models, from rest, from a static deflection or from a given state, under
//! the case's time-varying loads.
//!
//! A model whose integration stops does not stop the run: the other models are simulated, every
//! file holds the output times that were reached, `status.txt` says which model stopped where,
//! and the command exits with status 1.

mod files;
mod progress;
mod report;

use std::io::{IsTerminal as _, Write as _};
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use flexwing::model::{AppliedLoads, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{
    Bdf, BdfOptions, Dopri5, Dopri5Options, ImplicitMidpoint, IntegratorStats, MidpointOptions,
    Radau, RadauOptions, Tolerances,
};
use flexwing::solve::{
    solve_static, Damping, EquationsOfMotion, Gyroscopic, Modes, StaticOptions, TimeFunction,
};
use flexwing::InputError;

use super::{clean, default_out_dir, model_line, Failure};
use crate::case::{
    case_field, Case, DynamicPlan, InitialPlan, Integrator, IntegratorSettings, ModelKind,
    ModelPlan,
};
use progress::Progress;

/// Most node snapshots per model in `dynamic_nodes.csv`: with more output times, every k-th is
/// written.
pub const MAX_NODE_SNAPSHOTS: usize = 201;
/// Number of intervals between the snapshots of the snapshot plot (so 11 shapes).
pub const PLOT_SNAPSHOT_INTERVALS: usize = 10;

/// Options of `flexwing dynamic`.
#[derive(Debug, Args)]
pub struct DynamicArgs {
    /// Case file (TOML) with [dynamic] and usually [[loads]]; see docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write dynamic_tip.svg/.png (tip histories) and dynamic_snapshots.svg/.png (deformed
    /// shapes of the first model).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the table (and never a progress bar).
    #[arg(long)]
    pub json: bool,
}

/// The simulation of one model.
#[derive(Debug, Clone)]
pub struct ModelRun {
    /// `full`, `simplified`, `reduced-r2`, `reduced-modes-1-3`.
    pub label: String,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// Retained modes (1-based) of a reduced model; `None` for the full and simplified models.
    pub modes: Option<Vec<usize>>,
    /// The integrator used.
    pub integrator: Integrator,
    /// How the gyroscopic term was obtained.
    pub gyroscopic: Gyroscopic,
    /// Integrator counters (up to the failure, if any).
    pub stats: IntegratorStats,
    /// Wall time of the integration (s).
    pub wall_time_s: f64,
    /// One sample per output time reached.
    pub samples: Vec<Sample>,
    /// Node positions at the output times written to `dynamic_nodes.csv` and plotted.
    pub snapshots: Vec<Snapshot>,
    /// Why the run stopped early, one line.
    pub error: Option<String>,
    /// Differences from the first model (not for the first model itself).
    pub comparison: Option<Comparison>,
}

/// The tip and the energies at one output time.
#[derive(Debug, Clone, Copy)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Tip node position (m).
    pub tip_x: f64,
    /// Tip node position (m).
    pub tip_y: f64,
    /// Twist of the tip element (rad).
    pub tip_twist: f64,
    /// Kinetic energy `½ pᵀ ẋ` (J).
    pub kinetic: f64,
    /// Strain energy `½ xᵀ K x` (J).
    pub strain: f64,
}

impl Sample {
    /// Kinetic plus strain energy (J).
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain
    }
}

/// The deformed elastic axis at one output time.
#[derive(Debug, Clone)]
pub struct Snapshot {
    /// Index of the output time.
    pub index: usize,
    /// Time (s).
    pub t: f64,
    /// Node positions `x_0 … x_n` (m).
    pub x: Vec<f64>,
    /// Node positions `y_0 … y_n` (m).
    pub y: Vec<f64>,
    /// Twist at each node (rad): that of the element inboard of it, 0 at the clamp.
    pub twist: Vec<f64>,
}

/// How far a model's tip history is from the first model's, over the output times both reached.
#[derive(Debug, Clone, Copy)]
pub struct Comparison {
    /// `max_t |tip − tip_first|` (m).
    pub max_tip_difference: f64,
    /// `max_t |Δx| / max_t |x_first − L|`: relative to the first model's axial tip displacement.
    pub relative_x: Option<f64>,
    /// `max_t |Δy| / max_t |y_first|`.
    pub relative_y: Option<f64>,
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
    /// Span (m).
    pub length: f64,
    /// One line per load, with its time history.
    pub loads: Vec<String>,
    /// One line describing the initial state.
    pub initial: String,
    /// Lines describing the damping and the integrator settings.
    pub settings: report::PlanLines,
    /// Simulated time (s).
    pub end_time: f64,
    /// The planned output times (s).
    pub output_times: Vec<f64>,
    /// Indices of the output times written to `dynamic_nodes.csv`.
    pub node_indices: Vec<usize>,
    /// Indices of the output times of the snapshot plot.
    pub plot_indices: Vec<usize>,
    /// The simulated models, in the order run.
    pub runs: Vec<ModelRun>,
    /// What did not complete.
    pub incomplete: Vec<Incomplete>,
}

impl Outcome {
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

    /// Wall time of `run` over that of the first model.
    pub fn ratio_to_first(&self, run: &ModelRun) -> Option<f64> {
        let first = self.runs.first()?;
        (first.wall_time_s > 0.0).then(|| run.wall_time_s / first.wall_time_s)
    }
}

/// A model ready to simulate: the plan, the model and its damping.
struct Prepared {
    plan: ModelPlan,
    reduced: Option<ReducedModel>,
    damping: Damping,
}

/// Run the command.
pub fn run(args: &DynamicArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let input = |e: InputError| Failure::input(format!("{name}: {e}"));
    let case = Case::load(&args.case).map_err(Failure::input)?;
    let full = FullModel::new(case.to_beam().map_err(input)?);
    let loads = case.to_loads(full.beam()).map_err(input)?;
    let all_loads = full
        .apply(&loads, "loads")
        .map_err(|e| input(case_field(e)))?;
    let plan = case.dynamic_plan(full.n_dofs()).map_err(input)?;
    let active: Vec<Load> = plan.active.iter().map(|&i| loads[i].clone()).collect();
    let active_loads = full
        .apply(&active, "loads")
        .map_err(|e| input(case_field(e)))?;

    let needs_modes = plan
        .models
        .iter()
        .any(|m| matches!(m.kind, ModelKind::Reduced(_)));
    let modes = if needs_modes {
        Some(Modes::undeformed(&full).map_err(|e| {
            Failure::run(format!(
                "{name}: modal analysis about the undeformed state failed: {e}"
            ))
        })?)
    } else {
        None
    };
    let prepared = prepare(&full, &plan, modes.as_ref()).map_err(input)?;
    // Build every model's equations once before running any, so that input the library rejects
    // is reported (exit status 2) before anything is computed.
    for p in &prepared {
        let check = match &p.reduced {
            None => equations(&full, &active_loads, &plan.time_functions, p).map(drop),
            Some(m) => equations(m, &active_loads, &plan.time_functions, p).map(drop),
        };
        check.map_err(|e| input(dynamic_field(e)))?;
    }

    let n_out = plan.output_times.len();
    let node_indices = node_indices(n_out);
    let plot_indices = plot_indices(n_out);
    let mut snapshot_indices: Vec<usize> =
        node_indices.iter().chain(&plot_indices).copied().collect();
    snapshot_indices.sort_unstable();
    snapshot_indices.dedup();

    let show_progress = !args.json && std::io::stderr().is_terminal();
    let mut progress = Progress::new(show_progress, plan.end_time, prepared.len());
    let simulator = Simulator {
        full: &full,
        all_loads: &all_loads,
        active_loads: &active_loads,
        plan: &plan,
        snapshot_indices: &snapshot_indices,
    };
    let mut runs = Vec::new();
    for (k, p) in prepared.iter().enumerate() {
        progress.start_model(k, &p.plan.label);
        let run = match &p.reduced {
            None => simulator.run(&full, p, &mut progress),
            Some(m) => simulator.run(m, p, &mut progress),
        };
        progress.finish_model();
        runs.push(run);
    }
    compare_with_first(&mut runs, full.beam().length());

    let incomplete = runs
        .iter()
        .filter_map(|r| {
            r.error.as_ref().map(|e| Incomplete {
                what: r.label.clone(),
                message: e.clone(),
            })
        })
        .collect();
    let outcome = Outcome {
        case_name: name.clone(),
        title: case.title.clone(),
        model_line: model_line(&full),
        n_elements: full.n_elements(),
        has_torsion: full.has_torsion(),
        length: full.beam().length(),
        loads: report::describe_loads(&case, &loads, &plan),
        initial: report::describe_initial(&plan.initial),
        settings: report::PlanLines::of(&plan),
        end_time: plan.end_time,
        output_times: plan.output_times.clone(),
        node_indices,
        plot_indices,
        runs,
        incomplete,
    };

    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    let written = files::write_files(&dir, &outcome, &case, args.plot).map_err(Failure::Run)?;
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

/// Build the reduced models and each model's damping.
fn prepare(
    full: &FullModel,
    plan: &DynamicPlan,
    modes: Option<&Modes>,
) -> Result<Vec<Prepared>, InputError> {
    plan.models
        .iter()
        .map(|m| {
            let reduced = match (&m.kind, modes) {
                (ModelKind::Reduced(r), Some(modes)) => Some(r.build(full, modes)?),
                _ => None,
            };
            let damping = match &reduced {
                Some(r) => reduced_damping(&plan.damping, r.mode_indices()),
                None => plan.damping.clone(),
            };
            Ok(Prepared {
                plan: m.clone(),
                reduced,
                damping,
            })
        })
        .collect()
}

/// The damping of a reduced model on the modes `indices` (0-based) that projects the full
/// model's, `C_r = Φ_rᵀ C Φ_r`.
///
/// Rayleigh damping projects onto itself (`Φᵀ M(0) Φ = M_r(0)`, `Φᵀ K Φ = K_r`). Modal damping
/// `C = M₀ Φ diag(2 ζ_k ω_k) Φᵀ M₀` projects onto `diag(2 ζ_k ω_k)` over the retained modes, but the
/// library numbers a model's ratios by that model's own modes, which for a reduced model are the
/// retained modes in order of frequency: so mode `j` of the reduced model gets the ratio of the
/// `j`-th smallest retained index (0 if the case gives none for it).
fn reduced_damping(damping: &Damping, indices: &[usize]) -> Damping {
    match damping {
        Damping::Modal { ratios } => {
            let mut sorted = indices.to_vec();
            sorted.sort_unstable();
            Damping::Modal {
                ratios: sorted
                    .iter()
                    .map(|&k| ratios.get(k).copied().unwrap_or(0.0))
                    .collect(),
            }
        }
        other => other.clone(),
    }
}

fn equations<'a, M: StructuralModel>(
    model: &'a M,
    loads: &'a AppliedLoads,
    time_functions: &[TimeFunction],
    p: &Prepared,
) -> Result<EquationsOfMotion<'a, M>, InputError> {
    EquationsOfMotion::new(
        model,
        loads,
        time_functions.to_vec(),
        p.plan.gyroscopic,
        &p.damping,
    )
}

/// The library names damping fields `damping.*`; the case file has them under `dynamic.`.
fn dynamic_field(mut e: InputError) -> InputError {
    if e.field == "damping" || e.field.starts_with("damping.") {
        e.field = format!("dynamic.{}", e.field);
    }
    e
}

/// Indices of the output times written to `dynamic_nodes.csv`: all of them up to
/// [`MAX_NODE_SNAPSHOTS`], else every k-th from the first with `k = ⌈n / MAX⌉`.
pub fn node_indices(n: usize) -> Vec<usize> {
    let k = n.div_ceil(MAX_NODE_SNAPSHOTS).max(1);
    (0..n).step_by(k).collect()
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

/// What every model's simulation shares.
struct Simulator<'a> {
    full: &'a FullModel,
    all_loads: &'a AppliedLoads,
    active_loads: &'a AppliedLoads,
    plan: &'a DynamicPlan,
    snapshot_indices: &'a [usize],
}

impl Simulator<'_> {
    /// Simulate `model`, timing the integration alone.
    fn run<M: StructuralModel>(
        &self,
        model: &M,
        p: &Prepared,
        progress: &mut Progress,
    ) -> ModelRun {
        let mut run = ModelRun {
            label: p.plan.label.clone(),
            dofs: model.n_dofs(),
            modes: p
                .reduced
                .as_ref()
                .map(|r| r.mode_indices().iter().map(|k| k + 1).collect()),
            integrator: p.plan.integrator,
            gyroscopic: p.plan.gyroscopic,
            stats: IntegratorStats::default(),
            wall_time_s: 0.0,
            samples: Vec::new(),
            snapshots: Vec::new(),
            error: None,
            comparison: None,
        };
        let (x0, xdot0) = match self.initial_state(model, p.reduced.as_ref()) {
            Ok(s) => s,
            Err(message) => {
                run.error = Some(message);
                return run;
            }
        };
        // Checked before the runs started; cannot fail here.
        let mut eom = match equations(model, self.active_loads, &self.plan.time_functions, p) {
            Ok(eom) => eom,
            Err(e) => {
                run.error = Some(dynamic_field(e).to_string());
                return run;
            }
        };
        let y0 = eom.state(&x0, &xdot0);
        let tolerances = Tolerances {
            rtol: self.plan.settings.rtol,
            atol: eom.state_atol(self.plan.settings.atol),
        };
        let t_out = &self.plan.output_times;
        let mut report = |t: f64| progress.update(t);
        let start = Instant::now();
        let result = integrate(
            p.plan.integrator,
            &self.plan.settings,
            tolerances,
            &mut eom,
            &y0,
            t_out,
            &mut report,
        );
        run.wall_time_s = start.elapsed().as_secs_f64();
        let trajectory = match result {
            Ok((trajectory, stats)) => {
                run.stats = stats;
                trajectory
            }
            Err(failure) => {
                run.stats = failure.stats;
                run.error = Some(failure.error.to_string());
                failure.trajectory
            }
        };
        let n = model.n_dofs();
        let mut next_snapshot = self.snapshot_indices.iter().peekable();
        for (index, (&t, y)) in trajectory.t.iter().zip(&trajectory.y).enumerate() {
            let q = model.full_coordinates(&y[..n]);
            let (kinetic, strain) = eom.energies(y);
            let (x, yy, twist) = self.nodes(&q);
            let tip = x.len() - 1;
            run.samples.push(Sample {
                t,
                tip_x: x[tip],
                tip_y: yy[tip],
                tip_twist: twist[tip],
                kinetic,
                strain,
            });
            if next_snapshot.peek() == Some(&&index) {
                next_snapshot.next();
                run.snapshots.push(Snapshot {
                    index,
                    t,
                    x,
                    y: yy,
                    twist,
                });
            }
        }
        run
    }

    /// The model's coordinates and velocities at `t = 0`, or why they could not be found.
    fn initial_state<M: StructuralModel>(
        &self,
        model: &M,
        reduced: Option<&ReducedModel>,
    ) -> Result<(Vec<f64>, Vec<f64>), String> {
        let n = model.n_dofs();
        match &self.plan.initial {
            InitialPlan::Rest => Ok((vec![0.0; n], vec![0.0; n])),
            InitialPlan::Static { loads, names } => {
                let mut scales = vec![0.0; self.all_loads.n_loads()];
                for &i in loads {
                    scales[i] = 1.0;
                }
                solve_static(model, self.all_loads, &scales, &StaticOptions::default())
                    .map(|s| (s.x, vec![0.0; n]))
                    .map_err(|e| {
                        format!(
                            "the initial static deflection under {} failed: {e}",
                            names.join(", ")
                        )
                    })
            }
            InitialPlan::Given { q, qdot } => Ok(match reduced {
                None => (q.clone(), qdot.clone()),
                Some(r) => (r.reduce_coordinates(q), r.reduce_coordinates(qdot)),
            }),
        }
    }

    /// Node positions and nodal twists of the full model's joint rotations `q`.
    fn nodes(&self, q: &[f64]) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let full = self.full;
        let kin = full.kinematics(q);
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
        (
            nodes.iter().map(|p| clean(p[0])).collect(),
            nodes.iter().map(|p| clean(p[1])).collect(),
            twist,
        )
    }
}

/// Run the chosen integrator.
fn integrate<M: StructuralModel>(
    integrator: Integrator,
    settings: &IntegratorSettings,
    tolerances: Tolerances,
    eom: &mut EquationsOfMotion<'_, M>,
    y0: &[f64],
    t_out: &[f64],
    progress: &mut dyn FnMut(f64),
) -> flexwing::solve::integrate::IntegrationResult {
    let max_step = settings.max_step.unwrap_or(f64::INFINITY);
    match integrator {
        Integrator::Bdf => Bdf {
            options: BdfOptions {
                tolerances,
                max_order: settings.max_order,
                max_steps: settings.max_steps,
                max_step,
                ..BdfOptions::default()
            },
        }
        .integrate(eom, 0.0, y0, t_out, progress),
        Integrator::Dopri5 => Dopri5 {
            options: Dopri5Options {
                tolerances,
                max_steps: settings.max_steps,
                max_step,
                ..Dopri5Options::default()
            },
        }
        .integrate(eom, 0.0, y0, t_out, progress),
        Integrator::Midpoint => ImplicitMidpoint {
            options: MidpointOptions {
                tolerances,
                step: settings.step,
                max_steps: settings.max_steps,
                max_step,
                ..MidpointOptions::default()
            },
        }
        .integrate(eom, 0.0, y0, t_out, progress),
        Integrator::Radau => Radau {
            options: RadauOptions {
                tolerances,
                max_steps: settings.max_steps,
                max_step,
                ..RadauOptions::default()
            },
        }
        .integrate(eom, 0.0, y0, t_out, progress),
    }
}

/// Fill in each model's differences from the first model's tip history, over the output times
/// both reached.
fn compare_with_first(runs: &mut [ModelRun], length: f64) {
    let Some((first, others)) = runs.split_first_mut() else {
        return;
    };
    for run in others {
        let common = run.samples.len().min(first.samples.len());
        if common == 0 {
            continue;
        }
        let pairs = || run.samples[..common].iter().zip(&first.samples[..common]);
        let max = |f: &dyn Fn(&Sample, &Sample) -> f64| {
            pairs().map(|(a, b)| f(a, b)).fold(0.0_f64, f64::max)
        };
        let relative = |diff: f64, scale: f64| (scale > 0.0).then(|| diff / scale);
        run.comparison = Some(Comparison {
            max_tip_difference: max(&|a, b| (a.tip_x - b.tip_x).hypot(a.tip_y - b.tip_y)),
            relative_x: relative(
                max(&|a, b| (a.tip_x - b.tip_x).abs()),
                max(&|_, b| (b.tip_x - length).abs()),
            ),
            relative_y: relative(
                max(&|a, b| (a.tip_y - b.tip_y).abs()),
                max(&|_, b| b.tip_y.abs()),
            ),
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_snapshots_are_capped() {
        assert_eq!(node_indices(5), [0, 1, 2, 3, 4]);
        assert_eq!(node_indices(201).len(), 201);
        let v = node_indices(202);
        assert_eq!(v[1], 2);
        assert!(v.len() <= MAX_NODE_SNAPSHOTS);
        let v = node_indices(100_000);
        assert!(
            v.len() <= MAX_NODE_SNAPSHOTS && v.len() > 190,
            "{}",
            v.len()
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
    fn modal_damping_of_a_reduced_model_follows_its_modes() {
        let d = Damping::Modal {
            ratios: vec![0.1, 0.2, 0.3],
        };
        let Damping::Modal { ratios } = reduced_damping(&d, &[4, 0, 2]) else {
            panic!("not modal")
        };
        assert_eq!(ratios, [0.1, 0.3, 0.0]);
        let r = Damping::Rayleigh {
            alpha: 1.0,
            beta: 2.0,
        };
        assert_eq!(reduced_damping(&r, &[0]), r);
    }
}
