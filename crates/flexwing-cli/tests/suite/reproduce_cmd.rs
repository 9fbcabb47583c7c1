//! `flexwing reproduce` end to end, as a smoke test: one timing sample and a 1 s long run (the
//! study's numbers are tested part by part in `crates/flexwing-paper/tests/study.rs`, and the
//! energy over 30 s in the library's tests): every table and figure is written, the report
//! holds every section and says how it was made, and the tables have their rows.

use std::fs;
use std::path::Path;

use crate::common::{assert_success, flexwing_in, stderr, TempDir};

/// Number of data rows of a CSV file.
fn rows(dir: &Path, name: &str) -> usize {
    let path = dir.join(name);
    let mut reader =
        csv::Reader::from_path(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    reader
        .records()
        .inspect(|r| assert!(r.is_ok(), "{name}: {r:?}"))
        .count()
}

#[test]
fn reproduce_writes_every_table_and_figure() {
    let dir = TempDir::new("reproduce");
    let out = dir.path().join("results");
    let o = flexwing_in(
        dir.path(),
        &[
            "reproduce",
            "--out",
            out.to_str().unwrap(),
            "--repeats",
            "1",
            "--long-run",
            "1",
        ],
    );
    assert_success(&o);
    for step in 1..=5 {
        assert!(
            stderr(&o).contains(&format!("[{step}/5]")),
            "no progress: {}",
            stderr(&o)
        );
    }
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
    let report = fs::read_to_string(out.join("report.md")).unwrap();
    for heading in [
        "## Conclusions checked by this run",
        "## Table 2:",
        "## Table 3:",
        "## Figure 4 and Table 5:",
        "## Table 6:",
        "## Figure 5 and Table 7:",
        "## Figure 6 and Table 8:",
        "accuracy of the reduced models",
        "energy drift",
        "Machine: ",
        "--repeats 1 --long-run 1",
        "Over 1 s the full model",
        "Files: `table5.csv`, `figure4.csv`, `figure4.svg`, `figure4.png`.",
    ] {
        assert!(report.contains(heading), "report.md lacks {heading:?}");
    }
    assert!(!report.contains("NaN"), "NaN in report.md");
    assert!(!report.contains("did not complete"), "{report}");
    for figure in ["figure4", "figure5", "figure6"] {
        for ext in ["svg", "png"] {
            let len = fs::metadata(out.join(format!("{figure}.{ext}")))
                .map(|m| m.len())
                .unwrap_or(0);
            assert!(len > 1000, "{figure}.{ext}: {len} bytes");
        }
    }
    for (table, count) in [
        ("table2.csv", 18),
        ("table3.csv", 6),
        ("table5.csv", 6),
        ("figure4.csv", 16 * 6),
        ("table6.csv", 3),
        ("table7.csv", 2),
        ("simplified_blowup.csv", 7),
        ("energy_drift.csv", 6),
        // The simplified model released from 150 N blows up within 2 output intervals (the
        // energy audit checks every step; the guard before it checked every output interval
        // and saw it after 3), the one released from 10 N runs the whole second.
        ("figure5.csv", 2 + 201),
        ("table8.csv", 9),
        ("figure6.csv", 8 * 201),
        ("reduced_accuracy.csv", 15),
    ] {
        assert_eq!(rows(&out, table), count, "{table}");
    }
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(stdout.matches("wrote ").count(), 12 + 6 + 2, "{stdout}");
}

#[test]
fn reproduce_rejects_bad_arguments() {
    let dir = TempDir::new("reproduce-bad");
    for (args, name) in [
        (&["reproduce", "--repeats", "0"][..], "--repeats"),
        (&["reproduce", "--long-run", "0"][..], "--long-run"),
    ] {
        let o = flexwing_in(dir.path(), args);
        assert_eq!(o.status.code(), Some(2));
        assert!(stderr(&o).contains(name), "{}", stderr(&o));
        assert!(!dir.path().join("results").exists());
    }
}
