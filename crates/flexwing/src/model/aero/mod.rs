//! Strip-theory aerodynamics on the lumped chain (docs/aeroelastic-model.md): section data, the
//! aerodynamic models, the fluid's inertia, and [`Aeroelastic`], a structural model (the planar
//! chain, full or reduced, or the 3-D chain) with its strips.
//!
//! One strip per element, at the element's midpoint, in the deformed geometry: on the planar
//! chain `chain.rs` and `strip.rs`, on the 3-D chain `spatial.rs` (the same section theory in the
//! section frame, docs/chain3d-model.md "Strip aerodynamics"). The conventions
//! (leading edge on `+z`, twist nose-up, `d0 > 0` toward the leading edge, the free stream tilted
//! by the root angle) are fixed in docs/aeroelastic-model.md §1 and checked by hand in
//! `strip.rs`'s tests.

mod chain;
mod flap;
mod fluid;
mod lag;
// Generated table (peters_poles.py): its element type is the data layout, not worth an alias.
#[allow(clippy::type_complexity)]
mod peters_poles;
mod spatial;
mod strip;
mod theodorsen;

pub(crate) use chain::AeroScratch;
pub use flap::FlapCoefficients;
pub(crate) use flap::{flap_air, hinge_moment, FlapAir, StripFlap};
pub(crate) use fluid::FluidInertia;
pub(crate) use lag::Lag;
pub(crate) use strip::{section_loads, Air, StripData};
pub use theodorsen::{theodorsen, theodorsen_derivative};

use nalgebra::DMatrix;

use crate::beam::profile::Sign;
use crate::beam::Profile;
use crate::error::{Error, InputError};
use crate::model::{AppliedLoads, Chain3d, FullModel, Load, ReducedModel, StructuralModel};

/// Aerodynamic section data along the span, each a number or a spanwise table (like the beam's
/// section properties). Angles in radians.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroSection {
    /// Chord `c` (m), positive.
    pub chord: Profile,
    /// Elastic-axis position as a fraction of the chord from the leading edge, in `[0, 1]`
    /// (Theodorsen's `a = 2 x_ea − 1`).
    pub elastic_axis: Profile,
    /// Lift slope `c_lα` (1/rad), positive; `2π` for thin-airfoil theory.
    pub lift_slope: Profile,
    /// Zero-lift angle of attack `α0` (rad).
    pub zero_lift_angle: Profile,
    /// Pitching-moment coefficient about the aerodynamic centre `c_m0` (nose-up positive).
    pub cm0: Profile,
    /// Drag coefficient `c_d0`, non-negative (its force is chordwise, reacted by the clamp).
    pub cd0: Profile,
    /// Trailing-edge control surfaces (none by default).
    pub surfaces: Vec<ControlSurface>,
}

/// A trailing-edge control surface (flap, aileron) over a span range, with Theodorsen's
/// thin-airfoil flap aerodynamics (`model/aero/flap.rs`, docs/aeroelastic-model.md §3b). The
/// deflection `δ` is positive **trailing edge down** (it raises the lift), the hinge moment is
/// positive in the sense of `δ`.
#[derive(Debug, Clone, PartialEq)]
pub struct ControlSurface {
    /// Its name (unique among the surfaces): the inputs and outputs are named after it.
    pub name: String,
    /// Inboard end, span station (m) from the root, in `[0, to)`.
    pub from: f64,
    /// Outboard end, span station (m), in `(from, L]`.
    pub to: f64,
    /// Hinge line as a fraction of the chord from the leading edge, in `(0, 1)` (Theodorsen's
    /// `c = 2 x_h − 1`): `0.75` is a flap of a quarter of the chord.
    pub hinge: Profile,
    /// Deflection `δ` (rad, trailing edge down positive) of the equilibrium (static runs, the
    /// equilibria of flutter and of the linear model, the start of a response).
    pub deflection: f64,
}

impl ControlSurface {
    /// The surface `name` over `[from, to]` with hinge at chord fraction `hinge`, undeflected.
    pub fn new(name: &str, from: f64, to: f64, hinge: f64) -> Self {
        Self {
            name: name.to_string(),
            from,
            to,
            hinge: Profile::Uniform(hinge),
            deflection: 0.0,
        }
    }
}

impl AeroSection {
    /// A thin symmetric airfoil: the given chord and elastic axis, `c_lα = 2π`, `α0 = 0`,
    /// `c_m0 = 0`, `c_d0 = 0`.
    pub fn new(chord: Profile, elastic_axis: Profile) -> Self {
        Self {
            chord,
            elastic_axis,
            lift_slope: Profile::Uniform(2.0 * std::f64::consts::PI),
            zero_lift_angle: Profile::Uniform(0.0),
            cm0: Profile::Uniform(0.0),
            cd0: Profile::Uniform(0.0),
            surfaces: Vec::new(),
        }
    }
}

