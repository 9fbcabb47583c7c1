//! Case (b), the sinusoidal tip force on the Table 4 beam (n = 20): every model against the full
//! one and against itself integrated tightly (Table 8, Figure 6), the converged full model
//! against the independent Python implementation, and the gyroscopic term at the final state
//! (Table 6).

use anyhow::Result;
use flexwing::analysis::dynamics::DynamicPlan;
use flexwing::model::{AppliedLoads, FullModel, PlanarModel, ReducedModel};
use flexwing::solve::integrate::{IntegratorStats, OdeSystem};
use flexwing::solve::{EquationsOfMotion, Gyroscopic, Modes, TimeFunction};

use crate::accuracy::AccuracyRow;
use crate::figure::{Figure, FigureKind, HistoryFigure, TipSeries};
use crate::integrators::{
    explicit_method, full_method, full_reference, integrate, rom_method, Integrator,
};
use crate::printed::{TABLE6, TABLE8_RATIO};
use crate::table::{Cell, Fmt, Table};
use crate::timing::Timing;
use crate::{cases, distance, references, stopped, tips, Section};

/// Uncertainty of the independent Python reference (m): its SciPy Radau and DOP853 solutions
/// are this far apart (`crates/flexwing/tests/data/dynamics_reference/README.md`).
const INDEPENDENT_UNCERTAINTY: f64 = 6.4e-10;

/// A model of case (b).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SineModelKind {
    /// The full model, exact gyroscopic term.
    Full,
    /// The full model, gyroscopic term neglected.
    Simplified,
    /// A reduced model on the first `r` modes, integrated as the full model.
    Reduced(usize),
    /// A reduced model on the first `r` modes, integrated by the explicit alternative.
    ReducedExplicit(usize),
}

impl SineModelKind {
    /// The model's name in the tables.
    pub fn label(self) -> String {
        let modes = |r: usize| format!("{r} mode{}", if r == 1 { "" } else { "s" });
        match self {
            Self::Full => "full (exact γ)".into(),
            Self::Simplified => "simplified (γ = 0)".into(),
            Self::Reduced(r) => format!("reduced, {}", modes(r)),
            Self::ReducedExplicit(r) => format!("reduced, {}, explicit", modes(r)),
        }
    }
}

/// One model of case (b): its timed run and its tight run.
#[derive(Debug, Clone)]
pub struct SineModel {
    /// Which model.
    pub kind: SineModelKind,
    /// Number of coordinates.
    pub dofs: usize,
    /// The integrator of the timed run.
    pub integrator: Integrator,
    /// Counters of the timed run.
    pub stats: IntegratorStats,
    /// Output times (s).
    pub t: Vec<f64>,
    /// Tip `(x, y)` of the timed run at the output times (m).
    pub tips: Vec<(f64, f64)>,
    /// Tip of the same model integrated tightly ([`full_reference`]).
    pub converged: Vec<(f64, f64)>,
    /// The state `(x, p)` of the tight run at the last output time.
    pub final_state: Vec<f64>,
    /// Time of the whole timed run.
    pub timing: Timing,
}

/// Case (b).
#[derive(Debug, Clone)]
pub struct SineStudy {
    /// The models, the full one first and the simplified one second.
    pub models: Vec<SineModel>,
    /// The independent Python implementation's tip history `(t, x, y)`.
    pub independent: Vec<[f64; 3]>,
    /// The gyroscopic term at the converged full model's final state.
    pub gamma: GammaStudy,
}

/// Table 6: the gyroscopic term exact, by finite differences and neglected.
#[derive(Debug, Clone)]
pub struct GammaStudy {
    /// Largest component of the exact term (N·m).
    pub largest: f64,
    /// Mean absolute error of the finite differences.
    pub mean_absolute_error: f64,
    /// Mean relative error of the finite differences.
    pub mean_relative_error: f64,
    /// Time of one right-hand side with the exact term.
    pub exact: Timing,
    /// … with the finite-difference term.
    pub finite_difference: Timing,
    /// … without the term.
    pub neglected: Timing,
}

