//! [`RobosuiteEnv`]: robosuite's environment mechanics (`MujocoEnv` / `RobotEnv` /
//! `ManipulationEnv`) around any task, implementing [`gym_core::Env`].

use crate::assets::Assets;
use crate::cameras::rig::CameraRig;
use crate::config::EnvConfig;
use crate::controllers::config::robot_default;
use crate::controllers::{CompositeControllerConfig, Timing};
use crate::models::robots::{RobotModel, robot_info};
use crate::models::scene::{Compiled, Scene, compile_shared_with_source};
use crate::observables::{ObsLayout, ObsSpec, total_len};
use crate::robots::{Robot, RobotState};
use crate::sim::Sim;
use crate::tasks::{RewardConfig, Task, TaskOptions, TaskScene, TaskSpec, configured};
use gym_core::{
    BoxSpace, DictSpace, DictValue, EnvRng, Error, Frame, Info, Metadata, RenderMode, ResetOptions,
    Result, Step, Transition, entropy_seed, rng_from_seed,
};
use mujoco_rs::wrappers::mj_model::MjModel;
use ndarray::ArrayD;
use std::ops::Range;
use std::path::Path;
use std::sync::Arc;

/// Where the compiled model came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelSource {
    /// Composed by this crate from robosuite's model files.
    Composed,
    /// A scene MJCF supplied by the caller (for instance saved by robosuite); object sizes
    /// stay as the file says (robosuite's soft reset).
    Supplied,
}

/// Everything needed to continue an episode bit-identically: the full simulator state
/// (`mjSTATE_INTEGRATION`), the controllers' goals and gripper commands, the task's
/// randomised parameters and observation cache, the last observation and the episode
/// counter. Made by [`RobosuiteEnv::snapshot`].
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct EnvSnapshot {
    physics: Vec<f64>,
    robots: Vec<RobotState>,
    task: Vec<f64>,
    observation: Vec<f64>,
    timestep: u64,
    phase: Phase,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
enum Phase {
    NeedsReset,
    Running,
    Ended,
    Closed,
}

/// A robosuite manipulation environment: robots with their controllers, a task, and the
/// simulator, stepped exactly as robosuite 1.5.2 steps them.
///
/// * **Scene**: composed from robosuite's own model files as robosuite composes it (see
///   [`models`](crate::models)), so names, element order and counts are robosuite's.
/// * **Step**: the action (per robot: each arm's controller input, then each arm's gripper
///   input) must have the right length and be finite (else [`Error::InvalidAction`],
///   nothing is simulated); values outside `[-1, 1]` are clipped by the controllers, as in
///   robosuite. Each env step runs `substeps` (25 at 20 Hz) × {`mj_step1`; controllers
///   (goal set on the first substep only); `mj_step2`}. Sensors are computed only in the
///   last substep's `mj_step2`, the only one whose sensor values anybody reads
///   (bit-identical trajectories; see [`Sim::step2_without_sensors`]).
/// * **Allocation**: [`Env::step_into`](gym_core::Env::step_into) writes the observation and
///   info into the caller's buffers and allocates nothing; `step` allocates the returned
///   observation dict.
/// * **One-substep lag**: observations, reward and success are read right after the last
///   `mj_step2` without another `mj_forward`, as robosuite does, so positions and contacts
///   derived from kinematics (`eef_pos`, object poses, grasp contacts) describe the state one
///   substep (2 ms) before `qpos` / `qvel`.
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
    task_range: Range<usize>,
    obs_space: DictSpace,
    act_space: BoxSpace<f64>,
    action_splits: Vec<Range<usize>>,
    metadata: Metadata,
    rng: EnvRng,
    rng_seeded: bool,
    buf: Vec<f64>,
    action_buf: Vec<f64>,
    substeps: usize,
    /// The next substep of an env step taken one substep at a time
    /// ([`RobosuiteEnv::begin_step`]); `None` when no such step is under way.
    split_step: Option<usize>,
    timestep: u64,
    phase: Phase,
    cameras: Option<CameraRig>,
    /// The MJCF text the model was compiled from (shared by envs of one scene); for a model
    /// without texture images, the text with them.
    source_xml: Arc<str>,
    /// Whether the model holds the scene's texture images (see
    /// [`RobosuiteEnv::textures_loaded`]).
    textures_loaded: bool,
    /// The task's constructor arguments it was built with.
    task_options: TaskOptions,
    /// The task's objects (robosuite's `env.model.mujoco_objects`).
    objects: Vec<MujocoObjectInfo>,
    /// Every observable of the robots and the task, in order (the observation buffer's
    /// layout); those `use_object_obs` leaves out do not exist (see
    /// [`RobosuiteEnv::observable_exists`]).
    obs_specs: Vec<ObsSpec>,
    /// Per observable of `obs_specs`: enabled, active (robosuite's two flags; both false
    /// for one that does not exist).
    obs_flags: Vec<(bool, bool)>,
    #[cfg(feature = "render")]
    viewer_renderer: Option<crate::render::OffscreenRenderer>,
    /// Whether [`RobosuiteEnv::visualize`] was called: resets then hide the sites again.
    visualized: bool,
    /// The configured task and its part of the scene, to bind the task again when the
    /// model is replaced in place ([`RobosuiteEnv::reset_from_xml_string`]).
    rebind: Arc<Rebind>,
}

/// A configured task with the scene part it was built with.
#[derive(Debug)]
struct Rebind {
    spec: Box<dyn TaskSpec>,
    scene: TaskScene,
}

/// How [`RobosuiteEnv::reset_from_xml_string`] loaded a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneLoad {
    /// Into the env's own model, in place: the new scene differs from the current one at
    /// most in the sizes of generated boxes (robosuite's per-episode cube sizes), so the
    /// cached compile of that scene was copied into the model and the boxes resized. The
    /// model and data stay where they were (views of them stay valid).
    InPlace,
    /// Compiled (or copied from a cached compile) into a new model and data.
    Compiled,
}

/// One observable as robosuite's observables API describes it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObservableInfo {
    /// Key, shape, dtype and modality.
    pub spec: ObsSpec,
    /// Whether it is computed (robosuite's `enabled`).
    pub enabled: bool,
    /// Whether it is returned in observations (robosuite's `active`).
    pub active: bool,
}

/// robosuite's observable attributes that [`RobosuiteEnv::modify_observable`] sets.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ObservableFlag {
    /// `enabled`: computed at all.
    Enabled,
    /// `active`: returned in observations.
    Active,
}

