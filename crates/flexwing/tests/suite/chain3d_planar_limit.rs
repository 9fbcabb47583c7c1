//! The planar limit: with in-plane loads, no twist, no pretwist and `d0 = 0`, the 3-D chain's
//! flap bending is the planar chain's (`FullModel`) — the same springs (the tip-load
//! calibration on both), masses and bar inertias, the same kinematics in another
//! parametrization. Both models' equations are compared at the same states (to round-off), and
//! a static solve and a dynamic run of each are compared (to the solvers' tolerances).

use flexwing::beam::{
    Beam, Calibration, Discretization, Profile, RotaryInertia, SectionProperties,
};
use flexwing::model::chain3d::{
    Beam3d, Chain3d, Geometry3d, JointCalibration, SectionInertia, SectionStiffness,
};
use flexwing::model::{DistributedForce, Force, FullModel, Load, StructuralModel};
use flexwing::solve::integrate::{ImplicitMidpoint, MidpointOptions, Tolerances};
use flexwing::solve::TimeFunction;
use flexwing::solve::{solve_static, Damping, EquationsOfMotion, Gyroscopic, StaticOptions};
use nalgebra::DVector;

const L: f64 = 1.5;

fn taper(root: f64, tip: f64) -> Profile {
    Profile::Table {
        x: vec![0.0, 0.4 * L, L],
        value: vec![root, 0.5 * (root + tip) * 1.07, tip],
    }
}

/// The same tapered cantilever as a planar chain (bending only, bars) and a 3-D chain.
fn models(n: usize) -> (FullModel, Chain3d) {
    let (ei, m) = (taper(80.0, 30.0), taper(0.5, 0.2));
    let section = SectionProperties {
        ei: ei.clone(),
        mass_per_length: m.clone(),
        torsion: None,
    };
    let beam = Beam::new(
        L,
        &section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )
    .unwrap()
    .with_rotary_inertia(
        "beam",
        &section,
        &RotaryInertia {
            elements: true,
            section: None,
        },
    )
    .unwrap();
    let planar = FullModel::new(beam);
    let stiffness = SectionStiffness {
        gj: Profile::Uniform(40.0),
        ei_flap: ei,
        ei_lag: taper(300.0, 100.0),
        coupling: None,
    };
    let mut inertia = SectionInertia::uniform(1.0, 0.01);
    inertia.mass_per_length = m;
    let chain = Chain3d::new(
        Beam3d::new(
            &Geometry3d::straight(L, n),
            &stiffness,
            &inertia,
            JointCalibration::TipLoad,
        )
        .unwrap(),
    );
    (planar, chain)
}

fn planar_loads() -> Vec<Load> {
    vec![
        Load::PointForce {
            span: L,
            force: Force::Follower {
                tangential: 0.5,
                normal: -20.0,
            },
        },
        Load::PointForce {
            span: 0.6 * L,
            force: Force::Dead { fx: 3.0, fy: 15.0 },
        },
        Load::Moment {
            span: 0.3 * L,
            value: 2.0,
        },
        // Uniform: the planar model's midpoint lumping is then the exact first moment too.
        Load::Distributed(DistributedForce::Dead {
            fx: Profile::Uniform(0.0),
            fy: Profile::Uniform(-4.0),
        }),
        Load::Gravity { g: 9.81 },
    ]
}

/// The 3-D coordinates of a planar state: the flap components.
fn lift(q: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0; 3 * q.len()];
    for (i, v) in q.iter().enumerate() {
        x[3 * i + 2] = *v;
    }
    x
}

#[test]
fn the_equations_are_the_planar_chains_at_every_in_plane_state() {
    let n = 12;
    let (planar, chain) = models(n);
    let loads = planar_loads();
    let (lp, lc) = (
        planar.apply(&loads, "loads").unwrap(),
        chain.apply_planar(&loads, "loads").unwrap(),
    );
    let scales = vec![0.8, 1.0, 1.3, 0.6, 1.0];
    let (mut wp, mut wc) = (planar.workspace(), chain.workspace());
    for k in 0..4 {
        let q: Vec<f64> = (0..n)
            .map(|i| 0.15 * (k as f64 + 1.0) * (0.9 * i as f64 + k as f64).sin())
            .collect();
        let qd: Vec<f64> = (0..n)
            .map(|i| 2.0 * (1.7 * i as f64 - k as f64).cos())
            .collect();
        let x = lift(&q);
        let xd = lift(&qd);
        // Positions.
        let pp = planar.node_positions(&planar.kinematics(&q));
        let pc = chain.node_positions(&x);
        for (a, b) in pp.iter().zip(&pc) {
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 1e-14, "{a:?} vs {b:?}");
            }
        }
        // Stiffness, forces, momentum, gyroscopic term, velocities.
        let kc = chain.stiffness_matrix();
        let (mut qp, mut qc) = (DVector::zeros(n), DVector::zeros(3 * n));
        planar.generalized_forces_into(&q, &lp, &scales, &mut wp, &mut qp);
        chain.generalized_forces_into(&x, &lc, &scales, &mut wc, &mut qc);
        let (mut mp, mut mc) = (vec![0.0; n], vec![0.0; 3 * n]);
        StructuralModel::momentum_into(&planar, &q, &qd, &mut wp, &mut mp);
        StructuralModel::momentum_into(&chain, &x, &xd, &mut wc, &mut mc);
        let (mut gp, mut gc) = (vec![0.0; n], vec![0.0; 3 * n]);
        StructuralModel::gyroscopic_into(&planar, &q, &qd, &mut wp, &mut gp);
        StructuralModel::gyroscopic_into(&chain, &x, &xd, &mut wc, &mut gc);
        let (mut vp, mut vc) = (vec![0.0; n], vec![0.0; 3 * n]);
        assert!(planar.velocities_into(&q, &mp, &mut wp, &mut vp));
        assert!(chain.velocities_into(&x, &mc, &mut wc, &mut vc));
        let scale = |v: &[f64]| v.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
        let (sq, sm, sg, sv) = (qp.amax(), scale(&mp), scale(&gp), scale(&vp));
        for i in 0..n {
            // Round-off of O(n)-term sums in another arithmetic: 1e-13 of the largest entry.
            assert!((kc[(3 * i + 2, 3 * i + 2)] / planar.stiffness()[i] - 1.0).abs() < 1e-15);
            assert!((qc[3 * i + 2] - qp[i]).abs() < 1e-13 * sq, "Q[{i}]");
            assert!((mc[3 * i + 2] - mp[i]).abs() < 1e-13 * sm, "p[{i}]");
            assert!((gc[3 * i + 2] - gp[i]).abs() < 1e-13 * sg, "γ[{i}]");
            assert!((vc[3 * i + 2] - vp[i]).abs() < 1e-11 * sv, "ẋ[{i}]");
            for a in 0..2 {
                // Out of plane: exact zeros.
                assert_eq!(
                    (qc[3 * i + a], mc[3 * i + a], gc[3 * i + a]),
                    (0.0, 0.0, 0.0)
                );
                assert_eq!(vc[3 * i + a], 0.0);
            }
        }
    }
}

