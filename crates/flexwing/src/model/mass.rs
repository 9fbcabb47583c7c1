//! The configuration-dependent mass matrix in O(n²).
//!
//! In absolute angles `(θ, ψ)` the kinetic energy `T = ½ Σ m_i |ġ_i|² + ½ Σ J_i ψ̇_i² + ½ Σ J_b,i θ̇_i²`
//! (the last, rotary inertia in bending, zero in the paper's model) has the
//! matrix (model.md, "Equations of motion"; `a_kj = ℓ_j` for `j < k`, `ℓ_k/2` for `j = k`):
//!
//! ```text
//! θθ, j < k :  A_jk cos(θ_j − θ_k) − m_k d0_k sin ψ_k ℓ_j sin(θ_k − θ_j)
//! θθ, k = k :  A_kk + m_k d0_k² sin² ψ_k
//! θψ, j ≤ k :  m_k d0_k cos ψ_k a_kj cos(θ_j − θ_k)          (zero for j > k)
//! ψψ, k = k :  m_k d0_k² + J_k                               (diagonal)
//! ```
//!
//! with `A_jk = Σ_{i ≥ max(j,k)} m_i a_ij a_ik = ℓ_j ℓ_k μ_k` (`j < k`). The `d0` terms come from
//! `∂g_k/∂θ_k = (ℓ_k/2) n_k − d0_k sin ψ_k e_k` and `∂g_k/∂ψ_k = d0_k (cos ψ_k n_k − sin ψ_k ẑ)`.
//! The joint-coordinate matrix is `M(q) = Tᵀ M_abs T`, a two-sided suffix sum, also O(n²): no
//! dense product `Jᵀ M J` is formed.

use nalgebra::DMatrix;

use super::aero::FluidInertia;
use super::{suffix_sum_in_blocks, FullModel, Kinematics};

impl FullModel {
    /// Mass matrix `M(q)` at the configuration described by `kin`, into `out`.
    /// Costs O(n²) and allocates nothing.
    ///
    /// # Panics
    /// If `out` is not `n_dofs × n_dofs`.
    pub fn mass_matrix_kin_into(&self, kin: &Kinematics, out: &mut DMatrix<f64>) {
        let n = self.n;
        let nd = self.n_dofs();
        assert_eq!(
            out.shape(),
            (nd, nd),
            "mass matrix buffer has the wrong shape"
        );
        let (ct, st) = (&kin.cos_theta, &kin.sin_theta);
        for k in 0..n {
            let dk = self.d0[k];
            let coupling = self.mass[k] * dk * kin.sin_psi[k];
            for j in 0..k {
                let cos_jk = ct[j] * ct[k] + st[j] * st[k];
                let sin_kj = st[k] * ct[j] - ct[k] * st[j];
                let v = self.ell[j] * (self.ell[k] * self.mu[k] * cos_jk - coupling * sin_kj);
                out[(j, k)] = v;
                out[(k, j)] = v;
            }
            out[(k, k)] = self.a_diag[k] + coupling * dk * kin.sin_psi[k];
        }
        if self.torsion {
            for k in 0..n {
                let w = self.mass[k] * self.d0[k] * kin.cos_psi[k];
                for j in 0..n {
                    let v = if j < k {
                        w * self.ell[j] * (ct[j] * ct[k] + st[j] * st[k])
                    } else if j == k {
                        w * 0.5 * self.ell[k]
                    } else {
                        0.0
                    };
                    out[(j, n + k)] = v;
                    out[(n + k, j)] = v;
                }
                for j in 0..n {
                    out[(n + j, n + k)] = 0.0;
                }
                out[(n + k, n + k)] = self.mass[k] * self.d0[k] * self.d0[k] + self.inertia[k];
            }
        }
        if let Some(f) = &self.fluid {
            self.add_fluid_mass(kin, f, out);
        }
        suffix_sum_blocks(out, n);
    }

