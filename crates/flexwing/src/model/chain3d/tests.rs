//! Consistency of the 3-D chain's recursions with each other and with their definitions: the
//! momentum and gyroscopic term against dual-number derivatives of the kinetic energy, the
//! composite-rigid-body mass matrix against the momentum, the articulated-body solve against the
//! mass matrix, the generalized forces against virtual work and the load potential, the exact
//! Jacobians against finite differences. (Consistency tests: the references are the model's own
//! definitions, computed by other code paths; validation against closed forms is in
//! `tests/suite/chain3d_*.rs`.)

use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

use super::kinematics::{Frames, Motion};
use super::*;
use crate::beam::{Discretization, InertiaAxis, Profile};
use crate::model::{hamiltonian_derivatives_dense, StructuralModel};

/// A chain where nothing is symmetric: swept, with dihedral and pretwist tables, offsets in both
/// directions, coupled stiffness, rotary inertias.
fn general_chain(n: usize) -> Chain3d {
    let l = 2.0;
    let table = |a: f64, b: f64| Profile::Table {
        x: vec![0.0, 0.7, l],
        value: vec![a, 0.5 * (a + b) * 1.1, b],
    };
    let geometry = Geometry3d::Span {
        length: l,
        discretization: Discretization::Uniform(n),
        sweep: table(0.1, 0.4),
        dihedral: table(0.05, -0.1),
        pretwist: table(0.0, 0.3),
    };
    let stiffness = SectionStiffness {
        gj: table(3.0, 2.0),
        ei_flap: table(5.0, 4.0),
        ei_lag: table(20.0, 12.0),
        coupling: Some(StiffnessCoupling {
            twist_flap: table(0.8, 0.5),
            twist_lag: table(-0.3, 0.2),
            lag_flap: table(0.5, 0.1),
        }),
    };
    let inertia = SectionInertia {
        mass_per_length: table(1.0, 0.6),
        polar_inertia: table(0.05, 0.03),
        polar_inertia_about: InertiaAxis::MassCentre,
        d0: table(0.1, -0.05),
        d0_normal: table(0.02, 0.04),
        rotary_inertia_flap: table(0.01, 0.004),
        rotary_inertia_lag: table(0.03, 0.01),
        element_inertia: ElementInertia::Bar,
    };
    Chain3d::new(
        Beam3d::new(
            &geometry,
            &stiffness,
            &inertia,
            JointCalibration::Compliance,
        )
        .unwrap(),
    )
}

/// [`general_chain`] with the fluid's inertia (varying per element, offsets of both signs).
fn wet_chain(n: usize) -> Chain3d {
    general_chain(n).with_fluid(crate::model::aero::FluidInertia {
        mass: (0..n).map(|i| 0.3 + 0.05 * i as f64).collect(),
        station: (0..n).map(|i| -0.06 + 0.03 * i as f64).collect(),
        inertia: (0..n).map(|i| 2e-3 * (1.0 + i as f64)).collect(),
    })
}

/// The dry and the wet chain of `n` elements.
fn both_chains(n: usize) -> [Chain3d; 2] {
    [general_chain(n), wet_chain(n)]
}

fn state(n: usize) -> (Vec<f64>, Vec<f64>) {
    let x = (0..3 * n)
        .map(|i| 0.4 * (1.3 * i as f64 + 0.2).sin())
        .collect();
    let xd = (0..3 * n)
        .map(|i| 1.5 * (0.7 * i as f64 + 1.0).cos())
        .collect();
    (x, xd)
}

fn kinetic_energy_dual(model: &Chain3d, x: &[Dual64], xd: &[Dual64]) -> Dual64 {
    let mut fr = Frames::new(model.n);
    model.configure(x, &mut fr);
    let mut mo = Motion::new(model.n);
    model.motion(&fr, xd, &mut mo);
    model.kinetic_energy_of(&fr, &mo)
}

fn lift(v: &[f64]) -> Vec<Dual64> {
    v.iter().map(|&a| Dual64::from(a)).collect()
}

#[test]
fn momentum_and_gyroscopic_term_are_the_derivatives_of_the_kinetic_energy() {
    let n = 5;
    for model in both_chains(n) {
        momentum_and_gyroscopic_term(&model);
    }
}

