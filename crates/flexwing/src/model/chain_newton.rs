//! O(n) solves of the chain's linearized equations of motion about a moving state, and of its
//! static tangent: the Newton systems of the implicit integrators and of statics, by a backward
//! Riccati sweep and a forward substitution along the chain that never form a matrix.
//!
//! For a perturbation `δu = (δθ_j, δψ_j)` of the absolute angles with rates `δu̇ = c_v δu`, the
//! swept operator is
//!
//! ```text
//! S δu = c_p δp(δu, δu̇) − g δ(∂T/∂u)(δu, δu̇) + κ K δu + G δu,
//! ```
//!
//! `p = ∂T/∂u̇`, `T` the kinetic energy (model.md), `K` the joint springs, `G = −∂Q/∂u` the load
//! stiffness; `g = 1` with the gyroscopic term, `0` without (the simplified model). With
//! `c_p = c_v = c` and `κ = 1` it is the operator `c² M + c (B − Bᵀ) + K − ∂Q/∂q − ∂γ/∂q|_q̇`
//! (`B = ∂(M q̇)/∂q`) to which an implicit method's Newton system `(c I − J) Δ = r` on the
//! Hamiltonian state `(q, p)` reduces exactly (docs/model-choices.md, "O(n) Newton systems";
//! `solve/eom_newton.rs`); Rayleigh damping enters as `c_p = c + α`, `κ = 1 + β c`; statics is
//! `c_p = c_v = 0`, `κ = 1`.
//!
//! The operator keeps the chain's structure because everything an element contributes depends on
//! its own angles and on the velocity perturbation `δV_{j−1}` of its inboard node: with the
//! interface state `s_j = (δV_j, δθ_j, δψ_j)` and the reaction of the chain outboard of it,
//! `r_j = (δS_j, F_j, spring_θ, spring_ψ)` (`δS_j` the perturbed momentum of the outboard
//! elements, `F_j` the perturbed follower forces, the springs of joint `j + 1`),
//!
//! ```text
//! s_j = E s_{j−1} + A_j δu_j,                 A_j = [a_j, 0; 1, 0; 0, 1],  a_j = ℓ_j (c_v n_j − θ̇_j e_j)
//! row j:   H_j δu_j + G_j s_{j−1} + Â_jᵀ r_j = b_j,      Â_j = [â_j, 0; ℓ_j n_j, 0; 1, 0; 0, 1]
//! r_{j−1} = F r_j + L_j δu_j + N_j s_{j−1}
//! ```
//!
//! (`E = diag(1, 1, 0, 0)`, `F = diag(1, 1, 1, 1, 0, 0)`, `â_j = ℓ_j (c_p n_j + g θ̇_j e_j)`; the
//! element blocks `H_j`, `G_j`, `L_j`, `N_j` are written out in docs/model-choices.md). The
//! ansatz `r_j = P_j s_j + w_j` (`P` 6 × 4, `P_n = 0`, `w_n = 0`) gives from the tip
//!
//! ```text
//! Ĥ = H_j + Âᵀ P A,   Ĝ = G_j + Âᵀ P E,   L̂ = F P A + L_j,   K_j = Ĥ⁻¹ Ĝ
//! P_{j−1} = F P E + N_j − L̂ K_j,        w_{j−1} = F w + L̂ Ĥ⁻¹ (b_j − Âᵀ w)
//! ```
//!
//! and forward `δu_j = Ĥ⁻¹ (b_j − Âᵀ w_j) − K_j s_{j−1}`. Joint coordinates enter by
//! `b_abs,j = b_j − b_{j+1}` and `x_j = δu_j − δu_{j−1}` (blockwise), as in `model::chain_solve`.
//! This is the articulated-body idea (Featherstone, *Rigid Body Dynamics Algorithms*, Springer
//! 2008, ch. 7: the chain eliminated joint by joint from the tip, joint-space terms — there the
//! armature, here the springs, the shifts and the load stiffness — added to each joint's pivot)
//! in the form of the discrete two-point boundary-value problem of linear–quadratic control
//! (Anderson & Moore, *Optimal Control: Linear Quadratic Methods*, §2.4), here not symmetric.
//!
//! For a real symmetric operator (statics with conservative loads: `c = 0`) the sweep is block
//! `L D Lᵀ` elimination from the tip: the pivots `Ĥ` are Schur complements, so their eigenvalue
//! signs give the operator's inertia (Sylvester), which [`ChainFactor::negative_pivots`] reports.
//! About 200 scalar operations per element; nothing allocates after construction.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};

use nalgebra::Complex;
use num_dual::Dual64;

use super::kinetic::KineticScratch;
use super::loads::Resultants;
use super::{AppliedLoads, FullModel, Kinematics};

/// The scalars of the sweeps: `f64` (statics, real shifts) and `Complex<f64>` (complex shifts).
pub(crate) trait Field:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Mul<f64, Output = Self>
    + AddAssign
    + SubAssign
    + From<f64>
{
    /// Whether every part is finite.
    fn finite(self) -> bool;
    /// `|re| + |im|`.
    fn norm1(self) -> f64;
}

impl Field for f64 {
    fn finite(self) -> bool {
        self.is_finite()
    }
    fn norm1(self) -> f64 {
        self.abs()
    }
}

impl Field for Complex<f64> {
    fn finite(self) -> bool {
        self.re.is_finite() && self.im.is_finite()
    }
    fn norm1(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
}

/// The coefficients of the swept operator (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shift<T> {
    /// Rates per unit perturbation, `δu̇ = c_v δu`.
    pub(crate) cv: T,
    /// Multiplier of the momentum perturbation.
    pub(crate) cp: T,
    /// Multiplier of the joint springs.
    pub(crate) kappa: T,
    /// Whether the gyroscopic term `∂T/∂u` is in the equations (`g`).
    pub(crate) gyroscopic: bool,
}

