//! Benchmark of the error weights (`EquationsOfMotion::state_atol`) on the paper's case (b) (tip
//! force 10 sin(20 t) N, 1 s, output every 5 ms, Table 4 beam): the full model and the reduced
//! models on the first r = 1 … 6 modes, integrated by Radau IIA with the same `rtol` and `atol`,
//! with their steps, right-hand sides, CPU time (of the thread, `common::cpu_time`), the tip error
//! against a tight run of the full model (model plus integration error) and against a tight run of
//! the same model (integration error alone). "before" uses the previous weights (`atol` on every
//! coordinate, `atol · M_kk(0) / (1 s)` on the momenta).
//!
//! Run: `cargo bench -p flexwing --bench error_weights` (add `-- --quick` for n = 20 only and
//! fewer settings).

use std::time::Duration;

mod common;
use common::{cpu_per_call, fmt_time};

use flexwing::model::{AppliedLoads, Force, Load, PlanarModel, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{IntegratorStats, Radau, RadauOptions, Tolerances};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction};
use nalgebra::DMatrix;

/// The weights before: `atol` on the coordinates, `atol · M_kk(0)` on the momenta.
fn previous_weights<M: StructuralModel>(model: &M, atol: f64) -> Vec<f64> {
    let n = model.n_dofs();
    let mut m0 = DMatrix::zeros(n, n);
    model.mass_matrix_into(&vec![0.0; n], &mut model.workspace(), &mut m0);
    let mut v = vec![atol; n];
    v.extend((0..n).map(|i| atol * m0[(i, i)]));
    v
}

fn tips<M: PlanarModel>(
    model: &M,
    loads: &AppliedLoads,
    rtol: f64,
    atol: f64,
    previous: bool,
) -> (Vec<[f64; 2]>, IntegratorStats) {
    let full = model.full_model();
    let tf = vec![TimeFunction::Sine {
        omega: 20.0,
        phase: 0.0,
    }];
    let mut eom =
        EquationsOfMotion::new(model, loads, tf, Gyroscopic::Exact, &Damping::None).expect("eom");
    let atol = if previous {
        previous_weights(model, atol)
    } else {
        eom.state_atol(atol)
    };
    let t: Vec<f64> = (0..=200).map(|k| k as f64 * 0.005).collect();
    let (traj, stats) = Radau {
        options: RadauOptions {
            tolerances: Tolerances { rtol, atol },
            ..Default::default()
        },
    }
    .integrate(
        &mut eom,
        0.0,
        &vec![0.0; 2 * model.n_dofs()],
        &t,
        &mut |_| {},
    )
    .expect("integrates");
    let tips = traj
        .y
        .iter()
        .map(|y| {
            let q = model.full_coordinates(&y[..model.n_dofs()]);
            let p = full.node_positions(&full.kinematics(&q))[full.n_elements()];
            [p[0], p[1]]
        })
        .collect();
    (tips, stats)
}

fn max_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let budget = Duration::from_millis(if quick { 100 } else { 300 });
    let sizes: &[usize] = if quick { &[20] } else { &[20, 40, 80] };
    // (rtol, atol, previous weights)
    let settings: Vec<(f64, f64, bool)> = if quick {
        vec![(1e-3, 1e-5, false), (1e-6, 1e-8, false), (1e-6, 1e-8, true)]
    } else {
        vec![
            (1e-3, 1e-5, false),
            (1e-4, 1e-6, false),
            (1e-6, 1e-8, false),
            (1e-6, 1e-8, true),
        ]
    };
    println!("Case (b), Radau IIA, the same rtol and atol for every model. Tip errors: max over the outputs against the full model at rtol 1e-10 (\"total\") and against the same model at rtol 1e-10 (\"integration\").");
    for &n in sizes {
        let full = flexwing::paper::table4_beam(n).expect("beam");
        let loads = full
            .apply(
                &[Load::PointForce {
                    span: 1.0,
                    force: Force::Dead { fx: 0.0, fy: 10.0 },
                }],
                "loads",
            )
            .expect("loads");
        let modes = Modes::undeformed(&full).expect("modes");
        let roms: Vec<ReducedModel> = (1..=6)
            .map(|r| ReducedModel::first(&full, modes.shapes(), r).expect("rom"))
            .collect();
        let (reference, _) = tips(&full, &loads, 1e-10, 1e-12, false);
        let rom_references: Vec<Vec<[f64; 2]>> = roms
            .iter()
            .map(|rom| tips(rom, &loads, 1e-10, 1e-12, false).0)
            .collect();
        for &(rtol, atol, previous) in &settings {
            println!(
                "\nn = {n}, rtol {rtol:.0e}, atol {atol:.0e} rad, {} weights\n",
                if previous {
                    "before: previous"
                } else {
                    "physical"
                }
            );
            println!("| model | steps (rejected) | RHS | Jacobians | CPU | ratio to full | tip error, total (m) | tip error, integration (m) |");
            println!("|---|---|---|---|---|---|---|---|");
            let (h, stats) = tips(&full, &loads, rtol, atol, previous);
            let t_full = cpu_per_call(budget, || {
                std::hint::black_box(tips(&full, &loads, rtol, atol, previous));
            });
            let e = max_distance(&h, &reference);
            println!(
                "| full | {} ({}) | {} | {} | {} | 1 | {e:.1e} | {e:.1e} |",
                stats.steps,
                stats.rejected_steps,
                stats.rhs_evaluations,
                stats.jacobian_evaluations,
                fmt_time(t_full)
            );
            for (rom, own) in roms.iter().zip(&rom_references) {
                let (h, stats) = tips(rom, &loads, rtol, atol, previous);
                let t = cpu_per_call(budget, || {
                    std::hint::black_box(tips(rom, &loads, rtol, atol, previous));
                });
                println!(
                    "| r = {} | {} ({}) | {} | {} | {} | {:.3} | {:.1e} | {:.1e} |",
                    rom.n_modes(),
                    stats.steps,
                    stats.rejected_steps,
                    stats.rhs_evaluations,
                    stats.jacobian_evaluations,
                    fmt_time(t),
                    t / t_full,
                    max_distance(&h, &reference),
                    max_distance(&h, own)
                );
            }
        }
    }
}
