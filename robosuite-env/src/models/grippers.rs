//! robosuite's grippers (`robosuite/models/grippers/`): which file, which initial finger
//! positions, which geoms are finger pads, and how one gripper action drives the fingers
//! (its `format_action`).

use super::GRIPPER_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::XmlModel;
use gym_core::{Error, Result};

/// How a gripper turns its action into commands for its actuators (robosuite's
/// `format_action`), each command in `[-1, 1]` and mapped onto the actuator's ctrlrange
/// by the `GRIP` controller.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum GripAction {
    /// No action (no actuators, or none driven): the wiping tool and the null gripper.
    None,
    /// One action whose sign moves an integrator per actuator:
    /// `c_i ← clip(c_i + signs_i · speed · sign(a), −1, 1)`, zeroed at reset (Panda's
    /// `[-1, 1]`, speed 0.2).
    SignIntegrator {
        /// The direction each actuator's command moves for a positive (closing) action.
        signs: &'static [f64],
        /// The change per env step.
        speed: f64,
    },
}

impl GripAction {
    /// The number of action dimensions (robosuite's gripper `dof`).
    pub fn dof(&self) -> usize {
        match self {
            Self::None => 0,
            Self::SignIntegrator { .. } => 1,
        }
    }
}

/// A gripper class of robosuite: the figures its Python class holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GripperInfo {
    /// robosuite's class name, such as `"PandaGripper"`.
    pub name: &'static str,
    /// Its model file under `models/assets`.
    pub file: &'static str,
    /// The finger joints' initial positions (robosuite's `init_qpos`; `None`: not set).
    pub init_qpos: Option<&'static [f64]>,
    /// How the action drives the actuators.
    pub action: GripAction,
    /// Contact geoms of the left finger pad group (`_check_grasp`), unprefixed.
    pub left_fingerpad: &'static [&'static str],
    /// Contact geoms of the right finger pad group, unprefixed.
    pub right_fingerpad: &'static [&'static str],
    /// Every geom of the left finger, unprefixed.
    pub left_finger: &'static [&'static str],
    /// Every geom of the right finger, unprefixed.
    pub right_finger: &'static [&'static str],
    /// Extra named geoms (the wiping tool's `corners`).
    pub corners: &'static [&'static str],
}

/// robosuite's `PandaGripper`.
pub const PANDA_GRIPPER: GripperInfo = GripperInfo {
    name: "PandaGripper",
    file: "grippers/panda_gripper.xml",
    init_qpos: Some(&[0.020833, -0.020833]),
    action: GripAction::SignIntegrator {
        signs: &[-1.0, 1.0],
        speed: 0.2,
    },
    left_fingerpad: &["finger1_pad_collision"],
    right_fingerpad: &["finger2_pad_collision"],
    left_finger: &["finger1_collision", "finger1_pad_collision"],
    right_finger: &["finger2_collision", "finger2_pad_collision"],
    corners: &[],
};

/// robosuite's `WipingGripper` (Wipe's tool: no fingers, no action).
pub const WIPING_GRIPPER: GripperInfo = GripperInfo {
    name: "WipingGripper",
    file: "grippers/wiping_gripper.xml",
    init_qpos: None,
    action: GripAction::None,
    left_fingerpad: &[],
    right_fingerpad: &[],
    left_finger: &[],
    right_finger: &[],
    corners: &[
        "wiping_corner1",
        "wiping_corner2",
        "wiping_corner3",
        "wiping_corner4",
    ],
};

/// robosuite's `NullGripper`: what an arm carries with `gripper_types=None`.
pub const NULL_GRIPPER: GripperInfo = GripperInfo {
    name: "NullGripper",
    file: "grippers/null_gripper.xml",
    init_qpos: None,
    action: GripAction::None,
    left_fingerpad: &[],
    right_fingerpad: &[],
    left_finger: &[],
    right_finger: &[],
    corners: &[],
};

/// Every gripper [`gripper_info`] knows, by robosuite's class name.
pub const GRIPPERS: &[GripperInfo] = &[PANDA_GRIPPER, WIPING_GRIPPER];

/// The gripper robosuite names `name`.
///
/// # Errors
/// [`Error::InvalidArgument`] (argument `gripper_types`) listing the valid names.
pub fn gripper_info(name: &str) -> Result<GripperInfo> {
    GRIPPERS
        .iter()
        .find(|g| g.name == name)
        .copied()
        .ok_or_else(|| {
            Error::invalid_argument(
                "gripper_types",
                format!(
                    "unknown gripper `{name}`; valid: {}, or None",
                    GRIPPERS
                        .iter()
                        .map(|g| g.name)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
        })
}

/// A gripper's model file prepared as robosuite's `GripperModel` (prefix
/// `gripper{robot}_{arm}_`), with its figures.
#[derive(Debug, Clone)]
pub struct GripperModel {
    /// The prepared file.
    pub xml: XmlModel,
    /// The gripper's figures.
    pub info: GripperInfo,
}

impl GripperModel {
    /// Loads gripper `info` for arm `arm` (`"right"` or `"left"`) of robot `robot`.
    ///
    /// # Errors
    /// [`Error::Model`] when its file is missing or malformed.
    pub fn load(assets: &Assets, info: GripperInfo, robot: usize, arm: &str) -> Result<Self> {
        let xml = XmlModel::load(
            &assets.file(info.file)?,
            &format!("gripper{robot}_{arm}_"),
            GRIPPER_COLLISION_COLOR,
        )?;
        Ok(Self { xml, info })
    }
}