impl Shift<f64> {
    /// The static tangent `K + G`.
    pub(crate) fn statics() -> Self {
        Self {
            cv: 0.0,
            cp: 0.0,
            kappa: 1.0,
            gyroscopic: true,
        }
    }
}

/// Per-element data of the linearization that the sweeps read (all at the linearization point).
#[derive(Debug, Clone, Copy, Default)]
struct Element {
    ell: f64,
    m: f64,
    /// Polar inertia `J` (0 without torsion).
    inertia: f64,
    /// Rotary inertia in bending `J_b` (0 in the paper's model).
    rotary: f64,
    /// Joint springs `k_θ`, `k_ψ` (0 without torsion).
    k: [f64; 2],
    e: [f64; 2],
    n: [f64; 2],
    theta_dot: f64,
    /// `B = ∂ġ/∂u̇`: `b_θ` (in plane), `b_ψ` (in plane, and its `ẑ` part).
    bt: [f64; 2],
    bp: [f64; 3],
    /// `C = ∂(B u̇)/∂u` at the current rates, same layout.
    ct: [f64; 2],
    cp: [f64; 3],
    /// `∂(Bᵀ ġ)/∂u` and `∂(Cᵀ ġ)/∂u` at fixed `ġ`, symmetric, as `[θθ, θψ, ψψ]`.
    d: [f64; 3],
    ee: [f64; 3],
    /// `n · S` and `e · S`, `S` the momentum of the elements outboard.
    n_s: f64,
    e_s: f64,
    /// Local load stiffness `[θθ, θψ, ψψ]` and follower-force rate `f'`.
    load: [f64; 3],
    rate: [f64; 2],
}

/// The chain at one state `(q, q̇)` and load level: what the sweeps need, computed once per
/// linearization in O(n + load items).
#[derive(Debug, Clone)]
pub(crate) struct ChainLinearization {
    kin: Kinematics,
    kinetic: KineticScratch<f64>,
    resultants: Resultants,
    elements: Vec<Element>,
    local: Vec<[f64; 3]>,
    rate: Vec<[f64; 2]>,
    symmetric: bool,
    /// Whether the load stiffness's chain form is exact (`Resultants::chain_exact`).
    exact: bool,
    /// Velocities of the linearization point (zeros at rest).
    qdot: Vec<f64>,
    duals: Duals,
}

/// Dual-number buffers of the products with the linearized momentum and gyroscopic term.
#[derive(Debug, Clone)]
struct Duals {
    scratch: KineticScratch<Dual64>,
    qdot: Vec<Dual64>,
    p: Vec<Dual64>,
    gamma: Vec<Dual64>,
    abs: Vec<f64>,
    zeros: Vec<f64>,
}

impl ChainLinearization {
    /// Buffers for `model`, linearized at rest in the undeformed state without loads.
    pub(crate) fn new(model: &FullModel) -> Self {
        let n = model.n;
        let nd = model.n_dofs();
        let z = Dual64::from(0.0);
        let mut lin = Self {
            kin: Kinematics::new(n),
            kinetic: KineticScratch::new(n),
            resultants: Resultants::zeros(n),
            elements: vec![Element::default(); n],
            local: vec![[0.0; 3]; n],
            rate: vec![[0.0; 2]; n],
            symmetric: true,
            exact: true,
            qdot: vec![0.0; nd],
            duals: Duals {
                scratch: KineticScratch::new(n),
                qdot: vec![z; nd],
                p: vec![z; nd],
                gamma: vec![z; nd],
                abs: vec![0.0; nd],
                zeros: vec![0.0; nd],
            },
        };
        lin.update(model, &vec![0.0; nd], None, None);
        lin
    }

