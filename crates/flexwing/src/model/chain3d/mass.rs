//! The mass matrix of the 3-D chain by the composite-rigid-body algorithm (Featherstone, *Rigid
//! Body Dynamics Algorithms*, 2008, §6.2), O(n²) blocks of 3×3, and the spatial-inertia algebra
//! it shares with the articulated-body solve (`aba.rs`).
//!
//! Spatial quantities are in global components about a point: a motion `(ω, v)` (`v` the
//! velocity of the body point at the reference point), a force `(moment, force)`. A body of mass
//! `m`, mass centre `P + c`, inertia `I` about its mass centre has the spatial inertia about `P`
//!
//! ```text
//! ⎡ I − m ĉ ĉ   m ĉ ⎤     (moment, force) = I_P (ω, v)
//! ⎣ −m ĉ        m 1 ⎦
//! ```
//!
//! Moving the reference point from `P' = P + d` to `P`: a force `(n, f) → (n + d × f, f)`, a
//! motion `(ω, v) → (ω, v − d × ω)`, an inertia `I_P = Xᵀ I_P' X` with `X = [1 0; −d̂ 1]`.

use nalgebra::DMatrix;

use super::algebra::{add, column, hat, madd, mm, mscale, msub, mtm, scale, transpose, Real, M3};
use super::kinematics::Frames;
use super::Chain3d;

/// A symmetric spatial inertia `[[a, b], [bᵀ, c]]` (3×3 blocks).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Spatial<D> {
    pub(crate) a: M3<D>,
    pub(crate) b: M3<D>,
    pub(crate) c: M3<D>,
}

impl<D: Real> Spatial<D> {
    pub(crate) fn zero() -> Self {
        let z = [[D::from(0.0); 3]; 3];
        Self { a: z, b: z, c: z }
    }

    /// Body `i` about its inboard node `P_i`.
    pub(crate) fn body(model: &Chain3d, fr: &Frames<D>, i: usize) -> Self {
        let m = D::from(model.beam.masses[i]);
        let ch = hat(&fr.arm[i]);
        let mut c = [[D::from(0.0); 3]; 3];
        for k in 0..3 {
            c[k][k] = m;
        }
        let mut body = Self {
            a: msub(&fr.inertia[i], &mscale(m, &mm(&ch, &ch))),
            b: mscale(m, &ch),
            c,
        };
        if let Some(f) = &model.fluid {
            // The fluid's directional mass A = m_a n nᵀ at the mid-chord point (arm r from P_i)
            // and its polar inertia J = J_a t tᵀ: [[J − r̂ A r̂, r̂ A], [−A r̂, A]].
            let r = &fr.r[i];
            let arm = add(
                &scale(D::from(0.5), &fr.d[i]),
                &scale(D::from(f.station[i]), &column(r, 2)),
            );
            let (n, t) = (column(r, 1), column(r, 0));
            let a: M3<D> =
                std::array::from_fn(|p| std::array::from_fn(|q| n[p] * n[q] * f.mass[i]));
            let j: M3<D> =
                std::array::from_fn(|p| std::array::from_fn(|q| t[p] * t[q] * f.inertia[i]));
            let rh = hat(&arm);
            let ra = mm(&rh, &a);
            body.a = madd(&body.a, &msub(&j, &mm(&ra, &rh)));
            body.b = madd(&body.b, &ra);
            body.c = madd(&body.c, &a);
        }
        body
    }

    /// `self + Xᵀ other X`: `other`, about `P + d`, added about `P`.
    pub(crate) fn add_moved(&mut self, other: &Self, d: &[D; 3]) {
        let dh = hat(d);
        // a − b d̂ + d̂ bᵀ − d̂ c d̂,  b + d̂ c,  c.
        let bd = mm(&other.b, &dh);
        let dbt = transpose(&bd);
        let dcd = mm(&dh, &mm(&other.c, &dh));
        for r in 0..3 {
            for k in 0..3 {
                self.a[r][k] += other.a[r][k] - bd[r][k] - dbt[r][k] - dcd[r][k];
            }
        }
        let dc = mm(&dh, &other.c);
        for r in 0..3 {
            for k in 0..3 {
                self.b[r][k] += other.b[r][k] + dc[r][k];
                self.c[r][k] += other.c[r][k];
            }
        }
    }
}

impl Chain3d {
    /// The mass matrix `M(x)` (`3n × 3n`) at the configuration `fr` into `out`: composite
    /// inertias from the tip, `M_ji = H_jᵀ [moment of I^C_i S_i moved to P_j]` for `j ≤ i`.
    pub(crate) fn mass_matrix_frames(&self, fr: &Frames<f64>, out: &mut DMatrix<f64>) {
        let n = self.n;
        assert_eq!(
            out.shape(),
            (3 * n, 3 * n),
            "mass matrix has the wrong shape"
        );
        let mut composite = Spatial::<f64>::zero();
        for i in (0..n).rev() {
            let mut ic = Spatial::body(self, fr, i);
            if i + 1 < n {
                ic.add_moved(&composite, &fr.d[i]);
            }
            composite = ic;
            let h = &fr.h[i];
            // F = I^C S: moment a H, force bᵀ H (about P_i).
            let mut top = mm(&composite.a, h);
            let bottom = mtm(&composite.b, h);
            for j in (0..=i).rev() {
                if j < i {
                    // Move the force from P_{j+1} to P_j: moment += d_j × force.
                    let dh = hat(&fr.d[j]);
                    let add = mm(&dh, &bottom);
                    for r in 0..3 {
                        for k in 0..3 {
                            top[r][k] += add[r][k];
                        }
                    }
                }
                let block = mtm(&fr.h[j], &top);
                for r in 0..3 {
                    for k in 0..3 {
                        out[(3 * j + r, 3 * i + k)] = block[r][k];
                        out[(3 * i + k, 3 * j + r)] = block[r][k];
                    }
                }
            }
        }
    }
}
