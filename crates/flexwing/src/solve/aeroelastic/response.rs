//! Time response of the aeroelastic system to gusts and to changes of speed or root angle
//! (docs/aeroelastic-model.md §5), with the existing Radau IIA integrator and the exact Jacobian
//! of `equations.rs` (Newton systems by elimination of the lag states, `schur.rs`). The run starts
//! from the static aeroelastic equilibrium of the initial flight condition, at rest, with the lag
//! states in steady state.

use super::equations::AeroelasticEquations;
use super::flight::FlightHistory;
use super::schur::AeroNewtonSystems;
use super::statics::SteadyAeroModel;
use crate::error::{InputError, SolveError};
use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic};
use crate::model::{Load, StructuralModel};
use crate::solve::integrate::{IntegratorStats, Radau, RadauOptions, Tolerances};
use crate::solve::{continue_static, Damping, StaticOptions, TimeFunction};

/// A time response, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseOptions {
    /// The flight condition over time (initial condition, changes, gust).
    pub flight: FlightHistory,
    /// Other loads, each scaled by its time function.
    pub loads: Vec<Load>,
    /// Time functions of the other loads (one per load).
    pub time_functions: Vec<TimeFunction>,
    /// Structural damping.
    pub damping: Damping,
    /// Duration (s), from `t = 0`.
    pub duration: f64,
    /// Output interval (s).
    pub output_step: f64,
    /// Relative tolerance of the integrator; the absolute tolerance is `rtol` rad on the
    /// coordinates, scaled for the momenta and lag states (`AeroelasticEquations::state_atol`).
    pub rtol: f64,
    /// Largest step (s); infinite for none.
    pub max_step: f64,
    /// Options of the static solver for the initial equilibrium.
    pub static_options: StaticOptions,
    /// How Radau's Newton systems are solved (default: lag states eliminated, `schur.rs`).
    pub newton_systems: AeroNewtonSystems,
}

impl ResponseOptions {
    /// A response of `duration` s in the flight `flight`, output every `output_step` s, rtol 1e-6,
    /// no other loads, no damping.
    pub fn new(flight: FlightHistory, duration: f64, output_step: f64) -> Self {
        Self {
            flight,
            loads: vec![],
            time_functions: vec![],
            damping: Damping::None,
            duration,
            output_step,
            rtol: 1e-6,
            max_step: f64::INFINITY,
            static_options: StaticOptions::default(),
            newton_systems: AeroNewtonSystems::Auto,
        }
    }

    /// Check the plan for a wing of span `length`; `field` prefixes the fields.
    pub fn validate(&self, field: &str, length: f64) -> Result<(), InputError> {
        let pos = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(InputError::new(
                    format!("{field}.{name}"),
                    format!(
                        "must be a finite positive number, got {}",
                        crate::text::short(v)
                    ),
                ))
            }
        };
        pos("duration", self.duration)?;
        pos("output_step", self.output_step)?;
        pos("rtol", self.rtol)?;
        if !(self.max_step > 0.0) {
            return Err(InputError::new(
                format!("{field}.max_step"),
                format!(
                    "must be positive, got {}",
                    crate::text::short(self.max_step)
                ),
            ));
        }
        if self.time_functions.len() != self.loads.len() {
            return Err(InputError::new(
                format!("{field}.loads"),
                format!(
                    "{} loads but {} time functions",
                    self.loads.len(),
                    self.time_functions.len()
                ),
            ));
        }
        for (i, f) in self.time_functions.iter().enumerate() {
            f.validate(&format!("{field}.time_functions[{i}]"), 0.0, self.duration)?;
        }
        self.flight
            .validate(&format!("{field}.flight"), length, 0.0, self.duration)?;
        self.static_options
            .validate(&format!("{field}.static_options"))
    }
}

/// The outputs of the response at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResponseSample {
    /// Time (s).
    pub t: f64,
    /// Tip displacement of the elastic axis from the undeformed tip `(dx, dy, dz)` (m; `dz`,
    /// chordwise toward the leading edge, is 0 on the planar chain).
    pub tip: [f64; 3],
    /// Tip twist (rad, nose-up).
    pub tip_twist: f64,
    /// Root bending moment, the clamp spring's moment `K_θ,1 q_1` (N·m).
    pub root_bending_moment: f64,
    /// Total aerodynamic force along the ground's vertical (N).
    pub lift: f64,
}

