//! The gyroscopic term `γ = ∂T/∂x|_ẋ` of the equations of motion: exact, by central differences
//! (the paper's eq. 17), or neglected (its simplified model, eq. 18).

use crate::error::InputError;
use crate::text::short;

/// How the gyroscopic term `γ = ∂T/∂x|_ẋ = −½ ∂(pᵀ M⁻¹ p)/∂x|_p` is obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gyroscopic {
    /// Exact, in O(n) (the chain recursion of `model::kinetic`).
    Exact,
    /// Central finite differences of `−½ pᵀ M(x)⁻¹ p` with step `step` (paper eq. 17); costs
    /// `2 n_dofs` velocity solves per evaluation.
    FiniteDifference {
        /// Step `h` (rad), e.g. `1e-6`.
        step: f64,
    },
    /// Neglected: the paper's "simplified model" (eq. 18). Energy is then not conserved.
    Neglected,
}

impl Gyroscopic {
    /// The usual step `h` of [`Gyroscopic::FiniteDifference`] (rad), as the paper's eq. 17.
    pub const DEFAULT_STEP: f64 = 1e-6;

    /// Check the finite-difference step; `step_field` is the caller's name for it.
    ///
    /// # Errors
    /// A finite-difference step that is not a finite positive number.
    pub fn validate(&self, step_field: &str) -> Result<(), InputError> {
        match *self {
            Gyroscopic::FiniteDifference { step } if !(step > 0.0 && step.is_finite()) => {
                Err(InputError::new(
                    step_field,
                    format!("must be a finite positive number, got {}", short(step)),
                ))
            }
            _ => Ok(()),
        }
    }
}
