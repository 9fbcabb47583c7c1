//! Non-linear statics: `K x = Q(x)` by Newton's method with an exact tangent, load stepping with
//! automatic cut-back, and a backtracking line search. Works for any [`StructuralModel`]: the
//! full model and reduced models.

use nalgebra::DVector;

use super::tangent::{Stiffness, Tangent};
use crate::error::SolveError;
use crate::model::{AppliedLoads, FullModel, StructuralModel};

/// Options of the static solver.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticOptions {
    /// Convergence when `‖K x − Q(x)‖∞ ≤ tolerance · max(‖K x‖∞, ‖Q(x)‖∞)`. Default `1e-10`.
    pub tolerance: f64,
    /// Newton iterations allowed per load step before the step is cut. Default 30.
    pub max_iterations: usize,
    /// First load-factor increment (fraction of the whole load change). Default `1.0`: try the
    /// whole load at once, cut back if Newton fails.
    pub initial_step: f64,
    /// Smallest increment before giving up. Default `1e-6`.
    pub min_step: f64,
    /// Backtracking line search on `‖R‖₂`. Default `true`.
    pub line_search: bool,
}

impl Default for StaticOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_iterations: 30,
            initial_step: 1.0,
            min_step: 1e-6,
            line_search: true,
        }
    }
}

impl StaticOptions {
    /// Check the options: finite positive tolerance and steps, `min_step ≤ initial_step ≤ 1`,
    /// at least one iteration (fields `static.*`).
    pub fn validate(&self) -> Result<(), crate::InputError> {
        let bad = |f: &str, v: f64, what: &str| {
            Err(crate::InputError::new(
                format!("static.{f}"),
                format!("must be {what}, got {v}"),
            ))
        };
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return bad("tolerance", self.tolerance, "a finite positive number");
        }
        if !(self.min_step > 0.0 && self.min_step <= 1.0) {
            return bad("min_step", self.min_step, "in (0, 1]");
        }
        if !(self.initial_step >= self.min_step && self.initial_step <= 1.0) {
            return bad("initial_step", self.initial_step, "in [min_step, 1]");
        }
        if self.max_iterations == 0 {
            return bad("max_iterations", 0.0, "at least 1");
        }
        Ok(())
    }
}

/// Counters of a static solve.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct StaticStats {
    /// Accepted load steps.
    pub load_steps: usize,
    /// Load steps rejected (Newton failed) and retried with a smaller increment.
    pub rejected_steps: usize,
    /// Newton iterations, over all steps (accepted or not).
    pub iterations: usize,
    /// Evaluations of the residual `K x − Q(x)`.
    pub residual_evaluations: usize,
    /// Evaluations and factorizations of the tangent `K − ∂Q/∂x` (O(n) chain sweeps for the
    /// full model, dense LU otherwise: `solve/tangent.rs`).
    pub factorizations: usize,
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
    /// Solver counters.
    pub stats: StaticStats,
}

/// Solve `K x = Q(x; scales)` for the loads `loads` scaled by `scales`, starting at rest
/// (`x = 0`, no load) and stepping the load factor from 0 to 1.
///
/// # Errors
/// [`SolveError::StaticDiverged`] with the load factor reached if the step had to be cut below
/// `options.min_step`.
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

/// Continue an equilibrium `start = (x, scales₀)` to new load scales `scales₁` along
/// `s(μ) = scales₀ + μ (scales₁ − scales₀)`, `μ: 0 → 1`, with adaptive increments of `μ`.
///
/// # Errors
/// [`SolveError::StaticDiverged`] if the increment had to be cut below `options.min_step`; its
/// `load_factor` is the last `μ` at which an equilibrium was found.
pub fn continue_static<M: StructuralModel>(
    model: &M,
    loads: &AppliedLoads,
    start: (&[f64], &[f64]),
    scales: &[f64],
    options: &StaticOptions,
) -> Result<StaticSolution, SolveError> {
    options.validate().map_err(SolveError::from_input)?;
    let (x_start, s_start) = start;
    let nd = model.n_dofs();
    let mut ws = Newton::new(model, loads, options);
    let s_at = |mu: f64| -> Vec<f64> {
        s_start
            .iter()
            .zip(scales)
            .map(|(a, b)| a + mu * (b - a))
            .collect()
    };
    let mut mu = 0.0;
    let mut x = DVector::from_column_slice(x_start);
    let mut x_prev: Option<(f64, DVector<f64>)> = None;
    let mut step = options.initial_step.clamp(options.min_step, 1.0);
    while mu < 1.0 {
        let target = (mu + step).min(1.0);
        let dmu = target - mu;
        // Secant predictor from the previous two equilibria.
        let guess = match &x_prev {
            Some((mu_p, xp)) if mu - mu_p > 0.0 => &x + (&x - xp) * (dmu / (mu - mu_p)),
            _ => x.clone(),
        };
        match ws.solve(guess, &s_at(target)) {
            Ok((x_new, iterations)) => {
                ws.stats.load_steps += 1;
                x_prev = Some((mu, std::mem::replace(&mut x, x_new)));
                mu = target;
                if iterations <= options.max_iterations / 4 {
                    step = (2.0 * step).min(1.0);
                }
            }
            Err((iterations, residual_norm)) => {
                ws.stats.rejected_steps += 1;
                step *= 0.25;
                if step < options.min_step {
                    return Err(SolveError::StaticDiverged {
                        load_factor: mu,
                        attempted: target,
                        iterations,
                        residual_norm,
                    });
                }
            }
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
        stats: ws.stats,
    })
}

/// Newton iteration state and buffers for one model and load set.
struct Newton<'a, M: StructuralModel> {
    model: &'a M,
    loads: &'a AppliedLoads,
    options: &'a StaticOptions,
    ws: M::Workspace,
    stiffness: Stiffness,
    f: DVector<f64>,
    tangent: Tangent,
    stats: StaticStats,
}

impl<'a, M: StructuralModel> Newton<'a, M> {
    fn new(model: &'a M, loads: &'a AppliedLoads, options: &'a StaticOptions) -> Self {
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
    fn residual(&mut self, x: &DVector<f64>, scales: &[f64]) -> DVector<f64> {
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

    fn converged(&self, x: &DVector<f64>, r: &DVector<f64>) -> bool {
        let scale = self.stiffness.times(x).amax().max(self.f.amax());
        r.amax() <= self.options.tolerance * scale || r.amax() == 0.0
    }

    /// Newton from `x`; on failure returns (iterations, last residual norm).
    fn solve(
        &mut self,
        mut x: DVector<f64>,
        scales: &[f64],
    ) -> Result<(DVector<f64>, usize), (usize, f64)> {
        let mut r = self.residual(&x, scales);
        for it in 0..self.options.max_iterations {
            if !r.iter().all(|v| v.is_finite()) {
                return Err((it, f64::NAN));
            }
            if self.converged(&x, &r) {
                return Ok((x, it));
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
                return Err((it + 1, r.amax()));
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
            return Ok((x, self.options.max_iterations));
        }
        Err((self.options.max_iterations, r.amax()))
    }
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
    let mut done: Vec<StaticSolution> = Vec::with_capacity(points.len());
    for (i, scales) in points.iter().enumerate() {
        let result = match done.last() {
            None => solve_static(model, loads, scales, options),
            Some(prev) => continue_static(model, loads, (&prev.x, &prev.scales), scales, options),
        };
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