fn momentum_and_gyroscopic_term(model: &Chain3d) {
    let n = model.n;
    let (x, xd) = state(n);
    let mut ws = model.workspace();
    let (mut p, mut g) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
    model.momentum_into(&x, &xd, &mut ws, &mut p);
    model.gyroscopic_into(&x, &xd, &mut ws, &mut g);
    let scale_p = p.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    let scale_g = g.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
    for k in 0..3 * n {
        let (xl, mut xdl) = (lift(&x), lift(&xd));
        xdl[k].eps = 1.0;
        let dt_dv = kinetic_energy_dual(model, &xl, &xdl).eps;
        let (mut xl, xdl) = (lift(&x), lift(&xd));
        xl[k].eps = 1.0;
        let dt_dx = kinetic_energy_dual(model, &xl, &xdl).eps;
        // Exact derivatives of the same energy by another path: round-off only.
        assert!(
            (p[k] - dt_dv).abs() < 1e-13 * scale_p,
            "p[{k}]: {} vs {dt_dv}",
            p[k]
        );
        assert!(
            (g[k] - dt_dx).abs() < 1e-12 * scale_g,
            "γ[{k}]: {} vs {dt_dx}",
            g[k]
        );
    }
    let t = model.kinetic_energy(&x, &xd);
    let half_pv: f64 = 0.5 * p.iter().zip(&xd).map(|(a, b)| a * b).sum::<f64>();
    assert!((t - half_pv).abs() < 1e-14 * t);
}

#[test]
fn mass_matrix_velocity_solve_and_momentum_agree() {
    for model in both_chains(6) {
        mass_matrix_velocity_solve_and_momentum(&model);
    }
}

fn mass_matrix_velocity_solve_and_momentum(model: &Chain3d) {
    let n = model.n;
    let (x, xd) = state(n);
    let mut ws = model.workspace();
    let nd = 3 * n;
    let mut m = DMatrix::zeros(nd, nd);
    model.mass_matrix_into(&x, &mut ws, &mut m);
    let mut p = vec![0.0; nd];
    model.momentum_into(&x, &xd, &mut ws, &mut p);
    let mp = &m * DVector::from_column_slice(&xd);
    let scale = m.amax();
    for k in 0..nd {
        assert!((mp[k] - p[k]).abs() < 1e-13 * scale * 10.0, "row {k}");
    }
    assert!((&m - m.transpose()).amax() < 1e-15 * scale);
    assert!(m.clone().cholesky().is_some());
    let mut v = vec![0.0; nd];
    assert!(model.velocities_into(&x, &p, &mut ws, &mut v));
    let err = v
        .iter()
        .zip(&xd)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    // M⁻¹ (M ẋ) = ẋ to the conditioning of M (κ ≈ 1e5 here): 1e-10.
    assert!(err < 1e-10, "{err:e}");
}

#[test]
fn generalized_forces_are_the_virtual_work_of_the_loads() {
    let n = 5;
    let model = general_chain(n);
    let (x, _) = state(n);
    let l = model.beam().length();
    let loads = [
        SpatialLoad::PointForce {
            span: l,
            force: SpatialVector::Dead([0.3, 1.0, -0.5]),
        },
        SpatialLoad::PointForce {
            span: 0.77,
            force: SpatialVector::Follower([0.2, -0.4, 0.9]),
        },
        SpatialLoad::PointMoment {
            span: 1.3,
            moment: SpatialVector::Dead([0.5, 0.1, -0.2]),
        },
        SpatialLoad::PointMoment {
            span: l,
            moment: SpatialVector::Follower([-0.3, 0.6, 0.2]),
        },
    ];
    let applied = model.apply(&loads, "loads").unwrap();
    let scales = [1.0, 0.7, 1.2, 0.9];
    let mut ws = model.workspace();
    let mut q = DVector::zeros(3 * n);
    model.generalized_forces_into(&x, &applied, &scales, &mut ws, &mut q);
    // Q = J_Xᵀ F + J_ωᵀ N with the Jacobians of the public functions.
    let frames = model.element_frames(&x);
    let element = |s: f64| ((s / l * n as f64).ceil() as usize).clamp(1, n) - 1;
    let mut want = DVector::zeros(3 * n);
    for (ld, &s) in loads.iter().zip(&scales) {
        match ld {
            SpatialLoad::PointForce { span, force } => {
                let f = match force {
                    SpatialVector::Dead(v) => *v,
                    SpatialVector::Follower(v) => super::algebra::mv(&frames[element(*span)], v),
                };
                let j = model.point_jacobian(&x, *span);
                want += j.transpose() * DVector::from_column_slice(&f) * s;
            }
            SpatialLoad::PointMoment { span, moment } => {
                let m = match moment {
                    SpatialVector::Dead(v) => *v,
                    SpatialVector::Follower(v) => super::algebra::mv(&frames[element(*span)], v),
                };
                let j = model.angular_velocity_jacobian(&x, element(*span));
                want += j.transpose() * DVector::from_column_slice(&m) * s;
            }
            _ => unreachable!(),
        }
    }
    assert!(
        (&q - &want).amax() < 1e-14 * want.amax() * 10.0,
        "{q} vs {want}"
    );
}

