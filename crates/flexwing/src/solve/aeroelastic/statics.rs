//! Static aeroelastic equilibrium, sweeps in speed and the divergence speed
//! (docs/aeroelastic-model.md §5).
//!
//! At rest the steady aerodynamic load is exactly `q_∞ Q̂(x)`: the angle of attack depends on the
//! direction of the free stream only. So the aerodynamics is one more load of the static solver
//! (`solve::statics`: Newton with the exact tangent, load stepping with cut-back) whose scale is
//! the dynamic pressure, and a sweep in `U` is a sweep in that scale. The model seen by the static
//! solver is [`SteadyAeroModel`], the structure with the aerodynamic load appended to its loads.
//!
//! Divergence: at an equilibrium `x*` the frozen-state divergence pressure `μ(x*)` is the smallest
//! positive `μ` with `K − ∂Q_o/∂x − μ ∂Q̂/∂x` singular (`1/λ` for the largest positive real
//! eigenvalue `λ` of `(K − ∂Q_o/∂x)⁻¹ ∂Q̂/∂x`); the wing diverges where `μ(x*(q)) = q`. About the
//! undeformed state (zero root angle, no gravity) `μ` is the linear divergence pressure itself.

use nalgebra::{DMatrix, DVector};

use super::evaluator::{AeroDerivatives, AeroEvaluator};
use crate::error::{InputError, SolveError};
use crate::model::aero::{AeroStructure, Aerodynamics, Aeroelastic, FlightCondition};
use crate::model::{AppliedLoads, Load, StructuralModel};
use crate::solve::{continue_static_to_instability, StaticOptions, StaticStats};

/// A static aeroelastic sweep, validated: speeds in increasing order, the root angle, gravity and
/// other (dead, follower…) loads.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroStaticOptions {
    /// Free-stream speeds (m/s), strictly increasing, non-negative.
    pub speeds: Vec<f64>,
    /// Root angle of attack (rad).
    pub root_angle: f64,
    /// Gravity (m/s²), or none.
    pub gravity: Option<f64>,
    /// Other loads, at full value at every speed.
    pub loads: Vec<Load>,
    /// Static solver options.
    pub options: StaticOptions,
    /// Refine the divergence speed to this relative tolerance on the dynamic pressure (e.g.
    /// 1e-6) when the sweep brackets it.
    pub divergence_tolerance: f64,
}

