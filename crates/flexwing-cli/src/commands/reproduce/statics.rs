//! The static cases on the Table 4 beam: Table 3 (a 150 N dead tip force, n = 20) and Table 5 with
//! Figure 4 (a tip force F1 swept 0…150 N with −150 N at mid-span, n = 10), full and reduced, with
//! the elastica as reference.

use anyhow::Result;
use flexwing::model::{AppliedLoads, Force, FullModel, Load, ReducedModel, StructuralModel};
use flexwing::solve::{solve_static, sweep_static, Modes, StaticOptions};

use super::paper::{self, TABLE3_RATIOS, TABLE5_RATIOS};
use super::table::{Cell, Fmt, Table, Timing};
use super::{distance, tip, AccuracyRow, Context, Section};
use crate::plot::{write_shapes, ModelShapes, ShapePlot};

/// Reduced models of the static cases (the paper's 2 and 3, and the others for the accuracy
/// study).
const MODES: [usize; 5] = [1, 2, 3, 4, 6];

fn paper_ratio(ratios: &[(usize, f64)], r: Option<usize>) -> Cell {
    match r {
        None => Cell::fixed(1.0, 2),
        Some(r) => Cell::opt(
            ratios.iter().find(|(k, _)| *k == r).map(|(_, v)| *v),
            Fmt::Fixed(2),
        ),
    }
}

fn label(r: Option<usize>) -> String {
    r.map_or_else(
        || "full".into(),
        |r| format!("reduced, {r} mode{}", if r == 1 { "" } else { "s" }),
    )
}

/// Table 3: one dead tip force of 150 N, n = 20.
pub fn table3(ctx: &Context) -> Result<(Section, Vec<AccuracyRow>)> {
    let force = 150.0;
    let full = paper::table4_beam(20)?;
    let loads = full.apply(
        &[Load::PointForce {
            span: 1.0,
            force: Force::Dead { fx: 0.0, fy: force },
        }],
        "loads",
    )?;
    let reference = paper::elastica_tip(force)?;
    let options = StaticOptions::default();
    let modes_timing = Timing::measure(ctx.repeats, || {
        std::hint::black_box(Modes::undeformed(&full).ok());
    });
    let modes = Modes::undeformed(&full)?;
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
    let mut accuracy = Vec::new();
    let mut full_tip = (0.0, 0.0);
    let mut full_time = 0.0;
    for r in std::iter::once(None).chain(MODES.iter().map(|&r| Some(r))) {
        let (sol_tip, timing) = match r {
            None => solve_timed(ctx, &full, &full, &loads, &options)?,
            Some(r) => {
                let rom = ReducedModel::first(&full, modes.shapes(), r)?;
                solve_timed(ctx, &full, &rom, &loads, &options)?
            }
        };
        if r.is_none() {
            full_tip = sol_tip;
            full_time = timing.median;
        }
        let diff = distance(sol_tip, full_tip);
        let displacement = distance(full_tip, (1.0, 0.0));
        if let Some(r) = r {
            accuracy.push(AccuracyRow {
                case: "static, tip force 150 N (n = 20)".into(),
                modes: r,
                difference: diff,
                relative: diff / displacement,
                reference_error: Some(distance(sol_tip, reference)),
            });
        }
        table.push(vec![
            Cell::text(label(r)),
            Cell::Num(r.unwrap_or(full.n_dofs()) as f64, Fmt::Fixed(0)),
            Cell::fixed(sol_tip.0, 5),
            Cell::fixed(sol_tip.1, 5),
            Cell::sci(distance(sol_tip, reference), 2),
            if r.is_some() {
                Cell::sci(diff, 2)
            } else {
                Cell::Empty
            },
            Cell::time(timing.median),
            Cell::fixed(timing.spread_percent(), 0),
            Cell::fixed(timing.median / full_time, 2),
            paper_ratio(&TABLE3_RATIOS, r),
        ]);
    }
    let mut text = format!(
        "Table 4 beam (L = 1 m, EI = 50 N·m², m = 0.2 kg/m), n = 20, dead vertical tip force \
         {force} N (α = FL²/EI = 3), Newton with load stepping from rest. Elastica tip: \
         ({:.5}, {:.5}) m. Times are one complete static solve (median over {} samples; spread \
         = (max − min)/median); reduced models exclude the offline modal analysis, {}.\n\n",
        reference.0,
        reference.1,
        ctx.repeats,
        modes_timing.text()
    );
    text.push_str(&table.markdown());
    Ok((
        Section {
            title: "Table 3: static tip force, full against reduced".into(),
            text,
            files: vec![table.write_csv(&ctx.out)?],
        },
        accuracy,
    ))
}

/// Solve once for the tip, then time repeated solves.
fn solve_timed<M: StructuralModel>(
    ctx: &Context,
    full: &FullModel,
    model: &M,
    loads: &AppliedLoads,
    options: &StaticOptions,
) -> Result<((f64, f64), Timing)> {
    let sol = solve_static(model, loads, &[1.0], options)?;
    let timing = Timing::measure(ctx.repeats, || {
        std::hint::black_box(solve_static(model, loads, &[1.0], options).ok());
    });
    Ok((tip(full, &sol.q), timing))
}

