//! Benchmarks of the aeroelastic analyses on Patil's HALE wing (semi-span 16 m, chord 1 m, elastic
//! axis and mass centre at mid-chord, m = 0.75 kg/m, I = 0.1 kg·m, GJ = 1e4, EI = 2e4, ρ = 0.0889,
//! c_lα = 2π) with Peters' inflow (6 states per strip): the flutter speed of the full model against
//! n, the reduced model (r = 6), a V-g sweep of 100 speeds, a 1−cos gust response of 2 s, and
//! the discrete gust family of `examples/patil_gust_family.toml` (20 CS 25.341(a) gusts).
//! Prints Markdown tables for docs/performance.md.
//!
//! Run: `cargo bench -p flexwing --bench aero` (add `-- --quick` for a short run; name sections
//! to run only those: `-- flutter`, `-- sweep`, `-- gust`, `-- audit`: the cost of the energy
//! audit on the gust response, `-- family`: the gust family, `-- turbulence`: the output
//! spectra and RMS of 500 frequencies in von Kármán turbulence).

use std::hint::black_box;
use std::time::Duration;

mod common;
use common::{cpu_per_call, cpu_time, fmt_time, measure};

use flexwing::analysis::aero::gust_family::{self, GustFamilyPlan, GustLengths, FOOT};
use flexwing::analysis::aero::response::AeroDynamicPlan;
use flexwing::analysis::aero::Aero;
use flexwing::analysis::dynamics::DynamicPlan;
use flexwing::analysis::NoProgress;
use flexwing::model::aero::AeroSection;

use flexwing::beam::Profile;
use flexwing::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
use flexwing::model::{AppliedLoads, ReducedModel, StructuralModel};
use flexwing::solve::aeroelastic::{
    flutter, response, AeroelasticEquations, FlightHistory, FlutterMethod, FlutterOptions,
    FlutterSolution, Gust, GustPenetration, GustShape, ResponseOptions, ResponseSolution,
};
use flexwing::solve::integrate::{IntegratorStats, Radau, RadauOptions, Tolerances};
use flexwing::solve::{AuditLimits, Damping};

fn patil(n: usize) -> Aeroelastic {
    flexwing::wings::patil_wing(n, Aerodynamics::Peters { states: 6 }).expect("valid wing")
}

/// The flutter-speed plan: `modes` branches through `speeds` equal steps to 40 m/s, flutter
/// speed to 1e-6.
fn flutter_plan(modes: usize, speeds: usize) -> FlutterOptions {
    FlutterOptions::new(
        (1..=speeds)
            .map(|k| 40.0 * k as f64 / speeds as f64)
            .collect(),
        modes,
    )
}

fn gust_plan(rtol: f64) -> ResponseOptions {
    let flight = FlightHistory {
        deflection_changes: Vec::new(),
        initial: FlightCondition::at_speed(25.0),
        speed_change: None,
        root_angle_change: None,
        gust: Some(Gust {
            shape: GustShape::OneMinusCosine { length: 10.0 },
            amplitude: 1.0,
            start: 0.05,
            spanwise: Profile::Uniform(1.0),
            penetration: GustPenetration::Uniform,
        }),
    };
    let mut plan = ResponseOptions::new(flight, 2.0, 0.02);
    plan.rtol = rtol;
    plan
}

fn slope(t: f64, prev: Option<(usize, f64)>, n: usize) -> String {
    match prev {
        Some((n0, t0)) => format!("{:.2}", (t / t0).ln() / (n as f64 / n0 as f64).ln()),
        None => "–".into(),
    }
}

