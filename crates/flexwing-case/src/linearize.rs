//! `[linearize]` and `[aero.flight]` into the library's
//! [`flexwing::analysis::aero::linearize::LinearizePlan`]: the equilibrium's flight condition is
//! `[aero.flight]` (its `speed` required), the models, signals and states `[linearize]`'s. The
//! library parses the signal names and checks every value under the case file's names. The
//! structure is `[beam]`'s planar chain or, with `beam.model = "chain3d"`, the 3-D chain.

use flexwing::analysis::aero::linearize::{LinearStructure, LinearizePlan};
use flexwing::model::FullModel;
use flexwing::solve::aeroelastic::StateBasis;
use flexwing::InputError;

use super::aero::{condition, fields, refuse_histories, LINEAR_RUN};
use super::spec::Case;
use super::spec_aero::StatesSpec;
use crate::CaseError;

impl Case {
    /// The linearization of `[aero]` at `aero.flight.speed` (root angle, gravity), `[[loads]]`
    /// and `[linearize]` (defaults without it), with the static solver's options of `[static]`,
    /// validated.
    ///
    /// # Errors
    /// No `[aero]` or `aero.flight.speed`, and every error of [`LinearizePlan::validate`]
    /// (unknown signal names, a speed that is not positive, …), named as in the case file.
    pub fn linearize_plan(&self) -> Result<LinearizePlan, CaseError> {
        self.checked_linearize_plan().map_err(|e| self.error(e))
    }

    pub(crate) fn checked_linearize_plan(&self) -> Result<LinearizePlan, InputError> {
        let (spec, aero) = self.aero_of()?;
        refuse_histories(spec, LINEAR_RUN)?;
        let speed = spec.flight.speed.ok_or_else(|| {
            InputError::new(
                "aero.flight.speed",
                "missing: a linear model is taken about the static aeroelastic equilibrium at \
                 this free-stream speed (m/s)",
            )
        })?;
        let (model, loads): (LinearStructure, _) = if self.is_chain3d() {
            let chain = self.beam.chain3d()?;
            let loads = self.aero_loads3d(&chain)?;
            (chain.into(), loads)
        } else {
            let model = FullModel::new(self.to_beam()?);
            let loads = self.aero_loads(&model)?;
            (model.into(), loads)
        };
        let l = self.linearize.clone().unwrap_or_default();
        let mut plan = LinearizePlan::new(model, aero, condition(&spec.flight, speed));
        plan.loads = loads;
        plan.full = l.full;
        plan.reduced = l.reduced;
        plan.reduced_modes = l.reduced_modes;
        if let Some(inputs) = l.inputs {
            plan.inputs = inputs;
        }
        if let Some(outputs) = l.outputs {
            plan.outputs = outputs;
        }
        plan.states = match l.states {
            None | Some(StatesSpec::Velocities) => StateBasis::Velocities,
            Some(StatesSpec::Momenta) => StateBasis::Momenta,
        };
        plan.static_options = self.static_options();
        plan.validate(&fields("linearize"))?;
        Ok(plan)
    }
}

#[cfg(test)]
mod tests {
    use crate::Case;

    const CASE: &str = r#"
[beam]
length = 16.0
elements = 8

[beam.section]
EI = 2.0e4
GJ = 1.0e4
mass_per_length = 0.75
polar_inertia = 0.1
polar_inertia_about = "mass-centre"

[aero]
chord = 1.0
elastic_axis = 0.5
density = 0.0889
aerodynamics = { model = "wagner" }

[aero.flight]
speed = 20.0
"#;

    #[test]
    fn the_plan_takes_linearize_and_the_flight() {
        let text = format!(
            "{CASE}\n[linearize]\nreduced = [4]\ninputs = [\"gust\", \"force[8]\"]\n\
             outputs = [\"tip_twist\"]\nstates = \"momenta\"\n"
        );
        let plan = Case::from_toml_str(&text)
            .unwrap()
            .linearize_plan()
            .unwrap();
        assert_eq!(plan.flight.speed, 20.0);
        assert_eq!(plan.inputs, ["gust", "force[8]"]);
        assert_eq!(plan.outputs, ["tip_twist"]);
        assert_eq!(plan.reduced, [4]);
        assert_eq!(
            plan.states,
            flexwing::solve::aeroelastic::StateBasis::Momenta
        );
        // Without [linearize]: the defaults.
        let plan = Case::from_toml_str(CASE).unwrap().linearize_plan().unwrap();
        assert_eq!(plan.inputs, ["gust"]);
    }

    #[test]
    fn errors_name_the_key() {
        let cases = [
            (
                format!("{CASE}\n[linearize]\ninputs = [\"gust\", \"wind\"]\n"),
                "linearize.inputs[1]: unknown input \"wind\"",
            ),
            (
                format!("{CASE}\n[linearize]\noutputs = [\"y[9]\"]\n"),
                "linearize.outputs[0]: node 9 is out of range",
            ),
            (
                format!("{CASE}\n[linearize]\nstates = \"positions\"\n"),
                "linearize.states",
            ),
            (
                CASE.replace("speed = 20.0", "root_angle = 0.01"),
                "aero.flight.speed: missing",
            ),
            (
                CASE.replace("speed = 20.0", "speed = 0.0"),
                "aero.flight.speed: missing or not positive",
            ),
        ];
        for (text, expected) in cases {
            let e = match Case::from_toml_str(&text) {
                Ok(case) => case.linearize_plan().unwrap_err(),
                Err(e) => e,
            };
            let message = e.to_string();
            assert!(message.contains(expected), "{message}");
        }
    }
}
