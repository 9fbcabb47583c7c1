//! Result tables of `flexwing reproduce`: one value type written both as CSV (full precision) and
//! as a Markdown table (rounded for reading), and the repeated timing of a computation.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::Result;

use crate::output;

/// How a number is shown in Markdown (CSV always has the shortest exact representation).
#[derive(Debug, Clone, Copy)]
pub enum Fmt {
    /// Fixed decimals.
    Fixed(usize),
    /// Scientific with this many decimals.
    Sci(usize),
    /// A time in seconds, shown in ms or µs.
    Time,
}

/// One cell.
#[derive(Debug, Clone)]
pub enum Cell {
    /// Text, written as is.
    Text(String),
    /// A number and how to show it.
    Num(f64, Fmt),
    /// No value (`–` in Markdown, empty in CSV).
    Empty,
}

impl Cell {
    /// Text cell.
    pub fn text(s: impl Into<String>) -> Self {
        Self::Text(s.into())
    }

    /// Number with fixed decimals.
    pub fn fixed(v: f64, decimals: usize) -> Self {
        Self::Num(v, Fmt::Fixed(decimals))
    }

    /// Number in scientific notation.
    pub fn sci(v: f64, decimals: usize) -> Self {
        Self::Num(v, Fmt::Sci(decimals))
    }

    /// A time (s).
    pub fn time(v: f64) -> Self {
        Self::Num(v, Fmt::Time)
    }

    /// A number or, for `None`, no value.
    pub fn opt(v: Option<f64>, fmt: Fmt) -> Self {
        v.map_or(Self::Empty, |v| Self::Num(v, fmt))
    }

    fn csv(&self) -> String {
        match self {
            Self::Text(s) => s.clone(),
            Self::Num(v, _) => format!("{}", v + 0.0),
            Self::Empty => String::new(),
        }
    }

    fn markdown(&self) -> String {
        match self {
            Self::Text(s) => s.replace('|', "\\|"),
            Self::Num(v, _) if !v.is_finite() => format!("{v}"),
            Self::Num(v, Fmt::Fixed(d)) => format!("{:.*}", d, v + 0.0),
            Self::Num(v, Fmt::Sci(d)) => format!("{v:.d$e}"),
            Self::Num(v, Fmt::Time) => duration_text(*v),
            Self::Empty => "–".into(),
        }
    }
}

/// `12.3 ms`, `45.6 µs`, `1.23 s`.
pub fn duration_text(seconds: f64) -> String {
    if seconds >= 1.0 {
        format!("{seconds:.2} s")
    } else if seconds >= 1e-3 {
        format!("{:.2} ms", seconds * 1e3)
    } else {
        format!("{:.2} µs", seconds * 1e6)
    }
}

/// A table: CSV columns (machine names) and Markdown headers (with units) side by side.
#[derive(Debug, Clone)]
pub struct Table {
    /// CSV file stem, e.g. `table2`.
    pub stem: String,
    /// Column names in the CSV.
    pub columns: Vec<String>,
    /// Column headers in Markdown.
    pub headers: Vec<String>,
    /// Rows of cells.
    pub rows: Vec<Vec<Cell>>,
}

