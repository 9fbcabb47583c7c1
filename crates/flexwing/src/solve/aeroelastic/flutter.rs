//! Stability about the static equilibrium, V-g/V-ω data with modes tracked across speeds, and
//! the flutter speeds (onset and offset of every unstable branch) (docs/aeroelastic-model.md §5).
//!
//! Branches start at `U = 0` from the wet natural modes (structure plus fluid inertia, the exact
//! eigenvalues there) and are continued in `U` by Newton's method on the rational eigenproblem of
//! `linear.rs`, with a secant predictor. A step is accepted when every branch converges, keeps its
//! shape (modal assurance criterion against the previous step at least [`MAC_MIN`]) and no two
//! branches meet; otherwise the speed step is halved (down to `1e-7` of the last speed), and the
//! step after an accepted one is at most twice as long. The work per interval of the plan is
//! bounded: at most [`MAX_SUBSTEPS`] accepted sub-steps, at most [`MAX_MERGED_STEPS`] smallest
//! steps in a row with two branches on one root; beyond either the analysis stops and says
//! between which speeds ([`FlutterStop::BranchLost`]). A sign change of `Re s` between two accepted
//! steps is refined by the Illinois (regula falsi) method on `Re s(U)` to the plan's tolerance.
//! The equilibrium is recomputed at every speed (static solver, load stepping in dynamic
//! pressure, continued from the previous speed), so deflected wings are linearized about their
//! deflected shape.

use nalgebra::{Complex, DMatrix, DVector};

use super::equations::AeroelasticEquations;
use super::flight::FlightHistory;
use super::linear::{mac, Linearization, NewtonWorkspace, Transfer};
use super::statics::SteadyAeroModel;
use crate::error::{InputError, SolveError};
use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
use crate::model::{AppliedLoads, Load, StructuralModel};
use crate::solve::integrate::OdeSystem;
use crate::solve::{continue_static, Damping, StaticOptions};

type C64 = Complex<f64>;
/// The tracked eigenpairs of every branch at one accepted speed.
type Step = (f64, Vec<(C64, DVector<C64>)>);

/// Smallest modal assurance criterion between a branch's eigenvectors at consecutive accepted
/// steps.
pub const MAC_MIN: f64 = 0.8;

/// Most accepted sub-steps between two consecutive speeds of the plan (and from `U = 0` to the
/// first). A well-resolved sweep takes one per interval; the step control (halve on failure,
/// then at most double) needs about `log2(interval / smallest step)` more to cross a coalescence.
/// An interval that needs more stops the analysis honestly ([`FlutterStop::BranchLost`] with
/// `branch: None`): refine the sweep there.
pub const MAX_SUBSTEPS: usize = 1000;

/// Most consecutive steps accepted at the smallest speed step with two branches on the same
/// root. Crossing a coalescence takes one or two; branches that stay on one root have lost one
/// of them, and following them at the smallest step would take `interval / (1e-7 U_max)` steps
/// (the minutes-long runs of issue 9): the analysis stops instead.
pub const MAX_MERGED_STEPS: usize = 4;

/// How the eigenvalues of the linearized system are computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FlutterMethod {
    /// The eigenvalues of the model with its own lag (finite states, quasi-steady or steady):
    /// exact for the model.
    #[default]
    Eigenvalues,
    /// The p-k method with Theodorsen's `C(k)` in place of the model's lag (Hodges & Pierce
    /// §5.4): `C` evaluated at the branch's own frequency, iterated to a fixed point. Exact
    /// Theodorsen flutter where `Re s = 0`; elsewhere an approximation of the damping. Needs an
    /// unsteady model (for its apparent mass and rate terms).
    PkTheodorsen,
}

/// A flutter analysis, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct FlutterPlan {
    /// Speeds of the V-g data (m/s), positive and strictly increasing. Branches are continued
    /// from `U = 0` through them (with smaller steps where needed).
    pub speeds: Vec<f64>,
    /// Root angle of attack (rad).
    pub root_angle: f64,
    /// Gravity (m/s²), or none.
    pub gravity: Option<f64>,
    /// Other loads at full value.
    pub loads: Vec<Load>,
    /// Structural damping.
    pub damping: Damping,
    /// Number of branches tracked: the lowest wet modes at `U = 0`.
    pub modes: usize,
    /// Relative tolerance of the flutter speeds (e.g. 1e-6).
    pub tolerance: f64,
    /// Options of the static solver for the equilibria.
    pub static_options: StaticOptions,
    /// Eigenvalues of the model, or the p-k method with Theodorsen's function.
    pub method: FlutterMethod,
}