#[test]
fn conservative_forces_derive_from_their_potential_and_jacobians_are_exact() {
    let n = 4;
    let model = general_chain(n);
    let (x, _) = state(n);
    let l = model.beam().length();
    let table = Profile::Table {
        x: vec![0.0, 1.1, l],
        value: vec![0.5, -0.2, 0.8],
    };
    let dead = [
        SpatialLoad::PointForce {
            span: 1.6,
            force: SpatialVector::Dead([0.3, 1.0, -0.5]),
        },
        SpatialLoad::Distributed(SpatialDistributed::Dead([
            table.clone(),
            Profile::Uniform(-0.3),
            table.clone(),
        ])),
        SpatialLoad::Gravity {
            acceleration: [0.5, -9.81, 0.2],
        },
    ];
    let applied = model.apply(&dead, "loads").unwrap();
    let scales = [1.0, 0.8, 0.1];
    assert!(model.loads_are_conservative(&applied, &scales));
    let mut ws = model.workspace();
    let nd = 3 * n;
    let mut q = DVector::zeros(nd);
    model.generalized_forces_into(&x, &applied, &scales, &mut ws, &mut q);
    // Q = −∂V/∂x by central differences of the potential (h = 1e-5: truncation ~1e-10, round-off
    // ~1e-11 of |V|): 1e-8 of |Q|.
    let h = 1e-5;
    for k in 0..nd {
        let mut xp = x.clone();
        xp[k] += h;
        let vp = model.load_potential_energy(&xp, &applied, &scales);
        xp[k] -= 2.0 * h;
        let vm = model.load_potential_energy(&xp, &applied, &scales);
        let fd = -(vp - vm) / (2.0 * h);
        assert!(
            (q[k] - fd).abs() < 1e-8 * q.amax(),
            "Q[{k}] {} vs {fd}",
            q[k]
        );
    }
    // The load Jacobian, symmetric for conservative loads, and against central differences of Q
    // for follower loads too.
    let mut all = dead.to_vec();
    all.push(SpatialLoad::PointForce {
        span: l,
        force: SpatialVector::Follower([0.2, -0.4, 0.9]),
    });
    all.push(SpatialLoad::Distributed(SpatialDistributed::Follower([
        Profile::Uniform(0.1),
        table.clone(),
        Profile::Uniform(0.4),
    ])));
    all.push(SpatialLoad::PointMoment {
        span: 0.9,
        moment: SpatialVector::Dead([0.5, 0.1, -0.2]),
    });
    let applied_all = model.apply(&all, "loads").unwrap();
    for (loads, sc, symmetric) in [
        (&applied, scales.to_vec(), true),
        (&applied_all, vec![1.0, 0.8, 0.1, 0.6, 0.9, 1.1], false),
    ] {
        let mut jac = DMatrix::zeros(nd, nd);
        model.load_jacobian_into(&x, loads, &sc, &mut ws, &mut jac);
        if symmetric {
            assert!((&jac - jac.transpose()).amax() < 1e-13 * jac.amax());
        } else {
            assert!(!model.loads_are_conservative(loads, &sc));
        }
        let h = 1e-6;
        for k in 0..nd {
            let (mut qp, mut qm) = (DVector::zeros(nd), DVector::zeros(nd));
            let mut xp = x.clone();
            xp[k] += h;
            model.generalized_forces_into(&xp, loads, &sc, &mut ws, &mut qp);
            xp[k] -= 2.0 * h;
            model.generalized_forces_into(&xp, loads, &sc, &mut ws, &mut qm);
            let fd = (qp - qm) / (2.0 * h);
            // Central differences: truncation ~h² |Q'''|, round-off ~ε|Q|/h: 1e-8 of |∂Q/∂x|.
            let err = (&fd - jac.column(k)).amax();
            assert!(err < 1e-8 * jac.amax(), "column {k}: {err:e}");
        }
    }
}

#[test]
fn exact_kinetic_and_hamiltonian_derivatives_match_the_dense_path_and_differences() {
    for model in both_chains(4) {
        exact_kinetic_and_hamiltonian_derivatives(&model);
    }
}

