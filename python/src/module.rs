//! The contents of the extension module `robosuite_rs._native` ([`init`]; the module
//! itself is the `robosuite-native` crate).

use crate::convert::py_to_json;
use crate::errors::to_pyerr;
use crate::pool::PyEnvPool;
use crate::pyenv::{PyEnv, PyVecEnv};
use crate::robosuite::PyRobosuiteEnv;
use adapters::ThreadOptions;
use gym_core::{BoxedEnv, IntoBoxedEnv};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use robosuite_env::{EnvConfig, RobosuiteEnv};
use std::path::PathBuf;

/// robosuite's `make` keyword arguments as JSON (Python values as they are: lists as
/// lists, dicts as dicts, `None` as null).
fn kwargs_json(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<gym_core::registry::Kwargs> {
    let mut out = gym_core::registry::Kwargs::new();
    for (k, v) in kwargs.into_iter().flat_map(|d| d.iter()) {
        let key: String = k
            .extract()
            .map_err(|_| pyo3::exceptions::PyTypeError::new_err("keyword names must be strs"))?;
        let value = py_to_json(&v, &key)?;
        out.insert(key, value);
    }
    Ok(out)
}

/// The configuration of the task `env_name` from robosuite's `make` keyword arguments
/// (`EnvConfig::from_kwargs`); an argument neither robosuite's nor the task's is a
/// `TypeError`, as Python's for an unexpected keyword argument.
fn config(env_name: &str, kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<EnvConfig> {
    let kwargs = kwargs_json(kwargs)?;
    EnvConfig::from_kwargs(env_name, &kwargs).map_err(|e| match e {
        gym_core::Error::UnknownKey { key, .. } => {
            let own = robosuite_env::make_task(env_name)
                .map(|t| t.options().keys().cloned().collect::<Vec<_>>().join(", "))
                .unwrap_or_default();
            pyo3::exceptions::PyTypeError::new_err(format!(
                "make() got an unexpected keyword argument '{key}' for {env_name}; supported: \
                 {}; {env_name}'s own: {}",
                robosuite_env::config::kwarg_names().join(", "),
                if own.is_empty() { "none" } else { own.as_str() }
            ))
        }
        other => to_pyerr(other),
    })
}

fn build(
    env_name: &str,
    config: EnvConfig,
    model_xml: Option<&PathBuf>,
) -> gym_core::Result<RobosuiteEnv> {
    match model_xml {
        None => robosuite_env::make_with(env_name, config),
        Some(path) => RobosuiteEnv::from_scene_file(
            robosuite_env::make_task(env_name)?.as_ref(),
            path,
            config,
        ),
    }
}

/// Makes the robosuite task `env_name` with robosuite's keyword arguments (see
/// `robosuite_env::config::kwarg_names` and the task's own), optionally on the scene file
/// `model_xml`.
#[pyfunction]
#[pyo3(signature = (env_name, kwargs=None, model_xml=None))]
fn make_robosuite(
    py: Python<'_>,
    env_name: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
    model_xml: Option<PathBuf>,
) -> PyResult<PyRobosuiteEnv> {
    let config = config(env_name, kwargs)?;
    let env = py
        .detach(|| build(env_name, config, model_xml.as_ref()))
        .map_err(to_pyerr)?;
    Ok(PyRobosuiteEnv::new(env, env_name))
}

/// `num_envs` GymWrapper'd robosuite envs stepped in parallel Rust threads;
/// `max_episode_steps` wraps each in a `TimeLimit`.
#[pyfunction]
#[pyo3(signature = (env_name, num_envs, kwargs=None, keys=None, flatten_obs=true, model_xml=None, threads=None, max_episode_steps=None, pin_threads=false))]
#[allow(clippy::too_many_arguments)]
fn make_robosuite_vec(
    py: Python<'_>,
    env_name: &str,
    num_envs: usize,
    kwargs: Option<&Bound<'_, PyDict>>,
    keys: Option<Vec<String>>,
    flatten_obs: bool,
    model_xml: Option<PathBuf>,
    threads: Option<usize>,
    max_episode_steps: Option<u64>,
    pin_threads: bool,
) -> PyResult<PyVecEnv> {
    let envs = gym_wrapped(
        py,
        env_name,
        num_envs,
        kwargs,
        GymOptions {
            keys,
            flatten_obs,
            model_xml,
            max_episode_steps,
        },
    )?;
    PyVecEnv::new(envs, thread_options(threads, pin_threads))
}

/// `num_envs` GymWrapper'd robosuite envs in an asynchronous pool whose `recv` returns
/// `batch_size` of them; `max_episode_steps` wraps each in a `TimeLimit`.
#[pyfunction]
#[pyo3(signature = (env_name, num_envs, batch_size, kwargs=None, keys=None, flatten_obs=true, model_xml=None, threads=None, max_episode_steps=None, pin_threads=false))]
#[allow(clippy::too_many_arguments)]
fn make_robosuite_pool(
    py: Python<'_>,
    env_name: &str,
    num_envs: usize,
    batch_size: usize,
    kwargs: Option<&Bound<'_, PyDict>>,
    keys: Option<Vec<String>>,
    flatten_obs: bool,
    model_xml: Option<PathBuf>,
    threads: Option<usize>,
    max_episode_steps: Option<u64>,
    pin_threads: bool,
) -> PyResult<PyEnvPool> {
    let envs = gym_wrapped(
        py,
        env_name,
        num_envs,
        kwargs,
        GymOptions {
            keys,
            flatten_obs,
            model_xml,
            max_episode_steps,
        },
    )?;
    PyEnvPool::new(envs, batch_size, thread_options(threads, pin_threads))
}

/// Python's `threads` / `pin_threads` as [`ThreadOptions`].
fn thread_options(threads: Option<usize>, pin_threads: bool) -> ThreadOptions {
    ThreadOptions {
        num_threads: threads,
        pin: pin_threads,
    }
}

/// How each env of a vector or pool is wrapped: GymWrapper's `keys` / `flatten_obs`, the
/// scene file, and Gymnasium's `max_episode_steps` (a `TimeLimit` around the GymWrapper).
struct GymOptions {
    keys: Option<Vec<String>>,
    flatten_obs: bool,
    model_xml: Option<PathBuf>,
    max_episode_steps: Option<u64>,
}

/// `num_envs` robosuite envs behind a GymWrapper (and a `TimeLimit`), boxed.
fn gym_wrapped(
    py: Python<'_>,
    env_name: &str,
    num_envs: usize,
    kwargs: Option<&Bound<'_, PyDict>>,
    options: GymOptions,
) -> PyResult<Vec<BoxedEnv>> {
    let config = config(env_name, kwargs)?;
    let GymOptions {
        keys,
        flatten_obs,
        model_xml,
        max_episode_steps,
    } = options;
    py.detach(|| {
        (0..num_envs)
            .map(|_| {
                let env = build(env_name, config.clone(), model_xml.as_ref())?;
                // The flat wrapper's `step_into` writes the flat observation in place (the
                // same observations as GymWrapper's with `flatten_obs`).
                let gym = if flatten_obs {
                    adapters::FlatGymWrapper::new(env, keys.clone())?.boxed()
                } else {
                    adapters::GymWrapper::new(env, keys.clone(), false)?.boxed()
                };
                Ok(match max_episode_steps {
                    None => gym,
                    Some(steps) => adapters::TimeLimit::new(gym, steps)?.boxed(),
                })
            })
            .collect::<gym_core::Result<Vec<BoxedEnv>>>()
    })
    .map_err(to_pyerr)
}

/// Makes any env registered in `gym_core::registry` by id, as a [`PyEnv`].
#[pyfunction]
#[pyo3(signature = (env_id, kwargs=None))]
fn make_registered(
    py: Python<'_>,
    env_id: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyEnv> {
    let kwargs = serde_json::Value::Object(kwargs_json(kwargs)?);
    let env = py
        .detach(|| gym_core::registry::make(env_id, &kwargs))
        .map_err(to_pyerr)?;
    Ok(PyEnv::new(env))
}

/// The MJCF text of the scene the task `env_name` builds with these keyword arguments: a robosuite-style scene file for `make(..., model_xml=path)`.
#[pyfunction]
#[pyo3(signature = (env_name, kwargs=None))]
fn scene_xml(
    py: Python<'_>,
    env_name: &str,
    kwargs: Option<&Bound<'_, PyDict>>,
) -> PyResult<String> {
    let config = config(env_name, kwargs)?;
    py.detach(|| robosuite_env::scene_xml(env_name, &config))
        .map_err(to_pyerr)
}

/// Turns on (the default) or off the patching of cached scenes (a scene that differs from
/// one compiled before only in generated box sizes is made by resizing a copy of it); also
/// empties the cache of compiled scenes.
#[pyfunction]
fn set_scene_patching(enabled: bool) {
    robosuite_env::models::scene::set_scene_patching(enabled);
}

/// How many scenes were made by patching a cached one since the process started.
#[pyfunction]
fn scenes_patched() -> usize {
    robosuite_env::models::scene::scenes_patched()
}

/// Compiles (through the cache, as envs do) the MJCF text `xml` and saves the model as an
/// MJB file at `path` (for comparing models field by field).
#[pyfunction]
fn save_scene_model(py: Python<'_>, xml: &str, path: PathBuf) -> PyResult<()> {
    py.detach(|| {
        let model = robosuite_env::models::scene::compile_cached(xml)?;
        model
            .save_to_file(&path)
            .map_err(|e| gym_core::Error::model(format!("cannot save {}: {e}", path.display())))
    })
    .map_err(to_pyerr)
}

/// The folder of robosuite's package whose model files the envs are built from (what
/// robosuite's `edit_model_xml` points scene asset paths at).
#[pyfunction]
fn robosuite_package_dir() -> PyResult<String> {
    let assets = robosuite_env::assets::Assets::locate().map_err(to_pyerr)?;
    Ok(assets.package().to_string_lossy().into_owned())
}

/// Every id registered in `gym_core::registry`.
#[pyfunction]
fn registered_ids() -> Vec<String> {
    gym_core::registry::registered_ids()
}

/// The robosuite task names this build provides.
#[pyfunction]
fn robosuite_env_names() -> Vec<String> {
    robosuite_env::ENV_NAMES
        .iter()
        .map(|s| (*s).to_owned())
        .collect()
}

/// How many robots the robosuite task `env_name` takes by default (two for the two-arm
/// tasks, one otherwise).
#[pyfunction]
fn task_robot_count(env_name: &str) -> PyResult<usize> {
    Ok(robosuite_env::make_task(env_name)
        .map_err(to_pyerr)?
        .robots()
        .num_robots())
}

/// The robosuite task `env_name`'s own constructor arguments with their defaults, as JSON
/// text (robosuite's names and values: lists as arrays, `None` as `null`).
#[pyfunction]
fn task_options(env_name: &str) -> PyResult<String> {
    let spec = robosuite_env::make_task(env_name).map_err(to_pyerr)?;
    Ok(serde_json::Value::Object(spec.options()).to_string())
}

/// The keys of robosuite's `controller_configs` argument (a config dict or a list of them)
/// that robosuite's controllers ignore, and so does this package, as paths (for a
/// warning).
#[pyfunction]
fn controller_ignored_keys(configs: &Bound<'_, PyAny>) -> PyResult<Vec<String>> {
    Ok(match py_to_json(configs, "controller_configs")? {
        serde_json::Value::Array(list) => list
            .iter()
            .flat_map(robosuite_env::controllers::config::ignored_keys)
            .collect(),
        one => robosuite_env::controllers::config::ignored_keys(&one),
    })
}

/// robosuite's `make` keyword arguments this build takes besides the tasks' own (the
/// configuration schema's names, declared in Rust).
#[pyfunction]
fn supported_kwargs() -> Vec<&'static str> {
    robosuite_env::config::kwarg_names().to_vec()
}

/// robosuite's `load_composite_controller_config(controller, robot)`, as JSON text: the
/// dict robosuite returns, read from robosuite's own files.
#[pyfunction]
#[pyo3(signature = (controller=None, robot=None))]
fn load_composite_controller_config(
    controller: Option<&str>,
    robot: Option<&str>,
) -> PyResult<String> {
    let assets = robosuite_env::assets::Assets::locate().map_err(to_pyerr)?;
    robosuite_env::controllers::config::load_composite_controller_config(&assets, controller, robot)
        .map(|v| v.to_string())
        .map_err(to_pyerr)
}

/// robosuite's `load_part_controller_config(custom_fpath, default_controller)`, as JSON
/// text.
#[pyfunction]
#[pyo3(signature = (custom_fpath=None, default_controller=None))]
fn load_part_controller_config(
    custom_fpath: Option<PathBuf>,
    default_controller: Option<&str>,
) -> PyResult<String> {
    use robosuite_env::controllers::config as cc;
    let value = match (default_controller, custom_fpath) {
        (Some(kind), _) => {
            let assets = robosuite_env::assets::Assets::locate().map_err(to_pyerr)?;
            cc::load_part_controller_config(&assets, kind)
        }
        (None, Some(path)) => cc::read_json(&path),
        (None, None) => Err(gym_core::Error::invalid_argument(
            "default_controller",
            "give custom_fpath or default_controller (robosuite asserts the same)",
        )),
    };
    value.map(|v| v.to_string()).map_err(to_pyerr)
}

/// robosuite's robot model `name` on its own as robot `idn` (`robosuite.models.robots.
/// <name>(idn)`: names, figures and MJCF), as JSON text.
#[pyfunction]
#[pyo3(signature = (name, idn=0))]
fn describe_robot(name: &str, idn: usize) -> PyResult<String> {
    let assets = robosuite_env::assets::Assets::locate().map_err(to_pyerr)?;
    let description =
        robosuite_env::models::robots::describe_robot(&assets, name, idn).map_err(to_pyerr)?;
    serde_json::to_string(&description)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))
}

