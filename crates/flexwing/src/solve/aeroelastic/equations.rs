//! The aeroelastic equations of motion (docs/aeroelastic-model.md §3–4): the Hamiltonian
//! equations of the wet structure (`solve::dynamics`, whose mass matrix carries the fluid's
//! inertia) with the strip loads added, and the lag states appended,
//!
//! ```text
//! ẋ = M(x)⁻¹ p
//! ṗ = −K x + γ(x, ẋ) − C ẋ + Q_other(x, t) + Q_grav(x) + Q_aero(x, ẋ, a, t)
//! ȧ_i = (V_i/b_i) (H̄ a_i + B̄ w_i(x, ẋ, t))
//! ```
//!
//! with the exact Jacobian (structural part from `EquationsOfMotion`, aerodynamic part from the
//! structured derivatives of `evaluator.rs`): with `A = ∂ẋ/∂x|_p`, `M⁻¹ = ∂ẋ/∂p`,
//! `Q̃_v = Q_v + G D̄ W_v`,
//!
//! ```text
//! ∂ṗ/∂x += Q_x + G D̄ W_x + Q̃_v A        ∂ṗ/∂p += Q̃_v M⁻¹        ∂ṗ/∂a_i = G_i C̄
//! ∂ȧ_i/∂x = (V_i/b_i) B̄ (W_x,i + W_v,i A)   ∂ȧ_i/∂p = (V_i/b_i) B̄ W_v,i M⁻¹   ∂ȧ_i/∂a_i = (V_i/b_i) H̄
//! ```

use std::ops::ControlFlow;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;

use nalgebra::{Complex, DMatrix, DVector};

use super::audit::{dot, AeroAudit};
use super::evaluator::{AeroDerivatives, AeroEvaluator};
use super::flight::{FlightHistory, FlightOffsets, GustPenetration};
use super::linear::Linearization;
use super::schur::{AeroNewtonSystems, LagSchur, StructuredJacobian};
use crate::error::InputError;
use crate::model::aero::{AeroChain, AeroStructure, Aerodynamics, Aeroelastic};
use crate::model::{AppliedLoads, Load};
use crate::solve::integrate::{NewtonSolver, OdeSystem};
use crate::solve::{Damping, EquationsOfMotion, Gyroscopic, TimeFunction};

/// The aeroelastic system linearized about a static equilibrium, with the lag of every strip
/// left as its transfer function `T_i(s)` (docs/aeroelastic-model.md §5): the eigenvalues other
/// than the lag's are the roots of
/// `det[s² M + s C̃ + K̃ − Σ_i T_i(s/r_i) g_i (w_x,i + s w_v,i)ᵀ] = 0`, with `g_i` the column `i`
/// of `load_per_upwash` and `w_x,i`, `w_v,i` the rows `i` of the upwash derivatives. For a
/// finite-state model `T_i` is the lag's transfer function, for the p-k method Theodorsen's
/// `C(k)`. Model coordinates throughout; all derivatives exact (dual numbers).
#[derive(Debug, Clone, PartialEq)]
pub struct LinearSystem {
    /// The wet mass matrix `M` (structure plus fluid inertia), `n × n`.
    pub mass: DMatrix<f64>,
    /// `C̃ = C − ∂Q/∂ẋ` at fixed lagged upwash: structural damping and the non-circulatory rate
    /// terms, `n × n`.
    pub damping: DMatrix<f64>,
    /// `K̃ = K − ∂Q_other/∂x − ∂Q_aero/∂x` at fixed lagged upwash, `n × n`.
    pub stiffness: DMatrix<f64>,
    /// `g_i = ∂Q/∂w_eff,i`: generalized force per unit lagged upwash of strip `i`, `n × strips`.
    pub load_per_upwash: DMatrix<f64>,
    /// `∂w_i/∂x`: upwash at the three-quarter chord per unit coordinate, `strips × n`.
    pub upwash_displacement: DMatrix<f64>,
    /// `∂w_i/∂ẋ`, `strips × n`.
    pub upwash_velocity: DMatrix<f64>,
    /// `r_i = V_i/b_i` (1/s): the lag's time scale per strip, `s̄ = s/r_i`.
    pub lag_rates: Vec<f64>,
}

/// The first-order aeroelastic system on `y = (x, p, a)` for the integrators and the stability
/// analysis. Evaluations of the right-hand side allocate nothing.
pub struct AeroelasticEquations<'a, M: AeroStructure> {
    aero: &'a Aeroelastic<M>,
    pub(super) structural: EquationsOfMotion<'a, M>,
    loads: &'a AppliedLoads,
    time_functions: Vec<TimeFunction>,
    eval: AeroEvaluator<'a, M>,
    flight: FlightHistory,
    /// Inputs added to the flight history (a stepper's), zero by default.
    offsets: FlightOffsets,
    gravity: Option<AppliedLoads>,
    ws: M::Workspace,
    pub(super) n: usize,
    pub(super) na: usize,
    force: DVector<f64>,
    gravity_jac: DMatrix<f64>,
    derivatives: AeroDerivatives,
    /// Scratch of the Jacobian: `∂ẋ/∂x`, `M⁻¹`, `Q̃_v` (`n × n`), `ẋ`, lag rates.
    dxdx: DMatrix<f64>,
    minv: DMatrix<f64>,
    qv: DMatrix<f64>,
    xdot: Vec<f64>,
    scratch_a: Vec<f64>,
    /// The structured Jacobian of the dense path.
    structured: StructuredJacobian,
    newton_systems: AeroNewtonSystems,
    /// The Newton solver by elimination of the lag states, made on first use.
    schur: Option<LagSchur>,
    /// The energy audit, if on (`audit.rs`): the state then ends with `W` and `D`.
    pub(super) audit: Option<AeroAudit>,
    /// A flag that, once set, stops the integration after the next accepted step.
    pub(super) halt: Option<Arc<AtomicBool>>,
    /// Per strip: the time the gust front takes from the wing's most upstream leading-edge point
    /// to the strip's leading edge (s; zero unless Küssner's penetration).
    gust_delays: Vec<f64>,
    /// Per strip: the gust velocity, its rate and its Küssner-lagged velocity of the instant.
    gust_now: [Vec<f64>; 3],
    /// Per surface: `(δ, δ̇, δ̈)` of the instant.
    deflections: Vec<[f64; 3]>,
    /// Right-hand-side evaluations.
    pub rhs_evaluations: usize,
    /// Jacobian evaluations.
    pub jacobian_evaluations: usize,
}

