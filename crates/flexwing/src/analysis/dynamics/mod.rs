//! Non-linear dynamics: time histories of the full model, the simplified model (gyroscopic term
//! neglected) and reduced models, from rest, from a static deflection or from a given state,
//! under time-varying loads ([`crate::solve::EquationsOfMotion`], integrated by
//! [`crate::solve::integrate::integrate`]).
//!
//! A model whose integration stops does not stop the analysis: the other models are simulated,
//! and each run keeps the output times it reached with the reason it stopped.

mod audit;
pub mod chain3d;
mod outcome;
mod run;

pub use audit::{
    integrate_audited, AuditSettings, AuditedRun, EnergyAudit, DEFAULT_RUNAWAY, MAX_TOLERANCE,
    MIN_TOLERANCE,
};
pub(crate) use audit::{output_interval, status_of};
pub use outcome::{Comparison, DynamicOutcome, DynamicRun, Sample, Snapshot};
pub use run::run;

use super::models::{reduced_models, ModelKind};
use crate::error::InputError;
use crate::model::{FullModel, Load};
use crate::solve::integrate::{IntegratorSettings, Method};
use crate::solve::{Damping, Gyroscopic, TimeFunction};
use crate::text::short;

/// The case file's name of a way to get the gyroscopic term: `exact`, `finite-difference` or
/// `neglected`.
pub fn gyroscopic_name(g: Gyroscopic) -> &'static str {
    match g {
        Gyroscopic::Exact => "exact",
        Gyroscopic::FiniteDifference { .. } => "finite-difference",
        Gyroscopic::Neglected => "neglected",
    }
}

/// Most output times of a run: every output time keeps a sample per model in memory.
pub const MAX_OUTPUT_TIMES: usize = 100_000;

/// Smallest `atol` of a dynamic run (rad): below it the error test asks for less than the
/// round-off of joint rotations of order 1.
pub const MIN_ATOL: f64 = 1e-15;
/// Largest `atol` of a dynamic run (rad): a joint-rotation error of 0.1 rad is no answer.
pub const MAX_ATOL: f64 = 0.1;
/// Largest `max_steps` of a dynamic run: a budget of a billion steps per model is hours of
/// computing; a larger one guards against nothing.
pub const MAX_STEPS: usize = 1_000_000_000;

/// A dynamic analysis. Build it with [`DynamicPlan::new`], set the fields, and check it with
/// [`DynamicPlan::validate`] under the caller's names.
#[derive(Debug, Clone)]
pub struct DynamicPlan {
    /// The full model.
    pub model: FullModel,
    /// Every load: those acting during the motion and those that only set the initial state.
    pub loads: Vec<Load>,
    /// The time history `f(t)` of each load during the motion, `Q(t) = f(t) Q₀` (one per load);
    /// `None` for a load that does not act during the motion. Errors name
    /// `{loads_field}[i].time`.
    pub time: Vec<Option<TimeFunction>>,
    /// End of the simulated time (s); the run starts at 0.
    pub end_time: f64,
    /// Output times (s), strictly increasing, within `[0, end_time]`.
    pub output_times: Vec<f64>,
    /// Simulate the full model. Default `true`.
    pub full: bool,
    /// Simulate the full model with the gyroscopic term neglected. Default `false`.
    pub simplified: bool,
    /// Reduced models on the first `r` modes, one per entry.
    pub reduced: Vec<usize>,
    /// Reduced models on listed modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// How the gyroscopic term of the full and reduced models is obtained (the simplified model
    /// neglects it). The finite-difference step's errors name `{prefix}.gyroscopic_step`.
    pub gyroscopic: Gyroscopic,
    /// The time integrator of every model.
    pub integrator: Method,
    /// Tolerances and options of the integrator; errors name `{prefix}.rtol`, ….
    pub settings: IntegratorSettings,
    /// Structural damping of the full model; reduced models get its projection
    /// ([`crate::model::ReducedModel::project_damping`]).
    pub damping: Damping,
    /// The state at `t = 0`.
    pub initial: Initial,
    /// Indices of the output times at which each model's deformed shape is recorded as a
    /// [`Snapshot`] (the tip is recorded at every output time). Default: none.
    pub snapshots: Vec<usize>,
    /// The energy audit of every run; errors name `{prefix}.energy_tolerance`, ….
    pub audit: AuditSettings,
    /// How the caller names each load in messages (a case file: its `name`); a load without
    /// an entry is `loads[i]`.
    pub load_names: Vec<String>,
}