impl FlutterPlan {
    /// A plan with no root angle, gravity, loads or damping, tracking `modes` branches through
    /// `speeds`, flutter speeds to 1e-6.
    pub fn new(speeds: Vec<f64>, modes: usize) -> Self {
        Self {
            speeds,
            root_angle: 0.0,
            gravity: None,
            loads: vec![],
            damping: Damping::None,
            modes,
            tolerance: 1e-6,
            static_options: StaticOptions::default(),
            method: FlutterMethod::Eigenvalues,
        }
    }

    /// Check the plan against a model with `n_dofs` coordinates; `field` prefixes the fields.
    pub fn validate(&self, field: &str, n_dofs: usize) -> Result<(), InputError> {
        if self.speeds.is_empty() {
            return Err(InputError::new(
                format!("{field}.speeds"),
                "needs at least one speed",
            ));
        }
        for (i, &u) in self.speeds.iter().enumerate() {
            if !(u.is_finite() && u > 0.0) || (i > 0 && u <= self.speeds[i - 1]) {
                return Err(InputError::new(
                    format!("{field}.speeds[{i}]"),
                    format!(
                        "speeds must be finite, positive and strictly increasing, got {}",
                        crate::text::short(u)
                    ),
                ));
            }
        }
        FlightCondition {
            speed: self.speeds[0],
            root_angle: self.root_angle,
            gravity: self.gravity,
        }
        .validate(field)?;
        if self.modes == 0 || self.modes > n_dofs {
            return Err(InputError::new(
                format!("{field}.modes"),
                format!(
                    "must be between 1 and {n_dofs} (the model's coordinates), got {}",
                    self.modes
                ),
            ));
        }
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(InputError::new(
                format!("{field}.tolerance"),
                format!(
                    "must be in (0, 1), got {}",
                    crate::text::short(self.tolerance)
                ),
            ));
        }
        self.static_options
            .validate(&format!("{field}.static_options"))
    }
}

/// One tracked branch: the eigenvalue `s = σ + iω` (Im ≥ 0) at every speed of the plan.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// Index of the wet mode it starts from at `U = 0` (0-based, by frequency).
    pub mode: usize,
    /// Its wet natural frequency at `U = 0` (rad/s).
    pub wet_frequency: f64,
    /// Eigenvalue at each speed reached (1/s).
    pub eigenvalues: Vec<C64>,
    /// Some step had to be accepted at the smallest speed step without passing the shape check
    /// (a coalescence, or two branches very close): the tracking there is uncertain.
    pub uncertain: bool,
}

impl Branch {
    /// Frequencies `ω = Im s` (rad/s) at the speeds reached.
    pub fn frequencies(&self) -> Vec<f64> {
        self.eigenvalues.iter().map(|s| s.im).collect()
    }
    /// Damping ratios `ζ = −σ/|s|`.
    pub fn damping_ratios(&self) -> Vec<f64> {
        self.eigenvalues.iter().map(|s| -s.re / s.norm()).collect()
    }
    /// The V-g "structural damping required", `g = 2σ/ω` (positive: unstable; infinite for a
    /// real root).
    pub fn g(&self) -> Vec<f64> {
        self.eigenvalues.iter().map(|s| 2.0 * s.re / s.im).collect()
    }
}

/// Whether a branch becomes unstable or stable again with increasing speed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CrossingKind {
    /// `Re s` goes from negative to positive: flutter (or divergence, at zero frequency) onset.
    Onset,
    /// `Re s` goes from positive to negative: the branch is stable again.
    Offset,
}

