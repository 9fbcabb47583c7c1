//! Flutter: the tracked branches against the dense eigenvalues of the exact first-order
//! Jacobian, Patil's wing against the published point, the quasi-steady model's failure.

use crate::common;
use flexwing::model::aero::{Aerodynamics, FlightCondition};
use flexwing::solve::aeroelastic::{flutter, stability_eigenvalues, FlutterOptions};
use flexwing::solve::{Damping, StaticOptions};

/// The tracked branches are eigenvalues of the exact Jacobian of the whole first-order system
/// (lag states included), computed by a dense eigen-decomposition: the rational eigenproblem is
/// its exact Schur complement. Measured agreement 1e-12 relative; bound 1e-9.
#[test]
fn tracked_branches_are_eigenvalues_of_the_exact_jacobian() {
    for am in [Aerodynamics::Wagner, Aerodynamics::Peters { states: 4 }] {
        let wing = common::patil_wing(8, am);
        let plan = FlutterOptions::new(vec![10.0, 20.0, 25.0], 6);
        let out = flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap();
        assert!(out.stopped.is_none(), "{:?}", out.stopped);
        let dense = stability_eigenvalues(
            &wing,
            &FlightCondition::at_speed(25.0),
            &[],
            &Damping::None,
            &StaticOptions::default(),
            "flight",
        )
        .unwrap();
        for b in &out.branches {
            let s = b.eigenvalues[2];
            let d = dense
                .iter()
                .map(|e| (e - s).norm())
                .fold(f64::INFINITY, f64::min);
            println!(
                "{am:?} mode {}: s = {s:.6}, nearest dense eigenvalue {d:.2e}",
                b.mode
            );
            assert!(
                d < 1e-9 * s.norm(),
                "{s} not among the dense eigenvalues ({d:e})"
            );
        }
    }
}

/// Patil's wing with Peters' inflow (6 states): the flutter speed converges at second order in
/// the element length (measured 32.0488, 32.1011, 32.1148, 32.1182 m/s at n = 8 … 64: differences
/// 0.0523, 0.0137, 0.0034, ratios 3.8 and 4.0; Richardson extrapolation 32.119 m/s at
/// 22.520 rad/s). The published linear point, 32.21 m/s at 22.61 rad/s (Patil, Hodges & Cesnik
/// 2001), came from a coarse discretization; it lies 0.3 % above (the issue expects up to ~1 %):
/// bound 1 % on speed and frequency at n = 32.
#[test]
fn patil_wing_flutter_converges_in_n() {
    let mut points = Vec::new();
    for n in [8, 16, 32] {
        let wing = common::patil_wing(n, Aerodynamics::Peters { states: 6 });
        let speeds: Vec<f64> = (1..=10).map(|k| 4.0 * k as f64).collect();
        let out = flutter(
            &wing,
            &FlutterOptions::new(speeds, 6),
            "flutter",
            &mut |_| {},
        )
        .unwrap();
        assert!(out.unstable_at_start.is_empty() && out.stopped.is_none());
        let f = out.flutter.expect("flutters");
        println!(
            "n = {n}: flutter {:.5} m/s at {:.5} rad/s (branch {})",
            f.speed, f.frequency, f.branch
        );
        points.push((f.speed, f.frequency));
    }
    let ratio = (points[1].0 - points[0].0) / (points[2].0 - points[1].0);
    assert!(ratio > 3.5 && ratio < 4.5, "order: ratio {ratio}");
    let (u, w) = points[2];
    assert!((u - 32.21).abs() < 0.01 * 32.21 && (w - 22.61).abs() < 0.01 * 22.61);
}

/// The undeformed-wing fast path (two linearizations scaled in U) against the direct path (a
/// linearization at every speed, forced here by a zero load): the same flutter speed to the
/// refinement tolerance (1e-8 relative asked; measured 1e-12).
#[test]
fn scaled_and_direct_linearizations_agree() {
    use flexwing::model::{Force, Load};
    let wing = common::patil_wing(8, Aerodynamics::Peters { states: 6 });
    let mut plan = FlutterOptions::new((1..=10).map(|k| 4.0 * k as f64).collect(), 4);
    plan.tolerance = 1e-8;
    let fast = flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap();
    assert_eq!(
        fast.stats.static_solves, 0,
        "the fast path solves no equilibrium"
    );
    plan.loads = vec![Load::PointForce {
        span: 16.0,
        force: Force::Dead { fx: 0.0, fy: 0.0 },
    }];
    let direct = flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap();
    assert!(direct.stats.static_solves > 0);
    let (a, b) = (fast.flutter.unwrap(), direct.flutter.unwrap());
    println!("fast {a:?}\ndirect {b:?}");
    assert!((a.speed - b.speed).abs() < 1e-7 * a.speed);
    assert!((a.frequency - b.frequency).abs() < 1e-6 * a.frequency);
}

