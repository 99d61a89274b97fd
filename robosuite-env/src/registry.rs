//! Environments by name: [`make`], [`make_with`] and registration in
//! [`gym_core::registry`].

use crate::assets::Assets;
use crate::config::EnvConfig;
use crate::env::RobosuiteEnv;
use crate::tasks::{
    DoorSpec, LiftSpec, NutAssemblySpec, PickPlaceSpec, StackSpec, TaskSpec, ToolHangSpec,
    TwoArmHandoverSpec, TwoArmLiftSpec, TwoArmPegInHoleSpec, TwoArmTransportSpec, WipeSpec,
};
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
    "TwoArmLift",
    "TwoArmPegInHole",
    "TwoArmHandover",
    "TwoArmTransport",
];

/// The task registered under `name`, with robosuite's default settings.
///
/// # Errors
/// [`Error::UnknownEnv`] listing [`ENV_NAMES`].
pub fn make_task(name: &str) -> Result<Box<dyn TaskSpec>> {
    match name {
        "Lift" => Ok(Box::new(LiftSpec::default())),
        "Stack" => Ok(Box::new(StackSpec::default())),
        "Door" => Ok(Box::new(DoorSpec::default())),
        "Wipe" => Ok(Box::new(WipeSpec::default())),
        "ToolHang" => Ok(Box::new(ToolHangSpec::default())),
        "TwoArmLift" => Ok(Box::new(TwoArmLiftSpec::default())),
        "TwoArmPegInHole" => Ok(Box::new(TwoArmPegInHoleSpec::default())),
        "TwoArmHandover" => Ok(Box::new(TwoArmHandoverSpec::default())),
        "TwoArmTransport" => Ok(Box::new(TwoArmTransportSpec::default())),
        other => {
            if let Some(spec) = PickPlaceSpec::variant(other) {
                return Ok(Box::new(spec));
            }
            if let Some(spec) = NutAssemblySpec::variant(other) {
                return Ok(Box::new(spec));
            }
            Err(Error::UnknownEnv {
                id: other.to_owned(),
                available: ENV_NAMES.iter().map(|s| (*s).to_owned()).collect(),
            })
        }
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
    make_with(name, EnvConfig::default())
}

/// Makes the environment `name` with `config`.
///
/// # Errors
/// [`Error::UnknownEnv`] listing the valid names; [`Error::InvalidArgument`] for an invalid
/// configuration; [`Error::Model`] when the scene cannot be built.
pub fn make_with(name: &str, config: EnvConfig) -> Result<RobosuiteEnv> {
    RobosuiteEnv::new(make_task(name)?.as_ref(), config)
}

/// Makes the task `name` on a caller-supplied scene MJCF that follows robosuite's names.
///
/// # Errors
/// As [`RobosuiteEnv::from_scene_xml`], and [`Error::UnknownEnv`] for an unknown name.
pub fn make_from_scene_xml(name: &str, xml: &str, config: EnvConfig) -> Result<RobosuiteEnv> {
    RobosuiteEnv::from_scene_xml(make_task(name)?.as_ref(), xml, config)
}

/// The MJCF robosuite would compile for `make_with(name, config)` (its `get_xml()`: the
/// composed scene with robosuite's `njmax`/`nconmax`), for inspection or for
/// [`make_from_scene_xml`].
///
/// # Errors
/// As [`make_with`].
pub fn scene_xml(name: &str, config: &EnvConfig) -> Result<String> {
    let spec = make_task(name)?;
    let assets = Assets::locate()?;
    Ok(crate::env::compose_scene(spec.as_ref(), config, &assets)?.to_xml())
}

/// Registers every environment of this crate in [`gym_core::registry`], so that
/// `gym_core::registry::make("Lift", &kwargs)` works (robosuite's keyword arguments: see
/// [`EnvConfig::from_kwargs`]). Calling it again replaces the entries.
pub fn register_envs() {
    for &name in ENV_NAMES {
        register(EnvSpec {
            id: name.to_owned(),
            factory: Arc::new(move |kwargs| {
                let config = EnvConfig::from_kwargs(name, kwargs)?;
                Ok(make_with(name, config)?.boxed())
            }),
            max_episode_steps: None,
            nondeterministic: false,
            description: format!("robosuite 1.5.2 {name} on robosuite's own model files"),
        });
    }
}
