//! Aeroelastic time responses of the full model and of reduced models on its wet modes: gusts
//! (sharp-edged, 1−cos), changes of speed or root angle, other time-varying loads
//! ([`crate::solve::aeroelastic::AeroelasticEquations`], docs/aeroelastic-model.md §3–5), with
//! any of the integrators ([`crate::solve::integrate::integrate`]) and the outputs of a dynamic
//! run plus the root bending moment and the lift. A run starts from the static aeroelastic
//! equilibrium of the initial flight condition (the loads at their `t = 0` value, gravity), at
//! rest with the lag states in steady state, or undeformed at rest.

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

use nalgebra::DMatrix;

use super::{build, models, Aero, Built, Fields};
use crate::analysis::dynamics::{status_of, DynamicPlan, EnergyAudit, Initial, Snapshot};
use crate::analysis::{ModelKind, Progress, Status, Stop};
use crate::error::{Error, InputError, SolveError};
use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, PlanarStructure};
use crate::model::{AppliedLoads, Load};
use crate::solve::aeroelastic::{AeroelasticEquations, FlightHistory, SteadyAeroModel};
use crate::solve::integrate::{
    integrate, IntegratorSettings, IntegratorStats, Method, NewtonSolver, OdeSystem,
};
use crate::solve::{
    continue_static, Damping, EnergyBalance, Gyroscopic, StaticOptions, TimeFunction,
};

/// Where an aeroelastic response starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AeroStart {
    /// The static aeroelastic equilibrium of the initial flight condition (steady
    /// aerodynamics, the loads at their `t = 0` value, gravity), at rest, lag states steady.
    #[default]
    Equilibrium,
    /// Undeformed, at rest, lag states steady for the undeformed wing.
    Rest,
}

/// An aeroelastic time response. The structural part is a [`DynamicPlan`] (model, loads and
/// their time histories, times, models, integrator, damping, snapshots), checked by its own
/// `validate` under the analysis' names; it must not ask for the simplified model, a
/// gyroscopic term other than the exact one (the aeroelastic equations have it exactly) or an
/// initial state other than [`Initial::Rest`] (the start is [`AeroDynamicPlan::start`]).
#[derive(Debug, Clone)]
pub struct AeroDynamicPlan {
    /// The structural plan.
    pub structure: DynamicPlan,
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// The flight over time: initial speed, root angle and gravity, their changes, a gust.
    pub flight: FlightHistory,
    /// Where the run starts.
    pub start: AeroStart,
    /// Options of the static solver for the initial equilibrium.
    pub static_options: StaticOptions,
}

impl AeroDynamicPlan {
    /// The response of `structure` in `aero` and `flight`, from the equilibrium, default static
    /// options.
    pub fn new(structure: DynamicPlan, aero: Aero, flight: FlightHistory) -> Self {
        Self {
            structure,
            aero,
            flight,
            start: AeroStart::Equilibrium,
            static_options: StaticOptions::default(),
        }
    }

    /// Check the plan under the caller's names.
    ///
    /// # Errors
    /// Those of [`DynamicPlan::validate`]; the simplified model, a gyroscopic term other than
    /// the exact one, a structural initial state; invalid section data, air, aerodynamic model
    /// or flight history over `[0, end_time]`; invalid static options.
    pub fn validate(&self, fields: &Fields) -> Result<(), InputError> {
        let s = &self.structure;
        s.validate(fields.loads, fields.analysis)?;
        if s.simplified {
            return Err(InputError::new(
                fields.analysis("simplified"),
                "the aeroelastic equations keep the exact gyroscopic term: the simplified \
                 model is not available with aerodynamics",
            ));
        }
        if s.gyroscopic != Gyroscopic::Exact {
            return Err(InputError::new(
                fields.analysis("gyroscopic"),
                "the aeroelastic equations use the exact gyroscopic term only",
            ));
        }
        if s.initial != Initial::Rest {
            return Err(InputError::new(
                fields.analysis("initial"),
                "an aeroelastic response starts from the static aeroelastic equilibrium of its \
                 initial flight condition or undeformed at rest, not from a structural \
                 initial state",
            ));
        }
        self.aero.wing(&s.model, fields.aero)?;
        self.flight
            .validate(&fields.flight(), s.model.beam().length(), 0.0, s.end_time)?;
        let rest: Vec<f64> = self
            .aero
            .section
            .surfaces
            .iter()
            .map(|sf| sf.deflection)
            .collect();
        self.flight.validate_deflection_changes(
            &crate::field(fields.aero, "surfaces"),
            &rest,
            0.0,
            s.end_time,
        )?;
        self.static_options.validate(fields.statics)
    }

