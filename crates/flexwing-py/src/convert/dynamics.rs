//! [`DynamicOutcome`] into `DynamicResult` and its `DynamicRun`s.

use flexwing::analysis::dynamics::{DynamicOutcome, DynamicPlan, ModelRun, Sample, Snapshot};
use flexwing::solve::integrate::IntegratorStats;
use flexwing::solve::{EnergyBalance, Gyroscopic};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::statics::kind_name;
use super::status::{overall, status_fields};
use crate::arrays::{out1, out_rows};

/// The case-file name of a way to get the gyroscopic term.
pub fn gyroscopic_name(g: Gyroscopic) -> &'static str {
    match g {
        Gyroscopic::Exact => "exact",
        Gyroscopic::FiniteDifference { .. } => "finite-difference",
        Gyroscopic::Neglected => "neglected",
    }
}

/// The dynamic outcome as the dict of `DynamicResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &DynamicPlan,
    outcome: &DynamicOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| run(py, plan, r))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    d.set_item("end_time", plan.end_time)?;
    Ok(d)
}

/// An integrator's counters (`DynamicRun.stats`, `AeroDynamicRun.stats`).
pub fn integrator_stats<'py>(py: Python<'py>, s: &IntegratorStats) -> PyResult<Bound<'py, PyDict>> {
    let stats = PyDict::new(py);
    stats.set_item("steps", s.steps)?;
    stats.set_item("rejected_steps", s.rejected_steps)?;
    stats.set_item("newton_failures", s.newton_failures)?;
    stats.set_item("rhs_evaluations", s.rhs_evaluations)?;
    stats.set_item("jacobian_evaluations", s.jacobian_evaluations)?;
    stats.set_item("factorizations", s.factorizations)?;
    stats.set_item("newton_iterations", s.newton_iterations)?;
    Ok(stats)
}

/// What the energy audit found (the CLI's `energy_audit`, docs/validation.md "Energy audit"):
/// `balanced` (whether the model has an energy balance: all but the simplified model),
/// `max_error` and `max_error_time` (s), `limit` (`None` without a balance), `exceeded_time`
/// (s, the first time the error passed `limit`), `runaway_limit`, `runaway_time` (s), and
/// `reference_energy` (J, the largest energy held or given).
pub fn audit<'py>(py: Python<'py>, e: &EnergyBalance) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("balanced", e.limits.balance.is_some())?;
    d.set_item("max_error", e.max_error)?;
    d.set_item("max_error_time", e.max_error_time)?;
    d.set_item("limit", e.limits.balance)?;
    d.set_item("exceeded_time", e.exceeded_at)?;
    d.set_item("runaway_limit", e.limits.runaway)?;
    d.set_item("runaway_time", e.runaway_at)?;
    d.set_item("reference_energy", e.reference)?;
    Ok(d)
}

/// The snapshots as a dict: `index` and `t` `(S,)`, `x`, `y`, `twist` `(S, nodes)`.
pub fn snapshots<'py>(
    py: Python<'py>,
    shots: &[Snapshot],
    nodes: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item(
        "index",
        PyArray1::from_vec(py, shots.iter().map(|s| s.index as i64).collect()),
    )?;
    d.set_item("t", out1(py, shots.iter().map(|s| s.t).collect()))?;
    let rows = |f: fn(&Snapshot) -> &[f64]| {
        let r: Vec<&[f64]> = shots.iter().map(f).collect();
        out_rows(py, &r, nodes)
    };
    d.set_item("x", rows(|s| &s.shape.x))?;
    d.set_item("y", rows(|s| &s.shape.y))?;
    d.set_item("twist", rows(|s| &s.shape.twist))?;
    Ok(d)
}

fn run<'py>(py: Python<'py>, plan: &DynamicPlan, r: &ModelRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("integrator", r.integrator.name())?;
    d.set_item("gyroscopic", gyroscopic_name(r.gyroscopic))?;
    d.set_item("stats", integrator_stats(py, &r.stats)?)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    let (status, stop, message) = status_fields(py, &r.status, None)?;
    d.set_item("status", status)?;
    d.set_item("stop", stop)?;
    d.set_item("message", message)?;
    let column = |f: fn(&Sample) -> f64| out1(py, r.samples.iter().map(f).collect());
    d.set_item("t", column(|s| s.t))?;
    d.set_item("tip_x", column(|s| s.tip_x))?;
    d.set_item("tip_y", column(|s| s.tip_y))?;
    d.set_item("tip_twist", column(|s| s.tip_twist))?;
    d.set_item("kinetic", column(|s| s.kinetic))?;
    d.set_item("strain", column(|s| s.strain))?;
    d.set_item("total", column(Sample::total))?;
    d.set_item("work", column(|s| s.work))?;
    d.set_item("dissipated", column(|s| s.dissipated))?;
    d.set_item("balance_error", column(|s| s.balance_error))?;
    d.set_item(
        "energy_audit",
        r.energy.as_ref().map(|e| audit(py, e)).transpose()?,
    )?;
    let nodes = plan.model.beam().nodes().len();
    d.set_item("snapshots", snapshots(py, &r.snapshots, nodes)?)?;
    let comparison = match &r.comparison {
        None => None,
        Some(c) => {
            let m = PyDict::new(py);
            m.set_item("max_tip_difference", c.max_tip_difference)?;
            m.set_item("relative_x", c.relative_x)?;
            m.set_item("relative_y", c.relative_y)?;
            Some(m)
        }
    };
    d.set_item("comparison", comparison)?;
    Ok(d)
}
