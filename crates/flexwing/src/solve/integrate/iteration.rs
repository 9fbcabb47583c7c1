//! The iteration matrices `c I − J` of the implicit integrators, behind one interface: the
//! system's own solver when it has one ([`OdeSystem::newton_solver`]: the full beam model's O(n)
//! chain sweeps), else the dense Jacobian of [`OdeSystem::jacobian`] and allocation-free dense LU
//! factorizations (`lu.rs`), real and complex, allocated on first use.

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
}

impl IterationMatrices {
    /// For `system`: structured if it offers a solver, dense otherwise (nothing is allocated yet).
    pub(crate) fn new<S: OdeSystem + ?Sized>(system: &mut S) -> Self {
        let hints = system
            .newton_solver()
            .map(|s| (s.cheap_linearization(), s.newton_tolerance()));
        Self {
            structured: hints.is_some(),
            cheap: hints.is_some_and(|h| h.0),
            tolerance: hints.and_then(|h| h.1),
            jac: DMatrix::zeros(0, 0),
            real: Vec::new(),
            complex: Vec::new(),
        }
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
        if self.structured {
            return solver(system).factor_real(slot, c);
        }
        let n = self.jac.nrows();
        while self.real.len() <= slot {
            self.real.push(DenseLu::new(n));
        }
        let m = self.real[slot].matrix_mut();
        for (a, &b) in m.iter_mut().zip(self.jac.as_slice()) {
            *a = -b;
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
        if self.structured {
            return solver(system).factor_complex(slot, c);
        }
        let n = self.jac.nrows();
        while self.complex.len() <= slot {
            self.complex.push(ComplexLu::new(n));
        }
        let (re, im) = self.complex[slot].matrix_mut();
        for (a, &b) in re.iter_mut().zip(self.jac.as_slice()) {
            *a = -b;
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
        if self.structured {
            solver(system).solve_real(slot, b);
        } else {
            self.real[slot].solve_in_place(b);
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
        if self.structured {
            solver(system).solve_complex(slot, re, im);
        } else {
            self.complex[slot].solve_in_place(re, im);
        }
    }
}

fn solver<S: OdeSystem + ?Sized>(system: &mut S) -> &mut dyn super::NewtonSolver {
    system
        .newton_solver()
        .expect("the system's newton_solver() changed during the integration")
}
