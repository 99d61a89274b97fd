//! The Franka Panda with the Panda gripper, as robosuite 1.5.2 configures them.

use super::spec::{ArmSpec, GripperSpec, RobotSpec};
use crate::models::{PANDA_ARM_XML, PANDA_GRIPPER_XML, RETHINK_MOUNT_XML, WIPING_GRIPPER_XML};
use std::f64::consts::PI;

/// The Panda arm: `init_qpos = [0, π/16, 0, −π/2 − π/3, 0, π − 0.2, π/4]` on a Rethink mount.
pub const PANDA: ArmSpec = ArmSpec {
    name: "Panda",
    xml: PANDA_ARM_XML,
    mount_xml: Some(RETHINK_MOUNT_XML),
    joints: [
        "joint1", "joint2", "joint3", "joint4", "joint5", "joint6", "joint7",
    ],
    base_body: "base",
    hand_body: "right_hand",
    center_site: "right_center",
    init_qpos: [
        0.0,
        PI / 16.0,
        0.0,
        -PI / 2.0 - PI / 3.0,
        0.0,
        PI - 0.2,
        PI / 4.0,
    ],
};

/// The Panda gripper: two slide fingers, initial opening `[0.020833, −0.020833]`, speed 0.2.
pub const PANDA_GRIPPER: GripperSpec = GripperSpec {
    name: "PandaGripper",
    xml: PANDA_GRIPPER_XML,
    joints: &["finger_joint1", "finger_joint2"],
    init_qpos: &[0.020833, -0.020833],
    grip_site: "grip_site",
    left_pads: &["finger1_pad_collision"],
    right_pads: &["finger2_pad_collision"],
    speed: 0.2,
    command_signs: &[-1.0, 1.0],
};

/// The Panda with its default gripper.
pub fn panda() -> RobotSpec {
    RobotSpec {
        arm: PANDA,
        gripper: Some(PANDA_GRIPPER),
    }
}

/// robosuite's `WipingGripper` (Wipe's tool): no fingers, so no gripper action, no finger
/// pads; the grip site sits at the pad's centre, 1.5 cm below the hand.
pub const WIPING_GRIPPER: GripperSpec = GripperSpec {
    name: "WipingGripper",
    xml: WIPING_GRIPPER_XML,
    joints: &[],
    init_qpos: &[],
    grip_site: "grip_site",
    left_pads: &[],
    right_pads: &[],
    speed: 0.0,
    command_signs: &[],
};