    /// The models simulated, in order: full (if asked), `reduced`, `reduced_modes`.
    ///
    /// # Errors
    /// As [`AeroDynamicPlan::validate`] for the models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        let s = &self.structure;
        models(s.full, &s.reduced, &s.reduced_modes, s.model.n_dofs(), "")
    }
}

/// The outputs at one output time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AeroSample {
    /// Time (s).
    pub t: f64,
    /// Tip node position (m).
    pub tip_x: f64,
    /// Tip node position (m).
    pub tip_y: f64,
    /// Twist of the tip element (rad, nose-up).
    pub tip_twist: f64,
    /// Root bending moment, the clamp spring's moment `K_θ,1 q_1` (N·m).
    pub root_bending_moment: f64,
    /// Root torque, the clamp's torsion spring moment `K_ψ,1 q_{n+1}` (N·m; 0 without torsion).
    pub root_torque: f64,
    /// Total aerodynamic force along the ground's vertical (N).
    pub lift: f64,
    /// Free-stream speed `U(t)` (m/s).
    pub speed: f64,
    /// Kinetic energy of the structure and the fluid's apparent mass (J).
    pub kinetic: f64,
    /// Strain energy of the springs (J).
    pub strain: f64,
    /// Work of the applied, gravity and aerodynamic loads since `t = 0`,
    /// `W = ∫ ẋ·(Q_other + Q_grav + Q_aero) dt` (J).
    pub work: f64,
    /// Energy dissipated by the structural damping since `t = 0`, `D = ∫ ẋᵀ C ẋ dt` (J).
    pub dissipated: f64,
    /// The energy balance `(H − H(0) − W + D) / E` at this time, relative to the energy the run
    /// has held or been given ([`crate::solve::EnergyBalance`]); positive is energy created.
    pub balance_error: f64,
}

/// The response of one model.
#[derive(Debug, Clone)]
pub struct AeroDynamicRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of structural coordinates of the model.
    pub dofs: usize,
    /// Number of aerodynamic (lag) states.
    pub aero_states: usize,
    /// The integrator used.
    pub integrator: Method,
    /// Integrator counters (up to the stop, if any).
    pub stats: IntegratorStats,
    /// Wall time of the integration (s).
    pub wall_time_s: f64,
    /// One sample per output time reached.
    pub samples: Vec<AeroSample>,
    /// Each control surface's hinge moment (N·m, positive trailing edge down: the deflection,
    /// flap-rate and circulatory terms, as the linear model's `hinge_moment[NAME]` and the
    /// stepper's) at each sample: one row per sample, the surfaces in the order of
    /// `[[aero.surfaces]]`; empty rows without surfaces (and no rows in the gust family's
    /// output-only samples, `Samples::Outputs`, which never report them).
    pub hinge_moments: Vec<Vec<f64>>,
    /// The deformed shape at the plan's snapshot times reached.
    pub snapshots: Vec<Snapshot>,
    /// Whether every output time was reached and the energy balance held, or where and why the
    /// run stopped or is doubtful.
    pub status: Status,
    /// What the energy audit found over the accepted steps (`solve/aeroelastic/audit.rs`);
    /// `None` if the run did not start (its initial state or equations failed).
    pub energy_audit: Option<EnergyAudit>,
    /// Largest distance of the tip from the first model's, over the output times both reached
    /// (m); `None` for the first model.
    pub max_tip_difference: Option<f64>,
}

/// What an aeroelastic response produced.
#[derive(Debug, Clone)]
pub struct AeroDynamicOutcome {
    /// One run per model, in the order of [`AeroDynamicPlan::models`].
    pub runs: Vec<AeroDynamicRun>,
}

impl AeroDynamicOutcome {
    /// Whether every model reached every output time.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
    }

    /// Wall time of `run` over the first model's.
    pub fn ratio_to_first(&self, run: &AeroDynamicRun) -> Option<f64> {
        let first = self.runs.first()?;
        (first.wall_time_s > 0.0).then(|| run.wall_time_s / first.wall_time_s)
    }
}

