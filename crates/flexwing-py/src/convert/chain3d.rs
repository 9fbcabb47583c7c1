//! The 3-D chain's outcomes (`flexwing::analysis::chain3d`) into `Chain3dModesResult`,
//! `Chain3dStaticResult`, `Chain3dFlutterResult` and `Chain3dStudyResult`
//! (`python/flexwing/_chain3d_results.py`): the library's serialized outcome as a dict (the same
//! names as the CLI's JSON), the model's size beside it. The result classes give the arrays
//! (node `x, y, z`, section rotations, speeds) as NumPy views of these lists.

use flexwing::analysis::chain3d::{Chain3dOutcome, Chain3dPlan};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::status::data;

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
    Ok(d)
}

/// The result kind of `plan`: `chain3d-modes`, `chain3d-static`, `chain3d-flutter`,
/// `chain3d-study`.
pub fn kind(plan: &Chain3dPlan) -> String {
    format!("chain3d-{}", plan.name())
}
