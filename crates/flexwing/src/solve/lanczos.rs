//! The largest eigenvalues of a self-adjoint operator by thick-restart block Lanczos with full
//! reorthogonalization (docs/model-choices.md, "Modes").
//!
//! The problem is `A x = μ x` with `A` self-adjoint in the inner product `⟨x, y⟩_B = xᵀ B y`, `B`
//! symmetric positive definite; for modes `A = K⁻¹ M` and `B = M`, so the largest `μ = 1/ω²` are
//! the lowest modes, well separated (`μ_k ∝ k⁻⁴` in bending, `k⁻²` in torsion) and computed to a
//! relative accuracy `ε μ_1/μ_k` whatever the conditioning of `M` or `K` alone.
//!
//! Method. A `B`-orthonormal basis `V` of a block Krylov space is grown one block of [`BLOCK`]
//! vectors at a time: the next block is `A` applied to the last one, orthogonalized against all of
//! `V` by classical Gram–Schmidt done twice (full reorthogonalization; "twice is enough", Giraud et
//! al. 2005), then within the block. The projected matrix `H = Vᵀ B A V` is formed from inner
//! products of the stored `B V` and `A V` (not from recurrence coefficients), so it stays accurate
//! after restarts. Rayleigh–Ritz on `H` gives the Ritz pairs `(θ_i, V s_i)`; in a Krylov space
//! their residuals all lie along the next block, `A V s − θ V s = F R s_last`, so
//! `‖r_i‖_B = ‖R s_i,last‖` costs nothing (Parlett, *The Symmetric Eigenvalue Problem*, §13.2).
//! When the basis reaches its largest size the best Ritz vectors are kept and the next block is
//! added to them (thick restart: Wu & Simon, SIAM J. Matrix Anal. Appl. 22 (2000) 602–616;
//! Stewart's Krylov–Schur, 2001). Blocks of two find eigenvalues of multiplicity two (for example a bending
//! and a torsion mode of equal frequency in an uncoupled beam), which a single-vector Lanczos
//! would return once. Cost per basis vector: one `B x`, one `A` from `B x`, O(n m) for the
//! reorthogonalization against the `m` stored vectors; O(n m²) in all.

use nalgebra::{DMatrix, SymmetricEigen};

/// A self-adjoint operator `A` in the `B` inner product, applied through `B x` and `A x` from
/// `B x` (for modes: `M x` and `K⁻¹ (M x)`).
pub(crate) trait Pencil {
    /// Dimension of the space.
    fn dim(&self) -> usize;
    /// `out = B x`.
    fn apply_b(&mut self, x: &[f64], out: &mut [f64]);
    /// `out = A x`, given `bx = B x`.
    fn apply_a(&mut self, bx: &[f64], out: &mut [f64]);
}

/// Vectors per block.
pub(crate) const BLOCK: usize = 2;

/// The converged eigenpairs, largest eigenvalue first.
#[derive(Debug, Clone)]
pub(crate) struct Eigenpairs {
    /// Eigenvalues `μ`, descending.
    pub(crate) values: Vec<f64>,
    /// `B`-orthonormal eigenvectors as columns (`dim × count`).
    pub(crate) vectors: DMatrix<f64>,
    /// Work done.
    pub(crate) stats: LanczosStats,
}

/// Work done by [`largest`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct LanczosStats {
    /// Applications of `A` (each with one of `B`).
    pub(crate) applications: usize,
    /// Thick restarts.
    pub(crate) restarts: usize,
    /// Largest basis size.
    pub(crate) basis: usize,
}

/// Failure to converge within the restart budget: the number of eigenpairs that did converge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct NotConverged {
    pub(crate) converged: usize,
}

/// Residual a Ritz pair must reach, `‖A y − θ y‖_B ≤ RTOL θ + ATOL θ_max`: the first makes the
/// eigenvalue exact to `RTOL² / gap` and the vector to `RTOL / gap`; the second, below the
/// round-off of applying `A` (about `ε θ_max`), only guarantees that the test can be met (the
/// Krylov estimate of the residual keeps falling below that round-off: to 1e-18 θ_max on the
/// beams).
const RTOL: f64 = 1e-12;
const ATOL: f64 = 1e-15;

