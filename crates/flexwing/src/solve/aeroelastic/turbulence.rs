//! Continuous turbulence (docs/control.md, "Continuous turbulence"): the von Kármán and Dryden
//! spectra of the vertical gust velocity, the power spectra and RMS of a linear model's outputs
//! driven by it, and seeded time-domain realizations for the non-linear model.
//!
//! **Convention.** `Φ_w(ω)` is one-sided in the circular frequency `ω` (rad/s) seen by the wing
//! flying at `U` through frozen turbulence (Taylor's hypothesis, spatial frequency `Ω = ω/U`):
//! `∫₀^∞ Φ_w(ω) dω = σ_w²`. With the time scale `τ = L/U`,
//!
//! * von Kármán: `Φ_w = σ_w² τ/π (1 + 8/3 (a τ ω)²) / (1 + (a τ ω)²)^{11/6}`, `a = 1.339`;
//! * Dryden: `Φ_w = σ_w² τ/π (1 + 3 (τ ω)²) / (1 + (τ ω)²)²`
//!
//! (MIL-HDBK-1797, §3.7 and Appendix A: the vertical component; MIL-F-8785C §3.7.2; CS-25
//! AMC 25.341(b) uses von Kármán with `L = 2500 ft`). `a` is `∫₀^∞ (1 + 8/3 x²)(1 + x²)^{−11/6}
//! dx / π = 1.33898…` (from Γ functions), the value that makes the variance exactly `σ_w²`; the
//! handbook rounds it to 1.339.
//!
//! **Output spectra.** `Φ_y(ω) = |H_y(iω)|² Φ_w(ω)` with `H(iω) = C (iωI − A)⁻¹ (B_g + iω B_ġ) +
//! D_g + iω D_ġ`: the gust column and, if the model has it, the `gust_rate` column (the gust's
//! apparent mass). `A` is balanced and reduced once to Hessenberg form `Q H Qᵀ` (Laub, IEEE TAC
//! 26(2), 1981): each frequency then costs one O(n²) Hessenberg solve.
//!
//! **RMS.** The variance `∫₀^∞ Φ_y dω` by the trapezoidal rule in the variable of
//! [`FrequencyGrid::nodes`] (a logarithmic grid with a cluster per lightly damped pole), plus `ω_min Φ_y(ω_min)` below the grid (both spectra are flat there) and
//! the tail above `ω_max`: the band up to `ω_f = max(2 ω_max, 4 max |λ|)` (beyond every pole)
//! by the same rule on [`TAIL_POINTS`] nodes of its own (clustered at the poles there: a
//! resonance above the cut-off carries variance), and beyond `ω_f` from the asymptotic slope
//! `Φ_y ∝ ω^p` measured between `ω_f` and `2 ω_f`: `ω_f Φ_y(ω_f)/(−p − 1)` if `p < −1`, else
//! the variance diverges (an output with a direct feed-through of the gust rate, whose variance
//! is infinite for both spectra) and only the part below `ω_max` is given, flagged. The
//! quadrature error is estimated as `|T_h − T_2h|/3` (the trapezoidal rule on every other node)
//! on the grid and on the band, plus the low-end rectangle's `ω_min |ΔΦ_y|`, plus the whole
//! piece beyond `ω_f` (a model, not a quadrature).
//!
//! **Realizations.** A stationary Gaussian process of period `T` with the spectrum sampled at
//! the lines `ω_k = 2πk/T ≤ ω_max`: `w(t) = Σ_k a_k cos ω_k t + b_k sin ω_k t` with `a_k, b_k`
//! independent normal of variance `Φ_w(ω_k) 2π/T` (the spectral representation; Shinozuka &
//! Deodatis, Appl. Mech. Rev. 44(4), 1991, with Gaussian rather than fixed amplitudes so that
//! the record is Gaussian and its sample variance has a known spread). The same for both spectra
//! (no rational filter is needed). It is evaluated by an inverse FFT on `M ≥ 8 K` points per
//! period (value and exact rate at the nodes) and interpolated by cubic Hermite polynomials
//! (relative error below 1e-3 at `ω_max`, far less below). The coefficients come from
//! SplitMix64 (Steele, Lea & Flood, OOPSLA 2014) seeded by the user's seed, through the
//! Box–Muller transform: the same seed gives the same record.

use std::f64::consts::PI;

use nalgebra::Complex;

