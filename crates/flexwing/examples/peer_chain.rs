//! The flexwing side of the peer comparison (`crates/flexwing/benches/peers/`): exports the Table 4
//! chain (element lengths, masses, rotary inertias, joint stiffnesses of the tip-load calibration)
//! so that another code can build the identical chain, and times flexwing's static and dynamic
//! solves of the paper's cases on it, printing one JSON document on stdout.
//!
//! ```sh
//! cargo run --release -p flexwing --example peer_chain -- chain N
//! cargo run --release -p flexwing --example peer_chain -- static N FY SAMPLES
//! cargo run --release -p flexwing --example peer_chain -- dynamic N RTOL ATOL SAMPLES
//! cargo run --release -p flexwing --example peer_chain -- alpha N STEP RHO SAMPLES
//! ```
//!
//! * `chain`: the chain's data (SI units).
//! * `static`: a dead vertical tip force `FY` N, solved from rest by `solve_static` with the
//!   default options; the tip position and the CPU time of one solve.
//! * `dynamic`: case (b) (`flexwing::paper::sine_case`: tip force `10 sin(20 t)` N, 1 s, from
//!   rest), Radau IIA with `rtol`, `atol` (`IntegratorSettings`, the default Newton systems); the
//!   tip position every 5 ms, the counters and the CPU time of one solve.
//! * `alpha`: case (b) with generalized-α at the fixed step `STEP` s and spectral radius `RHO`
//!   (the method and settings of Exudyn's run), the same output.
//!
//! CPU time is that of the thread (`benches/common`, `/proc/thread-self/schedstat`), around the
//! solve only (the beam, its calibration and the loads are built before). Each of the `SAMPLES`
//! samples is the mean over as many solves as fill 0.2 s of CPU time (at least one), so that the
//! scheduler's tick does not matter; the document lists every sample and their median.

#[path = "../benches/common/mod.rs"]
mod common;

use flexwing::model::FullModel;
use flexwing::solve::integrate::{integrate, IntegratorSettings, Method};
use flexwing::solve::{solve_static, Damping, EquationsOfMotion, Gyroscopic, StaticOptions};
use std::hint::black_box;
use std::time::Duration;

fn usage() -> ! {
    eprintln!(
        "usage: peer_chain chain N | static N FY SAMPLES | dynamic N RTOL ATOL SAMPLES | \
         alpha N STEP RHO SAMPLES"
    );
    std::process::exit(2)
}

fn arg<T: std::str::FromStr>(args: &[String], i: usize) -> T {
    args.get(i)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| usage())
}

fn json_array(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", items.join(", "))
}

fn tip(model: &FullModel, q: &[f64]) -> [f64; 2] {
    let p = model.node_positions(&model.kinematics(q))[model.n_elements()];
    [p[0], p[1]]
}

