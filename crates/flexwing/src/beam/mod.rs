//! The continuous beam (section properties over the span), its cut into rigid elements, and the
//! calibration of the joint springs.
//!
//! [`Beam::new`] validates the input and resolves it into per-element quantities: lengths, masses,
//! mass-centre offsets, polar inertias and the spring stiffnesses of the lumped model.

pub(crate) mod calibration;
pub(crate) mod profile;

pub use calibration::Calibration;
pub use profile::Profile;

use crate::error::InputError;
use profile::{for_each_piece, Sign};

/// Axis about which the user gives the section's polar mass moment of inertia.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InertiaAxis {
    /// About the section's mass centre (`I_cg`).
    #[default]
    MassCentre,
    /// About the elastic axis (`I_ea = I_cg + m d0²`).
    ElasticAxis,
}

/// Torsion data of the section. Without it the model is bending-only.
#[derive(Debug, Clone, PartialEq)]
pub struct TorsionProperties {
    /// Torsional stiffness `GJ` (N·m²), strictly positive.
    pub gj: Profile,
    /// Polar mass moment of inertia per unit length (kg·m), about [`Self::inertia_axis`].
    pub polar_inertia: Profile,
    /// Axis of [`Self::polar_inertia`].
    pub inertia_axis: InertiaAxis,
    /// Chordwise offset `d0` of the mass centre from the elastic axis (m), along `+z` untwisted.
    pub offset: Profile,
}

/// Section properties of the continuous beam.
#[derive(Debug, Clone, PartialEq)]
pub struct SectionProperties {
    /// Bending stiffness `EI` (N·m²), strictly positive.
    pub ei: Profile,
    /// Mass per unit length `m` (kg/m), strictly positive.
    pub mass_per_length: Profile,
    /// Torsion data; `None` gives a bending-only model with `n` coordinates.
    pub torsion: Option<TorsionProperties>,
}

/// How the span is cut into elements.
#[derive(Debug, Clone, PartialEq)]
pub enum Discretization {
    /// `n` elements of equal length `L / n`.
    Uniform(usize),
    /// Explicit node stations `0 = x_0 < x_1 < … < x_n = L` (m).
    Stations(Vec<f64>),
}

/// Rotary inertia of the elements in bending, about `ẑ` through each element's midpoint. The
/// paper's model has none (point masses at the midpoints, [`RotaryInertia::default`]).
///
/// With point masses the chain's highest bending pattern — element angles alternating from
/// element to element, mass centres at rest — has almost no inertia: a near-null direction of
/// the mass matrix that makes implicit integrators fail Newton on long chains
/// (docs/model-choices.md, "Rotary inertia in bending"). Either term below gives it inertia.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RotaryInertia {
    /// Each element is a rigid bar rather than a point mass: it turns with its mass spread
    /// along its length, `∫ m(x) (x − x_mid)² dx` over the element (`m ℓ²/12` for uniform `m`).
    /// A property of the cut, not of the beam: it falls as `1/n²`, so the continuum limit is
    /// unchanged (Euler–Bernoulli).
    pub elements: bool,
    /// The section's own rotary (flap) inertia per unit length `ρI` (kg·m), about the bending
    /// axis: the Rayleigh beam's term, integrated over each element.
    pub section: Option<Profile>,
}

/// The lumped-mass beam: per-element data of the chain of rigid elements.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    length: f64,
    nodes: Vec<f64>,
    lengths: Vec<f64>,
    masses: Vec<f64>,
    offsets: Vec<f64>,
    inertias: Vec<f64>,
    bending_inertias: Vec<f64>,
    bending_stiffness: Vec<f64>,
    torsion_stiffness: Option<Vec<f64>>,
    calibration: Calibration,
}

impl Beam {
    /// Validate the continuous beam and cut it into elements.
    ///
    /// Element masses are `m_i = ∫ m dx` over the element, the element's mass-centre offset is
    /// the mass-weighted mean `d0_i = ∫ m d0 dx / m_i`, and its polar inertia about its mass centre
    /// is `J_i = ∫ I_ea dx − m_i d0_i²`, so that the element keeps the exact torsional inertia
    /// about the elastic axis and the exact static moment `∫ m d0 dx` of the continuous beam.
    /// For uniform properties these reduce to `m ℓ`, `d0` and `I_cg ℓ`.
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let beam = Beam::new(1.0, &section, &Discretization::Uniform(10), Calibration::TipLoad)?;
    /// assert_eq!(beam.n_elements(), 10);
    /// # Ok::<(), flexwing::InputError>(())
    /// ```
    pub fn new(
        length: f64,
        section: &SectionProperties,
        discretization: &Discretization,
        calibration: Calibration,
    ) -> Result<Self, InputError> {
        Self::named("beam", length, section, discretization, calibration)
    }