/// The aerodynamic model (docs/aeroelastic-model.md §4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Aerodynamics {
    /// Steady strip theory: the angle of attack from the geometry only. For statics and
    /// divergence; it gives no aerodynamic damping.
    Steady,
    /// Quasi-steady (`C(k) = 1`) with the section's velocity in the upwash and the apparent mass.
    /// Not a flutter model for an elastic axis at or aft of mid-chord.
    QuasiSteady,
    /// Wagner's function by R. T. Jones' two-state approximation, with the apparent mass.
    Wagner,
    /// Peters' finite-state inflow with `states` states per strip (1 to 15; 4–10 are usual: the
    /// 1995 coefficients approximate Theodorsen's function best near 8–10 states and worse beyond),
    /// with the apparent mass.
    Peters {
        /// Number of inflow states per strip.
        states: usize,
    },
}

impl std::fmt::Display for Aerodynamics {
    /// The model in words: `steady strip theory`, `Wagner's function (…) with apparent mass`, ….
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Aerodynamics::Steady => write!(f, "steady strip theory"),
            Aerodynamics::QuasiSteady => write!(f, "quasi-steady (C(k) = 1) with apparent mass"),
            Aerodynamics::Wagner => write!(
                f,
                "Wagner's function (R. T. Jones, 2 states per strip) with apparent mass"
            ),
            Aerodynamics::Peters { states } => write!(
                f,
                "Peters' finite-state inflow ({states} states per strip) with apparent mass"
            ),
        }
    }
}

impl Aerodynamics {
    /// The case file's name of the model: `steady`, `quasi-steady`, `wagner` or `peters`.
    pub fn name(&self) -> &'static str {
        match self {
            Aerodynamics::Steady => "steady",
            Aerodynamics::QuasiSteady => "quasi-steady",
            Aerodynamics::Wagner => "wagner",
            Aerodynamics::Peters { .. } => "peters",
        }
    }

    /// Whether the model has the section's velocity and the apparent mass (all but `Steady`).
    pub fn is_unsteady(&self) -> bool {
        !matches!(self, Aerodynamics::Steady)
    }
    /// Lag states per strip.
    pub fn states_per_strip(&self) -> usize {
        match self {
            Aerodynamics::Steady | Aerodynamics::QuasiSteady => 0,
            Aerodynamics::Wagner => 2,
            Aerodynamics::Peters { states } => *states,
        }
    }
    fn lag(&self) -> Option<Lag> {
        match self {
            Aerodynamics::Steady | Aerodynamics::QuasiSteady => None,
            Aerodynamics::Wagner => Some(Lag::jones()),
            Aerodynamics::Peters { states } => Some(Lag::peters(*states)),
        }
    }
}

/// Largest number of Peters states accepted: 16 states of the 1995 coefficients have an unstable
/// pole (`model/aero/lag.rs`); every smaller count is realized exactly to round-off.
const MAX_PETERS_STATES: usize = lag::PETERS_MAX_STATES;

/// The flight condition: free-stream speed, root angle of attack and gravity.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightCondition {
    /// Free-stream speed `U` (m/s), finite and non-negative.
    pub speed: f64,
    /// Root angle of attack `α_r` (rad): a rigid nose-up rotation of the clamp, `|α_r| < π/2`.
    pub root_angle: f64,
    /// Gravitational acceleration `g` (m/s²) along the ground's vertical, or `None`.
    pub gravity: Option<f64>,
}

impl FlightCondition {
    /// Flight at speed `speed`, zero root angle, no gravity.
    pub fn at_speed(speed: f64) -> Self {
        Self {
            speed,
            root_angle: 0.0,
            gravity: None,
        }
    }

    /// Check the condition; `field` prefixes the error fields (`{field}.speed`, …).
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        if !(self.speed.is_finite() && self.speed >= 0.0) {
            return Err(InputError::new(
                format!("{field}.speed"),
                format!(
                    "must be a finite non-negative speed, got {}",
                    crate::text::short(self.speed)
                ),
            ));
        }
        crate::magnitude::check(&format!("{field}.speed"), "", self.speed)?;
        if !(self.root_angle.is_finite() && self.root_angle.abs() < 0.5 * std::f64::consts::PI) {
            return Err(InputError::new(
                format!("{field}.root_angle"),
                format!(
                    "must be finite and below π/2 in magnitude (rad), got {}",
                    crate::text::short(self.root_angle)
                ),
            ));
        }
        if let Some(g) = self.gravity {
            if !g.is_finite() {
                return Err(InputError::new(
                    format!("{field}.gravity"),
                    format!("must be finite, got {g}"),
                ));
            }
            crate::magnitude::check(&format!("{field}.gravity"), "", g)?;
        }
        Ok(())
    }
}

