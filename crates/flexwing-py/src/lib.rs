//! # flexwing-py
//!
//! The `flexwing` Python package: the Rust extension `flexwing._native` built by maturin (with
//! the stable ABI, one wheel for Python ≥ 3.9), and the pure-Python part in `python/flexwing`
//! (the exception tree, the result classes, the type stubs). See `docs/python.md`.
//!
//! | module | what |
//! |---|---|
//! | `case` | `Case`: a case file, TOML text or dict; its analyses |
//! | `run` | running an analysis of a case detached from the interpreter: `Case::plan` of the case crate's `Analysis`, `flexwing::analysis::run`, the outcome into its result |
//! | `convert/` | library outcomes into result objects (dicts of NumPy arrays) |
//! | `batch` | `solve_many`: many cases, each one's status and error as data |
//! | `model` | `Beam`, `FullModel`, `ReducedModel` |
//! | `equations` | `Equations` (rhs, Jacobian, energies at a state) and `Stepper` |
//! | `arrays` | NumPy in (checked, converted, copied) and out |
//! | `errors` | library errors into Python exceptions; panics caught at the boundary |
//! | `values` | Python values into the case crate's serde types, errors naming the key path |
//! | `files` | result files through the output crate (`flexwing-io`): `.npz` node histories, VTK |
//! | `kwargs`, `progress` | keyword arguments checked by name; the progress callback |
//!
//! A new analysis of the library (a variant of `flexwing::analysis::Plan` and `Outcome`, built
//! by `Case::plan`) joins as one arm of [`run::to_python`], one converter in `convert/` and one
//! result class in `python/flexwing/_results.py`.

use pyo3::prelude::*;

mod aero_stepper;
mod arrays;
mod batch;
mod case;
mod convert;
mod equations;
mod errors;
mod files;
mod kwargs;
mod model;
mod progress;
mod run;
mod values;

/// What `__reduce__` returns: the callable that rebuilds the object, and its arguments.
type Reduce<'py, A> = PyResult<(Bound<'py, PyAny>, A)>;

/// Load NumPy's C API now, while the module is imported: `numpy` loads it on the first array
/// it makes, and a Ctrl-C pending then (the first analysis of a fresh process, interrupted)
/// made that import fail inside a call, as a panic. Here a `KeyboardInterrupt` during the
/// import of NumPy propagates as itself, and the import of `flexwing` fails with it.
fn load_numpy(py: Python<'_>) -> PyResult<()> {
    py.import("numpy")?;
    py.import("numpy.lib")?;
    let major: u32 = py
        .import("numpy")?
        .getattr("__version__")?
        .extract::<String>()?
        .split('.')
        .next()
        .and_then(|m| m.parse().ok())
        .unwrap_or(2);
    py.import(if major >= 2 {
        "numpy._core.multiarray"
    } else {
        "numpy.core.multiarray"
    })?;
    errors::guard(py, || {
        numpy::PyArray1::<f64>::zeros(py, 0, false);
        Ok(())
    })
}

/// The Rust half of the `flexwing` package; import `flexwing`, not this module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    load_numpy(m.py())?;
    m.add_class::<case::PyCase>()?;
    m.add_class::<model::PyBeam>()?;
    m.add_class::<model::PyFullModel>()?;
    m.add_class::<model::PyReducedModel>()?;
    m.add_class::<equations::PyEquations>()?;
    m.add_class::<equations::PyStepper>()?;
    m.add_class::<aero_stepper::PyAeroStepper>()?;
    m.add_function(wrap_pyfunction!(batch::solve_many, m)?)?;
    m.add_function(wrap_pyfunction!(files::write_node_npz, m)?)?;
    m.add_function(wrap_pyfunction!(files::write_planar_vtk, m)?)?;
    m.add_function(wrap_pyfunction!(files::write_spatial_vtk, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
