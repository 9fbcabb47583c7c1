//! Arc-length continuation of static equilibria: follows the path `R(x, λ) = K x − Q(x; s(λ)) = 0`,
//! `s(λ) = s₀ + λ (s₁ − s₀)`, through limit points (snap-through, snap-back) where load control
//! must stop, and marks the stability of every point.
//!
//! Method: Riks' arc-length method (E. Riks, "An incremental approach to the solution of snapping
//! and buckling problems", Int. J. Solids Struct. 15, 1979) in Keller's pseudo-arclength form
//! (H. B. Keller, "Numerical solution of bifurcation and nonlinear eigenvalue problems", 1977): a
//! tangent predictor `y_p = y_i + Δs t_i` for `y = (x, λ)`, then Newton on `R = 0` together with the
//! hyperplane constraint `⟨t_i, y − y_p⟩ = 0`, solved as one bordered system
//!
//! ```text
//! [ K_T      −∂Q/∂λ ] [δx]     [ R ]          ∂Q/∂λ = Q(x; s₁ − s₀)
//! [ (W t_x)ᵀ  ψ² t_λ ] [δλ] = − [ g ]          (Q is linear in the scales)
//! ```
//!
//! which stays regular at a limit point, where `K_T` is singular. The next tangent solves the
//! same matrix with the right-hand side `(0, 1)`, so it keeps the orientation of the previous one
//! (`⟨t_i, t_{i+1}⟩ > 0`) and the path turns at limit points by itself. Lengths are measured in
//! the metric `‖(δx, δλ)‖² = rms(δθ, δψ)² + ψ² δλ²`: the root mean square change of the elements'
//! absolute rotations (rad, independent of `n` and of the model's coordinates), and the load
//! factor weighted by `ψ`, by default the rms rotation per unit load factor of the linear
//! response at the start (so neither part dominates the first step). The step length follows
//! Crisfield's rule `Δs ← Δs √(I_d / I)` (M. A. Crisfield, *Non-linear Finite Element Analysis of
//! Solids and Structures*, vol. 1, 1991, §9.5), capped by the largest rotation change per step as
//! in load control. Crisfield's own spherical constraint was not chosen: its quadratic for `δλ`
//! has complex roots near sharp turns, while the linear constraint of the bordered system has none.
//!
//! The path ends at `λ = 1` (the step that crosses it is replaced by a load-control solve at
//! exactly `λ = 1`), or stops with the points found so far.

use nalgebra::{DMatrix, DVector};

use super::statics::{max_rotation, tangent_stability, Newton, Newtonian};
use super::{StaticOptions, StaticSolution, StaticStats};
use crate::error::{InputError, SolveError, StaticFailure};
use crate::model::{AppliedLoads, StructuralModel};

/// Options of arc-length continuation.
#[derive(Debug, Clone, PartialEq)]
pub struct ArcLengthOptions {
    /// Convergence when `‖R‖∞ ≤ tolerance · max(‖K x‖∞, ‖Q(x)‖∞)`. Default `1e-10`.
    pub tolerance: f64,
    /// Newton iterations allowed per step before the arc length is halved. Default 20.
    pub max_iterations: usize,
    /// Newton iterations a step should take; the next arc length scales with
    /// `√(target_iterations / iterations)`. Default 4.
    pub target_iterations: usize,
    /// First arc length (rad of rms rotation, see the module documentation), clamped to
    /// `[min_arc, max_arc]`. Default `0.05`.
    pub initial_arc: f64,
    /// Largest arc length. Default `0.2`.
    pub max_arc: f64,
    /// Smallest arc length before giving up. Default `1e-7`.
    pub min_arc: f64,
    /// Largest change of any element's absolute rotation per step (rad), as
    /// [`StaticOptions::max_rotation_step`]. Default `1.0`.
    pub max_rotation_step: f64,
    /// Most points on the path (the start included) before giving up. Default 2000.
    pub max_points: usize,
    /// Weight `ψ` of the load factor in the arc length (rad per unit load factor); `None`: the rms
    /// rotation per unit load factor of the linear response at the start. Default `None`.
    pub load_weight: Option<f64>,
}

