//! The strips of the whole chain: section motions from the joint coordinates and rates, upwash,
//! loads, and the generalized forces `Q = Tᵀ Q_abs` in O(n) (docs/aeroelastic-model.md §3),
//! generic over the scalar for dual-number derivatives. Each evaluation dispatches on the chain
//! the strips live on ([`super::AeroChain`]): the planar chain's code below, the 3-D chain's in
//! `spatial.rs`.
//!
//! With the node velocities `V_i = V_{i−1} + ℓ_i θ̇_i n_i` the strip's elastic-axis velocity is
//! `ċ_i = V_{i−1} + (ℓ_i/2) θ̇_i n_i`. A force `P_i = ℓ_i F_i` at `c_i` and a nose-up moment
//! `ℓ_i M_i` give, in absolute angles, `Q_θ,j = n_j·(ℓ_j R_j + (ℓ_j/2) P_j)` with the outboard
//! resultant `R_j = Σ_{i>j} P_i`, and `Q_ψ,j = ℓ_j M_j` (the generalized forces of a point force
//! at `c_i`, `∂c_i/∂θ_j = ℓ_j n_j` for `j < i`, `(ℓ_i/2) n_i` for `j = i`).

use num_dual::{Dual64, DualNum};

use super::spatial::{self, SpatialStrips};
use super::strip::{flow, loads, Air, Motion};
use super::{AeroChain, AeroStructure, Aeroelastic};
use crate::model::suffix_sum_in_blocks;

/// Per-element buffers of a chain evaluation for scalar `D`.
#[derive(Debug, Clone)]
pub(crate) struct AeroScratch<D> {
    /// Section motions on the planar chain (empty on the 3-D chain).
    pub(crate) motion: Vec<Motion<D>>,
    /// The 3-D chain's kinematics and strip velocities (`None` on the planar chain).
    pub(crate) spatial: Option<Box<SpatialStrips<D>>>,
    /// Upwash at the three-quarter chord `w_i`.
    pub(crate) w: Vec<D>,
    /// Chordwise relative speed `W_T,i`.
    pub(crate) wt: Vec<D>,
    /// Lagged upwash `w_eff,i` (set by the caller before [`Aeroelastic::set_loads`]).
    pub(crate) weff: Vec<D>,
    /// Force per unit span (global components).
    pub(crate) force: Vec<[D; 3]>,
    /// Nose-up moment per unit span about the elastic axis.
    pub(crate) moment: Vec<D>,
    /// Generalized forces in the full model's joint coordinates.
    pub(crate) q: Vec<D>,
}

impl<D: DualNum<Primitive = f64> + Copy> AeroScratch<D> {
    pub(crate) fn new(chain: AeroChain<'_>, n: usize) -> Self {
        let n_dofs = chain.n_dofs();
        let (planar, spatial) = match chain {
            AeroChain::Planar(_) => (n, None),
            AeroChain::Spatial(_) => (0, Some(Box::new(SpatialStrips::new(n)))),
        };
        let z = D::from(0.0);
        let rest = Motion {
            cos_theta: D::from(1.0),
            sin_theta: z,
            cos_psi: D::from(1.0),
            sin_psi: z,
            cdot: [z; 2],
            psi_dot: z,
        };
        Self {
            motion: vec![rest; planar],
            spatial,
            w: vec![z; n],
            wt: vec![z; n],
            weff: vec![z; n],
            force: vec![[z; 3]; n],
            moment: vec![z; n],
            q: vec![z; n_dofs],
        }
    }
}

impl AeroScratch<f64> {
    /// Strip `i`'s section at the evaluation: its chord direction toward the leading edge, its
    /// normal (global components) and its nose-up pitch rate, on either chain (the frame
    /// `strip::section_loads` takes).
    pub(crate) fn section_frame(&self, i: usize) -> ([f64; 3], [f64; 3], f64) {
        if let Some(sp) = self.spatial.as_deref() {
            let r = &sp.fr.r[i];
            return (
                crate::model::chain3d::algebra::column(r, 2),
                crate::model::chain3d::algebra::column(r, 1),
                sp.pitch_rate[i],
            );
        }
        let m = &self.motion[i];
        let (c, si, cp, sp) = (m.cos_theta, m.sin_theta, m.cos_psi, m.sin_psi);
        (
            [-(sp * si), sp * c, cp],
            [-(cp * si), cp * c, -sp],
            m.psi_dot,
        )
    }
}

