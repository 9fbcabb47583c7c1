//! Wall times of repeated runs of one computation (single-threaded, so wall time is its CPU time
//! on an idle machine).

use std::time::{Duration, Instant};

/// Wall times of repeated runs of one computation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Median time of one run (s).
    pub median: f64,
    /// Fastest sample (s per run).
    pub min: f64,
    /// Slowest sample (s per run).
    pub max: f64,
    /// Samples taken.
    pub samples: usize,
    /// Runs per sample (short computations are run several times per sample so that each sample
    /// lasts at least [`MIN_SAMPLE`]).
    pub runs_per_sample: usize,
}

/// Shortest duration of one timing sample: well above the clock's resolution.
pub const MIN_SAMPLE: Duration = Duration::from_millis(20);

impl Timing {
    /// Time `f`: `samples` samples, each of as many runs as it takes to last [`MIN_SAMPLE`]
    /// (found from a first, untimed-in-the-result, warm-up run).
    pub fn measure(samples: usize, mut f: impl FnMut()) -> Self {
        let start = Instant::now();
        f();
        let once = start.elapsed().as_secs_f64().max(1e-9);
        let runs = ((MIN_SAMPLE.as_secs_f64() / once).ceil() as usize).clamp(1, 100_000);
        let mut times: Vec<f64> = (0..samples.max(1))
            .map(|_| {
                let start = Instant::now();
                for _ in 0..runs {
                    f();
                }
                start.elapsed().as_secs_f64() / runs as f64
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let m = times.len();
        let median = if m % 2 == 1 {
            times[m / 2]
        } else {
            0.5 * (times[m / 2 - 1] + times[m / 2])
        };
        Self {
            median,
            min: times[0],
            max: times[m - 1],
            samples: m,
            runs_per_sample: runs,
        }
    }

    /// The result of `f` and its time, for a run too long to repeat (one sample of one run).
    pub fn once<T>(f: impl FnOnce() -> T) -> (T, Self) {
        let start = Instant::now();
        let value = f();
        let s = start.elapsed().as_secs_f64();
        let timing = Self {
            median: s,
            min: s,
            max: s,
            samples: 1,
            runs_per_sample: 1,
        };
        (value, timing)
    }

    /// Spread `(max − min) / median`, in %.
    pub fn spread_percent(&self) -> f64 {
        100.0 * (self.max - self.min) / self.median
    }

    /// `12.3 ms (±4 %, 5×20)`: median, spread and how it was measured.
    pub fn text(&self) -> String {
        format!(
            "{} ({:.0} %, {}×{})",
            duration_text(self.median),
            self.spread_percent(),
            self.samples,
            self.runs_per_sample
        )
    }
}

/// `12.3 ms`, `45.6 µs`, `1.23 s`.
pub fn duration_text(seconds: f64) -> String {
    if seconds >= 1.0 {
        format!("{seconds:.2} s")
    } else if seconds >= 1e-3 {
        format!("{:.2} ms", seconds * 1e3)
    } else {
        format!("{:.2} µs", seconds * 1e6)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timing_orders_its_samples() {
        let mut k = 0u64;
        let t = Timing::measure(3, || {
            for i in 0..1000 {
                k = k.wrapping_add(std::hint::black_box(i));
            }
        });
        assert!(t.min <= t.median && t.median <= t.max && t.min > 0.0);
        assert_eq!(t.samples, 3);
        assert_eq!(duration_text(0.0123), "12.30 ms");
        assert_eq!(duration_text(2.5e-5), "25.00 µs");
    }
}
