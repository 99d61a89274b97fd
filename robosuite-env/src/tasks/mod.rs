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
pub use crate::placement;
mod robot_setup;
mod stack;
pub mod table;
mod tool_hang;
pub mod two_arm;
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
use crate::models::arenas::Arena;
use crate::models::objects::ObjectModel;
use crate::models::robots::{GripperChoice, RobotModel};
use crate::observables::{ObsSpec, Observable, observe_all, specs};
use crate::robots::Robot;
use crate::sim::Sim;
use gym_core::{EnvRng, Result};
use mujoco_rs::wrappers::mj_model::MjModel;
pub use robot_setup::RobotSetup;

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

    /// The robots the task takes and where they stand (robosuite's
    /// `_check_robot_configuration` and the robot placement of its `_load_model`): the
    /// environment checks the configured robots against it and places them in the arena
    /// [`TaskSpec::build`] returns. The default is one single-arm robot.
    fn robots(&self) -> RobotSetup {
        RobotSetup::SingleArm
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

    /// robosuite's `_load_model`: builds the arena and the objects (the environment then
    /// places the robots as [`TaskSpec::robots`] says; a task may edit the robot models,
    /// as TwoArmPegInHole attaches its peg and hole to the hands). Sizes robosuite draws at
    /// every hard reset are built at a fixed value here and drawn by
    /// [`TaskLogic::randomize_model`] at every reset instead, so equal configurations
    /// compose equal scenes (and share one compiled model).
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when a model file is missing or malformed;
    /// [`gym_core::Error::InvalidArgument`] for an invalid task configuration.
    fn build(&self, assets: &Assets, robots: &mut [RobotModel]) -> Result<TaskScene>;

    /// Binds the task to the compiled scene: resolves every body, joint, geom and site it
    /// uses, and returns the run-time task with its observables
    /// (`Ok(Bound::boxed(task, observables))`, see [`Bound`]).
    ///
    /// # Errors
    /// [`gym_core::Error::Model`] when the model lacks a name robosuite gives.
    fn bind(&self, scene: &TaskScene, model: &MjModel, robots: &[Robot]) -> Result<Box<dyn Task>>;
}

/// What a task does at run time (the per-episode part of robosuite's environment
/// classes), written once per task; [`Bound`] pairs it with its observables into the
/// [`Task`] the environment runs.
///
/// The environment calls, on each reset, [`TaskLogic::randomize_model`] (before the robots
/// draw their noise), then [`TaskLogic::place_objects`] (after); on each step
/// [`TaskLogic::on_policy_step`] at the first substep, then after the physics
/// [`TaskLogic::reward`], [`TaskLogic::after_reward`], [`TaskLogic::check_success`] and
/// [`TaskLogic::check_terminated`]; and around every observation pass
/// [`TaskLogic::before_observe`] and [`TaskLogic::after_observe`].
pub trait TaskLogic: Send + std::fmt::Debug + 'static {
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

    /// Called before each observation pass reads the observables (Wipe computes what its
    /// observables share). The default does nothing.
    fn before_observe(&mut self, _sim: &Sim) {}

    /// Called after each observation pass (robosuite's sensors that read the observation
    /// cache remember the pass here, see [`common::ObjectSensors`]). The default does
    /// nothing.
    fn after_observe(&mut self, _sim: &Sim) {}

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

    /// Restores a state from [`TaskLogic::save_state`], editing the model if needed; the
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
                format!("the task has no task state, got {} values", state.len()),
            ))
        }
    }
}

/// A task bound to a compiled scene: its [`TaskLogic`] and its observables (in robosuite's
/// order, read from the task). It implements [`Task`].
#[derive(Debug, Clone)]
pub struct Bound<T> {
    logic: T,
    observables: Vec<Observable<T>>,
}

impl<T: TaskLogic> Bound<T> {
    /// `logic` with its `observables`.
    pub fn new(logic: T, observables: Vec<Observable<T>>) -> Self {
        Self { logic, observables }
    }