    /// As [`Beam::new`], with errors named under the caller's `prefix` for the beam:
    /// `{prefix}.length`, `{prefix}.elements` or `{prefix}.stations`, `{prefix}.section.EI`,
    /// `{prefix}.section.mass_per_length`, `{prefix}.section.GJ`, `{prefix}.section.polar_inertia`,
    /// `{prefix}.section.d0` (the keys of a case file's `[beam]`; [`Beam::new`] uses `beam`).
    ///
    /// # Errors
    /// As [`Beam::new`].
    pub fn named(
        prefix: &str,
        length: f64,
        section: &SectionProperties,
        discretization: &Discretization,
        calibration: Calibration,
    ) -> Result<Self, InputError> {
        let field = |key: &str| crate::field(prefix, key);
        if !(length.is_finite() && length > 0.0) {
            return Err(InputError::new(
                field("length"),
                format!(
                    "must be a finite positive number, got {}",
                    crate::text::short(length)
                ),
            ));
        }
        crate::magnitude::check(&field("length"), "", length)?;
        let nodes = stations(prefix, length, discretization)?;
        section
            .ei
            .validate(&field("section.EI"), length, Sign::Positive)?;
        section.mass_per_length.validate(
            &field("section.mass_per_length"),
            length,
            Sign::Positive,
        )?;
        if let Some(t) = &section.torsion {
            t.gj.validate(&field("section.GJ"), length, Sign::Positive)?;
            t.polar_inertia
                .validate(&field("section.polar_inertia"), length, Sign::NonNegative)?;
            t.offset.validate(&field("section.d0"), length, Sign::Any)?;
        }
        let n = nodes.len() - 1;
        let lengths: Vec<f64> = nodes.windows(2).map(|w| w[1] - w[0]).collect();
        let m = &section.mass_per_length;
        let bending_stiffness = calibration.bending(&section.ei, &nodes);
        let (masses, offsets, inertias, torsion_stiffness) = match &section.torsion {
            None => {
                let mut masses = vec![0.0; n];
                for_each_piece(&nodes, [m], |i, p| masses[i] += p.simpson(|v| v[0]));
                (masses, vec![0.0; n], vec![0.0; n], None)
            }
            Some(t) => {
                check_inertia_about_elastic_axis(&field("section.polar_inertia"), t, m, length)?;
                // Per element: ∫ m, ∫ m d0 and ∫ I_ea, exact (Simpson on each linear piece:
                // the integrands are polynomials of degree ≤ 3 there).
                let mut sums = vec![[0.0; 3]; n];
                let about_mass_centre = t.inertia_axis == InertiaAxis::MassCentre;
                for_each_piece(&nodes, [m, &t.offset, &t.polar_inertia], |i, p| {
                    sums[i][0] += p.simpson(|v| v[0]);
                    sums[i][1] += p.simpson(|v| v[0] * v[1]);
                    sums[i][2] += p.simpson(|v| {
                        if about_mass_centre {
                            v[2] + v[0] * v[1] * v[1]
                        } else {
                            v[2]
                        }
                    });
                });
                let mut masses = Vec::with_capacity(n);
                let mut offsets = Vec::with_capacity(n);
                let mut inertias = Vec::with_capacity(n);
                for (i, &[mass, static_moment, i_ea]) in sums.iter().enumerate() {
                    let d0 = static_moment / mass;
                    // Cauchy–Schwarz makes this non-negative up to round-off.
                    let j = (i_ea - mass * d0 * d0).max(0.0);
                    if !(i_ea > 0.0) {
                        return Err(InputError::new(
                            field("section.polar_inertia"),
                            format!(
                                "element {} (x = {}..{} m) has no torsional inertia: \
                                 polar_inertia and d0 are both zero there",
                                i + 1,
                                nodes[i],
                                nodes[i + 1]
                            ),
                        ));
                    }
                    masses.push(mass);
                    offsets.push(d0);
                    inertias.push(j);
                }
                let k = calibration::torsion(&t.gj, &nodes);
                (masses, offsets, inertias, Some(k))
            }
        };
        let beam = Self {
            length,
            nodes,
            lengths,
            masses,
            offsets,
            inertias,
            bending_inertias: vec![0.0; n],
            bending_stiffness,
            torsion_stiffness,
            calibration,
        };
        beam.check_frequencies(prefix, "section.EI")?;
        Ok(beam)
    }