use super::linearize::StateSpace;
use crate::error::InputError;
use crate::text::short;

/// One foot (m).
pub const FOOT: f64 = 0.3048;
/// The von Kármán scale length of CS-25 (AMC 25.341(b)) and MIL-HDBK-1797 above 2000 ft:
/// 2500 ft (m).
pub const VON_KARMAN_SCALE: f64 = 2500.0 * FOOT;
/// The Dryden scale length of MIL-F-8785C above 2000 ft: 1750 ft (m).
pub const DRYDEN_SCALE: f64 = 1750.0 * FOOT;
/// The von Kármán constant `a` (exact to double precision; 1.339 in the handbooks).
pub const VON_KARMAN_A: f64 = 1.338_985_279_065_279_6;

/// The spectrum of the vertical gust velocity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "kebab-case"))]
pub enum Spectrum {
    /// von Kármán's: `Φ ∝ ω^{−5/3}` at high frequency, as measured turbulence.
    VonKarman,
    /// Dryden's: rational, `Φ ∝ ω^{−2}` at high frequency.
    Dryden,
}

impl Spectrum {
    /// The case file's word.
    pub fn name(&self) -> &'static str {
        match self {
            Spectrum::VonKarman => "von-karman",
            Spectrum::Dryden => "dryden",
        }
    }

    /// The handbooks' scale length at altitude (m): [`VON_KARMAN_SCALE`], [`DRYDEN_SCALE`].
    pub fn default_scale_length(&self) -> f64 {
        match self {
            Spectrum::VonKarman => VON_KARMAN_SCALE,
            Spectrum::Dryden => DRYDEN_SCALE,
        }
    }
}

/// Continuous vertical turbulence: a spectrum, its intensity and scale length.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Turbulence {
    /// Which spectrum.
    pub spectrum: Spectrum,
    /// RMS vertical gust velocity `σ_w` (m/s).
    pub intensity: f64,
    /// Scale length `L` (m).
    pub scale_length: f64,
}

impl Turbulence {
    /// `spectrum` at intensity `σ_w` with its default scale length.
    pub fn new(spectrum: Spectrum, intensity: f64) -> Self {
        Self {
            spectrum,
            intensity,
            scale_length: spectrum.default_scale_length(),
        }
    }

    /// Check the intensity and scale length; errors name `{field}.intensity`,
    /// `{field}.scale_length`.
    ///
    /// # Errors
    /// A value that is not finite and positive, or outside the accepted magnitudes.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        for (key, v, what) in [
            (
                "intensity",
                self.intensity,
                "RMS vertical gust velocity (m/s)",
            ),
            ("scale_length", self.scale_length, "scale length (m)"),
        ] {
            let name = crate::field(field, key);
            if !(v.is_finite() && v > 0.0) {
                return Err(InputError::new(
                    name,
                    format!("must be a finite positive {what}, got {}", short(v)),
                ));
            }
            crate::magnitude::check(&name, "", v)?;
        }
        Ok(())
    }

    /// `Φ_w(ω)` (m²/s² per rad/s), one-sided in `ω` (rad/s) at the speed `speed` (m/s):
    /// `∫₀^∞ Φ_w dω = σ_w²`.
    pub fn psd(&self, omega: f64, speed: f64) -> f64 {
        let tau = self.scale_length / speed;
        let s2 = self.intensity * self.intensity;
        let x = tau * omega;
        match self.spectrum {
            Spectrum::Dryden => s2 * tau / PI * (1.0 + 3.0 * x * x) / (1.0 + x * x).powi(2),
            Spectrum::VonKarman => {
                let y = (VON_KARMAN_A * x).powi(2);
                s2 * tau / PI * (1.0 + 8.0 / 3.0 * y) / (1.0 + y).powf(11.0 / 6.0)
            }
        }
    }
}

/// The frequency response of a linear model's outputs to its gust input (and the gust's rate,
/// if it is an input), evaluated in O(n²) per frequency on the Hessenberg form of `A`.
#[derive(Debug, Clone)]
pub struct GustResponse {
    n: usize,
    /// The Hessenberg form of the balanced `A`, row-major.
    h: Vec<f64>,
    /// `C S Q` (outputs × n, row-major), `S` the balancing scales.
    cq: Vec<f64>,
    /// `Qᵀ S⁻¹ B` of the gust and of its rate.
    b_gust: Vec<f64>,
    b_rate: Vec<f64>,
    d_gust: Vec<f64>,
    d_rate: Vec<f64>,
    work: Vec<Complex<f64>>,
    rhs: Vec<Complex<f64>>,
}

