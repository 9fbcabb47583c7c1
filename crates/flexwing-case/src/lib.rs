//! # flexwing-case
//!
//! The flexwing case file: its schema ([`Case`], serde with `deny_unknown_fields`, one struct
//! per table), TOML with line/column errors, one typed error ([`CaseError`]) and the conversion
//! into the plans of [`flexwing::analysis`]. The keys and their defaults are documented in
//! `docs/case-file.md` (a test keeps the two in step).
//!
//! The data flow of every front end: a case (TOML text, a file, or any serde data format with the
//! same keys, such as a Python dict) → [`Case`] → a plan ([`Case::plan`] of an [`Analysis`]: the
//! library's `flexwing::analysis::Plan`, aeroelastic when the case has `[aero]`) →
//! `flexwing::analysis::run` → an outcome.
//!
//! ```
//! use flexwing::analysis::{modes, NoProgress};
//! use flexwing_case::Case;
//!
//! let case = Case::from_toml_str(
//!     "[beam]\nlength = 1.0\nelements = 20\n\n[beam.section]\nEI = 50.0\nmass_per_length = 0.2\n",
//! )?;
//! let plan = case.modes_plan()?;
//! let outcome = modes::run(&plan, &mut NoProgress)?;
//! assert_eq!(outcome.modes.len(), 10);
//! // The same case from another serde format, and back to TOML.
//! let again: Case = serde_json::from_value(serde_json::json!({
//!     "beam": { "length": 1.0, "elements": 20,
//!               "section": { "EI": 50.0, "mass_per_length": 0.2 } }
//! }))?;
//! assert_eq!(again, case);
//! assert_eq!(Case::from_toml_str(&case.to_toml_string()?)?, case);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Validation is split by who can see the rule: this crate checks which keys go together, load
//! names and node indices; the library checks every value (positive, finite, in range) when the
//! plan is validated, naming the case-file key it came from.

mod aero;
mod beam;
mod chain3d;
mod dynamic;
mod error;
mod gust_family;
mod linearize;
mod loads;
mod plan;
mod property;
mod spec;
mod spec_aero;
mod spec_chain3d;
mod spec_output;
mod statics;
mod turbulence;
mod words;

use std::path::Path;

use serde::Deserialize;

pub use error::{one_line, CaseError};
pub use loads::library_loads;
pub use plan::Analysis;
pub use property::Property;
pub use spec::{
    BeamSpec, CalibrationSpec, Case, DampingKindSpec, DampingSpec, DirectionSpec, DynamicSpec,
    EquationsSpec, GyroscopicSpec, InertiaAxisSpec, InitialKindSpec, InitialSpec, IntegrationSpec,
    IntegratorSpec, LoadKindSpec, LoadSpec, ModesSpec, SectionSpec, StaticSpec, SweepSpec,
    TimeKindSpec, TimeSpec,
};
pub use spec_aero::{
    AeroModelSpec, AeroSpec, AerodynamicsSpec, FlightSpec, FlutterSpec, GustFamilySpec,
    GustPenetrationSpec, GustShapeSpec, GustSpec, LinearizeSpec, SpectrumSpec, SpeedSweepSpec,
    StatesSpec, SurfaceSpec, TurbulenceSpec,
};
pub use spec_chain3d::{CouplingSpec, StructureSpec, StudyParameterSpec, StudySpec};
pub use spec_output::{thinned_indices, NodeTimesSpec, OutputFormatSpec, OutputSpec};
pub use words::{in_user_terms, keys, JARGON};

/// Largest case file read (bytes): 16 MiB, a thousand times the largest example; tables of
/// 100 000 stations fit.
pub const MAX_CASE_FILE_BYTES: u64 = 16 << 20;

impl Case {
    /// Read and parse the case file at `path`; errors name the file as `path` displays. Only a
    /// regular file of at most [`MAX_CASE_FILE_BYTES`] is read.
    ///
    /// # Errors
    /// `PATH: cannot read the case file: …`, or `PATH line L, column C: KEY: problem` for TOML
    /// and schema errors.
    pub fn load(path: &Path) -> Result<Self, CaseError> {
        use std::io::Read as _;
        let name = path.display().to_string();
        let fail = |reason: String| CaseError {
            file: Some(name.clone()),
            ..CaseError::new(reason)
        };
        // A device or a FIFO (`/dev/zero`, a pipe nobody writes to) would be read without end
        // or block: only regular files, and at most MAX_CASE_FILE_BYTES of them.
        let meta =
            std::fs::metadata(path).map_err(|e| fail(format!("cannot read the case file: {e}")))?;
        if !meta.is_file() {
            return Err(fail(
                "cannot read the case file: not a regular file (a directory, device or pipe)"
                    .into(),
            ));
        }
        if meta.len() > MAX_CASE_FILE_BYTES {
            return Err(fail(format!(
                "the case file has {} bytes; at most {MAX_CASE_FILE_BYTES} are read",
                meta.len()
            )));
        }
        let mut text = String::new();
        std::fs::File::open(path)
            .and_then(|f| f.take(MAX_CASE_FILE_BYTES + 1).read_to_string(&mut text))
            .map_err(|e| fail(format!("cannot read the case file: {e}")))?;
        if text.len() as u64 > MAX_CASE_FILE_BYTES {
            return Err(fail(format!(
                "the case file grew past {MAX_CASE_FILE_BYTES} bytes while read"
            )));
        }
        Self::parse(&text, Some(&name))
    }

