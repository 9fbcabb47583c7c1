//! [`AeroDynamicOutcome`] into `AeroDynamicResult` and its `AeroDynamicRun`s: the columns of the
//! CLI's `dynamic_aero.csv` and `dynamic_summary.csv`
//! (crates/flexwing-cli/src/render/aero_dynamic.rs), as arrays.

use flexwing::analysis::aero::response::{AeroDynamicOutcome, AeroDynamicPlan, AeroSample};
use flexwing::analysis::aero::response::{AeroDynamicRun, AeroStart};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::aero_statics::aerodynamics;
use super::dynamics::snapshots;
use super::statics::kind_name;
use super::status::{data, overall, set_status};
use crate::arrays::{out1, out_rows};

/// The aeroelastic response as the dict of `AeroDynamicResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &AeroDynamicPlan,
    outcome: &AeroDynamicOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let nodes = plan.structure.model.beam().nodes().len();
    let runs = outcome
        .runs
        .iter()
        .map(|r| run(py, r, nodes, outcome.ratio_to_first(r)))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    d.set_item("end_time", plan.structure.end_time)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.aero)?)?;
    d.set_item(
        "penetration",
        plan.flight.gust.as_ref().map(|g| g.penetration.name()),
    )?;
    d.set_item(
        "start",
        match plan.start {
            AeroStart::Equilibrium => "equilibrium",
            AeroStart::Rest => "rest",
        },
    )?;
    Ok(d)
}

fn run<'py>(
    py: Python<'py>,
    r: &AeroDynamicRun,
    nodes: usize,
    ratio_to_first: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("aero_states", r.aero_states)?;
    d.set_item("integrator", r.integrator.name())?;
    d.set_item("stats", super::dynamics::integrator_stats(py, &r.stats)?)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    d.set_item("ratio_to_first", ratio_to_first)?;
    set_status(&d, &r.status)?;
    let column = |f: fn(&AeroSample) -> f64| out1(py, r.samples.iter().map(f).collect());
    d.set_item("t", column(|s| s.t))?;
    d.set_item("tip_x", column(|s| s.tip_x))?;
    d.set_item("tip_y", column(|s| s.tip_y))?;
    d.set_item("tip_twist", column(|s| s.tip_twist))?;
    d.set_item("root_bending_moment", column(|s| s.root_bending_moment))?;
    d.set_item("lift", column(|s| s.lift))?;
    d.set_item("speed", column(|s| s.speed))?;
    d.set_item("kinetic", column(|s| s.kinetic))?;
    d.set_item("strain", column(|s| s.strain))?;
    d.set_item("total", column(|s| s.kinetic + s.strain))?;
    d.set_item("work", column(|s| s.work))?;
    d.set_item("dissipated", column(|s| s.dissipated))?;
    d.set_item("balance_error", column(|s| s.balance_error))?;
    let surfaces = r.hinge_moments.first().map_or(0, Vec::len);
    let hinges: Vec<&[f64]> = r.hinge_moments.iter().map(Vec::as_slice).collect();
    d.set_item("hinge_moments", out_rows(py, &hinges, surfaces))?;
    d.set_item(
        "energy_audit",
        r.energy_audit.as_ref().map(|e| data(py, e)).transpose()?,
    )?;
    d.set_item("snapshots", snapshots(py, &r.snapshots, nodes)?)?;
    d.set_item("max_tip_difference", r.max_tip_difference)?;
    Ok(d)
}
