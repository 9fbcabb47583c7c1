//! [`ModesOutcome`] into `ModesResult`.

use flexwing::analysis::modes::ModesOutcome;
use flexwing::model::FullModel;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{out1, out_rows};

/// The modes as the dict of `ModesResult`.
pub fn raw<'py>(
    py: Python<'py>,
    model: &FullModel,
    outcome: &ModesOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let modes = &outcome.modes;
    let column = |f: fn(&flexwing::analysis::modes::ModeResult) -> f64| {
        out1(py, modes.iter().map(f).collect())
    };
    let nodes = model.beam().nodes().len();
    d.set_item("omega", column(|m| m.omega))?;
    d.set_item("frequency_hz", column(|m| m.frequency_hz))?;
    d.set_item(
        "bending_energy_fraction",
        column(|m| m.bending_energy_fraction),
    )?;
    d.set_item("x", out1(py, model.beam().nodes().to_vec()))?;
    let rows = |f: fn(&flexwing::analysis::modes::ModeResult) -> &[f64]| {
        let r: Vec<&[f64]> = modes.iter().map(f).collect();
        out_rows(py, &r, nodes)
    };
    d.set_item("dx", rows(|m| &m.shape.dx))?;
    d.set_item("dy", rows(|m| &m.shape.dy))?;
    d.set_item("twist", rows(|m| &m.shape.twist))?;
    d.set_item("n_elements", model.n_elements())?;
    d.set_item("n_dofs", model.n_dofs())?;
    let mode_numbers = numpy::PyArray1::from_vec(py, modes.iter().map(|m| m.mode as i64).collect());
    d.set_item("mode", mode_numbers)?;
    Ok(d)
}
