//! Time responses: the lift after a sharp-edged gust follows Wagner's function (Jones' fit) on a
//! wing too stiff to move, and a root-angle change settles on the static aeroelastic equilibrium.

use crate::common;
use flexwing::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use flexwing::model::aero::{AeroSection, Aerodynamics, Aeroelastic, FlightCondition};
use flexwing::model::FullModel;
use flexwing::solve::aeroelastic::{
    response, static_sweep, AeroNewtonSystems, AeroStaticOptions, FlightHistory, Gust,
    GustPenetration, GustShape, ResponseOptions,
};
use flexwing::solve::{StaticOptions, TimeFunction};

/// Patil's planform made 1e6 times stiffer and 100 times heavier: under a gust it barely moves
/// (the plunge velocity of a suddenly loaded wing scales like 1/√(k m)).
fn stiff_wing(aerodynamics: Aerodynamics) -> Aeroelastic {
    let section = SectionProperties {
        ei: Profile::Uniform(2e10),
        mass_per_length: Profile::Uniform(75.0),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(1e10),
            polar_inertia: Profile::Uniform(10.0),
            inertia_axis: InertiaAxis::MassCentre,
            offset: Profile::Uniform(0.0),
        }),
    };
    let full = FullModel::new(
        Beam::new(
            16.0,
            &section,
            &Discretization::Uniform(8),
            Calibration::TipLoad,
        )
        .unwrap(),
    );
    let aero = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
    Aeroelastic::new(&full, &aero, 0.0889, aerodynamics, "aero").unwrap()
}

/// A sharp-edged gust on a rigid section with Jones' lag: the circulatory lift is
/// `L(t) = L_∞ φ(U(t − t0)/b)`, `φ(s) = 1 − 0.165 e^{−0.0455 s} − 0.335 e^{−0.3 s}` (the gust
/// enters the upwash at once, uniform over the chord: no Küssner penetration lag). The wing's own
/// motion under the gust changes the upwash a little (measured max deviation 8.2e-5 of L_∞; with
/// Patil's real stiffness ×1e4 and mass it was 8e-3, the plunge velocity of the suddenly loaded
/// wing); bound 5e-4.
#[test]
fn lift_after_a_sharp_edged_gust_follows_wagner() {
    let wing = stiff_wing(Aerodynamics::Wagner);
    let (u, vg, t0, b) = (30.0, 0.3, 0.01, 0.5);
    let flight = FlightHistory {
        deflection_changes: Vec::new(),
        initial: FlightCondition::at_speed(u),
        speed_change: None,
        root_angle_change: None,
        gust: Some(Gust {
            shape: GustShape::SharpEdged,
            amplitude: vg,
            start: t0,
            spanwise: Profile::Uniform(1.0),
            penetration: GustPenetration::Uniform,
        }),
    };
    let mut plan = ResponseOptions::new(flight, 1.0, 0.01);
    plan.rtol = 1e-8;
    plan.max_step = 0.005;
    let out = response(&wing, &plan, "response", &mut |_| {}).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    // Steady lift of the whole wing at the gust's angle atan(v_g/U), normal to the relative wind
    // (whose vertical component is cos of that angle): q c c_lα α cos α · L_span, q from |V∞+V_g|.
    let v2 = u * u + vg * vg;
    let alpha = (vg / u).atan();
    let l_inf = 0.5 * 0.0889 * v2 * 1.0 * 2.0 * std::f64::consts::PI * alpha * alpha.cos() * 16.0;
    let mut worst: f64 = 0.0;
    for s in out.samples.iter().filter(|s| s.t > t0) {
        let sb = (v2.sqrt()) * (s.t - t0) / b;
        let phi = 1.0 - 0.165 * (-0.0455 * sb).exp() - 0.335 * (-0.3 * sb).exp();
        worst = worst.max((s.lift / l_inf - phi).abs());
    }
    println!("max |L/L_inf − φ| = {worst:.2e}");
    assert!(worst < 5e-4, "{worst}");
}

/// A ramp of the root angle from 0 to 2° on the Goland wing at 100 m/s (below its flutter speed,
/// 137 m/s) with Peters' inflow: after 6 s the wing rests on the static aeroelastic equilibrium at
/// 2° computed by the static solver (a different code path: steady model, Newton). Measured
/// tip-twist and tip-deflection differences 9e-12 and 1e-12 relative; bound 1e-6.
#[test]
fn a_root_angle_ramp_settles_on_the_static_equilibrium() {
    let wing = common::goland_wing(8, Aerodynamics::Peters { states: 4 });
    let angle = 2f64.to_radians();
    let flight = FlightHistory {
        deflection_changes: Vec::new(),
        initial: FlightCondition::at_speed(100.0),
        speed_change: None,
        root_angle_change: Some((
            angle,
            TimeFunction::Ramp {
                start: 0.0,
                end: 0.5,
            },
        )),
        gust: None,
    };
    let out = response(
        &wing,
        &ResponseOptions::new(flight, 6.0, 0.5),
        "response",
        &mut |_| {},
    )
    .unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    let end = out.samples.last().unwrap();
    let statics = static_sweep(
        &wing,
        &AeroStaticOptions {
            speeds: vec![100.0],
            root_angle: angle,
            gravity: None,
            loads: vec![],
            options: StaticOptions::default(),
            divergence_tolerance: 1e-6,
        },
        "static",
        &mut |_| {},
    )
    .unwrap();
    let p = &statics.points[0];
    let (e_twist, e_tip) = (
        (end.tip_twist - p.tip_twist).abs() / p.tip_twist.abs(),
        (end.tip[1] - p.tip[1]).abs() / p.tip[1].abs(),
    );
    println!("twist {:.6e} vs {:.6e} ({e_twist:.1e}); tip {:.6e} vs {:.6e} ({e_tip:.1e}); lift {:.2} vs {:.2} N", end.tip_twist, p.tip_twist, end.tip[1], p.tip[1], end.lift, p.lift);
    assert!(e_twist < 1e-6 && e_tip < 1e-6);
}

