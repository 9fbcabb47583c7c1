//! Variable-step, variable-order BDF / NDF in the quasi-constant step-size formulation of
//! Shampine & Reichelt: the method of MATLAB's `ode15s` (and of SciPy's `BDF`, whose structure
//! this follows).
//!
//! Orders above 2 are not A-stable: their stability regions miss a sliver of the left half-plane
//! next to the imaginary axis, where undamped oscillatory modes live. Error control keeps the
//! result accurate, but for long undamped runs a maximum order of 2 is safer; `max_order` is an
//! option.
//!
//! # References
//! L. F. Shampine, M. W. Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 (1997) 1–22.
//! G. D. Byrne, A. C. Hindmarsh, "A Polyalgorithm for the Numerical Solution of ODEs", ACM TOMS
//! 1 (1975) 71–96.

use nalgebra::{DMatrix, DVector};

use super::dopri5::initial_step;
use super::{
    check_output_times, scaled_rms, failure, outputs_at_start, IntegrationResult, IntegratorStats, OdeSystem,
    Tolerances, Trajectory,
};
use crate::error::SolveError;

const NEWTON_MAXITER: usize = 4;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;
/// NDF coefficients κ (Shampine & Reichelt, Table 1); zero gives the plain BDF.
const KAPPA: [f64; 6] = [0.0, -0.1850, -1.0 / 9.0, -0.0823, -0.0415, 0.0];

/// Options of [`Bdf`].
#[derive(Debug, Clone, PartialEq)]
pub struct BdfOptions {
    /// Error tolerances.
    pub tolerances: Tolerances,
    /// Largest order, 1 to 5. Default 2: orders 3–5 are unstable for undamped modes with
    /// `h ω` of order one, and a beam model has modes at every frequency up to ~1e6 rad/s, so
    /// with them the step collapses (measured: 1.9 million steps instead of 775 for the paper's
    /// sinusoidal case at n = 20). `ode15s`'s default is 5.
    pub max_order: usize,
    /// Use the NDF coefficients (as `ode15s`) rather than plain BDF. Default `true`.
    pub ndf: bool,
    /// Largest step (s). Default infinite.
    pub max_step: f64,
    /// Budget of steps, accepted and rejected, before the run stops with
    /// [`SolveError::TooManySteps`] and the output so far. Default 1 000 000.
    pub max_steps: usize,
}

impl Default for BdfOptions {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            max_order: 2,
            ndf: true,
            max_step: f64::INFINITY,
            max_steps: 1_000_000,
        }
    }
}

/// The variable-order BDF/NDF integrator for stiff systems.
#[derive(Debug, Clone, Default)]
pub struct Bdf {
    /// Options.
    pub options: BdfOptions,
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

impl Bdf {
    /// Integrate `system` from `(t0, y0)` and return the state at each of `t_out`.
    ///
    /// # Errors
    /// As [`super::Dopri5::integrate`]; also a Newton iteration that keeps failing shrinks the
    /// step until it is too small.
    pub fn integrate<S: OdeSystem>(
        &self,
        system: &mut S,
        t0: f64,
        y0: &[f64],
        t_out: &[f64],
        progress: &mut dyn FnMut(f64),
    ) -> IntegrationResult {
        let dim = system.dim();
        let opts = &self.options;
        let mut stats = IntegratorStats::default();
        let mut traj = Trajectory::default();
        let fail = failure;
        if let Err(e) = check_output_times(t0, t_out)
            .and_then(|_| opts.tolerances.validate("options.tolerances", dim))
        {
            return fail(traj, stats, SolveError::from_input(e));
        }
        if !(1..=5).contains(&opts.max_order) {
            let e = crate::InputError::new(
                "options.max_order",
                format!("must be between 1 and 5, got {}", opts.max_order),
            );
            return fail(traj, stats, SolveError::from_input(e));
        }
        let max_order = opts.max_order;
        let atol = opts.tolerances.atol(dim);
        let rtol = opts.tolerances.rtol;
        let t_end = t_out.last().copied().unwrap_or(t0);
        let mut next_out = outputs_at_start(t0, y0, t_out, &mut traj);
        if next_out == t_out.len() {
            return Ok((traj, stats));
        }

        let kappa: Vec<f64> = KAPPA
            .iter()
            .map(|k| if opts.ndf { *k } else { 0.0 })
            .collect();
        let mut gamma = [0.0; 6];
        for i in 1..6 {
            gamma[i] = gamma[i - 1] + 1.0 / i as f64;
        }
        let alpha: Vec<f64> = (0..6).map(|i| (1.0 - kappa[i]) * gamma[i]).collect();
        let error_const: Vec<f64> = (0..6)
            .map(|i| kappa[i] * gamma[i] + 1.0 / (i as f64 + 1.0))
            .collect();
        let newton_tol = (10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt()));