/// Thick restarts before giving up.
const MAX_RESTARTS: usize = 200;

/// The `count` largest eigenpairs of `op` (`1 ≤ count ≤ op.dim()`).
pub(crate) fn largest(op: &mut impl Pencil, count: usize) -> Result<Eigenpairs, NotConverged> {
    let n = op.dim();
    assert!(
        count >= 1 && count <= n,
        "eigenpairs wanted: {count} of {n}"
    );
    // Basis size: room for the wanted pairs and as many again (at least 30 more) to separate
    // them from the rest; half of the extra room is kept at a restart.
    let wanted = count + count.max(30) + BLOCK;
    let max_dim = if wanted + BLOCK >= n { n } else { wanted };
    let keep = count + (max_dim - count) / 2;
    let mut s = State::new(n, max_dim);
    let mut rng = XorShift(0x9E37_79B9_7F4A_7C15);
    // Start: a pseudo-random block (fixed seed, so results are reproducible).
    let mut block = DMatrix::from_fn(n, BLOCK.min(n), |_, _| rng.next());
    let (_, mut b_block) = s.orthonormalize(op, &mut block, &mut rng);
    s.append(op, &block, &b_block);
    loop {
        let last = s.dim - block.ncols()..s.dim;
        if n - s.dim < last.len() {
            // Less room than a block: complete the basis to the whole space (any orthonormal
            // complement), where Rayleigh–Ritz is exact.
            let mut rest = DMatrix::from_fn(n, n - s.dim, |_, _| rng.next());
            let (_, b_rest) = s.orthonormalize(op, &mut rest, &mut rng);
            s.append(op, &rest, &b_rest);
            let (theta, vecs) = s.rayleigh_ritz();
            return Ok(s.finish(op, &theta, &vecs, count));
        }
        // Candidates: A applied to the last block, B-orthonormalized against the basis; their
        // coupling R to the last block gives every Ritz residual.
        let mut next = s.av.columns(last.start, last.len()).into_owned();
        let (coupling, b_next) = s.orthonormalize(op, &mut next, &mut rng);
        if s.dim < count + 2 * BLOCK && s.dim + next.ncols() <= max_dim {
            // Too few vectors for `count` converged pairs yet: grow without Rayleigh–Ritz,
            // which costs O(dim³) and dominates below a few hundred coordinates.
            block = next;
            b_block = b_next;
            s.append(op, &block, &b_block);
            continue;
        }
        let (theta, vecs) = s.rayleigh_ritz();
        let scale = theta[0].abs();
        let mut converged = 0;
        while converged < count {
            let s_last = vecs.view((last.start, converged), (last.len(), 1));
            let residual = (&coupling * s_last).norm();
            if residual > RTOL * theta[converged].abs() + ATOL * scale {
                break;
            }
            converged += 1;
        }
        if converged == count || s.dim == n {
            return Ok(s.finish(op, &theta, &vecs, count));
        }
        if s.dim + next.ncols() > max_dim {
            if s.stats.restarts == MAX_RESTARTS {
                return Err(NotConverged { converged });
            }
            s.restart(&theta, &vecs, keep);
        }
        block = next;
        b_block = b_next;
        s.append(op, &block, &b_block);
    }
}

/// The basis and its images.
struct State {
    /// `V`, `B V`, `A V` (`n × max_dim`, the first `dim` columns in use).
    v: DMatrix<f64>,
    bv: DMatrix<f64>,
    av: DMatrix<f64>,
    /// `H = Vᵀ B A V` (`max_dim × max_dim`, leading `dim × dim` in use).
    h: DMatrix<f64>,
    dim: usize,
    stats: LanczosStats,
}

impl State {
    fn new(n: usize, max_dim: usize) -> Self {
        Self {
            v: DMatrix::zeros(n, max_dim),
            bv: DMatrix::zeros(n, max_dim),
            av: DMatrix::zeros(n, max_dim),
            h: DMatrix::zeros(max_dim, max_dim),
            dim: 0,
            stats: LanczosStats::default(),
        }
    }

