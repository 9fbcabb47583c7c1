//! A plant in the loop (issue 21 §3): the aeroelastic response of an
//! [`AeroDynamicPlan`] advanced one communication interval per call, with named inputs set
//! between calls (root angle, speed, a uniform vertical gust, forces and torques at nodes) and
//! named outputs read after each (positions and twists, root bending moment and torque, lift):
//! the core that the Python `AeroStepper` and the co-simulation FMU (`crates/flexwing-fmu`)
//! share. The equations, integrators, energy audit and statuses are those of `flexwing dynamic`
//! (`response.rs`): the run starts where a response of the plan starts, the case's own flight
//! history and loads act as in the response, and the inputs are added to them: an input's change
//! from its start value (the initial root angle and speed; zero for the others) is added to the
//! case's root angle, speed, gust, or is a dead force or torque at its node.
//!
//! The signals are those of the linear model ([`Input`], [`Output`], `signals.rs`), one name per
//! concept; a new input (a control surface's deflection) is one arm in [`AeroStepper::step`]'s
//! offsets and one in [`check_input`].
//!
//! Each call restarts the integrator at the current state (its first step is chosen anew): a run
//! stepped in intervals agrees with the response of the same plan to the integration tolerance.
//! The energy audit runs across the calls (one balance from the start); a call that fails leaves
//! the stepper as before it (time, state, inputs, balance).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;
use std::time::Instant;

use self_cell::self_cell;

use super::response::{initial_coordinates, AeroDynamicPlan, Scaled};
use super::{build, Built, Fields};
use crate::analysis::dynamics::{status_of, EnergyAudit};
use crate::analysis::{ModelKind, Status, Stop};
use crate::error::{Error, InputError, SolveError};
use crate::model::aero::{AeroStructure, Aeroelastic, PlanarStructure};
use crate::model::{AppliedLoads, Force, FullModel, Load, ReducedModel};
use crate::solve::aeroelastic::flight::{FlightOffsets, Segment};
use crate::solve::aeroelastic::{AeroelasticEquations, Input, Output};
use crate::solve::integrate::{integrate, IntegratorSettings, IntegratorStats, Method};
use crate::solve::{AuditLimits, EnergyBalance, TimeFunction};
use crate::text::short;

/// How an input goes over a communication interval.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Hold {
    /// Linear from the value in force at the start of the interval to the value set for it,
    /// reached at its end (first-order hold: the inputs stay continuous in time).
    #[default]
    Linear,
    /// The value set, from the start of the interval (zero-order hold: a sampled controller's
    /// output, and FMI's co-simulation without input derivatives).
    Zero,
}

impl Hold {
    /// `linear` or `zero`.
    pub fn name(self) -> &'static str {
        match self {
            Hold::Linear => "linear",
            Hold::Zero => "zero",
        }
    }

    /// The hold called `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        [Hold::Linear, Hold::Zero]
            .into_iter()
            .find(|h| h.name() == name)
    }
}

/// What a stepper steps: which model of the plan, its inputs and outputs, the hold.
#[derive(Debug, Clone, PartialEq)]
pub struct StepperOptions {
    /// Index of the model among the plan's ([`AeroDynamicPlan::models`]: the full model first if
    /// the plan runs it, then the reduced ones).
    pub model: usize,
    /// The inputs, in order.
    pub inputs: Vec<Input>,
    /// The outputs, in order.
    pub outputs: Vec<Output>,
    /// How the inputs go over an interval.
    pub hold: Hold,
}

/// The inputs a stepper has unless told: `root_angle`, `speed`, `gust`.
pub const DEFAULT_INPUTS: &[Input] = &[Input::RootAngle, Input::Speed, Input::Gust];

impl StepperOptions {
    /// The first model, the default inputs and outputs ([`StepperOptions::default_outputs`]),
    /// linear hold.
    pub fn new(torsion: bool) -> Self {
        Self {
            model: 0,
            inputs: DEFAULT_INPUTS.to_vec(),
            outputs: Self::default_outputs(torsion),
            hold: Hold::Linear,
        }
    }

