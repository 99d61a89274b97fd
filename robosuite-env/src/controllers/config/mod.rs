//! robosuite's controller configurations, as robosuite users write them: the composite
//! `BASIC` config (`{"type": "BASIC", "body_parts": {"right": {...}, ...}}`, as
//! `load_composite_controller_config` returns it and robosuite's JSON files store it, with
//! or without the `"arms"` level) or a bare part config (`{"type": "OSC_POSITION", ...}`,
//! robosuite's `load_part_controller_config`), parsed once with serde and checked key by
//! key.
//!
//! Every error names the key (`controller_configs.body_parts.right.kp`) and lists what is
//! valid. Values are checked against the robot when the controllers are built, which
//! happens when the env is made.

mod files;
mod parts;
mod values;

pub use super::table::ARM_CONTROLLER_TYPES;
pub use files::{
    COMPOSITE_CONTROLLER_TYPES, load_composite_controller_config, load_part_controller_config,
    read_json, robot_config_name,
};
pub use parts::{
    ArmControllerConfig, GRIPPER_CONTROLLER_TYPES, GripperConfig, IkConfig, JointPositionConfig,
    JointTorqueConfig, JointVelocityConfig, OscConfig,
};
pub use values::{Bounds, ImpedanceMode, InputRefFrame, InputType, Interpolation, PerAxis};

use super::table::arm_controller;
use crate::assets::Assets;
use gym_core::{Error, Result};
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

/// The body parts robosuite's composite configs name: the arms, then the other parts of
/// mobile and humanoid robots (robosuite drops the config of a part a robot does not have,
/// with a warning).
pub const BODY_PARTS: &[&str] = &["right", "left", "torso", "head", "base", "legs"];

/// The controller types robosuite's part factories accept for a body part other than an
/// arm (`torso_controller_factory`, `head_controller_factory`,
/// `mobile_base_controller_factory`, `legs_controller_factory`); `None` for an arm or an
/// unknown part.
pub fn part_controller_types(part: &str) -> Option<&'static [&'static str]> {
    match part {
        "torso" | "head" => Some(&["JOINT_VELOCITY", "JOINT_POSITION"]),
        "base" => Some(&["JOINT_VELOCITY"]),
        "legs" => Some(&["JOINT_POSITION", "JOINT_TORQUE"]),
        _ => None,
    }
}

/// One arm's configuration: its controller and its gripper's.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ArmPartConfig {
    /// The arm controller.
    pub controller: ArmControllerConfig,
    /// The gripper controller (`GRIP`).
    pub gripper: GripperConfig,
}

impl From<ArmControllerConfig> for ArmPartConfig {
    fn from(controller: ArmControllerConfig) -> Self {
        Self {
            controller,
            gripper: GripperConfig::default(),
        }
    }
}

/// robosuite's composite controller configuration: its type, one part config per body
/// part, in the config's order (the order of the parts' slices of the action), and the
/// type's own settings.
#[derive(Debug, Clone, PartialEq)]
pub struct CompositeControllerConfig {
    /// The composite controller type, one of [`COMPOSITE_CONTROLLER_TYPES`] that
    /// robosuite-rs serves (`"BASIC"`, `"HYBRID_MOBILE_BASE"`, ...).
    pub kind: String,
    /// The arm parts (`"right"`, `"left"`) in the config's order.
    pub arms: Vec<(String, ArmPartConfig)>,
    /// The other body parts (`torso`, `head`, `base`, `legs`) in the config's order; the
    /// `base` config describes robosuite's `MobileBaseJointVelocityController`.
    pub parts: Vec<(String, ArmControllerConfig)>,
    /// Every body part the config names, arms and others, in the config's order.
    pub order: Vec<String>,
    /// `composite_controller_specific_configs` as given: the composite type reads the
    /// keys it uses (`BASIC` and `HYBRID_MOBILE_BASE` none but `body_part_ordering`).
    pub specific: Map<String, Value>,
}

impl Default for CompositeControllerConfig {
    fn default() -> Self {
        Self {
            kind: "BASIC".to_owned(),
            arms: Vec::new(),
            parts: Vec::new(),
            order: Vec::new(),
            specific: Map::new(),
        }
    }
}

impl CompositeControllerConfig {
    /// A `BASIC` config with `part` on the right arm.
    pub fn single_arm(part: impl Into<ArmPartConfig>) -> Self {
        let mut out = Self::default();
        out.set_arm("right", part.into());
        out
    }