impl<'a, M: AeroStructure> AeroelasticEquations<'a, M> {
    /// The equations of `aero` in the flight `flight`, with other loads `loads` scaled by
    /// `time_functions`, structural damping `damping` and the gyroscopic term `gyroscopic`.
    /// `field` prefixes the error fields of the flight history.
    ///
    /// # Errors
    /// The errors of [`EquationsOfMotion::new`] and an invalid flight condition.
    pub fn new(
        aero: &'a Aeroelastic<M>,
        loads: &'a AppliedLoads,
        time_functions: Vec<TimeFunction>,
        flight: FlightHistory,
        damping: &Damping,
        field: &str,
    ) -> Result<Self, InputError> {
        flight.initial.validate(field)?;
        if let Some(g) = &flight.gust {
            if g.penetration == GustPenetration::Kussner
                && !matches!(
                    aero.aerodynamics(),
                    Aerodynamics::Wagner | Aerodynamics::Peters { .. }
                )
            {
                return Err(InputError::new(
                    format!("{field}.gust.penetration"),
                    format!(
                        "\"kussner\" is the gust's circulation lag: it needs the wagner or \
                         peters model, not {}",
                        aero.aerodynamics().name()
                    ),
                ));
            }
        }
        let gust_delays = gust_delays(aero, &flight);
        let strips = aero.n_strips();
        let model = aero.structure();
        let structural = EquationsOfMotion::new(
            model,
            loads,
            time_functions.clone(),
            Gyroscopic::Exact,
            damping,
        )?;
        let n = model.n_dofs();
        let gravity = match flight.initial.gravity {
            Some(g) => Some(aero.apply(&[Load::Gravity { g }], field)?),
            None => None,
        };
        let na = aero.n_aero_states();
        Ok(Self {
            aero,
            structural,
            loads,
            time_functions,
            eval: AeroEvaluator::new(aero),
            flight,
            offsets: FlightOffsets::default(),
            gravity,
            ws: model.workspace(),
            n,
            na,
            force: DVector::zeros(n),
            gravity_jac: DMatrix::zeros(n, n),
            derivatives: AeroDerivatives::zeros(n, aero.n_strips()),
            dxdx: DMatrix::zeros(n, n),
            minv: DMatrix::zeros(n, n),
            qv: DMatrix::zeros(n, n),
            xdot: vec![0.0; n],
            scratch_a: vec![0.0; na],
            structured: StructuredJacobian::zeros(0, 0),
            newton_systems: AeroNewtonSystems::Auto,
            schur: None,
            audit: None,
            halt: None,
            gust_delays,
            gust_now: [vec![0.0; strips], vec![0.0; strips], vec![0.0; strips]],
            deflections: aero.rest_deflections(),
            rhs_evaluations: 0,
            jacobian_evaluations: 0,
        })
    }

    /// Number of structural coordinates `x`.
    pub fn n_dofs(&self) -> usize {
        self.n
    }
    /// Number of aerodynamic states.
    pub fn n_aero_states(&self) -> usize {
        self.na
    }
    /// The flight history.
    pub fn flight(&self) -> &FlightHistory {
        &self.flight
    }

    /// State `(x, p, a)` for coordinates `x`, velocities `ẋ` and lag states `a`; with the
    /// energy audit, followed by `W = D = 0`, and the audit restarts from it (`audit.rs`).
    pub fn state(&mut self, x: &[f64], xdot: &[f64], a: &[f64]) -> Vec<f64> {
        let mut y = self.structural.state(x, xdot);
        y.extend_from_slice(a);
        self.restart_audit(&mut y);
        y
    }

    /// Absolute tolerances for `(x, p, a)`: those of [`EquationsOfMotion::state_atol`] for
    /// `(x, p)`, and `atol · U₀` (m/s) for the lag states, which are upwash velocities.
    pub fn state_atol(&mut self, atol: f64) -> Vec<f64> {
        let mut v = self.structural.state_atol(atol);
        let u = self.flight.initial.speed.max(1.0);
        v.extend(std::iter::repeat_n(atol * u, self.na));
        // The audit's quadrature states are left out of the error control.
        v.resize(self.dim(), f64::INFINITY);
        v
    }

    /// Energies of `(x, p)`: kinetic (structure and fluid), strain (J). The velocity solve uses
    /// the workspace of [`Self::vertical_aerodynamic_force_at`], so that a sample's force and
    /// energies configure a reduced model once (its cache holds the last configuration).
    pub fn energies(&mut self, y: &[f64]) -> (f64, f64) {
        let n = self.n;
        let (x, p) = (&y[..n], &y[n..2 * n]);
        let mut xdot = std::mem::take(&mut self.xdot);
        let ok = self
            .aero
            .structure()
            .velocities_into(x, p, &mut self.ws, &mut xdot);
        let kinetic = if ok {
            0.5 * p.iter().zip(&xdot).map(|(a, b)| a * b).sum::<f64>()
        } else {
            f64::NAN
        };
        self.xdot = xdot;
        (kinetic, self.structural.strain_energy(x))
    }

    /// The steady lag states for the upwash of the configuration `x` at rest at time `t`:
    /// `a_i = −H̄⁻¹ B̄ w_i` (then `w_eff = w`).
    pub fn steady_states(&mut self, t: f64, x: &[f64]) -> Vec<f64> {
        self.set_air(t);
        let n = self.n;
        let ns = self.eval.states_per_strip();
        let mut a = vec![0.0; self.na];
        let mut f = vec![0.0; n];
        let mut adot = vec![0.0; self.na];
        self.eval
            .evaluate(x, &vec![0.0; n], &a, &mut f, false, &mut adot);
        if let Some(lag) = self.eval.lag() {
            let sol = lag.h.clone().lu().solve(&lag.b).expect("H̄ is invertible");
            for i in 0..self.aero.n_strips() {
                for k in 0..ns {
                    a[i * ns + k] = -sol[k] * self.eval.sc.w[i];
                }
            }
        }
        a
    }

    /// Total aerodynamic force along the ground's vertical (N) of the last right-hand side
    /// evaluated at time `t`.
    pub(crate) fn vertical_aerodynamic_force(&self, t: f64) -> f64 {
        let (sa, ca) = self.root_angle(t).sin_cos();
        self.eval
            .sc
            .force
            .iter()
            .zip(&self.aero.strips)
            .map(|(f, s)| s.width * (ca * f[1] + sa * f[2]))
            .sum()
    }

    /// Total aerodynamic force along the ground's vertical (N) at state `y` and time `t`: the
    /// velocities `ẋ = M⁻¹ p` and the strip loads only, not the whole right-hand side (the
    /// outputs of a response ask for it at every output time). NaN if `M(x)` is not positive
    /// definite.
    pub fn vertical_aerodynamic_force_at(&mut self, t: f64, y: &[f64]) -> f64 {
        let n = self.n;
        let (xp, a) = y[..2 * n + self.na].split_at(2 * n);
        let (x, p) = xp.split_at(n);
        let mut xdot = std::mem::take(&mut self.xdot);
        let mut scratch_a = std::mem::take(&mut self.scratch_a);
        let ok = self
            .aero
            .structure()
            .velocities_into(x, p, &mut self.ws, &mut xdot);
        self.set_air(t);
        self.force.fill(0.0);
        self.eval.evaluate(
            x,
            &xdot,
            a,
            self.force.as_mut_slice(),
            false,
            &mut scratch_a,
        );
        self.xdot = xdot;
        self.scratch_a = scratch_a;
        if ok {
            self.vertical_aerodynamic_force(t)
        } else {
            f64::NAN
        }
    }

