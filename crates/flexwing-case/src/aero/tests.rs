use super::*;
use flexwing::analysis::aero::response::AeroStart;

/// Patil's wing on 4 elements with every `[aero]` key.
const CASE: &str = r#"
[beam]
length = 16
elements = 4

[beam.section]
EI = 2e4
mass_per_length = 0.75
GJ = 1e4
polar_inertia = 0.1
polar_inertia_about = "mass-centre"

[aero]
chord = 1.0
elastic_axis = { x = [0, 16], value = [0.5, 0.45] }
lift_slope = 6.0
zero_lift_angle = -0.01
cm0 = -0.02
cd0 = 0.01
density = 0.0889
aerodynamics = { model = "peters", states = 6 }

[aero.flight]
speed = 20
root_angle = 0.05
gravity = 9.8
speed_change = 5
speed_function = { type = "ramp", start = 0.1, end = 0.5 }
root_angle_change = 0.01
root_angle_function = { type = "step", time = 0.2 }

[aero.flight.gust]
shape = "one-minus-cosine"
amplitude = 2
start = 0.05
length = 10
spanwise = { x = [0, 16], value = [1, 0.5] }

[aero.sweep]
from = 4
to = 40
steps = 10

[flutter]
reduced = [4]
modes = 3
tolerance = 1e-7
pk = true

[dynamic]
end_time = 1
output_step = 0.1
reduced = [4]
"#;

fn case(text: &str) -> Case {
    Case::from_toml_str(text).unwrap_or_else(|e| panic!("{e}"))
}

