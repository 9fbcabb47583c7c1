//! Torsion natural frequencies against the continuous shaft.
//! Uniform: `ω_k = (2k − 1) π / (2L) · √(GJ / I_ea)`. Tapered: the continuous reference of
//! `tests/data/continuous_beam/tapered_torsion.csv`. With `d0 = 0` torsion decouples from
//! bending; torsion modes are picked by their strain energy (bending share below 1e-6).

use crate::common::*;
use flexwing::beam::{Calibration, Profile};
use flexwing::solve::Modes;

fn torsion_frequencies(l: f64, gj: Profile, i_ea: Profile, n: usize) -> Vec<f64> {
    // A stiff, light bending half keeps bending modes out of the way; it does not couple.
    let section = coupled(
        Profile::Uniform(1e9),
        Profile::Uniform(1e-3),
        gj,
        i_ea,
        Profile::Uniform(0.0),
    );
    let m = model(l, &section, n, Calibration::TipLoad);
    // The lowest third of the modes holds the first torsion modes; the stiff bending modes at the
    // top of the spectrum (up to 1e7 times ω₁) are of no interest here.
    let modes = Modes::lowest(&m, m.n_dofs() / 3).unwrap();
    (0..modes.n_modes())
        .filter(|&k| modes.bending_energy_fraction(&m, k) < 1e-6)
        .map(|k| modes.omega()[k])
        .collect()
}

#[test]
fn uniform_shaft_first_three_within_one_percent_at_32_elements() {
    let (l, gj, i) = (2.0, 300.0, 0.05);
    let w = torsion_frequencies(l, Profile::Uniform(gj), Profile::Uniform(i), 32);
    for k in 1..=3 {
        let exact = (2 * k - 1) as f64 * std::f64::consts::PI / (2.0 * l) * (gj / i).sqrt();
        let e = w[k - 1] / exact - 1.0;
        assert!(e.abs() < 1e-2, "mode {k}: {e:.3e}");
    }
}

#[test]
fn tapered_shaft_converges_to_continuous_reference() {
    let reference = reference_frequencies("tapered_torsion.csv");
    let l = 10.0;
    let err = |n: usize| -> Vec<f64> {
        let w = torsion_frequencies(l, linear(l, 2e3, 5e2), linear(l, 0.2, 0.05), n);
        (0..3).map(|k| w[k] / reference[k] - 1.0).collect()
    };
    let (e32, e64) = (err(32), err(64));
    for k in 0..3 {
        // Within 1 % at n = 32 as for the uniform shaft, and second-order convergence.
        assert!(e32[k].abs() < 1e-2, "mode {}: {:.3e}", k + 1, e32[k]);
        let ratio = e32[k] / e64[k];
        assert!((3.5..4.5).contains(&ratio), "mode {}: ratio {ratio}", k + 1);
    }
}