impl AeroStaticOptions {
    /// Check the plan; `field` prefixes the error fields.
    pub fn validate(&self, field: &str) -> Result<(), InputError> {
        if self.speeds.is_empty() {
            return Err(InputError::new(
                format!("{field}.speeds"),
                "needs at least one speed",
            ));
        }
        for (i, &u) in self.speeds.iter().enumerate() {
            if !(u.is_finite() && u >= 0.0) || (i > 0 && u <= self.speeds[i - 1]) {
                return Err(InputError::new(
                    format!("{field}.speeds[{i}]"),
                    format!(
                        "speeds must be finite, non-negative and strictly increasing, got {}",
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
        if !(self.divergence_tolerance > 0.0 && self.divergence_tolerance < 1.0) {
            return Err(InputError::new(
                format!("{field}.divergence_tolerance"),
                format!(
                    "must be in (0, 1), got {}",
                    crate::text::short(self.divergence_tolerance)
                ),
            ));
        }
        self.options.validate(&format!("{field}.options"))
    }
}

/// One static aeroelastic equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroEquilibrium {
    /// Free-stream speed (m/s).
    pub speed: f64,
    /// Dynamic pressure `½ρU²` (Pa).
    pub dynamic_pressure: f64,
    /// Model coordinates.
    pub x: Vec<f64>,
    /// Joint rotations of the full model.
    pub q: Vec<f64>,
    /// Tip displacement of the elastic axis `(dx, dy, dz)` (m; `dz`, chordwise toward the
    /// leading edge, is 0 on the planar chain).
    pub tip: [f64; 3],
    /// Tip twist (rad, nose-up).
    pub tip_twist: f64,
    /// Total aerodynamic force along the ground's vertical (N): the sum of `strip_lift`.
    pub lift: f64,
    /// Each strip's aerodynamic force along the ground's vertical (N), in the order of the
    /// strips (root to tip).
    pub strip_lift: Vec<f64>,
    /// Root bending moment, the clamp spring's moment `K_θ,1 q_1` (N·m).
    pub root_bending_moment: f64,
    /// Hinge moment of each control surface (N·m, positive trailing edge down), in the order of
    /// [`Aeroelastic::surfaces`].
    pub hinge_moments: Vec<f64>,
    /// Divergence pressure of the frozen state `μ(x*)` (Pa), `None` if no real mode diverges.
    pub divergence_pressure: Option<f64>,
    /// Solver counters.
    pub stats: StaticStats,
}

/// Where the wing diverges.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Divergence {
    /// Divergence speed (m/s).
    pub speed: f64,
    /// Divergence dynamic pressure (Pa).
    pub dynamic_pressure: f64,
    /// How it was found.
    pub basis: DivergenceBasis,
    /// Whether the speed lies within the speeds the sweep attempted (its first to its last, or
    /// to the one where it stopped: past the divergence speed the static solver fails). A
    /// [`DivergenceBasis::Undeformed`] speed may lie beyond them: no equilibrium was computed
    /// there, so it holds only as far as the wing stays undeformed (no root angle, gravity or
    /// other load, and a symmetric section: then exactly).
    pub within_sweep: bool,
}

/// How a divergence speed was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DivergenceBasis {
    /// `μ(x*(q)) − q` changes sign between two speeds of the sweep: refined between them.
    Bracketed,
    /// Every equilibrium of the sweep is undeformed and has the same divergence pressure: the
    /// linear divergence pressure of the undeformed wing `μ(0)`, wherever it lies.
    Undeformed,
}

/// What a static aeroelastic sweep produced.
#[derive(Debug, Clone, PartialEq)]
pub struct AeroStaticSolution {
    /// The equilibria, one per speed reached.
    pub points: Vec<AeroEquilibrium>,
    /// The divergence speed: where `μ(x*(q)) = q` between two points of the sweep, refined; or,
    /// for a sweep whose equilibria do not move the divergence pressure (the undeformed wing),
    /// `μ` itself, flagged when it lies outside the sweep ([`Divergence::within_sweep`]). `None`
    /// if no real mode diverges, or the crossing lies beyond the sweep and the divergence
    /// pressure still changes with the state.
    pub divergence: Option<Divergence>,
    /// The sweep stopped at this speed index with this error (partial output kept above).
    pub stopped: Option<(usize, SolveError)>,
    /// The caller's poll asked the sweep to stop before the speed after the last point.
    pub interrupted: bool,
}

/// The structure with the steady aerodynamic load appended to its loads, for the static solver:
/// `Q(x; s) = Q_o(x; s_o) + s_last Q̂(x)`, the last scale being the dynamic pressure (Pa).
pub struct SteadyAeroModel<'a, M: AeroStructure> {
    aero: &'a Aeroelastic<M>,
    root_angle: f64,
}

/// Workspace of [`SteadyAeroModel`].
pub struct SteadyAeroWorkspace<'a, M: AeroStructure> {
    inner: M::Workspace,
    eval: AeroEvaluator<'a, M>,
    force: Vec<f64>,
    zeros: Vec<f64>,
    derivatives: AeroDerivatives,
    /// The last frozen-state divergence pressure and the state it is of: a sweep whose
    /// equilibrium does not move with the speed (Newton returns the start unchanged) asks for
    /// the same state at every speed.
    divergence_cache: Option<(Vec<f64>, Option<f64>)>,
}

impl<'a, M: AeroStructure> SteadyAeroModel<'a, M> {
    /// The steady aerodynamics of `aero` (its model must be [`Aerodynamics::Steady`]) at root
    /// angle `root_angle`.
    pub(crate) fn new(aero: &'a Aeroelastic<M>, root_angle: f64) -> Self {
        assert_eq!(aero.aerodynamics(), Aerodynamics::Steady);
        Self { aero, root_angle }
    }

    /// Aerodynamic load per unit dynamic pressure `Q̂(x)` into `out`.
    fn unit_load(&self, x: &[f64], ws: &mut SteadyAeroWorkspace<'a, M>, out: &mut [f64]) {
        ws.eval.evaluate(x, &ws.zeros, &[], out, false, &mut []);
    }
}

impl<'a, M: AeroStructure> StructuralModel for SteadyAeroModel<'a, M> {
    type Workspace = SteadyAeroWorkspace<'a, M>;

