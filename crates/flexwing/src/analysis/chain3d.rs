//! The analyses of the geometrically exact 3-D chain ([`crate::model::Chain3d`],
//! docs/chain3d-model.md) as one plan of the one dispatcher: natural modes about the undeformed
//! state, non-linear statics with load sweeps and the modes about the last equilibrium, static
//! aeroelastic equilibria at the flight speed or along a sweep in speed with the divergence
//! speed (steady strip aerodynamics on the deformed geometry), flutter
//! and divergence about the deformed equilibria on the 3-D deformed geometry, and the flutter
//! study against a load level ([`crate::solve::aeroelastic::deflection_study`]), and the
//! non-linear dynamics ([`super::dynamics::chain3d`]).
//!
//! Why a plan of its own rather than the planar plans made generic over the structure: the
//! planar plans' fields and outcomes (`FullModel`, the planar `Shape`, reduced models on the
//! planar modes, loaded modes through the O(n) planar tangent) are read by every front end and
//! every other branch; one variant [`crate::analysis::Plan::Chain3d`] with its own outcome adds
//! the 3-D chain to every front end through the same dispatcher, statuses and notes without
//! changing a line they read. The 3-D outcomes carry the 3-D shape (node `x, y, z` and each
//! element's section rotation) and serialize as plain data (feature `serde`), which is what the
//! CLI's JSON and Python's dicts show.

use std::time::Instant;

use super::aero::flutter::{check_solver, check_sweep};
use super::aero::statics::{check_divergence_tolerance, check_flight};
use super::aero::{Aero, Fields, SpeedSweep};
use super::dynamics::chain3d as dynamics;
pub use super::dynamics::chain3d::{Dynamic3d, Dynamic3dOutcome, Dynamic3dRun, Snapshot3d};
use super::statics::Sweep;
use super::{Note, Progress, Status, Stop};
use crate::error::{Error, InputError, SolveError};
use crate::model::aero::{Aeroelastic, FlightCondition};
use crate::model::chain3d::{Chain3d, SpatialLoad};
use crate::model::{AppliedLoads, Load, StructuralModel};
use crate::solve::aeroelastic::{
    deflection_study, flutter_polled, static_sweep_polled, AeroStaticOptions, Crossing,
    DeflectionStudyOptions, Divergence, FlutterMethod, FlutterOptions, StudyParameter,
};
use crate::solve::{sweep_static_until, Damping, Modes, StaticOptions, StaticStats};
use crate::text::short;

/// An analysis of the 3-D chain, validated by [`Chain3dPlan::validate`].
#[derive(Debug, Clone)]
pub struct Chain3dPlan {
    /// The chain (in vacuo).
    pub model: Chain3d,
    /// What is computed.
    pub analysis: Analysis3d,
}

/// What a [`Chain3dPlan`] computes.
#[derive(Debug, Clone)]
#[non_exhaustive]
#[allow(clippy::large_enum_variant)] // one per run
pub enum Analysis3d {
    /// The `count` lowest natural modes about the undeformed state.
    Modes {
        /// Number of modes, `1 ..= 3n`.
        count: usize,
    },
    /// Non-linear statics.
    Static(Static3d),
    /// Static aeroelastic equilibria and the divergence speed.
    AeroStatic(AeroStatic3d),
    /// Flutter and divergence along a sweep in speed.
    Flutter(Flutter3d),
    /// Flutter and divergence against a load level.
    Study(Study3d),
    /// Non-linear dynamics ([`super::dynamics::chain3d`]).
    Dynamic(Dynamic3d),
}

/// Non-linear statics of the 3-D chain.
#[derive(Debug, Clone)]
pub struct Static3d {
    /// The loads, applied together; each at scale 1 except the swept one.
    pub loads: Vec<SpatialLoad>,
    /// Newton's options.
    pub options: StaticOptions,
    /// The sweep of one load's scale; without it, one point with every load at scale 1.
    pub sweep: Option<Sweep>,
    /// Number of modes reported about the last equilibrium.
    pub modes: Option<usize>,
    /// How the caller names each load (a case file: its `name`).
    pub load_names: Vec<String>,
}

/// Static aeroelastic equilibria of the 3-D chain: the fields of the planar
/// [`super::aero::statics::AeroStaticPlan`] that apply to it (no reduced models yet). The
/// aerodynamics are steady whatever the model named: a static equilibrium has no motion to lag.
#[derive(Debug, Clone)]
pub struct AeroStatic3d {
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// The flight: its speed is the one point solved without a sweep; root angle and gravity
    /// hold at every point.
    pub flight: FlightCondition,
    /// A sweep in speed, in place of the flight's speed.
    pub sweep: Option<SpeedSweep>,
    /// Other loads (the planar loads, translated: `SpatialLoad::from_planar`), at every speed.
    pub loads: Vec<Load>,
    /// Newton's options.
    pub options: StaticOptions,
    /// Relative tolerance of the divergence dynamic pressure, in `(0, 1)`.
    pub divergence_tolerance: f64,
}

impl AeroStatic3d {
    /// The speeds solved: the sweep's, or the flight's speed.
    pub fn speeds(&self) -> Vec<f64> {
        self.sweep
            .as_ref()
            .map_or_else(|| vec![self.flight.speed], |s| s.speeds.clone())
    }

