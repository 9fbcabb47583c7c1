//! [`AeroStaticOutcome`] into `AeroStaticResult` and its `AeroStaticRun`s; the equilibria of a
//! flutter run use the same `AeroStaticRun` ([`equilibria`]). The columns are those of the CLI's
//! `static_aero.csv` and `static_nodes.csv` (crates/flexwing-cli/src/render/aero_static.rs).

use flexwing::analysis::aero::statics::{AeroPoint, AeroStaticOutcome, AeroStaticPlan};
use flexwing::analysis::aero::Aero;
use flexwing::analysis::{ModelKind, Status};
use flexwing::model::aero::Aerodynamics;
use flexwing::model::FullModel;
use flexwing::solve::aeroelastic::{Divergence, DivergenceBasis};
use flexwing::solve::StaticStats;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::statics::{kind_name, stats_dict};
use super::status::{overall, set_status};
use crate::arrays::{out1, out_rows};

/// The aerodynamics as a dict: `model` (the case file's name), `states` per strip (Peters
/// only, else `None`), `density` (kg/m³).
pub fn aerodynamics<'py>(py: Python<'py>, aero: &Aero) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let (model, states) = match aero.aerodynamics {
        Aerodynamics::Steady => ("steady", None),
        Aerodynamics::QuasiSteady => ("quasi-steady", None),
        Aerodynamics::Wagner => ("wagner", None),
        Aerodynamics::Peters { states } => ("peters", Some(states)),
    };
    d.set_item("model", model)?;
    d.set_item("states", states)?;
    d.set_item("density", aero.density)?;
    let surfaces = aero
        .section
        .surfaces
        .iter()
        .map(|sf| {
            let s = PyDict::new(py);
            s.set_item("name", &sf.name)?;
            s.set_item("from", sf.from)?;
            s.set_item("to", sf.to)?;
            s.set_item("deflection", sf.deflection)?;
            Ok(s)
        })
        .collect::<PyResult<Vec<_>>>()?;
    if !surfaces.is_empty() {
        d.set_item("surfaces", surfaces)?;
    }
    Ok(d)
}

/// The static aeroelastic outcome as the dict of `AeroStaticResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &AeroStaticPlan,
    outcome: &AeroStaticOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| {
            let run = Equilibria {
                kind: &r.kind,
                dofs: r.dofs,
                wall_time_s: Some(r.wall_time_s),
                points: &r.points,
                divergence: r.divergence.as_ref(),
                status: &r.status,
            };
            equilibria(py, &plan.model, &run)
        })
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("speeds", out1(py, plan.speeds()))?;
    d.set_item("root_angle", plan.flight.root_angle)?;
    d.set_item("gravity", plan.flight.gravity)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.aero)?)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    Ok(d)
}

/// What an `AeroStaticRun` is made of: a static run's, or a flutter run's equilibria.
pub struct Equilibria<'a> {
    /// Which model.
    pub kind: &'a ModelKind,
    /// Its coordinates.
    pub dofs: usize,
    /// Wall time of the sweep (s); `None` inside a flutter run (timed as a whole).
    pub wall_time_s: Option<f64>,
    /// The equilibria reached.
    pub points: &'a [AeroPoint],
    /// The divergence speed found.
    pub divergence: Option<&'a Divergence>,
    /// How the sweep ended.
    pub status: &'a Status,
}

/// The dict of an `AeroStaticRun`.
pub fn equilibria<'py>(
    py: Python<'py>,
    model: &FullModel,
    r: &Equilibria<'_>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    set_status(&d, r.status)?;
    d.set_item("divergence_speed", r.divergence.map(|v| v.speed))?;
    d.set_item(
        "divergence_dynamic_pressure",
        r.divergence.map(|v| v.dynamic_pressure),
    )?;
    d.set_item(
        "divergence_basis",
        r.divergence.map(|v| basis_word(v.basis)),
    )?;
    d.set_item(
        "divergence_within_sweep",
        r.divergence.map(|v| v.within_sweep),
    )?;
    let points = r.points;
    let column = |f: &dyn Fn(&AeroPoint) -> f64| out1(py, points.iter().map(f).collect());
    d.set_item("speed", column(&|p| p.speed))?;
    d.set_item("dynamic_pressure", column(&|p| p.dynamic_pressure))?;
    d.set_item("tip_x", column(&|p| p.tip().0))?;
    d.set_item("tip_y", column(&|p| p.tip().1))?;
    d.set_item("tip_twist", column(&|p| p.tip().2))?;
    d.set_item("lift", column(&|p| p.lift))?;
    d.set_item("root_bending_moment", column(&|p| p.root_bending_moment))?;
    // `None` where no real mode diverges (as the CLI's `null`): no infinity in an output.
    let divergence: Vec<Option<f64>> = points
        .iter()
        .map(|p| p.divergence_pressure.filter(|v| v.is_finite()))
        .collect();
    d.set_item("divergence_pressure", divergence)?;
    let nodes = model.beam().nodes().len();
    let rows = |f: fn(&AeroPoint) -> &[f64], width: usize| {
        let r: Vec<&[f64]> = points.iter().map(f).collect();
        out_rows(py, &r, width)
    };
    d.set_item("x", rows(|p| &p.shape.x, nodes))?;
    d.set_item("y", rows(|p| &p.shape.y, nodes))?;
    d.set_item("twist", rows(|p| &p.shape.twist, nodes))?;
    d.set_item("q", rows(|p| &p.q, model.n_dofs()))?;
    let surfaces = points.first().map_or(0, |p| p.hinge_moments.len());
    d.set_item("hinge_moments", rows(|p| &p.hinge_moments, surfaces))?;
    let differences: Option<Vec<f64>> = points.iter().map(|p| p.tip_difference).collect();
    d.set_item(
        "tip_difference",
        differences
            .filter(|_| r.kind.modes().is_some())
            .map(|v| out1(py, v)),
    )?;
    let stats: Vec<StaticStats> = points.iter().map(|p| p.stats).collect();
    d.set_item("stats", stats_dict(py, &stats)?)?;
    Ok(d)
}

/// The word of a divergence speed's basis (the CLI's JSON word).
pub fn basis_word(basis: DivergenceBasis) -> &'static str {
    match basis {
        DivergenceBasis::Bracketed => "bracketed",
        DivergenceBasis::Undeformed => "undeformed",
    }
}
