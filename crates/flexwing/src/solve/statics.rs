//! Non-linear statics: `K x = Q(x)` by Newton's method with an exact tangent and a backtracking
//! line search, load stepping that follows the equilibrium path from the start, and a stability
//! check of every equilibrium. Works for any [`StructuralModel`]: the full model and reduced
//! models. Statics of the model: docs/model.md ("Statics"); arc-length continuation through limit
//! points is in [`super::continuation`].
//!
//! Path following (load control). The load factor `μ` runs from the start (0) to the target (1)
//! in steps whose size is set by the solution, not only by Newton failures (Crisfield, *Non-linear
//! Finite Element Analysis of Solids and Structures*, vol. 1, 1991, §9.5, automatic increments): a
//! step is accepted only if Newton converges, no element's absolute rotation (bending angle or
//! twist) changed by more than `max_rotation_step`, and the new equilibrium is not unstable; the
//! next step grows or shrinks with that rotation and with the Newton iteration count. So one large
//! load cannot jump to a distant branch: Newton's first step from rest under `α = PL²/EI = 15`
//! predicts a tip rotation of 7.5 rad and is refused at once.
//!
//! Stability (docs/model-choices.md, "Stability of equilibria"). Under conservative loads an
//! equilibrium is stable when the tangent `K − ∂Q/∂x` is positive definite (a strict minimum of the
//! potential energy, Lagrange–Dirichlet), tested by one Cholesky attempt. Under follower forces the
//! tangent is not symmetric and has no potential behind it; a negative determinant still proves
//! instability (divergence: `det(K_T) < 0` gives a real positive root of `det(M s² + C s + K_T)`
//! for any mass and damping), but a positive one proves nothing (flutter is a dynamic question),
//! so such points are reported as not assessed.

use nalgebra::{DMatrix, DVector};

use super::newton_tangent::{Stiffness, Tangent};
use crate::error::{SolveError, StaticFailure};
use crate::model::{AppliedLoads, FullModel, StructuralModel};

/// Options of the static solver.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticOptions {
    /// Convergence when `‖K x − Q(x)‖∞ ≤ tolerance · max(‖K x‖∞, ‖Q(x)‖∞)`. Default `1e-10`.
    pub tolerance: f64,
    /// Newton iterations allowed per load step before the step is cut. Default 30.
    pub max_iterations: usize,
    /// First load-factor increment (fraction of the whole load change). Default `1.0`: try the
    /// whole load at once; `max_rotation_step` and Newton cut it as needed.
    pub initial_step: f64,
    /// Smallest increment before giving up. Default `1e-6`.
    pub min_step: f64,
    /// Backtracking line search on `‖R‖₂`. Default `true`.
    pub line_search: bool,
    /// Largest change of any element's absolute rotation (bending angle `θ_i` or twist `ψ_i`, of
    /// the full model) from one equilibrium to the next, rad. A first Newton step that goes more
    /// than twice this far from the last equilibrium ends the attempt at once. Default `1.0` (57°): the
    /// paper's 150 N tip load (tip rotation 0.99 rad) is still one step, while Newton's first
    /// step from rest under a load that rotates the tip by several radians is refused.
    pub max_rotation_step: f64,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 30,
            initial_step: 1.0,
            min_step: 1e-6,
            line_search: true,
            max_rotation_step: 1.0,
        }
    }
}

impl StaticOptions {
    /// Check the options: finite positive tolerance and rotation step, `min_step ≤ initial_step
    /// ≤ 1`, at least one iteration; errors name `{prefix}.tolerance`, ….
    pub fn validate(&self, prefix: &str) -> Result<(), crate::InputError> {
        let bad = |f: &str, v: f64, what: &str| {
            Err(crate::InputError::new(
                crate::field(prefix, f),
                format!("must be {what}, got {}", crate::text::short(v)),
            ))
        };
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return bad("tolerance", self.tolerance, "a finite positive number");
        }
        if !(self.min_step > 0.0 && self.min_step <= 1.0) {
            return bad(
                "min_step",
                self.min_step,
                "in (0, 1] (a fraction of the load change)",
            );
        }
        if !(self.initial_step >= self.min_step && self.initial_step <= 1.0) {
            return bad("initial_step", self.initial_step, "in [min_step, 1]");
        }
        if self.max_iterations == 0 {
            return bad("max_iterations", 0.0, "at least 1");
        }
        if !(self.max_rotation_step > 0.0 && self.max_rotation_step.is_finite()) {
            return bad(
                "max_rotation_step",
                self.max_rotation_step,
                "a finite positive angle (rad)",
            );
        }
        Ok(())
    }
}

