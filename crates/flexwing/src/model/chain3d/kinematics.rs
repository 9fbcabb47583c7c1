//! Forward kinematics of the 3-D chain (docs/chain3d-model.md, "Kinematics"), generic over the
//! scalar so that dual numbers differentiate it:
//!
//! ```text
//! B_i = R_{i−1} R⁰_i,   R_i = B_i exp(φ̂_i),   H_i = B_i T_L(φ_i)        (R_{−1} = I)
//! P_0 = 0,   P_{i+1} = P_i + ℓ_i t_i,   g_i = P_i + R_i ρ_i,   I_i = R_i J_i R_iᵀ
//! ω_i = ω_{i−1} + H_i φ̇_i,   V_0 = 0,   V_{i+1} = V_i + ω_i × (P_{i+1} − P_i),
//! ġ_i = V_i + ω_i × (R_i ρ_i)
//! ```
//!
//! `φ_i` is the rotation vector of joint `i` in the frame of element `i` (the same components
//! before and after the joint's rotation, since `exp(φ̂) φ = φ`), `H_i` maps its rate to the
//! global angular velocity it adds: a change `δφ_i` turns everything outboard of node `i` rigidly
//! about `P_i` by the global small rotation `H_i δφ_i`.

use super::algebra::{add, column, cross, dot, lift, lift_m, mm, mmt, mv, zero, Real, M3, V3};
use super::rotation::{exp_and_tangent, Coefficients};
use super::Chain3d;

/// The kinematics of one configuration: frames, joint axes, node positions, mass-centre arms and
/// the elements' inertia tensors, in global components.
#[derive(Debug, Clone)]
pub(crate) struct Frames<D> {
    /// Element orientations `R_i`.
    pub(crate) r: Vec<M3<D>>,
    /// `B_i = R_{i−1} R⁰_i`: the frame of element `i` before its joint's rotation.
    pub(crate) b: Vec<M3<D>>,
    /// Joint axes `H_i = B_i T_L(φ_i)`.
    pub(crate) h: Vec<M3<D>>,
    /// The joint rotation vectors `φ_i` and their coefficients.
    pub(crate) phi: Vec<V3<D>>,
    pub(crate) coefficients: Vec<Coefficients<D>>,
    /// Node positions `P_0 … P_n`.
    pub(crate) p: Vec<V3<D>>,
    /// `P_{i+1} − P_i = ℓ_i t_i`.
    pub(crate) d: Vec<V3<D>>,
    /// Mass-centre arms `R_i ρ_i = g_i − P_i`.
    pub(crate) arm: Vec<V3<D>>,
    /// Inertia tensors about the mass centres `I_i = R_i J_i R_iᵀ`.
    pub(crate) inertia: Vec<M3<D>>,
}

impl Frames<num_dual::Dual64> {
    /// The real frames of elements `from..end` of `base` (and nodes `from..=end`) as dual
    /// numbers with zero dual parts: with the elements before `from` already lifted, the part
    /// of the chain a change of joint `end` does not move. `kinetic` also lifts what the
    /// kinetic terms read (pre-joint frames, rotation vectors and their coefficients, arms,
    /// inertia tensors); the strips need the frames, joint axes and nodes only.
    pub(crate) fn lift_range(
        &mut self,
        base: &Frames<f64>,
        from: usize,
        end: usize,
        kinetic: bool,
    ) {
        use num_dual::Dual64;
        let l3 = |m: &M3<f64>| m.map(|r| r.map(Dual64::from));
        for i in from..end {
            self.r[i] = l3(&base.r[i]);
            self.h[i] = l3(&base.h[i]);
            self.d[i] = lift(&base.d[i]);
            if kinetic {
                self.b[i] = l3(&base.b[i]);
                self.phi[i] = lift(&base.phi[i]);
                self.arm[i] = lift(&base.arm[i]);
                self.inertia[i] = l3(&base.inertia[i]);
                let c = &base.coefficients[i];
                self.coefficients[i] = Coefficients {
                    s: Dual64::from(c.s),
                    a: Dual64::from(c.a),
                    b: Dual64::from(c.b),
                    da: Dual64::from(c.da),
                    db: Dual64::from(c.db),
                };
            }
        }
        for i in from..=end {
            self.p[i] = lift(&base.p[i]);
        }
    }
}

impl<D: Real> Frames<D> {
    pub(crate) fn new(n: usize) -> Self {
        let z = [[D::from(0.0); 3]; 3];
        let c = Coefficients::of(&zero::<D>());
        Self {
            r: vec![z; n],
            b: vec![z; n],
            h: vec![z; n],
            phi: vec![zero(); n],
            coefficients: vec![c; n],
            p: vec![zero(); n + 1],
            d: vec![zero(); n],
            arm: vec![zero(); n],
            inertia: vec![z; n],
        }
    }
}

/// Velocities of one motion, and the outboard momenta: `ω_i`, `V_i` (of node `i`), `ġ_i`, the
/// linear momentum `Π_j = Σ_{i≥j} m_i ġ_i` and the angular momentum about `P_j`,
/// `L_j = Σ_{i≥j} (m_i (g_i − P_j) × ġ_i + I_i ω_i)`.
#[derive(Debug, Clone)]
pub(crate) struct Motion<D> {
    pub(crate) omega: Vec<V3<D>>,
    pub(crate) v: Vec<V3<D>>,
    pub(crate) gdot: Vec<V3<D>>,
    pub(crate) l: Vec<V3<D>>,
    pub(crate) pi: Vec<V3<D>>,
}

