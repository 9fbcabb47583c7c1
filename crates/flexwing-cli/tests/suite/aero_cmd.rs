//! `flexwing static` and `flexwing dynamic` on cases with `[aero]`: the static tip twist against
//! the closed form of a uniform wing in steady strip theory, and the gust example.

use std::fs;

use crate::common::{assert_success, example, flexwing_in, stdout, TempDir};
use serde_json::Value;

/// Patil's wing (e = c/4 ahead of the elastic axis, d0 = 0) at a small root angle: linear torsion
/// `GJ ψ'' + q c c_lα e (α_r + ψ) = 0`, `ψ(0) = 0`, `ψ'(L) = 0` gives the tip twist
/// `α_r (1/cos λL − 1)`, `λ² = q c c_lα e / GJ` (docs/aeroelastic-model.md §5).
#[test]
fn static_tip_twist_matches_the_closed_form_of_a_uniform_wing() {
    let dir = TempDir::new("aero-static");
    let text = fs::read_to_string(example("patil_flutter.toml"))
        .unwrap()
        .replace(
            "{ model = \"peters\", states = 6 }",
            "{ model = \"steady\" }",
        )
        .replace(
            "[aero.sweep]\nfrom = 2.0                 # m/s\nto = 40.0\n",
            "[aero.flight]\nroot_angle = 0.001\n\n[aero.sweep]\nfrom = 5.0\nto = 10.0\n",
        )
        .replace("steps = 20 ", "steps = 2 ");
    let (head, _) = text.split_once("[flutter]").unwrap();
    let case = dir.write("static.toml", head);
    let out = dir.path().join("out");
    let o = flexwing_in(
        dir.path(),
        &[
            "static",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
        ],
    );
    assert_success(&o);
    let doc: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(doc["status"], "complete");
    let points = doc["models"][0]["points"].as_array().unwrap();
    assert_eq!(points.len(), 2);
    for p in points {
        let u = p["speed_m_s"].as_f64().unwrap();
        let q = 0.5 * 0.0889 * u * u;
        let lambda = (q * 1.0 * 2.0 * std::f64::consts::PI * 0.25 / 1e4).sqrt();
        let exact = 0.001 * (1.0 / (lambda * 16.0).cos() - 1.0);
        let twist = p["tip_twist_rad"].as_f64().unwrap();
        // n = 32: measured 1.46e-5 relative at 10 m/s (6.2e-5 at n = 16: O(1/n²)); the
        // geometric non-linearity at α_r = 1e-3 is O(α_r²). Bound twice the measured gap.
        assert!(
            (twist / exact - 1.0).abs() < 3e-5,
            "U = {u}: {twist} vs {exact}"
        );
    }
    let csv = fs::read_to_string(out.join("static_aero.csv")).unwrap();
    assert!(csv.starts_with("model,speed_m_s,dynamic_pressure_pa,tip_x_m,tip_y_m,tip_twist_rad"));
}

