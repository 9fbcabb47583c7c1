//! [`Chain3d`]: the geometrically exact 3-D chain as a [`StructuralModel`], so that statics,
//! modes and dynamics run on it unchanged (docs/chain3d-model.md).
//!
//! Coordinates: `x ∈ R^{3n}`, joint-major, `x[3i..3i+3] = φ_i` the rotation vector of joint `i`
//! (at node `i`, between element `i − 1` — the clamp for `i = 0` — and element `i`), components
//! `(twist, lag, flap)` about `(t, n, c)` of element `i`. Elastic energy `½ Σ φ_iᵀ K_i φ_i`:
//! the stiffness is constant and block diagonal; all the non-linearity is in the kinematics.

use nalgebra::{DMatrix, DVector};
use num_dual::{Dual64, DualNum};

use super::aba::Articulated;
use super::algebra::{cross, zero, V3};
use super::beam::Beam3d;
use super::kinematics::{Frames, Motion};
use super::shape::Shape3d;
use crate::model::{AppliedLoads, StructuralModel};

/// The 3-D chain: `n` rigid elements joined by three-axis rotational joints.
#[derive(Debug, Clone)]
pub struct Chain3d {
    pub(crate) beam: Beam3d,
    pub(crate) n: usize,
    /// The fluid's inertia (apparent mass) of an aeroelastic model, `None` in vacuo
    /// (`model::aero::fluid`; its terms in the recursions, `kinematics.rs` and `mass.rs`).
    pub(crate) fluid: Option<crate::model::aero::FluidInertia>,
}

impl Chain3d {
    /// The 3-D chain of a beam.
    pub fn new(beam: Beam3d) -> Self {
        let n = beam.n_elements();
        Self {
            beam,
            n,
            fluid: None,
        }
    }

    /// The same chain with the fluid's inertia added to its kinetic energy: per element a
    /// directional mass `m_a` along the section normal `n` at the mid-chord point
    /// `P_i + R_i (ℓ_i/2, 0, ζ_m)` and a polar inertia `J_a` about `t` (docs/chain3d-model.md,
    /// "Strip aerodynamics").
    ///
    /// # Panics
    /// If the vectors of `fluid` do not have one entry per element.
    pub(crate) fn with_fluid(mut self, fluid: crate::model::aero::FluidInertia) -> Self {
        let n = self.n;
        assert!(
            fluid.mass.len() == n && fluid.station.len() == n && fluid.inertia.len() == n,
            "fluid inertia needs one entry per element"
        );
        self.fluid = Some(fluid);
        self
    }

    /// The chain without the fluid's inertia.
    pub(crate) fn dry(&self) -> Self {
        Self {
            beam: self.beam.clone(),
            n: self.n,
            fluid: None,
        }
    }

    /// Whether the chain carries the fluid's inertia (an aeroelastic model's structure).
    pub fn has_fluid_inertia(&self) -> bool {
        self.fluid.is_some()
    }
    /// The beam this chain was built from.
    pub fn beam(&self) -> &Beam3d {
        &self.beam
    }
    /// Number of elements `n`.
    pub fn n_elements(&self) -> usize {
        self.n
    }
    /// Number of coordinates, `3n`.
    pub fn n_dofs(&self) -> usize {
        3 * self.n
    }

    fn frames(&self, x: &[f64]) -> Frames<f64> {
        assert_eq!(x.len(), self.n_dofs(), "x has the wrong length");
        let mut fr = Frames::new(self.n);
        self.configure(x, &mut fr);
        fr
    }

