//! Controllers: robosuite's arm part controllers behind one abstraction
//! ([`ArmController`], for an arm of any number of joints) — `OSC_POSE` and
//! `OSC_POSITION` ([`Osc`]), `IK_POSE` ([`InverseKinematics`]), `JOINT_POSITION`
//! ([`JointPosition`]), `JOINT_VELOCITY` ([`JointVelocity`]) and `JOINT_TORQUE`
//! ([`JointTorque`]) — the `GRIP` gripper controller ([`GripController`]), robosuite's
//! `WHOLE_BODY_IK` composite controller and its IK solver ([`whole_body_ik`]), and robosuite's
//! controller configurations ([`config`]). The other body parts' controllers implement the
//! same trait: torso, head and legs run `JOINT_POSITION` (or the types robosuite's part
//! factories allow), the mobile base [`MobileBaseJointVelocity`]. The arm controller types are the entries of
//! one table ([`table::ARM_CONTROLLERS`]), from which their list, config parsing and
//! building derive.
//!
//! Per env step an arm controller takes its slice of the action on the first substep
//! ([`ArmController::set_goal`]) and computes joint torques on every substep
//! ([`ArmController::compute`]) from the state after `mj_step1`; the arm clips them to its
//! motors' ctrlrange. None of them allocates in the substep loop.

pub mod config;
mod gripper;
mod ik;
mod interpolator;
mod joint_position;
mod joint_torque;
mod joint_velocity;
mod mobile_base;
mod opspace;
mod osc;
mod state;
pub mod table;
pub mod whole_body_ik;

pub use config::{ArmControllerConfig, ArmPartConfig, CompositeControllerConfig, ControllerConfig};
pub use gripper::GripController;
pub use ik::InverseKinematics;
pub use interpolator::{InterpolationKind, LinearInterpolator};
pub use joint_position::JointPosition;
pub use joint_torque::JointTorque;
pub use joint_velocity::JointVelocity;
pub use mobile_base::MobileBaseJointVelocity;
pub use osc::Osc;
pub use whole_body_ik::{IkSolver, WholeBodyIk, WholeBodyIkConfig};

use crate::sim::Sim;
use gym_core::{Error, Result};

/// Where an arm controller reads and writes in the model.
#[derive(Debug, Clone, PartialEq)]
pub struct ArmBinding {
    /// The controlled site (the gripper's grip site).
    pub site: usize,
    /// The site whose frame is the input's base frame (`{robot}{arm}_center`).
    pub base_site: usize,
    /// The `qpos` addresses of the arm's joints.
    pub qpos: Vec<usize>,
    /// The dof (`qvel`) addresses of the arm's joints.
    pub dofs: Vec<usize>,
    /// The model's number of dofs.
    pub nv: usize,
    /// The ctrlrange of each arm motor (robosuite's `actuator_range`).
    pub ctrlrange: Vec<[f64; 2]>,
    /// Whether a new goal is read in the base frame of the last torque computation (or the
    /// reset) rather than the current one: robosuite's `WheeledRobot` updates its arm
    /// controllers' origin only when the composite controller runs them, after the goal
    /// is set.
    pub stale_goal_origin: bool,
}

/// The rates a controller runs at.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// The physics timestep in seconds (robosuite's `model_timestep`, 0.002).
    pub timestep: f64,
    /// The env steps per second (robosuite's `control_freq`, the controllers'
    /// `policy_freq`).
    pub control_freq: f64,
}

/// A robosuite arm part controller.
pub trait ArmController: Send + Sync + std::fmt::Debug {
    /// robosuite's controller type, such as `"OSC_POSE"`.
    fn name(&self) -> &'static str;

    /// The length of this controller's slice of the action.
    fn action_dim(&self) -> usize;

    /// The action bounds `(low, high)` (robosuite's `control_limits`).
    fn action_limits(&self) -> (Vec<f64>, Vec<f64>);

    /// What robosuite does at every reset: creates the controller (reading the arm's state:
    /// `sim` must be forwarded, with the arm at its reset posture and the grippers not yet
    /// at theirs) and resets its goal to that state. Gains set by actions return to the
    /// configured ones.
    fn reset(&mut self, sim: &Sim);

    /// Sets the goal from this controller's slice of the action (first substep of an env
    /// step, after `mj_step1`). The slice has [`ArmController::action_dim`] finite values.
    fn set_goal(&mut self, sim: &Sim, action: &[f64]);

    /// Computes the joint torques for the current state into `torques` (one per arm joint,
    /// before the arm clips them to the motors' ctrlrange), without allocating.
    fn compute(&mut self, sim: &Sim, torques: &mut [f64]);

    /// The controller's internal state (goals, gains, interpolators, cached arm state), for
    /// snapshots.
    fn state(&self) -> Vec<f64>;

