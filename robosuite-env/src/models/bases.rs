//! robosuite's robot bases (`robosuite/models/bases/`): the fixed mounts a fixed-base robot
//! stands on, the mobile bases of wheeled robots and the leg bases of legged robots, one
//! table ([`MOUNTS`]).

use super::MOUNT_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::XmlModel;
use crate::mjcf::tree::{self, attr};
use gym_core::{Error, Result};

/// The kind of a robosuite base (its model class), which sets its name prefix and how
/// robosuite's `RobotModel.add_base` attaches it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BaseKind {
    /// `MountModel` (prefix `fixed_mount{i}_`): merged into the robot's root body.
    Mount,
    /// `MobileBaseModel` (prefix `mobilebase{i}_`): merged into the robot's root body, whose
    /// former contents move to a `manipulator_mount` body on the base's `support` body.
    MobileBase,
    /// `LegBaseModel` (prefix `leg{i}_`): its bodies go into the robot's root body, its free
    /// joint (if any) onto the root body, and the robot's arm onto the base's `support`
    /// body. A floating leg base (robosuite's `SpotFloating`) has its leg joints, leg
    /// motors and free joint removed and forward, side and yaw joints with velocity
    /// actuators added to its root body.
    LegBase {
        /// Whether the base floats on added mobile joints instead of standing on its legs.
        floating: bool,
    },
}

impl BaseKind {
    /// The name prefix of robot `robot`'s base.
    pub fn prefix(self, robot: usize) -> String {
        match self {
            Self::Mount => format!("fixed_mount{robot}_"),
            Self::MobileBase => format!("mobilebase{robot}_"),
            Self::LegBase { .. } => format!("leg{robot}_"),
        }
    }
}

/// A base class of robosuite (a mount or a mobile base).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountInfo {
    /// robosuite's class name, such as `"RethinkMount"`.
    pub name: &'static str,
    /// Its kind.
    pub kind: BaseKind,
    /// Its model file under `models/assets`.
    pub file: &'static str,
    /// From the mount's root body to its mounting surface (robosuite's `top_offset`).
    pub top_offset: [f64; 3],
    /// Its horizontal radius.
    pub horizontal_radius: f64,
}

/// robosuite's `RethinkMount` (the Sawyer pedestal every single-arm robot stands on).
pub const RETHINK_MOUNT: MountInfo = MountInfo {
    name: "RethinkMount",
    kind: BaseKind::Mount,
    file: "bases/rethink_mount.xml",
    top_offset: [0.0, 0.0, -0.01],
    horizontal_radius: 0.25,
};

/// robosuite's `RethinkMinimalMount` (Baxter's).
pub const RETHINK_MINIMAL_MOUNT: MountInfo = MountInfo {
    name: "RethinkMinimalMount",
    kind: BaseKind::Mount,
    file: "bases/rethink_minimal_mount.xml",
    top_offset: [0.0, 0.0, -0.062],
    horizontal_radius: 0.25,
};

/// robosuite's `NullMount`.
pub const NULL_MOUNT: MountInfo = MountInfo {
    name: "NullMount",
    kind: BaseKind::Mount,
    file: "bases/null_mount.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.0,
};

/// robosuite's `OmronMobileBase` (the Omron LD-60, PandaOmron's base: forward, side and
/// yaw velocity actuators and a torso lift).
pub const OMRON_MOBILE_BASE: MountInfo = MountInfo {
    name: "OmronMobileBase",
    kind: BaseKind::MobileBase,
    file: "bases/omron_mobile_base.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.25,
};

/// robosuite's `NullMobileBase` (forward, side and yaw velocity actuators without a body:
/// Tiago's base).
pub const NULL_MOBILE_BASE: MountInfo = MountInfo {
    name: "NullMobileBase",
    kind: BaseKind::MobileBase,
    file: "bases/null_mobile_base.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.0,
};