    /// The fluid's `Σ_i m_a,i r_i r_iᵀ + J_a,i` in absolute angles (`model::aero::fluid`), in
    /// O(n²): for `j ≤ k`, `Σ_{i>k} w_i cos(θ_i − θ_j) cos(θ_i − θ_k)` with `w_i = m_a,i cos²ψ_i`
    /// expands into suffix sums of `w_i (cos²θ_i, cos θ_i sin θ_i, sin²θ_i)`.
    fn add_fluid_mass(&self, kin: &Kinematics, f: &FluidInertia, out: &mut DMatrix<f64>) {
        let n = self.n;
        let (ct, st) = (&kin.cos_theta, &kin.sin_theta);
        let (mut scc, mut scs, mut sss) = (0.0, 0.0, 0.0); // Σ_{i>k}
        for k in (0..n).rev() {
            let cp = kin.cos_psi[k];
            let wk = f.mass[k] * cp * cp;
            let lk = self.ell[k];
            for j in 0..k {
                let lj = self.ell[j];
                let outboard = lj
                    * lk
                    * (ct[j] * ct[k] * scc
                        + (ct[j] * st[k] + st[j] * ct[k]) * scs
                        + st[j] * st[k] * sss);
                let own = wk * lj * 0.5 * lk * (ct[k] * ct[j] + st[k] * st[j]);
                out[(j, k)] += outboard + own;
                out[(k, j)] += outboard + own;
            }
            out[(k, k)] +=
                lk * lk * (ct[k] * ct[k] * scc + 2.0 * ct[k] * st[k] * scs + st[k] * st[k] * sss)
                    + wk * 0.25 * lk * lk;
            if self.torsion {
                // (θ_j, ψ_k), j ≤ k: m_a,k ζ_k cos ψ_k a_kj cos(θ_k − θ_j).
                let z = f.mass[k] * f.station[k] * cp;
                for j in 0..=k {
                    let a = if j < k { self.ell[j] } else { 0.5 * lk };
                    let v = z * a * (ct[k] * ct[j] + st[k] * st[j]);
                    out[(j, n + k)] += v;
                    out[(n + k, j)] += v;
                }
                out[(n + k, n + k)] += f.mass[k] * f.station[k] * f.station[k] + f.inertia[k];
            }
            scc += wk * ct[k] * ct[k];
            scs += wk * ct[k] * st[k];
            sss += wk * st[k] * st[k];
        }
    }
}

/// In place `X ← Tᵀ X T` with `T = blockdiag(T_n, …)`, `T_n` lower-triangular ones:
/// `(Tᵀ X T)_ab = Σ_{j ≥ a} Σ_{k ≥ b} X_jk`, the sums running to the end of each block.
pub(crate) fn suffix_sum_blocks(x: &mut DMatrix<f64>, n: usize) {
    let nd = x.nrows();
    let data = x.as_mut_slice(); // column-major: column c is data[c * nd..(c + 1) * nd]
    for column in data.chunks_mut(nd) {
        suffix_sum_in_blocks(column, n);
    }
    for start in (0..nd).step_by(n) {
        for col in (start..start + n - 1).rev() {
            let (left, right) = data.split_at_mut((col + 1) * nd);
            let dst = &mut left[col * nd..];
            for (d, s) in dst.iter_mut().zip(&right[..nd]) {
                *d += *s;
            }
        }
    }
}

impl FullModel {
    /// Diagonal of the mass matrix `M(q)` at `kin`, into `out` (`n_dofs` entries), in O(n)
    /// without forming `M`: `M_ii` is the kinetic energy (times 2) of the part outboard of
    /// joint `i` turning rigidly at unit rate about it, `Σ_{k≥i} m_k |g_k,xy − P_{i−1}|²` for a
    /// bending joint (turning about `ẑ` through node `i − 1`) and `Σ_{k≥i} (m_k d0_k² + J_k)` for a
    /// torsion joint (turning about each element's axis). Accumulated from the tip about the
    /// moving node (parallel-axis recursion), so that no large terms cancel.
    ///
    /// # Panics
    /// If `out.len() != n_dofs()`.
    pub fn mass_diagonal_into(&self, kin: &Kinematics, out: &mut [f64]) {
        let n = self.n;
        assert_eq!(
            out.len(),
            self.n_dofs(),
            "diagonal buffer has the wrong length"
        );
        let nodes = self.node_positions(kin);
        let centres = self.mass_centres(kin);
        // About node i: I = Σ m |g − P_i|², s = Σ m (g − P_i), mass Σ m, over k > i.
        let (mut inertia, mut first, mut mass) = (0.0, [0.0; 2], 0.0);
        let mut torsion = 0.0;
        for i in (0..n).rev() {
            // Move the reference point from node i + 1 to node i: d = P_{i+1} − P_i.
            let d = [nodes[i + 1][0] - nodes[i][0], nodes[i + 1][1] - nodes[i][1]];
            inertia +=
                2.0 * (d[0] * first[0] + d[1] * first[1]) + (d[0] * d[0] + d[1] * d[1]) * mass;
            first[0] += mass * d[0];
            first[1] += mass * d[1];
            let r = [centres[i][0] - nodes[i][0], centres[i][1] - nodes[i][1]];
            let m = self.mass[i];
            inertia += m * (r[0] * r[0] + r[1] * r[1]) + self.rotary[i];
            first[0] += m * r[0];
            first[1] += m * r[1];
            mass += m;
            out[i] = inertia;
            if self.torsion {
                torsion += m * self.d0[i] * self.d0[i] + self.inertia[i];
                out[n + i] = torsion;
            }
        }
    }
}
