//! The Newton systems `(c I − J) Δ = b` of the aeroelastic equations (`equations.rs`) with the
//! lag states eliminated (docs/aeroelastic-model.md §5, "Newton systems"): a Schur complement
//! onto the `2 n_dofs` structural states `s = (x, p)`.
//!
//! The Jacobian's lag part is block-diagonal per strip, `∂ȧ_i/∂a_i = r_i H̄` (`r_i = V_i/b_i`),
//! and each strip couples to the structure by rank one: `∂ṗ/∂a_i = g_i C̄ᵀ` and
//! `∂ȧ_i/∂s = r_i B̄ w_iᵀ`, with `g_i = ∂Q/∂w_eff,i` and `w_iᵀ = (W_x,i + W_v,i A, W_v,i M⁻¹)`
//! the upwash per unit state. With `D_i = c I − r_i H̄` (`ns × ns`), `d_i = D_i⁻¹ r_i B̄` and
//! `τ_i = C̄ᵀ d_i` (the lag's transfer function less its feed-through, at `s̄ = c/r_i`):
//!
//! ```text
//! S = c I − J_ss − Σ_i τ_i (0; g_i) w_iᵀ          (2 n_dofs × 2 n_dofs, dense LU)
//! u_i = D_i⁻¹ b_a,i
//! S Δs = b_s + Σ_i (0; g_i) C̄ᵀ u_i
//! Δa_i = u_i + d_i (w_iᵀ Δs)
//! ```
//!
//! The structural block is then reduced to the coordinates as the structural equations' own
//! Newton systems are (`solve/eom_newton.rs`): with `J_ss = [[A, M⁻¹], [P̃_x, P̃_p]]`
//! (`A = ∂ẋ/∂x`, `P̃` the momentum rows with the lag terms `Σ τ_i g_i w_iᵀ` added), the first block
//! row gives `Δp = M((c − A)Δx − b_x)`, and the second
//!
//! ```text
//! K(c) Δx = b_p' + (c M − P_p M − G τ W_v) b_x,
//! K(c) = c² M − c E + F − G diag(τ) (c W_v + W_x),   E = M A + P_p M,   F = P_p M A − P_x,
//! ```
//!
//! the linearized second-order equations `s² M + s C̃ + K̃ − Σ_i T_i g_i (w_x,i + s w_v,i)` of
//! `LinearSystem` at `s = c` (`W_x`, `W_v` the upwash derivatives at fixed `ẋ` and `x`). `M`, `M A`
//! and `P_p M` are formed once per linearization (three `n_dofs³` products); then a factorization
//! costs `strips` LUs of `ns × ns`, the product `G (diag τ …)` (O(n_dofs² strips)) and one LU of
//! `n_dofs × n_dofs` — against one of `2 n_dofs + strips ns` for the whole state (at n = 32:
//! 64 against 320); a solve O(n_dofs² + strips (ns² + n_dofs)). Exact algebra: the same Newton
//! step as the dense path, up to round-off, which grows with `cond M` through `M A` and `P_p M`
//! (`M (M⁻¹ B)` recovers `B`).

use nalgebra::{Complex, DMatrix, DMatrixViewMut};

use crate::model::aero::Lag;
use crate::solve::integrate::{ComplexLu, DenseLu};

/// How the implicit integrators solve the Newton systems of [`super::AeroelasticEquations`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AeroNewtonSystems {
    /// [`AeroNewtonSystems::LagSchur`] when the aerodynamics has lag states,
    /// [`AeroNewtonSystems::Dense`] otherwise (then the two are the same). The default.
    #[default]
    Auto,
    /// The whole Jacobian, formed and factored densely: O((2 n_dofs + lag states)³).
    Dense,
    /// The lag states eliminated strip by strip onto the structural states (`schur.rs`): an LU
    /// of `2 n_dofs` plus small solves per strip; the same Newton step as `Dense`.
    LagSchur,
}

