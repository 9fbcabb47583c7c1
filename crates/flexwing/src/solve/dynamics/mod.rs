//! Equations of motion in Hamiltonian form (model.md, "Equations of motion"), for any
//! [`StructuralModel`]: state `y = (x, p)`,
//!
//! ```text
//! ẋ = M(x)⁻¹ p
//! ṗ = −K x + γ(x, ẋ) − C ẋ + Σ_k f_k(t) Q_k(x)
//! ```
//!
//! with the gyroscopic term `γ` exact, by central differences of `−½ pᵀ M(x)⁻¹ p`, or neglected,
//! an exact Jacobian `∂(ẋ, ṗ)/∂(x, p)` for the implicit integrators, and for the full model O(n)
//! solves of their Newton systems with the Jacobian's structural part (`eom_newton.rs`).
//!
//! One file per concept: the equations (`equations.rs`) as an ODE system (`ode.rs`), how their
//! Newton systems are solved (`newton_systems.rs`), the gyroscopic term (`gyroscopic.rs`) and the
//! loads' time histories (`time_function.rs`).

mod equations;
mod gyroscopic;
mod newton_systems;
mod ode;
mod time_function;

pub use super::damping::Damping;
pub use equations::EquationsOfMotion;
pub use gyroscopic::Gyroscopic;
pub use newton_systems::{
    chain_newton_min_dofs, NewtonSystems, CHAIN3D_NEWTON_MIN_DOFS, CHAIN_NEWTON_MIN_DOFS,
};
pub use time_function::TimeFunction;

#[cfg(test)]
mod tests;
