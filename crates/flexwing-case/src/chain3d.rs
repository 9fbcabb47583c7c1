//! `beam.model = "chain3d"`: `[beam]` into the library's 3-D chain ([`Chain3d`]), and the
//! analyses a front end asks of such a case into one [`Chain3dPlan`] (modes, statics, static
//! aeroelastic equilibria with `[aero]`, flutter, the flutter study of `[flutter.study]`). The planar case files are unchanged: a 3-D key on a
//! planar case is a one-line error naming the key ([`BeamSpec::planar_only`]).

use flexwing::analysis::aero::statics::DIVERGENCE_TOLERANCE;
use flexwing::analysis::aero::SpeedSweep;
use flexwing::analysis::chain3d::{
    AeroStatic3d, Analysis3d, Chain3dPlan, Dynamic3d, Flutter3d, Static3d, Study3d,
};
use flexwing::analysis::modes::DEFAULT_COUNT;
use flexwing::beam::{InertiaAxis, Profile};
use flexwing::model::chain3d::{
    Beam3d, Chain3d, ElementInertia, Geometry3d, JointCalibration, SectionInertia,
    SectionStiffness, SpatialDistributed, SpatialLoad, SpatialVector, StiffnessCoupling,
};
use flexwing::model::Load;
use flexwing::solve::aeroelastic::StudyParameter;
use flexwing::InputError;

use crate::aero::{condition, fields, speed_sweep};
use crate::plan::Analysis;
use crate::spec::{BeamSpec, CalibrationSpec, ElementInertiaSpec, InertiaAxisSpec};
use crate::spec_chain3d::{StructureSpec, StudyParameterSpec};
use crate::{Case, CaseError};

impl BeamSpec {
    /// Whether `[beam]` is of the 3-D chain.
    pub fn is_chain3d(&self) -> bool {
        self.model == StructureSpec::Chain3d
    }

    /// Reject the 3-D chain's keys on a planar beam, and a 3-D beam where the planar model is
    /// asked for.
    pub(crate) fn planar_only(&self) -> Result<(), InputError> {
        if self.is_chain3d() {
            return Err(InputError::new(
                "beam.model",
                "the case is of the 3-D chain (\"chain3d\"); this run needs the planar model \
                 (\"planar\")",
            ));
        }
        let s = &self.section;
        let keys = [
            ("beam.sweep", self.sweep.is_some()),
            ("beam.dihedral", self.dihedral.is_some()),
            ("beam.pretwist", self.pretwist.is_some()),
            ("beam.section.EI_lag", s.ei_lag.is_some()),
            ("beam.section.d0_normal", s.d0_normal.is_some()),
            (
                "beam.section.rotary_inertia_lag",
                s.rotary_inertia_lag.is_some(),
            ),
            ("beam.section.coupling", s.coupling.is_some()),
        ];
        match keys.iter().find(|(_, given)| *given) {
            Some((key, _)) => Err(InputError::new(
                *key,
                "is a key of the 3-D chain: set beam.model = \"chain3d\" (the planar chain \
                 bends in one plane without lag, sweep or coupling)",
            )),
            None => Ok(()),
        }
    }

