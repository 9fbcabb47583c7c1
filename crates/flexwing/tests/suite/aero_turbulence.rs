//! Continuous turbulence (`solve::aeroelastic::turbulence`, docs/control.md): the RMS of long
//! non-linear runs of Patil's wing in seeded von Kármán turbulence of small intensity against
//! the linear frequency-domain value, the statistical error shrinking with the record length as
//! the estimator's standard error says.

use crate::common;
use flexwing::model::aero::{Aerodynamics, Aeroelastic, FlightCondition};
use flexwing::solve::aeroelastic::turbulence::{
    gust_spectra, FrequencyGrid, GustResponse, Realization, Spectrum, Turbulence,
};
use flexwing::solve::aeroelastic::{
    linearize, poles, AeroelasticEquations, FlightHistory, Gust, GustPenetration, GustShape, Input,
    LinearizeOptions, Output, StateBasis, StateSpace,
};
use flexwing::solve::integrate::{integrate, IntegratorSettings, Method};
use flexwing::solve::{Damping, StaticOptions};
use nalgebra::{Complex, DMatrix, DVector};

type C64 = Complex<f64>;

fn options(speed: f64) -> LinearizeOptions {
    LinearizeOptions {
        flight: FlightCondition {
            speed,
            root_angle: 0.02,
            gravity: Some(9.81),
        },
        loads: vec![],
        damping: Damping::None,
        static_options: StaticOptions::default(),
        inputs: vec![Input::Gust, Input::GustRate],
        outputs: vec![Output::TipY, Output::RootBendingMoment],
        basis: StateBasis::Velocities,
        mode_numbers: None,
    }
}

/// The linear model's periodic state at `t = 0` for the realization `r` (velocity basis):
/// `Σ_k Re[(iω_k − A)⁻¹ (B_g + iω_k B_ġ) (a_k − i b_k)]`, so that the non-linear run starts on
/// its periodic response (no transient but the O(σ²) mismatch).
fn periodic_state(ss: &StateSpace, r: &Realization) -> Vec<f64> {
    let n = ss.a.nrows();
    let mut x = vec![0.0; n];
    for l in &r.lines {
        let m = DMatrix::<C64>::identity(n, n) * C64::new(0.0, l.omega) - ss.a.map(C64::from);
        let b = DVector::from_fn(n, |i, _| C64::new(ss.b[(i, 0)], l.omega * ss.b[(i, 1)]));
        let z = m.lu().solve(&b).unwrap();
        let c = C64::new(l.a, -l.b);
        for i in 0..n {
            x[i] += (z[i] * c).re;
        }
    }
    x
}

struct Record {
    period: f64,
    /// The non-linear run's mean squares of the outputs about the equilibrium over one period.
    nonlinear: Vec<f64>,
    /// The linear model's for the same realization: `Σ_k |H(ω_k)|² (a_k² + b_k²)/2`.
    linear_same: Vec<f64>,
    /// The estimator's expectation `Σ_k |H(ω_k)|² Φ_w(ω_k) Δω` and standard error
    /// `(Σ_k (|H(ω_k)|² Φ_w(ω_k) Δω)²)^{1/2}` (each line's `(a² + b²)/2` is exponential).
    expected: Vec<f64>,
    standard_error: Vec<f64>,
}

