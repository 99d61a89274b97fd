//! Controllers: robosuite's `OSC_POSE` arm controller ([`OscPose`]) and the `GRIP` gripper
//! controller with the Panda gripper's command integrator ([`GripController`]).

mod config;
mod gripper;
pub mod math;
mod osc;

pub use config::OscConfig;
pub use gripper::GripController;
pub use osc::{OscBinding, OscPose, OscState};
