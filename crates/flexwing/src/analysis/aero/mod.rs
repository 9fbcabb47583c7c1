//! Aeroelastic analyses as plans and outcomes (docs/aeroelastic-model.md): static aeroelastic
//! equilibria and the divergence speed ([`statics`]), stability, V-g/V-ω data and the flutter
//! speeds along a sweep in speed ([`flutter`]), and time responses to gusts and to changes of
//! speed or root angle ([`response`]) — each for the full model and for reduced models on its wet
//! modes, in the style of [`super::statics`] and [`super::dynamics`]: a plan of plain data, its
//! `validate`, a `run(&plan, &mut progress)` and an outcome with one run per model.
//!
//! They wrap the solvers of [`crate::solve::aeroelastic`] ([`crate::solve::aeroelastic::static_sweep`],
//! [`crate::solve::aeroelastic::flutter`], the [`crate::solve::aeroelastic::AeroelasticEquations`]
//! integrated by any [`crate::solve::integrate::Method`]); this layer adds the models, the
//! names of the fields and the outputs a front end shows.
//!
//! Field names. A plan's parts come from different places of the caller's input (a case file:
//! `[[loads]]`, `[aero]`, `[static]`, `[flutter]` or `[dynamic]`), so `validate` takes their
//! prefixes as [`Fields`]: the aerodynamic data are named `{aero}.chord`, `{aero}.density`,
//! `{aero}.aerodynamics.states`, the flight `{aero}.flight.speed`, the gust
//! `{aero}.flight.gust.length`, the speeds `{aero}.sweep.speeds[i]`, the static solver's options
//! `{statics}.tolerance`, the analysis' own settings `{analysis}.reduced[i]`.

#[cfg(test)]
mod audit_tests;
pub mod flutter;
pub mod gust_family;
pub mod linearize;
pub mod response;
pub mod statics;
pub mod stepper;
pub mod turbulence;

use crate::error::{Error, InputError};
use crate::model::aero::{AeroSection, Aerodynamics, Aeroelastic};
use crate::model::{FullModel, ReducedModel};
use crate::text::short;

use super::ModelKind;

/// How a divergence speed was found, in one word: `bracketed` (between two speeds of the sweep)
/// or `undeformed` (the linear divergence pressure of the undeformed wing).
pub fn basis_name(basis: crate::solve::aeroelastic::DivergenceBasis) -> &'static str {
    use crate::solve::aeroelastic::DivergenceBasis;
    match basis {
        DivergenceBasis::Bracketed => "bracketed",
        DivergenceBasis::Undeformed => "undeformed",
    }
}

/// The aerodynamics of a plan: the section data along the span, the air and the aerodynamic
/// model. Errors name `{aero}.chord`, `{aero}.elastic_axis`, …, `{aero}.density`,
/// `{aero}.aerodynamics.states` (the section's fields are the prefix's own keys).
#[derive(Debug, Clone, PartialEq)]
pub struct Aero {
    /// Section data (chord, elastic axis, polar) along the span.
    pub section: AeroSection,
    /// Air density `ρ` (kg/m³).
    pub density: f64,
    /// The aerodynamic model.
    pub aerodynamics: Aerodynamics,
}

impl Aero {
    /// The full aeroelastic model of `model` with these aerodynamics; errors name
    /// `{prefix}.chord`, `{prefix}.density`, `{prefix}.aerodynamics.states`, ….
    ///
    /// # Errors
    /// The checks of [`Aeroelastic::new`].
    pub fn wing(&self, model: &FullModel, prefix: &str) -> Result<Aeroelastic, InputError> {
        Aeroelastic::new(
            model,
            &self.section,
            self.density,
            self.aerodynamics,
            prefix,
        )
    }
}

/// The caller's names of a plan's parts, for error messages. A case file uses
/// `Fields { loads: "loads", aero: "aero", statics: "static", analysis: "flutter" }` (the
/// analysis being `static`, `flutter` or `dynamic`); [`Fields::RELATIVE`] names the plan's own
/// fields.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fields<'a> {
    /// The loads: `{loads}[i]…`.
    pub loads: &'a str,
    /// The aerodynamic data, the flight and the sweep: `{aero}.chord`, `{aero}.flight.speed`,
    /// `{aero}.sweep.speeds[i]`.
    pub aero: &'a str,
    /// The static solver's options: `{statics}.tolerance`, ….
    pub statics: &'a str,
    /// The analysis' own settings: `{analysis}.reduced[i]`, `{analysis}.modes`, ….
    pub analysis: &'a str,
}

impl Fields<'_> {
    /// Names relative to a plan: `loads`, `aero`, `static_options`, and the plan's own fields
    /// without prefix.
    pub const RELATIVE: Fields<'static> = Fields {
        loads: "loads",
        aero: "aero",
        statics: "static_options",
        analysis: "",
    };

    /// `{aero}.flight`.
    pub fn flight(&self) -> String {
        crate::field(self.aero, "flight")
    }

    /// `{analysis}.key`.
    pub fn analysis(&self, key: &str) -> String {
        crate::field(self.analysis, key)
    }
}

