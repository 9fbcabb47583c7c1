//! The aeroelastic system linearized about a static equilibrium, with the lag states eliminated
//! strip by strip (docs/aeroelastic-model.md §5): its eigenvalues other than those of the lag
//! dynamics are the roots of the rational eigenproblem
//!
//! ```text
//! S(s) v = [ s² M + s C̃ + K̃ − G diag(T(s/r_i)) (W_x + s W_v) ] v = 0
//! ```
//!
//! with `M` the wet mass matrix, `C̃ = C − Q_v`, `K̃ = K − ∂Q_other/∂x − Q_x` (all at the
//! equilibrium, `ẋ = 0`, `w_eff = w`), `r_i = V_i/b_i`, and `T` the lag's transfer function
//! (`T = 1` without lag; Theodorsen's `C(k)` in the p-k method). At `p = 0` the momentum and
//! gyroscopic derivatives vanish, so this is exactly the Schur complement of the first-order
//! Jacobian on the lag states. Every matrix is `n_dofs × n_dofs`, whatever the number of lag
//! states: this is what makes the flutter search cheap.
//!
//! Each eigenpair is found by Newton's method for nonlinear eigenproblems (the "nonlinear inverse
//! iteration" of Ruhe, SIAM J. Numer. Anal. 10 (1973) 674–689): with `x = S(s)⁻¹ S'(s) v` and the
//! normalization `uᴴv = 1`, `s ← s − 1/(uᴴx)`, `v ← x/(uᴴx)`; quadratic convergence at simple
//! eigenvalues.
//!
//! In the p-k method `T = C(|Im s|/r_i)` depends on `Im s` alone: `S(σ, ω)` with `s = σ + iω` is
//! smooth but not analytic, and Newton's iteration is that of the real system `S v = 0`,
//! `uᴴv = 1` in `(v, σ, ω)`: with `x_σ = S⁻¹ ∂S/∂σ v` and `x_ω = S⁻¹ ∂S/∂ω v`
//! (`∂S/∂σ = S'` with `C` frozen, `∂S/∂ω = i S' − Σ_g dT_g/dω (P_g + s Q_g)`), the steps solve
//! `uᴴx_σ dσ + uᴴx_ω dω = −1` (one complex equation, two real unknowns), and
//! `v ← −(x_σ dσ + x_ω dω)`. It converges quadratically to the p-k fixed point (`C` at the
//! frequency it yields), which iterating "freeze `C`, solve, update the frequency" reaches only
//! linearly; when `T` is analytic (`x_ω = i x_σ`) it is Ruhe's step above.

use nalgebra::{Complex, DMatrix, DVector};

use super::clu::ComplexLu;
use crate::model::aero::{theodorsen, theodorsen_derivative, Lag};

type C64 = Complex<f64>;

/// How the lag's transfer function is evaluated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Transfer {
    /// The finite-state lag of the model (`T = 1` without lag): the exact eigenvalues.
    Model,
    /// The p-k method: Theodorsen's `C(k_i)` at each strip's reduced frequency
    /// `k_i = |Im s| / r_i`, the branch's own frequency. `S` is then a smooth function of
    /// `(Re s, Im s)` but not analytic in `s`, and Newton's iteration is done in the two real
    /// variables (module documentation).
    Theodorsen,
    /// Theodorsen's `C(k_i)` frozen at `k_i = ω / r_i` for a given `ω`: the inner problem of the
    /// classical p-k iteration ("freeze `C`, solve, update the frequency"), analytic in `s`.
    TheodorsenAt {
        /// Circular frequency `ω` (rad/s) at which `C` is evaluated.
        omega: f64,
    },
}

/// The largest relative change of the frequency `|Im s|` in one p-k Newton step (a trust region:
/// from a start 1 m/s away on a heavily damped branch at `k ≈ 0.05`, full steps ran off to
/// `|Im s| = 100` and failed to converge in 12 iterations; a frequency is followed by halving).
const PK_MAX_FREQUENCY_CHANGE: f64 = 0.5;

/// Strips sharing one lag rate `r = V/b`: `P = G_g W_x,g`, `Q = G_g W_v,g` (`n × n`), so that
/// their term of `S(s)` is `T(s/r) (P + s Q)` whatever the number of strips in the group.
#[derive(Debug, Clone)]
pub(crate) struct Group {
    rate: f64,
    px: DMatrix<f64>,
    pv: DMatrix<f64>,
}

/// The linearized aeroelastic system at one speed.
#[derive(Debug, Clone)]
pub(crate) struct Linearization {
    pub(crate) mass: DMatrix<f64>,
    pub(crate) damping: DMatrix<f64>,
    pub(crate) stiffness: DMatrix<f64>,
    groups: Vec<Group>,
    lag: Option<Lag>,
}

