//! Non-linear dynamics of the 3-D chain ([`crate::model::Chain3d`], docs/chain3d-model.md §5):
//! the planar dynamic run's models (full, simplified, reduced on the undeformed modes), loads
//! with time histories, initial states, integrators and energy audit, through the same audited
//! integration ([`super::run::Motion`]); what a run records is the 3-D chain's: the tip
//! `(x, y, z)` and the tip element's section rotation at every output time, and the node
//! positions and section rotations at the snapshot times.

use super::run::Motion;
use super::{
    active, check_something_to_simulate, gyroscopic_name, gyroscopic_of, model_kinds,
    reduced_models, AuditSettings, EnergyAudit, Initial, MotionChecks,
};
use crate::analysis::chain3d::Shape3dData;
use crate::analysis::models::{modes_needed, ModelKind};
use crate::analysis::{Note, Progress, Status, Stop};
use crate::error::{Error, InputError};
use crate::model::chain3d::{Chain3d, ReducedChain3d, SpatialLoad};
use crate::model::{AppliedLoads, StructuralModel};
use crate::solve::integrate::{IntegratorSettings, IntegratorStats, Method};
use crate::solve::{Damping, Gyroscopic, Modes, TimeFunction};

/// A dynamic run of the 3-D chain: the fields of the planar [`super::DynamicPlan`] with the
/// 3-D chain's loads. Build it with [`Dynamic3d::new`], set the fields, and check it with
/// [`Dynamic3d::validate`].
#[derive(Debug, Clone)]
pub struct Dynamic3d {
    /// Every load: those acting during the motion and those that only set the initial state.
    pub loads: Vec<SpatialLoad>,
    /// The time history of each load during the motion (`None`: not acting during it).
    pub time: Vec<Option<TimeFunction>>,
    /// End of the simulated time (s).
    pub end_time: f64,
    /// Output times (s), strictly increasing, within `[0, end_time]`.
    pub output_times: Vec<f64>,
    /// Simulate the full chain. Default `true`.
    pub full: bool,
    /// Simulate the full chain with the gyroscopic term neglected. Default `false`.
    pub simplified: bool,
    /// Reduced models on the first `r` undeformed modes, one per entry
    /// ([`ReducedChain3d`]).
    pub reduced: Vec<usize>,
    /// Reduced models on listed modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// How the gyroscopic term of the full and reduced models is obtained.
    pub gyroscopic: Gyroscopic,
    /// The time integrator of every model.
    pub integrator: Method,
    /// Its tolerances and options.
    pub settings: IntegratorSettings,
    /// Structural damping; reduced models get its projection.
    pub damping: Damping,
    /// The state at `t = 0` (`Given`: the full chain's `3n` joint rotations and rates).
    pub initial: Initial,
    /// Indices of the output times at which each model's shape is recorded.
    pub snapshots: Vec<usize>,
    /// The energy audit of every run.
    pub audit: AuditSettings,
    /// How the caller names each load.
    pub load_names: Vec<String>,
}

impl Dynamic3d {
    /// The full chain from rest under `loads`, each constant in time, over `[0, end_time]`
    /// with the given output times and the default integrator.
    pub fn new(loads: Vec<SpatialLoad>, end_time: f64, output_times: Vec<f64>) -> Self {
        Self {
            time: vec![Some(TimeFunction::Constant); loads.len()],
            loads,
            end_time,
            output_times,
            full: true,
            simplified: false,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            gyroscopic: Gyroscopic::Exact,
            integrator: Method::default(),
            settings: IntegratorSettings::default(),
            damping: Damping::None,
            initial: Initial::Rest,
            snapshots: Vec::new(),
            audit: AuditSettings::default(),
            load_names: Vec::new(),
        }
    }

    /// Check the run on `model`; errors name the loads `{loads_field}[i]…` and everything else
    /// `{prefix}.…`, as [`super::DynamicPlan::validate`]'s.
    ///
    /// # Errors
    /// Those of [`super::DynamicPlan::validate`], for the 3-D chain's loads and coordinates.
    pub fn validate(
        &self,
        model: &Chain3d,
        loads_field: &str,
        prefix: &str,
    ) -> Result<(), InputError> {
        let checks = MotionChecks {
            end_time: self.end_time,
            output_times: &self.output_times,
            settings: &self.settings,
            audit: &self.audit,
            gyroscopic: self.gyroscopic,
            time: &self.time,
            n_loads: self.loads.len(),
            damping: &self.damping,
            initial: &self.initial,
            n_dofs: model.n_dofs(),
        };
        checks.times(prefix)?;
        let reduced = reduced_models(&self.reduced, &self.reduced_modes, model.n_dofs(), prefix)?;
        check_something_to_simulate(self.full, self.simplified, reduced.is_empty(), prefix)?;
        model.apply(&self.loads, loads_field)?;
        checks.histories(loads_field)?;
        checks.state(prefix)
    }
}

