//! Running an analysis of a case: the plan from the case crate, the run from
//! `flexwing::analysis`, with the interpreter detached; then the outcome into its result object
//! and, for `check=True`, the first stopped model into a `SolverError` carrying the partial
//! result. [`Analysis`] is the one list of analyses: a new analysis is one variant, one arm in
//! [`execute`] and one converter in `convert/`. A case with `[aero]` runs the aeroelastic
//! static and dynamic analyses (the plans `flexwing static` and `flexwing dynamic` build for
//! it), never the structural ones with its `[aero]` table ignored.

use std::time::Instant;

use flexwing::analysis::aero::flutter::{FlutterOutcome, FlutterPlan};
use flexwing::analysis::aero::response::{AeroDynamicOutcome, AeroDynamicPlan};
use flexwing::analysis::aero::statics::{AeroStaticOutcome, AeroStaticPlan};
use flexwing::analysis::dynamics::{DynamicOutcome, DynamicPlan};
use flexwing::analysis::modes::{ModesOutcome, ModesPlan};
use flexwing::analysis::statics::{StaticOutcome, StaticPlan};
use flexwing::analysis::{self, Progress, Status};
use flexwing_case::{Case, CaseError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert;
use crate::errors;

/// An analysis of a case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Analysis {
    /// Natural modes (`[modes]`).
    Modes,
    /// Non-linear statics (`[[loads]]`, `[static]`); static aeroelastic equilibria with
    /// `[aero]`.
    Static,
    /// Non-linear dynamics (`[[loads]]`, `[dynamic]`); the aeroelastic response with `[aero]`.
    Dynamic,
    /// Flutter and divergence along `[aero.sweep]` (`[aero]`, `[flutter]`).
    Flutter,
}

impl Analysis {
    /// Every analysis, by name.
    pub const ALL: [(&'static str, Analysis); 4] = [
        ("modes", Analysis::Modes),
        ("static", Analysis::Static),
        ("dynamic", Analysis::Dynamic),
        ("flutter", Analysis::Flutter),
    ];

    /// The analysis called `name`, or an `InputError` naming `field`.
    pub fn parse(py: Python<'_>, name: &str, field: &str) -> PyResult<Self> {
        Self::ALL
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, a)| *a)
            .ok_or_else(|| {
                let names: Vec<String> = Self::ALL.iter().map(|(n, _)| format!("{n:?}")).collect();
                errors::input(
                    py,
                    field,
                    &format!(
                        "unknown analysis {name:?}; expected one of {}",
                        names.join(", ")
                    ),
                )
            })
    }
}

/// A finished analysis with its plan.
pub enum Outcome {
    /// Modes.
    Modes(Box<ModesPlan>, ModesOutcome),
    /// Statics, with the name of the swept load (for messages).
    Static(Box<StaticPlan>, StaticOutcome, Option<String>),
    /// Dynamics.
    Dynamic(Box<DynamicPlan>, DynamicOutcome),
    /// Static aeroelastic equilibria.
    AeroStatic(Box<AeroStaticPlan>, AeroStaticOutcome),
    /// Aeroelastic response.
    AeroDynamic(Box<AeroDynamicPlan>, AeroDynamicOutcome),
    /// Flutter.
    Flutter(Box<FlutterPlan>, FlutterOutcome),
}

/// Why an analysis produced no outcome.
pub enum Failure {
    /// The case does not make a valid plan.
    Case(CaseError),
    /// The analysis failed before any model ran (an invalid plan, the modal analysis).
    Library(flexwing::Error),
    /// A panic (a bug), caught.
    Panic(String),
}

impl Failure {
    /// The exception of the failure.
    pub fn to_py(&self, py: Python<'_>) -> PyErr {
        match self {
            Failure::Case(e) => errors::case(py, e),
            Failure::Library(e) => errors::library(py, e),
            Failure::Panic(m) => errors::internal(py, m),
        }
    }
}

/// Run `analysis` of `case` (no Python here: call it detached).
pub fn execute(
    case: &Case,
    analysis: Analysis,
    progress: &mut dyn Progress,
) -> Result<Outcome, Failure> {
    let run = || -> Result<Outcome, Failure> {
        Ok(match analysis {
            Analysis::Modes => {
                let plan = case.modes_plan().map_err(Failure::Case)?;
                let outcome = analysis::modes::run(&plan, progress)
                    .map_err(|e| Failure::Library(e.into()))?;
                Outcome::Modes(Box::new(plan), outcome)
            }
            Analysis::Static if case.is_aeroelastic() => {
                let plan = case.aero_static_plan().map_err(Failure::Case)?;
                let outcome =
                    analysis::aero::statics::run(&plan, progress).map_err(Failure::Library)?;
                Outcome::AeroStatic(Box::new(plan), outcome)
            }
            Analysis::Dynamic if case.is_aeroelastic() => {
                let plan = case.aero_dynamic_plan().map_err(Failure::Case)?;
                let outcome =
                    analysis::aero::response::run(&plan, progress).map_err(Failure::Library)?;
                Outcome::AeroDynamic(Box::new(plan), outcome)
            }
            Analysis::Flutter => {
                let plan = case.flutter_plan().map_err(Failure::Case)?;
                let outcome =
                    analysis::aero::flutter::run(&plan, progress).map_err(Failure::Library)?;
                Outcome::Flutter(Box::new(plan), outcome)
            }
            Analysis::Static => {
                let plan = case.static_plan().map_err(Failure::Case)?;
                let outcome = analysis::statics::run(&plan, progress).map_err(Failure::Library)?;
                let sweep = plan
                    .sweep
                    .as_ref()
                    .and_then(|s| case.loads.get(s.load))
                    .and_then(|l| l.name.clone());
                Outcome::Static(Box::new(plan), outcome, sweep)
            }
            Analysis::Dynamic => {
                let plan = case.dynamic_plan().map_err(Failure::Case)?;
                let outcome = analysis::dynamics::run(&plan, progress).map_err(Failure::Library)?;
                Outcome::Dynamic(Box::new(plan), outcome)
            }
        })
    };
    errors::catch(run).unwrap_or_else(|m| Err(Failure::Panic(m)))
}