        let mut f = vec![0.0; dim];
        system.rhs(t0, y0, &mut f);
        stats.rhs_evaluations += 1;
        let mut h_abs = initial_step(system, t0, y0, &f, &atol, rtol, 1, &mut stats)
            .min(opts.max_step)
            .min(t_end - t0);
        let mut jac = DMatrix::zeros(dim, dim);
        system.jacobian(t0, y0, &mut jac);
        stats.jacobian_evaluations += 1;
        let mut d: Vec<Vec<f64>> = vec![vec![0.0; dim]; max_order + 3];
        d[0].copy_from_slice(y0);
        for i in 0..dim {
            d[1][i] = f[i] * h_abs;
        }
        let mut order = 1usize;
        let mut n_equal_steps = 0usize;
        let mut lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>> = None;
        let mut t = t0;
        let mut y_predict = vec![0.0; dim];
        let mut psi = vec![0.0; dim];
        let mut scale = vec![0.0; dim];
        let mut y_new = vec![0.0; dim];
        let mut dcorr = vec![0.0; dim];
        let mut rhs_v = DVector::zeros(dim);

        while next_out < t_out.len() {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return fail(traj, stats, SolveError::TooManySteps { time: t, steps });
            }
            let min_step = 10.0 * f64::EPSILON * t.abs().max(1e-300);
            if h_abs > opts.max_step {
                change_d(&mut d, order, opts.max_step / h_abs);
                h_abs = opts.max_step;
                n_equal_steps = 0;
                lu = None;
            }
            let mut current_jac = false;
            let (t_new, n_iter, error_norm) = loop {
                if h_abs < min_step || !h_abs.is_finite() {
                    return fail(
                        traj,
                        stats,
                        SolveError::StepSizeTooSmall {
                            time: t,
                            step: h_abs,
                        },
                    );
                }
                let mut t_new = t + h_abs;
                if t_new > t_end {
                    t_new = t_end;
                    change_d(&mut d, order, (t_new - t) / h_abs);
                    n_equal_steps = 0;
                    lu = None;
                }
                let h = t_new - t;
                h_abs = h;
                for i in 0..dim {
                    y_predict[i] = (0..=order).map(|k| d[k][i]).sum();
                    scale[i] = atol[i] + rtol * y_predict[i].abs();
                    psi[i] = (1..=order).map(|k| d[k][i] * gamma[k]).sum::<f64>() / alpha[order];
                }
                let c = h / alpha[order];
                let mut converged;
                let mut n_iter = 0;
                loop {
                    if lu.is_none() {
                        let m = DMatrix::identity(dim, dim) - &jac * c;
                        lu = Some(m.lu());
                        stats.factorizations += 1;
                    }
                    // Simplified Newton on y = y_predict + d, d − c f(t_new, y) + psi = 0.
                    y_new.copy_from_slice(&y_predict);
                    dcorr.fill(0.0);
                    let mut dy_norm_old: Option<f64> = None;
                    converged = false;
                    for k in 0..NEWTON_MAXITER {
                        n_iter = k + 1;
                        stats.newton_iterations += 1;
                        system.rhs(t_new, &y_new, &mut f);
                        stats.rhs_evaluations += 1;
                        if f.iter().any(|v| !v.is_finite()) {
                            break;
                        }
                        for i in 0..dim {
                            rhs_v[i] = c * f[i] - psi[i] - dcorr[i];
                        }
                        let Some(dy) = lu.as_ref().and_then(|l| l.solve(&rhs_v)) else {
                            break;
                        };
                        let dy_norm = scaled_rms(dy.as_slice(), &scale);
                        let rate = dy_norm_old.map(|o| dy_norm / o);
                        if let Some(rate) = rate {
                            if rate >= 1.0
                                || rate.powi((NEWTON_MAXITER - k) as i32) / (1.0 - rate) * dy_norm
                                    > newton_tol
                            {
                                break;
                            }
                        }
                        for i in 0..dim {
                            y_new[i] += dy[i];
                            dcorr[i] += dy[i];
                        }
                        if dy_norm == 0.0
                            || rate.is_some_and(|r| r / (1.0 - r) * dy_norm < newton_tol)
                        {
                            converged = true;
                            break;
                        }
                        dy_norm_old = Some(dy_norm);
                    }
                    if converged || current_jac {
                        break;
                    }
                    system.jacobian(t_new, &y_predict, &mut jac);
                    stats.jacobian_evaluations += 1;
                    lu = None;
                    current_jac = true;
                }
                if !converged {
                    stats.rejected_steps += 1;
                    h_abs *= 0.5;
                    change_d(&mut d, order, 0.5);
                    n_equal_steps = 0;
                    lu = None;
                    continue;
                }
                for i in 0..dim {
                    scale[i] = atol[i] + rtol * y_new[i].abs();
                }
                let err: Vec<f64> = dcorr.iter().map(|v| error_const[order] * v).collect();
                let error_norm = scaled_rms(&err, &scale);
                if error_norm > 1.0 {
                    stats.rejected_steps += 1;
                    let safety = 0.9 * (2 * NEWTON_MAXITER + 1) as f64
                        / (2 * NEWTON_MAXITER + n_iter) as f64;
                    let factor =
                        MIN_FACTOR.max(safety * error_norm.powf(-1.0 / (order as f64 + 1.0)));
                    h_abs *= factor;
                    change_d(&mut d, order, factor);
                    n_equal_steps = 0;
                    continue;
                }
                break (t_new, n_iter, error_norm);
            };
            stats.steps += 1;
            n_equal_steps += 1;
            // Update the differences: D^{j+1} y_n = D^j y_n − D^j y_{n−1}.
            for i in 0..dim {
                d[order + 2][i] = dcorr[i] - d[order + 1][i];
                d[order + 1][i] = dcorr[i];
            }
            for k in (0..=order).rev() {
                for i in 0..dim {
                    let next = d[k + 1][i];
                    d[k][i] += next;
                }
            }
            // Dense output on (t, t_new] from the interpolating polynomial.
            while next_out < t_out.len() && t_out[next_out] <= t_new {
                let tt = t_out[next_out];
                let mut yo = d[0].clone();
                let mut p = 1.0;
                for j in 0..order {
                    let t_shift = t_new - h_abs * j as f64;
                    let denom = h_abs * (1.0 + j as f64);
                    p *= (tt - t_shift) / denom;
                    for i in 0..dim {
                        yo[i] += d[j + 1][i] * p;
                    }
                }
                traj.t.push(tt);
                traj.y.push(yo);
                next_out += 1;
            }
            t = t_new;
            progress(t);
            if system.step_accepted(t, &d[0]).is_break() {
                return failure(traj, stats, SolveError::Halted { time: t });
            }
            if n_equal_steps < order + 1 {
                continue;
            }
            let safety =
                0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + n_iter) as f64;
            let err_m = if order > 1 {
                let e: Vec<f64> = d[order]
                    .iter()
                    .map(|v| error_const[order - 1] * v)
                    .collect();
                scaled_rms(&e, &scale)
            } else {
                f64::INFINITY
            };
            let err_p = if order < max_order {
                let e: Vec<f64> = d[order + 2]
                    .iter()
                    .map(|v| error_const[order + 1] * v)
                    .collect();
                scaled_rms(&e, &scale)
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
            order = (order + best) - 1;
            let factor = MAX_FACTOR.min(safety * best_factor);
            h_abs *= factor;
            change_d(&mut d, order, factor);
            n_equal_steps = 0;
            lu = None;
        }
        Ok((traj, stats))
    }
}
