//! The energy audit of a dynamic run (docs/model-choices.md, "Energy audit"): the balance
//!
//! ```text
//! H(t) − H(0) − W(t) + D(t) = 0,    W = ∫ ẋ·Q(x, t) dt,    D = ∫ ẋᵀ C ẋ dt
//! ```
//!
//! of the Hamiltonian `H = T + V` of the model, the work `W` of the applied loads and the energy
//! `D` dissipated by the structural damping. It holds exactly for the equations of motion of the
//! full and reduced models with the exact gyroscopic term (model.md, "Equations of motion":
//! `dH/dt = ẋ·(Q − C ẋ)`), so what a run leaves of it is the integration error. The simplified
//! model (γ neglected) has no such balance: what it leaves is the energy its equations create,
//! reported the same way.
//!
//! `W` and `D` are appended to the state as quadrature states (`Ẇ = ẋ·Q`, `Ḋ = ẋᵀ C ẋ`), so
//! every integrator integrates them with its own formula and order, at no extra right-hand side;
//! their absolute tolerance is infinite, which keeps them out of the error control, so the steps
//! are those of the unaudited run. After each accepted step the balance is checked
//! ([`crate::solve::integrate::OdeSystem::step_accepted`]).
//!
//! The relative error is measured against the largest energy the run has held or been given,
//! `E = max(H(0), max_t |W(t)|, max_t D(t), E_floor)` over the whole run, with the floor `E_floor`
//! the energy of the absolute tolerance (an error of `atol` in every coordinate and momentum),
//! below which the integrator does not resolve energies: an error of 1e-8 J in the first steps of
//! a run that is later given 0.3 J is no error. The largest relative error of a run is
//! `max_t |H − H(0) − W + D| / E`; the time it went wrong is the first time that ratio exceeded
//! the limit. Both need the final `E`, so the audit keeps the record values of `|H − H(0) − W + D|`
//! (the steps at which it reached a new maximum: the first step beyond any threshold is one) and
//! [`EnergyBalance::finish`] reads them at the end. The runaway check cannot wait: it compares
//! the energy created with the running `E`, after every step.

use std::ops::ControlFlow;

/// When the audit of a run flags or stops it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuditLimits {
    /// Largest relative balance error `|H − H(0) − W + D| / E` before the run is flagged as
    /// suspect; `None` for a model without an energy balance (the simplified model).
    pub balance: Option<f64>,
    /// Relative energy gain `(H − H(0) − W + D) / E` (running `E`) at which the run is stopped
    /// as a runaway (energy created that no load supplied).
    pub runaway: f64,
    /// The energy floor `E_floor` (J) of the reference energy.
    pub floor: f64,
    /// Shortest time (s) between two audited steps: an accepted step closer than this to the
    /// last audited one is not audited, unless [`AUDIT_STRIDE`] steps went by unaudited (so a
    /// run that grinds to tiny steps is still audited); 0: every step. The library's analyses
    /// take the output interval: the audit's energies (a mass solve each) then cost at most one
    /// per output instead of one per step (docs/performance.md, "The energy audit's cost").
    pub interval: f64,
}

/// Most accepted steps in a row left unaudited by [`AuditLimits::interval`].
pub const AUDIT_STRIDE: usize = 16;

/// What the audit of a run found, over its accepted steps.
#[derive(Debug, Clone, PartialEq)]
pub struct EnergyBalance {
    /// The limits it was held to.
    pub limits: AuditLimits,
    /// `H(0)` (J).
    pub initial: f64,
    /// The reference energy `E` (J): the largest energy held or given so far.
    pub reference: f64,
    /// Largest relative error `|H − H(0) − W + D| / E` (after [`Self::finish`]; infinite for a
    /// non-finite energy).
    pub max_error: f64,
    /// Time of the largest error (s).
    pub max_error_time: f64,
    /// Largest relative gain `(H − H(0) − W + D) / E` against the running `E`: energy created
    /// (negative when the run only lost energy).
    pub max_gain: f64,
    /// The first time (s) the error exceeded `limits.balance`, if it did (after
    /// [`Self::finish`]).
    pub exceeded_at: Option<f64>,
    /// The time (s) the run was stopped because the gain exceeded `limits.runaway`, if it was.
    pub runaway_at: Option<f64>,
    /// Accepted steps audited.
    pub steps: usize,
    /// `(t, |H − H(0) − W + D|)` at each step where it reached a new maximum.
    records: Vec<(f64, f64)>,
    /// Time of the last audited step, and the accepted steps since (`AuditLimits::interval`).
    last: (f64, usize),
}

impl EnergyBalance {
    /// A new audit from the energy `initial` = `H(0)`.
    pub(crate) fn start(limits: AuditLimits, initial: f64) -> Self {
        Self {
            limits,
            initial,
            reference: initial.abs().max(limits.floor),
            max_error: 0.0,
            max_error_time: 0.0,
            max_gain: f64::NEG_INFINITY,
            exceeded_at: None,
            runaway_at: None,
            steps: 0,
            records: Vec::new(),
            last: (f64::NEG_INFINITY, 0),
        }
    }

    /// Whether the accepted step to time `t` is to be audited ([`AuditLimits::interval`]); if it
    /// is, the caller [`Self::check`]s it.
    pub(crate) fn due(&mut self, t: f64) -> bool {
        if self.limits.interval <= 0.0 {
            return true;
        }
        let (last, skipped) = &mut self.last;
        if t - *last >= self.limits.interval || *skipped + 1 >= AUDIT_STRIDE {
            *last = t;
            *skipped = 0;
            true
        } else {
            *skipped += 1;
            false
        }
    }