/// Compute case (b) from `examples/paper_sine.toml`, timing with `repeats` samples.
///
/// # Errors
/// A case or reference that does not load, or a run that stops.
pub fn run(repeats: usize) -> Result<SineStudy> {
    let plan = cases::sine()?;
    let full = &plan.model;
    let loads = full.apply(&plan.loads, "loads")?;
    let functions: Vec<TimeFunction> = plan.time.iter().flatten().cloned().collect();
    let modes = Modes::undeformed(full)?;
    let spec = RunSpec {
        plan: &plan,
        loads: &loads,
        functions: &functions,
        repeats,
    };
    let mut models = vec![
        run_model(
            full,
            &spec,
            SineModelKind::Full,
            Gyroscopic::Exact,
            full_method(),
        )?,
        run_model(
            full,
            &spec,
            SineModelKind::Simplified,
            Gyroscopic::Neglected,
            full_method(),
        )?,
    ];
    for &r in &plan.reduced {
        let rom = ReducedModel::first(full, modes.shapes(), r)?;
        let kind = SineModelKind::Reduced(r);
        models.push(run_model(&rom, &spec, kind, plan.gyroscopic, rom_method())?);
    }
    // The explicit alternative for the paper's reduced model.
    let rom = ReducedModel::first(full, modes.shapes(), 2)?;
    models.push(run_model(
        &rom,
        &spec,
        SineModelKind::ReducedExplicit(2),
        plan.gyroscopic,
        explicit_method(),
    )?);
    // Table 6 at the converged state at t = 1 s.
    let gamma = gamma(repeats, full, &loads, &functions, &models[0].final_state)?;
    Ok(SineStudy {
        models,
        independent: references::independent_case_b()?,
        gamma,
    })
}

/// What every run of case (b) shares.
struct RunSpec<'a> {
    plan: &'a DynamicPlan,
    loads: &'a AppliedLoads,
    functions: &'a [TimeFunction],
    repeats: usize,
}

/// Run `model` from rest with `integrator` (the run kept), time repeated runs, and run it
/// tightly.
fn run_model<M: PlanarModel>(
    model: &M,
    spec: &RunSpec,
    kind: SineModelKind,
    gyroscopic: Gyroscopic,
    integrator: Integrator,
) -> Result<SineModel> {
    let mut eom = EquationsOfMotion::new(
        model,
        spec.loads,
        spec.functions.to_vec(),
        gyroscopic,
        &spec.plan.damping,
    )?;
    let rest = vec![0.0; model.n_dofs()];
    let t_out = &spec.plan.output_times;
    let run = integrate(&mut eom, &rest, &rest, t_out, &integrator, None);
    if let Some(e) = stopped(&run) {
        anyhow::bail!("case (b), {} dofs: {e}", model.n_dofs());
    }
    let timing = Timing::measure(spec.repeats, || {
        std::hint::black_box(integrate(&mut eom, &rest, &rest, t_out, &integrator, None).stats);
    });
    let converged = integrate(&mut eom, &rest, &rest, t_out, &full_reference(), None);
    if let Some(e) = stopped(&converged) {
        anyhow::bail!("case (b), {} dofs, converged run: {e}", model.n_dofs());
    }
    Ok(SineModel {
        kind,
        dofs: model.n_dofs(),
        integrator,
        stats: run.stats,
        t: run.trajectory.t.clone(),
        tips: tips(model, &run),
        converged: tips(model, &converged),
        final_state: converged.trajectory.y.last().cloned().unwrap_or_default(),
        timing,
    })
}

