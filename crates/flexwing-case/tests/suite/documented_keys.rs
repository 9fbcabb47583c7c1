//! docs/case-file.md lists exactly the keys the schema accepts, table by table, with the defaults
//! the code uses. The schema's keys come from the schema itself (the error "unknown key …; the
//! keys here are …" for a bogus key in each table); the defaults from the plans a case without
//! the key produces.

use std::collections::{BTreeMap, BTreeSet};

use flexwing::analysis::dynamics::Initial;
use flexwing::beam::Calibration;
use flexwing::model::{Force, Load};
use flexwing::solve::{Damping, Gyroscopic, TimeFunction};
use flexwing_case::Case;

/// The documentation's key tables: for each table of the case file, its keys and the text of
/// their default column.
fn documented() -> BTreeMap<String, BTreeMap<String, String>> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/case-file.md");
    let text = std::fs::read_to_string(path).expect("docs/case-file.md");
    // The key tables of each section, in the order they appear.
    let sections: [(&str, &[&str]); 22] = [
        ("### Top level", &[""]),
        ("### `[beam]`", &["beam"]),
        ("### `[beam.section]`", &["beam.section"]),
        ("### `[beam.section.coupling]`", &["beam.section.coupling"]),
        ("### `[modes]`", &["modes"]),
        ("### `[[loads]]`", &["loads"]),
        ("### `[static]`", &["static"]),
        ("### `[static.sweep]`", &["static.sweep"]),
        ("### Time histories", &["loads.time"]),
        ("### `[dynamic]`", &["dynamic", "dynamic.damping"]),
        ("### `[dynamic.initial]`", &["dynamic.initial"]),
        ("### `[aero]`", &["aero", "aero.aerodynamics"]),
        ("### `[aero.flight]`", &["aero.flight"]),
        ("### `[aero.flight.gust]`", &["aero.flight.gust"]),
        ("### `[aero.sweep]`", &["aero.sweep"]),
        ("### `[[aero.surfaces]]`", &["aero.surfaces"]),
        ("### `[flutter]`", &["flutter"]),
        ("### `[flutter.study]`", &["flutter.study"]),
        ("### `[linearize]`", &["linearize"]),
        ("### `[gust_family]`", &["gust_family"]),
        ("### `[turbulence]`", &["turbulence"]),
        ("### `[output]`", &["output"]),
    ];
    let mut tables = BTreeMap::new();
    let mut pending: Vec<&str> = Vec::new();
    let mut lines = text.lines().peekable();
    while let Some(line) = lines.next() {
        if line.starts_with("## ") || line.starts_with("### ") {
            pending = sections
                .iter()
                .find(|(h, _)| line.starts_with(h))
                .map_or_else(Vec::new, |(_, t)| t.to_vec());
        }
        if !line.starts_with("| key |") {
            continue;
        }
        let table = if pending.is_empty() {
            panic!("a key table outside a known section: {line}")
        } else {
            pending.remove(0)
        };
        let header: Vec<&str> = line.split('|').map(str::trim).collect();
        let default = header
            .iter()
            .position(|h| *h == "default")
            .expect("default column");
        lines.next(); // |---|
        let mut keys = BTreeMap::new();
        while let Some(row) = lines.next_if(|l| l.starts_with('|')) {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            for key in cells[1].split(", ") {
                let key = key.trim_matches('`').to_string();
                keys.insert(key, cells[default].to_string());
            }
        }
        assert!(
            tables.insert(table.to_string(), keys).is_none(),
            "two key tables for {table}"
        );
    }
    tables
}

/// A case with every table, to which a bogus key is added in one table.
const BASE: &str = r#"title = "t"

[beam]
length = 1.0
elements = 4

[beam.section]
EI = 50
mass_per_length = 0.2

[modes]

[[loads]]
name = "G"
type = "gravity"
time = { type = "constant" }

[static]

[static.sweep]
load = "G"
scales = [1.0]

[dynamic]
end_time = 1.0
output_step = 0.5
damping = { type = "none" }

[dynamic.initial]
type = "rest"

[output]
"#;

/// BASE with every aeroelastic table (its structural plans are then refused: it is aeroelastic).
fn base_aero() -> String {
    format!(
        "{BASE}{}",
        r#"
[aero]
chord = 1.0
elastic_axis = 0.5
density = 1.2
aerodynamics = { model = "steady" }

[aero.flight]
speed = 10.0

[aero.flight.gust]
shape = "sharp-edged"
amplitude = 1.0

[aero.sweep]
speeds = [1.0, 2.0]

[[aero.surfaces]]
name = "aileron"
from = 0.5
to = 1.0
hinge = 0.75

[flutter]

[linearize]

[gust_family]
lengths = [10.0]
reference_velocity = 1.0

[turbulence]
intensity = 1.0
"#
    )
}

