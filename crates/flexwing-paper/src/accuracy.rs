//! Beyond the paper: the accuracy of the reduced models against the number of modes, over the
//! static and the dynamic cases.

use crate::table::{Cell, Fmt, Table};
use crate::Section;

/// The accuracy of one reduced model in one case.
#[derive(Debug, Clone, PartialEq)]
pub struct AccuracyRow {
    /// The case.
    pub case: String,
    /// Number of modes.
    pub modes: usize,
    /// Largest tip distance from the full model (m).
    pub difference: f64,
    /// `difference` over the largest tip displacement of the full model.
    pub relative: f64,
    /// Largest tip distance from the independent reference (m), where there is one.
    pub reference_error: Option<f64>,
}

/// Per case, the fewest modes within 1 % of the largest tip displacement (`None`: none tried).
pub type ModesNeeded = Vec<(String, Option<usize>)>;

/// The fewest modes of each case, in the order the cases first appear in `rows`.
pub fn modes_needed(rows: &[AccuracyRow]) -> ModesNeeded {
    let mut needed: ModesNeeded = Vec::new();
    for row in rows {
        let within = (row.relative <= 0.01).then_some(row.modes);
        match needed.iter_mut().find(|(c, _)| *c == row.case) {
            Some(entry) => {
                if entry.1.is_none() {
                    entry.1 = within;
                }
            }
            None => needed.push((row.case.clone(), within)),
        }
    }
    needed
}

/// The accuracy table.
pub fn table(rows: &[AccuracyRow]) -> Table {
    let mut table = Table::new(
        "reduced_accuracy",
        &[
            ("case", "case"),
            ("modes", "modes r"),
            ("max_tip_difference_m", "max |Δtip| vs full (m)"),
            ("relative_pct", "% of max tip displacement"),
            ("error_vs_reference_m", "max |Δtip| vs reference (m)"),
        ],
    );
    for row in rows {
        table.push(vec![
            Cell::text(&row.case),
            Cell::Num(row.modes as f64, Fmt::Fixed(0)),
            Cell::sci(row.difference, 2),
            Cell::fixed(100.0 * row.relative, 3),
            Cell::opt(row.reference_error, Fmt::Sci(2)),
        ]);
    }
    table
}

/// The report's section.
pub fn section(rows: &[AccuracyRow]) -> Section {
    let table = table(rows);
    let mut text = String::from(
        "Each reduced model projects the full model on its first r undeformed modes and keeps \
         the full geometric non-linearity. Difference: largest tip distance from the full model \
         of the same case over the whole sweep or history, also as a percentage of the full \
         model's largest tip displacement. Reference: the elastica, for the static cases.\n\n",
    );
    text.push_str(&table.markdown());
    text.push_str("\nFewest modes within 1 % of the largest tip displacement:\n\n");
    for (case, r) in modes_needed(rows) {
        text.push_str(&format!(
            "- {case}: {}\n",
            r.map_or_else(|| "more than tried".into(), |r| format!("r = {r}"))
        ));
    }
    Section {
        title: "Beyond the paper: accuracy of the reduced models against the number of modes"
            .into(),
        text,
        tables: vec![table],
        figures: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fewest_modes_within_one_percent() {
        let row = |case: &str, modes, relative| AccuracyRow {
            case: case.into(),
            modes,
            difference: relative,
            relative,
            reference_error: None,
        };
        let rows = [
            row("a", 1, 0.05),
            row("a", 2, 0.009),
            row("a", 3, 0.001),
            row("b", 1, 0.5),
        ];
        assert_eq!(
            modes_needed(&rows),
            [("a".to_string(), Some(2)), ("b".to_string(), None)]
        );
        let t = table(&rows);
        assert_eq!(t.rows.len(), 4);
        assert!(section(&rows)
            .text
            .contains("- a: r = 2\n- b: more than tried\n"));
    }
}
