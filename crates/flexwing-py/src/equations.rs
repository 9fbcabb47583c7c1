//! `Equations` (the right-hand side, Jacobian and energies of a full or reduced model's equations
//! of motion at a state, for users' own integrators) and `Stepper` (a run advanced one output
//! interval per call, with the loads set from Python between calls, for coupling to a
//! flight-dynamics or control model).
//!
//! Both own their model and loads and keep one [`EquationsOfMotion`] borrowing them (a
//! self-referential pair, `self_cell`), so its workspaces are allocated once and a call does no
//! set-up. The loads are scaled by factors the caller sets (`scales`), held constant until
//! changed: each load's time function is a constant table of its scale
//! ([`EquationsOfMotion::set_time_functions`]).

use std::time::Instant;

use flexwing::model::{AppliedLoads, FullModel, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{
    integrate, IntegratorSettings, IntegratorStats, Method, OdeSystem,
};
use flexwing::solve::{EquationsOfMotion, TimeFunction};
use flexwing_case::{EquationsSpec, IntegrationSpec, LoadSpec};
use nalgebra::DMatrix;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use self_cell::self_cell;

use crate::arrays::{self, out1, out_matrix};
use crate::errors;
use crate::kwargs::Kwargs;

/// A full or a reduced model.
pub enum AnyModel {
    /// The full model.
    Full(FullModel),
    /// A reduced model.
    Reduced(ReducedModel),
}

impl AnyModel {
    fn full(&self) -> &FullModel {
        match self {
            AnyModel::Full(m) => m,
            AnyModel::Reduced(r) => r.full_model(),
        }
    }
    fn n_dofs(&self) -> usize {
        match self {
            AnyModel::Full(m) => m.n_dofs(),
            AnyModel::Reduced(r) => r.n_dofs(),
        }
    }
    fn full_coordinates(&self, x: &[f64]) -> Vec<f64> {
        match self {
            AnyModel::Full(_) => x.to_vec(),
            AnyModel::Reduced(r) => r.full_coordinates(x),
        }
    }
}

/// What the equations borrow.
pub struct Owner {
    model: AnyModel,
    loads: AppliedLoads,
}

/// The equations of the full or a reduced model (built once per object: the size of the
/// full model's variant does not matter).
#[allow(clippy::large_enum_variant)]
pub enum Eom<'a> {
    /// Of the full model.
    Full(EquationsOfMotion<'a, FullModel>),
    /// Of a reduced model.
    Reduced(EquationsOfMotion<'a, ReducedModel>),
}

self_cell!(
    /// A model, its loads, and its equations of motion borrowing them.
    pub struct OwnedEom {
        owner: Owner,
        #[covariant]
        dependent: Eom,
    }
);

/// `$body` with `$e` bound to the equations of whichever model.
macro_rules! with_eom {
    ($cell:expr, |$owner:ident, $e:ident| $body:expr) => {
        $cell.with_dependent_mut(|$owner, dependent| match dependent {
            Eom::Full($e) => $body,
            Eom::Reduced($e) => $body,
        })
    };
}

/// A load factor held constant at every time.
fn held(scale: f64) -> TimeFunction {
    TimeFunction::Table {
        t: vec![0.0, 1.0],
        value: vec![scale, scale],
    }
}

/// The loads of a list of `[[loads]]` tables (dicts with the case file's keys).
fn loads_of(
    py: Python<'_>,
    model: &FullModel,
    loads: Option<&Bound<'_, PyAny>>,
) -> PyResult<AppliedLoads> {
    let Some(loads) = loads else {
        return Ok(AppliedLoads::none());
    };
    let specs: Vec<LoadSpec> = crate::values::read_or_raise(loads, "loads", false)?;
    for (i, s) in specs.iter().enumerate() {
        for (key, given) in [("time", s.time.is_some()), ("active", s.active.is_some())] {
            if given {
                return Err(errors::input(
                    py,
                    &format!("loads[{i}].{key}"),
                    "the model level takes the load factors from the caller (the scales \
                     argument), not from a time history",
                ));
            }
        }
    }
    errors::guard(py, || {
        let loads = flexwing_case::library_loads(&specs, model.beam())
            .map_err(|e| errors::library_input(py, &e))?;
        model
            .apply(&loads, "loads")
            .map_err(|e| errors::library_input(py, &e))
    })
}

/// The keyword arguments of `kw` that are keys of the case crate's table `T` (not `None`), read
/// as `T`: the keys, defaults and checks of the case file's `[dynamic]`.
fn spec<T: serde::de::DeserializeOwned>(py: Python<'_>, kw: &Kwargs<'_>) -> PyResult<T> {
    let given = PyDict::new(py);
    for key in flexwing_case::keys::<T>() {
        if let Some(v) = kw.get(key)? {
            given.set_item(key, v)?;
        }
    }
    crate::values::read_or_raise(given.as_any(), "", false)
}

/// The keywords a function takes: its own, then the keys of the case crate's tables `tables`.
fn keywords(own: &[&'static str], tables: &[&'static [&'static str]]) -> Vec<&'static str> {
    own.iter()
        .copied()
        .chain(tables.iter().flat_map(|t| t.iter().copied()))
        .collect()
}

/// The equations of `model` under `loads`, with the options of `kw` (`gyroscopic`,
/// `gyroscopic_step`, `damping`, `scales`).
fn owned_eom(
    py: Python<'_>,
    model: AnyModel,
    loads: Option<&Bound<'_, PyAny>>,
    kw: &Kwargs<'_>,
) -> PyResult<(OwnedEom, Vec<f64>)> {
    let applied = loads_of(py, model.full(), loads)?;
    let n_loads = applied.n_loads();
    let scales = match kw.get("scales")? {
        Some(s) => arrays::vector(&s, "scales", Some(n_loads))?,
        None => vec![1.0; n_loads],
    };
    let options: EquationsSpec = spec(py, kw)?;
    let library = |e: flexwing::InputError| errors::library_input(py, &e);
    let gyroscopic = options.to_gyroscopic("").map_err(library)?;
    gyroscopic.validate("gyroscopic_step").map_err(library)?;
    let damping = options.to_damping("").map_err(library)?;
    damping
        .validate("damping", model.n_dofs())
        .map_err(|e| errors::library_input(py, &e))?;
    let functions: Vec<TimeFunction> = scales.iter().map(|&s| held(s)).collect();
    let owner = Owner {
        model,
        loads: applied,
    };
    let cell = errors::guard(py, || {
        OwnedEom::try_new(owner, |o| match &o.model {
            AnyModel::Full(m) => {
                EquationsOfMotion::new(m, &o.loads, functions, gyroscopic, &damping).map(Eom::Full)
            }
            AnyModel::Reduced(r) => {
                let damping = r.project_damping(&damping);
                EquationsOfMotion::new(r, &o.loads, functions, gyroscopic, &damping)
                    .map(Eom::Reduced)
            }
        })
        .map_err(|e| errors::library_input(py, &e))
    })?;
    Ok((cell, scales))
}

/// Reject keyword arguments other than `allowed` (a fixed signature's own keywords are parsed
/// by it; this catches the rest).
fn no_other(
    py: Python<'_>,
    kwargs: Option<&Bound<'_, PyDict>>,
    allowed: &[&str],
    function: &str,
) -> PyResult<()> {
    Kwargs::new(py, kwargs, allowed, function).map(|_| ())
}

/// The equations of motion of a full or reduced model in Hamiltonian form, state
/// ``y = (x, p)`` (coordinates, rad or modal amplitudes; momenta), ``2 n_dofs`` values:
/// ``ẋ = M(x)⁻¹ p``, ``ṗ = −K x + γ(x, ẋ) − C ẋ + Σ_k scales[k] Q_k(x)``.
///
/// Build it with ``model.equations(loads, gyroscopic=…, damping=…, scales=…)``. ``rhs(t, y)``
/// and ``jacobian(t, y)`` have the signature of ``scipy.integrate.solve_ivp``'s ``fun`` and
/// ``jac``. One object per thread (its scratch buffers are reused between calls).
#[pyclass(module = "flexwing", name = "Equations")]
pub struct PyEquations {
    cell: OwnedEom,
    scales: Vec<f64>,
    n: usize,
    jac: DMatrix<f64>,
    dy: Vec<f64>,
}

impl PyEquations {
    /// Build from a model and the keyword arguments of `model.equations`.
    pub fn build(
        py: Python<'_>,
        model: AnyModel,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let allowed = keywords(&["scales"], &[flexwing_case::keys::<EquationsSpec>()]);
        let kw = Kwargs::new(py, kwargs, &allowed, "equations")?;
        let n = model.n_dofs();
        let (cell, scales) = owned_eom(py, model, loads, &kw)?;
        Ok(Self {
            cell,
            scales,
            n,
            jac: DMatrix::zeros(2 * n, 2 * n),
            dy: vec![0.0; 2 * n],
        })
    }

    fn state_arg(&self, y: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        arrays::vector(y, "y", Some(2 * self.n))
    }
}

#[pymethods]
impl PyEquations {
    /// Number of coordinates ``x`` (the state has twice as many values).
    #[getter]
    fn n_dofs(&self) -> usize {
        self.n
    }

    /// Number of loads.
    #[getter]
    fn n_loads(&self) -> usize {
        self.scales.len()
    }

    /// The load factors (one per load), held at every time until changed.
    #[getter]
    fn get_scales<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.scales.clone())
    }

    #[setter]
    fn set_scales(&mut self, py: Python<'_>, scales: &Bound<'_, PyAny>) -> PyResult<()> {
        let scales = arrays::vector(scales, "scales", Some(self.scales.len()))?;
        let functions = scales.iter().map(|&s| held(s)).collect();
        errors::guard(py, || {
            with_eom!(self.cell, |_o, e| e.set_time_functions(functions, "scales"))
                .map_err(|e| errors::library_input(py, &e))
        })?;
        self.scales = scales;
        Ok(())
    }

    /// The state ``y = (x, p)`` of coordinates ``x`` and velocities ``xdot``.
    fn state<'py>(
        &mut self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
        xdot: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let x = arrays::vector(x, "x", Some(self.n))?;
        let xdot = arrays::vector(xdot, "xdot", Some(self.n))?;
        let y = errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.state(&x, &xdot))))?;
        Ok(out1(py, y))
    }

    /// ``dy/dt`` at time ``t`` (s) and state ``y``: ``(ẋ, ṗ)``.
    #[pyo3(signature = (t, y, **kwargs))]
    fn rhs<'py>(
        &mut self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        no_other(py, kwargs, &["t", "y"], "rhs")?;
        let t = arrays::number(t, "t")?;
        let y = self.state_arg(y)?;
        let dy = &mut self.dy;
        errors::guard(py, || {
            with_eom!(self.cell, |_o, e| e.rhs(t, &y, dy));
            Ok(())
        })?;
        Ok(out1(py, self.dy.clone()))
    }

    /// The Jacobian ``∂(dy/dt)/∂y`` at time ``t`` (s) and state ``y``, ``(2 n_dofs, 2 n_dofs)``.
    #[pyo3(signature = (t, y, **kwargs))]
    fn jacobian<'py>(
        &mut self,
        py: Python<'py>,
        t: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        no_other(py, kwargs, &["t", "y"], "jacobian")?;
        let t = arrays::number(t, "t")?;
        let y = self.state_arg(y)?;
        let jac = &mut self.jac;
        errors::guard(py, || {
            with_eom!(self.cell, |_o, e| e.jacobian(t, &y, jac));
            Ok(())
        })?;
        Ok(out_matrix(py, &self.jac))
    }

    /// Energies of the state ``y``: ``(kinetic, strain)`` (J).
    fn energies(&mut self, py: Python<'_>, y: &Bound<'_, PyAny>) -> PyResult<(f64, f64)> {
        let y = self.state_arg(y)?;
        errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.energies(&y))))
    }

    /// Velocities ``ẋ = M(x)⁻¹ p`` of the state ``y``.
    fn velocities<'py>(
        &mut self,
        py: Python<'py>,
        y: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let y = self.state_arg(y)?;
        let v = errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.velocities(&y))))?;
        Ok(out1(py, v))
    }

    /// Joint rotations ``q`` (rad) of the full model for coordinates ``x``.
    fn full_coordinates<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let x = arrays::vector(x, "x", Some(self.n))?;
        let q = errors::guard(py, || {
            Ok(self.cell.borrow_owner().model.full_coordinates(&x))
        })?;
        Ok(out1(py, q))
    }

    fn __repr__(&self) -> String {
        format!(
            "Equations(n_dofs={}, n_loads={})",
            self.n,
            self.scales.len()
        )
    }
}

