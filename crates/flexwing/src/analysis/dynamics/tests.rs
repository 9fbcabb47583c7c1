use super::*;
use crate::model::Force;

fn plan() -> DynamicPlan {
    let model = crate::paper::table4_beam(4).unwrap();
    let tip = Load::PointForce {
        span: 1.0,
        force: Force::Dead { fx: 0.0, fy: 1.0 },
    };
    DynamicPlan::new(model, vec![tip], 1.0, vec![0.0, 0.5, 1.0])
}

#[test]
fn defaults() {
    let p = plan();
    assert!(p.validate("loads", "dynamic").is_ok());
    assert_eq!(p.models().unwrap(), [ModelKind::Full]);
    assert_eq!(p.integrator, Method::Radau);
    assert_eq!(p.settings, IntegratorSettings::default());
    assert_eq!(p.active(), [0]);
    let mut q = plan();
    q.simplified = true;
    q.reduced = vec![2];
    q.reduced_modes = vec![vec![1, 3]];
    let labels: Vec<String> = q.models().unwrap().iter().map(ModelKind::label).collect();
    assert_eq!(
        labels,
        ["full", "simplified", "reduced-r2", "reduced-modes-1-3"]
    );
    assert_eq!(
        q.gyroscopic_of(&ModelKind::Simplified),
        Gyroscopic::Neglected
    );
    assert_eq!(q.gyroscopic_of(&ModelKind::Full), Gyroscopic::Exact);
}

#[test]
fn errors_name_the_callers_fields() {
    type Change = Box<dyn Fn(&mut DynamicPlan)>;
    let cases: Vec<(Change, &str)> = vec![
        (
            Box::new(|p| p.end_time = -1.0),
            "dynamic.end_time: must be a finite positive number, got -1",
        ),
        (
            Box::new(|p| p.output_times = vec![0.0, 0.5, 0.7, 2.0]),
            "dynamic.output_times[3]: 2 is after end_time 1",
        ),
        (
            Box::new(|p| p.output_times = vec![0.0, 0.5, 0.5]),
            "dynamic.output_times[2]: 0.5 is not after",
        ),
        (
            Box::new(|p| p.output_times.clear()),
            "dynamic.output_times: must not be empty",
        ),
        (
            Box::new(|p| {
                p.time = vec![Some(TimeFunction::Table {
                    t: vec![0.0, 0.5],
                    value: vec![0.0, 1.0],
                })]
            }),
            "loads[0].time.t: table covers [0, 0.5] s but the simulation runs over [0, 1] s",
        ),
        (
            Box::new(|p| {
                p.time = vec![Some(TimeFunction::Ramp {
                    start: 0.5,
                    end: 0.2,
                })]
            }),
            "loads[0].time.end: must be after start",
        ),
        (
            Box::new(|p| p.settings.rtol = 1e-300),
            "dynamic.rtol: must be",
        ),
        (
            Box::new(|p| p.settings.atol = -1.0),
            "dynamic.atol: must be",
        ),
        (
            Box::new(|p| p.settings.max_order = 6),
            "dynamic.max_order: must be",
        ),
        (
            Box::new(|p| p.settings.max_step = Some(-1.0)),
            "dynamic.max_step: must be a finite positive number",
        ),
        (
            Box::new(|p| p.settings.step = Some(0.0)),
            "dynamic.step: must be",
        ),
        (
            Box::new(|p| p.gyroscopic = Gyroscopic::FiniteDifference { step: -1.0 }),
            "dynamic.gyroscopic_step: must be",
        ),
        (
            Box::new(|p| p.full = false),
            "dynamic.full: nothing to simulate",
        ),
        (
            Box::new(|p| p.reduced = vec![2, 2]),
            "dynamic.reduced[1]: the model reduced-r2 is already",
        ),
        (
            Box::new(|p| {
                p.damping = Damping::Rayleigh {
                    alpha: 0.0,
                    beta: -1.0,
                }
            }),
            "dynamic.damping.beta: must be a finite non-negative number",
        ),
        (
            Box::new(|p| {
                p.damping = Damping::Modal {
                    ratios: vec![0.1; 5],
                }
            }),
            "dynamic.damping.ratios: 5 ratios given but the model has 4 modes",
        ),
        (
            Box::new(|p| {
                p.damping = Damping::Modal {
                    ratios: vec![0.1, f64::NAN],
                }
            }),
            "dynamic.damping.ratios[1]: must be",
        ),
        (
            Box::new(|p| {
                p.initial = Initial::Given {
                    q: vec![0.0; 2],
                    qdot: vec![0.0; 4],
                }
            }),
            "dynamic.initial.q: needs 4 values",
        ),
        (
            Box::new(|p| {
                p.initial = Initial::Given {
                    q: vec![0.0; 4],
                    qdot: vec![0.0, 0.0, f64::INFINITY, 0.0],
                }
            }),
            "dynamic.initial.qdot[2]: must be finite",
        ),
        (
            Box::new(|p| p.initial = Initial::Static { loads: vec![0, 3] }),
            "dynamic.initial.loads[1]: there is no load 3",
        ),
    ];
    for (change, expected) in cases {
        let mut p = plan();
        change(&mut p);
        let msg = p.validate("loads", "dynamic").unwrap_err().to_string();
        assert!(msg.starts_with(expected), "{expected}: {msg}");
    }
}

/// Regression test of the runner on a small case: a failing step load keeps the outputs before
/// the failure; a static initial state starts at the deflection, at rest.
#[test]
fn a_stopped_run_keeps_its_output_and_the_initial_deflection_is_static() {
    let mut p = plan();
    p.output_times = vec![0.0, 0.1, 0.2, 0.5, 1.0];
    p.loads[0] = Load::PointForce {
        span: 1.0,
        force: Force::Dead { fx: 0.0, fy: 500.0 },
    };
    p.time = vec![Some(TimeFunction::Step { time: 0.3 })];
    p.integrator = Method::Midpoint;
    p.settings.step = Some(0.25);
    p.simplified = true;
    p.snapshots = vec![1, 0, 1];
    let outcome = run(&p, &mut crate::analysis::NoProgress).unwrap();
    assert!(!outcome.is_complete());
    for r in &outcome.runs {
        assert!(matches!(
            r.status.stop(),
            Some(crate::analysis::Stop::Integration(_))
        ));
        let t: Vec<f64> = r.samples.iter().map(|s| s.t).collect();
        assert_eq!(t, [0.0, 0.1, 0.2]);
        let indices: Vec<usize> = r.snapshots.iter().map(|s| s.index).collect();
        assert_eq!(indices, [0, 1]);
    }
    let mut p = plan();
    p.time = vec![None];
    p.initial = Initial::Static { loads: vec![0] };
    p.integrator = Method::Midpoint;
    let outcome = run(&p, &mut crate::analysis::NoProgress).unwrap();
    let first = outcome.runs[0].samples[0];
    assert_eq!(first.kinetic, 0.0);
    assert!(first.tip_y > 0.0 && first.strain > 0.0);
    // No load during the motion: the midpoint rule conserves the energy up to its Newton
    // tolerance (measured 1.1e-10; Radau's numerical damping would lose 2.2e-4 of it here):
    // bound 1e-6.
    let last = outcome.runs[0].samples.last().unwrap();
    let drift = (last.total() / first.total() - 1.0).abs();
    assert!(drift < 1e-6, "{drift:e}");
}