/// Run the aeroelastic response of `plan`. `progress` hears each model's start and the fraction
/// of its simulated time.
///
/// # Errors
/// An invalid plan (fields named relative to the plan, [`Fields::RELATIVE`]), or the wet modes
/// of a reduced model not found. A model whose run stops is in the outcome with its
/// [`Status`] ([`Stop::InitialState`] when the initial equilibrium is not found).
pub fn run(
    plan: &AeroDynamicPlan,
    progress: &mut dyn Progress,
) -> Result<AeroDynamicOutcome, Error> {
    let prepared = Prepared::new(plan)?;
    Ok(prepared.run(&plan.flight, Samples::All, progress))
}

/// What the output times of a run compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Samples {
    /// Every field of [`AeroSample`].
    All,
    /// The outputs of a gust family ([`super::gust_family::OUTPUTS`]: the tip, the root moments,
    /// the lift); the energies, work, dissipation and balance are NaN and no hinge moments are
    /// taken (not computed: the family reports peaks, and its energy audit is the run's own,
    /// over the accepted steps).
    Outputs,
}

/// A model's coordinates at `t = 0`, or why they were not found.
type InitialCoordinates = Result<Vec<f64>, SolveError>;

/// A validated plan with what every flight flown on it shares: the wing, the applied loads,
/// each model built (the wet modes of a reduced one found) and its initial equilibrium (which
/// depends on the initial flight condition and the loads at `t = 0` only, not on the gust or the
/// changes of the flight). A gust family flies its members on one.
pub(super) struct Prepared<'p> {
    plan: &'p AeroDynamicPlan,
    full: Aeroelastic,
    applied: AppliedLoads,
    time_functions: Vec<TimeFunction>,
    /// Sorted, without repeats.
    snapshots: Vec<usize>,
    /// Per model of [`AeroDynamicPlan::models`]: its kind, the model, its damping and its
    /// coordinates at `t = 0`.
    models: Vec<(ModelKind, Built, Damping, InitialCoordinates)>,
}

impl<'p> Prepared<'p> {
    /// Check `plan` (fields named relative to it, [`Fields::RELATIVE`]), build its models and
    /// their initial states.
    ///
    /// # Errors
    /// An invalid plan, or the wet modes of a reduced model not found.
    pub(super) fn new(plan: &'p AeroDynamicPlan) -> Result<Self, Error> {
        let fields = Fields::RELATIVE;
        plan.validate(&fields)?;
        let s = &plan.structure;
        let full = plan.aero.wing(&s.model, fields.aero)?;
        let active = s.active();
        let active_loads: Vec<Load> = active.iter().map(|&i| s.loads[i].clone()).collect();
        let time_functions: Vec<TimeFunction> =
            active.iter().filter_map(|&i| s.time[i].clone()).collect();
        let applied = full.full().apply(&active_loads, fields.loads)?;
        let mut snapshots = s.snapshots.clone();
        snapshots.sort_unstable();
        snapshots.dedup();
        let mut models = Vec::new();
        for kind in plan.models()? {
            let built = build(&full, &kind)?;
            let (damping, x0) = match &built {
                Built::Full => (
                    s.damping.clone(),
                    initial_coordinates(plan, &active_loads, &time_functions, &full),
                ),
                Built::Reduced(rom) => (
                    rom.structure().project_damping(&s.damping),
                    initial_coordinates(plan, &active_loads, &time_functions, rom.as_ref()),
                ),
            };
            models.push((kind, built, damping, x0));
        }
        Ok(Self {
            plan,
            full,
            applied,
            time_functions,
            snapshots,
            models,
        })
    }

    /// Fly `flight` (the plan's, or one with the same initial condition) on every model:
    /// `progress` hears each model's start and the fraction of its simulated time.
    pub(super) fn run(
        &self,
        flight: &FlightHistory,
        samples: Samples,
        progress: &mut dyn Progress,
    ) -> AeroDynamicOutcome {
        debug_assert_eq!(flight.initial, self.plan.flight.initial);
        let simulator = Simulator {
            plan: self.plan,
            flight,
            samples,
            applied: &self.applied,
            time_functions: &self.time_functions,
            snapshots: &self.snapshots,
        };
        let mut runs = Vec::with_capacity(self.models.len());
        for (k, (kind, built, damping, x0)) in self.models.iter().enumerate() {
            progress.start(k, self.models.len(), &kind.label());
            let run = match built {
                Built::Full => simulator.run(kind, &self.full, damping, x0, progress),
                Built::Reduced(rom) => simulator.run(kind, rom.as_ref(), damping, x0, progress),
            };
            progress.finish();
            runs.push(run);
        }
        compare_with_first(&mut runs);
        AeroDynamicOutcome { runs }
    }
}

