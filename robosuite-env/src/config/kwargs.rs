//! robosuite's `make` keyword arguments, declared once.
//!
//! [`Kwargs`] is the schema: every argument robosuite's `suite.make` takes that is not a
//! task's own, by robosuite's name, with robosuite's value types (a name or a list of
//! names, a dict, `None`), deserialized with serde from JSON values. Python's `make`, the
//! Gymnasium ids, the vector envs, the pool and Rust's [`gym_core::registry`] all read
//! their keyword arguments through [`EnvConfig::from_kwargs`]; [`kwarg_names`] is the
//! list they export. The tasks' own arguments (Lift's `table_full_size`, Door's
//! `use_latch`, ...) are the keys left over, checked against the task
//! ([`TaskSpec::options`](crate::tasks::TaskSpec::options)).

use super::{EnvConfig, EnvConfiguration};
use crate::cameras::{ImageConvention, RenderQuality, Segmentation};
use crate::controllers::ControllerConfig;
use crate::controllers::config::load_part_controller_config;
use crate::models::robots::GripperChoice;
use crate::robots::{InitNoise, NoiseKind};
use gym_core::{Error, RenderMode, Result};
use serde::de::{DeserializeOwned, Error as _};
use serde::{Deserialize, Deserializer};
use serde_json::{Map, Value};

/// robosuite's `make` arguments common to every task (see the module docs). Absent
/// arguments keep [`EnvConfig::default`]'s values, except `has_offscreen_renderer`, whose
/// default is robosuite's (`True`).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct Kwargs {
    /// A robot name or one per robot (robosuite's `_input2list`); `None`: a Panda each.
    #[serde(default, deserialize_with = "one_or_many")]
    robots: Option<Vec<String>>,
    env_configuration: Option<String>,
    /// A gripper name, `"default"` or `None` (no gripper), or one per robot.
    #[serde(default, deserialize_with = "one_or_many")]
    gripper_types: Option<Vec<Option<String>>>,
    /// A base name or `"default"`, or one per robot.
    #[serde(default, deserialize_with = "one_or_many")]
    base_types: Option<Vec<Option<String>>>,
    /// robosuite's `mount_types` (robosuite 1.4's name): `"default"` only.
    #[serde(default, deserialize_with = "one_or_many")]
    mount_types: Option<Vec<String>>,
    /// A composite or part config dict, or a list of one per robot.
    controller_configs: Option<Value>,
    /// A part controller type (`"OSC_POSITION"`) for every robot: a shortcut for
    /// `controller_configs=load_part_controller_config(default_controller=...)`.
    controller: Option<String>,
    /// `"default"`, `None` or `{"magnitude": m, "type": "gaussian" | "uniform"}`.
    #[serde(default, deserialize_with = "present")]
    initialization_noise: Option<Value>,
    horizon: Option<u64>,
    control_freq: Option<f64>,
    /// A number, or `None` for unnormalised rewards.
    #[serde(default, deserialize_with = "present")]
    reward_scale: Option<Option<f64>>,
    reward_shaping: Option<bool>,
    ignore_done: Option<bool>,
    use_object_obs: Option<bool>,
    seed: Option<u64>,
    lite_physics: Option<bool>,
    use_camera_obs: Option<bool>,
    has_offscreen_renderer: Option<bool>,
    #[serde(default, deserialize_with = "one_or_many")]
    camera_names: Option<Vec<String>>,
    #[serde(default, deserialize_with = "one_or_many")]
    camera_heights: Option<Vec<usize>>,
    #[serde(default, deserialize_with = "one_or_many")]
    camera_widths: Option<Vec<usize>>,
    /// A bool or one per camera; `None` is `False` (robomimic passes it).
    #[serde(default, deserialize_with = "one_or_many")]
    camera_depths: Option<Vec<Option<bool>>>,
    /// `None`, a level, levels for every camera, or one list (or `None`) per camera.
    #[serde(default, deserialize_with = "present")]
    camera_segmentations: Option<Value>,
    /// A camera name, `None` (robosuite's free camera; frames keep the default
    /// `frontview`) or, for the `"mujoco"` viewer, a list of names shown side by side
    /// (frames draw the first).
    #[serde(default, deserialize_with = "one_or_many")]
    render_camera: Option<Vec<Option<String>>>,
    /// Gymnasium's render mode: `"rgb_array"`, `"depth_array"` or `None`.
    #[serde(default, deserialize_with = "present")]
    render_mode: Option<Option<String>>,
    render_height: Option<usize>,
    render_width: Option<usize>,
    /// robosuite's `macros.IMAGE_CONVENTION`: `"opengl"` or `"opencv"`.
    image_convention: Option<String>,
    /// robosuite's on-screen viewer window, opened by the Python package (`env.render()`)
    /// and by the `view` example; the Rust env itself draws no window.
    has_renderer: Option<bool>,
    /// robosuite's viewer kind, any case: `"mjviewer"` (MuJoCo's interactive viewer, the
    /// default) or `"mujoco"` (an OpenCV window over offscreen frames, which turns the
    /// offscreen renderer on).
    renderer: Option<String>,
    /// robosuite's viewer settings: `None` or `{"cam_config": None | {"lookat": [x, y, z],
    /// "distance": d, "azimuth": a, "elevation": e}}` (the mjviewer's free camera).
    #[serde(default, deserialize_with = "present")]
    renderer_config: Option<Value>,
    /// `False` only.
    render_collision_mesh: Option<bool>,
    /// `True` only.
    render_visual_mesh: Option<bool>,
    /// The EGL device frames are drawn on, an index in EGL's device order (`-1`:
    /// `MUJOCO_EGL_DEVICE_ID` if set, else the first device that opens); an index that
    /// does not exist is an error when the renderer opens, listing the devices.
    render_gpu_device_id: Option<i64>,
    /// How frames are drawn: `"fast"` (default) or `"robosuite"` ([`RenderQuality`]).
    render_quality: Option<String>,
    /// robosuite's model reloading on reset: no effect (resets here never recompile).
    #[allow(dead_code)] // taken for robosuite's signature; nothing reads it
    hard_reset: Option<bool>,
}