    /// The balance `H − H(0) − W + D` (J) of the energy `h`, work `w` and dissipation `d`.
    pub fn residual(&self, h: f64, w: f64, d: f64) -> f64 {
        h - self.initial - w + d
    }

    /// Whether the accepted step to time `t` was audited, or one later.
    pub(crate) fn audited_at(&self, t: f64) -> bool {
        self.last.0 >= t
    }

    /// Take the step to time `t` with energy `h`, work `w` and dissipation `d`; `Break` when the
    /// run ran away.
    pub(crate) fn check(&mut self, t: f64, h: f64, w: f64, d: f64) -> ControlFlow<()> {
        self.steps += 1;
        self.reference = self.reference.max(w.abs()).max(d.abs());
        let residual = self.residual(h, w, d);
        // A non-finite energy is the worst error there is.
        let size = if residual.is_finite() {
            residual.abs()
        } else {
            f64::INFINITY
        };
        if self.records.last().is_none_or(|&(_, r)| size > r) {
            self.records.push((t, size));
        }
        let gain = if residual.is_nan() {
            f64::INFINITY
        } else {
            residual / self.reference
        };
        self.max_gain = self.max_gain.max(gain);
        if !(gain <= self.limits.runaway) {
            self.runaway_at = Some(t);
            return ControlFlow::Break(());
        }
        ControlFlow::Continue(())
    }

    /// Settle the largest error and the first time the limit was exceeded, against the final
    /// reference energy.
    pub fn finish(&mut self) {
        let e = self.reference;
        if let Some(&(t, r)) = self.records.last() {
            self.max_error = r / e;
            self.max_error_time = t;
        }
        self.exceeded_at = self.limits.balance.and_then(|limit| {
            self.records
                .iter()
                .find(|&&(_, r)| r / e > limit)
                .map(|&(t, _)| t)
        });
    }

    /// The relative error `(H − H(0) − W + D) / E` of the energy `h`, work `w` and dissipation
    /// `d` against the run's reference energy (signed: positive is a gain).
    pub fn relative(&self, h: f64, w: f64, d: f64) -> f64 {
        self.residual(h, w, d) / self.reference
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> AuditLimits {
        AuditLimits {
            balance: Some(1e-3),
            runaway: 1.0,
            floor: 1e-12,
            interval: 0.0,
        }
    }

    #[test]
    fn errors_are_relative_to_the_largest_energy_held_or_given() {
        let mut b = EnergyBalance::start(limits(), 10.0);
        // Free vibration: H stays 10 J to 1e-4 J.
        assert!(b.check(0.1, 10.0001, 0.0, 0.0).is_continue());
        // 30 J of work done and 5 J dissipated: H = 35 J balances; 35.1 J is an error of 0.1 J.
        assert!(b.check(0.2, 35.1, 30.0, 5.0).is_continue());
        // W back to 0, H back to 5 J balances; the reference keeps the largest work seen.
        assert!(b.check(0.3, 5.0, 0.0, 5.0).is_continue());
        assert_eq!(b.reference, 30.0);
        b.finish();
        // Against E = 30 J: 1e-4 / 30 at 0.1 s is within 1e-3, 0.1 / 30 at 0.2 s is not.
        assert!((b.max_error - 0.1 / 30.0).abs() < 1e-12);
        assert_eq!(b.max_error_time, 0.2);
        assert_eq!(b.exceeded_at, Some(0.2));
        // Energy created beyond the runaway limit stops the run: (70 − 10 − 0 + 5) / 30.
        assert!(b.check(0.4, 70.0, 0.0, 5.0).is_break());
        assert_eq!(b.runaway_at, Some(0.4));
        assert!((b.max_gain - 65.0 / 30.0).abs() < 1e-12);
        // A non-finite energy stops it too, and is an infinite error.
        let mut c = EnergyBalance::start(limits(), 1.0);
        assert!(c.check(0.1, f64::NAN, 0.0, 0.0).is_break());
        c.finish();
        assert_eq!(c.max_error, f64::INFINITY);
        assert_eq!(c.exceeded_at, Some(0.1));
    }

    #[test]
    fn an_early_error_is_judged_against_the_energy_given_later() {
        // From rest: 1e-8 J off after the first step, when only 1e-6 J was given (1 % of it),
        // then 1 J given with the balance held to 1e-8 J: no error at the scale of the run.
        let mut b = EnergyBalance::start(limits(), 0.0);
        assert_eq!(b.reference, 1e-12);
        assert!(b.check(1e-4, 1e-6 + 1e-8, 1e-6, 0.0).is_continue());
        assert!(b.check(1e-1, 1.0 + 1e-8, 1.0, 0.0).is_continue());
        b.finish();
        assert!((b.max_error - 1e-8).abs() < 1e-15);
        assert_eq!(b.exceeded_at, None);
        // A model without a balance is never flagged, only stopped when it runs away.
        let mut s = EnergyBalance::start(
            AuditLimits {
                balance: None,
                ..limits()
            },
            1.0,
        );
        assert!(s.check(0.1, 1.5, 0.0, 0.0).is_continue());
        s.finish();
        assert_eq!(s.exceeded_at, None);
        assert!((s.max_error - 0.5).abs() < 1e-15);
    }
}