/// Counters of a static solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct StaticStats {
    /// Accepted load steps.
    pub load_steps: usize,
    /// Load steps rejected and retried with a smaller increment, for any reason (the next two
    /// counters are part of this one).
    pub rejected_steps: usize,
    /// Load steps rejected because the solution moved too far (`max_rotation_step`).
    pub limited_steps: usize,
    /// Load steps rejected because they ended on an unstable equilibrium.
    pub unstable_steps: usize,
    /// Newton iterations, over all steps (accepted or not).
    pub iterations: usize,
    /// Evaluations of the residual `K x − Q(x)`.
    pub residual_evaluations: usize,
    /// Evaluations and factorizations of the tangent `K − ∂Q/∂x` in Newton iterations (O(n)
    /// chain sweeps for the full model, dense LU otherwise: `solve/newton_tangent.rs`).
    pub factorizations: usize,
    /// Stability checks (a tangent evaluation and one Cholesky attempt, or one LU for
    /// non-conservative loads).
    pub stability_checks: usize,
    /// `‖K x − Q(x)‖∞` at the solution.
    pub residual_norm: f64,
}

/// A static equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// Coordinates of the model (`q` for the full model, `η` for a reduced one).
    pub x: Vec<f64>,
    /// Joint rotations of the full model, `q` (`= Φ η` for a reduced model).
    pub q: Vec<f64>,
    /// Load scales this equilibrium is for.
    pub scales: Vec<f64>,
    /// Stability of the equilibrium, for the model solved (a reduced model's tangent is the
    /// projected one):
    /// * `Some(true)`: conservative loads and the tangent `K − ∂Q/∂x` is positive definite — a
    ///   strict minimum of the potential energy, stable;
    /// * `Some(false)`: unstable — under conservative loads the tangent is not positive definite
    ///   (a saddle or a neutral state); under follower loads its determinant is negative (static
    ///   divergence, unstable whatever the mass and damping);
    /// * `None`: follower (non-conservative) loads with a positive determinant: statics cannot
    ///   tell (the point may still flutter); not assessed. Also `None` under follower loads
    ///   strictly inside an element for models above [`FOLLOWER_STABILITY_MAX_DOFS`]
    ///   coordinates, where the determinant's dense LU (O(n³)) would cost more than the solve
    ///   (followers at nodes and element midpoints get the determinant's sign from the O(n)
    ///   chain factorization at any size).
    ///
    /// Load control ([`solve_static`], [`continue_static`], [`sweep_static`]) never returns a
    /// point with `Some(false)`: it stops with [`SolveError::StaticUnstable`] instead. Arc-length
    /// continuation returns unstable points, marked.
    pub stable: Option<bool>,
    /// Solver counters.
    pub stats: StaticStats,
}

/// Above this many coordinates the stability of an equilibrium under follower loads strictly
/// inside an element is not assessed ([`StaticSolution::stable`] is `None`): its test, the sign
/// of the tangent's determinant, takes a dense LU there, O(n³) — about 0.05 s at 600
/// coordinates, an hour at 20 000 (measured 12 min for the two n = 10 000 solves of
/// tests/suite/statics_elastica.rs). Followers at nodes and element midpoints (a tip follower force,
/// distributed followers) take the sign from the pivots of the O(n) chain factorization of the
/// full model, exact for them, at any size.
pub const FOLLOWER_STABILITY_MAX_DOFS: usize = 600;

/// Solve `K x = Q(x; scales)` for the loads `loads` scaled by `scales`, starting at rest
/// (`x = 0`, no load) and following the equilibrium path as the load factor steps from 0 to 1.
///
/// # Errors
/// [`SolveError::StaticDiverged`] or [`SolveError::StaticUnstable`] with the load factor reached
/// if the path could not be followed with steps down to `options.min_step`; see
/// [`continue_static`].
pub fn solve_static<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    scales: &[f64],
    options: &StaticOptions,
) -> Result<StaticSolution, SolveError> {
    let x0 = vec![0.0; model.n_dofs()];
    let s0 = vec![0.0; scales.len()];
    continue_static(model, loads, (&x0, &s0), scales, options)
}

