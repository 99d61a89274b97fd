//! robosuite's visual wrappers over a [`RobosuiteEnv`]: [`VisualizationWrapper`] (the
//! robots', grippers' and objects' sites, and indicator sites; see
//! [`RobosuiteEnv::visualize`]) and [`DomainRandomizationWrapper`] (robosuite's modders,
//! [`crate::modders`], run on reset and every few steps).
//!
//! Both are Gymnasium wrappers ([`gym_core::StepWrapper`]): `reset` and `step` do what
//! robosuite's do, everything else forwards to the env. A wrapper that refuses its
//! arguments returns the env untouched inside [`Refused`].
//!
//! ```no_run
//! use gym_core::{Env, Wrapper};
//! use robosuite_env::wrappers::{
//!     DomainRandomizationArgs, DomainRandomizationWrapper, IndicatorConfig,
//!     VisualizationWrapper,
//! };
//!
//! let mut env = VisualizationWrapper::new(
//!     robosuite_env::make("Lift")?,
//!     vec![IndicatorConfig::default_indicator(0)],
//! )?;
//! env.reset(Some(0), None)?;
//! env.set_indicator_pos("indicator0", [0.0, 0.1, 1.0])?;
//! env.set_visualization_setting("robots", false)?;
//!
//! let mut env = DomainRandomizationWrapper::new(
//!     env.into_inner(),
//!     DomainRandomizationArgs {
//!         seed: Some(0),
//!         ..Default::default()
//!     },
//! )?;
//! env.reset(Some(0), None)?; // a new look, new cameras, lights and dynamics
//! # Ok::<(), gym_core::Error>(())
//! ```

use crate::env::RobosuiteEnv;
use crate::modders::{
    CameraArgs, CameraModder, ColorArgs, DynamicsArgs, DynamicsModder, LightingArgs,
    LightingModder, TextureModder,
};
use gym_core::{
    DictValue, Env, EnvRng, Error, Info, ResetOptions, Result, Step, StepWrapper, Steps,
    Transition, Wrapper,
};
use mujoco_rs::wrappers::mj_model::MjtObjBase as mjtObj;
use ndarray::ArrayD;
use rand::{Rng, SeedableRng};

/// A wrapper's arguments refused: the error, and the env as it was given (unchanged).
#[derive(Debug)]
pub struct Refused {
    /// Why (an [`Error::InvalidArgument`] naming the argument).
    pub error: Error,
    /// The env, unchanged.
    pub env: Box<RobosuiteEnv>,
}

impl std::fmt::Display for Refused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.error.fmt(f)
    }
}

impl std::error::Error for Refused {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

impl From<Refused> for Error {
    fn from(r: Refused) -> Self {
        r.error
    }
}

// --- env.visualize --------------------------------------------------------------------

/// robosuite's visualization settings (`vis_settings`): whether the task objects'
/// (`env`), the robots' (`robots`) and the grippers' (`grippers`) sites are shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct VisualizationSettings {
    /// The task objects' sites.
    pub env: bool,
    /// The robots' sites.
    pub robots: bool,
    /// The grippers' sites (and the grip site coloured by its distance to the target).
    pub grippers: bool,
}

