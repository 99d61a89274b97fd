//! robosuite's robot models (`robosuite/models/robots/`): a robot's file with its mount and
//! grippers, prepared and composed as robosuite's `RobotModel`, `ManipulatorModel` and
//! `Robot.load_model` prepare and compose them.

use super::ROBOT_COLLISION_COLOR;
use super::bases::{BaseKind, MountInfo, MountModel, RETHINK_MOUNT};
use super::grippers::{GripperInfo, GripperModel, NULL_GRIPPER, gripper_info};
use crate::assets::Assets;
use crate::math::euler_xyz_to_quat_wxyz;
use crate::mjcf::tree::{self, array_to_string, attr, set_attr};
use crate::mjcf::{MergeBody, MjcfDoc, XmlModel};
use gym_core::{Error, Result};
use std::f64::consts::PI;

/// Where a robot stands relative to an arena's origin (robosuite's `base_xpos_offset`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BaseOffsets {
    /// In the bins arena.
    pub bins: [f64; 3],
    /// In the empty arena.
    pub empty: [f64; 3],
    /// At a table of length `l`: `(table_x - l / 2, 0, table_z)`.
    pub table_x: f64,
    /// The height of the offset at a table (a humanoid's pelvis).
    pub table_z: f64,
}

impl BaseOffsets {
    /// The offsets every single-arm robot of robosuite uses.
    pub const SINGLE_ARM: Self = Self {
        bins: [-0.5, -0.1, 0.0],
        empty: [-0.6, 0.0, 0.0],
        table_x: -0.16,
        table_z: 0.0,
    };

    /// The offset in an arena.
    pub fn for_arena(&self, kind: super::arenas::ArenaKind) -> [f64; 3] {
        match kind {
            super::arenas::ArenaKind::Table { length } => {
                [self.table_x - length / 2.0, 0.0, self.table_z]
            }
            super::arenas::ArenaKind::Bins => self.bins,
            super::arenas::ArenaKind::Empty => self.empty,
        }
    }
}

/// robosuite's robot classes (`robots/__init__.py`'s `ROBOT_CLASS_MAPPING`): how a robot
/// stands, which body parts it has and how its controls are applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, serde::Serialize)]
pub enum RobotKind {
    /// `FixedBaseRobot`: arms on a fixed mount; only the arms and grippers are controlled.
    FixedBase,
    /// `WheeledRobot`: a mobile base; arms, torso, head and base are controlled, and the
    /// arms' base frame is read once per reset.
    Wheeled,
    /// `LeggedRobot`: legs or a floating base; arms, torso, head, base and legs are
    /// controlled, and every part's controls are divided by its actuators' gear.
    Legged,
}

impl RobotKind {
    /// robosuite's class name.
    pub fn class_name(self) -> &'static str {
        match self {
            Self::FixedBase => "FixedBaseRobot",
            Self::Wheeled => "WheeledRobot",
            Self::Legged => "LeggedRobot",
        }
    }

    /// Whether the robot is mobile (robosuite's `is_mobile`; a `MobileRobot`).
    pub fn is_mobile(self) -> bool {
        self != Self::FixedBase
    }

    /// The body parts other than arms this class controls, in robosuite's order of
    /// loading their controllers.
    pub fn body_parts(self) -> &'static [&'static str] {
        match self {
            Self::FixedBase => &[],
            Self::Wheeled => &["base", "head", "torso"],
            Self::Legged => &["base", "legs", "head", "torso"],
        }
    }
}

/// robosuite's `update_joints` / `update_actuators`: the body part an element of a robot
/// belongs to by its (prefixed) name: `torso`, `base` (`mobile`), `head`, `legs` (`leg`),
/// else an arm.
pub fn body_part_of(name: &str) -> Option<&'static str> {
    if name.contains("torso") {
        Some("torso")
    } else if name.contains("mobile") {
        Some("base")
    } else if name.contains("head") {
        Some("head")
    } else if name.contains("leg") {
        Some("legs")
    } else {
        None
    }
}

/// A robot class of robosuite: the figures its Python class holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotInfo {
    /// robosuite's robot name, such as `"Panda"`.
    pub name: &'static str,
    /// Its model file under `models/assets`.
    pub file: &'static str,
    /// Its arms (`["right"]`, or `["right", "left"]` for a bimanual robot).
    pub arms: &'static [&'static str],
    /// The body each arm's gripper attaches to, unprefixed, per arm.
    pub eef_bodies: &'static [&'static str],
    /// The joints' rest positions (robosuite's `init_qpos`), all arms in joint order.
    pub init_qpos: &'static [f64],
    /// Joint damping the class sets over the file's (`set_joint_attribute`), if any.
    pub damping: Option<&'static [f64]>,
    /// The mount it stands on by default.
    pub default_mount: MountInfo,
    /// Its default gripper per arm (robosuite class names).
    pub default_grippers: &'static [&'static str],
    /// Where it stands in each arena.
    pub base_offsets: BaseOffsets,
    /// From its root body to its top.
    pub top_offset: [f64; 3],
    /// Its horizontal radius (the mount's is taken if larger).
    pub horizontal_radius: f64,
    /// robosuite's robot class.
    pub kind: RobotKind,
    /// The torso joints' rest positions (robosuite's `init_torso_qpos`), if any.
    pub init_torso_qpos: Option<&'static [f64]>,
    /// The base joints' rest positions (robosuite's `init_base_qpos`), if any.
    pub init_base_qpos: Option<&'static [f64]>,
    /// Per arm, the pose a gripper's first body takes on the eef body in place of its
    /// file's (robosuite's `gripper_mount_pos_offset` / `gripper_mount_quat_offset`);
    /// empty: every gripper as its file places it.
    pub gripper_mount_offsets: &'static [GripperMountOffset],
    /// The body parts whose joints and actuators the class removes from the file
    /// (robosuite's `_remove_joint_actuation`, by name substring: `"leg"`, `"head"`,
    /// `"torso"`), after the default joint attributes are set.
    pub removed_parts: &'static [&'static str],
    /// Whether the class removes the file's free joints (robosuite's `_remove_free_joint`).
    pub remove_free_joint: bool,
}

