//! Evaluation of the aerodynamic part of the aeroelastic equations for any structural model:
//! generalized forces, lag-state rates, and their exact derivatives by dual numbers
//! (docs/aeroelastic-model.md §3–5).
//!
//! The derivatives are kept in the structured form the stability analysis needs: at fixed lagged
//! upwash `w_eff`, `Q_x = ∂Q/∂x`, `Q_v = ∂Q/∂ẋ`; the upwash derivatives `W_x = ∂w/∂x`,
//! `W_v = ∂w/∂ẋ` (one row per strip); and `G = ∂Q/∂w_eff` (one column per strip). Every
//! directional derivative is one O(n) dual-number pass of the chain evaluation, along a unit
//! coordinate (a chain: the planar full model or the 3-D chain) or a column of the basis `Φ`
//! (reduced model), so the whole set costs O(n · n_dofs).

use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

use crate::model::aero::{AeroScratch, AeroStructure, Aeroelastic, Air, Lag};

/// Structured derivatives of the aerodynamic loads (model coordinates).
#[derive(Debug, Clone)]
pub(crate) struct AeroDerivatives {
    /// `∂Q/∂x` at fixed `ẋ`, `w_eff` (`n × n`).
    pub(crate) qx: DMatrix<f64>,
    /// `∂Q/∂ẋ` at fixed `x`, `w_eff` (`n × n`).
    pub(crate) qv: DMatrix<f64>,
    /// `∂w/∂x` (`strips × n`).
    pub(crate) wx: DMatrix<f64>,
    /// `∂w/∂ẋ` (`strips × n`).
    pub(crate) wv: DMatrix<f64>,
    /// `∂Q/∂w_eff` (`n × strips`).
    pub(crate) g: DMatrix<f64>,
}

impl AeroDerivatives {
    pub(crate) fn zeros(n: usize, strips: usize) -> Self {
        Self {
            qx: DMatrix::zeros(n, n),
            qv: DMatrix::zeros(n, n),
            wx: DMatrix::zeros(strips, n),
            wv: DMatrix::zeros(strips, n),
            g: DMatrix::zeros(n, strips),
        }
    }
}

/// Buffers and the air of the current instant for evaluating the aerodynamics of `aero`.
#[derive(Debug, Clone)]
pub(crate) struct AeroEvaluator<'a, M: AeroStructure> {
    pub(crate) aero: &'a Aeroelastic<M>,
    pub(crate) sc: AeroScratch<f64>,
    dsc: AeroScratch<Dual64>,
    pub(crate) air: Vec<Air>,
    gust: Vec<f64>,
    q: Vec<f64>,
    qdot: Vec<f64>,
    dq: Vec<Dual64>,
    unit: Vec<f64>,
    column: Vec<f64>,
    /// Nondimensional lag per strip (`None`: `w_eff = w`).
    lag: Option<Lag>,
    /// Each control surface's deflection, rate and acceleration `(δ, δ̇, δ̈)` (rad, rad/s,
    /// rad/s²); the equilibrium deflections until [`Self::set_deflections`].
    deflections: Vec<[f64; 3]>,
}

impl<'a, M: AeroStructure> AeroEvaluator<'a, M> {
    pub(crate) fn new(aero: &'a Aeroelastic<M>) -> Self {
        let nf = aero.chain().n_dofs();
        let s = aero.n_strips();
        Self {
            aero,
            sc: aero.scratch(),
            dsc: aero.scratch(),
            air: vec![Air::default(); s],
            gust: vec![0.0; s],
            q: vec![0.0; nf],
            qdot: vec![0.0; nf],
            dq: vec![Dual64::from(0.0); nf],
            unit: vec![0.0; nf],
            column: vec![0.0; nf],
            lag: aero.lag.clone(),
            deflections: aero.rest_deflections(),
        }
    }

    /// Set each surface's `(δ, δ̇, δ̈)` for the next [`Self::set_air`] or
    /// [`Self::set_air_with_gust`].
    pub(crate) fn set_deflections(&mut self, deflections: &[[f64; 3]]) {
        self.deflections.copy_from_slice(deflections);
    }

    /// Each surface's `(δ, δ̇, δ̈)` in force.
    pub(crate) fn deflections(&self) -> &[[f64; 3]] {
        &self.deflections
    }

    /// Hinge moment of every surface (N·m) at the last [`Self::evaluate`]
    /// ([`Aeroelastic::hinge_moments_into`]).
    pub(crate) fn hinge_moments(&self) -> Vec<f64> {
        let mut out = vec![0.0; self.deflections.len()];
        self.aero
            .hinge_moments_into(&self.sc, &self.air, &self.deflections, &mut out);
        out
    }

