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

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::ThreadId;
use std::time::Instant;

use pyo3::sync::MutexExt;

use flexwing::model::{AppliedLoads, FullModel, ReducedModel, StructuralModel};
use flexwing::solve::integrate::{
    integrate, IntegratorSettings, IntegratorStats, Method, OdeSystem,
};
use flexwing::solve::{EquationsOfMotion, TimeFunction};
use flexwing::text::short;
use flexwing_case::{EquationsSpec, IntegrationSpec, LoadSpec};
use nalgebra::DMatrix;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use self_cell::self_cell;

use crate::arrays::{self, finite1, finite_matrix, out1};
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
            AnyModel::Reduced(r) => r.full(),
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
/// ``jac``. One object per thread (its scratch buffers are reused between calls). A state
/// beyond the range the model can evaluate (a non-finite output) raises ``InputError`` naming
/// ``y``.
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

    /// The object, mutably: its arguments are converted before (the caller's `__array__` may
    /// run Python code), so only a call from inside the library could find it borrowed.
    fn this<'py>(slf: &Bound<'py, Self>) -> PyResult<PyRefMut<'py, Self>> {
        slf.try_borrow_mut().map_err(|_| {
            errors::reentrancy(
                slf.py(),
                "Equations",
                "is in use by another call (one object per thread)",
            )
        })
    }

    /// The state argument `y` (`2 n_dofs` values).
    fn state_arg(slf: &Bound<'_, Self>, y: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        let n = slf.borrow().n;
        arrays::vector(y, "y", Some(2 * n))
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
    fn set_scales(slf: &Bound<'_, Self>, scales: &Bound<'_, PyAny>) -> PyResult<()> {
        let py = slf.py();
        errors::guard(py, || {
            let count = slf.borrow().scales.len();
            let scales = arrays::vector(scales, "scales", Some(count))?;
            let functions = scales.iter().map(|&s| held(s)).collect();
            let mut this = Self::this(slf)?;
            with_eom!(this.cell, |_o, e| e.set_time_functions(functions, "scales"))
                .map_err(|e| errors::library_input(py, &e))?;
            this.scales = scales;
            Ok(())
        })
    }

    /// The state ``y = (x, p)`` of coordinates ``x`` and velocities ``xdot``.
    fn state<'py>(
        slf: &Bound<'py, Self>,
        x: &Bound<'py, PyAny>,
        xdot: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let py = slf.py();
        errors::guard(py, || {
            let n = slf.borrow().n;
            let x = arrays::vector(x, "x", Some(n))?;
            let xdot = arrays::vector(xdot, "xdot", Some(n))?;
            let mut this = Self::this(slf)?;
            let y = with_eom!(this.cell, |_o, e| e.state(&x, &xdot));
            finite1(py, y, "y", "xdot")
        })
    }

    /// ``dy/dt`` at time ``t`` (s) and state ``y``: ``(ẋ, ṗ)``.
    #[pyo3(signature = (t, y, **kwargs))]
    fn rhs<'py>(
        slf: &Bound<'py, Self>,
        t: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let py = slf.py();
        errors::guard(py, || {
            no_other(py, kwargs, &["t", "y"], "rhs")?;
            let t = arrays::number(t, "t")?;
            let y = Self::state_arg(slf, y)?;
            let mut this = Self::this(slf)?;
            let this = &mut *this;
            let dy = &mut this.dy;
            with_eom!(this.cell, |_o, e| e.rhs(t, &y, dy));
            finite1(py, this.dy.clone(), "dy", "y")
        })
    }

    /// The Jacobian ``∂(dy/dt)/∂y`` at time ``t`` (s) and state ``y``, ``(2 n_dofs, 2 n_dofs)``.
    #[pyo3(signature = (t, y, **kwargs))]
    fn jacobian<'py>(
        slf: &Bound<'py, Self>,
        t: &Bound<'py, PyAny>,
        y: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        let py = slf.py();
        errors::guard(py, || {
            no_other(py, kwargs, &["t", "y"], "jacobian")?;
            let t = arrays::number(t, "t")?;
            let y = Self::state_arg(slf, y)?;
            let mut this = Self::this(slf)?;
            let this = &mut *this;
            let jac = &mut this.jac;
            with_eom!(this.cell, |_o, e| e.jacobian(t, &y, jac));
            finite_matrix(py, &this.jac, "jacobian", "y")
        })
    }

    /// Energies of the state ``y``: ``(kinetic, strain)`` (J).
    fn energies(slf: &Bound<'_, Self>, y: &Bound<'_, PyAny>) -> PyResult<(f64, f64)> {
        let py = slf.py();
        errors::guard(py, || {
            let y = Self::state_arg(slf, y)?;
            let mut this = Self::this(slf)?;
            let (k, v) = with_eom!(this.cell, |_o, e| e.energies(&y));
            arrays::check_finite(py, &[k, v], "energies", "y")?;
            Ok((k, v))
        })
    }

    /// Velocities ``ẋ = M(x)⁻¹ p`` of the state ``y``.
    fn velocities<'py>(
        slf: &Bound<'py, Self>,
        y: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let py = slf.py();
        errors::guard(py, || {
            let y = Self::state_arg(slf, y)?;
            let mut this = Self::this(slf)?;
            let v = with_eom!(this.cell, |_o, e| e.velocities(&y));
            finite1(py, v, "xdot", "y")
        })
    }

    /// Joint rotations ``q`` (rad) of the full model for coordinates ``x``.
    fn full_coordinates<'py>(
        slf: &Bound<'py, Self>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        let py = slf.py();
        errors::guard(py, || {
            let n = slf.borrow().n;
            let x = arrays::vector(x, "x", Some(n))?;
            let q = slf.borrow().cell.borrow_owner().model.full_coordinates(&x);
            finite1(py, q, "q", "x")
        })
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

