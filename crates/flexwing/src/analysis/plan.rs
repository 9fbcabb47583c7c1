//! The one dispatcher: any analysis of the library as a [`Plan`], run by [`run`] into an
//! [`Outcome`], and what every front end asks of an outcome whatever its kind: each model's
//! label and [`Status`] ([`Outcome::entries`]), the [`Note`]s ([`Outcome::notes`]), the status
//! of the whole analysis ([`Outcome::status`]).
//!
//! A new analysis joins as one variant of [`Plan`] and of [`Outcome`], one arm in [`run`] and
//! one in each method of [`Outcome`]; the case crate's `Case::plan` builds it and the front ends
//! render it (ARCHITECTURE.md, "Adding an analysis or a model").

use super::aero::flutter::{self, FlutterOutcome, FlutterPlan};
use super::aero::gust_family::{self, GustFamilyOutcome, GustFamilyPlan};
use super::aero::linearize::{self, LinearizeOutcome, LinearizePlan};
use super::aero::response::{self, AeroDynamicOutcome, AeroDynamicPlan};
use super::aero::statics::{self as aero_statics, AeroStaticOutcome, AeroStaticPlan};
use super::aero::turbulence::{self, TurbulenceOutcome, TurbulencePlan};
use super::chain3d::{self, Chain3dOutcome, Chain3dPlan};
use super::dynamics::{self, DynamicOutcome, DynamicPlan};
use super::modes::{self, ModesOutcome, ModesPlan};
use super::statics::{self, StaticOutcome, StaticPlan};
use super::{ModelKind, Note, Progress, Status, Stop};
use crate::error::Error;
use crate::model::FullModel;

/// Any analysis, validated.
// One plan is built per run: the size of its largest variant does not matter, and unboxed
// variants keep `Plan::Static(plan)` as plain to build and match as the plan itself.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Plan {
    /// Natural modes.
    Modes(ModesPlan),
    /// Non-linear statics.
    Static(StaticPlan),
    /// Non-linear dynamics.
    Dynamic(DynamicPlan),
    /// Static aeroelastic equilibria and divergence.
    AeroStatic(AeroStaticPlan),
    /// Flutter along a sweep in speed.
    Flutter(FlutterPlan),
    /// Aeroelastic response.
    AeroDynamic(AeroDynamicPlan),
    /// A discrete gust family (CS 25.341(a)): peaks per gust length, critical lengths.
    GustFamily(GustFamilyPlan),
    /// Linear state-space models about the static aeroelastic equilibrium.
    Linearize(LinearizePlan),
    /// Output spectra and RMS in continuous turbulence, through the linear model.
    Turbulence(TurbulencePlan),
    /// An analysis of the 3-D chain (modes, statics, flutter, the study against a load).
    Chain3d(Chain3dPlan),
}

/// What any analysis produced.
#[allow(clippy::large_enum_variant)] // one per run, as `Plan`
#[derive(Debug, Clone)]
#[non_exhaustive]
pub enum Outcome {
    /// Natural modes.
    Modes(ModesOutcome),
    /// Non-linear statics.
    Static(StaticOutcome),
    /// Non-linear dynamics.
    Dynamic(DynamicOutcome),
    /// Static aeroelastic equilibria and divergence.
    AeroStatic(AeroStaticOutcome),
    /// Flutter along a sweep in speed.
    Flutter(FlutterOutcome),
    /// Aeroelastic response.
    AeroDynamic(AeroDynamicOutcome),
    /// A discrete gust family.
    GustFamily(GustFamilyOutcome),
    /// Linear state-space models.
    Linearize(LinearizeOutcome),
    /// Output spectra and RMS in continuous turbulence.
    Turbulence(TurbulenceOutcome),
    /// An analysis of the 3-D chain.
    Chain3d(Chain3dOutcome),
}

