//! Variable-step, variable-order BDF / NDF in the quasi-constant step-size formulation of
//! Shampine & Reichelt: the method of MATLAB's `ode15s` (and of SciPy's `BDF`, whose structure
//! this follows).
//!
//! Orders above 2 are not A-stable: their stability regions miss a sliver of the left half-plane
//! next to the imaginary axis, where undamped oscillatory modes live. Error control keeps the
//! result accurate, but for long undamped runs a maximum order of 2 is safer; `max_order` is an
//! option.
//!
//! The driver here (`integrate`: output, order and step-size changes) calls the parts of a step
//! in `bdf_step.rs` (predictor, simplified Newton iteration, error estimate, update of the
//! differences, dense output, order selection).
//!
//! # References
//! L. F. Shampine, M. W. Reichelt, "The MATLAB ODE Suite", SIAM J. Sci. Comput. 18 (1997) 1–22.
//! G. D. Byrne, A. C. Hindmarsh, "A Polyalgorithm for the Numerical Solution of ODEs", ACM TOMS
//! 1 (1975) 71–96.

use super::bdf_step::{Coefficients, State, MIN_FACTOR, NEWTON_MAXITER};
use super::dopri5::initial_step;
use super::{
    check_output_times, failure, outputs_at_start, IntegrationResult, IntegratorStats, OdeSystem,
    Tolerances, Trajectory,
};
use crate::error::SolveError;

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
        let coef = Coefficients::new(opts.ndf);

        let mut f = vec![0.0; dim];
        system.rhs(t0, y0, &mut f);
        stats.rhs_evaluations += 1;
        let h_abs = initial_step(system, t0, y0, &f, &atol, rtol, 1, &mut stats)
            .min(opts.max_step)
            .min(t_end - t0);
        let mut st = State::new(system, max_order, h_abs);
        st.t = t0;
        let newton_tol = st
            .mats
            .newton_tolerance((10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt())));
        let relinearize = st.mats.cheap_linearization();
        let mut jac_ok = st.mats.linearize(system, t0, y0);
        stats.jacobian_evaluations += 1;
        st.d[0].copy_from_slice(y0);
        for i in 0..dim {
            st.d[1][i] = f[i] * h_abs;
        }

        while next_out < t_out.len() {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return fail(traj, stats, SolveError::TooManySteps { time: st.t, steps });
            }
            if st.h_abs > opts.max_step {
                st.change_step(opts.max_step / st.h_abs);
                st.h_abs = opts.max_step;
            }
            let run = Run {
                coef: &coef,
                atol: &atol,
                rtol,
                t_end,
                newton_tol,
                relinearize,
            };
            let (t_new, n_iter, error_norm) =
                match attempt(system, &mut st, &run, &mut jac_ok, &mut stats) {
                    Ok(step) => step,
                    Err(e) => return fail(traj, stats, e),
                };
            stats.steps += 1;
            st.n_equal_steps += 1;
            st.accept();
            next_out = st.dense_output(t_new, t_out, next_out, &mut traj);
            st.t = t_new;
            progress(st.t);
            if system.step_accepted(st.t, &st.d[0]).is_break() {
                return fail(traj, stats, SolveError::Halted { time: st.t });
            }
            if st.n_equal_steps < st.order + 1 {
                continue;
            }
            st.choose_step_and_order(&coef, max_order, n_iter, error_norm);
        }
        Ok((traj, stats))
    }
}

/// What every step of a run reads.
struct Run<'a> {
    coef: &'a Coefficients,
    atol: &'a [f64],
    rtol: f64,
    t_end: f64,
    newton_tol: f64,
    /// Linearize at the predictor of every step (the system's linearizations are cheap).
    relinearize: bool,
}

/// Attempts at one step until the corrector converges and passes the error test: the step's end,
/// Newton's iterations and the error norm. A step whose Newton iteration fails is halved (with a
/// fresh Jacobian first); one that fails the error test shrinks as the error asks, keeping the
/// Newton matrix.
fn attempt<S: OdeSystem>(
    system: &mut S,
    st: &mut State,
    run: &Run<'_>,
    jac_ok: &mut bool,
    stats: &mut IntegratorStats,
) -> Result<(f64, usize, f64), SolveError> {
    let min_step = 10.0 * f64::EPSILON * st.t.abs().max(1e-300);
    let mut current_jac = false;
    loop {
        if st.h_abs < min_step || !st.h_abs.is_finite() {
            let e = SolveError::StepSizeTooSmall {
                time: st.t,
                step: st.h_abs,
            };
            return Err(e);
        }
        let mut t_new = st.t + st.h_abs;
        if t_new > run.t_end {
            t_new = run.t_end;
            st.change_step((t_new - st.t) / st.h_abs);
        }
        let h = t_new - st.t;
        st.h_abs = h;
        st.predict(run.coef, run.atol, run.rtol);
        if run.relinearize && !current_jac {
            // Cheap linearizations: a fresh one at the predictor of every step.
            *jac_ok = st.mats.linearize(system, t_new, &st.y_predict);
            stats.jacobian_evaluations += 1;
            st.lu_c = None;
            current_jac = true;
        }
        let c = h / run.coef.alpha[st.order];
        let (converged, n_iter) = loop {
            let (converged, n_iter) = if *jac_ok && st.factor(system, c, stats) {
                st.newton(system, t_new, c, run.newton_tol, stats)
            } else {
                (false, 0)
            };
            if converged || current_jac {
                break (converged, n_iter);
            }
            *jac_ok = st.mats.linearize(system, t_new, &st.y_predict);
            stats.jacobian_evaluations += 1;
            st.lu_c = None;
            current_jac = true;
        };
        if !converged {
            stats.rejected_steps += 1;
            stats.newton_failures += 1;
            st.h_abs *= 0.5;
            st.change_step(0.5);
            continue;
        }
        let error_norm = st.error_estimate(run.coef, run.atol, run.rtol);
        if error_norm > 1.0 {
            // As SciPy: the corrector converged, so the Newton matrix is kept.
            stats.rejected_steps += 1;
            let safety =
                0.9 * (2 * NEWTON_MAXITER + 1) as f64 / (2 * NEWTON_MAXITER + n_iter) as f64;
            let factor = MIN_FACTOR.max(safety * error_norm.powf(-1.0 / (st.order as f64 + 1.0)));
            st.h_abs *= factor;
            let lu_c = st.lu_c;
            st.change_step(factor);
            st.lu_c = lu_c;
            continue;
        }
        return Ok((t_new, n_iter, error_norm));
    }
}
