//! The non-linear reduced-order model (model.md, "Reduced-order model"): `q ≈ Φ_r η`.
//!
//! Evaluation. Everything is done in absolute angles with the constant absolute mode shapes
//! `Φ_abs = T Φ` (prefix sums, precomputed), so that no suffix sums are needed: `Φᵀ Tᵀ v =
//! Φ_absᵀ v`. At a new `η` the workspace computes once, and caches for further evaluations at the
//! same `η`: the absolute angles `Φ_abs η` and their sines and cosines (shared with the loads; one
//! reduction for each pair, `kinematics::sin_cos`), the mass-centre velocity
//! of every element per unit modal rate, `G_i^c = ∂ġ_i/∂η̇_c` (one forward sweep per mode), the
//! reduced mass matrix `M_r,ab = Σ_i m_i G_i^a · G_i^b + J_i ψ̇_i^a ψ̇_i^b` and its Cholesky
//! factor. Then `p_r = M_r η̇`, `ġ_i` (the forward sweep once on the absolute rates `Φ_abs η̇`)
//! and `γ_r = Φ_absᵀ γ_abs` (one backward sweep) cost O(n r) each, and `Q_r = Φ_absᵀ Q_abs` reuses the trigonometry.

use nalgebra::{DMatrix, DVector};

use super::kinematics::sin_cos;
use super::{AppliedLoads, FullModel, StructuralModel, Workspace};
use crate::error::InputError;
use crate::solve::Damping;

/// The full model projected on `r` of its natural modes: `M_r(η) = Φᵀ M(Φη) Φ`, `K_r = Φᵀ K Φ`,
/// `Q_r = Φᵀ Q(Φη)`. Positions and displacements are always recovered through `q = Φ η`, so the
/// reduced model keeps the full geometric non-linearity.
#[derive(Debug, Clone)]
pub struct ReducedModel {
    full: FullModel,
    phi: DMatrix<f64>,
    indices: Vec<usize>,
    k_r: DMatrix<f64>,
    /// `Φ_abs = T Φ`: absolute angle rates per unit modal rate.
    phi_abs: DMatrix<f64>,
    /// The configuration-independent part of the reduced mass matrix: the polar inertias of
    /// the structure and the fluid, `Σ_i (J_i + J_f,i) ψ̇_a,i ψ̇_b,i`, and the rotary inertias in
    /// bending, `Σ_i J_b,i θ̇_a,i θ̇_b,i`, per unit modal rates.
    mass_constant: DMatrix<f64>,
}

