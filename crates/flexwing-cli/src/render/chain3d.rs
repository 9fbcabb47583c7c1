//! The 3-D chain's runs (`beam.model = "chain3d"`; `dynamic` in `chain3d_dynamic.rs`): `flexwing
//! modes|static|flutter|study` (`static` with `[aero]`: the static aeroelastic equilibria,
//! `static_aero.csv`, `static_strips.csv`) write the node `x, y, z` and each element's section rotation (a
//! rotation vector, written at the element's outboard node) in their CSV files, a table, and a
//! JSON document that is the library's serialized outcome (`flexwing::analysis::chain3d`);
//! `study` also plots the flutter speed against the tip deflection beside the undeformed wing's.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::chain3d::{
    AeroStatic3dOutcome, Analysis3d, Chain3dOutcome, Chain3dPlan, Equilibrium3d, Flutter3dOutcome,
    Mode3d, Shape3dData, Stability3d, Static3dOutcome, Study3dOutcome,
};
use serde::Serialize;

use super::{finite, Context};
use crate::output;
use crate::plot::{write_lines, LinePlot, Panel, Series};

/// Every file a 3-D run of `plan` may write.
pub fn previous_files(plan: &Chain3dPlan) -> &'static [&'static str] {
    match plan.analysis {
        Analysis3d::Dynamic(_) => super::chain3d_dynamic::FILES,
        _ => FILES,
    }
}

/// Every file a 3-D run but a dynamic one may write.
pub const FILES: &[&str] = &[
    "frequencies.csv",
    "mode_shapes.csv",
    "static_tip.csv",
    "static_nodes.csv",
    "static_aero.csv",
    "static_strips.csv",
    "loaded_frequencies.csv",
    "flutter_summary.csv",
    "flutter_vg.csv",
    "flutter_equilibria.csv",
    "flutter_nodes.csv",
    "study.csv",
    "study.svg",
    "study.png",
];

/// One line describing the chain.
pub fn model_line(plan: &Chain3dPlan) -> String {
    chain_line(&plan.model)
}

/// One line describing a 3-D chain.
pub fn chain_line(m: &flexwing::model::Chain3d) -> String {
    format!(
        "model: 3-D chain, {} elements, {} dofs (twist, lag, flap per joint), {} calibration",
        m.n_elements(),
        m.n_dofs(),
        match m.beam().calibration() {
            flexwing::model::chain3d::JointCalibration::Compliance => "compliance",
            flexwing::model::chain3d::JointCalibration::TipLoad => "tip-load",
        }
    )
}

/// The aerodynamics of a static aeroelastic, flutter or study plan.
pub fn aero(plan: &Chain3dPlan) -> Option<(flexwing::model::aero::Aerodynamics, f64)> {
    let f = match &plan.analysis {
        Analysis3d::Flutter(f) => f,
        Analysis3d::Study(s) => &s.flutter,
        Analysis3d::AeroStatic(a) => return Some((a.aero.aerodynamics, a.aero.density)),
        _ => return None,
    };
    Some((f.aero.aerodynamics, f.aero.density))
}

#[derive(Serialize)]
struct NodeRow {
    point: usize,
    value: f64,
    node: usize,
    span_m: f64,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    rx_rad: Option<f64>,
    ry_rad: Option<f64>,
    rz_rad: Option<f64>,
}

/// The rows of one shape: node `k` with the rotation of element `k − 1` (none at the root).
fn node_rows(point: usize, value: f64, s: &Shape3dData) -> impl Iterator<Item = NodeRow> + '_ {
    (0..s.position.len()).map(move |k| {
        let r = k.checked_sub(1).map(|e| s.rotation[e]);
        NodeRow {
            point,
            value,
            node: k,
            span_m: s.span[k],
            x_m: s.position[k][0],
            y_m: s.position[k][1],
            z_m: s.position[k][2],
            rx_rad: r.map(|r| r[0]),
            ry_rad: r.map(|r| r[1]),
            rz_rad: r.map(|r| r[2]),
        }
    })
}

#[derive(Serialize)]
struct FrequencyRow {
    mode: usize,
    omega_rad_s: f64,
    frequency_hz: f64,
    twist_energy_fraction: f64,
    lag_energy_fraction: f64,
    flap_energy_fraction: f64,
}

