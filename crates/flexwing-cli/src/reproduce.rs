//! `flexwing reproduce`: every result of the paper's section 5, computed by the study of the
//! `flexwing-paper` crate and rendered here: one CSV per table, SVG and PNG per figure, and
//! `report.md`. A part that fails is reported (stderr, `report.md`, `status.txt`) while the
//! others still run.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::Result;
use clap::Args;
use flexwing_paper::figure::{Figure, FigureKind};
use flexwing_paper::report::{self, Provenance};
use flexwing_paper::study::{self, Study};
use flexwing_paper::{release, Section};

use crate::driver::Failure;
use crate::output;
use crate::plot;

/// Arguments of `flexwing reproduce`.
#[derive(Debug, Args)]
pub struct ReproduceArgs {
    /// Output directory (created if needed).
    #[arg(long, value_name = "DIR", default_value = "results")]
    pub out: PathBuf,
    /// Timing samples per measured computation (median and spread are reported), at least 1.
    #[arg(long, value_name = "N", default_value_t = 5)]
    pub repeats: usize,
    /// Duration (s) of the long free vibration of the energy study, at least 0.005 (one output
    /// interval); a shorter one makes a quick check of the whole command.
    #[arg(long, value_name = "SECONDS", default_value_t = release::LONG_RUN)]
    pub long_run: f64,
}

/// Run `flexwing reproduce`: the study, then its sections' files, `report.md` and
/// `status.txt`.
pub fn run(args: &ReproduceArgs) -> Result<(), Failure> {
    if args.repeats == 0 {
        return Err(Failure::input("--repeats: must be at least 1, got 0"));
    }
    if !(args.long_run >= 0.005 && args.long_run.is_finite()) {
        return Err(Failure::input(format!(
            "--long-run: must be a finite number of seconds, at least 0.005, got {}",
            args.long_run
        )));
    }
    let (dir, repeats) = (&args.out, args.repeats);
    output::create_dir(dir).map_err(Failure::Run)?;
    let started = Instant::now();
    let at = || started.elapsed().as_secs_f64();
    let study = Study::run(
        repeats,
        args.long_run,
        &mut |step, steps, what| eprintln!("[{step}/{steps}] {what} (at {:.1} s)", at()),
        &mut |what, why| eprintln!("error: {what}: {why}"),
    );
    let mut failed = study.failed.clone();
    let (mut sections, mut written, mut accuracy_written) = (Vec::new(), Vec::new(), false);
    for (part, section) in study.sections() {
        match write_section(dir, &section) {
            Ok(files) => {
                accuracy_written |= part == study::ACCURACY;
                written.extend(files);
                sections.push(section);
            }
            Err(e) => {
                eprintln!("error: {part}: {e:#}");
                failed.push((part.to_string(), format!("{e:#}")));
            }
        }
    }
    let conclusions = study.conclusions(&failed, accuracy_written);
    let long_run = if args.long_run == release::LONG_RUN {
        String::new()
    } else {
        format!(" --long-run {}", args.long_run)
    };
    let provenance = Provenance {
        command: format!(
            "flexwing reproduce --out {} --repeats {repeats}{long_run}",
            dir.display()
        ),
        machine: report::machine(),
        elapsed: at(),
    };
    let text = report::report(&provenance, &sections, &conclusions);
    let report_path = dir.join("report.md");
    output::write_bytes(&report_path, text.as_bytes()).map_err(Failure::Run)?;
    let status_path = dir.join("status.txt");
    let status: String = match failed.is_empty() {
        true => "complete\n".into(),
        false => (failed.iter())
            .map(|(what, message)| format!("stopped: {what}: {message}\n"))
            .collect(),
    };
    output::write_bytes(&status_path, status.as_bytes()).map_err(Failure::Run)?;
    for f in written.iter().chain([&report_path, &status_path]) {
        println!("wrote {}", f.display());
    }
    println!("done in {:.1} s", provenance.elapsed);
    if failed.is_empty() {
        return Ok(());
    }
    let parts: Vec<&str> = failed.iter().map(|(what, _)| what.as_str()).collect();
    Err(Failure::run(format!(
        "{} part(s) did not complete: {}; the others are in {}",
        failed.len(),
        parts.join(", "),
        report_path.display()
    )))
}

/// Write the tables (CSV) and figures (SVG, PNG) of `section` into `dir`; the paths written.
fn write_section(dir: &Path, section: &Section) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for table in &section.tables {
        let path = dir.join(table.file_name());
        output::write_bytes(&path, &table.csv()?)?;
        files.push(path);
    }
    for figure in &section.figures {
        files.extend(draw(dir, figure)?);
    }
    Ok(files)
}

/// Draw a figure of the study with the CLI's plots.
fn draw(dir: &Path, figure: &Figure) -> Result<Vec<PathBuf>> {
    let stem = &figure.stem;
    match &figure.kind {
        FigureKind::Shapes(f) => plot::write_shapes(dir, stem, f),
        FigureKind::History(f) => plot::write_history(dir, stem, f),
        FigureKind::Lines(f) => plot::write_lines(dir, stem, f),
    }
}