/// The Jacobian of the aeroelastic equations in its structured form (module documentation).
#[derive(Debug, Clone)]
pub(crate) struct StructuredJacobian {
    /// `J_ss = ∂(ẋ, ṗ)/∂(x, p)` (`2 n × 2 n`).
    pub(crate) ss: DMatrix<f64>,
    /// `g_i = ∂Q/∂w_eff,i` (`n × strips`): `∂ṗ/∂a_i = g_i C̄ᵀ`.
    pub(crate) g: DMatrix<f64>,
    /// `w_iᵀ`, the upwash per unit state (`strips × 2 n`): `∂ȧ_i/∂(x, p) = r_i B̄ w_iᵀ`.
    pub(crate) w: DMatrix<f64>,
    /// `r_i = V_i/b_i` (1/s).
    pub(crate) rates: Vec<f64>,
    /// For the second-order reduction (filled only for the Newton solver): `M`, `M A`,
    /// `P_p M`, `F = P_p M A − P_x` (`n × n`), `W_x`, `W_v` (`strips × n`).
    pub(crate) mass: DMatrix<f64>,
    pub(crate) ma: DMatrix<f64>,
    pub(crate) pm: DMatrix<f64>,
    pub(crate) f: DMatrix<f64>,
    pub(crate) wx: DMatrix<f64>,
    pub(crate) wv: DMatrix<f64>,
}

impl StructuredJacobian {
    pub(crate) fn zeros(n: usize, strips: usize) -> Self {
        Self {
            ss: DMatrix::zeros(2 * n, 2 * n),
            g: DMatrix::zeros(n, strips),
            w: DMatrix::zeros(strips, 2 * n),
            rates: vec![0.0; strips],
            mass: DMatrix::zeros(n, n),
            ma: DMatrix::zeros(n, n),
            pm: DMatrix::zeros(n, n),
            f: DMatrix::zeros(n, n),
            wx: DMatrix::zeros(strips, n),
            wv: DMatrix::zeros(strips, n),
        }
    }

    /// Whether every entry is finite (false where the velocities could not be solved).
    pub(crate) fn is_finite(&self) -> bool {
        let finite = |m: &DMatrix<f64>| m.as_slice().iter().all(|v| v.is_finite());
        finite(&self.ss)
            && finite(&self.g)
            && finite(&self.w)
            && self.rates.iter().all(|v| v.is_finite())
    }
}

/// A factorization: `K(c)` (`n × n`), the strips' `D_i`, `d_i` (`strips × ns`, strip-major)
/// and `τ_i`; complex ones with parts apart (`*_im` empty for a real shift).
struct Slot<L> {
    c: Complex<f64>,
    k: L,
    strips: Vec<L>,
    /// The factorization of each strip's `D_i` in `strips`: strips with the same lag rate
    /// `r_i` (a uniform chord in a uniform stream) share the first one's (same matrix).
    lu_of: Vec<usize>,
    d_re: Vec<f64>,
    d_im: Vec<f64>,
    tau_re: Vec<f64>,
    tau_im: Vec<f64>,
}

impl<L> Slot<L> {
    fn new(c: Complex<f64>, k: L, strips: Vec<L>, ns: usize) -> Self {
        let m = strips.len();
        Self {
            c,
            k,
            strips,
            lu_of: (0..m).collect(),
            d_re: vec![0.0; m * ns],
            d_im: vec![0.0; m * ns],
            tau_re: vec![0.0; m],
            tau_im: vec![0.0; m],
        }
    }
}

/// `y += α A x` for a column-major `A`.
fn gemv_add(a: &DMatrix<f64>, x: &[f64], y: &mut [f64], alpha: f64) {
    let rows = y.len();
    for (col, &xj) in a.as_slice().chunks_exact(rows).zip(x) {
        let s = alpha * xj;
        for (v, m) in y.iter_mut().zip(col) {
            *v += m * s;
        }
    }
}

/// Column `j` of a column-major `A`.
fn col(a: &DMatrix<f64>, j: usize) -> &[f64] {
    let r = a.nrows();
    &a.as_slice()[j * r..(j + 1) * r]
}

/// `Σ_k a_k b_k`.
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(a, b)| a * b).sum()
}

