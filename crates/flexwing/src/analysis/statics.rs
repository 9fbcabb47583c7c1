//! Non-linear statics of the full model and of reduced models under one set of loads, at one
//! load level or over a sweep of one load's scale, each point continued from the previous one
//! ([`crate::solve::sweep_static`]); optionally the modes about the full model's last
//! equilibrium.
//!
//! A model whose sweep stops early does not stop the analysis: the other models are solved and
//! each run keeps the points that converged, with the reason it stopped
//! ([`Stop::StaticPoint`]).

use std::time::Instant;

use super::models::{reduced_models, ModelKind};
use super::{Progress, Status, Stop};
use crate::error::{Error, InputError, SolveError};
use crate::model::StructuralModel;
use crate::model::{AppliedLoads, DistributedForce, Force, FullModel, Load, ReducedModel, Shape};
use crate::solve::{sweep_static_until, Modes, StaticOptions, StaticSolution, StaticStats};
use crate::text::short;

/// A static analysis. Build it with [`StaticPlan::new`], set the fields, and check it with
/// [`StaticPlan::validate`] under the caller's names.
#[derive(Debug, Clone)]
pub struct StaticPlan {
    /// The full model.
    pub model: FullModel,
    /// The loads, applied together; each at scale 1 except the swept one.
    pub loads: Vec<Load>,
    /// Solve the full model. Default `true`.
    pub full: bool,
    /// Reduced models on the first `r` modes, one per entry.
    pub reduced: Vec<usize>,
    /// Reduced models on listed modes (1-based), one per list.
    pub reduced_modes: Vec<Vec<usize>>,
    /// Newton's options; their errors name `{prefix}.tolerance`, `{prefix}.min_step`, ….
    pub options: StaticOptions,
    /// Number of modes reported about the full model's last equilibrium.
    pub modes: Option<usize>,
    /// The sweep of one load's scale; without it, one point with every load at scale 1.
    pub sweep: Option<Sweep>,
    /// How the caller names each load in messages (a case file: its `name`); a load without
    /// an entry is `loads[i]`.
    pub load_names: Vec<String>,
}

/// A sweep of the scale of one load.
#[derive(Debug, Clone, PartialEq)]
pub struct Sweep {
    /// Index of the swept load in [`StaticPlan::loads`].
    pub load: usize,
    /// Its scale at each point, in order.
    pub scales: Vec<f64>,
}

impl StaticPlan {
    /// The full model under `loads` at scale 1, with the default options.
    pub fn new(model: FullModel, loads: Vec<Load>) -> Self {
        Self {
            model,
            loads,
            full: true,
            reduced: Vec::new(),
            reduced_modes: Vec::new(),
            options: StaticOptions::default(),
            modes: None,
            sweep: None,
            load_names: Vec::new(),
        }
    }

    /// Check the plan; errors name the loads `{loads_field}[i]…` and everything else
    /// `{prefix}.…` (a case file: `loads` and `static`).
    ///
    /// # Errors
    /// No load, a load the model cannot carry, nothing to solve, a reduced model on modes the
    /// model does not have, options out of range, loaded modes without the full model or with
    /// follower loads (whose tangent stiffness is not symmetric), a sweep of no load or with
    /// non-finite scales.
    pub fn validate(&self, loads_field: &str, prefix: &str) -> Result<(), InputError> {
        let field = |key: &str| crate::field(prefix, key);
        if self.loads.is_empty() {
            return Err(InputError::new(
                loads_field,
                "a static analysis needs at least one load",
            ));
        }
        self.model.apply(&self.loads, loads_field)?;
        let n_dofs = self.model.n_dofs();
        let reduced = reduced_models(&self.reduced, &self.reduced_modes, n_dofs, prefix)?;
        if !self.full && reduced.is_empty() {
            return Err(InputError::new(
                field("full"),
                format!(
                    "nothing to solve: full = false and no reduced models (give {} or {})",
                    field("reduced"),
                    field("reduced_modes")
                ),
            ));
        }
        if let Some(count) = self.modes {
            self.check_loaded_modes(count, loads_field, &field("modes"))?;
        }
        if let Some(sweep) = &self.sweep {
            if sweep.load >= self.loads.len() {
                return Err(InputError::new(
                    field("sweep.load"),
                    format!("there is no load {} (of {})", sweep.load, self.loads.len()),
                ));
            }
            if sweep.scales.is_empty() {
                return Err(InputError::new(field("sweep.scales"), "must not be empty"));
            }
            if let Some(i) = sweep.scales.iter().position(|v| !v.is_finite()) {
                return Err(InputError::new(
                    field(&format!("sweep.scales[{i}]")),
                    format!("must be finite, got {}", short(sweep.scales[i])),
                ));
            }
            for (i, &v) in sweep.scales.iter().enumerate() {
                crate::magnitude::check(&field(&format!("sweep.scales[{i}]")), "", v)?;
            }
        }
        self.options.validate(prefix)
    }

