//! [`PyEnvPool`]: adapters' `ThreadEnvPool` (EnvPool's asynchronous mode) as a Python
//! object; the Python class `robosuite_rs.pool.EnvPool` delegates to it.

use crate::convert::{py_into_value, space_spec, value_to_py, value_view_to_py};
use crate::errors::to_pyerr;
use crate::fork::{ForkAwareGuard, ForkAwareMutex};
use crate::pyenv::{extract_seeds, lock_with_gil, metadata_into_py, vector_info_into_py};
use adapters::{BatchSpace, ThreadEnvPool, ThreadOptions};
use gym_core::{AnySpace, BoxedEnv, Metadata, Value};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A pool and the batch of actions that Python's actions are written into.
struct PoolState {
    pool: ThreadEnvPool<BoxedEnv>,
    actions: Value,
}

/// A pool of environments stepped asynchronously on Rust threads with the GIL released:
/// `recv` returns the first `batch_size` to finish (their ids in `info["env_id"]`), `send`
/// gives those their next actions. As for [`PyVecEnv`](crate::PyVecEnv), a call takes one
/// lock, converts actions once into a kept batch and copies observations once into NumPy.
#[pyclass(name = "NativeEnvPool", module = "robosuite_rs._native")]
pub struct PyEnvPool {
    state: ForkAwareMutex<PoolState>,
    observation_space: AnySpace,
    action_space: AnySpace,
    batched_action_space: AnySpace,
    metadata: Metadata,
}

impl PyEnvPool {
    /// Pools `envs`, returning `batch_size` per `recv`, on the threads `options` asks for.
    ///
    /// # Errors
    /// `ValueError` for an empty list, differing spaces or a batch size outside
    /// `1..=len(envs)`.
    pub fn new(envs: Vec<BoxedEnv>, batch_size: usize, options: ThreadOptions) -> PyResult<Self> {
        let metadata = envs
            .first()
            .map(|e| e.metadata().clone())
            .unwrap_or_default();
        let pool = ThreadEnvPool::with_options(envs, batch_size, options).map_err(to_pyerr)?;
        let observation_space = pool.single_observation_space().clone();
        let action_space = pool.single_action_space().clone();
        let batched_action_space = action_space.batch_space(batch_size).map_err(to_pyerr)?;
        let actions = action_space.create_empty_batch(batch_size);
        Ok(Self {
            state: ForkAwareMutex::new(PoolState { pool, actions }),
            observation_space,
            action_space,
            batched_action_space,
            metadata,
        })
    }

    fn lock(&self) -> gym_core::Result<ForkAwareGuard<'_, PoolState>> {
        self.state.lock()
    }
}

/// What `recv` returns to Python.
type RecvPy<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyDict>,
);

#[pymethods]
impl PyEnvPool {
    /// The number of environments.
    #[getter]
    fn num_envs(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(lock_with_gil(py, &self.state)
            .map_err(to_pyerr)?
            .pool
            .num_envs())
    }

    /// How many environments each `recv` returns.
    #[getter]
    fn batch_size(&self, py: Python<'_>) -> PyResult<usize> {
        Ok(lock_with_gil(py, &self.state)
            .map_err(to_pyerr)?
            .pool
            .batch_size())
    }

    /// Queues a reset of every environment (an integer seed gives env `i` `seed + i`; a
    /// list gives one optional seed per env); `recv` returns them.
    #[pyo3(signature = (seed=None))]
    fn async_reset(&self, py: Python<'_>, seed: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        let seeds = extract_seeds(seed)?;
        py.detach(|| self.lock()?.pool.reset(seeds))
            .map_err(to_pyerr)
    }

    /// `recv() -> (obs, rewards, terminations, truncations, info)` for the first
    /// `batch_size` environments to finish; `info["env_id"]` holds their ids.
    /// With `copy=False` the observations are read-only views of the pool's batch (no
    /// copy), overwritten by the next `recv`.
    #[pyo3(signature = (copy=true))]
    fn recv<'py>(slf: &Bound<'py, Self>, copy: bool) -> PyResult<RecvPy<'py>> {
        let py = slf.py();
        let this = slf.borrow();
        let mut state = lock_with_gil(py, &this.state).map_err(to_pyerr)?;
        let pool = &mut state.pool;
        let s = py.detach(move || pool.recv()).map_err(to_pyerr)?;
        let info_py = vector_info_into_py(py, s.infos)?;
        let ids: Vec<i64> = s.env_ids.iter().map(|&i| i as i64).collect();
        info_py.set_item("env_id", PyArray1::from_vec(py, ids))?;
        let observations = if copy {
            value_to_py(py, s.observations, false)?
        } else {
            // SAFETY: the pool's batch is allocated once, with the pool, which `slf` owns
            // and never replaces; `slf` is the views' base object.
            unsafe { value_view_to_py(py, s.observations, slf.as_any())? }
        };
        Ok((
            observations,
            PyArray1::from_slice(py, s.rewards),
            PyArray1::from_slice(py, s.terminations),
            PyArray1::from_slice(py, s.truncations),
            info_py,
        ))
    }

    /// Gives the environments `env_ids` (those of the last `recv`, one per row of
    /// `actions`) their next actions.
    fn send(&self, py: Python<'_>, actions: &Bound<'_, PyAny>, env_ids: Vec<i64>) -> PyResult<()> {
        let ids = env_ids
            .iter()
            .map(|&i| {
                usize::try_from(i)
                    .map_err(|_| PyValueError::new_err(format!("env_id {i} is negative")))
            })
            .collect::<PyResult<Vec<_>>>()?;
        let mut state = lock_with_gil(py, &self.state).map_err(to_pyerr)?;
        let PoolState {
            pool,
            actions: batch,
        } = &mut *state;
        py_into_value(actions, &self.batched_action_space, batch)?;
        let batch = &*batch;
        py.detach(move || pool.send(batch, &ids)).map_err(to_pyerr)
    }

    /// The description of one environment's observation space.
    fn observation_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        space_spec(py, &self.observation_space)
    }

    /// The description of one environment's action space.
    fn action_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        space_spec(py, &self.action_space)
    }

    /// The metadata of environment 0.
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        metadata_into_py(py, &self.metadata)
    }

    /// Closes every environment and joins the worker threads; calling it again does
    /// nothing.
    /// In a forked child whose copy was locked at the fork it does nothing.
    fn close(&self, py: Python<'_>) {
        py.detach(|| {
            if let Ok(mut state) = self.lock() {
                state.pool.close();
            }
        });
    }
}
