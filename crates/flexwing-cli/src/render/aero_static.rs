//! `flexwing static` on a case with `[aero]`: the static aeroelastic equilibria of every model at
//! each speed and the divergence speed; `static_aero.csv`, `static_nodes.csv`,
//! `static_summary.csv` and the shape plot. Non-finite numbers (none expected) are written as
//! empty fields (CSV) or `null` (JSON). The rows are shared with the equilibria of `flexwing
//! flutter`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::statics::{AeroPoint, AeroStaticOutcome, AeroStaticPlan};
use flexwing::analysis::ModelKind;
use flexwing::solve::aeroelastic::Divergence;
use serde::Serialize;

use super::{equilibria_shapes, finite, Context};
use crate::output::{self, short};
use crate::plot::{self, ShapePlot};

pub const FILES: &[&str] = &[
    "static_aero.csv",
    "static_hinges.csv",
    "static_nodes.csv",
    "static_summary.csv",
    "static_shapes.svg",
    "static_shapes.png",
];

/// A row of `static_aero.csv` (and of `flutter_equilibria.csv`, without the last two columns).
#[derive(Serialize)]
pub struct PointRow {
    pub model: String,
    pub speed_m_s: Option<f64>,
    pub dynamic_pressure_pa: Option<f64>,
    pub tip_x_m: Option<f64>,
    pub tip_y_m: Option<f64>,
    pub tip_twist_rad: Option<f64>,
    pub lift_n: Option<f64>,
    pub root_bending_moment_n_m: Option<f64>,
    pub divergence_pressure_pa: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tip_difference_m: Option<Option<f64>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub iterations: Option<usize>,
}

/// A row of the node files of the aeroelastic equilibria (`static_nodes.csv`,
/// `flutter_nodes.csv`).
#[derive(Serialize)]
pub struct NodeRow {
    model: String,
    speed_m_s: Option<f64>,
    node: usize,
    x_m: Option<f64>,
    y_m: Option<f64>,
    twist_rad: Option<f64>,
}

/// The rows of `points`, of the model `kind`; with `full`, the columns of `static_aero.csv`.
pub fn point_rows<'a>(
    kind: &'a ModelKind,
    points: &'a [AeroPoint],
    full: bool,
) -> impl Iterator<Item = PointRow> + 'a {
    points.iter().map(move |p| {
        let (x, y, twist) = p.tip();
        PointRow {
            model: kind.label(),
            speed_m_s: finite(p.speed),
            dynamic_pressure_pa: finite(p.dynamic_pressure),
            tip_x_m: finite(x),
            tip_y_m: finite(y),
            tip_twist_rad: finite(twist),
            lift_n: finite(p.lift),
            root_bending_moment_n_m: finite(p.root_bending_moment),
            divergence_pressure_pa: p.divergence_pressure.and_then(finite),
            tip_difference_m: full.then(|| p.tip_difference.and_then(finite)),
            iterations: full.then_some(p.stats.iterations),
        }
    })
}

/// The node rows of `points`, of the model `kind`.
pub fn node_rows<'a>(
    kind: &'a ModelKind,
    points: &'a [AeroPoint],
) -> impl Iterator<Item = NodeRow> + 'a {
    points.iter().flat_map(move |p| {
        (0..p.shape.x.len()).map(move |i| NodeRow {
            model: kind.label(),
            speed_m_s: finite(p.speed),
            node: i,
            x_m: finite(p.shape.x[i]),
            y_m: finite(p.shape.y[i]),
            twist_rad: finite(p.shape.twist[i]),
        })
    })
}

/// A row of `static_hinges.csv` (written when the wing has control surfaces): the hinge moment
/// of one surface at one equilibrium.
#[derive(Serialize)]
pub struct HingeRow {
    model: String,
    speed_m_s: Option<f64>,
    surface: String,
    deflection_rad: f64,
    hinge_moment_n_m: Option<f64>,
}

/// The hinge rows of `points`, of the model `kind`, for the surfaces of `plan`.
fn hinge_rows<'a>(
    plan: &'a AeroStaticPlan,
    kind: &'a ModelKind,
    points: &'a [AeroPoint],
) -> impl Iterator<Item = HingeRow> + 'a {
    points.iter().flat_map(move |p| {
        plan.aero
            .section
            .surfaces
            .iter()
            .zip(&p.hinge_moments)
            .map(move |(sf, &h)| HingeRow {
                model: kind.label(),
                speed_m_s: finite(p.speed),
                surface: sf.name.clone(),
                deflection_rad: sf.deflection,
                hinge_moment_n_m: finite(h),
            })
    })
}

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    wall_time_s: Option<f64>,
    divergence_speed_m_s: Option<f64>,
    /// False: the divergence speed lies beyond the sweep (not reached by it).
    divergence_within_sweep: Option<bool>,
    status: &'static str,
    error: Option<String>,
}

