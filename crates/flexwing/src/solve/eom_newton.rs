//! The Newton systems of the equations of motion (`dynamics/`) solved in O(n) for the full
//! model: the implicit integrators' `(c I − J) Δ = r` on the Hamiltonian state `(q, p)`.
//!
//! With `δq̇ = c Δq − r_q` (the first block row) and `Δp = M δq̇ + B Δq` (`B = ∂(M q̇)/∂q`), the
//! second block row becomes (docs/model-choices.md, "O(n) Newton systems")
//!
//! ```text
//! (c² M + c (B − Bᵀ) + K − ∂Q/∂q − ∂γ/∂q|_q̇ + c C) Δq = r_p + (c M − Bᵀ + C) r_q,
//! ```
//!
//! the chain's linearized equations of motion, which `model::chain_newton` solves by one sweep;
//! the products on the right and `Δp` are O(n) dual-number passes through the kinetic
//! recursion. Without damping this is the exact Jacobian's Newton system: Radau, BDF and the
//! midpoint rule keep their Newton convergence. Damping is approximated (a simplified Newton
//! iteration): Rayleigh `C = α M(0) + β K` as `α M(q) + β K` with `α B` added, modal damping
//! left out.

use nalgebra::Complex;

use super::damping::Damping;
use crate::model::{
    AppliedLoads, ChainFactor, ChainLinearization, FullModel, Shift, StructuralModel, Workspace,
};

/// A factorization slot: the shift it was factored for and the sweep's factors.
type Slot<T> = (T, ChainFactor<T>);

/// State of the O(n) Newton solves for one run: the linearization and the factored shifts.
pub(crate) struct ChainNewton {
    lin: ChainLinearization,
    ws: Workspace,
    real: Vec<Slot<f64>>,
    complex: Vec<Slot<Complex<f64>>>,
    /// Rayleigh `(α, β)`; `(0, 0)` for other damping (left out of the approximation).
    rayleigh: (f64, f64),
    gyroscopic: bool,
    /// Newton stopping tolerance the joint-momentum scale asks for (`dynamics/newton_systems.rs`).
    tolerance: f64,
    /// Scratch of length `n_dofs`.
    qdot: Vec<f64>,
    a: Vec<f64>,
    b: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
    v: Vec<Complex<f64>>,
    vr: Vec<f64>,
}

impl ChainNewton {
    /// For `model` with `damping`; `gyroscopic` tells whether the equations have the
    /// gyroscopic term.
    pub(crate) fn new(model: &FullModel, damping: &Damping, gyroscopic: bool) -> Self {
        let nd = model.n_dofs();
        let rayleigh = match damping {
            Damping::Rayleigh { alpha, beta } => (*alpha, *beta),
            _ => (0.0, 0.0),
        };
        let z = || vec![0.0; nd];
        let mut diagonal = z();
        model.mass_diagonal_into(&model.kinematics(&z()), &mut diagonal);
        let n = model.n_elements();
        let tolerance = 1e5 * diagonal[n - 1] / diagonal[0];
        Self {
            tolerance,
            lin: ChainLinearization::new(model),
            ws: model.workspace(),
            real: Vec::new(),
            complex: Vec::new(),
            rayleigh,
            gyroscopic,
            qdot: z(),
            a: z(),
            b: z(),
            c: z(),
            d: z(),
            v: vec![Complex::new(0.0, 0.0); nd],
            vr: z(),
        }
    }

    /// The Newton stopping tolerance the joint momenta's scale asks for: `1e5 M_nn(0)/M_11(0)`
    /// (bending joints; `dynamics/`).
    pub(crate) fn newton_tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Linearize at the state `y = (x, p)` under `loads` scaled by `scales`; false if `M(x)` is
    /// not positive definite there.
    pub(crate) fn linearize(
        &mut self,
        model: &FullModel,
        loads: &AppliedLoads,
        scales: &[f64],
        y: &[f64],
    ) -> bool {
        let nd = model.n_dofs();
        let (x, p) = y.split_at(nd);
        if !model.velocities_into(x, p, &mut self.ws, &mut self.qdot) {
            return false;
        }
        self.lin
            .update(model, x, Some(&self.qdot), Some((loads, scales)));
        true
    }

    /// The operator's coefficients for the shift `c` (module documentation).
    fn shift<T>(&self, c: T) -> Shift<T>
    where
        T: Copy + std::ops::Add<f64, Output = T> + std::ops::Mul<f64, Output = T>,
    {
        let (alpha, beta) = self.rayleigh;
        Shift {
            cv: c,
            cp: c + alpha,
            kappa: c * beta + 1.0,
            gyroscopic: self.gyroscopic,
        }
    }

