//! Benchmark of the generalized-α integrator on the paper's free vibration (the set-up of its
//! case (a)): the Table 4 beam released at rest from its static deflection under a 150 N dead tip
//! force, no load during the motion, 1 s, tip every 5 ms. It prints
//!
//! * the modal content of the released state (which modes carry how much of the tip motion);
//! * at n = 20, the tip error against a Dormand–Prince run at rtol 1e-10
//!   (`tests/data/free_vibration_reference/`, 7e-9 m from the rtol 1e-9 run), the energy kept
//!   and the counters and CPU time of generalized-α (fixed steps, three `ρ∞`; adaptive) and of
//!   Radau IIA at several tolerances;
//! * at n = 80, generalized-α at fixed steps, with its error against itself at a quarter of the
//!   step (a self-convergence figure, not a reference: no affordable independent run follows
//!   the 4e7 rad/s modes of that chain).
//!
//! With `-- --bars` instead: the same release at n = 20 on elements that are rigid bars
//! (`beam::RotaryInertia::elements`, docs/model-choices.md "Rotary inertia in bending"), whose
//! highest mode is 14× slower than the point masses' (58× at n = 80), every run against
//! Dormand–Prince at rtol 1e-11 on the same model (and that reference against Radau at rtol
//! 1e-11, printed: two methods' agreement). At n = 80 the explicit reference would need more
//! than a million steps, so the table stops at n = 20.
//!
//! Times are CPU time of the thread (`common::cpu_time`). Run: `cargo bench -p flexwing --bench
//! free_vibration` (add `-- --quick` for fewer settings).

use std::time::Duration;

mod common;
use common::{cpu_per_call, fmt_time};

use flexwing::beam::{Beam, Calibration, Discretization, RotaryInertia};
use flexwing::model::Force;
use flexwing::model::{FullModel, Load, StructuralModel};
use flexwing::solve::integrate::{
    Dopri5, Dopri5Options, GeneralizedAlpha, GeneralizedAlphaOptions, IntegrationResult,
    IntegratorStats, Radau, RadauOptions, Tolerances,
};
use flexwing::solve::{solve_static, Damping, EquationsOfMotion, Gyroscopic, Modes, StaticOptions};
use nalgebra::{DMatrix, DVector};

const REFERENCE_N20: &str = include_str!("../tests/data/free_vibration_reference/tip_n20.csv");

#[derive(Clone, Copy)]
enum Method {
    /// Generalized-α with a fixed step: (ρ∞, h).
    AlphaFixed(f64, f64),
    /// Generalized-α, adaptive: (ρ∞, rtol, atol).
    AlphaAdaptive(f64, f64, f64),
    /// Radau IIA: (rtol, atol).
    Radau(f64, f64),
    /// Dormand–Prince 5(4): (rtol, atol).
    Dopri5(f64, f64),
}

impl Method {
    fn label(self) -> (String, String) {
        match self {
            Method::AlphaFixed(rho, h) => {
                (format!("generalized-α ρ∞ = {rho}"), format!("h = {h:.3e}"))
            }
            Method::AlphaAdaptive(rho, r, a) => (
                format!("generalized-α ρ∞ = {rho}, adaptive"),
                format!("rtol {r:.0e}, atol {a:.0e}"),
            ),
            Method::Radau(r, a) => (
                "Radau IIA (5)".into(),
                format!("rtol {r:.0e}, atol {a:.0e}"),
            ),
            Method::Dopri5(r, a) => (
                "Dormand–Prince 5(4)".into(),
                format!("rtol {r:.0e}, atol {a:.0e}"),
            ),
        }
    }
}

struct Case {
    full: FullModel,
    y0: Vec<f64>,
    t: Vec<f64>,
}

impl Case {
    fn new(n: usize) -> Self {
        Self::with(flexwing::paper::table4_beam(n).expect("beam"))
    }

