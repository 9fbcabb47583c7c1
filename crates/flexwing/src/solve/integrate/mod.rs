//! Time integrators for first-order systems `y' = f(t, y)`: an explicit adaptive Runge–Kutta
//! (Dormand–Prince 5(4)), a variable-step variable-order BDF/NDF (the family of MATLAB's
//! `ode15s`), the three-stage Radau IIA method of order 5 (Hairer & Wanner's `RADAU5`, for stiff
//! systems), and the implicit midpoint rule (symplectic, for structural dynamics).
//!
//! One runtime choice selects them: [`Method`], with the [`IntegratorSettings`] every method reads
//! (tolerances, step limits) and the one dispatcher [`integrate`]; each method's own type and
//! options stay public for tuning beyond the shared settings.
//!
//! Each returns the solution at the requested output times (dense output, no extra steps) and its
//! counters. The implicit ones solve their Newton systems `(c I − J) Δ = r` with the system's own
//! solver when it offers one ([`OdeSystem::newton_solver`]), else by dense LU factorizations of
//! the Jacobian (`iteration.rs`). A run that cannot continue returns the output produced so far with the error, so that
//! callers can keep it and mark it incomplete.

mod bdf;
mod bdf_step;
mod dopri5;
mod generalized_alpha;
mod generalized_alpha_step;
mod iteration;
mod lu;
mod method;
mod midpoint;
mod midpoint_step;
mod radau;
mod radau_step;

pub use bdf::{Bdf, BdfOptions};
pub use dopri5::{Dopri5, Dopri5Options};
pub use generalized_alpha::{GeneralizedAlpha, GeneralizedAlphaOptions};
pub use method::{integrate, IntegratorSettings, Method, MIN_RTOL};
pub use midpoint::{ImplicitMidpoint, MidpointOptions};
pub use radau::{Radau, RadauOptions};

#[cfg(test)]
pub(crate) use iteration::assert_quadrature_rows;
pub(crate) use iteration::IterationMatrices;
pub(crate) use lu::{ComplexLu, DenseLu};

use std::ops::ControlFlow;

use nalgebra::{Complex, DMatrix};

use crate::error::SolveError;