    /// Node positions `P_0 … P_n` (m) and each element's nose-up pitch `atan2(−n·ẑ, c·ẑ)` (rad,
    /// the angle of its chord above `ẑ` in the section plane: `AeroChain::tip`'s twist) at `x`,
    /// with their derivatives along every coordinate (`d_positions[j][node]`,
    /// `d_pitch[j][element]`): one dual-number configuration per coordinate, O(n²) in all (the
    /// linear model's outputs, `solve::aeroelastic::linearize`).
    #[allow(clippy::type_complexity)]
    pub(crate) fn geometry_derivatives(
        &self,
        x: &[f64],
    ) -> (Vec<[f64; 3]>, Vec<Vec<[f64; 3]>>, Vec<f64>, Vec<Vec<f64>>) {
        let pitch = |r: &[[Dual64; 3]; 3]| (-r[2][1]).atan2(r[2][2]);
        let mut fr: Frames<Dual64> = Frames::new(self.n);
        let mut xd: Vec<Dual64> = x.iter().map(|&v| Dual64::from(v)).collect();
        let (mut dp, mut dpitch) = (Vec::with_capacity(x.len()), Vec::with_capacity(x.len()));
        let (mut p0, mut pitch0) = (Vec::new(), Vec::new());
        for j in 0..x.len() {
            xd[j] = Dual64::new(x[j], 1.0);
            self.configure_from(&xd, &mut fr, 0, false);
            xd[j] = Dual64::from(x[j]);
            if j == 0 {
                p0 = fr.p.iter().map(|p| p.map(|v| v.re)).collect();
                pitch0 = fr.r.iter().map(|r| pitch(r).re).collect();
            }
            dp.push(fr.p.iter().map(|p| p.map(|v| v.eps)).collect());
            dpitch.push(fr.r.iter().map(|r| pitch(r).eps).collect());
        }
        (p0, dp, pitch0, dpitch)
    }

    /// Node positions `P_0 … P_n` at the configuration `x` (m).
    ///
    /// # Panics
    /// If `x.len() != n_dofs()` (also for the other functions of a configuration).
    pub fn node_positions(&self, x: &[f64]) -> Vec<[f64; 3]> {
        self.frames(x).p
    }

    /// Element frames `R_i` at `x`: columns `t, n, c` in global components.
    pub fn element_frames(&self, x: &[f64]) -> Vec<[[f64; 3]; 3]> {
        self.frames(x).r
    }

    /// Element mass centres `g_i` at `x` (m).
    pub fn mass_centres(&self, x: &[f64]) -> Vec<[f64; 3]> {
        let fr = self.frames(x);
        (0..self.n)
            .map(|i| super::algebra::add(&fr.p[i], &fr.arm[i]))
            .collect()
    }

    /// The element carrying `span` and the distance from its inboard node (`None` at the clamp).
    fn locate(&self, span: f64) -> Option<(usize, f64)> {
        let nodes = self.beam.nodes();
        let span = span.clamp(0.0, self.beam.length());
        let k = nodes.partition_point(|&s| s < span).min(self.n);
        (k > 0).then(|| (k - 1, span - nodes[k - 1]))
    }

    /// Position of the elastic-axis point at arc length `span` (m).
    pub fn point_position(&self, x: &[f64], span: f64) -> [f64; 3] {
        let fr = self.frames(x);
        match self.locate(span) {
            None => [0.0; 3],
            Some((k, a)) => {
                let f = a / self.beam.reference.lengths[k];
                super::algebra::add(&fr.p[k], &super::algebra::scale(f, &fr.d[k]))
            }
        }
    }

    /// Jacobian `∂X/∂x` (3 × 3n) of the elastic-axis point at `span`: `−(X − P_j)^ H_j` for the
    /// joints `j` inboard of it.
    pub fn point_jacobian(&self, x: &[f64], span: f64) -> DMatrix<f64> {
        let fr = self.frames(x);
        let mut jac = DMatrix::zeros(3, self.n_dofs());
        if let Some((k, a)) = self.locate(span) {
            let f = a / self.beam.reference.lengths[k];
            let xp = super::algebra::add(&fr.p[k], &super::algebra::scale(f, &fr.d[k]));
            for j in 0..=k {
                let r = super::algebra::sub(&xp, &fr.p[j]);
                for c in 0..3 {
                    let col = super::algebra::column(&fr.h[j], c);
                    let v = cross(&col, &r);
                    for a in 0..3 {
                        jac[(a, 3 * j + c)] = v[a];
                    }
                }
            }
        }
        jac
    }

    /// Jacobian of element `i`'s angular velocity, `∂ω_i/∂ẋ` (3 × 3n): `H_j` for `j ≤ i`.
    pub fn angular_velocity_jacobian(&self, x: &[f64], i: usize) -> DMatrix<f64> {
        let fr = self.frames(x);
        let mut jac = DMatrix::zeros(3, self.n_dofs());
        for j in 0..=i {
            for a in 0..3 {
                for c in 0..3 {
                    jac[(a, 3 * j + c)] = fr.h[j][a][c];
                }
            }
        }
        jac
    }

    /// Angular velocities `ω_i` of the elements (rad/s) at `x` for the rates `xdot`.
    pub fn angular_velocities(&self, x: &[f64], xdot: &[f64]) -> Vec<[f64; 3]> {
        let fr = self.frames(x);
        let mut mo = Motion::new(self.n);
        self.motion(&fr, xdot, &mut mo);
        mo.omega
    }

