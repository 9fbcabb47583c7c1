//! The model level: `Beam` (from numbers or arrays of section properties), `FullModel` and
//! `ReducedModel` (matrices, shapes, modes), and the way into `Equations` and `Stepper`
//! (`equations.rs`). A beam is read through the case crate's `[beam]` table, so the rules are
//! the case file's, with errors named by the keyword argument (`EI`, `elements`).

use flexwing::analysis::modes::ModesPlan;
use flexwing::analysis::Plan;
use flexwing::model::{FullModel, PlanarModel, ReducedModel, StructuralModel};
use flexwing::solve::Modes;
use flexwing_case::{keys, BeamSpec, SectionSpec};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays::{self, finite1, finite_matrix, out1, out_matrix};
use crate::errors;
use crate::kwargs::Kwargs;

/// The argument a case-file key of `[beam]` came from: `beam.section.EI` → `EI`.
fn argument_of(key: &str) -> String {
    key.strip_prefix("beam.section.")
        .or_else(|| key.strip_prefix("beam."))
        .unwrap_or(key)
        .to_string()
}

/// The library beam of `spec` (a `[beam]` table), errors named by the keyword arguments.
fn beam_of(py: Python<'_>, spec: &Bound<'_, PyDict>) -> PyResult<(BeamSpec, FullModel)> {
    // A value of the wrong type (a text for a number) is a TypeError, as Python's own.
    let spec: BeamSpec = crate::values::read(spec.as_any(), "beam")?.map_err(|e| match &e.key {
        Some(key) if e.reason.starts_with("invalid type") => {
            errors::argument_type(py, &argument_of(key), &e.reason)
        }
        Some(key) => errors::input(py, &argument_of(key), &e.reason),
        None => errors::case(py, &e),
    })?;
    let model = errors::guard(py, || {
        spec.model()
            .map_err(|e| errors::input(py, &argument_of(&e.field), &e.reason))
    })?;
    Ok((spec, model))
}

/// The value of the keyword argument `key` of `Beam` as a case-file value: a text, a count
/// (`elements`), stations (`stations`), or a property — a number, or an array of values at the
/// stations `x` (the table `{x, value}`).
fn argument<'py>(
    py: Python<'py>,
    key: &str,
    v: &Bound<'py, PyAny>,
    x: Option<&[f64]>,
) -> PyResult<Bound<'py, PyAny>> {
    if v.is_instance_of::<pyo3::types::PyString>() {
        return Ok(v.clone());
    }
    match key {
        "elements" => return Ok(arrays::count(v, key)?.into_pyobject(py)?.into_any()),
        "stations" => return Ok(PyList::new(py, arrays::vector(v, key, None)?)?.into_any()),
        _ => {}
    }
    if !v.hasattr("__len__")? && !v.hasattr("__array__")? {
        return Ok(arrays::number(v, key)?.into_pyobject(py)?.into_any());
    }
    let values = arrays::vector(v, key, x.map(<[f64]>::len))?;
    let x = x.ok_or_else(|| {
        errors::input(
            py,
            "x",
            &format!("missing: {key} is an array of values at the stations x (m)"),
        )
    })?;
    let table = PyDict::new(py);
    table.set_item("x", x.to_vec())?;
    table.set_item("value", values)?;
    Ok(table.into_any())
}

/// A cantilever cut into rigid elements, with its section properties over the span.
///
/// Keyword arguments (SI units): ``length`` (m); ``elements`` (number of equal elements) or
/// ``stations`` (node positions, m, 0 … length); ``EI`` (N·m²) and ``mass_per_length`` (kg/m),
/// and for torsion ``GJ`` (N·m²), ``polar_inertia`` (kg·m), ``polar_inertia_about``
/// (``"mass-centre"`` or ``"elastic-axis"``) and ``d0`` (m, mass-centre offset); each property
/// a number, or an array of values at the stations ``x`` (m, piecewise linear, covering the
/// span); ``calibration`` (``"tip-load"``, the default, or ``"uniform"``); rotary inertia in
/// bending: ``element_inertia`` (``"point-mass"``, the default, or ``"bar"``: each element a
/// rigid bar, ``m ℓ²/12``) and ``rotary_inertia`` (kg·m, the section's ``ρI``, a property).
#[pyclass(module = "flexwing", name = "Beam", frozen)]
pub struct PyBeam {
    pub spec: BeamSpec,
    pub model: FullModel,
}