/// What every model's simulation shares.
struct Simulator<'a> {
    plan: &'a AeroDynamicPlan,
    flight: &'a FlightHistory,
    samples: Samples,
    applied: &'a AppliedLoads,
    time_functions: &'a [TimeFunction],
    /// Sorted, without repeats.
    snapshots: &'a [usize],
}

impl Simulator<'_> {
    fn run<M: PlanarStructure>(
        &self,
        kind: &ModelKind,
        aero: &Aeroelastic<M>,
        damping: &Damping,
        x0: &InitialCoordinates,
        progress: &mut dyn Progress,
    ) -> AeroDynamicRun {
        let s = &self.plan.structure;
        let n = aero.structure().n_dofs();
        let mut run = AeroDynamicRun {
            kind: kind.clone(),
            dofs: n,
            aero_states: aero.n_aero_states(),
            integrator: s.integrator,
            stats: IntegratorStats::default(),
            wall_time_s: 0.0,
            samples: Vec::new(),
            snapshots: Vec::new(),
            status: Status::Complete,
            energy_audit: None,
            max_tip_difference: None,
            hinge_moments: Vec::new(),
        };
        let x0 = match x0 {
            Ok(x) => x,
            Err(e) => {
                run.status = Status::Stopped(Stop::InitialState {
                    loads: Vec::new(),
                    error: e.clone(),
                });
                return run;
            }
        };
        let equations = AeroelasticEquations::new(
            aero,
            self.applied,
            self.time_functions.to_vec(),
            self.flight.clone(),
            damping,
            "flight",
        );
        let mut system = match equations {
            Ok(eqs) => Scaled(eqs),
            Err(e) => {
                run.status = Status::Stopped(Stop::Equations(e));
                return run;
            }
        };
        let eqs = &mut system.0;
        // The energy audit (as a structural run's, `integrate_audited`): on before the state is
        // built, so that it starts from H(0) and the state carries W and D.
        let floor = eqs.energy_resolution(s.settings.atol);
        let limits = crate::solve::AuditLimits {
            interval: crate::analysis::dynamics::output_interval(&s.output_times),
            ..s.audit.limits(true, &s.settings, floor)
        };
        eqs.set_energy_audit(Some(limits));
        // The caller's cancellation, polled after every step, stops the integrator through the
        // equations' halt flag.
        let halt = Arc::new(AtomicBool::new(false));
        eqs.set_halt(Some(Arc::clone(&halt)));
        let a0 = eqs.steady_states(0.0, x0);
        let y0 = eqs.state(x0, &vec![0.0; n], &a0);
        let end = s.end_time;
        let start = Instant::now();
        let result = integrate(
            s.integrator,
            &s.settings,
            &mut system,
            0.0,
            &y0,
            &s.output_times,
            &mut |t| {
                progress.advance((t / end).clamp(0.0, 1.0));
                if progress.cancelled() {
                    halt.store(true, Ordering::Relaxed);
                }
            },
        );
        run.wall_time_s = start.elapsed().as_secs_f64();
        let (trajectory, error) = match result {
            Ok((trajectory, stats)) => {
                run.stats = stats;
                if let (Some(&t), Some(y)) = (trajectory.t.last(), trajectory.y.last()) {
                    system.0.audit_final(t, y);
                }
                (trajectory, None)
            }
            Err(failure) => {
                run.stats = failure.stats;
                (failure.trajectory, Some(failure.error))
            }
        };
        let mut balance = system
            .0
            .energy_balance()
            .cloned()
            .unwrap_or_else(|| EnergyBalance::start(limits, 0.0));
        balance.finish();
        run.status = status_of(&balance, error, Some(&halt));
        let full = aero.full();
        let eqs = &mut system.0;
        let mut next_snapshot = self.snapshots.iter().peekable();
        for (index, (&t, y)) in trajectory.t.iter().zip(&trajectory.y).enumerate() {
            let q = aero.structure().full_coordinates(&y[..n]);
            let shape = full.shape(&q);
            let (tip_x, tip_y, tip_twist) = shape.tip();
            let lift = eqs.vertical_aerodynamic_force_at(t, y);
            let (kinetic, strain, work, dissipated, balance_error) = match self.samples {
                Samples::All => {
                    run.hinge_moments.push(eqs.hinge_moments_at(t, y));
                    let (kinetic, strain) = eqs.energies(y);
                    let (work, dissipated) = eqs.work_and_dissipation(y).unwrap_or((0.0, 0.0));
                    let error = balance.relative(kinetic + strain, work, dissipated);
                    (kinetic, strain, work, dissipated, error)
                }
                Samples::Outputs => (f64::NAN, f64::NAN, f64::NAN, f64::NAN, f64::NAN),
            };
            run.samples.push(AeroSample {
                t,
                tip_x,
                tip_y,
                tip_twist,
                root_bending_moment: full.stiffness()[0] * q[0],
                root_torque: root_torque(full, &q),
                lift,
                speed: eqs.speed(t),
                kinetic,
                strain,
                work,
                dissipated,
                balance_error,
            });
            if next_snapshot.peek() == Some(&&index) {
                next_snapshot.next();
                run.snapshots.push(Snapshot { index, t, shape });
            }
        }
        run.energy_audit = Some(EnergyAudit::of(&balance));
        run
    }
}