/// Flutter speed, its time and its spread for `aero` with `plan`.
fn time_flutter<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &FlutterOptions,
    budget: Duration,
    batches: usize,
) -> (f64, f64, f64, f64, usize) {
    let out = flutter(aero, plan, "flutter", &mut |_| {}).expect("plan");
    let f = out.flutter.expect("flutters");
    let (t, spread) = measure(budget, batches, || {
        black_box(flutter(aero, plan, "flutter", &mut |_| {}).expect("plan"));
    });
    (f.speed, f.frequency, t, spread, out.stats.newton_iterations)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let sections: Vec<&str> = args
        .iter()
        .map(String::as_str)
        .filter(|a| {
            [
                "flutter",
                "sweep",
                "gust",
                "audit",
                "family",
                "turbulence",
                "pk",
                "pk-once",
                "eigen-once",
            ]
            .contains(a)
        })
        .collect();
    if sections == ["pk-once"] || sections == ["eigen-once"] {
        let plan = patil_flutter_plan(if sections == ["pk-once"] {
            FlutterMethod::PkTheodorsen
        } else {
            FlutterMethod::Eigenvalues
        });
        let out = flutter(&patil(32), &plan, "flutter", &mut |_| {}).expect("plan");
        println!("{:?}\n{:?}", out.flutter, out.stats);
        return;
    }
    let want = |name: &str| sections.is_empty() || sections.contains(&name);
    let (budget, batches) = if quick {
        (Duration::from_millis(300), 3)
    } else {
        (Duration::from_millis(1500), 5)
    };

    let wing = patil(32);
    let rom6 = wing.reduced(&(0..6).collect::<Vec<_>>()).expect("rom");
    if want("flutter") {
        flutter_tables(&wing, budget, batches);
    }
    if want("sweep") {
        sweep_table(&wing, &rom6, budget, batches);
    }
    if want("gust") {
        gust_table(&wing, &rom6, budget, batches);
    }
    if want("audit") {
        audit_table(&wing, &rom6, budget, batches);
    }
    if want("pk") {
        pk_table(budget, batches);
    }
    if want("family") {
        family_table();
    }
    if want("turbulence") {
        turbulence_table(batches);
    }
}

/// The output spectra and RMS (`gust_spectra`, the linearization apart) of Patil's wing at
/// 25 m/s, 2°, in von Kármán turbulence (σ_w = 1 m/s, L = 2500 ft) on the default grid of 500
/// frequencies, full and reduced (r = 6), n = 16 and 32: the best of `batches` runs, CPU and
/// wall.
fn turbulence_table(batches: usize) {
    use flexwing::solve::aeroelastic::turbulence::{
        gust_spectra, FrequencyGrid, Spectrum, Turbulence,
    };
    use flexwing::solve::aeroelastic::{
        linearize, poles, Input, LinearizeOptions, Output, StateBasis,
    };
    println!("\nTurbulence: 500 frequencies, tip deflection, twist, root moment, lift; Patil's wing, Peters 6, 25 m/s\n");
    println!("| n | model | states | CPU (best of {batches}) | wall |");
    println!("|---|---|---|---|---|");
    let turbulence = Turbulence::new(Spectrum::VonKarman, 1.0);
    let grid = FrequencyGrid::default_for(25.0, turbulence.scale_length, 0.5);
    for n in [16, 32] {
        let wing = patil(n);
        for reduced in [false, true] {
            let options = LinearizeOptions {
                flight: FlightCondition {
                    speed: 25.0,
                    root_angle: 0.0349,
                    gravity: None,
                },
                loads: vec![],
                damping: Damping::None,
                static_options: Default::default(),
                inputs: vec![Input::Gust, Input::GustRate],
                outputs: vec![
                    Output::TipY,
                    Output::TipTwist,
                    Output::RootBendingMoment,
                    Output::Lift,
                ],
                basis: StateBasis::Velocities,
                mode_numbers: reduced.then(|| (1..=6).collect()),
            };
            let ss = if reduced {
                let rom = wing.reduced(&(0..6).collect::<Vec<_>>()).expect("rom");
                linearize(&rom, &options, "linearize")
            } else {
                linearize(&wing, &options, "linearize")
            }
            .expect("linear model");
            let Some(p) = poles(&ss.a) else {
                println!(
                    "| {n} | {} | {} | poles not computed (Schur form) | |",
                    if reduced { "reduced r = 6" } else { "full" },
                    ss.a.nrows()
                );
                continue;
            };
            let (mut cpu, mut wall) = (f64::INFINITY, f64::INFINITY);
            for _ in 0..batches {
                let (c0, w0) = (cpu_time(), std::time::Instant::now());
                let s = gust_spectra(&ss, &p, &turbulence, 25.0, &grid, "").expect("spectra");
                black_box(s);
                cpu = cpu.min(cpu_time() - c0);
                wall = wall.min(w0.elapsed().as_secs_f64());
            }
            println!(
                "| {n} | {} | {} | {} | {} |",
                if reduced { "reduced r = 6" } else { "full" },
                ss.a.nrows(),
                fmt_time(cpu),
                fmt_time(wall)
            );
        }
    }
}

