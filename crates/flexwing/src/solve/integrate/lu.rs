//! Dense LU factorization with partial pivoting, in place in a buffer allocated once, for real and
//! complex matrices: the iteration matrices of the implicit integrators are refactored many times
//! per run and must not allocate.

use nalgebra::Complex;
use std::ops::{Div, Mul, MulAssign, Sub, SubAssign};

/// The scalars of [`DenseLu`]: `f64` and `Complex<f64>`.
pub(crate) trait LuScalar:
    Copy
    + PartialEq
    + Mul<Output = Self>
    + Div<Output = Self>
    + Sub<Output = Self>
    + SubAssign
    + MulAssign
{
    const ZERO: Self;
    const ONE: Self;
    /// A cheap magnitude for pivoting (`|re| + |im|` for complex numbers, as LAPACK's `izamax`).
    fn magnitude(self) -> f64;
}

impl LuScalar for f64 {
    const ZERO: Self = 0.0;
    const ONE: Self = 1.0;
    fn magnitude(self) -> f64 {
        self.abs()
    }
}

impl LuScalar for Complex<f64> {
    const ZERO: Self = Complex { re: 0.0, im: 0.0 };
    const ONE: Self = Complex { re: 1.0, im: 0.0 };
    fn magnitude(self) -> f64 {
        self.re.abs() + self.im.abs()
    }
}

/// `P A = L U` of an `n × n` matrix, column-major, `L` unit lower triangular below the diagonal
/// and `U` on and above it.
#[derive(Debug, Clone)]
pub(crate) struct DenseLu<T> {
    n: usize,
    a: Vec<T>,
    pivots: Vec<usize>,
}

impl<T: LuScalar> DenseLu<T> {
    /// Buffers for `n × n` matrices.
    pub(crate) fn new(n: usize) -> Self {
        Self {
            n,
            a: vec![T::ZERO; n * n],
            pivots: vec![0; n],
        }
    }

    /// The matrix to factor, column-major (`a[i + j n]` is row `i`, column `j`); fill it, then
    /// call [`Self::factor`].
    pub(crate) fn matrix_mut(&mut self) -> &mut [T] {
        &mut self.a
    }

    /// Factor the matrix in place; false if a pivot is exactly zero (singular matrix).
    pub(crate) fn factor(&mut self) -> bool {
        let n = self.n;
        let a = &mut self.a;
        for k in 0..n {
            let mut p = k;
            let mut best = a[k + k * n].magnitude();
            for i in k + 1..n {
                let m = a[i + k * n].magnitude();
                if m > best {
                    best = m;
                    p = i;
                }
            }
            self.pivots[k] = p;
            if best == 0.0 || !best.is_finite() {
                return false;
            }
            if p != k {
                for j in 0..n {
                    a.swap(k + j * n, p + j * n);
                }
            }
            let inv = T::ONE / a[k + k * n];
            for i in k + 1..n {
                a[i + k * n] *= inv;
            }
            let (done, rest) = a.split_at_mut((k + 1) * n);
            let col_k = &done[k * n..];
            for col_j in rest.chunks_exact_mut(n) {
                let akj = col_j[k];
                if akj == T::ZERO {
                    continue;
                }
                for i in k + 1..n {
                    col_j[i] -= col_k[i] * akj;
                }
            }
        }
        true
    }

    /// Overwrite `b` with the solution of `A x = b`.
    pub(crate) fn solve_in_place(&self, b: &mut [T]) {
        let n = self.n;
        let a = &self.a;
        for k in 0..n {
            let p = self.pivots[k];
            if p != k {
                b.swap(k, p);
            }
        }
        // L y = P b, column by column.
        for k in 0..n {
            let bk = b[k];
            if bk != T::ZERO {
                let col = &a[k * n..(k + 1) * n];
                for i in k + 1..n {
                    b[i] -= col[i] * bk;
                }
            }
        }
        // U x = y.
        for k in (0..n).rev() {
            let col = &a[k * n..(k + 1) * n];
            let xk = b[k] / col[k];
            b[k] = xk;
            if xk != T::ZERO {
                for i in 0..k {
                    b[i] -= col[i] * xk;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    #[test]
    fn real_and_complex_solutions_match_nalgebra() {
        let n = 7;
        let m = DMatrix::from_fn(n, n, |i, j| {
            ((i * 7 + j * 3) % 11) as f64 - 5.0 + if i == j { 0.5 } else { 0.0 }
        });
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let mut lu = DenseLu::<f64>::new(n);
        lu.matrix_mut().copy_from_slice(m.as_slice());
        assert!(lu.factor());
        let mut x = b.clone();
        lu.solve_in_place(&mut x);
        let expected = m
            .clone()
            .lu()
            .solve(&nalgebra::DVector::from_vec(b))
            .unwrap();
        for i in 0..n {
            assert!((x[i] - expected[i]).abs() < 1e-12 * expected.amax());
        }
        let mc = m.map(|v| Complex::new(v, 0.3 * v.cos()));
        let bc: Vec<Complex<f64>> = (0..n).map(|i| Complex::new(1.0, i as f64)).collect();
        let mut luc = DenseLu::<Complex<f64>>::new(n);
        luc.matrix_mut().copy_from_slice(mc.as_slice());
        assert!(luc.factor());
        let mut xc = bc.clone();
        luc.solve_in_place(&mut xc);
        let r = &mc * nalgebra::DVector::from_vec(xc) - nalgebra::DVector::from_vec(bc);
        assert!(r.iter().all(|v| v.norm() < 1e-11));
    }

    #[test]
    fn a_singular_matrix_is_reported() {
        let mut lu = DenseLu::<f64>::new(2);
        lu.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
        assert!(!lu.factor());
    }
}
