//! Linear state-space models of the aeroelastic system about its static equilibrium
//! (docs/control.md): `ẋ = A x + B u`, `y = C x + D u` on perturbations about the equilibrium,
//! with named, unit-carrying states, inputs and outputs (`signals.rs`).
//!
//! * `A` is the exact Jacobian of the first-order system `(x, p, a)` of
//!   [`AeroelasticEquations`] (its `OdeSystem` Jacobian: the structural part from the equations
//!   of motion, the aerodynamic part from the structured dual-number derivatives) at the
//!   equilibrium `(x*, p = 0, a*)`, `a*` the steady lag states: so its eigenvalues are those of
//!   the flutter analysis ([`super::stability_eigenvalues`]). In the velocity basis
//!   `(x, ẋ, a)` it is `T⁻¹ A T`, `T = diag(I, M(x*), I)` (`δp = M δẋ` at `ẋ = 0`).
//! * The gust's rate `gust_rate` adds the gust's apparent mass `πρb² v̇_g` at mid-chord (the
//!   non-linear strips' uniform penetration): a load per unit rate, no wind, no lag input.
//! * The inputs of the air (root angle, speed, gusts) change the wind `W` of every strip; the
//!   strip's loads depend on it through the upwash `w = W·ν + …`, the chordwise speed
//!   `W_T = −W·t + …`, the dynamic pressure `½ρ|W|²` (the circulatory loads are proportional to
//!   it) and `|W|` (the non-circulatory velocity term, the lag's time scale `|W|/b`). Their
//!   derivatives in `w`, `W_T` and the lagged upwash are dual-number evaluations of the strip
//!   loads (`model::aero::strip`), assembled along the chain (`model::aero::chain`); the root
//!   angle also turns gravity. Forces and torques at nodes are the generalized forces of unit
//!   loads.
//! * Outputs: positions and twists are linear in `x`; the lift is the sum of the strips'
//!   vertical forces, differentiated by one dual-number pass of the chain per coordinate; the
//!   accelerations are `J M⁻¹ ṗ`, the root shear the external forces less `d/dt` of the wing's
//!   vertical momentum (`Σ m_i J_g,i ẋ` and the fluid's `Σ m_a u ν_y`), both with `D ≠ 0`.
//!
//! The reduced model's states are its modal amplitudes, their rates and every strip's lag
//! states (kept per strip, as in its time responses).

use nalgebra::{DMatrix, DVector};
use num_dual::Dual64;

use super::equations::AeroelasticEquations;
use super::evaluator::AeroEvaluator;
use super::flight::FlightHistory;
use super::signals::{Input, Output, Signal, StateBasis, Surface};
use super::statics::SteadyAeroModel;
use crate::error::{Error, InputError};
use crate::model::aero::{
    section_loads, AeroChain, AeroScratch, AeroStructure, Aerodynamics, Aeroelastic, FlapAir,
    FlightCondition,
};
use crate::model::{Chain3d, DistributedForce, Force, FullModel, Load, StructuralModel};
use crate::solve::integrate::OdeSystem;
use crate::solve::{continue_static, Damping, StaticOptions, TimeFunction};

/// What to linearize: the flight condition and loads of the equilibrium, the signals, the basis.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearizeOptions {
    /// Speed (positive), root angle and gravity of the equilibrium.
    pub flight: FlightCondition,
    /// Other loads, at full value.
    pub loads: Vec<Load>,
    /// Structural damping.
    pub damping: Damping,
    /// The static solver's options for the equilibrium.
    pub static_options: StaticOptions,
    /// The inputs, in order (at least one).
    pub inputs: Vec<Input>,
    /// The outputs, in order (at least one).
    pub outputs: Vec<Output>,
    /// Velocities or momenta.
    pub basis: StateBasis,
    /// The 1-based wet-mode numbers of a reduced model's coordinates, for the state names
    /// (`eta[3]`); `None`: `1 … r`.
    pub mode_numbers: Option<Vec<usize>>,
}

/// A linear model `ẋ = A x + B u`, `y = C x + D u` on perturbations about an equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct StateSpace {
    /// `A` (`states × states`).
    pub a: DMatrix<f64>,
    /// `B` (`states × inputs`).
    pub b: DMatrix<f64>,
    /// `C` (`outputs × states`).
    pub c: DMatrix<f64>,
    /// `D` (`outputs × inputs`).
    pub d: DMatrix<f64>,
    /// The states, in order: coordinates, rates (or momenta), lag states.
    pub states: Vec<Signal>,
    /// The inputs.
    pub inputs: Vec<Signal>,
    /// The outputs.
    pub outputs: Vec<Signal>,
    /// Velocities or momenta.
    pub basis: StateBasis,
    /// The state at the equilibrium (coordinates, zero rates or momenta, steady lag states).
    pub state_values: Vec<f64>,
    /// The inputs' values at the equilibrium (the root angle, the speed; zero for the others).
    pub input_values: Vec<f64>,
    /// The outputs' values at the equilibrium.
    pub output_values: Vec<f64>,
    /// Full-model joint rotations at the equilibrium (rad).
    pub q: Vec<f64>,
}