    fn validate(&self, model: &Chain3d, fields: &Fields) -> Result<(), InputError> {
        Aeroelastic::spatial(
            model,
            &self.aero.section,
            self.aero.density,
            self.aero.aerodynamics,
            fields.aero,
        )?;
        check_flight(&self.flight, self.sweep.as_ref(), fields)?;
        model.apply_planar(&self.loads, fields.loads)?;
        self.options.validate(fields.statics)?;
        check_divergence_tolerance(self.divergence_tolerance, fields)
    }
}

/// Flutter of the 3-D chain: the fields of the planar [`super::aero::flutter::FlutterPlan`]
/// that apply to it (no reduced models yet).
#[derive(Debug, Clone)]
pub struct Flutter3d {
    /// Section data, air, aerodynamic model.
    pub aero: Aero,
    /// Root angle and gravity (its speed is not used).
    pub flight: FlightCondition,
    /// The speeds of the V-g data (positive, increasing).
    pub sweep: Option<SpeedSweep>,
    /// Other loads (the planar loads, translated: `SpatialLoad::from_planar`), at every speed.
    pub loads: Vec<Load>,
    /// Number of branches tracked; `None`: `min(6, 3n)`.
    pub modes: Option<usize>,
    /// Relative tolerance of the flutter and divergence speeds, in `(0, 1)`.
    pub tolerance: f64,
    /// Also run the p-k method with Theodorsen's function.
    pub pk: bool,
    /// Options of the static solver for the equilibria.
    pub static_options: StaticOptions,
}

/// The flutter study against a load level: the flutter analysis `flutter` at every level.
#[derive(Debug, Clone)]
pub struct Study3d {
    /// The flutter analysis run at every level.
    pub flutter: Flutter3d,
    /// The load swept.
    pub parameter: StudyParameter,
    /// Its levels (N, a factor of `g`, or rad).
    pub levels: Vec<f64>,
    /// Also the divergence speed at every level.
    pub divergence: bool,
}

impl Chain3dPlan {
    /// `modes`, `static`, `aero-static`, `flutter`, `study` or `dynamic`.
    pub fn name(&self) -> &'static str {
        match self.analysis {
            Analysis3d::Modes { .. } => "modes",
            Analysis3d::Static(_) => "static",
            Analysis3d::AeroStatic(_) => "aero-static",
            Analysis3d::Flutter(_) => "flutter",
            Analysis3d::Study(_) => "study",
            Analysis3d::Dynamic(_) => "dynamic",
        }
    }

    /// Check the plan under the caller's names (a case file: `Fields { loads: "loads", aero:
    /// "aero", statics: "static", analysis: "flutter" }`, and `modes.count` for the modes).
    ///
    /// # Errors
    /// A number of modes outside `1 ..= 3n`, a load the chain cannot carry, options out of
    /// range, invalid section data, speeds, tolerance, levels.
    pub fn validate(&self, fields: &Fields) -> Result<(), InputError> {
        let n_dofs = self.model.n_dofs();
        let count_ok = |count: usize, field: String| {
            if (1..=n_dofs).contains(&count) {
                Ok(())
            } else {
                Err(InputError::new(
                    field,
                    format!(
                        "must be between 1 and the number of degrees of freedom ({n_dofs}), \
                         got {count}"
                    ),
                ))
            }
        };
        match &self.analysis {
            Analysis3d::Modes { count } => count_ok(*count, fields.analysis("count")),
            Analysis3d::Static(s) => {
                if s.loads.is_empty() {
                    return Err(InputError::new(
                        fields.loads,
                        "a static analysis needs at least one load",
                    ));
                }
                self.model.apply(&s.loads, fields.loads)?;
                if let Some(count) = s.modes {
                    count_ok(count, fields.analysis("modes"))?;
                }
                if let Some(sweep) = &s.sweep {
                    if sweep.load >= s.loads.len() {
                        return Err(InputError::new(
                            fields.analysis("sweep.load"),
                            format!("there is no load {} (of {})", sweep.load, s.loads.len()),
                        ));
                    }
                    if sweep.scales.is_empty() {
                        return Err(InputError::new(
                            fields.analysis("sweep.scales"),
                            "must not be empty",
                        ));
                    }
                    for (i, &v) in sweep.scales.iter().enumerate() {
                        let f = fields.analysis(&format!("sweep.scales[{i}]"));
                        if !v.is_finite() {
                            return Err(InputError::new(
                                f,
                                format!("must be finite, got {}", short(v)),
                            ));
                        }
                        crate::magnitude::check(&f, "", v)?;
                    }
                }
                s.options.validate(fields.analysis)
            }
            Analysis3d::AeroStatic(a) => a.validate(&self.model, fields),
            Analysis3d::Flutter(f) => f.validate(&self.model, fields).map(|_| ()),
            Analysis3d::Dynamic(d) => d.validate(&self.model, fields.loads, fields.analysis),
            Analysis3d::Study(s) => {
                let wing = s.flutter.validate(&self.model, fields)?;
                let field = fields.analysis("study");
                s.options().validate(&field, n_dofs, wing.chain().length())
            }
        }
    }
}