/// How the load factors go over an interval of `Stepper.step`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Hold {
    /// Linear from the previous call's factors to the new ones (first-order hold): the forces
    /// stay continuous in time, so no step of the load rings the model's highest modes.
    Linear,
    /// The new factors from the start of the interval (zero-order hold): a jump of the forces
    /// at each call, as a sampled controller's output.
    Zero,
}

/// A dynamic run advanced one output interval per call, with the load factors set from Python
/// between calls: for coupling the beam to a flight-dynamics or control model.
///
/// Build it with ``model.stepper(loads, x0=…, xdot0=…, t0=0, integrator=…, rtol=…, atol=…, …,
/// gyroscopic=…, damping=…, scales=…, hold="linear")`` (the integrator settings and their
/// defaults are those of the case file's ``[dynamic]``); then
/// ``stepper.step(dt, scales)``. ``hold="linear"`` (default) ramps the factors from the previous
/// call's to the new ones over the interval (continuous forces); ``hold="zero"`` switches them at
/// the start of the interval (a force step at every call, which rings the highest modes and
/// costs the integrator many small steps).
/// Each call restarts the integrator at the current state (its first step is chosen anew), and
/// runs detached from the interpreter.
#[pyclass(module = "flexwing", name = "Stepper")]
pub struct PyStepper {
    cell: OwnedEom,
    scales: Vec<f64>,
    n: usize,
    method: Method,
    settings: IntegratorSettings,
    t: f64,
    y: Vec<f64>,
    stats: IntegratorStats,
    calls: usize,
    rust_time_s: f64,
    hold: Hold,
}

