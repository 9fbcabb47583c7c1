//! One FMU instance as a safe state machine (FMI 2.0 §4.2.4): the calls the co-simulation
//! interface allows in each state, checked; value references checked against the settings; each
//! refusal an `Error` status with a logged message naming the function and why. `ffi.rs` is a
//! thin shim over this.
//!
//! Value references: Real `0 … ni − 1` the inputs, `ni … ni + no − 1` the outputs (the settings'
//! order); String `0` the `hold` parameter. FMU time is `startTime` (fmi2SetupExperiment) plus
//! the stepper's time, which starts at 0 as a `flexwing dynamic` run does.

use std::path::PathBuf;

use flexwing::analysis::aero::stepper::{AeroStepper, Hold, StepError};
use flexwing_case::Case;

use crate::{stepper_of, Settings, CASE_FILE, SETTINGS_FILE};

/// An FMI status (`fmi2Status`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(i32)]
pub enum Status {
    /// `fmi2OK`.
    Ok = 0,
    /// `fmi2Warning`.
    Warning = 1,
    /// `fmi2Discard`: the step was not done (the stepper is as before it).
    Discard = 2,
    /// `fmi2Error`.
    Error = 3,
    /// `fmi2Fatal`.
    Fatal = 4,
}

/// The co-simulation states of FMI 2.0 §4.2.4 (`stepComplete` stands for the initialized slave).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    /// After fmi2Instantiate or fmi2Reset.
    Instantiated,
    /// Between fmi2EnterInitializationMode and fmi2ExitInitializationMode.
    Initialization,
    /// Initialized: stepping.
    StepComplete,
    /// After fmi2Terminate.
    Terminated,
    /// After an error (only reading, fmi2Reset and fmi2FreeInstance are allowed).
    Error,
}

impl State {
    fn name(self) -> &'static str {
        match self {
            State::Instantiated => "instantiated",
            State::Initialization => "initialization mode",
            State::StepComplete => "initialized (stepping)",
            State::Terminated => "terminated",
            State::Error => "error",
        }
    }
}

/// Where log messages go: `(status, category, message)`.
pub type Logger = Box<dyn FnMut(Status, &str, &str)>;

/// One FMU instance.
pub struct Instance {
    log: Logger,
    debug: bool,
    case: Case,
    settings: Settings,
    stepper: AeroStepper,
    hold: Hold,
    state: State,
    start_time: f64,
    stop_time: Option<f64>,
    outputs: Vec<f64>,
    fresh: bool,
}

