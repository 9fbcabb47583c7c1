//! The iteration matrices `c I − J` of the implicit integrators, behind one interface: the
//! system's own solver when it has one ([`OdeSystem::newton_solver`]: the full beam model's O(n)
//! chain sweeps), else the dense Jacobian of [`OdeSystem::jacobian`] and allocation-free dense LU
//! factorizations (`lu.rs`), real and complex, allocated on first use. Quadrature states
//! ([`OdeSystem::quadrature_states`]) are left out of both: the leading components are solved,
//! then the system gives the quadratures' part from that solution.

use nalgebra::{Complex, DMatrix};

use super::lu::{ComplexLu, DenseLu};
use super::OdeSystem;

/// The Newton systems of one integration: the Jacobian (dense path) and the factorizations of
/// its shifts in numbered slots, or the system's structured solver.
pub(crate) struct IterationMatrices {
    structured: bool,
    cheap: bool,
    tolerance: Option<f64>,
    jac: DMatrix<f64>,
    real: Vec<DenseLu>,
    complex: Vec<ComplexLu>,
    /// Components solved by the LU or the system's solver: `dim − quadrature_states`.
    lead: usize,
    /// The shift of each slot (real, complex), for the quadratures' part.
    shifts: (Vec<f64>, Vec<Complex<f64>>),
    /// The leading part of `b` before a solve (real, imaginary), for the quadratures' part.
    b_lead: (Vec<f64>, Vec<f64>),
    /// The integrator steps the quadratures itself ([`Self::leave_quadratures`]).
    quadratures_left: bool,
}

impl IterationMatrices {
    /// For `system`: structured if it offers a solver, dense otherwise (nothing is allocated yet).
    pub(crate) fn new<S: OdeSystem + ?Sized>(system: &mut S) -> Self {
        let hints = system
            .newton_solver()
            .map(|s| (s.cheap_linearization(), s.newton_tolerance()));
        let lead = system.dim() - system.quadrature_states();
        let quadratures = lead < system.dim();
        let buffer = || {
            if quadratures {
                vec![0.0; lead]
            } else {
                Vec::new()
            }
        };
        Self {
            structured: hints.is_some(),
            cheap: hints.is_some_and(|h| h.0),
            tolerance: hints.and_then(|h| h.1),
            jac: DMatrix::zeros(0, 0),
            real: Vec::new(),
            complex: Vec::new(),
            lead,
            shifts: (Vec::new(), Vec::new()),
            b_lead: (buffer(), buffer()),
            quadratures_left: false,
        }
    }

    /// Leave the quadratures' part of every solve as it was in `b`: the integrator steps them
    /// itself (Radau IIA, from each stage's own point, `radau_step.rs`).
    pub(crate) fn leave_quadratures(&mut self) {
        self.quadratures_left = true;
    }

    /// Whether the system linearizes cheaply enough to do it at every step
    /// ([`super::NewtonSolver::cheap_linearization`]).
    pub(crate) fn cheap_linearization(&self) -> bool {
        self.cheap
    }

    /// The Newton stopping tolerance `default`, tightened to the system's bound
    /// ([`super::NewtonSolver::newton_tolerance`]).
    pub(crate) fn newton_tolerance(&self, default: f64) -> f64 {
        self.tolerance.map_or(default, |t| default.min(t))
    }

    /// The Jacobian (or the structured solver's approximation) at `(t, y)`; false if the system
    /// cannot be linearized there.
    pub(crate) fn linearize<S: OdeSystem + ?Sized>(
        &mut self,
        system: &mut S,
        t: f64,
        y: &[f64],
    ) -> bool {
        if self.structured {
            return solver(system).linearize(t, y);
        }
        let n = system.dim();
        if self.jac.nrows() != n {
            self.jac = DMatrix::zeros(n, n);
        }
        system.jacobian(t, y, &mut self.jac);
        true
    }