/// The first thing that did not complete: the first model that stopped, else the first whose
/// result is suspect.
pub struct Incomplete<'py> {
    /// `"stopped"` or `"suspect"` (or the name of a status the bindings do not know yet).
    pub word: String,
    /// The model's label (`None`: not a model's run).
    pub model: Option<String>,
    /// Where and why, as data.
    pub stop: Option<Bound<'py, PyDict>>,
    /// `LABEL: MESSAGE`.
    pub message: String,
}

/// The first model of `runs` (label, status) that stopped, else the first that is not complete.
fn first_incomplete<'py>(
    py: Python<'py>,
    runs: &[(String, &Status)],
    _sweep: Option<&str>,
) -> PyResult<Option<Incomplete<'py>>> {
    let stopped = runs.iter().find(|(_, s)| s.stop().is_some());
    let first = stopped.or_else(|| runs.iter().find(|(_, s)| !s.is_complete()));
    let Some((label, status)) = first else {
        return Ok(None);
    };
    let (word, stop, message) = convert::status::status_fields(py, status)?;
    Ok(Some(Incomplete {
        word,
        model: Some(label.clone()),
        stop,
        message: format!("{label}: {}", message.unwrap_or_default()),
    }))
}

/// The result object of `outcome`, and what did not complete first (if anything);
/// `rust_time_s` is the wall time of [`execute`] (the Rust side of the call, plan included).
pub fn to_python<'py>(
    py: Python<'py>,
    outcome: &Outcome,
    rust_time_s: f64,
) -> PyResult<(Bound<'py, PyAny>, Option<Incomplete<'py>>)> {
    let (kind, raw, incomplete) = match outcome {
        Outcome::Modes(plan, o) => ("modes", convert::modes::raw(py, &plan.model, o)?, None),
        Outcome::Static(plan, o, sweep) => {
            let raw = convert::statics::raw(py, plan, o, sweep.as_deref())?;
            let runs: Vec<_> = o.runs.iter().map(|r| (r.kind.label(), &r.status)).collect();
            let mut incomplete = first_incomplete(py, &runs, sweep.as_deref())?;
            if incomplete.is_none() {
                if let Some(Err(e)) = &o.loaded_modes {
                    incomplete = Some(Incomplete {
                        word: "stopped".into(),
                        model: Some("loaded modes".into()),
                        stop: Some(convert::status::described(py, e)?),
                        message: format!("loaded modes: {e}"),
                    });
                }
            }
            ("static", raw, incomplete)
        }
        Outcome::Dynamic(plan, o) => {
            let runs: Vec<_> = o.runs.iter().map(|r| (r.kind.label(), &r.status)).collect();
            let raw = convert::dynamics::raw(py, plan, o)?;
            ("dynamic", raw, first_incomplete(py, &runs, None)?)
        }
        Outcome::AeroStatic(plan, o) => {
            let runs: Vec<_> = o.runs.iter().map(|r| (r.kind.label(), &r.status)).collect();
            let raw = convert::aero_statics::raw(py, plan, o)?;
            ("aero-static", raw, first_incomplete(py, &runs, None)?)
        }
        Outcome::AeroDynamic(plan, o) => {
            let runs: Vec<_> = o.runs.iter().map(|r| (r.kind.label(), &r.status)).collect();
            let raw = convert::aero_dynamics::raw(py, plan, o)?;
            ("aero-dynamic", raw, first_incomplete(py, &runs, None)?)
        }
        Outcome::Flutter(plan, o) => {
            // The equilibria stopping past the divergence speed is expected (the eigen-analysis
            // goes on): only the eigen-analysis and the p-k check make a run incomplete, as in
            // `flexwing flutter`.
            let runs: Vec<_> = o.runs.iter().map(|r| (r.kind.label(), &r.status)).collect();
            let raw = convert::flutter::raw(py, plan, o)?;
            ("flutter", raw, first_incomplete(py, &runs, None)?)
        }
    };
    raw.set_item("rust_time_s", rust_time_s)?;
    Ok((convert::build(py, kind, raw)?, incomplete))
}

/// The `SolverError` of an incomplete result.
pub fn incomplete_error(
    py: Python<'_>,
    result: &Bound<'_, PyAny>,
    incomplete: Incomplete<'_>,
) -> PyErr {
    errors::solver(
        py,
        &incomplete.message,
        incomplete.model.as_deref(),
        incomplete.stop.map(|d| d.into_any().unbind()),
        Some(result.clone().unbind()),
    )
}

/// Run `analysis` of `case` detached from the interpreter, with an optional progress callback;
/// with `check`, a model that stopped raises `SolverError` (carrying the partial result).
pub fn run_case<'py>(
    py: Python<'py>,
    case: &Case,
    analysis: Analysis,
    progress: Option<Py<PyAny>>,
    check: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let mut reporter = crate::progress::PyProgress::new(progress);
    let (outcome, rust_time_s) = py.detach(|| {
        let start = Instant::now();
        let outcome = execute(case, analysis, &mut reporter);
        (outcome, start.elapsed().as_secs_f64())
    });
    reporter.check()?;
    let outcome = outcome.map_err(|f| f.to_py(py))?;
    let (result, incomplete) = to_python(py, &outcome, rust_time_s)?;
    match incomplete {
        Some(i) if check => Err(incomplete_error(py, &result, i)),
        _ => Ok(result),
    }
}
