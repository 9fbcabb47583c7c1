//! The Newton iteration of one implicit midpoint step (`midpoint.rs`), with Jacobian reuse: the
//! part of a step the driver calls once per step (fixed step, or its sub-steps after a Newton
//! failure) or three times (step doubling).

use super::{scaled_rms, IntegratorStats, IterationMatrices, OdeSystem};

/// Newton state of one implicit midpoint stage, with Jacobian reuse: `I − (h/2) J` is factored
/// as `(2/h) I − J` in real slot 0 of the iteration matrices, for the step `h` in `lu_h`.
pub(super) struct Stage {
    pub(super) mats: IterationMatrices,
    pub(super) lu_h: Option<f64>,
    pub(super) jac_fresh: bool,
    pub(super) f: Vec<f64>,
    pub(super) z: Vec<f64>,
    pub(super) dz: Vec<f64>,
}

impl Stage {
    /// For `system` (its dimension and its Newton solver), not yet linearized.
    pub(super) fn new<S: OdeSystem>(system: &mut S) -> Self {
        let dim = system.dim();
        Self {
            mats: IterationMatrices::new(system),
            lu_h: None,
            jac_fresh: true,
            f: vec![0.0; dim],
            z: vec![0.0; dim],
            dz: vec![0.0; dim],
        }
    }

    /// One step of size `h` from `(t, y0)` into `y1`; false if Newton fails.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn step<S: OdeSystem>(
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
            for _ in 0..10 {
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
                if norm <= tol {
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
