//! [`StaticOutcome`] into `StaticResult` and its `StaticRun`s.

use flexwing::analysis::statics::{ModelRun, StaticOutcome, StaticPlan};
use flexwing::analysis::ModelKind;
use flexwing::solve::StaticStats;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::status::{solve_error_dict, status_fields};
use crate::arrays::{out1, out_rows};

/// `"full"`, `"simplified"` or `"reduced"`.
pub fn kind_name(kind: &ModelKind) -> &'static str {
    match kind {
        ModelKind::Full => "full",
        ModelKind::Simplified => "simplified",
        ModelKind::Reduced(_) => "reduced",
    }
}

/// The static outcome as the dict of `StaticResult`; `sweep` names the swept load in stop
/// messages.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &StaticPlan,
    outcome: &StaticOutcome,
    sweep: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| run(py, plan, r, sweep))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    let (modes, error) = match &outcome.loaded_modes {
        None => (None, None),
        Some(Ok(modes)) => {
            let m = PyDict::new(py);
            let column = |f: fn(&flexwing::analysis::statics::LoadedMode) -> f64| {
                out1(py, modes.iter().map(f).collect())
            };
            m.set_item(
                "mode",
                PyArray1::from_vec(py, modes.iter().map(|x| x.mode as i64).collect()),
            )?;
            m.set_item("omega", column(|x| x.omega))?;
            m.set_item("frequency_hz", column(|x| x.frequency_hz))?;
            m.set_item("unloaded_omega", column(|x| x.unloaded_omega))?;
            (Some(m), None)
        }
        Some(Err(e)) => (None, Some(solve_error_dict(py, e)?)),
    };
    d.set_item("loaded_modes", modes)?;
    d.set_item("loaded_modes_error", error)?;
    d.set_item(
        "status",
        if outcome.is_complete() {
            "complete"
        } else {
            "stopped"
        },
    )?;
    d.set_item("sweep_load", plan.sweep.as_ref().map(|s| s.load))?;
    Ok(d)
}

/// The solver counters of each point as a dict of arrays (the `stats` of a static run).
pub fn stats_dict<'py>(py: Python<'py>, stats: &[&StaticStats]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let counter = |f: fn(&StaticStats) -> usize| {
        PyArray1::from_vec(py, stats.iter().map(|s| f(s) as i64).collect())
    };
    d.set_item("load_steps", counter(|s| s.load_steps))?;
    d.set_item("rejected_steps", counter(|s| s.rejected_steps))?;
    d.set_item("limited_steps", counter(|s| s.limited_steps))?;
    d.set_item("unstable_steps", counter(|s| s.unstable_steps))?;
    d.set_item("iterations", counter(|s| s.iterations))?;
    d.set_item("residual_evaluations", counter(|s| s.residual_evaluations))?;
    d.set_item("factorizations", counter(|s| s.factorizations))?;
    d.set_item("stability_checks", counter(|s| s.stability_checks))?;
    d.set_item(
        "residual_norm",
        out1(py, stats.iter().map(|s| s.residual_norm).collect()),
    )?;
    Ok(d)
}

fn run<'py>(
    py: Python<'py>,
    plan: &StaticPlan,
    r: &ModelRun,
    sweep: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    let (status, stop, message) = status_fields(py, &r.status, sweep)?;
    d.set_item("status", status)?;
    d.set_item("stop", stop)?;
    d.set_item("message", message)?;
    let points = &r.points;
    let column = |f: &dyn Fn(&flexwing::analysis::statics::PointResult) -> f64| {
        out1(py, points.iter().map(f).collect())
    };
    d.set_item("scale", column(&|p| p.scale))?;
    let n_loads = plan.loads.len();
    let scales: Vec<&[f64]> = points.iter().map(|p| p.scales.as_slice()).collect();
    d.set_item("scales", out_rows(py, &scales, n_loads))?;
    d.set_item("tip_x", column(&|p| p.tip().0))?;
    d.set_item("tip_y", column(&|p| p.tip().1))?;
    d.set_item("tip_twist", column(&|p| p.tip().2))?;
    let nodes = plan.model.beam().nodes().len();
    let rows = |f: fn(&flexwing::analysis::statics::PointResult) -> &[f64], width: usize| {
        let r: Vec<&[f64]> = points.iter().map(f).collect();
        out_rows(py, &r, width)
    };
    d.set_item("x", rows(|p| &p.shape.x, nodes))?;
    d.set_item("y", rows(|p| &p.shape.y, nodes))?;
    d.set_item("twist", rows(|p| &p.shape.twist, nodes))?;
    d.set_item("q", rows(|p| &p.q, plan.model.n_dofs()))?;
    let differences: Option<Vec<f64>> = points.iter().map(|p| p.tip_difference).collect();
    d.set_item(
        "tip_difference",
        differences
            .filter(|_| r.kind.modes().is_some())
            .map(|v| out1(py, v)),
    )?;
    let stats: Vec<&StaticStats> = points.iter().map(|p| &p.stats).collect();
    let stats = stats_dict(py, &stats)?;
    d.set_item("stats", stats)?;
    Ok(d)
}