    /// The Table 4 beam on `n` rigid bars.
    fn bars(n: usize) -> Self {
        let section = flexwing::paper::table4_section();
        let beam = Beam::new(
            1.0,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .expect("beam");
        let bars = RotaryInertia {
            elements: true,
            section: None,
        };
        Self::with(FullModel::new(
            beam.with_rotary_inertia("beam", &section, &bars)
                .expect("bars"),
        ))
    }

    /// Released at rest from the static deflection of `full` under 150 N at the tip.
    fn with(full: FullModel) -> Self {
        let n = full.n_dofs();
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
            .expect("static")
            .q;
        let none = full.apply(&[], "loads").expect("loads");
        let mut eom =
            EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Exact, &Damping::None)
                .expect("eom");
        let y0 = eom.state(&q0, &vec![0.0; n]);
        let t = (0..=200).map(|k| k as f64 * 0.005).collect();
        Self { full, y0, t }
    }

    /// Tips at the output times, final energy over initial, counters.
    fn run(&self, method: Method) -> (Vec<[f64; 2]>, f64, IntegratorStats, bool) {
        let n = self.full.n_dofs();
        let none = self.full.apply(&[], "loads").expect("loads");
        let mut eom =
            EquationsOfMotion::new(&self.full, &none, vec![], Gyroscopic::Exact, &Damping::None)
                .expect("eom");
        let tolerances =
            |eom: &mut EquationsOfMotion<'_, FullModel>, rtol: f64, atol: f64| Tolerances {
                rtol,
                atol: eom.state_atol(atol),
            };
        let result: IntegrationResult = match method {
            Method::AlphaFixed(rho, h) => GeneralizedAlpha {
                options: GeneralizedAlphaOptions {
                    spectral_radius: rho,
                    step: Some(h),
                    // The Newton scale of a fixed step (no error control).
                    tolerances: tolerances(&mut eom, 1e-4, 1e-6),
                    ..Default::default()
                },
            }
            .integrate(&mut eom, 0.0, &self.y0, &self.t, &mut |_| {}),
            Method::AlphaAdaptive(rho, rtol, atol) => GeneralizedAlpha {
                options: GeneralizedAlphaOptions {
                    spectral_radius: rho,
                    tolerances: tolerances(&mut eom, rtol, atol),
                    ..Default::default()
                },
            }
            .integrate(&mut eom, 0.0, &self.y0, &self.t, &mut |_| {}),
            Method::Radau(rtol, atol) => Radau {
                options: RadauOptions {
                    tolerances: tolerances(&mut eom, rtol, atol),
                    ..Default::default()
                },
            }
            .integrate(&mut eom, 0.0, &self.y0, &self.t, &mut |_| {}),
            Method::Dopri5(rtol, atol) => Dopri5 {
                options: Dopri5Options {
                    tolerances: tolerances(&mut eom, rtol, atol),
                    ..Default::default()
                },
            }
            .integrate(&mut eom, 0.0, &self.y0, &self.t, &mut |_| {}),
        };
        let (traj, stats, complete) = match result {
            Ok((traj, stats)) => (traj, stats, true),
            Err(f) => (f.trajectory, f.stats, false),
        };
        let tips = traj
            .y
            .iter()
            .map(|y| {
                let p = self.full.node_positions(&self.full.kinematics(&y[..n]))[n];
                [p[0], p[1]]
            })
            .collect();
        let (k0, s0) = eom.energies(&self.y0);
        let (k1, s1) = eom.energies(traj.y.last().expect("outputs"));
        (tips, (k1 + s1) / (k0 + s0), stats, complete)
    }
}

fn max_distance(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    if a.len() != b.len() {
        return f64::INFINITY;
    }
    a.iter()
        .zip(b)
        .map(|(p, q)| (p[0] - q[0]).hypot(p[1] - q[1]))
        .fold(0.0, f64::max)
}

