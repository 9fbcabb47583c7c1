//! The velocity solve `M(q) q̇ = p` in O(n), by a backward Riccati sweep along the chain and a
//! forward substitution, without ever forming `M` (the idea of the articulated-body algorithm).
//!
//! # References
//! R. Featherstone, *Rigid Body Dynamics Algorithms*, Springer (2008), ch. 7 (the articulated-body
//! algorithm: a backward sweep of articulated inertias from the tip, then a forward sweep); here
//! the same two sweeps solve the planar chain's linear–quadratic problem below.
//!
//! # Derivation
//!
//! Work in absolute angle rates, one pair per element, `u_i = (θ̇_i, ψ̇_i)`. The mass-centre
//! velocities of `model::kinetic` are, with the in-plane node velocities `V_i ∈ R²`,
//!
//! ```text
//! V_0 = 0,   V_i = V_{i−1} + A_i u_i,       A_i = [ℓ_i n_i, 0]                      (2 × 2)
//! ġ_i = V_{i−1} + B_i u_i,                  B_i = [b_θ,i, b_ψ,i]                   (3 × 2)
//! b_θ,i = (ℓ_i/2) n_i − d0_i sin ψ_i e_i,   b_ψ,i = d0_i (cos ψ_i n_i − sin ψ_i ẑ)
//! ```
//!
//! (`V` has no `ẑ` component; only `b_ψ` has one), so the kinetic energy is
//! `T(u) = ½ Σ_i m_i |V_{i−1} + B_i u_i|² + ½ Σ_i J_i ψ̇_i² + ½ Σ_i J_b,i θ̇_i² = ½ uᵀ M_abs u`
//! (`J_b`, rotary inertia in bending, is zero in the paper's model). `M_abs` is symmetric
//! positive definite, so `M_abs u = p_abs` is the minimum of `T(u) − p_absᵀ u`: a linear–quadratic
//! control problem with state `V` and controls `u_i`, solved by dynamic programming from the tip.
//! The cost to go from node `i`, `W_i(V) = ½ Vᵀ P_i V − w_iᵀ V + const` (`P_n = 0`, `w_n = 0`),
//! gives at element `i`, writing `P = P_i`, `w = w_i`, `V = V_{i−1}`:
//!
//! ```text
//! ½ m_i |V + B_i u|² + ½ J_i ψ̇² − p_iᵀ u + W_i(V + A_i u)
//!     = ½ uᵀ H_i u + uᵀ (G_i V − g_i) + ½ Vᵀ (m_i I + P) V − wᵀ V
//! H_i = m_i B_iᵀ B_i + diag(J_b,i, J_i) + A_iᵀ P A_i    (2 × 2)
//! G_i = m_i B_i,xyᵀ + A_iᵀ P                             (2 × 2, B_i,xy the in-plane rows)
//! g_i = p_i + A_iᵀ w
//! ```
//!
//! minimized by `u_i = k_i − K_i V` with `K_i = H_i⁻¹ G_i`, `k_i = H_i⁻¹ g_i`, which leaves
//!
//! ```text
//! P_{i−1} = m_i I + P − G_iᵀ K_i,       w_{i−1} = w − G_iᵀ k_i.
//! ```
//!
//! The backward sweep is block Gaussian elimination of `M_abs` from the tip: the `H_i` are its
//! pivots (Schur complements), so `M_abs` is positive definite exactly when every `H_i` is, which
//! the 2 × 2 `L D Lᵀ` factorization of each `H_i` checks. The forward sweep `V_0 = 0`,
//! `u_i = k_i − K_i V_{i−1}`, `V_i = V_{i−1} + A_i u_i` then gives `u`. With `B_iᵀ B_i` written out,
//! `H_i = [m_i |b_θ|² + ℓ_i² n_iᵀ P n_i,  m_i b_θ·b_ψ;  m_i b_θ·b_ψ,  m_i d0_i² + J_i]`
//! (`|b_ψ|² = d0²` for any `ψ`). A bending-only model has no `ψ̇`: it runs the same recursion with
//! `b_ψ = 0` and the placeholder pivot `H_ψψ = 1`, `p_ψ = 0`, which makes `ψ̇_i = 0`.
//!
//! Joint coordinates: `p = Tᵀ p_abs` and `u = T q̇` blockwise (`T` lower-triangular ones), so
//! `p_abs,i = p_i − p_{i+1}` and `q̇_i = u_i − u_{i−1}` (differences, O(n)). The whole solve is
//! about 80 flops per element and allocates nothing; it is generic over the scalar so that its
//! derivatives come from dual numbers.
//!
//! # The diagonal of `M⁻¹` in O(n)
//!
//! The backward sweep is also a factorization of the Gaussian density `∝ exp(−½ uᵀ M_abs u)`,
//! whose covariance is `M_abs⁻¹`: integrating out `u_n, u_{n−1}, …` from the tip (the same Schur
//! complements as the minimization) leaves `u_i | u_{<i} ~ N(−K_i V_{i−1}, H_i⁻¹)`, so `u` is
//! generated forward by `u_i = −K_i V_{i−1} + ε_i`, `V_i = F_i V_{i−1} + A_i ε_i` with
//! `F_i = I − A_i K_i`, `ε_i ~ N(0, H_i⁻¹)` independent, `V_0 = 0`. One forward sweep of the
//! node-velocity covariance `Σ_i = Cov(V_i)` then gives every block needed, 2 × 2 each:
//!
//! ```text
//! Σ_i = F_i Σ_{i−1} F_iᵀ + A_i H_i⁻¹ A_iᵀ                 (Σ_0 = 0, a sum of PSD terms)
//! S_ii = Cov(u_i) = K_i Σ_{i−1} K_iᵀ + H_i⁻¹
//! C_i = Cov(V_i, u_i) = −F_i Σ_{i−1} K_iᵀ + A_i H_i⁻¹
//! Cov(u_{i+1}, u_i) = −K_{i+1} C_i
//! ```
//!
//! and with `q̇_i = u_i − u_{i−1}` (per component θ, ψ), `(M⁻¹)_ii = Var(q̇_i) = S_ii + S_{i−1,i−1}
//! − 2 Cov(u_i, u_{i−1})`. This is the chain case of the O(n) diagonal of a tree's inverse mass
//! matrix (the "inverse inertia" sweeps of the articulated-body literature; here in the language
//! of the Rauch–Tung–Striebel smoother's covariances, Anderson & Moore, *Optimal Filtering*, §7.2).
//!
//! # References
//! Featherstone, *Rigid Body Dynamics Algorithms*, Springer 2008, ch. 7 (the articulated-body
//! algorithm, the same backward/forward structure for the inverse of a chain's mass matrix);
//! Anderson & Moore, *Optimal Control: Linear Quadratic Methods*, §2.4 (the discrete Riccati
//! recursion).

