//! Bad input gives exit status 2 and one line on stderr, `error: …`, that names the field;
//! never a panic.

use crate::common::{example, flexwing_in, stderr, TempDir};

/// A valid bending-only case to break one key at a time.
const BENDING: &str = r#"
[beam]
length = 1.0
elements = 4

[beam.section]
EI = 50.0
mass_per_length = 0.2
"#;

/// A valid coupled case.
const COUPLED: &str = r#"
[beam]
length = 16.0
elements = 8

[beam.section]
EI = 2.0e4
mass_per_length = 0.75
GJ = 1.0e3
polar_inertia = 0.1
polar_inertia_about = "mass-centre"
d0 = 0.267
"#;

fn edit(base: &str, from: &str, to: &str) -> String {
    assert!(base.contains(from), "{from:?} not in the base case");
    base.replacen(from, to, 1)
}

/// Run `modes` on `case`; check the failure and that stderr names every string of `names`.
fn assert_rejected(case: &str, status: i32, names: &[&str]) {
    let dir = TempDir::new("bad");
    let path = dir.write("case.toml", case);
    let out = dir.path().join("out");
    let o = flexwing_in(
        dir.path(),
        &[
            "modes",
            path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    );
    check_failure(&o, status, names);
    assert!(!out.exists(), "output written for a bad case");
}

fn check_failure(o: &std::process::Output, status: i32, names: &[&str]) {
    let err = stderr(o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(status), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err:?}");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    for name in names {
        assert!(err.contains(name), "{name:?} not named in {err:?}");
    }
    assert!(
        o.stdout.is_empty(),
        "stdout: {}",
        String::from_utf8_lossy(&o.stdout)
    );
}

#[test]
fn zero_elements() {
    assert_rejected(
        &edit(BENDING, "elements = 4", "elements = 0"),
        2,
        &["beam.elements"],
    );
}

#[test]
fn negative_stiffness() {
    assert_rejected(
        &edit(BENDING, "EI = 50.0", "EI = -1"),
        2,
        &["beam.section.EI", "-1"],
    );
}

#[test]
fn nan_stiffness() {
    assert_rejected(
        &edit(BENDING, "EI = 50.0", "EI = nan"),
        2,
        &["beam.section.EI", "NaN"],
    );
}

#[test]
fn negative_inertia() {
    assert_rejected(
        &edit(COUPLED, "polar_inertia = 0.1", "polar_inertia = -0.1"),
        2,
        &["beam.section.polar_inertia"],
    );
}

#[test]
fn decreasing_stations() {
    assert_rejected(
        &edit(BENDING, "elements = 4", "stations = [0.0, 0.5, 0.25, 1.0]"),
        2,
        &["beam.stations"],
    );
}

#[test]
fn both_elements_and_stations() {
    assert_rejected(
        &edit(
            BENDING,
            "elements = 4",
            "elements = 4\nstations = [0.0, 1.0]",
        ),
        2,
        &["beam.elements", "stations"],
    );
}

#[test]
fn table_not_covering_the_span() {
    assert_rejected(
        &edit(
            BENDING,
            "EI = 50.0",
            "EI = { x = [0.0, 0.5], value = [50.0, 40.0] }",
        ),
        2,
        &["beam.section.EI", "span"],
    );
}

#[test]
fn malformed_table() {
    assert_rejected(
        &edit(BENDING, "EI = 50.0", "EI = { x = [0.0, 1.0] }"),
        2,
        &["beam.section.EI", "value"],
    );
}

#[test]
fn unknown_key() {
    assert_rejected(
        &format!("{BENDING}foo = 1\n"),
        2,
        &["unknown key `foo`", "line 9, column 1"],
    );
}

#[test]
fn polar_inertia_without_its_axis() {
    assert_rejected(
        &edit(COUPLED, "polar_inertia_about = \"mass-centre\"\n", ""),
        2,
        &["beam.section.polar_inertia_about"],
    );
}

#[test]
fn torsion_key_without_gj() {
    assert_rejected(
        &format!("{BENDING}d0 = 0.2\n"),
        2,
        &["beam.section.d0", "GJ"],
    );
}

#[test]
fn count_out_of_range() {
    assert_rejected(
        &format!("{BENDING}\n[modes]\ncount = 5\n"),
        2,
        &["modes.count"],
    );
}

#[test]
fn toml_syntax_error() {
    assert_rejected("[beam\nlength = 1.0\n", 2, &["line 1, column"]);
}

#[test]
fn missing_case_file() {
    let dir = TempDir::new("missing");
    let o = flexwing_in(dir.path(), &["modes", "no_such_case.toml"]);
    check_failure(&o, 2, &["no_such_case.toml"]);
}

#[test]
fn directory_as_case_file() {
    let dir = TempDir::new("dir-case");
    let o = flexwing_in(dir.path(), &["modes", "."]);
    check_failure(&o, 2, &["cannot read the case file"]);
}

#[test]
fn output_directory_that_is_a_file() {
    let dir = TempDir::new("out-file");
    let blocker = dir.write("blocker", "not a directory");
    let o = flexwing_in(
        dir.path(),
        &[
            "modes",
            example("table4.toml").to_str().unwrap(),
            "--out",
            blocker.join("sub").to_str().unwrap(),
        ],
    );
    check_failure(&o, 1, &["output directory"]);
}

