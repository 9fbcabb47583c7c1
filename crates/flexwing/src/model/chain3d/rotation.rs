//! The rotation-vector parametrization of the joints: Rodrigues' formula `exp(φ̂)`, its tangent
//! maps `T_L` and `T_R` (`dexp`), and the derivative of `T_L(φ) v` with respect to `φ`.
//!
//! Source: the rotation vector and its tangent operator as in Simo & Vu-Quoc, *A
//! three-dimensional finite-strain rod model. Part II*, Comput. Methods Appl. Mech. Eng. 58
//! (1986), and Bullo & Murray's `dexp` (docs/chain3d-model.md, "Joint parametrization"):
//!
//! ```text
//! exp(φ̂) = I + s(θ²) φ̂ + a(θ²) φ̂²,       d exp(φ̂) = (T_L(φ) dφ)^ exp(φ̂) = exp(φ̂) (T_R(φ) dφ)^
//! T_L(φ) = I + a(θ²) φ̂ + b(θ²) φ̂²,       T_R(φ) = T_L(−φ) = T_L(φ)ᵀ
//! s = sin θ / θ,  a = (1 − cos θ) / θ²,  b = (θ − sin θ) / θ³,  θ² = φ·φ
//! ```
//!
//! The coefficients are functions of `θ² = φ·φ` (never of `θ`, whose derivative is singular at
//! `φ = 0`), by their Taylor series for `θ² < 4` and the closed forms beyond, so that dual numbers
//! get exact derivatives everywhere, the undeformed state included.

use super::algebra::{cross, dot, hat, identity, madd, mscale, Real, M3, V3};

/// `θ²` below which the coefficients are summed from their series (at `θ² = 4` the terms of
/// [`SERIES`] fall below 1e-28; the closed forms lose at most ~20 ε beyond).
const SERIES_BELOW: f64 = 4.0;
/// Terms of each series: the last is `4²⁰/42! ≈ 1e-39` of the first at `θ² = 4`.
const SERIES: usize = 20;

/// `(2k + j)!` reciprocals for the series: `INV_FACT[m] = 1/m!`.
const INV_FACT: [f64; 2 * SERIES + 4] = {
    let mut t = [0.0; 2 * SERIES + 4];
    t[0] = 1.0;
    let mut m = 1;
    while m < t.len() {
        t[m] = t[m - 1] / m as f64;
        m += 1;
    }
    t
};

/// The coefficients of the rotation-vector maps at `θ² = s2`: `s`, `a`, `b` and the derivatives
/// `a' = da/d(θ²)`, `b' = db/d(θ²)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Coefficients<D> {
    pub(crate) s: D,
    pub(crate) a: D,
    pub(crate) b: D,
    pub(crate) da: D,
    pub(crate) db: D,
}

impl<D: Real> Coefficients<D> {
    /// The coefficients for the rotation vector `phi`.
    pub(crate) fn of(phi: &V3<D>) -> Self {
        let s2 = dot(phi, phi);
        if s2.re() < SERIES_BELOW {
            Self::series(s2)
        } else {
            Self::closed(s2)
        }
    }