/// robosuite's custom gripper mount of one arm (`gripper_mount_pos_offset` and
/// `gripper_mount_quat_offset`): whatever gripper the arm carries, its first body is
/// placed at `pos` with orientation `quat` on the eef body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GripperMountOffset {
    /// The arm (`"right"` or `"left"`).
    pub arm: &'static str,
    /// The position, if robosuite sets one.
    pub pos: Option<[f64; 3]>,
    /// The orientation (w, x, y, z), if robosuite sets one.
    pub quat: Option<[f64; 4]>,
}

/// The fields every single-arm robot of robosuite shares: one right arm with its gripper on
/// `right_hand`, the Rethink mount, robosuite's single-arm base offsets, top offset 1 m,
/// horizontal radius 0.5.
const SINGLE_ARM: RobotInfo = RobotInfo {
    name: "",
    file: "",
    arms: &["right"],
    eef_bodies: &["right_hand"],
    init_qpos: &[],
    damping: None,
    default_mount: RETHINK_MOUNT,
    default_grippers: &[],
    base_offsets: BaseOffsets::SINGLE_ARM,
    top_offset: [0.0, 0.0, 1.0],
    horizontal_radius: 0.5,
    kind: RobotKind::FixedBase,
    init_torso_qpos: None,
    init_base_qpos: None,
    gripper_mount_offsets: &[],
    removed_parts: &[],
    remove_free_joint: false,
};

/// robosuite's `Panda` (Franka Emika Panda, 7 joints).
pub const PANDA: RobotInfo = RobotInfo {
    name: "Panda",
    file: "robots/panda/robot.xml",
    init_qpos: &[
        0.0,
        PI / 16.0,
        0.00,
        -PI / 2.0 - PI / 3.0,
        0.00,
        PI - 0.2,
        PI / 4.0,
    ],
    damping: Some(&[0.1, 0.1, 0.1, 0.1, 0.1, 0.01, 0.01]),
    default_grippers: &["PandaGripper"],
    ..SINGLE_ARM
};

/// robosuite's `Sawyer` (Rethink Robotics, 7 joints).
pub const SAWYER: RobotInfo = RobotInfo {
    name: "Sawyer",
    file: "robots/sawyer/robot.xml",
    init_qpos: &[0.0, -1.18, 0.00, 2.18, 0.00, 0.57, -1.57],
    default_grippers: &["RethinkGripper"],
    ..SINGLE_ARM
};

/// robosuite's `IIWA` (KUKA LBR iiwa, 7 joints).
pub const IIWA: RobotInfo = RobotInfo {
    name: "IIWA",
    file: "robots/iiwa/robot.xml",
    init_qpos: &[0.000, 0.650, 0.000, -1.890, 0.000, 0.600, 0.000],
    default_grippers: &["Robotiq140Gripper"],
    ..SINGLE_ARM
};

/// robosuite's `Jaco` (Kinova Jaco, 7 joints). Its last rest angle, 3.142, is robosuite's
/// literal, not π.
#[allow(clippy::approx_constant)]
pub const JACO: RobotInfo = RobotInfo {
    name: "Jaco",
    file: "robots/jaco/robot.xml",
    init_qpos: &[3.192, 3.680, -0.000, 1.170, 0.050, 3.760, 3.142],
    default_grippers: &["JacoThreeFingerGripper"],
    ..SINGLE_ARM
};

/// robosuite's `Kinova3` (Kinova Gen3, 7 joints).
pub const KINOVA3: RobotInfo = RobotInfo {
    name: "Kinova3",
    file: "robots/kinova3/robot.xml",
    init_qpos: &[0.000, 0.650, 0.000, 1.890, 0.000, 0.600, -PI / 2.0],
    default_grippers: &["Robotiq85Gripper"],
    ..SINGLE_ARM
};

/// robosuite's `UR5e` (Universal Robots, 6 joints).
pub const UR5E: RobotInfo = RobotInfo {
    name: "UR5e",
    file: "robots/ur5e/robot.xml",
    init_qpos: &[-0.470, -1.735, 2.480, -2.275, -1.590, -1.991],
    default_grippers: &["Robotiq85Gripper"],
    ..SINGLE_ARM
};

