use super::*;
use flexwing::analysis::ModelKind;
use flexwing::solve::integrate::IntegratorSettings;

const BEAM: &str = "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\n\
     mass_per_length = 0.2\n\n[[loads]]\nname = \"F0\"\ntype = \"point-force\"\nnode = 4\n\
     direction = \"dead\"\nfy = 1\n";

fn plan_of(loads: &str, dynamic: &str) -> Result<DynamicPlan, String> {
    let case = Case::from_toml_str(&format!("{BEAM}{loads}\n[dynamic]\n{dynamic}"))
        .map_err(|e| e.to_string())?;
    case.dynamic_plan().map_err(|e| e.to_string())
}

fn plan(dynamic: &str) -> Result<DynamicPlan, String> {
    plan_of("", dynamic)
}

#[test]
fn defaults() {
    let p = plan("end_time = 1\noutput_step = 0.25\n").unwrap();
    assert_eq!(p.output_times, [0.0, 0.25, 0.5, 0.75, 1.0]);
    let labels: Vec<_> = p.models().unwrap().iter().map(ModelKind::label).collect();
    assert_eq!(labels, ["full"]);
    assert_eq!(p.integrator, Method::Radau);
    assert_eq!(p.gyroscopic, Gyroscopic::Exact);
    assert_eq!(p.settings.rtol, IntegratorSettings::default().rtol);
    assert_eq!(p.settings.atol, IntegratorSettings::default().atol);
    assert_eq!(p.settings.max_order, 2);
    assert_eq!(p.damping, Damping::None);
    assert_eq!(p.initial, Initial::Rest);
    assert_eq!(p.active(), [0]);
    assert_eq!(p.time, [Some(TimeFunction::Constant)]);
}

#[test]
fn output_step_ends_at_end_time() {
    let p = plan("end_time = 1\noutput_step = 0.3\n").unwrap();
    assert_eq!(p.output_times.len(), 5);
    assert_eq!(p.output_times[4], 1.0);
    let p = plan("end_time = 1\noutput_step = 0.005\n").unwrap();
    assert_eq!(p.output_times.len(), 201);
    assert_eq!(p.output_times[200], 1.0);
    assert!((p.output_times[77] - 0.385).abs() < 1e-15);
}

#[test]
fn models_and_integrators() {
    let p = plan(
        "end_time = 1\noutput_step = 0.5\nsimplified = true\nreduced = [2]\n\
         reduced_modes = [[1, 3]]\n",
    )
    .unwrap();
    let got: Vec<_> = p
        .models()
        .unwrap()
        .iter()
        .map(|m| (m.label(), p.integrator, p.gyroscopic_of(m)))
        .collect();
    let radau = Method::Radau;
    assert_eq!(
        got,
        [
            ("full".to_string(), radau, Gyroscopic::Exact),
            ("simplified".to_string(), radau, Gyroscopic::Neglected),
            ("reduced-r2".to_string(), radau, Gyroscopic::Exact),
            ("reduced-modes-1-3".to_string(), radau, Gyroscopic::Exact),
        ]
    );
    let p = plan(
        "end_time = 1\noutput_step = 0.5\nreduced = [2]\nintegrator = \"midpoint\"\n\
         step = 1e-3\ngyroscopic = \"finite-difference\"\n",
    )
    .unwrap();
    let reduced = &p.models().unwrap()[1];
    assert_eq!(p.integrator, Method::Midpoint);
    assert_eq!(
        p.gyroscopic_of(reduced),
        Gyroscopic::FiniteDifference { step: 1e-6 }
    );
    assert_eq!(p.settings.step, Some(1e-3));
}

#[test]
fn time_histories_and_inactive_loads() {
    let loads = "time = { type = \"sine\", omega = 20 }\n\n[[loads]]\nname = \"G\"\n\
                 type = \"gravity\"\nactive = false\n";
    let p = plan_of(
        loads,
        "end_time = 1\noutput_step = 0.5\n\n[dynamic.initial]\ntype = \"static\"\n\
         loads = [\"G\"]\n",
    )
    .unwrap();
    assert_eq!(p.active(), [0]);
    assert_eq!(
        p.time,
        [
            Some(TimeFunction::Sine {
                omega: 20.0,
                phase: 0.0
            }),
            None
        ]
    );
    assert_eq!(p.initial, Initial::Static { loads: vec![1] });
}