/// Every keyword argument [`EnvConfig::from_kwargs`] takes besides the tasks' own, in the
/// order of the schema.
pub fn kwarg_names() -> &'static [&'static str] {
    serde_aux::serde_introspection::serde_introspect::<Kwargs>()
}

/// `T`, present (so `None` in the input is `Some(None)` for `Option<Option<_>>`).
fn present<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    d: D,
) -> std::result::Result<Option<T>, D::Error> {
    T::deserialize(d).map(Some)
}

/// One value or a list of them (robosuite's `_input2list`), as a list.
fn one_or_many<'de, D: Deserializer<'de>, T: DeserializeOwned>(
    d: D,
) -> std::result::Result<Option<Vec<T>>, D::Error> {
    match Value::deserialize(d)? {
        Value::Array(items) => items
            .into_iter()
            .enumerate()
            .map(|(i, v)| {
                serde_json::from_value(v).map_err(|e| D::Error::custom(format!("[{i}]: {e}")))
            })
            .collect::<std::result::Result<_, _>>()
            .map(Some),
        one => serde_json::from_value(one)
            .map(|v| Some(vec![v]))
            .map_err(|e| D::Error::custom(format!("{e} (or a list of them)"))),
    }
}

impl EnvConfig {
    /// A configuration from robosuite's `make` keyword arguments for the task `env_name`:
    /// the arguments of [`kwarg_names`] with robosuite's value types (`robots="Panda"` or
    /// `["Panda", "Sawyer"]`, `initialization_noise=None`, a `controller_configs` dict, ...)
    /// and the task's own arguments, which become [`EnvConfig::task_options`].
    ///
    /// ```
    /// use robosuite_env::EnvConfig;
    /// let kwargs = serde_json::json!({"robots": ["Sawyer"], "horizon": 200, "use_latch": false});
    /// let config = EnvConfig::from_kwargs("Door", kwargs.as_object().unwrap())?;
    /// assert_eq!((config.robots[0].as_str(), config.horizon), ("Sawyer", 200));
    /// assert_eq!(config.task_options["use_latch"], false);
    /// # Ok::<(), gym_core::Error>(())
    /// ```
    ///
    /// # Errors
    /// [`Error::UnknownEnv`] for an unknown task; [`Error::UnknownKey`] for an argument
    /// that is neither robosuite's nor the task's (listing both);
    /// [`Error::InvalidArgument`] naming the argument (and item) of the wrong type or out of
    /// range, or a robosuite setting this build does not have (collision meshes).
    pub fn from_kwargs(env_name: &str, kwargs: &Map<String, Value>) -> Result<Self> {
        let names = kwarg_names();
        let mut own = Map::new();
        let mut task_options = Map::new();
        for (key, value) in kwargs {
            if names.contains(&key.as_str()) {
                own.insert(key.clone(), value.clone());
            } else {
                task_options.insert(key.clone(), value.clone());
            }
        }
        if !task_options.is_empty() {
            let task = crate::registry::make_task(env_name)?.options();
            if let Some(unknown) = task_options.keys().find(|k| !task.contains_key(*k)) {
                return Err(Error::UnknownKey {
                    key: unknown.clone(),
                    available: names
                        .iter()
                        .map(|s| (*s).to_owned())
                        .chain(task.keys().cloned())
                        .collect(),
                });
            }
        }
        let kwargs: Kwargs = serde_path_to_error::deserialize(Value::Object(own)).map_err(|e| {
            let path = e.path().to_string();
            let name = path.split(['.', '[']).next().unwrap_or_default().to_owned();
            let inner = e.into_inner().to_string();
            let reason = match path.strip_prefix(name.as_str()) {
                Some(rest) if !rest.is_empty() => format!("{rest}: {inner}"),
                _ => inner,
            };
            Error::invalid_argument(
                if name.is_empty() || name == "." {
                    "kwargs".into()
                } else {
                    name
                },
                reason,
            )
        })?;
        let mut config = kwargs.into_config()?;
        config.task_options = task_options;
        config.validate()?;
        Ok(config)
    }
}