    fn check_loaded_modes(
        &self,
        count: usize,
        loads_field: &str,
        field: &str,
    ) -> Result<(), InputError> {
        let n_dofs = self.model.n_dofs();
        if !(1..=n_dofs).contains(&count) {
            return Err(InputError::new(
                field,
                format!(
                    "must be between 1 and the number of degrees of freedom ({n_dofs}), got {count}"
                ),
            ));
        }
        if !self.full {
            return Err(InputError::new(
                field,
                "loaded modes are computed about the full model's equilibrium, which needs \
                 full = true",
            ));
        }
        let follower = self.loads.iter().position(|l| {
            matches!(
                l,
                Load::PointForce {
                    force: Force::Follower { .. },
                    ..
                } | Load::Distributed(DistributedForce::Follower { .. })
            )
        });
        if let Some(i) = follower {
            return Err(InputError::new(
                field,
                format!(
                    "loaded modes need conservative loads, but {loads_field}[{i}] is a follower \
                     force (its tangent stiffness is not symmetric)"
                ),
            ));
        }
        Ok(())
    }

    /// The models solved, in order: the full model (if asked), then the reduced models of
    /// `reduced` and `reduced_modes`.
    ///
    /// # Errors
    /// As [`StaticPlan::validate`] for the reduced models.
    pub fn models(&self) -> Result<Vec<ModelKind>, InputError> {
        let reduced = reduced_models(&self.reduced, &self.reduced_modes, self.model.n_dofs(), "")?;
        let full = self.full.then_some(ModelKind::Full);
        Ok(full
            .into_iter()
            .chain(reduced.into_iter().map(|(k, _)| k))
            .collect())
    }

    /// The caller's name of load `i` ([`StaticPlan::load_names`], else `loads[i]`).
    pub fn load_name(&self, i: usize) -> String {
        super::load_name(&self.load_names, i)
    }

    /// The scale of the swept load at each point; `[1]` without a sweep.
    pub fn point_scales(&self) -> Vec<f64> {
        self.sweep.as_ref().map_or(vec![1.0], |s| s.scales.clone())
    }

    /// The scales of all loads at each point: 1, except the swept load.
    pub fn points(&self) -> Vec<Vec<f64>> {
        let n_loads = self.loads.len();
        match &self.sweep {
            None => vec![vec![1.0; n_loads]],
            Some(s) => s
                .scales
                .iter()
                .map(|&v| {
                    let mut p = vec![1.0; n_loads];
                    p[s.load] = v;
                    p
                })
                .collect(),
        }
    }
}

/// The equilibria of one model over the sweep.
#[derive(Debug, Clone)]
pub struct StaticRun {
    /// Which model.
    pub kind: ModelKind,
    /// Number of coordinates of the model.
    pub dofs: usize,
    /// Wall time of the solve over all points (s).
    pub wall_time_s: f64,
    /// The converged points, in sweep order from the first.
    pub points: Vec<StaticPoint>,
    /// Whether every point converged, or where and why the sweep stopped.
    pub status: Status,
}

impl StaticRun {
    /// Largest tip difference from the full model over the points both solved (reduced models).
    pub fn max_tip_difference(&self) -> Option<f64> {
        self.points
            .iter()
            .filter_map(|p| p.tip_difference)
            .reduce(f64::max)
    }
}