/// The state at `t = 0`.
#[derive(Debug, Clone, PartialEq)]
pub enum Initial {
    /// Undeformed, at rest.
    Rest,
    /// Each model's static equilibrium under these loads (indices into
    /// [`DynamicPlan::loads`]) at their full value, at rest.
    Static {
        /// The loads of the static deflection.
        loads: Vec<usize>,
    },
    /// Given joint rotations and rates of the full model; reduced models start from their
    /// projections `η = Φᵀ M(0) q`, `η̇ = Φᵀ M(0) q̇`.
    Given {
        /// Joint rotations (rad).
        q: Vec<f64>,
        /// Joint rotation rates (rad/s).
        qdot: Vec<f64>,
    },
}

impl DynamicPlan {
    /// The full model from rest under `loads`, each constant in time, over `[0, end_time]`
    /// with the given output times and the default integrator.
    pub fn new(model: FullModel, loads: Vec<Load>, end_time: f64, output_times: Vec<f64>) -> Self {
        let time = vec![Some(TimeFunction::Constant); loads.len()];
        Self {
            model,
            loads,
            time,
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

    /// Check the plan; errors name the loads `{loads_field}[i]…` and everything else
    /// `{prefix}.…` (a case file: `loads` and `dynamic`).
    ///
    /// # Errors
    /// A value out of range (end time, output times, tolerances, damping, time histories over
    /// `[0, end_time]`, the finite-difference step), a load the model cannot carry, nothing to
    /// simulate, reduced models on modes the model does not have, an initial state of the wrong
    /// size or of unknown loads.
    pub fn validate(&self, loads_field: &str, prefix: &str) -> Result<(), InputError> {
        let checks = self.checks();
        checks.times(prefix)?;
        let n_dofs = self.model.n_dofs();
        let reduced = reduced_models(&self.reduced, &self.reduced_modes, n_dofs, prefix)?;
        check_something_to_simulate(self.full, self.simplified, reduced.is_empty(), prefix)?;
        self.model.apply(&self.loads, loads_field)?;
        checks.histories(loads_field)?;
        checks.state(prefix)
    }

    /// The checks it shares with the 3-D chain's dynamic runs.
    fn checks(&self) -> MotionChecks<'_> {
        MotionChecks {
            end_time: self.end_time,
            output_times: &self.output_times,
            settings: &self.settings,
            audit: &self.audit,
            gyroscopic: self.gyroscopic,
            time: &self.time,
            n_loads: self.loads.len(),
            damping: &self.damping,
            initial: &self.initial,
            n_dofs: self.model.n_dofs(),
        }
    }

    /// The models simulated, in order: full, simplified, then the reduced models of `reduced`
    /// and `reduced_modes`.
    ///
    /// # Errors
    /// As [`DynamicPlan::validate`] for the reduced models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        model_kinds(
            self.full,
            self.simplified,
            &self.reduced,
            &self.reduced_modes,
            self.model.n_dofs(),
        )
    }

    /// How the gyroscopic term of a model of this kind is obtained.
    pub fn gyroscopic_of(&self, kind: &ModelKind) -> Gyroscopic {
        gyroscopic_of(self.gyroscopic, kind)
    }

    /// The caller's name of load `i` ([`DynamicPlan::load_names`], else `loads[i]`).
    pub fn load_name(&self, i: usize) -> String {
        super::load_name(&self.load_names, i)
    }

    /// Indices (in [`DynamicPlan::loads`]) of the loads that act during the motion.
    pub fn active(&self) -> Vec<usize> {
        active(&self.time)
    }
}

/// The models of a dynamic run, in order: full, simplified, then the reduced models of
/// `reduced` and `reduced_modes` on a model of `n_dofs` coordinates.
pub(crate) fn model_kinds(
    full: bool,
    simplified: bool,
    reduced: &[usize],
    reduced_modes: &[Vec<usize>],
    n_dofs: usize,
) -> Result<Vec<ModelKind>, InputError> {
    let reduced = reduced_models(reduced, reduced_modes, n_dofs, "")?;
    let full = full.then_some(ModelKind::Full);
    let simplified = simplified.then_some(ModelKind::Simplified);
    Ok(full
        .into_iter()
        .chain(simplified)
        .chain(reduced.into_iter().map(|(k, _)| k))
        .collect())
}

