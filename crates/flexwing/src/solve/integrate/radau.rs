//! The three-stage Radau IIA method (order 5, L-stable, stiffly accurate) with the step-size
//! control, the simplified Newton iteration and the error estimate of Hairer & Wanner's `RADAU5`.
//!
//! The `3N` Newton system of the stages is transformed with the eigenvectors `T` of the inverse
//! coefficient matrix `A⁻¹` into one real `N × N` system `(γ/h I − J)` and one complex system
//! `((α + iβ)/h I − J)`: one real and one complex LU per factorization instead of a `3N` one (or
//! the system's own solver of both, `OdeSystem::newton_solver`: the full beam model's O(n) chain
//! sweeps). The Jacobian is reused from step to step while Newton converges fast (contraction
//! `θ ≤ jacobian_reuse`), and the factorizations are kept when the step size changes by a factor
//! in `[1, 1.2]`; a system whose linearizations are cheap is linearized at every step instead.
//!
//! `integrate` is the driver: it keeps `RADAU5`'s control flow and calls the named parts of a
//! step in `radau_step.rs` (iteration matrices, starting values, Newton iteration, error
//! estimate, step-size proposal, collocation polynomial and dense output).
//!
//! Tolerances: the error estimate is of order 3 while the method is of order 5, so the relative
//! tolerance is transformed as in `RADAU5`, `rtol' = 0.1 rtol^(2/3)`, which makes the global
//! error roughly proportional to `rtol`. The absolute tolerance is applied **as given**
//! (`atol' = atol`). `RADAU5` scales it too, `atol' = atol rtol'/rtol = 0.1 rtol^(−1/3) atol`,
//! which loosens it as `rtol` is tightened (×46 at rtol 1e-8): a tighter `rtol` at a fixed `atol`
//! could then take fewer steps and give a worse answer (issue 24: a gust at rtol 1e-8 and atol
//! 1e-5 took 32 steps against 56 at the defaults, its twist 16× worse). With `atol' = atol` the
//! error test `|err_i| ≤ atol_i + rtol'|y_i|` only tightens with `rtol`
//! (`tests/suite/tolerances.rs` checks every integrator).
//!
//! # References
//! E. Hairer, G. Wanner, *Solving Ordinary Differential Equations II*, 2nd ed., Springer (1996),
//! §IV.8 (implementation of implicit Runge–Kutta methods) and the Fortran code `RADAU5` (version
//! of 2002) that it describes, whose constants and control logic this follows.
//! K. Gustafsson, "Control-theoretic techniques for stepsize selection in implicit Runge–Kutta
//! methods", ACM TOMS 20 (1994) 496–517 (the predictive controller).

use super::dopri5::initial_step;
use super::radau_step::{propose_step, Newton, Scratch, Settings, State};
use super::{
    check_output_times, failure, outputs_at_start, IntegrationResult, IntegratorStats,
    IterationMatrices, OdeSystem, Tolerances, Trajectory,
};
use crate::error::SolveError;

