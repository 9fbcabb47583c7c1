//! [`Beam3d`]: the 3-D chain's validated, resolved per-element data — reference geometry, joint
//! stiffness matrices, masses, mass-centre arms and inertias (docs/chain3d-model.md, "Data" and
//! "Joint stiffness"). All input validation happens here and returns `InputError { field,
//! reason }` with the caller's prefix, as `Beam::new` does.

use super::algebra::{cholesky, cholesky_inverse, madd, mm, mtm, M3, V3};
use super::geometry::{Geometry3d, Reference};
use super::section::{ElementInertia, JointCalibration, SectionInertia, SectionStiffness};
use crate::beam::calibration::flexibilities;
use crate::beam::profile::{for_each_piece, integrate, Sign};
use crate::beam::{Calibration, InertiaAxis, Profile};
use crate::error::InputError;

/// The 3-D chain's beam: `n` rigid elements on the reference geometry, `n` three-axis joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam3d {
    pub(crate) reference: Reference,
    /// Element masses `m_i` (kg).
    pub(crate) masses: Vec<f64>,
    /// Mass centre of element `i` from its inboard node, in its frame: `(ℓ_i/2, d̄_n, d̄_c)`.
    pub(crate) arms: Vec<V3<f64>>,
    /// Inertia of element `i` about its mass centre in its frame `(t, n, c)` (kg·m²), diagonal.
    pub(crate) inertias: Vec<[f64; 3]>,
    /// Joint stiffness `K_i` in the frame of element `i` (N·m/rad), symmetric positive definite.
    pub(crate) stiffness: Vec<M3<f64>>,
    pub(crate) calibration: JointCalibration,
}

/// The section stiffness matrix at `s`.
fn section_matrix(st: &SectionStiffness, s: f64) -> M3<f64> {
    let (gj, en, ec) = (st.gj.at(s), st.ei_lag.at(s), st.ei_flap.at(s));
    let (tn, tc, nc) = match &st.coupling {
        None => (0.0, 0.0, 0.0),
        Some(k) => (k.twist_lag.at(s), k.twist_flap.at(s), k.lag_flap.at(s)),
    };
    [[gj, tn, tc], [tn, en, nc], [tc, nc, ec]]
}

