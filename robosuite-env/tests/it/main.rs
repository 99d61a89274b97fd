//! robosuite-env's integration tests (`no_alloc` and `fuzz` stay binaries of their own: a counting allocator, and `make fuzz`).
//!
//! One test binary per crate: each binary links MuJoCo once, so merging the test files
//! into modules of one binary saves most of the link time of `make test`.

#[path = "../common/mod.rs"]
mod common;

mod camera_obs;
mod conformance;
mod controller_config;
mod controller_conformance;
mod controller_reference;
mod controller_replay;
mod dex_robots;
mod door_env;
mod humanoids;
mod legged_robots;
mod lift_env;
mod mobile_robots;
mod nut_assembly_env;
mod observation_layouts;
mod osc_fixed_size;
mod pick_place_env;
mod reliability;
mod render;
mod robosuite_replay;
mod scripted_lift;
mod sensor_skip;
mod shared_model;
mod stack_env;
mod task_options;
mod texture_free_env;
mod texture_free_scene;
mod tool_hang_env;
mod two_arm_env;
mod visual_wrappers;
mod whole_body_ik;
mod wipe_env;
