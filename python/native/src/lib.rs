//! The extension module `robosuite_rs._native`: everything of `robosuite_py::module`
//! under one `PyInit__native`. A crate of its own so that `robosuite-py` stays a library
//! that users' own pyo3 modules link without a second `PyInit__native`.

#[cfg(feature = "module")]
use pyo3::prelude::*;

/// The extension module.
#[cfg(feature = "module")]
#[pymodule(name = "_native")]
fn native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    robosuite_py::module::init(m)
}
