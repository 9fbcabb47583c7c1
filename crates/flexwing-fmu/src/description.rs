//! The `.fmu` archive (FMI 2.0 §2.2: `modelDescription.xml`, `binaries/<platform>/`,
//! `resources/`): its model description built from the stepper's own signal list (each input and
//! output an FMI variable, its unit and description from the signal), the case and the settings,
//! and the compiled library. `flexwing fmu` and Python's `Case.fmu` call [`write_fmu`].

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

use flexwing::analysis::aero::stepper::{AeroStepper, Hold};
use flexwing::solve::aeroelastic::{Input, Output};
use flexwing_case::Case;

use crate::{
    options_of, plan_of, Settings, CASE_FILE, LIBRARY_FILE, MODEL_IDENTIFIER, SETTINGS_FILE,
};

/// What the FMU is built with.
#[derive(Debug, Clone, PartialEq)]
pub struct FmuOptions {
    /// Input names (`None`: the stepper's defaults, `root_angle`, `speed`, `gust`).
    pub inputs: Option<Vec<String>>,
    /// Output names (`None`: the stepper's defaults).
    pub outputs: Option<Vec<String>>,
    /// Index of the model among the case's dynamic models (0: the first).
    pub model: usize,
    /// The `hold` parameter's start value.
    pub hold: Hold,
}

impl Default for FmuOptions {
    /// The stepper's inputs and outputs, the first model, the zero hold (FMI co-simulation's
    /// inputs without derivatives are constant over a step).
    fn default() -> Self {
        Self {
            inputs: None,
            outputs: None,
            model: 0,
            hold: Hold::Zero,
        }
    }
}

/// What [`write_fmu`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct FmuSummary {
    /// The model description's GUID.
    pub guid: String,
    /// The inputs (Real value references 0 … in order).
    pub inputs: Vec<String>,
    /// The outputs (Real value references after the inputs).
    pub outputs: Vec<String>,
    /// The model stepped (`full`, `reduced-r6`, …).
    pub model: String,
    /// The platform folder of the binary carried (`linux64`).
    pub platform: &'static str,
    /// Size of the archive (bytes).
    pub bytes: usize,
}

/// Why no FMU was written.
#[derive(Debug, Clone, PartialEq)]
pub enum FmuError {
    /// The case or an option is invalid (the CLI's exit status 2).
    Input(String),
    /// The compiled library is missing or unreadable, or the archive cannot be written.
    Io(String),
}

impl std::fmt::Display for FmuError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FmuError::Input(s) | FmuError::Io(s) => f.write_str(s),
        }
    }
}

impl std::error::Error for FmuError {}

/// The FMI platform folder of the binaries this build makes (FMI 2.0 §2.2.1).
pub const PLATFORM: &str = if cfg!(all(target_os = "linux", target_arch = "x86_64")) {
    "linux64"
} else if cfg!(all(target_os = "linux", target_arch = "x86")) {
    "linux32"
} else if cfg!(all(target_os = "windows", target_arch = "x86_64")) {
    "win64"
} else if cfg!(target_os = "macos") {
    "darwin64"
} else {
    "unknown"
};

/// The binary's file name inside `binaries/<platform>/`.
fn binary_name() -> String {
    let ext = if cfg!(target_os = "windows") {
        "dll"
    } else if cfg!(target_os = "macos") {
        "dylib"
    } else {
        "so"
    };
    format!("{MODEL_IDENTIFIER}.{ext}")
}

/// The command that builds the library.
pub const BUILD_COMMAND: &str = "cargo build --release -p flexwing-fmu";