/// A crossing of the imaginary axis, refined.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Branch index (into [`FlutterOutcome::branches`]).
    pub branch: usize,
    /// Onset or offset.
    pub kind: CrossingKind,
    /// Speed (m/s).
    pub speed: f64,
    /// Frequency `Im s` at the crossing (rad/s); 0 for a divergence-type (real) root.
    pub frequency: f64,
}

/// Counters of a flutter analysis.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct FlutterStats {
    /// Linearizations (equilibrium plus derivatives) computed.
    pub linearizations: usize,
    /// Newton iterations on the rational eigenproblem (each one complex LU of `n_dofs`).
    pub newton_iterations: usize,
    /// Speed steps halved.
    pub halvings: usize,
    /// Trial speeds (accepted or not): each one linearization and one Newton solve per branch.
    pub trials: usize,
    /// Static equilibria solved.
    pub static_solves: usize,
}

/// Why a flutter analysis stopped before its last speed.
#[derive(Debug, Clone, PartialEq)]
pub enum FlutterStop {
    /// The static equilibrium could not be found (e.g. past divergence).
    Equilibrium {
        /// Speed attempted (m/s).
        speed: f64,
        /// The static solver's error.
        error: SolveError,
    },
    /// A branch was lost between `from` and `speed`: Newton's method failed even at the
    /// smallest speed step, or two branches stayed on one root for more than
    /// [`MAX_MERGED_STEPS`] smallest steps; or (`branch: None`) the interval needed more than
    /// [`MAX_SUBSTEPS`] accepted sub-steps. Refine the sweep there.
    BranchLost {
        /// Branch index, if one branch was lost (`None`: the sub-step cap was reached).
        branch: Option<usize>,
        /// The last speed of the plan reached (m/s): the start of the interval.
        from: f64,
        /// Speed attempted (m/s).
        speed: f64,
        /// Sub-steps accepted in the interval before the stop.
        substeps: usize,
    },
    /// The caller cancelled the analysis (its callback returned `false`) at this speed (m/s).
    Cancelled {
        /// The last speed accepted (m/s).
        speed: f64,
    },
}

impl std::fmt::Display for FlutterStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        use crate::text::short;
        match self {
            Self::Equilibrium { speed, error } => {
                write!(
                    f,
                    "no static equilibrium at U = {} m/s: {error}",
                    short(*speed)
                )
            }
            Self::BranchLost {
                branch: Some(b),
                from,
                speed,
                substeps,
            } => write!(
                f,
                "branch {} lost between U = {} and {} m/s after {substeps} sub-steps (Newton's \
                 method failed, or two branches stayed on one root, even at the smallest speed \
                 step; refine the sweep there)",
                b + 1,
                short(*from),
                short(*speed)
            ),
            Self::BranchLost {
                branch: None,
                from,
                speed,
                substeps,
            } => write!(
                f,
                "branches not tracked between U = {} and {} m/s within {substeps} sub-steps (the \
                 cap per speed interval); refine the sweep there",
                short(*from),
                short(*speed)
            ),
            Self::Cancelled { speed } => write!(f, "interrupted at U = {} m/s", short(*speed)),
        }
    }
}

/// What a flutter analysis produced.
#[derive(Debug, Clone, PartialEq)]
pub struct FlutterOutcome {
    /// The plan's speeds reached (m/s).
    pub speeds: Vec<f64>,
    /// The tracked branches (V-g / V-ω data).
    pub branches: Vec<Branch>,
    /// Every crossing found, by speed.
    pub crossings: Vec<Crossing>,
    /// The flutter (or dynamic divergence) point: the lowest onset; `None` if there is none, or
    /// if some branch is already unstable at the first speed (see `unstable_at_start`).
    pub flutter: Option<Crossing>,
    /// Branches already unstable at the first speed of the plan: no onset can be given for them
    /// (e.g. the quasi-steady model with the elastic axis at mid-chord).
    pub unstable_at_start: Vec<usize>,
    /// Why the analysis stopped early, if it did (the data above are kept).
    pub stopped: Option<FlutterStop>,
    /// Counters.
    pub stats: FlutterStats,
}

/// The steady equilibrium along the speeds: continued from the closest speed solved below.
struct EquilibriumPath<'a, M: AeroStructure> {
    model: SteadyAeroModel<'a, M>,
    loads: AppliedLoads,
    options: StaticOptions,
    rho: f64,
    solved: Vec<(f64, Vec<f64>)>,
}

