//! The non-linear modal reduced-order model of the 3-D chain: the joints' rotation vectors
//! projected on `r` modes, `x ≈ Φ_r η`, as the paper's ROM on the planar chain
//! (`model/reduced.rs`; docs/chain3d-model.md, "Reduced-order model").
//!
//! The reduced model is the full chain's Lagrangian restricted to the span of the modes:
//! `T_r(η, η̇) = T(Φη, Φη̇)`, `V_r = ½ ηᵀ Φᵀ K Φ η`, `Q_r = Φᵀ Q(Φη)`, so that
//!
//! ```text
//! M_r(η) = Φᵀ M(Φη) Φ,   p_r = Φᵀ p(Φη, Φη̇),   γ_r = Φᵀ γ(Φη, Φη̇),   K_r = Φᵀ K Φ
//! ```
//!
//! exactly (`∂T_r/∂η = Φᵀ ∂T/∂x`), with every non-linearity of the kinematics kept: positions
//! and frames are always those of the full chain at `x = Φη`. Evaluation goes through the
//! full chain's O(n) recursions: `M_r` by `r` momentum passes (`M(x) φ_c`, O(n r) and `O(n r²)`
//! for the products), cached with its Cholesky factor per configuration; `p_r`, `γ_r`, `Q_r`
//! by one pass and one projection (O(n r)); the exact derivatives `Φᵀ (∂p/∂x) Φ`,
//! `Φᵀ (∂γ/∂x) Φ`, `Φᵀ (∂Q/∂x) Φ` by one dual-number pass along each mode (O(n r)). Exact where
//! the projection is: with every mode it is the full chain in other coordinates, and in the
//! linear limit its natural frequencies are the retained modes' own.

use nalgebra::{DMatrix, DVector};

use super::newton::Directional;
use super::{Chain3d, Workspace3d};
use crate::error::InputError;
use crate::model::{AppliedLoads, StructuralModel};
use crate::solve::Damping;

/// The 3-D chain projected on `r` of its modes: `M_r(η) = Φᵀ M(Φη) Φ`, `K_r = Φᵀ K Φ`,
/// `Q_r = Φᵀ Q(Φη)` (module documentation). The public API is [`crate::model::ReducedModel`]'s.
#[derive(Debug, Clone)]
pub struct ReducedChain3d {
    full: Chain3d,
    phi: DMatrix<f64>,
    indices: Vec<usize>,
    k_r: DMatrix<f64>,
}

