//! Equations of motion in Hamiltonian form (model.md, "Equations of motion"), for any
//! [`StructuralModel`]: state `y = (x, p)`,
//!
//! ```text
//! ẋ = M(x)⁻¹ p
//! ṗ = −K x + γ(x, ẋ) − C ẋ + Σ_k f_k(t) Q_k(x)
//! ```
//!
//! with the gyroscopic term `γ` exact, by central differences of `−½ pᵀ M(x)⁻¹ p`, or neglected,
//! and an exact Jacobian `∂(ẋ, ṗ)/∂(x, p)` for the implicit integrators.

use nalgebra::{DMatrix, DVector};

use super::integrate::OdeSystem;
use crate::error::InputError;
use crate::model::{AppliedLoads, StructuralModel};

/// How the gyroscopic term `γ = ∂T/∂x|_ẋ = −½ ∂(pᵀ M⁻¹ p)/∂x|_p` is obtained.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Gyroscopic {
    /// Exact, in O(n) (the chain recursion of `model::kinetic`).
    Exact,
    /// Central finite differences of `−½ pᵀ M(x)⁻¹ p` with step `step` (paper eq. 17); costs
    /// `2 n_dofs` mass-matrix factorizations per evaluation.
    FiniteDifference {
        /// Step `h` (rad), e.g. `1e-6`.
        step: f64,
    },
    /// Neglected: the paper's "simplified model" (eq. 18). Energy is then not conserved.
    Neglected,
}