    fn workspace(&self) -> Self::Workspace {
        let n = self.n_dofs();
        let mut eval = AeroEvaluator::new(self.aero);
        // Unit dynamic pressure: V = √(2/ρ).
        eval.set_air((2.0 / self.aero.density()).sqrt(), self.root_angle, |_| 0.0);
        SteadyAeroWorkspace {
            inner: self.aero.structure().workspace(),
            eval,
            force: vec![0.0; n],
            zeros: vec![0.0; n],
            derivatives: AeroDerivatives::zeros(n, self.aero.n_strips()),
            divergence_cache: None,
        }
    }
    fn n_dofs(&self) -> usize {
        self.aero.structure().n_dofs()
    }
    fn stiffness_matrix(&self) -> DMatrix<f64> {
        self.aero.structure().stiffness_matrix()
    }
    fn mass_matrix_into(&self, x: &[f64], ws: &mut Self::Workspace, out: &mut DMatrix<f64>) {
        self.aero
            .structure()
            .mass_matrix_into(x, &mut ws.inner, out)
    }
    fn generalized_forces_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Self::Workspace,
        out: &mut DVector<f64>,
    ) {
        let k = loads.n_loads();
        self.aero
            .structure()
            .generalized_forces_into(x, loads, &scales[..k], &mut ws.inner, out);
        let mut f = std::mem::take(&mut ws.force);
        self.unit_load(x, ws, &mut f);
        for (o, v) in out.iter_mut().zip(&f) {
            *o += scales[k] * v;
        }
        ws.force = f;
    }
    fn load_jacobian_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Self::Workspace,
        out: &mut DMatrix<f64>,
    ) {
        let k = loads.n_loads();
        self.aero
            .structure()
            .load_jacobian_into(x, loads, &scales[..k], &mut ws.inner, out);
        let mut f = std::mem::take(&mut ws.force);
        self.unit_load(x, ws, &mut f);
        ws.force = f;
        ws.eval.derivatives(&mut ws.derivatives);
        let d = &ws.derivatives;
        *out += (&d.qx + &d.g * &d.wx) * scales[k];
    }
    fn momentum_into(&self, x: &[f64], xdot: &[f64], ws: &mut Self::Workspace, out: &mut [f64]) {
        self.aero
            .structure()
            .momentum_into(x, xdot, &mut ws.inner, out)
    }
    /// The steady aerodynamic load (the last scale) is not conservative: its moment follows the
    /// twist, so the tangent is not symmetric once the dynamic pressure is non-zero.
    fn loads_are_conservative(&self, loads: &AppliedLoads, scales: &[f64]) -> bool {
        let k = loads.n_loads();
        scales[k] == 0.0
            && self
                .aero
                .structure()
                .loads_are_conservative(loads, &scales[..k])
    }
    fn velocities_into(
        &self,
        x: &[f64],
        p: &[f64],
        ws: &mut Self::Workspace,
        out: &mut [f64],
    ) -> bool {
        self.aero
            .structure()
            .velocities_into(x, p, &mut ws.inner, out)
    }
    fn gyroscopic_into(&self, x: &[f64], xdot: &[f64], ws: &mut Self::Workspace, out: &mut [f64]) {
        self.aero
            .structure()
            .gyroscopic_into(x, xdot, &mut ws.inner, out)
    }
    fn kinetic_derivatives_into(
        &self,
        x: &[f64],
        xdot: &[f64],
        ws: &mut Self::Workspace,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        self.aero
            .structure()
            .kinetic_derivatives_into(x, xdot, &mut ws.inner, dp, dgamma)
    }
    fn full_coordinates(&self, x: &[f64]) -> Vec<f64> {
        self.aero.structure().full_coordinates(x)
    }
    fn element_rotations(&self, dx: &[f64]) -> Vec<f64> {
        self.aero.structure().element_rotations(dx)
    }
}

/// Static aeroelastic equilibria of `aero` (its aerodynamic model is replaced by the steady one)
/// along `plan.speeds`, each continued from the previous one with load stepping in dynamic
/// pressure, the divergence pressure of each state, and the divergence speed. `progress` is
/// called with the fraction of the sweep done.
///
/// # Errors
/// An invalid plan or loads (`field` prefixes the fields). A solver failure is not an error: the
/// outcome keeps the equilibria found and says where and why the sweep stopped.
pub fn static_sweep<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &AeroStaticOptions,
    field: &str,
    progress: &mut dyn FnMut(f64),
) -> Result<AeroStaticSolution, InputError> {
    static_sweep_polled(aero, plan, field, &mut |f| {
        progress(f);
        true
    })
}

