//! Python values into the case crate's serde types, in two steps: first [`plain_value`] makes
//! plain data of the caller's values (dicts with string keys, lists, strings, booleans, finite
//! numbers, `None`) — the one place where the caller's objects are looked at — then the type's
//! own `Deserialize` reads that data, so a Python dict or keyword arguments take the case
//! file's keys, defaults and checks, with errors naming the key path (`beam.section.EI`,
//! `loads[0].fy`, `damping.alpha`). `case.rs`, `model.rs` and `equations.rs` read their
//! arguments here.
//!
//! The conversion is bounded: a dict or list that contains itself, or nesting deeper than
//! [`MAX_DEPTH`], is an error naming the path where it went too deep (no unbounded recursion,
//! no stack overflow). Non-finite numbers are refused where they are met (a case never holds
//! NaN). NumPy arrays and scalars become lists and numbers (masked arrays are refused: their
//! masked values would be used); other objects with `__index__` or `__float__` become numbers.
//! The serde reader then sees only plain data, so no code of the caller's runs inside it: an
//! exception the caller's `__float__`, `__index__` or `tolist` raises propagates as itself
//! unless it is a `TypeError`/`ValueError`/`OverflowError` ([`errors::foreign`]).

use flexwing_case::CaseError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use pythonize::Depythonizer;
use serde::de::DeserializeOwned;

use crate::errors;

/// How deep dicts and lists may nest in a value (a case file nests 5 deep at most:
/// `aero.flight.changes[0].t`); deeper is taken for a value that contains itself.
pub const MAX_DEPTH: usize = 32;

/// One step of a key path.
#[derive(Clone)]
enum Step {
    Key(String),
    Index(usize),
}

/// The key path of `steps` under `prefix` (`loads[0].fy`), the case file's notation.
fn path_text(prefix: &str, steps: &[Step]) -> String {
    let mut out = prefix.to_string();
    for s in steps {
        match s {
            Step::Key(k) => {
                if !out.is_empty() {
                    out.push('.');
                }
                out.push_str(k);
            }
            Step::Index(i) => out.push_str(&format!("[{i}]")),
        }
    }
    out
}

/// Why a value cannot be plain data: a case error naming its path, or the caller's own
/// exception (propagated as itself).
pub enum Bad {
    /// A value the case file could not hold, at `key`.
    Value(CaseError),
    /// An exception of the caller's code ([`errors::foreign`]).
    Python(PyErr),
}

struct Walk<'a> {
    prefix: &'a str,
    steps: Vec<Step>,
}

impl Walk<'_> {
    fn bad(&self, reason: impl Into<String>) -> Bad {
        let key = path_text(self.prefix, &self.steps);
        Bad::Value(CaseError {
            key: (!key.is_empty()).then_some(key),
            ..CaseError::new(reason)
        })
    }

    /// A Python error of the caller's code at this path: its own if foreign, else a value
    /// error with its message.
    fn python(&self, py: Python<'_>, e: PyErr, what: &str) -> Bad {
        if errors::foreign(py, &e) {
            Bad::Python(e)
        } else {
            self.bad(format!("{what} ({})", e.value(py)))
        }
    }

    fn value<'py>(&mut self, obj: &Bound<'py, PyAny>) -> Result<Bound<'py, PyAny>, Bad> {
        let py = obj.py();
        if self.steps.len() > MAX_DEPTH {
            // The path's first steps say where it starts; the rest repeats.
            let key = format!("{}…", path_text(self.prefix, &self.steps[..4]));
            return Err(Bad::Value(CaseError {
                key: Some(key),
                ..CaseError::new(format!(
                    "nested more than {MAX_DEPTH} levels deep (a dict or list that contains \
                     itself?)"
                ))
            }));
        }
        if obj.is_none() || obj.is_instance_of::<PyBool>() || obj.is_instance_of::<PyString>() {
            return Ok(obj.clone());
        }
        if obj.is_instance_of::<PyFloat>() {
            let v: f64 = obj
                .extract()
                .map_err(|e| self.python(py, e, "not a number"))?;
            return self.finite(py, v);
        }
        if obj.is_instance_of::<PyInt>() {
            return Ok(obj.clone());
        }
        if let Ok(d) = obj.cast::<PyDict>() {
            let out = PyDict::new(py);
            for (k, v) in d.iter() {
                let Ok(key) = k.cast::<PyString>() else {
                    let type_name = type_name(&k);
                    return Err(self.bad(format!(
                        "invalid type: the key {} ({type_name}); the keys of a table are texts",
                        short_repr(&k)
                    )));
                };
                let key_text = key.to_string();
                self.steps.push(Step::Key(key_text));
                let plain = self.value(&v);
                self.steps.pop();
                out.set_item(key, plain?).map_err(Bad::Python)?;
            }
            return Ok(out.into_any());
        }
        if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
            let items: Vec<Bound<'py, PyAny>> = match obj.cast::<PyList>() {
                Ok(l) => l.iter().collect(),
                Err(_) => obj
                    .cast::<PyTuple>()
                    .map(|t| t.iter().collect())
                    .unwrap_or_default(),
            };
            let mut out = Vec::with_capacity(items.len());
            for (i, v) in items.iter().enumerate() {
                self.steps.push(Step::Index(i));
                let plain = self.value(v);
                self.steps.pop();
                out.push(plain?);
            }
            return PyList::new(py, out)
                .map(Bound::into_any)
                .map_err(Bad::Python);
        }
        if obj.hasattr("dtype").map_err(Bad::Python)?
            && obj.hasattr("tolist").map_err(Bad::Python)?
        {
            if crate::arrays::is_masked(obj).map_err(Bad::Python)? {
                return Err(self.bad(crate::arrays::MASKED));
            }
            let list = obj
                .call_method0("tolist")
                .map_err(|e| self.python(py, e, "cannot be read"))?;
            // `tolist` of a NumPy value gives Python lists and numbers: one level, no loop.
            if list.hasattr("dtype").map_err(Bad::Python)? {
                return Err(self.bad(format!("invalid type: {}", type_name(obj))));
            }
            return self.value(&list);
        }
        if obj.hasattr("__index__").map_err(Bad::Python)? {
            return obj
                .call_method0("__index__")
                .map_err(|e| self.python(py, e, "not an integer"));
        }
        if obj.hasattr("__float__").map_err(Bad::Python)? {
            let v: f64 = obj
                .call_method0("__float__")
                .and_then(|f| f.extract())
                .map_err(|e| self.python(py, e, "not a number"))?;
            return self.finite(py, v);
        }
        Err(self.bad(format!(
            "invalid type: {}, expected a number, a text, a list or a table (dict)",
            type_name(obj)
        )))
    }

    fn finite<'py>(&self, py: Python<'py>, v: f64) -> Result<Bound<'py, PyAny>, Bad> {
        if v.is_finite() {
            Ok(PyFloat::new(py, v).into_any())
        } else {
            Err(self.bad(format!("must be finite, got {}", finite_word(v))))
        }
    }
}

