//! The 3-D chain from the command line (`beam.model = "chain3d"`): `flexwing flutter`, `modes`,
//! `study` and `static` on the 3-D examples, against references that do not come from the code:
//! the continuum Kirchhoff rod of `crates/flexwing/tests/data/chain3d_reference/` (README §2:
//! linearized about its exact static state with the same strip theory, solved by shooting,
//! exact to ~1e-11) for Patil's wing, and the closed forms of the uniform cantilever for its
//! modes. The chain's error is its O(n⁻²) discretization error (n = 32 here); the library tests
//! `aero3d_patil_deformed` and `chain3d_modes` show the second-order convergence, these check that
//! the case file, the dispatcher and the renderers carry those numbers through unchanged. The
//! static aeroelastic run (`flexwing static` with `[aero]`) is checked against the closed form
//! of a uniform wing in steady strip theory and against the rod's divergence.
//! Bad input on a 3-D case: one line naming the key, exit status 2.

use std::path::Path;

use crate::common::{example, flexwing_in, run_json_case, stderr, stdout, TempDir};
use serde_json::Value;

/// Run `flexwing COMMAND CASE --json` (files in `out`) and parse the document.
fn run_json(command: &str, case: &Path, dir: &TempDir) -> Value {
    run_json_case(dir, command, case, "out")
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

/// The rod's rows of `patil_deformed_flutter.csv`: `(load, tip_y, U)` of `model`, `quantity`.
fn rod(model: &str, quantity: &str) -> Vec<(f64, f64, f64, f64)> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../flexwing/tests/data/chain3d_reference/patil_deformed_flutter.csv");
    let text = std::fs::read_to_string(&path).unwrap();
    text.lines()
        .skip(1)
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|r| r[0] == "tip_force" && r[4] == model && r[5] == quantity)
        .map(|r| {
            let p = |s: &str| s.parse::<f64>().unwrap();
            (p(r[1]), p(r[3]), p(r[6]), p(r[7]))
        })
        .collect()
}

fn rod_at(model: &str, quantity: &str, load: f64) -> (f64, f64, f64) {
    let (_, y, u, w) = rod(model, quantity)
        .into_iter()
        .find(|r| r.0 == load)
        .unwrap_or_else(|| panic!("no rod {model} {quantity} at {load} N"));
    (y, u, w)
}

/// `examples/patil_3d_flutter.toml` (24 N tip force, Peters 6, n = 32): the flutter speed and
/// frequency, the divergence speed and the tip deflection against the rod. Measured: flutter
/// 23.31788 m/s against 23.327657 (−9.8e-3, the library test's n = 32 error), frequency
/// −2.5e-3 rad/s, divergence −3.6e-3 m/s, tip y +7.9e-4 m. Bounds 1.5 times those: the n = 32
/// discretization error, which the library test shows falling at second order.
#[test]
fn patil_3d_flutter_example_against_the_continuum_rod() {
    let dir = TempDir::new("patil3d");
    let doc = run_json("flutter", &example("patil_3d_flutter.toml"), &dir);
    assert_eq!(doc["status"], "complete", "{doc}");
    assert_eq!(doc["model"], "chain3d");
    assert_eq!(doc["n_dofs"], 96);
    let (tip_y, u, w) = rod_at("peters6", "flutter", 24.0);
    let flutter = &doc["stability"]["flutter"];
    let (du, dw) = (num(&flutter["speed"]) - u, num(&flutter["frequency"]) - w);
    println!("flutter error {du:+.3e} m/s, {dw:+.3e} rad/s");
    assert!(du.abs() < 1.5e-2, "flutter {flutter} against {u}");
    assert!(dw.abs() < 4e-3, "frequency {flutter} against {w}");
    let (_, u_div, _) = rod_at("steady", "divergence", 24.0);
    let dd = num(&doc["divergence"]["speed"]) - u_div;
    assert!(dd.abs() < 5.5e-3, "divergence error {dd}");
    // The equilibrium at the first speed (2 m/s: the lift at zero angle is nil, the tip force
    // alone bends the wing) against the rod's static tip.
    let tip = &doc["equilibria"][0]["tip"];
    let dy = num(&tip[1]) - tip_y;
    assert!(dy.abs() < 1.2e-3, "tip y error {dy}");
    // The 3-D shape is in the document: n + 1 nodes with x, y, z and n section rotations.
    let shape = &doc["equilibria"][0]["shape"];
    assert_eq!(shape["position"].as_array().unwrap().len(), 33);
    assert_eq!(shape["rotation"].as_array().unwrap().len(), 32);
    let nodes = std::fs::read_to_string(dir.path().join("out/flutter_nodes.csv")).unwrap();
    assert!(nodes.starts_with("point,value,node,span_m,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad"));
}

