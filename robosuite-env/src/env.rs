//! [`RobosuiteEnv`]: robosuite's environment mechanics (`MujocoEnv` / `RobotEnv` /
//! `ManipulationEnv`) around any [`Task`], implementing [`gym_core::Env`].

use crate::config::EnvConfig;
use crate::models::scene::SceneBuilder;
use crate::observations::{ObsKey, ObsLayout};
use crate::robots::{Robot, RobotState, robot_spec};
use crate::sim::{Sim, check_mujoco_version};
use crate::tasks::{ModelSource, RewardConfig, Task};
use gym_core::{
    BoxSpace, DictSpace, DictValue, EnvRng, Error, Info, Metadata, ResetOptions, Result, Step,
    Transition, entropy_seed, rng_from_seed,
};
use mujoco_rs::wrappers::mj_model::MjModel;
use ndarray::ArrayD;
use std::ops::Range;
use std::path::Path;

/// Everything needed to continue an episode bit-identically: the full simulator state
/// (`mjSTATE_INTEGRATION`), the controllers' goals and integrators, the task's randomised
/// parameters and the episode counter. Made by [`RobosuiteEnv::snapshot`].
#[derive(Debug, Clone, PartialEq)]
pub struct EnvSnapshot {
    physics: Vec<f64>,
    robots: Vec<RobotState>,
    task: Vec<f64>,
    timestep: u64,
    phase: Phase,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    NeedsReset,
    Running,
    Ended,
    Closed,
}

/// A robosuite manipulation environment: robots with their controllers, a task, and the
/// simulator, stepped exactly as robosuite 1.5.2 steps them.
///
/// * **Step**: the action (`[6 OSC, 1 gripper]` per robot) must have the right length and
///   be finite (else [`Error::InvalidAction`], nothing is simulated); values outside
///   `[-1, 1]` are clipped by the controllers, as in robosuite. Each env step runs
///   `substeps` (25 at 20 Hz) × {`mj_step1`; controllers (goal set on the first substep
///   only); `mj_step2`}. Sensors are computed only in the last substep's `mj_step2`, the
///   only one whose sensor values anybody reads (bit-identical trajectories, 4 % fewer
///   instructions; see [`Sim::step2_without_sensors`]).
/// * **Allocation**: [`Env::step_into`](gym_core::Env::step_into) writes the observation and
///   info into the caller's buffers and allocates nothing; `step` allocates the returned
///   observation dict.
/// * **One-substep lag**: observations, reward and success are read right after the last
///   `mj_step2` without another `mj_forward`, as robosuite does, so positions and contacts
///   derived from kinematics (`eef_pos`, `cube_pos`, quaternions, grasp contacts) describe
///   the state one substep (2 ms) before `qpos` / `qvel`.
/// * **Episode end**: reaching `horizon` gives `truncated = true` (unless `ignore_done`);
///   only tasks with early termination set `terminated`. Stepping again gives
///   [`Error::EpisodeEnded`]; stepping before the first reset [`Error::ResetNeeded`].
/// * **Reset** does not recompile: it re-draws the task's model parameters in place (Lift's
///   cube size), `mj_resetData`, writes the robots' initial posture plus noise, places the
///   objects and runs `mj_forward`. RNG order: model parameters, robot noise, placement.
#[derive(Debug)]
pub struct RobosuiteEnv {
    sim: Sim,
    robots: Vec<Robot>,
    task: Box<dyn Task>,
    config: EnvConfig,
    source: ModelSource,
    layout: ObsLayout,
    robot_ranges: Vec<Range<usize>>,
    robot_obs_len: Vec<usize>,
    object_range: Option<Range<usize>>,
    obs_space: DictSpace,
    act_space: BoxSpace<f64>,
    action_splits: Vec<Range<usize>>,
    metadata: Metadata,
    rng: EnvRng,
    rng_seeded: bool,
    buf: Vec<f64>,
    action_buf: Vec<f64>,
    substeps: usize,
    timestep: u64,
    phase: Phase,
}

