//! [`PyEnv`] and [`PyVecEnv`]: any boxed environment (and a vector of them) as a Python
//! object; the Python classes `robosuite_rs.wrappers.RustEnv` (a `gymnasium.Env`) and
//! `robosuite_rs.vector.RustVectorEnv` (a `gymnasium.vector.VectorEnv`) delegate to them.

use crate::convert::{
    array_to_py, info_into_py, py_into_value, py_to_info, space_spec, value_into_py, value_to_py,
    value_view_to_py,
};
use crate::errors::to_pyerr;
use crate::fork::{ForkAwareGuard, ForkAwareMutex};
use adapters::BatchSpace;
use adapters::vector::{
    Seeds, ThreadOptions, ThreadVectorEnv, VectorEnv, VectorInfo, VectorInfoValue,
};
use gym_core::{AnySpace, BoxedEnv, Frame, Info, Metadata, Value};
use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

/// A seed from Python: a non-negative integer that fits in 64 bits, or `None`.
pub(crate) fn extract_seed(seed: Option<&Bound<'_, PyAny>>) -> PyResult<Option<u64>> {
    match seed {
        None => Ok(None),
        Some(s) if s.is_none() => Ok(None),
        Some(s) => s.extract::<u64>().map(Some).map_err(|_| {
            PyValueError::new_err(format!(
                "seed must be a non-negative integer below 2**64, got {s}"
            ))
        }),
    }
}

/// Vector seeds from Python: `None`, an integer (env `i` gets `seed + i`), or a sequence
/// of optional integers, one per env.
pub(crate) fn extract_seeds(seed: Option<&Bound<'_, PyAny>>) -> PyResult<Seeds> {
    let list = seed
        .filter(|s| !s.is_instance_of::<pyo3::types::PyString>())
        .and_then(|s| s.extract::<Vec<Bound<'_, PyAny>>>().ok());
    match list {
        Some(items) => Ok(Seeds::PerEnv(
            items
                .iter()
                .map(|item| extract_seed(Some(item)))
                .collect::<PyResult<Vec<_>>>()?,
        )),
        None => Ok(extract_seed(seed)?.into()),
    }
}

/// `metadata` as a Python dict: `{"render_modes": [...], "render_fps": fps or None}`.
pub(crate) fn metadata_into_py<'py>(py: Python<'py>, m: &Metadata) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let modes: Vec<&str> = m.render_modes.iter().map(|r| r.as_str()).collect();
    d.set_item("render_modes", PyList::new(py, modes)?)?;
    d.set_item("render_fps", m.render_fps)?;
    Ok(d)
}

/// Any [`BoxedEnv`] as a Python object with Gymnasium's methods (`reset`, `step`, `close`)
/// and the descriptions of its spaces. Calls release the GIL while the environment runs.
/// Errors are Python exceptions carrying the Rust message (see [`to_pyerr`]); the
/// environment stays usable after an invalid action.
#[pyclass(name = "NativeEnv", module = "robosuite_rs._native")]
pub struct PyEnv {
    state: ForkAwareMutex<EnvState>,
    observation_space: AnySpace,
    action_space: AnySpace,
    metadata: Metadata,
}

/// An environment and the buffers its steps go through: the action Python's action is
/// written into, and the observation and info `step_into` writes in place.
struct EnvState {
    env: BoxedEnv,
    action: Value,
    observation: Value,
    info: Info,
}

/// A locked [`PyEnv`]'s environment.
pub struct EnvGuard<'a>(ForkAwareGuard<'a, EnvState>);

impl std::ops::Deref for EnvGuard<'_> {
    type Target = BoxedEnv;
    fn deref(&self) -> &BoxedEnv {
        &self.0.env
    }
}

impl std::ops::DerefMut for EnvGuard<'_> {
    fn deref_mut(&mut self) -> &mut BoxedEnv {
        &mut self.0.env
    }
}

impl PyEnv {
    /// Wraps `env`.
    pub fn new(env: BoxedEnv) -> Self {
        let observation_space = env.observation_space().clone();
        let action_space = env.action_space().clone();
        let metadata = env.metadata().clone();
        Self {
            state: ForkAwareMutex::new(EnvState {
                action: action_space.zero_element(),
                observation: observation_space.zero_element(),
                info: Info::new(),
                env,
            }),
            observation_space,
            action_space,
            metadata,
        }
    }

