//! The static cases on the Table 4 beam, full against reduced, with the elastica as reference:
//! Table 3 (a 150 N dead tip force, n = 20) and Table 5 with Figure 4 (a tip force F1 swept
//! 0 … 150 N with −150 N at mid-span, n = 10).

use anyhow::Result;
use flexwing::analysis::statics::StaticPlan;
use flexwing::model::{AppliedLoads, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::{solve_static, sweep_static, Modes, StaticOptions};

use crate::accuracy::AccuracyRow;
use crate::figure::{Figure, FigureKind, ModelShapes, ShapesFigure};
use crate::printed::{TABLE3_RATIOS, TABLE5_RATIOS};
use crate::references::{self, TwoLoadsPoint};
use crate::table::{Cell, Fmt, Table};
use crate::timing::Timing;
use crate::{cases, distance, tip, Section};

/// A model of a static case: the full model (`modes: None`) or a reduced one on its first
/// `modes` modes.
fn label(modes: Option<usize>) -> String {
    modes.map_or_else(
        || "full".into(),
        |r| format!("reduced, {r} mode{}", if r == 1 { "" } else { "s" }),
    )
}

fn paper_ratio(ratios: &[(usize, f64)], modes: Option<usize>) -> Cell {
    match modes {
        None => Cell::fixed(1.0, 2),
        Some(r) => Cell::opt(
            ratios.iter().find(|(k, _)| *k == r).map(|(_, v)| *v),
            Fmt::Fixed(2),
        ),
    }
}

/// The models of a static plan: the full one, then the reduced ones on the first `r` modes.
fn models(plan: &StaticPlan) -> Vec<Option<usize>> {
    std::iter::once(None)
        .chain(plan.reduced.iter().map(|&r| Some(r)))
        .collect()
}

/// Table 3: one equilibrium per model under the dead tip force.
#[derive(Debug, Clone)]
pub struct TipForceStudy {
    /// The tip force (N).
    pub force: f64,
    /// The elastica's tip `(x, y)` (m).
    pub reference: (f64, f64),
    /// Time of the offline modal analysis of the reduced models.
    pub modes_timing: Timing,
    /// The full model first, then the reduced ones.
    pub rows: Vec<StaticRow>,
}

/// One model's equilibrium and the time of a complete static solve.
#[derive(Debug, Clone)]
pub struct StaticRow {
    /// `None` for the full model, else the number of modes.
    pub modes: Option<usize>,
    /// Number of coordinates.
    pub dofs: usize,
    /// Tip position `(x, y)` (m).
    pub tip: (f64, f64),
    /// Time of one solve from rest.
    pub timing: Timing,
}

/// Compute Table 3 from `examples/paper_tip_force.toml`, timing with `repeats` samples.
///
/// # Errors
/// A case or reference that does not load, or a solve that fails.
pub fn tip_force(repeats: usize) -> Result<TipForceStudy> {
    let plan = cases::tip_force()?;
    let full = &plan.model;
    let force = match plan.loads.as_slice() {
        [Load::PointForce {
            force: flexwing::model::Force::Dead { fy, .. },
            ..
        }] => *fy,
        _ => anyhow::bail!("examples/paper_tip_force.toml: one dead point force expected"),
    };
    let loads = full.apply(&plan.loads, "loads")?;
    let reference = references::elastica_tip(force)?;
    let modes_timing = Timing::measure(repeats, || {
        std::hint::black_box(Modes::undeformed(full).ok());
    });
    let modes = Modes::undeformed(full)?;
    let mut rows = Vec::new();
    for r in models(&plan) {
        let (tip, timing, dofs) = match r {
            None => solve_timed(repeats, full, full, &loads, &plan.options)?,
            Some(r) => {
                let rom = ReducedModel::first(full, modes.shapes(), r)?;
                solve_timed(repeats, full, &rom, &loads, &plan.options)?
            }
        };
        rows.push(StaticRow {
            modes: r,
            dofs,
            tip,
            timing,
        });
    }
    Ok(TipForceStudy {
        force,
        reference,
        modes_timing,
        rows,
    })
}

/// Solve once for the tip, then time repeated solves.
fn solve_timed<M: StructuralModel>(
    repeats: usize,
    full: &FullModel,
    model: &M,
    loads: &AppliedLoads,
    options: &StaticOptions,
) -> Result<((f64, f64), Timing, usize)> {
    let sol = solve_static(model, loads, &[1.0], options)?;
    let timing = Timing::measure(repeats, || {
        std::hint::black_box(solve_static(model, loads, &[1.0], options).ok());
    });
    Ok((tip(full, &sol.q), timing, model.n_dofs()))
}

impl TipForceStudy {
    fn full(&self) -> &StaticRow {
        &self.rows[0]
    }

    /// Tip distance of `row` from the full model (m).
    pub fn difference(&self, row: &StaticRow) -> f64 {
        distance(row.tip, self.full().tip)
    }

    /// The reduced models' accuracy.
    pub fn accuracy(&self) -> Vec<AccuracyRow> {
        let displacement = distance(self.full().tip, (1.0, 0.0));
        self.rows
            .iter()
            .filter_map(|row| {
                let r = row.modes?;
                let difference = self.difference(row);
                Some(AccuracyRow {
                    case: "static, tip force 150 N (n = 20)".into(),
                    modes: r,
                    difference,
                    relative: difference / displacement,
                    reference_error: Some(distance(row.tip, self.reference)),
                })
            })
            .collect()
    }

    /// Table 3.
    pub fn table(&self) -> Table {
        let mut table = Table::new(
            "table3",
            &[
                ("model", "model"),
                ("dofs", "dimension"),
                ("tip_x_m", "tip x (m)"),
                ("tip_y_m", "tip y (m)"),
                ("error_vs_elastica_m", "|Δtip| vs elastica (m)"),
                ("difference_vs_full_m", "|Δtip| vs full (m)"),
                ("time_median_s", "time (median)"),
                ("time_spread_pct", "spread (%)"),
                ("cpu_ratio", "CPU ratio"),
                ("paper_cpu_ratio", "paper CPU ratio"),
            ],
        );
        let full_time = self.full().timing.median;
        for row in &self.rows {
            table.push(vec![
                Cell::text(label(row.modes)),
                Cell::Num(row.dofs as f64, Fmt::Fixed(0)),
                Cell::fixed(row.tip.0, 5),
                Cell::fixed(row.tip.1, 5),
                Cell::sci(distance(row.tip, self.reference), 2),
                if row.modes.is_some() {
                    Cell::sci(self.difference(row), 2)
                } else {
                    Cell::Empty
                },
                Cell::time(row.timing.median),
                Cell::fixed(row.timing.spread_percent(), 0),
                Cell::fixed(row.timing.median / full_time, 2),
                paper_ratio(&TABLE3_RATIOS, row.modes),
            ]);
        }
        table
    }

    /// The report's section; `repeats` as timed.
    pub fn section(&self, repeats: usize) -> Section {
        let table = self.table();
        let mut text = format!(
            "Table 4 beam (L = 1 m, EI = 50 N·m², m = 0.2 kg/m), n = 20, dead vertical tip force \
             {} N (α = FL²/EI = 3), Newton with load stepping from rest. Elastica tip: \
             ({:.5}, {:.5}) m. Times are one complete static solve (median over {} samples; spread \
             = (max − min)/median); reduced models exclude the offline modal analysis, {}.\n\n",
            self.force,
            self.reference.0,
            self.reference.1,
            repeats,
            self.modes_timing.text()
        );
        text.push_str(&table.markdown());
        Section {
            title: "Table 3: static tip force, full against reduced".into(),
            text,
            tables: vec![table],
            figures: Vec::new(),
        }
    }
}

/// Table 5 and Figure 4: every model over the sweep of F1.
#[derive(Debug, Clone)]
pub struct TwoForceStudy {
    /// The elastica at each F1 of the sweep.
    pub reference: Vec<TwoLoadsPoint>,
    /// The elastica's shapes `(F1, node positions)` at some F1.
    pub reference_shapes: Vec<references::Shape>,
    /// The full model first, then the reduced ones.
    pub rows: Vec<SweepRow>,
}

/// One model over the sweep.
#[derive(Debug, Clone)]
pub struct SweepRow {
    /// `None` for the full model, else the number of modes.
    pub modes: Option<usize>,
    /// Number of coordinates.
    pub dofs: usize,
    /// Tip `(x, y)` at each point (m).
    pub tips: Vec<(f64, f64)>,
    /// Mid-span point `(x, y)` at each point (m).
    pub mids: Vec<(f64, f64)>,
    /// Node positions at each point (m).
    pub shapes: Vec<Vec<(f64, f64)>>,
    /// Time of the whole sweep.
    pub timing: Timing,
}

/// Compute Table 5 and Figure 4 from `examples/paper_static.toml` at n = 10, timing with
/// `repeats` samples.
///
/// # Errors
/// A case or reference that does not load, or a sweep that fails.
pub fn two_forces(repeats: usize) -> Result<TwoForceStudy> {
    let plan = cases::two_forces()?;
    let full = &plan.model;
    let loads = full.apply(&plan.loads, "loads")?;
    let reference = references::elastica_two_loads()?;
    let points = plan.points();
    anyhow::ensure!(
        points.iter().zip(&reference).all(|(p, e)| p[0] == e.f1) && points.len() == reference.len(),
        "the sweep of examples/paper_static.toml is not that of the elastica reference"
    );
    let modes = Modes::undeformed(full)?;
    let mut rows = Vec::new();
    for r in models(&plan) {
        let rom = r
            .map(|r| ReducedModel::first(full, modes.shapes(), r))
            .transpose()?;
        let sweep = |o: &StaticOptions| match &rom {
            None => sweep_static(full, &loads, &points, o),
            Some(rom) => sweep_static(rom, &loads, &points, o),
        };
        let solutions = sweep(&plan.options)?;
        let timing = Timing::measure(repeats, || {
            std::hint::black_box(sweep(&plan.options).ok());
        });
        let mut row = SweepRow {
            modes: r,
            dofs: rom.as_ref().map_or(full.n_dofs(), StructuralModel::n_dofs),
            tips: Vec::new(),
            mids: Vec::new(),
            shapes: Vec::new(),
            timing,
        };
        for s in &solutions {
            let kin = full.kinematics(&s.q);
            let mid = full.point_position(&kin, 0.5);
            row.tips.push(tip(full, &s.q));
            row.mids.push((mid[0], mid[1]));
            row.shapes.push(
                full.node_positions(&kin)
                    .iter()
                    .map(|p| (p[0], p[1]))
                    .collect(),
            );
        }
        rows.push(row);
    }
    Ok(TwoForceStudy {
        reference,
        reference_shapes: references::elastica_two_loads_shapes()?,
        rows,
    })
}

/// The F1 (N) of the shapes of Figure 4.
const SHOWN: [f64; 4] = [0.0, 50.0, 100.0, 150.0];

impl TwoForceStudy {
    fn full(&self) -> &SweepRow {
        &self.rows[0]
    }

    /// Largest tip distance of `row` from the elastica over the sweep (m).
    pub fn error(&self, row: &SweepRow) -> f64 {
        row.tips
            .iter()
            .zip(&self.reference)
            .map(|(t, e)| distance(*t, e.tip))
            .fold(0.0, f64::max)
    }

    /// Largest tip distance of `row` from the full model over the sweep (m).
    pub fn difference(&self, row: &SweepRow) -> f64 {
        row.tips
            .iter()
            .zip(&self.full().tips)
            .map(|(a, b)| distance(*a, *b))
            .fold(0.0, f64::max)
    }

    /// The reduced models' accuracy.
    pub fn accuracy(&self) -> Vec<AccuracyRow> {
        let displacement = self
            .full()
            .tips
            .iter()
            .map(|t| distance(*t, (1.0, 0.0)))
            .fold(0.0, f64::max);
        self.rows
            .iter()
            .filter_map(|row| {
                let r = row.modes?;
                let difference = self.difference(row);
                Some(AccuracyRow {
                    case: "static, two forces, F1 = 0…150 N (n = 10)".into(),
                    modes: r,
                    difference,
                    relative: difference / displacement,
                    reference_error: Some(self.error(row)),
                })
            })
            .collect()
    }

    /// Table 5.
    pub fn table(&self) -> Table {
        let mut table = Table::new(
            "table5",
            &[
                ("model", "model"),
                ("dofs", "dimension"),
                ("max_error_vs_elastica_m", "max |Δtip| vs elastica (m)"),
                ("max_difference_vs_full_m", "max |Δtip| vs full (m)"),
                ("time_median_s", "time of the sweep (median)"),
                ("time_spread_pct", "spread (%)"),
                ("cpu_ratio", "CPU ratio"),
                ("paper_cpu_ratio", "paper CPU ratio"),
            ],
        );
        let full_time = self.full().timing.median;
        for row in &self.rows {
            table.push(vec![
                Cell::text(label(row.modes)),
                Cell::Num(row.dofs as f64, Fmt::Fixed(0)),
                Cell::sci(self.error(row), 2),
                if row.modes.is_some() {
                    Cell::sci(self.difference(row), 2)
                } else {
                    Cell::Empty
                },
                Cell::time(row.timing.median),
                Cell::fixed(row.timing.spread_percent(), 0),
                Cell::fixed(row.timing.median / full_time, 2),
                paper_ratio(&TABLE5_RATIOS, row.modes),
            ]);
        }
        table
    }

    /// Figure 4's data, every point of every model.
    pub fn points_table(&self) -> Table {
        let mut table = Table::new(
            "figure4",
            &[
                ("model", "model"),
                ("F1_N", "F1 (N)"),
                ("tip_x_m", "tip x"),
                ("tip_y_m", "tip y"),
                ("mid_x_m", "mid x"),
                ("mid_y_m", "mid y"),
                ("elastica_tip_x_m", "elastica tip x"),
                ("elastica_tip_y_m", "elastica tip y"),
                ("elastica_mid_x_m", "elastica mid x"),
                ("elastica_mid_y_m", "elastica mid y"),
            ],
        );
        for row in &self.rows {
            for ((t, m), e) in row.tips.iter().zip(&row.mids).zip(&self.reference) {
                table.push(vec![
                    Cell::text(label(row.modes)),
                    Cell::fixed(e.f1, 0),
                    Cell::fixed(t.0, 6),
                    Cell::fixed(t.1, 6),
                    Cell::fixed(m.0, 6),
                    Cell::fixed(m.1, 6),
                    Cell::fixed(e.tip.0, 6),
                    Cell::fixed(e.tip.1, 6),
                    Cell::fixed(e.mid.0, 6),
                    Cell::fixed(e.mid.1, 6),
                ]);
            }
        }
        table
    }

    /// Figure 4: the shapes at F1 = 0, 50, 100, 150 N of the full model, the paper's reduced
    /// models (2 and 3 modes) and the elastica.
    pub fn figure(&self) -> Figure {
        let mut models: Vec<ModelShapes> = self
            .rows
            .iter()
            .filter(|row| matches!(row.modes, None | Some(2) | Some(3)))
            .map(|row| ModelShapes {
                label: format!("{} (n = 10)", label(row.modes)),
                dashed: row.modes.is_some(),
                shapes: row
                    .shapes
                    .iter()
                    .zip(&self.reference)
                    .filter(|(_, e)| SHOWN.contains(&e.f1))
                    .map(|(s, _)| s.clone())
                    .collect(),
            })
            .collect();
        models.push(ModelShapes {
            label: "elastica (reference)".into(),
            dashed: true,
            shapes: self
                .reference_shapes
                .iter()
                .filter(|(f1, _)| SHOWN.contains(f1))
                .map(|(_, nodes)| nodes.clone())
                .collect(),
        });
        Figure {
            stem: "figure4".into(),
            kind: FigureKind::Shapes(ShapesFigure {
                title: "Figure 4: F1 = 0, 50, 100, 150 N at the tip, −150 N at mid-span".into(),
                length: 1.0,
                models,
                gradient: false,
            }),
        }
    }

    /// The report's section.
    pub fn section(&self) -> Section {
        let table = self.table();
        let mut text = String::from(
            "Table 4 beam, n = 10 (the paper's dimension for Table 5): dead upward tip force F1 \
             swept 0, 10, …, 150 N with a constant dead −150 N at mid-span; each point continued \
             from the previous one. Errors are the largest over the 16 points, against the \
             elastica. Times are the whole sweep (median; spread = (max − min)/median). Figure 4 \
             (figure4.svg, .png) shows the shapes at F1 = 0, 50, 100 and 150 N; figure4.csv has \
             every point.\n\n",
        );
        text.push_str(&table.markdown());
        Section {
            title: "Figure 4 and Table 5: two static forces, full against reduced".into(),
            text,
            tables: vec![table, self.points_table()],
            figures: vec![self.figure()],
        }
    }
}
