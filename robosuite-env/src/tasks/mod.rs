//! Tasks: what a manipulation environment adds to its robots (arena, objects, placement,
//! observations, reward, success).
//!
//! A [`Task`] is object safe; [`RobosuiteEnv`](crate::RobosuiteEnv) holds one as
//! `Box<dyn Task>`, so every robosuite task plugs into the same environment mechanics.

pub mod common;
mod door;
mod lift;
mod nut_assembly;
mod pick_place;
pub mod placement;
mod stack;
mod tool_hang;
mod wipe;

pub use door::{Door, DoorConfig, door_xml};
pub use lift::{Lift, LiftConfig};
pub use nut_assembly::{NutAssembly, PEG_POS, pegs_arena_xml};
pub use pick_place::{PickPlace, bins_arena_xml, in_quadrant, target_placement};
pub use stack::Stack;
pub use tool_hang::{ToolHang, frame_xml, stand_xml, tool_xml};
pub use wipe::{Wipe, WipeConfig};

use crate::models::scene::SceneBuilder;
use crate::observations::ObsKey;
use crate::robots::{Robot, RobotSpec};
use crate::sim::Sim;
use gym_core::{EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;

/// Where the compiled model came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelSource {
    /// Built by this crate from its own parts: the task may resize its objects on reset
    /// (robosuite's hard reset).
    Generated,
    /// A scene MJCF supplied by the caller (for instance exported from robosuite): object
    /// sizes stay as the file says (robosuite's soft reset).
    Supplied,
}

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

/// A robosuite task.
///
/// The environment calls, in order: [`Task::arena_xml`], [`Task::robot_base_pose`] and
/// [`Task::build_objects`] while composing the model (robots are added in between, so robot joints precede object
/// joints), [`Task::bind`] once compiled; on each reset [`Task::randomize_model`] (before
/// the robots draw their noise), then [`Task::place_objects`] (after); after each step
/// [`Task::reward`], [`Task::check_success`], [`Task::check_terminated`] and the object
/// observations.
pub trait Task: Send + std::fmt::Debug + 'static {
    /// robosuite's environment name, such as `"Lift"`.
    fn name(&self) -> &str;

    /// The number of robots the task needs.
    fn num_robots(&self) -> usize {
        1
    }

    /// The base position and orientation (wxyz) of robot `index`.
    fn robot_base_pose(&self, index: usize) -> ([f64; 3], [f64; 4]);

    /// The arena's MJCF; the content of its `<worldbody>` becomes the world's (see
    /// [`SceneBuilder::with_arena`]).
    fn arena_xml(&self) -> String;

    /// Adds the objects (after the robots are added).
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when a part does not attach.
    fn build_objects(&self, scene: &mut SceneBuilder) -> Result<()>;

    /// Resolves the task's bodies, joints, geoms and sites in the compiled model.
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when a name is missing.
    fn bind(&mut self, model: &MjModel, robots: &[Robot], source: ModelSource) -> Result<()>;

    /// Re-draws model parameters (object sizes) without recompiling; called first in every
    /// reset. The default does nothing.
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when the model cannot be edited.
    fn randomize_model(&mut self, _sim: &mut Sim, _rng: &mut EnvRng) -> Result<()> {
        Ok(())
    }

    /// Places the objects (writes their free-joint `qpos` or body poses); called after the
    /// robots were reset.
    ///
    /// # Errors
    /// [`gym_core::Error::Simulation`] when no valid placement is found.
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()>;

    /// The object observation keys, in robosuite's order (`object-state` concatenates them).
    fn observation_keys(&self) -> Vec<ObsKey>;

    /// Writes the object observations into `out`.
    fn write_observations(&self, sim: &Sim, robots: &[Robot], out: &mut [f64]);

    /// The reward for the current state.
    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64;

    /// Whether the task is solved in the current state.
    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool;

    /// The task's mutable state (for example randomised sizes), for snapshots. The default
    /// is empty.
    fn save_state(&self) -> Vec<f64> {
        Vec::new()
    }

    /// Restores a state from [`Task::save_state`], editing the model if needed; the
    /// environment restores the simulator state afterwards. The default does nothing.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for a state of the wrong shape.
    fn load_state(&mut self, _sim: &mut Sim, _state: &[f64]) -> Result<()> {
        Ok(())
    }

    /// Whether the episode ends early (only robosuite's Wipe does). The default is `false`.
    fn check_terminated(&self, _sim: &Sim, _robots: &[Robot]) -> bool {
        false
    }

    /// The robot the task uses for robot `index`, given the configured one (Wipe swaps in
    /// its wiping tool for the gripper). The default keeps it.
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] when the task cannot use the robot.
    fn robot_spec(&self, _index: usize, spec: RobotSpec) -> Result<RobotSpec> {
        Ok(spec)
    }

    /// Extra keys the task appends to robot `index`'s proprioception (Wipe's
    /// `robot0_contact`). The default has none.
    fn robot_observation_keys(&self, _index: usize) -> Vec<ObsKey> {
        Vec::new()
    }

    /// Writes the keys of [`Task::robot_observation_keys`].
    fn write_robot_observations(
        &self,
        _sim: &Sim,
        _robots: &[Robot],
        _index: usize,
        _out: &mut [f64],
    ) {
    }

    /// Called on the first substep of every env step, after the controllers wrote their
    /// controls (where robosuite pushes its per-step force/torque buffers). The default
    /// does nothing.
    fn on_policy_step(&mut self, _sim: &Sim, _robots: &[Robot]) {}

    /// Called after the step's reward was computed and before success and termination are
    /// checked (robosuite's reward updates Wipe's wiped markers). The default does
    /// nothing.
    fn after_reward(&mut self, _sim: &mut Sim, _robots: &[Robot], _config: &RewardConfig) {}
}
