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
use flexwing_paper::{accuracy, modal, release, sine, statics, Section};

use super::{status_text, Failure, Incomplete};
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

/// What did not complete, and the report's sections with the files written.
#[derive(Default)]
struct Run {
    failed: Vec<Incomplete>,
    sections: Vec<(Section, Vec<PathBuf>)>,
}

impl Run {
    /// The value of a part, or `None` with the failure recorded.
    fn attempt<T>(&mut self, what: &str, result: Result<T>) -> Option<T> {
        result.map_err(|e| self.fail(what, &e)).ok()
    }

    fn fail(&mut self, what: &str, e: &anyhow::Error) {
        let message = format!("{e:#}");
        eprintln!("error: {what}: {message}");
        self.failed.push(Incomplete::stopped(what, message));
    }

    /// Write the files of `section` (part `what`) into `dir` and keep it for the report.
    fn add(&mut self, what: &str, dir: &Path, section: Option<Section>) {
        let Some(section) = section else { return };
        match write_section(dir, &section) {
            Ok(files) => self.sections.push((section, files)),
            Err(e) => self.fail(what, &e),
        }
    }
}

/// Run `flexwing reproduce`.
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
    let total = 5;
    let mut step = 0;
    let mut progress = |what: &str| {
        step += 1;
        eprintln!(
            "[{step}/{total}] {what} (at {:.1} s)",
            started.elapsed().as_secs_f64()
        );
    };
    let mut run = Run::default();

    progress("Table 2: natural frequencies");
    let modal = run.attempt("Table 2", modal::run(repeats));
    run.add(
        "Table 2",
        dir,
        modal.as_ref().map(modal::ModalStudy::section),
    );

    progress("Tables 3 and 5, Figure 4: static cases");
    let tip_force = run.attempt("Table 3", statics::tip_force(repeats));
    run.add(
        "Table 3",
        dir,
        tip_force.as_ref().map(|s| s.section(repeats)),
    );
    let two_forces = run.attempt("Table 5 and Figure 4", statics::two_forces(repeats));
    let part = "Table 5 and Figure 4";
    run.add(
        part,
        dir,
        two_forces.as_ref().map(statics::TwoForceStudy::section),
    );

    progress("Tables 6 and 8, Figure 6: sinusoidal tip force");
    let part = "Tables 6 and 8, Figure 6";
    let sine = run.attempt(part, sine::run(repeats));

    progress("Table 7, Figure 5: free vibration, full against simplified");
    let release = run.attempt("Table 7 and Figure 5", release::run(repeats, args.long_run));
    // Paper order: Table 6 (γ), Table 7 / Figure 5, Table 8 / Figure 6.
    run.add(part, dir, sine.as_ref().map(|s| s.gamma.section(repeats)));
    let table7 = release.as_ref().map(|r| r.section(repeats));
    run.add("Table 7 and Figure 5", dir, table7);
    run.add(part, dir, sine.as_ref().map(|s| s.section(repeats)));

    progress("accuracy of the reduced models, report");
    let rows: Vec<accuracy::AccuracyRow> = (tip_force.iter().flat_map(|s| s.accuracy()))
        .chain(two_forces.iter().flat_map(|s| s.accuracy()))
        .chain(sine.iter().flat_map(|s| s.accuracy()))
        .collect();
    let before = run.failed.len();
    run.add("reduced accuracy", dir, Some(accuracy::section(&rows)));
    let needed = if run.failed.len() == before {
        accuracy::modes_needed(&rows)
    } else {
        Vec::new()
    };
    let energy = release.as_ref().map(release::ReleaseStudy::energy_section);
    run.add("Table 7 and Figure 5", dir, energy);

    let mut conclusions =
        report::conclusions(modal.as_ref(), sine.as_ref(), release.as_ref(), &needed);
    for f in &run.failed {
        conclusions.push_str(&format!(
            "- **{} did not complete:** {} Its conclusions are missing above.\n",
            f.what, f.message
        ));
    }
    let elapsed = started.elapsed().as_secs_f64();
    let provenance = Provenance {
        command: if args.long_run == release::LONG_RUN {
            format!(
                "flexwing reproduce --out {} --repeats {repeats}",
                dir.display()
            )
        } else {
            format!(
                "flexwing reproduce --out {} --repeats {repeats} --long-run {}",
                dir.display(),
                args.long_run
            )
        },
        machine: machine(),
        elapsed,
    };
    let sections: Vec<Section> = run.sections.iter().map(|(s, _)| s.clone()).collect();
    let text = report::report(&provenance, &sections, &conclusions);
    let report_path = dir.join("report.md");
    output::write_bytes(&report_path, text.as_bytes()).map_err(Failure::Run)?;
    let status_path = dir.join("status.txt");
    output::write_bytes(&status_path, status_text(&run.failed).as_bytes()).map_err(Failure::Run)?;
    for (_, files) in &run.sections {
        for f in files {
            println!("wrote {}", f.display());
        }
    }
    println!("wrote {}", report_path.display());
    println!("wrote {}", status_path.display());
    println!("done in {elapsed:.1} s");
    if run.failed.is_empty() {
        Ok(())
    } else {
        Err(Failure::run(format!(
            "{} part(s) did not complete: {}; the others are in {}",
            run.failed.len(),
            run.failed
                .iter()
                .map(|f| f.what.as_str())
                .collect::<Vec<_>>()
                .join(", "),
            report_path.display()
        )))
    }
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
        FigureKind::Shapes(f) => plot::write_shapes(
            dir,
            stem,
            &plot::ShapePlot {
                title: f.title.clone(),
                length: f.length,
                models: f
                    .models
                    .iter()
                    .map(|m| plot::ModelShapes {
                        label: m.label.clone(),
                        dashed: m.dashed,
                        shapes: m.shapes.clone(),
                    })
                    .collect(),
                gradient: false,
            },
        ),
        FigureKind::History(f) => plot::write_history(
            dir,
            stem,
            &plot::HistoryPlot {
                title: f.title.clone(),
                end_time: f.end_time,
                has_torsion: false,
                series: f
                    .series
                    .iter()
                    .map(|s| plot::HistorySeries {
                        label: s.label.clone(),
                        dashed: s.dashed,
                        t: s.t.clone(),
                        x: s.x.clone(),
                        y: s.y.clone(),
                        twist: Vec::new(),
                    })
                    .collect(),
            },
        ),
        FigureKind::Lines(f) => plot::write_lines(
            dir,
            stem,
            &plot::LinePlot {
                title: f.title.clone(),
                panels: f
                    .panels
                    .iter()
                    .map(|p| plot::Panel {
                        x_label: p.x_label.clone(),
                        y_label: p.y_label.clone(),
                        series: p
                            .series
                            .iter()
                            .map(|s| plot::Series {
                                colour: None,
                                label: s.label.clone(),
                                dashed: s.dashed,
                                points: s.points.clone(),
                            })
                            .collect(),
                    })
                    .collect(),
            },
        ),
    }
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let threads = std::thread::available_parallelism().map_or(0, |n| n.get());
    let build = if cfg!(debug_assertions) {
        "debug build (timings not representative: use --release)"
    } else {
        "optimized build"
    };
    format!(
        "{cpu}, {threads} hardware threads, {} {}, flexwing {}, {build}; every computation \
         runs on one thread",
        std::env::consts::OS,
        std::env::consts::ARCH,
        env!("CARGO_PKG_VERSION"),
    )
}