/// Why the last attempted load step was refused.
#[derive(Debug, Clone, Copy)]
enum Refusal {
    Newton {
        iterations: usize,
        residual: f64,
    },
    TooFar {
        iterations: usize,
        residual: f64,
        rotation: f64,
    },
    Unstable,
}

/// Continue an equilibrium `start = (x, scales₀)` to new load scales `scales₁` along
/// `s(μ) = scales₀ + μ (scales₁ − scales₀)`, `μ: 0 → 1`, following the equilibrium path with
/// adaptive increments of `μ` (module documentation): each accepted step converged, moved no
/// element by more than `options.max_rotation_step`, and ended on an equilibrium that is not
/// unstable.
///
/// # Errors
/// If the increment had to be cut below `options.min_step`, with the last `μ` at which an
/// equilibrium was found as `load_factor`:
/// * [`SolveError::StaticUnstable`]: the only equilibria found past it are unstable — the path
///   reaches a critical point (buckling or a limit point), which load control cannot pass;
/// * [`SolveError::StaticDiverged`]: Newton did not converge, or converged only to equilibria
///   farther than `max_rotation_step` (a limit point of the path, or too coarse a `min_step`).
pub fn continue_static<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    start: (&[f64], &[f64]),
    scales: &[f64],
    options: &StaticOptions,
) -> Result<StaticSolution, SolveError> {
    follow(
        model,
        loads,
        start,
        scales,
        options,
        None,
        AtInstability::Locate,
    )
}

/// What load control does when a step ends on an unstable equilibrium.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum AtInstability {
    /// Cut the step down to `min_step`: the load factor where stability is lost, to that
    /// precision ([`continue_static`]).
    Locate,
    /// Stop at once with [`SolveError::StaticUnstable`] between the last stable equilibrium and
    /// the unstable one ([`continue_static_to_instability`]).
    Stop,
}

/// [`continue_static`] for a caller that locates the critical point itself: a step that ends on
/// an unstable equilibrium stops the path at once with [`SolveError::StaticUnstable`] (the last
/// stable `μ` as `load_factor`, the unstable step's end as `attempted`), instead of cutting the
/// step down to `options.min_step` to pin the loss of stability. The static aeroelastic sweeps
/// use it: past the divergence speed their secant on the divergence pressure brackets the
/// divergence to its own tolerance (`aeroelastic/statics.rs`), and the fine step search (refused
/// steps cut by four down to `min_step`, each a Newton solve and a factorization) would only
/// repeat it less accurately.
///
/// # Errors
/// As [`continue_static`]; a `StaticUnstable` error's bracket `[load_factor, attempted]` is
/// that of one refused step.
pub(crate) fn continue_static_to_instability<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    start: (&[f64], &[f64]),
    scales: &[f64],
    options: &StaticOptions,
) -> Result<StaticSolution, SolveError> {
    follow(
        model,
        loads,
        start,
        scales,
        options,
        None,
        AtInstability::Stop,
    )
}