/// A first-order system `y' = f(t, y)` with its Jacobian `∂f/∂y`. Implementations keep their
/// scratch inside, hence `&mut self`.
pub trait OdeSystem {
    /// Dimension of `y`.
    fn dim(&self) -> usize;
    /// `dy = f(t, y)`.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    /// `jac = ∂f/∂y (t, y)` (`dim × dim`).
    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>);
    /// The scale of each component's absolute tolerance (`dim` values, 1 on entry): [`integrate`]
    /// uses `atol · scale[i]`, so that one tolerance fits components of different units. An
    /// infinite scale makes a component uncontrolled: it is integrated like the others but left
    /// out of every error norm (quadrature states, such as the work of the loads).
    fn atol_scale(&mut self, scale: &mut [f64]) {
        scale.fill(1.0);
    }

    /// Called by every integrator after each accepted step, with the time and the state reached
    /// (the output times up to `t` are already recorded). `ControlFlow::Break` stops the run
    /// there: the integrator returns the output so far with [`SolveError::Halted`]. Default:
    /// continue.
    fn step_accepted(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        let _ = (t, y);
        ControlFlow::Continue(())
    }

    /// The system's own solver of the implicit integrators' Newton systems `(c I − J) x = b`,
    /// when it has one that is faster than a dense LU factorization of `J` (a structured
    /// factorization, an approximate Jacobian for a simplified Newton iteration, …). The
    /// default, `None`, makes the integrators form `J` with [`OdeSystem::jacobian`] and factor
    /// `c I − J` densely. The answer must not change during an integration.
    fn newton_solver(&mut self) -> Option<&mut dyn NewtonSolver> {
        None
    }

    /// The number of trailing components of `y` that are quadratures: their rates depend on the
    /// other components, and no rate depends on them (the energy audit's work and dissipation
    /// integrals). The implicit integrators then solve their Newton systems for the other
    /// components alone (the Jacobian's leading block, or the system's [`NewtonSolver`] on the
    /// leading part) and take the quadratures' part from [`OdeSystem::quadrature_step_real`] and
    /// [`OdeSystem::quadrature_step_complex`], so that one Newton iteration converges them
    /// with the other stages; Radau IIA takes its quadrature of each stage's own rate moved by
    /// the Newton correction instead ([`OdeSystem::keep_quadrature_point`],
    /// [`OdeSystem::quadrature_gradient`]). Default 0.
    fn quadrature_states(&self) -> usize {
        0
    }

    /// The quadratures' part of the Newton step `(c I − J) Δ = b` for a real shift `c`: `lead`
    /// is `b`'s leading part as it was, `dy` its solution, and `q` the quadratures' part of `b`,
    /// replaced by theirs: with `g_k` the gradient of quadrature `k`'s rate with respect to the
    /// leading components (its row of `J`), `Δq_k = (b_q,k + g_k·dy) / c`. Default: `g = 0`.
    fn quadrature_step_real(&mut self, c: f64, lead: &[f64], dy: &[f64], q: &mut [f64]) {
        let _ = (lead, dy);
        for v in q {
            *v /= c;
        }
    }

    /// As [`OdeSystem::quadrature_step_real`] for a complex shift, each vector as its real and
    /// imaginary parts.
    fn quadrature_step_complex(
        &mut self,
        c: Complex<f64>,
        lead: (&[f64], &[f64]),
        dy: (&[f64], &[f64]),
        q: (&mut [f64], &mut [f64]),
    ) {
        let _ = (lead, dy);
        for (r, i) in q.0.iter_mut().zip(q.1.iter_mut()) {
            let v = Complex::new(*r, *i) / c;
            (*r, *i) = (v.re, v.im);
        }
    }

    /// Keep the terms of the last right-hand side that the quadratures' gradient needs (the
    /// energy audit's `Q`, `ẋ`, `C ẋ`) as point `slot` (0, 1, 2) for
    /// [`OdeSystem::quadrature_gradient`]: Radau IIA keeps one per stage. Default: nothing.
    fn keep_quadrature_point(&mut self, slot: usize) {
        let _ = slot;
    }

    /// `out_k = g_k·dy` for each quadrature `k`, with `g_k` the gradient of its rate with respect
    /// to the leading components at the point kept in `slot`
    /// ([`OdeSystem::keep_quadrature_point`]), `dy` a step of the leading components and
    /// `dy_rate` the change of their rates `J̃ dy` by the Newton systems' linearization (what
    /// the step moves `ẋ` by). Radau IIA moves each stage's quadrature rate by it, so that its
    /// quadratures are the method's quadrature of the rates at the converged stages after one
    /// Newton iteration. Default: zeros (`g = 0`).
    fn quadrature_gradient(&mut self, slot: usize, dy: &[f64], dy_rate: &[f64], out: &mut [f64]) {
        let _ = (slot, dy, dy_rate);
        out.fill(0.0);
    }

    /// Told by [`integrate`] before it runs which method and settings will solve the system, so
    /// that a system with several ways to solve its Newton systems can take the faster one for
    /// them (the equations of motion: `NewtonSystems::Auto`, whose dense/chain crossover depends
    /// on the method and the step control). Default: nothing.
    fn integrating_with(&mut self, method: Method, settings: &IntegratorSettings) {
        let _ = (method, settings);
    }
}

