//! Trailing-edge control surfaces (docs/aeroelastic-model.md §3b): Theodorsen's steady flap
//! coefficients against a thin-airfoil solution computed here independently (the lumped-vortex
//! discretization of the thin-airfoil integral equation), and the static aeroelastic equilibria
//! with a deflected surface against the closed forms of aileron reversal and effectiveness: the
//! typical section (Hodges & Pierce §4.3; Bisplinghoff, Ashley & Halfman §8-4) and the uniform
//! clamped wing in strip theory (the torsion ODE solved in closed form).

use crate::common;
use flexwing::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties, TorsionProperties,
};
use flexwing::model::aero::{
    AeroSection, Aerodynamics, Aeroelastic, ControlSurface, FlapCoefficients,
};
use flexwing::model::FullModel;
use flexwing::solve::aeroelastic::{static_sweep, AeroStaticOptions};
use flexwing::solve::StaticOptions;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// The lumped-vortex discretization of the steady thin-airfoil problem: `n` equal panels on the
/// chord `[0, 1]`, a vortex at each panel's quarter point, flow tangency at its three-quarter
/// point (exact for the flat plate with any `n`). The influence matrix depends on `n` alone, so
/// it is factored once for every hinge and load case.
struct LumpedVortex {
    xv: Vec<f64>,
    xc: Vec<f64>,
    lu: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
}

impl LumpedVortex {
    fn new(n: usize) -> Self {
        let h = 1.0 / n as f64;
        let xv: Vec<f64> = (0..n).map(|j| (j as f64 + 0.25) * h).collect();
        let xc: Vec<f64> = (0..n).map(|j| (j as f64 + 0.75) * h).collect();
        // Downwash of a unit vortex at xv_j at xc_i: 1/(2π (xc_i − xv_j)).
        let a = DMatrix::from_fn(n, n, |i, j| 1.0 / (2.0 * PI * (xc[i] - xv[j])));
        Self { lu: a.lu(), xv, xc }
    }

    /// `(c_l, c_m about the quarter chord, c_h about the hinge)` on `q c`, `q c²` for angle of
    /// attack `alpha` and flap deflection `delta` (trailing edge down) hinged at `xh` (a panel
    /// edge).
    fn loads(&self, xh: f64, alpha: f64, delta: f64) -> (f64, f64, f64) {
        let n = self.xv.len();
        // Tangency with the camber line of slope −δ aft of the hinge:
        // U(α − dz/dx) = Σ Γ_j / (2π (x_i − x_j)), U = 1.
        let rhs = DVector::from_fn(n, |i, _| alpha + if self.xc[i] > xh { delta } else { 0.0 });
        let gamma = self.lu.solve(&rhs).unwrap();
        // ρ = 1, U = 1: q = ½; lift ρUΓ per vortex.
        let (mut l, mut m, mut hm) = (0.0, 0.0, 0.0);
        for (g, &x) in gamma.iter().zip(&self.xv) {
            l += g;
            m -= g * (x - 0.25);
            if x > xh {
                hm -= g * (x - xh);
            }
        }
        (l / 0.5, m / 0.5, hm / 0.5)
    }
}

