//! robosuite's grippers (`robosuite/models/grippers/`): which file, which initial finger
//! positions, which geoms are finger pads, and how one gripper action drives the fingers
//! (its `format_action`).

use super::GRIPPER_COLLISION_COLOR;
use crate::assets::Assets;
use crate::mjcf::XmlModel;
use crate::mjcf::tree::{array_to_string, set_attr};
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
    /// One action whose *value* moves one shared integrator, `c ← clip(c + speed · a, −1, 1)`,
    /// driving the first `shared` actuators; the remaining actuators get the fixed
    /// commands `tail` (robosuite's `RobotiqThreeFingerGripper`: `[c, c, c, -1]`).
    ValueIntegrator {
        /// The change per env step per unit of action.
        speed: f64,
        /// How many actuators follow the integrator.
        shared: usize,
        /// The fixed commands of the other actuators.
        tail: &'static [f64],
    },
    /// One action per actuator, each moving its own integrator by its sign:
    /// `c_i ← clip(c_i + sign · speed · sign(a_i), −1, 1)` (the dexterous variants).
    PerActuator {
        /// The direction commands move for a positive action.
        sign: f64,
        /// The change per env step.
        speed: f64,
        /// The number of actions (and actuators).
        dof: usize,
    },
    /// One action per finger group, copied to the actuators by `indices` (actuator `i`
    /// gets action `indices[i]`) and used as is: the actuator's target with robosuite's
    /// `use_action_scaling: false`, else mapped from `[-1, 1]` onto its ctrlrange (the
    /// dexterous hands: `InspireLeftHand` / `InspireRightHand`, `FourierLeftHand` /
    /// `FourierRightHand`).
    Indexed {
        /// The action each actuator takes.
        indices: &'static [usize],
        /// The number of actions.
        dof: usize,
    },
}