impl Kwargs {
    fn into_config(self) -> Result<EnvConfig> {
        check_compat(&self)?;
        let mut c = EnvConfig::default();
        c.cameras.has_offscreen_renderer = true;
        if let Some(robots) = self.robots {
            c.robots = robots;
        }
        if let Some(name) = &self.env_configuration {
            c.env_configuration = EnvConfiguration::parse(name)?;
        }
        if let Some(grippers) = self.gripper_types {
            c.gripper_types = grippers
                .into_iter()
                .map(|g| match g.as_deref() {
                    None => GripperChoice::None,
                    Some("default") => GripperChoice::Default,
                    Some(name) => GripperChoice::Named(name.to_owned()),
                })
                .collect();
        }
        if let Some(bases) = self.base_types {
            c.base_types = bases
                .into_iter()
                .map(|b| b.filter(|name| name != "default"))
                .collect();
        }
        if let Some(value) = &self.controller_configs {
            c.controller_configs = controller_configs(value)?;
        }
        if let Some(kind) = &self.controller {
            let assets = crate::assets::Assets::locate()?;
            let part = load_part_controller_config(&assets, kind)?;
            c.controller_configs = vec![ControllerConfig::from_value(&part, "controller_configs")?];
        }
        if let Some(noise) = &self.initialization_noise {
            c.initialization_noise = initialization_noise(noise)?;
        }
        c.horizon = self.horizon.unwrap_or(c.horizon);
        c.control_freq = self.control_freq.unwrap_or(c.control_freq);
        c.reward_scale = self.reward_scale.unwrap_or(c.reward_scale);
        c.reward_shaping = self.reward_shaping.or(c.reward_shaping);
        c.ignore_done = self.ignore_done.unwrap_or(c.ignore_done);
        c.use_object_obs = self.use_object_obs.unwrap_or(c.use_object_obs);
        c.seed = self.seed;
        c.lite_physics = self.lite_physics.unwrap_or(c.lite_physics);
        let cams = &mut c.cameras;
        cams.use_camera_obs = self.use_camera_obs.unwrap_or(cams.use_camera_obs);
        cams.has_offscreen_renderer = self
            .has_offscreen_renderer
            .unwrap_or(cams.has_offscreen_renderer);
        if let Some(names) = self.camera_names {
            cams.camera_names = names;
        }
        if let Some(h) = self.camera_heights {
            cams.camera_heights = h;
        }
        if let Some(w) = self.camera_widths {
            cams.camera_widths = w;
        }
        if let Some(depths) = self.camera_depths {
            cams.camera_depths = depths.into_iter().map(|d| d.unwrap_or(false)).collect();
        }
        if let Some(segs) = &self.camera_segmentations {
            cams.camera_segmentations = segmentations(segs)?;
        }
        if let Some(camera) = self.render_camera.into_iter().flatten().flatten().next() {
            cams.render_camera = camera;
        }
        if self.has_renderer == Some(true) && renderer_name(self.renderer.as_deref())? == "mujoco" {
            // robosuite's OpenCV viewer shows offscreen frames.
            cams.has_offscreen_renderer = true;
        }
        if let Some(mode) = self.render_mode {
            cams.render_mode = mode.as_deref().map(render_mode).transpose()?;
        }
        if let Some(id) = self.render_gpu_device_id {
            cams.render_gpu_device_id = usize::try_from(id).ok();
        }
        cams.render_height = self.render_height.unwrap_or(cams.render_height);
        cams.render_width = self.render_width.unwrap_or(cams.render_width);
        if let Some(quality) = self.render_quality.as_deref() {
            cams.render_quality = RenderQuality::parse(quality)?;
        }
        if let Some(convention) = self.image_convention.as_deref() {
            cams.image_convention = match convention {
                "opengl" => ImageConvention::OpenGl,
                "opencv" => ImageConvention::OpenCv,
                other => {
                    return Err(Error::invalid_argument(
                        "image_convention",
                        format!("unknown convention `{other}`; valid: opengl, opencv"),
                    ));
                }
            };
        }
        Ok(c)
    }
}

