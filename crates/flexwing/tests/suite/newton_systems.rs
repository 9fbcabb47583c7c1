//! The implicit integrators' Newton systems solved by O(n) chain sweeps (`NewtonSystems::Chain`)
//! against the dense path (the exact Jacobian, dense LU): the same trajectories at n ≤ 160, for
//! bending and coupled bending–torsion beams and for Radau, BDF and the midpoint rule; and at
//! n = 1000 (dense is out of reach there) the case (b) setting against a run with half the step
//! and a tenth of the tolerance. These are consistency tests of the solver (the dense path is
//! validated against independent references in `tests/suite/dynamics.rs`).

use crate::common::*;
use flexwing::beam::{Beam, Calibration, Discretization, Profile, RotaryInertia};
use flexwing::model::{Force, FullModel, Load};
use flexwing::solve::integrate::{
    Bdf, BdfOptions, GeneralizedAlpha, GeneralizedAlphaOptions, ImplicitMidpoint, IntegratorStats,
    MidpointOptions, Radau, RadauOptions, Tolerances, Trajectory,
};
use flexwing::solve::{Damping, EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction};

/// Which integrator, with its step control.
#[derive(Clone, Copy)]
enum Method {
    /// Radau with rtol and a step cap.
    Radau(f64, f64),
    /// Radau with rtol and a step cap, relinearized at every step whatever the Newton systems
    /// (the chain path does it anyway: `NewtonSolver::cheap_linearization`).
    RadauFresh(f64, f64),
    /// BDF (order ≤ 2) with rtol.
    Bdf(f64),
    /// Fixed-step implicit midpoint.
    Midpoint(f64),
    /// Fixed-step generalized-α, `ρ∞ = 0.5`.
    Alpha(f64),
}

/// Integrate `model` under `loads` (each scaled by `10 sin(ω t)`-type functions `tf`) from rest
/// over the output times `t`, with the Newton systems `newton`; coordinate atol `20 rtol / n`
/// rad per joint (`flexwing reproduce` uses atol = rtol at n = 20; scaled with the joint's
/// share of the span so that the tolerance on the tip angle does not grow with n).
fn run(
    model: &FullModel,
    loads: &[Load],
    tf: Vec<TimeFunction>,
    t: &[f64],
    method: Method,
    newton: NewtonSystems,
) -> (Trajectory, IntegratorStats) {
    run_damped(model, loads, tf, t, method, newton, &Damping::None)
}