/// How the gyroscopic term of a model of `kind` is obtained when the plan asks for `gyroscopic`:
/// the simplified model neglects it.
pub(crate) fn gyroscopic_of(gyroscopic: Gyroscopic, kind: &ModelKind) -> Gyroscopic {
    match kind {
        ModelKind::Simplified => Gyroscopic::Neglected,
        _ => gyroscopic,
    }
}

/// Indices of the loads with a time history: those acting during the motion.
pub(crate) fn active(time: &[Option<TimeFunction>]) -> Vec<usize> {
    (0..time.len()).filter(|&i| time[i].is_some()).collect()
}

/// Refuse a plan that simulates no model; errors name `{prefix}.full`.
pub(crate) fn check_something_to_simulate(
    full: bool,
    simplified: bool,
    no_reduced: bool,
    prefix: &str,
) -> Result<(), InputError> {
    let field = |key: &str| crate::field(prefix, key);
    if !full && !simplified && no_reduced {
        return Err(InputError::new(
            field("full"),
            format!(
                "nothing to simulate: full = false, simplified = false and no reduced models \
                 (give {} or {})",
                field("reduced"),
                field("reduced_modes")
            ),
        ));
    }
    Ok(())
}

/// What a dynamic run checks whatever its model (the planar [`DynamicPlan`] and the 3-D
/// chain's [`crate::analysis::chain3d::Dynamic3d`]): the times, the integrator's settings, the
/// audit, the gyroscopic option, the time histories, the damping and the initial state.
pub(crate) struct MotionChecks<'a> {
    pub end_time: f64,
    pub output_times: &'a [f64],
    pub settings: &'a IntegratorSettings,
    pub audit: &'a AuditSettings,
    pub gyroscopic: Gyroscopic,
    pub time: &'a [Option<TimeFunction>],
    pub n_loads: usize,
    pub damping: &'a Damping,
    pub initial: &'a Initial,
    pub n_dofs: usize,
}

