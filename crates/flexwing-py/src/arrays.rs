//! NumPy in and out. Input: any array-like of real numbers (a list, a float32 or integer array,
//! a C- or Fortran-ordered or strided view) is converted to float64 and **copied** element by
//! element, in logical order, into owned Rust vectors and matrices before any arithmetic: no
//! strided view reaches nalgebra (whose arithmetic on strided views writes out of bounds,
//! nalgebra issue #1616). Shapes, dtypes and values are checked, and every error names the
//! argument (`y`, `EI[3]`): `ArgumentTypeError` for a wrong type or dtype (complex, boolean,
//! strings, objects), `InputError` for a wrong shape or a non-finite value. Output: new
//! C-ordered float64 arrays that Python owns.

use nalgebra::DMatrix;
use numpy::ndarray::{Array2, ArrayViewD};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt};

use crate::errors;

/// A float64 view of `obj`: the array itself if it already is one, else `numpy.asarray(obj)`
/// converted to float64 after checking that its dtype is real (floats, integers).
fn float64_array<'py>(
    obj: &Bound<'py, PyAny>,
    name: &str,
) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
    let py = obj.py();
    if let Ok(a) = obj.cast::<PyArrayDyn<f64>>() {
        return Ok(a.clone());
    }
    let numpy = py.import("numpy")?;
    let array = numpy.call_method1("asarray", (obj,)).map_err(|e| {
        errors::argument_type(
            py,
            name,
            &format!("must be an array of real numbers ({})", e.value(py)),
        )
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
    let v: f64 = obj.extract().map_err(|_| {
        let type_name = obj
            .get_type()
            .name()
            .map(|n| n.to_string())
            .unwrap_or_else(|_| "?".into());
        errors::argument_type(py, name, &format!("must be a real number, got {type_name}"))
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
    let v: i128 = obj
        .call_method0("__index__")
        .and_then(|i| i.extract())
        .map_err(|_| errors::argument_type(py, name, "must be an integer"))?;
    usize::try_from(v).map_err(|_| {
        errors::input(
            py,
            name,
            &format!("must be a non-negative integer, got {v}"),
        )
    })
}

/// A string.
pub fn text(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<String> {
    obj.extract()
        .map_err(|_| errors::argument_type(obj.py(), name, "must be a string"))
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