/// A sweep in free-stream speed.
#[derive(Debug, Clone, PartialEq)]
pub struct SpeedSweep {
    /// Free-stream speeds (m/s), strictly increasing; errors name `{aero}.sweep.speeds[i]`.
    pub speeds: Vec<f64>,
}

impl SpeedSweep {
    /// Check the speeds: at least one, finite, strictly increasing, and non-negative (or
    /// positive, with `positive`); errors name `{field}[i]`.
    pub fn validate(&self, field: &str, positive: bool) -> Result<(), InputError> {
        if self.speeds.is_empty() {
            return Err(InputError::new(field, "needs at least one speed"));
        }
        for (i, &u) in self.speeds.iter().enumerate() {
            let reason = if !u.is_finite() {
                format!("must be finite, got {}", short(u))
            } else if let Err(e) = crate::magnitude::check("", "", u) {
                e.reason
            } else if positive && u <= 0.0 {
                format!(
                    "must be positive (the branches start from the wet modes at U = 0), got {}",
                    short(u)
                )
            } else if u < 0.0 {
                format!("must not be negative, got {}", short(u))
            } else if i > 0 && u <= self.speeds[i - 1] {
                format!(
                    "{} is not above speeds[{}] = {}; speeds must increase",
                    short(u),
                    i - 1,
                    short(self.speeds[i - 1])
                )
            } else {
                continue;
            };
            return Err(InputError::new(format!("{field}[{i}]"), reason));
        }
        Ok(())
    }
}

/// One model of an analysis, built: the full aeroelastic model or a reduced one on its wet modes.
pub(crate) enum Built {
    Full,
    Reduced(Box<Aeroelastic<ReducedModel>>),
}

/// Build the model of `kind` from the full aeroelastic model `full`.
pub(crate) fn build(full: &Aeroelastic, kind: &ModelKind) -> Result<Built, Error> {
    Ok(match kind.mode_indices() {
        Some(indices) => Built::Reduced(Box::new(full.reduced(&indices)?)),
        None => Built::Full,
    })
}

/// The models of a plan: the full model (if asked) then the reduced ones, after checking them
/// against the `n_dofs` wet modes; errors name `{prefix}.reduced[i]`, `{prefix}.full`.
pub(crate) fn models(
    full: bool,
    reduced: &[usize],
    reduced_modes: &[Vec<usize>],
    n_dofs: usize,
    prefix: &str,
) -> Result<Vec<ModelKind>, InputError> {
    let reduced = super::models::reduced_models(reduced, reduced_modes, n_dofs, prefix)?;
    if !full && reduced.is_empty() {
        return Err(InputError::new(
            crate::field(prefix, "full"),
            format!(
                "nothing to run: full = false and no reduced models (give {} or {})",
                crate::field(prefix, "reduced"),
                crate::field(prefix, "reduced_modes")
            ),
        ));
    }
    Ok(full
        .then_some(ModelKind::Full)
        .into_iter()
        .chain(reduced.into_iter().map(|(k, _)| k))
        .collect())
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::beam::Profile;
    use crate::model::aero::AeroSection;

    /// Patil's wing (docs/aeroelastic-model.md §5) on `n` elements, as the plans take it.
    pub(crate) fn patil(n: usize, aerodynamics: Aerodynamics) -> (FullModel, Aero) {
        // Aeroelastic::new puts its own fluid inertia on the structure it is given.
        let model = crate::wings::patil_wing(n, Aerodynamics::Steady)
            .unwrap()
            .full()
            .clone();
        let aero = Aero {
            section: AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5)),
            density: 0.0889,
            aerodynamics,
        };
        (model, aero)
    }

    #[test]
    fn speeds_are_checked_under_the_callers_name() {
        let cases = [
            (vec![], true, "s: needs at least one speed"),
            (vec![0.0, 1.0], true, "s[0]: must be positive"),
            (vec![0.0, 1.0], false, ""),
            (vec![-1.0], false, "s[0]: must not be negative, got -1"),
            (vec![1.0, 1.0], false, "s[1]: 1 is not above speeds[0] = 1"),
            (vec![1.0, f64::NAN], false, "s[1]: must be finite"),
        ];
        for (speeds, positive, expected) in cases {
            let r = SpeedSweep { speeds }.validate("s", positive);
            match r {
                Ok(()) => assert_eq!(expected, ""),
                Err(e) => assert!(e.to_string().starts_with(expected), "{e}"),
            }
        }
    }

    #[test]
    fn models_need_something_to_run() {
        let e = models(false, &[], &[], 8, "flutter").unwrap_err();
        assert!(
            e.to_string().starts_with("flutter.full: nothing to run"),
            "{e}"
        );
        let kinds = models(true, &[2], &[vec![1, 3]], 8, "flutter").unwrap();
        let labels: Vec<String> = kinds.iter().map(ModelKind::label).collect();
        assert_eq!(labels, ["full", "reduced-r2", "reduced-modes-1-3"]);
    }
}