/// The linear model of `aero` about its static equilibrium in `options` (docs/control.md);
/// `field` prefixes the error fields (`{field}.speed`, `{field}.loads[0]`, `{field}.outputs`).
///
/// # Errors
/// Invalid input: a flight condition, speed not positive, loads, no input or output, an output
/// the model cannot give (the root shear with follower loads). A solve error if no stable
/// static equilibrium is found (past the divergence speed: `SolveError::StaticUnstable`).
pub fn linearize<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    options: &LinearizeOptions,
    field: &str,
) -> Result<StateSpace, Error> {
    let flight = options.flight;
    flight.validate(field)?;
    if !(flight.speed > 0.0) {
        return Err(InputError::new(
            crate::field(field, "speed"),
            "must be positive: a linear model about a static equilibrium in flight",
        )
        .into());
    }
    for (list, what) in [
        (options.inputs.is_empty(), "inputs"),
        (options.outputs.is_empty(), "outputs"),
    ] {
        if list {
            return Err(InputError::new(
                crate::field(field, what),
                format!("needs at least one of the {what}"),
            )
            .into());
        }
    }
    let followers = options.loads.iter().any(|l| {
        matches!(
            l,
            Load::PointForce {
                force: Force::Follower { .. },
                ..
            } | Load::Distributed(DistributedForce::Follower { .. })
        )
    });
    if followers && options.outputs.contains(&Output::RootShear) {
        return Err(InputError::new(
            crate::field(field, "outputs"),
            "root_shear is not available with follower loads (their vertical components \
             follow the deformation)",
        )
        .into());
    }
    let spatial = matches!(aero.chain(), AeroChain::Spatial(_));
    for (i, output) in options.outputs.iter().enumerate() {
        let key = crate::field(field, &format!("outputs[{i}]"));
        if !spatial {
            if let Some(e) = output.planar_error(&key) {
                return Err(e.into());
            }
        } else if *output == Output::RootShear {
            return Err(InputError::new(
                key,
                "root_shear is not available on the 3-D chain yet (the momentum of its mass \
                 centres and of the fluid along the vertical is not written): use lift and \
                 the root moments",
            )
            .into());
        }
    }
    let x = equilibrium(aero, options, field)?;
    let other = aero.apply(&options.loads, &crate::field(field, "loads"))?;
    let mut eqs = AeroelasticEquations::new(
        aero,
        &other,
        vec![TimeFunction::Constant; options.loads.len()],
        FlightHistory::steady(flight),
        &options.damping,
        field,
    )?;
    let lag_states = eqs.steady_states(0.0, &x);
    let n = aero.structure().n_dofs();
    let y0 = eqs.state(&x, &vec![0.0; n], &lag_states);
    let dim = eqs.dim();
    let mut a = DMatrix::zeros(dim, dim);
    eqs.jacobian(0.0, &y0, &mut a);
    let mut point = Point::new(aero, &x, &lag_states, &flight);
    let b = point.input_matrix(&options.inputs, field)?;
    let (c, d, output_values) =
        point.output_rows(&options.outputs, &options.inputs, &a, &b, &options.loads);
    let mass = point.mass.clone();
    let (a, b, c) = match options.basis {
        StateBasis::Momenta => (a, b, c),
        StateBasis::Velocities => to_velocities(a, b, c, &mass, n),
    };
    Ok(StateSpace {
        a,
        b,
        c,
        d,
        states: state_signals(aero, options),
        inputs: options.inputs.iter().map(Input::signal).collect(),
        outputs: options.outputs.iter().map(Output::signal).collect(),
        basis: options.basis,
        state_values: y0,
        input_values: options
            .inputs
            .iter()
            .map(|i| match i {
                Input::RootAngle => flight.root_angle,
                Input::Speed => flight.speed,
                Input::Deflection(s) => aero.surfaces()[s.index].deflection,
                _ => 0.0,
            })
            .collect(),
        output_values,
        q: aero.structure().full_coordinates(&x),
    })
}

/// The eigenvalues of `a` after balancing (`balance.rs`), or of `a` itself if that real Schur
/// form does not converge within 10 000 iterations (nalgebra's unbounded default can loop
/// forever on a matrix as ill-scaled as a reduced model's with lag states; the reduced model of
/// Patil's wing in the momenta basis converges only unbalanced); `None` if neither converges.
pub fn poles(a: &DMatrix<f64>) -> Option<Vec<nalgebra::Complex<f64>>> {
    let mut m = a.clone();
    super::balance::balance(&mut m);
    let schur = nalgebra::linalg::Schur::try_new(m, f64::EPSILON, 10_000)
        .or_else(|| nalgebra::linalg::Schur::try_new(a.clone(), f64::EPSILON, 10_000))?;
    Some(schur.complex_eigenvalues().iter().copied().collect())
}

/// The static aeroelastic equilibrium of `options` (the steady model, load stepping in dynamic
/// pressure from rest), as the flutter analysis' and the responses'.
fn equilibrium<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    options: &LinearizeOptions,
    field: &str,
) -> Result<Vec<f64>, Error> {
    let flight = options.flight;
    let steady = aero.with_aerodynamics(Aerodynamics::Steady, field)?;
    let mut all = options.loads.clone();
    if let Some(g) = flight.gravity {
        all.push(Load::Gravity {
            g: g * flight.root_angle.cos(),
        });
    }
    let applied = aero.apply(&all, &crate::field(field, "loads"))?;
    let model = SteadyAeroModel::new(&steady, flight.root_angle);
    let k = applied.n_loads();
    let n = model.n_dofs();
    let mut scales = vec![1.0; k];
    scales.push(0.5 * aero.density() * flight.speed * flight.speed);
    let sol = continue_static(
        &model,
        &applied,
        (&vec![0.0; n], &vec![0.0; k + 1]),
        &scales,
        &options.static_options,
    )?;
    Ok(sol.x)
}

