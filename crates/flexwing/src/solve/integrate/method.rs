//! One runtime choice of integrator: the [`Method`] enum, the [`IntegratorSettings`] every method
//! reads (tolerances belong to the problem, not to a method), and [`integrate`], the one
//! dispatcher to [`Radau`], [`Bdf`], [`Dopri5`], [`ImplicitMidpoint`] and [`GeneralizedAlpha`].
//!
//! Adding a method: one variant of [`Method`], its name in [`Method::name`] and [`Method::ALL`],
//! and one arm in [`integrate`] that builds its options from the settings.

use super::{
    Bdf, BdfOptions, Dopri5, Dopri5Options, GeneralizedAlpha, GeneralizedAlphaOptions,
    ImplicitMidpoint, IntegrationResult, MidpointOptions, OdeSystem, Radau, RadauOptions,
    Tolerances,
};
use crate::error::InputError;
use crate::text::short;

/// A time integrator of the library.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "kebab-case")
)]
pub enum Method {
    /// Radau IIA of order 5 (`RADAU5`): stiff, L-stable; the default, with the fewest
    /// right-hand sides on the paper's cases for the full and the reduced models
    /// (docs/performance.md).
    #[default]
    Radau,
    /// Variable-order BDF/NDF (as MATLAB's `ode15s`), orders up to [`IntegratorSettings::max_order`].
    Bdf,
    /// Dormand–Prince 5(4): explicit, for non-stiff problems.
    Dopri5,
    /// The implicit midpoint rule: symplectic, with the fixed step [`IntegratorSettings::step`]
    /// or adaptive by step doubling.
    Midpoint,
    /// Generalized-α (first-order form of Jansen, Whiting & Hulbert): second order, with the
    /// numerical damping of unresolved high modes set by
    /// [`IntegratorSettings::spectral_radius`]; the fixed step [`IntegratorSettings::step`] or
    /// adaptive.
    GeneralizedAlpha,
}

impl Method {
    /// Every method, in the order of the documentation.
    pub const ALL: [Method; 5] = [
        Method::Radau,
        Method::Bdf,
        Method::Dopri5,
        Method::Midpoint,
        Method::GeneralizedAlpha,
    ];

    /// The method's name as written in a case file (`radau`, `bdf`, `dopri5`, `midpoint`,
    /// `generalized-alpha`).
    pub fn name(self) -> &'static str {
        match self {
            Method::Radau => "radau",
            Method::Bdf => "bdf",
            Method::Dopri5 => "dopri5",
            Method::Midpoint => "midpoint",
            Method::GeneralizedAlpha => "generalized-alpha",
        }
    }
}

/// Smallest accepted relative tolerance: below it round-off dominates the error estimates.
pub const MIN_RTOL: f64 = 1e-13;

/// What every integrator reads; each method uses the settings that apply to it (the step
/// controls of the adaptive methods ignore `step`, only BDF reads `max_order`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(default, deny_unknown_fields)
)]
pub struct IntegratorSettings {
    /// Relative tolerance, in `[1e-13, 1)`. Default `1e-3` (as SciPy's and MATLAB's solvers):
    /// case (b)'s tip to about 1e-4 m (docs/performance.md, "Error weights in physical units").
    pub rtol: f64,
    /// Absolute tolerance in the units of the system's coordinates (rad for a beam), scaled per
    /// component by [`OdeSystem::atol_scale`] (the momenta of the equations of motion). Default
    /// `1e-5` rad.
    pub atol: f64,
    /// Budget of steps per run, accepted and rejected. Default 1 000 000.
    pub max_steps: usize,
    /// Largest step (s) of the adaptive methods; unlimited without it. Default `None`.
    pub max_step: Option<f64>,
    /// Fixed step (s) of the implicit midpoint rule and generalized-α; adaptive without it.
    /// Default `None`.
    pub step: Option<f64>,
    /// Largest order of BDF, 1 to 5. Default 2 (orders above 2 are not A-stable, see
    /// [`BdfOptions::max_order`]).
    pub max_order: usize,
    /// Spectral radius `ρ∞` of generalized-α at `h ω → ∞`, in `[0, 1]`: the fraction of an
    /// unresolved high mode that survives one step (1: no numerical damping, 0: the most).
    /// Default 0.5.
    pub spectral_radius: f64,
}