    /// Restores a state from [`ArmController::state`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a state of the wrong length or with a non-finite
    /// value; the controller is then unchanged.
    fn set_state(&mut self, state: &[f64]) -> Result<()>;

    /// robosuite's `set_goal_update_mode`: with `desired`, the next deltas apply to the
    /// last goal instead of the achieved pose (the `HYBRID_MOBILE_BASE` composite
    /// controller's base mode). Controllers without the notion ignore it.
    fn set_goal_update_mode(&mut self, desired: bool) {
        let _ = desired;
    }

    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn ArmController>;
}

impl Clone for Box<dyn ArmController> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}

/// Builds the controller `config` describes for the arm of `bind`; `path` names the config
/// in errors (such as `controller_configs.body_parts.right`).
///
/// # Errors
/// [`Error::InvalidArgument`] naming the key for a value that does not fit the arm (a list
/// of the wrong length) or is out of range (negative or non-finite gains, limits with low
/// above high, ...).
pub fn build_arm_controller(
    config: &ArmControllerConfig,
    bind: ArmBinding,
    timing: Timing,
    path: &str,
) -> Result<Box<dyn ArmController>> {
    (table::entry_of(config).build)(config, bind, timing, path)
}

/// robosuite's `scale_action`: inputs clipped to `[input_min, input_max]` and mapped
/// affinely onto `[output_min, output_max]`.
#[derive(Debug, Clone, PartialEq)]
pub struct ActionScale {
    input_min: Vec<f64>,
    input_max: Vec<f64>,
    scale: Vec<f64>,
    in_offset: Vec<f64>,
    out_offset: Vec<f64>,
}

impl ActionScale {
    /// The scaling from the resolved limits (`dim` values each); `path` names them in
    /// errors.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for non-finite limits or `input_min >= input_max`.
    pub fn new(
        input: (Vec<f64>, Vec<f64>),
        output: (Vec<f64>, Vec<f64>),
        path: &str,
    ) -> Result<Self> {
        let (input_min, input_max) = input;
        let (output_min, output_max) = output;
        for i in 0..input_min.len() {
            let (lo, hi) = (input_min[i], input_max[i]);
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(Error::invalid_argument(
                    config::join(path, "input_min/input_max"),
                    format!(
                        "need finite input_min < input_max on every axis, got [{lo}, {hi}] on axis {i}"
                    ),
                ));
            }
            let (lo, hi) = (output_min[i], output_max[i]);
            if !(lo.is_finite() && hi.is_finite()) {
                return Err(Error::invalid_argument(
                    config::join(path, "output_min/output_max"),
                    format!("need finite outputs, got [{lo}, {hi}] on axis {i}"),
                ));
            }
        }
        let n = input_min.len();
        Ok(Self {
            scale: (0..n)
                .map(|i| {
                    (output_max[i] - output_min[i]).abs() / (input_max[i] - input_min[i]).abs()
                })
                .collect(),
            in_offset: (0..n)
                .map(|i| (input_max[i] + input_min[i]) / 2.0)
                .collect(),
            out_offset: (0..n)
                .map(|i| (output_max[i] + output_min[i]) / 2.0)
                .collect(),
            input_min,
            input_max,
        })
    }

    /// The number of axes.
    pub fn dim(&self) -> usize {
        self.scale.len()
    }

    /// The input bounds.
    pub fn input_limits(&self) -> (&[f64], &[f64]) {
        (&self.input_min, &self.input_max)
    }

    /// Scales axis `i` of an input.
    pub fn apply(&self, i: usize, a: f64) -> f64 {
        let a = a.clamp(self.input_min[i], self.input_max[i]);
        (a - self.in_offset[i]) * self.scale[i] + self.out_offset[i]
    }
}

/// Checks gains: finite and `>= 0`.
pub(crate) fn check_gains(values: &[f64], key: &str) -> Result<()> {
    match values.iter().find(|v| !v.is_finite() || **v < 0.0) {
        Some(v) => Err(Error::invalid_argument(
            key,
            format!("must be finite and >= 0, got {v}"),
        )),
        None => Ok(()),
    }
}

/// Checks a ramp ratio for linear interpolation: in `(0, 1]`.
pub(crate) fn check_ramp_ratio(ratio: f64, key: &str) -> Result<()> {
    if ratio.is_finite() && ratio > 0.0 && ratio <= 1.0 {
        Ok(())
    } else {
        Err(Error::invalid_argument(
            key,
            format!("must be in (0, 1], got {ratio}"),
        ))
    }
}

/// The error for a controller state of the wrong length or with a non-finite value.
pub(crate) fn check_state(state: &[f64], len: usize, name: &str) -> Result<()> {
    if state.len() != len || state.iter().any(|v| !v.is_finite()) {
        return Err(Error::invalid_argument(
            "controller state",
            format!(
                "expected {len} finite values for {name}, got {}",
                state.len()
            ),
        ));
    }
    Ok(())
}
