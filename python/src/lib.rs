//! The Python export of robosuite-rs.
//!
//! Without features this crate is plain Rust (built and tested by `cargo test --workspace`):
//! [`SharedEnv`](shared::SharedEnv), one environment reachable from robosuite's Python env
//! object and from the `GymWrapper` over it. The wrappers and the vector environment are
//! the `adapters` crate's (`GymWrapper`, `ThreadVectorEnv`).
//!
//! With the `python` feature it offers Rust users the one call that turns any env into a
//! `gymnasium.Env` from their own pyo3 module (`export_env`; see
//! `python/examples/own_module`):
//!
//! ```text
//! use gym_core::IntoBoxedEnv;
//! use pyo3::prelude::*;
//!
//! #[pyfunction]
//! fn make_my_env(py: Python<'_>) -> PyResult<Py<PyAny>> {
//!     robosuite_py::export_env(py, MyEnv::new().boxed())
//! }
//! ```
//!
//! The extension module `robosuite_rs._native` is the `robosuite-native` crate
//! (`python/native`, built by maturin from the repository's `pyproject.toml`): one call of
//! `module::init` (feature `python`).

pub mod fork;
pub mod shared;

#[cfg(feature = "python")]
mod convert;
#[cfg(feature = "python")]
mod errors;
#[cfg(feature = "python")]
pub mod module;
#[cfg(feature = "python")]
mod pool;
#[cfg(feature = "python")]
mod pyenv;
#[cfg(feature = "python")]
pub mod robosuite;

#[cfg(feature = "python")]
pub use errors::to_pyerr;
#[cfg(feature = "python")]
pub use pool::PyEnvPool;
#[cfg(feature = "python")]
pub use pyenv::{EnvGuard, PyEnv, PyVecEnv, export_env, export_native_env};
