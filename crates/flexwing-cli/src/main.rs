//! `flexwing`: the command-line tool of the flexwing library. It reads a case file (TOML), calls
//! the library and writes results; all physics lives in the library.
//!
//! Errors are printed as one line, `error: …`, on stderr. Exit status: 0 on success, 2 for bad
//! input (command line or case file), 1 when the run fails (a solver, or writing the results).
//! With `--json`, stdout holds exactly one JSON document whatever happens: the command's, or
//! `{"status": "error", "error": …, "exit_status": …}` when it failed before printing one.

mod driver;
mod fmu;
mod interrupt;
mod output;
mod plot;
mod progress;
mod render;
mod reproduce;

use std::io::Write as _;
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Parser, Subcommand};

use driver::{CaseArgs, Failure, Overrides};
use flexwing_case::Analysis;

/// Non-linear dynamics of very flexible beams (lumped-mass model).
#[derive(Debug, Parser)]
#[command(
    name = "flexwing",
    version,
    long_about = "Non-linear dynamics of very flexible beams and wings with a lumped-mass model \
                  (rigid elements joined by bending and torsion springs).\n\n\
                  A run reads a case file (TOML, see docs/case-file.md), prints a summary and \
                  writes result files (CSV, optionally plots) into an output directory."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Every analysis command (`static`, `dynamic`, `flutter`) runs each model of the case: one that
