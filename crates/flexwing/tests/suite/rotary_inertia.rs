//! Rotary inertia in bending (`beam::RotaryInertia`): the elements as rigid bars (`m ℓ²/12`) and
//! the section's own rotary inertia `ρI` (the Rayleigh beam).
//!
//! * Every kinetic term of the full and reduced models against the definition
//!   `T = T_point masses + ½ Σ J_b,i θ̇_i²` (a consistency test of the O(n) recursions against the
//!   energy).
//! * The per-element integrals against closed forms.
//! * Natural frequencies against independent continuum references: the bars converge to the
//!   Euler–Bernoulli cantilever (closed form) at second order; with `ρI` the chain converges to
//!   the Rayleigh beam of `tests/data/rayleigh_beam/` (its own script, two methods).

use crate::common::*;
use flexwing::beam::{
    Beam, Calibration, Discretization, Profile, RotaryInertia, SectionProperties,
};
use flexwing::model::{FullModel, ReducedModel, StructuralModel};
use flexwing::solve::Modes;
use nalgebra::{DMatrix, DVector};

fn beam(length: f64, section: &SectionProperties, n: usize, rotary: &RotaryInertia) -> Beam {
    Beam::new(
        length,
        section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )
    .unwrap()
    .with_rotary_inertia("beam", section, rotary)
    .unwrap()
}

/// A tapered beam (mass per length 0.6 → 0.2 kg/m over 2 m), bending-only or coupled.
fn tapered(torsion: bool) -> SectionProperties {
    let (ei, m) = (linear(2.0, 14.0, 6.0), linear(2.0, 0.6, 0.2));
    if torsion {
        coupled(
            ei,
            m,
            Profile::Uniform(3.0),
            Profile::Uniform(0.01),
            Profile::Uniform(0.1),
        )
    } else {
        bending_only(ei, m)
    }
}

fn both() -> RotaryInertia {
    RotaryInertia {
        elements: true,
        section: Some(linear(2.0, 3e-3, 1e-3)),
    }
}

#[test]
fn element_inertias_are_the_closed_form_integrals() {
    // Uniform m: a bar's m ℓ²/12. Linear m(x) = m0 + s x on [a, b], about c = (a + b)/2:
    // ∫ m (x − c)² dx = m(c) ℓ³/12 (the odd part integrates to zero). Section ρI linear:
    // ∫ ρI dx = ℓ × ρI(c). Round-off bound: 1e-15 relative.
    let uniform = bending_only(Profile::Uniform(50.0), Profile::Uniform(0.2));
    let b = beam(
        1.0,
        &uniform,
        7,
        &RotaryInertia {
            elements: true,
            section: None,
        },
    );
    let l = 1.0 / 7.0;
    for &j in b.bending_inertias() {
        assert!((j / (0.2 * l * l * l / 12.0) - 1.0).abs() < 1e-13, "{j}");
    }
    let section = tapered(false);
    let n = 5;
    let b = beam(2.0, &section, n, &both());
    let l = 2.0 / n as f64;
    for (i, &j) in b.bending_inertias().iter().enumerate() {
        let c = (i as f64 + 0.5) * l;
        let m_c = 0.6 + (0.2 - 0.6) * c / 2.0;
        let ri_c = 3e-3 + (1e-3 - 3e-3) * c / 2.0;
        let expected = m_c * l.powi(3) / 12.0 + ri_c * l;
        assert!(
            (j / expected - 1.0).abs() < 1e-13,
            "element {i}: {j} vs {expected}"
        );
    }
    // Without rotary inertia: zeros, the paper's model.
    let plain = Beam::new(
        2.0,
        &section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )
    .unwrap();
    assert!(plain.bending_inertias().iter().all(|&j| j == 0.0));
}

#[test]
fn bad_rotary_inertia_is_an_input_error_naming_the_field() {
    let section = tapered(false);
    let b = Beam::new(
        2.0,
        &section,
        &Discretization::Uniform(4),
        Calibration::TipLoad,
    )
    .unwrap();
    for bad in [-1e-3, f64::NAN, f64::INFINITY] {
        let r = RotaryInertia {
            elements: false,
            section: Some(Profile::Uniform(bad)),
        };
        let e = b
            .clone()
            .with_rotary_inertia("wing", &section, &r)
            .unwrap_err();
        assert_eq!(e.field, "wing.section.rotary_inertia", "{e}");
    }
    // A rotary inertia that puts an element's bending frequency squared below 1e-60 (the range
    // of `magnitude::FREQUENCY_SQUARED`): one element of 1000 m, EI = m = 1e-30, ρI = 1e30 gives
    // K_θ/(m ℓ² + J_b) ≈ 3e-66.
    let tiny = bending_only(Profile::Uniform(1e-30), Profile::Uniform(1e-30));
    let b = Beam::new(
        1000.0,
        &tiny,
        &Discretization::Uniform(1),
        Calibration::TipLoad,
    )
    .unwrap();
    let r = RotaryInertia {
        elements: false,
        section: Some(Profile::Uniform(1e30)),
    };
    let e = b.with_rotary_inertia("wing", &tiny, &r).unwrap_err();
    assert_eq!(e.field, "wing.section.rotary_inertia", "{e}");
    assert!(e.reason.contains("K_θ/(m ℓ² + J_b)"), "{e}");
}

