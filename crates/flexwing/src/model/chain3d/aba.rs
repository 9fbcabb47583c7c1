//! The O(n) velocity solve `ẋ = M(x)⁻¹ p` of the 3-D chain: the articulated-body algorithm
//! (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, §7.3, Table 7.1) with the joint
//! momenta `p` as the joint forces and no velocity-product or gravity terms — `M ẋ = p` is
//! `M q̈ = τ` at rest. Generic over the scalar (dual numbers differentiate it), split into the
//! factorization, which depends on the configuration only, and the solve for each `p`.
//!
//! Joint `i` is a spherical joint at node `P_i` with motion subspace `S_i = (H_i, 0)` about
//! `P_i`. Backward from the tip: `I^A_i = I_i + Xᵀ I^a_{i+1} X`, `U_i = I^A_i S_i`,
//! `D_i = S_iᵀ U_i` (3×3, positive definite iff `M` is), `I^a_i = I^A_i − U_i D_i⁻¹ U_iᵀ`; for
//! each `p`, `u_i = p_i − S_iᵀ p^A_i`, `p^a_i = p^A_i + U_i D_i⁻¹ u_i`; forward from the clamp,
//! `ẋ_i = D_i⁻¹ (u_i − U_iᵀ a'_i)`, `a_i = a'_i + S_i ẋ_i`, with `a'_i` the spatial velocity
//! of element `i − 1` moved to `P_i`.

use super::algebra::{add, cholesky, cholesky_solve, cross, mm, mtm, mtv, mv, zero, Real, M3, V3};
use super::kinematics::Frames;
use super::mass::Spatial;
use super::Chain3d;

/// The factorization of `M(x)` along the chain and the buffers of a solve.
#[derive(Debug, Clone)]
pub(crate) struct Articulated<D> {
    /// `U_i`: moment part `a H_i`, force part `bᵀ H_i`.
    u_top: Vec<M3<D>>,
    u_bottom: Vec<M3<D>>,
    /// Cholesky factor of `D_i`.
    chol: Vec<M3<D>>,
    /// `u_i` of the last solve.
    u: Vec<V3<D>>,
}

impl<D: Real> Articulated<D> {
    pub(crate) fn new(n: usize) -> Self {
        let z = [[D::from(0.0); 3]; 3];
        Self {
            u_top: vec![z; n],
            u_bottom: vec![z; n],
            chol: vec![z; n],
            u: vec![zero(); n],
        }
    }
}

impl Chain3d {
    /// Factor `M` at the configuration `fr` into `ab`; false if a pivot block `D_i` is not
    /// numerically positive definite (then `M` is not). O(n).
    pub(crate) fn factor_mass<D: Real>(&self, fr: &Frames<D>, ab: &mut Articulated<D>) -> bool {
        self.factor_mass_spring(fr, ab, 0.0)
    }

    /// Factor `M + s K` (`K` the joint springs, block diagonal) into `ab`: the springs enter as
    /// the joints' armature, added to each pivot `D_i` (Featherstone §7.3); [`Self::solve_mass`]
    /// then solves `(M + s K) z = w`. The preconditioner of the 3-D chain's Newton systems
    /// (`newton.rs`). False if a pivot is not positive definite. O(n).
    pub(crate) fn factor_mass_spring<D: Real>(
        &self,
        fr: &Frames<D>,
        ab: &mut Articulated<D>,
        spring: f64,
    ) -> bool {
        let mut child = Spatial::<D>::zero();
        for i in (0..self.n).rev() {
            let mut ia = Spatial::body(self, fr, i);
            if i + 1 < self.n {
                ia.add_moved(&child, &fr.d[i]);
            }
            let h = &fr.h[i];
            let ut = mm(&ia.a, h);
            let ub = mtm(&ia.b, h);
            let mut dmat = mtm(h, &ut);
            if spring != 0.0 {
                let k = &self.beam.stiffness[i];
                for r in 0..3 {
                    for c in 0..3 {
                        dmat[r][c] += D::from(spring * k[r][c]);
                    }
                }
            }
            let Some(l) = cholesky(&dmat) else {
                return false;
            };
            // I^a = I^A − U D⁻¹ Uᵀ, block by block (W = D⁻¹ Uᵀ by columns of Uᵀ).
            let mut wt = [[D::from(0.0); 3]; 3]; // D⁻¹ U_topᵀ (3×3)
            let mut wb = [[D::from(0.0); 3]; 3]; // D⁻¹ U_bottomᵀ
            for k in 0..3 {
                let col_t = cholesky_solve(&l, &ut[k]);
                let col_b = cholesky_solve(&l, &ub[k]);
                for r in 0..3 {
                    wt[r][k] = col_t[r];
                    wb[r][k] = col_b[r];
                }
            }
            let a_sub = mm(&ut, &wt);
            let b_sub = mm(&ut, &wb);
            let c_sub = mm(&ub, &wb);
            for r in 0..3 {
                for k in 0..3 {
                    ia.a[r][k] -= a_sub[r][k];
                    ia.b[r][k] -= b_sub[r][k];
                    ia.c[r][k] -= c_sub[r][k];
                }
            }
            ab.u_top[i] = ut;
            ab.u_bottom[i] = ub;
            ab.chol[i] = l;
            child = ia;
        }
        true
    }

    /// `out = M⁻¹ p` with the factorization `ab` of the configuration `fr`. O(n).
    pub(crate) fn solve_mass<D: Real>(
        &self,
        fr: &Frames<D>,
        ab: &mut Articulated<D>,
        p: &[D],
        out: &mut [D],
    ) {
        let n = self.n;
        // Backward: p^A_i = p^a_{i+1} moved to P_i; u_i = p_i − H_iᵀ (moment of p^A_i).
        let (mut moment, mut force): (V3<D>, V3<D>) = (zero(), zero());
        for i in (0..n).rev() {
            if i + 1 < n {
                moment = add(&moment, &cross(&fr.d[i], &force));
            }
            let pi = [p[3 * i], p[3 * i + 1], p[3 * i + 2]];
            let hm = mtv(&fr.h[i], &moment);
            let u = [pi[0] - hm[0], pi[1] - hm[1], pi[2] - hm[2]];
            let y = cholesky_solve(&ab.chol[i], &u);
            moment = add(&moment, &mv(&ab.u_top[i], &y));
            force = add(&force, &mv(&ab.u_bottom[i], &y));
            ab.u[i] = u;
        }
        // Forward from the clamp.
        let (mut omega, mut v): (V3<D>, V3<D>) = (zero(), zero());
        for i in 0..n {
            if i > 0 {
                v = add(&v, &cross(&omega, &fr.d[i - 1]));
            }
            let ua = add(&mtv(&ab.u_top[i], &omega), &mtv(&ab.u_bottom[i], &v));
            let u = ab.u[i];
            let rhs = [u[0] - ua[0], u[1] - ua[1], u[2] - ua[2]];
            let qd = cholesky_solve(&ab.chol[i], &rhs);
            out[3 * i..3 * i + 3].copy_from_slice(&qd);
            omega = add(&omega, &mv(&fr.h[i], &qd));
        }
    }
}
