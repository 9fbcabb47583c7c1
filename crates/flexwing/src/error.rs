//! Error types of the library.
//!
//! Every variant carries data, not prose; the `Display` impls turn them into one line that names
//! the field (or the solver state) and the problem.

use thiserror::Error;

/// Invalid input: a field of the beam, a load or an option has a value the model cannot use.
#[derive(Debug, Clone, PartialEq, Error)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
#[error("{field}: {reason}")]
pub struct InputError {
    /// Dotted path of the offending field, e.g. `beam.section.EI`.
    pub field: String,
    /// What is wrong with it.
    pub reason: String,
}

impl InputError {
    /// Build an error for `field` with the given reason.
    ///
    /// ```
    /// let e = flexwing::InputError::new("beam.length", "must be positive, got -1");
    /// assert_eq!(e.to_string(), "beam.length: must be positive, got -1");
    /// ```
    pub fn new(field: impl Into<String>, reason: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            reason: reason.into(),
        }
    }
}

/// A time for messages: at most 10 decimals, trailing zeros dropped, so that the rounding of
/// accumulated steps does not show (`0.8250000000000001` prints as `0.825`).
fn seconds(t: &f64) -> String {
    if !t.is_finite() {
        return format!("{t}");
    }
    let s = format!("{t:.10}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.into()
    }
}

/// What failed in a static step (data of [`SolveError::StaticDiverged`] and
/// [`SolveError::ArcLengthStalled`]). Serialized as `cause` (`"newton"`, `"too-far"`) beside the
/// error's other fields.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "cause", rename_all = "kebab-case")
)]
pub enum StaticFailure {
    /// Newton's method did not converge (or the residual became non-finite).
    Newton,
    /// Newton's iterates or solution moved more than the allowed rotation from the last
    /// equilibrium.
    TooFar {
        /// Largest change of an element's rotation (rad).
        rotation: f64,
        /// The limit (`max_rotation_step`, rad).
        limit: f64,
    },
}

fn divergence_detail(cause: &StaticFailure, iterations: usize, residual: f64) -> String {
    match cause {
        StaticFailure::Newton => format!(
            "residual {residual:.3e} after {iterations} Newton iterations with the smallest load step"
        ),
        StaticFailure::TooFar { rotation, limit } => format!(
            "with the smallest step the solution moved {rotation:.3} rad from the last \
             equilibrium, more than max_rotation_step = {limit} rad: a limit point of the path, or \
             too coarse a smallest step"
        ),
    }
}