    pub(crate) fn factor_real(&mut self, model: &FullModel, slot: usize, c: f64) -> bool {
        while self.real.len() <= slot {
            self.real.push((0.0, ChainFactor::new(model.n_elements())));
        }
        let shift = self.shift(c);
        let s = &mut self.real[slot];
        s.0 = c;
        s.1.factor(model, &self.lin, shift)
    }

    pub(crate) fn factor_complex(
        &mut self,
        model: &FullModel,
        slot: usize,
        c: Complex<f64>,
    ) -> bool {
        while self.complex.len() <= slot {
            let z = Complex::new(0.0, 0.0);
            self.complex.push((z, ChainFactor::new(model.n_elements())));
        }
        let shift = self.shift(c);
        let s = &mut self.complex[slot];
        s.0 = c;
        s.1.factor(model, &self.lin, shift)
    }

    /// `b = (r_q, r_p) ← (Δq, Δp)` for the real shift of `slot` (module documentation).
    pub(crate) fn solve_real(&mut self, model: &FullModel, slot: usize, b: &mut [f64]) {
        let nd = model.n_dofs();
        let (alpha, beta) = self.rayleigh;
        let g = if self.gyroscopic { 1.0 } else { 0.0 };
        let k = model.stiffness();
        let (rq, rp) = b.split_at_mut(nd);
        let (c, f) = &mut self.real[slot];
        let c = *c;
        // M r_q and Bᵀ r_q.
        self.lin
            .kinetic_perturbation(model, None, rq, &mut self.a, Some(&mut self.b));
        for i in 0..nd {
            self.vr[i] = rp[i] + (c + alpha) * self.a[i] - g * self.b[i] + beta * k[i] * rq[i];
        }
        f.solve(model, &self.lin, &mut self.vr);
        // Δp = M (c Δq − r_q) + B Δq.
        for i in 0..nd {
            self.a[i] = c * self.vr[i] - rq[i];
        }
        self.lin
            .kinetic_perturbation(model, Some(&self.vr), &self.a, rp, None);
        rq.copy_from_slice(&self.vr);
    }