/// [`run`] with structural damping `damping`.
fn run_damped(
    model: &FullModel,
    loads: &[Load],
    tf: Vec<TimeFunction>,
    t: &[f64],
    method: Method,
    newton: NewtonSystems,
    damping: &Damping,
) -> (Trajectory, IntegratorStats) {
    let applied = model.apply(loads, "loads").unwrap();
    let mut eom = EquationsOfMotion::new(model, &applied, tf, Gyroscopic::Exact, damping).unwrap();
    eom.set_newton_systems(newton).unwrap();
    let n = model.n_elements();
    let y0 = vec![0.0; 2 * model.n_dofs()];
    let tolerances = |rtol: f64, eom: &mut EquationsOfMotion<'_, FullModel>| Tolerances {
        rtol,
        atol: eom.state_atol(20.0 * rtol / n as f64),
    };
    let result = match method {
        Method::Radau(rtol, max_step) => Radau {
            options: RadauOptions {
                tolerances: tolerances(rtol, &mut eom),
                max_step,
                ..Default::default()
            },
        }
        .integrate(&mut eom, 0.0, &y0, t, &mut |_| {}),
        Method::RadauFresh(rtol, max_step) => Radau {
            options: RadauOptions {
                tolerances: tolerances(rtol, &mut eom),
                max_step,
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
    let (traj, stats) = result.unwrap_or_else(|f| panic!("{newton:?}: {f}"));
    assert_eq!(traj.t.len(), t.len());
    (traj, stats)
}

/// Largest distance between the tips (and, with torsion, largest twist difference at the tip
/// times the span) of two trajectories.
fn tip_difference(model: &FullModel, a: &Trajectory, b: &Trajectory) -> f64 {
    let nd = model.n_dofs();
    let n = model.n_elements();
    let length = model.beam().length();
    a.y.iter()
        .zip(&b.y)
        .map(|(ya, yb)| {
            let (ka, kb) = (model.kinematics(&ya[..nd]), model.kinematics(&yb[..nd]));
            let (pa, pb) = (model.node_positions(&ka)[n], model.node_positions(&kb)[n]);
            let twist = (ka.psi[n - 1] - kb.psi[n - 1]).abs() * length;
            (pa[0] - pb[0]).hypot(pa[1] - pb[1]).max(twist)
        })
        .fold(0.0, f64::max)
}

fn times(end: f64, dt: f64) -> Vec<f64> {
    (0..=(end / dt).round() as usize)
        .map(|k| k as f64 * dt)
        .collect()
}

fn case_b_load() -> (Vec<Load>, Vec<TimeFunction>) {
    (
        vec![Load::PointForce {
            span: 1.0,
            force: Force::Dead { fx: 0.0, fy: 10.0 },
        }],
        vec![TimeFunction::Sine {
            omega: 20.0,
            phase: 0.0,
        }],
    )
}

#[test]
fn radau_on_case_b_gives_the_dense_paths_trajectory() {
    let (loads, tf) = case_b_load();
    // Tight tolerance at n = 40: both paths converge to the same solution, so they agree to
    // the integration error (measured 9.6e-8 m; bound 5e-7 m, rtol 1e-6).
    let model = table4(40);
    let t = times(1.0, 0.005);
    let method = Method::Radau(1e-6, f64::INFINITY);
    let (dense, _) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Dense);
    let (chain, stats) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Chain);
    let d = tip_difference(&model, &dense, &chain);
    eprintln!("n = 40, rtol 1e-6: chain − dense {d:.2e} m, {stats:?}");
    assert!(d < 5e-7, "{d:.2e}");
    // The case (b) setting of `flexwing reproduce` at n = 160: both are ~7e-5 m from the
    // converged tip (benches/dynamics.rs); they differ by much less (measured 2.7e-6 m; bound
    // 2e-5 m, a third of the integration error), and the chain's Newton iteration is exact
    // (measured 1.25 iterations per step, the dense path's 1.29; bound 2.2).
    let model = table4(160);
    let method = Method::Radau(1e-2, 6e-3);
    let (dense, dense_stats) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Dense);
    let (chain, stats) = run(&model, &loads, tf, &t, method, NewtonSystems::Chain);
    let d = tip_difference(&model, &dense, &chain);
    eprintln!("n = 160, reproduce setting: chain − dense {d:.2e} m; dense {dense_stats:?}, chain {stats:?}");
    assert!(d < 2e-5, "{d:.2e}");
    assert!(stats.newton_iterations as f64 <= 2.2 * stats.steps as f64);
    assert!(stats.steps < dense_stats.steps + 20, "{stats:?}");
}

/// The Table 1 beam (bending–torsion coupling through d0 = 0.267 m) with n = 24 (48
/// coordinates) under the tip force `100 sin(2 t)` N and the tip torque `50 sin(3 t)` N·m.
fn coupled_case() -> (FullModel, Vec<Load>, Vec<TimeFunction>) {
    let model = model(16.0, &table1_section(), 24, Calibration::TipLoad);
    let loads = vec![
        Load::PointForce {
            span: 16.0,
            force: Force::Dead { fx: 0.0, fy: 100.0 },
        },
        Load::Torque {
            span: 16.0,
            value: 50.0,
        },
    ];
    let tf = vec![
        TimeFunction::Sine {
            omega: 2.0,
            phase: 0.0,
        },
        TimeFunction::Sine {
            omega: 3.0,
            phase: 0.0,
        },
    ];
    (model, loads, tf)
}

