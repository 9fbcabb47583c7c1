//! A fuzz test of runs (issue 9): the example case files, mutated with a fixed seed as in the
//! case-file fuzz test (`crates/flexwing-case/tests/suite/mutate/mod.rs`: a value replaced by an
//! extreme, tiny, non-finite, wrong-typed or huge one, or by the edges of the accepted range of
//! magnitudes; a line deleted or doubled; one or two mutations per case), and those the case
//! layer accepts are **run** by the binary: `modes` always, `static` when the case has loads or
//! aerodynamics, `dynamic` with a `[dynamic]` table, `flutter` with a speed sweep.
//!
//! Sizes are capped so that the whole test stays within its budget (measured: 25 s in release
//! on 2 shared cores, 1120 cases, about 700 runs): at most 8 elements (load nodes moved in
//! proportion), 3 static sweep points, 3 listed speeds up to 300 or 5 speed steps of at most
//! 10, a dynamic run of at most 0.05 time units with 4 output intervals and 4000 steps. Each run
//! has a 60 s wall-clock bound (a hang fails the test); runs over 2 s are printed.
//!
//! Asserted of every run: no panic (exit status 0, 1 or 2, never 101 or a signal); stdout one
//! JSON document with a `status`, its `error` (if any) one line; no `NaN` or `inf` token in any
//! CSV file written, complete or not; and a run that exits 0 has `complete` in `status.txt` and
//! no null in its JSON document except where null means "none" ([`NULL_KEYS`]; the CLI writes
//! a non-finite number as null).

#[path = "../../../flexwing-case/tests/suite/mutate/mod.rs"]
mod mutate;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use crate::common::{example, TempDir};
use flexwing_case::Case;
use mutate::{mutate, Class, Lcg};

/// Mutated cases per example file.
const PER_FILE: usize = 80;
/// Largest speed of a flutter sweep run (m/s in the examples).
const MAX_SPEED: f64 = 300.0;
/// Largest number of elements run.
const MAX_ELEMENTS: usize = 8;

/// Cap the sizes of an accepted case so that its runs fit the test's budget.
fn capped(mut case: Case) -> Case {
    if let Some(n) = case.beam.elements {
        if n > MAX_ELEMENTS {
            case.beam.elements = Some(MAX_ELEMENTS);
            for load in &mut case.loads {
                if let Some(node) = load.node {
                    load.node = Some(node.saturating_mul(MAX_ELEMENTS).div_ceil(n));
                }
            }
        }
    }
    let stations = case.beam.stations.as_ref().map_or(0, |x| x.len());
    if stations > MAX_ELEMENTS + 1 {
        // Node indices refer to the stations given; a load moves to the node of the same
        // fraction of the count in the new, coarser, uniform cut.
        let n = stations - 1;
        case.beam.stations = None;
        case.beam.elements = Some(MAX_ELEMENTS);
        for load in &mut case.loads {
            if let Some(node) = load.node {
                load.node = Some(node.saturating_mul(MAX_ELEMENTS).div_ceil(n));
            }
        }
    }
    if let Some(sweep) = &mut case.statics.sweep {
        if let Some(s) = &mut sweep.scales {
            s.truncate(3);
        }
        if let Some(steps) = &mut sweep.steps {
            *steps = (*steps).min(3);
        }
    }
    if let Some(aero) = &mut case.aero {
        if let Some(sweep) = &mut aero.sweep {
            // Speeds up to MAX_SPEED, in steps of at most 10: the branch tracking refines a
            // coarse speed step for a long time (measured on Patil's wing, n = 8: 2 → 40 m/s in
            // 3 speeds 11.5 s, 2 → 300 m/s 60 s, 2 → 1000 m/s 116 s), too long for this test.
            if let Some(s) = &mut sweep.speeds {
                s.truncate(3);
                s.retain(|&u| !(u > MAX_SPEED));
            }
            if let (Some(from), Some(to), Some(steps)) =
                (sweep.from, &mut sweep.to, &mut sweep.steps)
            {
                if *to > from + 50.0 {
                    *to = from + 50.0;
                }
                *steps = 5;
            }
        }
    }
    if let Some(d) = &mut case.dynamic {
        if d.end_time.is_finite() && d.end_time > 0.05 {
            d.end_time = 0.05;
        }
        d.output_times = None;
        d.output_step = Some(d.end_time / 4.0);
        d.max_steps = Some(d.max_steps.unwrap_or(4000).min(4000));
    }
    case
}

