//! Errors across the boundary. Every error of the library and of the case crate becomes an
//! exception of the tree defined in `python/flexwing/_errors.py` (`FlexwingError` and its
//! subclasses, defined in Python so that they can also be `ValueError`s or `TypeError`s and
//! pickle with their attributes), carrying its data as attributes. Every call into the library
//! runs under [`guard`], which turns a Rust panic into `InternalError`: no `PanicException`
//! (which is not an `Exception`) reaches Python.

use std::panic::{catch_unwind, AssertUnwindSafe};

use flexwing::{InputError, SolveError};
use flexwing_case::CaseError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pyo3::IntoPyObjectExt;

use crate::convert::status::described;

/// An instance of `flexwing._errors.{class}` with `message` and the attributes of `attributes`.
fn exception(
    py: Python<'_>,
    class: &str,
    message: &str,
    attributes: &[(&str, Py<PyAny>)],
) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let module = py.import("flexwing._errors")?;
        let kwargs = PyDict::new(py);
        for (k, v) in attributes {
            kwargs.set_item(k, v)?;
        }
        let instance = module.getattr(class)?.call((message,), Some(&kwargs))?;
        Ok(PyErr::from_value(instance))
    };
    build().unwrap_or_else(|e| e)
}

fn obj<'py, T: IntoPyObjectExt<'py>>(py: Python<'py>, v: T) -> Py<PyAny> {
    v.into_py_any(py).unwrap_or_else(|_| py.None())
}

/// `InputError` (a `ValueError`) for the value `field`.
pub fn input(py: Python<'_>, field: &str, reason: &str) -> PyErr {
    exception(
        py,
        "InputError",
        &format!("{field}: {reason}"),
        &[("field", obj(py, field)), ("reason", obj(py, reason))],
    )
}

/// `ArgumentTypeError` (a `TypeError`) for the argument `field`.
pub fn argument_type(py: Python<'_>, field: &str, reason: &str) -> PyErr {
    exception(
        py,
        "ArgumentTypeError",
        &format!("{field}: {reason}"),
        &[("field", obj(py, field)), ("reason", obj(py, reason))],
    )
}

/// The library's `InputError`, with its field under the caller's name.
pub fn library_input(py: Python<'_>, e: &InputError) -> PyErr {
    input(py, &e.field, &e.reason)
}

/// `CaseFileError` with the case error's file, line, column and key.
pub fn case(py: Python<'_>, e: &CaseError) -> PyErr {
    exception(
        py,
        "CaseFileError",
        &e.to_string(),
        &[
            ("file", obj(py, e.file.clone())),
            ("line", obj(py, e.line)),
            ("column", obj(py, e.column)),
            ("key", obj(py, e.key.clone())),
            ("field", obj(py, e.key.clone())),
            ("reason", obj(py, e.reason.clone())),
        ],
    )
}

/// `SolverError` for a solver that failed before any model ran (or a stop of `model`), with
/// `stop` as data and the partial `result`.
pub fn solver(
    py: Python<'_>,
    message: &str,
    model: Option<&str>,
    stop: Option<Py<PyAny>>,
    result: Option<Py<PyAny>>,
) -> PyErr {
    exception(
        py,
        "SolverError",
        message,
        &[
            ("model", obj(py, model)),
            ("stop", stop.unwrap_or_else(|| py.None())),
            ("result", result.unwrap_or_else(|| py.None())),
        ],
    )
}

/// `SolverError` for a solver error outside any model's run.
pub fn solve(py: Python<'_>, e: &SolveError) -> PyErr {
    let stop = described(py, e).ok().map(|d| d.into_any().unbind());
    solver(py, &e.to_string(), None, stop, None)
}

/// Any error of the library.
pub fn library(py: Python<'_>, e: &flexwing::Error) -> PyErr {
    match e {
        flexwing::Error::Input(e) => library_input(py, e),
        flexwing::Error::Solve(e) => solve(py, e),
        other => exception(py, "FlexwingError", &other.to_string(), &[]),
    }
}

/// `InternalError`: a panic caught at the boundary.
pub fn internal(py: Python<'_>, what: &str) -> PyErr {
    exception(
        py,
        "InternalError",
        &format!(
            "internal error of flexwing (a bug; please report it with the input that caused \
             it): {what}"
        ),
        &[],
    )
}

/// A panic's message.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "a panic without a message".into())
}

/// Run `f` (a call into the library), turning a panic into `Err(message)`.
pub fn catch<T>(f: impl FnOnce() -> T) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).map_err(|p| panic_message(p.as_ref()))
}

/// Run `f` with the interpreter detached (other Python threads run meanwhile), turning a panic
/// into `InternalError`.
pub fn detached<T: Send>(py: Python<'_>, f: impl FnOnce() -> T + Send) -> PyResult<T> {
    py.detach(|| catch(f)).map_err(|m| internal(py, &m))
}

/// Run `f` attached (a short call: no need to let other threads run), turning a panic into
/// `InternalError`.
pub fn guard<T>(py: Python<'_>, f: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch(f).unwrap_or_else(|m| Err(internal(py, &m)))
}