impl Default for ArcLengthOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 20,
            target_iterations: 4,
            initial_arc: 0.05,
            max_arc: 0.2,
            min_arc: 1e-7,
            max_rotation_step: 1.0,
            max_points: 2000,
            load_weight: None,
        }
    }
}

impl ArcLengthOptions {
    /// Check the options; error fields are `{field}.tolerance` etc.
    ///
    /// # Errors
    /// A non-finite or non-positive tolerance, arc length, rotation step or load weight,
    /// `max_arc < min_arc`, no iteration, fewer than two points.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        let bad = |f: &str, v: f64, what: &str| {
            Err(InputError::new(
                format!("{field}.{f}"),
                format!("must be {what}, got {v}"),
            ))
        };
        let positive = |v: f64| v > 0.0 && v.is_finite();
        if !positive(self.tolerance) {
            return bad("tolerance", self.tolerance, "a finite positive number");
        }
        if !positive(self.min_arc) {
            return bad("min_arc", self.min_arc, "a finite positive number");
        }
        if !(positive(self.max_arc) && self.max_arc >= self.min_arc) {
            return bad("max_arc", self.max_arc, "finite and at least min_arc");
        }
        if !positive(self.initial_arc) {
            return bad("initial_arc", self.initial_arc, "a finite positive number");
        }
        if !positive(self.max_rotation_step) {
            return bad(
                "max_rotation_step",
                self.max_rotation_step,
                "a finite positive angle (rad)",
            );
        }
        if self.max_iterations == 0 {
            return bad("max_iterations", 0.0, "at least 1");
        }
        if self.target_iterations == 0 {
            return bad("target_iterations", 0.0, "at least 1");
        }
        if self.max_points < 2 {
            return bad("max_points", self.max_points as f64, "at least 2");
        }
        if let Some(w) = self.load_weight {
            if !positive(w) {
                return bad("load_weight", w, "a finite positive number");
            }
        }
        Ok(())
    }
}

/// One equilibrium on a path.
#[derive(Debug, Clone, PartialEq)]
pub struct PathPoint {
    /// Load factor `λ` (`scales = s₀ + λ (s₁ − s₀)`); may leave `[0, 1]` along the path.
    pub load_factor: f64,
    /// Arc length from the start, summed over the steps (chord lengths in the path metric).
    pub arc_length: f64,
    /// The equilibrium, its stability (`solution.stable`), and the counters of the step that
    /// found it.
    pub solution: StaticSolution,
}

/// An equilibrium path, in order from the start.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticPath {
    /// The points: the start first; the last is at `λ = 1` when the path is complete.
    pub points: Vec<PathPoint>,
    /// The load weight `ψ` used.
    pub load_weight: f64,
    /// Counters over the whole path.
    pub stats: StaticStats,
}

impl StaticPath {
    /// Indices of the points where the load factor turns (limit points, to the step size): `λ`
    /// rises to them and falls after them, or the reverse.
    pub fn limit_points(&self) -> Vec<usize> {
        let l: Vec<f64> = self.points.iter().map(|p| p.load_factor).collect();
        (1..l.len().saturating_sub(1))
            .filter(|&i| (l[i] - l[i - 1]) * (l[i + 1] - l[i]) < 0.0)
            .collect()
    }

    /// Number of points marked unstable (`stable == Some(false)`).
    pub fn unstable_points(&self) -> usize {
        self.points
            .iter()
            .filter(|p| p.solution.stable == Some(false))
            .count()
    }
}

/// A path that stopped before `λ = 1`: the points found and why it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct PathError {
    /// The path up to the last converged point.
    pub path: StaticPath,
    /// Why it stopped: [`SolveError::ArcLengthStalled`] or
    /// [`SolveError::ArcLengthTooManyPoints`] (or an invalid option).
    pub error: SolveError,
}