impl Plan {
    /// `modes`, `static`, `dynamic`, `aero-static`, `flutter`, `aero-dynamic`, `gust-family`,
    /// `linearize` or `turbulence` (the 3-D chain's: [`Chain3dPlan::name`]).
    pub fn name(&self) -> &'static str {
        match self {
            Plan::Modes(_) => "modes",
            Plan::Static(_) => "static",
            Plan::Dynamic(_) => "dynamic",
            Plan::AeroStatic(_) => "aero-static",
            Plan::Flutter(_) => "flutter",
            Plan::AeroDynamic(_) => "aero-dynamic",
            Plan::GustFamily(_) => "gust-family",
            Plan::Linearize(_) => "linearize",
            Plan::Turbulence(_) => "turbulence",
            Plan::Chain3d(p) => p.name(),
        }
    }

    /// The planar full model (in vacuo) the analysis is of; `None` for the 3-D chain's (a
    /// linearization or turbulence analysis of it too).
    pub fn model(&self) -> Option<&FullModel> {
        Some(match self {
            Plan::Modes(p) => &p.model,
            Plan::Static(p) => &p.model,
            Plan::Dynamic(p) => &p.model,
            Plan::AeroStatic(p) => &p.model,
            Plan::Flutter(p) => &p.model,
            Plan::AeroDynamic(p) => &p.structure.model,
            Plan::GustFamily(p) => &p.response.structure.model,
            Plan::Linearize(p) => return p.model.planar(),
            Plan::Turbulence(p) => return p.linearize.model.planar(),
            Plan::Chain3d(_) => return None,
        })
    }

    /// Whether the analysis polls its caller's [`Progress::cancelled`] only between parts that
    /// may take long (a sweep's points, a flutter analysis' parts) rather than after every
    /// integrator step: a front end may then end the process on a second interrupt.
    pub fn checks_seldom(&self) -> bool {
        matches!(
            self,
            Plan::Static(_)
                | Plan::AeroStatic(_)
                | Plan::Flutter(_)
                | Plan::Linearize(_)
                | Plan::Turbulence(_)
        ) || matches!(self, Plan::Chain3d(p) if !matches!(p.analysis, chain3d::Analysis3d::Dynamic(_)))
    }
}

/// Run the analysis of `plan`: the `run` of its module ([`modes::run`], [`statics::run`], …).
///
/// # Errors
/// Those of the analysis' `run`: an invalid plan, or a failure before any model ran (the modal
/// analysis of the undeformed state). A model that stops is in the outcome with its
/// [`Status`].
pub fn run(plan: &Plan, progress: &mut dyn Progress) -> Result<Outcome, Error> {
    Ok(match plan {
        Plan::Modes(p) => Outcome::Modes(modes::run(p, progress)?),
        Plan::Static(p) => Outcome::Static(statics::run(p, progress)?),
        Plan::Dynamic(p) => Outcome::Dynamic(dynamics::run(p, progress)?),
        Plan::AeroStatic(p) => Outcome::AeroStatic(aero_statics::run(p, progress)?),
        Plan::Flutter(p) => Outcome::Flutter(flutter::run(p, progress)?),
        Plan::AeroDynamic(p) => Outcome::AeroDynamic(response::run(p, progress)?),
        Plan::GustFamily(p) => Outcome::GustFamily(gust_family::run(p, progress)?),
        Plan::Linearize(p) => Outcome::Linearize(linearize::run(p, progress)?),
        Plan::Turbulence(p) => Outcome::Turbulence(turbulence::run(p, progress)?),
        Plan::Chain3d(p) => Outcome::Chain3d(chain3d::run(p, progress)?),
    })
}

/// One thing an analysis ran and how it ended: a model's run, and for a static analysis the
/// loaded modes ([`Stop::LoadedModes`]), for a flutter analysis a p-k check that stopped after
/// its eigen-analysis (`full p-k`).
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// The model's label (`full`, `reduced-r2`), `loaded modes`, or `LABEL p-k`.
    pub label: String,
    /// How it ended.
    pub status: Status,
}

