//! The chain's flutter (Theodorsen p-k) and divergence speeds converge at second order in `n`
//! to the continuous wing's, for Patil's HALE wing and the Goland wing. References: the
//! continuum strip-theory values of tests/data/aero_reference (Galerkin assumed modes, 20 per
//! field, solved in 30-digit arithmetic by an independent script), and the same script's exact
//! chain eigen-analysis at each `n` (which this test also checks the library against).

use crate::common;
use common::aero_reference::{beam_point, chain_point};
use flexwing::model::aero::{Aerodynamics, Aeroelastic};
use flexwing::solve::aeroelastic::{
    flutter, static_sweep, AeroStaticOptions, FlutterMethod, FlutterOptions,
};
use flexwing::solve::StaticOptions;

fn wing(case: &str, n: usize, am: Aerodynamics) -> Aeroelastic {
    if case == "patil" {
        common::patil_wing(n, am)
    } else {
        common::goland_wing(n, am)
    }
}

/// Theodorsen p-k flutter point (speed, frequency) of the chain with `n` elements.
fn pk_flutter(case: &str, n: usize) -> (f64, f64) {
    let step = if case == "patil" { 4.0 } else { 20.0 };
    let mut plan = FlutterOptions::new((1..=9).map(|k| step * k as f64).collect(), 6);
    plan.tolerance = 1e-12;
    plan.method = FlutterMethod::PkTheodorsen;
    let am = Aerodynamics::Peters { states: 6 };
    let out = flutter(&wing(case, n, am), &plan, "flutter", &mut |_| {}).unwrap();
    let f = out.flutter.expect("a flutter point");
    (f.speed, f.frequency)
}

fn divergence(case: &str, n: usize) -> f64 {
    let plan = AeroStaticOptions {
        speeds: vec![10.0],
        root_angle: 0.0,
        gravity: None,
        loads: vec![],
        options: StaticOptions::default(),
        divergence_tolerance: 1e-12,
    };
    static_sweep(
        &wing(case, n, Aerodynamics::Steady),
        &plan,
        "s",
        &mut |_| {},
    )
    .unwrap()
    .divergence
    .expect("a divergence speed")
    .speed
}

#[test]
fn flutter_and_divergence_converge_at_second_order_to_the_continuous_wing() {
    // Measured (this test's eprintln): p-k speed errors against the continuum at n = 8, 16, 32:
    // Patil −2.2e-3, −5.7e-4, −1.4e-4; Goland −4.9e-3, −1.2e-3, −3.1e-4 (ratios 3.9–4.0 per
    // halving of ℓ); divergence Patil −1.6e-3, −4.0e-4, −1.0e-4. Bounds: ratio in [3.5, 4.5]
    // (second order), and the chain against its own exact reference to 1e-10 (measured 1e-14:
    // the flutter root is refined to 1e-12).
    for case in ["patil", "goland"] {
        let (uc, wc) = beam_point(case, "flutter", "theodorsen", "galerkin", 20);
        let mut speed_errors = Vec::new();
        let mut frequency_errors = Vec::new();
        for n in [8, 16, 32] {
            let (u, w) = pk_flutter(case, n);
            let (ur, wr) = chain_point(case, "flutter", "theodorsen", n);
            assert!(((u - ur) / ur).abs() < 1e-10, "{case} n = {n}: {u} vs {ur}");
            assert!(((w - wr) / wr).abs() < 1e-10, "{case} n = {n}: {w} vs {wr}");
            speed_errors.push((u - uc) / uc);
            frequency_errors.push((w - wc) / wc);
        }
        eprintln!("{case}: speed errors {speed_errors:?}, frequency {frequency_errors:?}");
        for e in [&speed_errors, &frequency_errors] {
            for k in 0..2 {
                let ratio = e[k] / e[k + 1];
                assert!((3.5..4.5).contains(&ratio), "{case}: {e:?}");
            }
        }
    }
    // Divergence: the Patil wing's continuum value (closed form for the uniform wing,
    // tests/data/aero_reference) is 37.1539 m/s.
    let (dc, _) = beam_point("patil", "divergence", "steady", "closed_form", 0);
    let mut errors = Vec::new();
    for n in [8, 16, 32] {
        let d = divergence("patil", n);
        let (dr, _) = chain_point("patil", "divergence", "steady", n);
        assert!(((d - dr) / dr).abs() < 1e-10, "n = {n}: {d} vs {dr}");
        errors.push((d - dc) / dc);
    }
    eprintln!("patil divergence errors {errors:?}");
    for k in 0..2 {
        let ratio = errors[k] / errors[k + 1];
        assert!((3.5..4.5).contains(&ratio), "{errors:?}");
    }
}
