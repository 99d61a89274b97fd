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
//! * [`assets`]: where robosuite's own model files are (fetched by the build);
//! * [`models`]: robosuite's model classes (arenas, robots, mounts, grippers, objects) and
//!   the scene composed from them;
//! * [`sim`]: the simulator an environment owns, name lookups, contacts, in-place model edits;
//! * [`controllers`]: the arm controller abstraction, robosuite's six arm controllers and
//!   `GRIP`, and robosuite's controller configs;
//! * [`robots`]: robots bound to a compiled scene, with arms, grippers and observables;
//! * [`observables`]: robosuite's observables and its ordered observation dict;
//! * [`cameras`]: camera observations: their arguments, one env's camera rig and robosuite's
//!   segmentation groups; `render` (feature `render`): MuJoCo's offscreen renderer on
//!   EGL, the backend that draws them;
//! * [`tasks`]: [`TaskSpec`](tasks::TaskSpec) and [`TaskLogic`](tasks::TaskLogic) (run in
//!   a [`Bound`](tasks::Bound) [`Task`](tasks::Task)), the table and two-arm helpers, and
//!   the tasks;
//! * [`placement`]: robosuite's placement samplers;
//! * [`wrappers`]: robosuite's `VisualizationWrapper` and `DomainRandomizationWrapper`,
//!   with the [`modders`] (texture, camera, lighting, dynamics) the latter runs;
//! * [`prelude`]: what a user and a task author need, in one import;
//! * [`RobosuiteEnv`], [`EnvConfig`] and the name registry ([`make`], [`make_with`],
//!   [`register_envs`]), all reading one table of tasks ([`TASKS`]).

pub mod assets;
pub mod cameras;
pub mod config;
pub mod controllers;
pub mod env;
// Internals the public modules are built on (hidden from the documentation, not
// part of the extension surface): robosuite's float32 rotation helpers, its MJCF
// processing, and the saved-state text format behind pickling.
#[doc(hidden)]
pub mod math;
#[doc(hidden)]
pub mod mjcf;
pub mod modders;
pub mod models;
pub mod observables;
pub mod placement;
pub mod prelude;
pub mod registry;
#[cfg(feature = "render")]
pub mod render;
pub mod robots;
#[doc(hidden)]
pub mod saved;
pub mod sim;
pub mod tasks;
pub mod wrappers;

pub use config::{EnvConfig, EnvConfiguration};
#[cfg(feature = "render")]
pub use env::CameraFrame;
pub use env::{
    EnvSnapshot, ModelSource, MujocoObjectInfo, ObservableFlag, ObservableInfo, RobosuiteEnv,
    SceneLoad,
};
pub use registry::{
    ENV_NAMES, TASKS, TaskEntry, make, make_from_scene_xml, make_task, make_with, register_envs,
    scene_xml,
};
pub use robots::{InitNoise, NoiseKind};