    /// The 3-D chain of this `[beam]` table; errors name `beam.section.EI_lag`, ….
    ///
    /// # Errors
    /// A missing `EI_lag`, `GJ` or `polar_inertia`, the planar calibration `uniform`, and the
    /// library's checks ([`Beam3d::named`]).
    pub fn chain3d(&self) -> Result<Chain3d, InputError> {
        let s = &self.section;
        let p =
            |v: &Option<crate::Property>| v.as_ref().map_or(Profile::Uniform(0.0), |p| p.0.clone());
        let required = |v: &Option<crate::Property>, key: &str, what: &str| {
            v.as_ref().map(|p| p.0.clone()).ok_or_else(|| {
                InputError::new(
                    format!("beam.section.{key}"),
                    format!("missing: the 3-D chain needs {what}"),
                )
            })
        };
        let stiffness = SectionStiffness {
            gj: required(&s.gj, "GJ", "the torsional stiffness (N·m²)")?,
            ei_flap: s.ei.0.clone(),
            ei_lag: required(
                &s.ei_lag,
                "EI_lag",
                "the lag (in-plane) bending stiffness (N·m²)",
            )?,
            coupling: s.coupling.as_ref().map(|c| StiffnessCoupling {
                twist_flap: p(&c.twist_flap),
                twist_lag: p(&c.twist_lag),
                lag_flap: p(&c.lag_flap),
            }),
        };
        let inertia = SectionInertia {
            mass_per_length: s.mass_per_length.0.clone(),
            polar_inertia: required(
                &s.polar_inertia,
                "polar_inertia",
                "the polar mass moment of inertia per length (kg·m)",
            )?,
            polar_inertia_about: match s.polar_inertia_about {
                Some(InertiaAxisSpec::ElasticAxis) => InertiaAxis::ElasticAxis,
                Some(InertiaAxisSpec::MassCentre) => InertiaAxis::MassCentre,
                None => {
                    return Err(InputError::new(
                        "beam.section.polar_inertia_about",
                        "missing: say which axis polar_inertia is about, \"mass-centre\" or \
                         \"elastic-axis\"",
                    ))
                }
            },
            d0: p(&s.d0),
            d0_normal: p(&s.d0_normal),
            rotary_inertia_flap: p(&s.rotary_inertia),
            rotary_inertia_lag: p(&s.rotary_inertia_lag),
            element_inertia: match self.element_inertia {
                Some(ElementInertiaSpec::PointMass) => ElementInertia::Point,
                Some(ElementInertiaSpec::Bar) | None => ElementInertia::Bar,
            },
        };
        let calibration =
            match self.calibration {
                None | Some(CalibrationSpec::Compliance) => JointCalibration::Compliance,
                Some(CalibrationSpec::TipLoad) => JointCalibration::TipLoad,
                Some(CalibrationSpec::Uniform) => return Err(InputError::new(
                    "beam.calibration",
                    "\"uniform\" is the planar chain's; the 3-D chain takes \"compliance\" (the \
                     default) or \"tip-load\"",
                )),
            };
        let geometry = Geometry3d::Span {
            length: self.length,
            discretization: crate::beam::discretization(self)?,
            sweep: p(&self.sweep),
            dihedral: p(&self.dihedral),
            pretwist: p(&self.pretwist),
        };
        let beam = Beam3d::named("beam", &geometry, &stiffness, &inertia, calibration)
            .map_err(case_names)?;
        Ok(Chain3d::new(beam))
    }
}

/// The library's names of the 3-D section keys in the case file's: `EI_flap` is `EI`,
/// `rotary_inertia_flap` is `rotary_inertia`, the coupling terms are under `coupling`.
fn case_names(mut e: InputError) -> InputError {
    for (library, case) in [
        ("beam.section.EI_flap", "beam.section.EI"),
        (
            "beam.section.rotary_inertia_flap",
            "beam.section.rotary_inertia",
        ),
        (
            "beam.section.twist_flap",
            "beam.section.coupling.twist_flap",
        ),
        ("beam.section.twist_lag", "beam.section.coupling.twist_lag"),
        ("beam.section.lag_flap", "beam.section.coupling.lag_flap"),
    ] {
        if let Some(rest) = e.field.strip_prefix(library) {
            e.field = format!("{case}{rest}");
        }
    }
    e
}

impl Case {
    /// Whether the case is of the 3-D chain (`beam.model = "chain3d"`).
    pub fn is_chain3d(&self) -> bool {
        self.beam.is_chain3d()
    }

    /// The 3-D chain of `[beam]`.
    ///
    /// # Errors
    /// As [`BeamSpec::chain3d`].
    pub fn chain3d(&self) -> Result<Chain3d, CaseError> {
        self.beam.chain3d().map_err(|e| self.error(e))
    }

    /// The plan of `analysis` on the 3-D chain, validated.
    ///
    /// # Errors
    /// An analysis the 3-D chain cannot run yet (aeroelastic dynamics, gust families), the
    /// linearization and turbulence (plans of their own: [`Case::linearize_plan`]), the keys'
    /// errors, the plan's checks.
    pub fn chain3d_plan(&self, analysis: Analysis) -> Result<Chain3dPlan, CaseError> {
        self.checked_chain3d_plan(analysis)
            .map_err(|e| self.error(e))
    }

