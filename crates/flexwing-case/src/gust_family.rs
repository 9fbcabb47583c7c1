//! `[gust_family]` with `[aero]` and `[dynamic]` into a
//! [`flexwing::analysis::aero::gust_family::GustFamilyPlan`]: the aeroelastic response of
//! `flexwing dynamic` (models, integrator, output times, flight) run once per gust of the family,
//! each member's 1−cos gust replacing `[aero.flight.gust]`. The library checks the values
//! (gradients within [30 ft, 350 ft], `U_ref`, `F_g`, the end time); this module checks how the
//! gradients are spelled.

use flexwing::analysis::aero::gust_family::{GustFamilyPlan, GustLengths};
use flexwing::solve::aeroelastic::GustPenetration;
use flexwing::InputError;

use super::aero::{listed_or_spaced, Spaced};
use super::spec::Case;
use super::spec_aero::GustPenetrationSpec;
use crate::CaseError;

impl Case {
    /// The gust family of `[gust_family]`, on the aeroelastic response of the case
    /// ([`Case::aero_dynamic_plan`]) without its gust.
    ///
    /// # Errors
    /// No `[gust_family]`; the errors of the response plan and of the family's checks, under
    /// the case file's names.
    pub fn gust_family_plan(&self) -> Result<GustFamilyPlan, CaseError> {
        self.checked_gust_family_plan().map_err(|e| self.error(e))
    }

    fn checked_gust_family_plan(&self) -> Result<GustFamilyPlan, InputError> {
        let prefix = "gust_family";
        let spec = self.gust_family.as_ref().ok_or_else(|| {
            InputError::new(
                prefix,
                "missing: flexwing gust needs a [gust_family] table (the gust gradient \
                 distances and reference_velocity)",
            )
        })?;
        let mut response = self.checked_aero_dynamic_plan()?;
        // Each member's gust replaces [aero.flight.gust] (docs/case-file.md).
        response.flight.gust = None;
        let lengths = match listed_or_spaced(
            prefix,
            "lengths",
            &spec.lengths,
            (spec.from, spec.to, spec.steps),
        )? {
            Spaced::Listed(v) => GustLengths::List(v),
            Spaced::Range { from, to, steps } => GustLengths::Range { from, to, steps },
        };
        let plan = GustFamilyPlan {
            response,
            lengths,
            reference_velocity: spec.reference_velocity,
            alleviation: spec.alleviation.unwrap_or(1.0),
            start: spec.start.unwrap_or(0.0),
            penetration: match spec.penetration {
                None | Some(GustPenetrationSpec::Uniform) => GustPenetration::Uniform,
                Some(GustPenetrationSpec::Kussner) => GustPenetration::Kussner,
            },
        };
        plan.validate(prefix, &super::aero::fields("dynamic"))?;
        Ok(plan)
    }
}

#[cfg(test)]
mod tests {
    use flexwing::analysis::aero::gust_family::{GustLengths, FOOT};
    use flexwing::solve::aeroelastic::GustPenetration;

    use crate::{Analysis, Case};

    /// Patil's wing on 4 elements with a gust of its own and a family of three.
    const CASE: &str = r#"
[beam]
length = 16
elements = 4

[beam.section]
EI = 2e4
mass_per_length = 0.75
GJ = 1e4
polar_inertia = 0.1
polar_inertia_about = "mass-centre"

[aero]
chord = 1.0
elastic_axis = 0.5
density = 0.0889
aerodynamics = { model = "wagner" }

[aero.flight]
speed = 25
root_angle = 0.03

[aero.flight.gust]
shape = "sharp-edged"
amplitude = 2

[gust_family]
from = 9.144
to = 106.68
steps = 3
reference_velocity = 0.5
alleviation = 0.8
start = 0.1
penetration = "kussner"

[dynamic]
end_time = 9
output_step = 0.1
reduced = [4]
"#;

    fn plan(edit: (&str, &str)) -> Result<flexwing::analysis::Plan, crate::CaseError> {
        Case::from_toml_str(&CASE.replace(edit.0, edit.1))?.plan(Analysis::GustFamily)
    }

    /// Every key reaches its field; the family's gusts replace `[aero.flight.gust]`; the
    /// models are those of `[dynamic]`.
    #[test]
    fn keys_reach_the_plan() {
        let Ok(flexwing::analysis::Plan::GustFamily(p)) = plan(("", "")) else {
            panic!("a gust family plan")
        };
        assert_eq!(
            p.lengths,
            GustLengths::Range {
                from: 30.0 * FOOT,
                to: 350.0 * FOOT,
                steps: 3
            }
        );
        assert_eq!(
            (p.reference_velocity, p.alleviation, p.start),
            (0.5, 0.8, 0.1)
        );
        assert_eq!(p.penetration, GustPenetration::Kussner);
        assert!(p.response.flight.gust.is_none());
        assert_eq!(p.response.structure.reduced, vec![4]);
        let Ok(flexwing::analysis::Plan::GustFamily(p)) =
            plan(("from = 9.144\nto = 106.68\nsteps = 3", "lengths = [10, 20]"))
        else {
            panic!("a listed family")
        };
        assert_eq!(p.lengths, GustLengths::List(vec![10.0, 20.0]));
    }

    /// Errors name the case file's keys.
    #[test]
    fn errors_name_the_keys() {
        let cases = [
            (("steps = 3", ""), "gust_family.steps: missing"),
            (
                ("steps = 3", "steps = 3\nlengths = [10]"),
                "gust_family: give either lengths or from/to/steps",
            ),
            (("from = 9.144", "from = 9.0"), "gust_family.lengths: "),
            (("steps = 3", "steps = 0"), "gust_family.steps: "),
            (
                ("reference_velocity = 0.5", "reference_velocity = -1"),
                "gust_family.reference_velocity: ",
            ),
            (
                ("alleviation = 0.8", "alleviation = 2"),
                "gust_family.alleviation: ",
            ),
            (("start = 0.1", "start = -1"), "gust_family.start: "),
            (("end_time = 9", "end_time = 5"), "dynamic.end_time: "),
            (
                ("model = \"wagner\"", "model = \"steady\""),
                "gust_family.penetration: ",
            ),
        ];
        for (edit, expected) in cases {
            let e = plan(edit).unwrap_err();
            let msg = format!("{}: {}", e.key.clone().unwrap_or_default(), e.reason);
            assert!(msg.starts_with(expected), "{msg}");
        }
        let start = CASE.find("[gust_family]").unwrap();
        let end = CASE.find("[dynamic]").unwrap();
        let e = plan((&CASE[start..end], "")).unwrap_err();
        assert_eq!(e.key.as_deref(), Some("gust_family"), "{e}");
        assert!(e.reason.starts_with("missing: flexwing gust needs"), "{e}");
    }
}
