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
use super::iteration::IterationMatrices;
use super::{
    check_output_times, failure, outputs_at_start, scaled_rms, IntegrationResult, IntegratorStats,
    OdeSystem, Tolerances, Trajectory,
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

/// The parameters of the method for a spectral radius `ρ∞` (Jansen, Whiting & Hulbert 2000,
/// eqs. 21–22: second order, both roots `−ρ∞` at `hλ → ∞`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Parameters {
    pub(crate) alpha_m: f64,
    pub(crate) alpha_f: f64,
    pub(crate) gamma: f64,
    /// `ẏ_n ≈ y'(t_n + δ h)`: `δ = α_f − α_m`.
    pub(crate) delta: f64,
    /// Local error `C h³ y'''` on `y' = λy`: the principal root is `e^z + C z³ + O(z⁴)`.
    pub(crate) error_constant: f64,
    /// `c h` of the Newton matrix `c I − J`: `α_m / (α_f γ)`.
    pub(crate) shift: f64,
}

impl Parameters {
    pub(crate) fn new(rho: f64) -> Self {
        let alpha_m = 0.5 * (3.0 - rho) / (1.0 + rho);
        let alpha_f = 1.0 / (1.0 + rho);
        let gamma = 0.5 + alpha_m - alpha_f;
        Self {
            alpha_m,
            alpha_f,
            gamma,
            delta: alpha_f - alpha_m,
            error_constant: (rho * rho - rho + 1.0) / (3.0 * (1.0 + rho) * (1.0 + rho)),
            shift: alpha_m / (alpha_f * gamma),
        }
    }
}

/// The method's state between steps: `(t_n, y_n, ẏ_n)` and the past that the step-change
/// correction, the predictor, the error estimate and the dense output need.
pub(crate) struct State {
    pub(crate) t: f64,
    pub(crate) y: Vec<f64>,
    pub(crate) ydot: Vec<f64>,
    /// The step `ẏ_n` is consistent with (`None`: `ẏ_0 = f(t_0, y_0)`, offset 0).
    h_ydot: Option<f64>,
    /// `ẏ_{n−1}` moved to the offset of the step from it (valid when `h_ydot` is).
    ydot_prev: Vec<f64>,
    /// `y_{n−2}, y_{n−1}` (most recent last) and their times; the last `past_count` are valid.
    past: [Vec<f64>; 2],
    past_t: [f64; 2],
    past_count: usize,
}

impl State {
    pub(crate) fn new(t0: f64, y0: &[f64], f0: &[f64]) -> Self {
        let n = y0.len();
        Self {
            t: t0,
            y: y0.to_vec(),
            ydot: f0.to_vec(),
            h_ydot: None,
            ydot_prev: vec![0.0; n],
            past: [vec![0.0; n], vec![0.0; n]],
            past_t: [f64::NAN; 2],
            past_count: 0,
        }
    }

    /// Back to `(t0, y0)` with `ẏ = f0` and no past (no allocation).
    fn reset(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
        self.t = t0;
        self.y.copy_from_slice(y0);
        self.ydot.copy_from_slice(f0);
        self.h_ydot = None;
        self.past_t = [f64::NAN; 2];
        self.past_count = 0;
    }

    /// Move to the end of an accepted step of size `h` (its values taken from `step`).
    pub(crate) fn accept(&mut self, step: &mut Stepper, t_new: f64, h: f64) {
        self.past.swap(0, 1);
        self.past_t.swap(0, 1);
        self.past[1].copy_from_slice(&self.y);
        self.past_t[1] = self.t;
        self.past_count = (self.past_count + 1).min(2);
        // ẏ_n as the step used it (at the offset δ h): ẏ_{n+1} − ẏ_n spans exactly h.
        self.ydot_prev.copy_from_slice(&step.ydot_h);
        std::mem::swap(&mut self.y, &mut step.y_new);
        self.ydot.copy_from_slice(&step.ydot_new);
        self.h_ydot = Some(h);
        self.t = t_new;
    }