/// One of the task's objects as robosuite's `MujocoObject` describes it: names in the
/// compiled model and the extent placement uses.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MujocoObjectInfo {
    /// The object's name (`"cube"`).
    pub name: String,
    /// The prefix of every element name (`"cube_"`).
    pub naming_prefix: String,
    /// The root body's name (`"cube_main"`).
    pub root_body: String,
    /// The joints' names (`["cube_joint0"]`; none for a fixed object).
    pub joints: Vec<String>,
    /// The contact geoms' names.
    pub contact_geoms: Vec<String>,
    /// The visual geoms' names.
    pub visual_geoms: Vec<String>,
    /// The sites' names.
    pub sites: Vec<String>,
    /// From the root body to the object's bottom (robosuite's `bottom_offset`).
    pub bottom_offset: [f64; 3],
    /// From the root body to the object's top (robosuite's `top_offset`).
    pub top_offset: [f64; 3],
    /// The largest horizontal distance from the root body to the object's outline.
    pub horizontal_radius: f64,
    /// For generated boxes and cylinders, whose size resets may draw anew: the shape and
    /// the geom whose size gives the extent.
    #[serde(skip)]
    primitive: Option<(crate::models::objects::Shape, usize)>,
}

impl MujocoObjectInfo {
    fn of(o: &crate::models::objects::ObjectModel, model: &MjModel) -> Self {
        let primitive = o.shape.and_then(|shape| {
            let geom = o.contact_geoms().into_iter().next()?;
            Some((shape, crate::sim::geom_id(model, &geom).ok()?))
        });
        Self {
            name: o.name.clone(),
            naming_prefix: format!("{}_", o.name),
            root_body: o.root_body(),
            joints: o.joints(),
            contact_geoms: o.contact_geoms(),
            visual_geoms: o.visual_geoms(),
            sites: o.sites(),
            bottom_offset: o.bottom_offset,
            top_offset: o.top_offset,
            horizontal_radius: o.horizontal_radius,
            primitive,
        }
    }

    /// This object with the extent of its generated shape as `model` has it now
    /// (robosuite's `BoxObject` / `CylinderObject` rules).
    fn current(&self, model: &MjModel) -> Self {
        use crate::models::objects::Shape;
        let mut out = self.clone();
        if let Some((shape, geom)) = self.primitive {
            let size = model.geom_size()[geom];
            let (radius, half_height) = match shape {
                Shape::Box(_) => (size[0].hypot(size[1]), size[2]),
                Shape::Cylinder(_) => (size[0], size[1]),
            };
            out.horizontal_radius = radius;
            out.bottom_offset = [0.0, 0.0, -half_height];
            out.top_offset = [0.0, 0.0, half_height];
        }
        out
    }
}

/// The robots and task scene composed for a configuration, before compiling.
struct Composed {
    configuration: crate::config::EnvConfiguration,
    robots: Vec<RobotModel>,
    controllers: Vec<(CompositeControllerConfig, String)>,
    task_scene: TaskScene,
    scene: Scene,
}

/// The scene `spec` composes for `config` (robots, arena, objects), before compiling.
///
/// # Errors
/// As [`RobosuiteEnv::new`].
pub fn compose_scene(spec: &dyn TaskSpec, config: &EnvConfig, assets: &Assets) -> Result<Scene> {
    let spec = configured(spec, config)?;
    Ok(compose(spec.as_ref(), config, assets)?.scene)
}

fn compose(spec: &dyn TaskSpec, config: &EnvConfig, assets: &Assets) -> Result<Composed> {
    let setup = spec.robots();
    let config = &config.clone().with_default_robots(setup.num_robots());
    config.validate()?;
    let infos = config
        .robots
        .iter()
        .map(|name| robot_info(name))
        .collect::<Result<Vec<_>>>()?;
    let configuration = setup.check(spec.name(), &infos, config.env_configuration)?;
    let mut robots = Vec::with_capacity(infos.len());
    let mut controllers = Vec::with_capacity(infos.len());
    for (i, &info) in infos.iter().enumerate() {
        let grippers = (0..info.arms.len())
            .map(|arm| spec.gripper(i, arm, &config.gripper_choice(i, arm)))
            .collect::<Result<Vec<_>>>()?;
        let base = config
            .base_type(i)
            .map(crate::models::bases::mount_info)
            .transpose()?;
        let robot = RobotModel::build(assets, info, i, &grippers, base)?;
        // robosuite names every mobile base's manipulator mount `manipulator_mount`, so a
        // second one fails to compile there ("repeated name").
        let mobile = |r: &RobotModel| {
            r.mount
                .as_ref()
                .is_some_and(|m| m.info.kind == crate::models::bases::BaseKind::MobileBase)
        };
        if mobile(&robot) && robots.iter().any(mobile) {
            return Err(Error::invalid_argument(
                "robots",
                format!(
                    "{} is a second robot on a mobile base: robosuite 1.5.2 names each mobile \
                     base's mount body `manipulator_mount` and cannot compile two (\"repeated \
                     name\"); pair one mobile robot with fixed-base robots",
                    info.name
                ),
            ));
        }
        let (given, path) = config.controller_config(i);
        let parts = robot.body_parts();
        let resolved = match given {
            Some(c) => c.for_robot(assets, info.name, info.arms, &parts, &path)?,
            None => {
                robot_default(assets, info.name)?.fit_to(info.name, info.arms, &parts, &path)?
            }
        };
        controllers.push((resolved, path));
        robots.push(robot);
    }
    let task_scene = spec.build(assets, &mut robots)?;
    setup.place(&mut robots, configuration, &task_scene.arena);
    let mut scene = Scene::compose(assets, &task_scene.arena, &robots, &task_scene.objects)?;
    for object in &task_scene.attached {
        scene.doc_mut().merge_assets(&object.assets);
    }
    Ok(Composed {
        configuration,
        robots,
        controllers,
        task_scene,
        scene,
    })
}

impl RobosuiteEnv {
    /// Builds the task `spec` on the scene composed from robosuite's model files.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an invalid configuration (the message lists valid
    /// values); [`Error::Model`] when robosuite's model files are missing or MuJoCo rejects
    /// the scene.
    pub fn new(spec: &dyn TaskSpec, config: EnvConfig) -> Result<Self> {
        let spec = configured(spec, &config)?;
        let assets = Assets::locate()?;
        let composed = compose(spec.as_ref(), &config, &assets)?;
        // An env that never renders on its own simulates the scene without texture images.
        let textures = config.cameras.may_render();
        let (model, source) = if textures {
            composed.scene.compile_shared(spec.memory())?
        } else {
            composed
                .scene
                .compile_shared_without_textures(spec.memory())?
        };
        let mut env = Self::from_model(
            spec.as_ref(),
            composed,
            model,
            source,
            config,
            ModelSource::Composed,
        )?;
        env.textures_loaded = textures;
        Ok(env)
    }