impl GustResponse {
    /// The response of `model`'s outputs to its input `gust` (and `gust_rate`, if present).
    ///
    /// # Errors
    /// The model has no `gust` input (named `{field}.inputs`).
    pub fn new(model: &StateSpace, field: &str) -> Result<Self, InputError> {
        let column = |name: &str| model.inputs.iter().position(|s| s.name == name);
        let gust = column("gust").ok_or_else(|| {
            InputError::new(
                crate::field(field, "inputs"),
                "the response to turbulence needs the input \"gust\"",
            )
        })?;
        let rate = column("gust_rate");
        let n = model.a.nrows();
        let mut a = model.a.clone();
        let scales = super::balance::balance_scales(&mut a);
        let (q, h) = a.hessenberg().unpack();
        let mut hv = vec![0.0; n * n];
        for i in 0..n {
            for j in i.saturating_sub(1)..n {
                hv[i * n + j] = h[(i, j)];
            }
        }
        let p = model.c.nrows();
        let mut cs = model.c.clone();
        for j in 0..n {
            cs.column_mut(j).scale_mut(scales[j]);
        }
        let cq_m = &cs * &q;
        let mut cq = vec![0.0; p * n];
        for i in 0..p {
            for j in 0..n {
                cq[i * n + j] = cq_m[(i, j)];
            }
        }
        let projected = |k: Option<usize>| -> Vec<f64> {
            let Some(k) = k else { return vec![0.0; n] };
            let sb: nalgebra::DVector<f64> =
                nalgebra::DVector::from_fn(n, |i, _| model.b[(i, k)] / scales[i]);
            (q.transpose() * sb).iter().copied().collect()
        };
        let feed = |k: Option<usize>| -> Vec<f64> {
            k.map_or(vec![0.0; p], |k| {
                model.d.column(k).iter().copied().collect()
            })
        };
        Ok(Self {
            n,
            h: hv,
            cq,
            b_gust: projected(Some(gust)),
            b_rate: projected(rate),
            d_gust: feed(Some(gust)),
            d_rate: feed(rate),
            work: vec![Complex::new(0.0, 0.0); n * n],
            rhs: vec![Complex::new(0.0, 0.0); n],
        })
    }

    /// Number of outputs.
    pub fn n_outputs(&self) -> usize {
        self.d_gust.len()
    }

    /// `H_y(iω)` of every output into `out`.
    pub fn at(&mut self, omega: f64, out: &mut [Complex<f64>]) {
        let n = self.n;
        let iw = Complex::new(0.0, omega);
        let (w, r) = (&mut self.work, &mut self.rhs);
        for i in 0..n {
            let lo = i.saturating_sub(1);
            for j in lo..n {
                w[i * n + j] = Complex::new(-self.h[i * n + j], 0.0);
            }
            w[i * n + i] += iw;
            r[i] = Complex::new(self.b_gust[i], omega * self.b_rate[i]);
        }
        // Gaussian elimination with partial pivoting on the one subdiagonal.
        for k in 0..n.saturating_sub(1) {
            let (top, below) = w.split_at_mut((k + 1) * n);
            let row_k = &mut top[k * n..];
            let row_next = &mut below[..n];
            if row_next[k].norm_sqr() > row_k[k].norm_sqr() {
                row_k[k..].swap_with_slice(&mut row_next[k..]);
                r.swap(k, k + 1);
            }
            let pivot = row_k[k];
            if pivot == Complex::new(0.0, 0.0) {
                continue;
            }
            let l = row_next[k] / pivot;
            if l != Complex::new(0.0, 0.0) {
                for j in k + 1..n {
                    row_next[j] -= l * row_k[j];
                }
                r[k + 1] = r[k + 1] - l * r[k];
            }
        }
        for i in (0..n).rev() {
            let mut s = r[i];
            for j in i + 1..n {
                s -= w[i * n + j] * r[j];
            }
            r[i] = s / w[i * n + i];
        }
        for (k, o) in out.iter_mut().enumerate() {
            let row = &self.cq[k * n..(k + 1) * n];
            let mut s = Complex::new(self.d_gust[k], omega * self.d_rate[k]);
            for (c, z) in row.iter().zip(r.iter()) {
                s += z * *c;
            }
            *o = s;
        }
    }
}