/// [`static_sweep`] with a poll: `step(fraction)` is called before each speed with the fraction
/// done (and with 1 at the end); when it returns `false` the sweep stops there, keeping the
/// points computed (`interrupted` in the outcome).
pub fn static_sweep_polled<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    plan: &AeroStaticOptions,
    field: &str,
    step: &mut dyn FnMut(f64) -> bool,
) -> Result<AeroStaticSolution, InputError> {
    plan.validate(field)?;
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut loads = plan.loads.clone();
    if let Some(g) = plan.gravity {
        loads.push(Load::Gravity {
            g: g * plan.root_angle.cos(),
        });
    }
    let applied = aero.apply(&loads, &format!("{field}.loads"))?;
    let model = SteadyAeroModel::new(&steady, plan.root_angle);
    let mut ws = model.workspace();
    let k = applied.n_loads();
    let rho = aero.density();
    let pressure = |u: f64| 0.5 * rho * u * u;
    let scales_at = |q: f64| {
        let mut s = vec![1.0; k];
        s.push(q);
        s
    };
    let mut points: Vec<AeroEquilibrium> = Vec::with_capacity(plan.speeds.len());
    let mut stopped = None;
    let n = model.n_dofs();
    let mut state = (vec![0.0; n], vec![0.0; k + 1]);
    let mut interrupted = false;
    for (i, &u) in plan.speeds.iter().enumerate() {
        if !step(i as f64 / plan.speeds.len() as f64) {
            interrupted = true;
            break;
        }
        let target = scales_at(pressure(u));
        match continue_static_to_instability(
            &model,
            &applied,
            (&state.0, &state.1),
            &target,
            &plan.options,
        ) {
            Ok(sol) => {
                let point = equilibrium_point(
                    &model,
                    &applied,
                    &mut ws,
                    u,
                    pressure(u),
                    &sol.x,
                    sol.stats,
                    plan.root_angle,
                );
                state = (sol.x, sol.scales);
                points.push(point);
            }
            Err(e) => {
                stopped = Some((i, e));
                break;
            }
        }
    }
    if !interrupted {
        step(1.0);
    }
    let divergence = find_divergence(&model, &applied, &mut ws, &points, plan, rho).or_else(|| {
        let failed = stopped.as_ref().map(|(i, _)| *i)?;
        divergence_at_the_stop(&model, &applied, &mut ws, &points, failed, plan, rho)
    });
    Ok(AeroStaticSolution {
        points,
        divergence,
        stopped,
        interrupted,
    })
}

/// The equilibrium's outputs at `x`.
#[allow(clippy::too_many_arguments)]
fn equilibrium_point<'a, M: AeroStructure>(
    model: &SteadyAeroModel<'a, M>,
    loads: &AppliedLoads,
    ws: &mut SteadyAeroWorkspace<'a, M>,
    speed: f64,
    pressure: f64,
    x: &[f64],
    stats: StaticStats,
    root_angle: f64,
) -> AeroEquilibrium {
    let chain = model.aero.chain();
    let q = model.full_coordinates(x);
    let (tip, tip_twist) = chain.tip(&q);
    let mut f = vec![0.0; x.len()];
    model.unit_load(x, ws, &mut f);
    let (sa, ca) = root_angle.sin_cos();
    let strip_lift: Vec<f64> = ws
        .eval
        .sc
        .force
        .iter()
        .zip(&model.aero.strips)
        .map(|(f, s)| s.width * (ca * f[1] + sa * f[2]) * pressure)
        .collect();
    let lift = strip_lift.iter().sum();
    let hinge_moments = ws
        .eval
        .hinge_moments()
        .iter()
        .map(|h| h * pressure)
        .collect();
    let divergence_pressure = frozen_divergence_pressure(model, loads, ws, x);
    AeroEquilibrium {
        speed,
        dynamic_pressure: pressure,
        x: x.to_vec(),
        tip,
        tip_twist,
        lift,
        strip_lift,
        root_bending_moment: chain.root_bending_moment(&q),
        hinge_moments,
        q,
        divergence_pressure,
        stats,
    }
}

