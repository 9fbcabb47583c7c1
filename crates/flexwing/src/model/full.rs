//! The full lumped-mass model of `n` elements.

use nalgebra::{DMatrix, DVector};

use super::chain_solve::ChainScratch;
use super::kinetic::{KineticBuffers, KineticScratch};
use super::loads::Resultants;
use super::{AppliedLoads, Kinematics, StructuralModel};
use crate::beam::Beam;

/// The full model: `n` rigid elements, `n` bending joints and (with torsion data) `n` torsion
/// joints, so `n_dofs()` is `2n`, or `n` for a bending-only beam.
#[derive(Debug, Clone)]
pub struct FullModel {
    pub(super) beam: Beam,
    pub(super) n: usize,
    pub(super) torsion: bool,
    /// Element lengths `ℓ_i`.
    pub(super) ell: Vec<f64>,
    /// Element masses `m_i`.
    pub(super) mass: Vec<f64>,
    /// Mass-centre offsets `d0_i`.
    pub(super) d0: Vec<f64>,
    /// Polar inertias about the mass centre `J_i`.
    pub(super) inertia: Vec<f64>,
    /// Rotary inertias in bending `J_b,i` about `ẑ` (zeros: the paper's point masses). They add
    /// `½ Σ J_b,i θ̇_i²` to the kinetic energy: a constant diagonal in absolute angles, so no
    /// gyroscopic term.
    pub(super) rotary: Vec<f64>,
    /// `μ_k = m_k / 2 + Σ_{i>k} m_i`: `A_jk = ℓ_j ℓ_k μ_k` for `j < k`.
    pub(super) mu: Vec<f64>,
    /// `A_kk = ℓ_k² (m_k / 4 + Σ_{i>k} m_i) + J_b,k`.
    pub(super) a_diag: Vec<f64>,
    /// Diagonal of `K`.
    pub(super) stiffness: Vec<f64>,
    /// The fluid's inertia (apparent mass) of an aeroelastic model, `None` in vacuo
    /// (`model::aero::fluid`).
    pub(crate) fluid: Option<super::aero::FluidInertia>,
}

impl FullModel {
    /// Build the full model of a beam.
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
    /// use flexwing::model::FullModel;
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let beam = Beam::new(1.0, &section, &Discretization::Uniform(4), Calibration::TipLoad)?;
    /// let model = FullModel::new(beam);
    /// assert_eq!(model.n_dofs(), 4);
    /// # Ok::<(), flexwing::InputError>(())
    /// ```
    pub fn new(beam: Beam) -> Self {
        let n = beam.n_elements();
        let mass = beam.masses().to_vec();
        let ell = beam.lengths().to_vec();
        let rotary = beam.bending_inertias().to_vec();
        let mut outboard = 0.0; // Σ_{i>k} m_i
        let mut mu = vec![0.0; n];
        let mut a_diag = vec![0.0; n];
        for k in (0..n).rev() {
            mu[k] = 0.5 * mass[k] + outboard;
            a_diag[k] = ell[k] * ell[k] * (0.25 * mass[k] + outboard) + rotary[k];
            outboard += mass[k];
        }
        let mut stiffness = beam.bending_stiffness().to_vec();
        if let Some(kt) = beam.torsion_stiffness() {
            stiffness.extend_from_slice(kt);
        }
        Self {
            n,
            torsion: beam.has_torsion(),
            ell,
            mass,
            d0: beam.offsets().to_vec(),
            inertia: beam.inertias().to_vec(),
            rotary,
            mu,
            a_diag,
            stiffness,
            beam,
            fluid: None,
        }
    }

    /// The same model with the fluid's inertia added to its kinetic energy (`model::aero::fluid`).
    ///
    /// # Panics
    /// If the vectors of `fluid` do not have one entry per element.
    pub(crate) fn with_fluid(mut self, fluid: super::aero::FluidInertia) -> Self {
        let n = self.n;
        assert!(
            fluid.mass.len() == n && fluid.station.len() == n && fluid.inertia.len() == n,
            "fluid inertia needs one entry per element"
        );
        self.fluid = Some(fluid);
        self
    }

    /// Whether the model carries the fluid's inertia (an aeroelastic model's structure).
    pub fn has_fluid_inertia(&self) -> bool {
        self.fluid.is_some()
    }

