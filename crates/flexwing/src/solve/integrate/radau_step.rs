//! The parts of one Radau IIA step (`radau.rs`), named as in Hairer & Wanner II §IV.8 and done as
//! `RADAU5` does them: the iteration matrices, the starting values, the simplified Newton
//! iteration (`SLVRAD`), the error estimate (`ESTRAD`), the step-size proposal, and the
//! collocation polynomial kept for dense output (`CONTR5`). The driver loop in `radau.rs` decides
//! from their results; the state that lives from step to step is [`State`] (diffsol's split of a
//! method and its state).

use nalgebra::Complex;

use super::radau::{
    ALPHA, BETA, C1, C1M1, C1MC2, C2, C2M1, DD1, DD2, DD3, FACL, FACR, GAMMA, SAFE, SQ6, T11, T12,
    T13, T21, T22, T23, T31, TI11, TI12, TI13, TI21, TI22, TI23, TI31, TI32, TI33,
};
use super::{IntegratorStats, IterationMatrices, OdeSystem, Trajectory};

/// Settings of a run, derived once from the options.
pub(super) struct Settings {
    /// Tolerances transformed as `RADAU5` (module documentation of `radau.rs`).
    pub(super) rtol: f64,
    pub(super) atol: Vec<f64>,
    /// Newton iterations per step (`NIT`).
    pub(super) nit: usize,
    /// Contraction below which the Jacobian is kept (`THET`).
    pub(super) thet: f64,
    /// Newton stopping tolerance (`FNEWT`).
    pub(super) fnewt: f64,
    /// Step ratios that keep the step and the factorizations (`QUOT1`, `QUOT2`).
    pub(super) quot1: f64,
    pub(super) quot2: f64,
    /// `SAFE (1 + 2 NIT)`, the numerator of the step-size safety factor.
    pub(super) cfac: f64,
    /// Largest step.
    pub(super) hmaxn: f64,
    /// Linearize at every step (the system's linearizations are cheap).
    pub(super) relinearize: bool,
}

/// What a run carries from step to step: the solution, the step sizes and `RADAU5`'s flags.
pub(super) struct State {
    pub(super) t: f64,
    pub(super) y: Vec<f64>,
    /// Step to try, and the last accepted one (for the collocation polynomial).
    pub(super) h: f64,
    pub(super) h_old: f64,
    pub(super) first: bool,
    pub(super) reject: bool,
    pub(super) last: bool,
    pub(super) need_jac: bool,
    pub(super) need_lu: bool,
    /// The Jacobian is at the current `(t, y)` (`CALJAC`).
    pub(super) jac_current: bool,
    /// `θ/(1 − θ)` of the last Newton iteration (`FACCON`) and its contraction `θ`.
    pub(super) faccon: f64,
    pub(super) theta: f64,
    pub(super) n_singular: usize,
    pub(super) last_failure_non_finite: bool,
    /// Predictive controller: the last accepted step and its error.
    pub(super) h_acc: f64,
    pub(super) err_acc: f64,
}

impl State {
    /// At `(t0, y0)` with the first step `h` (cut to reach `t_end`); a Jacobian and its
    /// factorizations are needed.
    pub(super) fn new(t0: f64, y0: &[f64], h: f64, t_end: f64) -> Self {
        let mut st = State {
            t: t0,
            y: y0.to_vec(),
            h,
            h_old: h,
            first: true,
            reject: false,
            last: false,
            need_jac: true,
            need_lu: true,
            jac_current: false,
            faccon: 1.0,
            theta: 0.0,
            n_singular: 0,
            last_failure_non_finite: false,
            h_acc: h,
            err_acc: 1e-2,
        };
        if st.h >= t_end - st.t {
            st.h = t_end - st.t;
            st.last = true;
        }
        st.h_old = st.h;
        st.h_acc = st.h;
        st
    }

    /// A step rejected because its iteration matrix was singular or its Newton iteration
    /// failed: retry with the step times `factor`, with a fresh Jacobian unless it is current.
    pub(super) fn newton_failed(&mut self, factor: f64, stats: &mut IntegratorStats) {
        stats.rejected_steps += 1;
        stats.newton_failures += 1;
        self.h *= factor;
        self.reject = true;
        self.last = false;
        self.need_jac = !self.jac_current;
        self.need_lu = true;
    }

