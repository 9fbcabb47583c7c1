//! The tangent stiffness `K_T = K − ∂Q/∂q` of the full model, factored for solves in O(n)
//! (docs/model-choices.md, "Modes").
//!
//! # Structure
//!
//! `K` is diagonal in joint coordinates. The load Jacobian is `∂Q/∂q = Tᵀ D T` (`model::loads`:
//! everything is accumulated in absolute angles `(θ, ψ) = T q`), and for conservative loads —
//! dead forces, moments, torques, gravity — `D = ∂Q_abs/∂(θ, ψ)` is block diagonal: element `j`'s
//! generalized forces depend on its own angles `(θ_j, ψ_j)` only, so `D_j` is a symmetric 2 × 2
//! block (1 × 1 without torsion). Follower forces couple the elements and make `D` triangular
//! and `K_T` unsymmetric; such loads are refused before this point.
//!
//! # Elimination from the tip
//!
//! `½ xᵀ K_T x − bᵀ x = ½ Σ_a x_aᵀ K_a x_a − ½ Σ_j y_jᵀ D_j y_j − Σ_a b_aᵀ x_a` with `x_a` the
//! joint rotations at joint `a` and `y_j = Σ_{a ≤ j} x_a` the absolute angles. Eliminating the joints
//! from the tip, the quadratic form left after joint `a` is `−½ yᵀ P_a y − w_aᵀ y` in the absolute
//! angles `y = y_{a−1}` inboard of it, `P_n = 0`, `w_n = 0`, and with `G_a = D_a + P_{a+1}`:
//!
//! ```text
//! S_a = K_a − G_a                    (pivot, 2 × 2)
//! x_a = S_a⁻¹ (G_a y_{a−1} + b_a + w_{a+1})
//! P_a = G_a + G_a S_a⁻¹ G_a,         w_a = w_{a+1} + G_a S_a⁻¹ (b_a + w_{a+1}).
//! ```
//!
//! This is symmetric Gaussian elimination of `K_T` in the order `n, n − 1, …, 1`, so the `S_a`
//! are its pivots: `K_T` is positive definite exactly when every `S_a` is, and (Sylvester's law of
//! inertia) the number of non-positive pivot eigenvalues is the number of non-positive
//! eigenvalues of `K_T`. A backward sweep for `w` and a forward one for `x` then solve
//! `K_T x = b` in O(n), like the velocity solve of `model::chain_solve`. Without loads `S_a = K_a`
//! and the solve is a division.
//!
//! The blocks `D_j` are read off two products `(∂Q/∂q) e` with the first bending and the first
//! torsion joint (`T e` is all ones in that half), and a product with a pseudo-random direction
//! checks the structure; should a load ever break it, the tangent is formed and factored densely.

use nalgebra::{DMatrix, DVector};

use crate::error::SolveError;
use crate::model::{AppliedLoads, FullModel};

/// A factored tangent stiffness.
#[derive(Debug, Clone)]
pub(crate) enum Tangent {
    /// The O(n) elimination of the module documentation.
    Chain(ChainTangent),
    /// Dense Cholesky factor `L` of `K_T` (loads without the block structure).
    Dense(DMatrix<f64>),
}

/// The elimination of `K_T = K − Tᵀ D T` from the tip.
#[derive(Debug, Clone)]
pub(crate) struct ChainTangent {
    n: usize,
    torsion: bool,
    /// `L D Lᵀ` of each pivot `S_a`: `(d0, l, d1)`.
    pivot: Vec<(f64, f64, f64)>,
    /// `S_a⁻¹ G_a`, row-major.
    gain: Vec<[f64; 4]>,
    /// `G_a` as `(g00, g01, g11)`.
    coupling: Vec<[f64; 3]>,
    /// Feed-forward terms of the last solve.
    feed: Vec<[f64; 2]>,
    /// Non-positive pivot eigenvalues: the non-positive eigenvalues of `K_T`.
    non_positive: usize,
}

/// `x = S⁻¹ y` with `S` factored as `(d0, l, d1)`.
fn solve2(f: (f64, f64, f64), y: [f64; 2]) -> [f64; 2] {
    let (d0, l, d1) = f;
    let x1 = (y[1] - l * y[0]) / d1;
    [y[0] / d0 - l * x1, x1]
}

