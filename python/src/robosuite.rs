//! [`PyRobosuiteEnv`]: robosuite's environment API (`reset`, `step` → 4-tuple,
//! `action_spec`, `observation_spec`, `get_state` / `set_state`, ...) over a Rust
//! [`RobosuiteEnv`].

use crate::convert::{array_from_py, info_into_py, space_spec, value_into_py};
use crate::errors::to_pyerr;
use crate::fork::{ForkAwareGuard, ForkAwareMutex};
use crate::pyenv::{PyEnv, extract_seed};
use crate::shared::SharedEnv;
use gym_core::{AnySpace, Env, Info, IntoBoxedEnv, Value};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use robosuite_env::saved::SavedEnv;
use robosuite_env::sim::KeepAlive;
use robosuite_env::{ObservableFlag, RobosuiteEnv};
use std::sync::{Arc, Mutex, PoisonError};

/// The `mujoco.MjModel` / `mujoco.MjData` sharing an env's memory, with the addresses they
/// were made for (a replaced model or data makes new ones).
struct SharedSim {
    model_addr: usize,
    data_addr: usize,
    model: Py<PyAny>,
    data: Py<PyAny>,
}

/// A Python error raised while handing memory to MuJoCo's Python objects.
struct HandOverError(PyErr);

impl From<String> for HandOverError {
    fn from(message: String) -> Self {
        Self(PyRuntimeError::new_err(message))
    }
}

/// A flat `[time, qpos, qvel]` state from Python as float64 values.
fn flat_state(state: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    let array = array_from_py(state)?;
    if array.shape().len() != 1 {
        return Err(PyValueError::new_err(format!(
            "invalid argument `state`: expected a flat (1-D) array [time, qpos, qvel], got shape {:?}",
            array.shape()
        )));
    }
    Ok(array.cast(gym_core::DType::F64).to_f64_vec())
}

/// A robosuite environment as robosuite's Python API sees it. The Python class
/// `robosuite_rs.RobosuiteEnv` delegates to it; `gym_env` builds the GymWrapper over the
/// same (shared) environment.
#[pyclass(name = "RobosuiteEnv", module = "robosuite_rs._native")]
pub struct PyRobosuiteEnv {
    env: Arc<ForkAwareMutex<RobosuiteEnv>>,
    name: String,
    action_low: Vec<f64>,
    action_high: Vec<f64>,
    shared: Mutex<Option<SharedSim>>,
}

impl PyRobosuiteEnv {
    /// Wraps `env`, made for the task `name`.
    pub fn new(env: RobosuiteEnv, name: &str) -> Self {
        let act = env.action_space();
        let (action_low, action_high) = (
            act.low().iter().copied().collect(),
            act.high().iter().copied().collect(),
        );
        Self {
            env: Arc::new(ForkAwareMutex::new(env)),
            name: name.to_owned(),
            action_low,
            action_high,
            shared: Mutex::new(None),
        }
    }