#[test]
fn static_and_dynamic_runs_match_the_planar_chains() {
    let n = 16;
    let (planar, chain) = models(n);
    let loads = planar_loads();
    let (lp, lc) = (
        planar.apply(&loads, "loads").unwrap(),
        chain.apply_planar(&loads, "loads").unwrap(),
    );
    let scales = vec![1.0; loads.len()];
    let options = StaticOptions::default();
    let sp = solve_static(&planar, &lp, &scales, &options).unwrap();
    let sc = solve_static(&chain, &lc, &scales, &options).unwrap();
    let tp = planar.node_positions(&planar.kinematics(&sp.q))[n];
    let tc = chain.node_positions(&sc.x)[n];
    eprintln!(
        "static tip: planar ({:.12}, {:.12}), 3-D ({:.12}, {:.12}, {:e}); steps {} and {}",
        tp[0], tp[1], tc[0], tc[1], tc[2], sp.stats.load_steps, sc.stats.load_steps
    );
    let diff = (0..3).map(|c| (tp[c] - tc[c]).abs()).fold(0.0, f64::max);
    eprintln!("static tip difference {diff:.1e} m");
    // The same load steps and Newton iterates on the same equations: round-off (measured
    // 1e-16 level); bound 1e-11 m, a tenth of what Newton's tolerance (1e-10) alone would allow.
    assert!(diff < 1e-11, "{tp:?} vs {tc:?}");
    // A dynamic run from rest under the same loads: implicit midpoint at a fixed step, the
    // planar and the 3-D equations of motion.
    let tf = vec![TimeFunction::Constant; loads.len()];
    let t_out: Vec<f64> = (0..=40).map(|k| k as f64 * 0.005).collect();
    let mut ep =
        EquationsOfMotion::new(&planar, &lp, tf.clone(), Gyroscopic::Exact, &Damping::None)
            .unwrap();
    let mut ec =
        EquationsOfMotion::new(&chain, &lc, tf, Gyroscopic::Exact, &Damping::None).unwrap();
    let yp0 = ep.state(&vec![0.0; n], &vec![0.0; n]);
    let yc0 = ec.state(&vec![0.0; 3 * n], &vec![0.0; 3 * n]);
    let midpoint = |atol: Vec<f64>| ImplicitMidpoint {
        options: MidpointOptions {
            tolerances: Tolerances { rtol: 1e-12, atol },
            step: Some(2.5e-4),
            ..Default::default()
        },
    };
    let atol_p = ep.state_atol(1e-12);
    let atol_c = ec.state_atol(1e-12);
    let (trp, _) = midpoint(atol_p)
        .integrate(&mut ep, 0.0, &yp0, &t_out, &mut |_| {})
        .expect("planar run");
    let (trc, _) = midpoint(atol_c)
        .integrate(&mut ec, 0.0, &yc0, &t_out, &mut |_| {})
        .expect("3-D run");
    let mut worst = 0.0_f64;
    let mut amplitude = 0.0_f64;
    for (yp, yc) in trp.y.iter().zip(&trc.y) {
        let q: Vec<f64> = yp[..n].to_vec();
        let x: Vec<f64> = yc[..3 * n].to_vec();
        let a = planar.node_positions(&planar.kinematics(&q))[n];
        let b = chain.node_positions(&x)[n];
        worst = worst
            .max((a[0] - b[0]).abs())
            .max((a[1] - b[1]).abs())
            .max(b[2].abs());
        amplitude = amplitude.max(a[1].abs());
        for i in 0..n {
            assert_eq!((x[3 * i], x[3 * i + 1]), (0.0, 0.0), "out-of-plane motion");
        }
    }
    eprintln!("dynamic run: largest tip difference {worst:.2e} m, tip amplitude {amplitude:.3} m");
    // The same fixed steps on the same equations: round-off only (measured 2.6e-15 m over
    // 0.2 s and 800 steps, tip amplitude 0.54 m); bound 1e-12 m.
    assert!(worst < 1e-12, "{worst:e}");
    assert!(amplitude > 0.05);
}