impl ReducedModel {
    /// Project `full` on the columns `indices` (0-based) of `shapes`, the mass-normalized mode
    /// shapes as columns (`Modes::shapes()`).
    ///
    /// # Errors
    /// No index, a repeated index, or one beyond the number of modes (field `indices`).
    ///
    /// # Panics
    /// If `shapes` does not have `full.n_dofs()` rows.
    pub fn new(
        full: &FullModel,
        shapes: &DMatrix<f64>,
        indices: &[usize],
    ) -> Result<Self, InputError> {
        assert_eq!(
            shapes.nrows(),
            full.n_dofs(),
            "mode shapes of another model"
        );
        let f = "indices";
        if indices.is_empty() {
            return Err(InputError::new(f, "needs at least one mode"));
        }
        for (i, &k) in indices.iter().enumerate() {
            if k >= shapes.ncols() {
                return Err(InputError::new(
                    f,
                    format!(
                        "mode {} is out of range: the model has {} modes",
                        k + 1,
                        shapes.ncols()
                    ),
                ));
            }
            if indices[..i].contains(&k) {
                return Err(InputError::new(
                    f,
                    format!("mode {} is listed twice", k + 1),
                ));
            }
        }
        let nd = full.n_dofs();
        let mut phi = DMatrix::zeros(nd, indices.len());
        for (c, &k) in indices.iter().enumerate() {
            phi.set_column(c, &shapes.column(k));
        }
        let k_diag = DVector::from_column_slice(full.stiffness());
        let kphi = DMatrix::from_fn(nd, indices.len(), |r, c| k_diag[r] * phi[(r, c)]);
        let k_r = phi.transpose() * kphi;
        let mut phi_abs = phi.clone();
        for mut col in phi_abs.column_iter_mut() {
            for block in col.as_mut_slice().chunks_mut(full.n_elements()) {
                for i in 1..block.len() {
                    block[i] += block[i - 1];
                }
            }
        }
        // The configuration-independent inertias per absolute rate: rotary inertias in bending
        // (θ̇ rows), polar inertias of the structure and the fluid (ψ̇ rows); then
        // `mass_constant = Φ_absᵀ diag(w) Φ_abs`.
        let n = full.n_elements();
        let fluid = full.fluid.as_ref().map(|f| f.inertia.as_slice());
        let w: Vec<f64> = (0..full.n_dofs())
            .map(|k| match k.checked_sub(n) {
                None => full.rotary[k],
                Some(i) => full.inertia[i] + fluid.map_or(0.0, |f| f[i]),
            })
            .collect();
        let r = indices.len();
        let mass_constant = DMatrix::from_fn(r, r, |a, b| {
            (0..w.len())
                .map(|k| w[k] * phi_abs[(k, a)] * phi_abs[(k, b)])
                .sum::<f64>()
        });
        Ok(Self {
            full: full.clone(),
            phi,
            indices: indices.to_vec(),
            k_r,
            phi_abs,
            mass_constant,
        })
    }

    /// Project on the first `r` columns of `shapes`.
    ///
    /// # Errors
    /// `r = 0` or `r` larger than the number of modes (field `r`).
    ///
    /// ```
    /// use flexwing::beam::{Beam, Calibration, Discretization, Profile, SectionProperties};
    /// use flexwing::{model::{FullModel, ReducedModel}, solve::Modes};
    /// let section = SectionProperties {
    ///     ei: Profile::Uniform(50.0),
    ///     mass_per_length: Profile::Uniform(0.2),
    ///     torsion: None,
    /// };
    /// let full = FullModel::new(Beam::new(1.0, &section, &Discretization::Uniform(20), Calibration::TipLoad)?);
    /// let rom = ReducedModel::first(&full, Modes::undeformed(&full)?.shapes(), 3)?;
    /// assert_eq!(rom.n_modes(), 3);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn first(full: &FullModel, shapes: &DMatrix<f64>, r: usize) -> Result<Self, InputError> {
        if r == 0 || r > shapes.ncols() {
            return Err(InputError::new(
                "r",
                format!(
                    "must be between 1 and {} (the number of modes), got {r}",
                    shapes.ncols()
                ),
            ));
        }
        Self::new(full, shapes, &(0..r).collect::<Vec<_>>())
    }

    /// Modal coordinates `η = Φᵀ M(0) q` of joint rotations `q`: the mass-orthogonal projection,
    /// exact when `q` lies in the span of the basis. O(n r): `M(0) q` by the momentum recursion.
    pub fn reduce_coordinates(&self, q: &[f64]) -> Vec<f64> {
        let nd = self.full.n_dofs();
        let mut mq = vec![0.0; nd];
        self.full.momentum_into(&vec![0.0; nd], q, &mut mq);
        (self.phi.transpose() * DVector::from_column_slice(&mq))
            .as_slice()
            .to_vec()
    }

    /// Number of retained modes `r`.
    pub fn n_modes(&self) -> usize {
        self.indices.len()
    }
    /// 0-based indices of the retained modes.
    pub fn mode_indices(&self) -> &[usize] {
        &self.indices
    }
    /// The projection basis `Φ_r` (`n_dofs(full) × r`).
    pub fn basis(&self) -> &DMatrix<f64> {
        &self.phi
    }
    /// The full model projected.
    pub fn full(&self) -> &FullModel {
        &self.full
    }
}

