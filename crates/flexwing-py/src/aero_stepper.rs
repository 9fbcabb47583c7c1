//! `AeroStepper`: the library's [`flexwing::analysis::aero::stepper::AeroStepper`] (an aeroelastic
//! response of a case advanced one communication interval per call, with named inputs set
//! between calls and named outputs read after each), built by ``Case.stepper(...)``: the same
//! core as the co-simulation FMU (docs/python.md).

use std::collections::HashMap;
use std::sync::{Mutex, MutexGuard};

use flexwing::analysis::aero::stepper::{AeroStepper, Hold, StepError, StepperOptions};
use flexwing::analysis::Plan;
use flexwing::solve::aeroelastic::{Input, Output};
use flexwing_case::{Analysis, Case};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors;
use crate::kwargs::Kwargs;

/// An aeroelastic response advanced one communication interval per call, with the inputs set
/// from Python between calls (``Case.stepper``; docs/python.md).
#[pyclass(module = "flexwing", name = "AeroStepper", frozen)]
pub struct PyAeroStepper {
    inner: Mutex<AeroStepper>,
    input_names: Vec<String>,
    output_names: Vec<String>,
}

/// `m` locked; a poisoned lock (a panic caught at the boundary) is taken as it is: a step
/// commits its state only when it succeeds.
fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A list of names (a sequence of str) or `None`.
fn names(value: Option<Bound<'_, PyAny>>, field: &str) -> PyResult<Option<Vec<String>>> {
    let Some(v) = value else { return Ok(None) };
    let py = v.py();
    if v.is_instance_of::<pyo3::types::PyString>() {
        return Err(errors::argument_type(
            py,
            field,
            "must be a list of names, not one string",
        ));
    }
    let mut out = Vec::new();
    for (i, item) in v.try_iter()?.enumerate() {
        out.push(crate::arrays::text(&item?, &format!("{field}[{i}]"))?);
    }
    Ok(Some(out))
}

impl PyAeroStepper {
    /// Build from a case and the keyword arguments of `Case.stepper`.
    pub fn build(
        py: Python<'_>,
        case: &Case,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let kw = Kwargs::new(
            py,
            kwargs,
            &["inputs", "outputs", "hold", "model"],
            "stepper",
        )?;
        let plan = case
            .plan(Analysis::Dynamic)
            .map_err(|e| errors::case(py, &e))?;
        let Plan::AeroDynamic(plan) = plan else {
            return Err(errors::input(
                py,
                "aero",
                "missing: a stepper steps an aeroelastic response (the case needs [aero]); a \
                 structural run steps with model.stepper(...)",
            ));
        };
        let model = &plan.structure.model;
        let (ne, torsion) = (model.n_elements(), model.has_torsion());
        let surfaces = &plan.aero.section.surfaces;
        let mut options = StepperOptions::new(torsion);
        if let Some(list) = names(kw.get("inputs")?, "inputs")? {
            options.inputs = list
                .iter()
                .enumerate()
                .map(|(i, n)| Input::parse(n, ne, torsion, surfaces, &format!("inputs[{i}]")))
                .collect::<Result<_, _>>()
                .map_err(|e| errors::library_input(py, &e))?;
        }
        if let Some(list) = names(kw.get("outputs")?, "outputs")? {
            options.outputs = list
                .iter()
                .enumerate()
                .map(|(i, n)| Output::parse(n, ne, torsion, surfaces, &format!("outputs[{i}]")))
                .collect::<Result<_, _>>()
                .map_err(|e| errors::library_input(py, &e))?;
        }
        if let Some(h) = kw.get("hold")? {
            let name = crate::arrays::text(&h, "hold")?;
            options.hold = Hold::from_name(&name).ok_or_else(|| {
                errors::input(
                    py,
                    "hold",
                    &format!("unknown value {name:?}; expected \"linear\" or \"zero\""),
                )
            })?;
        }
        if let Some(m) = kw.get("model")? {
            options.model = m
                .extract::<usize>()
                .map_err(|_| errors::input(py, "model", "must be a non-negative integer"))?;
        }
        let stepper = errors::detached(py, || AeroStepper::new(&plan, &options))?
            .map_err(|e| errors::library(py, &e))?;
        Ok(Self {
            input_names: stepper.inputs().iter().map(Input::name).collect(),
            output_names: stepper.outputs().iter().map(Output::name).collect(),
            inner: Mutex::new(stepper),
        })
    }
}