    /// [`Bound::new`], boxed as [`TaskSpec::bind`] returns it.
    pub fn boxed(logic: T, observables: Vec<Observable<T>>) -> Box<dyn Task> {
        Box::new(Self::new(logic, observables))
    }

    /// The task's logic.
    pub fn logic(&self) -> &T {
        &self.logic
    }
}

/// A task bound to a compiled scene, as the environment runs it: [`Bound`] implements it
/// for every [`TaskLogic`] (see there for what each method does).
pub trait Task: Send + std::fmt::Debug {
    /// [`TaskLogic::randomize_model`].
    ///
    /// # Errors
    /// As [`TaskLogic::randomize_model`].
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()>;

    /// [`TaskLogic::place_objects`].
    ///
    /// # Errors
    /// As [`TaskLogic::place_objects`].
    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()>;

    /// [`TaskLogic::clear_observation_cache`].
    fn clear_observation_cache(&mut self);

    /// The specs of the task's observables, in robosuite's order (object observables, and
    /// robot ones a task adds, such as Wipe's `robot0_contact`).
    fn observation_specs(&self) -> Vec<ObsSpec>;

    /// Writes the task's observables, in the order of [`Task::observation_specs`]: one
    /// observation pass (after each step and each reset).
    fn observe(&mut self, sim: &Sim, out: &mut [f64]);

    /// [`TaskLogic::reward`].
    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64;

    /// [`TaskLogic::check_success`].
    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool;

    /// [`TaskLogic::check_terminated`].
    fn check_terminated(&self, sim: &Sim, robots: &[Robot]) -> bool;

    /// [`TaskLogic::on_policy_step`].
    fn on_policy_step(&mut self, sim: &Sim, robots: &[Robot]);

    /// [`TaskLogic::after_reward`].
    fn after_reward(&mut self, sim: &mut Sim, robots: &[Robot], config: &RewardConfig);

    /// [`TaskLogic::save_state`].
    fn save_state(&self) -> Vec<f64>;

    /// [`TaskLogic::load_state`].
    ///
    /// # Errors
    /// As [`TaskLogic::load_state`].
    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()>;
}

impl<T: TaskLogic> Task for Bound<T> {
    fn randomize_model(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        self.logic.randomize_model(sim, rng)
    }

    fn place_objects(&mut self, sim: &mut Sim, rng: &mut EnvRng) -> Result<()> {
        self.logic.place_objects(sim, rng)
    }

    fn clear_observation_cache(&mut self) {
        self.logic.clear_observation_cache();
    }

    fn observation_specs(&self) -> Vec<ObsSpec> {
        specs(&self.observables)
    }

    fn observe(&mut self, sim: &Sim, out: &mut [f64]) {
        self.logic.before_observe(sim);
        observe_all(&self.observables, &self.logic, sim, out);
        self.logic.after_observe(sim);
    }

    fn reward(&self, sim: &Sim, robots: &[Robot], config: &RewardConfig) -> f64 {
        self.logic.reward(sim, robots, config)
    }

    fn check_success(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.logic.check_success(sim, robots)
    }

    fn check_terminated(&self, sim: &Sim, robots: &[Robot]) -> bool {
        self.logic.check_terminated(sim, robots)
    }

    fn on_policy_step(&mut self, sim: &Sim, robots: &[Robot]) {
        self.logic.on_policy_step(sim, robots);
    }

    fn after_reward(&mut self, sim: &mut Sim, robots: &[Robot], config: &RewardConfig) {
        self.logic.after_reward(sim, robots, config);
    }

    fn save_state(&self) -> Vec<f64> {
        self.logic.save_state()
    }

    fn load_state(&mut self, sim: &mut Sim, state: &[f64]) -> Result<()> {
        self.logic.load_state(sim, state)
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