    /// Locks the environment (ignoring poisoning by an earlier panic).
    ///
    /// # Errors
    /// As [`ForkAwareMutex::lock`]: a call from inside another call on this env on the same
    /// thread, or from a forked child while another thread of the parent held it.
    pub fn lock(&self) -> gym_core::Result<EnvGuard<'_>> {
        self.state.lock().map(EnvGuard)
    }
}

/// What `step` returns to Python: `(obs, reward, terminated, truncated, info)`.
type StepPy<'py> = (Bound<'py, PyAny>, f64, bool, bool, Bound<'py, PyDict>);

#[pymethods]
impl PyEnv {
    /// `reset(seed=None, options=None) -> (obs, info)`: fresh arrays of the space's dtypes.
    #[pyo3(signature = (seed=None, options=None))]
    fn reset<'py>(
        &self,
        py: Python<'py>,
        seed: Option<&Bound<'py, PyAny>>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>)> {
        let seed = extract_seed(seed)?;
        let options = options
            .map(py_to_info)
            .transpose()?
            .filter(|o| !o.is_empty());
        let (obs, info) = py
            .detach(|| self.lock()?.reset(seed, options.as_ref()))
            .map_err(to_pyerr)?;
        Ok((value_into_py(py, obs, false)?, info_into_py(py, &info)?))
    }

    /// `step(action) -> (obs, reward: float, terminated: bool, truncated: bool, info)`.
    /// The action is converted once (a NumPy array of the space's shape is copied straight
    /// into the kept action), the env steps in place (`step_into`) with the GIL released,
    /// and the observation is copied once into a fresh NumPy array.
    fn step<'py>(&self, py: Python<'py>, action: &Bound<'py, PyAny>) -> PyResult<StepPy<'py>> {
        let mut state = lock_with_gil(py, &self.state).map_err(to_pyerr)?;
        let EnvState {
            env,
            action: buffer,
            observation,
            info,
        } = &mut *state;
        py_into_value(action, &self.action_space, buffer)?;
        let (buffer, obs, inf) = (&*buffer, &mut *observation, &mut *info);
        let t = py
            .detach(move || env.step_into(buffer, obs, inf))
            .map_err(to_pyerr)?;
        Ok((
            value_to_py(py, observation, false)?,
            t.reward,
            t.terminated,
            t.truncated,
            info_into_py(py, info)?,
        ))
    }

    /// The observation space's description (see `robosuite_rs.spaces.from_spec`).
    fn observation_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        space_spec(py, &self.observation_space)
    }

    /// The action space's description (see `robosuite_rs.spaces.from_spec`).
    fn action_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        space_spec(py, &self.action_space)
    }

    /// `{"render_modes": [...], "render_fps": ...}`.
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        metadata_into_py(py, &self.metadata)
    }

    /// The render mode chosen when the env was made (`"rgb_array"`, `"depth_array"`) or
    /// `None`.
    fn render_mode(&self, py: Python<'_>) -> PyResult<Option<&'static str>> {
        let state = lock_with_gil(py, &self.state).map_err(to_pyerr)?;
        Ok(state.env.render_mode().map(|m| m.as_str()))
    }

    /// `render()`: the frame of the render mode (an `H×W×3` uint8 array for `rgb_array`,
    /// `H×W` float32 for `depth_array`, a str for `ansi`) or `None` without a render mode.
    /// The GIL is released while drawing; the frame is moved into NumPy without a copy.
    fn render<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        let frame = py.detach(|| self.lock()?.render()).map_err(to_pyerr)?;
        Ok(frame.map(|f| frame_into_py(py, f)))
    }

    /// Closes the environment; calling it again does nothing.
    fn close(&self, py: Python<'_>) {
        py.detach(|| {
            if let Ok(mut env) = self.lock() {
                env.close();
            }
        });
    }

    fn __repr__(&self) -> String {
        format!(
            "NativeEnv(observation_space={}, action_space={})",
            self.observation_space, self.action_space
        )
    }
}

/// A rendered frame as a NumPy array (moved, not copied) or a Python str.
pub(crate) fn frame_into_py(py: Python<'_>, frame: Frame) -> Bound<'_, PyAny> {
    match frame {
        Frame::Rgb(a) => PyArray3::from_owned_array(py, a).into_any(),
        Frame::Depth(a) => PyArray2::from_owned_array(py, a).into_any(),
        Frame::Ansi(s) => pyo3::types::PyString::new(py, &s).into_any(),
    }
}

/// Locks `mutex` without ever blocking while holding the GIL: when another thread holds
/// it (a step running with the GIL released, which needs the GIL back to return), this
/// thread waits for it with the GIL released, then tries again.
///
/// # Errors
/// As [`ForkAwareMutex::lock`].
pub(crate) fn lock_with_gil<'a, T: Send>(
    py: Python<'_>,
    mutex: &'a ForkAwareMutex<T>,
) -> gym_core::Result<ForkAwareGuard<'a, T>> {
    loop {
        if let Some(guard) = mutex.try_lock()? {
            return Ok(guard);
        }
        py.detach(|| mutex.lock().map(drop))?;
    }
}

