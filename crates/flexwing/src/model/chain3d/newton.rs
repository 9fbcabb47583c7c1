//! O(n) solves of the implicit integrators' Newton systems `(c I − J) Δ = r` on the 3-D chain's
//! Hamiltonian state `(x, p)` (docs/chain3d-model.md, "O(n) Newton systems").
//!
//! As for the planar chain (`solve/eom_newton.rs`), the first block row gives `δẋ = c Δx − r_x`
//! and `Δp = M δẋ + B Δx` (`B = ∂(M ẋ)/∂x`), and the second becomes
//!
//! ```text
//! S Δx = r_p + (c M − g Bᵀ + C) r_x,     S = c² M + c (B − g Bᵀ) + K − ∂Q/∂x − g ∂γ/∂x|_ẋ + c C
//! ```
//!
//! (`g = 1` with the gyroscopic term, 0 without). Every product with `M`, `B`, `Bᵀ`, `∂γ/∂x` and
//! `∂Q/∂x` is one forward-mode dual-number pass through the O(n) recursions along a direction
//! `(δx, δẋ)`: `δp = B δx + M δẋ`, `δγ = ∂γ/∂x δx + Bᵀ δẋ`, `δQ = ∂Q/∂x δx`, so `S v` is one pass
//! along `(v, c v)` (two for a complex shift, real and imaginary parts). `S` is solved by GMRES
//! (Saad & Schultz, SIAM J. Sci. Stat. Comput. 7, 1986; restarted, modified Gram–Schmidt,
//! Givens rotations) preconditioned on the right by `P = c² M + K`, which the articulated-body
//! algorithm factors and solves in O(n) with the joint springs as the joints' armature
//! (`aba.rs`): `P⁻¹ S = I + P⁻¹ (c (B − g Bᵀ) − ∂Q/∂x − g ∂γ/∂x + c C)`, close to the identity
//! when the velocities are small against `|c|` times the lengths and the loads' stiffness small
//! against the springs', so a handful of iterations reach round-off. For a complex shift `P`
//! takes `|c|²` for `c²` (real, so one factorization serves both parts). Damping enters `S`
//! exactly (the damping operator's product), so the Newton iteration is exact for every model;
//! only the preconditioner approximates Rayleigh damping (`α M(x)` for `α M(0)`), and leaves
//! modal damping out.
//!
//! Cost per solve: `(iterations + 3)` passes (twice that for a complex shift) of a few
//! right-hand sides each, O(n); nothing is formed. The iteration stops at a residual of
//! [`RELATIVE_TOLERANCE`] of the right-hand side's norm, or after [`MAX_ITERATIONS`] (the
//! best iterate is returned; Newton then fails to converge and the integrator shrinks its step,
//! which brings `P` closer to `S`).

use nalgebra::{Complex, ComplexField};
use num_dual::Dual64;

use super::aba::Articulated;
use super::algebra::{mv, zero, V3};
use super::kinematics::{Frames, Motion};
use super::Chain3d;
use crate::model::AppliedLoads;

/// GMRES stops at this residual relative to the right-hand side: the Newton iterations then
/// solve the exact Jacobian's systems to round-off of the dense LU (1e-12, not 1e-15: the
/// operator's condition number, up to ~1e8 at small steps, bounds what any solve reaches).
pub(crate) const RELATIVE_TOLERANCE: f64 = 1e-12;
/// A solve that stagnates within this factor of [`RELATIVE_TOLERANCE`] counts as converged.
const STAGNATION: f64 = 1e3;
/// Iterations before GMRES restarts from its current iterate.
const RESTART: usize = 40;
/// Iterations in all before a solve gives up.
pub(crate) const MAX_ITERATIONS: usize = 200;

/// The damping product `out = C v` the equations of motion apply (zeros without damping).
pub(crate) type DampingProduct<'a> = &'a mut dyn FnMut(&[f64], &mut [f64]);

