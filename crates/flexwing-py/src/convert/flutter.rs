//! [`FlutterOutcome`] into `FlutterResult`, its `FlutterRun`s and their `Stability` (the
//! eigen-analysis, and the p-k check): the data of the CLI's `flutter_summary.csv`,
//! `flutter_crossings.csv`, `flutter_vg.csv` and `flutter_equilibria.csv`
//! (crates/flexwing-cli/src/render/flutter.rs), as arrays.

use flexwing::analysis::aero::flutter::{FlutterOutcome, FlutterPlan, FlutterRun, Stability};
use flexwing::solve::aeroelastic::CrossingKind;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::aero_statics::{aerodynamics, equilibria, Equilibria};
use super::statics::kind_name;
use super::status::{described, overall, set_status};
use crate::arrays::{out1, out_rows};

/// The flutter outcome as the dict of `FlutterResult`.
pub fn raw<'py>(
    py: Python<'py>,
    plan: &FlutterPlan,
    outcome: &FlutterOutcome,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let runs = outcome
        .runs
        .iter()
        .map(|r| run(py, plan, r))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("runs", runs)?;
    d.set_item("speeds", out1(py, plan.speeds().to_vec()))?;
    d.set_item("root_angle", plan.flight.root_angle)?;
    d.set_item("gravity", plan.flight.gravity)?;
    d.set_item("aerodynamics", aerodynamics(py, &plan.aero)?)?;
    d.set_item("tolerance", plan.tolerance)?;
    d.set_item("status", overall(outcome.runs.iter().map(|r| &r.status)))?;
    Ok(d)
}

fn run<'py>(py: Python<'py>, plan: &FlutterPlan, r: &FlutterRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("label", r.kind.label())?;
    d.set_item("kind", kind_name(&r.kind))?;
    d.set_item("modes", r.kind.modes())?;
    d.set_item("dofs", r.dofs)?;
    d.set_item("wall_time_s", r.wall_time_s)?;
    set_status(&d, &r.status)?;
    let others = r
        .other_stops
        .iter()
        .map(|s| described(py, s))
        .collect::<PyResult<Vec<_>>>()?;
    d.set_item("other_stops", others)?;
    d.set_item("notes", super::dynamics::notes(py, &r.notes)?)?;
    d.set_item("divergence_speed", r.divergence.as_ref().map(|v| v.speed))?;
    d.set_item(
        "divergence_dynamic_pressure",
        r.divergence.as_ref().map(|v| v.dynamic_pressure),
    )?;
    d.set_item(
        "divergence_basis",
        r.divergence
            .as_ref()
            .map(|v| super::aero_statics::basis_word(v.basis)),
    )?;
    d.set_item(
        "divergence_within_sweep",
        r.divergence.as_ref().map(|v| v.within_sweep),
    )?;
    d.set_item("flutter_speed", r.stability.flutter.map(|c| c.speed))?;
    d.set_item(
        "flutter_frequency",
        r.stability.flutter.map(|c| c.frequency),
    )?;
    d.set_item("eigenvalues", stability(py, &r.stability)?)?;
    d.set_item("pk", r.pk.as_ref().map(|s| stability(py, s)).transpose()?)?;
    let eq = Equilibria {
        kind: &r.kind,
        dofs: r.dofs,
        wall_time_s: None,
        points: &r.equilibria,
        divergence: r.divergence.as_ref(),
        status: &r.equilibria_status,
    };
    d.set_item("equilibria", equilibria(py, &plan.model, &eq)?)?;
    Ok(d)
}

/// The dict of a `Stability`: branches as rows `(B, S)` over the speeds reached.
fn stability<'py>(py: Python<'py>, s: &Stability) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let n = s.speeds.len();
    d.set_item("speeds", out1(py, s.speeds.clone()))?;
    let b = &s.branches;
    d.set_item(
        "mode",
        PyArray1::from_vec(py, b.iter().map(|x| x.mode as i64).collect()),
    )?;
    d.set_item(
        "wet_frequency",
        out1(py, b.iter().map(|x| x.wet_frequency).collect()),
    )?;
    // Every branch has one eigenvalue per speed reached (the solver pushes them together).
    let real: Vec<&[f64]> = b.iter().map(|x| &x.real[..n.min(x.real.len())]).collect();
    let imag: Vec<&[f64]> = b.iter().map(|x| &x.imag[..n.min(x.imag.len())]).collect();
    let zeta: Vec<Vec<f64>> = b
        .iter()
        .map(|x| x.damping_ratios().into_iter().take(n).collect())
        .collect();
    let zeta: Vec<&[f64]> = zeta.iter().map(Vec::as_slice).collect();
    d.set_item("real", out_rows(py, &real, n))?;
    d.set_item("imag", out_rows(py, &imag, n))?;
    d.set_item("damping_ratio", out_rows(py, &zeta, n))?;
    d.set_item(
        "uncertain",
        PyArray1::from_vec(py, b.iter().map(|x| x.uncertain).collect()),
    )?;
    d.set_item("flutter_speed", s.flutter.map(|c| c.speed))?;
    d.set_item("flutter_frequency", s.flutter.map(|c| c.frequency))?;
    d.set_item("flutter_branch", s.flutter.map(|c| c.branch))?;
    let c = &s.crossings;
    let crossings = PyDict::new(py);
    let kinds: Vec<&str> = c
        .iter()
        .map(|x| match x.kind {
            CrossingKind::Onset => "onset",
            CrossingKind::Offset => "offset",
        })
        .collect();
    crossings.set_item("kind", kinds)?;
    crossings.set_item("speed", out1(py, c.iter().map(|x| x.speed).collect()))?;
    crossings.set_item(
        "frequency",
        out1(py, c.iter().map(|x| x.frequency).collect()),
    )?;
    crossings.set_item(
        "branch",
        PyArray1::from_vec(py, c.iter().map(|x| x.branch as i64).collect()),
    )?;
    crossings.set_item(
        "mode",
        PyArray1::from_vec(
            py,
            c.iter()
                .map(|x| b.get(x.branch).map_or(0, |br| br.mode as i64))
                .collect(),
        ),
    )?;
    d.set_item("crossings", crossings)?;
    d.set_item("unstable_at_start", s.unstable_at_start.clone())?;
    let stats = PyDict::new(py);
    stats.set_item("linearizations", s.stats.linearizations)?;
    stats.set_item("newton_iterations", s.stats.newton_iterations)?;
    stats.set_item("halvings", s.stats.halvings)?;
    stats.set_item("trials", s.stats.trials)?;
    stats.set_item("static_solves", s.stats.static_solves)?;
    d.set_item("stats", stats)?;
    d.set_item("wall_time_s", s.wall_time_s)?;
    Ok(d)
}
