//! Per-step cost of a dynamic run of the 3-D chain against n (printed, not a timed test), with
//! the implicit integrators' Newton systems solved in O(n) (`NewtonSystems::Chain`, GMRES on
//! the exact operator preconditioned by the articulated-body solve, `model/chain3d/newton.rs`)
//! and, up to `DENSE_MAX` elements, by dense LU of the exact Jacobian for comparison. Prints
//! the log–log slope of the per-step cost from the first n to each n (1 for O(n)).
//!
//! ```sh
//! cargo run --release -p flexwing --example chain3d_dynamics_cost [-- SAMPLES]
//! ```
//!
//! The case: Patil's wing as a straight 3-D chain (16 m, `GJ = 1e4`, `EI_flap = 2e4`,
//! `EI_lag = 4e6` N·m², 0.75 kg/m, 0.1 kg·m), from rest under gravity and a follower tip force
//! `(0, 20, 5) sin(10 t)` N in `(t, n, c)`, 0.1 s, Radau IIA through `integrate()` at the
//! library's default tolerances (rtol 1e-3, atol 1e-5 rad) with steps of at most 1 ms. CPU time of the thread around the
//! integration only (the equations of motion and their error weights built before); each
//! sample one run; the table gives the minimum and the spread (max/min − 1) of the samples.

#[path = "../benches/common/mod.rs"]
mod common;

use flexwing::model::chain3d::{
    Beam3d, Chain3d, Geometry3d, JointCalibration, SectionInertia, SectionStiffness, SpatialLoad,
    SpatialVector,
};
use flexwing::solve::integrate::{integrate, IntegratorSettings, Method};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction};

/// Largest n run with the dense Newton systems (O(n³) per factorization).
const DENSE_MAX: usize = 160;

fn chain(n: usize) -> Chain3d {
    Chain3d::new(
        Beam3d::new(
            &Geometry3d::straight(16.0, n),
            &SectionStiffness::uncoupled(1e4, 2e4, 4e6),
            &SectionInertia::uniform(0.75, 0.1),
            JointCalibration::Compliance,
        )
        .expect("valid beam"),
    )
}

/// One run: (CPU seconds, steps, tip position at the end, mean GMRES iterations per solve).
fn run(model: &Chain3d, newton: NewtonSystems) -> (f64, usize, [f64; 3], f64) {
    let loads = model
        .apply(
            &[
                SpatialLoad::PointForce {
                    span: 16.0,
                    force: SpatialVector::Follower([0.0, 20.0, 5.0]),
                },
                SpatialLoad::Gravity {
                    acceleration: [0.0, -9.81, 0.0],
                },
            ],
            "loads",
        )
        .expect("valid loads");
    let tf = vec![
        TimeFunction::Sine {
            omega: 10.0,
            phase: 0.0,
        },
        TimeFunction::Constant,
    ];
    let mut eom = EquationsOfMotion::new(model, &loads, tf, Gyroscopic::Exact, &Damping::None)
        .expect("equations");
    eom.set_newton_systems(newton).expect("newton systems");
    let nd = model.n_dofs();
    let y0 = eom.state(&vec![0.0; nd], &vec![0.0; nd]);
    // The error weights (O(n²) for a model other than the planar chain) once, before the
    // clock: set-up, not per-step cost.
    eom.energy_resolution(1.0);
    // A step cap, so that every n takes the same ~100 steps and the per-step costs compare
    // equal work (without it the step count changes with n: 12 steps at n = 40, 72 at 80).
    let settings = IntegratorSettings {
        max_step: Some(1e-3),
        ..Default::default()
    };
    let t = [0.0, 0.05, 0.1];
    let start = common::cpu_time();
    let (traj, stats) = integrate(
        Method::Radau,
        &settings,
        &mut eom,
        0.0,
        &y0,
        &t,
        &mut |_| {},
    )
    .expect("integrates");
    let cpu = common::cpu_time() - start;
    let last = traj.y.last().expect("output");
    let tip = model.node_positions(&last[..nd])[model.n_elements()];
    let iterations = eom
        .chain3d_newton_counts()
        .map_or(0.0, |(s, i, _)| i as f64 / s.max(1) as f64);
    (cpu, stats.steps, tip, iterations)
}

fn main() {
    let samples: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(3);
    let ns = [40, 80, 160, 320, 640, 1000];
    println!("| n | steps | O(n) Newton: per step | spread | slope from n = 40 | GMRES its/solve | dense LU: per step | tips apart (m) |");
    println!("|---|---|---|---|---|---|---|---|");
    let mut first: Option<(usize, f64)> = None;
    for n in ns {
        let model = chain(n);
        let mut times = Vec::new();
        let mut out = None;
        for _ in 0..samples {
            let (cpu, steps, tip, its) = run(&model, NewtonSystems::Chain);
            times.push(cpu / steps as f64);
            out = Some((steps, tip, its));
        }
        let (steps, tip, its) = out.expect("one sample");
        let min = times.iter().copied().fold(f64::INFINITY, f64::min);
        let max = times.iter().copied().fold(0.0, f64::max);
        let (dense, apart) = if n <= DENSE_MAX {
            let (cpu, dsteps, dtip, _) = run(&model, NewtonSystems::Dense);
            let d = ((tip[0] - dtip[0]).powi(2)
                + (tip[1] - dtip[1]).powi(2)
                + (tip[2] - dtip[2]).powi(2))
            .sqrt();
            (common::fmt_time(cpu / dsteps as f64), format!("{d:.1e}"))
        } else {
            ("—".into(), "—".into())
        };
        let slope = match first {
            Some((n0, t0)) => format!("{:.2}", (min / t0).ln() / (n as f64 / n0 as f64).ln()),
            None => "".into(),
        };
        first.get_or_insert((n, min));
        println!(
            "| {n} | {steps} | {} | {:.0} % | {slope} | {its:.1} | {dense} | {apart} |",
            common::fmt_time(min),
            100.0 * (max / min - 1.0)
        );
    }
}