/// Modal content of the released state in the modes about the undeformed state: frequency, the
/// linearized tip displacement of the component, its share of the strain energy `½ ω² η²`.
fn modal_content(case: &Case, shown: usize) {
    let full = &case.full;
    let n = full.n_dofs();
    let modes = Modes::undeformed(full).expect("modes");
    let mut m0 = DMatrix::zeros(n, n);
    full.mass_matrix_into(&vec![0.0; n], &mut full.workspace(), &mut m0);
    let eta = modes.shapes().transpose() * (&m0 * DVector::from_column_slice(&case.y0[..n]));
    let energy: Vec<f64> = (0..n)
        .map(|k| (modes.omega()[k] * eta[k]).powi(2))
        .collect();
    let total: f64 = energy.iter().sum();
    println!("| mode | ω (rad/s) | tip displacement of the component (m) | energy share |");
    println!("|---|---|---|---|");
    for k in (0..n).filter(|&k| k < shown || k == n - 1) {
        let eps = 1e-6;
        let q: Vec<f64> = modes
            .shapes()
            .column(k)
            .iter()
            .map(|v| v * eta[k] * eps)
            .collect();
        let tip = full.node_positions(&full.kinematics(&q))[full.n_elements()][1] / eps;
        println!(
            "| {} | {:.0} | {:.1e} | {:.1e} |",
            k + 1,
            modes.omega()[k],
            tip.abs(),
            energy[k] / total
        );
    }
}

/// One table row per method (tip error against `reference`, energy kept, counters, CPU time);
/// the fastest complete run within 1e-4 m, if any, with its CPU time.
fn table_rows(
    case: &Case,
    methods: &[Method],
    reference: &[[f64; 2]],
    budget: Duration,
) -> Option<(f64, String)> {
    let mut best_1e4: Option<(f64, String)> = None;
    for &method in methods {
        let (tips, energy, stats, complete) = case.run(method);
        let err = max_distance(&tips, reference);
        let cpu = cpu_per_call(budget, || {
            std::hint::black_box(case.run(method));
        });
        let (name, setting) = method.label();
        println!(
            "| {name} | {setting} | {}{:.1e} | {energy:.6} | {} ({}) | {} / {} / {} | {} |",
            if complete { "" } else { "stopped: " },
            err,
            stats.steps,
            stats.rejected_steps,
            stats.rhs_evaluations,
            stats.jacobian_evaluations,
            stats.factorizations,
            fmt_time(cpu)
        );
        if complete && err <= 1e-4 && best_1e4.as_ref().is_none_or(|(c, _)| cpu < *c) {
            best_1e4 = Some((cpu, format!("{name}, {setting}")));
        }
    }
    best_1e4
}