/// Dual-number scratch of the directional derivatives ([`Chain3d::directional`]).
#[derive(Debug, Clone)]
pub(crate) struct Directional {
    fr: Frames<Dual64>,
    mo: Motion<Dual64>,
    x: Vec<Dual64>,
    xdot: Vec<Dual64>,
    p: Vec<Dual64>,
    g: Vec<Dual64>,
    q: Vec<Dual64>,
    own_f: Vec<V3<Dual64>>,
    own_n: Vec<V3<Dual64>>,
}

impl Directional {
    pub(crate) fn new(n: usize) -> Self {
        let zd = Dual64::from(0.0);
        let nd = 3 * n;
        Self {
            fr: Frames::new(n),
            mo: Motion::new(n),
            x: vec![zd; nd],
            xdot: vec![zd; nd],
            p: vec![zd; nd],
            g: vec![zd; nd],
            q: vec![zd; nd],
            own_f: vec![zero(); n],
            own_n: vec![zero(); n],
        }
    }
}

/// A factorization slot: the shift and the articulated factorization of `P`.
type Slot<T> = (T, Articulated<f64>);

/// The linearization point and the directional passes there.
#[derive(Debug, Clone)]
struct Point {
    x: Vec<f64>,
    xdot: Vec<f64>,
    scales: Vec<f64>,
    dir: Directional,
    gyroscopic: bool,
    /// Results of the last pass and scratch, of length `n_dofs`.
    dp: Vec<f64>,
    dg: Vec<f64>,
    dq: Vec<f64>,
    tmp: Vec<f64>,
    tmp2: Vec<f64>,
}

impl Point {
    /// One directional pass at the linearization point into `(dp, dg, dq)`.
    fn pass(&mut self, model: &Chain3d, loads: &AppliedLoads, dx: &[f64], dxdot: &[f64]) {
        model.directional(
            &mut self.dir,
            (&self.x, &self.xdot),
            (dx, dxdot),
            Some((loads, &self.scales)),
            self.gyroscopic,
            (&mut self.dp, &mut self.dg, &mut self.dq),
        );
    }
}

/// State of the O(n) Newton solves of one run on the 3-D chain.
#[derive(Debug, Clone)]
pub(crate) struct Newton3d {
    pt: Point,
    /// Real frames of the linearization point.
    fr: Frames<f64>,
    real: Vec<Slot<f64>>,
    complex: Vec<Slot<Complex<f64>>>,
    /// Rayleigh `(α, β)` for the preconditioner; `(0, 0)` otherwise.
    rayleigh: (f64, f64),
    /// GMRES iterations of every solve so far.
    pub(crate) iterations: usize,
    /// Solves so far, and those that stopped at [`MAX_ITERATIONS`] unconverged.
    pub(crate) solves: usize,
    pub(crate) unconverged: usize,
    /// Krylov bases kept between solves.
    basis: Vec<Vec<Complex<f64>>>,
    basis_real: Vec<Vec<f64>>,
}

impl Chain3d {
    /// `(δp, δγ, δQ)` along `(δx, δẋ)` at `(x, ẋ)`: one dual-number pass (module documentation).
    /// `δγ` is left zero without `gyroscopic`, `δQ` without loads at these scales.
    pub(crate) fn directional(
        &self,
        d: &mut Directional,
        (x, xdot): (&[f64], &[f64]),
        (dx, dxdot): (&[f64], &[f64]),
        loads: Option<(&AppliedLoads, &[f64])>,
        gyroscopic: bool,
        (dp, dg, dq): (&mut [f64], &mut [f64], &mut [f64]),
    ) {
        for (k, v) in d.x.iter_mut().enumerate() {
            *v = Dual64::new(x[k], dx[k]);
        }
        for (k, v) in d.xdot.iter_mut().enumerate() {
            *v = Dual64::new(xdot[k], dxdot[k]);
        }
        self.configure(&d.x, &mut d.fr);
        let gamma = gyroscopic.then_some(d.g.as_mut_slice());
        self.kinetic_terms(&d.fr, &d.xdot, &mut d.mo, Some(&mut d.p), gamma);
        for (o, v) in dp.iter_mut().zip(&d.p) {
            *o = v.eps;
        }
        match gyroscopic {
            true => dg.iter_mut().zip(&d.g).for_each(|(o, v)| *o = v.eps),
            false => dg.fill(0.0),
        }
        match loads.filter(|(l, s)| l.spatial.iter().any(|it| s[it.load] != 0.0)) {
            Some((loads, scales)) => {
                self.forces_frames(&d.fr, loads, scales, &mut d.own_f, &mut d.own_n, &mut d.q);
                dq.iter_mut().zip(&d.q).for_each(|(o, v)| *o = v.eps);
            }
            None => dq.fill(0.0),
        }
    }