/// [`continue_static`], with the equilibrium `before = (x, scales)` that preceded the start on
/// the path, if any: when the load keeps its direction, the first step's predictor is the
/// secant through it (as between the steps of one call).
fn follow<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    start: (&[f64], &[f64]),
    scales: &[f64],
    options: &StaticOptions,
    before: Option<(&[f64], &[f64])>,
    at_instability: AtInstability,
) -> Result<StaticSolution, SolveError> {
    options
        .validate("options")
        .map_err(SolveError::from_input)?;
    let (x_start, s_start) = start;
    let nd = model.n_dofs();
    let mut ws = Newton::new(model, loads, options.clone());
    // Follower scales are linear in μ: the path is conservative iff both ends are.
    let conservative =
        model.loads_are_conservative(loads, s_start) && model.loads_are_conservative(loads, scales);
    let s_at = |mu: f64| -> Vec<f64> {
        s_start
            .iter()
            .zip(scales)
            .map(|(a, b)| a + mu * (b - a))
            .collect()
    };
    let limit = options.max_rotation_step;
    let mut mu = 0.0;
    let mut x = DVector::from_column_slice(x_start);
    let mut stable = None;
    // The previous equilibrium, at μ_p < 0 on the same line of loads if the load keeps its
    // direction.
    let mut x_prev = previous_on_line(before, s_start, scales);
    let mut step = options.initial_step.clamp(options.min_step, 1.0);
    while mu < 1.0 {
        let target = (mu + step).min(1.0);
        let dmu = target - mu;
        let s_target = s_at(target);
        // Secant predictor from the previous two equilibria.
        let guess = match &x_prev {
            Some((mu_p, xp)) if mu - mu_p > 0.0 => &x + (&x - xp) * (dmu / (mu - mu_p)),
            _ => x.clone(),
        };
        let refusal = match ws.solve(guess, &s_target, Some((&x, 2.0 * limit))) {
            Newtonian::Converged(x_new, iterations) => {
                let rotation = ws.rotation_change(&x, &x_new);
                if rotation > limit {
                    Refusal::TooFar {
                        iterations,
                        residual: 0.0,
                        rotation,
                    }
                } else {
                    let stability = ws.stability(&x_new, &s_target, conservative);
                    if stability == Some(false) {
                        Refusal::Unstable
                    } else {
                        ws.stats.load_steps += 1;
                        stable = stability;
                        x_prev = Some((mu, std::mem::replace(&mut x, x_new)));
                        mu = target;
                        step = next_increment(step, dmu, rotation, iterations, options);
                        continue;
                    }
                }
            }
            Newtonian::Strayed {
                iterations,
                residual,
                rotation,
            } => Refusal::TooFar {
                iterations,
                residual,
                rotation,
            },
            Newtonian::Failed {
                iterations,
                residual,
            } => Refusal::Newton {
                iterations,
                residual,
            },
        };
        ws.stats.rejected_steps += 1;
        // The new increment: in proportion to the rotation limit when the solution went too
        // far (Newton's first step is linear in the increment), a quarter otherwise.
        step = match refusal {
            Refusal::TooFar { rotation, .. } => {
                ws.stats.limited_steps += 1;
                dmu * (0.9 * limit / rotation).clamp(0.01, 0.5)
            }
            Refusal::Unstable if at_instability == AtInstability::Stop => {
                ws.stats.unstable_steps += 1;
                return Err(refusal.error(mu, target, limit));
            }
            Refusal::Unstable => {
                ws.stats.unstable_steps += 1;
                0.25 * dmu
            }
            Refusal::Newton { .. } => 0.25 * dmu,
        };
        if step < options.min_step {
            return Err(refusal.error(mu, target, limit));
        }
    }
    let final_scales = s_at(1.0);
    let r = ws.residual(&x, &final_scales);
    ws.stats.residual_norm = r.amax();
    let xs = x.as_slice().to_vec();
    debug_assert_eq!(xs.len(), nd);
    Ok(StaticSolution {
        q: model.full_coordinates(&xs),
        x: xs,
        scales: final_scales,
        stable,
        stats: ws.stats,
    })
}

/// The equilibrium `before` as the previous point of the path, at `μ_p < 0` on the line of loads
/// from `s_start` to `scales`, if the load keeps its direction.
fn previous_on_line(
    before: Option<(&[f64], &[f64])>,
    s_start: &[f64],
    scales: &[f64],
) -> Option<(f64, DVector<f64>)> {
    before.and_then(|(xb, sb)| {
        let d_old: Vec<f64> = s_start.iter().zip(sb).map(|(a, b)| a - b).collect();
        let d_new: Vec<f64> = scales.iter().zip(s_start).map(|(a, b)| a - b).collect();
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let dot: f64 = d_old.iter().zip(&d_new).map(|(a, b)| a * b).sum();
        let (n_old, n_new) = (norm(&d_old), norm(&d_new));
        (n_old > 0.0 && n_new > 0.0 && dot >= (1.0 - 1e-9) * n_old * n_new)
            .then(|| (-n_old / n_new, DVector::from_column_slice(xb)))
    })
}

/// The increment after an accepted step of `dmu` (the increment tried was `step`) that rotated
/// the elements by `rotation` in `iterations` Newton iterations: grown or shrunk with the
/// rotation (aim at 0.8 of the limit) and with the iteration count.
fn next_increment(
    step: f64,
    dmu: f64,
    rotation: f64,
    iterations: usize,
    options: &StaticOptions,
) -> f64 {
    let limit = options.max_rotation_step;
    let by_rotation = if rotation > 0.0 {
        0.8 * limit / rotation
    } else {
        2.0
    };
    let by_iterations = if iterations <= options.max_iterations / 4 {
        2.0
    } else if iterations > options.max_iterations / 2 {
        0.5
    } else {
        1.0
    };
    let mut step = step;
    if dmu >= step * (1.0 - 1e-12) {
        step = (step * by_rotation.min(by_iterations).min(2.0)).min(1.0);
    }
    step.max(options.min_step)
}

