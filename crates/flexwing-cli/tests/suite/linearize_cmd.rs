//! `flexwing linearize` on Patil's wing (`examples/patil_linearize.toml`): the static gain of its
//! linear model, `G(0) = D − C A⁻¹ B`, against the non-linear static aeroelastic solution of
//! `flexwing static` at a small root angle (an independent path: the Newton solve of the static
//! equations, no Jacobian of the linearization); the files it writes; its bad-input errors.
//! The eigenvalues and frequency responses are validated in the library
//! (`crates/flexwing/tests/suite/aero_linearize.rs`), the `.mat` and `.npz` read back by SciPy
//! and NumPy in the Python suite (`test_linearize.py`).

use nalgebra::DMatrix;
use serde_json::Value;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};

pub(crate) fn matrix(v: &Value) -> DMatrix<f64> {
    let rows: Vec<Vec<f64>> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|r| {
            r.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        })
        .collect();
    let (n, m) = (rows.len(), rows.first().map_or(0, Vec::len));
    DMatrix::from_fn(n, m, |i, j| rows[i][j])
}

pub(crate) fn names(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap().to_string())
        .collect()
}

pub(crate) fn run_json(dir: &TempDir, case: &std::path::Path, extra: &[&str]) -> Value {
    let out = dir.path().join("out");
    let mut args = vec![
        "linearize",
        case.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(extra);
    let o = flexwing_in(dir.path(), &args);
    assert_success(&o);
    serde_json::from_str(&stdout(&o)).expect("one JSON document")
}

/// The full model's static gain from the root angle and from the gust, times a small root angle
/// `ε`, against the non-linear static solution at `ε` (tip deflection, tip twist, lift).
#[test]
fn static_gain_matches_the_nonlinear_static_solution() {
    let dir = TempDir::new("linearize-gain");
    let doc = run_json(&dir, &example("patil_linearize.toml"), &[]);
    let full = &doc["models"][0];
    assert_eq!(full["summary"]["model"], "full");
    let ss = &full["state_space"];
    let (a, b, c, d) = (
        matrix(&ss["a"]),
        matrix(&ss["b"]),
        matrix(&ss["c"]),
        matrix(&ss["d"]),
    );
    let gain = &d - &c * a.lu().solve(&b).expect("A is regular below divergence");
    let inputs = names(&ss["inputs"]);
    let outputs = names(&ss["outputs"]);
    let col = |n: &str| inputs.iter().position(|s| s == n).unwrap();
    let row = |n: &str| outputs.iter().position(|s| s == n).unwrap();

    // The same wing at 20 m/s with a root angle ε, solved by `flexwing static` (sweep 10 → 20).
    let eps = 1e-4;
    let base = std::fs::read_to_string(example("patil_linearize.toml")).unwrap();
    let case = base.replace(
        "speed = 20.0 ",
        &format!("root_angle = {eps}\nspeed = 20.0 "),
    ) + "\n[aero.sweep]\nfrom = 10.0\nto = 20.0\nsteps = 2\n";
    assert!(case.contains("root_angle = 0.0001"));
    let path = dir.write("static.toml", &case);
    let o = flexwing_in(
        dir.path(),
        &["static", path.to_str().unwrap(), "--out", "s", "--json"],
    );
    assert_success(&o);
    let st: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let point = st["models"][0]["points"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["speed_m_s"] == 20.0)
        .expect("the point at 20 m/s")
        .clone();
    for (output, key) in [
        ("tip_y", "tip_y_m"),
        ("tip_twist", "tip_twist_rad"),
        ("lift", "lift_n"),
    ] {
        let nonlinear = point[key].as_f64().unwrap();
        let by_angle = gain[(row(output), col("root_angle"))] * eps;
        // A gust w is the root angle w/U to first order (both turn the upwash uniformly; no
        // gravity here).
        let by_gust = gain[(row(output), col("gust"))] * 20.0 * eps;
        // Linearization error O(ε) relative (1e-4) plus the static solver's tolerance: 1e-3.
        for linear in [by_angle, by_gust] {
            assert!(
                (linear - nonlinear).abs() <= 1e-3 * nonlinear.abs(),
                "{output}: linear {linear:e}, non-linear {nonlinear:e}"
            );
        }
    }
}

/// The files of every model, the shapes of the JSON matrices against the signal lists, and
/// `--inputs`/`--outputs`/`--states` overriding the case (regression/contract test).
#[test]
fn writes_every_model_and_takes_the_overrides() {
    let dir = TempDir::new("linearize-files");
    let doc = run_json(
        &dir,
        &example("patil_linearize.toml"),
        &[
            "--inputs",
            "gust[3],torque[32]",
            "--outputs",
            "root_bending_moment",
            "--states",
            "momenta",
        ],
    );
    assert_eq!(doc["status"], "complete");
    assert_eq!(doc["states"], "momenta");
    let out = dir.path().join("out");
    for label in ["full", "reduced-r4"] {
        for ext in ["mat", "npz"] {
            let p = out.join(format!("linear_{label}.{ext}"));
            let bytes = std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            match ext {
                "mat" => assert!(bytes.starts_with(b"MATLAB 5.0 MAT-file")),
                _ => assert!(bytes.starts_with(b"PK\x03\x04")),
            }
        }
    }
    let models = doc["models"].as_array().unwrap();
    assert_eq!(models.len(), 2);
    for (m, states) in models.iter().zip([64 * 2 + 32 * 6, 4 * 2 + 32 * 6]) {
        let ss = &m["state_space"];
        assert_eq!(names(&ss["inputs"]), ["gust[3]", "torque[32]"]);
        assert_eq!(names(&ss["outputs"]), ["root_bending_moment"]);
        assert_eq!(names(&ss["states"]).len(), states);
        let a = matrix(&ss["a"]);
        assert_eq!((a.nrows(), a.ncols()), (states, states));
        assert_eq!(matrix(&ss["b"]).shape(), (states, 2));
        assert_eq!(matrix(&ss["c"]).shape(), (1, states));
        assert_eq!(matrix(&ss["d"]).shape(), (1, 2));
        assert_eq!(m["poles"].as_array().unwrap().len(), states);
    }
    let csv = std::fs::read_to_string(out.join("linear_summary.csv")).unwrap();
    assert_eq!(csv.lines().count(), 3, "{csv}");
}

/// Bad input: one line naming the key, status 2; past the divergence speed: no model, status 1.
#[test]
fn bad_input_names_the_key() {
    let dir = TempDir::new("linearize-bad");
    let case = example("patil_linearize.toml");
    let case = case.to_str().unwrap();
    for (extra, status, expected) in [
        (
            vec!["--inputs", "gust,wind"],
            2,
            "linearize.inputs[1]: unknown input \"wind\"",
        ),
        (vec!["--outputs", "y[40]"], 2, "linearize.outputs[0]"),
        (vec!["--states", "positions"], 2, "--states"),
        (vec!["--speed", "-3"], 2, "aero.flight.speed"),
        // Past the divergence speed (37.15 m/s): no stable equilibrium.
        (vec!["--speed", "40"], 1, "no stable static equilibrium"),
    ] {
        let mut args = vec!["linearize", case, "--out", "o"];
        args.extend_from_slice(&extra);
        let o = flexwing_in(dir.path(), &args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(status), "{extra:?}: {err}");
        assert!(err.contains(expected), "{extra:?}: {err}");
        assert!(
            err.contains("aero.flight.speed") || !extra.contains(&"40"),
            "{err}"
        );
        assert!(!err.contains("panicked"), "{err}");
    }
}
