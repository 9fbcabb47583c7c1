//! The parts of one BDF/NDF step (`bdf.rs`) in the quasi-constant step-size formulation of
//! Shampine & Reichelt (and of SciPy's `BDF`): the method's coefficients, the backward
//! differences and their rescaling, the predictor, the simplified Newton iteration of the
//! corrector, the error estimate, the update of the differences, dense output and the order and
//! step-size selection. The state carried from step to step is [`State`].

use nalgebra::DMatrix;

use super::{IntegratorStats, IterationMatrices, OdeSystem, Trajectory};

pub(super) const NEWTON_MAXITER: usize = 4;
pub(super) const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;
/// NDF coefficients κ (Shampine & Reichelt, Table 1); zero gives the plain BDF.
const KAPPA: [f64; 6] = [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];

fn rms(v: &[f64], scale: &[f64]) -> f64 {
    super::scaled_rms(v, scale)
}

/// `R` of the step-size change (Shampine & Reichelt, eq. 2.4).
fn compute_r(order: usize, factor: f64) -> DMatrix<f64> {
    let mut m = DMatrix::zeros(order + 1, order + 1);
    for j in 0..=order {
        m[(0, j)] = 1.0;
    }
    for i in 1..=order {
        for j in 1..=order {
            m[(i, j)] = (i as f64 - 1.0 - factor * j as f64) / i as f64;
        }
    }
    // Cumulative product down the rows.
    for i in 1..=order {
        for j in 0..=order {
            m[(i, j)] *= m[(i - 1, j)];
        }
    }
    m
}

/// Rescale the difference array `d` for a step-size change by `factor`.
fn change_d(d: &mut [Vec<f64>], order: usize, factor: f64) {
    let r = compute_r(order, factor);
    let u = compute_r(order, 1.0);
    let ru = r * u;
    let dim = d[0].len();
    let old: Vec<Vec<f64>> = d[..=order].to_vec();
    for i in 0..=order {
        for c in 0..dim {
            d[i][c] = (0..=order).map(|k| ru[(k, i)] * old[k][c]).sum();
        }
    }
}

/// The method's constants for the orders 0–5: NDF `κ`, `γ_k = Σ_{j≤k} 1/j`, `α_k = (1 − κ_k) γ_k`
/// and the error constants.
pub(super) struct Coefficients {
    pub(super) gamma: [f64; 6],
    pub(super) alpha: [f64; 6],
    pub(super) error_const: [f64; 6],
}

impl Coefficients {
    pub(super) fn new(ndf: bool) -> Self {
        let kappa: Vec<f64> = KAPPA.iter().map(|k| if ndf { *k } else { 0.0 }).collect();
        let mut gamma = [0.0; 6];
        for i in 1..6 {
            gamma[i] = gamma[i - 1] + 1.0 / i as f64;
        }
        let mut alpha = [0.0; 6];
        let mut error_const = [0.0; 6];
        for i in 0..6 {
            alpha[i] = (1.0 - kappa[i]) * gamma[i];
            error_const[i] = kappa[i] * gamma[i] + 1.0 / (i as f64 + 1.0);
        }
        Self {
            gamma,
            alpha,
            error_const,
        }
    }
}

/// What a run carries from step to step (diffsol's split of a method and its state): the
/// backward differences of the solution at the current step size, the order, and the Newton
/// matrix.
pub(super) struct State {
    pub(super) t: f64,
    pub(super) h_abs: f64,
    pub(super) order: usize,
    pub(super) n_equal_steps: usize,
    /// Backward differences `D^k y_n` scaled to the current step (Shampine & Reichelt).
    pub(super) d: Vec<Vec<f64>>,
    /// `I − c J` factored, as `(1/c) I − J` in real slot 0, and the `c` it was factored for.
    pub(super) mats: IterationMatrices,
    pub(super) lu_c: Option<f64>,
    pub(super) y_predict: Vec<f64>,
    pub(super) psi: Vec<f64>,
    pub(super) scale: Vec<f64>,
    pub(super) y_new: Vec<f64>,
    pub(super) dcorr: Vec<f64>,
    pub(super) f: Vec<f64>,
    pub(super) dy: Vec<f64>,
}

