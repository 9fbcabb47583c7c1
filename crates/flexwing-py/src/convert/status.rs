//! How a run ended, as data: [`Status`] becomes `"complete"`, `"suspect"` (the energy audit's
//! doubt, as a dict) or `"stopped"` with a `stop` dict
//! (`reason`, `message` and the values the solver stopped at), [`SolveError`] a dict with its
//! `kind`, `message` and values. Both enums are `#[non_exhaustive]`: a variant added in the
//! library gets its name (from its `Debug` form) and message here until it gets an arm of its
//! own, so a new status or stop reason never breaks the bindings.

use flexwing::analysis::{Doubt, Status, Stop};
use flexwing::solve::aeroelastic::FlutterStop;
use flexwing::text::short;
use flexwing::{SolveError, StaticFailure};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// `StepSizeTooSmall { … }` → `step-size-too-small`: the kebab-case name of an enum value.
pub fn variant_name(debug: &str) -> String {
    let head: String = debug
        .chars()
        .take_while(|c| c.is_alphanumeric() || *c == '_')
        .collect();
    let mut out = String::new();
    for (i, c) in head.chars().enumerate() {
        if c.is_uppercase() {
            if i > 0 {
                out.push('-');
            }
            out.extend(c.to_lowercase());
        } else {
            out.push(c);
        }
    }
    out
}

/// The solver error as a dict: `kind`, `message`, and its values (`time` in s, `load_factor`,
/// …).
pub fn solve_error_dict<'py>(py: Python<'py>, e: &SolveError) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("kind", variant_name(&format!("{e:?}")))?;
    d.set_item("message", e.to_string())?;
    if let Some(lf) = e.load_factor() {
        d.set_item("load_factor", lf)?;
    }
    match e {
        SolveError::StaticDiverged {
            attempted,
            iterations,
            residual_norm,
            cause,
            ..
        } => {
            d.set_item("attempted", attempted)?;
            d.set_item("iterations", iterations)?;
            d.set_item("residual_norm", residual_norm)?;
            failure(&d, cause)?;
        }
        SolveError::StaticUnstable { attempted, .. } => d.set_item("attempted", attempted)?,
        SolveError::ArcLengthStalled {
            points,
            arc_length,
            iterations,
            residual_norm,
            cause,
            ..
        } => {
            d.set_item("points", points)?;
            d.set_item("arc_length", arc_length)?;
            d.set_item("iterations", iterations)?;
            d.set_item("residual_norm", residual_norm)?;
            failure(&d, cause)?;
        }
        SolveError::ArcLengthTooManyPoints { points, .. } => d.set_item("points", points)?,
        SolveError::InvalidInput(i) => {
            d.set_item("field", &i.field)?;
            d.set_item("reason", &i.reason)?;
        }
        SolveError::StepSizeTooSmall { time, step } | SolveError::NewtonFailed { time, step } => {
            d.set_item("time", time)?;
            d.set_item("step", step)?;
        }
        SolveError::TooManySteps { time, steps } => {
            d.set_item("time", time)?;
            d.set_item("steps", steps)?;
        }
        SolveError::NonFinite { time } => d.set_item("time", time)?,
        SolveError::NonSymmetricTangent { asymmetry } => d.set_item("asymmetry", asymmetry)?,
        SolveError::IndefiniteTangent { non_positive } => {
            d.set_item("non_positive", non_positive)?
        }
        SolveError::ModesNotConverged { converged, wanted } => {
            d.set_item("converged", converged)?;
            d.set_item("wanted", wanted)?;
        }
        SolveError::BadEigenvalue { index, value } => {
            d.set_item("index", index)?;
            d.set_item("value", value)?;
        }
        _ => {}
    }
    Ok(d)
}

fn failure(d: &Bound<'_, PyDict>, cause: &StaticFailure) -> PyResult<()> {
    match cause {
        StaticFailure::Newton => d.set_item("cause", "newton"),
        StaticFailure::TooFar { rotation, limit } => {
            d.set_item("cause", "too-far")?;
            d.set_item("rotation", rotation)?;
            d.set_item("limit", limit)
        }
    }
}