/// robosuite's arguments of its viewer and GPU choice that are taken only with the values
/// this build honours.
fn check_compat(k: &Kwargs) -> Result<()> {
    let renderer = renderer_name(k.renderer.as_deref())?;
    if let Some(cameras) = &k.render_camera {
        if cameras.is_empty() {
            return Err(Error::invalid_argument(
                "render_camera",
                "give a camera name, None or a list of camera names",
            ));
        }
        if cameras.len() > 1 && (renderer == "mjviewer" || cameras.iter().any(Option::is_none)) {
            return Err(Error::invalid_argument(
                "render_camera",
                "a list of cameras is shown by renderer=\"mujoco\" only, and holds names \
                 (mjviewer shows one camera)",
            ));
        }
    }
    if let Some(config) = &k.renderer_config {
        check_renderer_config(config)?;
    }
    let fixed = [
        (
            "render_collision_mesh",
            k.render_collision_mesh == Some(true),
            "False",
        ),
        (
            "render_visual_mesh",
            k.render_visual_mesh == Some(false),
            "True",
        ),
        (
            "mount_types",
            k.mount_types.iter().flatten().any(|m| m != "default"),
            "\"default\" (robosuite 1.5 names mounts in base_types)",
        ),
    ];
    for (name, refused, valid) in fixed {
        if refused {
            return Err(Error::invalid_argument(
                name,
                format!("this value is not supported by this build; valid: {valid}"),
            ));
        }
    }
    if let Some(id) = k.render_gpu_device_id
        && id < -1
    {
        return Err(Error::invalid_argument(
            "render_gpu_device_id",
            format!("must be an int >= -1 (-1: any device), got {id}"),
        ));
    }
    Ok(())
}