/// A step's error as a Python exception.
fn step_error(py: Python<'_>, e: &StepError) -> PyErr {
    match e {
        StepError::Input(e) => errors::library_input(py, e),
        StepError::Stopped(stop) => {
            let described = crate::convert::status::described(py, &**stop)
                .ok()
                .map(|d| d.into_any().unbind());
            errors::solver(py, &stop.to_string(), None, described, None)
        }
    }
}

#[pymethods]
impl PyAeroStepper {
    /// Advance by ``dt`` (s) with the inputs ``inputs`` (a dict name → value, SI units; the
    /// others keep their values). With ``hold="linear"`` an input goes linearly from its value
    /// in force to the new one over the interval; with ``hold="zero"`` it takes the new value
    /// at once. Returns the new time (s). Raises ``InputError`` naming a bad input or ``dt``,
    /// ``SolverError`` (with ``stop``) if the integration stops inside the interval: the
    /// stepper is then as before the call.
    #[pyo3(signature = (dt, inputs = None))]
    fn step(
        &self,
        py: Python<'_>,
        dt: &Bound<'_, PyAny>,
        inputs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<f64> {
        errors::guard(py, || {
            let dt = crate::arrays::number(dt, "dt")?;
            let mut values = Vec::new();
            if let Some(d) = inputs {
                for (k, v) in d.iter() {
                    let name = crate::arrays::text(&k, "inputs")?;
                    let Some(index) = self.input_names.iter().position(|n| *n == name) else {
                        return Err(errors::input(
                            py,
                            "inputs",
                            &format!(
                                "unknown input {name:?}; this stepper's inputs are {}",
                                self.input_names.join(", ")
                            ),
                        ));
                    };
                    values.push((index, crate::arrays::number(&v, &name)?));
                }
            }
            let mut signals = crate::progress::Signals::new(py)?;
            let result = errors::detached(py, || {
                let mut s = lock(&self.inner);
                let before: Vec<f64> = s.input_values().to_vec();
                let restore = |s: &mut AeroStepper| {
                    for (j, b) in before.iter().enumerate() {
                        // The values were accepted before: this cannot fail.
                        let _ = s.set_input(j, *b);
                    }
                };
                for &(i, v) in &values {
                    if let Err(e) = s.set_input(i, v) {
                        restore(&mut s);
                        return Err(StepError::Input(e));
                    }
                }
                let halt = s.halt_flag();
                let r = s.step(dt, &mut |_| {
                    if signals.stop() {
                        halt.store(true, std::sync::atomic::Ordering::Relaxed);
                    }
                });
                if r.is_err() {
                    restore(&mut s);
                }
                r
            })?;
            match result {
                Ok(t) => Ok(t),
                Err(e) => Err(signals.error.take().unwrap_or_else(|| step_error(py, &e))),
            }
        })
    }

    /// Time (s).
    #[getter]
    fn t(&self) -> f64 {
        lock(&self.inner).t()
    }
    /// The input names, in order.
    #[getter]
    fn input_names(&self) -> Vec<String> {
        self.input_names.clone()
    }
    /// The output names, in order.
    #[getter]
    fn output_names(&self) -> Vec<String> {
        self.output_names.clone()
    }
    /// The SI unit of every input and output, by name.
    #[getter]
    fn units(&self) -> HashMap<String, &'static str> {
        let s = lock(&self.inner);
        let mut m: HashMap<String, &'static str> =
            s.inputs().iter().map(|i| (i.name(), i.unit())).collect();
        m.extend(s.outputs().iter().map(|o| (o.name(), o.unit())));
        m
    }
    /// The inputs' values set (name → value, SI units).
    #[getter]
    fn inputs(&self) -> HashMap<String, f64> {
        let s = lock(&self.inner);
        self.input_names
            .iter()
            .cloned()
            .zip(s.input_values().iter().copied())
            .collect()
    }
    /// The outputs at the current time (name → value: m, rad, N·m, N), with the inputs in
    /// force.
    #[getter]
    fn outputs(&self, py: Python<'_>) -> PyResult<HashMap<String, f64>> {
        errors::guard(py, || {
            let v = lock(&self.inner).output_values();
            Ok(self.output_names.iter().cloned().zip(v).collect())
        })
    }
    /// ``status`` (``"complete"``, ``"suspect"``: the energy balance exceeded its limit, or
    /// ``"stopped"``: the last step failed), ``stop`` and ``message``.
    #[getter]
    fn status<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let status = lock(&self.inner).status();
            let d = PyDict::new(py);
            crate::convert::status::set_status(&d, &status)?;
            Ok(d)
        })
    }
    /// What the energy audit found since the start (the fields of ``DynamicRun.energy_audit``;
    /// energies in J).
    #[getter]
    fn energy_audit<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            let audit = lock(&self.inner).energy_audit();
            crate::convert::status::data(py, &audit)
        })
    }
    /// Energies at ``t`` (J): ``kinetic``, ``strain``, ``work`` and ``dissipated`` since the
    /// start.
    fn energies(&self, py: Python<'_>) -> PyResult<HashMap<&'static str, f64>> {
        errors::guard(py, || {
            let [k, v, w, d] = lock(&self.inner).energies();
            Ok([
                ("kinetic", k),
                ("strain", v),
                ("work", w),
                ("dissipated", d),
            ]
            .into_iter()
            .collect())
        })
    }
    /// Counters summed over the calls (those of ``DynamicRun.stats``), ``calls`` and
    /// ``rust_time_s`` (the integration's wall time, s).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let s = lock(&self.inner);
            let d = crate::convert::dynamics::integrator_stats(py, &s.stats())?;
            d.set_item("calls", s.calls())?;
            d.set_item("rust_time_s", s.integration_time_s())?;
            Ok(d)
        })
    }

    fn __repr__(&self) -> String {
        let s = lock(&self.inner);
        format!(
            "AeroStepper(t={}, model={:?}, inputs={:?}, outputs={:?}, hold={:?})",
            s.t(),
            s.kind().label(),
            self.input_names,
            self.output_names,
            s.hold().name()
        )
    }
}

