//! `flexwing flutter`: divergence and flutter speeds along a sweep in free-stream speed, for the
//! full model and reduced models on its wet modes (`flexwing::analysis::aero::flutter`), with the
//! V-g/V-ω data, the static equilibria along the sweep and, optionally, the p-k check with
//! Theodorsen's function.
//!
//! A model whose eigen-analysis stops early does not stop the run: the other models are analysed,
//! every file is written with the speeds reached, `status.txt` says what stopped where, and the
//! command exits with status 1. Equilibria that stop past the divergence speed are expected (no
//! stable equilibrium exists there) and are reported as a note, not as a failure.

mod files;
mod report;

use std::path::PathBuf;

use clap::Args;
use flexwing::analysis::aero::flutter::{self, FlutterOutcome, FlutterRun};
use flexwing::analysis::Note;
use flexwing::model::aero::Aerodynamics;
use flexwing::Error;

use super::{default_out_dir, model_line, stop_message, Failure, Incomplete};
use flexwing_case::Case;

/// Options of `flexwing flutter`.
#[derive(Debug, Args)]
pub struct FlutterArgs {
    /// Case file (TOML) with [aero] and [aero.sweep], optionally [flutter]; see
    /// docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write flutter_vg.svg/.png (V-g and V-ω) and flutter_shapes.svg/.png (equilibria).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the tables.
    #[arg(long)]
    pub json: bool,
}

/// Everything the reports and files need.
#[derive(Debug)]
pub struct Outcome {
    /// Path of the case file as given.
    pub case_name: String,
    /// The case's title.
    pub title: Option<String>,
    /// One line describing the full model.
    pub model_line: String,
    /// One line describing the aerodynamics.
    pub aero_line: String,
    /// Span (m), for the shape plot.
    pub length: f64,
    /// The speeds of the sweep (m/s).
    pub speeds: Vec<f64>,
    /// What the analysis found.
    pub result: FlutterOutcome,
    /// What did not complete.
    pub incomplete: Vec<Incomplete>,
    /// Notes: equilibria that stopped (past divergence), branches unstable from the start.
    pub notes: Vec<String>,
}

impl Outcome {
    /// The analysed models, in the plan's order.
    pub fn runs(&self) -> &[FlutterRun] {
        &self.result.runs
    }

    /// `complete`, `incomplete` or `interrupted` ([`super::overall_word`]).
    pub fn status(&self) -> &'static str {
        super::overall_word(&self.incomplete)
    }

    /// Why `run` did not complete, if it did not.
    pub fn message_of(&self, run: &FlutterRun) -> Option<&str> {
        let label = run.kind.label();
        self.incomplete
            .iter()
            .find(|i| i.what == label)
            .map(|i| i.message.as_str())
    }

    /// `LABEL: MESSAGE` of everything incomplete, joined by `; `; `None` when complete.
    pub fn error(&self) -> Option<String> {
        super::error_text(&self.incomplete)
    }
}

/// One line naming the aerodynamic model and the air.
pub fn aero_line(aerodynamics: Aerodynamics, density: f64) -> String {
    let model = match aerodynamics {
        Aerodynamics::Steady => "steady strip theory".to_string(),
        Aerodynamics::QuasiSteady => "quasi-steady (C(k) = 1) with apparent mass".to_string(),
        Aerodynamics::Wagner => {
            "Wagner's function (R. T. Jones, 2 states per strip) with apparent mass".to_string()
        }
        Aerodynamics::Peters { states } => {
            format!("Peters' finite-state inflow ({states} states per strip) with apparent mass")
        }
    };
    format!(
        "aerodynamics: {model}, air density {} kg/m³",
        crate::output::short(density)
    )
}

/// Run the command.
pub fn run(args: &FlutterArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let case = Case::load(&args.case).map_err(Failure::input)?;
    let plan = case.flutter_plan().map_err(Failure::input)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    crate::output::prepare_dir(&dir, files::FILES, true).map_err(Failure::Run)?;
    super::interrupt::catch_interrupts(true);
    let result = flutter::run(&plan, &mut super::interrupt::Cancel).map_err(|e| match e {
        Error::Input(e) => Failure::input(format!("{name}: {e}")),
        e => Failure::run(format!("{name}: {e}")),
    })?;
    let mut incomplete = Vec::new();
    let mut notes = Vec::new();
    for r in &result.runs {
        let label = r.kind.label();
        if let Some(entry) = super::status_entry(&label, &r.status, None, &[]) {
            incomplete.push(entry);
        }
        for stop in &r.other_stops {
            incomplete.push(Incomplete::stopped(
                format!("{label} p-k"),
                stop_message(stop, None, &[]),
            ));
        }
        for note in &r.notes {
            let what = match note {
                Note::UnstableAtStart { pk: true, .. } => " p-k",
                _ => "",
            };
            notes.push(format!("{label}{what}: {note}"));
        }
    }
    let full = &plan.model;
    let outcome = Outcome {
        case_name: name.clone(),
        title: case.title.clone(),
        model_line: model_line(full),
        aero_line: aero_line(plan.aero.aerodynamics, plan.aero.density),
        length: full.beam().length(),
        speeds: plan.speeds().to_vec(),
        result,
        incomplete,
        notes,
    };
    let written = files::write_files(&dir, &outcome, args.plot).map_err(Failure::Run)?;
    let text = if args.json {
        report::json(&outcome, &written)
    } else {
        report::tables(&outcome, &written)
    };
    let printed = super::print_stdout(&text, args.json);
    if let Some(first) = outcome.incomplete.first() {
        return Err(Failure::run(format!(
            "{name}: {}: {} (see status.txt)",
            first.what, first.message
        )));
    }
    printed
}