/// The names and units of the states.
fn state_signals<M: AeroStructure>(
    aero: &Aeroelastic<M>,
    options: &LinearizeOptions,
) -> Vec<Signal> {
    let n = aero.structure().n_dofs();
    let mut names: Vec<(String, &'static str, &'static str, &'static str)> = Vec::new();
    match (aero.structure().basis(), aero.chain()) {
        (None, AeroChain::Spatial(_)) => {
            // Joint-major: the rotation vector of joint k in (t, n, c) of its element.
            for j in 0..n {
                let base = ["phi_twist", "phi_lag", "phi_flap"][j % 3];
                names.push((format!("{base}[{}]", j / 3 + 1), "rad", "rad/s", "N·m·s"));
            }
        }
        (None, AeroChain::Planar(full)) => {
            let ne = full.n_elements();
            for j in 0..n {
                let (base, k) = if j < ne {
                    ("theta", j + 1)
                } else {
                    ("psi", j - ne + 1)
                };
                names.push((format!("{base}[{k}]"), "rad", "rad/s", "N·m·s"));
            }
        }
        (Some(_), _) => {
            let numbers: Vec<usize> = options
                .mode_numbers
                .clone()
                .unwrap_or_else(|| (1..=n).collect());
            for k in numbers {
                names.push((format!("eta[{k}]"), "kg^0.5·m", "kg^0.5·m/s", "kg^0.5·m/s"));
            }
        }
    }
    let mut out: Vec<Signal> = names
        .iter()
        .map(|(name, unit, _, _)| Signal {
            name: name.clone(),
            unit,
        })
        .collect();
    for (name, _, rate, momentum) in &names {
        let (base, index) = name.split_at(name.find('[').unwrap_or(name.len()));
        out.push(match options.basis {
            StateBasis::Velocities => Signal {
                name: format!("{base}_dot{index}"),
                unit: rate,
            },
            StateBasis::Momenta => Signal {
                name: format!("p_{base}{index}"),
                unit: momentum,
            },
        });
    }
    let ns = aero.aerodynamics().states_per_strip();
    for i in 0..aero.n_strips() {
        for k in 0..ns {
            out.push(Signal {
                name: format!("lag[{}][{}]", i + 1, k + 1),
                unit: "m/s",
            });
        }
    }
    out
}

/// `(A, B, C)` of the momentum basis in the velocity basis: `T⁻¹ A T`, `T⁻¹ B`, `C T` with
/// `T = diag(I, M, I)`.
fn to_velocities(
    mut a: DMatrix<f64>,
    mut b: DMatrix<f64>,
    mut c: DMatrix<f64>,
    mass: &DMatrix<f64>,
    n: usize,
) -> (DMatrix<f64>, DMatrix<f64>, DMatrix<f64>) {
    let dim = a.nrows();
    // Columns of p: A[:, p] M, C[:, p] M.
    let ap = a.columns(n, n) * mass;
    a.columns_mut(n, n).copy_from(&ap);
    let cp = c.columns(n, n) * mass;
    c.columns_mut(n, n).copy_from(&cp);
    // Rows of p: M⁻¹ A[p, :], M⁻¹ B[p, :] (M symmetric positive definite at an equilibrium).
    let chol = mass
        .clone()
        .cholesky()
        .expect("the wet mass matrix is positive definite");
    let ar = chol.solve(&a.rows(n, n).into_owned());
    a.rows_mut(n, n).copy_from(&ar);
    let br = chol.solve(&b.rows(n, n).into_owned());
    b.rows_mut(n, n).copy_from(&br);
    debug_assert_eq!(a.ncols(), dim);
    (a, b, c)
}

/// The derivatives of one strip's loads per unit change of its wind `W` (wing frame), at the
/// equilibrium: force (3 components) and nose-up moment, per unit length.
#[derive(Debug, Clone, Copy, Default)]
struct WindDerivative {
    /// `∂(F, M)/∂W_k`, `k = x, y, z`.
    loads: [[f64; 4]; 3],
    /// `∂w/∂W_k` (the geometric upwash, the lag's input).
    upwash: [f64; 3],
    /// `∂|W|/∂W_k`.
    speed: [f64; 3],
    /// `∂(F, M)/∂w` with the lagged upwash following (`D̄`, 1 without lag) at fixed lag states:
    /// the loads per unit equivalent upwash of a flap.
    per_upwash: [f64; 4],
}

/// The linearization point: the evaluation of the strips at the equilibrium and what the rows
/// and columns of inputs and outputs need.
struct Point<'a, M: AeroStructure> {
    aero: &'a Aeroelastic<M>,
    eval: AeroEvaluator<'a, M>,
    x: Vec<f64>,
    adot: Vec<f64>,
    flight: FlightCondition,
    /// The wet mass matrix at the equilibrium.
    mass: DMatrix<f64>,
    wind: Vec<WindDerivative>,
    ws: M::Workspace,
}

impl<'a, M: AeroStructure> Point<'a, M> {
    fn new(
        aero: &'a Aeroelastic<M>,
        x: &[f64],
        lag_states: &[f64],
        flight: &FlightCondition,
    ) -> Self {
        let n = aero.structure().n_dofs();
        let mut eval = AeroEvaluator::new(aero);
        eval.set_air(flight.speed, flight.root_angle, |_| 0.0);
        let mut f = vec![0.0; n];
        let mut adot = vec![0.0; aero.n_aero_states()];
        eval.evaluate(x, &vec![0.0; n], lag_states, &mut f, false, &mut adot);
        let mut ws = aero.structure().workspace();
        let mut mass = DMatrix::zeros(n, n);
        aero.structure().mass_matrix_into(x, &mut ws, &mut mass);
        let mut point = Self {
            aero,
            eval,
            x: x.to_vec(),
            adot,
            flight: *flight,
            mass,
            wind: Vec::new(),
            ws,
        };
        point.wind = (0..aero.n_strips())
            .map(|i| point.wind_derivative(i))
            .collect();
        point
    }

    /// Strip `i`'s loads per unit wind (module documentation).
    fn wind_derivative(&self, i: usize) -> WindDerivative {
        let s = &self.aero.strips[i];
        let air = self.eval.air[i];
        let rho = self.aero.density();
        let unsteady = self.aero.aerodynamics().is_unsteady();
        let (t, nu, psi_dot) = self.eval.sc.section_frame(i);
        let dual = |v: [f64; 3]| v.map(Dual64::from);
        let frame = (dual(t), dual(nu), Dual64::from(psi_dot));
        let (w, wt, weff) = (self.eval.sc.w[i], self.eval.sc.wt[i], self.eval.sc.weff[i]);
        let along = |k: usize| {
            let v = |j: usize, x: f64| Dual64::new(x, if j == k { 1.0 } else { 0.0 });
            let (f, mo) = section_loads(
                s,
                frame,
                &air,
                rho,
                (v(0, w), v(1, wt), v(2, weff)),
                unsteady,
            );
            [f[0].eps, f[1].eps, f[2].eps, mo.eps]
        };
        let (dw, dwt, dweff) = (along(0), along(1), along(2));
        // The circulatory loads (proportional to the dynamic pressure) at the equilibrium.
        let (fc, mc) = section_loads(s, (t, nu, psi_dot), &air, rho, (w, wt, weff), false);
        let per_pressure = [fc[0], fc[1], fc[2], mc].map(|v| v / air.pressure);
        // The non-circulatory velocity term πρb²|W|ψ̇ along ν at the three-quarter chord.
        let nc = if unsteady {
            let fv = psi_dot * std::f64::consts::PI * rho * s.b * s.b;
            [fv * nu[0], fv * nu[1], fv * nu[2], fv * s.zeta_34()]
        } else {
            [0.0; 4]
        };
        let dbar = self.eval.feedthrough();
        let lagged = if self.eval.lag().is_some() { dbar } else { 1.0 };
        let mut out = WindDerivative::default();
        // A flap's equivalent upwash `φ V T10 δ/π` grows with the strip's speed `V = |W|`.
        let flap_per_speed = air.flap.upwash / air.speed;
        for k in 0..3 {
            let dq = rho * air.wind[k];
            let dv = air.wind[k] / air.speed;
            let (dwk, dwtk) = (nu[k] + flap_per_speed * dv, -t[k]);
            for r in 0..4 {
                out.loads[k][r] = dw[r] * dwk
                    + dwt[r] * dwtk
                    + dweff[r] * lagged * dwk
                    + per_pressure[r] * dq
                    + nc[r] * dv;
            }
            out.upwash[k] = dwk;
            out.speed[k] = dv;
        }
        out.per_upwash = std::array::from_fn(|r| dw[r] + dweff[r] * lagged);
        out
    }

