//! The serde types of the case file, one struct per TOML table. Units and defaults are documented
//! in `docs/case-file.md`; the conversion into library plans lives in `beam.rs`, `loads.rs`,
//! `statics.rs` and `dynamic.rs`. Every type also serializes, so a case round-trips through TOML
//! (or any serde format) with the same keys.

use flexwing::solve::integrate::Method;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::property::Property;
use super::spec_aero::{AeroSpec, FlutterSpec, LinearizeSpec};
use super::spec_chain3d::{CouplingSpec, StructureSpec};
use super::words::word_enum;

/// The whole case file.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct Case {
    /// Free text, echoed in the outputs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub title: Option<String>,
    /// `[beam]`.
    pub beam: BeamSpec,
    /// `[modes]`, optional.
    #[serde(default)]
    pub modes: ModesSpec,
    /// `[[loads]]`: the loads of a static run, applied together.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<LoadSpec>,
    /// `[static]`, optional (defaults: the full model only).
    #[serde(rename = "static", default)]
    pub statics: StaticSpec,
    /// `[dynamic]`, required by `flexwing dynamic` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dynamic: Option<DynamicSpec>,
    /// `[aero]`: strip aerodynamics; with it `static` and `dynamic` are aeroelastic runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub aero: Option<AeroSpec>,
    /// `[flutter]`, optional, for `flexwing flutter`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub flutter: Option<FlutterSpec>,
    /// `[linearize]`, optional, for `flexwing linearize`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linearize: Option<LinearizeSpec>,
    /// `[gust_family]`, required by `flexwing gust` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gust_family: Option<super::spec_aero::GustFamilySpec>,
    /// `[turbulence]`, required by `flexwing turbulence` only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub turbulence: Option<super::spec_aero::TurbulenceSpec>,
    /// `[output]`, optional: how the front ends write the results (`spec_output.rs`).
    #[serde(default, skip_serializing_if = "is_default")]
    pub output: super::spec_output::OutputSpec,
    /// The file the case was read from, for messages; not a key.
    #[serde(skip)]
    pub(crate) file: Option<String>,
}

/// `[beam]`: span, discretization, calibration and `[beam.section]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BeamSpec {
    /// The structural model: the paper's planar chain (default) or the 3-D chain.
    #[serde(default, skip_serializing_if = "is_default")]
    pub model: StructureSpec,
    /// Span `L` (m): the arc length of the reference axis on the 3-D chain.
    pub length: f64,
    /// Number of equal elements; exclusive with `stations`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elements: Option<usize>,
    /// Node stations `0 … L` (m); exclusive with `elements`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stations: Option<Vec<f64>>,
    /// Bending spring calibration (planar default `tip-load`, 3-D default `compliance`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub calibration: Option<CalibrationSpec>,
    /// What an element is in bending: a point mass (the paper's, the planar default) or a rigid
    /// bar (the 3-D default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub element_inertia: Option<ElementInertiaSpec>,
    /// Sweep angle along the span (rad, positive back; 3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep: Option<Property>,
    /// Dihedral angle along the span (rad, positive tip up; 3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dihedral: Option<Property>,
    /// Pretwist along the span (rad, positive nose-up; 3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pretwist: Option<Property>,
    /// `[beam.section]`.
    pub section: SectionSpec,
}

/// `beam.calibration`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum CalibrationSpec {
    /// The paper's tip-load-matched springs.
    #[default]
    TipLoad,
    /// `EI/ℓ` at every joint.
    Uniform,
    /// The 3-D chain's joint stiffness from the half-element compliances.
    Compliance,
}

word_enum!(CalibrationSpec { TipLoad = "tip-load", Uniform = "uniform", Compliance = "compliance" });

/// `beam.element_inertia`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ElementInertiaSpec {
    /// The paper's point masses at the element midpoints: no rotary inertia in bending.
    #[default]
    PointMass,
    /// Each element a rigid bar with its mass along its length: `m ℓ²/12` about its midpoint.
    Bar,
}

word_enum!(ElementInertiaSpec { PointMass = "point-mass", Bar = "bar" });

fn is_default<T: Default + PartialEq>(v: &T) -> bool {
    *v == T::default()
}