/// robosuite's viewer names (lower-cased, as robosuite's `initialize_renderer` does);
/// `None` is robosuite's default, `"mjviewer"`.
fn renderer_name(name: Option<&str>) -> Result<&'static str> {
    match name.map(str::to_ascii_lowercase).as_deref() {
        None | Some("mjviewer") => Ok("mjviewer"),
        Some("mujoco") => Ok("mujoco"),
        Some(other) => Err(Error::invalid_argument(
            "renderer",
            format!(
                "`{other}` is not a valid renderer name; valid: mjviewer (MuJoCo's viewer), \
                 mujoco (an OpenCV window)"
            ),
        )),
    }
}

/// `renderer_config`: `None` or robosuite's mjviewer settings, `{"cam_config": ...}`.
fn check_renderer_config(value: &Value) -> Result<()> {
    let bad = |why: String| Error::invalid_argument("renderer_config", why);
    let map = match value {
        Value::Null => return Ok(()),
        Value::Object(map) => map,
        other => return Err(bad(format!("must be None or a dict, got {other}"))),
    };
    for (key, v) in map {
        if key != "cam_config" {
            return Err(bad(format!("unsupported key `{key}`; valid: cam_config")));
        }
        let cam = match v {
            Value::Null => continue,
            Value::Object(cam) => cam,
            other => {
                return Err(bad(format!(
                    "cam_config must be None or a dict, got {other}"
                )));
            }
        };
        for name in ["lookat", "distance", "azimuth", "elevation"] {
            let ok = match (name, cam.get(name)) {
                ("lookat", Some(Value::Array(xyz))) => {
                    xyz.len() == 3 && xyz.iter().all(|x| x.as_f64().is_some_and(f64::is_finite))
                }
                (_, Some(x)) => x.as_f64().is_some_and(f64::is_finite),
                (_, None) => false,
            };
            if !ok {
                return Err(bad(format!(
                    "cam_config needs `{name}` ({}), got {}",
                    if name == "lookat" {
                        "3 finite numbers"
                    } else {
                        "a finite number"
                    },
                    cam.get(name).map_or("nothing".to_owned(), Value::to_string)
                )));
            }
        }
        if let Some(extra) = cam
            .keys()
            .find(|k| !["lookat", "distance", "azimuth", "elevation"].contains(&k.as_str()))
        {
            return Err(bad(format!(
                "cam_config: unsupported key `{extra}`; valid: lookat, distance, azimuth, elevation"
            )));
        }
    }
    Ok(())
}

/// `controller_configs`: one config (composite or part) or a list of them (`None`
/// entries: that robot's default is not expressible, so a list must be all dicts).
fn controller_configs(value: &Value) -> Result<Vec<ControllerConfig>> {
    match value {
        Value::Null => Ok(Vec::new()),
        Value::Array(list) => list
            .iter()
            .enumerate()
            .map(|(i, v)| ControllerConfig::from_value(v, &format!("controller_configs[{i}]")))
            .collect(),
        one => Ok(vec![ControllerConfig::from_value(
            one,
            "controller_configs",
        )?]),
    }
}