impl Flutter3d {
    /// The wing, after checking the analysis; errors as [`super::aero::flutter::FlutterPlan`]'s.
    fn validate(
        &self,
        model: &Chain3d,
        fields: &Fields,
    ) -> Result<Aeroelastic<Chain3d>, InputError> {
        let wing = self.wing(model, fields.aero)?;
        check_sweep(self.sweep.as_ref(), &self.flight, fields)?;
        model.apply_planar(&self.loads, fields.loads)?;
        check_solver(
            &self.static_options,
            self.tolerance,
            self.pk,
            &self.aero,
            fields,
        )?;
        let n = model.n_dofs();
        if let Some(count) = self.modes {
            if !(1..=n).contains(&count) {
                return Err(InputError::new(
                    fields.analysis("modes"),
                    format!(
                        "must be between 1 and {n} (the coordinates of the model), got {count}"
                    ),
                ));
            }
        }
        Ok(wing)
    }

    /// The aeroelastic 3-D chain.
    fn wing(&self, model: &Chain3d, prefix: &str) -> Result<Aeroelastic<Chain3d>, InputError> {
        Aeroelastic::spatial(
            model,
            &self.aero.section,
            self.aero.density,
            self.aero.aerodynamics,
            prefix,
        )
    }

    fn speeds(&self) -> Vec<f64> {
        self.sweep.as_ref().map_or(Vec::new(), |s| s.speeds.clone())
    }

    /// The solver's options with `method`.
    fn solver(&self, dofs: usize, method: FlutterMethod) -> FlutterOptions {
        FlutterOptions {
            speeds: self.speeds(),
            root_angle: self.flight.root_angle,
            gravity: self.flight.gravity,
            loads: self.loads.clone(),
            damping: Damping::None,
            modes: self
                .modes
                .unwrap_or(super::aero::flutter::DEFAULT_MODES.min(dofs)),
            tolerance: self.tolerance,
            static_options: self.static_options.clone(),
            method,
        }
    }
}

impl Study3d {
    fn options(&self) -> DeflectionStudyOptions {
        // The study's own flutter analysis has no model: the number of branches is that of a
        // chain of at least two elements when not given (checked against the model in run).
        let method = if self.flutter.pk {
            FlutterMethod::PkTheodorsen
        } else {
            FlutterMethod::Eigenvalues
        };
        let dofs = self
            .flutter
            .modes
            .unwrap_or(super::aero::flutter::DEFAULT_MODES);
        let mut o = DeflectionStudyOptions::new(
            self.flutter.solver(dofs, method),
            self.parameter,
            self.levels.clone(),
        );
        o.divergence = self.divergence;
        o
    }
}

/// A vector with its zeros unsigned.
fn unsigned3(v: [f64; 3]) -> [f64; 3] {
    v.map(|x| x + 0.0)
}

/// The deformed 3-D chain as reported: node stations, positions and each element's section
/// rotation vector (`R_i = exp(r̂_i)`, from the global axes to `(t, n, c)`).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Shape3dData {
    /// Node stations along the reference axis (m).
    pub span: Vec<f64>,
    /// Node positions `(x, y, z)` (m).
    pub position: Vec<[f64; 3]>,
    /// Section rotation vector of each element (rad, global components).
    pub rotation: Vec<[f64; 3]>,
}

impl Shape3dData {
    pub(crate) fn of(model: &Chain3d, q: &[f64]) -> Self {
        let shape = model.shape(q);
        Self {
            rotation: shape
                .rotation_vectors()
                .into_iter()
                .map(unsigned3)
                .collect(),
            span: shape.span,
            position: shape.position,
        }
    }

    /// Tip position `(x, y, z)` (m).
    pub fn tip(&self) -> [f64; 3] {
        self.position.last().copied().unwrap_or([0.0; 3])
    }
}

/// A natural mode of the 3-D chain.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Mode3d {
    /// Mode number, 1-based.
    pub mode: usize,
    /// Circular frequency (rad/s).
    pub omega: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Share of the strain energy `φᵀKφ` in the joints' twist, flap and lag coordinates
    /// (`Σ_{i ∈ axis} φ_i (Kφ)_i / φᵀKφ`: they sum to 1; with bend–twist coupling a share
    /// may be slightly negative).
    pub energy_fraction: EnergyFraction,
    /// Node displacements of the mass-normalized mode, `∂P_k/∂x φ` (m per unit modal amplitude).
    pub displacement: Vec<[f64; 3]>,
    /// Each element's small rotation `∂θ_i/∂x φ` (rad, global components).
    pub rotation: Vec<[f64; 3]>,
}

/// Strain-energy shares of a mode by joint axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EnergyFraction {
    /// Twist (about `t`).
    pub twist: f64,
    /// Lag (in-plane bending, about `n`).
    pub lag: f64,
    /// Flap (out-of-plane bending, about `c`).
    pub flap: f64,
}