/// Scratch buffers of a reduced model: those of the full model, full-size intermediates, and
/// the cache of the last configuration `η` (module documentation).
#[derive(Debug, Clone)]
pub struct ReducedWorkspace {
    full: Workspace,
    q: Vec<f64>,
    qdot: Vec<f64>,
    f: DVector<f64>,
    block: DMatrix<f64>,
    block2: DMatrix<f64>,
    column: Vec<f64>,
    /// The `η` the cache below belongs to (NaN: none yet).
    at: Vec<f64>,
    /// The components of `G_i^c = ∂ġ_i/∂η̇_c` at `element + n · mode`, one vector each (`gz`
    /// stays zero without torsion).
    gx: Vec<f64>,
    gy: Vec<f64>,
    gz: Vec<f64>,
    /// The fluid's normal velocity `u_i` per unit modal rate (`model::aero::fluid`), same
    /// layout; empty in vacuo.
    fluid_u: Vec<f64>,
    /// Reduced mass matrix `M_r(η)`.
    mass: DMatrix<f64>,
    /// Its Cholesky factor (lower triangle), valid if `factored`.
    factor: DMatrix<f64>,
    factored: bool,
}

/// `out = Φ_absᵀ v` for the first `v.len()` rows of `phi`.
fn project(phi: &DMatrix<f64>, v: &[f64], out: &mut [f64]) {
    let rows = phi.nrows();
    for (c, o) in out.iter_mut().enumerate() {
        let col = &phi.as_slice()[c * rows..c * rows + v.len()];
        *o = col.iter().zip(v).map(|(a, b)| a * b).sum();
    }
}

impl ReducedModel {
    fn expand(&self, eta: &[f64], q: &mut [f64]) {
        q.fill(0.0);
        for (col, &e) in self.phi.as_slice().chunks_exact(q.len()).zip(eta) {
            for (qi, p) in q.iter_mut().zip(col) {
                *qi += p * e;
            }
        }
    }