/// The Newton solver by elimination of the lag states and the momenta: the structured
/// Jacobian of the last linearization and the factored shifts.
pub(crate) struct LagSchur {
    /// Filled by the linearization (`AeroelasticEquations::structured_jacobian`).
    pub(crate) jac: StructuredJacobian,
    lag: Lag,
    n: usize,
    strips: usize,
    real: Vec<Slot<DenseLu>>,
    complex: Vec<Slot<ComplexLu>>,
    /// `diag(τ c) W_v + diag(τ) W_x` (`strips × n`), real and imaginary parts.
    tw_re: DMatrix<f64>,
    tw_im: DMatrix<f64>,
    /// `E = M A + P_p M` of the current linearization.
    e: DMatrix<f64>,
    /// `wᵀ` (`2 n × strips`) and `W_vᵀ` (`n × strips`): a strip's row contiguous.
    wt: DMatrix<f64>,
    wvt: DMatrix<f64>,
    /// Scratch of length `n` (four, real and imaginary parts).
    v: [Vec<f64>; 4],
}

impl LagSchur {
    /// For `n` coordinates, `strips` strips with the lag `lag` each.
    pub(crate) fn new(n: usize, strips: usize, lag: Lag) -> Self {
        Self {
            jac: StructuredJacobian::zeros(n, strips),
            lag,
            n,
            strips,
            real: Vec::new(),
            complex: Vec::new(),
            tw_re: DMatrix::zeros(strips, n),
            tw_im: DMatrix::zeros(strips, n),
            e: DMatrix::zeros(n, n),
            wt: DMatrix::zeros(2 * n, strips),
            wvt: DMatrix::zeros(n, strips),
            v: std::array::from_fn(|_| vec![0.0; n]),
        }
    }

    fn ns(&self) -> usize {
        self.lag.n_states()
    }

    /// After a linearization: `E = M A + P_p M`.
    pub(crate) fn linearized(&mut self) {
        self.e.copy_from(&self.jac.ma);
        self.e += &self.jac.pm;
        self.jac.w.transpose_to(&mut self.wt);
        self.jac.wv.transpose_to(&mut self.wvt);
    }

    /// `τ_i`, `d_i` and the factors of `D_i = c I − r_i H̄` of every strip into `sl` (complex
    /// arithmetic, real shifts included); false if a `D_i` is singular.
    fn factor_strips<L: StripLu>(&self, sl: &mut Slot<L>) -> bool {
        let ns = self.ns();
        let c = sl.c;
        let rates = &self.jac.rates;
        for i in 0..sl.strips.len() {
            let r = rates[i];
            let d = i * ns..(i + 1) * ns;
            if i > 0 && rates[i - 1] == r {
                // The previous strip's matrix: its factors, d and τ (exactly the same numbers).
                sl.lu_of[i] = sl.lu_of[i - 1];
                sl.d_re.copy_within(d.start - ns..d.start, d.start);
                sl.d_im.copy_within(d.start - ns..d.start, d.start);
                sl.tau_re[i] = sl.tau_re[i - 1];
                sl.tau_im[i] = sl.tau_im[i - 1];
                continue;
            }
            sl.lu_of[i] = i;
            let lu = &mut sl.strips[i];
            let (dr, di) = (&mut sl.d_re[d.clone()], &mut sl.d_im[d]);
            for (v, b) in dr.iter_mut().zip(self.lag.b.iter()) {
                *v = r * b;
            }
            di.fill(0.0);
            if !lu.factor_shifted(c, r, &self.lag.h) {
                return false;
            }
            lu.solve(dr, di);
            sl.tau_re[i] = dot(dr, self.lag.c.as_slice());
            sl.tau_im[i] = dot(di, self.lag.c.as_slice());
        }
        true
    }

    /// `diag(τ c) W_v + diag(τ) W_x` into `tw_re`, `tw_im`.
    fn coupling(&mut self, c: Complex<f64>, tau_re: &[f64], tau_im: &[f64]) {
        let jac = &self.jac;
        for i in 0..self.strips {
            let tau = Complex::new(tau_re[i], tau_im[i]);
            let tc = tau * c;
            for j in 0..self.n {
                let (wx, wv) = (jac.wx[(i, j)], jac.wv[(i, j)]);
                self.tw_re[(i, j)] = tc.re * wv + tau.re * wx;
                self.tw_im[(i, j)] = tc.im * wv + tau.im * wx;
            }
        }
    }