    /// The config of arm `side`, if the config has one.
    pub fn arm(&self, side: &str) -> Option<&ArmPartConfig> {
        self.arms.iter().find(|(s, _)| s == side).map(|(_, p)| p)
    }

    /// The config of body part `name` other than an arm (`torso`, `head`, `base`,
    /// `legs`), if the config has one.
    pub fn part(&self, name: &str) -> Option<&ArmControllerConfig> {
        self.parts.iter().find(|(s, _)| s == name).map(|(_, p)| p)
    }

    /// Sets the config of arm `side`, keeping its place (or appending it), as robosuite's
    /// `refactor_composite_controller_config` does.
    pub fn set_arm(&mut self, side: &str, part: ArmPartConfig) {
        match self.arms.iter_mut().find(|(s, _)| s == side) {
            Some((_, p)) => *p = part,
            None => {
                self.arms.push((side.to_owned(), part));
                self.order.push(side.to_owned());
            }
        }
    }

    /// Sets the config of body part `name` (not an arm), keeping its place (or appending
    /// it).
    pub fn set_part(&mut self, name: &str, part: ArmControllerConfig) {
        match self.parts.iter_mut().find(|(s, _)| s == name) {
            Some((_, p)) => *p = part,
            None => {
                self.parts.push((name.to_owned(), part));
                self.order.push(name.to_owned());
            }
        }
    }

    /// Parses a composite config (robosuite's dict) at `path` (the name errors give it,
    /// such as `controller_configs`).
    ///
    /// # Errors
    /// [`Error::UnknownKey`] for an unknown key or body part; [`Error::InvalidArgument`]
    /// for a missing or ill-typed value, an unknown controller type or one robosuite's
    /// factory refuses for the part; [`Error::Unsupported`] for a composite type
    /// robosuite-rs does not serve (see [`crate::robots::composite`]).
    pub fn from_value(value: &Value, path: &str) -> Result<Self> {
        const KEYS: &[&str] = &[
            "type",
            "body_parts",
            "composite_controller_specific_configs",
        ];
        let obj = object(value, path)?;
        if let Some(key) = obj.keys().find(|k| !KEYS.contains(&k.as_str())) {
            return Err(unknown_key(path, key, KEYS));
        }
        let kind = obj
            .get("type")
            .map_or(Ok("BASIC"), |t| string(t, &join(path, "type")))?;
        let entry = crate::robots::composite::composite_entry(kind, &join(path, "type"))?;
        let mut out = Self {
            kind: entry.name.to_owned(),
            ..Self::default()
        };
        if let Some(specific) = obj.get("composite_controller_specific_configs") {
            let at = join(path, "composite_controller_specific_configs");
            out.specific = object(specific, &at)?.clone();
            (entry.check_specific)(&out.specific, &at)?;
        }
        let parts_path = join(path, "body_parts");
        let parts = object(
            obj.get("body_parts").ok_or_else(|| {
                Error::invalid_argument(
                    &parts_path,
                    "missing (robosuite requires `type` and `body_parts`)",
                )
            })?,
            &parts_path,
        )?;
        for (name, part) in parts {
            if name == "arms" {
                let arms_path = join(&parts_path, "arms");
                for (arm, cfg) in object(part, &arms_path)? {
                    out.add_part(arm, cfg, &arms_path)?;
                }
            } else {
                out.add_part(name, part, &parts_path)?;
            }
        }
        Ok(out)
    }

    fn add_part(&mut self, name: &str, value: &Value, parent: &str) -> Result<()> {
        let at = join(parent, name);
        match name {
            "right" | "left" => {
                let part = parse_arm_part(value, &at)?;
                self.set_arm(name, part);
            }
            _ => match part_controller_types(name) {
                Some(types) => {
                    let kind = object(value, &at)?
                        .get("type")
                        .and_then(Value::as_str)
                        .unwrap_or("");
                    if !types.contains(&kind) {
                        return Err(Error::invalid_argument(
                            join(&at, "type"),
                            format!(
                                "robosuite's `{name}` controllers are {}, got `{kind}`",
                                types.join(", ")
                            ),
                        ));
                    }
                    let part = parse_arm_part(value, &at)?;
                    self.set_part(name, part.controller);
                }
                None => {
                    let mut valid = BODY_PARTS.to_vec();
                    valid.push("arms");
                    return Err(unknown_key(parent, name, &valid));
                }
            },
        }
        Ok(())
    }

