//! Case (a), the free vibration of the Table 4 beam (n = 10) released from its static deflection
//! under a tip force, full model against the simplified model (gyroscopic term neglected):
//! Table 7 and Figure 5 (released from 150 N, 1 s, and from 10 N for contrast), the energy over
//! 30 s, and the simplified model's blow-up against the integrator.

use anyhow::Result;
use flexwing::analysis::dynamics::AuditedRun;
use flexwing::analysis::Stop;
use flexwing::model::FullModel;
use flexwing::solve::{solve_static, EquationsOfMotion, Gyroscopic, StaticOptions};

use crate::figure::{Figure, FigureKind, LinesFigure, Panel, Series};
use crate::integrators::{integrate, long_method, release_method, Integrator, ENERGY_RUNAWAY};
use crate::printed::{FIGURE5_MAX_ERROR, TABLE7_RATIO};
use crate::table::{Cell, Fmt, Table};
use crate::timing::{duration_text, Timing};
use crate::{cases, stopped, tips, Section};

/// One release: the full and the simplified model from the same deflection.
#[derive(Debug, Clone)]
pub struct Release {
    /// The tip force of the static deflection (N).
    pub force: f64,
    /// The simulated time (s).
    pub end_time: f64,
    /// The full model's run.
    pub full: AuditedRun,
    /// The simplified model's run (guarded against blowing up).
    pub simplified: AuditedRun,
    /// Time of the full model's run.
    pub full_timing: Timing,
    /// Time of the simplified model's run.
    pub simplified_timing: Timing,
    /// The full model's energy `H = T + V` at its output times (J).
    pub energy_full: Vec<f64>,
    /// The simplified model's energy at its output times (J).
    pub energy_simplified: Vec<f64>,
    /// `|x_s − x_f| / max |x_f − L|` at the simplified model's output times.
    pub error_x: Vec<f64>,
    /// `|y_s − y_f| / max |y_f|` at the simplified model's output times.
    pub error_y: Vec<f64>,
    /// The tip of the full model at `t = 0` (m).
    pub initial_tip: (f64, f64),
}

/// A run of the simplified model released from 150 N with one integrator.
#[derive(Debug, Clone)]
pub struct BlowupRun {
    /// The integrator.
    pub integrator: Integrator,
    /// The run (its stop says when and why it blew up).
    pub run: AuditedRun,
}

/// Case (a).
#[derive(Debug, Clone)]
pub struct ReleaseStudy {
    /// Released from 150 N, 1 s, timed.
    pub big: Release,
    /// Released from 150 N, [`LONG_RUN`] (30 s) with the symplectic midpoint rule.
    pub long: Release,
    /// Released from 10 N, 1 s.
    pub small: Release,
    /// The simplified model released from 150 N with several integrators.
    pub blowup: Vec<BlowupRun>,
}

/// Duration of the long run of the energy study (s).
pub const LONG_RUN: f64 = 30.0;

/// Compute case (a) from `examples/paper_free_vibration.toml`, timing with `repeats` samples;
/// the energy study's long run lasts `long_run` seconds ([`LONG_RUN`] in the report).
///
/// # Errors
/// A case that does not load, or a full model that stops.
pub fn run(repeats: usize, long_run: f64) -> Result<ReleaseStudy> {
    let big = release(repeats, 150.0, 1.0, &release_method(), true)?;
    let long = release(repeats, 150.0, long_run, &long_method(), false)?;
    let small = release(repeats, 10.0, 1.0, &release_method(), false)?;
    // The simplified model's blow-up against the integrator: a converged solution blows up, and
    // the tighter the integration, the sooner.
    let mut blowup = Vec::new();
    for integrator in [
        Integrator::midpoint(1e-3),
        Integrator::midpoint(5e-4),
        Integrator::midpoint(2.5e-4),
        Integrator::radau(1e-3, None),
        Integrator::radau(1e-4, None),
        Integrator::radau(1e-5, None),
        Integrator::radau(1e-6, None),
    ] {
        let run = simplified_release(150.0, 1.0, &integrator)?;
        blowup.push(BlowupRun { integrator, run });
    }
    Ok(ReleaseStudy {
        big,
        long,
        small,
        blowup,
    })
}

/// The runaway limit of every run of case (a).
fn guard() -> Option<f64> {
    Some(ENERGY_RUNAWAY)
}

/// The model, its static deflection under the tip force `force`, and the output times.
fn deflected(force: f64, end_time: f64) -> Result<(FullModel, Vec<f64>, Vec<f64>)> {
    let plan = cases::free_vibration(force, end_time)?;
    let flexwing::analysis::dynamics::Initial::Static { loads } = &plan.initial else {
        anyhow::bail!("examples/paper_free_vibration.toml: a static initial state expected");
    };
    let mut scales = vec![0.0; plan.loads.len()];
    for &i in loads {
        scales[i] = 1.0;
    }
    let applied = plan.model.apply(&plan.loads, "loads")?;
    let q0 = solve_static(&plan.model, &applied, &scales, &StaticOptions::default())?.q;
    Ok((plan.model, q0, plan.output_times))
}

