//! Errors across the boundary. Every error of the library and of the case crate becomes an
//! exception of the tree defined in `python/flexwing/_errors.py` (`FlexwingError` and its
//! subclasses, defined in Python so that they can also be `ValueError`s or `TypeError`s and
//! pickle with their attributes), carrying its data as attributes.
//!
//! No panic crosses into Python: the body of every method and function of the extension runs
//! under [`guard`] (or [`detached`]), which turns a Rust panic into `InternalError` — the last
//! line of defence (`PanicException` is not an `Exception`, and a panic in a notebook or a
//! worker process must not take the session down). The causes are removed where they arise:
//! counts are checked before anything is allocated from them, and every conversion of Python
//! values is bounded in depth (`values.rs`).
//!
//! An exception raised by the caller's own code while an argument is converted (a `__float__`,
//! `__index__` or `__array__` method, a progress callback) is not ours to rename: a
//! `KeyboardInterrupt`, `MemoryError`, `RecursionError` or any class other than `TypeError`,
//! `ValueError` and `OverflowError` propagates as itself ([`foreign`]).

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

/// `ReentrancyError` (a `RuntimeError`): a call made from inside another flexwing call that
/// cannot be served (an object's method from a signal handler or callback run during one of its
/// own calls, analyses nested too deep in progress callbacks).
pub fn reentrancy(py: Python<'_>, field: &str, reason: &str) -> PyErr {
    exception(
        py,
        "ReentrancyError",
        &format!("{field}: {reason}"),
        &[("field", obj(py, field)), ("reason", obj(py, reason))],
    )
}

/// Whether `e`, raised by the caller's code while one of its values was converted, is to
/// propagate as itself rather than become an `ArgumentTypeError`/`InputError` of the argument:
/// anything but a `TypeError`, `ValueError` or `OverflowError` (a `KeyboardInterrupt`,
/// `MemoryError`, `RecursionError`, `SystemExit`, the caller's own exception classes).
pub fn foreign(py: Python<'_>, e: &PyErr) -> bool {
    use pyo3::exceptions::{PyOverflowError, PyTypeError, PyValueError};
    !(e.is_instance_of::<PyTypeError>(py)
        || e.is_instance_of::<PyValueError>(py)
        || e.is_instance_of::<PyOverflowError>(py))
}

/// `e` itself if it is [`foreign`], else the error `ours` makes of it (with `e` as its cause).
pub fn convert_error(py: Python<'_>, e: PyErr, ours: impl FnOnce(&PyErr) -> PyErr) -> PyErr {
    if foreign(py, &e) {
        return e;
    }
    let mine = ours(&e);
    mine.set_cause(py, Some(e));
    mine
}

/// Set `name` of the exception `e` to `value` when it can hold attributes (the partial result
/// of an interrupted call on its `KeyboardInterrupt`); an exception class with `__slots__`
/// is left as it is.
pub fn set_attribute(py: Python<'_>, e: &PyErr, name: &str, value: Py<PyAny>) {
    let _ = e.value(py).setattr(name, value);
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