/// Table 6: γ exact against central differences (h = 1e-6) at the state `y` (t = 1 s).
fn gamma(
    repeats: usize,
    full: &FullModel,
    loads: &AppliedLoads,
    functions: &[TimeFunction],
    y: &[f64],
) -> Result<GammaStudy> {
    let n = full.n_dofs();
    let rhs = |g: Gyroscopic| -> Result<(Vec<f64>, Timing)> {
        let none = flexwing::solve::Damping::None;
        let mut eom = EquationsOfMotion::new(full, loads, functions.to_vec(), g, &none)?;
        let mut dy = vec![0.0; 2 * n];
        eom.rhs(1.0, y, &mut dy);
        let timing = Timing::measure(repeats, || {
            eom.rhs(1.0, std::hint::black_box(y), &mut dy);
        });
        eom.rhs(1.0, y, &mut dy);
        Ok((dy, timing))
    };
    let (d_exact, exact) = rhs(Gyroscopic::Exact)?;
    let (d_fd, finite_difference) = rhs(Gyroscopic::FiniteDifference {
        step: Gyroscopic::DEFAULT_STEP,
    })?;
    let (d_none, neglected) = rhs(Gyroscopic::Neglected)?;
    // γ is the momentum rate with the term minus the one without it.
    let g_exact: Vec<f64> = (n..2 * n).map(|i| d_exact[i] - d_none[i]).collect();
    let g_fd: Vec<f64> = (n..2 * n).map(|i| d_fd[i] - d_none[i]).collect();
    let pairs = || g_exact.iter().zip(&g_fd);
    Ok(GammaStudy {
        largest: g_exact.iter().map(|v| v.abs()).fold(0.0, f64::max),
        mean_absolute_error: pairs().map(|(a, b)| (a - b).abs()).sum::<f64>() / n as f64,
        mean_relative_error: pairs()
            .filter(|(a, _)| **a != 0.0)
            .map(|(a, b)| ((a - b) / a).abs())
            .sum::<f64>()
            / n as f64,
        exact,
        finite_difference,
        neglected,
    })
}

fn max_distance(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| distance(*p, *q))
        .fold(0.0, f64::max)
}

impl SineStudy {
    fn full(&self) -> &SineModel {
        &self.models[0]
    }

    fn model(&self, kind: SineModelKind) -> Option<&SineModel> {
        self.models.iter().find(|m| m.kind == kind)
    }

    /// The converged full model's tips: the solution every model is compared with.
    pub fn reference_tips(&self) -> &[(f64, f64)] {
        &self.full().converged
    }

    /// Largest tip displacement of the converged full model (m).
    pub fn amplitude(&self) -> f64 {
        self.reference_tips()
            .iter()
            .map(|t| (t.0 - 1.0).hypot(t.1))
            .fold(0.0, f64::max)
    }

    /// Model error of `m`: its converged tip against the converged full model's (m).
    pub fn model_error(&self, m: &SineModel) -> f64 {
        max_distance(&m.converged, self.reference_tips())
    }

    /// Integration error of `m`: its timed run against its own tight run (m).
    pub fn integration_error(&self, m: &SineModel) -> f64 {
        max_distance(&m.tips, &m.converged)
    }

    /// The converged full model against the independent implementation, same output times (m).
    pub fn independent_difference(&self) -> f64 {
        self.reference_tips()
            .iter()
            .zip(&self.independent)
            .map(|(p, r)| distance(*p, (r[1], r[2])))
            .fold(0.0, f64::max)
    }

    /// CPU time of `m` over the full model's.
    pub fn ratio(&self, m: &SineModel) -> f64 {
        m.timing.median / self.full().timing.median
    }

    /// CPU ratio of the paper's reduced model (2 modes).
    pub fn ratio_r2(&self) -> f64 {
        self.model(SineModelKind::Reduced(2))
            .map_or(f64::NAN, |m| self.ratio(m))
    }

    /// Largest tip distance simplified − full, both converged (m).
    pub fn simplified_difference(&self) -> f64 {
        self.model(SineModelKind::Simplified)
            .map_or(f64::NAN, |m| self.model_error(m))
    }

    /// Tip error of the timed full run against the tight one (m).
    pub fn full_integration_error(&self) -> f64 {
        self.integration_error(self.full())
    }

    /// The reduced models' accuracy.
    pub fn accuracy(&self) -> Vec<AccuracyRow> {
        let amplitude = self.amplitude();
        self.models
            .iter()
            .filter_map(|m| match m.kind {
                SineModelKind::Reduced(r) => {
                    let difference = self.model_error(m);
                    Some(AccuracyRow {
                        case: "dynamic, tip force 10 sin(20 t) N, 1 s (n = 20)".into(),
                        modes: r,
                        difference,
                        relative: difference / amplitude,
                        reference_error: None,
                    })
                }
                _ => None,
            })
            .collect()
    }