/// Solves the Newton systems `(c I − J̃) x = b` of the implicit integrators for real and complex
/// shifts `c` (on the components before the quadratures, [`OdeSystem::quadrature_states`]: `b`
/// has `dim − quadrature_states` entries), `J̃` the system's Jacobian or an approximation of it (then the integrators' Newton
/// iterations are simplified Newton iterations, and converge more slowly), taken at the point
/// of the last [`NewtonSolver::linearize`]. Shifts are factored into numbered slots that are
/// kept independently (Radau IIA keeps a real and a complex one; BDF, the midpoint rule and
/// generalized-α one real one), real and complex slots apart.
pub trait NewtonSolver {
    /// Take `(t, y)` as the point of `J̃` (what [`OdeSystem::jacobian`] is to the dense path).
    /// False if the system cannot be linearized there (the integrator then shrinks its step).
    fn linearize(&mut self, t: f64, y: &[f64]) -> bool;
    /// Factor `c I − J̃` for the real shift `c` into real slot `slot`. False if it is singular.
    fn factor_real(&mut self, slot: usize, c: f64) -> bool;
    /// Factor `c I − J̃` for the complex shift `c` into complex slot `slot`. False if singular.
    fn factor_complex(&mut self, slot: usize, c: Complex<f64>) -> bool;
    /// `b ← (c I − J̃)⁻¹ b` with the factorization in real slot `slot`.
    fn solve_real(&mut self, slot: usize, b: &mut [f64]);
    /// `re + i im ← (c I − J̃)⁻¹ (re + i im)` with the factorization in complex slot `slot`.
    fn solve_complex(&mut self, slot: usize, re: &mut [f64], im: &mut [f64]);
    /// Whether a linearization and its factorizations cost less than a step, so that the
    /// integrators linearize at every step instead of reusing `J̃` while Newton converges
    /// (a fresh `J̃` converges in fewer iterations). Default false.
    fn cheap_linearization(&self) -> bool {
        false
    }
    /// The loosest stopping tolerance of the Newton iterations, relative to the error scale,
    /// that the system can take, when tighter than the integrators' defaults (`None`, the
    /// default, for no bound). An option set by the caller wins over it.
    fn newton_tolerance(&self) -> Option<f64> {
        None
    }
}

/// Counters of an integration (what SciPy reports as nfev, njev, nlu).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct IntegratorStats {
    /// Accepted steps.
    pub steps: usize,
    /// Rejected steps (error too large or Newton failure).
    pub rejected_steps: usize,
    /// Of the rejected steps, those whose Newton iteration failed (diverged, converged too
    /// slowly or met a singular matrix) rather than the error test (implicit methods).
    pub newton_failures: usize,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
    /// LU factorizations of iteration matrices.
    pub factorizations: usize,
    /// Newton iterations (implicit methods).
    pub newton_iterations: usize,
}

impl std::ops::AddAssign for IntegratorStats {
    /// Accumulate the counters of another run (a run continued in pieces).
    fn add_assign(&mut self, b: Self) {
        self.steps += b.steps;
        self.rejected_steps += b.rejected_steps;
        self.newton_failures += b.newton_failures;
        self.rhs_evaluations += b.rhs_evaluations;
        self.jacobian_evaluations += b.jacobian_evaluations;
        self.factorizations += b.factorizations;
        self.newton_iterations += b.newton_iterations;
    }
}

/// States at the output times.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Trajectory {
    /// Output times (s).
    pub t: Vec<f64>,
    /// State at each output time.
    pub y: Vec<Vec<f64>>,
}

/// An integration that stopped before the end: what was computed, and why it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegrationFailure {
    /// Output produced before the failure.
    pub trajectory: Trajectory,
    /// Counters up to the failure.
    pub stats: IntegratorStats,
    /// The reason, with the time reached.
    pub error: SolveError,
}

impl std::fmt::Display for IntegrationFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for IntegrationFailure {}

/// Result of an integration.
pub type IntegrationResult = Result<(Trajectory, IntegratorStats), Box<IntegrationFailure>>;

/// The failure result of a run that stopped: the output so far, the counters and the reason.
pub(crate) fn failure(
    trajectory: Trajectory,
    stats: IntegratorStats,
    error: SolveError,
) -> IntegrationResult {
    Err(Box::new(IntegrationFailure {
        trajectory,
        stats,
        error,
    }))
}

