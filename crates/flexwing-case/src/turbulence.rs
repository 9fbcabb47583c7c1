//! `[turbulence]` with `[aero]` and `[linearize]` into a
//! [`flexwing::analysis::aero::turbulence::TurbulencePlan`]: the linear models of
//! `flexwing linearize` (models, outputs, states; the inputs are the gust and its rate), driven
//! by von Kármán or Dryden turbulence. The library checks the values (intensity, scale length,
//! the frequency grid); this module fills in the defaults of the keys not given.

use flexwing::analysis::aero::turbulence::TurbulencePlan;
use flexwing::solve::aeroelastic::turbulence::{Spectrum, Turbulence};
use flexwing::InputError;

use super::spec::Case;
use super::spec_aero::SpectrumSpec;
use crate::CaseError;

impl Case {
    /// The response to the turbulence of `[turbulence]` through the linear models of
    /// [`Case::linearize_plan`], validated.
    ///
    /// # Errors
    /// No `[turbulence]`; the errors of the linearization and of the turbulence's checks,
    /// under the case file's names.
    pub fn turbulence_plan(&self) -> Result<TurbulencePlan, CaseError> {
        self.checked_turbulence_plan().map_err(|e| self.error(e))
    }

    fn checked_turbulence_plan(&self) -> Result<TurbulencePlan, InputError> {
        let prefix = "turbulence";
        let spec = self.turbulence.as_ref().ok_or_else(|| {
            InputError::new(
                prefix,
                "missing: flexwing turbulence needs a [turbulence] table (at least its \
                 intensity, the RMS vertical gust velocity in m/s)",
            )
        })?;
        let spectrum = match spec.spectrum {
            None | Some(SpectrumSpec::VonKarman) => Spectrum::VonKarman,
            Some(SpectrumSpec::Dryden) => Spectrum::Dryden,
        };
        let mut turbulence = Turbulence::new(spectrum, spec.intensity);
        if let Some(l) = spec.scale_length {
            turbulence.scale_length = l;
        }
        let mut plan = TurbulencePlan::new(self.checked_linearize_plan()?, turbulence);
        // The default grid depends on the scale length: checked before it is built.
        turbulence.validate(prefix)?;
        let mut grid = plan.grid();
        if let Some(n) = spec.frequencies {
            grid.points = n;
        }
        if let Some(w) = spec.min_frequency {
            grid.min_frequency = w;
        }
        if let Some(w) = spec.max_frequency {
            grid.max_frequency = w;
        }
        plan.grid = Some(grid);
        plan.validate(&super::aero::fields("linearize"), prefix)?;
        Ok(plan)
    }
}

#[cfg(test)]
mod tests {
    use flexwing::solve::aeroelastic::turbulence::{Spectrum, DRYDEN_SCALE, VON_KARMAN_SCALE};

    use crate::{Analysis, Case};

    const CASE: &str = r#"
[beam]
length = 16.0
elements = 4

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
    fn the_plan_takes_turbulence_and_linearize() {
        let text = format!(
            "{CASE}\n[linearize]\nreduced = [2]\noutputs = [\"tip_twist\"]\n\n[turbulence]\n\
             spectrum = \"dryden\"\nintensity = 1.5\nfrequencies = 64\nmax_frequency = 50.0\n"
        );
        let case = Case::from_toml_str(&text).unwrap();
        let plan = case.turbulence_plan().unwrap();
        assert_eq!(plan.turbulence.spectrum, Spectrum::Dryden);
        assert_eq!(plan.turbulence.intensity, 1.5);
        assert_eq!(plan.turbulence.scale_length, DRYDEN_SCALE);
        assert_eq!(plan.linearize.inputs, ["gust", "gust_rate"]);
        assert_eq!(plan.linearize.outputs, ["tip_twist"]);
        assert_eq!(plan.linearize.reduced, [2]);
        let grid = plan.grid();
        assert_eq!((grid.points, grid.max_frequency), (64, 50.0));
        // The default low end: 1e-3 U/L.
        assert_eq!(grid.min_frequency, 1e-3 * 20.0 / DRYDEN_SCALE);
        assert!(matches!(
            case.plan(Analysis::Turbulence).unwrap(),
            flexwing::analysis::Plan::Turbulence(_)
        ));
        let plan = Case::from_toml_str(&format!("{CASE}\n[turbulence]\nintensity = 1.0\n"))
            .unwrap()
            .turbulence_plan()
            .unwrap();
        assert_eq!(plan.turbulence.spectrum, Spectrum::VonKarman);
        assert_eq!(plan.turbulence.scale_length, VON_KARMAN_SCALE);
        assert_eq!(plan.grid().points, 500);
    }

    #[test]
    fn errors_name_the_key() {
        let cases = [
            (CASE.to_string(), "turbulence: missing"),
            (
                format!("{CASE}\n[turbulence]\nintensity = -1.0\n"),
                "turbulence.intensity: must be a finite positive",
            ),
            (
                format!("{CASE}\n[turbulence]\nintensity = 1.0\nscale_length = 0.0\n"),
                "turbulence.scale_length: must be a finite positive",
            ),
            (
                format!("{CASE}\n[turbulence]\nintensity = 1.0\nfrequencies = 3\n"),
                "turbulence.frequencies: must be between 16",
            ),
            (
                format!("{CASE}\n[turbulence]\nintensity = 1.0\nmax_frequency = 1e-6\n"),
                "turbulence.max_frequency: must be above min_frequency",
            ),
            (
                format!("{CASE}\n[turbulence]\nintensity = 1.0\nspectrum = \"kaimal\"\n"),
                "turbulence.spectrum",
            ),
            (format!("{CASE}\n[turbulence]\nsigma = 1.0\n"), "turbulence"),
            (
                format!(
                    "{CASE}\n[linearize]\noutputs = [\"y[9]\"]\n[turbulence]\nintensity = 1.0\n"
                ),
                "linearize.outputs[0]: node 9 is out of range",
            ),
        ];
        for (text, expected) in cases {
            let e = match Case::from_toml_str(&text) {
                Ok(case) => case.turbulence_plan().unwrap_err(),
                Err(e) => e,
            };
            let message = e.to_string();
            assert!(message.contains(expected), "{message}");
        }
    }
}