impl Refusal {
    /// The error of a path that stopped at `μ = mu` when the increment to `attempted` was
    /// refused for this reason and could not be cut further.
    fn error(self, mu: f64, attempted: f64, limit: f64) -> SolveError {
        match self {
            Refusal::Unstable => SolveError::StaticUnstable {
                load_factor: mu,
                attempted,
            },
            Refusal::Newton {
                iterations,
                residual,
            } => SolveError::StaticDiverged {
                load_factor: mu,
                attempted,
                iterations,
                residual_norm: residual,
                cause: StaticFailure::Newton,
            },
            Refusal::TooFar {
                iterations,
                residual,
                rotation,
            } => SolveError::StaticDiverged {
                load_factor: mu,
                attempted,
                iterations,
                residual_norm: residual,
                cause: StaticFailure::TooFar { rotation, limit },
            },
        }
    }
}

/// Result of one Newton solve.
pub(super) enum Newtonian {
    /// Converged to `x` in this many iterations.
    Converged(DVector<f64>, usize),
    /// An iterate (or a full Newton step) went farther than allowed from the anchor.
    Strayed {
        iterations: usize,
        residual: f64,
        rotation: f64,
    },
    /// No convergence within the iterations allowed (or a non-finite residual, or a singular
    /// tangent).
    Failed { iterations: usize, residual: f64 },
}

/// Newton iteration state and buffers for one model and load set.
pub(super) struct Newton<'a, M: StructuralModel> {
    model: &'a M,
    loads: &'a AppliedLoads,
    options: StaticOptions,
    ws: M::Workspace,
    stiffness: Stiffness,
    f: DVector<f64>,
    tangent: Tangent,
    pub(super) stats: StaticStats,
}

impl<'a, M: StructuralModel> Newton<'a, M> {
    pub(super) fn new(model: &'a M, loads: &'a AppliedLoads, options: StaticOptions) -> Self {
        let nd = model.n_dofs();
        Self {
            model,
            loads,
            options,
            ws: model.workspace(),
            stiffness: Stiffness::new(model),
            f: DVector::zeros(nd),
            tangent: Tangent::new(model),
            stats: StaticStats::default(),
        }
    }

    /// `R = K x − Q(x)`; leaves `Q` in `self.f`.
    pub(super) fn residual(&mut self, x: &DVector<f64>, scales: &[f64]) -> DVector<f64> {
        self.stats.residual_evaluations += 1;
        self.model.generalized_forces_into(
            x.as_slice(),
            self.loads,
            scales,
            &mut self.ws,
            &mut self.f,
        );
        self.stiffness.times(x) - &self.f
    }

    /// Generalized forces `Q(x; scales)` (into a new vector).
    pub(super) fn forces(&mut self, x: &DVector<f64>, scales: &[f64]) -> DVector<f64> {
        let mut out = DVector::zeros(x.len());
        self.model.generalized_forces_into(
            x.as_slice(),
            self.loads,
            scales,
            &mut self.ws,
            &mut out,
        );
        out
    }

    /// The tangent `K − ∂Q/∂x` at `x`, formed densely (into a new matrix; for the bordered
    /// systems of arc-length continuation and the stability of non-conservative loads).
    pub(super) fn tangent(&mut self, x: &DVector<f64>, scales: &[f64]) -> DMatrix<f64> {
        let nd = x.len();
        let mut jac = DMatrix::zeros(nd, nd);
        self.model
            .load_jacobian_into(x.as_slice(), self.loads, scales, &mut self.ws, &mut jac);
        self.stiffness.dense(nd) - jac
    }

    /// Stability of the equilibrium `x` (see [`StaticSolution::stable`]): for conservative loads
    /// from the pivots of the O(n) chain factorization of the tangent (Sylvester's law of
    /// inertia) where the model has one, else by a dense Cholesky attempt; for follower loads
    /// from the sign of the tangent's determinant, by the chain factorization's pivots where its
    /// tangent is exact (followers at nodes and element midpoints), else from a dense LU up to
    /// [`FOLLOWER_STABILITY_MAX_DOFS`] coordinates.
    pub(super) fn stability(
        &mut self,
        x: &DVector<f64>,
        scales: &[f64],
        conservative: bool,
    ) -> Option<bool> {
        if !conservative
            && self
                .tangent
                .factor(self.model, &mut self.ws, x.as_slice(), self.loads, scales)
        {
            if let Some(negative) = self.tangent.determinant_negative() {
                self.stats.stability_checks += 1;
                return negative.then_some(false);
            }
        }
        if !conservative && self.model.n_dofs() > FOLLOWER_STABILITY_MAX_DOFS {
            return None;
        }
        self.stats.stability_checks += 1;
        if conservative
            && self
                .tangent
                .factor(self.model, &mut self.ws, x.as_slice(), self.loads, scales)
        {
            if let Some(positive) = self.tangent.positive_definite() {
                return Some(positive);
            }
        }
        let tangent = self.tangent(x, scales);
        tangent_stability(tangent, conservative)
    }