impl State {
    /// At the start, of order 1 with the first step `h_abs`; the differences are still to be
    /// set (`d[0] = y0`, `d[1] = h f0`).
    pub(super) fn new<S: OdeSystem>(system: &mut S, max_order: usize, h_abs: f64) -> Self {
        let dim = system.dim();
        Self {
            t: 0.0,
            h_abs,
            order: 1,
            n_equal_steps: 0,
            d: vec![vec![0.0; dim]; max_order + 3],
            mats: IterationMatrices::new(system),
            lu_c: None,
            y_predict: vec![0.0; dim],
            psi: vec![0.0; dim],
            scale: vec![0.0; dim],
            y_new: vec![0.0; dim],
            dcorr: vec![0.0; dim],
            f: vec![0.0; dim],
            dy: vec![0.0; dim],
        }
    }

    /// Rescale the differences for a step-size change by `factor`; the Newton matrix goes.
    pub(super) fn change_step(&mut self, factor: f64) {
        change_d(&mut self.d, self.order, factor);
        self.n_equal_steps = 0;
        self.lu_c = None;
    }

    /// The predictor (the interpolating polynomial extrapolated), the error scale at it, and the
    /// history term `ψ` of the corrector equation.
    pub(super) fn predict(&mut self, coef: &Coefficients, atol: &[f64], rtol: f64) {
        let order = self.order;
        for i in 0..self.y_predict.len() {
            self.y_predict[i] = (0..=order).map(|k| self.d[k][i]).sum();
            self.scale[i] = atol[i] + rtol * self.y_predict[i].abs();
            self.psi[i] = (1..=order)
                .map(|k| self.d[k][i] * coef.gamma[k])
                .sum::<f64>()
                / coef.alpha[order];
        }
    }

    /// Simplified Newton iteration on `y = y_predict + d`, `d − c f(t_new, y) + ψ = 0`, with the
    /// Newton matrix of an earlier `c` if it is still there. Returns whether it converged and the
    /// iterations it took.
    pub(super) fn newton<S: OdeSystem>(
        &mut self,
        system: &mut S,
        t_new: f64,
        c: f64,
        newton_tol: f64,
        stats: &mut IntegratorStats,
    ) -> (bool, usize) {
        let dim = self.y_new.len();
        let mut n_iter = 0;
        let Some(c_lu) = self.lu_c else {
            return (false, 0);
        };
        self.y_new.copy_from_slice(&self.y_predict);
        self.dcorr.fill(0.0);
        let mut dy_norm_old: Option<f64> = None;
        for k in 0..NEWTON_MAXITER {
            n_iter = k + 1;
            stats.newton_iterations += 1;
            system.rhs(t_new, &self.y_new, &mut self.f);
            stats.rhs_evaluations += 1;
            if self.f.iter().any(|v| !v.is_finite()) {
                break;
            }
            // (I − c J) dy = r  ⇔  ((1/c) I − J) dy = r / c.
            for i in 0..dim {
                self.dy[i] = (c * self.f[i] - self.psi[i] - self.dcorr[i]) / c_lu;
            }
            self.mats.solve_real(system, 0, &mut self.dy);
            if self.dy.iter().any(|v| !v.is_finite()) {
                break;
            }
            let dy_norm = rms(&self.dy, &self.scale);
            let rate = dy_norm_old.map(|o| dy_norm / o);
            if let Some(rate) = rate {
                if rate >= 1.0
                    || rate.powi((NEWTON_MAXITER - k) as i32) / (1.0 - rate) * dy_norm > newton_tol
                {
                    break;
                }
            }
            for i in 0..dim {
                self.y_new[i] += self.dy[i];
                self.dcorr[i] += self.dy[i];
            }
            if dy_norm == 0.0 || rate.is_some_and(|r| r / (1.0 - r) * dy_norm < newton_tol) {
                return (true, n_iter);
            }
            dy_norm_old = Some(dy_norm);
        }
        (false, n_iter)
    }