    /// Node velocities `Ṗ_0 … Ṗ_n` (m/s) at `x` for the rates `xdot`. With a mode shape (or any
    /// increment `δx`) for `xdot`, the linearized nodal displacements `δP_k = (∂P_k/∂x) δx` of a
    /// mode plot; [`Chain3d::angular_velocities`] gives the elements' rotations likewise.
    pub fn node_velocities(&self, x: &[f64], xdot: &[f64]) -> Vec<[f64; 3]> {
        let fr = self.frames(x);
        let mut mo = Motion::new(self.n);
        self.motion(&fr, xdot, &mut mo);
        let mut out = mo.v;
        let last = self.n - 1;
        let tip = super::algebra::add(&out[last], &cross(&mo.omega[last], &fr.d[last]));
        out.push(tip);
        out
    }

    /// Kinetic energy `T(x, ẋ)` (J).
    pub fn kinetic_energy(&self, x: &[f64], xdot: &[f64]) -> f64 {
        let fr = self.frames(x);
        let mut mo = Motion::new(self.n);
        self.motion(&fr, xdot, &mut mo);
        self.kinetic_energy_of(&fr, &mo)
    }

    /// Elastic energy `½ Σ φ_iᵀ K_i φ_i` (J).
    pub fn elastic_energy(&self, x: &[f64]) -> f64 {
        let mut e = 0.0;
        for (i, k) in self.beam.stiffness.iter().enumerate() {
            let phi = [x[3 * i], x[3 * i + 1], x[3 * i + 2]];
            let kp = super::algebra::mv(k, &phi);
            e += 0.5 * super::algebra::dot(&phi, &kp);
        }
        e
    }

    /// Potential energy of the conservative loads (dead forces, gravity) at `x` (J), so that
    /// `Q = −∂V/∂x` for them.
    pub fn load_potential_energy(&self, x: &[f64], loads: &AppliedLoads, scales: &[f64]) -> f64 {
        self.load_potential(&self.frames(x), loads, scales)
    }

    /// The deformed shape at `x`.
    pub fn shape(&self, x: &[f64]) -> Shape3d {
        let fr = self.frames(x);
        Shape3d::new(self.beam.nodes().to_vec(), fr.p, fr.r)
    }
}

/// Dual-number scratch of the exact derivatives (allocated on first use).
#[derive(Debug, Clone)]
struct DualScratch {
    fr: Frames<Dual64>,
    mo: Motion<Dual64>,
    ab: Articulated<Dual64>,
    x: Vec<Dual64>,
    xdot: Vec<Dual64>,
    p: Vec<Dual64>,
    out: Vec<Dual64>,
    own_f: Vec<V3<Dual64>>,
    own_n: Vec<V3<Dual64>>,
    /// Leading elements of `fr` holding the real kinematics of the base configuration.
    lifted: usize,
}

impl DualScratch {
    fn new(n: usize) -> Self {
        let z = Dual64::from(0.0);
        Self {
            fr: Frames::new(n),
            mo: Motion::new(n),
            ab: Articulated::new(n),
            x: vec![z; 3 * n],
            xdot: vec![z; 3 * n],
            p: vec![z; 3 * n],
            out: vec![z; 3 * n],
            own_f: vec![zero(); n],
            own_n: vec![zero(); n],
            lifted: 0,
        }
    }

    /// `x + ε e_k` into `self.x`.
    fn seed(&mut self, x: &[f64], k: usize) {
        for (d, &v) in self.x.iter_mut().zip(x) {
            *d = Dual64::from(v);
        }
        self.x[k].eps = 1.0;
    }

    /// The kinematics along `x + ε e_k` into `self.fr`, from the real kinematics `base` of `x`:
    /// the elements inboard of joint `k / 3` are `base`'s, the rest configured with dual
    /// numbers (O(n − k/3)). Called for `k = 0, 1, …` in turn with one base (`k = 0` starts a
    /// new one), so only the elements between consecutive joints are lifted.
    fn configure_along(&mut self, model: &Chain3d, base: &Frames<f64>, x: &[f64], k: usize) {
        self.seed(x, k);
        let start = k / 3;
        if start == 0 {
            self.lifted = 0;
        }
        if start > self.lifted {
            self.fr.lift_range(base, self.lifted, start, true);
        }
        model.configure_from(&self.x, &mut self.fr, start, true);
        self.lifted = start;
    }
}

