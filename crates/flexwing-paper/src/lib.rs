//! # flexwing-paper
//!
//! The study of the results section of Veronese, Ribeiro & Moreira, *Reduced order modeling of
//! highly flexible structures* (COBEM 2021): every table and figure, beside the paper's printed
//! numbers ([`printed`]) and independent references ([`references`]). Not published: it is the
//! project's own study, rendered by `flexwing reproduce`.
//!
//! Each part computes first, then renders. An experiment ([`modal::run`],
//! [`statics::tip_force`], [`statics::two_forces`], [`sine::run`], [`release::run`]) builds its
//! cases from the example case files ([`cases`]), runs them through the library and returns its
//! numbers; separate methods of the returned study build the [`table::Table`]s (CSV and
//! Markdown), the [`figure::Figure`] data and the text of its [`Section`]; [`report`] puts the
//! conclusions and the sections together. The front end writes the files and draws the figures.

pub mod accuracy;
pub mod cases;
pub mod figure;
pub mod integrators;
pub mod modal;
pub mod printed;
pub mod references;
pub mod release;
pub mod report;
pub mod sine;
pub mod statics;
pub mod study;
pub mod table;
pub mod timing;

pub use report::Section;

use flexwing::analysis::dynamics::AuditedRun;
use flexwing::analysis::Stop;
use flexwing::model::{FullModel, PlanarModel};

/// Tip position `(x, y)` (m) of the full model at joint rotations `q`.
fn tip(full: &FullModel, q: &[f64]) -> (f64, f64) {
    let p = full.node_positions(&full.kinematics(q))[full.n_elements()];
    (p[0], p[1])
}

/// Tip positions `(x, y)` (m) of `model` at the output times of `run`.
fn tips<M: PlanarModel>(model: &M, run: &AuditedRun) -> Vec<(f64, f64)> {
    let full = model.full_model();
    let n = model.n_dofs();
    run.trajectory
        .y
        .iter()
        .map(|y| tip(full, &model.full_coordinates(&y[..n])))
        .collect()
}

/// Distance between two points `(x, y)` (m).
fn distance(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).hypot(a.1 - b.1)
}

/// Why a run stopped, in the library's one wording.
fn words(stop: &Stop) -> String {
    stop.to_string()
}

/// Why `run` stopped, worded, if it did.
fn stopped(run: &AuditedRun) -> Option<String> {
    run.stop().map(words)
}
