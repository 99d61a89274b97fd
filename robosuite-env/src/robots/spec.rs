//! Static robot descriptions: which MJCF part, which joint, body and site names (without
//! the `robot{i}_` / `gripper{i}_right_` prefixes), initial configuration.

/// An arm: its MJCF and the names the controllers and observations need.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmSpec {
    /// robosuite's robot name, such as `"Panda"`.
    pub name: &'static str,
    /// The arm's MJCF (unprefixed names).
    pub xml: &'static str,
    /// The mount's MJCF, attached under the base, if the robot has one.
    pub mount_xml: Option<&'static str>,
    /// The arm joints, base to tip.
    pub joints: [&'static str; 7],
    /// The root body.
    pub base_body: &'static str,
    /// The body the gripper attaches to (its orientation is `robotN_eef_quat`).
    pub hand_body: &'static str,
    /// The site whose frame is the controller's base frame (`robotN_right_center`).
    pub center_site: &'static str,
    /// robosuite's `init_qpos`.
    pub init_qpos: [f64; 7],
}

/// A gripper: its MJCF, joints, grip site and finger-pad geoms.
#[derive(Debug, Clone, PartialEq)]
pub struct GripperSpec {
    /// robosuite's gripper name, such as `"PandaGripper"`.
    pub name: &'static str,
    /// The gripper's MJCF (unprefixed names).
    pub xml: &'static str,
    /// The finger joints, in robosuite's order.
    pub joints: &'static [&'static str],
    /// The fingers' initial positions.
    pub init_qpos: &'static [f64],
    /// The site at the grasp point (the controller's reference, `robotN_eef_pos`).
    pub grip_site: &'static str,
    /// Contact geoms of the left finger pad group (`_check_grasp`).
    pub left_pads: &'static [&'static str],
    /// Contact geoms of the right finger pad group.
    pub right_pads: &'static [&'static str],
    /// Change of the grip command per env step (robosuite's `speed`).
    pub speed: f64,
    /// Direction each actuator's command moves for a positive (closing) action
    /// (robosuite's `format_action`; Panda: `[-1, 1]`).
    pub command_signs: &'static [f64],
}

/// An arm with its gripper.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotSpec {
    /// The arm.
    pub arm: ArmSpec,
    /// The gripper, if any.
    pub gripper: Option<GripperSpec>,
}