    /// Make the columns of `x` `B`-orthonormal and `B`-orthogonal to the basis, in place, and
    /// return their coupling `R` (`x_old = V c + x_new R`, `R` upper triangular). A column that
    /// vanishes (the Krylov space is invariant) is replaced by a random one, keeping its tiny
    /// `R_jj` so that the residual estimates stay bounds. Returns `R` and `B x` of the new
    /// columns.
    fn orthonormalize(
        &mut self,
        op: &mut impl Pencil,
        x: &mut DMatrix<f64>,
        rng: &mut XorShift,
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        let (n, p, m) = (x.nrows(), x.ncols(), self.dim);
        let mut r = DMatrix::zeros(p, p);
        let mut b_out = DMatrix::zeros(n, p);
        let mut bx = vec![0.0; n];
        for j in 0..p {
            let mut fresh = false;
            loop {
                let mut removed = 0.0;
                for _ in 0..2 {
                    // Against the basis (classical Gram–Schmidt, one matrix–vector product).
                    if m > 0 {
                        let c = self.bv.columns(0, m).tr_mul(&x.column(j));
                        removed += c.norm_squared();
                        x.column_mut(j).gemv(-1.0, &self.v.columns(0, m), &c, 1.0);
                    }
                    // Against the new columns before it.
                    for i in 0..j {
                        let c = b_out.column(i).dot(&x.column(j));
                        if !fresh {
                            r[(i, j)] += c;
                        }
                        removed += c * c;
                        let (xi, mut xj) = x.columns_range_pair_mut(i, j);
                        xj.axpy(-c, &xi, 1.0);
                    }
                }
                op.apply_b(x.column(j).as_slice(), &mut bx);
                let beta = x.column(j).dot(&nalgebra::DVectorView::from_slice(&bx, n));
                let beta = beta.max(0.0).sqrt();
                if !fresh {
                    r[(j, j)] = beta;
                }
                // Deflation: what is left is round-off of what was removed.
                if beta > 1e-10 * removed.sqrt() && beta > 0.0 {
                    x.column_mut(j).scale_mut(1.0 / beta);
                    for (d, b) in b_out.column_mut(j).iter_mut().zip(&bx) {
                        *d = b / beta;
                    }
                    break;
                }
                fresh = true;
                for e in x.column_mut(j).iter_mut() {
                    *e = rng.next();
                }
            }
        }
        (r, b_out)
    }

    /// Append the orthonormalized block `x` with its `B x`, compute its `A x` and extend `H`.
    fn append(&mut self, op: &mut impl Pencil, x: &DMatrix<f64>, bx: &DMatrix<f64>) {
        let (m, p) = (self.dim, x.ncols());
        let n = x.nrows();
        let mut ax = vec![0.0; n];
        for j in 0..p {
            self.v.set_column(m + j, &x.column(j));
            self.bv.set_column(m + j, &bx.column(j));
            op.apply_a(bx.column(j).as_slice(), &mut ax);
            self.av.column_mut(m + j).copy_from_slice(&ax);
        }
        self.stats.applications += p;
        self.dim = m + p;
        self.stats.basis = self.stats.basis.max(self.dim);
        // H[:, new] = (B V)ᵀ A V_new, mirrored into H[new, :].
        let cols = self.bv.columns(0, self.dim).tr_mul(&self.av.columns(m, p));
        for j in 0..p {
            for i in 0..self.dim {
                let v = cols[(i, j)];
                self.h[(i, m + j)] = v;
                self.h[(m + j, i)] = v;
            }
        }
        // The new diagonal block is symmetric in exact arithmetic: average its two halves.
        for a in 0..p {
            for b in a + 1..p {
                let v = 0.5 * (cols[(m + a, b)] + cols[(m + b, a)]);
                self.h[(m + a, m + b)] = v;
                self.h[(m + b, m + a)] = v;
            }
        }
    }

