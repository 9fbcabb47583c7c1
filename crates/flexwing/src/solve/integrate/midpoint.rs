//! The implicit midpoint rule `y₁ = y₀ + h f(t + h/2, (y₀ + y₁)/2)`: second order, A-stable,
//! symplectic, and it conserves quadratic invariants exactly, so the energy of an undamped
//! structure does not drift. Fixed step, or adaptive by step doubling (Richardson).
//!
//! The driver here (`integrate`: output, step control by a fixed step or step doubling) calls
//! the Newton iteration of one step in `midpoint_step.rs`.
//!
//! # References
//! Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., §II.1, §VI.3.

use super::dopri5::initial_step;
use super::midpoint_step::Stage;
use super::{
    check_output_times, error_norm, failure, outputs_at_start, IntegrationResult, IntegratorStats,
    OdeSystem, Tolerances, Trajectory,
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
        if let Err(e) = self.validate(t0, t_out, dim) {
            return failure(traj, stats, SolveError::from_input(e));
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
        let mut stage = Stage::new(system);
        // A system that cannot be linearized at the start fails its first step's Newton
        // iteration, after one more try (`Stage::step`).
        let _ = stage.mats.linearize(system, t, &y);
        stats.jacobian_evaluations += 1;
        let mut h = match opts.step {
            Some(h) => h,
            None => initial_step(system, t, &y, &f0, &atol, rtol, 2, &mut stats),
        }
        .min(opts.max_step);
        let mut sc = StepScratch {
            y_big: vec![0.0; dim],
            y_half: vec![0.0; dim],
            y_two: vec![0.0; dim],
            err: vec![0.0; dim],
        };
        let mut f1 = vec![0.0; dim];
        while next_out < t_out.len() {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return failure(traj, stats, SolveError::TooManySteps { time: t, steps });
            }
            let mut h_try = h.min(t_end - t);
            if t_end - t - h_try <= 1e-8 * h_try {
                // Reach the end exactly: fixed steps that add up to the interval in exact
                // arithmetic leave a rounding-error remainder (5e-16 s) in floating point.
                h_try = t_end - t;
            }
            if h_try < 10.0 * f64::EPSILON * t.abs().max(1.0) || !h_try.is_finite() {
                let e = SolveError::StepSizeTooSmall {
                    time: t,
                    step: h_try,
                };
                return failure(traj, stats, e);
            }
            let scale: Vec<f64> = (0..dim).map(|i| atol[i] + rtol * y[i].abs()).collect();
            let tol = stage.mats.newton_tolerance(opts.newton_tolerance);
            let ctx = (t, y.as_slice(), h_try, scale.as_slice(), tol);
            let accepted = if opts.step.is_some() {
                if let Err(e) = fixed_step(system, &mut stage, ctx, &mut sc, &mut stats) {
                    return failure(traj, stats, e);
                }
                Some(h)
            } else {
                match self.doubling_step(system, &mut stage, ctx, &atol, &mut sc, &mut stats) {
                    Ok(h_next) => Some(h_next),
                    Err(h_retry) => {
                        h = h_retry;
                        continue;
                    }
                }
            };
            let t_new = t + h_try;
            system.rhs(t_new, &sc.y_two, &mut f1);
            stats.rhs_evaluations += 1;
            let ends = (
                (t, y.as_slice(), f0.as_slice()),
                (h_try, sc.y_two.as_slice(), f1.as_slice()),
            );
            next_out = hermite_outputs(ends, t_out, next_out, &mut traj);
            t = t_new;
            y.copy_from_slice(&sc.y_two);
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

    /// The output times and the options.
    fn validate(&self, t0: f64, t_out: &[f64], dim: usize) -> Result<(), crate::InputError> {
        let opts = &self.options;
        check_output_times(t0, t_out)?;
        opts.tolerances.validate("options.tolerances", dim)?;
        match opts.step {
            Some(h) if !(h.is_finite() && h > 0.0) => Err(crate::InputError::new(
                "options.step",
                format!("must be a finite positive number, got {h}"),
            )),
            _ => Ok(()),
        }
    }

    /// Step doubling: one step of h and two of h/2; the difference over 2² − 1 estimates the
    /// error of the two half steps, which are kept (in `sc.y_two`). The next step, or `Err` with
    /// the step to retry with (the step is rejected).
    fn doubling_step<S: OdeSystem>(
        &self,
        system: &mut S,
        stage: &mut Stage,
        (t, y, h_try, scale, tol): StepContext<'_>,
        atol: &[f64],
        sc: &mut StepScratch,
        stats: &mut IntegratorStats,
    ) -> Result<f64, f64> {
        let rtol = self.options.tolerances.rtol;
        let ok = stage.step(system, t, y, h_try, scale, tol, stats, &mut sc.y_big)
            && stage.step(system, t, y, 0.5 * h_try, scale, tol, stats, &mut sc.y_half)
            && stage.step(
                system,
                t + 0.5 * h_try,
                &sc.y_half,
                0.5 * h_try,
                scale,
                tol,
                stats,
                &mut sc.y_two,
            );
        if !ok {
            stats.rejected_steps += 1;
            stats.newton_failures += 1;
            stage.lu_h = None;
            return Err(0.25 * h_try);
        }
        for i in 0..y.len() {
            sc.err[i] = (sc.y_two[i] - sc.y_big[i]) / 3.0;
        }
        let en = error_norm(&sc.err, y, &sc.y_two, atol, rtol);
        let factor = (0.9 * en.max(1e-10).powf(-1.0 / 3.0)).clamp(0.2, 5.0);
        if en > 1.0 || !en.is_finite() {
            stats.rejected_steps += 1;
            return Err(h_try * if en.is_finite() { factor } else { 0.25 });
        }
        Ok((h_try * factor).min(self.options.max_step))
    }
}

/// A step's start `t, y`, size, error scale and Newton tolerance.
type StepContext<'a> = (f64, &'a [f64], f64, &'a [f64], f64);

/// The step results: the full step, the first half step, the second (the step's result) and
/// the error estimate.
struct StepScratch {
    y_big: Vec<f64>,
    y_half: Vec<f64>,
    y_two: Vec<f64>,
    err: Vec<f64>,
}

/// Fixed step: if Newton fails, cover the step with 2, 4, … equal sub-steps (result in
/// `sc.y_two`); a Newton failure at 1024 sub-steps stops the run.
fn fixed_step<S: OdeSystem>(
    system: &mut S,
    stage: &mut Stage,
    (t, y, h_try, scale, tol): StepContext<'_>,
    sc: &mut StepScratch,
    stats: &mut IntegratorStats,
) -> Result<(), SolveError> {
    let mut parts = 1usize;
    loop {
        let sub = h_try / parts as f64;
        let mut ok = true;
        sc.y_half.copy_from_slice(y);
        for k in 0..parts {
            let t_k = t + k as f64 * sub;
            ok = stage.step(
                system,
                t_k,
                &sc.y_half,
                sub,
                scale,
                tol,
                stats,
                &mut sc.y_two,
            );
            if !ok {
                break;
            }
            sc.y_half.copy_from_slice(&sc.y_two);
        }
        if ok {
            return Ok(());
        }
        stats.rejected_steps += 1;
        stats.newton_failures += 1;
        stage.lu_h = None;
        parts *= 2;
        if parts > 1024 {
            return Err(SolveError::NewtonFailed { time: t, step: sub });
        }
    }
}

/// The output times in `(t, t + h]` by cubic Hermite interpolation between the step's ends
/// `((t, y0, f0), (h, y1, f1))`; returns the index of the next output time.
#[allow(clippy::type_complexity)]
fn hermite_outputs(
    ((t, y0, f0), (h, y1, f1)): ((f64, &[f64], &[f64]), (f64, &[f64], &[f64])),
    t_out: &[f64],
    mut next_out: usize,
    traj: &mut Trajectory,
) -> usize {
    while next_out < t_out.len() && t_out[next_out] <= t + h {
        let s = (t_out[next_out] - t) / h;
        let (h00, h10) = (
            2.0 * s.powi(3) - 3.0 * s * s + 1.0,
            s.powi(3) - 2.0 * s * s + s,
        );
        let (h01, h11) = (-2.0 * s.powi(3) + 3.0 * s * s, s.powi(3) - s * s);
        let yo: Vec<f64> = (0..y0.len())
            .map(|i| h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i])
            .collect();
        traj.t.push(t_out[next_out]);
        traj.y.push(yo);
        next_out += 1;
    }
    next_out
}
