//! Running a dynamic plan: build each model (reduced models on the undeformed modes, with the
//! projected damping), find its initial state, integrate it, and sample the tip, the energies
//! and the snapshots at the output times.

use std::time::Instant;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use super::audit::{integrate_audited, EnergyAudit};
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
        let (x0, xdot0) = match self.initial_state(model, reduced) {
            Ok(s) => s,
            Err(e) => {
                let loads = match &plan.initial {
                    Initial::Static { loads } => loads.iter().map(|&i| plan.load_name(i)).collect(),
                    _ => Vec::new(),
                };
                run.status = Status::Stopped(Stop::InitialState { loads, error: e });
                return run;
            }
        };
        let equations = EquationsOfMotion::new(
            model,
            self.active_loads,
            self.time_functions.to_vec(),
            gyroscopic,
            damping,
        );
        let mut eom = match equations {
            Ok(eom) => eom,
            Err(e) => {
                run.status = Status::Stopped(Stop::Equations(e));
                return run;
            }
        };
        let end = plan.end_time;
        // The caller's cancellation, polled after every step, stops the integrator through the
        // equations' halt flag.
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
            &plan.output_times,
            plan.integrator,
            &plan.settings,
            &plan.audit,
            Some(halt),
            &mut report,
        );
        run.wall_time_s = start.elapsed().as_secs_f64();
        run.stats = audited.stats;
        run.status = audited.status;
        let trajectory = audited.trajectory;
        let n = model.n_dofs();
        let balance = audited.balance;
        let mut next_snapshot = self.snapshots.iter().peekable();
        for (index, (&t, y)) in trajectory.t.iter().zip(&trajectory.y).enumerate() {
            let q = model.full_coordinates(&y[..n]);
            let (kinetic, strain) = eom.energies(y);
            let (work, dissipated) = (y[2 * n], y[2 * n + 1]);
            let shape = self.full.shape(&q);
            let (tip_x, tip_y, tip_twist) = shape.tip();
            run.samples.push(Sample {
                t,
                tip_x,
                tip_y,
                tip_twist,
                kinetic,
                strain,
                work,
                dissipated,
                balance_error: balance.relative(kinetic + strain, work, dissipated),
            });
            if next_snapshot.peek() == Some(&&index) {
                next_snapshot.next();
                run.snapshots.push(Snapshot { index, t, shape });
            }
        }
        run.energy_audit = Some(EnergyAudit::of(&balance));
        run.notes
            .extend(Note::newton(kind, plan.integrator, self.full, &run.stats));
        run
    }

    /// The model's coordinates and velocities at `t = 0`, or why the static deflection failed.
    fn initial_state<M: StructuralModel>(
        &self,
        model: &M,
        reduced: Option<&ReducedModel>,
    ) -> Result<(Vec<f64>, Vec<f64>), SolveError> {
        let n = model.n_dofs();
        match &self.plan.initial {
            Initial::Rest => Ok((vec![0.0; n], vec![0.0; n])),
            Initial::Static { loads } => {
                let mut scales = vec![0.0; self.all_loads.n_loads()];
                for &i in loads {
                    scales[i] = 1.0;
                }
                solve_static(model, self.all_loads, &scales, &StaticOptions::default())
                    .map(|s| (s.x, vec![0.0; n]))
            }
            Initial::Given { q, qdot } => Ok(match reduced {
                None => (q.clone(), qdot.clone()),
                Some(r) => (r.reduce_coordinates(q), r.reduce_coordinates(qdot)),
            }),
        }
    }
}
