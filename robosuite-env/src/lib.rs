//! robosuite 1.5.2's manipulation tasks on MuJoCo 3.17.0, in Rust.
//!
//! ```no_run
//! use gym_core::Env;
//! use ndarray::ArrayD;
//!
//! let mut env = robosuite_env::make("Lift")?;
//! let (obs, _info) = env.reset(Some(0), None)?;
//! assert_eq!(obs.len(), 15);
//! let step = env.step(&ArrayD::zeros(ndarray::IxDyn(&[7])))?;
//! println!("reward {} success {:?}", step.reward, step.info.get_bool("success"));
//! # Ok::<(), gym_core::Error>(())
//! ```
//!
//! Layout:
//! * [`models`]: our own MJCF parts (world, table arena, Panda arm, mount, gripper,
//!   objects) and the [`SceneBuilder`](models::scene::SceneBuilder) that composes them with
//!   robosuite's names;
//! * [`sim`]: the simulator an environment owns, name lookups, contacts, in-place model edits;
//! * [`controllers`]: `OSC_POSE` and the gripper controller;
//! * [`robots`]: robot descriptions and the run-time [`Robot`](robots::Robot);
//! * [`tasks`]: the [`Task`](tasks::Task) trait, placement samplers and the tasks (Lift,
//!   Stack, NutAssembly*, PickPlace*, Door, Wipe, ToolHang);
//! * [`observations`]: robosuite's ordered observation dict;
//! * [`RobosuiteEnv`], [`EnvConfig`] and the name registry ([`make`], [`make_with`],
//!   [`register_envs`]).

pub mod config;
pub mod controllers;
pub mod env;
pub mod models;
pub mod observations;
pub mod registry;
pub mod robots;
pub mod sim;
pub mod tasks;

pub use config::EnvConfig;
pub use env::{EnvSnapshot, RobosuiteEnv};
pub use registry::{
    ENV_NAMES, default_config, make, make_from_scene_xml, make_task, make_with, register_envs,
    scene_xml,
};
pub use robots::{InitNoise, NoiseKind};
