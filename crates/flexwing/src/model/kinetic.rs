//! Momentum `p = M(q) q̇` and the gyroscopic term `γ = ∂T/∂q|_q̇` in O(n), generic over the scalar
//! so that their derivatives come from forward-mode dual numbers.
//!
//! With the mass-centre velocities (model.md, "Kinematics")
//!
//! ```text
//! ġ_i = V_{i−1} + (ℓ_i/2) n_i θ̇_i + d0_i (−sin ψ_i e_i θ̇_i + cos ψ_i n_i ψ̇_i − sin ψ_i ẑ ψ̇_i),
//! V_k = Σ_{j ≤ k} ℓ_j n_j θ̇_j,    S_j = Σ_{i > j} m_i ġ_i,
//! ```
//!
//! the kinetic energy `T = ½ Σ m_i |ġ_i|² + ½ Σ J_i ψ̇_i²` has, in absolute angles,
//!
//! ```text
//! ∂T/∂θ̇_j = ℓ_j n_j·S_j + m_j ġ_j·((ℓ_j/2) n_j − d0_j sin ψ_j e_j)
//! ∂T/∂ψ̇_j = m_j d0_j ġ_j·(cos ψ_j n_j − sin ψ_j ẑ) + J_j ψ̇_j
//! ∂T/∂θ_j = −ℓ_j θ̇_j e_j·S_j − m_j ġ_j·((ℓ_j/2) θ̇_j e_j + d0_j sin ψ_j θ̇_j n_j + d0_j cos ψ_j ψ̇_j e_j)
//! ∂T/∂ψ_j = −m_j d0_j ġ_j·(cos ψ_j θ̇_j e_j + sin ψ_j ψ̇_j n_j + cos ψ_j ψ̇_j ẑ)
//! ```
//!
//! and in joint coordinates `p = Tᵀ ∂T/∂(θ̇, ψ̇)`, `γ = Tᵀ ∂T/∂(θ, ψ)` (suffix sums), with
//! `θ̇ = T q̇_b`, `ψ̇ = T q̇_t` (prefix sums). Everything is O(n), so the exact gyroscopic term costs
//! less than one mass-matrix assembly.

use nalgebra::DMatrix;
use num_dual::{Dual64, DualNum};

use super::chain_solve::ChainScratch;
use super::{suffix_sum_in_blocks, FullModel, Kinematics};

/// Scratch of the kinetic recursions for scalar `D`.
#[derive(Debug, Clone)]
pub(crate) struct KineticScratch<D> {
    pub(super) cos_theta: Vec<D>,
    pub(super) sin_theta: Vec<D>,
    pub(super) cos_psi: Vec<D>,
    pub(super) sin_psi: Vec<D>,
    pub(super) theta_dot: Vec<D>,
    pub(super) psi_dot: Vec<D>,
    pub(super) g_dot: Vec<[D; 3]>,
    /// Node velocities `V_{i−1}` (in plane), kept only for the fluid terms.
    pub(super) node_v: Vec<[D; 2]>,
    /// The fluid's normal velocity at mid-chord `u_i` (`model::aero::fluid`).
    pub(super) fluid_u: Vec<D>,
}

impl<D: DualNum<Primitive = f64> + Copy> KineticScratch<D> {
    pub(crate) fn new(n: usize) -> Self {
        let z = D::from(0.0);
        Self {
            cos_theta: vec![z; n],
            sin_theta: vec![z; n],
            cos_psi: vec![z; n],
            sin_psi: vec![z; n],
            theta_dot: vec![z; n],
            psi_dot: vec![z; n],
            g_dot: vec![[z; 3]; n],
            node_v: vec![[z; 2]; n],
            fluid_u: vec![z; n],
        }
    }
}

fn dot<D: DualNum<Primitive = f64> + Copy>(a: &[D; 3], b: &[D; 3]) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

