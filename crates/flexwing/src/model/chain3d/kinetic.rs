//! Momentum `p = M(x) ẋ` and gyroscopic term `γ = ∂T/∂x|_ẋ` of the 3-D chain in O(n), generic
//! over the scalar (dual numbers give their exact derivatives). Derivation in
//! docs/chain3d-model.md, "Kinetic energy"; the recursions are those of a serial chain of rigid
//! bodies with spherical joints (Featherstone, *Rigid Body Dynamics Algorithms*, 2008, ch. 5–7).
//!
//! With the outboard linear momentum `Π_j` and angular momentum about node `j`, `L_j`
//! ([`super::kinematics::Motion`]):
//!
//! ```text
//! p_j = H_jᵀ L_j
//! γ_j = H_jᵀ (L_j × ω_j + Π_j × V_j) + (∂(T_L(φ_j) φ̇_j)/∂φ_j)ᵀ B_jᵀ L_j
//! ```
//!
//! The first term of `γ_j` is the derivative of `T` under the rigid rotation of the outboard part
//! about `P_j` that `δφ_j` makes (the velocities of the outboard joints turn with it, `ω_j` and
//! `V_j` do not), the second the change of the joint's own axes `H_j` with `φ_j`.

use super::algebra::{cross, dot, mtv, Real};
use super::kinematics::{Frames, Motion};
use super::rotation::tangent_left_derivative;
use super::Chain3d;

impl Chain3d {
    /// `p = M ẋ` and/or `γ = ∂T/∂x|_ẋ` at the configuration `fr` for the rates `xdot`, from the
    /// motion `mo` (filled here). O(n).
    pub(crate) fn kinetic_terms<D: Real>(
        &self,
        fr: &Frames<D>,
        xdot: &[D],
        mo: &mut Motion<D>,
        p: Option<&mut [D]>,
        gamma: Option<&mut [D]>,
    ) {
        self.motion(fr, xdot, mo);
        if let Some(p) = p {
            for j in 0..self.n {
                let v = mtv(&fr.h[j], &mo.l[j]);
                p[3 * j..3 * j + 3].copy_from_slice(&v);
            }
        }
        if let Some(g) = gamma {
            for j in 0..self.n {
                let rigid = super::algebra::add(
                    &cross(&mo.l[j], &mo.omega[j]),
                    &cross(&mo.pi[j], &mo.v[j]),
                );
                let mut v = mtv(&fr.h[j], &rigid);
                let rate = [xdot[3 * j], xdot[3 * j + 1], xdot[3 * j + 2]];
                let dt = tangent_left_derivative(&fr.phi[j], &rate, &fr.coefficients[j]);
                let lambda = mtv(&fr.b[j], &mo.l[j]);
                let axes = mtv(&dt, &lambda);
                for a in 0..3 {
                    v[a] += axes[a];
                }
                g[3 * j..3 * j + 3].copy_from_slice(&v);
            }
        }
    }

    /// Kinetic energy `T = ½ Σ (m_i |ġ_i|² + ω_iᵀ I_i ω_i)` from a motion `mo`.
    pub(crate) fn kinetic_energy_of<D: Real>(&self, fr: &Frames<D>, mo: &Motion<D>) -> D {
        let mut t = D::from(0.0);
        for i in 0..self.n {
            let m = self.beam.masses[i];
            let w = &mo.omega[i];
            let iw = super::algebra::mv(&fr.inertia[i], w);
            t += dot(&mo.gdot[i], &mo.gdot[i]) * m + dot(w, &iw);
            if let Some(f) = &self.fluid {
                let (u, _, axis) = self.fluid_motion(fr, mo, i);
                let spin = dot(w, &axis);
                t += u * u * f.mass[i] + spin * spin * f.inertia[i];
            }
        }
        t * 0.5
    }
}
