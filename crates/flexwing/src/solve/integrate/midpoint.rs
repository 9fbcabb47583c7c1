//! The implicit midpoint rule `y₁ = y₀ + h f(t + h/2, (y₀ + y₁)/2)`: second order, A-stable,
//! symplectic, and it conserves quadratic invariants exactly, so the energy of an undamped
//! structure does not drift. Fixed step, or adaptive by step doubling (Richardson).
//!
//! # References
//! Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., §II.1, §VI.3.

use super::dopri5::initial_step;
use super::{
    check_output_times, error_norm, failure, outputs_at_start, scaled_rms, IntegrationResult,
    IntegratorStats, IterationMatrices, OdeSystem, Tolerances, Trajectory,
};
use crate::error::SolveError;

/// Options of [`ImplicitMidpoint`].
#[derive(Debug, Clone, PartialEq)]
pub struct MidpointOptions {
    /// Error tolerances for the adaptive step (ignored with a fixed `step`).
    pub tolerances: Tolerances,
    /// Fixed step (s); `None` (default) for the adaptive step.
    pub step: Option<f64>,
    /// Largest step (s). Default infinite.
    pub max_step: f64,
    /// Budget of steps, accepted and rejected, before the run stops with
    /// [`SolveError::TooManySteps`] and the output so far. Default 1 000 000.
    pub max_steps: usize,
    /// Newton tolerance, relative to the error scale `atol + rtol |y|`. Default `1e-4`: tight, so
    /// that the unconverged Newton residual does not spoil the energy conservation.
    pub newton_tolerance: f64,
}

impl Default for MidpointOptions {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            step: None,
            max_step: f64::INFINITY,
            max_steps: 1_000_000,
            newton_tolerance: 1e-4,
        }
    }
}

/// The implicit midpoint integrator.
#[derive(Debug, Clone, Default)]
pub struct ImplicitMidpoint {
    /// Options.
    pub options: MidpointOptions,
}

/// Newton state of one implicit midpoint stage, with Jacobian reuse: `I − (h/2) J` is factored
/// as `(2/h) I − J` in real slot 0 of the iteration matrices, for the step `h` in `lu_h`.
struct Stage {
    mats: IterationMatrices,
    lu_h: Option<f64>,
    jac_fresh: bool,
    f: Vec<f64>,
    z: Vec<f64>,
    dz: Vec<f64>,
}

impl Stage {
    /// One step of size `h` from `(t, y0)` into `y1`; false if Newton fails.
    #[allow(clippy::too_many_arguments)]
    fn step<S: OdeSystem>(
        &mut self,
        system: &mut S,
        t: f64,
        y0: &[f64],
        h: f64,
        scale: &[f64],
        tol: f64,
        stats: &mut IntegratorStats,
        y1: &mut [f64],
    ) -> bool {
        let dim = y0.len();
        let tm = t + 0.5 * h;
        // Cheap linearizations: a fresh one at every step, else only when Newton fails.
        let cheap = self.mats.cheap_linearization();
        if cheap {
            self.jac_fresh = false;
        }
        for attempt in 0..2 {
            if attempt == 1 || cheap {
                if self.jac_fresh {
                    return false;
                }
                let ok = self.mats.linearize(system, tm, y0);
                stats.jacobian_evaluations += 1;
                self.jac_fresh = true;
                self.lu_h = None;
                if !ok {
                    return false;
                }
            }
            if self.lu_h != Some(h) {
                stats.factorizations += 1;
                if !self.mats.factor_real(system, 0, 2.0 / h) {
                    self.lu_h = None;
                    continue;
                }
                self.lu_h = Some(h);
            }
            self.z.copy_from_slice(y0);
            let mut old: Option<f64> = None;
            let mut ok = false;
            let min_iterations = super::min_newton_iterations(scale);
            for iteration in 1..=10 {
                stats.newton_iterations += 1;
                system.rhs(tm, &self.z, &mut self.f);
                stats.rhs_evaluations += 1;
                if self.f.iter().any(|v| !v.is_finite()) {
                    break;
                }
                // (I − h/2 J) dz = g  ⇔  ((2/h) I − J) dz = (2/h) g.
                for i in 0..dim {
                    self.dz[i] = (y0[i] + 0.5 * h * self.f[i] - self.z[i]) * (2.0 / h);
                }
                self.mats.solve_real(system, 0, &mut self.dz);
                let norm = scaled_rms(&self.dz, scale);
                for i in 0..dim {
                    self.z[i] += self.dz[i];
                }
                if !norm.is_finite() {
                    break;
                }
                if norm <= tol && iteration >= min_iterations {
                    ok = true;
                    break;
                }
                if let Some(o) = old {
                    let rate = norm / o;
                    // Converged to round-off: the corrections stopped shrinking but are already
                    // far below the error scale.
                    if rate > 0.9 {
                        ok = norm <= 1e-2;
                        break;
                    }
                    // Geometric convergence: the remaining corrections sum to rate/(1−rate)·norm.
                    if rate / (1.0 - rate) * norm <= tol {
                        ok = true;
                        break;
                    }
                }
                old = Some(norm);
            }
            if ok {
                for i in 0..dim {
                    y1[i] = 2.0 * self.z[i] - y0[i];
                }
                self.jac_fresh = false;
                return true;
            }
        }
        false
    }
}

