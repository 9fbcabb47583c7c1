//! The serde types of the aeroelastic tables: `[aero]` (section data, air, aerodynamic model),
//! `[aero.flight]` (speed, root angle, gravity, their changes in time), `[aero.flight.gust]`,
//! `[aero.sweep]` (speeds) and `[flutter]`. Each key is the name of the library field it fills
//! ([`flexwing::model::aero::AeroSection`], [`flexwing::model::aero::FlightCondition`],
//! [`flexwing::solve::aeroelastic::FlightHistory`], [`flexwing::analysis::aero`]'s plans), so
//! the library's error fields are the case file's keys. Units and defaults: `docs/case-file.md`;
//! the conversion: `aero.rs`.

use serde::{Deserialize, Serialize};

use super::property::Property;
use super::spec::TimeSpec;
use super::words::word_enum;

/// `[aero]`: strip aerodynamics on every element.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct AeroSpec {
    /// Chord `c` (m).
    pub chord: Property,
    /// Elastic-axis position, fraction of the chord from the leading edge.
    pub elastic_axis: Property,
    /// Lift slope `c_lα` (1/rad); default 2π.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lift_slope: Option<Property>,
    /// Zero-lift angle of attack (rad); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub zero_lift_angle: Option<Property>,
    /// Pitching-moment coefficient about the aerodynamic centre; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cm0: Option<Property>,
    /// Drag coefficient; default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cd0: Option<Property>,
    /// Air density (kg/m³).
    pub density: f64,
    /// The aerodynamic model.
    pub aerodynamics: AerodynamicsSpec,
    /// `[aero.flight]`.
    #[serde(default)]
    pub flight: FlightSpec,
    /// `[aero.sweep]`: the speeds of a sweep (static) or of the V-g data (flutter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sweep: Option<SpeedSweepSpec>,
    /// `[[aero.surfaces]]`: trailing-edge control surfaces.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub surfaces: Vec<SurfaceSpec>,
}

/// `[[aero.surfaces]]`: one trailing-edge control surface
/// ([`flexwing::model::aero::ControlSurface`]).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceSpec {
    /// Name of the surface (unique).
    pub name: String,
    /// Inboard end (m from the root).
    pub from: f64,
    /// Outboard end (m from the root).
    pub to: f64,
    /// Hinge line, fraction of the chord from the leading edge (number or table).
    pub hinge: Property,
    /// Deflection of the equilibrium (rad, trailing edge down); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection: Option<f64>,
    /// Change of deflection `Δδ` (rad) in a dynamic run, times `deflection_function`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection_change: Option<f64>,
    /// Time history of the change of deflection.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub deflection_function: Option<TimeSpec>,
}

/// `aero.aerodynamics`: the model and its state count.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct AerodynamicsSpec {
    /// Which model.
    pub model: AeroModelSpec,
    /// Lag states per strip (Peters only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub states: Option<usize>,
}

/// `aero.aerodynamics.model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AeroModelSpec {
    /// Steady strip theory.
    Steady,
    /// Quasi-steady with apparent mass.
    QuasiSteady,
    /// Wagner's function (R. T. Jones), two states per strip.
    Wagner,
    /// Peters' finite-state inflow with `states` states per strip.
    Peters,
}

word_enum!(AeroModelSpec { Steady = "steady", QuasiSteady = "quasi-steady", Wagner = "wagner", Peters = "peters" });

/// `[aero.flight]`: the flight condition and its changes in time.
#[derive(Debug, Clone, Default, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FlightSpec {
    /// Free-stream speed `U` (m/s): the point of a static run without sweep, the initial speed
    /// of a dynamic run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed: Option<f64>,
    /// Root angle of attack (rad); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_angle: Option<f64>,
    /// Gravitational acceleration (m/s²) along the ground's vertical; none without it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gravity: Option<f64>,
    /// Change of speed `ΔU` (m/s) in a dynamic run, times `speed_function`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_change: Option<f64>,
    /// Time history of the change of speed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speed_function: Option<TimeSpec>,
    /// Change of root angle `Δα` (rad) in a dynamic run, times `root_angle_function`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_angle_change: Option<f64>,
    /// Time history of the change of root angle.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub root_angle_function: Option<TimeSpec>,
    /// `[aero.flight.gust]`: a vertical gust in a dynamic run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gust: Option<GustSpec>,
}

/// `[aero.flight.gust]`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GustSpec {
    /// Shape in time.
    pub shape: GustShapeSpec,
    /// Peak vertical velocity (m/s, up).
    pub amplitude: f64,
    /// Time the gust reaches the wing (s); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// Gust length (m) of a 1−cos gust.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub length: Option<f64>,
    /// Spanwise factor (dimensionless, number or table); default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spanwise: Option<Property>,
    /// How the gust front meets each section: `"uniform"` (default: the whole chord at once,
    /// with the gust's apparent mass) or `"kussner"` (Küssner's penetration).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penetration: Option<GustPenetrationSpec>,
}

/// `aero.flight.gust.penetration`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GustPenetrationSpec {
    /// The whole chord at once, every strip at the same time, with the apparent mass.
    Uniform,
    /// Küssner's function, the front convected over the chord and along a swept span.
    Kussner,
}