/// Whether `text` holds a non-finite number as a token (`NaN`, `inf`, `-inf`, `infinity`).
fn non_finite_token(text: &str) -> Option<String> {
    text.split(|c: char| {
        c == ',' || c == '"' || c.is_whitespace() || c == ':' || c == '[' || c == ']'
    })
    .map(|t| t.trim_start_matches(['+', '-']).to_ascii_lowercase())
    .find(|t| t == "nan" || t == "inf" || t == "infinity")
}

/// JSON keys whose null means "none" rather than a masked non-finite number (docs/cli.md): no
/// title, no error, no difference for the reference model, no loaded modes or sweep asked for,
/// no energy-audit event, no divergence or flutter found in the sweep. Every other null of a
/// complete run fails the test.
const NULL_KEYS: &[&str] = &[
    ".title",
    ".error",
    ".tip_difference_m",
    ".max_tip_difference_m",
    ".max_tip_difference",
    ".max_relative_error",
    ".modes",
    ".loaded_modes",
    ".sweep",
    ".runaway_time",
    ".exceeded_time",
    ".flutter",
    ".divergence",
    ".divergence_speed_m_s",
    ".divergence_pressure_pa",
    ".divergence_within_sweep",
    ".pk",
    ".limit",
    ".energy_audit",
    // The 3-D chain's documents (the library's serialized outcome): a complete status has no
    // stop or message, a level no tip at a flutter point it lacks, a follower load no
    // stability verdict, an undeformed wing without flutter no point.
    ".stop",
    ".message",
    ".tip_at_flutter",
    ".undeformed",
    ".stable",
    ".divergence_pressure",
];

/// Paths (`a.b[2].c`) of the null values of `v`.
fn null_paths(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Null => out.push(at.to_string()),
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                null_paths(x, &format!("{at}[{i}]"), out);
            }
        }
        serde_json::Value::Object(m) => {
            for (k, x) in m {
                null_paths(x, &format!("{at}.{k}"), out);
            }
        }
        _ => {}
    }
}

/// The outcome of one command on one case.
#[derive(Debug, Default)]
struct Tally {
    complete: usize,
    failed: usize,
    refused: usize,
    seconds: f64,
}

/// Run `command` on `case_path`; check everything the module header promises. Returns the exit
/// status.
fn run_checked(command: &str, case_path: &Path, dir: &Path, label: &str) -> i32 {
    let out = dir.join(format!("out-{command}"));
    let mut child = Command::new(env!("CARGO_BIN_EXE_flexwing"))
        .args([
            command,
            case_path.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--json",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the flexwing binary runs");
    // A 60 s bound per run: the capped runs take milliseconds; a hang takes forever.
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            break;
        }
        if start.elapsed() > Duration::from_secs(60) {
            let _ = child.kill();
            panic!("{label}: `flexwing {command}` ran over 60 s (a hang)");
        }
        std::thread::sleep(Duration::from_millis(2));
    }
    let o = child.wait_with_output().unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    let code = o
        .status
        .code()
        .unwrap_or_else(|| panic!("{label}: {command} killed by a signal: {stderr}"));
    assert!(
        [0, 1, 2].contains(&code),
        "{label}: {command} exit status {code}: {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{label}: {command}: {stderr}");
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap_or_else(|e| {
        panic!("{label}: {command}: stdout is not one JSON document ({e}): {stdout}")
    });
    assert!(json.get("status").is_some(), "{label}: {command}: {stdout}");
    if let Some(e) = json.get("error").and_then(|e| e.as_str()) {
        assert_eq!(e.lines().count(), 1, "{label}: {command}: {e}");
    }
    if code == 0 {
        // The CLI writes a non-finite number as JSON null (and an empty CSV cell): in a
        // complete run there is none, except where null means "none" (NULL_KEYS).
        let mut nulls = Vec::new();
        null_paths(&json, "", &mut nulls);
        nulls.retain(|p| !NULL_KEYS.iter().any(|k| p.ends_with(k)));
        assert!(
            nulls.is_empty(),
            "{label}: {command}: complete, with null at {nulls:?}: {stdout}"
        );
    }
    if let Ok(entries) = std::fs::read_dir(&out) {
        for entry in entries {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "csv") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            if let Some(t) = non_finite_token(&text) {
                panic!("{label}: {command}: {t} in {}:\n{text}", path.display());
            }
        }
        let status = out.join("status.txt");
        if code == 0 && status.exists() {
            let s = std::fs::read_to_string(&status).unwrap();
            assert!(
                s.starts_with("complete"),
                "{label}: {command}: exit 0 with {s}"
            );
        }
    }
    code
}

