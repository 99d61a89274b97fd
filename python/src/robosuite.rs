//! [`PyRobosuiteEnv`]: robosuite's environment API (`reset`, `step` → 4-tuple,
//! `action_spec`, `observation_spec`, `get_state` / `set_state`, ...) over a Rust
//! [`RobosuiteEnv`].

use crate::convert::{array_from_py, info_into_py, space_spec, value_into_py};
use crate::errors::to_pyerr;
use crate::pyenv::{PyEnv, extract_seed};
use crate::shared::SharedEnv;
use gym_core::{AnySpace, DictSpace, Env, IntoBoxedEnv, Value};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use robosuite_env::RobosuiteEnv;
use robosuite_env::saved::SavedEnv;
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

/// A robosuite environment as robosuite's Python API sees it. The Python class
/// `robosuite_rs.RobosuiteEnv` delegates to it; `gym_env` builds the GymWrapper over the
/// same (shared) environment.
#[pyclass(name = "RobosuiteEnv", module = "robosuite_rs._native")]
pub struct PyRobosuiteEnv {
    env: Arc<Mutex<RobosuiteEnv>>,
    name: String,
    observation_space: DictSpace,
    action_low: Vec<f64>,
    action_high: Vec<f64>,
}

impl PyRobosuiteEnv {
    /// Wraps `env`, made for the task `name`.
    pub fn new(env: RobosuiteEnv, name: &str) -> Self {
        let observation_space = env.observation_space().clone();
        let act = env.action_space();
        let (action_low, action_high) = (
            act.low().iter().copied().collect(),
            act.high().iter().copied().collect(),
        );
        Self {
            env: Arc::new(Mutex::new(env)),
            name: name.to_owned(),
            observation_space,
            action_low,
            action_high,
        }
    }

    fn lock(&self) -> MutexGuard<'_, RobosuiteEnv> {
        self.env.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[pymethods]
impl PyRobosuiteEnv {
    /// `reset(seed=None) -> OrderedDict` of observations (robosuite's `reset()`; `seed`
    /// re-seeds the environment RNG, an extension of robosuite's API).
    #[pyo3(signature = (seed=None))]
    fn reset<'py>(
        &self,
        py: Python<'py>,
        seed: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let seed = extract_seed(seed)?;
        let (obs, _info) = py
            .detach(|| self.lock().reset(seed, None))
            .map_err(to_pyerr)?;
        value_into_py(py, Value::Dict(obs), true)
    }