    /// Number of model coordinates.
    fn n(&self) -> usize {
        self.aero.structure().n_dofs()
    }

    /// Full-model coordinates of the last [`Self::evaluate`].
    pub(crate) fn coordinates(&self) -> &[f64] {
        &self.q
    }

    /// Lag states per strip.
    pub(crate) fn states_per_strip(&self) -> usize {
        self.lag.as_ref().map_or(0, |l| l.n_states())
    }

    /// The lag's direct feed-through `D̄` (1 without lag).
    pub(crate) fn feedthrough(&self) -> f64 {
        self.lag.as_ref().map_or(1.0, |l| l.d)
    }

    pub(crate) fn lag(&self) -> Option<&Lag> {
        self.lag.as_ref()
    }

    /// Set the air of every strip for speed `u`, root angle `alpha` and the gust `gust(s)`.
    pub(crate) fn set_air(&mut self, u: f64, alpha: f64, gust: impl Fn(f64) -> f64) {
        for (g, s) in self.gust.iter_mut().zip(&self.aero.strips) {
            *g = gust(s.station);
        }
        self.aero.air_into(u, alpha, &self.gust, &mut self.air);
        if !self.deflections.is_empty() {
            self.aero.flaps_into(&self.deflections, &mut self.air);
        }
    }

    /// Set the air of every strip for speed `u`, root angle `alpha` and, per strip, the gust
    /// velocity, its rate and its Küssner-lagged velocity ([`Aeroelastic::air_with_gust_into`]).
    pub(crate) fn set_air_with_gust(&mut self, u: f64, alpha: f64, gust: (&[f64], &[f64], &[f64])) {
        self.aero.air_with_gust_into(u, alpha, gust, &mut self.air);
        if !self.deflections.is_empty() {
            self.aero.flaps_into(&self.deflections, &mut self.air);
        }
    }

    /// Full-model coordinates `v_full = Φ v` into `out`.
    fn expand(&self, v: &[f64], out: &mut [f64]) {
        match self.aero.structure().basis() {
            None => out.copy_from_slice(v),
            Some(phi) => {
                // Raw column slices: nalgebra's column iterators do not vectorize (measured
                // 3× slower here).
                out.fill(0.0);
                for (col, &e) in phi.as_slice().chunks_exact(out.len()).zip(v) {
                    for (o, p) in out.iter_mut().zip(col) {
                        *o += p * e;
                    }
                }
            }
        }
    }

    /// `out (+)= Φᵀ v` (model coordinates); `add` accumulates.
    fn project(&self, v: &[f64], out: &mut [f64], add: bool) {
        match self.aero.structure().basis() {
            None => {
                for (o, x) in out.iter_mut().zip(v) {
                    *o = if add { *o + x } else { *x };
                }
            }
            Some(phi) => {
                for (col, o) in phi.as_slice().chunks_exact(v.len()).zip(out.iter_mut()) {
                    let s: f64 = col.iter().zip(v).map(|(a, b)| a * b).sum();
                    *o = if add { *o + s } else { s };
                }
            }
        }
    }

    /// Lagged upwash `w_eff,i = C̄ a_i + D̄ w_i` of every strip into `sc.weff`.
    fn set_lagged_upwash(&mut self, a: &[f64]) {
        match &self.lag {
            None => self.sc.weff.copy_from_slice(&self.sc.w),
            Some(lag) => {
                let ns = lag.n_states();
                for i in 0..self.sc.w.len() {
                    let ai = &a[i * ns..(i + 1) * ns];
                    let ca: f64 = lag.c.iter().zip(ai).map(|(c, a)| c * a).sum();
                    self.sc.weff[i] = ca + lag.d * self.sc.w[i];
                }
            }
        }
    }