impl Table {
    /// An empty table with `(csv name, markdown header)` columns.
    pub fn new(stem: &str, columns: &[(&str, &str)]) -> Self {
        Self {
            stem: stem.into(),
            columns: columns.iter().map(|c| c.0.to_string()).collect(),
            headers: columns.iter().map(|c| c.1.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Append a row.
    ///
    /// # Panics
    /// If the row does not have one cell per column (a programming error).
    pub fn push(&mut self, row: Vec<Cell>) {
        assert_eq!(row.len(), self.columns.len(), "row of table {}", self.stem);
        self.rows.push(row);
    }

    /// The Markdown rendering.
    pub fn markdown(&self) -> String {
        let headers: Vec<String> = self.headers.iter().map(|h| h.replace('|', "\\|")).collect();
        let mut s = format!("| {} |\n", headers.join(" | "));
        s.push_str(&format!("|{}\n", "---|".repeat(self.headers.len())));
        for row in &self.rows {
            let cells: Vec<String> = row.iter().map(Cell::markdown).collect();
            s.push_str(&format!("| {} |\n", cells.join(" | ")));
        }
        s
    }

    /// Write `<stem>.csv` into `dir`, atomically.
    pub fn write_csv(&self, dir: &Path) -> Result<std::path::PathBuf> {
        let path = dir.join(format!("{}.csv", self.stem));
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&self.columns)?;
        for row in &self.rows {
            w.write_record(row.iter().map(Cell::csv))?;
        }
        let bytes = w
            .into_inner()
            .map_err(|e| anyhow::anyhow!("{}", e.error()))?;
        output::write_bytes(&path, &bytes)?;
        Ok(path)
    }
}

/// Wall times of repeated runs of one computation (single-threaded, so wall time is its CPU
/// time on an idle machine).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Median time of one run (s).
    pub median: f64,
    /// Fastest sample (s per run).
    pub min: f64,
    /// Slowest sample (s per run).
    pub max: f64,
    /// Samples taken.
    pub samples: usize,
    /// Runs per sample (short computations are run several times per sample so that each sample
    /// lasts at least [`MIN_SAMPLE`]).
    pub runs_per_sample: usize,
}

/// Shortest duration of one timing sample: well above the clock's resolution.
pub const MIN_SAMPLE: Duration = Duration::from_millis(20);

impl Timing {
    /// Time `f`: `samples` samples, each of as many runs as it takes to last [`MIN_SAMPLE`]
    /// (found from a first, untimed-in-the-result, warm-up run).
    pub fn measure(samples: usize, mut f: impl FnMut()) -> Self {
        let start = Instant::now();
        f();
        let once = start.elapsed().as_secs_f64().max(1e-9);
        let runs = ((MIN_SAMPLE.as_secs_f64() / once).ceil() as usize).clamp(1, 100_000);
        let mut times: Vec<f64> = (0..samples.max(1))
            .map(|_| {
                let start = Instant::now();
                for _ in 0..runs {
                    f();
                }
                start.elapsed().as_secs_f64() / runs as f64
            })
            .collect();
        times.sort_by(f64::total_cmp);
        let m = times.len();
        let median = if m % 2 == 1 {
            times[m / 2]
        } else {
            0.5 * (times[m / 2 - 1] + times[m / 2])
        };
        Self {
            median,
            min: times[0],
            max: times[m - 1],
            samples: m,
            runs_per_sample: runs,
        }
    }

    /// The result of `f` and its time, for a run too long to repeat (one sample of one run).
    pub fn once<T>(f: impl FnOnce() -> T) -> (T, Self) {
        let start = Instant::now();
        let value = f();
        let s = start.elapsed().as_secs_f64();
        let timing = Self {
            median: s,
            min: s,
            max: s,
            samples: 1,
            runs_per_sample: 1,
        };
        (value, timing)
    }

    /// Spread `(max − min) / median`, in %.
    pub fn spread_percent(&self) -> f64 {
        100.0 * (self.max - self.min) / self.median
    }

    /// `12.3 ms (±4 %, 5×20)`: median, spread and how it was measured.
    pub fn text(&self) -> String {
        format!(
            "{} ({:.0} %, {}×{})",
            duration_text(self.median),
            self.spread_percent(),
            self.samples,
            self.runs_per_sample
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_and_csv_of_a_table() {
        let mut t = Table::new("t", &[("a", "A (m)"), ("b", "B")]);
        t.push(vec![Cell::fixed(1.23456, 2), Cell::Empty]);
        t.push(vec![Cell::text("x|y"), Cell::sci(1234.5, 1)]);
        assert_eq!(
            t.markdown(),
            "| A (m) | B |\n|---|---|\n| 1.23 | – |\n| x\\|y | 1.2e3 |\n"
        );
        let dir = std::env::temp_dir().join(format!("flexwing-table-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = t.write_csv(&dir).unwrap();
        let text = std::fs::read_to_string(path).unwrap();
        assert_eq!(text, "a,b\n1.23456,\nx|y,1234.5\n");
        std::fs::remove_dir_all(dir).unwrap();
    }

    #[test]
    fn timing_orders_its_samples() {
        let mut k = 0u64;
        let t = Timing::measure(3, || {
            for i in 0..1000 {
                k = k.wrapping_add(std::hint::black_box(i));
            }
        });
        assert!(t.min <= t.median && t.median <= t.max && t.min > 0.0);
        assert_eq!(t.samples, 3);
        assert_eq!(duration_text(0.0123), "12.30 ms");
        assert_eq!(duration_text(2.5e-5), "25.00 µs");
    }
}
