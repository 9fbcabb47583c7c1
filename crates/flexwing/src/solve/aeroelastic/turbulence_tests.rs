use nalgebra::{DMatrix, DVector};

use super::*;
use crate::solve::aeroelastic::{Signal, StateBasis};

fn signal(name: &str) -> Signal {
    Signal {
        name: name.into(),
        unit: "1",
    }
}

fn model(a: DMatrix<f64>, b: DMatrix<f64>, c: DMatrix<f64>, d: DMatrix<f64>) -> StateSpace {
    let (n, m, p) = (a.nrows(), b.ncols(), c.nrows());
    let inputs = ["gust", "gust_rate"][..m]
        .iter()
        .map(|s| signal(s))
        .collect();
    StateSpace {
        a,
        b,
        c,
        d,
        states: (0..n).map(|i| signal(&format!("x[{i}]"))).collect(),
        inputs,
        outputs: (0..p).map(|i| signal(&format!("y[{i}]"))).collect(),
        basis: StateBasis::Velocities,
        state_values: vec![0.0; n],
        input_values: vec![0.0; m],
        output_values: vec![0.0; p],
        q: Vec::new(),
    }
}

/// `∫₀^∞ Φ_w dω = σ_w²` for both spectra, by the trapezoidal rule in `ln ω` over 24 decades
/// (2·10⁵ points: error ~1e-10) with the tails in closed form (`Φ ∝ ω^{−5/3}` or `ω^{−2}`
/// above, flat below): the variance is `σ_w²` to 1e-8, which checks the constants (`a`, the
/// `τ/π` factor) and the one-sided convention.
#[test]
fn the_spectra_integrate_to_the_intensity_squared() {
    for spectrum in [Spectrum::VonKarman, Spectrum::Dryden] {
        let t = Turbulence {
            spectrum,
            intensity: 1.7,
            scale_length: 300.0,
        };
        let u = 40.0;
        let (lo, hi, n) = (1e-12f64, 1e12f64, 200_000);
        let step = (hi / lo).ln() / n as f64;
        let f = |x: f64| {
            let w = x.exp();
            t.psd(w, u) * w
        };
        let mut sum = 0.5 * (f(lo.ln()) + f(hi.ln()));
        for k in 1..n {
            sum += f(lo.ln() + k as f64 * step);
        }
        sum *= step;
        let p = match spectrum {
            Spectrum::VonKarman => -5.0 / 3.0,
            Spectrum::Dryden => -2.0,
        };
        sum += lo * t.psd(lo, u) + hi * t.psd(hi, u) / (-p - 1.0);
        let expected = t.intensity * t.intensity;
        assert!(
            (sum / expected - 1.0).abs() < 1e-8,
            "{spectrum:?}: {sum} vs {expected}"
        );
    }
}

/// The continuous Lyapunov equation `F P + P Fᵀ + G Gᵀ = 0` by the Kronecker form (small `F`).
fn lyapunov(f: &DMatrix<f64>, g: &DVector<f64>) -> DMatrix<f64> {
    let n = f.nrows();
    let i = DMatrix::<f64>::identity(n, n);
    let k = i.kronecker(f) + f.kronecker(&i);
    let q = -(g * g.transpose());
    let rhs = DVector::from_column_slice(q.as_slice());
    let p = k.lu().solve(&rhs).unwrap();
    DMatrix::from_column_slice(n, n, p.as_slice())
}

