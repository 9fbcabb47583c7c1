//! How a running analysis reports its progress: a callback the library calls, as argmin's
//! observers; the front end draws it (a progress bar, a Python callback) or ignores it.

/// What an analysis tells its caller while it runs. An analysis of several models runs them one
/// after the other: `start` names each, `advance` reports the fraction of its work done, `finish`
/// ends it.
///
/// A closure `|fraction: f64| …` is a `Progress` that sees only the fractions;
/// [`NoProgress`] ignores everything.
pub trait Progress {
    /// Model `index` (0-based) of `count`, called `label`, begins.
    fn start(&mut self, index: usize, count: usize, label: &str) {
        let _ = (index, count, label);
    }
    /// The current model has done `fraction` (0 to 1) of its work.
    fn advance(&mut self, fraction: f64);
    /// The current model is done (complete or not).
    fn finish(&mut self) {}
    /// Whether the caller wants the analysis to stop (Ctrl-C, a cancel button): polled after
    /// every integrator step and between static points and models; the analysis then returns
    /// what it computed, the runs stopped with [`super::Stop::Interrupted`]. Default: never.
    fn cancelled(&mut self) -> bool {
        false
    }
}

impl<F: FnMut(f64)> Progress for F {
    fn advance(&mut self, fraction: f64) {
        self(fraction)
    }
}

/// A [`Progress`] that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn advance(&mut self, _fraction: f64) {}
}