/// Theodorsen's steady lift, moment and hinge-moment coefficients per radian of deflection and
/// of angle of attack against the lumped-vortex solution. The discretization converges as
/// `O(1/n)` at the hinge's logarithmic singularity of the loading (measured: the hinge-moment
/// error falls 4.0× from n = 200 to 800); at n = 1600 it is below 2e-3 of the coefficient,
/// Theodorsen's closed forms agreeing to that level at every hinge.
#[test]
fn steady_coefficients_match_thin_airfoil_numerics() {
    let n = 1600;
    let fine = LumpedVortex::new(n);
    let coarse: Vec<(usize, LumpedVortex)> = [200, 800].map(|m| (m, LumpedVortex::new(m))).into();
    for &xh in &[0.5, 0.75, 0.875] {
        let f = FlapCoefficients::at_chord_fractions(xh, 0.5);
        let (cl_d, cm_d, ch_d) = fine.loads(xh, 0.0, 1.0);
        let (cl_a, cm_a, ch_a) = fine.loads(xh, 1.0, 0.0);
        for (m, lv) in &coarse {
            let (_, _, chm) = lv.loads(xh, 0.0, 1.0);
            eprintln!(
                "x_h = {xh}, n = {m}: c_hδ error {:.3e}",
                chm - f.hinge_per_deflection()
            );
        }
        eprintln!(
            "x_h = {xh}, n = {n}: c_lδ {:.3e}, c_mδ {:.3e}, c_hδ {:.3e}, c_hα {:.3e} (relative)",
            (cl_d / f.lift_per_deflection() - 1.0),
            (cm_d / f.quarter_chord_moment_per_deflection() - 1.0),
            (ch_d / f.hinge_per_deflection() - 1.0),
            (ch_a / f.hinge_per_angle() - 1.0)
        );
        let close = |got: f64, want: f64, scale: f64, what: &str| {
            // O(1/n) discretization of the lumped vortices at the hinge (see above).
            assert!(
                (got - want).abs() < 2e-3 * scale,
                "x_h = {xh}, {what}: lumped vortex {got}, Theodorsen {want}"
            );
        };
        close(
            cl_d,
            f.lift_per_deflection(),
            f.lift_per_deflection(),
            "c_lδ",
        );
        close(
            cm_d,
            f.quarter_chord_moment_per_deflection(),
            f.quarter_chord_moment_per_deflection().abs(),
            "c_mδ",
        );
        close(
            ch_d,
            f.hinge_per_deflection(),
            f.hinge_per_deflection().abs(),
            "c_hδ",
        );
        close(ch_a, f.hinge_per_angle(), f.hinge_per_angle().abs(), "c_hα");
        // The flat plate: exact for any n.
        assert!((cl_a - 2.0 * PI).abs() < 1e-9 && cm_a.abs() < 1e-9);
    }
}

/// Static equilibria at the speeds `speeds` of `aero` (steady aerodynamics); the lift (N) and the
/// hinge moments (N·m) at each.
fn statics(aero: &Aeroelastic, speeds: &[f64]) -> Vec<(f64, Vec<f64>, Vec<f64>)> {
    let plan = AeroStaticOptions {
        speeds: speeds.to_vec(),
        root_angle: 0.0,
        gravity: None,
        loads: vec![],
        options: StaticOptions::default(),
        divergence_tolerance: 1e-8,
    };
    let out = static_sweep(aero, &plan, "static", &mut |_| {}).unwrap();
    assert!(out.stopped.is_none(), "{:?}", out.stopped);
    out.points
        .iter()
        .map(|p| (p.lift, p.hinge_moments.clone(), p.q.clone()))
        .collect()
}

/// Small deflection (rad): the closed forms are linear; the strip's angle of attack is
/// `atan2(sin ψ + T10 δ/π, cos ψ)`, linear in δ to 1e-8 relative at this size.
const DELTA: f64 = 1e-4;

