//! `[[loads]]` into library loads. The library validates the values (positions on the beam,
//! finite numbers, tables covering the span); this module checks what it cannot see: which keys
//! were given together, names, and node indices.

use flexwing::beam::{Beam, Profile};
use flexwing::model::{DistributedForce, Force, Load};
use flexwing::InputError;

use super::spec::{Case, DirectionSpec, LoadKindSpec, LoadSpec};

/// Standard gravity (m/s²), the default of `g`.
pub const STANDARD_GRAVITY: f64 = 9.80665;

impl Case {
    /// The loads of `[[loads]]`, in order, with node indices turned into span positions of `beam`.
    ///
    /// # Errors
    /// A key that does not belong to the load's type or direction, a missing key, a repeated or
    /// empty name, a node beyond the tip. The values (positions on the beam, finite numbers, a
    /// torque on a bending-only beam) are checked by the library when the loads are applied.
    pub(crate) fn to_loads(&self, beam: &Beam) -> Result<Vec<Load>, InputError> {
        library_loads(&self.loads, beam)
    }

    /// Index of the load named `name`.
    pub fn load_index(&self, name: &str) -> Option<usize> {
        self.loads
            .iter()
            .position(|l| l.name.as_deref() == Some(name))
    }
}

/// The library loads of `[[loads]]` tables on `beam`, in order, with node indices turned into
/// span positions: what [`Case`] does with its own loads, for a front end that takes load tables
/// without a whole case (the Python model level). Errors name `loads[i]…`; a `time` or `active`
/// key is not read here (a dynamic plan reads them).
///
/// # Errors
/// As the loads of a case: a key that does not belong to the load's type or direction, a
/// missing key, a repeated or empty name, a node beyond the tip. The values are checked by the
/// library when the loads are applied ([`flexwing::model::FullModel::apply`]).
pub fn library_loads(specs: &[LoadSpec], beam: &Beam) -> Result<Vec<Load>, InputError> {
    check_names(specs)?;
    specs
        .iter()
        .enumerate()
        .map(|(i, spec)| load(i, spec, beam.nodes()))
        .collect()
}

/// The loads of `[[loads]]` on a chain with node stations `nodes`, as [`library_loads`], with
/// `fz` allowed (the 3-D chain): each planar load and the `fz` of a dead force, in order.
pub(crate) fn loads_with_fz(
    specs: &[LoadSpec],
    nodes: &[f64],
) -> Result<Vec<(Load, Option<Profile>)>, InputError> {
    check_names(specs)?;
    specs
        .iter()
        .enumerate()
        .map(|(i, spec)| {
            let Some(fz) = &spec.fz else {
                return load(i, spec, nodes).map(|l| (l, None));
            };
            let dead = spec.direction == Some(DirectionSpec::Dead);
            let takes = matches!(
                spec.kind,
                LoadKindSpec::PointForce | LoadKindSpec::Distributed
            );
            if !(dead && takes) {
                return Err(InputError::new(
                    format!("loads[{i}].fz"),
                    "belongs to a dead point force or distributed force (global z component)",
                ));
            }
            let mut planar = spec.clone();
            planar.fz = None;
            if planar.fx.is_none() && planar.fy.is_none() {
                planar.fy = Some(crate::Property(Profile::Uniform(0.0)));
            }
            if spec.kind == LoadKindSpec::PointForce && !matches!(fz.0, Profile::Uniform(_)) {
                return Err(InputError::new(
                    format!("loads[{i}].fz"),
                    "a point force takes a number (N), not a table",
                ));
            }
            load(i, &planar, nodes).map(|l| (l, Some(fz.0.clone())))
        })
        .collect()
}

fn check_names(loads: &[LoadSpec]) -> Result<(), InputError> {
    for (i, l) in loads.iter().enumerate() {
        let Some(name) = &l.name else { continue };
        if name.trim().is_empty() {
            return Err(InputError::new(
                format!("loads[{i}].name"),
                "must not be empty",
            ));
        }
        if let Some(j) = loads[..i]
            .iter()
            .position(|o| o.name.as_deref() == Some(name))
        {
            return Err(InputError::new(
                format!("loads[{i}].name"),
                format!("{name:?} is already the name of loads[{j}]; names must be unique"),
            ));
        }
    }
    Ok(())
}

fn type_name(kind: LoadKindSpec) -> &'static str {
    match kind {
        LoadKindSpec::PointForce => "point-force",
        LoadKindSpec::Moment => "moment",
        LoadKindSpec::Torque => "torque",
        LoadKindSpec::Distributed => "distributed",
        LoadKindSpec::Gravity => "gravity",
    }
}

/// The keys (besides `name` and `type`) that a load of this type takes, for messages.
fn keys_of(kind: LoadKindSpec) -> &'static str {
    match kind {
        LoadKindSpec::PointForce => {
            "span or node, direction, and fx/fy (dead) or tangential/normal (follower)"
        }
        LoadKindSpec::Moment | LoadKindSpec::Torque => "span or node, and value",
        LoadKindSpec::Distributed => "direction, and fx/fy (dead) or tangential/normal (follower)",
        LoadKindSpec::Gravity => "g",
    }
}

