//! Robots at run time: a robot composed into a scene ([`RobotModel`](crate::models::robots::RobotModel))
//! bound to the compiled model as a [`Robot`] with its arms, controllers, grippers, reset
//! noise and proprioceptive observables.

mod noise;
mod robot;

pub use noise::{InitNoise, MAX_NOISE_MAGNITUDE, NoiseKind};
pub use robot::{Arm, Gripper, Robot, RobotState};
