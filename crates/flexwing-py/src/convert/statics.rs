//! [`StaticOutcome`] into `StaticResult` and its `StaticRun`s.

use flexwing::analysis::statics::{StaticOutcome, StaticPlan, StaticRun};
use flexwing::analysis::ModelKind;
use flexwing::solve::StaticStats;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::status::{columns, described, set_status};
use crate::arrays::{out1, out_rows};
use flexwing::analysis::Status;

/// `"full"`, `"simplified"` or `"reduced"`.
pub fn kind_name(kind: &ModelKind) -> &'static str {
    match kind {
        ModelKind::Full => "full",
        ModelKind::Simplified => "simplified",
        ModelKind::Reduced(_) => "reduced",
    }
}

/// The static outcome as the dict of `StaticResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &StaticPlan,
    outcome: &StaticOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| run(py, plan, r))
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
        Some(Err(e)) => (None, Some(described(py, e)?)),
    };
    d.set_item("loaded_modes", modes)?;
    d.set_item("loaded_modes_error", error)?;
    let worst = Status::worst(outcome.runs.iter().map(|r| &r.status));
    let loaded_failed = matches!(outcome.loaded_modes, Some(Err(_)));
    d.set_item(
        "status",
        if worst == "complete" && loaded_failed {
            "stopped"
        } else {
            worst
        },
    )?;
    d.set_item("sweep_load", plan.sweep.as_ref().map(|s| s.load))?;
    Ok(d)
}

/// The solver counters of each point as a dict of arrays (the `stats` of a static run).
pub fn stats_dict<'py>(py: Python<'py>, stats: &[StaticStats]) -> PyResult<Bound<'py, PyDict>> {
    columns(py, stats)
}

fn run<'py>(py: Python<'py>, plan: &StaticPlan, r: &StaticRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    set_status(&d, &r.status)?;
    let points = &r.points;
    let column = |f: &dyn Fn(&flexwing::analysis::statics::StaticPoint) -> f64| {
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
    let rows = |f: fn(&flexwing::analysis::statics::StaticPoint) -> &[f64], width: usize| {
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
    let stats: Vec<StaticStats> = points.iter().map(|p| p.stats).collect();
    d.set_item("stats", stats_dict(py, &stats)?)?;
    Ok(d)
}
