//! `[beam]` into the library's beam and full model, and `[modes]` into a modal plan. The library
//! validates values (positivity, NaN, table coverage, increasing stations); this module only
//! checks what the library cannot see: which keys were given together.

use flexwing::analysis::modes::ModesPlan;
use flexwing::beam::{
    Beam, Calibration, Discretization, InertiaAxis, Profile, RotaryInertia, SectionProperties,
    TorsionProperties,
};
use flexwing::model::FullModel;
use flexwing::InputError;

use super::spec::{
    BeamSpec, CalibrationSpec, Case, ElementInertiaSpec, InertiaAxisSpec, SectionSpec,
};
use crate::CaseError;

impl Case {
    /// The full model of `[beam]`.
    ///
    /// # Errors
    /// Keys that do not go together (`elements` and `stations`, torsion data without `GJ`), and
    /// the library's checks of the values ([`Beam::new`]).
    pub fn model(&self) -> Result<FullModel, CaseError> {
        self.to_beam()
            .map(FullModel::new)
            .map_err(|e| self.error(e))
    }

    /// The modal analysis of `[beam]` and `[modes]`, validated.
    ///
    /// # Errors
    /// As [`Case::model`]; `modes.count` outside `1 ..= n_dofs`.
    pub fn modes_plan(&self) -> Result<ModesPlan, CaseError> {
        ModesPlan::new(self.model()?, self.modes.count, "modes.count").map_err(|e| self.error(e))
    }

    /// The lumped-mass beam of `[beam]`, validated by [`Beam::new`].
    pub(crate) fn to_beam(&self) -> Result<Beam, InputError> {
        self.beam.to_beam()
    }
}

impl BeamSpec {
    /// The full model of this `[beam]` table; errors name `beam.length`, `beam.section.EI`, ….
    ///
    /// # Errors
    /// As [`Case::model`].
    pub fn model(&self) -> Result<FullModel, InputError> {
        self.to_beam().map(FullModel::new)
    }

    /// The lumped-mass beam of this `[beam]` table, validated by [`Beam::new`].
    pub(crate) fn to_beam(&self) -> Result<Beam, InputError> {
        let b = self;
        b.planar_only()?;
        let section = section(&b.section)?;
        let beam = Beam::named(
            "beam",
            b.length,
            &section,
            &discretization(b)?,
            calibration(b.calibration.unwrap_or_default())?,
        )?;
        let rotary = RotaryInertia {
            elements: b.element_inertia == Some(ElementInertiaSpec::Bar),
            section: b.section.rotary_inertia.as_ref().map(|p| p.0.clone()),
        };
        if rotary == RotaryInertia::default() {
            return Ok(beam);
        }
        beam.with_rotary_inertia("beam", &section, &rotary)
    }
}

pub(crate) fn discretization(b: &BeamSpec) -> Result<Discretization, InputError> {
    match (b.elements, &b.stations) {
        (Some(n), None) => Ok(Discretization::Uniform(n)),
        (None, Some(x)) => Ok(Discretization::Stations(x.clone())),
        (Some(_), Some(_)) => Err(InputError::new(
            "beam.elements",
            "give either `elements` (number of equal elements) or `stations` \
             (node positions, m), not both",
        )),
        (None, None) => Err(InputError::new(
            "beam.elements",
            "missing: give `elements` (number of equal elements) or `stations` \
             (node positions, m)",
        )),
    }
}

fn calibration(c: CalibrationSpec) -> Result<Calibration, InputError> {
    match c {
        CalibrationSpec::TipLoad => Ok(Calibration::TipLoad),
        CalibrationSpec::Uniform => Ok(Calibration::Uniform),
        CalibrationSpec::Compliance => Err(InputError::new(
            "beam.calibration",
            "\"compliance\" is the 3-D chain's calibration (beam.model = \"chain3d\"); the \
             planar chain takes \"tip-load\" or \"uniform\"",
        )),
    }
}

fn section(s: &SectionSpec) -> Result<SectionProperties, InputError> {
    let torsion = match &s.gj {
        None => {
            let torsion_only = [
                ("polar_inertia", s.polar_inertia.is_some()),
                ("polar_inertia_about", s.polar_inertia_about.is_some()),
                ("d0", s.d0.is_some()),
            ];
            if let Some((key, _)) = torsion_only.iter().find(|(_, given)| *given) {
                return Err(InputError::new(
                    format!("beam.section.{key}"),
                    "is torsion data and needs `GJ` (torsional stiffness, N·m²); \
                     give GJ, or remove the torsion keys for a bending-only beam",
                ));
            }
            None
        }
        Some(gj) => {
            let polar_inertia = s.polar_inertia.as_ref().ok_or_else(|| {
                InputError::new(
                    "beam.section.polar_inertia",
                    "missing: required when GJ is given (polar mass moment of inertia \
                     per length, kg·m)",
                )
            })?;
            let about = s.polar_inertia_about.ok_or_else(|| {
                InputError::new(
                    "beam.section.polar_inertia_about",
                    "missing: say which axis polar_inertia is about, \
                     \"mass-centre\" or \"elastic-axis\"",
                )
            })?;
            Some(TorsionProperties {
                gj: gj.0.clone(),
                polar_inertia: polar_inertia.0.clone(),
                inertia_axis: match about {
                    InertiaAxisSpec::MassCentre => InertiaAxis::MassCentre,
                    InertiaAxisSpec::ElasticAxis => InertiaAxis::ElasticAxis,
                },
                offset: s.d0.as_ref().map_or(Profile::Uniform(0.0), |d| d.0.clone()),
            })
        }
    };
    Ok(SectionProperties {
        ei: s.ei.0.clone(),
        mass_per_length: s.mass_per_length.0.clone(),
        torsion,
    })
}
