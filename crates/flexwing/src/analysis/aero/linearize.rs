//! Linear state-space models about the static aeroelastic equilibrium, for the full model and
//! reduced models on its wet modes ([`crate::solve::aeroelastic::linearize`], docs/control.md):
//! `A, B, C, D` with named, unit-carrying states, inputs and outputs, the poles of `A`, and a
//! note when the equilibrium is dynamically unstable (past the flutter speed).
//!
//! A reduced model keeps its modal amplitudes, their rates and every strip's lag states: its
//! order is `2 r + strips × lag states`, its poles the structural ones of the flutter analysis'
//! reduced model.
//!
//! The structure is the paper's planar chain or the 3-D chain ([`LinearStructure`], the case
//! file's `beam.model`): one plan, one outcome and one set of signals for both, so every front
//! end renders the 3-D chain's linear model as the planar one's (the 3-D chain adds the outputs
//! `tip_z`, `z[k]`, `root_lag_moment`; its reduced models are not linearized yet).

use std::time::Instant;

use nalgebra::Complex;

use super::{build, models, Aero, Built, Fields};
use crate::analysis::{ModelKind, Note, Progress, Status, Stop};
use crate::error::{Error, InputError};
use crate::model::aero::{AeroStructure, Aeroelastic, FlightCondition};
use crate::model::{Chain3d, FullModel, Load};
use crate::solve::aeroelastic::{
    linearize as solve_linearize, poles as poles_of, Input, LinearizeOptions, Output, StateBasis,
    StateSpace,
};
use crate::solve::{Damping, StaticOptions};

/// The inputs when the plan names none.
pub const DEFAULT_INPUTS: [&str; 1] = ["gust"];
/// The outputs when the plan names none.
pub const DEFAULT_OUTPUTS: [&str; 3] = ["tip_y", "root_bending_moment", "lift"];

/// The structure of a linearization (in vacuo): the paper's planar chain or the 3-D chain.
#[derive(Debug, Clone)]
#[allow(clippy::large_enum_variant)] // one per plan
pub enum LinearStructure {
    /// The planar full model (its reduced models: [`LinearizePlan::reduced`]).
    Planar(FullModel),
    /// The 3-D chain (docs/chain3d-model.md), its full chain only.
    Chain3d(Chain3d),
}

impl From<FullModel> for LinearStructure {
    fn from(model: FullModel) -> Self {
        LinearStructure::Planar(model)
    }
}

impl From<Chain3d> for LinearStructure {
    fn from(model: Chain3d) -> Self {
        LinearStructure::Chain3d(model)
    }
}

impl LinearStructure {
    /// The planar full model, or `None` for the 3-D chain.
    pub fn planar(&self) -> Option<&FullModel> {
        match self {
            LinearStructure::Planar(m) => Some(m),
            LinearStructure::Chain3d(_) => None,
        }
    }
    /// Number of elements (strips).
    pub fn n_elements(&self) -> usize {
        match self {
            LinearStructure::Planar(m) => m.n_elements(),
            LinearStructure::Chain3d(m) => m.n_elements(),
        }
    }
    /// Number of coordinates.
    pub fn n_dofs(&self) -> usize {
        match self {
            LinearStructure::Planar(m) => m.n_dofs(),
            LinearStructure::Chain3d(m) => m.n_dofs(),
        }
    }
    /// Whether the structure twists (the 3-D chain always does).
    pub fn has_torsion(&self) -> bool {
        match self {
            LinearStructure::Planar(m) => m.has_torsion(),
            LinearStructure::Chain3d(_) => true,
        }
    }
    /// Length of the beam (m): the planar span, the 3-D reference axis' arc length.
    pub fn length(&self) -> f64 {
        match self {
            LinearStructure::Planar(m) => m.beam().length(),
            LinearStructure::Chain3d(m) => m.beam().length(),
        }
    }
}

/// A linearization. Build it with [`LinearizePlan::new`], set the fields, check it with
/// [`LinearizePlan::validate`].
#[derive(Debug, Clone)]
pub struct LinearizePlan {
    /// The structure (in vacuo).
    pub model: LinearStructure,
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// Speed (positive), root angle and gravity of the equilibrium (`{aero}.flight`).
    pub flight: FlightCondition,
    /// Other loads, at full value.
    pub loads: Vec<Load>,
    /// Linearize the full model. Default `true`.
    pub full: bool,
    /// Reduced models on the first `r` wet modes, one per entry.
    pub reduced: Vec<usize>,
    /// Reduced models on listed wet modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// The inputs by name (`gust`, `force[16]`, …; `solve::aeroelastic::INPUT_NAMES`).
    pub inputs: Vec<String>,
    /// The outputs by name (`tip_y`, `lift`, …; `solve::aeroelastic::OUTPUT_NAMES`).
    pub outputs: Vec<String>,
    /// Velocities or momenta.
    pub states: StateBasis,
    /// Options of the static solver for the equilibrium.
    pub static_options: StaticOptions,
}