/// The modes of `model` about `x` with `loads` at `scales`.
fn modes_about(
    model: &Chain3d,
    x: &[f64],
    loads: &AppliedLoads,
    scales: &[f64],
    count: usize,
) -> Result<Vec<Mode3d>, SolveError> {
    let modes = Modes::of_model(model, x, loads, scales, count)?;
    let k = model.stiffness_matrix();
    let nodes = model.beam().nodes().to_vec();
    let n = model.n_elements();
    let rotation_jacobians: Vec<_> = (0..n)
        .map(|i| model.angular_velocity_jacobian(x, i))
        .collect();
    let node_jacobians: Vec<_> = nodes.iter().map(|&s| model.point_jacobian(x, s)).collect();
    Ok((0..count.min(modes.n_modes()))
        .map(|j| {
            let phi = modes.shapes().column(j).into_owned();
            let kphi = &k * &phi;
            let mut e = [0.0; 3];
            for i in 0..phi.len() {
                e[i % 3] += phi[i] * kphi[i];
            }
            let total: f64 = e.iter().sum();
            let share = |v: f64| if total > 0.0 { v / total + 0.0 } else { 0.0 };
            let v3 = |m: &nalgebra::DMatrix<f64>| {
                let v = m * &phi;
                unsigned3([v[0], v[1], v[2]])
            };
            let omega = modes.omega()[j];
            Mode3d {
                mode: j + 1,
                omega,
                frequency_hz: omega / (2.0 * std::f64::consts::PI),
                energy_fraction: EnergyFraction {
                    twist: share(e[0]),
                    lag: share(e[1]),
                    flap: share(e[2]),
                },
                displacement: node_jacobians.iter().map(v3).collect(),
                rotation: rotation_jacobians.iter().map(v3).collect(),
            }
        })
        .collect())
}

/// One equilibrium of the 3-D chain.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Static3dPoint {
    /// Scale of the swept load (1 without a sweep).
    pub scale: f64,
    /// Scales of all loads.
    pub scales: Vec<f64>,
    /// The deformed shape.
    pub shape: Shape3dData,
    /// Joint rotations (twist, lag, flap per joint, rad).
    pub q: Vec<f64>,
    /// Whether the equilibrium is stable (`None`: follower loads, statics cannot tell).
    pub stable: Option<bool>,
    /// Solver counters.
    pub stats: StaticStats,
}

/// What a static analysis of the 3-D chain found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Static3dOutcome {
    /// Number of coordinates.
    pub dofs: usize,
    /// Wall time of the solve (s).
    pub wall_time_s: f64,
    /// The converged points in sweep order.
    pub points: Vec<Static3dPoint>,
    /// Whether every point converged, or where and why the sweep stopped.
    pub status: Status,
    /// The modes about the last equilibrium, if asked and reached.
    pub loaded_modes: Option<Vec<Mode3d>>,
    /// Why the modes about the last equilibrium were not found.
    pub loaded_modes_status: Status,
}

/// One static aeroelastic equilibrium of the 3-D chain.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Equilibrium3d {
    /// Free-stream speed (m/s).
    pub speed: f64,
    /// Dynamic pressure (Pa).
    pub dynamic_pressure: f64,
    /// Tip displacement of the elastic axis `(dx, dy, dz)` (m).
    pub tip: [f64; 3],
    /// Tip twist (rad, nose-up).
    pub tip_twist: f64,
    /// Total aerodynamic force along the vertical (N).
    pub lift: f64,
    /// Each strip's aerodynamic force along the vertical (N), root to tip (the strips' stations
    /// and widths: [`AeroStatic3dOutcome::strip_span`], one strip per element).
    pub strip_lift: Vec<f64>,
    /// Divergence pressure of the frozen state (Pa).
    pub divergence_pressure: Option<f64>,
    /// The deformed shape.
    pub shape: Shape3dData,
}

/// What a static aeroelastic analysis of the 3-D chain found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct AeroStatic3dOutcome {
    /// Number of coordinates.
    pub dofs: usize,
    /// Span station of each strip's midpoint along the reference axis (m).
    pub strip_span: Vec<f64>,
    /// The equilibria, one per speed reached.
    pub equilibria: Vec<Equilibrium3d>,
    /// The divergence speed, where the sweep finds it (bracketed between two speeds, or past
    /// the last stable one; see [`crate::solve::aeroelastic::AeroStaticSolution::divergence`]).
    pub divergence: Option<SpeedPoint>,
    /// Whether every speed was reached, or where and why the sweep stopped (past the
    /// divergence speed it does).
    pub status: Status,
    /// Wall time of the analysis (s).
    pub wall_time_s: f64,
}

/// A flutter or divergence point.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SpeedPoint {
    /// Speed (m/s).
    pub speed: f64,
    /// Frequency (rad/s), 0 for divergence.
    pub frequency: f64,
}

impl SpeedPoint {
    fn of(c: &Crossing) -> Self {
        Self {
            speed: c.speed,
            frequency: c.frequency,
        }
    }
}

/// One tracked branch.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Branch3d {
    /// The wet mode it starts from, 1-based.
    pub mode: usize,
    /// Its wet frequency at `U = 0` (rad/s).
    pub wet_frequency: f64,
    /// `σ = Re s` at each speed (1/s).
    pub real: Vec<f64>,
    /// `ω = Im s` at each speed (rad/s).
    pub imag: Vec<f64>,
}

/// The eigen-analysis along the speeds (the model's own lag, or the p-k method).
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Stability3d {
    /// `eigenvalues` or `pk-theodorsen`.
    pub method: &'static str,
    /// The speeds reached (m/s).
    pub speeds: Vec<f64>,
    /// The tracked branches.
    pub branches: Vec<Branch3d>,
    /// The flutter point (lowest onset), if any.
    pub flutter: Option<SpeedPoint>,
    /// Branches (1-based modes) unstable from the first speed.
    pub unstable_at_start: Vec<usize>,
    /// Whether it reached the last speed.
    pub status: Status,
    /// Wall time (s).
    pub wall_time_s: f64,
}

