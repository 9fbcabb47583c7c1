//! The linear state-space model of the 3-D chain (`solve::aeroelastic::linearize` on
//! `Aeroelastic<Chain3d>`, docs/control.md) against what it must agree with:
//!
//! * the planar limit: the straight, untwisted Patil wing at a root angle (in-plane loads,
//!   `d0 = 0`, point masses, tip-load calibration) has the planar chain's poles — the lag
//!   branches apart — and the planar outputs' transfer functions, to round-off (a consistency
//!   test between two codes of one theory; the planar model is validated in `aero_linearize.rs`);
//! * central differences of the non-linear 3-D model (its right-hand side and outputs) for `B`,
//!   `C`, `D` at a bent equilibrium (24 N at the tip, a root angle, gravity), Peters' inflow;
//! * the flutter analysis' eigenvalues about the same equilibrium (`flutter`: Newton on the
//!   rational eigenproblem with the lag states eliminated). The two share the structured
//!   dual-number derivatives of the strips (`solve/aeroelastic/evaluator.rs`), not their
//!   assembly: a consistency check, not an independent reference.

use crate::common;
use crate::common::chain3d::patil_wing_3d;
use flexwing::beam::Profile;
use flexwing::model::aero::{Aerodynamics, Aeroelastic, FlightCondition};
use flexwing::model::chain3d::{ElementInertia, JointCalibration};
use flexwing::model::{Chain3d, Force, Load};
use flexwing::solve::aeroelastic::{
    flutter, linearize, poles as poles_of, AeroelasticEquations, FlightHistory, FlutterOptions,
    Gust, GustPenetration, GustShape, Input, LinearizeOptions, Output, StateBasis, StateSpace,
};
use flexwing::solve::integrate::OdeSystem;
use flexwing::solve::{Damping, StaticOptions, TimeFunction};
use nalgebra::{Complex, DMatrix};

type C64 = Complex<f64>;

fn options(
    flight: FlightCondition,
    loads: Vec<Load>,
    inputs: Vec<Input>,
    outputs: Vec<Output>,
) -> LinearizeOptions {
    LinearizeOptions {
        flight,
        loads,
        damping: Damping::None,
        static_options: StaticOptions::default(),
        inputs,
        outputs,
        basis: StateBasis::Velocities,
        mode_numbers: None,
    }
}

fn nearest(set: &[C64], s: C64) -> f64 {
    set.iter()
        .map(|e| (e - s).norm())
        .fold(f64::INFINITY, f64::min)
}

/// `G(iω) = C (iωI − A)⁻¹ B + D`.
fn transfer(ss: &StateSpace, omega: f64) -> DMatrix<C64> {
    let dim = ss.a.nrows();
    let m = DMatrix::<C64>::identity(dim, dim) * C64::new(0.0, omega) - ss.a.map(C64::from);
    let x = m
        .lu()
        .solve(&ss.b.map(C64::from))
        .expect("iω is not a pole");
    ss.c.map(C64::from) * x + ss.d.map(C64::from)
}