impl<D: Real> Motion<D> {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            omega: vec![zero(); n],
            v: vec![zero(); n],
            gdot: vec![zero(); n],
            l: vec![zero(); n],
            pi: vec![zero(); n],
        }
    }
}

impl Chain3d {
    /// The kinematics of the configuration `x` (`3n` entries, joint-major) into `fr`. O(n).
    pub(crate) fn configure<D: Real>(&self, x: &[D], fr: &mut Frames<D>) {
        self.configure_from(x, fr, 0, true);
    }

    /// [`Chain3d::configure`] of elements `start ..` only, from the frames of the elements
    /// before `start` already in `fr` (those of `x`): a change of joint `start` moves nothing
    /// inboard of it, so a directional derivative along it costs O(n − start). Without
    /// `inertia`, the mass-centre arms and inertia tensors are not computed (the strips need
    /// the frames, joint axes and nodes only).
    pub(crate) fn configure_from<D: Real>(
        &self,
        x: &[D],
        fr: &mut Frames<D>,
        start: usize,
        inertia: bool,
    ) {
        let n = self.n;
        debug_assert_eq!(x.len(), 3 * n);
        let mut prev: M3<D> = if start == 0 {
            super::algebra::identity()
        } else {
            fr.r[start - 1]
        };
        let mut node: V3<D> = if start == 0 { zero() } else { fr.p[start] };
        fr.p[start] = node;
        let straight = self.beam.reference.straight;
        for i in start..n {
            let phi = [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
            let c = Coefficients::of(&phi);
            let b = if straight {
                prev
            } else {
                mm(&prev, &lift_m(&self.beam.reference.relative[i]))
            };
            let (e, t) = exp_and_tangent(&phi, &c);
            let r = mm(&b, &e);
            let h = mm(&b, &t);
            let l = D::from(self.beam.reference.lengths[i]);
            let d = [r[0][0] * l, r[1][0] * l, r[2][0] * l];
            if inertia {
                fr.arm[i] = mv(&r, &lift(&self.beam.arms[i]));
                let j = self.beam.inertias[i];
                // R J Rᵀ with J diagonal: (R diag(J)) Rᵀ.
                let rj: M3<D> = std::array::from_fn(|a| std::array::from_fn(|k| r[a][k] * j[k]));
                fr.inertia[i] = mmt(&rj, &r);
            }
            fr.phi[i] = phi;
            fr.coefficients[i] = c;
            fr.b[i] = b;
            fr.h[i] = h;
            fr.r[i] = r;
            fr.d[i] = d;
            node = add(&node, &d);
            fr.p[i + 1] = node;
            prev = r;
        }
    }

    /// Velocities `ω_i`, `V_i`, `ġ_i` of the rates `xdot` at the configuration `fr`, and the
    /// outboard momenta `Π_j`, `L_j`, into `mo`. O(n).
    pub(crate) fn motion<D: Real>(&self, fr: &Frames<D>, xdot: &[D], mo: &mut Motion<D>) {
        let n = self.n;
        let mut omega: V3<D> = zero();
        let mut v: V3<D> = zero();
        for i in 0..n {
            let rate = [xdot[3 * i], xdot[3 * i + 1], xdot[3 * i + 2]];
            omega = add(&omega, &mv(&fr.h[i], &rate));
            mo.omega[i] = omega;
            mo.v[i] = v;
            mo.gdot[i] = add(&v, &cross(&omega, &fr.arm[i]));
            v = add(&v, &cross(&omega, &fr.d[i]));
        }
        let mut pi: V3<D> = zero();
        let mut l: V3<D> = zero();
        for j in (0..n).rev() {
            let m = D::from(self.beam.masses[j]);
            let mut own = super::algebra::scale(m, &mo.gdot[j]);
            // About P_j: L_{j+1} moved from P_{j+1} by (P_{j+1} − P_j) × Π_{j+1}.
            l = add(
                &add(&l, &cross(&fr.d[j], &pi)),
                &add(&cross(&fr.arm[j], &own), &mv(&fr.inertia[j], &mo.omega[j])),
            );
            if let Some(f) = &self.fluid {
                // The fluid's momenta: m_a u n at the mid-chord point (arm a_f from P_j) and
                // J_a (ω·t) t, with u = n·(V_j + ω_j × a_f).
                let (u, arm, axis) = self.fluid_motion(fr, mo, j);
                let lin = super::algebra::scale(u * f.mass[j], &column(&fr.r[j], 1));
                let spin = dot(&mo.omega[j], &axis) * f.inertia[j];
                l = add(
                    &l,
                    &add(&cross(&arm, &lin), &super::algebra::scale(spin, &axis)),
                );
                own = add(&own, &lin);
            }
            pi = add(&pi, &own);
            mo.l[j] = l;
            mo.pi[j] = pi;
        }
    }

    /// The fluid's motion at element `j` (the chain must carry fluid inertia): the normal
    /// velocity `u = n·(V_j + ω_j × a_f)` of the mid-chord point, its arm `a_f = ½ d_j + ζ_m c_j`
    /// from `P_j`, and the span axis `t_j`.
    pub(crate) fn fluid_motion<D: Real>(
        &self,
        fr: &Frames<D>,
        mo: &Motion<D>,
        j: usize,
    ) -> (D, V3<D>, V3<D>) {
        let f = self.fluid.as_ref().expect("a wet chain");
        let r = &fr.r[j];
        let arm = add(
            &super::algebra::scale(D::from(0.5), &fr.d[j]),
            &super::algebra::scale(D::from(f.station[j]), &column(r, 2)),
        );
        let v = add(&mo.v[j], &cross(&mo.omega[j], &arm));
        (dot(&column(r, 1), &v), arm, column(r, 0))
    }
}