    /// Locks the env.
    ///
    /// # Errors
    /// As [`ForkAwareMutex::lock`]: a call from inside another call on this env on the same
    /// thread, or from a forked child while another thread of the parent stepped it.
    fn lock(&self) -> gym_core::Result<ForkAwareGuard<'_, RobosuiteEnv>> {
        self.env.lock()
    }

    /// [`Self::lock`] with its error as a Python exception.
    fn env(&self) -> PyResult<ForkAwareGuard<'_, RobosuiteEnv>> {
        self.lock().map_err(to_pyerr)
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
            .detach(|| self.lock()?.reset(seed, None))
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
        let step = py.detach(|| self.lock()?.step(&action)).map_err(to_pyerr)?;
        let done = step.terminated || step.truncated;
        Ok((
            value_into_py(py, Value::Dict(step.observation), true)?,
            step.reward,
            done,
            info_into_py(py, &step.info)?,
        ))
    }

    /// Starts an env step taken one substep at a time (for observables sampled between
    /// substeps): checks the action and the episode's phase (an error changes nothing).
    fn step_begin(&self, py: Python<'_>, action: &Bound<'_, PyAny>) -> PyResult<()> {
        let action = array_from_py(action)?.cast(gym_core::DType::F64);
        let action = action
            .to_typed::<f64>()
            .map_err(|e| PyValueError::new_err(format!("invalid action: {e}")))?;
        py.detach(|| self.lock()?.begin_step(&action))
            .map_err(to_pyerr)
    }

    /// Runs the next substep of the step under way (`sensors`: compute MuJoCo's sensors);
    /// returns whether it was the last.
    fn step_substep(&self, py: Python<'_>, sensors: bool) -> PyResult<bool> {
        py.detach(|| self.lock()?.substep(sensors))
            .map_err(to_pyerr)
    }

    /// Ends the step under way: `(obs, reward, done, info)` as `step` returns them.
    fn step_end<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, f64, bool, Bound<'py, PyDict>)> {
        let (obs, transition, success) = py
            .detach(|| {
                let mut env = self.lock()?;
                let (transition, success) = env.finish_step()?;
                Ok::<_, gym_core::Error>((env.observation(), transition, success))
            })
            .map_err(to_pyerr)?;
        let info = Info::new().with("success", success);
        Ok((
            value_into_py(py, Value::Dict(obs), true)?,
            transition.reward,
            transition.terminated || transition.truncated,
            info_into_py(py, &info)?,
        ))
    }

    /// The task's constructor arguments it was built with, as JSON text.
    #[getter]
    fn task_options(&self) -> PyResult<String> {
        Ok(serde_json::Value::Object(self.env()?.task_options().clone()).to_string())
    }

    /// The task's objects (robosuite's `env.model.mujoco_objects`: names, offsets,
    /// radius), as JSON text.
    #[getter]
    fn mujoco_objects(&self) -> PyResult<String> {
        Ok(
            serde_json::to_string(&self.env()?.mujoco_objects())
                .unwrap_or_else(|_| "[]".to_owned()),
        )
    }

    /// The number of physics substeps of an env step.
    #[getter]
    fn substeps(&self) -> PyResult<usize> {
        Ok(self.env()?.substeps())
    }

    /// MuJoCo's timestep (robosuite's `model_timestep`), in seconds.
    #[getter]
    fn model_timestep(&self) -> PyResult<f64> {
        Ok(self.env()?.sim().model().opt().timestep)
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
        let obs = self.env()?.observation();
        value_into_py(py, Value::Dict(obs), true)
    }

    /// Every observable's value from the last observation pass, whatever its flags.
    fn all_observations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let obs = self.env()?.all_observations();
        value_into_py(py, Value::Dict(obs), true)
    }

    /// The observation keys, in order (the active observables, then the modality
    /// concatenations).
    fn observation_keys(&self) -> PyResult<Vec<String>> {
        Ok(self.env()?.observation_keys())
    }

    /// The observation space's description (a Dict).
    fn observation_space_spec<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let space = self.env()?.observation_space().clone();
        space_spec(py, &AnySpace::Dict(space))
    }

    /// The task name (`"Lift"`).
    #[getter]
    fn name(&self) -> String {
        self.name.clone()
    }

    /// Episode length in env steps.
    #[getter]
    fn horizon(&self) -> PyResult<u64> {
        Ok(self.env()?.config().horizon)
    }

    /// Control frequency in Hz.
    #[getter]
    fn control_freq(&self) -> PyResult<f64> {
        Ok(self.env()?.config().control_freq)
    }

    /// The reward scale (`None`: unnormalised).
    #[getter]
    fn reward_scale(&self) -> PyResult<Option<f64>> {
        Ok(self.env()?.config().reward_scale)
    }

    /// Whether rewards are shaped (the task's default unless set).
    #[getter]
    fn reward_shaping(&self) -> PyResult<bool> {
        Ok(self.env()?.config().reward_shaping.unwrap_or(false))
    }

    /// Whether the horizon is ignored.
    #[getter]
    fn ignore_done(&self) -> PyResult<bool> {
        Ok(self.env()?.config().ignore_done)
    }

    /// Whether camera observations are included.
    #[getter]
    fn use_camera_obs(&self) -> PyResult<bool> {
        Ok(self.env()?.config().cameras.use_camera_obs)
    }

    /// Whether an offscreen renderer was created.
    #[getter]
    fn has_offscreen_renderer(&self) -> PyResult<bool> {
        let env = self.env()?;
        Ok(env.config().cameras.has_offscreen_renderer || env.cameras().is_some())
    }

    /// The observed cameras' names (robosuite's `camera_names`; empty without camera
    /// observations).
    #[getter]
    fn camera_names(&self) -> PyResult<Vec<String>> {
        let env = self.env()?;
        let c = &env.config().cameras;
        Ok(if c.use_camera_obs {
            c.camera_names.clone()
        } else {
            Vec::new()
        })
    }

    /// The keys robosuite's `GymWrapper` selects by default (`object-state`, the camera
    /// images, each robot's `proprio-state`), as `adapters::gym_wrapper::default_keys`.
    fn default_gym_keys(&self) -> PyResult<Vec<String>> {
        Ok(adapters::gym_wrapper::default_keys(
            self.env()?.observation_space(),
        ))
    }

    /// Whether object observations are included.
    #[getter]
    fn use_object_obs(&self) -> PyResult<bool> {
        Ok(self.env()?.config().use_object_obs)
    }

    /// Env steps taken in the current episode.
    #[getter]
    fn timestep(&self) -> PyResult<u64> {
        Ok(self.env()?.timestep())
    }

    /// Whether the task is solved in the current state.
    fn check_success(&self) -> PyResult<bool> {
        Ok(self.env()?.check_success())
    }

    /// The reward of the current state.
    fn reward(&self) -> PyResult<f64> {
        Ok(self.env()?.reward())
    }

    /// The flat simulator state `[time, qpos, qvel]` (robosuite's
    /// `env.sim.get_state().flatten()`).
    fn get_state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        Ok(PyArray1::from_vec(py, self.env()?.get_state()))
    }

    /// Sets the flat simulator state `[time, qpos, qvel]` and runs `mj_forward`.
    fn set_state(&self, state: &Bound<'_, PyAny>) -> PyResult<()> {
        let flat = flat_state(state)?;
        self.env()?.set_state(&flat).map_err(to_pyerr)
    }

    /// The whole run-time state (episode snapshot and RNG) as JSON text, for pickling and
    /// deep copies (see `robosuite_env::saved`).
    fn save_env_state(&self) -> PyResult<String> {
        SavedEnv::of(&*self.env()?).to_json().map_err(to_pyerr)
    }

    /// Restores [`save_env_state`](Self::save_env_state)'s text into an env made with the
    /// same configuration; it then continues bit-identically.
    fn load_env_state(&self, text: &str) -> PyResult<()> {
        let saved = SavedEnv::from_json(text).map_err(to_pyerr)?;
        saved.apply(&mut *self.env()?).map_err(to_pyerr)
    }

    /// `{"render_modes": ["rgb_array", "depth_array"], "render_fps": control_freq}`.
    fn metadata<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        crate::pyenv::metadata_into_py(py, self.env()?.metadata())
    }

    /// Closes the environment; calling it again does nothing.
    fn close(&self) {
        if let Ok(mut env) = self.lock() {
            env.close();
        }
    }

    /// robosuite's `GymWrapper(env, keys, flatten_obs)` over this same environment, as a
    /// [`PyEnv`].
    #[pyo3(signature = (keys=None, flatten_obs=true))]
    fn gym_env(&self, keys: Option<Vec<String>>, flatten_obs: bool) -> PyResult<PyEnv> {
        let shared = SharedEnv::from_arc(Arc::clone(&self.env)).map_err(to_pyerr)?;
        // The flat wrapper's `step_into` writes the flat observation in place (the same
        // observations as GymWrapper's with `flatten_obs`).
        let env = if flatten_obs {
            adapters::FlatGymWrapper::new(shared, keys).map(IntoBoxedEnv::boxed)
        } else {
            adapters::GymWrapper::new(shared, keys, false).map(IntoBoxedEnv::boxed)
        };
        Ok(PyEnv::new(env.map_err(to_pyerr)?))
    }

    /// `(mujoco.MjModel, mujoco.MjData)` sharing this env's model and data (no copy): on
    /// first use the model's memory is handed to a `mujoco.MjModel` (a model shared with
    /// other envs of the same scene is first copied, so the Python object is this env's
    /// alone; an env built without texture images loads them first) and the data moved into
    /// a `mujoco.MjData` made for it (state copied whole, so stepping continues
    /// bit-identically); both then belong to Python, so a view kept after `close()` or a
    /// model replacement stays valid. The same objects are returned until the model is
    /// replaced.
    fn sim_objects<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        let mut shared = self.shared.lock().unwrap_or_else(PoisonError::into_inner);
        let mut env = self.env()?;
        let (m, d) = {
            let sim = env.sim();
            (
                std::ptr::from_ref(sim.model().ffi()) as usize,
                std::ptr::from_ref(sim.data().ffi()) as usize,
            )
        };
        if let Some(s) = shared.as_ref()
            && s.model_addr == m
            && s.data_addr == d
        {
            return Ok((s.model.bind(py).clone(), s.data.bind(py).clone()));
        }
        let mujoco = py.import("mujoco")?;
        let model_class = mujoco.getattr("MjModel")?;
        let data_class = mujoco.getattr("MjData")?;
        let model = match shared.as_ref() {
            Some(s) if s.model_addr == m => s.model.clone_ref(py),
            _ => {
                // Python code may read or write texture images (`tex_data`, modders): an env
                // built without them loads them first.
                env.load_textures().map_err(to_pyerr)?;
                let mut made: Option<Py<PyAny>> = None;
                // SAFETY: `_from_model_ptr` wraps the pointer in a `mujoco.MjModel` that owns
                // it (mj_deleteModel when collected); the wrapper is kept by the Data until
                // it is dropped, and it never changes sizes.
                unsafe {
                    env.sim_mut().hand_over_model(|ptr| {
                        let obj = model_class.call_method1("_from_model_ptr", (ptr as usize,))?;
                        made = Some(obj.clone().unbind());
                        Ok::<KeepAlive, PyErr>(Box::new(obj.unbind()))
                    })?;
                }
                made.ok_or_else(|| PyRuntimeError::new_err("the model was handed over already"))?
            }
        };
        let mut made: Option<Py<PyAny>> = None;
        // SAFETY: `mujoco.MjData(model)` allocates an mjData for this very model with
        // `mj_makeData`; the Python object owns it and is kept by the Data until dropped.
        unsafe {
            env.sim_mut()
                .adopt_data(|_m| {
                    let obj = data_class.call1((model.bind(py),)).map_err(HandOverError)?;
                    let addr: usize = obj
                        .getattr("_address")
                        .and_then(|a| a.extract())
                        .map_err(HandOverError)?;
                    made = Some(obj.clone().unbind());
                    Ok::<_, HandOverError>((addr as *mut _, Box::new(obj.unbind()) as KeepAlive))
                })
                .map_err(|e| e.0)?;
        }
        let data = made.ok_or_else(|| PyRuntimeError::new_err("no mjData was made"))?;
        // Handing the model over made it the env's own (a view of the shared compiled model
        // is copied first), so its address may have changed.
        let m = std::ptr::from_ref(env.sim().model().ffi()) as usize;
        let d = std::ptr::from_ref(env.sim().data().ffi()) as usize;
        *shared = Some(SharedSim {
            model_addr: m,
            data_addr: d,
            model: model.clone_ref(py),
            data: data.clone_ref(py),
        });
        Ok((model.into_bound(py), data.into_bound(py)))
    }

    /// `mj_forward` on the env's simulator (robosuite's `sim.forward()`), through the env's
    /// guard: a MuJoCo error is a `RuntimeError` and the env then needs a reset.
    fn sim_forward(&self, py: Python<'_>) -> PyResult<()> {
        py.detach(|| self.lock()?.sim_mut().forward())
            .map_err(to_pyerr)
    }

    /// `mj_step` (robosuite's `sim.step()`), guarded as [`Self::sim_forward`].
    fn sim_step(&self, py: Python<'_>) -> PyResult<()> {
        py.detach(|| self.lock()?.sim_mut().step())
            .map_err(to_pyerr)
    }

    /// `mj_step1` (robosuite's `sim.step1()`).
    fn sim_step1(&self, py: Python<'_>) -> PyResult<()> {
        py.detach(|| self.lock()?.sim_mut().step1())
            .map_err(to_pyerr)
    }

    /// `mj_step2` (robosuite's `sim.step2()`).
    fn sim_step2(&self, py: Python<'_>) -> PyResult<()> {
        py.detach(|| self.lock()?.sim_mut().step2())
            .map_err(to_pyerr)
    }

    /// `mj_resetData` (robosuite's `sim.reset()`).
    fn sim_reset(&self, py: Python<'_>) {
        py.detach(|| {
            if let Ok(mut env) = self.lock() {
                env.sim_mut().reset_data();
            }
        });
    }

    /// Checks a flat state `[time, qpos, qvel]` for this model (robosuite's
    /// `set_state_from_flattened` input) without applying it.
    fn check_flat_state(&self, state: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
        let flat = flat_state(state)?;
        self.env()?.sim().check_state(&flat).map_err(to_pyerr)?;
        Ok(flat)
    }

    /// robomimic's inner loop of `dataset_states_to_obs.py` for the rows of `states` (flat
    /// `[time, qpos, qvel]`), natively: per row the state set and `mj_forward` (robosuite's
    /// `sim.set_state_from_flattened` + `sim.forward()`), every enabled and active observable
    /// read (the values `_get_observations(force_update=True)` gives), `reward()` and
    /// `_check_success()`. Returns `(observations stacked per key, rewards, successes)`.
    /// Every row is checked before any is set; the GIL is released meanwhile.
    fn observe_states<'py>(
        &self,
        py: Python<'py>,
        states: numpy::PyReadonlyArray2<'py, f64>,
    ) -> PyResult<(
        Bound<'py, PyDict>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
    )> {
        let states = states.as_array().as_standard_layout().into_owned();
        let (keys, stacked, rewards, successes) = py
            .detach(|| -> gym_core::Result<_> {
                let mut env = self.lock()?;
                for row in states.rows() {
                    env.sim().check_state(row.as_slice().unwrap_or(&[]))?;
                }
                let mut keys: Vec<String> = Vec::new();
                let mut values: Vec<Vec<gym_core::ArrayValue>> = Vec::new();
                let mut rewards = Vec::with_capacity(states.nrows());
                let mut successes = Vec::with_capacity(states.nrows());
                for row in states.rows() {
                    env.sim_mut().set_state(row.as_slice().unwrap_or(&[]))?;
                    let obs = env.update_observations()?;
                    rewards.push(env.reward());
                    successes.push(env.check_success());
                    if keys.is_empty() {
                        keys = obs.keys().cloned().collect();
                        values = vec![Vec::with_capacity(states.nrows()); keys.len()];
                    }
                    for (i, (_, v)) in obs.into_iter().enumerate() {
                        match (v, values.get_mut(i)) {
                            (Value::Array(a), Some(column)) => column.push(a),
                            _ => {
                                return Err(gym_core::Error::invalid_argument(
                                    "states",
                                    "an observation that is not an array cannot be stacked",
                                ));
                            }
                        }
                    }
                }
                let stacked = values
                    .iter()
                    .map(|column| stack_arrays(column))
                    .collect::<gym_core::Result<Vec<_>>>()?;
                Ok((keys, stacked, rewards, successes))
            })
            .map_err(to_pyerr)?;
        let dict = PyDict::new(py);
        for (k, a) in keys.into_iter().zip(stacked) {
            dict.set_item(k, crate::convert::array_into_py(py, a))?;
        }
        Ok((
            dict,
            PyArray1::from_vec(py, rewards),
            PyArray1::from_vec(py, successes),
        ))
    }

    /// robosuite's `_get_observations(force_update=True)`: every observable read from the
    /// simulator as it is now (no forward pass).
    fn update_observations<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let obs = py
            .detach(|| self.lock()?.update_observations())
            .map_err(to_pyerr)?;
        value_into_py(py, Value::Dict(obs), true)
    }

    /// robosuite's `sim.model.get_xml()`: the scene MJCF with the model's current values.
    fn get_xml(&self, py: Python<'_>) -> PyResult<String> {
        py.detach(|| self.lock()?.scene_xml()).map_err(to_pyerr)
    }

    /// The MJCF text the current model was compiled from.
    fn source_xml(&self) -> PyResult<String> {
        Ok(self.env()?.source_xml().to_owned())
    }

    /// robosuite's `reset_from_xml_string(xml)`: the scene `xml` (of this task, such as one
    /// saved by robosuite; asset paths through a `robosuite/` folder are redirected to the
    /// local model files), then a deterministic reset. Keeps the configuration, the RNG
    /// stream and the observables' flags; returns `(first observation, in_place)`, where
    /// `in_place` says the env's model and data were kept (a scene differing only in box
    /// sizes). On an error the env is unchanged.
    fn reset_from_xml_string<'py>(
        &self,
        py: Python<'py>,
        xml: &str,
    ) -> PyResult<(Bound<'py, PyAny>, bool)> {
        let (obs, _, load) = py
            .detach(|| self.lock()?.reset_from_xml_string(xml))
            .map_err(to_pyerr)?;
        let in_place = load == robosuite_env::SceneLoad::InPlace;
        Ok((value_into_py(py, Value::Dict(obs), true)?, in_place))
    }

    /// robosuite's deterministic reset: the robots at `init_qpos` without noise, objects as
    /// the model places them, nothing drawn from the RNG.
    fn reset_deterministic<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let (obs, _) = py
            .detach(|| self.lock()?.reset_deterministic())
            .map_err(to_pyerr)?;
        value_into_py(py, Value::Dict(obs), true)
    }

    /// Every observable: `[(name, modality, shape, dtype, enabled, active)]` in robosuite's
    /// order.
    fn observables<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let items = self.env()?.observables();
        let rows = items
            .into_iter()
            .map(|o| {
                (
                    o.spec.key,
                    o.spec.modality.name(),
                    o.spec.shape,
                    o.spec.dtype.name(),
                    o.enabled,
                    o.active,
                )
            })
            .collect::<Vec<_>>();
        PyList::new(py, rows)
    }

    /// robosuite's `modify_observable(name, attribute, value)` for `"enabled"` and
    /// `"active"`.
    fn modify_observable(&self, name: &str, attribute: &str, value: bool) -> PyResult<()> {
        let flag = match attribute {
            "enabled" => ObservableFlag::Enabled,
            "active" => ObservableFlag::Active,
            other => {
                return Err(PyValueError::new_err(format!(
                    "modify_observable: attribute {other:?} is not a flag (expected 'enabled' or 'active')"
                )));
            }
        };
        self.env()?
            .modify_observable(name, flag, value)
            .map_err(to_pyerr)
    }

    /// robosuite's `visualize(vis_settings)`: shows or hides the task objects' (`env`),
    /// robots' and grippers' sites and colours the grip sites by their distance to the
    /// task's target ([`RobosuiteEnv::visualize`]).
    fn visualize(&self, py: Python<'_>, env: bool, robots: bool, grippers: bool) -> PyResult<()> {
        py.detach(|| {
            self.lock().map(|mut e| {
                e.visualize(robosuite_env::wrappers::VisualizationSettings {
                    env,
                    robots,
                    grippers,
                });
            })
        })
        .map_err(to_pyerr)
    }

    /// Uploads texture `texture` (its bitmap changed in `sim.model.tex_data`) to the env's
    /// renderers again (MuJoCo's `mjr_uploadTexture`).
    fn upload_texture(&self, py: Python<'_>, texture: usize) -> PyResult<()> {
        py.detach(|| self.lock()?.upload_texture(texture))
            .map_err(to_pyerr)
    }

    /// robosuite's `sim.render(width, height, camera_name, depth, segmentation)` for fixed
    /// camera `camera`, or with `free=(lookat, distance, azimuth, elevation)` for MuJoCo's
    /// free camera: `rgb` (H×W×3 uint8, bottom row first), or `(rgb, depth)`; with
    /// `segmentation` the image is H×W×2 int32 `(object type, object id)`.
    #[pyo3(signature = (camera, width, height, depth=false, segmentation=false, free=None))]
    #[allow(clippy::too_many_arguments)]
    fn render_camera<'py>(
        &self,
        py: Python<'py>,
        camera: usize,
        width: usize,
        height: usize,
        depth: bool,
        segmentation: bool,
        free: Option<([f64; 3], f64, f64, f64)>,
    ) -> PyResult<Bound<'py, PyAny>> {
        use robosuite_env::render::{FreeCamera, View};
        let camera = match free {
            None => View::Fixed(camera),
            Some((lookat, distance, azimuth, elevation)) => View::Free(FreeCamera {
                lookat,
                distance,
                azimuth,
                elevation,
            }),
        };
        let frame = py
            .detach(|| {
                self.lock()?
                    .render_camera(camera, width, height, depth, segmentation)
            })
            .map_err(to_pyerr)?;
        let (h, w) = (frame.height, frame.width);
        let image: Bound<'py, PyAny> = match frame.segmentation {
            Some(seg) => PyArray1::from_vec(py, seg).reshape([h, w, 2])?.into_any(),
            None => PyArray1::from_vec(py, frame.rgb)
                .reshape([h, w, 3])?
                .into_any(),
        };
        match frame.depth {
            Some(d) => {
                let depth = PyArray1::from_vec(py, d).reshape([h, w])?.into_any();
                Ok((image, depth).into_pyobject(py)?.into_any())
            }
            None => Ok(image),
        }
    }

    /// The robots as plain values: per robot its name, index, joint `qpos` / `qvel`
    /// addresses, `init_qpos`, action dimension and limits, and per arm its side,
    /// controller, actuators, end-effector site and body, and gripper (name, actuators,
    /// joint addresses, action dimension); its robosuite class, composite controller,
    /// action layout (`(part, start, end)`) and other body parts; and the action's slices by
    /// part name where the composite controller's action is not its parts' (`WHOLE_BODY_IK`;
    /// else `None`).
    fn robots_info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let env = self.env()?;
        let list = PyList::empty(py);
        for r in env.robots() {
            let d = PyDict::new(py);
            d.set_item("name", r.name())?;
            d.set_item("index", r.index())?;
            d.set_item("joint_qpos", r.joint_qpos().to_vec())?;
            d.set_item("joint_dofs", r.joint_dofs().to_vec())?;
            d.set_item("init_qpos", r.init_qpos().to_vec())?;
            d.set_item("action_dim", r.action_dim())?;
            let (low, high) = r.action_limits();
            d.set_item("action_low", low)?;
            d.set_item("action_high", high)?;
            let arms = PyList::empty(py);
            for a in r.arms() {
                let ad = PyDict::new(py);
                ad.set_item("side", a.side())?;
                ad.set_item("controller", a.controller().name())?;
                ad.set_item("controller_dim", a.controller().action_dim())?;
                ad.set_item("actuators", a.actuators().to_vec())?;
                ad.set_item("eef_site", a.eef_site())?;
                ad.set_item("eef_body", a.eef_body())?;
                let g = a.gripper();
                ad.set_item("gripper", g.has_gripper().then_some(g.info().name))?;
                ad.set_item("gripper_actuators", g.actuators().to_vec())?;
                ad.set_item("gripper_qpos", g.qpos().to_vec())?;
                ad.set_item("gripper_dim", g.action_dim())?;
                arms.append(ad)?;
            }
            d.set_item("arms", arms)?;
            d.set_item("robot_class", r.kind().class_name())?;
            d.set_item("composite", r.composite_controller().name())?;
            let layout = PyList::empty(py);
            for slot in r.action_layout() {
                layout.append((slot.name.as_str(), slot.range.start, slot.range.end))?;
            }
            d.set_item("layout", layout)?;
            let parts = PyList::empty(py);
            for b in r.body_parts() {
                let bd = PyDict::new(py);
                bd.set_item("name", b.name())?;
                bd.set_item("controller", b.controller().name())?;
                bd.set_item("controller_dim", b.controller().action_dim())?;
                bd.set_item("joints", b.joint_names().to_vec())?;
                bd.set_item("qpos", b.qpos().to_vec())?;
                bd.set_item("actuators", b.actuators().to_vec())?;
                parts.append(bd)?;
            }
            d.set_item("body_parts", parts)?;
            let split = r.action_split().map(|s| {
                s.into_iter()
                    .map(|(name, range)| (name, range.start, range.end))
                    .collect::<Vec<_>>()
            });
            d.set_item("action_split", split)?;
            list.append(d)?;
        }
        Ok(list)
    }

    fn __repr__(&self) -> String {
        format!(
            "RobosuiteEnv({}, action_dim={}, keys={})",
            self.name,
            self.action_low.len(),
            self.lock().map_or(0, |env| env.observation_keys().len())
        )
    }
}