fn exact_kinetic_and_hamiltonian_derivatives(model: &Chain3d) {
    let n = model.n;
    let (x, xd) = state(n);
    let nd = 3 * n;
    let mut ws = model.workspace();
    let (mut dp, mut dg) = (DMatrix::zeros(nd, nd), DMatrix::zeros(nd, nd));
    model.kinetic_derivatives_into(&x, &xd, &mut ws, &mut dp, &mut dg);
    let h = 1e-6;
    for k in 0..nd {
        let (mut pp, mut pm, mut gp, mut gm) =
            (vec![0.0; nd], vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]);
        let mut xp = x.clone();
        xp[k] += h;
        model.momentum_into(&xp, &xd, &mut ws, &mut pp);
        model.gyroscopic_into(&xp, &xd, &mut ws, &mut gp);
        xp[k] -= 2.0 * h;
        model.momentum_into(&xp, &xd, &mut ws, &mut pm);
        model.gyroscopic_into(&xp, &xd, &mut ws, &mut gm);
        for r in 0..nd {
            let fdp = (pp[r] - pm[r]) / (2.0 * h);
            let fdg = (gp[r] - gm[r]) / (2.0 * h);
            // Central differences: 1e-7 of the largest entry.
            assert!((fdp - dp[(r, k)]).abs() < 1e-7 * dp.amax(), "dp ({r}, {k})");
            assert!((fdg - dg[(r, k)]).abs() < 1e-7 * dg.amax(), "dγ ({r}, {k})");
        }
    }
    let mut p = vec![0.0; nd];
    model.momentum_into(&x, &xd, &mut ws, &mut p);
    let (mut a, mut b) = (DMatrix::zeros(nd, nd), DMatrix::zeros(nd, nd));
    assert!(model.hamiltonian_derivatives_into(&x, &p, &mut ws, true, &mut a, &mut b));
    let (mut c, mut d) = (DMatrix::zeros(nd, nd), DMatrix::zeros(nd, nd));
    assert!(hamiltonian_derivatives_dense(
        model, &x, &p, &mut ws, true, &mut c, &mut d
    ));
    // Two exact paths: round-off amplified by the conditioning of M (~1e5): 1e-9.
    assert!((&a - &c).amax() < 1e-9 * c.amax(), "{:e}", (&a - &c).amax());
    assert!((&b - &d).amax() < 1e-9 * d.amax(), "{:e}", (&b - &d).amax());
}

#[test]
fn an_in_plane_state_keeps_exact_zeros_out_of_plane() {
    // Straight, uncoupled, d0 = 0: an in-plane state and in-plane loads give exactly zero
    // twist and lag forces, velocities and gyroscopic terms (the planar limit to round-off).
    let n = 5;
    let model = Chain3d::new(
        Beam3d::new(
            &Geometry3d::straight(1.0, n),
            &SectionStiffness::uncoupled(2.0, 5.0, 9.0),
            &SectionInertia::uniform(0.2, 0.01),
            JointCalibration::Compliance,
        )
        .unwrap(),
    );
    let mut x = vec![0.0; 3 * n];
    let mut xd = vec![0.0; 3 * n];
    for i in 0..n {
        x[3 * i + 2] = 0.3 * (i as f64 + 1.0).sin();
        xd[3 * i + 2] = 0.9 * (2.0 * i as f64).cos();
    }
    let loads = model
        .apply(
            &[
                SpatialLoad::PointForce {
                    span: 1.0,
                    force: SpatialVector::Follower([0.5, 2.0, 0.0]),
                },
                SpatialLoad::Gravity {
                    acceleration: [0.0, -9.81, 0.0],
                },
            ],
            "loads",
        )
        .unwrap();
    let mut ws = model.workspace();
    let mut q = DVector::zeros(3 * n);
    model.generalized_forces_into(&x, &loads, &[1.0, 1.0], &mut ws, &mut q);
    let (mut p, mut g, mut v) = (vec![0.0; 3 * n], vec![0.0; 3 * n], vec![0.0; 3 * n]);
    model.momentum_into(&x, &xd, &mut ws, &mut p);
    model.gyroscopic_into(&x, &xd, &mut ws, &mut g);
    assert!(model.velocities_into(&x, &p, &mut ws, &mut v));
    for i in 0..n {
        for a in 0..2 {
            assert_eq!(q[3 * i + a], 0.0);
            assert_eq!(p[3 * i + a], 0.0);
            assert_eq!(g[3 * i + a], 0.0);
            assert_eq!(v[3 * i + a], 0.0);
        }
    }
}

