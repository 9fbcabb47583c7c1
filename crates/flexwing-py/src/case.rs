//! `flexwing.Case`: a case file (TOML text, a file, or a dict / keyword arguments with the same
//! keys), read by the case crate, and its analyses. Immutable; `replace` makes a changed copy
//! (the building block of sweeps). Pickles as its TOML text.

use std::path::Path;

use flexwing_case::{Case, CaseError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::errors;
use crate::kwargs::Kwargs;
use crate::model::PyFullModel;
use crate::run::run_case;
use flexwing_case::Analysis;

/// A flexwing case: the beam, the loads and the settings of its analyses, with the keys of the
/// case file (docs/case-file.md).
///
/// Build it with ``Case.from_toml(text)``, ``Case.load(path)``, ``Case.from_dict(d)`` or
/// ``Case(d)`` / ``Case(beam={...}, loads=[...], dynamic={...})`` (``static`` is a Python
/// keyword: pass it in the dict). Run it with ``modes()``, ``statics()``, ``dynamics()`` and,
/// with ``[aero]``, ``flutter()``.
#[pyclass(module = "flexwing", name = "Case", frozen)]
pub struct PyCase {
    pub case: Case,
}

/// A case from a dict with the case file's keys; errors name the key (`beam.section.EI`).
pub fn case_from_dict(obj: &Bound<'_, PyAny>) -> PyResult<Case> {
    let py = obj.py();
    if !obj.is_instance_of::<PyDict>() {
        return Err(errors::argument_type(
            py,
            "data",
            "must be a dict with the keys of a case file",
        ));
    }
    crate::values::read_or_raise(obj, "", true)
}

/// `case` if every number in it is finite (a case from TOML text may hold `nan` or `inf`),
/// else the `CaseFileError` naming the key: a case never holds NaN, whatever it was built from.
fn finite(py: Python<'_>, case: Case) -> PyResult<Case> {
    let data = pythonize::pythonize(py, &case)
        .map_err(|e| errors::internal(py, &format!("the case does not convert to a dict: {e}")))?;
    match crate::values::first_non_finite(&data) {
        None => Ok(case),
        Some(e) => Err(errors::case(
            py,
            &CaseError {
                file: case.file().map(str::to_string),
                ..e
            },
        )),
    }
}

/// The keys of `path` (`"beam.section.EI"`, `"loads[0].fy"`): names and list indices.
enum Step {
    Key(String),
    Index(usize),
}

fn parse_path(py: Python<'_>, path: &str) -> PyResult<Vec<Step>> {
    let bad = || {
        errors::input(
            py,
            path,
            "is not a key path such as \"beam.section.EI\" or \"loads[0].fy\"",
        )
    };
    let mut steps = Vec::new();
    for part in path.split('.') {
        let (name, mut rest) = part.split_at(part.find('[').unwrap_or(part.len()));
        if name.is_empty() {
            return Err(bad());
        }
        steps.push(Step::Key(name.to_string()));
        while !rest.is_empty() {
            let close = rest.find(']').ok_or_else(bad)?;
            let index = rest[1..close].parse::<usize>().map_err(|_| bad())?;
            steps.push(Step::Index(index));
            rest = &rest[close + 1..];
            if !rest.is_empty() && !rest.starts_with('[') {
                return Err(bad());
            }
        }
    }
    Ok(steps)
}

/// Set `path` in the nested dicts and lists of `root` to `value` (creating missing tables).
fn set_path(root: &Bound<'_, PyAny>, path: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    let py = root.py();
    let steps = parse_path(py, path)?;
    let mut node = root.clone();
    for (k, step) in steps.iter().enumerate() {
        let last = k + 1 == steps.len();
        match step {
            Step::Key(key) => {
                let d = node.cast::<PyDict>().map_err(|_| {
                    errors::input(py, path, &format!("{key:?} is not inside a table"))
                })?;
                if last {
                    d.set_item(key, value)?;
                    return Ok(());
                }
                let next = match d.get_item(key)? {
                    Some(v) if !v.is_none() => v,
                    _ => {
                        let fresh = PyDict::new(py).into_any();
                        d.set_item(key, &fresh)?;
                        fresh
                    }
                };
                node = next;
            }
            Step::Index(i) => {
                let list = node
                    .cast::<PyList>()
                    .map_err(|_| errors::input(py, path, &format!("[{i}] is not inside a list")))?;
                if *i >= list.len() {
                    return Err(errors::input(
                        py,
                        path,
                        &format!(
                            "index {i} is out of range: the list has {} items",
                            list.len()
                        ),
                    ));
                }
                if last {
                    list.set_item(*i, value)?;
                    return Ok(());
                }
                node = list.get_item(*i)?;
            }
        }
    }
    Ok(())
}

fn to_dict<'py>(py: Python<'py>, case: &Case) -> PyResult<Bound<'py, PyAny>> {
    pythonize::pythonize(py, case)
        .map_err(|e| errors::internal(py, &format!("the case does not convert to a dict: {e}")))
}

