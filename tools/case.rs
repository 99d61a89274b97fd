//! What the measuring programs measure: a task, optionally on another robot or with another
//! arm controller.

use gym_core::Result;
use robosuite_env::assets::Assets;
use robosuite_env::controllers::ControllerConfig;
use robosuite_env::controllers::config::load_part_controller_config;
use robosuite_env::{EnvConfig, RobosuiteEnv};

/// One env to measure.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Case {
    /// The task, such as `"Lift"`.
    pub task: String,
    /// The robot (`None`: the Panda).
    pub robot: Option<String>,
    /// The arm controller type, configured by robosuite's part config file for it (`None`:
    /// the robot's default composite config).
    pub controller: Option<String>,
}

impl Case {
    /// The task on its default robot and controller.
    pub fn task(task: &str) -> Self {
        Self {
            task: task.to_owned(),
            robot: None,
            controller: None,
        }
    }

    /// The task, robot and controller as tables name them.
    pub fn label(&self) -> String {
        let mut label = self.task.clone();
        for part in [&self.robot, &self.controller].into_iter().flatten() {
            label.push_str(" / ");
            label.push_str(part);
        }
        label
    }

    /// A fresh env of this case.
    ///
    /// # Errors
    /// An unknown task, robot or controller, or model files that cannot be read.
    pub fn make(&self) -> Result<RobosuiteEnv> {
        let mut config = EnvConfig::default();
        if let Some(robot) = &self.robot {
            config = config.with_robots([robot.as_str()]);
        }
        if let Some(controller) = &self.controller {
            let part = load_part_controller_config(&Assets::locate()?, controller)?;
            config = config.with_controller(ControllerConfig::from_value(&part, "controller")?);
        }
        robosuite_env::make_with(&self.task, config)
    }
}
