//! Solvers: modal analysis and (linear) statics.

mod eigen;
mod modes;
mod statics;

pub use eigen::generalized_symmetric_eigen;
pub use modes::{ModeShape, Modes};
pub use statics::linear_static;