    /// The state at `tt ∈ (t_{n−1}, t_new]` from the quadratic through `y_{n−1}, y_n` and the
    /// step's result `y_new` (linear between `y_n` and `y_new` if there is no past yet).
    fn interpolate(&self, t_new: f64, y_new: &[f64], tt: f64) -> Vec<f64> {
        let (y, t) = (&self.y, self.t);
        if tt == t_new {
            y_new.to_vec()
        } else if self.past_count == 0 {
            let w = (tt - t) / (t_new - t);
            (0..y.len()).map(|i| y[i] + w * (y_new[i] - y[i])).collect()
        } else {
            let (ta, ya) = (self.past_t[1], &self.past[1]);
            let la = (tt - t) * (tt - t_new) / ((ta - t) * (ta - t_new));
            let lb = (tt - ta) * (tt - t_new) / ((t - ta) * (t - t_new));
            let lc = (tt - ta) * (tt - t) / ((t_new - ta) * (t_new - t));
            (0..y.len())
                .map(|i| la * ya[i] + lb * y[i] + lc * y_new[i])
                .collect()
        }
    }
}

/// What the Newton iteration of one step ended with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Newton {
    /// Converged, with the last contraction rate (0 after one iteration).
    Converged { theta: f64 },
    /// Diverging, too slow or non-finite: retry with a smaller step or a fresh Jacobian.
    Failed { non_finite: bool },
}

/// One step of the method: the Newton iteration, its matrix and the error estimate, with the
/// scratch of a run (allocated once).
pub(crate) struct Stepper {
    pub(crate) p: Parameters,
    /// The Newton matrices `c I − J` (the system's structured solver, or the dense Jacobian
    /// and LU), real slot 0.
    mats: IterationMatrices,
    /// The shift `c` slot 0 is factored with (NaN: not factored).
    c: f64,
    /// `ẏ_n` adjusted to the current step.
    ydot_h: Vec<f64>,
    /// Increment `Δ = y_{n+1} − y_n`.
    delta: Vec<f64>,
    corr: Vec<f64>,
    y_af: Vec<f64>,
    f: Vec<f64>,
    /// The step's result.
    pub(crate) y_new: Vec<f64>,
    pub(crate) ydot_new: Vec<f64>,
    err: Vec<f64>,
    /// Error scale `atol + rtol |y|`.
    scal: Vec<f64>,
    /// Newton's convergence factor carried from step to step (`RADAU5`'s `FACCON`).
    faccon: f64,
}

impl Stepper {
    /// For `system` (its dimension, and its structured Newton solver if it has one).
    pub(crate) fn new<S: OdeSystem>(system: &mut S, rho: f64) -> Self {
        let n = system.dim();
        Self {
            p: Parameters::new(rho),
            mats: IterationMatrices::new(system),
            c: f64::NAN,
            ydot_h: vec![0.0; n],
            delta: vec![0.0; n],
            corr: vec![0.0; n],
            y_af: vec![0.0; n],
            f: vec![0.0; n],
            y_new: vec![0.0; n],
            ydot_new: vec![0.0; n],
            err: vec![0.0; n],
            scal: vec![0.0; n],
            faccon: 1.0,
        }
    }

    /// Linearize `system` at `(t, y)` (the Jacobian, or the structured solver's point); the
    /// factorization is then stale. False if the system cannot be linearized there.
    pub(crate) fn linearize<S: OdeSystem>(&mut self, system: &mut S, t: f64, y: &[f64]) -> bool {
        self.c = f64::NAN;
        self.mats.linearize(system, t, y)
    }

    /// Whether the system linearizes cheaply enough to do it at every step
    /// ([`super::NewtonSolver::cheap_linearization`]).
    pub(crate) fn cheap_linearization(&self) -> bool {
        self.mats.cheap_linearization()
    }

