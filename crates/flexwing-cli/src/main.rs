//! `flexwing`: the command-line tool of the flexwing library. It reads a case file (TOML), calls
//! the library and writes results; all physics lives in the library.
//!
//! Errors are printed as one line, `error: …`, on stderr. Exit status: 0 on success, 2 for bad
//! input (command line or case file), 1 when the run fails (a solver, or writing the results).
//! With `--json`, stdout holds exactly one JSON document whatever happens: the command's, or
//! `{"status": "error", "error": …, "exit_status": …}` when it failed before printing one.

mod commands;
mod output;
mod plot;

use std::io::Write as _;
use std::process::ExitCode;

use clap::error::ErrorKind;
use clap::{Parser, Subcommand};

use commands::{dynamic, flutter, modes, reproduce, statics, Failure};

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

#[derive(Debug, Subcommand)]
enum Command {
    /// Natural frequencies and mode shapes about the undeformed state.
    #[command(
        long_about = "Natural frequencies and mode shapes about the undeformed state.\n\n\
        Prints a table (mode, ω in rad/s, f in Hz, share of the strain energy in bending, and \
        whether the mode is bending, torsion or coupled) and writes frequencies.csv and \
        mode_shapes.csv (mass-normalized nodal shapes) into the output directory. \
        With --plot also mode_shapes.svg and mode_shapes.png; with --json one JSON document \
        replaces the table. See docs/cli.md."
    )]
    Modes(modes::ModesArgs),
    /// Non-linear static equilibria of the full model and of reduced models, over a load sweep.
    #[command(
        long_about = "Non-linear static equilibria under the case's [[loads]], for the full model \
        and the reduced models of [static], at one load level or over the load sweep of \
        [static.sweep] (each point continued from the previous one).\n\n\
        Prints the tip position (and twist) of every model side by side, with the difference of \
        each reduced model from the full one, then a summary (dofs, wall time, ratio to full). \
        Writes static_tip.csv, static_nodes.csv, static_summary.csv, loaded_frequencies.csv \
        (with [static] modes) and status.txt into the output directory; with --plot also \
        static_shapes.svg and static_shapes.png. If a model fails to converge, the other \
        models still run, the files hold the points that converged, status.txt says \
        \"stopped\" and the exit status is 1. See docs/cli.md."
    )]
    Static(statics::StaticArgs),
    /// Time histories of the full, simplified and reduced models under time-varying loads.
    #[command(
        long_about = "Non-linear dynamics: time histories of the full model, the simplified model \
        (gyroscopic term neglected) and the reduced models of [dynamic], from rest, from a static \
        deflection or from a given state, under the case's [[loads]] with their time histories.\n\n\
        Prints, side by side per model, the integrator's work (steps, rejected steps, RHS and \
        Jacobian evaluations, factorizations), the wall time and its ratio to the first model, \
        and the largest tip difference from the first model. Writes dynamic_tip.csv, \
        dynamic_nodes.csv, dynamic_summary.csv and status.txt into the output directory; with \
        --plot also dynamic_tip.svg/.png and dynamic_snapshots.svg/.png. A progress bar appears \
        on stderr when it is a terminal and the run takes more than a second. If an integration \
        stops, the other models still run, the files hold the output times reached, status.txt \
        says \"stopped\" and the exit status is 1. See docs/cli.md."
    )]
    Dynamic(dynamic::DynamicArgs),
    /// Divergence and flutter speeds along a sweep in free-stream speed, full and reduced models.
    #[command(
        long_about = "Aeroelastic stability along the speeds of [aero.sweep]: for the full model and \
        the reduced models of [flutter], the static aeroelastic equilibrium and the divergence \
        speed, the eigenvalues of the linearized aeroelastic system about each equilibrium with \
        the lowest wet modes tracked across speeds (V-g and V-ω data), and every crossing of the \
        imaginary axis (flutter onset and offset) refined to [flutter] tolerance; with \
        [flutter] pk = true also the p-k method with Theodorsen's C(k).\n\n\
        Prints the divergence and flutter speeds and frequencies of every model with its wall \
        time, then every crossing. Writes flutter_summary.csv, flutter_crossings.csv, \
        flutter_vg.csv, flutter_equilibria.csv, flutter_nodes.csv and status.txt into the \
        output directory; with --plot also flutter_vg.svg/.png (V-g and V-ω) and \
        flutter_shapes.svg/.png (equilibria against U). A branch already unstable at the first \
        speed (quasi-steady aerodynamics with the elastic axis at or aft of mid-chord) gets no \
        flutter speed: it is listed as unstable at start. See docs/cli.md."
    )]
    Flutter(flutter::FlutterArgs),
    /// Regenerate every table and figure of the paper's results, beside the paper and references.
    #[command(
        long_about = "Regenerate every result of the paper's section 5 (Tables 2, 3, 5, 6, 7, 8 and \
        Figures 4, 5, 6), with the paper's numbers and independent references (continuous beam, \
        elastica) beside ours, plus the accuracy of each reduced model against the number of \
        modes and the energy drift of the full and simplified models.\n\n\
        Writes one CSV per table, figure4/5/6 as SVG and PNG, and report.md into the output \
        directory (default results/). Times are medians of --repeats samples. Progress goes to \
        stderr. See docs/reproduce.md."
    )]
    Reproduce(reproduce::ReproduceArgs),
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let json = std::env::args().any(|a| a == "--json");
            return usage_error(&e, json);
        }
    };
    let json = match &cli.command {
        Command::Modes(a) => a.json,
        Command::Static(a) => a.json,
        Command::Dynamic(a) => a.json,
        Command::Flutter(a) => a.json,
        Command::Reproduce(_) => false,
    };
    let result = match &cli.command {
        Command::Modes(args) => modes::run(args),
        Command::Static(args) => statics::run(args),
        Command::Dynamic(args) => dynamic::run(args),
        Command::Flutter(args) => flutter::run(args),
        Command::Reproduce(args) => reproduce::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => {
            report(&failure);
            if json && !commands::JSON_PRINTED.load(std::sync::atomic::Ordering::SeqCst) {
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
