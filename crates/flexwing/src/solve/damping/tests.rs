use super::*;
use crate::model::FullModel;
use crate::paper::{table1_beam, table4_beam};
use crate::solve::ModesMethod;

/// Reproducible pseudo-random numbers in [−1, 1] (a linear congruential generator).
fn random_vector(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed;
    (0..n)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        })
        .collect()
}

/// `max_i |a_i − b_i| / max_i |b_i|`.
fn relative_difference(a: &[f64], b: &[f64]) -> f64 {
    let scale = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .fold(0.0_f64, |m, (x, y)| m.max((x - y).abs()))
        / scale
}

/// The largest relative difference between the operator's `C v` (and its formed matrix's) and
/// the dense formulas' (the code the operator replaced, kept as `dense_damping`), over a few
/// random `v`.
fn operator_against_dense(model: &FullModel, damping: &Damping) -> f64 {
    let n = model.n_dofs();
    let reference = dense_damping(model, damping, "damping").unwrap();
    let mut op = DampingOperator::new(model, damping, "damping").unwrap();
    let formed = op.matrix(model).unwrap();
    let mut worst = 0.0_f64;
    let mut out = vec![0.0; n];
    for seed in 1..=4 {
        let v = random_vector(n, seed);
        let expected = (&reference * nalgebra::DVector::from_column_slice(&v))
            .as_slice()
            .to_vec();
        op.apply(model, &v, &mut out);
        worst = worst.max(relative_difference(&out, &expected));
        let from_matrix = &formed * nalgebra::DVector::from_column_slice(&v);
        worst = worst.max(relative_difference(from_matrix.as_slice(), &expected));
    }
    worst
}

/// `C v` of modal damping formed densely from every mode of the dense solver of `modes.rs` (the
/// inverse form `M φ = μ K φ`, accurate at any n): `M₀ Φ diag(2 ζ ω) Φᵀ M₀ v`.
fn modal_from_dense_modes(model: &FullModel, ratios: &[f64], v: &[f64]) -> Vec<f64> {
    let n = model.n_dofs();
    let modes = Modes::about(model, &vec![0.0; n], &model.stiffness_matrix()).unwrap();
    assert_eq!(modes.stats().method, ModesMethod::Dense);
    let mut m0 = DMatrix::zeros(n, n);
    model.mass_matrix_into(&vec![0.0; n], &mut model.workspace(), &mut m0);
    let mut c = DMatrix::zeros(n, n);
    for (k, z) in ratios.iter().enumerate() {
        let u = &m0 * modes.shapes().column(k);
        c += &u * u.transpose() * (2.0 * z * modes.omega()[k]);
    }
    (c * nalgebra::DVector::from_column_slice(v))
        .as_slice()
        .to_vec()
}