impl FullModel {
    /// Momentum `p = M(q) q̇` (into `p`) and/or gyroscopic term `γ = ∂T/∂q|_q̇` (into `gamma`),
    /// in O(n), for scalar `D` (f64, or dual numbers for derivatives).
    pub(crate) fn kinetic_terms<D: DualNum<Primitive = f64> + Copy>(
        &self,
        q: &[D],
        qdot: &[D],
        sc: &mut KineticScratch<D>,
        p: Option<&mut [D]>,
        gamma: Option<&mut [D]>,
    ) {
        self.configure(q, sc);
        self.kinetic_terms_configured(qdot, sc, p, gamma);
    }

    /// Sines and cosines of the absolute angles of `q` into `sc` (the costly part of the
    /// recursions, shared by every velocity evaluated at the same configuration).
    pub(crate) fn configure<D: DualNum<Primitive = f64> + Copy>(
        &self,
        q: &[D],
        sc: &mut KineticScratch<D>,
    ) {
        let n = self.n;
        let zero = D::from(0.0);
        let (mut th, mut ps) = (zero, zero);
        for i in 0..n {
            th += q[i];
            let (s, c) = th.sin_cos();
            sc.sin_theta[i] = s;
            sc.cos_theta[i] = c;
            if self.torsion {
                ps += q[n + i];
                let (sp, cp) = ps.sin_cos();
                sc.sin_psi[i] = sp;
                sc.cos_psi[i] = cp;
            } else {
                sc.sin_psi[i] = zero;
                sc.cos_psi[i] = D::from(1.0);
            }
        }
    }

    /// The trigonometry of `kin` into `sc` (f64 scratch), instead of recomputing it.
    pub(crate) fn configure_from(&self, kin: &super::Kinematics, sc: &mut KineticScratch<f64>) {
        sc.cos_theta.copy_from_slice(&kin.cos_theta);
        sc.sin_theta.copy_from_slice(&kin.sin_theta);
        sc.cos_psi.copy_from_slice(&kin.cos_psi);
        sc.sin_psi.copy_from_slice(&kin.sin_psi);
    }

    /// Dual trigonometry of `q + ε v` into `sc` from the real trigonometry `kin` of `q`, without
    /// any trigonometric call: `sin(θ + ε dθ) = sin θ + ε cos θ dθ`, with the absolute direction
    /// `dθ = T v` (prefix sums, into `abs`, length `n_dofs`).
    pub(crate) fn configure_along(
        &self,
        kin: &Kinematics,
        v: &[f64],
        abs: &mut [f64],
        sc: &mut KineticScratch<Dual64>,
    ) {
        let n = self.n;
        abs.copy_from_slice(v);
        for block in abs.chunks_mut(n) {
            for i in 1..block.len() {
                block[i] += block[i - 1];
            }
        }
        for i in 0..n {
            let (s, c, dt) = (kin.sin_theta[i], kin.cos_theta[i], abs[i]);
            sc.sin_theta[i] = Dual64::new(s, c * dt);
            sc.cos_theta[i] = Dual64::new(c, -s * dt);
            let (sp, cp) = (kin.sin_psi[i], kin.cos_psi[i]);
            let dp = if self.torsion { abs[n + i] } else { 0.0 };
            sc.sin_psi[i] = Dual64::new(sp, cp * dp);
            sc.cos_psi[i] = Dual64::new(cp, -sp * dp);
        }
    }

    /// [`Self::kinetic_terms`] at the configuration last given to [`Self::configure`].
    pub(crate) fn kinetic_terms_configured<D: DualNum<Primitive = f64> + Copy>(
        &self,
        qdot: &[D],
        sc: &mut KineticScratch<D>,
        p: Option<&mut [D]>,
        gamma: Option<&mut [D]>,
    ) {
        // Two monomorphic versions: the model in vacuo runs exactly the code it ran before the
        // fluid's inertia existed.
        if self.fluid.is_some() {
            self.kinetic_terms_impl::<D, true>(qdot, sc, p, gamma)
        } else {
            self.kinetic_terms_impl::<D, false>(qdot, sc, p, gamma)
        }
    }