    /// Make sure `c I − J` is factored for the step `h` (after [`Self::linearize`]); false if
    /// it is singular.
    pub(crate) fn factor<S: OdeSystem>(
        &mut self,
        system: &mut S,
        h: f64,
        stats: &mut IntegratorStats,
    ) -> bool {
        let c = self.p.shift / h;
        // Kept for a step that differs by rounding only (the last one, cut to reach the end).
        if (self.c - c).abs() <= 1e-10 * c {
            return true;
        }
        stats.factorizations += 1;
        let ok = self.mats.factor_real(system, 0, c);
        self.c = if ok { c } else { f64::NAN };
        ok
    }

    /// Prepare a step of size `h` from `st`: the error scale of `y_n`, `ẏ_n` moved to the
    /// offset `δ h` of this step, and the predictor `Δ = h (y_n − y_{n−1}) / h_{n−1}` (the last
    /// step's mean rate; on a mode far beyond the step's resolution it gives `y_{n+1} = −ρ∞ y_n`,
    /// the method's own answer, so that Newton starts converged there), or `h ẏ_0` on the first.
    pub(crate) fn predict(&mut self, st: &State, h: f64, atol: &[f64], rtol: f64) {
        let n = st.y.len();
        let yddot_scale = st.h_ydot.map_or(0.0, |hp| self.p.delta * (h - hp) / hp);
        let rate_scale = if st.past_count > 0 {
            h / (st.t - st.past_t[1])
        } else {
            0.0
        };
        for i in 0..n {
            self.scal[i] = atol[i] + rtol * st.y[i].abs();
            self.ydot_h[i] = st.ydot[i] + yddot_scale * (st.ydot[i] - st.ydot_prev[i]);
            self.delta[i] = if st.past_count > 0 {
                rate_scale * (st.y[i] - st.past[1][i])
            } else {
                h * self.ydot_h[i]
            };
        }
    }

    /// The Newton iteration of a step of size `h` from `st` (after [`Self::predict`] and
    /// [`Self::factor`]); on convergence, `y_new` and `ydot_new` hold the step's result. `tol`
    /// is the stopping tolerance relative to the error scale.
    pub(crate) fn newton<S: OdeSystem>(
        &mut self,
        system: &mut S,
        st: &State,
        h: f64,
        tol: f64,
        max_iterations: usize,
        stats: &mut IntegratorStats,
    ) -> Newton {
        let n = st.y.len();
        let p = self.p;
        let inv_hg = 1.0 / (h * p.gamma);
        let t_af = st.t + p.alpha_f * h;
        self.faccon = self.faccon.max(f64::EPSILON).powf(0.8);
        let mut old_norm = 0.0;
        let mut theta = 0.0;
        for k in 0..max_iterations {
            for i in 0..n {
                self.y_af[i] = st.y[i] + p.alpha_f * self.delta[i];
            }
            system.rhs(t_af, &self.y_af, &mut self.f);
            stats.rhs_evaluations += 1;
            stats.newton_iterations += 1;
            // Residual ẏ_{n+α_m} − f with ẏ_{n+1} = ẏ_n + (Δ − h ẏ_n)/(γ h); its derivative in
            // Δ is α_f (c I − J).
            for i in 0..n {
                let ydot_new = self.ydot_h[i] + (self.delta[i] - h * self.ydot_h[i]) * inv_hg;
                let r = self.ydot_h[i] + p.alpha_m * (ydot_new - self.ydot_h[i]) - self.f[i];
                self.corr[i] = -r / p.alpha_f;
            }
            self.mats.solve_real(system, 0, &mut self.corr);
            let norm = scaled_rms(&self.corr, &self.scal);
            if !norm.is_finite() {
                return Newton::Failed { non_finite: true };
            }
            for i in 0..n {
                self.delta[i] += self.corr[i];
            }
            let mut converged =
                self.faccon * norm <= tol && k + 1 >= super::min_newton_iterations(&self.scal);
            if k > 0 {
                theta = norm / old_norm;
                if theta >= 0.99 {
                    return Newton::Failed { non_finite: false };
                }
                self.faccon = theta / (1.0 - theta);
                converged = self.faccon * norm <= tol;
                // Too slow to converge within the iterations left.
                let left = (max_iterations - 1 - k) as i32;
                if !converged && self.faccon * norm * theta.powi(left) > tol {
                    return Newton::Failed { non_finite: false };
                }
            }
            if converged {
                for i in 0..n {
                    self.y_new[i] = st.y[i] + self.delta[i];
                    self.ydot_new[i] =
                        self.ydot_h[i] + (self.delta[i] - h * self.ydot_h[i]) * inv_hg;
                }
                return Newton::Converged { theta };
            }
            old_norm = norm.max(f64::EPSILON);
        }
        Newton::Failed { non_finite: false }
    }