    /// `tip_x`, `tip_y`, `tip_twist`, `root_bending_moment`, `root_torque`, `lift` (the twist and
    /// torque only with torsion).
    pub fn default_outputs(torsion: bool) -> Vec<Output> {
        let mut v = vec![Output::TipX, Output::TipY];
        if torsion {
            v.push(Output::TipTwist);
        }
        v.push(Output::RootBendingMoment);
        if torsion {
            v.push(Output::RootTorque);
        }
        v.push(Output::Lift);
        v
    }
}

/// Every input a stepper takes, for messages.
pub const STEPPER_INPUT_NAMES: &str =
    "root_angle, speed, gust, force[k] and torque[k] (node k), delta[NAME] (surface NAME)";
/// Every output a stepper gives, for messages.
pub const STEPPER_OUTPUT_NAMES: &str = "tip_x, tip_y, tip_twist, x[k], y[k], twist[k] (node k), \
                                        root_bending_moment, root_torque, lift, \
                                        hinge_moment[NAME] (surface NAME)";

/// Whether a stepper takes `input` (a linear model's input): the per-strip gusts are not yet,
/// and the gust's rate is its hold's (the gust's apparent mass follows the `gust` input).
///
/// # Errors
/// The reason, naming the inputs it takes.
pub fn check_input(input: &Input) -> Result<(), String> {
    match input {
        Input::RootAngle
        | Input::Speed
        | Input::Gust
        | Input::Force(_)
        | Input::Torque(_)
        | Input::Deflection(_) => Ok(()),
        Input::DeflectionRate(_) | Input::DeflectionAcceleration(_) => Err(format!(
            "{} is an input of the linear model only: a stepper takes a surface's rate from \
             its hold of delta (the slope over the interval, zero when held); it takes \
             {STEPPER_INPUT_NAMES}",
            input.name()
        )),
        Input::StripGust(_) => Err(format!(
            "{} is an input of the linear model only; a stepper takes {STEPPER_INPUT_NAMES}",
            input.name()
        )),
        Input::GustRate => Err(format!(
            "gust_rate is an input of the linear model only: a stepper takes the gust's rate \
             from its hold of gust (the slope over the interval, zero when held); it takes \
             {STEPPER_INPUT_NAMES}"
        )),
    }
}

/// Whether a stepper gives `output`: the root shear and the accelerations (which need the
/// state's rate) are outputs of the linear model only.
///
/// # Errors
/// The reason, naming the outputs it gives.
pub fn check_output(output: &Output) -> Result<(), String> {
    match output {
        Output::RootShear | Output::TipAcceleration | Output::Acceleration(_) => Err(format!(
            "{} is an output of the linear model only; a stepper gives {STEPPER_OUTPUT_NAMES}",
            output.name()
        )),
        _ if output.is_spatial() => Err(format!(
            "{} is an output of the 3-D chain's linear model; a stepper gives \
             {STEPPER_OUTPUT_NAMES}",
            output.name()
        )),
        _ => Ok(()),
    }
}

/// Why a call of [`AeroStepper::step`] or [`AeroStepper::set_input`] did nothing.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StepError {
    /// An invalid argument (an interval, an input value).
    #[error(transparent)]
    Input(#[from] InputError),
    /// The integration stopped inside the interval (the stepper is as before the call).
    #[error("{0}")]
    Stopped(Box<Stop>),
}

/// The wing the equations borrow, and the loads (the plan's active ones, then one unit load per
/// force or torque input).
struct Owner {
    wing: Wing,
    loads: AppliedLoads,
}

/// Built once per stepper: the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
enum Wing {
    Full(Aeroelastic<FullModel>),
    Reduced(Box<Aeroelastic<ReducedModel>>),
}