    fn kinetic_terms_impl<D: DualNum<Primitive = f64> + Copy, const FLUID: bool>(
        &self,
        qdot: &[D],
        sc: &mut KineticScratch<D>,
        mut p: Option<&mut [D]>,
        mut gamma: Option<&mut [D]>,
    ) {
        let n = self.n;
        let zero = D::from(0.0);
        let (mut thd, mut psd) = (zero, zero);
        for i in 0..n {
            thd += qdot[i];
            if self.torsion {
                psd += qdot[n + i];
            }
            sc.theta_dot[i] = thd;
            sc.psi_dot[i] = psd;
        }
        // Mass-centre velocities.
        let mut v = [zero; 2]; // V_{i−1}
        for i in 0..n {
            let (c, s, cp, sp) = (
                sc.cos_theta[i],
                sc.sin_theta[i],
                sc.cos_psi[i],
                sc.sin_psi[i],
            );
            let (td, pd) = (sc.theta_dot[i], sc.psi_dot[i]);
            let (h, d) = (0.5 * self.ell[i], self.d0[i]);
            // (ℓ/2) n θ̇ − d0 sψ e θ̇ + d0 cψ n ψ̇ − d0 sψ ẑ ψ̇, with e = (c, s), n = (−s, c).
            let a_n = td * h + cp * pd * d; // coefficient of n
            let a_e = -(sp * td * d); // coefficient of e
            sc.g_dot[i] = [
                v[0] + a_e * c - a_n * s,
                v[1] + a_e * s + a_n * c,
                -(sp * pd * d),
            ];
            if let (true, Some(f)) = (FLUID, &self.fluid) {
                // u = cos ψ (n·V) + (ℓ/2) cos ψ θ̇ + ζ_m ψ̇.
                sc.node_v[i] = v;
                sc.fluid_u[i] = cp * (c * v[1] - s * v[0] + td * h) + pd * f.station[i];
            }
            v[0] -= s * td * self.ell[i];
            v[1] += c * td * self.ell[i];
        }
        self.kinetic_backward_impl::<D, FLUID>(sc, p.as_deref_mut(), gamma.as_deref_mut());
        if let Some(p) = p {
            suffix_sum_in_blocks(p, n);
        }
        if let Some(gm) = gamma {
            suffix_sum_in_blocks(gm, n);
        }
    }

    /// The backward half of the recursions: from the rates `sc.theta_dot`, `sc.psi_dot` and the
    /// mass-centre velocities `sc.g_dot`, the momenta `∂T/∂(θ̇, ψ̇)` (into `p`) and the
    /// gyroscopic term `∂T/∂(θ, ψ)` (into `gamma`) in absolute angles (no suffix sums).
    pub(crate) fn kinetic_backward<D: DualNum<Primitive = f64> + Copy>(
        &self,
        sc: &KineticScratch<D>,
        p: Option<&mut [D]>,
        gamma: Option<&mut [D]>,
    ) {
        if self.fluid.is_some() {
            self.kinetic_backward_impl::<D, true>(sc, p, gamma)
        } else {
            self.kinetic_backward_impl::<D, false>(sc, p, gamma)
        }
    }

