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

/// One registered task: its name and its constructor with robosuite's defaults.
#[derive(Debug, Clone, Copy)]
pub struct TaskEntry {
    /// robosuite's environment name, such as `"Lift"` (the spec's [`TaskSpec::name`]).
    pub name: &'static str,
    /// The task with robosuite's default settings.
    pub make: fn() -> Box<dyn TaskSpec>,
}

fn boxed<T: TaskSpec + 'static>(spec: T) -> Box<dyn TaskSpec> {
    Box::new(spec)
}

fn pick_place(name: &str) -> Box<dyn TaskSpec> {
    boxed(PickPlaceSpec::variant(name).expect("a PickPlace variant"))
}

fn nut_assembly(name: &str) -> Box<dyn TaskSpec> {
    boxed(NutAssemblySpec::variant(name).expect("a NutAssembly variant"))
}

/// Every task this crate provides, in registration order: [`ENV_NAMES`], [`make_task`],
/// [`make`] and [`register_envs`] read this table. A task added here is available by name
/// everywhere (Rust, the registry, Python).
#[rustfmt::skip]
pub const TASKS: &[TaskEntry] = &[
    TaskEntry { name: "Lift", make: || boxed(LiftSpec::default()) },
    TaskEntry { name: "Stack", make: || boxed(StackSpec::default()) },
    TaskEntry { name: "NutAssembly", make: || nut_assembly("NutAssembly") },
    TaskEntry { name: "NutAssemblySingle", make: || nut_assembly("NutAssemblySingle") },
    TaskEntry { name: "NutAssemblySquare", make: || nut_assembly("NutAssemblySquare") },
    TaskEntry { name: "NutAssemblyRound", make: || nut_assembly("NutAssemblyRound") },
    TaskEntry { name: "PickPlace", make: || pick_place("PickPlace") },
    TaskEntry { name: "PickPlaceSingle", make: || pick_place("PickPlaceSingle") },
    TaskEntry { name: "PickPlaceMilk", make: || pick_place("PickPlaceMilk") },
    TaskEntry { name: "PickPlaceBread", make: || pick_place("PickPlaceBread") },
    TaskEntry { name: "PickPlaceCereal", make: || pick_place("PickPlaceCereal") },
    TaskEntry { name: "PickPlaceCan", make: || pick_place("PickPlaceCan") },
    TaskEntry { name: "Door", make: || boxed(DoorSpec::default()) },
    TaskEntry { name: "Wipe", make: || boxed(WipeSpec::default()) },
    TaskEntry { name: "ToolHang", make: || boxed(ToolHangSpec::default()) },
    TaskEntry { name: "TwoArmLift", make: || boxed(TwoArmLiftSpec::default()) },
    TaskEntry { name: "TwoArmPegInHole", make: || boxed(TwoArmPegInHoleSpec::default()) },
    TaskEntry { name: "TwoArmHandover", make: || boxed(TwoArmHandoverSpec::default()) },
    TaskEntry { name: "TwoArmTransport", make: || boxed(TwoArmTransportSpec::default()) },
];

const fn task_names<const N: usize>(tasks: &[TaskEntry]) -> [&'static str; N] {
    let mut names = [""; N];
    let mut i = 0;
    while i < N {
        names[i] = tasks[i].name;
        i += 1;
    }
    names
}

/// The environment names this crate provides: the names of [`TASKS`], in order.
pub const ENV_NAMES: &[&str] = &task_names::<{ TASKS.len() }>(TASKS);

/// The task registered under `name`, with robosuite's default settings.
///
/// # Errors
/// [`Error::UnknownEnv`] listing [`ENV_NAMES`].
pub fn make_task(name: &str) -> Result<Box<dyn TaskSpec>> {
    TASKS
        .iter()
        .find(|t| t.name == name)
        .map(|t| (t.make)())
        .ok_or_else(|| Error::UnknownEnv {
            id: name.to_owned(),
            available: ENV_NAMES.iter().map(|s| (*s).to_owned()).collect(),
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_makes_the_task_of_its_name() {
        assert_eq!(ENV_NAMES.len(), TASKS.len());
        for (entry, name) in TASKS.iter().zip(ENV_NAMES) {
            assert_eq!(entry.name, *name);
            assert_eq!((entry.make)().name(), entry.name);
            assert_eq!(make_task(name).unwrap().name(), entry.name);
        }
        assert!(matches!(make_task("Nope"), Err(Error::UnknownEnv { .. })));
    }
}