#[test]
fn coupled_torsion_beam_gives_the_dense_paths_trajectory() {
    // The Table 1 beam (bending–torsion coupling through d0 = 0.267 m), n = 24 (48 coordinates),
    // tip force 100 sin(2 t) N and tip torque 50 sin(3 t) N·m, 2 s, Radau at rtol 1e-8 with both
    // Newton systems, and the dense path at rtol 1e-10 as reference. Measured (since the momenta's
    // tolerances follow the diagonal of M(0)⁻¹): dense 6.5e-5 m and chain 1.00e-4 m from the
    // reference (the integration error at rtol 1e-8, on a 16 m span; the chain's sits at 1.00e-4
    // to within round-off of the tolerances), 3.5e-5 m apart. Bounds: 2e-4 m from the reference
    // (twice the larger), 5e-5 m apart.
    let (model, loads, tf) = coupled_case();
    let t = times(2.0, 0.02);
    let method = Method::Radau(1e-8, f64::INFINITY);
    let (dense, _) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Dense);
    let (chain, stats) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Chain);
    let tight = Method::Radau(1e-10, f64::INFINITY);
    let (reference, _) = run(&model, &loads, tf, &t, tight, NewtonSystems::Dense);
    let d = tip_difference(&model, &dense, &chain);
    let (ed, ec) = (
        tip_difference(&model, &dense, &reference),
        tip_difference(&model, &chain, &reference),
    );
    eprintln!("Table 1 beam, n = 24: chain − dense {d:.2e} m, errors dense {ed:.2e} chain {ec:.2e}, {stats:?}");
    assert!(ed < 2e-4 && ec < 2e-4, "{ed:.2e} {ec:.2e}");
    assert!(d < 5e-5, "{d:.2e}");
}

#[test]
fn coupled_beams_newton_failures_are_the_dense_paths() {
    // The Table 1 beam's Newton failures at loose tolerances are not the chain solver's
    // (docs/model-choices.md, "The coupled beam's Newton failures"): with the Jacobian
    // relinearized at every step on both paths, Radau at rtol 1e-3 takes the same steps, and
    // fails Newton on the same ones, with the dense Jacobian's LU as with the chain sweeps.
    // Measured at n = 24 (48 coordinates), tip force 100 sin(2 t) N, tip torque 50 sin(3 t) N·m,
    // 2 s: 122 steps, 22 rejected, all 22 by Newton, on both paths; the trajectories 2.7e-7 m
    // apart (round-off of two exact solves, grown over 122 loose steps), against the run's own
    // error of 8.1e-4 m (tip) and 3.4e-2 m (tip twist times span) from rtol 1e-10. Bounds: equal
    // counts; 1e-5 m, below a hundredth of the run's error.
    let (model, loads, tf) = coupled_case();
    let t = times(2.0, 0.02);
    let method = Method::RadauFresh(1e-3, 0.02);
    let (dense, ds) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Dense);
    let (chain, cs) = run(&model, &loads, tf, &t, method, NewtonSystems::Chain);
    let d = tip_difference(&model, &dense, &chain);
    eprintln!(
        "Table 1 beam, n = 24, rtol 1e-3: chain − dense {d:.2e} m; dense {ds:?}, chain {cs:?}"
    );
    assert_eq!(
        (ds.steps, ds.rejected_steps, ds.newton_failures),
        (cs.steps, cs.rejected_steps, cs.newton_failures)
    );
    assert!(d < 1e-5, "{d:.2e}");
}

/// The Table 1 section with the offset `d0` (m) and the rotary inertia `rotary` in bending,
/// `n` elements, tip-load springs.
fn table1_with(n: usize, d0: f64, rotary: &RotaryInertia) -> FullModel {
    let mut section = table1_section();
    if let Some(t) = section.torsion.as_mut() {
        t.offset = Profile::Uniform(d0);
    }
    let beam = Beam::new(
        16.0,
        &section,
        &Discretization::Uniform(n),
        Calibration::TipLoad,
    )
    .unwrap()
    .with_rotary_inertia("beam", &section, rotary)
    .unwrap();
    FullModel::new(beam)
}