    /// The beam this model was built from.
    pub fn beam(&self) -> &Beam {
        &self.beam
    }
    /// Number of elements `n`.
    pub fn n_elements(&self) -> usize {
        self.n
    }
    /// Number of generalized coordinates: `2n` with torsion, `n` without.
    pub fn n_dofs(&self) -> usize {
        if self.torsion {
            2 * self.n
        } else {
            self.n
        }
    }
    /// Whether the model has torsion coordinates.
    pub fn has_torsion(&self) -> bool {
        self.torsion
    }
    /// Diagonal of the stiffness matrix `K` (N·m/rad).
    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// Kinematics of the configuration `q`.
    ///
    /// # Panics
    /// If `q.len() != self.n_dofs()`.
    pub fn kinematics(&self, q: &[f64]) -> Kinematics {
        assert_eq!(q.len(), self.n_dofs(), "q has the wrong length");
        let mut k = Kinematics::new(self.n);
        k.update(q);
        k
    }

    /// Node positions `P_0 … P_n` on the elastic axis (m).
    pub fn node_positions(&self, kin: &Kinematics) -> Vec<[f64; 3]> {
        let mut p = [0.0; 3];
        let mut out = Vec::with_capacity(self.n + 1);
        out.push(p);
        for i in 0..self.n {
            p[0] += self.ell[i] * kin.cos_theta[i];
            p[1] += self.ell[i] * kin.sin_theta[i];
            out.push(p);
        }
        out
    }

    /// Element mass centres `g_1 … g_n` (m).
    pub fn mass_centres(&self, kin: &Kinematics) -> Vec<[f64; 3]> {
        let nodes = self.node_positions(kin);
        (0..self.n)
            .map(|i| {
                let (c, s) = (kin.cos_theta[i], kin.sin_theta[i]);
                let (cp, sp) = (kin.cos_psi[i], kin.sin_psi[i]);
                let h = 0.5 * self.ell[i];
                let d = self.d0[i];
                [
                    nodes[i][0] + h * c - d * sp * s,
                    nodes[i][1] + h * s + d * sp * c,
                    d * cp,
                ]
            })
            .collect()
    }

    /// Element containing span position `span` and the distance from its inboard node: the
    /// smallest `k ≥ 1` with `x_k ≥ span`; `(0, 0)` at the clamp.
    pub(super) fn locate(&self, span: f64) -> (usize, f64) {
        let nodes = self.beam.nodes();
        let k = nodes.partition_point(|&x| x < span).min(self.n);
        if k == 0 {
            (0, 0.0)
        } else {
            (k, span - nodes[k - 1])
        }
    }

    /// Position of the elastic-axis point at span `span` (m).
    pub fn point_position(&self, kin: &Kinematics, span: f64) -> [f64; 3] {
        let (k, a) = self.locate(span);
        let mut p = [0.0; 3];
        for j in 0..k {
            let len = if j + 1 == k { a } else { self.ell[j] };
            p[0] += len * kin.cos_theta[j];
            p[1] += len * kin.sin_theta[j];
        }
        p
    }

    /// Jacobian `∂X/∂q` (3 × `n_dofs`) of the elastic-axis point at span `span`.
    pub fn point_jacobian(&self, kin: &Kinematics, span: f64) -> DMatrix<f64> {
        let (k, a) = self.locate(span);
        let mut jac = DMatrix::zeros(3, self.n_dofs());
        // ∂X/∂θ_j = ℓ_j n(θ_j) for j < k, a n(θ_k) for j = k; then ∂/∂q_j = Σ_{i=j}^{k} ∂/∂θ_i.
        let (mut sx, mut sy) = (0.0, 0.0);
        for j in (0..k).rev() {
            let len = if j + 1 == k { a } else { self.ell[j] };
            sx -= len * kin.sin_theta[j];
            sy += len * kin.cos_theta[j];
            jac[(0, j)] = sx;
            jac[(1, j)] = sy;
        }
        jac
    }

    /// Velocities `q̇ = M(q)⁻¹ p` into `out`, in O(n) and without forming `M(q)`: a backward
    /// Riccati sweep along the chain and a forward substitution (derivation in the source of
    /// `model::chain_solve`). Returns false, leaving `out` unspecified, if `M(q)` is not
    /// numerically positive definite. Allocates nothing.
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
    /// use flexwing::model::{FullModel, StructuralModel};
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let model = FullModel::new(Beam::new(1.0, &section, &Discretization::Uniform(4), Calibration::TipLoad)?);
    /// let mut ws = model.workspace();
    /// let (q, qdot) = ([0.1, -0.2, 0.3, 0.0], [1.0, 2.0, -1.0, 0.5]);
    /// let mut p = [0.0; 4];
    /// model.momentum_into(&q, &qdot, &mut p);
    /// let mut v = [0.0; 4];
    /// assert!(model.solve_mass_into(&q, &p, &mut ws, &mut v));
    /// assert!(v.iter().zip(&qdot).all(|(a, b)| (a - b).abs() < 1e-12));
    /// # Ok::<(), flexwing::InputError>(())
    /// ```
    ///
    /// # Panics
    /// If a slice length differs from `n_dofs()`.
    pub fn solve_mass_into(
        &self,
        q: &[f64],
        p: &[f64],
        ws: &mut Workspace,
        out: &mut [f64],
    ) -> bool {
        let nd = self.n_dofs();
        assert!(
            q.len() == nd && p.len() == nd && out.len() == nd,
            "slices must have n_dofs entries"
        );
        ws.configure(self, q);
        self.solve_mass_configured(&ws.kinetic, p, &mut ws.chain, out)
    }