impl RobosuiteEnv {
    /// Builds `task` on a scene composed from this crate's models.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an invalid configuration (the message lists valid
    /// values); [`Error::Model`] when MuJoCo is not 3.17.0 or the scene does not compile.
    pub fn new(task: Box<dyn Task>, config: EnvConfig) -> Result<Self> {
        let model = compose_scene(task.as_ref(), &config)?.compile()?;
        Self::from_model(task, model, config, ModelSource::Generated)
    }

    /// Builds `task` on a caller-supplied scene MJCF that follows robosuite's names (for
    /// example one exported with robosuite's `env.sim.model.get_xml()`). Object sizes stay
    /// as the file gives them; everything else (robots, controllers, reset noise,
    /// placement, reward) is as in [`RobosuiteEnv::new`].
    ///
    /// # Errors
    /// [`Error::Model`] when the XML does not load or lacks a name the task needs;
    /// [`Error::InvalidArgument`] for an invalid configuration.
    pub fn from_scene_xml(task: Box<dyn Task>, xml: &str, config: EnvConfig) -> Result<Self> {
        config.validate()?;
        check_robot_count(task.as_ref(), &config)?;
        check_mujoco_version()?;
        let model = MjModel::from_xml_string(xml)
            .map_err(|e| Error::Model(format!("cannot load the scene XML: {e:?}")))?;
        Self::from_model(task, model, config, ModelSource::Supplied)
    }

    /// As [`RobosuiteEnv::from_scene_xml`], reading the MJCF from a file (relative asset
    /// paths resolve against its folder).
    ///
    /// # Errors
    /// As [`RobosuiteEnv::from_scene_xml`]; [`Error::Model`] when the file cannot be read.
    pub fn from_scene_file(
        task: Box<dyn Task>,
        path: impl AsRef<Path>,
        config: EnvConfig,
    ) -> Result<Self> {
        config.validate()?;
        check_robot_count(task.as_ref(), &config)?;
        check_mujoco_version()?;
        let path = path.as_ref();
        if !path.is_file() {
            return Err(Error::Model(format!("no scene file at {}", path.display())));
        }
        let model = MjModel::from_xml(path).map_err(|e| {
            Error::Model(format!(
                "cannot load the scene file {}: {e:?}",
                path.display()
            ))
        })?;
        Self::from_model(task, model, config, ModelSource::Supplied)
    }

    fn from_model(
        mut task: Box<dyn Task>,
        model: MjModel,
        config: EnvConfig,
        source: ModelSource,
    ) -> Result<Self> {
        let timestep = model.opt().timestep;
        if !(timestep.is_finite() && timestep > 0.0) {
            return Err(Error::Model(format!(
                "the model's timestep must be positive, got {timestep}"
            )));
        }
        let substeps = config.substeps(timestep);
        if substeps == 0 {
            return Err(Error::invalid_argument(
                "control_freq",
                format!(
                    "{} Hz leaves no {timestep} s substep per env step",
                    config.control_freq
                ),
            ));
        }
        let mut robots = Vec::with_capacity(config.robots.len());
        for (i, name) in config.robots.iter().enumerate() {
            robots.push(Robot::bind(
                &model,
                i,
                task.robot_spec(i, robot_spec(name)?)?,
                config.controller.clone(),
                config.initialization_noise,
            )?);
        }
        task.bind(&model, &robots, source)?;

        let mut layout = ObsLayout::new();
        let robot_keys: Vec<_> = robots
            .iter()
            .map(|r| {
                let mut keys = r.observation_keys();
                keys.extend(task.robot_observation_keys(r.index()));
                keys
            })
            .collect();
        let robot_obs_len: Vec<usize> = robots
            .iter()
            .map(|r| r.observation_keys().iter().map(ObsKey::len).sum())
            .collect();
        let object_keys = if config.use_object_obs {
            Some(task.observation_keys())
        } else {
            None
        };
        // robosuite's order: every sensor key (robots, then objects), then the modality
        // concatenations (robot proprio-states, then object-state).
        let mut robot_ranges = Vec::new();
        let mut deferred = Vec::new();
        for (r, keys) in robots.iter().zip(robot_keys) {
            let range = layout.push_group(None, keys);
            deferred.push((format!("robot{}_proprio-state", r.index()), range.clone()));
            robot_ranges.push(range);
        }
        let object_range = object_keys.map(|keys| layout.push_group(None, keys));
        for (name, range) in deferred {
            layout.add_group(&name, range);
        }
        if let Some(r) = &object_range {
            layout.add_group("object-state", r.clone());
        }
        let obs_space = layout.space()?;

        let mut action_splits = Vec::new();
        let mut dim = 0;
        for r in &robots {
            action_splits.push(dim..dim + r.action_dim());
            dim += r.action_dim();
        }
        let act_space = BoxSpace::<f64>::uniform(-1.0, 1.0, &[dim])?;
        let metadata = Metadata {
            render_modes: Vec::new(),
            render_fps: Some(config.control_freq),
        };
        let (rng, rng_seeded) = match config.seed {
            Some(s) => (rng_from_seed(s), true),
            None => (rng_from_seed(0), false),
        };
        let buf = vec![0.0; layout.len()];
        Ok(Self {
            sim: Sim::new(model)?,
            robots,
            task,
            config,
            source,
            layout,
            robot_ranges,
            robot_obs_len,
            object_range,
            obs_space,
            act_space,
            action_splits,
            metadata,
            rng,
            rng_seeded,
            buf,
            action_buf: Vec::with_capacity(dim),
            substeps,
            timestep: 0,
            phase: Phase::NeedsReset,
        })
    }

