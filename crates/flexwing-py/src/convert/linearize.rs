//! [`LinearizeOutcome`] into `LinearizeResult` and its `LinearModel`s (`_linear.py`): per model
//! `A, B, C, D`, the names and units of the states, inputs and outputs, the equilibrium's
//! values and the poles, as the CLI's `linear_LABEL.mat` (crates/flexwing-cli/src/render/
//! linearize.rs).

use flexwing::analysis::aero::linearize::{LinearizeOutcome, LinearizePlan};
use flexwing::solve::aeroelastic::Signal;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::aero_statics::aerodynamics;
use super::statics::kind_name;
use super::status::{overall, set_status};
use crate::arrays::{out1, out_matrix};

fn names(signals: &[Signal]) -> Vec<String> {
    signals.iter().map(|s| s.name.clone()).collect()
}

fn units(signals: &[Signal]) -> Vec<&'static str> {
    signals.iter().map(|s| s.unit).collect()
}

/// The linearization outcome as the dict of `LinearizeResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &LinearizePlan,
    outcome: &LinearizeOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let numpy = py.import("numpy")?;
    let runs = outcome
        .runs
        .iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("label", r.kind.label())?;
            d.set_item("kind", kind_name(&r.kind))?;
            d.set_item("modes", r.kind.modes())?;
            d.set_item("dofs", r.dofs)?;
            d.set_item("aero_states", r.aero_states)?;
            d.set_item("wall_time_s", r.wall_time_s)?;
            set_status(&d, &r.status)?;
            d.set_item("notes", super::dynamics::notes(py, &r.notes)?)?;
            d.set_item("basis", plan.states.name())?;
            let m = r.model.as_ref();
            let matrix =
                |f: fn(&flexwing::solve::aeroelastic::StateSpace) -> &nalgebra::DMatrix<f64>| {
                    m.map(|m| out_matrix(py, f(m)))
                };
            d.set_item("A", matrix(|m| &m.a))?;
            d.set_item("B", matrix(|m| &m.b))?;
            d.set_item("C", matrix(|m| &m.c))?;
            d.set_item("D", matrix(|m| &m.d))?;
            d.set_item("state_names", m.map(|m| names(&m.states)))?;
            d.set_item("state_units", m.map(|m| units(&m.states)))?;
            d.set_item("input_names", m.map(|m| names(&m.inputs)))?;
            d.set_item("input_units", m.map(|m| units(&m.inputs)))?;
            d.set_item("output_names", m.map(|m| names(&m.outputs)))?;
            d.set_item("output_units", m.map(|m| units(&m.outputs)))?;
            d.set_item("x0", m.map(|m| out1(py, m.state_values.clone())))?;
            d.set_item("u0", m.map(|m| out1(py, m.input_values.clone())))?;
            d.set_item("y0", m.map(|m| out1(py, m.output_values.clone())))?;
            let re = out1(py, r.poles.iter().map(|p| p.re).collect());
            let im = out1(py, r.poles.iter().map(|p| p.im).collect());
            let i = pyo3::types::PyComplex::from_doubles(py, 0.0, 1.0);
            let poles = numpy
                .getattr("add")?
                .call1((re, numpy.getattr("multiply")?.call1((im, i))?))?;
            d.set_item("poles", poles)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    let d = PyDict::new(py);
    d.set_item("runs", runs)?;
    d.set_item("speed", plan.flight.speed)?;
    d.set_item("root_angle", plan.flight.root_angle)?;
    d.set_item("gravity", plan.flight.gravity)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.aero)?)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    Ok(d)
}