    fn kinetic_backward_impl<D: DualNum<Primitive = f64> + Copy, const FLUID: bool>(
        &self,
        sc: &KineticScratch<D>,
        p: Option<&mut [D]>,
        gamma: Option<&mut [D]>,
    ) {
        let n = self.n;
        let zero = D::from(0.0);
        let mut outboard = [zero; 3]; // S_j = Σ_{i>j} m_i ġ_i
        let mut fluid_out = [zero; 2]; // S^f_j = Σ_{i>j} m_a,i u_i cos ψ_i n_i
        let mut p = p;
        let mut gamma = gamma;
        for j in (0..n).rev() {
            let (c, s, cp, sp) = (
                sc.cos_theta[j],
                sc.sin_theta[j],
                sc.cos_psi[j],
                sc.sin_psi[j],
            );
            let (td, pd) = (sc.theta_dot[j], sc.psi_dot[j]);
            let (l, h, d, m) = (self.ell[j], 0.5 * self.ell[j], self.d0[j], self.mass[j]);
            let e = [c, s, zero];
            let nv = [-s, c, zero];
            let zhat = [zero, zero, D::from(1.0)];
            let g = sc.g_dot[j];
            if let Some(p) = p.as_deref_mut() {
                let dgdthd = [nv[0] * h - e[0] * sp * d, nv[1] * h - e[1] * sp * d, zero];
                p[j] = dot(&nv, &outboard) * l + dot(&g, &dgdthd) * m + td * self.rotary[j];
                if self.torsion {
                    let dgdpsd = [nv[0] * cp * d, nv[1] * cp * d, -(sp * d)];
                    p[n + j] = dot(&g, &dgdpsd) * m + pd * self.inertia[j];
                }
            }
            if let Some(gm) = gamma.as_deref_mut() {
                // −(ℓ/2) θ̇ e − d0 sψ θ̇ n − d0 cψ ψ̇ e
                let w = [
                    -(e[0] * (td * h + cp * pd * d) + nv[0] * sp * td * d),
                    -(e[1] * (td * h + cp * pd * d) + nv[1] * sp * td * d),
                    zero,
                ];
                gm[j] = -(dot(&e, &outboard) * td * l) + dot(&g, &w) * m;
                if self.torsion {
                    let wp = [
                        -(e[0] * cp * td * d + nv[0] * sp * pd * d),
                        -(e[1] * cp * td * d + nv[1] * sp * pd * d),
                        -(zhat[2] * cp * pd * d),
                    ];
                    gm[n + j] = dot(&g, &wp) * m;
                }
            }
            for a in 0..3 {
                outboard[a] += g[a] * m;
            }
            if let (true, Some(f)) = (FLUID, &self.fluid) {
                // model::aero::fluid: the terms of T_f = ½ Σ m_a u² + ½ Σ J_a ψ̇².
                let (ma, u, v) = (f.mass[j], sc.fluid_u[j], sc.node_v[j]);
                let mu = u * ma;
                if let Some(p) = p.as_deref_mut() {
                    p[j] += (nv[0] * fluid_out[0] + nv[1] * fluid_out[1]) * l + mu * cp * h;
                    if self.torsion {
                        p[n + j] += mu * f.station[j] + pd * f.inertia[j];
                    }
                }
                if let Some(gm) = gamma.as_deref_mut() {
                    let e_s = e[0] * fluid_out[0] + e[1] * fluid_out[1];
                    let e_v = e[0] * v[0] + e[1] * v[1];
                    gm[j] -= e_s * td * l + mu * cp * e_v;
                    if self.torsion {
                        let n_v = nv[0] * v[0] + nv[1] * v[1];
                        gm[n + j] -= mu * sp * (n_v + td * h);
                    }
                }
                fluid_out[0] += mu * cp * nv[0];
                fluid_out[1] += mu * cp * nv[1];
            }
        }
    }

    /// Momentum `p = M(q) q̇` in O(n), into `out`.
    ///
    /// # Panics
    /// If a slice length differs from `n_dofs()`.
    pub fn momentum_into(&self, q: &[f64], qdot: &[f64], out: &mut [f64]) {
        let mut sc = KineticScratch::new(self.n);
        self.kinetic_terms(q, qdot, &mut sc, Some(out), None);
    }

    /// Gyroscopic term `γ(q, q̇) = ∂T/∂q|_q̇ = ½ q̇ᵀ (∂M/∂q) q̇` in O(n), into `out`.
    ///
    /// # Panics
    /// If a slice length differs from `n_dofs()`.
    pub fn gyroscopic_into(&self, q: &[f64], qdot: &[f64], out: &mut [f64]) {
        let mut sc = KineticScratch::new(self.n);
        self.kinetic_terms(q, qdot, &mut sc, None, Some(out));
    }

    /// Kinetic energy `T = ½ q̇ᵀ M(q) q̇` (J).
    pub fn kinetic_energy(&self, q: &[f64], qdot: &[f64]) -> f64 {
        let mut p = vec![0.0; self.n_dofs()];
        self.momentum_into(q, qdot, &mut p);
        0.5 * p.iter().zip(qdot).map(|(a, b)| a * b).sum::<f64>()
    }