/// One equilibrium, as nodal quantities of the full model.
#[derive(Debug, Clone)]
pub struct StaticPoint {
    /// Scale of the swept load (1 without a sweep).
    pub scale: f64,
    /// Scales of all loads.
    pub scales: Vec<f64>,
    /// The deformed shape.
    pub shape: Shape,
    /// Joint rotations of the full model at the equilibrium (rad).
    pub q: Vec<f64>,
    /// Solver counters of this point.
    pub stats: StaticStats,
    /// Distance of the tip from the full model's tip at the same point (m); reduced models only.
    pub tip_difference: Option<f64>,
}

impl StaticPoint {
    /// Tip position and twist `(x, y, twist)`.
    pub fn tip(&self) -> (f64, f64, f64) {
        self.shape.tip()
    }
}

/// A mode about the full model's final equilibrium.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoadedMode {
    /// Mode number, 1-based.
    pub mode: usize,
    /// Circular frequency about the loaded equilibrium (rad/s).
    pub omega: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Circular frequency of the same-numbered mode about the undeformed state (rad/s).
    pub unloaded_omega: f64,
}

/// What a static analysis found.
#[derive(Debug, Clone)]
pub struct StaticOutcome {
    /// One run per model, in the order of [`StaticPlan::models`].
    pub runs: Vec<StaticRun>,
    /// The loaded modes, if asked for and the full model reached the last point: the modes, or
    /// why the modal analysis failed.
    pub loaded_modes: Option<Result<Vec<LoadedMode>, SolveError>>,
}

impl StaticOutcome {
    /// The full model's run, if it was solved.
    pub fn full(&self) -> Option<&StaticRun> {
        self.runs.iter().find(|r| r.kind == ModelKind::Full)
    }

    /// Wall time of `run` over that of the full model.
    pub fn ratio_to_full(&self, run: &StaticRun) -> Option<f64> {
        let full = self.full()?;
        (full.wall_time_s > 0.0).then(|| run.wall_time_s / full.wall_time_s)
    }

    /// Whether every model reached every point and the loaded modes (if asked) were found.
    pub fn is_complete(&self) -> bool {
        self.runs.iter().all(|r| r.status.is_complete())
            && !matches!(self.loaded_modes, Some(Err(_)))
    }
}

/// Run the static analysis of `plan`.
///
/// # Errors
/// An invalid plan ([`StaticPlan::validate`], fields named relative to the plan), or the modal
/// analysis about the undeformed state (needed by reduced models and loaded modes) failing.
/// Solver failures of a model are in its run's [`Status`].
///
/// ```
/// use flexwing::analysis::{statics, NoProgress};
/// use flexwing::model::{Force, Load};
/// let model = flexwing::paper::table4_beam(20)?;
/// let tip = Load::PointForce { span: 1.0, force: Force::Dead { fx: 0.0, fy: 150.0 } };
/// let mut plan = statics::StaticPlan::new(model, vec![tip]);
/// plan.reduced = vec![3];
/// plan.validate("loads", "static")?;
/// let outcome = statics::run(&plan, &mut NoProgress)?;
/// let (x, y, _) = outcome.runs[0].points[0].tip();
/// // α = FL²/EI = 3: the elastica's tip is at (0.74558, 0.60325) m.
/// assert!((x - 0.74558).hypot(y - 0.60325) < 3e-4);
/// assert!(outcome.runs[1].max_tip_difference().unwrap() < 5e-4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn run(plan: &StaticPlan, progress: &mut dyn Progress) -> Result<StaticOutcome, Error> {
    plan.validate("loads", "")?;
    let full = &plan.model;
    let applied = full.apply(&plan.loads, "loads")?;
    let kinds = plan.models()?;
    let count = super::models::modes_needed(&kinds)
        .into_iter()
        .chain(plan.modes)
        .max();
    let unloaded = count.map(|c| Modes::lowest(full, c)).transpose()?;
    let solver = Solver {
        full,
        applied: &applied,
        points: plan.points(),
        scales: plan.point_scales(),
        options: &plan.options,
        swept: plan
            .sweep
            .as_ref()
            .map(|s| super::load_name(&plan.load_names, s.load)),
    };
    let mut runs = Vec::with_capacity(kinds.len());
    for (k, kind) in kinds.iter().enumerate() {
        progress.start(k, kinds.len(), &kind.label());
        let run = match (kind.mode_indices(), &unloaded) {
            (Some(indices), Some(modes)) => {
                let rom = ReducedModel::new(full, modes.shapes(), &indices)?;
                solver.run(kind.clone(), &rom, progress)
            }
            _ => solver.run(kind.clone(), full, progress),
        };
        progress.advance(1.0);
        progress.finish();
        runs.push(run);
    }
    compare_tips(&mut runs);
    let interrupted = runs
        .iter()
        .any(|r| matches!(r.status.stop(), Some(Stop::SweepInterrupted { .. })));
    let loaded_modes = match (plan.modes, &unloaded) {
        _ if interrupted => None,
        (Some(count), Some(unloaded)) => loaded_modes(full, &applied, &runs, count, unloaded),
        _ => None,
    };
    Ok(StaticOutcome { runs, loaded_modes })
}

