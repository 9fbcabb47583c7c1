//! Regression tests of the 3-D chain's O(n) Newton systems (`NewtonSystems::Chain`: GMRES on the
//! exact operator, preconditioned by the articulated-body solve, `model/chain3d/newton.rs`)
//! against the dense path (the exact Jacobian, dense LU): the same Newton steps to round-off
//! at a bent, fast-moving state under every kind of load and with damping, and the same
//! trajectories for Radau, BDF, the midpoint rule and generalized-α on a swept, pretwisted,
//! coupled chain. The dense path itself is validated against closed forms and the energy
//! balance in `chain3d_dynamics.rs`; these tests compare the model with itself.

use crate::common::chain3d::coupled_chain;
use flexwing::beam::Profile;
use flexwing::model::chain3d::{Chain3d, SpatialDistributed, SpatialLoad, SpatialVector};
use flexwing::solve::integrate::{
    Bdf, BdfOptions, GeneralizedAlpha, GeneralizedAlphaOptions, ImplicitMidpoint, MidpointOptions,
    OdeSystem, Radau, RadauOptions, Tolerances, Trajectory,
};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction};
use nalgebra::{Complex, DMatrix, DVector};

/// Every kind of load: follower and dead tip forces, a dead moment, a distributed follower
/// force and gravity.
fn loads() -> Vec<SpatialLoad> {
    vec![
        SpatialLoad::PointForce {
            span: 1.0,
            force: SpatialVector::Follower([0.5, 4.0, -2.0]),
        },
        SpatialLoad::PointForce {
            span: 0.55,
            force: SpatialVector::Dead([-1.0, 3.0, 1.5]),
        },
        SpatialLoad::PointMoment {
            span: 0.8,
            moment: SpatialVector::Dead([0.3, -0.2, 0.4]),
        },
        SpatialLoad::Distributed(SpatialDistributed::Follower([
            Profile::Uniform(0.2),
            Profile::Uniform(-0.7),
            Profile::Uniform(0.3),
        ])),
        SpatialLoad::Gravity {
            acceleration: [0.0, -9.81, 0.0],
        },
    ]
}

/// The chain's solves of `(c I − J) Δ = r` against a dense LU of the exact Jacobian (the
/// dense path's own matrix), at a bent and fast-moving state, for Radau's real and complex
/// shifts and the midpoint rule's, with and without the gyroscopic term and with Rayleigh
/// damping. The iteration solves the exact operator to a residual of 1e-12: agreement to the
/// conditioning of `c I − J` (up to ~1e8 at these shifts), bound 1e-8 relative.
#[test]
fn regression_chain3d_newton_solves_match_the_dense_jacobian() {
    let model = coupled_chain(8);
    let nd = model.n_dofs();
    let applied = model.apply(&loads(), "loads").unwrap();
    let cases = [
        (Gyroscopic::Exact, Damping::None),
        (Gyroscopic::Neglected, Damping::None),
        (
            Gyroscopic::Exact,
            Damping::Rayleigh {
                alpha: 0.5,
                beta: 1e-3,
            },
        ),
    ];
    for (gyroscopic, damping) in cases {
        let tf = vec![TimeFunction::Constant; 5];
        let mut eom = EquationsOfMotion::new(&model, &applied, tf, gyroscopic, &damping).unwrap();
        eom.set_newton_systems(NewtonSystems::Chain).unwrap();
        let x: Vec<f64> = (0..nd).map(|i| 0.2 * (1.0 + i as f64).sin()).collect();
        let xd: Vec<f64> = (0..nd).map(|i| 2.0 * (2.0 * i as f64).cos()).collect();
        let y = eom.state(&x, &xd);
        let mut jac = DMatrix::zeros(2 * nd, 2 * nd);
        eom.jacobian(0.3, &y, &mut jac);
        let r: Vec<f64> = (0..2 * nd).map(|i| (0.37 * i as f64).cos()).collect();
        let s = eom.newton_solver().expect("chain solver");
        assert!(s.linearize(0.3, &y));
        for c in [3.6 / 1e-2, 2.0 / 1e-3, 0.5] {
            let a = DMatrix::identity(2 * nd, 2 * nd) * c - &jac;
            let want = a.lu().solve(&DVector::from_column_slice(&r)).unwrap();
            assert!(s.factor_real(1, c));
            let mut got = r.clone();
            s.solve_real(1, &mut got);
            let err = (DVector::from_column_slice(&got) - &want).amax() / want.amax();
            eprintln!("{gyroscopic:?} {damping:?} c = {c}: {err:.2e}");
            assert!(err < 1e-8, "{gyroscopic:?} {damping:?} c = {c}: {err:.2e}");
        }
        let c = Complex::new(2.68, 3.05) / 1e-2;
        let a = (DMatrix::identity(2 * nd, 2 * nd) * c) - jac.map(|v| Complex::new(v, 0.0));
        let rc: Vec<Complex<f64>> = r
            .iter()
            .enumerate()
            .map(|(i, &v)| Complex::new(v, (0.1 * i as f64).sin()))
            .collect();
        let want = a.lu().solve(&DVector::from_column_slice(&rc)).unwrap();
        assert!(s.factor_complex(0, c));
        let mut re: Vec<f64> = rc.iter().map(|v| v.re).collect();
        let mut im: Vec<f64> = rc.iter().map(|v| v.im).collect();
        s.solve_complex(0, &mut re, &mut im);
        let scale = want.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let err = (0..2 * nd)
            .map(|i| (Complex::new(re[i], im[i]) - want[i]).norm())
            .fold(0.0, f64::max)
            / scale;
        eprintln!("{gyroscopic:?} {damping:?} complex: {err:.2e}");
        assert!(err < 1e-8, "{gyroscopic:?} {damping:?} complex: {err:.2e}");
    }
}

