use super::super::response::{run, AeroDynamicOutcome};
use super::super::tests::patil;
use super::*;
use crate::analysis::dynamics::DynamicPlan;
use crate::analysis::NoProgress;
use crate::beam::Profile;
use crate::model::aero::{Aerodynamics, FlightCondition};
use crate::solve::aeroelastic::{FlightHistory, Gust, GustPenetration, GustShape};

const DT: f64 = 0.05;
const STEPS: usize = 16;

/// The input histories of the comparison, sampled at the communication times: a gust pulse,
/// a root-angle ramp, a tip force.
fn gust(t: f64) -> f64 {
    if t < 0.4 - 1e-9 {
        1.5 * (std::f64::consts::PI * t / 0.4).sin().powi(2)
    } else {
        0.0
    }
}
fn angle(t: f64) -> f64 {
    0.01 * (t / 0.3).min(1.0)
}
fn force(t: f64) -> f64 {
    20.0 * (5.0 * t).sin()
}

fn table(f: fn(f64) -> f64) -> TimeFunction {
    let t: Vec<f64> = (0..=STEPS).map(|k| k as f64 * DT).collect();
    let value = t.iter().map(|&t| f(t)).collect();
    TimeFunction::Table { t, value }
}

fn plan(
    flight: FlightHistory,
    loads: Vec<Load>,
    time: Vec<Option<TimeFunction>>,
) -> AeroDynamicPlan {
    let (model, aero) = patil(8, Aerodynamics::Wagner);
    let times: Vec<f64> = (0..=STEPS).map(|k| k as f64 * DT).collect();
    let mut s = DynamicPlan::new(model, loads, STEPS as f64 * DT, times);
    s.time = time;
    s.settings.rtol = 1e-8;
    s.settings.atol = 1e-10;
    AeroDynamicPlan::new(s, aero, flight)
}

fn steady() -> FlightHistory {
    FlightHistory::steady(FlightCondition {
        speed: 20.0,
        root_angle: 0.02,
        gravity: Some(9.80665),
    })
}

fn reference() -> AeroDynamicOutcome {
    let mut flight = steady();
    flight.gust = Some(Gust {
        shape: GustShape::History(table(gust)),
        amplitude: 1.0,
        start: 0.0,
        spanwise: Profile::Uniform(1.0),
        penetration: GustPenetration::Uniform,
    });
    flight.root_angle_change = Some((1.0, table(angle)));
    let length = 16.0;
    let tip = Load::PointForce {
        span: length,
        force: Force::Dead { fx: 0.0, fy: 1.0 },
    };
    let p = plan(flight, vec![tip], vec![Some(table(force))]);
    assert_eq!(p.structure.model.beam().length(), length);
    let out = run(&p, &mut NoProgress).unwrap();
    assert!(out.is_complete(), "{:?}", out.runs[0].status);
    out
}

/// The stepper's inputs set at the communication times with the first-order hold reproduce the
/// response whose flight history and loads are those inputs as piecewise-linear time functions
/// (an independent path through the equations: the case's own gust, root-angle change and
/// load against the stepper's offsets and unit load): agreement to the integration tolerance.
/// The stepper restarts the integrator at each of its 16 intervals; at rtol 1e-8 (atol 1e-10
/// rad) each run's error is ~1e-8 of its motion, so the bounds: tip and twist 1e-6 (m, rad)
/// against a tip motion above 0.05 m, the lift 1e-4 relative, the root moment 1e-2 N·m.
#[test]
fn stepping_the_inputs_matches_the_response_to_their_histories() {
    let out = reference();
    let p = plan(steady(), vec![], vec![]);
    let options = StepperOptions {
        model: 0,
        inputs: vec![Input::Gust, Input::RootAngle, Input::Force(8)],
        outputs: vec![
            Output::TipY,
            Output::TipTwist,
            Output::RootBendingMoment,
            Output::Lift,
            Output::TipX,
        ],
        hold: Hold::Linear,
    };
    let mut stepper = AeroStepper::new(&p, &options).unwrap();
    assert_eq!(stepper.start_values(), &[0.0, 0.02, 0.0]);
    let mut worst = [0.0f64; 4];
    for (k, sample) in out.runs[0].samples.iter().enumerate() {
        let t = k as f64 * DT;
        assert!((stepper.t() - t).abs() < 1e-12);
        assert!((sample.t - t).abs() < 1e-12);
        let v = stepper.output_values();
        worst[0] = worst[0].max((v[0] - sample.tip_y).abs());
        worst[1] = worst[1].max((v[2] - sample.root_bending_moment).abs());
        worst[2] = worst[2].max((v[3] - sample.lift).abs() / sample.lift.abs().max(1.0));
        worst[3] = worst[3].max((v[1] - sample.tip_twist).abs());
        assert!((v[4] - sample.tip_x).abs() < 1e-6);
        if k == STEPS {
            break;
        }
        let next = (k + 1) as f64 * DT;
        stepper.set_input(0, gust(next)).unwrap();
        stepper.set_input(1, 0.02 + angle(next)).unwrap();
        stepper.set_input(2, force(next)).unwrap();
        stepper.step(DT, &mut |_| {}).unwrap();
    }
    assert!(worst[0] < 1e-6, "{worst:?}");
    assert!(worst[1] < 1e-2, "{worst:?}");
    assert!(worst[2] < 1e-4, "{worst:?}");
    assert!(worst[3] < 1e-6, "{worst:?}");
    // The gust moved the wing: the comparison is not of two resting wings.
    let tips: Vec<f64> = out.runs[0].samples.iter().map(|s| s.tip_y).collect();
    let range = tips.iter().cloned().fold(f64::MIN, f64::max)
        - tips.iter().cloned().fold(f64::MAX, f64::min);
    assert!(range > 0.05, "{range}");
    // The energy audit ran across the calls and closed (rtol 1e-8: the default limit 1e-5).
    assert_eq!(stepper.status(), Status::Complete);
    let audit = stepper.energy_audit();
    assert!(audit.balanced && audit.max_error < 1e-5, "{audit:?}");
    assert!(stepper.stats().steps > STEPS);
    let [kinetic, strain, work, _] = stepper.energies();
    assert!(kinetic > 0.0 && strain > 0.0 && work.abs() > 0.0);
}