    /// The configuration.
    pub fn config(&self) -> &EnvConfig {
        &self.config
    }

    /// The simulator (model and data).
    pub fn sim(&self) -> &Sim {
        &self.sim
    }

    /// The robots.
    pub fn robots(&self) -> &[Robot] {
        &self.robots
    }

    /// The task.
    pub fn task(&self) -> &dyn Task {
        self.task.as_ref()
    }

    /// Whether the model was built by this crate or supplied by the caller.
    pub fn model_source(&self) -> ModelSource {
        self.source
    }

    /// Physics substeps per env step (25 at 20 Hz).
    pub fn substeps(&self) -> usize {
        self.substeps
    }

    /// Env steps taken in the current episode.
    pub fn timestep(&self) -> u64 {
        self.timestep
    }

    /// The action dimension.
    pub fn action_dim(&self) -> usize {
        self.act_space.low().len()
    }

    /// The observation keys, in order.
    pub fn observation_keys(&self) -> Vec<String> {
        self.layout.key_names()
    }

    /// The flattened simulator state `[time, qpos, qvel]` (robosuite's
    /// `sim.get_state().flatten()`; Lift: 1 + 16 + 15 values).
    pub fn get_state(&self) -> Vec<f64> {
        self.sim.state()
    }

    /// Sets the flattened simulator state `[time, qpos, qvel]` and runs `mj_forward`.
    /// Controllers, the gripper integrator and the episode counter are kept.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a wrong length or a non-finite value (nothing is
    /// changed); [`Error::Closed`] after `close`.
    pub fn set_state(&mut self, state: &[f64]) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        self.sim.set_state(state)
    }

    /// A snapshot of the whole episode state (see [`EnvSnapshot`]); unlike
    /// [`RobosuiteEnv::get_state`] it also holds the controller goals, the gripper
    /// integrator, the warm start and the episode counter, so stepping on from a restored
    /// snapshot repeats the original steps bit for bit.
    pub fn snapshot(&self) -> EnvSnapshot {
        EnvSnapshot {
            physics: self.sim.integration_state(),
            robots: self.robots.iter().map(Robot::controller_state).collect(),
            task: self.task.save_state(),
            timestep: self.timestep,
            phase: self.phase,
        }
    }

    /// Restores a snapshot taken from this environment.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a snapshot of another kind of environment;
    /// [`Error::Closed`] after `close`.
    pub fn restore(&mut self, snapshot: &EnvSnapshot) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if snapshot.robots.len() != self.robots.len()
            || snapshot.physics.len() != self.sim.integration_state().len()
        {
            return Err(Error::invalid_argument(
                "snapshot",
                "the snapshot was taken from a different environment",
            ));
        }
        self.task.load_state(&mut self.sim, &snapshot.task)?;
        self.sim.set_integration_state(&snapshot.physics)?;
        for (robot, state) in self.robots.iter_mut().zip(&snapshot.robots) {
            robot.set_controller_state(state);
        }
        self.timestep = snapshot.timestep;
        self.phase = if snapshot.phase == Phase::Closed {
            Phase::NeedsReset
        } else {
            snapshot.phase
        };
        Ok(())
    }

    /// The observation of the current simulator state.
    pub fn observation(&mut self) -> DictValue {
        self.fill_observation();
        self.layout.to_dict(&self.buf)
    }

    /// The reward of the current simulator state.
    pub fn reward(&self) -> f64 {
        self.task
            .reward(&self.sim, &self.robots, &self.reward_config())
    }

    /// Whether the task is solved in the current simulator state.
    pub fn check_success(&self) -> bool {
        self.task.check_success(&self.sim, &self.robots)
    }

    fn reward_config(&self) -> RewardConfig {
        RewardConfig {
            reward_scale: self.config.reward_scale,
            reward_shaping: self.config.reward_shaping,
            horizon: self.config.horizon,
        }
    }

    fn fill_observation(&mut self) {
        for ((robot, range), own) in self
            .robots
            .iter()
            .zip(&self.robot_ranges)
            .zip(&self.robot_obs_len)
        {
            let out = &mut self.buf[range.clone()];
            robot.write_observations(&self.sim, &mut out[..*own]);
            if out.len() > *own {
                self.task.write_robot_observations(
                    &self.sim,
                    &self.robots,
                    robot.index(),
                    &mut out[*own..],
                );
            }
        }
        if let Some(range) = &self.object_range {
            self.task
                .write_observations(&self.sim, &self.robots, &mut self.buf[range.clone()]);
        }
    }

    fn check_action(&self, action: &ArrayD<f64>) -> Result<()> {
        let dim = self.action_dim();
        if action.len() != dim || action.ndim() != 1 {
            return Err(Error::InvalidAction(format!(
                "expected an action of shape [{dim}] (per robot: 6 OSC deltas, 1 gripper), got shape {:?}",
                action.shape()
            )));
        }
        if let Some((i, v)) = action.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(Error::InvalidAction(format!(
                "action[{i}] is not finite ({v})"
            )));
        }
        Ok(())
    }

    /// One env step without its observation: checks the order and the action, simulates,
    /// then rewards, task updates and end flags. Returns the transition and `success`.
    fn advance(&mut self, action: &ArrayD<f64>) -> Result<(Transition, bool)> {
        match self.phase {
            Phase::Closed => return Err(Error::Closed),
            Phase::NeedsReset => return Err(Error::ResetNeeded),
            Phase::Ended => return Err(Error::EpisodeEnded),
            Phase::Running => {}
        }
        self.check_action(action)?;
        let mut flat = std::mem::take(&mut self.action_buf);
        flat.clear();
        flat.extend(action.iter().copied());
        self.timestep += 1;
        self.simulate(&flat);
        self.action_buf = flat;
        let reward = self.reward();
        let reward_config = self.reward_config();
        self.task
            .after_reward(&mut self.sim, &self.robots, &reward_config);
        let success = self.check_success();
        let terminated = self.task.check_terminated(&self.sim, &self.robots);
        let truncated = self.timestep >= self.config.horizon && !self.config.ignore_done;
        if terminated || truncated {
            self.phase = Phase::Ended;
        }
        let transition = Transition {
            reward,
            terminated,
            truncated,
        };
        Ok((transition, success))
    }

    /// Runs one env step's physics for a checked action.
    fn simulate(&mut self, action: &[f64]) {
        for sub in 0..self.substeps {
            self.sim.step1();
            for (robot, split) in self.robots.iter_mut().zip(&self.action_splits) {
                if sub == 0 {
                    robot.set_goal(&self.sim, &action[split.clone()]);
                }
                robot.apply_control(&mut self.sim);
            }
            if sub == 0 {
                self.task.on_policy_step(&self.sim, &self.robots);
            }
            // Sensors are read only after an env step (and at its first substep, before
            // `mj_step2`), so only the last substep computes them.
            if sub + 1 == self.substeps {
                self.sim.step2();
            } else {
                self.sim.step2_without_sensors();
            }
        }
    }
}