/// The robots this build provides (robosuite's names).
#[pyfunction]
fn robot_names() -> Vec<&'static str> {
    robosuite_env::models::robots::robot_names()
}

/// robosuite's robot class of each robot this build provides (`ROBOT_CLASS_MAPPING`).
#[pyfunction]
fn robot_classes() -> Vec<(&'static str, &'static str)> {
    robosuite_env::models::robots::ROBOTS
        .iter()
        .map(|r| (r.name, r.kind.class_name()))
        .collect()
}

/// robosuite's arm part controllers.
#[pyfunction]
fn part_controller_types() -> Vec<String> {
    robosuite_env::controllers::config::ARM_CONTROLLER_TYPES
        .iter()
        .map(|s| (*s).to_owned())
        .collect()
}

/// Adds robosuite-rs's classes and functions to `m` (the body of `robosuite_rs._native`).
///
/// # Errors
/// When Python refuses an attribute.
pub fn init(m: &Bound<'_, PyModule>) -> PyResult<()> {
    robosuite_env::register_envs();
    m.add_class::<PyEnv>()?;
    m.add_class::<PyVecEnv>()?;
    m.add_class::<PyEnvPool>()?;
    m.add_class::<PyRobosuiteEnv>()?;
    m.add_function(wrap_pyfunction!(make_robosuite, m)?)?;
    m.add_function(wrap_pyfunction!(robosuite_package_dir, m)?)?;
    m.add_function(wrap_pyfunction!(set_scene_patching, m)?)?;
    m.add_function(wrap_pyfunction!(scenes_patched, m)?)?;
    m.add_function(wrap_pyfunction!(save_scene_model, m)?)?;
    m.add_function(wrap_pyfunction!(make_robosuite_vec, m)?)?;
    m.add_function(wrap_pyfunction!(make_robosuite_pool, m)?)?;
    m.add_function(wrap_pyfunction!(make_registered, m)?)?;
    m.add_function(wrap_pyfunction!(registered_ids, m)?)?;
    m.add_function(wrap_pyfunction!(scene_xml, m)?)?;
    m.add_function(wrap_pyfunction!(robosuite_env_names, m)?)?;
    m.add_function(wrap_pyfunction!(task_robot_count, m)?)?;
    m.add_function(wrap_pyfunction!(supported_kwargs, m)?)?;
    m.add_function(wrap_pyfunction!(task_options, m)?)?;
    m.add_function(wrap_pyfunction!(controller_ignored_keys, m)?)?;
    m.add_function(wrap_pyfunction!(load_composite_controller_config, m)?)?;
    m.add_function(wrap_pyfunction!(load_part_controller_config, m)?)?;
    m.add_function(wrap_pyfunction!(part_controller_types, m)?)?;
    m.add_function(wrap_pyfunction!(describe_robot, m)?)?;
    m.add_function(wrap_pyfunction!(robot_names, m)?)?;
    m.add_function(wrap_pyfunction!(robot_classes, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