/// The chain at one output time.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Snapshot3d {
    /// Index of the output time.
    pub index: usize,
    /// Time (s).
    pub t: f64,
    /// Node positions and section rotations.
    pub shape: Shape3dData,
}

/// The simulation of one model of the 3-D chain: its histories as columns, one value per output
/// time reached.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Dynamic3dRun {
    /// `full`, `simplified`, `reduced-r2`, `reduced-modes-1-2-4`.
    pub label: String,
    /// `full`, `simplified` or `reduced`.
    pub kind: &'static str,
    /// The retained modes of a reduced model (1-based).
    pub modes: Option<Vec<usize>>,
    /// Number of coordinates.
    pub dofs: usize,
    /// The integrator.
    pub integrator: Method,
    /// `exact`, `finite-difference` or `neglected`.
    pub gyroscopic: &'static str,
    /// Integrator counters.
    pub stats: IntegratorStats,
    /// Wall time of the integration (s).
    pub wall_time_s: f64,
    /// Output times reached (s).
    pub t: Vec<f64>,
    /// Tip position `x` (m).
    pub tip_x: Vec<f64>,
    /// Tip position `y` (m).
    pub tip_y: Vec<f64>,
    /// Tip position `z` (m).
    pub tip_z: Vec<f64>,
    /// The tip element's section rotation vector (rad, global components).
    pub tip_rotation: Vec<[f64; 3]>,
    /// Kinetic energy (J).
    pub kinetic: Vec<f64>,
    /// Strain energy (J).
    pub strain: Vec<f64>,
    /// Kinetic plus strain energy (J).
    pub total: Vec<f64>,
    /// Work of the applied loads since `t = 0` (J).
    pub work: Vec<f64>,
    /// Energy dissipated by the damping since `t = 0` (J).
    pub dissipated: Vec<f64>,
    /// The energy balance `(H − H(0) − W + D) / E` (as the planar run's).
    pub balance_error: Vec<f64>,
    /// The shapes at the plan's snapshot times reached.
    pub snapshots: Vec<Snapshot3d>,
    /// How the run ended.
    pub status: Status,
    /// What the energy audit found (`None`: the run did not start).
    pub energy_audit: Option<EnergyAudit>,
    /// `max_t |tip − tip_first|` (m) over the output times both reached (not for the first
    /// model).
    pub max_tip_difference: Option<f64>,
    /// Notes.
    pub notes: Vec<Note>,
}

/// What a dynamic run of the 3-D chain produced.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Dynamic3dOutcome {
    /// End of the simulated time (s).
    pub end_time: f64,
    /// One run per model: full, simplified, then the reduced models.
    pub runs: Vec<Dynamic3dRun>,
}

impl Dynamic3dRun {
    fn new(kind: &ModelKind, plan: &Dynamic3d, dofs: usize, status: Status) -> Self {
        Self {
            label: kind.label(),
            kind: match kind {
                ModelKind::Full => "full",
                ModelKind::Simplified => "simplified",
                ModelKind::Reduced(_) => "reduced",
            },
            modes: kind.modes(),
            dofs,
            integrator: plan.integrator,
            gyroscopic: gyroscopic_name(gyroscopic_of(plan.gyroscopic, kind)),
            stats: IntegratorStats::default(),
            wall_time_s: 0.0,
            t: Vec::new(),
            tip_x: Vec::new(),
            tip_y: Vec::new(),
            tip_z: Vec::new(),
            tip_rotation: Vec::new(),
            kinetic: Vec::new(),
            strain: Vec::new(),
            total: Vec::new(),
            work: Vec::new(),
            dissipated: Vec::new(),
            balance_error: Vec::new(),
            snapshots: Vec::new(),
            status,
            energy_audit: None,
            max_tip_difference: None,
            notes: Vec::new(),
        }
    }

    /// The tip position at output `k`.
    pub fn tip(&self, k: usize) -> [f64; 3] {
        [self.tip_x[k], self.tip_y[k], self.tip_z[k]]
    }
}

