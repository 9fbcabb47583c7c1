//! `flexwing dynamic`: the dynamic examples run and write what docs/cli.md promises; physical
//! checks that need no reference data (energy conservation of the full model in free vibration,
//! reduced models approaching the full one as modes are added, a reduced model on every mode
//! reproducing the full model); bad input is rejected with one line naming the field; an
//! integration that stops keeps what it computed and exits with status 1.
//!
//! Most checks compare the code with itself or with physical invariants; none is a comparison with
//! published numbers (the library's tests hold those).

use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};
use serde_json::Value;

fn read_csv(path: &Path) -> (String, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().expect("header").to_string();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

/// Run `flexwing dynamic CASE --out DIR [extra]`; returns the output and DIR.
fn run_dynamic(dir: &TempDir, case: &Path, extra: &[&str]) -> (Output, PathBuf) {
    let out = dir.path().join("out");
    let mut args = vec![
        "dynamic",
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

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("not an array: {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// A copy of the example `file` in `dir` with `end_time` set to `end_time` (s), for runs that
/// would be slow in full.
fn shortened(dir: &TempDir, file: &str, end_time: &str) -> PathBuf {
    let text = fs::read_to_string(example(file)).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("end_time"))
        .expect("an end_time line");
    dir.write(
        file,
        &text.replacen(line, &format!("end_time = {end_time}"), 1),
    )
}

/// Largest `|H(t) − H(0)| / H(0)` of a model's total energy.
fn energy_drift(m: &Value) -> f64 {
    let total = numbers(&m["energy"]["total_J"]);
    total
        .iter()
        .map(|h| (h - total[0]).abs() / total[0])
        .fold(0.0, f64::max)
}

/// Largest tip distance between two models over their common output times.
fn max_tip_distance(a: &Value, b: &Value) -> f64 {
    let (ax, ay) = (numbers(&a["tip"]["x_m"]), numbers(&a["tip"]["y_m"]));
    let (bx, by) = (numbers(&b["tip"]["x_m"]), numbers(&b["tip"]["y_m"]));
    (0..ax.len().min(bx.len()))
        .map(|k| (ax[k] - bx[k]).hypot(ay[k] - by[k]))
        .fold(0.0, f64::max)
}

/// Check the JSON document and the files of a complete run against docs/cli.md; returns the
/// document.
fn check_complete_run(case: &Path, labels: &[&str], times: usize, nodes: usize) -> Value {
    let name = case.file_name().unwrap().to_string_lossy().into_owned();
    let dir = TempDir::new("dynamic-example");
    let (o, out) = run_dynamic(&dir, case, &["--json", "--plot"]);
    assert_success(&o);
    assert!(o.stderr.is_empty(), "{name}: stderr: {}", stderr(&o));
    let doc = json(&o);
    assert!(doc["case"].as_str().unwrap().ends_with(&name));
    assert!(doc["title"].is_string());
    assert_eq!(doc["status"], "complete", "{name}");
    assert!(doc["error"].is_null());
    assert_eq!(doc["n_elements"], nodes - 1);
    assert!(doc["end_time_s"].as_f64().unwrap() > 0.0);
    let models = doc["models"].as_array().unwrap();
    let got: Vec<&str> = models
        .iter()
        .map(|m| m["label"].as_str().unwrap())
        .collect();
    assert_eq!(got, labels, "{name}");
    for (k, m) in models.iter().enumerate() {
        let label = m["label"].as_str().unwrap();
        assert!(m["dofs"].as_u64().unwrap() >= 1);
        assert!(["bdf", "dopri5", "midpoint", "radau"].contains(&m["integrator"].as_str().unwrap()));
        assert!(["exact", "finite-difference", "neglected"]
            .contains(&m["gyroscopic"].as_str().unwrap()));
        for key in [
            "steps",
            "rejected_steps",
            "newton_failures",
            "rhs_evaluations",
            "jacobian_evaluations",
            "factorizations",
            "newton_iterations",
        ] {
            assert!(m["stats"][key].is_u64(), "{label} stats {key}");
        }
        assert!(m["stats"]["steps"].as_u64().unwrap() > 0);
        assert!(m["wall_time_s"].as_f64().unwrap() > 0.0);
        assert_eq!(m["status"], "complete");
        assert!(m["error"].is_null());
        let t = numbers(&m["t_s"]);
        assert_eq!(t.len(), times, "{name} {label}");
        assert_eq!(t[0], 0.0);
        assert_eq!(t[times - 1], doc["end_time_s"].as_f64().unwrap());
        for key in ["x_m", "y_m", "twist_rad"] {
            assert_eq!(numbers(&m["tip"][key]).len(), times, "{label} tip {key}");
        }
        for key in ["kinetic_J", "strain_J", "total_J"] {
            assert_eq!(numbers(&m["energy"][key]).len(), times, "{label} {key}");
        }
        if k == 0 {
            assert_eq!(m["ratio_to_first"], 1.0);
            assert!(m["max_tip_difference_m"].is_null());
            assert!(m["max_relative_error"].is_null());
        } else {
            assert!(m["ratio_to_first"].as_f64().unwrap() > 0.0);
            let d = m["max_tip_difference_m"].as_f64().unwrap();
            assert!((d - max_tip_distance(m, &models[0])).abs() <= 1e-12 * d.max(1.0));
            assert!(m["max_relative_error"]["tip_y"].as_f64().unwrap() >= 0.0);
        }
        if label.starts_with("reduced") {
            assert!(m["modes"].is_array());
        } else {
            assert!(m["modes"].is_null());
        }
    }

    // The files: listed, present, with the documented columns, and no temporaries.
    let files: Vec<&str> = doc["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    for f in &files {
        assert!(Path::new(f).is_file(), "{f} listed but not written");
    }
    assert!(files.last().unwrap().ends_with("status.txt"));
    let mut expected = vec![
        "dynamic_nodes.csv",
        "dynamic_snapshots.png",
        "dynamic_snapshots.svg",
        "dynamic_summary.csv",
        "dynamic_tip.csv",
        "dynamic_tip.png",
        "dynamic_tip.svg",
        "status.txt",
    ];
    let mut names: Vec<String> = fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    expected.sort();
    assert_eq!(names, expected, "{name}: files (and no temporaries)");
    assert_eq!(files.len(), expected.len());

    let (header, rows) = read_csv(&out.join("dynamic_tip.csv"));
    assert_eq!(
        header,
        "model,t_s,tip_x_m,tip_y_m,tip_twist_rad,kinetic_J,strain_J,total_J,work_J,\
         dissipated_J,energy_balance_error"
    );
    assert_eq!(rows.len(), labels.len() * times);
    let (header, rows) = read_csv(&out.join("dynamic_nodes.csv"));
    assert_eq!(header, "model,t_s,node,x_m,y_m,twist_rad");
    assert_eq!(rows.len(), labels.len() * times.min(201) * nodes);
    let (header, rows) = read_csv(&out.join("dynamic_summary.csv"));
    assert_eq!(
        header,
        "model,dofs,integrator,steps,rejected_steps,newton_failures,rhs_evaluations,\
         jacobian_evaluations,\
         factorizations,wall_time_s,ratio_to_first,max_tip_difference_m,\
         max_relative_error_tip_x,max_relative_error_tip_y,energy_balance_max_error,\
         energy_balance_max_error_t_s,energy_balance_limit,status"
    );
    assert_eq!(rows.len(), labels.len());
    assert!(rows.iter().all(|r| r.last().unwrap() == "complete"));
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
    for stem in ["dynamic_tip", "dynamic_snapshots"] {
        let svg = fs::read_to_string(out.join(format!("{stem}.svg"))).unwrap();
        assert!(svg.starts_with("<svg"), "{stem}");
        assert!(svg.contains(labels[0]), "{stem}: first model not named");
        let png = fs::read(out.join(format!("{stem}.png"))).unwrap();
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "{stem}: not a PNG");
        assert!(png.len() > 10_000, "{stem}: PNG suspiciously small");
    }
    let tip_svg = fs::read_to_string(out.join("dynamic_tip.svg")).unwrap();
    for l in labels {
        assert!(tip_svg.contains(l), "{l} missing in the tip plot legend");
    }
    doc
}

#[test]
fn paper_sine_reduced_models_approach_the_full_model() {
    let labels = [
        "full",
        "reduced-r1",
        "reduced-r2",
        "reduced-r3",
        "reduced-r4",
    ];
    let doc = check_complete_run(&example("paper_sine.toml"), &labels, 201, 21);
    let full = model(&doc, "full");
    assert_eq!(full["integrator"], "radau");
    assert_eq!(model(&doc, "reduced-r1")["integrator"], "radau");
    assert_eq!(
        model(&doc, "reduced-r4")["modes"],
        serde_json::json!([1, 2, 3, 4])
    );
    // The beam starts at rest, undeformed: the tip at (L, 0) with no energy.
    assert_eq!(numbers(&full["tip"]["x_m"])[0], 1.0);
    assert_eq!(numbers(&full["energy"]["total_J"])[0], 0.0);
    // The 10 N tip force moves the tip by centimetres.
    let peak = numbers(&full["tip"]["y_m"])
        .iter()
        .fold(0.0_f64, |m, y| m.max(y.abs()));
    assert!(peak > 0.05 && peak < 0.2, "peak tip y {peak}");
    let r1 = max_tip_distance(model(&doc, "reduced-r1"), full);
    let r4 = max_tip_distance(model(&doc, "reduced-r4"), full);
    assert!(r4 < r1, "r = 4: {r4} m, r = 1: {r1} m");
    assert!(r4 < 0.01 * peak, "r = 4 off by {r4} m");
}

#[test]
fn a_step_cap_with_a_loose_tolerance_keeps_case_b_within_1e4_m() {
    // The fast setting of docs/performance.md: Radau, rtol 1e-2, steps ≤ 6 ms. Against the same
    // case at the example's rtol 1e-5 (its own error below 1e-5 m), the tip stays within 2e-4 m (the
    // benchmark measures 7.6e-5 m against rtol 1e-9), and the cap sets at least 1 s / 6 ms steps.
    let dir = TempDir::new("dynamic-max-step");
    let text = fs::read_to_string(example("paper_sine.toml")).unwrap();
    let fast = text
        .replace("rtol = 1e-5 ", "rtol = 1e-2\nmax_step = 6e-3 ")
        .replace("atol = 1e-7 ", "atol = 1e-2 ");
    assert_ne!(fast, text, "the example's tolerance lines changed");
    let (o, _) = run_dynamic(&dir, &dir.write("fast.toml", &fast), &["--json"]);
    assert_success(&o);
    let (o_ref, _) = run_dynamic(&dir, &example("paper_sine.toml"), &["--json"]);
    assert_success(&o_ref);
    let (doc, reference) = (json(&o), json(&o_ref));
    for label in ["full", "reduced-r2"] {
        let (m, r) = (model(&doc, label), model(&reference, label));
        let steps = m["stats"]["steps"].as_u64().unwrap();
        assert!(steps >= 167, "{label}: {steps} steps");
        let d = max_tip_distance(m, r);
        assert!(d < 2e-4, "{label}: {d} m from the tight run");
    }
}

#[test]
fn paper_free_vibration_full_conserves_energy_and_simplified_runs_away() {
    // Regression (issue 9, found (a)): the simplified model of the example grew its energy from
    // 34.7 J to 7889 J and the run said `complete`, exit 0. Now the energy audit stops it when
    // it created 9 times the energy it held (default energy_runaway), the run is `stopped`
    // and the exit status 1; the full model's balance holds.
    let dir = TempDir::new("free-vibration-copy");
    let case = shortened(&dir, "paper_free_vibration.toml", "0.1");
    let (o, out) = run_dynamic(&dir, &case, &["--json"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("simplified: stopped at t = "), "{err}");
    assert!(err.contains("energy_runaway = 9"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    let doc = json(&o);
    assert_eq!(doc["status"], "stopped");
    let full = model(&doc, "full");
    let simplified = model(&doc, "simplified");
    assert_eq!(full["gyroscopic"], "exact");
    assert_eq!(simplified["gyroscopic"], "neglected");
    assert_eq!(full["status"], "complete");
    assert_eq!(simplified["status"], "stopped");
    // Released at rest from the static deflection under the (inactive) 150 N tip force.
    assert_eq!(numbers(&full["energy"]["kinetic_J"])[0], 0.0);
    let y0 = numbers(&full["tip"]["y_m"])[0];
    assert!(y0 > 0.5 && y0 < 0.7, "initial tip y {y0}");
    assert_eq!(numbers(&simplified["tip"]["y_m"])[0], y0);
    // No load and no damping during the motion: H = T + V is conserved by the full model, and
    // its audit says so (measured 5e-5 over 0.1 s at rtol 1e-6, atol 1e-6 rad; limit 1e-3).
    let drift = energy_drift(full);
    assert!(drift < 1e-3, "full model energy drift {drift}");
    let audit = &full["energy_audit"];
    assert_eq!(audit["balanced"], true);
    assert!(audit["max_error"].as_f64().unwrap() < 1e-3, "{audit}");
    assert!(audit["exceeded_time"].is_null());
    // The simplified model has no balance: its error is the energy it created, beyond 9 E.
    let s = &simplified["energy_audit"];
    assert_eq!(s["balanced"], false);
    assert!(s["limit"].is_null());
    assert!(s["max_error"].as_f64().unwrap() > 9.0, "{s}");
    let stopped = s["runaway_time"].as_f64().unwrap();
    assert!(stopped > 0.0 && stopped < 0.1, "{s}");
    let status = fs::read_to_string(out.join("status.txt")).unwrap();
    assert!(
        status.starts_with("stopped: simplified: stopped at t = "),
        "{status}"
    );
}

#[test]
fn a_release_at_loose_tolerances_keeps_its_energy_or_is_not_complete() {
    // Regression (issue 9, found (b)): the full model released from the 150 N deflection,
    // n = 40, rtol = 1e-2, atol = 1e-3, max_step = 5e-4, 0.5 s, went from 34.6 J to 1948 J
    // between 0.47 and 0.5 s with no load and no damping, reported `complete`, exit 0. Since the
    // O(n) Newton systems and the momentum tolerances of main, the same run keeps its energy
    // (measured 34.59 → 34.57 J, audit error 5.7e-4): whatever its status, a `complete` run must
    // hold the energy of this free, undamped beam (a law, not a model output) to 1 %, and pass
    // its audit.
    let dir = TempDir::new("loose-release");
    let text = fs::read_to_string(example("paper_free_vibration.toml")).unwrap();
    let text = text
        .replace("elements = 10 ", "elements = 40 ")
        .replace("node = 10 ", "node = 40 ")
        .replace("end_time = 0.2 ", "end_time = 0.5 ")
        .replace("simplified = true ", "simplified = false ")
        .replace("\nrtol = 1e-6\n", "\nrtol = 1e-2\nmax_step = 5e-4\n")
        .replace("atol = 1e-6 ", "atol = 1e-3 ");
    assert!(text.contains("max_step = 5e-4") && text.contains("node = 40 "));
    let case = dir.write("case.toml", &text);
    let (o, _) = run_dynamic(&dir, &case, &["--json"]);
    let doc = json(&o);
    let full = model(&doc, "full");
    let energy = numbers(&full["energy"]["total_J"]);
    let h0 = energy[0];
    assert!((h0 - 34.6).abs() < 0.5, "initial energy {h0} J");
    let drift = energy
        .iter()
        .map(|e| (e - h0).abs() / h0)
        .fold(0.0, f64::max);
    if full["status"] == "complete" {
        assert_eq!(o.status.code(), Some(0));
        assert!(
            drift < 1e-2,
            "complete, but the energy drifted by {drift:.2e}"
        );
        let audit = &full["energy_audit"];
        assert!(audit["max_error"].as_f64().unwrap() <= audit["limit"].as_f64().unwrap());
    } else {
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    }
}

#[test]
fn an_inaccurate_run_is_suspect_not_complete() {
    // BDF of order 3 (not A-stable) at the default rtol 1e-3 on the small base case's step
    // load: its energy reaches 2.1 J where the tight run (rtol 1e-6) never exceeds 0.33 J, and
    // its tip is 7e-3 m off a 6.6e-2 m motion (measured). The energy audit marks it `suspect`
    // (balance error 5.3 against the limit 0.1), exit status 1; the same case at rtol 1e-6 is
    // `complete` (audit error 2.5e-4 against its limit 1e-3).
    let dir = TempDir::new("suspect");
    let run = |extra: &str| {
        let case = dir.write(
            "case.toml",
            &format!("{CASE}integrator = \"bdf\"\nmax_order = 3\n{extra}"),
        );
        let (o, out) = run_dynamic(&dir, &case, &["--json"]);
        let status = fs::read_to_string(out.join("status.txt")).unwrap();
        let doc = json(&o);
        (o, doc, status)
    };
    let (tight_o, tight, _) = run("rtol = 1e-6\natol = 1e-8\n");
    assert_success(&tight_o);
    let tight_max = numbers(&model(&tight, "full")["energy"]["total_J"])
        .into_iter()
        .fold(0.0, f64::max);
    let (o, doc, status) = run("");
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(doc["status"], "suspect");
    let full = model(&doc, "full");
    assert_eq!(full["status"], "suspect");
    let loose_max = numbers(&full["energy"]["total_J"])
        .into_iter()
        .fold(0.0, f64::max);
    // Independent evidence that the run is wrong: energy the loads never gave.
    assert!(
        loose_max > 3.0 * tight_max,
        "{loose_max} J vs {tight_max} J"
    );
    assert!(status.starts_with("suspect: full: "), "{status}");
    assert!(stderr(&o).contains("energy balance"), "{}", stderr(&o));
}

#[test]
fn gust_wing_runs_with_damping_and_torsion() {
    let dir = TempDir::new("gust-copy");
    let case = shortened(&dir, "gust_wing.toml", "0.5");
    let doc = check_complete_run(&case, &["full", "reduced-r6"], 51, 21);
    assert_eq!(doc["has_torsion"], true);
    let full = model(&doc, "full");
    assert_eq!(full["dofs"], 40);
    // The follower load, ramped up from zero, lifts the tip and the offset d0 twists it.
    let y = numbers(&full["tip"]["y_m"]);
    assert_eq!(y[0], 0.0);
    assert!(y.iter().cloned().fold(0.0, f64::max) > 0.5);
    let twist = numbers(&full["tip"]["twist_rad"]);
    assert!(twist.iter().any(|t| t.abs() > 0.01));
    let r6 = model(&doc, "reduced-r6");
    assert_eq!(r6["dofs"], 6);
    assert!(r6["max_tip_difference_m"].as_f64().unwrap() < 0.01);
}

#[test]
fn table_output_names_every_model_side_by_side() {
    let dir = TempDir::new("dynamic-table");
    let (o, out) = run_dynamic(&dir, &example("paper_sine.toml"), &[]);
    assert_success(&o);
    let text = stdout(&o);
    for needle in [
        "model: 20 elements",
        "× sin(20 t)",
        "initial state: at rest",
        "reduced-r4",
        "RHS evaluations",
        "Jacobian evaluations",
        "factorizations",
        "wall time (ms)",
        "ratio to first",
        "max Δtip from first (m)",
        "max |Δy| / max |y₁|",
        "status: complete",
        "wrote ",
    ] {
        assert!(text.contains(needle), "{needle:?} missing:\n{text}");
    }
    // One header line with every label, in order.
    let header = text
        .lines()
        .find(|l| l.contains("full") && l.contains("reduced-r1"))
        .unwrap();
    let positions: Vec<usize> = [
        "full",
        "reduced-r1",
        "reduced-r2",
        "reduced-r3",
        "reduced-r4",
    ]
    .iter()
    .map(|l| header.find(l).unwrap())
    .collect();
    assert!(positions.windows(2).all(|w| w[0] < w[1]), "{header}");
    assert!(
        !out.join("dynamic_tip.svg").exists(),
        "plots without --plot"
    );
}

/// A small bending-only beam (n = 4) with a named tip load, to vary one key at a time.
const CASE: &str = r#"
[beam]
length = 1.0
elements = 4

[beam.section]
EI = 50.0
mass_per_length = 0.2

[[loads]]
name = "F1"
type = "point-force"
node = 4
direction = "dead"
fy = 5.0

[dynamic]
end_time = 0.2
output_step = 0.01
"#;

fn edit(from: &str, to: &str) -> String {
    assert!(CASE.contains(from), "{from:?} not in the base case");
    CASE.replacen(from, to, 1)
}

#[test]
fn a_reduced_model_on_every_mode_reproduces_the_full_model() {
    // With all 4 modes (listed out of order) the projection is exact; modal damping must then
    // act on the same modes in both models.
    let dir = TempDir::new("all-modes");
    let case = dir.write(
        "case.toml",
        &format!(
            "{CASE}reduced_modes = [[4, 2, 3, 1]]\nintegrator = \"dopri5\"\nrtol = 1e-10\natol = 1e-12\n\
             damping = {{ type = \"modal\", ratios = [0.05, 0.1, 0.2] }}\n\n\
             [dynamic.initial]\ntype = \"given\"\nq = [0.2, -0.1, 0.05, 0.1]\n\
             qdot = [1.0, 0.0, -2.0, 0.5]\n"
        ),
    );
    let (o, _) = run_dynamic(&dir, &case, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let full = model(&doc, "full");
    let reduced = model(&doc, "reduced-modes-4-2-3-1");
    assert_eq!(reduced["modes"], serde_json::json!([4, 2, 3, 1]));
    // The given state: the first joint rotated by 0.2 rad, and so on.
    let x0 = numbers(&full["tip"]["x_m"])[0];
    let angles = [0.2_f64, 0.1, 0.15, 0.25];
    let expected: f64 = angles.iter().map(|a| 0.25 * a.cos()).sum();
    assert!((x0 - expected).abs() < 1e-12, "{x0} vs {expected}");
    let d = max_tip_distance(full, reduced);
    assert!(d < 1e-6, "reduced model on every mode off by {d} m");
    // Damped: the energy at the end is below the initial one.
    let total = numbers(&full["energy"]["total_J"]);
    assert!(total[total.len() - 1] < 0.9 * total[0]);

    // Free vibration (the tip force removed) of reduced models on single modes: the model on mode
    // 3 gets mode 3's ratio (the only non-zero one) and its energy dies out, while the undamped
    // mode 1 keeps its energy.
    let case = dir.write(
        "case.toml",
        &format!(
            "{}full = false
reduced_modes = [[3], [1]]
             damping = {{ type = \"modal\", ratios = [0.0, 0.0, 0.2] }}\n\n\
             [dynamic.initial]\ntype = \"given\"\nq = [0.01, 0.01, -0.01, 0.01]\n",
            edit("fy = 5.0\n", "fy = 5.0\nactive = false\n")
        ),
    );
    let (o, _) = run_dynamic(&dir, &case, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let energy = |label: &str| numbers(&model(&doc, label)["energy"]["total_J"]);
    let (third, first) = (energy("reduced-modes-3"), energy("reduced-modes-1"));
    assert!(third[20] < 1e-6 * third[0], "{} of {}", third[20], third[0]);
    assert!((first[20] / first[0] - 1.0).abs() < 1e-3, "{first:?}");
}

#[test]
fn every_integrator_and_gyroscopic_option_runs() {
    for extra in [
        "integrator = \"midpoint\"\n",
        "integrator = \"midpoint\"\nstep = 2e-3\n",
        "integrator = \"dopri5\"\ngyroscopic = \"finite-difference\"\ngyroscopic_step = 1e-6\n",
        "integrator = \"bdf\"\nmax_order = 3\nsimplified = true\nreduced = [2]\n",
        "gyroscopic = \"neglected\"\ndamping = { type = \"rayleigh\", alpha = 0.5, beta = 1e-4 }\n",
    ] {
        let dir = TempDir::new("options");
        // At rtol 1e-6 (the test predates the looser defaults): at the default rtol 1e-3, BDF3 on
        // this step load is marked suspect by the energy audit (balance error 5.3 of the energy).
        let case = dir.write(
            "case.toml",
            &format!("{CASE}rtol = 1e-6\natol = 1e-8\n{extra}"),
        );
        let (o, _) = run_dynamic(&dir, &case, &["--json"]);
        assert_success(&o);
        let doc = json(&o);
        assert_eq!(doc["status"], "complete", "{extra}");
        let full = model(&doc, "full");
        assert_eq!(numbers(&full["t_s"]).len(), 21, "{extra}");
        if extra.contains("midpoint") {
            assert_eq!(full["integrator"], "midpoint");
        }
    }
}

/// Generalized-α from the case file: a fixed step converges at second order to a tight Radau run
/// of the same model (a consistency test between two integrators, not a validation of the
/// model), and the adaptive step keeps to its tolerance.
#[test]
fn generalized_alpha_from_the_case_file_converges_at_second_order() {
    let dir = TempDir::new("generalized-alpha");
    // The force ramps up over 0.1 s: a step load would excite the highest modes of the chain,
    // which no step here resolves, and hide the method's order behind their phase errors.
    let ramped = edit(
        "fy = 5.0\n",
        "fy = 5.0\ntime = { type = \"ramp\", start = 0.0, end = 0.1 }\n",
    );
    let tip = |extra: &str| {
        let case = dir.write("case.toml", &format!("{ramped}{extra}"));
        let (o, _) = run_dynamic(&dir, &case, &["--json"]);
        assert_success(&o);
        let doc = json(&o);
        assert_eq!(doc["status"], "complete", "{extra}");
        numbers(&model(&doc, "full")["tip"]["y_m"])
    };
    let reference = tip("rtol = 1e-10\natol = 1e-12\n");
    let error = |y: &[f64]| {
        y.iter()
            .zip(&reference)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };
    let steps = [1e-3, 5e-4, 2.5e-4, 1.25e-4];
    let errors: Vec<f64> = steps
        .iter()
        .map(|h| {
            error(&tip(&format!(
                "integrator = \"generalized-alpha\"\nstep = {h}\nspectral_radius = 0.8\nrtol = 1e-10\natol = 1e-12\n"
            )))
        })
        .collect();
    // Second order: halving the step divides the error by about 4. Measured ratios 3.3, 4.5, 3.4
    // (errors 3.4e-5 … 6.7e-7 m; the kink of the ramp at 0.1 s rings in the high modes): the
    // bound allows observed orders 1.6 to 2.4.
    for w in errors.windows(2) {
        let ratio = w[0] / w[1];
        assert!((3.0..5.3).contains(&ratio), "errors {errors:?}");
    }
    // The tip moves 3.7e-2 m; the adaptive step at rtol 1e-6, atol 1e-8 stays within 1e-5 m of
    // the tight run (measured 7.9e-7 m).
    let adaptive = error(&tip(
        "integrator = \"generalized-alpha\"\nrtol = 1e-6\natol = 1e-8\n",
    ));
    assert!(
        adaptive < 1e-5,
        "adaptive generalized-α off by {adaptive} m"
    );
}

#[test]
fn time_histories_and_inactive_loads() {
    let dir = TempDir::new("histories");
    let case = dir.write(
        "case.toml",
        &format!(
            "{}\n[[loads]]\nname = \"G\"\ntype = \"gravity\"\nactive = false\n",
            edit(
                "fy = 5.0\n",
                "fy = 5.0\ntime = { type = \"table\", t = [0.0, 0.1, 0.2], value = [0.0, 1.0, 1.0] }\n"
            )
        ),
    );
    let (o, _) = run_dynamic(&dir, &case, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let y = numbers(&model(&doc, "full")["tip"]["y_m"]);
    // The force grows from zero: at rest at first, then lifted (the inactive gravity does not act).
    assert_eq!(y[0], 0.0);
    assert!(y[1].abs() < 0.05 * y[20], "{} vs {}", y[1], y[20]);
    assert!(y[20] > 0.01, "{}", y[20]);
    let (o, _) = run_dynamic(&dir, &case, &[]);
    let text = stdout(&o);
    assert!(
        text.contains("× table of 3 points over [0, 0.2] s"),
        "{text}"
    );
    assert!(text.contains("G: gravity"), "{text}");
    assert!(text.contains("(inactive: not used)"), "{text}");
}

#[test]
fn nodes_file_keeps_at_most_201_snapshots() {
    let dir = TempDir::new("snapshots");
    // 0, 0.0005, ..., 0.2 s: 401 output times, so every second one is written.
    let case = dir.write(
        "case.toml",
        &edit("output_step = 0.01", "output_step = 0.0005"),
    );
    let (o, out) = run_dynamic(&dir, &case, &[]);
    assert_success(&o);
    let (_, rows) = read_csv(&out.join("dynamic_tip.csv"));
    assert_eq!(rows.len(), 401);
    let (_, rows) = read_csv(&out.join("dynamic_nodes.csv"));
    assert_eq!(rows.len(), 201 * 5);
    assert_eq!(
        rows[5][1], "0.001",
        "the second snapshot is the third output time"
    );
}

/// `--node-times` (over `[output] node_times`) sets how many output times the node file keeps;
/// the text and the JSON say what was written; `--format npz` writes `.npz` instead of the CSV
/// (its content is checked against the CSV with NumPy: crates/flexwing-py/tests/test_files.py).
#[test]
fn node_times_and_format_options() {
    let dir = TempDir::new("node-times");
    // 401 output times.
    let case = dir.write(
        "case.toml",
        &edit("output_step = 0.01", "output_step = 0.0005"),
    );
    let (o, out) = run_dynamic(&dir, &case, &["--node-times", "50"]);
    assert_success(&o);
    let text = stdout(&o);
    // k = ⌈401 / 50⌉ = 9: indices 0, 9, …, 396, 45 of them.
    assert!(
        text.contains("node output: dynamic_nodes.csv, every 9th of 401 output times (45 written"),
        "{text}"
    );
    let (_, rows) = read_csv(&out.join("dynamic_nodes.csv"));
    assert_eq!(rows.len(), 45 * 5);
    // The second snapshot is the tenth output time, 9 × 0.0005 s (to round-off: k · step).
    let t: f64 = rows[5][1].parse().unwrap();
    assert!((t - 0.0045).abs() < 1e-15, "{t}");
    let (o, out) = run_dynamic(&dir, &case, &["--node-times", "all", "--json"]);
    assert_success(&o);
    let doc = json(&o);
    assert_eq!(doc["node_output"]["every"], 1);
    assert_eq!(doc["node_output"]["times"], 401);
    let (_, rows) = read_csv(&out.join("dynamic_nodes.csv"));
    assert_eq!(rows.len(), 401 * 5);
    // The case key, and the format: a previous run's CSV is removed, the .npz written.
    let keyed = dir.write(
        "keyed.toml",
        &format!(
            "{}\n[output]\nformat = \"npz\"\nnode_times = 3\n",
            edit("output_step = 0.01", "output_step = 0.0005")
        ),
    );
    let (o, out) = run_dynamic(&dir, &keyed, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    assert_eq!(doc["node_output"]["format"], "npz");
    assert_eq!(doc["node_output"]["times"], 3);
    assert!(out.join("dynamic_nodes.npz").is_file());
    assert!(!out.join("dynamic_nodes.csv").exists());
    // Bad values name the option or the key.
    for (args, expected) in [
        (
            &["--node-times", "0"][..],
            "--node-times: expected a whole number ≥ 1",
        ),
        (&["--format", "parquet"][..], "--format"),
    ] {
        let (o, _) = run_dynamic(&dir, &case, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(stderr(&o).contains(expected), "{}", stderr(&o));
    }
    let bad = dir.write(
        "bad.toml",
        &format!("{}\n[output]\nnode_times = 0\n", edit("", "")),
    );
    let (o, _) = run_dynamic(&dir, &bad, &[]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("output.node_times"), "{}", stderr(&o));
}

#[test]
fn default_output_directory_and_json_only_on_stdout() {
    let dir = TempDir::new("dynamic-default-out");
    dir.write("my_case.toml", CASE);
    let o = flexwing_in(dir.path(), &["dynamic", "my_case.toml", "--json"]);
    assert_success(&o);
    assert!(o.stderr.is_empty(), "stderr: {}", stderr(&o));
    json(&o);
    let out = dir.path().join("results").join("my_case");
    assert!(out.join("dynamic_tip.csv").is_file());
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
}

/// Run `dynamic` on `case`: exit status 2, one line `error: …` naming every string of `names`,
/// nothing on stdout, no output directory.
fn assert_rejected(case: &str, names: &[&str]) {
    let dir = TempDir::new("dynamic-bad");
    let path = dir.write("case.toml", case);
    let (o, out) = run_dynamic(&dir, &path, &[]);
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
fn bad_input_names_the_field() {
    let cases: Vec<(String, Vec<&str>)> = vec![
        (
            edit("end_time = 0.2", "end_time = -1"),
            vec!["dynamic.end_time: must be a finite positive number, got -1"],
        ),
        (
            edit("end_time = 0.2", "end_time = nan"),
            vec!["dynamic.end_time", "NaN"],
        ),
        (
            edit("output_step = 0.01", "output_times = [0.0, 0.05, 0.1, 2.0]"),
            vec!["dynamic.output_times[3]: 2 is after end_time 0.2"],
        ),
        (
            edit("output_step = 0.01", "output_times = [0.1, 0.05]"),
            vec!["dynamic.output_times[1]", "increase"],
        ),
        (
            edit("output_step = 0.01\n", ""),
            vec!["dynamic.output_step: missing"],
        ),
        (
            edit(
                "output_step = 0.01",
                "output_step = 0.01\noutput_times = [0.0]",
            ),
            vec!["dynamic.output_step", "not both"],
        ),
        (
            edit(
                "fy = 5.0\n",
                "fy = 5.0\ntime = { type = \"table\", t = [0.0, 0.1], value = [0.0, 1.0] }\n",
            ),
            vec![
                "loads[0].time.t: table covers [0, 0.1] s but the simulation runs over [0, 0.2] s",
            ],
        ),
        (
            edit(
                "fy = 5.0\n",
                "fy = 5.0\ntime = { type = \"sine\", omega = 20.0, time = 1.0 }\n",
            ),
            vec!["loads[0].time.time", "\"sine\""],
        ),
        (
            edit("fy = 5.0\n", "fy = 5.0\ntime = { type = \"wobble\" }\n"),
            vec!["loads[0].time.type", "must be one of \"constant\", \"sine\", \"step\", \"ramp\", \"table\", got the text \"wobble\""],
        ),
        (
            edit("fy = 5.0\n", "fy = 5.0\nactive = \"no\"\n"),
            vec!["loads[0].active", "must be true or false, got the text \"no\""],
        ),
        (
            format!("{CASE}rtol = 1e-300\n"),
            vec!["dynamic.rtol", "1e-300"],
        ),
        (format!("{CASE}atol = 0\n"), vec!["dynamic.atol: must be"]),
        // Regression (issue 9, found (c)): atol = 1e308 was accepted (8 steps, 2e23 J,
        // `complete`). Tolerances, step sizes and counts are bounded, each with one line.
        (
            format!("{CASE}atol = 1e308\n"),
            vec![
                "dynamic.atol: must be a number in [1e-15, 0.1]",
                "got 1e308",
            ],
        ),
        (
            format!("{CASE}rtol = 1e-20\n"),
            vec!["dynamic.rtol: must be a number in [1e-13, 1)"],
        ),
        (
            format!("{CASE}max_steps = 4611686018427387904\n"),
            vec!["dynamic.max_steps: must be at most 1e9"],
        ),
        (
            format!("{CASE}max_step = 1e-12\n"),
            vec!["dynamic.max_step: 1e-12 s needs at least 2e11 steps"],
        ),
        (
            format!("{CASE}energy_tolerance = 2.0\n"),
            vec!["dynamic.energy_tolerance: must be a number in [1e-10, 0.5]"],
        ),
        (
            format!("{CASE}energy_runaway = -1.0\n"),
            vec!["dynamic.energy_runaway: must be a number in [0.01, 1e6]"],
        ),
        (
            format!("{CASE}integrator = \"bdf\"\nmax_order = 9\n"),
            vec!["dynamic.max_order: must be between 1 and 5"],
        ),
        (
            format!("{CASE}step = 1e-3\n"),
            vec!["dynamic.step", "midpoint"],
        ),
        (
            format!("{CASE}integrator = \"rk4\"\n"),
            vec!["dynamic.integrator", "got \"rk4\""],
        ),
        (
            format!("{CASE}gyroscopic = \"finite-difference\"\ngyroscopic_step = 0\n"),
            vec!["dynamic.gyroscopic_step: must be"],
        ),
        (
            format!("{CASE}full = false\n"),
            vec!["dynamic.full: nothing to simulate"],
        ),
        (
            format!("{CASE}reduced = [9]\n"),
            vec!["dynamic.reduced[0]", "9"],
        ),
        (
            format!("{CASE}reduced_modes = [[1, 1]]\n"),
            vec!["dynamic.reduced_modes[0]", "listed twice"],
        ),
        (
            format!("{CASE}damping = {{ type = \"rayleigh\", alpha = -1.0 }}\n"),
            vec!["dynamic.damping.alpha: must be a finite non-negative number, got -1"],
        ),
        (
            format!("{CASE}damping = {{ type = \"modal\", ratios = [0.1, 0.1, 0.1, 0.1, 0.1] }}\n"),
            vec!["dynamic.damping.ratios", "4 modes"],
        ),
        (
            format!("{CASE}\n[dynamic.initial]\ntype = \"static\"\nloads = [\"F2\"]\n"),
            vec!["dynamic.initial.loads[0]: no load named \"F2\""],
        ),
        (
            format!("{CASE}\n[dynamic.initial]\ntype = \"given\"\nq = [0.1]\n"),
            vec!["dynamic.initial.q: needs 4 values"],
        ),
        (
            format!("{CASE}\n[dynamic.initial]\ntype = \"rest\"\nloads = [\"F1\"]\n"),
            vec!["dynamic.initial.loads", "\"rest\""],
        ),
        (
            format!("{CASE}bogus = 1\n"),
            vec!["dynamic", "unknown key `bogus`"],
        ),
        (
            CASE[..CASE.find("[dynamic]").unwrap()].to_string(),
            vec!["dynamic: missing"],
        ),
    ];
    for (case, names) in cases {
        assert_rejected(&case, &names);
    }
}

/// The full and simplified models with a fixed 0.25 s implicit midpoint step: quiet until a
/// 500 N tip force is switched on at 0.3 s, which Newton's method cannot follow (even with the
/// integrator's sub-steps), so both stop after the outputs at 0, 0.1 and 0.2 s.
fn failing_case() -> String {
    format!(
        "{}simplified = true\nintegrator = \"midpoint\"\nstep = 0.25\n",
        edit(
            "fy = 5.0\n",
            "fy = 500.0\ntime = { type = \"step\", time = 0.3 }\n"
        )
        .replace("end_time = 0.2", "end_time = 1.0")
        .replace("output_step = 0.01", "output_step = 0.1")
    )
}

#[test]
fn an_integration_failure_keeps_what_was_computed() {
    let dir = TempDir::new("dynamic-fail");
    let case = dir.write("case.toml", &failing_case());
    let (o, out) = run_dynamic(&dir, &case, &[]);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(1), "stderr: {err}");
    assert!(err.starts_with("error: "), "{err:?}");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    for needle in ["full: ", "time integration stopped at t = ", "simplified"] {
        assert!(err.contains(needle), "{needle:?} not in {err:?}");
    }
    assert!(stdout(&o).contains("status: stopped: full: "));

    let status = fs::read_to_string(out.join("status.txt")).unwrap();
    let lines: Vec<&str> = status.lines().collect();
    assert_eq!(lines.len(), 2, "{status}");
    assert!(lines[0].starts_with("stopped: full: time integration stopped at t = "));
    assert!(lines[1].starts_with("stopped: simplified: "));

    let (_, rows) = read_csv(&out.join("dynamic_tip.csv"));
    let times: Vec<(&str, &str)> = rows
        .iter()
        .map(|r| (r[0].as_str(), r[1].as_str()))
        .collect();
    assert_eq!(
        times,
        [
            ("full", "0.0"),
            ("full", "0.1"),
            ("full", "0.2"),
            ("simplified", "0.0"),
            ("simplified", "0.1"),
            ("simplified", "0.2"),
        ]
    );
    let (_, rows) = read_csv(&out.join("dynamic_nodes.csv"));
    assert_eq!(rows.len(), 2 * 3 * 5);
    let (_, rows) = read_csv(&out.join("dynamic_summary.csv"));
    assert!(rows.iter().all(|r| r.last().unwrap() == "stopped"));
}

#[test]
fn an_integration_failure_still_prints_one_json_document() {
    let dir = TempDir::new("dynamic-fail-json");
    let case = dir.write("case.toml", &failing_case());
    let (o, _) = run_dynamic(&dir, &case, &["--json", "--plot"]);
    assert_eq!(o.status.code(), Some(1));
    let doc = json(&o);
    assert_eq!(doc["status"], "stopped");
    assert!(doc["error"].as_str().unwrap().starts_with("full: "));
    let full = model(&doc, "full");
    assert_eq!(full["status"], "stopped");
    assert!(full["error"]
        .as_str()
        .unwrap()
        .contains("time integration stopped"));
    assert_eq!(numbers(&full["t_s"]), [0.0, 0.1, 0.2]);
}

#[test]
fn a_step_budget_stops_a_run_and_keeps_its_output() {
    // The paper's sine case with a budget of 50 integrator steps per model: every model stops
    // early, names the limit, and the output computed so far is kept and marked stopped.
    let dir = TempDir::new("dynamic-budget");
    let text = fs::read_to_string(example("paper_sine.toml")).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("end_time"))
        .expect("an end_time line");
    let case = dir.write(
        "case.toml",
        &text.replacen(line, &format!("{line}\nmax_steps = 50"), 1),
    );
    let (o, out) = run_dynamic(&dir, &case, &[]);
    let err = stderr(&o);
    assert!(!err.contains("panicked"), "panic: {err}");
    assert_eq!(o.status.code(), Some(1), "stderr: {err}");
    assert!(err.contains("max_steps"), "{err:?}");
    let status = fs::read_to_string(out.join("status.txt")).unwrap();
    assert!(status.starts_with("stopped: full: "), "{status}");
    let (_, rows) = read_csv(&out.join("dynamic_tip.csv"));
    assert!(!rows.is_empty(), "no partial output kept");
}

#[test]
fn radau_runs_full_and_reduced_models_and_agrees_with_bdf_and_dormand_prince() {
    // The small base case (n = 4, 5 N step load, 0.2 s) with a reduced model, with Radau (the
    // default) and with BDF and Dormand–Prince, at rtol 1e-6, atol 1e-8. (This
    // once compared "auto" with "radau", which became the same integrator: a comparison of the
    // code with itself.)
    let run = |extra: &str| {
        let dir = TempDir::new("radau");
        let case = dir.write(
            "case.toml",
            &format!("{CASE}reduced = [2]\nrtol = 1e-6\natol = 1e-8\n{extra}"),
        );
        let (o, _) = run_dynamic(&dir, &case, &["--json"]);
        assert_success(&o);
        json(&o)
    };
    let radau = run("");
    let bdf = run("integrator = \"bdf\"\n");
    let dopri5 = run("integrator = \"dopri5\"\n");
    assert_eq!(radau["status"], "complete");
    for (label, other, name) in [("full", &bdf, "bdf"), ("reduced-r2", &dopri5, "dopri5")] {
        let (a, b) = (model(other, label), model(&radau, label));
        assert_eq!(a["integrator"], name);
        assert_eq!(b["integrator"], "radau");
        assert_eq!(numbers(&b["t_s"]).len(), 21);
        assert!(b["stats"]["factorizations"].as_u64().unwrap() > 0);
        // Measured 2.9e-5 m (full; 2.9e-8 m reduced): BDF2's global error at rtol 1e-6, as in the benchmark of
        // case (b) (2.9e-5 m against a converged run; Radau's is 1.4e-6 m there). 1e-4 m bounds
        // it with a margin of 3 and still catches a wrong method (the tip moves ~5 cm).
        let d = max_tip_distance(a, b);
        eprintln!("{label}: {name} against Radau {d:.2e} m");
        assert!(d < 1e-4, "{label}: {d:.2e} m");
    }
}

/// Regression (issue 9, section 4): the output folder was checked only after the computation,
/// and a reused folder kept the previous run's files beside the new ones. Now the folder is
/// prepared first (a file named as the folder is refused at once, "not a directory"), the
/// previous run's result files are removed, and `status.txt` says `running` until the run ends.
#[test]
fn the_output_folder_is_checked_first_and_belongs_to_one_run() {
    let dir = TempDir::new("folder-first");
    let case = dir.write("case.toml", CASE);
    let file = dir.write("taken", "a file, not a folder");
    let o = flexwing_in(
        dir.path(),
        &[
            "dynamic",
            case.to_str().unwrap(),
            "--out",
            file.to_str().unwrap(),
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let err = stderr(&o);
    assert!(err.contains("is not a directory"), "{err}");
    // Nothing was computed: no summary on stdout.
    assert!(stdout(&o).is_empty(), "{}", stdout(&o));

    let out = dir.path().join("reused");
    fs::create_dir_all(&out).unwrap();
    for stale in [
        "dynamic_tip.svg",
        "dynamic_snapshots.png",
        "dynamic_tip.csv",
    ] {
        fs::write(out.join(stale), "from an older run").unwrap();
    }
    fs::write(out.join("status.txt"), "complete\n").unwrap();
    fs::write(out.join("notes.txt"), "the user's own file").unwrap();
    let o = flexwing_in(
        dir.path(),
        &[
            "dynamic",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
    );
    assert_success(&o);
    // The plots of the older run (this one has no --plot) are gone; the user's file stays.
    assert!(!out.join("dynamic_tip.svg").exists());
    assert!(!out.join("dynamic_snapshots.png").exists());
    assert!(out.join("notes.txt").exists());
    let tip = fs::read_to_string(out.join("dynamic_tip.csv")).unwrap();
    assert!(tip.starts_with("model,t_s"), "{tip}");
    assert_eq!(
        fs::read_to_string(out.join("status.txt")).unwrap(),
        "complete\n"
    );
}

#[test]
fn ctrl_c_and_kill_keep_what_was_computed_marked_interrupted() {
    // Regression (issue 9): an interrupted run left the previous run's files and `status.txt:
    // complete` in a reused folder. A run of 50 s (many minutes at rtol 1e-8) gets SIGINT, then
    // in a second run SIGTERM, after 2 s: each stops after its current step, writes the samples
    // it has, and `status.txt` says `interrupted`, exit status 1. Output every 1 ms, so that
    // samples past t = 0 exist within milliseconds even on a loaded machine (with 20 ms it
    // failed under a parallel workspace test: no sample after 2 s). atol 5e-9 is what Radau
    // applied for the former atol 1e-10 before it stopped scaling atol by 0.1 rtol^(-1/3)
    // (= 46 at rtol 1e-8; issue 24 item 4): the same run as before that change.
    let dir = TempDir::new("interrupt");
    let case = dir.write(
        "case.toml",
        &CASE
            .replace("elements = 4", "elements = 40")
            .replace("node = 4\n", "node = 40\n")
            .replace("end_time = 0.2", "end_time = 50.0")
            .replace(
                "output_step = 0.01",
                "output_step = 0.001\nrtol = 1e-8\natol = 5e-9",
            ),
    );
    assert!(case.exists());
    // The signal comes after 2 s; on a loaded machine (load 10–12 measured) the run may not
    // have kept a sample past t = 0 by then, so a run without one is repeated with a longer
    // delay (6 s, 15 s) before the test fails: every attempt still checks the interrupted status.
    for signal in ["-INT", "-TERM"] {
        let mut kept = 0;
        for delay_ms in [2000, 6000, 15000] {
            let out = dir.path().join("out");
            let child = std::process::Command::new(env!("CARGO_BIN_EXE_flexwing"))
                .args([
                    "dynamic",
                    case.to_str().unwrap(),
                    "--out",
                    out.to_str().unwrap(),
                ])
                .stdout(std::process::Stdio::piped())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .expect("the flexwing binary runs");
            std::thread::sleep(std::time::Duration::from_millis(delay_ms));
            let killed = std::process::Command::new("kill")
                .args([signal, &child.id().to_string()])
                .status()
                .expect("kill runs");
            assert!(killed.success());
            let o = child.wait_with_output().unwrap();
            assert_eq!(o.status.code(), Some(1), "{signal}: {}", stderr(&o));
            let status = fs::read_to_string(out.join("status.txt")).unwrap();
            assert!(
                status.starts_with("interrupted: full: "),
                "{signal}: {status}"
            );
            let (_, rows) = read_csv(&out.join("dynamic_tip.csv"));
            assert!(rows.len() < 50_001, "{signal}: the run was not stopped");
            kept = rows.len();
            if kept > 1 {
                break;
            }
        }
        assert!(kept > 1, "{signal}: no samples kept after 15 s");
    }
}

/// A long chain whose Radau steps mostly fail Newton (the alternating highest mode,
/// docs/model-choices.md) completes, counts the failures in its JSON and CSV, and says on standard
/// error that the run was slowed by them, with the advice; generalized-α at a fixed step runs the
/// same case without a failure and without the note, and so does Radau on elements that are rigid
/// bars (`beam.element_inertia = "bar"`); the tips agree.
#[test]
fn newton_failures_are_counted_and_a_long_chain_gets_a_note() {
    let dir = TempDir::new("newton-note");
    // `beam`: extra [beam] keys; `dynamic`: extra [dynamic] keys.
    let case = |beam: &str, dynamic: &str| {
        format!(
            "[beam]\nlength = 1.0\nelements = 4000\n{beam}[beam.section]\nEI = 50.0\n\
             mass_per_length = 0.2\n[[loads]]\ntype = \"point-force\"\nnode = 4000\n\
             direction = \"dead\"\nfy = 10.0\ntime = {{ type = \"sine\", omega = 20.0, phase = 0.0 }}\n\
             [dynamic]\nend_time = 0.3\noutput_step = 0.005\nfull = true\nrtol = 1e-2\n\
             atol = 5e-5\n{dynamic}"
        )
    };
    let radau = dir.write("radau.toml", &case("", "integrator = \"radau\"\n"));
    let (o, out) = run_dynamic(&dir, &radau, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let full = model(&doc, "full");
    let failed = full["stats"]["newton_failures"].as_u64().unwrap();
    let steps = full["stats"]["steps"].as_u64().unwrap();
    // Measured: 79 of 81 rejections failed Newton against 100 accepted steps (n = 4000), energy
    // balance error 9e-4 (limit 0.1). atol = 5e-5 rad is applied as given since issue 24 (Radau
    // applied 0.464 × 5e-5 = 2.3e-5 before); the case keeps 5e-5 because it is the tolerance a
    // user of a chain this long would pick (20 rtol / n, examples/long_chain.toml's rule, is
    // 5e-5 at rtol 1e-2) and it fails Newton as the test needs. The count is very sensitive to
    // atol on this chain (measured 88 failures / 108 steps at 2e-5, 222 / 145 at 2.3e-5, and
    // over 7000 / 4500 steps in 300 s at 3e-5): the pathology the note is about.
    assert!(failed >= 20 && 2 * failed >= steps, "{failed} of {steps}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("note: ")
            && err.contains("failed Newton")
            && err.contains("element_inertia = \"bar\"")
            && err.contains("generalized-alpha"),
        "{err}"
    );
    let (header, rows) = read_csv(&out.join("dynamic_summary.csv"));
    let column = header
        .split(',')
        .position(|c| c == "newton_failures")
        .unwrap();
    assert_eq!(rows[0][column], failed.to_string());
    let radau_tip = numbers(&full["tip"]["y_m"]);
    let largest_difference = |doc: &serde_json::Value| {
        numbers(&model(doc, "full")["tip"]["y_m"])
            .iter()
            .zip(&radau_tip)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
    };

    let alpha = dir.write(
        "alpha.toml",
        &case("", "integrator = \"generalized-alpha\"\nstep = 5e-4\n"),
    );
    let (o, _) = run_dynamic(&dir, &alpha, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    assert_eq!(model(&doc, "full")["stats"]["newton_failures"], 0);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("note: "));
    // Both are within their integration errors of the converged tip (Radau at rtol 1e-2 ~7e-5 m,
    // generalized-α at 0.5 ms ~2e-4 m over 1 s, docs/performance.md): measured 7.8e-5 m apart over
    // 0.3 s; bound 3e-4 m.
    let d = largest_difference(&doc);
    eprintln!("Radau − generalized-α: {d:.2e} m");
    assert!(d < 3e-4, "{d:.2e}");

    // Rigid bars: the same Radau run without the failures (measured: 34 steps, 6 rejected, none
    // by Newton, against 107 steps and 79 Newton failures; bound: fewer than 5). The bars' inertia
    // m ℓ²/12 changes the model by O(1/n²) (the continuum limit is the same); at n = 4000 that is
    // far below the integration error, so the bound on the tips is the integration error's, as
    // above (measured 8.6e-5 m apart).
    let bars = dir.write(
        "bars.toml",
        &case("element_inertia = \"bar\"\n", "integrator = \"radau\"\n"),
    );
    let (o, _) = run_dynamic(&dir, &bars, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let stats = &model(&doc, "full")["stats"];
    eprintln!("bars: {stats}");
    assert!(stats["newton_failures"].as_u64().unwrap() < 5, "{stats}");
    assert!(!String::from_utf8_lossy(&o.stderr).contains("note: "));
    let d = largest_difference(&doc);
    eprintln!("Radau on bars − Radau on point masses: {d:.2e} m");
    assert!(d < 3e-4, "{d:.2e}");
}

/// A coupled beam on rigid bars whose steps still mostly fail Newton (the offset mass's in-plane
/// inertia varies with the twist: docs/model-choices.md, "The coupled beam's Newton failures")
/// gets the note advising the section's flap inertia; with it, the failures go and the note with
/// them. The Table 1 beam on 1024 elements, tip force 100 sin(2t) N and tip torque 50 sin(3t)
/// N·m, 2 s, Radau at rtol 1e-3. Measured: 93 steps and 96 Newton failures on bars; 32 steps and
/// none with ρI = 0.005 kg·m. Bounds: the note's own condition (≥ 20 failures, ≥ half the
/// steps), and fewer than 5 failures with ρI.
#[test]
fn a_coupled_beam_on_bars_gets_the_flap_inertia_note() {
    let dir = TempDir::new("coupled-note");
    let case = |rotary: &str| {
        format!(
            "[beam]\nlength = 16.0\nelements = 1024\nelement_inertia = \"bar\"\n\
             [beam.section]\nEI = 2e4\nmass_per_length = 0.75\nGJ = 1e3\npolar_inertia = 0.1\n\
             polar_inertia_about = \"mass-centre\"\nd0 = 0.267\n{rotary}\
             [[loads]]\ntype = \"point-force\"\nnode = 1024\ndirection = \"dead\"\nfy = 100.0\n\
             time = {{ type = \"sine\", omega = 2.0, phase = 0.0 }}\n\
             [[loads]]\ntype = \"torque\"\nnode = 1024\nvalue = 50.0\n\
             time = {{ type = \"sine\", omega = 3.0, phase = 0.0 }}\n\
             [dynamic]\nend_time = 2.0\noutput_step = 0.02\nfull = true\nintegrator = \"radau\"\n\
             rtol = 1e-3\natol = 2e-5\n"
        )
    };
    let bars = dir.write("bars.toml", &case(""));
    let (o, _) = run_dynamic(&dir, &bars, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let stats = &model(&doc, "full")["stats"];
    let failed = stats["newton_failures"].as_u64().unwrap();
    let steps = stats["steps"].as_u64().unwrap();
    eprintln!("bars: {stats}");
    assert!(failed >= 20 && 2 * failed >= steps, "{stats}");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("note: ") && err.contains("beam.section.rotary_inertia"),
        "{err}"
    );

    let flap = dir.write("flap.toml", &case("rotary_inertia = 0.005\n"));
    let (o, _) = run_dynamic(&dir, &flap, &["--json"]);
    assert_success(&o);
    let doc = json(&o);
    let stats = &model(&doc, "full")["stats"];
    eprintln!("bars + flap inertia: {stats}");
    assert!(stats["newton_failures"].as_u64().unwrap() < 5, "{stats}");
    assert!(!String::from_utf8_lossy(&o.stderr).contains("note: "));
}