    /// Tip displacement of the elastic axis from the undeformed tip `(dx, dy, dz)` (m), tip
    /// twist (rad, [`crate::model::aero::AeroChain::tip`]) and the chain's coordinates of the
    /// configuration of the last evaluation of the loads (by the kinematics already computed
    /// there).
    pub(crate) fn last_tip(&self) -> ([f64; 3], f64, &[f64]) {
        let q = self.eval.coordinates();
        let full = match self.aero.chain() {
            AeroChain::Planar(full) => full,
            AeroChain::Spatial(chain) => {
                let fr = &self.eval.sc.spatial.as_deref().expect("a 3-D scratch").fr;
                let n = chain.n_elements();
                let reference = chain.beam().reference_positions()[n];
                let r = &fr.r[n - 1];
                let tip = std::array::from_fn(|k| fr.p[n][k] - reference[k]);
                return (tip, (-r[2][1]).atan2(r[2][2]), q);
            }
        };
        let motion = &self.eval.sc.motion;
        let mut tip = [-full.beam().length(), 0.0, 0.0];
        for (l, m) in full.beam().lengths().iter().zip(motion) {
            tip[0] += l * m.cos_theta;
            tip[1] += l * m.sin_theta;
        }
        let n = full.n_elements();
        let twist = if full.has_torsion() {
            q[n..].iter().sum()
        } else {
            0.0
        };
        (tip, twist, q)
    }

    /// Replace the flight history (same gravity loads: the gravitational acceleration of the
    /// history given at construction is kept, its root-angle factor follows the new history).
    pub(crate) fn set_flight(&mut self, flight: FlightHistory) {
        self.gust_delays = gust_delays(self.aero, &flight);
        self.flight = flight;
    }

