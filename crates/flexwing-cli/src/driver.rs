//! The one driver of `flexwing modes`, `static`, `dynamic`, `flutter`, `linearize`, `study` and
//! `gust`: read the case, build its plan (`Case::plan`: aeroelastic with `[aero]`), prepare the output folder, catch
//! interrupts, run the library's one dispatcher (`flexwing::analysis::run`), render the outcome
//! (`render`: files, then the table or the JSON document), write `status.txt`, print the notes,
//! and turn what did not complete into the exit status.

use std::io::IsTerminal as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

use clap::Args;
use flexwing::analysis::chain3d::Analysis3d;
use flexwing::analysis::modes::ModesPlan;
use flexwing::analysis::{self, Entry, NoProgress, Plan, Progress};
use flexwing::Error;
use flexwing_case::{Analysis, Case};

use crate::render::{self, Context, View};
use crate::{interrupt, output};

/// The options every analysis command takes.
#[derive(Debug, Args)]
pub struct CaseArgs {
    /// Case file (TOML); see docs/case-file.md for the keys.
    #[arg(value_name = "CASE.toml")]
    pub case: PathBuf,

    /// Directory for the result files (created if needed) [default: results/<case file stem>].
    #[arg(long, short, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Also write the command's plots, SVG and PNG (see the command's --help for which).
    #[arg(long)]
    pub plot: bool,

    /// Print one JSON document on stdout instead of the tables (and never a progress bar).
    #[arg(long)]
    pub json: bool,
}

/// The output options of the commands that write node histories or VTK files; each overrides
/// its `[output]` key (docs/case-file.md).
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Format of the node histories: `csv` or `npz` (NumPy); overrides `[output] format`
    /// [default: csv].
    #[arg(long, value_name = "FORMAT", value_parser = ["csv", "npz"])]
    pub format: Option<String>,

    /// Most output times in the node histories, a whole number ≥ 1 or `all`; overrides
    /// `[output] node_times` [default: 201].
    #[arg(long, value_name = "N|all")]
    pub node_times: Option<String>,

    #[command(flatten)]
    pub vtk: VtkArgs,
}

/// `--vtk` of `flexwing modes`, `static` and `dynamic`.
#[derive(Debug, Args)]
pub struct VtkArgs {
    /// Also write VTK XML files for ParaView into DIR/vtk (a .vtu per output time, load step or
    /// mode, a .pvd per model); sets `[output] vtk = true`.
    #[arg(long)]
    pub vtk: bool,
}