/// Record `y0` for the output times at or before `t0`; returns the index of the next output.
pub(crate) fn outputs_at_start(t0: f64, y0: &[f64], t_out: &[f64], traj: &mut Trajectory) -> usize {
    let mut next = 0;
    while next < t_out.len() && t_out[next] <= t0 {
        traj.t.push(t_out[next]);
        traj.y.push(y0.to_vec());
        next += 1;
    }
    next
}

/// Check output times against the start time: finite, non-decreasing, none before `t0`.
pub(crate) fn check_output_times(t0: f64, t_out: &[f64]) -> Result<(), crate::InputError> {
    for (i, &t) in t_out.iter().enumerate() {
        if !t.is_finite() || t < t0 || (i > 0 && t < t_out[i - 1]) {
            return Err(crate::InputError::new(
                format!("output_times[{i}]"),
                format!(
                    "must be finite, non-decreasing and not before the start time {t0} s, got {t}"
                ),
            ));
        }
    }
    Ok(())
}

/// Weighted RMS norm of `err` with scale `atol_i + rtol max(|a_i|, |b_i|)`, over the
/// error-controlled components (see [`scaled_rms`]).
pub(crate) fn error_norm(err: &[f64], a: &[f64], b: &[f64], atol: &[f64], rtol: f64) -> f64 {
    let mut s = 0.0;
    let mut count = 0usize;
    for i in 0..err.len() {
        let sc = atol[i] + rtol * a[i].abs().max(b[i].abs());
        if sc.is_finite() {
            s += (err[i] / sc).powi(2);
            count += 1;
        }
    }
    (s / count.max(1) as f64).sqrt()
}

/// RMS norm of `v / scale` over the error-controlled components: those of finite scale. A
/// component whose absolute tolerance is infinite ([`OdeSystem::atol_scale`]) is carried along
/// by the integrators but neither weighs in their error estimates and Newton tests nor counts in
/// the mean, so appending it (a quadrature of the energy balance) leaves the steps unchanged.
pub(crate) fn scaled_rms(v: &[f64], scale: &[f64]) -> f64 {
    let mut s = 0.0;
    let mut count = 0usize;
    for (a, sc) in v.iter().zip(scale) {
        if sc.is_finite() {
            s += (a / sc) * (a / sc);
            count += 1;
        }
    }
    (s / count.max(1) as f64).sqrt()
}

/// Tolerances shared by the adaptive integrators.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance. Default `1e-6`.
    pub rtol: f64,
    /// Absolute tolerance per component (one value is broadcast). Default `[1e-8]`.
    pub atol: Vec<f64>,
}

impl Default for Tolerances {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: vec![1e-8],
        }
    }
}

impl Tolerances {
    /// Absolute tolerances expanded to `dim` components.
    pub(crate) fn atol(&self, dim: usize) -> Vec<f64> {
        if self.atol.len() == dim {
            self.atol.clone()
        } else {
            vec![self.atol.first().copied().unwrap_or(1e-8); dim]
        }
    }