word_enum!(GustPenetrationSpec { Uniform = "uniform", Kussner = "kussner" });

/// `aero.flight.gust.shape`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GustShapeSpec {
    /// Full amplitude from `start` on.
    SharpEdged,
    /// `½ (1 − cos(2π U t / length))` over one gust length.
    OneMinusCosine,
}

word_enum!(GustShapeSpec { SharpEdged = "sharp-edged", OneMinusCosine = "one-minus-cosine" });

/// `[aero.sweep]`: speeds, listed or evenly spaced.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct SpeedSweepSpec {
    /// Explicit speeds (m/s); exclusive with `from`/`to`/`steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub speeds: Option<Vec<f64>>,
    /// First speed of an evenly spaced sweep (m/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Last speed of an evenly spaced sweep (m/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<f64>,
    /// Number of speeds of an evenly spaced sweep, both ends included (≥ 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
}

/// `[flutter]`: models, branches, tolerance and the p-k check of `flexwing flutter`.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct FlutterSpec {
    /// Analyse the full model.
    #[serde(default = "yes")]
    pub full: bool,
    /// Reduced models on the first `r` wet modes, one per entry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced: Vec<usize>,
    /// Reduced models on explicit 1-based lists of wet modes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced_modes: Vec<Vec<usize>>,
    /// Branches tracked, from the lowest wet modes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub modes: Option<usize>,
    /// Relative tolerance of the flutter and divergence speeds.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    /// Also run the p-k method with Theodorsen's function.
    #[serde(default)]
    pub pk: bool,
    /// `[flutter.study]`: the flutter study against a load level (`flexwing study`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub study: Option<crate::spec_chain3d::StudySpec>,
}

/// `[gust_family]`: the discrete 1−cos gusts of `flexwing gust` (CS 25.341(a)): gust gradient
/// distances `H` listed or evenly spaced, the design velocity `U_ds = U_ref F_g (H/350 ft)^(1/6)`
/// of each ([`flexwing::analysis::aero::gust_family::GustFamilyPlan`]).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GustFamilySpec {
    /// Gust gradient distances `H` (m); exclusive with `from`/`to`/`steps`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lengths: Option<Vec<f64>>,
    /// First `H` of evenly spaced distances (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub from: Option<f64>,
    /// Last `H` of evenly spaced distances (m).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub to: Option<f64>,
    /// Number of evenly spaced distances, both ends included.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<usize>,
    /// `U_ref`, the reference gust velocity (m/s, true air velocity).
    pub reference_velocity: f64,
    /// `F_g`, the flight profile alleviation factor; default 1.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub alleviation: Option<f64>,
    /// Time each gust front reaches the wing (s); default 0.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<f64>,
    /// How each gust front meets the sections, as `aero.flight.gust.penetration`; default
    /// `"uniform"`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penetration: Option<GustPenetrationSpec>,
}

/// `[turbulence]`: the continuous vertical turbulence of `flexwing turbulence`, through the linear
/// model of `[linearize]` ([`flexwing::analysis::aero::turbulence::TurbulencePlan`]).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct TurbulenceSpec {
    /// The gust velocity's spectrum; default von Kármán.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spectrum: Option<SpectrumSpec>,
    /// `σ_w`, the RMS vertical gust velocity (m/s).
    pub intensity: f64,
    /// `L` (m); default the spectrum's handbook value (2500 ft, 1750 ft).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale_length: Option<f64>,
    /// Number of frequencies of the output spectra.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frequencies: Option<usize>,
    /// Lowest frequency (rad/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_frequency: Option<f64>,
    /// Highest frequency (rad/s).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_frequency: Option<f64>,
}

/// `turbulence.spectrum`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpectrumSpec {
    /// von Kármán's.
    VonKarman,
    /// Dryden's.
    Dryden,
}

word_enum!(SpectrumSpec { VonKarman = "von-karman", Dryden = "dryden" });

/// `[linearize]`: the models, signals and states of `flexwing linearize` (the equilibrium's
/// flight condition is `[aero.flight]`).
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct LinearizeSpec {
    /// Linearize the full model.
    #[serde(default = "yes")]
    pub full: bool,
    /// Reduced models on the first `r` wet modes, one per entry.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced: Vec<usize>,
    /// Reduced models on explicit 1-based lists of wet modes.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub reduced_modes: Vec<Vec<usize>>,
    /// The inputs by name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub inputs: Option<Vec<String>>,
    /// The outputs by name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outputs: Option<Vec<String>>,
    /// Velocities or momenta.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub states: Option<StatesSpec>,
}

impl Default for LinearizeSpec {
    fn default() -> Self {
        Self {
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            inputs: None,
            outputs: None,
            states: None,
        }
    }
}

/// `linearize.states`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum StatesSpec {
    /// Coordinates, rates, lag states.
    Velocities,
    /// Coordinates, momenta, lag states.
    Momenta,
}

word_enum!(StatesSpec { Velocities = "velocities", Momenta = "momenta" });

fn yes() -> bool {
    true
}

impl Default for FlutterSpec {
    fn default() -> Self {
        Self {
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            modes: None,
            tolerance: None,
            pk: false,
            study: None,
        }
    }
}