/// Built once per stepper: the variants' sizes do not matter.
#[allow(clippy::large_enum_variant)]
enum Eqs<'a> {
    Full(Scaled<'a, FullModel>),
    Reduced(Scaled<'a, ReducedModel>),
}

self_cell!(
    struct Cell {
        owner: Owner,
        #[not_covariant]
        dependent: Eqs,
    }
);

/// `$body` with `$e` the equations (`Scaled`) of whichever model.
macro_rules! with_eqs {
    ($cell:expr, |$e:ident| $body:expr) => {
        $cell.with_dependent_mut(|_, dependent| match dependent {
            Eqs::Full($e) => $body,
            Eqs::Reduced($e) => $body,
        })
    };
}

/// A constant table: `value` at every time.
fn held(value: f64) -> TimeFunction {
    TimeFunction::Table {
        t: vec![0.0, 1.0],
        value: vec![value, value],
    }
}

/// An aeroelastic response advanced one interval per call (module documentation). Owns its
/// model and equations (built once: a call allocates only its outputs and the integrator's
/// trajectory).
pub struct AeroStepper {
    cell: Cell,
    kind: ModelKind,
    dofs: usize,
    aero_states: usize,
    method: Method,
    settings: IntegratorSettings,
    limits: AuditLimits,
    hold: Hold,
    inputs: Vec<Input>,
    outputs: Vec<Output>,
    /// The plan's active loads' time functions.
    case_functions: Vec<TimeFunction>,
    /// Input indices of the load inputs, in the order of their loads after the plan's.
    load_inputs: Vec<usize>,
    /// Each input's value at the start.
    start: Vec<f64>,
    /// Each input's value in force at `t` (reached at the end of the last interval).
    values: Vec<f64>,
    /// Each input's value set for the next interval.
    pending: Vec<f64>,
    /// The flight offsets of the last interval stepped (zero before the first): with the
    /// first-order hold, the outputs at its end see the gust's rate over it (its apparent mass).
    last_offsets: FlightOffsets,
    t: f64,
    y: Vec<f64>,
    stats: IntegratorStats,
    stop: Option<Stop>,
    halt: Arc<AtomicBool>,
    calls: usize,
    integration_time_s: f64,
}

impl AeroStepper {
    /// A stepper of `plan` (validated as a dynamic run of it; fields relative to the plan,
    /// [`Fields::RELATIVE`]), with `options` (errors name `inputs[i]`, `outputs[i]`, `model`).
    /// The plan's end time, output times and snapshots are not used: the caller steps as long as
    /// it likes.
    ///
    /// # Errors
    /// An invalid plan, input, output or model index; the wet modes of a reduced model not
    /// found; no initial equilibrium (a solve error).
    pub fn new(plan: &AeroDynamicPlan, options: &StepperOptions) -> Result<Self, Error> {
        let fields = Fields::RELATIVE;
        plan.validate(&fields)?;
        for (i, input) in options.inputs.iter().enumerate() {
            check_input(input).map_err(|r| InputError::new(format!("inputs[{i}]"), r))?;
            if options.inputs[..i].contains(input) {
                return Err(InputError::new(
                    format!("inputs[{i}]"),
                    format!("{} is given twice", input.name()),
                )
                .into());
            }
        }
        for (i, output) in options.outputs.iter().enumerate() {
            check_output(output).map_err(|r| InputError::new(format!("outputs[{i}]"), r))?;
        }
        let s = &plan.structure;
        let full = plan.aero.wing(&s.model, fields.aero)?;
        let ne = full.full().n_elements();
        let torsion = full.full().has_torsion();
        let surfaces = full.surfaces();
        // The signals' own checks (indices, torsion, surfaces), as their names parse.
        for (i, input) in options.inputs.iter().enumerate() {
            Input::parse(
                &input.name(),
                ne,
                torsion,
                surfaces,
                &format!("inputs[{i}]"),
            )?;
        }
        for (i, output) in options.outputs.iter().enumerate() {
            Output::parse(
                &output.name(),
                ne,
                torsion,
                surfaces,
                &format!("outputs[{i}]"),
            )?;
        }
        let kinds = plan.models()?;
        let kind = kinds.get(options.model).cloned().ok_or_else(|| {
            InputError::new(
                "model",
                format!(
                    "is {} but the plan has {} model(s) (0 is the first)",
                    options.model,
                    kinds.len()
                ),
            )
        })?;
        let active = s.active();
        let mut loads: Vec<Load> = active.iter().map(|&i| s.loads[i].clone()).collect();
        let case_functions: Vec<TimeFunction> =
            active.iter().filter_map(|&i| s.time[i].clone()).collect();
        let n_case = loads.len();
        let nodes = full.full().beam().nodes().to_vec();
        let mut load_inputs = Vec::new();
        for (i, input) in options.inputs.iter().enumerate() {
            let load = match input {
                Input::Force(k) => Load::PointForce {
                    span: nodes[*k],
                    force: Force::Dead { fx: 0.0, fy: 1.0 },
                },
                Input::Torque(k) => Load::Torque {
                    span: nodes[*k],
                    value: 1.0,
                },
                _ => continue,
            };
            loads.push(load);
            load_inputs.push(i);
        }
        let no_equilibrium = |e: SolveError| {
            InputError::new(
                "flight",
                format!("no static equilibrium in the initial flight condition: {e}"),
            )
        };
        let case_loads = &loads[..n_case];
        // The surfaces' deflections at the start (the equilibrium's and the history's).
        let mut deflections0 = full.rest_deflections();
        plan.flight.add_deflection_changes(0.0, &mut deflections0);
        let (wing, x0, damping, applied) = match build(&full, &kind)? {
            Built::Full => {
                let x0 = initial_coordinates(plan, case_loads, &case_functions, &full)
                    .map_err(no_equilibrium)?;
                let applied = full.apply(&loads, fields.loads)?;
                (Wing::Full(full), x0, s.damping.clone(), applied)
            }
            Built::Reduced(rom) => {
                let x0 = initial_coordinates(plan, case_loads, &case_functions, rom.as_ref())
                    .map_err(no_equilibrium)?;
                let damping = rom.structure().project_damping(&s.damping);
                let applied = rom.apply(&loads, fields.loads)?;
                (Wing::Reduced(rom), x0, damping, applied)
            }
        };
        let mut functions = case_functions.clone();
        functions.extend(load_inputs.iter().map(|_| held(0.0)));
        let flight = plan.flight.clone();
        let owner = Owner {
            wing,
            loads: applied,
        };
        let mut cell = Cell::try_new(owner, |o| -> Result<Eqs<'_>, InputError> {
            Ok(match &o.wing {
                Wing::Full(w) => Eqs::Full(Scaled(AeroelasticEquations::new(
                    w,
                    &o.loads,
                    functions.clone(),
                    flight.clone(),
                    &damping,
                    "flight",
                )?)),
                Wing::Reduced(w) => Eqs::Reduced(Scaled(AeroelasticEquations::new(
                    w,
                    &o.loads,
                    functions.clone(),
                    flight.clone(),
                    &damping,
                    "flight",
                )?)),
            })
        })?;
        let halt = Arc::new(AtomicBool::new(false));
        let (y, limits, dofs, aero_states) = with_eqs!(cell, |e| {
            let eqs = &mut e.0;
            let floor = eqs.energy_resolution(s.settings.atol);
            let limits = s.audit.limits(true, &s.settings, floor);
            eqs.set_energy_audit(Some(limits));
            eqs.set_halt(Some(Arc::clone(&halt)));
            let n = eqs.n_dofs();
            let a0 = eqs.steady_states(0.0, &x0);
            let y = eqs.state(&x0, &vec![0.0; n], &a0);
            (y, limits, n, eqs.n_aero_states())
        });
        let start: Vec<f64> = options
            .inputs
            .iter()
            .map(|i| match i {
                Input::RootAngle => plan.flight.root_angle(0.0),
                Input::Speed => plan.flight.speed(0.0),
                Input::Deflection(s) => deflections0[s.index][0],
                _ => 0.0,
            })
            .collect();
        Ok(Self {
            cell,
            kind,
            dofs,
            aero_states,
            method: s.integrator,
            settings: s.settings.clone(),
            limits,
            hold: options.hold,
            inputs: options.inputs.clone(),
            outputs: options.outputs.clone(),
            case_functions,
            load_inputs,
            values: start.clone(),
            pending: start.clone(),
            last_offsets: FlightOffsets::default(),
            start,
            t: 0.0,
            y,
            stats: IntegratorStats::default(),
            stop: None,
            halt,
            calls: 0,
            integration_time_s: 0.0,
        })
    }

    /// The inputs, in order.
    pub fn inputs(&self) -> &[Input] {
        &self.inputs
    }
    /// The outputs, in order.
    pub fn outputs(&self) -> &[Output] {
        &self.outputs
    }
    /// The model stepped.
    pub fn kind(&self) -> &ModelKind {
        &self.kind
    }
    /// Number of structural coordinates.
    pub fn n_dofs(&self) -> usize {
        self.dofs
    }
    /// Number of aerodynamic (lag) states.
    pub fn n_aero_states(&self) -> usize {
        self.aero_states
    }
    /// The integrator.
    pub fn method(&self) -> Method {
        self.method
    }
    /// The hold of the inputs.
    pub fn hold(&self) -> Hold {
        self.hold
    }
    /// Change the hold of the inputs (from the next interval on; the FMU's `hold` parameter).
    pub fn set_hold(&mut self, hold: Hold) {
        self.hold = hold;
    }
    /// Time (s).
    pub fn t(&self) -> f64 {
        self.t
    }
    /// The state `(x, p, a, W, D)`: coordinates, momenta, lag states, the work of the loads and
    /// the energy dissipated (J) since the start.
    pub fn state(&self) -> &[f64] {
        &self.y
    }
    /// Each input's value at the start (the initial root angle and speed, zero for the others).
    pub fn start_values(&self) -> &[f64] {
        &self.start
    }
    /// Each input's value set for the next interval (in force at `t` with [`Hold::Zero`]).
    pub fn input_values(&self) -> &[f64] {
        &self.pending
    }
    /// Integrator counters summed over the calls.
    pub fn stats(&self) -> IntegratorStats {
        self.stats
    }
    /// Calls of [`Self::step`] (also those that failed).
    pub fn calls(&self) -> usize {
        self.calls
    }
    /// Wall time spent integrating (s), summed over the calls.
    pub fn integration_time_s(&self) -> f64 {
        self.integration_time_s
    }
    /// A flag that, once set (from any thread), stops a running [`Self::step`] after the
    /// integrator's current step ([`Stop::Interrupted`]); cleared at the start of each call.
    pub fn halt_flag(&self) -> Arc<AtomicBool> {
        Arc::clone(&self.halt)
    }

    /// Set input `index` to `value` for the next interval.
    ///
    /// # Errors
    /// An index out of range or a non-finite value (naming the input), a negative speed.
    pub fn set_input(&mut self, index: usize, value: f64) -> Result<(), InputError> {
        let Some(input) = self.inputs.get(index) else {
            return Err(InputError::new(
                "inputs",
                format!(
                    "index {index} is out of range: the stepper has {} inputs",
                    self.inputs.len()
                ),
            ));
        };
        let name = input.name();
        if !value.is_finite() {
            return Err(InputError::new(
                name,
                format!("must be finite, got {value}"),
            ));
        }
        crate::magnitude::check(&name, "", value)?;
        if *input == Input::Speed && value < 0.0 {
            return Err(InputError::new(
                name,
                format!("must be non-negative (m/s), got {}", short(value)),
            ));
        }
        self.pending[index] = value;
        Ok(())
    }

    /// The index of the input called `name`, if the stepper has it.
    pub fn input_index(&self, name: &str) -> Option<usize> {
        self.inputs.iter().position(|i| i.name() == name)
    }

    /// The offsets of the flight and the load inputs' time functions over `[t0, t1]` from
    /// `from` (the values in force at `t0`) to `to`.
    fn forcing(
        &self,
        from: &[f64],
        to: &[f64],
        t0: f64,
        t1: f64,
    ) -> (FlightOffsets, Vec<TimeFunction>) {
        let segment = |i: usize| match self.hold {
            Hold::Linear => Segment {
                t0,
                t1,
                v0: from[i] - self.start[i],
                v1: to[i] - self.start[i],
            },
            Hold::Zero => Segment::held(to[i] - self.start[i]),
        };
        let mut offsets = FlightOffsets::default();
        for (i, input) in self.inputs.iter().enumerate() {
            match input {
                Input::RootAngle => offsets.root_angle = segment(i),
                Input::Speed => offsets.speed = segment(i),
                Input::Gust => offsets.gust = segment(i),
                Input::Deflection(s) => {
                    if offsets.deflections.len() <= s.index {
                        offsets.deflections.resize(s.index + 1, Segment::held(0.0));
                    }
                    offsets.deflections[s.index] = segment(i);
                }
                Input::Force(_)
                | Input::Torque(_)
                | Input::StripGust(_)
                | Input::GustRate
                | Input::DeflectionRate(_)
                | Input::DeflectionAcceleration(_) => {}
            }
        }
        let mut functions = self.case_functions.clone();
        functions.extend(self.load_inputs.iter().map(|&i| match self.hold {
            Hold::Linear => TimeFunction::Table {
                t: vec![t0, t1],
                value: vec![from[i], to[i]],
            },
            Hold::Zero => held(to[i]),
        }));
        (offsets, functions)
    }

    /// Advance by `dt` (s) with the inputs set ([`Self::set_input`]), polling `poll` with the
    /// time after each integrator step. Returns the new time.
    ///
    /// # Errors
    /// An interval that is not positive or below the time's resolution; the speed going
    /// negative; the integration stopping inside the interval (its [`Stop`]: an integrator
    /// failure, the energy running away, the halt flag). After an error the stepper is as before
    /// the call.
    pub fn step(&mut self, dt: f64, poll: &mut dyn FnMut(f64)) -> Result<f64, StepError> {
        let t0 = self.t;
        let t1 = interval_end(t0, dt)?;
        let (offsets, functions) = self.forcing(&self.values, &self.pending, t0, t1);
        let settings = &self.settings;
        let method = self.method;
        let y0 = &self.y;
        self.halt.store(false, Ordering::Relaxed);
        let start = Instant::now();
        let cell = &mut self.cell;
        let limits = self.limits;
        let result = with_eqs!(cell, |e| {
            let before_offsets = e.0.flight_offsets();
            let before_functions = functions_of(&e.0);
            let before_balance = e.0.energy_balance().cloned();
            e.0.set_flight_offsets(offsets.clone());
            if e.0.speed(t1) < 0.0 {
                e.0.set_flight_offsets(before_offsets);
                return Err(StepError::Input(InputError::new(
                    "speed",
                    format!(
                        "the speed would be {} m/s at t = {} s: it must stay non-negative",
                        short(e.0.speed(t1)),
                        short(t1)
                    ),
                )));
            }
            e.0.set_time_functions(functions, "inputs")?;
            let r = integrate(method, settings, e, t0, y0, &[t0, t1], poll);
            let failed = |e: &mut Scaled<'_, _>, error: SolveError| {
                let mut balance =
                    e.0.energy_balance()
                        .cloned()
                        .unwrap_or_else(|| EnergyBalance::start(limits, 0.0));
                balance.finish();
                let stop = match status_of(&balance, Some(error), Some(&self.halt)) {
                    Status::Stopped(stop) => stop,
                    _ => unreachable!("an error is a stop"),
                };
                e.0.set_flight_offsets(before_offsets);
                // The functions put back have the same length: this cannot fail.
                let _ = e.0.set_time_functions(before_functions.clone(), "inputs");
                if let Some(b) = before_balance.clone() {
                    e.0.restore_energy_balance(b);
                }
                stop
            };
            Ok(match r {
                Ok((mut trajectory, stats)) => match trajectory.y.pop() {
                    Some(y) if y.iter().all(|v| v.is_finite()) => Ok((y, stats)),
                    _ => Err((failed(e, SolveError::NonFinite { time: t1 }), stats)),
                },
                Err(f) => Err((failed(e, f.error), f.stats)),
            })
        })?;
        self.calls += 1;
        self.integration_time_s += start.elapsed().as_secs_f64();
        match result {
            Ok((y, stats)) => {
                self.stats += stats;
                self.y = y;
                self.t = t1;
                self.values.clone_from(&self.pending);
                self.last_offsets = offsets;
                self.stop = None;
                Ok(t1)
            }
            Err((stop, stats)) => {
                self.stats += stats;
                self.stop = Some(stop.clone());
                Err(StepError::Stopped(Box::new(stop)))
            }
        }
    }

    /// Each input's value in force at `t`: the values reached at the end of the last interval
    /// ([`Hold::Linear`]) or the values set ([`Hold::Zero`]).
    fn in_force(&self) -> &[f64] {
        match self.hold {
            Hold::Linear => &self.values,
            Hold::Zero => &self.pending,
        }
    }

    /// The outputs at the current time and state, in order, with the inputs in force
    /// ([`Self::in_force`]): into `out` (one value per output).
    pub fn outputs_into(&mut self, out: &mut [f64]) {
        let t = self.t;
        let in_force = self.in_force().to_vec();
        // With the first-order hold the values in force are the last interval's end values:
        // its segments also carry the rates over it (the gust's apparent mass), as the
        // integration ended with them.
        let offsets = match self.hold {
            Hold::Linear => self.last_offsets.clone(),
            Hold::Zero => self.forcing(&in_force, &in_force, t, t).0,
        };
        let y = &self.y;
        let outputs = &self.outputs;
        with_eqs!(self.cell, |e| {
            let eqs = &mut e.0;
            let before = eqs.flight_offsets();
            eqs.set_flight_offsets(offsets);
            evaluate(eqs, outputs, t, y, out);
            eqs.set_flight_offsets(before);
        })
    }

    /// The outputs at the current time and state ([`Self::outputs_into`]).
    pub fn output_values(&mut self) -> Vec<f64> {
        let mut out = vec![0.0; self.outputs.len()];
        self.outputs_into(&mut out);
        out
    }

    /// The energy balance from the start, finished (its largest error so far).
    fn balance(&self) -> EnergyBalance {
        let mut b =
            with_eqs_ref(&self.cell).unwrap_or_else(|| EnergyBalance::start(self.limits, 0.0));
        b.finish();
        b
    }

    /// What the energy audit found from the start to `t`.
    pub fn energy_audit(&self) -> EnergyAudit {
        EnergyAudit::of(&self.balance())
    }

    /// The energies at `t`: kinetic (structure and fluid), strain, the work of the loads since
    /// the start, the energy dissipated since the start (J).
    pub fn energies(&mut self) -> [f64; 4] {
        let y = &self.y;
        with_eqs!(self.cell, |e| {
            let (k, v) = e.0.energies(y);
            let (w, d) = e.0.work_and_dissipation(y).unwrap_or((0.0, 0.0));
            [k, v, w, d]
        })
    }

    /// How the run stands: stopped (the last call failed: its stop), suspect (the energy
    /// balance exceeded its limit at some time), or complete.
    pub fn status(&self) -> Status {
        match &self.stop {
            Some(stop) => Status::Stopped(stop.clone()),
            None => status_of(&self.balance(), None, None),
        }
    }
}