/// The optional keys given in `spec`, in the order of the documentation.
fn given(spec: &LoadSpec) -> Vec<&'static str> {
    [
        ("span", spec.span.is_some()),
        ("node", spec.node.is_some()),
        ("direction", spec.direction.is_some()),
        ("fx", spec.fx.is_some()),
        ("fy", spec.fy.is_some()),
        ("fz", spec.fz.is_some()),
        ("tangential", spec.tangential.is_some()),
        ("normal", spec.normal.is_some()),
        ("value", spec.value.is_some()),
        ("g", spec.g.is_some()),
    ]
    .into_iter()
    .filter_map(|(k, present)| present.then_some(k))
    .collect()
}

/// Reject keys that do not belong to the load's type.
fn check_keys(i: usize, spec: &LoadSpec) -> Result<(), InputError> {
    let allowed: &[&str] = match spec.kind {
        LoadKindSpec::PointForce => &[
            "span",
            "node",
            "direction",
            "fx",
            "fy",
            "tangential",
            "normal",
        ],
        LoadKindSpec::Moment | LoadKindSpec::Torque => &["span", "node", "value"],
        LoadKindSpec::Distributed => &["direction", "fx", "fy", "tangential", "normal"],
        LoadKindSpec::Gravity => &["g"],
    };
    match given(spec).into_iter().find(|k| !allowed.contains(k)) {
        None => Ok(()),
        Some("fz") => Err(InputError::new(
            format!("loads[{i}].fz"),
            "is a key of the 3-D chain (beam.model = \"chain3d\"): the planar chain carries \
             forces in the x-y plane only",
        )),
        Some(key) => Err(InputError::new(
            format!("loads[{i}].{key}"),
            format!(
                "is not a key of a {:?} load, which takes {}",
                type_name(spec.kind),
                keys_of(spec.kind)
            ),
        )),
    }
}

fn load(i: usize, spec: &LoadSpec, nodes: &[f64]) -> Result<Load, InputError> {
    check_keys(i, spec)?;
    let field = |key: &str| format!("loads[{i}].{key}");
    Ok(match spec.kind {
        LoadKindSpec::PointForce => {
            let span = position(i, spec, nodes)?;
            let [a, b] = components(i, spec, "point force")?;
            let number = |key: &str, p: Option<&Profile>| match p {
                None => Ok(0.0),
                Some(Profile::Uniform(v)) => Ok(*v),
                Some(Profile::Table { .. }) => Err(InputError::new(
                    field(key),
                    "a point force takes a number (N), not a table",
                )),
            };
            let force = match spec.direction {
                Some(DirectionSpec::Dead) => Force::Dead {
                    fx: number("fx", a)?,
                    fy: number("fy", b)?,
                },
                _ => Force::Follower {
                    tangential: number("tangential", a)?,
                    normal: number("normal", b)?,
                },
            };
            Load::PointForce { span, force }
        }
        LoadKindSpec::Moment => Load::Moment {
            span: position(i, spec, nodes)?,
            value: value(i, spec, "the moment about z (N·m)")?,
        },
        LoadKindSpec::Torque => Load::Torque {
            span: position(i, spec, nodes)?,
            value: value(i, spec, "the torque about the beam axis (N·m)")?,
        },
        LoadKindSpec::Distributed => {
            let [a, b] = components(i, spec, "distributed force")?;
            let profile = |p: Option<&Profile>| p.cloned().unwrap_or(Profile::Uniform(0.0));
            Load::Distributed(match spec.direction {
                Some(DirectionSpec::Dead) => DistributedForce::Dead {
                    fx: profile(a),
                    fy: profile(b),
                },
                _ => DistributedForce::Follower {
                    tangential: profile(a),
                    normal: profile(b),
                },
            })
        }
        LoadKindSpec::Gravity => Load::Gravity {
            g: spec.g.unwrap_or(STANDARD_GRAVITY),
        },
    })
}

/// The two force components of a point or distributed force, `(fx, fy)` for a dead force and
/// `(tangential, normal)` for a follower force, after checking `direction` and that the other
/// pair is absent and at least one component is given.
fn components<'a>(
    i: usize,
    spec: &'a LoadSpec,
    what: &str,
) -> Result<[Option<&'a Profile>; 2], InputError> {
    let field = |key: &str| format!("loads[{i}].{key}");
    let dead = [("fx", &spec.fx), ("fy", &spec.fy)];
    let follower = [("tangential", &spec.tangential), ("normal", &spec.normal)];
    let (used, other, name, other_name, unit) = match spec.direction {
        None => {
            return Err(InputError::new(
                field("direction"),
                "missing: \"dead\" (fx, fy along the global axes) or \"follower\" \
                 (tangential, normal in the frame of the loaded element)",
            ))
        }
        Some(DirectionSpec::Dead) => (dead, follower, "dead", "follower", "fx and/or fy"),
        Some(DirectionSpec::Follower) => (
            follower,
            dead,
            "follower",
            "dead",
            "tangential and/or normal",
        ),
    };
    if let Some((key, _)) = other.iter().find(|(_, v)| v.is_some()) {
        return Err(InputError::new(
            field(key),
            format!(
                "belongs to direction = {other_name:?}; a {name} {what} takes {}",
                if name == "dead" {
                    "fx and fy (global axes)"
                } else {
                    "tangential and normal (element frame)"
                }
            ),
        ));
    }
    if used.iter().all(|(_, v)| v.is_none()) {
        return Err(InputError::new(
            field(used[0].0),
            format!("missing: a {name} {what} needs {unit}"),
        ));
    }
    Ok([
        used[0].1.as_ref().map(|p| &p.0),
        used[1].1.as_ref().map(|p| &p.0),
    ])
}

