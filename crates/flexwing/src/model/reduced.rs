//! The non-linear reduced-order model (model.md, "Reduced-order model"): `q ≈ Φ_r η`.

use nalgebra::{DMatrix, DVector};

use super::{AppliedLoads, FullModel, StructuralModel, Workspace};
use crate::error::InputError;

/// The full model projected on `r` of its natural modes: `M_r(η) = Φᵀ M(Φη) Φ`, `K_r = Φᵀ K Φ`,
/// `Q_r = Φᵀ Q(Φη)`. Positions and displacements are always recovered through `q = Φ η`, so the
/// reduced model keeps the full geometric non-linearity.
#[derive(Debug, Clone)]
pub struct ReducedModel {
    full: FullModel,
    phi: DMatrix<f64>,
    indices: Vec<usize>,
    k_r: DMatrix<f64>,
}

impl ReducedModel {
    /// Project `full` on the columns `indices` (0-based) of `shapes`, the mass-normalized mode
    /// shapes as columns (`Modes::shapes()`).
    ///
    /// # Errors
    /// No index, a repeated index, or one beyond the number of modes (field `reduced.modes`).
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
        let f = "reduced.modes";
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
        Ok(Self {
            full: full.clone(),
            phi,
            indices: indices.to_vec(),
            k_r,
        })
    }

    /// Project on the first `r` columns of `shapes`.
    ///
    /// # Errors
    /// `r = 0` or `r` larger than the number of modes (field `reduced.modes`).
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
                "reduced.modes",
                format!(
                    "must be between 1 and {} (the number of modes), got {r}",
                    shapes.ncols()
                ),
            ));
        }
        Self::new(full, shapes, &(0..r).collect::<Vec<_>>())
    }

    /// Modal coordinates `η = Φᵀ M(0) q` of joint rotations `q`: the mass-orthogonal projection,
    /// exact when `q` lies in the span of the basis.
    pub fn reduce_coordinates(&self, q: &[f64]) -> Vec<f64> {
        let nd = self.full.n_dofs();
        let mut m0 = DMatrix::zeros(nd, nd);
        let mut ws = self.full.workspace();
        self.full.mass_matrix_into(&vec![0.0; nd], &mut ws, &mut m0);
        let mq = m0 * DVector::from_column_slice(q);
        (self.phi.transpose() * mq).as_slice().to_vec()
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
}

/// Scratch buffers of a reduced model: those of the full model plus full-size intermediates.
#[derive(Debug, Clone)]
pub struct ReducedWorkspace {
    full: Workspace,
    q: Vec<f64>,
    qdot: Vec<f64>,
    f: DVector<f64>,
    block: DMatrix<f64>,
    block2: DMatrix<f64>,
    column: Vec<f64>,
    /// Reduced mass matrix, then its Cholesky factor (lower triangle).
    factor: DMatrix<f64>,
}

/// `out = Φᵀ v`.
fn project(phi: &DMatrix<f64>, v: &[f64], out: &mut [f64]) {
    for (c, o) in out.iter_mut().enumerate() {
        *o = phi.column(c).iter().zip(v).map(|(a, b)| a * b).sum();
    }
}

impl ReducedModel {
    fn expand(&self, eta: &[f64], q: &mut [f64]) {
        q.fill(0.0);
        for (c, &e) in eta.iter().enumerate() {
            for (qi, p) in q.iter_mut().zip(self.phi.column(c).iter()) {
                *qi += p * e;
            }
        }
    }
}

impl StructuralModel for ReducedModel {
    type Workspace = ReducedWorkspace;

    fn workspace(&self) -> ReducedWorkspace {
        let nd = self.full.n_dofs();
        ReducedWorkspace {
            full: self.full.workspace(),
            q: vec![0.0; nd],
            qdot: vec![0.0; nd],
            f: DVector::zeros(nd),
            block: DMatrix::zeros(nd, self.phi.ncols()),
            block2: DMatrix::zeros(nd, self.phi.ncols()),
            column: vec![0.0; nd],
            factor: DMatrix::zeros(self.phi.ncols(), self.phi.ncols()),
        }
    }

    fn n_dofs(&self) -> usize {
        self.indices.len()
    }

    fn mass_matrix_into(&self, eta: &[f64], ws: &mut ReducedWorkspace, out: &mut DMatrix<f64>) {
        // Φᵀ M(q) Φ from the columns M(q) φ_c = p(q, φ_c): O(n r²), no full mass matrix, and
        // the trigonometry of q computed once for all columns.
        self.expand(eta, &mut ws.q);
        ws.full.configure(&self.full, &ws.q);
        for c in 0..self.phi.ncols() {
            self.full.kinetic_terms_configured(
                self.phi.column(c).as_slice(),
                &mut ws.full.kinetic,
                Some(&mut ws.column),
                None,
            );
            ws.block.column_mut(c).copy_from_slice(&ws.column);
        }
        self.phi.tr_mul_to(&ws.block, out);
    }

    fn momentum_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) {
        self.expand(eta, &mut ws.q);
        self.expand(etadot, &mut ws.qdot);
        ws.full.configure(&self.full, &ws.q);
        self.full.kinetic_terms_configured(
            &ws.qdot,
            &mut ws.full.kinetic,
            Some(&mut ws.column),
            None,
        );
        project(&self.phi, &ws.column, out);
    }

    fn velocities_into(
        &self,
        eta: &[f64],
        p: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) -> bool {
        let mut factor = std::mem::take(&mut ws.factor);
        self.mass_matrix_into(eta, ws, &mut factor);
        let ok = cholesky_in_place(&mut factor);
        if ok {
            out.copy_from_slice(p);
            cholesky_solve(&factor, out);
        }
        ws.factor = factor;
        ok
    }

    fn gyroscopic_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace,
        out: &mut [f64],
    ) {
        self.expand(eta, &mut ws.q);
        self.expand(etadot, &mut ws.qdot);
        ws.full.configure(&self.full, &ws.q);
        self.full.kinetic_terms_configured(
            &ws.qdot,
            &mut ws.full.kinetic,
            None,
            Some(&mut ws.column),
        );
        project(&self.phi, &ws.column, out);
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
        self.expand(eta, &mut ws.q);
        self.full
            .generalized_forces_into(&ws.q, loads, scales, &mut ws.full, &mut ws.f);
        self.phi.tr_mul_to(&ws.f, out);
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
        self.expand(eta, &mut ws.q);
        let full = &mut ws.full;
        full.kin.update(&ws.q);
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

    fn full_model(&self) -> &FullModel {
        &self.full
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
