//! Benchmark of the set-up work at large n: beam set-up (calibration), the lowest modes, and a
//! reduced model with 4 modes, against n = 10 … 10 000. Prints Markdown tables with the local
//! slope `log(t₂/t₁) / log(n₂/n₁)` against the previous row.
//!
//! Run: `cargo bench -p flexwing --bench modes` (add `-- --quick` for a short run, `-- setup` or
//! `-- modes` for one part; `FLEXWING_BENCH_MAX_N` caps n).

use std::hint::black_box;
use std::time::{Duration, Instant};

mod common;
use common::{fmt_time, measure};

use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
use flexwing::model::{FullModel, ReducedModel};
use flexwing::paper;
use flexwing::solve::Modes;

/// The `r` lowest modes (the path a user of the library takes).
fn lowest(model: &FullModel, r: usize) -> Modes {
    Modes::lowest(model, r).expect("modes")
}

/// A tapered beam whose `EI` and mass are tables of `points` points (a smooth taper with a
/// ripple, so that every piece has its own slope).
fn table_section(points: usize) -> SectionProperties {
    let x: Vec<f64> = (0..points)
        .map(|k| 10.0 * k as f64 / (points - 1) as f64)
        .collect();
    let ei = x
        .iter()
        .map(|s| 4e4 * (1.0 - 0.075 * s) * (1.0 + 0.05 * (3.0 * s).sin()))
        .collect();
    let m = x.iter().map(|s| 1.2 - 0.06 * s).collect();
    SectionProperties {
        ei: Profile::Table {
            x: x.clone(),
            value: ei,
        },
        mass_per_length: Profile::Table { x, value: m },
        torsion: None,
    }
}

fn slope(t: f64, prev: Option<(usize, f64)>, n: usize) -> String {
    match prev {
        Some((n0, t0)) => format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln()),
        None => "–".into(),
    }
}

/// One timing: `measure` for fast calls, a few single runs (median) for slow ones.
fn time(budget: Duration, batches: usize, mut f: impl FnMut()) -> (f64, f64) {
    let start = Instant::now();
    f();
    let once = start.elapsed().as_secs_f64();
    if once > 0.2 * budget.as_secs_f64() {
        let mut t: Vec<f64> = (0..3)
            .map(|_| {
                let s = Instant::now();
                f();
                s.elapsed().as_secs_f64()
            })
            .collect();
        t.sort_by(f64::total_cmp);
        (t[1], (t[2] - t[0]) / t[1])
    } else {
        measure(budget, batches, f)
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(20), 3)
    } else {
        (Duration::from_millis(200), 5)
    };
    let max_n: usize = std::env::var("FLEXWING_BENCH_MAX_N")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(10_000);
    let ns: Vec<usize> = [10, 20, 40, 80, 160, 320, 640, 1000, 2000, 4000, 10_000]
        .into_iter()
        .filter(|&n| n <= max_n)
        .collect();

    let args: Vec<String> = std::env::args().collect();
    let only = |part: &str| {
        !args.iter().any(|a| a == "setup" || a == "modes") || args.iter().any(|a| a == part)
    };
    if only("setup") {
        setup(&ns, budget, batches);
    }
    if only("modes") {
        modes(&ns, budget, batches);
    }
}

fn setup(ns: &[usize], budget: Duration, batches: usize) {
    println!("\n### Beam set-up (`Beam::new`, tip-load calibration)\n");
    println!("| n | Table 4 beam | slope | Table 1 beam | slope | 300-point tables | slope |");
    println!("|---|---|---|---|---|---|---|");
    let tables = table_section(300);
    let mut prev: [Option<(usize, f64)>; 3] = [None; 3];
    for &n in ns {
        let d = Discretization::Uniform(n);
        let cases = [
            (paper::TABLE4_LENGTH, paper::table4_section()),
            (paper::TABLE1_LENGTH, paper::table1_section()),
            (10.0, tables.clone()),
        ];
        let mut row = format!("| {n} ");
        for (k, (l, s)) in cases.iter().enumerate() {
            let (t, _) = time(budget, batches, || {
                black_box(Beam::new(*l, s, &d, Calibration::TipLoad).expect("beam"));
            });
            row += &format!("| {} | {} ", fmt_time(t), slope(t, prev[k], n));
            prev[k] = Some((n, t));
        }
        println!("{row}|");
    }

    println!("\n### Beam set-up with long tables (`Beam::new`, n = 100)\n");
    println!("| table points | time | slope |");
    println!("|---|---|---|");
    let mut prev = None;
    for points in [300, 2000, 20_000] {
        let s = table_section(points);
        let d = Discretization::Uniform(100);
        let (t, _) = time(budget, batches, || {
            black_box(Beam::new(10.0, &s, &d, Calibration::TipLoad).expect("beam"));
        });
        println!(
            "| {points} | {} | {} |",
            fmt_time(t),
            slope(t, prev, points)
        );
        prev = Some((points, t));
    }
}

fn modes(ns: &[usize], budget: Duration, batches: usize) {
    for (name, build) in [
        (
            "Table 4 beam (bending, n coordinates)",
            paper::table4_beam as fn(usize) -> _,
        ),
        (
            "Table 1 beam (bending–torsion, 2n coordinates)",
            paper::table1_beam,
        ),
    ] {
        println!("\n### Lowest modes and a reduced model with 4 modes, {name}\n");
        println!(
            "| n | 4 modes | slope | 10 modes | slope | reduced model r = 4 | slope | \
             solver (10 modes) | K_T⁻¹M products |"
        );
        println!("|---|---|---|---|---|---|---|---|---|");
        let mut prev: [Option<(usize, f64)>; 3] = [None; 3];
        for &n in ns {
            let full = build(n).expect("beam");
            let mut row = format!("| {n} ");
            for (k, r) in [4, 10].into_iter().enumerate() {
                let (t, _) = time(budget, batches, || {
                    black_box(lowest(&full, r));
                });
                row += &format!("| {} | {} ", fmt_time(t), slope(t, prev[k], n));
                prev[k] = Some((n, t));
            }
            let (t, _) = time(budget, batches, || {
                let modes = lowest(&full, 4);
                black_box(ReducedModel::first(&full, modes.shapes(), 4).expect("rom"));
            });
            row += &format!("| {} | {} ", fmt_time(t), slope(t, prev[2], n));
            prev[2] = Some((n, t));
            let stats = lowest(&full, 10).stats();
            row += &format!("| {:?} | {} ", stats.method, stats.operator_applications);
            println!("{row}|");
        }
    }
}