/// `flexwing static` with `[aero]` on Patil's 3-D wing without the tip force, steady strip
/// theory, root angle `α_r = 1e-3`, at 5 and 10 m/s: linear torsion `GJ ψ'' + q c c_lα e (α_r +
/// ψ) = 0`, `ψ(0) = 0`, `ψ'(L) = 0` (e = c/4 ahead of the elastic axis) gives `ψ(y) = α_r (tan λL
/// sin λy + cos λy − 1)`, `λ² = q c c_lα e / GJ`: the tip twist `α_r (1/cos λL − 1)`, each
/// strip's lift `q c c_lα (α_r + ψ(y)) ℓ` and the total `q c c_lα α_r tan(λL)/λ`. The 3-D chain
/// also bends and tilts its lift, effects of order `α_r²` here.
#[test]
fn patil_3d_static_aero_against_the_closed_form_of_a_uniform_wing() {
    let dir = TempDir::new("aero-static3d");
    let text = std::fs::read_to_string(example("patil_3d_flutter.toml")).unwrap();
    let (head, _) = text.split_once("[flutter]").unwrap();
    let (beam, rest) = head.split_once("[[loads]]").unwrap();
    let (_, aero) = rest.split_once("[aero]").unwrap();
    let case = format!("{beam}[aero]{aero}")
        .replace(
            "{ model = \"peters\", states = 6 }",
            "{ model = \"steady\" }",
        )
        .replace(
            "[aero.sweep]\nfrom = 2.0                 # m/s\nto = 40.0\nsteps = 20 ",
            "[aero.flight]\nroot_angle = 0.001\n\n[aero.sweep]\nfrom = 5.0\nto = 10.0\nsteps = 2 ",
        );
    assert!(case.contains("root_angle = 0.001") && !case.contains("fy = 24.0"));
    let case = format!("{case}\n[output]\nvtk = true\n");
    let doc = run_json("static", &dir.write("static.toml", &case), &dir);
    assert_eq!(doc["status"], "complete", "{doc}");
    let equilibria = doc["equilibria"].as_array().unwrap();
    assert_eq!(equilibria.len(), 2);
    let span: Vec<f64> = doc["strip_span"]
        .as_array()
        .unwrap()
        .iter()
        .map(num)
        .collect();
    assert_eq!(span.len(), 32);
    let (alpha, l, a) = (0.001, 16.0, 2.0 * std::f64::consts::PI);
    for e in equilibria {
        let u = num(&e["speed"]);
        let q = 0.5 * 0.0889 * u * u;
        let lambda = (q * a * 0.25 / 1e4).sqrt();
        let twist = alpha * (1.0 / (lambda * l).cos() - 1.0);
        let lift = q * a * alpha * (lambda * l).tan() / lambda;
        let dt = num(&e["tip_twist"]) / twist - 1.0;
        let dl = num(&e["lift"]) / lift - 1.0;
        let strips: Vec<f64> = e["strip_lift"]
            .as_array()
            .unwrap()
            .iter()
            .map(num)
            .collect();
        let width = l / 32.0;
        let ds = strips
            .iter()
            .zip(&span)
            .map(|(&f, &y)| {
                let psi = alpha * ((lambda * l).tan() * (lambda * y).sin() + (lambda * y).cos());
                f / (q * a * psi * width) - 1.0
            })
            .fold(0.0_f64, |m, d| m.max(d.abs()));
        println!("U = {u}: tip twist {dt:+.2e}, lift {dl:+.2e}, strips {ds:.2e} (relative)");
        // Measured at n = 32, 10 m/s: tip twist +6.8e-6, lift +2.9e-5, strips 2.2e-5 (5 m/s:
        // 1.5e-6, 7.3e-6, 5.5e-6). The lift converges at second order (1.2e-4, 2.9e-5, 6.2e-6
        // at n = 16, 32, 64); the tip twist goes 5.4e-5, 6.8e-6, −5.0e-6, a remainder of about
        // −5e-6 that does not fall with n (not identified; the lift, from the same twists,
        // shows no such floor). Bounds about twice the measured n = 32 gaps.
        assert!(dt.abs() < 1.5e-5, "U = {u}: tip twist {dt}");
        assert!(dl.abs() < 6e-5, "U = {u}: lift {dl}");
        assert!(ds < 4.5e-5, "U = {u}: strip lift {ds}");
    }
    let strips = std::fs::read_to_string(dir.path().join("out/static_strips.csv")).unwrap();
    assert!(strips.starts_with("point,speed_m_s,strip,span_m,lift_n"));
    assert_eq!(strips.lines().count(), 1 + 2 * 32);
    let nodes = std::fs::read_to_string(dir.path().join("out/static_nodes.csv")).unwrap();
    assert!(nodes.starts_with("point,value,node,span_m,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad"));
    // The VTK series: a frame per equilibrium, its time the speed.
    let pvd = std::fs::read_to_string(dir.path().join("out/vtk/static_aero.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 2, "{pvd}");
    assert!(pvd.contains("timestep=\"10.0\""), "{pvd}");
}

/// `flexwing static` on `examples/patil_3d_flutter.toml` (24 N tip force, sweep to 40 m/s):
/// the divergence speed against the rod (the bound of the flutter test above: the n = 32
/// error), the sweep stopped past it with its points kept; and, a regression check of the one
/// path the two commands share, its equilibria are those of `flexwing flutter` on the same case.
#[test]
fn patil_3d_static_aero_diverges_where_the_rod_does() {
    let dir = TempDir::new("aero-static3d-div");
    let case = example("patil_3d_flutter.toml");
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
    // Past the divergence (38 m/s) no equilibrium is stable: the run is incomplete.
    assert!(!o.status.success(), "{}", stderr(&o));
    let doc: Value = serde_json::from_str(&stdout(&o)).expect("one JSON document");
    assert_eq!(doc["status"], "stopped", "{doc}");
    let error = doc["error"].as_str().unwrap();
    assert!(error.contains("(U = 38 m/s)"), "{error}");
    let (_, u_div, _) = rod_at("steady", "divergence", 24.0);
    let dd = num(&doc["divergence"]["speed"]) - u_div;
    assert!(dd.abs() < 5.5e-3, "divergence error {dd}");
    let flutter = run_json("flutter", &case, &TempDir::new("aero-static3d-fl"));
    let (a, b) = (
        doc["equilibria"].as_array().unwrap(),
        flutter["equilibria"].as_array().unwrap(),
    );
    assert_eq!(a.len(), 18);
    assert_eq!(a, b, "the static run's equilibria are the flutter run's");
    assert_eq!(doc["divergence"], flutter["divergence"]);
}

/// `flexwing modes` on the same wing: the first two flap modes, the first lag and torsion modes
/// against Euler–Bernoulli (`(βL)² √(EI/(m L⁴))`) and St-Venant (`π/(2L) √(GJ/I)`) with the
/// energy share of each mode on its axis. Measured relative errors at n = 32 (bars):
/// −4.4e-4 (flap 1), −1.6e-3 (flap 2), −4.7e-4 (lag 1), −1.1e-4 (torsion 1); bounds 1e-3, and
/// 2.5e-3 for the second flap mode (O(n⁻²) with a coefficient growing with the mode's
/// wavenumber; the library test `chain3d_modes` shows the second-order convergence).
#[test]
fn patil_3d_modes_against_the_closed_forms() {
    let dir = TempDir::new("modes3d");
    let doc = run_json("modes", &example("patil_3d_flutter.toml"), &dir);
    let modes = doc["modes"].as_array().unwrap();
    let (l, m, ip): (f64, f64, f64) = (16.0, 0.75, 0.1);
    let eb = |beta: f64, ei: f64| beta * beta * (ei / (m * l.powi(4))).sqrt();
    let expected = [
        ("flap", eb(1.875_104_068_711_961, 2e4), 1e-3),
        ("flap", eb(4.694_091_132_974_175, 2e4), 2.5e-3),
        ("lag", eb(1.875_104_068_711_961, 4e6), 1e-3),
        (
            "twist",
            std::f64::consts::PI / (2.0 * l) * (1e4 / ip).sqrt(),
            1e-3,
        ),
    ];
    let mut seen = std::collections::HashMap::new();
    for (axis, omega, bound) in expected {
        let k = seen.entry(axis).or_insert(0usize);
        let mode = modes
            .iter()
            .filter(|md| num(&md["energy_fraction"][axis]) > 0.999)
            .nth(*k)
            .unwrap_or_else(|| panic!("no {axis} mode {k}"));
        *k += 1;
        let e = num(&mode["omega"]) / omega - 1.0;
        println!("{axis}: {} against {omega}: {e:+.2e}", mode["omega"]);
        assert!(e.abs() < bound, "{axis}: {e}");
        assert_eq!(mode["displacement"].as_array().unwrap().len(), 33);
    }
}

/// `flexwing study` on `examples/patil_3d_study.toml`: the flutter speed against the tip force
/// 0 … 33 N, every level against the rod. Measured flutter errors from −2.7e-3 m/s (0 N) to
/// −5.1e-2 m/s (33 N, where the curve turns and the flutter speed is most sensitive to the
/// deflection: −0.24 %), frequencies within 4.4e-3 rad/s, tips within 1.1e-3 m, divergence within
/// 3.8e-3 m/s. Bounds: 0.4 % on the speed, 6e-3 rad/s, 1.5e-3 m, 5e-3 m/s (the n = 32
/// discretization error, about 1.2–1.5 times the measured). The fall of the flutter speed is
/// the rod's: at 24 N, −27.4 % from the undeformed wing. The undeformed value printed beside it
/// (the planar model's at every level) is the rod's at 0 N within the same bound.
#[test]
fn patil_3d_study_against_the_continuum_rod() {
    let dir = TempDir::new("study3d");
    let doc = run_json("study", &example("patil_3d_study.toml"), &dir);
    assert_eq!(doc["status"], "complete", "{doc}");
    let points = doc["points"].as_array().unwrap();
    assert_eq!(points.len(), 12);
    let flutter = rod("peters6", "flutter");
    let divergence = rod("steady", "divergence");
    for p in points {
        let level = num(&p["level"]);
        let (_, y, u, w) = *flutter.iter().find(|r| r.0 == level).expect("a rod level");
        let (_, _, ud, _) = *divergence
            .iter()
            .find(|r| r.0 == level)
            .expect("a rod level");
        let f = &p["flutter"];
        let du = num(&f["speed"]) / u - 1.0;
        let dw = num(&f["frequency"]) - w;
        let dy = num(&p["tip"][1]) - y;
        let dd = num(&p["divergence"]["speed"]) - ud;
        println!("{level} N: {du:+.2e} (rel), {dw:+.2e} rad/s, tip {dy:+.2e} m, div {dd:+.2e}");
        assert!(du.abs() < 4e-3, "{level} N: flutter {f} against {u}");
        assert!(dw.abs() < 6e-3, "{level} N: frequency {f} against {w}");
        assert!(dy.abs() < 1.5e-3, "{level} N: tip {} against {y}", p["tip"]);
        assert!(dd.abs() < 5e-3, "{level} N: divergence against {ud}");
    }
    let (_, _, u0, _) = flutter[0];
    let undeformed = num(&doc["undeformed"]["speed"]);
    assert!((undeformed / u0 - 1.0).abs() < 4e-3);
    let csv = std::fs::read_to_string(dir.path().join("out/study.csv")).unwrap();
    assert_eq!(csv.lines().count(), 13, "a header and a row per level");
}

/// `flexwing static` and `modes` on the swept, coupled example: both complete, the 3-D shape has
/// out-of-plane parts (the chordwise force and the coupling bend the tip in z), and the modes
/// about the last equilibrium are reported (a regression check of the front end: the chain's
/// physics on this geometry is validated by the library tests `chain3d_*`).
#[test]
fn swept_example_runs_static_and_modes() {
    let dir = TempDir::new("swept3d");
    let doc = run_json("static", &example("swept_3d_wing.toml"), &dir);
    assert_eq!(doc["status"], "complete", "{doc}");
    let points = doc["points"].as_array().unwrap();
    assert_eq!(points.len(), 5);
    let first = &points[0]["shape"]["position"];
    let last = &points[4]["shape"]["position"];
    let tip = |p: &Value| p.as_array().unwrap().last().unwrap().clone();
    let moved: Vec<f64> = (0..3)
        .map(|i| num(&tip(last)[i]) - num(&tip(first)[i]))
        .collect();
    assert!(
        moved[1] > 0.0 && moved[2].abs() > 1e-3,
        "tip moved {moved:?}"
    );
    assert_eq!(doc["loaded_modes"].as_array().unwrap().len(), 4);
    let doc = run_json(
        "modes",
        &example("swept_3d_wing.toml"),
        &TempDir::new("swept3dm"),
    );
    assert_eq!(doc["modes"].as_array().unwrap().len(), 6);
}

/// A 3-D key on a planar case, a bad 3-D value, a table outside the span, an analysis the 3-D
/// chain cannot run from the case file yet: exit status 2 and one line naming the key.
#[test]
fn bad_3d_input_names_the_key() {
    let planar =
        "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50.0\nmass_per_length = 0.2\n";
    let chain = std::fs::read_to_string(example("swept_3d_wing.toml")).unwrap();
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "modes",
            planar.replace("EI = 50.0\n", "EI = 50.0\nEI_lag = 60.0\n"),
            "beam.section.EI_lag: is a key of the 3-D chain",
        ),
        (
            "modes",
            planar.replace("elements = 4\n", "elements = 4\nsweep = 0.1\n"),
            "beam.sweep: is a key of the 3-D chain",
        ),
        (
            "modes",
            chain.replace("EI_lag = 60.0", "EI_lag = -60.0"),
            "beam.section.EI_lag",
        ),
        (
            "modes",
            chain.replace(
                "dihedral = { x = [0.0, 1.0], value = [0.0, 0.15] }",
                "dihedral = { x = [0.0, 0.5], value = [0.0, 0.15] }",
            ),
            "beam.dihedral",
        ),
        (
            "dynamic",
            std::fs::read_to_string(example("patil_3d_flutter.toml")).unwrap(),
            "beam.model: the 3-D chain (\"chain3d\") has no aeroelastic dynamic run",
        ),
        (
            "study",
            planar.to_string(),
            "beam.model: the flutter study against a load level runs on the 3-D chain",
        ),
        (
            "static",
            chain.replace("[static]\n", "[static]\nreduced = [2]\n"),
            "static.reduced:",
        ),
        (
            "modes",
            chain.replace("[beam]\n", "[beam]\ncalibration = \"uniform\"\n"),
            "beam.calibration",
        ),
    ];
    for (command, text, expected) in cases {
        let dir = TempDir::new("bad3d");
        let path = dir.write("case.toml", &text);
        let out = dir.path().join("out");
        let o = flexwing_in(
            dir.path(),
            &[
                command,
                path.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        let err = stderr(&o);
        assert!(!err.contains("panicked"), "panic: {err}");
        assert_eq!(o.status.code(), Some(2), "{command}: {err}");
        assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
        assert!(
            err.contains(expected),
            "{command}: {err:?} lacks {expected:?}"
        );
    }
}