/// robosuite's `initialization_noise`: `"default"`, `None` or a dict.
fn initialization_noise(value: &Value) -> Result<InitNoise> {
    let bad = |why: String| Error::invalid_argument("initialization_noise", why);
    match value {
        Value::Null => Ok(InitNoise::none()),
        Value::String(s) if s == "default" => Ok(InitNoise::default()),
        Value::Object(map) => {
            let mut noise = InitNoise::default();
            for (key, v) in map {
                match key.as_str() {
                    "magnitude" => {
                        noise.magnitude = v
                            .as_f64()
                            .ok_or_else(|| bad(format!("magnitude must be a number, got {v}")))?
                    }
                    "type" => {
                        noise.kind = match v.as_str() {
                            Some("gaussian") => NoiseKind::Gaussian,
                            Some("uniform") => NoiseKind::Uniform,
                            _ => {
                                return Err(bad(format!(
                                    "unknown noise type {v}; valid: \"gaussian\", \"uniform\""
                                )));
                            }
                        }
                    }
                    other => {
                        return Err(bad(format!(
                            "unsupported key `{other}`; valid: magnitude, type"
                        )));
                    }
                }
            }
            Ok(noise)
        }
        other => Err(bad(format!(
            "must be \"default\", None or a dict with magnitude and type, got {other}"
        ))),
    }
}

/// robosuite's `camera_segmentations`: `None`, a level for every camera, a list of levels
/// for every camera, or a nested list with one list (or `None`) per camera.
fn segmentations(value: &Value) -> Result<Vec<Vec<Segmentation>>> {
    let bad = || {
        Error::invalid_argument(
            "camera_segmentations",
            format!(
                "must be None, a level (\"instance\", \"class\", \"element\"), a list of levels, \
                 or one list (or None) per camera, got {value}"
            ),
        )
    };
    let level = |v: &Value| v.as_str().ok_or_else(bad).and_then(Segmentation::parse);
    match value {
        Value::Null => Ok(Vec::new()),
        Value::String(_) => Ok(vec![vec![level(value)?]]),
        Value::Array(items) if items.iter().any(Value::is_array) => items
            .iter()
            .map(|cam| match cam {
                Value::Null => Ok(Vec::new()),
                Value::Array(levels) => levels.iter().map(level).collect(),
                one => Ok(vec![level(one)?]),
            })
            .collect(),
        Value::Array(items) => {
            let levels = items
                .iter()
                .filter(|v| !v.is_null())
                .map(level)
                .collect::<Result<Vec<_>>>()?;
            Ok(if levels.is_empty() {
                Vec::new()
            } else {
                vec![levels]
            })
        }
        _ => Err(bad()),
    }
}

