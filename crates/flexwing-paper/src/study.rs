//! The whole study in the report's order: every part computed ([`Study::run`]; a part that
//! fails is recorded and the others go on), then its sections for the front end to write
//! ([`Study::sections`]) and the conclusions of the parts that completed
//! ([`Study::conclusions`]).

use crate::accuracy::{self, AccuracyRow};
use crate::modal::{self, ModalStudy};
use crate::release::{self, ReleaseStudy};
use crate::sine::{self, SineStudy};
use crate::statics::{self, TipForceStudy, TwoForceStudy};
use crate::{report, Section};

/// The name of the accuracy section's part: its conclusions need the section written.
pub const ACCURACY: &str = "reduced accuracy";

/// Every part of the study that completed, and why the others did not.
pub struct Study {
    /// Table 2.
    pub modal: Option<ModalStudy>,
    /// Table 3.
    pub tip_force: Option<TipForceStudy>,
    /// Table 5 and Figure 4.
    pub two_forces: Option<TwoForceStudy>,
    /// Tables 6 and 8, Figure 6.
    pub sine: Option<SineStudy>,
    /// Table 7 and Figure 5, the energy drift.
    pub release: Option<ReleaseStudy>,
    /// The parts that failed: `(part, why)`.
    pub failed: Vec<(String, String)>,
    /// Timing samples per measured computation.
    pub repeats: usize,
}

impl Study {
    /// Run every part with `repeats` timing samples and the long free vibration of `long_run`
    /// seconds; `progress(step, steps, what)` before each step, `failed(part, why)` when a part
    /// fails.
    pub fn run(
        repeats: usize,
        long_run: f64,
        progress: &mut dyn FnMut(usize, usize, &str),
        failed: &mut dyn FnMut(&str, &str),
    ) -> Self {
        let mut failures = Vec::new();
        let mut attempt = |part: &str, e: anyhow::Error| {
            let why = format!("{e:#}");
            failed(part, &why);
            failures.push((part.to_string(), why));
        };
        const STEPS: usize = 5;
        progress(1, STEPS, "Table 2: natural frequencies");
        let modal = modal::run(repeats).map_err(|e| attempt("Table 2", e)).ok();
        progress(2, STEPS, "Tables 3 and 5, Figure 4: static cases");
        let tip_force = statics::tip_force(repeats)
            .map_err(|e| attempt("Table 3", e))
            .ok();
        let two_forces = statics::two_forces(repeats)
            .map_err(|e| attempt("Table 5 and Figure 4", e))
            .ok();
        progress(3, STEPS, "Tables 6 and 8, Figure 6: sinusoidal tip force");
        let sine = sine::run(repeats)
            .map_err(|e| attempt("Tables 6 and 8, Figure 6", e))
            .ok();
        progress(
            4,
            STEPS,
            "Table 7, Figure 5: free vibration, full against simplified",
        );
        let release = release::run(repeats, long_run)
            .map_err(|e| attempt("Table 7 and Figure 5", e))
            .ok();
        progress(5, STEPS, "accuracy of the reduced models, report");
        Study {
            modal,
            tip_force,
            two_forces,
            sine,
            release,
            failed: failures,
            repeats,
        }
    }

    /// The accuracy of every reduced model of the static and sinusoidal cases.
    pub fn accuracy(&self) -> Vec<AccuracyRow> {
        (self.tip_force.iter().flat_map(TipForceStudy::accuracy))
            .chain(self.two_forces.iter().flat_map(TwoForceStudy::accuracy))
            .chain(self.sine.iter().flat_map(SineStudy::accuracy))
            .collect()
    }

    /// The report's sections in the paper's order, each with the part it belongs to: Table 2,
    /// 3, Table 5 and Figure 4, Table 6 (γ), Table 7 and Figure 5, Table 8 and Figure 6, the
    /// accuracy ([`ACCURACY`]), the energy drift.
    pub fn sections(&self) -> Vec<(&'static str, Section)> {
        let repeats = self.repeats;
        let sine = "Tables 6 and 8, Figure 6";
        let release = "Table 7 and Figure 5";
        let mut v = Vec::new();
        v.extend(self.modal.as_ref().map(|s| ("Table 2", s.section())));
        v.extend(
            self.tip_force
                .as_ref()
                .map(|s| ("Table 3", s.section(repeats))),
        );
        let two = self.two_forces.as_ref();
        v.extend(two.map(|s| ("Table 5 and Figure 4", s.section())));
        v.extend(self.sine.as_ref().map(|s| (sine, s.gamma.section(repeats))));
        v.extend(self.release.as_ref().map(|s| (release, s.section(repeats))));
        v.extend(self.sine.as_ref().map(|s| (sine, s.section(repeats))));
        v.push((ACCURACY, accuracy::section(&self.accuracy())));
        v.extend(self.release.as_ref().map(|s| (release, s.energy_section())));
        v
    }

    /// The conclusions of the parts that completed, then a line per part in `failed` (those
    /// of [`Study::run`] and whatever failed writing the sections); the reduced models' accuracy
    /// is concluded on only when its section was written (`accuracy_written`).
    pub fn conclusions(&self, failed: &[(String, String)], accuracy_written: bool) -> String {
        let needed = if accuracy_written {
            accuracy::modes_needed(&self.accuracy())
        } else {
            Vec::new()
        };
        let mut s = report::conclusions(
            self.modal.as_ref(),
            self.sine.as_ref(),
            self.release.as_ref(),
            &needed,
        );
        for (what, message) in failed {
            s.push_str(&format!(
                "- **{what} did not complete:** {message} Its conclusions are missing above.\n"
            ));
        }
        s
    }
}