/// `NaN`, `inf`, `-inf`: the case crate's words.
fn finite_word(v: f64) -> &'static str {
    if v.is_nan() {
        "NaN"
    } else if v > 0.0 {
        "inf"
    } else {
        "-inf"
    }
}

/// The type name of `obj`, for messages.
pub fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// A short `repr` of `obj` for messages (at most 40 characters).
fn short_repr(obj: &Bound<'_, PyAny>) -> String {
    let r = obj
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "?".into());
    if r.chars().count() > 40 {
        format!("{}…", r.chars().take(39).collect::<String>())
    } else {
        r
    }
}

/// `obj` as plain data (see the module's documentation); errors name the path under `prefix`.
pub fn plain_value<'py>(obj: &Bound<'py, PyAny>, prefix: &str) -> Result<Bound<'py, PyAny>, Bad> {
    Walk {
        prefix,
        steps: Vec::new(),
    }
    .value(obj)
}

/// `obj` read as the serde type `T`: the outer error is the caller's own exception (to
/// propagate as itself), the inner one the `CaseError` of the value's key path with `prefix` in
/// front (`loads`: `loads[0].fy`; empty: the path alone), in the case file's words.
pub fn read<T: DeserializeOwned>(
    obj: &Bound<'_, PyAny>,
    prefix: &str,
) -> PyResult<Result<T, CaseError>> {
    let value = match plain_value(obj, prefix) {
        Ok(v) => v,
        Err(Bad::Python(e)) => return Err(e),
        Err(Bad::Value(e)) => return Ok(Err(e)),
    };
    let mut de = Depythonizer::from_object(&value);
    Ok(
        serde_path_to_error::deserialize::<_, T>(&mut de).map_err(|e| {
            let path = e.path().to_string();
            let key = match (path.as_str(), prefix) {
                (".", "") => None,
                (".", p) => Some(p.to_string()),
                (path, "") => Some(path.to_string()),
                (path, p) if path.starts_with('[') => Some(format!("{p}{path}")),
                (path, p) => Some(format!("{p}.{path}")),
            };
            let reason = flexwing_case::one_line(&e.inner().to_string());
            CaseError {
                key,
                ..CaseError::new(reason)
            }
        }),
    )
}

/// [`read`], an error raised as `InputError` naming the key (`ArgumentTypeError` for a value
/// of the wrong type), or `CaseFileError` with `case_file`.
pub fn read_or_raise<T: DeserializeOwned>(
    obj: &Bound<'_, PyAny>,
    prefix: &str,
    case_file: bool,
) -> PyResult<T> {
    let py = obj.py();
    errors::guard(py, || {
        read(obj, prefix)?.map_err(|e| match (case_file, &e.key) {
            (false, Some(key)) if e.reason.starts_with("invalid type") => {
                errors::argument_type(py, key, &e.reason)
            }
            (false, Some(key)) => errors::input(py, key, &e.reason),
            _ => errors::case(py, &e),
        })
    })
}

/// The first non-finite number in the plain data `value` (what `pythonize` makes of a case),
/// as the `CaseError` of its key path: a case read from TOML (where `nan` and `inf` parse) is
/// refused at construction as a dict is.
pub fn first_non_finite(value: &Bound<'_, PyAny>) -> Option<CaseError> {
    fn walk(v: &Bound<'_, PyAny>, w: &mut Walk<'_>) -> Option<CaseError> {
        if w.steps.len() > MAX_DEPTH {
            return None;
        }
        if let Ok(f) = v.cast::<PyFloat>() {
            let x = f.value();
            return (!x.is_finite()).then(|| match w.finite(v.py(), x) {
                Err(Bad::Value(e)) => e,
                _ => CaseError::new("must be finite"),
            });
        }
        if let Ok(d) = v.cast::<PyDict>() {
            for (k, x) in d.iter() {
                w.steps.push(Step::Key(k.to_string()));
                let found = walk(&x, w);
                w.steps.pop();
                if found.is_some() {
                    return found;
                }
            }
        } else if let Ok(l) = v.cast::<PyList>() {
            for (i, x) in l.iter().enumerate() {
                w.steps.push(Step::Index(i));
                let found = walk(&x, w);
                w.steps.pop();
                if found.is_some() {
                    return found;
                }
            }
        }
        None
    }
    walk(
        value,
        &mut Walk {
            prefix: "",
            steps: Vec::new(),
        },
    )
}
