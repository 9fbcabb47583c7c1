//! Discrete gust families (`analysis::aero::gust_family`, CS 25.341(a)): the design gust velocity
//! against the rule as written, in feet; and a family on Patil's wing whose members are the
//! response to the same gusts run one by one, linear in the gust velocity at small amplitudes.

use flexwing::analysis::aero::gust_family::{
    design_gust_velocity, run as family_run, GustFamilyPlan, GustLengths, FOOT, OUTPUTS,
};
use flexwing::analysis::aero::response::{run as response_run, AeroDynamicPlan};
use flexwing::analysis::aero::Aero;
use flexwing::analysis::dynamics::DynamicPlan;
use flexwing::analysis::NoProgress;
use flexwing::beam::Profile;
use flexwing::model::aero::{AeroSection, Aerodynamics, FlightCondition};
use flexwing::solve::aeroelastic::{FlightHistory, Gust, GustPenetration, GustShape};

/// `U_ds = U_ref F_g (H/350)^(1/6)` computed in feet (ft/s), CS 25.341(a)(5) at sea level
/// (`U_ref` = 56 ft/s) and at 15 000 ft (44 ft/s), `F_g` = 1 and 0.8: the library's metres agree
/// to round-off (bound 1e-12 relative); `U_ds = U_ref F_g` at H = 350 ft exactly; H outside
/// [30 ft, 350 ft], `U_ref ≤ 0` and `F_g` outside (0, 1] are one-line errors naming the key.
#[test]
fn design_gust_velocity_is_cs_25_341() {
    for u_ref_ft in [56.0, 44.0] {
        for fg in [1.0, 0.8] {
            for h_ft in [30.0, 60.0, 100.0, 200.0, 350.0] {
                let expected_ft: f64 =
                    u_ref_ft * fg * (h_ft / 350.0_f64).ln().mul_add(1.0 / 6.0, 0.0).exp();
                let got = design_gust_velocity(h_ft * FOOT, u_ref_ft * FOOT, fg, "g").unwrap();
                let rel = (got / FOOT - expected_ft).abs() / expected_ft;
                assert!(
                    rel < 1e-12,
                    "H = {h_ft} ft: {got} m/s against {expected_ft} ft/s"
                );
            }
        }
    }
    let at_350 = design_gust_velocity(350.0 * FOOT, 17.07, 0.9, "g").unwrap();
    assert!((at_350 - 17.07 * 0.9).abs() < 1e-12);
    for (h, u, fg, key) in [
        (29.0 * FOOT, 17.0, 1.0, "g.lengths"),
        (351.0 * FOOT, 17.0, 1.0, "g.lengths"),
        (100.0 * FOOT, 0.0, 1.0, "g.reference_velocity"),
        (100.0 * FOOT, 17.0, 0.0, "g.alleviation"),
        (100.0 * FOOT, 17.0, 1.2, "g.alleviation"),
    ] {
        let e = design_gust_velocity(h, u, fg, "g").unwrap_err();
        assert_eq!(e.field, key, "{e}");
    }
}

fn plan(end_time: f64) -> AeroDynamicPlan {
    let model = flexwing::wings::patil_wing(8, Aerodynamics::Steady)
        .unwrap()
        .full()
        .clone();
    let aero = Aero {
        section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
        density: 0.0889,
        aerodynamics: Aerodynamics::Peters { states: 4 },
    };
    let times: Vec<f64> = (0..=(end_time * 100.0).round() as usize)
        .map(|k| 0.01 * k as f64)
        .collect();
    let mut s = DynamicPlan::new(model, vec![], end_time, times);
    s.settings.rtol = 1e-6;
    s.settings.atol = 1e-8;
    let flight = FlightHistory {
        deflection_changes: Vec::new(),
        initial: FlightCondition {
            speed: 25.0,
            root_angle: 0.0349,
            gravity: None,
        },
        speed_change: None,
        root_angle_change: None,
        gust: None,
    };
    AeroDynamicPlan::new(s, aero, flight)
}