/// The compiled library: `explicit` if given, else `FLEXWING_FMU_LIBRARY`, else
/// [`LIBRARY_FILE`] in the folder `beside` (the `flexwing` executable's).
///
/// # Errors
/// The file missing, naming where it was looked for and the build command.
pub fn find_library(explicit: Option<&Path>, beside: Option<&Path>) -> Result<PathBuf, FmuError> {
    let (path, from) = if let Some(p) = explicit {
        (p.to_path_buf(), "given")
    } else if let Some(p) = std::env::var_os("FLEXWING_FMU_LIBRARY") {
        (PathBuf::from(p), "FLEXWING_FMU_LIBRARY")
    } else if let Some(dir) = beside {
        (dir.join(LIBRARY_FILE), "beside the flexwing executable")
    } else {
        return Err(FmuError::Io(format!(
            "library: the FMU's compiled library ({LIBRARY_FILE}) was not given: build it with \
             `{BUILD_COMMAND}` (it lands in target/release/) and pass its path (library=…) or set \
             FLEXWING_FMU_LIBRARY"
        )));
    };
    if path.is_file() {
        Ok(path)
    } else {
        Err(FmuError::Io(format!(
            "library: the FMU's compiled library {} ({from}) does not exist: build it with \
             `{BUILD_COMMAND}` (it lands in target/release/ beside flexwing) or give its path \
             with --library",
            path.display()
        )))
    }
}

/// An FMI unit: its name and base-unit exponents `(kg, m, s, rad)` (FMI 2.0 §2.2.2).
fn fmi_unit(unit: &str) -> Option<(&'static str, [i32; 4])> {
    Some(match unit {
        "m" => ("m", [0, 1, 0, 0]),
        "rad" => ("rad", [0, 0, 0, 1]),
        "m/s" => ("m/s", [0, 1, -1, 0]),
        "N" => ("N", [1, 1, -2, 0]),
        "N·m" => ("N.m", [1, 2, -2, 0]),
        "m/s²" => ("m/s2", [0, 1, -2, 0]),
        "rad/s" => ("rad/s", [0, 0, -1, 1]),
        "rad/s²" => ("rad/s2", [0, 0, -2, 1]),
        "1" => ("1", [0, 0, 0, 0]),
        _ => return None,
    })
}

