//! Finite-state lag of the circulatory lift (docs/aeroelastic-model.md §4): per strip
//! `ȧ = (V/b)(H̄ a + B̄ w)`, `w_eff = C̄ a + D̄ w`, nondimensional in the reduced time `s = ∫V dt/b`.
//!
//! * Wagner's function by R. T. Jones' two-term fit (NACA TR 681, 1940):
//!   `φ(s) = 1 − A1 e^{−β1 s} − A2 e^{−β2 s}`, `A = (0.165, 0.335)`, `β = (0.0455, 0.3)`:
//!   `H̄ = −diag β`, `B̄ = 1`, `C̄ = (A1 β1, A2 β2)`, `D̄ = 1 − A1 − A2`.
//! * Peters' finite-state inflow (Peters, Karunamoorthy & Cao, J. Aircraft 32(2), 1995)
//!   `A λ̇ + (V/b) λ = c ẇ`, `λ0 = ½ bᵀλ`, realized in partial-fraction (modal) form
//!   `T(s̄) = D + Σ_j r_j/(s̄ − s_j)`, `s_j = −1/eig(A)`: one state per real pole, two per
//!   conjugate pair (`H̄` block-diagonal, `B̄ = (1, 0, …)` per block). The poles and residues are
//!   derived from Peters' `A`, `b`, `c` in 80-digit arithmetic by `peters_poles.py` and rounded
//!   once (`peters_poles.rs`). The earlier realization in `μ = λ − A⁻¹c w` (`H̄ = −A⁻¹`) has the
//!   same transfer function but loses digits fast in double precision (`cond A` grows ~7× per
//!   state; measured error of `T(ik)`: 1.4e-10 at N = 8, 1.7e-8 at 10, 1e-6 at 12, 1.4e-4 at 14),
//!   while the modal form is exact to round-off for every N (docs/aeroelastic-model.md §4).
//!
//! The transfer function `T(s̄) = D̄ + C̄ (s̄ I − H̄)⁻¹ B̄` (`s̄ = s b/V`) approximates Theodorsen's
//! `C(k)` at `s̄ = ik`; `T(0) = 1` (no lag in steady state).

use nalgebra::{Complex, DMatrix, DVector};

use super::peters_poles::PETERS_MODAL;