    /// The same beam with rotary inertia in bending (zero before: the paper's point masses).
    /// `section` is the continuous beam's, the one [`Beam::new`] was given (its mass per length
    /// weighs the elements' bar inertia); errors are named as in [`Beam::named`], the section's
    /// rotary inertia as `{prefix}.section.rotary_inertia`.
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, RotaryInertia, SectionProperties};
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let beam = Beam::new(1.0, &section, &Discretization::Uniform(10), Calibration::TipLoad)?;
    /// let bars = RotaryInertia { elements: true, section: None };
    /// let beam = beam.with_rotary_inertia("beam", &section, &bars)?;
    /// // m ℓ² / 12 with m = 0.2 kg/m × 0.1 m and ℓ = 0.1 m.
    /// assert!((beam.bending_inertias()[3] - 0.02 * 0.01 / 12.0).abs() < 1e-18);
    /// # Ok::<(), flexwing::InputError>(())
    /// ```
    ///
    /// # Errors
    /// A negative or non-finite section rotary inertia, or one so large that an element's
    /// bending frequency leaves the range of [`Beam::new`].
    pub fn with_rotary_inertia(
        mut self,
        prefix: &str,
        section: &SectionProperties,
        rotary: &RotaryInertia,
    ) -> Result<Self, InputError> {
        let field = |key: &str| crate::field(prefix, key);
        if let Some(ri) = &rotary.section {
            ri.validate(
                &field("section.rotary_inertia"),
                self.length,
                Sign::NonNegative,
            )?;
        }
        let mut j = vec![0.0; self.n_elements()];
        let nodes = &self.nodes;
        let m = &section.mass_per_length;
        let zero = Profile::Uniform(0.0);
        let ri = rotary.section.as_ref().unwrap_or(&zero);
        // ∫ m (x − x_mid)² and ∫ ρI per piece: polynomials of degree ≤ 3, exact by Simpson.
        for_each_piece(nodes, [m, ri], |i, p| {
            let mid = 0.5 * (nodes[i] + nodes[i + 1]);
            if rotary.elements {
                // Simpson's rule in x needs the integrand at a, (a + b)/2 and b.
                let (a, b) = (p.a, p.b);
                let c = 0.5 * (a + b);
                let (ma, mb) = (p.at_a[0], p.at_b[0]);
                let mc = 0.5 * (ma + mb);
                j[i] += (b - a) / 6.0
                    * (ma * (a - mid).powi(2)
                        + 4.0 * mc * (c - mid).powi(2)
                        + mb * (b - mid).powi(2));
            }
            j[i] += p.simpson(|v| v[1]);
        });
        self.bending_inertias = j;
        // The rotary inertia only lowers the bending frequencies: out of range, it is to blame.
        self.check_frequencies(prefix, "section.rotary_inertia")?;
        Ok(self)
    }

    /// Span `L` (m).
    pub fn length(&self) -> f64 {
        self.length
    }
    /// Number of elements `n`.
    pub fn n_elements(&self) -> usize {
        self.lengths.len()
    }
    /// Node stations `x_0 = 0 … x_n = L` (m).
    pub fn nodes(&self) -> &[f64] {
        &self.nodes
    }
    /// Element lengths `ℓ_i` (m).
    pub fn lengths(&self) -> &[f64] {
        &self.lengths
    }
    /// Element masses `m_i` (kg).
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }
    /// Element mass-centre offsets `d0_i` (m); zeros for a bending-only beam.
    pub fn offsets(&self) -> &[f64] {
        &self.offsets
    }
    /// Element polar inertias about their mass centres `J_i` (kg·m²).
    pub fn inertias(&self) -> &[f64] {
        &self.inertias
    }
    /// Element rotary inertias in bending `J_b,i` about `ẑ` through the element's midpoint
    /// (kg·m²); zeros unless set by [`Beam::with_rotary_inertia`].
    pub fn bending_inertias(&self) -> &[f64] {
        &self.bending_inertias
    }

    /// The second rule of [`crate::magnitude`]: every element's frequency squared, its joint
    /// spring against its own inertia (`K_θ,i / (m_i ℓ_i² + J_b,i)` in bending, `K_ψ,i / (J_i +
    /// m_i d0_i²)` in torsion), lies within
    /// [`FREQUENCY_SQUARED`](crate::magnitude::FREQUENCY_SQUARED), so that the stiffness and mass
    /// matrices the solvers combine are within 120 decades of each other. A bending frequency
    /// outside names `{prefix}.{bending_key}`, a torsion one `{prefix}.section.GJ`.
    fn check_frequencies(&self, prefix: &str, bending_key: &str) -> Result<(), InputError> {
        let (lo, hi) = crate::magnitude::FREQUENCY_SQUARED;
        let check = |key: &str, i: usize, w2: f64, formula: &str| {
            if (lo..=hi).contains(&w2) {
                return Ok(());
            }
            Err(InputError::new(
                crate::field(prefix, key),
                format!(
                    "with the mass and length given, element {} has a frequency squared \
                     {formula} = {} (per time unit squared), outside [{lo:e}, {hi:e}]: \
                     stiffness, mass and length are out of proportion (the range accepted, \
                     docs/model-choices.md)",
                    i + 1,
                    crate::text::short(w2)
                ),
            ))
        };
        for i in 0..self.n_elements() {
            let (m, l, j_b) = (self.masses[i], self.lengths[i], self.bending_inertias[i]);
            let w2 = self.bending_stiffness[i] / (m * l * l + j_b);
            let formula = if j_b == 0.0 {
                "K_θ/(m ℓ²)"
            } else {
                "K_θ/(m ℓ² + J_b)"
            };
            check(bending_key, i, w2, formula)?;
            if let Some(k) = &self.torsion_stiffness {
                let w2 = k[i] / (self.inertias[i] + m * self.offsets[i] * self.offsets[i]);
                check("section.GJ", i, w2, "K_ψ/(J + m d0²)")?;
            }
        }
        Ok(())
    }
    /// Bending spring stiffnesses `K_θ,i` (N·m/rad), joint `i` at node `i − 1`.
    pub fn bending_stiffness(&self) -> &[f64] {
        &self.bending_stiffness
    }
    /// Torsion spring stiffnesses `K_ψ,i` (N·m/rad), or `None` for a bending-only beam.
    pub fn torsion_stiffness(&self) -> Option<&[f64]> {
        self.torsion_stiffness.as_deref()
    }
    /// Whether the beam has torsion degrees of freedom.
    pub fn has_torsion(&self) -> bool {
        self.torsion_stiffness.is_some()
    }
    /// The calibration rule used for the bending springs.
    pub fn calibration(&self) -> Calibration {
        self.calibration
    }
}

