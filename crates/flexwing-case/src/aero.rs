//! `[aero]`, `[aero.flight]`, `[aero.sweep]` and `[flutter]` into the plans of
//! [`flexwing::analysis::aero`]: the static aeroelastic run, the flutter analysis and the
//! aeroelastic response. The library checks every value under the case file's names
//! ([`Fields`]); this module checks what it cannot see: which keys go together (a Peters model
//! and its `states`, a change of speed and its time history, a gust shape and its length, how the
//! speeds are spelled, a gravity load beside `aero.flight.gravity`, the structural keys that have
//! no meaning with aerodynamics).

use flexwing::analysis::aero::flutter::FlutterPlan;
use flexwing::analysis::aero::response::{AeroDynamicPlan, AeroStart};
use flexwing::analysis::aero::statics::AeroStaticPlan;
use flexwing::analysis::aero::{Aero, Fields, SpeedSweep};
use flexwing::beam::Profile;
use flexwing::model::aero::{AeroSection, Aerodynamics, ControlSurface, FlightCondition};
use flexwing::model::{FullModel, Load};
use flexwing::solve::aeroelastic::{FlightHistory, Gust, GustPenetration, GustShape};
use flexwing::solve::{StaticOptions, TimeFunction};
use flexwing::InputError;

use super::dynamic::time_function;
use super::spec::{Case, InitialKindSpec, LoadKindSpec, TimeSpec};
use super::spec_aero::{
    AeroModelSpec, AeroSpec, FlightSpec, GustPenetrationSpec, GustShapeSpec, SpeedSweepSpec,
};
use super::statics::evenly_spaced;
use crate::CaseError;

/// The case file's names of an aeroelastic plan's parts, the analysis being `analysis`.
pub(crate) fn fields(analysis: &str) -> Fields<'_> {
    Fields {
        loads: "loads",
        aero: "aero",
        statics: "static",
        analysis,
    }
}

impl Case {
    /// Whether the case has `[aero]`: its `static` and `dynamic` runs are aeroelastic.
    pub fn is_aeroelastic(&self) -> bool {
        self.aero.is_some()
    }

    /// An error for the structural plan of an aeroelastic case: `method` builds its plan.
    pub(crate) fn not_aeroelastic(&self, method: &str) -> Result<(), InputError> {
        match self.aero {
            None => Ok(()),
            Some(_) => Err(InputError::new(
                "aero",
                format!(
                    "the case is aeroelastic: its plan is built by Case::{method}, which \
                     takes [aero] into account"
                ),
            )),
        }
    }

    /// The static aeroelastic analysis of `[aero]` (at `aero.flight.speed`, or along
    /// `[aero.sweep]`), `[[loads]]` and `[static]`, validated.
    ///
    /// # Errors
    /// No `[aero]`, keys that do not go together, a load sweep or loaded modes (structural
    /// only), and every error of [`AeroStaticPlan::validate`], named as in the case file.
    pub fn aero_static_plan(&self) -> Result<AeroStaticPlan, CaseError> {
        self.checked_aero_static_plan().map_err(|e| self.error(e))
    }

    fn checked_aero_static_plan(&self) -> Result<AeroStaticPlan, InputError> {
        let (spec, model, aero) = self.aero_parts()?;
        let s = &self.statics;
        let (flight, sweep) = self.aero_static_flight(spec)?;
        let loads = self.aero_loads(&model)?;
        let mut plan = AeroStaticPlan::new(model, aero, flight);
        plan.sweep = sweep;
        plan.loads = loads;
        plan.full = s.full;
        plan.reduced.clone_from(&s.reduced);
        plan.reduced_modes.clone_from(&s.reduced_modes);
        plan.options = self.static_options();
        plan.validate(&fields("static"))?;
        Ok(plan)
    }