/// How the frequencies of the output spectra are chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FrequencyGrid {
    /// Number of frequencies (at least 16).
    pub points: usize,
    /// Lowest frequency (rad/s).
    pub min_frequency: f64,
    /// Highest frequency (rad/s), above `min_frequency`.
    pub max_frequency: f64,
}

/// Default number of frequencies of the output spectra.
pub const DEFAULT_POINTS: usize = 500;
/// Frequencies clustered around each lightly damped pole (damping ratio below
/// [`CLUSTER_DAMPING`]), whose peak is narrower than the logarithmic grid's spacing.
pub const CLUSTER_POINTS: usize = 16;
/// Damping ratio below which a pole gets [`CLUSTER_POINTS`] of its own.
pub const CLUSTER_DAMPING: f64 = 0.1;

impl FrequencyGrid {
    /// The default grid at `speed` for a turbulence of scale length `scale_length` on a wing
    /// whose widest semi-chord is `semichord`: [`DEFAULT_POINTS`] frequencies from `1e-3 U/L`
    /// (the spectra are flat below `U/L`) to `2 U/b` (reduced frequency 2 at the widest strip:
    /// beyond it a gust uniform over the chord is a poor model of turbulence).
    pub fn default_for(speed: f64, scale_length: f64, semichord: f64) -> Self {
        Self {
            points: DEFAULT_POINTS,
            min_frequency: 1e-3 * speed / scale_length,
            max_frequency: 2.0 * speed / semichord,
        }
    }

    /// Check the grid; errors name `{field}.frequencies`, `{field}.min_frequency`,
    /// `{field}.max_frequency`.
    ///
    /// # Errors
    /// Fewer than 16 or more than 1 000 000 points, bounds not finite and positive, or not
    /// increasing.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        if !(16..=1_000_000).contains(&self.points) {
            return Err(InputError::new(
                crate::field(field, "frequencies"),
                format!("must be between 16 and 1000000, got {}", self.points),
            ));
        }
        for (key, v) in [
            ("min_frequency", self.min_frequency),
            ("max_frequency", self.max_frequency),
        ] {
            let name = crate::field(field, key);
            if !(v.is_finite() && v > 0.0) {
                return Err(InputError::new(
                    name,
                    format!(
                        "must be a finite positive frequency (rad/s), got {}",
                        short(v)
                    ),
                ));
            }
            crate::magnitude::check(&name, "", v)?;
        }
        if self.max_frequency <= self.min_frequency {
            return Err(InputError::new(
                crate::field(field, "max_frequency"),
                format!(
                    "must be above min_frequency = {} rad/s, got {}",
                    short(self.min_frequency),
                    short(self.max_frequency)
                ),
            ));
        }
        Ok(())
    }

    /// The frequencies (rad/s, increasing, `points` of them) and the quadrature's `dω/ds` at
    /// each: the nodes are evenly spaced in `s = F(ω)`, the cumulative of the point density
    /// `ρ(ω) = N_b/(ω ln(ω_max/ω_min)) + Σ_p (N_p/π) σ_p/((ω − ω_p)² + σ_p²)`: a logarithmic
    /// grid of `N_b` points plus [`CLUSTER_POINTS`] per lightly damped pole `λ_p = −σ_p + iω_p`
    /// inside the bounds (the lightest first, at most half the points), so that a resonance
    /// peak (a Lorentzian of half-width `σ_p`) is smooth in `s` and the trapezoidal rule in
    /// `s` integrates it at the rate it integrates the rest.
    pub fn nodes(&self, poles: &[Complex<f64>]) -> (Vec<f64>, Vec<f64>) {
        let (lo, hi) = (self.min_frequency, self.max_frequency);
        let mut peaks: Vec<(f64, f64)> = poles
            .iter()
            .filter(|p| p.im > 0.0 && p.re < 0.0 && p.im > lo && p.im < hi)
            .map(|p| (-p.re, p.im))
            .filter(|(s, w)| s / (s * s + w * w).sqrt() < CLUSTER_DAMPING)
            .collect();
        peaks.sort_by(|a, b| (a.0 / a.1).total_cmp(&(b.0 / b.1)));
        peaks.truncate((self.points / 2) / CLUSTER_POINTS);
        let np = CLUSTER_POINTS as f64;
        let nb = (self.points - 1) as f64 - np * peaks.len() as f64;
        let log = (hi / lo).ln();
        let cumulative = |w: f64| -> f64 {
            nb * (w / lo).ln() / log
                + peaks
                    .iter()
                    .map(|(s, c)| {
                        np / std::f64::consts::PI * (((w - c) / s).atan() - ((lo - c) / s).atan())
                    })
                    .sum::<f64>()
        };
        let density = |w: f64| -> f64 {
            nb / (w * log)
                + peaks
                    .iter()
                    .map(|(s, c)| np / std::f64::consts::PI * s / ((w - c).powi(2) + s * s))
                    .sum::<f64>()
        };
        let total = cumulative(hi);
        let n = self.points;
        let mut w = Vec::with_capacity(n);
        let mut jacobian = Vec::with_capacity(n);
        let (mut a, b) = (lo, hi);
        for j in 0..n {
            let target = total * j as f64 / (n - 1) as f64;
            let x = if j == 0 {
                lo
            } else if j == n - 1 {
                hi
            } else {
                // Bisection in ln ω from the previous node (F is increasing).
                let (mut l, mut r) = (a.ln(), b.ln());
                for _ in 0..100 {
                    let m = 0.5 * (l + r);
                    if cumulative(m.exp()) < target {
                        l = m;
                    } else {
                        r = m;
                    }
                    if r - l < 1e-15 * (1.0 + l.abs()) {
                        break;
                    }
                }
                (0.5 * (l + r)).exp()
            };
            a = x;
            w.push(x);
            // dω/ds with s scaled so that the nodes are one unit apart.
            jacobian.push(total / (n - 1) as f64 / density(x));
        }
        (w, jacobian)
    }
}

