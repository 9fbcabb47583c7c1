//! The generalized-α method for first-order systems `y' = f(t, y)` of Jansen, Whiting & Hulbert:
//! second order, A-stable, with the spectral radius `ρ∞` of its amplification at `h|λ| → ∞` set
//! by the user, so that the unresolved high modes of a structure are damped while the modes the
//! step resolves are barely touched. `ρ∞ = 1` is the implicit midpoint rule (no damping,
//! symplectic); `ρ∞ = 0` removes the modes far beyond the step's resolution within a step or two.
//! Adaptive step from a local error estimate, or a fixed step.
//!
//! One step from `(y_n, ẏ_n)` (the method carries a rate `ẏ` besides `y`):
//!
//! ```text
//! ẏ_{n+α_m} = f(t_n + α_f h, y_{n+α_f})
//! y_{n+1}   = y_n + h ẏ_n + γ h (ẏ_{n+1} − ẏ_n)
//! y_{n+α_f} = y_n + α_f (y_{n+1} − y_n),   ẏ_{n+α_m} = ẏ_n + α_m (ẏ_{n+1} − ẏ_n)
//! α_m = (3 − ρ∞) / (2 (1 + ρ∞)),   α_f = γ = 1 / (1 + ρ∞)
//! ```
//!
//! Newton's method solves for `Δ = y_{n+1} − y_n` with the matrix `c I − J`, `c = α_m / (α_f γ h)`
//! (the shifted Jacobian of the other implicit integrators, factored by their `IterationMatrices`:
//! the system's O(n) chain solver for the full beam model, else the dense Jacobian and LU). The choice of this form over a second-order (Chung–Hulbert) one, the local
//! error estimate, the treatment of variable steps and the dense output are derived in
//! `docs/model-choices.md` ("Generalized-α"); in short:
//!
//! * `ẏ_n` approximates `y'(t_n + δ h)` with `δ = α_f − α_m` (to `O(h²)`); when the step changes
//!   from `h_old` to `h`, `ẏ_n` is moved by `δ (h − h_old) ÿ` so that the method stays of
//!   second order on any step sequence.
//! * Local error `C h³ y'''` with `C = (ρ∞² − ρ∞ + 1) / (3 (1 + ρ∞)²)` (the constant of the
//!   principal root on `y' = λy`), `y'''` from the third divided difference of the last four
//!   solution values, filtered by `(I − J/c)⁻¹` so that components far beyond the step's
//!   resolution (which the method damps and does not follow) do not set the step.
//! * The first two steps have no four-point history: they are checked by the estimate of the
//!   third, and the run restarts with a smaller step if it fails.
//! * Output between steps: the quadratic through the last three solution values.
//!
//! # References
//! K. E. Jansen, C. H. Whiting, G. M. Hulbert, "A generalized-α method for integrating the
//! filtered Navier–Stokes equations with a stabilized finite element method", Comput. Methods
//! Appl. Mech. Engrg. 190 (2000) 305–319 (the method, its parameters and its spectral analysis).
//! J. Chung, G. M. Hulbert, "A time integration algorithm for structural dynamics with improved
//! numerical dissipation: the generalized-α method", J. Appl. Mech. 60 (1993) 371–375.
//! C. Kadapa, W. G. Dettmer, D. Perić, "On the advantages of using the first-order generalised-
//! alpha scheme for structural dynamic problems", Comput. Struct. 193 (2017) 226–238 (the
//! first-order form applied to structures).
//! E. Hairer, S. P. Nørsett, G. Wanner, *Solving Ordinary Differential Equations I*, §III.5–III.7
//! (variable-step multistep methods and their error estimates from differences).
//! E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, §IV.8 (the filtered error
//! estimate and the Newton control of `RADAU5`, followed here); L. F. Shampine, "Implementation
//! of implicit formulas for the solution of ODEs", SIAM J. Sci. Stat. Comput. 1 (1980) 103–118
//! (the filter).

use super::dopri5::initial_step;
#[cfg(test)]
use super::generalized_alpha_step::Parameters;
use super::generalized_alpha_step::{Newton, State, Stepper};
use super::{
    check_output_times, failure, outputs_at_start, IntegrationResult, IntegratorStats, OdeSystem,
    Tolerances, Trajectory,
};
use crate::error::SolveError;

