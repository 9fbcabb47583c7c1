//! Integration with an energy guard: a run that blows up (the simplified model released from a
//! large deflection, whose equations do not conserve energy) is stopped when its energy exceeds
//! a multiple of the initial one, instead of letting the integrator grind down to a tiny step.

use crate::analysis::Stop;
use crate::model::StructuralModel;
use crate::solve::integrate::{integrate, IntegratorSettings, IntegratorStats, Method, Trajectory};
use crate::solve::EquationsOfMotion;

/// When a guarded run stops: the run goes in windows of `window` output intervals, each with a
/// budget of `window_steps` steps, and stops after a window whose final energy exceeds `limit`
/// times the initial energy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnergyGuard {
    /// Largest energy over the initial energy.
    pub limit: f64,
    /// Output intervals per window (at least 1).
    pub window: usize,
    /// Steps allowed per window, accepted and rejected.
    pub window_steps: usize,
}

/// A run of [`integrate_guarded`]: the output reached, the integrator's counters and, if it
/// stopped early, why.
#[derive(Debug, Clone)]
pub struct GuardedRun {
    /// States at the output times reached.
    pub trajectory: Trajectory,
    /// Counters, summed over the windows.
    pub stats: IntegratorStats,
    /// Why the run stopped early ([`Stop::Integration`] or [`Stop::EnergyLimit`]).
    pub stop: Option<Stop>,
}

/// Integrate `eom` from `y0` at `t_out[0]` to the output times `t_out` with `method` and
/// `settings`. Without a guard this is one call of [`integrate`]; with one, the run goes in
/// windows and stops as [`EnergyGuard`] says.
pub fn integrate_guarded<M: StructuralModel>(
    eom: &mut EquationsOfMotion<'_, M>,
    y0: &[f64],
    t_out: &[f64],
    method: Method,
    settings: &IntegratorSettings,
    guard: Option<&EnergyGuard>,
) -> GuardedRun {
    let settings = match guard {
        Some(g) => IntegratorSettings {
            max_steps: g.window_steps,
            ..settings.clone()
        },
        None => settings.clone(),
    };
    let energy = |eom: &mut EquationsOfMotion<'_, M>, y: &[f64]| {
        let (k, s) = eom.energies(y);
        k + s
    };
    // The initial energy only matters to a guarded run; unguarded runs are often timed, and
    // this factorization would be timed with them.
    let h0 = if guard.is_some() {
        energy(eom, y0)
    } else {
        f64::NAN
    };
    let window = guard.map_or(t_out.len(), |g| g.window.max(1));
    let mut run = GuardedRun {
        trajectory: Trajectory::default(),
        stats: IntegratorStats::default(),
        stop: None,
    };
    let mut y = y0.to_vec();
    let mut start = 0;
    while start + 1 < t_out.len() || (start == 0 && t_out.len() == 1) {
        let end = (start + window).min(t_out.len() - 1);
        let times = &t_out[start..=end];
        let result = integrate(method, &settings, eom, times[0], &y, times, &mut |_| {});
        let (mut traj, stats, error) = match result {
            Ok((traj, stats)) => (traj, stats, None),
            Err(f) => (f.trajectory, f.stats, Some(f.error)),
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
            run.stop = Some(Stop::Integration(e));
            break;
        }
        if let Some(g) = guard {
            let h = energy(eom, &y);
            if !(h <= g.limit * h0) {
                run.stop = Some(Stop::EnergyLimit {
                    time: t_out[end],
                    ratio: h / h0,
                    limit: g.limit,
                });
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
