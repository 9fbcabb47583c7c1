//! Strip aerodynamics on the 3-D chain (docs/chain3d-model.md, "Strip aerodynamics"; working
//! notes `../shared/docs/chain3d.md` §6), generic over the scalar so that dual numbers give its
//! exact derivatives, as the planar chain's strips (`chain.rs`, `strip.rs`).
//!
//! Strip `i` is element `i`: its elastic-axis point `X_i = P_i + ½ d_i` (the element's
//! midpoint), width `ℓ_i`, section frame `R_i = (t, n, c)`: `t` the span, `n` the section normal
//! (the planar model's `ν`), `c` the chord toward the leading edge (the planar model's chord
//! direction `t`). The section point at chord station `ζ` is `X_i + ζ c_i`, its velocity
//! `Ẋ(ζ) = ċ_i + ω_i × ζ c_i`. The relative wind `W = V∞ + V_g − Ẋ` is resolved in the section
//! frame and its spanwise component (along `t`) discarded (the independence principle): with
//! `(ω × c)·n = −ω·t` and `(ω × c)·c = 0`,
//!
//! ```text
//! W_T = −(V∞ + V_g)·c + ċ·c                          chordwise, leading to trailing edge
//! w   = (V∞ + V_g − ċ)·n + b(½ − a) ψ̇,   ψ̇ = −ω·t    upwash through the three-quarter chord
//! ```
//!
//! exactly the planar formulas of docs/aeroelastic-model.md §2 with `(t, ν, ψ̇) → (c, n, −ω·t)`.
//! The loads per unit span are the planar ones in that frame (`strip::section_loads`): lift ⟂
//! the in-plane relative wind, drag along it, both at the aerodynamic centre, the moment about
//! `t`; so drag and the tilt of the lift now load lag bending. The strip's force `P_i = ℓ_i F_i`
//! at `X_i` and nose-up moment `ℓ_i M_i` (the moment vector `−ℓ_i M_i t_i`) give the generalized
//! forces `Q_j = H_jᵀ N_j`, `N_j` the moment about `P_j` of every strip outboard of node `j`
//! (virtual work, as `chain3d/loads.rs`), one sweep from the tip.

use num_dual::{Dual64, DualNum};

use super::strip::{section_loads, Air, StripData};
use crate::model::chain3d::algebra::{add, column, cross, dot, lift, mtv, mv, scale, sub, V3};
use crate::model::chain3d::kinematics::Frames;
use crate::model::Chain3d;

/// The 3-D chain's part of a strip evaluation for scalar `D`.
#[derive(Debug, Clone)]
pub(crate) struct SpatialStrips<D> {
    /// The chain's kinematics at the configuration.
    pub(crate) fr: Frames<D>,
    /// Velocity `ċ_i` of each strip's elastic-axis point (global components).
    pub(crate) cdot: Vec<V3<D>>,
    /// Nose-up pitch rate `ψ̇_i = −ω_i·t_i`.
    pub(crate) pitch_rate: Vec<D>,
    /// The configuration `x` (a dual one along a direction).
    x: Vec<D>,
    /// Leading elements of `fr` that hold the real frames of the base configuration (the
    /// directional derivatives along consecutive joints, from the first, re-lift only the
    /// elements in between).
    lifted: usize,
    own_f: Vec<V3<D>>,
    own_n: Vec<V3<D>>,
}

impl<D: DualNum<Primitive = f64> + Copy> SpatialStrips<D> {
    pub(crate) fn new(n: usize) -> Self {
        let z = [D::from(0.0); 3];
        Self {
            fr: Frames::new(n),
            cdot: vec![z; n],
            pitch_rate: vec![D::from(0.0); n],
            x: vec![D::from(0.0); 3 * n],
            lifted: 0,
            own_f: vec![z; n],
            own_n: vec![z; n],
        }
    }
}

impl Chain3d {
    /// The kinematics of the joint rotations `q` into `sp`.
    pub(crate) fn strip_configuration<D: DualNum<Primitive = f64> + Copy>(
        &self,
        q: &[D],
        sp: &mut SpatialStrips<D>,
    ) {
        self.configure_from(q, &mut sp.fr, 0, false);
    }