#[test]
fn coupled_beams_newton_failures_need_a_twist_independent_bending_inertia_regression() {
    // Regression test of the mechanism in docs/model-choices.md ("The coupled beam's Newton
    // failures"): an element's inertia in bending is J_b + m d0² sin²ψ, and Radau's Newton
    // iteration fails on the Table 1 beam where the twist-dependent part dominates. Rigid bars
    // give J_b = m ℓ²/12, which falls as 1/n² against m d0² ∝ ℓ: the failures remain and grow
    // with n. A section flap inertia ρI (∝ ℓ, like m d0²) of a tenth of m d0², or no offset,
    // removes them. Radau at rtol 1e-3 (coordinate atol 20 rtol / n), tip force 100 sin(2 t) N,
    // tip torque 50 sin(3 t) N·m, 2 s; measured at n = 256: bars 59 steps, 36 Newton failures;
    // bars + ρI = 0.005 kg·m (0.09 m d0²) 28 steps, 0; bars with d0 = 0 43 steps, 0; at
    // n = 1024 bars + ρI 30 steps, 0 (bars alone 99, 96). Bounds: at most 2 failures where
    // none were measured; bars alone at least 5 times as many as the two others together
    // (a change that removes the failures without ρI should update the docs and this test).
    let (_, loads, tf) = coupled_case();
    let t = times(2.0, 0.02);
    let method = Method::Radau(1e-3, f64::INFINITY);
    let bars = RotaryInertia {
        elements: true,
        section: None,
    };
    let flap = RotaryInertia {
        elements: true,
        section: Some(Profile::Uniform(0.005)),
    };
    let failures = |model: &FullModel| {
        let (_, s) = run(model, &loads, tf.clone(), &t, method, NewtonSystems::Chain);
        eprintln!("n = {}: {s:?}", model.n_elements());
        s.newton_failures
    };
    let bars_only = failures(&table1_with(256, 0.267, &bars));
    let with_flap = failures(&table1_with(256, 0.267, &flap));
    let no_offset = failures(&table1_with(256, 0.0, &bars));
    let with_flap_1024 = failures(&table1_with(1024, 0.267, &flap));
    assert!(with_flap <= 2 && no_offset <= 2 && with_flap_1024 <= 2);
    assert!(
        bars_only >= 5 * (with_flap + no_offset).max(1),
        "{bars_only} {with_flap} {no_offset}"
    );
}

#[test]
fn bdf_midpoint_and_generalized_alpha_give_the_dense_paths_trajectories() {
    // The chain path linearizes at every step, the dense one reuses its Jacobian: different
    // Newton iterates and, for BDF, slightly different steps, so the two agree to a fraction
    // of the integration error. Measured (n = 40, 0.3 s of case (b)): BDF at rtol 1e-5 1.5e-6 m
    // apart (its error is ~2e-4 m, docs/performance.md), the midpoint rule with fixed 1 ms
    // steps (same steps) 3e-10 m, generalized-α with the same steps 1.1e-8 m (the dense path
    // reuses its Jacobian and stops Newton at 0.03 of the error scale, ~5e-7 rad per joint).
    // Bounds 2e-5 m, 1e-8 m and 5e-8 m.
    let (loads, tf) = case_b_load();
    let model = table4(40);
    let t = times(0.3, 0.005);
    for (method, bound) in [
        (Method::Bdf(1e-5), 2e-5),
        (Method::Midpoint(1e-3), 1e-8),
        (Method::Alpha(1e-3), 5e-8),
    ] {
        let (dense, _) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Dense);
        let (chain, stats) = run(&model, &loads, tf.clone(), &t, method, NewtonSystems::Chain);
        let d = tip_difference(&model, &dense, &chain);
        eprintln!("chain − dense {d:.2e} m, {stats:?}");
        assert!(d < bound, "{d:.2e}");
    }
}