impl PyBeam {
    fn build(py: Python<'_>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        // The keys of `[beam]` and of `[beam.section]` (the case crate's), and `x`.
        let (beam_keys, section_keys) = (keys::<BeamSpec>(), keys::<SectionSpec>());
        let allowed: Vec<&str> = (beam_keys.iter().filter(|k| **k != "section"))
            .chain(section_keys)
            .chain(&["x"])
            .copied()
            .collect();
        let kw = Kwargs::new(py, kwargs, &allowed, "Beam")?;
        let beam = PyDict::new(py);
        let section = PyDict::new(py);
        let required = |name: &str| {
            kw.get(name)?
                .ok_or_else(|| errors::input(py, name, "missing: a required argument"))
        };
        beam.set_item("length", arrays::number(&required("length")?, "length")?)?;
        for key in ["EI", "mass_per_length"] {
            required(key)?;
        }
        let x = kw
            .get("x")?
            .map(|x| arrays::vector(&x, "x", None))
            .transpose()?;
        for key in beam_keys.iter().chain(section_keys) {
            let (Some(v), true) = (kw.get(key)?, *key != "length") else {
                continue;
            };
            let into = if section_keys.contains(key) {
                &section
            } else {
                &beam
            };
            into.set_item(key, argument(py, key, &v, x.as_deref())?)?;
        }
        beam.set_item("section", section)?;
        let (spec, model) = beam_of(py, &beam)?;
        Ok(Self { spec, model })
    }
}

#[pymethods]
impl PyBeam {
    #[new]
    #[pyo3(signature = (**kwargs))]
    fn new(py: Python<'_>, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        errors::guard(py, || Self::build(py, kwargs))
    }

    /// A beam from a ``[beam]`` table (a dict with the case file's keys).
    #[staticmethod]
    fn from_dict(py: Python<'_>, table: &Bound<'_, PyAny>) -> PyResult<Self> {
        errors::guard(py, || {
            let table = table
                .cast::<PyDict>()
                .map_err(|_| errors::argument_type(py, "table", "must be a dict"))?;
            let (spec, model) = beam_of(py, table)?;
            Ok(Self { spec, model })
        })
    }

    /// The beam as a ``[beam]`` table (a dict with the case file's keys).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            pythonize::pythonize(py, &self.spec).map_err(|e| errors::internal(py, &e.to_string()))
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> crate::Reduce<'py, (Bound<'py, PyAny>,)> {
        errors::guard(slf.py(), || {
            let table = slf.get().to_dict(slf.py())?;
            Ok((slf.get_type().getattr("from_dict")?, (table,)))
        })
    }

    /// Span ``L`` (m).
    #[getter]
    fn length(&self) -> f64 {
        self.model.beam().length()
    }
    /// Number of elements ``n``.
    #[getter]
    fn n_elements(&self) -> usize {
        self.model.n_elements()
    }
    /// Whether the beam has torsion degrees of freedom.
    #[getter]
    fn has_torsion(&self) -> bool {
        self.model.has_torsion()
    }
    /// Node stations ``x_0 = 0 … x_n = L`` (m), ``(n + 1,)``.
    #[getter]
    fn nodes<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().nodes().to_vec())
    }
    /// Element lengths (m), ``(n,)``.
    #[getter]
    fn lengths<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().lengths().to_vec())
    }
    /// Element masses (kg), ``(n,)``.
    #[getter]
    fn masses<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().masses().to_vec())
    }
    /// Element mass-centre offsets ``d0`` (m), ``(n,)``.
    #[getter]
    fn offsets<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().offsets().to_vec())
    }
    /// Element polar inertias about their mass centres (kg·m²), ``(n,)``.
    #[getter]
    fn inertias<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().inertias().to_vec())
    }
    /// Element rotary inertias in bending about their midpoints (kg·m²), ``(n,)``; zeros for
    /// point masses.
    #[getter]
    fn bending_inertias<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().bending_inertias().to_vec())
    }
    /// Bending spring stiffnesses (N·m/rad), ``(n,)``, joint ``i`` at node ``i``.
    #[getter]
    fn bending_stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray1<f64>> {
        out1(py, self.model.beam().bending_stiffness().to_vec())
    }
    /// Torsion spring stiffnesses (N·m/rad), ``(n,)``, or ``None`` without torsion.
    #[getter]
    fn torsion_stiffness<'py>(&self, py: Python<'py>) -> Option<Bound<'py, numpy::PyArray1<f64>>> {
        self.model
            .beam()
            .torsion_stiffness()
            .map(|k| out1(py, k.to_vec()))
    }

    fn __repr__(&self) -> String {
        format!(
            "Beam(length={}, n_elements={}, torsion={})",
            self.model.beam().length(),
            self.model.n_elements(),
            self.model.has_torsion()
        )
    }
}