    /// Factor `c I − J` for the real shift `c` into slot `slot`; false if singular.
    pub(crate) fn factor_real(&mut self, slot: usize, c: f64) -> bool {
        let (n, ns, strips) = (self.n, self.ns(), self.strips);
        let cc = Complex::new(c, 0.0);
        while self.real.len() <= slot {
            let lus = (0..strips).map(|_| DenseLu::new(ns)).collect();
            self.real.push(Slot::new(cc, DenseLu::new(n), lus, ns));
        }
        let mut sl = std::mem::replace(
            &mut self.real[slot],
            Slot::new(cc, DenseLu::new(0), Vec::new(), 0),
        );
        sl.c = cc;
        let ok = self.factor_strips(&mut sl) && {
            self.coupling(cc, &sl.tau_re, &sl.tau_im);
            let jac = &self.jac;
            let mut k = DMatrixViewMut::from_slice(sl.k.matrix_mut(), n, n);
            k.copy_from(&jac.f);
            k.gemm(-1.0, &jac.g, &self.tw_re, 1.0);
            k.zip_zip_apply(&jac.mass, &self.e, |k, m, e| *k += c * c * m - c * e);
            sl.k.factor()
        };
        self.real[slot] = sl;
        ok
    }

    /// Factor `c I − J` for the complex shift `c` into slot `slot`; false if singular.
    pub(crate) fn factor_complex(&mut self, slot: usize, c: Complex<f64>) -> bool {
        let (n, ns, strips) = (self.n, self.ns(), self.strips);
        while self.complex.len() <= slot {
            let lus = (0..strips).map(|_| ComplexLu::new(ns)).collect();
            self.complex.push(Slot::new(c, ComplexLu::new(n), lus, ns));
        }
        let mut sl = std::mem::replace(
            &mut self.complex[slot],
            Slot::new(c, ComplexLu::new(0), Vec::new(), 0),
        );
        sl.c = c;
        let ok = self.factor_strips(&mut sl) && {
            self.coupling(c, &sl.tau_re, &sl.tau_im);
            let jac = &self.jac;
            let c2 = c * c;
            let (kr, ki) = sl.k.matrix_mut();
            let mut kr = DMatrixViewMut::from_slice(kr, n, n);
            kr.copy_from(&jac.f);
            kr.gemm(-1.0, &jac.g, &self.tw_re, 1.0);
            kr.zip_zip_apply(&jac.mass, &self.e, |k, m, e| *k += c2.re * m - c.re * e);
            let mut ki = DMatrixViewMut::from_slice(ki, n, n);
            ki.gemm(-1.0, &jac.g, &self.tw_im, 0.0);
            ki.zip_zip_apply(&jac.mass, &self.e, |k, m, e| *k += c2.im * m - c.im * e);
            sl.k.factor()
        };
        self.complex[slot] = sl;
        ok
    }

