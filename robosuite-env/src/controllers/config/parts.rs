//! robosuite's part-controller configurations, one type per controller, with robosuite's
//! constructor defaults for every key a config leaves out.

use super::values::{Bounds, ImpedanceMode, InputRefFrame, InputType, Interpolation, PerAxis};
use crate::controllers::table::{arm_controller, entry_of};
use serde::{Deserialize, Serialize};
use serde_aux::serde_introspection::serde_introspect;

/// The gripper controllers (robosuite's `GRIP`).
pub const GRIPPER_CONTROLLER_TYPES: &[&str] = &["GRIP"];

fn one() -> PerAxis {
    PerAxis::Scalar(1.0)
}

fn minus_one() -> PerAxis {
    PerAxis::Scalar(-1.0)
}

fn yes() -> bool {
    true
}

fn ramp_ratio() -> f64 {
    0.2
}

/// `OSC_POSE` / `OSC_POSITION` (robosuite's `OperationalSpaceController`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OscConfig {
    /// Largest input, per action axis (default 1); delta inputs are clipped to it.
    #[serde(default = "one")]
    pub input_max: PerAxis,
    /// Smallest input (default −1).
    #[serde(default = "minus_one")]
    pub input_min: PerAxis,
    /// Delta at `input_max` (default 0.05 m per position axis, 0.5 rad per rotation axis).
    #[serde(default)]
    pub output_max: Option<PerAxis>,
    /// Delta at `input_min` (default −0.05 m, −0.5 rad).
    #[serde(default)]
    pub output_min: Option<PerAxis>,
    /// Stiffness per task axis, six values (default 150).
    #[serde(default = "OscConfig::default_kp")]
    pub kp: PerAxis,
    /// Damping ratio, `kd = 2·sqrt(kp)·damping_ratio` (default 1).
    #[serde(default = "one")]
    pub damping_ratio: PerAxis,
    /// Fixed gains or gains in the action (default fixed).
    #[serde(default)]
    pub impedance_mode: ImpedanceMode,
    /// Range of stiffness actions in the variable modes (default `[0, 300]`).
    #[serde(default = "OscConfig::default_kp_limits")]
    pub kp_limits: Bounds,
    /// Range of damping-ratio actions in the `variable` mode (default `[0, 100]`).
    #[serde(default = "OscConfig::default_damping_ratio_limits")]
    pub damping_ratio_limits: Bounds,
    /// Box the goal position is clipped to, in the input frame (default none).
    #[serde(default)]
    pub position_limits: Option<Bounds>,
    /// Box of xyz Euler angles the goal orientation is clipped to (default none).
    #[serde(default)]
    pub orientation_limits: Option<Bounds>,
    /// Separate position and orientation task inertias (default true).
    #[serde(default = "yes")]
    pub uncouple_pos_ori: bool,
    /// Delta or absolute inputs (default delta).
    #[serde(default)]
    pub input_type: InputType,
    /// Base or world frame (default base).
    #[serde(default)]
    pub input_ref_frame: InputRefFrame,
    /// Goal interpolation (default none).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Share of the env step over which an interpolated goal ramps (default 0.2).
    #[serde(default = "ramp_ratio")]
    pub ramp_ratio: f64,
}

impl OscConfig {
    fn default_kp() -> PerAxis {
        PerAxis::Scalar(150.0)
    }

    fn default_kp_limits() -> Bounds {
        Bounds::uniform(0.0, 300.0)
    }

    fn default_damping_ratio_limits() -> Bounds {
        Bounds::uniform(0.0, 100.0)
    }

    /// The same stiffness on every axis.
    #[must_use]
    pub fn with_kp(mut self, kp: f64) -> Self {
        self.kp = PerAxis::Scalar(kp);
        self
    }

    /// The same damping ratio on every axis.
    #[must_use]
    pub fn with_damping_ratio(mut self, ratio: f64) -> Self {
        self.damping_ratio = PerAxis::Scalar(ratio);
        self
    }

    /// Sets the impedance mode.
    #[must_use]
    pub fn with_impedance_mode(mut self, mode: ImpedanceMode) -> Self {
        self.impedance_mode = mode;
        self
    }

