//! `[output]`: how the front ends write a run's results — the format of the node histories
//! (`format`), how many output times they keep (`node_times`) and whether VTK files for ParaView
//! are written (`vtk`). Read by the CLI (with `--format`, `--node-times`, `--vtk` over them) and
//! by Python's `save_npz`/`write_vtk` defaults; the library never sees them. docs/case-file.md.

use serde::{Deserialize, Serialize};

use super::words::word_enum;

/// `[output]`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct OutputSpec {
    /// The file format of the node histories; default CSV.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub format: Option<OutputFormatSpec>,
    /// Most output times in the node histories; default [`OutputSpec::DEFAULT_NODE_TIMES`].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node_times: Option<NodeTimesSpec>,
    /// Also write VTK XML files (`.vtu` per output time, a `.pvd` collection); default false.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub vtk: Option<bool>,
}

impl OutputSpec {
    /// The default of `node_times`: 201 output times (every `k`-th past it).
    pub const DEFAULT_NODE_TIMES: usize = 201;

    /// `format`, or its default.
    pub fn format(&self) -> OutputFormatSpec {
        self.format.unwrap_or_default()
    }

    /// The most output times the node histories keep (`usize::MAX` for `"all"`).
    pub fn max_node_times(&self) -> usize {
        match self.node_times {
            None => Self::DEFAULT_NODE_TIMES,
            Some(NodeTimesSpec::All) => usize::MAX,
            Some(NodeTimesSpec::Most(k)) => k,
        }
    }

    /// `vtk`, or its default (false).
    pub fn vtk(&self) -> bool {
        self.vtk.unwrap_or(false)
    }
}

/// `output.format`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum OutputFormatSpec {
    /// Long-format CSV, one row per model, output time and node.
    #[default]
    Csv,
    /// NumPy `.npz`: one (time × node × field) array per model.
    Npz,
}

word_enum!(OutputFormatSpec { Csv = "csv", Npz = "npz" });

impl OutputFormatSpec {
    /// The case file's word.
    pub fn name(self) -> &'static str {
        match self {
            Self::Csv => "csv",
            Self::Npz => "npz",
        }
    }
}

/// `output.node_times`: a whole number ≥ 1, or `"all"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeTimesSpec {
    /// Every output time.
    All,
    /// At most this many (every `k`-th output time past it, the first included).
    Most(usize),
}

impl Serialize for NodeTimesSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::All => s.serialize_str("all"),
            Self::Most(k) => s.serialize_u64(*k as u64),
        }
    }
}

impl<'de> Deserialize<'de> for NodeTimesSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl serde::de::Visitor<'_> for Visitor {
            type Value = NodeTimesSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a whole number ≥ 1 or \"all\"")
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<Self::Value, E> {
                match usize::try_from(v) {
                    Ok(k) if k >= 1 => Ok(NodeTimesSpec::Most(k)),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Unsigned(v), &self)),
                }
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<Self::Value, E> {
                match u64::try_from(v) {
                    Ok(u) => self.visit_u64(u),
                    Err(_) => Err(E::invalid_value(serde::de::Unexpected::Signed(v), &self)),
                }
            }
            fn visit_str<E: serde::de::Error>(self, s: &str) -> Result<Self::Value, E> {
                match s {
                    "all" => Ok(NodeTimesSpec::All),
                    _ => Err(E::invalid_value(serde::de::Unexpected::Str(s), &self)),
                }
            }
        }
        d.deserialize_any(Visitor)
    }
}

/// Indices of the output times a node history keeps, of `n`: all of them up to `most`, else
/// every `k`-th from the first with `k = ⌈n / most⌉` (so at most `most`, and evenly spaced).
pub fn thinned_indices(n: usize, most: usize) -> Vec<usize> {
    let k = n.div_ceil(most.max(1)).max(1);
    (0..n).step_by(k).collect()
}
