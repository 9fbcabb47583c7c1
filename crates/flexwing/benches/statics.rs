//! Benchmark of the paper's static cases (section 5.2.1), full model against reduced models.
//! Prints a Markdown table for docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench statics` (add `-- --quick` for a short run).
//!
//! Cases, on the Table 4 beam (L = 1 m, EI = 50 N·m², m = 0.2 kg/m):
//! * `tip`: dead vertical tip force 150 N, solved from rest in one call;
//! * `two-load sweep`: dead tip force F1 = 0, 10, …, 150 N with F2 = −150 N at mid-span, each
//!   point continued from the previous one (the paper's Figure 4).
//!
//! The tip case runs for n = 10 … 320 with reduced models beside, and the full model alone on to
//! n = 10 000, to show how a static solve grows with n (full: an O(n) chain sweep per Newton
//! iteration from 10 coordinates on, `solve/tangent.rs`, dense below; reduced: O(n r) per
//! iteration plus O(r³)).
//!
//! The reduced models include their own cost of building (modal analysis and projection) in a
//! separate column, since a user pays it once per model.

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{fmt_time, measure};

use flexwing::model::{AppliedLoads, Force, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::{solve_static, sweep_static, Modes, StaticOptions};
use std::time::Instant;

fn table4(n: usize) -> FullModel {
    flexwing::paper::table4_beam(n).expect("valid beam")
}

fn run<M: StructuralModel>(model: &M, loads: &AppliedLoads, sweep: bool) {
    let opts = StaticOptions::default();
    if sweep {
        let points: Vec<Vec<f64>> = (0..=15).map(|k| vec![10.0 * k as f64, 1.0]).collect();
        black_box(sweep_static(model, loads, &points, &opts).expect("sweep"));
    } else {
        black_box(solve_static(model, loads, &[1.0], &opts).expect("solve"));
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(30), 3)
    } else {
        (Duration::from_millis(300), 7)
    };
    println!("| case | n | model | dofs | wall time | spread | ratio to full | build (modes + projection) |");
    println!("|---|---|---|---|---|---|---|---|");
    for (name, sweep, sizes) in [
        ("tip 150 N", false, &[10, 20, 40, 80, 160, 320][..]),
        ("two-load sweep", true, &[10, 20, 40][..]),
    ] {
        for &n in sizes {
            let full = table4(n);
            let loads = if sweep {
                vec![
                    Load::PointForce {
                        span: 1.0,
                        force: Force::Dead { fx: 0.0, fy: 1.0 },
                    },
                    Load::PointForce {
                        span: 0.5,
                        force: Force::Dead {
                            fx: 0.0,
                            fy: -150.0,
                        },
                    },
                ]
            } else {
                vec![Load::PointForce {
                    span: 1.0,
                    force: Force::Dead { fx: 0.0, fy: 150.0 },
                }]
            };
            let applied = full.apply(&loads, "loads").expect("valid loads");
            let (t_full, s_full) = measure(budget, batches, || run(&full, &applied, sweep));
            println!(
                "| {name} | {n} | full | {} | {} | {:.0} % | 1 | – |",
                full.n_dofs(),
                fmt_time(t_full),
                100.0 * s_full
            );
            for r in [2, 3] {
                let (t_build, _) = measure(budget / 4, batches, || {
                    let modes = Modes::undeformed(&full).expect("modes");
                    black_box(ReducedModel::first(&full, modes.shapes(), r).expect("rom"));
                });
                let modes = Modes::undeformed(&full).expect("modes");
                let rom = ReducedModel::first(&full, modes.shapes(), r).expect("rom");
                let (t, s) = measure(budget, batches, || run(&rom, &applied, sweep));
                println!(
                    "| {name} | {n} | reduced r = {r} | {r} | {} | {:.0} % | {:.3} | {} |",
                    fmt_time(t),
                    100.0 * s,
                    t / t_full,
                    fmt_time(t_build)
                );
            }
        }
    }
    println!("\nTip 150 N, full model against n (slope: against the previous row)\n");
    println!("| n | wall time | slope | Newton iterations | tip (m) |");
    println!("|---|---|---|---|---|");
    let sizes: &[usize] = if quick {
        &[10, 100, 1000, 10_000]
    } else {
        &[10, 30, 100, 300, 1000, 3000, 10_000]
    };
    let mut prev: Option<(usize, f64)> = None;
    for &n in sizes {
        let full = table4(n);
        let loads = full
            .apply(
                &[Load::PointForce {
                    span: 1.0,
                    force: Force::Dead { fx: 0.0, fy: 150.0 },
                }],
                "loads",
            )
            .expect("valid loads");
        let opts = StaticOptions::default();
        let t = if n <= 1000 {
            measure(budget, batches, || run(&full, &loads, false)).0
        } else {
            // Median of three single runs.
            let mut v: Vec<f64> = (0..3)
                .map(|_| {
                    let s = Instant::now();
                    run(&full, &loads, false);
                    s.elapsed().as_secs_f64()
                })
                .collect();
            v.sort_by(f64::total_cmp);
            v[1]
        };
        let sol = solve_static(&full, &loads, &[1.0], &opts).expect("solve");
        let tip = full.node_positions(&full.kinematics(&sol.q))[n];
        let slope = prev.map_or("–".to_string(), |(n0, t0)| {
            format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln())
        });
        println!(
            "| {n} | {} | {slope} | {} | ({:.9}, {:.9}) |",
            fmt_time(t),
            sol.stats.iterations,
            tip[0],
            tip[1]
        );
        prev = Some((n, t));
    }
}
