//! Equations of motion in Hamiltonian form (model.md, "Equations of motion"), for any
//! [`StructuralModel`]: state `y = (x, p)`,
//!
//! ```text
//! ẋ = M(x)⁻¹ p
//! ṗ = −K x + γ(x, ẋ) − C ẋ + Σ_k f_k(t) Q_k(x)
//! ```
//!
//! with the gyroscopic term `γ` exact, by central differences of `−½ pᵀ M(x)⁻¹ p`, or neglected,
//! an exact Jacobian `∂(ẋ, ṗ)/∂(x, p)` for the implicit integrators, and for the full model O(n)
//! solves of their Newton systems with the Jacobian's structural part (`eom_newton.rs`).

use nalgebra::{Complex, DMatrix, DVector};

use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

pub use super::damping::Damping;
use super::damping::DampingOperator;
use super::energy_audit::{AuditLimits, EnergyBalance};
use super::eom_newton::ChainNewton;
use super::integrate::{IntegratorSettings, Method, NewtonSolver, OdeSystem};
use crate::error::InputError;
use crate::model::{AppliedLoads, StructuralModel};
use crate::text::short;

/// From this many coordinates on, [`NewtonSystems::Auto`] solves the full model's Newton systems
/// by O(n) chain sweeps instead of dense LU factorizations of the exact Jacobian (measured on
/// case (b), docs/performance.md, "O(n) Newton systems"), unless [`integrate`] says which method
/// will run ([`chain_newton_min_dofs`]).
///
/// [`integrate`]: super::integrate::integrate
pub const CHAIN_NEWTON_MIN_DOFS: usize = 40;

/// The number of coordinates from which [`NewtonSystems::Auto`] takes the chain sweeps, for the
/// method and settings [`super::integrate::integrate`] runs with. The dense path factors the
/// exact Jacobian and reuses it over steps; the chain relinearizes at every step, O(n). Measured
/// crossovers (case (b), Table 4 beam, best of 3; docs/performance.md, "O(n) Newton systems"):
///
/// * Radau without a step cap: the step size changes from step to step, the dense LU pair is
///   refactored often, and the chain is faster from 16 coordinates (n = 16: 2.0 against 3.3 ms
///   at rtol 1e-3, 1.5 against 2.2 ms at rtol 1e-2; equal at 10).
/// * A fixed step (midpoint rule, generalized-α): one dense factorization serves many steps;
///   dense is faster up to 80 coordinates (gen-α h = 1/3000 s: 50 against 68 ms), the chain at
///   160 (134 against 148 ms): from 120.
/// * Otherwise (Radau with a step cap, BDF, adaptive midpoint and generalized-α) the crossover
///   lies between 24 and 40: [`CHAIN_NEWTON_MIN_DOFS`].
pub fn chain_newton_min_dofs(method: Method, settings: &IntegratorSettings) -> usize {
    match (method, settings.step, settings.max_step) {
        (Method::Midpoint | Method::GeneralizedAlpha, Some(_), _) => 120,
        (Method::Radau, _, None) => 16,
        _ => CHAIN_NEWTON_MIN_DOFS,
    }
}

/// How the implicit integrators solve the Newton systems `(c I − J) Δ = r` of the equations of
/// motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NewtonSystems {
    /// [`NewtonSystems::Chain`] for the full model in vacuo from [`CHAIN_NEWTON_MIN_DOFS`]
    /// coordinates on ([`chain_newton_min_dofs`] for the method when run by
    /// [`super::integrate::integrate`]), [`NewtonSystems::Dense`] otherwise. The default.
    #[default]
    Auto,
    /// The exact Jacobian, formed (O(n²)) and factored densely (O(n³)).
    Dense,
    /// Full model in vacuo only (not a wet model, whose fluid inertia the sweeps do not carry):
    /// O(n) sweeps along the chain's linearized equations, the exact Jacobian's Newton system
    /// without damping (velocity terms included); damping makes it a simplified Newton
    /// iteration (Rayleigh approximated, modal left out; `eom_newton.rs`). Never forms the
    /// Jacobian.
    Chain,
}

/// How the gyroscopic term `γ = ∂T/∂x|_ẋ = −½ ∂(pᵀ M⁻¹ p)/∂x|_p` is obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gyroscopic {
    /// Exact, in O(n) (the chain recursion of `model::kinetic`).
    Exact,
    /// Central finite differences of `−½ pᵀ M(x)⁻¹ p` with step `step` (paper eq. 17); costs
    /// `2 n_dofs` velocity solves per evaluation.
    FiniteDifference {
        /// Step `h` (rad), e.g. `1e-6`.
        step: f64,
    },
    /// Neglected: the paper's "simplified model" (eq. 18). Energy is then not conserved.
    Neglected,
}

impl Gyroscopic {
    /// The usual step `h` of [`Gyroscopic::FiniteDifference`] (rad), as the paper's eq. 17.
    pub const DEFAULT_STEP: f64 = 1e-6;

    /// Check the finite-difference step; `step_field` is the caller's name for it.
    ///
    /// # Errors
    /// A finite-difference step that is not a finite positive number.
    pub fn validate(&self, step_field: &str) -> Result<(), InputError> {
        match *self {
            Gyroscopic::FiniteDifference { step } if !(step > 0.0 && step.is_finite()) => {
                Err(InputError::new(
                    step_field,
                    format!("must be a finite positive number, got {}", short(step)),
                ))
            }
            _ => Ok(()),
        }
    }
}