impl Default for IntegratorSettings {
    fn default() -> Self {
        Self {
            rtol: 1e-3,
            atol: 1e-5,
            max_steps: 1_000_000,
            max_step: None,
            step: None,
            max_order: 2,
            spectral_radius: 0.5,
        }
    }
}

impl IntegratorSettings {
    /// Check the values; errors name `{prefix}.rtol`, `{prefix}.max_step`, ….
    ///
    /// # Errors
    /// `rtol` outside `[1e-13, 1)`, `atol`, `step` or `max_step` not finite and positive,
    /// `max_order` outside 1 to 5, `max_steps = 0`.
    ///
    /// ```
    /// use flexwing::solve::integrate::IntegratorSettings;
    /// let s = IntegratorSettings { rtol: 0.0, ..Default::default() };
    /// let e = s.validate("dynamic").unwrap_err();
    /// assert_eq!(e.to_string(), "dynamic.rtol: must be a number in [1e-13, 1), got 0");
    /// ```
    pub fn validate(&self, prefix: &str) -> Result<(), InputError> {
        let field = |key: &str| crate::field(prefix, key);
        if !(MIN_RTOL..1.0).contains(&self.rtol) {
            return Err(InputError::new(
                field("rtol"),
                format!(
                    "must be a number in [{}, 1), got {}",
                    short(MIN_RTOL),
                    short(self.rtol)
                ),
            ));
        }
        let positive = |key: &str, v: f64| {
            if v > 0.0 && v.is_finite() {
                Ok(())
            } else {
                Err(InputError::new(
                    field(key),
                    format!("must be a finite positive number, got {}", short(v)),
                ))
            }
        };
        positive("atol", self.atol)?;
        if !(1..=5).contains(&self.max_order) {
            return Err(InputError::new(
                field("max_order"),
                format!("must be between 1 and 5, got {}", self.max_order),
            ));
        }
        if !(0.0..=1.0).contains(&self.spectral_radius) {
            return Err(InputError::new(
                field("spectral_radius"),
                format!(
                    "must be a number in [0, 1], got {}",
                    short(self.spectral_radius)
                ),
            ));
        }
        if let Some(h) = self.step {
            positive("step", h)?;
        }
        if let Some(h) = self.max_step {
            positive("max_step", h)?;
        }
        if self.max_steps == 0 {
            return Err(InputError::new(
                field("max_steps"),
                "must be at least 1, got 0",
            ));
        }
        Ok(())
    }

    /// The tolerances for `system`: `rtol`, and `atol` times the system's scale per component.
    fn tolerances<S: OdeSystem>(&self, system: &mut S) -> Tolerances {
        let mut scale = vec![1.0; system.dim()];
        system.atol_scale(&mut scale);
        Tolerances {
            rtol: self.rtol,
            atol: scale.iter().map(|s| self.atol * s).collect(),
        }
    }
}

