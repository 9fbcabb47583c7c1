//! The example case files run, and `flexwing modes` writes what docs/cli.md promises.
//! These are regression/contract tests of the command-line tool; the numerical validation of
//! the frequencies lives in the library's tests.

use std::fs;
use std::path::Path;

use crate::common::{assert_success, example, flexwing_in, stdout, TempDir};

const EXAMPLES: [(&str, usize, usize); 3] = [
    // (file, modes reported by the case, nodes = elements + 1)
    ("table1.toml", 9, 17),
    ("table4.toml", 6, 21),
    ("tapered_wing.toml", 10, 41),
];

fn read_csv(path: &Path) -> (String, Vec<Vec<String>>) {
    let text = fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().expect("header").to_string();
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header, rows)
}

#[test]
fn every_example_writes_both_csv_files() {
    for (file, count, nodes) in EXAMPLES {
        let dir = TempDir::new("example");
        let out = dir.path().join("out");
        let o = flexwing_in(
            dir.path(),
            &[
                "modes",
                example(file).to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
        );
        assert_success(&o);
        let text = stdout(&o);
        assert!(text.contains("model: "), "{file}: {text}");
        assert!(text.contains("ω (rad/s)"), "{file}: {text}");

        let (header, rows) = read_csv(&out.join("frequencies.csv"));
        assert_eq!(
            header,
            "mode,omega_rad_s,frequency_hz,bending_energy_fraction"
        );
        assert_eq!(rows.len(), count, "{file}");
        let mut previous = 0.0;
        for (k, row) in rows.iter().enumerate() {
            assert_eq!(row[0], (k + 1).to_string());
            let omega: f64 = row[1].parse().unwrap();
            let hz: f64 = row[2].parse().unwrap();
            let share: f64 = row[3].parse().unwrap();
            assert!(omega > previous, "{file}: frequencies not ascending");
            assert!((omega / (2.0 * std::f64::consts::PI) - hz).abs() <= 1e-12 * omega);
            assert!((0.0..=1.0).contains(&share));
            previous = omega;
        }

        let (header, rows) = read_csv(&out.join("mode_shapes.csv"));
        assert_eq!(header, "mode,node,x_m,dx_m,dy_m,twist_rad");
        assert_eq!(rows.len(), count * nodes, "{file}");
        // No temporary files are left behind.
        let mut names: Vec<_> = fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["frequencies.csv", "mode_shapes.csv"], "{file}");
    }
}

#[test]
fn table1_reproduces_the_first_frequencies_of_table2() {
    // Paper's Table 2 (semi-analytical, continuous beam): 2.21, 9.55, 13.80 rad/s. The 16-element
    // model is within 1 % of them; tighter checks belong to the library's validation tests.
    let dir = TempDir::new("table1");
    let o = flexwing_in(
        dir.path(),
        &["modes", example("table1.toml").to_str().unwrap(), "--json"],
    );
    assert_success(&o);
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let omega: Vec<f64> = doc["modes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["omega_rad_s"].as_f64().unwrap())
        .collect();
    for (w, reference) in omega.iter().zip([2.21, 9.55, 13.80]) {
        assert!((w / reference - 1.0).abs() < 0.01, "{w} vs {reference}");
    }
}

#[test]
fn default_output_directory_is_results_slash_stem() {
    let dir = TempDir::new("default-out");
    let case = fs::read_to_string(example("table4.toml")).unwrap();
    dir.write("my_case.toml", &case);
    let o = flexwing_in(dir.path(), &["modes", "my_case.toml"]);
    assert_success(&o);
    let out = dir.path().join("results").join("my_case");
    assert!(out.join("frequencies.csv").is_file());
    assert!(out.join("mode_shapes.csv").is_file());
}

#[test]
fn json_output_has_the_documented_fields() {
    let dir = TempDir::new("json");
    let out = dir.path().join("out");
    let o = flexwing_in(
        dir.path(),
        &[
            "modes",
            example("table1.toml").to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--count",
            "4",
            "--json",
        ],
    );
    assert_success(&o);
    // Nothing but the JSON document on stdout.
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout)
        .unwrap_or_else(|e| panic!("stdout is not one JSON document: {e}\n{}", stdout(&o)));
    assert!(doc["case"].as_str().unwrap().ends_with("table1.toml"));
    assert!(doc["title"].as_str().unwrap().contains("Table 1"));
    assert_eq!(doc["n_elements"], 16);
    assert_eq!(doc["n_dofs"], 32);
    assert_eq!(doc["has_torsion"], true);
    assert_eq!(doc["calibration"], "tip-load");
    let modes = doc["modes"].as_array().unwrap();
    assert_eq!(modes.len(), 4, "--count overrides [modes] count");
    for (k, m) in modes.iter().enumerate() {
        assert_eq!(m["mode"], k + 1);
        for key in ["omega_rad_s", "frequency_hz", "bending_energy_fraction"] {
            assert!(m[key].is_f64(), "mode {}: {key}", k + 1);
        }
        for key in ["x_m", "dx_m", "dy_m", "twist_rad"] {
            assert_eq!(m["shape"][key].as_array().unwrap().len(), 17, "{key}");
        }
    }
    let files: Vec<&str> = doc["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(files.len(), 2);
    for f in files {
        assert!(Path::new(f).is_file(), "{f} listed but not written");
    }
}

#[test]
fn json_for_a_bending_only_beam() {
    let dir = TempDir::new("json-bending");
    let o = flexwing_in(
        dir.path(),
        &["modes", example("table4.toml").to_str().unwrap(), "--json"],
    );
    assert_success(&o);
    let doc: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(doc["has_torsion"], false);
    assert_eq!(doc["n_dofs"], 20);
    assert_eq!(doc["modes"].as_array().unwrap().len(), 6);
    assert_eq!(doc["modes"][0]["bending_energy_fraction"], 1.0);
}

#[test]
fn plot_writes_svg_and_png() {
    for file in ["table1.toml", "table4.toml"] {
        let dir = TempDir::new("plot");
        let out = dir.path().join("out");
        let o = flexwing_in(
            dir.path(),
            &[
                "modes",
                example(file).to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
                "--plot",
            ],
        );
        assert_success(&o);
        let svg = fs::read_to_string(out.join("mode_shapes.svg")).unwrap();
        assert!(svg.starts_with("<svg"), "{file}");
        assert!(svg.contains("mode 1:"), "{file}: legend missing");
        assert!(svg.contains("x (m)"), "{file}: axis label missing");
        let png = fs::read(out.join("mode_shapes.png")).unwrap();
        assert!(
            png.starts_with(b"\x89PNG\r\n\x1a\n"),
            "{file}: not a PNG file"
        );
        assert!(png.len() > 10_000, "{file}: PNG suspiciously small");
    }
}