    /// The config robosuite would run on a robot with arms `arms` and other body parts
    /// `parts` (those with actuators: `torso`, `head`, `base`, `legs`): every arm and
    /// every such part must have a config (robosuite fails on a missing one); configs of
    /// parts the robot does not have are dropped, as robosuite drops them (with a
    /// warning). The parts keep the config's order.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `path` when an arm or a part of the robot has no
    /// config.
    pub fn fit_to(&self, robot: &str, arms: &[&str], parts: &[&str], path: &str) -> Result<Self> {
        for side in arms {
            if self.arm(side).is_none() {
                return Err(Error::invalid_argument(
                    join(path, "body_parts"),
                    format!(
                        "no controller for the `{side}` arm of {robot}; {robot}'s arms: {}",
                        arms.join(", ")
                    ),
                ));
            }
        }
        for part in parts {
            if self.part(part).is_none() {
                return Err(Error::invalid_argument(
                    join(path, "body_parts"),
                    format!(
                        "no controller for the `{part}` of {robot}; {robot}'s body parts: {}",
                        arms.iter()
                            .chain(parts)
                            .copied()
                            .collect::<Vec<_>>()
                            .join(", ")
                    ),
                ));
            }
        }
        let keep = |name: &str| arms.contains(&name) || parts.contains(&name);
        Ok(Self {
            kind: self.kind.clone(),
            arms: self.arms.iter().filter(|(s, _)| keep(s)).cloned().collect(),
            parts: self
                .parts
                .iter()
                .filter(|(s, _)| keep(s))
                .cloned()
                .collect(),
            order: self.order.iter().filter(|s| keep(s)).cloned().collect(),
            specific: self.specific.clone(),
        })
    }

    /// The body parts of this config a robot with arms `arms` and other parts `parts`
    /// does not have: robosuite drops their configs with a warning.
    pub fn dropped_parts(&self, arms: &[&str], parts: &[&str]) -> Vec<String> {
        self.order
            .iter()
            .filter(|s| !arms.contains(&s.as_str()) && !parts.contains(&s.as_str()))
            .cloned()
            .collect()
    }
}

/// robosuite's `controller_configs` entry for one robot: a composite config, or a bare
/// part config that robosuite puts on every arm of the robot's default composite config
/// (`refactor_composite_controller_config`).
// A config is made once per env; boxing the larger variant would only burden matching.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum ControllerConfig {
    /// A composite `BASIC` config.
    Composite(CompositeControllerConfig),
    /// A part config for every arm, with the `GRIP` gripper controller.
    Part(ArmControllerConfig),
}

impl From<ArmControllerConfig> for ControllerConfig {
    fn from(part: ArmControllerConfig) -> Self {
        Self::Part(part)
    }
}

impl From<CompositeControllerConfig> for ControllerConfig {
    fn from(c: CompositeControllerConfig) -> Self {
        Self::Composite(c)
    }
}

impl ControllerConfig {
    /// Parses robosuite's dict (composite or part config; robosuite's
    /// `is_part_controller_config` tells them apart) at `path`.
    ///
    /// # Errors
    /// As [`CompositeControllerConfig::from_value`].
    pub fn from_value(value: &Value, path: &str) -> Result<Self> {
        let obj = object(value, path)?;
        let is_part = !obj.contains_key("body_parts")
            && obj
                .get("type")
                .and_then(Value::as_str)
                .is_some_and(|t| ARM_CONTROLLER_TYPES.contains(&t));
        if is_part {
            let mut part = parse_arm_part(value, path)?;
            // robosuite's refactor always gives the GRIP controller.
            part.gripper = GripperConfig::default();
            Ok(Self::Part(part.controller))
        } else {
            if let Some(t) = obj.get("type").and_then(Value::as_str)
                && !obj.contains_key("body_parts")
                && !COMPOSITE_CONTROLLER_TYPES.contains(&t)
            {
                return Err(unknown_type(t, &join(path, "type")));
            }
            Ok(Self::Composite(CompositeControllerConfig::from_value(
                value, path,
            )?))
        }
    }