use num_dual::DualNum;

use super::kinetic::KineticScratch;
use super::FullModel;

/// The factorization of `M(q)` by the backward sweep, per element: the `L D Lᵀ` factors of
/// `H_i`, the gain `K_i = H_i⁻¹ G_i` (row-major 2 × 2) and `G_i`; then the feed-forward terms
/// `k_i` of the last solve. Everything but `k_i` depends on `q` only, so one factorization
/// serves any number of right-hand sides at about a third of the cost of each.
#[derive(Debug, Clone)]
pub(crate) struct ChainScratch<D> {
    pivot: Vec<(D, D, D)>,
    gain: Vec<[D; 4]>,
    coupling: Vec<[D; 4]>,
    feed: Vec<[D; 2]>,
}

impl<D: DualNum<Primitive = f64> + Copy> ChainScratch<D> {
    pub(crate) fn new(n: usize) -> Self {
        let z = D::from(0.0);
        Self {
            pivot: vec![(z, z, z); n],
            gain: vec![[z; 4]; n],
            coupling: vec![[z; 4]; n],
            feed: vec![[z; 2]; n],
        }
    }
}

/// `x = H⁻¹ y` for the symmetric `H = [h00 h01; h01 h11]` factored as `(h00, l, d1)` with
/// `l = h01/h00`, `d1 = h11 − l h01`.
#[inline]
fn solve2<D: DualNum<Primitive = f64> + Copy>(f: (D, D, D), y: [D; 2]) -> [D; 2] {
    let (d0, l, d1) = f;
    let x1 = (y[1] - l * y[0]) / d1;
    [y[0] / d0 - l * x1, x1]
}

