//! The lowest modes at any n (issue 12, item 2): the first ten frequencies of the Table 4 beam
//! (bending, against the Euler–Bernoulli closed form) and of the Table 1 beam (coupled bending–
//! torsion, against `tests/data/continuous_beam/table1_coupled.csv`, the exact frequency equation
//! at 40 digits) converge monotonically, at second order, up to n = 10 000; Lanczos against the
//! dense solver, about the undeformed state and about a loaded equilibrium; the states that broke
//! the former Cholesky-of-M solver.

use crate::common::*;
use flexwing::beam::{Calibration, Profile};
use flexwing::model::{Force, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::{solve_static, Modes, ModesMethod, StaticOptions};
use flexwing::SolveError;
use nalgebra::DMatrix;

/// Relative errors of the first ten frequencies against `exact`, for each `n`.
fn errors(build: impl Fn(usize) -> FullModel, exact: &[f64], ns: &[usize]) -> Vec<[f64; 10]> {
    ns.iter()
        .map(|&n| {
            let modes = Modes::lowest(&build(n), 10).unwrap();
            assert_eq!(modes.stats().method, ModesMethod::Lanczos, "n = {n}");
            std::array::from_fn(|k| modes.omega()[k] / exact[k] - 1.0)
        })
        .collect()
}

/// Every mode's error keeps its sign, shrinks with every refinement, at an observed order
/// `log(e₁/e₂)/log(n₂/n₁)` within `0.02` of 2.
fn assert_monotone_second_order(name: &str, ns: &[usize], e: &[[f64; 10]]) {
    for k in 0..10 {
        for i in 1..ns.len() {
            let (a, b) = (e[i - 1][k], e[i][k]);
            assert!(
                a.signum() == b.signum() && b.abs() < a.abs(),
                "{name} mode {}: error {a:.3e} at n = {} then {b:.3e} at n = {}",
                k + 1,
                ns[i - 1],
                ns[i]
            );
            let order = (a / b).ln() / (ns[i] as f64 / ns[i - 1] as f64).ln();
            assert!(
                (order - 2.0).abs() < 0.02,
                "{name} mode {}: order {order:.4} from n = {} to {}",
                k + 1,
                ns[i - 1],
                ns[i]
            );
        }
    }
}

// Measured orders: 1.995–2.009 from n = 100 to 300 (Table 1 mode 4, whose error is 100 times
// smaller than its neighbours', is the slowest to settle; Table 4 mode 10 the fastest), and
// 2.000 to four digits above. The smallest error at n = 10 000 is 2.4e-10 (Table 1 mode 2), four
// orders above Lanczos's round-off (1e-14, `lanczos_agrees_with_the_dense_solver`), so the orders
// are not polluted by it.
const NS: [usize; 5] = [100, 300, 1000, 3000, 10_000];

#[test]
fn table4_beam_first_ten_converge_to_euler_bernoulli_up_to_10000_elements() {
    let (ei, m, l) = (50.0, 0.2, 1.0);
    let exact: Vec<f64> = euler_bernoulli_roots(10)
        .iter()
        .map(|bl| bl * bl * (ei / (m * f64::powi(l, 4))).sqrt())
        .collect();
    let section = bending_only(Profile::Uniform(ei), Profile::Uniform(m));
    let e = errors(|n| model(l, &section, n, Calibration::TipLoad), &exact, &NS);
    assert_monotone_second_order("Table 4", &NS, &e);
    // Magnitude: the first mode is 6.8e-10 off at n = 10 000 (0.068 / n²).
    assert!(e[4][0].abs() < 1e-9, "{:.3e}", e[4][0]);
}

#[test]
fn table1_beam_first_ten_converge_to_the_continuous_beam_up_to_10000_elements() {
    let exact = reference_frequencies("table1_coupled.csv");
    let e = errors(
        |n| model(16.0, &table1_section(), n, Calibration::TipLoad),
        &exact,
        &NS,
    );
    assert_monotone_second_order("Table 1", &NS, &e);
    // Magnitude: the tenth mode is 1.1e-7 off at n = 10 000.
    assert!(e[4][9].abs() < 2e-7, "{:.3e}", e[4][9]);
}

/// `Φᵀ M Φ` and `Φᵀ K_T Φ` of the first `r` modes.
fn projections(full: &FullModel, q: &[f64], k_t: &DMatrix<f64>, phi: &DMatrix<f64>) -> [f64; 2] {
    let nd = full.n_dofs();
    let mut mass = DMatrix::zeros(nd, nd);
    full.mass_matrix_into(q, &mut full.workspace(), &mut mass);
    let r = phi.ncols();
    let m_r = phi.transpose() * mass * phi;
    let k_r = phi.transpose() * k_t * phi;
    let orth = (m_r - DMatrix::identity(r, r)).amax();
    let off = (0..r)
        .flat_map(|i| (0..r).filter(move |&j| j != i).map(move |j| (i, j)))
        .map(|(i, j)| k_r[(i, j)].abs() / k_r[(i, i)].max(k_r[(j, j)]))
        .fold(0.0, f64::max);
    [orth, off]
}

/// Lanczos (`lowest`) against the dense solver (`about`) on the same model, for frequencies,
/// shapes and bending shares, and the orthogonality of the Lanczos modes.
fn compare(full: &FullModel, q: &[f64], k_t: &DMatrix<f64>, lanczos: &Modes) {
    let dense = Modes::about(full, q, k_t).unwrap();
    assert_eq!(lanczos.stats().method, ModesMethod::Lanczos);
    assert_eq!(dense.stats().method, ModesMethod::Dense);
    for k in 0..lanczos.n_modes() {
        // Both solve the inverse form to round-off: measured ≤ 1.2e-13 on ω; bound 1e-12.
        let dw = lanczos.omega()[k] / dense.omega()[k] - 1.0;
        assert!(dw.abs() < 1e-12, "mode {}: ω differs by {dw:.2e}", k + 1);
        // Shapes, same sign convention: measured ≤ 5.1e-12 (Lanczos's Ritz vectors purified
        // by one more application of K_T⁻¹ M; without it 5e-9); bound 1e-10.
        let ds = (lanczos.shapes().column(k) - dense.shapes().column(k)).amax()
            / dense.shapes().column(k).amax();
        assert!(ds < 1e-10, "mode {}: shape differs by {ds:.2e}", k + 1);
        let db = lanczos.bending_energy_fraction(full, k) - dense.bending_energy_fraction(full, k);
        // Measured ≤ 1.1e-14; bound 1e-12.
        assert!(db.abs() < 1e-12, "mode {}: bending share {db:.2e}", k + 1);
    }
    // Mass-normalized (against the closed-form M, while Lanczos normalizes with the O(n)
    // recursion) and K_T-orthogonal: measured ≤ 6.1e-13 and 6.7e-15; bounds 1e-11.
    let [orth, off] = projections(full, q, k_t, lanczos.shapes());
    assert!(orth < 1e-11 && off < 1e-11, "{orth:.2e}, {off:.2e}");
}

#[test]
fn lanczos_agrees_with_the_dense_solver() {
    for full in [
        flexwing::paper::table4_beam(60).unwrap(),
        flexwing::paper::table1_beam(40).unwrap(),
    ] {
        let q = vec![0.0; full.n_dofs()];
        let modes = Modes::lowest(&full, 10).unwrap();
        compare(&full, &q, &full.stiffness_matrix(), &modes);
    }
}

#[test]
fn lanczos_agrees_with_the_dense_solver_about_a_loaded_equilibrium() {
    // The Table 1 beam under a dead tip force, a torque and gravity, at its static equilibrium
    // (tip turned by about 30°): K_T = K − ∂Q/∂q is full and not diagonal.
    let full = flexwing::paper::table1_beam(40).unwrap();
    let loads = full
        .apply(
            &[
                Load::PointForce {
                    span: 16.0,
                    force: Force::Dead { fx: 0.0, fy: 150.0 },
                },
                Load::Torque {
                    span: 16.0,
                    value: 30.0,
                },
                Load::Gravity { g: 9.81 },
            ],
            "loads",
        )
        .unwrap();
    let scales = [1.0, 1.0, 1.0];
    let eq = solve_static(&full, &loads, &scales, &StaticOptions::default()).unwrap();
    let q = eq.q.clone();
    let tip_angle = q[..40].iter().sum::<f64>();
    assert!(tip_angle > 0.4, "a large deflection: {tip_angle}");
    let nd = full.n_dofs();
    let mut jac = DMatrix::zeros(nd, nd);
    full.load_jacobian_into(&q, &loads, &scales, &mut full.workspace(), &mut jac);
    let k_t = full.stiffness_matrix() - jac;
    let k_t = (&k_t + k_t.transpose()) * 0.5;
    let modes = Modes::lowest_loaded(&full, &q, &loads, &scales, 10).unwrap();
    compare(&full, &q, &k_t, &modes);
    // The load changes the frequencies (the dead load stiffens, gravity softens): not a
    // comparison that could pass with the undeformed modes.
    let free = Modes::lowest(&full, 10).unwrap();
    assert!((modes.omega()[0] / free.omega()[0] - 1.0).abs() > 1e-3);
}

#[test]
fn unstable_equilibria_have_no_modes() {
    // Axial compression beyond the Euler load π² EI/(4 L²) = 123.4 N at n = 200 (Lanczos path):
    // the elimination finds one negative pivot; below it the modes exist.
    let full = flexwing::paper::table4_beam(200).unwrap();
    let q = vec![0.0; 200];
    let compress = |p: f64| {
        full.apply(
            &[Load::PointForce {
                span: 1.0,
                force: Force::Dead { fx: -p, fy: 0.0 },
            }],
            "loads",
        )
        .unwrap()
    };
    let stable = Modes::lowest_loaded(&full, &q, &compress(120.0), &[1.0], 4).unwrap();
    let free = Modes::lowest(&full, 4).unwrap();
    // Compression softens the first mode: ω₁² falls in proportion to 1 − P/P_cr ≈ 0.028.
    assert!(stable.omega()[0] < 0.2 * free.omega()[0]);
    let e = Modes::lowest_loaded(&full, &q, &compress(130.0), &[1.0], 4).unwrap_err();
    assert_eq!(e, SolveError::IndefiniteTangent { non_positive: 1 });
    let follower = full
        .apply(
            &[Load::PointForce {
                span: 1.0,
                // Compressive along the tip element: its tangent is unsymmetric even at q = 0
                // (a normal follower force's Jacobian vanishes there).
                force: Force::Follower {
                    tangential: -10.0,
                    normal: 0.0,
                },
            }],
            "loads",
        )
        .unwrap();
    let e = Modes::lowest_loaded(&full, &q, &follower, &[1.0], 4).unwrap_err();
    assert!(matches!(e, SolveError::NonSymmetricTangent { .. }), "{e}");
}

#[test]
fn the_states_that_broke_the_former_solver() {
    // Regression (issue 12): the first frequency of the Table 4 beam was 0 at n = 800 and 78.6
    // at n = 1000, and a reduced model at n = 3000 failed with MassNotPositiveDefinite. The
    // Euler–Bernoulli value is 55.5931 rad/s; the lumped model is 0.0682/n² above it (measured
    // at all three n).
    for n in [800, 1000, 3000] {
        let full = flexwing::paper::table4_beam(n).unwrap();
        let modes = Modes::lowest(&full, 4).unwrap();
        let e = modes.omega()[0] / 55.593_082_681_944_77 - 1.0;
        assert!(e > 0.0 && e < 0.07 / (n * n) as f64, "n = {n}: {e:.3e}");
        // The reduced model: M_r(0) = Φᵀ M(0) Φ = I (with M φ from the O(n) momentum
        // recursion: the model's workspace would hold an n × n matrix) and K_r = diag(ω²)
        // (measured ≤ 4.5e-14 and 2.2e-14; bound 1e-12).
        let rom = ReducedModel::first(&full, modes.shapes(), 4).unwrap();
        let phi = rom.basis();
        let mut m_phi = DMatrix::zeros(n, 4);
        for j in 0..4 {
            let mut p = vec![0.0; n];
            full.momentum_into(&vec![0.0; n], phi.column(j).as_slice(), &mut p);
            m_phi.set_column(j, &nalgebra::DVector::from_vec(p));
        }
        let m_r = phi.transpose() * m_phi;
        assert!((m_r - DMatrix::identity(4, 4)).amax() < 1e-12);
        let k_r = rom.stiffness_matrix();
        for i in 0..4 {
            let w2 = modes.omega()[i].powi(2);
            assert!((k_r[(i, i)] / w2 - 1.0).abs() < 1e-12);
        }
    }
}