impl std::fmt::Display for PathError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for PathError {}

/// Follow the equilibrium path from `start = (x, scales₀)` (an equilibrium) towards the load
/// scales `scales₁`, by arc-length continuation in the load factor `λ` of
/// `s(λ) = scales₀ + λ (scales₁ − scales₀)`, until `λ = 1`. Unlike load control the path may pass
/// limit points (where `λ` turns back) and unstable stretches; every point carries its stability
/// (`solution.stable`, see [`StaticSolution::stable`]).
///
/// ```
/// use flexwing::model::{Force, Load};
/// use flexwing::solve::{arc_length_static, ArcLengthOptions};
///
/// let full = flexwing::paper::table4_beam(20)?;
/// let loads = full.apply(&[Load::PointForce { span: 1.0, force: Force::Dead { fx: 0.0, fy: 150.0 } }], "loads")?;
/// let rest = vec![0.0; 20];
/// let path = arc_length_static(&full, &loads, (&rest, &[0.0]), &[1.0], &ArcLengthOptions::default())?;
/// let end = path.points.last().unwrap();
/// assert_eq!(end.load_factor, 1.0);
/// assert_eq!(end.solution.stable, Some(true));
/// assert!(path.limit_points().is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`PathError`] (boxed) with the points found: the corrector failed down to `options.min_arc`
/// ([`SolveError::ArcLengthStalled`]), the path used up `options.max_points`
/// ([`SolveError::ArcLengthTooManyPoints`]), the tangent at the start is singular, or an option
/// is invalid (fields `arc_length.*`).
pub fn arc_length_static<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    start: (&[f64], &[f64]),
    scales: &[f64],
    options: &ArcLengthOptions,
) -> Result<StaticPath, Box<PathError>> {
    let (x_start, s_start) = start;
    let mut run = Run::new(model, loads, s_start, scales, options);
    if let Err(e) = options.validate("arc_length") {
        return Err(run.stop(SolveError::InvalidInput(e)));
    }
    let x = DVector::from_column_slice(x_start);
    let k_t = run.newton.tangent(&x, s_start);
    let stable = tangent_stability(k_t.clone(), run.conservative);
    run.newton.stats.stability_checks += 1;
    // Initial tangent: K_T v = ∂Q/∂λ, t = (v, 1) normalized.
    let f = run.newton.forces(&x, &run.direction);
    let Some(v) = k_t.lu().solve(&f) else {
        return Err(run.stop(SolveError::ArcLengthStalled {
            load_factor: 0.0,
            points: 0,
            arc_length: 0.0,
            iterations: 0,
            residual_norm: f64::NAN,
            cause: StaticFailure::Newton,
        }));
    };
    let v_norm = run.norm_x(&v);
    run.psi = options
        .load_weight
        .unwrap_or(if v_norm > 0.0 && v_norm.is_finite() {
            v_norm
        } else {
            1.0
        });
    let mut t = run.normalize(v, 1.0);
    run.push(x, 0.0, stable, StaticStats::default());
    let mut arc = options.initial_arc.clamp(options.min_arc, options.max_arc);
    loop {
        if run.points.len() >= options.max_points {
            let load_factor = run.last().load_factor;
            let points = run.points.len();
            return Err(run.stop(SolveError::ArcLengthTooManyPoints {
                load_factor,
                points,
            }));
        }
        let before = run.newton.stats;
        match run.step(&t, arc) {
            Step::Converged {
                x,
                lambda,
                iterations,
                rotation,
                residual,
            } => {
                run.newton.stats.residual_norm = residual;
                let lambda0 = run.last().load_factor;
                let x0 = DVector::from_column_slice(&run.last().solution.x);
                if (lambda0 - 1.0) * (lambda - 1.0) <= 0.0 && lambda != lambda0 {
                    // The step crosses λ = 1: land there exactly, by load control from the
                    // interpolated state.
                    let w = (1.0 - lambda0) / (lambda - lambda0);
                    let guess = &x0 + (&x - &x0) * w;
                    let s1 = run.scales_at(1.0);
                    let limit = 2.0 * options.max_rotation_step;
                    if let Newtonian::Converged(x1, _) =
                        run.newton.solve(guess, &s1, Some((&x0, limit)))
                    {
                        let stable = run.newton.stability(&x1, &s1, run.conservative);
                        run.newton.stats.residual_norm = run.newton.residual(&x1, &s1).amax();
                        run.newton.stats.load_steps += 1;
                        let stats = since(&run.newton.stats, &before);
                        run.push(x1, 1.0, stable, stats);
                        return Ok(run.finish());
                    }
                    // The landing failed: a shorter step, which lands from closer.
                    run.newton.stats.rejected_steps += 1;
                    arc *= 0.5;
                    if arc < options.min_arc {
                        return Err(run.stalled(arc, iterations, residual, StaticFailure::Newton));
                    }
                } else {
                    // Next tangent: same bordered matrix, right-hand side (0, 1).
                    let k_t = run.newton.tangent(&x, &run.scales_at(lambda));
                    let stable = tangent_stability(k_t.clone(), run.conservative);
                    run.newton.stats.stability_checks += 1;
                    let f = run.newton.forces(&x, &run.direction);
                    let mut rhs = DVector::zeros(x.len() + 1);
                    rhs[x.len()] = 1.0;
                    let Some(z) = run.bordered(k_t, &f, &t).lu().solve(&rhs) else {
                        // Singular bordered matrix (a branch point exactly on the step): retry
                        // with a shorter step.
                        run.newton.stats.rejected_steps += 1;
                        arc *= 0.5;
                        if arc < options.min_arc {
                            return Err(run.stalled(
                                arc,
                                iterations,
                                f64::NAN,
                                StaticFailure::Newton,
                            ));
                        }
                        continue;
                    };
                    let nd = x.len();
                    t = run.normalize(z.rows(0, nd).into_owned(), z[nd]);
                    run.newton.stats.load_steps += 1;
                    let stats = since(&run.newton.stats, &before);
                    run.push(x, lambda, stable, stats);
                    let by_iterations = (options.target_iterations as f64
                        / iterations.max(1) as f64)
                        .sqrt()
                        .clamp(0.5, 2.0);
                    let by_rotation = if rotation > 0.0 {
                        0.8 * options.max_rotation_step / rotation
                    } else {
                        2.0
                    };
                    arc = (arc * by_iterations.min(by_rotation))
                        .clamp(options.min_arc, options.max_arc);
                }
            }
            Step::Failed {
                iterations,
                residual,
                cause,
            } => {
                run.newton.stats.rejected_steps += 1;
                if let StaticFailure::TooFar { .. } = cause {
                    run.newton.stats.limited_steps += 1;
                }
                arc *= match cause {
                    StaticFailure::TooFar { rotation, limit } => {
                        (0.9 * limit / rotation).clamp(0.1, 0.5)
                    }
                    StaticFailure::Newton => 0.5,
                };
                if arc < options.min_arc {
                    return Err(run.stalled(arc, iterations, residual, cause));
                }
            }
        }
    }
}

