//! Finite-state lag of the circulatory lift (docs/aeroelastic-model.md §4): per strip
//! `ȧ = (V/b)(H̄ a + B̄ w)`, `w_eff = C̄ a + D̄ w`, nondimensional in the reduced time `s = ∫V dt/b`.
//!
//! * Wagner's function by R. T. Jones' two-term fit (NACA TR 681, 1940):
//!   `φ(s) = 1 − A1 e^{−β1 s} − A2 e^{−β2 s}`, `A = (0.165, 0.335)`, `β = (0.0455, 0.3)`:
//!   `H̄ = −diag β`, `B̄ = 1`, `C̄ = (A1 β1, A2 β2)`, `D̄ = 1 − A1 − A2`.
//! * Peters' finite-state inflow (Peters, Karunamoorthy & Cao, J. Aircraft 32(2), 1995)
//!   `A λ̇ + (V/b) λ = c ẇ`, `λ0 = ½ bᵀλ`, written in `μ = λ − A⁻¹c w` so that no acceleration
//!   appears: `H̄ = −A⁻¹`, `B̄ = −A⁻²c`, `C̄ = −½ bᵀ`, `D̄ = 1 − ½ bᵀA⁻¹c`.
//!
//! The transfer function `T(s̄) = D̄ + C̄ (s̄ I − H̄)⁻¹ B̄` (`s̄ = s b/V`) approximates Theodorsen's
//! `C(k)` at `s̄ = ik`; `T(0) = 1` (no lag in steady state).

use nalgebra::{Complex, DMatrix, DVector};

/// The nondimensional state-space realization of a lag model.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Lag {
    pub(crate) h: DMatrix<f64>,
    pub(crate) b: DVector<f64>,
    pub(crate) c: DVector<f64>,
    pub(crate) d: f64,
}

/// Jones' coefficients of Wagner's function.
pub(crate) const JONES_A: [f64; 2] = [0.165, 0.335];
/// Jones' exponents (per half-chord of travel).
pub(crate) const JONES_BETA: [f64; 2] = [0.0455, 0.3];

impl Lag {
    /// Number of states per strip.
    pub(crate) fn n_states(&self) -> usize {
        self.b.len()
    }

    /// R. T. Jones' two-state approximation of Wagner's function.
    pub(crate) fn jones() -> Self {
        Self {
            h: DMatrix::from_diagonal(&DVector::from_vec(vec![-JONES_BETA[0], -JONES_BETA[1]])),
            b: DVector::from_vec(vec![1.0, 1.0]),
            c: DVector::from_vec(vec![JONES_A[0] * JONES_BETA[0], JONES_A[1] * JONES_BETA[1]]),
            d: 1.0 - JONES_A[0] - JONES_A[1],
        }
    }

    /// Peters' finite-state inflow with `n` states (`n ≥ 1`).
    pub(crate) fn peters(n: usize) -> Self {
        let (a, b, c) = peters_matrices(n);
        let ainv = a.clone().try_inverse().expect("Peters' A is invertible");
        let ainv_c = &ainv * &c;
        Self {
            h: -&ainv,
            b: -(&ainv * &ainv_c),
            c: -0.5 * &b,
            d: 1.0 - 0.5 * b.dot(&ainv_c),
        }
    }

    /// `T(s̄) = D̄ + C̄ (s̄ I − H̄)⁻¹ B̄`.
    pub(crate) fn transfer(&self, s: Complex<f64>) -> Complex<f64> {
        let n = self.n_states();
        let m = DMatrix::from_fn(n, n, |i, j| {
            let v = Complex::new(-self.h[(i, j)], 0.0);
            if i == j {
                v + s
            } else {
                v
            }
        });
        let rhs = self.b.map(|v| Complex::new(v, 0.0));
        let x = m
            .lu()
            .solve(&rhs)
            .unwrap_or_else(|| DVector::from_element(n, Complex::new(f64::NAN, 0.0)));
        let cx: Complex<f64> = (0..n).map(|i| x[i] * self.c[i]).sum();
        cx + self.d
    }

    /// `T'(s̄) = −C̄ (s̄ I − H̄)⁻² B̄`.
    pub(crate) fn transfer_derivative(&self, s: Complex<f64>) -> Complex<f64> {
        let n = self.n_states();
        let m = DMatrix::from_fn(n, n, |i, j| {
            let v = Complex::new(-self.h[(i, j)], 0.0);
            if i == j {
                v + s
            } else {
                v
            }
        });
        let lu = m.lu();
        let rhs = self.b.map(|v| Complex::new(v, 0.0));
        let nan = || DVector::from_element(n, Complex::new(f64::NAN, 0.0));
        let x = lu.solve(&rhs).unwrap_or_else(nan);
        let y = lu.solve(&x).unwrap_or_else(nan);
        -(0..n).map(|i| y[i] * self.c[i]).sum::<Complex<f64>>()
    }
}