    /// Builds the task `spec` on a caller-supplied scene MJCF that follows robosuite's names
    /// (for example one saved with robosuite's `env.sim.model.get_xml()`, even on another
    /// machine: asset paths through a `robosuite/` folder are redirected to the local model
    /// files, as robosuite's `edit_model_xml` does). Object sizes stay as the file gives
    /// them; everything else (robots, controllers, reset noise, placement, reward) is as in
    /// [`RobosuiteEnv::new`].
    ///
    /// # Errors
    /// [`Error::Model`] when the XML does not load or lacks a name the task needs;
    /// [`Error::InvalidArgument`] for an invalid configuration.
    pub fn from_scene_xml(spec: &dyn TaskSpec, xml: &str, config: EnvConfig) -> Result<Self> {
        let spec = configured(spec, &config)?;
        let spec = spec.as_ref();
        let assets = Assets::locate()?;
        let composed = compose(spec, &config, &assets)?;
        if xml.contains('\0') {
            return Err(Error::model("the scene XML contains a NUL byte"));
        }
        let xml = redirect_asset_paths(xml, &assets);
        let (model, source) = compile_shared_with_source(&xml)?;
        Self::from_model(spec, composed, model, source, config, ModelSource::Supplied)
    }

    /// As [`RobosuiteEnv::from_scene_xml`], reading the MJCF from a file.
    ///
    /// # Errors
    /// As [`RobosuiteEnv::from_scene_xml`]; [`Error::Model`] when the file cannot be read.
    pub fn from_scene_file(
        spec: &dyn TaskSpec,
        path: impl AsRef<Path>,
        config: EnvConfig,
    ) -> Result<Self> {
        let path = path.as_ref();
        let xml = std::fs::read_to_string(path).map_err(|e| {
            Error::model(format!(
                "cannot read the scene file {}: {e}",
                path.display()
            ))
        })?;
        Self::from_scene_xml(spec, &xml, config)
    }

    fn from_model(
        spec: &dyn TaskSpec,
        composed: Composed,
        model: Compiled,
        source_xml: Arc<str>,
        config: EnvConfig,
        source: ModelSource,
    ) -> Result<Self> {
        // The robots and the robot set-up the scene was composed with.
        let mut config = config.with_default_robots(spec.robots().num_robots());
        config.env_configuration = composed.configuration;
        config.reward_shaping = Some(
            config
                .reward_shaping
                .unwrap_or_else(|| spec.default_reward_shaping()),
        );
        let timestep = model.model().opt().timestep;
        if !(timestep.is_finite() && timestep > 0.0) {
            return Err(Error::model(format!(
                "the model's timestep must be positive, got {timestep}"
            )));
        }
        // A cached scene is shared copy-on-write with every env built from it.
        let mut sim = match model {
            Compiled::Shared(shared) => Sim::new_shared(&shared)?,
            Compiled::Own(model) => Sim::new(model)?,
        };
        let model = sim.model();
        crate::config::check_substeps(config.control_freq, timestep)?;
        let substeps = config.substeps(timestep);
        let timing = Timing {
            timestep,
            control_freq: config.control_freq,
        };
        let robots = composed
            .robots
            .iter()
            .zip(&composed.controllers)
            .map(|(r, (c, path))| {
                Robot::bind(model, r, c, timing, config.initialization_noise, path)
            })
            .collect::<Result<Vec<_>>>()?;
        let task = spec.bind(&composed.task_scene, model, &robots)?;
        let objects = composed
            .task_scene
            .objects
            .iter()
            .map(|o| MujocoObjectInfo::of(o, model))
            .collect();

        // robosuite's order: every robot's observables, then the task's; `use_object_obs =
        // false` leaves out the task's object observables (and those robosuite creates only
        // with them, such as Wipe's `robot0_contact`).
        let mut obs_specs: Vec<ObsSpec> = Vec::new();
        let mut robot_ranges = Vec::with_capacity(robots.len());
        for r in &robots {
            let specs = r.observation_specs();
            let start = total_len(&obs_specs);
            robot_ranges.push(start..start + total_len(&specs));
            obs_specs.extend(specs);
        }
        let task_start = total_len(&obs_specs);
        // robosuite's `RobotEnv` adds the camera observables after the robots' and before
        // the task's; frames live outside the buffer.
        crate::cameras::rig::prepare_model(&config.cameras, sim.model_mut());
        let model = sim.model();
        let cameras = CameraRig::new(
            &config.cameras,
            model,
            &crate::cameras::segmentation::groups(&composed.task_scene, &composed.robots),
        )?;
        if let Some(rig) = &cameras {
            obs_specs.extend(rig.specs().iter().cloned());
        }
        let task_specs = task.observation_specs();
        let task_range = task_start..task_start + total_len(&task_specs);
        obs_specs.extend(task_specs);
        let use_object_obs = config.use_object_obs;
        let exists = |s: &ObsSpec| use_object_obs || !s.needs_object_obs;
        // Enabled when it exists; active when it exists and robosuite makes it active.
        let obs_flags = obs_specs
            .iter()
            .map(|s| (exists(s), exists(s) && s.active))
            .collect();
        let layout = ObsLayout::new(obs_specs.clone(), |s| exists(s) && s.active);
        let obs_space = layout.space()?;

        let mut action_splits = Vec::new();
        let (mut low, mut high) = (Vec::new(), Vec::new());
        for r in &robots {
            let start = low.len();
            let (l, h) = r.action_limits();
            low.extend(l);
            high.extend(h);
            action_splits.push(start..low.len());
        }
        let dim = low.len();
        let act_space = BoxSpace::<f64>::new(
            ndarray::Array1::from(low).into_dyn(),
            ndarray::Array1::from(high).into_dyn(),
        )?;
        let metadata = Metadata {
            render_modes: if cfg!(feature = "render") {
                vec![RenderMode::RgbArray, RenderMode::DepthArray]
            } else {
                Vec::new()
            },
            render_fps: Some(config.control_freq),
        };
        let (rng, rng_seeded) = match config.seed {
            Some(s) => (rng_from_seed(s), true),
            None => (rng_from_seed(0), false),
        };
        let buf = vec![0.0; task_range.end];
        let task_options = spec.options();
        Ok(Self {
            sim,
            robots,
            task,
            config,
            source,
            layout,
            robot_ranges,
            task_range,
            obs_space,
            act_space,
            action_splits,
            metadata,
            rng,
            rng_seeded,
            buf,
            action_buf: Vec::with_capacity(dim),
            substeps,
            split_step: None,
            timestep: 0,
            phase: Phase::NeedsReset,
            cameras,
            source_xml,
            textures_loaded: true,
            task_options,
            objects,
            obs_specs,
            obs_flags,
            #[cfg(feature = "render")]
            viewer_renderer: None,
            visualized: false,
            rebind: Arc::new(Rebind {
                spec: spec.clone_box(),
                scene: composed.task_scene,
            }),
        })
    }
}

