//! The progress bar of `flexwing dynamic` on stderr: simulated time over end time, one bar per
//! model. It stays hidden unless stderr is a terminal (and `--json` is off), and appears only
//! once the run has taken [`DELAY`], so that short runs print nothing.

use std::time::{Duration, Instant};

use flexwing::analysis;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Time after which the bar appears.
const DELAY: Duration = Duration::from_secs(1);
/// Resolution of the bar: positions per end time.
const TICKS: u64 = 1000;

/// Progress over the models of a run.
pub struct Progress {
    enabled: bool,
    start: Instant,
    shown: bool,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// A reporter; `enabled` when a bar may be drawn.
    pub fn new(enabled: bool) -> Self {
        Self {
            enabled,
            start: Instant::now(),
            shown: false,
            bar: None,
        }
    }
}

impl analysis::Progress for Progress {
    /// Begin model `k` (0-based) of `n_models`, labelled `label`.
    fn start(&mut self, k: usize, n_models: usize, label: &str) {
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
        bar.set_prefix(format!("{label} ({}/{n_models})", k + 1));
        self.bar = Some(bar);
    }

    /// The integration of the current model reached this fraction of the simulated time.
    fn advance(&mut self, fraction: f64) {
        let Some(bar) = &self.bar else {
            return;
        };
        if !self.shown && self.start.elapsed() >= DELAY {
            self.shown = true;
            bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        bar.set_position((fraction * TICKS as f64) as u64);
    }

    /// Whether Ctrl-C or `kill` came (after [`crate::interrupt::catch_interrupts`]).
    fn cancelled(&mut self) -> bool {
        crate::interrupt::interrupted()
    }

    /// The current model is done: clear its bar.
    fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}
