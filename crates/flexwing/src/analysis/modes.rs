//! Modal analysis: the natural frequencies and mode shapes of the full model about its
//! undeformed state ([`crate::solve::Modes`], docs/model.md "Modes").

use super::Progress;
use crate::error::{InputError, SolveError};
use crate::model::FullModel;
use crate::solve::{ModeShape, Modes};

/// Number of modes reported when the plan does not say: `min(10, n_dofs)`.
pub const DEFAULT_COUNT: usize = 10;

/// A modal analysis, validated.
#[derive(Debug, Clone)]
pub struct ModesPlan {
    /// The full model.
    pub model: FullModel,
    /// Number of modes reported, `1 ..= n_dofs`.
    pub count: usize,
}

impl ModesPlan {
    /// The plan for `model` reporting `count` modes (`None`: [`DEFAULT_COUNT`], or every mode
    /// of a smaller model); `field` is the caller's name for `count`.
    ///
    /// # Errors
    /// `count` outside `1 ..= n_dofs`.
    pub fn new(model: FullModel, count: Option<usize>, field: &str) -> Result<Self, InputError> {
        let n_dofs = model.n_dofs();
        let count = match count {
            None => DEFAULT_COUNT.min(n_dofs),
            Some(c) if (1..=n_dofs).contains(&c) => c,
            Some(c) => {
                return Err(InputError::new(
                    field,
                    format!(
                        "must be between 1 and the number of degrees of freedom ({n_dofs}), \
                         got {c}"
                    ),
                ))
            }
        };
        Ok(Self { model, count })
    }
}

/// One mode.
#[derive(Debug, Clone)]
pub struct ModeResult {
    /// Mode number, 1-based.
    pub mode: usize,
    /// Circular frequency (rad/s).
    pub omega: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Share of the strain energy in the bending springs (1: pure bending, 0: pure torsion).
    pub bending_energy_fraction: f64,
    /// Nodal shape, mass-normalized; zeros carry no sign.
    pub shape: ModeShape,
}

/// What a modal analysis found.
#[derive(Debug, Clone)]
pub struct ModesOutcome {
    /// The first `count` modes, by increasing frequency.
    pub modes: Vec<ModeResult>,
}

/// Run the modal analysis of `plan`.
///
/// # Errors
/// The eigensolver's failure (a mass matrix that is not positive definite, a bad eigenvalue).
///
/// ```
/// use flexwing::analysis::{modes, NoProgress};
/// let plan = modes::ModesPlan::new(flexwing::paper::table4_beam(20)?, Some(3), "count")?;
/// let outcome = modes::run(&plan, &mut NoProgress)?;
/// // Euler–Bernoulli: 1.8751² √(EI / (m L⁴)) = 55.6 rad/s.
/// assert!((outcome.modes[0].omega / 55.6 - 1.0).abs() < 0.01);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(plan: &ModesPlan, progress: &mut dyn Progress) -> Result<ModesOutcome, SolveError> {
    progress.start(0, 1, "modes");
    let model = &plan.model;
    let modes = Modes::lowest(model, plan.count);
    progress.finish();
    let modes = modes?;
    Ok(ModesOutcome {
        modes: (0..plan.count.min(modes.n_modes()))
            .map(|k| mode_result(model, &modes, k))
            .collect(),
    })
}

/// Mode `k` (0-based) of `modes` as reported.
pub(crate) fn mode_result(model: &FullModel, modes: &Modes, k: usize) -> ModeResult {
    let mut shape = modes.shape(model, k);
    for v in [&mut shape.x, &mut shape.dx, &mut shape.dy, &mut shape.twist] {
        v.iter_mut().for_each(|x| *x += 0.0);
    }
    let omega = modes.omega()[k];
    ModeResult {
        mode: k + 1,
        omega,
        frequency_hz: omega / (2.0 * std::f64::consts::PI),
        bending_energy_fraction: modes.bending_energy_fraction(model, k),
        shape,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_defaults_and_limits() {
        let model = crate::paper::table1_beam(16).unwrap();
        assert_eq!(ModesPlan::new(model.clone(), None, "n").unwrap().count, 10);
        let small = crate::paper::table4_beam(4).unwrap();
        assert_eq!(ModesPlan::new(small, None, "n").unwrap().count, 4);
        assert_eq!(
            ModesPlan::new(model.clone(), Some(3), "n").unwrap().count,
            3
        );
        let e = ModesPlan::new(model.clone(), Some(0), "modes.count").unwrap_err();
        assert_eq!(
            e.to_string(),
            "modes.count: must be between 1 and the number of degrees of freedom (32), got 0"
        );
        assert!(ModesPlan::new(model, Some(33), "--count")
            .unwrap_err()
            .to_string()
            .starts_with("--count:"));
    }
}
