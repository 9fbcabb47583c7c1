//! `flexwing static` with control surfaces (`examples/patil_aileron.toml`): the rigid limit of
//! the wing against the thin-airfoil closed forms of the aileron's lift (Glauert) and hinge
//! moment (Theodorsen, written out here), the hinge-moment outputs (text, CSV, JSON), and bad
//! surfaces as one-line errors naming the key.

use std::fs;

use crate::common::{assert_success, example, run_case, run_json_case, stderr, stdout, TempDir};
use serde_json::Value;
use std::f64::consts::PI;

fn run(dir: &TempDir, case: &str, extra: &[&str]) -> std::process::Output {
    let path = dir.write("case.toml", case);
    run_case(dir, "static", &path, "out", extra)
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

/// `flexwing linearize` with the surfaces' signals on the stiff wing: the static gain
/// `D − C A⁻¹ B` of `delta[aileron]` on the lift and on the aileron's hinge moment against the
/// same thin-airfoil closed forms per radian, `q c c_lδ` and `q c² c_hδ` over its 4 m; the flap's
/// deflection leaves the aileron's hinge moment alone but through the (stiff) structure.
#[test]
fn stiff_wing_linear_model_gains_match_thin_airfoil_theory() {
    use crate::linearize_cmd::{matrix, names, run_json};
    let dir = TempDir::new("surfaces-linearize");
    let case = fs::read_to_string(example("patil_aileron.toml"))
        .unwrap()
        .replace("EI = 2.0e4 ", "EI = 2.0e10 ")
        .replace("GJ = 1.0e4 ", "GJ = 1.0e10 ")
        .replace(
            "[aero.sweep]",
            "[aero.flight]\nspeed = 20.0\n\n[aero.sweep]",
        );
    let path = dir.write("case.toml", &case);
    let doc = run_json(
        &dir,
        &path,
        &[
            "--inputs",
            "delta[aileron],delta[flap]",
            "--outputs",
            "lift,hinge_moment[aileron]",
        ],
    );
    let ss = &doc["models"][0]["state_space"];
    assert_eq!(names(&ss["inputs"]), ["delta[aileron]", "delta[flap]"]);
    assert_eq!(names(&ss["outputs"]), ["lift", "hinge_moment[aileron]"]);
    let (a, b, c, d) = (
        matrix(&ss["a"]),
        matrix(&ss["b"]),
        matrix(&ss["c"]),
        matrix(&ss["d"]),
    );
    let gain = &d - &c * a.lu().solve(&b).unwrap();
    let (xh, span, rho, u): (f64, f64, f64, f64) = (0.8, 4.0, 0.0889, 20.0);
    let q = 0.5 * rho * u * u;
    let theta = (1.0 - 2.0 * xh).acos();
    let cl_delta = 2.0 * (PI - theta + theta.sin());
    let cc: f64 = 2.0 * xh - 1.0;
    let (s, f) = ((1.0 - cc * cc).sqrt(), cc.acos());
    let (t4, t5, t10) = (-f + cc * s, -s * s - f * f + 2.0 * cc * s * f, s + f);
    let t12 = s * (2.0 + cc) - f * (2.0 * cc + 1.0);
    let ch_delta = -((t5 - t4 * t10) + t10 * t12) / (2.0 * PI);
    // About δ₀ = 0.02 the strip's angle is ε = atan ξ, ξ = T10 δ₀/π = 0.011, and its lift,
    // normal to the relative flow, has the vertical share cos ε: the slope of ξ ↦ atan ξ cos ε
    // is 1 − 5ξ²/2 (3.0e-4 below the linear theory's; measured −3.022e-4 before the factor).
    // Left: O(ξ⁴) ~1e-8 and the stiff wing's twist ~1e-7. Bound 1e-5.
    let xi = t10 * 0.02 / PI;
    let lift = gain[(0, 0)];
    let want = q * cl_delta * span * (1.0 - 2.5 * xi * xi);
    let h = gain[(1, 0)];
    let want_h = q * ch_delta * span;
    eprintln!(
        "lift {:.3e}, hinge {:.3e}",
        lift / want - 1.0,
        h / want_h - 1.0
    );
    assert!((lift / want - 1.0).abs() < 1e-5, "{lift} vs {want}");
    // The circulatory part's atan has the slope 1 − ξ² (measured −3.6e-5 overall). Bound 1e-4.
    assert!((h / want_h - 1.0).abs() < 1e-4, "{h} vs {want_h}");
    // The flap's lift (8 m, hinge 75 %) but no direct hinge moment on the aileron: the stiff
    // wing's twist carries ~1e-6 of it.
    assert!(gain[(0, 1)] > lift, "{}", gain[(0, 1)]);
    assert!(gain[(1, 1)].abs() < 1e-4 * h.abs(), "{}", gain[(1, 1)]);
    assert_eq!(d[(1, 1)], 0.0);
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
        assert_refused(&o, key, "");
    }
}