    /// `step(action) -> (OrderedDict obs, reward, done, info)` (robosuite's 4-tuple;
    /// `done` is `terminated or truncated`, `info` has `success`).
    fn step<'py>(
        &self,
        py: Python<'py>,
        action: &Bound<'py, PyAny>,
    ) -> PyResult<(Bound<'py, PyAny>, f64, bool, Bound<'py, PyDict>)> {
        let action = array_from_py(action)?.cast(gym_core::DType::F64);
        let action = action
            .to_typed::<f64>()
            .map_err(|e| PyValueError::new_err(format!("invalid action: {e}")))?;
        let step = py.detach(|| self.lock().step(&action)).map_err(to_pyerr)?;
        let done = step.terminated || step.truncated;
        Ok((
            value_into_py(py, Value::Dict(step.observation), true)?,
            step.reward,
            done,
            info_into_py(py, &step.info)?,
        ))
    }

    /// `(low, high)`: the action bounds as float64 arrays.
    #[getter]
    fn action_spec<'py>(
        &self,
        py: Python<'py>,
    ) -> (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>) {
        (
            PyArray1::from_vec(py, self.action_low.clone()),
            PyArray1::from_vec(py, self.action_high.clone()),
        )
    }

    /// The action dimension.
    #[getter]
    fn action_dim(&self) -> usize {
        self.action_low.len()
    }

    /// The current observations (robosuite's `observation_spec()`).
    fn observation_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let obs = self.lock().observation();
        value_into_py(py, Value::Dict(obs), true)
    }

    /// The observation keys, in order.
    fn observation_keys(&self) -> Vec<String> {
        self.observation_space.keys().map(str::to_owned).collect()
    }

    /// The observation space's description (a Dict).
    fn observation_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        space_spec(py, &AnySpace::Dict(self.observation_space.clone()))
    }

    /// The task name (`"Lift"`).
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// Episode length in env steps.
    #[getter]
    fn horizon(&self) -> u64 {
        self.lock().config().horizon
    }

    /// Control frequency in Hz.
    #[getter]
    fn control_freq(&self) -> f64 {
        self.lock().config().control_freq
    }

    /// The reward scale (`None`: unnormalised).
    #[getter]
    fn reward_scale(&self) -> Option<f64> {
        self.lock().config().reward_scale
    }

    /// Whether rewards are shaped (the task's default unless set).
    #[getter]
    fn reward_shaping(&self) -> bool {
        self.lock().config().reward_shaping.unwrap_or(false)
    }

    /// Whether the horizon is ignored.
    #[getter]
    fn ignore_done(&self) -> bool {
        self.lock().config().ignore_done
    }

    /// Whether camera observations are included.
    #[getter]
    fn use_camera_obs(&self) -> bool {
        self.lock().config().cameras.use_camera_obs
    }

    /// Whether an offscreen renderer was created.
    #[getter]
    fn has_offscreen_renderer(&self) -> bool {
        let env = self.lock();
        env.config().cameras.has_offscreen_renderer || env.cameras().is_some()
    }

    /// The observed cameras' names (robosuite's `camera_names`; empty without camera
    /// observations).
    #[getter]
    fn camera_names(&self) -> Vec<String> {
        let env = self.lock();
        let c = &env.config().cameras;
        if c.use_camera_obs {
            c.camera_names.clone()
        } else {
            Vec::new()
        }
    }

    /// The keys robosuite's `GymWrapper` selects by default (`object-state`, the camera
    /// images, each robot's `proprio-state`), as `adapters::gym_wrapper::default_keys`.
    fn default_gym_keys(&self) -> Vec<String> {
        adapters::gym_wrapper::default_keys(&self.observation_space)
    }

    /// Whether object observations are included.
    #[getter]
    fn use_object_obs(&self) -> bool {
        self.lock().config().use_object_obs
    }

    /// Env steps taken in the current episode.
    #[getter]
    fn timestep(&self) -> u64 {
        self.lock().timestep()
    }

    /// Whether the task is solved in the current state.
    fn check_success(&self) -> bool {
        self.lock().check_success()
    }

    /// The reward of the current state.
    fn reward(&self) -> f64 {
        self.lock().reward()
    }

    /// The flat simulator state `[time, qpos, qvel]` (robosuite's
    /// `env.sim.get_state().flatten()`).
    fn get_state<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, self.lock().get_state())
    }

    /// Sets the flat simulator state `[time, qpos, qvel]` and runs `mj_forward`.
    fn set_state(&self, state: &Bound<'_, PyAny>) -> PyResult<()> {
        let array = array_from_py(state)?;
        if array.shape().len() != 1 {
            return Err(PyValueError::new_err(format!(
                "invalid argument `state`: expected a flat (1-D) array [time, qpos, qvel], got shape {:?}",
                array.shape()
            )));
        }
        let flat = array.cast(gym_core::DType::F64).to_f64_vec();
        self.lock().set_state(&flat).map_err(to_pyerr)
    }

    /// The whole run-time state (episode snapshot and RNG) as JSON text, for pickling and
    /// deep copies (see `robosuite_env::saved`).
    fn save_env_state(&self) -> PyResult<String> {
        SavedEnv::of(&self.lock()).to_json().map_err(to_pyerr)
    }

    /// Restores [`save_env_state`](Self::save_env_state)'s text into an env made with the
    /// same configuration; it then continues bit-identically.
    fn load_env_state(&self, text: &str) -> PyResult<()> {
        let saved = SavedEnv::from_json(text).map_err(to_pyerr)?;
        saved.apply(&mut self.lock()).map_err(to_pyerr)
    }

    /// `{"render_modes": ["rgb_array", "depth_array"], "render_fps": control_freq}`.
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::pyenv::metadata_into_py(py, self.lock().metadata())
    }

    /// Closes the environment; calling it again does nothing.
    fn close(&self) {
        self.lock().close();
    }

    /// robosuite's `GymWrapper(env, keys, flatten_obs)` over this same environment, as a
    /// [`PyEnv`].
    #[pyo3(signature = (keys=None, flatten_obs=true))]
    fn gym_env(&self, keys: Option<Vec<String>>, flatten_obs: bool) -> PyResult<PyEnv> {
        let shared = SharedEnv::from_arc(Arc::clone(&self.env));
        // The flat wrapper's `step_into` writes the flat observation in place (the same
        // observations as GymWrapper's with `flatten_obs`).
        let env = if flatten_obs {
            adapters::FlatGymWrapper::new(shared, keys).map(IntoBoxedEnv::boxed)
        } else {
            adapters::GymWrapper::new(shared, keys, false).map(IntoBoxedEnv::boxed)
        };
        Ok(PyEnv::new(env.map_err(to_pyerr)?))
    }

    fn __repr__(&self) -> String {
        format!(
            "RobosuiteEnv({}, action_dim={}, keys={})",
            self.name,
            self.action_low.len(),
            self.observation_space.len()
        )
    }
}