    /// Largest change of an element's absolute rotation between `a` and `b`.
    pub(super) fn rotation_change(&self, a: &DVector<f64>, b: &DVector<f64>) -> f64 {
        max_rotation(self.model, (b - a).as_slice())
    }

    pub(super) fn converged(&self, x: &DVector<f64>, r: &DVector<f64>) -> bool {
        let scale = self.stiffness.times(x).amax().max(self.f.amax());
        r.amax() <= self.options.tolerance * scale || r.amax() == 0.0
    }

    /// Newton from `x`. With `anchor = (x₀, limit)`, gives up at once if the first full Newton
    /// step lands more than `limit` (largest absolute rotation) away from `x₀`.
    pub(super) fn solve(
        &mut self,
        mut x: DVector<f64>,
        scales: &[f64],
        anchor: Option<(&DVector<f64>, f64)>,
    ) -> Newtonian {
        let mut r = self.residual(&x, scales);
        for it in 0..self.options.max_iterations {
            if !r.iter().all(|v| v.is_finite()) {
                return Newtonian::Failed {
                    iterations: it,
                    residual: f64::NAN,
                };
            }
            if self.converged(&x, &r) {
                return Newtonian::Converged(x, it);
            }
            self.stats.iterations += 1;
            self.stats.factorizations += 1;
            let factored =
                self.tangent
                    .factor(self.model, &mut self.ws, x.as_slice(), self.loads, scales);
            let mut dx = -&r;
            if factored {
                self.tangent.solve(self.model, &mut dx);
            }
            if !factored || !dx.iter().all(|v| v.is_finite()) {
                return Newtonian::Failed {
                    iterations: it + 1,
                    residual: r.amax(),
                };
            }
            // The first step shows a load step that is too large (from an equilibrium it is the
            // linear response); later iterates that stray are caught at convergence.
            if let (Some((x0, limit)), 0) = (anchor, it) {
                let rotation = max_rotation(self.model, (&x + &dx - x0).as_slice());
                if rotation > limit {
                    return Newtonian::Strayed {
                        iterations: it + 1,
                        residual: r.amax(),
                        rotation,
                    };
                }
            }
            let r0 = r.norm();
            let mut alpha = 1.0;
            loop {
                let x_try = &x + &dx * alpha;
                let r_try = self.residual(&x_try, scales);
                let ok = r_try.iter().all(|v| v.is_finite())
                    && (r_try.norm() <= (1.0 - 1e-4 * alpha) * r0 || !self.options.line_search);
                if ok || alpha < 1.0 / 64.0 {
                    x = x_try;
                    r = r_try;
                    break;
                }
                alpha *= 0.5;
            }
        }
        if self.converged(&x, &r) {
            return Newtonian::Converged(x, self.options.max_iterations);
        }
        Newtonian::Failed {
            iterations: self.options.max_iterations,
            residual: r.amax(),
        }
    }
}

/// Largest absolute rotation `max_i |θ_i|, |ψ_i|` of the full model for the model coordinates
/// `dx` (the map `x ↦ q` is linear, so for a difference of two states this is the largest
/// change of an element's rotation between them).
pub(super) fn max_rotation<M: StructuralModel>(model: &M, dx: &[f64]) -> f64 {
    let mut worst = 0.0_f64;
    for angle in model.element_rotations(dx) {
        if angle.is_nan() {
            // A non-finite state is infinitely far.
            return f64::INFINITY;
        }
        worst = worst.max(angle.abs());
    }
    worst
}

