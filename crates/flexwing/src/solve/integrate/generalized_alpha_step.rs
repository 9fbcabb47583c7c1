//! The parts of one generalized-α step (`generalized_alpha.rs`): the method's parameters, the
//! state carried from step to step (with the past values the step-change correction, the
//! predictor, the error estimate and the dense output need), and the [`Stepper`]: the Newton
//! matrix, the predictor, the Newton iteration and the filtered local error estimate. The driver
//! loop in `generalized_alpha.rs` decides from their results.

use super::iteration::IterationMatrices;
use super::{scaled_rms, IntegratorStats, OdeSystem};

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
    pub(super) h_ydot: Option<f64>,
    /// `ẏ_{n−1}` moved to the offset of the step from it (valid when `h_ydot` is).
    ydot_prev: Vec<f64>,
    /// `y_{n−2}, y_{n−1}` (most recent last) and their times; the last `past_count` are valid.
    past: [Vec<f64>; 2],
    pub(super) past_t: [f64; 2],
    pub(super) past_count: usize,
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
    pub(crate) fn reset(&mut self, t0: f64, y0: &[f64], f0: &[f64]) {
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
    pub(crate) fn interpolate(&self, t_new: f64, y_new: &[f64], tt: f64) -> Vec<f64> {
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
            let mut converged = self.faccon * norm <= tol;
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