    /// Parses a JSON text (a robosuite controller JSON file's contents).
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] naming `path` for text that is not JSON; otherwise as
    /// [`ControllerConfig::from_value`].
    pub fn from_json(text: &str, path: &str) -> Result<Self> {
        let value: Value = serde_json::from_str(text)
            .map_err(|e| Error::invalid_argument(path, format!("not valid JSON: {e}")))?;
        Self::from_value(&value, path)
    }

    /// The composite config for robot `robot` (arms `arms`, other body parts `parts`): a
    /// composite config as is, a part config on every arm of the robot's default config
    /// (robosuite's `refactor_composite_controller_config`: `default_{robot}.json` by the
    /// robot's lower-cased name, else a `BASIC` config of the arms alone), then fitted to
    /// the robot ([`CompositeControllerConfig::fit_to`]).
    ///
    /// # Errors
    /// [`Error::Model`] when robosuite's default config file cannot be read;
    /// [`Error::InvalidArgument`] when an arm has no config.
    pub fn for_robot(
        &self,
        assets: &Assets,
        robot: &str,
        arms: &[&str],
        parts: &[&str],
        path: &str,
    ) -> Result<CompositeControllerConfig> {
        match self {
            Self::Composite(c) => c.fit_to(robot, arms, parts, path),
            Self::Part(part) => {
                let mut base = refactor_default(assets, robot)?;
                for side in arms {
                    base.set_arm(side, ArmPartConfig::from(part.clone()));
                }
                base.fit_to(robot, arms, parts, path)
            }
        }
    }
}

/// robosuite's `refactor_composite_controller_config` base for a part config given to
/// `robot`: its `default_{robot}.json` (the robot's name lower-cased) if robosuite has one,
/// else an empty `BASIC` config.
fn refactor_default(assets: &Assets, robot: &str) -> Result<CompositeControllerConfig> {
    let own = assets
        .controller_config_dir()
        .join(format!("robots/default_{}.json", robot.to_lowercase()));
    if own.is_file() {
        robot_default(assets, robot)
    } else {
        Ok(CompositeControllerConfig::default())
    }
}

/// robosuite's default composite config for `robot` (`load_composite_controller_config(robot=...)`).
///
/// # Errors
/// [`Error::Model`] when the file cannot be read or parsed; [`Error::Unsupported`] when it
/// names a composite controller this crate does not serve (GR1FixedLowerBody's
/// `WHOLE_BODY_MINK_IK`).
pub fn robot_default(assets: &Assets, robot: &str) -> Result<CompositeControllerConfig> {
    let value = load_composite_controller_config(assets, None, Some(robot))?;
    CompositeControllerConfig::from_value(&value, "controller_configs").map_err(|e| {
        let message = format!("robosuite's default controller config for {robot}: {e}");
        match e {
            Error::Unsupported(_) => Error::unsupported(message),
            _ => Error::model(message),
        }
    })
}

/// The keys of robosuite controller config `value` (composite or part) that robosuite's
/// controllers accept and ignore (their constructors take `**kwargs`) and so does this
/// crate: keys of another controller type left in a config, `damping_limits` beside
/// `damping_ratio_limits`, misspellings. Each as its path (`body_parts.right.foo`), so a
/// caller can warn about them; the values of keys that are used are still checked.
pub fn ignored_keys(value: &Value) -> Vec<String> {
    fn arm(value: &Value, path: &str, out: &mut Vec<String>) {
        let Some(obj) = value.as_object() else { return };
        let Some((keys, ignored)) = obj
            .get("type")
            .and_then(Value::as_str)
            .and_then(ArmControllerConfig::keys_of)
        else {
            return;
        };
        for key in obj.keys() {
            let k = key.as_str();
            if !(k == "type" || k == "gripper" || keys.contains(&k) || ignored.contains(&k)) {
                out.push(join(path, k));
            }
        }
    }
    let mut out = Vec::new();
    let Some(obj) = value.as_object() else {
        return out;
    };
    match obj.get("body_parts").and_then(Value::as_object) {
        None => arm(value, "", &mut out),
        Some(parts) => {
            for (name, part) in parts {
                let at = join("body_parts", name);
                match (name.as_str(), part.as_object()) {
                    ("arms", Some(arms)) => {
                        for (side, cfg) in arms {
                            arm(cfg, &join(&at, side), &mut out);
                        }
                    }
                    ("right" | "left" | "torso" | "head" | "base" | "legs", _) => {
                        arm(part, &at, &mut out);
                    }
                    _ => {}
                }
            }
        }
    }
    out
}

