//! Tasks: what a manipulation environment adds to its robots (arena, objects, placement,
//! observables, reward, success).
//!
//! A task comes in two types. A [`TaskSpec`] is its configuration: it builds its part of
//! the scene from robosuite's model files ([`TaskSpec::build`]: arena, objects, robot
//! placement) and, once the scene is compiled, binds to it ([`TaskSpec::bind`]), returning
//! the [`Task`] that runs episodes. A bound task holds every id it needs; there is no
//! half-built state.

pub mod common;
mod door;
mod lift;
pub mod mode_objects;
mod nut_assembly;
pub mod options;
mod pick_place;
pub mod placement;
mod stack;
mod tool_hang;
mod two_arm;
mod two_arm_handover;
mod two_arm_lift;
mod two_arm_peg_in_hole;
mod two_arm_transport;
mod wipe;

pub use door::{Door, DoorSpec};
pub use lift::{Lift, LiftSpec};
pub use nut_assembly::{NUTS, NutAssembly, NutAssemblySpec};
pub use options::TaskOptions;
pub use pick_place::{PICK_PLACE_OBJECTS, PickPlace, PickPlaceSpec};
pub use stack::{CUBE_A_HALF, CUBE_B_HALF, Stack, StackSpec};
pub use tool_hang::{ToolHang, ToolHangSpec};
pub use two_arm_handover::{TwoArmHandover, TwoArmHandoverSpec};
pub use two_arm_lift::{TwoArmLift, TwoArmLiftSpec};
pub use two_arm_peg_in_hole::{TwoArmPegInHole, TwoArmPegInHoleSpec};
pub use two_arm_transport::{TwoArmTransport, TwoArmTransportSpec};
pub use wipe::{Wipe, WipeConfig, WipeSpec};

use crate::assets::Assets;
use crate::config::EnvConfiguration;
use crate::models::arenas::Arena;
use crate::models::objects::ObjectModel;
use crate::models::robots::{GripperChoice, RobotInfo, RobotModel};
use crate::observables::ObsSpec;
use crate::robots::Robot;
use crate::sim::Sim;
use gym_core::{EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// Reward settings shared by all tasks (robosuite's `reward_scale` and `reward_shaping`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RewardConfig {
    /// Scale of the maximal reward; `None` leaves rewards unnormalised.
    pub reward_scale: Option<f64>,
    /// Dense staged rewards instead of the sparse success reward.
    pub reward_shaping: bool,
    /// The episode length (Wipe normalises its reward by it).
    pub horizon: u64,
}

/// A task's part of the scene: the arena and the objects, in robosuite's merge order.
#[derive(Debug, Clone)]
pub struct TaskScene {
    /// The arena.
    pub arena: Arena,
    /// The objects.
    pub objects: Vec<ObjectModel>,
    /// Objects the task attached inside a robot's model (TwoArmPegInHole's peg and hole):
    /// only their assets are merged, after the objects'.
    pub attached: Vec<ObjectModel>,
}

/// A task's configuration: robosuite's environment class before `_load_model`.
pub trait TaskSpec: TaskSpecClone + Send + Sync + std::fmt::Debug {
    /// robosuite's environment name, such as `"Lift"`.
    fn name(&self) -> &str;

    /// The task's robosuite constructor arguments as they stand, by robosuite's names
    /// (Lift: `table_full_size`, `table_friction`); empty for a task that takes none.
    fn options(&self) -> TaskOptions {
        TaskOptions::new()
    }

    /// Sets robosuite constructor arguments by name (see [`TaskSpec::options`]); the values
    /// are checked when the scene is built.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] naming an argument the task does not take
    /// (listing those it takes) or a value of the wrong type; the task is unchanged then.
    fn configure(&mut self, options: &TaskOptions) -> Result<()> {
        match options.keys().next() {
            None => Ok(()),
            Some(key) => Err(options::unknown(self.name(), key, std::iter::empty())),
        }
    }

