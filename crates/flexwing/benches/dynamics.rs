//! Benchmark of time integration: the paper's sinusoidal case (b) (tip force 10 sin(20 t) N,
//! 1 s, Table 4 beam) for the full and reduced models, with the tip error against a converged
//! run; and the cost of one right-hand side and one Jacobian against n.
//!
//! Run: `cargo bench -p flexwing --bench dynamics` (add `-- --quick` for a short run).

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{fmt_time, measure};

use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
use flexwing::model::{AppliedLoads, Force, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{Bdf, BdfOptions, Dopri5, Dopri5Options, OdeSystem, Tolerances};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction};
use nalgebra::DMatrix;

fn table4(n: usize) -> FullModel {
    let section = SectionProperties {
        ei: Profile::Uniform(50.0),
        mass_per_length: Profile::Uniform(0.2),
        torsion: None,
    };
    FullModel::new(
        Beam::new(
            1.0,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .expect("valid beam"),
    )
}

fn tip_history<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    rtol: f64,
    bdf: bool,
) -> Vec<[f64; 2]> {
    let full = model.full_model();
    let tf = vec![TimeFunction::Sine {
        omega: 20.0,
        phase: 0.0,
    }];
    let mut eom =
        EquationsOfMotion::new(model, loads, tf, Gyroscopic::Exact, &Damping::None).expect("eom");
    let tolerances = Tolerances {
        rtol,
        atol: eom.state_atol(rtol * 1e-2),
    };
    let t: Vec<f64> = (0..=200).map(|k| k as f64 * 0.005).collect();
    let y0 = vec![0.0; 2 * model.n_dofs()];
    let traj = if bdf {
        Bdf {
            options: BdfOptions {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, &t, &mut |_| {})
    } else {
        Dopri5 {
            options: Dopri5Options {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, &t, &mut |_| {})
    }
    .expect("integrates")
    .0;
    traj.y
        .iter()
        .map(|y| {
            let q = model.full_coordinates(&y[..model.n_dofs()]);
            let p = full.node_positions(&full.kinematics(&q))[full.n_elements()];
            [p[0], p[1]]
        })
        .collect()
}

fn max_diff(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let (budget, batches) = if quick {
        (Duration::from_millis(50), 3)
    } else {
        (Duration::from_millis(500), 5)
    };
    let full = table4(20);
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
    println!("Case (b), 1 s, output every 5 ms. Error: max tip distance from the same model at rtol 1e-9.\n");
    println!("| model | integrator | rtol | tip error (m) | wall time | spread |");
    println!("|---|---|---|---|---|---|");
    let reference = tip_history(&full, &loads, 1e-9, true);
    for rtol in [1e-4, 1e-5, 1e-6] {
        let h = tip_history(&full, &loads, rtol, true);
        let (t, s) = measure(budget, batches, || {
            black_box(tip_history(&full, &loads, rtol, true));
        });
        println!(
            "| full n = 20 | BDF (order ≤ 2) | {rtol:.0e} | {:.1e} | {} | {:.0} % |",
            max_diff(&h, &reference),
            fmt_time(t),
            100.0 * s
        );
    }
    for r in [1, 2, 3, 4] {
        let rom = ReducedModel::first(&full, modes.shapes(), r).expect("rom");
        let reference = tip_history(&rom, &loads, 1e-10, false);
        for rtol in [1e-4, 1e-6] {
            let h = tip_history(&rom, &loads, rtol, false);
            let (t, s) = measure(budget, batches, || {
                black_box(tip_history(&rom, &loads, rtol, false));
            });
            println!(
                "| reduced r = {r} | Dormand–Prince | {rtol:.0e} | {:.1e} | {} | {:.0} % |",
                max_diff(&h, &reference),
                fmt_time(t),
                100.0 * s
            );
        }
    }
    println!("\nCost of one evaluation of the equations of motion (full model, exact γ)\n");
    println!("| n | state size | right-hand side | Jacobian |");
    println!("|---|---|---|---|");
    for n in [10, 20, 40, 80, 160, 320] {
        let full = table4(n);
        let none = full.apply(&[], "loads").expect("loads");
        let mut eom =
            EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Exact, &Damping::None)
                .expect("eom");
        let q: Vec<f64> = (0..n).map(|i| 0.02 * (i as f64).sin()).collect();
        let y = eom.state(&q, &vec![0.1; n]);
        let mut dy = vec![0.0; 2 * n];
        let mut jac = DMatrix::zeros(2 * n, 2 * n);
        let (t_rhs, _) = measure(budget / 5, batches, || eom.rhs(0.0, black_box(&y), &mut dy));
        let (t_jac, _) = measure(budget / 5, batches, || {
            eom.jacobian(0.0, black_box(&y), &mut jac)
        });
        println!(
            "| {n} | {} | {} | {} |",
            2 * n,
            fmt_time(t_rhs),
            fmt_time(t_jac)
        );
    }
}