    /// Sets the input type.
    #[must_use]
    pub fn with_input_type(mut self, input_type: InputType) -> Self {
        self.input_type = input_type;
        self
    }

    /// Sets the input frame.
    #[must_use]
    pub fn with_input_ref_frame(mut self, frame: InputRefFrame) -> Self {
        self.input_ref_frame = frame;
        self
    }

    /// Sets the interpolation.
    #[must_use]
    pub fn with_interpolation(mut self, interpolation: Interpolation) -> Self {
        self.interpolation = interpolation;
        self
    }
}

impl Default for OscConfig {
    /// robosuite's constructor defaults (`default_panda.json` differs only in
    /// `damping_ratio_limits`, `[0, 10]`).
    fn default() -> Self {
        Self {
            input_max: one(),
            input_min: minus_one(),
            output_max: None,
            output_min: None,
            kp: Self::default_kp(),
            damping_ratio: one(),
            impedance_mode: ImpedanceMode::Fixed,
            kp_limits: Self::default_kp_limits(),
            damping_ratio_limits: Self::default_damping_ratio_limits(),
            position_limits: None,
            orientation_limits: None,
            uncouple_pos_ori: true,
            input_type: InputType::Delta,
            input_ref_frame: InputRefFrame::Base,
            interpolation: Interpolation::None,
            ramp_ratio: ramp_ratio(),
        }
    }
}

/// `JOINT_POSITION` (robosuite's `JointPositionController`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointPositionConfig {
    /// Largest input per joint (default 1).
    #[serde(default = "one")]
    pub input_max: PerAxis,
    /// Smallest input per joint (default −1).
    #[serde(default = "minus_one")]
    pub input_min: PerAxis,
    /// Joint delta at `input_max` (default 0.05 rad).
    #[serde(default = "JointPositionConfig::default_output_max")]
    pub output_max: PerAxis,
    /// Joint delta at `input_min` (default −0.05 rad).
    #[serde(default = "JointPositionConfig::default_output_min")]
    pub output_min: PerAxis,
    /// Stiffness per joint (default 50).
    #[serde(default = "JointPositionConfig::default_kp")]
    pub kp: PerAxis,
    /// Damping ratio (default 1).
    #[serde(default = "one")]
    pub damping_ratio: PerAxis,
    /// Damping gains given directly, replacing `2·sqrt(kp)·damping_ratio` (default none).
    #[serde(default)]
    pub kd: Option<PerAxis>,
    /// Fixed gains or gains in the action (default fixed).
    #[serde(default)]
    pub impedance_mode: ImpedanceMode,
    /// Range of stiffness actions (default `[0, 300]`).
    #[serde(default = "OscConfig::default_kp_limits")]
    pub kp_limits: Bounds,
    /// Range of damping-ratio actions (default `[0, 100]`).
    #[serde(default = "OscConfig::default_damping_ratio_limits")]
    pub damping_ratio_limits: Bounds,
    /// Box the goal joint positions are clipped to (default none).
    #[serde(default)]
    pub qpos_limits: Option<Bounds>,
    /// Delta or absolute joint targets (default delta; absolute needs fixed impedance).
    #[serde(default)]
    pub input_type: InputType,
    /// Multiply by the mass matrix and add gravity and Coriolis torques (default true).
    #[serde(default = "yes")]
    pub use_torque_compensation: bool,
    /// Goal interpolation (default none).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Share of the env step over which an interpolated goal ramps (default 0.2).
    #[serde(default = "ramp_ratio")]
    pub ramp_ratio: f64,
}

impl JointPositionConfig {
    fn default_output_max() -> PerAxis {
        PerAxis::Scalar(0.05)
    }

    fn default_output_min() -> PerAxis {
        PerAxis::Scalar(-0.05)
    }

    fn default_kp() -> PerAxis {
        PerAxis::Scalar(50.0)
    }
}