/// The planar limit at 20 m/s about the undeformed wing (n = 8, Wagner; no root angle, no
/// gravity: a bent and twisted 3-D chain is not the planar one, whose twist joints turn about
/// the span rather than the bent element's axis, docs/chain3d-model.md): every pole of the planar model is a pole of the 3-D one (measured
/// 2.3e-11 of |s|; bound 1e-9, dense eigenvalues of non-normal matrices of order 48 and 64;
/// the 3-D model's 16 others are its lag joints', not compared), and
/// the transfer functions of every planar output from the root angle, the gust and a tip force
/// agree at ω = 0.5, 3, 20 rad/s (measured ≤ 3.4e-12 of the largest entry; bound 1e-9).
#[test]
fn the_planar_limit_has_the_planar_model() {
    let n = 8;
    let am = Aerodynamics::Wagner;
    let planar = common::patil_wing(n, am);
    let spatial = patil_wing_3d(n, am, ElementInertia::Point, JointCalibration::TipLoad);
    let flight = FlightCondition {
        speed: 20.0,
        root_angle: 0.0,
        gravity: None,
    };
    let inputs = vec![Input::RootAngle, Input::Gust, Input::Force(n)];
    let outputs = vec![
        Output::TipY,
        Output::TipTwist,
        Output::Y(4),
        Output::RootBendingMoment,
        Output::RootTorque,
        Output::Lift,
        Output::TipAcceleration,
    ];
    let o = options(flight, vec![], inputs, outputs);
    let p = linearize(&planar, &o, "linearize").unwrap();
    let s = linearize(&spatial, &o, "linearize").unwrap();
    assert_eq!(
        (p.a.nrows(), s.a.nrows()),
        (2 * 2 * n + 2 * n, 2 * 3 * n + 2 * n)
    );
    let pp = poles_of(&p.a).unwrap();
    let sp = poles_of(&s.a).unwrap();
    let worst = pp
        .iter()
        .map(|e| nearest(&sp, *e) / e.norm().max(1.0))
        .fold(0.0, f64::max);
    println!("planar poles among the 3-D ones within {worst:.1e} relative");
    assert!(worst < 1e-9, "{worst:e}");
    for omega in [0.5, 3.0, 20.0] {
        let (gp, gs) = (transfer(&p, omega), transfer(&s, omega));
        let scale = gp.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let diff = (&gp - &gs).iter().map(|v| v.norm()).fold(0.0, f64::max);
        println!(
            "ω = {omega}: transfer functions differ by {:.1e} of the largest",
            diff / scale
        );
        assert!(diff < 1e-9 * scale, "ω = {omega}: {diff:e} of {scale:e}");
    }
    // The equilibrium's outputs are the planar ones too.
    for (a, b) in p.output_values.iter().zip(&s.output_values) {
        assert!((a - b).abs() < 1e-9 * (1.0 + a.abs()), "{a} vs {b}");
    }
}

/// The bent wing of the next tests: n = 6, Peters 3 states, 24 N up at the tip, gravity, a root
/// angle of 0.02 rad, 18 m/s; bars and the compliance calibration (the 3-D defaults).
fn bent() -> (Aeroelastic<Chain3d>, LinearizeOptions) {
    let n = 6;
    let wing = patil_wing_3d(
        n,
        Aerodynamics::Peters { states: 3 },
        ElementInertia::Bar,
        JointCalibration::Compliance,
    );
    let loads = vec![Load::PointForce {
        span: 16.0,
        force: Force::Dead { fx: 0.0, fy: 24.0 },
    }];
    let flight = FlightCondition {
        speed: 18.0,
        root_angle: 0.02,
        gravity: Some(9.81),
    };
    let inputs = vec![
        Input::RootAngle,
        Input::Speed,
        Input::Gust,
        Input::StripGust(3),
        Input::GustRate,
        Input::Force(n),
        Input::Torque(4),
    ];
    let outputs = vec![
        Output::TipY,
        Output::TipZ,
        Output::Z(3),
        Output::TipTwist,
        Output::Twist(2),
        Output::RootBendingMoment,
        Output::RootLagMoment,
        Output::RootTorque,
        Output::Lift,
    ];
    let mut o = options(flight, loads, inputs, outputs);
    o.basis = StateBasis::Momenta;
    (wing, o)
}

