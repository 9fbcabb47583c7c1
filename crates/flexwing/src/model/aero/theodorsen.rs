//! Theodorsen's function `C(k) = H₁⁽²⁾(k) / (H₁⁽²⁾(k) + i H₀⁽²⁾(k))`, `H_n⁽²⁾ = J_n − i Y_n`
//! (Theodorsen, NACA TR 496, 1935; Hodges & Pierce §5.3), with the Bessel functions of the first
//! and second kind of orders 0 and 1 computed here: the ascending series for `x ≤ 12`
//! (Abramowitz & Stegun 9.1.10–9.1.11; the largest term is below 5e3, so at most 4 digits cancel)
//! and Hankel's asymptotic expansion beyond (A&S 9.2.5–9.2.10, summed to its smallest term, below
//! 1e-10 relative at `x = 12`). The Wronskian `J₁Y₀ − J₀Y₁ = 2/(πx)` checks both (tests).

use nalgebra::Complex;

const EULER_GAMMA: f64 = 0.577_215_664_901_532_9;
const SERIES_LIMIT: f64 = 12.0;

/// `(J₀(x), J₁(x), Y₀(x), Y₁(x))` for `x > 0`.
pub(crate) fn bessel01(x: f64) -> (f64, f64, f64, f64) {
    if x <= SERIES_LIMIT {
        series(x)
    } else {
        asymptotic(x)
    }
}

fn series(x: f64) -> (f64, f64, f64, f64) {
    let z = 0.25 * x * x; // x²/4
    let half = 0.5 * x;
    // J₀ = Σ (−z)^k/(k!)², J₁ = (x/2) Σ (−z)^k/(k!(k+1)!)
    // Y₀ = (2/π)(ln(x/2) + γ) J₀ + (2/π) Σ_{k≥1} (−1)^{k+1} H_k z^k/(k!)²
    // Y₁ = (2/π) ln(x/2) J₁ − 2/(πx) − (1/π)(x/2) Σ (ψ(k+1) + ψ(k+2)) (−z)^k/(k!(k+1)!)
    let (mut j0, mut j1s, mut y0s, mut y1s) = (0.0, 0.0, 0.0, 0.0);
    let mut t0 = 1.0; // (−z)^k/(k!)²
    let mut t1 = 1.0; // (−z)^k/(k!(k+1)!)
    let mut harmonic = 0.0; // H_k
    for k in 0..200 {
        if k > 0 {
            let kf = k as f64;
            t0 *= -z / (kf * kf);
            t1 *= -z / (kf * (kf + 1.0));
            harmonic += 1.0 / kf;
        }
        j0 += t0;
        j1s += t1;
        y0s -= harmonic * t0; // (−1)^{k+1} H_k z^k/(k!)² = −H_k t0
        let psi_sum = 2.0 * (harmonic - EULER_GAMMA) + 1.0 / (k as f64 + 1.0);
        y1s += psi_sum * t1;
        if k > 2 && t0.abs() < 1e-18 * j0.abs().max(1e-300) && t1.abs() < 1e-18 {
            break;
        }
    }
    let pi = std::f64::consts::PI;
    let j1 = half * j1s;
    let ln = half.ln();
    let y0 = 2.0 / pi * ((ln + EULER_GAMMA) * j0 + y0s);
    let y1 = 2.0 / pi * ln * j1 - 2.0 / (pi * x) - half / pi * y1s;
    (j0, j1, y0, y1)
}

/// Hankel's expansion: `J_ν = √(2/(πx)) (P cos χ − Q sin χ)`, `Y_ν = √(2/(πx)) (P sin χ + Q cos χ)`,
/// `χ = x − (ν/2 + ¼)π`, summed until the terms stop decreasing.
fn asymptotic(x: f64) -> (f64, f64, f64, f64) {
    let pi = std::f64::consts::PI;
    let amp = (2.0 / (pi * x)).sqrt();
    let mut out = [0.0; 4];
    for nu in 0..2 {
        let mu = 4.0 * (nu * nu) as f64;
        let (mut p, mut q) = (1.0, 0.0);
        let mut a = 1.0; // a_k = Π (μ − (2j−1)²) / (k! (8x)^k)
        let mut last = f64::INFINITY;
        for k in 1..60 {
            let odd = (2 * k - 1) as f64;
            a *= (mu - odd * odd) / (k as f64 * 8.0 * x);
            if a.abs() >= last || a == 0.0 {
                break;
            }
            last = a.abs();
            let sign = if (k / 2) % 2 == 0 { 1.0 } else { -1.0 };
            if k % 2 == 0 {
                p += sign * a;
            } else {
                q += sign * a;
            }
        }
        let chi = x - (0.5 * nu as f64 + 0.25) * pi;
        let (s, c) = chi.sin_cos();
        out[nu] = amp * (p * c - q * s);
        out[2 + nu] = amp * (p * s + q * c);
    }
    (out[0], out[1], out[2], out[3])
}

/// Theodorsen's function `C(k)` for a reduced frequency `k = ω b / U > 0`; `C(0) = 1`.
pub fn theodorsen(k: f64) -> Complex<f64> {
    if k <= 0.0 {
        return Complex::new(1.0, 0.0);
    }
    let (j0, j1, y0, y1) = bessel01(k);
    let h1 = Complex::new(j1, -y1);
    let h0 = Complex::new(j0, -y0);
    h1 / (h1 + Complex::new(0.0, 1.0) * h0)
}