    /// Ritz values (descending) and the eigenvectors of `H` as columns.
    fn rayleigh_ritz(&self) -> (Vec<f64>, DMatrix<f64>) {
        let m = self.dim;
        let eig = SymmetricEigen::new(self.h.view((0, 0), (m, m)).into_owned());
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| eig.eigenvalues[b].total_cmp(&eig.eigenvalues[a]));
        let theta = order.iter().map(|&i| eig.eigenvalues[i]).collect();
        let vecs = DMatrix::from_fn(m, m, |r, c| eig.eigenvectors[(r, order[c])]);
        (theta, vecs)
    }

    /// Keep the first `k` Ritz vectors as the basis.
    fn restart(&mut self, theta: &[f64], vecs: &DMatrix<f64>, k: usize) {
        let m = self.dim;
        let s = vecs.view((0, 0), (m, k));
        for mat in [&mut self.v, &mut self.bv, &mut self.av] {
            let kept = mat.columns(0, m) * s;
            mat.columns_mut(0, k).copy_from(&kept);
        }
        self.h.fill(0.0);
        for (i, &t) in theta.iter().take(k).enumerate() {
            self.h[(i, i)] = t;
        }
        self.dim = k;
        self.stats.restarts += 1;
    }

    /// The first `count` Ritz pairs, each vector purified and scaled to unit `B`-norm.
    ///
    /// Purification (Ericsson & Ruhe, Math. Comp. 35 (1980) 1251–1268, §3): a Ritz vector `y`
    /// converges in the `B`-norm, which hardly sees round-off along the eigenvectors of tiny `μ`
    /// (for modes: the zig-zags of the highest, whose mass is tiny); those components, ~1e-9 of
    /// the vector at n = 60, would pollute the stiffness-weighted shape. `A y / θ` damps each of
    /// them by `μ_k/θ`, and costs nothing: `A V` is stored.
    fn finish(
        &self,
        op: &mut impl Pencil,
        theta: &[f64],
        vecs: &DMatrix<f64>,
        count: usize,
    ) -> Eigenpairs {
        let m = self.dim;
        let mut y = self.av.columns(0, m) * vecs.view((0, 0), (m, count));
        let mut by = vec![0.0; y.nrows()];
        for mut col in y.column_iter_mut() {
            op.apply_b(col.as_slice(), &mut by);
            let norm = col.iter().zip(&by).map(|(a, b)| a * b).sum::<f64>().sqrt();
            col.scale_mut(1.0 / norm);
        }
        Eigenpairs {
            values: theta[..count].to_vec(),
            vectors: y,
            stats: self.stats,
        }
    }
}