    /// Diagonal of `M(q)⁻¹`, or `None` if `M(q)` is not positive definite: one chain
    /// factorization and one forward sweep of covariances, O(n) time and memory
    /// (`model/chain_solve.rs`, "The diagonal of `M⁻¹` in O(n)"). Used once per run to give
    /// momentum tolerances their meaning (`EquationsOfMotion::state_atol`).
    pub fn inverse_mass_diagonal(&self, q: &[f64], ws: &mut Workspace) -> Option<Vec<f64>> {
        let nd = self.n_dofs();
        assert_eq!(q.len(), nd, "q must have n_dofs entries");
        ws.configure(self, q);
        if !self.factor_mass_configured(&ws.kinetic, &mut ws.chain) {
            return None;
        }
        let mut diagonal = vec![0.0; nd];
        self.inverse_diagonal_factored(&ws.kinetic, &ws.chain, &mut diagonal);
        Some(diagonal)
    }

    /// Jacobian `∂g_i/∂q` (3 × `n_dofs`) of the mass centre of element `i` (0-based).
    pub fn mass_centre_jacobian(&self, kin: &Kinematics, i: usize) -> DMatrix<f64> {
        let mut jac = DMatrix::zeros(3, self.n_dofs());
        let (c, s) = (kin.cos_theta[i], kin.sin_theta[i]);
        let (cp, sp) = (kin.cos_psi[i], kin.sin_psi[i]);
        let d = self.d0[i];
        // ∂g_i/∂θ_i = (ℓ_i/2) n_i − d0 sin ψ_i e_i.
        let mut sx = -0.5 * self.ell[i] * s - d * sp * c;
        let mut sy = 0.5 * self.ell[i] * c - d * sp * s;
        jac[(0, i)] = sx;
        jac[(1, i)] = sy;
        for j in (0..i).rev() {
            sx -= self.ell[j] * kin.sin_theta[j];
            sy += self.ell[j] * kin.cos_theta[j];
            jac[(0, j)] = sx;
            jac[(1, j)] = sy;
        }
        if self.torsion {
            // ∂g_i/∂ψ_i = d0 (cos ψ_i n_i − sin ψ_i ẑ), the same for every q_{n+j}, j ≤ i.
            let col = [-d * cp * s, d * cp * c, -d * sp];
            for j in 0..=i {
                for r in 0..3 {
                    jac[(r, self.n + j)] = col[r];
                }
            }
        }
        jac
    }
}

/// From this many coordinates on, the Jacobian's kinetic part is taken from dual-number velocity
/// solves (O(n²)) instead of `B = ∂(M q̇)/∂q` and a matrix product (O(n³) with a small constant).
const DUAL_SOLVE_MIN_DOFS: usize = 128;

/// Scratch buffers of the full model: the kinematics of the current configuration and the
/// per-element load resultants.
#[derive(Debug, Clone)]
pub struct Workspace {
    pub(super) kin: Kinematics,
    pub(super) resultants: Resultants,
    pub(super) dir: Vec<f64>,
    pub(super) kinetic: KineticScratch<f64>,
    /// Configuration whose trigonometry `kinetic` holds (NaN: none yet).
    pub(super) kinetic_at: Vec<f64>,
    pub(super) duals: KineticBuffers,
    pub(super) chain: ChainScratch<f64>,
    pub(super) identity: DMatrix<f64>,
}

impl Workspace {
    /// Make the kinematics and the kinetic scratch hold the trigonometry of `q`, unless they
    /// already do: one set of sines and cosines per configuration, shared by the mass matrix,
    /// the velocity solve, the kinetic recursions and the loads.
    pub(super) fn configure(&mut self, model: &FullModel, q: &[f64]) {
        if self.kinetic_at.as_slice() != q {
            self.kin.update(q);
            model.configure_from(&self.kin, &mut self.kinetic);
            self.kinetic_at.copy_from_slice(q);
        }
    }

