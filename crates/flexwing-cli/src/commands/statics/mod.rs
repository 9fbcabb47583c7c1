//! `flexwing static`: non-linear static equilibria of the full model and of reduced models,
//! at one load level or over a load sweep continued from point to point.
//!
//! A model whose sweep stops early does not stop the run: the other models are solved, every
//! file is written with the points that converged, `status.txt` says what stopped where, and the
//! command exits with status 1.

mod aero;
mod files;
pub(crate) mod report;

use std::path::PathBuf;

use clap::Args;
use flexwing::analysis::statics::{self, LoadedMode, StaticOutcome, StaticRun};
use flexwing::model::Load;
use flexwing::Error;

use super::{default_out_dir, model_line, overall_word, status_entry, Failure};
use flexwing_case::Case;

/// Options of `flexwing static`.
#[derive(Debug, Args)]
pub struct StaticArgs {
    /// Case file (TOML) with [[loads]] and optionally [static]; see docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write static_shapes.svg and static_shapes.png (deformed shapes of every point).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the tables.
    #[arg(long)]
    pub json: bool,
}

/// A sweep as the reports show it: the swept load's name and its scales.
#[derive(Debug, Clone)]
pub struct NamedSweep {
    /// Name of the swept load.
    pub name: String,
    /// Its scale at each point.
    pub scales: Vec<f64>,
}

pub use super::Incomplete;

/// Everything the reports and files need: the case's context and the library's outcome.
#[derive(Debug)]
pub struct Outcome {
    /// Path of the case file as given.
    pub case_name: String,
    /// The case's title.
    pub title: Option<String>,
    /// One line describing the full model.
    pub model_line: String,
    /// Number of elements.
    pub n_elements: usize,
    /// Whether the model has torsion.
    pub has_torsion: bool,
    /// One line per load.
    pub loads: Vec<String>,
    /// The sweep, if any.
    pub sweep: Option<NamedSweep>,
    /// Scale of the swept load at each point (`[1]` without a sweep).
    pub scales: Vec<f64>,
    /// What the analysis found.
    pub result: StaticOutcome,
    /// What did not complete.
    pub incomplete: Vec<Incomplete>,
}

impl Outcome {
    /// The solved models, the full model first.
    pub fn runs(&self) -> &[StaticRun] {
        &self.result.runs
    }

    /// The loaded modes, if computed.
    pub fn loaded_modes(&self) -> Option<&[LoadedMode]> {
        match &self.result.loaded_modes {
            Some(Ok(m)) => Some(m),
            _ => None,
        }
    }

    /// Why `run` did not complete, if it did not.
    pub fn message_of(&self, run: &StaticRun) -> Option<&str> {
        let label = run.kind.label();
        self.incomplete
            .iter()
            .find(|i| i.what == label)
            .map(|i| i.message.as_str())
    }

    /// `complete`, `suspect`, `incomplete` or `interrupted` ([`overall_word`]).
    pub fn status(&self) -> &'static str {
        overall_word(&self.incomplete)
    }

    /// `LABEL: MESSAGE` of everything incomplete, joined by `; `; `None` when complete.
    pub fn error(&self) -> Option<String> {
        super::error_text(&self.incomplete)
    }
}

/// Run the command.
pub fn run(args: &StaticArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let case = Case::load(&args.case).map_err(Failure::input)?;
    if case.is_aeroelastic() {
        return aero::run(args, &case);
    }
    let plan = case.static_plan().map_err(Failure::input)?;
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    crate::output::prepare_dir(&dir, files::FILES, true).map_err(Failure::Run)?;
    super::interrupt::catch_interrupts(true);
    let result = statics::run(&plan, &mut super::interrupt::Cancel).map_err(|e| match e {
        Error::Input(e) => Failure::input(format!("{name}: {e}")),
        e => Failure::run(format!(
            "{name}: modal analysis about the undeformed state failed: {e}"
        )),
    })?;
    let sweep = plan.sweep.as_ref().map(|s| NamedSweep {
        name: case.loads[s.load].name.clone().unwrap_or_default(),
        scales: s.scales.clone(),
    });
    let mut incomplete: Vec<Incomplete> = result
        .runs
        .iter()
        .filter_map(|r| {
            let sweep = sweep.as_ref().map(|s| s.name.as_str());
            status_entry(&r.kind.label(), &r.status, sweep, &[])
        })
        .collect();
    if let Some(Err(e)) = &result.loaded_modes {
        incomplete.push(Incomplete::stopped("loaded modes", e.to_string()));
    }
    let full = &plan.model;
    let outcome = Outcome {
        case_name: name.clone(),
        title: case.title.clone(),
        model_line: model_line(full),
        n_elements: full.n_elements(),
        has_torsion: full.has_torsion(),
        loads: describe_loads(&case, &plan.loads),
        sweep,
        scales: plan.point_scales(),
        result,
        incomplete,
    };

    let written =
        files::write_files(&dir, &outcome, full, &case, args.plot).map_err(Failure::Run)?;
    let text = if args.json {
        report::json(&outcome, &written)
    } else {
        report::tables(&outcome, &written)
    };
    let printed = super::print_stdout(&text, args.json);
    if let Some(first) = outcome.incomplete.first() {
        let others: Vec<&str> = outcome.incomplete[1..]
            .iter()
            .map(|i| i.what.as_str())
            .collect();
        let also = if others.is_empty() {
            String::new()
        } else {
            format!(" (also incomplete: {}; see status.txt)", others.join(", "))
        };
        return Err(Failure::run(format!(
            "{name}: {}: {}{also}",
            first.what, first.message
        )));
    }
    printed
}

/// One line per load, for the table report.
fn describe_loads(case: &Case, loads: &[Load]) -> Vec<String> {
    loads
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let name = case.loads[i]
                .name
                .clone()
                .unwrap_or_else(|| format!("loads[{i}]"));
            format!("{name}: {}", report::describe_load(l))
        })
        .collect()
}