impl ImplicitMidpoint {
    /// Integrate `system` from `(t0, y0)` and return the state at each of `t_out` (cubic Hermite
    /// interpolation between steps).
    ///
    /// # Errors
    /// As [`super::Dopri5::integrate`].
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
        let mut checks = check_output_times(t0, t_out)
            .and_then(|_| opts.tolerances.validate("options.tolerances", dim));
        if let Some(h) = opts.step {
            if !(h.is_finite() && h > 0.0) && checks.is_ok() {
                checks = Err(crate::InputError::new(
                    "options.step",
                    format!("must be a finite positive number, got {h}"),
                ));
            }
        }
        if let Err(e) = checks {
            return fail(traj, stats, SolveError::from_input(e));
        }
        let atol = opts.tolerances.atol(dim);
        let rtol = opts.tolerances.rtol;
        let t_end = t_out.last().copied().unwrap_or(t0);
        let mut t = t0;
        let mut y = y0.to_vec();
        let mut f0 = vec![0.0; dim];
        system.rhs(t, &y, &mut f0);
        stats.rhs_evaluations += 1;
        let mut next_out = outputs_at_start(t0, y0, t_out, &mut traj);
        let mut stage = Stage {
            mats: IterationMatrices::new(system),
            lu_h: None,
            jac_fresh: true,
            f: vec![0.0; dim],
            z: vec![0.0; dim],
            dz: vec![0.0; dim],
        };
        // A system that cannot be linearized at the start fails its first step's Newton
        // iteration, after one more try (`Stage::step`).
        let _ = stage.mats.linearize(system, t, &y);
        stats.jacobian_evaluations += 1;
        let mut h = match opts.step {
            Some(h) => h,
            None => initial_step(system, t, &y, &f0, &atol, rtol, 2, &mut stats),
        }
        .min(opts.max_step);
        let (mut y_big, mut y_half, mut y_two) = (vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]);
        let mut f1 = vec![0.0; dim];
        let mut err = vec![0.0; dim];
        while next_out < t_out.len() {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return fail(traj, stats, SolveError::TooManySteps { time: t, steps });
            }
            let mut h_try = h.min(t_end - t);
            if t_end - t - h_try <= 1e-8 * h_try {
                // Reach the end exactly: fixed steps that add up to the interval in exact
                // arithmetic leave a rounding-error remainder (5e-16 s) in floating point.
                h_try = t_end - t;
            }
            if h_try < 10.0 * f64::EPSILON * t.abs().max(1.0) || !h_try.is_finite() {
                return fail(
                    traj,
                    stats,
                    SolveError::StepSizeTooSmall {
                        time: t,
                        step: h_try,
                    },
                );
            }
            let scale: Vec<f64> = (0..dim).map(|i| atol[i] + rtol * y[i].abs()).collect();
            let tol = stage.mats.newton_tolerance(opts.newton_tolerance);
            let accepted = if opts.step.is_some() {
                // Fixed step: if Newton fails, cover the step with 2, 4, … equal sub-steps.
                let mut parts = 1usize;
                loop {
                    let sub = h_try / parts as f64;
                    let mut ok = true;
                    y_half.copy_from_slice(&y);
                    for k in 0..parts {
                        let t_k = t + k as f64 * sub;
                        ok = stage.step(
                            system, t_k, &y_half, sub, &scale, tol, &mut stats, &mut y_two,
                        );
                        if !ok {
                            break;
                        }
                        y_half.copy_from_slice(&y_two);
                    }
                    if ok {
                        break;
                    }
                    stats.rejected_steps += 1;
                    stats.newton_failures += 1;
                    stage.lu_h = None;
                    parts *= 2;
                    if parts > 1024 {
                        return fail(traj, stats, SolveError::NewtonFailed { time: t, step: sub });
                    }
                }
                Some(h)
            } else {
                // Step doubling: one step of h and two of h/2; the difference over 2² − 1
                // estimates the error of the two half steps, which are kept.
                let ok = stage.step(system, t, &y, h_try, &scale, tol, &mut stats, &mut y_big)
                    && stage.step(
                        system,
                        t,
                        &y,
                        0.5 * h_try,
                        &scale,
                        tol,
                        &mut stats,
                        &mut y_half,
                    )
                    && stage.step(
                        system,
                        t + 0.5 * h_try,
                        &y_half,
                        0.5 * h_try,
                        &scale,
                        tol,
                        &mut stats,
                        &mut y_two,
                    );
                if !ok {
                    stats.rejected_steps += 1;
                    stats.newton_failures += 1;
                    h = 0.25 * h_try;
                    stage.lu_h = None;
                    continue;
                }
                for i in 0..dim {
                    err[i] = (y_two[i] - y_big[i]) / 3.0;
                }
                let en = error_norm(&err, &y, &y_two, &atol, rtol);
                let factor = (0.9 * en.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 5.0);
                if en > 1.0 || !en.is_finite() {
                    stats.rejected_steps += 1;
                    h = h_try * if en.is_finite() { factor } else { 0.25 };
                    continue;
                }
                Some((h_try * factor).min(opts.max_step))
            };
            let t_new = t + h_try;
            system.rhs(t_new, &y_two, &mut f1);
            stats.rhs_evaluations += 1;
            while next_out < t_out.len() && t_out[next_out] <= t_new {
                let s = (t_out[next_out] - t) / h_try;
                let (h00, h10) = (
                    2.0 * s.powi(3) - 3.0 * s * s + 1.0,
                    s.powi(3) - 2.0 * s * s + s,
                );
                let (h01, h11) = (-2.0 * s.powi(3) + 3.0 * s * s, s.powi(3) - s * s);
                let yo: Vec<f64> = (0..dim)
                    .map(|i| {
                        h00 * y[i] + h10 * h_try * f0[i] + h01 * y_two[i] + h11 * h_try * f1[i]
                    })
                    .collect();
                traj.t.push(t_out[next_out]);
                traj.y.push(yo);
                next_out += 1;
            }
            t = t_new;
            y.copy_from_slice(&y_two);
            f0.copy_from_slice(&f1);
            stats.steps += 1;
            progress(t);
            if system.step_accepted(t, &y).is_break() {
                return failure(traj, stats, SolveError::Halted { time: t });
            }
            if let Some(hn) = accepted {
                h = hn;
            }
        }
        Ok((traj, stats))
    }
}