/// Stability from the tangent `K − ∂Q/∂x` (see [`StaticSolution::stable`]): one Cholesky attempt
/// under conservative loads; under follower loads the sign of the determinant, from one LU.
pub(super) fn tangent_stability(tangent: DMatrix<f64>, conservative: bool) -> Option<bool> {
    if conservative {
        return Some(tangent.cholesky().is_some());
    }
    let lu = tangent.lu();
    let mut sign = lu.p().determinant::<f64>();
    for d in lu.u().diagonal().iter() {
        sign *= d.signum();
    }
    (sign < 0.0).then_some(false)
}

/// Linear static solution `q = K⁻¹ Q(0)` of `loads` about the undeformed state, and the linearized
/// nodal displacements `δP_i = J_{P_i}(0) q` as `(dx, dy)` per node `0 … n`.
pub fn linear_static(model: &FullModel, loads: &AppliedLoads) -> (DVector<f64>, Vec<[f64; 2]>) {
    let nd = model.n_dofs();
    let kin = model.kinematics(&vec![0.0; nd]);
    let mut f = DVector::zeros(nd);
    model.generalized_forces_kin_into(&kin, loads, &vec![1.0; loads.n_loads()], &mut f);
    let q = f.component_div(&DVector::from_column_slice(model.stiffness()));
    let ell = model.beam().lengths();
    let mut theta = 0.0;
    let mut y = 0.0;
    let mut disp = vec![[0.0, 0.0]];
    for j in 0..model.n_elements() {
        theta += q[j];
        y += ell[j] * theta;
        disp.push([0.0, y]);
    }
    (q, disp)
}

/// A load sweep that stopped early: the equilibria found so far and why it stopped.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepError {
    /// Equilibria of the sweep points completed before the failure, in order.
    pub completed: Vec<StaticSolution>,
    /// Index of the sweep point that failed.
    pub point: usize,
    /// The solver's error at that point.
    pub error: SolveError,
}

impl std::fmt::Display for SweepError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "sweep point {}: {}", self.point + 1, self.error)
    }
}

impl std::error::Error for SweepError {}

/// Solve a sequence of load levels, each continued from the previous equilibrium (the first one
/// from rest), as in the paper's Figure 4.
///
/// # Errors
/// [`SweepError`] with the equilibria found before the point that failed.
pub fn sweep_static<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    points: &[Vec<f64>],
    options: &StaticOptions,
) -> Result<Vec<StaticSolution>, SweepError> {
    sweep_static_until(model, loads, points, options, &mut || false)
}