/// What a step works on: the equations (with their load factors' time functions) and the
/// integrator. Locked for the whole of a step.
struct Core {
    cell: OwnedEom,
    /// The time functions in force (restored when a step fails).
    functions: Vec<TimeFunction>,
    settings: IntegratorSettings,
}

/// The stepper's state as the caller sees it: changed only when a step succeeds (or by
/// `set_state`), read at any time from any thread.
#[derive(Clone)]
struct State {
    t: f64,
    y: Vec<f64>,
    scales: Vec<f64>,
    stats: IntegratorStats,
    calls: usize,
    rust_time_s: f64,
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
/// runs detached from the interpreter; a step that fails or is interrupted leaves the stepper
/// as it was before the call (time, state, load factors). The state can be read from any thread
/// while a step runs (it is the state before the step); steps from several threads run one
/// after the other.
#[pyclass(module = "flexwing", name = "Stepper", frozen)]
pub struct PyStepper {
    core: Mutex<Core>,
    /// The thread running a step (holding `core`), to refuse a re-entrant call from it.
    holder: Mutex<Option<ThreadId>>,
    state: Mutex<State>,
    /// The model, for the coordinates and shapes of the state (without the equations).
    model: AnyModel,
    n: usize,
    method: Method,
    hold: Hold,
}

/// `m` locked; a poisoned lock (a panic while it was held, caught at the boundary) is taken as
/// it is: every step works on a copy of the state and commits it only when it succeeds.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
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
        let copy = match &model {
            AnyModel::Full(m) => AnyModel::Full(m.clone()),
            AnyModel::Reduced(r) => AnyModel::Reduced(r.clone()),
        };
        let (mut cell, scales) = owned_eom(py, model, loads, &kw)?;
        let y = with_eom!(cell, |_o, e| e.state(&x0, &xdot0));
        arrays::check_finite(py, &y, "y", "xdot0")?;
        let functions = scales.iter().map(|&s| held(s)).collect();
        Ok(Self {
            core: Mutex::new(Core {
                cell,
                functions,
                settings,
            }),
            holder: Mutex::new(None),
            state: Mutex::new(State {
                t,
                y,
                scales,
                stats: IntegratorStats::default(),
                calls: 0,
                rust_time_s: 0.0,
            }),
            model: copy,
            n,
            method,
            hold,
        })
    }

    /// The state, copied (the lock is held only for the copy).
    fn snapshot(&self) -> State {
        lock(&self.state).clone()
    }

    /// Run `f` on the core, locked: waits (detached) for a step of another thread; a call
    /// from inside this thread's own step (a signal handler) is a `ReentrancyError`.
    fn with_core<T>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Core) -> PyResult<T>,
    ) -> PyResult<T> {
        let me = std::thread::current().id();
        if *lock(&self.holder) == Some(me) {
            return Err(errors::reentrancy(
                py,
                "Stepper",
                "called from inside its own step on this thread (a signal handler or callback \
                 run during step()): read t, y, x, scales or stats there, which do not wait",
            ));
        }
        let mut core = self
            .core
            .lock_py_attached(py)
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        *lock(&self.holder) = Some(me);
        let result = f(&mut core);
        *lock(&self.holder) = None;
        result
    }

    /// The load factors' time functions of a step from `t0` to `t1` towards `scales`, from
    /// `previous`.
    fn functions(&self, previous: &[f64], scales: &[f64], t0: f64, t1: f64) -> Vec<TimeFunction> {
        match self.hold {
            Hold::Linear => previous
                .iter()
                .zip(scales)
                .map(|(&a, &b)| TimeFunction::Table {
                    t: vec![t0, t1],
                    value: vec![a, b],
                })
                .collect(),
            Hold::Zero => scales.iter().map(|&v| held(v)).collect(),
        }
    }
}