/// The chain whose joint coordinates the strips are evaluated on: the paper's planar chain or
/// the 3-D chain. What the aerodynamics needs of a structure: strip kinematics from its joint
/// rotations and rates, generalized forces of the strip loads, the loads and outputs in the
/// chain's terms.
#[derive(Debug, Clone, Copy)]
pub enum AeroChain<'a> {
    /// The planar chain (`model.md`): bending and twist joints.
    Planar(&'a FullModel),
    /// The 3-D chain (docs/chain3d-model.md): three-axis joints.
    Spatial(&'a Chain3d),
}

impl AeroChain<'_> {
    /// Number of joint coordinates.
    pub fn n_dofs(&self) -> usize {
        match self {
            AeroChain::Planar(f) => f.n_dofs(),
            AeroChain::Spatial(c) => c.n_dofs(),
        }
    }
    /// Number of elements (strips).
    pub fn n_elements(&self) -> usize {
        match self {
            AeroChain::Planar(f) => f.n_elements(),
            AeroChain::Spatial(c) => c.n_elements(),
        }
    }
    /// Length of the beam (m): the span of the planar chain, the arc length of the 3-D chain's
    /// reference axis.
    pub fn length(&self) -> f64 {
        match self {
            AeroChain::Planar(f) => f.beam().length(),
            AeroChain::Spatial(c) => c.beam().length(),
        }
    }
    /// Node stations along the beam (m).
    pub fn nodes(&self) -> &[f64] {
        match self {
            AeroChain::Planar(f) => f.beam().nodes(),
            AeroChain::Spatial(c) => c.beam().nodes(),
        }
    }
    /// The planar model's loads resolved on this chain (on the 3-D chain by
    /// [`crate::model::chain3d::SpatialLoad::from_planar`]); `field` prefixes the error fields.
    ///
    /// # Errors
    /// Those of [`FullModel::apply`] or [`Chain3d::apply_planar`].
    pub fn apply(&self, loads: &[Load], field: &str) -> Result<AppliedLoads, InputError> {
        match self {
            AeroChain::Planar(f) => f.apply(loads, field),
            AeroChain::Spatial(c) => c.apply_planar(loads, field),
        }
    }
    /// Tip displacement of the elastic axis from the undeformed tip `(dx, dy, dz)` (m; `dz = 0`
    /// on the planar chain) and the tip section's nose-up pitch (rad) at the joint rotations
    /// `q`: the planar chain's tip twist `ψ_n`; on the 3-D chain the angle of the tip chord `c`
    /// above the chordwise axis `ẑ` in the section plane, `atan2(−n·ẑ, c·ẑ)` (the same angle in
    /// the planar limit).
    pub fn tip(&self, q: &[f64]) -> ([f64; 3], f64) {
        match self {
            AeroChain::Planar(full) => {
                let kin = full.kinematics(q);
                let nodes = full.node_positions(&kin);
                let nel = full.n_elements();
                let tip = nodes[nel];
                let twist = if full.has_torsion() {
                    kin.psi[nel - 1]
                } else {
                    0.0
                };
                ([tip[0] - full.beam().length(), tip[1], 0.0], twist)
            }
            AeroChain::Spatial(chain) => {
                let shape = chain.shape(q);
                let n = chain.n_elements();
                let reference = chain.beam().reference_positions()[n];
                let p = shape.tip();
                let r = shape.frames[n - 1];
                let twist = (-r[2][1]).atan2(r[2][2]);
                (std::array::from_fn(|k| p[k] - reference[k]), twist)
            }
        }
    }
    /// Root bending moment (N·m): the clamp spring's flap moment, `K_θ,1 q_1` on the planar
    /// chain, the flap component `(K_0 φ_0)_c` on the 3-D chain.
    pub fn root_bending_moment(&self, q: &[f64]) -> f64 {
        match self {
            AeroChain::Planar(full) => full.stiffness()[0] * q[0],
            AeroChain::Spatial(chain) => {
                let k = &chain.beam().joint_stiffness()[0];
                (0..3).map(|c| k[2][c] * q[c]).sum()
            }
        }
    }
}

