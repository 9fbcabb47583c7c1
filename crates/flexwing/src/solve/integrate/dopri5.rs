//! Dormand–Prince 5(4) with PI-free standard step control and 4th-order dense output.
//!
//! # References
//! Hairer, Nørsett & Wanner, *Solving Ordinary Differential Equations I*, 2nd ed., §II.4–II.6
//! (the coefficients and the continuous extension of `DOPRI5`).

use super::{
    check_output_times, error_norm, failure, outputs_at_start, scaled_rms, IntegrationResult,
    IntegratorStats, OdeSystem, Tolerances, Trajectory,
};
use crate::error::SolveError;

/// Options of [`Dopri5`].
#[derive(Debug, Clone, PartialEq)]
pub struct Dopri5Options {
    /// Error tolerances.
    pub tolerances: Tolerances,
    /// Largest step (s). Default infinite.
    pub max_step: f64,
    /// Budget of steps, accepted and rejected, before the run stops with
    /// [`SolveError::TooManySteps`] and the output so far. Default 1 000 000.
    pub max_steps: usize,
    /// First step (s); `None` picks one from the problem's scales.
    pub first_step: Option<f64>,
}

impl Default for Dopri5Options {
    fn default() -> Self {
        Self {
            tolerances: Tolerances::default(),
            max_step: f64::INFINITY,
            max_steps: 1_000_000,
            first_step: None,
        }
    }
}

/// The explicit adaptive Runge–Kutta method of Dormand and Prince, order 5 with an embedded
/// order-4 error estimate. For non-stiff problems, such as reduced models with few modes.
#[derive(Debug, Clone, Default)]
pub struct Dopri5 {
    /// Options.
    pub options: Dopri5Options,
}

const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order solution minus the embedded fourth-order one.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];
/// Weight of the previous error in the PI step-size controller.
const PI_BETA: f64 = 0.04;
/// Dense-output coefficients.
const D: [f64; 7] = [
    -12715105075.0 / 11282082432.0,
    0.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
];