/// The keys the schema accepts in `table`, from serde's message for an unknown key.
fn schema_keys(table: &str) -> BTreeSet<String> {
    let bogus = "zzz_bogus = 1\n";
    let text = match table {
        "" => format!("{bogus}{BASE}"),
        "loads.time" => BASE.replace(
            "{ type = \"constant\" }",
            "{ type = \"constant\", zzz_bogus = 1 }",
        ),
        "dynamic.damping" => {
            BASE.replace("{ type = \"none\" }", "{ type = \"none\", zzz_bogus = 1 }")
        }
        "loads" => BASE.replace("[[loads]]\n", &format!("[[loads]]\n{bogus}")),
        "beam.section.coupling" => BASE.replace(
            "[modes]\n",
            &format!("[beam.section.coupling]\n{bogus}\n[modes]\n"),
        ),
        "flutter.study" => base_aero().replace(
            "[flutter]\n",
            &format!("[flutter]\n\n[flutter.study]\n{bogus}"),
        ),
        "aero.aerodynamics" => base_aero().replace(
            "{ model = \"steady\" }",
            "{ model = \"steady\", zzz_bogus = 1 }",
        ),
        "aero.surfaces" => base_aero().replace(
            "[[aero.surfaces]]\n",
            &format!("[[aero.surfaces]]\n{bogus}"),
        ),
        t if t.starts_with("aero")
            || ["flutter", "linearize", "gust_family", "turbulence"].contains(&t) =>
        {
            let header = format!("[{t}]\n");
            let base = base_aero();
            assert!(base.contains(&header), "{t}");
            base.replacen(&header, &format!("{header}{bogus}"), 1)
        }
        t => {
            let header = format!("[{t}]\n");
            assert!(BASE.contains(&header), "{t}");
            BASE.replacen(&header, &format!("{header}{bogus}"), 1)
        }
    };
    let e = Case::from_toml_str(&text).expect_err("a bogus key");
    let expected = e
        .reason
        .split_once("the keys here are ")
        .unwrap_or_else(|| panic!("{table}: {e}"))
        .1;
    expected
        .replace("` or `", "`, `")
        .split(", ")
        .map(|k| k.trim_matches('`').to_string())
        .collect()
}

#[test]
fn the_documentation_lists_exactly_the_keys_of_the_schema() {
    let docs = documented();
    for (table, keys) in &docs {
        let mut schema = schema_keys(table);
        // Sub-tables are documented under their own heading, not as keys.
        let subtables: &[&str] = match table.as_str() {
            "" => &[
                "beam",
                "modes",
                "loads",
                "static",
                "dynamic",
                "aero",
                "flutter",
                "linearize",
                "gust_family",
                "turbulence",
                "output",
            ],
            "beam" => &["section"],
            "beam.section" => &["coupling"],
            "flutter" => &["study"],
            "aero" => &["flight", "sweep", "surfaces"],
            "aero.flight" => &["gust"],
            "static" => &["sweep"],
            "dynamic" => &["initial"],
            _ => &[],
        };
        for s in subtables {
            assert!(schema.remove(*s), "{table}: no sub-table {s}");
            let path = if table.is_empty() {
                s.to_string()
            } else {
                format!("{table}.{s}")
            };
            assert!(docs.contains_key(&path), "{path} is not documented");
        }
        let documented: BTreeSet<String> = keys.keys().cloned().collect();
        assert_eq!(documented, schema, "keys of [{table}]");
    }
    assert_eq!(docs.len(), 24, "{:?}", docs.keys());
}

