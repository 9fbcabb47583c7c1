//! Benchmark of the paper's static cases (section 5.2.1), full model against reduced models.
//! Prints a Markdown table for docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench statics` (add `-- --quick` for a short run).
//!
//! Cases, on the Table 4 beam (L = 1 m, EI = 50 N·m², m = 0.2 kg/m):
//! * `tip`: dead vertical tip force 150 N, solved from rest in one call;
//! * `two-load sweep`: dead tip force F1 = 0, 10, …, 150 N with F2 = −150 N at mid-span, each
//!   point continued from the previous one (the paper's Figure 4);
//! * `tip 750 N`: dead vertical tip force 750 N (α = 15) in one call from rest: load control
//!   follows the path in steps (Newton's first step from rest is refused);
//! * `arc-length S-curve`: the compressed beam of `tests/suite/statics_arclength.rs` (dead tip force
//!   1.5 × Euler and a tip moment M = −2 → 30 N·m, through two limit points), arc-length
//!   continuation with the default options from the equilibrium at M = −2 N·m.
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
use flexwing::solve::{
    arc_length_static, solve_static, sweep_static, ArcLengthOptions, Modes, StaticOptions,
};
use std::time::Instant;

fn table4(n: usize) -> FullModel {
    flexwing::paper::table4_beam(n).expect("valid beam")
}

#[derive(Clone, Copy, PartialEq)]
enum Case {
    Tip,
    Sweep,
    ArcLength,
}

fn run<M: StructuralModel>(model: &M, loads: &AppliedLoads, case: Case, start: &[f64]) {
    let opts = StaticOptions::default();
    match case {
        Case::Sweep => {
            let points: Vec<Vec<f64>> = (0..=15).map(|k| vec![10.0 * k as f64, 1.0]).collect();
            black_box(sweep_static(model, loads, &points, &opts).expect("sweep"));
        }
        Case::Tip => {
            black_box(solve_static(model, loads, &[1.0], &opts).expect("solve"));
        }
        Case::ArcLength => {
            let path = arc_length_static(
                model,
                loads,
                (start, &[1.0, -2.0]),
                &[1.0, 30.0],
                &ArcLengthOptions::default(),
            );
            black_box(path.expect("path"));
        }
    }
}

/// The start of the arc-length case (M = −2 N·m, by load control); empty for the others.
fn start<M: StructuralModel>(model: &M, loads: &AppliedLoads, case: Case) -> Vec<f64> {
    if case != Case::ArcLength {
        return Vec::new();
    }
    solve_static(model, loads, &[1.0, -2.0], &StaticOptions::default())
        .expect("start")
        .x
}

fn loads_of(case: Case, tip: f64) -> Vec<Load> {
    match case {
        Case::Sweep => vec![
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
        ],
        // Table 3's load (examples/paper_tip_force.toml) at `tip` N.
        Case::Tip => vec![flexwing::paper::table4_tip_force(tip)],
        Case::ArcLength => vec![
            Load::PointForce {
                span: 1.0,
                force: Force::Dead {
                    fx: -1.5 * std::f64::consts::PI.powi(2) * 50.0 / 4.0,
                    fy: 0.0,
                },
            },
            Load::Moment {
                span: 1.0,
                value: 1.0,
            },
        ],
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
    for (name, case, tip, sizes) in [
        (
            "tip 150 N",
            Case::Tip,
            150.0,
            &[10, 20, 40, 80, 160, 320][..],
        ),
        ("two-load sweep", Case::Sweep, 0.0, &[10, 20, 40][..]),
        ("tip 750 N", Case::Tip, 750.0, &[10, 20, 40, 80][..]),
        ("arc-length S-curve", Case::ArcLength, 0.0, &[20, 40][..]),
    ] {
        for &n in sizes {
            let full = table4(n);
            let applied = full
                .apply(&loads_of(case, tip), "loads")
                .expect("valid loads");
            let x0 = start(&full, &applied, case);
            let (t_full, s_full) = measure(budget, batches, || run(&full, &applied, case, &x0));
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
                let x0 = start(&rom, &applied, case);
                let (t, s) = measure(budget, batches, || run(&rom, &applied, case, &x0));
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
            measure(budget, batches, || run(&full, &loads, Case::Tip, &[])).0
        } else {
            // Median of three single runs.
            let mut v: Vec<f64> = (0..3)
                .map(|_| {
                    let s = Instant::now();
                    run(&full, &loads, Case::Tip, &[]);
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