impl ReducedChain3d {
    /// Project `full` on the columns `indices` (0-based) of `shapes`, the mode shapes as columns
    /// (`Modes::shapes()` of [`crate::solve::Modes::of_model`]: mass-normalized).
    ///
    /// # Errors
    /// No index, a repeated index, or one beyond the number of modes (field `indices`).
    ///
    /// # Panics
    /// If `shapes` does not have `full.n_dofs()` rows.
    pub fn new(
        full: &Chain3d,
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
        let r = indices.len();
        let mut phi = DMatrix::zeros(nd, r);
        for (c, &k) in indices.iter().enumerate() {
            phi.set_column(c, &shapes.column(k));
        }
        let mut kphi = DMatrix::zeros(nd, r);
        for c in 0..r {
            let mut col = vec![0.0; nd];
            full.stiffness_product(phi.column(c).as_slice(), &mut col);
            kphi.set_column(c, &DVector::from_vec(col));
        }
        let k_r = phi.transpose() * kphi;
        // Symmetric by construction; remove the round-off asymmetry.
        let k_r = (&k_r + k_r.transpose()) * 0.5;
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
    /// `r = 0` or `r` larger than the number of modes (field `r`).
    pub fn first(full: &Chain3d, shapes: &DMatrix<f64>, r: usize) -> Result<Self, InputError> {
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

    /// Modal coordinates `η = Φᵀ M(0) x` of joint rotation vectors `x`: the mass-orthogonal
    /// projection, exact when `x` lies in the span of the (mass-normalized) basis. O(n r).
    pub fn reduce_coordinates(&self, x: &[f64]) -> Vec<f64> {
        let nd = self.full.n_dofs();
        let mut mx = vec![0.0; nd];
        let mut ws = self.full.workspace();
        self.full.momentum_into(&vec![0.0; nd], x, &mut ws, &mut mx);
        (self.phi.transpose() * DVector::from_column_slice(&mx))
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
    /// The full 3-D chain underneath.
    pub fn full(&self) -> &Chain3d {
        &self.full
    }

    /// The damping of this model that projects the full model's `damping`, as
    /// [`crate::model::ReducedModel::project_damping`]: Rayleigh onto itself, modal onto the
    /// retained modes' ratios in order of frequency.
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

    /// `out = Φᵀ v`.
    fn project(&self, v: &[f64], out: &mut [f64]) {
        for (c, o) in out.iter_mut().enumerate() {
            *o = self.phi.column(c).iter().zip(v).map(|(a, b)| a * b).sum();
        }
    }

    /// `out = Φ η`.
    fn expand(&self, eta: &[f64], out: &mut [f64]) {
        out.fill(0.0);
        for (c, &e) in eta.iter().enumerate() {
            for (o, p) in out.iter_mut().zip(self.phi.column(c).iter()) {
                *o += e * p;
            }
        }
    }

    /// `x = Φη`, `M_r(η)` and its Cholesky factor into the workspace, unless cached.
    fn configure(&self, eta: &[f64], ws: &mut ReducedWorkspace3d) {
        if ws.at.as_slice() == eta {
            return;
        }
        let (nd, r) = (self.full.n_dofs(), self.indices.len());
        self.expand(eta, &mut ws.x);
        for c in 0..r {
            let col = self.phi.column(c);
            self.full
                .momentum_into(&ws.x, col.as_slice(), &mut ws.full, &mut ws.v);
            for a in 0..r {
                ws.mass[(a, c)] = (0..nd).map(|k| self.phi[(k, a)] * ws.v[k]).sum();
            }
        }
        let m = (&ws.mass + ws.mass.transpose()) * 0.5;
        ws.mass.copy_from(&m);
        ws.factor = m.cholesky();
        ws.at.copy_from_slice(eta);
    }
}

/// Scratch of a reduced 3-D chain: the full chain's, full-size vectors, and the cache of the
/// last configuration `η` (`M_r` and its factor).
#[derive(Debug, Clone)]
pub struct ReducedWorkspace3d {
    full: Workspace3d,
    dir: Box<Directional>,
    x: Vec<f64>,
    xdot: Vec<f64>,
    v: Vec<f64>,
    dp: Vec<f64>,
    dg: Vec<f64>,
    dq: Vec<f64>,
    f: DVector<f64>,
    /// The `η` the cache belongs to (NaN: none yet).
    at: Vec<f64>,
    mass: DMatrix<f64>,
    factor: Option<nalgebra::Cholesky<f64, nalgebra::Dyn>>,
}

impl StructuralModel for ReducedChain3d {
    type Workspace = ReducedWorkspace3d;

    fn workspace(&self) -> ReducedWorkspace3d {
        let (nd, r) = (self.full.n_dofs(), self.indices.len());
        ReducedWorkspace3d {
            full: self.full.workspace(),
            dir: Box::new(Directional::new(self.full.n_elements())),
            x: vec![0.0; nd],
            xdot: vec![0.0; nd],
            v: vec![0.0; nd],
            dp: vec![0.0; nd],
            dg: vec![0.0; nd],
            dq: vec![0.0; nd],
            f: DVector::zeros(nd),
            at: vec![f64::NAN; r],
            mass: DMatrix::zeros(r, r),
            factor: None,
        }
    }

    fn n_dofs(&self) -> usize {
        self.indices.len()
    }

    fn stiffness_matrix(&self) -> DMatrix<f64> {
        self.k_r.clone()
    }

    fn mass_matrix_into(&self, eta: &[f64], ws: &mut ReducedWorkspace3d, out: &mut DMatrix<f64>) {
        self.configure(eta, ws);
        out.copy_from(&ws.mass);
    }

    fn generalized_forces_into(
        &self,
        eta: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut ReducedWorkspace3d,
        out: &mut DVector<f64>,
    ) {
        self.expand(eta, &mut ws.x);
        self.full
            .generalized_forces_into(&ws.x, loads, scales, &mut ws.full, &mut ws.f);
        self.project(ws.f.as_slice(), out.as_mut_slice());
    }

    fn load_jacobian_into(
        &self,
        eta: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut ReducedWorkspace3d,
        out: &mut DMatrix<f64>,
    ) {
        let r = self.indices.len();
        self.expand(eta, &mut ws.x);
        ws.xdot.fill(0.0);
        let zeros = vec![0.0; self.full.n_dofs()];
        let mut col = vec![0.0; r];
        for c in 0..r {
            self.full.directional(
                &mut ws.dir,
                (&ws.x, &ws.xdot),
                (self.phi.column(c).as_slice(), &zeros),
                Some((loads, scales)),
                false,
                (&mut ws.dp, &mut ws.dg, &mut ws.dq),
            );
            self.project(&ws.dq, &mut col);
            out.set_column(c, &DVector::from_column_slice(&col));
        }
    }

    fn momentum_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace3d,
        out: &mut [f64],
    ) {
        self.expand(eta, &mut ws.x);
        self.expand(etadot, &mut ws.xdot);
        self.full
            .momentum_into(&ws.x, &ws.xdot, &mut ws.full, &mut ws.v);
        self.project(&ws.v, out);
    }

    fn velocities_into(
        &self,
        eta: &[f64],
        p: &[f64],
        ws: &mut ReducedWorkspace3d,
        out: &mut [f64],
    ) -> bool {
        self.configure(eta, ws);
        match &ws.factor {
            Some(ch) => {
                let v = ch.solve(&DVector::from_column_slice(p));
                out.copy_from_slice(v.as_slice());
                out.iter().all(|v| v.is_finite())
            }
            None => false,
        }
    }

    fn gyroscopic_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace3d,
        out: &mut [f64],
    ) {
        self.expand(eta, &mut ws.x);
        self.expand(etadot, &mut ws.xdot);
        self.full
            .gyroscopic_into(&ws.x, &ws.xdot, &mut ws.full, &mut ws.v);
        self.project(&ws.v, out);
    }

    fn kinetic_derivatives_into(
        &self,
        eta: &[f64],
        etadot: &[f64],
        ws: &mut ReducedWorkspace3d,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        let r = self.indices.len();
        self.expand(eta, &mut ws.x);
        self.expand(etadot, &mut ws.xdot);
        let zeros = vec![0.0; self.full.n_dofs()];
        let mut col = vec![0.0; r];
        for c in 0..r {
            self.full.directional(
                &mut ws.dir,
                (&ws.x, &ws.xdot),
                (self.phi.column(c).as_slice(), &zeros),
                None,
                true,
                (&mut ws.dp, &mut ws.dg, &mut ws.dq),
            );
            self.project(&ws.dp, &mut col);
            dp.set_column(c, &DVector::from_column_slice(&col));
            self.project(&ws.dg, &mut col);
            dgamma.set_column(c, &DVector::from_column_slice(&col));
        }
    }

    fn loads_are_conservative(&self, loads: &AppliedLoads, scales: &[f64]) -> bool {
        loads.is_conservative(scales)
    }

    fn full_coordinates(&self, eta: &[f64]) -> Vec<f64> {
        let mut x = vec![0.0; self.full.n_dofs()];
        self.expand(eta, &mut x);
        x
    }

    /// The full chain's measure of the rotations of `Φ dη`.
    fn element_rotations(&self, deta: &[f64]) -> Vec<f64> {
        self.full.element_rotations(&self.full_coordinates(deta))
    }
}
