//! Environments by name: [`make`], [`make_with`] and registration in
//! [`gym_core::registry`].

use crate::config::EnvConfig;
use crate::env::RobosuiteEnv;
use crate::tasks::{Door, Lift, LiftConfig, NutAssembly, PickPlace, Stack, Task, ToolHang, Wipe};
use gym_core::registry::{EnvSpec, register};
use gym_core::{Error, IntoBoxedEnv, Result};
use std::sync::Arc;

/// The environment names this crate provides.
pub const ENV_NAMES: &[&str] = &[
    "Lift",
    "Stack",
    "NutAssembly",
    "NutAssemblySingle",
    "NutAssemblySquare",
    "NutAssemblyRound",
    "PickPlace",
    "PickPlaceSingle",
    "PickPlaceMilk",
    "PickPlaceBread",
    "PickPlaceCereal",
    "PickPlaceCan",
    "Door",
    "Wipe",
    "ToolHang",
];

/// The task registered under `name`, with its default settings.
///
/// # Errors
/// [`Error::UnknownEnv`] listing [`ENV_NAMES`].
pub fn make_task(name: &str) -> Result<Box<dyn Task>> {
    match name {
        "Lift" => Ok(Box::new(Lift::new(LiftConfig::default())?)),
        "Stack" => Ok(Box::new(Stack::new())),
        "Door" => Ok(Box::new(Door::default())),
        "Wipe" => Ok(Box::new(Wipe::default())),
        "ToolHang" => Ok(Box::new(ToolHang::new())),
        n if n.starts_with("NutAssembly") => Ok(Box::new(NutAssembly::variant(n)?)),
        n if n.starts_with("PickPlace") => Ok(Box::new(PickPlace::variant(n)?)),
        other => Err(Error::UnknownEnv {
            id: other.to_owned(),
            available: ENV_NAMES.iter().map(|s| (*s).to_owned()).collect(),
        }),
    }
}

/// Makes the environment `name` with robosuite's defaults (Panda, `OSC_POSE`).
///
/// ```
/// let env = robosuite_env::make("Lift")?;
/// assert_eq!(env.action_dim(), 7);
/// # Ok::<(), gym_core::Error>(())
/// ```
///
/// # Errors
/// [`Error::UnknownEnv`] listing the valid names; [`Error::Model`] when the scene cannot
/// be built.
pub fn make(name: &str) -> Result<RobosuiteEnv> {
    make_with(name, default_config(name))
}

/// robosuite's default configuration for `name`: [`EnvConfig::default`], except that
/// `Wipe` shapes its reward by default.
pub fn default_config(name: &str) -> EnvConfig {
    EnvConfig::default().with_reward_shaping(name == "Wipe")
}

/// Makes the environment `name` with `config`.
///
/// # Errors
/// [`Error::UnknownEnv`] listing the valid names; [`Error::InvalidArgument`] for an invalid
/// configuration; [`Error::Model`] when the scene cannot be built.
pub fn make_with(name: &str, config: EnvConfig) -> Result<RobosuiteEnv> {
    RobosuiteEnv::new(make_task(name)?, config)
}

/// Makes the task `name` on a caller-supplied scene MJCF that follows robosuite's names.
///
/// # Errors
/// As [`RobosuiteEnv::from_scene_xml`], and [`Error::UnknownEnv`] for an unknown name.
pub fn make_from_scene_xml(name: &str, xml: &str, config: EnvConfig) -> Result<RobosuiteEnv> {
    RobosuiteEnv::from_scene_xml(make_task(name)?, xml, config)
}

/// The MJCF of the scene `make_with(name, config)` builds (with the cube at its mean size),
/// for inspection or for [`make_from_scene_xml`].
///
/// # Errors
/// As [`make_with`].
pub fn scene_xml(name: &str, config: &EnvConfig) -> Result<String> {
    let task = make_task(name)?;
    crate::env::compose_scene(task.as_ref(), config)?.to_xml()
}

/// Registers every environment of this crate in [`gym_core::registry`], so that
/// `gym_core::registry::make("Lift", &kwargs)` works (keyword arguments: see
/// [`EnvConfig::from_kwargs`]). Calling it again replaces the entries.
pub fn register_envs() {
    for &name in ENV_NAMES {
        register(EnvSpec {
            id: name.to_owned(),
            factory: Arc::new(move |kwargs| {
                let mut config = EnvConfig::from_kwargs(kwargs)?;
                if name == "Wipe" && kwargs.get("reward_shaping").is_none() {
                    config.reward_shaping = true;
                }
                Ok(make_with(name, config)?.boxed())
            }),
            max_episode_steps: None,
            nondeterministic: false,
            description: format!(
                "robosuite 1.5.2 {name} with a Panda arm, OSC_POSE and the Panda gripper"
            ),
        });
    }
}