/// The full model of a beam: ``n`` bending coordinates (joint rotations, rad), and ``n``
/// torsion coordinates with torsion.
#[pyclass(module = "flexwing", name = "FullModel", frozen)]
pub struct PyFullModel {
    pub spec: BeamSpec,
    pub model: FullModel,
}

impl PyFullModel {
    /// The model of a case's `[beam]` table `spec`: it pickles as that table, as a model built
    /// from a `Beam` does.
    pub fn of_case(spec: BeamSpec, model: FullModel) -> Self {
        Self { spec, model }
    }
}

/// The shape of `q` as a dict of node arrays; a non-finite position (a `q` beyond the model's
/// range) is an error naming `argument`.
fn shape_dict<'py>(
    py: Python<'py>,
    model: &FullModel,
    q: &[f64],
    argument: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let shape = model.shape(q);
    let d = PyDict::new(py);
    d.set_item("x", finite1(py, shape.x, "x", argument)?)?;
    d.set_item("y", finite1(py, shape.y, "y", argument)?)?;
    d.set_item("twist", finite1(py, shape.twist, "twist", argument)?)?;
    Ok(d)
}

/// The 1-based modes of `modes` (an int `r`: the first `r`; or a list), each checked against
/// `n_dofs` as it is read: nothing is allocated from an unchecked count.
fn mode_list(py: Python<'_>, modes: &Bound<'_, PyAny>, n_dofs: usize) -> PyResult<Vec<usize>> {
    let out_of_range = |field: &str, m: usize| {
        errors::input(
            py,
            field,
            &format!("mode numbers run from 1 to {n_dofs} (the model's coordinates), got {m}"),
        )
    };
    let mut list: Vec<usize> = Vec::new();
    if modes.is_instance_of::<PyList>() || modes.hasattr("__len__")? {
        for (i, m) in modes.try_iter()?.enumerate() {
            let field = format!("modes[{i}]");
            let m = arrays::count(&m?, &field)?;
            if !(1..=n_dofs).contains(&m) {
                return Err(out_of_range(&field, m));
            }
            if list.contains(&m) {
                return Err(errors::input(
                    py,
                    &field,
                    &format!("mode {m} is listed twice"),
                ));
            }
            list.push(m);
        }
    } else {
        let r = arrays::count(modes, "modes")?;
        if r > n_dofs {
            return Err(errors::input(
                py,
                "modes",
                &format!("at most {n_dofs} modes (the model's coordinates), got {r}"),
            ));
        }
        list.extend(1..=r);
    }
    if list.is_empty() {
        return Err(errors::input(py, "modes", "needs at least one mode"));
    }
    Ok(list)
}

/// The mass matrix of `model` at `x`, checked finite (naming `argument`).
fn mass_matrix<'py, M: StructuralModel>(
    py: Python<'py>,
    model: &M,
    x: &[f64],
    argument: &str,
) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
    let n = model.n_dofs();
    let mut m = nalgebra::DMatrix::zeros(n, n);
    let mut ws = model.workspace();
    model.mass_matrix_into(x, &mut ws, &mut m);
    finite_matrix(py, &m, "mass_matrix", argument)
}

#[pymethods]
impl PyFullModel {
    #[new]
    fn py_new(beam: &Bound<'_, PyBeam>) -> Self {
        let b = beam.get();
        Self {
            spec: b.spec.clone(),
            model: b.model.clone(),
        }
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> crate::Reduce<'py, (Bound<'py, PyAny>,)> {
        let py = slf.py();
        errors::guard(py, || {
            let beam = slf.get().beam(py)?;
            Ok((slf.get_type().into_any(), (beam.into_any(),)))
        })
    }

    /// The beam (for a case's model, the beam of its ``[beam]`` table).
    #[getter]
    fn beam<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBeam>> {
        errors::guard(py, || {
            Bound::new(
                py,
                PyBeam {
                    spec: self.spec.clone(),
                    model: self.model.clone(),
                },
            )
        })
    }