/// Options of [`Radau`].
#[derive(Debug, Clone, PartialEq)]
pub struct RadauOptions {
    /// Error tolerances (transformed internally as in `RADAU5`, see the module documentation).
    pub tolerances: Tolerances,
    /// Largest step (s). Default infinite.
    pub max_step: f64,
    /// Budget of steps, accepted and rejected, before the run stops with
    /// [`SolveError::TooManySteps`] and the output so far. Default 1 000 000.
    pub max_steps: usize,
    /// First step (s); `None` (default) picks one from the problem's scales.
    pub first_step: Option<f64>,
    /// Largest number of simplified Newton iterations per step (`RADAU5`'s `NIT`). Default 7.
    pub max_newton_iterations: usize,
    /// Contraction rate of the Newton iteration below which the Jacobian is kept for the next
    /// step (`RADAU5`'s `THET`). Default 0.1, `RADAU5`'s advice for Jacobians that are expensive
    /// (a beam model's costs about ten right-hand sides; on the paper's case (b) it halves the
    /// Jacobian evaluations against `RADAU5`'s default 0.001). A negative value recomputes it at
    /// every step. Not used when the system linearizes cheaply
    /// (`NewtonSolver::cheap_linearization`): it is then linearized at every step.
    pub jacobian_reuse: f64,
    /// When the proposed new step over the current one lies in `[lower, upper]`, the step and
    /// the factorizations are kept (`RADAU5`'s `WORK(5)`, `WORK(6)`). Default `(1.0, 1.2)`;
    /// `RADAU5` suggests `(0.99, 2.0)` for large systems, where an LU costs more than a few
    /// right-hand sides.
    pub unchanged_step_ratio: (f64, f64),
    /// Stopping tolerance of the Newton iteration relative to the error scale (`RADAU5`'s
    /// `FNEWT`); `None` (default) for `max(10 ε/rtol', min(0.03, √rtol'))`, or the system's
    /// bound if it is tighter (`NewtonSolver::newton_tolerance`).
    pub newton_tolerance: Option<f64>,
}

impl Default for RadauOptions {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            max_step: f64::INFINITY,
            max_steps: 1_000_000,
            first_step: None,
            max_newton_iterations: 7,
            jacobian_reuse: 0.1,
            unchanged_step_ratio: (QUOT1, QUOT2),
            newton_tolerance: None,
        }
    }
}

/// The Radau IIA implicit Runge–Kutta integrator of order 5, for stiff systems.
///
/// Counters: `factorizations` counts the pairs (one real, one complex LU) of `N × N` iteration
/// matrices, as `RADAU5`'s `NDEC` (with a system's own solver: its factorization pairs, and
/// `jacobian_evaluations` its linearizations); `rhs_evaluations` includes those of the error
/// estimate and of the initial step; `newton_iterations` counts the solves of the transformed
/// system (each costs three right-hand sides).
#[derive(Debug, Clone, Default)]
pub struct Radau {
    /// Options.
    pub options: RadauOptions,
}