    fn checked_chain3d_plan(&self, analysis: Analysis) -> Result<Chain3dPlan, InputError> {
        let model = self.beam.chain3d()?;
        let not_yet = |what: &str| {
            Err(InputError::new(
                "beam.model",
                format!(
                    "the 3-D chain (\"chain3d\") has no {what} through the case file yet: run \
                     modes, static, dynamic (without [aero]), flutter or study"
                ),
            ))
        };
        let (analysis3d, prefix) = match analysis {
            Analysis::Modes => {
                let count = self
                    .modes
                    .count
                    .unwrap_or(DEFAULT_COUNT.min(model.n_dofs()));
                (Analysis3d::Modes { count }, "modes")
            }
            Analysis::Static if self.is_aeroelastic() => (
                Analysis3d::AeroStatic(self.aero_static3d(&model)?),
                "static",
            ),
            Analysis::Static => (Analysis3d::Static(self.static3d(&model)?), "static"),
            Analysis::Flutter => (Analysis3d::Flutter(self.flutter3d(&model)?), "flutter"),
            Analysis::Study => {
                let spec = self
                    .flutter
                    .as_ref()
                    .and_then(|f| f.study.as_ref())
                    .ok_or_else(|| {
                        InputError::new(
                            "flutter.study",
                            "missing: flexwing study needs [flutter.study] with parameter and \
                             levels",
                        )
                    })?;
                let parameter = match spec.parameter {
                    StudyParameterSpec::TipForce => StudyParameter::TipForce,
                    StudyParameterSpec::GravityFactor => StudyParameter::GravityFactor {
                        g: spec.g.unwrap_or(crate::loads::STANDARD_GRAVITY),
                    },
                    StudyParameterSpec::RootAngle => StudyParameter::RootAngle,
                };
                if spec.g.is_some() && spec.parameter != StudyParameterSpec::GravityFactor {
                    return Err(InputError::new(
                        "flutter.study.g",
                        "belongs to parameter = \"gravity-factor\"",
                    ));
                }
                let study = Study3d {
                    flutter: self.flutter3d(&model)?,
                    parameter,
                    levels: spec.levels.clone(),
                    divergence: spec.divergence.unwrap_or(true),
                };
                (Analysis3d::Study(study), "flutter")
            }
            Analysis::Dynamic if self.is_aeroelastic() => {
                return not_yet("aeroelastic dynamic run (gust or manoeuvre response)")
            }
            Analysis::Dynamic => (Analysis3d::Dynamic(self.dynamic3d(&model)?), "dynamic"),
            Analysis::Linearize | Analysis::Turbulence => {
                // One linear model for both chains: `Case::plan` gives `Plan::Linearize` or
                // `Plan::Turbulence` of the 3-D chain (`Case::linearize_plan`).
                return Err(InputError::new(
                    "beam.model",
                    "the 3-D chain's linear models are the planar chain's plans: \
                     Case::linearize_plan and Case::turbulence_plan take the 3-D chain",
                ));
            }
            Analysis::GustFamily => return not_yet("gust family"),
        };
        let plan = Chain3dPlan {
            model,
            analysis: analysis3d,
        };
        plan.validate(&fields(prefix))?;
        Ok(plan)
    }

    /// The loads of `[[loads]]` on the 3-D chain: the planar loads translated, with `fz`.
    fn spatial_loads(&self, model: &Chain3d) -> Result<Vec<SpatialLoad>, InputError> {
        let loads = crate::loads::loads_with_fz(&self.loads, model.beam().nodes())?;
        Ok(loads
            .into_iter()
            .map(|(load, fz)| {
                let mut l = SpatialLoad::from_planar(&load);
                match (&mut l, fz) {
                    (
                        SpatialLoad::PointForce {
                            force: SpatialVector::Dead(f),
                            ..
                        },
                        Some(Profile::Uniform(z)),
                    ) => f[2] = z,
                    (SpatialLoad::Distributed(SpatialDistributed::Dead(f)), Some(z)) => f[2] = z,
                    _ => {}
                }
                l
            })
            .collect())
    }

