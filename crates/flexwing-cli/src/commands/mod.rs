//! One module per subcommand. Each returns a [`Failure`] that says whether the input or the run
//! was at fault, which decides the exit status.

pub mod dynamic;
pub mod flutter;
pub mod interrupt;
pub mod modes;
pub mod reproduce;
pub mod statics;

use std::fmt::Display;
use std::path::{Path, PathBuf};

use flexwing::analysis::{Doubt, Status, Stop};
use flexwing::beam::Calibration;
use flexwing::model::FullModel;

/// Set once a command has printed its JSON document on stdout, so that `main` prints the
/// error document of `--json` only when none was printed: stdout always holds exactly one.
pub static JSON_PRINTED: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Print `text` (a command's output) on stdout; with `json`, mark the JSON document printed.
pub fn print_stdout(text: &str, json: bool) -> Result<(), Failure> {
    use std::io::Write as _;
    if json {
        JSON_PRINTED.store(true, std::sync::atomic::Ordering::SeqCst);
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| Failure::run(format!("cannot write to standard output: {e}")))
}

/// Why a command failed.
#[derive(Debug)]
pub enum Failure {
    /// The input is wrong (command line or case file): exit status 2.
    Input(anyhow::Error),
    /// The run failed (a solver, or writing the results): exit status 1.
    Run(anyhow::Error),
}

impl Failure {
    /// A bad-input failure with the given message.
    pub fn input(message: impl Display) -> Self {
        Self::Input(anyhow::anyhow!("{message}"))
    }
    /// A run failure with the given message.
    pub fn run(message: impl Display) -> Self {
        Self::Run(anyhow::anyhow!("{message}"))
    }
    /// Exit status of the process.
    pub fn exit_status(&self) -> u8 {
        match self {
            Self::Input(_) => 2,
            Self::Run(_) => 1,
        }
    }
    /// The error, for printing.
    pub fn error(&self) -> &anyhow::Error {
        match self {
            Self::Input(e) | Self::Run(e) => e,
        }
    }
}

/// `results/<case file stem>`, relative to the working directory.
pub fn default_out_dir(case: &Path) -> PathBuf {
    let stem = case
        .file_stem()
        .map_or_else(|| "case".into(), |s| s.to_string_lossy().into_owned());
    Path::new("results").join(stem)
}

/// The case-file spelling of a calibration.
pub fn calibration_name(c: Calibration) -> &'static str {
    match c {
        Calibration::TipLoad => "tip-load",
        Calibration::Uniform => "uniform",
    }
}

/// One line describing the model: elements, dofs, calibration, torsion.
pub fn model_line(model: &FullModel) -> String {
    let beam = model.beam();
    let kind = if !model.has_torsion() {
        "bending only"
    } else if beam.offsets().iter().any(|&d| d != 0.0) {
        "bending and torsion coupled by the mass-centre offset d0"
    } else {
        "bending and torsion, uncoupled (d0 = 0)"
    };
    let (n, dofs) = (model.n_elements(), model.n_dofs());
    format!(
        "model: {n} element{}, {dofs} dof{}, {} calibration, {kind}",
        if n == 1 { "" } else { "s" },
        if dofs == 1 { "" } else { "s" },
        calibration_name(beam.calibration()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exit_statuses() {
        assert_eq!(Failure::input("bad key").exit_status(), 2);
        assert_eq!(Failure::run("solver failed").exit_status(), 1);
    }
}

/// Something that did not complete (a model's run, the loaded modes), or whose result is
/// doubtful, for `status.txt`, stdout and stderr.
#[derive(Debug, Clone)]
pub struct Incomplete {
    /// The model label, or `loaded modes`.
    pub what: String,
    /// One-line reason, naming where the solver stopped or what check failed.
    pub message: String,
    /// `stopped`, `interrupted` (by the user) or `suspect` (reached its end, but a
    /// check of the result failed).
    pub word: &'static str,
}

impl Incomplete {
    /// A run that stopped.
    pub fn stopped(what: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            what: what.into(),
            message: message.into(),
            word: "stopped",
        }
    }
}

/// The word of a whole run: `complete` when nothing is listed, else the worst of the list:
/// `interrupted`, then `stopped`, then `suspect`.
pub fn overall_word(incomplete: &[Incomplete]) -> &'static str {
    ["interrupted", "stopped", "suspect"]
        .into_iter()
        .find(|w| incomplete.iter().any(|i| i.word == *w))
        .unwrap_or("complete")
}

/// The word of one model's run in the reports: `complete`, `suspect`, `incomplete`, or
/// `interrupted` when the user stopped it.
pub fn run_word(status: &Status) -> &'static str {
    match status.stop() {
        Some(Stop::Interrupted { .. } | Stop::SweepInterrupted { .. }) => "interrupted",
        _ => status.word(),
    }
}

/// `WHAT: MESSAGE` of everything listed, joined by `; `; `None` when nothing is: the `error` of
/// a JSON document.
pub fn error_text(incomplete: &[Incomplete]) -> Option<String> {
    (!incomplete.is_empty()).then(|| {
        incomplete
            .iter()
            .map(|i| format!("{}: {}", i.what, i.message))
            .collect::<Vec<_>>()
            .join("; ")
    })
}

/// `complete`, or one line `WORD: WHAT: MESSAGE` per thing that did not complete or is suspect:
/// the text of `status.txt`.
pub fn status_text(incomplete: &[Incomplete]) -> String {
    if incomplete.is_empty() {
        return "complete\n".into();
    }
    incomplete
        .iter()
        .map(|i| format!("{}: {}: {}\n", i.word, i.what, i.message))
        .collect()
}

/// What went wrong with a run of `status`, if anything: the stop (worded by [`stop_message`]) or
/// the doubt ([`doubt_message`]).
pub fn status_entry(
    what: &str,
    status: &Status,
    sweep: Option<&str>,
    initial: &[String],
) -> Option<Incomplete> {
    match status {
        Status::Stopped(stop @ (Stop::Interrupted { .. } | Stop::SweepInterrupted { .. })) => {
            Some(Incomplete {
                what: what.into(),
                message: stop_message(stop, sweep, initial),
                word: "interrupted",
            })
        }
        Status::Stopped(stop) => Some(Incomplete::stopped(
            what,
            stop_message(stop, sweep, initial),
        )),
        Status::Suspect(doubt) => Some(Incomplete {
            what: what.into(),
            message: doubt_message(doubt),
            word: "suspect",
        }),
        _ => None,
    }
}

/// One line saying why a result is doubtful.
pub fn doubt_message(doubt: &Doubt) -> String {
    doubt.to_string()
}

/// One line saying why a run stopped.
pub fn stop_message(stop: &Stop, _sweep: Option<&str>, _initial: &[String]) -> String {
    stop.to_string()
}