    /// The scaled RMS of the local error of the step to `(t_new, y_new)` (after a converged
    /// [`Self::newton`]): `C h³ y'''` with `y''' ≈ 6 y[t_{n−2}, t_{n−1}, t_n, t_{n+1}]`, filtered
    /// by `(I − J/c)⁻¹`. `None` without two past values. The scale is `atol + rtol max(|y_n|,
    /// |y_{n+1}|)`.
    pub(crate) fn error<S: OdeSystem>(
        &mut self,
        system: &mut S,
        st: &State,
        t_new: f64,
        h: f64,
        atol: &[f64],
        rtol: f64,
    ) -> Option<f64> {
        if st.past_count < 2 {
            return None;
        }
        let [ta, tb] = st.past_t;
        let (tc, td) = (st.t, t_new);
        // (I − J/c)⁻¹ = c (c I − J)⁻¹.
        let k = 6.0 * self.p.error_constant * h * h * h * self.c;
        let [ya, yb] = &st.past;
        for i in 0..st.y.len() {
            let (yc, yd) = (st.y[i], self.y_new[i]);
            let (dab, dbc, dcd) = (
                (yb[i] - ya[i]) / (tb - ta),
                (yc - yb[i]) / (tc - tb),
                (yd - yc) / (td - tc),
            );
            let (dabc, dbcd) = ((dbc - dab) / (tc - ta), (dcd - dbc) / (td - tb));
            self.err[i] = k * (dbcd - dabc) / (td - ta);
            self.scal[i] = atol[i] + rtol * yc.abs().max(yd.abs());
        }
        self.mats.solve_real(system, 0, &mut self.err);
        let e = scaled_rms(&self.err, &self.scal);
        Some(if e.is_finite() { e } else { 1e10 })
    }
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
        let atol = opts.tolerances.atol(n);
        let rtol = opts.tolerances.rtol;
        let adaptive = opts.step.is_none();
        let (keep_lower, keep_upper) = opts.unchanged_step_ratio;

        let mut f0 = vec![0.0; n];
        system.rhs(t0, y0, &mut f0);
        stats.rhs_evaluations += 1;
        if f0.iter().any(|v| !v.is_finite()) {
            return failure(traj, stats, SolveError::NonFinite { time: t0 });
        }
        // In adaptive mode at least three steps, so that the first estimate (at the third step)
        // checks the first two.
        let startup_max = if adaptive {
            (t_end - t0) / 3.0
        } else {
            f64::INFINITY
        };
        let hmax = opts.max_step.min(t_end - t0);
        let mut h = match (opts.step, opts.first_step) {
            (Some(h), _) | (None, Some(h)) => h,
            // Half the usual guess: the first two steps are only checked at the third.
            (None, None) => 0.5 * initial_step(system, t0, y0, &f0, &atol, rtol, 2, &mut stats),
        }
        .min(hmax)
        .min(startup_max);