fn frequency_rows(modes: &[Mode3d]) -> impl Iterator<Item = FrequencyRow> + '_ {
    modes.iter().map(|m| FrequencyRow {
        mode: m.mode,
        omega_rad_s: m.omega,
        frequency_hz: m.frequency_hz,
        twist_energy_fraction: m.energy_fraction.twist,
        lag_energy_fraction: m.energy_fraction.lag,
        flap_energy_fraction: m.energy_fraction.flap,
    })
}

#[derive(Serialize)]
struct ModeShapeRow {
    mode: usize,
    node: usize,
    span_m: f64,
    x_m: f64,
    y_m: f64,
    z_m: f64,
    dx_m: f64,
    dy_m: f64,
    dz_m: f64,
    rx_rad: Option<f64>,
    ry_rad: Option<f64>,
    rz_rad: Option<f64>,
}

pub fn files(
    ctx: &Context,
    plan: &Chain3dPlan,
    outcome: &Chain3dOutcome,
    dir: &Path,
    plot: bool,
) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    match outcome {
        Chain3dOutcome::Modes { modes, shape } => {
            let f = dir.join("frequencies.csv");
            output::write_csv(&f, frequency_rows(modes))?;
            files.push(f);
            let f = dir.join("mode_shapes.csv");
            output::write_csv(
                &f,
                modes.iter().flat_map(|m| {
                    (0..shape.position.len()).map(move |k| {
                        let r = k.checked_sub(1).map(|e| m.rotation[e]);
                        ModeShapeRow {
                            mode: m.mode,
                            node: k,
                            span_m: shape.span[k],
                            x_m: shape.position[k][0],
                            y_m: shape.position[k][1],
                            z_m: shape.position[k][2],
                            dx_m: m.displacement[k][0],
                            dy_m: m.displacement[k][1],
                            dz_m: m.displacement[k][2],
                            rx_rad: r.map(|r| r[0]),
                            ry_rad: r.map(|r| r[1]),
                            rz_rad: r.map(|r| r[2]),
                        }
                    })
                }),
            )?;
            files.push(f);
        }
        Chain3dOutcome::Static(o) => static_files(o, dir, &mut files)?,
        Chain3dOutcome::AeroStatic(o) => aero_static_files(o, dir, &mut files)?,
        Chain3dOutcome::Flutter(o) => flutter_files(o, dir, &mut files)?,
        Chain3dOutcome::Dynamic(o) => {
            if let Analysis3d::Dynamic(d) = &plan.analysis {
                files.extend(super::chain3d_dynamic::files(ctx, d, o, dir, plot)?);
            }
        }
        Chain3dOutcome::Study(o) => {
            let f = dir.join("study.csv");
            output::write_csv(&f, study_rows(o))?;
            files.push(f);
            if plot {
                files.extend(study_plot(ctx, o, dir)?);
            }
        }
    }
    Ok(files)
}

#[derive(Serialize)]
struct StaticTipRow {
    point: usize,
    scale: f64,
    tip_x_m: f64,
    tip_y_m: f64,
    tip_z_m: f64,
    stable: Option<bool>,
    iterations: usize,
}

fn static_files(o: &Static3dOutcome, dir: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    let f = dir.join("static_tip.csv");
    output::write_csv(
        &f,
        o.points.iter().enumerate().map(|(i, p)| {
            let t = p.shape.tip();
            StaticTipRow {
                point: i,
                scale: p.scale,
                tip_x_m: t[0],
                tip_y_m: t[1],
                tip_z_m: t[2],
                stable: p.stable,
                iterations: p.stats.iterations,
            }
        }),
    )?;
    files.push(f);
    let f = dir.join("static_nodes.csv");
    output::write_csv(
        &f,
        o.points
            .iter()
            .enumerate()
            .flat_map(|(i, p)| node_rows(i, p.scale, &p.shape)),
    )?;
    files.push(f);
    if let Some(modes) = &o.loaded_modes {
        let f = dir.join("loaded_frequencies.csv");
        output::write_csv(&f, frequency_rows(modes))?;
        files.push(f);
    }
    Ok(())
}

#[derive(Serialize)]
struct SummaryRow {
    method: &'static str,
    flutter_speed_m_s: Option<f64>,
    flutter_frequency_rad_s: Option<f64>,
    divergence_speed_m_s: Option<f64>,
    status: &'static str,
}

#[derive(Serialize)]
struct VgRow {
    method: &'static str,
    mode: usize,
    speed_m_s: f64,
    real_1_s: f64,
    imag_rad_s: f64,
    damping_ratio: Option<f64>,
}

