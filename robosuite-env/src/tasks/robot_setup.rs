//! The robots a task takes and where they stand.

use super::table::place_single_robot;
use super::two_arm::{check_two_arm_robots, place_two_arm_robots};
use crate::config::EnvConfiguration;
use crate::models::arenas::Arena;
use crate::models::robots::{RobotInfo, RobotModel, robot_names};
use gym_core::{Error, Result};

/// The robots a task takes and where they stand ([`TaskSpec::robots`](super::TaskSpec::robots)):
/// robosuite's `_check_robot_configuration` and the robot placement of its `_load_model`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RobotSetup {
    /// One robot, single-arm or bimanual (configuration `default`), at its base offset for
    /// the arena.
    SingleArm,
    /// robosuite's two-arm tasks (`two_arm_env.py`): one bimanual robot (`single-robot`) or
    /// two single-arm robots `opposed` (the default) or `parallel`, placed as
    /// [`place_two_arm_robots`] says with these shifts along y.
    TwoArm {
        /// The `opposed` robots' shift along y (robot 0 by `−shift`, robot 1 by `+shift`).
        opposed_shift: f64,
        /// The `parallel` robots' shift along y (robot 0 by `−shift`, robot 1 by `+shift`).
        parallel_shift: f64,
    },
}

impl RobotSetup {
    /// The number of robots the task takes by default (a Panda each when
    /// [`crate::EnvConfig::robots`] is empty).
    pub fn num_robots(&self) -> usize {
        match self {
            Self::SingleArm => 1,
            Self::TwoArm { .. } => 2,
        }
    }

    /// robosuite's `_check_robot_configuration` for `task`: checks the robots and the
    /// requested `env_configuration` and returns the configuration the task runs with.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `robots` or `env_configuration` and listing what
    /// is valid.
    pub fn check(
        &self,
        task: &str,
        robots: &[RobotInfo],
        configuration: EnvConfiguration,
    ) -> Result<EnvConfiguration> {
        match self {
            Self::SingleArm => check_single_arm_robot(task, robots, configuration),
            Self::TwoArm { .. } => check_two_arm_robots(task, robots, configuration),
        }
    }

    /// Places the robots in `arena` for `configuration` (as [`RobotSetup::check`] returned
    /// it).
    pub fn place(&self, robots: &mut [RobotModel], configuration: EnvConfiguration, arena: &Arena) {
        match *self {
            Self::SingleArm => place_single_robot(robots, arena),
            Self::TwoArm {
                opposed_shift,
                parallel_shift,
            } => place_two_arm_robots(
                robots,
                configuration,
                arena.kind,
                opposed_shift,
                parallel_shift,
            ),
        }
    }
}

/// A single-arm task's check (robosuite's `ManipulationEnv._check_robot_configuration`):
/// one robot, single-arm or bimanual (a bimanual robot's arms both act on the task: its
/// grippers and per-arm observables), and configuration `default`.
fn check_single_arm_robot(
    task: &str,
    robots: &[RobotInfo],
    configuration: EnvConfiguration,
) -> Result<EnvConfiguration> {
    if robots.len() != 1 {
        return Err(Error::invalid_argument(
            "robots",
            format!(
                "{task} needs 1 robot, got {} ({:?}); valid robots: {}",
                robots.len(),
                robots.iter().map(|r| r.name).collect::<Vec<_>>(),
                robot_names().join(", ")
            ),
        ));
    }
    if configuration != EnvConfiguration::Default {
        return Err(Error::invalid_argument(
            "env_configuration",
            format!(
                "{task} is a single-robot task: only `default` is valid, got `{}`",
                configuration.as_str()
            ),
        ));
    }
    Ok(configuration)
}