/// `text` escaped for an XML attribute.
fn xml(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A number as XML Schema's `xs:double` takes it (round-trip exact).
fn number(v: f64) -> String {
    format!("{v:?}")
}

/// A GUID (`{8-4-4-4-12}` hex digits) that is a hash of `parts` (FNV-1a, 64 bits, twice with
/// two offsets: defined by its constants, the same in every build): the same inputs give the
/// same FMU, different cases or settings different GUIDs.
fn guid(parts: &[&str]) -> String {
    let hash = |offset: u64| {
        let mut h = offset;
        for p in parts {
            for &b in p.as_bytes().iter().chain(&[0xff]) {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
        h
    };
    let (a, b) = (hash(0xcbf2_9ce4_8422_2325), hash(0x6c62_272e_07bb_0142));
    format!(
        "{{{:08x}-{:04x}-{:04x}-{:04x}-{:012x}}}",
        a >> 32,
        (a >> 16) & 0xffff,
        a & 0xffff,
        b >> 48,
        b & 0xffff_ffff_ffff
    )
}

/// Whether `name` is a legal FMI 2.0 structured name of the forms the signals take: an identifier
/// (`[A-Za-z_][A-Za-z0-9_]*`), optionally with one unsigned integer index (`x[12]`).
fn structured(name: &str) -> bool {
    let (base, index) = match name.split_once('[') {
        Some((b, rest)) => match rest.strip_suffix(']') {
            Some(i) => (b, Some(i)),
            None => return false,
        },
        None => (name, None),
    };
    let mut chars = base.chars();
    chars
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
        && index.is_none_or(|i| !i.is_empty() && i.chars().all(|c| c.is_ascii_digit()))
}

/// What a model description says of the run.
pub struct Header<'a> {
    /// `modelName`.
    pub name: &'a str,
    /// `description`.
    pub description: &'a str,
    /// The default experiment: stop time and communication step (s).
    pub stop_time: f64,
    /// The default communication step (s).
    pub step: f64,
}

/// The `modelDescription.xml` of `stepper`'s signals.
///
/// # Errors
/// A signal whose unit has no FMI definition here (add it to `fmi_unit`).
pub fn model_description(
    header: &Header<'_>,
    stepper: &AeroStepper,
    hold: Hold,
    guid: &str,
) -> Result<String, FmuError> {
    let mut units: Vec<(&str, [i32; 4])> = Vec::new();
    let mut unit_of = |unit: &str, name: &str| -> Result<&'static str, FmuError> {
        let (n, exps) = fmi_unit(unit).ok_or_else(|| {
            FmuError::Input(format!(
                "{name}: its unit {unit:?} has no FMI definition in flexwing-fmu (a bug: add it \
                 to description.rs's fmi_unit)"
            ))
        })?;
        if !units.iter().any(|(u, _)| *u == n) {
            units.push((n, exps));
        }
        Ok(n)
    };
    let mut vars = String::new();
    let inputs: Vec<(Input, f64)> = stepper
        .inputs()
        .iter()
        .cloned()
        .zip(stepper.start_values().iter().copied())
        .collect();
    let mut vr = 0usize;
    for (input, start) in &inputs {
        let unit = unit_of(input.unit(), &input.name())?;
        let _ = write!(
            vars,
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" causality=\"input\" \
             variability=\"continuous\" description=\"{}\">\n      <Real start=\"{}\" \
             unit=\"{unit}\"/>\n    </ScalarVariable>\n",
            xml(&input.name()),
            xml(&input.description()),
            number(*start)
        );
        vr += 1;
    }
    let first_output = inputs.len() + 1;
    let outputs: Vec<Output> = stepper.outputs().to_vec();
    for output in &outputs {
        let unit = unit_of(output.unit(), &output.name())?;
        let _ = write!(
            vars,
            "    <ScalarVariable name=\"{}\" valueReference=\"{vr}\" causality=\"output\" \
             variability=\"continuous\" initial=\"calculated\" description=\"{}\">\n      \
             <Real unit=\"{unit}\"/>\n    </ScalarVariable>\n",
            xml(&output.name()),
            xml(&output.description())
        );
        vr += 1;
    }
    let _ = write!(
        vars,
        "    <ScalarVariable name=\"hold\" valueReference=\"0\" causality=\"parameter\" \
         variability=\"fixed\" initial=\"exact\" description=\"how the inputs go over a \
         communication step: zero (the value set, from the step's start) or linear (from the \
         value in force to the value set, reached at the step's end)\">\n      <String \
         start=\"{}\"/>\n    </ScalarVariable>\n",
        hold.name()
    );
    let mut unit_defs = String::new();
    for (name, [kg, m, s, rad]) in &units {
        let mut base = String::new();
        for (symbol, e) in [("kg", kg), ("m", m), ("s", s), ("rad", rad)] {
            if *e != 0 {
                let _ = write!(base, " {symbol}=\"{e}\"");
            }
        }
        let _ = writeln!(
            unit_defs,
            "    <Unit name=\"{}\">\n      <BaseUnit{base}/>\n    </Unit>",
            xml(name)
        );
    }
    // FMI 2.0's structured names take integer array indices only (`force[3]`); a surface's
    // `delta[aileron]` is a legal flat name (any string), so the convention follows the names.
    let convention = if inputs
        .iter()
        .map(|(i, _)| i.name())
        .chain(outputs.iter().map(Output::name))
        .all(|n| structured(&n))
    {
        "structured"
    } else {
        "flat"
    };
    let unknowns: String = (first_output..first_output + outputs.len())
        .map(|i| format!("      <Unknown index=\"{i}\"/>\n"))
        .collect();
    Ok(format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <fmiModelDescription fmiVersion=\"2.0\" modelName=\"{name}\" guid=\"{guid}\" \
         description=\"{description}\" generationTool=\"flexwing {version}\" \
         variableNamingConvention=\"{convention}\" numberOfEventIndicators=\"0\">\n  \
         <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" \
         canRunAsynchronuously=\"false\" canBeInstantiatedOnlyOncePerProcess=\"false\" \
         canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"false\" \
         canSerializeFMUstate=\"false\" providesDirectionalDerivative=\"false\"/>\n  \
         <UnitDefinitions>\n{unit_defs}  </UnitDefinitions>\n  \
         <DefaultExperiment startTime=\"0.0\" stopTime=\"{stop}\" stepSize=\"{step}\"/>\n  \
         <ModelVariables>\n{vars}  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n\
         {unknowns}    </Outputs>\n    <InitialUnknowns>\n{unknowns}    </InitialUnknowns>\n  \
         </ModelStructure>\n</fmiModelDescription>\n",
        name = xml(header.name),
        description = xml(header.description),
        version = env!("CARGO_PKG_VERSION"),
        stop = number(header.stop_time),
        step = number(header.step),
    ))
}

