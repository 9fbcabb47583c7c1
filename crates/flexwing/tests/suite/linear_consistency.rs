//! Linear consistency of the tip-load-matched calibration: under a small tip force the lumped
//! model's linear nodal deflections equal the Euler–Bernoulli cantilever's exactly (up to
//! round-off), for every `n`, uneven stations and a tapered `EI`.

use crate::common::*;
use flexwing::beam::{Beam, Calibration, Discretization, Profile};
use flexwing::model::{Force, FullModel, Load};
use flexwing::solve::linear_static;

const P: f64 = 1e-3; // N; linear statics, so the size only sets the scale.

fn tip_deflections(beam: Beam) -> Vec<[f64; 2]> {
    let length = beam.length();
    let model = FullModel::new(beam);
    let load = [Load::PointForce {
        span: length,
        force: Force::Dead { fx: 0.0, fy: P },
    }];
    let applied = model.apply(&load, "loads").expect("valid load");
    linear_static(&model, &applied).1
}

#[test]
fn uniform_beam_nodal_deflections_are_exact_for_every_n() {
    let (l, ei) = (1.0, 50.0);
    let section = bending_only(Profile::Uniform(ei), Profile::Uniform(0.2));
    let exact = |x: f64| P * x * x * (3.0 * l - x) / (6.0 * ei);
    for n in 1..=64 {
        let beam = Beam::new(
            l,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap();
        let nodes = beam.nodes().to_vec();
        let d = tip_deflections(beam);
        // 1e-9 relative: the rule is exact; what remains is round-off of sums of n terms.
        let tip = P * l.powi(3) / (3.0 * ei);
        assert!(
            (d[n][1] / tip - 1.0).abs() < 1e-9,
            "n = {n}: {} vs {tip}",
            d[n][1]
        );
        for (k, x) in nodes.iter().enumerate() {
            assert!(
                (d[k][1] - exact(*x)).abs() < 1e-9 * tip,
                "n = {n}, node {k}"
            );
        }
    }
}

#[test]
fn uneven_stations_and_coupled_beam_are_exact_too() {
    let l = 16.0;
    let stations = vec![0.0, 0.5, 1.5, 3.0, 5.5, 8.0, 11.0, 13.0, 15.2, 16.0];
    let beam = Beam::new(
        l,
        &table1_section(),
        &Discretization::Stations(stations),
        Calibration::TipLoad,
    )
    .unwrap();
    let d = tip_deflections(beam);
    let tip = P * l.powi(3) / (3.0 * 2e4);
    assert!((d[9][1] / tip - 1.0).abs() < 1e-9);
}

#[test]
fn tapered_beam_tip_deflection_matches_closed_form() {
    // EI(x) = a + b x. w(L) = P ∫ (L − s)² / EI(s) ds
    //       = P / b³ [c² ln(c/a) − 2c(c − a) + (c² − a²)/2],  c = EI(L).
    let (l, a, c): (f64, f64, f64) = (10.0, 4e4, 1e4);
    let b = (c - a) / l;
    let exact = P / b.powi(3) * (c * c * (c / a).ln() - 2.0 * c * (c - a) + 0.5 * (c * c - a * a));
    for n in [1, 2, 3, 7, 20, 50] {
        let section = bending_only(linear(l, a, c), Profile::Uniform(1.0));
        let beam = Beam::new(
            l,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap();
        let d = tip_deflections(beam);
        // The calibration integrates 1/EI by adaptive Gauss–Legendre to 1e-14: 1e-9 is round-off.
        assert!(
            (d[n][1] / exact - 1.0).abs() < 1e-9,
            "n = {n}: {} vs {exact}",
            d[n][1]
        );
    }
}

#[test]
fn uniform_rule_is_not_exact() {
    // The control: the uniform rule under-estimates the root stiffness, so the same check fails
    // (by about 1/(2n)·3/2 relative): the test above can tell the rules apart.
    let section = bending_only(Profile::Uniform(50.0), Profile::Uniform(0.2));
    let beam = Beam::new(
        1.0,
        &section,
        &Discretization::Uniform(10),
        Calibration::Uniform,
    )
    .unwrap();
    let d = tip_deflections(beam);
    let tip = P / (3.0 * 50.0);
    assert!((d[10][1] / tip - 1.0).abs() > 1e-2);
}