/// Run `plan` on `model` (checked by the caller).
pub(crate) fn run(
    model: &Chain3d,
    plan: &Dynamic3d,
    progress: &mut dyn Progress,
) -> Result<Dynamic3dOutcome, Error> {
    let all_loads = model.apply(&plan.loads, "loads")?;
    let active = active(&plan.time);
    let active_list: Vec<SpatialLoad> = active.iter().map(|&i| plan.loads[i].clone()).collect();
    let active_loads = model.apply(&active_list, "loads")?;
    let time_functions: Vec<TimeFunction> = active
        .iter()
        .filter_map(|&i| plan.time[i].clone())
        .collect();
    let kinds = model_kinds(
        plan.full,
        plan.simplified,
        &plan.reduced,
        &plan.reduced_modes,
        model.n_dofs(),
    )?;
    let x0 = vec![0.0; model.n_dofs()];
    let modes = modes_needed(&kinds)
        .map(|count| Modes::of_model(model, &x0, &AppliedLoads::none(), &[], count))
        .transpose()?;
    let mut snapshots = plan.snapshots.clone();
    snapshots.sort_unstable();
    snapshots.dedup();
    let motion = Motion {
        all_loads: &all_loads,
        active_loads: &active_loads,
        time_functions: &time_functions,
        initial: &plan.initial,
        load_names: &plan.load_names,
        end_time: plan.end_time,
        output_times: &plan.output_times,
        integrator: plan.integrator,
        settings: &plan.settings,
        audit: &plan.audit,
    };
    let mut runs = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        if progress.cancelled() {
            let stop = Status::Stopped(Stop::Interrupted { time: None });
            runs.push(Dynamic3dRun::new(kind, plan, 0, stop));
            continue;
        }
        progress.start(k, kinds.len(), &kind.label());
        let run = match (kind.mode_indices(), &modes) {
            (Some(indices), Some(modes)) => {
                let rom = ReducedChain3d::new(model, modes.shapes(), &indices)?;
                let damping = rom.project_damping(&plan.damping);
                let reduce = Some(|x: &[f64]| rom.reduce_coordinates(x));
                simulate(
                    model, &rom, reduce, &damping, kind, plan, &motion, &snapshots, progress,
                )
            }
            _ => {
                let reduce = None::<fn(&[f64]) -> Vec<f64>>;
                let damping = &plan.damping;
                simulate(
                    model, model, reduce, damping, kind, plan, &motion, &snapshots, progress,
                )
            }
        };
        progress.finish();
        runs.push(run);
    }
    if let Some((first, others)) = runs.split_first_mut() {
        for run in others {
            let common = run.t.len().min(first.t.len());
            run.max_tip_difference = (common > 0).then(|| {
                (0..common)
                    .map(|k| {
                        let (a, b) = (run.tip(k), first.tip(k));
                        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2))
                            .sqrt()
                    })
                    .fold(0.0, f64::max)
            });
        }
    }
    Ok(Dynamic3dOutcome {
        end_time: plan.end_time,
        runs,
    })
}

/// Simulate `model` (the chain itself or a reduced model of `chain`) and sample it.
#[allow(clippy::too_many_arguments)]
fn simulate<M: StructuralModel>(
    chain: &Chain3d,
    model: &M,
    reduce: Option<impl Fn(&[f64]) -> Vec<f64>>,
    damping: &Damping,
    kind: &ModelKind,
    plan: &Dynamic3d,
    motion: &Motion<'_>,
    snapshots: &[usize],
    progress: &mut dyn Progress,
) -> Dynamic3dRun {
    let interrupted = Status::Stopped(Stop::Interrupted { time: None });
    let mut run = Dynamic3dRun::new(kind, plan, model.n_dofs(), interrupted);
    let gyroscopic = gyroscopic_of(plan.gyroscopic, kind);
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
    let mut next_snapshot = snapshots.iter().peekable();
    for (index, p) in sim.points(model).into_iter().enumerate() {
        let shape = Shape3dData::of(chain, &p.q);
        let tip = shape.tip();
        run.t.push(p.t);
        run.tip_x.push(tip[0]);
        run.tip_y.push(tip[1]);
        run.tip_z.push(tip[2]);
        run.tip_rotation
            .push(shape.rotation.last().copied().unwrap_or([0.0; 3]));
        run.kinetic.push(p.kinetic);
        run.strain.push(p.strain);
        run.total.push(p.kinetic + p.strain);
        run.work.push(p.work);
        run.dissipated.push(p.dissipated);
        run.balance_error.push(p.balance_error);
        if next_snapshot.peek() == Some(&&index) {
            next_snapshot.next();
            run.snapshots.push(Snapshot3d {
                index,
                t: p.t,
                shape,
            });
        }
    }
    run.energy_audit = Some(EnergyAudit::of(&sim.audited.balance));
    run
}