impl VisualizationSettings {
    /// robosuite's setting names, sorted (`get_visualization_settings`).
    pub const NAMES: [&'static str; 3] = ["env", "grippers", "robots"];

    /// Every setting `on`.
    pub const fn all(on: bool) -> Self {
        Self {
            env: on,
            robots: on,
            grippers: on,
        }
    }

    /// Sets the setting `name` (one of [`VisualizationSettings::NAMES`]).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for another name (nothing changed).
    pub fn set(&mut self, name: &str, visible: bool) -> Result<()> {
        match name {
            "env" => self.env = visible,
            "robots" => self.robots = visible,
            "grippers" => self.grippers = visible,
            _ => {
                return Err(Error::invalid_argument(
                    "setting",
                    format!(
                        "Invalid visualization setting specified. Valid options are {:?}, got {name}",
                        Self::NAMES
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// A target the grip site is coloured by: a body or a site.
#[derive(Debug, Clone, Copy)]
enum Target {
    Body(usize),
    Site(usize),
}

/// The sites one env's settings toggle, and its grip sites with their targets.
#[derive(Debug, Clone, Default)]
struct VisualSites {
    env: Vec<usize>,
    robots: Vec<usize>,
    grippers: Vec<usize>,
    /// Per coloured grip site: the targets (coloured by the closest).
    grips: Vec<(usize, Vec<Target>)>,
}

impl RobosuiteEnv {
    fn visual_sites(&self) -> VisualSites {
        let model = self.sim().model();
        let nsite = model.ffi().nsite.max(0) as usize;
        let site = |n: &str| {
            (!n.contains('\0'))
                .then(|| model.name_to_id(mjtObj::mjOBJ_SITE, n))
                .flatten()
        };
        let body = |n: &str| {
            (!n.contains('\0'))
                .then(|| model.name_to_id(mjtObj::mjOBJ_BODY, n))
                .flatten()
        };
        let prefixed = |prefix: &str| -> Vec<usize> {
            (0..nsite)
                .filter(|&i| {
                    model
                        .id_to_name(mjtObj::mjOBJ_SITE, i)
                        .is_some_and(|n| n.starts_with(prefix))
                })
                .collect()
        };
        let objects = self.mujoco_objects();
        let env = objects
            .iter()
            .flat_map(|o| o.sites.iter().filter_map(|s| site(s)))
            .collect();
        let mut robots = Vec::new();
        let mut grippers = Vec::new();
        for (i, robot) in self.robots().iter().enumerate() {
            robots.extend(prefixed(&format!("robot{i}_")));
            for arm in robot.arms() {
                if arm.gripper().has_gripper() {
                    grippers.extend(prefixed(&format!("gripper{i}_{}_", arm.side())));
                }
            }
        }
        // Each task's `visualize`: robot 0's grippers coloured by the distance to its target.
        let name = self.task_name().to_owned();
        let object = |n: &str| objects.iter().find(|o| o.name == n);
        let robot0_grips: Vec<usize> = self
            .robots()
            .first()
            .map(|r| {
                r.arms()
                    .iter()
                    .filter(|a| a.gripper().has_gripper())
                    .map(|a| a.eef_site())
                    .collect()
            })
            .unwrap_or_default();
        let to_all = |targets: Vec<Target>| -> Vec<(usize, Vec<Target>)> {
            if targets.is_empty() {
                return Vec::new();
            }
            robot0_grips.iter().map(|&g| (g, targets.clone())).collect()
        };
        let root = |n: &str| {
            object(n)
                .and_then(|o| body(&o.root_body))
                .map(Target::Body)
                .into_iter()
                .collect::<Vec<_>>()
        };
        let grips = match name.as_str() {
            "Lift" => to_all(root("cube")),
            "Stack" => to_all(root("cubeA")),
            "ToolHang" => to_all(root("tool")),
            "Door" if object("Door").is_some() => {
                to_all(site("Door_handle").map(Target::Site).into_iter().collect())
            }
            n if n.starts_with("NutAssembly") => to_all(
                objects
                    .iter()
                    .filter(|o| o.name.ends_with("Nut"))
                    .filter_map(|o| site(&format!("{}_handle_site", o.name)).map(Target::Site))
                    .collect(),
            ),
            n if n.starts_with("PickPlace") => to_all(
                objects
                    .iter()
                    .filter(|o| !o.name.starts_with("Visual"))
                    .filter_map(|o| body(&o.root_body).map(Target::Body))
                    .collect(),
            ),
            "TwoArmLift" if object("pot").is_some() => {
                let grips: Vec<usize> = if self.robots().len() == 1 {
                    robot0_grips.clone()
                } else {
                    self.robots()
                        .iter()
                        .filter_map(|r| r.arms().first())
                        .filter(|a| a.gripper().has_gripper())
                        .map(|a| a.eef_site())
                        .collect()
                };
                grips
                    .into_iter()
                    .zip(["pot_handle0", "pot_handle1"])
                    .filter_map(|(g, h)| site(h).map(|s| (g, vec![Target::Site(s)])))
                    .collect()
            }
            _ => Vec::new(),
        };
        VisualSites {
            env,
            robots,
            grippers,
            grips,
        }
    }

    fn apply_visualization(&mut self, sites: &VisualSites, settings: VisualizationSettings) {
        let model = self.sim_mut().model_mut();
        for (ids, on) in [
            (&sites.env, settings.env),
            (&sites.robots, settings.robots),
            (&sites.grippers, settings.grippers),
        ] {
            for &i in ids {
                let a = model.site_rgba()[i][3].abs();
                model.site_rgba_mut()[i][3] = if on { a } else { -a };
            }
        }
        if !settings.grippers {
            return;
        }
        let data = self.sim().data();
        let pos = |t: Target| match t {
            Target::Body(b) => data.xpos()[b],
            Target::Site(s) => data.site_xpos()[s],
        };
        let colours: Vec<(usize, [f32; 3])> = sites
            .grips
            .iter()
            .map(|(grip, targets)| {
                let g = data.site_xpos()[*grip];
                let sq = |t: Target| {
                    let p = pos(t);
                    (0..3).map(|k| (p[k] - g[k]).powi(2)).sum::<f64>()
                };
                let dist = targets.iter().map(|&t| sq(t)).fold(f64::INFINITY, f64::min);
                let scaled = (1.0 - (dist / 0.1).min(1.0)).powi(15);
                (*grip, [(1.0 - scaled) as f32, scaled as f32, 0.0])
            })
            .collect();
        let model = self.sim_mut().model_mut();
        for (grip, rgb) in colours {
            model.site_rgba_mut()[grip][..3].copy_from_slice(&rgb);
        }
    }

    /// robosuite's `visualize(vis_settings)`: shows or hides each setting's sites (the task
    /// objects' for `env`, the robots' for `robots`, the grippers' for `grippers`) by the
    /// sign of their alpha, and with `grippers` on colours robot 0's grip sites from red
    /// (far) to green (at the task's target: Lift's cube, Stack's cube A, the closest nut
    /// handle or object, the door handle, the tool, the pot handles), as robosuite's tasks
    /// do. The next reset hides them all again, as robosuite's reset does.
    pub fn visualize(&mut self, settings: VisualizationSettings) {
        let sites = self.visual_sites();
        self.apply_visualization(&sites, settings);
        self.set_visualized(true);
    }
}

// --- VisualizationWrapper -------------------------------------------------------------

/// MJCF `<site>` attributes an indicator may set besides its fields.
const SITE_ATTRIBUTES: [&str; 9] = [
    "class",
    "group",
    "quat",
    "axisangle",
    "xyaxes",
    "zaxis",
    "euler",
    "fromto",
    "material",
];
/// MJCF site types.
const SITE_TYPES: [&str; 5] = ["sphere", "capsule", "ellipsoid", "cylinder", "box"];

/// One indicator site (robosuite's indicator config): a site of its own body in the
/// world, at `pos`.
#[derive(Debug, Clone, PartialEq)]
pub struct IndicatorConfig {
    /// The site's name (its body is `{name}_body`).
    pub name: String,
    /// The MJCF site type (`None`: MuJoCo's default, a sphere).
    pub site_type: Option<String>,
    /// The site's size (1 to 3 values).
    pub size: Vec<f64>,
    /// The site's colour.
    pub rgba: [f64; 4],
    /// The body's position in the world.
    pub pos: [f64; 3],
    /// Other MJCF site attributes (`group`, `quat`, `material`, ...), as text.
    pub attributes: Vec<(String, String)>,
}

impl IndicatorConfig {
    /// A site `name` with robosuite's `new_site` defaults: size 0.005, red, at the origin.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            site_type: None,
            size: vec![0.005],
            rgba: [1.0, 0.0, 0.0, 1.0],
            pos: [0.0; 3],
            attributes: Vec::new(),
        }
    }

    /// robosuite's `"default"` indicator number `i`: `indicator{i}`, a red,
    /// half-transparent sphere of radius 3 cm.
    pub fn default_indicator(i: usize) -> Self {
        Self {
            site_type: Some("sphere".into()),
            size: vec![0.03],
            rgba: [1.0, 0.0, 0.0, 0.5],
            ..Self::new(format!("indicator{i}"))
        }
    }

    fn check(&self) -> Result<()> {
        let bad = |reason: String| Err(Error::invalid_argument("indicator_configs", reason));
        let n = &self.name;
        if n.is_empty() || n.contains('\0') {
            return bad("Name must be specified for all indicator object configurations!".into());
        }
        if let Some(t) = &self.site_type
            && !SITE_TYPES.contains(&t.as_str())
        {
            return bad(format!(
                "indicator `{n}`: type must be one of {SITE_TYPES:?}, got `{t}`"
            ));
        }
        if self.size.is_empty() || self.size.len() > 3 || self.size.iter().any(|v| !v.is_finite()) {
            return bad(format!(
                "indicator `{n}`: size must be 1 to 3 finite numbers, got {:?}",
                self.size
            ));
        }
        if self.size.iter().any(|&v| v < 0.0) {
            return bad(format!(
                "indicator `{n}`: size must not be negative, got {:?}",
                self.size
            ));
        }
        if self.rgba.iter().chain(&self.pos).any(|v| !v.is_finite()) {
            return bad(format!(
                "indicator `{n}`: rgba and pos must be finite numbers"
            ));
        }
        if let Some((k, _)) = self
            .attributes
            .iter()
            .find(|(k, v)| !SITE_ATTRIBUTES.contains(&k.as_str()) || v.contains('\0'))
        {
            return bad(format!(
                "indicator `{n}`: unknown site attribute `{k}`; valid: name, type, size, rgba, pos, {}",
                SITE_ATTRIBUTES.join(", ")
            ));
        }
        Ok(())
    }
}

fn join(v: &[f64]) -> String {
    v.iter().map(f64::to_string).collect::<Vec<_>>().join(" ")
}

/// `xml` with each indicator (a body holding its site) added to the worldbody.
fn add_indicators(xml: &str, indicators: &[IndicatorConfig]) -> Result<String> {
    use xmltree::{Element, XMLNode};
    let mut root = Element::parse(xml.as_bytes())
        .map_err(|e| Error::model(format!("cannot parse the scene: {e}")))?;
    let world = root
        .get_mut_child("worldbody")
        .ok_or_else(|| Error::model("the scene has no worldbody"))?;
    for c in indicators {
        let mut site = Element::new("site");
        site.attributes.insert("name".into(), c.name.clone());
        if let Some(t) = &c.site_type {
            site.attributes.insert("type".into(), t.clone());
        }
        site.attributes.insert("pos".into(), "0 0 0".into());
        site.attributes.insert("size".into(), join(&c.size));
        site.attributes.insert("rgba".into(), join(&c.rgba));
        for (k, v) in &c.attributes {
            site.attributes.insert(k.clone(), v.clone());
        }
        let mut body = Element::new("body");
        body.attributes
            .insert("name".into(), format!("{}_body", c.name));
        body.attributes.insert("pos".into(), join(&c.pos));
        body.children.push(XMLNode::Element(site));
        world.children.push(XMLNode::Element(body));
    }
    let mut out = Vec::new();
    root.write(&mut out)
        .map_err(|e| Error::model(format!("cannot write the scene: {e}")))?;
    String::from_utf8(out).map_err(|e| Error::model(e.to_string()))
}

/// robosuite's `VisualizationWrapper`: applies its visualization settings (all on at
/// first; see [`RobosuiteEnv::visualize`]) after every reset and step, and adds indicator
/// sites to the scene (the env is reloaded from its scene with them, see
/// [`RobosuiteEnv::reset_from_xml_string`]), moved with
/// [`VisualizationWrapper::set_indicator_pos`]. A reset puts the indicators back at their
/// configured positions, as robosuite's reload does.
#[derive(Debug)]
pub struct VisualizationWrapper {
    env: RobosuiteEnv,
    indicators: Vec<IndicatorConfig>,
    /// Per indicator: its body.
    indicator_bodies: Vec<usize>,
    settings: VisualizationSettings,
    sites: VisualSites,
    /// The model the cached sites belong to (its buffer).
    sites_of: usize,
}

impl VisualizationWrapper {
    /// Wraps `env`, adding `indicator_configs` (none: no reload).
    ///
    /// # Errors
    /// [`Refused`] (with the env unchanged) holding [`Error::InvalidArgument`] for an env
    /// with camera segmentations, an indicator without a name, an unknown site type or
    /// attribute, sizes or colours that are not finite, negative sizes, two indicators of
    /// one name or a name the scene already uses; [`Error::Model`] when the scene with the
    /// indicators cannot be loaded.
    pub fn new(
        mut env: RobosuiteEnv,
        indicator_configs: Vec<IndicatorConfig>,
    ) -> std::result::Result<Self, Refused> {
        if let Err(error) = Self::check(&env, &indicator_configs) {
            return Err(Refused {
                error,
                env: Box::new(env),
            });
        }
        if !indicator_configs.is_empty() {
            let loaded = add_indicators(env.source_xml(), &indicator_configs)
                .and_then(|xml| env.reset_from_xml_string(&xml));
            if let Err(error) = loaded {
                return Err(Refused {
                    error,
                    env: Box::new(env),
                });
            }
        }
        let model = env.sim().model();
        let indicator_bodies = indicator_configs
            .iter()
            .filter_map(|c| model.name_to_id(mjtObj::mjOBJ_BODY, &format!("{}_body", c.name)))
            .collect();
        let mut wrapper = Self {
            env,
            indicators: indicator_configs,
            indicator_bodies,
            settings: VisualizationSettings::all(true),
            sites: VisualSites::default(),
            sites_of: 0,
        };
        wrapper.show_indicators();
        Ok(wrapper)
    }

    fn check(env: &RobosuiteEnv, configs: &[IndicatorConfig]) -> Result<()> {
        let cams = &env.config().cameras;
        if cams.use_camera_obs && !cams.camera_segmentations.iter().all(Vec::is_empty) {
            return Err(Error::invalid_argument(
                "env",
                "Cannot use camera segmentations with visualization wrapper!",
            ));
        }
        let model = env.sim().model();
        for (i, c) in configs.iter().enumerate() {
            c.check()?;
            if configs[..i].iter().any(|o| o.name == c.name) {
                return Err(Error::invalid_argument(
                    "indicator_configs",
                    format!(
                        "indicator names must be distinct, `{}` is given twice",
                        c.name
                    ),
                ));
            }
            if model.name_to_id(mjtObj::mjOBJ_SITE, &c.name).is_some()
                || model
                    .name_to_id(mjtObj::mjOBJ_BODY, &format!("{}_body", c.name))
                    .is_some()
            {
                return Err(Error::invalid_argument(
                    "indicator_configs",
                    format!("indicator `{}`: the scene has a site of that name", c.name),
                ));
            }
        }
        Ok(())
    }

    /// The indicators' alphas made positive (the scene's sites start hidden) and their
    /// bodies at the configured positions.
    fn show_indicators(&mut self) {
        let model = self.env.sim_mut().model_mut();
        for (c, &b) in self.indicators.iter().zip(&self.indicator_bodies) {
            model.body_pos_mut()[b] = c.pos;
            if let Some(s) = model.name_to_id(mjtObj::mjOBJ_SITE, &c.name) {
                let a = model.site_rgba()[s][3].abs();
                model.site_rgba_mut()[s][3] = a;
            }
        }
    }

    /// The indicators' names (robosuite's `get_indicator_names`).
    pub fn get_indicator_names(&self) -> Vec<&str> {
        self.indicators.iter().map(|c| c.name.as_str()).collect()
    }

    /// Moves `indicator` to world position `pos` (shown from the next `mj_forward` or step).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown indicator or a position that is not
    /// finite (nothing changed).
    pub fn set_indicator_pos(&mut self, indicator: &str, pos: [f64; 3]) -> Result<()> {
        let Some(i) = self.indicators.iter().position(|c| c.name == indicator) else {
            return Err(Error::invalid_argument(
                "indicator",
                format!(
                    "Invalid indicator name specified. Valid options are {:?}, got {indicator}",
                    self.get_indicator_names()
                ),
            ));
        };
        if pos.iter().any(|v| !v.is_finite()) {
            return Err(Error::invalid_argument(
                "pos",
                format!("pos must be 3 finite numbers, got {pos:?}"),
            ));
        }
        let b = self.indicator_bodies[i];
        self.env.sim_mut().model_mut().body_pos_mut()[b] = pos;
        Ok(())
    }

    /// The settings' names (robosuite's `get_visualization_settings`).
    pub fn get_visualization_settings(&self) -> [&'static str; 3] {
        VisualizationSettings::NAMES
    }

    /// The current settings.
    pub fn visualization_settings(&self) -> VisualizationSettings {
        self.settings
    }

    /// Shows (`visible`) or hides the sites of `setting` from the next step or reset.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for an unknown setting (nothing changed).
    pub fn set_visualization_setting(&mut self, setting: &str, visible: bool) -> Result<()> {
        self.settings.set(setting, visible)
    }

    /// Applies the settings (the site lists are found once per model).
    fn apply(&mut self) {
        let of = self.env.sim().model().ffi().buffer as usize;
        if of != self.sites_of {
            self.sites = self.env.visual_sites();
            self.sites_of = of;
        }
        self.env.apply_visualization(&self.sites, self.settings);
        self.env.set_visualized(true);
    }
}

impl Wrapper for VisualizationWrapper {
    type Inner = RobosuiteEnv;
    type Kind = Steps;

    fn inner(&self) -> &RobosuiteEnv {
        &self.env
    }

    fn inner_mut(&mut self) -> &mut RobosuiteEnv {
        &mut self.env
    }

    fn into_inner(self) -> RobosuiteEnv {
        self.env
    }
}

impl StepWrapper for VisualizationWrapper {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        let out = this.env.reset(seed, options)?;
        this.show_indicators();
        this.env.sim_mut().forward()?;
        this.apply();
        Ok(out)
    }

    fn step(this: &mut Self, action: &ArrayD<f64>) -> Result<Step<DictValue>> {
        let step = this.env.step(action)?;
        this.apply();
        Ok(step)
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f64>,
        observation: &mut DictValue,
        info: &mut Info,
    ) -> Result<Transition> {
        let t = this.env.step_into(action, observation, info)?;
        this.apply();
        Ok(t)
    }
}

// --- DomainRandomizationWrapper -------------------------------------------------------

/// robosuite's `DomainRandomizationWrapper` arguments (its defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct DomainRandomizationArgs {
    /// The randomization RNG's seed; `None`: a stream drawn from the env's RNG at every
    /// reset (so the env's seed decides it).
    pub seed: Option<u64>,
    /// Randomize colours and textures ([`TextureModder`]).
    pub randomize_color: bool,
    /// Randomize cameras ([`CameraModder`]).
    pub randomize_camera: bool,
    /// Randomize lights ([`LightingModder`]).
    pub randomize_lighting: bool,
    /// Randomize dynamics ([`DynamicsModder`]).
    pub randomize_dynamics: bool,
    /// The texture modder's arguments.
    pub color_randomization_args: ColorArgs,
    /// The camera modder's arguments.
    pub camera_randomization_args: CameraArgs,
    /// The lighting modder's arguments.
    pub lighting_randomization_args: LightingArgs,
    /// The dynamics modder's arguments.
    pub dynamics_randomization_args: DynamicsArgs,
    /// Randomize at every reset.
    pub randomize_on_reset: bool,
    /// Randomize before every n-th step of an episode (0: never).
    pub randomize_every_n_steps: u64,
}

impl Default for DomainRandomizationArgs {
    fn default() -> Self {
        Self {
            seed: None,
            randomize_color: true,
            randomize_camera: true,
            randomize_lighting: true,
            randomize_dynamics: true,
            color_randomization_args: ColorArgs::default(),
            camera_randomization_args: CameraArgs::default(),
            lighting_randomization_args: LightingArgs::default(),
            dynamics_randomization_args: DynamicsArgs::default(),
            randomize_on_reset: true,
            randomize_every_n_steps: 1,
        }
    }
}

/// Mixed into the env's next draw to make the randomization stream's seed.
const STREAM_SALT: u64 = 0x9E37_79B9_7F4A_7C15;

/// robosuite's `DomainRandomizationWrapper`: runs the enabled modders (colour, camera,
/// lighting, dynamics, in that order) on each reset (`randomize_on_reset`, after saving
/// the reset's values as the defaults) and before every `randomize_every_n_steps`-th step,
/// each time from the defaults. Before each reset the defaults are written back, so the
/// env resets from its own model. Changed textures are uploaded to the env's render
/// contexts, so camera observations and `RobosuiteEnv::render_camera` show them.
///
/// Draws come from an [`EnvRng`] seeded by `seed`, or without one from the env's RNG at
/// every reset (the env's own stream is not advanced): the same seed gives the same
/// domain, frames and dynamics. Only this env's model changes.
#[derive(Debug)]
pub struct DomainRandomizationWrapper {
    env: RobosuiteEnv,
    args: DomainRandomizationArgs,
    rng: EnvRng,
    texture: Option<TextureModder>,
    camera: Option<CameraModder>,
    lighting: Option<LightingModder>,
    dynamics: Option<DynamicsModder>,
    step_counter: u64,
}

/// The texture, camera, lighting and dynamics modders of a [`DomainRandomizationWrapper`].
type Modders = (
    Option<TextureModder>,
    Option<CameraModder>,
    Option<LightingModder>,
    Option<DynamicsModder>,
);

impl DomainRandomizationWrapper {
    /// Wraps `env`, making (and checking) every enabled modder on its model. With colour
    /// randomisation, an env built without texture images loads them once the arguments
    /// are checked ([`RobosuiteEnv::load_textures`]).
    ///
    /// # Errors
    /// [`Refused`] (with the env unchanged) holding [`Error::InvalidArgument`] for any
    /// modder argument its `new` refuses (unknown names, negative or non-finite
    /// perturbations, ...), or the error of [`RobosuiteEnv::load_textures`].
    pub fn new(
        mut env: RobosuiteEnv,
        args: DomainRandomizationArgs,
    ) -> std::result::Result<Self, Refused> {
        let made = Self::modders(&env, &args);
        // Colour randomisation rewrites texture images: an env built without them (see
        // `RobosuiteEnv::textures_loaded`) loads them once every argument is checked, and
        // its texture modder is made on the model with them.
        let made = match made {
            Ok(m) if args.randomize_color && !env.textures_loaded() => env
                .load_textures()
                .and_then(|()| {
                    TextureModder::new(env.sim().model(), args.color_randomization_args.clone())
                })
                .map(|texture| (Some(texture), m.1, m.2, m.3)),
            other => other,
        };
        let (texture, camera, lighting, dynamics) = match made {
            Ok(m) => m,
            Err(error) => {
                return Err(Refused {
                    error,
                    env: Box::new(env),
                });
            }
        };
        let rng = match args.seed {
            Some(seed) => gym_core::rng_from_seed(seed),
            None => Self::stream_of(&env),
        };
        Ok(Self {
            env,
            args,
            rng,
            texture,
            camera,
            lighting,
            dynamics,
            step_counter: 0,
        })
    }

    /// The modders `args` enables, made on `env`'s model.
    fn modders(env: &RobosuiteEnv, args: &DomainRandomizationArgs) -> Result<Modders> {
        let model = env.sim().model();
        Ok((
            args.randomize_color
                .then(|| TextureModder::new(model, args.color_randomization_args.clone()))
                .transpose()?,
            args.randomize_camera
                .then(|| CameraModder::new(model, args.camera_randomization_args.clone()))
                .transpose()?,
            args.randomize_lighting
                .then(|| LightingModder::new(model, args.lighting_randomization_args.clone()))
                .transpose()?,
            args.randomize_dynamics
                .then(|| DynamicsModder::new(model, args.dynamics_randomization_args.clone()))
                .transpose()?,
        ))
    }

    /// A stream drawn from the env's RNG without advancing it.
    fn stream_of(env: &RobosuiteEnv) -> EnvRng {
        let (mut rng, _) = env.rng_state();
        EnvRng::seed_from_u64(rng.next_u64() ^ STREAM_SALT)
    }

    /// The arguments.
    pub fn args(&self) -> &DomainRandomizationArgs {
        &self.args
    }

    /// The texture modder (with `randomize_color`).
    pub fn texture_modder(&self) -> Option<&TextureModder> {
        self.texture.as_ref()
    }

    /// The camera modder (with `randomize_camera`).
    pub fn camera_modder(&self) -> Option<&CameraModder> {
        self.camera.as_ref()
    }

    /// The lighting modder (with `randomize_lighting`).
    pub fn light_modder(&self) -> Option<&LightingModder> {
        self.lighting.as_ref()
    }

    /// The dynamics modder (with `randomize_dynamics`).
    pub fn dynamics_modder(&self) -> Option<&DynamicsModder> {
        self.dynamics.as_ref()
    }

    /// Steps counted since the last reset.
    pub fn step_counter(&self) -> u64 {
        self.step_counter
    }

    /// Runs every enabled modder once (robosuite's `randomize_domain`), uploads the
    /// changed textures, then `mj_forward`.
    ///
    /// # Errors
    /// [`Error::Simulation`] when MuJoCo raises an error; [`Error::Render`] when a texture
    /// cannot be uploaded; [`Error::Closed`] after `close`.
    pub fn randomize_domain(&mut self) -> Result<()> {
        let sim = self.env.sim_mut();
        let changed = match &self.texture {
            Some(t) => t.randomize(sim, &mut self.rng),
            None => Vec::new(),
        };
        if let Some(c) = &self.camera {
            c.randomize(sim, &mut self.rng);
        }
        if let Some(l) = &self.lighting {
            l.randomize(sim, &mut self.rng);
        }
        match &self.dynamics {
            Some(d) => d.randomize(sim, &mut self.rng)?,
            None => sim.forward()?,
        }
        self.upload(&changed)
    }

    #[cfg(feature = "render")]
    fn upload(&mut self, textures: &[usize]) -> Result<()> {
        for &t in textures {
            self.env.upload_texture(t)?;
        }
        Ok(())
    }

    #[cfg(not(feature = "render"))]
    #[allow(clippy::unused_self, clippy::unnecessary_wraps)]
    fn upload(&mut self, _textures: &[usize]) -> Result<()> {
        Ok(())
    }

    /// Saves the model's current values as every modder's defaults (robosuite's
    /// `save_default_domain`).
    pub fn save_default_domain(&mut self) {
        let model = self.env.sim().model();
        if let Some(t) = &mut self.texture {
            t.save_defaults(model);
        }
        if let Some(c) = &mut self.camera {
            c.save_defaults(model);
        }
        if let Some(l) = &mut self.lighting {
            l.save_defaults(model);
        }
        if let Some(d) = &mut self.dynamics {
            d.save_defaults(model);
        }
    }

    /// Writes every modder's defaults back (robosuite's `restore_default_domain`) and
    /// uploads the textures.
    ///
    /// # Errors
    /// As [`DomainRandomizationWrapper::randomize_domain`].
    pub fn restore_default_domain(&mut self) -> Result<()> {
        self.restore(true)
    }

    /// [`DomainRandomizationWrapper::restore_default_domain`]; `upload = false` leaves the
    /// render contexts' textures as they are (for a randomization that follows at once).
    fn restore(&mut self, upload: bool) -> Result<()> {
        let sim = self.env.sim_mut();
        let changed = match &self.texture {
            Some(t) => t.restore_defaults(sim),
            None => Vec::new(),
        };
        if let Some(c) = &self.camera {
            c.restore_defaults(sim);
        }
        if let Some(l) = &self.lighting {
            l.restore_defaults(sim);
        }
        if let Some(d) = &self.dynamics {
            d.restore_defaults(sim)?;
        }
        if upload {
            self.upload(&changed)?;
        }
        Ok(())
    }

    /// Counts a step and randomizes on every `randomize_every_n_steps`-th (robosuite's
    /// `step_randomization`).
    ///
    /// # Errors
    /// As [`DomainRandomizationWrapper::randomize_domain`].
    pub fn step_randomization(&mut self) -> Result<()> {
        let n = self.args.randomize_every_n_steps;
        if n > 0 && self.step_counter.is_multiple_of(n) {
            self.randomize_domain()?;
        }
        self.step_counter += 1;
        Ok(())
    }
}

impl Wrapper for DomainRandomizationWrapper {
    type Inner = RobosuiteEnv;
    type Kind = Steps;

    fn inner(&self) -> &RobosuiteEnv {
        &self.env
    }

    fn inner_mut(&mut self) -> &mut RobosuiteEnv {
        &mut self.env
    }

    fn into_inner(self) -> RobosuiteEnv {
        self.env
    }
}

impl StepWrapper for DomainRandomizationWrapper {
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        // The textures are uploaded once, after the randomization, when one follows: the
        // frames the env's reset draws in between are replaced.
        let randomizes_textures = this.args.randomize_on_reset && this.texture.is_some();
        this.restore(!randomizes_textures)?;
        let (obs, info) = this.env.reset(seed, options)?;
        this.save_default_domain();
        this.step_counter = 0;
        if this.args.seed.is_none() {
            this.rng = DomainRandomizationWrapper::stream_of(&this.env);
        }
        if !this.args.randomize_on_reset {
            return Ok((obs, info));
        }
        this.randomize_domain()?;
        let obs = this.env.update_observations()?;
        Ok((obs, info))
    }

    fn step(this: &mut Self, action: &ArrayD<f64>) -> Result<Step<DictValue>> {
        this.step_randomization()?;
        this.env.step(action)
    }

    fn step_into(
        this: &mut Self,
        action: &ArrayD<f64>,
        observation: &mut DictValue,
        info: &mut Info,
    ) -> Result<Transition> {
        this.step_randomization()?;
        this.env.step_into(action, observation, info)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indicators_are_added_to_the_worldbody() {
        let xml = "<mujoco><worldbody><geom size=\"1\"/></worldbody></mujoco>";
        let mut marker = IndicatorConfig::new("marker");
        marker.site_type = Some("box".into());
        marker.pos = [0.1, -0.1, 1.0];
        marker.attributes.push(("group".into(), "1".into()));
        let out = add_indicators(xml, &[IndicatorConfig::default_indicator(0), marker]).unwrap();
        assert!(
            out.contains("<body name=\"indicator0_body\" pos=\"0 0 0\">"),
            "{out}"
        );
        assert!(out.contains("rgba=\"1 0 0 0.5\""), "{out}");
        assert!(
            out.contains("<body name=\"marker_body\" pos=\"0.1 -0.1 1\">"),
            "{out}"
        );
        assert!(out.contains("group=\"1\""), "{out}");
    }

    #[test]
    fn settings_by_name() {
        let mut s = VisualizationSettings::all(false);
        s.set("robots", true).unwrap();
        assert_eq!(
            s,
            VisualizationSettings {
                env: false,
                robots: true,
                grippers: false
            }
        );
        let err = s.set("walls", true).unwrap_err();
        assert!(
            err.to_string().contains("Invalid visualization setting"),
            "{err}"
        );
        assert!(s.robots && !s.env);
    }
}