impl ChainTangent {
    /// Factor `K − Tᵀ D T` for the symmetric blocks `d[j] = (D_θθ, D_θψ, D_ψψ)`.
    fn new(model: &FullModel, d: &[[f64; 3]]) -> Self {
        let n = model.n_elements();
        let torsion = model.has_torsion();
        let k = model.stiffness();
        let mut f = Self {
            n,
            torsion,
            pivot: vec![(1.0, 0.0, 1.0); n],
            gain: vec![[0.0; 4]; n],
            coupling: vec![[0.0; 3]; n],
            feed: vec![[0.0; 2]; n],
            non_positive: 0,
        };
        let mut p = [0.0; 3]; // P_{a+1}
        for a in (0..n).rev() {
            let g = [d[a][0] + p[0], d[a][1] + p[1], d[a][2] + p[2]];
            // Without torsion the ψ row is a placeholder: S_ψψ = 1, no coupling.
            let (s00, s01, s11) = if torsion {
                (k[a] - g[0], -g[1], k[n + a] - g[2])
            } else {
                (k[a] - g[0], 0.0, 1.0)
            };
            let l = if s00 != 0.0 { s01 / s00 } else { 0.0 };
            let d1 = s11 - l * s01;
            f.non_positive += usize::from(!(s00 > 0.0)) + usize::from(!(d1 > 0.0));
            let piv = (s00, l, d1);
            // S⁻¹ G column by column (G symmetric).
            let c0 = solve2(piv, [g[0], g[1]]);
            let c1 = solve2(piv, [g[1], g[2]]);
            let gain = [c0[0], c1[0], c0[1], c1[1]];
            // P_a = G + G S⁻¹ G, symmetrized.
            let gg01 = 0.5 * (g[0] * gain[1] + g[1] * gain[3] + g[1] * gain[0] + g[2] * gain[2]);
            p = [
                g[0] + g[0] * gain[0] + g[1] * gain[2],
                g[1] + gg01,
                g[2] + g[1] * gain[1] + g[2] * gain[3],
            ];
            f.pivot[a] = piv;
            f.gain[a] = gain;
            f.coupling[a] = g;
        }
        f
    }

    /// `out = K_T⁻¹ b`.
    fn solve(&mut self, b: &[f64], out: &mut [f64]) {
        let n = self.n;
        let mut w = [0.0; 2];
        for a in (0..n).rev() {
            let rhs = [
                b[a] + w[0],
                if self.torsion { b[n + a] + w[1] } else { 0.0 },
            ];
            let k = solve2(self.pivot[a], rhs);
            let g = self.coupling[a];
            w[0] += g[0] * k[0] + g[1] * k[1];
            w[1] += g[1] * k[0] + g[2] * k[1];
            self.feed[a] = k;
        }
        let mut y = [0.0; 2];
        for a in 0..n {
            let (l, k) = (self.gain[a], self.feed[a]);
            let x = [
                l[0] * y[0] + l[1] * y[1] + k[0],
                l[2] * y[0] + l[3] * y[1] + k[1],
            ];
            out[a] = x[0];
            y[0] += x[0];
            if self.torsion {
                out[n + a] = x[1];
                y[1] += x[1];
            }
        }
    }
}

