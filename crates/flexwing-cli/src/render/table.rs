//! Text tables: columns side by side under group titles (one group per model), and rows of
//! named cells with one column per model.

use std::fmt::Write as _;

/// A column of a side-by-side table.
pub struct Column {
    pub header: &'static str,
    pub width: usize,
    pub cells: Vec<String>,
}

/// Columns under a common title.
pub struct Group {
    pub title: String,
    pub columns: Vec<Column>,
}

/// The groups side by side, `rows` rows: a title line, a rule, the headers, the cells.
pub fn groups(groups: &[Group], rows: usize) -> String {
    let width =
        |g: &Group| g.columns.iter().map(|c| c.width).sum::<usize>() + 2 * (g.columns.len() - 1);
    let sep = |k: usize| if k == 0 { "" } else { "   " };
    let mut lines = [String::new(), String::new(), String::new()];
    for (k, g) in groups.iter().enumerate() {
        let w = width(g);
        let _ = write!(lines[0], "{}{:^w$}", sep(k), g.title);
        let rule = if g.title.is_empty() { " " } else { "─" }.repeat(w);
        let _ = write!(lines[1], "{}{rule}", sep(k));
        let headers: Vec<String> = g
            .columns
            .iter()
            .map(|c| format!("{:>w$}", c.header, w = c.width))
            .collect();
        let _ = write!(lines[2], "{}{}", sep(k), headers.join("  "));
    }
    let mut s = String::new();
    for l in &lines {
        let _ = writeln!(s, "{}", l.trim_end());
    }
    for row in 0..rows {
        let mut line = String::new();
        for (k, g) in groups.iter().enumerate() {
            let cells: Vec<String> = g
                .columns
                .iter()
                .map(|c| format!("{:>w$}", c.cells[row], w = c.width))
                .collect();
            let _ = write!(line, "{}{}", sep(k), cells.join("  "));
        }
        let _ = writeln!(s, "{}", line.trim_end());
    }
    s
}

/// Named rows of cells, one column per model headed by its label, right-aligned to the widest
/// cell (at least 8).
pub fn rows(labels: &[String], rows: &[(&str, Vec<String>)]) -> String {
    let head = rows
        .iter()
        .map(|(h, _)| h.chars().count())
        .max()
        .unwrap_or(0);
    let widths: Vec<usize> = labels
        .iter()
        .enumerate()
        .map(|(k, l)| {
            rows.iter()
                .map(|(_, cells)| cells[k].chars().count())
                .chain([l.chars().count(), 8])
                .max()
                .unwrap_or(8)
        })
        .collect();
    let mut s = String::new();
    let mut line = format!("{:head$}", "");
    for (l, w) in labels.iter().zip(&widths) {
        let _ = write!(line, "  {l:>w$}");
    }
    let _ = writeln!(s, "{}", line.trim_end());
    for (h, cells) in rows {
        let mut line = format!("{h}{}", " ".repeat(head - h.chars().count()));
        for (c, w) in cells.iter().zip(&widths) {
            let _ = write!(line, "  {c:>w$}");
        }
        let _ = writeln!(s, "{}", line.trim_end());
    }
    s
}