/// The default the code uses for each key whose documented default is a literal.
fn actual_defaults() -> BTreeMap<(&'static str, &'static str), String> {
    let case = Case::from_toml_str(
        &BASE
            .replace("[static.sweep]\nload = \"G\"\nscales = [1.0]\n", "")
            .replace("damping = { type = \"none\" }\n", "")
            .replace("time = { type = \"constant\" }\n", "")
            .replace("[dynamic.initial]\ntype = \"rest\"\n", ""),
    )
    .unwrap();
    let statics = case.static_plan().unwrap();
    let dynamic = case.dynamic_plan().unwrap();
    // The plan of BASE with `line` in place of its damping line, in [dynamic].
    let from = |line: &str| {
        let text = BASE.replace("damping = { type = \"none\" }\n", line);
        Case::from_toml_str(&text).unwrap().dynamic_plan().unwrap()
    };
    let o = &statics.options;
    let s = &dynamic.settings;
    let mut d = BTreeMap::new();
    let mut put = |table, key, v: String| {
        d.insert((table, key), v);
    };
    let calibration = match statics.model.beam().calibration() {
        Calibration::TipLoad => "tip-load",
        Calibration::Uniform => "uniform",
    };
    put("beam", "calibration", format!("\"{calibration}\""));
    let model = if case.is_chain3d() {
        "chain3d"
    } else {
        "planar"
    };
    put("beam", "model", format!("\"{model}\""));
    put(
        "flutter.study",
        "divergence",
        study_divergence().to_string(),
    );
    put(
        "output",
        "format",
        format!("\"{}\"", case.output.format().name()),
    );
    put(
        "output",
        "node_times",
        case.output.max_node_times().to_string(),
    );
    put("output", "vtk", case.output.vtk().to_string());
    // Point masses: no element has rotary inertia in bending.
    let point_masses = statics
        .model
        .beam()
        .bending_inertias()
        .iter()
        .all(|&j| j == 0.0);
    let element = if point_masses { "point-mass" } else { "bar" };
    put("beam", "element_inertia", format!("\"{element}\""));
    // min(10, n_dofs): 4 here, 10 for a 20-element beam.
    let count = |elements: &str| {
        let text = BASE.replace("elements = 4", elements);
        Case::from_toml_str(&text)
            .unwrap()
            .modes_plan()
            .unwrap()
            .count
    };
    assert_eq!((count("elements = 4"), count("elements = 20")), (4, 10));
    let default = flexwing::analysis::modes::DEFAULT_COUNT;
    put("modes", "count", format!("min({default}, n_dofs)"));
    let torsion = Case::from_toml_str(&BASE.replace(
        "mass_per_length = 0.2\n",
        "mass_per_length = 0.2\nGJ = 1\npolar_inertia = 0.1\npolar_inertia_about = \"mass-centre\"\n",
    ))
    .unwrap()
    .model()
    .unwrap();
    put(
        "beam.section",
        "d0",
        torsion.beam().offsets()[0].to_string(),
    );
    let loads = |body: &str| {
        let text = BASE.replace(
            "[[loads]]\nname = \"G\"\ntype = \"gravity\"\ntime = { type = \"constant\" }\n",
            &format!("[[loads]]\nname = \"G\"\n{body}"),
        );
        Case::from_toml_str(&text)
            .unwrap()
            .static_plan()
            .unwrap()
            .loads[0]
            .clone()
    };
    let Load::PointForce {
        force: Force::Dead { fx, .. },
        ..
    } = loads("type = \"point-force\"\nnode = 4\ndirection = \"dead\"\nfy = 1\n")
    else {
        panic!("a dead point force")
    };
    put("loads", "fx", fx.to_string());
    let Load::PointForce {
        force: Force::Dead { fy, .. },
        ..
    } = loads("type = \"point-force\"\nnode = 4\ndirection = \"dead\"\nfx = 1\n")
    else {
        panic!("a dead point force")
    };
    put("loads", "fy", fy.to_string());
    let Load::PointForce {
        force: Force::Follower { tangential, .. },
        ..
    } = loads("type = \"point-force\"\nnode = 4\ndirection = \"follower\"\nnormal = 1\n")
    else {
        panic!("a follower point force")
    };
    put("loads", "tangential", tangential.to_string());
    let Load::PointForce {
        force: Force::Follower { normal, .. },
        ..
    } = loads("type = \"point-force\"\nnode = 4\ndirection = \"follower\"\ntangential = 1\n")
    else {
        panic!("a follower point force")
    };
    put("loads", "normal", normal.to_string());
    let Load::Gravity { g } = loads("type = \"gravity\"\n") else {
        panic!("gravity")
    };
    put("loads", "g", g.to_string());
    put("loads", "active", dynamic.time[0].is_some().to_string());
    put("static", "full", statics.full.to_string());
    put("static", "reduced", format!("{:?}", statics.reduced));
    put(
        "static",
        "reduced_modes",
        format!("{:?}", statics.reduced_modes),
    );
    put("static", "tolerance", o.tolerance.to_string());
    put("static", "max_iterations", o.max_iterations.to_string());
    put("static", "min_step", o.min_step.to_string());
    put("static", "line_search", o.line_search.to_string());
    put("dynamic", "full", dynamic.full.to_string());
    put("dynamic", "simplified", dynamic.simplified.to_string());
    put("dynamic", "reduced", format!("{:?}", dynamic.reduced));
    put(
        "dynamic",
        "reduced_modes",
        format!("{:?}", dynamic.reduced_modes),
    );
    let gyroscopic = match dynamic.gyroscopic {
        Gyroscopic::Exact => "exact",
        Gyroscopic::FiniteDifference { .. } => "finite-difference",
        Gyroscopic::Neglected => "neglected",
    };
    put("dynamic", "gyroscopic", format!("\"{gyroscopic}\""));
    let Gyroscopic::FiniteDifference { step } =
        from("gyroscopic = \"finite-difference\"\n").gyroscopic
    else {
        panic!("finite differences")
    };
    put("dynamic", "gyroscopic_step", step.to_string());
    // "auto" is the case file's name for the library's default method.
    assert_eq!(
        dynamic.integrator,
        flexwing::solve::integrate::Method::default()
    );
    put("dynamic", "integrator", "\"auto\"".into());
    put("dynamic", "rtol", s.rtol.to_string());
    put("dynamic", "atol", s.atol.to_string());
    put("dynamic", "max_order", s.max_order.to_string());
    put("dynamic", "spectral_radius", s.spectral_radius.to_string());
    put("dynamic", "max_steps", s.max_steps.to_string());
    put(
        "dynamic",
        "energy_runaway",
        dynamic.audit.runaway.to_string(),
    );
    assert_eq!(dynamic.audit.tolerance, None, "energy_tolerance: see text");
    let time = |spec: &str| {
        let text = BASE.replace("{ type = \"constant\" }", spec);
        Case::from_toml_str(&text)
            .unwrap()
            .dynamic_plan()
            .unwrap()
            .time[0]
            .clone()
    };
    let Some(TimeFunction::Sine { phase, .. }) = time("{ type = \"sine\", omega = 1 }") else {
        panic!("a sine")
    };
    put("loads.time", "phase", phase.to_string());
    let Some(TimeFunction::Ramp { start, .. }) = time("{ type = \"ramp\", end = 0.5 }") else {
        panic!("a ramp")
    };
    put("loads.time", "start", start.to_string());
    let Damping::Rayleigh { alpha, .. } =
        from("damping = { type = \"rayleigh\", beta = 1 }\n").damping
    else {
        panic!("Rayleigh")
    };
    put("dynamic.damping", "alpha", alpha.to_string());
    let Damping::Rayleigh { beta, .. } =
        from("damping = { type = \"rayleigh\", alpha = 1 }\n").damping
    else {
        panic!("Rayleigh")
    };
    put("dynamic.damping", "beta", beta.to_string());
    let Initial::Given { q, .. } = Case::from_toml_str(&BASE.replace(
        "type = \"rest\"\n",
        "type = \"given\"\nqdot = [1, 1, 1, 1]\n",
    ))
    .unwrap()
    .dynamic_plan()
    .unwrap()
    .initial
    else {
        panic!("given")
    };
    assert_eq!(q, [0.0; 4], "q defaults to zeros, as documented");
    aero_defaults(&mut put);
    d
}