    /// After an accepted step whose error proposed `h_new`: the next step, kept with its
    /// factorizations when the ratio to the current one lies within `[quot1, quot2]` (and the
    /// Jacobian is kept), else set with fresh factorizations (and a fresh Jacobian when Newton
    /// converged slowly or the system relinearizes at every step).
    pub(super) fn next_step(&mut self, h_new: f64, set: &Settings, t_end: f64) {
        let mut h_new = h_new.min(set.hmaxn);
        if self.reject {
            h_new = h_new.min(self.h);
        }
        self.reject = false;
        if self.t + h_new / set.quot1 >= t_end {
            self.h = t_end - self.t;
            self.last = true;
        } else {
            let qt = h_new / self.h;
            if !set.relinearize && self.theta <= set.thet && (set.quot1..=set.quot2).contains(&qt) {
                return;
            }
            self.h = h_new;
        }
        self.need_lu = true;
        self.need_jac = set.relinearize || self.theta > set.thet;
    }
}

/// What the simplified Newton iteration of one step ended with.
pub(super) enum Newton {
    /// Converged after this many iterations.
    Converged(usize),
    /// Diverging, too slow, or a non-finite value: halve the step.
    Failed,
    /// Converging too slowly for the iterations left: retry with the step times this factor.
    Slow(f64),
}

/// Scratch of the integrator, allocated once per run.
pub(super) struct Scratch {
    /// `γ/h I − J` (real slot 0) and `(α + iβ)/h I − J` (complex slot 0).
    pub(super) mats: IterationMatrices,
    /// Stage increments `Z_i = Y_i − y` (and the right-hand sides during an iteration).
    z: [Vec<f64>; 3],
    /// Transformed increments `W = T⁻¹ Z`.
    w: [Vec<f64>; 3],
    /// Coefficients of the collocation polynomial of the last accepted step.
    cont: [Vec<f64>; 3],
    /// Stage state, error-estimate vectors.
    tmp: Vec<f64>,
    f2: Vec<f64>,
    err: Vec<f64>,
    /// The quadratures ([`Quadratures`]), if the system has any.
    quadratures: Option<Quadratures>,
    /// `f(t, y)` at the start of the step.
    pub(super) f0: Vec<f64>,
    pub(super) scal: Vec<f64>,
}

/// Radau's own step of the quadrature states ([`OdeSystem::quadrature_states`]): their stages
/// are the method's quadrature `Z_q = h A F_q` of their rates at the stages, each rate taken at
/// the stage's own point and moved by the Newton correction to first order,
/// `F_q,j = f_q(Y_j) + g_j·ΔZ_j` ([`OdeSystem::quadrature_gradient`], with `g_j` at stage `j`'s
/// own `Q`, `ẋ`). So they are converged with the other stages after one Newton iteration, to
/// the stages' convergence error and a term of second order in their correction.
/// `ΔZ_j = Σ_k T_jk ΔW_k` and `J̃ ΔZ_j = Σ_k T_jk J̃ ΔW_k` with `J̃ ΔW_k = c_k ΔW_k − b_k` from
/// the transformed systems `(c_k I − J̃) ΔW_k = b_k` (their first block row is what the step
/// changes `ẋ` by).
struct Quadratures {
    /// Components solved by the Newton systems (`dim − quadrature_states`).
    lead: usize,
    /// The quadrature rates at each stage's point, then moved by the correction.
    rates: [Vec<f64>; 3],
    /// The transformed right-hand sides `b_k` of the last solve (leading part).
    b: [Vec<f64>; 3],
    /// `ΔZ_j` and `J̃ ΔZ_j` (leading part).
    dz: [Vec<f64>; 3],
    jdz: [Vec<f64>; 3],
    gradient: Vec<f64>,
}

