//! How the run of one model ended, as data: which solver failed where, with the values it
//! stopped at ([`Stop`]), or why a result that reached its end is doubtful ([`Doubt`]). Each has
//! one wording, its `Display`, which every front end prints; with the `serde` feature each
//! serializes with the same names in every front end (the CLI's JSON, Python's dicts):
//!
//! ```text
//! Status   {"status": "complete" | "suspect" | "stopped" | "interrupted",
//!           "stop": {"reason": "integration", "error": {"kind": "too-many-steps", …,
//!                    "message": …}, "message": …} | null,
//!           "message": … | null}
//! ```

use std::fmt;

use crate::error::{InputError, SolveError};
use crate::solve::aeroelastic::FlutterStop;
use crate::text::short;

/// How the run of one model ended. More variants may follow, so match with a wildcard arm.
///
/// Serialized (feature `serde`) as `status` ([`Status::word`]), `stop` (the [`Stop`] or
/// [`Doubt`] with its `message`, or null) and `message` (the same one line, or null).
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

/// The words of [`Status::word`], from the best to the worst: what a whole analysis is when
/// one of its runs is (the worst wins).
pub const STATUS_WORDS: [&str; 4] = ["complete", "suspect", "stopped", "interrupted"];

impl Status {
    /// Whether every output time or sweep point was reached and every check passed.
    pub fn is_complete(&self) -> bool {
        matches!(self, Status::Complete)
    }

    /// `complete`, `suspect`, `stopped`, or `interrupted` (stopped by the caller: Ctrl-C, a
    /// cancelled progress): the one word of every front end.
    pub fn word(&self) -> &'static str {
        match self {
            Status::Complete => "complete",
            Status::Suspect(_) => "suspect",
            Status::Stopped(s) if s.is_interruption() => "interrupted",
            Status::Stopped(_) => "stopped",
        }
    }

    /// The worst word of `statuses` ([`STATUS_WORDS`] order), `complete` for none.
    pub fn worst<'a>(statuses: impl IntoIterator<Item = &'a Status>) -> &'static str {
        let rank = |w: &str| STATUS_WORDS.iter().position(|x| *x == w).unwrap_or(0);
        statuses
            .into_iter()
            .map(Status::word)
            .max_by_key(|w| rank(w))
            .unwrap_or("complete")
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

    /// Why the run did not complete, in one line ([`Stop`]'s or [`Doubt`]'s wording); `None`
    /// when it completed.
    pub fn message(&self) -> Option<String> {
        match self {
            Status::Complete => None,
            Status::Suspect(d) => Some(d.to_string()),
            Status::Stopped(s) => Some(s.to_string()),
        }
    }
}

/// Why a run stopped before its end. Serialized (feature `serde`) with its `reason`
/// (`"integration"`, `"static-point"`, …) beside its values; an error it carries is `error`
/// (with its `kind`, values and `message`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "reason", rename_all = "kebab-case")
)]
#[non_exhaustive]
pub enum Stop {
    /// The time integration stopped: the error says where (its time) and why.
    Integration(#[cfg_attr(feature = "serde", serde(serialize_with = "ser::error"))] SolveError),
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
        /// The name of the swept load (the plan's `load_names`); `None` without a sweep.
        load: Option<String>,
        /// The solver's error.
        #[cfg_attr(feature = "serde", serde(serialize_with = "ser::described"))]
        error: SolveError,
    },
    /// The initial static deflection of a dynamic run (under the loads named `loads`), or the
    /// initial equilibrium of an aeroelastic response (`loads` empty), failed.
    InitialState {
        /// Names of the loads of the static deflection.
        loads: Vec<String>,
        /// The static solver's error.
        #[cfg_attr(feature = "serde", serde(serialize_with = "ser::described"))]
        error: SolveError,
    },
    /// The modes about the full model's last static equilibrium (a static analysis' loaded
    /// modes) were not found; the equilibria are kept.
    LoadedModes(#[cfg_attr(feature = "serde", serde(serialize_with = "ser::error"))] SolveError),
    /// The equations of motion could not be set up for this model.
    Equations(#[cfg_attr(feature = "serde", serde(serialize_with = "ser::error"))] InputError),
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
        #[cfg_attr(feature = "serde", serde(serialize_with = "ser::described"))]
        error: SolveError,
    },
    /// The flutter analysis found no static equilibrium at `speed` (m/s) to linearize about;
    /// its data up to there are kept.
    FlutterEquilibrium {
        /// Speed attempted (m/s).
        speed: f64,
        /// The static solver's error.
        #[cfg_attr(feature = "serde", serde(serialize_with = "ser::described"))]
        error: SolveError,
    },
    /// A linearization found no stable static equilibrium at `speed` (m/s, the value of the
    /// caller's key `field`) to linearize about: past the divergence speed, or the static solver
    /// failed.
    LinearizationEquilibrium {
        /// The caller's name of the speed (`aero.flight.speed`).
        field: String,
        /// The speed (m/s).
        speed: f64,
        /// The static solver's error.
        #[cfg_attr(feature = "serde", serde(serialize_with = "ser::described"))]
        error: SolveError,
    },
    /// The linear model of a turbulence analysis at `speed` (m/s) has `count` unstable poles
    /// (past the flutter speed): its response to turbulence is not stationary, it has no
    /// spectra.
    TurbulenceUnstable {
        /// How many poles have a positive real part.
        count: usize,
        /// The largest real part (1/s).
        real: f64,
        /// Its frequency `|Im s|` (rad/s).
        frequency: f64,
        /// The speed (m/s).
        speed: f64,
    },
    /// The poles of the linear model of a turbulence analysis at `speed` (m/s) were not
    /// computed (the real Schur form did not converge): its stability is unknown, so its
    /// spectra are not computed.
    TurbulencePolesUnknown {
        /// The speed (m/s).
        speed: f64,
    },
    /// The flutter analysis lost a branch between `from` and `speed` (m/s), or (`branch:
    /// None`) needed more sub-steps than its cap there
    /// ([`crate::solve::aeroelastic::FlutterStop::BranchLost`]); its data up to there are kept.
    FlutterBranchLost {
        /// Branch index, if one branch was lost.
        branch: Option<usize>,
        /// The last speed of the plan reached (m/s).
        from: f64,
        /// Speed attempted (m/s).
        speed: f64,
        /// Sub-steps accepted in the interval before the stop.
        substeps: usize,
    },
}

impl Stop {
    /// Whether the caller stopped the run (Ctrl-C, a cancelled progress callback).
    pub fn is_interruption(&self) -> bool {
        matches!(
            self,
            Stop::Interrupted { .. } | Stop::SweepInterrupted { .. }
        )
    }

