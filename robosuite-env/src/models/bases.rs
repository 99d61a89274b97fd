//! robosuite's robot bases (`robosuite/models/bases/`): the fixed mounts a fixed-base robot
//! stands on and the mobile bases of wheeled robots, one table ([`MOUNTS`]).

use super::MOUNT_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::XmlModel;
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
}

impl BaseKind {
    /// The name prefix of robot `robot`'s base.
    pub fn prefix(self, robot: usize) -> String {
        match self {
            Self::Mount => format!("fixed_mount{robot}_"),
            Self::MobileBase => format!("mobilebase{robot}_"),
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
        let xml = XmlModel::load(
            &assets.file(info.file)?,
            &info.kind.prefix(robot),
            MOUNT_COLLISION_COLOR,
        )?;
        Ok(Self { xml, info })
    }

    /// From the root body to the bottom (robosuite's `bottom_offset`: the root body's `pos`
    /// in the file).
    pub fn bottom_offset(&self) -> [f64; 3] {
        self.xml.base_offset
    }
}
