//! `solve_many`: a batch of cases in one call, each case's status and error returned as data,
//! so that one bad or diverged case does not stop a sweep of thousands. Engine-agnostic: it is
//! the unit of work a Dask (or joblib, Ray, multiprocessing) task runs on a chunk of cases, and
//! it can itself spread the chunk over threads of this process (no global pool, no state kept
//! between calls, nothing written to disk).

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;
use std::time::Instant;

use flexwing::analysis::NoProgress;
use flexwing_case::Case;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays;
use crate::case::{case_from_dict, PyCase};
use crate::convert;
use crate::errors;
use crate::kwargs::Kwargs;
use crate::run::{execute, incomplete_error, to_python, Done as Outcome, Failure};
use flexwing_case::Analysis;

/// One case's run: its outcome or failure, and its wall time.
type Done = (Result<Outcome, Failure>, f64);

fn run_one(case: &Case, analysis: Analysis) -> Done {
    let start = Instant::now();
    let outcome = execute(case, analysis, &mut NoProgress);
    (outcome, start.elapsed().as_secs_f64())
}

/// Call `progress(done, total)`, keeping its first exception.
fn report(progress: &Option<Py<PyAny>>, error: &Mutex<Option<PyErr>>, done: usize, total: usize) {
    let Some(cb) = progress else { return };
    let Ok(mut slot) = error.lock() else { return };
    if slot.is_some() {
        return;
    }
    if let Err(e) = Python::attach(|py| cb.call1(py, (done, total)).map(|_| ())) {
        *slot = Some(e);
    }
}

/// Run `analysis` of every case; `threads` of this process share the cases.
fn run_all(
    cases: &[Option<Case>],
    analysis: Analysis,
    threads: usize,
    progress: &Option<Py<PyAny>>,
    error: &Mutex<Option<PyErr>>,
) -> Vec<Option<Done>> {
    let total = cases.len();
    let next = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let slots: Vec<Mutex<Option<Done>>> = (0..total).map(|_| Mutex::new(None)).collect();
    let work = || loop {
        let i = next.fetch_add(1, Ordering::Relaxed);
        if i >= total {
            break;
        }
        if let Some(case) = &cases[i] {
            let done = run_one(case, analysis);
            if let Ok(mut slot) = slots[i].lock() {
                *slot = Some(done);
            }
        }
        let count = finished.fetch_add(1, Ordering::Relaxed) + 1;
        report(progress, error, count, total);
    };
    if threads <= 1 {
        work();
    } else {
        std::thread::scope(|s| {
            for _ in 0..threads.min(total.max(1)) {
                s.spawn(work);
            }
        });
    }
    slots
        .into_iter()
        .map(|m| m.into_inner().ok().flatten())
        .collect()
}

/// The `BatchItem` of case `index`.
fn item<'py>(
    py: Python<'py>,
    index: usize,
    done: Result<Done, PyErr>,
) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item("index", index)?;
    type Item<'py> = (String, Option<Bound<'py, PyAny>>, Option<PyErr>, f64);
    let (status, result, error, wall): Item<'py> = match done {
        Err(e) => ("error".into(), None, Some(e), 0.0),
        Ok((Err(f), wall)) => ("error".into(), None, Some(f.to_py(py)), wall),
        Ok((Ok(outcome), wall)) => {
            let (result, incomplete) = to_python(py, &outcome, wall)?;
            match incomplete {
                None => ("complete".into(), Some(result), None, wall),
                Some(i) => {
                    let word = i.word.clone();
                    let e = incomplete_error(py, &result, i);
                    (word, Some(result), Some(e), wall)
                }
            }
        }
    };
    d.set_item("status", status)?;
    d.set_item("result", result)?;
    let message = error.as_ref().map(|e| e.value(py).to_string());
    d.set_item("error", error.map(|e| e.into_value(py)))?;
    d.set_item("message", message)?;
    d.set_item("wall_time_s", wall)?;
    convert::build(py, "batch", d)
}

/// Solve ``analysis`` (``"static"``, ``"modes"``, ``"dynamic"`` or ``"flutter"``; with
/// ``[aero]``, ``"static"`` and ``"dynamic"`` are aeroelastic) for every case of ``cases``
/// (``Case`` objects or dicts with the case file's keys) and return one ``BatchItem`` per case,
/// in order: its ``status`` (``"complete"``, ``"suspect"`` (an energy balance beyond its limit),
/// ``"stopped"``, ``"error"``), ``result``, ``error``
/// (the exception the case would raise, as data) and wall time. No case's failure stops the
/// others, and nothing is raised for them.
///
/// Keyword arguments: ``threads`` (default 1): threads of this process sharing the cases, the
/// interpreter released meanwhile; ``progress``: ``callback(done, total)`` after each case.
#[pyfunction]
#[pyo3(signature = (cases, analysis = None, **kwargs))]
pub fn solve_many<'py>(
    py: Python<'py>,
    cases: &Bound<'py, PyAny>,
    analysis: Option<&Bound<'py, PyAny>>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    let kw = Kwargs::new(py, kwargs, &["threads", "progress"], "solve_many")?;
    let analysis = match analysis {
        None => Analysis::Static,
        Some(a) => crate::run::parse(py, &arrays::text(a, "analysis")?, "analysis")?,
    };
    let threads = match kw.get("threads")? {
        None => 1,
        Some(t) => {
            let t = arrays::count(&t, "threads")?;
            if t == 0 {
                return Err(errors::input(py, "threads", "must be at least 1, got 0"));
            }
            t
        }
    };
    let progress = kw.get("progress")?.map(Bound::unbind);
    let iter = cases
        .try_iter()
        .map_err(|_| errors::argument_type(py, "cases", "must be an iterable of Case or dict"))?;
    let mut parsed: Vec<Result<Case, PyErr>> = Vec::new();
    for (i, c) in iter.enumerate() {
        let c = c?;
        parsed.push(if let Ok(case) = c.cast::<PyCase>() {
            Ok(case.get().case.clone())
        } else if c.is_instance_of::<PyDict>() {
            case_from_dict(&c)
        } else {
            Err(errors::argument_type(
                py,
                &format!("cases[{i}]"),
                "must be a Case or a dict with the keys of a case file",
            ))
        });
    }
    let runnable: Vec<Option<Case>> = parsed.iter().map(|r| r.as_ref().ok().cloned()).collect();
    let error = Mutex::new(None);
    let done = errors::detached(py, || {
        run_all(&runnable, analysis, threads, &progress, &error)
    })?;
    if let Some(e) = error.into_inner().ok().flatten() {
        return Err(e);
    }
    parsed
        .into_iter()
        .zip(done)
        .enumerate()
        .map(|(i, (case, done))| {
            let done = match (case, done) {
                (Err(e), _) => Err(e),
                (Ok(_), Some(d)) => Ok(d),
                (Ok(_), None) => Err(errors::internal(py, "a case of the batch was not run")),
            };
            item(py, i, done)
        })
        .collect()
}