    /// `[static]`'s model choices: the 3-D chain solves its full chain only.
    fn refuse_static_reduced(&self) -> Result<(), InputError> {
        let s = &self.statics;
        match [
            ("static.full", !s.full),
            ("static.reduced", !s.reduced.is_empty()),
            ("static.reduced_modes", !s.reduced_modes.is_empty()),
        ]
        .iter()
        .find_map(|(k, given)| given.then_some(*k))
        {
            Some(key) => Err(InputError::new(
                key,
                "the 3-D chain's reduced models are not reachable from the case file yet: the \
                 full chain is solved",
            )),
            None => Ok(()),
        }
    }

    fn static3d(&self, model: &Chain3d) -> Result<Static3d, InputError> {
        let s = &self.statics;
        self.refuse_static_reduced()?;
        Ok(Static3d {
            loads: self.spatial_loads(model)?,
            options: self.static_options(),
            sweep: s.sweep.as_ref().map(|spec| self.sweep(spec)).transpose()?,
            modes: s.modes,
            load_names: self.load_names(),
        })
    }

    fn dynamic3d(&self, model: &Chain3d) -> Result<Dynamic3d, InputError> {
        let p = self.dynamic_parts(model.n_dofs())?;
        let mut plan = Dynamic3d::new(self.spatial_loads(model)?, p.end_time, Vec::new());
        crate::dynamic::set_dynamic_parts!(plan, p);
        Ok(plan)
    }

    /// The planar loads of an aeroelastic run of the 3-D chain (in the x-y plane: no `fz`; no
    /// gravity load, which is `aero.flight.gravity`).
    pub(crate) fn aero_loads3d(&self, model: &Chain3d) -> Result<Vec<Load>, InputError> {
        self.refuse_gravity_loads()?;
        if let Some(i) = self.loads.iter().position(|l| l.fz.is_some()) {
            return Err(InputError::new(
                format!("loads[{i}].fz"),
                "the aeroelastic runs of the 3-D chain take the loads in the x-y plane only",
            ));
        }
        Ok(
            crate::loads::loads_with_fz(&self.loads, model.beam().nodes())?
                .into_iter()
                .map(|(l, _)| l)
                .collect(),
        )
    }

    fn aero_static3d(&self, model: &Chain3d) -> Result<AeroStatic3d, InputError> {
        let (spec, aero) = self.aero_of()?;
        self.refuse_static_reduced()?;
        let (flight, sweep) = self.aero_static_flight(spec)?;
        Ok(AeroStatic3d {
            aero,
            flight,
            sweep,
            loads: self.aero_loads3d(model)?,
            options: self.static_options(),
            divergence_tolerance: DIVERGENCE_TOLERANCE,
        })
    }

    fn flutter3d(&self, model: &Chain3d) -> Result<Flutter3d, InputError> {
        let (spec, aero) = self.aero_of()?;
        crate::aero::refuse_histories(spec, crate::aero::FLUTTER_RUN)?;
        let speeds =
            match &spec.sweep {
                Some(sw) => speed_sweep(sw, "aero.sweep")?.speeds,
                None => return Err(InputError::new(
                    "aero.sweep",
                    "missing: flexwing flutter sweeps the free-stream speed; give [aero.sweep] \
                     with speeds = [...] or from, to and steps",
                )),
            };
        let loads = self.aero_loads3d(model)?;
        let f = self.flutter.clone().unwrap_or_default();
        if let Some(key) = [
            ("flutter.full", !f.full),
            ("flutter.reduced", !f.reduced.is_empty()),
            ("flutter.reduced_modes", !f.reduced_modes.is_empty()),
        ]
        .iter()
        .find_map(|(k, given)| given.then_some(*k))
        {
            return Err(InputError::new(
                key,
                "the 3-D chain's reduced models are not reachable from the case file yet: the \
                 full chain is analysed",
            ));
        }
        Ok(Flutter3d {
            aero,
            flight: condition(&spec.flight, 0.0),
            sweep: Some(SpeedSweep { speeds }),
            loads,
            modes: f.modes,
            tolerance: f.tolerance.unwrap_or(1e-6),
            pk: f.pk,
            static_options: self.static_options(),
        })
    }
}
