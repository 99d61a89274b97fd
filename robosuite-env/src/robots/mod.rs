//! Robots: static descriptions of arms and grippers ([`RobotSpec`]) and the run-time
//! [`Robot`] that binds one to a compiled model, owns its controllers and reads its
//! proprioception.

mod panda;
mod robot;
mod spec;

pub use panda::{PANDA, PANDA_GRIPPER, WIPING_GRIPPER, panda};
pub use robot::{ARM_DOF, InitNoise, NoiseKind, Robot, RobotState};
pub use spec::{ArmSpec, GripperSpec, RobotSpec};

use gym_core::{Error, Result};

/// The robot names [`robot_spec`] knows.
pub const ROBOT_NAMES: &[&str] = &["Panda"];

/// The description of a robot by robosuite's name, with its default gripper.
///
/// # Errors
/// [`Error::InvalidArgument`] listing the valid names for an unknown robot.
pub fn robot_spec(name: &str) -> Result<RobotSpec> {
    match name {
        "Panda" => Ok(panda()),
        other => Err(Error::invalid_argument(
            "robots",
            format!("unknown robot `{other}`; valid: {}", ROBOT_NAMES.join(", ")),
        )),
    }
}