/// `μ(x)`: `1/λ` for the largest positive real eigenvalue `λ` of `(K − ∂Q_o/∂x)⁻¹ ∂Q̂/∂x`
/// (the loads at their full value: one sweep's, so that the state alone decides, and the last
/// state's value is kept in `ws`).
fn frozen_divergence_pressure<'a, M: AeroStructure>(
    model: &SteadyAeroModel<'a, M>,
    loads: &AppliedLoads,
    ws: &mut SteadyAeroWorkspace<'a, M>,
    x: &[f64],
) -> Option<f64> {
    if let Some((at, mu)) = &ws.divergence_cache {
        if at.as_slice() == x {
            return *mu;
        }
    }
    let mu = frozen_divergence_pressure_at(model, loads, ws, x);
    ws.divergence_cache = Some((x.to_vec(), mu));
    mu
}

fn frozen_divergence_pressure_at<'a, M: AeroStructure>(
    model: &SteadyAeroModel<'a, M>,
    loads: &AppliedLoads,
    ws: &mut SteadyAeroWorkspace<'a, M>,
    x: &[f64],
) -> Option<f64> {
    let n = model.n_dofs();
    let k = loads.n_loads();
    let mut jo = DMatrix::zeros(n, n);
    model
        .aero
        .structure()
        .load_jacobian_into(x, loads, &vec![1.0; k], &mut ws.inner, &mut jo);
    let k0 = model.stiffness_matrix() - jo;
    let mut f = vec![0.0; n];
    model.unit_load(x, ws, &mut f);
    ws.eval.derivatives(&mut ws.derivatives);
    let d = &ws.derivatives;
    let ja = &d.qx + &d.g * &d.wx;
    let b = k0.lu().solve(&ja)?;
    let scale = b.amax();
    let eig = b.complex_eigenvalues();
    eig.iter()
        .filter(|l| l.re > 1e-12 * scale && l.im.abs() <= 1e-9 * l.re.abs().max(scale * 1e-12))
        .map(|l| l.re)
        .fold(None, |m: Option<f64>, v| Some(m.map_or(v, |m| m.max(v))))
        .map(|l| 1.0 / l)
}

/// The divergence speed from the sweep: the first interval where `μ − q` changes sign, refined
/// by the secant method on `μ(x*(q)) − q` with static solves continued from its left end.
fn find_divergence<'a, M: AeroStructure>(
    model: &SteadyAeroModel<'a, M>,
    loads: &AppliedLoads,
    ws: &mut SteadyAeroWorkspace<'a, M>,
    points: &[AeroEquilibrium],
    plan: &AeroStaticOptions,
    rho: f64,
) -> Option<Divergence> {
    let speed = |q: f64| (2.0 * q / rho).sqrt();
    let first = points.first()?;
    // A divergence pressure that does not move along the sweep (undeformed wing) is exact.
    let mus: Vec<Option<f64>> = points.iter().map(|p| p.divergence_pressure).collect();
    if let Some(mu0) = mus[0] {
        if mus
            .iter()
            .all(|m| m.is_some_and(|m| (m - mu0).abs() <= 1e-9 * mu0))
            && points.iter().all(|p| p.x.iter().all(|v| v.abs() < 1e-12))
        {
            // The last speed attempted: the last one, or the one where the sweep stopped (past
            // the divergence speed the static solver fails).
            let last = plan.speeds[points.len().min(plan.speeds.len() - 1)];
            let last_q = 0.5 * rho * last * last;
            return Some(Divergence {
                speed: speed(mu0),
                dynamic_pressure: mu0,
                basis: DivergenceBasis::Undeformed,
                within_sweep: (first.dynamic_pressure..=last_q).contains(&mu0),
            });
        }
    }
    let k = loads.n_loads();
    for w in points.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let (Some(ma), Some(mb)) = (a.divergence_pressure, b.divergence_pressure) else {
            continue;
        };
        let (fa, fb) = (ma - a.dynamic_pressure, mb - b.dynamic_pressure);
        if fa > 0.0 && fb <= 0.0 {
            // Secant (regula falsi, Illinois) on f(q) = μ(x*(q)) − q in [q_a, q_b].
            let (mut qa, mut qb, mut ga, mut gb) = (a.dynamic_pressure, b.dynamic_pressure, fa, fb);
            let mut qm = qa;
            for _ in 0..60 {
                qm = qb - gb * (qb - qa) / (gb - ga);
                let mut s = vec![1.0; k];
                s.push(qm);
                let mut s0 = vec![1.0; k];
                s0.push(a.dynamic_pressure);
                let Ok(sol) =
                    continue_static_to_instability(model, loads, (&a.x, &s0), &s, &plan.options)
                else {
                    break;
                };
                let Some(mu) = frozen_divergence_pressure(model, loads, ws, &sol.x) else {
                    break;
                };
                let g = mu - qm;
                if (qb - qa).abs() <= plan.divergence_tolerance * qm
                    || g.abs() <= plan.divergence_tolerance * qm
                {
                    break;
                }
                if g > 0.0 {
                    qa = qm;
                    ga = g;
                    gb *= 0.5;
                } else {
                    qb = qm;
                    gb = g;
                    ga *= 0.5;
                }
            }
            return Some(Divergence {
                speed: speed(qm),
                dynamic_pressure: qm,
                basis: DivergenceBasis::Bracketed,
                within_sweep: true,
            });
        }
    }
    None
}

