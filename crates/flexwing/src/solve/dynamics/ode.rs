//! The equations of motion as an [`OdeSystem`]: the right-hand side `(ẋ, ṗ)` (with the energy
//! audit's rates), the exact Jacobian `∂(ẋ, ṗ)/∂(x, p)` and its dense buffers.

use nalgebra::{Complex, DMatrix};

use std::ops::ControlFlow;
use std::sync::atomic::Ordering;

use super::newton_systems::chain_newton_min_dofs;
use super::{EquationsOfMotion, Gyroscopic};
use crate::model::StructuralModel;
use crate::solve::eom_newton::ChainNewton;
use crate::solve::integrate::{IntegratorSettings, Method, NewtonSolver, OdeSystem};

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
        if !self.audit.as_mut().is_some_and(|a| a.due(t)) {
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
            let v = self.force[i] + self.gamma[i] - self.c_xdot[i] - self.k.row_dot(i, x);
            power += self.xdot[i] * self.force[i];
            dissipation += self.xdot[i] * self.c_xdot[i];
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
            // The quadrature states feed back into nothing, and their rows are not used: the
            // integrators solve the other states and take theirs from `quadrature_step_*`.
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
        // `(∂Q/∂x)ᵀ ẋ` at the linearization point, for the audit's quadrature steps (these
        // equations' or the aeroelastic equations', which audit them themselves): O(n²) as the
        // load Jacobian.
        self.load_rate.clear();
        self.load_rate.extend((0..n).map(|j| {
            let col = &d.load_jac.as_slice()[j * n..(j + 1) * n];
            col.iter().zip(&self.xdot).map(|(a, b)| a * b).sum::<f64>()
        }));
        // M⁻¹ by one factorization and one O(n) velocity solve per column.
        self.model
            .velocities_block_into(x, &d.identity, &mut self.ws, &mut d.minv);
        jac.view_mut((0, 0), (n, n)).copy_from(&d.dxdx);
        jac.view_mut((0, n), (n, n)).copy_from(&d.minv);
        jac.view_mut((n, 0), (n, n)).copy_from(&d.load_jac);
        self.k.subtract_from(jac.view_mut((n, 0), (n, n)));
        let mut dpdx = jac.view_mut((n, 0), (n, n));
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
        if let Some(chain) = self.model.as_chain3d() {
            if self.chain3d.is_none() {
                let gyroscopic = !matches!(self.gyroscopic, Gyroscopic::Neglected);
                let rayleigh = match self.damping {
                    crate::solve::Damping::Rayleigh { alpha, beta } => (alpha, beta),
                    _ => (0.0, 0.0),
                };
                self.chain3d = Some(crate::model::chain3d::Newton3d::new(
                    chain,
                    rayleigh,
                    gyroscopic,
                    self.time_functions.len(),
                ));
            }
            return Some(self);
        }
        if self.chain.is_none() {
            let full = self.model.as_full_model()?;
            let gyroscopic = !matches!(self.gyroscopic, Gyroscopic::Neglected);
            self.chain = Some(ChainNewton::new(full, &self.damping, gyroscopic));
        }
        Some(self)
    }

    /// With the audit, `W` and `D` (module `energy_audit`).
    fn quadrature_states(&self) -> usize {
        if self.audit.is_some() {
            2
        } else {
            0
        }
    }

    /// The audit's `W` and `D` converged with the other stages in one Newton iteration: their
    /// rows of `J`, the gradients of `Ẇ = ẋ·Q` and `Ḋ = ẋᵀ C ẋ` ([`Self::power_gradient`]),
    /// applied to the step `Δy` without forming them, with `δẋ = (∂ẋ/∂y) Δy = c Δx − b_x` the
    /// Newton system's first block row (whatever solved it) and `Q`, `C ẋ` those of the last
    /// right-hand side (the latest stage).
    fn quadrature_step_real(&mut self, c: f64, lead: &[f64], dy: &[f64], q: &mut [f64]) {
        let (w, d) = self.power_gradient(
            &self.force.as_slice()[..self.n],
            &self.c_xdot,
            |i| (c * dy[i] - lead[i]).into(),
            |i| dy[i].into(),
        );
        if let [qw, qd] = q {
            *qw = (*qw + w.re) / c;
            *qd = (*qd + d.re) / c;
        }
    }

    fn quadrature_step_complex(
        &mut self,
        c: Complex<f64>,
        lead: (&[f64], &[f64]),
        dy: (&[f64], &[f64]),
        q: (&mut [f64], &mut [f64]),
    ) {
        let dx = |i: usize| Complex::new(dy.0[i], dy.1[i]);
        let (w, d) = self.power_gradient(
            &self.force.as_slice()[..self.n],
            &self.c_xdot,
            |i| c * dx(i) - Complex::new(lead.0[i], lead.1[i]),
            dx,
        );
        let (re, im) = q;
        for (k, add) in [w, d].into_iter().enumerate() {
            if let (Some(r), Some(i)) = (re.get_mut(k), im.get_mut(k)) {
                let v = (Complex::new(*r, *i) + add) / c;
                (*r, *i) = (v.re, v.im);
            }
        }
    }

    /// `Q` and `C ẋ` of the last right-hand side, kept as stage `slot`'s.
    fn keep_quadrature_point(&mut self, slot: usize) {
        let n = self.n;
        let point = &mut self.quadrature_points[slot];
        point.clear();
        point.extend_from_slice(&self.force.as_slice()[..n]);
        point.extend_from_slice(&self.c_xdot);
    }

    /// The change of `Ẇ`, `Ḋ` from the kept point `slot` along `dy`, with `δẋ = dy_rate[..n]`:
    /// their gradients ([`Self::power_gradient`]) and `Ḋ`'s term of second order `δẋᵀ C δẋ`.
    fn quadrature_gradient(&mut self, slot: usize, dy: &[f64], dy_rate: &[f64], out: &mut [f64]) {
        let point = &self.quadrature_points[slot];
        let (force, c_xdot) = point.split_at(self.n);
        let (w, d) = self.power_gradient(force, c_xdot, |i| dy_rate[i].into(), |i| dy[i].into());
        let second = self.damping_power_of(&dy_rate[..self.n]);
        if let [qw, qd] = out {
            (*qw, *qd) = (w.re, d.re + second);
        }
    }

    fn integrating_with(&mut self, method: Method, settings: &IntegratorSettings) {
        self.auto_chain_min_dofs = chain_newton_min_dofs(method, settings);
    }
}