    /// Factor `c I − J` into real slot `slot`; false if singular.
    pub(crate) fn factor_real<S: OdeSystem + ?Sized>(
        &mut self,
        system: &mut S,
        slot: usize,
        c: f64,
    ) -> bool {
        set_slot(&mut self.shifts.0, slot, c);
        if self.structured {
            return solver(system).factor_real(slot, c);
        }
        let (n, rows) = (self.lead, self.jac.nrows());
        while self.real.len() <= slot {
            self.real.push(DenseLu::new(n));
        }
        let m = self.real[slot].matrix_mut();
        for (col, jc) in m
            .chunks_exact_mut(n)
            .zip(self.jac.as_slice().chunks_exact(rows))
        {
            for (a, &b) in col.iter_mut().zip(&jc[..n]) {
                *a = -b;
            }
        }
        for i in 0..n {
            m[i + i * n] += c;
        }
        self.real[slot].factor()
    }

    /// Factor `c I − J` into complex slot `slot`; false if singular.
    pub(crate) fn factor_complex<S: OdeSystem + ?Sized>(
        &mut self,
        system: &mut S,
        slot: usize,
        c: Complex<f64>,
    ) -> bool {
        set_slot(&mut self.shifts.1, slot, c);
        if self.structured {
            return solver(system).factor_complex(slot, c);
        }
        let (n, rows) = (self.lead, self.jac.nrows());
        while self.complex.len() <= slot {
            self.complex.push(ComplexLu::new(n));
        }
        let (re, im) = self.complex[slot].matrix_mut();
        for (col, jc) in re
            .chunks_exact_mut(n)
            .zip(self.jac.as_slice().chunks_exact(rows))
        {
            for (a, &b) in col.iter_mut().zip(&jc[..n]) {
                *a = -b;
            }
        }
        im.fill(0.0);
        for i in 0..n {
            re[i + i * n] += c.re;
            im[i + i * n] = c.im;
        }
        self.complex[slot].factor()
    }

    /// `b ← (c I − J)⁻¹ b` with real slot `slot`.
    pub(crate) fn solve_real<S: OdeSystem + ?Sized>(
        &mut self,
        system: &mut S,
        slot: usize,
        b: &mut [f64],
    ) {
        let quadratures = self.lead < b.len() && !self.quadratures_left;
        let (dy, q) = b.split_at_mut(self.lead);
        if quadratures {
            self.b_lead.0.copy_from_slice(dy);
        }
        if self.structured {
            solver(system).solve_real(slot, dy);
        } else {
            self.real[slot].solve_in_place(dy);
        }
        if quadratures {
            system.quadrature_step_real(self.shifts.0[slot], &self.b_lead.0, dy, q);
        }
    }

    /// `re + i im ← (c I − J)⁻¹ (re + i im)` with complex slot `slot`.
    pub(crate) fn solve_complex<S: OdeSystem + ?Sized>(
        &mut self,
        system: &mut S,
        slot: usize,
        re: &mut [f64],
        im: &mut [f64],
    ) {
        let quadratures = self.lead < re.len() && !self.quadratures_left;
        let (dy_re, q_re) = re.split_at_mut(self.lead);
        let (dy_im, q_im) = im.split_at_mut(self.lead);
        if quadratures {
            self.b_lead.0.copy_from_slice(dy_re);
            self.b_lead.1.copy_from_slice(dy_im);
        }
        if self.structured {
            solver(system).solve_complex(slot, dy_re, dy_im);
        } else {
            self.complex[slot].solve_in_place(dy_re, dy_im);
        }
        if quadratures {
            let lead = (self.b_lead.0.as_slice(), self.b_lead.1.as_slice());
            let dy = (&*dy_re, &*dy_im);
            system.quadrature_step_complex(self.shifts.1[slot], lead, dy, (q_re, q_im));
        }
    }
}

/// `slots[slot] = value`, growing `slots` as needed.
fn set_slot<T: Copy + Default>(slots: &mut Vec<T>, slot: usize, value: T) {
    if slots.len() <= slot {
        slots.resize(slot + 1, T::default());
    }
    slots[slot] = value;
}