impl LinearizePlan {
    /// The full model (planar or 3-D) in `aero` at `flight`, the default inputs and outputs,
    /// velocities.
    pub fn new(model: impl Into<LinearStructure>, aero: Aero, flight: FlightCondition) -> Self {
        Self {
            model: model.into(),
            aero,
            flight,
            loads: Vec::new(),
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            inputs: DEFAULT_INPUTS.iter().map(|s| s.to_string()).collect(),
            outputs: DEFAULT_OUTPUTS.iter().map(|s| s.to_string()).collect(),
            states: StateBasis::Velocities,
            static_options: StaticOptions::default(),
        }
    }

    /// The inputs and outputs, parsed; errors name `{analysis}.inputs[i]`, `{analysis}.outputs[i]`.
    ///
    /// # Errors
    /// An unknown name, an index outside the chain, a torsion signal of a bending-only beam, a
    /// 3-D output of the planar chain, the root shear of the 3-D chain, an empty list, a name
    /// given twice.
    pub fn signals(&self, fields: &Fields) -> Result<(Vec<Input>, Vec<Output>), InputError> {
        let n = self.model.n_elements();
        let torsion = self.model.has_torsion();
        fn parse<T: PartialEq>(
            names: &[String],
            key: String,
            what: &str,
            one: impl Fn(&str, &str) -> Result<T, InputError>,
        ) -> Result<Vec<T>, InputError> {
            if names.is_empty() {
                return Err(InputError::new(
                    key,
                    format!("needs at least one of the {what}"),
                ));
            }
            let mut out = Vec::with_capacity(names.len());
            for (i, name) in names.iter().enumerate() {
                let field = format!("{key}[{i}]");
                if let Some(j) = names[..i].iter().position(|m| m == name) {
                    return Err(InputError::new(
                        field,
                        format!("{name:?} is already {key}[{j}]"),
                    ));
                }
                out.push(one(name, &field)?);
            }
            Ok(out)
        }
        let surfaces = &self.aero.section.surfaces;
        let inputs = parse(&self.inputs, fields.analysis("inputs"), "inputs", |s, f| {
            Input::parse(s, n, torsion, surfaces, f)
        })?;
        let spatial = matches!(self.model, LinearStructure::Chain3d(_));
        let outputs = parse(
            &self.outputs,
            fields.analysis("outputs"),
            "outputs",
            |s, f| {
                let output = Output::parse(s, n, torsion, surfaces, f)?;
                if spatial && output == Output::RootShear {
                    return Err(InputError::new(
                        f,
                        "root_shear is not available on the 3-D chain yet (the vertical \
                         momentum of its mass centres and of the fluid is not written): use \
                         lift and the root moments",
                    ));
                }
                match output.planar_error(f) {
                    Some(e) if !spatial => Err(e),
                    _ => Ok(output),
                }
            },
        )?;
        Ok((inputs, outputs))
    }

    /// Check the plan under the caller's names.
    ///
    /// # Errors
    /// Invalid section data, air or aerodynamic model, flight condition (a speed that is not
    /// positive), loads, options, inputs or outputs ([`LinearizePlan::signals`]); reduced
    /// models on modes the model does not have; nothing to run.
    pub fn validate(&self, fields: &Fields) -> Result<(), InputError> {
        let flight = fields.flight();
        self.flight.validate(&flight)?;
        if !(self.flight.speed > 0.0) {
            return Err(InputError::new(
                crate::field(&flight, "speed"),
                "missing or not positive: a linear model is taken about the static \
                 equilibrium in flight at this speed (m/s)",
            ));
        }
        let dofs = match &self.model {
            LinearStructure::Planar(model) => {
                self.aero.wing(model, fields.aero)?;
                model.apply(&self.loads, fields.loads)?;
                model.n_dofs()
            }
            LinearStructure::Chain3d(model) => {
                self.spatial_wing(model, fields.aero)?;
                model.apply_planar(&self.loads, fields.loads)?;
                let reduced = [
                    ("reduced", !self.reduced.is_empty()),
                    ("reduced_modes", !self.reduced_modes.is_empty()),
                ];
                if let Some((key, _)) = reduced.iter().find(|(_, given)| *given) {
                    return Err(InputError::new(
                        fields.analysis(key),
                        "the 3-D chain's reduced models are not linearized yet: the full chain \
                         is",
                    ));
                }
                model.n_dofs()
            }
        };
        self.static_options.validate(fields.statics)?;
        self.signals(fields)?;
        models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            dofs,
            fields.analysis,
        )?;
        Ok(())
    }

    /// The aeroelastic 3-D chain of `model`; errors name `{prefix}.chord`, ….
    fn spatial_wing(
        &self,
        model: &Chain3d,
        prefix: &str,
    ) -> Result<Aeroelastic<Chain3d>, InputError> {
        Aeroelastic::spatial(
            model,
            &self.aero.section,
            self.aero.density,
            self.aero.aerodynamics,
            prefix,
        )
    }

    /// The models linearized, in order: full (if asked), `reduced`, `reduced_modes`.
    ///
    /// # Errors
    /// As [`LinearizePlan::validate`] for the models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        models(
            self.full,
            &self.reduced,
            &self.reduced_modes,
            self.model.n_dofs(),
            "",
        )
    }
}