impl PyStepper {
    /// Build from a model and the keyword arguments of `model.stepper`.
    pub fn build(
        py: Python<'_>,
        model: AnyModel,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let allowed = keywords(
            &["scales", "x0", "xdot0", "t0", "hold"],
            &[
                flexwing_case::keys::<EquationsSpec>(),
                flexwing_case::keys::<IntegrationSpec>(),
            ],
        );
        let kw = Kwargs::new(py, kwargs, &allowed, "stepper")?;
        let n = model.n_dofs();
        let integration: IntegrationSpec = spec(py, &kw)?;
        let (method, settings) = integration
            .to_settings("")
            .map_err(|e| errors::library_input(py, &e))?;
        settings
            .validate("")
            .map_err(|e| errors::library_input(py, &e))?;
        let x0 = match kw.get("x0")? {
            Some(x) => arrays::vector(&x, "x0", Some(n))?,
            None => vec![0.0; n],
        };
        let xdot0 = match kw.get("xdot0")? {
            Some(x) => arrays::vector(&x, "xdot0", Some(n))?,
            None => vec![0.0; n],
        };
        let hold = match kw.get("hold")? {
            None => Hold::Linear,
            Some(h) => match arrays::text(&h, "hold")?.as_str() {
                "linear" => Hold::Linear,
                "zero" => Hold::Zero,
                other => {
                    return Err(errors::input(
                        py,
                        "hold",
                        &format!("unknown value {other:?}; expected \"linear\" or \"zero\""),
                    ))
                }
            },
        };
        let t = match kw.get("t0")? {
            Some(t) => arrays::number(&t, "t0")?,
            None => 0.0,
        };
        let (mut cell, scales) = owned_eom(py, model, loads, &kw)?;
        let y = errors::guard(py, || Ok(with_eom!(cell, |_o, e| e.state(&x0, &xdot0))))?;
        Ok(Self {
            cell,
            scales,
            n,
            method,
            settings,
            t,
            y,
            stats: IntegratorStats::default(),
            calls: 0,
            rust_time_s: 0.0,
            hold,
        })
    }
}

