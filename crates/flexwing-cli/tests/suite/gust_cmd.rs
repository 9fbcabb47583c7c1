//! `flexwing gust` on Patil's wing (`examples/patil_gust_family.toml`, cut to 3 gusts on 8
//! elements): the files it writes and what they hold, the JSON document, the plot, the errors of
//! a case without `[gust_family]`. A contract test of the command: the family's numbers are
//! validated in the library (`crates/flexwing/tests/suite/aero_gust_family.rs`) and against
//! SciPy in the Python suite (`test_gust_family.py`).

use serde_json::Value;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};

/// The example with 3 gusts (30, 190, 350 ft) on 8 elements.
fn small_case(dir: &TempDir) -> std::path::PathBuf {
    let text = std::fs::read_to_string(example("patil_gust_family.toml"))
        .unwrap()
        .replace("steps = 20", "steps = 3")
        .replace("elements = 16", "elements = 8");
    dir.write("family.toml", &text)
}

/// The CSV files: one row per model and gust, the critical rows agree with the members' peaks
/// (the member of largest magnitude, its signed extreme); the JSON document carries the same;
/// `--plot` writes the figure.
#[test]
fn gust_writes_its_files_and_document() {
    let dir = TempDir::new("gust-cmd");
    let case = small_case(&dir);
    let out = dir.path().join("out");
    let o = flexwing_in(
        dir.path(),
        &[
            "gust",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
            "--plot",
        ],
    );
    assert_success(&o);
    let doc: Value = serde_json::from_str(&stdout(&o)).expect("one JSON document");
    assert_eq!(doc["status"], "complete");
    let models = doc["models"].as_array().unwrap();
    let labels: Vec<&str> = models
        .iter()
        .map(|m| m["model"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["full", "reduced-r6"]);
    let outputs: Vec<&str> = doc["family"]["outputs"]
        .as_array()
        .unwrap()
        .iter()
        .map(|o| o["name"].as_str().unwrap())
        .collect();
    assert_eq!(
        outputs,
        [
            "tip_y",
            "tip_twist",
            "root_bending_moment",
            "root_torque",
            "lift"
        ]
    );
    for m in models {
        let members = m["members"].as_array().unwrap();
        assert_eq!(members.len(), 3);
        let h: Vec<f64> = members
            .iter()
            .map(|r| r["gradient_ft"].as_f64().unwrap())
            .collect();
        for (got, want) in h.iter().zip([30.0, 190.0, 350.0]) {
            assert!((got - want).abs() < 1e-9, "{h:?}");
        }
        // U_ds = U_ref (H/350 ft)^(1/6) with U_ref = 1 m/s, F_g = 1.
        for r in members {
            let u = r["design_velocity_m_s"].as_f64().unwrap();
            let expected = (r["gradient_ft"].as_f64().unwrap() / 350.0).powf(1.0 / 6.0);
            assert!((u - expected).abs() < 1e-12, "{u} {expected}");
        }
        for c in m["critical"].as_array().unwrap() {
            let name = c["output"].as_str().unwrap();
            let unit = match name {
                "tip_y" => "m",
                "tip_twist" => "rad",
                "lift" => "n",
                _ => "n_m",
            };
            let peak =
                |r: &Value, which: &str| r[format!("{name}_{which}_{unit}")].as_f64().unwrap();
            let best = members
                .iter()
                .max_by(|a, b| {
                    let m = |r: &Value| peak(r, "max").abs().max(peak(r, "min").abs());
                    m(a).total_cmp(&m(b))
                })
                .unwrap();
            assert_eq!(c["gradient_m"], best["gradient_m"], "{name}");
            let (max, min) = (peak(best, "max"), peak(best, "min"));
            let extreme = if max.abs() >= min.abs() { max } else { min };
            assert_eq!(c["peak"].as_f64().unwrap(), extreme, "{name}");
        }
    }
    let csv = std::fs::read_to_string(out.join("gust_family.csv")).unwrap();
    let mut lines = csv.lines();
    let header = lines.next().unwrap();
    assert!(
        header.starts_with("model,gradient_m,gradient_ft,design_velocity_m_s,tip_y_max_m,"),
        "{header}"
    );
    assert_eq!(lines.count(), 6, "2 models × 3 gusts");
    let critical = std::fs::read_to_string(out.join("gust_family_critical.csv")).unwrap();
    assert_eq!(critical.lines().count(), 1 + 2 * 5, "{critical}");
    for f in ["gust_family.png", "gust_family.svg", "status.txt"] {
        assert!(out.join(f).exists(), "{f}");
    }
}

/// A case without `[gust_family]`, and one whose end time does not let the longest gust pass:
/// exit status 2 and one line naming the key.
#[test]
fn gust_errors_name_the_key() {
    let dir = TempDir::new("gust-errors");
    let text = std::fs::read_to_string(small_case(&dir)).unwrap();
    let start = text.find("[gust_family]").unwrap();
    let end = text.find("[dynamic]").unwrap();
    for (label, text, key) in [
        (
            "no table",
            format!("{}{}", &text[..start], &text[end..]),
            "gust_family: missing",
        ),
        (
            "short",
            text.replace("end_time = 10.0", "end_time = 5.0"),
            "dynamic.end_time: the longest gust",
        ),
    ] {
        let case = dir.write(&format!("{label}.toml"), &text);
        let o = flexwing_in(dir.path(), &["gust", case.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{label}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim().lines().count(), 1, "{label}: {e}");
        assert!(e.contains(key), "{label}: {e}");
    }
}
