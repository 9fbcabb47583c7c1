//! The geometrically exact 3-D chain: `n` rigid elements joined by three-axis rotational joints
//! (twist, lag, flap), beside the paper's planar model (docs/chain3d-model.md; working notes in
//! `../shared/docs/chain3d.md`).
//!
//! Sources: the continuum it converges to is Simo & Vu-Quoc's rod (*A three-dimensional
//! finite-strain rod model, Part II*, CMAME 58, 1986); the discrete curvature is the rotation
//! vector of the relative rotation of neighbouring elements, as in Bergou et al., *Discrete
//! elastic rods* (SIGGRAPH 2008); the recursions are Featherstone's (*Rigid Body Dynamics
//! Algorithms*, 2008: composite-rigid-body mass matrix, articulated-body velocity solve).
//!
//! * `section.rs`, `geometry.rs`: the input (section stiffness and inertia, reference axis);
//! * `beam.rs`: [`Beam3d`], validated per-element data and the joint stiffness;
//! * `rotation.rs`, `algebra.rs`: rotation vectors (`exp`, `dexp`) and 3×3 algebra over any
//!   scalar;
//! * `kinematics.rs`, `kinetic.rs`, `mass.rs`, `aba.rs`: frames and velocities, momentum and
//!   gyroscopic term, mass matrix, O(n) velocity solve;
//! * `loads.rs`: [`SpatialLoad`] and the generalized forces;
//! * `model.rs`: [`Chain3d`], a [`crate::model::StructuralModel`];
//! * `newton.rs`: O(n) solves of the implicit integrators' Newton systems (GMRES on the exact
//!   operator, preconditioned by the articulated-body solve of `c² M + K`);
//! * `reduced.rs`: [`ReducedChain3d`], the non-linear modal ROM on the chain;
//! * `shape.rs`: [`Shape3d`], the deformed chain for output.

mod aba;
pub(crate) mod algebra;
mod beam;
mod geometry;
pub(crate) mod kinematics;
mod kinetic;
mod loads;
mod mass;
mod model;
mod newton;
mod reduced;
mod rotation;
mod section;
mod shape;

pub use beam::Beam3d;
pub use geometry::Geometry3d;
pub(crate) use loads::SpatialItem;
pub use loads::{SpatialDistributed, SpatialLoad, SpatialVector};
pub use model::{Chain3d, Workspace3d};
pub(crate) use newton::Newton3d;
pub use reduced::{ReducedChain3d, ReducedWorkspace3d};
pub use rotation::{rotation_matrix, rotation_vector};
pub use section::{
    ElementInertia, JointCalibration, SectionInertia, SectionStiffness, StiffnessCoupling,
};
pub use shape::Shape3d;

#[cfg(test)]
mod tests;