#[test]
fn usage_errors_are_one_line_with_status_2() {
    let dir = TempDir::new("usage");
    for args in [
        &["modes"][..],
        &["modes", "a.toml", "--bogus"],
        &["modes", "a.toml", "--count", "x"],
        &["nonsense"],
    ] {
        let o = flexwing_in(dir.path(), args);
        check_failure(&o, 2, &[]);
    }
}

/// Regression (issue 9, section 4): `--json` printed nothing when the input was bad or the
/// output folder unusable. Now stdout is always one JSON document with `status` and `error`.
#[test]
fn json_is_always_one_document_with_status_and_error() {
    let dir = TempDir::new("json-always");
    let bad = dir.write("bad.toml", &edit(BENDING, "EI = 50.0", "EI = -50.0"));
    let good = example("paper_sine.toml");
    let file = dir.write("a_file", "not a folder");
    let file_out = file.join("x");
    let cases: Vec<(Vec<&str>, i32)> = vec![
        (vec!["modes", "--json", "/nonexistent/case.toml"], 2),
        (vec!["modes", "--json", bad.to_str().unwrap()], 2),
        (vec!["static", "--json", bad.to_str().unwrap()], 2),
        (vec!["dynamic", "--json", bad.to_str().unwrap()], 2),
        (vec!["dynamic", "--json", "--no-such-flag"], 2),
        (
            vec![
                "modes",
                "--json",
                good.to_str().unwrap(),
                "--out",
                file_out.to_str().unwrap(),
            ],
            1,
        ),
    ];
    for (args, status) in cases {
        let o = flexwing_in(dir.path(), &args);
        assert_eq!(o.status.code(), Some(status), "{args:?}: {}", stderr(&o));
        let out = String::from_utf8_lossy(&o.stdout);
        let doc: serde_json::Value =
            serde_json::from_str(&out).unwrap_or_else(|e| panic!("{args:?}: {e}: {out:?}"));
        assert_eq!(doc["status"], "error", "{args:?}");
        let error = doc["error"].as_str().unwrap();
        assert!(!error.is_empty() && !error.contains('\n'), "{error}");
        assert_eq!(doc["exit_status"], status);
        assert_eq!(stderr(&o).lines().count(), 1, "{args:?}: {}", stderr(&o));
    }
}

/// Issue 9, "found": `length = 1e300` or `d0 = 1e160` made `modes` loop (later: fail with a
/// misleading modal error), `static` with `length = 1e308` too. Each command now refuses the
/// magnitude at input, naming the field and the range, within the 10 s bound of
/// `magnitude_run` (a hang would fail it). Regression test against the rule of
/// docs/model-choices.md ("Magnitudes accepted").
#[test]
fn magnitudes_outside_the_physical_range_are_refused_at_input() {
    let cases: &[(&str, &str, &str, &str, &str)] = &[
        // command, example, text to replace, replacement, field named
        (
            "modes",
            "table4.toml",
            "length = 1.0 ",
            "length = 1e300 ",
            "beam.length",
        ),
        (
            "modes",
            "gravity_wing.toml",
            "d0 = 0.2 ",
            "d0 = 1e160 ",
            "beam.section.d0",
        ),
        (
            "static",
            "paper_tip_force.toml",
            "length = 1.0 ",
            "length = 1e308 ",
            "beam.length",
        ),
        (
            "static",
            "gravity_wing.toml",
            "d0 = 0.2 ",
            "d0 = 1e160 ",
            "beam.section.d0",
        ),
        (
            "dynamic",
            "paper_sine.toml",
            "length = 1.0 ",
            "length = 1e300 ",
            "beam.length",
        ),
        (
            "flutter",
            "goland_flutter.toml",
            "d0 = -0.18288 ",
            "d0 = 1e160 ",
            "beam.section.d0",
        ),
        (
            "flutter",
            "goland_flutter.toml",
            "length = 6.096 ",
            "length = 1e300 ",
            "beam.length",
        ),
        // A length inside the per-value range, but 1e-30 m with EI = 50, m = 0.2: element
        // frequencies of 1e128 s⁻², refused by the second rule.
        (
            "modes",
            "table4.toml",
            "length = 1.0 ",
            "length = 1e-30 ",
            "beam.section.EI",
        ),
    ];
    for &(command, name, from, to, field) in cases {
        let text = std::fs::read_to_string(example(name)).unwrap();
        let case = edit(&text, from, to);
        let dir = TempDir::new("magnitude");
        let path = dir.write("case.toml", &case);
        let out = dir.path().join("out");
        let start = std::time::Instant::now();
        let o = flexwing_in(
            dir.path(),
            &[
                command,
                path.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        // Refused at input: a hang or a computation would take far longer than this bound
        // (measured: 5 ms per refusal).
        assert!(
            start.elapsed().as_secs_f64() < 10.0,
            "{command} {name} {to}: took {:?}",
            start.elapsed()
        );
        check_failure(&o, 2, &[field]);
        let err = stderr(&o);
        assert!(
            err.contains("1e-30") && err.contains("1e30") || err.contains("1e60"),
            "{command} {name} {to}: the range is not said: {err}"
        );
        assert!(!out.exists(), "output written for a refused case");
    }
}