impl<M: AeroStructure> EquilibriumPath<'_, M> {
    fn at(&mut self, u: f64, stats: &mut FlutterStats) -> Result<Vec<f64>, SolveError> {
        let k = self.loads.n_loads();
        let scales = |u: f64| {
            let mut s = vec![1.0; k];
            s.push(0.5 * self.rho * u * u);
            s
        };
        // A speed already solved (a refinement may ask again) is not solved twice.
        if let Some((_, x)) = self.solved.iter().find(|(v, _)| *v == u) {
            return Ok(x.clone());
        }
        let from = self
            .solved
            .iter()
            .filter(|(v, _)| *v <= u)
            .max_by(|a, b| a.0.total_cmp(&b.0));
        let (x0, s0) = match from {
            Some((v, x)) => (x.clone(), scales(*v)),
            None => (vec![0.0; self.model.n_dofs()], vec![0.0; k + 1]),
        };
        stats.static_solves += 1;
        let sol = continue_static(
            &self.model,
            &self.loads,
            (&x0, &s0),
            &scales(u),
            &self.options,
        )?;
        self.solved.push((u, sol.x.clone()));
        Ok(sol.x)
    }
}

/// The flutter analysis of `aero` (any aerodynamic model; `Steady` gives coupled-mode flutter
/// without aerodynamic damping) along `plan.speeds`. `progress` is called with the fraction of
/// the speed range covered.
///
/// # Errors
/// An invalid plan or loads. Failures of the analysis itself are reported in
/// [`FlutterOutcome::stopped`] with the data up to there.
pub fn flutter<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &FlutterPlan,
    field: &str,
    progress: &mut dyn FnMut(f64),
) -> Result<FlutterOutcome, InputError> {
    flutter_polled(aero, plan, field, &mut |f| {
        progress(f);
        true
    })
}