fn value(i: usize, spec: &LoadSpec, what: &str) -> Result<f64, InputError> {
    spec.value
        .ok_or_else(|| InputError::new(format!("loads[{i}].value"), format!("missing: {what}")))
}

/// `span` as given, or the station of `node`.
fn position(i: usize, spec: &LoadSpec, nodes: &[f64]) -> Result<f64, InputError> {
    match (spec.span, spec.node) {
        (Some(span), None) => Ok(span),
        (None, Some(node)) => {
            let last = nodes.len() - 1;
            nodes.get(node).copied().ok_or_else(|| {
                InputError::new(
                    format!("loads[{i}].node"),
                    format!("{node} is beyond the last node {last} (nodes are 0 = clamp to {last} = tip)"),
                )
            })
        }
        (Some(_), Some(_)) => Err(InputError::new(
            format!("loads[{i}]"),
            "give either span or node, not both",
        )),
        (None, None) => Err(InputError::new(
            format!("loads[{i}].span"),
            "missing: give span (m along the undeformed span) or node (node index, 0 = clamp)",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BEAM: &str =
        "[beam]\nlength = 1.0\nelements = 4\n\n[beam.section]\nEI = 50\nmass_per_length = 0.2\n";

    /// The loads of `extra`, applied to the beam (as every analysis does).
    fn loads(extra: &str) -> Result<Vec<Load>, String> {
        let case = Case::from_toml_str(&format!("{BEAM}{extra}")).map_err(|e| e.to_string())?;
        let model = flexwing::model::FullModel::new(case.to_beam().map_err(|e| e.to_string())?);
        let loads = case.to_loads(model.beam()).map_err(|e| e.to_string())?;
        model.apply(&loads, "loads").map_err(|e| e.to_string())?;
        Ok(loads)
    }

    #[test]
    fn node_becomes_span() {
        let l =
            loads("[[loads]]\ntype = \"point-force\"\nnode = 2\ndirection = \"dead\"\nfy = 3\n")
                .unwrap();
        assert_eq!(
            l,
            [Load::PointForce {
                span: 0.5,
                force: Force::Dead { fx: 0.0, fy: 3.0 }
            }]
        );
    }

    #[test]
    fn key_errors_name_the_field() {
        let cases = [
            (
                "type = \"moment\"\nspan = 1\nvalue = 1\nfy = 2\n",
                "loads[0].fy: is not a key of a \"moment\" load",
            ),
            (
                "type = \"point-force\"\nspan = 1\ndirection = \"follower\"\nfy = 2\n",
                "loads[0].fy: belongs to direction = \"dead\"",
            ),
            (
                "type = \"point-force\"\nspan = 1\nfy = 2\n",
                "loads[0].direction: missing",
            ),
            (
                "type = \"point-force\"\nspan = 1\nnode = 2\ndirection = \"dead\"\nfy = 2\n",
                "loads[0]: give either span or node, not both",
            ),
            (
                "type = \"point-force\"\nnode = 5\ndirection = \"dead\"\nfy = 2\n",
                "loads[0].node: 5 is beyond the last node 4",
            ),
            (
                "type = \"point-force\"\nspan = 1\ndirection = \"dead\"\nfy = { x = [0, 1], value = [1, 2] }\n",
                "loads[0].fy: a point force takes a number",
            ),
            ("type = \"moment\"\nspan = 1\n", "loads[0].value: missing"),
            (
                "type = \"torque\"\nspan = 1\nvalue = 1\n",
                "loads[0]: a torque needs torsion",
            ),
            (
                "type = \"distributed\"\ndirection = \"dead\"\n",
                "loads[0].fx: missing",
            ),
        ];
        for (body, expected) in cases {
            let msg = loads(&format!("[[loads]]\n{body}")).unwrap_err();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }

    #[test]
    fn names_are_unique() {
        let one = "[[loads]]\nname = \"A\"\ntype = \"gravity\"\n";
        let msg = loads(&format!("{one}{one}")).unwrap_err();
        assert!(msg.starts_with("loads[1].name: \"A\" is already"), "{msg}");
    }
}
