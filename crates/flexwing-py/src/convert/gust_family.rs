//! [`GustFamilyOutcome`] into `GustFamilyResult` and its `GustFamilyRun`s: the columns of the
//! CLI's `gust_family.csv` and `gust_family_critical.csv`
//! (crates/flexwing-cli/src/render/gust_family.rs), as arrays over the gusts.

use flexwing::analysis::aero::gust_family::{GustFamilyOutcome, GustFamilyPlan, Peak, OUTPUTS};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::aero_statics::aerodynamics;
use super::statics::kind_name;
use super::status::{overall, set_status};
use crate::arrays::out1;

/// The gust family as the dict of `GustFamilyResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &GustFamilyPlan,
    outcome: &GustFamilyOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let statuses = outcome.statuses();
    let runs = (0..statuses.len())
        .map(|k| run(py, outcome, k))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("status", overall(statuses.iter().map(|(_, s)| *s)))?;
    d.set_item("outputs", OUTPUTS.to_vec())?;
    d.set_item("reference_velocity", plan.reference_velocity)?;
    d.set_item("alleviation", plan.alleviation)?;
    d.set_item("start", plan.start)?;
    d.set_item("penetration", plan.penetration.name())?;
    d.set_item("end_time", plan.response.structure.end_time)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.response.aero)?)?;
    Ok(d)
}

fn run<'py>(
    py: Python<'py>,
    outcome: &GustFamilyOutcome,
    k: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let (kind, status) = outcome.statuses()[k];
    let members = &outcome.members;
    d.set_item("label", kind.label())?;
    d.set_item("kind", kind_name(kind))?;
    d.set_item("modes", kind.modes())?;
    set_status(&d, status)?;
    d.set_item(
        "gradient",
        out1(py, members.iter().map(|m| m.gradient).collect()),
    )?;
    d.set_item(
        "design_velocity",
        out1(py, members.iter().map(|m| m.design_velocity).collect()),
    )?;
    for (j, name) in OUTPUTS.iter().enumerate() {
        let column = |f: fn(&Peak) -> f64| {
            out1(py, members.iter().map(|m| f(&m.runs[k].peaks[j])).collect())
        };
        d.set_item(format!("{name}_max"), column(|p| p.max))?;
        d.set_item(format!("{name}_max_time"), column(|p| p.max_time))?;
        d.set_item(format!("{name}_min"), column(|p| p.min))?;
        d.set_item(format!("{name}_min_time"), column(|p| p.min_time))?;
    }
    let steps: Vec<i64> = members.iter().map(|m| m.runs[k].steps as i64).collect();
    d.set_item("steps", numpy::PyArray1::from_vec(py, steps))?;
    d.set_item(
        "member_status",
        members
            .iter()
            .map(|m| m.runs[k].status.word())
            .collect::<Vec<_>>(),
    )?;
    d.set_item("wall_time_s", outcome.wall_time_s(k))?;
    let critical = PyDict::new(py);
    for (j, name) in OUTPUTS.iter().enumerate() {
        let Some(m) = outcome.critical(k, j) else {
            critical.set_item(*name, py.None())?;
            continue;
        };
        let (peak, time) = m.runs[k].peaks[j].extreme();
        let c = PyDict::new(py);
        c.set_item("gradient", m.gradient)?;
        c.set_item("design_velocity", m.design_velocity)?;
        c.set_item("peak", peak)?;
        c.set_item("time", time)?;
        critical.set_item(*name, c)?;
    }
    d.set_item("critical", critical)?;
    Ok(d)
}