/// examples/patil_aileron.toml with its first `from` replaced by `to`.
fn aileron_with(from: &str, to: &str) -> String {
    let base = fs::read_to_string(example("patil_aileron.toml")).unwrap();
    assert!(base.contains(from), "{from}");
    base.replacen(from, to, 1)
}

/// `o` exited with status 2 and one line naming `key` and saying `what`.
fn assert_refused(o: &std::process::Output, key: &str, what: &str) {
    assert_eq!(o.status.code(), Some(2), "{key}: {}", stderr(o));
    let err = stderr(o);
    assert!(err.contains(key) && err.contains(what), "{key}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}

/// A deflection's time history (`deflection_change`, `deflection_function`) is a dynamic run's:
/// `flexwing static`, `flutter` and `linearize` (which hold the surface at its `deflection`)
/// refuse it with exit status 2 and one line naming the key, rather than ignore it.
#[test]
fn runs_about_an_equilibrium_refuse_a_deflection_history() {
    let text = aileron_with(
        "deflection = 0.02",
        "deflection = 0.02\ndeflection_change = 0.01\ndeflection_function = { type = \"ramp\", \
         start = 0.0, end = 1.0 }",
    );
    // patil_aileron.toml has no [aero.flight] speed; linearize needs one.
    let text = format!("{text}\n[aero.flight]\nspeed = 10.0\n");
    let key = "aero.surfaces[1].deflection_change";
    for command in ["static", "flutter", "linearize"] {
        let dir = TempDir::new("surfaces-history");
        let path = dir.write("case.toml", &text);
        let o = run_case(&dir, command, &path, "out", &[]);
        assert_refused(&o, key, "holds the surface");
    }
}

/// `flexwing dynamic` writes each surface's hinge moment per output time (`dynamic_hinges.csv`,
/// `hinge_moments` in the JSON). The response starts at the static aeroelastic equilibrium
/// and, with nothing changing, stays there: its hinge moments equal those of `flexwing static`
/// at the same speed (the static solver's equilibrium, an independent path) at every output
/// time, within 1e-6 relative (the static Newton tolerance and the integration's, rtol 1e-8).
#[test]
fn dynamic_hinge_moments_of_a_wing_at_rest_are_the_static_ones() {
    let text = aileron_with(
        "[aero.sweep]\nspeeds = [5.0, 10.0, 15.0, 20.0, 25.0, 30.0, 35.0]",
        "[aero.flight]\nspeed = 10.0\n\n[dynamic]\nend_time = 0.1\noutput_step = 0.05\n\
         rtol = 1e-8\natol = 1e-10\nreduced = []\n",
    );
    let dir = TempDir::new("surfaces-dynamic-hinges");
    let path = dir.write("case.toml", &text);
    let json = |command: &str| run_json_case(&dir, command, &path, command);
    let statics = json("static");
    let dynamic = json("dynamic");
    let csv = fs::read_to_string(dir.path().join("dynamic/dynamic_hinges.csv")).unwrap();
    assert!(
        csv.starts_with("model,t_s,surface,hinge_moment_n_m\n"),
        "{csv}"
    );
    // 3 output times × 2 surfaces.
    assert_eq!(csv.lines().count(), 1 + 3 * 2, "{csv}");
    let rows = |doc: &Value| {
        doc["models"][0]["hinge_moments"]
            .as_array()
            .unwrap()
            .clone()
    };
    let reference = rows(&statics);
    let hinges = rows(&dynamic);
    assert_eq!(hinges.len(), 6);
    for h in &hinges {
        let surface = h["surface"].as_str().unwrap();
        let r = reference.iter().find(|r| r["surface"] == surface).unwrap()["hinge_moment_n_m"]
            .as_f64()
            .unwrap();
        let v = h["hinge_moment_n_m"].as_f64().unwrap();
        assert!((v - r).abs() <= 1e-6 * r.abs(), "{surface}: {v} vs {r}");
    }
}
