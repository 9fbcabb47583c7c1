//! Strip-theory aerodynamics on the lumped chain (docs/aeroelastic-model.md).

mod fluid;

pub(crate) use fluid::FluidInertia;
