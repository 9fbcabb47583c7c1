//! Prints the dynamics figures of `docs/validation.md`: energy drift per integrator, exact
//! against finite-difference gyroscopic term (the paper's Table 6),
//! and full against reduced models under a sinusoidal tip load
//! (Figure 6 / Table 8).
//!
//! Run: `cargo run --release -p flexwing --example dynamics_report`

use std::time::Instant;

use flexwing::model::{FullModel, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{integrate, IntegratorSettings, Method, OdeSystem, Trajectory};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction};

fn table4(n: usize) -> FullModel {
    flexwing::paper::table4_beam(n).expect("valid beam")
}

fn tip(full: &FullModel, q: &[f64]) -> [f64; 2] {
    let p = full.node_positions(&full.kinematics(q))[full.n_elements()];
    [p[0], p[1]]
}

/// Integrate with `method` at relative tolerance `rtol` (coordinate tolerance `rtol/100`) and,
/// for the midpoint rule, a fixed `step`.
fn run<M: StructuralModel>(
    eom: &mut EquationsOfMotion<'_, M>,
    y0: &[f64],
    t_out: &[f64],
    method: Method,
    rtol: f64,
    step: Option<f64>,
) -> (Trajectory, String, f64) {
    let settings = IntegratorSettings {
        rtol,
        atol: rtol * 1e-2,
        step,
        ..Default::default()
    };
    let start = Instant::now();
    let r = integrate(method, &settings, eom, 0.0, y0, t_out, &mut |_| {});
    let wall = start.elapsed().as_secs_f64();
    let (traj, stats) = r.expect("integration");
    (
        traj,
        format!("{} steps, {} rhs", stats.steps, stats.rhs_evaluations),
        wall,
    )
}

