//! The linear algebra of the static Newton iteration (`statics.rs`): the stiffness `K` as an
//! operator and the tangent `K_T = K − ∂Q/∂x`, factored once per iteration and solved for any
//! number of right-hand sides. For the full model `K_T` is factored by the O(n) chain sweep of
//! `model::chain_newton` (exact for every load kind, follower forces included), which also gives
//! its inertia from the pivots' signs; other models (and the full model below
//! [`CHAIN_TANGENT_MIN_DOFS`]) form `K_T` and factor it densely.

use nalgebra::{DMatrix, DVector};

use crate::model::{AppliedLoads, ChainFactor, ChainLinearization, Shift, StructuralModel};

/// From this many coordinates on, the full model's tangent is factored by the chain sweep rather
/// than formed and factored densely (measured, `benches/statics.rs`: docs/performance.md,
/// "Statics at large n").
pub const CHAIN_TANGENT_MIN_DOFS: usize = 10;

/// `K` as an operator: diagonal (the full model; never formed) or dense.
pub(crate) enum Stiffness {
    Diagonal(Vec<f64>),
    Dense(DMatrix<f64>),
}

impl Stiffness {
    pub(crate) fn new<M: StructuralModel>(model: &M) -> Self {
        match model.as_full_model() {
            Some(full) => Stiffness::Diagonal(full.stiffness().to_vec()),
            None => Stiffness::Dense(model.stiffness_matrix()),
        }
    }

    /// `K` as a dense `nd × nd` matrix.
    pub(crate) fn dense(&self, nd: usize) -> DMatrix<f64> {
        match self {
            Stiffness::Diagonal(k) => DMatrix::from_diagonal(&DVector::from_column_slice(k)),
            Stiffness::Dense(k) => {
                debug_assert_eq!(k.nrows(), nd);
                k.clone()
            }
        }
    }

    /// `K x`.
    pub(crate) fn times(&self, x: &DVector<f64>) -> DVector<f64> {
        match self {
            Stiffness::Diagonal(k) => DVector::from_fn(x.len(), |i, _| k[i] * x[i]),
            Stiffness::Dense(k) => k * x,
        }
    }
}

/// The factored tangent of one Newton iteration.
pub(crate) enum Tangent {
    /// The full model's chain sweep.
    Chain {
        lin: Box<ChainLinearization>,
        factor: ChainFactor<f64>,
    },
    /// Dense `K − ∂Q/∂x` and its LU factors.
    Dense {
        k: DMatrix<f64>,
        jac: DMatrix<f64>,
        lu: Option<nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>>,
        symmetric: bool,
        positive: Option<bool>,
    },
}

impl Tangent {
    /// The tangent solver for `model`: the chain sweep for the full model from
    /// [`CHAIN_TANGENT_MIN_DOFS`] coordinates on, dense otherwise.
    pub(crate) fn new<M: StructuralModel>(model: &M) -> Self {
        match model.as_full_model() {
            Some(full) if full.n_dofs() >= CHAIN_TANGENT_MIN_DOFS => Tangent::Chain {
                lin: Box::new(ChainLinearization::new(full)),
                factor: ChainFactor::new(full.n_elements()),
            },
            _ => {
                let nd = model.n_dofs();
                Tangent::Dense {
                    k: model.stiffness_matrix(),
                    jac: DMatrix::zeros(nd, nd),
                    lu: None,
                    symmetric: false,
                    positive: None,
                }
            }
        }
    }

