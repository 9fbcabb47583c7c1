//! The caller's side of a long call: the Python progress callback, signals (Ctrl-C), and
//! nesting.
//!
//! A long call (an analysis, a batch, a `Stepper.step`) runs detached from the interpreter and
//! polls [`Signals`] as the CLI polls Ctrl-C, through the library's `Progress::cancelled`: on
//! the main thread, at most every [`POLL`], it re-attaches and runs `PyErr_CheckSignals`, so a
//! Ctrl-C (or any signal whose Python handler raises) stops the call at the analysis' next
//! check (after the current integrator step, before the next sweep point). The call then
//! returns what was computed and raises the handler's exception — a `KeyboardInterrupt` —
//! carrying the partial result as its `result` attribute. Off the main thread Python runs no
//! signal handler, so nothing is polled there.
//!
//! A progress callback is called at most once per percent of the work, re-attached; its first
//! exception stops the call in the same way and is raised with the partial result.
//!
//! A progress callback may itself run an analysis; [`Nesting`] bounds how deep such calls nest
//! on one thread (each level holds the stack of an analysis), so that a callback that re-enters
//! without end raises `ReentrancyError` instead of overflowing the stack.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use flexwing::analysis::Progress;
use pyo3::prelude::*;

use crate::errors;

/// How often a long call polls for signals (at most; at the analysis' checks).
pub const POLL: Duration = Duration::from_millis(50);

/// How deep calls of the extension may nest on one thread (through progress callbacks).
pub const MAX_NESTED: usize = 16;

thread_local! {
    static DEPTH: Cell<usize> = const { Cell::new(0) };
    /// Whether this thread is Python's main thread (asked once per thread).
    static IS_MAIN: Cell<Option<bool>> = const { Cell::new(None) };
}

/// One level of nesting of long calls on this thread, left when dropped.
pub struct Nesting(());

impl Nesting {
    /// Enter a long call, or `ReentrancyError` if [`MAX_NESTED`] are running on this thread.
    pub fn enter(py: Python<'_>) -> PyResult<Self> {
        let depth = DEPTH.with(Cell::get);
        if depth >= MAX_NESTED {
            return Err(errors::reentrancy(
                py,
                "progress",
                &format!(
                    "an analysis run from inside {MAX_NESTED} nested analyses (a progress \
                     callback that starts an analysis, whose callback starts another, …): \
                     nesting is limited to {MAX_NESTED} levels"
                ),
            ));
        }
        DEPTH.with(|d| d.set(depth + 1));
        Ok(Self(()))
    }
}

impl Drop for Nesting {
    fn drop(&mut self) {
        DEPTH.with(|d| d.set(d.get().saturating_sub(1)));
    }
}

/// Signals reaching a call that runs detached: polled on the main thread, at most every
/// [`POLL`]; the first exception a signal handler raised is kept.
pub struct Signals {
    main: bool,
    last: Instant,
    /// The first exception (of a signal handler or of the progress callback).
    pub error: Option<PyErr>,
}

impl Signals {
    /// Signals for a call made on the current thread.
    pub fn new(py: Python<'_>) -> PyResult<Self> {
        let main = match IS_MAIN.with(Cell::get) {
            Some(main) => main,
            None => {
                let threading = py.import("threading")?;
                let main = threading
                    .call_method0("main_thread")?
                    .is(&threading.call_method0("current_thread")?);
                IS_MAIN.with(|m| m.set(Some(main)));
                main
            }
        };
        Ok(Self {
            main,
            last: Instant::now(),
            error: None,
        })
    }

    /// Whether the call is to stop: an exception is kept, or (polled now, on the main thread,
    /// if [`POLL`] has passed) a signal handler raised one. Call it detached.
    pub fn stop(&mut self) -> bool {
        if self.error.is_some() {
            return true;
        }
        if self.main && self.last.elapsed() >= POLL {
            self.last = Instant::now();
            if let Err(e) = Python::attach(|py| py.check_signals()) {
                self.error = Some(e);
            }
        }
        self.error.is_some()
    }

