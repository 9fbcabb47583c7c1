//! `flexwing static` with control surfaces (`examples/patil_aileron.toml`): the rigid limit of
//! the wing against the thin-airfoil closed forms of the aileron's lift (Glauert) and hinge
//! moment (Theodorsen, written out here), the hinge-moment outputs (text, CSV, JSON), and bad
//! surfaces as one-line errors naming the key.

use std::fs;

use crate::common::{assert_success, example, flexwing_in, stderr, stdout, TempDir};
use serde_json::Value;
use std::f64::consts::PI;

fn run(dir: &TempDir, case: &str, extra: &[&str]) -> std::process::Output {
    let path = dir.write("case.toml", case);
    let out = dir.path().join("out");
    let mut args = vec![
        "static",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    flexwing_in(dir.path(), &args)
}

/// A stiff wing (EI and GJ × 1e6) barely twists: the aileron's lift is `q c c_lδ δ` over its
/// 4 m, `c_lδ = 2(π − θ + sin θ)`, `cos θ = 1 − 2 x_h` (Glauert), and its hinge moment
/// `q c² c_hδ δ` over 4 m with Theodorsen's `c_hδ = −[(T5 − T4 T10) + T10 T12]/(2π)`; the
/// undeflected flap carries none.
#[test]
fn stiff_wing_aileron_matches_thin_airfoil_theory() {
    let dir = TempDir::new("surfaces");
    let case = fs::read_to_string(example("patil_aileron.toml"))
        .unwrap()
        .replace("EI = 2.0e4 ", "EI = 2.0e10 ")
        .replace("GJ = 1.0e4 ", "GJ = 1.0e10 ");
    let o = run(&dir, &case, &["--json"]);
    assert_success(&o);
    let doc: Value = serde_json::from_str(&stdout(&o)).unwrap();
    let model = &doc["models"][0];
    let (xh, delta, span, rho): (f64, f64, f64, f64) = (0.8, 0.02, 4.0, 0.0889);
    let theta = (1.0 - 2.0 * xh).acos();
    let cl_delta = 2.0 * (PI - theta + theta.sin());
    let c: f64 = 2.0 * xh - 1.0;
    let (s, f) = ((1.0 - c * c).sqrt(), c.acos());
    let (t4, t5, t10) = (-f + c * s, -s * s - f * f + 2.0 * c * s * f, s + f);
    let t12 = s * (2.0 + c) - f * (2.0 * c + 1.0);
    let ch_delta = -((t5 - t4 * t10) + t10 * t12) / (2.0 * PI);
    let points = model["points"].as_array().unwrap();
    let hinges = model["hinge_moments"].as_array().unwrap();
    assert_eq!(hinges.len(), 2 * points.len());
    for (k, p) in points.iter().enumerate() {
        let u = p["speed_m_s"].as_f64().unwrap();
        let q = 0.5 * rho * u * u;
        let lift = p["lift_n"].as_f64().unwrap();
        let want = q * cl_delta * delta * span;
        // The strip's angle of attack is atan(T10 δ/π): its lift falls short of the linear
        // c_lδ δ by (T10 δ/π)²/3 = 4e-5 relative; the stiff wing's twist adds ~1e-7. Bound 5×.
        assert!(
            (lift / want - 1.0).abs() < 2e-4,
            "U = {u}: {lift} vs {want}"
        );
        let aileron = &hinges[2 * k + 1];
        assert_eq!(aileron["surface"], "aileron");
        let h = aileron["hinge_moment_n_m"].as_f64().unwrap();
        let want_h = q * ch_delta * delta * span;
        // The circulatory part follows the lift (the same O(δ²) as above).
        assert!((h / want_h - 1.0).abs() < 2e-4, "U = {u}: {h} vs {want_h}");
        let flap = hinges[2 * k]["hinge_moment_n_m"].as_f64().unwrap();
        assert!(flap.abs() < 1e-6 * h.abs(), "flap {flap}");
    }
    let csv = fs::read_to_string(dir.path().join("out/static_hinges.csv")).unwrap();
    assert!(csv.starts_with("model,speed_m_s,surface,deflection_rad,hinge_moment_n_m\n"));
    assert_eq!(csv.lines().count(), 1 + 2 * points.len());
}

/// The example's text report lists the hinge moments.
#[test]
fn the_example_reports_hinge_moments() {
    let dir = TempDir::new("surfaces-text");
    let case = fs::read_to_string(example("patil_aileron.toml")).unwrap();
    let o = run(&dir, &case, &[]);
    assert_success(&o);
    let text = stdout(&o);
    assert!(
        text.contains("hinge moments (N·m, trailing edge down positive):"),
        "{text}"
    );
    assert!(text.contains("aileron (δ = 0.02 rad)"), "{text}");
}

/// Bad surfaces: exit status 2, one line naming the key.
#[test]
fn bad_surfaces_are_one_line_errors_naming_the_key() {
    let base = fs::read_to_string(example("patil_aileron.toml")).unwrap();
    let cases = [
        ("hinge = 0.8", "hinge = 1.2", "aero.surfaces[1].hinge"),
        ("to = 16.0", "to = 17.0", "aero.surfaces[1].to"),
        ("from = 12.0", "from = 7.5", "aero.surfaces[1].from"),
        (
            "name = \"aileron\"",
            "name = \"flap\"",
            "aero.surfaces[1].name",
        ),
        (
            "deflection = 0.02",
            "deflection = 0.02\nangle = 1.0",
            "angle",
        ),
    ];
    for (from, to, key) in cases {
        assert!(base.contains(from), "{from}");
        let dir = TempDir::new("surfaces-bad");
        let o = run(&dir, &base.replacen(from, to, 1), &[]);
        assert_eq!(o.status.code(), Some(2), "{from} → {to}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(err.contains(key), "{key}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
}