    /// Evaluate at coordinates `x`, velocities `xdot` and lag states `a`: the generalized forces
    /// (model coordinates) into `force` (added if `add`), and the lag-state rates into `adot`.
    /// Leaves the evaluation in `self.sc` for [`Self::derivatives`].
    pub(crate) fn evaluate(
        &mut self,
        x: &[f64],
        xdot: &[f64],
        a: &[f64],
        force: &mut [f64],
        add: bool,
        adot: &mut [f64],
    ) {
        let mut q = std::mem::take(&mut self.q);
        let mut qdot = std::mem::take(&mut self.qdot);
        self.expand(x, &mut q);
        self.expand(xdot, &mut qdot);
        let aero = self.aero;
        aero.set_configuration(&q, &mut self.sc);
        aero.set_rates(&qdot, &mut self.sc);
        aero.set_flow(&self.air, &mut self.sc);
        self.set_lagged_upwash(a);
        aero.set_loads(&self.air, &mut self.sc);
        aero.assemble(&mut self.sc);
        let sq = std::mem::take(&mut self.sc.q);
        self.project(&sq, force, add);
        self.sc.q = sq;
        if let Some(lag) = &self.lag {
            let ns = lag.n_states();
            let h = lag.h.as_slice();
            for (i, s) in aero.strips.iter().enumerate() {
                let rate = self.air[i].speed / s.b;
                let ai = &a[i * ns..(i + 1) * ns];
                let di = &mut adot[i * ns..(i + 1) * ns];
                for (d, b) in di.iter_mut().zip(lag.b.iter()) {
                    *d = b * self.sc.w[i];
                }
                // d += H̄ a_i, by columns of the column-major H̄.
                for (col, &aj) in h.chunks_exact(ns).zip(ai) {
                    for (d, hk) in di.iter_mut().zip(col) {
                        *d += hk * aj;
                    }
                }
                for d in di.iter_mut() {
                    *d *= rate;
                }
            }
        }
        self.q = q;
        self.qdot = qdot;
    }

    /// The structured derivatives at the point of the last [`Self::evaluate`] into `d`.
    pub(crate) fn derivatives(&mut self, d: &mut AeroDerivatives) {
        let aero = self.aero;
        let n = self.n();
        let nf = self.q.len();
        let unsteady = aero.aerodynamics().is_unsteady();
        let weff: Vec<Dual64> = self.sc.weff.iter().map(|&v| Dual64::from(v)).collect();
        let qdot_d: Vec<Dual64> = self.qdot.iter().map(|&v| Dual64::from(v)).collect();
        for k in 0..n {
            self.direction(k);
            // Along x: dual configuration, real rates.
            aero.set_configuration_along(&self.sc, &self.q, &self.unit, &mut self.dsc);
            // The steady model's flow and loads do not read the rates.
            if unsteady {
                aero.set_rates(&qdot_d, &mut self.dsc);
            }
            aero.set_flow(&self.air, &mut self.dsc);
            self.dsc.weff.copy_from_slice(&weff);
            aero.set_loads(&self.air, &mut self.dsc);
            aero.assemble(&mut self.dsc);
            for i in 0..self.dsc.w.len() {
                d.wx[(i, k)] = self.dsc.w[i].eps;
            }
            self.take_column(d, k, false);
            // Along ẋ: real configuration, dual rates.
            if unsteady {
                aero.freeze_configuration(&self.sc, &mut self.dsc);
                for j in 0..nf {
                    self.dq[j] = Dual64::new(self.qdot[j], self.unit[j]);
                }
                let dq = std::mem::take(&mut self.dq);
                aero.set_rates(&dq, &mut self.dsc);
                self.dq = dq;
                aero.set_flow(&self.air, &mut self.dsc);
                self.dsc.weff.copy_from_slice(&weff);
                aero.set_loads(&self.air, &mut self.dsc);
                aero.assemble(&mut self.dsc);
                for i in 0..self.dsc.w.len() {
                    d.wv[(i, k)] = self.dsc.w[i].eps;
                }
                self.take_column(d, k, true);
            } else {
                d.wv.column_mut(k).fill(0.0);
                d.qv.column_mut(k).fill(0.0);
            }
        }
        let mut col = vec![0.0; n];
        for i in 0..aero.n_strips() {
            let mut c = std::mem::take(&mut self.column);
            aero.load_per_upwash(&self.sc, &self.air, i, &mut c);
            self.project(&c, &mut col, false);
            self.column = c;
            d.g.column_mut(i).copy_from_slice(&col);
        }
    }

    /// The `k`-th direction (unit vector or basis column) in full coordinates into `self.unit`.
    fn direction(&mut self, k: usize) {
        match self.aero.structure().basis() {
            None => {
                self.unit.fill(0.0);
                self.unit[k] = 1.0;
            }
            Some(phi) => self.unit.copy_from_slice(phi.column(k).as_slice()),
        }
    }

    /// Column `k` of `Q_x` (or `Q_v` if `rates`) from the dual parts of `self.dsc.q`.
    fn take_column(&mut self, d: &mut AeroDerivatives, k: usize, rates: bool) {
        for (c, v) in self.column.iter_mut().zip(&self.dsc.q) {
            *c = v.eps;
        }
        let n = self.n();
        let mut col = DVector::zeros(n);
        self.project(&self.column, col.as_mut_slice(), false);
        let target = if rates { &mut d.qv } else { &mut d.qx };
        target.set_column(k, &col);
    }
}
