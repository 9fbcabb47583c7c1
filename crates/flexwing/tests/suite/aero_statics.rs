//! Static aeroelasticity: divergence of a uniform clamped wing against the closed form, and the
//! non-linear equilibrium under a root angle against the linear torsion solution.

use crate::common;
use flexwing::model::aero::Aerodynamics;
use flexwing::solve::aeroelastic::{static_sweep, AeroStaticOptions, DivergenceBasis};
use flexwing::solve::StaticOptions;

fn plan(speeds: Vec<f64>, root_angle: f64) -> AeroStaticOptions {
    AeroStaticOptions {
        speeds,
        root_angle,
        gravity: None,
        loads: vec![],
        options: StaticOptions::default(),
        divergence_tolerance: 1e-8,
    }
}

/// Divergence of Patil's wing. Closed form (docs/aeroelastic-model.md §5): GJ ψ'' + q c c_lα e ψ =
/// 0, ψ(0) = ψ'(L) = 0, so q_D = π² GJ / (4 L² e c c_lα) with e = ζ_ac = 0.25 m: 61.36 Pa,
/// U_D = 37.15 m/s. The chain's torsion is a second-order finite-difference discretization of
/// the shaft (springs between element midpoints, the aerodynamic moment at the midpoints).
#[test]
fn divergence_of_a_uniform_wing_converges_to_the_closed_form() {
    let (gj, l, e, c, cla, rho) = (1e4, 16.0, 0.25, 1.0, 2.0 * std::f64::consts::PI, 0.0889);
    let pi = std::f64::consts::PI;
    let q_exact = pi * pi * gj / (4.0 * l * l * e * c * cla);
    let u_exact = (2.0 * q_exact / rho).sqrt();
    let mut errors = Vec::new();
    for n in [8, 16, 32, 64] {
        let wing = common::patil_wing(n, Aerodynamics::Steady);
        let out = static_sweep(&wing, &plan(vec![10.0, 20.0], 0.0), "static", &mut |_| {}).unwrap();
        assert!(out.stopped.is_none());
        let d = out.divergence.expect("the wing diverges");
        let err = (d.dynamic_pressure - q_exact) / q_exact;
        println!(
            "n = {n}: q_D = {:.6} Pa, U_D = {:.5} m/s, error {err:.3e}",
            d.dynamic_pressure, d.speed
        );
        errors.push(err.abs());
    }
    println!("closed form: q_D = {q_exact:.6} Pa, U_D = {u_exact:.5} m/s (published 37.29 m/s)");
    // Second order: each halving of the element length divides the error by ~4 (measured
    // ratios printed above); bound 3.5 per halving and 1e-3 at n = 64.
    for w in errors.windows(2) {
        assert!(w[0] / w[1] > 3.5, "{errors:?}");
    }
    assert!(errors[3] < 1e-3, "{errors:?}");
}

/// Regression test (examples/section_flutter.toml printed a divergence speed beyond its sweep as
/// found): the undeformed wing's divergence speed is its linear one wherever it lies, and says
/// whether the sweep reached it; a deformed wing whose `μ(x*(q)) − q` does not change sign
/// within the sweep has none. Patil's wing, n = 16: U_D = 37.1 m/s (test above).
#[test]
fn a_divergence_speed_beyond_the_sweep_is_flagged_and_a_deformed_one_is_not_extrapolated() {
    let wing = common::patil_wing(16, Aerodynamics::Steady);
    let sweep = |speeds: Vec<f64>, root_angle: f64, stops: bool| {
        let out = static_sweep(&wing, &plan(speeds, root_angle), "static", &mut |_| {}).unwrap();
        assert_eq!(out.stopped.is_some(), stops);
        out.divergence
    };
    let below = sweep(vec![10.0, 20.0], 0.0, false).expect("the undeformed wing's divergence");
    // Past the divergence speed the static solver stops (at 40 m/s): the sweep attempted it.
    let across = sweep(vec![10.0, 20.0, 30.0, 40.0, 50.0], 0.0, true).expect("reached");
    println!("sweep to 20 m/s: {below:?}\nsweep to 50 m/s, stopped at 40: {across:?}");
    assert_eq!(below.basis, DivergenceBasis::Undeformed);
    assert!(below.speed > 20.0 && !below.within_sweep);
    assert_eq!(across.basis, DivergenceBasis::Undeformed);
    assert!(across.within_sweep);
    // The same number either way (one linear eigenproblem about x = 0): bound 1e-12 relative.
    assert!((below.speed - across.speed).abs() < 1e-12 * across.speed);
    // With a root angle the equilibria deform and μ moves with them: no crossing within 10 to
    // 30 m/s, so none reported (the crossing near 37 m/s is not extrapolated).
    assert_eq!(sweep(vec![10.0, 20.0, 30.0], 1e-3, false), None);
}

/// The equilibrium at a small root angle against the linear torsion solution of the uniform wing,
/// `ψ(x) = α_r (cos λ(L − x)/cos λL − 1)`, `λ² = q c c_lα e/GJ`, with the lift
/// `∫ q c c_lα (α_r + ψ) dx = q c c_lα α_r tan(λL)/λ`. At α_r = 1e-3 rad the non-linear terms are
/// O(α_r) ~ 1e-3 relative and the discretization error at n = 32 about 3e-4 (O(1/n²), the
/// divergence test); measured 8e-5 (tip twist) and 4e-5 (lift) at 20 and 30 m/s: bound 3e-3.
#[test]
fn small_root_angle_matches_the_linear_torsion_solution() {
    let (gj, l, e, c, cla, rho) = (1e4, 16.0, 0.25, 1.0, 2.0 * std::f64::consts::PI, 0.0889);
    let alpha = 1e-3;
    let wing = common::patil_wing(32, Aerodynamics::Peters { states: 6 });
    let out = static_sweep(&wing, &plan(vec![20.0, 30.0], alpha), "static", &mut |_| {}).unwrap();
    assert!(out.stopped.is_none());
    for p in &out.points {
        let q = 0.5 * rho * p.speed * p.speed;
        let lam = (q * c * cla * e / gj).sqrt();
        let tip = alpha * (1.0 / (lam * l).cos() - 1.0);
        let lift = q * c * cla * alpha * (lam * l).tan() / lam;
        println!(
            "U = {}: tip twist {:.6e} (linear {tip:.6e}), lift {:.5} N (linear {lift:.5})",
            p.speed, p.tip_twist, p.lift
        );
        assert!(
            (p.tip_twist - tip).abs() < 3e-3 * tip,
            "{} vs {tip}",
            p.tip_twist
        );
        assert!((p.lift - lift).abs() < 3e-3 * lift, "{} vs {lift}", p.lift);
        assert!(p.tip[1] > 0.0, "the wing bends up");
    }
}