/// Peters' `A`, `b`, `c` for `n` states: `A = D + d bᵀ + c dᵀ + ½ c bᵀ`,
/// `D_{k,k−1} = 1/(2k)`, `D_{k,k+1} = −1/(2k)`, `b_k = (−1)^{k−1} (n+k−1)!/((n−k−1)! (k!)²)`
/// (`k < n`), `b_n = (−1)^{n−1}`, `c_k = 2/k`, `d = (½, 0, …)` (1-based `k`).
pub(crate) fn peters_matrices(n: usize) -> (DMatrix<f64>, DVector<f64>, DVector<f64>) {
    let mut b = DVector::zeros(n);
    for k in 1..=n {
        let sign = if k % 2 == 1 { 1.0 } else { -1.0 };
        b[k - 1] = if k < n {
            // (n+k−1)!/(n−k−1)! = Π_{j=n−k}^{n+k−1} j, divided by (k!)² factor by factor.
            let mut v = 1.0;
            for j in (n - k)..=(n + k - 1) {
                v *= j as f64;
            }
            for j in 1..=k {
                v /= (j * j) as f64;
            }
            sign * v
        } else {
            sign
        };
    }
    let c = DVector::from_fn(n, |k, _| 2.0 / (k + 1) as f64);
    let mut d = DVector::zeros(n);
    d[0] = 0.5;
    let mut dm = DMatrix::zeros(n, n);
    for k in 1..=n {
        if k >= 2 {
            dm[(k - 1, k - 2)] = 1.0 / (2 * k) as f64;
        }
        if k < n {
            dm[(k - 1, k)] = -1.0 / (2 * k) as f64;
        }
    }
    let a = dm + &d * b.transpose() + &c * d.transpose() + 0.5 * &c * b.transpose();
    (a, b, c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::aero::theodorsen::theodorsen;

    /// Jones' fit against Theodorsen's function (its known accuracy: a few per cent of |C|;
    /// measured max |T − C| = 0.0145 over k ∈ [0.02, 2]), and Peters' inflow converging to `C(k)`
    /// with the number of states over the range of reduced frequencies of flutter, k ∈ [0.2, 2]
    /// (measured max |T − C|: N = 2: 0.144, 4: 0.0183, 6: 0.0121, 8: 0.0066; the largest error
    /// sits at the low end of the range). The convergence is slow and stops near N = 8–10
    /// (N = 10: 0.0085, N = 12: 0.032 over k ∈ [0.02, 2]): the logarithmic singularity of `C` at
    /// k = 0, and Peters' `A` gains a factor ~6.5 of condition number per state (2e9 at N = 12).
    #[test]
    fn finite_state_lags_approximate_theodorsen() {
        let err = |lag: &Lag, k0: f64| {
            (0..=100)
                .map(|i| k0 + (2.0 - k0) * i as f64 / 100.0)
                .map(|k| (lag.transfer(Complex::new(0.0, k)) - theodorsen(k)).norm())
                .fold(0.0, f64::max)
        };
        let jones = err(&Lag::jones(), 0.02);
        assert!(jones < 0.02, "Jones {jones}");
        let e: Vec<f64> = [2, 4, 6, 8]
            .iter()
            .map(|&n| err(&Lag::peters(n), 0.2))
            .collect();
        println!("Jones {jones:.3e}; Peters N = 2, 4, 6, 8 over k in [0.2, 2]: {e:?}");
        assert!(e.windows(2).all(|w| w[1] < w[0]), "{e:?}");
        assert!(e[2] < 0.015 && e[3] < 0.008, "{e:?}");
        for lag in [Lag::jones(), Lag::peters(6)] {
            // No lag in steady state (round-off of Peters' A: cond 2.8e4 at N = 6, bound 1e-10),
            // and T' against central differences.
            let t0 = lag.transfer(Complex::new(0.0, 0.0));
            assert!((t0 - Complex::new(1.0, 0.0)).norm() < 1e-10, "{t0}");
            let s = Complex::new(0.1, 0.4);
            // Step 1e-6: round-off ε·cond(s̄I − H̄)/h, measured 3e-8 for Peters N = 6: bound 1e-6.
            let h = 1e-6;
            let fd = (lag.transfer(s + h) - lag.transfer(s - h)) / (2.0 * h);
            let exact = lag.transfer_derivative(s);
            assert!((fd - exact).norm() < 1e-6 * exact.norm(), "{fd} vs {exact}");
        }
    }
}
