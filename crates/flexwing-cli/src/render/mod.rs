//! The renderers: one module per kind of [`Outcome`], each writing its result files, its text
//! report and its JSON document from the library's data. [`View`] pairs a plan with its outcome;
//! [`files`], [`text`] and [`json`] dispatch on it; the rest of this module is what the
//! renderers share (the header and footer of a report, the JSON document's frame, the
//! descriptions of loads and of the aerodynamics, shapes for plots).
//!
//! A new analysis of the library gets one module here, one arm of [`View`] and one arm in each
//! dispatcher (ARCHITECTURE.md, "Adding an analysis or a model").

mod aero_dynamic;
mod aero_static;
mod chain3d;
mod chain3d_dynamic;
mod dynamic;
mod flutter;
mod gust_family;
mod linearize;
mod modes;
mod statics;
mod table;
mod turbulence;
pub mod vtk;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::flutter::{FlutterOutcome, FlutterPlan};
use flexwing::analysis::aero::gust_family::{GustFamilyOutcome, GustFamilyPlan};
use flexwing::analysis::aero::linearize::{LinearStructure, LinearizeOutcome, LinearizePlan};
use flexwing::analysis::aero::response::{AeroDynamicOutcome, AeroDynamicPlan};
use flexwing::analysis::aero::statics::{AeroPoint, AeroStaticOutcome, AeroStaticPlan};
use flexwing::analysis::aero::turbulence::{TurbulenceOutcome, TurbulencePlan};
use flexwing::analysis::chain3d::{Chain3dOutcome, Chain3dPlan};
use flexwing::analysis::dynamics::{DynamicOutcome, DynamicPlan};
use flexwing::analysis::modes::{ModesOutcome, ModesPlan};
use flexwing::analysis::statics::{StaticOutcome, StaticPlan};
use flexwing::analysis::{Entry, Outcome, Plan};
use flexwing::model::aero::Aerodynamics;
use flexwing::model::{FullModel, Shape};
use flexwing_case::Case;
use serde::Serialize;

pub use dynamic::plot_indices;

use crate::output::short;
use crate::plot::ModelShapes;

/// What every renderer knows besides the plan and the outcome.
pub struct Context<'a> {
    /// The case file's path as given.
    pub name: &'a str,
    /// The case.
    pub case: &'a Case,
    /// What did not complete ([`Outcome::incomplete`]).
    pub incomplete: Vec<Entry>,
    /// The notes of the outcome, each `LABEL: NOTE` ([`Outcome::notes`]).
    pub notes: Vec<String>,
}

impl Context<'_> {
    /// The case's title, or the case file's name: what a plot is of.
    fn what(&self) -> String {
        self.case.title.clone().unwrap_or_else(|| {
            Path::new(self.name)
                .file_name()
                .map_or_else(String::new, |s| s.to_string_lossy().into_owned())
        })
    }

    /// Why the run of `label` did not complete, if it did not.
    fn message_of(&self, label: &str) -> Option<String> {
        self.incomplete
            .iter()
            .find(|e| e.label == label)
            .and_then(|e| e.status.message())
    }

    /// `LABEL: MESSAGE` of everything that did not complete, joined by `; `.
    fn error(&self) -> Option<String> {
        (!self.incomplete.is_empty()).then(|| {
            self.incomplete
                .iter()
                .map(|e| format!("{}: {}", e.label, e.status.message().unwrap_or_default()))
                .collect::<Vec<_>>()
                .join("; ")
        })
    }

    /// The worst status word.
    fn status(&self) -> &'static str {
        flexwing::analysis::Status::worst(self.incomplete.iter().map(|e| &e.status))
    }
}