/// A structural model the aerodynamics can act on: a chain (the planar full model or the 3-D
/// chain), or a reduced model whose coordinates map linearly to a chain's (`q = Φ η`).
pub trait AeroStructure: StructuralModel + Clone {
    /// The basis `Φ` (`n_dofs(chain) × n_dofs`), or `None` for a chain itself (`Φ = I`).
    fn basis(&self) -> Option<&DMatrix<f64>>;
    /// The chain the strips are evaluated on (the full model underneath a reduced model).
    fn chain(&self) -> AeroChain<'_>;
}

impl AeroStructure for FullModel {
    fn basis(&self) -> Option<&DMatrix<f64>> {
        None
    }
    fn chain(&self) -> AeroChain<'_> {
        AeroChain::Planar(self)
    }
}

impl AeroStructure for ReducedModel {
    fn basis(&self) -> Option<&DMatrix<f64>> {
        Some(ReducedModel::basis(self))
    }
    fn chain(&self) -> AeroChain<'_> {
        AeroChain::Planar(self.full())
    }
}

impl AeroStructure for Chain3d {
    fn basis(&self) -> Option<&DMatrix<f64>> {
        None
    }
    fn chain(&self) -> AeroChain<'_> {
        AeroChain::Spatial(self)
    }
}

/// A structure on the paper's planar chain (the full model or a reduced model on it), whose
/// full model [`Aeroelastic::full`] gives.
pub trait PlanarStructure: AeroStructure + crate::model::PlanarModel {}
impl PlanarStructure for FullModel {}
impl PlanarStructure for ReducedModel {}

/// A structural model with its aerodynamic strips: the structure carries the fluid's inertia
/// (its mass matrix is the wet one), and every aeroelastic analysis takes this type.
#[derive(Debug, Clone)]
pub struct Aeroelastic<M: AeroStructure = FullModel> {
    structure: M,
    pub(crate) strips: Vec<StripData>,
    density: f64,
    aerodynamics: Aerodynamics,
    pub(crate) lag: Option<Lag>,
    surfaces: Vec<ControlSurface>,
}

impl Aeroelastic<FullModel> {
    /// The full model `structure` (in vacuo; its fluid inertia, if any, is replaced) with the
    /// section data `section`, air density `density` and aerodynamic model `aerodynamics`.
    /// `field` prefixes the error fields (`{field}.chord`, `{field}.density`, …).
    ///
    /// # Errors
    /// A section profile that is not finite, a chord or lift slope that is not positive, an
    /// elastic axis outside `[0, 1]`, a negative drag coefficient, a density that is not positive,
    /// a number of Peters states outside `1..=15`.
    pub fn new(
        structure: &FullModel,
        section: &AeroSection,
        density: f64,
        aerodynamics: Aerodynamics,
        field: &str,
    ) -> Result<Self, InputError> {
        let beam = structure.beam();
        let (strips, fluid) =
            strips_and_fluid(beam.nodes(), section, density, aerodynamics, field)?;
        let mut dry = structure.clone();
        dry.fluid = None;
        Ok(Self {
            structure: dry.with_fluid(fluid),
            strips,
            density,
            aerodynamics,
            lag: aerodynamics.lag(),
            surfaces: section.surfaces.clone(),
        })
    }

    /// The reduced aeroelastic model on the wet natural modes `indices` (0-based) of the full
    /// model about the undeformed state at rest (`U = 0`: structure plus fluid inertia). The
    /// strips and the aerodynamic model are the same; aerodynamic loads are projected on the modes.
    ///
    /// # Errors
    /// The errors of [`crate::solve::Modes::undeformed`] and [`ReducedModel::new`].
    pub fn reduced(&self, indices: &[usize]) -> Result<Aeroelastic<ReducedModel>, Error> {
        let modes = crate::solve::Modes::undeformed(&self.structure)?;
        let rom = ReducedModel::new(&self.structure, modes.shapes(), indices)?;
        Ok(Aeroelastic {
            structure: rom,
            strips: self.strips.clone(),
            density: self.density,
            aerodynamics: self.aerodynamics,
            lag: self.lag.clone(),
            surfaces: self.surfaces.clone(),
        })
    }
}