/// Regression test (the eliminated Newton systems against the dense ones, same code otherwise):
/// a 1−cos gust on Patil's wing (n = 8, Peters' 6 states, 144 states in all) over 1 s at rtol
/// 1e-6, with Radau's Newton systems solved by eliminating the lag states (the default) and by
/// dense LU of the whole state. The Newton steps agree to round-off (unit test in `schur.rs`),
/// so the runs take the same steps (54); measured tip difference 1.1e-15 of the peak, twist 6e-17 rad;
/// bound 1e-9 of the peak, far below the integration error (rtol 1e-6).
#[test]
fn regression_gust_response_with_eliminated_lag_states_matches_dense_newton() {
    let wing = common::patil_wing(8, Aerodynamics::Peters { states: 6 });
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
    let mut plan = ResponseOptions::new(flight, 1.0, 0.02);
    let schur = response(&wing, &plan, "response", &mut |_| {}).unwrap();
    plan.newton_systems = AeroNewtonSystems::Dense;
    let dense = response(&wing, &plan, "response", &mut |_| {}).unwrap();
    assert!(schur.stopped.is_none() && dense.stopped.is_none());
    assert_eq!(schur.samples.len(), dense.samples.len());
    let peak = dense
        .samples
        .iter()
        .map(|s| s.tip[1].abs())
        .fold(0.0, f64::max);
    let (mut tip, mut twist): (f64, f64) = (0.0, 0.0);
    for (a, b) in schur.samples.iter().zip(&dense.samples) {
        tip = tip.max((a.tip[1] - b.tip[1]).abs() / peak);
        twist = twist.max((a.tip_twist - b.tip_twist).abs());
    }
    println!(
        "peak {peak:.4e} m; tip difference {tip:.1e} of the peak, twist {twist:.1e} rad; steps {} / {}",
        schur.stats.steps, dense.stats.steps
    );
    assert!(peak > 0.01, "the gust moves the wing: {peak}");
    assert!(tip < 1e-9 && twist < 1e-9, "{tip:.1e} {twist:.1e}");
}

/// The 1−cos gust of the benchmark (`benches/aero.rs`: Patil's wing, n = 32, Peters' 6 states,
/// 1 m/s over 10 m at 25 m/s, 2 s; full model and the reduced one of the first 6 wet modes) at
/// the tolerances the benchmark times, each model against itself at rtol 1e-9 (integration
/// error only; its own error ~1e-9). The absolute tolerance means `rtol` rad on a joint rotation
/// (`EquationsOfMotion::state_atol`). Measured, tip deflection error / peak change (0.34 m) and
/// tip twist error: full 8.2e-5 / 4.0e-5 rad at rtol 1e-3, 3.5e-5 / 2.1e-5 rad at 1e-4; reduced
/// 1.1e-3 / 1.7e-3 rad and 3.2e-4 / 3.9e-4 rad. The reduced model meets its tolerance less
/// tightly: its error norm weighs each modal momentum by the mode's energy, while the full
/// model's weighs each joint's momentum by that joint's local energy, which over-weights the
/// smooth momentum errors of the low modes (docs/performance.md, gust response). Bounds: full
/// `rtol` (of the peak, and rad); reduced `5 rtol`.
#[test]
fn gust_response_errors_follow_the_tolerance_against_a_tight_reference() {
    let wing = common::patil_wing(32, Aerodynamics::Peters { states: 6 });
    let rom = wing.reduced(&(0..6).collect::<Vec<_>>()).unwrap();
    let plan = |rtol: f64| {
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
        let mut p = ResponseOptions::new(flight, 2.0, 0.02);
        p.rtol = rtol;
        p
    };
    let errors = |run: &dyn Fn(f64) -> flexwing::solve::aeroelastic::ResponseSolution| {
        let reference = run(1e-9);
        let peak = reference
            .samples
            .iter()
            .map(|s| (s.tip[1] - reference.samples[0].tip[1]).abs())
            .fold(0.0, f64::max);
        assert!(peak > 0.3, "the gust moves the tip: {peak}");
        [1e-3, 1e-4].map(|rtol| {
            let out = run(rtol);
            assert!(out.stopped.is_none());
            let (mut tip, mut twist): (f64, f64) = (0.0, 0.0);
            for (a, b) in out.samples.iter().zip(&reference.samples) {
                tip = tip.max((a.tip[1] - b.tip[1]).abs());
                twist = twist.max((a.tip_twist - b.tip_twist).abs());
            }
            (rtol, peak, tip, twist, out.stats.steps)
        })
    };
    let full = errors(&|rtol| response(&wing, &plan(rtol), "response", &mut |_| {}).unwrap());
    let reduced = errors(&|rtol| response(&rom, &plan(rtol), "response", &mut |_| {}).unwrap());
    for (name, rows, factor) in [("full", full, 1.0), ("reduced r = 6", reduced, 5.0)] {
        for (rtol, peak, tip, twist, steps) in rows {
            println!(
                "{name}, rtol {rtol:.0e}: {steps} steps, tip error {tip:.1e} m (peak change {peak:.3} m), twist error {twist:.1e} rad"
            );
            let bound = factor * rtol;
            assert!(
                tip < bound * peak && twist < bound,
                "{name} {rtol}: {tip:.1e} {twist:.1e}"
            );
        }
    }
}