/// Points asset paths that run through a `robosuite/` folder (a scene saved by robosuite on
/// any machine) at the local robosuite package, as robosuite's `edit_model_xml` does.
fn redirect_asset_paths(xml: &str, assets: &Assets) -> String {
    let local = assets.package().to_string_lossy().into_owned();
    let mut out = String::with_capacity(xml.len());
    let mut rest = xml;
    while let Some(at) = rest.find("file=\"") {
        let (head, tail) = rest.split_at(at + 6);
        out.push_str(head);
        let end = tail.find('"').unwrap_or(tail.len());
        let path = &tail[..end];
        match path.rfind("/robosuite/") {
            Some(i) => {
                out.push_str(&local);
                out.push_str(&path[i + "/robosuite".len()..]);
            }
            None if path.starts_with("robosuite/") => {
                out.push_str(&local);
                out.push_str(&path["robosuite".len()..]);
            }
            _ => out.push_str(path),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

impl RobosuiteEnv {
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

    /// The task's constructor arguments by robosuite's names, as the env was built with
    /// them (see [`TaskSpec::options`]).
    pub fn task_options(&self) -> &TaskOptions {
        &self.task_options
    }

    /// Whether the model was composed by this crate or supplied by the caller.
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

    /// Sets the flattened simulator state `[time, qpos, qvel]`, runs `mj_forward` and takes
    /// a fresh observation (robosuite's `set_state_from_flattened`, `forward` and
    /// `_get_observations(force_update=True)`). Controllers, gripper commands and the
    /// episode counter are kept.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a wrong length, a non-finite value or a position or
    /// velocity beyond [`MAX_STATE_MAGNITUDE`](crate::sim::MAX_STATE_MAGNITUDE) (nothing is
    /// changed); [`Error::Simulation`] when MuJoCo raises an error (the env then needs a
    /// reset); [`Error::Closed`] after `close`.
    pub fn set_state(&mut self, state: &[f64]) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if let Err(e) = self.sim.set_state(state) {
            if self.sim.failed() {
                self.phase = Phase::NeedsReset;
            }
            return Err(e);
        }
        self.split_step = None;
        self.observe()
    }

    /// Starts an episode at a given state instead of a sampled one (robosuite's
    /// deterministic reset, robomimic's `reset_to`): the task's parameters from
    /// `task_state` ([`Task::save_state`]'s layout; Lift: the cube half-extents), the
    /// simulator state `[time, qpos, qvel]` from `state`; controllers re-based on it, gripper
    /// commands zeroed, observation cache cleared, episode counter 0. Draws nothing from the
    /// RNG.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a task state or state of the wrong length, with
    /// non-finite values or beyond [`MAX_STATE_MAGNITUDE`](crate::sim::MAX_STATE_MAGNITUDE)
    /// (nothing is changed then); [`Error::Simulation`] when MuJoCo raises an error;
    /// [`Error::Closed`] after `close`.
    pub fn reset_to_state(
        &mut self,
        task_state: &[f64],
        state: &[f64],
    ) -> Result<(DictValue, Info)> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        self.sim.check_state(state)?;
        self.task.load_state(&mut self.sim, task_state)?;
        self.phase = Phase::NeedsReset;
        self.sim.reset_data();
        for robot in &mut self.robots {
            robot.reset_to(&mut self.sim, state)?;
        }
        self.task.clear_observation_cache();
        self.sim.set_state(state)?;
        self.begin_episode()
    }

    /// A snapshot of the whole episode state (see [`EnvSnapshot`]); unlike
    /// [`RobosuiteEnv::get_state`] it also holds the controller goals, the gripper commands,
    /// the warm start, the observation cache and the episode counter, so stepping on from a
    /// restored snapshot repeats the original steps bit for bit.
    pub fn snapshot(&self) -> EnvSnapshot {
        EnvSnapshot {
            physics: self.sim.integration_state(),
            robots: self.robots.iter().map(Robot::controller_state).collect(),
            task: self.task.save_state(),
            observation: self.buf.clone(),
            timestep: self.timestep,
            phase: self.phase,
        }
    }

    /// The environment RNG and whether it was seeded (see [`RobosuiteEnv::set_rng`]).
    pub fn rng_state(&self) -> (EnvRng, bool) {
        (self.rng.clone(), self.rng_seeded)
    }

    /// Replaces the environment RNG (with [`RobosuiteEnv::restore`], a copy continues the
    /// original's episode bit for bit, resets included). `seeded = false` draws a fresh
    /// entropy seed at the next unseeded reset.
    pub fn set_rng(&mut self, rng: EnvRng, seeded: bool) {
        self.rng = rng;
        self.rng_seeded = seeded;
    }

    /// Restores a snapshot taken from this environment.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a snapshot of another kind of environment (nothing is
    /// changed then); [`Error::Closed`] after `close`.
    pub fn restore(&mut self, snapshot: &EnvSnapshot) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if snapshot.robots.len() != self.robots.len()
            || snapshot.physics.len() != self.sim.integration_state().len()
            || snapshot.observation.len() != self.buf.len()
        {
            return Err(Error::invalid_argument(
                "snapshot",
                "the snapshot was taken from a different environment",
            ));
        }
        let mut robots = self.robots.clone();
        for (robot, state) in robots.iter_mut().zip(&snapshot.robots) {
            robot.set_controller_state(state)?;
        }
        self.task.load_state(&mut self.sim, &snapshot.task)?;
        self.sim.set_integration_state(&snapshot.physics)?;
        self.robots = robots;
        self.buf.copy_from_slice(&snapshot.observation);
        self.observe_cameras()?;
        self.timestep = snapshot.timestep;
        self.split_step = None;
        self.phase = if snapshot.phase == Phase::Closed {
            Phase::NeedsReset
        } else {
            snapshot.phase
        };
        Ok(())
    }

    /// The observation of the last observation pass (after the last step, reset or
    /// [`RobosuiteEnv::set_state`]), as robosuite's `observation_spec()` returns it.
    pub fn observation(&self) -> DictValue {
        self.layout.to_dict_with(&self.buf, self.frames())
    }

    /// Every observable's value from the last observation pass, whatever its enabled and
    /// active flags (the buffer holds them all), with the `{modality}-state`
    /// concatenations of them all: what robosuite's disabled or inactive observables would
    /// read.
    pub fn all_observations(&self) -> DictValue {
        ObsLayout::new(self.obs_specs.clone(), |s| self.observable_exists(s))
            .to_dict_with(&self.buf, self.frames())
    }

    /// The camera frames of the last observation pass (empty without camera observations).
    fn frames(&self) -> &[gym_core::ArrayValue] {
        self.cameras.as_ref().map_or(&[], CameraRig::frames)
    }

    /// The cameras: observed cameras, their frames and the renderer (`None` when neither
    /// camera observations nor a render mode were asked for).
    pub fn cameras(&self) -> Option<&CameraRig> {
        self.cameras.as_ref()
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
            reward_shaping: self.config.reward_shaping.unwrap_or(false),
            horizon: self.config.horizon,
        }
    }

    /// One observation pass: every robot's observables, then the task's, into the buffer;
    /// then the camera frames.
    fn observe(&mut self) -> Result<()> {
        for (robot, range) in self.robots.iter().zip(&self.robot_ranges) {
            robot.observe(&self.sim, &mut self.buf[range.clone()]);
        }
        self.task
            .observe(&self.sim, &mut self.buf[self.task_range.clone()]);
        self.observe_cameras()
    }

    /// Draws the observed cameras' frames (nothing without camera observations).
    fn observe_cameras(&mut self) -> Result<()> {
        match &mut self.cameras {
            Some(rig) => rig.observe(self.sim.data_mut()),
            None => Ok(()),
        }
    }

    /// The end of every reset: episode counter 0, running, a first observation.
    fn begin_episode(&mut self) -> Result<(DictValue, Info)> {
        self.split_step = None;
        self.timestep = 0;
        self.observe()?;
        self.phase = Phase::Running;
        let info = Info::new().with("success", self.check_success());
        Ok((self.observation(), info))
    }

    fn check_action(&self, action: &ArrayD<f64>) -> Result<()> {
        let dim = self.action_dim();
        if action.len() != dim || action.ndim() != 1 {
            return Err(Error::invalid_action(format!(
                "expected an action of shape [{dim}] (per robot: each arm's controller input, \
                 then each arm's gripper input), got shape {:?}",
                action.shape()
            )));
        }
        if let Some((i, v)) = action.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(Error::invalid_action(format!(
                "action[{i}] is not finite ({v})"
            )));
        }
        Ok(())
    }

    /// One env step without its observation: checks the order and the action, simulates,
    /// then rewards, task updates and end flags. Returns the transition and `success`.
    fn advance(&mut self, action: &ArrayD<f64>) -> Result<(Transition, bool)> {
        self.begin_step(action)?;
        for sub in 0..self.substeps {
            // Sensors are read only after an env step (and at its first substep, before
            // `mj_step2`), so only the last substep computes them.
            self.substep(sub + 1 == self.substeps)?;
        }
        self.finish_step()
    }
}