/// Time history `f(t)` that scales a load: `Q(t) = f(t) Q₀`.
#[derive(Debug, Clone, PartialEq)]
pub enum TimeFunction {
    /// `f = 1`.
    Constant,
    /// `f = sin(ω t + φ)`.
    Sine {
        /// Circular frequency `ω` (rad/s).
        omega: f64,
        /// Phase `φ` (rad).
        phase: f64,
    },
    /// `f = 0` before `time`, 1 after.
    Step {
        /// Switch time (s).
        time: f64,
    },
    /// `f = 0` before `start`, rising linearly to 1 at `end`, then 1.
    Ramp {
        /// Start of the ramp (s).
        start: f64,
        /// End of the ramp (s), after `start`.
        end: f64,
    },
    /// Piecewise-linear table `(t, value)`; must cover the simulated time.
    Table {
        /// Times (s), strictly increasing.
        t: Vec<f64>,
        /// Values (dimensionless factors).
        value: Vec<f64>,
    },
}

impl TimeFunction {
    /// Value at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        match self {
            TimeFunction::Constant => 1.0,
            TimeFunction::Sine { omega, phase } => (omega * t + phase).sin(),
            TimeFunction::Step { time } => {
                if t >= *time {
                    1.0
                } else {
                    0.0
                }
            }
            TimeFunction::Ramp { start, end } => ((t - start) / (end - start)).clamp(0.0, 1.0),
            TimeFunction::Table { t: ts, value } => {
                let last = ts.len() - 1;
                if t <= ts[0] {
                    return value[0];
                }
                if t >= ts[last] {
                    return value[last];
                }
                let k = ts.partition_point(|&s| s <= t);
                let w = (t - ts[k - 1]) / (ts[k] - ts[k - 1]);
                value[k - 1] + w * (value[k] - value[k - 1])
            }
        }
    }

    /// Check the function for a simulation over `[t0, t1]`; `field` names it in errors.
    pub fn validate(&self, field: &str, t0: f64, t1: f64) -> Result<(), InputError> {
        let finite = |name: &str, v: f64| {
            if v.is_finite() {
                crate::magnitude::check(&format!("{field}.{name}"), "", v).map(|_| ())
            } else {
                Err(InputError::new(
                    format!("{field}.{name}"),
                    format!("must be finite, got {v}"),
                ))
            }
        };
        match self {
            TimeFunction::Constant => Ok(()),
            TimeFunction::Sine { omega, phase } => {
                finite("omega", *omega)?;
                finite("phase", *phase)
            }
            TimeFunction::Step { time } => finite("time", *time),
            TimeFunction::Ramp { start, end } => {
                finite("start", *start)?;
                finite("end", *end)?;
                if end > start {
                    Ok(())
                } else {
                    Err(InputError::new(
                        format!("{field}.end"),
                        format!("must be after start ({start} s), got {end} s"),
                    ))
                }
            }
            TimeFunction::Table { t, value } => {
                if t.len() != value.len() || t.len() < 2 {
                    return Err(InputError::new(
                        field,
                        format!("table needs at least two (t, value) pairs of equal length, got {} and {}", t.len(), value.len()),
                    ));
                }
                for k in 0..t.len() {
                    finite(&format!("t[{k}]"), t[k])?;
                    finite(&format!("value[{k}]"), value[k])?;
                    if k > 0 && t[k] <= t[k - 1] {
                        return Err(InputError::new(
                            format!("{field}.t"),
                            format!(
                                "must be strictly increasing, but t[{k}] = {} <= t[{}] = {}",
                                t[k],
                                k - 1,
                                t[k - 1]
                            ),
                        ));
                    }
                }
                if t[0] > t0 || t[t.len() - 1] < t1 {
                    return Err(InputError::new(
                        format!("{field}.t"),
                        format!(
                            "table covers [{}, {}] s but the simulation runs over [{t0}, {t1}] s",
                            t[0],
                            t[t.len() - 1]
                        ),
                    ));
                }
                Ok(())
            }
        }
    }
}

/// The equations of motion of a model under time-varying loads, as a first-order system for the
/// integrators. Evaluations allocate nothing.
pub struct EquationsOfMotion<'a, M: StructuralModel> {
    model: &'a M,
    loads: &'a AppliedLoads,
    time_functions: Vec<TimeFunction>,
    gyroscopic: Gyroscopic,
    /// `K`, dense, when it is not diagonal (empty otherwise).
    k: DMatrix<f64>,
    /// The diagonal of `K` when `K` is diagonal (the full model): `K x` in O(n).
    k_diag: Option<Vec<f64>>,
    /// `v ↦ C v` (`damping.rs`): O(n) or O(n r) for the full model, never forming `C`.
    c: DampingOperator<M>,
    /// `C ẋ`, written by every right-hand side.
    c_xdot: Vec<f64>,
    damping: Damping,
    ws: M::Workspace,
    n: usize,
    scales: Vec<f64>,
    xdot: Vec<f64>,
    gamma: Vec<f64>,
    force: DVector<f64>,
    x_shift: Vec<f64>,
    fd_velocity: Vec<f64>,
    /// Buffers of the dense Jacobian, allocated on its first evaluation.
    dense: Option<DenseBuffers>,
    newton: NewtonSystems,
    chain: Option<ChainNewton>,
    /// Where [`NewtonSystems::Auto`] switches to the chain (coordinates).
    auto_chain_min_dofs: usize,
    /// `state_atol(1.0)`, computed once (O(n²) for the full model).
    unit_atol: Option<Vec<f64>>,
    /// The energy audit, if on: its limits and what it found since the last [`Self::state`].
    audit: Option<EnergyBalance>,
    /// A flag that, once set, stops the integration after the next accepted step.
    halt: Option<Arc<AtomicBool>>,
    /// The shifts of the chain factorizations' slots (real, complex), for the audit's
    /// quadrature states.
    shifts: (Vec<f64>, Vec<Complex<f64>>),
    /// Right-hand-side evaluations.
    pub rhs_evaluations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
}