/// Regression/consistency test: the O(n) operator against the dense `C` of the formulas it
/// replaced, on the Table 4 beam (bending, n coordinates) and the Table 1 beam (bending and
/// torsion, 2n), at n = 10 and 40.
///
/// * Rayleigh: `M(0) v` by the momentum recursion against the dense `M(0)` times `v`, `K`
///   diagonal: round-off only, measured ≤ 2.8e-15 relative to the largest entry of `C v`;
///   bound 1e-13.
/// * Modal: the operator's modes come from `Modes::lowest` (the inverse form `M φ = μ K φ`,
///   Lanczos above 48 coordinates), the replaced code's from the Cholesky factor of `M(0)`, whose
///   condition number grows like n⁶ (modes.rs): that reference carries the round-off `ε κ(M)`
///   itself. Measured ≤ 2.0e-11 at n = 10 and ≤ 1.4e-8 at n = 40; bounds 1e-10 and 1e-7. Against
///   the same formula on the modes of the accurate dense solver the operator agrees to round-off
///   (measured ≤ 1.5e-14 with three modes, also for the Table 1 beam's 80 coordinates, where the
///   operator takes the Lanczos path; 1.4e-13 with every mode at n = 10): bound 1e-12.
#[test]
fn regression_operator_equals_the_dense_damping_matrix() {
    let rayleigh = Damping::Rayleigh {
        alpha: 0.7,
        beta: 3e-3,
    };
    for n in [10, 40] {
        for (name, model) in [("table 4", table4_beam(n)), ("table 1", table1_beam(n))] {
            let model = model.unwrap();
            let nd = model.n_dofs();
            let d = operator_against_dense(&model, &rayleigh);
            eprintln!("{name} n = {n}: Rayleigh {d:.1e}");
            assert!(d < 1e-13, "{name} n = {n}: Rayleigh {d:.1e}");
            let bound = if n <= 10 { 1e-10 } else { 1e-7 };
            // A few ratios (the low-rank path, Lanczos when the model is large enough) and, at
            // n = 10, one per coordinate (the dense modal path).
            let mut counts = vec![3];
            if n == 10 {
                counts.push(nd);
            }
            for count in counts {
                let modal = Damping::Modal {
                    ratios: (0..count).map(|k| 0.01 + 0.002 * k as f64).collect(),
                };
                let d = operator_against_dense(&model, &modal);
                eprintln!("{name} n = {n}: modal × {count} {d:.1e}");
                assert!(d < bound, "{name} n = {n}: modal × {count} {d:.1e}");
                let Damping::Modal { ratios } = &modal else {
                    unreachable!()
                };
                let mut op = DampingOperator::new(&model, &modal, "damping").unwrap();
                let (v, mut out) = (random_vector(nd, 7), vec![0.0; nd]);
                op.apply(&model, &v, &mut out);
                let d = relative_difference(&out, &modal_from_dense_modes(&model, ratios, &v));
                eprintln!("{name} n = {n}: modal × {count} against accurate modes {d:.1e}");
                assert!(d < 1e-12, "{name} n = {n}: modal × {count} {d:.1e}");
            }
        }
    }
    // The 80 coordinates of the Table 1 beam at n = 40 took the Lanczos path above.
    let model = table1_beam(40).unwrap();
    let modes = Modes::lowest(&model, 3).unwrap();
    assert_eq!(modes.stats().method, ModesMethod::Lanczos);
}

/// `C` is symmetric and positive semi-definite for every kind (`vᵀ C v ≥ 0`): the dissipation
/// of the energy audit is never negative. Exact properties of the formulas: Rayleigh's
/// `α vᵀ M v + β vᵀ K v` and modal `Σ w_k (uₖᵀ v)²` are sums of non-negative terms (to round-off:
/// bound −1e-14 relative to `|v|² ‖C‖`), and the formed matrix's asymmetry is round-off.
#[test]
fn the_operator_is_symmetric_and_dissipative() {
    let model = table1_beam(30).unwrap();
    let n = model.n_dofs();
    for damping in [
        Damping::Rayleigh {
            alpha: 0.5,
            beta: 1e-3,
        },
        Damping::Modal {
            ratios: vec![0.05; 4],
        },
    ] {
        let mut op = DampingOperator::new(&model, &damping, "damping").unwrap();
        let c = op.matrix(&model).unwrap();
        let asymmetry = (&c - c.transpose()).amax() / c.amax();
        assert!(asymmetry < 1e-12, "{damping:?}: {asymmetry:.1e}");
        let mut cv = vec![0.0; n];
        for seed in 10..20 {
            let v = random_vector(n, seed);
            op.apply(&model, &v, &mut cv);
            let power: f64 = v.iter().zip(&cv).map(|(a, b)| a * b).sum();
            let scale = v.iter().map(|x| x * x).sum::<f64>() * c.amax();
            assert!(power >= -1e-14 * scale, "{damping:?}: {power:e}");
        }
    }
}

/// Modal damping needs modes that double precision resolves: asking for a ratio on a mode it
/// does not resolve (the highest of a large model) is an error naming the caller's field, not
/// a damping of a mode that is round-off; a missing ratio list damps nothing.
#[test]
fn modal_ratios_beyond_the_resolved_modes_are_an_input_error() {
    // At n = 400 `Modes::lowest` drops the highest one or two modes (modes.rs, `RESOLVED`).
    let model = table4_beam(400).unwrap();
    let modes = Modes::lowest(&model, 400).unwrap();
    assert!(modes.n_modes() < 400, "{}", modes.n_modes());
    let damping = Damping::Modal {
        ratios: vec![0.01; 400],
    };
    let err = DampingOperator::new(&model, &damping, "dynamic.damping")
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.starts_with("dynamic.damping.ratios: 400 ratios given but double precision"),
        "{err}"
    );
    let none = Damping::Modal { ratios: vec![] };
    let mut op = DampingOperator::new(&model, &none, "damping").unwrap();
    assert!(op.matrix(&model).is_none());
}