/// Largest number of elements accepted: the full model's implicit solvers keep dense `2n × 2n`
/// matrices (3.2 GB at this size) and a modal analysis of every mode is O(n³), so a larger `n`
/// would exhaust memory or time rather than give an answer. (Set-up and the lowest modes are
/// O(n) and would go further.)
pub const MAX_ELEMENTS: usize = 10_000;

pub(crate) fn stations(
    prefix: &str,
    length: f64,
    d: &Discretization,
) -> Result<Vec<f64>, InputError> {
    let field = |key: &str| crate::field(prefix, key);
    let count = match d {
        Discretization::Uniform(n) => *n,
        Discretization::Stations(x) => x.len().saturating_sub(1),
    };
    if count > MAX_ELEMENTS {
        let field = match d {
            Discretization::Uniform(_) => field("elements"),
            Discretization::Stations(_) => field("stations"),
        };
        return Err(InputError::new(
            field,
            format!("at most {MAX_ELEMENTS} elements are supported, got {count}"),
        ));
    }
    match d {
        Discretization::Uniform(n) => {
            if *n == 0 {
                return Err(InputError::new(
                    field("elements"),
                    "must be at least 1, got 0",
                ));
            }
            Ok((0..=*n).map(|i| length * i as f64 / *n as f64).collect())
        }
        Discretization::Stations(x) => {
            let f = field("stations");
            if x.len() < 2 {
                return Err(InputError::new(
                    f,
                    format!("needs at least two stations (one element), got {}", x.len()),
                ));
            }
            let tol = 1e-9 * length;
            if x[0].abs() > tol {
                return Err(InputError::new(
                    f,
                    format!("must start at 0, got {}", crate::text::short(x[0])),
                ));
            }
            let last = x[x.len() - 1];
            if !((last - length).abs() <= tol) {
                return Err(InputError::new(
                    f,
                    format!(
                        "must end at the length {}, got {}",
                        crate::text::short(length),
                        crate::text::short(last)
                    ),
                ));
            }
            for k in 1..x.len() {
                if !(x[k] > x[k - 1]) {
                    return Err(InputError::new(
                        f,
                        format!(
                            "must be strictly increasing, but x[{k}] = {} <= x[{}] = {}",
                            crate::text::short(x[k]),
                            k - 1,
                            crate::text::short(x[k - 1])
                        ),
                    ));
                }
            }
            let mut out = x.clone();
            out[0] = 0.0;
            *out.last_mut().expect("len >= 2") = length;
            Ok(out)
        }
    }
}