/// Scratch of the 3-D chain's evaluations: the kinematics of the last configuration, its mass
/// factorization, load and velocity buffers. Evaluations allocate nothing (the dual-number
/// buffers of the exact derivatives on their first use).
#[derive(Debug, Clone)]
pub struct Workspace3d {
    fr: Frames<f64>,
    /// Configuration `fr` holds (NaN: none yet).
    at: Vec<f64>,
    factored: bool,
    mo: Motion<f64>,
    ab: Articulated<f64>,
    own_f: Vec<V3<f64>>,
    own_n: Vec<V3<f64>>,
    dual: Option<Box<DualScratch>>,
}

impl Workspace3d {
    fn configure(&mut self, model: &Chain3d, x: &[f64]) {
        assert_eq!(x.len(), model.n_dofs(), "x has the wrong length");
        if self.at.as_slice() != x {
            model.configure(x, &mut self.fr);
            self.at.copy_from_slice(x);
            self.factored = false;
        }
    }

    /// Configure and factor `M(x)`; false if it is not positive definite.
    fn factor(&mut self, model: &Chain3d, x: &[f64]) -> bool {
        self.configure(model, x);
        if !self.factored {
            self.factored = model.factor_mass(&self.fr, &mut self.ab);
        }
        self.factored
    }

    fn dual(&mut self, n: usize) -> &mut DualScratch {
        self.dual
            .get_or_insert_with(|| Box::new(DualScratch::new(n)))
    }
}

impl StructuralModel for Chain3d {
    type Workspace = Workspace3d;

    fn workspace(&self) -> Workspace3d {
        let n = self.n;
        Workspace3d {
            fr: Frames::new(n),
            at: vec![f64::NAN; 3 * n],
            factored: false,
            mo: Motion::new(n),
            ab: Articulated::new(n),
            own_f: vec![zero(); n],
            own_n: vec![zero(); n],
            dual: None,
        }
    }

    fn n_dofs(&self) -> usize {
        3 * self.n
    }

    fn stiffness_matrix(&self) -> DMatrix<f64> {
        let nd = self.n_dofs();
        let mut k = DMatrix::zeros(nd, nd);
        for (i, b) in self.beam.stiffness.iter().enumerate() {
            for r in 0..3 {
                for c in 0..3 {
                    k[(3 * i + r, 3 * i + c)] = b[r][c];
                }
            }
        }
        k
    }

    fn mass_matrix_into(&self, x: &[f64], ws: &mut Workspace3d, out: &mut DMatrix<f64>) {
        ws.configure(self, x);
        self.mass_matrix_frames(&ws.fr, out);
    }