/// `[beam.section]`: section properties, each a number or a table over the span.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SectionSpec {
    /// Bending stiffness (N·m²).
    #[serde(rename = "EI")]
    pub ei: Property,
    /// Mass per length (kg/m).
    pub mass_per_length: Property,
    /// Torsional stiffness (N·m²); its presence switches torsion on.
    #[serde(rename = "GJ", default, skip_serializing_if = "Option::is_none")]
    pub gj: Option<Property>,
    /// Polar mass moment of inertia per length (kg·m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polar_inertia: Option<Property>,
    /// Axis of `polar_inertia`; required with it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub polar_inertia_about: Option<InertiaAxisSpec>,
    /// Chordwise mass-centre offset from the elastic axis (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub d0: Option<Property>,
    /// Rotary (flap) inertia of the section per length about the bending axis (kg·m): the
    /// Rayleigh beam's term.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary_inertia: Option<Property>,
    /// Lag (in-plane) bending stiffness (N·m²; 3-D chain only, required there).
    #[serde(rename = "EI_lag", default, skip_serializing_if = "Option::is_none")]
    pub ei_lag: Option<Property>,
    /// Mass-centre offset along the section normal (m; 3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub d0_normal: Option<Property>,
    /// Rotary (lag) inertia per length about the section normal (kg·m; 3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotary_inertia_lag: Option<Property>,
    /// `[beam.section.coupling]`: off-diagonal section stiffnesses (3-D chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coupling: Option<CouplingSpec>,
}

/// `beam.section.polar_inertia_about`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum InertiaAxisSpec {
    /// About the section's mass centre (`I_cg`).
    MassCentre,
    /// About the elastic axis (`I_ea = I_cg + m d0²`).
    ElasticAxis,
}

word_enum!(InertiaAxisSpec { MassCentre = "mass-centre", ElasticAxis = "elastic-axis" });

/// `[modes]`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct ModesSpec {
    /// Number of modes reported; default `min(10, n_dofs)`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub count: Option<usize>,
}

/// One `[[loads]]` table. Which keys a load takes depends on its `type` (and `direction`); the
/// conversion (`loads.rs`) rejects the keys that do not belong, naming them.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LoadSpec {
    /// Optional unique name, used by `[static.sweep]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// What kind of load.
    #[serde(rename = "type")]
    pub kind: LoadKindSpec,
    /// Position along the undeformed span (m); exclusive with `node`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub span: Option<f64>,
    /// Node index `0 ..= n`; exclusive with `span`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node: Option<usize>,
    /// Dead or follower (point forces and distributed forces).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub direction: Option<DirectionSpec>,
    /// Global spanwise component: N (point force) or N/m (distributed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fx: Option<Property>,
    /// Global vertical component: N (point force) or N/m (distributed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fy: Option<Property>,
    /// Global chordwise component, toward the leading edge: N or N/m (dead forces on the 3-D
    /// chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fz: Option<Property>,
    /// Component along the element axis: N or N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangential: Option<Property>,
    /// Component along the element normal: N or N/m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub normal: Option<Property>,
    /// Moment or torque (N·m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<f64>,
    /// Gravitational acceleration (m/s²).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub g: Option<f64>,
    /// Time history of the load in a dynamic run (default constant).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<TimeSpec>,
    /// Whether the load acts during a dynamic run (default true); an inactive load stays
    /// available for `[dynamic.initial] loads`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub active: Option<bool>,
}

/// `loads[].type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
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

word_enum!(LoadKindSpec { PointForce = "point-force", Moment = "moment", Torque = "torque", Distributed = "distributed", Gravity = "gravity" });

/// `loads[].direction`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DirectionSpec {
    /// Fixed global components `fx`, `fy`.
    Dead,
    /// Components `tangential`, `normal` in the frame of the loaded element.
    Follower,
}

word_enum!(DirectionSpec { Dead = "dead", Follower = "follower" });

/// `[static]`: which models to solve, solver options, loaded modes and the sweep.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct StaticSpec {
    /// Solve the full model.
    #[serde(default = "yes")]
    pub full: bool,
    /// Reduced models on the first `r` modes, one per entry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced: Vec<usize>,
    /// Reduced models on explicit 1-based mode lists.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced_modes: Vec<Vec<usize>>,
    /// `StaticOptions::tolerance`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// `StaticOptions::max_iterations`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_iterations: Option<usize>,
    /// `StaticOptions::min_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_step: Option<f64>,
    /// `StaticOptions::line_search`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub line_search: Option<bool>,
    /// Number of loaded modes reported about the full model's final equilibrium.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// `[static.sweep]`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
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
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SweepSpec {
    /// Name of the swept load.
    pub load: String,
    /// Explicit scale factors; exclusive with `from`/`to`/`steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scales: Option<Vec<f64>>,
    /// First scale of an evenly spaced sweep.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Last scale of an evenly spaced sweep.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<f64>,
    /// Number of points of an evenly spaced sweep, both ends included (≥ 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
}

