//! Solvers: modal analysis, non-linear statics, and time integration.

mod dynamics;
mod eigen;
mod eom_newton;
pub mod integrate;
mod modes;
mod statics;
mod tangent;

pub use dynamics::{
    Damping, EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction, CHAIN_NEWTON_MIN_DOFS,
};
pub use eigen::generalized_symmetric_eigen;
pub use modes::{ModeShape, Modes};
pub use statics::{
    continue_static, linear_static, solve_static, sweep_static, StaticOptions, StaticSolution,
    StaticStats, SweepError,
};
pub use tangent::CHAIN_TANGENT_MIN_DOFS;