/// Table 5 and Figure 4: F1 = 0, 10, …, 150 N upward at the tip with F2 = −150 N at mid-span,
/// each point continued from the previous one, n = 10.
pub fn table5(ctx: &Context) -> Result<(Section, Vec<AccuracyRow>)> {
    let full = paper::table4_beam(10)?;
    let loads = full.apply(
        &[
            Load::PointForce {
                span: 1.0,
                force: Force::Dead { fx: 0.0, fy: 1.0 },
            },
            Load::PointForce {
                span: 0.5,
                force: Force::Dead {
                    fx: 0.0,
                    fy: -150.0,
                },
            },
        ],
        "loads",
    )?;
    let reference = paper::elastica_two_loads()?;
    let points: Vec<Vec<f64>> = reference.iter().map(|p| vec![p.f1, 1.0]).collect();
    let options = StaticOptions::default();
    let modes = Modes::undeformed(&full)?;
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
    let mut points_table = Table::new(
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
    let shown = [0.0, 50.0, 100.0, 150.0];
    let mut shapes = Vec::new();
    let mut accuracy = Vec::new();
    let mut full_tips: Vec<(f64, f64)> = Vec::new();
    let mut full_time = 0.0;
    for r in std::iter::once(None).chain(MODES.iter().map(|&r| Some(r))) {
        let rom = r
            .map(|r| ReducedModel::first(&full, modes.shapes(), r))
            .transpose()?;
        let sweep = |o: &StaticOptions| match &rom {
            None => sweep_static(&full, &loads, &points, o),
            Some(rom) => sweep_static(rom, &loads, &points, o),
        };
        let solutions = sweep(&options)?;
        let timing = Timing::measure(ctx.repeats, || {
            std::hint::black_box(sweep(&options).ok());
        });
        let tips: Vec<(f64, f64)> = solutions.iter().map(|s| tip(&full, &s.q)).collect();
        if r.is_none() {
            full_tips = tips.clone();
            full_time = timing.median;
        }
        let error = tips
            .iter()
            .zip(&reference)
            .map(|(t, e)| distance(*t, e.tip))
            .fold(0.0, f64::max);
        let diff = tips
            .iter()
            .zip(&full_tips)
            .map(|(a, b)| distance(*a, *b))
            .fold(0.0, f64::max);
        let displacement = full_tips
            .iter()
            .map(|t| distance(*t, (1.0, 0.0)))
            .fold(0.0, f64::max);
        if let Some(r) = r {
            accuracy.push(AccuracyRow {
                case: "static, two forces, F1 = 0…150 N (n = 10)".into(),
                modes: r,
                difference: diff,
                relative: diff / displacement,
                reference_error: Some(error),
            });
        }
        table.push(vec![
            Cell::text(label(r)),
            Cell::Num(r.unwrap_or(full.n_dofs()) as f64, Fmt::Fixed(0)),
            Cell::sci(error, 2),
            if r.is_some() {
                Cell::sci(diff, 2)
            } else {
                Cell::Empty
            },
            Cell::time(timing.median),
            Cell::fixed(timing.spread_percent(), 0),
            Cell::fixed(timing.median / full_time, 2),
            paper_ratio(&TABLE5_RATIOS, r),
        ]);
        for ((sol, e), t) in solutions.iter().zip(&reference).zip(&tips) {
            let kin = full.kinematics(&sol.q);
            let mid = full.point_position(&kin, 0.5);
            points_table.push(vec![
                Cell::text(label(r)),
                Cell::fixed(e.f1, 0),
                Cell::fixed(t.0, 6),
                Cell::fixed(t.1, 6),
                Cell::fixed(mid[0], 6),
                Cell::fixed(mid[1], 6),
                Cell::fixed(e.tip.0, 6),
                Cell::fixed(e.tip.1, 6),
                Cell::fixed(e.mid.0, 6),
                Cell::fixed(e.mid.1, 6),
            ]);
        }
        if matches!(r, None | Some(2) | Some(3)) {
            shapes.push(ModelShapes {
                label: format!("{} (n = 10)", label(r)),
                dashed: r.is_some(),
                shapes: solutions
                    .iter()
                    .zip(&reference)
                    .filter(|(_, e)| shown.contains(&e.f1))
                    .map(|(s, _)| {
                        full.node_positions(&full.kinematics(&s.q))
                            .iter()
                            .map(|p| (p[0], p[1]))
                            .collect()
                    })
                    .collect(),
            });
        }
    }
    shapes.push(ModelShapes {
        label: "elastica (reference)".into(),
        dashed: true,
        shapes: paper::elastica_two_loads_shapes()?
            .into_iter()
            .filter(|(f1, _)| shown.contains(f1))
            .map(|(_, nodes)| nodes)
            .collect(),
    });
    let mut files = vec![
        table.write_csv(&ctx.out)?,
        points_table.write_csv(&ctx.out)?,
    ];
    files.extend(write_shapes(
        &ctx.out,
        "figure4",
        &ShapePlot {
            title: "Figure 4: F1 = 0, 50, 100, 150 N at the tip, −150 N at mid-span".into(),
            length: 1.0,
            models: shapes,
            gradient: false,
        },
    )?);
    let mut text = String::from(
        "Table 4 beam, n = 10 (the paper's dimension for Table 5): dead upward tip force F1 \
         swept 0, 10, …, 150 N with a constant dead −150 N at mid-span; each point continued \
         from the previous one. Errors are the largest over the 16 points, against the \
         elastica. Times are the whole sweep (median; spread = (max − min)/median). Figure 4 \
         (figure4.svg, .png) shows the shapes at F1 = 0, 50, 100 and 150 N; figure4.csv has \
         every point.\n\n",
    );
    text.push_str(&table.markdown());
    Ok((
        Section {
            title: "Figure 4 and Table 5: two static forces, full against reduced".into(),
            text,
            files,
        },
        accuracy,
    ))
}