/// The spectra and RMS of a linear model's outputs in turbulence.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct GustSpectra {
    /// The frequencies (rad/s), increasing.
    pub frequencies: Vec<f64>,
    /// `Φ_w` at them (m²/s² per rad/s).
    pub gust_psd: Vec<f64>,
    /// `Φ_y` per output, at the frequencies (unit² per rad/s).
    pub psd: Vec<Vec<f64>>,
    /// RMS per output: the square root of the variance below the grid, on it and (where it
    /// converges) above it.
    pub rms: Vec<f64>,
    /// Estimated quadrature error of each output's variance (unit²).
    pub variance_error: Vec<f64>,
    /// Each output's variance above `max_frequency` included in `rms` (unit²); `None` where the
    /// variance diverges with the cut-off (`rms` is then the part below it).
    pub tail: Vec<Option<f64>>,
    /// The asymptotic exponent `p` of `Φ_y ∝ ω^p`, per output, measured beyond every pole
    /// (`4 max |λ|`): `−5/3` (von Kármán) or `−2` (Dryden) for an output that follows the gust,
    /// steeper for one that filters it, above `−1` where the gust's rate feeds through.
    pub tail_slope: Vec<f64>,
    /// The gust's RMS over the same grid and tails (m/s): `σ_w` up to the quadrature error.
    pub gust_rms: f64,
}

