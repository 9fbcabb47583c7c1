//! Keyword arguments checked by name: the functions that take options or the keys of a case
//! take them as `**kwargs` and check them here, so that a misspelt keyword is an
//! `ArgumentTypeError` (a `TypeError` and a `FlexwingError`) naming it and listing the accepted
//! ones, as every other bad argument.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::errors;

/// The keyword arguments of one call.
pub struct Kwargs<'py> {
    dict: Option<Bound<'py, PyDict>>,
}

impl<'py> Kwargs<'py> {
    /// Check that every keyword of `kwargs` is one of `allowed`; `function` names the call.
    pub fn new(
        py: Python<'py>,
        kwargs: Option<&Bound<'py, PyDict>>,
        allowed: &[&str],
        function: &str,
    ) -> PyResult<Self> {
        if let Some(d) = kwargs {
            for key in d.keys() {
                let name = key
                    .cast::<PyString>()
                    .map(|s| s.to_string())
                    .unwrap_or_else(|_| format!("{key}"));
                if !allowed.contains(&name.as_str()) {
                    return Err(errors::argument_type(
                        py,
                        &name,
                        &format!(
                            "{function}() got an unexpected keyword argument; it takes {}",
                            allowed.join(", ")
                        ),
                    ));
                }
            }
        }
        Ok(Self {
            dict: kwargs.cloned(),
        })
    }

    /// The value of `name`, if given and not `None`.
    pub fn get(&self, name: &str) -> PyResult<Option<Bound<'py, PyAny>>> {
        let Some(d) = &self.dict else { return Ok(None) };
        Ok(d.get_item(name)?.filter(|v| !v.is_none()))
    }
}
