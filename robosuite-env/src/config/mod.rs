//! Environment configuration (robosuite's constructor arguments) with validation.

pub use crate::cameras::{CameraConfig, ImageConvention, Segmentation};
use crate::controllers::ControllerConfig;
use crate::models::grippers::gripper_info;
use crate::models::robots::{GripperChoice, robot_info};
use crate::robots::InitNoise;
use crate::tasks::TaskOptions;
use gym_core::{Error, Result};

mod kwargs;
pub use kwargs::kwarg_names;

/// robosuite's environment arguments that this crate supports.
///
/// Build it with `EnvConfig::default()` and the `with_*` methods; it is validated when an
/// environment is made.
///
/// ```
/// use robosuite_env::EnvConfig;
/// let config = EnvConfig::default().with_horizon(200).with_reward_shaping(true).with_seed(7);
/// assert!(config.validate().is_ok());
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct EnvConfig {
    /// Robot names, one per robot the task needs (robosuite's `robots`); empty (the
    /// default): a Panda for each robot the task needs.
    pub robots: Vec<String>,
    /// Grippers, one choice per robot applied to each of its arms (robosuite's
    /// `gripper_types`), or one for every robot; empty: every robot's default gripper.
    pub gripper_types: Vec<GripperChoice>,
    /// robosuite's `controller_configs`: empty for each robot's default
    /// (`default_{robot}.json`: `OSC_POSE`), one config for every robot, or one per robot.
    pub controller_configs: Vec<ControllerConfig>,
    /// Episode length in env steps (default 1000); reaching it truncates the episode.
    pub horizon: u64,
    /// Control frequency in Hz (default 20, i.e. 25 physics substeps of 2 ms).
    pub control_freq: f64,
    /// Scale of the maximal reward, `None` for unnormalised rewards (default `Some(1.0)`).
    pub reward_scale: Option<f64>,
    /// Dense staged rewards; `None` takes the task's default (robosuite: false, Wipe: true).
    pub reward_shaping: Option<bool>,
    /// Never end the episode at the horizon (default false).
    pub ignore_done: bool,
    /// Noise added to the arm's initial joint positions on each reset (default Gaussian 0.02).
    pub initialization_noise: InitNoise,
    /// Include the object observations (default true).
    pub use_object_obs: bool,
    /// Seed of the environment RNG; `None` seeds from entropy at the first reset.
    pub seed: Option<u64>,
    /// robosuite's camera arguments (`use_camera_obs`, `has_offscreen_renderer`,
    /// `camera_names`, ...) and the render mode's camera; see [`CameraConfig`].
    pub cameras: CameraConfig,
    /// How the robots are set up (robosuite's `env_configuration`; default `Default`).
    pub env_configuration: EnvConfiguration,
    /// robosuite's `lite_physics` (default true): each substep is `mj_step1`, control,
    /// `mj_step2`; `false` runs `mj_forward`, control, `mj_step` as robosuite ≤ 1.4.1 did
    /// (for datasets recorded then; about twice the physics cost).
    pub lite_physics: bool,
    /// The task's own constructor arguments by robosuite's names (Lift's
    /// `table_full_size`, Door's `use_latch`, Wipe's `task_config`, PickPlace's
    /// `single_object_mode`, ...), checked against the task when the env is made; see
    /// [`TaskSpec::options`](crate::tasks::TaskSpec::options).
    pub task_options: TaskOptions,
    /// robosuite's `base_types`: per robot its base (mount) by robosuite's name
    /// (`RethinkMount`, `RethinkMinimalMount`, `NullMount`), `None` for the robot's default;
    /// empty (the default) or one entry for every robot.
    pub base_types: Vec<Option<String>>,
}

/// robosuite's `env_configuration`: how a two-arm task sets up its robots.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum EnvConfiguration {
    /// `"default"`: single-arm tasks' only setting; two single-arm robots stand `opposed`.
    #[default]
    Default,
    /// `"opposed"` (or robosuite's older `"single-arm-opposed"`): two single-arm robots
    /// facing each other across the table.
    Opposed,
    /// `"parallel"` (or `"single-arm-parallel"`): two single-arm robots side by side.
    Parallel,
    /// `"single-robot"`: one bimanual robot (robosuite sets it whenever one robot is given
    /// to a two-arm task).
    SingleRobot,
}

impl EnvConfiguration {
    /// The names [`EnvConfiguration::parse`] accepts.
    pub const NAMES: &'static [&'static str] = &[
        "default",
        "opposed",
        "parallel",
        "single-robot",
        "bimanual",
        "single-arm-opposed",
        "single-arm-parallel",
    ];

    /// robosuite's name.
    pub fn as_str(self) -> &'static str {
        match self {
            Self::Default => "default",
            Self::Opposed => "opposed",
            Self::Parallel => "parallel",
            Self::SingleRobot => "single-robot",
        }
    }

    /// The configuration robosuite names `name` (its older names included).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] (argument `env_configuration`) listing the valid names.
    pub fn parse(name: &str) -> Result<Self> {
        match name {
            "default" => Ok(Self::Default),
            "opposed" | "single-arm-opposed" => Ok(Self::Opposed),
            "parallel" | "single-arm-parallel" => Ok(Self::Parallel),
            // robosuite's demos pass "bimanual" with one bimanual robot (robosuite then sets
            // `single-robot` whatever the string; with two robots it is an error there too).
            "single-robot" | "bimanual" => Ok(Self::SingleRobot),
            other => Err(Error::invalid_argument(
                "env_configuration",
                format!(
                    "unknown configuration `{other}`; valid: {}",
                    Self::NAMES.join(", ")
                ),
            )),
        }
    }
}

