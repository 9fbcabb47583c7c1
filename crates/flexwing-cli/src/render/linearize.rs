//! `flexwing linearize`: the linear state-space models of every model — `linear_LABEL.mat`
//! (MATLAB, `scipy.io.loadmat`), `linear_LABEL.npz` (NumPy), `linear_summary.csv`,
//! `linear_poles.csv`, and the whole of each model in the JSON document (`--json`). The
//! variables of the binary files: `A`, `B`, `C`, `D`, `state_names`, `state_units`,
//! `input_names`, `input_units`, `output_names`, `output_units`, `x0`, `u0`, `y0` (the
//! equilibrium's state, inputs and outputs), `speed` (m/s), `poles` (complex) — docs/control.md.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::linearize::{LinearizeOutcome, LinearizePlan, LinearizeRun};
use flexwing::solve::aeroelastic::{Signal, StateSpace};
use serde::Serialize;

use super::{finite, Context};
use crate::output;
use flexwing_io::{matfile, npz, Value};

pub const FILES: &[&str] = &["linear_summary.csv", "linear_poles.csv"];

/// Remove a previous run's `linear_*.mat` and `linear_*.npz` (their names follow its models).
fn remove_previous(dir: &Path) -> Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let path = entry?.path();
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if name.starts_with("linear_") && (name.ends_with(".mat") || name.ends_with(".npz")) {
            std::fs::remove_file(&path)?;
        }
    }
    Ok(())
}

#[derive(Serialize)]
struct SummaryRow {
    model: String,
    dofs: usize,
    aero_states: usize,
    states: Option<usize>,
    inputs: Option<usize>,
    outputs: Option<usize>,
    unstable_poles: Option<usize>,
    largest_real_part_1_s: Option<f64>,
    wall_time_s: Option<f64>,
    status: &'static str,
    error: Option<String>,
}

fn summaries<'a>(
    ctx: &'a Context,
    outcome: &'a LinearizeOutcome,
) -> impl Iterator<Item = SummaryRow> + 'a {
    outcome.runs.iter().map(|r| {
        let m = r.model.as_ref();
        SummaryRow {
            error: ctx.message_of(&r.kind.label()),
            model: r.kind.label(),
            dofs: r.dofs,
            aero_states: r.aero_states,
            states: m.map(|m| m.states.len()),
            inputs: m.map(|m| m.inputs.len()),
            outputs: m.map(|m| m.outputs.len()),
            unstable_poles: m.map(|_| r.poles.iter().filter(|p| p.re > 0.0).count()),
            largest_real_part_1_s: r.poles.first().and_then(|p| finite(p.re)),
            wall_time_s: finite(r.wall_time_s),
            status: r.status.word(),
        }
    })
}

#[derive(Serialize)]
struct PoleRow {
    model: String,
    real_1_s: Option<f64>,
    imag_rad_s: Option<f64>,
}

fn names(signals: &[Signal]) -> Vec<String> {
    signals.iter().map(|s| s.name.clone()).collect()
}

fn units(signals: &[Signal]) -> Vec<String> {
    signals.iter().map(|s| s.unit.to_string()).collect()
}

/// The named values of a model's MAT and NPZ files.
fn variables(
    plan: &LinearizePlan,
    run: &LinearizeRun,
    m: &StateSpace,
) -> Vec<(&'static str, Value)> {
    vec![
        ("A", Value::matrix(&m.a)),
        ("B", Value::matrix(&m.b)),
        ("C", Value::matrix(&m.c)),
        ("D", Value::matrix(&m.d)),
        ("state_names", Value::Strings(names(&m.states))),
        ("state_units", Value::Strings(units(&m.states))),
        ("input_names", Value::Strings(names(&m.inputs))),
        ("input_units", Value::Strings(units(&m.inputs))),
        ("output_names", Value::Strings(names(&m.outputs))),
        ("output_units", Value::Strings(units(&m.outputs))),
        ("x0", Value::column(&m.state_values)),
        ("u0", Value::column(&m.input_values)),
        ("y0", Value::column(&m.output_values)),
        ("speed", Value::scalar(plan.flight.speed)),
        (
            "poles",
            Value::Complex(run.poles.iter().map(|p| (p.re, p.im)).collect()),
        ),
    ]
}

pub fn files(
    ctx: &Context,
    plan: &LinearizePlan,
    outcome: &LinearizeOutcome,
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    remove_previous(dir)?;
    let summary = dir.join("linear_summary.csv");
    output::write_csv(&summary, summaries(ctx, outcome))?;
    let poles = dir.join("linear_poles.csv");
    output::write_csv(
        &poles,
        outcome.runs.iter().flat_map(|r| {
            r.poles.iter().map(|p| PoleRow {
                model: r.kind.label(),
                real_1_s: finite(p.re),
                imag_rad_s: finite(p.im),
            })
        }),
    )?;
    let mut files = vec![summary, poles];
    for r in &outcome.runs {
        let Some(m) = &r.model else { continue };
        let label = r.kind.label();
        let vars = variables(plan, r, m);
        let description = format!(
            "flexwing linear model ({label}) of {} at {} m/s",
            ctx.name, plan.flight.speed
        );
        let mat = dir.join(format!("linear_{label}.mat"));
        output::write_bytes(&mat, &matfile::bytes(&description, &vars))?;
        let npz_path = dir.join(format!("linear_{label}.npz"));
        output::write_bytes(&npz_path, &npz::bytes(&vars)?)?;
        files.push(mat);
        files.push(npz_path);
    }
    Ok(files)
}

