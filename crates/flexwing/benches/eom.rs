//! Benchmark of one evaluation of the equations of motion: right-hand side and Jacobian of the full
//! model against n (bending-only Table 4 beam and coupled Table 1 beam), the reduced model's
//! right-hand side against r and n, and the reduced r = 2 run of the paper's case (b) end to end.
//! Prints Markdown tables for docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench eom` (add `-- --quick` for a short run).
//!
//! Each figure is the median over several batches of the mean time per call within a batch.
//! `slope` is the local exponent `log(t₂/t₁) / log(n₂/n₁)` against the previous row.

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{fmt_time, measure};

use flexwing::model::{FullModel, Load, ReducedModel};
use flexwing::solve::integrate::{Dopri5, Dopri5Options, OdeSystem, Tolerances};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction};
use nalgebra::DMatrix;

fn table4(n: usize) -> FullModel {
    flexwing::paper::table4_beam(n).expect("valid beam")
}

fn table1(n: usize) -> FullModel {
    flexwing::paper::table1_beam(n).expect("valid beam")
}

/// The loads of case (b) (the library's preset).
fn tip_force() -> Vec<Load> {
    flexwing::paper::sine_case(1).expect("case (b)").loads
}

/// The time histories of case (b)'s loads (the library's preset).
fn sine() -> Vec<TimeFunction> {
    let case = flexwing::paper::sine_case(1).expect("case (b)");
    case.time.into_iter().flatten().collect()
}

fn slope(t: f64, prev: Option<(usize, f64)>, n: usize) -> String {
    match prev {
        Some((n0, t0)) => format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln()),
        None => "–".into(),
    }
}

/// (right-hand side, Jacobian) time of the full model at a bent, moving state.
fn full_costs(model: &FullModel, budget: Duration, batches: usize) -> (f64, f64) {
    let nd = model.n_dofs();
    let none = model.apply(&[], "loads").expect("loads");
    let mut eom = EquationsOfMotion::new(model, &none, vec![], Gyroscopic::Exact, &Damping::None)
        .expect("eom");
    let q: Vec<f64> = (0..nd).map(|i| 0.02 * (i as f64).sin()).collect();
    let y = eom.state(&q, &vec![0.1; nd]);
    let mut dy = vec![0.0; 2 * nd];
    let mut jac = DMatrix::zeros(2 * nd, 2 * nd);
    let (t_rhs, _) = measure(budget, batches, || eom.rhs(0.0, black_box(&y), &mut dy));
    let jac_budget = if nd >= 320 { budget * 4 } else { budget };
    let (t_jac, _) = measure(jac_budget, batches, || {
        eom.jacobian(0.0, black_box(&y), &mut jac)
    });
    (t_rhs, t_jac)
}

fn reduced_rhs(full: &FullModel, r: usize, budget: Duration, batches: usize) -> f64 {
    let modes = Modes::undeformed(full).expect("modes");
    let rom = ReducedModel::first(full, modes.shapes(), r).expect("rom");
    let loads = full.apply(&tip_force(), "loads").expect("loads");
    let mut eom = EquationsOfMotion::new(&rom, &loads, sine(), Gyroscopic::Exact, &Damping::None)
        .expect("eom");
    let eta: Vec<f64> = (0..r).map(|i| 0.05 / (i + 1) as f64).collect();
    let etadot: Vec<f64> = (0..r).map(|i| 0.3 / (i + 1) as f64).collect();
    let y = eom.state(&eta, &etadot);
    let mut dy = vec![0.0; 2 * r];
    // Alternate two states, as an integrator does, so that nothing can be cached across calls.
    let mut y2 = y.clone();
    y2[0] *= 1.0001;
    let mut flip = false;
    let (t, _) = measure(budget, batches, || {
        flip = !flip;
        let s = if flip { &y } else { &y2 };
        eom.rhs(0.01, black_box(s), &mut dy);
    });
    t
}

/// Wall time of the paper's case (b) with the reduced model (r modes, n = 20), DOPRI5 at `rtol`,
/// output every 5 ms; and the number of right-hand sides.
fn case_b_reduced(r: usize, rtol: f64, budget: Duration, batches: usize) -> (f64, usize) {
    let full = table4(20);
    let loads = full.apply(&tip_force(), "loads").expect("loads");
    let modes = Modes::undeformed(&full).expect("modes");
    let rom = ReducedModel::first(&full, modes.shapes(), r).expect("rom");
    let t_out: Vec<f64> = (0..=200).map(|k| k as f64 * 0.005).collect();
    let run = || {
        let mut eom =
            EquationsOfMotion::new(&rom, &loads, sine(), Gyroscopic::Exact, &Damping::None)
                .expect("eom");
        let tolerances = Tolerances {
            rtol,
            atol: eom.state_atol(rtol * 1e-2),
        };
        let y0 = vec![0.0; 2 * r];
        let (_, stats) = Dopri5 {
            options: Dopri5Options {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, &t_out, &mut |_| {})
        .expect("integrates");
        stats.rhs_evaluations
    };
    let evaluations = run();
    let (t, _) = measure(budget, batches, || {
        black_box(run());
    });
    (t, evaluations)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(20), 3)
    } else {
        (Duration::from_millis(200), 5)
    };
    for (name, build) in [
        (
            "bending-only Table 4 beam, n dofs",
            table4 as fn(usize) -> FullModel,
        ),
        ("coupled Table 1 beam, 2n dofs", table1),
    ] {
        println!("\nFull model, exact γ, no loads: {name}\n");
        println!("| n | dofs | right-hand side | slope | Jacobian | slope |");
        println!("|---|---|---|---|---|---|");
        let (mut prev_r, mut prev_j) = (None, None);
        for n in [10, 20, 40, 80, 160, 320] {
            let model = build(n);
            let (tr, tj) = full_costs(&model, budget, batches);
            println!(
                "| {n} | {} | {} | {} | {} | {} |",
                model.n_dofs(),
                fmt_time(tr),
                slope(tr, prev_r, n),
                fmt_time(tj),
                slope(tj, prev_j, n)
            );
            prev_r = Some((n, tr));
            prev_j = Some((n, tj));
        }
    }

    println!("\nReduced model right-hand side (Table 4 beam, tip force 10 sin 20t N, exact γ)\n");
    println!("| n | r | right-hand side |");
    println!("|---|---|---|");
    let full20 = table4(20);
    for r in 1..=4 {
        let t = reduced_rhs(&full20, r, budget, batches);
        println!("| 20 | {r} | {} |", fmt_time(t));
    }
    let mut prev = None;
    println!("\n| n | r | right-hand side | slope |");
    println!("|---|---|---|---|");
    for n in [10, 20, 40, 80, 160, 320] {
        let t = reduced_rhs(&table4(n), 2, budget, batches);
        println!("| {n} | 2 | {} | {} |", fmt_time(t), slope(t, prev, n));
        prev = Some((n, t));
    }

    println!("\nCase (b), reduced model on n = 20, Dormand–Prince, 1 s, output every 5 ms\n");
    println!("| r | rtol | right-hand sides | wall time | per right-hand side |");
    println!("|---|---|---|---|---|");
    for (r, rtol) in [(2, 1e-4), (2, 1e-6), (4, 1e-4)] {
        let (t, evals) = case_b_reduced(r, rtol, budget * 2, batches);
        println!(
            "| {r} | {rtol:.0e} | {evals} | {} | {} |",
            fmt_time(t),
            fmt_time(t / evals as f64)
        );
    }
}