    /// `Σ_k (−θ²)^k / (2k + j)!` (and the derivatives), by Horner's rule, to the first term
    /// `K` whose size `θ^{2K}/(2K)!` falls below 1e-20 (20 terms at `θ² = 4`, 4 at `θ² = 1e-4`):
    /// the omitted tail is below 1e-20 of the leading term, and so are its derivatives' (the
    /// derivative series has the same ratio of terms), for the values and the dual parts.
    fn series(s2: D) -> Self {
        let x = -s2;
        let r = s2.re().abs();
        let mut terms = 1;
        let mut size = 1.0;
        while terms < SERIES && size > 1e-20 {
            size *= r / ((2 * terms - 1) * (2 * terms)) as f64;
            terms += 1;
        }
        // f_j(x) = Σ_k x^k / (2k + j)!, f_j'(x) = Σ_{k≥1} k x^{k−1} / (2k + j)!; d/d(θ²) = −d/dx.
        let sum = |j: usize| {
            let mut v = D::from(INV_FACT[2 * (terms - 1) + j]);
            for k in (0..terms - 1).rev() {
                v = v * x + INV_FACT[2 * k + j];
            }
            v
        };
        let deriv = |j: usize| {
            if terms < 2 {
                return D::from(0.0);
            }
            let mut v = D::from((terms - 1) as f64 * INV_FACT[2 * (terms - 1) + j]);
            for k in (1..terms - 1).rev() {
                v = v * x + k as f64 * INV_FACT[2 * k + j];
            }
            -v
        };
        Self {
            s: sum(1),
            a: sum(2),
            b: sum(3),
            da: deriv(2),
            db: deriv(3),
        }
    }

    fn closed(s2: D) -> Self {
        let th = s2.sqrt();
        let sin = th.sin();
        // 1 − cos θ = 2 sin²(θ/2): no cancellation.
        let half = (th * 0.5).sin();
        let one_m_cos = half * half * 2.0;
        let th_m_sin = th - sin;
        let s4 = s2 * s2;
        Self {
            s: sin / th,
            a: one_m_cos / s2,
            b: th_m_sin / (s2 * th),
            da: (th * sin - one_m_cos * 2.0) / (s4 * 2.0),
            db: (one_m_cos * th - th_m_sin * 3.0) / (s4 * th * 2.0),
        }
    }
}

/// `exp(φ̂)` (Rodrigues).
#[cfg(test)]
pub(crate) fn exp<D: Real>(phi: &V3<D>, c: &Coefficients<D>) -> M3<D> {
    let h = hat(phi);
    let h2 = super::algebra::mm(&h, &h);
    madd(&madd(&identity(), &mscale(c.s, &h)), &mscale(c.a, &h2))
}

/// [`exp`] and [`tangent_left`] together, sharing `φ̂` and `φ̂²`.
pub(crate) fn exp_and_tangent<D: Real>(phi: &V3<D>, c: &Coefficients<D>) -> (M3<D>, M3<D>) {
    let h = hat(phi);
    let h2 = super::algebra::mm(&h, &h);
    let e = madd(&madd(&identity(), &mscale(c.s, &h)), &mscale(c.a, &h2));
    let t = madd(&madd(&identity(), &mscale(c.a, &h)), &mscale(c.b, &h2));
    (e, t)
}

/// `T_L(φ) = I + a φ̂ + b φ̂²`: the spatial angular velocity of `exp(φ̂)` is `T_L(φ) φ̇`.
#[cfg(test)]
pub(crate) fn tangent_left<D: Real>(phi: &V3<D>, c: &Coefficients<D>) -> M3<D> {
    let h = hat(phi);
    let h2 = super::algebra::mm(&h, &h);
    madd(&madd(&identity(), &mscale(c.a, &h)), &mscale(c.b, &h2))
}

/// `∂(T_L(φ) v)/∂φ` (3×3), for `T_L(φ) v = v + a φ × v + b φ × (φ × v)`:
///
/// ```text
/// (φ × v)(2 a' φ)ᵀ − a v̂ + (φ × (φ × v))(2 b' φ)ᵀ + b ((φ·v) I + φ vᵀ − 2 v φᵀ)
/// ```
pub(crate) fn tangent_left_derivative<D: Real>(
    phi: &V3<D>,
    v: &V3<D>,
    c: &Coefficients<D>,
) -> M3<D> {
    let pv = cross(phi, v);
    let ppv = cross(phi, &pv);
    let phv = dot(phi, v);
    let vh = hat(v);
    let mut out = [[D::from(0.0); 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            let mut e = pv[i] * c.da * phi[j] * 2.0 - c.a * vh[i][j]
                + ppv[i] * c.db * phi[j] * 2.0
                + c.b * (phi[i] * v[j] - v[i] * phi[j] * 2.0);
            if i == j {
                e += c.b * phv;
            }
            out[i][j] = e;
        }
    }
    out
}