    /// `out = K v`, joint block by joint block.
    pub(crate) fn stiffness_product(&self, v: &[f64], out: &mut [f64]) {
        for (i, k) in self.beam.stiffness.iter().enumerate() {
            let kv = mv(k, &[v[3 * i], v[3 * i + 1], v[3 * i + 2]]);
            out[3 * i..3 * i + 3].copy_from_slice(&kv);
        }
    }
}

/// The preconditioner's factors for `s1 = c`, `s2 = c²` (or `|c|`, `|c|²`) with Rayleigh
/// `(α, β)`: `P = (s2 + α s1) (M + K (1 + β s1)/(s2 + α s1))`, returned as (mass factor,
/// spring factor).
fn spring_factor((alpha, beta): (f64, f64), s1: f64, s2: f64) -> (f64, f64) {
    let mass = s2 + alpha * s1;
    (mass, (1.0 + beta * s1) / mass)
}

impl Newton3d {
    /// For `model` with Rayleigh coefficients `rayleigh` (`(0, 0)` for other damping) and
    /// `n_loads` loads; `gyroscopic` tells whether the equations have the gyroscopic term.
    pub(crate) fn new(
        model: &Chain3d,
        rayleigh: (f64, f64),
        gyroscopic: bool,
        n_loads: usize,
    ) -> Self {
        let (n, nd) = (model.n, model.n_dofs());
        let z = || vec![0.0; nd];
        Self {
            pt: Point {
                x: z(),
                xdot: z(),
                scales: vec![0.0; n_loads],
                dir: Directional::new(n),
                gyroscopic,
                dp: z(),
                dg: z(),
                dq: z(),
                tmp: z(),
                tmp2: z(),
            },
            fr: Frames::new(n),
            real: Vec::new(),
            complex: Vec::new(),
            rayleigh,
            iterations: 0,
            solves: 0,
            unconverged: 0,
            basis: Vec::new(),
            basis_real: Vec::new(),
        }
    }

    /// Linearize at `(x, p)` with the load scales `scales`; false if `M(x)` is not positive
    /// definite there.
    pub(crate) fn linearize(
        &mut self,
        model: &Chain3d,
        x: &[f64],
        p: &[f64],
        scales: &[f64],
    ) -> bool {
        model.configure(x, &mut self.fr);
        self.pt.x.copy_from_slice(x);
        self.pt.scales.copy_from_slice(scales);
        let mut ab = Articulated::new(model.n);
        if !model.factor_mass(&self.fr, &mut ab) {
            return false;
        }
        model.solve_mass(&self.fr, &mut ab, p, &mut self.pt.xdot);
        self.pt.xdot.iter().all(|v| v.is_finite())
    }

    pub(crate) fn factor_real(&mut self, model: &Chain3d, slot: usize, c: f64) -> bool {
        while self.real.len() <= slot {
            self.real.push((0.0, Articulated::new(model.n)));
        }
        let (mass, spring) = spring_factor(self.rayleigh, c, c * c);
        if !(mass > 0.0 && spring.is_finite()) {
            return false;
        }
        let s = &mut self.real[slot];
        s.0 = c;
        model.factor_mass_spring(&self.fr, &mut s.1, spring)
    }

    pub(crate) fn factor_complex(&mut self, model: &Chain3d, slot: usize, c: Complex<f64>) -> bool {
        while self.complex.len() <= slot {
            let z = Complex::new(0.0, 0.0);
            self.complex.push((z, Articulated::new(model.n)));
        }
        let m = c.norm();
        let (mass, spring) = spring_factor(self.rayleigh, m, m * m);
        if !(mass > 0.0 && spring.is_finite()) {
            return false;
        }
        let s = &mut self.complex[slot];
        s.0 = c;
        model.factor_mass_spring(&self.fr, &mut s.1, spring)
    }

