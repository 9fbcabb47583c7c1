//! Natural modes of the linearized model (model.md, "Modes"; the method and its accuracy in
//! docs/model-choices.md, "Modes").
//!
//! `K_T φ = ω² M φ` about an equilibrium `q*`. In joint coordinates `M(q*)` is badly conditioned
//! (its condition number grows like n⁶: 2e15 at n = 320), while `K_T` is well conditioned (`K` is
//! diagonal), so the problem is solved in the inverse form `M φ = μ K_T φ`, `μ = 1/ω²`: the
//! lowest modes are the largest, well separated `μ`, computed to a relative round-off of about
//! `ε (ω_k/ω_1)²` whatever the size of the model.
//!
//! * The lowest `r` modes of a large model: thick-restart block Lanczos on `K_T⁻¹ M` in the `M`
//!   inner product (`lanczos.rs`), with `M v` from the O(n) momentum recursion and `K_T⁻¹` from the
//!   O(n) elimination of `tangent.rs`: O(n r²) in all.
//! * Every request on a model of at most [`DENSE_MAX_DOFS`] coordinates, and requests for more
//!   than a quarter of the modes of a larger one: the dense solver of `eigen.rs` on `(M, K_T)`
//!   (Cholesky of `K_T`, symmetric eigen-decomposition of `L⁻¹ M L⁻ᵀ`), O(n³).
//!
//! The former dense solver factored `M` instead; its first frequency was off by 3e-11 at n = 16,
//! 1e-8 at n = 48, 1.6e-7 at n = 64, and wrong from n ≈ 800 (0 rad/s at 800, 78.6 instead of
//! 55.6 at 1000; Table 4 beam, docs/validation.md).

use nalgebra::DMatrix;

use super::generalized_symmetric_eigen;
use super::lanczos::{self, Pencil};
use super::tangent::Tangent;
use crate::error::{InputError, SolveError};
use crate::model::{AppliedLoads, FullModel, KineticScratch, StructuralModel};

/// Largest number of coordinates for which every modal analysis is dense: below it the dense
/// solver is as fast as Lanczos for ten modes and faster for more (measured crossover at 48
/// coordinates, `benches/modes.rs`).
pub const DENSE_MAX_DOFS: usize = 48;

/// A mode is returned only if its `μ = 1/ω²` exceeds this multiple of `ε μ_max`: below it the
/// round-off `≈ ε μ_max` of the dense solver would be a sizeable part of `μ`. That is a mode more
/// than 8.4e6 times as fast as the first: for the paper's beams every mode passes up to 150
/// elements (Table 4 beam: `ω_max/ω_1 = 3.0e6` at n = 128), and one or two of the highest,
/// non-physical modes of the lumped chain are dropped from 200 elements on.
const RESOLVED: f64 = 64.0;

/// Natural frequencies and mass-normalized mode shapes, sorted by frequency.
#[derive(Debug, Clone)]
pub struct Modes {
    omega: Vec<f64>,
    shapes: DMatrix<f64>,
    about: Vec<f64>,
    stats: ModesStats,
}

/// Which eigensolver computed the modes (module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModesMethod {
    /// Dense generalized eigen-decomposition of `(M, K_T)`, O(n³).
    Dense,
    /// Thick-restart block Lanczos on `K_T⁻¹ M` with O(n) operators, O(n r²).
    Lanczos,
}

/// How the modes were computed and the work it took.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ModesStats {
    /// The eigensolver.
    pub method: ModesMethod,
    /// Applications of `K_T⁻¹ M` (Lanczos; 0 for the dense solver).
    pub operator_applications: usize,
    /// Thick restarts of Lanczos.
    pub restarts: usize,
    /// Largest Lanczos basis (vectors of `n_dofs` entries kept at once).
    pub basis: usize,
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

/// `K_T⁻¹ M` at one configuration, in the `M` inner product: the operator of [`lanczos`].
struct ModalPencil<'a> {
    model: &'a FullModel,
    kinetic: KineticScratch<f64>,
    tangent: Tangent,
}

impl Pencil for ModalPencil<'_> {
    fn dim(&self) -> usize {
        self.model.n_dofs()
    }
    fn apply_b(&mut self, x: &[f64], out: &mut [f64]) {
        self.model
            .kinetic_terms_configured(x, &mut self.kinetic, Some(out), None);
    }
    fn apply_a(&mut self, bx: &[f64], out: &mut [f64]) {
        self.tangent.solve(self.model, bx, out);
    }
}