impl OutputArgs {
    /// Change `output` as the options say.
    fn apply(&self, output: &mut flexwing_case::OutputSpec) -> Result<(), Failure> {
        use flexwing_case::{NodeTimesSpec, OutputFormatSpec};
        if let Some(f) = &self.format {
            output.format = Some(match f.as_str() {
                "npz" => OutputFormatSpec::Npz,
                _ => OutputFormatSpec::Csv,
            });
        }
        if let Some(n) = &self.node_times {
            output.node_times = Some(match (n.as_str(), n.parse::<usize>()) {
                ("all", _) => NodeTimesSpec::All,
                (_, Ok(k)) if k >= 1 => NodeTimesSpec::Most(k),
                _ => {
                    return Err(Failure::input(format!(
                        "--node-times: expected a whole number ≥ 1 or \"all\", got {n:?}"
                    )))
                }
            });
        }
        Ok(())
    }
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
    pub fn input(message: impl std::fmt::Display) -> Self {
        Self::Input(anyhow::anyhow!("{message}"))
    }
    /// A run failure with the given message.
    pub fn run(message: impl std::fmt::Display) -> Self {
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

/// Set once a command has printed its JSON document on stdout, so that `main` prints the
/// error document of `--json` only when none was printed: stdout always holds exactly one.
pub static JSON_PRINTED: AtomicBool = AtomicBool::new(false);

/// Print `text` (a command's output) on stdout; with `json`, mark the JSON document printed.
fn print_stdout(text: &str, json: bool) -> Result<(), Failure> {
    use std::io::Write as _;
    if json {
        JSON_PRINTED.store(true, Ordering::SeqCst);
    }
    let mut stdout = std::io::stdout().lock();
    stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
        .map_err(|e| Failure::run(format!("cannot write to standard output: {e}")))
}

/// `results/<case file stem>`, relative to the working directory.
pub fn default_out_dir(case: &Path) -> PathBuf {
    let stem = case
        .file_stem()
        .map_or_else(|| "case".into(), |s| s.to_string_lossy().into_owned());
    Path::new("results").join(stem)
}

/// The text of `status.txt`: `complete`, or one line `WORD: WHAT: MESSAGE` per entry that did
/// not complete.
fn status_text(incomplete: &[Entry]) -> String {
    if incomplete.is_empty() {
        return "complete\n".into();
    }
    incomplete
        .iter()
        .map(|e| {
            let message = e.status.message().unwrap_or_default();
            format!("{}: {}: {message}\n", e.status.word(), e.label)
        })
        .collect()
}

/// What a command's options change in its case: `flexwing modes --count`, `flexwing linearize
/// --speed --inputs --outputs --states`.
#[derive(Debug, Default)]
pub struct Overrides<'a> {
    /// `--format`, `--node-times`: `[output]`.
    pub output: Option<&'a OutputArgs>,
    /// `--vtk`: `[output] vtk`.
    pub vtk: Option<&'a VtkArgs>,
    /// `--count`.
    pub count: Option<usize>,
    /// `--speed`: `aero.flight.speed`.
    pub speed: Option<f64>,
    /// `--inputs`: `linearize.inputs`.
    pub inputs: Option<Vec<String>>,
    /// `--outputs`: `linearize.outputs`.
    pub outputs: Option<Vec<String>>,
    /// `--states`: `linearize.states`.
    pub states: Option<String>,
}

impl Overrides<'_> {
    /// Change `case` as the options say (into its keys, so that errors name them).
    fn apply(&self, case: &mut Case) -> Result<(), Failure> {
        if let Some(o) = self.output {
            o.apply(&mut case.output)?;
        }
        let vtk = self.vtk.or(self.output.map(|o| &o.vtk));
        if vtk.is_some_and(|v| v.vtk) {
            case.output.vtk = Some(true);
        }
        if self.count.is_some() {
            // `--count` wins over `[modes] count`.
            case.modes.count = None;
        }
        if let Some(speed) = self.speed {
            match case.aero.as_mut() {
                Some(aero) => aero.flight.speed = Some(speed),
                None => return Err(Failure::input("--speed: the case has no [aero] table")),
            }
        }
        let lin = |case: &mut Case| case.linearize.get_or_insert_with(Default::default).clone();
        if self.inputs.is_some() || self.outputs.is_some() || self.states.is_some() {
            let mut l = lin(case);
            if let Some(v) = &self.inputs {
                l.inputs = Some(v.clone());
            }
            if let Some(v) = &self.outputs {
                l.outputs = Some(v.clone());
            }
            if let Some(v) = &self.states {
                l.states = Some(match v.as_str() {
                    "velocities" => flexwing_case::StatesSpec::Velocities,
                    "momenta" => flexwing_case::StatesSpec::Momenta,
                    other => {
                        return Err(Failure::input(format!(
                            "--states: expected \"velocities\" or \"momenta\", got {other:?}"
                        )))
                    }
                });
            }
            case.linearize = Some(l);
        }
        Ok(())
    }
}