    /// The kinematics along `q + ε v` (dual numbers) into `sp`, from those of `q` in `base`:
    /// the elements inboard of the first joint `v` moves are `base`'s (O(n) copies), the rest
    /// is configured with dual numbers.
    pub(crate) fn strip_configuration_along(
        &self,
        base: &SpatialStrips<f64>,
        q: &[f64],
        v: &[f64],
        sp: &mut SpatialStrips<Dual64>,
    ) {
        for ((x, &a), &b) in sp.x.iter_mut().zip(q).zip(v) {
            *x = Dual64::new(a, b);
        }
        let start = v.iter().position(|&e| e != 0.0).map_or(self.n, |k| k / 3);
        // A direction from the first joint starts a new set (a new base): nothing is lifted.
        if start == 0 {
            sp.lifted = 0;
        }
        if start > sp.lifted {
            sp.fr.lift_range(&base.fr, sp.lifted, start, false);
        }
        if start < self.n {
            self.configure_from(&sp.x, &mut sp.fr, start, false);
        }
        sp.lifted = start;
    }

    /// The real configuration of `base` as a dual one (derivatives along the rates).
    pub(crate) fn strip_freeze(&self, base: &SpatialStrips<f64>, sp: &mut SpatialStrips<Dual64>) {
        sp.fr.lift_range(&base.fr, 0, self.n, false);
        sp.lifted = self.n;
    }

    /// The strips' velocities `ċ_i` and pitch rates `ψ̇_i` for the joint rates `qdot` at the
    /// configuration in `sp`: `ω_i = ω_{i−1} + H_i φ̇_i`, `ċ_i = V_i + ω_i × ½ d_i`,
    /// `V_{i+1} = V_i + ω_i × d_i`. O(n).
    pub(crate) fn strip_rates<D: DualNum<Primitive = f64> + Copy>(
        &self,
        qdot: &[D],
        sp: &mut SpatialStrips<D>,
    ) {
        let fr = &sp.fr;
        let zero = [D::from(0.0); 3];
        let (mut omega, mut v) = (zero, zero);
        for i in 0..self.n {
            let rate = [qdot[3 * i], qdot[3 * i + 1], qdot[3 * i + 2]];
            omega = add(&omega, &mv(&fr.h[i], &rate));
            let half = scale(D::from(0.5), &fr.d[i]);
            sp.cdot[i] = add(&v, &cross(&omega, &half));
            sp.pitch_rate[i] = -dot(&omega, &column(&fr.r[i], 0));
            v = add(&v, &cross(&omega, &fr.d[i]));
        }
    }
}

/// Upwash at the three-quarter chord `w` and chordwise relative speed `W_T` of strip `i`;
/// `steady` drops the section's own velocity (geometry only).
pub(crate) fn flow<D: DualNum<Primitive = f64> + Copy>(
    s: &StripData,
    sp: &SpatialStrips<D>,
    i: usize,
    air: &Air,
    steady: bool,
) -> (D, D) {
    let r = &sp.fr.r[i];
    let (n, c) = (column(r, 1), column(r, 2));
    let wind: V3<D> = lift(&air.wind);
    let (wind_n, wind_c) = (dot(&wind, &n), dot(&wind, &c));
    if steady {
        return (wind_n, -wind_c);
    }
    let cd = &sp.cdot[i];
    let w = wind_n - dot(cd, &n) + sp.pitch_rate[i] * (s.b * (0.5 - s.a));
    let wt = -wind_c + dot(cd, &c);
    (w, wt)
}

/// Loads per unit span on strip `i` (`strip::section_loads` in the section frame): the force
/// (global components) and the nose-up moment about the elastic axis.
pub(crate) fn loads<D: DualNum<Primitive = f64> + Copy>(
    s: &StripData,
    sp: &SpatialStrips<D>,
    i: usize,
    air: &Air,
    density: f64,
    flow: (D, D, D),
    unsteady: bool,
) -> ([D; 3], D) {
    let r = &sp.fr.r[i];
    let frame = (column(r, 2), column(r, 1), sp.pitch_rate[i]);
    section_loads(s, frame, air, density, flow, unsteady)
}