/// `T_L(φ) v` without forming the matrix.
#[cfg(test)]
pub(crate) fn tangent_left_times<D: Real>(phi: &V3<D>, v: &V3<D>, c: &Coefficients<D>) -> V3<D> {
    let pv = cross(phi, v);
    let ppv = cross(phi, &pv);
    super::algebra::add(
        v,
        &super::algebra::add(
            &super::algebra::scale(c.a, &pv),
            &super::algebra::scale(c.b, &ppv),
        ),
    )
}

/// The rotation matrix `exp(r̂)` of a rotation vector (the inverse of [`rotation_vector`]), for
/// output: a section frame from the rotation vector a shape reports.
pub fn rotation_matrix(r: [f64; 3]) -> [[f64; 3]; 3] {
    exp_and_tangent(&r, &Coefficients::of(&r)).0
}

/// The rotation vector of a rotation matrix (`log`, the inverse of [`exp`] for angles in
/// `[0, π]`), for output: the axis from the skew part, the angle from `atan2` of the skew part's
/// norm and the trace (accurate at every angle; near π from the symmetric part).
pub fn rotation_vector(r: &[[f64; 3]; 3]) -> [f64; 3] {
    let w = [
        0.5 * (r[2][1] - r[1][2]),
        0.5 * (r[0][2] - r[2][0]),
        0.5 * (r[1][0] - r[0][1]),
    ];
    let sin = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let cos = 0.5 * (r[0][0] + r[1][1] + r[2][2] - 1.0);
    let angle = sin.atan2(cos);
    if angle < 1e-8 {
        // θ/sin θ = 1 + θ²/6: below 1e-8 the factor is 1 to round-off.
        return w;
    }
    if cos > -0.9 {
        let f = angle / sin;
        return [w[0] * f, w[1] * f, w[2] * f];
    }
    // Near π: the axis from the largest diagonal of (R + Rᵀ)/2 − cos θ I = (1 − cos θ) u uᵀ.
    let k = (0..3)
        .max_by(|&i, &j| r[i][i].total_cmp(&r[j][j]))
        .unwrap_or(0);
    let one_m_cos = 1.0 - cos;
    let mut u = [0.0; 3];
    for i in 0..3 {
        u[i] = 0.5 * (r[i][k] + r[k][i]) - if i == k { cos } else { 0.0 };
    }
    let norm = (u[k] * one_m_cos).sqrt();
    for v in u.iter_mut() {
        *v /= norm;
    }
    // The sign from the skew part (sin θ u = w).
    let s = if u[0] * w[0] + u[1] * w[1] + u[2] * w[2] < 0.0 {
        -1.0
    } else {
        1.0
    };
    [s * angle * u[0], s * angle * u[1], s * angle * u[2]]
}

#[cfg(test)]
mod tests {
    use super::super::algebra::{mm, mtm, mv, transpose};
    use super::*;
    use num_dual::{Dual64, DualStruct};

    fn coefficients_f64(phi: &[f64; 3]) -> Coefficients<f64> {
        Coefficients::of(phi)
    }

    #[test]
    fn series_and_closed_forms_agree_at_the_switch() {
        // Just below and above θ² = 4, and the closed forms' own values in between: the
        // coefficients agree to 1e-14 relative (measured 3e-16 for s, a, b; 4e-15 for b').
        for s2 in [3.999_999, 4.0, 4.000_001] {
            let lo = Coefficients::<f64>::series(s2);
            let hi = Coefficients::<f64>::closed(s2);
            for (x, y) in [
                (lo.s, hi.s),
                (lo.a, hi.a),
                (lo.b, hi.b),
                (lo.da, hi.da),
                (lo.db, hi.db),
            ] {
                assert!((x / y - 1.0).abs() < 1e-13, "θ² = {s2}: {x} vs {y}");
            }
        }
        // At θ = 0 the series are the Taylor coefficients.
        let c = Coefficients::<f64>::series(0.0);
        assert_eq!((c.s, c.a, c.b), (1.0, 0.5, 1.0 / 6.0));
        assert!((c.da + 1.0 / 24.0).abs() < 1e-17 && (c.db + 1.0 / 120.0).abs() < 1e-17);
    }