/// stops does not stop the others, the files hold what it reached, `status.txt` says which
/// stopped where, and the exit status is 1. `--json` prints one JSON document instead of the
/// tables. See docs/cli.md.
#[derive(Debug, Subcommand)]
enum Command {
    /// Natural frequencies and mode shapes about the undeformed state.
    #[command(
        long_about = "Natural frequencies and mode shapes about the undeformed state: a table \
        (mode, ω, f, share of the strain energy in bending, bending/torsion/coupled), \
        frequencies.csv and mode_shapes.csv (mass-normalized nodal shapes); with --plot \
        mode_shapes.svg/.png. See docs/cli.md."
    )]
    Modes(ModesArgs),
    /// Non-linear static equilibria of the full model and of reduced models, over a load sweep.
    #[command(
        long_about = "Non-linear static equilibria under [[loads]] of the full and reduced models \
        of [static], at one load level or along [static.sweep] (each point continued from the \
        previous one); with [aero] the static aeroelastic equilibria at aero.flight.speed or \
        along [aero.sweep] and the divergence speed. Writes static_tip.csv (static_aero.csv \
        with [aero]), static_nodes.csv, static_summary.csv, loaded_frequencies.csv and \
        status.txt; with --plot static_shapes.svg/.png. A model that fails to converge stops, \
        the others still run; the exit status is then 1. See docs/cli.md."
    )]
    Static(StaticArgs),
    /// Time histories of the full, simplified and reduced models under time-varying loads.
    #[command(
        long_about = "Non-linear dynamics of the full, simplified (gyroscopic term neglected) and \
        reduced models of [dynamic] under [[loads]] and their time histories; with [aero] the \
        aeroelastic response to the gust and changes of [aero.flight]. Prints each model's \
        integrator work, wall time and tip against the first model's; writes dynamic_tip.csv \
        (dynamic_aero.csv with [aero]), dynamic_nodes.csv (.npz with --format npz), \
        dynamic_summary.csv and status.txt; with --vtk VTK files for ParaView; with --plot dynamic_tip.svg/.png and dynamic_snapshots.svg/.png. A \
        progress bar appears on a terminal's stderr after a second. An integration that stops \
        keeps the output times reached; the exit status is then 1. Tolerances: a step is \
        accepted when the RMS of err_i / (atol_i + rtol |y_i|) is at most 1, atol_i being \
        [dynamic] atol (rad of joint rotation) converted per coordinate, momentum and lag state, \
        as given by every integrator; rtol is as given too, except by Radau, which uses \
        0.1 rtol^(2/3); with a fixed step they set only Newton's test (docs/model-choices.md, \
        \"Error weights in physical units\"). See docs/cli.md."
    )]
    Dynamic(DynamicArgs),
    /// Divergence and flutter speeds along a sweep in free-stream speed, full and reduced models.
    #[command(
        long_about = "Aeroelastic stability along [aero.sweep] for the full and reduced models of \
        [flutter]: the static equilibria and the divergence speed, the eigenvalues about each \
        equilibrium with the lowest wet modes tracked (V-g, V-ω), every crossing of the \
        imaginary axis refined to [flutter] tolerance, and with pk = true the p-k method. \
        Writes flutter_summary.csv, flutter_crossings.csv, flutter_vg.csv, \
        flutter_equilibria.csv, flutter_nodes.csv and status.txt; with --plot \
        flutter_vg.svg/.png and flutter_shapes.svg/.png. A branch unstable at the first speed \
        gets no flutter speed. See docs/cli.md."
    )]
    Flutter(CaseArgs),
    /// Flutter and divergence against a load level on the 3-D chain ([flutter.study]).
    #[command(
        long_about = "The flutter study of a case of the 3-D chain (beam.model = \"chain3d\"): \
        the flutter analysis of [aero.sweep] and [flutter] at every level of \
        [flutter.study] (a tip force, a gravity factor or a root angle), with the tip \
        deflection at rest, the flutter speed and frequency and the divergence speed at each \
        level, beside the undeformed wing's flutter speed (what the planar model gives at \
        every level). Writes study.csv and status.txt; with --plot study.svg/.png (flutter \
        speed against tip deflection). See docs/cli.md."
    )]
    Study(CaseArgs),
    /// Linear state-space models A, B, C, D about the static aeroelastic equilibrium.
    #[command(
        long_about = "Linear state-space models x' = A x + B u, y = C x + D u about the static \
        aeroelastic equilibrium at aero.flight.speed (root angle, gravity, [[loads]]) for the \
        full and reduced models of [linearize], with the inputs, outputs and states it names \
        (--speed, --inputs, --outputs, --states override the case). Writes linear_LABEL.mat \
        (MATLAB, scipy.io.loadmat), linear_LABEL.npz (NumPy), linear_summary.csv, \
        linear_poles.csv and status.txt; --json prints every matrix. Signs and units of \
        every signal: docs/control.md. Past the divergence speed there is no stable \
        equilibrium: the model stops and the exit status is 1."
    )]
    Linearize(LinearizeArgs),
    /// Discrete 1−cos gusts over a range of gust lengths (CS 25.341(a)): peaks, critical lengths.
    #[command(
        long_about = "A discrete gust family as in CS 25.341(a) / FAR 25.341(a): the aeroelastic \
        response of [dynamic] (full and reduced models, integrator, output times) in the flight \
        of [aero.flight], once per 1−cos gust of [gust_family], the gust gradient distance H \
        from 30 to 350 ft at the design velocity U_ds = U_ref F_g (H/350 ft)^(1/6); each \
        gust replaces [aero.flight.gust]. Reports, per model and output (tip deflection and \
        twist, root bending moment and torque, lift), the largest and smallest change from \
        the equilibrium with their times for every H, and the critical H. Writes \
        gust_family.csv, gust_family_critical.csv and status.txt; with --plot \
        gust_family.svg/.png (peaks against H). See docs/cli.md."
    )]
    Gust(CaseArgs),
    /// Output power spectra and RMS in continuous (von Kármán or Dryden) turbulence.
    #[command(
        long_about = "The response to continuous vertical turbulence of [turbulence] (von Kármán \
        or Dryden spectrum, intensity sigma_w, scale length L) through the linear models of \
        [linearize] about the static aeroelastic equilibrium at aero.flight.speed, driven by \
        the uniform gust and its rate: per model and output the power spectrum \
        Phi_y = |H_y(i w)|^2 Phi_w and the RMS, with the quadrature's error estimate and the \
        tail above the grid. Writes turbulence_rms.csv, turbulence_psd.csv and status.txt; \
        with --plot turbulence_psd.svg/.png (log-log spectra). A model past the flutter speed \
        has no stationary response: it stops and the exit status is 1. See docs/control.md."
    )]
    Turbulence(CaseArgs),
    /// Regenerate every table and figure of the paper's results, beside the paper and references.
    #[command(
        long_about = "Regenerate the paper's section 5 (Tables 2, 3, 5–8, Figures 4–6) beside the \
        paper's numbers and independent references, with the accuracy of the reduced models and \
        the energy drift: one CSV per table, figure4/5/6 as SVG and PNG, report.md (default \
        results/). Times are medians of --repeats samples. See docs/reproduce.md."
    )]
    Reproduce(reproduce::ReproduceArgs),
    /// A co-simulation FMU (FMI 2.0) of the case's aeroelastic response, for Simulink, Modelica.
    #[command(
        long_about = "A co-simulation FMU (FMI 2.0) of the aeroelastic response of the case \
        ([aero] and [dynamic]): the stepper's inputs (root angle, speed, gust, node forces and \
        torques) and outputs (tip position and twist, root moments, lift) as FMI variables with \
        units, the case in its resources and the integrator inside; a `hold` parameter (zero or \
        linear). Carries the compiled library of `cargo build --release -p flexwing-fmu` \
        (found beside flexwing, or --library). See docs/control.md."
    )]
    Fmu(fmu::FmuArgs),
}

/// Options of `flexwing modes`.
#[derive(Debug, clap::Args)]
struct ModesArgs {
    #[command(flatten)]
    case: CaseArgs,

    /// Number of modes to report, 1 to n_dofs; overrides `[modes] count` of the case
    /// [default: min(10, n_dofs)].
    #[arg(long, short = 'n', value_name = "N")]
    count: Option<usize>,

    #[command(flatten)]
    vtk: driver::VtkArgs,
}

/// Options of `flexwing static`.
#[derive(Debug, clap::Args)]
struct StaticArgs {
    #[command(flatten)]
    case: CaseArgs,