/// The simplified model released from the deflection under `force`, with the energy guard.
fn simplified_release(force: f64, end_time: f64, integrator: &Integrator) -> Result<AuditedRun> {
    let (full, q0, t_out) = deflected(force, end_time)?;
    let none = full.apply(&[], "loads")?;
    let damping = flexwing::solve::Damping::None;
    let mut eom = EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Neglected, &damping)?;
    let rest = vec![0.0; full.n_dofs()];
    Ok(integrate(&mut eom, &q0, &rest, &t_out, integrator, guard()))
}

fn release(
    repeats: usize,
    force: f64,
    end_time: f64,
    integrator: &Integrator,
    timed: bool,
) -> Result<Release> {
    let (full, q0, t_out) = deflected(force, end_time)?;
    let none = full.apply(&[], "loads")?;
    let go = |g: Gyroscopic| -> Result<(AuditedRun, Timing, Vec<f64>)> {
        let damping = flexwing::solve::Damping::None;
        let mut eom = EquationsOfMotion::new(&full, &none, vec![], g, &damping)?;
        let rest = vec![0.0; full.n_dofs()];
        let (run, timing) = if timed {
            let run = integrate(&mut eom, &q0, &rest, &t_out, integrator, guard());
            let timing = Timing::measure(repeats, || {
                std::hint::black_box(
                    integrate(&mut eom, &q0, &rest, &t_out, integrator, guard()).stats,
                );
            });
            (run, timing)
        } else {
            Timing::once(|| integrate(&mut eom, &q0, &rest, &t_out, integrator, guard()))
        };
        let energy = run
            .trajectory
            .y
            .iter()
            .map(|y| {
                let (k, s) = eom.energies(y);
                k + s
            })
            .collect();
        Ok((run, timing, energy))
    };
    let (full_run, full_timing, energy_full) = go(Gyroscopic::Exact)?;
    if let Some(e) = stopped(&full_run) {
        anyhow::bail!("case (a), full model released from {force} N: {e}");
    }
    let (simplified, simplified_timing, energy_simplified) = go(Gyroscopic::Neglected)?;
    let tf = tips(&full, &full_run);
    let ts = tips(&full, &simplified);
    let x_scale = tf.iter().map(|p| (p.0 - 1.0).abs()).fold(0.0, f64::max);
    let y_scale = tf.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let error_x = ts
        .iter()
        .zip(&tf)
        .map(|(s, f)| (s.0 - f.0).abs() / x_scale)
        .collect();
    let error_y = ts
        .iter()
        .zip(&tf)
        .map(|(s, f)| (s.1 - f.1).abs() / y_scale)
        .collect();
    Ok(Release {
        force,
        end_time,
        initial_tip: tf[0],
        full: full_run,
        simplified,
        full_timing,
        simplified_timing,
        energy_full,
        energy_simplified,
        error_x,
        error_y,
    })
}

fn max_of(v: &[f64]) -> f64 {
    v.iter().copied().fold(0.0, f64::max)
}

/// Largest `|H − H0| / H0`.
fn drift(e: &[f64]) -> f64 {
    let h0 = e.first().copied().unwrap_or(0.0);
    e.iter().map(|h| (h - h0).abs() / h0).fold(0.0, f64::max)
}

fn t_reached(run: &AuditedRun) -> f64 {
    run.trajectory.t.last().copied().unwrap_or(0.0)
}

fn status(run: &AuditedRun) -> String {
    stopped(run).unwrap_or_else(|| "complete".into())
}

impl Release {
    /// Largest relative errors `(x, y)` of the simplified model over the time it ran.
    pub fn max_errors(&self) -> (f64, f64) {
        (max_of(&self.error_x), max_of(&self.error_y))
    }
}

impl ReleaseStudy {
    /// Why the simplified model released from 150 N stopped, if it did.
    pub fn simplified_stopped(&self) -> Option<&Stop> {
        self.big.simplified.stop()
    }

    /// Energy drift of the full model over the long run.
    pub fn full_drift_long(&self) -> f64 {
        drift(&self.long.energy_full)
    }