/// Whether the study of a 3-D case without `flutter.study.divergence` runs the divergence.
fn study_divergence() -> bool {
    use flexwing::analysis::chain3d::Analysis3d;
    let text = r#"
[beam]
model = "chain3d"
length = 1.0
elements = 4

[beam.section]
EI = 50
EI_lag = 500
GJ = 20
mass_per_length = 0.2
polar_inertia = 0.01
polar_inertia_about = "mass-centre"

[aero]
chord = 0.1
elastic_axis = 0.5
density = 1.2
aerodynamics = { model = "quasi-steady" }

[aero.sweep]
speeds = [1.0, 2.0]

[flutter.study]
parameter = "tip-force"
levels = [0.0]
"#;
    let plan = Case::from_toml_str(text)
        .unwrap()
        .chain3d_plan(flexwing_case::Analysis::Study)
        .unwrap();
    match plan.analysis {
        Analysis3d::Study(s) => s.divergence,
        _ => panic!("a study"),
    }
}

/// The defaults of the aeroelastic tables, from the plans of a case without those keys.
fn aero_defaults(put: &mut impl FnMut(&'static str, &'static str, String)) {
    use flexwing::beam::Profile;
    // Without the gravity load (with [aero] gravity is aero.flight.gravity) and its sweep.
    let text = base_aero()
        .replace("[flutter]\n", "")
        .replace("[linearize]\n", "")
        .replace(
            "[[loads]]\nname = \"G\"\ntype = \"gravity\"\ntime = { type = \"constant\" }\n",
            "",
        )
        .replace("[static.sweep]\nload = \"G\"\nscales = [1.0]\n", "");
    let case = Case::from_toml_str(&text).unwrap();
    let flutter = case.flutter_plan().unwrap();
    let uniform = |p: &Profile| match p {
        Profile::Uniform(v) => v.to_string(),
        other => format!("{other:?}"),
    };
    let s = &flutter.aero.section;
    put("aero", "zero_lift_angle", uniform(&s.zero_lift_angle));
    put("aero", "cm0", uniform(&s.cm0));
    put("aero", "cd0", uniform(&s.cd0));
    put(
        "aero.surfaces",
        "deflection",
        s.surfaces[0].deflection.to_string(),
    );
    assert_eq!(
        s.lift_slope,
        Profile::Uniform(2.0 * std::f64::consts::PI),
        "2π"
    );
    put(
        "aero.flight",
        "root_angle",
        flutter.flight.root_angle.to_string(),
    );
    assert_eq!(flutter.flight.gravity, None, "no gravity, as documented");
    put("flutter", "full", flutter.full.to_string());
    put("flutter", "reduced", format!("{:?}", flutter.reduced));
    put(
        "flutter",
        "reduced_modes",
        format!("{:?}", flutter.reduced_modes),
    );
    put("flutter", "tolerance", flutter.tolerance.to_string());
    put("flutter", "pk", flutter.pk.to_string());
    let linear = case.linearize_plan().unwrap();
    put("linearize", "full", linear.full.to_string());
    put("linearize", "reduced", format!("{:?}", linear.reduced));
    put(
        "linearize",
        "reduced_modes",
        format!("{:?}", linear.reduced_modes),
    );
    put("linearize", "inputs", format!("{:?}", linear.inputs));
    put("linearize", "outputs", format!("{:?}", linear.outputs));
    put(
        "linearize",
        "states",
        format!("\"{}\"", linear.states.name()),
    );
    let dynamic = case.aero_dynamic_plan().unwrap();
    let gust = dynamic.flight.gust.expect("a gust");
    put("aero.flight.gust", "start", gust.start.to_string());
    put("aero.flight.gust", "spanwise", uniform(&gust.spanwise));
    put(
        "aero.flight.gust",
        "penetration",
        format!("\"{}\"", gust.penetration.name()),
    );
    // The family's one 10 m gust passes the wing at 10 m/s in 2 s.
    let family = Case::from_toml_str(&text.replace("end_time = 1.0", "end_time = 2.5"))
        .unwrap()
        .gust_family_plan()
        .unwrap();
    put("gust_family", "alleviation", family.alleviation.to_string());
    put("gust_family", "start", family.start.to_string());
    put(
        "gust_family",
        "penetration",
        format!("\"{}\"", family.penetration.name()),
    );
    let turbulence = case.turbulence_plan().unwrap();
    put(
        "turbulence",
        "spectrum",
        format!("\"{}\"", turbulence.turbulence.spectrum.name()),
    );
    put(
        "turbulence",
        "frequencies",
        turbulence.grid().points.to_string(),
    );
}

/// A documented default that is a literal: `1e-6`, `true`, `[]`, `"auto"`, `0` (with a note
/// after it); `None` for a described one ("required", "none", "see below", …).
fn literal(cell: &str) -> Option<String> {
    let rest = cell.strip_prefix('`')?;
    let value = &rest[..rest.find('`')?];
    Some(value.to_string())
}

#[test]
fn documented_defaults_are_the_codes() {
    let docs = documented();
    let actual = actual_defaults();
    let mut checked = 0;
    for (table, keys) in &docs {
        for (key, cell) in keys {
            let Some(doc) = literal(cell) else { continue };
            let code = actual
                .get(&(table.as_str(), key.as_str()))
                .unwrap_or_else(|| {
                    panic!("{table}.{key}: documented default {doc} is not checked")
                });
            let same = match (doc.parse::<f64>(), code.parse::<f64>()) {
                (Ok(a), Ok(b)) => a == b,
                _ => doc == *code,
            };
            assert!(same, "{table}.{key}: documented {doc}, code {code}");
            checked += 1;
        }
    }
    // Every default the code knows is documented as a literal.
    assert_eq!(checked, actual.len(), "{actual:?}");
}