/// An env step taken one substep at a time, for callers that read the simulation between
/// substeps (robosuite's observables sample at their own rate, on whichever substep their
/// timer falls). [`RobosuiteEnv::begin_step`], then [`RobosuiteEnv::substep`] until it
/// returns `true`, then [`RobosuiteEnv::finish_step`] is exactly one
/// [`Env::step`](gym_core::Env::step): the same trajectory, bit for bit.
impl RobosuiteEnv {
    /// Starts an env step with `action`: checks the episode's phase and the action (an
    /// error changes nothing), then counts the step. A reset, `set_state` or `restore`
    /// abandons a step under way.
    ///
    /// # Errors
    /// [`Error::Closed`], [`Error::ResetNeeded`], [`Error::EpisodeEnded`],
    /// [`Error::InvalidAction`] as for a step; [`Error::InvalidArgument`] when a step is
    /// already under way.
    pub fn begin_step(&mut self, action: &ArrayD<f64>) -> Result<()> {
        match self.phase {
            Phase::Closed => return Err(Error::Closed),
            Phase::NeedsReset => return Err(Error::ResetNeeded),
            Phase::Ended => return Err(Error::EpisodeEnded),
            Phase::Running => {}
        }
        if self.split_step.is_some() {
            return Err(Error::invalid_argument(
                "begin_step",
                "a step is under way: run its substeps and finish_step first",
            ));
        }
        self.check_action(action)?;
        self.action_buf.clear();
        self.action_buf.extend(action.iter().copied());
        self.timestep += 1;
        self.sim.clear_divergence();
        self.split_step = Some(0);
        Ok(())
    }

    /// Runs the next physics substep of the step under way (robosuite's
    /// `sim.step1(); _pre_action(action, policy_step); sim.step2()`, or with
    /// `lite_physics=False` `sim.forward(); _pre_action(...); sim.step()`). `sensors`:
    /// whether MuJoCo's sensors are computed (they feed nothing back into the dynamics).
    /// Returns whether this was the step's last substep.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when no step is under way or its substeps are done;
    /// [`Error::Simulation`] when MuJoCo raised an error or the simulation diverged (the
    /// episode then needs a reset).
    pub fn substep(&mut self, sensors: bool) -> Result<bool> {
        let sub = match self.split_step {
            Some(sub) if sub < self.substeps => sub,
            _ => {
                return Err(Error::invalid_argument(
                    "substep",
                    "no substep is due: call begin_step first (finish_step after the last)",
                ));
            }
        };
        let result = self.run_substep(sub, sensors);
        if let Err(e) = result {
            // A MuJoCo error or a diverged simulation: the episode cannot go on.
            self.split_step = None;
            self.phase = Phase::NeedsReset;
            return Err(e);
        }
        self.split_step = Some(sub + 1);
        Ok(sub + 1 == self.substeps)
    }

    /// Ends the step under way after its last substep: observations, reward, the task's
    /// updates and the end flags. Returns the transition and `success`.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when substeps remain or no step is under way.
    pub fn finish_step(&mut self) -> Result<(Transition, bool)> {
        if self.split_step != Some(self.substeps) {
            return Err(Error::invalid_argument(
                "finish_step",
                "the step's substeps are not all run (or no step is under way)",
            ));
        }
        self.split_step = None;
        // robosuite samples its observables on the last substep, before `_post_action`
        // computes the reward (which updates Wipe's wiped markers).
        self.observe()?;
        let reward = self.reward();
        let reward_config = self.reward_config();
        self.task
            .after_reward(&mut self.sim, &self.robots, &reward_config);
        let success = self.check_success();
        let terminated = self.task.check_terminated(&self.sim, &self.robots);
        let truncated = self.timestep >= self.config.horizon && !self.config.ignore_done;
        // With `ignore_done` the episode goes on after the task terminates (Wipe's early
        // terminations), as robosuite, whose step refuses only past the horizon.
        if truncated || (terminated && !self.config.ignore_done) {
            self.phase = Phase::Ended;
        }
        let transition = Transition {
            reward,
            terminated,
            truncated,
        };
        Ok((transition, success))
    }

    /// Runs substep `sub` of the step under way.
    fn run_substep(&mut self, sub: usize, sensors: bool) -> Result<()> {
        let lite = self.config.lite_physics;
        if lite {
            self.sim.step1()?;
        } else {
            self.sim.forward()?;
        }
        for (robot, split) in self.robots.iter_mut().zip(&self.action_splits) {
            if sub == 0 {
                robot.set_goal(&self.sim, &self.action_buf[split.clone()]);
            }
            robot.apply_control(&mut self.sim);
        }
        if sub == 0 {
            self.task.on_policy_step(&self.sim, &self.robots);
        }
        if !lite {
            self.sim.step()?;
        } else if sensors {
            self.sim.step2()?;
        } else {
            self.sim.step2_without_sensors()?;
        }
        self.sim.check_diverged()
    }
}

/// A frame drawn by [`RobosuiteEnv::render_camera`], rows bottom first (OpenGL's order, as
/// robosuite's `sim.render` returns them).
#[cfg(feature = "render")]
#[derive(Debug, Clone, PartialEq)]
pub struct CameraFrame {
    /// Width in pixels.
    pub width: usize,
    /// Height in pixels.
    pub height: usize,
    /// RGB bytes, `height × width × 3`.
    pub rgb: Vec<u8>,
    /// Raw depth in `[0, 1]`, `height × width` (when asked for).
    pub depth: Option<Vec<f32>>,
    /// Per pixel `(object type, object id)`, `height × width × 2`, `-1` for the background
    /// (when asked for).
    pub segmentation: Option<Vec<i32>>,
}