#[test]
fn errors_name_the_field() {
    let d = "end_time = 1\noutput_step = 0.5\n";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "",
            "end_time = -1\noutput_step = 0.5\n".into(),
            "dynamic.end_time: must be a finite positive number, got -1",
        ),
        (
            "",
            "end_time = 1\noutput_times = [0, 0.5, 0.7, 2.0]\n".into(),
            "dynamic.output_times[3]: 2 is after end_time 1",
        ),
        (
            "",
            "end_time = 1\noutput_times = [0, 0.5, 0.5]\n".into(),
            "dynamic.output_times[2]: 0.5 is not after",
        ),
        ("", "end_time = 1\n".into(), "dynamic.output_step: missing"),
        (
            "",
            "end_time = 1\noutput_step = 0.1\noutput_times = [0]\n".into(),
            "dynamic.output_step: give either",
        ),
        (
            "",
            "end_time = 1\noutput_step = 1e-9\n".into(),
            "dynamic.output_step: gives",
        ),
        (
            "time = { type = \"table\", t = [0, 0.5], value = [0, 1] }\n",
            d.into(),
            "loads[0].time.t: table covers [0, 0.5] s but the simulation runs over [0, 1] s",
        ),
        (
            "time = { type = \"sine\" }\n",
            d.into(),
            "loads[0].time.omega: missing",
        ),
        (
            "time = { type = \"step\", omega = 3 }\n",
            d.into(),
            "loads[0].time.omega: is not a key of a \"step\" time history",
        ),
        (
            "time = { type = \"ramp\", start = 0.5, end = 0.2 }\n",
            d.into(),
            "loads[0].time.end: must be after start",
        ),
        (
            "active = false\ntime = { type = \"step\", time = 0.1 }\n",
            d.into(),
            "loads[0].time: the load is inactive",
        ),
        ("", format!("{d}rtol = 1e-300\n"), "dynamic.rtol: must be"),
        ("", format!("{d}rtol = 0\n"), "dynamic.rtol: must be"),
        ("", format!("{d}atol = -1\n"), "dynamic.atol: must be"),
        (
            "",
            format!("{d}integrator = \"bdf\"\nmax_order = 6\n"),
            "dynamic.max_order: must be",
        ),
        (
            "",
            format!("{d}integrator = \"dopri5\"\nmax_order = 3\n"),
            "dynamic.max_order: is an option of the BDF",
        ),
        (
            "",
            format!("{d}step = 1e-3\n"),
            "dynamic.step: is the fixed step",
        ),
        (
            "",
            format!("{d}max_step = -1\n"),
            "dynamic.max_step: must be a finite positive number",
        ),
        (
            "",
            format!("{d}integrator = \"midpoint\"\nstep = 1e-3\nmax_step = 1e-2\n"),
            "dynamic.max_step: caps the steps",
        ),
        (
            "",
            format!("{d}integrator = \"midpoint\"\nstep = 0\n"),
            "dynamic.step: must be",
        ),
        (
            "",
            format!("{d}gyroscopic_step = 1e-5\n"),
            "dynamic.gyroscopic_step: is the step",
        ),
        (
            "",
            format!("{d}gyroscopic = \"finite-difference\"\ngyroscopic_step = -1\n"),
            "dynamic.gyroscopic_step: must be",
        ),
        (
            "",
            format!("{d}full = false\n"),
            "dynamic.full: nothing to simulate",
        ),
        (
            "",
            format!("{d}reduced = [2, 2]\n"),
            "dynamic.reduced[1]: the model reduced-r2 is already",
        ),
        (
            "",
            format!("{d}damping = {{ type = \"rayleigh\", ratios = [0.1] }}\n"),
            "dynamic.damping.ratios: is not a key of \"rayleigh\" damping",
        ),
        (
            "",
            format!("{d}damping = {{ type = \"rayleigh\", beta = -1 }}\n"),
            "dynamic.damping.beta: must be a finite non-negative number",
        ),
        (
            "",
            format!("{d}damping = {{ type = \"modal\", ratios = [0.1, 0.1, 0.1, 0.1, 0.1] }}\n"),
            "dynamic.damping.ratios: 5 ratios given but the model has 4 modes",
        ),
        (
            "",
            format!("{d}damping = {{ type = \"modal\", ratios = [0.1, nan] }}\n"),
            "dynamic.damping.ratios[1]: must be",
        ),
        (
            "",
            format!("{d}\n[dynamic.initial]\ntype = \"static\"\nloads = [\"F9\"]\n"),
            "dynamic.initial.loads[0]: no load named \"F9\" (the named loads are \"F0\")",
        ),
        (
            "",
            format!("{d}\n[dynamic.initial]\ntype = \"static\"\n"),
            "dynamic.initial.loads: missing",
        ),
        (
            "",
            format!("{d}\n[dynamic.initial]\ntype = \"rest\"\nq = [0, 0, 0, 0]\n"),
            "dynamic.initial.q: is not a key of a \"rest\" initial state",
        ),
        (
            "",
            format!("{d}\n[dynamic.initial]\ntype = \"given\"\nq = [0, 0]\n"),
            "dynamic.initial.q: needs 4 values",
        ),
        (
            "",
            format!("{d}\n[dynamic.initial]\ntype = \"given\"\nqdot = [0, 0, inf, 0]\n"),
            "dynamic.initial.qdot[2]: must be finite",
        ),
    ];
    for (loads, dynamic, expected) in cases {
        let msg = plan_of(loads, &dynamic).unwrap_err();
        assert!(msg.starts_with(expected), "{loads}{dynamic}: {msg}");
    }
    let case = Case::from_toml_str(BEAM).unwrap();
    let msg = case.dynamic_plan().unwrap_err().to_string();
    assert!(msg.starts_with("dynamic: missing"), "{msg}");
}