/// The clamp's torsion spring moment `K_ψ,1 q_{n+1}` of the full coordinates `q` (N·m), 0 on a
/// bending-only beam (the root torque of the linear model's `root_torque` output).
pub(crate) fn root_torque(full: &crate::model::FullModel, q: &[f64]) -> f64 {
    let ne = full.n_elements();
    if full.has_torsion() {
        full.stiffness()[ne] * q[ne]
    } else {
        0.0
    }
}

/// The coordinates at `t = 0` of a response of `plan` by `aero`, with the plan's active loads
/// `active_loads` and their time functions: the static equilibrium of the initial flight
/// condition, or zero.
pub(super) fn initial_coordinates<M: AeroStructure>(
    plan: &AeroDynamicPlan,
    active_loads: &[Load],
    time_functions: &[TimeFunction],
    aero: &Aeroelastic<M>,
) -> Result<Vec<f64>, SolveError> {
    let n = aero.structure().n_dofs();
    if plan.start == AeroStart::Rest {
        return Ok(vec![0.0; n]);
    }
    let initial = plan.flight.initial;
    let steady = aero
        .with_aerodynamics(Aerodynamics::Steady, "aero")
        .map_err(SolveError::from_input)?;
    let mut loads = active_loads.to_vec();
    let mut scales: Vec<f64> = time_functions.iter().map(|f| f.at(0.0)).collect();
    if let Some(g) = initial.gravity {
        loads.push(Load::Gravity { g });
        scales.push(initial.root_angle.cos());
    }
    let applied = aero
        .apply(&loads, "loads")
        .map_err(SolveError::from_input)?;
    let model = SteadyAeroModel::new(&steady, initial.root_angle);
    scales.push(0.5 * aero.density() * initial.speed * initial.speed);
    let zero = vec![0.0; scales.len()];
    continue_static(
        &model,
        &applied,
        (&vec![0.0; n], &zero),
        &scales,
        &plan.static_options,
    )
    .map(|s| s.x)
}

/// The aeroelastic equations with absolute tolerances in the units of each state (those of
/// [`AeroelasticEquations::state_atol`]: rad for the coordinates, scaled for the momenta, the
/// speed for the lag states), so that one `atol` fits them all as in a structural run.
pub(super) struct Scaled<'a, M: AeroStructure>(pub(super) AeroelasticEquations<'a, M>);