/// Parses one arm part (`{"type": ..., ..., "gripper": {...}}`) at `path`.
fn parse_arm_part(value: &Value, path: &str) -> Result<ArmPartConfig> {
    let obj = object(value, path)?;
    let type_path = join(path, "type");
    let kind = string(
        obj.get("type").ok_or_else(|| {
            Error::invalid_argument(
                &type_path,
                format!("missing; valid: {}", ARM_CONTROLLER_TYPES.join(", ")),
            )
        })?,
        &type_path,
    )?;
    let entry = arm_controller(kind).ok_or_else(|| unknown_type(kind, &type_path))?;
    let keys = (entry.keys)();
    let mut fields = Map::new();
    for (key, v) in obj {
        if keys.contains(&key.as_str()) {
            fields.insert(key.clone(), v.clone());
        }
        // Other keys (`type`, `gripper` below; robosuite's ignored ones, and any other:
        // robosuite's controllers take `**kwargs`) are not the controller's settings; see
        // [`ignored_keys`].
    }
    let controller = (entry.parse)(Value::Object(fields), path)?;
    let gripper = match obj.get("gripper") {
        None | Some(Value::Null) => GripperConfig::default(),
        Some(g) => parse_gripper(g, &join(path, "gripper"))?,
    };
    Ok(ArmPartConfig {
        controller,
        gripper,
    })
}

fn parse_gripper(value: &Value, path: &str) -> Result<GripperConfig> {
    let obj = object(value, path)?;
    let type_path = join(path, "type");
    let kind = obj
        .get("type")
        .map_or(Ok("GRIP"), |t| string(t, &type_path))?;
    if !GRIPPER_CONTROLLER_TYPES.contains(&kind) {
        return Err(Error::invalid_argument(
            type_path,
            format!(
                "unknown gripper controller `{kind}`; valid: {}",
                GRIPPER_CONTROLLER_TYPES.join(", ")
            ),
        ));
    }
    let mut fields = Map::new();
    for (key, v) in obj {
        if key == "type" {
            continue;
        }
        if !GripperConfig::keys().contains(&key.as_str()) {
            let mut valid = vec!["type"];
            valid.extend_from_slice(GripperConfig::keys());
            return Err(unknown_key(path, key, &valid));
        }
        fields.insert(key.clone(), v.clone());
    }
    typed(Value::Object(fields), path)
}

/// Deserializes `value` into `T`, naming the offending key in the error.
pub(crate) fn typed<T: DeserializeOwned>(value: Value, path: &str) -> Result<T> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let inner = e.path().to_string();
        let at = if inner == "." {
            path.to_owned()
        } else {
            join(path, &inner)
        };
        Error::invalid_argument(at, e.into_inner().to_string())
    })
}

fn unknown_type(kind: &str, path: &str) -> Error {
    Error::invalid_argument(
        path,
        format!(
            "unknown controller `{kind}`; valid arm controllers: {} (composite configs: {} with `body_parts`)",
            ARM_CONTROLLER_TYPES.join(", "),
            COMPOSITE_CONTROLLER_TYPES.join(", ")
        ),
    )
}

fn unknown_key(path: &str, key: &str, valid: &[&str]) -> Error {
    Error::UnknownKey {
        key: join(path, key),
        available: valid.iter().map(|s| (*s).to_owned()).collect(),
    }
}

fn object<'a>(value: &'a Value, path: &str) -> Result<&'a Map<String, Value>> {
    value.as_object().ok_or_else(|| {
        Error::invalid_argument(path, format!("expected a dict, got {}", kind_of(value)))
    })
}

fn string<'a>(value: &'a Value, path: &str) -> Result<&'a str> {
    value.as_str().ok_or_else(|| {
        Error::invalid_argument(path, format!("expected a string, got {}", kind_of(value)))
    })
}

fn kind_of(value: &Value) -> &'static str {
    match value {
        Value::Null => "null",
        Value::Bool(_) => "a bool",
        Value::Number(_) => "a number",
        Value::String(_) => "a string",
        Value::Array(_) => "a list",
        Value::Object(_) => "a dict",
    }
}

/// `parent.key`.
pub(crate) fn join(parent: &str, key: &str) -> String {
    if parent.is_empty() {
        key.to_owned()
    } else {
        format!("{parent}.{key}")
    }
}