/// The right-hand side (momentum basis) and the outputs of the non-linear 3-D model at state
/// `y`, input `j` changed by `h`.
fn nonlinear(
    aero: &Aeroelastic<Chain3d>,
    o: &LinearizeOptions,
    y: &[f64],
    change: Option<(usize, f64)>,
) -> (Vec<f64>, Vec<f64>) {
    let mut loads = o.loads.clone();
    let mut flight = FlightHistory::steady(o.flight);
    let nodes = aero.chain().nodes().to_vec();
    let stations = aero.strip_stations();
    if let Some((j, h)) = change {
        let gust = |spanwise: Profile, shape: GustShape| Gust {
            shape,
            amplitude: h,
            start: 0.0,
            spanwise,
            penetration: GustPenetration::Uniform,
        };
        match &o.inputs[j] {
            Input::RootAngle => flight.initial.root_angle += h,
            Input::Speed => flight.initial.speed += h,
            Input::Gust => flight.gust = Some(gust(Profile::Uniform(1.0), GustShape::SharpEdged)),
            Input::StripGust(k) => {
                let value = (1..=stations.len())
                    .map(|i| if i == *k { 1.0 } else { 0.0 })
                    .collect();
                flight.gust = Some(gust(
                    Profile::Table {
                        x: stations.clone(),
                        value,
                    },
                    GustShape::SharpEdged,
                ));
            }
            // h sin t: no gust at t = 0, its rate h (the apparent mass only).
            Input::GustRate => {
                flight.gust = Some(gust(
                    Profile::Uniform(1.0),
                    GustShape::History(TimeFunction::Sine {
                        omega: 1.0,
                        phase: 0.0,
                    }),
                ))
            }
            Input::Force(k) => loads.push(Load::PointForce {
                span: nodes[*k],
                force: Force::Dead { fx: 0.0, fy: h },
            }),
            Input::Torque(k) => loads.push(Load::Torque {
                span: nodes[*k],
                value: h,
            }),
            other => panic!("{other:?} is not perturbed here"),
        }
    }
    let applied = aero.apply(&loads, "loads").unwrap();
    let mut eqs = AeroelasticEquations::new(
        aero,
        &applied,
        vec![TimeFunction::Constant; loads.len()],
        flight,
        &o.damping,
        "f",
    )
    .unwrap();
    let mut dy = vec![0.0; eqs.dim()];
    eqs.rhs(0.0, y, &mut dy);
    let chain = aero.structure();
    let n = chain.n_dofs();
    let x = &y[..n];
    let p = chain.node_positions(x);
    let ne = chain.n_elements();
    let pitch = |e: usize| {
        let r = chain.shape(x).frames[e];
        (-r[2][1]).atan2(r[2][2])
    };
    let k = &chain.beam().joint_stiffness()[0];
    let spring = |axis: usize| (0..3).map(|c| k[axis][c] * x[c]).sum::<f64>();
    let lift = eqs.vertical_aerodynamic_force_at(0.0, y);
    let values = o
        .outputs
        .iter()
        .map(|out| match out {
            Output::TipY => p[ne][1],
            Output::TipZ => p[ne][2],
            Output::Z(k) => p[*k][2],
            Output::TipTwist => pitch(ne - 1),
            Output::Twist(k) => pitch(k - 1),
            Output::RootBendingMoment => spring(2),
            Output::RootLagMoment => spring(1),
            Output::RootTorque => -spring(0),
            Output::Lift => lift,
            other => panic!("{other:?} is not evaluated here"),
        })
        .collect();
    (dy, values)
}