    /// Bring the cache of `ws` to the configuration `eta` (no work if it is there already).
    fn configure(&self, eta: &[f64], ws: &mut ReducedWorkspace) {
        if ws.at.as_slice() == eta {
            return;
        }
        let full = &self.full;
        let n = full.n;
        let nd = full.n_dofs();
        let pa = self.phi_abs.as_slice();
        // Absolute angles `θ = Φ_abs η` straight from the absolute modes (no joint rotations,
        // no prefix sums), then their sines and cosines by one reduction each
        // (`kinematics::sin_cos`), written where the loads (`kin`) and the kinetic sweeps
        // (`kinetic`) read them.
        let kin = &mut ws.full.kin;
        combine(pa, nd, 0, eta, &mut kin.theta);
        if full.torsion {
            combine(pa, nd, n, eta, &mut kin.psi);
        }
        let sc = &mut ws.full.kinetic;
        for i in 0..n {
            let (s, c) = sin_cos(kin.theta[i]);
            (kin.sin_theta[i], kin.cos_theta[i]) = (s, c);
            (sc.sin_theta[i], sc.cos_theta[i]) = (s, c);
        }
        if full.torsion {
            for i in 0..n {
                let (s, c) = sin_cos(kin.psi[i]);
                (kin.sin_psi[i], kin.cos_psi[i]) = (s, c);
                (sc.sin_psi[i], sc.cos_psi[i]) = (s, c);
            }
        }
        let kin = &ws.full.kin;
        let r = eta.len();
        let (gx, gy, gz) = (&mut ws.gx, &mut ws.gy, &mut ws.gz);
        // Mass-centre velocity per unit modal rate (model::kinetic's forward sweep), one mode
        // at a time; bending only, the ψ terms vanish (sin ψ = 0, ψ̇ = 0) and `gz` stays 0.
        for c in 0..r {
            let col = &pa[c * nd..(c + 1) * nd];
            let (gx, gy) = (&mut gx[c * n..(c + 1) * n], &mut gy[c * n..(c + 1) * n]);
            let mut v = [0.0; 2];
            if !full.torsion && full.fluid.is_none() {
                for i in 0..n {
                    let (co, si) = (kin.cos_theta[i], kin.sin_theta[i]);
                    let (l, td) = (full.ell[i], col[i]);
                    let a_n = 0.5 * l * td;
                    gx[i] = v[0] - a_n * si;
                    gy[i] = v[1] + a_n * co;
                    v[0] -= l * si * td;
                    v[1] += l * co * td;
                }
                continue;
            }
            for i in 0..n {
                let (co, si) = (kin.cos_theta[i], kin.sin_theta[i]);
                let (cp, sp) = (kin.cos_psi[i], kin.sin_psi[i]);
                let td = col[i];
                let pd = if full.torsion { col[n + i] } else { 0.0 };
                let (l, d) = (full.ell[i], full.d0[i]);
                let a_n = 0.5 * l * td + d * cp * pd;
                let a_e = -d * sp * td;
                gx[i] = v[0] + a_e * co - a_n * si;
                gy[i] = v[1] + a_e * si + a_n * co;
                gz[c * n + i] = -d * sp * pd;
                if let Some(f) = &full.fluid {
                    let u = cp * (co * v[1] - si * v[0] + 0.5 * l * td) + f.station[i] * pd;
                    ws.fluid_u[c * n + i] = u;
                }
                v[0] -= l * si * td;
                v[1] += l * co * td;
            }
        }
        // `M_r,ab = Σ_i m_i G_i^a · G_i^b` (+ the fluid's `Σ m_a,i u_i^a u_i^b`), O(n r²):
        // slices of one component each, which vectorize. The polar and rotary inertias' part
        // does not depend on the configuration (`mass_constant`).
        // Four running sums (independent chains, which the compiler keeps in one vector
        // register) instead of one: a single sum waited on its addition's latency at every
        // element, half of `configure` at n = 80, r = 6 by `perf`.
        let dot = |w: &[f64], a: &[f64], b: &[f64]| -> f64 {
            let mut lanes = [0.0; 4];
            let (wc, ac, bc) = (w.chunks_exact(4), a.chunks_exact(4), b.chunks_exact(4));
            let tail: f64 = wc
                .remainder()
                .iter()
                .zip(ac.remainder())
                .zip(bc.remainder())
                .map(|((w, a), b)| w * a * b)
                .sum();
            for ((w, a), b) in wc.zip(ac).zip(bc) {
                for k in 0..4 {
                    lanes[k] += w[k] * a[k] * b[k];
                }
            }
            (lanes[0] + lanes[1]) + (lanes[2] + lanes[3]) + tail
        };
        fn part(v: &[f64], a: usize, n: usize) -> &[f64] {
            &v[a * n..(a + 1) * n]
        }
        for a in 0..r {
            for b in a..r {
                let mut m: f64 = self.mass_constant[(a, b)];
                m += dot(&full.mass, part(&ws.gx, a, n), part(&ws.gx, b, n));
                m += dot(&full.mass, part(&ws.gy, a, n), part(&ws.gy, b, n));
                if full.torsion {
                    m += dot(&full.mass, part(&ws.gz, a, n), part(&ws.gz, b, n));
                }
                if let Some(f) = &full.fluid {
                    m += dot(&f.mass, part(&ws.fluid_u, a, n), part(&ws.fluid_u, b, n));
                }
                ws.mass[(a, b)] = m;
                ws.mass[(b, a)] = m;
            }
        }
        ws.factor.copy_from(&ws.mass);
        ws.factored = cholesky_in_place(&mut ws.factor);
        ws.at.copy_from_slice(eta);
    }