    #[command(flatten)]
    vtk: driver::VtkArgs,
}

/// Options of `flexwing dynamic`.
#[derive(Debug, clap::Args)]
struct DynamicArgs {
    #[command(flatten)]
    case: CaseArgs,

    #[command(flatten)]
    output: driver::OutputArgs,
}

/// Options of `flexwing linearize`.
#[derive(Debug, clap::Args)]
struct LinearizeArgs {
    #[command(flatten)]
    case: CaseArgs,

    /// Free-stream speed of the equilibrium (m/s); overrides `aero.flight.speed`.
    #[arg(long, value_name = "U", allow_negative_numbers = true)]
    speed: Option<f64>,

    /// Inputs, comma-separated (`gust,force[16]`); override `linearize.inputs`.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    inputs: Option<Vec<String>>,

    /// Outputs, comma-separated (`tip_y,lift`); override `linearize.outputs`.
    #[arg(long, value_name = "NAMES", value_delimiter = ',')]
    outputs: Option<Vec<String>>,

    /// `velocities` or `momenta`; overrides `linearize.states`.
    #[arg(long, value_name = "BASIS")]
    states: Option<String>,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let json = std::env::args().any(|a| a == "--json");
            return usage_error(&e, json);
        }
    };
    let (json, result) = match &cli.command {
        Command::Modes(a) => {
            let o = Overrides {
                count: a.count,
                vtk: Some(&a.vtk),
                ..Overrides::default()
            };
            (a.case.json, driver::run(Analysis::Modes, &a.case, &o))
        }
        Command::Static(a) => {
            let o = Overrides {
                vtk: Some(&a.vtk),
                ..Overrides::default()
            };
            (a.case.json, driver::run(Analysis::Static, &a.case, &o))
        }
        Command::Dynamic(a) => {
            let o = Overrides {
                output: Some(&a.output),
                ..Overrides::default()
            };
            (a.case.json, driver::run(Analysis::Dynamic, &a.case, &o))
        }
        Command::Flutter(a) => (
            a.json,
            driver::run(Analysis::Flutter, a, &Overrides::default()),
        ),
        Command::Study(a) => (
            a.json,
            driver::run(Analysis::Study, a, &Overrides::default()),
        ),
        Command::Linearize(a) => {
            let o = Overrides {
                speed: a.speed,
                inputs: a.inputs.clone(),
                outputs: a.outputs.clone(),
                states: a.states.clone(),
                ..Overrides::default()
            };
            (a.case.json, driver::run(Analysis::Linearize, &a.case, &o))
        }
        Command::Gust(a) => (
            a.json,
            driver::run(Analysis::GustFamily, a, &Overrides::default()),
        ),
        Command::Turbulence(a) => (
            a.json,
            driver::run(Analysis::Turbulence, a, &Overrides::default()),
        ),
        Command::Reproduce(a) => (false, reproduce::run(a)),
        Command::Fmu(a) => (false, fmu::run(a)),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            report(&failure);
            if json && !driver::JSON_PRINTED.load(std::sync::atomic::Ordering::SeqCst) {
                let message = flexwing_case::one_line(&format!("{:#}", failure.error()));
                print_json_error(&message, failure.exit_status());
            }
            ExitCode::from(failure.exit_status())
        }
    }
}

fn report(failure: &Failure) {
    // `{:#}` joins the context chain with ": ".
    print_error(&flexwing_case::one_line(&format!("{:#}", failure.error())));
}

/// The JSON document of a failed `--json` run on stdout.
fn print_json_error(message: &str, exit_status: u8) {
    let doc = serde_json::json!({
        "status": "error",
        "error": message,
        "exit_status": exit_status,
    });
    let text = serde_json::to_string_pretty(&doc).unwrap_or_default();
    let _ = writeln!(std::io::stdout(), "{text}");
}

/// `error: MESSAGE` on stderr; a closed stderr is ignored (`eprintln!` would panic).
fn print_error(message: &str) {
    let _ = writeln!(std::io::stderr(), "error: {message}");
}

/// `--help` and `--version` print and succeed; a usage error becomes one line and exit status 2.
fn usage_error(e: &clap::Error, json: bool) -> ExitCode {
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::from(2)
        }
        _ => {
            let rendered = e.render().to_string();
            // Keep the message and tips, drop the usage block that follows them.
            let message = rendered
                .split("\nUsage:")
                .next()
                .unwrap_or(&rendered)
                .trim_start_matches("error:");
            let mut line = String::new();
            for part in message
                .lines()
                .map(flexwing_case::one_line)
                .filter(|l| !l.is_empty())
            {
                if !line.is_empty() {
                    line.push_str(if line.ends_with(':') { " " } else { "; " });
                }
                line.push_str(&part);
            }
            let line = format!("{line}; try '--help'");
            print_error(&line);
            // A usage error of a command line that asked for JSON still gets its document.
            if json {
                print_json_error(&line, 2);
            }
            ExitCode::from(2)
        }
    }
}
