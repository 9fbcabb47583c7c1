//! The integrators of the study: each is the library's one choice of method and its settings
//! ([`flexwing::solve::integrate`]), named for the tables; runs go through the library's audited
//! integration ([`integrate_audited`]), the one used by every dynamic analysis, which keeps the
//! energy balance of the run and stops a run whose energy explodes (the simplified model released
//! from a large deflection) instead of letting the integrator grind to a tiny step.

use flexwing::analysis::dynamics::{integrate_audited, AuditSettings, AuditedRun};
use flexwing::model::StructuralModel;
use flexwing::solve::integrate::{IntegratorSettings, Method};
use flexwing::solve::EquationsOfMotion;

/// An integrator and its accuracy setting. Tolerances: `rtol`, and an absolute tolerance on the
/// coordinates (rad) with consistent momenta of `rtol/100` for Dormand–Prince and `rtol` for
/// Radau (whose tolerances are rescaled internally as in `RADAU5`); the midpoint rule's fixed
/// step uses the library's defaults.
#[derive(Debug, Clone, PartialEq)]
pub struct Integrator {
    /// The method.
    pub method: Method,
    /// Its settings.
    pub settings: IntegratorSettings,
}

impl Integrator {
    /// Dormand–Prince 5(4) at relative tolerance `rtol`.
    pub fn dopri5(rtol: f64) -> Self {
        Self {
            method: Method::Dopri5,
            settings: IntegratorSettings {
                rtol,
                atol: rtol * 1e-2,
                ..Default::default()
            },
        }
    }

    /// The implicit midpoint rule with the fixed step `h` (s).
    pub fn midpoint(h: f64) -> Self {
        Self {
            method: Method::Midpoint,
            settings: IntegratorSettings {
                step: Some(h),
                ..Default::default()
            },
        }
    }

    /// Radau IIA of order 5 at relative tolerance `rtol`, steps at most `max_step` (s).
    pub fn radau(rtol: f64, max_step: Option<f64>) -> Self {
        Self {
            method: Method::Radau,
            settings: IntegratorSettings {
                rtol,
                atol: rtol,
                max_step,
                ..Default::default()
            },
        }
    }

    /// Description for the report.
    pub fn describe(&self) -> String {
        let s = &self.settings;
        match (self.method, s.step, s.max_step) {
            (Method::Dopri5, ..) => format!("Dormand–Prince 5(4), rtol {:.0e}", s.rtol),
            (Method::Midpoint, Some(h), _) => format!("implicit midpoint, h = {h:.1e} s"),
            (Method::Radau, _, Some(h)) => {
                format!("Radau IIA order 5, rtol {:.0e}, steps ≤ {h} s", s.rtol)
            }
            (Method::Radau, _, None) => format!("Radau IIA order 5, rtol {:.0e}", s.rtol),
            (method, ..) => format!("{}, rtol {:.0e}", method.name(), s.rtol),
        }
    }

    /// Short name for tables.
    pub fn short(&self) -> String {
        let s = &self.settings;
        match (self.method, s.step) {
            (Method::Dopri5, _) => format!("DOPRI5 {:.0e}", s.rtol),
            (Method::Midpoint, Some(h)) => format!("midpoint h {h:.1e}"),
            (Method::Radau, _) => format!("Radau {:.0e}", s.rtol),
            (method, _) => format!("{} {:.0e}", method.name(), s.rtol),
        }
    }
}

/// Integrator of the full model in case (b): its tip error against a tight run is reported.
/// Measured on this case: with steps capped at 1.2 output intervals, Radau's error control never
/// binds at rtol 1e-2, the Jacobian and the factorizations are reused across steps, and the tip
/// error (dominated by the third-order dense output between steps) is about 5e-5 m; leaving the
/// step free at rtol 1e-3 costs twice as much for 1.2e-4 m.
pub fn full_method() -> Integrator {
    Integrator::radau(1e-2, Some(6e-3))
}

/// The tight run that serves as the converged solution of each model of case (b).
pub fn full_reference() -> Integrator {
    Integrator::radau(1e-9, None)
}

/// Integrator of the reduced models: the same as the full model's. Measured on this case, it
/// needs fewer right-hand sides than Dormand–Prince already at r = 2 (Dormand–Prince is limited
/// by the tolerance on the small modal amplitudes at r = 2, by stability from r = 3 on).
pub fn rom_method() -> Integrator {
    full_method()
}

/// The explicit alternative, shown for r = 2. rtol 1e-5: with the error weights in physical units
/// (`state_atol`) it gives 1.8e-5 m in 1946 right-hand sides (rtol 1e-3 gives 1.9e-3 m; before
/// those weights, rtol 1e-3 took 2090 right-hand sides for 4.5e-5 m).
pub fn explicit_method() -> Integrator {
    Integrator::dopri5(1e-5)
}

/// Integrator of the free-vibration case (a), both models, over 1 s.
pub fn release_method() -> Integrator {
    Integrator::radau(1e-5, None)
}

/// Integrator of the 30 s free vibration: symplectic, so the energy error does not drift.
pub fn long_method() -> Integrator {
    Integrator::midpoint(2.5e-4)
}

/// The runaway limit of the study: a free vibration whose energy reached 10 times its initial
/// value (an energy gain `(H − H(0)) / H(0)` of 9) has blown up.
pub const ENERGY_RUNAWAY: f64 = 9.0;

/// Integrate `eom` from the coordinates `x0` at rest (`xdot0`) at `t_out[0]` to the output
/// times `t_out`, with the energy audit of every dynamic analysis (default limits, or the
/// runaway limit `runaway`).
pub fn integrate<M: StructuralModel>(
    eom: &mut EquationsOfMotion<'_, M>,
    x0: &[f64],
    xdot0: &[f64],
    t_out: &[f64],
    integrator: &Integrator,
    runaway: Option<f64>,
) -> AuditedRun {
    let mut audit = AuditSettings::default();
    if let Some(limit) = runaway {
        audit.runaway = limit;
    }
    integrate_audited(
        eom,
        x0,
        xdot0,
        t_out,
        integrator.method,
        &integrator.settings,
        &audit,
        None,
        &mut |_| {},
    )
}