    /// Table 8.
    pub fn table(&self) -> Table {
        let mut table = Table::new(
            "table8",
            &[
                ("model", "model"),
                ("dofs", "dimension"),
                ("integrator", "integrator"),
                ("steps", "steps"),
                ("rhs_evaluations", "RHS evaluations"),
                (
                    "max_tip_difference_m",
                    "model error: max |Δtip| vs full (m)",
                ),
                ("relative_pct", "% of max tip displacement"),
                (
                    "integration_error_m",
                    "integration error of the timed run (m)",
                ),
                ("time_median_s", "time (median)"),
                ("time_spread_pct", "spread (%)"),
                ("cpu_ratio", "CPU ratio"),
                ("paper_cpu_ratio", "paper CPU ratio"),
            ],
        );
        let amplitude = self.amplitude();
        for m in &self.models {
            let diff = self.model_error(m);
            let paper = match m.kind {
                SineModelKind::Full => Cell::fixed(1.0, 3),
                SineModelKind::Reduced(2) => Cell::fixed(TABLE8_RATIO, 3),
                _ => Cell::Empty,
            };
            table.push(vec![
                Cell::text(m.kind.label()),
                Cell::Num(m.dofs as f64, Fmt::Fixed(0)),
                Cell::text(m.integrator.short()),
                Cell::Num(m.stats.steps as f64, Fmt::Fixed(0)),
                Cell::Num(m.stats.rhs_evaluations as f64, Fmt::Fixed(0)),
                Cell::sci(diff, 2),
                Cell::fixed(100.0 * diff / amplitude, 3),
                Cell::sci(self.integration_error(m), 2),
                Cell::time(m.timing.median),
                Cell::fixed(m.timing.spread_percent(), 0),
                Cell::fixed(self.ratio(m), 3),
                paper,
            ]);
        }
        let independent = self.independent_difference();
        table.push(vec![
            Cell::text("independent Python implementation (reference)"),
            Cell::Num(self.full().dofs as f64, Fmt::Fixed(0)),
            Cell::text("SciPy Radau 1e-10"),
            Cell::Empty,
            Cell::Empty,
            Cell::sci(independent, 2),
            Cell::fixed(100.0 * independent / amplitude, 5),
            Cell::sci(INDEPENDENT_UNCERTAINTY, 1),
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
        ]);
        table
    }

    /// Figure 6's data: every model's tip history.
    pub fn history_table(&self) -> Table {
        let mut history = Table::new(
            "figure6",
            &[
                ("model", "model"),
                ("t_s", "t (s)"),
                ("tip_x_m", "tip x (m)"),
                ("tip_y_m", "tip y (m)"),
            ],
        );
        for m in &self.models {
            for (t, p) in m.t.iter().zip(&m.tips) {
                history.push(vec![
                    Cell::text(m.kind.label()),
                    Cell::fixed(*t, 3),
                    Cell::fixed(p.0, 6),
                    Cell::fixed(p.1, 6),
                ]);
            }
        }
        history
    }

    /// Figure 6: the tip of the full model and of the reduced models on 1, 2 and 3 modes.
    pub fn figure(&self) -> Figure {
        let shown =
            |k: SineModelKind| matches!(k, SineModelKind::Full | SineModelKind::Reduced(1..=3));
        Figure {
            stem: "figure6".into(),
            kind: FigureKind::History(HistoryFigure {
                title: "Figure 6: tip position under F = 10 sin(20 t) N, n = 20, full and reduced"
                    .into(),
                end_time: 1.0,
                has_torsion: false,
                series: self
                    .models
                    .iter()
                    .filter(|m| shown(m.kind))
                    .map(|m| TipSeries {
                        label: m.kind.label(),
                        dashed: m.kind != SineModelKind::Full,
                        t: m.t.clone(),
                        x: m.tips.iter().map(|p| p.0).collect(),
                        y: m.tips.iter().map(|p| p.1).collect(),
                        twist: Vec::new(),
                    })
                    .collect(),
            }),
        }
    }