    #[test]
    fn exp_is_a_rotation_about_its_vector() {
        for phi in [
            [0.3, -0.2, 0.5],
            [1.5, 2.0, -0.7],
            [0.0, 0.0, 3.0],
            [1e-9, 0.0, 0.0],
        ] {
            let r = exp(&phi, &coefficients_f64(&phi));
            let rtr = mtm(&r, &r);
            for i in 0..3 {
                for j in 0..3 {
                    let e = if i == j { 1.0 } else { 0.0 };
                    assert!((rtr[i][j] - e).abs() < 1e-15);
                }
            }
            let axis = mv(&r, &phi);
            for k in 0..3 {
                assert!((axis[k] - phi[k]).abs() < 1e-15);
            }
            let back = rotation_vector(&r);
            for k in 0..3 {
                assert!((back[k] - phi[k]).abs() < 1e-13, "{back:?} vs {phi:?}");
            }
        }
        // About z by θ: the plane rotation.
        let th: f64 = 0.7;
        let r = exp(&[0.0, 0.0, th], &coefficients_f64(&[0.0, 0.0, th]));
        assert!((r[0][0] - th.cos()).abs() < 1e-16 && (r[1][0] - th.sin()).abs() < 1e-16);
    }

    #[test]
    fn left_tangent_gives_the_spatial_angular_velocity() {
        // (d/dt exp(φ̂)) exp(φ̂)ᵀ = (T_L φ̇)^, with the time derivative from dual numbers.
        for phi in [[0.3, -0.2, 0.5], [1.5, 2.0, -0.7], [0.0, 0.0, 0.0]] {
            let v = [0.4, 1.1, -0.6];
            let pd: [Dual64; 3] = std::array::from_fn(|k| Dual64::new(phi[k], v[k]));
            let r = exp(&pd, &Coefficients::of(&pd));
            let rdot: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[i][j].eps));
            let rre: [[f64; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|j| r[i][j].re()));
            let w = mm(&rdot, &transpose(&rre));
            let want = tangent_left_times(&phi, &v, &coefficients_f64(&phi));
            let got = [w[2][1], w[0][2], w[1][0]];
            for k in 0..3 {
                assert!((got[k] - want[k]).abs() < 1e-14, "{got:?} vs {want:?}");
            }
            let tl = tangent_left(&phi, &coefficients_f64(&phi));
            let tv = mv(&tl, &v);
            for k in 0..3 {
                assert!((tv[k] - want[k]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn derivative_of_the_tangent_matches_dual_numbers() {
        // On both sides of the series/closed-form switch and at zero.
        for phi in [
            [0.3, -0.2, 0.5],
            [1.5, 2.0, -0.7],
            [0.0, 0.0, 0.0],
            [1.2, 1.0, 1.0],
        ] {
            let v = [0.4, 1.1, -0.6];
            let d = tangent_left_derivative(&phi, &v, &coefficients_f64(&phi));
            for j in 0..3 {
                let pd: [Dual64; 3] =
                    std::array::from_fn(|k| Dual64::new(phi[k], if k == j { 1.0 } else { 0.0 }));
                let vd: [Dual64; 3] = std::array::from_fn(|k| Dual64::from(v[k]));
                let t = tangent_left_times(&pd, &vd, &Coefficients::of(&pd));
                for i in 0..3 {
                    assert!((t[i].eps - d[i][j]).abs() < 1e-14, "{phi:?}: ({i}, {j})");
                }
            }
        }
    }
}