#[derive(Serialize)]
struct EquilibriumRow {
    speed_m_s: f64,
    dynamic_pressure_pa: f64,
    tip_dx_m: f64,
    tip_dy_m: f64,
    tip_dz_m: f64,
    tip_twist_rad: f64,
    lift_n: f64,
    divergence_pressure_pa: Option<f64>,
}

fn equilibrium_rows(equilibria: &[Equilibrium3d]) -> impl Iterator<Item = EquilibriumRow> + '_ {
    equilibria.iter().map(|e| EquilibriumRow {
        speed_m_s: e.speed,
        dynamic_pressure_pa: e.dynamic_pressure,
        tip_dx_m: e.tip[0],
        tip_dy_m: e.tip[1],
        tip_dz_m: e.tip[2],
        tip_twist_rad: e.tip_twist,
        lift_n: e.lift,
        divergence_pressure_pa: e.divergence_pressure,
    })
}

#[derive(Serialize)]
struct StripRow {
    point: usize,
    speed_m_s: f64,
    strip: usize,
    span_m: f64,
    lift_n: f64,
}

/// `static_aero.csv` (the rows of `flutter_equilibria.csv`), `static_nodes.csv` (each
/// equilibrium's nodes, `value` its speed) and `static_strips.csv` (each strip's lift).
fn aero_static_files(o: &AeroStatic3dOutcome, dir: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    equilibria_files(
        &o.equilibria,
        "static_aero.csv",
        "static_nodes.csv",
        dir,
        files,
    )?;
    let f = dir.join("static_strips.csv");
    output::write_csv(
        &f,
        o.equilibria.iter().enumerate().flat_map(|(i, e)| {
            e.strip_lift
                .iter()
                .zip(&o.strip_span)
                .enumerate()
                .map(move |(k, (&lift, &span))| StripRow {
                    point: i,
                    speed_m_s: e.speed,
                    strip: k,
                    span_m: span,
                    lift_n: lift,
                })
        }),
    )?;
    files.push(f);
    Ok(())
}

fn stabilities(o: &Flutter3dOutcome) -> impl Iterator<Item = &Stability3d> {
    std::iter::once(&o.stability).chain(o.pk.as_ref())
}

fn flutter_files(o: &Flutter3dOutcome, dir: &Path, files: &mut Vec<PathBuf>) -> Result<()> {
    let f = dir.join("flutter_summary.csv");
    output::write_csv(
        &f,
        stabilities(o).map(|s| SummaryRow {
            method: s.method,
            flutter_speed_m_s: s.flutter.map(|p| p.speed),
            flutter_frequency_rad_s: s.flutter.map(|p| p.frequency),
            divergence_speed_m_s: o.divergence.map(|d| d.speed),
            status: s.status.word(),
        }),
    )?;
    files.push(f);
    let f = dir.join("flutter_vg.csv");
    output::write_csv(
        &f,
        stabilities(o).flat_map(|s| {
            s.branches.iter().flat_map(move |b| {
                s.speeds.iter().enumerate().map(move |(i, &u)| VgRow {
                    method: s.method,
                    mode: b.mode,
                    speed_m_s: u,
                    real_1_s: b.real[i],
                    imag_rad_s: b.imag[i],
                    damping_ratio: finite(-b.real[i] / b.real[i].hypot(b.imag[i])),
                })
            })
        }),
    )?;
    files.push(f);
    equilibria_files(
        &o.equilibria,
        "flutter_equilibria.csv",
        "flutter_nodes.csv",
        dir,
        files,
    )
}

/// The equilibria's rows in `table` and their nodes in `nodes` (`value` the speed).
fn equilibria_files(
    equilibria: &[Equilibrium3d],
    table: &str,
    nodes: &str,
    dir: &Path,
    files: &mut Vec<PathBuf>,
) -> Result<()> {
    let f = dir.join(table);
    output::write_csv(&f, equilibrium_rows(equilibria))?;
    files.push(f);
    let f = dir.join(nodes);
    output::write_csv(
        &f,
        equilibria
            .iter()
            .enumerate()
            .flat_map(|(i, e)| node_rows(i, e.speed, &e.shape)),
    )?;
    files.push(f);
    Ok(())
}

