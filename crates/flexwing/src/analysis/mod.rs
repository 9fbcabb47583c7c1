//! What a run is: a validated plan in, an outcome out. This is the public way to run any
//! analysis; the command-line tool, the case-file crate and the Python front end all come here.
//!
//! | analysis | plan | run | outcome |
//! |---|---|---|---|
//! | natural modes | [`modes::ModesPlan`] | [`modes::run`] | [`modes::ModesOutcome`] |
//! | non-linear statics, load sweeps, loaded modes | [`statics::StaticPlan`] | [`statics::run`] | [`statics::StaticOutcome`] |
//! | non-linear dynamics | [`dynamics::DynamicPlan`] | [`dynamics::run`] | [`dynamics::DynamicOutcome`] |
//! | static aeroelasticity, divergence | [`aero::statics::AeroStaticPlan`] | [`aero::statics::run`] | [`aero::statics::AeroStaticOutcome`] |
//! | flutter (V-g, V-ω, p-k check) | [`aero::flutter::FlutterPlan`] | [`aero::flutter::run`] | [`aero::flutter::FlutterOutcome`] |
//! | gust and manoeuvre responses | [`aero::response::AeroDynamicPlan`] | [`aero::response::run`] | [`aero::response::AeroDynamicOutcome`] |
//! | discrete gust families (CS 25.341(a)) | [`aero::gust_family::GustFamilyPlan`] | [`aero::gust_family::run`] | [`aero::gust_family::GustFamilyOutcome`] |
//! | linear state-space models | [`aero::linearize::LinearizePlan`] | [`aero::linearize::run`] | [`aero::linearize::LinearizeOutcome`] |
//! | the 3-D chain: modes, statics, flutter, flutter against a load | [`chain3d::Chain3dPlan`] | [`chain3d::run`] | [`chain3d::Chain3dOutcome`] |
//! | any of these | [`Plan`] | [`run`] | [`Outcome`] |
//!
//! [`Plan`], [`run`] and [`Outcome`] are the one dispatcher every front end calls (the case
//! crate's `Case::plan` builds the plan): [`Outcome::entries`] says how each model ended,
//! [`Outcome::notes`] what its numbers mean that the status does not show.
//!
//! A plan is plain data: the full model, the loads and the settings. Build it (by hand, or from a
//! case file with the `flexwing-case` crate), then check it with its `validate`, which names the
//! offending field with the prefixes the caller passes (`validate("loads", "dynamic")` reports
//! `dynamic.rtol`, `loads[2].time.t`). `run(&plan, &mut progress)` validates again (fields named
//! relative to the plan), runs every model of the plan and returns the outcome: per model, the
//! results it reached and its [`Status`], which says why it stopped if it did ([`Stop`], data
//! for the front end to word). A model that stops does not stop the others.
//!
//! [`Progress`] reports what is running; a closure `|fraction: f64| …` or [`NoProgress`] will do.
//!
//! ```
//! use flexwing::analysis::{modes, statics, NoProgress};
//! use flexwing::model::{Force, Load};
//!
//! let model = flexwing::paper::table4_beam(20)?;
//! let plan = modes::ModesPlan::new(model.clone(), Some(4), "count")?;
//! let frequencies = modes::run(&plan, &mut NoProgress)?;
//! assert_eq!(frequencies.modes.len(), 4);
//!
//! let tip = Load::PointForce { span: 1.0, force: Force::Dead { fx: 0.0, fy: 10.0 } };
//! let mut plan = statics::StaticPlan::new(model, vec![tip]);
//! plan.reduced = vec![2];
//! plan.validate("loads", "static")?;
//! let equilibria = statics::run(&plan, &mut NoProgress)?;
//! assert!(equilibria.is_complete());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod aero;
pub mod chain3d;
pub mod dynamics;
mod models;
pub mod modes;
mod notes;
mod plan;
mod progress;
pub mod statics;
mod status;

pub use models::{ModelKind, ReducedChoice};
pub use notes::{NewtonAdvice, Note, NEWTON_NOTE_FAILURES, PLANAR_DEFLECTION_NOTE};
pub use plan::{run, Entry, Outcome, Plan};
pub use progress::{NoProgress, Progress};
pub use status::{Doubt, Status, Stop, STATUS_WORDS};

/// The caller's name of load `i` for messages: `names[i]`, else `loads[i]`.
pub(crate) fn load_name(names: &[String], i: usize) -> String {
    names
        .get(i)
        .cloned()
        .unwrap_or_else(|| format!("loads[{i}]"))
}
