//! Consistency of the linear model with the non-linear equations it linearizes: `B`, `C` and `D`
//! against central differences of the non-linear right-hand side and outputs with the inputs
//! changed where the non-linear model takes them (the flight history, the loads); the vertical
//! momentum of the root shear against differences of positions in time; the two bases'
//! transfer functions. The wing carries two control surfaces (one covering parts of its end
//! strips), deflected at the equilibrium, so that the surfaces' inputs and hinge moments are
//! checked with the others.

use nalgebra::{Complex, DMatrix, DVector};

use super::super::equations::tests::{test_wing, test_wing_with};
use super::super::evaluator::AeroEvaluator;
use super::super::flight::{FlightHistory, Gust, GustPenetration, GustShape};
use super::*;
use crate::beam::Profile;
use crate::model::aero::{ControlSurface, PlanarStructure};
use crate::model::ReducedModel;

/// The two surfaces of the test wing (3 m, 5 elements of 0.6 m): a flap over 0.4–1.7 m (a
/// third of element 1 and all but a sixth of element 3), an aileron over 1.8–3 m with a hinge
/// table; both deflected.
fn surfaces() -> Vec<ControlSurface> {
    let mut flap = ControlSurface::new("flap", 0.4, 1.7, 0.75);
    flap.deflection = 0.04;
    let mut aileron = ControlSurface::new("aileron", 1.8, 3.0, 0.8);
    aileron.hinge = Profile::Table {
        x: vec![0.0, 3.0],
        value: vec![0.7, 0.8],
    };
    aileron.deflection = -0.02;
    vec![flap, aileron]
}

fn surface(index: usize) -> super::super::signals::Surface {
    super::super::signals::Surface {
        index,
        name: surfaces()[index].name.clone(),
    }
}

fn flapped_wing(n: usize, aerodynamics: Aerodynamics) -> Aeroelastic {
    test_wing_with(n, aerodynamics, surfaces())
}

fn inputs() -> Vec<Input> {
    vec![
        Input::Deflection(surface(0)),
        Input::DeflectionRate(surface(0)),
        Input::DeflectionAcceleration(surface(1)),
        Input::Deflection(surface(1)),
        Input::RootAngle,
        Input::Speed,
        Input::Gust,
        Input::StripGust(2),
        Input::GustRate,
        Input::Force(3),
        Input::Torque(2),
    ]
}

fn outputs(n: usize) -> Vec<Output> {
    vec![
        Output::TipX,
        Output::TipY,
        Output::TipTwist,
        Output::Y(2),
        Output::Twist(3),
        Output::RootBendingMoment,
        Output::RootTorque,
        Output::Lift,
        Output::RootShear,
        Output::TipAcceleration,
        Output::Acceleration(n - 1),
        Output::HingeMoment(surface(0)),
        Output::HingeMoment(surface(1)),
    ]
}

fn options(basis: StateBasis, n: usize) -> LinearizeOptions {
    LinearizeOptions {
        flight: FlightCondition {
            speed: 12.0,
            root_angle: 0.05,
            gravity: Some(9.81),
        },
        loads: vec![Load::PointForce {
            span: 3.0,
            force: Force::Dead { fx: 0.5, fy: -2.0 },
        }],
        damping: Damping::Rayleigh {
            alpha: 0.1,
            beta: 1e-3,
        },
        static_options: StaticOptions::default(),
        inputs: inputs(),
        outputs: outputs(n),
        basis,
        mode_numbers: None,
    }
}

/// The non-linear model with input `j` changed by `h`: its equations' loads and flight. A
/// deflection's acceleration cannot be changed alone by a time history: it is `δ = δ₀ + h cos ωt`
/// (at t = 0 the change `h`, no rate, the acceleration `−ω² h`), `omega` its `ω`.
struct Perturbed {
    loads: Vec<Load>,
    flight: FlightHistory,
}