/// Options of [`GeneralizedAlpha`].
#[derive(Debug, Clone, PartialEq)]
pub struct GeneralizedAlphaOptions {
    /// Error tolerances of the adaptive step (with a fixed `step`, they only scale the Newton
    /// tolerance).
    pub tolerances: Tolerances,
    /// Spectral radius `ρ∞ ∈ [0, 1]` of the amplification at `h ω → ∞`: the fraction of a mode
    /// far beyond the step's resolution that survives one step. Default 0.5.
    pub spectral_radius: f64,
    /// Fixed step (s); `None` (default) for the adaptive step.
    pub step: Option<f64>,
    /// Largest step (s). Default infinite.
    pub max_step: f64,
    /// Budget of steps, accepted and rejected, before the run stops with
    /// [`SolveError::TooManySteps`] and the output so far. Default 1 000 000.
    pub max_steps: usize,
    /// First step (s); `None` (default) picks one from the problem's scales.
    pub first_step: Option<f64>,
    /// Largest number of Newton iterations per step. Default 7.
    pub max_newton_iterations: usize,
    /// Contraction rate of the Newton iteration below which the Jacobian is kept for the next
    /// step (as [`super::RadauOptions::jacobian_reuse`]). Default 0.1; a negative value
    /// recomputes it at every step.
    pub jacobian_reuse: f64,
    /// Newton stops when its estimated remaining error is below this fraction of the error
    /// scale `atol + rtol |y|`. Default 0.03 (`RADAU5`'s `FNEWT` at moderate tolerances). With a
    /// fixed step the tolerances serve only this scale. Unlike Radau's, it is not tightened to
    /// the system's bound (`NewtonSolver::newton_tolerance`): see `integrate`.
    pub newton_tolerance: f64,
    /// When the proposed new step over the current one lies in `[lower, upper]`, the step and
    /// the factorization are kept (as [`super::RadauOptions::unchanged_step_ratio`]). Default
    /// `(0.9, 2.0)`: an LU of `c I − J` costs several right-hand sides.
    pub unchanged_step_ratio: (f64, f64),
}

impl Default for GeneralizedAlphaOptions {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            spectral_radius: 0.5,
            step: None,
            max_step: f64::INFINITY,
            max_steps: 1_000_000,
            first_step: None,
            max_newton_iterations: 7,
            jacobian_reuse: 0.1,
            newton_tolerance: 0.03,
            unchanged_step_ratio: (0.9, 2.0),
        }
    }
}

/// The generalized-α integrator in first-order form: second order, with the numerical damping
/// of the unresolved high modes set by [`GeneralizedAlphaOptions::spectral_radius`].
///
/// Counters: `rhs_evaluations` counts one per Newton iteration plus those of the start;
/// `factorizations` the LUs of `c I − J`; `newton_iterations` the linear solves of Newton.
#[derive(Debug, Clone, Default)]
pub struct GeneralizedAlpha {
    /// Options.
    pub options: GeneralizedAlphaOptions,
}

/// Safety factor of the step-size selection.
const SAFETY: f64 = 0.9;
/// The step shrinks at most 5-fold and grows at most 4-fold per step.
const FAC_MIN: f64 = 0.2;
const FAC_MAX: f64 = 4.0;

impl GeneralizedAlpha {
    fn validate(&self, dim: usize) -> Result<(), crate::InputError> {
        let o = &self.options;
        o.tolerances.validate("dynamic.tolerances", dim)?;
        let bad = |field: &str, msg: String| Err(crate::InputError::new(field, msg));
        let rho = o.spectral_radius;
        if !(0.0..=1.0).contains(&rho) {
            return bad(
                "dynamic.spectral_radius",
                format!("must be between 0 and 1, got {rho}"),
            );
        }
        for (field, v, finite) in [
            ("dynamic.step", o.step, true),
            ("dynamic.max_step", Some(o.max_step), false),
            ("dynamic.first_step", o.first_step, true),
            ("dynamic.newton_tolerance", Some(o.newton_tolerance), true),
        ] {
            if let Some(v) = v {
                if !(v > 0.0) || (finite && !v.is_finite()) {
                    let what = if finite {
                        "finite positive"
                    } else {
                        "positive"
                    };
                    return bad(field, format!("must be a {what} number, got {v}"));
                }
            }
        }
        if o.max_newton_iterations == 0 {
            return bad(
                "dynamic.max_newton_iterations",
                "must be at least 1, got 0".into(),
            );
        }
        if o.jacobian_reuse.is_nan() || o.jacobian_reuse >= 1.0 {
            return bad(
                "dynamic.jacobian_reuse",
                format!("must be below 1, got {}", o.jacobian_reuse),
            );
        }
        let (q1, q2) = o.unchanged_step_ratio;
        if !(q1 > 0.0 && q1 <= 1.0 && q2 >= 1.0 && q2.is_finite()) {
            return bad(
                "dynamic.unchanged_step_ratio",
                format!("needs 0 < lower ≤ 1 ≤ upper (finite), got ({q1}, {q2})"),
            );
        }
        Ok(())
    }

