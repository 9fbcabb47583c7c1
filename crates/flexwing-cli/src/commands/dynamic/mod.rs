//! `flexwing dynamic`: time histories of the full model, the simplified model (gyroscopic term
//! neglected) and reduced models, from rest, from a static deflection or from a given state, under
//! the case's time-varying loads.
//!
//! A model whose integration stops does not stop the run: the other models are simulated, every
//! file holds the output times that were reached, `status.txt` says which model stopped where,
//! and the command exits with status 1.

mod aero;
mod files;
mod progress;
mod report;

use std::io::IsTerminal as _;
use std::path::PathBuf;

use clap::Args;
use flexwing::analysis::dynamics::{self, DynamicOutcome, DynamicRun, Initial};
use flexwing::Error;

use super::{default_out_dir, model_line, overall_word, status_entry, Failure};
use flexwing_case::Case;
use progress::Progress;

/// Most node snapshots per model in `dynamic_nodes.csv`: with more output times, every k-th is
/// written.
pub const MAX_NODE_SNAPSHOTS: usize = 201;
/// Number of intervals between the snapshots of the snapshot plot (so 11 shapes).
pub const PLOT_SNAPSHOT_INTERVALS: usize = 10;

/// Options of `flexwing dynamic`.
#[derive(Debug, Args)]
pub struct DynamicArgs {
    /// Case file (TOML) with [dynamic] and usually [[loads]]; see docs/case-file.md.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write dynamic_tip.svg/.png (tip histories) and dynamic_snapshots.svg/.png (deformed
    /// shapes of the first model).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the table (and never a progress bar).
    #[arg(long)]
    pub json: bool,
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
    /// Span (m).
    pub length: f64,
    /// One line per load, with its time history.
    pub loads: Vec<String>,
    /// One line describing the initial state.
    pub initial: String,
    /// Lines describing the damping and the integrator settings.
    pub settings: report::PlanLines,
    /// Simulated time (s).
    pub end_time: f64,
    /// The planned output times (s).
    pub output_times: Vec<f64>,
    /// Indices of the output times written to `dynamic_nodes.csv`.
    pub node_indices: Vec<usize>,
    /// Indices of the output times of the snapshot plot.
    pub plot_indices: Vec<usize>,
    /// What the analysis produced.
    pub result: DynamicOutcome,
    /// What did not complete.
    pub incomplete: Vec<Incomplete>,
}

impl Outcome {
    /// The simulated models, in the order run.
    pub fn runs(&self) -> &[DynamicRun] {
        &self.result.runs
    }

    /// `complete`, `suspect`, `incomplete` or `interrupted` ([`overall_word`]).
    pub fn status(&self) -> &'static str {
        overall_word(&self.incomplete)
    }

    /// `LABEL: MESSAGE` of everything incomplete, joined by `; `; `None` when complete.
    pub fn error(&self) -> Option<String> {
        super::error_text(&self.incomplete)
    }

    /// Why `run` did not complete, if it did not.
    pub fn message_of(&self, run: &DynamicRun) -> Option<&str> {
        let label = run.kind.label();
        self.incomplete
            .iter()
            .find(|i| i.what == label)
            .map(|i| i.message.as_str())
    }
}