    /// The flight and the speed sweep of a static aeroelastic run (the planar chain's and the 3-D
    /// chain's): `[aero.sweep]`, or the speed of `[aero.flight]`; a load sweep and loaded modes
    /// refused.
    pub(crate) fn aero_static_flight(
        &self,
        spec: &AeroSpec,
    ) -> Result<(FlightCondition, Option<SpeedSweep>), InputError> {
        refuse_histories(spec, STATIC_RUN)?;
        let s = &self.statics;
        if s.sweep.is_some() {
            return Err(InputError::new(
                "static.sweep",
                "a load sweep is not available with [aero]: sweep the free-stream speed with \
                 [aero.sweep]",
            ));
        }
        if s.modes.is_some() {
            return Err(InputError::new(
                "static.modes",
                "loaded modes are not available with [aero] (the aerodynamic load is not \
                 conservative); flexwing flutter gives the aeroelastic modes along the speeds",
            ));
        }
        let sweep = spec
            .sweep
            .as_ref()
            .map(|sw| speed_sweep(sw, "aero.sweep"))
            .transpose()?;
        let speed = match (sweep.is_some(), spec.flight.speed) {
            (_, Some(u)) => u,
            (true, None) => 0.0,
            (false, None) => {
                return Err(InputError::new(
                    "aero.flight.speed",
                    "missing: the static aeroelastic equilibrium needs the free-stream speed \
                     (m/s), or the speeds of [aero.sweep]",
                ))
            }
        };
        Ok((condition(&spec.flight, speed), sweep))
    }

    /// The flutter analysis of `[aero]` (speeds of `[aero.sweep]`), `[[loads]]`, `[flutter]`
    /// (defaults without it) and the solver options of `[static]`, validated.
    ///
    /// # Errors
    /// No `[aero]` or `[aero.sweep]`, keys that do not go together, and every error of
    /// [`FlutterPlan::validate`], named as in the case file.
    pub fn flutter_plan(&self) -> Result<FlutterPlan, CaseError> {
        self.checked_flutter_plan().map_err(|e| self.error(e))
    }

    fn checked_flutter_plan(&self) -> Result<FlutterPlan, InputError> {
        let (spec, model, aero) = self.aero_parts()?;
        refuse_histories(spec, FLUTTER_RUN)?;
        let speeds =
            match &spec.sweep {
                Some(sw) => speed_sweep(sw, "aero.sweep")?.speeds,
                None => return Err(InputError::new(
                    "aero.sweep",
                    "missing: flexwing flutter sweeps the free-stream speed; give [aero.sweep] \
                     with speeds = [...] or from, to and steps",
                )),
            };
        let loads = self.aero_loads(&model)?;
        let f = self.flutter.clone().unwrap_or_default();
        let mut plan = FlutterPlan::new(model, aero, speeds);
        plan.flight = condition(&spec.flight, 0.0);
        plan.loads = loads;
        plan.full = f.full;
        plan.reduced = f.reduced;
        plan.reduced_modes = f.reduced_modes;
        plan.modes = f.modes;
        plan.tolerance = f.tolerance.unwrap_or(plan.tolerance);
        plan.pk = f.pk;
        plan.static_options = self.static_options();
        plan.validate(&fields("flutter"))?;
        Ok(plan)
    }

    /// The aeroelastic response of `[aero]` (flight, changes, gust), `[[loads]]` and
    /// `[dynamic]`, validated.
    ///
    /// # Errors
    /// No `[aero]` or `[dynamic]`, keys that do not go together, a structural initial state,
    /// and every error of [`AeroDynamicPlan::validate`], named as in the case file.
    pub fn aero_dynamic_plan(&self) -> Result<AeroDynamicPlan, CaseError> {
        self.checked_aero_dynamic_plan().map_err(|e| self.error(e))
    }

    pub(crate) fn checked_aero_dynamic_plan(&self) -> Result<AeroDynamicPlan, InputError> {
        let (spec, model, aero) = self.aero_parts()?;
        let initial = self.dynamic.as_ref().and_then(|d| d.initial.as_ref());
        let start = match initial.map(|i| i.kind) {
            None => AeroStart::Equilibrium,
            Some(InitialKindSpec::Rest) => AeroStart::Rest,
            Some(_) => {
                return Err(InputError::new(
                    "dynamic.initial.type",
                    "with [aero] a run starts from the static aeroelastic equilibrium of the \
                     initial flight (without [dynamic.initial]) or undeformed at rest \
                     (type = \"rest\")",
                ))
            }
        };
        self.aero_loads(&model)?;
        let structure = self.checked_dynamic_plan()?;
        let speed = spec.flight.speed.ok_or_else(|| {
            InputError::new(
                "aero.flight.speed",
                "missing: an aeroelastic response needs the initial free-stream speed (m/s)",
            )
        })?;
        let flight = history(&spec.flight, &spec.surfaces, speed)?;
        let mut plan = AeroDynamicPlan::new(structure, aero, flight);
        plan.start = start;
        plan.static_options = self.static_options();
        plan.validate(&fields("dynamic"))?;
        Ok(plan)
    }