/// The `.fmu` archive of `case` with `options`, carrying `library` (the compiled
/// `flexwing-fmu` of this platform) as its binary.
///
/// # Errors
/// An invalid case or option; no stepper (no initial equilibrium, …).
pub fn fmu_bytes(
    case: &Case,
    options: &FmuOptions,
    library: &[u8],
) -> Result<(Vec<u8>, FmuSummary), FmuError> {
    let input = FmuError::Input;
    let plan = plan_of(case).map_err(input)?;
    let stepper_options = options_of(
        &plan,
        options.inputs.as_deref(),
        options.outputs.as_deref(),
        options.model,
        options.hold,
    )
    .map_err(input)?;
    // The stepper itself, built once here: the FMU's variables are its own signal list, and a
    // case it cannot start from (no equilibrium) fails now rather than in the host.
    let stepper = AeroStepper::new(&plan, &stepper_options).map_err(|e| input(e.to_string()))?;
    let case_text = case.to_toml_string().map_err(|e| input(e.to_string()))?;
    let inputs: Vec<String> = stepper.inputs().iter().map(Input::name).collect();
    let outputs: Vec<String> = stepper.outputs().iter().map(Output::name).collect();
    let model = stepper.kind().label();
    let title = case.title.clone().unwrap_or_else(|| {
        case.file()
            .and_then(|f| Path::new(f).file_stem())
            .map_or_else(
                || "flexwing case".to_string(),
                |s| s.to_string_lossy().into_owned(),
            )
    });
    let step = match plan.structure.output_times.as_slice() {
        [a, b, ..] => b - a,
        _ => plan.structure.end_time,
    };
    let description = format!("{title} (flexwing, the {model} model)");
    let header = Header {
        name: &title,
        description: &description,
        stop_time: plan.structure.end_time,
        step,
    };
    let settings_key = format!(
        "{inputs:?}{outputs:?}{}{}",
        options.model,
        options.hold.name()
    );
    let guid = guid(&[&case_text, &settings_key, env!("CARGO_PKG_VERSION")]);
    let xml = model_description(&header, &stepper, options.hold, &guid)?;
    let settings = Settings {
        guid: guid.clone(),
        inputs: inputs.clone(),
        outputs: outputs.clone(),
        model: options.model,
        hold: options.hold.name().to_string(),
    };
    let settings_text = serde_json::to_string_pretty(&settings)
        .map_err(|e| FmuError::Io(format!("settings: {e}")))?;
    let io = |e: zip::result::ZipError| FmuError::Io(format!("the FMU archive: {e}"));
    let mut zip = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    let binary = stored.unix_permissions(0o755);
    for (name, bytes, opts) in [
        ("modelDescription.xml".to_string(), xml.as_bytes(), stored),
        (
            format!("resources/{CASE_FILE}"),
            case_text.as_bytes(),
            stored,
        ),
        (
            format!("resources/{SETTINGS_FILE}"),
            settings_text.as_bytes(),
            stored,
        ),
        (
            format!("binaries/{PLATFORM}/{}", binary_name()),
            library,
            binary,
        ),
    ] {
        zip.start_file(name, opts).map_err(io)?;
        zip.write_all(bytes)
            .map_err(|e| FmuError::Io(format!("the FMU archive: {e}")))?;
    }
    let bytes = zip.finish().map_err(io)?.into_inner();
    let summary = FmuSummary {
        guid,
        inputs,
        outputs,
        model,
        platform: PLATFORM,
        bytes: bytes.len(),
    };
    Ok((bytes, summary))
}