    /// Evaluate and factor `K − ∂Q/∂x` at `x` under `loads` scaled by `scales`; false if it is
    /// singular (or not finite).
    pub(crate) fn factor<M: StructuralModel>(
        &mut self,
        model: &M,
        ws: &mut M::Workspace,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> bool {
        match self {
            Tangent::Chain { lin, factor } => {
                let Some(full) = model.as_full_model() else {
                    return false;
                };
                lin.update(full, x, None, Some((loads, scales)));
                factor.factor(full, lin, Shift::statics())
            }
            Tangent::Dense {
                k,
                jac,
                lu,
                symmetric,
                positive,
            } => {
                model.load_jacobian_into(x, loads, scales, ws, jac);
                let t = &*k - &*jac;
                let asym = (&t - t.transpose()).amax();
                *symmetric = asym <= 1e-12 * t.amax();
                *positive = None;
                let f = t.lu();
                let ok = f.is_invertible() && f.u().iter().all(|v| v.is_finite());
                *lu = Some(f);
                ok
            }
        }
    }

    /// `b ← K_T⁻¹ b` with the last factorization.
    pub(crate) fn solve<M: StructuralModel>(&mut self, model: &M, b: &mut DVector<f64>) {
        match self {
            Tangent::Chain { lin, factor } => {
                if let Some(full) = model.as_full_model() {
                    factor.solve(full, lin, b.as_mut_slice());
                }
            }
            Tangent::Dense { lu, .. } => {
                let solved = lu.as_ref().and_then(|f| f.solve(b));
                match solved {
                    Some(x) => b.copy_from(&x),
                    None => b.fill(f64::NAN),
                }
            }
        }
    }

    /// Whether the determinant of the last factored tangent is negative, from the chain sweep's
    /// pivots at no extra cost, symmetric or not (`ChainFactor::determinant_negative`); `None`
    /// for the dense path, and where the sweep's load stiffness is not exact (a follower force
    /// strictly inside an element: `ChainLinearization::is_exact`).
    pub(crate) fn determinant_negative(&self) -> Option<bool> {
        match self {
            Tangent::Chain { lin, factor } => lin.is_exact().then(|| factor.determinant_negative()),
            Tangent::Dense { .. } => None,
        }
    }

    /// Whether the last factored tangent is positive definite (the equilibrium is stable):
    /// `Some` for a symmetric tangent (conservative loads), `None` when it is not symmetric
    /// (follower forces). From the pivots' signs for the chain sweep (no extra cost), by a
    /// Cholesky attempt for the dense path (computed on the first call per factorization).
    pub(crate) fn positive_definite(&mut self) -> Option<bool> {
        match self {
            Tangent::Chain { factor, .. } => factor.negative_pivots().map(|neg| neg == 0),
            Tangent::Dense {
                k,
                jac,
                symmetric,
                positive,
                ..
            } => {
                if !*symmetric {
                    return None;
                }
                if positive.is_none() {
                    let t = &*k - &*jac;
                    *positive = Some(t.cholesky().is_some());
                }
                *positive
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Force, FullModel, Load, ReducedModel};
    use crate::solve::Modes;

    /// The chain tangent against the dense one on the same states (a buckled state included):
    /// the same Newton step and the same answer to "positive definite?".
    #[test]
    fn chain_and_dense_tangents_agree() {
        let full: FullModel = crate::paper::table4_beam(12).unwrap();
        let nd = full.n_dofs();
        for (fx, follower) in [(-1.0, false), (-400.0, false), (-1.0, true)] {
            let force = if follower {
                Force::Follower {
                    tangential: fx,
                    normal: 3.0,
                }
            } else {
                Force::Dead { fx, fy: 0.3 }
            };
            let loads = full
                .apply(
                    &[
                        Load::PointForce { span: 1.0, force },
                        Load::Gravity { g: 9.81 },
                    ],
                    "loads",
                )
                .unwrap();
            let x: Vec<f64> = (0..nd).map(|i| 0.02 * (1.0 + i as f64).sin()).collect();
            let mut ws = full.workspace();
            let mut chain = Tangent::new(&full);
            assert!(matches!(chain, Tangent::Chain { .. }));
            let mut dense = Tangent::Dense {
                k: full.stiffness_matrix(),
                jac: DMatrix::zeros(nd, nd),
                lu: None,
                symmetric: false,
                positive: None,
            };
            assert!(chain.factor(&full, &mut ws, &x, &loads, &[1.0, 1.0]));
            assert!(dense.factor(&full, &mut ws, &x, &loads, &[1.0, 1.0]));
            let b = DVector::from_fn(nd, |i, _| (0.3 * i as f64).cos());
            let (mut xc, mut xd) = (b.clone(), b.clone());
            chain.solve(&full, &mut xc);
            dense.solve(&full, &mut xd);
            // Condition numbers up to ~1e4 here: 1e-11 relative.
            assert!((&xc - &xd).amax() <= 1e-11 * xd.amax(), "{fx} {follower}");
            assert_eq!(chain.positive_definite(), dense.positive_definite());
            if fx == -400.0 {
                assert_eq!(chain.positive_definite(), Some(false), "buckled");
            }
            if follower {
                assert_eq!(chain.positive_definite(), None);
            }
        }
        // A reduced model takes the dense path.
        let modes = Modes::undeformed(&full).unwrap();
        let rom = ReducedModel::first(&full, modes.shapes(), 3).unwrap();
        assert!(matches!(Tangent::new(&rom), Tangent::Dense { .. }));
    }
}