/// Counters accumulated since `before` (the residual norm is the current one).
fn since(now: &StaticStats, before: &StaticStats) -> StaticStats {
    StaticStats {
        load_steps: now.load_steps - before.load_steps,
        rejected_steps: now.rejected_steps - before.rejected_steps,
        limited_steps: now.limited_steps - before.limited_steps,
        unstable_steps: now.unstable_steps - before.unstable_steps,
        iterations: now.iterations - before.iterations,
        residual_evaluations: now.residual_evaluations - before.residual_evaluations,
        factorizations: now.factorizations - before.factorizations,
        stability_checks: now.stability_checks - before.stability_checks,
        residual_norm: now.residual_norm,
    }
}

enum Step {
    Converged {
        x: DVector<f64>,
        lambda: f64,
        iterations: usize,
        rotation: f64,
        residual: f64,
    },
    Failed {
        iterations: usize,
        residual: f64,
        cause: StaticFailure,
    },
}

/// State of one continuation run.
struct Run<'a, M: StructuralModel> {
    model: &'a M,
    newton: Newton<'a, M>,
    options: &'a ArcLengthOptions,
    s_start: Vec<f64>,
    /// `s₁ − s₀`.
    direction: Vec<f64>,
    conservative: bool,
    /// `G` with `G x` = the absolute rotations of the full model / √(their number).
    g: DMatrix<f64>,
    psi: f64,
    points: Vec<PathPoint>,
}

