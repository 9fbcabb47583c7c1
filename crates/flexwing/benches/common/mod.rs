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