    /// Directional derivatives with respect to `q` (at fixed `q̇`) of the momentum and of the
    /// gyroscopic term along the columns of `dirs` (`n_dofs × r`): `dp = (∂(M q̇)/∂q) dirs`,
    /// `dgamma = (∂γ/∂q) dirs`. Exact (forward-mode dual numbers), O(n r).
    pub(crate) fn kinetic_directional(
        &self,
        q: &[f64],
        qdot: &[f64],
        dirs: &DMatrix<f64>,
        sc: &mut KineticBuffers,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        let nd = self.n_dofs();
        for (i, v) in qdot.iter().enumerate() {
            sc.qdot[i] = Dual64::from(*v);
        }
        sc.kin.update(q);
        for col in 0..dirs.ncols() {
            self.configure_along(
                &sc.kin,
                dirs.column(col).as_slice(),
                &mut sc.dir,
                &mut sc.scratch,
            );
            self.kinetic_terms_configured(
                &sc.qdot,
                &mut sc.scratch,
                Some(&mut sc.p),
                Some(&mut sc.gamma),
            );
            for i in 0..nd {
                dp[(i, col)] = sc.p[i].eps;
                dgamma[(i, col)] = sc.gamma[i].eps;
            }
        }
    }
}

impl FullModel {
    /// [`crate::model::StructuralModel::hamiltonian_derivatives_into`] in O(n²): for each unit
    /// direction `e_k` of `q`, one dual-number pass of the O(n) velocity solve
    /// `ẋ = M(q + ε e_k)⁻¹ p` (dual part: column `k` of `∂ẋ/∂q|_p`) and, if `with_gamma`, of the
    /// gyroscopic recursion at `(q + ε e_k, ẋ)` (dual part: column `k` of `dγ/dq|_p`). No
    /// `∂(M q̇)/∂q` and no matrix product.
    pub(crate) fn hamiltonian_directional(
        &self,
        q: &[f64],
        p: &[f64],
        buf: &mut KineticBuffers,
        with_gamma: bool,
        dxdx: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) -> bool {
        let nd = self.n_dofs();
        let KineticBuffers {
            qdot,
            p: pd,
            gamma,
            scratch,
            chain,
            kin,
            dir,
            unit,
        } = buf;
        for i in 0..nd {
            pd[i] = Dual64::from(p[i]);
        }
        unit.fill(0.0);
        kin.update(q);
        for col in 0..nd {
            unit[col] = 1.0;
            self.configure_along(kin, unit, dir, scratch);
            unit[col] = 0.0;
            if !self.solve_mass_configured(scratch, pd, chain, qdot) {
                return false;
            }
            for i in 0..nd {
                dxdx[(i, col)] = qdot[i].eps;
            }
            if with_gamma {
                self.kinetic_terms_configured(qdot, scratch, None, Some(gamma));
                for i in 0..nd {
                    dgamma[(i, col)] = gamma[i].eps;
                }
            }
        }
        true
    }
}

/// Dual-number buffers for [`FullModel::kinetic_directional`] and
/// [`FullModel::hamiltonian_directional`].
#[derive(Debug, Clone)]
pub(crate) struct KineticBuffers {
    qdot: Vec<Dual64>,
    p: Vec<Dual64>,
    gamma: Vec<Dual64>,
    scratch: KineticScratch<Dual64>,
    chain: ChainScratch<Dual64>,
    kin: Kinematics,
    dir: Vec<f64>,
    unit: Vec<f64>,
}