/// `loads[].time`: the time history `f(t)` that scales a load, `Q(t) = f(t) Q₀`. Which keys it
/// takes depends on `type`; the conversion (`dynamic.rs`) rejects the others, naming them.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TimeSpec {
    /// Which function.
    #[serde(rename = "type")]
    pub kind: TimeKindSpec,
    /// Circular frequency of a sine (rad/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub omega: Option<f64>,
    /// Phase of a sine (rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub phase: Option<f64>,
    /// Switch time of a step (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time: Option<f64>,
    /// Start of a ramp (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// End of a ramp (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub end: Option<f64>,
    /// Times of a table (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub t: Option<Vec<f64>>,
    /// Values of a table (dimensionless factors).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub value: Option<Vec<f64>>,
}

/// `loads[].time.type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum TimeKindSpec {
    /// `f = 1`.
    Constant,
    /// `f = sin(ω t + φ)`.
    Sine,
    /// `f = 0` before `time`, 1 after.
    Step,
    /// `f` rises linearly from 0 at `start` to 1 at `end`.
    Ramp,
    /// Piecewise linear through `(t, value)`.
    Table,
}

word_enum!(TimeKindSpec { Constant = "constant", Sine = "sine", Step = "step", Ramp = "ramp", Table = "table" });

/// `[dynamic]`: time span, output times, models, integrator, damping and `[dynamic.initial]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DynamicSpec {
    /// Simulated time (s), from 0.
    pub end_time: f64,
    /// Evenly spaced output times (s); exclusive with `output_times`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output_step: Option<f64>,
    /// Explicit output times (s); exclusive with `output_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub output_times: Option<Vec<f64>>,
    /// Simulate the full model.
    #[serde(default = "yes")]
    pub full: bool,
    /// Also the full model with the gyroscopic term neglected.
    #[serde(default)]
    pub simplified: bool,
    /// Reduced models on the first `r` modes, one per entry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced: Vec<usize>,
    /// Reduced models on explicit 1-based mode lists.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced_modes: Vec<Vec<usize>>,
    /// How the gyroscopic term of the full and reduced models is obtained.
    #[serde(default)]
    pub gyroscopic: GyroscopicSpec,
    /// Step `h` of the finite-difference gyroscopic term (rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyroscopic_step: Option<f64>,
    /// The time integrator.
    #[serde(default)]
    pub integrator: IntegratorSpec,
    /// Relative tolerance.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rtol: Option<f64>,
    /// Absolute tolerance on the coordinates (rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
    /// Largest BDF order.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_order: Option<usize>,
    /// Fixed step of the implicit midpoint rule or generalized-α (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// Spectral radius `ρ∞` of generalized-α.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectral_radius: Option<f64>,
    /// Budget of integrator steps (accepted and rejected) per model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<usize>,
    /// Largest step of the adaptive integrators (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_step: Option<f64>,
    /// Largest relative energy-balance error before a run is marked suspect.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy_tolerance: Option<f64>,
    /// Relative energy gain at which a run is stopped as a runaway.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub energy_runaway: Option<f64>,
    /// Structural damping; none without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
    /// `[dynamic.initial]`; at rest without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub initial: Option<InitialSpec>,
}

/// `dynamic.gyroscopic`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GyroscopicSpec {
    /// Exact.
    #[default]
    Exact,
    /// Central finite differences with step `gyroscopic_step`.
    FiniteDifference,
    /// Neglected.
    Neglected,
}

word_enum!(GyroscopicSpec { Exact = "exact", FiniteDifference = "finite-difference", Neglected = "neglected" });

/// `dynamic.integrator`: `"auto"` (the library's default method, [`Method::default`]) or the
/// name of a [`Method`] (`"radau"`, `"bdf"`, `"dopri5"`, `"midpoint"`), read through the
/// library's own serde names, so that a new method is a new case-file value.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IntegratorSpec(pub Option<Method>);

impl IntegratorSpec {
    /// The method chosen.
    pub fn method(self) -> Method {
        self.0.unwrap_or_default()
    }
}