    /// The aeroelastic model.
    pub(crate) fn aero(&self) -> &'a Aeroelastic<M> {
        self.aero
    }

    /// The other loads' time functions.
    pub(crate) fn time_functions(&self) -> &[TimeFunction] {
        &self.time_functions
    }

    /// Set the increments added to the flight history (a stepper's inputs).
    pub(crate) fn set_flight_offsets(&mut self, offsets: FlightOffsets) {
        self.offsets = offsets;
    }

    /// The increments added to the flight history.
    pub(crate) fn flight_offsets(&self) -> FlightOffsets {
        self.offsets.clone()
    }

    /// Free-stream speed at `t` (m/s): the history's and the offset's.
    pub fn speed(&self, t: f64) -> f64 {
        self.flight.speed(t) + self.offsets.speed.at(t)
    }

    /// Root angle at `t` (rad): the history's and the offset's.
    pub fn root_angle(&self, t: f64) -> f64 {
        self.flight.root_angle(t) + self.offsets.root_angle.at(t)
    }

    /// Replace the other loads' time functions (one per load); errors name `field`.
    pub(crate) fn set_time_functions(
        &mut self,
        functions: Vec<TimeFunction>,
        field: &str,
    ) -> Result<(), InputError> {
        self.structural
            .set_time_functions(functions.clone(), field)?;
        self.time_functions = functions;
        Ok(())
    }

    /// The system linearized at the static equilibrium `(x, p = 0, a)` at time 0
    /// (`linear.rs`): `M`, `C̃ = C − Q_v`, `K̃ = K − ∂Q_other/∂x − Q_x`, `G`, `W_x`, `W_v`, `r_i`.
    pub(crate) fn linearize(&mut self, x: &[f64], a: &[f64]) -> Linearization {
        let m = self.linear_system(x, a);
        Linearization::new(
            m.mass,
            m.damping,
            m.stiffness,
            &m.load_per_upwash,
            &m.upwash_displacement,
            &m.upwash_velocity,
            &m.lag_rates,
            self.eval.lag().cloned(),
        )
    }

    /// The matrices of the system linearized at the static equilibrium `(x, p = 0, a)` at time
    /// 0, `a` the steady lag states of `x` ([`Self::steady_states`]); see [`LinearSystem`].
    /// O(n²) but for the dual-number derivatives, O(n · n_dofs).
    pub fn linear_system(&mut self, x: &[f64], a: &[f64]) -> LinearSystem {
        // At p = 0 the momentum and gyroscopic derivatives vanish: ∂ṗ/∂x = −K + ∂Q_o/∂x,
        // ∂ṗ/∂ẋ = −C.
        let n = self.n;
        let model = self.aero.structure();
        let mut mass = DMatrix::zeros(n, n);
        model.mass_matrix_into(x, &mut self.ws, &mut mass);
        let mut stiffness = model.stiffness_matrix();
        let scales: Vec<f64> = self.time_functions.iter().map(|f| f.at(0.0)).collect();
        model.load_jacobian_into(x, self.loads, &scales, &mut self.ws, &mut self.gravity_jac);
        stiffness -= &self.gravity_jac;
        // The structural damping matrix, formed once by the structural equations (`damping.rs`).
        let mut damping = match self.structural.damping_matrix() {
            Some(c) => c.clone(),
            None => DMatrix::zeros(n, n),
        };
        if let Some(g) = &self.gravity {
            let s = self.gravity_scale(0.0);
            model.load_jacobian_into(x, g, &s, &mut self.ws, &mut self.gravity_jac);
            stiffness -= &self.gravity_jac;
        }
        self.set_air(0.0);
        let zeros = vec![0.0; n];
        let mut f = vec![0.0; n];
        let mut adot = vec![0.0; self.na];
        self.eval.evaluate(x, &zeros, a, &mut f, false, &mut adot);
        self.eval.derivatives(&mut self.derivatives);
        let d = &self.derivatives;
        stiffness -= &d.qx;
        damping -= &d.qv;
        let lag_rates: Vec<f64> = self
            .aero
            .strips
            .iter()
            .zip(&self.eval.air)
            .map(|(s, air)| air.speed / s.b)
            .collect();
        LinearSystem {
            mass,
            damping,
            stiffness,
            load_per_upwash: d.g.clone(),
            upwash_displacement: d.wx.clone(),
            upwash_velocity: d.wv.clone(),
            lag_rates,
        }
    }

    /// How the implicit integrators solve the Newton systems (default
    /// [`AeroNewtonSystems::Auto`]); set it before integrating.
    pub fn set_newton_systems(&mut self, choice: AeroNewtonSystems) {
        self.newton_systems = choice;
        self.schur = None;
    }

    /// Whether the Newton systems are solved by eliminating the lag states (`schur.rs`): with
    /// lag states, unless [`AeroNewtonSystems::Dense`] is chosen.
    pub fn uses_lag_schur(&self) -> bool {
        self.na > 0
            && match self.newton_systems {
                AeroNewtonSystems::Auto | AeroNewtonSystems::LagSchur => true,
                AeroNewtonSystems::Dense => false,
            }
    }

    /// The Jacobian at `(t, y)` in the structured form of [`StructuredJacobian`] (module
    /// documentation): `J_ss` by `EquationsOfMotion::jacobian` plus the aerodynamic terms, and
    /// the strips' rank-one couplings to the lag states; with `second_order` also the matrices
    /// of the reduction to the coordinates.
    pub(crate) fn structured_jacobian(
        &mut self,
        t: f64,
        y: &[f64],
        sj: &mut StructuredJacobian,
        second_order: bool,
    ) {
        self.jacobian_evaluations += 1;
        let n = self.n;
        let (xp, a) = y.split_at(2 * n);
        let (x, p) = xp.split_at(n);
        self.structural.jacobian(t, xp, &mut sj.ss);
        self.dxdx.copy_from(&sj.ss.view((0, 0), (n, n)));
        self.minv.copy_from(&sj.ss.view((0, n), (n, n)));
        if let Some(g) = &self.gravity {
            let s = self.gravity_scale(t);
            self.aero
                .structure()
                .load_jacobian_into(x, g, &s, &mut self.ws, &mut self.gravity_jac);
            let mut b = sj.ss.view_mut((n, 0), (n, n));
            b += &self.gravity_jac;
        }
        // ẋ, then the aerodynamic derivatives at (x, ẋ, a).
        let mut xdot = std::mem::take(&mut self.xdot);
        for (i, v) in xdot.iter_mut().enumerate() {
            *v = self.minv.row(i).iter().zip(p).map(|(m, p)| m * p).sum();
        }
        self.set_air(t);
        let mut scratch_a = std::mem::take(&mut self.scratch_a);
        self.force.fill(0.0);
        self.eval.evaluate(
            x,
            &xdot,
            a,
            self.force.as_mut_slice(),
            false,
            &mut scratch_a,
        );
        self.xdot = xdot;
        self.scratch_a = scratch_a;
        self.eval.derivatives(&mut self.derivatives);
        let d = &self.derivatives;
        let dbar = self.eval.feedthrough();
        // Q̃_v = Q_v + G D̄ W_v.
        self.qv.copy_from(&d.qv);
        self.qv.gemm(dbar, &d.g, &d.wv, 1.0);
        // ∂ṗ/∂x += Q_x + G D̄ W_x + Q̃_v A,  ∂ṗ/∂p += Q̃_v M⁻¹.
        let mut b = sj.ss.view_mut((n, 0), (n, n));
        b += &d.qx;
        b.gemm(dbar, &d.g, &d.wx, 1.0);
        b.gemm(1.0, &self.qv, &self.dxdx, 1.0);
        let mut b = sj.ss.view_mut((n, n), (n, n));
        b.gemm(1.0, &self.qv, &self.minv, 1.0);
        // The upwash per unit state: (W_x + W_v A, W_v M⁻¹).
        let strips = d.wx.nrows();
        let mut w = sj.w.view_mut((0, 0), (strips, n));
        w.copy_from(&d.wx);
        w.gemm(1.0, &d.wv, &self.dxdx, 1.0);
        sj.w.view_mut((0, n), (strips, n))
            .gemm(1.0, &d.wv, &self.minv, 0.0);
        sj.g.copy_from(&d.g);
        for ((r, s), air) in sj
            .rates
            .iter_mut()
            .zip(&self.aero.strips)
            .zip(&self.eval.air)
        {
            *r = air.speed / s.b;
        }
        if second_order {
            // M, M A, P_p M, F = P_p M A − P_x for the reduction to the coordinates.
            sj.wx.copy_from(&d.wx);
            sj.wv.copy_from(&d.wv);
            self.aero
                .structure()
                .mass_matrix_into(x, &mut self.ws, &mut sj.mass);
            sj.ma.gemm(1.0, &sj.mass, &self.dxdx, 0.0);
            sj.pm.gemm(1.0, &sj.ss.view((n, n), (n, n)), &sj.mass, 0.0);
            sj.f.copy_from(&sj.ss.view((n, 0), (n, n)));
            sj.f.gemm(1.0, &sj.pm, &self.dxdx, -1.0);
        }
    }

    /// Keep the audit's power terms of the last right-hand side (`Q_other + Q_grav + Q_aero`,
    /// `ẋ`, `C ẋ`, and the last linearization's `(∂Q_other/∂x)ᵀ ẋ`) as point `slot` (0–2:
    /// Radau's stages, 3: the point of a quadrature step).
    fn keep_power_point(&mut self, slot: usize) {
        let n = self.n;
        let (_, xdot, c_xdot, load_rate) = self.structural.last_power_terms();
        let Some(audit) = self.audit.as_mut() else {
            return;
        };
        let point = &mut audit.points[slot];
        point.clear();
        point.extend_from_slice(&audit.force);
        point.extend_from_slice(xdot);
        point.extend_from_slice(c_xdot);
        point.extend((0..n).map(|i| load_rate.get(i).copied().unwrap_or(0.0)));
    }

    /// `(∇Ẇ·Δy, ∇Ḋ·Δy)` of the audit's quadrature rates (`audit.rs`) at the kept point `slot`
    /// for a step `Δy = dy(i)` of the leading components that changes `ẋ` by
    /// `δẋ = xdot_step(i)`: `∇Ẇ·Δy = F·δẋ + ẋ·(∂Q_other/∂x) Δx + ẋ·(∂F_ga/∂y) Δy`, `F` the
    /// forces on the structure other than `−K x + γ − C ẋ`, `F_ga` those of gravity and the
    /// aerodynamics, `(∂F_ga/∂y) Δy = (∂Q_grav/∂x + Q_x + G D̄ W_x) Δx + Q̃_v δẋ + G C̄ Δa` (the
    /// blocks of the last structured Jacobian: a simplified Newton's gradient, as `J`);
    /// `∇Ḋ·Δy = 2 (C ẋ)·δẋ`. `F`, `ẋ` and `C ẋ` are the point's.
    fn power_gradient(
        &self,
        slot: usize,
        xdot_step: impl Fn(usize) -> Complex<f64>,
        dy: impl Fn(usize) -> Complex<f64>,
    ) -> (Complex<f64>, Complex<f64>) {
        let n = self.n;
        let z = Complex::new(0.0, 0.0);
        let Some(audit) = self.audit.as_ref() else {
            return (z, z);
        };
        let point = &audit.points[slot];
        let (force, rest) = point.split_at(n);
        let (xdot, rest) = rest.split_at(n);
        let (c_xdot, load_rate) = rest.split_at(n);
        let xd = DVector::from_column_slice(xdot);
        // ẋᵀ (∂Q_grav/∂x + Q_x), ẋᵀ Q̃_v, ẋᵀ G, from the last structured Jacobian.
        let d = &self.derivatives;
        let mut hx = d.qx.tr_mul(&xd);
        if self.gravity.is_some() {
            hx += self.gravity_jac.tr_mul(&xd);
        }
        let hv = self.qv.tr_mul(&xd);
        let hg = d.g.tr_mul(&xd);
        let dbar = self.eval.feedthrough();
        let (mut w, mut dd) = (z, z);
        for i in 0..n {
            let v = xdot_step(i);
            w += v * (force[i] + hv[i]) + dy(i) * (hx[i] + load_rate[i]);
            dd += v * c_xdot[i];
        }
        // G D̄ W_x Δx and G C̄ Δa, strip by strip.
        let ns = self.eval.lag().map_or(0, |l| l.n_states());
        for (s, &g) in hg.iter().enumerate() {
            let mut upwash = z;
            for i in 0..n {
                upwash += dy(i) * d.wx[(s, i)];
            }
            w += upwash * (g * dbar);
            if let Some(lag) = self.eval.lag() {
                for k in 0..ns {
                    w += dy(2 * n + s * ns + k) * (g * lag.c[k]);
                }
            }
        }
        (w, dd * 2.0)
    }

    /// `δF = (∂Q_grav/∂x + Q_x) Δx + Q̃_v δẋ + G (D̄ W_x Δx + C̄ Δa)`: the change of the
    /// gravity and aerodynamic forces along the step `dy` (leading components) with
    /// `δẋ = xdot_step`, from the last structured Jacobian's blocks ([`Self::power_gradient`]).
    fn force_step(&self, dy: &[f64], xdot_step: &[f64]) -> DVector<f64> {
        let n = self.n;
        let d = &self.derivatives;
        let dx = DVector::from_column_slice(&dy[..n]);
        let mut f = &d.qx * &dx + &self.qv * DVector::from_column_slice(xdot_step);
        if self.gravity.is_some() {
            f += &self.gravity_jac * &dx;
        }
        let mut strip = &d.wx * &dx * self.eval.feedthrough();
        if let Some(lag) = self.eval.lag() {
            let ns = lag.n_states();
            for (s, v) in strip.iter_mut().enumerate() {
                *v += (0..ns)
                    .map(|k| dy[2 * n + s * ns + k] * lag.c[k])
                    .sum::<f64>();
            }
        }
        f + &d.g * strip
    }

    /// The quadratures' part of a Newton step `(c I − J) Δ = b` at the last right-hand side
    /// (`OdeSystem::quadrature_step_*`): `δẋ = c Δx − b_x`, the first block row.
    fn power_steps(
        &mut self,
        c: Complex<f64>,
        lead: impl Fn(usize) -> Complex<f64>,
        dy: impl Fn(usize) -> Complex<f64>,
    ) -> (Complex<f64>, Complex<f64>) {
        self.keep_power_point(3);
        self.power_gradient(3, |i| c * dy(i) - lead(i), &dy)
    }

    fn set_air(&mut self, t: f64) {
        let u = self.speed(t);
        let alpha = self.root_angle(t);
        let flight = &self.flight;
        // The stepper's uniform gust (its offset) with its rate, then the case's gust.
        let (offset, offset_rate) = (self.offsets.gust.at(t), self.offsets.gust.rate(t));
        let u0 = flight.initial.speed;
        let [v, rate, lagged] = &mut self.gust_now;
        v.fill(offset);
        rate.fill(offset_rate);
        lagged.fill(0.0);
        if let Some(g) = &flight.gust {
            for (i, s) in self.aero.strips.iter().enumerate() {
                let amplitude = g.amplitude * g.spanwise.at(s.station);
                match g.penetration {
                    GustPenetration::Uniform => {
                        v[i] += amplitude * g.factor(t, u0);
                        rate[i] += amplitude * g.rate(t, u0);
                    }
                    GustPenetration::Kussner => {
                        lagged[i] = amplitude * g.kussner_factor(t, u0, s.b, self.gust_delays[i]);
                    }
                }
            }
        }
        if !self.deflections.is_empty() {
            // The surfaces' deflections: equilibrium, the history's changes, the offsets.
            for (d, s) in self.deflections.iter_mut().zip(self.aero.surfaces()) {
                *d = [s.deflection, 0.0, 0.0];
            }
            flight.add_deflection_changes(t, &mut self.deflections);
            self.offsets.add_deflections(t, &mut self.deflections);
            self.eval.set_deflections(&self.deflections);
        }
        self.eval.set_air_with_gust(u, alpha, (v, rate, lagged));
    }

    /// Each surface's hinge moment (N·m, trailing edge down) at state `y` and time `t`
    /// ([`Aeroelastic::hinge_moments_into`]: the deflection, flap-rate and circulatory terms),
    /// by one evaluation of the strips as [`Self::vertical_aerodynamic_force_at`].
    pub fn hinge_moments_at(&mut self, t: f64, y: &[f64]) -> Vec<f64> {
        if self.deflections.is_empty() {
            return Vec::new();
        }
        if self.vertical_aerodynamic_force_at(t, y).is_nan() {
            return vec![f64::NAN; self.deflections.len()];
        }
        self.eval.hinge_moments()
    }

    fn gravity_scale(&self, t: f64) -> [f64; 1] {
        [self.root_angle(t).cos()]
    }
}

