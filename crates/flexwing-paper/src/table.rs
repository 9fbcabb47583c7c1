//! Result tables: one value type rendered both as CSV (full precision) and as a Markdown table
//! (rounded for reading).

use anyhow::Result;

use crate::timing::duration_text;

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

    /// The CSV rendering, `<stem>.csv`'s content: column names, then full-precision cells.
    ///
    /// # Errors
    /// The CSV writer's (none for text and numbers).
    pub fn csv(&self) -> Result<Vec<u8>> {
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(&self.columns)?;
        for row in &self.rows {
            w.write_record(row.iter().map(Cell::csv))?;
        }
        w.into_inner().map_err(|e| anyhow::anyhow!("{}", e.error()))
    }

    /// The file name of the CSV rendering.
    pub fn file_name(&self) -> String {
        format!("{}.csv", self.stem)
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
        let text = String::from_utf8(t.csv().unwrap()).unwrap();
        assert_eq!(text, "a,b\n1.23456,\nx|y,1234.5\n");
        assert_eq!(t.file_name(), "t.csv");
    }
}
