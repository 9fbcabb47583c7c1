//! `solve_many`: a batch of cases in one call, each case's status and error returned as data,
//! so that one bad or diverged case does not stop a sweep of thousands. Engine-agnostic: it is
//! the unit of work a Dask (or joblib, Ray, multiprocessing) task runs on a chunk of cases, and
//! it can itself spread the chunk over threads of this process (no global pool, no state kept
//! between calls, nothing written to disk).
//!
//! Every case is isolated: a case that cannot be read is an `"error"` item (read before
//! anything runs, each conversion bounded), a case whose analysis fails or panics is an
//! `"error"` item, and a result that cannot be built is an `"error"` item. Only the caller
//! stops a batch: a progress callback that raises, or a signal (Ctrl-C) — then no further case
//! starts, the running ones stop at their next check (`"interrupted"`), and that exception is
//! raised carrying the items computed so far (`result`, a list in input order).
//!
//! Worker threads (`threads >= 2`) run only the library: the calling thread collects their
//! cases in order of completion, calls the progress callback (so `done` counts up one by one,
//! on the caller's own thread and stack) and polls for signals.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use flexwing_case::{Analysis, Case};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays;
use crate::case::{case_from_dict, PyCase};
use crate::convert;
use crate::errors;
use crate::kwargs::Kwargs;
use crate::progress::{Flag, Serial, Signals, POLL};
use crate::run::{execute, incomplete_error, to_python, Done as Outcome, Failure};

/// One case's run: its outcome or failure, and its wall time.
type Done = (Result<Outcome, Failure>, f64);

/// The most threads a batch starts (a larger `threads` is an error naming it).
pub const MAX_THREADS: usize = 1024;

/// Stack of each worker thread: as a main thread's on Linux (the analyses of a long chain
/// recurse along it in places; Rust's 2 MiB default is left for the platform's threads).
const WORKER_STACK: usize = 8 << 20;

fn run_one(
    case: &Case,
    analysis: Analysis,
    progress: &mut dyn flexwing::analysis::Progress,
) -> Done {
    let start = Instant::now();
    let outcome = execute(case, analysis, progress);
    (outcome, start.elapsed().as_secs_f64())
}

/// The run of a case that could not be read: a placeholder, its item is the reading error.
fn not_read() -> Done {
    (
        Err(Failure::Panic("the case could not be read".into())),
        0.0,
    )
}

/// The batch's state on the calling thread: the runs received, the callback, signals.
struct Collect<'py> {
    py: Python<'py>,
    slots: Vec<Option<Done>>,
    progress: Option<Py<PyAny>>,
    signals: Signals,
    done: usize,
}

impl Collect<'_> {
    /// Store case `i`'s run and report it; whether the batch goes on.
    fn receive(&mut self, i: usize, done: Done) -> bool {
        self.slots[i] = Some(done);
        self.done += 1;
        if let Some(cb) = &self.progress {
            if self.signals.error.is_none() {
                let total = self.slots.len();
                if let Err(e) = cb.call1(self.py, (self.done, total)) {
                    self.signals.error = Some(e);
                }
            }
        }
        !self.signals.stop_attached(self.py)
    }
}

/// Run every runnable case on the calling thread, the interpreter released during each.
fn run_serial(c: &mut Collect<'_>, cases: &[Option<Case>], analysis: Analysis) {
    for (i, case) in cases.iter().enumerate() {
        let done = match case {
            None => not_read(),
            Some(case) => {
                let signals = &mut c.signals;
                c.py.detach(|| run_one(case, analysis, &mut Serial { signals }))
            }
        };
        if !c.receive(i, done) {
            break;
        }
    }
}