    /// Per strip, what a unit deflection input adds (`flap::flap_air` of a unit `δ`, `δ̇` or
    /// `δ̈` of its surface, linear in them); `None` for another input.
    fn flap_per_unit(&self, input: &Input) -> Option<Vec<FlapAir>> {
        let (surface, unit) = match input {
            Input::Deflection(s) => (s, [1.0, 0.0, 0.0]),
            Input::DeflectionRate(s) => (s, [0.0, 1.0, 0.0]),
            Input::DeflectionAcceleration(s) => (s, [0.0, 0.0, 1.0]),
            _ => return None,
        };
        Some(
            self.aero
                .strips
                .iter()
                .zip(&self.eval.air)
                .map(|(s, air)| match &s.flap {
                    Some(f) if f.surface == surface.index => crate::model::aero::flap_air(
                        f,
                        s.b,
                        self.aero.density(),
                        air.speed,
                        unit,
                        self.aero.aerodynamics().is_unsteady(),
                    ),
                    _ => FlapAir::default(),
                })
                .collect(),
        )
    }

    /// The wind change per unit input at strip `i` (wing frame), `None` for a non-wind input.
    fn wind_of(&self, input: &Input, i: usize) -> Option<[f64; 3]> {
        let (sa, ca) = self.flight.root_angle.sin_cos();
        let u = self.flight.speed;
        // W = (0, U sin α + g cos α, −U cos α + g sin α) (`Aeroelastic::air_into`).
        match input {
            Input::RootAngle => Some([0.0, u * ca, u * sa]),
            Input::Speed => Some([0.0, sa, -ca]),
            Input::Gust => Some([0.0, ca, sa]),
            Input::StripGust(k) => Some(if *k == i + 1 { [0.0, ca, sa] } else { [0.0; 3] }),
            Input::GustRate
            | Input::Force(_)
            | Input::Torque(_)
            | Input::Deflection(_)
            | Input::DeflectionRate(_)
            | Input::DeflectionAcceleration(_) => None,
        }
    }

    /// The strips' load changes `(δF, δM)` per unit `input` (zeros for a non-wind input but the
    /// gust's rate).
    fn strip_changes(&self, input: &Input) -> Vec<[f64; 4]> {
        if *input == Input::GustRate {
            return self.apparent_mass_of_gust_rate();
        }
        if let Some(flaps) = self.flap_per_unit(input) {
            // The equivalent upwash through the loads' upwash derivatives, the normal force
            // along ν and the moment (`model::aero::strip::loads`).
            return flaps
                .iter()
                .enumerate()
                .map(|(i, fa)| {
                    let d = &self.wind[i];
                    let (_, nu, _) = self.eval.sc.section_frame(i);
                    let mut c: [f64; 4] = std::array::from_fn(|r| d.per_upwash[r] * fa.upwash);
                    for k in 0..3 {
                        c[k] += nu[k] * fa.normal;
                    }
                    c[3] += fa.moment;
                    c
                })
                .collect();
        }
        (0..self.aero.n_strips())
            .map(|i| match self.wind_of(input, i) {
                None => [0.0; 4],
                Some(dw) => {
                    let d = &self.wind[i];
                    std::array::from_fn(|r| (0..3).map(|k| d.loads[k][r] * dw[k]).sum())
                }
            })
            .collect()
    }

    /// The strips' loads per unit rate of the uniform gust: its apparent mass `πρb² (ġ·ν) ν` at
    /// mid-chord (moment `πρb² (ġ·ν) a b`), `ġ = (0, cos α, sin α)` per unit rate, as the
    /// non-linear strips apply it (`model::aero::strip::section_loads`); none with steady
    /// aerodynamics.
    fn apparent_mass_of_gust_rate(&self) -> Vec<[f64; 4]> {
        let (sa, ca) = self.flight.root_angle.sin_cos();
        let unsteady = self.aero.aerodynamics().is_unsteady();
        let rho = self.aero.density();
        (0..self.aero.n_strips())
            .map(|i| {
                if !unsteady {
                    return [0.0; 4];
                }
                let s = &self.aero.strips[i];
                let (_, nu, _) = self.eval.sc.section_frame(i);
                let fa = (nu[1] * ca + nu[2] * sa) * std::f64::consts::PI * rho * s.b * s.b;
                [fa * nu[0], fa * nu[1], fa * nu[2], fa * s.a * s.b]
            })
            .collect()
    }

    /// Generalized forces (model coordinates) of per-length strip loads `changes`.
    fn assemble(&self, changes: &[[f64; 4]]) -> DVector<f64> {
        let mut sc = self.eval.sc.clone();
        for (i, c) in changes.iter().enumerate() {
            sc.force[i] = [c[0], c[1], c[2]];
            sc.moment[i] = c[3];
        }
        self.aero.assemble(&mut sc);
        project(self.aero, &sc.q)
    }

