//! Audited integration: every dynamic run of the analysis goes through [`integrate_audited`],
//! which keeps the energy balance of the run (module [`crate::solve::EnergyBalance`],
//! docs/model-choices.md "Energy audit"), stops a run whose energy runs away, and turns what the
//! audit found into the run's status: suspect when the balance error exceeded its limit.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use crate::analysis::{Doubt, Status, Stop};
use crate::error::{InputError, SolveError};
use crate::model::StructuralModel;
use crate::solve::integrate::{integrate, IntegratorSettings, IntegratorStats, Method, Trajectory};
use crate::solve::{AuditLimits, EnergyBalance, EquationsOfMotion, Gyroscopic};
use crate::text::short;

/// The energy audit of a dynamic run: when a model's run is suspect, and when it is stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuditSettings {
    /// Largest relative energy-balance error `|H − H(0) − W + D| / E` of a run of the full or a
    /// reduced model before it is marked suspect; `None`: [`AuditSettings::default_tolerance`]
    /// of the plan's integrator settings.
    pub tolerance: Option<f64>,
    /// Relative energy gain `(H − H(0) − W + D) / E` at which a run (of any model, the
    /// simplified one included) is stopped as a runaway. Default [`DEFAULT_RUNAWAY`].
    pub runaway: f64,
}

/// Default runaway limit: a run that created nine times the energy it held or was given (its
/// energy grew tenfold without a cause) has blown up. The limit of the paper study's guard
/// before the audit (an energy ten times the initial one).
pub const DEFAULT_RUNAWAY: f64 = 9.0;

/// Default balance tolerance of an adaptive run, in units of its `rtol` (before the clamp to
/// `[1e-5, 0.1]` of [`AuditSettings::default_tolerance`]); it was 10⁴ before the measurement
/// written there.
pub const DEFAULT_TOLERANCE_FACTOR: f64 = 1e3;

/// Default balance tolerance of a fixed-step run, whose error no tolerance sets: 1 % of the
/// energy held or given.
pub const FIXED_STEP_TOLERANCE: f64 = 1e-2;

/// Bounds of the balance tolerance: below `MIN_TOLERANCE` round-off in the energies decides,
/// above `MAX_TOLERANCE` the check checks nothing.
pub const MIN_TOLERANCE: f64 = 1e-10;
/// See [`MIN_TOLERANCE`].
pub const MAX_TOLERANCE: f64 = 0.5;

impl Default for AuditSettings {
    fn default() -> Self {
        Self {
            tolerance: None,
            runaway: DEFAULT_RUNAWAY,
        }
    }
}

impl AuditSettings {
    /// The default balance tolerance of a run with the integrator `settings`:
    /// [`DEFAULT_TOLERANCE_FACTOR`] `rtol`, at least `1e-5` and at most 0.1, for an adaptive step;
    /// [`FIXED_STEP_TOLERANCE`] for a fixed step. Measured (docs/validation.md, "Energy audit":
    /// the dynamic examples, undamped and with 20 % modal damping, full and reduced models, Radau,
    /// BDF and Dormand–Prince at rtol 1e-3 to 1e-10): every run that completed kept its balance
    /// within 66 `rtol` for rtol ≥ 1e-6 (BDF, damped reduced models) and within 3.1e-6 in
    /// absolute terms below (BDF's error stops falling with rtol there: 1.1e-6 at rtol 1e-9). The
    /// limit `1000 rtol` leaves a margin of 15 above the first; the floor `1e-5` one of 3 above
    /// the second; the ceiling 0.1 one of 2 above Dormand–Prince's 5e-2 at rtol 1e-3.
    pub fn default_tolerance(settings: &IntegratorSettings) -> f64 {
        match settings.step {
            Some(_) => FIXED_STEP_TOLERANCE,
            None => (DEFAULT_TOLERANCE_FACTOR * settings.rtol).clamp(1e-5, 0.1),
        }
    }

    /// The balance tolerance of a run with the integrator `settings`.
    pub fn tolerance_for(&self, settings: &IntegratorSettings) -> f64 {
        self.tolerance
            .unwrap_or_else(|| Self::default_tolerance(settings))
    }

    /// Check the values; errors name `{prefix}.energy_tolerance` and `{prefix}.energy_runaway`.
    ///
    /// # Errors
    /// A tolerance outside `[1e-10, 0.5]`, a runaway limit outside `[0.01, 1e6]`.
    pub fn validate(&self, prefix: &str) -> Result<(), InputError> {
        if let Some(t) = self.tolerance {
            if !(MIN_TOLERANCE..=MAX_TOLERANCE).contains(&t) {
                return Err(InputError::new(
                    crate::field(prefix, "energy_tolerance"),
                    format!(
                        "must be a number in [{}, {}] (a relative energy error), got {}",
                        short(MIN_TOLERANCE),
                        short(MAX_TOLERANCE),
                        short(t)
                    ),
                ));
            }
        }
        if !(0.01..=1e6).contains(&self.runaway) {
            return Err(InputError::new(
                crate::field(prefix, "energy_runaway"),
                format!(
                    "must be a number in [0.01, 1e6] (energy created over the energy held or \
                     given), got {}",
                    short(self.runaway)
                ),
            ));
        }
        Ok(())
    }

    /// The limits of the audit of a model with (`balanced`) or without an energy balance, for
    /// the integrator `settings`, with the energy floor `floor` (J).
    pub fn limits(&self, balanced: bool, settings: &IntegratorSettings, floor: f64) -> AuditLimits {
        AuditLimits {
            balance: balanced.then(|| self.tolerance_for(settings)),
            runaway: self.runaway,
            floor,
            interval: 0.0,
        }
    }
}