/// [`flutter`] that can be cancelled: `keep_going` hears the fraction of the speed range covered
/// before every trial speed, after every accepted one and before every crossing refinement, and
/// returning `false` stops the analysis there ([`FlutterStop::Cancelled`], the data up to there
/// kept). Between two calls there is at most one linearization (a static solve on a deformed wing)
/// and one set of branch solves.
///
/// # Errors
/// As [`flutter`].
pub fn flutter_polled<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &FlutterPlan,
    field: &str,
    keep_going: &mut dyn FnMut(f64) -> bool,
) -> Result<FlutterOutcome, InputError> {
    let n = aero.structure().n_dofs();
    plan.validate(field, n)?;
    if plan.method == FlutterMethod::PkTheodorsen && !aero.aerodynamics().is_unsteady() {
        return Err(InputError::new(
            format!("{field}.method"),
            "the p-k method replaces an unsteady model's lag by Theodorsen's function: choose \
             a quasi-steady, Wagner or Peters model",
        ));
    }
    let method = plan.method;
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut loads = plan.loads.clone();
    if let Some(g) = plan.gravity {
        loads.push(Load::Gravity {
            g: g * plan.root_angle.cos(),
        });
    }
    let applied = aero.full().apply(&loads, &format!("{field}.loads"))?;
    let mut path = EquilibriumPath {
        model: SteadyAeroModel::new(&steady, plan.root_angle),
        loads: applied,
        options: plan.static_options.clone(),
        rho: aero.density(),
        solved: Vec::new(),
    };
    // The equations carry the other loads only through the linearization's K̃, which comes from
    // the structural Jacobian: give them the same loads (gravity is handled by the flight).
    let other = aero.full().apply(&plan.loads, &format!("{field}.loads"))?;
    let condition = |u: f64| FlightCondition {
        speed: u,
        root_angle: plan.root_angle,
        gravity: plan.gravity,
    };
    let mut eqs = AeroelasticEquations::new(
        aero,
        &other,
        vec![crate::solve::TimeFunction::Constant; plan.loads.len()],
        FlightHistory::steady(condition(0.0)),
        &plan.damping,
        field,
    )?;
    let mut stats = FlutterStats::default();
    let linearize = |u: f64,
                     path: &mut EquilibriumPath<'_, M>,
                     eqs: &mut AeroelasticEquations<'_, M>,
                     stats: &mut FlutterStats|
     -> Result<Linearization, SolveError> {
        let x = path.at(u, stats)?;
        eqs.set_flight(FlightHistory::steady(condition(u)));
        let a = eqs.steady_states(0.0, &x);
        stats.linearizations += 1;
        Ok(eqs.linearize(&x, &a))
    };
    // A wing that stays undeformed at every speed (no root angle, gravity or loads, and no
    // aerodynamic load at rest: a symmetric section with c_m0 = 0) has a linearization
    // polynomial in U: two linearizations serve every speed, once checked against a third.
    let mut scaled: Option<(Linearization, Linearization)> = None;
    if plan.loads.is_empty() && plan.gravity.is_none() && plan.root_angle == 0.0 {
        let model = SteadyAeroModel::new(&steady, 0.0);
        let mut ws = model.workspace();
        let mut f = DVector::zeros(n);
        model.generalized_forces_into(
            &vec![0.0; n],
            &AppliedLoads::none(),
            &[1.0],
            &mut ws,
            &mut f,
        );
        if f.amax() == 0.0 {
            let u_max = *plan.speeds.last().expect("validated");
            let lin = |u: f64, eqs: &mut AeroelasticEquations<'_, M>, stats: &mut FlutterStats| {
                eqs.set_flight(FlightHistory::steady(condition(u)));
                let x = vec![0.0; n];
                let a = eqs.steady_states(0.0, &x);
                stats.linearizations += 1;
                eqs.linearize(&x, &a)
            };
            let (l0, l1) = (
                lin(0.0, &mut eqs, &mut stats),
                lin(1.0, &mut eqs, &mut stats),
            );
            let check = lin(0.61 * u_max, &mut eqs, &mut stats);
            if Linearization::scaled(&l0, &l1, 0.61 * u_max).distance(&check) < 1e-9 {
                scaled = Some((l0, l1));
            }
        }
    }
    let linearize = |u: f64,
                     path: &mut EquilibriumPath<'_, M>,
                     eqs: &mut AeroelasticEquations<'_, M>,
                     stats: &mut FlutterStats|
     -> Result<Linearization, SolveError> {
        match &scaled {
            Some((l0, l1)) => Ok(Linearization::scaled(l0, l1, u)),
            None => linearize(u, path, eqs, stats),
        }
    };
    let mut outcome = FlutterOutcome {
        speeds: vec![],
        branches: vec![],
        crossings: vec![],
        flutter: None,
        unstable_at_start: vec![],
        stopped: None,
        stats,
    };
    // Seeds: the wet modes at U = 0.
    let lin0 = match linearize(0.0, &mut path, &mut eqs, &mut stats) {
        Ok(l) => l,
        Err(error) => {
            outcome.stopped = Some(FlutterStop::Equilibrium { speed: 0.0, error });
            outcome.stats = stats;
            return Ok(outcome);
        }
    };
    let seeds = wet_modes(&lin0, plan.modes);
    let mut nws = NewtonWorkspace::new(n);
    let tol = 1e-11;
    let mut current: Vec<(C64, DVector<C64>)> = Vec::with_capacity(plan.modes);
    for (k, (s, v)) in seeds.iter().enumerate() {
        let pair = solve_branch(&lin0, *s, v, method, tol, 30, &mut nws);
        stats.newton_iterations += pair.as_ref().map_or(30, |p| p.iterations);
        let (s, v) = pair.map_or((*s, v.clone()), |p| (p.s, p.v));
        current.push((s, v));
        outcome.branches.push(Branch {
            mode: k,
            wet_frequency: seeds[k].0.im,
            eigenvalues: vec![],
            uncertain: false,
        });
    }
    // March in speed. `history` keeps every accepted step for the crossing refinement.
    let u_max = *plan.speeds.last().expect("validated");
    let h_min = 1e-7 * u_max;
    let mut history: Vec<Step> = vec![(0.0, current.clone())];
    let mut u_prev = 0.0;
    let mut slope: Option<Vec<C64>> = None; // ds/dU of the last step
                                            // Consecutive steps accepted at the smallest step with two branches on one root.
    let mut merged_run = 0;
    'speeds: for &target in &plan.speeds {
        let from = u_prev;
        let mut substeps = 0;
        // The first trial of an interval is the whole interval (a well-resolved sweep takes one
        // step per speed); after a halving, a step at most twice the last accepted one.
        let mut h_next = target - u_prev;
        while u_prev < target {
            if substeps == MAX_SUBSTEPS {
                outcome.stopped = Some(FlutterStop::BranchLost {
                    branch: None,
                    from,
                    speed: target,
                    substeps,
                });
                break 'speeds;
            }
            let mut h = h_next.min(target - u_prev);
            let accepted = loop {
                if !keep_going(u_prev / u_max) {
                    outcome.stopped = Some(FlutterStop::Cancelled { speed: u_prev });
                    break 'speeds;
                }
                // The whole remainder lands on the plan's speed exactly.
                let u = if h == target - u_prev {
                    target
                } else {
                    u_prev + h
                };
                stats.trials += 1;
                let lin = match linearize(u, &mut path, &mut eqs, &mut stats) {
                    Ok(l) => l,
                    Err(error) => {
                        if h > h_min {
                            h *= 0.5;
                            stats.halvings += 1;
                            continue;
                        }
                        outcome.stopped = Some(FlutterStop::Equilibrium { speed: u, error });
                        break 'speeds;
                    }
                };
                let mut next = Vec::with_capacity(current.len());
                let mut ok = true;
                let mut lost = None;
                for (b, (s, v)) in current.iter().enumerate() {
                    let pred = *s + slope.as_ref().map_or(C64::new(0.0, 0.0), |d| d[b] * h);
                    match solve_branch(&lin, pred, v, method, tol, 12, &mut nws) {
                        Some(p) => {
                            stats.newton_iterations += p.iterations;
                            if mac(&p.v, v) < MAC_MIN {
                                ok = false;
                            }
                            next.push((p.s, p.v));
                        }
                        None => {
                            stats.newton_iterations += 12;
                            ok = false;
                            lost = Some(b);
                            next.push((*s, v.clone()));
                        }
                    }
                }
                // Two branches converged to the same root?
                let mut merged = None;
                for a in 0..next.len() {
                    for b in 0..a {
                        if (next[a].0 - next[b].0).norm() <= 1e-7 * next[a].0.norm().max(1e-6) {
                            ok = false;
                            merged = Some(a);
                        }
                    }
                }
                if ok {
                    merged_run = 0;
                    break (u, next);
                }
                if h > h_min {
                    h *= 0.5;
                    stats.halvings += 1;
                    continue;
                }
                if let Some(b) = lost {
                    outcome.stopped = Some(FlutterStop::BranchLost {
                        branch: Some(b),
                        from,
                        speed: u,
                        substeps,
                    });
                    break 'speeds;
                }
                // Accepted at the smallest step: a coalescence is passed in a step or two; two
                // branches that stay on one root have lost one of them.
                if let Some(b) = merged {
                    merged_run += 1;
                    if merged_run > MAX_MERGED_STEPS {
                        outcome.stopped = Some(FlutterStop::BranchLost {
                            branch: Some(b),
                            from,
                            speed: u,
                            substeps,
                        });
                        break 'speeds;
                    }
                } else {
                    merged_run = 0;
                }
                for br in outcome.branches.iter_mut() {
                    br.uncertain = true;
                }
                break (u, next);
            };
            let (u, next) = accepted;
            substeps += 1;
            h_next = 2.0 * (u - u_prev);
            slope = Some(
                next.iter()
                    .zip(&current)
                    .map(|(a, b)| (a.0 - b.0) / (u - u_prev))
                    .collect(),
            );
            current = next;
            u_prev = u;
            history.push((u, current.clone()));
            keep_going(u / u_max);
        }
        outcome.speeds.push(target);
        for (br, (s, _)) in outcome.branches.iter_mut().zip(&current) {
            br.eigenvalues.push(*s);
        }
    }
    // Branches unstable at the first speed of the plan.
    outcome.unstable_at_start = outcome
        .branches
        .iter()
        .enumerate()
        .filter(|(_, b)| b.eigenvalues.first().is_some_and(|s| s.re > 0.0))
        .map(|(i, _)| i)
        .collect();
    // Crossings after the first speed of the plan.
    let first = plan.speeds[0];
    'crossings: for w in history.windows(2) {
        let ((ua, sa), (ub, sb)) = (&w[0], &w[1]);
        if *ub <= first {
            continue;
        }
        for b in 0..sa.len() {
            let (ra, rb) = (sa[b].0.re, sb[b].0.re);
            if (ra < 0.0) == (rb < 0.0) {
                continue;
            }
            if !keep_going(u_prev / u_max) {
                outcome
                    .stopped
                    .get_or_insert(FlutterStop::Cancelled { speed: u_prev });
                break 'crossings;
            }
            let kind = if ra < 0.0 {
                CrossingKind::Onset
            } else {
                CrossingKind::Offset
            };
            let (speed, frequency) = refine(
                (*ua, &sa[b]),
                (*ub, &sb[b]),
                plan.tolerance,
                &mut |u| linearize(u, &mut path, &mut eqs, &mut stats),
                method,
                &mut nws,
            );
            outcome.crossings.push(Crossing {
                branch: b,
                kind,
                speed,
                // A real root (divergence) has no frequency; below 1e-9 |s| it is round-off.
                frequency: if frequency.abs() <= 1e-9 * sb[b].0.norm() {
                    0.0
                } else {
                    frequency.abs()
                },
            });
        }
    }
    outcome
        .crossings
        .sort_by(|a, b| a.speed.total_cmp(&b.speed));
    // A branch unstable from the first speed means the wing is unstable below any onset found:
    // no flutter speed then (the caller reads `unstable_at_start`).
    outcome.flutter = if outcome.unstable_at_start.is_empty() {
        outcome
            .crossings
            .iter()
            .find(|c| c.kind == CrossingKind::Onset)
            .copied()
    } else {
        None
    };
    outcome.stats = stats;
    Ok(outcome)
}

