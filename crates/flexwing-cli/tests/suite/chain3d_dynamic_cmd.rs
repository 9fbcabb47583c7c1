//! `flexwing dynamic` on the 3-D chain (`beam.model = "chain3d"`), against references that are
//! not the run itself: the planar chain's run of the same in-plane case (the planar limit, a
//! cross-model test), the linear modal solution (superposition of the chain's modes from
//! `flexwing modes` with their closed-form step response) at small amplitude, and the energy
//! balance of a large coupled twist–flap–lag release (`examples/swept_3d_wing.toml`). Every
//! integrator runs; bad `[dynamic]` values name the key; the VTK series carry the section
//! frames.

use std::path::Path;

use crate::common::{assert_success, example, flexwing_in, stdout, TempDir};
use serde_json::Value;

/// Run `flexwing COMMAND CASE --json` (and `extra` arguments) and parse the document.
fn run_json(command: &str, case: &Path, dir: &TempDir, extra: &[&str]) -> Value {
    let out = dir.path().join("out");
    let mut args = vec![
        command,
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

fn column(run: &Value, key: &str) -> Vec<f64> {
    run[key]
        .as_array()
        .unwrap_or_else(|| panic!("no column {key}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// A uniform cantilever (1 m, EI 50, m 0.2, bars, tip-load calibration) under a dead tip force
/// `F(t) = 10 sin(20 t)` N in the x-y plane; `chain3d` adds the 3-D chain's keys (stiff lag,
/// torsion, polar inertia, no offset): the planar limit of the same beam.
fn planar_limit_case(chain3d: bool) -> String {
    let three_d = if chain3d { "model = \"chain3d\"\n" } else { "" };
    let section_3d = if chain3d {
        "EI_lag = 400.0\nGJ = 30.0\npolar_inertia = 0.002\npolar_inertia_about = \"mass-centre\"\n"
    } else {
        ""
    };
    format!(
        r#"
[beam]
{three_d}length = 1.0
elements = 10
calibration = "tip-load"
element_inertia = "bar"

[beam.section]
EI = 50.0
mass_per_length = 0.2
{section_3d}
[[loads]]
name = "F"
type = "point-force"
span = 1.0
direction = "dead"
fy = 10.0
fx = 2.0
time = {{ type = "sine", omega = 20.0, phase = 0.0 }}

[dynamic]
end_time = 0.3
output_step = 0.01
integrator = "midpoint"
step = 5e-4
rtol = 1e-12
atol = 1e-12
"#
    )
}

/// The planar limit: the 3-D chain's dynamic run of an in-plane case is the planar chain's, run
/// through the case file, the dispatcher and the JSON of each. The same fixed midpoint steps on
/// equations that are the same to round-off (library test `chain3d_planar_limit`): measured
/// 2.5e-15 m over 31 output times at a tip amplitude of 0.10 m, no out-of-plane motion;
/// bound 1e-12 m (Newton's tolerance at rtol 1e-12 on states of order 1).
#[test]
fn planar_limit_dynamic_run_equals_the_planar_chains() {
    let dir = TempDir::new("dyn3d-planar");
    let planar = dir.write("planar.toml", &planar_limit_case(false));
    let chain = dir.write("chain.toml", &planar_limit_case(true));
    let p = run_json("dynamic", &planar, &TempDir::new("dyn3d-p"), &[]);
    let c = run_json("dynamic", &chain, &TempDir::new("dyn3d-c"), &[]);
    assert_eq!(c["model"], "chain3d");
    assert_eq!(c["status"], "complete", "{c}");
    let (pr, cr) = (&p["models"][0], &c["runs"][0]);
    let px = column(&pr["tip"], "x_m");
    let py = column(&pr["tip"], "y_m");
    let (cx, cy, cz) = (
        column(cr, "tip_x"),
        column(cr, "tip_y"),
        column(cr, "tip_z"),
    );
    assert_eq!(px.len(), 31);
    assert_eq!(cx.len(), px.len());
    let mut worst = 0.0_f64;
    let mut amplitude = 0.0_f64;
    for k in 0..px.len() {
        worst = worst
            .max((px[k] - cx[k]).abs())
            .max((py[k] - cy[k]).abs())
            .max(cz[k].abs());
        amplitude = amplitude.max(py[k].abs());
    }
    println!("planar limit: largest tip difference {worst:.2e} m, amplitude {amplitude:.3} m");
    assert!(amplitude > 0.05, "{amplitude}");
    assert!(worst < 1e-12, "{worst:e}");
    // The energies too (the same H and W): relative to the largest energy.
    let (pe, ce) = (column(&pr["energy"], "total_J"), column(cr, "total"));
    let (pw, cw) = (column(&pr["energy"], "work_J"), column(cr, "work"));
    let scale = pe.iter().fold(0.0_f64, |a, &b| a.max(b.abs()));
    for k in 0..pe.len() {
        assert!((pe[k] - ce[k]).abs() < 1e-10 * scale, "energy at {k}");
        assert!((pw[k] - cw[k]).abs() < 1e-10 * scale, "work at {k}");
    }
}

/// Small amplitude against the linear modal solution: a uniform cantilever (n = 8, flap, lag
/// and twist distinct, chordwise offset d0 coupling flap and twist) under a suddenly applied
/// dead tip force `(0, fy, fz)` of 1 mN, from rest. Linearized, the tip is
/// `Σ_j d_j (d_j · F) (1 − cos ω_j t) / ω_j²` over all 3n mass-normalized modes `(ω_j, d_j)`
/// (the tip displacements of `flexwing modes`), the closed-form step response of each mode.
/// The non-linear run differs by the geometric non-linearity, O(tip/L) relative: the tip moves
/// 3.3e-5 m here, measured relative difference 1.9e-5 of the largest tip excursion (of the
/// order of tip/L, as a geometric non-linearity is); bound 1e-4
/// (the integrator at rtol 1e-10 adds far less).
#[test]
fn small_amplitude_response_is_the_modal_superposition() {
    let n = 8;
    let case = format!(
        r#"
[beam]
model = "chain3d"
length = 1.0
elements = {n}

[beam.section]
EI = 20.0
EI_lag = 90.0
GJ = 6.0
mass_per_length = 0.4
polar_inertia = 0.003
polar_inertia_about = "mass-centre"
d0 = 0.03

[modes]
count = {dofs}

[[loads]]
name = "F"
type = "point-force"
span = 1.0
direction = "dead"
fy = 1e-3
fz = 6e-4

[dynamic]
end_time = 0.4
output_step = 0.01
rtol = 1e-10
atol = 1e-14
"#,
        dofs = 3 * n
    );
    let dir = TempDir::new("dyn3d-modal");
    let path = dir.write("case.toml", &case);
    let modes = run_json("modes", &path, &TempDir::new("dyn3d-m"), &[]);
    let doc = run_json("dynamic", &path, &TempDir::new("dyn3d-d"), &[]);
    assert_eq!(doc["status"], "complete", "{doc}");
    let run = &doc["runs"][0];
    let t = column(run, "t");
    let tip = [
        column(run, "tip_x"),
        column(run, "tip_y"),
        column(run, "tip_z"),
    ];
    let force = [0.0, 1e-3, 6e-4];
    let modes = modes["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 3 * n);
    let mut worst = 0.0_f64;
    let mut largest = 0.0_f64;
    for (k, &tk) in t.iter().enumerate() {
        let mut linear = [1.0, 0.0, 0.0];
        for m in modes {
            let omega = m["omega"].as_f64().unwrap();
            let d: Vec<f64> = m["displacement"][n]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            let modal_force: f64 = (0..3).map(|i| d[i] * force[i]).sum();
            let response = modal_force * (1.0 - (omega * tk).cos()) / (omega * omega);
            for i in 0..3 {
                linear[i] += d[i] * response;
            }
        }
        for i in 0..3 {
            worst = worst.max((tip[i][k] - linear[i]).abs());
        }
        largest = largest.max(((linear[1]).powi(2) + linear[2].powi(2)).sqrt());
    }
    let relative = worst / largest;
    println!("modal superposition: tip excursion {largest:.3e} m, difference {relative:.2e} of it");
    assert!(largest > 1e-5, "{largest:e}");
    assert!(relative < 1e-4, "{relative:e}");
}

/// The large coupled release of `examples/swept_3d_wing.toml` (swept, dihedral, pretwisted,
/// bend–twist coupled, offset mass centre; the tip force let go at t = 0): no load works, so
/// `H = H(0)`; the audit's balance error is the energy drift. Measured: the tip swings by 0.19
/// m (a fifth of the span) and the energy balance error stays at 2.0e-5 (rtol 1e-5), within the
/// audit's default limit 1e-2 (1000 rtol); bound 2e-4: ten times the measurement, so that a
/// wrong gyroscopic term (the simplified model here drifts by more, see below) cannot pass.
#[test]
fn swept_release_keeps_its_energy_and_writes_the_3d_files() {
    let dir = TempDir::new("dyn3d-swept");
    let doc = run_json(
        "dynamic",
        &example("swept_3d_wing.toml"),
        &dir,
        &["--vtk", "--plot"],
    );
    assert_eq!(doc["status"], "complete", "{doc}");
    let run = &doc["runs"][0];
    assert_eq!(run["label"], "full");
    assert_eq!(run["integrator"], "radau");
    let (y, z) = (column(run, "tip_y"), column(run, "tip_z"));
    let swing = y
        .iter()
        .zip(&z)
        .map(|(a, b)| ((a - y[0]).powi(2) + (b - z[0]).powi(2)).sqrt())
        .fold(0.0, f64::max);
    let work = column(run, "work");
    assert!(work.iter().all(|&w| w == 0.0), "no load acts: {work:?}");
    let total = column(run, "total");
    let drift = total
        .iter()
        .map(|h| (h - total[0]).abs() / total[0])
        .fold(0.0, f64::max);
    let audit = run["energy_audit"]["max_error"].as_f64().unwrap();
    println!("swept release: swing {swing:.3} m, drift {drift:.2e}, audit {audit:.2e}");
    assert!(swing > 0.1, "{swing}");
    assert!(drift < 2e-4 && audit < 2e-4, "{drift:e} {audit:e}");
    // The node file: 25 nodes at 51 output times, rotations empty at the root.
    let out = dir.path().join("out");
    let nodes = std::fs::read_to_string(out.join("dynamic_nodes.csv")).unwrap();
    let mut lines = nodes.lines();
    assert_eq!(
        lines.next().unwrap(),
        "model,t_s,node,span_m,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad"
    );
    assert_eq!(lines.clone().count(), 25 * 51);
    assert!(lines.next().unwrap().ends_with(",,,"));
    assert_eq!(doc["node_output"]["times"], 51);
    for f in ["dynamic_tip.csv", "dynamic_summary.csv", "dynamic_tip.svg"] {
        assert!(out.join(f).exists(), "{f}");
    }
    // The VTK series: one frame per node time, with the section axes as point vectors.
    let pvd = std::fs::read_to_string(out.join("vtk/dynamic_full.pvd")).unwrap();
    assert_eq!(pvd.matches("<DataSet").count(), 51);
    let vtu = std::fs::read_to_string(out.join("vtk/dynamic_full_0050.vtu")).unwrap();
    for name in ["displacement", "rotation", "\"t\"", "\"n\"", "\"c\""] {
        assert!(vtu.contains(name), "{name} missing");
    }
}

/// Every integrator of `[dynamic] integrator` on the 3-D chain: a short release from a static
/// 3-D deflection against Radau at rtol 1e-10 (a consistency test: the reference is the
/// library's own tight run). Measured differences at t = 0.05 s: at most 4.7e-7 m (BDF at
/// rtol 1e-6; fixed steps of 1e-4 s: 2.4e-7 m); bound 1e-4 m, a margin of 200.
#[test]
fn every_integrator_runs_on_the_3d_chain() {
    let case = |integrator: &str, extra: &str| {
        format!(
            r#"
[beam]
model = "chain3d"
length = 1.0
elements = 4

[beam.section]
EI = 10.0
EI_lag = 40.0
GJ = 5.0
mass_per_length = 0.5
polar_inertia = 0.004
polar_inertia_about = "mass-centre"
d0 = 0.02

[[loads]]
name = "pull"
type = "point-force"
span = 1.0
direction = "dead"
fy = 4.0
fz = -2.0
active = false

[dynamic]
end_time = 0.05
output_step = 0.01
integrator = "{integrator}"
{extra}

[dynamic.initial]
type = "static"
loads = ["pull"]
"#
        )
    };
    let tip_at_end = |integrator: &str, extra: &str| {
        let dir = TempDir::new("dyn3d-int");
        let path = dir.write("case.toml", &case(integrator, extra));
        let doc = run_json("dynamic", &path, &dir, &[]);
        assert_eq!(doc["status"], "complete", "{integrator}: {doc}");
        let run = &doc["runs"][0];
        assert_eq!(run["integrator"], integrator);
        ["tip_x", "tip_y", "tip_z"].map(|k| *column(run, k).last().unwrap())
    };
    let reference = tip_at_end("radau", "rtol = 1e-10\natol = 1e-12");
    for (integrator, extra) in [
        ("radau", "rtol = 1e-6\natol = 1e-8"),
        ("bdf", "rtol = 1e-6\natol = 1e-8"),
        ("dopri5", "rtol = 1e-6\natol = 1e-8"),
        ("midpoint", "rtol = 1e-6\natol = 1e-8"),
        ("midpoint", "step = 1e-4"),
        ("generalized-alpha", "rtol = 1e-6\natol = 1e-8"),
        ("generalized-alpha", "step = 1e-4\nspectral_radius = 0.9"),
    ] {
        let tip = tip_at_end(integrator, extra);
        let diff = (0..3)
            .map(|i| (tip[i] - reference[i]).abs())
            .fold(0.0, f64::max);
        println!("{integrator} ({extra:?}): {diff:.2e} m from the reference");
        assert!(diff < 1e-4, "{integrator}: {diff:e}");
    }
}

/// Bad `[dynamic]` input on a 3-D case: exit status 2 and one line naming the key.
#[test]
fn bad_3d_dynamic_input_names_the_key() {
    let chain = std::fs::read_to_string(example("swept_3d_wing.toml")).unwrap();
    let cases: Vec<(String, &str)> = vec![
        (chain.replace("rtol = 1e-5", "rtol = 2.0"), "dynamic.rtol"),
        (
            chain.replace("rtol = 1e-5", "rtol = 1e-5\nstep = 1e-3"),
            "dynamic.step: is the fixed step",
        ),
        (
            chain.replace(
                "type = \"static\"\nloads = [\"tip\"]",
                "type = \"given\"\nq = [0.1]",
            ),
            "dynamic.initial.q: needs 72 values",
        ),
        (
            chain.replace("rtol = 1e-5", "rtol = 1e-5\nreduced = [80]"),
            "dynamic.reduced[0]: must be between 1 and 72",
        ),
        (
            chain.replace(
                "active = false ",
                "time = { type = \"sine\", omega = 1e40, phase = 0.0 } ",
            ),
            "loads[0].time",
        ),
    ];
    for (text, expected) in cases {
        let dir = TempDir::new("bad3ddyn");
        let path = dir.write("case.toml", &text);
        let out = dir.path().join("out");
        let o = flexwing_in(
            dir.path(),
            &[
                "dynamic",
                path.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        let err = crate::common::stderr(&o);
        assert!(!err.contains("panicked"), "panic: {err}");
        assert_eq!(o.status.code(), Some(2), "{expected}: {err}");
        assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
        assert!(err.contains(expected), "{err:?} lacks {expected:?}");
    }
}

/// Ctrl-C during a long 3-D dynamic run (the swept release for 90 s at output steps of 1 ms:
/// minutes of computing): the run stops after its current step, writes the output times it
/// reached, `status.txt` says `interrupted`, exit status 1 — the planar run's behaviour
/// (`dynamic_cmd`), a regression test against docs/cli.md. A run that kept no sample past
/// t = 0 by the signal (a loaded machine) is repeated with a longer delay.
#[test]
fn ctrl_c_keeps_the_3d_output_reached() {
    let dir = TempDir::new("dyn3d-int");
    let text = std::fs::read_to_string(example("swept_3d_wing.toml"))
        .unwrap()
        .replace("end_time = 0.25 ", "end_time = 90.0 ")
        .replace("output_step = 0.005", "output_step = 0.001");
    let case = dir.write("case.toml", &text);
    let mut kept = 0;
    for delay_ms in [1500, 5000, 12000] {
        let out = dir.path().join("out");
        let args = [
            "dynamic",
            case.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        let after = std::time::Duration::from_millis(delay_ms);
        let (o, _) = crate::interrupt_cmd::interrupted_run(&args, "-INT", after);
        assert_eq!(o.status.code(), Some(1), "{}", crate::common::stderr(&o));
        let status = std::fs::read_to_string(out.join("status.txt")).unwrap();
        assert!(status.starts_with("interrupted: full: "), "{status}");
        let rows = std::fs::read_to_string(out.join("dynamic_tip.csv"))
            .unwrap()
            .lines()
            .count()
            - 1;
        assert!(rows < 90_001, "the run was not stopped");
        kept = rows;
        if kept > 1 {
            break;
        }
    }
    assert!(kept > 1, "no samples kept after 12 s");
}
