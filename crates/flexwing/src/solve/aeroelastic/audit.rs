//! The energy audit of an aeroelastic time response (docs/model-choices.md, "Energy audit";
//! docs/aeroelastic-model.md §5, "Energy balance of a time response"): the balance of the
//! structural audit (`solve::energy_audit`),
//!
//! ```text
//! H(t) − H(0) − W(t) + D(t) = 0,   W = ∫ ẋ·(Q_other + Q_grav + Q_aero) dt,   D = ∫ ẋᵀ C ẋ dt,
//! ```
//!
//! with `H = ½ pᵀ M⁻¹ p + ½ xᵀ K x` of the **wet** structure: the fluid's apparent mass is in `M`
//! (aeroelastic-model.md §3), so `p` and `γ` carry it and the equations `ẋ = M⁻¹ p`,
//! `ṗ = −K x + γ − C ẋ + Q` with `γ = −∂T/∂x|_p` give `dH/dt = ẋ·Q − ẋᵀ C ẋ` exactly. Every other
//! aerodynamic term is a generalized force in `Q_aero(x, ẋ, a, t)`: the circulatory loads (with
//! the lag states `a`, whose own rates carry no energy of `H`), the non-circulatory velocity
//! term `π ρ b² V ψ̇`, the gust and the time-varying `U(t)` and root angle (through the strip
//! speeds `V_i(t)` and the free-stream direction). The apparent mass `π ρ b²`, `π ρ b⁴/8` depends
//! on the density and the semi-chord only, not on `U` or `t`, so `∂H/∂t = 0`; gravity's factor
//! `cos α_r(t)` is a time-varying generalized force, in `W`. So the balance holds for the
//! equations as written, for every aerodynamic model, and what a run leaves of it is the
//! integration error.
//!
//! `W` and `D` are quadrature states appended after the lag states, `y = (x, p, a, W, D)`, left out
//! of the error control (infinite absolute tolerance) as in the structural audit: every
//! integrator integrates them with its own formula and order, from the rates of the right-hand
//! side it evaluates anyway. `Ẇ` is the structural equations' load power (they return it with
//! their rates) plus `ẋ·(Q_grav + Q_aero)`, taken as the change of `ẋ·ṗ` over the gravity and
//! strip loads (no extra force evaluation); `Ḋ` is the structural damping's `ẋᵀ C ẋ`. The
//! integrators solve the other states' Newton systems (the lag-state elimination of `schur.rs`,
//! or the dense LU) and take `W`'s and `D`'s part from [`AeroelasticEquations`]'
//! `quadrature_step_*`: their rows of the Jacobian, the gradients of their rates, applied to the
//! solved step from the Jacobian's blocks, so that one Newton iteration converges them with the
//! other stages (`equations.rs`); Radau IIA moves each stage's own rates by its correction
//! instead (`quadrature_gradient`, `integrate/radau_step.rs`).

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

use super::equations::AeroelasticEquations;
use crate::model::aero::AeroStructure;
use crate::solve::{AuditLimits, EnergyBalance};

/// The energy audit inside [`AeroelasticEquations`].
pub(super) struct AeroAudit {
    /// The balance so far.
    balance: EnergyBalance,
    /// The structural equations' rates `(ẋ, ṗ)` followed by their load power `ẋ·Q_other` and
    /// damping power `ẋᵀ C ẋ` (`2n + 2`).
    pub(super) structural: Vec<f64>,
    /// The forces on the structure other than its own `−K x + γ − C ẋ` (`Q_other + Q_grav +
    /// Q_aero`) at the last right-hand side (`n`), for the quadrature step.
    pub(super) force: Vec<f64>,
    /// The power terms kept for the quadratures' gradient (`equations.rs`, `keep_power_point`):
    /// Radau's three stages and the point of a quadrature step.
    pub(super) points: [Vec<f64>; 4],
}

impl AeroAudit {
    fn new(limits: AuditLimits, n: usize) -> Self {
        Self {
            balance: EnergyBalance::start(limits, 0.0),
            structural: vec![0.0; 2 * n + 2],
            force: vec![0.0; n],
            points: Default::default(),
        }
    }

    /// Write `Ẇ`, `Ḋ` into `quadrature` given the power `ẋ·(Q_grav + Q_aero)`.
    pub(super) fn quadrature_rates(&self, aero_power: f64, quadrature: &mut [f64]) {
        let n2 = self.structural.len() - 2;
        if let [w, d] = quadrature {
            *w = self.structural[n2] + aero_power;
            *d = self.structural[n2 + 1];
        }
    }
}