impl Outcome {
    /// How each model's run ended, in the order run, then what else the analysis ran that did
    /// not complete (see [`Entry`]). A modal analysis has none: it fails as a whole.
    pub fn entries(&self) -> Vec<Entry> {
        let entry = |kind: &ModelKind, status: &Status| Entry {
            label: kind.label(),
            status: status.clone(),
        };
        match self {
            Outcome::Modes(_) => Vec::new(),
            Outcome::Chain3d(o) => o
                .entries()
                .into_iter()
                .map(|(label, status)| Entry { label, status })
                .collect(),
            Outcome::Static(o) => {
                let mut v: Vec<Entry> = o.runs.iter().map(|r| entry(&r.kind, &r.status)).collect();
                if let Some(Err(e)) = &o.loaded_modes {
                    v.push(Entry {
                        label: "loaded modes".into(),
                        status: Status::Stopped(Stop::LoadedModes(e.clone())),
                    });
                }
                v
            }
            Outcome::Dynamic(o) => o.runs.iter().map(|r| entry(&r.kind, &r.status)).collect(),
            Outcome::AeroStatic(o) => o.runs.iter().map(|r| entry(&r.kind, &r.status)).collect(),
            Outcome::AeroDynamic(o) => o.runs.iter().map(|r| entry(&r.kind, &r.status)).collect(),
            Outcome::GustFamily(o) => o
                .statuses()
                .into_iter()
                .map(|(kind, status)| entry(kind, status))
                .collect(),
            Outcome::Linearize(o) => o.runs.iter().map(|r| entry(&r.kind, &r.status)).collect(),
            Outcome::Turbulence(o) => o
                .runs
                .iter()
                .map(|r| entry(&r.linear.kind, &r.status))
                .collect(),
            Outcome::Flutter(o) => o
                .runs
                .iter()
                .flat_map(|r| {
                    let others = r.other_stops.iter().map(|s| Entry {
                        label: format!("{} p-k", r.kind.label()),
                        status: Status::Stopped(s.clone()),
                    });
                    std::iter::once(entry(&r.kind, &r.status)).chain(others)
                })
                .collect(),
        }
    }

    /// The entries that did not complete ([`Outcome::entries`]), in order.
    pub fn incomplete(&self) -> Vec<Entry> {
        self.entries()
            .into_iter()
            .filter(|e| !e.status.is_complete())
            .collect()
    }

    /// The worst status word of the entries ([`Status::worst`]): `complete`, `suspect`,
    /// `stopped` or `interrupted`.
    pub fn status(&self) -> &'static str {
        Status::worst(self.entries().iter().map(|e| &e.status))
    }

    /// Whether every entry completed.
    pub fn is_complete(&self) -> bool {
        self.entries().iter().all(|e| e.status.is_complete())
    }

    /// The notes of every model's run with the label they are about (`full`, or `full p-k`
    /// for a note on the p-k check), in order.
    pub fn notes(&self) -> Vec<(String, &Note)> {
        fn of<'a>(kind: &ModelKind, notes: &'a [Note]) -> Vec<(String, &'a Note)> {
            let label = kind.label();
            notes
                .iter()
                .map(|n| match n {
                    Note::UnstableAtStart { pk: true, .. } => (format!("{label} p-k"), n),
                    _ => (label.clone(), n),
                })
                .collect()
        }
        match self {
            Outcome::Dynamic(o) => o.runs.iter().flat_map(|r| of(&r.kind, &r.notes)).collect(),
            Outcome::Flutter(o) => o.runs.iter().flat_map(|r| of(&r.kind, &r.notes)).collect(),
            Outcome::Linearize(o) => o.runs.iter().flat_map(|r| of(&r.kind, &r.notes)).collect(),
            Outcome::Turbulence(o) => o
                .runs
                .iter()
                .flat_map(|r| of(&r.linear.kind, &r.notes))
                .collect(),
            Outcome::Chain3d(o) => o.notes().into_iter().map(|n| ("full".into(), n)).collect(),
            _ => Vec::new(),
        }
    }
}