    /// Linearize at the coordinates `q` with velocities `qdot` (`None`: at rest) and the loads
    /// `loads` scaled by `scales` (or none).
    ///
    /// # Panics
    /// If a slice has not `n_dofs` entries.
    pub(crate) fn update(
        &mut self,
        model: &FullModel,
        q: &[f64],
        qdot: Option<&[f64]>,
        loads: Option<(&AppliedLoads, &[f64])>,
    ) {
        let n = model.n;
        self.kin.update(q);
        model.configure_from(&self.kin, &mut self.kinetic);
        match qdot {
            Some(v) => self.qdot.copy_from_slice(v),
            None => self.qdot.fill(0.0),
        }
        // Rates, mass-centre velocities ġ_j (and the momentum, unused) at the state.
        model.kinetic_terms_configured(&self.qdot, &mut self.kinetic, None, None);
        self.symmetric = qdot.is_none_or(|v| v.iter().all(|&x| x == 0.0));
        match loads {
            Some((loads, scales)) => {
                self.resultants.update(model, &self.kin, loads, scales);
                self.symmetric &= model.chain_load_stiffness(
                    &self.kin,
                    &self.resultants,
                    &mut self.local,
                    &mut self.rate,
                );
                self.exact = self.resultants.chain_exact(&model.ell);
            }
            None => {
                self.exact = true;
                self.local.fill([0.0; 3]);
                self.rate.fill([0.0; 2]);
            }
        }
        let stiffness = model.stiffness();
        let sc = &self.kinetic;
        let mut outboard = [0.0; 2];
        for i in (0..n).rev() {
            let (c, s) = (self.kin.cos_theta[i], self.kin.sin_theta[i]);
            let (cp, sp) = (self.kin.cos_psi[i], self.kin.sin_psi[i]);
            let (l, h, d, m) = (model.ell[i], 0.5 * model.ell[i], model.d0[i], model.mass[i]);
            let (td, pd) = (sc.theta_dot[i], sc.psi_dot[i]);
            let gd = sc.g_dot[i];
            let e = [c, s];
            let nv = [-s, c];
            let el = &mut self.elements[i];
            el.ell = l;
            el.m = m;
            el.e = e;
            el.n = nv;
            el.theta_dot = td;
            el.n_s = nv[0] * outboard[0] + nv[1] * outboard[1];
            el.e_s = e[0] * outboard[0] + e[1] * outboard[1];
            // b_θ = h n − d sψ e, b_ψ = d cψ n − d sψ ẑ.
            el.bt = [h * nv[0] - d * sp * e[0], h * nv[1] - d * sp * e[1]];
            el.bp = [d * cp * nv[0], d * cp * nv[1], -d * sp];
            // c_θ = −(h θ̇ + d cψ ψ̇) e − d sψ θ̇ n, c_ψ = −d cψ θ̇ e − d sψ ψ̇ n − d cψ ψ̇ ẑ.
            let w = h * td + d * cp * pd;
            el.ct = [
                -w * e[0] - d * sp * td * nv[0],
                -w * e[1] - d * sp * td * nv[1],
            ];
            el.cp = [
                -d * cp * td * e[0] - d * sp * pd * nv[0],
                -d * cp * td * e[1] - d * sp * pd * nv[1],
                -d * cp * pd,
            ];
            let dot = |a: [f64; 2]| a[0] * gd[0] + a[1] * gd[1];
            // ∂b/∂u · ġ and ∂c/∂u · ġ (docs/model-choices.md).
            el.d = [
                dot([-h * e[0] - d * sp * nv[0], -h * e[1] - d * sp * nv[1]]),
                dot([-d * cp * e[0], -d * cp * e[1]]),
                dot([-d * sp * nv[0], -d * sp * nv[1]]) - d * cp * gd[2],
            ];
            el.ee = [
                dot([
                    -w * nv[0] + d * sp * td * e[0],
                    -w * nv[1] + d * sp * td * e[1],
                ]),
                dot([
                    d * sp * pd * e[0] - d * cp * td * nv[0],
                    d * sp * pd * e[1] - d * cp * td * nv[1],
                ]),
                dot([
                    d * sp * td * e[0] - d * cp * pd * nv[0],
                    d * sp * td * e[1] - d * cp * pd * nv[1],
                ]) + d * sp * pd * gd[2],
            ];
            if model.torsion {
                el.inertia = model.inertia[i];
                el.k = [stiffness[i], stiffness[n + i]];
            } else {
                el.inertia = 0.0;
                el.k = [stiffness[i], 0.0];
            }
            el.rotary = model.rotary[i];
            el.load = self.local[i];
            el.rate = self.rate[i];
            outboard[0] += m * gd[0];
            outboard[1] += m * gd[1];
        }
    }

    /// Whether the static tangent of this linearization is exact: every follower force at a
    /// node or an element midpoint (otherwise the sweep solves a nearby operator, and Newton
    /// iterations with it are simplified ones).
    pub(crate) fn is_exact(&self) -> bool {
        self.exact
    }

    /// Whether every real operator of this linearization is symmetric: at rest, and no
    /// follower force.
    #[cfg(test)]
    pub(crate) fn is_symmetric(&self) -> bool {
        self.symmetric
    }

    /// The perturbed momentum and gyroscopic term for a perturbation `dq` of the coordinates and
    /// `dqdot` of the velocities (`dq = None`: zero), in O(n) by dual numbers through the
    /// kinetic recursion: `p_out = M dqdot + B dq` and, if given, `gamma_out = Bᵀ dqdot + G_x dq`
    /// (`B = ∂(M q̇)/∂q`, `G_x = ∂γ/∂q|_q̇` at the linearization point).
    pub(crate) fn kinetic_perturbation(
        &mut self,
        model: &FullModel,
        dq: Option<&[f64]>,
        dqdot: &[f64],
        p_out: &mut [f64],
        gamma_out: Option<&mut [f64]>,
    ) {
        let d = &mut self.duals;
        let dq = dq.unwrap_or(&d.zeros);
        model.configure_along(&self.kin, dq, &mut d.abs, &mut d.scratch);
        for i in 0..dqdot.len() {
            d.qdot[i] = Dual64::new(self.qdot[i], dqdot[i]);
        }
        let want_gamma = gamma_out.is_some();
        model.kinetic_terms_configured(
            &d.qdot,
            &mut d.scratch,
            Some(&mut d.p),
            want_gamma.then_some(&mut d.gamma[..]),
        );
        for i in 0..p_out.len() {
            p_out[i] = d.p[i].eps;
        }
        if let Some(g) = gamma_out {
            for i in 0..g.len() {
                g[i] = d.gamma[i].eps;
            }
        }
    }
}

/// A factorization of the swept operator (module documentation): per element the inverse pivot
/// `Ĥ⁻¹`, the gain `K_j = Ĥ⁻¹ Ĝ`, the momentum and follower rows of `L̂`, and the element's
/// `a_j`, `â_j`.
#[derive(Debug, Clone)]
pub(crate) struct ChainFactor<T> {
    kappa: T,
    pivot_inv: Vec<[T; 4]>,
    gain: Vec<[T; 8]>,
    lhat: Vec<[T; 8]>,
    a: Vec<[T; 4]>,
    feed: Vec<[T; 2]>,
    /// Negative eigenvalues over all pivots (meaningful for real symmetric operators).
    negative: usize,
    symmetric: bool,
}