/// Failure of a numerical algorithm. Serialized (feature `serde`) with its `kind`
/// (`"static-diverged"`, `"too-many-steps"`, …) beside its values.
#[derive(Debug, Clone, PartialEq, Error)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "kind", rename_all = "kebab-case")
)]
#[non_exhaustive]
pub enum SolveError {
    /// The mass matrix is not positive definite (a massless degree of freedom).
    #[error("mass matrix is not positive definite (is some degree of freedom massless?)")]
    MassNotPositiveDefinite,
    /// Load control could not reach the requested load even with the smallest load step: Newton
    /// did not converge there, or converged only to equilibria too far from the last one.
    #[error(
        "static solver did not converge: equilibrium found up to load factor {load_factor:.6}, \
         failed at {attempted:.6} ({})",
        divergence_detail(.cause, *.iterations, *.residual_norm)
    )]
    StaticDiverged {
        /// Last load factor (0 → 1) at which an equilibrium was found.
        load_factor: f64,
        /// Load factor of the failed attempt.
        attempted: f64,
        /// Newton iterations of the last failed attempt.
        iterations: usize,
        /// `‖K x − Q(x)‖∞` at the end of the last failed attempt (NaN if it blew up).
        residual_norm: f64,
        /// What failed.
        #[cfg_attr(feature = "serde", serde(flatten))]
        cause: StaticFailure,
    },
    /// Load control reached a critical point of the equilibrium path (buckling or a limit
    /// point): past `load_factor`, every equilibrium found down to the smallest load step is
    /// unstable (the static aeroelastic sweeps stop at the first unstable step instead, and
    /// locate the divergence themselves: `solve::statics::continue_static_to_instability`).
    #[error(
        "static load path loses stability at load factor {load_factor:.6}: the equilibria found \
         beyond it (tried up to {attempted:.6}) are unstable (buckling or a limit point); load \
         control stops there, arc-length continuation follows the path through it"
    )]
    StaticUnstable {
        /// Last load factor (0 → 1) at which a stable equilibrium was found.
        load_factor: f64,
        /// Load factor of the last attempt (its equilibrium was unstable).
        attempted: f64,
    },
    /// Arc-length continuation could not take a step, even with the smallest arc length.
    #[error(
        "arc-length continuation stopped at load factor {load_factor:.6} after {points} points: \
         no converged step with arc length {arc_length:.3e} ({})",
        divergence_detail(.cause, *.iterations, *.residual_norm)
    )]
    ArcLengthStalled {
        /// Load factor of the last point on the path.
        load_factor: f64,
        /// Points on the path so far (the start included).
        points: usize,
        /// The arc length of the last attempt.
        arc_length: f64,
        /// Newton iterations of the last attempt.
        iterations: usize,
        /// `‖K x − Q(x)‖∞` at the end of the last attempt.
        residual_norm: f64,
        /// What failed.
        #[cfg_attr(feature = "serde", serde(flatten))]
        cause: StaticFailure,
    },
    /// Arc-length continuation used up its budget of points before the target load.
    #[error(
        "arc-length continuation stopped at load factor {load_factor:.6}: {points} points \
         reached the limit max_points before the load factor reached 1"
    )]
    ArcLengthTooManyPoints {
        /// Load factor of the last point on the path.
        load_factor: f64,
        /// Points on the path (the start included).
        points: usize,
    },
    /// An input of the solver is invalid.
    #[error(transparent)]
    InvalidInput(InputError),
    /// The adaptive step size fell below what floating point can resolve.
    #[error("time integration stopped at t = {} s: step size {step:.3e} s too small", seconds(.time))]
    StepSizeTooSmall {
        /// Time reached (s).
        time: f64,
        /// Step size attempted (s).
        step: f64,
    },
    /// The run used up its budget of steps (`max_steps`), e.g. a solution that blows up.
    #[error(
        "time integration stopped at t = {} s: {steps} steps (accepted and rejected) reached the \
         limit max_steps",
        seconds(.time)
    )]
    TooManySteps {
        /// Time reached (s).
        time: f64,
        /// Steps taken, accepted and rejected.
        steps: usize,
    },
    /// Newton's method of an implicit step did not converge even on small sub-steps.
    #[error(
        "time integration stopped at t = {} s: Newton's method did not converge with step \
         {step:.3e} s",
        seconds(.time)
    )]
    NewtonFailed {
        /// Time reached (s).
        time: f64,
        /// Smallest step tried (s).
        step: f64,
    },
    /// The system being integrated asked the integrator to stop after an accepted step
    /// ([`crate::solve::integrate::OdeSystem::step_accepted`]): an energy audit that saw the
    /// run blow up, or a caller that interrupted it. The caller knows which and says so.
    #[error("time integration halted at t = {} s by its caller", seconds(.time))]
    Halted {
        /// Time reached (s).
        time: f64,
    },
    /// The right-hand side produced a non-finite value (NaN or infinity).
    #[error(
        "time integration stopped at t = {} s: the state became non-finite (NaN or infinity)",
        seconds(.time)
    )]
    NonFinite {
        /// Time reached (s).
        time: f64,
    },
    /// Modes were asked about a state whose tangent stiffness is not symmetric (follower loads).
    #[error(
        "modal analysis: the tangent stiffness is not symmetric (relative asymmetry {asymmetry:.2e}); \
         follower loads are non-conservative and are not supported for loaded modes"
    )]
    NonSymmetricTangent {
        /// `max |K_T − K_Tᵀ| / max |K_T|`.
        asymmetry: f64,
    },
    /// Modes were asked about a state whose tangent stiffness is not positive definite: an
    /// unstable equilibrium (or one at a bifurcation), which has no natural modes.
    #[error(
        "modal analysis: the tangent stiffness K − ∂Q/∂q has {non_positive} non-positive \
         eigenvalue(s): the equilibrium is unstable (or at a bifurcation) and has no natural modes"
    )]
    IndefiniteTangent {
        /// Number of eigenvalues of the tangent stiffness that are not positive.
        non_positive: usize,
    },
    /// The iterative eigensolver did not converge within its iteration budget.
    #[error(
        "modal analysis: the eigensolver converged {converged} of the {wanted} modes asked for \
         within its iteration limit"
    )]
    ModesNotConverged {
        /// Modes that converged (the lowest).
        converged: usize,
        /// Modes asked for.
        wanted: usize,
    },
    /// The symmetric eigensolver produced a non-finite or negative eigenvalue.
    #[error("modal analysis: eigenvalue {index} is {value} (stiffness not positive definite at this state?)")]
    BadEigenvalue {
        /// Index of the eigenvalue in ascending order.
        index: usize,
        /// The offending value of `ω²`.
        value: f64,
    },
}

impl SolveError {
    /// An input error found by a solver (bad tolerances, output times…).
    pub(crate) fn from_input(e: InputError) -> Self {
        SolveError::InvalidInput(e)
    }

    /// Whether the error is a failure to converge (as opposed to a singular problem).
    pub fn is_divergence(&self) -> bool {
        matches!(
            self,
            SolveError::StaticDiverged { .. } | SolveError::ArcLengthStalled { .. }
        )
    }

    /// The load factor reached by a static solver that stopped (the last equilibrium found), if
    /// the error comes from one.
    pub fn load_factor(&self) -> Option<f64> {
        match self {
            SolveError::StaticDiverged { load_factor, .. }
            | SolveError::StaticUnstable { load_factor, .. }
            | SolveError::ArcLengthStalled { load_factor, .. }
            | SolveError::ArcLengthTooManyPoints { load_factor, .. } => Some(*load_factor),
            _ => None,
        }
    }
}

/// Any error of the library.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// Invalid input.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A solver failed.
    #[error(transparent)]
    Solve(#[from] SolveError),
}

/// Result alias of the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_in_messages_hide_step_rounding() {
        let e = SolveError::StepSizeTooSmall {
            time: 0.825_000_000_000_000_1,
            step: 5.551e-16,
        };
        assert_eq!(
            e.to_string(),
            "time integration stopped at t = 0.825 s: step size 5.551e-16 s too small"
        );
        assert_eq!(seconds(&30.0), "30");
        assert_eq!(seconds(&1.5e-7), "0.00000015");
        assert_eq!(seconds(&f64::NAN), "NaN");
    }
}