/// A plan with its outcome, of the same kind.
#[non_exhaustive]
pub enum View<'a> {
    /// Natural modes.
    Modes(&'a ModesPlan, &'a ModesOutcome),
    /// Statics.
    Static(&'a StaticPlan, &'a StaticOutcome),
    /// Dynamics.
    Dynamic(&'a DynamicPlan, &'a DynamicOutcome),
    /// Static aeroelastic equilibria.
    AeroStatic(&'a AeroStaticPlan, &'a AeroStaticOutcome),
    /// Flutter.
    Flutter(&'a FlutterPlan, &'a FlutterOutcome),
    /// Aeroelastic response.
    AeroDynamic(&'a AeroDynamicPlan, &'a AeroDynamicOutcome),
    /// A discrete gust family.
    GustFamily(&'a GustFamilyPlan, &'a GustFamilyOutcome),
    /// Linear state-space models.
    Linearize(&'a LinearizePlan, &'a LinearizeOutcome),
    /// Output spectra and RMS in continuous turbulence.
    Turbulence(&'a TurbulencePlan, &'a TurbulenceOutcome),
    /// The 3-D chain's analyses.
    Chain3d(&'a Chain3dPlan, &'a Chain3dOutcome),
}

impl<'a> View<'a> {
    /// `plan` and `outcome` paired, if they are of the same kind (the outcome of `plan`).
    pub fn of(plan: &'a Plan, outcome: &'a Outcome) -> Option<Self> {
        Some(match (plan, outcome) {
            (Plan::Modes(p), Outcome::Modes(o)) => View::Modes(p, o),
            (Plan::Static(p), Outcome::Static(o)) => View::Static(p, o),
            (Plan::Dynamic(p), Outcome::Dynamic(o)) => View::Dynamic(p, o),
            (Plan::AeroStatic(p), Outcome::AeroStatic(o)) => View::AeroStatic(p, o),
            (Plan::Flutter(p), Outcome::Flutter(o)) => View::Flutter(p, o),
            (Plan::AeroDynamic(p), Outcome::AeroDynamic(o)) => View::AeroDynamic(p, o),
            (Plan::GustFamily(p), Outcome::GustFamily(o)) => View::GustFamily(p, o),
            (Plan::Linearize(p), Outcome::Linearize(o)) => View::Linearize(p, o),
            (Plan::Turbulence(p), Outcome::Turbulence(o)) => View::Turbulence(p, o),
            (Plan::Chain3d(p), Outcome::Chain3d(o)) => View::Chain3d(p, o),
            _ => return None,
        })
    }

    /// The line describing the model the analysis is of.
    fn model_line(&self) -> String {
        Some(match self {
            View::Chain3d(p, _) => return chain3d::model_line(p),
            View::Modes(p, _) => &p.model,
            View::Static(p, _) => &p.model,
            View::Dynamic(p, _) => &p.model,
            View::AeroStatic(p, _) => &p.model,
            View::Flutter(p, _) => &p.model,
            View::AeroDynamic(p, _) => &p.structure.model,
            View::GustFamily(p, _) => &p.response.structure.model,
            View::Linearize(p, _) => return structure_line(&p.model),
            View::Turbulence(p, _) => return structure_line(&p.linearize.model),
        })
        .map_or_else(String::new, model_line)
    }

    /// The aerodynamic model and the air density of an aeroelastic analysis.
    fn aero(&self) -> Option<(Aerodynamics, f64)> {
        let a = match self {
            View::AeroStatic(p, _) => &p.aero,
            View::Flutter(p, _) => &p.aero,
            View::AeroDynamic(p, _) => &p.aero,
            View::GustFamily(p, _) => &p.response.aero,
            View::Linearize(p, _) => &p.aero,
            View::Turbulence(p, _) => &p.linearize.aero,
            View::Chain3d(p, _) => return chain3d::aero(p),
            _ => return None,
        };
        Some((a.aerodynamics, a.density))
    }
}

/// Every result file a run of `plan` may write (besides `status.txt`): removed before a run, so
/// that a folder holds one run's files only.
pub fn previous_files(plan: &Plan) -> &'static [&'static str] {
    match plan {
        Plan::Modes(_) => modes::FILES,
        Plan::Static(_) => statics::FILES,
        Plan::Dynamic(_) => dynamic::FILES,
        Plan::AeroStatic(_) => aero_static::FILES,
        Plan::Flutter(_) => flutter::FILES,
        Plan::AeroDynamic(_) => aero_dynamic::FILES,
        Plan::GustFamily(_) => gust_family::FILES,
        Plan::Linearize(_) => linearize::FILES,
        Plan::Turbulence(_) => turbulence::FILES,
        Plan::Chain3d(p) => chain3d::previous_files(p),
        _ => &[],
    }
}