    /// `[aero]`, the full model and the library's aerodynamics of the case.
    pub(crate) fn aero_parts(&self) -> Result<(&AeroSpec, FullModel, Aero), InputError> {
        let (spec, aero) = self.aero_of()?;
        let model = FullModel::new(self.to_beam()?);
        Ok((spec, model, aero))
    }

    /// `[aero]` and the library's aerodynamics of the case (for either structural model).
    pub(crate) fn aero_of(&self) -> Result<(&AeroSpec, Aero), InputError> {
        let spec = self.aero.as_ref().ok_or_else(|| {
            InputError::new(
                "aero",
                "missing: an aeroelastic run needs an [aero] table (at least chord, \
                 elastic_axis, density and aerodynamics)",
            )
        })?;
        let section = AeroSection {
            chord: spec.chord.0.clone(),
            elastic_axis: spec.elastic_axis.0.clone(),
            lift_slope: spec
                .lift_slope
                .as_ref()
                .map_or(Profile::Uniform(2.0 * std::f64::consts::PI), |p| {
                    p.0.clone()
                }),
            zero_lift_angle: or_zero(spec.zero_lift_angle.as_ref()),
            cm0: or_zero(spec.cm0.as_ref()),
            cd0: or_zero(spec.cd0.as_ref()),
            surfaces: spec.surfaces.iter().map(surface).collect(),
        };
        let a = spec.aerodynamics;
        let aerodynamics = match (a.model, a.states) {
            (AeroModelSpec::Peters, Some(states)) => Aerodynamics::Peters { states },
            (AeroModelSpec::Peters, None) => {
                return Err(InputError::new(
                    "aero.aerodynamics.states",
                    "missing: Peters' inflow needs its number of states per strip (1 to 15; \
                     4 to 8 are usual)",
                ))
            }
            (_, Some(_)) => {
                return Err(InputError::new(
                    "aero.aerodynamics.states",
                    "is the state count of Peters' inflow; it needs model = \"peters\" \
                     (Wagner's function has 2 states, the steady and quasi-steady models none)",
                ))
            }
            (AeroModelSpec::Steady, None) => Aerodynamics::Steady,
            (AeroModelSpec::QuasiSteady, None) => Aerodynamics::QuasiSteady,
            (AeroModelSpec::Wagner, None) => Aerodynamics::Wagner,
        };
        let aero = Aero {
            section,
            density: spec.density,
            aerodynamics,
        };
        Ok((spec, aero))
    }

    /// With `[aero]`, gravity belongs to the flight (it follows the root angle), not to
    /// `[[loads]]`: the first gravity load is an error naming its `type`.
    pub(crate) fn refuse_gravity_loads(&self) -> Result<(), InputError> {
        if let Some(i) = self
            .loads
            .iter()
            .position(|l| l.kind == LoadKindSpec::Gravity)
        {
            return Err(InputError::new(
                format!("loads[{i}].type"),
                "with [aero], give gravity as aero.flight.gravity (m/s²): it acts along the \
                 ground's vertical, which the root angle tilts in the wing's frame",
            ));
        }
        Ok(())
    }

    /// The loads of an aeroelastic run: gravity belongs to the flight (it follows the root
    /// angle), not to `[[loads]]`.
    pub(crate) fn aero_loads(&self, model: &FullModel) -> Result<Vec<Load>, InputError> {
        self.refuse_gravity_loads()?;
        self.to_loads(model.beam())
    }

    /// The static solver's options of `[static]`.
    pub(crate) fn static_options(&self) -> StaticOptions {
        let s = &self.statics;
        let mut o = StaticOptions::default();
        o.tolerance = s.tolerance.unwrap_or(o.tolerance);
        o.max_iterations = s.max_iterations.unwrap_or(o.max_iterations);
        o.min_step = s.min_step.unwrap_or(o.min_step);
        o.line_search = s.line_search.unwrap_or(o.line_search);
        o
    }
}

/// A control surface of `[[aero.surfaces]]`.
fn surface(s: &super::spec_aero::SurfaceSpec) -> ControlSurface {
    ControlSurface {
        name: s.name.clone(),
        from: s.from,
        to: s.to,
        hinge: s.hinge.0.clone(),
        deflection: s.deflection.unwrap_or(0.0),
    }
}