    /// `b = (r_x, r_p) ← (Δx, Δp)` for the real shift of `slot` (module documentation).
    pub(crate) fn solve_real(
        &mut self,
        model: &Chain3d,
        loads: &AppliedLoads,
        damping: DampingProduct<'_>,
        slot: usize,
        b: &mut [f64],
    ) {
        let nd = model.n_dofs();
        let (rq, rp) = b.split_at_mut(nd);
        let c = self.real[slot].0;
        let zeros = vec![0.0; nd];
        let pt = &mut self.pt;
        // rhs = r_p + (c M − g Bᵀ + C) r_x.
        pt.pass(model, loads, &zeros, rq);
        damping(rq, &mut pt.tmp);
        let rhs: Vec<f64> = (0..nd)
            .map(|i| rp[i] + c * pt.dp[i] - pt.dg[i] + pt.tmp[i])
            .collect();
        let mut dx = vec![0.0; nd];
        let (mass, _) = spring_factor(self.rayleigh, c, c * c);
        let (fr, ab) = (&self.fr, &mut self.real[slot].1);
        let mut cv = vec![0.0; nd];
        let mut scratch = vec![0.0; nd];
        let (iterations, converged) = gmres(
            &rhs,
            &mut dx,
            &mut self.basis_real,
            &mut |v: &[f64], out: &mut [f64]| {
                for (o, x) in cv.iter_mut().zip(v) {
                    *o = c * x;
                }
                pt.pass(model, loads, v, &cv);
                damping(v, &mut pt.tmp);
                model.stiffness_product(v, &mut pt.tmp2);
                for i in 0..nd {
                    out[i] = c * pt.dp[i] - pt.dg[i] + pt.tmp2[i] - pt.dq[i] + c * pt.tmp[i];
                }
            },
            &mut |w: &mut [f64]| {
                scratch.copy_from_slice(w);
                model.solve_mass(fr, ab, &scratch, w);
                w.iter_mut().for_each(|v| *v /= mass);
            },
        );
        self.count(iterations, converged);
        // Δp = M (c Δx − r_x) + B Δx.
        for i in 0..nd {
            cv[i] = c * dx[i] - rq[i];
        }
        let pt = &mut self.pt;
        pt.pass(model, loads, &dx, &cv);
        rp.copy_from_slice(&pt.dp);
        rq.copy_from_slice(&dx);
    }

