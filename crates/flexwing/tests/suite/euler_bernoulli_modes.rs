//! Bending-only natural frequencies against the Euler–Bernoulli cantilever,
//! `ω_k = (β_k L)² √(EI / (m L⁴))` with `β_k L` the roots of `1 + cos x cosh x = 0`.
//! Also the tapered bending-only beam against the continuous reference of
//! `tests/data/continuous_beam/tapered_bending.csv` (see its README for provenance).

use crate::common::*;
use flexwing::beam::{Calibration, Profile};
use flexwing::solve::Modes;

fn errors(n: usize, cal: Calibration) -> Vec<f64> {
    let (l, ei, m) = (1.0, 50.0, 0.2);
    let roots = euler_bernoulli_roots(4);
    let section = bending_only(Profile::Uniform(ei), Profile::Uniform(m));
    let modes = Modes::undeformed(&model(l, &section, n, cal)).unwrap();
    roots
        .iter()
        .enumerate()
        .map(|(k, bl)| modes.omega()[k] / (bl * bl * (ei / (m * l.powi(4))).sqrt()) - 1.0)
        .collect()
}

#[test]
fn roots_are_the_textbook_values() {
    let r = euler_bernoulli_roots(4);
    for (a, b) in r
        .iter()
        .zip([1.8751040687, 4.6940911330, 7.8547574382, 10.9955407349])
    {
        assert!((a - b).abs() < 1e-9);
    }
}

#[test]
fn first_three_within_half_percent_at_32_elements() {
    let e = errors(32, Calibration::TipLoad);
    for k in 0..3 {
        assert!(e[k].abs() < 5e-3, "mode {}: {:.3e}", k + 1, e[k]);
    }
}

#[test]
fn frequencies_converge_at_the_expected_order() {
    // Tip-load rule: lumped masses and exact-deflection springs, error ∝ 1/n², so doubling n
    // divides it by ≈ 4. Uniform rule: the root spring EI/ℓ is half the clamp's stiffness, an
    // O(1/n) error, so doubling n halves it. The bands (3.5–4.5 and 1.6–2.3) check the order,
    // not the constant; the uniform rule is checked from n = 32 on, where modes 3–4 have left
    // the pre-asymptotic range (ratio 1.65 from 16 to 32 for mode 3).
    for (cal, band, ns) in [
        (Calibration::TipLoad, 3.5..4.5, [16, 32, 64]),
        (Calibration::Uniform, 1.6..2.3, [32, 64, 128]),
    ] {
        let e: Vec<Vec<f64>> = ns.iter().map(|&n| errors(n, cal)).collect();
        for k in 0..4 {
            for w in e.windows(2) {
                let ratio = w[0][k] / w[1][k];
                assert!(
                    band.contains(&ratio),
                    "{cal:?} mode {}: ratio {ratio}",
                    k + 1
                );
            }
        }
    }
}

#[test]
fn tip_load_calibration_beats_uniform_on_the_first_mode() {
    for n in [8, 16, 32] {
        let tip = errors(n, Calibration::TipLoad)[0].abs();
        let uni = errors(n, Calibration::Uniform)[0].abs();
        assert!(
            tip < uni,
            "n = {n}: tip-load {tip:.2e} vs uniform {uni:.2e}"
        );
    }
}

#[test]
fn tapered_bending_beam_converges_to_continuous_reference() {
    let reference = reference_frequencies("tapered_bending.csv");
    let l = 10.0;
    let section = bending_only(linear(l, 4e4, 1e4), linear(l, 1.2, 0.6));
    let err = |n: usize| -> Vec<f64> {
        let modes = Modes::undeformed(&model(l, &section, n, Calibration::TipLoad)).unwrap();
        (0..4)
            .map(|k| modes.omega()[k] / reference[k] - 1.0)
            .collect()
    };
    let (e32, e64) = (err(32), err(64));
    for k in 0..4 {
        // Same O(1/n²) behaviour as the uniform beam: within 0.5 % at n = 64 for the first four
        // modes and the error quarters (ratio 3.5–4.5) from n = 32 to 64.
        assert!(e64[k].abs() < 5e-3, "mode {}: {:.3e}", k + 1, e64[k]);
        let ratio = e32[k] / e64[k];
        assert!((3.5..4.5).contains(&ratio), "mode {}: ratio {ratio}", k + 1);
    }
}