fn summaries<'a>(
    ctx: &'a Context,
    outcome: &'a AeroStaticOutcome,
) -> impl Iterator<Item = SummaryRow> + 'a {
    outcome.runs.iter().map(|r| SummaryRow {
        error: ctx.message_of(&r.kind.label()),
        model: r.kind.label(),
        dofs: r.dofs,
        wall_time_s: finite(r.wall_time_s),
        divergence_speed_m_s: r.divergence.as_ref().and_then(|d| finite(d.speed)),
        divergence_within_sweep: r.divergence.as_ref().map(|d| d.within_sweep),
        status: r.status.word(),
    })
}

pub fn files(
    ctx: &Context,
    plan: &AeroStaticPlan,
    outcome: &AeroStaticOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let runs = &outcome.runs;
    let points = dir.join("static_aero.csv");
    output::write_csv(
        &points,
        runs.iter()
            .flat_map(|r| point_rows(&r.kind, &r.points, true)),
    )?;
    let nodes = dir.join("static_nodes.csv");
    output::write_csv(
        &nodes,
        runs.iter().flat_map(|r| node_rows(&r.kind, &r.points)),
    )?;
    let summary = dir.join("static_summary.csv");
    output::write_csv(&summary, summaries(ctx, outcome))?;
    let mut files = vec![points, nodes, summary];
    if !plan.aero.section.surfaces.is_empty() {
        let hinges = dir.join("static_hinges.csv");
        output::write_csv(
            &hinges,
            runs.iter()
                .flat_map(|r| hinge_rows(plan, &r.kind, &r.points)),
        )?;
        files.push(hinges);
    }
    if with_plot {
        let plot = ShapePlot {
            title: format!("Static aeroelastic equilibria: {}", ctx.what()),
            length: plan.model.beam().length(),
            models: runs
                .iter()
                .map(|r| {
                    let label = format!("{} ({} dofs)", r.kind.label(), r.dofs);
                    equilibria_shapes(label, r.kind.modes().is_some(), &r.points)
                })
                .collect(),
            gradient: false,
        };
        files.extend(plot::write_shapes(dir, "static_shapes", &plot)?);
    }
    Ok(files)
}

/// The divergence line of a model's report.
pub fn divergence_line(d: Option<&Divergence>) -> String {
    match d {
        Some(d) if d.within_sweep => format!("divergence speed: {:.5} m/s", d.speed),
        Some(d) => format!(
            "divergence speed: {:.5} m/s, beyond the sweep and not reached by it: the linear \
             divergence speed of the undeformed wing, which stayed undeformed at every speed of \
             the sweep",
            d.speed
        ),
        None => "divergence speed: not reached".into(),
    }
}

pub fn text(s: &mut String, plan: &AeroStaticPlan, outcome: &AeroStaticOutcome) {
    let _ = writeln!(s, "static aeroelastic equilibria (steady strip theory)");
    for r in &outcome.runs {
        let _ = writeln!(s);
        let _ = writeln!(s, "{} ({} dofs):", r.kind.label(), r.dofs);
        let _ = writeln!(
            s,
            "{:>10}  {:>11}  {:>11}  {:>12}  {:>10}  {:>12}  {:>4}",
            "U (m/s)", "tip x (m)", "tip y (m)", "twist (rad)", "lift (N)", "root M (N·m)", "iter"
        );
        for p in &r.points {
            let (x, y, twist) = p.tip();
            let _ = writeln!(
                s,
                "{:>10}  {x:>11.6}  {y:>11.6}  {twist:>12.6}  {:>10.4}  {:>12.4}  {:>4}",
                short(p.speed),
                p.lift,
                p.root_bending_moment,
                p.stats.iterations
            );
        }
        let surfaces = &plan.aero.section.surfaces;
        if !surfaces.is_empty() {
            let _ = writeln!(s, "hinge moments (N·m, trailing edge down positive):");
            for p in &r.points {
                let list: Vec<String> = surfaces
                    .iter()
                    .zip(&p.hinge_moments)
                    .map(|(sf, h)| format!("{} (δ = {} rad) {h:.6}", sf.name, short(sf.deflection)))
                    .collect();
                let _ = writeln!(s, "  U = {} m/s: {}", short(p.speed), list.join(", "));
            }
        }
        let _ = writeln!(s, "{}", divergence_line(r.divergence.as_ref()));
        let _ = writeln!(s, "wall time: {:.3} ms", 1e3 * r.wall_time_s);
    }
}

#[derive(Serialize)]
pub struct Json {
    model: String,
    aerodynamics: String,
    models: Vec<JsonModel>,
}

#[derive(Serialize)]
struct JsonModel {
    summary: SummaryRow,
    points: Vec<PointRow>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    hinge_moments: Vec<HingeRow>,
}

pub fn json(ctx: &Context, plan: &AeroStaticPlan, outcome: &AeroStaticOutcome) -> Json {
    Json {
        model: super::model_line(&plan.model),
        aerodynamics: super::aero_line(plan.aero.aerodynamics, plan.aero.density),
        models: summaries(ctx, outcome)
            .zip(&outcome.runs)
            .map(|(summary, r)| JsonModel {
                summary,
                points: point_rows(&r.kind, &r.points, true).collect(),
                hinge_moments: hinge_rows(plan, &r.kind, &r.points).collect(),
            })
            .collect(),
    }
}