/// Buffers of the Newton iterations (allocated once per analysis).
#[derive(Debug, Clone)]
pub(crate) struct NewtonWorkspace {
    lu: ComplexLu,
    xr: Vec<f64>,
    xi: Vec<f64>,
    transfers: Vec<(C64, C64)>,
}

impl NewtonWorkspace {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            lu: ComplexLu::new(n),
            xr: vec![0.0; n],
            xi: vec![0.0; n],
            transfers: Vec::new(),
        }
    }

    /// `S⁻¹ b` with the factorization in the workspace.
    fn solve(&mut self, b: &DVector<C64>) -> DVector<C64> {
        for (i, bi) in b.iter().enumerate() {
            self.xr[i] = bi.re;
            self.xi[i] = bi.im;
        }
        self.lu.solve(&mut self.xr, &mut self.xi);
        DVector::from_fn(b.len(), |i, _| C64::new(self.xr[i], self.xi[i]))
    }
}

/// An eigenpair of `S(s) v = 0`.
#[derive(Debug, Clone)]
pub(crate) struct EigenPair {
    pub(crate) s: C64,
    pub(crate) v: DVector<C64>,
    pub(crate) iterations: usize,
    /// For the p-k method, `|dω'/dω|` at the root, `ω'` the frequency that freezing `C` at `ω`
    /// yields: the classical p-k iteration converges to the root if it is below 1 and is
    /// repelled from it otherwise (0 for the other transfers).
    pub(crate) pk_contraction: f64,
}

