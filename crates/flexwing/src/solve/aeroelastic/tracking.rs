//! The named steps of the flutter analysis (`flutter.rs`, docs/aeroelastic-model.md §5): the
//! equilibrium along the speeds and the linearization at each speed ([`Linearizer`]), the seeds
//! at `U = 0`, the march of the branches in speed with its step control ([`Tracker`]), the
//! crossings of the imaginary axis and their refinement, and the solve of one branch at one
//! speed (the model's eigenvalues, or the p-k fixed point).

use nalgebra::{Complex, DVector};

use super::equations::AeroelasticEquations;
use super::flight::FlightHistory;
use super::flutter::{
    Branch, Crossing, CrossingKind, FlutterMethod, FlutterOptions, FlutterSolution, FlutterStats,
    FlutterStop, MAC_MIN, MAX_MERGED_STEPS, MAX_SUBSTEPS,
};
use super::linear::{mac, EigenPair, Linearization, NewtonWorkspace, Transfer};
use super::statics::SteadyAeroModel;
use crate::error::SolveError;
use crate::model::aero::{AeroStructure, FlightCondition};
use crate::model::{AppliedLoads, StructuralModel};
use crate::solve::{continue_static, StaticOptions};

type C64 = Complex<f64>;
/// The tracked eigenpairs of every branch at one accepted speed.
type Step = (f64, Vec<(C64, DVector<C64>)>);

/// The steady equilibrium along the speeds: continued from the closest speed solved below.
pub(super) struct EquilibriumPath<'a, M: AeroStructure> {
    pub(super) model: SteadyAeroModel<'a, M>,
    pub(super) loads: AppliedLoads,
    pub(super) options: StaticOptions,
    pub(super) rho: f64,
    pub(super) solved: Vec<(f64, Vec<f64>)>,
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

/// The linearization of the aeroelastic system at any speed: about the equilibrium found along
/// the path, or, for a wing that stays undeformed at every speed, from two linearizations scaled
/// in `U` ([`Linearizer::check_polynomial`]).
pub(super) struct Linearizer<'a, M: AeroStructure> {
    pub(super) path: EquilibriumPath<'a, M>,
    pub(super) eqs: AeroelasticEquations<'a, M>,
    pub(super) root_angle: f64,
    pub(super) gravity: Option<f64>,
    /// The linearizations at `U = 0` and `U = 1` when the linearization is polynomial in `U`.
    pub(super) scaled: Option<(Linearization, Linearization)>,
}