/// Gymnasium's render mode by name (`"human"` is refused when the config is validated).
fn render_mode(name: &str) -> Result<RenderMode> {
    match name {
        "rgb_array" => Ok(RenderMode::RgbArray),
        "depth_array" => Ok(RenderMode::DepthArray),
        "human" => Ok(RenderMode::Human),
        other => Err(Error::invalid_argument(
            "render_mode",
            format!("unknown render mode `{other}`; valid: rgb_array, depth_array, None"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn config(env: &str, kwargs: Value) -> Result<EnvConfig> {
        EnvConfig::from_kwargs(env, kwargs.as_object().expect("an object"))
    }

    fn invalid(env: &str, kwargs: Value) -> (String, String) {
        match config(env, kwargs) {
            Err(Error::InvalidArgument { name, reason }) => (name, reason),
            other => panic!("expected InvalidArgument, got {other:?}"),
        }
    }

    #[test]
    fn robosuites_values_as_they_are() {
        let c = config(
            "TwoArmLift",
            json!({
                "robots": ["Sawyer", "Panda"],
                "gripper_types": ["default", null],
                "camera_names": ["agentview", "birdview"],
                "camera_heights": [84, 128],
                "camera_widths": 64,
                "camera_depths": null,
                "camera_segmentations": [["element", "class"], null],
                "initialization_noise": {"magnitude": 0.1, "type": "uniform"},
                "reward_scale": null,
                "render_camera": null,
                "seed": 4,
            }),
        )
        .unwrap();
        assert_eq!(c.robots, ["Sawyer", "Panda"]);
        assert_eq!(
            c.gripper_types,
            [GripperChoice::Default, GripperChoice::None]
        );
        assert_eq!(c.cameras.camera_heights, [84, 128]);
        assert_eq!(c.cameras.camera_widths, [64]);
        assert_eq!(c.cameras.camera_depths, [false]);
        assert_eq!(
            c.cameras.camera_segmentations,
            [vec![Segmentation::Element, Segmentation::Class], vec![]]
        );
        assert_eq!(
            c.initialization_noise,
            InitNoise {
                magnitude: 0.1,
                kind: NoiseKind::Uniform
            }
        );
        assert_eq!((c.reward_scale, c.seed), (None, Some(4)));
        assert_eq!(c.cameras.render_camera, "frontview");
        // One value for a list argument; robosuite's defaults where absent.
        let c = config(
            "Lift",
            json!({"robots": "IIWA", "camera_segmentations": "instance"}),
        )
        .unwrap();
        assert_eq!(c.robots, ["IIWA"]);
        assert_eq!(
            c.cameras.camera_segmentations,
            [vec![Segmentation::Instance]]
        );
        assert_eq!(c.reward_scale, Some(1.0));
        assert!(c.cameras.has_offscreen_renderer, "robosuite's default");
        assert_eq!(c.initialization_noise, InitNoise::default());
        // One gripper for every robot, as robosuite's `_input2list` broadcasts it.
        let two = config(
            "TwoArmLift",
            json!({"robots": ["Panda", "Panda"], "gripper_types": "RethinkGripper"}),
        )
        .unwrap();
        let rethink = GripperChoice::Named("RethinkGripper".into());
        assert_eq!(
            (two.gripper_choice(0, 0), two.gripper_choice(1, 0)),
            (rethink.clone(), rethink)
        );
        let none = config("Lift", json!({"initialization_noise": null})).unwrap();
        assert_eq!(none.initialization_noise, InitNoise::none());
    }

    #[test]
    fn the_tasks_own_arguments_are_task_options() {
        let c = config("Door", json!({"use_latch": false, "horizon": 9})).unwrap();
        assert_eq!(c.task_options["use_latch"], false);
        assert_eq!(c.horizon, 9);
        match config("Door", json!({"table_full_size": [1, 1, 1]})) {
            Err(Error::UnknownKey { key, available }) => {
                assert_eq!(key, "table_full_size");
                assert!(available.iter().any(|k| k == "use_latch"), "{available:?}");
                assert!(
                    available.iter().any(|k| k == "camera_names"),
                    "{available:?}"
                );
            }
            other => panic!("expected UnknownKey, got {other:?}"),
        }
        assert!(matches!(
            config("Nope", json!({"use_latch": true})),
            Err(Error::UnknownEnv { .. })
        ));
    }

    #[test]
    fn ill_typed_values_name_the_argument_and_item() {
        let (name, reason) = invalid("Lift", json!({"horizon": "x"}));
        assert_eq!(name, "horizon");
        assert!(reason.contains("invalid type"), "{reason}");
        let (name, reason) = invalid("Lift", json!({"camera_heights": [84, "a"]}));
        assert_eq!(name, "camera_heights");
        assert!(reason.contains("[1]"), "{reason}");
        let (name, _) = invalid("Lift", json!({"robots": 3}));
        assert_eq!(name, "robots");
        let (name, reason) = invalid("Lift", json!({"initialization_noise": {"kind": "x"}}));
        assert_eq!(name, "initialization_noise");
        assert!(reason.contains("magnitude, type"), "{reason}");
        let (name, _) = invalid("Lift", json!({"camera_segmentations": ["pixel"]}));
        assert_eq!(name, "camera_segmentations");
        let (name, reason) = invalid("Lift", json!({"render_mode": "ansi"}));
        assert_eq!(name, "render_mode");
        assert!(reason.contains("rgb_array"), "{reason}");
        let (name, _) = invalid("Lift", json!({"image_convention": "directx"}));
        assert_eq!(name, "image_convention");
    }

    #[test]
    fn robosuites_viewer_arguments_only_with_what_this_build_honours() {
        let ok = json!({
            "has_renderer": false, "renderer": "mjviewer", "renderer_config": null,
            "render_collision_mesh": false, "render_visual_mesh": true,
            "render_gpu_device_id": 0, "hard_reset": false, "mount_types": "default",
        });
        assert!(config("Lift", ok).is_ok());
        for (bad, key) in [
            (
                json!({"render_collision_mesh": true}),
                "render_collision_mesh",
            ),
            (json!({"renderer_config": {"cam_id": 0}}), "renderer_config"),
            (
                json!({"renderer_config": {"cam_config": {"distance": 2}}}),
                "renderer_config",
            ),
            (json!({"renderer": "pygame"}), "renderer"),
            (
                json!({"has_renderer": true, "render_camera": ["frontview", "agentview"]}),
                "render_camera",
            ),
            (json!({"render_camera": []}), "render_camera"),
            (json!({"mount_types": ["RethinkMount"]}), "mount_types"),
            (json!({"render_gpu_device_id": -2}), "render_gpu_device_id"),
            (json!({"render_quality": "ultra"}), "render_quality"),
        ] {
            assert_eq!(invalid("Lift", bad).0, key);
        }
    }

    #[test]
    fn robosuites_viewers_are_taken() {
        // MuJoCo's viewer (the default) leaves the offscreen renderer as asked.
        let mj = config(
            "Lift",
            json!({"has_renderer": true, "has_offscreen_renderer": false,
                   "renderer_config": {"cam_config": {"lookat": [0, 0, 1], "distance": 2,
                                                      "azimuth": 180, "elevation": -20}}}),
        )
        .unwrap();
        assert!(!mj.cameras.has_offscreen_renderer);
        // robosuite's OpenCV viewer draws offscreen frames, so it turns the renderer on;
        // a list of cameras is its side-by-side view, and frames draw the first.
        let cv = config(
            "Lift",
            json!({"has_renderer": true, "renderer": "MuJoCo", "has_offscreen_renderer": false,
                   "render_camera": ["agentview", "frontview"]}),
        )
        .unwrap();
        assert!(cv.cameras.has_offscreen_renderer);
        assert_eq!(cv.cameras.render_camera, "agentview");
        let free = config("Lift", json!({"has_renderer": true, "render_camera": null})).unwrap();
        assert_eq!(free.cameras.render_camera, "frontview");
    }

    #[test]
    fn the_exported_names_are_the_schemas() {
        let names = kwarg_names();
        for key in [
            "robots",
            "controller_configs",
            "camera_segmentations",
            "has_renderer",
        ] {
            assert!(names.contains(&key), "{key}");
        }
        // Every exported name is taken (a value of the right type for each, `null` where
        // the argument allows it).
        for &key in names {
            let value = match key {
                "robots" | "camera_names" => json!("Panda"),
                "env_configuration" | "mount_types" | "initialization_noise" => json!("default"),
                "controller" => json!("OSC_POSITION"),
                "render_camera" => json!("frontview"),
                "image_convention" => json!("opengl"),
                "render_quality" => json!("robosuite"),
                "renderer" => json!("mujoco"),
                "horizon" | "seed" | "render_height" | "render_width" | "camera_heights"
                | "camera_widths" => json!(64),
                "control_freq" | "reward_scale" => json!(20.0),
                "render_gpu_device_id" => json!(-1),
                "render_visual_mesh" | "has_offscreen_renderer" => json!(true),
                k if k.starts_with("use_")
                    || k.starts_with("has_")
                    || k.starts_with("reward_")
                    || ["ignore_done", "lite_physics", "hard_reset", "camera_depths"]
                        .contains(&k)
                    || k == "render_collision_mesh" =>
                {
                    json!(false)
                }
                _ => Value::Null,
            };
            let kwargs = json!({ key: value });
            assert!(config("Lift", kwargs).is_ok(), "{key}");
        }
    }
}