/// The divergence speed of a sweep that stopped at speed index `failed` (the static solver found
/// no stable equilibrium there, past the divergence) after a last equilibrium with `μ − q > 0`:
/// the load where `μ(x*(q)) = q` between the two, approached from the stable side. Each trial
/// aims just below the root predicted by the secant through the last two stable equilibria on
/// `g(q) = μ(x*(q)) − q` (slope −1 from one: a frozen `μ`), and a trial without a stable
/// equilibrium closes the bracket from above (bisection when the prediction leaves it). The
/// divergence is reported once `g` at a stable equilibrium is within the tolerance, as the
/// secant's root from there; `None` when the bracket closes with `g` still large (the solver
/// failed for another reason than divergence).
fn divergence_at_the_stop<'a, M: AeroStructure>(
    model: &SteadyAeroModel<'a, M>,
    loads: &AppliedLoads,
    ws: &mut SteadyAeroWorkspace<'a, M>,
    points: &[AeroEquilibrium],
    failed: usize,
    plan: &AeroStaticOptions,
    rho: f64,
) -> Option<Divergence> {
    let last = points.last()?;
    if failed != points.len() {
        return None;
    }
    let tol = plan.divergence_tolerance;
    let mut g_lo = last.divergence_pressure? - last.dynamic_pressure;
    if !(g_lo > 0.0) {
        return None;
    }
    let k = loads.n_loads();
    let scales = |q: f64| {
        let mut s = vec![1.0; k];
        s.push(q);
        s
    };
    let (mut q_lo, mut x_lo) = (last.dynamic_pressure, last.x.clone());
    let mut hi = 0.5 * rho * plan.speeds[failed].powi(2);
    let mut previous = points.len().checked_sub(2).and_then(|i| {
        Some((
            points[i].dynamic_pressure,
            points[i].divergence_pressure? - points[i].dynamic_pressure,
        ))
    });
    let slope_of = |previous: Option<(f64, f64)>, q_lo: f64, g_lo: f64| {
        previous
            .map(|(q, g)| (g_lo - g) / (q_lo - q))
            .filter(|s| s.is_finite() && *s < 0.0)
            .unwrap_or(-1.0)
    };
    for _ in 0..60 {
        let slope = slope_of(previous, q_lo, g_lo);
        if g_lo <= tol * q_lo {
            let q = q_lo - g_lo / slope;
            return Some(Divergence {
                speed: (2.0 * q / rho).sqrt(),
                dynamic_pressure: q,
                basis: DivergenceBasis::Bracketed,
                within_sweep: true,
            });
        }
        if hi - q_lo <= tol * q_lo {
            break;
        }
        let root = q_lo - g_lo / slope;
        let mut q = root * (1.0 - 0.5 * tol);
        if !(q > q_lo && q < hi) {
            q = 0.5 * (q_lo + hi);
        }
        let r = continue_static_to_instability(
            model,
            loads,
            (&x_lo, &scales(q_lo)),
            &scales(q),
            &plan.options,
        );
        let stable = r.ok().and_then(|sol| {
            let mu = frozen_divergence_pressure(model, loads, ws, &sol.x)?;
            (mu - q > 0.0).then_some((sol.x, mu - q))
        });
        match stable {
            Some((x, g)) => {
                previous = Some((q_lo, g_lo));
                (q_lo, x_lo, g_lo) = (q, x, g);
            }
            None => hi = q,
        }
    }
    // The bracket closed: a divergence only if g vanished with it.
    let slope = slope_of(previous, q_lo, g_lo);
    (g_lo <= 10.0 * tol * q_lo * slope.abs().max(1.0)).then(|| {
        let q = q_lo - g_lo / slope;
        Divergence {
            speed: (2.0 * q / rho).sqrt(),
            dynamic_pressure: q,
            basis: DivergenceBasis::Bracketed,
            within_sweep: true,
        }
    })
}