    /// Table 7.
    pub fn table(&self) -> Table {
        let big = &self.big;
        let mut table = Table::new(
            "table7",
            &[
                ("model", "model"),
                ("dofs", "dimension"),
                ("integrator", "integrator"),
                ("t_reached_s", "t reached (s)"),
                ("max_rel_error_x_pct", "max rel. error tip x (%)"),
                ("max_rel_error_y_pct", "max rel. error tip y (%)"),
                ("time_median_s", "time (median)"),
                ("time_spread_pct", "spread (%)"),
                ("cpu_ratio", "CPU ratio"),
                ("paper_cpu_ratio", "paper CPU ratio"),
                ("status", "status"),
            ],
        );
        table.push(vec![
            Cell::text("full (exact γ)"),
            Cell::Num(10.0, Fmt::Fixed(0)),
            Cell::text(release_method().short()),
            Cell::fixed(t_reached(&big.full), 3),
            Cell::Empty,
            Cell::Empty,
            Cell::time(big.full_timing.median),
            Cell::fixed(big.full_timing.spread_percent(), 0),
            Cell::fixed(1.0, 3),
            Cell::fixed(1.0, 3),
            Cell::text(status(&big.full)),
        ]);
        let (ex, ey) = big.max_errors();
        table.push(vec![
            Cell::text("simplified (γ = 0)"),
            Cell::Num(10.0, Fmt::Fixed(0)),
            Cell::text(release_method().short()),
            Cell::fixed(t_reached(&big.simplified), 3),
            Cell::fixed(100.0 * ex, 2),
            Cell::fixed(100.0 * ey, 2),
            Cell::time(big.simplified_timing.median),
            Cell::fixed(big.simplified_timing.spread_percent(), 0),
            // A run that stopped early did less work: its time is no measure of the model's cost.
            if big.simplified.stop().is_none() {
                Cell::fixed(big.simplified_timing.median / big.full_timing.median, 3)
            } else {
                Cell::Empty
            },
            Cell::fixed(TABLE7_RATIO, 3),
            Cell::text(status(&big.simplified)),
        ]);
        table
    }

    /// The simplified model's blow-up against the integrator.
    pub fn blowup_table(&self) -> Table {
        let mut table = Table::new(
            "simplified_blowup",
            &[
                ("integrator", "integrator"),
                ("t_reached_s", "t reached (s)"),
                ("steps", "steps"),
                ("status", "status"),
            ],
        );
        for b in &self.blowup {
            table.push(vec![
                Cell::text(b.integrator.describe()),
                Cell::fixed(t_reached(&b.run), 3),
                Cell::Num(b.run.stats.steps as f64, Fmt::Fixed(0)),
                Cell::text(status(&b.run)),
            ]);
        }
        table
    }

    /// The energy drift of every run.
    pub fn energy_table(&self) -> Table {
        let mut table = Table::new(
            "energy_drift",
            &[
                ("case", "case"),
                ("model", "model"),
                ("duration_s", "duration (s)"),
                ("t_reached_s", "t reached (s)"),
                ("max_energy_drift", "max |H − H0| / H0"),
                ("max_rel_error_x_pct", "max rel. error tip x vs full (%)"),
                ("max_rel_error_y_pct", "max rel. error tip y vs full (%)"),
            ],
        );
        for rel in [&self.big, &self.long, &self.small] {
            let case = format!("release from {} N", rel.force);
            table.push(vec![
                Cell::text(&case),
                Cell::text("full (exact γ)"),
                Cell::fixed(rel.end_time, 0),
                Cell::fixed(t_reached(&rel.full), 3),
                Cell::sci(drift(&rel.energy_full), 2),
                Cell::Empty,
                Cell::Empty,
            ]);
            let (ex, ey) = rel.max_errors();
            table.push(vec![
                Cell::text(&case),
                Cell::text("simplified (γ = 0)"),
                Cell::fixed(rel.end_time, 0),
                Cell::fixed(t_reached(&rel.simplified), 3),
                Cell::sci(drift(&rel.energy_simplified), 2),
                Cell::fixed(100.0 * ex, 2),
                Cell::fixed(100.0 * ey, 2),
            ]);
        }
        table
    }

    /// Figure 5's data: the relative errors and energies of the 1 s releases.
    pub fn errors_table(&self) -> Table {
        let mut table = Table::new(
            "figure5",
            &[
                ("case", "case"),
                ("t_s", "t (s)"),
                ("rel_error_x", "relative error x"),
                ("rel_error_y", "relative error y"),
                ("energy_full_J", "H full (J)"),
                ("energy_simplified_J", "H simplified (J)"),
            ],
        );
        for rel in [&self.big, &self.small] {
            let case = format!("{} N", rel.force);
            for (k, t) in rel.simplified.trajectory.t.iter().enumerate() {
                table.push(vec![
                    Cell::text(&case),
                    Cell::fixed(*t, 3),
                    Cell::sci(rel.error_x[k], 4),
                    Cell::sci(rel.error_y[k], 4),
                    Cell::fixed(rel.energy_full[k], 6),
                    Cell::fixed(rel.energy_simplified[k], 6),
                ]);
            }
        }
        table
    }