/// The output spectra of `model` in `turbulence` at `speed` on `grid` (its poles `poles` place
/// the clustered frequencies).
///
/// # Errors
/// The model has no `gust` input.
pub fn gust_spectra(
    model: &StateSpace,
    poles: &[Complex<f64>],
    turbulence: &Turbulence,
    speed: f64,
    grid: &FrequencyGrid,
    field: &str,
) -> Result<GustSpectra, InputError> {
    let mut response = GustResponse::new(model, field)?;
    let p = response.n_outputs();
    let (frequencies, jacobian) = grid.nodes(poles);
    let mut h = vec![Complex::new(0.0, 0.0); p];
    let mut psd = vec![Vec::with_capacity(frequencies.len()); p];
    let gust_psd: Vec<f64> = frequencies
        .iter()
        .map(|&w| turbulence.psd(w, speed))
        .collect();
    for (&w, &pw) in frequencies.iter().zip(&gust_psd) {
        response.at(w, &mut h);
        for (k, hk) in h.iter().enumerate() {
            psd[k].push(hk.norm_sqr() * pw);
        }
    }
    // The asymptotic slope, between ω_far and 2 ω_far beyond every pole (a resonance just
    // above ω_max would make a local slope meaningless).
    let top = grid.max_frequency;
    let far = poles
        .iter()
        .map(|p| p.norm())
        .fold(2.0 * top, |a, b| a.max(4.0 * b));
    response.at(far, &mut h);
    let at_far: Vec<f64> = h
        .iter()
        .map(|hk| hk.norm_sqr() * turbulence.psd(far, speed))
        .collect();
    response.at(2.0 * far, &mut h);
    let slopes: Vec<f64> = h
        .iter()
        .zip(&at_far)
        .map(|(hk, &f)| local_slope(f, hk.norm_sqr() * turbulence.psd(2.0 * far, speed)))
        .collect();
    // The band above ω_max up to ω_far, on a grid of its own clustered at the poles there (a
    // resonance above the cut-off carries variance that no slope at ω_max sees).
    let band = FrequencyGrid {
        points: TAIL_POINTS,
        min_frequency: top,
        max_frequency: far,
    };
    let (tail_w, tail_jacobian) = band.nodes(poles);
    let mut tail_psd = vec![Vec::with_capacity(TAIL_POINTS); p];
    for &w in &tail_w {
        response.at(w, &mut h);
        let pw = turbulence.psd(w, speed);
        for (k, hk) in h.iter().enumerate() {
            tail_psd[k].push(hk.norm_sqr() * pw);
        }
    }
    let (mut rms, mut variance_error, mut tail, mut tail_slope) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (k, phi) in psd.iter().enumerate() {
        let above = Tail {
            jacobian: &tail_jacobian,
            phi: &tail_psd[k],
            far,
            slope: slopes[k],
        };
        let v = variance(&frequencies, &jacobian, phi, &above);
        rms.push(v.variance.max(0.0).sqrt());
        variance_error.push(v.error);
        tail.push(v.tail);
        tail_slope.push(slopes[k]);
    }
    let gust_tail: Vec<f64> = tail_w.iter().map(|&w| turbulence.psd(w, speed)).collect();
    let gust = variance(
        &frequencies,
        &jacobian,
        &gust_psd,
        &Tail {
            jacobian: &tail_jacobian,
            phi: &gust_tail,
            far,
            slope: local_slope(turbulence.psd(far, speed), turbulence.psd(2.0 * far, speed)),
        },
    );
    Ok(GustSpectra {
        frequencies,
        gust_psd,
        psd,
        rms,
        variance_error,
        tail,
        tail_slope,
        gust_rms: gust.variance.sqrt(),
    })
}

/// The exponent `p` of `Φ ∝ ω^p` from `Φ` at `ω` and `2ω` (`−∞` where either is zero).
fn local_slope(at: f64, above: f64) -> f64 {
    if at > 0.0 && above > 0.0 {
        (above / at).ln() / 2f64.ln()
    } else {
        f64::NEG_INFINITY
    }
}

/// Frequencies of the band between `ω_max` and `ω_f` that the tail is integrated on.
pub const TAIL_POINTS: usize = 64;

/// A variance by quadrature (module documentation).
struct Variance {
    variance: f64,
    error: f64,
    tail: Option<f64>,
}

/// The spectrum above the grid: on the band `ω_max … ω_f` (nodes evenly spaced in `s`,
/// `dω/ds` = `jacobian`), then `∝ ω^slope` beyond `far`.
struct Tail<'a> {
    jacobian: &'a [f64],
    phi: &'a [f64],
    far: f64,
    slope: f64,
}

/// The trapezoidal rule in `s` on unit spacing and on every other node, of `phi · jacobian`.
fn trapezoids(jacobian: &[f64], phi: &[f64]) -> (f64, f64) {
    let n = phi.len();
    let rule = |step: usize| -> f64 {
        let mut idx: Vec<usize> = (0..n).step_by(step).collect();
        if *idx.last().unwrap_or(&0) != n - 1 {
            idx.push(n - 1);
        }
        idx.windows(2)
            .map(|p| {
                let h = (p[1] - p[0]) as f64;
                0.5 * h * (phi[p[0]] * jacobian[p[0]] + phi[p[1]] * jacobian[p[1]])
            })
            .sum()
    };
    (rule(1), rule(2))
}