    /// The report's section of Table 8 and Figure 6; `repeats` as timed.
    pub fn section(&self, repeats: usize) -> Section {
        let table = self.table();
        let mut text = format!(
            "Table 4 beam, n = 20, dead vertical tip force 10 sin(20 t) N from rest, 1 s, output \
             every 5 ms, exact gyroscopic term unless stated (the paper ran this case with γ \
             neglected in both models). Model errors compare each model with the full one, both \
             integrated tightly ({}); integration errors compare each timed run ({} unless stated) \
             with the same model integrated tightly; the full model's is {:.1e} m. The converged full \
             model is {:.1e} m from an independent Python implementation of the model (reference; \
             its own uncertainty 6.4e-10 m). The largest tip displacement is \
             {:.4} m. Times: the whole 1 s integration (median of {} samples). Reduced models \
             exclude the offline modal analysis and projection.\n\n",
            full_reference().describe(),
            full_method().describe(),
            self.full_integration_error(),
            self.independent_difference(),
            self.amplitude(),
            repeats,
        );
        text.push_str(&table.markdown());
        text.push_str(
            "\nFigure 6 (figure6.svg, .png): tip y and x against time; figure6.csv has every model.\n",
        );
        Section {
            title: "Figure 6 and Table 8: sinusoidal tip force, full against reduced".into(),
            text,
            tables: vec![table, self.history_table()],
            figures: vec![self.figure()],
        }
    }
}

impl GammaStudy {
    /// Cost of the finite-difference term over the exact one, per right-hand side.
    pub fn fd_cost_ratio(&self) -> f64 {
        self.finite_difference.median / self.exact.median
    }

    /// Cost of a right-hand side with the exact term over one without it.
    pub fn exact_cost(&self) -> f64 {
        self.exact.median / self.neglected.median
    }

    /// Table 6.
    pub fn table(&self) -> Table {
        let mut table = Table::new(
            "table6",
            &[
                ("method", "method"),
                ("mean_absolute_error", "mean absolute error"),
                ("mean_relative_error", "mean relative error"),
                ("time_per_rhs_s", "time per RHS (median)"),
                ("time_spread_pct", "spread (%)"),
                ("cpu_ratio", "CPU ratio"),
                ("paper_mean_absolute_error", "paper: mean abs. error"),
                ("paper_mean_relative_error", "paper: mean rel. error"),
                ("paper_cpu_ratio", "paper: CPU ratio"),
            ],
        );
        let (t_exact, t_fd, t_none) = (&self.exact, &self.finite_difference, &self.neglected);
        table.push(vec![
            Cell::text("exact (O(n) recursion)"),
            Cell::fixed(0.0, 0),
            Cell::fixed(0.0, 0),
            Cell::time(t_exact.median),
            Cell::fixed(t_exact.spread_percent(), 0),
            Cell::fixed(1.0, 3),
            Cell::fixed(0.0, 0),
            Cell::fixed(0.0, 0),
            Cell::fixed(1.0, 3),
        ]);
        table.push(vec![
            Cell::text("central differences, h = 1e-6"),
            Cell::sci(self.mean_absolute_error, 2),
            Cell::sci(self.mean_relative_error, 2),
            Cell::time(t_fd.median),
            Cell::fixed(t_fd.spread_percent(), 0),
            Cell::fixed(t_fd.median / t_exact.median, 3),
            Cell::sci(TABLE6.0, 2),
            Cell::sci(TABLE6.1, 2),
            Cell::fixed(TABLE6.2, 3),
        ]);
        table.push(vec![
            Cell::text("neglected (simplified model)"),
            Cell::Empty,
            Cell::Empty,
            Cell::time(t_none.median),
            Cell::fixed(t_none.spread_percent(), 0),
            Cell::fixed(t_none.median / t_exact.median, 3),
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
        ]);
        table
    }

    /// The report's section of Table 6; `repeats` as timed.
    pub fn section(&self, repeats: usize) -> Section {
        let table = self.table();
        let mut text = format!(
            "The state of the converged full run of case (b) at t = 1 s (n = 20), as in the paper. \
             γ = ∂T/∂q at fixed velocities; the largest component is {:.3e} N·m. Times are \
             one evaluation of the whole right-hand side (the O(n) velocity solve, loads, γ), median \
             of {} samples. The paper's exact γ came from automatic differentiation of the \
             symbolic inverse and was 12 times slower than its finite differences; ours is an O(n) \
             recursion, so the finite differences (2n evaluations of the kinetic energy, each \
             with its own O(n) velocity solve: O(n²)) are the slow option here.\n\n",
            self.largest, repeats
        );
        text.push_str(&table.markdown());
        Section {
            title: "Table 6: gyroscopic term, exact against finite differences".into(),
            text,
            tables: vec![table],
            figures: Vec::new(),
        }
    }
}