/// The balance of whichever model's equations.
fn with_eqs_ref(cell: &Cell) -> Option<EnergyBalance> {
    cell.with_dependent(|_, dependent| match dependent {
        Eqs::Full(e) => e.0.energy_balance().cloned(),
        Eqs::Reduced(e) => e.0.energy_balance().cloned(),
    })
}

/// The other loads' time functions of `eqs`.
fn functions_of<M: AeroStructure>(eqs: &AeroelasticEquations<'_, M>) -> Vec<TimeFunction> {
    eqs.time_functions().to_vec()
}

/// The outputs `outputs` of state `y` at time `t` into `out`.
fn evaluate<M: PlanarStructure>(
    eqs: &mut AeroelasticEquations<'_, M>,
    outputs: &[Output],
    t: f64,
    y: &[f64],
    out: &mut [f64],
) {
    let aero = eqs.aero();
    let n = eqs.n_dofs();
    let full = aero.full();
    let ne = full.n_elements();
    let q = aero.structure().full_coordinates(&y[..n]);
    let shape = full.shape(&q);
    let needs_lift = outputs.contains(&Output::Lift);
    let lift = if needs_lift {
        eqs.vertical_aerodynamic_force_at(t, y)
    } else {
        0.0
    };
    let hinge_moments = if outputs.iter().any(|o| matches!(o, Output::HingeMoment(_))) {
        eqs.hinge_moments_at(t, y)
    } else {
        Vec::new()
    };
    for (o, output) in out.iter_mut().zip(outputs) {
        *o = match output {
            Output::TipX => shape.x[ne],
            Output::TipY => shape.y[ne],
            Output::TipTwist => shape.twist[ne],
            Output::X(k) => shape.x[*k],
            Output::Y(k) => shape.y[*k],
            Output::Twist(k) => shape.twist[*k],
            Output::RootBendingMoment => full.stiffness()[0] * q[0],
            Output::RootTorque => super::response::root_torque(full, &q),
            Output::Lift => lift,
            Output::HingeMoment(s) => hinge_moments[s.index],
            // Refused by `check_output`.
            Output::RootShear
            | Output::TipAcceleration
            | Output::Acceleration(_)
            | Output::TipZ
            | Output::Z(_)
            | Output::RootLagMoment => f64::NAN,
        };
    }
}

/// The end of an interval of `dt` from `t0`, or the `InputError` of `dt` if the interval
/// is not positive or not what was asked for at the time's resolution (a step of 1 ms at
/// t = 1e20 s).
///
/// # Errors
/// As said.
pub fn interval_end(t0: f64, dt: f64) -> Result<f64, InputError> {
    if !(dt > 0.0) || !dt.is_finite() {
        return Err(InputError::new(
            "dt",
            format!("must be a finite positive interval (s), got {dt}"),
        ));
    }
    let t1 = t0 + dt;
    // The interval integrated is [t0, t1] exactly as the two numbers hold it; rounded to the
    // time's resolution it differs from dt. Beyond 0.1 % it is not the step asked for.
    let taken = t1 - t0;
    if !t1.is_finite() || !(taken > 0.0) || ((taken - dt) / dt).abs() > 1e-3 {
        return Err(InputError::new(
            "dt",
            format!(
                "a step of {} s from t = {} s is below the resolution of the time there (the \
                 interval taken would be {} s)",
                short(dt),
                short(t0),
                short(taken)
            ),
        ));
    }
    Ok(t1)
}

#[cfg(test)]
#[path = "stepper_tests.rs"]
mod tests;