/// The linear model of one model.
#[derive(Debug, Clone)]
pub struct LinearizeRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of structural coordinates.
    pub dofs: usize,
    /// Number of aerodynamic (lag) states.
    pub aero_states: usize,
    /// The model, if the equilibrium was found.
    pub model: Option<StateSpace>,
    /// The eigenvalues of `A` (1/s), by decreasing real part; empty if they did not converge
    /// ([`crate::solve::aeroelastic::poles`]).
    pub poles: Vec<Complex<f64>>,
    /// Wall time of the linearization (s), the poles apart.
    pub wall_time_s: f64,
    /// Complete, or stopped: no stable static equilibrium.
    pub status: Status,
    /// Unstable poles (past the flutter speed).
    pub notes: Vec<Note>,
}

/// What a linearization produced.
#[derive(Debug, Clone)]
pub struct LinearizeOutcome {
    /// One run per model, in the order of [`LinearizePlan::models`].
    pub runs: Vec<LinearizeRun>,
}

impl LinearizeOutcome {
    /// Whether every model was linearized.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
    }
}

/// Linearize every model of `plan`.
///
/// # Errors
/// An invalid plan (fields named relative to the plan, [`Fields::RELATIVE`]), or the wet modes
/// of a reduced model not found. A model without a stable static equilibrium is in the outcome
/// with its [`Status`] ([`Stop::LinearizationEquilibrium`]).
pub fn run(plan: &LinearizePlan, progress: &mut dyn Progress) -> Result<LinearizeOutcome, Error> {
    let fields = Fields::RELATIVE;
    plan.validate(&fields)?;
    let (inputs, outputs) = plan.signals(&fields)?;
    let kinds = plan.models()?;
    let mut runs = Vec::with_capacity(kinds.len());
    let wing = match &plan.model {
        LinearStructure::Planar(model) => Ok(plan.aero.wing(model, fields.aero)?),
        LinearStructure::Chain3d(model) => Err(plan.spatial_wing(model, fields.aero)?),
    };
    for (k, kind) in kinds.iter().enumerate() {
        progress.start(k, kinds.len(), &kind.label());
        let options = LinearizeOptions {
            flight: plan.flight,
            loads: plan.loads.clone(),
            damping: Damping::None,
            static_options: plan.static_options.clone(),
            inputs: inputs.clone(),
            outputs: outputs.clone(),
            basis: plan.states,
            mode_numbers: kind.modes(),
        };
        let run = match &wing {
            Ok(full) => match build(full, kind)? {
                Built::Full => linearize_model(kind, full, &options, &fields),
                Built::Reduced(rom) => linearize_model(kind, rom.as_ref(), &options, &fields),
            },
            // The 3-D chain: its full chain only (validated).
            Err(chain) => linearize_model(kind, chain, &options, &fields),
        }?;
        progress.finish();
        runs.push(run);
    }
    Ok(LinearizeOutcome { runs })
}

fn linearize_model<M: AeroStructure>(
    kind: &ModelKind,
    aero: &Aeroelastic<M>,
    options: &LinearizeOptions,
    fields: &Fields,
) -> Result<LinearizeRun, Error> {
    let start = Instant::now();
    let result = solve_linearize(aero, options, "");
    let wall_time_s = start.elapsed().as_secs_f64();
    let mut run = LinearizeRun {
        kind: kind.clone(),
        dofs: aero.structure().n_dofs(),
        aero_states: aero.n_aero_states(),
        model: None,
        poles: Vec::new(),
        wall_time_s,
        status: Status::Complete,
        notes: Vec::new(),
    };
    match result {
        Ok(ss) => {
            let mut poles = poles_of(&ss.a).unwrap_or_default();
            poles.sort_by(|a, b| b.re.total_cmp(&a.re).then(b.im.total_cmp(&a.im)));
            let unstable: Vec<&Complex<f64>> = poles.iter().filter(|p| p.re > 0.0).collect();
            if let Some(first) = unstable.first() {
                run.notes.push(Note::UnstablePoles {
                    count: unstable.len(),
                    real: first.re,
                    frequency: first.im.abs(),
                    speed: options.flight.speed,
                });
            }
            run.poles = poles;
            run.model = Some(ss);
        }
        Err(Error::Solve(error)) => {
            run.status = Status::Stopped(Stop::LinearizationEquilibrium {
                field: crate::field(&fields.flight(), "speed"),
                speed: options.flight.speed,
                error,
            });
        }
        Err(e) => return Err(e),
    }
    Ok(run)
}