/// Run the cases on `threads` worker threads; the calling thread collects and reports.
fn run_parallel(c: &mut Collect<'_>, cases: &[Option<Case>], analysis: Analysis, threads: usize) {
    let total = cases.len();
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    let (tx, rx) = mpsc::channel::<(usize, Done)>();
    std::thread::scope(|s| {
        let mut started = 0;
        for k in 0..threads.min(total) {
            let tx = tx.clone();
            let (next, stop) = (&next, &stop);
            let work = move || loop {
                if stop.load(Ordering::Relaxed) {
                    break;
                }
                let i = next.fetch_add(1, Ordering::Relaxed);
                if i >= total {
                    break;
                }
                let done = match &cases[i] {
                    None => not_read(),
                    Some(case) => run_one(case, analysis, &mut Flag(stop)),
                };
                if tx.send((i, done)).is_err() {
                    break;
                }
            };
            let spawned = std::thread::Builder::new()
                .name(format!("flexwing-batch-{k}"))
                .stack_size(WORKER_STACK)
                .spawn_scoped(s, work);
            if spawned.is_ok() {
                started += 1;
            }
        }
        drop(tx);
        if started == 0 {
            // No thread could be started: run here.
            drop(rx);
            return run_serial(c, cases, analysis);
        }
        let mut rx = rx;
        loop {
            // The receiver moves into the detached wait and back (it is not `Sync`).
            let (received, back) = c.py.detach(move || (rx.recv_timeout(POLL), rx));
            rx = back;
            match received {
                Ok((i, done)) => {
                    if !c.receive(i, done) {
                        stop.store(true, Ordering::Relaxed);
                    }
                }
                Err(mpsc::RecvTimeoutError::Timeout) => {
                    if c.signals.stop_attached(c.py) {
                        stop.store(true, Ordering::Relaxed);
                    }
                }
                Err(mpsc::RecvTimeoutError::Disconnected) => break,
            }
        }
    });
}

/// The `BatchItem` of case `index` (`start` added): its outcome as data; a result that cannot
/// be built is an error item too. Only a `KeyboardInterrupt`-like exception (not an
/// `Exception`) raised while building it propagates.
fn item<'py>(
    py: Python<'py>,
    index: usize,
    done: Result<Done, PyErr>,
) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item("index", index)?;
    type Item<'py> = (String, Option<Bound<'py, PyAny>>, Option<PyErr>, f64);
    let built = |done: Result<Done, PyErr>| -> PyResult<Item<'py>> {
        Ok(match done {
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
        })
    };
    let (status, result, error, wall): Item<'py> = match built(done) {
        Ok(item) => item,
        Err(e) if !e.is_instance_of::<pyo3::exceptions::PyException>(py) => return Err(e),
        Err(e) => {
            let message = format!("the result could not be built: {}", e.value(py));
            (
                "error".into(),
                None,
                Some(errors::internal(py, &message)),
                0.0,
            )
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

/// A case of the batch: a `Case`, or a dict with the keys of a case file.
fn parse_case(c: &Bound<'_, PyAny>, i: usize) -> PyResult<Result<Case, PyErr>> {
    let py = c.py();
    if let Ok(case) = c.cast::<PyCase>() {
        return Ok(Ok(case.get().case.clone()));
    }
    if !c.is_instance_of::<PyDict>() {
        return Ok(Err(errors::argument_type(
            py,
            &format!("cases[{i}]"),
            "must be a Case or a dict with the keys of a case file",
        )));
    }
    match case_from_dict(c) {
        Ok(case) => Ok(Ok(case)),
        // The caller's own exception (a KeyboardInterrupt while reading) stops the batch.
        Err(e)
            if errors::foreign(py, &e)
                && !e.is_instance_of::<pyo3::exceptions::PyException>(py) =>
        {
            Err(e)
        }
        Err(e) => Ok(Err(e)),
    }
}

/// Solve ``analysis`` (``"static"``, ``"modes"``, ``"dynamic"`` or ``"flutter"``; with
/// ``[aero]``, ``"static"`` and ``"dynamic"`` are aeroelastic) for every case of ``cases``
/// (``Case`` objects or dicts with the case file's keys) and return one ``BatchItem`` per case,
/// in order (a ``Batch``: a list with ``to_pandas()`` and ``to_xarray()``): its ``index`` (``start`` + its position), ``status`` (``"complete"``,
/// ``"suspect"`` (an energy balance beyond its limit), ``"stopped"``, ``"interrupted"``,
/// ``"error"``), ``result``, ``error`` (the exception the case would raise, as data) and wall
/// time. No case's failure stops the others, and nothing is raised for them.
///
/// Keyword arguments: ``threads`` (default 1, at most 1024): threads of this process sharing
/// the cases, the interpreter released meanwhile; ``progress``: ``callback(done, total)``
/// after each case, on the calling thread, ``done`` counting 1, 2, …; ``start`` (default 0):
/// the index of the first case (for a chunk of a larger sweep). A callback that raises, or
/// Ctrl-C, stops the batch: no further case starts, the running ones stop at their next check,
/// and the exception is raised with the items computed so far as its ``result`` attribute.
#[pyfunction]
#[pyo3(signature = (cases, analysis = None, **kwargs))]
pub fn solve_many<'py>(
    py: Python<'py>,
    cases: &Bound<'py, PyAny>,
    analysis: Option<&Bound<'py, PyAny>>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    errors::guard(py, || solve_many_guarded(py, cases, analysis, kwargs))
}

