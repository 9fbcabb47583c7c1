//! The serde types of the 3-D chain's keys: `beam.model`, `[beam.section.coupling]` and
//! `[flutter.study]` (the other 3-D keys are fields of `[beam]` and `[beam.section]` in
//! `spec.rs`). Documented in docs/case-file.md; converted in `chain3d.rs`.

use serde::{Deserialize, Serialize};

use super::property::Property;
use super::words::word_enum;

/// `beam.model`: which structural model the case is of.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum StructureSpec {
    /// The paper's planar chain: bending in one plane, each element twisting about its axis.
    #[default]
    Planar,
    /// The geometrically exact 3-D chain: twist, flap and lag at every joint.
    Chain3d,
}

word_enum!(StructureSpec { Planar = "planar", Chain3d = "chain3d" });

/// `[beam.section.coupling]`: the off-diagonal terms of the 3×3 section stiffness (N·m²), each
/// a number or a table over the span; a term not given is zero.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct CouplingSpec {
    /// Bend (flap)–twist coupling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub twist_flap: Option<Property>,
    /// Lag–twist coupling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub twist_lag: Option<Property>,
    /// Lag–flap coupling.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lag_flap: Option<Property>,
}

/// `[flutter.study]`: flutter and divergence against a load level (`flexwing study`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StudySpec {
    /// The load swept.
    pub parameter: StudyParameterSpec,
    /// Its levels: N (tip force), a factor of `g` (gravity), rad (root angle).
    pub levels: Vec<f64>,
    /// Gravity of level 1 (m/s²) for `gravity-factor`; default 9.80665.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<f64>,
    /// Also the divergence speed at every level (default true).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub divergence: Option<bool>,
}

/// `flutter.study.parameter`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum StudyParameterSpec {
    /// A dead vertical force at the tip (N), added to the loads.
    TipForce,
    /// Gravity `level · g`, replacing `aero.flight.gravity`.
    GravityFactor,
    /// The root angle (rad), replacing `aero.flight.root_angle`.
    RootAngle,
}

word_enum!(StudyParameterSpec {
    TipForce = "tip-force",
    GravityFactor = "gravity-factor",
    RootAngle = "root-angle"
});