    /// `(re, im) = (r_x, r_p) ← (Δx, Δp)` for the complex shift of `slot`.
    pub(crate) fn solve_complex(
        &mut self,
        model: &Chain3d,
        loads: &AppliedLoads,
        damping: DampingProduct<'_>,
        slot: usize,
        re: &mut [f64],
        im: &mut [f64],
    ) {
        let nd = model.n_dofs();
        let (rq_re, rp_re) = re.split_at_mut(nd);
        let (rq_im, rp_im) = im.split_at_mut(nd);
        let c = self.complex[slot].0;
        let zeros = vec![0.0; nd];
        let pt = &mut self.pt;
        // rhs = r_p + (c M − g Bᵀ + C) r_x, by parts: (M r, Bᵀ r, C r) of each part.
        pt.pass(model, loads, &zeros, rq_re);
        damping(rq_re, &mut pt.tmp);
        let part_re: Vec<[f64; 3]> = (0..nd).map(|i| [pt.dp[i], pt.dg[i], pt.tmp[i]]).collect();
        pt.pass(model, loads, &zeros, rq_im);
        damping(rq_im, &mut pt.tmp);
        let rhs: Vec<Complex<f64>> = (0..nd)
            .map(|i| {
                let [m, bt, cr] = part_re[i];
                let m = Complex::new(m, pt.dp[i]);
                let bt = Complex::new(bt, pt.dg[i]);
                let cr = Complex::new(cr, pt.tmp[i]);
                Complex::new(rp_re[i], rp_im[i]) + c * m - bt + cr
            })
            .collect();
        let mut dx = vec![Complex::new(0.0, 0.0); nd];
        let m = c.norm();
        let (mass, _) = spring_factor(self.rayleigh, m, m * m);
        let (fr, ab) = (&self.fr, &mut self.complex[slot].1);
        let (mut vr, mut vi, mut cvr, mut cvi) =
            (zeros.clone(), zeros.clone(), zeros.clone(), zeros.clone());
        let (mut pr, mut pi, mut zr, mut zi) =
            (zeros.clone(), zeros.clone(), zeros.clone(), zeros.clone());
        let mut first = vec![[0.0; 4]; nd];
        let (iterations, converged) = gmres(
            &rhs,
            &mut dx,
            &mut self.basis,
            &mut |v: &[Complex<f64>], out: &mut [Complex<f64>]| {
                for i in 0..nd {
                    let w = c * v[i];
                    (vr[i], vi[i], cvr[i], cvi[i]) = (v[i].re, v[i].im, w.re, w.im);
                }
                // S v = c δp − g δγ + K v − δQ + c C v, δ(·) linear: one pass per part.
                pt.pass(model, loads, &vr, &cvr);
                damping(&vr, &mut pt.tmp);
                model.stiffness_product(&vr, &mut pt.tmp2);
                for i in 0..nd {
                    first[i] = [pt.dp[i], pt.dg[i] + pt.dq[i], pt.tmp[i], pt.tmp2[i]];
                }
                pt.pass(model, loads, &vi, &cvi);
                damping(&vi, &mut pt.tmp);
                model.stiffness_product(&vi, &mut pt.tmp2);
                for i in 0..nd {
                    let [p0, gq0, c0, k0] = first[i];
                    let dp = Complex::new(p0, pt.dp[i]);
                    let dgq = Complex::new(gq0, pt.dg[i] + pt.dq[i]);
                    let cv = Complex::new(c0, pt.tmp[i]);
                    let kv = Complex::new(k0, pt.tmp2[i]);
                    out[i] = c * dp - dgq + kv + c * cv;
                }
            },
            &mut |w: &mut [Complex<f64>]| {
                for i in 0..nd {
                    (pr[i], pi[i]) = (w[i].re, w[i].im);
                }
                model.solve_mass(fr, ab, &pr, &mut zr);
                model.solve_mass(fr, ab, &pi, &mut zi);
                for i in 0..nd {
                    w[i] = Complex::new(zr[i], zi[i]) / mass;
                }
            },
        );
        self.count(iterations, converged);
        // Δp = M (c Δx − r_x) + B Δx, by parts.
        for i in 0..nd {
            let dqdot = c * dx[i] - Complex::new(rq_re[i], rq_im[i]);
            (vr[i], vi[i], cvr[i], cvi[i]) = (dx[i].re, dx[i].im, dqdot.re, dqdot.im);
        }
        let pt = &mut self.pt;
        pt.pass(model, loads, &vr, &cvr);
        rp_re.copy_from_slice(&pt.dp);
        pt.pass(model, loads, &vi, &cvi);
        rp_im.copy_from_slice(&pt.dp);
        rq_re.copy_from_slice(&vr);
        rq_im.copy_from_slice(&vi);
    }

    fn count(&mut self, iterations: usize, converged: bool) {
        self.iterations += iterations;
        self.solves += 1;
        if !converged {
            self.unconverged += 1;
        }
    }
}