/// Write the result files of `view` into `dir` (plots with `plot`); the paths in order.
pub fn files(ctx: &Context, view: &View, dir: &Path, plot: bool) -> Result<Vec<PathBuf>> {
    crate::output::create_dir(dir)?;
    let mut written = match view {
        View::Modes(p, o) => modes::files(ctx, p, o, dir, plot),
        View::Static(p, o) => statics::files(ctx, p, o, dir, plot),
        View::Dynamic(p, o) => dynamic::files(ctx, p, o, dir, plot),
        View::AeroStatic(p, o) => aero_static::files(ctx, p, o, dir, plot),
        View::Flutter(p, o) => flutter::files(ctx, p, o, dir, plot),
        View::AeroDynamic(p, o) => aero_dynamic::files(ctx, p, o, dir, plot),
        View::GustFamily(p, o) => gust_family::files(ctx, p, o, dir, plot),
        View::Linearize(p, o) => linearize::files(ctx, p, o, dir),
        View::Turbulence(p, o) => turbulence::files(ctx, p, o, dir, plot),
        View::Chain3d(p, o) => chain3d::files(ctx, p, o, dir, plot),
    }?;
    if ctx.case.output.vtk() {
        written.extend(vtk::files(ctx, view, dir)?);
    }
    Ok(written)
}

/// The text report: the header, the renderer's tables, the footer.
pub fn text(ctx: &Context, view: &View, files: &[PathBuf]) -> String {
    let mut s = String::new();
    if let Some(title) = &ctx.case.title {
        let _ = writeln!(s, "{title}");
    }
    let _ = writeln!(s, "{}", view.model_line());
    if let Some((aerodynamics, density)) = view.aero() {
        let _ = writeln!(s, "{}", aero_line(aerodynamics, density));
    }
    match view {
        View::Modes(_, o) => modes::text(&mut s, o),
        View::Static(p, o) => statics::text(&mut s, p, o),
        View::Dynamic(p, o) => dynamic::text(ctx, &mut s, p, o),
        View::AeroStatic(p, o) => aero_static::text(&mut s, p, o),
        View::Flutter(p, o) => flutter::text(&mut s, ctx, p, o),
        View::AeroDynamic(p, o) => aero_dynamic::text(ctx, &mut s, p, o),
        View::GustFamily(p, o) => gust_family::text(ctx, &mut s, p, o),
        View::Linearize(p, o) => linearize::text(&mut s, p, o),
        View::Turbulence(_, o) => turbulence::text(ctx, &mut s, o),
        View::Chain3d(p, o) => chain3d::text(ctx, &mut s, p, o),
    }
    let _ = writeln!(s);
    let modes3d = matches!(
        view,
        View::Chain3d(_, flexwing::analysis::chain3d::Chain3dOutcome::Modes { .. })
    );
    if !matches!(view, View::Modes(..)) && !modes3d {
        if ctx.incomplete.is_empty() {
            let _ = writeln!(s, "status: complete");
        }
        for e in &ctx.incomplete {
            let message = e.status.message().unwrap_or_default();
            let _ = writeln!(s, "status: {}: {}: {message}", e.status.word(), e.label);
        }
    }
    for f in files {
        let _ = writeln!(s, "wrote {}", f.display());
    }
    s
}

