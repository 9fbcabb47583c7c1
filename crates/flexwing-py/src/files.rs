//! Result files from Python through the output crate (`flexwing-io`), the CLI's writers: the
//! `.npz` node histories (`DynamicResult.save_npz`) and the VTK files (`write_vtk`).

use std::path::PathBuf;

use numpy::{PyReadonlyArray1, PyReadonlyArray2, PyReadonlyArray3};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;

use flexwing_io::nodes::{self, NodeHistory};
use flexwing_io::vtk;

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
    let vars = crate::errors::guard(py, || node_variables(py, &fields, &histories))?;
    crate::errors::detached(py, || {
        flexwing_io::atomic::write_with(&path, |f| flexwing_io::npz::write(f, &vars))
    })?
    .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// The named arrays of `histories`, checked.
fn node_variables(
    py: Python<'_>,
    fields: &[(String, String)],
    histories: &[History<'_>],
) -> PyResult<Vec<(String, flexwing_io::Value)>> {
    let mut list = Vec::with_capacity(histories.len());
    for (label, t, index, values) in histories {
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
    Ok(nodes::variables(fields, &list))
}

/// Write a planar chain's frames to `folder` as `STEM_0000.vtu`, … and `STEM.pvd`
/// (`flexwing_io::vtk::write_series`); returns the `.pvd`'s path. Per frame `k`: `times[k]`,
/// the nodes `x[k]`, `y[k]` (deformed positions; with `modes`, the nodal displacements of a
/// mode shape drawn on the undeformed nodes), `twist[k]`; `stations` the undeformed nodes'
/// spanwise positions.
#[pyfunction]
#[pyo3(signature = (folder, stem, times, x, y, twist, stations, modes = false))]
#[allow(clippy::too_many_arguments)]
pub fn write_planar_vtk(
    py: Python<'_>,
    folder: PathBuf,
    stem: String,
    times: PyReadonlyArray1<'_, f64>,
    x: PyReadonlyArray2<'_, f64>,
    y: PyReadonlyArray2<'_, f64>,
    twist: PyReadonlyArray2<'_, f64>,
    stations: PyReadonlyArray1<'_, f64>,
    modes: bool,
) -> PyResult<String> {
    let frames = crate::errors::guard(py, || {
        planar_frames(py, &times, &x, &y, &twist, &stations, modes)
    })?;
    crate::errors::detached(py, || vtk::write_series(&folder, &stem, &frames))?
        .map(|p| p.to_string_lossy().into_owned())
        .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// The frames of `write_planar_vtk`, checked.
fn planar_frames(
    py: Python<'_>,
    times: &PyReadonlyArray1<'_, f64>,
    x: &PyReadonlyArray2<'_, f64>,
    y: &PyReadonlyArray2<'_, f64>,
    twist: &PyReadonlyArray2<'_, f64>,
    stations: &PyReadonlyArray1<'_, f64>,
    modes: bool,
) -> PyResult<Vec<vtk::Frame>> {
    let (times, x, y, twist) = (
        times.as_array(),
        x.as_array(),
        y.as_array(),
        twist.as_array(),
    );
    let stations: Vec<f64> = stations.as_array().iter().copied().collect();
    let shape = (times.len(), stations.len());
    for (name, a) in [("x", &x), ("y", &y), ("twist", &twist)] {
        if a.dim() != shape {
            return Err(crate::errors::input(
                py,
                name,
                &format!("shape {:?}, expected {shape:?} (times, nodes)", a.dim()),
            ));
        }
    }
    let reference = vtk::straight(&stations);
    let row = |a: &numpy::ndarray::ArrayView2<f64>, k: usize| -> Vec<f64> {
        a.row(k).iter().copied().collect()
    };
    let frames: Vec<vtk::Frame> = (0..times.len())
        .map(|k| {
            let (xk, yk, tk) = (row(&x, k), row(&y, k), row(&twist, k));
            if modes {
                vtk::planar_mode_frame(times[k], &xk, &yk, &tk, &reference)
            } else {
                vtk::planar_frame(times[k], &xk, &yk, &tk, &reference)
            }
        })
        .collect();
    Ok(frames)
}

/// Write frames of the 3-D chain to `folder` as `STEM_0000.vtu`, … and `STEM.pvd`; returns the
/// `.pvd`'s path. Per frame `k`: `times[k]`, the node positions `position[k]` `(nodes, 3)` and
/// the elements' section rotation vectors `rotation[k]` `(nodes − 1, 3)` (the section frames
/// are their rotation matrices); `reference` `(nodes, 3)` the undeformed nodes. With `modes`,
/// `position[k]` is a mode's nodal displacements drawn on `reference`.
#[pyfunction]
#[pyo3(signature = (folder, stem, times, position, rotation, reference, modes = false))]
#[allow(clippy::too_many_arguments)]
pub fn write_spatial_vtk(
    py: Python<'_>,
    folder: PathBuf,
    stem: String,
    times: PyReadonlyArray1<'_, f64>,
    position: PyReadonlyArray3<'_, f64>,
    rotation: PyReadonlyArray3<'_, f64>,
    reference: PyReadonlyArray2<'_, f64>,
    modes: bool,
) -> PyResult<String> {
    let frames = crate::errors::guard(py, || {
        spatial_frames(py, &times, &position, &rotation, &reference, modes)
    })?;
    crate::errors::detached(py, || vtk::write_series(&folder, &stem, &frames))?
        .map(|p| p.to_string_lossy().into_owned())
        .map_err(|e| PyOSError::new_err(e.to_string()))
}

/// The frames of `write_spatial_vtk`, checked.
fn spatial_frames(
    py: Python<'_>,
    times: &PyReadonlyArray1<'_, f64>,
    position: &PyReadonlyArray3<'_, f64>,
    rotation: &PyReadonlyArray3<'_, f64>,
    reference: &PyReadonlyArray2<'_, f64>,
    modes: bool,
) -> PyResult<Vec<vtk::Frame>> {
    let (times, position, rotation, reference) = (
        times.as_array(),
        position.as_array(),
        rotation.as_array(),
        reference.as_array(),
    );
    let nodes = reference.nrows();
    let expected = [
        ("position", position.dim(), (times.len(), nodes, 3)),
        (
            "rotation",
            rotation.dim(),
            (times.len(), nodes.saturating_sub(1), 3),
        ),
    ];
    for (name, got, want) in expected {
        if got != want || reference.ncols() != 3 || nodes < 2 {
            return Err(crate::errors::input(
                py,
                name,
                &format!("shape {got:?}, expected {want:?} (times, nodes, 3)"),
            ));
        }
    }
    let rows = |a: &numpy::ndarray::ArrayView2<f64>| -> Vec<[f64; 3]> {
        a.rows().into_iter().map(|r| [r[0], r[1], r[2]]).collect()
    };
    let reference = rows(&reference);
    Ok((0..times.len())
        .map(|k| {
            let p = rows(&position.index_axis(numpy::ndarray::Axis(0), k));
            let r = rows(&rotation.index_axis(numpy::ndarray::Axis(0), k));
            if modes {
                vtk::spatial_mode_frame(times[k], &p, &r, &reference)
            } else {
                let frames: Vec<[[f64; 3]; 3]> = r
                    .iter()
                    .map(|&v| flexwing::model::chain3d::rotation_matrix(v))
                    .collect();
                vtk::spatial_frame(times[k], &p, &r, &frames, &reference)
            }
        })
        .collect())
}
