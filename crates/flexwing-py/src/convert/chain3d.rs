//! The 3-D chain's outcomes (`flexwing::analysis::chain3d`) into `Chain3dModesResult`,
//! `Chain3dStaticResult`, `Chain3dAeroStaticResult`, `Chain3dFlutterResult`, `Chain3dStudyResult`
//! and `Chain3dDynamicResult`
//! (`python/flexwing/_chain3d_results.py`): the library's serialized outcome as a dict (the same
//! names as the CLI's JSON), the model's size beside it; a dynamic run's columns as NumPy arrays. The result classes give the arrays
//! (node `x, y, z`, section rotations, speeds) as NumPy views of these lists.

use flexwing::analysis::chain3d::{Chain3dOutcome, Chain3dPlan, Dynamic3dOutcome};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::status::{data, overall, set_status};
use crate::arrays::{out1, out_rows};

/// The dict of `outcome`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &Chain3dPlan,
    outcome: &Chain3dOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = data(py, outcome)?.cast_into::<PyDict>()?;
    d.del_item("analysis")?;
    d.set_item("n_elements", plan.model.n_elements())?;
    d.set_item("n_dofs", plan.model.n_dofs())?;
    if let Chain3dOutcome::Dynamic(o) = outcome {
        dynamic_runs(py, &d, o)?;
    }
    if matches!(
        outcome,
        Chain3dOutcome::Dynamic(_) | Chain3dOutcome::Static(_)
    ) {
        // The undeformed nodes: the VTK files' displacements are from them.
        let zero = vec![0.0; plan.model.n_dofs()];
        d.set_item("reference", plan.model.node_positions(&zero))?;
    }
    Ok(d)
}

/// The runs of a dynamic outcome as `Chain3dDynamicRun`'s dicts: the history columns as NumPy
/// arrays (`tip_rotation` `(T, 3)`), the status as its word, `stop` and `message` (as the planar
/// `DynamicRun`'s); the result's `status` the worst of its runs'.
fn dynamic_runs(py: Python<'_>, d: &Bound<'_, PyDict>, o: &Dynamic3dOutcome) -> PyResult<()> {
    let runs = d
        .get_item("runs")?
        .ok_or_else(|| crate::errors::internal(py, "the serialized dynamic outcome has no runs"))?;
    for (r, run) in o.runs.iter().zip(runs.try_iter()?) {
        let rd = run?.cast_into::<PyDict>()?;
        for (name, v) in [
            ("t", &r.t),
            ("tip_x", &r.tip_x),
            ("tip_y", &r.tip_y),
            ("tip_z", &r.tip_z),
            ("kinetic", &r.kinetic),
            ("strain", &r.strain),
            ("total", &r.total),
            ("work", &r.work),
            ("dissipated", &r.dissipated),
            ("balance_error", &r.balance_error),
        ] {
            rd.set_item(name, out1(py, v.clone()))?;
        }
        let rows: Vec<&[f64]> = r.tip_rotation.iter().map(|v| v.as_slice()).collect();
        rd.set_item("tip_rotation", out_rows(py, &rows, 3))?;
        set_status(&rd, &r.status)?;
    }
    d.set_item("status", overall(o.runs.iter().map(|r| &r.status)))
}

/// The result kind of `plan`: `chain3d-modes`, `chain3d-static`, `chain3d-aero-static`,
/// `chain3d-flutter`, `chain3d-study`, `chain3d-dynamic`.
pub fn kind(plan: &Chain3dPlan) -> String {
    format!("chain3d-{}", plan.name())
}