#[test]
fn bad_loads_name_their_field() {
    let model = general_chain(3);
    let e = model
        .apply(
            &[SpatialLoad::PointForce {
                span: 2.5,
                force: SpatialVector::Dead([0.0, 1.0, 0.0]),
            }],
            "loads",
        )
        .unwrap_err();
    assert_eq!(e.field, "loads[0].span");
    let e = model
        .apply(
            &[
                SpatialLoad::Gravity {
                    acceleration: [0.0, -9.81, 0.0],
                },
                SpatialLoad::PointMoment {
                    span: 1.0,
                    moment: SpatialVector::Follower([0.0, f64::NAN, 0.0]),
                },
            ],
            "loads",
        )
        .unwrap_err();
    assert_eq!(e.field, "loads[1].moment");
    assert!(e.reason.contains("component 1"), "{e}");
    let e = model
        .apply(
            &[SpatialLoad::Distributed(SpatialDistributed::Dead([
                Profile::Uniform(0.0),
                Profile::Table {
                    x: vec![0.0, 1.0],
                    value: vec![1.0, 2.0],
                },
                Profile::Uniform(0.0),
            ]))],
            "loads",
        )
        .unwrap_err();
    assert_eq!(e.field, "loads[0].force[1]");
}

#[test]
fn node_velocities_are_the_point_jacobians_times_the_rates() {
    let n = 4;
    let model = general_chain(n);
    let (x, xd) = state(n);
    let v = model.node_velocities(&x, &xd);
    let nodes = model.beam().nodes().to_vec();
    for (k, s) in nodes.iter().enumerate() {
        let j = model.point_jacobian(&x, *s);
        let want = j * DVector::from_column_slice(&xd);
        for a in 0..3 {
            assert!(
                (v[k][a] - want[a]).abs() < 1e-13 * want.amax().max(1.0),
                "node {k}"
            );
        }
    }
}

/// The fluid's kinetic energy of a wet chain against its definition, computed from positions
/// and frames alone: `T_wet − T_dry = Σ ½ m_a (n·Ẋ_m)² + ½ J_a (ω·t)²`, with the mid-chord point
/// `X_m = P_i + ½ d_i + ζ_m c_i` and the angular velocity from central differences of the
/// frames along `ẋ` (`R(x + hẋ) R(x − hẋ)ᵀ = I + 2h ω̂ + O(h²)`, step 1e-5: truncation ~1e-10 of
/// the energy; tolerance 1e-8).
#[test]
fn the_fluid_energy_is_that_of_its_definition() {
    let n = 5;
    let (dry, wet) = (general_chain(n), wet_chain(n));
    let f = wet.fluid.clone().unwrap();
    let (x, xd) = state(n);
    let h = 1e-5;
    let along = |s: f64| -> Vec<f64> { x.iter().zip(&xd).map(|(a, b)| a + s * b).collect() };
    let (xp, xm) = (along(h), along(-h));
    let point = |x: &[f64], i: usize| -> [f64; 3] {
        let p = wet.node_positions(x);
        let r = wet.element_frames(x)[i];
        std::array::from_fn(|k| 0.5 * (p[i][k] + p[i + 1][k]) + f.station[i] * r[k][2])
    };
    let frames = wet.element_frames(&x);
    let (fp, fm) = (wet.element_frames(&xp), wet.element_frames(&xm));
    let mut fluid = 0.0;
    for i in 0..n {
        let (a, b) = (point(&xp, i), point(&xm, i));
        let v: [f64; 3] = std::array::from_fn(|k| (a[k] - b[k]) / (2.0 * h));
        let r = frames[i];
        let u: f64 = (0..3).map(|k| r[k][1] * v[k]).sum();
        // ω̂ ≈ (R_p R_mᵀ − R_m R_pᵀ)/(4h): its axial vector.
        let w = |a: usize, b: usize| -> f64 {
            (0..3)
                .map(|k| fp[i][a][k] * fm[i][b][k] - fm[i][a][k] * fp[i][b][k])
                .sum::<f64>()
                / (4.0 * h)
        };
        let omega = [w(2, 1), w(0, 2), w(1, 0)];
        let spin: f64 = (0..3).map(|k| r[k][0] * omega[k]).sum();
        fluid += 0.5 * f.mass[i] * u * u + 0.5 * f.inertia[i] * spin * spin;
    }
    let got = wet.kinetic_energy(&x, &xd) - dry.kinetic_energy(&x, &xd);
    assert!(
        (got - fluid).abs() < 1e-8 * wet.kinetic_energy(&x, &xd),
        "{got} vs {fluid}"
    );
}