/// `B`, `C`, `D` of the bent wing against central differences of the non-linear model
/// (momentum basis: the integrators' own state). Step 1e-6 (truncation ~1e-12, round-off
/// ~1e-10 of the largest entry); tolerance 1e-6 of each column's largest entry, as the planar
/// model's test (`solve/aeroelastic/linearize_tests.rs`). The bent equilibrium couples lag with
/// flap and twist: the lag outputs' rows are not zero (checked). Measured: 1.8e-8 of a
/// column's largest entry at worst.
#[test]
fn b_c_d_of_the_bent_wing_agree_with_finite_differences() {
    let (wing, o) = bent();
    let ss = linearize(&wing, &o, "linearize").unwrap();
    let y0 = ss.state_values.clone();
    let (f0, g0) = nonlinear(&wing, &o, &y0, None);
    let scale = f0.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
    assert!(
        f0.iter().all(|v| v.abs() < 1e-7 * scale.max(1e3)),
        "not an equilibrium: {f0:?}"
    );
    for (r, (g, v)) in g0.iter().zip(&ss.output_values).enumerate() {
        assert!(
            (g - v).abs() <= 1e-7 * (1.0 + g.abs()),
            "{}: {g} vs {v}",
            o.outputs[r].name()
        );
    }
    let h = 1e-6;
    let output_scale: Vec<f64> = g0.iter().map(|v| v.abs()).collect();
    let state_zero = vec![0.0; y0.len()];
    // Each entry within 1e-6 of its column's largest plus the round-off of the difference
    // quotient, 10 ε |value| / h, with the value's scale per row (`floor`: the outputs' values
    // for C and D; for B the right-hand side is zero at the equilibrium and the floor is zero).
    let compare = |what: &str, fd: &[f64], exact: &[f64], floor: &[f64]| {
        let m = exact.iter().chain(fd).fold(0.0_f64, |m, v| m.max(v.abs()));
        let worst = fd
            .iter()
            .zip(exact)
            .zip(floor)
            .map(|((a, b), f)| ((a - b).abs() - 10.0 * f64::EPSILON * f / h).max(0.0))
            .fold(0.0, f64::max);
        assert!(
            worst <= 1e-6 * m + 1e-12,
            "{what}: finite differences differ by {worst:e} of {m:e}"
        );
        worst / m.max(1e-300)
    };
    let diff = |p: &[f64], m: &[f64]| -> Vec<f64> {
        p.iter().zip(m).map(|(a, b)| (a - b) / (2.0 * h)).collect()
    };
    let mut worst: f64 = 0.0;
    for j in 0..o.inputs.len() {
        let (fp, gp) = nonlinear(&wing, &o, &y0, Some((j, h)));
        let (fm, gm) = nonlinear(&wing, &o, &y0, Some((j, -h)));
        let name = o.inputs[j].name();
        worst = worst.max(compare(
            &format!("B[:, {name}]"),
            &diff(&fp, &fm),
            ss.b.column(j).as_slice(),
            &state_zero,
        ));
        worst = worst.max(compare(
            &format!("D[:, {name}]"),
            &diff(&gp, &gm),
            ss.d.column(j).as_slice(),
            &output_scale,
        ));
    }
    for c in 0..y0.len() {
        let (mut yp, mut ym) = (y0.clone(), y0.clone());
        yp[c] += h;
        ym[c] -= h;
        let (_, gp) = nonlinear(&wing, &o, &yp, None);
        let (_, gm) = nonlinear(&wing, &o, &ym, None);
        worst = worst.max(compare(
            &format!("C[:, {c}]"),
            &diff(&gp, &gm),
            ss.c.column(c).as_slice(),
            &output_scale,
        ));
    }
    println!("B, C, D against central differences: worst {worst:.1e} of a column's largest entry");
    // Lag responds to flap and twist on the bent wing.
    for out in [1, 6] {
        let row = ss.c.row(out);
        assert!(
            row.iter().any(|v| v.abs() > 1e-6),
            "{}: row is zero",
            o.outputs[out].name()
        );
    }
}

/// The poles of the bent wing's linear model are the flutter analysis' eigenvalues at the same
/// speed (every tracked branch: measured ≤ 4.6e-13 relative; bound 1e-9, as the planar test), in
/// both bases.
#[test]
fn poles_of_the_bent_wing_are_the_flutter_eigenvalues() {
    let (wing, mut o) = bent();
    let speed = o.flight.speed;
    let mut plan = FlutterOptions::new(vec![6.0, 12.0, speed], 6);
    plan.root_angle = o.flight.root_angle;
    plan.gravity = o.flight.gravity;
    plan.loads = o.loads.clone();
    let out = flutter(&wing, &plan, "flutter", &mut |_| {}).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    for basis in [StateBasis::Velocities, StateBasis::Momenta] {
        o.basis = basis;
        let ss = linearize(&wing, &o, "linearize").unwrap();
        // Balanced (Parlett–Reinsch) before the dense eigenvalues: the momenta basis of a wing
        // with EI_lag = 200 EI_flap is ill-scaled (unbalanced: 4.6e-8, 2026-12-03).
        let poles = poles_of(&ss.a).expect("the Schur form converges");
        for b in &out.branches {
            let s = b.eigenvalues[2];
            let d = nearest(&poles, s);
            println!(
                "{basis:?} mode {}: s = {s:.6}, nearest pole {:.1e}",
                b.mode,
                d / s.norm()
            );
            assert!(d < 1e-9 * s.norm(), "{s}: nearest pole {d:e}");
        }
    }
}
