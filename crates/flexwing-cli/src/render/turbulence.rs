//! `flexwing turbulence`: the power spectra and RMS of every model's outputs in continuous
//! turbulence — `turbulence_rms.csv` (one row per model and output), `turbulence_psd.csv` (long
//! format: model, output, frequency, `Φ_w`, `Φ_y`), with `--plot` `turbulence_psd.svg/.png`
//! (log–log, one panel per output), and the whole in the JSON document (`--json`).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use flexwing::analysis::aero::turbulence::{TurbulenceOutcome, TurbulencePlan};
use serde::Serialize;

use super::{finite, Context};
use crate::output;
use crate::plot::{write_lines, LinePlot, Panel, Series};

pub const FILES: &[&str] = &[
    "turbulence_rms.csv",
    "turbulence_psd.csv",
    "turbulence_psd.svg",
    "turbulence_psd.png",
];

#[derive(Serialize)]
struct RmsRow {
    model: String,
    output: String,
    unit: String,
    rms: Option<f64>,
    /// The estimated quadrature error of the variance (unit²).
    variance_error: Option<f64>,
    /// The variance above max_frequency included in `rms` (unit²); empty where it diverges.
    tail_variance: Option<f64>,
    tail_slope: Option<f64>,
    diverges: bool,
}

fn rms_rows<'a>(outcome: &'a TurbulenceOutcome) -> impl Iterator<Item = RmsRow> + 'a {
    outcome.runs.iter().flat_map(|r| {
        let label = r.linear.kind.label();
        let outputs = r.linear.model.as_ref().map_or(&[][..], |m| &m.outputs[..]);
        r.spectra.iter().flat_map(move |s| {
            let label = label.clone();
            outputs.iter().enumerate().map(move |(k, sig)| RmsRow {
                model: label.clone(),
                output: sig.name.clone(),
                unit: sig.unit.to_string(),
                rms: finite(s.rms[k]),
                variance_error: finite(s.variance_error[k]),
                tail_variance: s.tail[k].and_then(finite),
                tail_slope: finite(s.tail_slope[k]),
                diverges: s.tail[k].is_none(),
            })
        })
    })
}

#[derive(Serialize)]
struct PsdRow<'a> {
    model: &'a str,
    output: &'a str,
    frequency_rad_s: f64,
    gust_psd: Option<f64>,
    psd: Option<f64>,
}

fn write_psd(path: &Path, outcome: &TurbulenceOutcome) -> Result<()> {
    let labels: Vec<String> = outcome.runs.iter().map(|r| r.linear.kind.label()).collect();
    let rows =
        outcome.runs.iter().zip(&labels).flat_map(|(r, label)| {
            let outputs = r.linear.model.as_ref().map_or(&[][..], |m| &m.outputs[..]);
            r.spectra.iter().flat_map(move |s| {
                outputs.iter().enumerate().flat_map(move |(k, sig)| {
                    s.frequencies.iter().zip(&s.gust_psd).zip(&s.psd[k]).map(
                        move |((&w, &g), &p)| PsdRow {
                            model: label,
                            output: &sig.name,
                            frequency_rad_s: w,
                            gust_psd: finite(g),
                            psd: finite(p),
                        },
                    )
                })
            })
        });
    output::write_csv(path, rows)
}

pub fn files(
    ctx: &Context,
    plan: &TurbulencePlan,
    outcome: &TurbulenceOutcome,
    dir: &Path,
    with_plot: bool,
) -> Result<Vec<PathBuf>> {
    let rms = dir.join("turbulence_rms.csv");
    output::write_csv(&rms, rms_rows(outcome))?;
    let psd = dir.join("turbulence_psd.csv");
    write_psd(&psd, outcome)?;
    let mut files = vec![rms, psd];
    if with_plot {
        files.extend(write_lines(
            dir,
            "turbulence_psd",
            &psd_plot(ctx, plan, outcome),
        )?);
    }
    Ok(files)
}

/// One panel per output: each model's `log10 Φ_y` against `log10 ω` (the figure's axes are
/// linear).
fn psd_plot(ctx: &Context, plan: &TurbulencePlan, outcome: &TurbulenceOutcome) -> LinePlot {
    let first = outcome.runs.iter().find_map(|r| r.linear.model.as_ref());
    let outputs = first.map_or(&[][..], |m| &m.outputs[..]);
    let panel = |k: usize| Panel {
        x_label: "log10 ω (rad/s)".into(),
        y_label: format!(
            "log10 Φ of {} (({})²/(rad/s))",
            outputs[k].name, outputs[k].unit
        ),
        series: outcome
            .runs
            .iter()
            .enumerate()
            .filter_map(|(j, r)| {
                let s = r.spectra.as_ref()?;
                Some(Series {
                    label: r.linear.kind.label(),
                    dashed: j > 0,
                    colour: Some(j),
                    points: s
                        .frequencies
                        .iter()
                        .zip(&s.psd[k])
                        .map(|(w, p)| (w.log10(), p.log10()))
                        .collect(),
                })
            })
            .collect(),
    };
    LinePlot {
        title: format!(
            "Output spectra in {} turbulence, σ_w = {} m/s, L = {} m: {}",
            plan.turbulence.spectrum.name(),
            plan.turbulence.intensity,
            plan.turbulence.scale_length,
            ctx.what()
        ),
        panels: (0..outputs.len()).map(panel).collect(),
    }
}