/// A vector env and the batch of actions that Python's actions are written into.
struct VecState {
    vec: ThreadVectorEnv<BoxedEnv>,
    actions: gym_core::Value,
}

/// Several boxed environments stepped in parallel on persistent Rust worker threads
/// (adapters' [`ThreadVectorEnv`], Gymnasium's `NEXT_STEP` autoreset) with the GIL
/// released. Observations come back batched (`(n, ...)` arrays), infos with Gymnasium's
/// `_key` masks.
///
/// A step takes one lock, converts the actions once (a NumPy array of the action space's
/// shape is copied straight into the batch the vector env reads, casting a float dtype to
/// the space's), steps with the GIL released (environments that write rows, the robosuite
/// tasks, write their observations, camera images included, straight into the batch), and
/// copies the observations once more into fresh NumPy arrays, or with `copy=False` returns
/// read-only views of the batch.
#[pyclass(name = "NativeVecEnv", module = "robosuite_rs._native")]
pub struct PyVecEnv {
    state: ForkAwareMutex<VecState>,
    observation_space: AnySpace,
    action_space: AnySpace,
    batched_action_space: AnySpace,
    metadata: Metadata,
    num_envs: usize,
}

impl PyVecEnv {
    /// Vectorises `envs` on the threads `options` asks for.
    ///
    /// # Errors
    /// `ValueError` for an empty list or differing spaces.
    pub fn new(envs: Vec<BoxedEnv>, options: ThreadOptions) -> PyResult<Self> {
        let vec = ThreadVectorEnv::with_options(envs, options).map_err(to_pyerr)?;
        let actions = vec.single_action_space().create_empty_batch(vec.num_envs());
        Ok(Self {
            observation_space: vec.single_observation_space().clone(),
            action_space: vec.single_action_space().clone(),
            batched_action_space: vec.action_space().clone(),
            metadata: vec.metadata().clone(),
            num_envs: vec.num_envs(),
            state: ForkAwareMutex::new(VecState { vec, actions }),
        })
    }
}

/// A batched info as Gymnasium's dict: one array per key (length `n`) and a `_key` mask.
pub(crate) fn vector_info_into_py<'py>(
    py: Python<'py>,
    info: &VectorInfo,
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    for (k, v) in info.iter() {
        let value = match v {
            VectorInfoValue::Bool(b) => PyArray1::from_slice(py, b).into_any(),
            VectorInfoValue::Int(x) => PyArray1::from_slice(py, x).into_any(),
            VectorInfoValue::Float(x) => PyArray1::from_slice(py, x).into_any(),
            VectorInfoValue::Array(a) => array_to_py(py, a),
            VectorInfoValue::Objects(items) => {
                let objs = items
                    .iter()
                    .map(|o| match o {
                        None => Ok(py.None().into_bound(py)),
                        Some(x) => {
                            let d = info_into_py(py, &Info::new().with("v", x.clone()))?;
                            Ok(d.get_item("v")?.expect("just inserted"))
                        }
                    })
                    .collect::<PyResult<Vec<_>>>()?;
                object_array(py, objs)?
            }
            VectorInfoValue::Observations(items) => {
                let objs = items
                    .iter()
                    .map(|o| match o {
                        None => Ok(py.None().into_bound(py)),
                        Some(x) => value_to_py(py, x, false),
                    })
                    .collect::<PyResult<Vec<_>>>()?;
                object_array(py, objs)?
            }
            VectorInfoValue::Map(m) => vector_info_into_py(py, m)?.into_any(),
        };
        out.set_item(k, value)?;
    }
    Ok(out)
}

/// A NumPy object array holding `items` (as Gymnasium builds for `final_obs`).
fn object_array<'py>(
    py: Python<'py>,
    items: Vec<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let arr = py
        .import("numpy")?
        .call_method1("empty", (items.len(), "object"))?;
    for (i, item) in items.into_iter().enumerate() {
        arr.set_item(i, item)?;
    }
    Ok(arr)
}

