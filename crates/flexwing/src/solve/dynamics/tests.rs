//! Tests of the equations of motion: the Jacobian against differences of the right-hand side,
//! the tolerances of the state.

use nalgebra::DMatrix;

use super::*;
use crate::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use crate::model::{Force, FullModel, Load, ReducedModel};
use crate::model::{PlanarModel, StructuralModel};
use crate::solve::integrate::OdeSystem;
use crate::solve::AuditLimits;
use crate::solve::Modes;

fn model(torsion: bool) -> FullModel {
    let section = SectionProperties {
        ei: Profile::Uniform(10.0),
        mass_per_length: Profile::Table {
            x: vec![0.0, 2.0],
            value: vec![0.6, 0.2],
        },
        torsion: torsion.then_some(TorsionProperties {
            gj: Profile::Uniform(3.0),
            polar_inertia: Profile::Uniform(0.01),
            inertia_axis: InertiaAxis::MassCentre,
            offset: Profile::Uniform(0.1),
        }),
    };
    FullModel::new(
        Beam::new(
            2.0,
            &section,
            &Discretization::Uniform(6),
            Calibration::TipLoad,
        )
        .unwrap(),
    )
}

/// The analytic Jacobian against central differences of the right-hand side (step 1e-6,
/// truncation ~1e-12 relative, round-off ~1e-10 relative: tolerance 1e-6 relative).
fn check_jacobian<M: PlanarModel>(model: &M, gyroscopic: Gyroscopic, damping: &Damping) {
    let full = model.full_model();
    let loads = full
        .apply(
            &[
                Load::PointForce {
                    span: 2.0,
                    force: Force::Follower {
                        tangential: 0.5,
                        normal: 2.0,
                    },
                },
                Load::Gravity { g: 9.81 },
            ],
            "loads",
        )
        .unwrap();
    let tf = vec![TimeFunction::Constant, TimeFunction::Constant];
    let mut eom = EquationsOfMotion::new(model, &loads, tf, gyroscopic, damping).unwrap();
    let nd = model.n_dofs();
    let x: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
    let xd: Vec<f64> = (0..nd).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
    let y = eom.state(&x, &xd);
    let mut jac = DMatrix::zeros(2 * nd, 2 * nd);
    eom.jacobian(0.0, &y, &mut jac);
    let h = 1e-6;
    let (mut fp, mut fm) = (vec![0.0; 2 * nd], vec![0.0; 2 * nd]);
    let scale = jac.amax();
    for c in 0..2 * nd {
        let (mut yp, mut ym) = (y.clone(), y.clone());
        yp[c] += h;
        ym[c] -= h;
        eom.rhs(0.0, &yp, &mut fp);
        eom.rhs(0.0, &ym, &mut fm);
        for r in 0..2 * nd {
            let fd = (fp[r] - fm[r]) / (2.0 * h);
            assert!(
                (fd - jac[(r, c)]).abs() <= 1e-6 * scale,
                "{gyroscopic:?} ({r}, {c}): {fd} vs {}",
                jac[(r, c)]
            );
        }
    }
}

#[test]
fn state_atol_means_a_joint_rotation_for_every_model() {
    let atol = 1e-6;
    for torsion in [false, true] {
        let full = model(torsion);
        let none = full.apply(&[], "loads").unwrap();
        let nq = full.n_dofs();
        let mut eom =
            EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Exact, &Damping::None)
                .unwrap();
        let a = eom.state_atol(atol);
        let k = full.stiffness_matrix();
        let mut m0 = DMatrix::zeros(nq, nq);
        full.mass_matrix_into(&vec![0.0; nq], &mut full.workspace(), &mut m0);
        let m0_inverse = m0.try_inverse().unwrap();
        for i in 0..nq {
            // Full model: atol on each joint rotation; on each momentum the error that
            // carries the energy ½ K_ii atol², √(K_ii / (M⁻¹)_ii) atol, with M⁻¹ here from
            // the dense closed-form mass matrix (the library uses its chain solve): to the
            // conditioning of M(0) (κ ≈ 1e7 at n = 6 with torsion).
            assert_eq!(a[i], atol);
            let p = atol * (k[(i, i)] / m0_inverse[(i, i)]).sqrt();
            assert!(
                (a[nq + i] - p).abs() <= 1e-8 * p,
                "{i}: {} vs {p}",
                a[nq + i]
            );
        }
        let modes = Modes::undeformed(&full).unwrap();
        for r in [1, 3] {
            let rom = ReducedModel::first(&full, modes.shapes(), r).unwrap();
            let mut eom =
                EquationsOfMotion::new(&rom, &none, vec![], Gyroscopic::Exact, &Damping::None)
                    .unwrap();
            let a = eom.state_atol(atol);
            for c in 0..r {
                // An error of a_c in mode c moves the joints by Φ_c a_c; the full model's RMS
                // norm of that (over its nq joints, each weighed by atol) equals the reduced
                // model's RMS norm of the single error a_c over its r coordinates, 1/√r.
                let phi = rom.basis().column(c);
                let full_norm =
                    (phi.iter().map(|v| (v * a[c] / atol).powi(2)).sum::<f64>() / nq as f64).sqrt();
                let expected = 1.0 / (r as f64).sqrt();
                assert!(
                    (full_norm - expected).abs() < 1e-12,
                    "{full_norm} vs {expected}"
                );
                // Mass-normalized modes: K_r = diag(ω²), M_r(0) = I, so the momentum
                // tolerance is ω_c a_c (to the accuracy of the eigen-decomposition).
                let p = modes.omega()[c] * a[c];
                assert!((a[r + c] - p).abs() < 1e-8 * p, "{c}: {} vs {p}", a[r + c]);
            }
        }
    }
}