impl<M: AeroStructure> OdeSystem for Scaled<'_, M> {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.0.rhs(t, y, dy)
    }
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        self.0.jacobian(t, y, jac)
    }
    fn atol_scale(&mut self, scale: &mut [f64]) {
        // `state_atol` is linear in its tolerance: at 1 it gives the scales (infinite for the
        // audit's quadrature states).
        scale.copy_from_slice(&self.0.state_atol(1.0));
    }
    fn step_accepted(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        self.0.step_accepted(t, y)
    }
    fn quadrature_states(&self) -> usize {
        self.0.quadrature_states()
    }
    fn quadrature_step_real(&mut self, c: f64, lead: &[f64], dy: &[f64], q: &mut [f64]) {
        self.0.quadrature_step_real(c, lead, dy, q)
    }
    fn quadrature_step_complex(
        &mut self,
        c: nalgebra::Complex<f64>,
        lead: (&[f64], &[f64]),
        dy: (&[f64], &[f64]),
        q: (&mut [f64], &mut [f64]),
    ) {
        self.0.quadrature_step_complex(c, lead, dy, q)
    }
    // The lag states' elimination (`solve/aeroelastic/schur.rs`): without it the implicit
    // integrators factor the whole `2 n_dofs + lag states` Jacobian densely.
    fn newton_solver(&mut self) -> Option<&mut dyn NewtonSolver> {
        self.0.newton_solver()
    }
    fn integrating_with(&mut self, method: Method, settings: &IntegratorSettings) {
        self.0.integrating_with(method, settings)
    }
    fn keep_quadrature_point(&mut self, slot: usize) {
        self.0.keep_quadrature_point(slot)
    }
    fn quadrature_gradient(&mut self, slot: usize, dy: &[f64], dy_rate: &[f64], out: &mut [f64]) {
        self.0.quadrature_gradient(slot, dy, dy_rate, out)
    }
}

