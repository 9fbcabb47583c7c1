//! The report: its sections, the paper's conclusions checked by the run, and `report.md`'s text.

use crate::modal::ModalStudy;
use crate::release::ReleaseStudy;
use crate::sine::SineStudy;
use crate::table::Table;
use crate::{figure::Figure, references, words};

/// A part of the report: a heading, Markdown text (tables included), and the tables (written as
/// CSV) and figures it comes with.
#[derive(Debug, Clone)]
pub struct Section {
    /// Heading.
    pub title: String,
    /// Markdown text.
    pub text: String,
    /// Tables, each written as `<stem>.csv`.
    pub tables: Vec<Table>,
    /// Figures, each drawn as `<stem>.svg` and `<stem>.png`.
    pub figures: Vec<Figure>,
}

impl Section {
    /// The names of the files of the section, tables first: `table5.csv`, `figure4.csv`,
    /// `figure4.svg`, `figure4.png`.
    pub fn file_names(&self) -> Vec<String> {
        let tables = self.tables.iter().map(Table::file_name);
        let figures = self
            .figures
            .iter()
            .flat_map(|f| [format!("{}.svg", f.stem), format!("{}.png", f.stem)]);
        tables.chain(figures).collect()
    }
}

/// How the report was made, for its header.
#[derive(Debug, Clone)]
pub struct Provenance {
    /// The command that made it.
    pub command: String,
    /// The machine it ran on.
    pub machine: String,
    /// Its run time (s).
    pub elapsed: f64,
}

/// The conclusions of the paper checked by the studies that completed; `needed` from
/// [`crate::accuracy::modes_needed`].
pub fn conclusions(
    modal: Option<&ModalStudy>,
    sine: Option<&SineStudy>,
    release: Option<&ReleaseStudy>,
    needed: &[(String, Option<usize>)],
) -> String {
    let mut s = String::new();
    if let Some(modal) = modal {
        s.push_str(&format!(
        "- **Modal analysis.** At n = 32 the nine coupled frequencies are within {:.2} % of the \
         continuous beam.\n",
        modal.max_error_n32()
        ));
    }
    if let (Some(sine), Some(release)) = (sine, release) {
        gyroscopic_conclusions(&mut s, sine, release);
    }
    if !needed.is_empty() {
        s.push_str("- **Modes for 1 % accuracy:** ");
        let parts: Vec<String> = needed
            .iter()
            .map(|(case, r)| {
                format!(
                    "{case}: {}",
                    r.map_or_else(|| "more than tried".into(), |r| format!("{r}"))
                )
            })
            .collect();
        s.push_str(&parts.join("; "));
        s.push_str(".\n");
    }
    if let Some(sine) = sine {
        s.push_str(&format!(
            "- **Reduced against full cost.** In the sinusoidal case the reduced model with 2 \
             modes takes {:.3} of the full model's time (the paper: 0.146); the timed full run is \
             {:.1e} m from the converged solution.\n",
            sine.ratio_r2(),
            sine.full_integration_error()
        ));
        s.push_str(&format!(
            "- **Independent check of the dynamics.** The converged full model of the sinusoidal \
             case is {:.1e} m from a separate Python implementation of the model (SciPy).\n",
            sine.independent_difference()
        ));
    }
    s
}

fn gyroscopic_conclusions(s: &mut String, sine: &SineStudy, release: &ReleaseStudy) {
    let (max_150, max_10) = (release.big.max_errors(), release.small.max_errors());
    let released = match release.simplified_stopped().map(words) {
        Some(why) => format!(
            "Released from the 150 N deflection, the simplified model does not stay near the \
             full one: {why}; before that its tip differs by up to {:.0} % (x) and {:.0} % (y) \
             of the full model's displacement",
            100.0 * max_150.0,
            100.0 * max_150.1
        ),
        None => format!(
            "Released from the 150 N deflection, the simplified model's tip differs by up to \
             {:.1} % (x) and {:.1} % (y) over 1 s (the paper: up to 4 %)",
            100.0 * max_150.0,
            100.0 * max_150.1
        ),
    };
    let large = release.simplified_stopped().is_some() || max_150.0.max(max_150.1) > 0.01;
    let verdict = if large {
        "Not at large amplitude (above 1 % or unstable)."
    } else {
        "Yes here: within 1 % at large amplitude."
    };
    let gamma = &sine.gamma;
    let advice = if gamma.exact_cost() < 2.0 && gamma.fd_cost_ratio() > 1.0 {
        "there is no reason to neglect or approximate it"
    } else {
        "weigh its cost against the error"
    };
    s.push_str(&format!(
        "- **Is the gyroscopic term negligible?** {verdict} {released}. Released \
         from 10 N the differences are {:.2} % (x) and {:.2} % (y). Under the sinusoidal \
         10 N force the simplified model's tip is {:.1e} m ({:.2} % of the largest \
         displacement) from the full one. The exact term costs {:.2} times a right-hand side \
         without it (an O(n) recursion), and the paper's finite differences are {:.1e} off \
         and {:.0} times slower: {advice}.\n",
        100.0 * max_10.0,
        100.0 * max_10.1,
        sine.simplified_difference(),
        100.0 * sine.simplified_difference() / sine.amplitude(),
        gamma.exact_cost(),
        gamma.mean_absolute_error,
        gamma.fd_cost_ratio(),
    ));
    s.push_str(&format!(
        "- **Energy.** Over {} s the full model with the exact term keeps its energy to \
         {:.1e} (relative).\n",
        release.long.end_time,
        release.full_drift_long()
    ));
}

/// `report.md`: the header, the conclusions and every section with its files.
pub fn report(provenance: &Provenance, sections: &[Section], conclusions: &str) -> String {
    let mut s = String::from(
        "# flexwing: reproduction of Veronese, Ribeiro & Moreira, \"Reduced order modeling of \
         highly flexible structures\", section 5\n\n",
    );
    s.push_str(&format!(
        "Generated by `{}` in {:.1} s.\n\nMachine: {}.\n\n",
        provenance.command, provenance.elapsed, provenance.machine
    ));
    s.push_str(
        "Columns marked *paper* are copied from the paper. Columns marked *reference* come from \
         independent solutions checked into the repository. Every other number, including the \
         conclusions below, was computed by this run. Times are wall-clock medians of repeated \
         samples on one thread (spread = (max − min)/median); short computations are repeated \
         within a sample to last at least 20 ms. CPU ratios compare our own runs; the paper's \
         ratios are its own and were measured with MATLAB.\n\n",
    );
    s.push_str(&format!("{}\n\n", references::REFERENCE_NOTE));
    s.push_str("## Conclusions checked by this run\n\n");
    s.push_str(conclusions);
    for section in sections {
        s.push_str(&format!("\n## {}\n\n{}", section.title, section.text));
        let files: Vec<String> = section
            .file_names()
            .iter()
            .map(|f| format!("`{f}`"))
            .collect();
        if !files.is_empty() {
            s.push_str(&format!("\nFiles: {}.\n", files.join(", ")));
        }
    }
    s
}

/// The machine and build of this run, for the provenance of the report.
pub fn machine() -> String {
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