fn or_zero(p: Option<&crate::Property>) -> Profile {
    p.map_or(Profile::Uniform(0.0), |p| p.0.clone())
}

/// The first time history of a dynamic run in `spec` (a surface's `deflection_change` or
/// `deflection_function`, the flight's `speed_change`, `root_angle_change` or their functions),
/// as an error naming its key: `run` ("flexwing static", …) solves the equilibria of the flight
/// at its start values and would not apply it. A run about an equilibrium with a change of the
/// operating point in the file is most likely a mistake (which point was meant: the start, the
/// end?), so it is refused rather than ignored (docs/case-file.md). The gust is a disturbance of
/// a dynamic run, not a change of the operating point: it is left to the dynamic runs.
pub(crate) fn refuse_histories(spec: &AeroSpec, run: &str) -> Result<(), InputError> {
    let surface = spec.surfaces.iter().enumerate().find_map(|(k, s)| {
        let key = match (
            s.deflection_change.is_some(),
            s.deflection_function.is_some(),
        ) {
            (true, _) => "deflection_change",
            (false, true) => "deflection_function",
            (false, false) => return None,
        };
        Some(InputError::new(
            format!("aero.surfaces[{k}].{key}"),
            format!(
                "is the deflection's time history in a dynamic run (flexwing dynamic, gust, the \
                 stepper, the FMU); {run} holds the surface {:?} at its deflection: set \
                 deflection, or remove deflection_change and deflection_function{}",
                s.name,
                if run == LINEAR_RUN {
                    format!(" (the input delta[{}] takes a history)", s.name)
                } else {
                    String::new()
                }
            ),
        ))
    });
    if let Some(e) = surface {
        return Err(e);
    }
    let f = &spec.flight;
    let flight = [
        (
            "speed",
            f.speed_change.is_some(),
            f.speed_function.is_some(),
        ),
        (
            "root_angle",
            f.root_angle_change.is_some(),
            f.root_angle_function.is_some(),
        ),
    ];
    match flight.iter().find(|(_, c, f)| *c || *f) {
        Some((name, change, _)) => {
            let key = if *change { "change" } else { "function" };
            Err(InputError::new(
                format!("aero.flight.{name}_{key}"),
                format!(
                    "is the {}'s time history in a dynamic run (flexwing dynamic, gust, the \
                     stepper, the FMU); {run} holds the flight at its start: remove \
                     {name}_change and {name}_function",
                    name.replace('_', " ")
                ),
            ))
        }
        None => Ok(()),
    }
}

/// The static equilibria, as [`refuse_histories`] names them.
pub(crate) const STATIC_RUN: &str = "flexwing static";
/// The flutter analysis' equilibria.
pub(crate) const FLUTTER_RUN: &str = "flexwing flutter";
/// The linear model's equilibrium (and the turbulence response's, through it).
pub(crate) const LINEAR_RUN: &str = "the linear model (linearize, turbulence)";

/// The flight condition of `[aero.flight]` at speed `speed`.
pub(crate) fn condition(f: &FlightSpec, speed: f64) -> FlightCondition {
    FlightCondition {
        speed,
        root_angle: f.root_angle.unwrap_or(0.0),
        gravity: f.gravity,
    }
}