/// `samples` figures of the CPU time per call of `f` and their median.
fn cpu_samples(samples: usize, mut f: impl FnMut()) -> (Vec<f64>, f64) {
    let mut s: Vec<f64> = (0..samples.max(1))
        .map(|_| common::cpu_per_call(Duration::from_millis(200), &mut f))
        .collect();
    let listed = s.clone();
    s.sort_by(f64::total_cmp);
    (listed, s[s.len() / 2])
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let n: usize = arg(&args, 1);
    let model = flexwing::paper::table4_beam(n).unwrap_or_else(|e| {
        eprintln!("error: {e}");
        std::process::exit(2)
    });
    match args.first().map(String::as_str) {
        Some("chain") => {
            let beam = model.beam();
            println!(
                "{{\"n\": {n}, \"length\": {:?}, \"lengths\": {}, \"masses\": {}, \"inertias\": {}, \"stiffness\": {}}}",
                beam.length(),
                json_array(beam.lengths()),
                json_array(beam.masses()),
                json_array(beam.inertias()),
                json_array(beam.bending_stiffness()),
            );
        }
        Some("static") => {
            let fy: f64 = arg(&args, 2);
            let samples: usize = arg(&args, 3);
            let loads = model
                .apply(&[flexwing::paper::table4_tip_force(fy)], "loads")
                .expect("loads");
            let opts = StaticOptions::default();
            let solution = solve_static(&model, &loads, &[1.0], &opts).expect("static solve");
            let (listed, median) = cpu_samples(samples, || {
                black_box(solve_static(&model, &loads, &[1.0], &opts).expect("static solve"));
            });
            let t = tip(&model, &solution.q);
            println!(
                "{{\"n\": {n}, \"fy\": {fy:?}, \"tip\": {}, \"iterations\": {}, \"cpu_s\": {}, \"cpu_median_s\": {median:?}}}",
                json_array(&t),
                solution.stats.iterations,
                json_array(&listed),
            );
        }
        Some("dynamic") => {
            let rtol: f64 = arg(&args, 2);
            let atol: f64 = arg(&args, 3);
            let samples: usize = arg(&args, 4);
            let settings = IntegratorSettings {
                rtol,
                atol,
                ..Default::default()
            };
            let head = format!("\"n\": {n}, \"rtol\": {rtol:?}, \"atol\": {atol:?}");
            case_b(n, Method::Radau, &settings, samples, &head);
        }
        Some("alpha") => {
            let step: f64 = arg(&args, 2);
            let rho: f64 = arg(&args, 3);
            let samples: usize = arg(&args, 4);
            // The tolerances (the library's defaults) only scale the Newton test at a fixed step.
            let settings = IntegratorSettings {
                step: Some(step),
                spectral_radius: rho,
                ..Default::default()
            };
            let head = format!("\"n\": {n}, \"step\": {step:?}, \"spectral_radius\": {rho:?}");
            case_b(n, Method::GeneralizedAlpha, &settings, samples, &head);
        }
        _ => usage(),
    }
}

/// Case (b) at `n` elements with `method` and `settings`: prints one JSON document that starts
/// with the fields `head`, then the tips, the counters and the CPU samples.
fn case_b(n: usize, method: Method, settings: &IntegratorSettings, samples: usize, head: &str) {
    let case = flexwing::paper::sine_case(n).expect("case (b)");
    let loads = case.model.apply(&case.loads, "loads").expect("loads");
    let time: Vec<_> = case.time.iter().flatten().cloned().collect();
    let y0 = vec![0.0; 2 * n];
    let run = || {
        let mut eom = EquationsOfMotion::new(
            &case.model,
            &loads,
            time.clone(),
            Gyroscopic::Exact,
            &Damping::None,
        )
        .expect("equations of motion");
        integrate(
            method,
            settings,
            &mut eom,
            0.0,
            &y0,
            &case.output_times,
            &mut |_| {},
        )
        .expect("integrates")
    };
    let (traj, stats) = run();
    let (listed, median) = if samples == 0 {
        (Vec::new(), f64::NAN)
    } else {
        cpu_samples(samples, || {
            black_box(run());
        })
    };
    let tips: Vec<String> = traj
        .y
        .iter()
        .map(|y| json_array(&tip(&case.model, &y[..n])))
        .collect();
    let median = if median.is_nan() {
        "null".to_string()
    } else {
        format!("{median:?}")
    };
    println!(
        "{{{head}, \"t\": {}, \"tips\": [{}], \"steps\": {}, \"rejected\": {}, \"newton_failures\": {}, \"rhs\": {}, \"jacobians\": {}, \"factorizations\": {}, \"cpu_s\": {}, \"cpu_median_s\": {median}}}",
        json_array(&traj.t),
        tips.join(", "),
        stats.steps,
        stats.rejected_steps,
        stats.newton_failures,
        stats.rhs_evaluations,
        stats.jacobian_evaluations,
        stats.factorizations,
        json_array(&listed),
    );
}
