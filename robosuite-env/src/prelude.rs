//! What a user and a task author need, in one import: `use robosuite_env::prelude::*;`.
//!
//! * Using environments: [`make`], [`make_with`], [`EnvConfig`], [`RobosuiteEnv`], the
//!   task table ([`TASKS`], [`ENV_NAMES`]) and [`Env`] (reset and step).
//! * Writing a task (see `examples/custom_task.rs`): [`TaskSpec`] (scene and binding),
//!   [`TaskLogic`] (run time) wrapped by [`Bound`], [`RobotSetup`], [`Observable`] with
//!   [`Modality`], the placement samplers, the table and two-arm helpers, and the model
//!   and simulator types their signatures use.

pub use crate::assets::Assets;
pub use crate::config::{EnvConfig, EnvConfiguration};
pub use crate::env::RobosuiteEnv;
pub use crate::models::arenas::Arena;
pub use crate::models::objects::primitive::Primitive;
pub use crate::models::objects::{ObjectModel, Shape};
pub use crate::models::robots::RobotModel;
pub use crate::observables::{Modality, Observable};
pub use crate::placement::{
    Axis, PlacedObject, Pose, Rotation, SequentialCompositeSampler, UniformRandomSampler,
};
pub use crate::registry::{ENV_NAMES, TASKS, TaskEntry, make, make_task, make_with};
pub use crate::robots::Robot;
pub use crate::sim::Sim;
pub use crate::tasks::common::{
    FreeBody, dist, eef_pos, geoms_of, is_grasped, robot0_grasps, scale_reward, sub, wood_material,
};
pub use crate::tasks::table::{TABLE_OFFSET, place_single_robot, table_arena};
pub use crate::tasks::two_arm::{ArmRef, task_arms};
pub use crate::tasks::{
    Bound, RewardConfig, RobotSetup, Task, TaskLogic, TaskOptions, TaskScene, TaskSpec,
};
pub use gym_core::{Env, EnvRng, Error, Result};
pub use mujoco_rs::wrappers::mj_model::MjModel;