impl Quadratures {
    fn new(dim: usize, states: usize) -> Option<Self> {
        let lead = dim - states;
        let v = |m: usize| [vec![0.0; m], vec![0.0; m], vec![0.0; m]];
        (states > 0).then(|| Self {
            lead,
            rates: v(states),
            b: v(lead),
            dz: v(lead),
            jdz: v(lead),
            gradient: vec![0.0; states],
        })
    }
}

/// Radau IIA's coefficients `a_ij` (Hairer & Wanner II, Table IV.5.6), for the quadratures.
pub(super) const A: [[f64; 3]; 3] = [
    [
        (88.0 - 7.0 * SQ6) / 360.0,
        (296.0 - 169.0 * SQ6) / 1800.0,
        (-2.0 + 3.0 * SQ6) / 225.0,
    ],
    [
        (296.0 + 169.0 * SQ6) / 1800.0,
        (88.0 + 7.0 * SQ6) / 360.0,
        (-2.0 - 3.0 * SQ6) / 225.0,
    ],
    [(16.0 - SQ6) / 36.0, (16.0 + SQ6) / 36.0, 1.0 / 9.0],
];

/// RMS norm of `v / scal`.
fn scaled_rms(v: &[f64], scal: &[f64]) -> f64 {
    super::scaled_rms(v, scal)
}