impl<T: Field> ChainFactor<T> {
    /// Buffers for a chain of `n` elements.
    pub(crate) fn new(n: usize) -> Self {
        let z = T::from(0.0);
        Self {
            kappa: z,
            pivot_inv: vec![[z; 4]; n],
            gain: vec![[z; 8]; n],
            lhat: vec![[z; 8]; n],
            a: vec![[z; 4]; n],
            feed: vec![[z; 2]; n],
            negative: 0,
            symmetric: false,
        }
    }

    /// Factor the operator of `shift` at the linearization `lin`. False if a pivot is singular
    /// or not finite. `sign` maps a pivot `[h00, h01, h10, h11]` to its number of negative
    /// eigenvalues (see [`ChainFactor::negative_pivots`]).
    fn factor_with(
        &mut self,
        model: &FullModel,
        lin: &ChainLinearization,
        shift: Shift<T>,
        sign: impl Fn([T; 4]) -> usize,
    ) -> bool {
        let zero = T::from(0.0);
        let one = T::from(1.0);
        let Shift {
            cv,
            cp,
            kappa,
            gyroscopic,
        } = shift;
        let g = if gyroscopic { 1.0 } else { 0.0 };
        self.kappa = kappa;
        self.negative = 0;
        // P (6 × 4): rows δS (2), F (2), springs (2); columns δV (2), δθ, δψ.
        let mut p = [[zero; 4]; 6];
        for j in (0..model.n).rev() {
            let el = &lin.elements[j];
            let l = el.ell;
            let m = el.m;
            // a = ℓ (c_v n − θ̇ e), â = ℓ (c_p n + g θ̇ e).
            let a = [
                (cv * el.n[0] - T::from(el.theta_dot * el.e[0])) * l,
                (cv * el.n[1] - T::from(el.theta_dot * el.e[1])) * l,
            ];
            let ah = [
                (cp * el.n[0] + T::from(g * el.theta_dot * el.e[0])) * l,
                (cp * el.n[1] + T::from(g * el.theta_dot * el.e[1])) * l,
            ];
            let ln = [el.n[0] * l, el.n[1] * l];
            // B̃ = c_v B + C (δġ per δu), B̂ = c_p B − g C (the row's coefficient of m δġ).
            let bt_t = [
                cv * el.bt[0] + T::from(el.ct[0]),
                cv * el.bt[1] + T::from(el.ct[1]),
            ];
            let bt_p = [
                cv * el.bp[0] + T::from(el.cp[0]),
                cv * el.bp[1] + T::from(el.cp[1]),
                cv * el.bp[2] + T::from(el.cp[2]),
            ];
            let bh_t = [
                cp * el.bt[0] - T::from(g * el.ct[0]),
                cp * el.bt[1] - T::from(g * el.ct[1]),
            ];
            let bh_p = [
                cp * el.bp[0] - T::from(g * el.cp[0]),
                cp * el.bp[1] - T::from(g * el.cp[1]),
                cp * el.bp[2] - T::from(g * el.cp[2]),
            ];
            let kt = kappa * el.k[0];
            let kp = kappa * el.k[1];
            // H = m B̂ᵀ B̃ + (c_p − g c_v) m D − g m E + (g ℓ θ̇ n·S + (g c_v − c_p) ℓ e·S) e_θ e_θᵀ
            //     + c_p c_v (J_b e_θ e_θᵀ + J e_ψ e_ψᵀ) + κ diag(k) + G_loc.
            let mut h00 = (bh_t[0] * bt_t[0] + bh_t[1] * bt_t[1]) * m
                + (cp - cv * g) * (m * el.d[0])
                + T::from(-g * m * el.ee[0] + g * l * el.theta_dot * el.n_s + el.load[0])
                + (cv * g - cp) * (l * el.e_s)
                + cp * cv * el.rotary
                + kt;
            let mut h01 = (bh_t[0] * bt_p[0] + bh_t[1] * bt_p[1]) * m
                + (cp - cv * g) * (m * el.d[1])
                + T::from(-g * m * el.ee[1] + el.load[1]);
            let mut h10 = (bh_p[0] * bt_t[0] + bh_p[1] * bt_t[1]) * m
                + (cp - cv * g) * (m * el.d[1])
                + T::from(-g * m * el.ee[1] + el.load[1]);
            let mut h11 = if model.torsion {
                (bh_p[0] * bt_p[0] + bh_p[1] * bt_p[1] + bh_p[2] * bt_p[2]) * m
                    + (cp - cv * g) * (m * el.d[2])
                    + T::from(-g * m * el.ee[2] + el.load[2])
                    + cp * cv * el.inertia
                    + kp
            } else {
                one
            };
            // P A (6 × 2) and Âᵀ P (2 × 4).
            let mut pa = [[zero; 2]; 6];
            for r in 0..6 {
                pa[r][0] = p[r][0] * a[0] + p[r][1] * a[1] + p[r][2];
                pa[r][1] = p[r][3];
            }
            let ap = |col: usize| -> [T; 2] {
                [
                    ah[0] * p[0][col]
                        + ah[1] * p[1][col]
                        + p[2][col] * ln[0]
                        + p[3][col] * ln[1]
                        + p[4][col],
                    p[5][col],
                ]
            };
            let ap_cols = [ap(0), ap(1), ap(2), ap(3)];
            // Ĥ = H + Âᵀ P A.
            let top = |c: usize| {
                ah[0] * pa[0][c] + ah[1] * pa[1][c] + pa[2][c] * ln[0] + pa[3][c] * ln[1] + pa[4][c]
            };
            h00 += top(0);
            h01 += top(1);
            h10 += pa[5][0];
            h11 += pa[5][1];
            if !model.torsion {
                h01 = zero;
                h10 = zero;
                h11 = one;
            }
            let det = h00 * h11 - h01 * h10;
            if !(det.finite() && h00.finite() && h11.finite()) || det.norm1() == 0.0 {
                return false;
            }
            let hinv = [h11 / det, -h01 / det, -h10 / det, h00 / det];
            self.negative += sign([h00, h01, h10, h11]);
            // Ĝ = G + Âᵀ P E: G = [m B̂_xyᵀ, −κ diag(k)].
            let gh = [
                [
                    bh_t[0] * m + ap_cols[0][0],
                    bh_t[1] * m + ap_cols[1][0],
                    -kt,
                    zero,
                ],
                [
                    bh_p[0] * m + ap_cols[0][1],
                    bh_p[1] * m + ap_cols[1][1],
                    zero,
                    -kp,
                ],
            ];
            let mut k = [zero; 8];
            for c in 0..4 {
                k[c] = hinv[0] * gh[0][c] + hinv[1] * gh[1][c];
                k[4 + c] = hinv[2] * gh[0][c] + hinv[3] * gh[1][c];
            }
            // L̂ = F P A + L: rows δS (+ m B̃_xy), F (− f' in the θ column); springs −κ diag(k).
            let lh = [
                [pa[0][0] + bt_t[0] * m, pa[0][1] + bt_p[0] * m],
                [pa[1][0] + bt_t[1] * m, pa[1][1] + bt_p[1] * m],
                [pa[2][0] - T::from(el.rate[0]), pa[2][1]],
                [pa[3][0] - T::from(el.rate[1]), pa[3][1]],
            ];
            // P ← F P E + N − L̂ K.
            let mut next = [[zero; 4]; 6];
            for r in 0..4 {
                for c in 0..4 {
                    next[r][c] = -(lh[r][0] * k[c] + lh[r][1] * k[4 + c]);
                }
                next[r][0] += p[r][0];
                next[r][1] += p[r][1];
            }
            next[0][0] += T::from(m);
            next[1][1] += T::from(m);
            for c in 0..4 {
                next[4][c] = kt * k[c];
                next[5][c] = kp * k[4 + c];
            }
            next[4][2] += kt;
            next[5][3] += kp;
            p = next;
            self.pivot_inv[j] = hinv;
            self.gain[j] = k;
            self.lhat[j] = [
                lh[0][0], lh[0][1], lh[1][0], lh[1][1], lh[2][0], lh[2][1], lh[3][0], lh[3][1],
            ];
            self.a[j] = [a[0], a[1], ah[0], ah[1]];
        }
        true
    }

