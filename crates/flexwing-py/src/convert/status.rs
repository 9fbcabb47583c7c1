//! The library's outcome data as Python values: whatever the library serializes (`Status`,
//! `Stop`, `SolveError`, the counters, the energy audit, the notes) becomes dicts, lists and
//! numbers through `pythonize`, with the library's names — never restated field by field here.
//! A run's status is `status` (`"complete"`, `"suspect"`, `"stopped"`, `"interrupted"`), `stop`
//! (where and why, with its `reason`, values and `message`, or `None`) and `message`.

use std::fmt::Display;

use flexwing::analysis::Status;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use serde::Serialize;

use crate::errors;

/// `value` as Python data (dicts, lists, numbers, strings, `None`).
pub fn data<'py, T: Serialize + ?Sized>(py: Python<'py>, value: &T) -> PyResult<Bound<'py, PyAny>> {
    pythonize::pythonize(py, value)
        .map_err(|e| errors::internal(py, &format!("a result does not convert: {e}")))
}

/// `value` as a dict with its `message` (its one-line `Display`) beside its fields.
pub fn described<'py, T: Serialize + Display>(
    py: Python<'py>,
    value: &T,
) -> PyResult<Bound<'py, PyDict>> {
    let d = data(py, value)?.cast_into::<PyDict>()?;
    d.set_item("message", value.to_string())?;
    Ok(d)
}

/// `(status, stop, message)` of a run.
pub fn status_fields<'py>(
    py: Python<'py>,
    status: &Status,
) -> PyResult<(String, Option<Bound<'py, PyDict>>, Option<String>)> {
    let d = data(py, status)?.cast_into::<PyDict>()?;
    let word: String = d
        .get_item("status")?
        .map_or_else(|| Ok(status.word().to_string()), |w| w.extract())?;
    let stop = d
        .get_item("stop")?
        .filter(|s| !s.is_none())
        .map(|s| s.cast_into::<PyDict>())
        .transpose()?;
    Ok((word, stop, status.message()))
}

/// Set `status`, `stop` and `message` of a run's dict.
pub fn set_status(d: &Bound<'_, PyDict>, status: &Status) -> PyResult<()> {
    let (word, stop, message) = status_fields(d.py(), status)?;
    d.set_item("status", word)?;
    d.set_item("stop", stop)?;
    d.set_item("message", message)
}

/// The word of a whole analysis: the worst of its runs' ([`Status::worst`]).
pub fn overall<'a>(statuses: impl IntoIterator<Item = &'a Status>) -> &'static str {
    Status::worst(statuses)
}

/// The fields of `items` as arrays, one per field, in the order the library serializes them:
/// `{"iterations": array([…]), "residual_norm": array([…]), …}` (int64 for integer fields,
/// float64 otherwise; every field present, with no items too).
pub fn columns<'py, T: Serialize + Default>(
    py: Python<'py>,
    items: &[T],
) -> PyResult<Bound<'py, PyDict>> {
    let numpy = py.import("numpy")?;
    let template = data(py, &T::default())?.cast_into::<PyDict>()?;
    let rows = items
        .iter()
        .map(|x| data(py, x)?.cast_into::<PyDict>().map_err(PyErr::from))
        .collect::<PyResult<Vec<_>>>()?;
    let out = PyDict::new(py);
    for (key, value) in template.iter() {
        let dtype = if value.is_instance_of::<pyo3::types::PyInt>() {
            "int64"
        } else {
            "float64"
        };
        let column = rows
            .iter()
            .map(|r| {
                r.get_item(&key)
                    .map(|v| v.unwrap_or_else(|| py.None().into_bound(py)))
            })
            .collect::<PyResult<Vec<_>>>()?;
        let kwargs = PyDict::new(py);
        kwargs.set_item("dtype", dtype)?;
        out.set_item(
            &key,
            numpy.call_method("asarray", (column,), Some(&kwargs))?,
        )?;
    }
    Ok(out)
}