impl Scratch {
    pub(super) fn new<S: OdeSystem>(system: &mut S) -> Self {
        let n = system.dim();
        let quadratures = Quadratures::new(n, system.quadrature_states());
        let mut mats = IterationMatrices::new(system);
        if quadratures.is_some() {
            mats.leave_quadratures();
        }
        Self {
            mats,
            quadratures,
            z: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            w: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            cont: [vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            tmp: vec![0.0; n],
            f2: vec![0.0; n],
            err: vec![0.0; n],
            f0: vec![0.0; n],
            scal: vec![0.0; n],
        }
    }

    /// The error scale `atol + rtol |y|`.
    pub(super) fn update_scale(&mut self, y: &[f64], set: &Settings) {
        for i in 0..y.len() {
            self.scal[i] = set.atol[i] + set.rtol * y[i].abs();
        }
    }

    /// The iteration matrices a step of `st` needs: a new Jacobian if asked for, and new
    /// factorizations after it or if asked for; false if the system cannot be linearized or a
    /// matrix is singular.
    pub(super) fn iteration_matrices<S: OdeSystem>(
        &mut self,
        system: &mut S,
        st: &mut State,
        stats: &mut IntegratorStats,
    ) -> bool {
        let mut singular = false;
        if st.need_jac {
            singular = !self.mats.linearize(system, st.t, &st.y);
            stats.jacobian_evaluations += 1;
            st.jac_current = !singular;
            st.need_jac = false;
            st.need_lu = true;
        }
        if st.need_lu && !singular {
            stats.factorizations += 1;
            singular = !self.factor(system, st.h);
            st.need_lu = singular;
        }
        !singular
    }

    /// Iteration matrices: factor `γ/h I − J` and `(α + iβ)/h I − J`; false if either is
    /// singular.
    pub(super) fn factor<S: OdeSystem>(&mut self, system: &mut S, h: f64) -> bool {
        self.mats.factor_real(system, 0, GAMMA / h)
            && self
                .mats
                .factor_complex(system, 0, Complex::new(ALPHA / h, BETA / h))
    }

    /// Starting values of the stage increments: the collocation polynomial of the previous
    /// step, extrapolated (zero at the first step).
    pub(super) fn starting_values(&mut self, st: &State) {
        if st.first {
            for k in 0..3 {
                self.z[k].fill(0.0);
                self.w[k].fill(0.0);
            }
            return;
        }
        let c3q = st.h / st.h_old;
        let (c1q, c2q) = (C1 * c3q, C2 * c3q);
        for i in 0..self.tmp.len() {
            let (ak1, ak2, ak3) = (self.cont[0][i], self.cont[1][i], self.cont[2][i]);
            let z1 = c1q * (ak1 + (c1q - C2M1) * (ak2 + (c1q - C1M1) * ak3));
            let z2 = c2q * (ak1 + (c2q - C2M1) * (ak2 + (c2q - C1M1) * ak3));
            let z3 = c3q * (ak1 + (c3q - C2M1) * (ak2 + (c3q - C1M1) * ak3));
            self.z[0][i] = z1;
            self.z[1][i] = z2;
            self.z[2][i] = z3;
            self.w[0][i] = TI11 * z1 + TI12 * z2 + TI13 * z3;
            self.w[1][i] = TI21 * z1 + TI22 * z2 + TI23 * z3;
            self.w[2][i] = TI31 * z1 + TI32 * z2 + TI33 * z3;
        }
    }

    /// Solve the transformed Newton system for the corrections of `W`: on entry `z` holds
    /// `T⁻¹ F(Z)`, on exit the corrections `ΔW` (`RADAU5`'s `SLVRAD`).
    fn solve<S: OdeSystem>(&mut self, system: &mut S, h: f64) {
        let (fac1, alphn, betan) = (GAMMA / h, ALPHA / h, BETA / h);
        let n = self.tmp.len();
        let [z1, z2, z3] = &mut self.z;
        let [w1, w2, w3] = &self.w;
        for i in 0..n {
            z1[i] -= w1[i] * fac1;
            let (s2, s3) = (-w2[i], -w3[i]);
            z2[i] += s2 * alphn - s3 * betan;
            z3[i] += s3 * alphn + s2 * betan;
        }
        if let Some(q) = &mut self.quadratures {
            for (b, z) in q.b.iter_mut().zip([&*z1, &*z2, &*z3]) {
                b.copy_from_slice(&z[..q.lead]);
            }
        }
        self.mats.solve_real(system, 0, z1);
        self.mats.solve_complex(system, 0, z2, z3);
    }

    /// The simplified Newton iteration of the stages on `[t, t_new]`, with `RADAU5`'s
    /// convergence monitoring (contraction `θ`, predicted final error).
    pub(super) fn newton<S: OdeSystem>(
        &mut self,
        system: &mut S,
        st: &mut State,
        set: &Settings,
        t_new: f64,
        stats: &mut IntegratorStats,
    ) -> Newton {
        let (t, h, n, nit) = (st.t, st.h, self.tmp.len(), set.nit);
        st.faccon = st.faccon.max(f64::EPSILON).powf(0.8);
        st.theta = set.thet.abs();
        let mut newt = 0;
        let mut dyno_old = 0.0;
        let mut thq_old = 0.0;
        loop {
            if newt >= nit {
                return Newton::Failed;
            }
            let nodes = [t + C1 * h, t + C2 * h, t_new];
            let mut finite = true;
            for k in 0..3 {
                for i in 0..n {
                    self.tmp[i] = st.y[i] + self.z[k][i];
                }
                system.rhs(nodes[k], &self.tmp, &mut self.z[k]);
                finite &= self.z[k].iter().all(|v| v.is_finite());
                if let Some(q) = &mut self.quadratures {
                    system.keep_quadrature_point(k);
                    q.rates[k].copy_from_slice(&self.z[k][q.lead..]);
                }
            }
            stats.rhs_evaluations += 3;
            if !finite {
                st.last_failure_non_finite = true;
                return Newton::Failed;
            }
            {
                let [z1, z2, z3] = &mut self.z;
                for i in 0..n {
                    let (a1, a2, a3) = (z1[i], z2[i], z3[i]);
                    z1[i] = TI11 * a1 + TI12 * a2 + TI13 * a3;
                    z2[i] = TI21 * a1 + TI22 * a2 + TI23 * a3;
                    z3[i] = TI31 * a1 + TI32 * a2 + TI33 * a3;
                }
            }
            self.solve(system, h);
            stats.newton_iterations += 1;
            newt += 1;
            let dyno = ((scaled_rms(&self.z[0], &self.scal).powi(2)
                + scaled_rms(&self.z[1], &self.scal).powi(2)
                + scaled_rms(&self.z[2], &self.scal).powi(2))
                / 3.0)
                .sqrt();
            if !dyno.is_finite() {
                st.last_failure_non_finite = true;
                return Newton::Failed;
            }
            if newt > 1 && newt < nit {
                let thq = dyno / dyno_old;
                st.theta = if newt == 2 {
                    thq
                } else {
                    (thq * thq_old).sqrt()
                };
                thq_old = thq;
                if st.theta < 0.99 {
                    st.faccon = st.theta / (1.0 - st.theta);
                    let dyth =
                        st.faccon * dyno * st.theta.powi((nit - 1 - newt) as i32) / set.fnewt;
                    if dyth >= 1.0 {
                        let qnewt = dyth.clamp(1e-4, 20.0);
                        return Newton::Slow(
                            0.8 * qnewt.powf(-1.0 / (4.0 + nit as f64 - 1.0 - newt as f64)),
                        );
                    }
                } else {
                    return Newton::Failed;
                }
            }
            dyno_old = dyno.max(f64::EPSILON);
            self.quadrature_corrections(h);
            let [z1, z2, z3] = &mut self.z;
            let [w1, w2, w3] = &mut self.w;
            for i in 0..n {
                let (f1, f2, f3) = (w1[i] + z1[i], w2[i] + z2[i], w3[i] + z3[i]);
                w1[i] = f1;
                w2[i] = f2;
                w3[i] = f3;
                z1[i] = T11 * f1 + T12 * f2 + T13 * f3;
                z2[i] = T21 * f1 + T22 * f2 + T23 * f3;
                z3[i] = T31 * f1 + f2;
            }
            // The quadratures (out of `dyno`: infinite atol) from the stages' own rates moved
            // by the correction ([`Quadratures`]): converged with the other stages.
            self.step_quadratures(system, h);
            if st.faccon * dyno <= set.fnewt {
                return Newton::Converged(newt);
            }
        }
    }

    /// `ΔZ_j` and `J̃ ΔZ_j` of the leading components from the corrections `ΔW` (in `z`) and
    /// the right-hand sides `b` of the transformed systems ([`Quadratures`]).
    fn quadrature_corrections(&mut self, h: f64) {
        let Some(q) = &mut self.quadratures else {
            return;
        };
        let (fac1, alphn, betan) = (GAMMA / h, ALPHA / h, BETA / h);
        let [z1, z2, z3] = &self.z;
        for i in 0..q.lead {
            let (d1, d2, d3) = (z1[i], z2[i], z3[i]);
            let j1 = fac1 * d1 - q.b[0][i];
            let j2 = alphn * d2 - betan * d3 - q.b[1][i];
            let j3 = betan * d2 + alphn * d3 - q.b[2][i];
            for (out, (a1, a2, a3)) in [(&mut q.dz, (d1, d2, d3)), (&mut q.jdz, (j1, j2, j3))] {
                out[0][i] = T11 * a1 + T12 * a2 + T13 * a3;
                out[1][i] = T21 * a1 + T22 * a2 + T23 * a3;
                out[2][i] = T31 * a1 + a2;
            }
        }
    }

    /// The quadratures' stages `Z_q = h A F_q` with each stage's rate moved by its correction
    /// ([`Quadratures`]), and their transformed `W_q = T⁻¹ Z_q`.
    fn step_quadratures<S: OdeSystem>(&mut self, system: &mut S, h: f64) {
        let Some(q) = &mut self.quadratures else {
            return;
        };
        for j in 0..3 {
            system.quadrature_gradient(j, &q.dz[j], &q.jdz[j], &mut q.gradient);
            for (r, g) in q.rates[j].iter_mut().zip(&q.gradient) {
                *r += g;
            }
        }
        for k in 0..q.gradient.len() {
            let i = q.lead + k;
            let f = [q.rates[0][k], q.rates[1][k], q.rates[2][k]];
            let z = A.map(|a| h * (a[0] * f[0] + a[1] * f[1] + a[2] * f[2]));
            for (zj, v) in self.z.iter_mut().zip(z) {
                zj[i] = v;
            }
            self.w[0][i] = TI11 * z[0] + TI12 * z[1] + TI13 * z[2];
            self.w[1][i] = TI21 * z[0] + TI22 * z[1] + TI23 * z[2];
            self.w[2][i] = TI31 * z[0] + TI32 * z[1] + TI33 * z[2];
        }
    }

    /// The error estimate (`RADAU5`'s `ESTRAD`): `(γ/h I − J)⁻¹` filters the stiff components
    /// of the difference to the embedded order-3 solution; after a rejected or the first step a
    /// second, better filtered estimate if the first fails.
    pub(super) fn error_estimate<S: OdeSystem>(
        &mut self,
        system: &mut S,
        st: &State,
        stats: &mut IntegratorStats,
    ) -> f64 {
        let n = self.tmp.len();
        let h = st.h;
        let (hee1, hee2, hee3) = (DD1 / h, DD2 / h, DD3 / h);
        for i in 0..n {
            self.f2[i] = hee1 * self.z[0][i] + hee2 * self.z[1][i] + hee3 * self.z[2][i];
            self.err[i] = self.f2[i] + self.f0[i];
        }
        self.mats.solve_real(system, 0, &mut self.err);
        let mut err = scaled_rms(&self.err, &self.scal).max(1e-10);
        if err >= 1.0 && (st.first || st.reject) {
            for i in 0..n {
                self.tmp[i] = st.y[i] + self.err[i];
            }
            system.rhs(st.t, &self.tmp, &mut self.err);
            stats.rhs_evaluations += 1;
            for i in 0..n {
                self.err[i] += self.f2[i];
            }
            self.mats.solve_real(system, 0, &mut self.err);
            err = scaled_rms(&self.err, &self.scal).max(1e-10);
            if !err.is_finite() {
                err = 1e10;
            }
        }
        err
    }

    /// Accept the step to `t_new`: `y ← y + Z_3`, and the coefficients of the collocation
    /// polynomial for dense output and the next starting values (`CONTR5`).
    pub(super) fn accept(&mut self, st: &mut State, t_new: f64) {
        st.h_old = st.h;
        st.t = t_new;
        let [z1, z2, z3] = &self.z;
        let [c1, c2, c3] = &mut self.cont;
        for i in 0..st.y.len() {
            st.y[i] += z3[i];
            c1[i] = (z2[i] - z3[i]) / C2M1;
            let ak = (z1[i] - z2[i]) / C1MC2;
            let acont3 = (ak - z1[i] / C1) / C2;
            c2[i] = (ak - c1[i]) / C1M1;
            c3[i] = c2[i] - acont3;
        }
    }

    /// Dense output on `(t − h_old, t]` from the collocation polynomial (exact at `t`) for the
    /// output times from `next_out`; returns the index of the next output time.
    pub(super) fn dense_output(
        &self,
        st: &State,
        t_out: &[f64],
        mut next_out: usize,
        traj: &mut Trajectory,
    ) -> usize {
        while next_out < t_out.len() && t_out[next_out] <= st.t {
            let tt = t_out[next_out];
            let sq = (tt - st.t) / st.h_old;
            let [c1, c2, c3] = &self.cont;
            let yo: Vec<f64> = (0..st.y.len())
                .map(|i| st.y[i] + sq * (c1[i] + (sq - C2M1) * (c2[i] + (sq - C1M1) * c3[i])))
                .collect();
            traj.t.push(tt);
            traj.y.push(yo);
            next_out += 1;
        }
        next_out
    }
}

/// Step-size control: the step proposed after an error `err` with `newt` Newton iterations,
/// at most 8 times larger and 5 times smaller than `h`; with `predictive`, Gustafsson's
/// predictive controller (accepted steps after the first) may shorten it.
pub(super) fn propose_step(
    st: &State,
    set: &Settings,
    err: f64,
    newt: usize,
    predictive: bool,
) -> f64 {
    let h = st.h;
    let fac = SAFE.min(set.cfac / (newt + 2 * set.nit) as f64);
    let mut quot = (err.powf(0.25) / fac).clamp(FACR, FACL);
    if predictive {
        let facgus =
            ((st.h_acc / h) * (err * err / st.err_acc).powf(0.25) / SAFE).clamp(FACR, FACL);
        quot = quot.max(facgus);
    }
    h / quot
}
