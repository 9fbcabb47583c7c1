//! Notes on a run, as data: what made it slow or what its numbers mean that its [`Status`]
//! does not show, with the advice that follows from the model's data. The front ends word them
//! with their `Display` (the CLI on standard error, Python in `run.notes`); serialized (feature
//! `serde`) with their `kind` beside their values.
//!
//! [`Status`]: super::Status

use std::fmt;

use crate::model::FullModel;
use crate::solve::integrate::{IntegratorStats, Method};
use crate::text::short;

use super::{ModelKind, Stop};

/// A note on the run of one model. More variants may follow.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(tag = "kind", rename_all = "kebab-case")
)]
#[non_exhaustive]
pub enum Note {
    /// Most of the run's step attempts failed Newton (at least [`NEWTON_NOTE_FAILURES`], and at
    /// least half as many as were accepted): what made it slow.
    NewtonFailures {
        /// Step attempts whose Newton iteration failed.
        failed: usize,
        /// Accepted steps.
        steps: usize,
        /// What may avoid them, from the model's data.
        advice: NewtonAdvice,
    },
    /// The static equilibria of a flutter analysis stopped (past the divergence speed no stable
    /// equilibrium exists); the eigen-analysis went on about the last one found.
    EquilibriaStopped {
        /// Why they stopped.
        #[cfg_attr(
            feature = "serde",
            serde(serialize_with = "super::status::ser::described")
        )]
        stop: Stop,
    },
    /// A branch of a flutter analysis is already unstable at the first speed: it has no flutter
    /// speed (quasi-steady aerodynamics with the elastic axis at or aft of mid-chord).
    UnstableAtStart {
        /// Whether it is the p-k check's branch (else the eigen-analysis'); front ends name
        /// the check beside the model (`full p-k`).
        pk: bool,
        /// The wet mode it starts from, 1-based.
        mode: usize,
        /// Its wet frequency at `U = 0` (rad/s).
        wet_frequency: f64,
        /// The first speed of the sweep (m/s).
        speed: f64,
    },
    /// A linear model has poles with a positive real part: its equilibrium is dynamically
    /// unstable (past the flutter speed, or a divergence the static solver did not see).
    UnstablePoles {
        /// How many.
        count: usize,
        /// The largest real part (1/s).
        real: f64,
        /// Its frequency `|Im s|` (rad/s); 0 for a real pole.
        frequency: f64,
        /// The speed of the equilibrium (m/s).
        speed: f64,
    },
    /// The power spectrum of an output in turbulence falls no faster than `1/ω` at high
    /// frequency (`Φ_y ∝ ω^slope` beyond every pole): its variance diverges with the cut-off (an output
    /// with a direct feed-through of the gust's rate, whose variance is infinite in von Kármán
    /// and Dryden turbulence); its RMS is the part below `max_frequency`.
    VarianceDiverges {
        /// The output's name.
        output: String,
        /// The exponent `p` of `Φ_y ∝ ω^p` at high frequency.
        slope: f64,
        /// The cut-off (rad/s).
        max_frequency: f64,
    },
    /// A flutter analysis of the planar chain about an equilibrium whose tip is deflected by at
    /// least [`PLANAR_DEFLECTION_NOTE`] of the span: the planar chain bends in one plane and
    /// cannot couple torsion with lag through the flap deflection, and its flutter speed stays
    /// the undeformed wing's where the wing's own falls (docs/chain3d-model.md).
    PlanarDeflection {
        /// The largest tip deflection of the equilibria up to the flutter speed (m).
        tip_deflection: f64,
        /// The span (m).
        span: f64,
        /// The speed of that equilibrium (m/s).
        speed: f64,
    },
}

/// The least tip deflection, as a fraction of the span, for [`Note::PlanarDeflection`]: 2 %.
/// On Patil's wing the 3-D chain's flutter speed falls by `≈ 47 (δ/L)²` at small deflections
/// (the continuum rod of `tests/data/chain3d_reference/`: −0.8 % at `δ/L = 1.3 %`, −3.0 % at
/// 2.6 %, −27 % at 10 %), so at 2 % the planar chain's speed is already about 2 %
/// unconservative.
pub const PLANAR_DEFLECTION_NOTE: f64 = 0.02;

/// Least number of Newton failures for [`Note::NewtonFailures`].
pub const NEWTON_NOTE_FAILURES: usize = 20;

/// What may avoid a run's Newton failures (docs/model-choices.md, "Rotary inertia in bending" and
/// "The coupled beam's Newton failures").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(rename_all = "kebab-case")
)]
pub enum NewtonAdvice {
    /// A full model on bars with a mass offset: the section's flap inertia
    /// (`beam.section.rotary_inertia`) outweighs the twist-dependent in-plane inertia
    /// `m d0² sin²ψ`.
    FlapInertia,
    /// A full model of point masses: rigid bars (`beam.element_inertia = "bar"`) give the
    /// chain's highest pattern the inertia point masses lack; or generalized-α at a fixed step.
    Bars,
    /// Generalized-α already: a fixed step.
    FixedStep,
    /// A full model on bars: generalized-α with a fixed step.
    GeneralizedAlpha,
    /// A reduced model: a smaller `max_step` or tighter tolerances.
    SmallerSteps,
}