#[cfg(test)]
mod tests {
    use super::super::tests::patil;
    use super::*;
    use crate::analysis::NoProgress;
    use crate::model::aero::Aerodynamics;

    /// The full model and a reduced one linearized through the plan (a regression test of the
    /// wrapper: the solver is validated in tests/suite/aero_linearize.rs); past the divergence
    /// speed (37.09 m/s at n = 8) the run stops and says why, naming the key.
    #[test]
    fn runs_linearize_every_model_and_stop_past_divergence() {
        let (model, aero) = patil(8, Aerodynamics::Peters { states: 6 });
        let mut plan = LinearizePlan::new(model, aero, FlightCondition::at_speed(25.0));
        plan.reduced = vec![4];
        plan.inputs = vec!["gust".into(), "force[8]".into()];
        let out = run(&plan, &mut NoProgress).unwrap();
        assert!(out.is_complete());
        let full = out.runs[0].model.as_ref().unwrap();
        assert_eq!(full.a.nrows(), 2 * 16 + 8 * 6);
        assert_eq!((full.b.ncols(), full.c.nrows()), (2, 3));
        assert_eq!(out.runs[1].model.as_ref().unwrap().a.nrows(), 2 * 4 + 8 * 6);
        assert_eq!(out.runs[1].model.as_ref().unwrap().states[0].name, "eta[1]");
        // Below the flutter speed (32.05 m/s) every pole is stable.
        assert!(out.runs[0].poles.iter().all(|p| p.re < 0.0));
        assert!(out.runs[0].notes.is_empty());
        plan.flight.speed = 40.0;
        let out = run(&plan, &mut NoProgress).unwrap();
        let stop = out.runs[0].status.stop().expect("stopped");
        let message = stop.to_string();
        assert!(
            message.starts_with("aero.flight.speed = 40 m/s: no stable static equilibrium"),
            "{message}"
        );
    }

    /// Past the flutter speed the model is built and its unstable poles noted.
    #[test]
    fn unstable_poles_are_noted() {
        let (model, aero) = patil(8, Aerodynamics::Peters { states: 6 });
        let plan = LinearizePlan::new(model, aero, FlightCondition::at_speed(34.0));
        // Past the divergence speed? No: 34 < 37.09 m/s, past flutter (32.05 m/s).
        let out = run(&plan, &mut NoProgress).unwrap();
        let note = out.runs[0].notes.first().expect("noted").to_string();
        assert!(note.contains("unstable"), "{note}");
    }

    #[test]
    fn errors_name_the_callers_fields() {
        let fields = Fields {
            loads: "loads",
            aero: "aero",
            statics: "static",
            analysis: "linearize",
        };
        type Change = Box<dyn Fn(&mut LinearizePlan)>;
        let cases: Vec<(Change, &str)> = vec![
            (
                Box::new(|p| p.flight.speed = 0.0),
                "aero.flight.speed: missing or not positive",
            ),
            (
                Box::new(|p| p.inputs = vec!["gust".into(), "gusts".into()]),
                "linearize.inputs[1]: unknown input \"gusts\"",
            ),
            (
                Box::new(|p| p.outputs = vec!["y[9]".into()]),
                "linearize.outputs[0]: node 9 is out of range: 0 to 8",
            ),
            (
                Box::new(|p| p.outputs = vec!["lift".into(), "lift".into()]),
                "linearize.outputs[1]: \"lift\" is already linearize.outputs[0]",
            ),
            (
                Box::new(|p| p.inputs.clear()),
                "linearize.inputs: needs at least one",
            ),
            (
                Box::new(|p| p.reduced = vec![40]),
                "linearize.reduced[0]: must be between",
            ),
        ];
        for (change, expected) in cases {
            let (model, aero) = patil(8, Aerodynamics::Wagner);
            let mut p = LinearizePlan::new(model, aero, FlightCondition::at_speed(20.0));
            change(&mut p);
            let msg = p.validate(&fields).unwrap_err().to_string();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }
}