impl<M: AeroStructure> Linearizer<'_, M> {
    fn condition(&self, u: f64) -> FlightCondition {
        FlightCondition {
            speed: u,
            root_angle: self.root_angle,
            gravity: self.gravity,
        }
    }

    /// About the equilibrium at `u` (the static solve continued along the path).
    fn about_equilibrium(
        &mut self,
        u: f64,
        stats: &mut FlutterStats,
    ) -> Result<Linearization, SolveError> {
        let x = self.path.at(u, stats)?;
        self.eqs
            .set_flight(FlightHistory::steady(self.condition(u)));
        let a = self.eqs.steady_states(0.0, &x);
        stats.linearizations += 1;
        Ok(self.eqs.linearize(&x, &a))
    }

    /// About the state `x` at `u` (an equilibrium at every speed: the undeformed wing, or the
    /// structural equilibrium where the steady aerodynamic load vanishes).
    fn about(&mut self, x: &[f64], u: f64, stats: &mut FlutterStats) -> Linearization {
        self.eqs
            .set_flight(FlightHistory::steady(self.condition(u)));
        let a = self.eqs.steady_states(0.0, x);
        stats.linearizations += 1;
        self.eqs.linearize(x, &a)
    }

    /// The linearization at `u`.
    pub(super) fn at(
        &mut self,
        u: f64,
        stats: &mut FlutterStats,
    ) -> Result<Linearization, SolveError> {
        match &self.scaled {
            Some((l0, l1)) => Ok(Linearization::scaled(l0, l1, u)),
            None => self.about_equilibrium(u, stats),
        }
    }

    /// A wing whose equilibrium does not move with the speed has a linearization polynomial in
    /// U: two linearizations serve every speed, once checked against a third at `0.61 u_max`.
    /// Such a wing is one that stays undeformed (no root angle, gravity or loads, and no
    /// aerodynamic load at rest: a symmetric section with c_m0 = 0), or one whose structural
    /// equilibrium under the other loads and gravity carries no steady aerodynamic load (zero
    /// angle of attack everywhere: a symmetric, untwisted wing at zero root angle bent in its
    /// plane of symmetry, `d0 = 0`, by vertical loads; its load must vanish to 1e-12 of what one
    /// radian of angle of attack would give). Past the divergence speed the linearization is
    /// then about that equilibrium, unstable there, as for the undeformed wing.
    pub(super) fn check_polynomial(&mut self, plan: &FlutterOptions, stats: &mut FlutterStats) {
        let undeformed = plan.loads.is_empty() && plan.gravity.is_none() && plan.root_angle == 0.0;
        let n = self.path.model.n_dofs();
        let x0 = if undeformed {
            vec![0.0; n]
        } else if plan.root_angle == 0.0 {
            match self.path.at(0.0, stats) {
                Ok(x) => x,
                Err(_) => return,
            }
        } else {
            return;
        };
        let model = &self.path.model;
        let mut ws = model.workspace();
        let mut f = DVector::zeros(n);
        model.generalized_forces_into(&x0, &AppliedLoads::none(), &[1.0], &mut ws, &mut f);
        if undeformed {
            if f.amax() != 0.0 {
                return;
            }
        } else {
            let mut slope = nalgebra::DMatrix::zeros(n, n);
            model.load_jacobian_into(&x0, &AppliedLoads::none(), &[1.0], &mut ws, &mut slope);
            if !(f.amax() <= 1e-12 * slope.amax()) {
                return;
            }
        }
        let u_max = *plan.speeds.last().expect("validated");
        let (l0, l1) = (self.about(&x0, 0.0, stats), self.about(&x0, 1.0, stats));
        let check = self.about(&x0, 0.61 * u_max, stats);
        if Linearization::scaled(&l0, &l1, 0.61 * u_max).distance(&check) < 1e-9 {
            self.scaled = Some((l0, l1));
        }
    }
}

/// Newton's stopping tolerance on the branches while marching.
const TRACK_TOLERANCE: f64 = 1e-11;

/// A branch with `|Re s| ≤ NEUTRAL |s|` has no aerodynamic damping there: its `Re s` is
/// round-off, whose sign changes are not crossings and whose sign at the first speed is not an
/// instability. The lag branch of a straight 3-D wing at zero lift without drag is one: its
/// loads do not depend on the lag motion to first order, and its `Re s` measured 1e-86 |s|.
pub(super) const NEUTRAL: f64 = 1e-10;

/// The seeds of the branches: the wet modes at `U = 0` (`lin0`) refined by Newton, and the
/// branches they start, pushed into `out`.
pub(super) fn seed_branches(
    lin0: &Linearization,
    modes: usize,
    method: FlutterMethod,
    nws: &mut NewtonWorkspace,
    stats: &mut FlutterStats,
    out: &mut FlutterSolution,
) -> Vec<(C64, DVector<C64>)> {
    let seeds = wet_modes(lin0, modes);
    let mut current = Vec::with_capacity(modes);
    for (k, (s, v)) in seeds.iter().enumerate() {
        let pair = solve_branch(lin0, *s, v, method, TRACK_TOLERANCE, 30, nws);
        stats.newton_iterations += pair.as_ref().map_or(30, |p| p.iterations);
        let (s, v) = pair.map_or((*s, v.clone()), |p| (p.s, p.v));
        current.push((s, v));
        out.branches.push(Branch {
            mode: k,
            // |s| of Newton's root (the natural frequency, also with structural damping): the
            // symmetric eigensolver's seed carries the round-off of the whole spectrum's spread
            // (6e-8 relative on the lowest mode of a 3-D wing whose lag stiffness is 200 times
            // its flap stiffness).
            wet_frequency: s.norm(),
            eigenvalues: vec![],
            uncertain: false,
        });
    }
    current
}

/// The branches' solves at one trial speed.
struct Trial {
    next: Vec<(C64, DVector<C64>)>,
    /// Every branch converged with its shape kept and no two on one root.
    ok: bool,
    /// A branch whose Newton iteration failed.
    lost: Option<usize>,
    /// A branch that converged to another's root.
    merged: Option<usize>,
}