/// The generalized forces of the strip loads `force`, `moment` (per unit span; widths from
/// `strips`) in the chain's joint coordinates into `out`, one sweep from the tip.
pub(crate) fn assemble<D: DualNum<Primitive = f64> + Copy>(
    strips: &[StripData],
    sp: &mut SpatialStrips<D>,
    force: &[[D; 3]],
    moment: &[D],
    out: &mut [D],
) {
    let fr = &sp.fr;
    let n = strips.len();
    for i in 0..n {
        let w = strips[i].width;
        let p = scale(D::from(w), &force[i]);
        let t = column(&fr.r[i], 0);
        let half = scale(D::from(0.5), &fr.d[i]);
        sp.own_n[i] = add(&scale(-(moment[i] * w), &t), &cross(&half, &p));
        sp.own_f[i] = p;
    }
    let zero = [D::from(0.0); 3];
    let (mut f, mut m) = (zero, zero);
    for j in (0..n).rev() {
        m = add(&add(&m, &cross(&fr.d[j], &f)), &sp.own_n[j]);
        f = add(&f, &sp.own_f[j]);
        out[3 * j..3 * j + 3].copy_from_slice(&mtv(&fr.h[j], &m));
    }
}

/// The generalized forces of strip `i`'s force `dp` (N) at its elastic-axis point and nose-up
/// moment `dm` (N·m) into `out` (zero beyond joint `i`): `Q_j = H_jᵀ (−dm t_i + (X_i − P_j) ×
/// dp)`, `j ≤ i`.
pub(crate) fn strip_load(
    sp: &SpatialStrips<f64>,
    i: usize,
    dp: [f64; 3],
    dm: f64,
    out: &mut [f64],
) {
    let fr = &sp.fr;
    out.fill(0.0);
    let x = add(&fr.p[i], &scale(0.5, &fr.d[i]));
    let own = scale(-dm, &column(&fr.r[i], 0));
    for j in 0..=i {
        let arm = sub(&x, &fr.p[j]);
        let moment = add(&own, &cross(&arm, &dp));
        out[3 * j..3 * j + 3].copy_from_slice(&mtv(&fr.h[j], &moment));
    }
}

#[cfg(test)]
mod tests {
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::aero::{AeroScratch, AeroSection, Aerodynamics, Aeroelastic, Air};
    use crate::model::chain3d::{
        Beam3d, ElementInertia, Geometry3d, JointCalibration, SectionInertia, SectionStiffness,
    };
    use crate::model::{Chain3d, FullModel};