    /// Figure 5: the relative errors of the simplified model against time, released from 150 N
    /// and from 10 N, and the energy of both models released from 150 N.
    pub fn figure(&self) -> Figure {
        let (big, small) = (&self.big, &self.small);
        let pct = |t: &[f64], v: &[f64]| -> Vec<(f64, f64)> {
            t.iter().zip(v).map(|(t, v)| (*t, 100.0 * v)).collect()
        };
        let ratio = |t: &[f64], e: &[f64]| -> Vec<(f64, f64)> {
            let h0 = e.first().copied().unwrap_or(1.0);
            t.iter().zip(e).map(|(t, h)| (*t, h / h0)).collect()
        };
        let ts = &big.simplified.trajectory.t;
        let ts_small = &small.simplified.trajectory.t;
        let series = |label: &str, dashed: bool, points| Series {
            label: label.into(),
            dashed,
            colour: None,
            points,
        };
        let errors = |y_label: &str, big_v: &[f64], small_v: &[f64]| Panel {
            x_label: "t (s)".into(),
            y_label: y_label.into(),
            series: vec![
                series("released from 150 N", false, pct(ts, big_v)),
                series("released from 10 N", true, pct(ts_small, small_v)),
            ],
        };
        Figure {
            stem: "figure5".into(),
            kind: FigureKind::Lines(LinesFigure {
                title: "Figure 5: simplified (γ = 0) against full model, free vibration, n = 10"
                    .into(),
                panels: vec![
                    errors("relative error, tip x (%)", &big.error_x, &small.error_x),
                    errors("relative error, tip y (%)", &big.error_y, &small.error_y),
                    Panel {
                        x_label: "t (s)".into(),
                        y_label: "energy H(t) / H(0)".into(),
                        series: vec![
                            series(
                                "full, 150 N",
                                false,
                                ratio(&big.full.trajectory.t, &big.energy_full),
                            ),
                            series("simplified, 150 N", true, ratio(ts, &big.energy_simplified)),
                        ],
                    },
                ],
            }),
        }
    }

    /// The report's section of Table 7 and Figure 5; `repeats` as timed.
    pub fn section(&self, repeats: usize) -> Section {
        let table = self.table();
        let blowup = self.blowup_table();
        let mut text = format!(
            "Table 4 beam, n = 10, released at rest from the static deflection under a 150 N dead tip \
             force (tip at ({:.3}, {:.3}) m), no load during the motion; output every 5 ms; {} for \
             both models. Relative errors as in Figure 5: |x_s − x_f| / max|x_f − L| and |y_s − y_f| \
             / max|y_f|, over the time the simplified run reached. A run is stopped when its energy \
             exceeds {ENERGY_RUNAWAY} times its initial value. Times: the 1 s run (median of {} \
             samples); no CPU ratio is given for a run that stopped early. The paper reports relative errors up to {:.0} %.\n\n",
            self.big.initial_tip.0,
            self.big.initial_tip.1,
            release_method().describe(),
            repeats,
            100.0 * FIGURE5_MAX_ERROR,
        );
        text.push_str(&table.markdown());
        text.push_str(
            "\nThe simplified model released from 150 N with several integrators (1 s, the same \
             guard): the tighter the integration, the sooner it blows up, so the blow-up is a \
             property of the simplified equations, not of an integrator; loose integrators damp the \
             growing high-frequency motion for a while.\n\n",
        );
        text.push_str(&blowup.markdown());
        text.push_str(
            "\nFigure 5 (figure5.svg, .png): relative errors of the simplified model against time, \
             released from 150 N and, for contrast, from 10 N, and the energy of both models; \
             figure5.csv has the data.\n",
        );
        Section {
            title: "Figure 5 and Table 7: free vibration, full against simplified".into(),
            text,
            tables: vec![table, blowup, self.energy_table(), self.errors_table()],
            figures: vec![self.figure()],
        }
    }

    /// The report's section on the energy drift (its table is written with Table 7's section).
    pub fn energy_section(&self) -> Section {
        let long = self.long.end_time;
        let mut text = format!(
            "Energy H = T + V of the unloaded, undamped beam, which the exact equations conserve. \
             Largest |H − H0|/H0 over each run. The 1 s runs use {}; the {long} s runs use {}, \
             which conserves quadratic invariants and has no secular energy drift (the full \
             model's {long} s run took {}, one run). The simplified model's equations do not \
             conserve H (dH/dt = −γ·q̇).\n\n",
            release_method().describe(),
            long_method().describe(),
            duration_text(self.long.full_timing.median),
        );
        text.push_str(&self.energy_table().markdown());
        Section {
            title: "Beyond the paper: energy drift of the full and the simplified model".into(),
            text,
            tables: Vec::new(),
            figures: Vec::new(),
        }
    }
}
