//! Rust errors as Python exceptions.

use gym_core::Error;
use pyo3::PyErr;
use pyo3::exceptions::{PyNotImplementedError, PyRuntimeError, PyValueError};

/// Converts a [`gym_core::Error`] into the Python exception that carries its message:
/// `ValueError` for a bad action, argument, key, env id or value (and for stepping an
/// ended episode, as robosuite does), `NotImplementedError` for an unsupported feature,
/// `RuntimeError` for everything else.
pub fn to_pyerr(e: Error) -> PyErr {
    let msg = e.to_string();
    match e {
        Error::InvalidAction(_)
        | Error::InvalidArgument { .. }
        | Error::UnknownEnv { .. }
        | Error::UnknownKey { .. }
        | Error::Space(_)
        | Error::EpisodeEnded => PyValueError::new_err(msg),
        Error::Unsupported(_) => PyNotImplementedError::new_err(msg),
        _ => PyRuntimeError::new_err(msg),
    }
}
