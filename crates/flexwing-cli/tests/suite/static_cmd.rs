//! `flexwing static`: the new examples run and write what docs/cli.md promises; the paper's
//! two-load case and the follower tip force agree with the independent elastica solutions of
//! `crates/flexwing/tests/data/elastica/` (see its README: inextensible elastica, L = 1 m,
//! EI = 50 N m², solved to far better than 1e-10 m); bad input is rejected with one line naming
//! the field; a run that does not converge keeps what converged and exits with status 1.

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};
use serde_json::Value;

/// Tolerance of the comparisons with the elastica (m). The lumped model's error is O(L/n²):
/// about 1e-4 m at n = 20 and 4e-4 m at n = 40 for these loads.
const ELASTICA_TOLERANCE: f64 = 1e-3;

fn read_csv(path: &Path) -> (String, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().expect("header").to_string();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

/// Rows of an elastica reference file as numbers.
fn elastica(file: &str) -> Vec<Vec<f64>> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../flexwing/tests/data/elastica")
        .join(file);
    read_csv(&path)
        .1
        .iter()
        .map(|r| r.iter().map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Run `flexwing static CASE --out DIR --json [extra]`; returns the output and DIR.
fn run_static(dir: &TempDir, case: &Path, extra: &[&str]) -> (Output, PathBuf) {
    let out = dir.path().join("out");
    let mut args = vec![
        "static",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    (flexwing_in(dir.path(), &args), out)
}

fn json(o: &Output) -> Value {
    serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("stdout is not one JSON document: {e}\n{}", stdout(o)))
}

fn model<'a>(doc: &'a Value, label: &str) -> &'a Value {
    doc["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["label"] == label)
        .unwrap_or_else(|| panic!("no model {label}"))
}

fn tip(point: &Value) -> (f64, f64) {
    (
        point["tip"]["x_m"].as_f64().unwrap(),
        point["tip"]["y_m"].as_f64().unwrap(),
    )
}

fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// Check the JSON document and the files of a complete run against docs/cli.md.
fn check_complete_run(
    file: &str,
    labels: &[&str],
    points: usize,
    nodes: usize,
    loaded: Option<usize>,
) -> Value {
    let dir = TempDir::new("static-example");
    let (o, out) = run_static(&dir, &example(file), &["--json"]);
    assert_success(&o);
    assert!(o.stderr.is_empty(), "{file}: stderr: {}", stderr(&o));
    let doc = json(&o);
    assert!(doc["case"].as_str().unwrap().ends_with(file));
    assert!(doc["title"].is_string());
    assert_eq!(doc["status"], "complete", "{file}");
    assert!(doc["error"].is_null(), "{file}");
    assert_eq!(doc["n_elements"], nodes - 1);
    let models = doc["models"].as_array().unwrap();
    let got: Vec<&str> = models
        .iter()
        .map(|m| m["label"].as_str().unwrap())
        .collect();
    assert_eq!(got, labels, "{file}");
    for m in models {
        let label = m["label"].as_str().unwrap();
        assert!(m["dofs"].as_u64().unwrap() >= 1);
        assert!(m["wall_time_s"].as_f64().unwrap() >= 0.0);
        assert_eq!(m["status"], "complete");
        assert!(m["error"].is_null());
        let pts = m["points"].as_array().unwrap();
        assert_eq!(pts.len(), points, "{file} {label}");
        for (k, p) in pts.iter().enumerate() {
            assert_eq!(p["point"], k + 1);
            assert!(p["scale"].is_f64());
            for key in ["x_m", "y_m", "twist_rad"] {
                assert!(p["tip"][key].is_f64(), "{label} tip {key}");
                assert_eq!(p["nodes"][key].as_array().unwrap().len(), nodes, "{key}");
            }
            for key in [
                "load_steps",
                "rejected_steps",
                "iterations",
                "residual_evaluations",
                "factorizations",
            ] {
                assert!(p["stats"][key].is_u64(), "{label} stats {key}");
            }
            assert!(p["stats"]["residual_norm"].as_f64().unwrap() < 1e-6);
            let nodes_x = p["nodes"]["x_m"].as_array().unwrap();
            assert_eq!(nodes_x[0], 0.0, "the clamp stays at the origin");
            assert_eq!(p["tip"]["x_m"], nodes_x[nodes - 1]);
            if label == "full" {
                assert!(p["tip_difference_m"].is_null());
            } else {
                assert!(p["tip_difference_m"].as_f64().unwrap() >= 0.0);
            }
        }
        if label == "full" {
            assert!(m["modes"].is_null());
            assert_eq!(m["ratio_to_full"], 1.0);
            assert!(m["max_tip_difference_m"].is_null());
        } else {
            assert!(m["modes"].is_array());
            assert!(m["max_tip_difference_m"].is_f64());
        }
    }
    match loaded {
        Some(count) => {
            let modes = doc["loaded_modes"].as_array().unwrap();
            assert_eq!(modes.len(), count);
            for (k, m) in modes.iter().enumerate() {
                assert_eq!(m["mode"], k + 1);
                let omega = m["omega_rad_s"].as_f64().unwrap();
                let hz = m["frequency_hz"].as_f64().unwrap();
                assert!((omega / (2.0 * std::f64::consts::PI) - hz).abs() <= 1e-12 * omega);
            }
        }
        None => assert!(doc["loaded_modes"].is_null()),
    }

    // The files: listed in the JSON, present, with the documented columns.
    let files: Vec<&str> = doc["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    for f in &files {
        assert!(Path::new(f).is_file(), "{f} listed but not written");
    }
    let mut expected = vec![
        "static_tip.csv",
        "static_nodes.csv",
        "static_summary.csv",
        "status.txt",
    ];
    if loaded.is_some() {
        expected.push("loaded_frequencies.csv");
    }
    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    expected.sort();
    assert_eq!(names, expected, "{file}: files (and no temporaries)");
    assert_eq!(files.len(), expected.len());

    let (header, rows) = read_csv(&out.join("static_tip.csv"));
    assert_eq!(
        header,
        "model,point,scale,tip_x_m,tip_y_m,tip_twist_rad,load_steps,iterations,residual_norm"
    );
    assert_eq!(rows.len(), labels.len() * points);
    let (header, rows) = read_csv(&out.join("static_nodes.csv"));
    assert_eq!(header, "model,point,scale,node,x_m,y_m,twist_rad");
    assert_eq!(rows.len(), labels.len() * points * nodes);
    let (header, rows) = read_csv(&out.join("static_summary.csv"));
    assert_eq!(
        header,
        "model,dofs,wall_time_s,ratio_to_full,max_tip_difference_m"
    );
    assert_eq!(rows.len(), labels.len());
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
    if let Some(count) = loaded {
        let (header, rows) = read_csv(&out.join("loaded_frequencies.csv"));
        assert_eq!(header, "mode,omega_rad_s,frequency_hz");
        assert_eq!(rows.len(), count);
    }
    doc
}

#[test]
fn paper_static_agrees_with_the_elastica() {
    let doc = check_complete_run(
        "paper_static.toml",
        &["full", "reduced-r2", "reduced-r3", "reduced-r4"],
        16,
        21,
        None,
    );
    // Columns: F1_N, tip_x_m, tip_y_m, mid_x_m, mid_y_m; rows F1 = 0, 10, ..., 150 N.
    let reference = elastica("paper_two_loads.csv");
    let full = model(&doc, "full")["points"].as_array().unwrap();
    assert_eq!(full.len(), reference.len());
    for (p, r) in full.iter().zip(&reference) {
        assert_eq!(p["scale"].as_f64().unwrap(), r[0], "scale is F1 in N");
        let error = distance(tip(p), (r[1], r[2]));
        assert!(
            error < ELASTICA_TOLERANCE,
            "F1 = {} N: tip off by {error} m",
            r[0]
        );
    }
    let last = reference.last().unwrap();
    assert_eq!(last[0], 150.0);
    assert!(distance(tip(&full[15]), (last[1], last[2])) < ELASTICA_TOLERANCE);

    // More modes, closer to the full model at F1 = 150 N.
    let at_last = |label: &str| {
        model(&doc, label)["points"][15]["tip_difference_m"]
            .as_f64()
            .unwrap()
    };
    assert!(
        at_last("reduced-r4") < at_last("reduced-r2"),
        "r = 4: {}, r = 2: {}",
        at_last("reduced-r4"),
        at_last("reduced-r2")
    );
    // The difference reported is the distance between the tips.
    let r2 = model(&doc, "reduced-r2")["points"][15].clone();
    assert!((distance(tip(&r2), tip(&full[15])) - at_last("reduced-r2")).abs() < 1e-15);
}

#[test]
fn paper_tip_force_agrees_with_the_elastica() {
    let doc = check_complete_run(
        "paper_tip_force.toml",
        &[
            "full",
            "reduced-r1",
            "reduced-r2",
            "reduced-r3",
            "reduced-r4",
            "reduced-r6",
        ],
        1,
        21,
        None,
    );
    // Columns: alpha, P_N, tip_x_m, tip_y_m, tip_angle_rad; the row of P = 150 N (alpha = 3).
    let reference = elastica("dead_tip.csv");
    let r = reference.iter().find(|r| r[1] == 150.0).expect("P = 150 N");
    let full = &model(&doc, "full")["points"][0];
    // Measured 1.95e-4 m at n = 20 (second-order discretization error).
    assert!(distance(tip(full), (r[2], r[3])) < ELASTICA_TOLERANCE);
    // Two modes within 0.2 % of L, three within 0.05 % (measured 1.15e-3 and 3.5e-4 m).
    let d = |label: &str| {
        model(&doc, label)["points"][0]["tip_difference_m"]
            .as_f64()
            .unwrap()
    };
    assert!(d("reduced-r2") < 2e-3 && d("reduced-r3") < 5e-4);
}

#[test]
fn tip_follower_agrees_with_the_elastica() {
    let doc = check_complete_run("tip_follower.toml", &["full"], 41, 41, None);
    // Columns: alpha, P_N, tip_x_m, tip_y_m, tip_angle_rad; alpha = 0, 0.25, ..., 10.
    let reference = elastica("follower_tip.csv");
    let full = model(&doc, "full")["points"].as_array().unwrap();
    assert_eq!(full.len(), reference.len());
    for (p, r) in full.iter().zip(&reference) {
        assert!((p["scale"].as_f64().unwrap() - r[0]).abs() < 1e-12);
        let error = distance(tip(p), (r[2], r[3]));
        assert!(
            error < ELASTICA_TOLERANCE,
            "alpha = {}: tip off by {error} m",
            r[0]
        );
    }
}

#[test]
fn gravity_wing_reports_loaded_modes() {
    let doc = check_complete_run("gravity_wing.toml", &["full", "reduced-r6"], 1, 41, Some(6));
    assert_eq!(doc["has_torsion"], true);
    assert!(doc["sweep"].is_null());
    let full = &model(&doc, "full")["points"][0];
    assert_eq!(full["scale"], 1.0);
    assert_eq!(full["scales"], serde_json::json!([1.0, 1.0]));
    assert!(
        full["tip"]["y_m"].as_f64().unwrap() < 0.0,
        "gravity pulls down"
    );
    assert!(
        full["tip"]["twist_rad"].as_f64().unwrap() > 0.0,
        "the torque twists"
    );
    assert_eq!(
        model(&doc, "reduced-r6")["modes"],
        serde_json::json!([1, 2, 3, 4, 5, 6])
    );
}

#[test]
fn table_output_and_plot() {
    let dir = TempDir::new("static-plot");
    let (o, out) = run_static(&dir, &example("paper_static.toml"), &["--plot"]);
    assert_success(&o);
    let text = stdout(&o);
    for needle in [
        "model: 20 elements",
        "reduced-r4",
        "tip x (m)",
        "Δtip (m)",
        "wall time (ms)",
        "ratio to full",
        "status: complete",
        "wrote ",
    ] {
        assert!(text.contains(needle), "{needle:?} missing:\n{text}");
    }
    let svg = fs::read_to_string(out.join("static_shapes.svg")).unwrap();
    assert!(svg.starts_with("<svg"));
    for needle in [
        "undeformed",
        "full (20 dofs)",
        "reduced-r2",
        "x (m)",
        "y (m)",
    ] {
        assert!(svg.contains(needle), "{needle:?} missing in the SVG");
    }
    let png = fs::read(out.join("static_shapes.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "not a PNG file");
    assert!(png.len() > 10_000, "PNG suspiciously small");
}

/// A bending-only beam with one named tip load, to break one key at a time.
const CASE: &str = r#"
[beam]
length = 1.0
elements = 20

[beam.section]
EI = 50.0
mass_per_length = 0.2

[[loads]]
name = "F1"
type = "point-force"
node = 20
direction = "dead"
fy = 10.0
"#;

fn edit(from: &str, to: &str) -> String {
    assert!(CASE.contains(from), "{from:?} not in the base case");
    CASE.replacen(from, to, 1)
}

#[test]
fn a_case_without_static_solves_the_full_model_once() {
    let dir = TempDir::new("static-default");
    let case = dir.write("case.toml", CASE);
    let (o, out) = run_static(&dir, &case, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let models = doc["models"].as_array().unwrap();
    assert_eq!(models.len(), 1);
    assert_eq!(models[0]["label"], "full");
    assert_eq!(models[0]["points"].as_array().unwrap().len(), 1);
    assert!(out.join("status.txt").is_file());
}

#[test]
fn default_output_directory_is_results_slash_stem() {
    let dir = TempDir::new("static-default-out");
    dir.write("my_case.toml", CASE);
    let o = flexwing_in(dir.path(), &["static", "my_case.toml"]);
    assert_success(&o);
    let out = dir.path().join("results").join("my_case");
    assert!(out.join("static_tip.csv").is_file());
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
}

/// Run `static` on `case`: exit status 2, one line `error: …` naming every string of `names`,
/// nothing on stdout, no output directory.
fn assert_rejected(case: &str, names: &[&str]) {
    let dir = TempDir::new("static-bad");
    let path = dir.write("case.toml", case);
    let (o, out) = run_static(&dir, &path, &[]);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err:?}");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    for name in names {
        assert!(err.contains(name), "{name:?} not named in {err:?}");
    }
    assert!(o.stdout.is_empty(), "stdout: {}", stdout(&o));
    assert!(!out.exists(), "output written for a bad case");
}

#[test]
fn unknown_load_type() {
    assert_rejected(
        &edit("\"point-force\"", "\"point-farce\""),
        &[
            "loads[0].type",
            "got the text \"point-farce\"",
            "line 12, column 8",
        ],
    );
}

#[test]
fn both_span_and_node() {
    assert_rejected(
        &edit("node = 20", "node = 20\nspan = 1.0"),
        &["loads[0]: give either span or node, not both"],
    );
}

#[test]
fn node_out_of_range() {
    assert_rejected(
        &edit("node = 20", "node = 42"),
        &["loads[0].node: 42 is beyond the last node 20"],
    );
}

#[test]
fn nan_force() {
    assert_rejected(&edit("fy = 10.0", "fy = nan"), &["loads[0].fy", "NaN"]);
}

#[test]
fn span_off_the_beam() {
    assert_rejected(&edit("node = 20", "span = 1.5"), &["loads[0].span", "1.5"]);
}

#[test]
fn key_of_another_load_type() {
    assert_rejected(
        &edit("fy = 10.0", "fy = 10.0\nvalue = 3.0"),
        &["loads[0].value", "point-force"],
    );
}

#[test]
fn follower_component_on_a_dead_force() {
    assert_rejected(
        &edit("fy = 10.0", "normal = 10.0"),
        &["loads[0].normal", "follower"],
    );
}

#[test]
fn torque_on_a_bending_only_beam() {
    assert_rejected(
        &format!("{CASE}\n[[loads]]\ntype = \"torque\"\nnode = 20\nvalue = 1.0\n"),
        // The library rejects the load itself (it once was `loads[1].type`, from a second check
        // of the same rule in the case layer).
        &["loads[1]: a torque needs torsion"],
    );
}

#[test]
fn sweep_of_a_missing_load() {
    assert_rejected(
        &format!("{CASE}\n[static.sweep]\nload = \"F3\"\nscales = [0.0, 1.0]\n"),
        &["static.sweep.load: no load named \"F3\""],
    );
}

#[test]
fn sweep_with_scales_and_a_range() {
    assert_rejected(
        &format!("{CASE}\n[static.sweep]\nload = \"F1\"\nscales = [1.0]\nfrom = 0.0\n"),
        &["static.sweep", "not both"],
    );
}

#[test]
fn reduced_zero() {
    assert_rejected(
        &format!("{CASE}\n[static]\nreduced = [0]\n"),
        &["static.reduced[0]", "got 0"],
    );
}

#[test]
fn reduced_beyond_the_modes() {
    assert_rejected(
        &format!("{CASE}\n[static]\nreduced = [2, 999]\n"),
        &["static.reduced[1]", "999"],
    );
}

#[test]
fn reduced_modes_repeated() {
    assert_rejected(
        &format!("{CASE}\n[static]\nreduced_modes = [[1, 1]]\n"),
        &["static.reduced_modes[0]", "mode 1 is listed twice"],
    );
}

#[test]
fn loaded_modes_with_a_follower_force() {
    assert_rejected(
        &format!(
            "{}\n[static]\nmodes = 3\n",
            edit(
                "direction = \"dead\"\nfy",
                "direction = \"follower\"\nnormal"
            )
        ),
        &["static.modes", "follower"],
    );
}

#[test]
fn no_loads() {
    let beam = &CASE[..CASE.find("[[loads]]").unwrap()];
    assert_rejected(beam, &["loads", "at least one"]);
}

#[test]
fn unknown_static_key() {
    assert_rejected(
        &format!("{CASE}\n[static]\ntolerence = 1e-8\n"),
        &["static", "unknown key `tolerence`"],
    );
}

/// A sweep whose last point cannot be reached with one Newton iteration per step and no load-step
/// cutting below half the step; the first three points (tiny loads) converge.
fn non_converging_case() -> String {
    format!(
        "{}\n[static]\nreduced = [2]\nmax_iterations = 2\nmin_step = 0.5\n\n\
         [static.sweep]\nload = \"F1\"\nscales = [0.0, 0.001, 0.002, 15.0]\n",
        CASE
    )
}

#[test]
fn a_run_that_does_not_converge_keeps_the_converged_points() {
    let dir = TempDir::new("static-diverge");
    let case = dir.write("case.toml", &non_converging_case());
    let (o, out) = run_static(&dir, &case, &[]);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(1), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err:?}");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    for needle in [
        "full",
        "sweep point 4 of 4",
        "did not converge",
        "reduced-r2",
    ] {
        assert!(err.contains(needle), "{needle:?} not in {err:?}");
    }
    assert!(stdout(&o).contains("status: stopped: full: "));

    let status = fs::read_to_string(out.join("status.txt")).unwrap();
    let lines: Vec<&str> = status.lines().collect();
    assert_eq!(lines.len(), 2, "{status}");
    assert!(lines[0].starts_with("stopped: full: stopped at sweep point 4 of 4"));
    assert!(lines[1].starts_with("stopped: reduced-r2: "));

    // The converged points are in the files.
    let (_, rows) = read_csv(&out.join("static_tip.csv"));
    let points: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r[0].as_str(), r[1].as_str()))
        .collect();
    assert_eq!(
        points,
        [
            ("full", "1"),
            ("full", "2"),
            ("full", "3"),
            ("reduced-r2", "1"),
            ("reduced-r2", "2"),
            ("reduced-r2", "3"),
        ]
    );
    let (_, rows) = read_csv(&out.join("static_nodes.csv"));
    assert_eq!(rows.len(), 2 * 3 * 21);
    assert!(out.join("static_summary.csv").is_file());
}