    /// [`Signals::stop`] from an attached caller (between the cases of a batch).
    pub fn stop_attached(&mut self, py: Python<'_>) -> bool {
        if self.error.is_none() && self.main && self.last.elapsed() >= POLL {
            self.last = Instant::now();
            if let Err(e) = py.check_signals() {
                self.error = Some(e);
            }
        }
        self.error.is_some()
    }
}

/// Check that `callback` (the `progress` argument) can be called, before anything runs.
pub fn callback(
    py: Python<'_>,
    callback: Option<Bound<'_, PyAny>>,
    signature: &str,
) -> PyResult<Option<Py<PyAny>>> {
    match callback {
        None => Ok(None),
        Some(c) if c.is_callable() => Ok(Some(c.unbind())),
        Some(c) => Err(errors::argument_type(
            py,
            "progress",
            &format!(
                "must be None or a callable, {signature}; got {}",
                crate::values::type_name(&c)
            ),
        )),
    }
}

/// Calls `callback(done, label)`: `done` the fraction (0 to 1) of the whole analysis, `label`
/// the model running (`"full"`, `"reduced-r2"`, …); polls [`Signals`]; cancels the analysis
/// on the first exception of either.
pub struct PyProgress {
    callback: Option<Py<PyAny>>,
    /// Signals, and the first exception.
    pub signals: Signals,
    index: usize,
    count: usize,
    label: String,
    last: f64,
}

impl PyProgress {
    /// A progress reporter calling `callback` (none: report nothing, poll signals only).
    pub fn new(py: Python<'_>, callback: Option<Py<PyAny>>) -> PyResult<Self> {
        Ok(Self {
            callback,
            signals: Signals::new(py)?,
            index: 0,
            count: 1,
            label: String::new(),
            last: -1.0,
        })
    }

    fn call(&mut self, fraction: f64) {
        let Some(cb) = &self.callback else { return };
        if self.signals.error.is_some() {
            return;
        }
        let done = ((self.index as f64 + fraction.clamp(0.0, 1.0)) / self.count.max(1) as f64)
            .clamp(0.0, 1.0);
        let label = self.label.clone();
        let result = Python::attach(|py| cb.call1(py, (done, label)).map(|_| ()));
        if let Err(e) = result {
            self.signals.error = Some(e);
        }
    }

    /// The first exception (of the callback or a signal handler), if any.
    pub fn take_error(&mut self) -> Option<PyErr> {
        self.signals.error.take()
    }
}

impl Progress for PyProgress {
    fn start(&mut self, index: usize, count: usize, label: &str) {
        self.index = index;
        self.count = count;
        label.clone_into(&mut self.label);
        self.last = 0.0;
        self.call(0.0);
    }

    fn advance(&mut self, fraction: f64) {
        if fraction - self.last >= 0.01 {
            self.last = fraction;
            self.call(fraction);
        }
    }

    fn finish(&mut self) {
        self.last = 1.0;
        self.call(1.0);
    }

    fn cancelled(&mut self) -> bool {
        self.signals.stop()
    }
}

/// A [`Progress`] that only reads a shared flag: a case of a batch on a worker thread, which
/// runs no Python (the calling thread polls signals and calls the callback).
pub struct Flag<'a>(pub &'a AtomicBool);

impl Progress for Flag<'_> {
    fn advance(&mut self, _fraction: f64) {}

    fn cancelled(&mut self) -> bool {
        self.0.load(Ordering::Relaxed)
    }
}

/// A [`Progress`] for a case of a batch run on the calling thread: it polls [`Signals`] and the
/// batch's flag.
pub struct Serial<'a> {
    /// The calling thread's signals.
    pub signals: &'a mut Signals,
}

impl Progress for Serial<'_> {
    fn advance(&mut self, _fraction: f64) {}

    fn cancelled(&mut self) -> bool {
        self.signals.stop()
    }
}