/// robosuite's env object beyond the Gymnasium API: direct simulator access, observation
/// refresh, deterministic reset, the scene as MJCF, observable flags and free rendering.
impl RobosuiteEnv {
    /// The task's robosuite name (`"Lift"`).
    pub(crate) fn task_name(&self) -> &str {
        self.rebind.spec.name()
    }

    /// Marks the sites as shown by [`RobosuiteEnv::visualize`] (the next reset hides them).
    pub(crate) fn set_visualized(&mut self, visualized: bool) {
        self.visualized = visualized;
    }

    /// The simulator, mutably (robosuite's `env.sim`): what is written here (positions,
    /// velocities, controls, model values that keep every size) is what the next step
    /// starts from. Call [`Sim::forward`] after writing positions, as with robosuite.
    pub fn sim_mut(&mut self) -> &mut Sim {
        &mut self.sim
    }

    /// robosuite's `_get_observations(force_update=True)`: reads every observable from the
    /// simulator as it is now (no forward pass) and returns the observations.
    ///
    /// # Errors
    /// [`Error::Closed`] after `close`; [`Error::Render`] when a camera frame cannot be
    /// drawn.
    pub fn update_observations(&mut self) -> Result<DictValue> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        self.observe()?;
        Ok(self.observation())
    }

    /// robosuite's deterministic reset (after `reset_from_xml_string`): the scene's object
    /// sizes and poses as the model gives them (nothing re-drawn, no placement), the robots
    /// at their `init_qpos` without noise; draws nothing from the RNG.
    ///
    /// # Errors
    /// [`Error::Closed`] after `close`; [`Error::Simulation`] when MuJoCo raises an error.
    pub fn reset_deterministic(&mut self) -> Result<(DictValue, Info)> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        self.phase = Phase::NeedsReset;
        self.sim.reset_data();
        for robot in &mut self.robots {
            robot.reset_deterministic(&mut self.sim)?;
        }
        self.task.clear_observation_cache();
        self.sim.forward()?;
        self.begin_episode()
    }

    /// robosuite's `reset_from_xml_string(xml)`: the env reloaded from a scene MJCF of this
    /// task (for instance one saved by robosuite, see [`RobosuiteEnv::from_scene_xml`]),
    /// then [`RobosuiteEnv::reset_deterministic`]. The configuration, the RNG stream and
    /// the observables' flags are kept.
    ///
    /// When the new scene differs from the current one at most in the sizes of generated
    /// boxes (the demonstrations of one task: robosuite saves each episode's cube size),
    /// the env's own model is overwritten in place with the cached compile of that scene
    /// and the boxes resized, which equals loading it anew (see [`SceneLoad::InPlace`]);
    /// otherwise the scene is compiled and the env rebuilt on it.
    ///
    /// # Errors
    /// As [`RobosuiteEnv::from_scene_xml`] (the env is then unchanged); [`Error::Closed`]
    /// after `close`.
    pub fn reset_from_xml_string(&mut self, xml: &str) -> Result<(DictValue, Info, SceneLoad)> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if xml.contains('\0') {
            return Err(Error::model("the scene XML contains a NUL byte"));
        }
        let assets = Assets::locate()?;
        let xml = redirect_asset_paths(xml, &assets);
        if let Some(plan) = crate::models::scene::in_place(&self.source_xml, &xml) {
            let previous = Arc::clone(&self.source_xml);
            match self.load_in_place(&xml, &plan) {
                Ok(true) => {
                    let (obs, info) = self.reset_deterministic()?;
                    return Ok((obs, info, SceneLoad::InPlace));
                }
                Ok(false) => {}
                Err(e) => {
                    // The model was overwritten: rebuild on the new scene, or else on the
                    // previous one, and report the error.
                    return self.rebuild(&xml).or_else(|_| {
                        self.rebuild(&previous)?;
                        Err(e)
                    });
                }
            }
        }
        self.rebuild(&xml)
    }

    /// The env rebuilt on the scene `xml` (see [`RobosuiteEnv::reset_from_xml_string`]),
    /// replacing `self` only on success.
    fn rebuild(&mut self, xml: &str) -> Result<(DictValue, Info, SceneLoad)> {
        let spec = crate::registry::make_task(self.rebind.spec.name())?;
        let mut fresh = Self::from_scene_xml(spec.as_ref(), xml, self.config.clone())?;
        fresh.set_rng(self.rng.clone(), self.rng_seeded);
        if fresh.obs_specs == self.obs_specs && fresh.obs_flags != self.obs_flags {
            fresh.set_observable_flags(self.obs_flags.clone())?;
        }
        let (obs, info) = fresh.reset_deterministic()?;
        *self = fresh;
        Ok((obs, info, SceneLoad::Compiled))
    }

    /// Overwrites the model with `plan` (see [`SceneLoad::InPlace`]) and binds the task
    /// again; `Ok(false)`, with nothing changed, when the model's sizes differ from the
    /// plan's.
    fn load_in_place(&mut self, xml: &str, plan: &crate::models::scene::InPlace) -> Result<bool> {
        let (cur, base) = (self.sim.model().ffi(), plan.base.model().ffi());
        let same = cur.nbuffer == base.nbuffer
            && (
                cur.nq, cur.nv, cur.nu, cur.na, cur.nbody, cur.ngeom, cur.nsite, cur.ncam,
            ) == (
                base.nq, base.nv, base.nu, base.na, base.nbody, base.ngeom, base.nsite, base.ncam,
            )
            && cur.opt.timestep == base.opt.timestep;
        if !same {
            return Ok(false);
        }
        let model = self.sim.model_mut();
        // SAFETY: both are compiled models of one skeleton with equal buffer sizes (checked:
        // MuJoCo requires it), so every count, address and array length of the env's model
        // stays as the robots, task and cameras were bound to; the buffer is overwritten
        // in place.
        unsafe { mujoco_rs::mujoco_c::mj_copyModel(model.ffi_mut(), plan.base.model().ffi()) };
        for r in &plan.resizes {
            // half-extents are positive and finite (checked by the plan)
            crate::sim::resize_box_body(&mut self.sim, r.update(), r.half)?;
        }
        crate::cameras::rig::prepare_model(&self.config.cameras, self.sim.model_mut());
        let rebind = Arc::clone(&self.rebind);
        self.task = rebind
            .spec
            .bind(&rebind.scene, self.sim.model(), &self.robots)?;
        let model = self.sim.model();
        self.objects = rebind
            .scene
            .objects
            .iter()
            .map(|o| MujocoObjectInfo::of(o, model))
            .collect();
        self.sim.clear_divergence();
        self.source = ModelSource::Supplied;
        self.source_xml = Arc::from(xml);
        Ok(true)
    }

    /// The task's objects in robosuite's order (its `env.model.mujoco_objects`: the
    /// visual objects, then the physical ones, for the tasks that have both).
    /// Generated boxes and cylinders have the size the last reset drew.
    pub fn mujoco_objects(&self) -> Vec<MujocoObjectInfo> {
        let model = self.sim.model();
        self.objects.iter().map(|o| o.current(model)).collect()
    }

    /// The MJCF text the model was compiled from.
    pub fn source_xml(&self) -> &str {
        &self.source_xml
    }

    /// The scene as MJCF with the model's current values (robosuite's
    /// `env.sim.model.get_xml()`): the compiled text, parsed again and given every
    /// real-valued model array as it is now (MuJoCo's `mj_copyBack`: object sizes re-drawn
    /// at reset, masses, positions, edits through [`RobosuiteEnv::sim_mut`]), saved by
    /// MuJoCo. Loading it with [`RobosuiteEnv::from_scene_xml`] gives this model back.
    ///
    /// # Errors
    /// [`Error::Model`] when MuJoCo cannot parse, compile or save the scene.
    pub fn scene_xml(&self) -> Result<String> {
        let model = self.model_with_textures()?;
        crate::sim::scene_xml(&self.source_xml, model.as_ref())
    }

    /// Whether the env's model holds the scene's texture images (`tex_data`,
    /// `tex_width`, ...). An env whose configuration never renders on its own (see
    /// [`crate::cameras::CameraConfig::may_render`]: no offscreen renderer, no camera
    /// observations, no render mode) is built on its scene without them: the same physics,
    /// names and counts, each texture a 1×1 placeholder. Its frames
    /// ([`RobosuiteEnv::render_camera`]) are still drawn with the images (the render
    /// context is made from the scene compiled with them, once per process), and
    /// [`RobosuiteEnv::load_textures`] gives its model the images.
    pub fn textures_loaded(&self) -> bool {
        self.textures_loaded
    }

    /// Gives the env's model its scene's texture images (see
    /// [`RobosuiteEnv::textures_loaded`]), keeping every other value of the model and the
    /// simulation state: for code that reads or writes `tex_data` (texture randomisation).
    /// The model is then the env's own (not shared with other envs). Does nothing when the
    /// images are loaded.
    ///
    /// # Errors
    /// [`Error::Model`] when the scene cannot be compiled; [`Error::Closed`] after
    /// `close`. The env is then unchanged.
    pub fn load_textures(&mut self) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        if self.textures_loaded {
            return Ok(());
        }
        let textured = self.textured_scene_model()?;
        self.sim.replace_with_textured(textured)?;
        self.textures_loaded = true;
        Ok(())
    }

    /// A copy of the scene compiled with its texture images (cached per process).
    fn textured_scene_model(&self) -> Result<MjModel> {
        let (compiled, _) = compile_shared_with_source(&self.source_xml)?;
        Ok(compiled.into_model())
    }

    /// The env's model, or, without texture images, a copy of it with them.
    fn model_with_textures(&self) -> Result<std::borrow::Cow<'_, MjModel>> {
        if self.textures_loaded {
            return Ok(std::borrow::Cow::Borrowed(self.sim.model()));
        }
        let textured = self.textured_scene_model()?;
        Ok(std::borrow::Cow::Owned(
            self.sim.with_textures_of(textured)?,
        ))
    }

    /// Whether observable `spec` exists in this env: robosuite creates the object
    /// observables only with `use_object_obs`.
    fn observable_exists(&self, spec: &ObsSpec) -> bool {
        self.config.use_object_obs || !spec.needs_object_obs
    }

    /// Every observable of the env in robosuite's order with its flags (robosuite's
    /// `observation_names`, `enabled_observables`, `active_observables`).
    pub fn observables(&self) -> Vec<ObservableInfo> {
        self.obs_specs
            .iter()
            .zip(&self.obs_flags)
            .filter(|(s, _)| self.observable_exists(s))
            .map(|(s, &(enabled, active))| ObservableInfo {
                spec: s.clone(),
                enabled,
                active,
            })
            .collect()
    }

    /// robosuite's `modify_observable(name, "enabled" | "active", value)`: an observable
    /// that is not enabled and active is left out of the observations (and of the
    /// `{modality}-state` concatenations) from the next observation on; the observation
    /// space changes with it.
    ///
    /// # Errors
    /// [`Error::UnknownKey`] listing the observables for an unknown name (nothing changes).
    pub fn modify_observable(
        &mut self,
        name: &str,
        flag: ObservableFlag,
        value: bool,
    ) -> Result<()> {
        let Some(i) = self
            .obs_specs
            .iter()
            .position(|s| s.key == name && self.observable_exists(s))
        else {
            return Err(Error::UnknownKey {
                key: name.to_owned(),
                available: self
                    .obs_specs
                    .iter()
                    .filter(|s| self.observable_exists(s))
                    .map(|s| s.key.clone())
                    .collect(),
            });
        };
        let mut flags = self.obs_flags.clone();
        match flag {
            ObservableFlag::Enabled => flags[i].0 = value,
            ObservableFlag::Active => flags[i].1 = value,
        }
        self.set_observable_flags(flags)
    }

    /// Every observable's `(enabled, active)` flags at once, with the observation layout
    /// and space they give.
    ///
    /// # Errors
    /// As [`ObsLayout::space`].
    fn set_observable_flags(&mut self, flags: Vec<(bool, bool)>) -> Result<()> {
        let shown: std::collections::HashSet<&str> = self
            .obs_specs
            .iter()
            .zip(&flags)
            .filter(|(_, (e, a))| *e && *a)
            .map(|(s, _)| s.key.as_str())
            .collect();
        let layout = ObsLayout::new(self.obs_specs.clone(), |s| shown.contains(s.key.as_str()));
        let space = layout.space()?;
        self.layout = layout;
        self.obs_space = space;
        self.obs_flags = flags;
        Ok(())
    }

    /// Uploads texture `texture` (its bitmap in the model's `tex_data`, changed since the
    /// env's renderers were made, as robosuite's `TextureModder` does) to every renderer
    /// of this env: the camera observations', the render mode's and `render_camera`'s.
    /// Renderers made later read the model as it is then. Without a renderer it does
    /// nothing.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a texture id out of range (nothing is uploaded);
    /// [`Error::Unsupported`] when the model holds no texture images (see
    /// [`RobosuiteEnv::load_textures`]);
    /// [`Error::Render`] when a rendering context cannot be made current; [`Error::Closed`]
    /// after `close`.
    #[cfg(feature = "render")]
    pub fn upload_texture(&mut self, texture: usize) -> Result<()> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        let ntex = self.sim.model().ffi().ntex.max(0) as usize;
        if texture >= ntex {
            return Err(Error::invalid_argument(
                "texture",
                format!("texture id {texture} out of range (the model has {ntex} textures)"),
            ));
        }
        if !self.textures_loaded {
            return Err(Error::unsupported(
                "the env's model holds no texture images (its configuration never renders): \
                 call load_textures() before changing textures",
            ));
        }
        if let Some(rig) = &mut self.cameras {
            rig.upload_texture(self.sim.model(), texture)?;
        }
        if let Some(renderer) = &mut self.viewer_renderer {
            renderer.upload_texture(self.sim.model(), texture)?;
        }
        Ok(())
    }

    /// robosuite's `sim.render(width, height, camera_name=..., depth=..., segmentation=...)`:
    /// a frame of `camera` (a fixed camera by id, or MuJoCo's free camera) at any size up to
    /// [`crate::cameras::MAX_CAMERA_SIZE`], drawn with the env's own offscreen renderer for free
    /// rendering (made on first use, grown when a larger frame is asked for), whether or not
    /// the env has camera observations.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown camera id or a size out of range;
    /// [`Error::Render`] when no rendering context can be opened; [`Error::Closed`] after
    /// `close`.
    #[cfg(feature = "render")]
    pub fn render_camera(
        &mut self,
        camera: impl Into<crate::render::View>,
        width: usize,
        height: usize,
        depth: bool,
        segmentation: bool,
    ) -> Result<CameraFrame> {
        use crate::render::{OffscreenRenderer, Outputs, Request};
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        let camera = camera.into();
        let ncam = self.sim.model().ffi().ncam.max(0) as usize;
        if let crate::render::View::Fixed(id) = camera
            && id >= ncam
        {
            return Err(Error::invalid_argument(
                "camera",
                format!("camera id {id} out of range (the model has {ncam} cameras)"),
            ));
        }
        let fits = self
            .viewer_renderer
            .as_ref()
            .is_some_and(|r| r.max_size().0 >= width && r.max_size().1 >= height);
        if !fits {
            let (w0, h0) = self
                .viewer_renderer
                .as_ref()
                .map_or((0, 0), OffscreenRenderer::max_size);
            // Without texture images in the env's model, the render context is made from
            // a copy with them (frames as a textured env's).
            let context_model = self.model_with_textures()?;
            let renderer = OffscreenRenderer::with_context_model(
                self.sim.model(),
                context_model.as_ref(),
                width.max(w0),
                height.max(h0),
                crate::render::Supersampling::NONE,
                self.config.cameras.render_gpu_device_id,
            )?;
            drop(context_model);
            self.viewer_renderer = Some(renderer);
        }
        let n = width * height;
        let mut rgb = vec![0u8; 3 * n];
        let mut depth_buf = depth.then(|| vec![0f32; n]);
        let (mut ids, mut types) = if segmentation {
            (Some(vec![0i32; n]), Some(vec![0i32; n]))
        } else {
            (None, None)
        };
        let renderer = self
            .viewer_renderer
            .as_mut()
            .ok_or_else(|| Error::Render("no renderer".into()))?;
        let mut request = [Request {
            camera,
            width,
            height,
            out: Outputs {
                rgb: Some(&mut rgb),
                depth: depth_buf.as_deref_mut(),
                segmentation: ids.as_deref_mut(),
                segmentation_type: types.as_deref_mut(),
            },
        }];
        renderer.render(self.sim.data_mut(), &mut request)?;
        let segmentation = match (types, ids) {
            (Some(t), Some(i)) => Some(t.iter().zip(&i).flat_map(|(&t, &i)| [t, i]).collect()),
            _ => None,
        };
        Ok(CameraFrame {
            width,
            height,
            rgb,
            depth: depth_buf,
            segmentation,
        })
    }
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
        if self.source == ModelSource::Composed {
            self.task.randomize_model(&mut self.sim, &mut self.rng)?;
        }
        self.sim.reset_data();
        for robot in &mut self.robots {
            robot.reset(&mut self.sim, &mut self.rng)?;
        }
        self.task.clear_observation_cache();
        self.task.place_objects(&mut self.sim, &mut self.rng)?;
        self.sim.forward()?;
        if self.visualized {
            // robosuite's reset calls `visualize` with every setting off.
            self.visualize(crate::wrappers::VisualizationSettings::all(false));
        }
        self.begin_episode()
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

    /// [`Env::step`](gym_core::Env::step) writing into `observation` and `info` in place
    /// when they hold the previous step's keys, shapes and dtypes: a loop of steps does not
    /// allocate.
    fn step_into(
        &mut self,
        action: &ArrayD<f64>,
        observation: &mut DictValue,
        info: &mut Info,
    ) -> Result<Transition> {
        let (transition, success) = self.advance(action)?;
        let frames = self.cameras.as_ref().map_or(&[][..], CameraRig::frames);
        self.layout.write_dict_with(&self.buf, frames, observation);
        if info.len() != 1 || info.get("success").is_none() {
            info.clear();
        }
        info.set("success", success);
        Ok(transition)
    }

    /// Observations are written into batch rows: the camera frames and the low-dim values
    /// go from the environment's buffers straight into a vector environment's batch.
    fn writes_rows(&self) -> bool {
        true
    }

    /// [`Env::step_into`](gym_core::Env::step_into) without the observation (it stays in
    /// the environment's buffers for [`write_observation_row`](gym_core::Env::write_observation_row)).
    fn step_for_row(&mut self, action: &ArrayD<f64>, info: &mut Info) -> Result<Transition> {
        let (transition, success) = self.advance(action)?;
        if info.len() != 1 || info.get("success").is_none() {
            info.clear();
        }
        info.set("success", success);
        Ok(transition)
    }

    /// Writes the current observation (that of the last step or reset) into `row`.
    fn write_observation_row(&self, row: &mut gym_core::ObsRow<'_>) -> Result<()> {
        let frames = self.cameras.as_ref().map_or(&[][..], CameraRig::frames);
        self.layout.write_row(&self.buf, frames, row)
    }

    fn metadata(&self) -> &Metadata {
        &self.metadata
    }

    fn render_mode(&self) -> Option<RenderMode> {
        self.cameras.as_ref().and_then(CameraRig::render_mode)
    }

    /// A frame of `render_camera` at `render_width × render_height`, top row first: RGB
    /// for `rgb_array`, raw depth in `[0, 1]` for `depth_array`; `None` without a render
    /// mode.
    fn render(&mut self) -> Result<Option<Frame>> {
        if self.phase == Phase::Closed {
            return Err(Error::Closed);
        }
        match &mut self.cameras {
            Some(rig) => rig.render(self.sim.data_mut()),
            None => Ok(None),
        }
    }

    /// Marks the env closed and releases its renderer (a later env of the same scene takes
    /// over its OpenGL context).
    fn close(&mut self) {
        self.phase = Phase::Closed;
        if let Some(rig) = &mut self.cameras {
            rig.release_renderer();
        }
    }

    fn rng(&self) -> Option<&EnvRng> {
        Some(&self.rng)
    }
}
