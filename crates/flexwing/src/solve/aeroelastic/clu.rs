//! Dense complex LU with partial pivoting in split (real, imaginary) column-major storage,
//! allocation-free after construction: the `n_dofs × n_dofs` solves of the rational eigenproblem
//! (Golub & Van Loan, *Matrix Computations*, 4th ed., Algorithm 3.4.1, right-looking, column
//! oriented).

/// `A = P L U` of a complex `n × n` matrix, factored in place.
#[derive(Debug, Clone)]
pub(crate) struct ComplexLu {
    n: usize,
    pub(crate) re: Vec<f64>,
    pub(crate) im: Vec<f64>,
    pivots: Vec<usize>,
}

impl ComplexLu {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            re: vec![0.0; n * n],
            im: vec![0.0; n * n],
            pivots: vec![0; n],
        }
    }

    /// Factor the matrix held in `re`, `im` (column-major). False if a pivot is zero.
    pub(crate) fn factor(&mut self) -> bool {
        let n = self.n;
        let (re, im) = (&mut self.re, &mut self.im);
        for k in 0..n {
            // Pivot: largest |a_ik|, i ≥ k.
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
            // Update the trailing columns: a_ij −= l_ik a_kj (split borrows: no bounds checks in
            // the inner loop, which then vectorizes).
            for j in k + 1..n {
                let (src_re, dst_re) = re.split_at_mut(j * n);
                let (src_im, dst_im) = im.split_at_mut(j * n);
                let (ur, ui) = (dst_re[k], dst_im[k]);
                if ur == 0.0 && ui == 0.0 {
                    continue;
                }
                let lre = &src_re[col + k + 1..col + n];
                let lim = &src_im[col + k + 1..col + n];
                let dre = &mut dst_re[k + 1..n];
                let dim = &mut dst_im[k + 1..n];
                for (((dr, di), &lr), &li) in dre.iter_mut().zip(dim.iter_mut()).zip(lre).zip(lim) {
                    *dr -= lr * ur - li * ui;
                    *di -= lr * ui + li * ur;
                }
            }
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

    /// Against nalgebra's complex LU on a random-ish matrix that needs pivoting.
    #[test]
    fn solves_like_nalgebra() {
        let n = 7;
        let a = DMatrix::from_fn(n, n, |i, j| {
            Complex::new(
                ((i * 3 + j * 5) % 7) as f64 - 3.0,
                ((i + 2 * j) % 5) as f64 * 0.3,
            )
        });
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
        for i in 0..n {
            assert!((Complex::new(br[i], bi[i]) - want[i]).norm() < 1e-12 * want.norm());
        }
    }
}