impl GripAction {
    /// The number of action dimensions (robosuite's gripper `dof`).
    pub fn dof(&self) -> usize {
        match self {
            Self::None => 0,
            Self::SignIntegrator { .. } | Self::ValueIntegrator { .. } => 1,
            Self::PerActuator { dof, .. } | Self::Indexed { dof, .. } => *dof,
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

/// robosuite's `RethinkGripper` (Sawyer's two-finger parallel jaw).
pub const RETHINK_GRIPPER: GripperInfo = GripperInfo {
    name: "RethinkGripper",
    file: "grippers/rethink_gripper.xml",
    init_qpos: Some(&[0.020833, -0.020833]),
    action: GripAction::SignIntegrator {
        signs: &[1.0, -1.0],
        speed: 0.2,
    },
    left_fingerpad: &["l_fingerpad_g0"],
    right_fingerpad: &["r_fingerpad_g0"],
    left_finger: &[
        "l_finger_g0",
        "l_finger_g1",
        "l_fingertip_g0",
        "l_fingerpad_g0",
    ],
    right_finger: &[
        "r_finger_g0",
        "r_finger_g1",
        "r_fingertip_g0",
        "r_fingerpad_g0",
    ],
    corners: &[],
};

/// The finger geoms of both Robotiq parallel grippers.
const ROBOTIQ_LEFT_FINGER: &[&str] = &[
    "left_outer_finger_collision",
    "left_inner_finger_collision",
    "left_fingertip_collision",
    "left_fingerpad_collision",
];
const ROBOTIQ_RIGHT_FINGER: &[&str] = &[
    "right_outer_finger_collision",
    "right_inner_finger_collision",
    "right_fingertip_collision",
    "right_fingerpad_collision",
];

/// robosuite's `Robotiq85Gripper` (UR5e's and Kinova3's).
pub const ROBOTIQ85_GRIPPER: GripperInfo = GripperInfo {
    name: "Robotiq85Gripper",
    file: "grippers/robotiq_gripper_85.xml",
    init_qpos: Some(&[-0.026, -0.267, -0.200, -0.026, -0.267, -0.200]),
    action: GripAction::SignIntegrator {
        signs: &[1.0, 1.0],
        speed: 0.2,
    },
    left_fingerpad: &["left_fingerpad_collision"],
    right_fingerpad: &["right_fingerpad_collision"],
    left_finger: ROBOTIQ_LEFT_FINGER,
    right_finger: ROBOTIQ_RIGHT_FINGER,
    corners: &[],
};

/// robosuite's `Robotiq140Gripper` (IIWA's).
pub const ROBOTIQ140_GRIPPER: GripperInfo = GripperInfo {
    name: "Robotiq140Gripper",
    file: "grippers/robotiq_gripper_140.xml",
    init_qpos: Some(&[0.012, 0.065, 0.065, -0.012, 0.065, 0.065]),
    action: GripAction::SignIntegrator {
        signs: &[1.0, -1.0],
        speed: 0.2,
    },
    left_fingerpad: &["left_fingerpad_collision"],
    right_fingerpad: &["right_fingerpad_collision"],
    left_finger: ROBOTIQ_LEFT_FINGER,
    right_finger: ROBOTIQ_RIGHT_FINGER,
    corners: &[],
};

/// The figures both Jaco three-finger grippers share.
const JACO_THREE_FINGER: GripperInfo = GripperInfo {
    name: "JacoThreeFingerGripper",
    file: "grippers/jaco_three_finger_gripper.xml",
    init_qpos: Some(&[0.5, 0.0, 0.5, 0.0, 0.5, 0.0]),
    action: GripAction::SignIntegrator {
        signs: &[-1.0, -1.0, -1.0],
        speed: 0.01,
    },
    left_fingerpad: &["index_pad_collision", "pinky_pad_collision"],
    right_fingerpad: &["thumb_pad_collision"],
    left_finger: &[
        "index_proximal_collision",
        "index_distal_collision",
        "index_tip_collision",
        "pinky_proximal_collision",
        "pinky_distal_collision",
        "pinky_tip_collision",
        "index_tip_collision",
        "pinky_pad_collision",
    ],
    right_finger: &[
        "thumb_proximal_collision",
        "thumb_distal_collision",
        "thumb_tip_collision",
        "thumb_pad_collision",
    ],
    corners: &[],
};

/// robosuite's `JacoThreeFingerGripper` (Jaco's; one action closes all three fingers).
pub const JACO_THREE_FINGER_GRIPPER: GripperInfo = JACO_THREE_FINGER;

/// robosuite's `JacoThreeFingerDexterousGripper` (one action per finger).
pub const JACO_THREE_FINGER_DEXTEROUS_GRIPPER: GripperInfo = GripperInfo {
    name: "JacoThreeFingerDexterousGripper",
    action: GripAction::PerActuator {
        sign: -1.0,
        speed: 0.01,
        dof: 3,
    },
    ..JACO_THREE_FINGER
};

/// The figures both Robotiq three-finger grippers share.
const ROBOTIQ_THREE_FINGER: GripperInfo = GripperInfo {
    name: "RobotiqThreeFingerGripper",
    file: "grippers/robotiq_gripper_s.xml",
    init_qpos: Some(&[0.0; 11]),
    action: GripAction::ValueIntegrator {
        speed: 0.2,
        shared: 3,
        tail: &[-1.0],
    },
    left_fingerpad: &["f1_pad_collision", "f2_pad_collision"],
    right_fingerpad: &["finger_middle_pad_collision"],
    left_finger: &[
        "f1_l0",
        "f1_l1",
        "f1_l2",
        "f1_l3",
        "f2_l0",
        "f2_l1",
        "f2_l2",
        "f2_l3",
        "f1_tip_collision",
        "f2_tip_collision",
        "f1_pad_collision",
        "f2_pad_collision",
    ],
    right_finger: &[
        "f3_l0",
        "f3_l1",
        "f3_l2",
        "f3_l3",
        "finger_middle_tip_collision",
        "finger_middle_pad_collision",
    ],
    corners: &[],
};

/// robosuite's `RobotiqThreeFingerGripper` (one action for the three fingers; the scissor
/// joint held open).
pub const ROBOTIQ_THREE_FINGER_GRIPPER: GripperInfo = ROBOTIQ_THREE_FINGER;

/// robosuite's `RobotiqThreeFingerDexterousGripper` (one action per finger and the scissor).
pub const ROBOTIQ_THREE_FINGER_DEXTEROUS_GRIPPER: GripperInfo = GripperInfo {
    name: "RobotiqThreeFingerDexterousGripper",
    action: GripAction::PerActuator {
        sign: 1.0,
        speed: 0.2,
        dof: 4,
    },
    ..ROBOTIQ_THREE_FINGER
};

/// robosuite's `XArm7Gripper`.
///
/// robosuite 1.5.2 names its finger pads `finger1_pad_collision` / `finger2_pad_collision`,
/// geoms its model file does not have (the pads are `left_finger_pad_1`, ...); its
/// name-based contact check therefore never reports a grasp with this gripper. The pad
/// groups are empty here, which reproduces that.
pub const XARM7_GRIPPER: GripperInfo = GripperInfo {
    name: "XArm7Gripper",
    file: "grippers/xarm7_gripper.xml",
    init_qpos: Some(&[0.02, 0.0, 0.0, -0.02, 0.0, 0.0]),
    action: GripAction::SignIntegrator {
        signs: &[1.0],
        speed: 0.2,
    },
    left_fingerpad: &[],
    right_fingerpad: &[],
    left_finger: &[],
    right_finger: &[],
    corners: &[],
};

/// robosuite's `BDGripper` (the Spot arm's one-jaw gripper, one position actuator).
/// robosuite names its finger pads `left_finger_coll` / `right_finger_coll`, mesh names,
/// not geoms of its model file (whose geoms are unnamed); its name-based contact check
/// therefore never reports a grasp with this gripper. The pad groups are empty here, which
/// reproduces that.
pub const BD_GRIPPER: GripperInfo = GripperInfo {
    name: "BDGripper",
    file: "grippers/bd_gripper.xml",
    init_qpos: Some(&[-1.57]),
    action: GripAction::SignIntegrator {
        signs: &[1.0],
        speed: 0.2,
    },
    left_fingerpad: &[],
    right_fingerpad: &[],
    left_finger: &[],
    right_finger: &[],
    corners: &[],
};

/// The action index each actuator of an Inspire hand copies (robosuite's `format_action`:
/// actuators pinky, ring, middle, index (two each), thumb bend (three), thumb rotation).
const INSPIRE_ACTION_INDICES: &[usize] = &[0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 4, 5];

/// robosuite's `InspireRightHand` (the Inspire dexterous hand: 12 joints, 12 position
/// actuators, 6 actions).
pub const INSPIRE_RIGHT_HAND: GripperInfo = GripperInfo {
    name: "InspireRightHand",
    file: "grippers/inspire_right_hand.xml",
    init_qpos: Some(&[0.0; 12]),
    action: GripAction::Indexed {
        indices: INSPIRE_ACTION_INDICES,
        dof: 6,
    },
    left_fingerpad: &[
        "r_thumb_proximal_col",
        "r_thumb_proximal_2_col",
        "r_thumb_middle_col",
        "r_thumb_distal_col",
    ],
    right_fingerpad: &[
        "r_index_proximal_col",
        "r_index_distal_col",
        "r_middle_proximal_col",
        "r_middle_distal_col",
        "r_ring_proximal_col",
        "r_ring_distal_col",
        "r_pinky_proximal_col",
        "r_pinky_distal_col",
    ],
    left_finger: &[
        "r_thumb_proximal_col",
        "r_thumb_proximal_2_col",
        "r_thumb_middle_col",
        "r_thumb_distal_col",
    ],
    right_finger: &[
        "r_index_proximal_col",
        "r_index_distal_col",
        "r_middle_proximal_col",
        "r_middle_distal_col",
        "r_ring_proximal_col",
        "r_ring_distal_col",
        "r_pinky_proximal_col",
        "r_pinky_distal_col",
    ],
    corners: &[],
};

/// robosuite's `InspireLeftHand` (the mirror of [`INSPIRE_RIGHT_HAND`]).
pub const INSPIRE_LEFT_HAND: GripperInfo = GripperInfo {
    name: "InspireLeftHand",
    file: "grippers/inspire_left_hand.xml",
    left_fingerpad: &[
        "l_thumb_proximal_col",
        "l_thumb_proximal_2_col",
        "l_thumb_middle_col",
        "l_thumb_distal_col",
    ],
    right_fingerpad: &[
        "l_index_proximal_col",
        "l_index_distal_col",
        "l_middle_proximal_col",
        "l_middle_distal_col",
        "l_ring_proximal_col",
        "l_ring_distal_col",
        "l_pinky_proximal_col",
        "l_pinky_distal_col",
    ],
    left_finger: &[
        "l_thumb_proximal_col",
        "l_thumb_proximal_2_col",
        "l_thumb_middle_col",
        "l_thumb_distal_col",
    ],
    right_finger: &[
        "l_index_proximal_col",
        "l_index_distal_col",
        "l_middle_proximal_col",
        "l_middle_distal_col",
        "l_ring_proximal_col",
        "l_ring_distal_col",
        "l_pinky_proximal_col",
        "l_pinky_distal_col",
    ],
    ..INSPIRE_RIGHT_HAND
};

/// The actions of a Fourier hand's 11 actuators (pinky, ring, middle, index: two each;
/// the thumb's bend two, its rotation one): robosuite's `format_action` indices.
const FOURIER_HAND_ACTION: GripAction = GripAction::Indexed {
    indices: &[0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5],
    dof: 6,
};

/// robosuite's `FourierLeftHand` (GR1's left hand: 11 finger joints, 6 actions).
pub const FOURIER_LEFT_HAND: GripperInfo = GripperInfo {
    name: "FourierLeftHand",
    file: "grippers/fourier_left_hand.xml",
    init_qpos: Some(&[0.0; 11]),
    action: FOURIER_HAND_ACTION,
    left_fingerpad: &[
        "L_thumb_proximal_base_link_col",
        "L_thumb_proximal_link_col",
        "L_thumb_distal_link_col",
    ],
    right_fingerpad: &[
        "L_index_proximal_link_col",
        "L_index_intermediate_link_col",
        "L_middle_proximal_link_col",
        "L_middle_proximal_link_col",
        "L_ring_proximal_link_col",
        "L_ring_intermediate_link_col",
        "L_pinky_proximal_link_col",
        "L_pinky_intermediate_link_col",
    ],
    left_finger: &[
        "L_thumb_proximal_base_link_col",
        "L_thumb_proximal_link_col",
        "L_thumb_distal_link_col",
    ],
    right_finger: &[
        "L_index_proximal_link_col",
        "L_index_intermediate_link_col",
        "L_middle_proximal_link_col",
        "L_middle_proximal_link_col",
        "L_ring_proximal_link_col",
        "L_ring_intermediate_link_col",
        "L_pinky_proximal_link_col",
        "L_pinky_intermediate_link_col",
    ],
    corners: &[],
};

/// robosuite's `FourierRightHand` (GR1's right hand).
pub const FOURIER_RIGHT_HAND: GripperInfo = GripperInfo {
    name: "FourierRightHand",
    file: "grippers/fourier_right_hand.xml",
    init_qpos: Some(&[0.0; 11]),
    action: FOURIER_HAND_ACTION,
    left_fingerpad: &[
        "R_thumb_proximal_base_link_col",
        "R_thumb_proximal_link_col",
        "R_thumb_distal_link_col",
    ],
    right_fingerpad: &[
        "R_index_proximal_link_col",
        "R_index_intermediate_link_col",
        "R_middle_proximal_link_col",
        "R_middle_proximal_link_col",
        "R_ring_proximal_link_col",
        "R_ring_intermediate_link_col",
        "R_pinky_proximal_link_col",
        "R_pinky_intermediate_link_col",
    ],
    left_finger: &[
        "R_thumb_proximal_base_link_col",
        "R_thumb_proximal_link_col",
        "R_thumb_distal_link_col",
    ],
    right_finger: &[
        "R_index_proximal_link_col",
        "R_index_intermediate_link_col",
        "R_middle_proximal_link_col",
        "R_middle_proximal_link_col",
        "R_ring_proximal_link_col",
        "R_ring_intermediate_link_col",
        "R_pinky_proximal_link_col",
        "R_pinky_intermediate_link_col",
    ],
    corners: &[],
};

/// Every gripper [`gripper_info`] knows, by robosuite's class name (with `None`, robosuite
/// attaches [`NULL_GRIPPER`]).
pub const GRIPPERS: &[GripperInfo] = &[
    PANDA_GRIPPER,
    RETHINK_GRIPPER,
    ROBOTIQ85_GRIPPER,
    ROBOTIQ140_GRIPPER,
    JACO_THREE_FINGER_GRIPPER,
    JACO_THREE_FINGER_DEXTEROUS_GRIPPER,
    ROBOTIQ_THREE_FINGER_GRIPPER,
    ROBOTIQ_THREE_FINGER_DEXTEROUS_GRIPPER,
    XARM7_GRIPPER,
    WIPING_GRIPPER,
    BD_GRIPPER,
    INSPIRE_RIGHT_HAND,
    INSPIRE_LEFT_HAND,
    FOURIER_LEFT_HAND,
    FOURIER_RIGHT_HAND,
];

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

    /// robosuite's custom gripper mount: sets the position and (w, x, y, z) orientation
    /// of the gripper's first body, where given.
    pub fn set_mount_offset(&mut self, pos: Option<[f64; 3]>, quat: Option<[f64; 4]>) {
        let body = self.xml.root_body_element_mut();
        if let Some(pos) = pos {
            set_attr(body, "pos", array_to_string(&pos));
        }
        if let Some(quat) = quat {
            set_attr(body, "quat", array_to_string(&quat));
        }
    }
}