/// robosuite's `XArm7` (UFactory xArm 7, 7 joints).
pub const XARM7: RobotInfo = RobotInfo {
    name: "XArm7",
    file: "robots/xarm7/robot.xml",
    init_qpos: &[0.0, 0.0, 0.0, 0.39 * PI, 0.0, 0.39 * PI, 0.0],
    damping: Some(&[0.1, 0.1, 0.1, 0.1, 0.1, 0.01, 0.01]),
    default_grippers: &["XArm7Gripper"],
    ..SINGLE_ARM
};

/// robosuite's `Baxter` (Rethink Robotics, bimanual: a right and a left arm of 7 joints),
/// on the Rethink minimal mount with a Rethink gripper on each arm.
pub const BAXTER: RobotInfo = RobotInfo {
    name: "Baxter",
    file: "robots/baxter/robot.xml",
    arms: &["right", "left"],
    eef_bodies: &["right_hand", "left_hand"],
    init_qpos: &[
        0.403, -0.636, 0.114, 1.432, 0.735, 1.205, -0.269, -0.403, -0.636, -0.114, 1.432, -0.735,
        1.205, 0.269,
    ],
    damping: None,
    default_mount: super::bases::RETHINK_MINIMAL_MOUNT,
    default_grippers: &["RethinkGripper", "RethinkGripper"],
    base_offsets: BaseOffsets {
        bins: [-0.5, -0.1, 0.0],
        empty: [-0.29, 0.0, 0.0],
        table_x: -0.26,
        table_z: 0.0,
    },
    top_offset: [0.0, 0.0, 1.0],
    horizontal_radius: 0.5,
    kind: RobotKind::FixedBase,
    init_torso_qpos: None,
    init_base_qpos: None,
    gripper_mount_offsets: &[],
    removed_parts: &[],
    remove_free_joint: false,
};

/// robosuite's `PandaOmron`: a Panda on the Omron LD-60 mobile base (a `WheeledRobot`
/// with a torso lift).
pub const PANDA_OMRON: RobotInfo = RobotInfo {
    name: "PandaOmron",
    init_qpos: &[
        0.0,
        PI / 16.0 - 0.2,
        0.00,
        -PI / 2.0 - PI / 3.0,
        0.00,
        PI - 0.4,
        PI / 4.0,
    ],
    default_mount: super::bases::OMRON_MOBILE_BASE,
    base_offsets: BaseOffsets {
        bins: [-0.6, -0.1, 0.0],
        empty: [-0.6, 0.0, 0.0],
        table_x: -0.16,
        table_z: 0.0,
    },
    kind: RobotKind::Wheeled,
    init_torso_qpos: Some(&[0.2]),
    ..PANDA
};

/// robosuite's `Tiago` (PAL Robotics, bimanual: a torso lift, a two-joint head and two arms
/// of 6 joints on a velocity-driven base, robosuite's `NullMobileBase`; a `WheeledRobot`).
pub const TIAGO: RobotInfo = RobotInfo {
    name: "Tiago",
    file: "robots/tiago/robot.xml",
    arms: &["right", "left"],
    eef_bodies: &["right_hand", "left_hand"],
    init_qpos: &[
        0.1, 0.0, 0.0, 0.0, -0.9, 1.45, 1.7, -1.5, 0.5, 0.0, -0.9, 1.45, 1.7, -1.5, 0.5,
    ],
    damping: None,
    default_mount: super::bases::NULL_MOBILE_BASE,
    default_grippers: &["Robotiq85Gripper", "Robotiq85Gripper"],
    base_offsets: BaseOffsets {
        bins: [-0.5, -0.1, 0.0],
        empty: [-0.29, 0.0, 0.0],
        table_x: -0.20,
        table_z: 0.0,
    },
    top_offset: [0.0, 0.0, 1.0],
    horizontal_radius: 0.5,
    kind: RobotKind::Wheeled,
    init_torso_qpos: None,
    init_base_qpos: None,
    gripper_mount_offsets: &[],
    removed_parts: &[],
    remove_free_joint: false,
};

/// robosuite's `PandaDexRH`: a Panda with the Inspire right hand on its flange.
pub const PANDA_DEX_RH: RobotInfo = RobotInfo {
    name: "PandaDexRH",
    default_grippers: &["InspireRightHand"],
    gripper_mount_offsets: &[GripperMountOffset {
        arm: "right",
        pos: Some([0.0, 0.0, 0.0]),
        quat: Some([-0.5, 0.5, 0.5, -0.5]),
    }],
    ..PANDA
};

/// robosuite's `PandaDexLH`: a Panda with the Inspire left hand on its flange.
pub const PANDA_DEX_LH: RobotInfo = RobotInfo {
    name: "PandaDexLH",
    default_grippers: &["InspireLeftHand"],
    gripper_mount_offsets: &[GripperMountOffset {
        arm: "right",
        pos: Some([0.0, 0.0, 0.0]),
        quat: Some([0.5, -0.5, 0.5, -0.5]),
    }],
    ..PANDA
};

