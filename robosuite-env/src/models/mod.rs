//! Our own MJCF models, embedded in the crate, and the scene composer that puts them
//! together with robosuite's names.
//!
//! Parts: the world (physics options), arenas, robot arms, mounts, grippers and objects. A
//! scene is the world with an arena, each robot (arm + mount + gripper, prefixed
//! `robot{i}_`, `fixed_mount{i}_`, `gripper{i}_right_`) and the task's objects attached with
//! MuJoCo's model editing ([`scene::SceneBuilder`]).

pub mod arenas;
pub mod objects;
pub mod scene;

/// The world every scene starts from: compiler settings and robosuite 1.5.2's physics
/// options (timestep 0.002, Euler, elliptic cones, Newton, impratio 20, air density 1.2 and
/// viscosity 2e-5) with a 2 MiB arena (see [`scene::SceneBuilder::set_memory`]).
pub const WORLD_XML: &str = include_str!("assets/world.xml");

/// The Franka Panda arm (prefix `robot{i}_`).
pub const PANDA_ARM_XML: &str = include_str!("assets/panda_arm.xml");

/// The Panda parallel-jaw gripper (prefix `gripper{i}_right_`).
pub const PANDA_GRIPPER_XML: &str = include_str!("assets/panda_gripper.xml");

/// The Rethink-style pedestal mount under the robot base (prefix `fixed_mount{i}_`).
pub const RETHINK_MOUNT_XML: &str = include_str!("assets/rethink_mount.xml");

/// robosuite's WipingGripper: a flat wiping tool without fingers (prefix `gripper{i}_right_`).
pub const WIPING_GRIPPER_XML: &str = include_str!("assets/wiping_gripper.xml");
