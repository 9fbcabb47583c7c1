//! # flexwing
//!
//! Geometrically non-linear structural dynamics of very flexible wings and slender blades, and
//! the non-linear reduced-order models that make them fast.
//!
//! A cantilever is cut into `n` rigid elements joined by bending springs (geometrically
//! non-linear, in-plane) and torsion springs (linear), coupled through the chordwise offset `d0`
//! of each element's mass centre. The model is specified exactly in `docs/model.md`; the method
//! is that of Veronese, Ribeiro & Moreira, *Reduced order modeling of highly flexible
//! structures* (COBEM 2021).
//!
//! The modules form a chain: [`beam`] (section properties, discretization, stiffness calibration)
//! → [`model`] (kinematics, mass matrix, generalized forces) → [`solve`] (modes, statics,
//! dynamics) → [`analysis`] (what a run is: validated plans in, outcomes out; the public way to
//! run any analysis); [`paper`] holds the paper's beams.
//!
//! ```
//! use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
//! use flexwing::{model::FullModel, solve::Modes};
//!
//! let section = SectionProperties {
//!     ei: Profile::Uniform(50.0),          // N·m²
//!     mass_per_length: Profile::Uniform(0.2), // kg/m
//!     torsion: None,                        // bending only
//! };
//! let beam = Beam::new(1.0, &section, &Discretization::Uniform(20), Calibration::TipLoad)?;
//! let model = FullModel::new(beam);
//! let modes = Modes::undeformed(&model)?;
//! assert_eq!(modes.n_modes(), 20);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]
#![allow(non_snake_case)]

pub mod analysis;
pub mod beam;
mod error;
pub mod magnitude;
pub mod model;
pub mod paper;
pub mod solve;
pub mod text;
pub mod wings;

pub use error::{Error, InputError, Result, SolveError, StaticFailure};

/// `prefix.key`, or `key` alone with an empty prefix: the name of a field of the caller's input
/// for error messages (`field("dynamic", "rtol")` is `dynamic.rtol`).
pub(crate) fn field(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}