/// The strips (one per element of the chain with node stations `nodes`, at the element
/// midpoints) and the fluid's inertia of the section data, validated; `field` prefixes the
/// error fields.
fn strips_and_fluid(
    nodes: &[f64],
    section: &AeroSection,
    density: f64,
    aerodynamics: Aerodynamics,
    field: &str,
) -> Result<(Vec<StripData>, FluidInertia), InputError> {
    let length = nodes[nodes.len() - 1];
    let f = |name: &str| format!("{field}.{name}");
    section
        .chord
        .validate(&f("chord"), length, Sign::Positive)?;
    section
        .elastic_axis
        .validate(&f("elastic_axis"), length, Sign::Any)?;
    let values: Vec<f64> = match &section.elastic_axis {
        Profile::Uniform(v) => vec![*v],
        Profile::Table { value, .. } => value.clone(),
    };
    if let Some(v) = values.iter().find(|v| !(0.0..=1.0).contains(*v)) {
        return Err(InputError::new(
            f("elastic_axis"),
            format!(
                "must lie on the chord, a fraction in [0, 1] from the leading edge, got {}",
                crate::text::short(*v)
            ),
        ));
    }
    section
        .lift_slope
        .validate(&f("lift_slope"), length, Sign::Positive)?;
    section
        .zero_lift_angle
        .validate(&f("zero_lift_angle"), length, Sign::Any)?;
    section.cm0.validate(&f("cm0"), length, Sign::Any)?;
    section.cd0.validate(&f("cd0"), length, Sign::NonNegative)?;
    if !(density.is_finite() && density > 0.0) {
        return Err(InputError::new(
            f("density"),
            format!(
                "must be a finite positive number (kg/m³), got {}",
                crate::text::short(density)
            ),
        ));
    }
    crate::magnitude::check(&f("density"), "", density)?;
    if let Aerodynamics::Peters { states } = aerodynamics {
        if !(1..=MAX_PETERS_STATES).contains(&states) {
            return Err(InputError::new(
                f("aerodynamics.states"),
                format!("Peters' inflow needs 1 to {MAX_PETERS_STATES} states, got {states}"),
            ));
        }
    }
    let strips: Vec<StripData> = nodes
        .windows(2)
        .map(|w| {
            let x = 0.5 * (w[0] + w[1]);
            StripData {
                b: 0.5 * section.chord.at(x),
                a: 2.0 * section.elastic_axis.at(x) - 1.0,
                lift_slope: section.lift_slope.at(x),
                alpha0: section.zero_lift_angle.at(x),
                cm0: section.cm0.at(x),
                cd0: section.cd0.at(x),
                width: w[1] - w[0],
                station: x,
                flap: None,
            }
        })
        .collect();
    let mut strips = strips;
    surfaces_on_strips(nodes, &section.surfaces, &mut strips, field)?;
    let pi = std::f64::consts::PI;
    let fluid = FluidInertia {
        mass: strips
            .iter()
            .map(|s| pi * density * s.b * s.b * s.width)
            .collect(),
        station: strips.iter().map(|s| s.a * s.b).collect(),
        inertia: strips
            .iter()
            .map(|s| pi * density * s.b.powi(4) * s.width / 8.0)
            .collect(),
    };
    Ok((strips, fluid))
}

/// Check the control surfaces and put them on the strips they cover (`strip.flap`); errors name
/// `{field}.surfaces[k].…`.
fn surfaces_on_strips(
    nodes: &[f64],
    surfaces: &[ControlSurface],
    strips: &mut [StripData],
    field: &str,
) -> Result<(), InputError> {
    let length = nodes[nodes.len() - 1];
    let short = crate::text::short;
    for (k, sf) in surfaces.iter().enumerate() {
        let f = |name: &str| format!("{field}.surfaces[{k}].{name}");
        if sf.name.trim().is_empty() {
            return Err(InputError::new(f("name"), "must not be empty"));
        }
        if let Some(j) = surfaces[..k].iter().position(|o| o.name == sf.name) {
            return Err(InputError::new(
                f("name"),
                format!("\"{}\" is also the name of {field}.surfaces[{j}]", sf.name),
            ));
        }
        if !(sf.from.is_finite() && (0.0..length).contains(&sf.from)) {
            return Err(InputError::new(
                f("from"),
                format!(
                    "must lie on the span [0, {}) m, got {}",
                    short(length),
                    short(sf.from)
                ),
            ));
        }
        if !(sf.to.is_finite() && sf.to > sf.from && sf.to <= length * (1.0 + 1e-12)) {
            return Err(InputError::new(
                f("to"),
                format!(
                    "must lie on the span, after from = {} m and at most {} m, got {}",
                    short(sf.from),
                    short(length),
                    short(sf.to)
                ),
            ));
        }
        sf.hinge.validate(&f("hinge"), length, Sign::Any)?;
        let values: Vec<f64> = match &sf.hinge {
            Profile::Uniform(v) => vec![*v],
            Profile::Table { value, .. } => value.clone(),
        };
        if let Some(v) = values.iter().find(|v| !(**v > 0.0 && **v < 1.0)) {
            return Err(InputError::new(
                f("hinge"),
                format!(
                    "must lie inside the chord, a fraction in (0, 1) from the leading edge, got {}",
                    short(*v)
                ),
            ));
        }
        if !(sf.deflection.is_finite() && sf.deflection.abs() < 0.5 * std::f64::consts::PI) {
            return Err(InputError::new(
                f("deflection"),
                format!(
                    "must be finite and below π/2 in magnitude (rad), got {}",
                    short(sf.deflection)
                ),
            ));
        }
        for (i, (s, w)) in strips.iter_mut().zip(nodes.windows(2)).enumerate() {
            let covered = sf.to.min(w[1]) - sf.from.max(w[0]);
            if covered <= 1e-12 * (w[1] - w[0]) {
                continue;
            }
            if let Some(other) = s.flap {
                return Err(InputError::new(
                    f("from"),
                    format!(
                        "overlaps {field}.surfaces[{}] on the same strip (element {}, {}–{} m): \
                         one surface per strip",
                        other.surface,
                        i + 1,
                        short(w[0]),
                        short(w[1])
                    ),
                ));
            }
            let x = s.station.clamp(sf.from, sf.to);
            s.flap = Some(StripFlap {
                surface: k,
                coverage: (covered / (w[1] - w[0])).min(1.0),
                coefficients: FlapCoefficients::new(2.0 * sf.hinge.at(x) - 1.0, s.a),
            });
        }
    }
    Ok(())
}