/// Structural damping `C`.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Damping {
    /// No damping.
    #[default]
    None,
    /// Rayleigh: `C = α M(0) + β K`.
    Rayleigh {
        /// Mass-proportional coefficient `α` (1/s).
        alpha: f64,
        /// Stiffness-proportional coefficient `β` (s).
        beta: f64,
    },
    /// Modal damping ratios `ζ_k` of the first modes about the undeformed state:
    /// `C = M₀ Φ diag(2 ζ_k ω_k) Φᵀ M₀` over the modes given (others undamped).
    Modal {
        /// Damping ratios of modes 1, 2, … (dimensionless).
        ratios: Vec<f64>,
    },
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
                Ok(())
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
    k: DMatrix<f64>,
    c: Option<DMatrix<f64>>,
    ws: M::Workspace,
    n: usize,
    mass: DMatrix<f64>,
    /// Cholesky factor of the last mass matrix (lower triangle), if it was positive definite.
    factor: DMatrix<f64>,
    factored: bool,
    scales: Vec<f64>,
    xdot: Vec<f64>,
    gamma: Vec<f64>,
    force: DVector<f64>,
    dp: DMatrix<f64>,
    dgamma: DMatrix<f64>,
    load_jac: DMatrix<f64>,
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
    /// finite-difference step is not positive, or damping coefficients are not finite and
    /// non-negative (field `damping`).
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
        if let Gyroscopic::FiniteDifference { step } = gyroscopic {
            if !(step > 0.0 && step.is_finite()) {
                return Err(InputError::new(
                    "dynamic.gyroscopic_step",
                    format!("must be a finite positive number, got {step}"),
                ));
            }
        }
        let n = model.n_dofs();
        let mut ws = model.workspace();
        let c = damping_matrix(model, &mut ws, damping)?;
        Ok(Self {
            model,
            loads,
            scales: vec![0.0; time_functions.len()],
            time_functions,
            gyroscopic,
            k: model.stiffness_matrix(),
            c,
            ws,
            n,
            mass: DMatrix::zeros(n, n),
            factor: DMatrix::zeros(n, n),
            factored: false,
            xdot: vec![0.0; n],
            gamma: vec![0.0; n],
            force: DVector::zeros(n),
            dp: DMatrix::zeros(n, n),
            dgamma: DMatrix::zeros(n, n),
            load_jac: DMatrix::zeros(n, n),
            rhs_evaluations: 0,
            jacobian_evaluations: 0,
        })
    }

    /// Number of coordinates `x` (the state has twice as many).
    pub fn n_dofs(&self) -> usize {
        self.n
    }

    /// The model.
    pub fn model(&self) -> &M {
        self.model
    }

    /// State `(x, p)` for coordinates `x` and velocities `ẋ`.
    pub fn state(&mut self, x: &[f64], xdot: &[f64]) -> Vec<f64> {
        let mut y = x.to_vec();
        let mut p = vec![0.0; self.n];
        self.model.momentum_into(x, xdot, &mut self.ws, &mut p);
        y.extend(p);
        y
    }

    /// Absolute tolerances for the state `(x, p)` from one tolerance `atol` on the coordinates
    /// (rad): `atol` for `x`, and `atol · M_ii(0) / (1 s)` for the momenta, so that both halves
    /// of the state are measured in consistent units.
    pub fn state_atol(&mut self, atol: f64) -> Vec<f64> {
        let x0 = vec![0.0; self.n];
        self.model
            .mass_matrix_into(&x0, &mut self.ws, &mut self.mass);
        let mut v = vec![atol; self.n];
        v.extend((0..self.n).map(|i| atol * self.mass[(i, i)]));
        v
    }

    /// Velocities `ẋ = M(x)⁻¹ p` of the state `y`.
    pub fn velocities(&mut self, y: &[f64]) -> Vec<f64> {
        self.factor_mass(&y[..self.n]);
        self.solve_velocities(&y[self.n..]);
        self.xdot.clone()
    }

    /// Energies of the state `y`: (kinetic `½ pᵀ ẋ`, strain `½ xᵀ K x`) (J).
    pub fn energies(&mut self, y: &[f64]) -> (f64, f64) {
        let n = self.n;
        let v = self.velocities(y);
        let kinetic = 0.5 * y[n..].iter().zip(&v).map(|(a, b)| a * b).sum::<f64>();
        let x = DVector::from_column_slice(&y[..n]);
        let strain = 0.5 * x.dot(&(&self.k * &x));
        (kinetic, strain)
    }

    fn factor_mass(&mut self, x: &[f64]) {
        self.model.mass_matrix_into(x, &mut self.ws, &mut self.mass);
        self.factor.copy_from(&self.mass);
        self.factored = cholesky_in_place(&mut self.factor);
    }

    /// `ẋ = M⁻¹ p` into `self.xdot`, with the factor of the last `factor_mass` (no allocation).
    fn solve_velocities(&mut self, p: &[f64]) {
        self.xdot.copy_from_slice(p);
        if self.factored {
            cholesky_solve(&self.factor, &mut self.xdot);
        } else {
            self.xdot.fill(f64::NAN);
        }
    }

    fn update_scales(&mut self, t: f64) {
        for (s, f) in self.scales.iter_mut().zip(&self.time_functions) {
            *s = f.at(t);
        }
    }

    /// `γ` by central differences of `H_T(x) = ½ pᵀ M(x)⁻¹ p` at fixed `p`: `γ = −∂H_T/∂x`.
    fn gyroscopic_fd(&mut self, x: &[f64], p: &[f64], h: f64) {
        let n = self.n;
        let mut xs = x.to_vec();
        let mut v = vec![0.0; n];
        let mut m = DMatrix::zeros(n, n);
        for i in 0..n {
            let mut half_energy = [0.0; 2];
            for (k, sign) in [1.0, -1.0].iter().enumerate() {
                xs[i] = x[i] + sign * h;
                self.model.mass_matrix_into(&xs, &mut self.ws, &mut m);
                half_energy[k] = if cholesky_in_place(&mut m) {
                    v.copy_from_slice(p);
                    cholesky_solve(&m, &mut v);
                    0.5 * p.iter().zip(&v).map(|(a, b)| a * b).sum::<f64>()
                } else {
                    f64::NAN
                };
            }
            xs[i] = x[i];
            self.gamma[i] = -(half_energy[0] - half_energy[1]) / (2.0 * h);
        }
    }
}

/// In-place Cholesky factorization `A = L Lᵀ`: the lower triangle of `a` becomes `L`. Returns
/// false if `a` is not (numerically) positive definite.
fn cholesky_in_place(a: &mut DMatrix<f64>) -> bool {
    let n = a.nrows();
    for j in 0..n {
        let mut d = a[(j, j)];
        for k in 0..j {
            d -= a[(j, k)] * a[(j, k)];
        }
        if !(d > 0.0) {
            return false;
        }
        let d = d.sqrt();
        a[(j, j)] = d;
        for i in j + 1..n {
            let mut v = a[(i, j)];
            for k in 0..j {
                v -= a[(i, k)] * a[(j, k)];
            }
            a[(i, j)] = v / d;
        }
    }
    true
}

