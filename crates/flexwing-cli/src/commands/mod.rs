//! One module per subcommand. Each returns a [`Failure`] that says whether the input or the run
//! was at fault, which decides the exit status.

pub mod dynamic;
pub mod flutter;
pub mod modes;
pub mod reproduce;
pub mod statics;

use std::fmt::Display;
use std::path::{Path, PathBuf};

use flexwing::analysis::Stop;
use flexwing::beam::Calibration;
use flexwing::model::FullModel;
use flexwing::solve::aeroelastic::FlutterStop;
use flexwing::text::short;

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
    format!(
        "model: {} elements, {} dofs, {} calibration, {kind}",
        model.n_elements(),
        model.n_dofs(),
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

/// Something that did not complete (a model's run, the loaded modes), for `status.txt`, stdout
/// and stderr.
#[derive(Debug, Clone)]
pub struct Incomplete {
    /// The model label, or `loaded modes`.
    pub what: String,
    /// One-line reason, naming where the solver stopped.
    pub message: String,
}

/// `complete`, or one line `incomplete: WHAT: MESSAGE` per thing that did not complete: the text
/// of `status.txt`.
pub fn status_text(incomplete: &[Incomplete]) -> String {
    if incomplete.is_empty() {
        return "complete\n".into();
    }
    incomplete
        .iter()
        .map(|i| format!("incomplete: {}: {}\n", i.what, i.message))
        .collect()
}

/// One line saying why a run stopped. `sweep` is the name of the swept load of a static sweep,
/// `initial` the names of the loads of a static initial state.
pub fn stop_message(stop: &Stop, sweep: Option<&str>, initial: &[String]) -> String {
    match stop {
        Stop::Integration(e) => e.to_string(),
        Stop::InitialState(e) => format!(
            "the initial static deflection under {} failed: {e}",
            initial.join(", ")
        ),
        Stop::StaticPoint {
            point,
            points,
            scale,
            reached,
            error,
        } => match sweep {
            Some(name) => {
                let reached = reached
                    .map(|r| format!(", converged up to scale {}", short(r)))
                    .unwrap_or_default();
                format!(
                    "stopped at sweep point {} of {points} ({name} scale {}{reached}): {error}",
                    point + 1,
                    short(*scale),
                )
            }
            None => error.to_string(),
        },
        Stop::Equations(e) => e.to_string(),
        Stop::SpeedPoint {
            point,
            points,
            speed,
            error,
        } => format!(
            "stopped at speed {} of {points} (U = {} m/s): {error}",
            point + 1,
            short(*speed)
        ),
        Stop::Flutter(FlutterStop::Equilibrium { speed, error }) => format!(
            "no static equilibrium at U = {} m/s: {error}",
            short(*speed)
        ),
        Stop::Flutter(FlutterStop::BranchLost { branch, speed }) => format!(
            "branch {} lost at U = {} m/s (Newton's method failed even at the smallest speed \
             step; refine the sweep)",
            branch + 1,
            short(*speed)
        ),
        Stop::EnergyLimit { time, ratio, limit } => format!(
            "stopped at t = {} s: the energy grew to {ratio:.3} times its initial value \
             (a blown-up run; limit {limit})",
            short(*time)
        ),
        other => format!("{other:?}"),
    }
}