    /// `b ← S⁻¹ b` (joint coordinates, `n_dofs` entries) with this factorization.
    pub(crate) fn solve(&mut self, model: &FullModel, lin: &ChainLinearization, b: &mut [T]) {
        let n = model.n;
        let zero = T::from(0.0);
        let torsion = model.torsion;
        // Backward: k_j = Ĥ⁻¹ (b_abs,j − Âᵀ w) and w ← F w + L̂ k_j.
        let mut w = [zero; 6];
        for j in (0..n).rev() {
            let el = &lin.elements[j];
            let next = |k: usize| if j + 1 < n { b[k + 1] } else { zero };
            let bt = b[j] - next(j);
            let bp = if torsion {
                b[n + j] - next(n + j)
            } else {
                zero
            };
            let ah = self.a[j];
            let r0 = bt
                - (ah[2] * w[0]
                    + ah[3] * w[1]
                    + w[2] * (el.n[0] * el.ell)
                    + w[3] * (el.n[1] * el.ell)
                    + w[4]);
            let r1 = bp - w[5];
            let hi = self.pivot_inv[j];
            let k = [hi[0] * r0 + hi[1] * r1, hi[2] * r0 + hi[3] * r1];
            let l = self.lhat[j];
            for r in 0..4 {
                w[r] += l[2 * r] * k[0] + l[2 * r + 1] * k[1];
            }
            w[4] = -(self.kappa * el.k[0]) * k[0];
            w[5] = -(self.kappa * el.k[1]) * k[1];
            self.feed[j] = k;
        }
        // Forward: δu_j = k_j − K_j s_{j−1}, s_j = E s_{j−1} + A_j δu_j; joint values are
        // differences of the absolute ones.
        let mut s = [zero; 4];
        let (mut prev_t, mut prev_p) = (zero, zero);
        for j in 0..n {
            let g = self.gain[j];
            let k = self.feed[j];
            let ut = k[0] - (g[0] * s[0] + g[1] * s[1] + g[2] * s[2] + g[3] * s[3]);
            b[j] = ut - prev_t;
            prev_t = ut;
            if torsion {
                let up = k[1] - (g[4] * s[0] + g[5] * s[1] + g[6] * s[2] + g[7] * s[3]);
                b[n + j] = up - prev_p;
                prev_p = up;
                s[3] = up;
            }
            let a = self.a[j];
            s[0] += a[0] * ut;
            s[1] += a[1] * ut;
            s[2] = ut;
        }
    }

    /// Number of negative eigenvalues of the factored operator, from the signs of the pivots:
    /// `Some(0)` means positive definite. `None` unless the operator is real and symmetric (at
    /// rest, no follower force), where the sweep is a block `L D Lᵀ` factorization and
    /// Sylvester's law of inertia applies.
    pub(crate) fn negative_pivots(&self) -> Option<usize> {
        self.symmetric.then_some(self.negative)
    }