        let mut st = State::new(t0, y0, &f0);
        let mut step = Stepper::new(system, opts.spectral_radius);
        // The option alone, not tightened to the system's bound (`NewtonSolver::newton_tolerance`,
        // which Radau needs for the full model's joint momenta): with generalized-α's predictor
        // the bound only doubles the iterations. Measured on case (b) with fixed 0.5 ms steps
        // (docs/performance.md): the same tip error (2.01e-4 m at n = 3000 and 10 000) with 1.15
        // instead of 2.0 iterations per step.
        let newton_tolerance = opts.newton_tolerance;
        // A structured solver that linearizes cheaply does it at every step (fewer iterations).
        let relinearize = step.cheap_linearization();
        let mut need_jac = true;
        let mut jac_current = false;
        let mut last_failure_non_finite = false;
        let mut after_rejection = false;

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
                let e = if last_failure_non_finite {
                    SolveError::NonFinite { time: t }
                } else if adaptive {
                    SolveError::StepSizeTooSmall { time: t, step: h }
                } else {
                    SolveError::NewtonFailed { time: t, step: h }
                };
                return failure(traj, stats, e);
            }
            let mut jac_ok = true;
            if need_jac {
                jac_ok = step.linearize(system, t, &st.y);
                stats.jacobian_evaluations += 1;
                jac_current = true;
                need_jac = false;
            }
            step.predict(&st, h, &atol, rtol);
            let outcome = if jac_ok && step.factor(system, h, &mut stats) {
                step.newton(
                    system,
                    &st,
                    h,
                    newton_tolerance,
                    opts.max_newton_iterations,
                    &mut stats,
                )
            } else {
                Newton::Failed { non_finite: false }
            };
            let theta = match outcome {
                Newton::Converged { theta } => theta,
                Newton::Failed { non_finite } => {
                    // A stale Jacobian first, then a smaller step.
                    last_failure_non_finite = non_finite;
                    stats.rejected_steps += 1;
                    stats.newton_failures += 1;
                    after_rejection = true;
                    if jac_current {
                        h *= 0.5;
                    } else {
                        need_jac = true;
                    }
                    continue;
                }
            };
            last_failure_non_finite = false;
            let t_new = if last { t_end } else { t + h };

            let mut factor = None;
            if adaptive {
                if let Some(e) = step.error(system, &st, t_new, h, &atol, rtol) {
                    let f = (SAFETY * e.max(1e-10).powf(-1.0 / 3.0)).clamp(FAC_MIN, FAC_MAX);
                    if e > 1.0 {
                        stats.rejected_steps += 1;
                        after_rejection = true;
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
                            need_jac = true;
                        }
                        continue;
                    }
                    factor = Some(if after_rejection { f.min(1.0) } else { f });
                }
            }

            // Accepted. Outputs up to t_new, except on the first step, whose outputs wait for
            // the quadratic through three values (they are emitted at the second).
            stats.steps += 1;
            after_rejection = false;
            let emit_until = if st.past_count > 0 || last { t_new } else { t };
            while next_out < t_out.len() && t_out[next_out] <= emit_until {
                let tt = t_out[next_out];
                traj.t.push(tt);
                traj.y.push(st.interpolate(t_new, &step.y_new, tt));
                next_out += 1;
            }
            st.accept(&mut step, t_new, h);
            jac_current = false;
            progress(st.t);
            if system.step_accepted(st.t, &st.y).is_break() {
                return failure(traj, stats, SolveError::Halted { time: st.t });
            }
            if last || next_out == t_out.len() {
                return Ok((traj, stats));
            }
            need_jac = relinearize || theta > opts.jacobian_reuse;
            h = match (opts.step, factor) {
                (Some(hf), _) => hf,
                // Keep the step, and the factorization, for moderate changes.
                (None, Some(f)) if (keep_lower..=keep_upper).contains(&f) && !need_jac => h,
                (None, Some(f)) => h * f,
                // The first two steps keep the first step.
                (None, None) => h,
            }
            .min(hmax);
            if st.past_count < 2 {
                h = h.min(startup_max);
            }
        }
    }
}

#[cfg(test)]
mod tests;