/// A 1-DOF oscillator `ẍ + 2ζω_n ẋ + ω_n² x = k w + m ẇ` in Dryden turbulence: the variances
/// of `x` and `ẋ` by quadrature against the exact ones from the Lyapunov equation of the
/// oscillator with Dryden's shaping filter `σ √τ (1 + √3 τ s)/(1 + τ s)²` driven by white
/// noise of one-sided spectrum `1/π` (an independent method: no frequency grid). The
/// oscillator's peak (ζ = 0.01) is narrower than the logarithmic grid's spacing: the pole's
/// cluster resolves it. Both within the estimated quadrature error and 1e-4 relative.
#[test]
fn the_rms_of_an_oscillator_in_dryden_turbulence_is_the_lyapunov_one() {
    let (wn, zeta, k, m) = (10.0, 0.01, 2.0, 0.3);
    let (u, l, sigma): (f64, f64, f64) = (50.0, 50.0, 1.5);
    let tau = l / u;
    let a = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -wn * wn, -2.0 * zeta * wn]);
    let b = DMatrix::from_row_slice(2, 2, &[0.0, 0.0, k, m]);
    let c = DMatrix::<f64>::identity(2, 2);
    let d = DMatrix::zeros(2, 2);
    let ss = model(a.clone(), b, c, d);
    // The shaping filter: z̈ + 2/τ ż + z/τ² = n, w = h·z.
    let f = DMatrix::from_row_slice(2, 2, &[0.0, 1.0, -1.0 / (tau * tau), -2.0 / tau]);
    let h = [
        sigma * tau.sqrt() / (tau * tau),
        sigma * tau.sqrt() * 3f64.sqrt() / tau,
    ];
    let mut big = DMatrix::zeros(4, 4);
    big.view_mut((0, 0), (2, 2)).copy_from(&a);
    big.view_mut((2, 2), (2, 2)).copy_from(&f);
    // ẍ gets k h·z + m h·(F z + g n).
    for j in 0..2 {
        let hf: f64 = (0..2).map(|i| h[i] * f[(i, j)]).sum();
        big[(1, 2 + j)] = k * h[j] + m * hf;
    }
    let g = DVector::from_column_slice(&[0.0, m * h[1], 0.0, 1.0]);
    let p = lyapunov(&big, &g);
    let turbulence = Turbulence {
        spectrum: Spectrum::Dryden,
        intensity: sigma,
        scale_length: l,
    };
    let poles = crate::solve::aeroelastic::poles(&ss.a).unwrap();
    let grid = FrequencyGrid {
        points: 500,
        min_frequency: 1e-3,
        max_frequency: 1e3,
    };
    let s = gust_spectra(&ss, &poles, &turbulence, u, &grid, "").unwrap();
    for i in 0..2 {
        let exact = p[(i, i)];
        let got = s.rms[i] * s.rms[i];
        let error = (got - exact).abs();
        assert!(
            error < 1e-4 * exact && error <= s.variance_error[i].max(1e-9 * exact) * 3.0,
            "output {i}: {got} vs {exact} (estimated error {:.2e})",
            s.variance_error[i]
        );
    }
    assert!((s.gust_rms / sigma - 1.0).abs() < 1e-4, "{}", s.gust_rms);
}

/// The Hessenberg solve against a dense complex LU of `(iωI − A)` on a random, badly scaled
/// model (entries over 8 decades) with a gust and gust-rate input: to 1e-10 relative.
#[test]
fn the_hessenberg_response_is_the_dense_solve() {
    let n = 12;
    let mut seed = SplitMix64(7);
    let scale = |i: usize| 10f64.powi(i as i32 % 5 - 2);
    let a = DMatrix::from_fn(n, n, |i, j| {
        (seed.uniform() - 0.5) * scale(i) / scale(j) - if i == j { 3.0 } else { 0.0 }
    });
    let b = DMatrix::from_fn(n, 2, |i, _| seed.uniform() * scale(i));
    let c = DMatrix::from_fn(3, n, |_, j| seed.uniform() / scale(j));
    let d = DMatrix::from_fn(3, 2, |_, _| seed.uniform());
    let ss = model(a, b, c, d);
    let mut r = GustResponse::new(&ss, "").unwrap();
    let mut out = vec![Complex::new(0.0, 0.0); 3];
    for omega in [0.0, 0.01, 1.0, 3.0, 47.0, 1e4] {
        r.at(omega, &mut out);
        let reference = dense_response(&ss, omega);
        for (x, y) in out.iter().zip(&reference) {
            assert!(
                (x - y).norm() < 1e-10 * y.norm().max(1e-300),
                "{omega}: {x} vs {y}"
            );
        }
    }
    let no_gust = model(
        DMatrix::identity(1, 1),
        DMatrix::zeros(1, 0),
        DMatrix::zeros(1, 1),
        DMatrix::zeros(1, 0),
    );
    let e = GustResponse::new(&no_gust, "turbulence").unwrap_err();
    assert_eq!(e.field, "turbulence.inputs");
}