/// robosuite's `SpotWithArm` (Boston Dynamics Spot: the 6-joint Spot arm with the
/// `BDGripper` on robosuite's `Spot` leg base, twelve motor-driven leg joints on a free
/// body; a `LeggedRobot`).
pub const SPOT_WITH_ARM: RobotInfo = RobotInfo {
    name: "SpotWithArm",
    file: "robots/spot_arm/robot.xml",
    init_qpos: &[0.0, -2.0, 1.26, -0.335, 0.862, 0.0],
    damping: Some(&[0.1, 0.1, 0.1, 0.1, 0.1, 0.01]),
    default_mount: super::bases::SPOT,
    default_grippers: &["BDGripper"],
    base_offsets: BaseOffsets {
        bins: [-1.05, -0.1, -0.22],
        empty: [-1.1, 0.0, -0.22],
        table_x: -0.5,
        table_z: -0.22,
    },
    kind: RobotKind::Legged,
    ..SINGLE_ARM
};

/// robosuite's `SpotWithArmFloating`: the Spot arm on robosuite's `SpotFloating` (Spot's
/// body moved by forward, side and yaw velocity actuators instead of legs; a
/// `LeggedRobot`).
pub const SPOT_WITH_ARM_FLOATING: RobotInfo = RobotInfo {
    name: "SpotWithArmFloating",
    default_mount: super::bases::SPOT_FLOATING,
    base_offsets: BaseOffsets {
        bins: [-0.7, -0.1, 0.0],
        empty: [-0.6, 0.0, 0.0],
        table_x: -0.5,
        table_z: 0.0,
    },
    ..SPOT_WITH_ARM
};

/// GR1's rest posture: the torso and head (6 joints) upright, both arms half extended.
const GR1_UPPER_QPOS: [f64; 20] = [
    0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.1, 0.0, -1.57, 0.0, 0.0, 0.0, 0.0, 0.1, 0.0, -1.57, 0.0,
    0.0, 0.0,
];

/// [`GR1_UPPER_QPOS`] then the legs (12 joints) straight.
const GR1_QPOS: [f64; 32] = {
    let mut q = [0.0; 32];
    let mut i = 0;
    while i < 20 {
        q[i] = GR1_UPPER_QPOS[i];
        i += 1;
    }
    q
};

/// robosuite's `GR1` (Fourier GR1 humanoid, a `LeggedRobot`: a torso of 3 joints, a head of
/// 3, two arms of 7 with Fourier hands and two legs of 6, on robosuite's
/// `NoActuationBase`, which fixes its pelvis in place).
pub const GR1: RobotInfo = RobotInfo {
    name: "GR1",
    file: "robots/gr1/robot.xml",
    arms: &["right", "left"],
    eef_bodies: &["right_eef", "left_eef"],
    init_qpos: &GR1_QPOS,
    damping: None,
    default_mount: super::bases::NO_ACTUATION_BASE,
    default_grippers: &["FourierRightHand", "FourierLeftHand"],
    base_offsets: BaseOffsets {
        bins: [-0.30, -0.1, 0.95],
        empty: [-0.29, 0.0, 0.95],
        table_x: -0.15,
        table_z: 0.95,
    },
    top_offset: [0.0, 0.0, 1.0],
    horizontal_radius: 0.5,
    kind: RobotKind::Legged,
    init_torso_qpos: None,
    init_base_qpos: None,
    gripper_mount_offsets: &[],
    removed_parts: &[],
    remove_free_joint: false,
};

/// robosuite's `GR1FixedLowerBody`: [`GR1`] without its legs' joints.
pub const GR1_FIXED_LOWER_BODY: RobotInfo = RobotInfo {
    name: "GR1FixedLowerBody",
    init_qpos: &GR1_UPPER_QPOS,
    removed_parts: &["leg"],
    remove_free_joint: true,
    ..GR1
};

/// robosuite's `GR1FloatingBody`: [`GR1`] without its legs' joints, its pelvis driven by
/// robosuite's `FloatingLeggedBase` (forward, side and yaw velocity actuators).
pub const GR1_FLOATING_BODY: RobotInfo = RobotInfo {
    name: "GR1FloatingBody",
    default_mount: super::bases::FLOATING_LEGGED_BASE,
    base_offsets: BaseOffsets {
        bins: [-0.30, -0.1, 0.97],
        empty: [-0.29, 0.0, 0.97],
        table_x: -0.15,
        table_z: 0.97,
    },
    ..GR1_FIXED_LOWER_BODY
};

/// robosuite's `GR1ArmsOnly`: [`GR1`] with only its arms' (and hands') joints.
pub const GR1_ARMS_ONLY: RobotInfo = RobotInfo {
    name: "GR1ArmsOnly",
    init_qpos: &[
        0.0, -0.1, 0.0, -1.57, 0.0, 0.0, 0.0, 0.0, 0.1, 0.0, -1.57, 0.0, 0.0, 0.0,
    ],
    removed_parts: &["leg", "head", "torso"],
    remove_free_joint: true,
    ..GR1
};