    /// The count of [`ChainFactor::negative_pivots`] for a caller that has established by
    /// other means that the operator is symmetric (a linearization flagged unsymmetric only by
    /// a follower force scaled to zero).
    pub(crate) fn negative_pivots_assuming_symmetry(&self) -> usize {
        self.negative
    }

    /// Whether the determinant of the factored real operator is negative, symmetric or not:
    /// each 2 × 2 pivot adds 1 to the count exactly when its determinant is negative (0 or 2
    /// otherwise), the sweep is a block elimination, and the map from joint to absolute angles
    /// has determinant 1, so the count's parity is the sign of the product of the pivots'
    /// determinants (test `pivot_parity_is_the_determinant_sign_under_follower_loads`).
    pub(crate) fn determinant_negative(&self) -> bool {
        self.negative % 2 == 1
    }
}

impl ChainFactor<f64> {
    /// Factor the real operator of `shift` at `lin`; false if a pivot is singular.
    pub(crate) fn factor(
        &mut self,
        model: &FullModel,
        lin: &ChainLinearization,
        shift: Shift<f64>,
    ) -> bool {
        let ok = self.factor_with(model, lin, shift, |h| {
            // Eigenvalue signs of the (symmetric) 2 × 2 pivot.
            let (det, tr) = (h[0] * h[3] - h[1] * h[2], h[0] + h[3]);
            if det < 0.0 {
                1
            } else if tr < 0.0 {
                2
            } else {
                0
            }
        });
        self.symmetric = lin.symmetric && shift.cv == shift.cp;
        ok
    }
}