/// robosuite's `Spot` (Boston Dynamics Spot's body on four legs of three joints each,
/// driven by motors; `SpotWithArm`'s base).
pub const SPOT: MountInfo = MountInfo {
    name: "Spot",
    kind: BaseKind::LegBase { floating: false },
    file: "robots/spot/robot.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.1,
};

/// robosuite's `SpotFloating` (Spot's body without leg actuation, moved by forward, side
/// and yaw velocity actuators; `SpotWithArmFloating`'s base).
pub const SPOT_FLOATING: MountInfo = MountInfo {
    name: "SpotFloating",
    kind: BaseKind::LegBase { floating: true },
    file: "robots/spot/robot.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.1,
};

/// The leg joints' rest positions of robosuite's `Spot` (its `init_qpos`: hip x, hip y,
/// knee per leg, front right, front left, rear right, rear left).
pub const SPOT_LEGS_INIT_QPOS: [f64; 12] = [
    0.0, 0.9, -1.8, 0.0, 0.9, -1.8, 0.0, 0.9, -1.8, 0.0, 0.9, -1.8,
];

impl MountInfo {
    /// The leg joints' rest positions a legged robot's reset writes (robosuite's leg base
    /// `init_qpos`); empty for every other base.
    pub fn legs_init_qpos(&self) -> &'static [f64] {
        match self.kind {
            BaseKind::LegBase { floating: false } => &SPOT_LEGS_INIT_QPOS,
            _ => &[],
        }
    }
}

/// robosuite's `NoActuationBase` (a mobile base without joints: GR1's, which fixes the
/// robot's root in place).
pub const NO_ACTUATION_BASE: MountInfo = MountInfo {
    name: "NoActuationBase",
    kind: BaseKind::MobileBase,
    file: "bases/no_actuation_base.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.0,
};

/// robosuite's `FloatingLeggedBase` (forward, side and yaw velocity actuators without a
/// body: GR1FloatingBody's).
pub const FLOATING_LEGGED_BASE: MountInfo = MountInfo {
    name: "FloatingLeggedBase",
    kind: BaseKind::MobileBase,
    file: "bases/floating_legged_base.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.0,
};

/// Every base [`mount_info`] knows.
pub const MOUNTS: &[MountInfo] = &[
    RETHINK_MOUNT,
    RETHINK_MINIMAL_MOUNT,
    NULL_MOUNT,
    OMRON_MOBILE_BASE,
    NULL_MOBILE_BASE,
    SPOT,
    SPOT_FLOATING,
    NO_ACTUATION_BASE,
    FLOATING_LEGGED_BASE,
];

/// The mount robosuite names `name`.
///
/// # Errors
/// [`Error::InvalidArgument`] (argument `base_types`) listing the valid names.
pub fn mount_info(name: &str) -> Result<MountInfo> {
    MOUNTS
        .iter()
        .find(|m| m.name == name)
        .copied()
        .ok_or_else(|| {
            Error::invalid_argument(
                "base_types",
                format!(
                    "unknown mount `{name}`; valid: {}",
                    MOUNTS.iter().map(|m| m.name).collect::<Vec<_>>().join(", ")
                ),
            )
        })
}

/// A mount's model file prepared as robosuite's `MountModel` (prefix `fixed_mount{robot}_`).
#[derive(Debug, Clone)]
pub struct MountModel {
    /// The prepared file.
    pub xml: XmlModel,
    /// The mount's figures.
    pub info: MountInfo,
}

impl MountModel {
    /// Loads base `info` for robot `robot` (prefixed as its kind says).
    ///
    /// # Errors
    /// [`Error::Model`] when its file is missing or malformed.
    pub fn load(assets: &Assets, info: MountInfo, robot: usize) -> Result<Self> {
        let mut xml = XmlModel::load(
            &assets.file(info.file)?,
            &info.kind.prefix(robot),
            MOUNT_COLLISION_COLOR,
        )?;
        if info.kind == (BaseKind::LegBase { floating: true }) {
            remove_joint_actuation(&mut xml, "leg");
            tree::visit_mut(xml.doc.worldbody_mut(), &mut |e| {
                tree::take_children(e, |c| c.name == "freejoint");
            });
            add_mobile_joints(&mut xml);
        }
        Ok(Self { xml, info })
    }