#[derive(Clone, Copy, Debug)]
enum Method {
    Radau(f64),
    Bdf(f64),
    Midpoint(f64),
    Alpha(f64),
}

/// A release from rest under the loads of [`loads`] (the tip force as `sin(9 t)`, the others
/// constant) over `t`, with the Newton systems `newton`.
fn run(model: &Chain3d, t: &[f64], method: Method, newton: NewtonSystems) -> Trajectory {
    let applied = model.apply(&loads(), "loads").unwrap();
    let mut tf = vec![TimeFunction::Constant; 5];
    tf[0] = TimeFunction::Sine {
        omega: 9.0,
        phase: 0.0,
    };
    let mut eom =
        EquationsOfMotion::new(model, &applied, tf, Gyroscopic::Exact, &Damping::None).unwrap();
    eom.set_newton_systems(newton).unwrap();
    let nd = model.n_dofs();
    let y0 = vec![0.0; 2 * nd];
    let tolerances = |rtol: f64, eom: &mut EquationsOfMotion<'_, Chain3d>| Tolerances {
        rtol,
        atol: eom.state_atol(rtol),
    };
    let result = match method {
        Method::Radau(rtol) => Radau {
            options: RadauOptions {
                tolerances: tolerances(rtol, &mut eom),
                // Relinearized at every step on both paths (the chain does it anyway,
                // `NewtonSolver::cheap_linearization`), so that both run the same iteration.
                jacobian_reuse: -1.0,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, t, &mut |_| {}),
        Method::Bdf(rtol) => Bdf {
            options: BdfOptions {
                tolerances: tolerances(rtol, &mut eom),
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, t, &mut |_| {}),
        Method::Midpoint(step) => ImplicitMidpoint {
            options: MidpointOptions {
                tolerances: tolerances(1e-6, &mut eom),
                step: Some(step),
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, t, &mut |_| {}),
        Method::Alpha(step) => GeneralizedAlpha {
            options: GeneralizedAlphaOptions {
                tolerances: tolerances(1e-6, &mut eom),
                step: Some(step),
                spectral_radius: 0.5,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, t, &mut |_| {}),
    };
    let (traj, _) = result.unwrap_or_else(|f| panic!("{method:?} {newton:?}: {f}"));
    if newton == NewtonSystems::Chain {
        let (solves, iterations, unconverged) = eom.chain3d_newton_counts().expect("chain ran");
        eprintln!(
            "{method:?}: {solves} solves, {:.1} GMRES iterations each, {unconverged} unconverged",
            iterations as f64 / solves.max(1) as f64
        );
        assert!(solves > 0);
    }
    traj
}

/// Largest distance between the tips of two trajectories (m), and the largest tip travel.
fn tip_difference(model: &Chain3d, a: &Trajectory, b: &Trajectory) -> (f64, f64) {
    let (nd, n) = (model.n_dofs(), model.n_elements());
    let dist = |p: [f64; 3], q: [f64; 3]| {
        ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
    };
    let start = model.node_positions(&vec![0.0; nd])[n];
    let mut worst = 0.0_f64;
    let mut travel = 0.0_f64;
    for (ya, yb) in a.y.iter().zip(&b.y) {
        let (pa, pb) = (
            model.node_positions(&ya[..nd])[n],
            model.node_positions(&yb[..nd])[n],
        );
        worst = worst.max(dist(pa, pb));
        travel = travel.max(dist(pa, start));
    }
    (worst, travel)
}

/// The same trajectories from both Newton paths, for every implicit integrator. Radau
/// relinearizes at every step on both paths, so both run the same Newton iteration, whose
/// steps agree to ~1e-11 (above): the tips agree to round-off (measured 3.6e-16 m; bound
/// 1e-12 m). The other integrators reuse the dense Jacobian over steps, while the chain
/// relinearizes at every step (its linearization is O(n)): different Newton iterates,
/// stopped at the Newton tolerance, so agreement to the integrators' tolerances — BDF at rtol
/// 1e-5 measured 1.5e-5 m (bound 1e-4 m, ten times rtol on the 1 m span); the fixed-step
/// midpoint rule and generalized-α (Newton tolerance 1e-4 of atol 1e-6) 2.7e-8 and 5.5e-7 m
/// (bound 1e-5 m, ten times atol).
#[test]
fn regression_chain3d_newton_trajectories_match_the_dense_path() {
    let model = coupled_chain(16);
    let t: Vec<f64> = (0..=20).map(|k| k as f64 * 0.01).collect();
    for method in [
        Method::Radau(1e-6),
        Method::Bdf(1e-5),
        Method::Midpoint(1e-3),
        Method::Alpha(1e-3),
    ] {
        let dense = run(&model, &t, method, NewtonSystems::Dense);
        let chain = run(&model, &t, method, NewtonSystems::Chain);
        let (diff, travel) = tip_difference(&model, &dense, &chain);
        eprintln!("{method:?}: tips {diff:.2e} m apart (travel {travel:.3} m)");
        assert!(travel > 0.02, "{travel}");
        let bound = match method {
            Method::Radau(_) => 1e-12,
            Method::Bdf(_) => 1e-4,
            Method::Midpoint(_) | Method::Alpha(_) => 1e-5,
        };
        assert!(diff < bound, "{method:?}: {diff:e}");
    }
}
