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
