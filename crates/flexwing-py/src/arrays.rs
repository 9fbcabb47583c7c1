//! NumPy in and out. Input: any array-like of real numbers (a list, a float32 or integer array,
//! a C- or Fortran-ordered or strided view) is converted to float64 and **copied** element by
//! element, in logical order, into owned Rust vectors and matrices before any arithmetic: no
//! strided view reaches nalgebra (whose arithmetic on strided views writes out of bounds,
//! nalgebra issue #1616). Shapes, dtypes and values are checked, and every error names the
//! argument (`y`, `EI[3]`): `ArgumentTypeError` for a wrong type or dtype (complex, boolean,
//! strings, objects, masked arrays), `InputError` for a wrong shape or a non-finite value; an
//! exception the caller's own `__array__`, `__float__` or `__index__` raises propagates as
//! itself unless it is a `TypeError`, `ValueError` or `OverflowError`
//! ([`errors::foreign`]: a `KeyboardInterrupt` stays a `KeyboardInterrupt`). Masked arrays
//! are refused rather than read with their masked values. Output: new C-ordered float64
//! arrays that Python owns; [`finite1`] and [`finite_matrix`] refuse a non-finite output of a
//! model-level call (a state beyond the model's range) instead of returning it.

use nalgebra::DMatrix;
use numpy::ndarray::{Array2, ArrayViewD};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyFloat, PyInt, PyType};

use crate::errors;

/// The message of a refused masked array.
pub const MASKED: &str =
    "invalid type: a masked array (numpy.ma) is refused, as its masked values \
                          would be used: pass a.filled(value) or a.compressed()";

/// Whether `obj` is a NumPy masked array (`numpy.ma.MaskedArray`). Cheap for what arguments
/// usually are: an exact `numpy.ndarray`, float, int, list or tuple is not one; for anything
/// else `numpy.ma` is looked up only if it was imported (an object cannot be a masked array
/// otherwise).
pub fn is_masked(obj: &Bound<'_, PyAny>) -> PyResult<bool> {
    static NDARRAY: PyOnceLock<Py<PyType>> = PyOnceLock::new();
    let py = obj.py();
    let ndarray = NDARRAY.get_or_try_init(py, || -> PyResult<_> {
        Ok(py
            .import("numpy")?
            .getattr("ndarray")?
            .cast_into::<PyType>()?
            .unbind())
    })?;
    let t = obj.get_type();
    if t.is(ndarray.bind(py))
        || obj.is_exact_instance_of::<PyFloat>()
        || obj.is_exact_instance_of::<PyInt>()
        || obj.is_exact_instance_of::<pyo3::types::PyList>()
        || obj.is_exact_instance_of::<pyo3::types::PyTuple>()
    {
        return Ok(false);
    }
    let modules = py.import("sys")?.getattr("modules")?;
    let Some(ma) = modules.get_item("numpy.ma").ok().filter(|m| !m.is_none()) else {
        return Ok(false);
    };
    obj.is_instance(&ma.getattr("MaskedArray")?)
}

/// A float64 view of `obj`: the array itself if it already is one, else `numpy.asarray(obj)`
/// converted to float64 after checking that its dtype is real (floats, integers).
fn float64_array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let py = obj.py();
    if is_masked(obj)? {
        return Err(errors::argument_type(py, name, MASKED));
    }
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        return Ok(a.clone());
    }
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("asarray", (obj,)).map_err(|e| {
        errors::convert_error(py, e, |e| {
            errors::argument_type(
                py,
                name,
                &format!("must be an array of real numbers ({})", e.value(py)),
            )
        })
    })?;
    let dtype = array.getattr("dtype")?;
    let kind: String = dtype.getattr("kind")?.extract()?;
    if !matches!(kind.as_str(), "f" | "i" | "u") {
        let described: String = dtype.str()?.extract()?;
        return Err(errors::argument_type(
            py,
            name,
            &format!(
                "must be an array of real numbers (float or integer dtype), got dtype {described}"
            ),
        ));
    }
    let converted = array.call_method1("astype", (numpy.getattr("float64")?,))?;
    converted
        .cast_into::<PyArrayDyn<f64>>()
        .map_err(|_| errors::argument_type(py, name, "could not be converted to float64"))
}

/// Copy `view` in logical (row-major) order, checking that every value is finite; `index`
/// names an element for the error.
fn copy_finite(
    py: Python<'_>,
    view: &ArrayViewD<'_, f64>,
    name: &str,
    index: impl Fn(usize) -> String,
) -> PyResult<Vec<f64>> {
    let mut out = Vec::with_capacity(view.len());
    for (k, &v) in view.iter().enumerate() {
        if !v.is_finite() {
            return Err(errors::input(
                py,
                &format!("{name}{}", index(k)),
                &format!("must be finite, got {v}"),
            ));
        }
        out.push(v);
    }
    Ok(out)
}

/// A 1-D array of finite reals, copied; `len` checks its length.
pub fn vector(obj: &Bound<'_, PyAny>, name: &str, len: Option<usize>) -> PyResult<Vec<f64>> {
    let py = obj.py();
    if is_scalar(obj) {
        return Err(errors::input(
            py,
            name,
            &format!(
                "must be a 1-D array{}, got a scalar",
                len.map_or(String::new(), |n| format!(" of {n} values"))
            ),
        ));
    }
    let array = float64_array(obj, name)?;
    let ro = array
        .try_readonly()
        .map_err(|e| errors::input(py, name, &format!("cannot be read: {e}")))?;
    let view = ro.as_array();
    if view.ndim() != 1 {
        return Err(errors::input(
            py,
            name,
            &format!(
                "must be a 1-D array{}, got shape {:?}",
                len.map_or(String::new(), |n| format!(" of {n} values")),
                view.shape()
            ),
        ));
    }
    if let Some(n) = len {
        if view.len() != n {
            return Err(errors::input(
                py,
                name,
                &format!("needs {n} values, got {}", view.len()),
            ));
        }
    }
    copy_finite(py, &view, name, |k| format!("[{k}]"))
}