/// `½ Σ J_b,i θ̇_i²`, `θ̇` the running sums of the bending rates.
fn rotary_energy(model: &FullModel, qd: &[f64]) -> f64 {
    let mut th_d = 0.0;
    let mut t = 0.0;
    for (i, j) in model.beam().bending_inertias().iter().enumerate() {
        th_d += qd[i];
        t += 0.5 * j * th_d * th_d;
    }
    t
}

#[test]
fn rotary_inertia_enters_every_kinetic_term_consistently() {
    for torsion in [false, true] {
        let section = tapered(torsion);
        let n = 6;
        let model = FullModel::new(beam(2.0, &section, n, &both()));
        let plain = FullModel::new(
            Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(n),
                Calibration::TipLoad,
            )
            .unwrap(),
        );
        let nd = model.n_dofs();
        let q: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
        let qd: Vec<f64> = (0..nd).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
        let energy = plain.kinetic_energy(&q, &qd) + rotary_energy(&model, &qd);
        assert!(
            rotary_energy(&model, &qd) > 1e-3 * energy,
            "the term is exercised"
        );
        let mut ws = model.workspace();
        let mut m = DMatrix::zeros(nd, nd);
        model.mass_matrix_into(&q, &mut ws, &mut m);
        let qv = DVector::from_column_slice(&qd);
        // The O(n²) matrix against the energy; the O(n) momentum, velocity solve, diagonals and
        // gyroscopic term against the matrix and the point-mass model (a constant inertia adds
        // no gyroscopic term). Round-off bounds: 1e-12 relative, 1e-11 on the solves.
        assert!(
            (0.5 * qv.dot(&(&m * &qv)) - energy).abs() < 1e-12 * energy,
            "{torsion}"
        );
        let mut p = vec![0.0; nd];
        StructuralModel::momentum_into(&model, &q, &qd, &mut ws, &mut p);
        let mq = &m * &qv;
        for i in 0..nd {
            assert!((p[i] - mq[i]).abs() < 1e-12 * mq.amax(), "{torsion} {i}");
        }
        let mut back = vec![0.0; nd];
        assert!(model.velocities_into(&q, &p, &mut ws, &mut back));
        for i in 0..nd {
            assert!((back[i] - qd[i]).abs() < 1e-11, "{torsion} {i}");
        }
        let mut diagonal = vec![0.0; nd];
        model.mass_diagonal_into(&model.kinematics(&q), &mut diagonal);
        let inverse = m.clone().try_inverse().unwrap();
        let inverse_diagonal = model.inverse_mass_diagonal(&q, &mut ws).unwrap();
        for i in 0..nd {
            assert!(
                (diagonal[i] - m[(i, i)]).abs() < 1e-12 * m[(i, i)],
                "{torsion} {i}"
            );
            let d = inverse[(i, i)];
            assert!((inverse_diagonal[i] - d).abs() < 1e-10 * d, "{torsion} {i}");
        }
        let (mut g, mut g_plain) = (vec![0.0; nd], vec![0.0; nd]);
        StructuralModel::gyroscopic_into(&model, &q, &qd, &mut ws, &mut g);
        let mut pws = plain.workspace();
        StructuralModel::gyroscopic_into(&plain, &q, &qd, &mut pws, &mut g_plain);
        for i in 0..nd {
            assert!((g[i] - g_plain[i]).abs() < 1e-12 * (1.0 + g_plain[i].abs()));
        }

        // The reduced model: M_r = Φᵀ M Φ at a deformed state.
        let rom =
            ReducedModel::first(&model, Modes::undeformed(&model).unwrap().shapes(), 4).unwrap();
        let eta = [0.3, -0.2, 0.1, 0.05];
        let q = rom.full_coordinates(&eta);
        model.mass_matrix_into(&q, &mut ws, &mut m);
        let phi = rom.basis();
        let m_r = phi.transpose() * &m * phi;
        let mut rws = rom.workspace();
        let mut got = DMatrix::zeros(4, 4);
        rom.mass_matrix_into(&eta, &mut rws, &mut got);
        assert!((&got - &m_r).amax() < 1e-12 * m_r.amax(), "{torsion}");
    }
}

/// Relative errors of the first `count` frequencies of `model` against `reference`.
fn errors(model: &FullModel, reference: &[f64], count: usize) -> Vec<f64> {
    let modes = Modes::lowest(model, count).unwrap();
    (0..count)
        .map(|k| modes.omega()[k] / reference[k] - 1.0)
        .collect()
}

