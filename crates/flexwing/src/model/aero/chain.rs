//! The strips of the whole chain: section motions from the joint coordinates and rates, upwash,
//! loads, and the generalized forces `Q = Tᵀ Q_abs` in O(n) (docs/aeroelastic-model.md §3),
//! generic over the scalar for dual-number derivatives.
//!
//! With the node velocities `V_i = V_{i−1} + ℓ_i θ̇_i n_i` the strip's elastic-axis velocity is
//! `ċ_i = V_{i−1} + (ℓ_i/2) θ̇_i n_i`. A force `P_i = ℓ_i F_i` at `c_i` and a nose-up moment
//! `ℓ_i M_i` give, in absolute angles, `Q_θ,j = n_j·(ℓ_j R_j + (ℓ_j/2) P_j)` with the outboard
//! resultant `R_j = Σ_{i>j} P_i`, and `Q_ψ,j = ℓ_j M_j` (the generalized forces of a point force
//! at `c_i`, `∂c_i/∂θ_j = ℓ_j n_j` for `j < i`, `(ℓ_i/2) n_i` for `j = i`).

use num_dual::{Dual64, DualNum};

use super::strip::{flow, loads, Air, Motion};
use super::{AeroStructure, Aeroelastic};
use crate::model::suffix_sum_in_blocks;

/// Per-element buffers of a chain evaluation for scalar `D`.
#[derive(Debug, Clone)]
pub(crate) struct AeroScratch<D> {
    pub(crate) motion: Vec<Motion<D>>,
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
    pub(crate) fn new(n: usize, n_dofs: usize) -> Self {
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
            motion: vec![rest; n],
            w: vec![z; n],
            wt: vec![z; n],
            weff: vec![z; n],
            force: vec![[z; 3]; n],
            moment: vec![z; n],
            q: vec![z; n_dofs],
        }
    }
}

impl<M: AeroStructure> Aeroelastic<M> {
    /// Buffers for chain evaluations.
    pub(crate) fn scratch<D: DualNum<Primitive = f64> + Copy>(&self) -> AeroScratch<D> {
        AeroScratch::new(self.n_strips(), self.full().n_dofs())
    }

    /// Trigonometry of the joint rotations `q` (full model) into `sc`.
    pub(crate) fn set_configuration<D: DualNum<Primitive = f64> + Copy>(
        &self,
        q: &[D],
        sc: &mut AeroScratch<D>,
    ) {
        let full = self.full();
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
    pub(crate) fn set_configuration_along(
        &self,
        base: &AeroScratch<f64>,
        v: &[f64],
        sc: &mut AeroScratch<Dual64>,
    ) {
        let full = self.full();
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

    /// Section velocities from the joint rates `qdot` at the configuration in `sc`.
    pub(crate) fn set_rates<D: DualNum<Primitive = f64> + Copy>(
        &self,
        qdot: &[D],
        sc: &mut AeroScratch<D>,
    ) {
        let full = self.full();
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
        for (i, s) in self.strips.iter().enumerate() {
            let (w, wt) = flow(s, &sc.motion[i], &air[i], steady);
            sc.w[i] = w;
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
        let full = self.full();
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
        let full = self.full();
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
