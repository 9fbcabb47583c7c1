//! The tangent stiffness `K_T = K − ∂Q/∂q` of the full model, factored for solves in O(n), as
//! Lanczos needs it (docs/model-choices.md, "Modes"): a symmetric `K_T` (conservative loads)
//! and the number of its non-positive eigenvalues.
//!
//! The factorization is the static tangent sweep of `model::chain_newton` (the one static
//! Newton uses, `newton_tangent.rs`): block elimination from the tip, exact for every load kind,
//! whose pivots are those of a symmetric `L D Lᵀ` factorization when `K_T` is symmetric, so
//! (Sylvester's law of inertia) their signs count the non-positive eigenvalues of `K_T`. This
//! module adds what modal analysis asks beyond statics: follower forces (an unsymmetric `K_T`,
//! a non-conservative problem) are refused, measured on two pseudo-random probes.

use nalgebra::{DMatrix, DVector};

use crate::error::SolveError;
use crate::model::{AppliedLoads, ChainFactor, ChainLinearization, FullModel, Shift};

/// A factored, symmetric tangent stiffness of the full model.
#[derive(Debug, Clone)]
pub(crate) struct Tangent {
    lin: Box<ChainLinearization>,
    factor: ChainFactor<f64>,
    /// Non-positive pivot eigenvalues: the non-positive eigenvalues of `K_T`.
    non_positive: usize,
}

impl Tangent {
    /// `K` alone (no load).
    pub(crate) fn unloaded(model: &FullModel) -> Self {
        // ChainLinearization::new linearizes at rest, undeformed, without loads: K_T = K.
        Self::factored(model, Box::new(ChainLinearization::new(model)))
    }

    /// `K − ∂Q/∂q` at `q` for `loads` scaled by `scales`.
    ///
    /// # Errors
    /// [`SolveError::NonSymmetricTangent`] if the load Jacobian is not symmetric (follower
    /// forces), measured on pseudo-random directions `u`, `v` as
    /// `|uᵀ K_T v − vᵀ K_T u| / (‖u‖ ‖K_T v‖ + ‖v‖ ‖K_T u‖)`.
    pub(crate) fn loaded(
        model: &FullModel,
        q: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> Result<Self, SolveError> {
        let asymmetry = asymmetry(model, q, loads, scales);
        if asymmetry > 1e-10 {
            return Err(SolveError::NonSymmetricTangent { asymmetry });
        }
        let mut lin = Box::new(ChainLinearization::new(model));
        lin.update(model, q, None, Some((loads, scales)));
        Ok(Self::factored(model, lin))
    }

    /// Factor the static tangent of `lin`. A singular pivot (`K_T` singular: a bifurcation)
    /// counts as one non-positive eigenvalue at least.
    fn factored(model: &FullModel, lin: Box<ChainLinearization>) -> Self {
        let mut factor = ChainFactor::<f64>::new(model.n_elements());
        let regular = factor.factor(model, &lin, Shift::statics());
        // The probes vouch for symmetry (a follower force scaled to zero leaves the
        // linearization flagged unsymmetric, yet its pivots are those of L D Lᵀ).
        let negative = factor.negative_pivots_assuming_symmetry();
        let non_positive = if regular { negative } else { negative.max(1) };
        Self {
            lin,
            factor,
            non_positive,
        }
    }

    /// Non-positive eigenvalues of `K_T` (0: positive definite).
    pub(crate) fn non_positive(&self) -> usize {
        self.non_positive
    }

    /// `out = K_T⁻¹ b` for the `model` this tangent was factored for.
    pub(crate) fn solve(&mut self, model: &FullModel, b: &[f64], out: &mut [f64]) {
        out.copy_from_slice(b);
        self.factor.solve(model, &self.lin, out);
    }
}

/// `|uᵀ K_T v − vᵀ K_T u| / (‖u‖ ‖K_T v‖ + ‖v‖ ‖K_T u‖)` for two fixed pseudo-random `u`, `v`
/// (reproducible), in O(n) by two load-Jacobian products.
fn asymmetry(model: &FullModel, q: &[f64], loads: &AppliedLoads, scales: &[f64]) -> f64 {
    let nd = model.n_dofs();
    let kin = model.kinematics(q);
    let mut seed = 0x2545_F491_4F6C_DD1Du64;
    let probes = DMatrix::from_fn(nd, 2, |_, _| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    });
    let mut j_probes = DMatrix::zeros(nd, 2);
    model.load_jacobian_times_kin_into(&kin, loads, scales, &probes, &mut j_probes);
    let k = DVector::from_column_slice(model.stiffness());
    let kt = |c: usize| probes.column(c).component_mul(&k) - j_probes.column(c);
    let (u, v) = (probes.column(0), probes.column(1));
    let (ktu, ktv) = (kt(0), kt(1));
    (u.dot(&ktv) - v.dot(&ktu)).abs() / (u.norm() * ktv.norm() + v.norm() * ktu.norm())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{DistributedForce, Force, Load};