    /// Rates and mass-centre velocities of the modal rates `etadot` into the kinetic scratch,
    /// at the configuration of the last [`Self::configure`]: the absolute rates `Φ_abs η̇`
    /// (O(n r)), then the mass-centre and node velocities by the forward sweep of
    /// `configure` run once on those rates (O(n)) instead of `Σ_c η̇_c G^c` (O(n r) per
    /// component).
    fn set_rates(&self, etadot: &[f64], ws: &mut ReducedWorkspace) {
        let full = &self.full;
        let n = full.n;
        let nd = full.n_dofs();
        let pa = self.phi_abs.as_slice();
        let sc = &mut ws.full.kinetic;
        combine(pa, nd, 0, etadot, &mut sc.theta_dot);
        if full.torsion {
            combine(pa, nd, n, etadot, &mut sc.psi_dot);
        }
        let mut v = [0.0; 2];
        for i in 0..n {
            let (co, si) = (sc.cos_theta[i], sc.sin_theta[i]);
            let (cp, sp) = (sc.cos_psi[i], sc.sin_psi[i]);
            let (l, d, td, pd) = (full.ell[i], full.d0[i], sc.theta_dot[i], sc.psi_dot[i]);
            let a_n = 0.5 * l * td + d * cp * pd;
            let a_e = -d * sp * td;
            sc.g_dot[i] = [
                v[0] + a_e * co - a_n * si,
                v[1] + a_e * si + a_n * co,
                -d * sp * pd,
            ];
            if let Some(f) = &full.fluid {
                sc.node_v[i] = v;
                sc.fluid_u[i] = cp * (co * v[1] - si * v[0] + 0.5 * l * td) + f.station[i] * pd;
            }
            v[0] -= l * si * td;
            v[1] += l * co * td;
        }
    }
}

/// `out = Σ_c w_c Φ_abs[offset.., c]` over the first `out.len()` rows from `offset`: absolute
/// angles (offset 0: bending, n: torsion) or their rates of modal coordinates or rates `w`.
fn combine(pa: &[f64], rows: usize, offset: usize, w: &[f64], out: &mut [f64]) {
    out.fill(0.0);
    for (c, &e) in w.iter().enumerate() {
        let col = &pa[c * rows + offset..c * rows + offset + out.len()];
        for (o, p) in out.iter_mut().zip(col) {
            *o += e * p;
        }
    }
}

impl StructuralModel for ReducedModel {
    type Workspace = ReducedWorkspace;

    fn workspace(&self) -> ReducedWorkspace {
        let nd = self.full.n_dofs();
        let r = self.phi.ncols();
        let mut full = self.full.workspace();
        // Bending only, `configure` never writes the twists' trigonometry: ψ = 0.
        full.kinetic.cos_psi.fill(1.0);
        ReducedWorkspace {
            full,
            q: vec![0.0; nd],
            qdot: vec![0.0; nd],
            f: DVector::zeros(nd),
            block: DMatrix::zeros(nd, r),
            block2: DMatrix::zeros(nd, r),
            column: vec![0.0; nd],
            at: vec![f64::NAN; r],
            gx: vec![0.0; self.full.n * r],
            gy: vec![0.0; self.full.n * r],
            gz: vec![0.0; self.full.n * r],
            fluid_u: if self.full.fluid.is_some() {
                vec![0.0; self.full.n * r]
            } else {
                Vec::new()
            },
            mass: DMatrix::zeros(r, r),
            factor: DMatrix::zeros(r, r),
            factored: false,
        }
    }

    fn n_dofs(&self) -> usize {
        self.indices.len()
    }

    fn mass_matrix_into(&self, eta: &[f64], ws: &mut ReducedWorkspace, out: &mut DMatrix<f64>) {
        self.configure(eta, ws);
        out.copy_from(&ws.mass);
    }