/// With the inertia given about the elastic axis, `I_cg = I_ea − m d0²` must not be negative.
fn check_inertia_about_elastic_axis(
    field: &str,
    t: &TorsionProperties,
    m: &Profile,
    length: f64,
) -> Result<(), InputError> {
    if t.inertia_axis != InertiaAxis::ElasticAxis {
        return Ok(());
    }
    // I_ea − m d0² is piecewise quadratic: sampling each piece densely finds a negative value.
    let mut xs = vec![0.0, length];
    for p in [&t.polar_inertia, m, &t.offset] {
        if let Profile::Table { x, .. } = p {
            xs.extend(x.iter().copied().filter(|&s| s > 0.0 && s < length));
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    for w in xs.windows(2) {
        for k in 0..=16 {
            let x = w[0] + (w[1] - w[0]) * k as f64 / 16.0;
            let i_cg = t.polar_inertia.at(x) - m.at(x) * t.offset.at(x).powi(2);
            if i_cg < -1e-12 * t.polar_inertia.at(x).abs().max(1e-300) {
                return Err(InputError::new(
                    field,
                    format!(
                        "about the elastic axis it must be at least m·d0², but at x = {} m \
                         I_ea = {} and m·d0² = {} (negative inertia about the mass centre)",
                        crate::text::short(x),
                        crate::text::short(t.polar_inertia.at(x)),
                        crate::text::short(m.at(x) * t.offset.at(x).powi(2))
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::profile::integrate;
    use super::*;

    /// A table over `[0, l]` with `points` stations (its own set for each property, so that the
    /// pieces of different properties interleave).
    fn table(l: f64, points: usize, f: impl Fn(f64) -> f64) -> Profile {
        let x: Vec<f64> = (0..points)
            .map(|k| l * (k as f64 / (points - 1) as f64).powf(1.3))
            .collect();
        let value = x.iter().map(|&s| f(s)).collect();
        Profile::Table { x, value }
    }

    #[test]
    fn element_data_equal_the_quadrature_they_replaced() {
        // Regression against the former adaptive Gauss–Legendre quadrature (1e-14 relative) of
        // the definitions ∫ m, ∫ m d0 / m_i, ∫ I_ea − m_i d0_i², for both inertia axes, tables
        // of 57, 31 and 23 stations cut into 13 uneven elements.
        let l = 3.0;
        let m = table(l, 57, |s| 1.2 - 0.2 * s + 0.05 * (5.0 * s).sin());
        let d = table(l, 31, |s| 0.1 + 0.03 * (3.0 * s).cos());
        let ip = table(l, 23, |s| 0.2 - 0.04 * s);
        let stations: Vec<f64> = (0..=13).map(|k| l * (k as f64 / 13.0).powf(0.8)).collect();
        for axis in [InertiaAxis::MassCentre, InertiaAxis::ElasticAxis] {
            let section = SectionProperties {
                ei: Profile::Uniform(10.0),
                mass_per_length: m.clone(),
                torsion: Some(TorsionProperties {
                    gj: Profile::Uniform(5.0),
                    polar_inertia: ip.clone(),
                    inertia_axis: axis,
                    offset: d.clone(),
                }),
            };
            let beam = Beam::new(
                l,
                &section,
                &Discretization::Stations(stations.clone()),
                Calibration::TipLoad,
            )
            .unwrap();
            for (i, w) in stations.windows(2).enumerate() {
                let (a, b) = (w[0], w[1]);
                let ps = [&m, &d, &ip];
                let mass = integrate(&ps, a, b, |x| m.at(x));
                let d0 = integrate(&ps, a, b, |x| m.at(x) * d.at(x)) / mass;
                let i_ea = integrate(&ps, a, b, |x| match axis {
                    InertiaAxis::MassCentre => ip.at(x) + m.at(x) * d.at(x).powi(2),
                    InertiaAxis::ElasticAxis => ip.at(x),
                });
                let j = i_ea - mass * d0 * d0;
                // Simpson is exact for these cubics; what differs is round-off (measured
                // ≤ 3.4e-16); bound 1e-13.
                for (got, want) in [
                    (beam.masses()[i], mass),
                    (beam.offsets()[i], d0),
                    (beam.inertias()[i], j),
                ] {
                    assert!(
                        (got / want - 1.0).abs() < 1e-13,
                        "element {i}: {got} vs {want}"
                    );
                }
            }
        }
    }
}