/// Patil's wing (n = 8, Peters 4, 25 m/s, 2°, rtol 1e-6), H = 30, 100 and 350 ft at `U_ref` =
/// 0.025, 0.05 and 0.1 m/s: (1) regression: each member's root-bending-moment peak is that of the
/// response to its gust run directly (the same code path: bound 1e-12 relative); (2) linear
/// theory: each peak doubles with `U_ref`, and its departure from ×2 is the model's non-linearity,
/// O(U): it doubles from the pair (0.025, 0.05) to (0.05, 0.1) (measured ratios 1.9–2.2 where it
/// exceeds 2e-5 (1e-4 for the root torque), below which the integration error at rtol 1e-6 is
/// comparable; bound 1.6), and
/// stays below 3e-2 (measured up to 1.3e-2, the 350 ft gust, whose tip deflection is 0.14 m per
/// 0.05 m/s: quasi-static at this speed); (3) an end time before the longest gust has passed is an error naming `dynamic.end_time`.
#[test]
fn a_family_is_its_members_run_one_by_one() {
    let lengths = GustLengths::List(vec![30.0 * FOOT, 100.0 * FOOT, 350.0 * FOOT]);
    let start = 0.05;
    let end = start + 2.0 * 350.0 * FOOT / 25.0 + 0.5;
    let family = |u_ref: f64| GustFamilyPlan {
        response: plan(end),
        lengths: lengths.clone(),
        reference_velocity: u_ref,
        alleviation: 1.0,
        start,
        penetration: GustPenetration::Uniform,
    };
    let t0 = std::time::Instant::now();
    let small = family_run(&family(0.025), &mut NoProgress).unwrap();
    println!(
        "family of 3 (n = 8, full): {:.2} s",
        t0.elapsed().as_secs_f64()
    );
    let middle = family_run(&family(0.05), &mut NoProgress).unwrap();
    let large = family_run(&family(0.1), &mut NoProgress).unwrap();
    assert!(small.is_complete() && middle.is_complete() && large.is_complete());
    for ((m, l), s) in middle
        .members
        .iter()
        .zip(&large.members)
        .zip(&small.members)
    {
        let mut direct = plan(end);
        direct.flight.gust = Some(Gust {
            shape: GustShape::OneMinusCosine {
                length: 2.0 * m.gradient,
            },
            amplitude: m.design_velocity,
            start,
            spanwise: Profile::Uniform(1.0),
            penetration: GustPenetration::Uniform,
        });
        let d = response_run(&direct, &mut NoProgress).unwrap();
        let s0 = &d.runs[0].samples;
        let rbm = s0
            .iter()
            .map(|s| s.root_bending_moment - s0[0].root_bending_moment);
        let max = rbm.fold(f64::NEG_INFINITY, f64::max);
        let p = &m.runs[0].peaks;
        assert!(
            (p[2].max - max).abs() <= 1e-12 * max.abs(),
            "{} vs {max}",
            p[2].max
        );
        for (r, name) in OUTPUTS.iter().enumerate() {
            let ratio =
                |a: &flexwing::analysis::aero::gust_family::GustMember,
                 b: &flexwing::analysis::aero::gust_family::GustMember| {
                    b.runs[0].peaks[r].magnitude() / a.runs[0].peaks[r].magnitude()
                };
            let (d1, d2) = ((ratio(s, m) - 2.0).abs(), (ratio(m, l) - 2.0).abs());
            println!(
                "H = {:.2} m, U_ds = {:.4} m/s: {name} peak {:+.4e} at {:.2} s / {:+.4e} at \
                 {:.2} s; ×2 U_ref departs from ×2 by {d1:.1e} (0.025 → 0.05 m/s), {d2:.1e} \
                 (0.05 → 0.1)",
                m.gradient, m.design_velocity, p[r].max, p[r].max_time, p[r].min, p[r].min_time
            );
            assert!(d2 < 3e-2, "{name}, H = {}: {d2:e}", m.gradient);
            // The root torque is the first torsion joint's spring, a small part of a state
            // the error control weighs as a whole: its departure at H = 30 ft is 5.2e-5 and
            // then 5.0e-5 (2026-12-03), not doubling, so integration error, not the model's.
            let floor = if *name == "root_torque" { 1e-4 } else { 2e-5 };
            assert!(
                d2 > 1.6 * d1 || d2 < floor,
                "{name}, H = {}: {d1:e} → {d2:e}",
                m.gradient
            );
        }
    }
    for (r, name) in OUTPUTS.iter().enumerate() {
        let c = middle.critical(0, r).unwrap();
        println!("critical H for {name}: {:.2} m", c.gradient);
    }
    let e = family_run(
        &GustFamilyPlan {
            response: plan(2.0),
            ..family(0.05)
        },
        &mut NoProgress,
    )
    .unwrap_err();
    assert!(e.to_string().starts_with("dynamic.end_time"), "{e}");
}