#[derive(Serialize)]
struct StudyRow {
    level: f64,
    tip_dx_m: f64,
    tip_dy_m: f64,
    tip_dz_m: f64,
    tip_deflection_m: f64,
    tip_twist_rad: f64,
    flutter_speed_m_s: Option<f64>,
    flutter_frequency_rad_s: Option<f64>,
    divergence_speed_m_s: Option<f64>,
    undeformed_flutter_speed_m_s: Option<f64>,
    status: &'static str,
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

fn study_rows(o: &Study3dOutcome) -> impl Iterator<Item = StudyRow> + '_ {
    o.points.iter().map(|p| StudyRow {
        level: p.level,
        tip_dx_m: p.tip[0],
        tip_dy_m: p.tip[1],
        tip_dz_m: p.tip[2],
        tip_deflection_m: norm(p.tip),
        tip_twist_rad: p.tip_twist,
        flutter_speed_m_s: p.flutter.map(|f| f.speed),
        flutter_frequency_rad_s: p.flutter.map(|f| f.frequency),
        divergence_speed_m_s: p.divergence.map(|d| d.speed),
        undeformed_flutter_speed_m_s: o.undeformed.map(|f| f.speed),
        status: p.status.word(),
    })
}

/// The signed vertical tip deflection (m): the study plot's abscissa.
fn study_plot(ctx: &Context, o: &Study3dOutcome, dir: &Path) -> Result<Vec<PathBuf>> {
    let speed: Vec<(f64, f64)> = o
        .points
        .iter()
        .filter_map(|p| p.flutter.map(|f| (p.tip[1], f.speed)))
        .collect();
    let frequency: Vec<(f64, f64)> = o
        .points
        .iter()
        .filter_map(|p| p.flutter.map(|f| (p.tip[1], f.frequency)))
        .collect();
    let divergence: Vec<(f64, f64)> = o
        .points
        .iter()
        .filter_map(|p| p.divergence.map(|d| (p.tip[1], d.speed)))
        .collect();
    let xs: Vec<f64> = o.points.iter().map(|p| p.tip[1]).collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let mut speeds = vec![
        Series {
            label: "flutter, 3-D chain".into(),
            dashed: false,
            colour: Some(0),
            points: speed,
        },
        Series {
            label: "divergence, 3-D chain".into(),
            dashed: false,
            colour: Some(2),
            points: divergence,
        },
    ];
    if let Some(u) = o.undeformed {
        speeds.push(Series {
            label: "flutter, undeformed (the planar model at every load)".into(),
            dashed: true,
            colour: Some(1),
            points: vec![(lo, u.speed), (hi, u.speed)],
        });
    }
    let plot = LinePlot {
        title: format!("Flutter against tip deflection: {}", ctx.what()),
        panels: vec![
            Panel {
                x_label: "tip deflection y (m)".into(),
                y_label: "speed (m/s)".into(),
                series: speeds,
            },
            Panel {
                x_label: "tip deflection y (m)".into(),
                y_label: "flutter frequency (rad/s)".into(),
                series: vec![Series {
                    label: "3-D chain".into(),
                    dashed: false,
                    colour: Some(0),
                    points: frequency,
                }],
            },
        ],
    };
    write_lines(dir, "study", &plot)
}

