//! Robots at run time: a robot composed into a scene ([`RobotModel`](crate::models::robots::RobotModel))
//! bound to the compiled model as a [`Robot`] with its body parts (arms with grippers,
//! torso, head, base, legs), their part controllers, the composite controller that splits
//! the action among them ([`composite`]), reset noise and proprioceptive observables.

pub mod composite;
mod noise;
mod robot;

pub use composite::{ActionSlot, CompositeController, PartRef};
pub use noise::{InitNoise, MAX_NOISE_MAGNITUDE, NoiseKind};
pub use robot::{Arm, BodyPart, Gripper, Robot, RobotState};