/// The march of the branches in speed: where they are, the secant slope of the last step, and
/// every accepted step (for the crossing refinement).
pub(super) struct Tracker {
    method: FlutterMethod,
    current: Vec<(C64, DVector<C64>)>,
    /// `ds/dU` of the last step.
    slope: Option<Vec<C64>>,
    pub(super) history: Vec<Step>,
    pub(super) u_prev: f64,
    /// Consecutive steps accepted at the smallest step with two branches on one root.
    merged_run: usize,
    pub(super) u_max: f64,
    h_min: f64,
}

impl Tracker {
    pub(super) fn new(
        current: Vec<(C64, DVector<C64>)>,
        method: FlutterMethod,
        u_max: f64,
    ) -> Self {
        Self {
            method,
            history: vec![(0.0, current.clone())],
            current,
            slope: None,
            u_prev: 0.0,
            merged_run: 0,
            u_max,
            h_min: 1e-7 * u_max,
        }
    }

    /// The current eigenvalue of every branch.
    pub(super) fn eigenvalues(&self) -> impl Iterator<Item = C64> + '_ {
        self.current.iter().map(|(s, _)| *s)
    }

    /// March from the last speed reached to the plan's speed `target` in accepted sub-steps.
    /// The first trial of an interval is the whole interval (a well-resolved sweep takes one
    /// step per speed); after a halving, a step at most twice the last accepted one.
    pub(super) fn interval<M: AeroStructure>(
        &mut self,
        target: f64,
        lin: &mut Linearizer<'_, M>,
        nws: &mut NewtonWorkspace,
        stats: &mut FlutterStats,
        branches: &mut [Branch],
        keep_going: &mut dyn FnMut(f64) -> bool,
    ) -> Result<(), FlutterStop> {
        let from = self.u_prev;
        let mut substeps = 0;
        let mut h_next = target - self.u_prev;
        while self.u_prev < target {
            if substeps == MAX_SUBSTEPS {
                return Err(FlutterStop::BranchLost {
                    branch: None,
                    from,
                    speed: target,
                    substeps,
                });
            }
            let h = h_next.min(target - self.u_prev);
            let interval = (from, target, substeps);
            let (u, next) = self.step(interval, h, lin, nws, stats, branches, keep_going)?;
            substeps += 1;
            h_next = 2.0 * (u - self.u_prev);
            self.slope = Some(
                next.iter()
                    .zip(&self.current)
                    .map(|(a, b)| (a.0 - b.0) / (u - self.u_prev))
                    .collect(),
            );
            self.current = next;
            self.u_prev = u;
            self.history.push((u, self.current.clone()));
            keep_going(u / self.u_max);
        }
        Ok(())
    }

    /// One accepted sub-step of the interval `(from, target, substeps so far)`, first tried
    /// with the speed step `h` and halved down to the smallest step while a trial fails; at the
    /// smallest step a trial whose branches all converged is accepted, marked uncertain.
    #[allow(clippy::too_many_arguments)]
    fn step<M: AeroStructure>(
        &mut self,
        (from, target, substeps): (f64, f64, usize),
        mut h: f64,
        lin: &mut Linearizer<'_, M>,
        nws: &mut NewtonWorkspace,
        stats: &mut FlutterStats,
        branches: &mut [Branch],
        keep_going: &mut dyn FnMut(f64) -> bool,
    ) -> Result<Step, FlutterStop> {
        loop {
            if !keep_going(self.u_prev / self.u_max) {
                return Err(FlutterStop::Cancelled { speed: self.u_prev });
            }
            // The whole remainder lands on the plan's speed exactly.
            let u = if h == target - self.u_prev {
                target
            } else {
                self.u_prev + h
            };
            stats.trials += 1;
            let linearization = match lin.at(u, stats) {
                Ok(l) => l,
                Err(error) => {
                    if h > self.h_min {
                        h *= 0.5;
                        stats.halvings += 1;
                        continue;
                    }
                    return Err(FlutterStop::Equilibrium { speed: u, error });
                }
            };
            let trial = self.trial(&linearization, h, nws, stats);
            if trial.ok {
                self.merged_run = 0;
                return Ok((u, trial.next));
            }
            if h > self.h_min {
                h *= 0.5;
                stats.halvings += 1;
                continue;
            }
            let lost = |b| FlutterStop::BranchLost {
                branch: Some(b),
                from,
                speed: u,
                substeps,
            };
            if let Some(b) = trial.lost {
                return Err(lost(b));
            }
            // Accepted at the smallest step: a coalescence is passed in a step or two; two
            // branches that stay on one root have lost one of them.
            if let Some(b) = trial.merged {
                self.merged_run += 1;
                if self.merged_run > MAX_MERGED_STEPS {
                    return Err(lost(b));
                }
            } else {
                self.merged_run = 0;
            }
            for br in branches.iter_mut() {
                br.uncertain = true;
            }
            return Ok((u, trial.next));
        }
    }

    /// Solve every branch at the speed step `h` ahead, from the secant predictor, and check
    /// their shapes (MAC) and that no two met.
    fn trial(
        &self,
        lin: &Linearization,
        h: f64,
        nws: &mut NewtonWorkspace,
        stats: &mut FlutterStats,
    ) -> Trial {
        let mut next = Vec::with_capacity(self.current.len());
        let mut ok = true;
        let mut lost = None;
        for (b, (s, v)) in self.current.iter().enumerate() {
            let pred = *s + self.slope.as_ref().map_or(C64::new(0.0, 0.0), |d| d[b] * h);
            match solve_branch(lin, pred, v, self.method, TRACK_TOLERANCE, 12, nws) {
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
        Trial {
            next,
            ok,
            lost,
            merged,
        }
    }
}

/// Every sign change of `Re s` between two accepted steps after the plan's first speed,
/// refined to the plan's tolerance, into `out.crossings` (sorted by speed). `keep_going` is
/// asked before each refinement; a refusal stops the search ([`FlutterStop::Cancelled`]).
pub(super) fn find_crossings<M: AeroStructure>(
    tracker: &Tracker,
    plan: &FlutterOptions,
    lin: &mut Linearizer<'_, M>,
    nws: &mut NewtonWorkspace,
    stats: &mut FlutterStats,
    out: &mut FlutterSolution,
    keep_going: &mut dyn FnMut(f64) -> bool,
) {
    let first = plan.speeds[0];
    let (u_prev, u_max) = (tracker.u_prev, tracker.u_max);
    'crossings: for w in tracker.history.windows(2) {
        let ((ua, sa), (ub, sb)) = (&w[0], &w[1]);
        if *ub <= first {
            continue;
        }
        for b in 0..sa.len() {
            let (ra, rb) = (sa[b].0.re, sb[b].0.re);
            if (ra < 0.0) == (rb < 0.0) {
                continue;
            }
            if ra.abs() <= NEUTRAL * sa[b].0.norm() && rb.abs() <= NEUTRAL * sb[b].0.norm() {
                continue;
            }
            if !keep_going(u_prev / u_max) {
                out.stopped
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
                &mut |u| lin.at(u, stats),
                tracker.method,
                nws,
            );
            out.crossings.push(Crossing {
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
    out.crossings.sort_by(|a, b| a.speed.total_cmp(&b.speed));
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

/// One eigenpair near `(s, v)`: Newton on the model's rational eigenproblem, or on the p-k
/// problem (Theodorsen's `C` at the branch's own frequency; `linear.rs`). A p-k root that the
/// classical p-k iteration would be repelled from (`EigenPair::pk_contraction` ≥ 1: where a
/// heavily damped branch also has an overdamped root with `C(0)`, Newton can reach that one
/// from a coarse predictor) is not taken: the classical iteration then finds the root from
/// `(s, v)` ([`pk_fixed_point`]), as before the Newton iteration existed.
fn solve_branch(
    lin: &Linearization,
    s: C64,
    v: &DVector<C64>,
    method: FlutterMethod,
    tol: f64,
    max_iterations: usize,
    ws: &mut NewtonWorkspace,
) -> Option<EigenPair> {
    match method {
        FlutterMethod::Eigenvalues => lin.newton(s, v, Transfer::Model, tol, max_iterations, ws),
        FlutterMethod::PkTheodorsen => {
            let how = Transfer::Theodorsen;
            match lin.newton(s, v, how, tol, max_iterations, ws) {
                Some(p) if p.pk_contraction >= 1.0 => {
                    let mut classical = pk_fixed_point(lin, s, v, tol, max_iterations, ws);
                    if let Some(c) = classical.as_mut() {
                        c.iterations += p.iterations;
                    }
                    classical
                }
                // Converged, or failed: the tracker then halves its speed step.
                newton => newton,
            }
        }
    }
}

/// The classical p-k iteration (Hodges & Pierce §5.4): Newton with `C(k)` frozen at the current
/// frequency, then the frequency updated, until it stops moving; it converges linearly, to the
/// roots whose [`EigenPair::pk_contraction`] is below 1.
fn pk_fixed_point(
    lin: &Linearization,
    s: C64,
    v: &DVector<C64>,
    tol: f64,
    max_iterations: usize,
    ws: &mut NewtonWorkspace,
) -> Option<EigenPair> {
    let (mut s, mut v) = (s, v.clone());
    let mut iterations = 0;
    for _ in 0..50 {
        let omega = s.im.abs();
        let how = Transfer::TheodorsenAt { omega };
        let p = lin.newton(s, &v, how, tol, max_iterations, ws)?;
        iterations += p.iterations;
        let moved = (p.s.im.abs() - omega).abs();
        s = p.s;
        v = p.v;
        if moved <= tol * s.norm().max(1e-3) {
            return Some(EigenPair {
                s,
                v,
                iterations,
                pk_contraction: 0.0,
            });
        }
    }
    None
}

/// The `count` lowest wet modes of the linearization at `U = 0`: `(iω_k, φ_k)`, from the
/// symmetric part of `K̃` and `M` (exact when the other loads are conservative; Newton then
/// refines the seeds with the damping and any non-symmetric load).
pub(super) fn wet_modes(lin: &Linearization, count: usize) -> Vec<(C64, DVector<C64>)> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::aero::Aerodynamics;
    use crate::solve::aeroelastic::equations::tests::test_wing;
    use crate::solve::Damping;

    /// The p-k Newton iteration in `(Re s, Im s)` against the classical p-k iteration (freeze
    /// `C`, solve, update the frequency; an independent way to the same fixed point) on a tapered
    /// wing (two chords: several lag rates, so several `C(k_i)`), its 4 lowest branches marched
    /// from the wet modes in 1 m/s steps to 30 m/s, each speed started from the last: both reach
    /// the same root to 1e-9 relative (each stops at 1e-11 on its own step), Newton in at most 6
    /// iterations (quadratic from a start 1 m/s away) and at a root the classical iteration
    /// converges to (`pk_contraction` < 1).
    #[test]
    fn pk_newton_reaches_the_fixed_point_of_the_classical_iteration() {
        let wing = test_wing(6, Aerodynamics::Peters { states: 4 });
        let loads = wing.full().apply(&[], "loads").unwrap();
        let flight = |u: f64| FlightHistory::steady(FlightCondition::at_speed(u));
        let mut eqs =
            AeroelasticEquations::new(&wing, &loads, vec![], flight(0.0), &Damping::None, "aero")
                .unwrap();
        let n = wing.structure().n_dofs();
        let x = vec![0.0; n];
        let mut lin_at = |u: f64| {
            eqs.set_flight(flight(u));
            let a = eqs.steady_states(0.0, &x);
            eqs.linearize(&x, &a)
        };
        let mut ws = NewtonWorkspace::new(n);
        let mut branches = wet_modes(&lin_at(0.0), 4);
        let (mut worst, mut most, mut classical_most) = (0.0f64, 0, 0);
        for k in 1..=30 {
            let lin = lin_at(k as f64);
            for (b, (s, v)) in branches.iter_mut().enumerate() {
                let newton = lin
                    .newton(*s, v, Transfer::Theodorsen, 1e-11, 12, &mut ws)
                    .unwrap_or_else(|| panic!("U = {k}, branch {b}: Newton failed"));
                let classical = pk_fixed_point(&lin, *s, v, 1e-11, 12, &mut ws)
                    .unwrap_or_else(|| panic!("U = {k}, branch {b}: classical failed"));
                let d = (newton.s - classical.s).norm() / classical.s.norm();
                worst = worst.max(d);
                most = most.max(newton.iterations);
                classical_most = classical_most.max(classical.iterations);
                assert!(
                    d < 1e-9,
                    "U = {k}, branch {b}: {} vs {}",
                    newton.s,
                    classical.s
                );
                assert!(newton.iterations <= 6, "U = {k}, branch {b}: {newton:?}");
                assert!(newton.pk_contraction < 1.0, "U = {k}, branch {b}");
                (*s, *v) = (newton.s, newton.v);
            }
        }
        eprintln!(
            "largest difference {worst:.1e}; most iterations: Newton {most}, classical \
             {classical_most}"
        );
    }
}
