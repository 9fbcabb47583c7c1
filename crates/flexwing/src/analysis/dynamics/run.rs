//! Running a dynamic plan: build each model (reduced models on the undeformed modes, with the
//! projected damping), find its initial state, integrate it, and sample the tip, the energies
//! and the snapshots at the output times.

use std::time::Instant;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use super::audit::{integrate_audited, AuditedRun, EnergyAudit};
use super::outcome::{compare_with_first, DynamicOutcome, DynamicRun, Sample, Snapshot};
use super::{DynamicPlan, Initial};
use crate::analysis::models::ModelKind;
use crate::analysis::{Note, Progress, Status, Stop};
use crate::error::{Error, SolveError};
use crate::model::{AppliedLoads, FullModel, ReducedModel, StructuralModel};
use crate::solve::integrate::IntegratorStats;
use crate::solve::{solve_static, Damping, EquationsOfMotion, Modes, StaticOptions, TimeFunction};

/// Run the dynamic analysis of `plan`. `progress` hears each model's start and the fraction of
/// its simulated time.
///
/// # Errors
/// An invalid plan ([`DynamicPlan::validate`], fields named relative to the plan), or the modal
/// analysis about the undeformed state (needed by reduced models) failing. A model whose run
/// stops is in the outcome with its [`Status`].
///
/// ```
/// use flexwing::analysis::{dynamics, NoProgress};
/// use flexwing::model::{Force, Load};
/// use flexwing::solve::TimeFunction;
/// let model = flexwing::paper::table4_beam(10)?;
/// let tip = Load::PointForce { span: 1.0, force: Force::Dead { fx: 0.0, fy: 10.0 } };
/// let times: Vec<f64> = (0..=10).map(|k| 0.01 * k as f64).collect();
/// let mut plan = dynamics::DynamicPlan::new(model, vec![tip], 0.1, times);
/// plan.time = vec![Some(TimeFunction::Sine { omega: 20.0, phase: 0.0 })];
/// plan.reduced = vec![2];
/// plan.validate("loads", "dynamic")?;
/// let outcome = dynamics::run(&plan, &mut NoProgress)?;
/// assert!(outcome.is_complete());
/// assert_eq!(outcome.runs[1].samples.len(), 11);
/// assert!(outcome.runs[1].comparison.unwrap().max_tip_difference < 1e-3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(plan: &DynamicPlan, progress: &mut dyn Progress) -> Result<DynamicOutcome, Error> {
    plan.validate("loads", "")?;
    let full = &plan.model;
    let all_loads = full.apply(&plan.loads, "loads")?;
    let active = plan.active();
    let active_list: Vec<_> = active.iter().map(|&i| plan.loads[i].clone()).collect();
    let active_loads = full.apply(&active_list, "loads")?;
    let time_functions: Vec<TimeFunction> = active
        .iter()
        .filter_map(|&i| plan.time[i].clone())
        .collect();
    let kinds = plan.models()?;
    let modes = super::super::models::modes_needed(&kinds)
        .map(|count| Modes::lowest(full, count))
        .transpose()?;
    let mut snapshots = plan.snapshots.clone();
    snapshots.sort_unstable();
    snapshots.dedup();
    let simulator = Simulator {
        plan,
        full,
        all_loads: &all_loads,
        active_loads: &active_loads,
        time_functions: &time_functions,
        snapshots: &snapshots,
    };
    let mut runs = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        if progress.cancelled() {
            runs.push(DynamicRun::not_run(
                kind,
                plan,
                Stop::Interrupted { time: None },
            ));
            continue;
        }
        progress.start(k, kinds.len(), &kind.label());
        let run = match (kind.mode_indices(), &modes) {
            (Some(indices), Some(modes)) => {
                let rom = ReducedModel::new(full, modes.shapes(), &indices)?;
                let damping = rom.project_damping(&plan.damping);
                simulator.run(kind, &rom, Some(&rom), &damping, progress)
            }
            _ => simulator.run(kind, full, None, &plan.damping, progress),
        };
        progress.finish();
        runs.push(run);
    }
    compare_with_first(&mut runs, full.beam().length());
    Ok(DynamicOutcome { runs })
}