/// The line saying what the turbulence and grid are.
fn turbulence_line(outcome: &TurbulenceOutcome) -> String {
    let (t, g) = (&outcome.turbulence, &outcome.grid);
    format!(
        "{} turbulence at U = {} m/s: σ_w = {} m/s, L = {} m; {} frequencies from {:.4e} to {:.4e} \
         rad/s",
        t.spectrum.name(),
        outcome.speed,
        t.intensity,
        t.scale_length,
        g.points,
        g.min_frequency,
        g.max_frequency
    )
}

pub fn text(ctx: &Context, s: &mut String, outcome: &TurbulenceOutcome) {
    let _ = writeln!(s, "{}", turbulence_line(outcome));
    let _ = writeln!(s);
    let w = super::label_width(outcome.runs.iter().map(|r| &r.linear.kind));
    let _ = writeln!(
        s,
        "{:<w$}  {:>20}  {:>14}  {:>10}  {:>10}  {:>8}",
        "model", "output", "RMS", "error", "tail", "slope"
    );
    for row in rms_rows(outcome) {
        let rel = |v: Option<f64>| match (v, row.rms) {
            (Some(v), Some(r)) if r > 0.0 => format!("{:.1e}", v / (r * r)),
            _ => "-".into(),
        };
        let _ = writeln!(
            s,
            "{:<w$}  {:>20}  {:>14}  {:>10}  {:>10}  {:>8}",
            row.model,
            row.output,
            row.rms
                .map_or_else(|| "-".into(), |v| format!("{v:.5e} {}", row.unit)),
            rel(row.variance_error),
            if row.diverges {
                "diverges".into()
            } else {
                rel(row.tail_variance)
            },
            row.tail_slope
                .map_or_else(|| "-".into(), |v| format!("{v:.2}")),
        );
    }
    let _ = writeln!(
        s,
        "(error and tail: fractions of the variance; slope: Φ_y ∝ ω^slope beyond every pole)"
    );
    for r in &outcome.runs {
        let label = r.linear.kind.label();
        if let Some(sp) = &r.spectra {
            let _ = writeln!(
                s,
                "{label}: gust RMS over the grid {:.5} m/s, spectra in {:.3} ms",
                sp.gust_rms,
                1e3 * r.wall_time_s
            );
        }
        if let Some(message) = ctx.message_of(&label) {
            let _ = writeln!(s, "  {message}");
        }
    }
    for note in &ctx.notes {
        let _ = writeln!(s, "note: {note}");
    }
}

#[derive(Serialize)]
pub struct Json {
    model: String,
    aerodynamics: String,
    speed_m_s: f64,
    spectrum: &'static str,
    intensity_m_s: f64,
    scale_length_m: f64,
    frequencies: usize,
    min_frequency_rad_s: f64,
    max_frequency_rad_s: f64,
    models: Vec<JsonModel>,
    notes: Vec<String>,
}

#[derive(Serialize)]
struct JsonModel {
    model: String,
    status: &'static str,
    error: Option<String>,
    wall_time_s: f64,
    gust_rms_m_s: Option<f64>,
    frequencies_rad_s: Vec<f64>,
    gust_psd: Vec<Option<f64>>,
    outputs: Vec<JsonOutput>,
}

#[derive(Serialize)]
struct JsonOutput {
    #[serde(flatten)]
    rms: RmsRow,
    psd: Vec<Option<f64>>,
}

pub fn json(ctx: &Context, plan: &TurbulencePlan, outcome: &TurbulenceOutcome) -> Json {
    let mut rows = rms_rows(outcome).peekable();
    let l = &plan.linearize;
    Json {
        model: super::structure_line(&l.model),
        aerodynamics: super::aero_line(l.aero.aerodynamics, l.aero.density),
        speed_m_s: outcome.speed,
        spectrum: outcome.turbulence.spectrum.name(),
        intensity_m_s: outcome.turbulence.intensity,
        scale_length_m: outcome.turbulence.scale_length,
        frequencies: outcome.grid.points,
        min_frequency_rad_s: outcome.grid.min_frequency,
        max_frequency_rad_s: outcome.grid.max_frequency,
        models: outcome
            .runs
            .iter()
            .map(|r| {
                let label = r.linear.kind.label();
                let mut outputs = Vec::new();
                let mut k = 0;
                while let Some(row) = rows.next_if(|row| row.model == label) {
                    let psd = r
                        .spectra
                        .as_ref()
                        .map_or_else(Vec::new, |s| s.psd[k].iter().map(|v| finite(*v)).collect());
                    outputs.push(JsonOutput { rms: row, psd });
                    k += 1;
                }
                let s = r.spectra.as_ref();
                JsonModel {
                    status: r.status.word(),
                    error: ctx.message_of(&label),
                    wall_time_s: r.wall_time_s,
                    gust_rms_m_s: s.and_then(|s| finite(s.gust_rms)),
                    frequencies_rad_s: s.map_or_else(Vec::new, |s| s.frequencies.clone()),
                    gust_psd: s.map_or_else(Vec::new, |s| {
                        s.gust_psd.iter().map(|v| finite(*v)).collect()
                    }),
                    outputs,
                    model: label,
                }
            })
            .collect(),
        notes: ctx.notes.clone(),
    }
}