/// The root of `Re s(U)` between `a` and `b` (opposite signs): secant steps on the two latest
/// points, kept inside the bracket (bisection otherwise), each trial speed linearized by
/// `linearize` and its eigenvalue found by Newton from the linear interpolation of the latest two.
/// Returns `(U, Im s)`.
fn refine(
    a: (f64, &(C64, DVector<C64>)),
    b: (f64, &(C64, DVector<C64>)),
    tolerance: f64,
    linearize: &mut dyn FnMut(f64) -> Result<Linearization, SolveError>,
    method: FlutterMethod,
    ws: &mut NewtonWorkspace,
) -> (f64, f64) {
    let (mut lo, mut hi) = (a.0, b.0);
    let f_lo_negative = a.1 .0.re < 0.0;
    let mut p1 = (a.0, a.1 .0);
    let mut p2 = (b.0, b.1 .0);
    let mut v = b.1 .1.clone();
    let mut best = (b.0, b.1 .0.im);
    for _ in 0..60 {
        let (u1, s1) = p1;
        let (u2, s2) = p2;
        let mut u = u2 - s2.re * (u2 - u1) / (s2.re - s1.re);
        if !(u.is_finite() && u > lo && u < hi) {
            u = 0.5 * (lo + hi);
        }
        let Ok(lin) = linearize(u) else { break };
        let guess = s1 + (s2 - s1) * ((u - u1) / (u2 - u1));
        let Some(p) = solve_branch(&lin, guess, &v, method, 1e-12, 20, ws) else {
            break;
        };
        best = (u, p.s.im);
        let step = (u - u2).abs();
        if (p.s.re < 0.0) == f_lo_negative {
            lo = u;
        } else {
            hi = u;
        }
        v = p.v;
        p1 = p2;
        p2 = (u, p.s);
        if step <= tolerance * u || hi - lo <= tolerance * u || p.s.re == 0.0 {
            break;
        }
    }
    best
}