/// The arrays of one observation key over several states, stacked on a new first axis.
fn stack_arrays(column: &[gym_core::ArrayValue]) -> gym_core::Result<gym_core::ArrayValue> {
    use gym_core::ArrayValue as A;
    let mismatch = || {
        gym_core::Error::invalid_argument(
            "states",
            "an observation changed its dtype or shape between states",
        )
    };
    macro_rules! stack_as {
        ($variant:ident) => {{
            let views = column
                .iter()
                .map(|v| match v {
                    A::$variant(a) => Some(a.view()),
                    _ => None,
                })
                .collect::<Option<Vec<_>>>()
                .ok_or_else(mismatch)?;
            A::$variant(ndarray::stack(ndarray::Axis(0), &views).map_err(|_| mismatch())?)
        }};
    }
    Ok(match column.first() {
        None => A::F64(ndarray::ArrayD::zeros(ndarray::IxDyn(&[0]))),
        Some(A::I8(_)) => stack_as!(I8),
        Some(A::I16(_)) => stack_as!(I16),
        Some(A::I32(_)) => stack_as!(I32),
        Some(A::I64(_)) => stack_as!(I64),
        Some(A::U8(_)) => stack_as!(U8),
        Some(A::F32(_)) => stack_as!(F32),
        Some(A::F64(_)) => stack_as!(F64),
        Some(A::Bool(_)) => stack_as!(Bool),
    })
}
