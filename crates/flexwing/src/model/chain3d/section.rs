//! The input of the 3-D chain: section stiffness and inertia along the span, element inertia,
//! joint calibration (docs/chain3d-model.md, "Data"). Every property is a [`Profile`]: a number
//! or a piecewise-linear table over the span.
//!
//! Components are in the section frame `(t, n, c)`: `t` along the reference axis (span), `n` the
//! section normal (the planar model's flap direction `y` on a straight beam), `c = t × n`
//! chordwise toward the leading edge (`z`). Rotations are right-handed rotation vectors in that
//! frame: twist about `t` (nose-up is a rotation about `−t`, the planar model's sign), lag bending
//! about `n`, flap bending about `c`.

use crate::beam::{InertiaAxis, Profile};

/// The section's stiffness: the 3×3 matrix `C` relating the moment `m = C κ` to the curvature
/// (the rotation-vector rate) `κ`, both in `(t, n, c)` components,
///
/// ```text
///     ⎡ GJ          twist_lag   twist_flap ⎤
/// C = ⎢ twist_lag   EI_lag      lag_flap   ⎥
///     ⎣ twist_flap  lag_flap    EI_flap    ⎦
/// ```
///
/// positive definite at every station.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionStiffness {
    /// Torsional stiffness `GJ` (N·m²).
    pub gj: Profile,
    /// Flap bending stiffness `EI_flap`, about `c` (N·m²): the planar model's `EI`.
    pub ei_flap: Profile,
    /// Lag (chordwise, in-plane) bending stiffness `EI_lag`, about `n` (N·m²).
    pub ei_lag: Profile,
    /// Off-diagonal terms (bend–twist and flap–lag coupling), `None` for an uncoupled section.
    pub coupling: Option<StiffnessCoupling>,
}

/// Off-diagonal terms of [`SectionStiffness`] (N·m²), in rotation-vector components about
/// `(t, n, c)`: a positive `twist_flap` makes a positive flap curvature (about `+c`, tip up on a
/// straight beam) carry a positive moment about `+t` (nose-down).
#[derive(Debug, Clone, PartialEq)]
pub struct StiffnessCoupling {
    /// `C_tc`: twist–flap.
    pub twist_flap: Profile,
    /// `C_tn`: twist–lag.
    pub twist_lag: Profile,
    /// `C_nc`: lag–flap.
    pub lag_flap: Profile,
}

/// How each element's rotary inertia in bending is lumped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ElementInertia {
    /// Each element a rigid bar: `∫ m (s − s_mid)² ds` (`m ℓ²/12` for a uniform element) about
    /// the flap and lag axes, plus the section's rotary inertias. The default: it converges to
    /// Euler–Bernoulli at second order and leaves no near-null inertia direction at large n.
    #[default]
    Bar,
    /// Point masses: the section's rotary inertias only (the paper's lumping, as the planar
    /// model's default).
    Point,
}

/// The section's mass properties, per unit length.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionInertia {
    /// Mass per length `m` (kg/m), positive.
    pub mass_per_length: Profile,
    /// Polar mass moment of inertia per length about `t` (kg·m), about the axis named by
    /// `polar_inertia_about`.
    pub polar_inertia: Profile,
    /// The axis `polar_inertia` is given about (as the planar model's `polar_inertia_about`).
    pub polar_inertia_about: InertiaAxis,
    /// Chordwise offset of the mass centre from the elastic axis along `c` (m): the planar
    /// model's `d0`.
    pub d0: Profile,
    /// Offset of the mass centre along the section normal `n` (m).
    pub d0_normal: Profile,
    /// Section rotary inertia per length in flap, about `c` (kg·m): the planar model's
    /// `rotary_inertia`. Zero for Euler–Bernoulli.
    pub rotary_inertia_flap: Profile,
    /// Section rotary inertia per length in lag, about `n` (kg·m).
    pub rotary_inertia_lag: Profile,
    /// Lumping of the elements' rotary inertia in bending.
    pub element_inertia: ElementInertia,
}

impl SectionInertia {
    /// A section with mass `m` and polar inertia `polar` (about the mass centre), no offsets, no
    /// section rotary inertia in bending, elements as bars.
    pub fn uniform(m: f64, polar: f64) -> Self {
        Self {
            mass_per_length: Profile::Uniform(m),
            polar_inertia: Profile::Uniform(polar),
            polar_inertia_about: InertiaAxis::MassCentre,
            d0: Profile::Uniform(0.0),
            d0_normal: Profile::Uniform(0.0),
            rotary_inertia_flap: Profile::Uniform(0.0),
            rotary_inertia_lag: Profile::Uniform(0.0),
            element_inertia: ElementInertia::Bar,
        }
    }
}

impl SectionStiffness {
    /// An uncoupled section.
    pub fn uncoupled(gj: f64, ei_flap: f64, ei_lag: f64) -> Self {
        Self {
            gj: Profile::Uniform(gj),
            ei_flap: Profile::Uniform(ei_flap),
            ei_lag: Profile::Uniform(ei_lag),
            coupling: None,
        }
    }
}

/// How the joint springs are obtained from the section stiffness (docs/chain3d-model.md,
/// "Joint stiffness").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum JointCalibration {
    /// Every axis: joint `i` joins the midpoints of elements `i − 1` and `i` (the clamp for the
    /// first), and its compliance is that of the continuous rod between them, the two
    /// half-elements' compliances `∫ C⁻¹ ds` combined in the frame of element `i`:
    /// `K_i = (R⁰_iᵀ S⁺_{i−1} R⁰_i + S⁻_i)⁻¹`. Second order for any geometry. The default.
    #[default]
    Compliance,
    /// The paper's tip-load rule on both bending axes (flap with `EI_flap`, lag with `EI_lag`:
    /// the springs reproduce the exact linear nodal deflections of the cantilever under a tip
    /// force, the planar model's `Calibration::TipLoad`), torsion by the compliance rule. Only for
    /// an uncoupled section on a straight reference axis without pretwist, where the axes do
    /// not mix.
    TipLoad,
}
