//! An FMU instance, built from the resources the writer puts in the archive: the FMI 2.0
//! co-simulation state machine (out-of-order calls refused with a logged message, the state
//! unchanged), value references, the `hold` parameter, and a regression test of its steps
//! against the library's stepper.

use std::cell::RefCell;
use std::io::Read as _;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use flexwing::analysis::aero::stepper::{AeroStepper, Hold};
use flexwing_case::Case;
use flexwing_fmu::description::fmu_bytes;
use flexwing_fmu::{path_of_uri, FmuOptions, Instance, State, Status};

/// The example gust case, 0.2 s, its reduced model only.
fn case() -> Case {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/patil_gust.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let text = text
        .replace("end_time = 2.0", "end_time = 0.2")
        .replace("full = true", "full = false");
    Case::from_toml_str(&text).unwrap()
}

/// The archive's resources unpacked into a fresh folder; its GUID.
fn resources(name: &str, options: &FmuOptions) -> (PathBuf, String) {
    let (bytes, summary) = fmu_bytes(&case(), options, b"not a library").unwrap();
    let dir = std::env::temp_dir().join(format!("flexwing-fmu-{name}-{}", std::process::id()));
    let res = dir.join("resources");
    std::fs::create_dir_all(&res).unwrap();
    let mut zip = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    for i in 0..zip.len() {
        let mut f = zip.by_index(i).unwrap();
        if let Some(file) = f.name().strip_prefix("resources/").map(str::to_string) {
            let mut data = Vec::new();
            f.read_to_end(&mut data).unwrap();
            std::fs::write(res.join(file), data).unwrap();
        }
    }
    (res, summary.guid)
}

type Log = Rc<RefCell<Vec<(Status, String)>>>;

fn instance(name: &str) -> (Instance, Log) {
    let (res, guid) = resources(name, &FmuOptions::default());
    let log: Log = Rc::default();
    let sink = Rc::clone(&log);
    let uri = format!("file://{}", res.display());
    let i = Instance::new(
        &guid,
        &uri,
        false,
        Box::new(move |s, _, m| sink.borrow_mut().push((s, m.to_string()))),
    )
    .unwrap();
    (i, log)
}

fn last(log: &Log) -> String {
    log.borrow()
        .last()
        .map(|(_, m)| m.clone())
        .unwrap_or_default()
}

#[test]
fn calls_out_of_order_are_refused_and_leave_the_state_as_it_was() {
    let (mut i, log) = instance("order");
    assert_eq!(i.state(), State::Instantiated);
    assert_eq!(i.do_step(0.0, 0.01), Status::Error);
    assert!(last(&log).starts_with("fmi2DoStep: called in state instantiated"));
    assert_eq!(i.exit_initialization(), Status::Error);
    assert_eq!(i.terminate(), Status::Error);
    let mut v = [0.0];
    assert_eq!(i.get_real(&[3], &mut v), Status::Error);
    assert_eq!(i.state(), State::Instantiated);
    assert_eq!(i.setup_experiment(Some(1e-6), 0.0, Some(1.0)), Status::Ok);
    assert_eq!(i.enter_initialization(), Status::Ok);
    assert_eq!(i.setup_experiment(None, 0.0, None), Status::Error);
    assert_eq!(i.enter_initialization(), Status::Error);
    assert_eq!(i.state(), State::Initialization);
    assert_eq!(i.exit_initialization(), Status::Ok);
    assert_eq!(i.state(), State::StepComplete);
    assert_eq!(i.do_step(0.0, 0.01), Status::Ok);
    assert_eq!(i.do_step(0.0, 0.01), Status::Error, "the time is 0.01 now");
    assert!(last(&log).contains("currentCommunicationPoint 0 is not the FMU's time 0.01"));
    assert_eq!(i.terminate(), Status::Ok);
    assert_eq!(i.do_step(0.01, 0.01), Status::Error);
    assert_eq!(i.reset(), Status::Ok);
    assert_eq!((i.state(), i.time()), (State::Instantiated, 0.0));
    assert!(log.borrow().iter().all(|(s, _)| *s == Status::Error));
}