/// `∫₀^∞ Φ dω` from `Φ` at the nodes `w` (evenly spaced in `s`, `dω/ds` = `jacobian`) and
/// the spectrum above them.
fn variance(w: &[f64], jacobian: &[f64], phi: &[f64], above: &Tail) -> Variance {
    let (fine, coarse) = trapezoids(jacobian, phi);
    let low = w[0] * phi[0];
    let low_error = w[0] * (phi[1] - phi[0]).abs();
    let last = above.phi[above.phi.len() - 1];
    let tail = if above.slope < -1.0 || last == 0.0 {
        let (band, band_coarse) = trapezoids(above.jacobian, above.phi);
        let beyond = if last == 0.0 {
            0.0
        } else {
            above.far * last / (-above.slope - 1.0)
        };
        // The band's quadrature error and the asymptotic piece beyond ω_f, whole.
        Some((band + beyond, (band - band_coarse).abs() / 3.0 + beyond))
    } else {
        None
    };
    Variance {
        variance: low + fine + tail.map_or(0.0, |t| t.0),
        error: (fine - coarse).abs() / 3.0 + low_error + tail.map_or(0.0, |t| t.1),
        tail: tail.map(|t| t.0),
    }
}

/// One line of a realization: `a cos ωt + b sin ωt` (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// `ω` (rad/s).
    pub omega: f64,
    /// Cosine coefficient (m/s).
    pub a: f64,
    /// Sine coefficient (m/s).
    pub b: f64,
}

/// A seeded realization of continuous turbulence: a vertical gust velocity history of period
/// `period` (module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Realization {
    /// The record's period `T` (s).
    pub period: f64,
    /// The spectral lines `ω_k = 2πk/T`, `k = 1 … K`, `ω_K ≤ max_frequency`.
    pub lines: Vec<Line>,
    /// The expected variance of the record, `Σ Φ_w(ω_k) 2π/T` (m²/s²).
    pub variance: f64,
    step: f64,
    values: Vec<f64>,
    rates: Vec<f64>,
}

impl Realization {
    /// A realization of `turbulence` at `speed` with period `period` (s) and the lines up to
    /// `max_frequency` (rad/s), from `seed`; errors name `{field}.period`,
    /// `{field}.max_frequency`.
    ///
    /// # Errors
    /// A period or frequency that is not finite and positive, no line below `max_frequency`
    /// (`2π/period` above it), more than 2²² lines.
    pub fn new(
        turbulence: &Turbulence,
        speed: f64,
        seed: u64,
        period: f64,
        max_frequency: f64,
        field: &str,
    ) -> Result<Self, InputError> {
        let bad = |key: &str, what: &str, v: f64| {
            InputError::new(
                crate::field(field, key),
                format!("must be a finite positive {what}, got {}", short(v)),
            )
        };
        if !(period.is_finite() && period > 0.0) {
            return Err(bad("period", "duration (s)", period));
        }
        if !(max_frequency.is_finite() && max_frequency > 0.0) {
            return Err(bad("max_frequency", "frequency (rad/s)", max_frequency));
        }
        let dw = 2.0 * PI / period;
        let k_max = (max_frequency / dw).floor();
        if k_max < 1.0 || k_max > (1u64 << 22) as f64 {
            return Err(InputError::new(
                crate::field(field, "max_frequency"),
                format!(
                    "gives {k_max} spectral lines 2π k/T up to it over a period of {} s: \
                     it must allow between 1 and 4194304",
                    short(period)
                ),
            ));
        }
        let k_max = k_max as usize;
        let mut rng = SplitMix64(seed);
        let lines: Vec<Line> = (1..=k_max)
            .map(|k| {
                let omega = k as f64 * dw;
                let s = (turbulence.psd(omega, speed) * dw).sqrt();
                let (g1, g2) = rng.normal_pair();
                Line {
                    omega,
                    a: s * g1,
                    b: s * g2,
                }
            })
            .collect();
        let variance = lines
            .iter()
            .map(|l| turbulence.psd(l.omega, speed) * dw)
            .sum();
        // w(t_j) = Re Σ_k (a_k − i b_k) e^{i k 2π j/M}, w' = Re Σ_k iω_k (a_k − i b_k) e^{…}.
        let m = (8 * k_max).next_power_of_two().max(16);
        let mut v = vec![Complex::new(0.0, 0.0); m];
        let mut r = vec![Complex::new(0.0, 0.0); m];
        for (k, l) in lines.iter().enumerate() {
            let c = Complex::new(l.a, -l.b);
            v[k + 1] = c;
            r[k + 1] = c * Complex::new(0.0, l.omega);
        }
        inverse_fft(&mut v);
        inverse_fft(&mut r);
        Ok(Self {
            period,
            lines,
            variance,
            step: period / m as f64,
            values: v.iter().map(|z| z.re).collect(),
            rates: r.iter().map(|z| z.re).collect(),
        })
    }