// Nodes and the constants of RADAU5 (Hairer & Wanner II, §IV.8, and the code).
pub(super) const SQ6: f64 = 2.449_489_742_783_178;
pub(super) const C1: f64 = (4.0 - SQ6) / 10.0;
pub(super) const C2: f64 = (4.0 + SQ6) / 10.0;
pub(super) const C1M1: f64 = C1 - 1.0;
pub(super) const C2M1: f64 = C2 - 1.0;
pub(super) const C1MC2: f64 = C1 - C2;
/// Coefficients of the embedded error estimate.
pub(super) const DD1: f64 = -(13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD2: f64 = (-13.0 + 7.0 * SQ6) / 3.0;
pub(super) const DD3: f64 = -1.0 / 3.0;
/// The real eigenvalue `γ` of `A⁻¹`, and its complex pair `α ± iβ`.
pub(super) const GAMMA: f64 = 3.637_834_252_744_496;
pub(super) const ALPHA: f64 = 2.681_082_873_627_752_3;
pub(super) const BETA: f64 = 3.050_430_199_247_410_5;
/// Eigenvectors of `A⁻¹` (`T`) and the inverse (`T⁻¹`): `T⁻¹ A⁻¹ T = [[γ, 0, 0], [0, α, −β],
/// [0, β, α]]`.
pub(super) const T11: f64 = 9.123_239_487_089_295e-2;
pub(super) const T12: f64 = -0.141_255_295_020_954_2;
pub(super) const T13: f64 = -3.002_919_410_514_742_4e-2;
pub(super) const T21: f64 = 0.241_717_932_707_107;
pub(super) const T22: f64 = 0.204_129_352_293_799_94;
pub(super) const T23: f64 = 0.382_942_112_757_261_8;
pub(super) const T31: f64 = 0.966_048_182_615_093;
pub(super) const TI11: f64 = 4.325_579_890_063_155;
pub(super) const TI12: f64 = 0.339_199_251_815_809_87;
pub(super) const TI13: f64 = 0.541_770_539_935_874_9;
pub(super) const TI21: f64 = -4.178_718_591_551_905;
pub(super) const TI22: f64 = -0.327_682_820_761_062_4;
pub(super) const TI23: f64 = 0.476_623_554_500_550_45;
pub(super) const TI31: f64 = -0.502_872_634_945_786_9;
pub(super) const TI32: f64 = 2.571_926_949_855_605;
pub(super) const TI33: f64 = -0.596_039_204_828_224_9;
/// Safety factor of the step-size selection.
pub(super) const SAFE: f64 = 0.9;
/// Bounds of `h/h_new` (`RADAU5`'s `FACL`, `FACR`): the step grows at most 8-fold and shrinks at
/// most 5-fold.
pub(super) const FACL: f64 = 5.0;
pub(super) const FACR: f64 = 1.0 / 8.0;
/// Default bounds of [`RadauOptions::unchanged_step_ratio`].
pub(super) const QUOT1: f64 = 1.0;
pub(super) const QUOT2: f64 = 1.2;

impl Radau {
    fn validate(&self, dim: usize) -> Result<(), crate::InputError> {
        let o = &self.options;
        o.tolerances.validate("options.tolerances", dim)?;
        let positive = |field: &str, v: f64| {
            if v.is_nan() || v <= 0.0 {
                Err(crate::InputError::new(
                    field,
                    format!("must be a positive number, got {v}"),
                ))
            } else {
                Ok(())
            }
        };
        positive("options.max_step", o.max_step)?;
        if let Some(h) = o.first_step {
            if !(h.is_finite() && h > 0.0) {
                return Err(crate::InputError::new(
                    "options.first_step",
                    format!("must be a finite positive number, got {h}"),
                ));
            }
        }
        if o.max_newton_iterations == 0 {
            return Err(crate::InputError::new(
                "options.max_newton_iterations",
                "must be at least 1, got 0",
            ));
        }
        if o.jacobian_reuse.is_nan() || o.jacobian_reuse >= 1.0 {
            return Err(crate::InputError::new(
                "options.jacobian_reuse",
                format!("must be below 1, got {}", o.jacobian_reuse),
            ));
        }
        let (q1, q2) = o.unchanged_step_ratio;
        if !(q1 > 0.0 && q1 <= 1.0 && q2 >= 1.0 && q2.is_finite()) {
            return Err(crate::InputError::new(
                "options.unchanged_step_ratio",
                format!("needs 0 < lower ≤ 1 ≤ upper (finite), got ({q1}, {q2})"),
            ));
        }
        if let Some(f) = o.newton_tolerance {
            if !(f.is_finite() && f > 0.0) {
                return Err(crate::InputError::new(
                    "options.newton_tolerance",
                    format!("must be a finite positive number, got {f}"),
                ));
            }
        }
        Ok(())
    }

    /// Integrate `system` from `(t0, y0)` and return the state at each of `t_out`
    /// (non-decreasing, not before `t0`), from the collocation polynomial of the step that
    /// covers it. `progress` is called with the time after each step.
    ///
    /// # Errors
    /// Invalid output times or options are [`crate::InputError`]s wrapped in the failure; a step
    /// size below round-off (after repeated error-test or Newton failures), a non-finite
    /// state or the step budget stop the run with the output so far.
    pub fn integrate<S: OdeSystem>(
        &self,
        system: &mut S,
        t0: f64,
        y0: &[f64],
        t_out: &[f64],
        progress: &mut dyn FnMut(f64),
    ) -> IntegrationResult {
        let n = system.dim();
        let opts = &self.options;
        let mut stats = IntegratorStats::default();
        let mut traj = Trajectory::default();
        let fail = failure;
        if let Err(e) = check_output_times(t0, t_out).and_then(|_| self.validate(n)) {
            return fail(traj, stats, SolveError::from_input(e));
        }
        let t_end = t_out.last().copied().unwrap_or(t0);
        let mut next_out = outputs_at_start(t0, y0, t_out, &mut traj);
        if next_out == t_out.len() {
            return Ok((traj, stats));
        }
        let mut s = Scratch::new(system);
        let set = self.settings(n, t0, t_end, &s.mats);
        system.rhs(t0, y0, &mut s.f0);
        stats.rhs_evaluations += 1;
        if s.f0.iter().any(|v| !v.is_finite()) {
            return fail(traj, stats, SolveError::NonFinite { time: t0 });
        }
        s.update_scale(y0, &set);
        let h = match opts.first_step {
            Some(h) => h,
            None => initial_step(system, t0, y0, &s.f0, &set.atol, set.rtol, 3, &mut stats),
        }
        .min(set.hmaxn);
        let mut st = State::new(t0, y0, h, t_end);

        loop {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return fail(traj, stats, SolveError::TooManySteps { time: st.t, steps });
            }
            if !st.last && t_end - (st.t + st.h) <= 1e-8 * st.h {
                // A step that would stop a rounding error short of the end (after a kept or a
                // rejected step) is stretched to it: the step after it would be too small.
                st.h = t_end - st.t;
                st.last = true;
                st.need_lu = true;
            }
            if !(0.1 * st.h.abs() > st.t.abs() * f64::EPSILON) || !st.h.is_finite() {
                let e = if st.last_failure_non_finite {
                    SolveError::NonFinite { time: st.t }
                } else {
                    SolveError::StepSizeTooSmall {
                        time: st.t,
                        step: st.h,
                    }
                };
                return fail(traj, stats, e);
            }

            // Iteration matrices: a new Jacobian and/or new factorizations when asked for.
            if !s.iteration_matrices(system, &mut st, &mut stats) {
                // Singular iteration matrix: RADAU5 halves the step, five times at most.
                st.n_singular += 1;
                if st.n_singular >= 5 {
                    let e = SolveError::NewtonFailed {
                        time: st.t,
                        step: st.h,
                    };
                    return fail(traj, stats, e);
                }
                st.newton_failed(0.5, &mut stats);
                continue;
            }
            let t_new = if st.last { t_end } else { st.t + st.h };

            s.starting_values(&st);
            let newt = match s.newton(system, &mut st, &set, t_new, &mut stats) {
                Newton::Converged(newt) => newt,
                Newton::Slow(f) => {
                    st.newton_failed(f, &mut stats);
                    continue;
                }
                Newton::Failed => {
                    st.newton_failed(0.5, &mut stats);
                    continue;
                }
            };
            st.last_failure_non_finite = false;

            let err = s.error_estimate(system, &st, &mut stats);

            if err >= 1.0 {
                // Rejected.
                let h_new = propose_step(&st, &set, err, newt, false);
                st.reject = true;
                st.last = false;
                st.h = if st.first { 0.1 * st.h } else { h_new };
                stats.rejected_steps += 1;
                st.need_lu = true;
                st.need_jac = !st.jac_current;
                continue;
            }

            // Accepted.
            st.first = false;
            stats.steps += 1;
            let h_new = propose_step(&st, &set, err, newt, stats.steps > 1);
            st.h_acc = st.h;
            st.err_acc = err.max(1e-2);
            s.accept(&mut st, t_new);
            s.update_scale(&st.y, &set);
            next_out = s.dense_output(&st, t_out, next_out, &mut traj);
            progress(st.t);
            if system.step_accepted(st.t, &st.y).is_break() {
                return fail(traj, stats, SolveError::Halted { time: st.t });
            }
            st.jac_current = false;
            if st.last || next_out == t_out.len() {
                return Ok((traj, stats));
            }
            system.rhs(st.t, &st.y, &mut s.f0);
            stats.rhs_evaluations += 1;
            if s.f0.iter().any(|v| !v.is_finite()) {
                return fail(traj, stats, SolveError::NonFinite { time: st.t });
            }

            // The next step: kept with its factorizations when close enough to the proposal.
            st.next_step(h_new, &set, t_end);
        }
    }

    /// The settings of a run of dimension `n` on `[t0, t_end]`: `rtol` transformed as `RADAU5`,
    /// `atol` as given (module documentation), and the Newton and step-size constants.
    fn settings(&self, n: usize, t0: f64, t_end: f64, mats: &IterationMatrices) -> Settings {
        let opts = &self.options;
        let rtol_user = opts.tolerances.rtol;
        let rtol = 0.1 * rtol_user.powf(2.0 / 3.0);
        let _ = rtol_user;
        let atol: Vec<f64> = opts.tolerances.atol(n).to_vec();
        let nit = opts.max_newton_iterations;
        let (quot1, quot2) = opts.unchanged_step_ratio;
        Settings {
            rtol,
            atol,
            nit,
            thet: opts.jacobian_reuse,
            fnewt: opts.newton_tolerance.unwrap_or_else(|| {
                mats.newton_tolerance((10.0 * f64::EPSILON / rtol).max(0.03f64.min(rtol.sqrt())))
            }),
            relinearize: mats.cheap_linearization(),
            quot1,
            quot2,
            cfac: SAFE * (1 + 2 * nit) as f64,
            hmaxn: opts.max_step.min(t_end - t0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use nalgebra::DMatrix;

    use crate::solve::integrate::tests::{Oscillator, Riccati};

    /// The quadratures' coefficients `A` (`radau_step.rs`) against the method's definition:
    /// the collocation conditions `Σ_j a_ij c_j^(k−1) = c_i^k / k` for k = 1, 2, 3 at the nodes
    /// `c = (C1, C2, 1)` (Hairer & Wanner II, §IV.5, C(3)), and against `RADAU5`'s transformation:
    /// `T⁻¹ A⁻¹ T = diag(γ, [[α, −β], [β, α]])`, checked as `A T Λ = T`. Bound 1e-14: round-off
    /// of sums of a few terms of order 1 (the largest of `T⁻¹`'s entries is 4.3).
    #[test]
    fn quadrature_coefficients_are_radau_iia() {
        use super::super::radau_step::A;
        let c = [C1, C2, 1.0];
        for (i, row) in A.iter().enumerate() {
            for k in 1..=3 {
                let sum: f64 = (0..3).map(|j| row[j] * c[j].powi(k - 1)).sum();
                let want = c[i].powi(k) / k as f64;
                assert!(
                    (sum - want).abs() < 1e-14,
                    "row {i}, k = {k}: {sum} vs {want}"
                );
            }
        }
        let t = [[T11, T12, T13], [T21, T22, T23], [T31, 1.0, 0.0]];
        // T Λ: columns γ t₁, α t₂ + β t₃, −β t₂ + α t₃.
        let tl: Vec<[f64; 3]> = (0..3)
            .map(|i| {
                let r = t[i];
                [
                    GAMMA * r[0],
                    ALPHA * r[1] + BETA * r[2],
                    -BETA * r[1] + ALPHA * r[2],
                ]
            })
            .collect();
        for i in 0..3 {
            for k in 0..3 {
                let atl: f64 = (0..3).map(|j| A[i][j] * tl[j][k]).sum();
                assert!(
                    (atl - t[i][k]).abs() < 1e-14,
                    "(A T Λ)[{i}][{k}] = {atl} vs {}",
                    t[i][k]
                );
            }
        }
    }

    /// Van der Pol, `ε` form (Hairer & Wanner II, §IV.1).
    struct VanDerPol(f64);

    impl OdeSystem for VanDerPol {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = ((1.0 - y[0] * y[0]) * y[1] - y[0]) / self.0;
        }
        fn jacobian(&mut self, _t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
            jac[(0, 0)] = 0.0;
            jac[(0, 1)] = 1.0;
            jac[(1, 0)] = (-2.0 * y[0] * y[1] - 1.0) / self.0;
            jac[(1, 1)] = (1.0 - y[0] * y[0]) / self.0;
        }
    }

    /// Robertson's chemical kinetics (Hairer & Wanner II, §IV.1).
    struct Robertson;

    impl OdeSystem for Robertson {
        fn dim(&self) -> usize {
            3
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
            dy[2] = 3e7 * y[1] * y[1];
            dy[1] = -dy[0] - dy[2];
        }
        fn jacobian(&mut self, _t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
            jac[(0, 0)] = -0.04;
            jac[(0, 1)] = 1e4 * y[2];
            jac[(0, 2)] = 1e4 * y[1];
            jac[(2, 0)] = 0.0;
            jac[(2, 1)] = 6e7 * y[1];
            jac[(2, 2)] = 0.0;
            for j in 0..3 {
                jac[(1, j)] = -jac[(0, j)] - jac[(2, j)];
            }
        }
    }

    /// Van der Pol (`ε = 1e-6`, `y(0) = (2, 0)`) at `t = 2`, and Robertson at `t = 1e4`:
    /// `tests/data/stiff_reference/reference.txt` (SciPy Radau and LSODA at rtol 1e-12 agree to
    /// 3e-11; the van der Pol values also agree with the Test Set for IVP Solvers of Mazzia &
    /// Magherini, problem VDPOL, to 1e-13).
    const VDPOL_T2_Y1: f64 = 1.706_167_732_170_415_4;
    const VDPOL_T2_Y2: f64 = -0.892_809_701_024_869_9;
    const ROBER_T1E4: [[f64; 3]; 1] = [[
        1.073_004_285_378_039_4e-1,
        4.800_166_972_571_668e-7,
        8.926_990_914_454_962e-1,
    ]];

    fn radau(rtol: f64, atol: f64) -> Radau {
        Radau {
            options: RadauOptions {
                tolerances: Tolerances {
                    rtol,
                    atol: vec![atol],
                },
                ..Default::default()
            },
        }
    }

    #[test]
    fn oscillator_error_follows_the_tolerance() {
        // 1.6 periods of ω = 10. With RADAU5's transformation the steps scale as
        // rtol'^(1/4) ∝ rtol^(1/6) and the global error of the order-5 method as rtol^(5/6):
        // measured 0.09, 0.3, 0.3 and 0.7 times rtol^(5/6) for rtol = 1e-4 … 1e-10.
        let w = 10.0;
        let t: Vec<f64> = (0..=20).map(|k| 0.05 * k as f64).collect();
        let mut last = f64::INFINITY;
        for rtol in [1e-4, 1e-6, 1e-8, 1e-10] {
            let (traj, stats) = radau(rtol, rtol)
                .integrate(&mut Oscillator(w), 0.0, &[1.0, 0.0], &t, &mut |_| {})
                .expect("integrates");
            let err = traj
                .t
                .iter()
                .zip(&traj.y)
                .map(|(&s, y)| {
                    (y[0] - (w * s).cos())
                        .abs()
                        .max((y[1] + w * (w * s).sin()).abs() / w)
                })
                .fold(0.0, f64::max);
            eprintln!("rtol {rtol:.0e}: max error {err:.2e}, {stats:?}");
            assert!(
                err < rtol.powf(5.0 / 6.0),
                "rtol {rtol:.0e}: error {err:.2e}"
            );
            assert!(err < last);
            last = err;
        }
    }

    #[test]
    fn restarts_on_short_windows_reach_every_end() {
        // Windows [0.005 k, 0.005 (k + 1)] computed as multiples of 0.005: their lengths differ
        // from 0.005 by rounding, which once left a last step of 5e-16 s that was "too small".
        let w = 1000.0;
        let mut y = vec![1.0, 0.0];
        for k in 0..200 {
            let t = [0.005 * k as f64, 0.005 * (k + 1) as f64];
            let (traj, _) = radau(1e-5, 1e-5)
                .integrate(&mut Oscillator(w), t[0], &y, &t, &mut |_| {})
                .unwrap_or_else(|e| panic!("window {k}: {e}"));
            y.clone_from(traj.y.last().unwrap());
        }
        assert!((y[0] - (w * 1.0_f64).cos()).abs() < 1e-2, "{y:?}");
    }

    #[test]
    fn converges_at_fifth_order_with_a_fixed_step() {
        // Loose tolerances and max_step = first_step = h: every step is h (error estimate far below
        // one); a tight Newton tolerance with enough iterations keeps the iteration error out.
        let errors: Vec<f64> = [0.25, 0.125, 0.0625]
            .iter()
            .map(|&h| {
                let r = Radau {
                    options: RadauOptions {
                        tolerances: Tolerances {
                            rtol: 1.0,
                            atol: vec![1.0],
                        },
                        first_step: Some(h),
                        max_step: h,
                        max_newton_iterations: 30,
                        newton_tolerance: Some(1e-13),
                        ..Default::default()
                    },
                };
                let (traj, stats) = r
                    .integrate(&mut Riccati, 0.0, &[1.0], &[2.0], &mut |_| {})
                    .expect("integrates");
                assert_eq!(stats.steps, (2.0 / h) as usize);
                assert_eq!(stats.rejected_steps, 0);
                (traj.y[0][0] - 1.0 / 5.0).abs()
            })
            .collect();
        eprintln!("fixed-step errors {errors:?}");
        for e in errors.windows(2) {
            let order = (e[0] / e[1]).log2();
            // Radau IIA with 3 stages: order 2s − 1 = 5 at the grid points.
            assert!((4.6..5.6).contains(&order), "order {order}");
        }
    }

    #[test]
    fn dense_output_is_accurate_between_steps() {
        // Output every 1e-3 s while the steps are ~0.05 s: the collocation polynomial (order 3
        // inside the step) carries the error between the grid points.
        let t: Vec<f64> = (0..=1000).map(|k| 1e-3 * k as f64).collect();
        let (traj, stats) = radau(1e-8, 1e-8)
            .integrate(&mut Oscillator(10.0), 0.0, &[1.0, 0.0], &t, &mut |_| {})
            .expect("integrates");
        assert!(stats.steps < 200, "{stats:?}");
        assert_eq!(traj.t, t);
        let err = t
            .iter()
            .zip(&traj.y)
            .map(|(&s, y)| (y[0] - (10.0 * s).cos()).abs())
            .fold(0.0, f64::max);
        eprintln!("dense output error {err:.2e} with {} steps", stats.steps);
        assert!(err < 1e-6, "{err:.2e}");
    }

    #[test]
    fn van_der_pol_and_robertson_match_the_scipy_references() {
        // tests/data/stiff_reference (SciPy Radau and LSODA at rtol 1e-12, agreeing to 1e-10).
        let (traj, stats) = radau(1e-8, 1e-8)
            .integrate(
                &mut VanDerPol(1e-6),
                0.0,
                &[2.0, 0.0],
                &[1.0, 2.0],
                &mut |_| {},
            )
            .expect("integrates");
        let reference = [VDPOL_T2_Y1, VDPOL_T2_Y2];
        let err = (0..2)
            .map(|i| (traj.y[1][i] - reference[i]).abs() / reference[i].abs())
            .fold(0.0, f64::max);
        eprintln!("van der Pol ε = 1e-6, rtol 1e-8: relative error {err:.2e}, {stats:?}");
        // Global error of the order of rtol (the solution passes through two fast transitions).
        assert!(err < 1e-6, "{err:.2e}");
        assert!(stats.steps < 2000, "{stats:?}");

        let (traj, stats) = Radau {
            options: RadauOptions {
                tolerances: Tolerances {
                    rtol: 1e-8,
                    atol: vec![1e-12, 1e-16, 1e-12],
                },
                ..Default::default()
            },
        }
        .integrate(
            &mut Robertson,
            0.0,
            &[1.0, 0.0, 0.0],
            &[40.0, 1e4],
            &mut |_| {},
        )
        .expect("integrates");
        let reference = ROBER_T1E4;
        let err = (0..3)
            .map(|i| (traj.y[1][i] - reference[0][i]).abs() / reference[0][i].abs())
            .fold(0.0, f64::max);
        eprintln!("Robertson t = 1e4, rtol 1e-8: relative error {err:.2e}, {stats:?}");
        assert!(err < 1e-6, "{err:.2e}");
    }

    #[test]
    fn bad_options_are_input_errors_naming_the_field() {
        let cases: Vec<(RadauOptions, &str)> = vec![
            (
                RadauOptions {
                    tolerances: Tolerances {
                        rtol: 0.0,
                        atol: vec![1e-8],
                    },
                    ..Default::default()
                },
                "options.tolerances.rtol",
            ),
            (
                RadauOptions {
                    tolerances: Tolerances {
                        rtol: 1e-6,
                        atol: vec![-1e-8],
                    },
                    ..Default::default()
                },
                "options.tolerances.atol",
            ),
            (
                RadauOptions {
                    first_step: Some(0.0),
                    ..Default::default()
                },
                "options.first_step",
            ),
            (
                RadauOptions {
                    max_newton_iterations: 0,
                    ..Default::default()
                },
                "options.max_newton_iterations",
            ),
        ];
        for (options, field) in cases {
            let f = Radau { options }
                .integrate(&mut Oscillator(1.0), 0.0, &[1.0, 0.0], &[1.0], &mut |_| {})
                .expect_err("bad input");
            match f.error {
                SolveError::InvalidInput(e) => assert_eq!(e.field, field),
                e => panic!("{e:?}"),
            }
        }
    }

    #[test]
    fn a_step_budget_and_a_blow_up_stop_the_run_with_the_output_so_far() {
        let t: Vec<f64> = (0..=10).map(|k| 0.1 * k as f64).collect();
        let limited = Radau {
            options: RadauOptions {
                max_steps: 5,
                tolerances: Tolerances {
                    rtol: 1e-10,
                    atol: vec![1e-10],
                },
                ..Default::default()
            },
        }
        .integrate(&mut Oscillator(10.0), 0.0, &[1.0, 0.0], &t, &mut |_| {})
        .expect_err("budget of 5 steps");
        assert!(matches!(
            limited.error,
            SolveError::TooManySteps { steps: 5, .. }
        ));
        assert!(!limited.trajectory.t.is_empty() && limited.trajectory.t.len() < t.len());

        // y' = y², y(0) = 1 blows up at t = 1.
        struct BlowUp;
        impl OdeSystem for BlowUp {
            fn dim(&self) -> usize {
                1
            }
            fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
                dy[0] = y[0] * y[0];
            }
            fn jacobian(&mut self, _t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
                jac[(0, 0)] = 2.0 * y[0];
            }
        }
        let f = radau(1e-6, 1e-6)
            .integrate(&mut BlowUp, 0.0, &[1.0], &[0.5, 2.0], &mut |_| {})
            .expect_err("blows up");
        let time = match f.error {
            SolveError::StepSizeTooSmall { time, .. } | SolveError::NonFinite { time } => time,
            e => panic!("{e:?}"),
        };
        // The exact solution blows up at t = 1; the implicit stages may carry it slightly further.
        assert!((0.99..1.01).contains(&time), "stopped at {time}");
        assert_eq!(f.trajectory.t, vec![0.5]);
        assert!((f.trajectory.y[0][0] - 2.0).abs() < 1e-5);
    }
}