    /// The number of robots the task takes by default (a Panda each when
    /// [`crate::EnvConfig::robots`] is empty); [`TaskSpec::check_robots`] says what else it
    /// takes (the two-arm tasks also take one bimanual robot).
    fn num_robots(&self) -> usize {
        1
    }

    /// robosuite's `_check_robot_configuration`: checks the robots and the requested
    /// `env_configuration` and returns the configuration the task runs with. The default is
    /// a single-arm task's: [`TaskSpec::num_robots`] single-arm robots and `"default"`.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] naming `robots` or `env_configuration` and
    /// listing what is valid.
    fn check_robots(
        &self,
        robots: &[RobotInfo],
        configuration: EnvConfiguration,
    ) -> Result<EnvConfiguration> {
        let need = self.num_robots();
        if robots.len() != need {
            return Err(gym_core::Error::invalid_argument(
                "robots",
                format!(
                    "{} needs {need} single-arm robot(s), got {} ({:?}); valid robots: {}",
                    self.name(),
                    robots.len(),
                    robots.iter().map(|r| r.name).collect::<Vec<_>>(),
                    crate::models::robots::single_arm_robot_names().join(", ")
                ),
            ));
        }
        if let Some(r) = robots.iter().find(|r| r.arms.len() != 1) {
            return Err(gym_core::Error::invalid_argument(
                "robots",
                format!(
                    "{} is a single-arm task and {} is bimanual; valid robots: {}",
                    self.name(),
                    r.name,
                    crate::models::robots::single_arm_robot_names().join(", ")
                ),
            ));
        }
        if configuration != EnvConfiguration::Default {
            return Err(gym_core::Error::invalid_argument(
                "env_configuration",
                format!(
                    "{} is a single-arm task: only `default` is valid, got `{}`",
                    self.name(),
                    configuration.as_str()
                ),
            ));
        }
        Ok(configuration)
    }

    /// The gripper the task needs on arm `arm` of robot `robot` given the configured
    /// choice, or an error when the task cannot take it (robosuite's Wipe requires its
    /// wiping tool). The default takes the configured choice.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] naming what the task needs.
    fn gripper(
        &self,
        _robot: usize,
        _arm: usize,
        configured: &GripperChoice,
    ) -> Result<GripperChoice> {
        Ok(configured.clone())
    }

    /// Whether the task shapes its reward by default (robosuite: only Wipe).
    fn default_reward_shaping(&self) -> bool {
        false
    }

    /// Bytes of MuJoCo arena per `mjData` (contacts, constraints, solver stack).
    fn memory(&self) -> usize {
        crate::models::scene::DEFAULT_MEMORY
    }

    /// robosuite's `_load_model`: places the robots and builds the arena and the objects.
    /// Sizes robosuite draws at every hard reset are built at a fixed value here and drawn
    /// by [`Task::randomize_model`] at every reset instead, so equal configurations compose
    /// equal scenes (and share one compiled model).
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when a model file is missing or malformed;
    /// [`gym_core::Error::InvalidArgument`] for an invalid task configuration.
    fn build(&self, assets: &Assets, robots: &mut [RobotModel]) -> Result<TaskScene>;

    /// [`TaskSpec::build`] for the configuration [`TaskSpec::check_robots`] returned (how
    /// two-arm tasks place their robots). The default ignores it.
    ///
    /// # Errors
    /// As [`TaskSpec::build`].
    fn build_configured(
        &self,
        assets: &Assets,
        robots: &mut [RobotModel],
        _configuration: EnvConfiguration,
    ) -> Result<TaskScene> {
        self.build(assets, robots)
    }

    /// Binds the task to the compiled scene: resolves every body, joint, geom and site it
    /// uses.
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when the model lacks a name robosuite gives.
    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>>;
}

