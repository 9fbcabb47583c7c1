//! Dense complex LU with partial pivoting in split (real, imaginary) column-major storage,
//! allocation-free after construction: the `n_dofs × n_dofs` solves of the rational eigenproblem
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., Algorithm 3.4.1, right-looking, column
//! oriented; from [`BLOCKED_MIN`] on blocked, §3.4.7: panels of [`PANEL`] columns, the trailing
//! matrix updated by matrix products).
//!
//! Why blocked: the unblocked update sweeps the whole trailing matrix once per column with
//! two-wide vector arithmetic; a panel's update as four real products (`A₂₂ −= L₂₁ U₁₂` in real
//! and imaginary parts) goes through nalgebra's `gemm`, which uses the processor's widest vectors
//! (matrixmultiply's kernels, chosen at run time). Measured on one 96 × 96 factorization (the 3-D
//! chain at n = 32, docs/performance.md): 1.3–1.5 times faster; below 64 the products are too
//! small to gain, so smaller matrices stay unblocked.

use nalgebra::{DMatrixView, DMatrixViewMut};

/// Columns of a panel of the blocked factorization.
const PANEL: usize = 16;

/// From this order on the factorization is blocked (measured break-even 48–64).
const BLOCKED_MIN: usize = 64;

/// `A = P L U` of a complex `n × n` matrix, factored in place.
#[derive(Debug, Clone)]
pub(crate) struct ComplexLu {
    n: usize,
    pub(crate) re: Vec<f64>,
    pub(crate) im: Vec<f64>,
    pivots: Vec<usize>,
    /// A panel's rows of `U` right of it (`PANEL × n`, column-major), real and imaginary parts.
    u_re: Vec<f64>,
    u_im: Vec<f64>,
}

/// `a[rows, j] −= l[rows, k] a[k, j]`: column `k`'s elimination in a later column `j > k`
/// (split borrows: no bounds checks in the loop, which then vectorizes).
fn eliminate(
    re: &mut [f64],
    im: &mut [f64],
    n: usize,
    k: usize,
    j: usize,
    rows: std::ops::Range<usize>,
) {
    let (ur, ui) = (re[j * n + k], im[j * n + k]);
    if (ur == 0.0 && ui == 0.0) || rows.is_empty() {
        return;
    }
    let (src_re, dst_re) = re.split_at_mut(j * n);
    let (src_im, dst_im) = im.split_at_mut(j * n);
    let lre = &src_re[k * n + rows.start..k * n + rows.end];
    let lim = &src_im[k * n + rows.start..k * n + rows.end];
    let dre = &mut dst_re[rows.clone()];
    let dim = &mut dst_im[rows];
    for (((dr, di), &lr), &li) in dre.iter_mut().zip(dim.iter_mut()).zip(lre).zip(lim) {
        *dr -= lr * ur - li * ui;
        *di -= lr * ui + li * ur;
    }
}