    /// The kinematics of the last configuration evaluated.
    pub fn kinematics(&self) -> &Kinematics {
        &self.kin
    }
}

impl StructuralModel for FullModel {
    type Workspace = Workspace;

    fn workspace(&self) -> Workspace {
        Workspace {
            kin: Kinematics::new(self.n),
            resultants: Resultants::zeros(self.n),
            dir: vec![0.0; self.n_dofs()],
            kinetic: KineticScratch::new(self.n),
            kinetic_at: vec![f64::NAN; self.n_dofs()],
            duals: KineticBuffers::new(self),
            chain: ChainScratch::new(self.n),
            // Allocated on first use by the dense derivatives (n² entries).
            identity: DMatrix::zeros(0, 0),
        }
    }

    fn n_dofs(&self) -> usize {
        FullModel::n_dofs(self)
    }

    fn mass_matrix_into(&self, q: &[f64], ws: &mut Workspace, out: &mut DMatrix<f64>) {
        ws.configure(self, q);
        self.mass_matrix_kin_into(&ws.kin, out);
    }

    fn stiffness_matrix(&self) -> DMatrix<f64> {
        DMatrix::from_diagonal(&DVector::from_column_slice(&self.stiffness))
    }

    fn generalized_forces_into(
        &self,
        q: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Workspace,
        out: &mut DVector<f64>,
    ) {
        ws.configure(self, q);
        ws.resultants.update(self, &ws.kin, loads, scales);
        self.forces_from(&ws.kin, &ws.resultants, out);
    }

    fn load_jacobian_into(
        &self,
        q: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Workspace,
        out: &mut DMatrix<f64>,
    ) {
        ws.configure(self, q);
        ws.resultants.update(self, &ws.kin, loads, scales);
        self.jacobian_from(&ws.kin, &ws.resultants, &mut ws.dir, out);
    }

    fn momentum_into(&self, q: &[f64], qdot: &[f64], ws: &mut Workspace, out: &mut [f64]) {
        ws.configure(self, q);
        self.kinetic_terms_configured(qdot, &mut ws.kinetic, Some(out), None);
    }

    fn velocities_into(&self, q: &[f64], p: &[f64], ws: &mut Workspace, out: &mut [f64]) -> bool {
        self.solve_mass_into(q, p, ws, out)
    }

    fn velocities_block_into(
        &self,
        q: &[f64],
        p: &DMatrix<f64>,
        ws: &mut Workspace,
        out: &mut DMatrix<f64>,
    ) -> bool {
        assert_eq!(p.shape(), out.shape(), "output block has the wrong shape");
        ws.configure(self, q);
        if !self.factor_mass_configured(&ws.kinetic, &mut ws.chain) {
            return false;
        }
        for c in 0..p.ncols() {
            let col = out.column_mut(c).data.into_slice_mut();
            self.solve_factored(&ws.kinetic, &mut ws.chain, p.column(c).as_slice(), col);
        }
        true
    }

    fn gyroscopic_into(&self, q: &[f64], qdot: &[f64], ws: &mut Workspace, out: &mut [f64]) {
        ws.configure(self, q);
        self.kinetic_terms_configured(qdot, &mut ws.kinetic, None, Some(out));
    }

    fn kinetic_derivatives_into(
        &self,
        q: &[f64],
        qdot: &[f64],
        ws: &mut Workspace,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        let nd = self.n_dofs();
        if ws.identity.nrows() != nd {
            ws.identity = DMatrix::identity(nd, nd);
        }
        self.kinetic_directional(q, qdot, &ws.identity, &mut ws.duals, dp, dgamma);
    }

    fn hamiltonian_derivatives_into(
        &self,
        q: &[f64],
        p: &[f64],
        ws: &mut Workspace,
        with_gamma: bool,
        dxdx: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) -> bool {
        // Both are exact. The dual-number solves are O(n²) but cost about 4 times a dense product
        // per entry; measured crossover (benches/eom.rs) between 80 and 160 coordinates.
        if self.n_dofs() < DUAL_SOLVE_MIN_DOFS {
            super::hamiltonian_derivatives_dense(self, q, p, ws, with_gamma, dxdx, dgamma)
        } else {
            self.hamiltonian_directional(q, p, &mut ws.duals, with_gamma, dxdx, dgamma)
        }
    }

    fn full_coordinates(&self, x: &[f64]) -> Vec<f64> {
        x.to_vec()
    }

    fn as_full_model(&self) -> Option<&FullModel> {
        Some(self)
    }

    fn element_rotations(&self, dx: &[f64]) -> Vec<f64> {
        super::planar_element_rotations(dx, self.n_elements())
    }
}
