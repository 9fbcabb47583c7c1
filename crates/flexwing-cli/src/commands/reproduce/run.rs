//! Time integration for the reproduction: one driver over the library's integrators (those the
//! reproduction uses), with a
//! guard that stops a run whose energy explodes (the simplified model released from a large
//! deflection) instead of letting the integrator grind to a tiny step.

use flexwing::model::StructuralModel;
use flexwing::solve::integrate::{
    Dopri5, Dopri5Options, ImplicitMidpoint, IntegratorStats, MidpointOptions, Radau, RadauOptions,
    Tolerances, Trajectory,
};
use flexwing::solve::EquationsOfMotion;

/// An integrator and its accuracy setting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Method {
    /// Dormand–Prince 5(4), relative tolerance.
    Dopri5(f64),
    /// Implicit midpoint rule with a fixed step (s).
    Midpoint(f64),
    /// Radau IIA of order 5, relative tolerance and largest step (s).
    Radau(f64, f64),
}

impl Method {
    /// Description for the report.
    pub fn describe(&self) -> String {
        match self {
            Self::Dopri5(rtol) => format!("Dormand–Prince 5(4), rtol {rtol:.0e}"),
            Self::Midpoint(h) => format!("implicit midpoint, h = {h:.1e} s"),
            Self::Radau(rtol, h) if h.is_finite() => {
                format!("Radau IIA order 5, rtol {rtol:.0e}, steps ≤ {h} s")
            }
            Self::Radau(rtol, _) => format!("Radau IIA order 5, rtol {rtol:.0e}"),
        }
    }

    /// Short name for tables.
    pub fn short(&self) -> String {
        match self {
            Self::Dopri5(rtol) => format!("DOPRI5 {rtol:.0e}"),
            Self::Midpoint(h) => format!("midpoint h {h:.1e}"),
            Self::Radau(rtol, _) => format!("Radau {rtol:.0e}"),
        }
    }
}

/// Steps allowed per window of a guarded run: 5 000 steps for one output interval means steps
/// below 2e-4 of the output interval, a hundred times more than the full model needs at the
/// tightest tolerance used here, unless it blew up.
pub const WINDOW_STEPS: usize = 5_000;

/// A run: the output reached, the integrator's counters and, if it stopped early, why.
pub struct Run {
    pub trajectory: Trajectory,
    pub stats: IntegratorStats,
    pub stopped: Option<String>,
}

/// Integrate `eom` from `y0` at `t_out[0]` to the output times `t_out`. With `energy_limit`, the
/// run goes in windows of `window` output intervals and stops when the energy exceeds that
/// multiple of its initial value, or when one window needs more than [`WINDOW_STEPS`] steps (a
/// blown-up run). Tolerances: `rtol`, and an absolute tolerance on the coordinates (rad) with
/// consistent momenta (`EquationsOfMotion::state_atol`) of `rtol/100` (`rtol` for Radau, whose
/// tolerances are rescaled internally as in `RADAU5`).
pub fn integrate<M: StructuralModel>(
    eom: &mut EquationsOfMotion<'_, M>,
    y0: &[f64],
    t_out: &[f64],
    method: Method,
    energy_limit: Option<(f64, usize)>,
) -> Run {
    let (rtol, atol) = match method {
        Method::Dopri5(r) => (r, r * 1e-2),
        Method::Radau(r, _) => (r, r),
        Method::Midpoint(_) => (1e-6, 1e-8),
    };
    let tolerances = Tolerances {
        rtol,
        atol: eom.state_atol(atol),
    };
    let max_steps = if energy_limit.is_some() {
        WINDOW_STEPS
    } else {
        1_000_000
    };
    let energy = |eom: &mut EquationsOfMotion<'_, M>, y: &[f64]| {
        let (k, s) = eom.energies(y);
        k + s
    };
    // The initial energy only matters to a guarded run; unguarded runs are timed, and this
    // factorization would be timed with them.
    let h0 = if energy_limit.is_some() {
        energy(eom, y0)
    } else {
        f64::NAN
    };
    let window = energy_limit.map_or(t_out.len(), |(_, w)| w.max(1));
    let mut run = Run {
        trajectory: Trajectory::default(),
        stats: IntegratorStats::default(),
        stopped: None,
    };
    let mut y = y0.to_vec();
    let mut start = 0;
    while start + 1 < t_out.len() || (start == 0 && t_out.len() == 1) {
        let end = (start + window).min(t_out.len() - 1);
        let times = &t_out[start..=end];
        let t0 = times[0];
        let result = match method {
            Method::Dopri5(_) => Dopri5 {
                options: Dopri5Options {
                    tolerances: tolerances.clone(),
                    max_steps,
                    ..Default::default()
                },
            }
            .integrate(eom, t0, &y, times, &mut |_| {}),
            Method::Midpoint(h) => ImplicitMidpoint {
                options: MidpointOptions {
                    tolerances: tolerances.clone(),
                    step: Some(h),
                    max_steps,
                    ..Default::default()
                },
            }
            .integrate(eom, t0, &y, times, &mut |_| {}),
            Method::Radau(_, max_step) => Radau {
                options: RadauOptions {
                    tolerances: tolerances.clone(),
                    max_step,
                    max_steps,
                    ..Default::default()
                },
            }
            .integrate(eom, t0, &y, times, &mut |_| {}),
        };
        let (mut traj, stats, error) = match result {
            Ok((traj, stats)) => (traj, stats, None),
            Err(f) => (f.trajectory, f.stats, Some(f.error.to_string())),
        };
        run.stats += stats;
        // Each window repeats the previous window's last output as its first.
        let skip = usize::from(start > 0 && !traj.t.is_empty());
        if let Some(last) = traj.y.last() {
            y.clone_from(last);
        }
        run.trajectory.t.extend(traj.t.drain(skip..));
        run.trajectory.y.extend(traj.y.drain(skip..));
        if let Some(e) = error {
            run.stopped = Some(e);
            break;
        }
        if let Some((limit, _)) = energy_limit {
            let h = energy(eom, &y);
            if !(h <= limit * h0) {
                run.stopped = Some(format!(
                    "stopped at t = {} s: the energy grew to {:.3} times its initial value \
                     (a blown-up run; limit {limit})",
                    crate::output::short(t_out[end]),
                    h / h0
                ));
                break;
            }
        }
        if end + 1 >= t_out.len() {
            break;
        }
        start = end;
    }
    run
}