/// One eigenpair near `(s, v)`: Newton on the model's rational eigenproblem, or the p-k fixed
/// point (Newton at `C(k)` frozen at the current frequency, then the frequency updated, until it
/// stops moving).
fn solve_branch(
    lin: &Linearization,
    s: C64,
    v: &DVector<C64>,
    method: FlutterMethod,
    tol: f64,
    max_iterations: usize,
    ws: &mut NewtonWorkspace,
) -> Option<super::linear::EigenPair> {
    match method {
        FlutterMethod::Eigenvalues => lin.newton(s, v, Transfer::Model, tol, max_iterations, ws),
        FlutterMethod::PkTheodorsen => {
            let (mut s, mut v) = (s, v.clone());
            let mut iterations = 0;
            for _ in 0..50 {
                let omega = s.im.abs();
                let p = lin.newton(
                    s,
                    &v,
                    Transfer::Theodorsen { omega },
                    tol,
                    max_iterations,
                    ws,
                )?;
                iterations += p.iterations;
                let moved = (p.s.im.abs() - omega).abs();
                s = p.s;
                v = p.v;
                if moved <= tol * s.norm().max(1e-3) {
                    return Some(super::linear::EigenPair { s, v, iterations });
                }
            }
            None
        }
    }
}

/// The `count` lowest wet modes of the linearization at `U = 0`: `(iω_k, φ_k)`, from the
/// symmetric part of `K̃` and `M` (exact when the other loads are conservative; Newton then
/// refines the seeds with the damping and any non-symmetric load).
fn wet_modes(lin: &Linearization, count: usize) -> Vec<(C64, DVector<C64>)> {
    let k = (&lin.stiffness + lin.stiffness.transpose()) * 0.5;
    match crate::solve::generalized_symmetric_eigen(&k, &lin.mass) {
        Ok((lambda, phi)) => (0..count)
            .map(|i| {
                let w = lambda[i].max(0.0).sqrt();
                (C64::new(0.0, w), phi.column(i).map(|x| C64::new(x, 0.0)))
            })
            .collect(),
        Err(_) => Vec::new(),
    }
}