    /// The stop of a flutter analysis that stopped with `stop` after `done` of its `points`
    /// speeds: its cancellation is a [`Stop::SweepInterrupted`].
    pub(crate) fn of_flutter(stop: FlutterStop, done: usize, points: usize) -> Self {
        match stop {
            FlutterStop::Equilibrium { speed, error } => Stop::FlutterEquilibrium { speed, error },
            FlutterStop::BranchLost {
                branch,
                from,
                speed,
                substeps,
            } => Stop::FlutterBranchLost {
                branch,
                from,
                speed,
                substeps,
            },
            FlutterStop::Cancelled { .. } => Stop::SweepInterrupted { done, points },
        }
    }
}

impl fmt::Display for Stop {
    /// One line saying why the run stopped: where, and what the solver said.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Stop::Integration(e) => write!(f, "{e}"),
            Stop::InitialState { loads, error } if loads.is_empty() => {
                write!(f, "the initial static deflection failed: {error}")
            }
            Stop::InitialState { loads, error } => write!(
                f,
                "the initial static deflection under {} failed: {error}",
                loads.join(", ")
            ),
            Stop::StaticPoint {
                point,
                points,
                scale,
                reached,
                load: Some(name),
                error,
            } => {
                let reached = reached
                    .map(|r| format!(", converged up to scale {}", short(r)))
                    .unwrap_or_default();
                write!(
                    f,
                    "stopped at sweep point {} of {points} ({name} scale {}{reached}): {error}",
                    point + 1,
                    short(*scale),
                )
            }
            Stop::StaticPoint { error, .. } => write!(f, "{error}"),
            Stop::Equations(e) => write!(f, "{e}"),
            Stop::LoadedModes(e) => write!(f, "{e}"),
            Stop::SpeedPoint {
                point,
                points,
                speed,
                error,
            } => write!(
                f,
                "stopped at speed {} of {points} (U = {} m/s): {error}",
                point + 1,
                short(*speed)
            ),
            Stop::FlutterEquilibrium { speed, error } => {
                let stop = FlutterStop::Equilibrium {
                    speed: *speed,
                    error: error.clone(),
                };
                write!(f, "{stop}")
            }
            Stop::LinearizationEquilibrium {
                field,
                speed,
                error,
            } => write!(
                f,
                "{field} = {} m/s: no stable static equilibrium to linearize about (past the \
                 divergence speed, or the static solver failed): {error}",
                short(*speed)
            ),
            Stop::TurbulenceUnstable {
                count,
                real,
                frequency,
                speed,
            } => write!(
                f,
                "the linear model at {} m/s has {count} unstable pole{} (the largest real part \
                 {} 1/s at {} rad/s: past the flutter speed): its response to turbulence is not \
                 stationary and has no spectra",
                short(*speed),
                if *count == 1 { "" } else { "s" },
                short(*real),
                short(*frequency)
            ),
            Stop::TurbulencePolesUnknown { speed } => write!(
                f,
                "the poles of the linear model at {} m/s were not computed (the Schur form did \
                 not converge): its stability is unknown, and its response to turbulence is not \
                 computed",
                short(*speed)
            ),
            Stop::FlutterBranchLost {
                branch,
                from,
                speed,
                substeps,
            } => {
                let stop = FlutterStop::BranchLost {
                    branch: *branch,
                    from: *from,
                    speed: *speed,
                    substeps: *substeps,
                };
                write!(f, "{stop}")
            }
            Stop::EnergyRunaway { time, gain, limit } => write!(
                f,
                "stopped at t = {} s: the run created energy that no load supplied, {} times the \
                 energy it held or was given (limit energy_runaway = {}): a blown-up run",
                short(*time),
                short(*gain),
                short(*limit)
            ),
            Stop::Interrupted { time: Some(t) } => write!(
                f,
                "interrupted at t = {} s; the output up to there is kept",
                short(*t)
            ),
            Stop::Interrupted { time: None } => write!(f, "interrupted before it started"),
            Stop::SweepInterrupted { done, points } => write!(
                f,
                "interrupted after {done} of {points} points; the points computed are kept"
            ),
        }
    }
}

