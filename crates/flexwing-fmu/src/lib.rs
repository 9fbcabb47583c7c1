//! # flexwing-fmu
//!
//! A co-simulation FMU (FMI 2.0, the standard's co-simulation interface) of a flexwing case's
//! aeroelastic response (issue 21 §3, docs/control.md): the library's
//! [`flexwing::analysis::aero::stepper::AeroStepper`] behind the FMI C functions, and the writer of
//! the `.fmu` archive (`flexwing fmu`, Python's `Case.fmu`).
//!
//! * [`description`]: the archive: `modelDescription.xml` (the stepper's own inputs and outputs as
//!   FMI variables, with units and descriptions; the `hold` parameter), the case and the settings
//!   in `resources/`, the library in `binaries/linux64/`.
//! * `instance` (private): one FMU instance as a safe state machine (the FMI 2.0 co-simulation
//!   states; out-of-order calls and unknown value references are errors with a logged message).
//! * `ffi` (private): the exported C functions, the only module with `unsafe`; every entry point
//!   catches panics, so none crosses into the host.
//!
//! Source: FMI 2.0.4, "Functional Mock-up Interface for Model Exchange and Co-Simulation"
//! (Modelica Association, 2022), chapters 2 (common concepts, the model description) and 4
//! (co-simulation: the state machine of section 4.2.4).

#![deny(unsafe_code)]

pub mod description;
mod ffi;
mod instance;

use flexwing::analysis::aero::response::AeroDynamicPlan;
use flexwing::analysis::aero::stepper::{AeroStepper, Hold, StepperOptions};
use flexwing::analysis::Plan;
use flexwing::solve::aeroelastic::{Input, Output};
use flexwing_case::{Analysis, Case};
use serde::{Deserialize, Serialize};

pub use description::{write_fmu, FmuError, FmuOptions, FmuSummary};
pub use instance::{path_of_uri, Instance, State, Status};

/// The model identifier: the name of the binary in `binaries/<platform>/` and of the C symbols'
/// prefix-free FMI 2.0 functions.
pub const MODEL_IDENTIFIER: &str = "flexwing_fmu";
/// The case file in the FMU's `resources/`.
pub const CASE_FILE: &str = "case.toml";
/// The settings (GUID, inputs, outputs, model) in the FMU's `resources/`.
pub const SETTINGS_FILE: &str = "flexwing-fmu.json";
/// The file name cargo gives the compiled library on this platform.
pub const LIBRARY_FILE: &str = if cfg!(target_os = "windows") {
    "flexwing_fmu.dll"
} else if cfg!(target_os = "macos") {
    "libflexwing_fmu.dylib"
} else {
    "libflexwing_fmu.so"
};

/// What the FMU steps, written by [`write_fmu`] into `resources/` and read at instantiation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Settings {
    /// The model description's GUID (an instance checks it).
    pub guid: String,
    /// The inputs, in value-reference order (Real 0, 1, …).
    pub inputs: Vec<String>,
    /// The outputs, in value-reference order after the inputs.
    pub outputs: Vec<String>,
    /// Index of the model among the plan's (the full model first if the case runs it).
    pub model: usize,
    /// The `hold` parameter's start value (`zero` or `linear`): an instance starts with it.
    pub hold: String,
}

impl Settings {
    /// The `hold` parameter's start value.
    ///
    /// # Errors
    /// Not `zero` or `linear`.
    pub fn start_hold(&self) -> Result<Hold, String> {
        Hold::from_name(&self.hold).ok_or_else(|| {
            format!(
                "hold: unknown value {:?} in the settings; expected \"zero\" or \"linear\"",
                self.hold
            )
        })
    }
}

/// The aeroelastic dynamic plan of `case`.
///
/// # Errors
/// The case's error; a case without `[aero]`.
pub fn plan_of(case: &Case) -> Result<AeroDynamicPlan, String> {
    match case.plan(Analysis::Dynamic).map_err(|e| e.to_string())? {
        Plan::AeroDynamic(plan) => Ok(plan),
        _ => Err(
            "aero: missing: an FMU steps an aeroelastic response (the case needs [aero])".into(),
        ),
    }
}

/// The stepper options of the named inputs and outputs (`None`: the stepper's defaults).
///
/// # Errors
/// An unknown name (naming `inputs[i]` or `outputs[i]`).
pub fn options_of(
    plan: &AeroDynamicPlan,
    inputs: Option<&[String]>,
    outputs: Option<&[String]>,
    model: usize,
    hold: Hold,
) -> Result<StepperOptions, String> {
    let m = &plan.structure.model;
    let (ne, torsion) = (m.n_elements(), m.has_torsion());
    let surfaces = &plan.aero.section.surfaces;
    let mut options = StepperOptions::new(torsion);
    if let Some(list) = inputs {
        options.inputs = list
            .iter()
            .enumerate()
            .map(|(i, n)| Input::parse(n, ne, torsion, surfaces, &format!("inputs[{i}]")))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
    }
    if let Some(list) = outputs {
        options.outputs = list
            .iter()
            .enumerate()
            .map(|(i, n)| Output::parse(n, ne, torsion, surfaces, &format!("outputs[{i}]")))
            .collect::<Result<_, _>>()
            .map_err(|e| e.to_string())?;
    }
    options.model = model;
    options.hold = hold;
    Ok(options)
}

/// The stepper of `case` with `settings`.
///
/// # Errors
/// As [`plan_of`], [`options_of`] and [`AeroStepper::new`].
pub fn stepper_of(case: &Case, settings: &Settings, hold: Hold) -> Result<AeroStepper, String> {
    let plan = plan_of(case)?;
    let options = options_of(
        &plan,
        Some(&settings.inputs),
        Some(&settings.outputs),
        settings.model,
        hold,
    )?;
    AeroStepper::new(&plan, &options).map_err(|e| e.to_string())
}