impl Linearization {
    /// Assemble from the structured derivatives: strips with equal rates `r_i` are grouped.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        mass: DMatrix<f64>,
        damping: DMatrix<f64>,
        stiffness: DMatrix<f64>,
        g: &DMatrix<f64>,
        wx: &DMatrix<f64>,
        wv: &DMatrix<f64>,
        rates: &[f64],
        lag: Option<Lag>,
    ) -> Self {
        let n = mass.nrows();
        let mut groups: Vec<Group> = Vec::new();
        for (i, &r) in rates.iter().enumerate() {
            let k = match groups.iter().position(|gr| gr.rate == r) {
                Some(k) => k,
                None => {
                    groups.push(Group {
                        rate: r,
                        px: DMatrix::zeros(n, n),
                        pv: DMatrix::zeros(n, n),
                    });
                    groups.len() - 1
                }
            };
            let gr = &mut groups[k];
            gr.px.ger(1.0, &g.column(i), &wx.row(i).transpose(), 1.0);
            gr.pv.ger(1.0, &g.column(i), &wv.row(i).transpose(), 1.0);
        }
        Self {
            mass,
            damping,
            stiffness,
            groups,
            lag,
        }
    }

    /// The linearization at speed `u` of a wing whose equilibrium is the undeformed state at
    /// every speed, from those at `U = 0` (`at0`) and `U = 1` (`at1`): every term is then
    /// homogeneous in `U` — `K̃ = K̃₀ + U² K̃₂`, `C̃ = C̃₀ + U C̃₁`, `G W_x ∝ U²`, `G W_v ∝ U`,
    /// `r ∝ U` (the loads scale with `q = ½ρU²`, the upwash with `U`, the lag rate with `U/b`;
    /// the flutter analysis checks this against a direct linearization before it relies on it).
    pub(crate) fn scaled(at0: &Self, at1: &Self, u: f64) -> Self {
        let groups = at1
            .groups
            .iter()
            .map(|g| Group {
                rate: g.rate * u,
                px: &g.px * (u * u),
                pv: &g.pv * u,
            })
            .collect();
        Self {
            mass: at0.mass.clone(),
            damping: &at0.damping + (&at1.damping - &at0.damping) * u,
            stiffness: &at0.stiffness + (&at1.stiffness - &at0.stiffness) * (u * u),
            groups,
            lag: at1.lag.clone(),
        }
    }

    /// Largest relative difference between two linearizations of the same model (their
    /// matrices and groups), for the check of [`Self::scaled`].
    pub(crate) fn distance(&self, other: &Self) -> f64 {
        let rel = |a: &DMatrix<f64>, b: &DMatrix<f64>| {
            (a - b).amax() / a.amax().max(b.amax()).max(1e-300)
        };
        let mut d = rel(&self.mass, &other.mass)
            .max(rel(&self.stiffness, &other.stiffness))
            .max(rel(&self.damping, &other.damping));
        if self.groups.len() != other.groups.len() {
            return f64::INFINITY;
        }
        for (a, b) in self.groups.iter().zip(&other.groups) {
            d = d
                .max((a.rate - b.rate).abs() / a.rate.abs().max(1e-300))
                .max(rel(&a.px, &b.px))
                .max(rel(&a.pv, &b.pv));
        }
        d
    }

    /// `T` of every group and its derivative into `out`: `(T(s/r), dT/ds)` for the model's lag,
    /// `(C(|Im s|/r), dC/dω)` for the p-k method.
    fn transfers(&self, s: C64, how: Transfer, out: &mut Vec<(C64, C64)>) {
        out.clear();
        let zero = C64::new(0.0, 0.0);
        for gr in &self.groups {
            let r = gr.rate;
            out.push(match (how, &self.lag) {
                (Transfer::Theodorsen, _) => {
                    if r > 0.0 {
                        let (c, dc) = theodorsen_derivative(s.im.abs() / r);
                        // d|ω|/dω = sign ω; none at ω = 0, where C' is singular (a real root
                        // stays real).
                        let sign = if s.im == 0.0 { 0.0 } else { s.im.signum() };
                        (c, dc * (sign / r))
                    } else {
                        (C64::new(0.5, 0.0), zero)
                    }
                }
                (Transfer::TheodorsenAt { omega }, _) => {
                    let c = if r > 0.0 {
                        theodorsen(omega / r)
                    } else {
                        C64::new(0.5, 0.0)
                    };
                    (c, zero)
                }
                (Transfer::Model, None) => (C64::new(1.0, 0.0), zero),
                (Transfer::Model, Some(lag)) => {
                    if r > 0.0 {
                        (lag.transfer(s / r), lag.transfer_derivative(s / r) / r)
                    } else {
                        (C64::new(lag.d, 0.0), zero)
                    }
                }
            });
        }
    }

    /// `S(s)` into the workspace's LU storage (split real/imaginary, column-major).
    fn fill(&self, s: C64, ws: &mut NewtonWorkspace) {
        let (a, b) = (s.re, s.im);
        let (s2r, s2i) = (a * a - b * b, 2.0 * a * b);
        let (re, im) = (&mut ws.lu.re, &mut ws.lu.im);
        let (k, c, m) = (
            self.stiffness.as_slice(),
            self.damping.as_slice(),
            self.mass.as_slice(),
        );
        for e in 0..re.len() {
            re[e] = k[e] + a * c[e] + s2r * m[e];
            im[e] = b * c[e] + s2i * m[e];
        }
        for (gr, &(t, _)) in self.groups.iter().zip(&ws.transfers) {
            let (p, q) = (gr.px.as_slice(), gr.pv.as_slice());
            for e in 0..re.len() {
                // t (P + s Q)
                let (xr, xi) = (p[e] + a * q[e], b * q[e]);
                re[e] -= t.re * xr - t.im * xi;
                im[e] -= t.re * xi + t.im * xr;
            }
        }
    }

    /// `S'(s) v = 2s M v + C̃ v − Σ_g [T'_g (P_g + s Q_g) v + T_g Q_g v]` for the model's lag;
    /// for the p-k method (`how`), `∂S/∂σ v` (the same with `T'_g = 0`) and `∂S/∂ω v =
    /// i ∂S/∂σ v − Σ_g dT_g/dω (P_g + s Q_g) v`. Returns `(∂S/∂σ v, ∂S/∂ω v)`, the second `None`
    /// for the model's lag (it is `i` times the first).
    fn derivative_times(
        &self,
        s: C64,
        v: &DVector<C64>,
        transfers: &[(C64, C64)],
        how: Transfer,
    ) -> (DVector<C64>, Option<DVector<C64>>) {
        let vc = |m: &DMatrix<f64>| -> DVector<C64> {
            let re = m * v.map(|x| x.re);
            let im = m * v.map(|x| x.im);
            DVector::from_fn(v.len(), |i, _| C64::new(re[i], im[i]))
        };
        let mut out = vc(&self.mass) * (s * 2.0) + vc(&self.damping);
        let mut along_omega = DVector::zeros(v.len());
        for (gr, &(t, dt)) in self.groups.iter().zip(transfers) {
            let pv = vc(&gr.px);
            let qv = vc(&gr.pv);
            match how {
                Transfer::Model | Transfer::TheodorsenAt { .. } => {
                    out -= (pv + &qv * s) * dt + qv * t
                }
                Transfer::Theodorsen => {
                    along_omega -= (pv + &qv * s) * dt;
                    out -= qv * t;
                }
            }
        }
        match how {
            Transfer::Model | Transfer::TheodorsenAt { .. } => (out, None),
            Transfer::Theodorsen => {
                let i_out = &out * C64::new(0.0, 1.0);
                (out, Some(along_omega + i_out))
            }
        }
    }

    /// Newton's method from `(s0, v0)` to relative tolerance `tol` on `s`, at most
    /// `max_iterations`; `None` if it does not converge or `S` is singular along the way. For the
    /// p-k method (`how`), Newton's iteration in `(Re s, Im s)` (module documentation).
    pub(crate) fn newton(
        &self,
        s0: C64,
        v0: &DVector<C64>,
        how: Transfer,
        tol: f64,
        max_iterations: usize,
        ws: &mut NewtonWorkspace,
    ) -> Option<EigenPair> {
        let u = v0.clone() / C64::new(v0.norm().max(1e-300), 0.0);
        let mut v = v0.clone() / u.dotc(v0);
        let mut s = s0;
        let mut transfers = std::mem::take(&mut ws.transfers);
        let mut result = None;
        let mut prev_step: Option<f64> = None;
        let mut pk_contraction = 0.0;
        for it in 1..=max_iterations {
            self.transfers(s, how, &mut transfers);
            let (rhs, rhs_omega) = self.derivative_times(s, &v, &transfers, how);
            ws.transfers = std::mem::take(&mut transfers);
            self.fill(s, ws);
            transfers = std::mem::take(&mut ws.transfers);
            if !ws.lu.factor() {
                break;
            }
            let x = ws.solve(&rhs);
            let ux = u.dotc(&x);
            if !(ux.norm() > 0.0) || !ux.re.is_finite() {
                break;
            }
            let step = match rhs_omega {
                None => {
                    v = x / ux;
                    -ux.inv()
                }
                Some(rhs_omega) => {
                    // uᴴx_σ dσ + uᴴx_ω dω = −1 in real (dσ, dω); v ← −(x_σ dσ + x_ω dω).
                    let x_omega = ws.solve(&rhs_omega);
                    let uw = u.dotc(&x_omega);
                    let det = ux.re * uw.im - uw.re * ux.im;
                    if !(det.abs() > 0.0) || !det.is_finite() {
                        break;
                    }
                    let (mut d_sigma, mut d_omega) = (-uw.im / det, ux.im / det);
                    // C(k) bends sharply at small k (like k ln k) and has a kink at ω = 0:
                    // Newton's linear model holds only for moderate changes of the frequency, so
                    // a step is cut to change ω by at most half (v is renormalized below).
                    let cut = (PK_MAX_FREQUENCY_CHANGE * s.im.abs() / d_omega.abs()).min(1.0);
                    if cut < 1.0 {
                        d_sigma *= cut;
                        d_omega *= cut;
                    }
                    // Freezing C: ds/dω_C = −uᴴx_C / uᴴx_σ with x_C = x_ω − i x_σ (exact at the
                    // root, where S⁻¹ is dominated by its eigenvector's pole).
                    let x_c = &x_omega - &x * C64::new(0.0, 1.0);
                    pk_contraction = (u.dotc(&x_c) / ux).im.abs();
                    v = x * C64::new(-d_sigma, 0.0) + x_omega * C64::new(-d_omega, 0.0);
                    if cut < 1.0 {
                        let uv = u.dotc(&v);
                        v /= uv;
                    }
                    C64::new(d_sigma, d_omega)
                }
            };
            s += step;
            if !s.re.is_finite() || !s.im.is_finite() {
                break;
            }
            // Converged: the step is below the tolerance, or it fell quadratically and the next
            // one (about its square over |s|) would be.
            let scale = s.norm().max(1e-3);
            let quadratic = prev_step.is_some_and(|p: f64| step.norm() < 0.1 * p)
                && step.norm() * step.norm() <= 0.01 * tol * scale * scale;
            prev_step = Some(step.norm());
            if step.norm() <= tol * scale || quadratic {
                result = Some(EigenPair {
                    s,
                    v: v.clone(),
                    iterations: it,
                    pk_contraction,
                });
                break;
            }
        }
        ws.transfers = transfers;
        result
    }
}

/// Modal assurance criterion `|aᴴb|² / (|a|² |b|²)` of two complex vectors.
pub(crate) fn mac(a: &DVector<C64>, b: &DVector<C64>) -> f64 {
    let ab = a.dotc(b).norm_sqr();
    let aa = a.dotc(a).re;
    let bb = b.dotc(b).re;
    if aa > 0.0 && bb > 0.0 {
        ab / (aa * bb)
    } else {
        0.0
    }
}