/// Write the `.fmu` of `case` with `options` to `out`, carrying the library at `library`.
///
/// # Errors
/// As [`fmu_bytes`]; the library unreadable; `out` not writable.
pub fn write_fmu(
    case: &Case,
    options: &FmuOptions,
    library: &Path,
    out: &Path,
) -> Result<FmuSummary, FmuError> {
    let lib = std::fs::read(library).map_err(|e| {
        FmuError::Io(format!(
            "library: cannot read {}: {e} (build it with `{BUILD_COMMAND}`)",
            library.display()
        ))
    })?;
    let (bytes, summary) = fmu_bytes(case, options, &lib)?;
    // Atomically (a temporary beside `out`, synced, renamed): an interrupted write leaves no
    // archive that looks complete.
    flexwing_io::write_bytes(out, &bytes).map_err(|e| FmuError::Io(e.to_string()))?;
    Ok(summary)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The structured names FMI 2.0 allows (its grammar, §2.2.9: an identifier with integer
    /// indices) against the signals' names: a surface's name in brackets is not one.
    #[test]
    fn structured_names_are_identifiers_with_integer_indices() {
        for name in ["tip_y", "force[12]", "x[0]", "_a1"] {
            assert!(structured(name), "{name}");
        }
        for name in [
            "delta[aileron]",
            "hinge_moment[flap]",
            "x[]",
            "1x",
            "x[1",
            "a-b",
            "",
        ] {
            assert!(!structured(name), "{name}");
        }
    }

    #[test]
    fn every_signal_unit_has_an_fmi_definition() {
        let n = 4;
        let inputs = [
            "root_angle",
            "speed",
            "gust",
            "gust[1]",
            "force[1]",
            "torque[1]",
        ];
        for name in inputs {
            let i = Input::parse(name, n, true, &[], "i").unwrap();
            assert!(fmi_unit(i.unit()).is_some(), "{name}: {}", i.unit());
        }
        let outputs = [
            "tip_x",
            "tip_y",
            "tip_twist",
            "x[1]",
            "y[1]",
            "twist[1]",
            "root_bending_moment",
            "root_shear",
            "root_torque",
            "lift",
            "tip_acceleration",
            "acceleration[1]",
        ];
        for name in outputs {
            let o = Output::parse(name, n, true, &[], "o").unwrap();
            assert!(fmi_unit(o.unit()).is_some(), "{name}: {}", o.unit());
        }
    }

    #[test]
    fn guids_have_the_fmi_form_and_differ_with_their_parts() {
        let a = guid(&["case", "settings"]);
        let b = guid(&["case", "other"]);
        assert_ne!(a, b);
        assert_eq!(a, guid(&["case", "settings"]));
        let groups: Vec<usize> = a
            .trim_matches(|c| c == '{' || c == '}')
            .split('-')
            .map(str::len)
            .collect();
        assert_eq!(groups, [8, 4, 4, 4, 12], "{a}");
    }

    #[test]
    fn xml_attributes_are_escaped() {
        assert_eq!(xml("a<b & \"c\""), "a&lt;b &amp; &quot;c&quot;");
    }
}