impl Modes {
    /// The modes of `model` linearized about the configuration `q_star` with the dense tangent
    /// stiffness `k_tangent` (`K − ∂Q/∂q`, symmetric; `model.stiffness_matrix()` with no load),
    /// by the dense solver: every mode that double precision resolves (all of them for the paper's
    /// beams up to 150 elements), O(n³). [`Modes::lowest`] and [`Modes::lowest_loaded`] build
    /// the tangent themselves and choose the solver.
    ///
    /// # Errors
    /// [`SolveError::IndefiniteTangent`] if `k_tangent` is not positive definite (an unstable
    /// equilibrium), [`SolveError::MassNotPositiveDefinite`] if `M` is numerically not,
    /// [`SolveError::BadEigenvalue`] for a non-finite eigenvalue.
    pub fn about(
        model: &FullModel,
        q_star: &[f64],
        k_tangent: &DMatrix<f64>,
    ) -> Result<Self, SolveError> {
        Self::dense(model, q_star, k_tangent, model.n_dofs())
    }

    /// Every mode about the undeformed state with no load that double precision resolves (all
    /// of them for the paper's beams up to 150 elements): [`Modes::lowest`] with
    /// `count = n_dofs`.
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
    ///
    /// # Errors
    /// Those of [`Modes::lowest`].
    pub fn undeformed(model: &FullModel) -> Result<Self, SolveError> {
        Self::lowest(model, model.n_dofs())
    }

    /// The `count` lowest modes about the undeformed state with no load (fewer if double
    /// precision does not resolve that many, which only happens for the highest modes of large
    /// models, more than 8.4e6 times as fast as the first: see [`Modes::n_modes`]).
    ///
    /// Above [`DENSE_MAX_DOFS`] coordinates and up to a quarter of the modes: Lanczos, O(n r²);
    /// otherwise the dense solver, O(n³) (module documentation).
    ///
    /// ```
    /// // The first frequency of the Table 4 beam at n = 2000, against Euler–Bernoulli's
    /// // 1.87510407² √(EI / m L⁴) = 55.5930827 rad/s: the lumped model's error is 1.7e-8 there.
    /// let model = flexwing::paper::table4_beam(2000)?;
    /// let modes = flexwing::solve::Modes::lowest(&model, 3)?;
    /// assert_eq!(modes.n_modes(), 3);
    /// assert!((modes.omega()[0] / 55.5930827 - 1.0).abs() < 1e-7);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    /// [`SolveError::InvalidInput`] (field `count`) for `count = 0` or more modes than
    /// coordinates; [`SolveError::ModesNotConverged`] if Lanczos does not converge (not seen on
    /// any beam); [`SolveError::MassNotPositiveDefinite`] if `M` is numerically not positive
    /// definite.
    pub fn lowest(model: &FullModel, count: usize) -> Result<Self, SolveError> {
        let q0 = vec![0.0; model.n_dofs()];
        Self::compute(
            model,
            &q0,
            count,
            || Ok(Tangent::unloaded(model)),
            || Ok(model.stiffness_matrix()),
        )
    }