#[test]
fn case_b_at_n_1000_converges_with_the_step() {
    // Dense Newton systems are out of reach at n = 1000 (2000 states); the case (b) setting
    // (rtol 1e-2, steps ≤ 6 ms) against half the step and a tenth of the tolerance over the
    // first 0.3 s: measured 2.7e-5 m, within the integration error of the setting at every n
    // (benches/dynamics.rs: 6.7e-5 … 7.0e-5 m over 1 s from n = 10 to 3000); bound 1e-4 m.
    let (loads, tf) = case_b_load();
    let model = table4(1000);
    let t = times(0.3, 0.005);
    let (coarse, stats) = run(
        &model,
        &loads,
        tf.clone(),
        &t,
        Method::Radau(1e-2, 6e-3),
        NewtonSystems::Auto,
    );
    let (fine, _) = run(
        &model,
        &loads,
        tf,
        &t,
        Method::Radau(1e-3, 3e-3),
        NewtonSystems::Auto,
    );
    let d = tip_difference(&model, &coarse, &fine);
    eprintln!("n = 1000: coarse − fine {d:.2e} m, {stats:?}");
    assert!(d < 1e-4, "{d:.2e}");
    // Exact Newton: measured 1.9 iterations per step with the tighter stopping tolerance.
    assert!(
        stats.newton_iterations as f64 <= 2.5 * stats.steps as f64,
        "{stats:?}"
    );
}

#[test]
fn generalized_alpha_at_n_3000_converges_at_second_order_to_radau() {
    // Where Radau's steps start failing Newton (n ≥ 3000, docs/model-choices.md), generalized-α
    // (ρ∞ = 0.5) on the chain Newton systems: fixed steps of 1, 0.5 and 0.25 ms over the first
    // 0.3 s of case (b) against Radau at rtol 1e-7 on n = 1000 (another method; the model at
    // n = 1000 differs from n = 3000 by the O(1/n²) discretization, ~2e-8 m at the tip).
    let (loads, tf) = case_b_load();
    let t = times(0.3, 0.005);
    let small = table4(1000);
    let (reference, _) = run(
        &small,
        &loads,
        tf.clone(),
        &t,
        Method::Radau(1e-7, 1e-3),
        NewtonSystems::Auto,
    );
    let model = table4(3000);
    let mut errors = Vec::new();
    for h in [1e-3, 5e-4, 2.5e-4] {
        let (traj, stats) = run(
            &model,
            &loads,
            tf.clone(),
            &t,
            Method::Alpha(h),
            NewtonSystems::Auto,
        );
        let tips = |m: &FullModel, tr: &Trajectory| -> Vec<[f64; 2]> {
            let n = m.n_elements();
            tr.y.iter()
                .map(|y| {
                    let p = m.node_positions(&m.kinematics(&y[..m.n_dofs()]))[n];
                    [p[0], p[1]]
                })
                .collect()
        };
        let e = tips(&model, &traj)
            .iter()
            .zip(tips(&small, &reference))
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max);
        eprintln!("n = 3000, h = {h}: {e:.3e} m against Radau, {stats:?}");
        // No step fails Newton (Radau's fail from n ≈ 3000 on in the full case (b)).
        assert_eq!(stats.newton_failures, 0, "{stats:?}");
        errors.push(e);
    }
    let orders: Vec<f64> = errors.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("observed orders {orders:?}");
    // Second order (measured above); bounds leave room for the O(h³) terms at 1 ms.
    assert!(orders.iter().all(|o| (1.7..2.4).contains(o)), "{orders:?}");
}