/// `Case.fmu(path, ...)`: the co-simulation FMU of the case, written by the same writer as
/// `flexwing fmu` (the `flexwing-fmu` crate). Returns what was written as a dict.
pub fn export_fmu<'py>(
    py: Python<'py>,
    case: &Case,
    path: &Bound<'py, PyAny>,
    kwargs: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    use flexwing_fmu::description::find_library;
    use flexwing_fmu::{write_fmu, FmuError, FmuOptions};
    let kw = Kwargs::new(
        py,
        kwargs,
        &["inputs", "outputs", "hold", "model", "library"],
        "fmu",
    )?;
    let out: std::path::PathBuf = path
        .extract()
        .map_err(|_| errors::argument_type(py, "path", "must be a str or os.PathLike"))?;
    let mut options = FmuOptions {
        inputs: names(kw.get("inputs")?, "inputs")?,
        outputs: names(kw.get("outputs")?, "outputs")?,
        ..FmuOptions::default()
    };
    if let Some(h) = kw.get("hold")? {
        let name = crate::arrays::text(&h, "hold")?;
        options.hold = Hold::from_name(&name).ok_or_else(|| {
            errors::input(
                py,
                "hold",
                &format!("unknown value {name:?}; expected \"zero\" or \"linear\""),
            )
        })?;
    }
    if let Some(m) = kw.get("model")? {
        options.model = m
            .extract::<usize>()
            .map_err(|_| errors::input(py, "model", "must be a non-negative integer"))?;
    }
    let library: Option<std::path::PathBuf> =
        match kw.get("library")? {
            Some(l) if !l.is_none() => Some(l.extract().map_err(|_| {
                errors::argument_type(py, "library", "must be a str or os.PathLike")
            })?),
            _ => None,
        };
    let as_error = |e: FmuError| -> PyErr {
        let text = e.to_string();
        match (&e, text.split_once(": ")) {
            (FmuError::Input(_), Some((field, reason))) => errors::input(py, field, reason),
            (FmuError::Io(_), Some(("library", reason))) => errors::input(py, "library", reason),
            (FmuError::Input(_), None) => errors::input(py, "case", &text),
            (FmuError::Io(_), _) => pyo3::exceptions::PyOSError::new_err(text),
        }
    };
    let library = find_library(library.as_deref(), None).map_err(as_error)?;
    let summary =
        errors::detached(py, || write_fmu(case, &options, &library, &out))?.map_err(as_error)?;
    let d = PyDict::new(py);
    d.set_item("path", out)?;
    d.set_item("guid", summary.guid)?;
    d.set_item("inputs", summary.inputs)?;
    d.set_item("outputs", summary.outputs)?;
    d.set_item("model", summary.model)?;
    d.set_item("hold", options.hold.name())?;
    d.set_item("platform", summary.platform)?;
    d.set_item("bytes", summary.bytes)?;
    Ok(d)
}