impl<'a, M: StructuralModel> EquationsOfMotion<'a, M> {
    /// Equations of `model` under `loads`, load `k` scaled by `time_functions[k]`.
    ///
    /// # Errors
    /// If the number of time functions differs from the number of loads (field `loads`), a
    /// finite-difference step is not positive (field `gyroscopic.step`), damping coefficients
    /// are not finite and non-negative (fields `damping.*`, [`Damping::validate`]), or modal
    /// damping asks for modes that cannot be computed or that double precision does not resolve
    /// (fields `damping`, `damping.ratios`).
    pub fn new(
        model: &'a M,
        loads: &'a AppliedLoads,
        time_functions: Vec<TimeFunction>,
        gyroscopic: Gyroscopic,
        damping: &Damping,
    ) -> Result<Self, InputError> {
        if time_functions.len() != loads.n_loads() {
            return Err(InputError::new(
                "loads",
                format!(
                    "{} loads but {} time functions",
                    loads.n_loads(),
                    time_functions.len()
                ),
            ));
        }
        gyroscopic.validate("gyroscopic.step")?;
        let n = model.n_dofs();
        let ws = model.workspace();
        let c = DampingOperator::new(model, damping, "damping")?;
        // The full model's K is diagonal: never form it (n² entries at large n).
        let (k, k_diag) = match model.as_full_model() {
            Some(full) => (DMatrix::zeros(0, 0), Some(full.stiffness().to_vec())),
            None => {
                let k = model.stiffness_matrix();
                let diagonal = (0..n).all(|j| (0..n).all(|i| i == j || k[(i, j)] == 0.0));
                match diagonal {
                    true => (DMatrix::zeros(0, 0), Some(k.diagonal().as_slice().to_vec())),
                    false => (k, None),
                }
            }
        };
        Ok(Self {
            model,
            loads,
            scales: vec![0.0; time_functions.len()],
            time_functions,
            gyroscopic,
            k,
            k_diag,
            c,
            c_xdot: vec![0.0; n],
            damping: damping.clone(),
            ws,
            n,
            x_shift: vec![0.0; n],
            fd_velocity: vec![0.0; n],
            xdot: vec![0.0; n],
            gamma: vec![0.0; n],
            force: DVector::zeros(n),
            dense: None,
            newton: NewtonSystems::Auto,
            chain: None,
            auto_chain_min_dofs: CHAIN_NEWTON_MIN_DOFS,
            unit_atol: None,
            audit: None,
            halt: None,
            shifts: (Vec::new(), Vec::new()),
            rhs_evaluations: 0,
            jacobian_evaluations: 0,
        })
    }

    /// Choose how the implicit integrators solve the Newton systems (default
    /// [`NewtonSystems::Auto`]).
    ///
    /// # Errors
    /// [`NewtonSystems::Chain`] for a model other than the full model, or for a wet one (with
    /// the fluid's inertia, which the chain sweeps do not carry) (field `newton_systems`).
    pub fn set_newton_systems(&mut self, choice: NewtonSystems) -> Result<(), InputError> {
        if choice == NewtonSystems::Chain && self.model.as_full_model().is_none() {
            return Err(InputError::new(
                "newton_systems",
                "the chain solves need the full model; a reduced model has dense Newton systems",
            ));
        }
        if choice == NewtonSystems::Chain
            && self
                .model
                .as_full_model()
                .is_some_and(|full| full.has_fluid_inertia())
        {
            return Err(InputError::new(
                "newton_systems",
                "the chain solves do not carry the fluid's inertia; a wet model has dense Newton \
                 systems",
            ));
        }
        self.newton = choice;
        self.chain = None;
        Ok(())
    }

    /// Whether the Newton systems are solved by chain sweeps (the resolved choice).
    pub fn uses_chain_newton(&self) -> bool {
        // The chain sweeps do not carry the fluid's inertia (`model::aero::fluid`): on a wet
        // model they would solve another system, and Newton would fail (a wet Patil wing at
        // 16 coordinates stopped with "step size too small"), so a wet model stays dense.
        self.model
            .as_full_model()
            .is_some_and(|full| !full.has_fluid_inertia())
            && match self.newton {
                NewtonSystems::Auto => self.n >= self.auto_chain_min_dofs,
                NewtonSystems::Dense => false,
                NewtonSystems::Chain => true,
            }
    }

    /// The same equations with the energy audit on (module [`super::energy_audit`]): the state
    /// gets two more components, the work of the loads `W` and the dissipated energy `D`
    /// (quadrature states, left out of the error control), and the balance
    /// `H − H(0) − W + D` is checked after every accepted step; a run whose energy gain exceeds
    /// `limits.runaway` is stopped ([`crate::SolveError::Halted`]). The audit runs from the
    /// state last built by [`Self::state`]; [`Self::energy_balance`] says what it found.
    pub fn with_energy_audit(mut self, limits: AuditLimits) -> Self {
        self.set_energy_audit(Some(limits));
        self
    }

    /// Switch the energy audit on with `limits`, or off ([`Self::with_energy_audit`]); the
    /// state's size changes with it.
    pub fn set_energy_audit(&mut self, limits: Option<AuditLimits>) {
        self.audit = limits.map(|l| EnergyBalance::start(l, 0.0));
    }