impl<'a, M: StructuralModel> Run<'a, M> {
    fn new(
        model: &'a M,
        loads: &'a AppliedLoads,
        s_start: &[f64],
        scales: &[f64],
        options: &'a ArcLengthOptions,
    ) -> Self {
        // Newton options of the landing at λ = 1 (load control).
        let newton_options = StaticOptions {
            tolerance: options.tolerance,
            max_iterations: options.max_iterations,
            max_rotation_step: options.max_rotation_step,
            ..StaticOptions::default()
        };
        let nd = model.n_dofs();
        let n_angles = model.element_rotations(&vec![0.0; nd]).len();
        let mut g = DMatrix::zeros(n_angles, nd);
        let mut e = vec![0.0; nd];
        let scale = 1.0 / (n_angles as f64).sqrt();
        for j in 0..nd {
            e[j] = 1.0;
            let angles = model.element_rotations(&e);
            e[j] = 0.0;
            for (i, angle) in angles.iter().enumerate() {
                g[(i, j)] = angle * scale;
            }
        }
        let direction: Vec<f64> = s_start.iter().zip(scales).map(|(a, b)| b - a).collect();
        Self {
            model,
            newton: Newton::new(model, loads, newton_options),
            options,
            s_start: s_start.to_vec(),
            conservative: model.loads_are_conservative(loads, s_start)
                && model.loads_are_conservative(loads, scales),
            direction,
            g,
            psi: 1.0,
            points: Vec::new(),
        }
    }

    fn scales_at(&self, lambda: f64) -> Vec<f64> {
        self.s_start
            .iter()
            .zip(&self.direction)
            .map(|(a, d)| a + lambda * d)
            .collect()
    }

    /// `W v = Gᵀ G v`.
    fn metric(&self, v: &DVector<f64>) -> DVector<f64> {
        self.g.tr_mul(&(&self.g * v))
    }

    fn norm_x(&self, v: &DVector<f64>) -> f64 {
        (&self.g * v).norm()
    }

    /// The unit tangent `(v, l) / ‖(v, l)‖`.
    fn normalize(&self, v: DVector<f64>, l: f64) -> (DVector<f64>, f64) {
        let norm = self.norm_x(&v).hypot(self.psi * l);
        (v / norm, l / norm)
    }

    /// The bordered matrix `[[K_T, −f], [(W t_x)ᵀ, ψ² t_λ]]`.
    fn bordered(
        &self,
        k_t: DMatrix<f64>,
        f: &DVector<f64>,
        t: &(DVector<f64>, f64),
    ) -> DMatrix<f64> {
        let nd = f.len();
        let wt = self.metric(&t.0);
        let mut a = k_t.resize(nd + 1, nd + 1, 0.0);
        for i in 0..nd {
            a[(i, nd)] = -f[i];
            a[(nd, i)] = wt[i];
        }
        a[(nd, nd)] = self.psi * self.psi * t.1;
        a
    }

    fn last(&self) -> &PathPoint {
        self.points.last().expect("the start is on the path")
    }

