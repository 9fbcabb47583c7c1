//! The planar limit of the 3-D chain's aeroelasticity: the straight undeformed Patil wing on the
//! 3-D chain (point masses, tip-load calibration: the planar chain's lumping) has the planar
//! chain's flutter and divergence at the same `n`, for every aerodynamic model.
//!
//! Why they must agree: about the undeformed state a twist or flap motion of the 3-D chain is the
//! planar chain's (same springs, same inertia, same strips: `model/aero/spatial.rs`), and the lag
//! motion decouples — at zero lift without drag the strip loads do not depend on it to first
//! order. So the 3-D linearization is the planar one plus lag branches that are neutral (their
//! `Re s` is round-off, 1e-86 |s| measured, and the analysis gives them no crossings). A
//! regression/consistency test between two codes of the same theory; the planar chain itself is
//! validated against independent references in `aero_*.rs`.

use crate::common;
use crate::common::chain3d::patil_wing_3d;
use flexwing::model::aero::{AeroStructure, Aerodynamics, Aeroelastic};
use flexwing::model::chain3d::{ElementInertia, JointCalibration};
use flexwing::solve::aeroelastic::{
    flutter, static_sweep, AeroStaticOptions, DivergenceBasis, FlutterMethod, FlutterOptions,
    FlutterSolution,
};
use flexwing::solve::StaticOptions;

fn speeds() -> Vec<f64> {
    (1..=20).map(|k| 2.0 * k as f64).collect()
}

fn run<M: AeroStructure>(
    wing: &Aeroelastic<M>,
    modes: usize,
    method: FlutterMethod,
) -> FlutterSolution {
    let mut plan = FlutterOptions::new(speeds(), modes);
    plan.method = method;
    let out = flutter(wing, &plan, "flutter", &mut |_| {}).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    out
}

/// Flutter with every aerodynamic model and the p-k method: the flutter point (or the branches
/// unstable from the start), every crossing, and every tracked flap and torsion branch at every
/// speed agree with the planar chain's to round-off. Measured: flutter speeds 6e-16 relative
/// (Peters 6: 32.10109449865742 against …744 m/s at n = 16), branch eigenvalues ≤ 1e-13;
/// bound 1e-10 (the linearizations agree to round-off and the Newton and secant iterations
/// are smooth functions of them, stopping at 1e-11 … 1e-12).
#[test]
fn flutter_equals_the_planar_chain_s_for_every_model() {
    let n = 12;
    let cases = [
        (Aerodynamics::Steady, FlutterMethod::Eigenvalues),
        (Aerodynamics::QuasiSteady, FlutterMethod::Eigenvalues),
        (Aerodynamics::Wagner, FlutterMethod::Eigenvalues),
        (
            Aerodynamics::Peters { states: 6 },
            FlutterMethod::Eigenvalues,
        ),
        (
            Aerodynamics::Peters { states: 6 },
            FlutterMethod::PkTheodorsen,
        ),
    ];
    for (am, method) in cases {
        let planar = run(&common::patil_wing(n, am), 4, method);
        let wing = patil_wing_3d(n, am, ElementInertia::Point, JointCalibration::TipLoad);
        // The 3-D chain's lowest wet modes: the planar four and the first lag mode (31.7 rad/s).
        let spatial = run(&wing, 5, method);
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs().max(1e-300);
        // Branches matched by their wet frequency at U = 0.
        let mut lag = 0;
        println!(
            "{am:?}: wet frequencies 3-D {:?}, planar {:?}",
            spatial
                .branches
                .iter()
                .map(|b| b.wet_frequency)
                .collect::<Vec<_>>(),
            planar
                .branches
                .iter()
                .map(|b| b.wet_frequency)
                .collect::<Vec<_>>()
        );
        for b in &spatial.branches {
            match planar
                .branches
                .iter()
                .find(|p| rel(b.wet_frequency, p.wet_frequency) < 1e-10)
            {
                Some(p) => {
                    for (s3, s2) in b.eigenvalues.iter().zip(&p.eigenvalues) {
                        assert!(
                            (s3 - s2).norm() <= 1e-10 * s2.norm(),
                            "{am:?} {method:?} mode {}: {s3} vs {s2}",
                            p.mode
                        );
                    }
                }
                None => {
                    lag += 1;
                    // The lag branch: neutral, at its in-vacuo frequency at every speed.
                    for s in &b.eigenvalues {
                        assert!(s.re.abs() <= 1e-10 * s.norm(), "{am:?}: lag {s}");
                    }
                }
            }
        }
        assert_eq!(lag, 1, "{am:?}: one lag branch among the five");
        let crossings = |o: &FlutterSolution| -> Vec<(f64, f64)> {
            o.crossings.iter().map(|c| (c.speed, c.frequency)).collect()
        };
        let (c2, c3) = (crossings(&planar), crossings(&spatial));
        assert_eq!(c2.len(), c3.len(), "{am:?} {method:?}: {c2:?} vs {c3:?}");
        for (a, b) in c3.iter().zip(&c2) {
            assert!(
                rel(a.0, b.0) < 1e-10 && (a.1 - b.1).abs() < 1e-10 * b.0,
                "{a:?} vs {b:?}"
            );
        }
        assert_eq!(
            planar.unstable_at_start.is_empty(),
            spatial.unstable_at_start.is_empty(),
            "{am:?}"
        );
        match (&planar.flutter, &spatial.flutter) {
            (Some(a), Some(b)) => {
                println!(
                    "{am:?} {method:?}: flutter {:.14} vs planar {:.14} m/s ({:.1e}), ω {:.12}",
                    b.speed,
                    a.speed,
                    rel(b.speed, a.speed),
                    b.frequency
                );
                assert!(rel(b.speed, a.speed) < 1e-10 && rel(b.frequency, a.frequency) < 1e-10);
            }
            (None, None) => println!(
                "{am:?} {method:?}: no flutter point on either (unstable from the start: {:?})",
                spatial.unstable_at_start
            ),
            (a, b) => panic!("{am:?} {method:?}: {a:?} vs {b:?}"),
        }
    }
}

/// The divergence speed of the straight wing (steady equilibria along a sweep, the undeformed
/// wing's divergence pressure) equals the planar chain's: both are the smallest root of the same
/// torsion–aerodynamic pencil, the 3-D chain's lag and flap rows decoupled from it. Measured
/// 37.15 m/s at n = 12 on both to 1e-15 relative; bound 1e-12.
#[test]
fn divergence_equals_the_planar_chain_s() {
    let n = 12;
    let plan = AeroStaticOptions {
        speeds: vec![10.0, 20.0, 30.0],
        root_angle: 0.0,
        gravity: None,
        loads: vec![],
        options: StaticOptions::default(),
        divergence_tolerance: 1e-10,
    };
    let planar = static_sweep(
        &common::patil_wing(n, Aerodynamics::Steady),
        &plan,
        "s",
        &mut |_| {},
    )
    .unwrap()
    .divergence
    .unwrap();
    let wing = patil_wing_3d(
        n,
        Aerodynamics::Steady,
        ElementInertia::Point,
        JointCalibration::TipLoad,
    );
    let spatial = static_sweep(&wing, &plan, "s", &mut |_| {})
        .unwrap()
        .divergence
        .unwrap();
    println!(
        "divergence: 3-D {:.15} vs planar {:.15} m/s",
        spatial.speed, planar.speed
    );
    assert_eq!(spatial.basis, DivergenceBasis::Undeformed);
    assert!((spatial.speed - planar.speed).abs() < 1e-12 * planar.speed);
}