impl ChainFactor<Complex<f64>> {
    /// Factor the complex operator of `shift` at `lin`; false if a pivot is singular.
    pub(crate) fn factor(
        &mut self,
        model: &FullModel,
        lin: &ChainLinearization,
        shift: Shift<Complex<f64>>,
    ) -> bool {
        self.symmetric = false;
        self.factor_with(model, lin, shift, |_| 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, RotaryInertia, SectionProperties,
        TorsionProperties,
    };
    use crate::model::{DistributedForce, Force, Load, StructuralModel};
    use nalgebra::{DMatrix, DVector};

    fn model(torsion: bool, n: usize) -> FullModel {
        let section = SectionProperties {
            ei: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![14.0, 6.0],
            },
            mass_per_length: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![0.6, 0.2],
            },
            torsion: torsion.then_some(TorsionProperties {
                gj: Profile::Uniform(3.0),
                polar_inertia: Profile::Uniform(0.01),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.1),
            }),
        };
        // With rotary inertia in bending (bars and a section table), so that every sweep is
        // checked with it; the paper's point masses are the special case J_b = 0.
        let rotary = RotaryInertia {
            elements: true,
            section: Some(Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![3e-3, 1e-3],
            }),
        };
        FullModel::new(
            Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(n),
                Calibration::TipLoad,
            )
            .unwrap()
            .with_rotary_inertia("beam", &section, &rotary)
            .unwrap(),
        )
    }

    /// Every kind of load, follower forces included (`follower = false` keeps them out). The
    /// follower point force sits on node 7, where the chain form of its rates is exact.
    fn loads(model: &FullModel, follower: bool) -> AppliedLoads {
        loads_with_follower_at(model, follower.then(|| model.beam().nodes()[7]))
    }

    /// As [`loads`], with the follower forces (if `follower_span`) and the point one at that span.
    fn loads_with_follower_at(model: &FullModel, follower_span: Option<f64>) -> AppliedLoads {
        let follower = follower_span.is_some();
        let mut l = vec![
            Load::PointForce {
                span: 2.0,
                force: Force::Dead { fx: -3.0, fy: 5.0 },
            },
            Load::PointForce {
                span: 0.9,
                force: Force::Dead { fx: 1.0, fy: -2.0 },
            },
            Load::Moment {
                span: 1.3,
                value: 0.7,
            },
            Load::Distributed(DistributedForce::Dead {
                fx: Profile::Uniform(0.3),
                fy: Profile::Table {
                    x: vec![0.0, 2.0],
                    value: vec![1.0, -2.0],
                },
            }),
            Load::Gravity { g: 9.81 },
        ];
        if follower {
            l.push(Load::PointForce {
                span: follower_span.unwrap_or_default(),
                force: Force::Follower {
                    tangential: 0.8,
                    normal: 4.0,
                },
            });
            l.push(Load::Distributed(DistributedForce::Follower {
                tangential: Profile::Uniform(-0.4),
                normal: Profile::Uniform(1.5),
            }));
        }
        if model.has_torsion() {
            l.push(Load::Torque {
                span: 1.1,
                value: 0.5,
            });
        }
        model.apply(&l, "loads").unwrap()
    }

    /// Mass matrix, `K` and the load stiffness `G = −∂Q/∂q`, dense.
    fn dense(model: &FullModel, q: &[f64], loads: &AppliedLoads) -> [DMatrix<f64>; 3] {
        let nd = model.n_dofs();
        let kin = model.kinematics(q);
        let mut m = DMatrix::zeros(nd, nd);
        model.mass_matrix_kin_into(&kin, &mut m);
        let mut g = DMatrix::zeros(nd, nd);
        model.load_jacobian_kin_into(&kin, loads, &vec![1.0; loads.n_loads()], &mut g);
        [m, model.stiffness_matrix(), -g]
    }

    fn state(nd: usize) -> Vec<f64> {
        (0..nd)
            .map(|i| 0.3 * (1.0 + 1.7 * i as f64).sin())
            .collect()
    }

    #[test]
    fn static_tangent_solves_match_dense_lu() {
        // K − ∂Q/∂q with every kind of load, follower forces (non-symmetric) included.
        for torsion in [false, true] {
            for follower in [false, true] {
                let model = model(torsion, 9);
                let nd = model.n_dofs();
                let q = state(nd);
                let loads = loads(&model, follower);
                let [_, k, g] = dense(&model, &q, &loads);
                let mut lin = ChainLinearization::new(&model);
                lin.update(
                    &model,
                    &q,
                    None,
                    Some((&loads, &vec![1.0; loads.n_loads()])),
                );
                // Follower forces at a node and distributed ones: the chain form is exact.
                assert!(lin.is_exact());
                assert_eq!(lin.is_symmetric(), !follower);
                let b: Vec<f64> = (0..nd).map(|i| 1.0 + (0.7 * i as f64).sin()).collect();
                let want = (&k + &g)
                    .lu()
                    .solve(&DVector::from_column_slice(&b))
                    .unwrap();
                let mut f = ChainFactor::<f64>::new(model.n_elements());
                assert!(f.factor(&model, &lin, Shift::statics()));
                assert_eq!(f.negative_pivots().is_some(), !follower);
                let mut x = b.clone();
                f.solve(&model, &lin, &mut x);
                let err = (DVector::from_column_slice(&x) - &want).amax() / want.amax();
                // Condition numbers ~1e3 here: 1e-11 relative.
                assert!(
                    err < 1e-11,
                    "torsion {torsion}, follower {follower}: {err:.2e}"
                );
            }
        }
    }

    #[test]
    fn a_follower_force_inside_an_element_makes_the_chain_solve_a_simplified_newton_step() {
        // At span 1.7 (between node 7 at 1.556 and element 8's midpoint at 1.667… no: inside
        // element 8, past its midpoint) the force turns with θ_8 and θ_9; the chain form leaves
        // out the term of θ_9 on joint 8 through the force's arm (loads.rs, chain_load_stiffness).
        // The chain solve is then an approximate inverse: iterative refinement with it converges
        // to the dense solution, as the simplified Newton iterations of statics and dynamics do.
        for torsion in [false, true] {
            let model = model(torsion, 9);
            let nd = model.n_dofs();
            let q = state(nd);
            let loads = loads_with_follower_at(&model, Some(1.7));
            let [_, k, g] = dense(&model, &q, &loads);
            let a = &k + &g;
            let mut lin = ChainLinearization::new(&model);
            lin.update(
                &model,
                &q,
                None,
                Some((&loads, &vec![1.0; loads.n_loads()])),
            );
            assert!(!lin.is_exact(), "the linearization knows it is approximate");
            let mut f = ChainFactor::<f64>::new(model.n_elements());
            assert!(f.factor(&model, &lin, Shift::statics()));
            let b = DVector::from_fn(nd, |i, _| 1.0 + (0.7 * i as f64).sin());
            let want = a.clone().lu().solve(&b).unwrap();
            let mut x = DVector::zeros(nd);
            let mut errors = Vec::new();
            for _ in 0..12 {
                let mut d = (&b - &a * &x).as_slice().to_vec();
                f.solve(&model, &lin, &mut d);
                x += DVector::from_column_slice(&d);
                errors.push((&x - &want).amax() / want.amax());
            }
            // Measured contraction ≈ 0.05 per step: twelve steps reach round-off.
            assert!(errors[0] < 0.5, "torsion {torsion}: {errors:?}");
            assert!(errors[11] < 1e-10, "torsion {torsion}: {errors:?}");
        }
    }

    #[test]
    fn mass_diagonal_matches_the_mass_matrix() {
        for torsion in [false, true] {
            let model = model(torsion, 7);
            let nd = model.n_dofs();
            let q = state(nd);
            let loads = loads(&model, false);
            let [m, _, _] = dense(&model, &q, &loads);
            let mut diag = vec![0.0; nd];
            model.mass_diagonal_into(&model.kinematics(&q), &mut diag);
            for i in 0..nd {
                // Sums of positive terms: round-off only.
                assert!((diag[i] - m[(i, i)]).abs() <= 1e-12 * m[(i, i)], "{i}");
            }
        }
    }

    #[test]
    fn pivot_signs_count_the_negative_eigenvalues_of_the_tangent() {
        // A compressive dead tip force past the first buckling loads makes K + G indefinite.
        for torsion in [false, true] {
            let model = model(torsion, 12);
            let nd = model.n_dofs();
            for (fx, q_amp) in [(-1.0, 0.0), (-40.0, 0.0), (-400.0, 0.02), (-3000.0, 0.05)] {
                let l = model
                    .apply(
                        &[
                            Load::PointForce {
                                span: 2.0,
                                force: Force::Dead { fx, fy: 0.5 },
                            },
                            Load::Gravity { g: 9.81 },
                        ],
                        "loads",
                    )
                    .unwrap();
                let q: Vec<f64> = state(nd).iter().map(|v| v * q_amp).collect();
                let [_, k, g] = dense(&model, &q, &l);
                let a = &k + &g;
                let a = (&a + a.transpose()) * 0.5;
                let eig = a.symmetric_eigenvalues();
                let want = eig.iter().filter(|&&v| v < 0.0).count();
                let mut lin = ChainLinearization::new(&model);
                lin.update(&model, &q, None, Some((&l, &[1.0, 1.0])));
                let mut f = ChainFactor::<f64>::new(model.n_elements());
                assert!(f.factor(&model, &lin, Shift::statics()));
                assert_eq!(
                    f.negative_pivots(),
                    Some(want),
                    "torsion {torsion}, fx {fx}"
                );
                if fx == -3000.0 {
                    assert!(want > 0, "the test needs an indefinite case");
                }
            }
        }
    }

    /// With follower forces (at the tip node, where the chain form of their rates is exact) the
    /// static tangent is not symmetric and the pivot count has no meaning of its own, but its
    /// parity is the sign of `det K_T`: each real 2 × 2 pivot adds 1 exactly when its determinant
    /// is negative (0 or 2 otherwise), the sweep is a block elimination, and `T` (joint to
    /// absolute angles) has determinant 1. Checked against the sign of the dense LU's
    /// determinant on compressed, bent states, two with `det K_T < 0` (divergence); the
    /// determinants here are 1e20–1e53 in size, far from a sign change. What the stability of
    /// follower-loaded equilibria (`solve/statics.rs`) rests on.
    #[test]
    fn pivot_parity_is_the_determinant_sign_under_follower_loads() {
        for torsion in [false, true] {
            let model = model(torsion, 12);
            let nd = model.n_dofs();
            let mut negative_seen = 0;
            // (follower tangential, follower normal, dead fx, amplitude of the bent state)
            for (ft, fnorm, fx, q_amp) in [
                (-1.0, 0.5, -1.0, 0.0),
                (-5.0, 3.0, -40.0, 0.0),
                (-5.0, 5.0, -400.0, 0.02),
                (2.0, 1.0, -3000.0, 0.05),
                (-20.0, 20.0, -9000.0, 0.1),
                (-150.0, 0.0, -150.0, 0.3),
                (10.0, 3.0, -100.0, 0.01),
                (-30.0, 3.0, -30.0, 0.01),
                (-300.0, 3.0, 0.0, 0.01),
            ] {
                let l = model
                    .apply(
                        &[
                            Load::PointForce {
                                span: 2.0,
                                force: Force::Follower {
                                    tangential: ft,
                                    normal: fnorm,
                                },
                            },
                            Load::PointForce {
                                span: 2.0,
                                force: Force::Dead { fx, fy: 0.5 },
                            },
                            Load::Gravity { g: 9.81 },
                        ],
                        "loads",
                    )
                    .unwrap();
                let q: Vec<f64> = state(nd).iter().map(|v| v * q_amp).collect();
                let [_, k, g] = dense(&model, &q, &l);
                let det = (&k + &g).lu().determinant();
                let mut lin = ChainLinearization::new(&model);
                lin.update(&model, &q, None, Some((&l, &[1.0, 1.0, 1.0])));
                assert!(!lin.is_symmetric());
                assert!(lin.is_exact(), "a follower force at a node");
                let mut f = ChainFactor::<f64>::new(model.n_elements());
                assert!(f.factor(&model, &lin, Shift::statics()));
                assert_eq!(f.negative_pivots(), None, "unsymmetric: no inertia");
                assert_eq!(
                    f.determinant_negative(),
                    det < 0.0,
                    "torsion {torsion}, follower {ft}/{fnorm}, dead {fx}: det {det:e}"
                );
                negative_seen += usize::from(det < 0.0);
            }
            assert!(negative_seen > 0, "the test needs a negative determinant");
        }
    }

    /// The operator about a moving state, `c_v c_p M + c_p B − g c_v Bᵀ − g G_x + K` (`B =
    /// ∂(M q̇)/∂q`, `G_x = ∂γ/∂q|_q̇`; module documentation), against the dense matrices of
    /// `model::kinetic` (dual numbers, checked against finite differences there), for the
    /// shifts' limiting cases and with and without the gyroscopic term: exact to round-off.
    #[test]
    fn dynamic_operator_matches_the_dense_kinetic_derivatives() {
        for torsion in [false, true] {
            let model = model(torsion, 7);
            let nd = model.n_dofs();
            let q = state(nd);
            let qd: Vec<f64> = (0..nd).map(|i| 2.0 * (2.0 * i as f64).cos()).collect();
            let mut ws = model.workspace();
            let (mut bm, mut gx) = (DMatrix::zeros(nd, nd), DMatrix::zeros(nd, nd));
            model.kinetic_derivatives_into(&q, &qd, &mut ws, &mut bm, &mut gx);
            let mut m = DMatrix::zeros(nd, nd);
            model.mass_matrix_into(&q, &mut ws, &mut m);
            let k = model.stiffness_matrix();
            let mut lin = ChainLinearization::new(&model);
            lin.update(&model, &q, Some(&qd), None);
            assert!(!lin.is_symmetric());
            let b: Vec<f64> = (0..nd).map(|i| 1.0 + (0.7 * i as f64).sin()).collect();
            for gyroscopic in [true, false] {
                let g = if gyroscopic { 1.0 } else { 0.0 };
                for (cv, cp) in [
                    (30.0, 30.0),
                    (30.0, 31.5),
                    (5.0, 0.0),
                    (0.0, 5.0),
                    (0.0, 0.0),
                ] {
                    let s = &m * (cv * cp) + &bm * cp - bm.transpose() * (g * cv) - &gx * g + &k;
                    let want = s.lu().solve(&DVector::from_column_slice(&b)).unwrap();
                    let mut f = ChainFactor::<f64>::new(model.n_elements());
                    let shift = Shift {
                        cv,
                        cp,
                        kappa: 1.0,
                        gyroscopic,
                    };
                    assert!(f.factor(&model, &lin, shift));
                    assert_eq!(f.negative_pivots(), None);
                    let mut x = b.clone();
                    f.solve(&model, &lin, &mut x);
                    let err = (DVector::from_column_slice(&x) - &want).amax() / want.amax();
                    // Measured below 1e-15; condition numbers ~1e3.
                    assert!(
                        err < 1e-12,
                        "{torsion} {gyroscopic} ({cv}, {cp}): {err:.2e}"
                    );
                }
            }
        }
    }
}