/// What a vector step returns to Python.
type VecStepPy<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyArray1<bool>>,
    Bound<'py, PyDict>,
);

#[pymethods]
impl PyVecEnv {
    /// The number of environments.
    #[getter]
    fn num_envs(&self) -> usize {
        self.num_envs
    }

    /// `reset(seed=None, options=None) -> (batched obs, infos)`. `seed`: an integer (env
    /// `i` gets `seed + i`) or one optional seed per env; `options["reset_mask"]` (a bool
    /// array) resets only some envs, the other options go to every env.
    /// With `copy=False` the observations are views of the batch, as for `step`.
    #[pyo3(signature = (seed=None, options=None, copy=true))]
    fn reset<'py>(
        slf: &Bound<'py, Self>,
        seed: Option<&Bound<'py, PyAny>>,
        options: Option<&Bound<'py, PyDict>>,
        copy: bool,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyDict>)> {
        let py = slf.py();
        let this = slf.borrow();
        let seeds = extract_seeds(seed)?;
        let options = options.map(py_to_info).transpose()?;
        let mut state = lock_with_gil(py, &this.state).map_err(to_pyerr)?;
        let vec = &mut state.vec;
        let (obs, info) = py
            .detach(move || vec.reset(seeds, options.as_ref()))
            .map_err(to_pyerr)?;
        let observations = if copy {
            value_to_py(py, obs, false)?
        } else {
            // SAFETY: as in `step`.
            unsafe { value_view_to_py(py, obs, slf.as_any())? }
        };
        Ok((observations, vector_info_into_py(py, info)?))
    }

    /// `step(actions, copy=True) -> (batched obs, rewards, terminations, truncations,
    /// infos)` for batched actions (an `(n, ...)` array for Box action spaces). With
    /// `copy=False` the observations are read-only views of the vector env's batch (no
    /// copy), overwritten by the next `step` or `reset`.
    #[pyo3(signature = (actions, copy=true))]
    fn step<'py>(
        slf: &Bound<'py, Self>,
        actions: &Bound<'py, PyAny>,
        copy: bool,
    ) -> PyResult<VecStepPy<'py>> {
        let py = slf.py();
        let this = slf.borrow();
        let mut state = lock_with_gil(py, &this.state).map_err(to_pyerr)?;
        let VecState {
            vec,
            actions: batch,
        } = &mut *state;
        py_into_value(actions, &this.batched_action_space, batch)?;
        let batch = &*batch;
        let s = py.detach(move || vec.step(batch)).map_err(to_pyerr)?;
        let observations = if copy {
            value_to_py(py, s.observations, false)?
        } else {
            // SAFETY: the batch is allocated once, with the vector env, which `slf` owns
            // and never replaces; `slf` is the views' base object.
            unsafe { value_view_to_py(py, s.observations, slf.as_any())? }
        };
        Ok((
            observations,
            PyArray1::from_slice(py, s.rewards),
            PyArray1::from_slice(py, s.terminations),
            PyArray1::from_slice(py, s.truncations),
            vector_info_into_py(py, s.infos)?,
        ))
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
            if let Ok(mut state) = self.state.lock() {
                state.vec.close();
            }
        });
    }
}

/// Exports any environment (anything that converts into a [`BoxedEnv`] with
/// `gym_core::IntoBoxedEnv::boxed`) as a real `gymnasium.Env`: the Python class
/// `robosuite_rs.wrappers.RustEnv` around a [`PyEnv`]. This is the one call a Rust user
/// needs in their own pyo3 module.
///
/// # Errors
/// When the Python package `robosuite_rs` (which holds the `gymnasium.Env` shim) cannot be
/// imported.
pub fn export_env(py: Python<'_>, env: BoxedEnv) -> PyResult<Py<PyAny>> {
    let native = Py::new(py, PyEnv::new(env))?;
    let cls = py.import("robosuite_rs.wrappers")?.getattr("RustEnv")?;
    Ok(cls.call1((native,))?.unbind())
}

/// Exports an environment as the bare [`PyEnv`] (no `gymnasium.Env` shim); wrap it in
/// Python with `robosuite_rs.wrappers.RustEnv(native)`.
///
/// # Errors
/// Only when Python fails to allocate the object.
pub fn export_native_env(py: Python<'_>, env: BoxedEnv) -> PyResult<Py<PyEnv>> {
    Py::new(py, PyEnv::new(env))
}