/// `C(k)` and its derivative `dC/dk` for `k > 0` (the p-k method's Newton iteration): with the
/// Hankel functions' `H₀' = −H₁` and `H₁' = H₀ − H₁/k` (A&S 9.1.27–9.1.28),
/// `C' = i (H₀² − H₀ H₁/k + H₁²) / (H₁ + i H₀)²`. At `k ≤ 0`, `(1, 0)` (`C'` is singular at 0,
/// like `k ln k`; the p-k iteration does not use it there).
pub fn theodorsen_derivative(k: f64) -> (Complex<f64>, Complex<f64>) {
    if k <= 0.0 {
        return (Complex::new(1.0, 0.0), Complex::new(0.0, 0.0));
    }
    let (j0, j1, y0, y1) = bessel01(k);
    let h1 = Complex::new(j1, -y1);
    let h0 = Complex::new(j0, -y0);
    let i = Complex::new(0.0, 1.0);
    let d = h1 + i * h0;
    (h1 / d, i * (h0 * h0 - h0 * h1 / k + h1 * h1) / (d * d))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `dC/dk` against mpmath at 30 digits (`mp.diff` of `H₁⁽²⁾/(H₁⁽²⁾ + i H₀⁽²⁾)` with
    /// `mp.hankel2`), on both sides of the series/asymptotic split at 12. Tolerance 1e-8 of
    /// `|C'|`: the Bessel functions' error (up to 4 digits cancel in the series, 1e-10 relative
    /// in the asymptotic expansion at 12) over the derivative's size. Central differences of `C`
    /// are worse than this near 12 (1.6e-5 relative at k = 11 with a step 1e-5 k).
    #[test]
    fn theodorsen_derivative_matches_mpmath() {
        for (k, re, im) in [
            (0.01, -1.84405653216631, -3.43986723265412),
            (0.1, -1.35054000822932, -0.479977051191847),
            (0.5, -0.224824757000174, 0.136832546160899),
            (1.0, -0.057953740263657, 0.0709612441615034),
            (4.0, -0.00173701870934441, 0.00728581228202496),
            (11.0, -9.21647338180892e-05, 0.00102221796702188),
            (13.0, -5.61260866926156e-05, 0.000734037647887291),
            (40.0, -1.95023804814886e-06, 7.80610825137268e-05),
        ] {
            let (c, dc) = theodorsen_derivative(k);
            assert_eq!(c, theodorsen(k));
            let want = Complex::new(re, im);
            assert!(
                (dc - want).norm() <= 1e-8 * want.norm(),
                "k = {k}: {dc} vs {want}"
            );
        }
    }

    /// Values of Abramowitz & Stegun, Table 9.1 (x = 1, 5, 10) and the series/asymptotic split.
    #[test]
    fn bessel_functions_match_tabulated_values_and_the_wronskian() {
        let table = [
            // x, J0, J1, Y0, Y1 (A&S Table 9.1, 10 digits)
            (
                1.0,
                0.765_197_686_6,
                0.440_050_585_7,
                0.088_256_964_22,
                -0.781_212_821_3,
            ),
            (
                5.0,
                -0.177_596_771_3,
                -0.327_579_137_6,
                -0.308_517_625_2,
                0.147_863_143_4,
            ),
            (
                10.0,
                -0.245_935_764_5,
                0.043_472_746_17,
                0.055_671_167_28,
                0.249_015_424_2,
            ),
        ];
        for (x, a, b, c, d) in table {
            let (j0, j1, y0, y1) = bessel01(x);
            for (got, want) in [(j0, a), (j1, b), (y0, c), (y1, d)] {
                // The table has 10 significant digits.
                assert!((got - want).abs() < 2e-10, "x = {x}: {got} vs {want}");
            }
        }
        // Wronskian J₁Y₀ − J₀Y₁ = 2/(πx): 1e-12 relative in the series range, 1e-10 beyond (the
        // asymptotic expansion's smallest term at x = 12).
        for i in 1..400 {
            let x = 0.05 * i as f64;
            let (j0, j1, y0, y1) = bessel01(x);
            let w = (j1 * y0 - j0 * y1) * std::f64::consts::PI * x / 2.0;
            assert!((w - 1.0).abs() < 1e-10, "x = {x}: {w}");
        }
    }

    /// Bisplinghoff, Ashley & Halfman, Table 5-1 (F + iG, 4 digits).
    #[test]
    fn theodorsen_function_matches_the_classical_table() {
        for (k, f, g) in [
            (0.1, 0.8319, -0.1723),
            (0.2, 0.7276, -0.1886),
            (0.5, 0.5979, -0.1507),
            (1.0, 0.5394, -0.1003),
        ] {
            let c = theodorsen(k);
            assert!(
                (c.re - f).abs() < 1e-4 && (c.im - g).abs() < 1e-4,
                "k = {k}: {c}"
            );
        }
        // Limits: C → 1 as k → 0, C → ½ as k → ∞.
        assert!((theodorsen(1e-6) - Complex::new(1.0, 0.0)).norm() < 1e-4);
        assert!((theodorsen(200.0) - Complex::new(0.5, 0.0)).norm() < 1e-3);
    }
}