/// With the zero-order hold, inputs held constant over the whole run are the response to
/// constant histories: a regression test of the hold (same equations), and of the outputs'
/// direct dependence on an input set but not yet stepped (the lift on the gust).
#[test]
fn zero_hold_and_direct_feedthrough() {
    let mut flight = steady();
    flight.gust = Some(Gust {
        shape: GustShape::SharpEdged,
        amplitude: 0.5,
        // Just after the start: the response's lag states start steady without the gust, as the
        // stepper's (whose gust is set for the first interval).
        start: 1e-9,
        spanwise: Profile::Uniform(1.0),
        penetration: GustPenetration::Uniform,
    });
    let p = plan(flight, vec![], vec![]);
    let out = run(&p, &mut NoProgress).unwrap();
    let mut stepper = AeroStepper::new(
        &plan(steady(), vec![], vec![]),
        &StepperOptions {
            hold: Hold::Zero,
            ..StepperOptions::new(true)
        },
    )
    .unwrap();
    let lift_index = stepper
        .outputs()
        .iter()
        .position(|o| *o == Output::Lift)
        .unwrap();
    let before = stepper.output_values()[lift_index];
    let gust = stepper.input_index("gust").unwrap();
    stepper.set_input(gust, 0.5).unwrap();
    let after = stepper.output_values()[lift_index];
    // A 0.5 m/s upward gust at 20 m/s raises the angle of attack by 0.025 rad: more lift.
    assert!(after > before, "{before} {after}");
    for sample in &out.runs[0].samples[1..] {
        stepper.step(DT, &mut |_| {}).unwrap();
        let v = stepper.output_values();
        assert!(
            (v[1] - sample.tip_y).abs() < 1e-6,
            "{} {}",
            v[1],
            sample.tip_y
        );
    }
}

/// Bad arguments are errors naming what is wrong, and a step stopped inside its interval leaves
/// the stepper as it was.
#[test]
fn errors_and_a_stopped_step_leave_the_stepper_as_it_was() {
    let p = plan(steady(), vec![], vec![]);
    let bad = |inputs: Vec<Input>, outputs: Vec<Output>, model: usize| {
        AeroStepper::new(
            &p,
            &StepperOptions {
                model,
                inputs,
                outputs,
                hold: Hold::Linear,
            },
        )
        .err()
        .unwrap()
        .to_string()
    };
    let cases = [
        (
            bad(vec![Input::StripGust(2)], vec![Output::Lift], 0),
            "inputs[0]: gust[2] is an input of the linear model only",
        ),
        (
            bad(vec![Input::Gust, Input::Gust], vec![Output::Lift], 0),
            "inputs[1]: gust is given twice",
        ),
        (
            bad(vec![Input::Gust], vec![Output::RootShear], 0),
            "outputs[0]: root_shear is an output of the linear model only",
        ),
        (
            bad(vec![Input::Force(9)], vec![Output::Lift], 0),
            "inputs[0]: node 9 is out of range",
        ),
        (
            bad(vec![Input::Gust], vec![Output::Lift], 1),
            "model: is 1 but the plan has 1 model(s)",
        ),
    ];
    for (msg, expected) in cases {
        assert!(msg.starts_with(expected), "{msg}");
    }
    let mut stepper = AeroStepper::new(&p, &StepperOptions::new(true)).unwrap();
    let cases = [
        (
            stepper.set_input(0, f64::NAN).unwrap_err(),
            "root_angle: must be finite",
        ),
        (
            stepper.set_input(1, -1.0).unwrap_err(),
            "speed: must be non-negative",
        ),
        (
            stepper.set_input(7, 1.0).unwrap_err(),
            "inputs: index 7 is out of range",
        ),
    ];
    for (e, expected) in cases {
        assert!(e.to_string().starts_with(expected), "{e}");
    }
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let e = stepper.step(dt, &mut |_| {}).unwrap_err().to_string();
        assert!(
            e.starts_with("dt: must be a finite positive interval"),
            "{e}"
        );
    }
    stepper.step(DT, &mut |_| {}).unwrap();
    let (t, y) = (stepper.t(), stepper.state().to_vec());
    let audit = stepper.energy_audit();
    stepper.set_input(2, 3.0).unwrap();
    let halt = stepper.halt_flag();
    let e = stepper
        .step(DT, &mut |_| halt.store(true, Ordering::Relaxed))
        .unwrap_err();
    assert!(
        matches!(&e, StepError::Stopped(s) if matches!(**s, Stop::Interrupted { .. })),
        "{e}"
    );
    assert!(matches!(
        stepper.status(),
        Status::Stopped(Stop::Interrupted { .. })
    ));
    assert_eq!((stepper.t(), stepper.state()), (t, &y[..]));
    assert_eq!(stepper.energy_audit(), audit);
    // A retry goes on from there.
    stepper.step(DT, &mut |_| {}).unwrap();
    assert_eq!(stepper.status(), Status::Complete);
    assert!((stepper.t() - 2.0 * DT).abs() < 1e-15);
}