    /// Integrate `system` from `(t0, y0)` and return the state at each of `t_out`
    /// (non-decreasing, not before `t0`), from the quadratic through the last three solution
    /// values. `progress` is called with the time after each step.
    ///
    /// # Errors
    /// Invalid output times or options are [`crate::InputError`]s wrapped in the failure; a step
    /// size below round-off (after repeated error-test or Newton failures), a non-finite state or
    /// the step budget stop the run with the output so far.
    pub fn integrate<S: OdeSystem>(
        &self,
        system: &mut S,
        t0: f64,
        y0: &[f64],
        t_out: &[f64],
        progress: &mut dyn FnMut(f64),
    ) -> IntegrationResult {
        let n = system.dim();
        let opts = &self.options;
        let mut stats = IntegratorStats::default();
        let mut traj = Trajectory::default();
        if let Err(e) = check_output_times(t0, t_out).and_then(|_| self.validate(n)) {
            return failure(traj, stats, SolveError::from_input(e));
        }
        let t_end = t_out.last().copied().unwrap_or(t0);
        let first_out = outputs_at_start(t0, y0, t_out, &mut traj);
        if first_out == t_out.len() {
            return Ok((traj, stats));
        }
        let first_len = traj.t.len();
        let mut next_out = first_out;
        let (atol, rtol) = (opts.tolerances.atol(n), opts.tolerances.rtol);
        let adaptive = opts.step.is_none();

        let mut f0 = vec![0.0; n];
        system.rhs(t0, y0, &mut f0);
        stats.rhs_evaluations += 1;
        if f0.iter().any(|v| !v.is_finite()) {
            return failure(traj, stats, SolveError::NonFinite { time: t0 });
        }
        let (mut h, hmax, startup_max) =
            self.first_step(system, t0, y0, &f0, t_end, &atol, &mut stats);
        let mut st = State::new(t0, y0, &f0);
        let mut step = Stepper::new(system, opts.spectral_radius);
        // A structured solver that linearizes cheaply does it at every step (fewer iterations).
        let relinearize = step.cheap_linearization();
        let mut ctl = Control {
            need_jac: true,
            jac_current: false,
            last_failure_non_finite: false,
            after_rejection: false,
        };

        loop {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return failure(traj, stats, SolveError::TooManySteps { time: st.t, steps });
            }
            let t = st.t;
            // Reach the end exactly; a step that would stop a rounding error short of it is
            // stretched.
            let last = t + h >= t_end - 1e-8 * h;
            if last {
                h = t_end - t;
            }
            if !(h > 10.0 * f64::EPSILON * t.abs().max(1.0)) || !h.is_finite() {
                let e = if ctl.last_failure_non_finite {
                    SolveError::NonFinite { time: t }
                } else if adaptive {
                    SolveError::StepSizeTooSmall { time: t, step: h }
                } else {
                    SolveError::NewtonFailed { time: t, step: h }
                };
                return failure(traj, stats, e);
            }
            let theta =
                match self.solve_step(system, &mut step, (&st, h), &atol, &mut ctl, &mut stats) {
                    Newton::Converged { theta } => theta,
                    Newton::Failed { non_finite } => {
                        // A stale Jacobian first, then a smaller step.
                        ctl.last_failure_non_finite = non_finite;
                        stats.rejected_steps += 1;
                        stats.newton_failures += 1;
                        ctl.after_rejection = true;
                        if ctl.jac_current {
                            h *= 0.5;
                        } else {
                            ctl.need_jac = true;
                        }
                        continue;
                    }
                };
            ctl.last_failure_non_finite = false;
            let t_new = if last { t_end } else { t + h };

            let mut factor = None;
            if adaptive {
                if let Some(e) = step.error(system, &st, t_new, h, &atol, rtol) {
                    let f = (SAFETY * e.max(1e-10).powf(-1.0 / 3.0)).clamp(FAC_MIN, FAC_MAX);
                    if e > 1.0 {
                        stats.rejected_steps += 1;
                        ctl.after_rejection = true;
                        h *= f;
                        if st.past_t[0] == t0 {
                            // The first estimate also judged the two unchecked steps before
                            // it: restart from the initial state with the step it asks for.
                            stats.rejected_steps += 2;
                            stats.steps -= 2;
                            st.reset(t0, y0, &f0);
                            traj.t.truncate(first_len);
                            traj.y.truncate(first_len);
                            next_out = first_out;
                            ctl.need_jac = true;
                        }
                        continue;
                    }
                    factor = Some(if ctl.after_rejection { f.min(1.0) } else { f });
                }
            }

            // Accepted.
            stats.steps += 1;
            ctl.after_rejection = false;
            next_out = emit_outputs(&st, &step, t_new, last, t_out, next_out, &mut traj);
            st.accept(&mut step, t_new, h);
            ctl.jac_current = false;
            progress(st.t);
            if system.step_accepted(st.t, &st.y).is_break() {
                return failure(traj, stats, SolveError::Halted { time: st.t });
            }
            if last || next_out == t_out.len() {
                return Ok((traj, stats));
            }
            ctl.need_jac = relinearize || theta > opts.jacobian_reuse;
            h = self.next_step(h, factor, ctl.need_jac).min(hmax);
            if st.past_count < 2 {
                h = h.min(startup_max);
            }
        }
    }

    /// The first step, the largest step, and the largest step of the first two (in adaptive
    /// mode at least three steps, so that the first estimate, at the third step, checks the
    /// first two).
    #[allow(clippy::too_many_arguments)]
    fn first_step<S: OdeSystem>(
        &self,
        system: &mut S,
        t0: f64,
        y0: &[f64],
        f0: &[f64],
        t_end: f64,
        atol: &[f64],
        stats: &mut IntegratorStats,
    ) -> (f64, f64, f64) {
        let opts = &self.options;
        let startup_max = if opts.step.is_none() {
            (t_end - t0) / 3.0
        } else {
            f64::INFINITY
        };
        let hmax = opts.max_step.min(t_end - t0);
        let rtol = opts.tolerances.rtol;
        let h = match (opts.step, opts.first_step) {
            (Some(h), _) | (None, Some(h)) => h,
            // Half the usual guess: the first two steps are only checked at the third.
            (None, None) => 0.5 * initial_step(system, t0, y0, f0, atol, rtol, 2, stats),
        }
        .min(hmax)
        .min(startup_max);
        (h, hmax, startup_max)
    }

    /// The Newton iteration of a step of size `h` from `st`: a fresh linearization if asked for,
    /// the predictor, the factorization and the iterations.
    fn solve_step<S: OdeSystem>(
        &self,
        system: &mut S,
        step: &mut Stepper,
        (st, h): (&State, f64),
        atol: &[f64],
        ctl: &mut Control,
        stats: &mut IntegratorStats,
    ) -> Newton {
        let opts = &self.options;
        let mut jac_ok = true;
        if ctl.need_jac {
            jac_ok = step.linearize(system, st.t, &st.y);
            stats.jacobian_evaluations += 1;
            ctl.jac_current = true;
            ctl.need_jac = false;
        }
        step.predict(st, h, atol, opts.tolerances.rtol);
        if !(jac_ok && step.factor(system, h, stats)) {
            return Newton::Failed { non_finite: false };
        }
        // The option alone, not tightened to the system's bound
        // (`NewtonSolver::newton_tolerance`, which Radau needs for the full model's joint
        // momenta): with generalized-α's predictor the bound only doubles the iterations.
        // Measured on case (b) with fixed 0.5 ms steps (docs/performance.md): the same tip error
        // (2.01e-4 m at n = 3000 and 10 000) with 1.15 instead of 2.0 iterations per step.
        let tol = opts.newton_tolerance;
        step.newton(system, st, h, tol, opts.max_newton_iterations, stats)
    }

    /// The step after an accepted one of size `h`, whose error estimate asked for `factor`.
    fn next_step(&self, h: f64, factor: Option<f64>, need_jac: bool) -> f64 {
        let (keep_lower, keep_upper) = self.options.unchanged_step_ratio;
        match (self.options.step, factor) {
            (Some(hf), _) => hf,
            // Keep the step, and the factorization, for moderate changes.
            (None, Some(f)) if (keep_lower..=keep_upper).contains(&f) && !need_jac => h,
            (None, Some(f)) => h * f,
            // The first two steps keep the first step.
            (None, None) => h,
        }
    }
}

/// The driver's flags about the Newton matrix and the last failure.
struct Control {
    need_jac: bool,
    /// The Jacobian is at the current `(t, y)`.
    jac_current: bool,
    last_failure_non_finite: bool,
    after_rejection: bool,
}

/// The outputs up to `t_new` of the accepted step from `st` (except on the first step, whose
/// outputs wait for the quadratic through three values: they are emitted at the second);
/// returns the index of the next output time.
fn emit_outputs(
    st: &State,
    step: &Stepper,
    t_new: f64,
    last: bool,
    t_out: &[f64],
    mut next_out: usize,
    traj: &mut Trajectory,
) -> usize {
    let emit_until = if st.past_count > 0 || last {
        t_new
    } else {
        st.t
    };
    while next_out < t_out.len() && t_out[next_out] <= emit_until {
        let tt = t_out[next_out];
        traj.t.push(tt);
        traj.y.push(st.interpolate(t_new, &step.y_new, tt));
        next_out += 1;
    }
    next_out
}

#[cfg(test)]
mod tests;