    fn momentum_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) {
        self.configure(eta, ws);
        for (a, o) in out.iter_mut().enumerate() {
            *o = (0..etadot.len()).map(|b| ws.mass[(a, b)] * etadot[b]).sum();
        }
    }

    fn velocities_into(
        &self,
        eta: &[f64],
        p: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) -> bool {
        self.configure(eta, ws);
        if ws.factored {
            out.copy_from_slice(p);
            cholesky_solve(&ws.factor, out);
        }
        ws.factored
    }

    fn gyroscopic_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) {
        self.configure(eta, ws);
        self.set_rates(etadot, ws);
        self.full
            .kinetic_backward(&ws.full.kinetic, None, Some(&mut ws.column));
        project(&self.phi_abs, &ws.column, out);
    }

    fn kinetic_derivatives_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        // Φᵀ (∂p/∂q) Φ and Φᵀ (∂γ/∂q) Φ, the inner products along the r columns of Φ: O(n r²).
        self.expand(eta, &mut ws.q);
        self.expand(etadot, &mut ws.qdot);
        self.full.kinetic_directional(
            &ws.q,
            &ws.qdot,
            &self.phi,
            &mut ws.full.duals,
            &mut ws.block,
            &mut ws.block2,
        );
        self.phi.tr_mul_to(&ws.block, dp);
        self.phi.tr_mul_to(&ws.block2, dgamma);
    }

    fn stiffness_matrix(&self) -> DMatrix<f64> {
        self.k_r.clone()
    }

    fn generalized_forces_into(
        &self,
        eta: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut DVector<f64>,
    ) {
        self.configure(eta, ws);
        let full = &mut ws.full;
        full.resultants.update(&self.full, &full.kin, loads, scales);
        self.full
            .forces_abs_from(&full.kin, &full.resultants, ws.f.as_mut_slice());
        project(&self.phi_abs, ws.f.as_slice(), out.as_mut_slice());
    }

    fn load_jacobian_into(
        &self,
        eta: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut DMatrix<f64>,
    ) {
        // Φᵀ (∂Q/∂q Φ): the product is formed column by column in O(n r), never ∂Q/∂q itself.
        self.configure(eta, ws);
        let full = &mut ws.full;
        full.resultants.update(&self.full, &full.kin, loads, scales);
        self.full.jacobian_times_from(
            &full.kin,
            &full.resultants,
            &self.phi,
            &mut full.dir,
            &mut ws.block,
        );
        self.phi.tr_mul_to(&ws.block, out);
    }

    fn full_coordinates(&self, eta: &[f64]) -> Vec<f64> {
        let mut q = vec![0.0; self.full.n_dofs()];
        self.expand(eta, &mut q);
        q
    }

    fn element_rotations(&self, deta: &[f64]) -> Vec<f64> {
        let dq = self.full_coordinates(deta);
        super::planar_element_rotations(&dq, self.full.n_elements())
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

/// The damping of a reduced model: the projection of the full model's.
impl ReducedModel {
    /// The damping of this model that projects the full model's `damping`, `C_r = Φ_rᵀ C Φ_r`.
    ///
    /// Rayleigh damping projects onto itself (`Φᵀ M(0) Φ = M_r(0)`, `Φᵀ K Φ = K_r`). Modal damping
    /// `C = M₀ Φ diag(2 ζ_k ω_k) Φᵀ M₀` projects onto `diag(2 ζ_k ω_k)` over the retained modes,
    /// but [`Damping::Modal`] numbers a model's ratios by that model's own modes, which for a
    /// reduced model are the retained modes in order of frequency: so mode `j` of the reduced
    /// model gets the ratio of the `j`-th smallest retained index (0 if `damping` gives none for
    /// it).
    pub fn project_damping(&self, damping: &Damping) -> Damping {
        match damping {
            Damping::Modal { ratios } => {
                let mut sorted = self.indices.clone();
                sorted.sort_unstable();
                Damping::Modal {
                    ratios: sorted
                        .iter()
                        .map(|&k| ratios.get(k).copied().unwrap_or(0.0))
                        .collect(),
                }
            }
            other => other.clone(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::{Force, Load};
    use crate::solve::Modes;

    /// The cached, absolute-angle evaluation of the reduced terms against the definitions
    /// `Φᵀ (full-model term)(Φ η, Φ η̇)`, at alternating configurations (so that a stale cache
    /// would show), with and without torsion.
    #[test]
    fn reduced_terms_are_the_projected_full_terms() {
        for torsion in [false, true] {
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
            let beam = Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(7),
                Calibration::TipLoad,
            )
            .unwrap();
            let full = FullModel::new(beam);
            let loads = full
                .apply(
                    &[
                        Load::PointForce {
                            span: 1.3,
                            force: Force::Follower {
                                tangential: 0.4,
                                normal: 2.0,
                            },
                        },
                        Load::Gravity { g: 9.81 },
                    ],
                    "loads",
                )
                .unwrap();
            let scales = [0.7, 1.0];
            let rom =
                ReducedModel::first(&full, Modes::undeformed(&full).unwrap().shapes(), 3).unwrap();
            let (nd, r) = (full.n_dofs(), 3);
            let mut ws = rom.workspace();
            let mut fws = full.workspace();
            for k in 0..4 {
                let s = if k % 2 == 0 { 1.0 } else { -0.6 };
                let eta = [0.4 * s, -0.2, 0.1 * s];
                let etadot = [1.0, 0.5 * s, -2.0];
                let q = rom.full_coordinates(&eta);
                let qdot = rom.full_coordinates(&etadot);
                let phi = rom.basis();
                let mut m = DMatrix::zeros(nd, nd);
                full.mass_matrix_into(&q, &mut fws, &mut m);
                let m_r = phi.transpose() * &m * phi;
                let mut got = DMatrix::zeros(r, r);
                rom.mass_matrix_into(&eta, &mut ws, &mut got);
                assert!((&got - &m_r).amax() < 1e-12 * m_r.amax());
                let mut v = vec![0.0; nd];
                StructuralModel::gyroscopic_into(&full, &q, &qdot, &mut fws, &mut v);
                let gamma = phi.transpose() * DVector::from_column_slice(&v);
                let mut g = vec![0.0; r];
                rom.gyroscopic_into(&eta, &etadot, &mut ws, &mut g);
                let mut f = DVector::zeros(nd);
                full.generalized_forces_into(&q, &loads, &scales, &mut fws, &mut f);
                let force = phi.transpose() * f;
                let mut fr = DVector::zeros(r);
                rom.generalized_forces_into(&eta, &loads, &scales, &mut ws, &mut fr);
                let mut p = vec![0.0; r];
                rom.momentum_into(&eta, &etadot, &mut ws, &mut p);
                let mut back = vec![0.0; r];
                assert!(rom.velocities_into(&eta, &p, &mut ws, &mut back));
                for a in 0..r {
                    assert!((g[a] - gamma[a]).abs() < 1e-12 * (1.0 + gamma.amax()));
                    assert!((fr[a] - force[a]).abs() < 1e-12 * (1.0 + force.amax()));
                    let pa: f64 = (0..r).map(|b| m_r[(a, b)] * etadot[b]).sum();
                    assert!((p[a] - pa).abs() < 1e-12 * m_r.amax());
                    assert!((back[a] - etadot[a]).abs() < 1e-10);
                }
            }
        }
    }

    #[test]
    fn modal_damping_of_a_reduced_model_follows_its_modes() {
        let full = crate::paper::table4_beam(6).unwrap();
        let modes = crate::solve::Modes::undeformed(&full).unwrap();
        let rom = ReducedModel::new(&full, modes.shapes(), &[4, 0, 2]).unwrap();
        let d = Damping::Modal {
            ratios: vec![0.1, 0.2, 0.3],
        };
        let Damping::Modal { ratios } = rom.project_damping(&d) else {
            panic!("not modal")
        };
        assert_eq!(ratios, [0.1, 0.3, 0.0]);
        let r = Damping::Rayleigh {
            alpha: 1.0,
            beta: 2.0,
        };
        assert_eq!(rom.project_damping(&r), r);
    }
}
