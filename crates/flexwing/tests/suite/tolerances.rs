//! Tolerances that mean what they say (issue 24, item 4): the `atol` a user sets is the one the
//! error test applies, and a tighter `rtol` at a fixed `atol` never gives a less accurate answer,
//! for every integrator, on a closed-form reference (a lightly damped two-mode oscillator) and
//! on the case (Patil's wing in the patil_gust flight, against a run at rtol = atol =
//! 1e-11).

use flexwing::analysis::aero::response::{run as aero_run, AeroDynamicPlan};
use flexwing::analysis::aero::Aero;
use flexwing::analysis::dynamics::DynamicPlan;
use flexwing::analysis::NoProgress;
use flexwing::beam::Profile;
use flexwing::model::aero::{AeroSection, Aerodynamics, FlightCondition};
use flexwing::solve::aeroelastic::{FlightHistory, Gust, GustPenetration, GustShape};
use flexwing::solve::integrate::{integrate, IntegratorSettings, Method, OdeSystem};
use nalgebra::DMatrix;

/// Two uncoupled damped oscillators `ẍ + 2ζω ẋ + ω² x = 0` (ω = 3 and 40 rad/s, ζ = 0.01), in
/// first-order form `(x1, x2, v1, v2)`: a slow and a fast mode, the exact solution in closed form.
struct Oscillators;
const OMEGA: [f64; 2] = [3.0, 40.0];
const ZETA: f64 = 0.01;

impl OdeSystem for Oscillators {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        for k in 0..2 {
            let w = OMEGA[k];
            dy[k] = y[2 + k];
            dy[2 + k] = -w * w * y[k] - 2.0 * ZETA * w * y[2 + k];
        }
    }
    fn jacobian(&mut self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
        jac.fill(0.0);
        for k in 0..2 {
            let w = OMEGA[k];
            jac[(k, 2 + k)] = 1.0;
            jac[(2 + k, k)] = -w * w;
            jac[(2 + k, 2 + k)] = -2.0 * ZETA * w;
        }
    }
}

/// `x_k(t)` from `x(0) = 1e-3`, `ẋ(0) = 0` (amplitudes of the order of the chain's joint
/// rotations, so that `atol` matters).
fn exact(k: usize, t: f64) -> f64 {
    let w = OMEGA[k];
    let wd = w * (1.0 - ZETA * ZETA).sqrt();
    1e-3 * (-ZETA * w * t).exp() * ((wd * t).cos() + ZETA * w / wd * (wd * t).sin())
}

fn oscillator_error(method: Method, rtol: f64, atol: f64) -> (f64, usize) {
    let settings = IntegratorSettings {
        rtol,
        atol,
        max_steps: 1_000_000,
        ..IntegratorSettings::default()
    };
    let t: Vec<f64> = (0..=40).map(|k| 0.05 * k as f64).collect();
    let (traj, stats) = integrate(
        method,
        &settings,
        &mut Oscillators,
        0.0,
        &[1e-3, 1e-3, 0.0, 0.0],
        &t,
        &mut |_| {},
    )
    .unwrap_or_else(|f| panic!("{method:?} {rtol:e}: {}", f.error));
    let err = traj
        .t
        .iter()
        .zip(&traj.y)
        .map(|(&s, y)| (y[0] - exact(0, s)).abs().max((y[1] - exact(1, s)).abs()))
        .fold(0.0, f64::max);
    (err, stats.steps)
}

/// For every integrator, `rtol` from 1e-3 to 1e-9 at `atol` = 1e-6 (joint-rotation units, ~1e-3
/// of the amplitude) and at 1e-9: each tightening of `rtol` gives an error no larger than
/// 1.25 times the previous one. (Once `atol` dominates the error test, tightening `rtol` no longer
/// changes the steps much and the error stays at the `atol` floor: the step-size controllers'
/// round-off of the step sequence moves it by up to ~20 %: measured at most 1.19, Radau from
/// rtol 1e-7 to 1e-8 at atol 1e-6, 3.1e-8 → 3.7e-8; an error that grows by more than 25 % is the
/// failure of the issue.)
#[test]
fn a_tighter_rtol_never_loosens_any_integrator() {
    let methods = [
        Method::Radau,
        Method::Bdf,
        Method::Dopri5,
        Method::Midpoint,
        Method::GeneralizedAlpha,
    ];
    for method in methods {
        for atol in [1e-6, 1e-9] {
            let mut previous: Option<(f64, f64)> = None;
            for rtol in [1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9] {
                let (err, steps) = oscillator_error(method, rtol, atol);
                println!(
                    "{method:?} atol {atol:e} rtol {rtol:e}: error {err:.3e} in {steps} steps"
                );
                if let Some((prev_rtol, prev)) = previous {
                    assert!(
                        err <= 1.25 * prev,
                        "{method:?}, atol {atol:e}: error {err:.2e} at rtol {rtol:e} against \
                         {prev:.2e} at {prev_rtol:e}"
                    );
                }
                previous = Some((rtol, err));
            }
        }
    }
}