/// Per strip, the time the gust front takes from the wing's most upstream leading-edge point to
/// the strip's leading edge, convected along the initial free stream at `U₀` (undeformed
/// geometry); zeros unless Küssner's penetration (a uniform gust meets every strip at once).
fn gust_delays<M: AeroStructure>(aero: &Aeroelastic<M>, flight: &FlightHistory) -> Vec<f64> {
    let n = aero.n_strips();
    let kussner = flight
        .gust
        .as_ref()
        .is_some_and(|g| g.penetration == GustPenetration::Kussner);
    let u0 = flight.initial.speed;
    if !kussner || !(u0 > 0.0) {
        return vec![0.0; n];
    }
    // Distance along the free stream's direction (sin α ŷ − cos α ẑ).
    let (sa, ca) = flight.initial.root_angle.sin_cos();
    let along: Vec<f64> = aero
        .leading_edges()
        .iter()
        .map(|p| sa * p[1] - ca * p[2])
        .collect();
    let first = along.iter().copied().fold(f64::INFINITY, f64::min);
    along.iter().map(|d| (d - first) / u0).collect()
}

impl<M: AeroStructure> OdeSystem for AeroelasticEquations<'_, M> {
    fn dim(&self) -> usize {
        2 * self.n + self.na + if self.audit.is_some() { 2 } else { 0 }
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.rhs_evaluations += 1;
        let n = self.n;
        let (xp, a) = y[..2 * n + self.na].split_at(2 * n);
        let (dxp, rest) = dy.split_at_mut(2 * n);
        let (da, quadrature) = rest.split_at_mut(self.na);
        match self.audit.as_mut() {
            // The structural rates with the power of its loads and damping (`audit.rs`).
            Some(audit) => {
                self.structural.rhs(t, xp, &mut audit.structural);
                dxp.copy_from_slice(&audit.structural[..2 * n]);
            }
            None => self.structural.rhs(t, xp, dxp),
        }
        let x = &xp[..n];
        let (dx, dp) = dxp.split_at_mut(n);
        let structural_power = if self.audit.is_some() {
            dot(dx, dp)
        } else {
            0.0
        };
        if let Some(g) = &self.gravity {
            let s = self.gravity_scale(t);
            self.aero
                .structure()
                .generalized_forces_into(x, g, &s, &mut self.ws, &mut self.force);
            for (d, f) in dp.iter_mut().zip(self.force.iter()) {
                *d += f;
            }
        }
        self.set_air(t);
        self.eval.evaluate(x, dx, a, dp, true, da);
        if let Some(audit) = self.audit.as_mut() {
            audit.quadrature_rates(dot(dx, dp) - structural_power, quadrature);
            // Q_other + Q_grav + Q_aero: ṗ less the structure's own −K x + γ − C ẋ.
            let q_other = self.structural.last_power_terms().0;
            for i in 0..n {
                audit.force[i] = dp[i] - audit.structural[n + i] + q_other[i];
            }
        }
    }

    /// The halt flag, then the energy audit's check of the balance at the step's end.
    fn step_accepted(&mut self, t: f64, y: &[f64]) -> ControlFlow<()> {
        self.audit_step(t, y)
    }

    fn jacobian(&mut self, t: f64, y: &[f64], jac: &mut DMatrix<f64>) {
        let mut sj = std::mem::replace(&mut self.structured, StructuredJacobian::zeros(0, 0));
        if sj.ss.nrows() != 2 * self.n {
            sj = StructuredJacobian::zeros(self.n, self.aero.n_strips());
        }
        let m = 2 * self.n + self.na;
        self.structured_jacobian(t, &y[..m], &mut sj, false);
        let n = self.n;
        jac.fill(0.0);
        jac.view_mut((0, 0), (2 * n, 2 * n)).copy_from(&sj.ss);
        if let Some(lag) = self.eval.lag() {
            let ns = lag.n_states();
            for (i, &rate) in sj.rates.iter().enumerate() {
                let r0 = 2 * n + i * ns;
                for k in 0..ns {
                    for c in 0..n {
                        jac[(n + c, r0 + k)] = sj.g[(c, i)] * lag.c[k];
                    }
                    for c in 0..2 * n {
                        jac[(r0 + k, c)] = rate * lag.b[k] * sj.w[(i, c)];
                    }
                    for j in 0..ns {
                        jac[(r0 + k, r0 + j)] = rate * lag.h[(k, j)];
                    }
                }
            }
        }
        self.structured = sj;
    }

    /// With the audit, `W` and `D` (`audit.rs`).
    fn quadrature_states(&self) -> usize {
        if self.audit.is_some() {
            2
        } else {
            0
        }
    }

    fn quadrature_step_real(&mut self, c: f64, lead: &[f64], dy: &[f64], q: &mut [f64]) {
        let (w, d) = self.power_steps(
            c.into(),
            |i| Complex::new(lead[i], 0.0),
            |i| Complex::new(dy[i], 0.0),
        );
        if let [qw, qd] = q {
            *qw = (*qw + w.re) / c;
            *qd = (*qd + d.re) / c;
        }
    }

    fn quadrature_step_complex(
        &mut self,
        c: Complex<f64>,
        lead: (&[f64], &[f64]),
        dy: (&[f64], &[f64]),
        q: (&mut [f64], &mut [f64]),
    ) {
        let (w, d) = self.power_steps(
            c,
            |i| Complex::new(lead.0[i], lead.1[i]),
            |i| Complex::new(dy.0[i], dy.1[i]),
        );
        let (re, im) = q;
        for (k, add) in [w, d].into_iter().enumerate() {
            if let (Some(r), Some(i)) = (re.get_mut(k), im.get_mut(k)) {
                let v = (Complex::new(*r, *i) + add) / c;
                (*r, *i) = (v.re, v.im);
            }
        }
    }

    fn keep_quadrature_point(&mut self, slot: usize) {
        self.keep_power_point(slot);
    }

    /// The change of `Ẇ`, `Ḋ` from the kept point `slot` along `dy` to second order in the
    /// velocities: the gradients ([`Self::power_gradient`]) and `δẋ·δF_ga` ([`Self::force_step`]),
    /// `δẋᵀ C δẋ`. The aerodynamic power is quadratic in the velocities (`Q̃_v δẋ`), and Radau's
    /// one Newton correction of a large step moves it by a second-order term that the gradient
    /// alone misses (at rtol 1e-3 the reduced gust's balance error 1.2e-1 with the gradient,
    /// 6.8e-3 with this term, `benches/audit.rs`).
    fn quadrature_gradient(&mut self, slot: usize, dy: &[f64], dy_rate: &[f64], out: &mut [f64]) {
        let (w, d) = self.power_gradient(slot, |i| dy_rate[i].into(), |i| dy[i].into());
        let n = self.n;
        let damping = self.structural.damping_power_of(&dy_rate[..n]);
        let aero = dot(&dy_rate[..n], self.force_step(dy, &dy_rate[..n]).as_slice());
        if let [qw, qd] = out {
            (*qw, *qd) = (w.re + aero, d.re + damping);
        }
    }

    fn newton_solver(&mut self) -> Option<&mut dyn NewtonSolver> {
        if !self.uses_lag_schur() {
            return None;
        }
        if self.schur.is_none() {
            let lag = self.eval.lag()?.clone();
            self.schur = Some(LagSchur::new(self.n, self.aero.n_strips(), lag));
        }
        Some(self)
    }
}