    /// The planar limit of the 3-D strips: a straight, untwisted wing in a planar motion (flap
    /// bending only, or twist only) has the planar chain's upwash, chordwise speed and flap and
    /// twist generalized forces, to round-off, with a root angle, a gust and every load term
    /// (lift, drag, `c_m0`, the non-circulatory rate term). (A consistency test between two
    /// codes of the same theory: the planar strips are validated in `strip.rs` by hand and in
    /// `tests/suite/aero_*.rs` against independent references.)
    #[test]
    fn planar_motions_give_the_planar_strips() {
        let n = 5;
        let section = SectionProperties {
            ei: Profile::Uniform(400.0),
            mass_per_length: Profile::Uniform(1.0),
            torsion: Some(TorsionProperties {
                gj: Profile::Uniform(150.0),
                polar_inertia: Profile::Uniform(0.02),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.0),
            }),
        };
        let beam = Beam::new(
            3.0,
            &section,
            &Discretization::Uniform(n),
            Calibration::TipLoad,
        )
        .unwrap();
        let full = FullModel::new(beam);
        let chain = Chain3d::new(
            Beam3d::new(
                &Geometry3d::straight(3.0, n),
                &SectionStiffness::uncoupled(150.0, 400.0, 3000.0),
                &SectionInertia {
                    element_inertia: ElementInertia::Point,
                    ..SectionInertia::uniform(1.0, 0.02)
                },
                JointCalibration::TipLoad,
            )
            .unwrap(),
        );
        let aero = AeroSection {
            chord: Profile::Table {
                x: vec![0.0, 3.0],
                value: vec![0.5, 0.3],
            },
            elastic_axis: Profile::Uniform(0.35),
            lift_slope: Profile::Uniform(5.8),
            zero_lift_angle: Profile::Uniform(-0.03),
            cm0: Profile::Uniform(-0.02),
            cd0: Profile::Uniform(0.01),
            surfaces: Vec::new(),
        };
        let am = Aerodynamics::Wagner;
        let planar = Aeroelastic::new(&full, &aero, 1.1, am, "a").unwrap();
        let spatial = Aeroelastic::spatial(&chain, &aero, 1.1, am, "a").unwrap();
        let mut air = vec![Air::default(); n];
        let gust: Vec<f64> = (0..n).map(|i| 0.3 + 0.1 * i as f64).collect();
        planar.air_into(12.0, 0.04, &gust, &mut air);
        for twist in [false, true] {
            // Planar coordinates (bending, then twist) and the 3-D ones: φ = (−ψ, 0, θ).
            let (mut q, mut qd) = (vec![0.0; 2 * n], vec![0.0; 2 * n]);
            let (mut x, mut xd) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
            for i in 0..n {
                let (a, b) = (0.1 * (1.0 + i as f64).sin(), 0.7 * (2.0 * i as f64).cos());
                let k = if twist { n + i } else { i };
                q[k] = a;
                qd[k] = b;
                let c = if twist { 3 * i } else { 3 * i + 2 };
                let sign = if twist { -1.0 } else { 1.0 };
                x[c] = sign * a;
                xd[c] = sign * b;
            }
            let mut sp: AeroScratch<f64> = planar.scratch();
            let mut ss: AeroScratch<f64> = spatial.scratch();
            for (model_q, model_qd, sc, m) in [(&q, &qd, &mut sp, 0), (&x, &xd, &mut ss, 1)] {
                if m == 0 {
                    planar.set_configuration(model_q, sc);
                    planar.set_rates(model_qd, sc);
                    planar.set_flow(&air, sc);
                    sc.weff.copy_from_slice(&sc.w.clone());
                    planar.set_loads(&air, sc);
                    planar.assemble(sc);
                } else {
                    spatial.set_configuration(model_q, sc);
                    spatial.set_rates(model_qd, sc);
                    spatial.set_flow(&air, sc);
                    sc.weff.copy_from_slice(&sc.w.clone());
                    spatial.set_loads(&air, sc);
                    spatial.assemble(sc);
                }
            }
            let scale = sp.q.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for i in 0..n {
                // Flow to round-off.
                assert!((sp.w[i] - ss.w[i]).abs() < 1e-13, "{twist} w[{i}]");
                assert!((sp.wt[i] - ss.wt[i]).abs() < 1e-13, "{twist} wt[{i}]");
                assert!(
                    (sp.moment[i] - ss.moment[i]).abs() < 1e-12,
                    "{twist} m[{i}]"
                );
                // The in-plane force components; the chordwise one loads lag in 3-D.
                for k in 0..3 {
                    assert!(
                        (sp.force[i][k] - ss.force[i][k]).abs() < 1e-12,
                        "{twist} f[{i}]"
                    );
                }
                // The forces of the coordinates that move: the twist ones on the straight wing,
                // the flap ones on the untwisted bent wing. (The others differ by construction:
                // on a bent wing a twist joint turns the outboard wing about its own axis and
                // the chordwise forces have a torsion arm, docs/chain3d-model.md; on a twisted
                // joint the rotation vector's flap component is not the planar bending angle.)
                if twist {
                    assert!(
                        (sp.q[n + i] + ss.q[3 * i]).abs() < 1e-12 * scale,
                        "twist {i}"
                    );
                } else {
                    assert!(
                        (sp.q[i] - ss.q[3 * i + 2]).abs() < 1e-12 * scale,
                        "flap {i}"
                    );
                }
            }
            // Drag and the tilted lift load lag.
            assert!(ss
                .q
                .iter()
                .skip(1)
                .step_by(3)
                .any(|v| v.abs() > 1e-3 * scale));
        }
    }
}