/// Composes the scene of `task` with the robots of `config` (arena, robots with mounts and
/// grippers, objects), uncompiled.
///
/// # Errors
/// [`Error::InvalidArgument`] for an invalid configuration; [`Error::Model`] when a part
/// does not attach.
pub fn compose_scene(task: &dyn Task, config: &EnvConfig) -> Result<SceneBuilder> {
    config.validate()?;
    check_robot_count(task, config)?;
    let mut scene = SceneBuilder::with_arena(&task.arena_xml())?;
    for (i, name) in config.robots.iter().enumerate() {
        let (pos, quat) = task.robot_base_pose(i);
        scene.add_robot(i, &task.robot_spec(i, robot_spec(name)?)?, pos, quat)?;
    }
    task.build_objects(&mut scene)?;
    Ok(scene)
}

fn check_robot_count(task: &dyn Task, config: &EnvConfig) -> Result<()> {
    let need = task.num_robots();
    if config.robots.len() != need {
        return Err(Error::invalid_argument(
            "robots",
            format!(
                "{} needs {need} robot(s), got {} ({:?})",
                task.name(),
                config.robots.len(),
                config.robots
            ),
        ));
    }
    Ok(())
}

impl gym_core::Env for RobosuiteEnv {
    type Obs = DictValue;
    type Act = ArrayD<f64>;
    type ObsSpace = DictSpace;
    type ActSpace = BoxSpace<f64>;