/// Each model's largest tip distance from the first model's, over the times both reached.
fn compare_with_first(runs: &mut [AeroDynamicRun]) {
    let Some((first, others)) = runs.split_first_mut() else {
        return;
    };
    for run in others {
        run.max_tip_difference = Some(
            run.samples
                .iter()
                .zip(&first.samples)
                .map(|(a, b)| (a.tip_x - b.tip_x).hypot(a.tip_y - b.tip_y))
                .fold(0.0, f64::max),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::patil;
    use super::*;
    use crate::analysis::NoProgress;
    use crate::beam::Profile;
    use crate::model::aero::FlightCondition;
    use crate::solve::aeroelastic::{response, Gust, GustPenetration, GustShape, ResponseOptions};

    fn gust() -> FlightHistory {
        FlightHistory {
            deflection_changes: Vec::new(),
            initial: FlightCondition {
                speed: 20.0,
                root_angle: 0.02,
                gravity: Some(9.80665),
            },
            speed_change: None,
            root_angle_change: None,
            gust: Some(Gust {
                shape: GustShape::OneMinusCosine { length: 10.0 },
                amplitude: 1.0,
                start: 0.05,
                spanwise: Profile::Uniform(1.0),
                penetration: GustPenetration::Uniform,
            }),
        }
    }

    fn plan(aerodynamics: Aerodynamics) -> AeroDynamicPlan {
        let (model, aero) = patil(8, aerodynamics);
        let times: Vec<f64> = (0..=20).map(|k| 0.05 * k as f64).collect();
        let mut s = DynamicPlan::new(model, vec![], 1.0, times);
        s.settings.rtol = 1e-8;
        s.settings.atol = 1e-10;
        AeroDynamicPlan::new(s, aero, gust())
    }

    /// With Radau the run is the library's `response` (same equations, same integrator and
    /// tolerances: a regression test of the wrapper, agreement to the integration tolerance);
    /// another integrator agrees to its tolerance (BDF2 at rtol 1e-8: measured 2e-7 m on the
    /// tip, bound 1e-5 m against a tip motion of ~0.3 m).
    #[test]
    fn runs_are_the_library_response_with_any_integrator() {
        let p = plan(Aerodynamics::Wagner);
        let out = run(&p, &mut NoProgress).unwrap();
        assert!(out.is_complete(), "{:?}", out.runs[0].status);
        let mut direct = ResponseOptions::new(gust(), 1.0, 0.05);
        direct.rtol = 1e-8;
        let wing = p.aero.wing(&p.structure.model, "aero").unwrap();
        let reference = response(&wing, &direct, "r", &mut |_| {}).unwrap();
        assert_eq!(reference.samples.len(), out.runs[0].samples.len());
        let length = p.structure.model.beam().length();
        for (a, b) in out.runs[0].samples.iter().zip(&reference.samples) {
            assert!(
                (a.tip_y - b.tip[1]).abs() < 1e-6,
                "{} {}",
                a.tip_y,
                b.tip[1]
            );
            assert!((a.tip_x - length - b.tip[0]).abs() < 1e-6);
            assert!((a.lift - b.lift).abs() < 1e-4 * b.lift.abs().max(1.0));
            assert!((a.root_bending_moment - b.root_bending_moment).abs() < 1e-4 * 100.0);
        }
        let mut bdf = p.clone();
        bdf.structure.integrator = Method::Bdf;
        let other = run(&bdf, &mut NoProgress).unwrap();
        assert!(other.is_complete());
        for (a, b) in other.runs[0].samples.iter().zip(&out.runs[0].samples) {
            assert!((a.tip_y - b.tip_y).abs() < 1e-5, "{} {}", a.tip_y, b.tip_y);
        }
        // The gust lifts the wing: the tip rises above its equilibrium.
        let y0 = out.runs[0].samples[0].tip_y;
        assert!(out.runs[0].samples.iter().any(|s| s.tip_y > y0 + 0.01));
    }

    /// The wrapper that scales the tolerances keeps the equations' own Newton solver (the lag
    /// states eliminated strip by strip, `schur.rs`): a wrapper without it made the CLI's and
    /// Python's gust runs factor the whole Jacobian densely (n = 16, Peters 6: 160 × 160 against
    /// 32 × 32; the gust family of examples/patil_gust_family.toml ran 80 % in dense LUs).
    /// Without lag states there is nothing to eliminate and the dense path is the one.
    #[test]
    fn the_scaled_equations_eliminate_the_lag_states() {
        for (aerodynamics, eliminated) in [
            (Aerodynamics::Wagner, true),
            (Aerodynamics::Peters { states: 4 }, true),
            (Aerodynamics::QuasiSteady, false),
        ] {
            let p = plan(aerodynamics);
            let wing = p.aero.wing(&p.structure.model, "aero").unwrap();
            let loads = AppliedLoads::none();
            let eqs =
                AeroelasticEquations::new(&wing, &loads, vec![], gust(), &Damping::None, "flight")
                    .unwrap();
            let mut scaled = Scaled(eqs);
            assert_eq!(
                scaled.newton_solver().is_some(),
                eliminated,
                "{aerodynamics:?}"
            );
        }
    }

    /// Starting at rest (undeformed) in steady flight without gust: the wing rises towards the
    /// equilibrium the `Equilibrium` start begins at.
    #[test]
    fn rest_start_and_errors() {
        let mut p = plan(Aerodynamics::Peters { states: 4 });
        p.flight.gust = None;
        p.start = AeroStart::Rest;
        p.structure.reduced = vec![4];
        let out = run(&p, &mut NoProgress).unwrap();
        assert!(out.is_complete());
        assert_eq!(out.runs[0].samples[0].tip_y, 0.0);
        assert_eq!(out.runs[0].aero_states, 32);
        assert!(out.runs[1].max_tip_difference.unwrap() < 0.05);
        let fields = Fields {
            loads: "loads",
            aero: "aero",
            statics: "static",
            analysis: "dynamic",
        };
        type Change = Box<dyn Fn(&mut AeroDynamicPlan)>;
        let cases: Vec<(Change, &str)> = vec![
            (
                Box::new(|p| p.structure.simplified = true),
                "dynamic.simplified:",
            ),
            (
                Box::new(|p| p.structure.gyroscopic = Gyroscopic::Neglected),
                "dynamic.gyroscopic:",
            ),
            (
                Box::new(|p| {
                    p.structure.initial = Initial::Given {
                        q: vec![0.0; 16],
                        qdot: vec![0.0; 16],
                    }
                }),
                "dynamic.initial:",
            ),
            (
                Box::new(|p| p.structure.end_time = -1.0),
                "dynamic.end_time:",
            ),
            (Box::new(|p| p.aero.density = f64::NAN), "aero.density:"),
            (
                Box::new(|p| {
                    p.flight.gust = Some(Gust {
                        shape: GustShape::OneMinusCosine { length: -1.0 },
                        amplitude: 1.0,
                        start: 0.0,
                        spanwise: Profile::Uniform(1.0),
                        penetration: GustPenetration::Uniform,
                    })
                }),
                "aero.flight.gust.length:",
            ),
            (
                Box::new(|p| p.flight.speed_change = Some((-50.0, TimeFunction::Constant))),
                "aero.flight.speed_change:",
            ),
            (
                Box::new(|p| p.static_options.tolerance = 0.0),
                "static.tolerance:",
            ),
        ];
        for (change, expected) in cases {
            let mut p = plan(Aerodynamics::Wagner);
            change(&mut p);
            let msg = p.validate(&fields).unwrap_err().to_string();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }
}
