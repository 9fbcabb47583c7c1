//! Balancing of a non-symmetric matrix before its eigenvalues are computed: a diagonal
//! similarity `D⁻¹ A D` by powers of two (exact in binary arithmetic, so the eigenvalues do not
//! change) that makes the norms of each row and its column comparable. Parlett & Reinsch,
//! *Balancing a matrix for calculation of eigenvalues and eigenvectors*, Numer. Math. 13 (1969)
//! 293–304 (the scaling step of LAPACK's `xGEBAL`).
//!
//! Why: the first-order aeroelastic Jacobian on `(x, p, a)` mixes stiffnesses (1e7 N·m/rad for
//! the Goland wing), inverse masses and lag rates; unbalanced, the Hessenberg–QR eigenvalues of
//! nalgebra (which does not balance) lose up to 4e-6 relative on a mode of the Goland wing at
//! n = 8 (tests/suite/aero_linear_matrices.rs, against the independent reference); balanced, 1e-12.

use nalgebra::DMatrix;

/// Balance `a` in place (row and column norms excluding the diagonal, radix 2, until no scaling
/// reduces the sum of a row's and its column's norms by 5 %).
pub(crate) fn balance(a: &mut DMatrix<f64>) {
    balance_scales(a);
}

/// [`balance`], returning the scales `d` of the similarity `D⁻¹ A D`, `D = diag(d)`.
pub(crate) fn balance_scales(a: &mut DMatrix<f64>) -> Vec<f64> {
    const RADIX: f64 = 2.0;
    let n = a.nrows();
    let mut scales = vec![1.0; n];
    let mut converged = false;
    while !converged {
        converged = true;
        for i in 0..n {
            let (mut c, mut r) = (0.0, 0.0);
            for j in 0..n {
                if j != i {
                    c += a[(j, i)].abs();
                    r += a[(i, j)].abs();
                }
            }
            if c == 0.0 || r == 0.0 || !(c + r).is_finite() {
                continue;
            }
            let s = c + r;
            let mut f = 1.0;
            let g = r / RADIX;
            while c < g {
                f *= RADIX;
                c *= RADIX * RADIX;
            }
            let g = r * RADIX;
            while c > g {
                f /= RADIX;
                c /= RADIX * RADIX;
            }
            if (c + r) / f < 0.95 * s {
                converged = false;
                scales[i] *= f;
                for j in 0..n {
                    a[(i, j)] /= f;
                    a[(j, i)] *= f;
                }
            }
        }
    }
    scales
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A badly scaled matrix (entries 1e-8 … 1e8) keeps its eigenvalues (the similarity is
    /// exact) and ends with rows and columns of comparable norm.
    #[test]
    fn balancing_is_an_exact_similarity() {
        let a = DMatrix::from_row_slice(3, 3, &[1.0, 1e8, 0.0, 1e-8, 2.0, 1e6, 0.0, 1e-6, 3.0]);
        let mut b = a.clone();
        balance(&mut b);
        let (ta, tb) = (a.trace(), b.trace());
        assert_eq!(ta, tb);
        let (da, db) = (a.determinant(), b.determinant());
        assert!((da - db).abs() < 1e-12 * da.abs(), "{da} vs {db}");
        // Off-diagonal row and column norms within a factor 4 after balancing (radix 2).
        for i in 0..3 {
            let r: f64 = (0..3).filter(|&j| j != i).map(|j| b[(i, j)].abs()).sum();
            let c: f64 = (0..3).filter(|&j| j != i).map(|j| b[(j, i)].abs()).sum();
            assert!(r / c < 4.0 && c / r < 4.0, "row {i}: {r} vs {c}");
        }
        assert!(b.amax() < 1e-3 * a.amax(), "{b}");
    }
}