    /// `B` in the momentum basis.
    fn input_matrix(&mut self, inputs: &[Input], field: &str) -> Result<DMatrix<f64>, Error> {
        let n = self.aero.structure().n_dofs();
        let na = self.aero.n_aero_states();
        let ns = self.aero.aerodynamics().states_per_strip();
        let mut b = DMatrix::zeros(2 * n + na, inputs.len());
        let nodes = self.aero.chain().nodes().to_vec();
        for (col, input) in inputs.iter().enumerate() {
            let q = match input {
                Input::Force(k) | Input::Torque(k) => {
                    let load = match input {
                        Input::Force(_) => Load::PointForce {
                            span: nodes[*k],
                            force: Force::Dead { fx: 0.0, fy: 1.0 },
                        },
                        _ => Load::Torque {
                            span: nodes[*k],
                            value: 1.0,
                        },
                    };
                    let applied = self
                        .aero
                        .apply(&[load], &crate::field(field, &format!("inputs[{col}]")))?;
                    let mut out = DVector::zeros(n);
                    self.aero.structure().generalized_forces_into(
                        &self.x,
                        &applied,
                        &[1.0],
                        &mut self.ws,
                        &mut out,
                    );
                    out
                }
                _ => {
                    let mut q = self.assemble(&self.strip_changes(input));
                    if let (Input::RootAngle, Some(g)) = (input, self.flight.gravity) {
                        // Gravity's share in the wing frame: g cos α.
                        let grav = self.aero.apply(&[Load::Gravity { g }], field)?;
                        let mut out = DVector::zeros(n);
                        self.aero.structure().generalized_forces_into(
                            &self.x,
                            &grav,
                            &[1.0],
                            &mut self.ws,
                            &mut out,
                        );
                        q -= out * self.flight.root_angle.sin();
                    }
                    // The lag states: ȧ_i = r_i (H̄ a_i + B̄ w_i), r_i = |W|/b_i.
                    if let Some(lag) = self.eval.lag() {
                        for i in 0..self.aero.n_strips() {
                            let Some(dw) = self.wind_of(input, i) else {
                                continue;
                            };
                            let d = &self.wind[i];
                            let dup: f64 = (0..3).map(|k| d.upwash[k] * dw[k]).sum();
                            let dv: f64 = (0..3).map(|k| d.speed[k] * dw[k]).sum();
                            let air = &self.eval.air[i];
                            let rate = air.speed / self.aero.strips[i].b;
                            for k in 0..ns {
                                let r = i * ns + k;
                                b[(2 * n + r, col)] =
                                    rate * lag.b[k] * dup + self.adot[r] / air.speed * dv;
                            }
                        }
                        // A flap's equivalent upwash is the lag's input as the strip's own.
                        if let Some(flaps) = self.flap_per_unit(input) {
                            for (i, fa) in flaps.iter().enumerate() {
                                let rate = self.eval.air[i].speed / self.aero.strips[i].b;
                                for k in 0..ns {
                                    b[(2 * n + i * ns + k, col)] = rate * lag.b[k] * fa.upwash;
                                }
                            }
                        }
                    }
                    q
                }
            };
            b.view_mut((n, col), (n, 1)).copy_from(&q);
        }
        Ok(b)
    }

    /// Per-strip load changes along a direction of the coordinates (`rates`: of the velocities),
    /// at fixed lag states: one dual-number pass of the chain.
    fn strip_changes_along(&self, direction: &[f64], rates: bool) -> Vec<[f64; 4]> {
        let dsc = self.along(direction, rates);
        dsc.force
            .iter()
            .zip(&dsc.moment)
            .map(|(f, m)| [f[0].eps, f[1].eps, f[2].eps, m.eps])
            .collect()
    }

    /// The chain's evaluation along a direction of the coordinates (`rates`: of the
    /// velocities) at fixed lag states, as dual numbers: flows, lagged upwash and loads.
    fn along(&self, direction: &[f64], rates: bool) -> AeroScratch<Dual64> {
        let aero = self.aero;
        let sc = &self.eval.sc;
        let mut dsc = aero.scratch::<Dual64>();
        let nf = direction.len();
        let dbar = self.eval.feedthrough();
        if rates {
            aero.freeze_configuration(sc, &mut dsc);
            let dq: Vec<Dual64> = direction.iter().map(|&v| Dual64::new(0.0, v)).collect();
            aero.set_rates(&dq, &mut dsc);
        } else {
            aero.set_configuration_along(sc, self.eval.coordinates(), direction, &mut dsc);
            aero.set_rates(&vec![Dual64::from(0.0); nf], &mut dsc);
        }
        aero.set_flow(&self.eval.air, &mut dsc);
        // The lagged upwash w_eff = C̄ a + D̄ w at fixed a (w_eff = w without lag).
        for i in 0..dsc.w.len() {
            dsc.weff[i] = Dual64::new(sc.weff[i], dbar * dsc.w[i].eps);
        }
        aero.set_loads(&self.eval.air, &mut dsc);
        dsc
    }

    /// The per-strip load changes per unit lag state `(strip i, state k)`: `∂F_i/∂w_eff C̄_k`.
    fn strip_changes_per_lag(&self, i: usize) -> [f64; 4] {
        let s = &self.aero.strips[i];
        let (t, nu, psi_dot) = self.eval.sc.section_frame(i);
        let lift3 = |v: [f64; 3]| v.map(Dual64::from);
        let dual = |v: f64| Dual64::from(v);
        let sc = &self.eval.sc;
        let (f, mo) = section_loads(
            s,
            (lift3(t), lift3(nu), Dual64::from(psi_dot)),
            &self.eval.air[i],
            self.aero.density(),
            (dual(sc.w[i]), dual(sc.wt[i]), Dual64::new(sc.weff[i], 1.0)),
            self.aero.aerodynamics().is_unsteady(),
        );
        [f[0].eps, f[1].eps, f[2].eps, mo.eps]
    }

