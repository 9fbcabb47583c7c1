//! How the implicit integrators solve the Newton systems of the equations of motion
//! ([`NewtonSystems`], and where `Auto` switches to the chain: [`chain_newton_min_dofs`]), and the
//! full model's O(n) solves of them by the chain sweeps of `eom_newton.rs`, the
//! [`NewtonSolver`] of [`EquationsOfMotion`] (docs/model-choices.md, "O(n) Newton systems").

use nalgebra::Complex;

use super::EquationsOfMotion;
use crate::model::StructuralModel;
use crate::solve::integrate::{IntegratorSettings, Method, NewtonSolver};
use nalgebra::DMatrix;

/// From this many coordinates on, [`NewtonSystems::Auto`] solves the full model's Newton systems
/// by O(n) chain sweeps instead of dense LU factorizations of the exact Jacobian (measured on
/// case (b), docs/performance.md, "O(n) Newton systems"), unless [`integrate`] says which method
/// will run ([`chain_newton_min_dofs`]).
///
/// [`integrate`]: super::integrate::integrate
pub const CHAIN_NEWTON_MIN_DOFS: usize = 40;

/// From this many coordinates on, [`NewtonSystems::Auto`] solves the 3-D chain's Newton systems
/// in O(n) (`model/chain3d/newton.rs`) whatever the method: measured on the straight 3-D chain
/// with Radau at a 1 ms step cap (`examples/chain3d_dynamics_cost.rs`), dense LU is faster at
/// 120 coordinates (n = 40: 1.0 against 2.4 ms per step), the O(n) path at 240 (n = 80: 4.6
/// against 18 ms); between them, 180.
pub const CHAIN3D_NEWTON_MIN_DOFS: usize = 180;

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

/// The full model's O(n) Newton solves (`eom_newton.rs`); reached only through
/// [`OdeSystem::newton_solver`], which offers them when [`EquationsOfMotion::uses_chain_newton`].
impl<M: StructuralModel> NewtonSolver for EquationsOfMotion<'_, M> {
    fn linearize(&mut self, t: f64, y: &[f64]) -> bool {
        let model = self.model;
        for (s, f) in self.scales.iter_mut().zip(&self.time_functions) {
            *s = f.at(t);
        }
        if let (Some(chain), Some(newton)) = (model.as_chain3d(), self.chain3d.as_mut()) {
            self.jacobian_evaluations += 1;
            let n = self.n;
            return newton.linearize(chain, &y[..n], &y[n..2 * n], &self.scales);
        }
        let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) else {
            return false;
        };
        self.jacobian_evaluations += 1;
        let ok = chain.linearize(full, self.loads, &self.scales, &y[..2 * self.n]);
        if ok && self.audit.is_some() {
            // The load stiffness along ẋ for the audit's quadrature step: `(∂Q/∂x) ẋ`, the
            // transposed product `(∂Q/∂x)ᵀ ẋ` for conservative loads (symmetric ∂Q/∂x); for
            // follower loads its antisymmetric part is left out (`ode.rs`).
            let n = self.n;
            let (x, p) = y.split_at(n);
            if self.solve_velocities(x, &p[..n]) {
                let kin = full.kinematics(x);
                let v = DMatrix::from_column_slice(n, 1, &self.xdot);
                let mut out = DMatrix::zeros(n, 1);
                full.load_jacobian_times_kin_into(&kin, self.loads, &self.scales, &v, &mut out);
                self.load_rate = out.as_slice().to_vec();
            }
        }
        ok
    }

    fn factor_real(&mut self, slot: usize, c: f64) -> bool {
        let model = self.model;
        if let (Some(chain), Some(newton)) = (model.as_chain3d(), self.chain3d.as_mut()) {
            return newton.factor_real(chain, slot, c);
        }
        match (model.as_full_model(), self.chain.as_mut()) {
            (Some(full), Some(chain)) => chain.factor_real(full, slot, c),
            _ => false,
        }
    }

    fn factor_complex(&mut self, slot: usize, c: Complex<f64>) -> bool {
        let model = self.model;
        if let (Some(chain), Some(newton)) = (model.as_chain3d(), self.chain3d.as_mut()) {
            return newton.factor_complex(chain, slot, c);
        }
        match (model.as_full_model(), self.chain.as_mut()) {
            (Some(full), Some(chain)) => chain.factor_complex(full, slot, c),
            _ => false,
        }
    }

    fn solve_real(&mut self, slot: usize, b: &mut [f64]) {
        let model = self.model;
        let n2 = 2 * self.n;
        if let (Some(chain), Some(newton)) = (model.as_chain3d(), self.chain3d.as_mut()) {
            let damping = &mut self.c;
            let mut product = |v: &[f64], out: &mut [f64]| damping.apply(model, v, out);
            newton.solve_real(chain, self.loads, &mut product, slot, &mut b[..n2]);
        } else if let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) {
            chain.solve_real(full, slot, &mut b[..n2]);
        }
    }

    fn solve_complex(&mut self, slot: usize, re: &mut [f64], im: &mut [f64]) {
        let model = self.model;
        let n2 = 2 * self.n;
        if let (Some(chain), Some(newton)) = (model.as_chain3d(), self.chain3d.as_mut()) {
            let damping = &mut self.c;
            let mut product = |v: &[f64], out: &mut [f64]| damping.apply(model, v, out);
            newton.solve_complex(
                chain,
                self.loads,
                &mut product,
                slot,
                &mut re[..n2],
                &mut im[..n2],
            );
        } else if let (Some(full), Some(chain)) = (model.as_full_model(), self.chain.as_mut()) {
            chain.solve_complex(full, slot, &mut re[..n2], &mut im[..n2]);
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
    /// The 3-D chain takes the integrators' defaults.
    fn newton_tolerance(&self) -> Option<f64> {
        self.chain.as_ref().map(|c| c.newton_tolerance())
    }
}