impl Tangent {
    /// `K` alone (no load).
    pub(crate) fn unloaded(model: &FullModel) -> Self {
        Tangent::Chain(ChainTangent::new(
            model,
            &vec![[0.0; 3]; model.n_elements()],
        ))
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
        let (n, nd) = (model.n_elements(), model.n_dofs());
        let kin = model.kinematics(q);
        let jacobian_times = |v: &DMatrix<f64>| {
            let mut out = DMatrix::zeros(nd, v.ncols());
            model.load_jacobian_times_kin_into(&kin, loads, scales, v, &mut out);
            out
        };
        // Probes: K_T u and K_T v for pseudo-random u, v (fixed, so results are reproducible).
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let probes = DMatrix::from_fn(nd, 2, |_, _| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        });
        let j_probes = jacobian_times(&probes);
        let k = DVector::from_column_slice(model.stiffness());
        let kt = |c: usize| probes.column(c).component_mul(&k) - j_probes.column(c);
        let (u, v) = (probes.column(0), probes.column(1));
        let (ktu, ktv) = (kt(0), kt(1));
        let asymmetry =
            (u.dot(&ktv) - v.dot(&ktu)).abs() / (u.norm() * ktv.norm() + v.norm() * ktu.norm());
        if asymmetry > 1e-10 {
            return Err(SolveError::NonSymmetricTangent { asymmetry });
        }
        // The blocks D_j from the columns of ∂Q/∂q at the first bending and torsion joints:
        // Tᵀ (D T e) is a suffix sum of D's columns, undone by differences.
        let mut unit = DMatrix::zeros(nd, nd / n);
        for c in 0..nd / n {
            unit[(c * n, c)] = 1.0;
        }
        let cols = jacobian_times(&unit);
        let diff = |c: usize, r: usize| {
            let next = if r % n + 1 < n { cols[(r + 1, c)] } else { 0.0 };
            cols[(r, c)] - next
        };
        let blocks: Vec<[f64; 3]> = (0..n)
            .map(|j| {
                if model.has_torsion() {
                    let off = 0.5 * (diff(0, n + j) + diff(1, j));
                    [diff(0, j), off, diff(1, n + j)]
                } else {
                    [diff(0, j), 0.0, 0.0]
                }
            })
            .collect();
        // Check the structure on the probe v: Tᵀ D T v against ∂Q/∂q v.
        let mut y = [0.0; 2];
        let mut structured = vec![0.0; nd];
        for j in 0..n {
            y[0] += v[j];
            let d = blocks[j];
            if model.has_torsion() {
                y[1] += v[n + j];
                structured[j] = d[0] * y[0] + d[1] * y[1];
                structured[n + j] = d[1] * y[0] + d[2] * y[1];
            } else {
                structured[j] = d[0] * y[0];
            }
        }
        crate::model::suffix_sum_in_blocks(&mut structured, n);
        let jv = j_probes.column(1);
        let gap = jv
            .iter()
            .zip(&structured)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let size = jv.amax().max(k.amax() * v.amax());
        if gap <= 1e-10 * size {
            return Ok(Tangent::Chain(ChainTangent::new(model, &blocks)));
        }
        Self::dense(model, q, loads, scales)
    }

    /// The dense route: form `∂Q/∂q`, symmetrize `K_T` and factor it by Cholesky.
    fn dense(
        model: &FullModel,
        q: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
    ) -> Result<Self, SolveError> {
        let k_t = super::modes::dense_tangent(model, q, loads, scales)?;
        match k_t.clone().cholesky() {
            Some(c) => Ok(Tangent::Dense(c.l())),
            None => {
                let lambda = k_t.symmetric_eigenvalues();
                let non_positive = lambda.iter().filter(|&&l| !(l > 0.0)).count().max(1);
                Err(SolveError::IndefiniteTangent { non_positive })
            }
        }
    }

    /// Non-positive eigenvalues of `K_T` (0: positive definite).
    pub(crate) fn non_positive(&self) -> usize {
        match self {
            Tangent::Chain(c) => c.non_positive,
            Tangent::Dense(_) => 0,
        }
    }

    /// `out = K_T⁻¹ b`.
    pub(crate) fn solve(&mut self, b: &[f64], out: &mut [f64]) {
        match self {
            Tangent::Chain(c) => c.solve(b, out),
            Tangent::Dense(l) => {
                let mut x = DVector::from_column_slice(b);
                l.solve_lower_triangular_mut(&mut x);
                l.tr_solve_lower_triangular_mut(&mut x);
                out.copy_from_slice(x.as_slice());
            }
        }
    }
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
        // K_T x = b through the O(n) elimination against the dense K − ∂Q/∂q, with and without
        // torsion, every conservative load type, at a bent configuration. Residual relative to
        // ‖K_T‖ ‖x‖: measured ≤ 1.1e-16, and the dense route within 6.1e-16; bounds 1e-13 and
        // 1e-12.
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
            assert!(
                matches!(t, Tangent::Chain(_)),
                "the loads have the block structure"
            );
            assert_eq!(t.non_positive(), 0);
            let k_t = super::super::modes::dense_tangent(&model, &q, &loads, &scales).unwrap();
            let nd = model.n_dofs();
            let b: Vec<f64> = (0..nd).map(|i| (1.3 * i as f64).cos()).collect();
            let mut x = vec![0.0; nd];
            t.solve(&b, &mut x);
            let x = DVector::from_column_slice(&x);
            let r = &k_t * &x - DVector::from_column_slice(&b);
            let rel = r.amax() / (k_t.amax() * x.amax());
            assert!(rel < 1e-13, "residual {rel:.2e}");
            // The dense route gives the same solve.
            let mut d = Tangent::dense(&model, &q, &loads, &scales).unwrap();
            let mut y = vec![0.0; nd];
            d.solve(&b, &mut y);
            let gap = (DVector::from_column_slice(&y) - &x).amax() / x.amax();
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