/// The flight's time histories of [`CASE`]: a dynamic run's, refused by the runs about an
/// equilibrium.
const CHANGES: &str = "speed_change = 5
speed_function = { type = \"ramp\", start = 0.1, end = 0.5 }
root_angle_change = 0.01
root_angle_function = { type = \"step\", time = 0.2 }
";

/// `text` without [`CHANGES`]: a case for the runs about an equilibrium (static, flutter).
fn held(text: &str) -> Case {
    assert!(text.contains(CHANGES));
    case(&text.replacen(CHANGES, "", 1))
}

/// Every key ends in the library field of the same name.
#[test]
fn every_key_reaches_its_field() {
    let c = case(CASE);
    assert!(c.is_aeroelastic());
    let f = held(CASE).flutter_plan().unwrap();
    let s = &f.aero.section;
    assert_eq!(s.chord, Profile::Uniform(1.0));
    assert_eq!(
        s.elastic_axis,
        Profile::Table {
            x: vec![0.0, 16.0],
            value: vec![0.5, 0.45]
        }
    );
    assert_eq!(s.lift_slope, Profile::Uniform(6.0));
    assert_eq!(s.zero_lift_angle, Profile::Uniform(-0.01));
    assert_eq!(s.cm0, Profile::Uniform(-0.02));
    assert_eq!(s.cd0, Profile::Uniform(0.01));
    assert_eq!(f.aero.density, 0.0889);
    assert_eq!(f.aero.aerodynamics, Aerodynamics::Peters { states: 6 });
    assert_eq!(f.flight.root_angle, 0.05);
    assert_eq!(f.flight.gravity, Some(9.8));
    assert_eq!(f.speeds().len(), 10);
    assert_eq!((f.speeds()[0], f.speeds()[9]), (4.0, 40.0));
    assert_eq!(f.reduced, [4]);
    assert_eq!((f.modes, f.tolerance, f.pk), (Some(3), 1e-7, true));

    let d = c.aero_dynamic_plan().unwrap();
    let h = &d.flight;
    assert_eq!(h.initial.speed, 20.0);
    assert_eq!(
        h.speed_change,
        Some((
            5.0,
            TimeFunction::Ramp {
                start: 0.1,
                end: 0.5
            }
        ))
    );
    assert_eq!(
        h.root_angle_change,
        Some((0.01, TimeFunction::Step { time: 0.2 }))
    );
    let g = h.gust.as_ref().unwrap();
    assert_eq!(g.shape, GustShape::OneMinusCosine { length: 10.0 });
    assert_eq!((g.amplitude, g.start), (2.0, 0.05));
    assert_eq!(d.start, AeroStart::Equilibrium);
    assert_eq!(d.structure.reduced, [4]);

    // The static run sweeps the speeds of [aero.sweep]; without it, the flight's speed.
    let st = held(CASE).aero_static_plan().unwrap();
    assert_eq!(st.speeds().len(), 10);
    let single = held(&CASE.replace("[aero.sweep]\nfrom = 4\nto = 40\nsteps = 10\n", ""));
    assert_eq!(single.aero_static_plan().unwrap().speeds(), [20.0]);
}

#[test]
fn defaults() {
    let text = CASE
        .replace(
            "lift_slope = 6.0\nzero_lift_angle = -0.01\ncm0 = -0.02\ncd0 = 0.01\n",
            "",
        )
        .replace(
            "[flutter]\nreduced = [4]\nmodes = 3\ntolerance = 1e-7\npk = true\n",
            "",
        );
    let c = held(&text);
    let f = c.flutter_plan().unwrap();
    let s = &f.aero.section;
    assert_eq!(s.lift_slope, Profile::Uniform(2.0 * std::f64::consts::PI));
    assert_eq!(s.cm0, Profile::Uniform(0.0));
    assert_eq!((f.full, f.modes, f.pk), (true, None, false));
    assert!(f.reduced.is_empty());
    assert_eq!(f.tolerance, 1e-6);
}

#[test]
fn errors_name_the_case_files_keys() {
    type Edit = (&'static str, &'static str);
    let cases: [(Edit, &str, &str); 19] = [
        (("chord = 1.0", "chord = -1.0"), "flutter", "aero.chord: "),
        (
            ("density = 0.0889", "density = 0"),
            "flutter",
            "aero.density: ",
        ),
        (
            (
                "{ model = \"peters\", states = 6 }",
                "{ model = \"peters\" }",
            ),
            "flutter",
            "aero.aerodynamics.states: missing",
        ),
        (
            (
                "{ model = \"peters\", states = 6 }",
                "{ model = \"wagner\", states = 2 }",
            ),
            "flutter",
            "aero.aerodynamics.states: is the state count of Peters",
        ),
        (
            (
                "{ model = \"peters\", states = 6 }",
                "{ model = \"peters\", states = 40 }",
            ),
            "flutter",
            "aero.aerodynamics.states: Peters' inflow needs 1 to 15",
        ),
        (
            ("root_angle = 0.05", "root_angle = 3"),
            "flutter",
            "aero.flight.root_angle: ",
        ),
        (
            ("from = 4", "from = 0"),
            "flutter",
            "aero.sweep.speeds[0]: must be positive",
        ),
        (
            ("steps = 10", "steps = 1"),
            "flutter",
            "aero.sweep.steps: must be at least 2",
        ),
        (("to = 40\n", ""), "flutter", "aero.sweep.to: missing"),
        (
            ("modes = 3", "modes = 9"),
            "flutter",
            "flutter.modes: must be between 1 and 4",
        ),
        (
            ("tolerance = 1e-7", "tolerance = 0"),
            "flutter",
            "flutter.tolerance: ",
        ),
        (
            ("length = 10\n", ""),
            "dynamic",
            "aero.flight.gust.length: missing",
        ),
        (
            ("shape = \"one-minus-cosine\"", "shape = \"sharp-edged\""),
            "dynamic",
            "aero.flight.gust.length: is the length of a 1−cos gust",
        ),
        (
            ("speed_change = 5\n", ""),
            "dynamic",
            "aero.flight.speed_change: missing",
        ),
        (
            (
                "root_angle_function = { type = \"step\", time = 0.2 }\n",
                "",
            ),
            "dynamic",
            "aero.flight.root_angle_function: missing",
        ),
        (
            (
                "{ type = \"ramp\", start = 0.1, end = 0.5 }",
                "{ type = \"ramp\", start = 0.1 }",
            ),
            "dynamic",
            "aero.flight.speed_function.end: missing",
        ),
        (
            ("speed_change = 5", "speed_change = -30"),
            "dynamic",
            "aero.flight.speed_change: makes the speed negative",
        ),
        (
            ("speed = 20\n", ""),
            "dynamic",
            "aero.flight.speed: missing",
        ),
        (
            ("output_step = 0.1", "output_step = 0.1\nsimplified = true"),
            "dynamic",
            "dynamic.simplified: ",
        ),
    ];
    for ((from, to), analysis, expected) in cases {
        assert!(CASE.contains(from), "{from}");
        let text = CASE.replacen(from, to, 1);
        let e = match analysis {
            "flutter" => held(&text).flutter_plan().map(|_| ()),
            _ => case(&text).aero_dynamic_plan().map(|_| ()),
        }
        .unwrap_err();
        assert!(e.to_string().starts_with(expected), "{to}: {e}");
    }
}

#[test]
fn key_combinations_of_the_runs() {
    let gravity = "\n[[loads]]\ntype = \"gravity\"\n";
    let c = held(&format!("{CASE}{gravity}"));
    let e = c.flutter_plan().unwrap_err().to_string();
    assert!(
        e.starts_with("loads[0].type: with [aero], give gravity as aero.flight.gravity"),
        "{e}"
    );
    let c = case(&format!(
        "{CASE}\n[dynamic.initial]\ntype = \"given\"\nq = [0, 0, 0, 0, 0, 0, 0, 0]\n"
    ));
    let e = c.aero_dynamic_plan().unwrap_err().to_string();
    assert!(e.starts_with("dynamic.initial.type: with [aero]"), "{e}");
    let c = case(&format!("{CASE}\n[dynamic.initial]\ntype = \"rest\"\n"));
    assert_eq!(c.aero_dynamic_plan().unwrap().start, AeroStart::Rest);
    // The structural plans refuse an aeroelastic case rather than ignore [aero].
    let e = c.static_plan().unwrap_err().to_string();
    assert!(e.starts_with("aero: the case is aeroelastic"), "{e}");
    assert!(c.dynamic_plan().is_err());
    let no_sweep = held(&CASE.replace("[aero.sweep]\nfrom = 4\nto = 40\nsteps = 10\n", ""));
    let e = no_sweep.flutter_plan().unwrap_err().to_string();
    assert!(e.starts_with("aero.sweep: missing"), "{e}");
    let bare = held(
        &CASE
            .replace("[aero.sweep]\nfrom = 4\nto = 40\nsteps = 10\n", "")
            .replace("speed = 20\n", ""),
    );
    let e = bare.aero_static_plan().unwrap_err().to_string();
    assert!(e.starts_with("aero.flight.speed: missing"), "{e}");
    let e = held(&format!("{CASE}\n[static]\nmodes = 2\n"))
        .aero_static_plan()
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("static.modes: loaded modes are not available"),
        "{e}"
    );
    let e = held(&CASE.replace("steps = 10", "steps = 10\nspeeds = [1, 2]"))
        .aero_static_plan()
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("aero.sweep: give either"), "{e}");
    let e = Case::from_toml_str(
        "[beam]\nlength = 1\nelements = 2\n[beam.section]\nEI = 1\nmass_per_length = 1\n",
    )
    .unwrap()
    .flutter_plan()
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("aero: missing"), "{e}");
}