/// The JSON document of `--json`: `case`, `title`, the renderer's fields, `files`, `status`,
/// `error`.
pub fn json(ctx: &Context, view: &View, files: &[PathBuf]) -> String {
    match view {
        View::Modes(p, o) => document(ctx, modes::json(p, o), files),
        View::Static(p, o) => document(ctx, statics::json(ctx, p, o), files),
        View::Dynamic(p, o) => document(ctx, dynamic::json(ctx, p, o), files),
        View::AeroStatic(p, o) => document(ctx, aero_static::json(ctx, p, o), files),
        View::Flutter(p, o) => document(ctx, flutter::json(ctx, p, o), files),
        View::AeroDynamic(p, o) => document(ctx, aero_dynamic::json(ctx, p, o), files),
        View::GustFamily(p, o) => document(ctx, gust_family::json(ctx, p, o), files),
        View::Linearize(p, o) => document(ctx, linearize::json(ctx, p, o), files),
        View::Turbulence(p, o) => document(ctx, turbulence::json(ctx, p, o), files),
        View::Chain3d(p, o) => document(ctx, chain3d::json(ctx, p, o), files),
    }
}

fn document<T: Serialize>(ctx: &Context, body: T, files: &[PathBuf]) -> String {
    #[derive(Serialize)]
    struct Document<'a, T> {
        case: &'a str,
        title: Option<&'a str>,
        #[serde(flatten)]
        body: T,
        files: Vec<String>,
        status: &'static str,
        error: Option<String>,
    }
    let doc = Document {
        case: ctx.name,
        title: ctx.case.title.as_deref(),
        body,
        files: files.iter().map(|f| f.display().to_string()).collect(),
        status: ctx.status(),
        error: ctx.error(),
    };
    // Plain structs of strings and numbers: serializing cannot fail; a non-finite number
    // becomes null.
    let mut text = serde_json::to_string_pretty(&doc).unwrap_or_default();
    text.push('\n');
    text
}

/// `Some(v)` for a finite `v`: what a CSV cell or a JSON number holds (empty, or null, else).
pub fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

/// One line describing the model: elements, dofs, calibration, torsion.
/// One line describing the structure of a linear model: the planar chain's or the 3-D chain's.
pub fn structure_line(model: &LinearStructure) -> String {
    match model {
        LinearStructure::Planar(full) => model_line(full),
        LinearStructure::Chain3d(chain) => chain3d::chain_line(chain),
    }
}

pub fn model_line(model: &FullModel) -> String {
    let beam = model.beam();
    let kind = if !model.has_torsion() {
        "bending only"
    } else if beam.offsets().iter().any(|&d| d != 0.0) {
        "bending and torsion coupled by the mass-centre offset d0"
    } else {
        "bending and torsion, uncoupled (d0 = 0)"
    };
    let (n, dofs) = (model.n_elements(), model.n_dofs());
    format!(
        "model: {n} element{}, {dofs} dof{}, {} calibration, {kind}",
        if n == 1 { "" } else { "s" },
        if dofs == 1 { "" } else { "s" },
        beam.calibration().name(),
    )
}

/// One line naming the aerodynamic model and the air.
pub fn aero_line(aerodynamics: Aerodynamics, density: f64) -> String {
    format!(
        "aerodynamics: {aerodynamics}, air density {} kg/m³",
        short(density)
    )
}

/// The node positions `(x, y)` of a shape: a polyline of a shape plot.
pub fn polyline(shape: &Shape) -> Vec<(f64, f64)> {
    shape
        .x
        .iter()
        .copied()
        .zip(shape.y.iter().copied())
        .collect()
}

/// The shapes of a model's equilibria for a shape plot.
pub fn equilibria_shapes(label: String, dashed: bool, points: &[AeroPoint]) -> ModelShapes {
    ModelShapes {
        label,
        dashed,
        shapes: points.iter().map(|p| polyline(&p.shape)).collect(),
    }
}

/// The width of a table's model column: the widest label, at least 10 characters.
pub fn label_width<'a>(labels: impl Iterator<Item = &'a flexwing::analysis::ModelKind>) -> usize {
    labels
        .map(|k| k.label().chars().count())
        .max()
        .unwrap_or(0)
        .max(10)
}

/// Named values serialized as one JSON object, in their order.
pub struct Fields<T>(pub Vec<(&'static str, T)>);

impl<T: Serialize> Serialize for Fields<T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap as _;
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}
