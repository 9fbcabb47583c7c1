//! Natural modes of the linearized model (model.md, "Modes").

use nalgebra::DMatrix;

use super::generalized_symmetric_eigen;
use crate::error::SolveError;
use crate::model::{AppliedLoads, FullModel, StructuralModel};

/// Natural frequencies and mass-normalized mode shapes, sorted by frequency.
#[derive(Debug, Clone)]
pub struct Modes {
    omega: Vec<f64>,
    shapes: DMatrix<f64>,
    about: Vec<f64>,
}

/// A mode shape as nodal quantities (linearized about the equilibrium the modes were computed at).
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShape {
    /// Node stations `x_0 … x_n` along the undeformed span (m).
    pub x: Vec<f64>,
    /// Nodal displacement along global `x` per unit modal amplitude (m).
    pub dx: Vec<f64>,
    /// Nodal displacement along global `y` (vertical) per unit modal amplitude (m).
    pub dy: Vec<f64>,
    /// Twist at each node (rad): that of the element inboard of the node, zero at the clamp;
    /// all zeros in a bending-only model.
    pub twist: Vec<f64>,
}

impl Modes {
    /// Modes of `model` linearized about the configuration `q_star` with tangent stiffness
    /// `k_tangent` (`K − ∂Q/∂q`; pass `model.stiffness_matrix()` with no load).
    ///
    /// # Errors
    /// If the mass matrix is not positive definite or an eigenvalue is negative or not finite
    /// (a tangent stiffness that is not positive definite: the equilibrium is unstable).
    pub fn about(
        model: &FullModel,
        q_star: &[f64],
        k_tangent: &DMatrix<f64>,
    ) -> Result<Self, SolveError> {
        let nd = model.n_dofs();
        let mut m = DMatrix::zeros(nd, nd);
        model.mass_matrix_into(q_star, &mut model.workspace(), &mut m);
        let (lambda, shapes) = generalized_symmetric_eigen(k_tangent, &m)?;
        let mut omega = Vec::with_capacity(nd);
        for (index, &l) in lambda.iter().enumerate() {
            // The eigenvalues of L⁻¹ K L⁻ᵀ carry an absolute round-off of about ε·λ_max, so a
            // zero eigenvalue may come out as −64 ε λ_max at worst; below that the tangent
            // stiffness is indefinite (the equilibrium is unstable).
            let scale = lambda.last().copied().unwrap_or(1.0).abs();
            if !l.is_finite() || l < -64.0 * f64::EPSILON * scale {
                return Err(SolveError::BadEigenvalue { index, value: l });
            }
            omega.push(l.max(0.0).sqrt());
        }
        Ok(Self {
            omega,
            shapes,
            about: q_star.to_vec(),
        })
    }

    /// Modes about the undeformed state with no load.
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
    /// use flexwing::{model::FullModel, solve::Modes};
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let beam = Beam::new(1.0, &section, &Discretization::Uniform(32), Calibration::TipLoad)?;
    /// let modes = Modes::undeformed(&FullModel::new(beam))?;
    /// // Euler–Bernoulli: ω₁ = 1.8751² √(EI / m L⁴) = 55.6 rad/s.
    /// assert!((modes.omega()[0] / 55.596 - 1.0).abs() < 2e-3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn undeformed(model: &FullModel) -> Result<Self, SolveError> {
        let q0 = vec![0.0; model.n_dofs()];
        Self::about(model, &q0, &model.stiffness_matrix())
    }

    /// Modes about a loaded equilibrium `q_star` (a static solution for `loads` scaled by
    /// `scales`): `K_T = K − ∂Q/∂q` at `q_star`.
    ///
    /// # Errors
    /// [`SolveError::NonSymmetricTangent`] if the loads include follower forces (whose tangent is
    /// not symmetric: the problem is then non-conservative and its eigenvalues may be complex),
    /// and the errors of [`Modes::about`].
    pub fn loaded(
        model: &FullModel,
        q_star: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> Result<Self, SolveError> {
        let nd = model.n_dofs();
        let mut jac = DMatrix::zeros(nd, nd);
        model.load_jacobian_into(q_star, loads, scales, &mut model.workspace(), &mut jac);
        let k_t = model.stiffness_matrix() - jac;
        let asym = (&k_t - k_t.transpose()).amax();
        if asym > 1e-10 * k_t.amax() {
            return Err(SolveError::NonSymmetricTangent {
                asymmetry: asym / k_t.amax(),
            });
        }
        Self::about(model, q_star, &((&k_t + k_t.transpose()) * 0.5))
    }

    /// Number of modes (`n_dofs`).
    pub fn n_modes(&self) -> usize {
        self.omega.len()
    }
    /// Natural circular frequencies `ω` (rad/s), ascending.
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }
    /// Natural frequencies in Hz.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.omega
            .iter()
            .map(|w| w / (2.0 * std::f64::consts::PI))
            .collect()
    }
    /// Mode shapes as columns (`n_dofs × n_modes`), with `Φᵀ M Φ = I`.
    pub fn shapes(&self) -> &DMatrix<f64> {
        &self.shapes
    }
    /// The configuration the modes were computed about.
    pub fn equilibrium(&self) -> &[f64] {
        &self.about
    }

    /// Share of mode `k`'s strain energy stored in the bending springs,
    /// `φ_bᵀ K_b φ_b / φᵀ K φ`: 1 for a pure bending mode, 0 for a pure torsion mode.
    ///
    /// # Panics
    /// If `k >= n_modes()`.
    pub fn bending_energy_fraction(&self, model: &FullModel, k: usize) -> f64 {
        let phi = self.shapes.column(k);
        let kd = model.stiffness();
        let n = model.n_elements();
        let energy =
            |r: std::ops::Range<usize>| -> f64 { r.map(|i| kd[i] * phi[i] * phi[i]).sum() };
        let bending = energy(0..n);
        let total = bending + energy(n..model.n_dofs());
        if total > 0.0 {
            bending / total
        } else {
            1.0
        }
    }

    /// Nodal displacements and twists of mode `k` (0-based): `δP_i = Σ_{j ≤ i} ℓ_j n(θ*_j) δθ_j`
    /// with `δθ = T φ_b`, and `δψ = T φ_t`.
    ///
    /// # Panics
    /// If `k >= n_modes()`.
    pub fn shape(&self, model: &FullModel, k: usize) -> ModeShape {
        let n = model.n_elements();
        let kin = model.kinematics(&self.about);
        let phi = self.shapes.column(k);
        let ell = model.beam().lengths();
        let mut x = Vec::with_capacity(n + 1);
        let (mut dx, mut dy, mut twist) = (vec![0.0], vec![0.0], vec![0.0]);
        x.extend_from_slice(model.beam().nodes());
        let (mut dtheta, mut dpsi) = (0.0, 0.0);
        let (mut px, mut py) = (0.0, 0.0);
        for j in 0..n {
            dtheta += phi[j];
            px -= ell[j] * kin.sin_theta[j] * dtheta;
            py += ell[j] * kin.cos_theta[j] * dtheta;
            if model.has_torsion() {
                dpsi += phi[n + j];
            }
            dx.push(px);
            dy.push(py);
            twist.push(dpsi);
        }
        ModeShape { x, dx, dy, twist }
    }
}