fn main() {
    // Energy drift: free vibration from a large first-mode deflection (tip 0.4 L), n = 10.
    let full = table4(10);
    let modes10 = Modes::undeformed(&full).unwrap();
    let phi: Vec<f64> = modes10.shapes().column(0).iter().copied().collect();
    let unit = tip(&full, &phi.iter().map(|v| v * 1e-6).collect::<Vec<_>>())[1] / 1e-6;
    let q0: Vec<f64> = phi.iter().map(|v| v * 0.4 / unit).collect();
    let none = full.apply(&[], "loads").unwrap();
    println!("\nEnergy drift over 30 s of free vibration (Table 4 beam, n = 10, released from a first-mode deflection with the tip at 0.4 L)\n");
    println!("| model | integrator | max |H(t) − H(0)| / H(0) | work | wall time |");
    println!("|---|---|---|---|---|");
    let t_out: Vec<f64> = (0..=600).map(|k| k as f64 * 0.05).collect();
    for (label, g) in [
        ("full (exact γ)", Gyroscopic::Exact),
        ("simplified (γ = 0)", Gyroscopic::Neglected),
    ] {
        for (name, method, rtol, step) in [
            (
                "implicit midpoint, h = 2.5e-4",
                Method::Midpoint,
                1e-6,
                Some(2.5e-4),
            ),
            ("BDF (order ≤ 2), rtol 1e-4", Method::Bdf, 1e-4, None),
        ] {
            let mut eom = EquationsOfMotion::new(&full, &none, vec![], g, &Damping::None).unwrap();
            let y0 = eom.state(&q0, &[0.0; 10]);
            let (traj, work, wall) = run(&mut eom, &y0, &t_out, method, rtol, step);
            let mut e = |y: &[f64]| {
                let (k, s) = eom.energies(y);
                k + s
            };
            let h0 = e(&traj.y[0]);
            let drift = traj
                .y
                .iter()
                .map(|y| (e(y) - h0).abs() / h0)
                .fold(0.0, f64::max);
            println!(
                "| {label} | {name} | {drift:.2e} | {work} | {:.0} ms |",
                wall * 1e3
            );
        }
    }
    let modes = Modes::undeformed(&full).unwrap();
    let rom = ReducedModel::first(&full, modes.shapes(), 4).unwrap();
    let eta0 = rom.reduce_coordinates(&q0);
    let mut eom =
        EquationsOfMotion::new(&rom, &none, vec![], Gyroscopic::Exact, &Damping::None).unwrap();
    let y0 = eom.state(&eta0, &[0.0; 4]);
    let (traj, work, wall) = run(&mut eom, &y0, &t_out, Method::Dopri5, 1e-9, None);
    let mut e = |y: &[f64]| {
        let (k, s) = eom.energies(y);
        k + s
    };
    let h0 = e(&traj.y[0]);
    let drift = traj
        .y
        .iter()
        .map(|y| (e(y) - h0).abs() / h0)
        .fold(0.0, f64::max);
    println!(
        "| reduced r = 4 (exact γ) | Dormand–Prince, rtol 1e-9 | {drift:.2e} | {work} | {:.0} ms |",
        wall * 1e3
    );

    // Table 6: exact against finite-difference γ at the state of the sine case at t = 1 s.
    let case = flexwing::paper::sine_case(20).unwrap();
    let full20 = case.model.clone();
    let sine = full20.apply(&case.loads, "loads").unwrap();
    let tf: Vec<TimeFunction> = case.time.iter().flatten().cloned().collect();
    let t_out = case.output_times.clone();
    let mut eom = EquationsOfMotion::new(
        &full20,
        &sine,
        tf.clone(),
        Gyroscopic::Exact,
        &Damping::None,
    )
    .unwrap();
    let (traj_full, _, _) = run(&mut eom, &vec![0.0; 40], &t_out, Method::Bdf, 1e-8, None);
    let y1 = traj_full.y[200].clone();
    let mut d_exact = vec![0.0; 40];
    let mut d_fd = vec![0.0; 40];
    let t = Instant::now();
    for _ in 0..100 {
        eom.rhs(1.0, &y1, &mut d_exact);
    }
    let t_exact = t.elapsed().as_secs_f64() / 100.0;
    let mut eom_fd = EquationsOfMotion::new(
        &full20,
        &sine,
        tf.clone(),
        Gyroscopic::FiniteDifference { step: 1e-6 },
        &Damping::None,
    )
    .unwrap();
    let t = Instant::now();
    for _ in 0..100 {
        eom_fd.rhs(1.0, &y1, &mut d_fd);
    }
    let t_fd = t.elapsed().as_secs_f64() / 100.0;
    let mut d_none = vec![0.0; 40];
    let mut eom_none = EquationsOfMotion::new(
        &full20,
        &sine,
        tf.clone(),
        Gyroscopic::Neglected,
        &Damping::None,
    )
    .unwrap();
    eom_none.rhs(1.0, &y1, &mut d_none);
    let gamma_exact: Vec<f64> = (20..40).map(|i| d_exact[i] - d_none[i]).collect();
    let gamma_fd: Vec<f64> = (20..40).map(|i| d_fd[i] - d_none[i]).collect();
    let mae = gamma_exact
        .iter()
        .zip(&gamma_fd)
        .map(|(a, b)| (a - b).abs())
        .sum::<f64>()
        / 20.0;
    let mre = gamma_exact
        .iter()
        .zip(&gamma_fd)
        .map(|(a, b)| (a - b).abs() / a.abs().max(1e-300))
        .sum::<f64>()
        / 20.0;
    let gmax = gamma_exact.iter().map(|v| v.abs()).fold(0.0, f64::max);
    println!("\nGyroscopic term, exact against central differences (h = 1e-6), state of the sine case at t = 1 s, n = 20 (Table 6)\n");
    println!(
        "| method | mean absolute error | mean relative error | max |γ| | time per RHS | ratio |"
    );
    println!("|---|---|---|---|---|---|");
    println!(
        "| exact (O(n)) | 0 | 0 | {gmax:.3e} | {:.2} µs | 1 |",
        t_exact * 1e6
    );
    println!(
        "| finite differences | {mae:.2e} | {mre:.2e} | | {:.2} µs | {:.1} |",
        t_fd * 1e6,
        t_fd / t_exact
    );

    // Table 8 / Figure 6: full n = 20 against reduced r = 1…4.
    println!("\nSinusoidal tip load F = 10 sin(20 t) N, 1 s (Figure 6, Table 8): full n = 20 (BDF) against reduced (DOPRI5)\n");
    println!("| model | max |Δ tip| (m) | max |Δ tip| / max |tip y| | wall time | ratio |");
    println!("|---|---|---|---|---|");
    let tip_full: Vec<[f64; 2]> = traj_full.y.iter().map(|y| tip(&full20, &y[..20])).collect();
    let amp = tip_full.iter().map(|p| p[1].abs()).fold(0.0, f64::max);
    let mut eom = EquationsOfMotion::new(
        &full20,
        &sine,
        tf.clone(),
        Gyroscopic::Exact,
        &Damping::None,
    )
    .unwrap();
    let (_, _, wall_full) = run(&mut eom, &vec![0.0; 40], &t_out, Method::Bdf, 1e-6, None);
    println!(
        "| full, rtol 1e-6 | – | – | {:.1} ms | 1 |",
        wall_full * 1e3
    );
    let modes = Modes::undeformed(&full20).unwrap();
    for r in [1, 2, 3, 4, 6] {
        let rom = ReducedModel::first(&full20, modes.shapes(), r).unwrap();
        let mut eom =
            EquationsOfMotion::new(&rom, &sine, tf.clone(), Gyroscopic::Exact, &Damping::None)
                .unwrap();
        let (traj, _, wall) = run(
            &mut eom,
            &vec![0.0; 2 * r],
            &t_out,
            Method::Dopri5,
            1e-6,
            None,
        );
        let err = traj
            .y
            .iter()
            .zip(&tip_full)
            .map(|(y, p)| {
                let t = tip(&full20, &rom.full_coordinates(&y[..r]));
                (t[0] - p[0]).hypot(t[1] - p[1])
            })
            .fold(0.0, f64::max);
        println!(
            "| reduced r = {r} | {err:.2e} | {:.2} % | {:.2} ms | {:.3} |",
            100.0 * err / amp,
            wall * 1e3,
            wall / wall_full
        );
    }
}