/// The gust family of `examples/patil_gust_family.toml` (20 gusts, H = 30 … 350 ft, U_ref =
/// 1 m/s, 25 m/s at 2°, 10 s, output step 0.01 s) on Patil's wing with `n` elements, the full
/// model or the reduced one on 6 wet modes, at `rtol` (atol = rtol / 100).
fn family_plan(n: usize, reduced: bool, rtol: f64) -> GustFamilyPlan {
    let model = flexwing::wings::patil_wing(n, Aerodynamics::Steady)
        .expect("valid wing")
        .full()
        .clone();
    let aero = Aero {
        section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
        density: 0.0889,
        aerodynamics: Aerodynamics::Peters { states: 6 },
    };
    let times: Vec<f64> = (0..=1000).map(|k| 0.01 * k as f64).collect();
    let mut s = DynamicPlan::new(model, vec![], 10.0, times);
    s.settings.rtol = rtol;
    s.settings.atol = rtol * 1e-2;
    s.full = !reduced;
    s.reduced = if reduced { vec![6] } else { vec![] };
    let flight = FlightHistory {
        initial: FlightCondition {
            speed: 25.0,
            root_angle: 0.0349,
            gravity: None,
        },
        speed_change: None,
        root_angle_change: None,
        gust: None,
        deflection_changes: Vec::new(),
    };
    GustFamilyPlan {
        response: AeroDynamicPlan::new(s, aero, flight),
        lengths: GustLengths::Range {
            from: 30.0 * FOOT,
            to: 350.0 * FOOT,
            steps: 20,
        },
        reference_velocity: 1.0,
        alleviation: 1.0,
        start: 0.1,
        penetration: GustPenetration::Uniform,
    }
}

/// The family's CPU time (one run each: seconds, not microseconds), steps and the critical
/// root-bending-moment peak, full and reduced, n = 16 and 32, two tolerances.
fn family_table() {
    println!("\nGust family (examples/patil_gust_family.toml: 20 gusts, 10 s each), Patil's wing, Peters 6\n");
    println!("| n | model | rtol | steps (20 gusts) | CPU | wall | critical H, RBM (m) | RBM peak (N·m) |");
    println!("|---|---|---|---|---|---|---|---|");
    for n in [16, 32] {
        for rtol in [1e-6, 1e-4] {
            for reduced in [false, true] {
                let plan = family_plan(n, reduced, rtol);
                let (cpu0, wall0) = (cpu_time(), std::time::Instant::now());
                let out = gust_family::run(&plan, &mut NoProgress).expect("plan");
                let (cpu, wall) = (cpu_time() - cpu0, wall0.elapsed().as_secs_f64());
                let steps: usize = out.members.iter().map(|m| m.runs[0].steps).sum();
                let c = out.critical(0, 2).expect("a complete run");
                println!(
                    "| {n} | {} | {rtol:.0e} | {steps} | {} | {} | {:.2} | {:.2} |",
                    if reduced { "reduced r = 6" } else { "full" },
                    fmt_time(cpu),
                    fmt_time(wall),
                    c.gradient,
                    c.runs[0].peaks[2].extreme().0,
                );
            }
        }
    }
}

/// `examples/patil_flutter.toml`'s flutter plan: 4 branches through 2, 4, … 40 m/s, flutter
/// speeds to 1e-7.
fn patil_flutter_plan(method: FlutterMethod) -> FlutterOptions {
    let mut plan = FlutterOptions::new((1..=20).map(|k| 2.0 * k as f64).collect(), 4);
    plan.tolerance = 1e-7;
    plan.method = method;
    plan
}