/// What a flutter analysis of the 3-D chain found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Flutter3dOutcome {
    /// Number of coordinates.
    pub dofs: usize,
    /// The static equilibria along the speeds.
    pub equilibria: Vec<Equilibrium3d>,
    /// The static divergence speed.
    pub divergence: Option<SpeedPoint>,
    /// Whether the equilibria reached the last speed (past divergence they stop).
    pub equilibria_status: Status,
    /// The eigen-analysis with the model's own lag.
    pub stability: Stability3d,
    /// The p-k check, when asked.
    pub pk: Option<Stability3d>,
    /// Wall time of the whole analysis (s).
    pub wall_time_s: f64,
    /// Notes (equilibria that stopped, branches unstable from the start).
    pub notes: Vec<Note>,
}

/// One level of the study.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct StudyPoint {
    /// The level of the swept load.
    pub level: f64,
    /// Tip displacement at rest (m).
    pub tip: [f64; 3],
    /// Tip twist at rest (rad).
    pub tip_twist: f64,
    /// Tip displacement at the flutter speed (m).
    pub tip_at_flutter: Option<[f64; 3]>,
    /// The flutter point.
    pub flutter: Option<SpeedPoint>,
    /// The divergence speed.
    pub divergence: Option<SpeedPoint>,
    /// Whether the level's flutter analysis reached its last speed.
    pub status: Status,
}

/// What the flutter study against a load level found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Study3dOutcome {
    /// `tip-force`, `gravity-factor` or `root-angle`.
    pub parameter: &'static str,
    /// One point per level reached.
    pub points: Vec<StudyPoint>,
    /// The flutter point of the undeformed wing (no load, no gravity, no root angle): what the
    /// planar model gives at every level (it ignores the deflection).
    pub undeformed: Option<SpeedPoint>,
    /// Whether every level completed (an interruption stops the study).
    pub status: Status,
    /// Wall time (s).
    pub wall_time_s: f64,
}

/// What an analysis of the 3-D chain found.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[cfg_attr(feature = "serde", serde(tag = "analysis", rename_all = "kebab-case"))]
#[allow(clippy::large_enum_variant)] // one per run
pub enum Chain3dOutcome {
    /// Natural modes.
    Modes {
        /// The modes, by increasing frequency.
        modes: Vec<Mode3d>,
        /// The undeformed shape.
        shape: Shape3dData,
    },
    /// Statics.
    Static(Static3dOutcome),
    /// Static aeroelastic equilibria.
    AeroStatic(AeroStatic3dOutcome),
    /// Flutter.
    Flutter(Flutter3dOutcome),
    /// The study against a load level.
    Study(Study3dOutcome),
    /// Dynamics.
    Dynamic(Dynamic3dOutcome),
}

impl Chain3dOutcome {
    /// How the run ended, with the label `full` (the one model it runs), and for flutter the
    /// p-k check as `full p-k`.
    pub fn entries(&self) -> Vec<(String, Status)> {
        match self {
            Chain3dOutcome::Modes { .. } => Vec::new(),
            Chain3dOutcome::Static(o) => {
                let mut v = vec![("full".to_string(), o.status.clone())];
                if !o.loaded_modes_status.is_complete() {
                    v.push(("loaded modes".into(), o.loaded_modes_status.clone()));
                }
                v
            }
            Chain3dOutcome::AeroStatic(o) => vec![("full".to_string(), o.status.clone())],
            Chain3dOutcome::Flutter(o) => {
                let mut v = vec![("full".to_string(), o.stability.status.clone())];
                if let Some(pk) = &o.pk {
                    v.push(("full p-k".into(), pk.status.clone()));
                }
                v
            }
            Chain3dOutcome::Study(o) => vec![("full".to_string(), o.status.clone())],
            Chain3dOutcome::Dynamic(o) => o
                .runs
                .iter()
                .map(|r| (r.label.clone(), r.status.clone()))
                .collect(),
        }
    }

    /// The notes of the run.
    pub fn notes(&self) -> Vec<&Note> {
        match self {
            Chain3dOutcome::Flutter(o) => o.notes.iter().collect(),
            Chain3dOutcome::Dynamic(o) => o.runs.iter().flat_map(|r| &r.notes).collect(),
            _ => Vec::new(),
        }
    }
}

/// Run the analysis of `plan`.
///
/// # Errors
/// An invalid plan (fields named relative to the plan, [`Fields::RELATIVE`]); the eigensolver's
/// failure for modes. Failures of a sweep are in the outcome's statuses.
pub fn run(plan: &Chain3dPlan, progress: &mut dyn Progress) -> Result<Chain3dOutcome, Error> {
    plan.validate(&Fields::RELATIVE)?;
    let model = &plan.model;
    Ok(match &plan.analysis {
        Analysis3d::Modes { count } => {
            progress.start(0, 1, "modes");
            let x0 = vec![0.0; model.n_dofs()];
            let modes = modes_about(model, &x0, &AppliedLoads::none(), &[], *count);
            progress.finish();
            Chain3dOutcome::Modes {
                modes: modes?,
                shape: Shape3dData::of(model, &x0),
            }
        }
        Analysis3d::Static(s) => Chain3dOutcome::Static(statics(model, s, progress)?),
        Analysis3d::AeroStatic(a) => Chain3dOutcome::AeroStatic(aero_statics(model, a, progress)?),
        Analysis3d::Flutter(f) => Chain3dOutcome::Flutter(flutter(model, f, progress)?),
        Analysis3d::Study(s) => Chain3dOutcome::Study(study(model, s, progress)?),
        Analysis3d::Dynamic(d) => Chain3dOutcome::Dynamic(dynamics::run(model, d, progress)?),
    })
}