    fn generalized_forces_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Workspace3d,
        out: &mut DVector<f64>,
    ) {
        ws.configure(self, x);
        self.forces_frames(
            &ws.fr,
            loads,
            scales,
            &mut ws.own_f,
            &mut ws.own_n,
            out.as_mut_slice(),
        );
    }

    fn load_jacobian_into(
        &self,
        x: &[f64],
        loads: &AppliedLoads,
        scales: &[f64],
        ws: &mut Workspace3d,
        out: &mut DMatrix<f64>,
    ) {
        let nd = self.n_dofs();
        assert_eq!(out.shape(), (nd, nd), "Jacobian buffer has the wrong shape");
        if loads.spatial.iter().all(|it| scales[it.load] == 0.0) {
            out.fill(0.0);
            return;
        }
        // Column k: Q along x + ε e_k (exact; O(n) per column).
        ws.configure(self, x);
        let Workspace3d { fr, dual, .. } = ws;
        let d = dual.get_or_insert_with(|| Box::new(DualScratch::new(self.n)));
        for k in 0..nd {
            d.configure_along(self, fr, x, k);
            self.forces_frames(&d.fr, loads, scales, &mut d.own_f, &mut d.own_n, &mut d.out);
            for (r, v) in d.out.iter().enumerate() {
                out[(r, k)] = v.eps;
            }
        }
    }

    fn momentum_into(&self, x: &[f64], xdot: &[f64], ws: &mut Workspace3d, out: &mut [f64]) {
        ws.configure(self, x);
        self.kinetic_terms(&ws.fr, xdot, &mut ws.mo, Some(out), None);
    }

    fn velocities_into(&self, x: &[f64], p: &[f64], ws: &mut Workspace3d, out: &mut [f64]) -> bool {
        if !ws.factor(self, x) {
            return false;
        }
        self.solve_mass(&ws.fr, &mut ws.ab, p, out);
        true
    }

    fn velocities_block_into(
        &self,
        x: &[f64],
        p: &DMatrix<f64>,
        ws: &mut Workspace3d,
        out: &mut DMatrix<f64>,
    ) -> bool {
        assert_eq!(p.shape(), out.shape(), "output block has the wrong shape");
        if !ws.factor(self, x) {
            return false;
        }
        for c in 0..p.ncols() {
            let col = out.column_mut(c).data.into_slice_mut();
            self.solve_mass(&ws.fr, &mut ws.ab, p.column(c).as_slice(), col);
        }
        true
    }

    fn gyroscopic_into(&self, x: &[f64], xdot: &[f64], ws: &mut Workspace3d, out: &mut [f64]) {
        ws.configure(self, x);
        self.kinetic_terms(&ws.fr, xdot, &mut ws.mo, None, Some(out));
    }

    fn kinetic_derivatives_into(
        &self,
        x: &[f64],
        xdot: &[f64],
        ws: &mut Workspace3d,
        dp: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) {
        let nd = self.n_dofs();
        ws.configure(self, x);
        let Workspace3d { fr, dual, .. } = ws;
        let d = dual.get_or_insert_with(|| Box::new(DualScratch::new(self.n)));
        for (v, &r) in d.xdot.iter_mut().zip(xdot) {
            *v = Dual64::from(r);
        }
        for k in 0..nd {
            d.configure_along(self, fr, x, k);
            self.kinetic_terms(&d.fr, &d.xdot, &mut d.mo, Some(&mut d.p), Some(&mut d.out));
            for r in 0..nd {
                dp[(r, k)] = d.p[r].eps;
                dgamma[(r, k)] = d.out[r].eps;
            }
        }
    }

    fn hamiltonian_derivatives_into(
        &self,
        x: &[f64],
        p: &[f64],
        ws: &mut Workspace3d,
        with_gamma: bool,
        dxdx: &mut DMatrix<f64>,
        dgamma: &mut DMatrix<f64>,
    ) -> bool {
        // Dual numbers through the O(n) velocity solve: ẋ(x + ε e_k) at fixed p, then γ there;
        // O(n) per column, O(n²) in all.
        let nd = self.n_dofs();
        if !ws.factor(self, x) {
            return false;
        }
        let d = ws.dual(self.n);
        for (v, &r) in d.p.iter_mut().zip(p) {
            *v = Dual64::from(r);
        }
        for k in 0..nd {
            d.seed(x, k);
            self.configure(&d.x, &mut d.fr);
            d.lifted = 0;
            if !self.factor_mass(&d.fr, &mut d.ab) {
                return false;
            }
            let (fr, ab, pd, xd) = (&d.fr, &mut d.ab, &d.p, &mut d.xdot);
            self.solve_mass(fr, ab, pd, xd);
            for r in 0..nd {
                dxdx[(r, k)] = d.xdot[r].eps;
            }
            if with_gamma {
                self.kinetic_terms(&d.fr, &d.xdot, &mut d.mo, None, Some(&mut d.out));
                for r in 0..nd {
                    dgamma[(r, k)] = d.out[r].eps;
                }
            }
        }
        true
    }

    fn loads_are_conservative(&self, loads: &AppliedLoads, scales: &[f64]) -> bool {
        loads.is_conservative(scales)
    }

    fn as_chain3d(&self) -> Option<&Chain3d> {
        Some(self)
    }

    fn stiffness_blocks(&self) -> Option<Vec<[[f64; 3]; 3]>> {
        Some(self.beam.stiffness.clone())
    }

    fn full_coordinates(&self, x: &[f64]) -> Vec<f64> {
        x.to_vec()
    }

    /// The joints' rotation vectors summed from the clamp, component by component, per element:
    /// the absolute rotation of each element exactly when the rotations share an axis (the
    /// planar limit), a measure of it otherwise (the frames in which the components are taken
    /// turn along the chain).
    fn element_rotations(&self, dx: &[f64]) -> Vec<f64> {
        let mut out = Vec::with_capacity(dx.len());
        let mut sum = [0.0; 3];
        for phi in dx.chunks(3) {
            for a in 0..3 {
                sum[a] += phi[a];
            }
            out.extend_from_slice(&sum);
        }
        out
    }
}