impl<M: StructuralModel> EquationsOfMotion<'_, M> {
    /// Audit the state `y` of the last accepted step, at `t`, if [`AuditLimits::interval`] left it
    /// unaudited: a completed run's balance then includes its final state.
    ///
    /// [`AuditLimits::interval`]: crate::solve::AuditLimits::interval
    pub(crate) fn audit_final(&mut self, t: f64, y: &[f64]) {
        if self.audit.as_ref().is_none_or(|a| a.audited_at(t)) {
            return;
        }
        let (kinetic, strain) = self.energies(y);
        let n2 = 2 * self.n;
        if let Some(audit) = &mut self.audit {
            let _ = audit.check(t, kinetic + strain, y[n2], y[n2 + 1]);
        }
    }

    /// The generalized forces `Q`, the velocities `ẋ` and the damping forces `C ẋ` of the last
    /// right-hand side, and `(∂Q/∂x)ᵀ ẋ` at the last linearization with its `ẋ`: what the
    /// audit's quadrature step of a caller that audits these equations itself needs (the
    /// aeroelastic equations).
    pub(crate) fn last_power_terms(&mut self) -> (&[f64], &[f64], &[f64], Vec<f64>) {
        let load_rate = self.quadrature_load_rate();
        (self.force.as_slice(), &self.xdot, &self.c_xdot, load_rate)
    }

    /// The gradients of the audit's rates `Ẇ = ẋ·Q` and `Ḋ = ẋᵀ C ẋ` at a point with forces
    /// `force` (`Q`) and damping forces `c_xdot` (`C ẋ`) applied to a step whose change of `ẋ`
    /// is `xdot_step(i)` and of `x` is `x_step(i)`: `∇Ẇ·Δy = Q·δẋ + ẋ·(∂Q/∂x) Δx` and
    /// `∇Ḋ·Δy = 2 (C ẋ)·δẋ`. The load stiffness term `(∂Q/∂x)ᵀ ẋ` is that of the last
    /// linearization with its own `ẋ` (the dense Jacobian's or the chain's,
    /// `newton_systems.rs`): a simplified Newton's gradient, as `J`.
    fn power_gradient(
        &self,
        force: &[f64],
        c_xdot: &[f64],
        xdot_step: impl Fn(usize) -> Complex<f64>,
        x_step: impl Fn(usize) -> Complex<f64>,
    ) -> (Complex<f64>, Complex<f64>) {
        let (mut w, mut d) = (Complex::new(0.0, 0.0), Complex::new(0.0, 0.0));
        for i in 0..self.n {
            let v = xdot_step(i);
            w += v * force[i] + x_step(i) * self.load_rate.get(i).copied().unwrap_or(0.0);
            d += v * c_xdot[i];
        }
        (w, d * 2.0)
    }

    /// `vᵀ C v`: the damping's power at the velocities `v` (zero without damping).
    pub(crate) fn damping_power_of(&mut self, v: &[f64]) -> f64 {
        if self.damping == crate::solve::Damping::None {
            return 0.0;
        }
        self.c_step.resize(self.n, 0.0);
        self.c.apply(self.model, v, &mut self.c_step);
        v.iter().zip(&self.c_step).map(|(a, b)| a * b).sum()
    }

    /// `(∂Q/∂x)ᵀ ẋ` for the audit's quadrature step, at the last linearization (the dense
    /// Jacobian's or the chain's, with the `ẋ` of that point: a simplified Newton's gradient, as
    /// the other rows' `J`), into the scratch taken from `load_rate_scratch`.
    fn quadrature_load_rate(&mut self) -> Vec<f64> {
        let mut out = std::mem::take(&mut self.load_rate_scratch);
        out.clear();
        out.extend_from_slice(&self.load_rate);
        out
    }
}

/// Buffers of the dense Jacobian (`n_dofs × n_dofs` each), and the damping matrix it needs.
pub(super) struct DenseBuffers {
    /// `C`, formed once from the damping operator; `None` without damping.
    pub(super) c: Option<DMatrix<f64>>,
    pub(super) dgamma: DMatrix<f64>,
    pub(super) load_jac: DMatrix<f64>,
    pub(super) identity: DMatrix<f64>,
    pub(super) minv: DMatrix<f64>,
    pub(super) dxdx: DMatrix<f64>,
}

impl DenseBuffers {
    pub(super) fn new(n: usize, c: Option<DMatrix<f64>>) -> Self {
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
