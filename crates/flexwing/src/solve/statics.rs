//! Linear statics about the undeformed state.

use nalgebra::DVector;

use crate::error::InputError;
use crate::model::{FullModel, Load, StructuralModel};

/// Linear static solution `q = K⁻¹ Q(0)` of `loads` about the undeformed state, and the linearized
/// nodal displacements `δP_i = J_{P_i}(0) q` as `(dx, dy)` per node `0 … n`.
///
/// # Errors
/// If a load is invalid for this model (see [`FullModel::check_loads`]).
pub fn linear_static(
    model: &FullModel,
    loads: &[Load],
) -> Result<(DVector<f64>, Vec<[f64; 2]>), InputError> {
    model.check_loads(loads, "loads")?;
    let nd = model.n_dofs();
    let q0 = vec![0.0; nd];
    let mut f = DVector::zeros(nd);
    model.generalized_forces_into(&q0, loads, &mut f);
    let q = f.component_div(&DVector::from_column_slice(model.stiffness()));
    let ell = model.beam().lengths();
    let mut theta = 0.0;
    let mut y = 0.0;
    let mut disp = vec![[0.0, 0.0]];
    for j in 0..model.n_elements() {
        theta += q[j];
        y += ell[j] * theta;
        disp.push([0.0, y]);
    }
    Ok((q, disp))
}