impl Serialize for IntegratorSpec {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            None => s.serialize_str("auto"),
            Some(m) => m.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for IntegratorSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::{Error, IntoDeserializer};
        let name = String::deserialize(d)?;
        if name == "auto" {
            return Ok(Self(None));
        }
        let as_method: Result<Method, serde::de::value::Error> =
            Method::deserialize(name.as_str().into_deserializer());
        as_method.map(|m| Self(Some(m))).map_err(|_| {
            let names: Vec<String> = std::iter::once("auto")
                .chain(Method::ALL.iter().map(|m| m.name()))
                .map(|n| format!("`{n}`"))
                .collect();
            D::Error::custom(format!(
                "unknown variant `{name}`, expected one of {}",
                names.join(", ")
            ))
        })
    }
}

/// `dynamic.damping`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct DampingSpec {
    /// Which damping.
    #[serde(rename = "type")]
    pub kind: DampingKindSpec,
    /// Mass-proportional Rayleigh coefficient (1/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alpha: Option<f64>,
    /// Stiffness-proportional Rayleigh coefficient (s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
    /// Modal damping ratios of modes 1, 2, ….
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ratios: Option<Vec<f64>>,
}

/// `dynamic.damping.type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DampingKindSpec {
    /// No damping.
    None,
    /// `C = α M(0) + β K`.
    Rayleigh,
    /// Damping ratios of the modes about the undeformed state.
    Modal,
}

word_enum!(DampingKindSpec { None = "none", Rayleigh = "rayleigh", Modal = "modal" });

/// `[dynamic.initial]`: the state at `t = 0`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct InitialSpec {
    /// Which initial state.
    #[serde(rename = "type")]
    pub kind: InitialKindSpec,
    /// Names of the loads of the initial static solution.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub loads: Option<Vec<String>>,
    /// Joint rotations of the full model (rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub q: Option<Vec<f64>>,
    /// Joint rotation rates of the full model (rad/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub qdot: Option<Vec<f64>>,
}

/// `dynamic.initial.type`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum InitialKindSpec {
    /// Undeformed, at rest.
    Rest,
    /// The static deflection under the listed loads, at rest.
    Static,
    /// Given joint rotations and rates.
    Given,
}

word_enum!(InitialKindSpec { Rest = "rest", Static = "static", Given = "given" });

/// The options of the equations of motion a front end sets at the model level (Python's
/// `model.equations(…)` and `model.stepper(…)`): the keys of `[dynamic]` that make the
/// equations, with the same names, defaults and checks.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct EquationsSpec {
    /// As `dynamic.gyroscopic`.
    #[serde(default)]
    pub gyroscopic: GyroscopicSpec,
    /// As `dynamic.gyroscopic_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gyroscopic_step: Option<f64>,
    /// As `dynamic.damping`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub damping: Option<DampingSpec>,
}

/// The integrator and its options at the model level (Python's `model.stepper(…)`): the keys of
/// `[dynamic]` that choose and tune the integrator, with the same names, defaults and checks.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct IntegrationSpec {
    /// As `dynamic.integrator`.
    #[serde(default)]
    pub integrator: IntegratorSpec,
    /// As `dynamic.rtol`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rtol: Option<f64>,
    /// As `dynamic.atol`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub atol: Option<f64>,
    /// As `dynamic.max_order`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_order: Option<usize>,
    /// As `dynamic.step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub step: Option<f64>,
    /// As `dynamic.spectral_radius`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectral_radius: Option<f64>,
    /// As `dynamic.max_steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_steps: Option<usize>,
    /// As `dynamic.max_step`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_step: Option<f64>,
}

impl DynamicSpec {
    /// The keys of `[dynamic]` that make the equations.
    pub fn equations(&self) -> EquationsSpec {
        EquationsSpec {
            gyroscopic: self.gyroscopic,
            gyroscopic_step: self.gyroscopic_step,
            damping: self.damping.clone(),
        }
    }

    /// The keys of `[dynamic]` that choose and tune the integrator.
    pub fn integration(&self) -> IntegrationSpec {
        IntegrationSpec {
            integrator: self.integrator,
            rtol: self.rtol,
            atol: self.atol,
            max_order: self.max_order,
            step: self.step,
            spectral_radius: self.spectral_radius,
            max_steps: self.max_steps,
            max_step: self.max_step,
        }
    }
}