/// The free vibration on rigid bars at n = 20 (module documentation).
fn bars(quick: bool, budget: Duration) {
    println!(
        "Free vibration from the 150 N static deflection on rigid bars (element_inertia = \"bar\"), \
         Table 4 beam, 1 s, tip every 5 ms; tip error against Dormand–Prince at rtol 1e-11 on the \
         same model.\n"
    );
    let n = 20;
    let point = Modes::undeformed(&Case::new(n).full).expect("modes");
    let case = Case::bars(n);
    let modes = Modes::undeformed(&case.full).expect("modes");
    let (reference, ..) = case.run(Method::Dopri5(1e-11, 1e-13));
    let (radau, ..) = case.run(Method::Radau(1e-11, 1e-13));
    println!(
        "n = {n}: highest mode {:.1e} rad/s on bars ({:.1e} on point masses); reference \
         against Radau at rtol 1e-11: {:.1e} m\n",
        modes.omega().last().expect("modes"),
        point.omega().last().expect("modes"),
        max_distance(&reference, &radau)
    );
    println!("| integrator | setting | tip error (m) | H(1 s)/H(0) | steps (rejected) | f / J / LU | CPU |");
    println!("|---|---|---|---|---|---|---|");
    let tolerances: Vec<(f64, f64)> = if quick {
        vec![(1e-4, 1e-6), (1e-6, 1e-8)]
    } else {
        vec![(1e-4, 1e-6), (1e-5, 1e-7), (1e-6, 1e-8), (1e-7, 1e-9)]
    };
    let mut methods: Vec<Method> = tolerances
        .iter()
        .map(|&(r, a)| Method::Radau(r, a))
        .collect();
    methods.extend(tolerances.iter().map(|&(r, a)| Method::Dopri5(r, a)));
    methods.extend([2.5e-4, 1.25e-4, 6.25e-5].map(|h| Method::AlphaFixed(0.5, h)));
    let best_1e4 = table_rows(&case, &methods, &reference, budget);
    match best_1e4 {
        Some((cpu, what)) => println!(
            "\nn = {n}, fastest run within 1e-4 m: {what}, {}.\n",
            fmt_time(cpu)
        ),
        None => println!("\nn = {n}: no run reached 1e-4 m.\n"),
    }
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let budget = Duration::from_millis(if quick { 100 } else { 300 });
    if std::env::args().any(|a| a == "--bars") {
        bars(quick, budget);
        return;
    }

    let case = Case::new(20);
    println!(
        "Free vibration from the 150 N static deflection, Table 4 beam, 1 s, tip every 5 ms.\n"
    );
    println!("Modal content of the released state, n = 20 (modes about the undeformed state):\n");
    modal_content(&case, 10);
    let reference: Vec<[f64; 2]> = REFERENCE_N20
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|s| s.parse().expect("number")).collect();
            [v[1], v[2]]
        })
        .collect();

    let rhos = if quick {
        vec![0.5]
    } else {
        vec![0.0, 0.5, 0.9]
    };
    let steps: Vec<f64> = if quick {
        vec![1e-3, 2.5e-4]
    } else {
        vec![1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5, 3.125e-5]
    };
    let mut methods: Vec<Method> = rhos
        .iter()
        .flat_map(|&rho| steps.iter().map(move |&h| Method::AlphaFixed(rho, h)))
        .collect();
    let tolerances: Vec<(f64, f64)> = if quick {
        vec![(1e-3, 1e-5), (1e-4, 1e-6)]
    } else {
        vec![
            (1e-2, 1e-4),
            (1e-3, 1e-5),
            (1e-4, 1e-6),
            (1e-5, 1e-7),
            (1e-6, 1e-8),
        ]
    };
    methods.extend(
        tolerances
            .iter()
            .map(|&(r, a)| Method::AlphaAdaptive(0.5, r, a)),
    );
    methods.extend(tolerances.iter().map(|&(r, a)| Method::Radau(r, a)));

    println!("\nn = 20: tip error against Dormand–Prince at rtol 1e-10 (max over the outputs)\n");
    println!("| integrator | setting | tip error (m) | H(1 s)/H(0) | steps (rejected) | f / J / LU | CPU |");
    println!("|---|---|---|---|---|---|---|");
    match table_rows(&case, &methods, &reference, budget) {
        Some((cpu, what)) => println!(
            "\nFastest run within 1e-4 m: {what}, {} (goal: under 10 ms).",
            fmt_time(cpu)
        ),
        None => println!("\nNo run reached 1e-4 m (goal: 1e-4 m in under 10 ms)."),
    }

    let n80 = Case::new(80);
    let modes80 = Modes::undeformed(&n80.full).expect("modes");
    println!(
        "\nn = 80 (highest mode {:.1e} rad/s): generalized-α ρ∞ = 0.5 at fixed steps, error against itself at h/4\n",
        modes80.omega().last().expect("modes")
    );
    println!("| h | tip distance to h/4 (m) | H(1 s)/H(0) | steps (rejected) | f / J / LU | CPU |");
    println!("|---|---|---|---|---|---|");
    let steps80: Vec<f64> = if quick {
        vec![1e-3]
    } else {
        vec![1e-3, 5e-4, 2.5e-4]
    };
    for h in steps80 {
        let (tips, energy, stats, complete) = n80.run(Method::AlphaFixed(0.5, h));
        let (fine, _, _, _) = n80.run(Method::AlphaFixed(0.5, h / 4.0));
        let cpu = cpu_per_call(budget, || {
            std::hint::black_box(n80.run(Method::AlphaFixed(0.5, h)));
        });
        println!(
            "| {h:.2e} | {}{:.1e} | {energy:.6} | {} ({}) | {} / {} / {} | {} |",
            if complete { "" } else { "stopped: " },
            max_distance(&tips, &fine),
            stats.steps,
            stats.rejected_steps,
            stats.rhs_evaluations,
            stats.jacobian_evaluations,
            stats.factorizations,
            fmt_time(cpu)
        );
    }
}
