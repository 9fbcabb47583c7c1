//! Cost of the 3-D chain's evaluations against n (printed, not a timed test): the equations of
//! motion's right-hand side (velocity solve, generalized forces, gyroscopic term), the O(n)
//! articulated-body velocity solve alone, and the momentum, for n = 40 … 1000, with the
//! log–log slope between consecutive n (1 for O(n)).
//!
//! ```sh
//! cargo run --release -p flexwing --example chain3d_costs [-- SAMPLES]
//! ```
//!
//! CPU time of the thread (`benches/common`), each sample the mean over 0.1 s of calls; the table
//! gives the minimum and the spread (max/min − 1) of the samples.

#[path = "../benches/common/mod.rs"]
mod common;

use flexwing::model::chain3d::{
    Beam3d, Chain3d, Geometry3d, JointCalibration, SectionInertia, SectionStiffness, SpatialLoad,
    SpatialVector,
};
use flexwing::model::StructuralModel;
use flexwing::solve::integrate::OdeSystem;
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, TimeFunction};
use std::hint::black_box;
use std::time::Duration;

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

fn stats(samples: &[f64]) -> (f64, f64) {
    let min = samples.iter().copied().fold(f64::INFINITY, f64::min);
    let max = samples.iter().copied().fold(0.0, f64::max);
    (min, max / min - 1.0)
}

fn main() {
    let samples: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(5);
    let ns = [40, 80, 160, 320, 640, 1000];
    println!("| n | right-hand side | spread | slope | velocity solve M⁻¹p | spread | slope | momentum M ẋ | slope |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut prev: Option<(usize, f64, f64, f64)> = None;
    let mut first: Option<(usize, f64, f64, f64)> = None;
    for n in ns {
        let model = chain(n);
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
        let tf = vec![TimeFunction::Constant; 2];
        let mut eom = EquationsOfMotion::new(&model, &loads, tf, Gyroscopic::Exact, &Damping::None)
            .expect("equations");
        let nd = model.n_dofs();
        let x: Vec<f64> = (0..nd).map(|i| 0.02 * (0.3 * i as f64).sin()).collect();
        let xd: Vec<f64> = (0..nd).map(|i| 0.5 * (0.7 * i as f64).cos()).collect();
        let y = eom.state(&x, &xd);
        let mut dy = vec![0.0; y.len()];
        let mut ws = model.workspace();
        let mut p = vec![0.0; nd];
        model.momentum_into(&x, &xd, &mut ws, &mut p);
        let mut v = vec![0.0; nd];
        // The right-hand side reconfigures at every new state; time it at alternating states so
        // that the kinematics cache does not hide the cost.
        let mut y2 = y.clone();
        y2[0] += 1e-9;
        let mut flip = false;
        let budget = Duration::from_millis(100);
        let rhs: Vec<f64> = (0..samples)
            .map(|_| {
                common::cpu_per_call(budget, || {
                    flip = !flip;
                    eom.rhs(0.0, if flip { &y } else { &y2 }, &mut dy);
                    black_box(&dy);
                })
            })
            .collect();
        let mut x2 = x.clone();
        x2[0] += 1e-9;
        let solve: Vec<f64> = (0..samples)
            .map(|_| {
                common::cpu_per_call(budget, || {
                    flip = !flip;
                    let xs = if flip { &x } else { &x2 };
                    black_box(model.velocities_into(xs, &p, &mut ws, &mut v));
                })
            })
            .collect();
        let momentum: Vec<f64> = (0..samples)
            .map(|_| {
                common::cpu_per_call(budget, || {
                    flip = !flip;
                    let xs = if flip { &x } else { &x2 };
                    model.momentum_into(xs, &xd, &mut ws, &mut p);
                    black_box(&p);
                })
            })
            .collect();
        let (r, rs) = stats(&rhs);
        let (s, ss) = stats(&solve);
        let (m, _) = stats(&momentum);
        let slope = |a: f64, b: f64, n0: usize| (b / a).ln() / (n as f64 / n0 as f64).ln();
        let (sr, sv, sm) = match prev {
            Some((n0, r0, s0, m0)) => (
                format!("{:.2}", slope(r0, r, n0)),
                format!("{:.2}", slope(s0, s, n0)),
                format!("{:.2}", slope(m0, m, n0)),
            ),
            None => ("".into(), "".into(), "".into()),
        };
        println!(
            "| {n} | {} | {:.0} % | {sr} | {} | {:.0} % | {sv} | {} | {sm} |",
            common::fmt_time(r),
            100.0 * rs,
            common::fmt_time(s),
            100.0 * ss,
            common::fmt_time(m)
        );
        prev = Some((n, r, s, m));
        first.get_or_insert((n, r, s, m));
    }
    if let (Some((n0, r0, s0, m0)), Some((n1, r1, s1, m1))) = (first, prev) {
        let k = (n1 as f64 / n0 as f64).ln();
        println!(
            "\nSlopes log-log between consecutive rows; from n = {n0} to {n1}: right-hand side \
             {:.2}, velocity solve {:.2}, momentum {:.2}.",
            (r1 / r0).ln() / k,
            (s1 / s0).ln() / k,
            (m1 / m0).ln() / k
        );
    }
}
