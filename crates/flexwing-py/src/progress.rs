//! A Python progress callback as an [`analysis::Progress`](flexwing::analysis::Progress): the
//! analysis runs detached from the interpreter and re-attaches only to call the callback, at
//! most once per percent of the work. The callback's first exception stops the calls and is
//! raised when the analysis returns (the library's analyses cannot be cancelled mid-run).

use flexwing::analysis::Progress;
use pyo3::prelude::*;

/// Calls `callback(done, label)`: `done` the fraction (0 to 1) of the whole analysis, `label`
/// the model running (`"full"`, `"reduced-r2"`, …).
pub struct PyProgress {
    callback: Option<Py<PyAny>>,
    /// The callback's first exception.
    pub error: Option<PyErr>,
    index: usize,
    count: usize,
    label: String,
    last: f64,
}

impl PyProgress {
    /// A progress reporter calling `callback` (none: report nothing).
    pub fn new(callback: Option<Py<PyAny>>) -> Self {
        Self {
            callback,
            error: None,
            index: 0,
            count: 1,
            label: String::new(),
            last: -1.0,
        }
    }

    fn call(&mut self, fraction: f64) {
        let Some(cb) = &self.callback else { return };
        if self.error.is_some() {
            return;
        }
        let done = ((self.index as f64 + fraction.clamp(0.0, 1.0)) / self.count.max(1) as f64)
            .clamp(0.0, 1.0);
        let label = self.label.clone();
        let result = Python::attach(|py| cb.call1(py, (done, label)).map(|_| ()));
        if let Err(e) = result {
            self.error = Some(e);
        }
    }

    /// Raise the callback's exception, if any.
    pub fn check(self) -> PyResult<()> {
        self.error.map_or(Ok(()), Err)
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
}
