//! The lumped-mass model: kinematics, mass matrix, stiffness and generalized forces.
//!
//! Coordinates (model.md, "Frames and coordinates"): `q_1 … q_n` are the bending joint rotations,
//! `q_{n+1} … q_{2n}` the torsion joint rotations (absent in a bending-only model). Absolute angles
//! are `θ = T q_b`, `ψ = T q_t` with `T` the lower-triangular matrix of ones.

pub mod aero;
pub mod chain3d;
mod chain_newton;
mod chain_solve;
mod full;
mod kinematics;
mod kinetic;
mod loads;
mod mass;
mod reduced;
mod shape;

pub(crate) use chain_newton::{ChainFactor, ChainLinearization, Shift};
pub use full::{FullModel, Workspace};
pub use kinematics::Kinematics;
pub(crate) use kinetic::KineticScratch;
pub use loads::{AppliedLoads, DistributedForce, Force, Load};
pub(crate) use mass::suffix_sum_blocks;

/// Suffix sums within each consecutive block of `n` entries, `x ← Tᵀ x` for joint coordinates:
/// the map from forces conjugate to absolute angles to forces conjugate to joint rotations.
pub(crate) fn suffix_sum_in_blocks<D: num_dual::DualNum<Primitive = f64> + Copy>(
    x: &mut [D],
    n: usize,
) {
    for block in x.chunks_mut(n) {
        for i in (0..block.len().saturating_sub(1)).rev() {
            let next = block[i + 1];
            block[i] += next;
        }
    }
}
pub use chain3d::Chain3d;

/// The planar chain's absolute angles for joint rotations `q` in blocks of `n` (bending, then
/// torsion): the running sums within each block.
pub(crate) fn planar_element_rotations(q: &[f64], n: usize) -> Vec<f64> {
    let mut out = Vec::with_capacity(q.len());
    for block in q.chunks(n.max(1)) {
        let mut angle = 0.0;
        for dq in block {
            angle += dq;
            out.push(angle);
        }
    }
    out
}

/// A model on the paper's planar chain: the full model, or a reduced model projected on its
/// modes, with the planar full model underneath. The 3-D chain is not one (it has no planar
/// full model), so nothing generic over [`StructuralModel`] can ask it for one.
pub trait PlanarModel: StructuralModel {
    /// The full model underneath (itself for the full model).
    fn full_model(&self) -> &FullModel;
}

impl PlanarModel for FullModel {
    fn full_model(&self) -> &FullModel {
        self
    }
}

impl PlanarModel for ReducedModel {
    fn full_model(&self) -> &FullModel {
        self.full()
    }
}
pub use reduced::{ReducedModel, ReducedWorkspace};
pub use shape::Shape;

use nalgebra::{DMatrix, DVector};