fn perturbed<M: PlanarStructure>(
    aero: &Aeroelastic<M>,
    o: &LinearizeOptions,
    (j, h, omega): (usize, f64, f64),
) -> Perturbed {
    let mut loads = o.loads.clone();
    let mut flight = FlightHistory::steady(o.flight);
    let nodes = aero.full().beam().nodes().to_vec();
    let stations = aero.strip_stations();
    let gust = |spanwise: Profile| Gust {
        shape: GustShape::SharpEdged,
        amplitude: h,
        start: 0.0,
        spanwise,
        penetration: GustPenetration::Uniform,
    };
    fn deflect(
        flight: &mut FlightHistory,
        s: &super::super::signals::Surface,
        h: f64,
        f: TimeFunction,
    ) {
        flight.deflection_changes.resize(s.index + 1, None);
        flight.deflection_changes[s.index] = Some((h, f));
    }
    match &o.inputs[j] {
        Input::Deflection(s) => deflect(&mut flight, s, h, TimeFunction::Constant),
        // h sin t: no change at t = 0, the rate h.
        Input::DeflectionRate(s) => deflect(
            &mut flight,
            s,
            h,
            TimeFunction::Sine {
                omega: 1.0,
                phase: 0.0,
            },
        ),
        Input::DeflectionAcceleration(s) => deflect(
            &mut flight,
            s,
            h,
            TimeFunction::Sine {
                omega,
                phase: 0.5 * std::f64::consts::PI,
            },
        ),
        Input::RootAngle => flight.initial.root_angle += h,
        Input::Speed => flight.initial.speed += h,
        Input::Gust => flight.gust = Some(gust(Profile::Uniform(1.0))),
        Input::StripGust(k) => {
            // 1 at the strip of element k, 0 at every other strip.
            let value = (1..=stations.len())
                .map(|i| if i == *k { 1.0 } else { 0.0 })
                .collect();
            flight.gust = Some(gust(Profile::Table {
                x: stations.clone(),
                value,
            }));
        }
        // A gust h sin t: zero at t = 0, its rate h there (the gust's apparent mass only).
        Input::GustRate => {
            flight.gust = Some(Gust {
                shape: GustShape::History(TimeFunction::Sine {
                    omega: 1.0,
                    phase: 0.0,
                }),
                ..gust(Profile::Uniform(1.0))
            })
        }
        Input::Force(k) => loads.push(Load::PointForce {
            span: nodes[*k],
            force: Force::Dead { fx: 0.0, fy: h },
        }),
        Input::Torque(k) => loads.push(Load::Torque {
            span: nodes[*k],
            value: h,
        }),
    }
    Perturbed { loads, flight }
}