impl Note {
    /// The Newton note of a run of `kind` with `integrator` on `model` that ended with `stats`,
    /// if most of its steps failed Newton: on long full models of point masses this is the
    /// chain's alternating highest pattern, which has almost no inertia; on bars with a mass
    /// offset, the twist-dependent in-plane inertia remains.
    pub fn newton(
        kind: &ModelKind,
        integrator: Method,
        model: &FullModel,
        stats: &IntegratorStats,
    ) -> Option<Self> {
        let (failed, steps) = (stats.newton_failures, stats.steps);
        if failed < NEWTON_NOTE_FAILURES || 2 * failed < steps {
            return None;
        }
        let beam = model.beam();
        let point_masses = beam.bending_inertias().iter().all(|&j| j == 0.0);
        let offset = beam.offsets().iter().any(|&d| d != 0.0);
        let full = matches!(kind, ModelKind::Full | ModelKind::Simplified);
        let advice = match (integrator, full, point_masses) {
            (_, true, false) if offset => NewtonAdvice::FlapInertia,
            (_, true, true) => NewtonAdvice::Bars,
            (Method::GeneralizedAlpha, true, false) => NewtonAdvice::FixedStep,
            (_, true, false) => NewtonAdvice::GeneralizedAlpha,
            _ => NewtonAdvice::SmallerSteps,
        };
        Some(Note::NewtonFailures {
            failed,
            steps,
            advice,
        })
    }
}

impl fmt::Display for NewtonAdvice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            NewtonAdvice::FlapInertia => {
                "with a mass offset d0 the elements' bending inertia still varies with the \
                 twist; the section's flap inertia beam.section.rotary_inertia, when known, \
                 avoids this (docs/model-choices.md, \"The coupled beam's Newton failures\")"
            }
            NewtonAdvice::Bars => {
                "on long chains beam.element_inertia = \"bar\" avoids this (it gives the chain's \
                 highest pattern the inertia point masses lack; docs/model-choices.md, \"Rotary \
                 inertia in bending\"), as does integrator = \"generalized-alpha\" with a fixed \
                 `step`"
            }
            NewtonAdvice::FixedStep => "a fixed `step` (dynamic.step) may avoid this",
            NewtonAdvice::GeneralizedAlpha => {
                "integrator = \"generalized-alpha\" with a fixed `step` may avoid this \
                 (docs/performance.md, \"O(n) Newton systems\")"
            }
            NewtonAdvice::SmallerSteps => "a smaller max_step or tighter tolerances may help",
        })
    }
}

impl fmt::Display for Note {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Note::NewtonFailures {
                failed,
                steps,
                advice,
            } => write!(
                f,
                "{failed} step attempts failed Newton against {steps} accepted steps, which \
                 made the run slow; {advice}"
            ),
            Note::EquilibriaStopped { stop } => write!(
                f,
                "equilibria: {stop} (expected past the divergence speed; the eigen-analysis \
                 continues about the last equilibrium found)"
            ),
            Note::UnstableAtStart {
                mode,
                wet_frequency,
                speed,
                ..
            } => write!(
                f,
                "the branch of wet mode {mode} ({} rad/s at U = 0) is already unstable at the \
                 first speed, {} m/s: no flutter speed is given (with quasi-steady aerodynamics \
                 and the elastic axis at or aft of mid-chord the pitch damping vanishes; use \
                 wagner or peters)",
                short(*wet_frequency),
                short(*speed),
            ),
            Note::UnstablePoles {
                count,
                real,
                frequency,
                speed,
            } => write!(
                f,
                "the linear model at {} m/s is unstable: {count} pole{} with a positive real \
                 part, the largest {} 1/s at {} rad/s (past the flutter speed)",
                short(*speed),
                if *count == 1 { "" } else { "s" },
                short(*real),
                short(*frequency),
            ),
            Note::PlanarDeflection {
                tip_deflection,
                span,
                speed,
            } => write!(
                f,
                "the equilibrium at {} m/s has its tip deflected {} m ({:.1} % of the span): the \
                 planar chain bends in one plane and cannot couple torsion with lag through the \
                 flap deflection, so its flutter speed is the undeformed wing's while the \
                 deflected wing's falls (Patil's wing: by 27 % at a tip deflection of 10 % of \
                 the span); the 3-D chain models this (docs/chain3d-model.md)",
                short(*speed),
                short(*tip_deflection),
                100.0 * tip_deflection / span,
            ),
            Note::VarianceDiverges {
                output,
                slope,
                max_frequency,
            } => write!(
                f,
                "the power spectrum of {output} falls as ω^{} at high frequency, no faster \
                 than 1/ω: its variance diverges with the cut-off (the gust's rate feeds \
                 through, and its variance is infinite in this turbulence); its RMS is the part \
                 below max_frequency = {} rad/s",
                crate::text::significant(*slope, 3),
                short(*max_frequency)
            ),
        }
    }
}
