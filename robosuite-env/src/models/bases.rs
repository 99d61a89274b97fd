//! robosuite's robot bases (`robosuite/models/bases/`): the fixed mounts a single-arm robot
//! stands on.

use super::MOUNT_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::XmlModel;
use gym_core::{Error, Result};

/// A mount class of robosuite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MountInfo {
    /// robosuite's class name, such as `"RethinkMount"`.
    pub name: &'static str,
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
    file: "bases/rethink_mount.xml",
    top_offset: [0.0, 0.0, -0.01],
    horizontal_radius: 0.25,
};

/// robosuite's `RethinkMinimalMount` (Baxter's).
pub const RETHINK_MINIMAL_MOUNT: MountInfo = MountInfo {
    name: "RethinkMinimalMount",
    file: "bases/rethink_minimal_mount.xml",
    top_offset: [0.0, 0.0, -0.062],
    horizontal_radius: 0.25,
};

/// robosuite's `NullMount`.
pub const NULL_MOUNT: MountInfo = MountInfo {
    name: "NullMount",
    file: "bases/null_mount.xml",
    top_offset: [0.0, 0.0, 0.0],
    horizontal_radius: 0.0,
};

/// Every mount [`mount_info`] knows.
pub const MOUNTS: &[MountInfo] = &[RETHINK_MOUNT, RETHINK_MINIMAL_MOUNT, NULL_MOUNT];

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
    /// Loads mount `info` for robot `robot`.
    ///
    /// # Errors
    /// [`Error::Model`] when its file is missing or malformed.
    pub fn load(assets: &Assets, info: MountInfo, robot: usize) -> Result<Self> {
        let xml = XmlModel::load(
            &assets.file(info.file)?,
            &format!("fixed_mount{robot}_"),
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
