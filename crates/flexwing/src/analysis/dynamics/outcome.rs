//! What a dynamic analysis produced: per model, the tip and the energies at every output time,
//! deformed shapes at chosen output times, the integrator's counters, the wall time, how the run
//! ended and how far it is from the first model.

use super::super::models::ModelKind;
use super::super::{Note, Status};
use super::EnergyAudit;
use crate::model::Shape;
use crate::solve::integrate::{IntegratorStats, Method};
use crate::solve::Gyroscopic;

/// The simulation of one model.
#[derive(Debug, Clone)]
pub struct DynamicRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// The integrator used.
    pub integrator: Method,
    /// How the gyroscopic term was obtained.
    pub gyroscopic: Gyroscopic,
    /// Integrator counters (up to the stop, if any).
    pub stats: IntegratorStats,
    /// Wall time of the integration (s).
    pub wall_time_s: f64,
    /// One sample per output time reached.
    pub samples: Vec<Sample>,
    /// The deformed shape at the plan's snapshot times that were reached.
    pub snapshots: Vec<Snapshot>,
    /// Whether every output time was reached and the energy balance held, or where and why the
    /// run stopped or is doubtful.
    pub status: Status,
    /// What the energy audit found over the accepted steps; `None` if the run did not start
    /// (its initial state or equations failed).
    pub energy_audit: Option<EnergyAudit>,
    /// Differences from the first model's tip history (not for the first model itself).
    pub comparison: Option<Comparison>,
    /// What made the run slow that its status does not show ([`Note::newton`]).
    pub notes: Vec<Note>,
}

impl DynamicRun {
    /// Whether the model has an energy balance (all but the simplified model): its audit error
    /// is an integration error; the simplified model's is the energy its equations create.
    pub fn has_energy_balance(&self) -> bool {
        self.kind != ModelKind::Simplified
    }
}

/// The tip and the energies at one output time.
#[derive(Debug, Clone, Copy, PartialEq)]
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
    /// Work of the applied loads since `t = 0`, `W = ∫ ẋ·Q dt` (J).
    pub work: f64,
    /// Energy dissipated by the structural damping since `t = 0`, `D = ∫ ẋᵀ C ẋ dt` (J).
    pub dissipated: f64,
    /// The energy balance `(H − H(0) − W + D) / E` at this time, relative to the energy the run
    /// has held or been given up to here ([`crate::solve::EnergyBalance`]); positive is energy
    /// created.
    pub balance_error: f64,
}

impl Sample {
    /// Kinetic plus strain energy (J).
    pub fn total(&self) -> f64 {
        self.kinetic + self.strain
    }
}

/// The deformed elastic axis at one output time.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot {
    /// Index of the output time.
    pub index: usize,
    /// Time (s).
    pub t: f64,
    /// The shape.
    pub shape: Shape,
}

/// How far a model's tip history is from the first model's, over the output times both reached.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// `max_t |tip − tip_first|` (m).
    pub max_tip_difference: f64,
    /// `max_t |Δx| / max_t |x_first − L|`: relative to the first model's axial tip displacement.
    pub relative_x: Option<f64>,
    /// `max_t |Δy| / max_t |y_first|`.
    pub relative_y: Option<f64>,
}

/// What a dynamic analysis produced.
#[derive(Debug, Clone)]
pub struct DynamicOutcome {
    /// One run per model, in the order of [`super::DynamicPlan::models`].
    pub runs: Vec<DynamicRun>,
}

impl DynamicOutcome {
    /// Wall time of `run` over that of the first model.
    pub fn ratio_to_first(&self, run: &DynamicRun) -> Option<f64> {
        let first = self.runs.first()?;
        (first.wall_time_s > 0.0).then(|| run.wall_time_s / first.wall_time_s)
    }

    /// Whether every model reached every output time.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
    }
}

/// Fill in each model's differences from the first model's tip history, over the output times
/// both reached; `length` is the span `L`.
pub(super) fn compare_with_first(runs: &mut [DynamicRun], length: f64) {
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