#[test]
fn a_run_that_does_not_converge_still_prints_one_json_document() {
    let dir = TempDir::new("static-diverge-json");
    let case = dir.write("case.toml", &non_converging_case());
    let (o, _) = run_static(&dir, &case, &["--json"]);
    assert_eq!(o.status.code(), Some(1));
    let doc = json(&o);
    assert_eq!(doc["status"], "stopped");
    assert!(doc["error"].as_str().unwrap().starts_with("full: "));
    let full = model(&doc, "full");
    assert_eq!(full["status"], "stopped");
    assert!(full["error"].as_str().unwrap().contains("did not converge"));
    assert_eq!(full["points"].as_array().unwrap().len(), 3);
}

#[test]
fn an_impossible_tolerance_is_a_run_failure() {
    let dir = TempDir::new("static-tolerance");
    let case = dir.write(
        "case.toml",
        &format!("{CASE}\n[static]\ntolerance = 1e-30\nmin_step = 0.01\n"),
    );
    let (o, out) = run_static(&dir, &case, &[]);
    assert_eq!(o.status.code(), Some(1), "stderr: {}", stderr(&o));
    assert!(stderr(&o).contains("full: static solver did not converge"));
    let status = fs::read_to_string(out.join("status.txt")).unwrap();
    assert!(status.starts_with("stopped: full: "), "{status}");
}