    /// From the root body to the bottom (robosuite's `bottom_offset`: the root body's `pos`
    /// in the file).
    pub fn bottom_offset(&self) -> [f64; 3] {
        self.xml.base_offset
    }
}

/// robosuite's `LegBaseModel._remove_joint_actuation(part)`: removes every joint and motor
/// whose (prefixed) name contains `part`, and the joint sensors on those joints.
fn remove_joint_actuation(xml: &mut XmlModel, part: &str) {
    let prefix = xml.prefix.clone();
    let hit = |e: &xmltree::Element, key: &str| attr(e, key).is_some_and(|n| n.contains(part));
    tree::visit_mut(xml.doc.worldbody_mut(), &mut |e| {
        tree::take_children(e, |c| c.name == "joint" && hit(c, "name"));
    });
    tree::take_children(xml.doc.section_mut("actuator"), |c| {
        c.name == "motor" && hit(c, "name")
    });
    tree::take_children(xml.doc.section_mut("sensor"), |c| {
        matches!(
            c.name.as_str(),
            "jointpos" | "jointvel" | "jointactuatorfrc"
        ) && hit(c, "joint")
    });
    let keep = |n: &String| !format!("{prefix}{n}").contains(part);
    xml.names.joints.retain(keep);
    xml.names.actuators.retain(keep);
}

/// robosuite's `LegBaseModel._add_mobile_joint`: forward (y), side (x) slide and yaw hinge
/// joints on the root body, each with a velocity actuator.
fn add_mobile_joints(xml: &mut XmlModel) {
    let p = xml.prefix.clone();
    let joint = |name: &str, axis: &str, kind: &str| {
        tree::element(
            "joint",
            &[
                ("name", format!("{p}{name}")),
                ("pos", "0 0 0".to_owned()),
                ("axis", axis.to_owned()),
                ("type", kind.to_owned()),
                ("limited", "false".to_owned()),
                ("damping", "0".to_owned()),
                ("armature", "0.0".to_owned()),
                ("frictionloss", "250".to_owned()),
            ],
        )
    };
    let actuator = |joint: &str, name: &str, range: &str, kv: &str| {
        tree::element(
            "velocity",
            &[
                ("ctrllimited", "true".to_owned()),
                ("ctrlrange", range.to_owned()),
                ("joint", format!("{p}{joint}")),
                ("kv", kv.to_owned()),
                ("name", format!("{p}{name}")),
                ("forcelimited", "true".to_owned()),
                ("forcerange", "-600 600".to_owned()),
            ],
        )
    };
    let joints = [
        joint("joint_mobile_forward", "0 1 0", "slide"),
        joint("joint_mobile_side", "1 0 0", "slide"),
        joint("joint_mobile_yaw", "0 0 1", "hinge"),
    ];
    let actuators = [
        actuator(
            "joint_mobile_forward",
            "actuator_mobile_forward",
            "-1.00 1.00",
            "1000",
        ),
        actuator(
            "joint_mobile_side",
            "actuator_mobile_side",
            "-1.00 1.00",
            "1000",
        ),
        actuator(
            "joint_mobile_yaw",
            "actuator_mobile_yaw",
            "-1.50 1.50",
            "1500",
        ),
    ];
    for j in joints {
        xml.names
            .joints
            .push(attr(&j, "name").unwrap_or_default()[p.len()..].to_owned());
        tree::append(xml.root_body_element_mut(), j);
    }
    for a in actuators {
        xml.names
            .actuators
            .push(attr(&a, "name").unwrap_or_default()[p.len()..].to_owned());
        tree::append(xml.doc.section_mut("actuator"), a);
    }
}