/// Eigenvalues of the exact Jacobian of the first-order aeroelastic system `(x, p, a)` at the
/// static equilibrium in the flight condition `flight` with other loads `loads`: a dense
/// eigen-decomposition of the whole system (lag states included), O((2n + n_a)³), after
/// balancing (`balance.rs`: without it the Goland wing's modes lost up to 4e-6). The tracked
/// branches of [`flutter`] are a subset of these (tested).
///
/// # Errors
/// Invalid input, or the static equilibrium not found.
pub fn stability_eigenvalues<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    flight: &FlightCondition,
    loads: &[Load],
    damping: &Damping,
    options: &StaticOptions,
    field: &str,
) -> Result<Vec<C64>, crate::Error> {
    flight.validate(field)?;
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut all = loads.to_vec();
    if let Some(g) = flight.gravity {
        all.push(Load::Gravity {
            g: g * flight.root_angle.cos(),
        });
    }
    let applied = aero.full().apply(&all, &format!("{field}.loads"))?;
    let model = SteadyAeroModel::new(&steady, flight.root_angle);
    let k = applied.n_loads();
    let n = model.n_dofs();
    let mut scales = vec![1.0; k];
    scales.push(0.5 * aero.density() * flight.speed * flight.speed);
    let sol = continue_static(
        &model,
        &applied,
        (&vec![0.0; n], &vec![0.0; k + 1]),
        &scales,
        options,
    )?;
    let other = aero.full().apply(loads, &format!("{field}.loads"))?;
    let mut eqs = AeroelasticEquations::new(
        aero,
        &other,
        vec![crate::solve::TimeFunction::Constant; loads.len()],
        FlightHistory::steady(*flight),
        damping,
        field,
    )?;
    let a = eqs.steady_states(0.0, &sol.x);
    let y = eqs.state(&sol.x, &vec![0.0; n], &a);
    let dim = eqs.dim();
    let mut jac = DMatrix::zeros(dim, dim);
    eqs.jacobian(0.0, &y, &mut jac);
    super::balance::balance(&mut jac);
    Ok(jac.complex_eigenvalues().iter().copied().collect())
}