/// The right-hand side and the outputs of the non-linear model at state `y` (momentum basis)
/// with input `j` changed by `h` (`None`: no change; `ω` as [`perturbed`]).
fn nonlinear<M: PlanarStructure>(
    aero: &Aeroelastic<M>,
    o: &LinearizeOptions,
    y: &[f64],
    input: Option<(usize, f64, f64)>,
) -> (Vec<f64>, Vec<f64>) {
    let p = match input {
        Some(change) => perturbed(aero, o, change),
        None => Perturbed {
            loads: o.loads.clone(),
            flight: FlightHistory::steady(o.flight),
        },
    };
    let applied = aero.full().apply(&p.loads, "loads").unwrap();
    let mut eqs = AeroelasticEquations::new(
        aero,
        &applied,
        vec![TimeFunction::Constant; p.loads.len()],
        p.flight.clone(),
        &o.damping,
        "f",
    )
    .unwrap();
    let n = eqs.n_dofs();
    let mut dy = vec![0.0; eqs.dim()];
    eqs.rhs(0.0, y, &mut dy);
    let structure = aero.structure();
    let x = &y[..n];
    let mut ws = structure.workspace();
    let mut mass = DMatrix::zeros(n, n);
    structure.mass_matrix_into(x, &mut ws, &mut mass);
    let chol = mass.cholesky().unwrap();
    let xdot = chol.solve(&DVector::from_column_slice(&y[n..2 * n]));
    let xddot = chol.solve(&DVector::from_column_slice(&dy[n..2 * n]));
    let full = aero.full();
    let q = structure.full_coordinates(x);
    let kin = full.kinematics(&q);
    let shape = full.shape(&q);
    let ne = full.n_elements();
    let mut hinges = Vec::new();
    let mut lift_of = |wy: f64, wz: f64| {
        let mut ev = AeroEvaluator::new(aero);
        let mut deflections = aero.rest_deflections();
        p.flight.add_deflection_changes(0.0, &mut deflections);
        ev.set_deflections(&deflections);
        let flight = &p.flight;
        // The gust and its rate (its apparent mass, uniform penetration) at every strip.
        let gust: Vec<f64> = aero
            .strips
            .iter()
            .map(|s| flight.gust(s.station, 0.0))
            .collect();
        let rate: Vec<f64> = aero
            .strips
            .iter()
            .map(|s| {
                flight.gust.as_ref().map_or(0.0, |g| {
                    g.amplitude * g.spanwise.at(s.station) * g.rate(0.0, flight.initial.speed)
                })
            })
            .collect();
        let lagged = vec![0.0; aero.n_strips()];
        ev.set_air_with_gust(
            flight.speed(0.0),
            flight.root_angle(0.0),
            (&gust, &rate, &lagged),
        );
        let mut f = vec![0.0; n];
        let mut adot = vec![0.0; aero.n_aero_states()];
        ev.evaluate(x, xdot.as_slice(), &y[2 * n..], &mut f, false, &mut adot);
        hinges = ev.hinge_moments();
        ev.sc
            .force
            .iter()
            .zip(&aero.strips)
            .map(|(f, s)| s.width * (wy * f[1] + wz * f[2]))
            .sum::<f64>()
    };
    let accel = |k: usize| {
        let j = full.point_jacobian(&kin, full.beam().nodes()[k]);
        let jr = project(aero, &j.row(1).iter().copied().collect::<Vec<f64>>());
        jr.dot(&xddot)
    };
    let alpha = p.flight.root_angle(0.0);
    let lift = lift_of(alpha.cos(), alpha.sin());
    let lift_y = lift_of(1.0, 0.0);
    let values = o
        .outputs
        .iter()
        .map(|out| match out {
            Output::TipX => shape.x[ne],
            Output::TipY => shape.y[ne],
            Output::TipTwist => shape.twist[ne],
            Output::X(k) => shape.x[*k],
            Output::Y(k) => shape.y[*k],
            Output::Twist(k) => shape.twist[*k],
            Output::RootBendingMoment => full.stiffness()[0] * q[0],
            Output::RootTorque => full.stiffness()[ne] * q[ne],
            Output::Lift => lift,
            Output::HingeMoment(s) => hinges[s.index],
            Output::TipAcceleration => accel(ne),
            Output::Acceleration(k) => accel(*k),
            Output::TipZ | Output::Z(_) | Output::RootLagMoment => {
                unreachable!("the 3-D chain's outputs: tests/suite/aero3d_linearize.rs")
            }
            Output::RootShear => {
                // External vertical forces less the rate of the vertical momentum: the
                // momentum's own change with x multiplies ẍ = 0 at the equilibrium.
                let total: f64 = full.beam().masses().iter().sum();
                let gravity = -9.81 * alpha.cos() * total;
                let applied: f64 = p
                    .loads
                    .iter()
                    .map(|l| match l {
                        Load::PointForce {
                            force: Force::Dead { fy, .. },
                            ..
                        } => *fy,
                        _ => 0.0,
                    })
                    .sum();
                let lp = momentum_row(aero, x);
                lift_y + gravity + applied - lp.dot(&xddot)
            }
        })
        .collect();
    (dy, values)
}

/// `∂P_y/∂ẋ` (model coordinates) from `Point::shear_parts`.
fn momentum_row<M: PlanarStructure>(aero: &Aeroelastic<M>, x: &[f64]) -> DVector<f64> {
    let flight = FlightCondition::at_speed(1.0);
    let n = aero.structure().n_dofs();
    let a = vec![0.0; aero.n_aero_states()];
    let point = Point::new(aero, x, &a, &flight);
    let q = aero.structure().full_coordinates(x);
    let (m, _, _) = point.shear_parts(&q, &[]);
    let r = project(aero, m.as_slice());
    assert_eq!(r.len(), n);
    r
}

