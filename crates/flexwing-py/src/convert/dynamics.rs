//! [`DynamicOutcome`] into `DynamicResult` and its `DynamicRun`s.

use flexwing::analysis::dynamics::{DynamicOutcome, DynamicPlan, DynamicRun, Sample, Snapshot};
use flexwing::solve::integrate::IntegratorStats;
use flexwing::solve::Gyroscopic;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::statics::kind_name;
use super::status::{data, overall, set_status};
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

/// An integrator's counters (`DynamicRun.stats`, `AeroDynamicRun.stats`, `Stepper.stats`):
/// the library's `IntegratorStats`, field for field.
pub fn integrator_stats<'py>(py: Python<'py>, s: &IntegratorStats) -> PyResult<Bound<'py, PyDict>> {
    Ok(data(py, s)?.cast_into::<PyDict>()?)
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

fn run<'py>(py: Python<'py>, plan: &DynamicPlan, r: &DynamicRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("integrator", r.integrator.name())?;
    d.set_item("gyroscopic", gyroscopic_name(r.gyroscopic))?;
    d.set_item("stats", integrator_stats(py, &r.stats)?)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    set_status(&d, &r.status)?;
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
        r.energy_audit.as_ref().map(|e| data(py, e)).transpose()?,
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
    d.set_item("notes", notes(py, &r.notes)?)?;
    Ok(d)
}

/// The notes of a run: one dict per note, its `kind`, values and `message`.
pub fn notes<'py>(
    py: Python<'py>,
    notes: &[flexwing::analysis::Note],
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    notes
        .iter()
        .map(|n| super::status::described(py, n))
        .collect()
}