impl ComplexLu {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            re: vec![0.0; n * n],
            im: vec![0.0; n * n],
            pivots: vec![0; n],
            u_re: vec![0.0; PANEL * n],
            u_im: vec![0.0; PANEL * n],
        }
    }

    /// Factor the matrix held in `re`, `im` (column-major). False if a pivot is zero.
    pub(crate) fn factor(&mut self) -> bool {
        let n = self.n;
        let panel = if n >= BLOCKED_MIN { PANEL } else { n };
        let mut k0 = 0;
        while k0 < n {
            let end = (k0 + panel).min(n);
            let (re, im) = (&mut self.re, &mut self.im);
            // The panel, column by column, with the updates inside it.
            for k in k0..end {
                // Pivot: largest |a_ik|, i ≥ k; its row swapped across the whole matrix.
                let col = k * n;
                let mut p = k;
                let mut best = -1.0;
                for i in k..n {
                    let m = re[col + i] * re[col + i] + im[col + i] * im[col + i];
                    if m > best {
                        best = m;
                        p = i;
                    }
                }
                self.pivots[k] = p;
                if !(best > 0.0) || !best.is_finite() {
                    return false;
                }
                if p != k {
                    for j in 0..n {
                        re.swap(j * n + k, j * n + p);
                        im.swap(j * n + k, j * n + p);
                    }
                }
                // Multipliers l_ik = a_ik / a_kk.
                let (pr, pi) = (re[col + k], im[col + k]);
                let d = pr * pr + pi * pi;
                let (ir, ii) = (pr / d, -pi / d);
                for i in k + 1..n {
                    let (ar, ai) = (re[col + i], im[col + i]);
                    re[col + i] = ar * ir - ai * ii;
                    im[col + i] = ar * ii + ai * ir;
                }
                for j in k + 1..end {
                    eliminate(re, im, n, k, j, k + 1..n);
                }
            }
            if end == n {
                break;
            }
            // U₁₂ = L₁₁⁻¹ A₁₂ (unit lower triangle), kept aside for the products.
            let (nb, m) = (end - k0, n - end);
            for j in end..n {
                for k in k0..end {
                    eliminate(re, im, n, k, j, k + 1..end);
                }
                let c = (j - end) * nb;
                self.u_re[c..c + nb].copy_from_slice(&re[j * n + k0..j * n + end]);
                self.u_im[c..c + nb].copy_from_slice(&im[j * n + k0..j * n + end]);
            }
            // A₂₂ −= L₂₁ U₁₂: real part −(L_r U_r − L_i U_i), imaginary −(L_r U_i + L_i U_r).
            let ur = DMatrixView::from_slice(&self.u_re[..nb * m], nb, m);
            let ui = DMatrixView::from_slice(&self.u_im[..nb * m], nb, m);
            let (left_re, right_re) = re.split_at_mut(end * n);
            let (left_im, right_im) = im.split_at_mut(end * n);
            let lr = DMatrixView::from_slice_with_strides(&left_re[k0 * n + end..], m, nb, 1, n);
            let li = DMatrixView::from_slice_with_strides(&left_im[k0 * n + end..], m, nb, 1, n);
            let mut ar =
                DMatrixViewMut::from_slice_with_strides_mut(&mut right_re[end..], m, m, 1, n);
            ar.gemm(-1.0, &lr, &ur, 1.0);
            ar.gemm(1.0, &li, &ui, 1.0);
            let mut ai =
                DMatrixViewMut::from_slice_with_strides_mut(&mut right_im[end..], m, m, 1, n);
            ai.gemm(-1.0, &lr, &ui, 1.0);
            ai.gemm(-1.0, &li, &ur, 1.0);
            k0 = end;
        }
        true
    }

    /// Solve `A x = b` in place (`br`, `bi`) with the factors.
    pub(crate) fn solve(&self, br: &mut [f64], bi: &mut [f64]) {
        let n = self.n;
        let (re, im) = (&self.re, &self.im);
        for k in 0..n {
            let p = self.pivots[k];
            if p != k {
                br.swap(k, p);
                bi.swap(k, p);
            }
        }
        // L y = b (unit lower), column-oriented.
        for k in 0..n {
            let (yr, yi) = (br[k], bi[k]);
            let col = k * n;
            for i in k + 1..n {
                let (lr, li) = (re[col + i], im[col + i]);
                br[i] -= lr * yr - li * yi;
                bi[i] -= lr * yi + li * yr;
            }
        }
        // U x = y.
        for k in (0..n).rev() {
            let col = k * n;
            let (ur, ui) = (re[col + k], im[col + k]);
            let d = ur * ur + ui * ui;
            let (xr, xi) = ((br[k] * ur + bi[k] * ui) / d, (bi[k] * ur - br[k] * ui) / d);
            br[k] = xr;
            bi[k] = xi;
            for i in 0..k {
                let (ar, ai) = (re[col + i], im[col + i]);
                br[i] -= ar * xr - ai * xi;
                bi[i] -= ar * xi + ai * xr;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Complex, DMatrix, DVector};

    /// Against nalgebra's complex LU on random-ish matrices that need pivoting: unblocked (7),
    /// and blocked with a last panel narrower than the others (70 = 4 · 16 + 6).
    #[test]
    fn solves_like_nalgebra() {
        for n in [7, 70] {
            solves_like_nalgebra_at(n);
        }
    }

    fn solves_like_nalgebra_at(n: usize) {
        // Entries uniform in [−0.5, 0.5) from a linear congruential generator: no dominant
        // diagonal, so rows are swapped all along.
        let mut seed = 12_345_u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (seed >> 11) as f64 / (1_u64 << 53) as f64 - 0.5
        };
        let a = DMatrix::from_fn(n, n, |_, _| Complex::new(next(), next()));
        let b = DVector::from_fn(n, |i, _| Complex::new(i as f64, 1.0 - i as f64));
        let want = a.clone().lu().solve(&b).unwrap();
        let mut lu = ComplexLu::new(n);
        for j in 0..n {
            for i in 0..n {
                lu.re[j * n + i] = a[(i, j)].re;
                lu.im[j * n + i] = a[(i, j)].im;
            }
        }
        assert!(lu.factor());
        let mut br: Vec<f64> = b.iter().map(|c| c.re).collect();
        let mut bi: Vec<f64> = b.iter().map(|c| c.im).collect();
        lu.solve(&mut br, &mut bi);
        // Both solutions within round-off times the condition of a random matrix (about n).
        let x = DVector::from_fn(n, |i, _| Complex::new(br[i], bi[i]));
        assert!(
            (&x - &want).norm() < 1e-12 * n as f64 * want.norm(),
            "n = {n}"
        );
        assert!((&a * &x - &b).norm() < 1e-13 * n as f64 * a.norm() * x.norm());
    }
}