fn points_of(s: &Static3d) -> (Vec<Vec<f64>>, Vec<f64>) {
    let n = s.loads.len();
    match &s.sweep {
        None => (vec![vec![1.0; n]], vec![1.0]),
        Some(sw) => (
            sw.scales
                .iter()
                .map(|&v| {
                    let mut p = vec![1.0; n];
                    p[sw.load] = v;
                    p
                })
                .collect(),
            sw.scales.clone(),
        ),
    }
}

fn statics(
    model: &Chain3d,
    s: &Static3d,
    progress: &mut dyn Progress,
) -> Result<Static3dOutcome, Error> {
    let applied = model.apply(&s.loads, "loads")?;
    let (points, scales) = points_of(s);
    progress.start(0, 1, "full");
    let start = Instant::now();
    let result = sweep_static_until(model, &applied, &points, &s.options, &mut || {
        progress.cancelled()
    });
    let wall_time_s = start.elapsed().as_secs_f64();
    progress.advance(1.0);
    progress.finish();
    let swept = s
        .sweep
        .as_ref()
        .map(|sw| super::load_name(&s.load_names, sw.load));
    let (solutions, status) = match result {
        Ok(sol) if sol.len() < points.len() => {
            let stop = Stop::SweepInterrupted {
                done: sol.len(),
                points: points.len(),
            };
            (sol, Status::Stopped(stop))
        }
        Ok(sol) => (sol, Status::Complete),
        Err(e) => {
            let scale = scales[e.point];
            let reached = match &e.error {
                SolveError::StaticDiverged { load_factor, .. } => {
                    let previous = e.point.checked_sub(1).map_or(0.0, |p| scales[p]);
                    Some(previous + load_factor * (scale - previous))
                }
                _ => None,
            };
            let stop = Stop::StaticPoint {
                point: e.point,
                points: points.len(),
                scale,
                reached,
                load: swept,
                error: e.error,
            };
            (e.completed, Status::Stopped(stop))
        }
    };
    let points: Vec<Static3dPoint> = solutions
        .iter()
        .zip(&scales)
        .map(|(sol, &scale)| Static3dPoint {
            scale,
            scales: sol.scales.clone(),
            shape: Shape3dData::of(model, &sol.q),
            q: sol.q.clone(),
            stable: sol.stable,
            stats: sol.stats,
        })
        .collect();
    let (loaded_modes, loaded_modes_status) = match (s.modes, points.last()) {
        (Some(count), Some(last)) if status.is_complete() => {
            match modes_about(model, &last.q, &applied, &last.scales, count) {
                Ok(m) => (Some(m), Status::Complete),
                Err(e) => (None, Status::Stopped(Stop::LoadedModes(e))),
            }
        }
        _ => (None, Status::Complete),
    };
    Ok(Static3dOutcome {
        dofs: model.n_dofs(),
        wall_time_s,
        points,
        status,
        loaded_modes,
        loaded_modes_status,
    })
}

/// The eigen-analysis `out` as reported.
fn stability(
    out: crate::solve::aeroelastic::FlutterSolution,
    method: FlutterMethod,
    wall_time_s: f64,
    points: usize,
) -> Stability3d {
    let done = out.speeds.len();
    let status = out.stopped.map_or(Status::Complete, |s| {
        Status::Stopped(Stop::of_flutter(s, done, points))
    });
    Stability3d {
        method: match method {
            FlutterMethod::Eigenvalues => "eigenvalues",
            FlutterMethod::PkTheodorsen => "pk-theodorsen",
        },
        speeds: out.speeds,
        branches: out
            .branches
            .iter()
            .map(|b| Branch3d {
                mode: b.mode + 1,
                wet_frequency: b.wet_frequency,
                real: b.eigenvalues.iter().map(|s| s.re).collect(),
                imag: b.eigenvalues.iter().map(|s| s.im).collect(),
            })
            .collect(),
        flutter: out.flutter.as_ref().map(SpeedPoint::of),
        unstable_at_start: out
            .unstable_at_start
            .iter()
            .map(|&b| out.branches[b].mode + 1)
            .collect(),
        status,
        wall_time_s,
    }
}