/// A task bound to a compiled scene: the per-episode part of robosuite's environment
/// classes.
///
/// The environment calls, on each reset, [`Task::randomize_model`] (before the robots draw
/// their noise), then [`Task::place_objects`] (after); on each step [`Task::on_policy_step`]
/// at the first substep, then after the physics [`Task::reward`], [`Task::after_reward`],
/// [`Task::check_success`] and [`Task::check_terminated`]; and [`Task::observe`] whenever
/// it builds an observation.
pub trait Task: Send + std::fmt::Debug {
    /// robosuite's environment name.
    fn name(&self) -> &str;

    /// Re-draws model parameters (object sizes, marker layouts) without recompiling;
    /// called first in every reset. The default does nothing.
    ///
    /// # Errors
    /// [`gym_core::Error::Simulation`] when no valid layout is found.
    fn randomize_model(&mut self, _sim: &mut Sim, _rng: &mut EnvRng) -> Result<()> {
        Ok(())
    }

    /// Places the objects (writes their free-joint `qpos` or body poses); called after the
    /// robots were reset.
    ///
    /// # Errors
    /// [`gym_core::Error::Simulation`] when no valid placement is found.
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()>;

    /// Clears the task's observation cache (every reset, before the first observation
    /// pass). The default has none.
    fn clear_observation_cache(&mut self) {}

    /// The specs of the task's observables, in robosuite's order (object observables, and
    /// robot ones a task adds, such as Wipe's `robot0_contact`).
    fn observation_specs(&self) -> Vec<ObsSpec>;

    /// Writes the task's observables, in the order of [`Task::observation_specs`]: one
    /// observation pass (after each step and each reset). Mutable because some of
    /// robosuite's sensors read its observation cache, the values of the previous pass
    /// (see [`common::ObjectSensors`]).
    fn observe(&mut self, sim: &Sim, out: &mut [f64]);

    /// The reward for the current state.
    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64;

    /// Whether the task is solved in the current state.
    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool;

    /// Whether the episode ends early (only robosuite's Wipe does). The default is `false`.
    fn check_terminated(&self, _sim: &Sim, _robots: &[Robot]) -> bool {
        false
    }

    /// Called on the first substep of every env step, after the controllers wrote their
    /// controls (where robosuite pushes its per-step force/torque buffers). The default
    /// does nothing.
    fn on_policy_step(&mut self, _sim: &Sim, _robots: &[Robot]) {}

    /// Called after the step's reward was computed and before success and termination are
    /// checked (robosuite's reward updates Wipe's wiped markers). The default does nothing.
    fn after_reward(&mut self, _sim: &mut Sim, _robots: &[Robot], _config: &RewardConfig) {}

    /// The task's randomised model parameters and episode state (Lift's cube size, Wipe's
    /// markers), for snapshots and replays. The default is empty.
    fn save_state(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Restores a state from [`Task::save_state`], editing the model if needed; the
    /// environment restores the simulator state afterwards. The default accepts only an
    /// empty state.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for a state of the wrong shape; nothing is
    /// changed then.
    fn load_state(&mut self, _sim: &mut Sim, state: &[f64]) -> Result<()> {
        if state.is_empty() {
            Ok(())
        } else {
            Err(gym_core::Error::invalid_argument(
                "task state",
                format!(
                    "{} has no task state, got {} values",
                    self.name(),
                    state.len()
                ),
            ))
        }
    }
}

/// Copying a boxed [`TaskSpec`] (implemented for every `TaskSpec` that is `Clone`).
pub trait TaskSpecClone {
    /// A copy of this task's configuration.
    fn clone_box(&self) -> Box<dyn TaskSpec>;
}

impl<T: TaskSpec + Clone + 'static> TaskSpecClone for T {
    fn clone_box(&self) -> Box<dyn TaskSpec> {
        Box::new(self.clone())
    }
}

/// `spec` with `config`'s task arguments ([`crate::EnvConfig::task_options`]) applied.
///
/// # Errors
/// As [`TaskSpec::configure`].
pub(crate) fn configured(
    spec: &dyn TaskSpec,
    config: &crate::EnvConfig,
) -> Result<Box<dyn TaskSpec>> {
    let mut spec = spec.clone_box();
    spec.configure(&config.task_options)?;
    Ok(spec)
}