    fn push(&mut self, x: DVector<f64>, lambda: f64, stable: Option<bool>, stats: StaticStats) {
        let arc_length = match self.points.last() {
            None => 0.0,
            Some(p) => {
                let dx = &x - DVector::from_column_slice(&p.solution.x);
                p.arc_length + self.norm_x(&dx).hypot(self.psi * (lambda - p.load_factor))
            }
        };
        let xs = x.as_slice().to_vec();
        self.points.push(PathPoint {
            load_factor: lambda,
            arc_length,
            solution: StaticSolution {
                q: self.model.full_coordinates(&xs),
                x: xs,
                scales: self.scales_at(lambda),
                stable,
                stats,
            },
        });
    }

    /// One predictor–corrector step of arc length `arc` along the unit tangent `t`.
    fn step(&mut self, t: &(DVector<f64>, f64), arc: f64) -> Step {
        let last = self.last();
        let x0 = DVector::from_column_slice(&last.solution.x);
        let lambda0 = last.load_factor;
        let x_p = &x0 + &t.0 * arc;
        let lambda_p = lambda0 + t.1 * arc;
        let wt = self.metric(&t.0);
        let psi2 = self.psi * self.psi;
        let limit = self.options.max_rotation_step;
        let (mut x, mut lambda) = (x_p.clone(), lambda_p);
        let nd = x.len();
        let mut residual = f64::NAN;
        for it in 0..=self.options.max_iterations {
            let s = self.scales_at(lambda);
            let r = self.newton.residual(&x, &s);
            if !r.iter().all(|v| v.is_finite()) {
                break;
            }
            residual = r.amax();
            let g = wt.dot(&(&x - &x_p)) + psi2 * t.1 * (lambda - lambda_p);
            if self.newton.converged(&x, &r) && g.abs() <= 1e-10 * arc {
                let rotation = max_rotation(self.model, (&x - &x0).as_slice());
                if rotation > limit {
                    return Step::Failed {
                        iterations: it,
                        residual,
                        cause: StaticFailure::TooFar { rotation, limit },
                    };
                }
                return Step::Converged {
                    x,
                    lambda,
                    iterations: it,
                    rotation,
                    residual,
                };
            }
            if it == self.options.max_iterations {
                break;
            }
            self.newton.stats.iterations += 1;
            self.newton.stats.factorizations += 1;
            let k_t = self.newton.tangent(&x, &s);
            let f = self.newton.forces(&x, &self.direction);
            let mut rhs = DVector::zeros(nd + 1);
            rhs.rows_mut(0, nd).copy_from(&(-&r));
            rhs[nd] = -g;
            let Some(d) = self.bordered(k_t, &f, t).lu().solve(&rhs) else {
                break;
            };
            x += d.rows(0, nd);
            lambda += d[nd];
            let rotation = max_rotation(self.model, (&x - &x0).as_slice());
            if rotation > 2.0 * limit {
                return Step::Failed {
                    iterations: it + 1,
                    residual,
                    cause: StaticFailure::TooFar { rotation, limit },
                };
            }
        }
        Step::Failed {
            iterations: self.options.max_iterations,
            residual,
            cause: StaticFailure::Newton,
        }
    }

    fn stalled(
        self,
        arc: f64,
        iterations: usize,
        residual_norm: f64,
        cause: StaticFailure,
    ) -> Box<PathError> {
        let load_factor = self.last().load_factor;
        let points = self.points.len();
        self.stop(SolveError::ArcLengthStalled {
            load_factor,
            points,
            arc_length: arc,
            iterations,
            residual_norm,
            cause,
        })
    }

    fn stop(self, error: SolveError) -> Box<PathError> {
        Box::new(PathError {
            path: self.finish(),
            error,
        })
    }

    fn finish(self) -> StaticPath {
        StaticPath {
            points: self.points,
            load_weight: self.psi,
            stats: self.newton.stats,
        }
    }
}