impl FullModel {
    /// Velocities `q̇ = M(q)⁻¹ p` into `out` at the configuration whose trigonometry `sc` holds
    /// (see [`FullModel::configure`]), in O(n) (module documentation). Returns false, with `out`
    /// unspecified, if `M(q)` is not numerically positive definite.
    pub(crate) fn solve_mass_configured<D: DualNum<Primitive = f64> + Copy>(
        &self,
        sc: &KineticScratch<D>,
        p: &[D],
        chain: &mut ChainScratch<D>,
        out: &mut [D],
    ) -> bool {
        if !self.factor_mass_configured(sc, chain) {
            return false;
        }
        self.solve_factored(sc, chain, p, out);
        true
    }

    /// The backward sweep's `p`-independent part: pivots `H_i`, gains `K_i`, couplings `G_i`.
    /// False if a pivot is not positive definite (then `M(q)` is not).
    pub(crate) fn factor_mass_configured<D: DualNum<Primitive = f64> + Copy>(
        &self,
        sc: &KineticScratch<D>,
        chain: &mut ChainScratch<D>,
    ) -> bool {
        // Two monomorphic versions: in vacuo, exactly the arithmetic of the dry chain.
        if self.fluid.is_some() {
            self.factor_impl::<D, true>(sc, chain)
        } else {
            self.factor_impl::<D, false>(sc, chain)
        }
    }

    fn factor_impl<D: DualNum<Primitive = f64> + Copy, const FLUID: bool>(
        &self,
        sc: &KineticScratch<D>,
        chain: &mut ChainScratch<D>,
    ) -> bool {
        let zero = D::from(0.0);
        // P = [p00 p01; p01 p11].
        let (mut p00, mut p01, mut p11) = (zero, zero, zero);
        for i in (0..self.n).rev() {
            let (c, s) = (sc.cos_theta[i], sc.sin_theta[i]);
            let (l, h, d, m) = (self.ell[i], 0.5 * self.ell[i], self.d0[i], self.mass[i]);
            let nv = [-s, c];
            // b_θ (in plane) and b_ψ (in plane, plus −d0 sin ψ ẑ).
            let (bt, bp, h11) = if self.torsion {
                let (cp, sp) = (sc.cos_psi[i], sc.sin_psi[i]);
                (
                    [nv[0] * h - c * sp * d, nv[1] * h - s * sp * d],
                    [nv[0] * cp * d, nv[1] * cp * d],
                    D::from(m * d * d + self.inertia[i]),
                )
            } else {
                ([nv[0] * h, nv[1] * h], [zero; 2], D::from(1.0))
            };
            // P a with a = ℓ n.
            let pa = [
                (p00 * nv[0] + p01 * nv[1]) * l,
                (p01 * nv[0] + p11 * nv[1]) * l,
            ];
            let mut h00 = (bt[0] * bt[0] + bt[1] * bt[1]) * m
                + (pa[0] * nv[0] + pa[1] * nv[1]) * l
                + D::from(self.rotary[i]);
            let mut h01 = (bt[0] * bp[0] + bt[1] * bp[1]) * m;
            let mut h11 = h11;
            // G rows: m b_θ + P a, and m b_ψ.
            let mut g0 = [bt[0] * m + pa[0], bt[1] * m + pa[1]];
            let mut g1 = [bp[0] * m, bp[1] * m];
            // The fluid (model::aero::fluid): ½ m_a (rᵀV + βᵀu)², r = cos ψ n, β = ((ℓ/2) cos ψ, ζ_m).
            if let (true, Some(f)) = (FLUID, &self.fluid) {
                let ma = f.mass[i];
                let cp = if self.torsion {
                    sc.cos_psi[i]
                } else {
                    D::from(1.0)
                };
                let r = [nv[0] * cp, nv[1] * cp];
                let b0 = cp * h;
                h00 += b0 * b0 * ma;
                g0 = [g0[0] + b0 * r[0] * ma, g0[1] + b0 * r[1] * ma];
                if self.torsion {
                    let b1 = D::from(f.station[i]);
                    h01 += b0 * b1 * ma;
                    h11 += b1 * b1 * ma + D::from(f.inertia[i]);
                    g1 = [g1[0] + b1 * r[0] * ma, g1[1] + b1 * r[1] * ma];
                }
                // P += m_a r rᵀ (the rest of the P update below).
                p00 += r[0] * r[0] * ma;
                p01 += r[0] * r[1] * ma;
                p11 += r[1] * r[1] * ma;
            }
            if !(h00.re() > 0.0) {
                return false;
            }
            let lf = h01 / h00;
            let d1 = h11 - lf * h01;
            if !(d1.re() > 0.0) {
                return false;
            }
            let f = (h00, lf, d1);
            // K = H⁻¹ G column by column (columns of G are the V components).
            let kx = solve2(f, [g0[0], g1[0]]);
            let ky = solve2(f, [g0[1], g1[1]]);
            chain.pivot[i] = f;
            chain.gain[i] = [kx[0], ky[0], kx[1], ky[1]];
            chain.coupling[i] = [g0[0], g0[1], g1[0], g1[1]];
            // P ← m I + P − Gᵀ K, with Gᵀ = [g0 g1] (columns).
            p00 += D::from(m) - (g0[0] * kx[0] + g1[0] * kx[1]);
            p01 -= g0[0] * ky[0] + g1[0] * ky[1];
            p11 += D::from(m) - (g0[1] * ky[0] + g1[1] * ky[1]);
        }
        true
    }