    /// The same equations, stopped after the next accepted step once `flag` is set (by another
    /// thread, a signal handler or a progress callback): the integrator returns the output so
    /// far with [`crate::SolveError::Halted`].
    pub fn with_halt(mut self, flag: Option<Arc<AtomicBool>>) -> Self {
        self.set_halt(flag);
        self
    }

    /// Set or clear the halt flag ([`Self::with_halt`]).
    pub fn set_halt(&mut self, flag: Option<Arc<AtomicBool>>) {
        self.halt = flag;
    }

    /// What the energy audit found since the last [`Self::state`]; `None` without the audit.
    pub fn energy_balance(&self) -> Option<&EnergyBalance> {
        self.audit.as_ref()
    }

    /// The work of the loads `W` and the dissipated energy `D` (J) carried by an audited state
    /// `y`; `None` without the audit.
    pub fn work_and_dissipation(&self, y: &[f64]) -> Option<(f64, f64)> {
        let n2 = 2 * self.n;
        self.audit.as_ref().map(|_| (y[n2], y[n2 + 1]))
    }

    /// The energy that an error of `atol` (rad) in every coordinate, and the matching error in
    /// every momentum ([`Self::state_atol`]), carries (J): `Σ_k K_kk a_k²`. The energy audit
    /// does not judge energies below it.
    pub fn energy_resolution(&mut self, atol: f64) -> f64 {
        let unit = self.unit_atol();
        let n = self.n;
        (0..n)
            .map(|k| {
                let stiffness = match &self.k_diag {
                    Some(d) => d[k],
                    None => self.k[(k, k)],
                };
                stiffness * (atol * unit[k]).powi(2)
            })
            .sum()
    }

    /// `state_atol(1.0)`, computed on first use and kept.
    fn unit_atol(&mut self) -> Vec<f64> {
        if self.unit_atol.is_none() {
            self.unit_atol = Some(self.state_atol(1.0));
        }
        self.unit_atol.clone().unwrap_or_default()
    }

    /// How the gyroscopic term is obtained.
    pub fn gyroscopic(&self) -> Gyroscopic {
        self.gyroscopic
    }

    /// Number of coordinates `x` (the state has twice as many).
    pub fn n_dofs(&self) -> usize {
        self.n
    }

    /// The model.
    pub fn model(&self) -> &M {
        self.model
    }

    /// The damping matrix `C` (`n_dofs × n_dofs`; `None` without damping), formed once from the
    /// damping operator and kept with the dense Jacobian's buffers: for the linearizations of
    /// small models, O(n²) (`damping.rs`).
    pub(crate) fn damping_matrix(&mut self) -> Option<&DMatrix<f64>> {
        let (model, c, n) = (self.model, &mut self.c, self.n);
        self.dense
            .get_or_insert_with(|| DenseBuffers::new(n, c.matrix(model)))
            .c
            .as_ref()
    }

    /// State `(x, p)` for coordinates `x` and velocities `ẋ`; with the energy audit, followed
    /// by `W = D = 0`, and the audit restarts from it.
    pub fn state(&mut self, x: &[f64], xdot: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        let mut p = vec![0.0; self.n];
        self.model.momentum_into(x, xdot, &mut self.ws, &mut p);
        y.extend(p);
        if let Some(limits) = self.audit.as_ref().map(|a| a.limits) {
            let (kinetic, strain) = self.energies(&y);
            self.audit = Some(EnergyBalance::start(limits, kinetic + strain));
            y.extend([0.0, 0.0]);
        }
        y
    }

    /// Absolute tolerances for the state `(x, p)` from one tolerance `atol` on the joint
    /// rotations (rad), with the same meaning for every model (docs/model-choices.md, "Error
    /// weights in physical units"):
    ///
    /// * coordinate `k`: `atol √(N/r) / ‖∂q/∂x_k‖₂`, with `N` joint rotations `q`, `r`
    ///   coordinates `x`. An error in `x_k` then weighs in the integrators' RMS error norm as
    ///   much as the joint rotations it moves would weigh in the full model's: `atol` itself for
    ///   the full model (`q = x`); for a reduced model, the tolerance of a modal amplitude is
    ///   `atol` over the joint rotations of a unit of its mode.
    /// * momentum `k`: the coordinate's tolerance times `√(K_kk / (M(0)⁻¹)_kk)`, so that an error
    ///   of its size in `p_k` alone carries the kinetic energy `½ (M⁻¹)_kk δp_k²` that an error of
    ///   the coordinate's tolerance in `x_k` alone carries as strain energy `½ K_kk δx_k²` (for
    ///   a reduced model on mass-normalized modes, the modal frequency times the amplitude's
    ///   tolerance; for a coordinate without stiffness, `1 / (M(0)⁻¹)_kk` per second). For the
    ///   full model `(M(0)⁻¹)_kk` comes from [`crate::model::FullModel::inverse_mass_diagonal`] in O(n).
    pub fn state_atol(&mut self, atol: f64) -> Vec<f64> {
        let r = self.n;
        let x0 = vec![0.0; r];
        if let Some(full) = self.model.as_full_model() {
            // q = x: every coordinate gets `atol`; (M(0)⁻¹)_kk by one chain factorization and
            // one forward covariance sweep, O(n).
            let k = full.stiffness();
            let mut v = vec![atol; r];
            match full.inverse_mass_diagonal(&x0, &mut full.workspace()) {
                Some(minv) => v.extend((0..r).map(|i| {
                    if k[i] > 0.0 {
                        atol * (k[i] / minv[i]).sqrt()
                    } else {
                        atol / minv[i]
                    }
                })),
                // A mass matrix that is not positive definite fails every run anyway.
                None => v.extend(std::iter::repeat_n(atol, r)),
            }
            return v;
        }
        let q0 = self.model.full_coordinates(&x0);
        let joints = q0.len();
        let mut unit = x0.clone();
        let mut v: Vec<f64> = (0..r)
            .map(|k| {
                unit[k] = 1.0;
                let q = self.model.full_coordinates(&unit);
                unit[k] = 0.0;
                let norm = q
                    .iter()
                    .zip(&q0)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum::<f64>();
                atol * (joints as f64 / r as f64).sqrt() / norm.sqrt()
            })
            .collect();
        // M(0)⁻¹ by the model's own velocity solve, column by column.
        let identity = DMatrix::identity(r, r);
        let mut minv = DMatrix::zeros(r, r);
        let positive = self
            .model
            .velocities_block_into(&x0, &identity, &mut self.ws, &mut minv);
        for k in 0..r {
            let stiffness = match &self.k_diag {
                Some(d) => d[k],
                None => self.k[(k, k)],
            };
            let inverse_mass = minv[(k, k)];
            let momentum_per_coordinate = match (positive, stiffness > 0.0) {
                (true, true) => (stiffness / inverse_mass).sqrt(),
                (true, false) => 1.0 / inverse_mass,
                // A mass matrix that is not positive definite fails every run anyway.
                (false, _) => 1.0,
            };
            v.push(v[k] * momentum_per_coordinate);
        }
        v
    }