    /// `b ← (c I − J)⁻¹ b` with real slot `slot`.
    pub(crate) fn solve_real(&mut self, slot: usize, b: &mut [f64]) {
        let (n, ns) = (self.n, self.ns());
        let sl = &self.real[slot];
        let c = sl.c.re;
        let jac = &self.jac;
        let (bs, ba) = b.split_at_mut(2 * n);
        let (bx, bp) = bs.split_at_mut(n);
        // Lag states: u_i = D_i⁻¹ b_a,i, b_p += Σ g_i C̄ᵀ u_i, and − G τ W_v b_x.
        for (i, ui) in ba.chunks_exact_mut(ns).enumerate() {
            sl.strips[sl.lu_of[i]].solve_in_place(ui);
            let cu = dot(ui, self.lag.c.as_slice());
            let wb = dot(col(&self.wvt, i), bx);
            let s = cu - sl.tau_re[i] * wb;
            for (v, g) in bp.iter_mut().zip(col(&jac.g, i)) {
                *v += g * s;
            }
        }
        // K Δx = b_p + (c M − P_p M) b_x; Δp = c M Δx − M A Δx − M b_x.
        let [mbx, _, _, _] = &mut self.v;
        mbx.fill(0.0);
        gemv_add(&jac.mass, bx, mbx, 1.0);
        for (v, m) in bp.iter_mut().zip(mbx.iter()) {
            *v += c * m;
        }
        gemv_add(&jac.pm, bx, bp, -1.0);
        sl.k.solve_in_place(bp);
        bx.copy_from_slice(bp);
        for (v, m) in bp.iter_mut().zip(mbx.iter()) {
            *v = -m;
        }
        gemv_add(&jac.mass, bx, bp, c);
        gemv_add(&jac.ma, bx, bp, -1.0);
        // Δa_i = u_i + d_i (w_iᵀ Δs).
        for (i, (ui, di)) in ba
            .chunks_exact_mut(ns)
            .zip(sl.d_re.chunks_exact(ns))
            .enumerate()
        {
            let ws = dot(col(&self.wt, i), bs);
            for (u, d) in ui.iter_mut().zip(di) {
                *u += d * ws;
            }
        }
    }

    /// `re + i im ← (c I − J)⁻¹ (re + i im)` with complex slot `slot`.
    pub(crate) fn solve_complex(&mut self, slot: usize, re: &mut [f64], im: &mut [f64]) {
        let (n, ns) = (self.n, self.ns());
        let sl = &self.complex[slot];
        let c = sl.c;
        let jac = &self.jac;
        let (sr, ar) = re.split_at_mut(2 * n);
        let (si, ai) = im.split_at_mut(2 * n);
        let (xr, pr) = sr.split_at_mut(n);
        let (xi, pi) = si.split_at_mut(n);
        for (i, (ur, ui)) in ar
            .chunks_exact_mut(ns)
            .zip(ai.chunks_exact_mut(ns))
            .enumerate()
        {
            sl.strips[sl.lu_of[i]].solve_in_place(ur, ui);
            let cr: f64 = ur.iter().zip(self.lag.c.iter()).map(|(u, c)| u * c).sum();
            let ci: f64 = ui.iter().zip(self.lag.c.iter()).map(|(u, c)| u * c).sum();
            let (mut wr, mut wi) = (0.0, 0.0);
            for ((w, a), b) in col(&self.wvt, i).iter().zip(xr.iter()).zip(xi.iter()) {
                wr += w * a;
                wi += w * b;
            }
            let tw = Complex::new(sl.tau_re[i], sl.tau_im[i]) * Complex::new(wr, wi);
            let (s_re, s_im) = (cr - tw.re, ci - tw.im);
            for ((vr, vi), g) in pr.iter_mut().zip(pi.iter_mut()).zip(col(&jac.g, i)) {
                *vr += g * s_re;
                *vi += g * s_im;
            }
        }
        let [mr, mi, _, _] = &mut self.v;
        mr.fill(0.0);
        mi.fill(0.0);
        gemv_add(&jac.mass, xr, mr, 1.0);
        gemv_add(&jac.mass, xi, mi, 1.0);
        for k in 0..n {
            pr[k] += c.re * mr[k] - c.im * mi[k];
            pi[k] += c.re * mi[k] + c.im * mr[k];
        }
        gemv_add(&jac.pm, xr, pr, -1.0);
        gemv_add(&jac.pm, xi, pi, -1.0);
        sl.k.solve_in_place(pr, pi);
        xr.copy_from_slice(pr);
        xi.copy_from_slice(pi);
        // Δp = c M Δx − M A Δx − M b_x.
        let [mbr, mbi, mxr, mxi] = &mut self.v;
        mxr.fill(0.0);
        mxi.fill(0.0);
        gemv_add(&jac.mass, xr, mxr, 1.0);
        gemv_add(&jac.mass, xi, mxi, 1.0);
        for k in 0..n {
            pr[k] = c.re * mxr[k] - c.im * mxi[k] - mbr[k];
            pi[k] = c.re * mxi[k] + c.im * mxr[k] - mbi[k];
        }
        gemv_add(&jac.ma, xr, pr, -1.0);
        gemv_add(&jac.ma, xi, pi, -1.0);
        for i in 0..self.strips {
            let w = col(&self.wt, i);
            let (mut wr, mut wi) = (0.0, 0.0);
            for ((w, a), b) in w.iter().zip(sr.iter()).zip(si.iter()) {
                wr += w * a;
                wi += w * b;
            }
            let k = i * ns..(i + 1) * ns;
            let it = ar[k.clone()]
                .iter_mut()
                .zip(ai[k.clone()].iter_mut())
                .zip(sl.d_re[k.clone()].iter().zip(&sl.d_im[k]));
            for ((ur, ui), (&dr, &di)) in it {
                *ur += dr * wr - di * wi;
                *ui += dr * wi + di * wr;
            }
        }
    }
}