    /// Parse a case from TOML text.
    ///
    /// # Errors
    /// `line L, column C: KEY: problem` for TOML and schema errors.
    pub fn from_toml_str(text: &str) -> Result<Self, CaseError> {
        Self::parse(text, None)
    }

    /// Parse a case from TOML text; `file` names it in errors.
    ///
    /// # Errors
    /// As [`Case::from_toml_str`], with the file name in front.
    pub fn parse(text: &str, file: Option<&str>) -> Result<Self, CaseError> {
        let mut case: Case = toml::from_str(text).map_err(|e| CaseError::toml(&e, text, file))?;
        case.file = file.map(str::to_string);
        Ok(case)
    }

    /// A case from any serde data format with the case file's keys (a JSON value, a Python
    /// dict through a binding). `Case` is also `Deserialize` itself; this wraps its error.
    ///
    /// # Errors
    /// The format's error, as the reason.
    pub fn from_deserializer<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Self, CaseError> {
        Case::deserialize(d)
            .map_err(|e| CaseError::new(words::in_user_terms(&one_line(&e.to_string()))))
    }

    /// The case as TOML text (the file it was read from, if any, is not part of it).
    ///
    /// # Errors
    /// A value TOML cannot hold (none of the schema's).
    pub fn to_toml_string(&self) -> Result<String, CaseError> {
        toml::to_string(self).map_err(|e| CaseError::new(one_line(&e.to_string())))
    }

    /// The file the case was read from, as given.
    pub fn file(&self) -> Option<&str> {
        self.file.as_deref()
    }

