//! Solvers: modal analysis, non-linear statics, and time integration.

mod continuation;
mod dynamics;
mod eigen;
pub mod integrate;
mod modes;
mod statics;

pub use continuation::{arc_length_static, ArcLengthOptions, PathError, PathPoint, StaticPath};
pub use dynamics::{Damping, EquationsOfMotion, Gyroscopic, TimeFunction};
pub use eigen::generalized_symmetric_eigen;
pub use modes::{ModeShape, Modes};
pub use statics::{
    continue_static, linear_static, solve_static, sweep_static, StaticOptions, StaticSolution,
    StaticStats, SweepError,
};