    /// The rows of `C` (momentum basis) and `D` and the outputs' values at the equilibrium;
    /// `a`, `b` the momentum-basis `A` and `B` of `inputs`, `loads` the other loads.
    fn output_rows(
        &mut self,
        outputs: &[Output],
        inputs: &[Input],
        a: &DMatrix<f64>,
        b: &DMatrix<f64>,
        loads: &[Load],
    ) -> (DMatrix<f64>, DMatrix<f64>, Vec<f64>) {
        let aero = self.aero;
        let structure = aero.structure();
        let n = structure.n_dofs();
        let ne = aero.chain().n_elements();
        let dim = a.nrows();
        let q = structure.full_coordinates(&self.x);
        let geometry = Geometry::new(aero.chain(), &q);
        let phi = |row: &DVector<f64>| -> DVector<f64> { project(aero, row.as_slice()) };
        // M⁻¹ [A_p, B_p]: the coordinates' accelerations per unit state and input.
        let chol = self
            .mass
            .clone()
            .cholesky()
            .expect("the wet mass matrix is positive definite");
        let acc_a = chol.solve(&a.rows(n, n).into_owned());
        let acc_b = chol.solve(&b.rows(n, n).into_owned());
        let (sa, ca) = self.flight.root_angle.sin_cos();
        let mut c = DMatrix::zeros(outputs.len(), dim);
        let mut d = DMatrix::zeros(outputs.len(), inputs.len());
        let mut values = Vec::with_capacity(outputs.len());
        let mut vertical: Option<VerticalForce> = None;
        for (r, output) in outputs.iter().enumerate() {
            let (row, value): (Option<DVector<f64>>, f64) = match output {
                Output::TipAcceleration | Output::Acceleration(_) => {
                    let k = match output {
                        Output::Acceleration(k) => *k,
                        _ => ne,
                    };
                    let j = phi(&geometry.row(&Output::Y(k)).0);
                    c.row_mut(r).copy_from(&(j.transpose() * &acc_a));
                    d.row_mut(r).copy_from(&(j.transpose() * &acc_b));
                    (None, 0.0)
                }
                Output::HingeMoment(surface) => {
                    let (crow, drow) = self.hinge_rows(surface, inputs);
                    c.row_mut(r).copy_from(&crow.transpose());
                    d.row_mut(r).copy_from(&drow.transpose());
                    (None, self.eval.hinge_moments()[surface.index])
                }
                Output::Lift | Output::RootShear => {
                    let v = vertical.get_or_insert_with(|| self.vertical_force(inputs));
                    let lift = matches!(output, Output::Lift);
                    let (wy, wz) = if lift { (ca, sa) } else { (1.0, 0.0) };
                    let mut crow = &v.x_y * wy + &v.x_z * wz;
                    let mut drow = &v.u_y * wy + &v.u_z * wz;
                    let mut value = v.value[0] * wy + v.value[1] * wz;
                    if lift {
                        // The ground's vertical turns with the root angle.
                        for (j, input) in inputs.iter().enumerate() {
                            if *input == Input::RootAngle {
                                drow[j] += -sa * v.value[0] + ca * v.value[1];
                            }
                        }
                    } else {
                        let (momentum, gravity, applied) = self.shear_parts(&q, loads);
                        let lp = phi(&momentum).transpose();
                        crow -= (&lp * &acc_a).transpose();
                        drow -= (&lp * &acc_b).transpose();
                        value += gravity + applied;
                        for (j, input) in inputs.iter().enumerate() {
                            match input {
                                Input::Force(_) => drow[j] += 1.0,
                                // Gravity's share along y is −g cos α Σ m.
                                Input::RootAngle => drow[j] -= gravity * sa / ca,
                                _ => {}
                            }
                        }
                    }
                    c.row_mut(r).copy_from(&crow.transpose());
                    d.row_mut(r).copy_from(&drow.transpose());
                    (None, value)
                }
                geometric => {
                    let (row, value) = geometry.row(geometric);
                    (Some(phi(&row)), value)
                }
            };
            if let Some(row) = row {
                c.view_mut((r, 0), (1, n)).copy_from(&row.transpose());
            }
            values.push(value);
        }
        (c, d, values)
    }

    /// The wing's vertical momentum per unit velocity `∂P_y/∂q̇` (full coordinates: the
    /// structure's mass centres and the fluid's normal momentum at mid-chord), gravity's share
    /// of the external vertical force and the applied dead loads' (N) at the equilibrium.
    fn shear_parts(&self, q: &[f64], loads: &[Load]) -> (DVector<f64>, f64, f64) {
        let AeroChain::Planar(full) = self.aero.chain() else {
            unreachable!("root_shear is refused on the 3-D chain (`linearize`)")
        };
        let kin = &full.kinematics(q);
        let ne = full.n_elements();
        let nf = full.n_dofs();
        let masses = full.beam().masses();
        let mut momentum = DVector::zeros(nf);
        for (i, &m) in masses.iter().enumerate() {
            let j = full.mass_centre_jacobian(kin, i);
            for c in 0..nf {
                momentum[c] += m * j[(1, c)];
            }
        }
        if let Some(fluid) = &full.fluid {
            for (i, s) in self.aero.strips.iter().enumerate() {
                let (c, si) = (kin.cos_theta[i], kin.sin_theta[i]);
                let (cp, sp) = (kin.cos_psi[i], kin.sin_psi[i]);
                let nu = [-(cp * si), cp * c, -sp];
                let jc = full.point_jacobian(kin, s.station);
                let weight = fluid.mass[i] * nu[1];
                for col in 0..nf {
                    let mut u: f64 = (0..3).map(|k| nu[k] * jc[(k, col)]).sum();
                    if full.has_torsion() && col >= ne && col - ne <= i {
                        u += fluid.station[i];
                    }
                    momentum[col] += weight * u;
                }
            }
        }
        let total: f64 = masses.iter().sum();
        let length = full.beam().length();
        let gravity = self
            .flight
            .gravity
            .map_or(0.0, |g| -g * self.flight.root_angle.cos() * total);
        let applied: f64 = loads
            .iter()
            .map(|l| match l {
                Load::PointForce {
                    force: Force::Dead { fy, .. },
                    ..
                } => *fy,
                Load::Distributed(DistributedForce::Dead { fy, .. }) => {
                    crate::beam::profile::integrate(&[fy], 0.0, length, |x| fy.at(x))
                }
                Load::Gravity { g } => -g * total,
                _ => 0.0,
            })
            .sum();
        (momentum, gravity, applied)
    }