impl DynamicRun {
    /// A run of `kind` that did not get to integrate, with the reason.
    fn not_run(kind: &ModelKind, plan: &DynamicPlan, stop: Stop) -> Self {
        DynamicRun {
            kind: kind.clone(),
            dofs: 0,
            integrator: plan.integrator,
            gyroscopic: plan.gyroscopic_of(kind),
            stats: IntegratorStats::default(),
            wall_time_s: 0.0,
            samples: Vec::new(),
            snapshots: Vec::new(),
            status: Status::Stopped(stop),
            energy_audit: None,
            comparison: None,
            notes: Vec::new(),
        }
    }
}

/// What every model's simulation shares.
struct Simulator<'a> {
    plan: &'a DynamicPlan,
    full: &'a FullModel,
    all_loads: &'a AppliedLoads,
    active_loads: &'a AppliedLoads,
    time_functions: &'a [TimeFunction],
    /// Sorted, without repeats.
    snapshots: &'a [usize],
}

impl Simulator<'_> {
    /// Simulate `model` (`reduced` is the same model when it is a reduced one), timing the
    /// integration alone.
    fn run<M: StructuralModel>(
        &self,
        kind: &ModelKind,
        model: &M,
        reduced: Option<&ReducedModel>,
        damping: &Damping,
        progress: &mut dyn Progress,
    ) -> DynamicRun {
        let plan = self.plan;
        let gyroscopic = plan.gyroscopic_of(kind);
        let mut run = DynamicRun {
            dofs: model.n_dofs(),
            ..DynamicRun::not_run(kind, plan, Stop::Interrupted { time: None })
        };
        let motion = Motion {
            all_loads: self.all_loads,
            active_loads: self.active_loads,
            time_functions: self.time_functions,
            initial: &plan.initial,
            load_names: &plan.load_names,
            end_time: plan.end_time,
            output_times: &plan.output_times,
            integrator: plan.integrator,
            settings: &plan.settings,
            audit: &plan.audit,
        };
        let reduce = reduced.map(|r| move |x: &[f64]| r.reduce_coordinates(x));
        let mut sim = match motion.simulate(model, reduce, gyroscopic, damping, progress) {
            Ok(sim) => sim,
            Err(stop) => {
                run.status = Status::Stopped(*stop);
                return run;
            }
        };
        run.wall_time_s = sim.wall_time_s;
        run.stats = sim.audited.stats;
        run.status = sim.audited.status.clone();
        let mut next_snapshot = self.snapshots.iter().peekable();
        for (index, p) in sim.points(model).into_iter().enumerate() {
            let shape = self.full.shape(&p.q);
            let (tip_x, tip_y, tip_twist) = shape.tip();
            run.samples.push(Sample {
                t: p.t,
                tip_x,
                tip_y,
                tip_twist,
                kinetic: p.kinetic,
                strain: p.strain,
                work: p.work,
                dissipated: p.dissipated,
                balance_error: p.balance_error,
            });
            if next_snapshot.peek() == Some(&&index) {
                next_snapshot.next();
                run.snapshots.push(Snapshot {
                    index,
                    t: p.t,
                    shape,
                });
            }
        }
        run.energy_audit = Some(EnergyAudit::of(&sim.audited.balance));
        run.notes
            .extend(Note::newton(kind, plan.integrator, self.full, &run.stats));
        run
    }
}

/// What one model's dynamic run needs besides the model, whatever its kind (the planar
/// chain's runs and the 3-D chain's, `analysis::chain3d`).
pub(crate) struct Motion<'a> {
    /// Every load (those of a static initial state too).
    pub all_loads: &'a AppliedLoads,
    /// The loads acting during the motion.
    pub active_loads: &'a AppliedLoads,
    /// Their time histories.
    pub time_functions: &'a [TimeFunction],
    /// The state at `t = 0`.
    pub initial: &'a Initial,
    /// The caller's load names, for a failed static initial state.
    pub load_names: &'a [String],
    pub end_time: f64,
    pub output_times: &'a [f64],
    pub integrator: crate::solve::integrate::Method,
    pub settings: &'a crate::solve::integrate::IntegratorSettings,
    pub audit: &'a super::AuditSettings,
}

/// One model's audited integration: its equations (for the energies at the samples), the run
/// and the wall time of the integration alone.
pub(crate) struct Simulated<'a, M: StructuralModel> {
    pub eom: EquationsOfMotion<'a, M>,
    pub audited: AuditedRun,
    pub wall_time_s: f64,
}