#[test]
fn bars_converge_to_euler_bernoulli_at_second_order() {
    // The bars' inertia m ℓ²/12 is a property of the cut: it falls as 1/n², so the chain still
    // converges to the Euler–Bernoulli cantilever (Table 4 beam: L = 1 m, EI = 50 N·m², m = 0.2
    // kg/m; closed form (β_k L)² √(EI/(m L⁴))), at second order: error ratio 3.5–4.5 on doubling
    // n (order 1.8–2.2), the band of tests/suite/euler_bernoulli_modes.rs.
    //
    // It is not free: the point-mass chain's low frequencies are unusually accurate (mode 2 at
    // n = 64: 2.2e-5), and the bars lower them by about the first-order Rayleigh-beam shift
    // −½ r² ∫W'²/∫W² with the bar's radius of gyration r² = ℓ²/12, i.e. −(β_k ℓ)²/24 times a
    // mode-shape factor ∫W'²/(β_k² ∫W²) of order one (measured 1.18–1.47). Band for the shift
    // (bars − point masses at the same n): 0.5–2 times (β_k ℓ)²/24.
    let (ei, m) = (50.0, 0.2);
    let section = bending_only(Profile::Uniform(ei), Profile::Uniform(m));
    let roots = euler_bernoulli_roots(4);
    let reference: Vec<f64> = roots.iter().map(|bl| bl * bl * (ei / m).sqrt()).collect();
    let bars = RotaryInertia {
        elements: true,
        section: None,
    };
    let ns = [16, 32, 64];
    let e: Vec<Vec<f64>> = ns
        .iter()
        .map(|&n| {
            errors(
                &FullModel::new(beam(1.0, &section, n, &bars)),
                &reference,
                4,
            )
        })
        .collect();
    let n = 64;
    let point = errors(
        &model(1.0, &section, n, Calibration::TipLoad),
        &reference,
        4,
    );
    for k in 0..4 {
        let shift = e[2][k] - point[k];
        let estimate = -(roots[k] / n as f64).powi(2) / 24.0;
        eprintln!(
            "mode {}: bars {:.3e} {:.3e} {:.3e} (n = 16, 32, 64); point masses at 64 {:.3e}; \
             shift {shift:.3e}, estimate {estimate:.3e}",
            k + 1,
            e[0][k],
            e[1][k],
            e[2][k],
            point[k]
        );
        for w in e.windows(2) {
            let ratio = w[0][k] / w[1][k];
            assert!((3.5..4.5).contains(&ratio), "mode {}: ratio {ratio}", k + 1);
        }
        let factor = shift / estimate;
        assert!((0.5..2.0).contains(&factor), "mode {}: {factor}", k + 1);
    }
}

#[test]
fn section_rotary_inertia_converges_to_the_rayleigh_beam() {
    // The Table 4 beam with the section's rotary inertia ρI = m r² (r = 0.05 and 0.02 m, the
    // effect up to 45 % on mode 10) against the Rayleigh beam's first 10 frequencies of
    // tests/data/rayleigh_beam/ (its script: the exact frequency equation, checked against a
    // Rayleigh–Ritz solution to 1e-20 relative). With and without the bars' own inertia (which
    // falls as 1/n²). Measured: every error falls 4.0× per doubling of n from n = 32 (second
    // order); band 3.5–4.5. At n = 2000 (the Lanczos path, `Modes::lowest`) each error is its
    // n = 256 value extrapolated at second order, (256/2000)² e(256), to within 10 % (the
    // measured ratios are 4.00 ± 0.03, so higher-order terms are a few per cent at n = 256).
    let (ei, m) = (50.0, 0.2);
    let section = bending_only(Profile::Uniform(ei), Profile::Uniform(m));
    for (file, r) in [("table4_r005.csv", 0.05), ("table4_r002.csv", 0.02)] {
        let reference = reference_frequencies(&format!("../rayleigh_beam/{file}"));
        for elements in [false, true] {
            let rotary = RotaryInertia {
                elements,
                section: Some(Profile::Uniform(m * r * r)),
            };
            let errors_at = |n: usize| {
                errors(
                    &FullModel::new(beam(1.0, &section, n, &rotary)),
                    &reference,
                    10,
                )
            };
            let e: Vec<Vec<f64>> = [32, 64, 128, 256].map(errors_at).to_vec();
            let large = errors_at(2000);
            for k in 0..10 {
                eprintln!(
                    "{file}, bars {elements}, mode {}: {:.2e} {:.2e} {:.2e} {:.2e} (n = 32 … 256), \
                     {:.2e} (n = 2000)",
                    k + 1,
                    e[0][k],
                    e[1][k],
                    e[2][k],
                    e[3][k],
                    large[k]
                );
                for w in e.windows(2) {
                    let ratio = w[0][k] / w[1][k];
                    assert!(
                        (3.5..4.5).contains(&ratio),
                        "{file} {elements} mode {}: {ratio}",
                        k + 1
                    );
                }
                let extrapolated = e[3][k] * (256.0f64 / 2000.0).powi(2);
                let off = large[k] / extrapolated - 1.0;
                assert!(
                    off.abs() < 0.1,
                    "{file} {elements} mode {}: {off:.3}",
                    k + 1
                );
            }
        }
    }
}