/// Every robot [`robot_info`] knows.
pub const ROBOTS: &[RobotInfo] = &[
    PANDA,
    SAWYER,
    IIWA,
    JACO,
    KINOVA3,
    UR5E,
    XARM7,
    BAXTER,
    PANDA_OMRON,
    TIAGO,
    SPOT_WITH_ARM,
    SPOT_WITH_ARM_FLOATING,
    PANDA_DEX_RH,
    PANDA_DEX_LH,
    GR1,
    GR1_FIXED_LOWER_BODY,
    GR1_ARMS_ONLY,
    GR1_FLOATING_BODY,
];

/// The names of [`ROBOTS`].
pub fn robot_names() -> Vec<&'static str> {
    ROBOTS.iter().map(|r| r.name).collect()
}

/// The names of the single-arm robots of [`ROBOTS`].
pub fn single_arm_robot_names() -> Vec<&'static str> {
    ROBOTS
        .iter()
        .filter(|r| r.arms.len() == 1)
        .map(|r| r.name)
        .collect()
}

/// The robot robosuite names `name`.
///
/// # Errors
/// [`Error::InvalidArgument`] (argument `robots`) listing the valid names.
pub fn robot_info(name: &str) -> Result<RobotInfo> {
    ROBOTS
        .iter()
        .find(|r| r.name == name)
        .copied()
        .ok_or_else(|| {
            Error::invalid_argument(
                "robots",
                format!(
                    "unknown robot `{name}`; valid: {}",
                    robot_names().join(", ")
                ),
            )
        })
}

/// Which gripper an arm carries: robosuite's `gripper_types` entry.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum GripperChoice {
    /// The robot's default gripper (`"default"`).
    #[default]
    Default,
    /// No gripper (`None`): robosuite attaches its `NullGripper`.
    None,
    /// A gripper by robosuite's class name.
    Named(String),
}

impl GripperChoice {
    /// The gripper for `arm` of `robot`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown gripper name.
    pub fn resolve(&self, robot: &RobotInfo, arm: usize) -> Result<(GripperInfo, bool)> {
        match self {
            Self::Default => Ok((gripper_info(robot.default_grippers[arm])?, true)),
            Self::None => Ok((NULL_GRIPPER, false)),
            Self::Named(name) => Ok((gripper_info(name)?, true)),
        }
    }
}

/// One arm of a composed robot model: its eef body and gripper.
#[derive(Debug, Clone)]
pub struct ArmModel {
    /// `"right"` or `"left"`.
    pub side: &'static str,
    /// The gripper model (the null gripper when the arm has none).
    pub gripper: GripperModel,
    /// Whether the arm has a gripper (robosuite's `has_gripper`; false with `None`).
    pub has_gripper: bool,
}

/// A robot's model composed as robosuite's `Robot.load_model` composes it: the robot file
/// (prefix `robot{idn}_`, default joint friction, damping and armature), its mount under
/// the root body (prefix `fixed_mount{idn}_`) and a gripper on each arm's eef body (prefix
/// `gripper{idn}_{arm}_`).
#[derive(Debug, Clone)]
pub struct RobotModel {
    /// The composed document with its element names (the robot's own, not the mount's or
    /// the grippers').
    pub xml: XmlModel,
    /// The robot's figures.
    pub info: RobotInfo,
    /// Its index (`robot{idn}_`).
    pub idn: usize,
    /// The mount's figures, if it has one.
    pub mount: Option<MountModel>,
    /// Its arms, in robosuite's order.
    pub arms: Vec<ArmModel>,
}

impl RobotModel {
    /// Builds robot `info` as robot `idn` on `base` (robosuite's `base_types`; `None`: the
    /// robot's default mount) with the given grippers (one choice per arm).
    ///
    /// # Errors
    /// [`Error::Model`] when a file is missing or malformed; [`Error::InvalidArgument`] for
    /// a wrong number of gripper choices or an unknown gripper.
    pub fn build(
        assets: &Assets,
        info: RobotInfo,
        idn: usize,
        grippers: &[GripperChoice],
        base: Option<MountInfo>,
    ) -> Result<Self> {
        if grippers.len() != info.arms.len() {
            return Err(Error::invalid_argument(
                "gripper_types",
                format!(
                    "{} has {} arm(s), got {} gripper choice(s)",
                    info.name,
                    info.arms.len(),
                    grippers.len()
                ),
            ));
        }
        let xml = load_prepared(assets, info, idn)?;
        let mut model = Self {
            xml,
            info,
            idn,
            mount: None,
            arms: Vec::new(),
        };
        let mount = base.unwrap_or(info.default_mount);
        model.add_mount(MountModel::load(assets, mount, idn)?)?;
        for (i, side) in info.arms.iter().enumerate() {
            let (gripper_info, has_gripper) = grippers[i].resolve(&info, i)?;
            let mut gripper = GripperModel::load(assets, gripper_info, idn, side)?;
            if let Some(offset) = info.gripper_mount_offsets.iter().find(|o| o.arm == *side) {
                gripper.set_mount_offset(offset.pos, offset.quat);
            }
            let eef = model.xml.name(info.eef_bodies[i]);
            model
                .xml
                .doc
                .merge(gripper.xml.doc.clone(), MergeBody::Body(&eef))?;
            model.arms.push(ArmModel {
                side,
                gripper,
                has_gripper,
            });
        }
        Ok(model)
    }

