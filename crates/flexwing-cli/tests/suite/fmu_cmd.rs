//! `flexwing fmu`: the archive it writes (its entries, the model description's variables from
//! the options) and its errors (a missing library names the build command, bad options exit 2).
//! FMPy validates and runs the FMU in the Python suite (crates/flexwing-py/tests/test_fmu.py).

use std::io::Read as _;

use crate::common::{example, flexwing_in, stderr, stdout, TempDir};

#[test]
fn the_fmu_holds_the_description_the_case_and_the_library() {
    let dir = TempDir::new("fmu");
    // Any file stands for the library here: the archive carries its bytes as they are.
    let lib = dir.write("libflexwing_fmu.so", "a library");
    let case = example("patil_gust.toml");
    let args = [
        "fmu",
        case.to_str().unwrap(),
        "-o",
        "wing.fmu",
        "--library",
        lib.to_str().unwrap(),
        "--inputs",
        "gust,force[16]",
        "--outputs",
        "tip_y,lift",
        "--model",
        "1",
        "--hold",
        "linear",
    ];
    let o = flexwing_in(dir.path(), &args);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(stdout(&o).contains("the reduced-r6 model, binary for linux64"));
    let bytes = std::fs::read(dir.path().join("wing.fmu")).unwrap();
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    let mut read = |name: &str| {
        let mut s = String::new();
        zip.by_name(name).unwrap().read_to_string(&mut s).unwrap();
        s
    };
    assert_eq!(read("binaries/linux64/flexwing_fmu.so"), "a library");
    let md = read("modelDescription.xml");
    for expected in [
        "name=\"gust\" valueReference=\"0\" causality=\"input\"",
        "name=\"force[16]\" valueReference=\"1\" causality=\"input\"",
        "name=\"tip_y\" valueReference=\"2\" causality=\"output\"",
        "name=\"lift\" valueReference=\"3\" causality=\"output\"",
        "<Real start=\"0.0\" unit=\"N\"/>",
        "<String start=\"linear\"/>",
        "stopTime=\"2.0\" stepSize=\"0.01\"",
    ] {
        assert!(md.contains(expected), "{expected} not in {md}");
    }
    let settings = read("resources/flexwing-fmu.json");
    assert!(settings.contains("\"model\": 1") && settings.contains("\"hold\": \"linear\""));
    assert!(read("resources/case.toml").contains("[aero.flight.gust]"));
}

#[test]
fn a_missing_library_names_the_build_command_and_bad_options_exit_2() {
    let dir = TempDir::new("fmu-errors");
    let case = example("patil_gust.toml");
    let case = case.to_str().unwrap();
    let o = flexwing_in(dir.path(), &["fmu", case, "--library", "nowhere.so"]);
    assert_eq!(o.status.code(), Some(1));
    let e = stderr(&o);
    assert!(
        e.contains("nowhere.so") && e.contains("cargo build --release -p flexwing-fmu"),
        "{e}"
    );
    for (args, message) in [
        (vec!["--hold", "first"], "--hold: unknown value \"first\""),
        (
            vec!["--inputs", "wind"],
            "inputs[0]: unknown input \"wind\"",
        ),
        (
            vec!["--outputs", "root_shear"],
            "outputs[0]: root_shear is an output of the linear model only",
        ),
        (
            vec!["--model", "5"],
            "model: is 5 but the plan has 2 model(s)",
        ),
    ] {
        let lib = dir.write("lib.so", "x");
        let mut all = vec!["fmu", case, "--library", lib.to_str().unwrap()];
        all.extend(args);
        let o = flexwing_in(dir.path(), &all);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(message), "{all:?}: {}", stderr(&o));
    }
    let o = flexwing_in(
        dir.path(),
        &["fmu", &example("paper_sine.toml").to_string_lossy()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("aero: missing"), "{}", stderr(&o));
    assert!(!dir.path().join("paper_sine.fmu").exists());
}
