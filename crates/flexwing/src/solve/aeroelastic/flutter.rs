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

use nalgebra::{Complex, DMatrix};

use super::equations::AeroelasticEquations;
use super::flight::FlightHistory;
use super::linear::NewtonWorkspace;
use super::statics::SteadyAeroModel;
use super::tracking::{find_crossings, seed_branches, EquilibriumPath, Linearizer, Tracker};
use crate::error::{InputError, SolveError};
use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
use crate::model::{Load, StructuralModel};
use crate::solve::integrate::OdeSystem;
use crate::solve::{continue_static, Damping, StaticOptions};

type C64 = Complex<f64>;

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
pub struct FlutterOptions {
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

impl FlutterOptions {
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
    /// Branch index (into [`FlutterSolution::branches`]).
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
pub struct FlutterSolution {
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

/// The flutter analysis of `aero` (any aerodynamic model; `Steady` gives coupled-mode flutter
/// without aerodynamic damping) along `plan.speeds`. `progress` is called with the fraction of
/// the speed range covered.
///
/// # Errors
/// An invalid plan or loads. Failures of the analysis itself are reported in
/// [`FlutterSolution::stopped`] with the data up to there.
pub fn flutter<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &FlutterOptions,
    field: &str,
    progress: &mut dyn FnMut(f64),
) -> Result<FlutterSolution, InputError> {
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
    plan: &FlutterOptions,
    field: &str,
    keep_going: &mut dyn FnMut(f64) -> bool,
) -> Result<FlutterSolution, InputError> {
    let n = aero.structure().n_dofs();
    plan.validate(field, n)?;
    if plan.method == FlutterMethod::PkTheodorsen && !aero.aerodynamics().is_unsteady() {
        return Err(InputError::new(
            format!("{field}.method"),
            "the p-k method replaces an unsteady model's lag by Theodorsen's function: choose \
             a quasi-steady, Wagner or Peters model",
        ));
    }
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut loads = plan.loads.clone();
    if let Some(g) = plan.gravity {
        loads.push(Load::Gravity {
            g: g * plan.root_angle.cos(),
        });
    }
    // The equations carry the other loads only through the linearization's K̃, which comes from
    // the structural Jacobian: give them the same loads (gravity is handled by the flight).
    let other = aero.apply(&plan.loads, &format!("{field}.loads"))?;
    let mut lin = Linearizer {
        path: EquilibriumPath {
            model: SteadyAeroModel::new(&steady, plan.root_angle),
            loads: aero.apply(&loads, &format!("{field}.loads"))?,
            options: plan.static_options.clone(),
            rho: aero.density(),
            solved: Vec::new(),
        },
        eqs: AeroelasticEquations::new(
            aero,
            &other,
            vec![crate::solve::TimeFunction::Constant; plan.loads.len()],
            FlightHistory::steady(FlightCondition {
                speed: 0.0,
                root_angle: plan.root_angle,
                gravity: plan.gravity,
            }),
            &plan.damping,
            field,
        )?,
        root_angle: plan.root_angle,
        gravity: plan.gravity,
        scaled: None,
    };
    let mut stats = FlutterStats::default();
    lin.check_polynomial(plan, &mut stats);
    let mut out = FlutterSolution {
        speeds: vec![],
        branches: vec![],
        crossings: vec![],
        flutter: None,
        unstable_at_start: vec![],
        stopped: None,
        stats,
    };
    let lin0 = match lin.at(0.0, &mut stats) {
        Ok(l) => l,
        Err(error) => {
            out.stopped = Some(FlutterStop::Equilibrium { speed: 0.0, error });
            out.stats = stats;
            return Ok(out);
        }
    };
    let mut nws = NewtonWorkspace::new(n);
    let seeds = seed_branches(
        &lin0,
        plan.modes,
        plan.method,
        &mut nws,
        &mut stats,
        &mut out,
    );
    let u_max = *plan.speeds.last().expect("validated");
    let mut tracker = Tracker::new(seeds, plan.method, u_max);
    for &target in &plan.speeds {
        let marched = tracker.interval(
            target,
            &mut lin,
            &mut nws,
            &mut stats,
            &mut out.branches,
            keep_going,
        );
        if let Err(stop) = marched {
            out.stopped = Some(stop);
            break;
        }
        out.speeds.push(target);
        for (br, s) in out.branches.iter_mut().zip(tracker.eigenvalues()) {
            br.eigenvalues.push(s);
        }
    }
    out.unstable_at_start = out
        .branches
        .iter()
        .enumerate()
        .filter(|(_, b)| {
            b.eigenvalues
                .first()
                .is_some_and(|s| s.re > super::tracking::NEUTRAL * s.norm())
        })
        .map(|(i, _)| i)
        .collect();
    find_crossings(
        &tracker, plan, &mut lin, &mut nws, &mut stats, &mut out, keep_going,
    );
    // A branch unstable from the first speed means the wing is unstable below any onset found:
    // no flutter speed then (the caller reads `unstable_at_start`).
    out.flutter = if out.unstable_at_start.is_empty() {
        out.crossings
            .iter()
            .find(|c| c.kind == CrossingKind::Onset)
            .copied()
    } else {
        None
    };
    out.stats = stats;
    Ok(out)
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
    let applied = aero.apply(&all, &format!("{field}.loads"))?;
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
    let other = aero.apply(loads, &format!("{field}.loads"))?;
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