/// The flight history of `[aero.flight]`: the initial condition, the changes of speed and root
/// angle with their time histories, the gust; and the changes of the `[[aero.surfaces]]`'
/// deflections.
fn history(
    f: &FlightSpec,
    surfaces: &[super::spec_aero::SurfaceSpec],
    speed: f64,
) -> Result<FlightHistory, InputError> {
    let mut deflection_changes = surfaces
        .iter()
        .enumerate()
        .map(|(k, s)| {
            change(
                &format!("aero.surfaces[{k}]"),
                ("deflection_change", s.deflection_change),
                ("deflection_function", s.deflection_function.as_ref()),
                "rad",
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    while deflection_changes.last() == Some(&None) {
        deflection_changes.pop();
    }
    Ok(FlightHistory {
        deflection_changes,
        initial: condition(f, speed),
        speed_change: change(
            "aero.flight",
            ("speed_change", f.speed_change),
            ("speed_function", f.speed_function.as_ref()),
            "m/s",
        )?,
        root_angle_change: change(
            "aero.flight",
            ("root_angle_change", f.root_angle_change),
            ("root_angle_function", f.root_angle_function.as_ref()),
            "rad",
        )?,
        gust: f.gust.as_ref().map(gust).transpose()?,
    })
}

/// A change and its time history under the table `table`: both or neither.
fn change(
    table: &str,
    (key, value): (&str, Option<f64>),
    (function_key, function): (&str, Option<&TimeSpec>),
    unit: &str,
) -> Result<Option<(f64, TimeFunction)>, InputError> {
    let field = |k: &str| format!("{table}.{k}");
    match (value, function) {
        (None, None) => Ok(None),
        (Some(v), Some(spec)) => Ok(Some((v, time_function(&field(function_key), spec)?))),
        (Some(_), None) => Err(InputError::new(
            field(function_key),
            format!(
                "missing: {key} needs its time history, e.g. {function_key} = \
                 {{ type = \"ramp\", start = 0.0, end = 1.0 }}"
            ),
        )),
        (None, Some(_)) => Err(InputError::new(
            field(key),
            format!("missing: {function_key} scales the change {key} ({unit}), which is not given"),
        )),
    }
}

fn gust(g: &crate::GustSpec) -> Result<Gust, InputError> {
    let shape = match (g.shape, g.length) {
        (GustShapeSpec::SharpEdged, None) => GustShape::SharpEdged,
        (GustShapeSpec::SharpEdged, Some(_)) => {
            return Err(InputError::new(
                "aero.flight.gust.length",
                "is the length of a 1−cos gust; a sharp-edged gust has none",
            ))
        }
        (GustShapeSpec::OneMinusCosine, Some(length)) => GustShape::OneMinusCosine { length },
        (GustShapeSpec::OneMinusCosine, None) => {
            return Err(InputError::new(
                "aero.flight.gust.length",
                "missing: a 1−cos gust needs its length (m)",
            ))
        }
    };
    Ok(Gust {
        shape,
        amplitude: g.amplitude,
        start: g.start.unwrap_or(0.0),
        spanwise: g
            .spanwise
            .as_ref()
            .map_or(Profile::Uniform(1.0), |p| p.0.clone()),
        penetration: match g.penetration {
            None | Some(GustPenetrationSpec::Uniform) => GustPenetration::Uniform,
            Some(GustPenetrationSpec::Kussner) => GustPenetration::Kussner,
        },
    })
}

/// The speeds of `[aero.sweep]`: listed, or evenly spaced.
pub(crate) fn speed_sweep(spec: &SpeedSweepSpec, prefix: &str) -> Result<SpeedSweep, InputError> {
    let speeds = match listed_or_spaced(
        prefix,
        "speeds",
        &spec.speeds,
        (spec.from, spec.to, spec.steps),
    )? {
        Spaced::Listed(v) => v,
        Spaced::Range { from, to, steps } => evenly_spaced(prefix, from, to, steps)?,
    };
    Ok(SpeedSweep { speeds })
}

/// Values a table lists (`{key} = [...]`) or spaces evenly (`from`, `to`, `steps`).
pub(crate) enum Spaced {
    Listed(Vec<f64>),
    Range { from: f64, to: f64, steps: usize },
}

/// How the values of table `prefix` are spelled: `{key} = [...]` or `from`, `to` and `steps`
/// together, not both; errors name `{prefix}.{key}`, `{prefix}.from`, ….
pub(crate) fn listed_or_spaced(
    prefix: &str,
    key: &str,
    listed: &Option<Vec<f64>>,
    (from, to, steps): (Option<f64>, Option<f64>, Option<usize>),
) -> Result<Spaced, InputError> {
    match (listed, from, to, steps) {
        (Some(v), None, None, None) => Ok(Spaced::Listed(v.clone())),
        (None, Some(from), Some(to), Some(steps)) => Ok(Spaced::Range { from, to, steps }),
        (Some(_), ..) => Err(InputError::new(
            prefix,
            format!("give either {key} or from/to/steps, not both"),
        )),
        (None, None, None, None) => Err(InputError::new(
            format!("{prefix}.{key}"),
            format!("missing: give {key} = [...] or from, to and steps"),
        )),
        (None, from, to, _) => {
            let missing = if from.is_none() {
                "from"
            } else if to.is_none() {
                "to"
            } else {
                "steps"
            };
            Err(InputError::new(
                format!("{prefix}.{missing}"),
                "missing: from, to and steps go together",
            ))
        }
    }
}

#[cfg(test)]
mod tests;