/// One model's flutter analysis.
type FlutterRun<'a> = dyn Fn(&FlutterOptions) -> Result<FlutterSolution, flexwing::InputError> + 'a;

/// The p-k method (Theodorsen's `C(k)`) against the eigenvalue flutter (Peters 6 states) of the
/// same model and plan (`examples/patil_flutter.toml`: n = 32, 4 branches, 20 speeds, 1e-7),
/// full and reduced; the ratio is p-k over eigenvalues. Also n = 64.
fn pk_table(budget: Duration, batches: usize) {
    println!("\np-k (Theodorsen) against the eigenvalue flutter (Peters 6), Patil's wing, 4 branches × 20 speeds, tolerance 1e-7\n");
    println!("| model | method | flutter speed (m/s) | frequency (rad/s) | Newton iterations | linearizations | time | spread | CPU | p-k / eigenvalues (CPU) |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for n in [32, 64] {
        let wing = patil(n);
        let rom4 = wing.reduced(&(0..4).collect::<Vec<_>>()).expect("rom");
        let rom8 = wing.reduced(&(0..8).collect::<Vec<_>>()).expect("rom");
        let models: Vec<(String, Box<FlutterRun<'_>>)> = vec![
            (
                format!("full, n = {n}"),
                Box::new(|p: &FlutterOptions| flutter(&wing, p, "flutter", &mut |_| {})),
            ),
            (
                format!("reduced r = 4, n = {n}"),
                Box::new(|p: &FlutterOptions| flutter(&rom4, p, "flutter", &mut |_| {})),
            ),
            (
                format!("reduced r = 8, n = {n}"),
                Box::new(|p: &FlutterOptions| flutter(&rom8, p, "flutter", &mut |_| {})),
            ),
        ];
        for (name, run) in &models {
            if n == 64 && name.starts_with("reduced") {
                continue;
            }
            let mut eigen_cpu = f64::NAN;
            for method in [FlutterMethod::Eigenvalues, FlutterMethod::PkTheodorsen] {
                let plan = patil_flutter_plan(method);
                let out = run(&plan).expect("plan");
                let f = out.flutter.expect("flutters");
                let (t, spread) = measure(budget, batches, || {
                    black_box(run(&plan).expect("plan"));
                });
                let cpu = cpu_per_call(budget, || {
                    black_box(run(&plan).expect("plan"));
                });
                let ratio = if method == FlutterMethod::Eigenvalues {
                    eigen_cpu = cpu;
                    "–".to_string()
                } else {
                    format!("{:.2}", cpu / eigen_cpu)
                };
                println!(
                    "| {name} | {} | {:.8} | {:.8} | {} | {} | {} | {:.0} % | {} | {ratio} |",
                    match method {
                        FlutterMethod::Eigenvalues => "eigenvalues",
                        FlutterMethod::PkTheodorsen => "p-k",
                    },
                    f.speed,
                    f.frequency,
                    out.stats.newton_iterations,
                    out.stats.linearizations,
                    fmt_time(t),
                    spread * 100.0,
                    fmt_time(cpu)
                );
            }
        }
    }
}