/// The end of an interval of `dt` from `t0`, or the `InputError` of `dt` if the interval
/// is not what was asked for at the time's resolution (a step of 1 ms at t = 1e20 s).
fn interval_end(py: Python<'_>, t0: f64, dt: f64) -> PyResult<f64> {
    let t1 = t0 + dt;
    // The interval integrated is [t0, t1] exactly as the two numbers hold it; rounded to the
    // time's resolution it differs from dt. Beyond 0.1 % it is not the step asked for (at
    // t = 1e9 s a 1 ms step is taken as 1.00005 ms, kept; a 0.1 µs step is taken as 0 or
    // 0.12 µs, refused).
    let taken = t1 - t0;
    if !t1.is_finite() || !(taken > 0.0) || ((taken - dt) / dt).abs() > 1e-3 {
        return Err(errors::input(
            py,
            "dt",
            &format!(
                "a step of {} s from t = {} s is below the resolution of the time there (the \
                 interval taken would be {} s): restart the time lower (set_state(x, xdot, t))",
                short(dt),
                short(t0),
                short(taken)
            ),
        ));
    }
    Ok(t1)
}

#[pymethods]
impl PyStepper {
    /// Advance by ``dt`` (s) to the load factors ``scales`` (one per load; default: those of
    /// the previous call, held). With ``hold="linear"`` (the default) the factors go linearly
    /// from the previous ones to these over the interval; with ``hold="zero"`` they take these
    /// values at once. Returns the new time (s).
    ///
    /// Raises ``SolverError`` if the integrator stops inside the interval
    /// (``stop["error"]["time"]`` says where); ``InputError`` naming ``dt`` for an interval below the time's resolution.
    /// Ctrl-C stops the step after the integrator's current step and raises
    /// ``KeyboardInterrupt``. After any of these the stepper is as before the call: its time,
    /// state and load factors (a retry ramps from the same factors).
    #[pyo3(signature = (dt, scales = None, **kwargs))]
    fn step(
        &self,
        py: Python<'_>,
        dt: &Bound<'_, PyAny>,
        scales: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<f64> {
        errors::guard(py, || {
            no_other(py, kwargs, &["dt", "scales"], "step")?;
            let dt = arrays::number(dt, "dt")?;
            if !(dt > 0.0) {
                return Err(errors::input(
                    py,
                    "dt",
                    &format!("must be positive, got {dt}"),
                ));
            }
            let n_loads = lock(&self.state).scales.len();
            let new_scales = scales
                .map(|s| arrays::vector(s, "scales", Some(n_loads)))
                .transpose()?;
            let _nesting = crate::progress::Nesting::enter(py)?;
            let mut signals = crate::progress::Signals::new(py)?;
            self.with_core(py, |core| {
                self.step_locked(py, core, dt, new_scales, &mut signals)
            })
        })
    }

    /// Set the state from coordinates ``x`` and velocities ``xdot`` (and the time ``t``, s).
    #[pyo3(signature = (x, xdot, t = None))]
    fn set_state(
        &self,
        py: Python<'_>,
        x: &Bound<'_, PyAny>,
        xdot: &Bound<'_, PyAny>,
        t: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        errors::guard(py, || {
            let x = arrays::vector(x, "x", Some(self.n))?;
            let xdot = arrays::vector(xdot, "xdot", Some(self.n))?;
            let t = t.map(|t| arrays::number(t, "t")).transpose()?;
            let y = self.with_core(py, |core| {
                Ok(with_eom!(core.cell, |_o, e| e.state(&x, &xdot)))
            })?;
            arrays::check_finite(py, &y, "y", "xdot")?;
            let mut state = lock(&self.state);
            state.y = y;
            if let Some(t) = t {
                state.t = t;
            }
            Ok(())
        })
    }

    /// Time (s).
    #[getter]
    fn t(&self) -> f64 {
        lock(&self.state).t
    }
    /// Number of coordinates.
    #[getter]
    fn n_dofs(&self) -> usize {
        self.n
    }
    /// The load factors in force.
    #[getter]
    fn scales<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.snapshot().scales)
    }
    /// The state ``y = (x, p)``.
    #[getter]
    fn y<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.snapshot().y)
    }
    /// Coordinates ``x`` (rad, or modal amplitudes of a reduced model).
    #[getter]
    fn x<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        let mut y = self.snapshot().y;
        y.truncate(self.n);
        out1(py, y)
    }
    /// Velocities ``ẋ`` (waits for a step running in another thread).
    #[getter]
    fn xdot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        errors::guard(py, || {
            let v = self.with_core(py, |core| {
                let y = self.snapshot().y;
                Ok(with_eom!(core.cell, |_o, e| e.velocities(&y)))
            })?;
            finite1(py, v, "xdot", "y")
        })
    }
    /// Joint rotations ``q`` of the full model (rad).
    #[getter]
    fn q<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        errors::guard(py, || {
            let y = self.snapshot().y;
            finite1(py, self.model.full_coordinates(&y[..self.n]), "q", "y")
        })
    }
    /// Tip position and twist ``(x, y, twist)`` (m, m, rad).
    #[getter]
    fn tip(&self, py: Python<'_>) -> PyResult<(f64, f64, f64)> {
        errors::guard(py, || {
            let y = self.snapshot().y;
            let q = self.model.full_coordinates(&y[..self.n]);
            let tip = self.model.full().shape(&q).tip();
            arrays::check_finite(py, &[tip.0, tip.1, tip.2], "tip", "y")?;
            Ok(tip)
        })
    }
    /// Energies ``(kinetic, strain)`` (J) (waits for a step running in another thread).
    fn energies(&self, py: Python<'_>) -> PyResult<(f64, f64)> {
        errors::guard(py, || {
            let (k, v) = self.with_core(py, |core| {
                let y = self.snapshot().y;
                Ok(with_eom!(core.cell, |_o, e| e.energies(&y)))
            })?;
            arrays::check_finite(py, &[k, v], "energies", "y")?;
            Ok((k, v))
        })
    }
    /// The deformed shape: a dict of node arrays ``x``, ``y`` (m) and ``twist`` (rad).
    fn shape<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let y = self.snapshot().y;
            let q = self.model.full_coordinates(&y[..self.n]);
            let shape = self.model.full().shape(&q);
            let d = PyDict::new(py);
            d.set_item("x", finite1(py, shape.x, "x", "y")?)?;
            d.set_item("y", finite1(py, shape.y, "y", "y")?)?;
            d.set_item("twist", finite1(py, shape.twist, "twist", "y")?)?;
            Ok(d)
        })
    }
    /// Counters summed over the calls: the integrator's (``steps``, ``rejected_steps``,
    /// ``newton_failures``, ``rhs_evaluations``, ``jacobian_evaluations``, ``factorizations``,
    /// ``newton_iterations``: those of ``DynamicRun.stats``), ``calls``, and ``rust_time_s``, the
    /// wall time spent in the library (s: setting the load factors and integrating): a call's
    /// cost beyond it is the binding's overhead.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let state = self.snapshot();
            let d = crate::convert::dynamics::integrator_stats(py, &state.stats)?;
            d.set_item("calls", state.calls)?;
            d.set_item("rust_time_s", state.rust_time_s)?;
            Ok(d)
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "Stepper(t={}, n_dofs={}, integrator={:?})",
            lock(&self.state).t,
            self.n,
            self.method.name()
        )
    }
}