/// The Newton systems by elimination of the lag states (`schur.rs`), offered by
/// [`OdeSystem::newton_solver`] when [`AeroelasticEquations::uses_lag_schur`].
impl<M: AeroStructure> NewtonSolver for AeroelasticEquations<'_, M> {
    fn linearize(&mut self, t: f64, y: &[f64]) -> bool {
        let Some(mut schur) = self.schur.take() else {
            return false;
        };
        let m = 2 * self.n + self.na;
        self.structured_jacobian(t, &y[..m], &mut schur.jac, true);
        let finite = schur.jac.is_finite();
        schur.linearized();
        self.schur = Some(schur);
        finite
    }
    fn factor_real(&mut self, slot: usize, c: f64) -> bool {
        self.schur.as_mut().is_some_and(|s| s.factor_real(slot, c))
    }
    fn factor_complex(&mut self, slot: usize, c: Complex<f64>) -> bool {
        self.schur
            .as_mut()
            .is_some_and(|s| s.factor_complex(slot, c))
    }
    fn solve_real(&mut self, slot: usize, b: &mut [f64]) {
        if let Some(s) = self.schur.as_mut() {
            s.solve_real(slot, b);
        }
    }
    fn solve_complex(&mut self, slot: usize, re: &mut [f64], im: &mut [f64]) {
        if let Some(s) = self.schur.as_mut() {
            s.solve_complex(slot, re, im);
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::beam::{
        Beam, Calibration, Discretization, InertiaAxis, Profile, SectionProperties,
        TorsionProperties,
    };
    use crate::model::aero::{AeroSection, Aerodynamics, FlightCondition};
    use crate::model::{Chain3d, Force, FullModel};
    use crate::solve::aeroelastic::flight::{Gust, GustShape};

    /// A small tapered wing with an offset mass centre, every section datum non-trivial.
    pub(crate) fn test_wing(n: usize, aerodynamics: Aerodynamics) -> Aeroelastic {
        test_wing_with(n, aerodynamics, Vec::new())
    }

    /// [`test_wing`] with the control surfaces `surfaces`.
    pub(crate) fn test_wing_with(
        n: usize,
        aerodynamics: Aerodynamics,
        surfaces: Vec<crate::model::aero::ControlSurface>,
    ) -> Aeroelastic {
        let section = SectionProperties {
            ei: Profile::Uniform(400.0),
            mass_per_length: Profile::Table {
                x: vec![0.0, 3.0],
                value: vec![1.2, 0.6],
            },
            torsion: Some(TorsionProperties {
                gj: Profile::Uniform(150.0),
                polar_inertia: Profile::Uniform(0.02),
                inertia_axis: InertiaAxis::MassCentre,
                offset: Profile::Uniform(0.03),
            }),
        };
        let full = FullModel::new(
            Beam::new(
                3.0,
                &section,
                &Discretization::Uniform(n),
                Calibration::TipLoad,
            )
            .unwrap(),
        );
        let aero = AeroSection {
            chord: Profile::Table {
                x: vec![0.0, 3.0],
                value: vec![0.5, 0.3],
            },
            elastic_axis: Profile::Uniform(0.35),
            lift_slope: Profile::Uniform(5.8),
            zero_lift_angle: Profile::Uniform(-0.03),
            cm0: Profile::Uniform(-0.02),
            cd0: Profile::Uniform(0.01),
            surfaces,
        };
        Aeroelastic::new(&full, &aero, 1.1, aerodynamics, "aero").unwrap()
    }

    /// A small 3-D wing where nothing is symmetric: swept, with dihedral and a pretwist table, a
    /// coupled section, mass-centre offsets in both directions, the tapered section data of
    /// [`test_wing`].
    pub(crate) fn test_wing_3d(n: usize, aerodynamics: Aerodynamics) -> Aeroelastic<Chain3d> {
        use crate::model::chain3d::{
            Beam3d, ElementInertia, Geometry3d, JointCalibration, SectionInertia, SectionStiffness,
            StiffnessCoupling,
        };
        let table = |a: f64, b: f64| Profile::Table {
            x: vec![0.0, 3.0],
            value: vec![a, b],
        };
        let geometry = Geometry3d::Span {
            length: 3.0,
            discretization: Discretization::Uniform(n),
            sweep: Profile::Uniform(0.15),
            dihedral: Profile::Uniform(0.05),
            pretwist: table(0.02, -0.03),
        };
        let stiffness = SectionStiffness {
            gj: Profile::Uniform(150.0),
            ei_flap: Profile::Uniform(400.0),
            ei_lag: Profile::Uniform(3000.0),
            coupling: Some(StiffnessCoupling {
                twist_flap: Profile::Uniform(20.0),
                twist_lag: Profile::Uniform(-10.0),
                lag_flap: Profile::Uniform(30.0),
            }),
        };
        let inertia = SectionInertia {
            mass_per_length: table(1.2, 0.6),
            polar_inertia: Profile::Uniform(0.02),
            polar_inertia_about: InertiaAxis::MassCentre,
            d0: Profile::Uniform(0.03),
            d0_normal: Profile::Uniform(-0.01),
            rotary_inertia_flap: Profile::Uniform(0.0),
            rotary_inertia_lag: Profile::Uniform(0.0),
            element_inertia: ElementInertia::Bar,
        };
        let chain = Chain3d::new(
            Beam3d::new(
                &geometry,
                &stiffness,
                &inertia,
                JointCalibration::Compliance,
            )
            .unwrap(),
        );
        let aero = AeroSection {
            chord: table(0.5, 0.3),
            elastic_axis: Profile::Uniform(0.35),
            lift_slope: Profile::Uniform(5.8),
            zero_lift_angle: Profile::Uniform(-0.03),
            cm0: Profile::Uniform(-0.02),
            cd0: Profile::Uniform(0.01),
            surfaces: Vec::new(),
        };
        Aeroelastic::spatial(&chain, &aero, 1.1, aerodynamics, "aero").unwrap()
    }

    /// The exact Jacobian against central differences of the right-hand side (step 1e-6:
    /// truncation ~1e-12 and round-off ~1e-10 of the largest entry; tolerance 1e-6 of it), for
    /// every aerodynamic model, full and reduced, and on the 3-D chain, with a root angle,
    /// gravity, a gust and a follower load, at a deformed moving state.
    #[test]
    fn jacobian_agrees_with_finite_differences() {
        let models = [
            Aerodynamics::Steady,
            Aerodynamics::QuasiSteady,
            Aerodynamics::Wagner,
            Aerodynamics::Peters { states: 3 },
        ];
        for am in models {
            let full = test_wing(5, am);
            check(&full);
            let rom = full.reduced(&[0, 1, 2, 3]).unwrap();
            check(&rom);
            check(&test_wing_3d(4, am));
        }
    }

    fn check<M: AeroStructure>(aero: &Aeroelastic<M>) {
        let loads = aero
            .apply(
                &[Load::PointForce {
                    span: 3.0,
                    force: Force::Follower {
                        tangential: 0.3,
                        normal: 4.0,
                    },
                }],
                "loads",
            )
            .unwrap();
        let flight = FlightHistory {
            deflection_changes: Vec::new(),
            initial: FlightCondition {
                speed: 12.0,
                root_angle: 0.05,
                gravity: Some(9.81),
            },
            speed_change: None,
            root_angle_change: None,
            gust: Some(Gust {
                shape: GustShape::OneMinusCosine { length: 10.0 },
                amplitude: 1.5,
                start: 0.0,
                spanwise: Profile::Table {
                    x: vec![0.0, 3.0],
                    value: vec![1.0, 0.5],
                },
                penetration: GustPenetration::Uniform,
            }),
        };
        let damping = Damping::Rayleigh {
            alpha: 0.1,
            beta: 1e-3,
        };
        let mut eom = AeroelasticEquations::new(
            aero,
            &loads,
            vec![TimeFunction::Constant],
            flight,
            &damping,
            "flight",
        )
        .unwrap();
        let n = eom.n_dofs();
        let na = eom.n_aero_states();
        let x: Vec<f64> = (0..n).map(|i| 0.1 * (1.0 + i as f64).sin()).collect();
        let xd: Vec<f64> = (0..n).map(|i| 0.5 * (2.0 * i as f64).cos()).collect();
        let a: Vec<f64> = (0..na).map(|i| 0.3 * (0.7 * i as f64).cos()).collect();
        let y = eom.state(&x, &xd, &a);
        let dim = eom.dim();
        let t = 0.3;
        let mut jac = DMatrix::zeros(dim, dim);
        eom.jacobian(t, &y, &mut jac);
        let h = 1e-6;
        let scale = jac.amax();
        let (mut fp, mut fm) = (vec![0.0; dim], vec![0.0; dim]);
        for c in 0..dim {
            let (mut yp, mut ym) = (y.clone(), y.clone());
            yp[c] += h;
            ym[c] -= h;
            eom.rhs(t, &yp, &mut fp);
            eom.rhs(t, &ym, &mut fm);
            for r in 0..dim {
                let fd = (fp[r] - fm[r]) / (2.0 * h);
                assert!(
                    (fd - jac[(r, c)]).abs() <= 1e-6 * scale,
                    "{:?} ({r}, {c}): {fd} vs {}",
                    aero.aerodynamics(),
                    jac[(r, c)]
                );
            }
        }
    }

    /// The linearization's `C̃ = C − ∂Q/∂ẋ` carries the structural damping of the wet model: the
    /// difference between a damped and an undamped linearization at the same state is the
    /// dense formula's `C` (`damping.rs`; the wet `M(0)` includes the fluid's inertia). A
    /// regression/consistency test of the plumbing: Rayleigh to round-off (measured 7.5e-17 of
    /// the largest entry; bound 1e-12), modal to the conditioning of the dense formula's Cholesky
    /// factor of `M(0)` (measured 1.7e-14 at 10 coordinates; bound 1e-10), for the full and a
    /// reduced model.
    #[test]
    fn linearization_carries_the_structural_damping() {
        let wing = test_wing(5, Aerodynamics::QuasiSteady);
        let rom = wing.reduced(&[0, 1, 2, 3]).unwrap();
        let dampings = [
            Damping::Rayleigh {
                alpha: 0.4,
                beta: 2e-3,
            },
            Damping::Modal {
                ratios: vec![0.02, 0.03, 0.05],
            },
        ];
        fn difference<M: AeroStructure>(aero: &Aeroelastic<M>, damping: &Damping) -> f64 {
            let loads = AppliedLoads::none();
            let flight = FlightHistory::steady(FlightCondition::at_speed(15.0));
            let linear_damping = |d: &Damping| {
                let mut eom =
                    AeroelasticEquations::new(aero, &loads, vec![], flight.clone(), d, "f")
                        .unwrap();
                let (n, na) = (eom.n_dofs(), eom.n_aero_states());
                eom.linear_system(&vec![0.0; n], &vec![0.0; na]).damping
            };
            let structural = linear_damping(damping) - linear_damping(&Damping::None);
            let model = aero.structure();
            let reference = crate::solve::damping::dense_damping(model, damping, "d").unwrap();
            (structural - &reference).amax() / reference.amax()
        }
        for damping in &dampings {
            let d_full = difference(&wing, damping);
            let d_rom = difference(&rom, damping);
            eprintln!("{damping:?}: full {d_full:.1e}, reduced {d_rom:.1e}");
            let bound = match damping {
                Damping::Rayleigh { .. } => 1e-12,
                _ => 1e-10,
            };
            assert!(
                d_full < bound && d_rom < bound,
                "{damping:?}: {d_full:.1e} {d_rom:.1e}"
            );
        }
    }

    /// At `U = 0` the aerodynamic model is the fluid's inertia only: the strip loads vanish
    /// exactly and the energy `H = ½ pᵀ M⁻¹ p + V` of the wet structure is conserved. Radau over
    /// 1 s of free vibration from a deformed, moving state: measured relative drift 9.2e-9 at
    /// rtol 1e-10 and 2.4e-10 at rtol 1e-12 (it follows the tolerance: integration error, not a
    /// model error); bound 2e-9 at rtol 1e-12.
    #[test]
    fn energy_is_conserved_at_zero_speed() {
        use crate::solve::integrate::{Radau, RadauOptions, Tolerances};
        for am in [
            Aerodynamics::QuasiSteady,
            Aerodynamics::Peters { states: 4 },
        ] {
            let aero = test_wing(6, am);
            let loads = AppliedLoads::none();
            let flight = FlightHistory::steady(FlightCondition::at_speed(0.0));
            let mut eom =
                AeroelasticEquations::new(&aero, &loads, vec![], flight, &Damping::None, "f")
                    .unwrap();
            let n = eom.n_dofs();
            let na = eom.n_aero_states();
            let x: Vec<f64> = (0..n).map(|i| 0.05 * (1.0 + i as f64).sin()).collect();
            let xd: Vec<f64> = (0..n).map(|i| 0.8 * (2.0 * i as f64).cos()).collect();
            let y0 = eom.state(&x, &xd, &vec![0.1; na]);
            let mut dy = vec![0.0; eom.dim()];
            eom.rhs(0.0, &y0, &mut dy);
            assert!(
                dy[2 * n..].iter().all(|v| *v == 0.0),
                "lag states frozen at U = 0"
            );
            let e0: f64 = {
                let (k, v) = eom.energies(&y0);
                k + v
            };
            let atol = eom.state_atol(1e-14);
            let (traj, _) = Radau {
                options: RadauOptions {
                    tolerances: Tolerances { rtol: 1e-12, atol },
                    ..Default::default()
                },
            }
            .integrate(&mut eom, 0.0, &y0, &[0.5, 1.0], &mut |_| {})
            .unwrap();
            for y in &traj.y {
                let (k, v) = eom.energies(y);
                let drift = ((k + v) - e0).abs() / e0;
                assert!(drift < 2e-9, "{am:?}: {drift}");
            }
        }
    }
}
