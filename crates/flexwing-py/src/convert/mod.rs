//! Library outcomes into the result objects of `python/flexwing/` (`_results.py`,
//! `_aero_results.py`, on the base of `_base.py`): each outcome becomes a dict of NumPy arrays,
//! numbers and strings here — what the library serializes (statuses, stops, counters, the
//! energy audit, notes) through `status.rs`, the columns as arrays — and the Python class is
//! built from it. Adding a field is one `set_item` here and one attribute there (the test suite
//! checks the two agree); a new analysis is one module here and one class there.

pub mod aero_dynamics;
pub mod aero_statics;
pub mod chain3d;
pub mod dynamics;
pub mod flutter;
pub mod gust_family;
pub mod linearize;
pub mod modes;
pub mod statics;
pub mod status;
pub mod turbulence;

use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The result object of `kind` (`"modes"`, `"static"`, `"dynamic"`, `"aero-static"`,
/// `"aero-dynamic"`, `"flutter"`, `"batch"`) from `raw`.
pub fn build<'py>(
    py: Python<'py>,
    kind: &str,
    raw: Bound<'py, PyDict>,
) -> PyResult<Bound<'py, PyAny>> {
    py.import("flexwing._base")?
        .getattr("_build")?
        .call1((kind, raw))
}