pub fn text(ctx: &Context, s: &mut String, plan: &Chain3dPlan, outcome: &Chain3dOutcome) {
    match outcome {
        Chain3dOutcome::Dynamic(o) => {
            if let Analysis3d::Dynamic(d) = &plan.analysis {
                super::chain3d_dynamic::text(ctx, s, d, o);
            }
        }
        Chain3dOutcome::Modes { modes, .. } => {
            let _ = writeln!(
                s,
                "{:>4}  {:>13}  {:>12}  {:>7}  {:>7}  {:>7}",
                "mode", "ω (rad/s)", "f (Hz)", "twist", "lag", "flap"
            );
            for m in modes {
                let e = m.energy_fraction;
                let _ = writeln!(
                    s,
                    "{:>4}  {:>13.4}  {:>12.4}  {:>7.3}  {:>7.3}  {:>7.3}",
                    m.mode, m.omega, m.frequency_hz, e.twist, e.lag, e.flap
                );
            }
        }
        Chain3dOutcome::Static(o) => {
            let _ = writeln!(
                s,
                "{:>6}  {:>10}  {:>11}  {:>11}  {:>11}  stable",
                "point", "scale", "tip x (m)", "tip y (m)", "tip z (m)"
            );
            for (i, p) in o.points.iter().enumerate() {
                let t = p.shape.tip();
                let stable = p.stable.map_or("-", |b| if b { "yes" } else { "NO" });
                let _ = writeln!(
                    s,
                    "{i:>6}  {:>10.4}  {:>11.5}  {:>11.5}  {:>11.5}  {stable}",
                    p.scale, t[0], t[1], t[2]
                );
            }
            if let Some(modes) = &o.loaded_modes {
                let _ = writeln!(s, "modes about the last equilibrium (rad/s):");
                for m in modes {
                    let _ = writeln!(s, "{:>4}  {:>13.4}", m.mode, m.omega);
                }
            }
            let _ = writeln!(s, "wall time: {:.3} s", o.wall_time_s);
        }
        Chain3dOutcome::AeroStatic(o) => {
            let _ = writeln!(
                s,
                "{:>9}  {:>11}  {:>11}  {:>11}  {:>12}  {:>10}",
                "U (m/s)", "tip dx (m)", "tip dy (m)", "tip dz (m)", "twist (rad)", "lift (N)"
            );
            for e in &o.equilibria {
                let _ = writeln!(
                    s,
                    "{:>9.4}  {:>11.5}  {:>11.5}  {:>11.5}  {:>12.6}  {:>10.4}",
                    e.speed, e.tip[0], e.tip[1], e.tip[2], e.tip_twist, e.lift
                );
            }
            let _ = match o.divergence {
                Some(d) => writeln!(s, "divergence: {:.4} m/s", d.speed),
                None => writeln!(s, "divergence: none found"),
            };
            let _ = writeln!(s, "wall time: {:.3} s", o.wall_time_s);
        }
        Chain3dOutcome::Flutter(o) => {
            let rest = o.equilibria.first();
            if let Some(e) = rest {
                let _ = writeln!(
                    s,
                    "tip displacement at {} m/s: ({:.4}, {:.4}, {:.4}) m",
                    e.speed, e.tip[0], e.tip[1], e.tip[2]
                );
            }
            let _ = match o.divergence {
                Some(d) => writeln!(s, "divergence: {:.4} m/s", d.speed),
                None => writeln!(s, "divergence: none within the sweep"),
            };
            for st in stabilities(o) {
                let _ = match st.flutter {
                    Some(f) => writeln!(
                        s,
                        "flutter ({}): {:.4} m/s at {:.4} rad/s",
                        st.method, f.speed, f.frequency
                    ),
                    None => writeln!(s, "flutter ({}): none within the sweep", st.method),
                };
            }
            let _ = writeln!(s, "wall time: {:.3} s", o.wall_time_s);
        }
        Chain3dOutcome::Study(o) => {
            let _ = writeln!(
                s,
                "{:>10}  {:>11}  {:>13}  {:>11}  {:>15}",
                o.parameter, "tip y (m)", "flutter (m/s)", "ω (rad/s)", "divergence (m/s)"
            );
            let cell = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.4}"));
            for p in &o.points {
                let _ = writeln!(
                    s,
                    "{:>10.4}  {:>11.4}  {:>13}  {:>11}  {:>15}",
                    p.level,
                    p.tip[1],
                    cell(p.flutter.map(|f| f.speed)),
                    cell(p.flutter.map(|f| f.frequency)),
                    cell(p.divergence.map(|d| d.speed))
                );
            }
            let _ = writeln!(
                s,
                "undeformed wing (the planar model at every level): flutter {} m/s",
                cell(o.undeformed.map(|f| f.speed))
            );
            let _ = writeln!(s, "wall time: {:.3} s", o.wall_time_s);
        }
    }
}

#[derive(Serialize)]
pub struct Json<'a> {
    model: &'static str,
    n_elements: usize,
    n_dofs: usize,
    #[serde(flatten)]
    outcome: &'a Chain3dOutcome,
    #[serde(skip_serializing_if = "Option::is_none")]
    node_output: Option<super::dynamic::NodeOutput>,
    notes: &'a [String],
}

pub fn json<'a>(ctx: &'a Context, plan: &'a Chain3dPlan, outcome: &'a Chain3dOutcome) -> Json<'a> {
    Json {
        model: "chain3d",
        n_elements: plan.model.n_elements(),
        n_dofs: plan.model.n_dofs(),
        outcome,
        node_output: super::chain3d_dynamic::node_output(ctx, plan),
        notes: &ctx.notes,
    }
}
