//! The serde types of the case file, one struct per TOML table. Units and defaults are documented
//! in `docs/case-file.md`; the conversion into library types lives in `convert.rs`.

use serde::Deserialize;

use super::property::Property;

/// The whole case file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Free text, echoed in the outputs.
    #[serde(default)]
    pub title: Option<String>,
    /// `[beam]`.
    pub beam: BeamSpec,
    /// `[modes]`, optional.
    #[serde(default)]
    pub modes: ModesSpec,
    /// `[[loads]]`: the loads of a static run, applied together.
    #[serde(default)]
    pub loads: Vec<LoadSpec>,
    /// `[static]`, optional (defaults: the full model only).
    #[serde(rename = "static", default)]
    pub statics: StaticSpec,
}

/// `[beam]`: span, discretization, calibration and `[beam.section]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BeamSpec {
    /// Span `L` (m).
    pub length: f64,
    /// Number of equal elements; exclusive with `stations`.
    #[serde(default)]
    pub elements: Option<usize>,
    /// Node stations `0 … L` (m); exclusive with `elements`.
    #[serde(default)]
    pub stations: Option<Vec<f64>>,
    /// Bending spring calibration.
    #[serde(default)]
    pub calibration: CalibrationSpec,
    /// `[beam.section]`.
    pub section: SectionSpec,
}

/// `beam.calibration`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CalibrationSpec {
    /// The paper's tip-load-matched springs.
    #[default]
    TipLoad,
    /// `EI/ℓ` at every joint.
    Uniform,
}

/// `[beam.section]`: section properties, each a number or a table over the span.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Bending stiffness (N·m²).
    #[serde(rename = "EI")]
    pub ei: Property,
    /// Mass per length (kg/m).
    pub mass_per_length: Property,
    /// Torsional stiffness (N·m²); its presence switches torsion on.
    #[serde(rename = "GJ", default)]
    pub gj: Option<Property>,
    /// Polar mass moment of inertia per length (kg·m).
    #[serde(default)]
    pub polar_inertia: Option<Property>,
    /// Axis of `polar_inertia`; required with it.
    #[serde(default)]
    pub polar_inertia_about: Option<InertiaAxisSpec>,
    /// Chordwise mass-centre offset from the elastic axis (m).
    #[serde(default)]
    pub d0: Option<Property>,
}

/// `beam.section.polar_inertia_about`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum InertiaAxisSpec {
    /// About the section's mass centre (`I_cg`).
    MassCentre,
    /// About the elastic axis (`I_ea = I_cg + m d0²`).
    ElasticAxis,
}

/// `[modes]`.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModesSpec {
    /// Number of modes reported; default `min(10, n_dofs)`.
    #[serde(default)]
    pub count: Option<usize>,
}

/// One `[[loads]]` table. Which keys a load takes depends on its `type` (and `direction`); the
/// conversion (`loads.rs`) rejects the keys that do not belong, naming them.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Optional unique name, used by `[static.sweep]`.
    #[serde(default)]
    pub name: Option<String>,
    /// What kind of load.
    #[serde(rename = "type")]
    pub kind: LoadKindSpec,
    /// Position along the undeformed span (m); exclusive with `node`.
    #[serde(default)]
    pub span: Option<f64>,
    /// Node index `0 ..= n`; exclusive with `span`.
    #[serde(default)]
    pub node: Option<usize>,
    /// Dead or follower (point forces and distributed forces).
    #[serde(default)]
    pub direction: Option<DirectionSpec>,
    /// Global spanwise component: N (point force) or N/m (distributed).
    #[serde(default)]
    pub fx: Option<Property>,
    /// Global vertical component: N (point force) or N/m (distributed).
    #[serde(default)]
    pub fy: Option<Property>,
    /// Component along the element axis: N or N/m.
    #[serde(default)]
    pub tangential: Option<Property>,
    /// Component along the element normal: N or N/m.
    #[serde(default)]
    pub normal: Option<Property>,
    /// Moment or torque (N·m).
    #[serde(default)]
    pub value: Option<f64>,
    /// Gravitational acceleration (m/s²).
    #[serde(default)]
    pub g: Option<f64>,
}

/// `loads[].type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LoadKindSpec {
    /// A point force.
    PointForce,
    /// A bending moment about z.
    Moment,
    /// A torque about the beam axis.
    Torque,
    /// A force per length over the whole span.
    Distributed,
    /// The weight of the beam.
    Gravity,
}

/// `loads[].direction`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DirectionSpec {
    /// Fixed global components `fx`, `fy`.
    Dead,
    /// Components `tangential`, `normal` in the frame of the loaded element.
    Follower,
}

/// `[static]`: which models to solve, solver options, loaded modes and the sweep.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticSpec {
    /// Solve the full model.
    #[serde(default = "yes")]
    pub full: bool,
    /// Reduced models on the first `r` modes, one per entry.
    #[serde(default)]
    pub reduced: Vec<usize>,
    /// Reduced models on explicit 1-based mode lists.
    #[serde(default)]
    pub reduced_modes: Vec<Vec<usize>>,
    /// `StaticOptions::tolerance`.
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// `StaticOptions::max_iterations`.
    #[serde(default)]
    pub max_iterations: Option<usize>,
    /// `StaticOptions::min_step`.
    #[serde(default)]
    pub min_step: Option<f64>,
    /// `StaticOptions::line_search`.
    #[serde(default)]
    pub line_search: Option<bool>,
    /// Number of loaded modes reported about the full model's final equilibrium.
    #[serde(default)]
    pub modes: Option<usize>,
    /// `[static.sweep]`.
    #[serde(default)]
    pub sweep: Option<SweepSpec>,
}

fn yes() -> bool {
    true
}

impl Default for StaticSpec {
    fn default() -> Self {
        Self {
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            tolerance: None,
            max_iterations: None,
            min_step: None,
            line_search: None,
            modes: None,
            sweep: None,
        }
    }
}

/// `[static.sweep]`: the scale of one named load over a list of points.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Name of the swept load.
    pub load: String,
    /// Explicit scale factors; exclusive with `from`/`to`/`steps`.
    #[serde(default)]
    pub scales: Option<Vec<f64>>,
    /// First scale of an evenly spaced sweep.
    #[serde(default)]
    pub from: Option<f64>,
    /// Last scale of an evenly spaced sweep.
    #[serde(default)]
    pub to: Option<f64>,
    /// Number of points of an evenly spaced sweep, both ends included (≥ 2).
    #[serde(default)]
    pub steps: Option<usize>,
}