impl<M: AeroStructure> Aeroelastic<M> {
    /// Buffers for chain evaluations.
    pub(crate) fn scratch<D: DualNum<Primitive = f64> + Copy>(&self) -> AeroScratch<D> {
        AeroScratch::new(self.chain(), self.n_strips())
    }

    /// Trigonometry of the joint rotations `q` (full model) into `sc`.
    pub(crate) fn set_configuration<D: DualNum<Primitive = f64> + Copy>(
        &self,
        q: &[D],
        sc: &mut AeroScratch<D>,
    ) {
        let full = match self.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(chain) => {
                return chain.strip_configuration(q, spatial_of(sc));
            }
        };
        let n = full.n_elements();
        let torsion = full.has_torsion();
        let zero = D::from(0.0);
        let (mut th, mut ps) = (zero, zero);
        for i in 0..n {
            th += q[i];
            let (s, c) = th.sin_cos();
            let m = &mut sc.motion[i];
            m.sin_theta = s;
            m.cos_theta = c;
            if torsion {
                ps += q[n + i];
                let (sp, cp) = ps.sin_cos();
                m.sin_psi = sp;
                m.cos_psi = cp;
            }
        }
    }

    /// Dual trigonometry of `q + ε v` from the real trigonometry of `q` in `base`, without a
    /// trigonometric call (the absolute direction `T v` by prefix sums).
    /// `q` is the configuration of `base` (the 3-D chain evaluates its kinematics along
    /// `q + ε v` with dual numbers).
    pub(crate) fn set_configuration_along(
        &self,
        base: &AeroScratch<f64>,
        q: &[f64],
        v: &[f64],
        sc: &mut AeroScratch<Dual64>,
    ) {
        let full = match self.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(chain) => {
                let b = base.spatial.as_deref().expect("a 3-D chain's scratch");
                return chain.strip_configuration_along(b, q, v, spatial_of(sc));
            }
        };
        let n = full.n_elements();
        let torsion = full.has_torsion();
        let (mut dt, mut dp) = (0.0, 0.0);
        for i in 0..n {
            dt += v[i];
            if torsion {
                dp += v[n + i];
            }
            let b = &base.motion[i];
            let m = &mut sc.motion[i];
            m.sin_theta = Dual64::new(b.sin_theta, b.cos_theta * dt);
            m.cos_theta = Dual64::new(b.cos_theta, -b.sin_theta * dt);
            m.sin_psi = Dual64::new(b.sin_psi, b.cos_psi * dp);
            m.cos_psi = Dual64::new(b.cos_psi, -b.sin_psi * dp);
        }
    }

    /// The real configuration of `base` in the dual scratch `sc` (for derivatives along the
    /// rates).
    pub(crate) fn freeze_configuration(
        &self,
        base: &AeroScratch<f64>,
        sc: &mut AeroScratch<Dual64>,
    ) {
        match self.chain() {
            AeroChain::Planar(_) => {
                for (m, b) in sc.motion.iter_mut().zip(&base.motion) {
                    m.cos_theta = Dual64::from(b.cos_theta);
                    m.sin_theta = Dual64::from(b.sin_theta);
                    m.cos_psi = Dual64::from(b.cos_psi);
                    m.sin_psi = Dual64::from(b.sin_psi);
                }
            }
            AeroChain::Spatial(chain) => {
                let b = base.spatial.as_deref().expect("a 3-D chain's scratch");
                chain.strip_freeze(b, spatial_of(sc));
            }
        }
    }

    /// Section velocities from the joint rates `qdot` at the configuration in `sc`.
    pub(crate) fn set_rates<D: DualNum<Primitive = f64> + Copy>(
        &self,
        qdot: &[D],
        sc: &mut AeroScratch<D>,
    ) {
        let full = match self.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(chain) => return chain.strip_rates(qdot, spatial_of(sc)),
        };
        let n = full.n_elements();
        let torsion = full.has_torsion();
        let ell = full.beam().lengths();
        let zero = D::from(0.0);
        let (mut td, mut pd) = (zero, zero);
        let mut v = [zero; 2];
        for i in 0..n {
            td += qdot[i];
            if torsion {
                pd += qdot[n + i];
            }
            let m = &mut sc.motion[i];
            let (c, s) = (m.cos_theta, m.sin_theta);
            let h = td * (0.5 * ell[i]);
            m.cdot = [v[0] - s * h, v[1] + c * h];
            m.psi_dot = pd;
            let l = td * ell[i];
            v = [v[0] - s * l, v[1] + c * l];
        }
    }

    /// Upwash and chordwise speed of every strip into `sc.w`, `sc.wt`.
    pub(crate) fn set_flow<D: DualNum<Primitive = f64> + Copy>(
        &self,
        air: &[Air],
        sc: &mut AeroScratch<D>,
    ) {
        let steady = !self.aerodynamics().is_unsteady();
        // A flap adds its equivalent upwash (independent of the state) to the circulatory one.
        if let Some(sp) = sc.spatial.as_deref() {
            for (i, s) in self.strips.iter().enumerate() {
                let (w, wt) = spatial::flow(s, sp, i, &air[i], steady);
                sc.w[i] = w + D::from(air[i].flap.upwash);
                sc.wt[i] = wt;
            }
            return;
        }
        for (i, s) in self.strips.iter().enumerate() {
            let (w, wt) = flow(s, &sc.motion[i], &air[i], steady);
            sc.w[i] = w + D::from(air[i].flap.upwash);
            sc.wt[i] = wt;
        }
    }

    /// Loads of every strip for the lagged upwash in `sc.weff`, into `sc.force`, `sc.moment`.
    pub(crate) fn set_loads<D: DualNum<Primitive = f64> + Copy>(
        &self,
        air: &[Air],
        sc: &mut AeroScratch<D>,
    ) {
        let unsteady = self.aerodynamics().is_unsteady();
        let rho = self.density();
        if let Some(sp) = sc.spatial.as_deref() {
            for (i, s) in self.strips.iter().enumerate() {
                let flow = (sc.w[i], sc.wt[i], sc.weff[i]);
                let (f, m) = spatial::loads(s, sp, i, &air[i], rho, flow, unsteady);
                sc.force[i] = f;
                sc.moment[i] = m;
            }
            return;
        }
        for (i, s) in self.strips.iter().enumerate() {
            let (f, m) = loads(
                s,
                &sc.motion[i],
                &air[i],
                rho,
                (sc.w[i], sc.wt[i], sc.weff[i]),
                unsteady,
            );
            sc.force[i] = f;
            sc.moment[i] = m;
        }
    }

    /// Generalized forces of the strip loads in the full model's joint coordinates, into `sc.q`.
    pub(crate) fn assemble<D: DualNum<Primitive = f64> + Copy>(&self, sc: &mut AeroScratch<D>) {
        let full = match self.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(_) => {
                let sp = sc.spatial.as_deref_mut().expect("a 3-D chain's scratch");
                return spatial::assemble(&self.strips, sp, &sc.force, &sc.moment, &mut sc.q);
            }
        };
        let n = full.n_elements();
        let torsion = full.has_torsion();
        let ell = full.beam().lengths();
        let zero = D::from(0.0);
        let mut outboard = [zero; 2];
        for j in (0..n).rev() {
            let m = &sc.motion[j];
            let p = [sc.force[j][0] * ell[j], sc.force[j][1] * ell[j]];
            let lever = [
                outboard[0] * ell[j] + p[0] * (0.5 * ell[j]),
                outboard[1] * ell[j] + p[1] * (0.5 * ell[j]),
            ];
            sc.q[j] = m.cos_theta * lever[1] - m.sin_theta * lever[0];
            if torsion {
                sc.q[n + j] = sc.moment[j] * ell[j];
            }
            outboard = [outboard[0] + p[0], outboard[1] + p[1]];
        }
        suffix_sum_in_blocks(&mut sc.q, n);
    }

    /// The generalized forces of a unit change of strip `i`'s lagged upwash, `∂Q/∂w_eff,i`
    /// (full joint coordinates), into `out`: one dual-number evaluation of the strip and an
    /// O(n) assembly. `sc` holds the current evaluation (motions, flows, `weff`).
    pub(crate) fn load_per_upwash(
        &self,
        sc: &AeroScratch<f64>,
        air: &[Air],
        i: usize,
        out: &mut [f64],
    ) {
        let full = match self.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(_) => return self.spatial_load_per_upwash(sc, air, i, out),
        };
        let n = full.n_elements();
        let ell = full.beam().lengths();
        let m = &sc.motion[i];
        let md = Motion {
            cos_theta: Dual64::from(m.cos_theta),
            sin_theta: Dual64::from(m.sin_theta),
            cos_psi: Dual64::from(m.cos_psi),
            sin_psi: Dual64::from(m.sin_psi),
            cdot: [Dual64::from(m.cdot[0]), Dual64::from(m.cdot[1])],
            psi_dot: Dual64::from(m.psi_dot),
        };
        let (f, mom) = loads(
            &self.strips[i],
            &md,
            &air[i],
            self.density(),
            (
                Dual64::from(sc.w[i]),
                Dual64::from(sc.wt[i]),
                Dual64::new(sc.weff[i], 1.0),
            ),
            self.aerodynamics().is_unsteady(),
        );
        out.fill(0.0);
        let p = [f[0].eps * ell[i], f[1].eps * ell[i]];
        // Absolute angles: θ_j, j < i: ℓ_j n_j·P; θ_i: (ℓ_i/2) n_i·P; ψ_i: ℓ_i dM. Then Tᵀ.
        for j in 0..=i {
            let mj = &sc.motion[j];
            let arm = if j < i { ell[j] } else { 0.5 * ell[i] };
            out[j] = arm * (mj.cos_theta * p[1] - mj.sin_theta * p[0]);
        }
        if full.has_torsion() {
            out[n + i] = mom.eps * ell[i];
        }
        suffix_sum_in_blocks(out, n);
    }
}