    /// `(re, im) = (r_q, r_p) ← (Δq, Δp)` for the complex shift of `slot`.
    pub(crate) fn solve_complex(
        &mut self,
        model: &FullModel,
        slot: usize,
        re: &mut [f64],
        im: &mut [f64],
    ) {
        let nd = model.n_dofs();
        let (alpha, beta) = self.rayleigh;
        let g = if self.gyroscopic { 1.0 } else { 0.0 };
        let k = model.stiffness();
        let (rq_re, rp_re) = re.split_at_mut(nd);
        let (rq_im, rp_im) = im.split_at_mut(nd);
        let (c, f) = &mut self.complex[slot];
        let c = *c;
        let cp = c + alpha;
        // M r_q and Bᵀ r_q, real and imaginary parts.
        self.lin
            .kinetic_perturbation(model, None, rq_re, &mut self.a, Some(&mut self.b));
        self.lin
            .kinetic_perturbation(model, None, rq_im, &mut self.c, Some(&mut self.d));
        for i in 0..nd {
            let m_r = Complex::new(self.a[i], self.c[i]);
            let b_r = Complex::new(self.b[i], self.d[i]);
            let rq = Complex::new(rq_re[i], rq_im[i]);
            self.v[i] = Complex::new(rp_re[i], rp_im[i]) + cp * m_r - b_r * g + rq * (beta * k[i]);
        }
        f.solve(model, &self.lin, &mut self.v);
        // Δp = M (c Δq − r_q) + B Δq, by parts.
        for i in 0..nd {
            let dqdot = c * self.v[i] - Complex::new(rq_re[i], rq_im[i]);
            self.a[i] = dqdot.re;
            self.c[i] = dqdot.im;
            self.vr[i] = self.v[i].re;
            self.b[i] = self.v[i].im;
        }
        self.lin
            .kinetic_perturbation(model, Some(&self.vr), &self.a, rp_re, None);
        self.lin
            .kinetic_perturbation(model, Some(&self.b), &self.c, rp_im, None);
        rq_re.copy_from_slice(&self.vr);
        rq_im.copy_from_slice(&self.b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::{DistributedForce, Force, Load};
    use crate::solve::integrate::OdeSystem;
    use crate::solve::{EquationsOfMotion, Gyroscopic, NewtonSystems, TimeFunction};
    use nalgebra::{DMatrix, DVector};

    fn model(torsion: bool, n: usize) -> FullModel {
        let section = SectionProperties {
            ei: Profile::Uniform(10.0),
            mass_per_length: Profile::Table {
                x: vec![0.0, 2.0],
                value: vec![0.6, 0.2],
            },
            torsion: torsion.then_some(TorsionProperties {
                gj: Profile::Uniform(3.0),
                polar_inertia: Profile::Uniform(0.01),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.1),
            }),
        };
        FullModel::new(
            Beam::new(
                2.0,
                &section,
                &Discretization::Uniform(n),
                Calibration::TipLoad,
            )
            .unwrap(),
        )
    }

    /// The chain solve of `(c I − J) Δ = r` against a dense LU of the exact Jacobian (itself
    /// checked against finite differences in `dynamics.rs`), at a bent and fast-moving state
    /// under every kind of load, for Radau's real and complex shifts and the midpoint rule's.
    /// Without damping the chain solve is exact: agreement to round-off (the matrices have
    /// condition numbers up to ~1e8 at these shifts: 1e-8 relative).
    #[test]
    fn chain_newton_solves_match_the_dense_jacobian() {
        for torsion in [false, true] {
            let full = model(torsion, 8);
            let nd = full.n_dofs();
            let loads = full
                .apply(
                    &[
                        Load::PointForce {
                            span: 2.0,
                            force: Force::Follower {
                                tangential: 0.5,
                                normal: 2.0,
                            },
                        },
                        Load::PointForce {
                            span: 1.1,
                            force: Force::Dead { fx: -1.0, fy: 3.0 },
                        },
                        Load::Distributed(DistributedForce::Follower {
                            tangential: Profile::Uniform(0.2),
                            normal: Profile::Uniform(-0.7),
                        }),
                        Load::Gravity { g: 9.81 },
                    ],
                    "loads",
                )
                .unwrap();
            for gyroscopic in [Gyroscopic::Exact, Gyroscopic::Neglected] {
                let tf = vec![TimeFunction::Constant; 4];
                let mut eom =
                    EquationsOfMotion::new(&full, &loads, tf, gyroscopic, &Damping::None).unwrap();
                eom.set_newton_systems(NewtonSystems::Chain).unwrap();
                let x: Vec<f64> = (0..nd).map(|i| 0.3 * (1.0 + i as f64).sin()).collect();
                let xd: Vec<f64> = (0..nd).map(|i| 2.0 * (2.0 * i as f64).cos()).collect();
                let y = eom.state(&x, &xd);
                let mut jac = DMatrix::zeros(2 * nd, 2 * nd);
                eom.jacobian(0.3, &y, &mut jac);
                let r: Vec<f64> = (0..2 * nd).map(|i| (0.37 * i as f64).cos()).collect();
                let s = eom.newton_solver().expect("chain solver");
                assert!(s.linearize(0.3, &y));
                for c in [3.6 / 1e-2, 2.0 / 1e-3, 0.5] {
                    let a = DMatrix::identity(2 * nd, 2 * nd) * c - &jac;
                    let want = a.lu().solve(&DVector::from_column_slice(&r)).unwrap();
                    assert!(s.factor_real(1, c));
                    let mut got = r.clone();
                    s.solve_real(1, &mut got);
                    let err = (DVector::from_column_slice(&got) - &want).amax() / want.amax();
                    assert!(err < 1e-8, "{torsion} {gyroscopic:?} c = {c}: {err:.2e}");
                }
                let c = Complex::new(2.68, 3.05) / 1e-2;
                let a = (DMatrix::identity(2 * nd, 2 * nd) * c) - jac.map(|v| Complex::new(v, 0.0));
                let rc: Vec<Complex<f64>> = r
                    .iter()
                    .enumerate()
                    .map(|(i, &v)| Complex::new(v, (0.1 * i as f64).sin()))
                    .collect();
                let want = a.lu().solve(&DVector::from_column_slice(&rc)).unwrap();
                assert!(s.factor_complex(0, c));
                let mut re: Vec<f64> = rc.iter().map(|v| v.re).collect();
                let mut im: Vec<f64> = rc.iter().map(|v| v.im).collect();
                s.solve_complex(0, &mut re, &mut im);
                let scale = want.iter().map(|v| v.norm()).fold(0.0, f64::max);
                let err = (0..2 * nd)
                    .map(|i| (Complex::new(re[i], im[i]) - want[i]).norm())
                    .fold(0.0, f64::max);
                assert!(
                    err < 1e-8 * scale,
                    "{torsion} {gyroscopic:?} complex: {:.2e}",
                    err / scale
                );
            }
        }
    }
}
