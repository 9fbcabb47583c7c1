//! The node histories of a run as named arrays, the one layout of the `.npz` files that the CLI
//! (`flexwing dynamic`, `[output] format = "npz"`) and Python (`DynamicResult.save_npz`) write:
//!
//! * `models` — the model labels, in the run's order;
//! * `fields`, `units` — the names and units of the last axis of every `nodes` array
//!   (the planar chain: `x`, `y` in m, `twist` in rad; the 3-D chain: `x`, `y`, `z` in m and
//!   the section rotation vector `rx`, `ry`, `rz` in rad);
//! * `LABEL/t` `(S,)` — the times of the model's node snapshots (s);
//! * `LABEL/index` `(S,)` — their indices among the run's output times (every `k`-th when the
//!   history was thinned, docs/cli.md);
//! * `LABEL/nodes` `(S, nodes, fields)` — the values, row-major (NumPy's default order).

use crate::Value;

/// The fields (name, unit) of the planar chain's node histories.
pub const PLANAR: [(&str, &str); 3] = [("x", "m"), ("y", "m"), ("twist", "rad")];

/// The fields (name, unit) of the 3-D chain's node histories: the node positions and the
/// section rotation vector of the element inboard of each node (NaN at the root).
pub const SPATIAL: [(&str, &str); 6] = [
    ("x", "m"),
    ("y", "m"),
    ("z", "m"),
    ("rx", "rad"),
    ("ry", "rad"),
    ("rz", "rad"),
];

/// One model's node history.
#[derive(Debug, Clone, PartialEq)]
pub struct NodeHistory {
    /// The model's label (`full`, `reduced-r2`, …).
    pub label: String,
    /// Times of the snapshots (s), `S` of them.
    pub t: Vec<f64>,
    /// Their indices among the output times.
    pub index: Vec<i64>,
    /// Number of nodes.
    pub nodes: usize,
    /// `S × nodes × fields` values, row-major.
    pub values: Vec<f64>,
}

/// The named arrays of the layout above.
///
/// # Panics
/// Never for consistent input; a history whose `values` do not have `S × nodes × fields`
/// entries is a bug of the caller (debug assertion).
pub fn variables<S: AsRef<str>>(
    fields: &[(S, S)],
    histories: &[NodeHistory],
) -> Vec<(String, Value)> {
    let mut out = vec![
        (
            "models".to_string(),
            Value::Strings(histories.iter().map(|h| h.label.clone()).collect()),
        ),
        (
            "fields".to_string(),
            Value::Strings(fields.iter().map(|f| f.0.as_ref().to_string()).collect()),
        ),
        (
            "units".to_string(),
            Value::Strings(fields.iter().map(|f| f.1.as_ref().to_string()).collect()),
        ),
    ];
    for h in histories {
        debug_assert_eq!(h.values.len(), h.t.len() * h.nodes * fields.len());
        out.push((
            format!("{}/t", h.label),
            Value::Array {
                shape: vec![h.t.len()],
                data: h.t.clone(),
            },
        ));
        out.push((format!("{}/index", h.label), Value::Ints(h.index.clone())));
        out.push((
            format!("{}/nodes", h.label),
            Value::Array {
                shape: vec![h.t.len(), h.nodes, fields.len()],
                data: h.values.clone(),
            },
        ));
    }
    out
}