fn flutter(
    model: &Chain3d,
    f: &Flutter3d,
    progress: &mut dyn Progress,
) -> Result<Flutter3dOutcome, Error> {
    let start = Instant::now();
    let wing = f.wing(model, "aero")?;
    let dofs = model.n_dofs();
    let speeds = f.speeds();
    let parts = if f.pk { 3.0 } else { 2.0 };
    progress.start(0, 1, "full");
    let statics = AeroStaticOptions {
        speeds: speeds.clone(),
        root_angle: f.flight.root_angle,
        gravity: f.flight.gravity,
        loads: f.loads.clone(),
        options: f.static_options.clone(),
        divergence_tolerance: f.tolerance,
    };
    let (equilibria, divergence, equilibria_status) =
        sweep_equilibria(model, &wing, &statics, &mut |x| {
            progress.advance(x / parts);
            !progress.cancelled()
        })?;
    let eig = |method: FlutterMethod, k: f64, progress: &mut dyn Progress| {
        let t = Instant::now();
        let out = flutter_polled(&wing, &f.solver(dofs, method), "", &mut |x| {
            progress.advance((k + x) / parts);
            !progress.cancelled()
        })?;
        Ok::<_, InputError>(stability(
            out,
            method,
            t.elapsed().as_secs_f64(),
            speeds.len(),
        ))
    };
    let main = eig(FlutterMethod::Eigenvalues, 1.0, progress)?;
    let pk = if f.pk {
        Some(eig(FlutterMethod::PkTheodorsen, 2.0, progress)?)
    } else {
        None
    };
    progress.finish();
    let mut notes: Vec<Note> = equilibria_status
        .stop()
        .map(|stop| Note::EquilibriaStopped { stop: stop.clone() })
        .into_iter()
        .collect();
    let first = speeds.first().copied().unwrap_or(0.0);
    for (is_pk, s) in std::iter::once((false, &main)).chain(pk.as_ref().map(|p| (true, p))) {
        for &mode in &s.unstable_at_start {
            let wet = s
                .branches
                .iter()
                .find(|b| b.mode == mode)
                .map_or(f64::NAN, |b| b.wet_frequency);
            notes.push(Note::UnstableAtStart {
                pk: is_pk,
                mode,
                wet_frequency: wet,
                speed: first,
            });
        }
    }
    Ok(Flutter3dOutcome {
        dofs,
        equilibria,
        divergence,
        equilibria_status,
        stability: main,
        pk,
        wall_time_s: start.elapsed().as_secs_f64(),
        notes,
    })
}

/// The static aeroelastic sweep `statics` of `wing` as reported: the equilibria with their 3-D
/// shapes, the divergence point, and how the sweep ended (flutter's equilibria and the static
/// aeroelastic run share it). `step` hears the fraction done and stops the sweep with `false`.
fn sweep_equilibria(
    model: &Chain3d,
    wing: &Aeroelastic<Chain3d>,
    statics: &AeroStaticOptions,
    step: &mut dyn FnMut(f64) -> bool,
) -> Result<(Vec<Equilibrium3d>, Option<SpeedPoint>, Status), InputError> {
    let eq = static_sweep_polled(wing, statics, "", step)?;
    let speeds = &statics.speeds;
    let equilibria: Vec<Equilibrium3d> = eq
        .points
        .iter()
        .map(|p| Equilibrium3d {
            speed: p.speed,
            dynamic_pressure: p.dynamic_pressure,
            tip: unsigned3(p.tip),
            tip_twist: p.tip_twist + 0.0,
            lift: p.lift,
            strip_lift: p.strip_lift.clone(),
            divergence_pressure: p.divergence_pressure,
            shape: Shape3dData::of(model, &p.q),
        })
        .collect();
    let status = match eq.stopped {
        None if eq.interrupted => Status::Stopped(Stop::SweepInterrupted {
            done: equilibria.len(),
            points: speeds.len(),
        }),
        None => Status::Complete,
        Some((point, error)) => Status::Stopped(Stop::SpeedPoint {
            point,
            points: speeds.len(),
            speed: speeds[point],
            error,
        }),
    };
    Ok((
        equilibria,
        eq.divergence.as_ref().map(divergence_point),
        status,
    ))
}

fn aero_statics(
    model: &Chain3d,
    a: &AeroStatic3d,
    progress: &mut dyn Progress,
) -> Result<AeroStatic3dOutcome, Error> {
    let start = Instant::now();
    let wing = Aeroelastic::spatial(
        model,
        &a.aero.section,
        a.aero.density,
        a.aero.aerodynamics,
        "aero",
    )?;
    let statics = AeroStaticOptions {
        speeds: a.speeds(),
        root_angle: a.flight.root_angle,
        gravity: a.flight.gravity,
        loads: a.loads.clone(),
        options: a.options.clone(),
        divergence_tolerance: a.divergence_tolerance,
    };
    progress.start(0, 1, "full");
    let (equilibria, divergence, status) = sweep_equilibria(model, &wing, &statics, &mut |x| {
        progress.advance(x);
        !progress.cancelled()
    })?;
    progress.finish();
    Ok(AeroStatic3dOutcome {
        dofs: model.n_dofs(),
        strip_span: wing.strips.iter().map(|s| s.station).collect(),
        equilibria,
        divergence,
        status,
        wall_time_s: start.elapsed().as_secs_f64(),
    })
}

fn divergence_point(d: &Divergence) -> SpeedPoint {
    SpeedPoint {
        speed: d.speed,
        frequency: 0.0,
    }
}