impl KineticBuffers {
    pub(crate) fn new(model: &FullModel) -> Self {
        let nd = model.n_dofs();
        let z = Dual64::from(0.0);
        Self {
            qdot: vec![z; nd],
            p: vec![z; nd],
            gamma: vec![z; nd],
            scratch: KineticScratch::new(model.n_elements()),
            chain: ChainScratch::new(model.n_elements()),
            kin: Kinematics::new(model.n_elements()),
            dir: vec![0.0; nd],
            unit: vec![0.0; nd],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };

    /// The O(n²) dual-number path of the Jacobian's kinetic part (used from 128 coordinates on)
    /// against the dense path (`B`, velocity solves, a matrix product), whose Jacobian is
    /// checked against finite differences in `solve::dynamics`.
    #[test]
    fn dual_velocity_solves_match_the_dense_hamiltonian_derivatives() {
        use crate::model::StructuralModel;
        for torsion in [false, true] {
            let section = SectionProperties {
                ei: Profile::Uniform(10.0),
                mass_per_length: Profile::Uniform(0.4),
                torsion: torsion.then_some(TorsionProperties {
                    gj: Profile::Uniform(3.0),
                    polar_inertia: Profile::Uniform(0.01),
                    inertia_axis: InertiaAxis::MassCentre,
                    offset: Profile::Uniform(0.1),
                }),
            };
            let beam = Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(6),
                Calibration::TipLoad,
            )
            .unwrap();
            let model = FullModel::new(beam);
            let nd = model.n_dofs();
            let q: Vec<f64> = (0..nd).map(|i| 0.3 * (i as f64 + 1.0).sin()).collect();
            let p: Vec<f64> = (0..nd).map(|i| 0.7 * (2.0 * i as f64).cos()).collect();
            let mut ws = model.workspace();
            let z = || DMatrix::zeros(nd, nd);
            let (mut a, mut ga, mut b, mut gb) = (z(), z(), z(), z());
            assert!(crate::model::hamiltonian_derivatives_dense(
                &model, &q, &p, &mut ws, true, &mut a, &mut ga
            ));
            assert!(model.hamiltonian_directional(&q, &p, &mut ws.duals, true, &mut b, &mut gb));
            assert!((&a - &b).amax() <= 1e-10 * a.amax());
            assert!((&ga - &gb).amax() <= 1e-10 * ga.amax());
        }
    }

    #[test]
    fn dual_directional_derivatives_match_finite_differences() {
        let section = SectionProperties {
            ei: Profile::Uniform(10.0),
            mass_per_length: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![0.6, 0.2],
            },
            torsion: Some(TorsionProperties {
                gj: Profile::Uniform(3.0),
                polar_inertia: Profile::Uniform(0.01),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.1),
            }),
        };
        let model = FullModel::new(
            Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(5),
                Calibration::TipLoad,
            )
            .unwrap(),
        );
        let nd = model.n_dofs();
        let q: Vec<f64> = (0..nd).map(|i| 0.3 * (i as f64 + 1.0).sin()).collect();
        let qd: Vec<f64> = (0..nd).map(|i| 0.7 * (2.0 * i as f64).cos()).collect();
        let dirs = DMatrix::from_fn(nd, 3, |r, c| ((r + 2 * c) as f64).cos());
        let (mut dp, mut dg) = (DMatrix::zeros(nd, 3), DMatrix::zeros(nd, 3));
        let mut buf = KineticBuffers::new(&model);
        model.kinetic_directional(&q, &qd, &dirs, &mut buf, &mut dp, &mut dg);
        let h = 1e-6;
        for c in 0..3 {
            let qp: Vec<f64> = (0..nd).map(|i| q[i] + h * dirs[(i, c)]).collect();
            let qm: Vec<f64> = (0..nd).map(|i| q[i] - h * dirs[(i, c)]).collect();
            let (mut pp, mut pm, mut gp, mut gm) =
                (vec![0.0; nd], vec![0.0; nd], vec![0.0; nd], vec![0.0; nd]);
            model.momentum_into(&qp, &qd, &mut pp);
            model.momentum_into(&qm, &qd, &mut pm);
            model.gyroscopic_into(&qp, &qd, &mut gp);
            model.gyroscopic_into(&qm, &qd, &mut gm);
            for i in 0..nd {
                assert!(((pp[i] - pm[i]) / (2.0 * h) - dp[(i, c)]).abs() < 1e-7);
                assert!(((gp[i] - gm[i]) / (2.0 * h) - dg[(i, c)]).abs() < 1e-7);
            }
        }
    }
}