/// As [`sweep_static`], polling `stop` before each point: when it returns `true` the sweep
/// returns the equilibria found so far, fewer than `points` (an interrupted run).
///
/// # Errors
/// As [`sweep_static`].
pub fn sweep_static_until<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    points: &[Vec<f64>],
    options: &StaticOptions,
    stop: &mut dyn FnMut() -> bool,
) -> Result<Vec<StaticSolution>, SweepError> {
    let mut done: Vec<StaticSolution> = Vec::with_capacity(points.len());
    for (i, scales) in points.iter().enumerate() {
        if stop() {
            break;
        }
        // Each point from the previous one (the first from rest), with the one before it (or
        // rest) for the secant predictor.
        let rest = (vec![0.0; model.n_dofs()], vec![0.0; scales.len()]);
        let start = done
            .last()
            .map_or((&rest.0, &rest.1), |p| (&p.x, &p.scales));
        let before = match done.len() {
            0 => None,
            1 => Some((&rest.0[..], &rest.1[..])),
            k => Some((&done[k - 2].x[..], &done[k - 2].scales[..])),
        };
        let result = follow(
            model,
            loads,
            (start.0, start.1),
            scales,
            options,
            before,
            AtInstability::Locate,
        );
        match result {
            Ok(sol) => done.push(sol),
            Err(error) => {
                return Err(SweepError {
                    completed: done,
                    point: i,
                    error,
                })
            }
        }
    }
    Ok(done)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stability_of_small_tangents() {
        let m = |rows: &[f64]| DMatrix::from_row_slice(2, 2, rows);
        // Symmetric: positive definite is stable; indefinite or singular is not.
        assert_eq!(
            tangent_stability(m(&[2.0, 1.0, 1.0, 2.0]), true),
            Some(true)
        );
        assert_eq!(
            tangent_stability(m(&[1.0, 2.0, 2.0, 1.0]), true),
            Some(false)
        );
        assert_eq!(
            tangent_stability(m(&[1.0, 1.0, 1.0, 1.0]), true),
            Some(false)
        );
        // Non-symmetric: a negative determinant is divergence (unstable) whatever the pivoting;
        // a positive one proves nothing.
        assert_eq!(
            tangent_stability(m(&[1.0, 3.0, 1.0, 2.0]), false),
            Some(false)
        );
        assert_eq!(
            tangent_stability(m(&[0.0, 1.0, 1.0, 0.0]), false),
            Some(false)
        );
        assert_eq!(tangent_stability(m(&[1.0, 5.0, -5.0, 1.0]), false), None);
        assert_eq!(tangent_stability(m(&[-1.0, 0.0, 0.0, -1.0]), false), None);
    }

    /// The stability of follower-loaded states from the chain factorization's pivots (the sign of
    /// `det K_T`) against the dense LU's determinant sign, below and above
    /// `FOLLOWER_STABILITY_MAX_DOFS`: Table 4 beam, dead tip compression `P` between the first two
    /// buckling loads (123 N and 1110 N: one negative eigenvalue, divergence) or below the first,
    /// plus a tip follower force, straight and bent (tip angle ≈ 0.08 rad) states. Signs: exact
    /// agreement required.
    /// With the follower strictly inside an element the chain's tangent is not exact, and above
    /// the limit stability is not assessed (`None`), as before.
    #[test]
    fn follower_stability_from_the_chain_pivots_at_any_size() {
        use crate::model::{Force, Load};
        for n in [40, 700] {
            let model = crate::paper::table4_beam(n).unwrap();
            for (p, bend, expect_divergence) in [
                (200.0, 0.0, true),
                (200.0, 0.08, true),
                (60.0, 0.0, false),
                (60.0, 0.08, false),
            ] {
                let loads = model
                    .apply(
                        &[
                            Load::PointForce {
                                span: 1.0,
                                force: Force::Dead { fx: -p, fy: 0.0 },
                            },
                            Load::PointForce {
                                span: 1.0,
                                force: Force::Follower {
                                    tangential: -5.0,
                                    normal: 3.0,
                                },
                            },
                        ],
                        "loads",
                    )
                    .unwrap();
                // Joint rotations `bend/n (1 + sin)`: a tip angle of about `bend`.
                let x =
                    DVector::from_fn(n, |i, _| bend / n as f64 * (1.0 + (0.3 * i as f64).sin()));
                let mut newton = Newton::new(&model, &loads, StaticOptions::default());
                let chain = newton.stability(&x, &[1.0, 1.0], false);
                assert_eq!(newton.stats.stability_checks, 1);
                let dense = tangent_stability(newton.tangent(&x, &[1.0, 1.0]), false);
                assert_eq!(dense, expect_divergence.then_some(false), "n {n}, P {p}");
                assert_eq!(chain, dense, "n {n}, P {p}, bend {bend}");
            }
            // A follower force strictly inside an element (at 0.3 of element n/2, between its
            // inboard node and midpoint: it turns with two elements' angles).
            let span = ((n / 2) as f64 + 0.3) / n as f64;
            let loads = model
                .apply(
                    &[
                        Load::PointForce {
                            span: 1.0,
                            force: Force::Dead {
                                fx: -200.0,
                                fy: 0.0,
                            },
                        },
                        Load::PointForce {
                            span,
                            force: Force::Follower {
                                tangential: -5.0,
                                normal: 3.0,
                            },
                        },
                    ],
                    "loads",
                )
                .unwrap();
            let x = DVector::from_fn(n, |i, _| 0.08 / n as f64 * (1.0 + (0.3 * i as f64).sin()));
            let mut newton = Newton::new(&model, &loads, StaticOptions::default());
            let got = newton.stability(&x, &[1.0, 1.0], false);
            if n > FOLLOWER_STABILITY_MAX_DOFS {
                assert_eq!(got, None, "inexact chain tangent above the dense limit");
            } else {
                assert_eq!(got, Some(false), "the dense determinant below it");
            }
        }
    }

    #[test]
    fn rotation_change_is_the_largest_absolute_angle() {
        let model = crate::paper::table4_beam(4).unwrap();
        // Joint rotations (0.1, 0.2, −0.5, 0.1): absolute angles 0.1, 0.3, −0.2, −0.1.
        assert!((max_rotation(&model, &[0.1, 0.2, -0.5, 0.1]) - 0.3).abs() < 1e-15);
        assert_eq!(
            max_rotation(&model, &[0.0, f64::NAN, 0.0, 0.0]),
            f64::INFINITY
        );
    }
}
