//! What robosuite's two-arm tasks share (`environments/manipulation/two_arm_env.py`): the
//! robot set-ups of `env_configuration`, where the robots stand, and which arms are the
//! task's "gripper 0" and "gripper 1". A task takes them with
//! [`RobotSetup::TwoArm`](super::RobotSetup::TwoArm).

use crate::config::EnvConfiguration;
use crate::math::euler2mat;
use crate::models::arenas::ArenaKind;
use crate::models::robots::{ROBOTS, RobotInfo, RobotModel, single_arm_robot_names};
use crate::robots::Robot;
use crate::sim::Sim;
use gym_core::{Error, Result};
use nalgebra::Vector3;
use std::f64::consts::PI;

/// The bimanual robots this crate knows.
fn bimanual_robot_names() -> Vec<&'static str> {
    ROBOTS
        .iter()
        .filter(|r| r.arms.len() == 2)
        .map(|r| r.name)
        .collect()
}

/// robosuite's `TwoArmEnv._check_robot_configuration`: one bimanual robot (configuration
/// `single-robot`, whatever was asked), or two single-arm robots `opposed` (also for
/// `default`) or `parallel`.
///
/// # Errors
/// [`Error::InvalidArgument`] naming `robots` (a wrong count, a single-arm robot alone, a
/// bimanual robot in a pair) or `env_configuration` (`single-robot` with two robots), and
/// listing what is valid.
pub fn check_two_arm_robots(
    task: &str,
    robots: &[RobotInfo],
    configuration: EnvConfiguration,
) -> Result<EnvConfiguration> {
    let bimanual = bimanual_robot_names();
    let listed = |names: &[&str]| {
        if names.is_empty() {
            "none yet".to_owned()
        } else {
            names.join(", ")
        }
    };
    match robots {
        [one] if one.arms.len() == 2 => Ok(EnvConfiguration::SingleRobot),
        [one] => Err(Error::invalid_argument(
            "robots",
            format!(
                "{task} with one robot needs a bimanual robot ({}), got the single-arm {}; \
                 or give two single-arm robots ({})",
                listed(&bimanual),
                one.name,
                single_arm_robot_names().join(", ")
            ),
        )),
        [a, b] => {
            if let Some(r) = [a, b].into_iter().find(|r| r.arms.len() != 1) {
                return Err(Error::invalid_argument(
                    "robots",
                    format!(
                        "{task} with two robots needs single-arm robots ({}), got the bimanual {}",
                        single_arm_robot_names().join(", "),
                        r.name
                    ),
                ));
            }
            match configuration {
                EnvConfiguration::Default | EnvConfiguration::Opposed => {
                    Ok(EnvConfiguration::Opposed)
                }
                EnvConfiguration::Parallel => Ok(EnvConfiguration::Parallel),
                EnvConfiguration::SingleRobot => Err(Error::invalid_argument(
                    "env_configuration",
                    format!(
                        "{task} with two robots takes `opposed` (also `default`) or `parallel`, \
                         got `single-robot`"
                    ),
                )),
            }
        }
        _ => Err(Error::invalid_argument(
            "robots",
            format!(
                "{task} needs one bimanual robot ({}) or two single-arm robots ({}), got {} robots",
                listed(&bimanual),
                single_arm_robot_names().join(", "),
                robots.len()
            ),
        )),
    }
}

/// Where robosuite's two-arm tasks put their robots (their `_load_model`), from each
/// robot's base offset in the arena `kind`:
///
/// * `single-robot`: the robot at its table offset;
/// * `opposed`: the offsets rotated by +π/2 (robot 0) and −π/2 (robot 1) about z, the bases
///   turned the same, then shifted by `∓opposed_shift` along y;
/// * `parallel`: the offsets shifted by `∓parallel_shift` along y.
pub fn place_two_arm_robots(
    robots: &mut [RobotModel],
    configuration: EnvConfiguration,
    kind: ArenaKind,
    opposed_shift: f64,
    parallel_shift: f64,
) {
    let offset = |r: &RobotModel| r.info.base_offsets.for_arena(kind);
    match configuration {
        EnvConfiguration::SingleRobot | EnvConfiguration::Default => {
            if let Some(r) = robots.first_mut() {
                let x = offset(r);
                r.set_base_xpos(x);
            }
        }
        EnvConfiguration::Opposed => {
            let turns = [(PI / 2.0, -opposed_shift), (-PI / 2.0, opposed_shift)];
            for (r, (rotation, shift)) in robots.iter_mut().zip(turns) {
                let x = offset(r);
                let rot = [0.0, 0.0, rotation];
                let p = euler2mat(rot) * Vector3::new(x[0], x[1], x[2]);
                r.set_base_xpos([p[0], p[1] + shift, p[2]]);
                r.set_base_ori(rot);
            }
        }
        EnvConfiguration::Parallel => {
            for (r, shift) in robots.iter_mut().zip([-parallel_shift, parallel_shift]) {
                let x = offset(r);
                r.set_base_xpos([x[0], x[1] + shift, x[2]]);
            }
        }
    }
}

/// One of a two-arm task's grippers: a robot's arm.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArmRef {
    /// The robot.
    pub robot: usize,
    /// The arm of the robot.
    pub arm: usize,
}

impl ArmRef {
    /// The grip-site position (as read without a forward pass).
    pub fn eef_pos(self, sim: &Sim, robots: &[Robot]) -> [f64; 3] {
        robots[self.robot].eef_pos(sim, self.arm)
    }
}

/// robosuite's "gripper 0" and "gripper 1" of a two-arm task: with one bimanual robot its
/// right and its left arm, else the (first) arm of robot 0 and of robot 1.
pub fn task_arms(robots: &[Robot]) -> [ArmRef; 2] {
    match robots {
        [one] => {
            let side = |s: &str| one.arms().iter().position(|a| a.side() == s).unwrap_or(0);
            [
                ArmRef {
                    robot: 0,
                    arm: side("right"),
                },
                ArmRef {
                    robot: 0,
                    arm: side("left"),
                },
            ]
        }
        _ => [ArmRef { robot: 0, arm: 0 }, ArmRef { robot: 1, arm: 0 }],
    }
}