/// Central differences of the non-linear model against `B`, `C`, `D` (momentum basis), for
/// every aerodynamic model, full and reduced, at a deformed equilibrium with a root angle,
/// gravity, a dead load and damping. Step 1e-6 (truncation ~1e-12, round-off ~1e-10 of the
/// largest entry); tolerance 1e-6 of each column's largest entry, as the Jacobian's test.
#[test]
fn b_c_d_agree_with_finite_differences() {
    for am in [
        Aerodynamics::Steady,
        Aerodynamics::QuasiSteady,
        Aerodynamics::Wagner,
        Aerodynamics::Peters { states: 3 },
    ] {
        let wing = flapped_wing(5, am);
        check(&wing);
        check(&wing.reduced(&[0, 1, 2, 3]).unwrap());
    }
}

fn check<M: PlanarStructure>(aero: &Aeroelastic<M>) {
    let o = options(StateBasis::Momenta, aero.n_strips());
    let ss = linearize(aero, &o, "linearize").unwrap();
    let y0 = ss.state_values.clone();
    let dim = y0.len();
    let h = 1e-6;
    let (f0, g0) = nonlinear(aero, &o, &y0, None);
    // The equilibrium: rates vanish (the lag states steady), outputs as reported.
    let scale = f0.iter().fold(1.0_f64, |m, v| m.max(v.abs()));
    assert!(f0.iter().all(|v| v.abs() < 1e-7 * scale.max(1e3)), "{f0:?}");
    // The equilibrium's residual is the static solver's (tolerance 1e-10 relative): the
    // accelerations are zero to ~1e-8 (measured 3.6e-9 m/s²).
    for (r, (g, v)) in g0.iter().zip(&ss.output_values).enumerate() {
        assert!(
            (g - v).abs() <= 1e-7 * (1.0 + g.abs()),
            "{}: {g} vs {v}",
            o.outputs[r].name()
        );
    }
    let compare = |what: &str, fd: &[f64], exact: &[f64]| {
        let m = exact.iter().chain(fd).fold(0.0_f64, |m, v| m.max(v.abs()));
        for (k, (a, b)) in fd.iter().zip(exact).enumerate() {
            assert!(
                (a - b).abs() <= 1e-6 * m + 1e-12,
                "{:?} {what} [{k}]: finite differences {a}, exact {b}",
                aero.aerodynamics()
            );
        }
    };
    let central = |j: usize, omega: f64, h: f64| {
        let (fp, gp) = nonlinear(aero, &o, &y0, Some((j, h, omega)));
        let (fm, gm) = nonlinear(aero, &o, &y0, Some((j, -h, omega)));
        let diff = |p: &[f64], m: &[f64]| -> Vec<f64> {
            p.iter().zip(m).map(|(a, b)| (a - b) / (2.0 * h)).collect()
        };
        (diff(&fp, &fm), diff(&gp, &gm))
    };
    for j in 0..o.inputs.len() {
        let (db, dd) = match o.inputs[j] {
            // `h cos ωt` changes by `B_δ − ω² B_δ̈` per unit h: ω = 1 and 2 give `B_δ̈`. The
            // flap's apparent mass is small (its column ~1e-3 of the others): step 1e-4 keeps
            // the round-off (~1e-16 |f|/h) below the bound; the truncation, O(h²) through the
            // lift's atan2 of the deflection's upwash, is ~1e-8 relative.
            Input::DeflectionAcceleration(_) => {
                let ((b1, d1), (b2, d2)) = (central(j, 1.0, 1e-4), central(j, 2.0, 1e-4));
                let third = |a: &[f64], b: &[f64]| -> Vec<f64> {
                    a.iter().zip(b).map(|(x, y)| (x - y) / 3.0).collect()
                };
                (third(&b1, &b2), third(&d1, &d2))
            }
            _ => central(j, 0.0, h),
        };
        let name = o.inputs[j].name();
        compare(&format!("B[:, {name}]"), &db, ss.b.column(j).as_slice());
        compare(&format!("D[:, {name}]"), &dd, ss.d.column(j).as_slice());
    }
    for c in 0..dim {
        let (mut yp, mut ym) = (y0.clone(), y0.clone());
        yp[c] += h;
        ym[c] -= h;
        let (_, gp) = nonlinear(aero, &o, &yp, None);
        let (_, gm) = nonlinear(aero, &o, &ym, None);
        let dc: Vec<f64> = gp
            .iter()
            .zip(&gm)
            .map(|(a, b)| (a - b) / (2.0 * h))
            .collect();
        compare(&format!("C[:, {c}]"), &dc, ss.c.column(c).as_slice());
    }
}