/// A dynamic run's time histories are refused by the runs about an equilibrium (static, flutter,
/// linearize and so turbulence), naming the key given, rather than ignored; the dynamic run takes
/// them (`every_key_reaches_its_field`).
#[test]
fn runs_about_an_equilibrium_refuse_the_time_histories() {
    let surface = "\n[[aero.surfaces]]\nname = \"aileron\"\nfrom = 12\nto = 16\nhinge = 0.8\n";
    let ramp = "{ type = \"ramp\", start = 0, end = 1 }";
    let base = CASE.replacen(CHANGES, "", 1);
    let cases = [
        (
            format!("{base}{surface}deflection_change = 0.01\ndeflection_function = {ramp}\n"),
            "aero.surfaces[0].deflection_change: ",
        ),
        (
            format!("{base}{surface}deflection_function = {ramp}\n"),
            "aero.surfaces[0].deflection_function: ",
        ),
        (CASE.to_string(), "aero.flight.speed_change: "),
        (
            base.replacen(
                "gravity = 9.8\n",
                &format!("gravity = 9.8\nroot_angle_function = {ramp}\n"),
                1,
            ),
            "aero.flight.root_angle_function: ",
        ),
    ];
    let linearize = "\n[linearize]\ninputs = [\"gust\"]\n";
    for (text, key) in &cases {
        let text = format!("{text}{linearize}");
        let c = case(&text);
        for (run, e) in [
            ("flexwing static", c.aero_static_plan().map(|_| ())),
            ("flexwing flutter", c.flutter_plan().map(|_| ())),
            ("the linear model", c.linearize_plan().map(|_| ())),
        ] {
            let e = e.unwrap_err().to_string();
            assert!(e.starts_with(key), "{key}: {e}");
            assert!(e.contains(run) && !e.contains('\n'), "{e}");
        }
        // The dynamic run takes a change with its function (alone, each is an error of its own).
        if !key.ends_with("function: ") {
            assert!(c.aero_dynamic_plan().is_ok(), "{key}");
        }
    }
    assert!(held(CASE).flutter_plan().is_ok());
}