impl Default for EnvConfig {
    fn default() -> Self {
        Self {
            robots: Vec::new(),
            gripper_types: Vec::new(),
            controller_configs: Vec::new(),
            horizon: 1000,
            control_freq: 20.0,
            reward_scale: Some(1.0),
            reward_shaping: None,
            ignore_done: false,
            initialization_noise: InitNoise::default(),
            use_object_obs: true,
            seed: None,
            env_configuration: EnvConfiguration::Default,
            cameras: CameraConfig::default(),
            lite_physics: true,
            task_options: TaskOptions::new(),
            base_types: Vec::new(),
        }
    }
}

/// The most physics substeps one env step may run: 5 s of simulated time per env step at
/// robosuite's 2 ms timestep (`control_freq` ≥ 0.2 Hz), about a second of computing for the
/// costliest task. A configuration or model that asks for more is rejected when the env is
/// made, so that no single step runs for hours.
pub const MAX_SUBSTEPS: usize = 2_500;

/// Checks that `control_freq` gives between 1 and [`MAX_SUBSTEPS`] substeps of `timestep`.
///
/// # Errors
/// [`Error::InvalidArgument`] naming `control_freq` and the valid range.
pub fn check_substeps(control_freq: f64, timestep: f64) -> Result<()> {
    let ok = control_freq.is_finite() && control_freq > 0.0 && {
        let n = (1.0 / control_freq) / timestep;
        (1.0..(MAX_SUBSTEPS + 1) as f64).contains(&n)
    };
    if ok {
        return Ok(());
    }
    let (low, high) = (1.0 / (MAX_SUBSTEPS as f64 * timestep), 1.0 / timestep);
    Err(Error::invalid_argument(
        "control_freq",
        format!(
            "must be in [{low}, {high}] Hz so that an env step holds between 1 and \
             {MAX_SUBSTEPS} substeps of {timestep} s, got {control_freq}"
        ),
    ))
}

impl EnvConfig {
    /// Sets the robots.
    #[must_use]
    pub fn with_robots<S: Into<String>>(mut self, robots: impl IntoIterator<Item = S>) -> Self {
        self.robots = robots.into_iter().map(Into::into).collect();
        self
    }

    /// Sets the grippers, one choice per robot.
    #[must_use]
    pub fn with_gripper_types(mut self, grippers: impl IntoIterator<Item = GripperChoice>) -> Self {
        self.gripper_types = grippers.into_iter().collect();
        self
    }

    /// The gripper choice for arm `arm` of robot `robot` (one choice applies to every
    /// robot, as robosuite's `_input2list` broadcasts it).
    pub fn gripper_choice(&self, robot: usize, _arm: usize) -> GripperChoice {
        match self.gripper_types.as_slice() {
            [one] => one.clone(),
            many => many.get(robot).cloned().unwrap_or_default(),
        }
    }

    /// Robot `robot`'s base (see [`EnvConfig::base_types`]): `None` for its default.
    pub fn base_type(&self, robot: usize) -> Option<&str> {
        match self.base_types.as_slice() {
            [one] => one.as_deref(),
            many => many.get(robot).and_then(Option::as_deref),
        }
    }

    /// Sets robosuite's `base_types` (see [`EnvConfig::base_types`]).
    #[must_use]
    pub fn with_base_types<S: Into<String>>(
        mut self,
        bases: impl IntoIterator<Item = Option<S>>,
    ) -> Self {
        self.base_types = bases.into_iter().map(|b| b.map(Into::into)).collect();
        self
    }

    /// Sets one controller configuration for every robot (a composite config, or a part
    /// config robosuite puts on every arm).
    #[must_use]
    pub fn with_controller(mut self, controller: impl Into<ControllerConfig>) -> Self {
        self.controller_configs = vec![controller.into()];
        self
    }

    /// Sets robosuite's `controller_configs`: one for every robot, or one per robot.
    #[must_use]
    pub fn with_controller_configs(
        mut self,
        configs: impl IntoIterator<Item = ControllerConfig>,
    ) -> Self {
        self.controller_configs = configs.into_iter().collect();
        self
    }

    /// The controller configuration of robot `robot` (`None`: its default) and the name
    /// errors give it.
    pub fn controller_config(&self, robot: usize) -> (Option<&ControllerConfig>, String) {
        match self.controller_configs.len() {
            0 => (None, "controller_configs".to_owned()),
            1 => (
                self.controller_configs.first(),
                "controller_configs".to_owned(),
            ),
            _ => (
                self.controller_configs.get(robot),
                format!("controller_configs[{robot}]"),
            ),
        }
    }