pub fn text(s: &mut String, plan: &LinearizePlan, outcome: &LinearizeOutcome) {
    let f = &plan.flight;
    let _ = writeln!(
        s,
        "linear models about the static equilibrium at U = {} m/s, root angle {} rad ({} states)",
        f.speed,
        f.root_angle,
        plan.states.name()
    );
    for r in &outcome.runs {
        let _ = writeln!(s);
        let _ = writeln!(
            s,
            "{} ({} dofs, {} lag states):",
            r.kind.label(),
            r.dofs,
            r.aero_states
        );
        let Some(m) = &r.model else {
            let _ = writeln!(s, "no model: {}", r.status.message().unwrap_or_default());
            continue;
        };
        let _ = writeln!(
            s,
            "states {}, inputs {} ({}), outputs {} ({})",
            m.states.len(),
            m.inputs.len(),
            names(&m.inputs).join(", "),
            m.outputs.len(),
            names(&m.outputs).join(", ")
        );
        let unstable = r.poles.iter().filter(|p| p.re > 0.0).count();
        match r.poles.first() {
            Some(p) => {
                let _ = writeln!(
                    s,
                    "poles: {} ({unstable} unstable), largest real part {:.6} 1/s at {:.4} rad/s",
                    r.poles.len(),
                    p.re,
                    p.im.abs()
                );
            }
            None => {
                let _ = writeln!(s, "poles: not computed (the Schur form did not converge)");
            }
        }
        let _ = writeln!(s, "{:>24}  {:>14}  {:>8}", "output", "equilibrium", "unit");
        for (sig, v) in m.outputs.iter().zip(&m.output_values) {
            let _ = writeln!(s, "{:>24}  {v:>14.6e}  {:>8}", sig.name, sig.unit);
        }
        let _ = writeln!(s, "wall time: {:.3} ms", 1e3 * r.wall_time_s);
    }
}

#[derive(Serialize)]
pub struct Json {
    model: String,
    aerodynamics: String,
    speed_m_s: f64,
    root_angle_rad: f64,
    states: &'static str,
    models: Vec<JsonModel>,
}

#[derive(Serialize)]
struct JsonModel {
    summary: SummaryRow,
    state_space: Option<JsonStateSpace>,
    poles: Vec<[Option<f64>; 2]>,
}

#[derive(Serialize)]
struct JsonStateSpace {
    a: Vec<Vec<Option<f64>>>,
    b: Vec<Vec<Option<f64>>>,
    c: Vec<Vec<Option<f64>>>,
    d: Vec<Vec<Option<f64>>>,
    states: Vec<Signal>,
    inputs: Vec<Signal>,
    outputs: Vec<Signal>,
    x0: Vec<Option<f64>>,
    u0: Vec<Option<f64>>,
    y0: Vec<Option<f64>>,
}

fn rows(m: &nalgebra::DMatrix<f64>) -> Vec<Vec<Option<f64>>> {
    m.row_iter()
        .map(|r| r.iter().map(|v| finite(*v)).collect())
        .collect()
}

fn column(v: &[f64]) -> Vec<Option<f64>> {
    v.iter().map(|x| finite(*x)).collect()
}

pub fn json(ctx: &Context, plan: &LinearizePlan, outcome: &LinearizeOutcome) -> Json {
    Json {
        model: super::structure_line(&plan.model),
        aerodynamics: super::aero_line(plan.aero.aerodynamics, plan.aero.density),
        speed_m_s: plan.flight.speed,
        root_angle_rad: plan.flight.root_angle,
        states: plan.states.name(),
        models: summaries(ctx, outcome)
            .zip(&outcome.runs)
            .map(|(summary, r)| JsonModel {
                summary,
                state_space: r.model.as_ref().map(|m| JsonStateSpace {
                    a: rows(&m.a),
                    b: rows(&m.b),
                    c: rows(&m.c),
                    d: rows(&m.d),
                    states: m.states.clone(),
                    inputs: m.inputs.clone(),
                    outputs: m.outputs.clone(),
                    x0: column(&m.state_values),
                    u0: column(&m.input_values),
                    y0: column(&m.output_values),
                }),
                poles: r
                    .poles
                    .iter()
                    .map(|p| [finite(p.re), finite(p.im)])
                    .collect(),
            })
            .collect(),
    }
}
