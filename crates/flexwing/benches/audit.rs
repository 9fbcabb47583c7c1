//! The cost of the energy audit (`solve/energy_audit.rs`, `solve/aeroelastic/audit.rs`): every
//! integrator on the structural case (b) (full model at n = 20 and n = 1000, reduced model on 2
//! modes) and on the 1−cos gust response of Patil's wing (full model at n = 32 with Peters' 6
//! states, reduced on 6 modes), each run without and with the audit from the same state. Prints
//! one Markdown table: the counters off/on, the CPU time of each (min over the repeats and the
//! spread (max − min)/min), the ratio audited/unaudited of the minima, and the audit's largest
//! balance error. docs/performance.md, "The energy audit's cost".
//!
//! Run: `cargo bench -p flexwing --bench audit` (`-- --quick`: 3 repeats of 0.1 s instead of 5 of
//! 0.3 s, and no n = 1000 rows; `-- TEXT`: only the rows whose model and integrator contain
//! `TEXT`). Dormand–Prince is left out of the full models' rows: case (b) and the gust are stiff
//! for it at n = 20 and 32 (unaudited, it stops at its step limit after 4.7 s and 1.9 s; the
//! audit stops it within a few steps, when the energy runs away).

use std::time::Duration;

mod common;
use common::{cpu_per_call, fmt_time};

use flexwing::beam::Profile;
use flexwing::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
use flexwing::model::{AppliedLoads, FullModel, ReducedModel, StructuralModel};
use flexwing::solve::aeroelastic::{
    response, AeroelasticEquations, FlightHistory, Gust, GustPenetration, GustShape,
    ResponseOptions,
};
use flexwing::solve::integrate::{
    integrate, Bdf, BdfOptions, Dopri5, Dopri5Options, GeneralizedAlpha, GeneralizedAlphaOptions,
    ImplicitMidpoint, IntegrationResult, IntegratorSettings, IntegratorStats, Method,
    MidpointOptions, OdeSystem, Radau, RadauOptions, Tolerances,
};
use flexwing::solve::{AuditLimits, Damping, EquationsOfMotion, Gyroscopic, Modes, TimeFunction};

/// The default balance limit of a run at `rtol` (`AuditSettings::default_tolerance`), audited at
/// most once per output interval `interval` (as the library's analyses do).
fn limits(rtol: f64, floor: f64, interval: f64) -> AuditLimits {
    AuditLimits {
        balance: Some((1e3 * rtol).clamp(1e-5, 0.1)),
        runaway: 9.0,
        floor,
        interval,
    }
}

/// One run: the counters, the largest balance error (audited), and whether it completed.
type Run = (IntegratorStats, Option<f64>, bool);

/// Case (b) (the tip force 10 sin(20 t) N on the Table 4 beam, 1 s, from rest) on `model` by
/// `method` with `settings`, with or without the audit.
fn case_b<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    method: Method,
    settings: &IntegratorSettings,
    audit: bool,
) -> Run {
    let tf = vec![TimeFunction::Sine {
        omega: 20.0,
        phase: 0.0,
    }];
    let mut eom =
        EquationsOfMotion::new(model, loads, tf, Gyroscopic::Exact, &Damping::None).expect("eom");
    if audit {
        let floor = eom.energy_resolution(settings.atol);
        eom.set_energy_audit(Some(limits(settings.rtol, floor, 0.005)));
    }
    let nd = model.n_dofs();
    let y0 = eom.state(&vec![0.0; nd], &vec![0.0; nd]);
    let t_out: Vec<f64> = (0..=200).map(|k| 0.005 * k as f64).collect();
    let result = integrate(method, settings, &mut eom, 0.0, &y0, &t_out, &mut |_| {});
    finish(result, eom.energy_balance().cloned())
}

fn finish(result: IntegrationResult, balance: Option<flexwing::solve::EnergyBalance>) -> Run {
    let (stats, complete) = match result {
        Ok((_, stats)) => (stats, true),
        Err(f) => (f.stats, false),
    };
    let error = balance.map(|mut b| {
        b.finish();
        b.max_error
    });
    (stats, error, complete)
}