    /// robosuite's `add_base`: the base's root body goes to `base_offset - top_offset`; a
    /// mount's bodies go into the robot's root body (`add_mount`); a mobile base's too, and
    /// the root body's former contents (but its inertial) move into a new
    /// `manipulator_mount` body on the base's `support` body (`add_mobile_base`).
    fn add_mount(&mut self, mut mount: MountModel) -> Result<()> {
        let offset = sub(self.xml.base_offset, mount.info.top_offset);
        set_attr(
            mount.xml.root_body_element_mut(),
            "pos",
            array_to_string(&offset),
        );
        let root = self.xml.root_body();
        match mount.info.kind {
            BaseKind::Mount => {
                self.xml
                    .doc
                    .merge(mount.xml.doc.clone(), MergeBody::Body(&root))?;
            }
            BaseKind::MobileBase => {
                let old = tree::take_children(
                    tree::body_mut(self.xml.doc.worldbody_mut(), &root)?,
                    |_| true,
                );
                self.xml
                    .doc
                    .merge(mount.xml.doc.clone(), MergeBody::Body(&root))?;
                let mut manipulator_mount =
                    tree::element("body", &[("name", "manipulator_mount".to_owned())]);
                for child in old {
                    if child.name != "inertial" && child.name != "freejoint" {
                        tree::append(&mut manipulator_mount, child);
                    }
                }
                let support = mount.xml.name("support");
                tree::append(
                    tree::body_mut(self.xml.doc.worldbody_mut(), &support)?,
                    manipulator_mount,
                );
            }
            BaseKind::LegBase { .. } => self.add_leg_base(&mount)?,
        }
        self.mount = Some(mount);
        Ok(())
    }

    /// robosuite's `add_leg_base`: the base's bodies go into the robot's root body, the
    /// base's free joint (if any) moves onto the root body, and the robot's arm (the first
    /// body under the root body) moves onto the base's `support` body; the base's assets,
    /// actuators, sensors, tendons, equalities and contacts are merged.
    fn add_leg_base(&mut self, mount: &MountModel) -> Result<()> {
        let mut doc = mount.xml.doc.clone();
        let bodies = std::mem::take(&mut doc.worldbody_mut().children);
        let root_name = self.xml.root_body();
        let root = tree::body_mut(self.xml.doc.worldbody_mut(), &root_name)?;
        // robosuite's `find_elements(worldbody, "body")[1]`: the first body under the root
        // body in document order, found before the base's bodies are appended.
        let arm_path = root
            .children
            .iter()
            .position(|n| matches!(n, xmltree::XMLNode::Element(e) if e.name == "body"))
            .ok_or_else(|| {
                Error::model(format!(
                    "{}: the root body holds no arm body",
                    self.info.name
                ))
            })?;
        root.children.extend(bodies);
        let mut free = None;
        tree::visit_mut(root, &mut |e| {
            if free.is_none() && e.name == "body" {
                let taken = tree::take_children(e, |c| c.name == "freejoint");
                free = taken.into_iter().next();
            }
        });
        let xmltree::XMLNode::Element(arm) = root.children.remove(arm_path) else {
            return Err(Error::model("the arm's position holds no element"));
        };
        if let Some(free) = free {
            tree::append(root, free);
        }
        let support = mount.xml.name("support");
        tree::append(tree::body_mut(root, &support)?, arm);
        self.xml.doc.merge(doc, MergeBody::None)?;
        Ok(())
    }

    /// From the root body to the bottom of the mount (robosuite's `bottom_offset`).
    pub fn bottom_offset(&self) -> [f64; 3] {
        match &self.mount {
            Some(m) => add(
                sub(m.bottom_offset(), m.info.top_offset),
                self.xml.base_offset,
            ),
            None => self.xml.base_offset,
        }
    }

    /// robosuite's `set_base_xpos`: puts the bottom of the robot (its mount) at `pos`.
    pub fn set_base_xpos(&mut self, pos: [f64; 3]) {
        let at = sub(pos, self.bottom_offset());
        set_attr(
            self.xml.root_body_element_mut(),
            "pos",
            array_to_string(&at),
        );
    }

    /// robosuite's `set_base_ori`: rotates the robot by the x-y-z Euler angles `rot`.
    pub fn set_base_ori(&mut self, rot: [f64; 3]) {
        let q = euler_xyz_to_quat_wxyz(rot);
        set_attr(
            self.xml.root_body_element_mut(),
            "quat",
            array_to_string(&q),
        );
    }

    /// The robot's joints, prefixed (robosuite's `robot_model.joints`).
    pub fn joints(&self) -> Vec<String> {
        self.xml.names_of(&self.xml.names.joints)
    }

    /// The robot's actuators, prefixed.
    pub fn actuators(&self) -> Vec<String> {
        self.xml.names_of(&self.xml.names.actuators)
    }

    /// The robot's joints then its base's, prefixed (robosuite's `all_joints`).
    pub fn all_joints(&self) -> Vec<String> {
        let mut out = self.joints();
        if let Some(m) = &self.mount {
            out.extend(m.xml.names_of(&m.xml.names.joints));
        }
        out
    }