impl PyStepper {
    /// A step, the core locked: set the load factors, integrate detached (signals polled after
    /// every integrator step through the equations' halt flag), then commit the new state — or,
    /// on any failure, put the load factors back and leave the state as it was.
    fn step_locked(
        &self,
        py: Python<'_>,
        core: &mut Core,
        dt: f64,
        new_scales: Option<Vec<f64>>,
        signals: &mut crate::progress::Signals,
    ) -> PyResult<f64> {
        let State {
            t: t0,
            y: y0,
            scales: previous,
            ..
        } = self.snapshot();
        let t1 = interval_end(py, t0, dt)?;
        let start = Instant::now();
        let scales = new_scales.unwrap_or_else(|| previous.clone());
        let before = core.functions.clone();
        // Unchanged factors keep the functions in force (the previous ramp, held at its end).
        let functions = if scales == previous {
            before.clone()
        } else {
            self.functions(&previous, &scales, t0, t1)
        };
        with_eom!(core.cell, |_o, e| e
            .set_time_functions(functions.clone(), "scales"))
        .map_err(|e| errors::library_input(py, &e))?;
        let halt = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&halt);
        let method = self.method;
        let settings = &core.settings;
        let cell = &mut core.cell;
        let result = errors::detached(py, || {
            with_eom!(cell, |_o, e| {
                e.set_halt(Some(Arc::clone(&halt)));
                let mut poll = |_t: f64| {
                    if signals.stop() {
                        flag.store(true, Ordering::Relaxed);
                    }
                };
                let r = integrate(method, settings, e, t0, &y0, &[t0, t1], &mut poll);
                e.set_halt(None);
                r
            })
        });
        let elapsed = start.elapsed().as_secs_f64();
        let commit = |stats: IntegratorStats, next: Option<(Vec<f64>, Vec<f64>)>| {
            let mut state = lock(&self.state);
            state.calls += 1;
            state.rust_time_s += elapsed;
            state.stats += stats;
            if let Some((y, scales)) = next {
                state.t = t1;
                state.y = y;
                state.scales = scales;
            }
        };
        let outcome = match result {
            Ok(Ok((mut trajectory, stats))) => match trajectory.y.pop() {
                Some(y) if y.iter().all(|v| v.is_finite()) => {
                    commit(stats, Some((y, scales)));
                    core.functions = functions;
                    return Ok(t1);
                }
                _ => {
                    commit(stats, None);
                    Err(errors::internal(
                        py,
                        "the integrator returned no finite state",
                    ))
                }
            },
            Ok(Err(failure)) => {
                commit(failure.stats, None);
                match signals.error.take() {
                    Some(e) => Err(e),
                    None => {
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
            Err(panic) => Err(panic),
        };
        // Not committed: the load factors' functions go back to those in force before.
        let _ = with_eom!(core.cell, |_o, e| e.set_time_functions(before, "scales"));
        outcome
    }
}