/// A realization: the interpolated record against the sum of its lines (relative to σ_w: 1e-3,
/// the Hermite error at ω_max with 8 nodes per period of the highest line), its rate against a
/// central difference, periodic, the same for the same seed; its sample variance over one period
/// is `Σ (a_k² + b_k²)/2` (Parseval) and its expected variance tends to σ_w² as the period and
/// the cut-off grow (the missing variance is the spectrum below `2π/T` and above `ω_max`).
#[test]
fn realizations_are_seeded_periodic_records_of_the_spectrum() {
    let t = Turbulence {
        spectrum: Spectrum::VonKarman,
        intensity: 2.0,
        scale_length: 100.0,
    };
    let u = 50.0;
    let r = Realization::new(&t, u, 42, 200.0, 60.0, "").unwrap();
    let again = Realization::new(&t, u, 42, 200.0, 60.0, "").unwrap();
    assert_eq!(r, again);
    let other = Realization::new(&t, u, 43, 200.0, 60.0, "").unwrap();
    assert_ne!(r.lines[0], other.lines[0]);
    let mut worst: f64 = 0.0;
    for k in 0..2000 {
        let time = 0.0973 * k as f64;
        let (v, rate) = r.value_and_rate(time);
        worst = worst.max((v - r.exact(time)).abs());
        let fd = (r.value_and_rate(time + 1e-6).0 - r.value_and_rate(time - 1e-6).0) / 2e-6;
        assert!(
            (fd - rate).abs() < 1e-5 * (1.0 + rate.abs()),
            "{time}: {fd} vs {rate}"
        );
        assert!((r.value_and_rate(time + 200.0).0 - v).abs() < 1e-9);
    }
    assert!(worst < 1e-3 * t.intensity, "{worst}");
    let samples = 1 << 16;
    let mean_square: f64 = (0..samples)
        .map(|j| r.exact(200.0 * j as f64 / samples as f64).powi(2))
        .sum::<f64>()
        / samples as f64;
    let parseval: f64 = r.lines.iter().map(|l| 0.5 * (l.a * l.a + l.b * l.b)).sum();
    assert!((mean_square / parseval - 1.0).abs() < 1e-9);
    let mut missing = Vec::new();
    for (period, top) in [(100.0, 10.0), (1000.0, 100.0), (10000.0, 1000.0)] {
        let r = Realization::new(&t, u, 1, period, top, "").unwrap();
        missing.push(1.0 - r.variance / (t.intensity * t.intensity));
    }
    assert!(
        missing[0] > missing[1] && missing[1] > missing[2] && missing[2] < 0.01,
        "{missing:?}"
    );
    let e = Realization::new(&t, u, 1, 1.0, 1.0, "turbulence").unwrap_err();
    assert_eq!(e.field, "turbulence.max_frequency");
}

/// The grid: `points` frequencies, increasing, inside the bounds, a cluster around a lightly
/// damped pole and none around a well-damped one.
#[test]
fn the_grid_clusters_around_lightly_damped_poles() {
    let grid = FrequencyGrid {
        points: 100,
        min_frequency: 0.1,
        max_frequency: 100.0,
    };
    let poles = [
        Complex::new(-0.01, 5.0),
        Complex::new(-0.01, -5.0),
        Complex::new(-10.0, 20.0),
        Complex::new(-3.0, 0.0),
    ];
    let (w, jacobian) = grid.nodes(&poles);
    // The quadrature of dω over the nodes is the interval's length.
    let length: f64 = (0..99).map(|j| 0.5 * (jacobian[j] + jacobian[j + 1])).sum();
    assert!((length / 99.9 - 1.0).abs() < 1e-3, "{length}");
    assert_eq!(w.len(), 100);
    assert!(w.windows(2).all(|p| p[0] <= p[1]));
    assert!(w[0] == 0.1 && w[99] == 100.0);
    let near = |c: f64, h: f64| w.iter().filter(|&&x| (x - c).abs() < h).count();
    assert!(near(5.0, 0.1) >= CLUSTER_POINTS / 2, "{w:?}");
    assert!(near(20.0, 2.0) < 4, "{w:?}");
    let e = FrequencyGrid {
        max_frequency: 0.05,
        ..grid
    }
    .validate("turbulence")
    .unwrap_err();
    assert_eq!(e.field, "turbulence.max_frequency");
}