/// What the solvers need of a structural model; implemented by the full and the reduced model so
/// that statics, modes and time integration are written once.
///
/// Evaluations take a caller-owned [`StructuralModel::Workspace`] (from
/// [`StructuralModel::workspace`]) and write into caller-owned buffers, so a solver loop
/// allocates nothing.
pub trait StructuralModel {
    /// Scratch buffers for evaluations.
    type Workspace;
    /// Fresh scratch buffers for this model.
    fn workspace(&self) -> Self::Workspace;
    /// Number of generalized coordinates.
    fn n_dofs(&self) -> usize;
    /// Stiffness matrix `K` (constant).
    fn stiffness_matrix(&self) -> DMatrix<f64>;
    /// Mass matrix `M(x)` into `out` (`n_dofs × n_dofs`).
    fn mass_matrix_into(&self, x: &[f64], ws: &mut Self::Workspace, out: &mut DMatrix<f64>);
    /// Generalized forces `Q(x) = Σ_k scales[k] Q_k(x)` into `out`.
    fn generalized_forces_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Self::Workspace,
        out: &mut DVector<f64>,
    );
    /// Load Jacobian `∂Q/∂x` into `out`.
    fn load_jacobian_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Self::Workspace,
        out: &mut DMatrix<f64>,
    );
    /// Momentum `p = M(x) ẋ` into `out`.
    fn momentum_into(&self, x: &[f64], xdot: &[f64], ws: &mut Self::Workspace, out: &mut [f64]);
    /// Velocities `ẋ = M(x)⁻¹ p` into `out`: O(n) for the full model (a Riccati sweep along the
    /// chain, `model::chain_solve`), a dense `r × r` Cholesky factorization for the reduced one.
    /// Returns false, leaving `out` unspecified, if `M(x)` is not numerically positive definite.
    fn velocities_into(
        &self,
        x: &[f64],
        p: &[f64],
        ws: &mut Self::Workspace,
        out: &mut [f64],
    ) -> bool;
    /// `M(x)⁻¹ P` for the columns of `p` into `out` (same shape), factoring `M(x)` once.
    /// Returns false, leaving `out` unspecified, if `M(x)` is not positive definite.
    fn velocities_block_into(
        &self,
        x: &[f64],
        p: &DMatrix<f64>,
        ws: &mut Self::Workspace,
        out: &mut DMatrix<f64>,
    ) -> bool {
        (0..p.ncols()).all(|c| {
            let col = out.column_mut(c).data.into_slice_mut();
            self.velocities_into(x, p.column(c).as_slice(), ws, col)
        })
    }
    /// Gyroscopic term `γ = ∂T/∂x|_ẋ` into `out`.
    fn gyroscopic_into(&self, x: &[f64], xdot: &[f64], ws: &mut Self::Workspace, out: &mut [f64]);
    /// Exact derivatives with respect to `x` at fixed `ẋ` of the momentum, `∂(M ẋ)/∂x`, and of
    /// the gyroscopic term, `∂γ/∂x`, into `dp` and `dgamma` (`n_dofs × n_dofs`). The derivative
    /// of `γ` with respect to `ẋ` is `(∂(M ẋ)/∂x)ᵀ`.
    fn kinetic_derivatives_into(
        &self,
        x: &[f64],
        xdot: &[f64],
        ws: &mut Self::Workspace,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    );
    /// Derivatives at fixed momentum `p` of the velocities and of the gyroscopic term:
    /// `dxdx = ∂ẋ/∂x|_p = −M⁻¹ B` and, if `with_gamma`, `dgamma = d γ(x, ẋ(x, p))/dx|_p =
    /// ∂γ/∂x|_ẋ + Bᵀ dxdx`, with `B = ∂(M ẋ)/∂x|_ẋ` (`n_dofs × n_dofs` each; `dgamma` is
    /// scratch otherwise). False if `M(x)` is not positive definite.
    ///
    /// The default forms `B` and the product `Bᵀ dxdx` (O(n_dofs³)); the full model, from 128
    /// coordinates on, uses dual numbers through the O(n) velocity solve instead, O(n²) in all.
    fn hamiltonian_derivatives_into(
        &self,
        x: &[f64],
        p: &[f64],
        ws: &mut Self::Workspace,
        with_gamma: bool,
        dxdx: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) -> bool {
        hamiltonian_derivatives_dense(self, x, p, ws, with_gamma, dxdx, dgamma)
    }
    /// Whether the loads at these scales derive from a potential, so that the tangent
    /// `K − ∂Q/∂x` is symmetric and its positive definiteness decides stability. `scales` is the
    /// slice the model's force methods take (a model may append scales of its own loads).
    fn loads_are_conservative(&self, loads: &AppliedLoads, scales: &[f64]) -> bool {
        loads.is_conservative(scales)
    }
    /// Joint rotations `q` of the full model for the model's coordinates `x`.
    fn full_coordinates(&self, x: &[f64]) -> Vec<f64>;
    /// The elements' rotations that a change `dx` of the coordinates makes, linear in `dx`: the
    /// measure of how far a static step went (`StaticOptions::max_rotation_step`, the largest
    /// magnitude) and arc-length continuation's metric. The planar chain's are its absolute
    /// angles `θ_i = Σ_{j≤i} Δq_j` and `ψ_i = Σ_{j≤i} Δq_{n+j}` of
    /// [`StructuralModel::full_coordinates`] (`planar_element_rotations`); the 3-D chain sums
    /// its joints' rotation vectors.
    fn element_rotations(&self, dx: &[f64]) -> Vec<f64>;
    /// This model as the full model, when it is one (its coordinates are the joint rotations):
    /// the solvers then solve their Newton systems by O(n) sweeps along the chain
    /// (`model::chain_newton`). `None` (the default) for other models.
    fn as_full_model(&self) -> Option<&FullModel> {
        None
    }
    /// This model as the 3-D chain, when it is one (its coordinates are the joints' rotation
    /// vectors): the implicit integrators then solve their Newton systems in O(n)
    /// (`model::chain3d::newton`). `None` (the default) for other models.
    fn as_chain3d(&self) -> Option<&Chain3d> {
        None
    }
    /// `K` as 3×3 diagonal blocks (row-major, one per joint), when it is block diagonal with
    /// such blocks (the 3-D chain): the equations of motion then never form it. `None` (the
    /// default) otherwise.
    fn stiffness_blocks(&self) -> Option<Vec<[[f64; 3]; 3]>> {
        None
    }
}

/// [`StructuralModel::hamiltonian_derivatives_into`] from `B = ∂(M ẋ)/∂x` and dense products:
/// `∂ẋ/∂x = −M⁻¹ B` (velocity solves by column), `dγ/dx = G_x + Bᵀ ∂ẋ/∂x` (one matrix product).
pub(crate) fn hamiltonian_derivatives_dense<M: StructuralModel + ?Sized>(
    model: &M,
    x: &[f64],
    p: &[f64],
    ws: &mut M::Workspace,
    with_gamma: bool,
    dxdx: &mut DMatrix<f64>,
    dgamma: &mut DMatrix<f64>,
) -> bool {
    let n = model.n_dofs();
    let mut xdot = vec![0.0; n];
    if !model.velocities_into(x, p, ws, &mut xdot) {
        return false;
    }
    let mut b = DMatrix::zeros(n, n);
    model.kinetic_derivatives_into(x, &xdot, ws, &mut b, dgamma);
    if !model.velocities_block_into(x, &b, ws, dxdx) {
        return false;
    }
    dxdx.neg_mut();
    if with_gamma {
        dgamma.gemm_tr(1.0, &b, dxdx, 1.0);
    }
    true
}