/// A run's state at one output time: the full model's coordinates and the energies.
pub(crate) struct Point {
    pub t: f64,
    /// The full model's coordinates (a reduced model's expanded).
    pub q: Vec<f64>,
    pub kinetic: f64,
    pub strain: f64,
    pub work: f64,
    pub dissipated: f64,
    /// The energy balance relative to the energy held or given so far.
    pub balance_error: f64,
}

impl<M: StructuralModel> Simulated<'_, M> {
    /// The run at every output time reached.
    pub fn points(&mut self, model: &M) -> Vec<Point> {
        let n = model.n_dofs();
        let (trajectory, balance) = (&self.audited.trajectory, &self.audited.balance);
        trajectory
            .t
            .iter()
            .zip(&trajectory.y)
            .map(|(&t, y)| {
                let (kinetic, strain) = self.eom.energies(y);
                let (work, dissipated) = (y[2 * n], y[2 * n + 1]);
                Point {
                    t,
                    q: model.full_coordinates(&y[..n]),
                    kinetic,
                    strain,
                    work,
                    dissipated,
                    balance_error: balance.relative(kinetic + strain, work, dissipated),
                }
            })
            .collect()
    }
}

impl<'a> Motion<'a> {
    /// Integrate `model` from its initial state (`reduce` projects a given full state on a
    /// reduced model's coordinates) with the energy audit; the caller's cancellation, polled
    /// after every step, stops the integrator through the equations' halt flag.
    ///
    /// # Errors
    /// The stop of a run that did not get to integrate: its static initial state or its
    /// equations failed.
    pub fn simulate<M: StructuralModel>(
        &self,
        model: &'a M,
        reduce: Option<impl Fn(&[f64]) -> Vec<f64>>,
        gyroscopic: crate::solve::Gyroscopic,
        damping: &Damping,
        progress: &mut dyn Progress,
    ) -> Result<Simulated<'a, M>, Box<Stop>> {
        let (x0, xdot0) = self.initial_state(model, reduce).map_err(|error| {
            let loads = match self.initial {
                Initial::Static { loads } => loads
                    .iter()
                    .map(|&i| crate::analysis::load_name(self.load_names, i))
                    .collect(),
                _ => Vec::new(),
            };
            Box::new(Stop::InitialState { loads, error })
        })?;
        let mut eom = EquationsOfMotion::new(
            model,
            self.active_loads,
            self.time_functions.to_vec(),
            gyroscopic,
            damping,
        )
        .map_err(|e| Box::new(Stop::Equations(e)))?;
        let end = self.end_time;
        let halt = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&halt);
        let mut report = |t: f64| {
            progress.advance((t / end).clamp(0.0, 1.0));
            if progress.cancelled() {
                flag.store(true, Ordering::Relaxed);
            }
        };
        let start = Instant::now();
        let audited = integrate_audited(
            &mut eom,
            &x0,
            &xdot0,
            self.output_times,
            self.integrator,
            self.settings,
            self.audit,
            Some(halt),
            &mut report,
        );
        Ok(Simulated {
            eom,
            audited,
            wall_time_s: start.elapsed().as_secs_f64(),
        })
    }

    /// The model's coordinates and velocities at `t = 0`, or why the static deflection failed.
    fn initial_state<M: StructuralModel>(
        &self,
        model: &M,
        reduce: Option<impl Fn(&[f64]) -> Vec<f64>>,
    ) -> Result<(Vec<f64>, Vec<f64>), SolveError> {
        let n = model.n_dofs();
        match self.initial {
            Initial::Rest => Ok((vec![0.0; n], vec![0.0; n])),
            Initial::Static { loads } => {
                let mut scales = vec![0.0; self.all_loads.n_loads()];
                for &i in loads {
                    scales[i] = 1.0;
                }
                solve_static(model, self.all_loads, &scales, &StaticOptions::default())
                    .map(|s| (s.x, vec![0.0; n]))
            }
            Initial::Given { q, qdot } => Ok(match reduce {
                None => (q.clone(), qdot.clone()),
                Some(r) => (r(q), r(qdot)),
            }),
        }
    }
}