    fn observation_space(&self) -> &DictSpace {
        &self.obs_space
    }

    fn action_space(&self) -> &BoxSpace<f64> {
        &self.act_space
    }

    /// Starts an episode. `seed` re-seeds the environment RNG; without one the stream
    /// continues (seeded from `config.seed`, or from entropy at the very first reset).
    /// No reset options are defined.
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if let Some(key) = options.and_then(|o| o.keys().next()) {
            return Err(Error::UnknownKey {
                key: key.to_owned(),
                available: Vec::new(),
            });
        }
        match seed {
            Some(s) => {
                self.rng = rng_from_seed(s);
                self.rng_seeded = true;
            }
            None if !self.rng_seeded => {
                self.rng = rng_from_seed(entropy_seed());
                self.rng_seeded = true;
            }
            None => {}
        }
        // A failure below leaves the episode unusable until a successful reset.
        self.phase = Phase::NeedsReset;
        self.task.randomize_model(&mut self.sim, &mut self.rng)?;
        self.sim.reset_data();
        for robot in &mut self.robots {
            robot.reset(&mut self.sim, &mut self.rng);
        }
        self.task.place_objects(&mut self.sim, &mut self.rng)?;
        self.sim.forward();
        for robot in &mut self.robots {
            robot.rebase(&self.sim);
        }
        self.timestep = 0;
        self.phase = Phase::Running;
        let info = Info::new().with("success", self.check_success());
        Ok((self.observation(), info))
    }

    fn step(&mut self, action: &ArrayD<f64>) -> Result<Step<DictValue>> {
        let (transition, success) = self.advance(action)?;
        Ok(Step {
            observation: self.observation(),
            reward: transition.reward,
            terminated: transition.terminated,
            truncated: transition.truncated,
            info: Info::new().with("success", success),
        })
    }

    /// [`Env::step`] writing into `observation` and `info` in place when they hold the
    /// previous step's keys, shapes and dtypes: a loop of steps does not allocate.
    fn step_into(
        &mut self,
        action: &ArrayD<f64>,
        observation: &mut DictValue,
        info: &mut Info,
    ) -> Result<Transition> {
        let (transition, success) = self.advance(action)?;
        self.fill_observation();
        self.layout.write_dict(&self.buf, observation);
        if info.len() != 1 || info.get("success").is_none() {
            info.clear();
        }
        info.set("success", success);
        Ok(transition)
    }

    fn metadata(&self) -> &Metadata {
        &self.metadata
    }

    fn close(&mut self) {
        self.phase = Phase::Closed;
    }

    fn rng(&self) -> Option<&EnvRng> {
        Some(&self.rng)
    }

    gym_core::base_env!();
}