fn solve_many_guarded<'py>(
    py: Python<'py>,
    cases: &Bound<'py, PyAny>,
    analysis: Option<&Bound<'py, PyAny>>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyAny>> {
    let kw = Kwargs::new(py, kwargs, &["threads", "progress", "start"], "solve_many")?;
    let analysis = match analysis {
        None => Analysis::Static,
        Some(a) => crate::run::parse(py, &arrays::text(a, "analysis")?, "analysis")?,
    };
    let threads = match kw.get("threads")? {
        None => 1,
        Some(t) => {
            let t = arrays::count(&t, "threads")?;
            if !(1..=MAX_THREADS).contains(&t) {
                return Err(errors::input(
                    py,
                    "threads",
                    &format!("must be between 1 and {MAX_THREADS}, got {t}"),
                ));
            }
            t
        }
    };
    let start = match kw.get("start")? {
        None => 0,
        Some(s) => arrays::count(&s, "start")?,
    };
    let progress =
        crate::progress::callback(py, kw.get("progress")?, "callback(done: int, total: int)")?;
    let _nesting = crate::progress::Nesting::enter(py)?;
    let iter = cases
        .try_iter()
        .map_err(|_| errors::argument_type(py, "cases", "must be an iterable of Case or dict"))?;
    let mut parsed: Vec<Result<Case, PyErr>> = Vec::new();
    for (i, c) in iter.enumerate() {
        parsed.push(parse_case(&c?, i)?);
    }
    let runnable: Vec<Option<Case>> = parsed.iter().map(|r| r.as_ref().ok().cloned()).collect();
    let mut collect = Collect {
        py,
        slots: (0..runnable.len()).map(|_| None).collect(),
        progress,
        signals: Signals::new(py)?,
        done: 0,
    };
    if threads <= 1 || runnable.len() <= 1 {
        run_serial(&mut collect, &runnable, analysis);
    } else {
        run_parallel(&mut collect, &runnable, analysis, threads);
    }
    let stopped_by = collect.signals.error.take();
    let items = PyList::empty(py);
    for (i, (case, done)) in parsed.into_iter().zip(collect.slots).enumerate() {
        let done = match (case, done) {
            (Err(e), Some(_)) => Err(e),
            (Ok(_), Some(d)) => Ok(d),
            // Not run: the batch was stopped before it.
            (_, None) => continue,
        };
        items.append(item(py, start + i, done)?)?;
    }
    // A `flexwing.Batch`: the list with the views of a sweep (to_pandas, to_xarray).
    let batch = py
        .import("flexwing._results")?
        .getattr("Batch")?
        .call1((items,))?;
    if let Some(e) = stopped_by {
        errors::set_attribute(py, &e, "result", batch.unbind());
        return Err(e);
    }
    Ok(batch)
}
