//! The progress bar of `flexwing dynamic` on stderr: simulated time over end time, one bar per
//! model. It stays hidden unless stderr is a terminal (and `--json` is off), and appears only
//! once the run has taken [`DELAY`], so that short runs print nothing.

use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Time after which the bar appears.
const DELAY: Duration = Duration::from_secs(1);
/// Resolution of the bar: positions per end time.
const TICKS: u64 = 1000;

/// Progress over the models of a run.
pub struct Progress {
    enabled: bool,
    end_time: f64,
    n_models: usize,
    start: Instant,
    shown: bool,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A reporter for `n_models` runs to `end_time` (s); `enabled` when a bar may be drawn.
    pub fn new(enabled: bool, end_time: f64, n_models: usize) -> Self {
        Self {
            enabled,
            end_time,
            n_models,
            start: Instant::now(),
            shown: false,
            bar: None,
        }
    }

    /// Begin model `k` (0-based) labelled `label`.
    pub fn start_model(&mut self, k: usize, label: &str) {
        if !self.enabled {
            return;
        }
        let target = if self.shown {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        let bar = ProgressBar::with_draw_target(Some(TICKS), target);
        if let Ok(style) = ProgressStyle::with_template(
            "{prefix} {wide_bar} {percent:>3}% of the simulated time, {elapsed} (eta {eta})",
        ) {
            bar.set_style(style);
        }
        bar.set_prefix(format!("{label} ({}/{})", k + 1, self.n_models));
        self.bar = Some(bar);
    }

    /// The integration of the current model reached time `t` (s).
    pub fn update(&mut self, t: f64) {
        let Some(bar) = &self.bar else {
            return;
        };
        if !self.shown && self.start.elapsed() >= DELAY {
            self.shown = true;
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        let fraction = (t / self.end_time).clamp(0.0, 1.0);
        bar.set_position((fraction * TICKS as f64) as u64);
    }

    /// The current model is done: clear its bar.
    pub fn finish_model(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