/// Flutter speed against n, and at n = 32 by plan and for reduced models.
fn flutter_tables(wing: &Aeroelastic, budget: Duration, batches: usize) {
    println!("\nFlutter speed, full model, 6 branches through 10 speeds to 40 m/s\n");
    println!("| n | dofs | lag states | flutter speed (m/s) | frequency (rad/s) | Newton iterations | time | spread | slope |");
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut prev = None;
    for n in [8, 16, 32, 64] {
        let wing = patil(n);
        let (u, w, t, spread, it) = time_flutter(&wing, &flutter_plan(6, 10), budget, batches);
        println!(
            "| {n} | {} | {} | {u:.4} | {w:.4} | {it} | {} | {:.0} % | {} |",
            2 * n,
            wing.n_aero_states(),
            fmt_time(t),
            spread * 100.0,
            slope(t, prev, n)
        );
        prev = Some((n, t));
    }

    println!("\nFlutter speed at n = 32: plans, and the reduced model (first r wet modes)\n");
    println!("| model | branches × speeds | flutter speed (m/s) | error | Newton iterations | time | spread | ratio to full |");
    println!("|---|---|---|---|---|---|---|---|");
    let (u_full, _, t_full, s_full, it_full) =
        time_flutter(wing, &flutter_plan(6, 10), budget, batches);
    println!(
        "| full | 6 × 10 | {u_full:.4} | – | {it_full} | {} | {:.0} % | 1 |",
        fmt_time(t_full),
        s_full * 100.0
    );
    let (u, _, t, s, it) = time_flutter(wing, &flutter_plan(4, 8), budget, batches);
    println!(
        "| full | 4 × 8 | {u:.4} | {:.1e} | {it} | {} | {:.0} % | {:.3} |",
        (u - u_full) / u_full,
        fmt_time(t),
        s * 100.0,
        t / t_full
    );
    for r in [4, 6, 8] {
        let rom = wing.reduced(&(0..r).collect::<Vec<_>>()).expect("rom");
        let (u, _, t, s, it) = time_flutter(&rom, &flutter_plan(4, 10), budget, batches);
        println!(
            "| reduced r = {r} | 4 × 10 | {u:.4} | {:.1e} | {it} | {} | {:.0} % | {:.3} |",
            (u - u_full) / u_full,
            fmt_time(t),
            s * 100.0,
            t / t_full
        );
    }
}

/// A V-g sweep of 100 speeds, full and reduced.
fn sweep_table(
    wing: &Aeroelastic,
    rom6: &Aeroelastic<ReducedModel>,
    budget: Duration,
    batches: usize,
) {
    println!("\nV-g sweep: 100 speeds from 0.4 to 40 m/s, 6 branches, n = 32\n");
    println!("| model | Newton iterations | time | spread |");
    println!("|---|---|---|---|");
    let sweep = flutter_plan(6, 100);
    for (name, t) in [
        ("full", {
            let (_, _, t, s, it) = time_flutter(wing, &sweep, budget, batches);
            (t, s, it)
        }),
        ("reduced r = 6", {
            let (_, _, t, s, it) = time_flutter(rom6, &sweep, budget, batches);
            (t, s, it)
        }),
    ] {
        println!(
            "| {name} | {} | {} | {:.0} % |",
            t.2,
            fmt_time(t.0),
            t.1 * 100.0
        );
    }
}