#[test]
fn jacobian_agrees_with_finite_differences_of_the_right_hand_side() {
    let rayleigh = Damping::Rayleigh {
        alpha: 0.3,
        beta: 0.01,
    };
    for torsion in [false, true] {
        let full = model(torsion);
        for damping in [&Damping::None, &rayleigh] {
            check_jacobian(&full, Gyroscopic::Exact, damping);
            check_jacobian(&full, Gyroscopic::Neglected, damping);
        }
        let modes = Modes::undeformed(&full).unwrap();
        let rom = ReducedModel::first(&full, modes.shapes(), 3).unwrap();
        check_jacobian(&rom, Gyroscopic::Exact, &rayleigh);
        check_jacobian(&rom, Gyroscopic::Neglected, &Damping::None);
    }
}

/// Loads of the audit tests: a dead tip force and gravity (conservative), and optionally a
/// follower force.
fn audit_loads(full: &FullModel, follower: bool) -> crate::model::AppliedLoads {
    let mut loads = vec![
        Load::PointForce {
            span: 2.0,
            force: Force::Dead { fx: 0.7, fy: 1.5 },
        },
        Load::Gravity { g: 9.81 },
    ];
    if follower {
        loads.push(Load::PointForce {
            span: 1.3,
            force: Force::Follower {
                tangential: 0.5,
                normal: 2.0,
            },
        });
    }
    full.apply(&loads, "loads").unwrap()
}

fn audit_limits() -> AuditLimits {
    AuditLimits {
        balance: Some(1e-3),
        runaway: 9.0,
        floor: 1e-12,
        interval: 0.0,
    }
}

/// The quadrature states' part of a Newton step from the integrators' iteration matrices
/// (`quadrature_step_*`, `ode.rs`) against the exact bordered step `(b_q + g·Δy) / c` with the
/// same leading solution `Δy`, `g` the gradients of the rates `ẋ·Q`, `ẋᵀ C ẋ` by central
/// differences of the right-hand side (step 1e-6: truncation ~1e-12, round-off ~1e-10 of the
/// rates; tolerance 1e-6 of `Σ |g_j Δy_j| / |c|`), at a real shift and a complex one, with the
/// last right-hand side and the linearization at the state (as after a converged iteration).
/// Dense path: full and reduced models under dead, gravity and follower loads with Rayleigh
/// damping (exact); chain path: the full model under conservative loads (exact there; a follower
/// load's antisymmetric stiffness is left out, `newton_systems.rs`).
#[test]
fn quadrature_steps_are_the_bordered_newton_steps() {
    let damping = Damping::Rayleigh {
        alpha: 0.3,
        beta: 0.01,
    };
    for torsion in [false, true] {
        let full = model(torsion);
        let modes = Modes::undeformed(&full).unwrap();
        let rom = ReducedModel::first(&full, modes.shapes(), 3).unwrap();
        let with_follower = audit_loads(&full, true);
        let conservative = audit_loads(&full, false);
        check_quadrature_step(&full, &with_follower, &damping, NewtonSystems::Dense);
        check_quadrature_step(&rom, &with_follower, &damping, NewtonSystems::Dense);
        check_quadrature_step(&full, &conservative, &damping, NewtonSystems::Chain);
        check_quadrature_step(&full, &conservative, &Damping::None, NewtonSystems::Chain);
    }
}

fn check_quadrature_step<M: StructuralModel>(
    model: &M,
    loads: &crate::model::AppliedLoads,
    damping: &Damping,
    systems: NewtonSystems,
) {
    let tf = vec![TimeFunction::Constant; loads.n_loads()];
    let mut eom = EquationsOfMotion::new(model, loads, tf, Gyroscopic::Exact, damping)
        .unwrap()
        .with_energy_audit(audit_limits());
    eom.set_newton_systems(systems).unwrap();
    let nd = model.n_dofs();
    let x: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
    let xd: Vec<f64> = (0..nd).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
    let y = eom.state(&x, &xd);
    let label = format!("{systems:?}");
    crate::solve::integrate::assert_quadrature_rows(&mut eom, 0.0, &y, 2 * nd, &label);
}
