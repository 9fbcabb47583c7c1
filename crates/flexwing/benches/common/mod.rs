//! Timing helpers shared by the benchmark binaries (no external harness: each bench prints a
//! Markdown table).
#![allow(dead_code)]

use std::time::{Duration, Instant};

/// Median and relative spread of the per-call time over `batches` batches of about `budget`
/// each.
pub fn measure(budget: Duration, batches: usize, mut f: impl FnMut()) -> (f64, f64) {
    // Calibrate the number of calls per batch.
    let start = Instant::now();
    let mut calls = 0u64;
    while start.elapsed() < budget / 10 || calls == 0 {
        f();
        calls += 1;
    }
    let per_call = start.elapsed().as_secs_f64() / calls as f64;
    let reps = ((budget.as_secs_f64() / per_call).ceil() as u64).max(1);
    let mut means: Vec<f64> = (0..batches)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            t.elapsed().as_secs_f64() / reps as f64
        })
        .collect();
    means.sort_by(f64::total_cmp);
    let median = means[means.len() / 2];
    (median, (means[means.len() - 1] - means[0]) / median)
}

pub fn fmt_time(s: f64) -> String {
    if s < 1e-6 {
        format!("{:.0} ns", s * 1e9)
    } else if s < 1e-3 {
        format!("{:.2} µs", s * 1e6)
    } else if s < 1.0 {
        format!("{:.2} ms", s * 1e3)
    } else {
        format!("{s:.2} s")
    }
}

/// CPU time of this thread (s): from `/proc/thread-self/schedstat` on Linux (on-CPU nanoseconds,
/// which a loaded machine does not inflate with waiting), else the wall clock since the first
/// call. The kernel may update it only at scheduler ticks (4 ms here): [`cpu_per_call`] runs long
/// enough for that not to matter.
pub fn cpu_time() -> f64 {
    static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse::<f64>().ok())
        .map_or_else(
            || START.get_or_init(Instant::now).elapsed().as_secs_f64(),
            |ns| ns * 1e-9,
        )
}

/// CPU time per call of `f`, repeating it until `total` of CPU time has been spent (at least
/// once): with a 4 ms tick, 0.2 s gives the figure to 2 %.
pub fn cpu_per_call(total: Duration, mut f: impl FnMut()) -> f64 {
    let start = cpu_time();
    let mut calls = 0u32;
    while calls == 0 || cpu_time() - start < total.as_secs_f64() {
        f();
        calls += 1;
    }
    (cpu_time() - start) / f64::from(calls)
}