    /// `out = M(q)⁻¹ p` with the factorization of [`Self::factor_mass_configured`]: the
    /// backward sweep of `w` and `k_i`, then the forward sweep.
    pub(crate) fn solve_factored<D: DualNum<Primitive = f64> + Copy>(
        &self,
        sc: &KineticScratch<D>,
        chain: &mut ChainScratch<D>,
        p: &[D],
        out: &mut [D],
    ) {
        let n = self.n;
        let zero = D::from(0.0);
        let mut w = [zero; 2];
        for i in (0..n).rev() {
            // Absolute-angle momenta: differences of the joint momenta.
            let next = |k: usize| if i + 1 < n { p[k + 1] } else { zero };
            let p_th = p[i] - next(i);
            let p_ps = if self.torsion {
                p[n + i] - next(n + i)
            } else {
                zero
            };
            let (c, s, l) = (sc.cos_theta[i], sc.sin_theta[i], self.ell[i]);
            let rhs = [p_th + (c * w[1] - s * w[0]) * l, p_ps];
            let k = solve2(chain.pivot[i], rhs);
            let g = chain.coupling[i];
            // w ← w − Gᵀ k.
            w[0] -= g[0] * k[0] + g[2] * k[1];
            w[1] -= g[1] * k[0] + g[3] * k[1];
            chain.feed[i] = k;
        }
        // Forward sweep, and joint rates as differences of the absolute ones.
        let mut v = [zero; 2];
        let (mut prev_th, mut prev_ps) = (zero, zero);
        for i in 0..n {
            let kk = chain.gain[i];
            let k = chain.feed[i];
            let u_th = k[0] - kk[0] * v[0] - kk[1] * v[1];
            out[i] = u_th - prev_th;
            prev_th = u_th;
            if self.torsion {
                let u_ps = k[1] - kk[2] * v[0] - kk[3] * v[1];
                out[n + i] = u_ps - prev_ps;
                prev_ps = u_ps;
            }
            let l = self.ell[i];
            v[0] -= sc.sin_theta[i] * u_th * l;
            v[1] += sc.cos_theta[i] * u_th * l;
        }
    }

