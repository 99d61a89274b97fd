//! Helpers for tasks on robosuite's table (Lift, Stack, Door, ToolHang, TwoArmLift, ...):
//! the table top, the table arena and where a single-arm robot stands.

use crate::assets::Assets;
use crate::models::arenas::Arena;
use crate::models::robots::RobotModel;
use gym_core::Result;

/// robosuite's table top for Lift, Stack, ToolHang and TwoArmLift (`table_offset`).
pub const TABLE_OFFSET: [f64; 3] = [0.0, 0.0, 0.8];

/// robosuite's `TableArena(table_full_size, table_friction, table_offset)` from
/// `arenas/table_arena.xml`, then `set_origin([0, 0, 0])`: the arena of a table task's
/// `_load_model`.
///
/// # Errors
/// As [`Arena::table`].
pub fn table_arena(
    assets: &Assets,
    full_size: [f64; 3],
    friction: [f64; 3],
    offset: [f64; 3],
) -> Result<Arena> {
    let mut arena = Arena::table(
        assets,
        "arenas/table_arena.xml",
        full_size,
        friction,
        offset,
    )?;
    arena.set_origin([0.0; 3])?;
    Ok(arena)
}

/// Places robot 0 at its base offset for the arena, as every single-arm task of robosuite
/// does (`robot_model.set_base_xpos(base_xpos_offset[arena])`); the environment does it for
/// a task with [`RobotSetup::SingleArm`](super::RobotSetup::SingleArm).
pub fn place_single_robot(robots: &mut [RobotModel], arena: &Arena) {
    if let Some(robot) = robots.first_mut() {
        let xpos = robot.info.base_offsets.for_arena(arena.kind);
        robot.set_base_xpos(xpos);
    }
}