    /// The robot's actuators then its base's, prefixed (robosuite's `all_actuators`).
    pub fn all_actuators(&self) -> Vec<String> {
        let mut out = self.actuators();
        if let Some(m) = &self.mount {
            out.extend(m.xml.names_of(&m.xml.names.actuators));
        }
        out
    }

    /// The base's `center` site, prefixed (the frame of a mobile robot's base
    /// observables and base controller), if the robot has a base.
    pub fn base_center_site(&self) -> Option<String> {
        self.mount.as_ref().map(|m| m.xml.name("center"))
    }

    /// The body parts other than arms this robot controls (robosuite's `has_part` with
    /// actuators), in robosuite's order of loading their controllers.
    pub fn body_parts(&self) -> Vec<&'static str> {
        let joints = self.all_joints();
        let actuators = self.all_actuators();
        self.info
            .kind
            .body_parts()
            .iter()
            .copied()
            .filter(|&p| {
                joints.iter().any(|j| body_part_of(j) == Some(p))
                    && actuators.iter().any(|a| body_part_of(a) == Some(p))
            })
            .collect()
    }

    /// The eef body of arm `i`, prefixed.
    pub fn eef_body(&self, i: usize) -> String {
        self.xml.name(self.info.eef_bodies[i])
    }

    /// The camera names in the robot's model (robot and gripper cameras).
    pub fn cameras(&self) -> Vec<String> {
        tree::find_all(self.xml.doc.worldbody(), "camera")
            .into_iter()
            .filter_map(|c| attr(c, "name").map(str::to_owned))
            .collect()
    }

    /// The composed document, for merging into a task.
    pub fn doc(&self) -> &MjcfDoc {
        &self.xml.doc
    }
}