    /// `(w, ẇ)` at `t` (s; periodic), by cubic Hermite interpolation between the nodes.
    pub fn value_and_rate(&self, t: f64) -> (f64, f64) {
        let m = self.values.len();
        let x = t.rem_euclid(self.period) / self.step;
        let j = (x.floor() as usize).min(m - 1);
        let s = x - j as f64;
        let j1 = (j + 1) % m;
        let h = self.step;
        let (p0, p1) = (self.values[j], self.values[j1]);
        let (m0, m1) = (self.rates[j] * h, self.rates[j1] * h);
        let (s2, s3) = (s * s, s * s * s);
        let value = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * p1
            + (s3 - s2) * m1;
        let rate = ((6.0 * s2 - 6.0 * s) * p0
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (-6.0 * s2 + 6.0 * s) * p1
            + (3.0 * s2 - 2.0 * s) * m1)
            / h;
        (value, rate)
    }

    /// The sum of the lines at `t` (the reference of the interpolation; O(K)).
    pub fn exact(&self, t: f64) -> f64 {
        self.lines
            .iter()
            .map(|l| {
                let (s, c) = (l.omega * t).sin_cos();
                l.a * c + l.b * s
            })
            .sum()
    }
}

/// SplitMix64: a 64-bit generator with a 64-bit state, every seed valid.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in (0, 1]: 53 random bits.
    fn uniform(&mut self) -> f64 {
        ((self.next() >> 11) + 1) as f64 / (1u64 << 53) as f64
    }

    /// Two independent standard normal numbers (Box–Muller).
    fn normal_pair(&mut self) -> (f64, f64) {
        let (u1, u2) = (self.uniform(), self.uniform());
        let r = (-2.0 * u1.ln()).sqrt();
        let (s, c) = (2.0 * PI * u2).sin_cos();
        (r * c, r * s)
    }
}

/// In place `x_j ← Σ_k x_k e^{+2πi jk/M}` (unnormalized), `M` a power of two (iterative
/// radix-2 Cooley–Tukey).
fn inverse_fft(x: &mut [Complex<f64>]) {
    let m = x.len();
    let bits = m.trailing_zeros();
    for i in 0..m {
        let j = i.reverse_bits() >> (usize::BITS - bits);
        if j > i {
            x.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= m {
        let angle = 2.0 * PI / len as f64;
        let root = Complex::new(angle.cos(), angle.sin());
        for start in (0..m).step_by(len) {
            let mut w = Complex::new(1.0, 0.0);
            for k in 0..len / 2 {
                let u = x[start + k];
                let v = x[start + k + len / 2] * w;
                x[start + k] = u + v;
                x[start + k + len / 2] = u - v;
                w *= root;
            }
        }
        len *= 2;
    }
}

/// A dense `(iωI − A)⁻¹` solve of the gust response (tests: the reference of the Hessenberg
/// solve).
#[cfg(test)]
pub(crate) fn dense_response(model: &StateSpace, omega: f64) -> Vec<Complex<f64>> {
    let n = model.a.nrows();
    let gust = model.inputs.iter().position(|s| s.name == "gust").unwrap();
    let rate = model.inputs.iter().position(|s| s.name == "gust_rate");
    let iw = Complex::new(0.0, omega);
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| {
        let d = if i == j { iw } else { Complex::new(0.0, 0.0) };
        d - Complex::new(model.a[(i, j)], 0.0)
    });
    let b = nalgebra::DVector::from_fn(n, |i, _| {
        Complex::new(
            model.b[(i, gust)],
            rate.map_or(0.0, |r| omega * model.b[(i, r)]),
        )
    });
    let x = m.lu().solve(&b).unwrap();
    (0..model.c.nrows())
        .map(|k| {
            let mut s = Complex::new(
                model.d[(k, gust)],
                rate.map_or(0.0, |r| omega * model.d[(k, r)]),
            );
            for j in 0..n {
                s += x[j] * model.c[(k, j)];
            }
            s
        })
        .collect()
}

#[cfg(test)]
#[path = "turbulence_tests.rs"]
mod tests;
