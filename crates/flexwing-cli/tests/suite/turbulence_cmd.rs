//! `flexwing turbulence` on Patil's wing (`examples/patil_turbulence.toml`, run as it is): the
//! files it writes and what they hold, the JSON document, the plot, and the errors of a bad
//! key. A contract test of the command: the spectra are validated in the library
//! (`solve/aeroelastic/turbulence_tests.rs`, `tests/suite/aero_turbulence.rs`) and against
//! SciPy in the Python suite (`test_turbulence.py`).

use serde_json::Value;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};

/// The RMS rows and the PSD rows of both models and four outputs; the RMS² of each convergent
/// output is the trapezoidal rule of its `turbulence_psd.csv` in `ω` (a second quadrature of the
/// written numbers) within 1e-3 of the variance: the two rules differ by the low-end rectangle
/// (`ω_min Φ(ω_min)`, below 1e-4 of the variance with `ω_min = 1e-3 U/L`) and the resolution
/// of the peaks on 500 points (the trapezoid in `ω` is the cruder one). The lift is flagged as
/// diverging, with a note.
#[test]
fn turbulence_writes_its_files_and_document() {
    let dir = TempDir::new("turbulence-cmd");
    let out = dir.path().join("out");
    let case = example("patil_turbulence.toml");
    let o = flexwing_in(
        dir.path(),
        &[
            "turbulence",
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
    assert_eq!(doc["spectrum"], "von-karman");
    assert_eq!(doc["frequencies"], 500);
    let models = doc["models"].as_array().unwrap();
    let labels: Vec<&str> = models
        .iter()
        .map(|m| m["model"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["full", "reduced-r6"]);
    for m in models {
        let w: Vec<f64> = m["frequencies_rad_s"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(w.len(), 500);
        assert!(w.windows(2).all(|p| p[1] > p[0]));
        // The gust's own RMS over the grid and tails is σ_w = 1 m/s (von Kármán's constant is
        // exact; the quadrature error is below 1e-4 here).
        assert!((m["gust_rms_m_s"].as_f64().unwrap() - 1.0).abs() < 1e-4);
        let outputs = m["outputs"].as_array().unwrap();
        let names: Vec<&str> = outputs
            .iter()
            .map(|o| o["output"].as_str().unwrap())
            .collect();
        assert_eq!(names, ["tip_y", "tip_twist", "root_bending_moment", "lift"]);
        for o in outputs {
            let psd: Vec<f64> = o["psd"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let trapezoid: f64 = w
                .windows(2)
                .zip(psd.windows(2))
                .map(|(x, y)| 0.5 * (x[1] - x[0]) * (y[0] + y[1]))
                .sum();
            let rms = o["rms"].as_f64().unwrap();
            let diverges = o["diverges"].as_bool().unwrap();
            assert_eq!(diverges, o["output"] == "lift", "{o}");
            let tail = o["tail_variance"].as_f64().unwrap_or(0.0);
            let relative = (trapezoid + tail) / (rms * rms) - 1.0;
            assert!(relative.abs() < 1e-3, "{}: {relative:e}", o["output"]);
        }
    }
    let notes = doc["notes"].as_array().unwrap();
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(notes[0].as_str().unwrap().contains("lift"));
    let rms = std::fs::read_to_string(out.join("turbulence_rms.csv")).unwrap();
    assert_eq!(rms.lines().count(), 1 + 2 * 4, "{rms}");
    assert!(
        rms.starts_with("model,output,unit,rms,variance_error,tail_variance,tail_slope,diverges\n")
    );
    let psd = std::fs::read_to_string(out.join("turbulence_psd.csv")).unwrap();
    assert_eq!(psd.lines().count(), 1 + 2 * 4 * 500);
    for f in ["turbulence_psd.svg", "turbulence_psd.png", "status.txt"] {
        assert!(out.join(f).exists(), "{f}");
    }
}

/// A case without `[turbulence]`, a misspelt key, a bad value: exit status 2 and one line
/// naming the key.
#[test]
fn turbulence_errors_name_the_key() {
    let dir = TempDir::new("turbulence-errors");
    let text = std::fs::read_to_string(example("patil_turbulence.toml")).unwrap();
    let start = text.find("[turbulence]").unwrap();
    for (label, text, key) in [
        ("no table", text[..start].to_string(), "turbulence: missing"),
        (
            "misspelt",
            text.replace("intensity = 1.0", "sigma = 1.0"),
            "sigma",
        ),
        (
            "negative",
            text.replace("intensity = 1.0", "intensity = -1.0"),
            "turbulence.intensity: must be a finite positive",
        ),
        (
            "few frequencies",
            text.replace("frequencies = 500", "frequencies = 8"),
            "turbulence.frequencies",
        ),
    ] {
        let case = dir.write(&format!("{label}.toml"), &text);
        let o = flexwing_in(dir.path(), &["turbulence", case.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(2), "{label}: {}", stderr(&o));
        let e = stderr(&o);
        assert_eq!(e.trim().lines().count(), 1, "{label}: {e}");
        assert!(e.contains(key), "{label}: {e}");
    }
}