    /// The rows of `C` (momentum basis) and `D` of the hinge moment of `surface`
    /// (`Aeroelastic::hinge_moments_into`): per covered strip `h = h_δ(V, δ) + κ L_c`,
    /// `κ = −T12 b/(2π)`, `L_c = q 2b c_lα (atan2(ŵ, W_T) − α0)` with `ŵ` the lagged upwash
    /// plus the uncovered share of the flap's, differentiated in `ŵ`, `W_T`, `q` and `V`.
    fn hinge_rows(&self, surface: &Surface, inputs: &[Input]) -> (DVector<f64>, DVector<f64>) {
        let aero = self.aero;
        let n = aero.structure().n_dofs();
        let ns = aero.aerodynamics().states_per_strip();
        let unsteady = aero.aerodynamics().is_unsteady();
        let rho = aero.density();
        let nf = aero.chain().n_dofs();
        let rest = self.eval.deflections()[surface.index];
        let lagged = if self.eval.lag().is_some() {
            self.eval.feedthrough()
        } else {
            1.0
        };
        // Per covered strip: (i, weight φℓ, ∂h/∂ŵ, ∂h/∂W_T, ∂h/∂q, ∂h/∂V, its flap).
        let mut parts = Vec::new();
        for (i, s) in aero.strips.iter().enumerate() {
            let Some(f) = s.flap.filter(|f| f.surface == surface.index) else {
                continue;
            };
            let air = &self.eval.air[i];
            let (w, wt) = (
                self.eval.sc.weff[i] + (1.0 - f.coverage) * air.flap.covered_upwash,
                self.eval.sc.wt[i],
            );
            let kappa = -f.coefficients.t[12] * s.b / (2.0 * std::f64::consts::PI);
            let slope = kappa * air.pressure * 2.0 * s.b * s.lift_slope / (w * w + wt * wt);
            let per_pressure = kappa * 2.0 * s.b * s.lift_slope * (w.atan2(wt) - s.alpha0);
            // h_δ is `V² δ` times a constant at the equilibrium (δ̇ = δ̈ = 0).
            let flap =
                crate::model::aero::hinge_moment(&f, s.b, rho, air.speed, rest, unsteady, 0.0);
            let per_speed = 2.0 * flap / air.speed;
            let weight = f.coverage * s.width;
            parts.push((
                i,
                weight,
                slope * wt,
                -slope * w,
                per_pressure,
                per_speed,
                f,
            ));
        }
        let mut crow = DVector::zeros(2 * n + aero.n_aero_states());
        let mut rate_row = DVector::zeros(n);
        for k in 0..n {
            let dir: Vec<f64> = match aero.structure().basis() {
                None => (0..nf).map(|j| if j == k { 1.0 } else { 0.0 }).collect(),
                Some(phi) => phi.column(k).iter().copied().collect(),
            };
            let flows = |dsc: &AeroScratch<Dual64>| -> f64 {
                parts
                    .iter()
                    .map(|&(i, weight, hw, ht, ..)| {
                        weight * (hw * dsc.weff[i].eps + ht * dsc.wt[i].eps)
                    })
                    .sum()
            };
            crow[k] = flows(&self.along(&dir, false));
            if unsteady {
                rate_row[k] = flows(&self.along(&dir, true));
            }
        }
        // ∂/∂p = ∂/∂ẋ M⁻¹ (M symmetric).
        let chol = self
            .mass
            .clone()
            .cholesky()
            .expect("the wet mass matrix is positive definite");
        crow.rows_mut(n, n).copy_from(&chol.solve(&rate_row));
        if let Some(lag) = self.eval.lag() {
            for &(i, weight, hw, ..) in &parts {
                for k in 0..ns {
                    crow[2 * n + i * ns + k] = weight * hw * lag.c[k];
                }
            }
        }
        let mut drow = DVector::zeros(inputs.len());
        for (j, input) in inputs.iter().enumerate() {
            if let Some(flaps) = self.flap_per_unit(input) {
                // The surface's own terms for its own deflection only.
                let unit = match input {
                    Input::Deflection(s) if s == surface => [1.0, 0.0, 0.0],
                    Input::DeflectionRate(s) if s == surface => [0.0, 1.0, 0.0],
                    Input::DeflectionAcceleration(s) if s == surface => [0.0, 0.0, 1.0],
                    _ => [0.0; 3],
                };
                drow[j] = parts
                    .iter()
                    .map(|&(i, weight, hw, _, _, _, f)| {
                        let fa = &flaps[i];
                        let s = &aero.strips[i];
                        let speed = self.eval.air[i].speed;
                        let dw = lagged * fa.upwash + (1.0 - f.coverage) * fa.covered_upwash;
                        let own = crate::model::aero::hinge_moment(
                            &f, s.b, rho, speed, unit, unsteady, 0.0,
                        );
                        weight * (hw * dw + own)
                    })
                    .sum();
                continue;
            }
            drow[j] = parts
                .iter()
                .map(|&(i, weight, hw, ht, hq, hv, f)| {
                    let Some(dw) = self.wind_of(input, i) else {
                        return 0.0;
                    };
                    let d = &self.wind[i];
                    let air = &self.eval.air[i];
                    let (t, _, _) = self.eval.sc.section_frame(i);
                    let dot = |v: &[f64; 3]| -> f64 { (0..3).map(|k| v[k] * dw[k]).sum() };
                    let dv = dot(&d.speed);
                    let dq = rho * dot(&air.wind);
                    // The uncovered share of the flap's upwash grows with the speed as `V δ`.
                    let dhat = lagged * dot(&d.upwash)
                        + (1.0 - f.coverage) * air.flap.covered_upwash / air.speed * dv;
                    let dwt = -dot(&t);
                    weight * (hw * dhat + ht * dwt + hq * dq + hv * dv)
                })
                .sum();
        }
        (crow, drow)
    }

    /// The strips' summed forces along the wing frame's `y` and `z` per unit state and input,
    /// and their values at the equilibrium.
    fn vertical_force(&self, inputs: &[Input]) -> VerticalForce {
        let aero = self.aero;
        let n = aero.structure().n_dofs();
        let na = aero.n_aero_states();
        let ns = aero.aerodynamics().states_per_strip();
        let widths: Vec<f64> = aero.strips.iter().map(|s| s.width).collect();
        let sum = |changes: &[[f64; 4]], comp: usize| -> f64 {
            changes.iter().zip(&widths).map(|(c, w)| w * c[comp]).sum()
        };
        let dim = 2 * n + na;
        let mut out = VerticalForce {
            x_y: DVector::zeros(dim),
            x_z: DVector::zeros(dim),
            u_y: DVector::zeros(inputs.len()),
            u_z: DVector::zeros(inputs.len()),
            value: [0.0; 2],
        };
        let nf = aero.chain().n_dofs();
        let mut rate_y = DVector::zeros(n);
        let mut rate_z = DVector::zeros(n);
        for k in 0..n {
            let dir: Vec<f64> = match aero.structure().basis() {
                None => (0..nf).map(|j| if j == k { 1.0 } else { 0.0 }).collect(),
                Some(phi) => phi.column(k).iter().copied().collect(),
            };
            let along_x = self.strip_changes_along(&dir, false);
            out.x_y[k] = sum(&along_x, 1);
            out.x_z[k] = sum(&along_x, 2);
            if aero.aerodynamics().is_unsteady() {
                let along_v = self.strip_changes_along(&dir, true);
                rate_y[k] = sum(&along_v, 1);
                rate_z[k] = sum(&along_v, 2);
            }
        }
        // ∂/∂p = ∂/∂ẋ M⁻¹ (M symmetric).
        let chol = self
            .mass
            .clone()
            .cholesky()
            .expect("the wet mass matrix is positive definite");
        out.x_y.rows_mut(n, n).copy_from(&chol.solve(&rate_y));
        out.x_z.rows_mut(n, n).copy_from(&chol.solve(&rate_z));
        if let Some(lag) = self.eval.lag() {
            for i in 0..aero.n_strips() {
                let per = self.strip_changes_per_lag(i);
                for k in 0..ns {
                    let r = 2 * n + i * ns + k;
                    out.x_y[r] = widths[i] * per[1] * lag.c[k];
                    out.x_z[r] = widths[i] * per[2] * lag.c[k];
                }
            }
        }
        for (j, input) in inputs.iter().enumerate() {
            let changes = self.strip_changes(input);
            out.u_y[j] = sum(&changes, 1);
            out.u_z[j] = sum(&changes, 2);
        }
        for (f, w) in self.eval.sc.force.iter().zip(&widths) {
            out.value[0] += w * f[1];
            out.value[1] += w * f[2];
        }
        out
    }
}