    /// Replace the time history of every load (one function per load, in order): how a caller
    /// that drives the loads itself sets them between integration calls (the Python stepper, a
    /// flight-dynamics or control loop). The functions are not checked against a time span here;
    /// use [`TimeFunction::validate`] for that.
    ///
    /// # Errors
    /// A number of functions other than the number of loads (field `field`).
    pub fn set_time_functions(
        &mut self,
        time_functions: Vec<TimeFunction>,
        field: &str,
    ) -> Result<(), InputError> {
        if time_functions.len() != self.time_functions.len() {
            return Err(InputError::new(
                field,
                format!(
                    "needs one value per load ({}), got {}",
                    self.time_functions.len(),
                    time_functions.len()
                ),
            ));
        }
        self.time_functions = time_functions;
        Ok(())
    }

    /// Number of loads (and of time functions).
    pub fn n_loads(&self) -> usize {
        self.time_functions.len()
    }

    /// Velocities `ẋ = M(x)⁻¹ p` of the state `y`.
    pub fn velocities(&mut self, y: &[f64]) -> Vec<f64> {
        let (x, p) = (&y[..self.n], &y[self.n..2 * self.n]);
        self.solve_velocities(x, p);
        self.xdot.clone()
    }

    /// Energies of the state `y`: (kinetic `½ pᵀ ẋ`, strain `½ xᵀ K x`) (J).
    pub fn energies(&mut self, y: &[f64]) -> (f64, f64) {
        let n = self.n;
        let (x, p) = (&y[..n], &y[n..2 * n]);
        self.solve_velocities(x, p);
        let kinetic = 0.5 * p.iter().zip(&self.xdot).map(|(a, b)| a * b).sum::<f64>();
        let strain = 0.5
            * match &self.k_diag {
                Some(k) => (0..n).map(|i| k[i] * x[i] * x[i]).sum::<f64>(),
                None => {
                    let x = DVector::from_column_slice(x);
                    x.dot(&(&self.k * &x))
                }
            };
        (kinetic, strain)
    }

    /// `ẋ = M(x)⁻¹ p` into `self.xdot` (NaN if `M(x)` is not positive definite); false if
    /// it is not. No allocation.
    fn solve_velocities(&mut self, x: &[f64], p: &[f64]) -> bool {
        let ok = self
            .model
            .velocities_into(x, p, &mut self.ws, &mut self.xdot);
        if !ok {
            self.xdot.fill(f64::NAN);
        }
        ok
    }

    fn update_scales(&mut self, t: f64) {
        for (s, f) in self.scales.iter_mut().zip(&self.time_functions) {
            *s = f.at(t);
        }
    }

    /// `γ` by central differences of `H_T(x) = ½ pᵀ M(x)⁻¹ p` at fixed `p`: `γ = −∂H_T/∂x`.
    /// Each of the `2 n` energies costs one velocity solve.
    fn gyroscopic_fd(&mut self, x: &[f64], p: &[f64], h: f64) {
        let n = self.n;
        self.x_shift.copy_from_slice(x);
        for i in 0..n {
            let mut half_energy = [0.0; 2];
            for (k, sign) in [1.0, -1.0].iter().enumerate() {
                self.x_shift[i] = x[i] + sign * h;
                let v = &mut self.fd_velocity;
                half_energy[k] = if self
                    .model
                    .velocities_into(&self.x_shift, p, &mut self.ws, v)
                {
                    0.5 * p.iter().zip(v.iter()).map(|(a, b)| a * b).sum::<f64>()
                } else {
                    f64::NAN
                };
            }
            self.x_shift[i] = x[i];
            self.gamma[i] = -(half_energy[0] - half_energy[1]) / (2.0 * h);
        }
    }
}

