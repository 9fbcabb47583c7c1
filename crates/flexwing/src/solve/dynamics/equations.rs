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
//!
//! This file holds the equations' data, their construction, states, tolerances and energies;
//! the right-hand side and the dense Jacobian are in `ode.rs`, the chain's Newton solves in
//! `newton_systems.rs`.

use nalgebra::{DMatrix, DVector};

use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use super::ode::DenseBuffers;
use super::{Gyroscopic, NewtonSystems, TimeFunction, CHAIN_NEWTON_MIN_DOFS};
use crate::error::InputError;
use crate::model::{AppliedLoads, StructuralModel};
use crate::solve::damping::{Damping, DampingOperator};
use crate::solve::energy_audit::{AuditLimits, EnergyBalance};
use crate::solve::eom_newton::ChainNewton;

/// The equations of motion of a model under time-varying loads, as a first-order system for the
/// integrators. Evaluations allocate nothing.
pub struct EquationsOfMotion<'a, M: StructuralModel> {
    pub(super) model: &'a M,
    pub(super) loads: &'a AppliedLoads,
    pub(super) time_functions: Vec<TimeFunction>,
    pub(super) gyroscopic: Gyroscopic,
    /// `K`: diagonal (the full model), block diagonal (the 3-D chain, 3×3 per joint) or dense,
    /// so that `K x` is O(n) for the first two.
    pub(super) k: Stiffness,
    /// `v ↦ C v` (`damping.rs`): O(n) or O(n r) for the full model, never forming `C`.
    pub(super) c: DampingOperator<M>,
    /// `C ẋ`, written by every right-hand side.
    pub(super) c_xdot: Vec<f64>,
    pub(super) damping: Damping,
    pub(super) ws: M::Workspace,
    pub(super) n: usize,
    pub(super) scales: Vec<f64>,
    pub(super) xdot: Vec<f64>,
    pub(super) gamma: Vec<f64>,
    pub(super) force: DVector<f64>,
    pub(super) x_shift: Vec<f64>,
    pub(super) fd_velocity: Vec<f64>,
    /// Buffers of the dense Jacobian, allocated on its first evaluation.
    pub(super) dense: Option<DenseBuffers>,
    pub(super) newton: NewtonSystems,
    pub(super) chain: Option<ChainNewton>,
    /// The 3-D chain's O(n) Newton solves (`model::chain3d::newton`), built on first use.
    pub(super) chain3d: Option<crate::model::chain3d::Newton3d>,
    /// Where [`NewtonSystems::Auto`] switches to the chain (coordinates).
    pub(super) auto_chain_min_dofs: usize,
    /// `state_atol(1.0)`, computed once (O(n²) for the full model).
    pub(super) unit_atol: Option<Vec<f64>>,
    /// The energy audit, if on: its limits and what it found since the last [`Self::state`].
    pub(super) audit: Option<EnergyBalance>,
    /// A flag that, once set, stops the integration after the next accepted step.
    pub(super) halt: Option<Arc<AtomicBool>>,
    /// `(∂Q/∂x)ᵀ ẋ` at the chain's last linearization, for the audit's quadrature step
    /// (`ode.rs`); empty without the audit or on the dense path.
    pub(super) load_rate: Vec<f64>,
    /// Scratch of the quadrature step.
    pub(super) load_rate_scratch: Vec<f64>,
    /// `Q` and `C ẋ` of the right-hand sides kept for Radau's stages
    /// (`OdeSystem::keep_quadrature_point`, `ode.rs`).
    pub(super) quadrature_points: [Vec<f64>; 3],
    /// `C δẋ` of a quadrature step's second-order term (`ode.rs`).
    pub(super) c_step: Vec<f64>,
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
        // The full model's K is diagonal, the 3-D chain's block diagonal: never form them (n²
        // entries at large n).
        let k = match (model.as_full_model(), model.stiffness_blocks()) {
            (Some(full), _) => Stiffness::Diagonal(full.stiffness().to_vec()),
            (None, Some(blocks)) => Stiffness::Blocks(blocks),
            (None, None) => {
                let k = model.stiffness_matrix();
                let diagonal = (0..n).all(|j| (0..n).all(|i| i == j || k[(i, j)] == 0.0));
                match diagonal {
                    true => Stiffness::Diagonal(k.diagonal().as_slice().to_vec()),
                    false => Stiffness::Dense(k),
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
            chain3d: None,
            auto_chain_min_dofs: CHAIN_NEWTON_MIN_DOFS,
            unit_atol: None,
            audit: None,
            halt: None,
            load_rate: Vec::new(),
            load_rate_scratch: Vec::new(),
            quadrature_points: Default::default(),
            c_step: Vec::new(),
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
        if choice == NewtonSystems::Chain
            && self.model.as_full_model().is_none()
            && self.model.as_chain3d().is_none()
        {
            return Err(InputError::new(
                "newton_systems",
                "the chain solves need the full model or the 3-D chain; a reduced model has \
                 dense Newton systems",
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
        self.chain3d = None;
        Ok(())
    }

    /// Whether the Newton systems are solved by chain sweeps (the resolved choice).
    pub fn uses_chain_newton(&self) -> bool {
        // The chain sweeps do not carry the fluid's inertia (`model::aero::fluid`): on a wet
        // model they would solve another system, and Newton would fail (a wet Patil wing at
        // 16 coordinates stopped with "step size too small"), so a wet model stays dense.
        // The 3-D chain's solves apply the exact operator through the model's own recursions
        // (the fluid's inertia included) and need no such restriction.
        (self
            .model
            .as_full_model()
            .is_some_and(|full| !full.has_fluid_inertia())
            || self.model.as_chain3d().is_some())
            && match self.newton {
                NewtonSystems::Auto if self.model.as_chain3d().is_some() => {
                    self.n >= super::CHAIN3D_NEWTON_MIN_DOFS
                }
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
            .map(|k| self.k.entry(k) * (atol * unit[k]).powi(2))
            .sum()
    }

    /// `state_atol(1.0)`, computed on first use and kept.
    pub(super) fn unit_atol(&mut self) -> Vec<f64> {
        if self.unit_atol.is_none() {
            self.unit_atol = Some(self.state_atol(1.0));
        }
        self.unit_atol.clone().unwrap_or_default()
    }

    /// The 3-D chain's Newton solves so far: (solves, GMRES iterations, unconverged solves);
    /// `None` if the dense path or another model's ran.
    pub fn chain3d_newton_counts(&self) -> Option<(usize, usize, usize)> {
        self.chain3d
            .as_ref()
            .map(|c| (c.solves, c.iterations, c.unconverged))
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
            let stiffness = self.k.entry(k);
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
        (kinetic, self.strain_energy(x))
    }

    /// The strain energy `½ xᵀ K x` of the coordinates `x` (J).
    pub fn strain_energy(&self, x: &[f64]) -> f64 {
        0.5 * (0..self.n)
            .map(|i| x[i] * self.k.row_dot(i, x))
            .sum::<f64>()
    }

    /// `ẋ = M(x)⁻¹ p` into `self.xdot` (NaN if `M(x)` is not positive definite); false if
    /// it is not. No allocation.
    pub(super) fn solve_velocities(&mut self, x: &[f64], p: &[f64]) -> bool {
        let ok = self
            .model
            .velocities_into(x, p, &mut self.ws, &mut self.xdot);
        if !ok {
            self.xdot.fill(f64::NAN);
        }
        ok
    }

    pub(super) fn update_scales(&mut self, t: f64) {
        for (s, f) in self.scales.iter_mut().zip(&self.time_functions) {
            *s = f.at(t);
        }
    }

    /// `γ` by central differences of `H_T(x) = ½ pᵀ M(x)⁻¹ p` at fixed `p`: `γ = −∂H_T/∂x`.
    /// Each of the `2 n` energies costs one velocity solve.
    pub(super) fn gyroscopic_fd(&mut self, x: &[f64], p: &[f64], h: f64) {
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

/// The stiffness `K` of the equations of motion in the form that keeps `K x` cheapest.
pub(crate) enum Stiffness {
    /// Diagonal (the full model).
    Diagonal(Vec<f64>),
    /// Block diagonal, 3×3 per joint, row-major (the 3-D chain).
    Blocks(Vec<[[f64; 3]; 3]>),
    /// Dense (a reduced model).
    Dense(DMatrix<f64>),
}

impl Stiffness {
    /// `K_kk`.
    pub(crate) fn entry(&self, k: usize) -> f64 {
        match self {
            Self::Diagonal(d) => d[k],
            Self::Blocks(b) => b[k / 3][k % 3][k % 3],
            Self::Dense(m) => m[(k, k)],
        }
    }

    /// `(K x)_i`: O(1) for the diagonal and block forms.
    pub(crate) fn row_dot(&self, i: usize, x: &[f64]) -> f64 {
        match self {
            Self::Diagonal(d) => d[i] * x[i],
            Self::Blocks(b) => {
                let j = i / 3;
                let row = &b[j][i % 3];
                row[0] * x[3 * j] + row[1] * x[3 * j + 1] + row[2] * x[3 * j + 2]
            }
            Self::Dense(m) => m.row(i).iter().zip(x).map(|(a, b)| a * b).sum(),
        }
    }

    /// `out −= K` (a square view).
    pub(crate) fn subtract_from(&self, mut out: nalgebra::DMatrixViewMut<'_, f64>) {
        match self {
            Self::Diagonal(d) => {
                for (i, v) in d.iter().enumerate() {
                    out[(i, i)] -= v;
                }
            }
            Self::Blocks(b) => {
                for (j, block) in b.iter().enumerate() {
                    for r in 0..3 {
                        for c in 0..3 {
                            out[(3 * j + r, 3 * j + c)] -= block[r][c];
                        }
                    }
                }
            }
            Self::Dense(m) => out -= m,
        }
    }
}