#[pymethods]
impl PyStepper {
    /// Advance by ``dt`` (s) to the load factors ``scales`` (one per load; default: those of
    /// the previous call, held). With ``hold="linear"`` (the default) the factors go linearly
    /// from the previous ones to these over the interval; with ``hold="zero"`` they take these
    /// values at once. Returns the new time (s).
    ///
    /// Raises ``SolverError`` if the integrator stops inside the interval (``stop["time"]``
    /// says where); the state then stays at the start of the interval.
    #[pyo3(signature = (dt, scales = None, **kwargs))]
    fn step(
        &mut self,
        py: Python<'_>,
        dt: &Bound<'_, PyAny>,
        scales: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<f64> {
        no_other(py, kwargs, &["dt", "scales"], "step")?;
        let dt = arrays::number(dt, "dt")?;
        if !(dt > 0.0) {
            return Err(errors::input(
                py,
                "dt",
                &format!("must be positive, got {dt}"),
            ));
        }
        let (t0, t1) = (self.t, self.t + dt);
        let mut load_time_s = 0.0;
        if let Some(s) = scales {
            let s = arrays::vector(s, "scales", Some(self.scales.len()))?;
            let start = Instant::now();
            let functions = match self.hold {
                Hold::Linear => self
                    .scales
                    .iter()
                    .zip(&s)
                    .map(|(&a, &b)| TimeFunction::Table {
                        t: vec![t0, t1],
                        value: vec![a, b],
                    })
                    .collect(),
                Hold::Zero => s.iter().map(|&v| held(v)).collect(),
            };
            errors::guard(py, || {
                with_eom!(self.cell, |_o, e| e.set_time_functions(functions, "scales"))
                    .map_err(|e| errors::library_input(py, &e))
            })?;
            load_time_s = start.elapsed().as_secs_f64();
            self.scales = s;
        }
        let method = self.method;
        let settings = &self.settings;
        let y0 = &self.y;
        let cell = &mut self.cell;
        let (result, elapsed) = errors::detached(py, || {
            let start = Instant::now();
            let result = with_eom!(cell, |_o, e| integrate(
                method,
                settings,
                e,
                t0,
                y0,
                &[t0, t1],
                &mut |_| {}
            ));
            (result, start.elapsed().as_secs_f64())
        })?;
        self.calls += 1;
        self.rust_time_s += load_time_s + elapsed;
        match result {
            Ok((mut trajectory, stats)) => {
                self.stats += stats;
                if let Some(y) = trajectory.y.pop() {
                    self.y = y;
                }
                self.t = t1;
                Ok(t1)
            }
            Err(failure) => {
                self.stats += failure.stats;
                let message = failure.error.to_string();
                let stop = flexwing::analysis::Stop::Integration(failure.error);
                let stop = crate::convert::status::described(py, &stop)?;
                Err(errors::solver(
                    py,
                    &message,
                    None,
                    Some(stop.into_any().unbind()),
                    None,
                ))
            }
        }
    }

    /// Set the state from coordinates ``x`` and velocities ``xdot`` (and the time ``t``, s).
    #[pyo3(signature = (x, xdot, t = None))]
    fn set_state(
        &mut self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        xdot: &Bound<'_, PyAny>,
        t: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let x = arrays::vector(x, "x", Some(self.n))?;
        let xdot = arrays::vector(xdot, "xdot", Some(self.n))?;
        let t = t.map(|t| arrays::number(t, "t")).transpose()?;
        self.y = errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.state(&x, &xdot))))?;
        if let Some(t) = t {
            self.t = t;
        }
        Ok(())
    }

    /// Time (s).
    #[getter]
    fn t(&self) -> f64 {
        self.t
    }
    /// Number of coordinates.
    #[getter]
    fn n_dofs(&self) -> usize {
        self.n
    }
    /// The load factors in force.
    #[getter]
    fn scales<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.scales.clone())
    }
    /// The state ``y = (x, p)``.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.y.clone())
    }
    /// Coordinates ``x`` (rad, or modal amplitudes of a reduced model).
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.y[..self.n].to_vec())
    }
    /// Velocities ``ẋ``.
    #[getter]
    fn xdot<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let y = &self.y;
        let v = errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.velocities(y))))?;
        Ok(out1(py, v))
    }
    /// Joint rotations ``q`` of the full model (rad).
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let q = errors::guard(py, || {
            Ok(self
                .cell
                .borrow_owner()
                .model
                .full_coordinates(&self.y[..self.n]))
        })?;
        Ok(out1(py, q))
    }
    /// Tip position and twist ``(x, y, twist)`` (m, m, rad).
    #[getter]
    fn tip(&self, py: Python<'_>) -> PyResult<(f64, f64, f64)> {
        errors::guard(py, || {
            let model = &self.cell.borrow_owner().model;
            let q = model.full_coordinates(&self.y[..self.n]);
            Ok(model.full().shape(&q).tip())
        })
    }
    /// Energies ``(kinetic, strain)`` (J).
    fn energies(&mut self, py: Python<'_>) -> PyResult<(f64, f64)> {
        let y = &self.y;
        errors::guard(py, || Ok(with_eom!(self.cell, |_o, e| e.energies(y))))
    }
    /// The deformed shape: a dict of node arrays ``x``, ``y`` (m) and ``twist`` (rad).
    fn shape<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let shape = errors::guard(py, || {
            let model = &self.cell.borrow_owner().model;
            let q = model.full_coordinates(&self.y[..self.n]);
            Ok(model.full().shape(&q))
        })?;
        let d = PyDict::new(py);
        d.set_item("x", out1(py, shape.x))?;
        d.set_item("y", out1(py, shape.y))?;
        d.set_item("twist", out1(py, shape.twist))?;
        Ok(d)
    }
    /// Counters summed over the calls: the integrator's (``steps``, ``rejected_steps``,
    /// ``newton_failures``, ``rhs_evaluations``, ``jacobian_evaluations``, ``factorizations``,
    /// ``newton_iterations``: those of ``DynamicRun.stats``), ``calls``, and ``rust_time_s``, the
    /// wall time spent in the library (s: setting the load factors and integrating): a call's
    /// cost beyond it is the binding's overhead.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = crate::convert::dynamics::integrator_stats(py, &self.stats)?;
        d.set_item("calls", self.calls)?;
        d.set_item("rust_time_s", self.rust_time_s)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Stepper(t={}, n_dofs={}, integrator={:?})",
            self.t,
            self.n,
            self.method.name()
        )
    }
}