    /// An error of a value, in this case's file.
    pub(crate) fn error(&self, e: flexwing::InputError) -> CaseError {
        CaseError::input(e, self.file())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_of(text: &str) -> String {
        Case::parse(text, Some("x.toml")).unwrap_err().to_string()
    }

    const BEAM: &str =
        "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\nmass_per_length = 0.2\n";

    #[test]
    fn unknown_key_is_one_line_with_line_column_and_path() {
        let msg = error_of(&format!("{BEAM}foo = 1\n"));
        assert_eq!(
            msg.lines().count(),
            1,
            "message spans several lines: {msg:?}"
        );
        assert!(
            msg.starts_with("x.toml line 8, column 1: beam.section: unknown key `foo`"),
            "{msg}"
        );
        assert!(msg.contains("the keys here are `EI`"), "{msg}");
    }

    #[test]
    fn type_error_names_the_key() {
        let msg = error_of(&BEAM.replace("EI = 50", "EI = \"50\""));
        assert!(
            msg.starts_with(
                "x.toml line 6, column 6: beam.section.EI: must be a number, or a table \
                 { x = [...], value = [...] }, got the text \"50\""
            ),
            "{msg}"
        );
    }

    #[test]
    fn syntax_error_is_one_line() {
        let msg = error_of("[beam\nlength = 1\n");
        assert_eq!(msg.lines().count(), 1, "{msg:?}");
        assert!(msg.starts_with("x.toml line 1, column "), "{msg}");
    }

    #[test]
    fn malformed_table_says_what_is_missing() {
        let msg = error_of(&BEAM.replace("EI = 50", "EI = { x = [0.0, 1.0] }"));
        assert!(msg.contains("beam.section.EI"), "{msg}");
        assert!(msg.contains("missing `value`"), "{msg}");
    }

    #[test]
    fn rotary_inertia_keys_reach_the_beam_and_bad_values_name_their_key() {
        // Bars: m ℓ²/12 = 0.2 · 0.25 · 0.0625 / 12; plus ρI ℓ = 1e-3 · 0.25.
        let text = BEAM.replace(
            "elements = 4\n",
            "elements = 4\nelement_inertia = \"bar\"\n",
        );
        let bars = Case::parse(&text, Some("x.toml"))
            .unwrap()
            .to_beam()
            .unwrap();
        let expected = 0.2 * 0.25 * 0.0625 / 12.0;
        assert!((bars.bending_inertias()[2] - expected).abs() < 1e-15 * expected);
        let text = format!("{text}rotary_inertia = 1e-3\n");
        let both = Case::parse(&text, Some("x.toml"))
            .unwrap()
            .to_beam()
            .unwrap();
        let expected = expected + 1e-3 * 0.25;
        assert!((both.bending_inertias()[0] - expected).abs() < 1e-15 * expected);
        let point = Case::parse(BEAM, Some("x.toml"))
            .unwrap()
            .to_beam()
            .unwrap();
        assert!(point.bending_inertias().iter().all(|&j| j == 0.0));
        let msg = error_of(&BEAM.replace(
            "elements = 4\n",
            "elements = 4\nelement_inertia = \"rod\"\n",
        ));
        assert!(
            msg.contains("beam.element_inertia: must be one of \"point-mass\", \"bar\""),
            "{msg}"
        );
        let e = Case::parse(&format!("{BEAM}rotary_inertia = -1\n"), Some("x.toml"))
            .unwrap()
            .modes_plan()
            .unwrap_err();
        assert_eq!(e.key.as_deref(), Some("beam.section.rotary_inertia"), "{e}");
    }

    #[test]
    fn the_keys_of_a_table_are_its_serde_names() {
        assert_eq!(
            keys::<SectionSpec>(),
            [
                "EI",
                "mass_per_length",
                "GJ",
                "polar_inertia",
                "polar_inertia_about",
                "d0",
                "rotary_inertia",
                "EI_lag",
                "d0_normal",
                "rotary_inertia_lag",
                "coupling"
            ]
        );
        assert!(keys::<IntegrationSpec>().contains(&"spectral_radius"));
        assert_eq!(
            keys::<EquationsSpec>(),
            ["gyroscopic", "gyroscopic_step", "damping"]
        );
    }

    #[test]
    fn integers_are_accepted_for_floats() {
        let case = Case::parse(BEAM, Some("x.toml")).unwrap();
        let beam = case.to_beam().unwrap();
        assert_eq!(beam.n_elements(), 4);
    }

    #[test]
    fn keys_in_arrays_of_tables_get_their_index() {
        let load = "\n[[loads]]\ntype = \"gravity\"\n";
        let msg = error_of(&format!(
            "{BEAM}{load}{load}{}",
            load.replace("gravity", "gravitas")
        ));
        assert!(
            msg.starts_with(
                "x.toml line 16, column 8: loads[2].type: must be one of \"point-force\", \
                 \"moment\", \"torque\", \"distributed\", \"gravity\", got the text \"gravitas\""
            ),
            "{msg}"
        );
        let msg = error_of(&format!("{BEAM}{load}bogus = 1\n"));
        assert!(msg.contains(": loads[0]: unknown key `bogus`"), "{msg}");
    }

    #[test]
    fn errors_carry_file_line_column_and_key_as_data() {
        let e = Case::parse(&BEAM.replace("EI = 50", "EI = \"50\""), Some("x.toml")).unwrap_err();
        assert_eq!(e.file.as_deref(), Some("x.toml"));
        assert_eq!((e.line, e.column), (Some(6), Some(6)));
        assert_eq!(e.key.as_deref(), Some("beam.section.EI"));
        assert!(e.reason.starts_with("must be a number"), "{}", e.reason);
        let e = Case::from_toml_str(&BEAM.replace("length = 1.0", "length = -1.0"))
            .unwrap()
            .modes_plan()
            .unwrap_err();
        assert_eq!((e.file, e.line), (None, None));
        assert_eq!(e.key.as_deref(), Some("beam.length"));
    }

    #[test]
    fn any_serde_format_reads_the_same_keys_and_every_example_round_trips() {
        let json = serde_json::json!({
            "title": "t",
            "beam": { "length": 1.0, "elements": 4, "calibration": "uniform",
                      "section": { "EI": 50, "mass_per_length": { "x": [0.0, 1.0], "value": [0.3, 0.1] } } },
            "loads": [{ "name": "F", "type": "point-force", "node": 4, "direction": "dead", "fy": 1.0,
                        "time": { "type": "sine", "omega": 20.0 } }],
            "dynamic": { "end_time": 1.0, "output_step": 0.5, "integrator": "bdf", "max_order": 3 }
        });
        let case_json = json.clone();
        let case = Case::from_deserializer(json).unwrap();
        let plan = case.dynamic_plan().unwrap();
        assert_eq!(plan.integrator, flexwing::solve::integrate::Method::Bdf);
        assert_eq!(plan.settings.max_order, 3);
        assert_eq!(
            Case::from_toml_str(&case.to_toml_string().unwrap()).unwrap(),
            case
        );
        let mut bad = case_json;
        bad["beam"]["sections"] = serde_json::json!(1);
        let e = Case::from_deserializer(bad).unwrap_err();
        assert!(e.reason.starts_with("unknown key `sections`"), "{e}");
        let examples = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
        let mut count = 0;
        for entry in std::fs::read_dir(examples).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "toml") {
                let case = Case::load(&path).unwrap();
                let text = case.to_toml_string().unwrap();
                let mut again =
                    Case::from_toml_str(&text).unwrap_or_else(|e| panic!("{text}\n{e}"));
                again.file.clone_from(&case.file);
                assert_eq!(again, case, "{}", path.display());
                count += 1;
            }
        }
        assert!(count >= 9, "{count} examples");
    }
}