/// The stop as a dict: `reason`, `message`, and where it stopped. `sweep` names the swept
/// load in messages.
pub fn stop_dict<'py>(
    py: Python<'py>,
    stop: &Stop,
    sweep: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("reason", variant_name(&format!("{stop:?}")))?;
    let message = match stop {
        Stop::Integration(e) => {
            let error = solve_error_dict(py, e)?;
            if let Some(t) = error.get_item("time")? {
                d.set_item("time", t)?;
            }
            d.set_item("error", error)?;
            e.to_string()
        }
        Stop::StaticPoint {
            point,
            points,
            scale,
            reached,
            error,
        } => {
            d.set_item("point", point)?;
            d.set_item("points", points)?;
            d.set_item("scale", scale)?;
            d.set_item("reached", reached)?;
            d.set_item("load_factor", error.load_factor())?;
            d.set_item("error", solve_error_dict(py, error)?)?;
            let reached = reached
                .map(|r| format!(", converged up to scale {}", short(r)))
                .unwrap_or_default();
            match sweep {
                Some(name) => format!(
                    "stopped at sweep point {} of {points} ({name} scale {}{reached}): {error}",
                    point + 1,
                    short(*scale)
                ),
                None => error.to_string(),
            }
        }
        Stop::InitialState(e) => {
            d.set_item("error", solve_error_dict(py, e)?)?;
            format!("the initial static deflection failed: {e}")
        }
        Stop::Equations(e) => {
            d.set_item("field", &e.field)?;
            d.set_item("reason_detail", &e.reason)?;
            e.to_string()
        }
        Stop::EnergyRunaway { time, gain, limit } => {
            d.set_item("time", time)?;
            d.set_item("gain", gain)?;
            d.set_item("limit", limit)?;
            format!(
                "stopped at t = {} s: the run created energy that no load supplied, {} times the \
                 energy it held or was given (limit energy_runaway = {}): a blown-up run",
                short(*time),
                short(*gain),
                short(*limit)
            )
        }
        Stop::Interrupted { time } => {
            d.set_item("time", time)?;
            match time {
                Some(t) => format!("interrupted at t = {} s", short(*t)),
                None => "interrupted before it started".into(),
            }
        }
        Stop::SpeedPoint {
            point,
            points,
            speed,
            error,
        } => {
            d.set_item("point", point)?;
            d.set_item("points", points)?;
            d.set_item("speed", speed)?;
            d.set_item("error", solve_error_dict(py, error)?)?;
            format!(
                "stopped at speed {} of {points} (U = {} m/s): {error}",
                point + 1,
                short(*speed)
            )
        }
        Stop::Flutter(FlutterStop::Equilibrium { speed, error }) => {
            d.set_item("reason", "flutter-equilibrium")?;
            d.set_item("speed", speed)?;
            d.set_item("error", solve_error_dict(py, error)?)?;
            format!(
                "no static equilibrium at U = {} m/s: {error}",
                short(*speed)
            )
        }
        Stop::Flutter(
            stop @ FlutterStop::BranchLost {
                branch,
                from,
                speed,
                substeps,
            },
        ) => {
            d.set_item("reason", "flutter-branch-lost")?;
            d.set_item("branch", branch)?;
            d.set_item("from", from)?;
            d.set_item("speed", speed)?;
            d.set_item("substeps", substeps)?;
            stop.to_string()
        }
        other => format!("{other:?}"),
    };
    d.set_item("message", &message)?;
    Ok(d)
}

/// `(status, stop, message)` of a run: `"complete"` with `None`s, or `"stopped"` with the stop
/// dict and its message. A status the bindings do not know yet is reported by its name.
pub fn status_fields<'py>(
    py: Python<'py>,
    status: &Status,
    sweep: Option<&str>,
) -> PyResult<(String, Option<Bound<'py, PyDict>>, Option<String>)> {
    Ok(match status {
        Status::Complete => ("complete".into(), None, None),
        Status::Stopped(stop) => {
            let d = stop_dict(py, stop, sweep)?;
            let message: Option<String> =
                d.get_item("message")?.map(|m| m.extract()).transpose()?;
            ("stopped".into(), Some(d), message)
        }
        Status::Suspect(Doubt::EnergyBalance {
            time,
            max_error,
            max_error_time,
            limit,
        }) => {
            let d = PyDict::new(py);
            d.set_item("reason", "energy-balance")?;
            d.set_item("time", time)?;
            d.set_item("max_error", max_error)?;
            d.set_item("max_error_time", max_error_time)?;
            d.set_item("limit", limit)?;
            let message = format!(
                "the energy balance |H − H(0) − W + D| / E exceeded its limit {} at t = {} s \
                 (largest {} at t = {} s): the integration error is larger than the tolerances \
                 suggest; tighten rtol and atol (or max_step), or raise energy_tolerance",
                short(*limit),
                short(*time),
                short(*max_error),
                short(*max_error_time)
            );
            d.set_item("message", &message)?;
            ("suspect".into(), Some(d), Some(message))
        }
        other => {
            let name = variant_name(&format!("{other:?}"));
            let d = PyDict::new(py);
            d.set_item("reason", &name)?;
            d.set_item("message", format!("{other:?}"))?;
            (name, Some(d), Some(format!("{other:?}")))
        }
    })
}

/// `"complete"` if every status is, else `"stopped"` if one stopped, else `"suspect"`.
pub fn overall<'a>(statuses: impl IntoIterator<Item = &'a Status>) -> &'static str {
    let mut word = "complete";
    for s in statuses {
        match s {
            Status::Complete => {}
            Status::Suspect(_) => {
                if word == "complete" {
                    word = "suspect";
                }
            }
            _ => return "stopped",
        }
    }
    word
}

/// Whether a status counts as complete for `check=True` (anything but `"complete"` raises).
pub fn is_complete(status: &Status) -> bool {
    status.is_complete()
}
