//! Fixed-size 3-vectors and 3×3 matrices over a generic scalar (`f64` or a dual number), the
//! arithmetic of the 3-D chain's recursions. Arrays rather than nalgebra types so that the same
//! code runs on `num_dual` scalars without allocation; matrices are row-major, `m[row][col]`.

use num_dual::DualNum;

/// A scalar the recursions run on: `f64`, or a forward-mode dual number over `f64`.
pub(crate) trait Real: DualNum<Primitive = f64> + Copy {}
impl<D: DualNum<Primitive = f64> + Copy> Real for D {}

/// A 3-vector.
pub(crate) type V3<D> = [D; 3];
/// A 3×3 matrix, row-major.
pub(crate) type M3<D> = [[D; 3]; 3];

#[inline]
pub(crate) fn zero<D: Real>() -> V3<D> {
    [D::from(0.0); 3]
}

#[inline]
pub(crate) fn lift<D: Real>(v: &[f64; 3]) -> V3<D> {
    [D::from(v[0]), D::from(v[1]), D::from(v[2])]
}

#[inline]
pub(crate) fn lift_m<D: Real>(m: &[[f64; 3]; 3]) -> M3<D> {
    [lift(&m[0]), lift(&m[1]), lift(&m[2])]
}

#[inline]
pub(crate) fn add<D: Real>(a: &V3<D>, b: &V3<D>) -> V3<D> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
pub(crate) fn sub<D: Real>(a: &V3<D>, b: &V3<D>) -> V3<D> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub(crate) fn scale<D: Real>(s: D, a: &V3<D>) -> V3<D> {
    [s * a[0], s * a[1], s * a[2]]
}

#[inline]
pub(crate) fn dot<D: Real>(a: &V3<D>, b: &V3<D>) -> D {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross<D: Real>(a: &V3<D>, b: &V3<D>) -> V3<D> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The skew matrix `â` with `â b = a × b`.
#[inline]
pub(crate) fn hat<D: Real>(a: &V3<D>) -> M3<D> {
    let z = D::from(0.0);
    [[z, -a[2], a[1]], [a[2], z, -a[0]], [-a[1], a[0], z]]
}

#[inline]
pub(crate) fn identity<D: Real>() -> M3<D> {
    let (o, z) = (D::from(1.0), D::from(0.0));
    [[o, z, z], [z, o, z], [z, z, o]]
}

/// `A b`.
#[inline]
pub(crate) fn mv<D: Real>(a: &M3<D>, b: &V3<D>) -> V3<D> {
    [dot(&a[0], b), dot(&a[1], b), dot(&a[2], b)]
}

/// `Aᵀ b`.
#[inline]
pub(crate) fn mtv<D: Real>(a: &M3<D>, b: &V3<D>) -> V3<D> {
    [
        a[0][0] * b[0] + a[1][0] * b[1] + a[2][0] * b[2],
        a[0][1] * b[0] + a[1][1] * b[1] + a[2][1] * b[2],
        a[0][2] * b[0] + a[1][2] * b[1] + a[2][2] * b[2],
    ]
}

/// `A B`.
#[inline]
pub(crate) fn mm<D: Real>(a: &M3<D>, b: &M3<D>) -> M3<D> {
    let mut c = [[D::from(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
        }
    }
    c
}

/// `Aᵀ B`.
#[inline]
pub(crate) fn mtm<D: Real>(a: &M3<D>, b: &M3<D>) -> M3<D> {
    let mut c = [[D::from(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = a[0][i] * b[0][j] + a[1][i] * b[1][j] + a[2][i] * b[2][j];
        }
    }
    c
}

/// `A Bᵀ`.
#[inline]
pub(crate) fn mmt<D: Real>(a: &M3<D>, b: &M3<D>) -> M3<D> {
    let mut c = [[D::from(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] = dot(&a[i], &b[j]);
        }
    }
    c
}

#[inline]
pub(crate) fn transpose<D: Real>(a: &M3<D>) -> M3<D> {
    [
        [a[0][0], a[1][0], a[2][0]],
        [a[0][1], a[1][1], a[2][1]],
        [a[0][2], a[1][2], a[2][2]],
    ]
}

#[inline]
pub(crate) fn madd<D: Real>(a: &M3<D>, b: &M3<D>) -> M3<D> {
    let mut c = *a;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] += b[i][j];
        }
    }
    c
}