/// Run `analysis` of the case of `args`, changed by the command's `overrides`.
pub fn run(analysis: Analysis, args: &CaseArgs, overrides: &Overrides) -> Result<(), Failure> {
    let name = args.case.display().to_string();
    let mut case = Case::load(&args.case).map_err(Failure::input)?;
    overrides.apply(&mut case)?;
    let count = overrides.count;
    let mut plan = case.plan(analysis).map_err(Failure::input)?;
    match &mut plan {
        Plan::Modes(p) if count.is_some() => {
            *p = ModesPlan::new(p.model.clone(), count, "--count")
                .map_err(|e| Failure::input(format!("{name}: {e}")))?;
        }
        // The node file's snapshots (`[output] node_times`, in the plan) and the plot's.
        Plan::Dynamic(p) => p
            .snapshots
            .extend(render::plot_indices(p.output_times.len())),
        Plan::Chain3d(p) => {
            if let (Analysis3d::Modes { count: c }, Some(count)) = (&mut p.analysis, count) {
                *c = count;
                let fields = flexwing::analysis::aero::Fields {
                    analysis: "--",
                    ..flexwing::analysis::aero::Fields::RELATIVE
                };
                p.validate(&fields).map_err(|e| {
                    Failure::input(format!(
                        "{name}: {}",
                        e.to_string().replacen("--.", "--", 1)
                    ))
                })?;
            }
        }
        _ => {}
    }
    let modes = matches!(plan, Plan::Modes(_));
    let dir = args
        .out
        .clone()
        .unwrap_or_else(|| default_out_dir(&args.case));
    output::prepare_dir(&dir, render::previous_files(&plan), !modes).map_err(Failure::Run)?;
    render::vtk::remove_previous(&dir).map_err(Failure::Run)?;

    // A bar of the simulated time for dynamic runs (and Ctrl-C polled by every analysis but
    // the modal one).
    let dynamic = matches!(
        plan,
        Plan::Dynamic(_) | Plan::AeroDynamic(_) | Plan::GustFamily(_)
    ) || matches!(&plan, Plan::Chain3d(p) if matches!(p.analysis, Analysis3d::Dynamic(_)));
    let shown = dynamic && !args.json && std::io::stderr().is_terminal();
    let mut bar = crate::progress::Progress::new(shown);
    let progress: &mut dyn Progress = if modes { &mut NoProgress } else { &mut bar };
    if !modes {
        interrupt::catch_interrupts(plan.checks_seldom());
    }
    let outcome = analysis::run(&plan, progress).map_err(|e| match (e, &plan) {
        (e, Plan::Modes(_)) => Failure::run(format!("{name}: modal analysis failed: {e}")),
        (Error::Input(e), _) => Failure::input(format!("{name}: {e}")),
        (e, Plan::Static(_) | Plan::Dynamic(_)) => Failure::run(format!(
            "{name}: modal analysis about the undeformed state failed: {e}"
        )),
        (e, _) => Failure::run(format!("{name}: {e}")),
    })?;
    let view = View::of(&plan, &outcome)
        .ok_or_else(|| Failure::run(format!("{name}: the outcome is not of its plan's kind")))?;
    let ctx = Context {
        name: &name,
        case: &case,
        incomplete: outcome.incomplete(),
        notes: outcome
            .notes()
            .into_iter()
            .map(|(label, note)| format!("{label}: {note}"))
            .collect(),
    };
    let mut written = render::files(&ctx, &view, &dir, args.plot).map_err(Failure::Run)?;
    if !modes {
        let status = dir.join("status.txt");
        output::write_bytes(&status, status_text(&ctx.incomplete).as_bytes())
            .map_err(Failure::Run)?;
        written.push(status);
    }
    let text = if args.json {
        render::json(&ctx, &view, &written)
    } else {
        render::text(&ctx, &view, &written)
    };
    let printed = print_stdout(&text, args.json);
    if matches!(plan, Plan::Dynamic(_)) {
        for note in &ctx.notes {
            eprintln!("note: {name}: {note}");
        }
    }
    match ctx.incomplete.split_first() {
        None => printed,
        Some((first, others)) => {
            let word = match first.status.word() {
                "suspect" => "suspect: ",
                _ => "",
            };
            let others: Vec<&str> = others.iter().map(|e| e.label.as_str()).collect();
            let also = if others.is_empty() {
                " (see status.txt)".to_string()
            } else {
                format!(
                    " (also not complete: {}; see status.txt)",
                    others.join(", ")
                )
            };
            let message = first.status.message().unwrap_or_default();
            Err(Failure::run(format!(
                "{name}: {}: {word}{message}{also}",
                first.label
            )))
        }
    }
}