    /// Diagonal of `M(q)⁻¹` in joint coordinates into `out`, in O(n), with the factorization of
    /// [`Self::factor_mass_configured`]: one forward sweep of the node-velocity covariance
    /// (module documentation, "The diagonal of `M⁻¹` in O(n)"). A bending-only model fills the
    /// first `n` entries.
    pub(crate) fn inverse_diagonal_factored(
        &self,
        sc: &KineticScratch<f64>,
        chain: &ChainScratch<f64>,
        out: &mut [f64],
    ) {
        type M2 = [[f64; 2]; 2];
        let mul = |a: &M2, b: &M2| -> M2 {
            let mut c = [[0.0; 2]; 2];
            for r in 0..2 {
                for k in 0..2 {
                    c[r][k] = a[r][0] * b[0][k] + a[r][1] * b[1][k];
                }
            }
            c
        };
        let tr = |a: &M2| -> M2 { [[a[0][0], a[1][0]], [a[0][1], a[1][1]]] };
        let n = self.n;
        // Σ_{i−1}, Cov(V_{i−1}, u_{i−1}) and Var(u_{i−1}) carried from the previous element.
        let mut sigma: M2 = [[0.0; 2]; 2];
        let mut c_prev: M2 = [[0.0; 2]; 2];
        let mut s_prev: M2 = [[0.0; 2]; 2];
        for i in 0..n {
            let g = chain.gain[i];
            let k: M2 = [[g[0], g[1]], [g[2], g[3]]];
            // H⁻¹ column by column.
            let h0 = solve2(chain.pivot[i], [1.0, 0.0]);
            let h1 = solve2(chain.pivot[i], [0.0, 1.0]);
            let hinv: M2 = [[h0[0], h1[0]], [h0[1], h1[1]]];
            // A = [ℓ n, 0]: A X has rows ℓ n_r X[0][·].
            let l = self.ell[i];
            let a_col = [-sc.sin_theta[i] * l, sc.cos_theta[i] * l];
            let a_mul = |x: &M2| -> M2 {
                [
                    [a_col[0] * x[0][0], a_col[0] * x[0][1]],
                    [a_col[1] * x[0][0], a_col[1] * x[0][1]],
                ]
            };
            let ak = a_mul(&k);
            let f: M2 = [[1.0 - ak[0][0], -ak[0][1]], [-ak[1][0], 1.0 - ak[1][1]]];
            let sigma_kt = mul(&sigma, &tr(&k));
            let ks = mul(&k, &sigma_kt);
            let s_ii: M2 = [
                [ks[0][0] + hinv[0][0], ks[0][1] + hinv[0][1]],
                [ks[1][0] + hinv[1][0], ks[1][1] + hinv[1][1]],
            ];
            // Cov(u_i, u_{i−1}) = −K_i C_{i−1}.
            let cross = mul(&k, &c_prev);
            out[i] = s_ii[0][0] + s_prev[0][0] + 2.0 * cross[0][0];
            if self.torsion {
                out[n + i] = s_ii[1][1] + s_prev[1][1] + 2.0 * cross[1][1];
            }
            // C_i = −F Σ Kᵀ + A H⁻¹, Σ_i = F Σ Fᵀ + A H⁻¹ Aᵀ.
            let fsk = mul(&f, &sigma_kt);
            let ah = a_mul(&hinv);
            c_prev = [
                [ah[0][0] - fsk[0][0], ah[0][1] - fsk[0][1]],
                [ah[1][0] - fsk[1][0], ah[1][1] - fsk[1][1]],
            ];
            let fsf = mul(&f, &mul(&sigma, &tr(&f)));
            let q = hinv[0][0];
            sigma = [
                [
                    fsf[0][0] + a_col[0] * a_col[0] * q,
                    fsf[0][1] + a_col[0] * a_col[1] * q,
                ],
                [
                    fsf[1][0] + a_col[1] * a_col[0] * q,
                    fsf[1][1] + a_col[1] * a_col[1] * q,
                ],
            ];
            s_prev = s_ii;
        }
    }
}