/// What the energy audit of a run found over its accepted steps (docs/validation.md, "Energy
/// audit"), in the names every front end shows (the CLI's `energy_audit`, Python's
/// `run.energy_audit`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EnergyAudit {
    /// Whether the model has an energy balance (all but the simplified model): its error is an
    /// integration error; the simplified model's is the energy its equations create.
    pub balanced: bool,
    /// Largest relative balance error `max_t |H − H(0) − W + D| / E`.
    pub max_error: f64,
    /// Its time (s).
    pub max_error_time: f64,
    /// The limit of `max_error` (`None` without a balance).
    pub limit: Option<f64>,
    /// The first time the error exceeded `limit` (s): the run is then suspect.
    pub exceeded_time: Option<f64>,
    /// The runaway limit of the energy created.
    pub runaway_limit: f64,
    /// The time the run was stopped as a runaway (s), if it was.
    pub runaway_time: Option<f64>,
    /// The reference energy `E` (J): the largest energy held or given.
    pub reference_energy: f64,
}

impl EnergyAudit {
    /// What the balance `b` of a finished run says.
    pub fn of(b: &EnergyBalance) -> Self {
        Self {
            balanced: b.limits.balance.is_some(),
            max_error: b.max_error,
            max_error_time: b.max_error_time,
            limit: b.limits.balance,
            exceeded_time: b.exceeded_at,
            runaway_limit: b.limits.runaway,
            runaway_time: b.runaway_at,
            reference_energy: b.reference,
        }
    }
}

/// An audited run: the output reached, the integrator's counters, the energy balance and how the
/// run ended.
#[derive(Debug, Clone)]
pub struct AuditedRun {
    /// States at the output times reached (with the audit's `W` and `D` appended).
    pub trajectory: Trajectory,
    /// Counters.
    pub stats: IntegratorStats,
    /// What the energy audit found.
    pub balance: EnergyBalance,
    /// Complete, suspect (the balance error exceeded its limit) or stopped (why).
    pub status: Status,
}

impl AuditedRun {
    /// Why the run stopped, if it did.
    pub fn stop(&self) -> Option<&Stop> {
        self.status.stop()
    }
}

/// Integrate `eom` with the energy audit from the coordinates `x0` and velocities `xdot0` at
/// `t_out[0]` to the output times `t_out`: the audit is switched on with the limits of
/// `audit` (no balance limit for equations without a balance: γ neglected), the run stops
/// when its energy runs away or when `halt` is set (checked after every step; `progress` is
/// called with the time after each step), and the status says what happened. `eom` keeps the
/// audit on afterwards (its states carry `W` and `D`).
#[allow(clippy::too_many_arguments)]
pub fn integrate_audited<M: StructuralModel>(
    eom: &mut EquationsOfMotion<'_, M>,
    x0: &[f64],
    xdot0: &[f64],
    t_out: &[f64],
    method: Method,
    settings: &IntegratorSettings,
    audit: &AuditSettings,
    halt: Option<Arc<AtomicBool>>,
    progress: &mut dyn FnMut(f64),
) -> AuditedRun {
    let floor = eom.energy_resolution(settings.atol);
    let balanced = !matches!(eom.gyroscopic(), Gyroscopic::Neglected);
    let limits = AuditLimits {
        interval: output_interval(t_out),
        ..audit.limits(balanced, settings, floor)
    };
    eom.set_energy_audit(Some(limits));
    eom.set_halt(halt.clone());
    let y0 = eom.state(x0, xdot0);
    let result = integrate(method, settings, eom, t_out[0], &y0, t_out, progress);
    let (trajectory, stats, error) = match result {
        Ok((trajectory, stats)) => {
            if let (Some(&t), Some(y)) = (trajectory.t.last(), trajectory.y.last()) {
                eom.audit_final(t, y);
            }
            (trajectory, stats, None)
        }
        Err(f) => (f.trajectory, f.stats, Some(f.error)),
    };
    // The audit was switched on above: its balance is there.
    let mut balance = eom
        .energy_balance()
        .cloned()
        .unwrap_or_else(|| EnergyBalance::start(limits, 0.0));
    balance.finish();
    let status = status_of(&balance, error, halt.as_deref());
    AuditedRun {
        trajectory,
        stats,
        balance,
        status,
    }
}

/// The audit's interval of a run with the output times `t_out` (`AuditLimits::interval`): their
/// mean spacing, 0 for a single output.
pub(crate) fn output_interval(t_out: &[f64]) -> f64 {
    match (t_out.first(), t_out.last()) {
        (Some(a), Some(b)) if t_out.len() > 1 => (b - a) / (t_out.len() - 1) as f64,
        _ => 0.0,
    }
}

/// The status of a run that ended with `error` (if any), after the audit found `balance`.
pub(crate) fn status_of(
    balance: &EnergyBalance,
    error: Option<SolveError>,
    halt: Option<&AtomicBool>,
) -> Status {
    match error {
        Some(SolveError::Halted { time }) => {
            if let Some(t) = balance.runaway_at {
                Status::Stopped(Stop::EnergyRunaway {
                    time: t,
                    gain: balance.max_gain,
                    limit: balance.limits.runaway,
                })
            } else if halt.is_some_and(|h| h.load(Ordering::Relaxed)) {
                Status::Stopped(Stop::Interrupted { time: Some(time) })
            } else {
                Status::Stopped(Stop::Integration(SolveError::Halted { time }))
            }
        }
        Some(e) => Status::Stopped(Stop::Integration(e)),
        None => match (balance.exceeded_at, balance.limits.balance) {
            (Some(time), Some(limit)) => Status::Suspect(Doubt::EnergyBalance {
                time,
                max_error: balance.max_error,
                max_error_time: balance.max_error_time,
                limit,
            }),
            _ => Status::Complete,
        },
    }
}