impl<M: StructuralModel> OdeSystem for EquationsOfMotion<'_, M> {
    fn dim(&self) -> usize {
        2 * self.n + if self.audit.is_some() { 2 } else { 0 }
    }

    /// One tolerance on the coordinates (rad) with consistent momenta, as [`Self::state_atol`];
    /// the audit's quadrature states are not error-controlled.
    fn atol_scale(&mut self, scale: &mut [f64]) {
        // `state_atol` is linear in its tolerance: at 1 it gives the scales.
        let n2 = 2 * self.n;
        scale[..n2].copy_from_slice(&self.unit_atol());
        scale[n2..].fill(f64::INFINITY);
    }

    /// The halt flag, then the energy audit's check of the balance at the step's end.
    fn step_accepted(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        if self
            .halt
            .as_ref()
            .is_some_and(|h| h.load(Ordering::Relaxed))
        {
            return ControlFlow::Break(());
        }
        if self.audit.is_none() {
            return ControlFlow::Continue(());
        }
        let (kinetic, strain) = self.energies(y);
        let n2 = 2 * self.n;
        match &mut self.audit {
            Some(audit) => audit.check(t, kinetic + strain, y[n2], y[n2 + 1]),
            None => ControlFlow::Continue(()),
        }
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_evaluations += 1;
        let n = self.n;
        let (x, p) = (&y[..n], &y[n..2 * n]);
        self.solve_velocities(x, p);
        self.update_scales(t);
        self.model.generalized_forces_into(
            x,
            self.loads,
            &self.scales,
            &mut self.ws,
            &mut self.force,
        );
        match self.gyroscopic {
            Gyroscopic::Exact => {
                self.model
                    .gyroscopic_into(x, &self.xdot, &mut self.ws, &mut self.gamma)
            }
            Gyroscopic::FiniteDifference { step } => self.gyroscopic_fd(x, p, step),
            Gyroscopic::Neglected => self.gamma.fill(0.0),
        }
        let (dx, rest) = dy.split_at_mut(n);
        let (dp, quadrature) = rest.split_at_mut(n);
        dx.copy_from_slice(&self.xdot);
        // C ẋ by the damping operator (zeros without damping).
        self.c.apply(self.model, &self.xdot, &mut self.c_xdot);
        // The audit's rates: power of the loads ẋ·Q and of the damping ẋᵀ C ẋ.
        let (mut power, mut dissipation) = (0.0, 0.0);
        for i in 0..n {
            let mut v = self.force[i] + self.gamma[i] - self.c_xdot[i];
            power += self.xdot[i] * self.force[i];
            dissipation += self.xdot[i] * self.c_xdot[i];
            match &self.k_diag {
                Some(k) => v -= k[i] * x[i],
                None => {
                    for j in 0..n {
                        v -= self.k[(i, j)] * x[j];
                    }
                }
            }
            dp[i] = v;
        }
        if let [w, d] = quadrature {
            *w = power;
            *d = dissipation;
        }
    }

    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        // With B = ∂(M ẋ)/∂x|_ẋ:  ∂ẋ/∂x = −M⁻¹ B,  ∂ẋ/∂p = M⁻¹,
        // ∂ṗ/∂x = −K + ∂Q/∂x + G_x + (Bᵀ − C) ∂ẋ/∂x,  ∂ṗ/∂p = (Bᵀ − C) M⁻¹,
        // G_x = ∂γ/∂x|_ẋ, and ∂γ/∂ẋ = Bᵀ. Without γ (simplified model) Bᵀ and G_x drop out.
        // With the finite-difference γ the exact γ's derivatives are used (Newton needs only an
        // approximate Jacobian).
        self.jacobian_evaluations += 1;
        let n = self.n;
        let (x, p) = (&y[..n], &y[n..2 * n]);
        if self.audit.is_some() {
            // The quadrature states feed back into nothing, and their own rows are left zero:
            // a simplified Newton that is exact for them once the other stages converge.
            let n2 = 2 * n;
            jac.rows_mut(n2, 2).fill(0.0);
            jac.columns_mut(n2, 2).fill(0.0);
        }
        self.update_scales(t);
        if !self.solve_velocities(x, p) {
            jac.fill(f64::NAN);
            return;
        }
        let (model, c) = (self.model, &mut self.c);
        let d = self
            .dense
            .get_or_insert_with(|| DenseBuffers::new(n, c.matrix(model)));
        let with_gamma = !matches!(self.gyroscopic, Gyroscopic::Neglected);
        // ∂ẋ/∂x = −M⁻¹ B and dγ/dx|_p = G_x + Bᵀ ∂ẋ/∂x: O(n²) for the full model (dual numbers
        // through the O(n) velocity solve), a few dense products for the reduced one.
        self.model.hamiltonian_derivatives_into(
            x,
            p,
            &mut self.ws,
            with_gamma,
            &mut d.dxdx,
            &mut d.dgamma,
        );
        self.model
            .load_jacobian_into(x, self.loads, &self.scales, &mut self.ws, &mut d.load_jac);
        // M⁻¹ by one factorization and one O(n) velocity solve per column.
        self.model
            .velocities_block_into(x, &d.identity, &mut self.ws, &mut d.minv);
        jac.view_mut((0, 0), (n, n)).copy_from(&d.dxdx);
        jac.view_mut((0, n), (n, n)).copy_from(&d.minv);
        let mut dpdx = jac.view_mut((n, 0), (n, n));
        dpdx.copy_from(&d.load_jac);
        match &self.k_diag {
            Some(k) => {
                for i in 0..n {
                    dpdx[(i, i)] -= k[i];
                }
            }
            None => dpdx -= &self.k,
        }
        if with_gamma {
            dpdx += &d.dgamma;
        }
        if let Some(c) = &d.c {
            dpdx.gemm(-1.0, c, &d.dxdx, 1.0);
        }
        // ∂ṗ/∂p = (Bᵀ − C) M⁻¹ with Bᵀ M⁻¹ = (M⁻¹ B)ᵀ = −(∂ẋ/∂x)ᵀ since M is symmetric.
        let mut dpdp = jac.view_mut((n, n), (n, n));
        if matches!(self.gyroscopic, Gyroscopic::Neglected) {
            dpdp.fill(0.0);
        } else {
            dpdp.copy_from(&d.dxdx.transpose());
            dpdp.neg_mut();
        }
        if let Some(c) = &d.c {
            dpdp.gemm(-1.0, c, &d.minv, 1.0);
        }
    }

    fn newton_solver(&mut self) -> Option<&mut dyn NewtonSolver> {
        if !self.uses_chain_newton() {
            return None;
        }
        if self.chain.is_none() {
            let full = self.model.as_full_model()?;
            let gyroscopic = !matches!(self.gyroscopic, Gyroscopic::Neglected);
            self.chain = Some(ChainNewton::new(full, &self.damping, gyroscopic));
        }
        Some(self)
    }

    fn integrating_with(&mut self, method: Method, settings: &IntegratorSettings) {
        self.auto_chain_min_dofs = chain_newton_min_dofs(method, settings);
    }
}