/// A one-element chain is a typical section in pitch (the lift does not depend on the plunge in
/// steady flow): torsion spring `K_ψ = 2 GJ/ℓ` per `ℓ = 1 m` of span (`aero_typical_section.rs`).
/// Elastic axis at 30 % of the chord (`e = 0.05 c` behind the aerodynamic centre), hinge at
/// 75 %. Closed forms: `q_D = K/(c e c_lα)`, `q_R = −c_lδ K/(c² c_lα c_mδ)` (`c_mδ` about the
/// aerodynamic centre), effectiveness `L/L_rigid = (1 − q/q_R)/(1 − q/q_D)`.
#[test]
fn typical_section_reversal_and_effectiveness() {
    let (c, xea, xh, rho) = (1.0, 0.3, 0.75, 1.2);
    let gj = 50.0;
    let section = SectionProperties {
        ei: Profile::Uniform(1e4),
        mass_per_length: Profile::Uniform(10.0),
        torsion: Some(TorsionProperties {
            gj: Profile::Uniform(gj),
            polar_inertia: Profile::Uniform(1.0),
            inertia_axis: InertiaAxis::ElasticAxis,
            offset: Profile::Uniform(0.0),
        }),
    };
    let full = FullModel::new(
        Beam::new(
            1.0,
            &section,
            &Discretization::Uniform(1),
            Calibration::TipLoad,
        )
        .unwrap(),
    );
    let mut sec = AeroSection::new(Profile::Uniform(c), Profile::Uniform(xea));
    let mut aileron = ControlSurface::new("aileron", 0.0, 1.0, xh);
    aileron.deflection = DELTA;
    sec.surfaces = vec![aileron];
    let aero = Aeroelastic::new(&full, &sec, rho, Aerodynamics::Steady, "aero").unwrap();
    let k = 2.0 * gj; // K_ψ per unit span, ℓ = 1
    let f = FlapCoefficients::at_chord_fractions(xh, xea);
    let (cla, cld, cmd) = (
        2.0 * PI,
        f.lift_per_deflection(),
        f.quarter_chord_moment_per_deflection(),
    );
    let e = (0.25 - xea).abs() * c;
    let q_d = k / (c * e * cla);
    let q_r = -cld * k / (c * c * cla * cmd);
    assert!(q_r < q_d, "the chosen section reverses before it diverges");
    let speed = |q: f64| (2.0 * q / rho).sqrt();
    let fractions = [0.2, 0.5, 0.9, 1.1, 1.5];
    let speeds: Vec<f64> = fractions.iter().map(|r| speed(r * q_r)).collect();
    let points = statics(&aero, &speeds);
    for ((r, u), (lift, hinge, q)) in fractions.iter().zip(&speeds).zip(&points) {
        let qd = 0.5 * rho * u * u;
        let rigid = qd * c * cld * DELTA;
        let want = (1.0 - qd / q_r) / (1.0 - qd / q_d);
        eprintln!(
            "typical section q/q_R = {r}: η = {:.9}, closed form {want:.9}",
            lift / rigid
        );
        // Linear in δ to 1e-8 (DELTA) and the lift's tilt with the bending (cos θ, θ ~ 1e-5).
        assert!(
            (lift / rigid - want).abs() < 1e-6,
            "q/q_R = {r}: effectiveness {} vs closed form {want}",
            lift / rigid
        );
        // The hinge moment of the equilibrium: the coefficients at the twist ψ found.
        let psi = q[1];
        let h = qd * c * c * (f.hinge_per_deflection() * DELTA + f.hinge_per_angle() * psi);
        assert!((hinge[0] - h).abs() < 1e-6 * h.abs(), "{} vs {h}", hinge[0]);
    }
    // Reversal: the lift changes sign at q_R.
    assert!(points[2].0 > 0.0 && points[3].0 < 0.0);
}