impl MotionChecks<'_> {
    /// End time, output times, tolerances and steps, the audit, the gyroscopic step; errors
    /// name `{prefix}.end_time`, ….
    pub fn times(&self, prefix: &str) -> Result<(), InputError> {
        let field = |key: &str| crate::field(prefix, key);
        let end = self.end_time;
        if !(end > 0.0 && end.is_finite()) {
            return Err(InputError::new(
                field("end_time"),
                format!("must be a finite positive number, got {}", short(end)),
            ));
        }
        crate::magnitude::check(&field("end_time"), "", end)?;
        self.check_output_times(prefix)?;
        self.settings.validate(prefix)?;
        self.check_steps(prefix)?;
        self.audit.validate(prefix)?;
        self.gyroscopic.validate(&field("gyroscopic_step"))
    }

    /// One time history per load, each valid over `[0, end_time]`; errors name
    /// `{loads_field}[i].time`.
    pub fn histories(&self, loads_field: &str) -> Result<(), InputError> {
        if self.time.len() != self.n_loads {
            return Err(InputError::new(
                loads_field,
                format!(
                    "{} loads but {} time histories",
                    self.n_loads,
                    self.time.len()
                ),
            ));
        }
        for (i, f) in self.time.iter().enumerate() {
            if let Some(f) = f {
                f.validate(&format!("{loads_field}[{i}].time"), 0.0, self.end_time)?;
            }
        }
        Ok(())
    }

    /// The damping and the initial state; errors name `{prefix}.damping`, `{prefix}.initial`.
    pub fn state(&self, prefix: &str) -> Result<(), InputError> {
        let field = |key: &str| crate::field(prefix, key);
        self.damping.validate(&field("damping"), self.n_dofs)?;
        self.check_initial(&field("initial"))
    }
    /// Bounds of the tolerances and steps that the generic integrator settings do not know:
    /// `atol` is a joint rotation (rad), at most [`MAX_ATOL`] (a larger error is no answer) and
    /// at least [`MIN_ATOL`] (below round-off of the joint rotations); `max_steps` at most
    /// [`MAX_STEPS`]; a fixed step or a step cap so small that the run cannot reach `end_time`
    /// within `max_steps` is refused before it starts.
    fn check_steps(&self, prefix: &str) -> Result<(), InputError> {
        let st = self.settings;
        if !(MIN_ATOL..=MAX_ATOL).contains(&st.atol) {
            return Err(InputError::new(
                crate::field(prefix, "atol"),
                format!(
                    "must be a number in [{}, {}] (rad, an error in the joint rotations), got {}",
                    short(MIN_ATOL),
                    short(MAX_ATOL),
                    short(st.atol)
                ),
            ));
        }
        if st.max_steps > MAX_STEPS {
            return Err(InputError::new(
                crate::field(prefix, "max_steps"),
                format!(
                    "must be at most {} (a budget of steps per model), got {}",
                    short(MAX_STEPS as f64),
                    short(st.max_steps as f64)
                ),
            ));
        }
        for (key, h) in [("step", st.step), ("max_step", st.max_step)] {
            let Some(h) = h else { continue };
            let needed = self.end_time / h;
            if needed > st.max_steps as f64 {
                return Err(InputError::new(
                    crate::field(prefix, key),
                    format!(
                        "{} s needs at least {} steps to reach end_time {} s, more than \
                         max_steps = {}",
                        short(h),
                        short(needed.ceil()),
                        short(self.end_time),
                        short(st.max_steps as f64)
                    ),
                ));
            }
        }
        Ok(())
    }

    fn check_output_times(&self, prefix: &str) -> Result<(), InputError> {
        let field = crate::field(prefix, "output_times");
        let (times, end) = (self.output_times, self.end_time);
        if times.is_empty() {
            return Err(InputError::new(field, "must not be empty"));
        }
        if times.len() > MAX_OUTPUT_TIMES {
            return Err(InputError::new(
                field,
                format!(
                    "gives {} output times; at most {MAX_OUTPUT_TIMES} are allowed",
                    times.len()
                ),
            ));
        }
        for (i, &t) in times.iter().enumerate() {
            let at = format!("{field}[{i}]");
            let reason = if !t.is_finite() {
                format!("must be finite, got {}", short(t))
            } else if t < 0.0 {
                format!("{} is before the start time 0", short(t))
            } else if t > end {
                format!("{} is after end_time {}", short(t), short(end))
            } else if i > 0 && t <= times[i - 1] {
                format!(
                    "{} is not after output_times[{}] = {}; output times must increase",
                    short(t),
                    i - 1,
                    short(times[i - 1])
                )
            } else {
                continue;
            };
            return Err(InputError::new(at, reason));
        }
        Ok(())
    }

    fn check_initial(&self, field: &str) -> Result<(), InputError> {
        let n_dofs = self.n_dofs;
        match &self.initial {
            Initial::Rest => Ok(()),
            Initial::Static { loads } => {
                if loads.is_empty() {
                    return Err(InputError::new(
                        format!("{field}.loads"),
                        "missing: a static initial state needs the loads it is the \
                         equilibrium under",
                    ));
                }
                match loads.iter().position(|&i| i >= self.n_loads) {
                    Some(k) => Err(InputError::new(
                        format!("{field}.loads[{k}]"),
                        format!("there is no load {} (of {})", loads[k], self.n_loads),
                    )),
                    None => Ok(()),
                }
            }
            Initial::Given { q, qdot } => {
                for (key, v) in [("q", q), ("qdot", qdot)] {
                    if v.len() != n_dofs {
                        return Err(InputError::new(
                            format!("{field}.{key}"),
                            format!(
                                "needs {n_dofs} values (one per coordinate of the full model), \
                                 got {}",
                                v.len()
                            ),
                        ));
                    }
                    if let Some(k) = v.iter().position(|x| !x.is_finite()) {
                        return Err(InputError::new(
                            format!("{field}.{key}[{k}]"),
                            format!("must be finite, got {}", short(v[k])),
                        ));
                    }
                    for (k, &x) in v.iter().enumerate() {
                        crate::magnitude::check(&format!("{field}.{key}[{k}]"), "", x)?;
                    }
                }
                Ok(())
            }
        }
    }
}

#[cfg(test)]
mod tests;