/// The 1−cos gust of `benches/aero.rs` (1 m/s over 10 m at 25 m/s, 2 s) on `aero` from its
/// equilibrium `x0`, integrated by `method` at `rtol` (tolerances in each state's units, the lag
/// states eliminated from the Newton systems), with or without the audit.
fn gust<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    x0: &[f64],
    method: Method,
    rtol: f64,
    step: Option<f64>,
    audit: bool,
) -> Run {
    let loads = AppliedLoads::none();
    let mut eqs =
        AeroelasticEquations::new(aero, &loads, vec![], flight(), &Damping::None, "flight")
            .expect("equations");
    if audit {
        let floor = eqs.energy_resolution(rtol);
        eqs.set_energy_audit(Some(limits(rtol, floor, 0.02)));
    }
    let a0 = eqs.steady_states(0.0, x0);
    let y0 = eqs.state(x0, &vec![0.0; x0.len()], &a0);
    let tolerances = Tolerances {
        rtol,
        atol: eqs.state_atol(rtol),
    };
    let t_out: Vec<f64> = (0..=100).map(|k| 0.02 * k as f64).collect();
    let result = by_method(method, tolerances, step, &mut eqs, &y0, &t_out);
    finish(result, eqs.energy_balance().cloned())
}

/// `integrate` with per-component tolerances (the aeroelastic equations' own units).
fn by_method<S: OdeSystem>(
    method: Method,
    tolerances: Tolerances,
    step: Option<f64>,
    system: &mut S,
    y0: &[f64],
    t_out: &[f64],
) -> IntegrationResult {
    let settings = IntegratorSettings {
        rtol: tolerances.rtol,
        step,
        ..Default::default()
    };
    system.integrating_with(method, &settings);
    let p = &mut |_| {};
    match method {
        Method::Radau => Radau {
            options: RadauOptions {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(system, 0.0, y0, t_out, p),
        Method::Bdf => Bdf {
            options: BdfOptions {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(system, 0.0, y0, t_out, p),
        Method::Dopri5 => Dopri5 {
            options: Dopri5Options {
                tolerances,
                ..Default::default()
            },
        }
        .integrate(system, 0.0, y0, t_out, p),
        Method::Midpoint => ImplicitMidpoint {
            options: MidpointOptions {
                tolerances,
                step,
                ..Default::default()
            },
        }
        .integrate(system, 0.0, y0, t_out, p),
        Method::GeneralizedAlpha => GeneralizedAlpha {
            options: GeneralizedAlphaOptions {
                tolerances,
                step,
                ..Default::default()
            },
        }
        .integrate(system, 0.0, y0, t_out, p),
    }
}

fn flight() -> FlightHistory {
    FlightHistory {
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
    }
}

/// The wing's coordinates at the gust's start: the static equilibrium the library response
/// starts from.
fn equilibrium<M: AeroStructure>(aero: &Aeroelastic<M>, rtol: f64) -> Vec<f64> {
    let mut plan = ResponseOptions::new(flight(), 0.02, 0.02);
    plan.rtol = rtol;
    let out = response(aero, &plan, "response", &mut |_| {}).expect("plan");
    out.states[0][..aero.structure().n_dofs()].to_vec()
}

struct Timing {
    repeats: usize,
    total: Duration,
    /// Only the rows whose "model integrator" contains this.
    filter: Option<String>,
}

/// The table row of one model and integrator: both runs once for the counters, then the CPU
/// time of each, alternating, `repeats` times.
fn row(label: &str, method: &str, timing: &Timing, mut go: impl FnMut(bool) -> Run) {
    if let Some(f) = &timing.filter {
        if !format!("{label} {method}").contains(f.as_str()) {
            return;
        }
    }
    let (off, _, off_ok) = go(false);
    let (on, error, on_ok) = go(true);
    let (mut t_off, mut t_on) = (Vec::new(), Vec::new());
    for _ in 0..timing.repeats {
        t_off.push(cpu_per_call(timing.total, || {
            std::hint::black_box(go(false));
        }));
        t_on.push(cpu_per_call(timing.total, || {
            std::hint::black_box(go(true));
        }));
    }
    let stat = |t: &[f64]| {
        let min = t.iter().copied().fold(f64::INFINITY, f64::min);
        let max = t.iter().copied().fold(0.0, f64::max);
        (min, (max - min) / min)
    };
    let ((off_min, off_spread), (on_min, on_spread)) = (stat(&t_off), stat(&t_on));
    let status = match (off_ok, on_ok) {
        (true, true) => "",
        _ => " (stopped)",
    };
    println!(
        "| {label} | {method}{status} | {}/{} | {}/{} | {}/{} | {} ({:.0} %) | {} ({:.0} %) | **{:.3}** | {:.1e} |",
        off.steps,
        on.steps,
        off.newton_iterations,
        on.newton_iterations,
        off.rhs_evaluations,
        on.rhs_evaluations,
        fmt_time(off_min),
        100.0 * off_spread,
        fmt_time(on_min),
        100.0 * on_spread,
        on_min / off_min,
        error.unwrap_or(f64::NAN)
    );
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    let filter = std::env::args().skip(1).find(|a| !a.starts_with("--"));
    let timing = if quick {
        Timing {
            repeats: 3,
            total: Duration::from_millis(100),
            filter,
        }
    } else {
        Timing {
            repeats: 5,
            total: Duration::from_millis(300),
            filter,
        }
    };
    println!(
        "\nEnergy audit: CPU time audited/unaudited, {} repeats of ≥ {} ms each\n",
        timing.repeats,
        timing.total.as_millis()
    );
    println!(
        "| model | integrator | steps off/on | Newton iterations off/on | right-hand sides \
         off/on | CPU off (spread) | CPU on (spread) | on/off | balance error |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");

    // Case (b): rtol 1e-3, atol 1e-5 rad (the library's defaults); the fixed steps those of
    // docs/performance.md (generalized-α 0.35 ms, the midpoint rule 1 ms).
    let adaptive = IntegratorSettings::default();
    let fixed = |h: f64| IntegratorSettings {
        step: Some(h),
        ..Default::default()
    };
    let structural: Vec<(&str, Method, IntegratorSettings)> = vec![
        ("Radau", Method::Radau, adaptive.clone()),
        ("BDF", Method::Bdf, adaptive.clone()),
        ("midpoint", Method::Midpoint, adaptive.clone()),
        ("midpoint h = 1 ms", Method::Midpoint, fixed(1e-3)),
        ("generalized-α", Method::GeneralizedAlpha, adaptive.clone()),
        (
            "generalized-α h = 0.35 ms",
            Method::GeneralizedAlpha,
            fixed(3.5e-4),
        ),
        ("Dormand–Prince", Method::Dopri5, adaptive.clone()),
    ];
    let case = flexwing::paper::sine_case(20).expect("case (b)");
    let full: FullModel = case.model.clone();
    let loads = full.apply(&case.loads, "loads").expect("loads");
    let modes = Modes::undeformed(&full).expect("modes");
    let rom = ReducedModel::first(&full, modes.shapes(), 2).expect("rom");
    for (name, method, settings) in structural.iter().filter(|s| s.1 != Method::Dopri5) {
        row("case (b) full n = 20", name, &timing, |audit| {
            case_b(&full, &loads, *method, settings, audit)
        });
    }
    for (name, method, settings) in &structural {
        row("case (b) reduced r = 2", name, &timing, |audit| {
            case_b(&rom, &loads, *method, settings, audit)
        });
    }
    if !quick {
        let case = flexwing::paper::sine_case(1000).expect("case (b)");
        let long: FullModel = case.model.clone();
        let loads = long.apply(&case.loads, "loads").expect("loads");
        for (name, method, settings) in [&structural[0], &structural[1], &structural[5]] {
            row("case (b) full n = 1000", name, &timing, |audit| {
                case_b(&long, &loads, *method, settings, audit)
            });
        }
    }

    // The gust: rtol 1e-3 (the library response's default) and the tolerances of each state.
    let wing = flexwing::wings::patil_wing(32, Aerodynamics::Peters { states: 6 }).expect("wing");
    let rom6 = wing.reduced(&(0..6).collect::<Vec<_>>()).expect("rom");
    let rtol = 1e-3;
    let (x_full, x_rom) = (equilibrium(&wing, rtol), equilibrium(&rom6, rtol));
    let aero: [(&str, Method, Option<f64>); 6] = [
        ("Radau", Method::Radau, None),
        ("BDF", Method::Bdf, None),
        ("midpoint", Method::Midpoint, None),
        ("generalized-α", Method::GeneralizedAlpha, None),
        (
            "generalized-α h = 2 ms",
            Method::GeneralizedAlpha,
            Some(2e-3),
        ),
        ("Dormand–Prince", Method::Dopri5, None),
    ];
    for (name, method, step) in aero.into_iter().filter(|a| a.1 != Method::Dopri5) {
        row("gust full n = 32", name, &timing, |audit| {
            gust(&wing, &x_full, method, rtol, step, audit)
        });
    }
    for (name, method, step) in aero {
        row("gust reduced r = 6", name, &timing, |audit| {
            gust(&rom6, &x_rom, method, rtol, step, audit)
        });
    }
}
