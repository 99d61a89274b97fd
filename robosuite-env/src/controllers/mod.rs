//! Controllers: the arm controller abstraction ([`ArmController`]) with robosuite's
//! `OSC_POSE` ([`OscPose`]), and the `GRIP` gripper controller ([`GripController`]).
//!
//! An arm controller turns its slice of the action into joint torques for an arm of any
//! number of joints: the goal is set on the first substep of each env step, the torques are
//! computed on every substep from the state after `mj_step1`; the arm clips them to its
//! motors' ctrlrange.

mod config;
mod gripper;
mod osc;

pub use config::OscConfig;
pub use gripper::GripController;
pub use osc::OscPose;

use crate::sim::Sim;
use gym_core::Result;

/// Where an arm controller reads in the model.
#[derive(Debug, Clone, PartialEq, Eq)]
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
}

/// A robosuite arm part controller.
pub trait ArmController: Send + Sync + std::fmt::Debug {
    /// robosuite's controller type, such as `"OSC_POSE"`.
    fn name(&self) -> &'static str;

    /// The length of this controller's slice of the action.
    fn action_dim(&self) -> usize;

    /// The action bounds `(low, high)` (robosuite's `control_limits`).
    fn action_limits(&self) -> (Vec<f64>, Vec<f64>);

    /// Records what robosuite's controller caches when robosuite creates it during a reset:
    /// the state after the arm's posture is written and before the gripper's is (its
    /// `update(force=True)`). robosuite's first torque computation after the reset reuses
    /// that cache (its `new_update` flag is still down), so the first substep here does too.
    /// `sim` must be forwarded.
    fn capture_reset(&mut self, sim: &Sim);

    /// Re-bases the controller on the current (forwarded) state after a reset: robosuite
    /// creates its controllers anew at every reset.
    fn reset(&mut self, sim: &Sim);

    /// Sets the goal from this controller's slice of the action (first substep of an env
    /// step, after `mj_step1`). The slice has [`ArmController::action_dim`] finite values.
    fn set_goal(&mut self, sim: &Sim, action: &[f64]);

    /// Computes the joint torques for the current state into `torques` (one per arm joint,
    /// before clipping), without allocating.
    fn compute(&mut self, sim: &Sim, torques: &mut [f64]);

    /// The controller's internal state (goals, targets), for snapshots.
    fn state(&self) -> Vec<f64>;

    /// Restores a state from [`ArmController::state`].
    ///
    /// # Errors
    /// [`gym_core::Error::InvalidArgument`] for a state of the wrong length or with a
    /// non-finite value; the controller is then unchanged.
    fn set_state(&mut self, state: &[f64]) -> Result<()>;

    /// A boxed copy.
    fn clone_box(&self) -> Box<dyn ArmController>;
}

impl Clone for Box<dyn ArmController> {
    fn clone(&self) -> Self {
        self.clone_box()
    }
}