/// The 1−cos gust response, full and reduced: wall time (median of batches) and CPU time of the
/// thread; tip error against the full model at rtol 1e-9 (integration and, for the reduced
/// model, truncation error) and against the same model at rtol 1e-9 (integration error only).
fn gust_table(
    wing: &Aeroelastic,
    rom6: &Aeroelastic<ReducedModel>,
    budget: Duration,
    batches: usize,
) {
    println!(
        "\n1−cos gust (1 m/s, 10 m, at 25 m/s), 2 s, Radau, n = 32: tip errors against rtol 1e-9\n"
    );
    println!("| model | states | rtol | steps | rejected | Jacobians | LU | tip error vs full (m) | vs own (m) | time | spread | CPU |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let reference = response(wing, &gust_plan(1e-9), "response", &mut |_| {}).expect("plan");
    let reference_rom = response(rom6, &gust_plan(1e-9), "response", &mut |_| {}).expect("plan");
    let tip_error = |a: &ResponseSolution, b: &ResponseSolution| {
        a.samples
            .iter()
            .zip(&b.samples)
            .map(|(a, b)| (a.tip[1] - b.tip[1]).abs())
            .fold(0.0, f64::max)
    };
    for (name, rtol) in [
        ("full", 1e-4),
        ("full", 1e-3),
        ("reduced r = 6", 1e-4),
        ("reduced r = 6", 1e-3),
    ] {
        let full = name == "full";
        let run = || {
            if full {
                response(wing, &gust_plan(rtol), "response", &mut |_| {}).expect("plan")
            } else {
                response(rom6, &gust_plan(rtol), "response", &mut |_| {}).expect("plan")
            }
        };
        let out = run();
        let err = tip_error(&out, &reference);
        let own = tip_error(&out, if full { &reference } else { &reference_rom });
        let states = out.states[0].len();
        let (t, s) = measure(budget, batches, || {
            black_box(run());
        });
        let cpu = cpu_per_call(budget, || {
            black_box(run());
        });
        println!(
            "| {name} | {states} | {rtol:.0e} | {} | {} | {} | {} | {err:.1e} | {own:.1e} | {} | {:.0} % | {} |",
            out.stats.steps,
            out.stats.rejected_steps,
            out.stats.jacobian_evaluations,
            out.stats.factorizations,
            fmt_time(t),
            s * 100.0,
            fmt_time(cpu)
        );
    }
}

/// The gust response of `aero` integrated by Radau (lag states eliminated in the Newton
/// systems) from the initial equilibrium `x0`, with or without the energy audit: the counters
/// and the audit's largest balance error.
fn audited_gust<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    x0: &[f64],
    rtol: f64,
    audit: bool,
) -> (IntegratorStats, Option<f64>) {
    let loads = AppliedLoads::none();
    let plan = gust_plan(rtol);
    let mut eqs =
        AeroelasticEquations::new(aero, &loads, vec![], plan.flight, &Damping::None, "flight")
            .expect("equations");
    if audit {
        let floor = eqs.energy_resolution(rtol);
        eqs.set_energy_audit(Some(AuditLimits {
            balance: Some((1e3 * rtol).clamp(1e-5, 0.1)),
            runaway: 9.0,
            floor,
            interval: 0.0,
        }));
    }
    let a0 = eqs.steady_states(0.0, x0);
    let y0 = eqs.state(x0, &vec![0.0; x0.len()], &a0);
    let atol = eqs.state_atol(rtol);
    let t_out: Vec<f64> = (0..=100).map(|k| 0.02 * k as f64).collect();
    let (_, stats) = Radau {
        options: RadauOptions {
            tolerances: Tolerances { rtol, atol },
            ..Default::default()
        },
    }
    .integrate(&mut eqs, 0.0, &y0, &t_out, &mut |_| {})
    .expect("gust response");
    let error = eqs.energy_balance().map(|b| {
        let mut b = b.clone();
        b.finish();
        b.max_error
    });
    (stats, error)
}

/// The cost of the energy audit on the 1−cos gust response (the gust table's runs, integrated
/// here with Radau's default options, with and without the audit).
fn audit_table(
    wing: &Aeroelastic,
    rom6: &Aeroelastic<ReducedModel>,
    budget: Duration,
    batches: usize,
) {
    println!("\nEnergy audit of the 1−cos gust response, 2 s, Radau, n = 32: cost\n");
    println!(
        "| model | rtol | steps off/on | Newton iterations off/on | time off | time on | \
         cost | balance error |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for (name, rtol) in [
        ("full", 1e-4),
        ("full", 1e-3),
        ("reduced r = 6", 1e-4),
        ("reduced r = 6", 1e-3),
    ] {
        let full = name == "full";
        let x0 = |rtol| -> Vec<f64> {
            let out = if full {
                response(wing, &gust_plan(rtol), "response", &mut |_| {})
            } else {
                response(rom6, &gust_plan(rtol), "response", &mut |_| {})
            };
            let n = if full {
                wing.structure().n_dofs()
            } else {
                rom6.structure().n_dofs()
            };
            out.expect("plan").states[0][..n].to_vec()
        };
        let x0 = x0(rtol);
        let go = |audit| {
            if full {
                audited_gust(wing, &x0, rtol, audit)
            } else {
                audited_gust(rom6, &x0, rtol, audit)
            }
        };
        let ((off, _), (on, error)) = (go(false), go(true));
        let (t_off, _) = measure(budget, batches, || {
            black_box(go(false));
        });
        let (t_on, _) = measure(budget, batches, || {
            black_box(go(true));
        });
        println!(
            "| {name} | {rtol:.0e} | {}/{} | {}/{} | {} | {} | {:+.0} % | {:.1e} |",
            off.steps,
            on.steps,
            off.newton_iterations,
            on.newton_iterations,
            fmt_time(t_off),
            fmt_time(t_on),
            100.0 * (t_on / t_off - 1.0),
            error.unwrap_or(f64::NAN)
        );
    }
}