impl Aeroelastic<Chain3d> {
    /// The 3-D chain `structure` (in vacuo; its fluid inertia, if any, is replaced) with the
    /// section data `section`, air density `density` and aerodynamic model `aerodynamics`: one
    /// strip per element at its midpoint along the reference axis (docs/chain3d-model.md, "Strip
    /// aerodynamics"). `field` prefixes the error fields.
    ///
    /// # Errors
    /// As [`Aeroelastic::new`].
    pub fn spatial(
        structure: &Chain3d,
        section: &AeroSection,
        density: f64,
        aerodynamics: Aerodynamics,
        field: &str,
    ) -> Result<Self, InputError> {
        let (strips, fluid) = strips_and_fluid(
            structure.beam().nodes(),
            section,
            density,
            aerodynamics,
            field,
        )?;
        Ok(Self {
            structure: structure.dry().with_fluid(fluid),
            strips,
            density,
            aerodynamics,
            lag: aerodynamics.lag(),
            surfaces: section.surfaces.clone(),
        })
    }
}

impl<M: PlanarStructure> Aeroelastic<M> {
    /// The planar full model underneath (itself for a full aeroelastic model).
    pub fn full(&self) -> &FullModel {
        self.structure.full_model()
    }
}

impl<M: AeroStructure> Aeroelastic<M> {
    /// The structural model (with the fluid's inertia).
    pub fn structure(&self) -> &M {
        &self.structure
    }
    /// The chain the strips are evaluated on (the full model underneath a reduced model).
    pub fn chain(&self) -> AeroChain<'_> {
        self.structure.chain()
    }
    /// The planar model's loads resolved on the chain ([`AeroChain::apply`]).
    ///
    /// # Errors
    /// Those of [`AeroChain::apply`].
    pub fn apply(&self, loads: &[Load], field: &str) -> Result<AppliedLoads, InputError> {
        self.chain().apply(loads, field)
    }
    /// Air density `ρ` (kg/m³).
    pub fn density(&self) -> f64 {
        self.density
    }
    /// The aerodynamic model.
    pub fn aerodynamics(&self) -> Aerodynamics {
        self.aerodynamics
    }
    /// The same structure and strips with another aerodynamic model.
    ///
    /// # Errors
    /// A number of Peters states outside `1..=15` (field `{field}.states`).
    pub fn with_aerodynamics(
        &self,
        aerodynamics: Aerodynamics,
        field: &str,
    ) -> Result<Self, InputError> {
        if let Aerodynamics::Peters { states } = aerodynamics {
            if !(1..=MAX_PETERS_STATES).contains(&states) {
                return Err(InputError::new(
                    format!("{field}.states"),
                    format!("Peters' inflow needs 1 to {MAX_PETERS_STATES} states, got {states}"),
                ));
            }
        }
        Ok(Self {
            structure: self.structure.clone(),
            strips: self.strips.clone(),
            density: self.density,
            aerodynamics,
            lag: aerodynamics.lag(),
            surfaces: self.surfaces.clone(),
        })
    }
    /// Number of strips (one per element).
    pub fn n_strips(&self) -> usize {
        self.strips.len()
    }
    /// Number of aerodynamic states (strips × lag states per strip).
    pub fn n_aero_states(&self) -> usize {
        self.strips.len() * self.aerodynamics.states_per_strip()
    }
    /// Span stations of the strips' midpoints (m).
    pub fn strip_stations(&self) -> Vec<f64> {
        self.strips.iter().map(|s| s.station).collect()
    }

    /// The control surfaces.
    pub fn surfaces(&self) -> &[ControlSurface] {
        &self.surfaces
    }

    /// The surfaces' equilibrium deflections `(δ, 0, 0)` (rad), one per surface.
    pub(crate) fn rest_deflections(&self) -> Vec<[f64; 3]> {
        self.surfaces
            .iter()
            .map(|s| [s.deflection, 0.0, 0.0])
            .collect()
    }

    /// The flaps' part of the air of every strip (`out[i].flap`) for the deflections, rates and
    /// accelerations `deflections[k] = (δ, δ̇, δ̈)` of each surface; the speeds of `out` must be
    /// set ([`Self::air_into`]).
    pub(crate) fn flaps_into(&self, deflections: &[[f64; 3]], out: &mut [Air]) {
        let unsteady = self.aerodynamics.is_unsteady();
        for (o, s) in out.iter_mut().zip(&self.strips) {
            o.flap = match &s.flap {
                None => FlapAir::default(),
                Some(f) => flap::flap_air(
                    f,
                    s.b,
                    self.density,
                    o.speed,
                    deflections[f.surface],
                    unsteady,
                ),
            };
        }
    }

    /// Hinge moment of every surface (N·m, positive trailing edge down) into `out`, from the
    /// evaluation in `sc` (flow and lagged upwash) with the air `air` and the deflections
    /// `deflections`: the steady, circulatory and flap-rate terms of Theodorsen's hinge moment,
    /// summed over the covered width of the strips. The terms of the structure's own rates and
    /// accelerations (`α̇`, `α̈`, `ḧ`) are not included (zero at an equilibrium).
    pub(crate) fn hinge_moments_into(
        &self,
        sc: &AeroScratch<f64>,
        air: &[Air],
        deflections: &[[f64; 3]],
        out: &mut [f64],
    ) {
        out.fill(0.0);
        let unsteady = self.aerodynamics.is_unsteady();
        for (i, s) in self.strips.iter().enumerate() {
            let Some(f) = &s.flap else { continue };
            let a = &air[i];
            // The circulatory lift of the covered part: its upwash carries the whole flap
            // (the strip's carries the covered fraction of it).
            let w = sc.weff[i] + (1.0 - f.coverage) * a.flap.covered_upwash;
            let cl = s.lift_slope * (w.atan2(sc.wt[i]) - s.alpha0);
            let lift = a.pressure * 2.0 * s.b * cl;
            let h = flap::hinge_moment(
                f,
                s.b,
                self.density,
                a.speed,
                deflections[f.surface],
                unsteady,
                lift,
            );
            out[f.surface] += h * f.coverage * s.width;
        }
    }

    /// The air at every strip for free-stream speed `speed`, root angle `root_angle` and gust
    /// velocities `gust[i]` (m/s, up, ground frame), into `out` (docs/aeroelastic-model.md §1).
    pub(crate) fn air_into(&self, speed: f64, root_angle: f64, gust: &[f64], out: &mut [Air]) {
        let (sa, ca) = root_angle.sin_cos();
        for ((o, &g), _) in out.iter_mut().zip(gust).zip(&self.strips) {
            let wind = [0.0, speed * sa + g * ca, -speed * ca + g * sa];
            let v2 = wind[1] * wind[1] + wind[2] * wind[2];
            *o = Air {
                wind,
                speed: v2.sqrt(),
                pressure: 0.5 * self.density * v2,
                ..Air::default()
            };
        }
    }

    /// [`Self::air_into`] with the gust's rate `rate[i]` (m/s², uniform penetration: its
    /// apparent mass) and the gust through Küssner's function `lagged[i]` (m/s, not in the
    /// wind), both vertical in the ground frame (docs/aeroelastic-model.md §3a).
    pub(crate) fn air_with_gust_into(
        &self,
        speed: f64,
        root_angle: f64,
        (gust, rate, lagged): (&[f64], &[f64], &[f64]),
        out: &mut [Air],
    ) {
        self.air_into(speed, root_angle, gust, out);
        let (sa, ca) = root_angle.sin_cos();
        for ((o, &r), &l) in out.iter_mut().zip(rate).zip(lagged) {
            o.gust_rate = [0.0, r * ca, r * sa];
            o.gust_lagged = [0.0, l * ca, l * sa];
        }
    }

    /// The point of each strip's leading edge in the undeformed wing (wing frame, m): the strip's
    /// elastic-axis point plus `b(1 + a)` along its chord toward the leading edge.
    pub(crate) fn leading_edges(&self) -> Vec<[f64; 3]> {
        match self.chain() {
            AeroChain::Planar(_) => self
                .strips
                .iter()
                .map(|s| [s.station, 0.0, s.b * (1.0 + s.a)])
                .collect(),
            AeroChain::Spatial(chain) => {
                let p = chain.beam().reference_positions();
                let frames = chain.beam().reference_frames();
                self.strips
                    .iter()
                    .enumerate()
                    .map(|(i, s)| {
                        let r = &frames[i];
                        let le = s.b * (1.0 + s.a);
                        std::array::from_fn(|k| 0.5 * (p[i][k] + p[i + 1][k]) + le * r[k][2])
                    })
                    .collect()
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, SectionProperties, TorsionProperties,
    };

    fn wing() -> FullModel {
        let section = SectionProperties {
            ei: Profile::Uniform(2e4),
            mass_per_length: Profile::Uniform(0.75),
            torsion: Some(TorsionProperties {
                gj: Profile::Uniform(1e4),
                polar_inertia: Profile::Uniform(0.1),
                inertia_axis: InertiaAxis::ElasticAxis,
                offset: Profile::Uniform(0.0),
            }),
        };
        FullModel::new(
            Beam::new(
                16.0,
                &section,
                &Discretization::Uniform(4),
                Calibration::TipLoad,
            )
            .unwrap(),
        )
    }

    /// Bad section data and flight conditions name the caller's field.
    #[test]
    fn bad_input_names_the_field() {
        let full = wing();
        let ok = AeroSection::new(Profile::Uniform(1.0), Profile::Uniform(0.5));
        let cases: Vec<(AeroSection, f64, Aerodynamics, &str)> = vec![
            (
                AeroSection {
                    chord: Profile::Uniform(-1.0),
                    ..ok.clone()
                },
                1.0,
                Aerodynamics::Steady,
                "wing.aero.chord",
            ),
            (
                AeroSection {
                    elastic_axis: Profile::Uniform(1.2),
                    ..ok.clone()
                },
                1.0,
                Aerodynamics::Steady,
                "wing.aero.elastic_axis",
            ),
            (
                AeroSection {
                    lift_slope: Profile::Uniform(0.0),
                    ..ok.clone()
                },
                1.0,
                Aerodynamics::Steady,
                "wing.aero.lift_slope",
            ),
            (
                AeroSection {
                    cd0: Profile::Uniform(-0.1),
                    ..ok.clone()
                },
                1.0,
                Aerodynamics::Steady,
                "wing.aero.cd0",
            ),
            (
                AeroSection {
                    cm0: Profile::Uniform(f64::NAN),
                    ..ok.clone()
                },
                1.0,
                Aerodynamics::Steady,
                "wing.aero.cm0",
            ),
            (ok.clone(), 0.0, Aerodynamics::Steady, "wing.aero.density"),
            (
                ok.clone(),
                1.0,
                Aerodynamics::Peters { states: 0 },
                "wing.aero.aerodynamics.states",
            ),
            (
                ok.clone(),
                1.0,
                Aerodynamics::Peters { states: 16 },
                "wing.aero.aerodynamics.states",
            ),
        ];
        for (section, rho, aero, field) in cases {
            let e = Aeroelastic::new(&full, &section, rho, aero, "wing.aero").unwrap_err();
            assert_eq!(e.field, field, "{e}");
        }
        let bad = FlightCondition {
            speed: -1.0,
            root_angle: 0.0,
            gravity: None,
        };
        assert_eq!(bad.validate("flight").unwrap_err().field, "flight.speed");
        let bad = FlightCondition {
            speed: 1.0,
            root_angle: 2.0,
            gravity: None,
        };
        assert_eq!(
            bad.validate("flight").unwrap_err().field,
            "flight.root_angle"
        );
        let bad = FlightCondition {
            speed: 1.0,
            root_angle: 0.0,
            gravity: Some(f64::INFINITY),
        };
        assert_eq!(bad.validate("flight").unwrap_err().field, "flight.gravity");
        // A valid model: strips at the element midpoints, the wet structure.
        let aero =
            Aeroelastic::new(&full, &ok, 0.0889, Aerodynamics::Peters { states: 6 }, "a").unwrap();
        assert_eq!(aero.strip_stations(), vec![2.0, 6.0, 10.0, 14.0]);
        assert_eq!(aero.n_aero_states(), 24);
        assert!(aero.structure().has_fluid_inertia() && !full.has_fluid_inertia());
    }
}