/// What every model's sweep shares.
struct Solver<'a> {
    full: &'a FullModel,
    applied: &'a AppliedLoads,
    points: Vec<Vec<f64>>,
    scales: Vec<f64>,
    options: &'a StaticOptions,
    /// The name of the swept load, if any.
    swept: Option<String>,
}

impl Solver<'_> {
    /// Sweep `model`, timing the solve alone; `progress` is asked before each point whether
    /// to stop ([`Stop::SweepInterrupted`]).
    fn run<M: StructuralModel>(
        &self,
        kind: ModelKind,
        model: &M,
        progress: &mut dyn Progress,
    ) -> StaticRun {
        let start = Instant::now();
        let result =
            sweep_static_until(model, self.applied, &self.points, self.options, &mut || {
                progress.cancelled()
            });
        let wall_time_s = start.elapsed().as_secs_f64();
        let (solutions, status) = match result {
            Ok(s) if s.len() < self.points.len() => {
                let stop = Stop::SweepInterrupted {
                    done: s.len(),
                    points: self.points.len(),
                };
                (s, Status::Stopped(stop))
            }
            Ok(s) => (s, Status::Complete),
            Err(e) => {
                // The solver's load factor runs from the previous point (rest before the first)
                // to the failed one; say which scale it reached.
                let scale = self.scales[e.point];
                let reached = match &e.error {
                    SolveError::StaticDiverged { load_factor, .. } => {
                        let previous = e.point.checked_sub(1).map_or(0.0, |p| self.scales[p]);
                        Some(previous + load_factor * (scale - previous))
                    }
                    _ => None,
                };
                let stop = Stop::StaticPoint {
                    point: e.point,
                    points: self.points.len(),
                    scale,
                    reached,
                    load: self.swept.clone(),
                    error: e.error,
                };
                (e.completed, Status::Stopped(stop))
            }
        };
        StaticRun {
            kind,
            dofs: model.n_dofs(),
            wall_time_s,
            points: solutions
                .iter()
                .zip(&self.scales)
                .map(|(s, &scale)| self.point(s, scale))
                .collect(),
            status,
        }
    }

    fn point(&self, sol: &StaticSolution, scale: f64) -> StaticPoint {
        StaticPoint {
            scale,
            scales: sol.scales.clone(),
            shape: self.full.shape(&sol.q),
            q: sol.q.clone(),
            stats: sol.stats,
            tip_difference: None,
        }
    }
}

/// Fill in each reduced model's tip distance from the full model, point by point.
fn compare_tips(runs: &mut [StaticRun]) {
    let Some(full) = runs.iter().position(|r| r.kind == ModelKind::Full) else {
        return;
    };
    let tips: Vec<(f64, f64, f64)> = runs[full].points.iter().map(StaticPoint::tip).collect();
    for run in runs.iter_mut().filter(|r| r.kind.modes().is_some()) {
        for (p, reference) in run.points.iter_mut().zip(&tips) {
            let (x, y, _) = p.tip();
            p.tip_difference = Some((x - reference.0).hypot(y - reference.1));
        }
    }
}