#[test]
fn value_references_are_checked_and_named() {
    let (mut i, log) = instance("refs");
    i.enter_initialization();
    // Real 0-2 the inputs (root_angle, speed, gust), 3-8 the outputs; String 0 the hold.
    let mut v = [0.0; 3];
    assert_eq!(i.get_real(&[0, 1, 2], &mut v), Status::Ok);
    assert_eq!(v, [0.0349, 25.0, 0.0]);
    assert_eq!(i.get_real(&[9], &mut v[..1]), Status::Error);
    assert!(last(&log).contains("unknown value reference 9 (Real); the Real variables are 0 to 8"));
    assert_eq!(i.set_real(&[4], &[1.0]), Status::Error);
    assert!(last(&log).contains("value reference 4 is the output tip_y"));
    assert_eq!(i.set_real(&[1], &[-3.0]), Status::Error);
    assert!(last(&log).contains("speed: must be non-negative"));
    assert_eq!(
        i.no_variables("fmi2GetInteger", "Integer", &[0]),
        Status::Error
    );
    assert_eq!(i.no_variables("fmi2GetInteger", "Integer", &[]), Status::Ok);
    assert_eq!(i.get_string(&[0]).unwrap(), ["zero"]);
    assert_eq!(i.get_string(&[1]), Err(Status::Error));
    assert_eq!(i.set_string(&[0], &[Some("linear")]), Status::Ok);
    assert_eq!(i.hold(), Hold::Linear);
    assert_eq!(i.set_string(&[0], &[Some("first")]), Status::Error);
    assert_eq!(i.set_string(&[0], &[None]), Status::Error);
    i.exit_initialization();
    assert_eq!(
        i.set_string(&[0], &[Some("zero")]),
        Status::Error,
        "a fixed parameter"
    );
    assert_eq!(i.hold(), Hold::Linear);
}

#[test]
fn a_wrong_guid_or_resource_location_is_refused_with_a_message() {
    let (res, guid) = resources("guid", &FmuOptions::default());
    let uri = format!("file://{}", res.display());
    let msg: Log = Rc::default();
    let sink = Rc::clone(&msg);
    let log = move || {
        let sink = Rc::clone(&sink);
        Box::new(move |s: Status, _: &str, m: &str| sink.borrow_mut().push((s, m.to_string())))
    };
    let e = Instance::new("{0}", &uri, false, log()).err().unwrap();
    assert!(e.contains("fmuGUID \"{0}\" is not this FMU's"), "{e}");
    let e = Instance::new(&guid, "http://example.invalid/r", false, log())
        .err()
        .unwrap();
    assert!(e.contains("is not a file URI"), "{e}");
    let e = Instance::new(&guid, "file:///nonexistent/resources", false, log())
        .err()
        .unwrap();
    assert!(e.contains("cannot read"), "{e}");
    assert_eq!(msg.borrow().len(), 3, "each refusal is logged");
}

#[test]
fn file_uris_decode_to_local_paths() {
    assert_eq!(
        path_of_uri("file:///a/b%20c").unwrap(),
        PathBuf::from("/a/b c")
    );
    assert_eq!(path_of_uri("file:/a/b").unwrap(), PathBuf::from("/a/b"));
    assert_eq!(
        path_of_uri("file://localhost/a").unwrap(),
        PathBuf::from("/a")
    );
    assert_eq!(
        path_of_uri("file:///a/%zz").unwrap(),
        PathBuf::from("/a/%zz")
    );
    assert!(path_of_uri("file://host/a").is_err());
}

/// Regression (the instance against the stepper it wraps, not an independent reference): with
/// the zero hold, steps of the instance with an input set before each are the stepper's steps
/// with the same inputs, to the last bit.
#[test]
fn regression_steps_are_the_stepper_steps() {
    let (mut i, _) = instance("steps");
    i.setup_experiment(None, 0.0, None);
    i.enter_initialization();
    i.exit_initialization();
    let c = case();
    let plan = flexwing_fmu::plan_of(&c).unwrap();
    let options = flexwing_fmu::options_of(&plan, None, None, 0, Hold::Zero).unwrap();
    let mut s = AeroStepper::new(&plan, &options).unwrap();
    let mut out = [0.0; 6];
    for k in 0..5 {
        let gust = 0.2 * f64::from(k);
        assert_eq!(i.set_real(&[2], &[gust]), Status::Ok);
        s.set_input(2, gust).unwrap();
        assert_eq!(i.do_step(i.time(), 0.01), Status::Ok);
        s.step(0.01, &mut |_| {}).unwrap();
        assert_eq!(i.get_real(&[3, 4, 5, 6, 7, 8], &mut out), Status::Ok);
        assert_eq!(out.to_vec(), s.output_values());
    }
    assert!((i.time() - 0.05).abs() < 1e-15);
}

#[test]
fn an_instance_starts_with_the_hold_the_fmu_was_written_with() {
    let options = FmuOptions {
        hold: Hold::Linear,
        ..FmuOptions::default()
    };
    let (res, guid) = resources("linear", &options);
    let uri = format!("file://{}", res.display());
    let mut i = Instance::new(&guid, &uri, false, Box::new(|_, _, _| {})).unwrap();
    assert_eq!(i.hold(), Hold::Linear);
    assert_eq!(i.get_string(&[0]).unwrap(), ["linear"]);
    assert_eq!(i.stepper().hold(), Hold::Linear);
    assert_eq!(i.set_string(&[0], &[Some("zero")]), Status::Ok);
    assert_eq!(i.reset(), Status::Ok);
    assert_eq!(i.hold(), Hold::Linear, "reset: the start value again");
}