/// xorshift64* (Vigna 2016): reproducible start vectors, uniform in `[−1, 1)`.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let bits = self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11;
        bits as f64 / (1u64 << 52) as f64 - 1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DVector;

    /// `A = K⁻¹ B` for dense SPD `K` and `B`.
    struct Dense {
        b: DMatrix<f64>,
        k: nalgebra::Cholesky<f64, nalgebra::Dyn>,
    }

    impl Pencil for Dense {
        fn dim(&self) -> usize {
            self.b.nrows()
        }
        fn apply_b(&mut self, x: &[f64], out: &mut [f64]) {
            out.copy_from_slice((&self.b * DVector::from_column_slice(x)).as_slice());
        }
        fn apply_a(&mut self, bx: &[f64], out: &mut [f64]) {
            out.copy_from_slice(self.k.solve(&DVector::from_column_slice(bx)).as_slice());
        }
    }

    /// An SPD matrix with eigenvalues `lambda` and a fixed pseudo-random eigenbasis.
    fn spd(lambda: &[f64], seed: u64) -> DMatrix<f64> {
        let n = lambda.len();
        let mut rng = XorShift(seed);
        let q = DMatrix::from_fn(n, n, |_, _| rng.next()).qr().q();
        &q * DMatrix::from_diagonal(&DVector::from_column_slice(lambda)) * q.transpose()
    }

    /// Reference: the largest eigenvalues of `K⁻¹ B` as those of `L⁻¹ B L⁻ᵀ` (dense).
    fn reference(p: &Dense) -> Vec<f64> {
        let l = p.k.l();
        let li = l.clone().try_inverse().unwrap();
        let c = &li * &p.b * li.transpose();
        let mut e: Vec<f64> = SymmetricEigen::new((&c + c.transpose()) * 0.5)
            .eigenvalues
            .iter()
            .copied()
            .collect();
        e.sort_by(|a, b| b.total_cmp(a));
        e
    }

    fn check(p: &mut Dense, count: usize, tol: f64) -> Eigenpairs {
        let want = reference(p);
        let got = largest(p, count).expect("converges");
        let (b, x) = (&p.b, &got.vectors);
        // B-orthonormal, and A x = μ x.
        let gram = x.transpose() * b * x;
        assert!((&gram - DMatrix::identity(count, count)).amax() < 1e-12);
        for i in 0..count {
            assert!(
                (got.values[i] / want[i] - 1.0).abs() < tol,
                "μ_{i}: {} vs {}",
                got.values[i],
                want[i]
            );
            // The true residual in the B-norm: the stopping test's RTOL θ_i, or the round-off of
            // applying A = K⁻¹ B (dense products, up to n ε κ(K) θ_1 = 3.6e-12 θ_1 here):
            // measured ≤ 6.1e-13 θ_1 for this pencil, ≤ 3.6e-14 θ_1 for the diagonal ones.
            let x = got.vectors.column(i);
            let r = p.k.solve(&(b * x)) - x * got.values[i];
            let r = (r.transpose() * b * &r)[(0, 0)].sqrt();
            let bound = 10.0 * RTOL * got.values[i] + 3.6e-12 * got.values[0];
            assert!(r < bound, "residual {i}: {r:.2e} vs {bound:.2e}");
        }
        got
    }

    #[test]
    fn finds_the_largest_eigenvalues_of_a_dense_pencil() {
        // K with condition 100, B with a beam-like spectrum 1/k⁴ (condition 7e8): the ten
        // largest μ of K⁻¹ B to 1e-12 (measured ≤ 5e-13, the dense reference's own round-off
        // ε κ(K) μ_1/μ_k for μ_7; ≤ 1e-14 for the first five).
        let n = 160;
        let kl: Vec<f64> = (0..n).map(|i| 1.0 + 99.0 * i as f64 / n as f64).collect();
        let bl: Vec<f64> = (1..=n).map(|i| 1.0 / (i as f64).powi(4)).collect();
        let mut p = Dense {
            b: spd(&bl, 7),
            k: spd(&kl, 11).cholesky().unwrap(),
        };
        check(&mut p, 10, 1e-12);
    }

    #[test]
    fn restarts_until_a_cluster_converges() {
        // Slowly decaying spectrum with a tight pair at the edge of the wanted set (relative
        // gap 1e-3): needs a thick restart (the basis holds 38 vectors). Measured ≤ 4e-15.
        let n = 400;
        let mut lam: Vec<f64> = (1..=n).map(|i| 1.0 / (i as f64).sqrt()).collect();
        lam[6] = lam[5] * (1.0 - 1e-3);
        let mut p = Dense {
            b: DMatrix::from_diagonal(&DVector::from_column_slice(&lam)),
            k: DMatrix::identity(n, n).cholesky().unwrap(),
        };
        let got = check(&mut p, 6, 1e-12);
        assert!(got.stats.restarts > 0, "{:?}", got.stats);
    }

    #[test]
    fn finds_both_copies_of_a_double_eigenvalue() {
        // Two equal eigenvalues (a bending and a torsion mode of one frequency): blocks of two
        // find both, with B-orthonormal vectors spanning the eigenspace.
        let n = 120;
        let mut lam: Vec<f64> = (1..=n).map(|i| 1.0 / (i as f64).powi(2)).collect();
        lam[2] = lam[1];
        let mut p = Dense {
            b: spd(&lam, 3),
            k: DMatrix::identity(n, n).cholesky().unwrap(),
        };
        let got = check(&mut p, 4, 1e-12);
        assert!((got.values[1] / got.values[2] - 1.0).abs() < 1e-13);
    }

    #[test]
    fn small_spaces_are_completed_and_solved_exactly() {
        // Asking for nearly all of a small space fills the basis: Rayleigh–Ritz is then exact.
        let n = 9;
        let lam: Vec<f64> = (1..=n).map(|i| i as f64).collect();
        let mut p = Dense {
            b: spd(&lam, 5),
            k: spd(&[2.0, 1.0, 3.0, 1.5, 1.2, 2.2, 1.1, 1.7, 1.3], 9)
                .cholesky()
                .unwrap(),
        };
        check(&mut p, 8, 1e-12);
    }
}
