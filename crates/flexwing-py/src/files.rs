//! Result files from Python through the output crate (`flexwing-io`), the CLI's writers: the
//! `.npz` node histories (`DynamicResult.save_npz`) and the VTK files (`write_vtk`).

use std::path::PathBuf;

use numpy::{PyReadonlyArray1, PyReadonlyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;

use flexwing_io::nodes::{self, NodeHistory};

/// One model's history as Python passes it: label, `t` `(S,)`, `index` `(S,)`, values
/// `(S, nodes, fields)`.
type History<'py> = (
    String,
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray3<'py, f64>,
);

/// Write the node histories to `path` (`.npz`, atomically) in the layout of
/// `flexwing_io::nodes`; `fields` the (name, unit) of the last axis.
#[pyfunction]
pub fn write_node_npz(
    py: Python<'_>,
    path: PathBuf,
    fields: Vec<(String, String)>,
    histories: Vec<History<'_>>,
) -> PyResult<()> {
    let mut list = Vec::with_capacity(histories.len());
    for (label, t, index, values) in &histories {
        let (t, index, values) = (t.as_array(), index.as_array(), values.as_array());
        let shape = values.shape();
        if shape[0] != t.len() || shape[0] != index.len() || shape[2] != fields.len() {
            return Err(crate::errors::input(
                py,
                "histories",
                &format!(
                    "{label}: values of shape {shape:?} for {} times, {} indices and {} fields",
                    t.len(),
                    index.len(),
                    fields.len()
                ),
            ));
        }
        list.push(NodeHistory {
            label: label.clone(),
            t: t.iter().copied().collect(),
            index: index.iter().copied().collect(),
            nodes: shape[1],
            // Logical (row-major) order, whatever the array's memory layout.
            values: values.iter().copied().collect(),
        });
    }
    let vars = nodes::variables(&fields, &list);
    py.detach(|| flexwing_io::atomic::write_with(&path, |f| flexwing_io::npz::write(f, &vars)))
        .map_err(|e| PyOSError::new_err(e.to_string()))
}