fn is_scalar(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyFloat>() || obj.is_instance_of::<PyInt>()
}

/// A finite real number (a Python or NumPy float or integer; not a boolean).
pub fn number(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<f64> {
    let py = obj.py();
    if obj.is_instance_of::<PyBool>() {
        return Err(errors::argument_type(
            py,
            name,
            "must be a real number, got a boolean",
        ));
    }
    if is_masked(obj)? {
        return Err(errors::argument_type(py, name, MASKED));
    }
    let v: f64 = obj.extract().map_err(|e| {
        errors::convert_error(py, e, |_| {
            let type_name = crate::values::type_name(obj);
            errors::argument_type(py, name, &format!("must be a real number, got {type_name}"))
        })
    })?;
    if !v.is_finite() {
        return Err(errors::input(py, name, &format!("must be finite, got {v}")));
    }
    Ok(v)
}

/// A non-negative integer (a Python or NumPy integer).
pub fn count(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<usize> {
    let py = obj.py();
    if obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyFloat>() {
        return Err(errors::argument_type(py, name, "must be an integer"));
    }
    if !obj.hasattr("__index__")? {
        return Err(errors::argument_type(py, name, "must be an integer"));
    }
    let v: i128 = obj
        .call_method0("__index__")
        .and_then(|i| i.extract())
        .map_err(|e| {
            if e.is_instance_of::<pyo3::exceptions::PyOverflowError>(py) {
                return errors::input(py, name, "is too large");
            }
            errors::convert_error(py, e, |_| {
                errors::argument_type(py, name, "must be an integer")
            })
        })?;
    if v < 0 {
        return Err(errors::input(
            py,
            name,
            &format!("must be a non-negative integer, got {v}"),
        ));
    }
    usize::try_from(v).map_err(|_| errors::input(py, name, &format!("is too large, got {v}")))
}

/// A string.
pub fn text(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    obj.cast::<pyo3::types::PyString>()
        .map_err(|_| errors::argument_type(obj.py(), name, "must be a string"))?
        .extract::<String>()
        .map_err(|_| errors::input(obj.py(), name, "is not valid text (unpaired surrogates)"))
}

/// `values` as a new 1-D array if every value is finite, else the `InputError` of `argument`
/// saying which output (`what`, `what[i]`) is not: a model-level call at a state beyond the
/// model's range (a huge rotation or momentum) says so instead of returning NaN or inf.
pub fn finite1<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    what: &str,
    argument: &str,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    check_finite(py, &values, what, argument)?;
    Ok(out1(py, values))
}

/// [`finite1`] for a matrix (`what[i, j]` in the message).
pub fn finite_matrix<'py>(
    py: Python<'py>,
    m: &DMatrix<f64>,
    what: &str,
    argument: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    if let Some(k) = m.iter().position(|v| !v.is_finite()) {
        let (r, c) = (k % m.nrows().max(1), k / m.nrows().max(1));
        return Err(non_finite(
            py,
            &format!("{what}[{r}, {c}]"),
            m[(r, c)],
            argument,
        ));
    }
    Ok(out_matrix(py, m))
}

/// Err naming `argument` if a value of `values` is not finite.
pub fn check_finite(py: Python<'_>, values: &[f64], what: &str, argument: &str) -> PyResult<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(i) => Err(non_finite(py, &format!("{what}[{i}]"), values[i], argument)),
        None => Ok(()),
    }
}

fn non_finite(py: Python<'_>, what: &str, v: f64, argument: &str) -> PyErr {
    errors::input(
        py,
        argument,
        &format!(
            "gives a non-finite {what} = {v}: the value is beyond the range the model can \
             evaluate (a rotation, velocity or momentum too large)"
        ),
    )
}

/// A new 1-D array.
pub fn out1<'py>(py: Python<'py>, v: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, v)
}

/// A new C-ordered 2-D array of `rows` rows from row-major `data`.
pub fn out2<'py>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    data: Vec<f64>,
) -> Bound<'py, PyArray2<f64>> {
    match Array2::from_shape_vec((rows, cols), data) {
        Ok(a) => a.into_pyarray(py),
        // The callers pass rows * cols values; keep an empty array rather than panic.
        Err(_) => Array2::<f64>::zeros((0, cols)).into_pyarray(py),
    }
}

/// A new C-ordered 2-D array from a nalgebra matrix.
pub fn out_matrix<'py>(py: Python<'py>, m: &DMatrix<f64>) -> Bound<'py, PyArray2<f64>> {
    let (r, c) = m.shape();
    let mut data = Vec::with_capacity(r * c);
    for i in 0..r {
        for j in 0..c {
            data.push(m[(i, j)]);
        }
    }
    out2(py, r, c, data)
}

/// A new C-ordered 2-D array from rows of equal length `cols`.
pub fn out_rows<'py>(py: Python<'py>, rows: &[&[f64]], cols: usize) -> Bound<'py, PyArray2<f64>> {
    let mut data = Vec::with_capacity(rows.len() * cols);
    for r in rows {
        data.extend_from_slice(r);
    }
    out2(py, rows.len(), cols, data)
}