    /// Number of coordinates.
    #[getter]
    fn n_dofs(&self) -> usize {
        self.model.n_dofs()
    }
    /// Number of elements.
    #[getter]
    fn n_elements(&self) -> usize {
        self.model.n_elements()
    }
    /// Whether the model has torsion coordinates.
    #[getter]
    fn has_torsion(&self) -> bool {
        self.model.has_torsion()
    }

    /// Stiffness matrix ``K`` (N·m/rad), ``(n_dofs, n_dofs)``.
    fn stiffness_matrix<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        errors::guard(py, || Ok(out_matrix(py, &self.model.stiffness_matrix())))
    }

    /// Mass matrix ``M(q)`` (kg·m²) at joint rotations ``q`` (rad), ``(n_dofs, n_dofs)``.
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        errors::guard(py, || {
            let q = arrays::vector(q, "q", Some(self.model.n_dofs()))?;
            mass_matrix(py, &self.model, &q, "q")
        })
    }

    /// The deformed shape at joint rotations ``q`` (rad): a dict of node arrays ``x``, ``y``
    /// (m) and ``twist`` (rad).
    fn shape<'py>(&self, py: Python<'py>, q: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let q = arrays::vector(q, "q", Some(self.model.n_dofs()))?;
            shape_dict(py, &self.model, &q, "q")
        })
    }

    /// The lowest ``count`` natural modes about the undeformed state (default
    /// ``min(10, n_dofs)``), as a ``ModesResult``. Ctrl-C stops it as an analysis of a case.
    #[pyo3(signature = (count = None))]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        count: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            let count = count.map(|c| arrays::count(c, "count")).transpose()?;
            let plan = ModesPlan::new(self.model.clone(), count, "count")
                .map_err(|e| errors::library_input(py, &e))?;
            crate::run::run_detached(py, None, true, |p| {
                crate::run::execute_plan(Plan::Modes(plan), p)
            })
        })
    }

    /// The reduced model on ``modes`` of the undeformed state: an int ``r`` (the first ``r``)
    /// or a list of 1-based mode numbers.
    fn reduced(&self, py: Python<'_>, modes: &Bound<'_, PyAny>) -> PyResult<PyReducedModel> {
        errors::guard(py, || {
            PyReducedModel::build(py, self.spec.clone(), &self.model, modes)
        })
    }

    /// The equations of motion under ``loads`` (see ``Equations``).
    #[pyo3(signature = (loads = None, **kwargs))]
    fn equations(
        &self,
        py: Python<'_>,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<crate::equations::PyEquations> {
        errors::guard(py, || {
            crate::equations::PyEquations::build(
                py,
                crate::equations::AnyModel::Full(self.model.clone()),
                loads,
                kwargs,
            )
        })
    }

    /// A stepper of the equations of motion under ``loads`` (see ``Stepper``).
    #[pyo3(signature = (loads = None, **kwargs))]
    fn stepper(
        &self,
        py: Python<'_>,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<crate::equations::PyStepper> {
        errors::guard(py, || {
            crate::equations::PyStepper::build(
                py,
                crate::equations::AnyModel::Full(self.model.clone()),
                loads,
                kwargs,
            )
        })
    }

    fn __repr__(&self) -> String {
        format!(
            "FullModel(n_elements={}, n_dofs={})",
            self.model.n_elements(),
            self.model.n_dofs()
        )
    }
}

/// The full model projected on some of its natural modes about the undeformed state: the
/// coordinates are modal amplitudes ``η`` with ``q = Φ η``; geometry stays non-linear.
#[pyclass(module = "flexwing", name = "ReducedModel", frozen)]
pub struct PyReducedModel {
    spec: BeamSpec,
    pub model: ReducedModel,
    modes: Vec<usize>,
}

impl PyReducedModel {
    fn build(
        py: Python<'_>,
        spec: BeamSpec,
        full: &FullModel,
        modes: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let modes = mode_list(py, modes, full.n_dofs())?;
        let highest = modes.iter().copied().max().unwrap_or(1);
        let indices: Vec<usize> = modes.iter().map(|m| m - 1).collect();
        let model = errors::detached(py, || {
            Modes::lowest(full, highest)
                .map_err(flexwing::Error::from)
                .and_then(|m| Ok(ReducedModel::new(full, m.shapes(), &indices)?))
        })?
        .map_err(|e| errors::library(py, &e))?;
        Ok(Self { spec, model, modes })
    }

