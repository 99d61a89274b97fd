//! robosuite's model classes (`robosuite/models/`) in Rust: arenas, robots, mounts,
//! grippers and objects built from robosuite 1.5.2's own model files, and the scene that
//! merges them as robosuite's `ManipulationTask` does.
//!
//! * [`arenas`]: tables, bins, the empty arena;
//! * [`robots`], [`bases`], [`grippers`]: robots with their mounts and grippers;
//! * [`objects`]: objects from robosuite's files and generated ones;
//! * [`wipe_arena`]: Wipe's table with its dirt markers and their random walk;
//! * [`scene`]: the world (`base.xml`), the merge and the final MJCF.

pub mod arenas;
pub mod bases;
pub mod grippers;
pub mod objects;
pub mod robots;
pub mod scene;
pub mod wipe_arena;

/// robosuite's colour for the collision geoms of robots (`ROBOT_COLLISION_COLOR`).
pub const ROBOT_COLLISION_COLOR: [f64; 4] = [0.0, 0.5, 0.0, 1.0];
/// robosuite's colour for the collision geoms of mounts.
pub const MOUNT_COLLISION_COLOR: [f64; 4] = [0.5, 0.5, 0.0, 1.0];
/// robosuite's colour for the collision geoms of grippers.
pub const GRIPPER_COLLISION_COLOR: [f64; 4] = [0.0, 0.0, 0.5, 1.0];
/// robosuite's colour for the collision geoms of objects.
pub const OBJECT_COLLISION_COLOR: [f64; 4] = [0.5, 0.0, 0.0, 1.0];
/// robosuite's colour for the collision geoms of arenas.
pub const ENVIRONMENT_COLLISION_COLOR: [f64; 4] = [0.5, 0.5, 0.0, 1.0];