    /// Factor the Newton matrix for `c` unless it is there; false if it is singular.
    pub(super) fn factor<S: OdeSystem>(
        &mut self,
        system: &mut S,
        c: f64,
        stats: &mut IntegratorStats,
    ) -> bool {
        if self.lu_c.is_some() {
            return true;
        }
        stats.factorizations += 1;
        if self.mats.factor_real(system, 0, 1.0 / c) {
            self.lu_c = Some(c);
            true
        } else {
            false
        }
    }

    /// The error estimate of the corrected step: `error_const[order]` times the correction, in
    /// the scale of the new solution.
    pub(super) fn error_estimate(&mut self, coef: &Coefficients, atol: &[f64], rtol: f64) -> f64 {
        for i in 0..self.y_new.len() {
            self.scale[i] = atol[i] + rtol * self.y_new[i].abs();
        }
        let e = coef.error_const[self.order];
        e.abs() * rms(&self.dcorr, &self.scale)
    }

    /// Accept the step: `D^{j+1} y_n = D^j y_n − D^j y_{n−1}` from the correction.
    pub(super) fn accept(&mut self) {
        let order = self.order;
        let d = &mut self.d;
        for i in 0..self.dcorr.len() {
            d[order + 2][i] = self.dcorr[i] - d[order + 1][i];
            d[order + 1][i] = self.dcorr[i];
        }
        for k in (0..=order).rev() {
            for i in 0..self.dcorr.len() {
                let next = d[k + 1][i];
                d[k][i] += next;
            }
        }
    }

    /// Dense output on `(t, t_new]` from the interpolating polynomial, for the output times from
    /// `next_out`; returns the index of the next output time.
    pub(super) fn dense_output(
        &self,
        t_new: f64,
        t_out: &[f64],
        mut next_out: usize,
        traj: &mut Trajectory,
    ) -> usize {
        while next_out < t_out.len() && t_out[next_out] <= t_new {
            let tt = t_out[next_out];
            let mut yo = self.d[0].clone();
            let mut p = 1.0;
            for j in 0..self.order {
                let t_shift = t_new - self.h_abs * j as f64;
                let denom = self.h_abs * (1.0 + j as f64);
                p *= (tt - t_shift) / denom;
                for (o, dj) in yo.iter_mut().zip(&self.d[j + 1]) {
                    *o += dj * p;
                }
            }
            traj.t.push(tt);
            traj.y.push(yo);
            next_out += 1;
        }
        next_out
    }

    /// Step-size and order control after `order + 1` steps of equal size: the order among
    /// `order − 1`, `order`, `order + 1` that allows the largest step.
    pub(super) fn choose_step_and_order(
        &mut self,
        coef: &Coefficients,
        max_order: usize,
        n_iter: usize,
        error_norm: f64,
    ) {
        let order = self.order;
        let safety = 0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + n_iter) as f64;
        let err_m = if order > 1 {
            let e: Vec<f64> = self.d[order]
                .iter()
                .map(|v| coef.error_const[order - 1] * v)
                .collect();
            rms(&e, &self.scale)
        } else {
            f64::INFINITY
        };
        let err_p = if order < max_order {
            let e: Vec<f64> = self.d[order + 2]
                .iter()
                .map(|v| coef.error_const[order + 1] * v)
                .collect();
            rms(&e, &self.scale)
        } else {
            f64::INFINITY
        };
        let norms = [err_m, error_norm, err_p];
        let mut best = 1usize;
        let mut best_factor = f64::NEG_INFINITY;
        for (k, e) in norms.iter().enumerate() {
            let fct = e.powf(-1.0 / (order as f64 + k as f64));
            let fct = if fct.is_nan() { f64::INFINITY } else { fct };
            if fct > best_factor {
                best_factor = fct;
                best = k;
            }
        }
        self.order = (order + best) - 1;
        let factor = MAX_FACTOR.min(safety * best_factor);
        self.h_abs *= factor;
        self.change_step(factor);
    }
}