    /// Every resolved mode about a loaded equilibrium: [`Modes::lowest_loaded`] with
    /// `count = n_dofs`.
    ///
    /// # Errors
    /// Those of [`Modes::lowest_loaded`].
    pub fn loaded(
        model: &FullModel,
        q_star: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> Result<Self, SolveError> {
        Self::lowest_loaded(model, q_star, loads, scales, model.n_dofs())
    }

    /// The `count` lowest modes about a loaded equilibrium `q_star` (a static solution for
    /// `loads` scaled by `scales`): `K_T = K − ∂Q/∂q` at `q_star`, by the same path as
    /// [`Modes::lowest`], with `K_T` factored in O(n) for Lanczos (`tangent.rs`).
    ///
    /// # Errors
    /// [`SolveError::NonSymmetricTangent`] if the loads include follower forces (whose tangent is
    /// not symmetric: the problem is then non-conservative and its eigenvalues may be complex),
    /// [`SolveError::IndefiniteTangent`] if `K_T` is not positive definite (an unstable
    /// equilibrium, or one at a bifurcation), and the errors of [`Modes::lowest`].
    pub fn lowest_loaded(
        model: &FullModel,
        q_star: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        count: usize,
    ) -> Result<Self, SolveError> {
        Self::compute(
            model,
            q_star,
            count,
            || Tangent::loaded(model, q_star, loads, scales),
            || dense_tangent(model, q_star, loads, scales),
        )
    }

    /// The `count` lowest modes about `q_star` by the path the module documentation describes.
    fn compute(
        model: &FullModel,
        q_star: &[f64],
        count: usize,
        tangent: impl FnOnce() -> Result<Tangent, SolveError>,
        dense: impl FnOnce() -> Result<DMatrix<f64>, SolveError>,
    ) -> Result<Self, SolveError> {
        let nd = model.n_dofs();
        if count == 0 || count > nd {
            return Err(SolveError::from_input(InputError::new(
                "count",
                format!("must be between 1 and {nd} (the number of coordinates), got {count}"),
            )));
        }
        if nd <= DENSE_MAX_DOFS || 4 * count > nd {
            return Self::dense(model, q_star, &dense()?, count);
        }
        let tangent = tangent()?;
        if tangent.non_positive() > 0 {
            return Err(SolveError::IndefiniteTangent {
                non_positive: tangent.non_positive(),
            });
        }
        let mut kinetic = KineticScratch::new(model.n_elements());
        model.configure(q_star, &mut kinetic);
        let mut pencil = ModalPencil {
            model,
            kinetic,
            tangent,
        };
        let pairs =
            lanczos::largest(&mut pencil, count).map_err(|e| SolveError::ModesNotConverged {
                converged: e.converged,
                wanted: count,
            })?;
        let mut omega = Vec::with_capacity(count);
        let mut shapes = pairs.vectors;
        for (index, (&mu, mut col)) in pairs
            .values
            .iter()
            .zip(shapes.column_iter_mut())
            .enumerate()
        {
            if !(mu.is_finite() && mu > 0.0) {
                return Err(SolveError::BadEigenvalue {
                    index,
                    value: 1.0 / mu,
                });
            }
            omega.push(1.0 / mu.sqrt());
            fix_sign(col.as_mut_slice());
        }
        Ok(Self {
            omega,
            shapes,
            about: q_star.to_vec(),
            stats: ModesStats {
                method: ModesMethod::Lanczos,
                operator_applications: pairs.stats.applications,
                restarts: pairs.stats.restarts,
                basis: pairs.stats.basis,
            },
        })
    }

    /// The dense solver: `M φ = μ K_T φ` with the Cholesky factor of `K_T`, the `count` largest
    /// resolved `μ`, `ω = μ^{−1/2}`, each `φ` scaled to `φᵀ M φ = 1`.
    fn dense(
        model: &FullModel,
        q_star: &[f64],
        k_t: &DMatrix<f64>,
        count: usize,
    ) -> Result<Self, SolveError> {
        if k_t.clone().cholesky().is_none() {
            let lambda = k_t.symmetric_eigenvalues();
            let non_positive = lambda.iter().filter(|&&l| !(l > 0.0)).count().max(1);
            return Err(SolveError::IndefiniteTangent { non_positive });
        }
        let m = mass_matrix(model, q_star);
        let (mu, phi) = generalized_symmetric_eigen(&m, k_t)?;
        let nd = mu.len();
        let mu_max = mu[nd - 1];
        if let Some(i) = mu.iter().position(|x| !x.is_finite()) {
            return Err(SolveError::BadEigenvalue {
                index: nd - 1 - i,
                value: 1.0 / mu[i],
            });
        }
        if mu[0] < -RESOLVED * f64::EPSILON * mu_max {
            // K_T is positive definite, so a negative μ beyond round-off is M that is not.
            return Err(SolveError::MassNotPositiveDefinite);
        }
        let resolved = mu
            .iter()
            .filter(|&&x| x > RESOLVED * f64::EPSILON * mu_max)
            .count();
        let count = count.min(resolved);
        let mut shapes = DMatrix::zeros(nd, count);
        let mut omega = Vec::with_capacity(count);
        let mut mphi = vec![0.0; nd];
        for k in 0..count {
            let i = nd - 1 - k;
            omega.push(1.0 / mu[i].sqrt());
            let col = phi.column(i);
            model.momentum_into(q_star, col.as_slice(), &mut mphi);
            let norm = col
                .iter()
                .zip(&mphi)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .sqrt();
            shapes.set_column(k, &(col / norm));
        }
        Ok(Self {
            omega,
            shapes,
            about: q_star.to_vec(),
            stats: ModesStats {
                method: ModesMethod::Dense,
                operator_applications: 0,
                restarts: 0,
                basis: 0,
            },
        })
    }

    /// Number of modes computed.
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
    /// Mode shapes as columns (`n_dofs × n_modes`), with `Φᵀ M Φ = I`, each with its
    /// largest-magnitude component positive.
    pub fn shapes(&self) -> &DMatrix<f64> {
        &self.shapes
    }
    /// How the modes were computed.
    pub fn stats(&self) -> ModesStats {
        self.stats
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

/// The mass matrix `M(q)` (dense, O(n²)), without a model workspace.
fn mass_matrix(model: &FullModel, q: &[f64]) -> DMatrix<f64> {
    let nd = model.n_dofs();
    let mut m = DMatrix::zeros(nd, nd);
    model.mass_matrix_kin_into(&model.kinematics(q), &mut m);
    m
}

/// The dense tangent `K − ∂Q/∂q` at `q`, symmetrized.
///
/// # Errors
/// [`SolveError::NonSymmetricTangent`] if `K_T` is not symmetric (follower forces).
pub(crate) fn dense_tangent(
    model: &FullModel,
    q: &[f64],
    loads: &AppliedLoads,
    scales: &[f64],
) -> Result<DMatrix<f64>, SolveError> {
    let nd = model.n_dofs();
    let mut jac = DMatrix::zeros(nd, nd);
    model.load_jacobian_kin_into(&model.kinematics(q), loads, scales, &mut jac);
    let k_t = model.stiffness_matrix() - jac;
    let asym = (&k_t - k_t.transpose()).amax();
    if asym > 1e-10 * k_t.amax() {
        return Err(SolveError::NonSymmetricTangent {
            asymmetry: asym / k_t.amax(),
        });
    }
    Ok((&k_t + k_t.transpose()) * 0.5)
}

/// Make the largest-magnitude component positive (the first of equal magnitudes).
fn fix_sign(v: &mut [f64]) {
    let big = v
        .iter()
        .copied()
        .fold(0.0_f64, |b, x| if x.abs() > b.abs() { x } else { b });
    if big < 0.0 {
        v.iter_mut().for_each(|x| *x = -*x);
    }
}

impl Modes {
    /// The `count` lowest modes of any structural model about the configuration `x_star`, an
    /// equilibrium under `loads` scaled by `scales` (`AppliedLoads::none()` and `&[]` for the
    /// unloaded model about its undeformed state): the dense solver of [`Modes::about`] on
    /// `(M(x*), K − ∂Q/∂x)` through the model's own [`StructuralModel`] evaluations, O(n³).
    /// The path of the models without an O(n) tangent here, such as the 3-D chain
    /// ([`crate::model::Chain3d`]).
    ///
    /// # Errors
    /// [`SolveError::InvalidInput`] (field `count`) for `count = 0` or more modes than
    /// coordinates, [`SolveError::NonSymmetricTangent`] for non-conservative loads,
    /// [`SolveError::IndefiniteTangent`] for an unstable equilibrium,
    /// [`SolveError::MassNotPositiveDefinite`], [`SolveError::BadEigenvalue`].
    pub fn of_model<M: StructuralModel>(
        model: &M,
        x_star: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        count: usize,
    ) -> Result<Self, SolveError> {
        let nd = model.n_dofs();
        if count == 0 || count > nd {
            return Err(SolveError::from_input(InputError::new(
                "count",
                format!("must be between 1 and {nd} (the number of coordinates), got {count}"),
            )));
        }
        let mut ws = model.workspace();
        let mut jac = DMatrix::zeros(nd, nd);
        model.load_jacobian_into(x_star, loads, scales, &mut ws, &mut jac);
        let k_t = model.stiffness_matrix() - jac;
        let asym = (&k_t - k_t.transpose()).amax();
        if asym > 1e-10 * k_t.amax() {
            return Err(SolveError::NonSymmetricTangent {
                asymmetry: asym / k_t.amax(),
            });
        }
        let k_t = (&k_t + k_t.transpose()) * 0.5;
        if k_t.clone().cholesky().is_none() {
            let lambda = k_t.symmetric_eigenvalues();
            let non_positive = lambda.iter().filter(|&&l| !(l > 0.0)).count().max(1);
            return Err(SolveError::IndefiniteTangent { non_positive });
        }
        let mut m = DMatrix::zeros(nd, nd);
        model.mass_matrix_into(x_star, &mut ws, &mut m);
        let (mu, phi) = generalized_symmetric_eigen(&m, &k_t)?;
        let mu_max = mu[nd - 1];
        if let Some(i) = mu.iter().position(|x| !x.is_finite()) {
            return Err(SolveError::BadEigenvalue {
                index: nd - 1 - i,
                value: 1.0 / mu[i],
            });
        }
        if mu[0] < -RESOLVED * f64::EPSILON * mu_max {
            return Err(SolveError::MassNotPositiveDefinite);
        }
        let resolved = mu
            .iter()
            .filter(|&&x| x > RESOLVED * f64::EPSILON * mu_max)
            .count();
        let count = count.min(resolved);
        let mut shapes = DMatrix::zeros(nd, count);
        let mut omega = Vec::with_capacity(count);
        let mut mphi = vec![0.0; nd];
        for k in 0..count {
            let i = nd - 1 - k;
            omega.push(1.0 / mu[i].sqrt());
            let col = phi.column(i);
            model.momentum_into(x_star, col.as_slice(), &mut ws, &mut mphi);
            let norm = col
                .iter()
                .zip(&mphi)
                .map(|(a, b)| a * b)
                .sum::<f64>()
                .sqrt();
            let mut v = col / norm;
            fix_sign(v.as_mut_slice());
            shapes.set_column(k, &v);
        }
        Ok(Self {
            omega,
            shapes,
            about: x_star.to_vec(),
            stats: ModesStats {
                method: ModesMethod::Dense,
                operator_applications: 0,
                restarts: 0,
                basis: 0,
            },
        })
    }
}