/// The local path of `uri` (`file:///a/b`, `file:/a/b`, `file://localhost/a/b`, percent-encoded),
/// or a plain path.
///
/// # Errors
/// Another scheme or host.
pub fn path_of_uri(uri: &str) -> Result<PathBuf, String> {
    let rest = if let Some(r) = uri.strip_prefix("file://") {
        if r.starts_with('/') {
            r.to_string()
        } else if let Some(r) = r.strip_prefix("localhost") {
            r.to_string()
        } else {
            return Err(format!(
                "fmuResourceLocation {uri:?} names another host; only local file URIs are read"
            ));
        }
    } else if let Some(r) = uri.strip_prefix("file:") {
        r.to_string()
    } else if uri.contains("://") {
        return Err(format!(
            "fmuResourceLocation {uri:?} is not a file URI (file:///…)"
        ));
    } else {
        uri.to_string()
    };
    // Percent-decoding (RFC 3986 §2.1).
    let bytes = rest.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            let hex = std::str::from_utf8(&bytes[i + 1..i + 3]).ok();
            if let Some(v) = hex.and_then(|h| u8::from_str_radix(h, 16).ok()) {
                out.push(v);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    let text = String::from_utf8(out)
        .map_err(|_| format!("fmuResourceLocation {uri:?} is not UTF-8 once decoded"))?;
    // Windows: `/C:/x` is `C:/x`.
    let text = match text.as_bytes() {
        [b'/', d, b':', ..] if cfg!(windows) && d.is_ascii_alphabetic() => text[1..].to_string(),
        _ => text,
    };
    Ok(PathBuf::from(text))
}

impl Instance {
    /// An instance of the FMU whose resources are at `resource_location` (a file URI), checked
    /// against `guid`; messages go to `log`.
    ///
    /// # Errors
    /// The message (also logged): the resources unreadable, another GUID, an invalid case, no
    /// stepper.
    pub fn new(
        guid: &str,
        resource_location: &str,
        debug: bool,
        mut log: Logger,
    ) -> Result<Self, String> {
        let built = (|| {
            let dir = path_of_uri(resource_location)?;
            let settings_path = dir.join(SETTINGS_FILE);
            let text = std::fs::read_to_string(&settings_path)
                .map_err(|e| format!("cannot read {}: {e}", settings_path.display()))?;
            let settings: Settings = serde_json::from_str(&text)
                .map_err(|e| format!("{}: {e}", settings_path.display()))?;
            if settings.guid != guid {
                return Err(format!(
                    "fmuGUID {guid:?} is not this FMU's ({:?}): the model description and the \
                     resources come from different FMUs",
                    settings.guid
                ));
            }
            let case = Case::load(&dir.join(CASE_FILE)).map_err(|e| e.to_string())?;
            let hold = settings.start_hold()?;
            let stepper = stepper_of(&case, &settings, hold)?;
            Ok((case, settings, stepper, hold))
        })();
        let (case, settings, stepper, hold) = match built {
            Ok(b) => b,
            Err(e) => {
                let message = format!("fmi2Instantiate: {e}");
                log(Status::Error, "logStatusError", &message);
                return Err(message);
            }
        };
        let n = stepper.outputs().len();
        Ok(Self {
            log,
            debug,
            case,
            settings,
            stepper,
            hold,
            state: State::Instantiated,
            start_time: 0.0,
            stop_time: None,
            outputs: vec![0.0; n],
            fresh: false,
        })
    }

    /// The state.
    pub fn state(&self) -> State {
        self.state
    }

    /// The stepper.
    pub fn stepper(&self) -> &AeroStepper {
        &self.stepper
    }

    /// The `hold` parameter.
    pub fn hold(&self) -> Hold {
        self.hold
    }

    /// Log `message` as an error of `function` and return [`Status::Error`].
    pub fn error(&mut self, function: &str, message: &str) -> Status {
        (self.log)(
            Status::Error,
            "logStatusError",
            &format!("{function}: {message}"),
        );
        Status::Error
    }

    /// Log `message` when debug logging is on.
    fn info(&mut self, function: &str, message: &str) {
        if self.debug {
            (self.log)(Status::Ok, "logAll", &format!("{function}: {message}"));
        }
    }

    /// `Ok` if the state is one of `allowed`, else the logged error.
    fn allowed(&mut self, function: &str, allowed: &[State]) -> Result<(), Status> {
        if allowed.contains(&self.state) {
            Ok(())
        } else {
            let names: Vec<&str> = allowed.iter().map(|s| s.name()).collect();
            let message = format!(
                "called in state {}; allowed in: {}",
                self.state.name(),
                names.join(", ")
            );
            Err(self.error(function, &message))
        }
    }

    /// `fmi2SetDebugLogging`.
    pub fn set_debug_logging(&mut self, on: bool) -> Status {
        self.debug = on;
        Status::Ok
    }

    /// `fmi2SetupExperiment`.
    pub fn setup_experiment(
        &mut self,
        tolerance: Option<f64>,
        start_time: f64,
        stop_time: Option<f64>,
    ) -> Status {
        let f = "fmi2SetupExperiment";
        if let Err(s) = self.allowed(f, &[State::Instantiated]) {
            return s;
        }
        if !start_time.is_finite() {
            return self.error(f, &format!("startTime must be finite, got {start_time}"));
        }
        if let Some(stop) = stop_time {
            if !(stop >= start_time) {
                return self.error(
                    f,
                    &format!("stopTime {stop} is before startTime {start_time}"),
                );
            }
        }
        if let Some(t) = tolerance {
            self.info(
                f,
                &format!("tolerance {t} not used: the case's rtol and atol set the integrator"),
            );
        }
        self.start_time = start_time;
        self.stop_time = stop_time;
        Status::Ok
    }

    /// `fmi2EnterInitializationMode`.
    pub fn enter_initialization(&mut self) -> Status {
        match self.allowed("fmi2EnterInitializationMode", &[State::Instantiated]) {
            Ok(()) => {
                self.state = State::Initialization;
                Status::Ok
            }
            Err(s) => s,
        }
    }

    /// `fmi2ExitInitializationMode`.
    pub fn exit_initialization(&mut self) -> Status {
        match self.allowed("fmi2ExitInitializationMode", &[State::Initialization]) {
            Ok(()) => {
                self.state = State::StepComplete;
                Status::Ok
            }
            Err(s) => s,
        }
    }

    /// `fmi2Terminate`.
    pub fn terminate(&mut self) -> Status {
        match self.allowed("fmi2Terminate", &[State::StepComplete]) {
            Ok(()) => {
                self.state = State::Terminated;
                Status::Ok
            }
            Err(s) => s,
        }
    }

    /// `fmi2Reset`: back to the instantiated state, the stepper at its start.
    pub fn reset(&mut self) -> Status {
        let hold = self.settings.start_hold();
        match hold.and_then(|h| stepper_of(&self.case, &self.settings, h).map(|s| (s, h))) {
            Ok((s, hold)) => {
                self.stepper = s;
                self.hold = hold;
                self.state = State::Instantiated;
                self.start_time = 0.0;
                self.stop_time = None;
                self.fresh = false;
                Status::Ok
            }
            Err(e) => {
                self.state = State::Error;
                self.error("fmi2Reset", &e)
            }
        }
    }

    /// Number of inputs.
    fn n_inputs(&self) -> usize {
        self.settings.inputs.len()
    }

    /// The name of Real value reference `vr`, if any.
    fn real_name(&self, vr: u32) -> Option<&str> {
        let i = vr as usize;
        let ni = self.n_inputs();
        if i < ni {
            Some(&self.settings.inputs[i])
        } else {
            self.settings.outputs.get(i - ni).map(String::as_str)
        }
    }

    /// The error of an unknown value reference of `kind`.
    fn unknown(&mut self, function: &str, kind: &str, vr: u32) -> Status {
        let known = match kind {
            "Real" => format!(
                "the Real variables are 0 to {}",
                self.n_inputs() + self.settings.outputs.len() - 1
            ),
            "String" => "the String variable is 0 (hold)".to_string(),
            _ => format!("the FMU has no {kind} variables"),
        };
        self.error(
            function,
            &format!("unknown value reference {vr} ({kind}); {known}"),
        )
    }

    /// `fmi2GetReal`: inputs (the values set), outputs (at the current time).
    pub fn get_real(&mut self, vrs: &[u32], values: &mut [f64]) -> Status {
        let f = "fmi2GetReal";
        if let Err(s) = self.allowed(
            f,
            &[
                State::Initialization,
                State::StepComplete,
                State::Terminated,
                State::Error,
            ],
        ) {
            return s;
        }
        let ni = self.n_inputs();
        for &vr in vrs {
            if self.real_name(vr).is_none() {
                return self.unknown(f, "Real", vr);
            }
        }
        if vrs.iter().any(|&vr| vr as usize >= ni) && !self.fresh {
            self.stepper.outputs_into(&mut self.outputs);
            self.fresh = true;
        }
        for (v, &vr) in values.iter_mut().zip(vrs) {
            let i = vr as usize;
            *v = if i < ni {
                self.stepper.input_values()[i]
            } else {
                self.outputs[i - ni]
            };
        }
        Status::Ok
    }

    /// `fmi2SetReal`: inputs only.
    pub fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Status {
        let f = "fmi2SetReal";
        if let Err(s) = self.allowed(
            f,
            &[
                State::Instantiated,
                State::Initialization,
                State::StepComplete,
            ],
        ) {
            return s;
        }
        let ni = self.n_inputs();
        for (&vr, &v) in vrs.iter().zip(values) {
            let Some(name) = self.real_name(vr).map(str::to_string) else {
                return self.unknown(f, "Real", vr);
            };
            if vr as usize >= ni {
                return self.error(
                    f,
                    &format!("value reference {vr} is the output {name}: it cannot be set"),
                );
            }
            if let Err(e) = self.stepper.set_input(vr as usize, v) {
                return self.error(f, &e.to_string());
            }
            self.fresh = false;
        }
        Status::Ok
    }

    /// `fmi2GetString`: the `hold` parameter.
    pub fn get_string(&mut self, vrs: &[u32]) -> Result<Vec<&'static str>, Status> {
        let f = "fmi2GetString";
        self.allowed(
            f,
            &[
                State::Instantiated,
                State::Initialization,
                State::StepComplete,
                State::Terminated,
                State::Error,
            ],
        )?;
        let mut out = Vec::with_capacity(vrs.len());
        for &vr in vrs {
            if vr != 0 {
                return Err(self.unknown(f, "String", vr));
            }
            out.push(self.hold.name());
        }
        Ok(out)
    }

    /// `fmi2SetString`: the `hold` parameter, before initialization ends.
    pub fn set_string(&mut self, vrs: &[u32], values: &[Option<&str>]) -> Status {
        let f = "fmi2SetString";
        if let Err(s) = self.allowed(f, &[State::Instantiated, State::Initialization]) {
            return s;
        }
        for (&vr, v) in vrs.iter().zip(values) {
            if vr != 0 {
                return self.unknown(f, "String", vr);
            }
            let Some(hold) = v.and_then(Hold::from_name) else {
                return self.error(
                    f,
                    &match v {
                        Some(v) => {
                            format!("hold: unknown value {v:?}; expected \"zero\" or \"linear\"")
                        }
                        None => "hold: a null string; expected \"zero\" or \"linear\"".to_string(),
                    },
                );
            };
            self.hold = hold;
            self.stepper.set_hold(hold);
            self.fresh = false;
        }
        Status::Ok
    }

    /// `fmi2Get/SetInteger`, `fmi2Get/SetBoolean`: the FMU has none of these variables.
    pub fn no_variables(&mut self, function: &str, kind: &str, vrs: &[u32]) -> Status {
        if let Err(s) = self.allowed(
            function,
            &[
                State::Instantiated,
                State::Initialization,
                State::StepComplete,
                State::Terminated,
                State::Error,
            ],
        ) {
            return s;
        }
        match vrs.first() {
            Some(&vr) => self.unknown(function, kind, vr),
            None => Status::Ok,
        }
    }

    /// The FMU time (s).
    pub fn time(&self) -> f64 {
        self.start_time + self.stepper.t()
    }

    /// `fmi2DoStep` from `t` (the current communication point) by `h`.
    pub fn do_step(&mut self, t: f64, h: f64) -> Status {
        let f = "fmi2DoStep";
        if let Err(s) = self.allowed(f, &[State::StepComplete]) {
            return s;
        }
        let now = self.time();
        // The master's time and the FMU's: the same sums of the same steps, or rounded apart by
        // a few ulps of the time (a master that adds its steps in another order).
        if !t.is_finite() || (t - now).abs() > 1e-9 * now.abs().max(1.0) {
            return self.error(
                f,
                &format!(
                    "currentCommunicationPoint {t} is not the FMU's time {now} (the steps must \
                     follow on from each other)"
                ),
            );
        }
        self.fresh = false;
        match self.stepper.step(h, &mut |_| {}) {
            Ok(_) => Status::Ok,
            Err(StepError::Input(e)) if e.field == "dt" => {
                self.error(f, &format!("communicationStepSize: {}", e.reason))
            }
            Err(StepError::Input(e)) => self.error(f, &e.to_string()),
            Err(StepError::Stopped(stop)) => {
                (self.log)(
                    Status::Discard,
                    "logStatusDiscard",
                    &format!(
                        "{f}: the integration stopped inside the step from t = {now} s: {stop} \
                         (the FMU stays at t = {now} s)"
                    ),
                );
                Status::Discard
            }
        }
    }

    /// Whether `fmi2Terminated` would say the slave cannot go on (never: a discarded step leaves
    /// the stepper as before it).
    pub fn terminated(&self) -> bool {
        false
    }

    /// Mark the instance failed after `message` (a panic caught at the boundary).
    pub fn fail(&mut self, function: &str, message: &str) -> Status {
        self.state = State::Error;
        self.error(
            function,
            &format!("internal error (a bug; please report it): {message}"),
        )
    }
}