/// robosuite's `set_joint_attribute`: sets `attrib` of every robot joint (in order) to its
/// value, keeping values the file sets unless `force`.
fn set_joint_attribute(
    xml: &mut XmlModel,
    attrib: &str,
    values: &[f64],
    force: bool,
) -> Result<()> {
    let joints = xml.names_of(&xml.names.joints);
    if values.len() != joints.len() {
        return Err(Error::model(format!(
            "{attrib}: {} values for {} joints",
            values.len(),
            joints.len()
        )));
    }
    for (name, v) in joints.iter().zip(values) {
        let joint = tree::find_mut(xml.doc.worldbody_mut(), "joint", &[("name", Some(name))])
            .ok_or_else(|| Error::model(format!("no joint `{name}`")))?;
        if force || attr(joint, attrib).is_none() {
            set_attr(joint, attrib, array_to_string(&[*v]));
        }
    }
    Ok(())
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// robot `info`'s file as robot `idn`, prepared as robosuite's `ManipulatorModel` prepares
/// it (prefixed names, robosuite's joint friction, damping and armature), before a mount
/// or grippers are added.
fn load_prepared(assets: &Assets, info: RobotInfo, idn: usize) -> Result<XmlModel> {
    let mut xml = XmlModel::load(
        &assets.file(info.file)?,
        &format!("robot{idn}_"),
        ROBOT_COLLISION_COLOR,
    )?;
    let dof = xml.names.joints.len();
    let removed = removed_joints(&xml, info.removed_parts);
    if dof - removed != info.init_qpos.len() {
        return Err(Error::model(format!(
            "{} has {} joints in {}, but {} initial positions",
            info.name,
            dof - removed,
            info.file,
            info.init_qpos.len()
        )));
    }
    let frictionloss = vec![0.1; dof];
    let damping = vec![0.1; dof];
    let armature: Vec<f64> = (0..dof).map(|i| 5.0 / (i + 1) as f64).collect();
    set_joint_attribute(&mut xml, "frictionloss", &frictionloss, false)?;
    set_joint_attribute(&mut xml, "damping", &damping, false)?;
    set_joint_attribute(&mut xml, "armature", &armature, false)?;
    for part in info.removed_parts {
        remove_joint_actuation(&mut xml, part);
    }
    if info.remove_free_joint {
        tree::visit_mut(xml.doc.worldbody_mut(), &mut |e| {
            tree::take_children(e, |c| c.name == "freejoint");
        });
    }
    if let Some(values) = info.damping {
        set_joint_attribute(&mut xml, "damping", values, true)?;
    }
    Ok(xml)
}

/// How many of the file's joints [`remove_joint_actuation`] removes for `parts`.
fn removed_joints(xml: &XmlModel, parts: &[&str]) -> usize {
    xml.names_of(&xml.names.joints)
        .iter()
        .filter(|j| parts.iter().any(|p| j.contains(p)))
        .count()
}

/// robosuite's `_remove_joint_actuation(part)`: removes every joint whose (prefixed) name
/// contains `part`, the motors and position actuators so named, the fixed tendons and
/// joint equalities over such joints, and the joint sensors on them.
fn remove_joint_actuation(xml: &mut XmlModel, part: &str) {
    let has = |e: &xmltree::Element, key: &str| attr(e, key).is_some_and(|v| v.contains(part));
    let prefix = xml.prefix.clone();
    let named = |raw: &String| format!("{prefix}{raw}").contains(part);
    xml.names.joints.retain(|j| !named(j));
    let doc = &mut xml.doc;
    tree::visit_mut(doc.worldbody_mut(), &mut |e| {
        tree::take_children(e, |c| c.name == "joint" && has(c, "name"));
    });
    let mut removed_actuators = Vec::new();
    tree::visit_mut(doc.section_mut("actuator"), &mut |e| {
        for a in tree::take_children(e, |c| {
            (c.name == "motor" || c.name == "position") && has(c, "name")
        }) {
            removed_actuators.extend(attr(&a, "name").map(str::to_owned));
        }
    });
    xml.names
        .actuators
        .retain(|a| !removed_actuators.contains(&format!("{prefix}{a}")));
    tree::visit_mut(doc.section_mut("tendon"), &mut |e| {
        tree::take_children(e, |c| {
            c.name == "fixed" && tree::children(c).any(|j| j.name == "joint" && has(j, "joint"))
        });
    });
    tree::visit_mut(doc.section_mut("equality"), &mut |e| {
        tree::take_children(e, |c| {
            c.name == "joint" && (has(c, "joint1") || has(c, "joint2"))
        });
    });
    tree::visit_mut(doc.root_mut(), &mut |e| {
        tree::take_children(e, |c| {
            matches!(
                c.name.as_str(),
                "jointpos" | "jointvel" | "jointactuatorfrc"
            ) && has(c, "joint")
        });
    });
}

/// A robot model as robosuite's `RobotModel` describes it on its own (`robosuite.models.
/// robots.Panda(idn)`: the robot's file prepared, before a task adds a mount and
/// grippers): its names, figures and MJCF.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RobotDescription {
    /// robosuite's robot name.
    pub name: &'static str,
    /// The robot's index.
    pub idn: usize,
    /// The prefix of every element name (`robot0_`).
    pub naming_prefix: String,
    /// robosuite's `arm_type`: `"single"` or `"bimanual"`.
    pub arm_type: &'static str,
    /// The arms (`["right"]`, `["right", "left"]`).
    pub arms: &'static [&'static str],
    /// The root body, prefixed.
    pub root_body: String,
    /// The body each arm's gripper attaches to, prefixed (robosuite's `eef_name`).
    pub eef_name: Vec<String>,
    /// Every body, prefixed, the root body first.
    pub bodies: Vec<String>,
    /// The joints, prefixed.
    pub joints: Vec<String>,
    /// The actuators, prefixed.
    pub actuators: Vec<String>,
    /// The sites, prefixed.
    pub sites: Vec<String>,
    /// The contact geoms, prefixed.
    pub contact_geoms: Vec<String>,
    /// The visual geoms, prefixed.
    pub visual_geoms: Vec<String>,
    /// The joints' rest positions.
    pub init_qpos: &'static [f64],
    /// The default gripper per arm (robosuite's class names).
    pub default_grippers: &'static [&'static str],
    /// The default base (mount) class name.
    pub default_base: &'static str,
    /// Where the robot stands in the bins and empty arenas, and the x (minus half the
    /// table's length) and z of its offset at a table.
    pub base_xpos_offset: ([f64; 3], [f64; 3], f64, f64),
    /// From the root body to the robot's top.
    pub top_offset: [f64; 3],
    /// The robot's horizontal radius.
    pub horizontal_radius: f64,
    /// The root body's position in the file (robosuite's `bottom_offset` without a mount).
    pub base_offset: [f64; 3],
    /// The prepared MJCF.
    pub xml: String,
}

/// robosuite's robot model `name` on its own as robot `idn` (see [`RobotDescription`]).
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown robot (listing the robots); [`Error::Model`]
/// when its file is missing or malformed.
pub fn describe_robot(assets: &Assets, name: &str, idn: usize) -> Result<RobotDescription> {
    let info = robot_info(name)?;
    let xml = load_prepared(assets, info, idn)?;
    let names = |list: &[String]| xml.names_of(list);
    Ok(RobotDescription {
        name: info.name,
        idn,
        naming_prefix: xml.prefix.clone(),
        arm_type: if info.arms.len() > 1 {
            "bimanual"
        } else {
            "single"
        },
        arms: info.arms,
        root_body: xml.root_body(),
        eef_name: info.eef_bodies.iter().map(|b| xml.name(b)).collect(),
        bodies: names(&xml.names.bodies),
        joints: names(&xml.names.joints),
        actuators: names(&xml.names.actuators),
        sites: names(&xml.names.sites),
        contact_geoms: names(&xml.names.contact_geoms),
        visual_geoms: names(&xml.names.visual_geoms),
        init_qpos: info.init_qpos,
        default_grippers: info.default_grippers,
        default_base: info.default_mount.name,
        base_xpos_offset: (
            info.base_offsets.bins,
            info.base_offsets.empty,
            info.base_offsets.table_x,
            info.base_offsets.table_z,
        ),
        top_offset: info.top_offset,
        horizontal_radius: info.horizontal_radius,
        base_offset: xml.base_offset,
        xml: xml.doc.to_xml(),
    })
}
