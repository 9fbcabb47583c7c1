//! [`TurbulenceOutcome`] into `TurbulenceResult` and its `TurbulenceRun`s: the columns of the
//! CLI's `turbulence_rms.csv` and `turbulence_psd.csv`
//! (crates/flexwing-cli/src/render/turbulence.rs), as arrays over the frequencies and outputs.

use flexwing::analysis::aero::turbulence::{TurbulenceOutcome, TurbulencePlan};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::aero_statics::aerodynamics;
use super::statics::kind_name;
use super::status::{overall, set_status};
use crate::arrays::{out1, out2};

/// The turbulence analysis as the dict of `TurbulenceResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &TurbulencePlan,
    outcome: &TurbulenceOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| {
            let d = PyDict::new(py);
            d.set_item("label", r.linear.kind.label())?;
            d.set_item("kind", kind_name(&r.linear.kind))?;
            d.set_item("modes", r.linear.kind.modes())?;
            set_status(&d, &r.status)?;
            let outputs = r.linear.model.as_ref().map_or(&[][..], |m| &m.outputs[..]);
            d.set_item(
                "outputs",
                outputs.iter().map(|s| s.name.clone()).collect::<Vec<_>>(),
            )?;
            d.set_item(
                "output_units",
                outputs
                    .iter()
                    .map(|s| s.unit.to_string())
                    .collect::<Vec<_>>(),
            )?;
            let s = r.spectra.as_ref();
            let column =
                |f: &dyn Fn(&flexwing::solve::aeroelastic::turbulence::GustSpectra) -> Vec<f64>| {
                    out1(py, s.map_or_else(Vec::new, f))
                };
            d.set_item("frequency", column(&|s| s.frequencies.clone()))?;
            d.set_item("gust_psd", column(&|s| s.gust_psd.clone()))?;
            // (frequencies, outputs), row-major.
            let rows = s.map_or(0, |s| s.frequencies.len());
            let psd: Vec<f64> = s.map_or_else(Vec::new, |s| {
                (0..rows)
                    .flat_map(|i| s.psd.iter().map(move |p| p[i]))
                    .collect()
            });
            d.set_item("psd", out2(py, rows, outputs.len(), psd))?;
            d.set_item("rms", column(&|s| s.rms.clone()))?;
            d.set_item("variance_error", column(&|s| s.variance_error.clone()))?;
            d.set_item(
                "tail_variance",
                column(&|s| s.tail.iter().map(|t| t.unwrap_or(f64::NAN)).collect()),
            )?;
            d.set_item("tail_slope", column(&|s| s.tail_slope.clone()))?;
            d.set_item(
                "diverges",
                s.map_or_else(Vec::new, |s| s.tail.iter().map(Option::is_none).collect()),
            )?;
            d.set_item("gust_rms", s.map(|s| s.gust_rms))?;
            d.set_item("wall_time_s", r.wall_time_s)?;
            d.set_item("notes", super::dynamics::notes(py, &r.notes)?)?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    d.set_item("spectrum", outcome.turbulence.spectrum.name())?;
    d.set_item("intensity", outcome.turbulence.intensity)?;
    d.set_item("scale_length", outcome.turbulence.scale_length)?;
    d.set_item("speed", outcome.speed)?;
    d.set_item("frequencies", outcome.grid.points)?;
    d.set_item("min_frequency", outcome.grid.min_frequency)?;
    d.set_item("max_frequency", outcome.grid.max_frequency)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.linearize.aero)?)?;
    Ok(d)
}
