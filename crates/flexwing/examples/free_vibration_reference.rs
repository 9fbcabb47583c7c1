//! Computes `tests/data/free_vibration_reference/tip_n20.csv`: the paper's case (a) set-up (Table 4
//! beam, n = 20, released at rest from the static deflection under a 150 N dead tip force, no
//! load during the motion), 1 s, tip every 5 ms, by Dormand–Prince 5(4) at rtol 1e-10 (and 1e-9,
//! to bound its error). An explicit method: it follows every mode of the released chain (up to
//! 6.3e5 rad/s, which sets its steps by stability), with none of the numerical damping of the
//! generalized-α method the reference is used to check.
//!
//! Run: `cargo run --release -p flexwing --example free_vibration_reference` (about 30 s).

use std::fmt::Write as _;
use std::time::Instant;

use flexwing::model::{Force, Load};
use flexwing::solve::integrate::{Dopri5, Dopri5Options, Tolerances};
use flexwing::solve::{solve_static, Damping, EquationsOfMotion, Gyroscopic, StaticOptions};

fn main() {
    let n = 20;
    let full = flexwing::paper::table4_beam(n).expect("beam");
    let release = full
        .apply(
            &[Load::PointForce {
                span: 1.0,
                force: Force::Dead { fx: 0.0, fy: 150.0 },
            }],
            "loads",
        )
        .expect("loads");
    let q0 = solve_static(&full, &release, &[1.0], &StaticOptions::default())
        .expect("static deflection")
        .q;
    let none = full.apply(&[], "loads").expect("no loads");
    let mut eom = EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Exact, &Damping::None)
        .expect("equations");
    let y0 = eom.state(&q0, &vec![0.0; n]);
    let t: Vec<f64> = (0..=200).map(|k| k as f64 * 0.005).collect();
    let mut runs = vec![];
    for rtol in [1e-9, 1e-10] {
        let start = Instant::now();
        let (traj, stats) = Dopri5 {
            options: Dopri5Options {
                tolerances: Tolerances {
                    rtol,
                    atol: eom.state_atol(rtol),
                },
                max_steps: 50_000_000,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, &t, &mut |_| {})
        .expect("integrates");
        eprintln!(
            "rtol {rtol:.0e}: {:.1} s, {stats:?}",
            start.elapsed().as_secs_f64()
        );
        let tips: Vec<[f64; 3]> = traj
            .y
            .iter()
            .map(|y| {
                let p = full.node_positions(&full.kinematics(&y[..n]))[n];
                let (kinetic, strain) = eom.energies(y);
                [p[0], p[1], kinetic + strain]
            })
            .collect();
        runs.push(tips);
    }
    let diff = runs[0]
        .iter()
        .zip(&runs[1])
        .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
        .fold(0.0, f64::max);
    eprintln!("max tip distance rtol 1e-9 against 1e-10: {diff:.2e} m");
    let mut csv = String::from("t,tip_x,tip_y,energy\n");
    for (tt, p) in t.iter().zip(&runs[1]) {
        writeln!(csv, "{tt},{:.15e},{:.15e},{:.15e}", p[0], p[1], p[2]).expect("write");
    }
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/free_vibration_reference/tip_n20.csv"
    );
    std::fs::create_dir_all(std::path::Path::new(path).parent().expect("folder"))
        .expect("data folder");
    std::fs::write(path, csv).expect("write the reference");
    eprintln!("wrote {path}");
}