/// Stations of the tables among `profiles`, inside `(0, length)`, with `0` and `length`.
fn breakpoints(profiles: &[&Profile], length: f64) -> Vec<f64> {
    let mut xs = vec![0.0, length];
    for p in profiles {
        if let Profile::Table { x, .. } = p {
            xs.extend(x.iter().copied().filter(|&s| s > 0.0 && s < length));
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.dedup();
    xs
}

impl Beam3d {
    /// Validate and resolve a 3-D chain's beam; errors name `beam.…` ([`Beam3d::named`]).
    ///
    /// # Errors
    /// See [`Beam3d::named`].
    pub fn new(
        geometry: &Geometry3d,
        stiffness: &SectionStiffness,
        inertia: &SectionInertia,
        calibration: JointCalibration,
    ) -> Result<Self, InputError> {
        Self::named("beam", geometry, stiffness, inertia, calibration)
    }

    /// [`Beam3d::new`] with the errors' field names under `prefix` (`beam` gives
    /// `beam.section.GJ`, `beam.points`, …).
    ///
    /// # Errors
    /// A geometry that is not finite, has fewer than one element or zero-length elements, a
    /// curve that does not start at the root or whose normals lie along it; a stiffness or mass
    /// that is not positive, a section stiffness matrix that is not positive definite, an
    /// inertia that is negative (about the mass centre) or leaves an element without torsional
    /// inertia; the tip-load calibration on a geometry or section where the axes mix; element
    /// frequencies outside the accepted range.
    pub fn named(
        prefix: &str,
        geometry: &Geometry3d,
        stiffness: &SectionStiffness,
        inertia: &SectionInertia,
        calibration: JointCalibration,
    ) -> Result<Self, InputError> {
        let field = |key: &str| crate::field(prefix, key);
        let reference = Reference::new(prefix, geometry)?;
        let length = reference.length();
        let nodes = reference.nodes.clone();
        let n = nodes.len() - 1;
        // Stiffness.
        stiffness
            .gj
            .validate(&field("section.GJ"), length, Sign::Positive)?;
        stiffness
            .ei_flap
            .validate(&field("section.EI_flap"), length, Sign::Positive)?;
        stiffness
            .ei_lag
            .validate(&field("section.EI_lag"), length, Sign::Positive)?;
        let mut all: Vec<&Profile> = vec![&stiffness.gj, &stiffness.ei_flap, &stiffness.ei_lag];
        if let Some(k) = &stiffness.coupling {
            k.twist_flap
                .validate(&field("section.twist_flap"), length, Sign::Any)?;
            k.twist_lag
                .validate(&field("section.twist_lag"), length, Sign::Any)?;
            k.lag_flap
                .validate(&field("section.lag_flap"), length, Sign::Any)?;
            all.extend([&k.twist_flap, &k.twist_lag, &k.lag_flap]);
            // C(s) is linear between consecutive stations of the tables, and a convex
            // combination of positive definite matrices is positive definite: checking the
            // stations suffices.
            for s in breakpoints(&all, length) {
                if cholesky(&section_matrix(stiffness, s)).is_none() {
                    return Err(InputError::new(
                        field("section"),
                        format!(
                            "the section stiffness matrix is not positive definite at s = {} m: \
                             the coupling terms are too large for GJ, EI_flap and EI_lag there",
                            crate::text::short(s)
                        ),
                    ));
                }
            }
        }
        // Half-element compliances S⁻_i = ∫_{s_i}^{mid_i} C⁻¹, S⁺_i = ∫_{mid_i}^{s_{i+1}} C⁻¹,
        // each in the frame of element i (the section frame's rotation inside an element, by
        // the pretwist rate, is left out: an O(ℓ²) term; docs/chain3d-model.md).
        let mut bounds = Vec::with_capacity(2 * n + 1);
        for i in 0..n {
            bounds.push(nodes[i]);
            bounds.push(0.5 * (nodes[i] + nodes[i + 1]));
        }
        bounds.push(nodes[n]);
        let halves: Vec<M3<f64>> = match &stiffness.coupling {
            None => {
                let ft = flexibilities(&stiffness.gj, &bounds);
                let fnn = flexibilities(&stiffness.ei_lag, &bounds);
                let fc = flexibilities(&stiffness.ei_flap, &bounds);
                (0..2 * n)
                    .map(|k| [[ft[k], 0.0, 0.0], [0.0, fnn[k], 0.0], [0.0, 0.0, fc[k]]])
                    .collect()
            }
            Some(_) => bounds
                .windows(2)
                .map(|w| {
                    let mut s = [[0.0; 3]; 3];
                    for r in 0..3 {
                        for c in r..3 {
                            let v = integrate(&all, w[0], w[1], |x| {
                                let inv = cholesky(&section_matrix(stiffness, x))
                                    .map(|l| cholesky_inverse(&l))
                                    .unwrap_or([[f64::NAN; 3]; 3]);
                                inv[r][c]
                            });
                            s[r][c] = v;
                            s[c][r] = v;
                        }
                    }
                    s
                })
                .collect(),
        };
        let mut joint_stiffness = Vec::with_capacity(n);
        for i in 0..n {
            let mut s = halves[2 * i];
            if i > 0 {
                // The outboard half of element i − 1, turned into the frame of element i.
                let r0 = &reference.relative[i];
                s = madd(&mtm(r0, &mm(&halves[2 * i - 1], r0)), &s);
            }
            for r in 0..3 {
                for c in 0..r {
                    let m = 0.5 * (s[r][c] + s[c][r]);
                    s[r][c] = m;
                    s[c][r] = m;
                }
            }
            let k = cholesky(&s).map(|l| cholesky_inverse(&l)).ok_or_else(|| {
                InputError::new(
                    field("section"),
                    format!("joint {} has a singular compliance", i + 1),
                )
            })?;
            joint_stiffness.push(k);
        }
        if calibration == JointCalibration::TipLoad {
            if !reference.straight || stiffness.coupling.is_some() {
                return Err(InputError::new(
                    field("calibration"),
                    "the tip-load calibration needs a straight, untwisted reference axis and an \
                     uncoupled section (the bending axes would mix); use the compliance \
                     calibration",
                ));
            }
            let lag = Calibration::TipLoad.bending(&stiffness.ei_lag, &nodes);
            let flap = Calibration::TipLoad.bending(&stiffness.ei_flap, &nodes);
            for i in 0..n {
                let t = joint_stiffness[i][0][0];
                joint_stiffness[i] = [[t, 0.0, 0.0], [0.0, lag[i], 0.0], [0.0, 0.0, flap[i]]];
            }
        }
        // Mass.
        let m = &inertia.mass_per_length;
        m.validate(&field("section.mass_per_length"), length, Sign::Positive)?;
        inertia.polar_inertia.validate(
            &field("section.polar_inertia"),
            length,
            Sign::NonNegative,
        )?;
        inertia
            .d0
            .validate(&field("section.d0"), length, Sign::Any)?;
        inertia
            .d0_normal
            .validate(&field("section.d0_normal"), length, Sign::Any)?;
        inertia.rotary_inertia_flap.validate(
            &field("section.rotary_inertia_flap"),
            length,
            Sign::NonNegative,
        )?;
        inertia.rotary_inertia_lag.validate(
            &field("section.rotary_inertia_lag"),
            length,
            Sign::NonNegative,
        )?;
        if inertia.polar_inertia_about == InertiaAxis::ElasticAxis {
            check_elastic_axis_inertia(&field("section.polar_inertia"), inertia, length)?;
        }
        let about_mass_centre = inertia.polar_inertia_about == InertiaAxis::MassCentre;
        // Per element: ∫ m, ∫ m d0, ∫ m d0_n, ∫ I_ea, ∫ ρI_flap, ∫ ρI_lag, ∫ m (s − s_mid)²:
        // polynomials of degree ≤ 3 on each linear piece, exact by Simpson's rule.
        let mut sums = vec![[0.0; 7]; n];
        let profiles = [
            m,
            &inertia.d0,
            &inertia.d0_normal,
            &inertia.polar_inertia,
            &inertia.rotary_inertia_flap,
            &inertia.rotary_inertia_lag,
        ];
        for_each_piece(&nodes, profiles, |i, p| {
            sums[i][0] += p.simpson(|v| v[0]);
            sums[i][1] += p.simpson(|v| v[0] * v[1]);
            sums[i][2] += p.simpson(|v| v[0] * v[2]);
            sums[i][3] += p.simpson(|v| {
                if about_mass_centre {
                    v[3] + v[0] * (v[1] * v[1] + v[2] * v[2])
                } else {
                    v[3]
                }
            });
            sums[i][4] += p.simpson(|v| v[4]);
            sums[i][5] += p.simpson(|v| v[5]);
            let mid = 0.5 * (nodes[i] + nodes[i + 1]);
            let (a, b) = (p.a, p.b);
            let c = 0.5 * (a + b);
            let (ma, mb) = (p.at_a[0], p.at_b[0]);
            let mc = 0.5 * (ma + mb);
            sums[i][6] += (b - a) / 6.0
                * (ma * (a - mid).powi(2) + 4.0 * mc * (c - mid).powi(2) + mb * (b - mid).powi(2));
        });
        let bar = inertia.element_inertia == ElementInertia::Bar;
        let (mut masses, mut arms, mut inertias) = (
            Vec::with_capacity(n),
            Vec::with_capacity(n),
            Vec::with_capacity(n),
        );
        for (i, s) in sums.iter().enumerate() {
            let mass = s[0];
            let (dc, dn) = (s[1] / mass, s[2] / mass);
            let i_ea = s[3];
            if !(i_ea > 0.0) {
                return Err(InputError::new(
                    field("section.polar_inertia"),
                    format!(
                        "element {} (s = {}..{} m) has no torsional inertia: polar_inertia, d0 \
                         and d0_normal are all zero there",
                        i + 1,
                        crate::text::short(nodes[i]),
                        crate::text::short(nodes[i + 1])
                    ),
                ));
            }
            // Cauchy–Schwarz makes this non-negative up to round-off.
            let j_t = (i_ea - mass * (dc * dc + dn * dn)).max(0.0);
            let bar_term = if bar { s[6] } else { 0.0 };
            masses.push(mass);
            arms.push([0.5 * reference.lengths[i], dn, dc]);
            inertias.push([j_t, bar_term + s[5], bar_term + s[4]]);
        }
        let beam = Self {
            reference,
            masses,
            arms,
            inertias,
            stiffness: joint_stiffness,
            calibration,
        };
        beam.check_frequencies(prefix)?;
        Ok(beam)
    }

    /// Every element's frequency squared per axis within the accepted range (as `Beam`).
    fn check_frequencies(&self, prefix: &str) -> Result<(), InputError> {
        let (lo, hi) = crate::magnitude::FREQUENCY_SQUARED;
        for i in 0..self.n_elements() {
            let (m, l) = (self.masses[i], self.reference.lengths[i]);
            let a = self.arms[i];
            let j = self.inertias[i];
            let k = &self.stiffness[i];
            for (axis, key, w2) in [
                (
                    "twist",
                    "section.GJ",
                    k[0][0] / (j[0] + m * (a[1] * a[1] + a[2] * a[2])),
                ),
                ("lag", "section.EI_lag", k[1][1] / (m * l * l + j[1])),
                ("flap", "section.EI_flap", k[2][2] / (m * l * l + j[2])),
            ] {
                if !(lo..=hi).contains(&w2) {
                    return Err(InputError::new(
                        crate::field(prefix, key),
                        format!(
                            "with the mass and length given, element {} has a {axis} frequency \
                             squared {} (per time unit squared), outside [{lo:e}, {hi:e}]: \
                             stiffness, mass and length are out of proportion (the range \
                             accepted, docs/model-choices.md)",
                            i + 1,
                            crate::text::short(w2)
                        ),
                    ));
                }
            }
        }
        Ok(())
    }

    /// Arc length of the reference axis `L` (m).
    pub fn length(&self) -> f64 {
        self.reference.length()
    }
    /// Number of elements `n`.
    pub fn n_elements(&self) -> usize {
        self.masses.len()
    }
    /// Node stations along the reference axis `s_0 = 0 … s_n = L` (m).
    pub fn nodes(&self) -> &[f64] {
        &self.reference.nodes
    }
    /// Element lengths `ℓ_i` (m).
    pub fn lengths(&self) -> &[f64] {
        &self.reference.lengths
    }
    /// Element masses `m_i` (kg).
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }
    /// Mass centre of each element from its inboard node in its frame `(t, n, c)` (m).
    pub fn mass_centre_arms(&self) -> &[[f64; 3]] {
        &self.arms
    }
    /// Inertia of each element about its mass centre, `(J_t, J_n, J_c)` in its frame (kg·m²).
    pub fn inertias(&self) -> &[[f64; 3]] {
        &self.inertias
    }
    /// Joint stiffness matrices `K_i` in the frame of element `i` (N·m/rad).
    pub fn joint_stiffness(&self) -> &[[[f64; 3]; 3]] {
        &self.stiffness
    }
    /// Reference node positions `P_0 … P_n` (m).
    pub fn reference_positions(&self) -> &[[f64; 3]] {
        &self.reference.positions
    }
    /// Reference frame of each element, columns `t, n, c` (global components).
    pub fn reference_frames(&self) -> &[[[f64; 3]; 3]] {
        &self.reference.frames
    }
    /// The joint calibration.
    pub fn calibration(&self) -> JointCalibration {
        self.calibration
    }
}

/// With the polar inertia given about the elastic axis, `I_cg = I_ea − m (d0² + d0_n²)` must not
/// be negative: it is piecewise quadratic, so dense sampling of each piece finds a negative value.
fn check_elastic_axis_inertia(
    field: &str,
    inertia: &SectionInertia,
    length: f64,
) -> Result<(), InputError> {
    let m = &inertia.mass_per_length;
    let xs = breakpoints(
        &[&inertia.polar_inertia, m, &inertia.d0, &inertia.d0_normal],
        length,
    );
    for w in xs.windows(2) {
        for k in 0..=16 {
            let x = w[0] + (w[1] - w[0]) * k as f64 / 16.0;
            let ea = inertia.polar_inertia.at(x);
            let md2 = m.at(x) * (inertia.d0.at(x).powi(2) + inertia.d0_normal.at(x).powi(2));
            if ea - md2 < -1e-12 * ea.abs().max(1e-300) {
                return Err(InputError::new(
                    field,
                    format!(
                        "about the elastic axis it must be at least m·(d0² + d0_normal²), but \
                         at s = {} m I_ea = {} and m·(d0² + d0_normal²) = {} (negative inertia \
                         about the mass centre)",
                        crate::text::short(x),
                        crate::text::short(ea),
                        crate::text::short(md2)
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::Discretization;

    fn uniform_beam(n: usize, geometry: Geometry3d) -> Beam3d {
        Beam3d::new(
            &geometry,
            &SectionStiffness::uncoupled(3.0, 5.0, 7.0),
            &SectionInertia::uniform(2.0, 0.1),
            JointCalibration::Compliance,
        )
        .unwrap_or_else(|e| panic!("{e}; n = {n}"))
    }

    #[test]
    fn a_straight_uniform_beam_has_the_midpoint_springs() {
        let b = uniform_beam(4, Geometry3d::straight(2.0, 4));
        let l = 0.5;
        // 2C/ℓ at the root (half an element to the clamp), C/ℓ between midpoints.
        for (i, k) in b.joint_stiffness().iter().enumerate() {
            let f = if i == 0 { 2.0 } else { 1.0 };
            let want = [3.0, 7.0, 5.0].map(|c| f * c / l);
            for a in 0..3 {
                assert!((k[a][a] / want[a] - 1.0).abs() < 1e-14, "{k:?}");
            }
        }
        // Bars: J_n = J_c = m ℓ³/12; J_t = I ℓ.
        let j = b.inertias()[1];
        assert!((j[1] - 2.0 * l.powi(3) / 12.0).abs() < 1e-15 && (j[0] - 0.1 * l).abs() < 1e-16);
    }

    #[test]
    fn a_kink_mixes_the_axes_in_one_frame() {
        // Sweep table with a kink: outboard of s = 1 the axis turns by 0.4 rad about n.
        let geometry = Geometry3d::Span {
            length: 2.0,
            discretization: Discretization::Uniform(2),
            sweep: Profile::Table {
                x: vec![0.0, 0.75, 1.25, 2.0],
                value: vec![0.0, 0.0, 0.4, 0.4],
            },
            dihedral: Profile::Uniform(0.0),
            pretwist: Profile::Uniform(0.0),
        };
        let b = uniform_beam(2, geometry);
        let k = b.joint_stiffness()[1];
        // The inboard half's twist and flap compliances rotate by the relative sweep (about n):
        // twist and flap couple.
        let (c, s) = (0.4f64.cos(), 0.4f64.sin());
        let half = 0.5;
        let inner = [
            [half / 3.0, 0.0, 0.0],
            [0.0, half / 7.0, 0.0],
            [0.0, 0.0, half / 5.0],
        ];
        let r0 = [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]];
        let mut want = madd(&mtm(&r0, &mm(&inner, &r0)), &inner);
        want = cholesky_inverse(&cholesky(&want).unwrap());
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (k[i][j] - want[i][j]).abs() < 1e-12 * want[0][0],
                    "{k:?} vs {want:?}"
                );
            }
        }
        assert!(k[0][2].abs() > 1e-3 * k[0][0]);
    }

    #[test]
    fn bad_input_names_the_field() {
        let geometry = Geometry3d::straight(1.0, 4);
        let e = Beam3d::new(
            &geometry,
            &SectionStiffness::uncoupled(-1.0, 1.0, 1.0),
            &SectionInertia::uniform(1.0, 0.1),
            JointCalibration::Compliance,
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.section.GJ");
        let e = Beam3d::new(
            &geometry,
            &SectionStiffness::uncoupled(1.0, 1.0, 1.0),
            &SectionInertia::uniform(1.0, 0.0),
            JointCalibration::Compliance,
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.section.polar_inertia");
        let mut st = SectionStiffness::uncoupled(1.0, 1.0, 1.0);
        st.coupling = Some(super::super::section::StiffnessCoupling {
            twist_flap: Profile::Uniform(1.5),
            twist_lag: Profile::Uniform(0.0),
            lag_flap: Profile::Uniform(0.0),
        });
        let e = Beam3d::new(
            &geometry,
            &st,
            &SectionInertia::uniform(1.0, 0.1),
            JointCalibration::Compliance,
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.section");
        let swept = Geometry3d::Span {
            length: 1.0,
            discretization: Discretization::Uniform(4),
            sweep: Profile::Uniform(0.1),
            dihedral: Profile::Uniform(0.0),
            pretwist: Profile::Uniform(0.0),
        };
        let e = Beam3d::new(
            &swept,
            &SectionStiffness::uncoupled(1.0, 1.0, 1.0),
            &SectionInertia::uniform(1.0, 0.1),
            JointCalibration::TipLoad,
        )
        .unwrap_err();
        assert_eq!(e.field, "beam.calibration");
    }
}