    /// Sets robosuite's `env_configuration`.
    #[must_use]
    pub fn with_env_configuration(mut self, configuration: EnvConfiguration) -> Self {
        self.env_configuration = configuration;
        self
    }

    /// This configuration with its robots resolved for a task that needs `count` robots:
    /// unchanged when robots are given, else a Panda for each.
    pub fn with_default_robots(mut self, count: usize) -> Self {
        if self.robots.is_empty() {
            self.robots = vec!["Panda".to_owned(); count];
        }
        self
    }

    /// Sets the horizon.
    #[must_use]
    pub fn with_horizon(mut self, horizon: u64) -> Self {
        self.horizon = horizon;
        self
    }

    /// Sets the control frequency (Hz).
    #[must_use]
    pub fn with_control_freq(mut self, hz: f64) -> Self {
        self.control_freq = hz;
        self
    }

    /// Sets the reward scale (`None`: unnormalised).
    #[must_use]
    pub fn with_reward_scale(mut self, scale: Option<f64>) -> Self {
        self.reward_scale = scale;
        self
    }

    /// Turns reward shaping on or off.
    #[must_use]
    pub fn with_reward_shaping(mut self, on: bool) -> Self {
        self.reward_shaping = Some(on);
        self
    }

    /// Sets `ignore_done`.
    #[must_use]
    pub fn with_ignore_done(mut self, on: bool) -> Self {
        self.ignore_done = on;
        self
    }

    /// Sets one of the task's constructor arguments by robosuite's name (see
    /// [`EnvConfig::task_options`]).
    ///
    /// ```
    /// use robosuite_env::EnvConfig;
    /// let config = EnvConfig::default().with_task_option("use_latch", false);
    /// let mut env = robosuite_env::make_with("Door", config)?;
    /// assert_eq!(env.task_options()["use_latch"], false);
    /// # Ok::<(), gym_core::Error>(())
    /// ```
    #[must_use]
    pub fn with_task_option(mut self, name: &str, value: impl Into<serde_json::Value>) -> Self {
        self.task_options.insert(name.to_owned(), value.into());
        self
    }

    /// Sets robosuite's `lite_physics` (see [`EnvConfig::lite_physics`]).
    #[must_use]
    pub fn with_lite_physics(mut self, on: bool) -> Self {
        self.lite_physics = on;
        self
    }

    /// Sets the initialisation noise.
    #[must_use]
    pub fn with_initialization_noise(mut self, noise: InitNoise) -> Self {
        self.initialization_noise = noise;
        self
    }

    /// Turns the object observations on or off.
    #[must_use]
    pub fn with_object_obs(mut self, on: bool) -> Self {
        self.use_object_obs = on;
        self
    }

    /// Seeds the environment RNG.
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = Some(seed);
        self
    }

    /// Sets the camera arguments.
    #[must_use]
    pub fn with_cameras(mut self, cameras: CameraConfig) -> Self {
        self.cameras = cameras;
        self
    }

    /// The number of physics substeps per env step: `int((1 / control_freq) / timestep)`, as
    /// robosuite truncates (at most [`MAX_SUBSTEPS`] in a valid configuration).
    pub fn substeps(&self, timestep: f64) -> usize {
        ((1.0 / self.control_freq) / timestep) as usize
    }

    /// Checks every value.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming the argument and what would be valid.
    pub fn validate(&self) -> Result<()> {
        for r in &self.robots {
            robot_info(r)?;
        }
        if !self.robots.is_empty()
            && self.gripper_types.len() > 1
            && self.gripper_types.len() != self.robots.len()
        {
            return Err(Error::invalid_argument(
                "gripper_types",
                format!(
                    "give one gripper choice for every robot or one per robot ({}), got {}",
                    self.robots.len(),
                    self.gripper_types.len()
                ),
            ));
        }
        for g in &self.gripper_types {
            if let GripperChoice::Named(name) = g {
                gripper_info(name)?;
            }
        }
        if self.base_types.len() > 1 && self.base_types.len() != self.robots.len() {
            return Err(Error::invalid_argument(
                "base_types",
                format!(
                    "give one base for every robot or one per robot ({}), got {}",
                    self.robots.len(),
                    self.base_types.len()
                ),
            ));
        }
        for name in self.base_types.iter().flatten() {
            crate::models::bases::mount_info(name)?;
        }
        if self.horizon == 0 {
            return Err(Error::invalid_argument("horizon", "must be at least 1"));
        }
        check_substeps(self.control_freq, 0.002)?;
        if let Some(s) = self.reward_scale
            && !s.is_finite()
        {
            return Err(Error::invalid_argument(
                "reward_scale",
                format!("must be finite or None, got {s}"),
            ));
        }
        let n = self.controller_configs.len();
        if n > 1 && !self.robots.is_empty() && n != self.robots.len() {
            return Err(Error::invalid_argument(
                "controller_configs",
                format!(
                    "give one config for every robot or one per robot ({}), got {n}",
                    self.robots.len()
                ),
            ));
        }
        self.initialization_noise.validate()?;
        self.cameras.validate()
    }
}