/// The case: Patil's wing (n = 16, Peters' 6 states) in the patil_gust flight, 1 s,
/// `atol` = 1e-5 fixed, for every integrator with an adaptive step: the tip twist's error at a
/// tighter `rtol` must not exceed that at the looser one (issue 24 measured 3.3e-2 of the twist
/// peak at 1e-8 against 2.1e-3 at the defaults with `RADAU5`'s scaling of `atol`). The reference
/// is a run of another integrator: BDF at rtol = atol = 1e-11 for Radau, Radau at 1e-11 for the
/// others (the two references agree to the figure printed, far below the errors measured). The
/// `rtol` pairs: 1e-6 → 1e-8 for the higher-order methods, 1e-4 → 1e-5 for the second-order
/// ones (their steps grow like rtol^(−1/2)). Measured errors of the peak (loose → tight): Radau
/// 5.1e-5 → 1.3e-5, BDF 2.6e-3 → 2.4e-3, Dormand–Prince 5.2e-4 → 5.1e-4 (both held by atol
/// there), midpoint 5.6e-3 → 2.7e-3, generalized-α 6.9e-3 → 3.1e-3; the references 4.1e-7
/// apart. Bound: no larger, ×1.25 for the controllers' noise (as above).
#[test]
fn the_gust_at_a_tighter_rtol_is_not_worse() {
    let twist = |method: Method, rtol: f64, atol: f64| -> Vec<f64> {
        let model = flexwing::wings::patil_wing(16, Aerodynamics::Steady)
            .unwrap()
            .full()
            .clone();
        let aero = Aero {
            section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
            density: 0.0889,
            aerodynamics: Aerodynamics::Peters { states: 6 },
        };
        let times: Vec<f64> = (0..=100).map(|k| 0.01 * k as f64).collect();
        let mut s = DynamicPlan::new(model, vec![], 1.0, times);
        s.integrator = method;
        s.settings.rtol = rtol;
        s.settings.atol = atol;
        s.settings.max_steps = 2_000_000;
        let flight = FlightHistory {
            deflection_changes: Vec::new(),
            initial: FlightCondition {
                speed: 25.0,
                root_angle: 0.0349,
                gravity: None,
            },
            speed_change: None,
            root_angle_change: None,
            gust: Some(Gust {
                shape: GustShape::OneMinusCosine { length: 10.0 },
                amplitude: 1.0,
                start: 0.1,
                spanwise: Profile::Uniform(1.0),
                penetration: GustPenetration::Uniform,
            }),
        };
        let out = aero_run(&AeroDynamicPlan::new(s, aero, flight), &mut NoProgress).unwrap();
        let r = &out.runs[0];
        // Every output time reached; a run may be `suspect`: the energy audit's default limit,
        // 1000 rtol but at least 1e-5, is below what atol = 1e-5 lets the balance drift (BDF at
        // rtol 1e-8: 1.3e-5), which is the audit doing its job, not this test's concern.
        assert!(
            matches!(r.status.word(), "complete" | "suspect"),
            "{method:?} {rtol:e}: {:?}",
            r.status
        );
        r.samples.iter().map(|s| s.tip_twist).collect()
    };
    let radau_reference = twist(Method::Radau, 1e-11, 1e-11);
    let bdf_reference = twist(Method::Bdf, 1e-11, 1e-11);
    let peak = radau_reference.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let error = |v: &[f64], reference: &[f64]| {
        v.iter()
            .zip(reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / peak
    };
    println!(
        "references: Radau − BDF at 1e-11: {:.2e} of the peak",
        error(&radau_reference, &bdf_reference)
    );
    let cases = [
        (Method::Radau, 1e-6, 1e-8),
        (Method::Bdf, 1e-6, 1e-8),
        (Method::Dopri5, 1e-6, 1e-8),
        (Method::Midpoint, 1e-4, 1e-5),
        (Method::GeneralizedAlpha, 1e-4, 1e-5),
    ];
    for (method, loose, tight) in cases {
        let reference = if method == Method::Radau {
            &bdf_reference
        } else {
            &radau_reference
        };
        let e_loose = error(&twist(method, loose, 1e-5), reference);
        let e_tight = error(&twist(method, tight, 1e-5), reference);
        println!(
            "{method:?}: twist error / peak: rtol {loose:e} {e_loose:.2e}, rtol {tight:e} \
             {e_tight:.2e} (atol 1e-5)"
        );
        assert!(
            e_tight <= 1.25 * e_loose,
            "{method:?}: {e_tight:.2e} > {e_loose:.2e}"
        );
    }
}