/// What a time response produced.
#[derive(Debug, Clone, PartialEq)]
pub struct ResponseSolution {
    /// Outputs at the output times reached.
    pub samples: Vec<ResponseSample>,
    /// States `(x, p, a)` at the output times reached.
    pub states: Vec<Vec<f64>>,
    /// Integrator counters.
    pub stats: IntegratorStats,
    /// Why the run stopped early, if it did (the output above is kept).
    pub stopped: Option<SolveError>,
}

/// The time response of `aero` to `plan`. `progress` is called with the time reached.
///
/// # Errors
/// An invalid plan or loads, or no initial equilibrium (as an input error naming
/// `{field}.flight`: the initial condition is past divergence or the loads too large).
pub fn response<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &ResponseOptions,
    field: &str,
    progress: &mut dyn FnMut(f64),
) -> Result<ResponseSolution, InputError> {
    plan.validate(field, aero.chain().length())?;
    let init = plan.flight.initial;
    // Initial equilibrium: the steady model with the loads at t = 0 and gravity.
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut loads0 = plan.loads.clone();
    let mut scales0: Vec<f64> = plan.time_functions.iter().map(|f| f.at(0.0)).collect();
    if let Some(g) = init.gravity {
        loads0.push(Load::Gravity { g });
        scales0.push(init.root_angle.cos());
    }
    let applied0 = aero.apply(&loads0, &format!("{field}.loads"))?;
    let model = SteadyAeroModel::new(&steady, init.root_angle);
    let n = model.n_dofs();
    scales0.push(0.5 * aero.density() * init.speed * init.speed);
    let zero_scales = vec![0.0; scales0.len()];
    let x0 = continue_static(
        &model,
        &applied0,
        (&vec![0.0; n], &zero_scales),
        &scales0,
        &plan.static_options,
    )
    .map_err(|e| {
        InputError::new(
            format!("{field}.flight"),
            format!("no static equilibrium in the initial flight condition: {e}"),
        )
    })?
    .x;
    let applied = aero.apply(&plan.loads, &format!("{field}.loads"))?;
    let mut eqs = AeroelasticEquations::new(
        aero,
        &applied,
        plan.time_functions.clone(),
        plan.flight.clone(),
        &plan.damping,
        &format!("{field}.flight"),
    )?;
    eqs.set_newton_systems(plan.newton_systems);
    let a0 = eqs.steady_states(0.0, &x0);
    let y0 = eqs.state(&x0, &vec![0.0; n], &a0);
    let steps = (plan.duration / plan.output_step).round().max(1.0) as usize;
    let t_out: Vec<f64> = (0..=steps)
        .map(|k| (k as f64 * plan.output_step).min(plan.duration))
        .collect();
    let atol = eqs.state_atol(plan.rtol);
    let radau = Radau {
        options: RadauOptions {
            tolerances: Tolerances {
                rtol: plan.rtol,
                atol,
            },
            max_step: plan.max_step,
            unchanged_step_ratio: unchanged_step_ratio(n),
            ..Default::default()
        },
    };
    let (trajectory, stats, stopped) = match radau.integrate(&mut eqs, 0.0, &y0, &t_out, progress) {
        Ok((t, s)) => (t, s, None),
        Err(f) => (f.trajectory, f.stats, Some(f.error)),
    };
    let samples = trajectory
        .t
        .iter()
        .zip(&trajectory.y)
        .map(|(&t, y)| sample(aero, &mut eqs, t, y))
        .collect();
    Ok(ResponseSolution {
        samples,
        states: trajectory.y,
        stats,
        stopped,
    })
}

/// Radau's `unchanged_step_ratio` for `n` coordinates: with more than 16, the step and its
/// factorizations are kept while the controller proposes 0.8 to 2 times the step (an LU of the
/// `n × n` Newton system, `schur.rs`, then costs several right-hand sides); `RADAU5`'s default
/// `[1, 1.2]` below. Measured on the 2 s gust of Patil's wing (`benches/aero.rs`): at 64
/// coordinates 30 % less time for the same or a smaller tip error; at 6 (reduced), 5–20 % more.
fn unchanged_step_ratio(n: usize) -> (f64, f64) {
    if n > 16 {
        (0.8, 2.0)
    } else {
        RadauOptions::default().unchanged_step_ratio
    }
}

/// The outputs of state `y` at time `t`.
fn sample<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    eqs: &mut AeroelasticEquations<'_, M>,
    t: f64,
    y: &[f64],
) -> ResponseSample {
    let lift = eqs.vertical_aerodynamic_force_at(t, y);
    let (tip, tip_twist, q) = eqs.last_tip();
    ResponseSample {
        t,
        tip,
        tip_twist,
        root_bending_moment: aero.chain().root_bending_moment(q),
        lift,
    }
}