#[test]
fn rayleigh_damped_case_b_at_n_2000_converges_with_the_step() {
    // Rayleigh damping at n = 2000, which the dense damping matrix (formed once, then an O(n²)
    // product at every right-hand side) made a matter of minutes (328 s for case (b) at n = 3000,
    // docs/performance.md, "Damping at large n"): the case (b) setting against half the step and
    // a tenth of the tolerance over the first 0.2 s. α = 5 /s, β = 1e-3 s: ζ₁ = 0.073 on the first
    // mode, so the damping changes the tip by far more than the bound (checked against the
    // undamped run). Measured coarse − fine 5.4e-7 m (the damped high modes leave less to
    // integrate than case (b) undamped, 2.7e-5 m at n = 1000 above); bound 1e-5 m. Three runs,
    // 1 s in release mode.
    let (loads, tf) = case_b_load();
    let model = table4(2000);
    let t = times(0.2, 0.005);
    let damping = Damping::Rayleigh {
        alpha: 5.0,
        beta: 1e-3,
    };
    let go = |method, damping: &Damping| {
        run_damped(
            &model,
            &loads,
            tf.clone(),
            &t,
            method,
            NewtonSystems::Auto,
            damping,
        )
    };
    let (coarse, stats) = go(Method::Radau(1e-2, 6e-3), &damping);
    let (fine, _) = go(Method::Radau(1e-3, 3e-3), &damping);
    let (undamped, _) = go(Method::Radau(1e-2, 6e-3), &Damping::None);
    let d = tip_difference(&model, &coarse, &fine);
    let effect = tip_difference(&model, &coarse, &undamped);
    eprintln!(
        "n = 2000, Rayleigh: coarse − fine {d:.2e} m, damped − undamped {effect:.2e} m, {stats:?}"
    );
    assert!(d < 1e-5, "{d:.2e}");
    // The damping's effect: measured 1.6e-2 m; at least a hundred times the bound.
    assert!(effect > 1e-3, "{effect:.2e}");
}

#[test]
fn auto_takes_the_newton_systems_measured_faster_for_the_method() {
    // `NewtonSystems::Auto` under `integrate()`: the crossovers of `chain_newton_min_dofs`
    // (measured, docs/performance.md): Radau without a step cap on the chain from 16
    // coordinates, fixed steps dense below 120, the rest from 40. Checked after a short run
    // (10 ms of case (b)) of each, by the resolved choice.
    use flexwing::solve::integrate::{integrate, IntegratorSettings, Method as M};
    let (loads, tf) = case_b_load();
    let uses_chain = |n: usize, method: M, settings: IntegratorSettings| {
        let model = table4(n);
        let applied = model.apply(&loads, "loads").unwrap();
        let mut eom = EquationsOfMotion::new(
            &model,
            &applied,
            tf.clone(),
            Gyroscopic::Exact,
            &Damping::None,
        )
        .unwrap();
        let y0 = vec![0.0; 2 * n];
        integrate(
            method,
            &settings,
            &mut eom,
            0.0,
            &y0,
            &[0.0, 0.01],
            &mut |_| {},
        )
        .unwrap();
        eom.uses_chain_newton()
    };
    let adaptive = IntegratorSettings::default();
    let capped = IntegratorSettings {
        max_step: Some(6e-3),
        ..Default::default()
    };
    let fixed = IntegratorSettings {
        step: Some(1e-3),
        ..Default::default()
    };
    assert!(!uses_chain(10, M::Radau, adaptive.clone()));
    assert!(uses_chain(16, M::Radau, adaptive.clone()));
    assert!(!uses_chain(24, M::Radau, capped.clone()));
    assert!(uses_chain(40, M::Radau, capped));
    assert!(!uses_chain(24, M::Bdf, adaptive.clone()));
    assert!(uses_chain(40, M::Bdf, adaptive.clone()));
    assert!(uses_chain(40, M::GeneralizedAlpha, adaptive));
    assert!(!uses_chain(80, M::GeneralizedAlpha, fixed.clone()));
    assert!(!uses_chain(80, M::Midpoint, fixed.clone()));
    assert!(uses_chain(120, M::GeneralizedAlpha, fixed));
}