fn record(
    wing: &Aeroelastic,
    ss: &StateSpace,
    o: &LinearizeOptions,
    turbulence: &Turbulence,
    period: f64,
    seed: u64,
) -> Record {
    let speed = o.flight.speed;
    let top = 40.0;
    let r = Realization::new(turbulence, speed, seed, period, top, "").unwrap();
    let dw = 2.0 * std::f64::consts::PI / period;
    let mut response = GustResponse::new(ss, "").unwrap();
    let mut h = vec![C64::new(0.0, 0.0); 2];
    let (mut linear_same, mut expected, mut se2) = (vec![0.0; 2], vec![0.0; 2], vec![0.0; 2]);
    for l in &r.lines {
        response.at(l.omega, &mut h);
        for k in 0..2 {
            let g2 = h[k].norm_sqr();
            linear_same[k] += g2 * 0.5 * (l.a * l.a + l.b * l.b);
            let s = g2 * turbulence.psd(l.omega, speed) * dw;
            expected[k] += s;
            se2[k] += s * s;
        }
    }
    let n = wing.structure().n_dofs();
    let x = periodic_state(ss, &r);
    let start: Vec<f64> = ss.state_values.iter().zip(&x).map(|(v, d)| v + d).collect();
    let mut flight = FlightHistory::steady(o.flight);
    flight.gust = Some(Gust {
        shape: GustShape::Turbulence(Box::new(r.clone())),
        amplitude: 1.0,
        start: 0.0,
        spanwise: flexwing::beam::Profile::Uniform(1.0),
        penetration: GustPenetration::Uniform,
    });
    let loads = wing.full().apply(&[], "loads").unwrap();
    let mut eqs =
        AeroelasticEquations::new(wing, &loads, vec![], flight, &Damping::None, "flight").unwrap();
    let y0 = eqs.state(&start[..n], &start[n..2 * n], &start[2 * n..]);
    // Samples of one period, 4 per period of the highest line: the mean of N equispaced samples
    // of a trigonometric polynomial of degree below N/2 is its mean over the period.
    let samples = 4 * r.lines.len();
    let times: Vec<f64> = (0..=samples)
        .map(|k| period * k as f64 / samples as f64)
        .collect();
    let settings = IntegratorSettings {
        rtol: 1e-7,
        atol: 1e-9,
        max_steps: 10_000_000,
        ..IntegratorSettings::default()
    };
    let (traj, _) = integrate(
        Method::Radau,
        &settings,
        &mut eqs,
        0.0,
        &y0,
        &times,
        &mut |_| {},
    )
    .unwrap();
    let full = wing.full();
    let ne = full.n_elements();
    let mut nonlinear = vec![0.0; 2];
    for y in traj.y.iter().skip(1) {
        let q = &y[..n];
        let shape = full.shape(q);
        let values = [shape.y[ne], full.stiffness()[0] * q[0]];
        for k in 0..2 {
            nonlinear[k] += (values[k] - ss.output_values[k]).powi(2) / samples as f64;
        }
    }
    Record {
        period,
        nonlinear,
        linear_same,
        expected,
        standard_error: se2.iter().map(|v| v.sqrt()).collect(),
    }
}

/// Patil's wing (n = 8, Peters 4) at 20 m/s, root angle 0.02 rad and gravity, in von Kármán
/// turbulence of σ_w = 0.02 m/s (a gust angle of 1e-3 rad) and L = 30 m, records of 25 to 200 s
/// (one seed each): the non-linear mean squares of the tip deflection and root moment
///
/// * equal the linear model's for the same realization within 2e-3 relative (the O(σ_w)
///   linearization error and the integration's rtol 1e-7; measured in the test's output);
/// * differ from the linear frequency-domain variance `σ_y²` (500 frequencies) by less than four
///   standard errors of the estimator plus the bias of the record's line spectrum (its
///   expectation less `σ_y²`, the variance below `2π/T` and above 40 rad/s, computed);
/// * and that standard error shrinks as `T^{−1/2}` (ratio 2.83 ± 20 % from 25 to 200 s).
#[test]
fn the_rms_of_long_nonlinear_runs_converges_to_the_linear_value() {
    let wing = common::patil_wing(8, Aerodynamics::Peters { states: 4 });
    let o = options(20.0);
    let ss = linearize(&wing, &o, "linearize").unwrap();
    let p = poles(&ss.a).unwrap();
    let turbulence = Turbulence {
        spectrum: Spectrum::VonKarman,
        intensity: 0.02,
        scale_length: 30.0,
    };
    let grid = FrequencyGrid {
        points: 500,
        min_frequency: 1e-4,
        max_frequency: 200.0,
    };
    let spectra = gust_spectra(&ss, &p, &turbulence, 20.0, &grid, "").unwrap();
    let exact: Vec<f64> = spectra.rms.iter().map(|r| r * r).collect();
    let mut errors = Vec::new();
    for (i, period) in [25.0, 50.0, 100.0, 200.0].into_iter().enumerate() {
        let rec = record(&wing, &ss, &o, &turbulence, period, 11 + i as u64);
        for k in 0..2 {
            let nl = rec.nonlinear[k];
            let same = (nl / rec.linear_same[k] - 1.0).abs();
            let bias = rec.expected[k] - exact[k];
            let z = (nl - exact[k]) / rec.standard_error[k];
            println!(
                "T = {:5} s, output {k}: non-linear {nl:.5e}, linear same record {:.5e} \
                 ({same:.1e}), σ_y² {:.5e}, relative deviation {:+.3}, standard error {:.3} \
                 (relative), bias {:+.4}, z {z:+.2}",
                rec.period,
                rec.linear_same[k],
                exact[k],
                nl / exact[k] - 1.0,
                rec.standard_error[k] / exact[k],
                bias / exact[k],
            );
            assert!(same < 2e-3, "T = {period}, output {k}: {same:e}");
            assert!(
                (nl - exact[k]).abs() < 4.0 * rec.standard_error[k] + bias.abs(),
                "T = {period}, output {k}: z = {z}"
            );
            errors.push(rec.standard_error[k] / exact[k]);
        }
    }
    for k in 0..2 {
        let ratio = errors[k] / errors[6 + k];
        assert!(
            (ratio / 8f64.sqrt() - 1.0).abs() < 0.2,
            "output {k}: {ratio}"
        );
    }
}