    fn conservative_loads(length: f64, torsion: bool) -> Vec<Load> {
        let mut loads = vec![
            Load::PointForce {
                span: length,
                force: Force::Dead { fx: -3.0, fy: 40.0 },
            },
            Load::PointForce {
                span: 0.37 * length,
                force: Force::Dead { fx: 5.0, fy: -9.0 },
            },
            Load::Moment {
                span: 0.6 * length,
                value: 7.0,
            },
            Load::Distributed(DistributedForce::Dead {
                fx: crate::beam::Profile::Uniform(0.0),
                fy: crate::beam::Profile::Uniform(-6.0),
            }),
            Load::Gravity { g: 9.81 },
        ];
        if torsion {
            loads.push(Load::Torque {
                span: length,
                value: 4.0,
            });
        }
        loads
    }

    /// A deformed configuration (not an equilibrium: the tangent is defined anywhere).
    fn bent(model: &FullModel) -> Vec<f64> {
        (0..model.n_dofs())
            .map(|i| 0.05 + 0.03 * (0.7 * i as f64).sin())
            .collect()
    }

    #[test]
    fn chain_elimination_solves_the_dense_tangent() {
        // K_T x = b through the O(n) elimination against the dense K − ∂Q/∂q (formed column by
        // column from the load Jacobian, `modes::dense_tangent`) and its Cholesky solve, with
        // and without torsion, every conservative load type, at a bent configuration. Residual
        // relative to ‖K_T‖ ‖x‖: measured ≤ 2.2e-16, and the dense solve within 6.1e-16; bounds
        // 1e-13 and 1e-12.
        for model in [
            crate::paper::table1_beam(9).unwrap(),
            crate::paper::table4_beam(11).unwrap(),
        ] {
            let l = model.beam().length();
            let loads = model
                .apply(&conservative_loads(l, model.has_torsion()), "loads")
                .unwrap();
            let scales = vec![0.8; loads.n_loads()];
            let q = bent(&model);
            let mut t = Tangent::loaded(&model, &q, &loads, &scales).unwrap();
            assert_eq!(t.non_positive(), 0);
            let k_t = super::super::modes::dense_tangent(&model, &q, &loads, &scales).unwrap();
            let nd = model.n_dofs();
            let b: Vec<f64> = (0..nd).map(|i| (1.3 * i as f64).cos()).collect();
            let mut x = vec![0.0; nd];
            t.solve(&model, &b, &mut x);
            let x = DVector::from_column_slice(&x);
            let r = &k_t * &x - DVector::from_column_slice(&b);
            let rel = r.amax() / (k_t.amax() * x.amax());
            assert!(rel < 1e-13, "residual {rel:.2e}");
            // The dense Cholesky solve gives the same answer.
            let y = k_t
                .clone()
                .cholesky()
                .expect("positive definite")
                .solve(&DVector::from_column_slice(&b));
            let gap = (y - &x).amax() / x.amax();
            assert!(gap < 1e-12, "dense and chain solves differ by {gap:.2e}");
        }
    }

    #[test]
    fn counts_the_non_positive_eigenvalues() {
        // Axial compression of the Table 4 beam (Euler load π² EI/(4 L²) = 123 N, the second
        // buckling load 9 times that): the number of negative pivots is the number of negative
        // eigenvalues of the dense K_T (Sylvester's law of inertia).
        let model = crate::paper::table4_beam(20).unwrap();
        let q = vec![0.0; 20];
        for (p, negative) in [(100.0, 0), (200.0, 1), (1500.0, 2)] {
            let loads = model
                .apply(
                    &[Load::PointForce {
                        span: 1.0,
                        force: Force::Dead { fx: -p, fy: 0.0 },
                    }],
                    "loads",
                )
                .unwrap();
            let t = Tangent::loaded(&model, &q, &loads, &[1.0]).unwrap();
            let k_t = super::super::modes::dense_tangent(&model, &q, &loads, &[1.0]).unwrap();
            let dense = k_t
                .symmetric_eigenvalues()
                .iter()
                .filter(|&&l| l < 0.0)
                .count();
            assert_eq!(dense, negative, "P = {p}");
            assert_eq!(t.non_positive(), negative, "P = {p}");
        }
    }

    #[test]
    fn follower_loads_are_refused() {
        let model = crate::paper::table4_beam(10).unwrap();
        let loads = model
            .apply(
                &[Load::PointForce {
                    span: 1.0,
                    force: Force::Follower {
                        tangential: 0.0,
                        normal: 50.0,
                    },
                }],
                "loads",
            )
            .unwrap();
        let q = bent(&model);
        let e = Tangent::loaded(&model, &q, &loads, &[1.0]).unwrap_err();
        assert!(matches!(e, SolveError::NonSymmetricTangent { .. }), "{e}");
        // The dense check agrees.
        assert!(super::super::modes::dense_tangent(&model, &q, &loads, &[1.0]).is_err());
    }
}