impl Dopri5 {
    /// Integrate `system` from `(t0, y0)` and return the state at each of `t_out`
    /// (non-decreasing, not before `t0`). `progress` is called with the time after each step.
    ///
    /// # Errors
    /// Invalid output times or tolerances are [`crate::InputError`]s wrapped in the failure;
    /// a step size below round-off or a non-finite state stop the run with the output so far.
    pub fn integrate<S: OdeSystem>(
        &self,
        system: &mut S,
        t0: f64,
        y0: &[f64],
        t_out: &[f64],
        progress: &mut dyn FnMut(f64),
    ) -> IntegrationResult {
        let dim = system.dim();
        let opts = &self.options;
        let atol = opts.tolerances.atol(dim);
        let rtol = opts.tolerances.rtol;
        let mut stats = IntegratorStats::default();
        let mut traj = Trajectory::default();
        let fail = failure;
        if let Err(e) = check_output_times(t0, t_out)
            .and_then(|_| opts.tolerances.validate("options.tolerances", dim))
        {
            return fail(traj, stats, SolveError::from_input(e));
        }
        let t_end = t_out.last().copied().unwrap_or(t0);
        let mut k = vec![vec![0.0; dim]; 7];
        let mut y = y0.to_vec();
        let mut y_new = vec![0.0; dim];
        let mut err = vec![0.0; dim];
        let mut stage = vec![0.0; dim];
        let mut t = t0;
        system.rhs(t, &y, &mut k[0]);
        stats.rhs_evaluations += 1;
        let mut next_out = outputs_at_start(t0, y0, t_out, &mut traj);
        let mut h = match opts.first_step {
            Some(h) => h,
            None => initial_step(system, t, &y, &k[0], &atol, rtol, 5, &mut stats),
        }
        .min(opts.max_step)
        .min((t_end - t).max(0.0));
        let mut rejected_last = false;
        let mut err_old: f64 = 1e-4;
        while next_out < t_out.len() {
            if stats.steps + stats.rejected_steps >= opts.max_steps {
                let steps = stats.steps + stats.rejected_steps;
                return fail(traj, stats, SolveError::TooManySteps { time: t, steps });
            }
            if h < 10.0 * f64::EPSILON * t.abs().max(1.0) || !h.is_finite() {
                return fail(
                    traj,
                    stats,
                    SolveError::StepSizeTooSmall { time: t, step: h },
                );
            }
            h = h.min(t_end - t);
            for s in 1..7 {
                for i in 0..dim {
                    let mut v = y[i];
                    for j in 0..s {
                        v += h * A[s][j] * k[j][i];
                    }
                    stage[i] = v;
                }
                let (done, rest) = k.split_at_mut(s);
                system.rhs(t + C[s] * h, &stage, &mut rest[0]);
                let _ = done;
                if s == 6 {
                    y_new.copy_from_slice(&stage);
                }
            }
            stats.rhs_evaluations += 6;
            for i in 0..dim {
                err[i] = h * (0..7).map(|j| E[j] * k[j][i]).sum::<f64>();
            }
            let en = error_norm(&err, &y, &y_new, &atol, rtol);
            if !en.is_finite() {
                stats.rejected_steps += 1;
                h *= 0.25;
                rejected_last = true;
                if y_new.iter().any(|v| !v.is_finite()) && h < 1e-12 {
                    return fail(traj, stats, SolveError::NonFinite { time: t });
                }
                continue;
            }
            if en <= 1.0 {
                // Dense output on (t, t + h].
                let t_new = t + h;
                while next_out < t_out.len() && t_out[next_out] <= t_new {
                    let theta = (t_out[next_out] - t) / h;
                    let th1 = 1.0 - theta;
                    let mut yo = vec![0.0; dim];
                    for i in 0..dim {
                        let ydiff = y_new[i] - y[i];
                        let bspl = h * k[0][i] - ydiff;
                        let r4 = ydiff - h * k[6][i] - bspl;
                        let r5 = h * (0..7).map(|j| D[j] * k[j][i]).sum::<f64>();
                        yo[i] = y[i] + theta * (ydiff + th1 * (bspl + theta * (r4 + th1 * r5)));
                    }
                    traj.t.push(t_out[next_out]);
                    traj.y.push(yo);
                    next_out += 1;
                }
                t = t_new;
                y.copy_from_slice(&y_new);
                k.swap(0, 6); // first same as last
                stats.steps += 1;
                progress(t);
                if system.step_accepted(t, &y).is_break() {
                    return failure(traj, stats, SolveError::Halted { time: t });
                }
                // PI step control (Hairer, Nørsett & Wanner I, §IV.2, as in DOPRI5, β = 0.04):
                // the previous error damps the oscillation between acceptance and rejection that
                // a pure I controller shows when the step is limited by stability.
                let mut factor =
                    0.9 * en.max(1e-10).powf(-(0.2 - 0.75 * PI_BETA)) * err_old.powf(PI_BETA);
                factor = factor.clamp(0.2, 5.0);
                if rejected_last {
                    factor = factor.min(1.0);
                }
                err_old = en.max(1e-4);
                rejected_last = false;
                h = (h * factor).min(opts.max_step);
            } else {
                stats.rejected_steps += 1;
                rejected_last = true;
                h *= (0.9 * en.powf(-0.2)).max(0.2);
            }
        }
        Ok((traj, stats))
    }
}

/// Initial step from the scales of `y` and `f` (Hairer, Nørsett & Wanner I, §II.4).
#[allow(clippy::too_many_arguments)]
pub(crate) fn initial_step<S: OdeSystem>(
    system: &mut S,
    t: f64,
    y: &[f64],
    f0: &[f64],
    atol: &[f64],
    rtol: f64,
    order: i32,
    stats: &mut IntegratorStats,
) -> f64 {
    let dim = y.len();
    let sc: Vec<f64> = (0..dim).map(|i| atol[i] + rtol * y[i].abs()).collect();
    let norm = |v: &[f64]| scaled_rms(v, &sc);
    let (d0, d1) = (norm(y), norm(f0));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    let y1: Vec<f64> = (0..dim).map(|i| y[i] + h0 * f0[i]).collect();
    let mut f1 = vec![0.0; dim];
    system.rhs(t + h0, &y1, &mut f1);
    stats.rhs_evaluations += 1;
    let diff: Vec<f64> = (0..dim).map(|i| f1[i] - f0[i]).collect();
    let d2 = norm(&diff) / h0;
    let h1 = if d1.max(d2) <= 1e-15 {
        (h0 * 1e-3).max(1e-6)
    } else {
        (0.01 / d1.max(d2)).powf(1.0 / (order as f64 + 1.0))
    };
    (100.0 * h0).min(h1)
}
