//! Running an analysis of a case through the library's one dispatcher: the plan from the case
//! crate (`Case::plan`, which picks the aeroelastic plans for a case with `[aero]`), the run from
//! `flexwing::analysis::run` with the interpreter detached; then the outcome into its result
//! object (`convert/`) and, for `check=True`, the first model that did not complete into a
//! `SolverError` carrying the partial result. A new analysis of the library needs one arm in
//! [`to_python`] and one converter in `convert/` here: its plan and run come with the library's
//! `Plan` and the case crate's `Analysis`.

use std::time::Instant;

use flexwing::analysis::{self, Outcome, Plan, Progress};
use flexwing_case::{Analysis, Case, CaseError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert;
use crate::errors;
use crate::progress::PyProgress;

/// The analysis called `name` (`"modes"`, `"static"`, `"dynamic"`, `"flutter"`), or an
/// `InputError` naming `field`.
pub fn parse(py: Python<'_>, name: &str, field: &str) -> PyResult<Analysis> {
    Analysis::from_name(name).ok_or_else(|| {
        let names: Vec<String> = Analysis::ALL
            .iter()
            .map(|a| format!("{:?}", a.name()))
            .collect();
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

/// A finished analysis with its plan.
pub struct Done {
    /// The plan run.
    pub plan: Plan,
    /// What it produced.
    pub outcome: Outcome,
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
) -> Result<Done, Failure> {
    let plan = match errors::catch(|| case.plan(analysis)) {
        Err(m) => return Err(Failure::Panic(m)),
        Ok(plan) => plan.map_err(Failure::Case)?,
    };
    execute_plan(plan, progress)
}

/// Run `plan` (no Python here: call it detached), a panic caught as [`Failure::Panic`].
pub fn execute_plan(plan: Plan, progress: &mut dyn Progress) -> Result<Done, Failure> {
    let run = || -> Result<Done, Failure> {
        let outcome = analysis::run(&plan, progress).map_err(Failure::Library)?;
        Ok(Done { plan, outcome })
    };
    errors::catch(run).unwrap_or_else(|m| Err(Failure::Panic(m)))
}

/// The first thing that did not complete: the first model that stopped, else the first whose
/// result is suspect.
pub struct Incomplete<'py> {
    /// `"stopped"`, `"interrupted"` or `"suspect"`.
    pub word: String,
    /// The model's label, or `"loaded modes"`.
    pub model: Option<String>,
    /// Where and why, as data.
    pub stop: Option<Bound<'py, PyDict>>,
    /// `LABEL: MESSAGE`.
    pub message: String,
}

/// What of `outcome` did not complete first: the first entry that stopped, else the first that
/// is not complete ([`Outcome::entries`]).
fn first_incomplete<'py>(py: Python<'py>, outcome: &Outcome) -> PyResult<Option<Incomplete<'py>>> {
    let incomplete = outcome.incomplete();
    let first = incomplete
        .iter()
        .find(|e| e.status.stop().is_some())
        .or_else(|| incomplete.first());
    let Some(entry) = first else {
        return Ok(None);
    };
    let (word, stop, message) = convert::status::status_fields(py, &entry.status)?;
    Ok(Some(Incomplete {
        word,
        model: Some(entry.label.clone()),
        stop,
        message: format!("{}: {}", entry.label, message.unwrap_or_default()),
    }))
}

/// The result object of `done`, and what did not complete first (if anything); `rust_time_s`
/// is the wall time of [`execute`] (the Rust side of the call, plan included).
pub fn to_python<'py>(
    py: Python<'py>,
    done: &Done,
    rust_time_s: f64,
) -> PyResult<(Bound<'py, PyAny>, Option<Incomplete<'py>>)> {
    use convert::*;
    let raw = match (&done.plan, &done.outcome) {
        (Plan::Modes(p), Outcome::Modes(o)) => modes::raw(py, &p.model, o)?,
        (Plan::Static(p), Outcome::Static(o)) => statics::raw(py, p, o)?,
        (Plan::Dynamic(p), Outcome::Dynamic(o)) => dynamics::raw(py, p, o)?,
        (Plan::AeroStatic(p), Outcome::AeroStatic(o)) => aero_statics::raw(py, p, o)?,
        (Plan::AeroDynamic(p), Outcome::AeroDynamic(o)) => aero_dynamics::raw(py, p, o)?,
        (Plan::Flutter(p), Outcome::Flutter(o)) => flutter::raw(py, p, o)?,
        (Plan::GustFamily(p), Outcome::GustFamily(o)) => gust_family::raw(py, p, o)?,
        (Plan::Linearize(p), Outcome::Linearize(o)) => linearize::raw(py, p, o)?,
        (Plan::Turbulence(p), Outcome::Turbulence(o)) => turbulence::raw(py, p, o)?,
        (Plan::Chain3d(p), Outcome::Chain3d(o)) => chain3d::raw(py, p, o)?,
        (plan, _) => {
            let what = format!("the outcome of a {} plan is of another kind", plan.name());
            return Err(errors::internal(py, &what));
        }
    };
    raw.set_item("rust_time_s", rust_time_s)?;
    let incomplete = first_incomplete(py, &done.outcome)?;
    let kind = match &done.plan {
        Plan::Chain3d(p) => convert::chain3d::kind(p),
        plan => plan.name().to_string(),
    };
    Ok((convert::build(py, &kind, raw)?, incomplete))
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

/// Run `plan_and_run` (an analysis: no Python inside) detached from the interpreter, with the
/// optional progress callback and signals polled ([`PyProgress`]), and build its result.
/// `check`: a model that did not complete raises `SolverError` carrying the partial result. A
/// callback's exception or a signal (Ctrl-C) stops the analysis at its next check: that
/// exception is raised, with the partial result as its `result` attribute.
pub fn run_detached<'py>(
    py: Python<'py>,
    progress: Option<Py<PyAny>>,
    check: bool,
    plan_and_run: impl FnOnce(&mut dyn Progress) -> Result<Done, Failure> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let _nesting = crate::progress::Nesting::enter(py)?;
    let mut reporter = PyProgress::new(py, progress)?;
    let (done, rust_time_s) = py.detach(|| {
        let start = Instant::now();
        let done = plan_and_run(&mut reporter);
        (done, start.elapsed().as_secs_f64())
    });
    // The callback's or a signal handler's exception wins over the analysis' own failure (it
    // may be why the analysis stopped); it is raised even when the analysis completed after
    // the last check (the caller asked to stop), with the result.
    let stopped_by = reporter.take_error();
    let done = match done {
        Err(f) => return Err(stopped_by.unwrap_or_else(|| f.to_py(py))),
        Ok(done) => done,
    };
    let (result, incomplete) = to_python(py, &done, rust_time_s)?;
    if let Some(e) = stopped_by {
        errors::set_attribute(py, &e, "result", result.unbind());
        return Err(e);
    }
    match incomplete {
        Some(i) if check => Err(incomplete_error(py, &result, i)),
        _ => Ok(result),
    }
}

/// Run `analysis` of `case` (see [`run_detached`]).
pub fn run_case<'py>(
    py: Python<'py>,
    case: &Case,
    analysis: Analysis,
    progress: Option<Py<PyAny>>,
    check: bool,
) -> PyResult<Bound<'py, PyAny>> {
    run_detached(py, progress, check, |p| execute(case, analysis, p))
}