/// The quasi-steady model (C(k) = 1) on Patil's wing, elastic axis at mid-chord: the torsion
/// branch has no aerodynamic pitch damping (docs/aeroelastic-model.md §5). The analysis must not
/// hand out a flutter speed silently: it reports what it finds at the lowest speed.
#[test]
fn quasi_steady_model_on_a_mid_chord_elastic_axis() {
    let wing = common::patil_wing(16, Aerodynamics::QuasiSteady);
    let plan = FlutterOptions::new(vec![0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 30.0, 40.0], 6);
    let out = flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap();
    // The torsion branches (wet frequencies 30.7 and 91.8 rad/s) are unstable at 0.5 m/s already
    // (measured Re s = 1.3e-5 and 1.5e-6 1/s, growing like U²).
    let torsion: Vec<usize> = out
        .branches
        .iter()
        .enumerate()
        .filter(|(_, b)| b.wet_frequency > 30.0 && b.wet_frequency < 31.0)
        .map(|(i, _)| i)
        .collect();
    assert_eq!(torsion.len(), 1);
    assert!(
        out.unstable_at_start.contains(&torsion[0]),
        "{:?}",
        out.unstable_at_start
    );
    assert!(
        out.flutter.is_none(),
        "no flutter speed handed out: {:?}",
        out.flutter
    );
    // The first bending branch becomes real and crosses zero at the static divergence speed
    // (37.139 m/s at n = 16, tests/suite/aero_statics.rs): the dynamic and static analyses agree.
    let divergence = out
        .crossings
        .iter()
        .find(|c| c.frequency == 0.0 && c.kind == flexwing::solve::aeroelastic::CrossingKind::Onset)
        .expect("divergence seen by the dynamic analysis");
    assert!((divergence.speed - 37.13895).abs() < 1e-4, "{divergence:?}");
}

/// The frequency-domain check on the full chains: the p-k method with Theodorsen's function on
/// the same linearization, against the finite-state models at their flutter points. Patil's wing
/// (n = 16) and the Goland wing (n = 16, classical strip-theory flutter about 137 m/s near
/// 70 rad/s). Peters with 6 states is within its C(k) fit (measured printed; bound 1.5 %), and
/// the Goland p-k point is within 2 % of the classical 137 m/s, 70 rad/s (the classical value
/// is itself from coarse modal solutions).
#[test]
fn p_k_theodorsen_validates_the_finite_state_flutter_points() {
    use flexwing::solve::aeroelastic::FlutterMethod;
    for (name, wing, speeds) in [
        (
            "Patil",
            common::patil_wing(16, Aerodynamics::Peters { states: 6 }),
            (1..=10).map(|k| 4.0 * k as f64).collect::<Vec<_>>(),
        ),
        (
            "Goland",
            common::goland_wing(16, Aerodynamics::Peters { states: 6 }),
            (1..=10).map(|k| 20.0 * k as f64).collect::<Vec<_>>(),
        ),
    ] {
        let mut plan = FlutterOptions::new(speeds, 6);
        let peters = flutter(&wing, &plan, "flutter", &mut |_| {})
            .unwrap()
            .flutter
            .unwrap();
        plan.method = FlutterMethod::PkTheodorsen;
        let pk = flutter(&wing, &plan, "flutter", &mut |_| {})
            .unwrap()
            .flutter
            .unwrap();
        let e = (peters.speed - pk.speed) / pk.speed;
        println!(
            "{name}: p-k Theodorsen {:.4} m/s at {:.4} rad/s; Peters 6 {:.4} m/s at {:.4} rad/s ({e:+.3e})",
            pk.speed, pk.frequency, peters.speed, peters.frequency
        );
        assert!(e.abs() < 0.015, "{name}: {e}");
        if name == "Goland" {
            assert!(
                (pk.speed - 137.0).abs() < 0.02 * 137.0
                    && (pk.frequency - 70.0).abs() < 0.02 * 70.0
            );
        }
    }
}