    /// Check that the tolerances are finite and positive (field prefix `field`).
    pub fn validate(&self, field: &str, dim: usize) -> Result<(), crate::InputError> {
        if !(self.rtol.is_finite() && self.rtol > 0.0) {
            return Err(crate::InputError::new(
                format!("{field}.rtol"),
                format!("must be a finite positive number, got {}", self.rtol),
            ));
        }
        if self.atol.len() != 1 && self.atol.len() != dim {
            return Err(crate::InputError::new(
                format!("{field}.atol"),
                format!("needs 1 or {dim} values, got {}", self.atol.len()),
            ));
        }
        // +∞: a component left out of the error control (quadrature states).
        for &a in &self.atol {
            if !(a > 0.0) {
                return Err(crate::InputError::new(
                    format!("{field}.atol"),
                    format!("must be a positive number, got {a}"),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y' = −ω² x`, `x' = y`: an undamped oscillator (shared by the integrators' tests).
    pub(super) struct Oscillator(pub(super) f64);

    impl OdeSystem for Oscillator {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -self.0 * self.0 * y[0];
        }
        fn jacobian(&mut self, _t: f64, _y: &[f64], jac: &mut DMatrix<f64>) {
            jac.fill(0.0);
            jac[(0, 1)] = 1.0;
            jac[(1, 0)] = -self.0 * self.0;
        }
    }

    /// `y' = −2 t y²`, `y(0) = 1`: `y = 1/(1 + t²)`. Non-linear and non-autonomous (shared by
    /// the integrators' tests).
    pub(super) struct Riccati;

    impl OdeSystem for Riccati {
        fn dim(&self) -> usize {
            1
        }
        fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = -2.0 * t * y[0] * y[0];
        }
        fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
            jac[(0, 0)] = -4.0 * t * y[0];
        }
    }

    #[test]
    fn fixed_midpoint_steps_reach_the_end_of_windows_cut_by_rounding() {
        // [0.25, 0.255] is 20 steps of 2.5e-4 in exact arithmetic; summing them in floating point
        // stops 5e-16 s short, which once ended the run with "step size too small".
        let mut y = vec![1.0, 0.0];
        for k in 0..200 {
            let t = [0.005 * k as f64, 0.005 * (k + 1) as f64];
            let (traj, stats) = ImplicitMidpoint {
                options: MidpointOptions {
                    step: Some(2.5e-4),
                    ..Default::default()
                },
            }
            .integrate(&mut Oscillator(10.0), t[0], &y, &t, &mut |_| {})
            .unwrap_or_else(|e| panic!("window {k}: {e}"));
            assert_eq!(stats.steps, 20, "window {k}");
            y.clone_from(traj.y.last().unwrap());
        }
    }

    #[test]
    fn every_integrator_is_accurate_on_an_oscillator_and_respects_its_step_budget() {
        let w = 10.0;
        let exact = (w * 1.0f64).cos();
        let tol = Tolerances {
            rtol: 1e-8,
            atol: vec![1e-10],
        };
        let t = [0.5, 1.0];
        let runs: Vec<IntegrationResult> = vec![
            Dopri5 {
                options: Dopri5Options {
                    tolerances: tol.clone(),
                    ..Default::default()
                },
            }
            .integrate(&mut Oscillator(w), 0.0, &[1.0, 0.0], &t, &mut |_| {}),
            Bdf {
                options: BdfOptions {
                    tolerances: tol.clone(),
                    max_order: 5,
                    ..Default::default()
                },
            }
            .integrate(&mut Oscillator(w), 0.0, &[1.0, 0.0], &t, &mut |_| {}),
            ImplicitMidpoint {
                options: MidpointOptions {
                    tolerances: tol.clone(),
                    ..Default::default()
                },
            }
            .integrate(&mut Oscillator(w), 0.0, &[1.0, 0.0], &t, &mut |_| {}),
        ];
        for (k, r) in runs.into_iter().enumerate() {
            let (traj, _) = r.expect("integrates");
            // Local tolerance 1e-8 over 1.6 periods: global error below 1e-5 for all three.
            assert!(
                (traj.y[1][0] - exact).abs() < 1e-5,
                "integrator {k}: {}",
                traj.y[1][0]
            );
        }
        let limited = Dopri5 {
            options: Dopri5Options {
                tolerances: tol,
                max_steps: 10,
                ..Default::default()
            },
        }
        .integrate(&mut Oscillator(w), 0.0, &[1.0, 0.0], &t, &mut |_| {});
        let failure = limited.expect_err("budget of 10 steps");
        assert!(matches!(
            failure.error,
            SolveError::TooManySteps { steps: 10, .. }
        ));
    }
}