#[pymethods]
impl PyCase {
    /// A case from a dict with the case file's keys, and/or keyword arguments (which override
    /// the dict's keys).
    #[new]
    #[pyo3(signature = (data = None, /, **kwargs))]
    fn new(
        py: Python<'_>,
        data: Option<&Bound<'_, PyAny>>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        errors::guard(py, || {
            let merged = PyDict::new(py);
            if let Some(d) = data {
                let d = d.cast::<PyDict>().map_err(|_| {
                    errors::argument_type(py, "data", "must be a dict with the keys of a case file")
                })?;
                merged.update(d.as_mapping())?;
            }
            if let Some(k) = kwargs {
                merged.update(k.as_mapping())?;
            }
            Ok(Self {
                case: case_from_dict(merged.as_any())?,
            })
        })
    }

    /// A case from TOML text; ``file`` names it in errors.
    #[staticmethod]
    #[pyo3(signature = (text, file = None))]
    fn from_toml(
        py: Python<'_>,
        text: &Bound<'_, PyAny>,
        file: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        errors::guard(py, || {
            let text = crate::arrays::text(text, "text")?;
            let file = file.map(|f| crate::arrays::text(f, "file")).transpose()?;
            let case = Case::parse(&text, file.as_deref()).map_err(|e| errors::case(py, &e))?;
            Ok(Self {
                case: finite(py, case)?,
            })
        })
    }

    /// Read the case file at ``path`` (a ``str`` or ``os.PathLike``).
    #[staticmethod]
    fn load(py: Python<'_>, path: &Bound<'_, PyAny>) -> PyResult<Self> {
        errors::guard(py, || {
            let path: String = py
                .import("os")?
                .call_method1("fspath", (path,))
                .and_then(|p| p.extract())
                .map_err(|e| {
                    errors::convert_error(py, e, |_| {
                        errors::argument_type(py, "path", "must be a str or an os.PathLike")
                    })
                })?;
            let case = Case::load(Path::new(&path)).map_err(|e| errors::case(py, &e))?;
            Ok(Self {
                case: finite(py, case)?,
            })
        })
    }

    /// A case from a dict with the case file's keys (NumPy arrays and scalars are accepted as
    /// values).
    #[staticmethod]
    fn from_dict(data: &Bound<'_, PyAny>) -> PyResult<Self> {
        errors::guard(data.py(), || {
            Ok(Self {
                case: case_from_dict(data)?,
            })
        })
    }

    /// The case as a dict with the case file's keys (absent optional keys are left out).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || to_dict(py, &self.case))
    }

    /// The case as TOML text.
    fn to_toml(&self, py: Python<'_>) -> PyResult<String> {
        errors::guard(py, || {
            self.case.to_toml_string().map_err(|e| errors::case(py, &e))
        })
    }

    /// A copy with the values at key paths changed: ``case.replace({"beam.section.EI": 60.0,
    /// "loads[0].fy": 12.0})``. Missing tables are created; errors name the path.
    fn replace(&self, py: Python<'_>, changes: &Bound<'_, PyAny>) -> PyResult<Self> {
        errors::guard(py, || {
            let changes = changes.cast::<PyDict>().map_err(|_| {
                errors::argument_type(py, "changes", "must be a dict of key paths and values")
            })?;
            let data = to_dict(py, &self.case)?;
            for (path, value) in changes.iter() {
                let path: String = path
                    .extract()
                    .map_err(|_| errors::argument_type(py, "changes", "keys must be strings"))?;
                set_path(&data, &path, &value)?;
            }
            let mut case = case_from_dict(&data)?;
            case = match self.case.file() {
                // Keep the file name for messages: reparse through TOML with it.
                Some(file) => {
                    let text = case.to_toml_string().map_err(|e| errors::case(py, &e))?;
                    Case::parse(&text, Some(file)).map_err(|e| errors::case(py, &e))?
                }
                None => case,
            };
            Ok(Self { case })
        })
    }

    /// The case's title, if any.
    #[getter]
    fn title(&self) -> Option<String> {
        self.case.title.clone()
    }

    /// Whether the case has an ``[aero]`` table: its ``statics()`` and ``dynamics()`` are then
    /// the aeroelastic analyses, and it can run ``flutter()``.
    #[getter]
    fn aeroelastic(&self) -> bool {
        self.case.is_aeroelastic()
    }

    /// The file the case was read from, if any.
    #[getter]
    fn file(&self) -> Option<String> {
        self.case.file().map(str::to_string)
    }

    /// The full model of ``[beam]``.
    fn model(&self, py: Python<'_>) -> PyResult<PyFullModel> {
        errors::guard(py, || {
            let model = self.case.model().map_err(|e| errors::case(py, &e))?;
            Ok(PyFullModel::of_case(self.case.beam.clone(), model))
        })
    }

    /// The natural modes of ``[beam]`` (``[modes] count``, default 10), in vacuo: an ``[aero]``
    /// table is not used (as ``flexwing modes``); the wet modes (with the fluid's apparent
    /// mass) start the branches of ``flutter()`` (``Stability.wet_frequency``).
    ///
    /// Keyword arguments: ``progress`` — ``callback(done, label)``, ``done`` the fraction of
    /// the analysis (0 to 1), ``label`` the model running; ``check`` (accepted as by every
    /// analysis: a modal analysis completes or raises). Ctrl-C or a callback that raises stops
    /// the analysis at its next check and raises that exception with the partial result as
    /// its ``result`` attribute.
    #[pyo3(signature = (**kwargs))]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || self.analysis(py, Analysis::Modes, kwargs, "modes"))
    }

    /// The non-linear statics of ``[[loads]]`` and ``[static]`` (sweeps, reduced models,
    /// loaded modes), as a ``StaticResult``; with ``[aero]``, the static aeroelastic equilibria
    /// at ``aero.flight.speed`` or along ``[aero.sweep]`` and the divergence speed, as an
    /// ``AeroStaticResult`` (as ``flexwing static``).
    ///
    /// Keyword arguments: ``progress`` (as ``modes``); ``check`` (default ``True``): raise
    /// ``SolverError`` (with the partial result) if a model stopped, else return the result
    /// with each run's ``status``.
    #[pyo3(signature = (**kwargs))]
    fn statics<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            self.analysis(py, Analysis::Static, kwargs, "statics")
        })
    }

    /// The non-linear dynamics of ``[[loads]]`` and ``[dynamic]`` (full, simplified and
    /// reduced models), as a ``DynamicResult`` (on the 3-D chain a ``Chain3dDynamicResult``);
    /// with ``[aero]``, the aeroelastic response to the gust and the changes of
    /// ``[aero.flight]``, as an ``AeroDynamicResult`` (as ``flexwing dynamic``). Keyword arguments as ``statics``; ``check`` also raises for a
    /// run whose energy balance is suspect.
    #[pyo3(signature = (**kwargs))]
    fn dynamics<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            self.analysis(py, Analysis::Dynamic, kwargs, "dynamics")
        })
    }

    /// Flutter and divergence along the speeds of ``[aero.sweep]`` (``[aero]``, ``[flutter]``)
    /// for the full and reduced models, with the V-g/V-ω data, the static equilibria and the
    /// p-k check, as a ``FlutterResult`` (as ``flexwing flutter``). Keyword arguments as
    /// ``statics``: ``check`` raises if an eigen-analysis (or the p-k check) stopped before
    /// the last speed; equilibria that stop past the divergence speed are expected and do not
    /// raise.
    #[pyo3(signature = (**kwargs))]
    fn flutter<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            self.analysis(py, Analysis::Flutter, kwargs, "flutter")
        })
    }

    /// A discrete gust family as in CS 25.341(a) (``[gust_family]`` on the aeroelastic response
    /// of ``[aero]`` and ``[dynamic]``): one 1−cos gust per gust gradient distance H at its
    /// design velocity, on the full and reduced models, with each output's peaks per H and the
    /// critical H, as a ``GustFamilyResult`` (as ``flexwing gust``). Keyword arguments as
    /// ``dynamics``.
    #[pyo3(signature = (**kwargs))]
    fn gust_family<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            self.analysis(py, Analysis::GustFamily, kwargs, "gust_family")
        })
    }

    /// The power spectra and RMS of the outputs in continuous turbulence (``[turbulence]``
    /// through the linear models of ``[linearize]``), as a ``TurbulenceResult`` (as
    /// ``flexwing turbulence``; spectra and conventions: docs/control.md).
    ///
    /// Keyword arguments: ``spectrum`` (``"von-karman"`` or ``"dryden"``), ``intensity``
    /// (m/s), ``scale_length`` (m), ``frequencies``, ``min_frequency``, ``max_frequency``
    /// (rad/s) override the keys of ``[turbulence]`` (which ``intensity`` can replace);
    /// ``progress`` and ``check`` as ``statics`` (``check`` raises ``SolverError`` if a model
    /// is past the flutter speed).
    #[pyo3(signature = (**kwargs))]
    fn turbulence<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            let kw = Kwargs::new(
                py,
                kwargs,
                &[
                    "spectrum",
                    "intensity",
                    "scale_length",
                    "frequencies",
                    "min_frequency",
                    "max_frequency",
                    "progress",
                    "check",
                ],
                "turbulence",
            )?;
            let mut case = self.case.clone();
            let intensity = match kw.get("intensity")? {
                Some(v) => Some(crate::arrays::number(&v, "intensity")?),
                None => None,
            };
            let mut spec = match (case.turbulence.clone(), intensity) {
                (Some(spec), _) => spec,
                (None, Some(intensity)) => flexwing_case::TurbulenceSpec {
                    spectrum: None,
                    intensity,
                    scale_length: None,
                    frequencies: None,
                    min_frequency: None,
                    max_frequency: None,
                },
                // The case's own error: `turbulence: missing`.
                (None, None) => return run_with(py, &kw, &case, Analysis::Turbulence),
            };
            if let Some(i) = intensity {
                spec.intensity = i;
            }
            if let Some(v) = kw.get("spectrum")? {
                spec.spectrum = Some(match crate::arrays::text(&v, "spectrum")?.as_str() {
                    "von-karman" => flexwing_case::SpectrumSpec::VonKarman,
                    "dryden" => flexwing_case::SpectrumSpec::Dryden,
                    other => {
                        return Err(errors::input(
                            py,
                            "spectrum",
                            &format!("expected \"von-karman\" or \"dryden\", got {other:?}"),
                        ))
                    }
                });
            }
            for (key, slot) in [
                ("scale_length", &mut spec.scale_length),
                ("min_frequency", &mut spec.min_frequency),
                ("max_frequency", &mut spec.max_frequency),
            ] {
                if let Some(v) = kw.get(key)? {
                    *slot = Some(crate::arrays::number(&v, key)?);
                }
            }
            if let Some(v) = kw.get("frequencies")? {
                spec.frequencies = Some(crate::arrays::count(&v, "frequencies")?);
            }
            case.turbulence = Some(spec);
            run_with(py, &kw, &case, Analysis::Turbulence)
        })
    }

    /// Flutter and divergence against a load level on the 3-D chain (``beam.model =
    /// "chain3d"``, ``[flutter.study]``): at every level of a tip force, gravity factor or root
    /// angle, the tip deflection at rest, the flutter speed and frequency and the divergence
    /// speed, beside the undeformed wing's flutter speed, as a ``Chain3dStudyResult`` (as
    /// ``flexwing study``). Keyword arguments as ``statics``.
    #[pyo3(signature = (**kwargs))]
    fn study<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || self.analysis(py, Analysis::Study, kwargs, "study"))
    }

    /// An ``AeroStepper`` of the case's aeroelastic response (``[aero]``, ``[dynamic]``): the run
    /// ``dynamics()`` makes, advanced by ``step(dt, inputs)`` with named inputs set between calls
    /// (docs/python.md). Keyword arguments: ``inputs`` (names; default
    /// ``["root_angle", "speed", "gust"]``; also ``"force[k]"``, ``"torque[k]"`` at node k),
    /// ``outputs`` (names; default tip position and twist, root bending moment and torque,
    /// lift), ``hold`` (``"linear"``, default, or ``"zero"``), ``model`` (index among the
    /// case's models, default 0).
    #[pyo3(signature = (**kwargs))]
    fn stepper(
        &self,
        py: Python<'_>,
        kwargs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<crate::aero_stepper::PyAeroStepper> {
        errors::guard(py, || {
            crate::aero_stepper::PyAeroStepper::build(py, &self.case, kwargs)
        })
    }

    /// Write a co-simulation FMU (FMI 2.0) of the case's aeroelastic response to ``path``
    /// (as ``flexwing fmu``; docs/control.md) and return what it holds (a dict: ``path``,
    /// ``guid``, ``inputs``, ``outputs``, ``model``, ``hold``, ``platform``, ``bytes``).
    ///
    /// Keyword arguments: ``inputs``, ``outputs``, ``model`` as ``stepper``; ``hold``
    /// (``"zero"``, default, or ``"linear"``: the start value of the FMU's ``hold``
    /// parameter); ``library``, the compiled FMU library (``libflexwing_fmu.so`` of ``cargo
    /// build --release -p flexwing-fmu``; default: the environment variable
    /// ``FLEXWING_FMU_LIBRARY``).
    #[pyo3(signature = (path, **kwargs))]
    fn fmu<'py>(
        &self,
        py: Python<'py>,
        path: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        errors::guard(py, || {
            crate::aero_stepper::export_fmu(py, &self.case, path, kwargs)
        })
    }

    /// The linear state-space models ``x' = A x + B u``, ``y = C x + D u`` about the static
    /// aeroelastic equilibrium at ``aero.flight.speed`` (m/s) of the full and reduced models
    /// of ``[linearize]``, as a ``LinearizeResult`` of ``LinearModel``s (as ``flexwing
    /// linearize``; signals, units and signs: docs/control.md).
    ///
    /// Keyword arguments: ``speed`` (m/s), ``inputs``, ``outputs`` (lists of names) and
    /// ``states`` (``"velocities"`` or ``"momenta"``) override ``aero.flight.speed`` and
    /// ``[linearize]``; ``progress`` and ``check`` as ``statics`` (``check`` raises
    /// ``SolverError`` if a model has no stable equilibrium, past the divergence speed).
    #[pyo3(signature = (**kwargs))]
    fn linearize<'py>(
        &self,
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            let kw = Kwargs::new(
                py,
                kwargs,
                &["speed", "inputs", "outputs", "states", "progress", "check"],
                "linearize",
            )?;
            let mut case = self.case.clone();
            if let Some(v) = kw.get("speed")? {
                let speed = crate::arrays::number(&v, "speed")?;
                match case.aero.as_mut() {
                    Some(aero) => aero.flight.speed = Some(speed),
                    None => return Err(errors::input(py, "speed", "the case has no [aero] table")),
                }
            }
            let mut spec = case.linearize.clone().unwrap_or_default();
            for (key, slot) in [("inputs", &mut spec.inputs), ("outputs", &mut spec.outputs)] {
                if let Some(v) = kw.get(key)? {
                    let list = v
                        .try_iter()
                        .and_then(|it| {
                            it.map(|x| x.and_then(|x| crate::arrays::text(&x, key)))
                                .collect::<PyResult<Vec<String>>>()
                        })
                        .map_err(|_| errors::argument_type(py, key, "must be a list of names"))?;
                    *slot = Some(list);
                }
            }
            if let Some(v) = kw.get("states")? {
                spec.states = Some(match crate::arrays::text(&v, "states")?.as_str() {
                    "velocities" => flexwing_case::StatesSpec::Velocities,
                    "momenta" => flexwing_case::StatesSpec::Momenta,
                    other => {
                        return Err(errors::input(
                            py,
                            "states",
                            &format!("expected \"velocities\" or \"momenta\", got {other:?}"),
                        ))
                    }
                });
            }
            case.linearize = Some(spec);
            run_with(py, &kw, &case, Analysis::Linearize)
        })
    }

    /// Run the analysis ``"modes"``, ``"static"``, ``"dynamic"``, ``"flutter"``, ``"linearize"``,
    /// ``"study"``, ``"gust"`` or ``"turbulence"`` (as the methods of the same names; ``"gust"``
    /// is ``gust_family``).
    #[pyo3(signature = (analysis, **kwargs))]
    fn run<'py>(
        &self,
        py: Python<'py>,
        analysis: &Bound<'py, PyAny>,
        kwargs: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let name = errors::guard(py, || crate::arrays::text(analysis, "analysis"))?;
        let analysis = crate::run::parse(py, &name, "analysis")?;
        self.analysis(py, analysis, kwargs, "run")
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> crate::Reduce<'py, (String, Option<String>)> {
        let py = slf.py();
        errors::guard(py, || {
            let this = slf.get();
            let text = this
                .case
                .to_toml_string()
                .map_err(|e| errors::case(py, &e))?;
            Ok((
                slf.get_type().getattr("from_toml")?,
                (text, this.case.file().map(str::to_string)),
            ))
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyCase>()
            .is_ok_and(|o| o.get().case == self.case)
    }

    fn __repr__(&self) -> String {
        let what = match (&self.case.title, self.case.file()) {
            (Some(t), _) => format!("{t:?}"),
            (None, Some(f)) => format!("file={f:?}"),
            (None, None) => String::new(),
        };
        format!("Case({what})")
    }
}

/// Run `analysis` on `case` with the keyword arguments every analysis takes: `progress` (a
/// callable) and `check` (a bool, default true).
fn run_with<'py>(
    py: Python<'py>,
    kw: &Kwargs<'py>,
    case: &Case,
    analysis: Analysis,
) -> PyResult<Bound<'py, PyAny>> {
    let progress =
        crate::progress::callback(py, kw.get("progress")?, "callback(done: float, label: str)")?;
    let check = match kw.get("check")? {
        None => true,
        Some(v) => v
            .extract::<bool>()
            .map_err(|_| errors::argument_type(py, "check", "must be True or False"))?,
    };
    run_case(py, case, analysis, progress, check)
}

impl PyCase {
    fn analysis<'py>(
        &self,
        py: Python<'py>,
        analysis: Analysis,
        kwargs: Option<&Bound<'py, PyDict>>,
        function: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        errors::guard(py, || {
            // `check` for every analysis, as the stubs declare (modes either complete or fail).
            let kw = Kwargs::new(py, kwargs, &["progress", "check"], function)?;
            run_with(py, &kw, &self.case, analysis)
        })
    }
}