#[test]
fn mutated_example_cases_run_without_panic_hang_or_non_finite_output() {
    let dir = example("");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "examples: {files:?}");
    let started = Instant::now();
    let mut rng = Lcg(20261201);
    let scratch = TempDir::new("fuzz-runs");
    // Counts per mutation class: cases made, cases accepted by the case layer.
    let mut made: BTreeMap<Class, (usize, usize)> = BTreeMap::new();
    let mut tallies: BTreeMap<&str, Tally> = BTreeMap::new();
    for path in &files {
        let text = std::fs::read_to_string(path).unwrap();
        let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
        for k in 0..PER_FILE {
            let (mut mutated, class) = mutate(&text, &mut rng);
            if rng.next(3) == 0 {
                mutated = mutate(&mutated, &mut rng).0;
            }
            let entry = made.entry(class).or_default();
            entry.0 += 1;
            let Ok(case) = Case::from_toml_str(&mutated) else {
                continue;
            };
            entry.1 += 1;
            let case = capped(case);
            let Ok(toml) = case.to_toml_string() else {
                continue;
            };
            let case_dir = scratch.path().join(format!("{stem}-{k}"));
            std::fs::create_dir_all(&case_dir).unwrap();
            let case_path = case_dir.join("case.toml");
            std::fs::write(&case_path, &toml).unwrap();
            let label = format!("{stem} mutation {k} ({class:?}), case:\n{toml}\n");
            let mut commands = vec!["modes"];
            if !case.loads.is_empty() || case.aero.is_some() {
                commands.push("static");
            }
            if case.dynamic.is_some() {
                commands.push("dynamic");
            }
            // With end_time capped the family is mostly refused (its longest gust has not
            // passed): the error path, one line naming dynamic.end_time.
            if case.gust_family.is_some() {
                commands.push("gust");
            }
            if case.aero.as_ref().is_some_and(|a| a.sweep.is_some()) {
                commands.push("flutter");
            }
            for command in commands {
                let start = Instant::now();
                let code = run_checked(command, &case_path, &case_dir, &label);
                let t = tallies.entry(command).or_default();
                let seconds = start.elapsed().as_secs_f64();
                t.seconds += seconds;
                if seconds > 2.0 {
                    eprintln!("slow: {seconds:.1} s, {command}, exit {code}: {label}");
                }
                match code {
                    0 => t.complete += 1,
                    1 => t.failed += 1,
                    _ => t.refused += 1,
                }
            }
            let _ = std::fs::remove_dir_all(&case_dir);
        }
    }
    eprintln!(
        "{} files × {PER_FILE} mutations in {:.1} s",
        files.len(),
        started.elapsed().as_secs_f64()
    );
    for (class, (n, accepted)) in &made {
        eprintln!("  {class:?}: {n} cases, {accepted} accepted by the case layer");
    }
    for (command, t) in &tallies {
        eprintln!(
            "  {command}: {} complete (exit 0), {} failed with a solver message (exit 1), {} \
             refused (exit 2), {:.1} s",
            t.complete, t.failed, t.refused, t.seconds
        );
    }
    // The test must exercise runs, not only refusals: every command ran to completion at least
    // once.
    for command in ["modes", "static", "dynamic", "flutter"] {
        let t = tallies.get(command).map_or(0, |t| t.complete);
        assert!(t > 0, "no complete `{command}` run among the mutations");
    }
}