    fn full(&self) -> PyFullModel {
        PyFullModel {
            spec: self.spec.clone(),
            model: self.model.full_model().clone(),
        }
    }
}

#[pymethods]
impl PyReducedModel {
    #[new]
    fn py_new(
        py: Python<'_>,
        full: &Bound<'_, PyFullModel>,
        modes: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        errors::guard(py, || {
            let f = full.get();
            Self::build(py, f.spec.clone(), &f.model, modes)
        })
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> crate::Reduce<'py, (Bound<'py, PyAny>, Vec<usize>)> {
        let py = slf.py();
        errors::guard(py, || {
            let this = slf.get();
            let full = Bound::new(py, this.full())?;
            Ok((
                slf.get_type().into_any(),
                (full.into_any(), this.modes.clone()),
            ))
        })
    }

    /// Number of coordinates (retained modes).
    #[getter]
    fn n_dofs(&self) -> usize {
        self.model.n_dofs()
    }
    /// The retained modes, 1-based.
    #[getter]
    fn modes(&self) -> Vec<usize> {
        self.modes.clone()
    }
    /// The full model underneath.
    #[getter]
    fn full_model(&self) -> PyFullModel {
        self.full()
    }
    /// The mass-normalized mode shapes ``Φ`` as columns, ``(full n_dofs, n_dofs)``.
    #[getter]
    fn basis<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        errors::guard(py, || Ok(out_matrix(py, self.model.basis())))
    }

    /// Joint rotations ``q = Φ η`` (rad) of modal amplitudes ``x``.
    fn full_coordinates<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        errors::guard(py, || {
            let x = arrays::vector(x, "x", Some(self.model.n_dofs()))?;
            finite1(py, self.model.full_coordinates(&x), "q", "x")
        })
    }

    /// Modal amplitudes ``η = Φᵀ M(0) q`` of joint rotations ``q`` (rad).
    fn reduce_coordinates<'py>(
        &self,
        py: Python<'py>,
        q: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray1<f64>>> {
        errors::guard(py, || {
            let q = arrays::vector(q, "q", Some(self.model.full_model().n_dofs()))?;
            finite1(py, self.model.reduce_coordinates(&q), "x", "q")
        })
    }

    /// Reduced stiffness ``K_r = Φᵀ K Φ``, ``(n_dofs, n_dofs)``.
    fn stiffness_matrix<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        errors::guard(py, || Ok(out_matrix(py, &self.model.stiffness_matrix())))
    }

    /// Reduced mass matrix ``M_r(η) = Φᵀ M(Φ η) Φ`` at modal amplitudes ``x``.
    fn mass_matrix<'py>(
        &self,
        py: Python<'py>,
        x: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        errors::guard(py, || {
            let x = arrays::vector(x, "x", Some(self.model.n_dofs()))?;
            mass_matrix(py, &self.model, &x, "x")
        })
    }

    /// The deformed shape at modal amplitudes ``x`` (see ``FullModel.shape``).
    fn shape<'py>(&self, py: Python<'py>, x: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            let x = arrays::vector(x, "x", Some(self.model.n_dofs()))?;
            let q = self.model.full_coordinates(&x);
            shape_dict(py, self.model.full_model(), &q, "x")
        })
    }

    /// The equations of motion under ``loads`` (see ``Equations``).
    #[pyo3(signature = (loads = None, **kwargs))]
    fn equations(
        &self,
        py: Python<'_>,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<crate::equations::PyEquations> {
        errors::guard(py, || {
            crate::equations::PyEquations::build(
                py,
                crate::equations::AnyModel::Reduced(self.model.clone()),
                loads,
                kwargs,
            )
        })
    }

    /// A stepper of the equations of motion under ``loads`` (see ``Stepper``).
    #[pyo3(signature = (loads = None, **kwargs))]
    fn stepper(
        &self,
        py: Python<'_>,
        loads: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<crate::equations::PyStepper> {
        errors::guard(py, || {
            crate::equations::PyStepper::build(
                py,
                crate::equations::AnyModel::Reduced(self.model.clone()),
                loads,
                kwargs,
            )
        })
    }

    fn __repr__(&self) -> String {
        format!("ReducedModel(modes={:?})", self.modes)
    }
}