#[inline]
pub(crate) fn msub<D: Real>(a: &M3<D>, b: &M3<D>) -> M3<D> {
    let mut c = *a;
    for i in 0..3 {
        for j in 0..3 {
            c[i][j] -= b[i][j];
        }
    }
    c
}

#[inline]
pub(crate) fn mscale<D: Real>(s: D, a: &M3<D>) -> M3<D> {
    let mut c = *a;
    for row in c.iter_mut() {
        for v in row.iter_mut() {
            *v *= s;
        }
    }
    c
}

/// Column `j` of `A`.
#[inline]
pub(crate) fn column<D: Real>(a: &M3<D>, j: usize) -> V3<D> {
    [a[0][j], a[1][j], a[2][j]]
}

/// The Cholesky factor `L` (lower) of a symmetric 3×3 matrix, `A = L Lᵀ`; `None` unless every
/// pivot is positive and finite (the matrix is numerically positive definite).
pub(crate) fn cholesky<D: Real>(a: &M3<D>) -> Option<M3<D>> {
    let z = D::from(0.0);
    let mut l = [[z; 3]; 3];
    for j in 0..3 {
        let mut d = a[j][j];
        for k in 0..j {
            d -= l[j][k] * l[j][k];
        }
        let dr = d.re();
        if !(dr > 0.0 && dr.is_finite()) {
            return None;
        }
        let s = d.sqrt();
        l[j][j] = s;
        for i in j + 1..3 {
            let mut v = a[i][j];
            for k in 0..j {
                v -= l[i][k] * l[j][k];
            }
            l[i][j] = v / s;
        }
    }
    Some(l)
}

/// `x = A⁻¹ b` from the Cholesky factor `L` of `A`.
pub(crate) fn cholesky_solve<D: Real>(l: &M3<D>, b: &V3<D>) -> V3<D> {
    let mut y = *b;
    for i in 0..3 {
        for k in 0..i {
            let t = l[i][k] * y[k];
            y[i] -= t;
        }
        y[i] /= l[i][i];
    }
    for i in (0..3).rev() {
        for k in i + 1..3 {
            let t = l[k][i] * y[k];
            y[i] -= t;
        }
        y[i] /= l[i][i];
    }
    y
}

/// `A⁻¹` of a symmetric positive definite matrix from its Cholesky factor.
pub(crate) fn cholesky_inverse<D: Real>(l: &M3<D>) -> M3<D> {
    let (o, z) = (D::from(1.0), D::from(0.0));
    let cols = [
        cholesky_solve(l, &[o, z, z]),
        cholesky_solve(l, &[z, o, z]),
        cholesky_solve(l, &[z, z, o]),
    ];
    // Symmetric: the columns are the rows.
    cols
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cholesky_inverts_a_positive_definite_matrix() {
        let a: [[f64; 3]; 3] = [[4.0, 1.0, 0.5], [1.0, 3.0, -0.2], [0.5, -0.2, 2.0]];
        let l = cholesky(&a).expect("positive definite");
        let inv = cholesky_inverse(&l);
        let p = mm(&a, &inv);
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((p[i][j] - e).abs() < 1e-15, "{p:?}");
            }
        }
        assert!(cholesky(&[[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]]).is_none());
    }

    #[test]
    fn products_follow_their_definitions() {
        let a = [[1.0, 2.0, 3.0], [0.5, -1.0, 2.0], [4.0, 0.0, -2.0]];
        let b = [[0.0, 1.0, -1.0], [2.0, 0.5, 1.0], [1.0, 1.0, 3.0]];
        let v = [0.3, -0.7, 1.1];
        assert_eq!(mtv(&a, &v), mv(&transpose(&a), &v));
        assert_eq!(mtm(&a, &b), mm(&transpose(&a), &b));
        assert_eq!(mmt(&a, &b), mm(&a, &transpose(&b)));
        assert_eq!(mv(&hat(&v), &[1.0, 2.0, 3.0]), cross(&v, &[1.0, 2.0, 3.0]));
    }
}