/// Buffers of the dense Jacobian (`n_dofs × n_dofs` each), and the damping matrix it needs.
struct DenseBuffers {
    /// `C`, formed once from the damping operator; `None` without damping.
    c: Option<DMatrix<f64>>,
    dgamma: DMatrix<f64>,
    load_jac: DMatrix<f64>,
    identity: DMatrix<f64>,
    minv: DMatrix<f64>,
    dxdx: DMatrix<f64>,
}

impl DenseBuffers {
    fn new(n: usize, c: Option<DMatrix<f64>>) -> Self {
        let z = || DMatrix::zeros(n, n);
        Self {
            c,
            dgamma: z(),
            load_jac: z(),
            identity: DMatrix::identity(n, n),
            minv: z(),
            dxdx: z(),
        }
    }
}

/// The full model's O(n) Newton solves (`eom_newton.rs`); reached only through
/// [`OdeSystem::newton_solver`], which offers them when [`EquationsOfMotion::uses_chain_newton`].
impl<M: StructuralModel> NewtonSolver for EquationsOfMotion<'_, M> {
    fn linearize(&mut self, t: f64, y: &[f64]) -> bool {
        let model = self.model;
        let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) else {
            return false;
        };
        self.jacobian_evaluations += 1;
        for (s, f) in self.scales.iter_mut().zip(&self.time_functions) {
            *s = f.at(t);
        }
        chain.linearize(full, self.loads, &self.scales, &y[..2 * self.n])
    }

    fn factor_real(&mut self, slot: usize, c: f64) -> bool {
        let model = self.model;
        match (model.as_full_model(), self.chain.as_mut()) {
            (Some(full), Some(chain)) => {
                set_slot(&mut self.shifts.0, slot, c);
                chain.factor_real(full, slot, c)
            }
            _ => false,
        }
    }

    fn factor_complex(&mut self, slot: usize, c: Complex<f64>) -> bool {
        let model = self.model;
        match (model.as_full_model(), self.chain.as_mut()) {
            (Some(full), Some(chain)) => {
                set_slot(&mut self.shifts.1, slot, c);
                chain.factor_complex(full, slot, c)
            }
            _ => false,
        }
    }

    fn solve_real(&mut self, slot: usize, b: &mut [f64]) {
        let model = self.model;
        let n2 = 2 * self.n;
        if let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) {
            chain.solve_real(full, slot, &mut b[..n2]);
        }
        // The audit's quadrature states: zero rows of the Jacobian, so `c Δ = r`.
        let c = self.shifts.0.get(slot).copied().unwrap_or(1.0);
        for v in &mut b[n2..] {
            *v /= c;
        }
    }

    fn solve_complex(&mut self, slot: usize, re: &mut [f64], im: &mut [f64]) {
        let model = self.model;
        let n2 = 2 * self.n;
        if let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) {
            chain.solve_complex(full, slot, &mut re[..n2], &mut im[..n2]);
        }
        let c = self
            .shifts
            .1
            .get(slot)
            .copied()
            .unwrap_or(Complex::new(1.0, 0.0));
        for (r, i) in re[n2..].iter_mut().zip(&mut im[n2..]) {
            let v = Complex::new(*r, *i) / c;
            (*r, *i) = (v.re, v.im);
        }
    }

    /// A linearization and its sweeps cost a few right-hand sides.
    fn cheap_linearization(&self) -> bool {
        true
    }

    /// The joint momenta's error scale is set by the root's (`p_1` is the angular momentum of
    /// the whole beam), so a Newton error small in it can be a large velocity error of the
    /// outboard elements, which, left in the state, grows through the gyroscopic term until
    /// Newton fails (docs/model-choices.md, "O(n) Newton systems"). The bound keeps that error
    /// in proportion, `1e5 · M_nn(0)/M_11(0)` (the tip joint's inertia over the root's, ~n⁻³:
    /// no bound below a few hundred elements); the constant is measured on case (b) with Radau
    /// at rtol 1e-2 (n = 1000 needs ≤ 1e-3, n = 3000 ≤ 1e-5). The chain's Newton iteration is
    /// exact, so each iteration divides the error by ~1e9 and the bound costs at most one.
    fn newton_tolerance(&self) -> Option<f64> {
        self.chain.as_ref().map(|c| c.newton_tolerance())
    }
}

