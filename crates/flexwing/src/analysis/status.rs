//! How the run of one model ended. A stop reason is data (the front end words it): which
//! solver failed where, with the values it stopped at.

use crate::error::{InputError, SolveError};
use crate::solve::aeroelastic::FlutterStop;

/// How the run of one model ended. More variants may follow, so match with a wildcard arm.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Status {
    /// Every output time or sweep point was reached and every check of the result passed.
    Complete,
    /// Every output time was reached, but a check of the result failed: the result is doubtful
    /// and is not complete.
    Suspect(Doubt),
    /// The run stopped early; its output up to there is kept.
    Stopped(Stop),
}

impl Status {
    /// Whether every output time or sweep point was reached and every check passed.
    pub fn is_complete(&self) -> bool {
        matches!(self, Status::Complete)
    }

    /// `complete`, `suspect` or `incomplete` (stopped): the word of every front end.
    pub fn word(&self) -> &'static str {
        match self {
            Status::Complete => "complete",
            Status::Suspect(_) => "suspect",
            Status::Stopped(_) => "incomplete",
        }
    }

    /// Why the result is doubtful, if it is.
    pub fn doubt(&self) -> Option<&Doubt> {
        match self {
            Status::Suspect(d) => Some(d),
            _ => None,
        }
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
    /// The energy audit stopped the run at `time` (s): the energy it created, over the energy it
    /// held or was given, reached `gain`, beyond `limit` — a blown-up run
    /// ([`crate::solve::EnergyBalance`]).
    EnergyRunaway {
        /// Time of the step at which it was stopped (s).
        time: f64,
        /// `(H − H(0) − W + D) / E` there.
        gain: f64,
        /// The runaway limit.
        limit: f64,
    },
    /// The caller interrupted the run (Ctrl-C, a cancelled progress callback) at `time` (s; the
    /// simulated time reached, for a dynamic run).
    Interrupted {
        /// Simulated time reached (dynamics), if any.
        time: Option<f64>,
    },
    /// The caller interrupted a sweep (a static load sweep, a flutter analysis) with Ctrl-C or a
    /// cancelled progress callback after `done` of its `points` points; those are kept.
    SweepInterrupted {
        /// Points (load levels, or speeds of the eigen-analysis) completed.
        done: usize,
        /// Points of the whole sweep.
        points: usize,
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

/// Why a run that reached its end is doubtful.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Doubt {
    /// The energy balance `|H − H(0) − W + D| / E` of the run exceeded `limit`, first at `time`
    /// (s); its largest value was `max_error`, at `max_error_time`. The integration error is
    /// larger than the tolerance suggests.
    EnergyBalance {
        /// First time the error exceeded the limit (s).
        time: f64,
        /// Largest relative balance error of the run.
        max_error: f64,
        /// Its time (s).
        max_error_time: f64,
        /// The limit.
        limit: f64,
    },
}