/// Regression test (issue 9's fuzz find): Patil's wing, n = 8, Peters 6 states, a coarse sweep
/// of 3 speeds from 2 to 1000 m/s. Before the step control took 92 s in the p-k check alone
/// (97 663 halvings, 10.8 million Newton iterations: after a coalescence every sub-step restarted
/// from the whole interval and fell to the smallest step). The work is now bounded by the rule of
/// `flutter.rs`: per interval of the plan at most `MAX_SUBSTEPS` accepted sub-steps, and at most
/// one halving per acceptance beyond `log2(interval / smallest step) < 25` — so at most
/// `2 MAX_SUBSTEPS + 25` trial speeds per interval. The outcome is either a flutter point equal to
/// the fine sweep's (2 m/s steps to 40 m/s, the same model, tolerance 1e-7 asked: bound 1e-6
/// relative) or none with an honest stop naming the interval; the coarse sweep finds the onset
/// before it stops (measured: eigenvalues, branch 3 lost between 2 and 88.99 m/s after 18
/// sub-steps, 61 trials; p-k, the sub-step cap between 2 and 501 m/s, 2019 trials).
#[test]
fn coarse_sweep_work_is_bounded_and_its_flutter_point_matches_a_fine_sweep() {
    use flexwing::solve::aeroelastic::{FlutterMethod, FlutterStop, MAX_SUBSTEPS};
    let wing = common::patil_wing(8, Aerodynamics::Peters { states: 6 });
    for method in [FlutterMethod::Eigenvalues, FlutterMethod::PkTheodorsen] {
        let run = |speeds: Vec<f64>| {
            let mut plan = FlutterOptions::new(speeds, 4);
            plan.tolerance = 1e-7;
            plan.method = method;
            flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap()
        };
        let fine = run((1..=20).map(|k| 2.0 * k as f64).collect());
        assert!(fine.stopped.is_none(), "{:?}", fine.stopped);
        let reference = fine.flutter.expect("the fine sweep flutters");
        let speeds = vec![2.0, 501.0, 1000.0];
        let coarse = run(speeds.clone());
        println!(
            "{method:?}: {:?}; stop: {}",
            coarse.stats,
            coarse
                .stopped
                .as_ref()
                .map_or("none".into(), |s| s.to_string())
        );
        // Three intervals of the plan (0 → 2 → 501 → 1000).
        let bound = speeds.len() * (2 * MAX_SUBSTEPS + 25);
        assert!(coarse.stats.trials <= bound, "{:?}", coarse.stats);
        let f = coarse.flutter.expect("the onset lies before the stop");
        assert!(
            (f.speed / reference.speed - 1.0).abs() < 1e-6
                && (f.frequency / reference.frequency - 1.0).abs() < 1e-6,
            "{f:?} against {reference:?}"
        );
        match &coarse.stopped {
            None => {}
            Some(FlutterStop::BranchLost {
                from,
                speed,
                substeps,
                ..
            }) => {
                assert!(speeds.contains(from) && speed > from && *speed <= 1000.0);
                assert!(*substeps <= MAX_SUBSTEPS);
            }
            Some(other) => panic!("{other:?}"),
        }
    }
}

/// Cancellation is polled inside the tracking: a callback that says stop after its third call
/// ends the analysis there with `Cancelled` and the data reached, and is not called again.
#[test]
fn a_cancelled_flutter_analysis_stops_at_once() {
    use flexwing::solve::aeroelastic::{flutter_polled, FlutterMethod, FlutterStop};
    let wing = common::patil_wing(8, Aerodynamics::Peters { states: 6 });
    let mut plan = FlutterOptions::new(vec![2.0, 501.0, 1000.0], 4);
    plan.method = FlutterMethod::PkTheodorsen;
    let mut calls = 0;
    let out = flutter_polled(&wing, &plan, "flutter", &mut |_| {
        calls += 1;
        calls < 3
    })
    .unwrap();
    assert!(
        matches!(out.stopped, Some(FlutterStop::Cancelled { .. })),
        "{:?}",
        out.stopped
    );
    assert_eq!(calls, 3);
    assert!(out.stats.trials <= 2, "{:?}", out.stats);
}
