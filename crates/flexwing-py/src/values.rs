//! Python values into the case crate's serde types: plain values first (NumPy arrays and
//! scalars into lists and numbers, tuples into lists), then the type's own `Deserialize` — so a
//! Python dict or keyword arguments take the case file's keys, defaults and checks, with
//! errors naming the key path (`beam.section.EI`, `loads[0].fy`, `damping.alpha`).
//! `case.rs`, `model.rs` and `equations.rs` read their arguments here.

use flexwing_case::CaseError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};
use pythonize::Depythonizer;
use serde::de::DeserializeOwned;

use crate::errors;

/// `obj` with NumPy arrays and scalars turned into lists and Python numbers, tuples into lists:
/// what the serde readers take.
pub fn plain_value<'py>(obj: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
    let py = obj.py();
    if let Ok(d) = obj.cast::<PyDict>() {
        let out = PyDict::new(py);
        for (k, v) in d.iter() {
            out.set_item(k, plain_value(&v)?)?;
        }
        return Ok(out.into_any());
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items = obj
            .try_iter()?
            .map(|v| v.and_then(|v| plain_value(&v)))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(PyList::new(py, items)?.into_any());
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(obj.clone());
    }
    if obj.hasattr("tolist")? && obj.hasattr("dtype")? {
        return plain_value(&obj.call_method0("tolist")?);
    }
    Ok(obj.clone())
}

/// `obj` read as the serde type `T`; an error is the `CaseError` of its key path with `prefix`
/// in front (`loads`: `loads[0].fy`; empty: the path alone), in the case file's words.
pub fn read<T: DeserializeOwned>(obj: &Bound<'_, PyAny>, prefix: &str) -> Result<T, CaseError> {
    let value = plain_value(obj).map_err(|e| CaseError::new(e.to_string()))?;
    let mut de = Depythonizer::from_object(&value);
    serde_path_to_error::deserialize::<_, T>(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let key = match (path.as_str(), prefix) {
            (".", "") => None,
            (".", p) => Some(p.to_string()),
            (path, "") => Some(path.to_string()),
            (path, p) if path.starts_with('[') => Some(format!("{p}{path}")),
            (path, p) => Some(format!("{p}.{path}")),
        };
        let reason = flexwing_case::one_line(&e.inner().to_string());
        CaseError {
            key,
            ..CaseError::new(reason)
        }
    })
}

/// [`read`], an error raised as `InputError` (`CaseFileError` with `case_file`) naming the key.
pub fn read_or_raise<T: DeserializeOwned>(
    obj: &Bound<'_, PyAny>,
    prefix: &str,
    case_file: bool,
) -> PyResult<T> {
    let py = obj.py();
    errors::guard(py, || {
        read(obj, prefix).map_err(|e| match (case_file, &e.key) {
            (false, Some(key)) => errors::input(py, key, &e.reason),
            _ => errors::case(py, &e),
        })
    })
}