/// The strips' small factorizations, real or complex.
trait StripLu {
    /// Factor `c I − r H̄`; false if singular (a real LU takes `Re c`).
    fn factor_shifted(&mut self, c: Complex<f64>, r: f64, h: &DMatrix<f64>) -> bool;
    /// `re + i im ← (c I − r H̄)⁻¹ (re + i im)` (a real LU: `im` stays 0).
    fn solve(&self, re: &mut [f64], im: &mut [f64]);
}

impl StripLu for DenseLu {
    fn factor_shifted(&mut self, c: Complex<f64>, r: f64, h: &DMatrix<f64>) -> bool {
        let ns = h.nrows();
        let m = self.matrix_mut();
        for (v, hv) in m.iter_mut().zip(h.iter()) {
            *v = -r * hv;
        }
        for k in 0..ns {
            m[k + k * ns] += c.re;
        }
        self.factor()
    }
    fn solve(&self, re: &mut [f64], _im: &mut [f64]) {
        self.solve_in_place(re);
    }
}

impl StripLu for ComplexLu {
    fn factor_shifted(&mut self, c: Complex<f64>, r: f64, h: &DMatrix<f64>) -> bool {
        let ns = h.nrows();
        let (mr, mi) = self.matrix_mut();
        for (v, hv) in mr.iter_mut().zip(h.iter()) {
            *v = -r * hv;
        }
        mi.fill(0.0);
        for k in 0..ns {
            mr[k + k * ns] += c.re;
            mi[k + k * ns] = c.im;
        }
        self.factor()
    }
    fn solve(&self, re: &mut [f64], im: &mut [f64]) {
        self.solve_in_place(re, im);
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::{Complex, DMatrix, DVector};

    use crate::beam::Profile;
    use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
    use crate::model::AppliedLoads;
    use crate::solve::aeroelastic::equations::tests::test_wing;
    use crate::solve::aeroelastic::{
        AeroelasticEquations, FlightHistory, Gust, GustPenetration, GustShape,
    };
    use crate::solve::integrate::OdeSystem;
    use crate::solve::Damping;

    /// Largest relative difference `‖x − x_ref‖∞ / ‖x_ref‖∞` between the eliminated and the
    /// dense Newton steps for the real shift `c` and the complex one `c (1 + i)`.
    fn newton_step_difference<M: AeroStructure>(aero: &Aeroelastic<M>, c: f64) -> f64 {
        let loads = AppliedLoads::none();
        let flight = FlightHistory {
            deflection_changes: Vec::new(),
            initial: FlightCondition {
                speed: 12.0,
                root_angle: 0.05,
                gravity: Some(9.81),
            },
            speed_change: None,
            root_angle_change: None,
            gust: Some(Gust {
                shape: GustShape::OneMinusCosine { length: 10.0 },
                amplitude: 1.5,
                start: 0.0,
                spanwise: Profile::Uniform(1.0),
                penetration: GustPenetration::Uniform,
            }),
        };
        let damping = Damping::Rayleigh {
            alpha: 0.1,
            beta: 1e-3,
        };
        let mut eom =
            AeroelasticEquations::new(aero, &loads, vec![], flight, &damping, "f").unwrap();
        let (n, na, dim) = (eom.n_dofs(), eom.n_aero_states(), eom.dim());
        // A deformed, moving state with "random" lag states (fixed pseudo-random sequence).
        let x: Vec<f64> = (0..n).map(|i| 0.1 * (1.0 + i as f64).sin()).collect();
        let xd: Vec<f64> = (0..n).map(|i| 0.5 * (2.3 * i as f64).cos()).collect();
        let a: Vec<f64> = (0..na)
            .map(|i| 0.3 * (0.7 * i as f64 + 0.2).cos())
            .collect();
        let y = eom.state(&x, &xd, &a);
        let b: Vec<f64> = (0..dim).map(|i| (1.7 * i as f64 + 0.3).sin()).collect();
        let bi: Vec<f64> = (0..dim).map(|i| (0.9 * i as f64 + 1.1).cos()).collect();
        let t = 0.3;
        let mut jac = DMatrix::zeros(dim, dim);
        eom.jacobian(t, &y, &mut jac);
        let cc = Complex::new(c, c);
        // Dense references by nalgebra's LU.
        let dense_real = (DMatrix::identity(dim, dim) * c - &jac)
            .lu()
            .solve(&DVector::from_column_slice(&b))
            .unwrap();
        let jc = jac.map(|v| Complex::new(v, 0.0));
        let bc = DVector::from_fn(dim, |i, _| Complex::new(b[i], bi[i]));
        let dense_complex = (DMatrix::identity(dim, dim) * cc - jc)
            .lu()
            .solve(&bc)
            .unwrap();
        let solver = eom.newton_solver().expect("lag states: eliminated");
        assert!(solver.linearize(t, &y));
        assert!(solver.factor_real(0, c) && solver.factor_complex(0, cc));
        let mut xr = b.clone();
        solver.solve_real(0, &mut xr);
        let (mut zr, mut zi) = (b.clone(), bi.clone());
        solver.solve_complex(0, &mut zr, &mut zi);
        let e_real = (0..dim)
            .map(|i| (xr[i] - dense_real[i]).abs())
            .fold(0.0, f64::max)
            / dense_real.amax();
        let scale = dense_complex.iter().map(|v| v.norm()).fold(0.0, f64::max);
        let e_complex = (0..dim)
            .map(|i| (Complex::new(zr[i], zi[i]) - dense_complex[i]).norm())
            .fold(0.0, f64::max)
            / scale;
        e_real.max(e_complex)
    }

    /// The Newton step by elimination of the lag states and momenta equals the dense LU's of
    /// the whole state, for Jones' and Peters' lags, full and reduced models, at the shifts of
    /// Radau steps of 1e-1 to 1e-4 s (`c = γ/h`). Both are backward-stable solves of the same
    /// system, the elimination through `M A = M (M⁻¹ B)` and `P_p M`, whose round-off grows with
    /// `cond M` and with `c` (the `c² M − c E` of `K(c)` cancel in the step): measured
    /// differences 1e-15 to 4e-11, the largest at `c = 3e4`; bound 1e-9. The tapered test wing
    /// has a lag rate of its own on every strip; Patil's uniform wing (n = 6) has one rate on
    /// all strips, whose factorization they share: measured up to 1.5e-8 at `c = 3e4` (the same
    /// to the digit with the sharing switched off: the round-off of `M A` for its 2.7 m
    /// elements, not the sharing); bound 1e-7.
    #[test]
    fn eliminated_newton_step_matches_the_dense_lu() {
        for am in [Aerodynamics::Wagner, Aerodynamics::Peters { states: 6 }] {
            for (full, bound) in [
                (test_wing(5, am), 1e-9),
                (crate::wings::patil_wing(6, am).unwrap(), 1e-7),
            ] {
                let rom = full.reduced(&[0, 1, 2, 3]).unwrap();
                for c in [30.0, 3e2, 3e3, 3e4] {
                    let ef = newton_step_difference(&full, c);
                    let er = newton_step_difference(&rom, c);
                    println!("{am:?} c = {c}: full {ef:.1e}, reduced {er:.1e}");
                    assert!(
                        ef < bound && er < bound,
                        "{am:?} c = {c}: {ef:.1e} {er:.1e}"
                    );
                }
            }
        }
    }
}