/// The uniform clamped wing in strip theory with a full-span aileron: `GJ ψ'' + q c e c_lα ψ =
/// −q (c e c_lδ + c² c_mδ) δ`, `ψ(0) = 0`, `ψ'(L) = 0` gives `ψ = β(cos λx + tan λL sin λx − 1)`,
/// `λ² = q c e c_lα/GJ`, `β = (e c_lδ + c c_mδ) δ/(e c_lα)`, and the lift relative to the rigid
/// wing `η = 1 + (e c_lδ + c c_mδ)/(e c_lδ) · (tan λL/(λL) − 1)`; reversal where
/// `tan λL/(λL) = c c_mδ/(e c_lδ + c c_mδ)`. Patil's structure (GJ = 1e4 N·m², L = 16 m), chord
/// 1 m, elastic axis at 35 % chord, hinge at 80 %, ρ = 0.0889.
#[test]
fn uniform_wing_reversal_converges_to_the_torsion_ode() {
    let (c, xea, xh, rho, gj, l) = (1.0, 0.35, 0.8, 0.0889, 1e4, 16.0);
    let f = FlapCoefficients::at_chord_fractions(xh, xea);
    let (cla, cld, cmd) = (
        2.0 * PI,
        f.lift_per_deflection(),
        f.quarter_chord_moment_per_deflection(),
    );
    let e = (xea - 0.25) * c;
    let ratio = c * cmd / (e * cld + c * cmd);
    // λL in (0, π/2) with tan x / x = ratio (> 1), by bisection.
    let (mut lo, mut hi) = (1e-9, 0.5 * PI - 1e-12);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid.tan() / mid < ratio {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let x_r = 0.5 * (lo + hi);
    let q_of = |x: f64| x * x * gj / (l * l * c * e * cla);
    let q_r = q_of(x_r);
    let q_d = q_of(0.5 * PI);
    assert!(q_r < q_d);
    let eta = |q: f64| {
        let x = (q * c * e * cla / gj).sqrt() * l;
        1.0 + (e * cld + c * cmd) / (e * cld) * (x.tan() / x - 1.0)
    };
    let fractions = [0.3, 0.7, 1.2];
    let speeds: Vec<f64> = fractions
        .iter()
        .map(|r| (2.0 * r * q_r / rho).sqrt())
        .collect();
    let mut errors = vec![];
    for n in [8, 32] {
        let mut sec = AeroSection::new(Profile::Uniform(c), Profile::Uniform(xea));
        let mut aileron = ControlSurface::new("aileron", 0.0, l, xh);
        aileron.deflection = DELTA;
        sec.surfaces = vec![aileron];
        let aero = Aeroelastic::new(
            &common::patil_structure(n),
            &sec,
            rho,
            Aerodynamics::Steady,
            "aero",
        )
        .unwrap();
        let points = statics(&aero, &speeds);
        let err = fractions
            .iter()
            .zip(&speeds)
            .zip(&points)
            .map(|((_, u), (lift, _, _))| {
                let q = 0.5 * rho * u * u;
                let rigid = q * c * cld * DELTA * l;
                (lift / rigid - eta(q)).abs()
            })
            .fold(0.0, f64::max);
        eprintln!("uniform wing, n = {n}: max |η − η_closed| = {err:.3e}");
        errors.push(err);
        // The sign of the lift changes between 0.7 q_R and 1.2 q_R.
        assert!(points[1].0 > 0.0 && points[2].0 < 0.0, "n = {n}");
    }
    // Second order in the element length (the lumped torsion springs and midpoint strips):
    // measured ratio of the errors, n = 8 → 32, close to 16.
    let order = (errors[0] / errors[1]).log(4.0);
    assert!(order > 1.8, "errors {errors:?}, order {order}");
    assert!(errors[1] < 2e-3, "{errors:?}");
}

/// Bad surfaces are one-line errors naming the key.
#[test]
fn bad_surfaces_name_the_key() {
    let full = common::patil_structure(8);
    let cases: Vec<(Vec<ControlSurface>, &str, &str)> = vec![
        (
            vec![ControlSurface::new("a", 10.0, 17.0, 0.75)],
            "aero.surfaces[0].to",
            "span",
        ),
        (
            vec![ControlSurface::new("a", -1.0, 4.0, 0.75)],
            "aero.surfaces[0].from",
            "span",
        ),
        (
            vec![ControlSurface::new("a", 4.0, 4.0, 0.75)],
            "aero.surfaces[0].to",
            "after from",
        ),
        (
            vec![ControlSurface::new("a", 0.0, 4.0, 1.0)],
            "aero.surfaces[0].hinge",
            "chord",
        ),
        (
            vec![ControlSurface::new("a", 0.0, 4.0, -0.1)],
            "aero.surfaces[0].hinge",
            "chord",
        ),
        (
            vec![
                ControlSurface::new("flap", 0.0, 8.0, 0.75),
                ControlSurface::new("aileron", 7.0, 16.0, 0.8),
            ],
            "aero.surfaces[1].from",
            "overlaps aero.surfaces[0]",
        ),
        (
            // Adjacent, but within one element (2 m long): on the same strip.
            vec![
                ControlSurface::new("flap", 0.0, 9.0, 0.75),
                ControlSurface::new("aileron", 9.0, 16.0, 0.8),
            ],
            "aero.surfaces[1].from",
            "same strip",
        ),
        (
            vec![
                ControlSurface::new("a", 0.0, 4.0, 0.75),
                ControlSurface::new("a", 8.0, 16.0, 0.8),
            ],
            "aero.surfaces[1].name",
            "also the name",
        ),
    ];
    for (surfaces, field, words) in cases {
        let mut sec = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
        sec.surfaces = surfaces;
        let e = Aeroelastic::new(&full, &sec, 0.0889, Aerodynamics::Steady, "aero").unwrap_err();
        assert_eq!(e.field, field, "{e}");
        assert!(e.to_string().contains(words), "{e}");
        assert!(!e.to_string().contains('\n'), "{e}");
    }
    // Adjacent surfaces on a node are accepted.
    let mut sec = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
    sec.surfaces = vec![
        ControlSurface::new("flap", 0.0, 8.0, 0.75),
        ControlSurface::new("aileron", 8.0, 16.0, 0.8),
    ];
    assert!(Aeroelastic::new(&full, &sec, 0.0889, Aerodynamics::Steady, "aero").is_ok());
}

/// Regression (the model against itself): a response that starts from the static equilibrium
/// with a deflected aileron stays there, for every unsteady model. The steady limits of the
/// unsteady flap terms (the lagged flap upwash `V T10 δ/π`, the moment `(T4 + T10) V² δ`) must
/// then be the steady model's, and the lag states must start at their steady values with the
/// flap's upwash in them. Patil's wing, n = 8, U = 20 m/s, aileron 12–16 m at 0.05 rad: the
/// static tip deflection is 0.74 m; the drift over 0.5 s is integration error (rtol 1e-9).
#[test]
fn a_deflected_wing_at_equilibrium_stays_there() {
    use flexwing::model::aero::FlightCondition;
    use flexwing::solve::aeroelastic::{response, FlightHistory, ResponseOptions};
    for model in [
        Aerodynamics::QuasiSteady,
        Aerodynamics::Wagner,
        Aerodynamics::Peters { states: 6 },
    ] {
        let mut sec = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
        let mut aileron = ControlSurface::new("aileron", 12.0, 16.0, 0.8);
        aileron.deflection = 0.05;
        sec.surfaces = vec![aileron];
        let wing =
            Aeroelastic::new(&common::patil_structure(8), &sec, 0.0889, model, "aero").unwrap();
        let mut plan = ResponseOptions::new(
            FlightHistory::steady(FlightCondition::at_speed(20.0)),
            0.5,
            0.05,
        );
        plan.rtol = 1e-9;
        let out = response(&wing, &plan, "response", &mut |_| {}).unwrap();
        assert!(out.stopped.is_none(), "{model}: {:?}", out.stopped);
        let y0 = out.samples[0].tip[1];
        assert!(y0 > 0.1, "{model}: the aileron lifts the wing ({y0} m)");
        let drift = out
            .samples
            .iter()
            .map(|s| (s.tip[1] - y0).abs())
            .fold(0.0, f64::max);
        eprintln!("{model}: tip {y0:.6} m, drift {drift:.2e} m");
        // Integration error of a run that should not move: measured 8e-14 m.
        assert!(drift < 1e-8 * y0, "{model}: drift {drift} m from {y0} m");
    }
}

/// The linear model about a deflected equilibrium: the static gain `D − C A⁻¹ B` of the speed
/// input against central differences of the non-linear static equilibria at `U ± h`. The
/// aileron's equivalent upwash `V T10 δ/π` grows with the speed, so this gain holds only if the
/// speed's column of `B` carries it (without that term the tip's gain came out 0.0368 m/(m/s)
/// instead of 0.0820: measured by removing it).
#[test]
fn speed_gain_of_a_deflected_wing_matches_the_static_equilibria() {
    use flexwing::model::aero::FlightCondition;
    use flexwing::solve::aeroelastic::{linearize, Input, LinearizeOptions, Output, StateBasis};
    use flexwing::solve::Damping;
    let mut sec = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
    let mut aileron = ControlSurface::new("aileron", 12.0, 16.0, 0.8);
    aileron.deflection = 0.05;
    sec.surfaces = vec![aileron];
    let u = 20.0;
    let wing = Aeroelastic::new(
        &common::patil_structure(8),
        &sec,
        0.0889,
        Aerodynamics::Wagner,
        "aero",
    )
    .unwrap();
    let ss = linearize(
        &wing,
        &LinearizeOptions {
            flight: FlightCondition::at_speed(u),
            loads: vec![],
            damping: Damping::None,
            static_options: StaticOptions::default(),
            inputs: vec![Input::Speed],
            outputs: vec![Output::TipY, Output::Lift],
            basis: StateBasis::Velocities,
            mode_numbers: None,
        },
        "linearize",
    )
    .unwrap();
    let x = ss.a.clone().lu().solve(&ss.b).unwrap();
    let gain = &ss.d - &ss.c * x;
    let h = 1e-3;
    let pts = statics(&wing, &[u - h, u + h]);
    let tip = |q: &[f64]| {
        let chain = wing.chain();
        chain.tip(q).0[1]
    };
    let fd_tip = (tip(&pts[1].2) - tip(&pts[0].2)) / (2.0 * h);
    let fd_lift = (pts[1].0 - pts[0].0) / (2.0 * h);
    eprintln!(
        "speed gain: tip {:.9e} vs {fd_tip:.9e}, lift {:.9e} vs {fd_lift:.9e}",
        gain[(0, 0)],
        gain[(1, 0)]
    );
    // Central differences: O(h²) = 1e-6 relative of the curvature, and the static solver's
    // tolerance over 2h; measured 4.5e-8 (tip) and 2.5e-9 (lift).
    assert!((gain[(0, 0)] / fd_tip - 1.0).abs() < 1e-5);
    assert!((gain[(1, 0)] / fd_lift - 1.0).abs() < 1e-5);
}