/// Largest number of Peters states with a table: N = 16 of the 1995 coefficients has an unstable
/// pole (`s̄ = 0.00145 + 0.246i`, `peters_poles.py`), so it is not offered.
pub(crate) const PETERS_MAX_STATES: usize = PETERS_MODAL.len();

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

    /// Peters' finite-state inflow with `n` states (`1 ≤ n ≤ PETERS_MAX_STATES`), in modal form:
    /// a real pole `s` is the state `ẋ = s x + w` with output `r x`; a pair `s, s̄` the states
    /// `(x₁, x₂)` = (Re, Im) of `ż = s z + w`, with output `2 Re(r z) = 2 Re r x₁ − 2 Im r x₂`.
    pub(crate) fn peters(n: usize) -> Self {
        let (d, poles) = PETERS_MODAL[n - 1];
        let mut h = DMatrix::zeros(n, n);
        let mut b = DVector::zeros(n);
        let mut c = DVector::zeros(n);
        let mut k = 0;
        for &(sr, si, rr, ri) in poles {
            h[(k, k)] = sr;
            b[k] = 1.0;
            if si == 0.0 {
                c[k] = rr;
                k += 1;
            } else {
                h[(k, k + 1)] = -si;
                h[(k + 1, k)] = si;
                h[(k + 1, k + 1)] = sr;
                c[k] = 2.0 * rr;
                c[k + 1] = -2.0 * ri;
                k += 2;
            }
        }
        debug_assert_eq!(k, n);
        Self { h, b, c, d }
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

/// Peters' `A`, `b`, `c` for `n` states (for the tests: the definition the table is checked
/// against): `A = D + d bᵀ + c dᵀ + ½ c bᵀ`,
/// `D_{k,k−1} = 1/(2k)`, `D_{k,k+1} = −1/(2k)`, `b_k = (−1)^{k−1} (n+k−1)!/((n−k−1)! (k!)²)`
/// (`k < n`), `b_n = (−1)^{n−1}`, `c_k = 2/k`, `d = (½, 0, …)` (1-based `k`).
#[cfg(test)]
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

    /// A file of the independent aeroelastic references (tests/data/aero_reference/README.md).
    fn reference(file: &str) -> String {
        let path = format!(
            "{}/tests/data/aero_reference/{file}",
            env!("CARGO_MANIFEST_DIR")
        );
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
    }

    /// The former realization, in `μ = λ − A⁻¹c w` with `A⁻¹` formed in double precision
    /// (`H̄ = −A⁻¹`, `B̄ = −A⁻²c`, `C̄ = −½bᵀ`, `D̄ = 1 − ½bᵀA⁻¹c`): kept here to show why it went.
    fn mu_realization(n: usize) -> Lag {
        let (a, b, c) = peters_matrices(n);
        let ainv = a.try_inverse().expect("Peters' A is invertible");
        let ainv_c = &ainv * &c;
        Lag {
            h: -&ainv,
            b: -(&ainv * &ainv_c),
            c: -0.5 * &b,
            d: 1.0 - 0.5 * b.dot(&ainv_c),
        }
    }

    /// Jones' fit against Theodorsen's function (its known accuracy: a few per cent of |C|;
    /// measured max |T − C| = 0.0145 over k ∈ [0.02, 2]), and Peters' inflow converging to `C(k)`
    /// with the number of states over the range of reduced frequencies of flutter, k ∈ [0.2, 2]
    /// (measured max |T − C|: N = 2: 0.144, 4: 0.0183, 6: 0.0121, 8: 0.0066; the largest error
    /// sits at the low end of the range). The convergence is slow and stops near N = 8–10
    /// (N = 10: 0.0085, N = 12: 0.032 over k ∈ [0.02, 2]): the 1995 coefficients themselves, not
    /// round-off (the 40-digit values of tests/data/aero_reference/ck_table.csv show the same).
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
            let s = Complex::new(0.1, 0.4);
            // T' against central differences, step 1e-6: round-off ε/h ~ 1e-10, truncation
            // h²|T‴| ~ 1e-12; measured 1.4e-10 (Jones), 9.4e-11 (Peters 6): bound 1e-8 relative.
            let h = 1e-6;
            let fd = (lag.transfer(s + h) - lag.transfer(s - h)) / (2.0 * h);
            let exact = lag.transfer_derivative(s);
            println!("T' error {:.1e}", (fd - exact).norm() / exact.norm());
            assert!((fd - exact).norm() < 1e-8 * exact.norm(), "{fd} vs {exact}");
        }
    }

    /// Peters' transfer function in the modal realization against its definition evaluated in
    /// 40-digit arithmetic by the independent reference (`ck_table.csv`: N = 2 … 14, twelve
    /// reduced frequencies k ∈ [0.01, 5], printed to 17 digits). Measured max |T − C_ref|
    /// 1.1e-16 to 1.4e-16 for every N (the former `μ` realization: 4.4e-14 at N = 4, 1.4e-10 at
    /// 8, 1.7e-8 at 10, 1.0e-6 at 12, 1.4e-4 at 14): bound 2e-15, a few ulps of |C| ≤ 1.
    #[test]
    fn peters_modal_realization_matches_the_40_digit_definition() {
        let text = reference("ck_table.csv");
        for n in [2usize, 4, 6, 8, 10, 12, 14] {
            let (modal, mu) = (Lag::peters(n), mu_realization(n));
            let name = format!("peters{n}");
            let (mut worst, mut worst_mu, mut rows) = (0.0f64, 0.0f64, 0);
            for line in text.lines().skip(1) {
                let f: Vec<&str> = line.split(',').collect();
                if f[0] != name {
                    continue;
                }
                let num = |i: usize| f[i].parse::<f64>().unwrap();
                let (k, c) = (num(1), Complex::new(num(2), num(3)));
                let s = Complex::new(0.0, k);
                worst = worst.max((modal.transfer(s) - c).norm());
                worst_mu = worst_mu.max((mu.transfer(s) - c).norm());
                rows += 1;
            }
            assert_eq!(rows, 12, "{name}");
            println!(
                "N = {n:2}: max |T − C_40 digits| modal {worst:.1e}, former μ form {worst_mu:.1e}"
            );
            assert!(worst < 2e-15, "N = {n}: {worst:e}");
        }
    }

    /// The poles and residues of the table against those of the reference's own modal
    /// realization (`peters_modal.csv`, N = 2 … 10, from `eig(−A⁻¹)` in 60 digits; here
    /// `eig(A)` and `r = ½γβ/μ²` in 80 digits, `peters_poles.py`). Both are rounded once from
    /// exact values: measured identical to the last bit (the N = 2 zero residue: 3e-63 there, 0
    /// here); bound 1e-14 (relative to the largest pole for
    /// the poles, absolute for the residues and D: zero-residue poles, N = 2: `s = −2`, occur).
    #[test]
    fn peters_poles_match_the_reference_realization() {
        let text = reference("peters_modal.csv");
        for n in [2usize, 4, 6, 8, 10] {
            let (d, ours) = PETERS_MODAL[n - 1];
            let mut theirs: Vec<(f64, f64, f64, f64, f64)> = text
                .lines()
                .skip(1)
                .map(|l| l.split(',').collect::<Vec<_>>())
                .filter(|f| f[0] == n.to_string())
                .map(|f| {
                    let v = |i: usize| f[i].parse::<f64>().unwrap();
                    (v(1), v(3), v(4), v(5), v(6))
                })
                .collect();
            assert_eq!(theirs.len(), ours.len(), "N = {n}");
            let scale = ours.iter().map(|p| p.0.hypot(p.1)).fold(0.0, f64::max);
            let mut worst = (d - theirs[0].0).abs();
            for &(sr, si, rr, ri) in ours {
                let (i, _) = theirs
                    .iter()
                    .enumerate()
                    .map(|(i, t)| (i, (t.1 - sr).hypot(t.2 - si)))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .unwrap();
                let t = theirs.swap_remove(i);
                worst = worst
                    .max((t.1 - sr).hypot(t.2 - si) / scale)
                    .max((t.3 - rr).hypot(t.4 - ri));
            }
            println!("N = {n:2}: poles, residues and D within {worst:.1e}");
            assert!(worst < 1e-14, "N = {n}: {worst:e}");
        }
    }

    /// Every offered count is a stable lag with no lag in steady state: the poles of `H̄` lie in
    /// the left half plane (the slowest, N = 15: Re s̄ = −0.0106; `peters_poles.py` shows N = 16
    /// unstable) and `T(0) = 1` (measured 2.2e-16 off at worst, the table's rounding; bound
    /// 1e-14).
    #[test]
    fn peters_lags_are_stable_and_steady_state_exact() {
        for n in 1..=PETERS_MAX_STATES {
            let lag = Lag::peters(n);
            assert_eq!(lag.n_states(), n);
            let slowest = lag
                .h
                .complex_eigenvalues()
                .iter()
                .map(|e| e.re)
                .fold(f64::NEG_INFINITY, f64::max);
            let t0 = lag.transfer(Complex::new(0.0, 0.0));
            println!(
                "N = {n:2}: max Re s = {slowest:.4e}, |T(0) − 1| = {:.1e}",
                (t0 - 1.0).norm()
            );
            assert!(slowest < -0.01, "N = {n}: {slowest}");
            assert!((t0 - 1.0).norm() < 1e-14, "N = {n}: {t0}");
        }
    }
}