/// Modes about the full model's equilibrium at the last point; `None` if the full model did
/// not reach it (its run says why).
fn loaded_modes(
    full: &FullModel,
    applied: &AppliedLoads,
    runs: &[StaticRun],
    count: usize,
    unloaded: &Modes,
) -> Option<Result<Vec<LoadedMode>, SolveError>> {
    let run = runs.iter().find(|r| r.kind == ModelKind::Full)?;
    if !run.status.is_complete() {
        return None;
    }
    let last = run.points.last()?;
    Some(
        Modes::lowest_loaded(full, &last.q, applied, &last.scales, count).map(|modes| {
            (0..count.min(modes.n_modes()).min(unloaded.n_modes()))
                .map(|k| LoadedMode {
                    mode: k + 1,
                    omega: modes.omega()[k],
                    frequency_hz: modes.omega()[k] / (2.0 * std::f64::consts::PI),
                    unloaded_omega: unloaded.omega()[k],
                })
                .collect()
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> StaticPlan {
        let model = crate::paper::table4_beam(4).unwrap();
        let loads = vec![
            Load::PointForce {
                span: 1.0,
                force: Force::Dead { fx: 0.0, fy: 1.0 },
            },
            Load::Gravity { g: 9.81 },
        ];
        StaticPlan::new(model, loads)
    }

    #[test]
    fn defaults_solve_the_full_model_at_scale_one() {
        let p = plan();
        assert!(p.validate("loads", "static").is_ok());
        assert_eq!(p.models().unwrap(), [ModelKind::Full]);
        assert_eq!(p.options, StaticOptions::default());
        assert_eq!(p.points(), [vec![1.0, 1.0]]);
        assert_eq!(p.point_scales(), [1.0]);
        let mut swept = plan();
        swept.sweep = Some(Sweep {
            load: 0,
            scales: vec![0.0, 0.3],
        });
        assert_eq!(swept.points()[1], [0.3, 1.0]);
    }

    #[test]
    fn errors_name_the_callers_fields() {
        type Change = Box<dyn Fn(&mut StaticPlan)>;
        let cases: Vec<(Change, &str)> =
            vec![
            (Box::new(|p| p.loads.clear()), "loads: a static analysis needs"),
            (
                Box::new(|p| p.loads.push(Load::Gravity { g: f64::NAN })),
                "loads[2].g: must be finite",
            ),
            (Box::new(|p| p.full = false), "static.full: nothing to solve"),
            (Box::new(|p| p.reduced = vec![2, 2]), "static.reduced[1]: the model"),
            (
                Box::new(|p| p.modes = Some(5)),
                "static.modes: must be between 1 and the number of degrees of freedom (4), got 5",
            ),
            (
                Box::new(|p| {
                    p.full = false;
                    p.reduced = vec![2];
                    p.modes = Some(2)
                }),
                "static.modes: loaded modes are computed about the full",
            ),
            (
                Box::new(|p| {
                    p.loads[0] = Load::PointForce {
                        span: 1.0,
                        force: Force::Follower {
                            tangential: 0.0,
                            normal: 1.0,
                        },
                    };
                    p.modes = Some(2)
                }),
                "static.modes: loaded modes need conservative loads, but loads[0]",
            ),
            (
                Box::new(|p| {
                    p.sweep = Some(Sweep {
                        load: 0,
                        scales: vec![0.0, f64::NAN],
                    })
                }),
                "static.sweep.scales[1]: must be finite",
            ),
            (
                Box::new(|p| p.options.tolerance = -1.0),
                "static.tolerance: must be a finite positive number, got -1",
            ),
            (Box::new(|p| p.options.min_step = 2.0), "static.min_step:"),
            (Box::new(|p| p.options.max_iterations = 0), "static.max_iterations:"),
        ];
        for (change, expected) in cases {
            let mut p = plan();
            change(&mut p);
            let msg = p.validate("loads", "static").unwrap_err().to_string();
            assert!(msg.starts_with(expected), "{msg}");
        }
    }
}