/// Run the command.
pub fn run(args: &DynamicArgs) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let case = Case::load(&args.case).map_err(Failure::input)?;
    if case.is_aeroelastic() {
        return aero::run(args, &case);
    }
    let mut plan = case.dynamic_plan().map_err(Failure::input)?;
    let n_out = plan.output_times.len();
    let node_indices = node_indices(n_out);
    let plot_indices = plot_indices(n_out);
    plan.snapshots = node_indices.iter().chain(&plot_indices).copied().collect();

    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    crate::output::prepare_dir(&dir, files::FILES, true).map_err(Failure::Run)?;

    let show_progress = !args.json && std::io::stderr().is_terminal();
    let mut progress = Progress::new(show_progress);
    super::interrupt::catch_interrupts(false);
    let result = dynamics::run(&plan, &mut progress).map_err(|e| match e {
        Error::Input(e) => Failure::input(format!("{name}: {e}")),
        e => Failure::run(format!(
            "{name}: modal analysis about the undeformed state failed: {e}"
        )),
    })?;
    let initial_names: Vec<String> = match &plan.initial {
        Initial::Static { loads } => loads.iter().map(|&i| load_name(&case, i)).collect(),
        _ => Vec::new(),
    };
    let incomplete = result
        .runs
        .iter()
        .filter_map(|r| status_entry(&r.kind.label(), &r.status, None, &initial_names))
        .collect();
    let full = &plan.model;
    let outcome = Outcome {
        case_name: name.clone(),
        title: case.title.clone(),
        model_line: model_line(full),
        n_elements: full.n_elements(),
        has_torsion: full.has_torsion(),
        length: full.beam().length(),
        loads: report::describe_loads(&case, &plan),
        initial: report::describe_initial(&plan.initial, &initial_names),
        settings: report::PlanLines::of(&plan),
        end_time: plan.end_time,
        output_times: plan.output_times.clone(),
        node_indices,
        plot_indices,
        result,
        incomplete,
    };

    let written = files::write_files(&dir, &outcome, &case, args.plot).map_err(Failure::Run)?;
    let text = if args.json {
        report::json(&outcome, &written)
    } else {
        report::tables(&outcome, &written)
    };
    let printed = super::print_stdout(&text, args.json);
    for r in &outcome.result.runs {
        for note in &r.notes {
            eprintln!("note: {name}: {}: {note}", r.kind.label());
        }
    }
    if let Some(first) = outcome.incomplete.first() {
        let others: Vec<&str> = outcome.incomplete[1..]
            .iter()
            .map(|i| i.what.as_str())
            .collect();
        let also = if others.is_empty() {
            String::new()
        } else {
            format!(
                " (also not complete: {}; see status.txt)",
                others.join(", ")
            )
        };
        return Err(Failure::run(format!(
            "{name}: {}: {}: {}{also}",
            first.what, first.word, first.message
        )));
    }
    printed
}

/// The name of load `i` of the case, or `loads[i]`.
fn load_name(case: &Case, i: usize) -> String {
    case.loads[i]
        .name
        .clone()
        .unwrap_or_else(|| format!("loads[{i}]"))
}

/// Indices of the output times written to `dynamic_nodes.csv`: all of them up to
/// [`MAX_NODE_SNAPSHOTS`], else every k-th from the first with `k = ⌈n / MAX⌉`.
pub fn node_indices(n: usize) -> Vec<usize> {
    let k = n.div_ceil(MAX_NODE_SNAPSHOTS).max(1);
    (0..n).step_by(k).collect()
}

/// Indices of about [`PLOT_SNAPSHOT_INTERVALS`] + 1 evenly spaced output times, first and last
/// included.
pub fn plot_indices(n: usize) -> Vec<usize> {
    if n <= PLOT_SNAPSHOT_INTERVALS + 1 {
        return (0..n).collect();
    }
    let mut v: Vec<usize> = (0..=PLOT_SNAPSHOT_INTERVALS)
        .map(|j| ((j * (n - 1)) as f64 / PLOT_SNAPSHOT_INTERVALS as f64).round() as usize)
        .collect();
    v.dedup();
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_snapshots_are_capped() {
        assert_eq!(node_indices(5), [0, 1, 2, 3, 4]);
        assert_eq!(node_indices(201).len(), 201);
        let v = node_indices(202);
        assert_eq!(v[1], 2);
        assert!(v.len() <= MAX_NODE_SNAPSHOTS);
        let v = node_indices(100_000);
        assert!(
            v.len() <= MAX_NODE_SNAPSHOTS && v.len() > 190,
            "{}",
            v.len()
        );
    }

    #[test]
    fn plot_snapshots_are_evenly_spaced() {
        assert_eq!(plot_indices(3), [0, 1, 2]);
        let v = plot_indices(201);
        assert_eq!(v.len(), 11);
        assert_eq!(v[1], 20);
        assert_eq!(v[10], 200);
    }
}