fn solver<S: OdeSystem + ?Sized>(system: &mut S) -> &mut dyn super::NewtonSolver {
    system
        .newton_solver()
        .expect("the system's newton_solver() changed during the integration")
}

/// Test support: the two quadrature rows `m`, `m + 1` of `system` (the energy audit's `W`, `D`
/// after its `m` dynamic states) are stepped consistently by the iteration matrices' real and
/// complex solves, and [`OdeSystem::quadrature_gradient`] (Radau's) agrees with their gradients. Their gradients by central differences (h = 1e-6) give the expected rows:
/// `x_q = (b_q + g·x) / c` for the shift `c` (and its complex twin); the bound `1e-6` is the
/// differences' relative error on the sum of the terms, `label` names the case in messages.
#[cfg(test)]
pub(crate) fn assert_quadrature_rows<S: OdeSystem>(
    system: &mut S,
    t: f64,
    y: &[f64],
    m: usize,
    label: &str,
) {
    let dim = system.dim();
    let h = 1e-6;
    let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
    let mut g = [vec![0.0; m], vec![0.0; m]];
    for c in 0..m {
        let (mut yp, mut ym) = (y.to_vec(), y.to_vec());
        yp[c] += h;
        ym[c] -= h;
        system.rhs(t, &yp, &mut fp);
        system.rhs(t, &ym, &mut fm);
        for k in 0..2 {
            g[k][c] = (fp[m + k] - fm[m + k]) / (2.0 * h);
        }
    }
    let mut mats = IterationMatrices::new(system);
    assert!(mats.linearize(system, t, y));
    system.rhs(t, y, &mut fp);
    system.keep_quadrature_point(0);
    let (c, cc) = (40.0, Complex::new(35.0, 20.0));
    assert!(mats.factor_real(system, 0, c) && mats.factor_complex(system, 0, cc));
    let b: Vec<f64> = (0..dim).map(|i| (1.7 * i as f64 + 0.3).sin()).collect();
    let bi: Vec<f64> = (0..dim).map(|i| (0.9 * i as f64 + 1.1).cos()).collect();
    let mut xr = b.clone();
    mats.solve_real(system, 0, &mut xr);
    let (mut zr, mut zi) = (b.clone(), bi.clone());
    mats.solve_complex(system, 0, &mut zr, &mut zi);
    for k in 0..2 {
        let dot = |v: &[f64]| (0..m).map(|j| g[k][j] * v[j]).sum::<f64>();
        let size = |v: &[f64]| (0..m).map(|j| (g[k][j] * v[j]).abs()).sum::<f64>();
        let want = (b[m + k] + dot(&xr)) / c;
        let bound = 1e-6 * size(&xr) / c + 1e-12;
        assert!(
            (xr[m + k] - want).abs() <= bound,
            "{label} real, quadrature {k}: {} vs {want}",
            xr[m + k]
        );
        // Radau's rate change at the kept point along the small step `s x` (its rates moved by
        // `s (c x − b)`, the real system's first block row): the gradient, to the differences'
        // 1e-6 and the second-order terms' relative `s |x|` (1e-6 here): bound 1e-5.
        let s = 1e-6;
        let dy: Vec<f64> = (0..m).map(|j| s * xr[j]).collect();
        let rate: Vec<f64> = (0..m).map(|j| s * (c * xr[j] - b[j])).collect();
        let mut change = vec![0.0; dim - m];
        system.quadrature_gradient(0, &dy, &rate, &mut change);
        let want = dot(&dy);
        assert!(
            (change[k] - want).abs() <= 1e-5 * size(&dy) + 1e-18,
            "{label} rate change, quadrature {k}: {} vs {want}",
            change[k]
        );
        let want = (Complex::new(b[m + k], bi[m + k]) + Complex::new(dot(&zr), dot(&zi))) / cc;
        let got = Complex::new(zr[m + k], zi[m + k]);
        let bound = 1e-6 * (size(&zr) + size(&zi)) / cc.norm() + 1e-12;
        assert!(
            (got - want).norm() <= bound,
            "{label} complex, quadrature {k}: {got} vs {want}"
        );
    }
}