/// The gust example: both models complete every output time; the run starts from the static
/// aeroelastic equilibrium, so the wing does not move before the gust arrives (t < 0.1 s).
#[test]
fn gust_example_starts_at_equilibrium_and_completes() {
    let dir = TempDir::new("aero-gust");
    let out = dir.path().join("out");
    let o = flexwing_in(
        dir.path(),
        &[
            "dynamic",
            example("patil_gust.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
        ],
    );
    assert_success(&o);
    let doc: Value = serde_json::from_str(&stdout(&o)).unwrap();
    assert_eq!(doc["status"], "complete");
    let models = doc["models"].as_array().unwrap();
    assert_eq!(models.len(), 2);
    for m in models {
        let s = m["samples"].as_array().unwrap();
        assert_eq!(s.len(), 201, "2 s every 0.01 s");
        let y = |k: usize| s[k]["tip_y_m"].as_f64().unwrap();
        // Before the gust the state is the equilibrium: any motion is the integrator's error on
        // a steady state (rtol 1e-6 of a tip deflection of a few metres).
        assert!(y(0) > 0.0);
        assert!((y(9) - y(0)).abs() < 1e-5 * y(0).abs(), "{} {}", y(0), y(9));
        // The upward gust raises the tip.
        let peak = (0..201).map(y).fold(f64::MIN, f64::max);
        assert!(peak > y(0) * 1.01, "{peak} vs {}", y(0));
    }
    let csv = fs::read_to_string(out.join("dynamic_aero.csv"))
        .unwrap()
        .to_lowercase();
    assert!(!csv.contains("nan") && !csv.contains("inf"));
    assert!(csv
        .lines()
        .next()
        .unwrap()
        .ends_with("kinetic_j,strain_j,work_j,dissipated_j,energy_balance_error"));
    // The energy audit: in the summary, in its own block and per sample, the same numbers; the
    // balance closes to the integration error (measured 7.2e-9 full, 2.8e-8 reduced at
    // rtol 1e-6; the limit is the default 1000 rtol = 1e-3). The gust does work on the wing.
    let summary = fs::read_to_string(out.join("dynamic_summary.csv")).unwrap();
    assert!(summary.contains("energy_balance_max_error,energy_balance_max_error_t_s"));
    for m in models {
        let audit = &m["energy_audit"];
        let max_error = audit["max_error"].as_f64().unwrap();
        assert_eq!(
            m["summary"]["energy_balance_max_error"].as_f64(),
            Some(max_error)
        );
        let limit = audit["limit"].as_f64().unwrap();
        assert!((limit - 1e-3).abs() < 1e-15, "{limit}");
        assert_eq!(m["summary"]["energy_balance_limit"].as_f64(), Some(limit));
        assert_eq!(audit["balanced"], true);
        assert!(audit["exceeded_time"].is_null() && audit["runaway_time"].is_null());
        assert!(max_error < 1e-6, "{audit}");
        let s = m["samples"].as_array().unwrap();
        let largest = s
            .iter()
            .map(|p| p["energy_balance_error"].as_f64().unwrap().abs())
            .fold(0.0, f64::max);
        // The samples are at output times, interpolated by the dense output between the
        // audited step ends: their balance carries the interpolation error too (measured
        // 5.6e-8 full against 7.2e-9 at the steps' ends).
        assert!(largest < 1e-6, "{largest} {max_error}");
        let work = s[200]["work_j"].as_f64().unwrap();
        assert!(work.abs() > 1.0, "{work}");
        assert_eq!(s[200]["dissipated_j"].as_f64(), Some(0.0));
    }
}

/// Runs made wrong on purpose are never `complete`: the gust example integrated by Dopri5
/// (explicit, on the stiff lag states) at rtol 1e-2, atol 0.1 blows up and is stopped by the
/// energy audit (measured: 21× the energy held at 0.09 s in the library test of the same
/// flight, `analysis::aero::audit_tests`); held to `energy_tolerance = 1e-10` a good run is
/// suspect. Both exit 1 and say so in the JSON and status.txt.
#[test]
fn gust_runs_that_go_wrong_are_stopped_or_suspect() {
    let dir = TempDir::new("aero-gust-wrong");
    let base = fs::read_to_string(example("patil_gust.toml"))
        .unwrap()
        .replace("end_time = 2.0 ", "end_time = 0.5 ")
        .replace("reduced = [6]", "reduced = []");
    let cases = [
        (
            base.replace("integrator = \"auto\"", "integrator = \"dopri5\"")
                .replace("rtol = 1e-6", "rtol = 1e-2")
                .replace("atol = 1e-8", "atol = 0.1"),
            "stopped",
            "runaway_time",
        ),
        (
            format!("{base}energy_tolerance = 1e-10\n"),
            "suspect",
            "exceeded_time",
        ),
    ];
    for (k, (text, word, when)) in cases.iter().enumerate() {
        let case = dir.write(&format!("wrong{k}.toml"), text);
        let out = dir.path().join(format!("out{k}"));
        let o = flexwing_in(
            dir.path(),
            &[
                "dynamic",
                case.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--json",
            ],
        );
        assert_eq!(o.status.code(), Some(1), "{}", stdout(&o));
        let doc: Value = serde_json::from_str(&stdout(&o)).unwrap();
        assert_eq!(doc["status"], *word, "{doc}");
        let m = &doc["models"][0];
        assert_eq!(m["summary"]["status"], *word);
        assert!(
            m["energy_audit"][when].as_f64().is_some(),
            "{}",
            m["energy_audit"]
        );
        let status = fs::read_to_string(out.join("status.txt")).unwrap();
        assert!(status.contains(word), "{status}");
    }
}
