//! Strip-theory aerodynamics on the lumped chain (docs/aeroelastic-model.md).

mod fluid;

pub(crate) use fluid::FluidInertia;
mod lag;
mod theodorsen;

pub(crate) use lag::Lag;
pub use theodorsen::theodorsen;
