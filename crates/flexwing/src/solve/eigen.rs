//! The generalized symmetric-definite eigenproblem `K φ = λ M φ`.

use nalgebra::{DMatrix, SymmetricEigen};

use crate::error::SolveError;

/// Solve `K φ = λ M φ` for symmetric `K` and symmetric positive definite `M`.
///
/// Returns the eigenvalues in ascending order and the `M`-orthonormal eigenvectors as columns
/// (`Φᵀ M Φ = I`), each with its largest-magnitude component made positive.
///
/// Method: Cholesky `M = L Lᵀ`, symmetric eigen-decomposition of `L⁻¹ K L⁻ᵀ`, back-transform
/// `φ = L⁻ᵀ v` (Golub & Van Loan, *Matrix Computations*, 4th ed., §8.7.2).
///
/// # Errors
/// [`SolveError::MassNotPositiveDefinite`] if the Cholesky factorization fails.
///
/// ```
/// use nalgebra::DMatrix;
/// let k = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 8.0]);
/// let m = DMatrix::identity(2, 2) * 2.0;
/// let (lambda, _phi) = flexwing::solve::generalized_symmetric_eigen(&k, &m).unwrap();
/// assert!((lambda[0] - 1.0).abs() < 1e-12 && (lambda[1] - 4.0).abs() < 1e-12);
/// ```
pub fn generalized_symmetric_eigen(
    k: &DMatrix<f64>,
    m: &DMatrix<f64>,
) -> Result<(Vec<f64>, DMatrix<f64>), SolveError> {
    let n = k.nrows();
    let chol = m
        .clone()
        .cholesky()
        .ok_or(SolveError::MassNotPositiveDefinite)?;
    let l = chol.l();
    // C = L⁻¹ K L⁻ᵀ: solve L X = K, then L Cᵀ = Xᵀ.
    let x = l
        .solve_lower_triangular(k)
        .ok_or(SolveError::MassNotPositiveDefinite)?;
    let c = l
        .solve_lower_triangular(&x.transpose())
        .ok_or(SolveError::MassNotPositiveDefinite)?;
    let c = (&c + c.transpose()) * 0.5;
    let eig = SymmetricEigen::new(c);
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| eig.eigenvalues[a].total_cmp(&eig.eigenvalues[b]));
    let lt = l.transpose();
    let mut phi = DMatrix::zeros(n, n);
    let mut lambda = Vec::with_capacity(n);
    for (col, &i) in order.iter().enumerate() {
        lambda.push(eig.eigenvalues[i]);
        let v = lt
            .solve_upper_triangular(&eig.eigenvectors.column(i).into_owned())
            .ok_or(SolveError::MassNotPositiveDefinite)?;
        let big = v
            .iter()
            .copied()
            .fold(0.0_f64, |b, x| if x.abs() > b.abs() { x } else { b });
        let sign = if big < 0.0 { -1.0 } else { 1.0 };
        phi.set_column(col, &(v * sign));
    }
    Ok((lambda, phi))
}