impl Default for JointPositionConfig {
    /// robosuite's constructor defaults.
    fn default() -> Self {
        Self {
            input_max: one(),
            input_min: minus_one(),
            output_max: Self::default_output_max(),
            output_min: Self::default_output_min(),
            kp: Self::default_kp(),
            damping_ratio: one(),
            kd: None,
            impedance_mode: ImpedanceMode::Fixed,
            kp_limits: OscConfig::default_kp_limits(),
            damping_ratio_limits: OscConfig::default_damping_ratio_limits(),
            qpos_limits: None,
            input_type: InputType::Delta,
            use_torque_compensation: true,
            interpolation: Interpolation::None,
            ramp_ratio: ramp_ratio(),
        }
    }
}

/// `JOINT_VELOCITY` (robosuite's `JointVelocityController`, a PID on joint velocities).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointVelocityConfig {
    /// Largest input per joint (default 1).
    #[serde(default = "one")]
    pub input_max: PerAxis,
    /// Smallest input per joint (default −1).
    #[serde(default = "minus_one")]
    pub input_min: PerAxis,
    /// Joint velocity at `input_max` (default 1 rad/s).
    #[serde(default = "one")]
    pub output_max: PerAxis,
    /// Joint velocity at `input_min` (default −1 rad/s).
    #[serde(default = "minus_one")]
    pub output_min: PerAxis,
    /// Proportional gain: a number is multiplied by each motor's torque range, a list is
    /// used as is (default 0.25); `ki = 0.005·kp`, `kd = 0.001·kp`.
    #[serde(default = "JointVelocityConfig::default_kp")]
    pub kp: PerAxis,
    /// Box the goal velocities are clipped to (default none).
    #[serde(default)]
    pub velocity_limits: Option<Bounds>,
    /// Add gravity and Coriolis torques (default true).
    #[serde(default = "yes")]
    pub use_torque_compensation: bool,
    /// Goal interpolation (default none).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Share of the env step over which an interpolated goal ramps (default 0.2).
    #[serde(default = "ramp_ratio")]
    pub ramp_ratio: f64,
}

impl JointVelocityConfig {
    fn default_kp() -> PerAxis {
        PerAxis::Scalar(0.25)
    }
}

impl Default for JointVelocityConfig {
    /// robosuite's constructor defaults (`joint_velocity.json`: output ±0.5, kp 3,
    /// velocity limits ±1).
    fn default() -> Self {
        Self {
            input_max: one(),
            input_min: minus_one(),
            output_max: one(),
            output_min: minus_one(),
            kp: Self::default_kp(),
            velocity_limits: None,
            use_torque_compensation: true,
            interpolation: Interpolation::None,
            ramp_ratio: ramp_ratio(),
        }
    }
}

/// `JOINT_TORQUE` (robosuite's `JointTorqueController`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointTorqueConfig {
    /// Largest input per joint (default 1).
    #[serde(default = "one")]
    pub input_max: PerAxis,
    /// Smallest input per joint (default −1).
    #[serde(default = "minus_one")]
    pub input_min: PerAxis,
    /// Torque at `input_max` (default 0.05 N·m).
    #[serde(default = "JointPositionConfig::default_output_max")]
    pub output_max: PerAxis,
    /// Torque at `input_min` (default −0.05 N·m).
    #[serde(default = "JointPositionConfig::default_output_min")]
    pub output_min: PerAxis,
    /// Box the torque goal is clipped to (default the motors' ctrlrange).
    #[serde(default)]
    pub torque_limits: Option<Bounds>,
    /// Add gravity and Coriolis torques (default true).
    #[serde(default = "yes")]
    pub use_torque_compensation: bool,
    /// Goal interpolation (default none).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Share of the env step over which an interpolated goal ramps (default 0.2).
    #[serde(default = "ramp_ratio")]
    pub ramp_ratio: f64,
}

impl Default for JointTorqueConfig {
    /// robosuite's constructor defaults (`joint_torque.json`: output ±0.1).
    fn default() -> Self {
        Self {
            input_max: one(),
            input_min: minus_one(),
            output_max: JointPositionConfig::default_output_max(),
            output_min: JointPositionConfig::default_output_min(),
            torque_limits: None,
            use_torque_compensation: true,
            interpolation: Interpolation::None,
            ramp_ratio: ramp_ratio(),
        }
    }
}