impl<M: AeroStructure> Aeroelastic<M> {
    /// [`Aeroelastic::load_per_upwash`] on the 3-D chain.
    fn spatial_load_per_upwash(
        &self,
        sc: &AeroScratch<f64>,
        air: &[Air],
        i: usize,
        out: &mut [f64],
    ) {
        let sp = sc.spatial.as_deref().expect("a 3-D chain's scratch");
        let r = &sp.fr.r[i];
        let l3 = |v: [f64; 3]| v.map(Dual64::from);
        let frame = (
            l3([r[0][2], r[1][2], r[2][2]]),
            l3([r[0][1], r[1][1], r[2][1]]),
            Dual64::from(sp.pitch_rate[i]),
        );
        let s = &self.strips[i];
        let (f, mom) = super::strip::section_loads(
            s,
            frame,
            &air[i],
            self.density(),
            (
                Dual64::from(sc.w[i]),
                Dual64::from(sc.wt[i]),
                Dual64::new(sc.weff[i], 1.0),
            ),
            self.aerodynamics().is_unsteady(),
        );
        let dp = f.map(|v| v.eps * s.width);
        spatial::strip_load(sp, i, dp, mom.eps * s.width, out);
    }
}

/// The 3-D chain's part of a scratch.
fn spatial_of<D>(sc: &mut AeroScratch<D>) -> &mut SpatialStrips<D> {
    sc.spatial.as_deref_mut().expect("a 3-D chain's scratch")
}