/// Solve `L Lᵀ x = b` in place with the factor of [`cholesky_in_place`].
fn cholesky_solve(l: &DMatrix<f64>, b: &mut [f64]) {
    let n = l.nrows();
    for i in 0..n {
        let mut v = b[i];
        for k in 0..i {
            v -= l[(i, k)] * b[k];
        }
        b[i] = v / l[(i, i)];
    }
    for i in (0..n).rev() {
        let mut v = b[i];
        for k in i + 1..n {
            v -= l[(k, i)] * b[k];
        }
        b[i] = v / l[(i, i)];
    }
}

/// The damping matrix of `damping` for `model` (`None` without damping).
fn damping_matrix<M: StructuralModel>(
    model: &M,
    ws: &mut M::Workspace,
    damping: &Damping,
) -> Result<Option<DMatrix<f64>>, InputError> {
    let n = model.n_dofs();
    let x0 = vec![0.0; n];
    let mut m0 = DMatrix::zeros(n, n);
    model.mass_matrix_into(&x0, ws, &mut m0);
    let check = |name: &str, v: f64| {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(InputError::new(
                format!("damping.{name}"),
                format!("must be a finite non-negative number, got {v}"),
            ))
        }
    };
    match damping {
        Damping::None => Ok(None),
        Damping::Rayleigh { alpha, beta } => {
            check("alpha", *alpha)?;
            check("beta", *beta)?;
            Ok(Some(&m0 * *alpha + model.stiffness_matrix() * *beta))
        }
        Damping::Modal { ratios } => {
            for (i, z) in ratios.iter().enumerate() {
                check(&format!("ratios[{i}]"), *z)?;
            }
            if ratios.len() > n {
                return Err(InputError::new(
                    "damping.ratios",
                    format!("{} ratios given but the model has {n} modes", ratios.len()),
                ));
            }
            let (lambda, phi) = super::generalized_symmetric_eigen(&model.stiffness_matrix(), &m0)
                .map_err(|e| InputError::new("damping", e.to_string()))?;
            let mut c = DMatrix::zeros(n, n);
            for (k, z) in ratios.iter().enumerate() {
                let u = &m0 * phi.column(k);
                c += &u * u.transpose() * (2.0 * z * lambda[k].max(0.0).sqrt());
            }
            Ok(Some(c))
        }
    }
}

impl<M: StructuralModel> OdeSystem for EquationsOfMotion<'_, M> {
    fn dim(&self) -> usize {
        2 * self.n
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_evaluations += 1;
        let n = self.n;
        let (x, p) = y.split_at(n);
        self.factor_mass(x);
        self.solve_velocities(p);
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
        let (dx, dp) = dy.split_at_mut(n);
        dx.copy_from_slice(&self.xdot);
        for i in 0..n {
            let mut v = self.force[i] + self.gamma[i];
            for j in 0..n {
                v -= self.k[(i, j)] * x[j];
            }
            if let Some(c) = &self.c {
                for j in 0..n {
                    v -= c[(i, j)] * self.xdot[j];
                }
            }
            dp[i] = v;
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
        let (x, p) = y.split_at(n);
        self.factor_mass(x);
        self.solve_velocities(p);
        self.update_scales(t);
        if !self.factored {
            jac.fill(f64::NAN);
            return;
        }
        self.model.kinetic_derivatives_into(
            x,
            &self.xdot,
            &mut self.ws,
            &mut self.dp,
            &mut self.dgamma,
        );
        self.model.load_jacobian_into(
            x,
            self.loads,
            &self.scales,
            &mut self.ws,
            &mut self.load_jac,
        );
        let mut minv = DMatrix::identity(n, n);
        for mut col in minv.column_iter_mut() {
            cholesky_solve(&self.factor, col.as_mut_slice());
        }
        let dxdx = -(&minv * &self.dp);
        let mut g_xdot = match self.gyroscopic {
            Gyroscopic::Neglected => DMatrix::zeros(n, n),
            _ => self.dp.transpose(),
        };
        if let Some(c) = &self.c {
            g_xdot -= c;
        }
        let mut dpdx = &self.load_jac - &self.k + &g_xdot * &dxdx;
        if !matches!(self.gyroscopic, Gyroscopic::Neglected) {
            dpdx += &self.dgamma;
        }
        let dpdp = &g_xdot * &minv;
        jac.view_mut((0, 0), (n, n)).copy_from(&dxdx);
        jac.view_mut((0, n), (n, n)).copy_from(&minv);
        jac.view_mut((n, 0), (n, n)).copy_from(&dpdx);
        jac.view_mut((n, n), (n, n)).copy_from(&dpdp);
    }
}