/// `IK_POSE` (robosuite's `InverseKinematicsController`): a damped least-squares
/// differential IK step per env step, tracked by a joint-position controller.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IkConfig {
    /// Largest position change per env step, in metres (default 0.02).
    #[serde(default = "IkConfig::default_pos_limit")]
    pub ik_pos_limit: f64,
    /// Largest rotation per env step, in radians (default 0.05).
    #[serde(default = "IkConfig::default_ori_limit")]
    pub ik_ori_limit: f64,
    /// Stiffness of the joint-position tracking (default 100).
    #[serde(default = "IkConfig::default_kp")]
    pub kp: PerAxis,
    /// Damping ratio of the tracking (default 1).
    #[serde(default = "one")]
    pub damping_ratio: PerAxis,
    /// Integration time of the IK step, in seconds (default 0.1).
    #[serde(default = "IkConfig::default_integration_dt")]
    pub ik_integration_dt: f64,
    /// Joint-target interpolation (default none).
    #[serde(default)]
    pub interpolation: Interpolation,
    /// Share of the env step over which an interpolated goal ramps (default 0.2).
    #[serde(default = "ramp_ratio")]
    pub ramp_ratio: f64,
}

impl IkConfig {
    fn default_pos_limit() -> f64 {
        0.02
    }

    fn default_ori_limit() -> f64 {
        0.05
    }

    fn default_kp() -> PerAxis {
        PerAxis::Scalar(100.0)
    }

    fn default_integration_dt() -> f64 {
        0.1
    }
}

impl Default for IkConfig {
    /// robosuite's `ik_pose.json` limits and its constructor's gains.
    fn default() -> Self {
        Self {
            ik_pos_limit: Self::default_pos_limit(),
            ik_ori_limit: Self::default_ori_limit(),
            kp: Self::default_kp(),
            damping_ratio: one(),
            ik_integration_dt: Self::default_integration_dt(),
            interpolation: Interpolation::None,
            ramp_ratio: ramp_ratio(),
        }
    }
}

/// The gripper part of an arm config (robosuite's `"gripper": {"type": "GRIP"}`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GripperConfig {
    /// Map each command from `[-1, 1]` onto the actuator's ctrlrange (default true);
    /// false writes the command as the actuator target.
    #[serde(default = "yes")]
    pub use_action_scaling: bool,
}

impl GripperConfig {
    /// The keys a gripper config may hold besides `type`: the fields of this struct.
    pub fn keys() -> &'static [&'static str] {
        serde_introspect::<Self>()
    }
}

impl Default for GripperConfig {
    fn default() -> Self {
        Self {
            use_action_scaling: true,
        }
    }
}

/// One arm's controller configuration, by robosuite's controller `type`.
#[derive(Debug, Clone, PartialEq)]
pub enum ArmControllerConfig {
    /// `OSC_POSE`: end-effector position and orientation.
    OscPose(OscConfig),
    /// `OSC_POSITION`: end-effector position, orientation held.
    OscPosition(OscConfig),
    /// `IK_POSE`: end-effector pose through differential IK.
    IkPose(IkConfig),
    /// `JOINT_POSITION`.
    JointPosition(JointPositionConfig),
    /// `JOINT_VELOCITY`.
    JointVelocity(JointVelocityConfig),
    /// `JOINT_TORQUE`.
    JointTorque(JointTorqueConfig),
}

impl Default for ArmControllerConfig {
    /// robosuite's default: `OSC_POSE` with the values of `default_panda.json`.
    fn default() -> Self {
        Self::OscPose(OscConfig {
            damping_ratio_limits: Bounds::uniform(0.0, 10.0),
            ..OscConfig::default()
        })
    }
}

impl ArmControllerConfig {
    /// robosuite's controller `type`.
    pub fn controller_type(&self) -> &'static str {
        entry_of(self).name
    }

    /// The keys a config of `controller_type` may hold besides `type` and `gripper` (the
    /// fields of its serde struct), and the keys robosuite's own configs carry that are
    /// accepted and ignored; `None` for an unknown type.
    pub fn keys_of(
        controller_type: &str,
    ) -> Option<(&'static [&'static str], &'static [&'static str])> {
        arm_controller(controller_type).map(|e| ((e.keys)(), e.ignored))
    }
}