/// The vertical momentum row of the root shear against differences in time of the positions
/// it comes from: the mass centres and the fluid's mid-chord points (`FullModel::mass_centres`,
/// `point_position`), `P_y = Σ m_i ġ_i,y + Σ m_a,i ν_y,i (ν_i · Ẋ_m,i)`. Step 1e-6 in time;
/// measured agreement ~1e-10 relative; bound 1e-7.
#[test]
fn the_vertical_momentum_is_that_of_the_positions() {
    let wing = test_wing(5, Aerodynamics::Wagner);
    let full = wing.full();
    let nf = full.n_dofs();
    let ne = full.n_elements();
    let x: Vec<f64> = (0..nf).map(|i| 0.1 * (1.0 + i as f64).sin()).collect();
    let v: Vec<f64> = (0..nf).map(|i| 0.5 * (2.0 * i as f64).cos()).collect();
    let row = momentum_row(&wing, &x);
    let exact = row.dot(&DVector::from_column_slice(&v));
    let h = 1e-6;
    let at = |s: f64| -> Vec<f64> { x.iter().zip(&v).map(|(a, b)| a + s * b).collect() };
    let fluid = full.fluid.as_ref().unwrap();
    let momentum = |q: &[f64], qp: &[f64], qm: &[f64]| -> f64 {
        let (kp, km) = (full.kinematics(qp), full.kinematics(qm));
        let (gp, gm) = (full.mass_centres(&kp), full.mass_centres(&km));
        let mut p: f64 = full
            .beam()
            .masses()
            .iter()
            .enumerate()
            .map(|(i, m)| m * (gp[i][1] - gm[i][1]) / (2.0 * h))
            .sum();
        let kin = full.kinematics(q);
        for (i, s) in wing.strips.iter().enumerate() {
            let mid = |k: &crate::model::Kinematics| -> [f64; 3] {
                let c = full.point_position(k, s.station);
                let (th_c, th_s) = (k.cos_theta[i], k.sin_theta[i]);
                let (cp, sp) = (k.cos_psi[i], k.sin_psi[i]);
                let t = [-(sp * th_s), sp * th_c, cp];
                let z = fluid.station[i];
                [c[0] + z * t[0], c[1] + z * t[1], c[2] + z * t[2]]
            };
            let (xp, xm) = (mid(&kp), mid(&km));
            let (c, si, cp, sp) = (
                kin.cos_theta[i],
                kin.sin_theta[i],
                kin.cos_psi[i],
                kin.sin_psi[i],
            );
            let nu = [-(cp * si), cp * c, -sp];
            let u: f64 = (0..3).map(|k| nu[k] * (xp[k] - xm[k]) / (2.0 * h)).sum();
            p += fluid.mass[i] * nu[1] * u;
        }
        p
    };
    let reference = momentum(&x, &at(h), &at(-h));
    eprintln!("P_y: row {exact}, positions {reference}");
    assert!(
        (exact - reference).abs() <= 1e-7 * exact.abs(),
        "{exact} vs {reference}"
    );
    assert!(ne > 0);
}

