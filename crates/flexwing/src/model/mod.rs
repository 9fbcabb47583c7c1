//! The lumped-mass model: kinematics, mass matrix, stiffness and generalized forces.
//!
//! Coordinates (model.md, "Frames and coordinates"): `q_1 … q_n` are the bending joint rotations,
//! `q_{n+1} … q_{2n}` the torsion joint rotations (absent in a bending-only model). Absolute angles
//! are `θ = T q_b`, `ψ = T q_t` with `T` the lower-triangular matrix of ones.

mod full;
mod kinematics;
mod loads;
mod mass;

pub use full::FullModel;
pub use kinematics::Kinematics;
pub use loads::{Force, Load};

use nalgebra::{DMatrix, DVector};

/// What the solvers need of a structural model; implemented by the full model (and, later, the
/// reduced one) so that statics, modes and time integration are written once.
pub trait StructuralModel {
    /// Number of generalized coordinates.
    fn n_dofs(&self) -> usize;
    /// Mass matrix `M(q)` into `out` (`n_dofs × n_dofs`).
    fn mass_matrix_into(&self, q: &[f64], out: &mut DMatrix<f64>);
    /// Stiffness matrix `K` (constant).
    fn stiffness_matrix(&self) -> DMatrix<f64>;
    /// Generalized forces `Q(q)` of `loads` into `out`.
    fn generalized_forces_into(&self, q: &[f64], loads: &[Load], out: &mut DVector<f64>);
}
