//! How the run of one model ended. A stop reason is data (the front end words it): which
//! solver failed where, with the values it stopped at.

use crate::error::{InputError, SolveError};
use crate::solve::aeroelastic::FlutterStop;

/// How the run of one model ended. More variants may follow (a run that completed but whose
/// energy balance is doubtful, for example), so match with a wildcard arm.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Status {
    /// Every output time or sweep point was reached.
    Complete,
    /// The run stopped early; its output up to there is kept.
    Stopped(Stop),
}

impl Status {
    /// Whether every output time or sweep point was reached.
    pub fn is_complete(&self) -> bool {
        matches!(self, Status::Complete)
    }

    /// Why the run stopped, if it did.
    pub fn stop(&self) -> Option<&Stop> {
        match self {
            Status::Stopped(s) => Some(s),
            _ => None,
        }
    }
}

/// Why a run stopped before its end.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Stop {
    /// The time integration stopped: the error says where (its time) and why.
    Integration(SolveError),
    /// The static solve of point `point` (0-based) of `points` failed, at scale `scale` of the
    /// swept load (1 without a sweep); the points before it are kept.
    StaticPoint {
        /// Index of the failed point.
        point: usize,
        /// Number of points.
        points: usize,
        /// Scale of the swept load at the failed point.
        scale: f64,
        /// Scale of the swept load up to which equilibria were found on the way from the
        /// previous point (from rest before the first), when the solver diverged.
        reached: Option<f64>,
        /// The solver's error.
        error: SolveError,
    },
    /// The initial static deflection of a dynamic run failed.
    InitialState(SolveError),
    /// The equations of motion could not be set up for this model.
    Equations(InputError),
    /// The energy grew beyond `limit` times its initial value: `ratio` times at `time` (s), a
    /// blown-up run.
    EnergyLimit {
        /// Output time at which the energy was checked (s).
        time: f64,
        /// Energy over its initial value.
        ratio: f64,
        /// The limit of that ratio.
        limit: f64,
    },
    /// The static aeroelastic equilibrium at speed `point` (0-based) of `points` was not found
    /// (past divergence, or the solver failed); the speeds before it are kept.
    SpeedPoint {
        /// Index of the failed speed.
        point: usize,
        /// Number of speeds.
        points: usize,
        /// The free-stream speed (m/s).
        speed: f64,
        /// The static solver's error.
        error: SolveError,
    },
    /// The flutter analysis stopped before the last speed; its data up to there are kept.
    Flutter(FlutterStop),
}