/// `a · b`.
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}

impl<M: AeroStructure> AeroelasticEquations<'_, M> {
    /// The same equations with the energy audit on (module documentation): the state gets two
    /// more components after the lag states, the work of the loads (applied, gravity and
    /// aerodynamic) `W` and the energy dissipated by the structural damping `D`, and the balance
    /// `H − H(0) − W + D` is checked after every accepted step; a run whose energy gain exceeds
    /// `limits.runaway` is stopped ([`crate::SolveError::Halted`]). The audit runs from the state
    /// last built by [`Self::state`]; [`Self::energy_balance`] says what it found.
    pub fn with_energy_audit(mut self, limits: AuditLimits) -> Self {
        self.set_energy_audit(Some(limits));
        self
    }

    /// Switch the energy audit on with `limits`, or off ([`Self::with_energy_audit`]); the
    /// state's size changes with it.
    pub fn set_energy_audit(&mut self, limits: Option<AuditLimits>) {
        let n = self.n;
        self.audit = limits.map(|l| AeroAudit::new(l, n));
    }

    /// The same equations, stopped after the next accepted step once `flag` is set.
    pub fn set_halt(&mut self, flag: Option<Arc<AtomicBool>>) {
        self.halt = flag;
    }

    /// What the energy audit found since the last [`Self::state`]; `None` without the audit.
    pub fn energy_balance(&self) -> Option<&EnergyBalance> {
        self.audit.as_ref().map(|a| &a.balance)
    }

    /// Put back a balance taken by [`Self::energy_balance`] (a stepper undoing a failed
    /// interval); nothing without the audit.
    pub(crate) fn restore_energy_balance(&mut self, balance: EnergyBalance) {
        if let Some(audit) = self.audit.as_mut() {
            audit.balance = balance;
        }
    }

    /// The work of the loads `W` and the dissipated energy `D` (J) carried by an audited state
    /// `y`; `None` without the audit.
    pub fn work_and_dissipation(&self, y: &[f64]) -> Option<(f64, f64)> {
        let m = 2 * self.n + self.na;
        self.audit.as_ref().map(|_| (y[m], y[m + 1]))
    }

    /// The energy an error of `atol` (rad) in every coordinate and the matching momentum error
    /// carries (J), that of the wet structure
    /// ([`crate::solve::EquationsOfMotion::energy_resolution`]): the audit's energy floor.
    pub fn energy_resolution(&mut self, atol: f64) -> f64 {
        self.structural.energy_resolution(atol)
    }

    /// Restart the audit from the state `y = (x, p, a)` and append `W = D = 0` to it.
    pub(super) fn restart_audit(&mut self, y: &mut Vec<f64>) {
        let Some(limits) = self.audit.as_ref().map(|a| a.balance.limits) else {
            return;
        };
        let (kinetic, strain) = self.energies(y);
        if let Some(audit) = self.audit.as_mut() {
            audit.balance = EnergyBalance::start(limits, kinetic + strain);
        }
        y.extend([0.0, 0.0]);
    }

    /// After an accepted step to `(t, y)`: the halt flag, then the balance check.
    pub(super) fn audit_step(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        if self
            .halt
            .as_ref()
            .is_some_and(|h| h.load(Ordering::Relaxed))
        {
            return ControlFlow::Break(());
        }
        if !self.audit.as_mut().is_some_and(|a| a.balance.due(t)) {
            return ControlFlow::Continue(());
        }
        self.audit_state(t, y)
    }

    /// Audit the state `y` of the last accepted step, at `t`, if `AuditLimits::interval` left it
    /// unaudited: a completed run's balance then includes its final state.
    pub(crate) fn audit_final(&mut self, t: f64, y: &[f64]) {
        if self
            .audit
            .as_ref()
            .is_some_and(|a| !a.balance.audited_at(t))
        {
            let _ = self.audit_state(t, y);
        }
    }

    fn audit_state(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        let Some((w, d)) = self.work_and_dissipation(y) else {
            return ControlFlow::Continue(());
        };
        let (kinetic, strain) = self.energies(y);
        match self.audit.as_mut() {
            Some(audit) => audit.balance.check(t, kinetic + strain, w, d),
            None => ControlFlow::Continue(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::equations::tests::test_wing;
    use super::super::flight::{FlightHistory, Gust, GustPenetration, GustShape};
    use super::super::schur::AeroNewtonSystems;
    use super::*;
    use crate::beam::Profile;
    use crate::model::aero::{Aerodynamics, FlightCondition};
    use crate::model::{Force, Load};
    use crate::solve::integrate::{OdeSystem, Radau, RadauOptions, Tolerances};
    use crate::solve::{Damping, TimeFunction};

    /// The audit through Radau's Newton systems solved by eliminating the lag states
    /// (`schur.rs`, the library response's path) and by dense LU: a small tapered wing with
    /// Wagner's and Peters' lag states, a follower tip force, gravity, Rayleigh damping, a gust
    /// and ramps of speed and root angle, from a deformed moving state. The balance (H of the
    /// wet structure against the integrated W and D, an energy-balance check) closes to the
    /// integration error on both paths (rtol 1e-8: measured 5.2e-9 (Wagner) and 4.9e-9
    /// (Peters) of the energy; bound 1e-7), the two paths take the same steps and agree on W and
    /// D to round-off (measured 1e-14 relative; bound 1e-10), and the audit barely changes the
    /// steps of the unaudited run.
    #[test]
    fn the_balance_closes_with_the_lag_elimination_and_dense_newton() {
        for am in [Aerodynamics::Wagner, Aerodynamics::Peters { states: 3 }] {
            let aero = test_wing(6, am);
            let loads = aero
                .full()
                .apply(
                    &[Load::PointForce {
                        span: 3.0,
                        force: Force::Follower {
                            tangential: 0.0,
                            normal: 3.0,
                        },
                    }],
                    "loads",
                )
                .unwrap();
            let flight = FlightHistory {
                deflection_changes: Vec::new(),
                initial: FlightCondition {
                    speed: 10.0,
                    root_angle: 0.03,
                    gravity: Some(9.81),
                },
                speed_change: Some((
                    2.0,
                    TimeFunction::Ramp {
                        start: 0.1,
                        end: 0.4,
                    },
                )),
                root_angle_change: Some((
                    0.02,
                    TimeFunction::Ramp {
                        start: 0.0,
                        end: 0.3,
                    },
                )),
                gust: Some(Gust {
                    shape: GustShape::OneMinusCosine { length: 3.0 },
                    amplitude: 1.0,
                    start: 0.05,
                    spanwise: Profile::Uniform(1.0),
                    penetration: GustPenetration::Uniform,
                }),
            };
            let damping = Damping::Rayleigh {
                alpha: 0.2,
                beta: 1e-3,
            };
            let mut results = Vec::new();
            for (newton, audit) in [
                (AeroNewtonSystems::LagSchur, true),
                (AeroNewtonSystems::Dense, true),
                (AeroNewtonSystems::LagSchur, false),
            ] {
                let mut eqs = AeroelasticEquations::new(
                    &aero,
                    &loads,
                    vec![TimeFunction::Sine {
                        omega: 5.0,
                        phase: 0.0,
                    }],
                    flight.clone(),
                    &damping,
                    "flight",
                )
                .unwrap();
                eqs.set_newton_systems(newton);
                let limits = AuditLimits {
                    balance: Some(1e-4),
                    runaway: 9.0,
                    floor: eqs.energy_resolution(1e-10),
                    interval: 0.0,
                };
                eqs.set_energy_audit(audit.then_some(limits));
                let n = eqs.n_dofs();
                let x: Vec<f64> = (0..n).map(|i| 0.05 * (1.0 + i as f64).sin()).collect();
                let xd: Vec<f64> = (0..n).map(|i| 0.3 * (2.0 * i as f64).cos()).collect();
                let a = eqs.steady_states(0.0, &x);
                let y0 = eqs.state(&x, &xd, &a);
                assert_eq!(y0.len(), eqs.dim());
                // 1e-10 as Radau applied it before issue 24 (`RADAU5` scaled it by
                // 0.1 rtol^(−1/3) = 46.4): the figures below were measured with it.
                let atol = eqs.state_atol(1e-10 * 0.1 * 1e-8f64.powf(-1.0 / 3.0));
                let (traj, stats) = Radau {
                    options: RadauOptions {
                        tolerances: Tolerances { rtol: 1e-8, atol },
                        ..Default::default()
                    },
                }
                .integrate(&mut eqs, 0.0, &y0, &[0.25, 0.5, 1.0], &mut |_| {})
                .unwrap();
                let y = traj.y.last().unwrap().clone();
                let balance = eqs.energy_balance().cloned();
                let wd = eqs.work_and_dissipation(&y);
                results.push((stats, balance, wd));
            }
            let (ws, wd) = (results[0].2.unwrap(), results[1].2.unwrap());
            for r in &results[..2] {
                let mut b = r.1.clone().unwrap();
                b.finish();
                assert!(b.max_error < 1e-7, "{am:?}: {b:?}");
                assert!(b.steps > 10 && b.exceeded_at.is_none() && b.runaway_at.is_none());
            }
            let e = results[0].1.as_ref().unwrap().reference;
            assert!(ws.1 > 0.0 && ws.0.abs() > 1e-3 * e, "{ws:?}");
            assert!((ws.0 - wd.0).abs() < 1e-10 * e && (ws.1 - wd.1).abs() < 1e-10 * e);
            // The audit barely changes the run: its quadrature states are out of the error
            // control and are stepped with the converged stages (`quadrature_step_*`). Measured
            // before that, with a second Newton iteration per step: (Wagner) 581 against 579 steps, 4107 against
            // 4053 right-hand sides; bound 5 %.
            let (on, off) = (&results[0].0, &results[2].0);
            assert!(
                on.steps as f64 <= 1.05 * off.steps as f64,
                "{am:?} {on:?} {off:?}"
            );
            assert!(on.rhs_evaluations as f64 <= 1.05 * off.rhs_evaluations as f64);
            assert!(results[2].1.is_none() && results[2].2.is_none());
        }
    }

    /// The quadrature states' part of a Newton step from the integrators' iteration matrices
    /// (`AeroelasticEquations::quadrature_step_*`) against the exact bordered step
    /// `(b_q + g·Δy) / c` with the same leading solution `Δy`, `g` the gradients of the rates
    /// `Ẇ`, `Ḋ` by central differences of the right-hand side (step 1e-6; tolerance 1e-6 of
    /// `Σ |g_j Δy_j| / |c|`), at a real and a complex shift, with the last right-hand side and the
    /// linearization at the state: on the tapered wing (a lag rate per strip) with an applied
    /// follower load, gravity, a gust at t = 0.3 s, Rayleigh damping and lag states, for the
    /// dense and the lag-eliminating Newton systems, full and reduced models, Wagner and Peters.
    #[test]
    fn quadrature_steps_are_the_bordered_newton_steps() {
        use crate::solve::integrate::assert_quadrature_rows;
        for am in [Aerodynamics::Wagner, Aerodynamics::Peters { states: 3 }] {
            let full = test_wing(5, am);
            let rom = full.reduced(&[0, 1, 2, 3]).unwrap();
            for systems in [AeroNewtonSystems::Dense, AeroNewtonSystems::LagSchur] {
                check_step(&full, systems);
                check_step(&rom, systems);
            }
        }

        fn check_step<M: crate::model::aero::PlanarStructure>(
            aero: &crate::model::aero::Aeroelastic<M>,
            systems: AeroNewtonSystems,
        ) {
            let loads = aero
                .full()
                .apply(
                    &[Load::PointForce {
                        span: 3.0,
                        force: Force::Follower {
                            tangential: 0.3,
                            normal: 4.0,
                        },
                    }],
                    "loads",
                )
                .unwrap();
            let flight = FlightHistory {
                deflection_changes: Vec::new(),
                initial: FlightCondition {
                    speed: 12.0,
                    root_angle: 0.05,
                    gravity: Some(9.81),
                },
                speed_change: None,
                root_angle_change: None,
                gust: Some(Gust {
                    shape: GustShape::OneMinusCosine { length: 10.0 },
                    amplitude: 1.5,
                    start: 0.0,
                    spanwise: Profile::Uniform(1.0),
                    penetration: GustPenetration::Uniform,
                }),
            };
            let damping = Damping::Rayleigh {
                alpha: 0.1,
                beta: 1e-3,
            };
            let mut eqs = AeroelasticEquations::new(
                aero,
                &loads,
                vec![TimeFunction::Constant],
                flight,
                &damping,
                "flight",
            )
            .unwrap();
            eqs.set_newton_systems(systems);
            eqs.set_energy_audit(Some(AuditLimits {
                balance: Some(1e-3),
                runaway: 9.0,
                floor: 1e-12,
                interval: 0.0,
            }));
            let (n, na) = (eqs.n_dofs(), eqs.n_aero_states());
            let x: Vec<f64> = (0..n).map(|i| 0.1 * (1.0 + i as f64).sin()).collect();
            let xd: Vec<f64> = (0..n).map(|i| 0.5 * (2.0 * i as f64).cos()).collect();
            let a: Vec<f64> = (0..na).map(|i| 0.3 * (0.7 * i as f64).cos()).collect();
            let y = eqs.state(&x, &xd, &a);
            let label = format!("{systems:?}");
            assert_quadrature_rows(&mut eqs, 0.3, &y, 2 * n + na, &label);
        }
    }
}