/// `slots[slot] = value`, growing `slots` as needed.
fn set_slot<T: Copy + Default>(slots: &mut Vec<T>, slot: usize, value: T) {
    if slots.len() <= slot {
        slots.resize(slot + 1, T::default());
    }
    slots[slot] = value;
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::{Force, FullModel, Load, ReducedModel};
    use crate::solve::Modes;

    fn model(torsion: bool) -> FullModel {
        let section = SectionProperties {
            ei: Profile::Uniform(10.0),
            mass_per_length: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![0.6, 0.2],
            },
            torsion: torsion.then_some(TorsionProperties {
                gj: Profile::Uniform(3.0),
                polar_inertia: Profile::Uniform(0.01),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.1),
            }),
        };
        FullModel::new(
            Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(6),
                Calibration::TipLoad,
            )
            .unwrap(),
        )
    }

    /// The analytic Jacobian against central differences of the right-hand side (step 1e-6,
    /// truncation ~1e-12 relative, round-off ~1e-10 relative: tolerance 1e-6 relative).
    fn check_jacobian<M: StructuralModel>(model: &M, gyroscopic: Gyroscopic, damping: &Damping) {
        let full = model.full_model();
        let loads = full
            .apply(
                &[
                    Load::PointForce {
                        span: 2.0,
                        force: Force::Follower {
                            tangential: 0.5,
                            normal: 2.0,
                        },
                    },
                    Load::Gravity { g: 9.81 },
                ],
                "loads",
            )
            .unwrap();
        let tf = vec![TimeFunction::Constant, TimeFunction::Constant];
        let mut eom = EquationsOfMotion::new(model, &loads, tf, gyroscopic, damping).unwrap();
        let nd = model.n_dofs();
        let x: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
        let xd: Vec<f64> = (0..nd).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
        let y = eom.state(&x, &xd);
        let mut jac = DMatrix::zeros(2 * nd, 2 * nd);
        eom.jacobian(0.0, &y, &mut jac);
        let h = 1e-6;
        let (mut fp, mut fm) = (vec![0.0; 2 * nd], vec![0.0; 2 * nd]);
        let scale = jac.amax();
        for c in 0..2 * nd {
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            eom.rhs(0.0, &yp, &mut fp);
            eom.rhs(0.0, &ym, &mut fm);
            for r in 0..2 * nd {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                assert!(
                    (fd - jac[(r, c)]).abs() <= 1e-6 * scale,
                    "{gyroscopic:?} ({r}, {c}): {fd} vs {}",
                    jac[(r, c)]
                );
            }
        }
    }

    #[test]
    fn state_atol_means_a_joint_rotation_for_every_model() {
        let atol = 1e-6;
        for torsion in [false, true] {
            let full = model(torsion);
            let none = full.apply(&[], "loads").unwrap();
            let nq = full.n_dofs();
            let mut eom =
                EquationsOfMotion::new(&full, &none, vec![], Gyroscopic::Exact, &Damping::None)
                    .unwrap();
            let a = eom.state_atol(atol);
            let k = full.stiffness_matrix();
            let mut m0 = DMatrix::zeros(nq, nq);
            full.mass_matrix_into(&vec![0.0; nq], &mut full.workspace(), &mut m0);
            let m0_inverse = m0.try_inverse().unwrap();
            for i in 0..nq {
                // Full model: atol on each joint rotation; on each momentum the error that
                // carries the energy ½ K_ii atol², √(K_ii / (M⁻¹)_ii) atol, with M⁻¹ here from
                // the dense closed-form mass matrix (the library uses its chain solve): to the
                // conditioning of M(0) (κ ≈ 1e7 at n = 6 with torsion).
                assert_eq!(a[i], atol);
                let p = atol * (k[(i, i)] / m0_inverse[(i, i)]).sqrt();
                assert!(
                    (a[nq + i] - p).abs() <= 1e-8 * p,
                    "{i}: {} vs {p}",
                    a[nq + i]
                );
            }
            let modes = Modes::undeformed(&full).unwrap();
            for r in [1, 3] {
                let rom = ReducedModel::first(&full, modes.shapes(), r).unwrap();
                let mut eom =
                    EquationsOfMotion::new(&rom, &none, vec![], Gyroscopic::Exact, &Damping::None)
                        .unwrap();
                let a = eom.state_atol(atol);
                for c in 0..r {
                    // An error of a_c in mode c moves the joints by Φ_c a_c; the full model's RMS
                    // norm of that (over its nq joints, each weighed by atol) equals the reduced
                    // model's RMS norm of the single error a_c over its r coordinates, 1/√r.
                    let phi = rom.basis().column(c);
                    let full_norm = (phi.iter().map(|v| (v * a[c] / atol).powi(2)).sum::<f64>()
                        / nq as f64)
                        .sqrt();
                    let expected = 1.0 / (r as f64).sqrt();
                    assert!(
                        (full_norm - expected).abs() < 1e-12,
                        "{full_norm} vs {expected}"
                    );
                    // Mass-normalized modes: K_r = diag(ω²), M_r(0) = I, so the momentum
                    // tolerance is ω_c a_c (to the accuracy of the eigen-decomposition).
                    let p = modes.omega()[c] * a[c];
                    assert!((a[r + c] - p).abs() < 1e-8 * p, "{c}: {} vs {p}", a[r + c]);
                }
            }
        }
    }

    #[test]
    fn jacobian_agrees_with_finite_differences_of_the_right_hand_side() {
        let rayleigh = Damping::Rayleigh {
            alpha: 0.3,
            beta: 0.01,
        };
        for torsion in [false, true] {
            let full = model(torsion);
            for damping in [&Damping::None, &rayleigh] {
                check_jacobian(&full, Gyroscopic::Exact, damping);
                check_jacobian(&full, Gyroscopic::Neglected, damping);
            }
            let modes = Modes::undeformed(&full).unwrap();
            let rom = ReducedModel::first(&full, modes.shapes(), 3).unwrap();
            check_jacobian(&rom, Gyroscopic::Exact, &rayleigh);
            check_jacobian(&rom, Gyroscopic::Neglected, &Damping::None);
        }
    }
}
