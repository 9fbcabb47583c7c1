//! Non-linear statics against closed forms: a tip moment `M = 2π EI/L` rolls the cantilever into a
//! full circle of radius `L/2π`; a compressive dead tip load buckles it at `π² EI/(4L²)`
//! (Euler); the reduced model with every mode is the full model.

use crate::common::*;
use flexwing::beam::Calibration;
use flexwing::model::{Force, Load, ReducedModel, StructuralModel};
use flexwing::solve::{solve_static, sweep_static, Modes, StaticOptions};
use nalgebra::DMatrix;
use std::f64::consts::PI;

const L: f64 = 1.0;
const EI: f64 = 50.0;

#[test]
fn tip_moment_rolls_the_beam_into_a_circle() {
    let n = 40;
    let full = table4(n);
    let loads = full
        .apply(
            &[Load::Moment {
                span: L,
                value: 2.0 * PI * EI / L,
            }],
            "loads",
        )
        .unwrap();
    let sol = solve_static(&full, &loads, &[1.0], &StaticOptions::default()).unwrap();
    let nodes = full.node_positions(&full.kinematics(&sol.q));
    let r = L / (2.0 * PI);
    let worst = nodes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let s = k as f64 * L / n as f64;
            ((p[0] - r * (s / r).sin()).powi(2) + (p[1] - r * (1.0 - (s / r).cos())).powi(2)).sqrt()
        })
        .fold(0.0, f64::max);
    // Expected discretization error. Under a pure moment every joint carries M, so q_i = M/K_i.
    // The tip-load rule gives K_i = EI/ℓ exactly for i ≥ 2 (the second difference of the cubic
    // deflection is exact) and K_1 = (2EI/ℓ)·3L/(3L − ℓ). The nodes thus lie on a regular polygon
    // of side ℓ, whose circumradius exceeds L/2π by the factor (π/n)/sin(π/n) ≈ 1 + π²/(6n²)
    // (node displacement up to 2R·π²/(6n²) = (π/6)/n² · L), rotated about the root by the root
    // angle error π/(3n²) (displacement up to 2R·π/(3n²) = L/(3n²)). Together
    // √((π/6)² + (1/3)²) L/n² = 0.62 L/n² = 3.9e-4 m at n = 40; we allow 0.7 L/n².
    assert!(
        worst < 0.7 * L / (n * n) as f64,
        "worst node error {worst:.3e} m"
    );
    // The polygon closes: the tip returns to the root (to round-off).
    assert!(nodes[n][0].abs() < 1e-12 && nodes[n][1].abs() < 1e-12);
    // And at twice the resolution the error quarters (second order).
    let full80 = table4(80);
    let loads80 = full80
        .apply(
            &[Load::Moment {
                span: L,
                value: 2.0 * PI * EI / L,
            }],
            "loads",
        )
        .unwrap();
    let sol80 = solve_static(&full80, &loads80, &[1.0], &StaticOptions::default()).unwrap();
    let mid80 = full80.node_positions(&full80.kinematics(&sol80.q))[40];
    let mid40 = nodes[20];
    let exact_mid = [0.0, 2.0 * r];
    let e40 = ((mid40[0] - exact_mid[0]).powi(2) + (mid40[1] - exact_mid[1]).powi(2)).sqrt();
    let e80 = ((mid80[0] - exact_mid[0]).powi(2) + (mid80[1] - exact_mid[1]).powi(2)).sqrt();
    assert!((3.5..4.5).contains(&(e40 / e80)), "ratio {}", e40 / e80);
}

#[test]
fn compressive_tip_load_buckles_at_the_euler_load() {
    // Straight beam, dead tip force −P along x: the straight state is an equilibrium for every P,
    // and its tangent K − ∂Q/∂q loses definiteness at the lumped model's buckling load.
    let n = 40;
    let full = table4(n);
    let p_euler = PI * PI * EI / (4.0 * L * L);
    let q0 = vec![0.0; n];
    let loads_for = |p: f64| {
        full.apply(
            &[Load::PointForce {
                span: L,
                force: Force::Dead { fx: -p, fy: 0.0 },
            }],
            "loads",
        )
        .unwrap()
    };
    // Stable while the tangent K − ∂Q/∂q is positive definite (its Cholesky factor exists).
    let stable = |p: f64| {
        let mut jac = DMatrix::zeros(n, n);
        full.load_jacobian_into(&q0, &loads_for(p), &[1.0], &mut full.workspace(), &mut jac);
        (full.stiffness_matrix() - jac).cholesky().is_some()
    };
    let (mut lo, mut hi) = (0.5 * p_euler, 1.5 * p_euler);
    assert!(stable(lo) && !stable(hi));
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if stable(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    // Lumped buckling load: second-order error, 0.128/n² (measured 1.28e-3, 3.2e-4, 8.0e-5 at
    // n = 10, 20, 40); allow 2e-4 at n = 40.
    assert!(
        (lo / p_euler - 1.0).abs() < 2e-4,
        "P_cr = {lo}, Euler {p_euler}"
    );
    let omega1 = |p: f64| Modes::loaded(&full, &q0, &loads_for(p), &[1.0]).map(|m| m.omega()[0]);
    // The first frequency falls as the load approaches buckling.
    let w0 = omega1(0.0).unwrap();
    let w_half = omega1(0.5 * p_euler).unwrap();
    let w_near = omega1(0.99 * lo).unwrap();
    assert!(w_near < w_half && w_half < w0);
    assert!(w_near < 0.15 * w0);
    // Beyond buckling the modal analysis refuses the unstable state rather than return NaN.
    assert!(omega1(1.05 * lo).is_err());
}

#[test]
fn reduced_model_with_every_mode_is_the_full_model() {
    let full = model(16.0, &table1_section(), 12, Calibration::TipLoad);
    let modes = Modes::undeformed(&full).unwrap();
    let rom = ReducedModel::first(&full, modes.shapes(), full.n_dofs()).unwrap();
    let loads = full
        .apply(
            &[
                Load::PointForce {
                    span: 16.0,
                    force: Force::Dead { fx: 0.0, fy: 400.0 },
                },
                Load::PointForce {
                    span: 8.0,
                    force: Force::Follower {
                        tangential: 0.0,
                        normal: -200.0,
                    },
                },
                Load::Torque {
                    span: 16.0,
                    value: 50.0,
                },
                Load::Gravity { g: 9.81 },
            ],
            "loads",
        )
        .unwrap();
    let points: Vec<Vec<f64>> = (1..=4).map(|k| vec![k as f64 / 4.0; 4]).collect();
    let opts = StaticOptions::default();
    let a = sweep_static(&full, &loads, &points, &opts).unwrap();
    let b = sweep_static(&rom, &loads, &points, &opts).unwrap();
    for (sa, sb) in a.iter().zip(&b) {
        // Both converge to a residual of 1e-10 relative; the change of basis is orthogonal in the
        // M-norm, so the coordinates agree to about the solver tolerance times the conditioning.
        let diff =
            sa.q.iter()
                .zip(&sb.q)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max);
        let scale = sa.q.iter().map(|x| x.abs()).fold(0.0, f64::max);
        assert!(diff < 1e-8 * scale, "difference {diff:.2e} of {scale:.2e}");
    }
    // Large enough to be non-linear: the tip turned by more than 30°.
    assert!(a[3].q[..12].iter().sum::<f64>().abs() > 0.5);
}
