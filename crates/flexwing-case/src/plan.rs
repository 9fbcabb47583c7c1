//! What a front end asks for — an [`Analysis`] of a case — into the library's one [`Plan`]:
//! the one place where a case with `[aero]` takes the aeroelastic plans (`static` and `dynamic`
//! become the static aeroelastic equilibria and the aeroelastic response), never the
//! structural ones with its `[aero]` table ignored.

use flexwing::analysis::Plan;

use crate::{Case, CaseError};

/// An analysis a front end asks of a case: the CLI's subcommand, Python's `Case` method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Analysis {
    /// Natural modes of `[beam]` (`[modes]`), in vacuo with `[aero]` too.
    Modes,
    /// Non-linear statics (`[[loads]]`, `[static]`); with `[aero]` the static aeroelastic
    /// equilibria and the divergence speed.
    Static,
    /// Non-linear dynamics (`[[loads]]`, `[dynamic]`); with `[aero]` the aeroelastic response.
    Dynamic,
    /// Flutter and divergence along `[aero.sweep]` (`[aero]`, `[flutter]`).
    Flutter,
    /// Linear state-space models about the static aeroelastic equilibrium at
    /// `aero.flight.speed` (`[aero]`, `[linearize]`).
    Linearize,
    /// Flutter and divergence against a load level (`[flutter.study]`; the 3-D chain).
    Study,
    /// A discrete gust family (`[gust_family]` on the aeroelastic response of `[aero]` and
    /// `[dynamic]`): `flexwing gust`.
    GustFamily,
    /// Output spectra and RMS in continuous turbulence (`[turbulence]` through the linear model
    /// of `[linearize]`): `flexwing turbulence`.
    Turbulence,
}

impl Analysis {
    /// Every analysis.
    pub const ALL: [Analysis; 8] = [
        Analysis::Modes,
        Analysis::Static,
        Analysis::Dynamic,
        Analysis::Flutter,
        Analysis::Linearize,
        Analysis::Study,
        Analysis::GustFamily,
        Analysis::Turbulence,
    ];

    /// `modes`, `static`, `dynamic`, `flutter`, `linearize`, `study`, `gust` or `turbulence`: the
    /// CLI's subcommand.
    pub fn name(self) -> &'static str {
        match self {
            Analysis::Modes => "modes",
            Analysis::Static => "static",
            Analysis::Dynamic => "dynamic",
            Analysis::Flutter => "flutter",
            Analysis::Linearize => "linearize",
            Analysis::Study => "study",
            Analysis::GustFamily => "gust",
            Analysis::Turbulence => "turbulence",
        }
    }

    /// The analysis called `name` ([`Analysis::name`]).
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|a| a.name() == name)
    }
}

impl Case {
    /// The plan of `analysis` for this case, validated: [`Case::modes_plan`],
    /// [`Case::static_plan`] or [`Case::aero_static_plan`], [`Case::dynamic_plan`] or
    /// [`Case::aero_dynamic_plan`], [`Case::flutter_plan`], [`Case::linearize_plan`],
    /// [`Case::gust_family_plan`], [`Case::turbulence_plan`] — the aeroelastic one when the case
    /// has `[aero]`.
    ///
    /// # Errors
    /// Those of the plan built.
    ///
    /// ```
    /// use flexwing::analysis::{self, NoProgress, Plan};
    /// use flexwing_case::{Analysis, Case};
    ///
    /// let case = Case::from_toml_str(
    ///     "[beam]\nlength = 1.0\nelements = 8\n\n[beam.section]\nEI = 50.0\nmass_per_length = 0.2\n",
    /// )?;
    /// let plan = case.plan(Analysis::Modes)?;
    /// assert!(matches!(plan, Plan::Modes(_)));
    /// let outcome = analysis::run(&plan, &mut NoProgress)?;
    /// assert_eq!(outcome.status(), "complete");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn plan(&self, analysis: Analysis) -> Result<Plan, CaseError> {
        let aero = self.is_aeroelastic();
        // The linear models (and turbulence through them) of either chain are one plan.
        if self.is_chain3d() && !matches!(analysis, Analysis::Linearize | Analysis::Turbulence) {
            return Ok(Plan::Chain3d(self.chain3d_plan(analysis)?));
        }
        Ok(match analysis {
            Analysis::Modes => Plan::Modes(self.modes_plan()?),
            Analysis::Static if aero => Plan::AeroStatic(self.aero_static_plan()?),
            Analysis::Static => Plan::Static(self.static_plan()?),
            Analysis::Dynamic if aero => Plan::AeroDynamic(self.aero_dynamic_plan()?),
            Analysis::Dynamic => Plan::Dynamic(self.dynamic_plan()?),
            Analysis::Flutter => Plan::Flutter(self.flutter_plan()?),
            Analysis::Linearize => Plan::Linearize(self.linearize_plan()?),
            Analysis::GustFamily => Plan::GustFamily(self.gust_family_plan()?),
            Analysis::Turbulence => Plan::Turbulence(self.turbulence_plan()?),
            Analysis::Study => {
                return Err(self.error(flexwing::InputError::new(
                    "beam.model",
                    "the flutter study against a load level runs on the 3-D chain: set                      beam.model = \"chain3d\" (the planar chain's flutter speed ignores the \
                     deflection)",
                )))
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use flexwing::analysis::{Status, Stop};
    use flexwing::SolveError;

    /// The serialized form every front end shows (the CLI's JSON, Python's dicts): the status
    /// word, the stop with its reason, values, nested error and one-line messages.
    #[test]
    fn a_status_serializes_as_its_word_stop_and_message() {
        let status = Status::Stopped(Stop::Integration(SolveError::TooManySteps {
            time: 0.25,
            steps: 100,
        }));
        let v = serde_json::to_value(&status).unwrap();
        let message = "time integration stopped at t = 0.25 s: 100 steps (accepted and \
                       rejected) reached the limit max_steps";
        assert_eq!(
            v,
            serde_json::json!({
                "status": "stopped",
                "stop": {
                    "reason": "integration",
                    "error": { "kind": "too-many-steps", "time": 0.25, "steps": 100,
                               "message": message },
                    "message": message,
                },
                "message": message,
            })
        );
        let v = serde_json::to_value(Status::Complete).unwrap();
        assert_eq!(
            v,
            serde_json::json!({"status": "complete", "stop": null, "message": null})
        );
    }
}