/// Why a run that reached its end is doubtful. Serialized (feature `serde`) with its `reason`
/// (`"energy-balance"`) beside its values.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "reason", rename_all = "kebab-case")
)]
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

impl fmt::Display for Doubt {
    /// One line saying why the result is doubtful and what to do.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Doubt::EnergyBalance {
                time,
                max_error,
                max_error_time,
                limit,
            } => write!(
                f,
                "the energy balance |H − H(0) − W + D| / E exceeded its limit {} at t = {} s \
                 (largest {} at t = {} s): the integration error is larger than the tolerances \
                 suggest; tighten rtol and atol (or max_step), or raise energy_tolerance",
                short(*limit),
                short(*time),
                short(*max_error),
                short(*max_error_time)
            ),
        }
    }
}

/// The serialized forms: an error or a stop with its one-line `message` beside its values.
#[cfg(feature = "serde")]
pub(crate) mod ser {
    use std::fmt::Display;

    use serde::{Serialize, Serializer};

    /// `value`'s fields and `message`, its `Display`.
    #[derive(Serialize)]
    pub(crate) struct Described<'a, T: Serialize> {
        #[serde(flatten)]
        value: &'a T,
        message: String,
    }

    impl<'a, T: Serialize + Display> Described<'a, T> {
        pub(crate) fn new(value: &'a T) -> Self {
            Self {
                value,
                message: value.to_string(),
            }
        }
    }

    /// A field serialized as [`Described`].
    pub(crate) fn described<T: Serialize + Display, S: Serializer>(
        value: &T,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        Described::new(value).serialize(s)
    }

    /// The content of a variant that wraps an error: `{"error": described}`.
    pub(crate) fn error<T: Serialize + Display, S: Serializer>(
        value: &T,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Wrapped<'a, T: Serialize> {
            error: Described<'a, T>,
        }
        Wrapped {
            error: Described::new(value),
        }
        .serialize(s)
    }

    impl Serialize for super::Status {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            #[derive(Serialize)]
            #[serde(untagged)]
            enum Detail<'a> {
                Stop(Described<'a, super::Stop>),
                Doubt(Described<'a, super::Doubt>),
            }
            #[derive(Serialize)]
            struct Data<'a> {
                status: &'static str,
                stop: Option<Detail<'a>>,
                message: Option<String>,
            }
            let stop = match self {
                super::Status::Complete => None,
                super::Status::Suspect(d) => Some(Detail::Doubt(Described::new(d))),
                super::Status::Stopped(stop) => Some(Detail::Stop(Described::new(stop))),
            };
            Data {
                status: self.word(),
                stop,
                message: self.message(),
            }
            .serialize(s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_the_worst_of_several() {
        let stopped = Status::Stopped(Stop::Interrupted { time: None });
        assert_eq!(stopped.word(), "interrupted");
        let runaway = Status::Stopped(Stop::EnergyRunaway {
            time: 0.5,
            gain: 9.5,
            limit: 9.0,
        });
        assert_eq!(runaway.word(), "stopped");
        assert_eq!(Status::worst([&Status::Complete, &runaway]), "stopped");
        assert_eq!(Status::worst([&runaway, &stopped]), "interrupted");
        assert_eq!(Status::worst([]), "complete");
        assert_eq!(
            runaway.message().unwrap(),
            "stopped at t = 0.5 s: the run created energy that no load supplied, 9.5 times the \
             energy it held or was given (limit energy_runaway = 9): a blown-up run"
        );
    }

    #[test]
    fn a_static_point_names_the_swept_load() {
        let error = SolveError::StaticUnstable {
            load_factor: 0.5,
            attempted: 0.6,
        };
        let mut stop = Stop::StaticPoint {
            point: 3,
            points: 4,
            scale: 2.0,
            reached: Some(1.5),
            load: Some("F".into()),
            error: error.clone(),
        };
        assert!(stop
            .to_string()
            .starts_with("stopped at sweep point 4 of 4 (F scale 2, converged up to scale 1.5): "));
        if let Stop::StaticPoint { load, .. } = &mut stop {
            *load = None;
        }
        assert_eq!(stop.to_string(), error.to_string());
    }
}