/// The outputs linear in the chain's joint coordinates — node positions, twists, the root
/// springs' moments — as rows `∂y/∂q` (full coordinates) with their values at `q`.
enum Geometry<'a> {
    Planar {
        full: &'a FullModel,
        kin: crate::model::Kinematics,
        positions: Vec<[f64; 3]>,
        twist: Vec<f64>,
        q: Vec<f64>,
    },
    /// Positions and pitches with their derivatives along each coordinate
    /// (`Chain3d::geometry_derivatives`).
    Spatial {
        chain: &'a Chain3d,
        positions: Vec<[f64; 3]>,
        d_positions: Vec<Vec<[f64; 3]>>,
        pitch: Vec<f64>,
        d_pitch: Vec<Vec<f64>>,
        q: Vec<f64>,
    },
}

impl<'a> Geometry<'a> {
    fn new(chain: AeroChain<'a>, q: &[f64]) -> Self {
        match chain {
            AeroChain::Planar(full) => {
                let kin = full.kinematics(q);
                Geometry::Planar {
                    full,
                    positions: full.node_positions(&kin),
                    twist: full.shape(q).twist,
                    kin,
                    q: q.to_vec(),
                }
            }
            AeroChain::Spatial(chain) => {
                let (positions, d_positions, pitch, d_pitch) = chain.geometry_derivatives(q);
                Geometry::Spatial {
                    chain,
                    positions,
                    d_positions,
                    pitch,
                    d_pitch,
                    q: q.to_vec(),
                }
            }
        }
    }

    /// The row and value of a geometric output (`tip_x` … `root_lag_moment`); the 3-D outputs
    /// are refused on the planar chain before (`linearize`).
    fn row(&self, output: &Output) -> (DVector<f64>, f64) {
        let n = match self {
            Geometry::Planar { full, .. } => full.n_elements(),
            Geometry::Spatial { chain, .. } => chain.n_elements(),
        };
        let (node, comp) = match output {
            Output::TipX => (n, 0),
            Output::TipY => (n, 1),
            Output::TipZ => (n, 2),
            Output::X(k) => (*k, 0),
            Output::Y(k) => (*k, 1),
            Output::Z(k) => (*k, 2),
            _ => (usize::MAX, 0),
        };
        let twist_node = match output {
            Output::TipTwist => Some(n),
            Output::Twist(k) => Some(*k),
            _ => None,
        };
        match self {
            Geometry::Planar {
                full,
                kin,
                positions,
                twist,
                q,
            } => {
                let nf = full.n_dofs();
                let mut r = DVector::zeros(nf);
                if node != usize::MAX {
                    let j = full.point_jacobian(kin, full.beam().nodes()[node]);
                    r.iter_mut()
                        .zip(j.row(comp).iter())
                        .for_each(|(r, v)| *r = *v);
                    return (r, positions[node][comp]);
                }
                if let Some(k) = twist_node {
                    for j in 0..k {
                        r[n + j] = 1.0;
                    }
                    return (r, twist[k]);
                }
                let k = match output {
                    Output::RootBendingMoment => 0,
                    Output::RootTorque => n,
                    _ => return (r, 0.0),
                };
                r[k] = full.stiffness()[k];
                (r, full.stiffness()[k] * q[k])
            }
            Geometry::Spatial {
                chain,
                positions,
                d_positions,
                pitch,
                d_pitch,
                q,
            } => {
                let nf = q.len();
                if node != usize::MAX {
                    let r = DVector::from_iterator(nf, d_positions.iter().map(|d| d[node][comp]));
                    return (r, positions[node][comp]);
                }
                if let Some(k) = twist_node {
                    // The pitch of the element inboard of node k (none at the clamp).
                    return match k.checked_sub(1) {
                        None => (DVector::zeros(nf), 0.0),
                        Some(e) => (
                            DVector::from_iterator(nf, d_pitch.iter().map(|d| d[e])),
                            pitch[e],
                        ),
                    };
                }
                // The clamp spring's moment K_0 φ_0 in (t, n, c) of the root element: flap about
                // c, lag about n, and the torque nose-up (about −t).
                let (axis, sign) = match output {
                    Output::RootBendingMoment => (2, 1.0),
                    Output::RootLagMoment => (1, 1.0),
                    Output::RootTorque => (0, -1.0),
                    _ => return (DVector::zeros(nf), 0.0),
                };
                let k = &chain.beam().joint_stiffness()[0];
                let mut r = DVector::zeros(nf);
                for col in 0..3 {
                    r[col] = sign * k[axis][col];
                }
                (r.clone(), (0..3).map(|col| r[col] * q[col]).sum())
            }
        }
    }
}

/// The strips' summed forces along `y` and `z` (N) per unit state (`x_*`, momentum basis) and
/// input (`u_*`), and at the equilibrium (`value`).
struct VerticalForce {
    x_y: DVector<f64>,
    x_z: DVector<f64>,
    u_y: DVector<f64>,
    u_z: DVector<f64>,
    value: [f64; 2],
}

/// `Φᵀ v` (model coordinates) of full-model coordinates `v`.
fn project<M: AeroStructure>(aero: &Aeroelastic<M>, v: &[f64]) -> DVector<f64> {
    match aero.structure().basis() {
        None => DVector::from_column_slice(v),
        Some(phi) => phi.transpose() * DVector::from_column_slice(v),
    }
}

#[cfg(test)]
#[path = "linearize_tests.rs"]
mod tests;