fn study(
    model: &Chain3d,
    s: &Study3d,
    progress: &mut dyn Progress,
) -> Result<Study3dOutcome, Error> {
    let start = Instant::now();
    let wing = s.flutter.wing(model, "aero")?;
    let mut options = s.options();
    options.flutter.modes = s
        .flutter
        .modes
        .unwrap_or(super::aero::flutter::DEFAULT_MODES.min(model.n_dofs()));
    progress.start(0, 1, "full");
    // The undeformed wing: the planar model's value at every level. A level 0 without other
    // loads, gravity or root angle is that wing: its flutter point is taken, not run twice.
    let bare = options.flutter.loads.is_empty()
        && options.flutter.gravity.is_none_or(|g| g == 0.0)
        && options.flutter.root_angle == 0.0;
    let zero_level = bare && s.levels.contains(&0.0);
    let share = if zero_level {
        0.0
    } else {
        1.0 / (s.levels.len() as f64 + 1.0)
    };
    let out = deflection_study(&wing, &options, "study", &mut |x| {
        progress.advance(share + (1.0 - share) * x);
        !progress.cancelled()
    })?;
    let undeformed = match out.points.iter().find(|p| p.level == 0.0) {
        Some(p) if zero_level => p.flutter.flutter.as_ref().map(SpeedPoint::of),
        _ if out.interrupted => None,
        _ => {
            let mut plan = options.flutter.clone();
            plan.loads.clear();
            plan.gravity = None;
            plan.root_angle = 0.0;
            flutter_polled(&wing, &plan, "study", &mut |_| !progress.cancelled())?
                .flutter
                .as_ref()
                .map(SpeedPoint::of)
        }
    };
    progress.finish();
    let points = out.points.len();
    let status = if out.interrupted {
        Status::Stopped(Stop::SweepInterrupted {
            done: points,
            points: s.levels.len(),
        })
    } else {
        Status::Complete
    };
    let speeds = options.flutter.speeds.len();
    Ok(Study3dOutcome {
        parameter: match s.parameter {
            StudyParameter::TipForce => "tip-force",
            StudyParameter::GravityFactor { .. } => "gravity-factor",
            StudyParameter::RootAngle => "root-angle",
        },
        points: out
            .points
            .iter()
            .map(|p| StudyPoint {
                level: p.level,
                tip: unsigned3(p.tip),
                tip_twist: p.tip_twist + 0.0,
                tip_at_flutter: p.tip_at_flutter.map(unsigned3),
                flutter: p.flutter.flutter.as_ref().map(SpeedPoint::of),
                divergence: p.divergence.as_ref().map(divergence_point),
                status: p.flutter.stopped.clone().map_or(Status::Complete, |st| {
                    Status::Stopped(Stop::of_flutter(st, p.flutter.speeds.len(), speeds))
                }),
            })
            .collect(),
        undeformed,
        status,
        wall_time_s: start.elapsed().as_secs_f64(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::Profile;
    use crate::model::aero::{AeroSection, Aerodynamics};
    use crate::model::chain3d::{Beam3d, Geometry3d, JointCalibration, SectionInertia};
    use crate::model::chain3d::{SectionStiffness, SpatialVector};

    fn chain() -> Chain3d {
        Chain3d::new(
            Beam3d::new(
                &Geometry3d::straight(1.0, 4),
                &SectionStiffness::uncoupled(8.0, 10.0, 60.0),
                &SectionInertia::uniform(0.5, 0.004),
                JointCalibration::Compliance,
            )
            .unwrap(),
        )
    }

    fn flutter3d(aerodynamics: Aerodynamics) -> Flutter3d {
        Flutter3d {
            aero: Aero {
                section: AeroSection::new(Profile::Uniform(0.1), Profile::Uniform(0.5)),
                density: 1.2,
                aerodynamics,
            },
            flight: FlightCondition::at_speed(0.0),
            sweep: Some(SpeedSweep {
                speeds: vec![1.0, 2.0],
            }),
            loads: Vec::new(),
            modes: None,
            tolerance: 1e-6,
            pk: false,
            static_options: StaticOptions::default(),
        }
    }

    #[test]
    fn errors_name_the_callers_fields() {
        let fields = crate::analysis::aero::Fields {
            loads: "loads",
            aero: "aero",
            statics: "static",
            analysis: "flutter",
        };
        let plan = |analysis| Chain3dPlan {
            model: chain(),
            analysis,
        };
        let tip = SpatialLoad::PointForce {
            span: 1.0,
            force: SpatialVector::Dead([0.0, 1.0, 0.0]),
        };
        let mut pk = flutter3d(Aerodynamics::Steady);
        pk.pk = true;
        let mut no_sweep = flutter3d(Aerodynamics::Wagner);
        no_sweep.sweep = None;
        let mut tolerance = flutter3d(Aerodynamics::Wagner);
        tolerance.tolerance = 2.0;
        let cases: Vec<(Analysis3d, &str)> = vec![
            (
                Analysis3d::Modes { count: 13 },
                "flutter.count: must be between 1 and the number of degrees of freedom (12)",
            ),
            (
                Analysis3d::Static(Static3d {
                    loads: Vec::new(),
                    options: StaticOptions::default(),
                    sweep: None,
                    modes: None,
                    load_names: Vec::new(),
                }),
                "loads: a static analysis needs at least one load",
            ),
            (
                Analysis3d::Static(Static3d {
                    loads: vec![tip],
                    options: StaticOptions::default(),
                    sweep: Some(Sweep {
                        load: 0,
                        scales: vec![0.0, f64::NAN],
                    }),
                    modes: None,
                    load_names: Vec::new(),
                }),
                "flutter.sweep.scales[1]: must be finite",
            ),
            (Analysis3d::Flutter(pk), "flutter.pk: the p-k method"),
            (Analysis3d::Flutter(no_sweep), "aero.sweep: missing"),
            (
                Analysis3d::Flutter(tolerance),
                "flutter.tolerance: must be in (0, 1)",
            ),
        ];
        for (analysis, expected) in cases {
            let e = plan(analysis).validate(&fields).unwrap_err().to_string();
            assert!(e.starts_with(expected), "{e}");
        }
    }
}