/// Solve `A x = b` by restarted GMRES with the right preconditioner `P` (`precondition(w)`:
/// `w ← P⁻¹ w`), from `x = 0`, to a residual of [`RELATIVE_TOLERANCE`] `‖b‖`; `basis` is
/// scratch kept between calls. Returns the iterations and whether it converged.
fn gmres<T>(
    b: &[T],
    x: &mut [T],
    basis: &mut Vec<Vec<T>>,
    apply: &mut dyn FnMut(&[T], &mut [T]),
    precondition: &mut dyn FnMut(&mut [T]),
) -> (usize, bool)
where
    T: ComplexField<RealField = f64> + Copy,
{
    let n = b.len();
    let zero = T::from_real(0.0);
    let norm = |v: &[T]| v.iter().map(|a| a.modulus_squared()).sum::<f64>().sqrt();
    let target = RELATIVE_TOLERANCE * norm(b);
    x.fill(zero);
    if target == 0.0 || !target.is_finite() {
        return (0, target == 0.0);
    }
    while basis.len() < RESTART + 1 {
        basis.push(vec![zero; n]);
    }
    let mut w = vec![zero; n];
    let mut r = b.to_vec();
    let mut total = 0;
    // Hessenberg columns, rotations, rotated right-hand side.
    let mut h = vec![vec![zero; RESTART + 1]; RESTART];
    let mut cs = [0.0; RESTART];
    let mut sn = [zero; RESTART];
    let mut g = [zero; RESTART + 1];
    let mut previous = f64::INFINITY;
    loop {
        let beta = norm(&r);
        if beta <= target {
            return (total, true);
        }
        // Stagnation: a restart cycle that did not halve the true residual has reached the
        // round-off of the operator's products (the Givens estimate went below the target, the
        // true residual did not); the iterate is as good as this arithmetic gives. Within
        // `STAGNATION` of the target that is a converged solve.
        if beta > 0.5 * previous || total >= MAX_ITERATIONS {
            return (total, beta <= STAGNATION * target);
        }
        previous = beta;
        for (v, ri) in basis[0].iter_mut().zip(&r) {
            *v = *ri / T::from_real(beta);
        }
        g.fill(zero);
        g[0] = T::from_real(beta);
        let mut k = 0;
        while k < RESTART && total < MAX_ITERATIONS {
            // w = A P⁻¹ v_k.
            let mut z = basis[k].clone();
            precondition(&mut z);
            apply(&z, &mut w);
            total += 1;
            for (i, v) in basis.iter().enumerate().take(k + 1) {
                let hij = v
                    .iter()
                    .zip(&w)
                    .fold(zero, |s, (a, b)| s + a.conjugate() * *b);
                h[k][i] = hij;
                for (wj, vj) in w.iter_mut().zip(v) {
                    *wj -= hij * *vj;
                }
            }
            let hn = norm(&w);
            h[k][k + 1] = T::from_real(hn);
            if hn > 0.0 {
                for (v, wj) in basis[k + 1].iter_mut().zip(&w) {
                    *v = *wj / T::from_real(hn);
                }
            }
            for i in 0..k {
                let (a, bb) = (h[k][i], h[k][i + 1]);
                h[k][i] = T::from_real(cs[i]) * a + sn[i] * bb;
                h[k][i + 1] = -sn[i].conjugate() * a + T::from_real(cs[i]) * bb;
            }
            let (a, bb) = (h[k][k], h[k][k + 1]);
            let (am, bm) = (a.modulus(), bb.modulus());
            let rho = am.hypot(bm);
            if am == 0.0 {
                cs[k] = 0.0;
                sn[k] = T::from_real(1.0);
                h[k][k] = bb;
            } else {
                let phase = a / T::from_real(am);
                cs[k] = am / rho;
                sn[k] = phase * bb.conjugate() / T::from_real(rho);
                h[k][k] = phase * T::from_real(rho);
            }
            h[k][k + 1] = zero;
            let gk = g[k];
            g[k] = T::from_real(cs[k]) * gk;
            g[k + 1] = -sn[k].conjugate() * gk;
            k += 1;
            if g[k].modulus() <= target || hn == 0.0 {
                break;
            }
        }
        // y from the triangle, x += P⁻¹ (V y).
        let mut y = vec![zero; k];
        for i in (0..k).rev() {
            let mut s = g[i];
            for j in i + 1..k {
                s -= h[j][i] * y[j];
            }
            y[i] = s / h[i][i];
        }
        let mut update = vec![zero; n];
        for (j, yj) in y.iter().enumerate() {
            for (u, v) in update.iter_mut().zip(&basis[j]) {
                *u += *yj * *v;
            }
        }
        precondition(&mut update);
        for (xi, u) in x.iter_mut().zip(&update) {
            *xi += *u;
        }
        // The true residual for the test and the restart.
        apply(x, &mut w);
        total += 1;
        for i in 0..n {
            r[i] = b[i] - w[i];
        }
        if !x.iter().all(|v| v.modulus().is_finite()) {
            return (total, false);
        }
    }
}