/// Integrate `system` from `(t0, y0)` with `method` and return the state at each of `t_out`
/// (non-decreasing, not before `t0`). `progress` is called with the time after each step.
///
/// # Errors
/// As the method's own `integrate`: invalid output times or settings are
/// [`crate::InputError`]s inside the failure; a failed step, a non-finite state or the step
/// budget stop the run with the output so far.
///
/// ```
/// use flexwing::solve::integrate::{integrate, IntegratorSettings, Method, OdeSystem};
/// # use nalgebra::DMatrix;
/// /// y' = −y.
/// struct Decay;
/// impl OdeSystem for Decay {
///     fn dim(&self) -> usize { 1 }
///     fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) { dy[0] = -y[0]; }
///     fn jacobian(&mut self, _t: f64, _y: &[f64], j: &mut DMatrix<f64>) { j[(0, 0)] = -1.0; }
/// }
/// let settings = IntegratorSettings { rtol: 1e-6, atol: 1e-8, ..Default::default() };
/// for method in Method::ALL {
///     let (trajectory, _) = integrate(method, &settings, &mut Decay, 0.0, &[1.0], &[1.0], &mut |_| {})?;
///     assert!((trajectory.y[0][0] - (-1.0f64).exp()).abs() < 1e-4, "{method:?}");
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn integrate<S: OdeSystem>(
    method: Method,
    settings: &IntegratorSettings,
    system: &mut S,
    t0: f64,
    y0: &[f64],
    t_out: &[f64],
    progress: &mut dyn FnMut(f64),
) -> IntegrationResult {
    system.integrating_with(method, settings);
    let tolerances = settings.tolerances(system);
    let max_step = settings.max_step.unwrap_or(f64::INFINITY);
    let max_steps = settings.max_steps;
    match method {
        Method::Radau => Radau {
            options: RadauOptions {
                tolerances,
                max_steps,
                max_step,
                ..RadauOptions::default()
            },
        }
        .integrate(system, t0, y0, t_out, progress),
        Method::Bdf => Bdf {
            options: BdfOptions {
                tolerances,
                max_order: settings.max_order,
                max_steps,
                max_step,
                ..BdfOptions::default()
            },
        }
        .integrate(system, t0, y0, t_out, progress),
        Method::Dopri5 => Dopri5 {
            options: Dopri5Options {
                tolerances,
                max_steps,
                max_step,
                ..Dopri5Options::default()
            },
        }
        .integrate(system, t0, y0, t_out, progress),
        Method::Midpoint => ImplicitMidpoint {
            options: MidpointOptions {
                tolerances,
                step: settings.step,
                max_steps,
                max_step,
                ..MidpointOptions::default()
            },
        }
        .integrate(system, t0, y0, t_out, progress),
        Method::GeneralizedAlpha => GeneralizedAlpha {
            options: GeneralizedAlphaOptions {
                tolerances,
                spectral_radius: settings.spectral_radius,
                step: settings.step,
                max_steps,
                max_step,
                ..GeneralizedAlphaOptions::default()
            },
        }
        .integrate(system, t0, y0, t_out, progress),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn settings_errors_name_the_callers_field() {
        let cases = [
            (
                IntegratorSettings {
                    rtol: 1e-300,
                    ..Default::default()
                },
                "d.rtol: must be a number in [1e-13, 1), got 1e-300",
            ),
            (
                IntegratorSettings {
                    atol: -1.0,
                    ..Default::default()
                },
                "d.atol: must be a finite positive number, got -1",
            ),
            (
                IntegratorSettings {
                    max_order: 6,
                    ..Default::default()
                },
                "d.max_order: must be between 1 and 5, got 6",
            ),
            (
                IntegratorSettings {
                    step: Some(0.0),
                    ..Default::default()
                },
                "d.step: must be a finite positive number, got 0",
            ),
            (
                IntegratorSettings {
                    max_step: Some(f64::NAN),
                    ..Default::default()
                },
                "d.max_step: must be a finite positive number, got NaN",
            ),
            (
                IntegratorSettings {
                    spectral_radius: 1.5,
                    ..Default::default()
                },
                "d.spectral_radius: must be a number in [0, 1], got 1.5",
            ),
            (
                IntegratorSettings {
                    max_steps: 0,
                    ..Default::default()
                },
                "d.max_steps: must be at least 1, got 0",
            ),
        ];
        for (settings, expected) in cases {
            assert_eq!(settings.validate("d").unwrap_err().to_string(), expected);
        }
        assert!(IntegratorSettings::default().validate("d").is_ok());
        let e = IntegratorSettings {
            rtol: 0.0,
            ..Default::default()
        }
        .validate("")
        .unwrap_err();
        assert_eq!(e.field, "rtol");
    }

    #[test]
    fn names_are_distinct() {
        let names: Vec<&str> = Method::ALL.iter().map(|m| m.name()).collect();
        assert_eq!(
            names,
            ["radau", "bdf", "dopri5", "midpoint", "generalized-alpha"]
        );
    }
}
