//! Solvers: modal analysis and non-linear statics.

mod eigen;
mod modes;
mod statics;

pub use eigen::generalized_symmetric_eigen;
pub use modes::{ModeShape, Modes};
pub use statics::{
    continue_static, linear_static, solve_static, sweep_static, StaticOptions, StaticSolution,
    StaticStats, SweepError,
};
