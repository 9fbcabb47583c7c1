//! Solvers: modal analysis, non-linear statics, and time integration.

pub mod aeroelastic;
mod continuation;
mod damping;
mod dynamics;
mod eigen;
mod energy_audit;
mod eom_newton;
pub mod integrate;
mod lanczos;
mod modes;
mod newton_tangent;
mod statics;
mod tangent;

pub use continuation::{arc_length_static, ArcLengthOptions, PathError, PathPoint, StaticPath};
pub use dynamics::{
    chain_newton_min_dofs, Damping, EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction,
    CHAIN3D_NEWTON_MIN_DOFS, CHAIN_NEWTON_MIN_DOFS,
};
pub use eigen::generalized_symmetric_eigen;
pub use energy_audit::{AuditLimits, EnergyBalance};
pub use modes::{ModeShape, Modes, ModesMethod, ModesStats, DENSE_MAX_DOFS};
pub use newton_tangent::CHAIN_TANGENT_MIN_DOFS;
pub(crate) use statics::continue_static_to_instability;
pub use statics::{
    continue_static, linear_static, solve_static, sweep_static, sweep_static_until, StaticOptions,
    StaticSolution, StaticStats, SweepError, FOLLOWER_STABILITY_MAX_DOFS,
};