/// The velocity and momentum bases are one model in two coordinates: the same transfer
/// function `C (sI − A)⁻¹ B + D` at a complex frequency (measured 1e-14 relative; bound 1e-10),
/// for the full and a reduced model.
#[test]
fn both_bases_have_one_transfer_function() {
    let wing = flapped_wing(5, Aerodynamics::Peters { states: 3 });
    let rom: Aeroelastic<ReducedModel> = wing.reduced(&[0, 1, 2]).unwrap();
    fn transfer<M: PlanarStructure>(
        aero: &Aeroelastic<M>,
        basis: StateBasis,
    ) -> DMatrix<Complex<f64>> {
        let ss = linearize(aero, &options(basis, aero.n_strips()), "l").unwrap();
        let s = Complex::new(0.3, 7.0);
        let dim = ss.a.nrows();
        let m = DMatrix::<Complex<f64>>::identity(dim, dim) * s - ss.a.map(Complex::from);
        let x = m.lu().solve(&ss.b.map(Complex::from)).unwrap();
        ss.c.map(Complex::from) * x + ss.d.map(Complex::from)
    }
    for (label, (v, p)) in [
        (
            "full",
            (
                transfer(&wing, StateBasis::Velocities),
                transfer(&wing, StateBasis::Momenta),
            ),
        ),
        (
            "reduced",
            (
                transfer(&rom, StateBasis::Velocities),
                transfer(&rom, StateBasis::Momenta),
            ),
        ),
    ] {
        let scale = p.iter().fold(0.0_f64, |m, z| m.max(z.norm()));
        let diff = (&v - &p).iter().fold(0.0_f64, |m, z| m.max(z.norm()));
        eprintln!(
            "{label}: transfer functions differ by {:.1e} relative",
            diff / scale
        );
        assert!(diff <= 1e-10 * scale, "{label}: {diff} of {scale}");
    }
}

/// Bad requests name the field: no inputs, a speed of zero, the root shear with a follower
/// load; past the divergence speed the static solver finds no stable equilibrium.
#[test]
fn bad_requests_and_no_equilibrium() {
    let wing = flapped_wing(5, Aerodynamics::Wagner);
    let mut o = options(StateBasis::Velocities, 5);
    o.inputs.clear();
    let e = linearize(&wing, &o, "linearize").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("linearize.inputs: needs at least one"),
        "{e}"
    );
    let mut o = options(StateBasis::Velocities, 5);
    o.flight.speed = 0.0;
    let e = linearize(&wing, &o, "aero.flight").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("aero.flight.speed: must be positive"),
        "{e}"
    );
    let mut o = options(StateBasis::Velocities, 5);
    o.loads.push(Load::PointForce {
        span: 2.0,
        force: Force::Follower {
            tangential: 0.0,
            normal: 1.0,
        },
    });
    let e = linearize(&wing, &o, "linearize").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("linearize.outputs: root_shear is not available"),
        "{e}"
    );
    let mut o = options(StateBasis::Velocities, 5);
    o.flight.speed = 200.0;
    let e = linearize(&wing, &o, "linearize").unwrap_err();
    assert!(matches!(e, Error::Solve(_)), "{e:?}");
}

/// The surfaces' inputs and hinge moments add columns and rows, not dynamics: `A` is the same
/// matrix (bit for bit) with or without them, so the poles are the flutter analysis' (tested in
/// `tests/suite/aero_linearize.rs`); and a positive deflection (trailing edge down) raises the
/// lift (the static gain `D − C A⁻¹ B` of `delta[flap]` on `lift` is positive).
#[test]
fn surface_signals_leave_a_alone_and_a_positive_deflection_raises_the_lift() {
    let wing = flapped_wing(5, Aerodynamics::Peters { states: 3 });
    let mut plain = options(StateBasis::Velocities, 5);
    plain.inputs = vec![Input::Gust];
    plain.outputs = vec![Output::Lift];
    let with = options(StateBasis::Velocities, 5);
    let (a, b) = (
        linearize(&wing, &plain, "l").unwrap(),
        linearize(&wing, &with, "l").unwrap(),
    );
    assert_eq!(a.a, b.a);
    let j = with
        .inputs
        .iter()
        .position(|i| *i == Input::Deflection(surface(0)))
        .unwrap();
    let r = with
        .outputs
        .iter()
        .position(|o| *o == Output::Lift)
        .unwrap();
    let x = b.a.clone().lu().solve(&b.b.column(j).into_owned()).unwrap();
    let gain = b.d[(r, j)] - (b.c.row(r) * x)[0];
    eprintln!("static lift per rad of flap: {gain:.3} N");
    assert!(gain > 0.0, "{gain}");
}
