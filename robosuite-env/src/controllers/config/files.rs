//! robosuite's controller JSON files (`controllers/config/` of the robosuite package, in the
//! same cache as its model files): the defaults robosuite hands out, read as robosuite's
//! `load_composite_controller_config` and `load_part_controller_config` read them.

use super::ARM_CONTROLLER_TYPES;
use crate::assets::{Assets, read_file};
use gym_core::{Error, Result};
use serde_json::{Map, Value};
use std::path::PathBuf;

/// robosuite's registered composite controllers (`REGISTERED_COMPOSITE_CONTROLLERS_DICT`).
pub const COMPOSITE_CONTROLLER_TYPES: &[&str] = &[
    "BASIC",
    "HYBRID_MOBILE_BASE",
    "WHOLE_BODY_IK",
    "WHOLE_BODY_MINK_IK",
];

/// robosuite's `load_composite_controller_config(controller, robot)`: with no `controller`,
/// the robot's `default_{robot}.json` (else `basic.json`); with a composite name such as
/// `"BASIC"`, its file in `default/composite/`; with a path ending in `.json`, that file.
/// The `"arms"` level is flattened into `body_parts`, as robosuite returns it.
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown composite controller, or neither argument;
/// [`Error::Model`] when the file is missing or not JSON.
pub fn load_composite_controller_config(
    assets: &Assets,
    controller: Option<&str>,
    robot: Option<&str>,
) -> Result<Value> {
    let dir = assets.controller_config_dir();
    let path = match (controller, robot) {
        (None, None) => {
            return Err(Error::invalid_argument(
                "robot",
                "give a robot when no controller is given (robosuite asserts the same)",
            ));
        }
        (None, Some(robot)) => {
            let own = dir.join(format!("robots/default_{}.json", robot_config_name(robot)));
            if own.is_file() {
                own
            } else {
                dir.join("default/composite/basic.json")
            }
        }
        (Some(c), _) if c.ends_with(".json") => PathBuf::from(c),
        (Some(c), _) if COMPOSITE_CONTROLLER_TYPES.contains(&c) => {
            dir.join(format!("default/composite/{}.json", c.to_lowercase()))
        }
        (Some(c), _) => {
            return Err(Error::invalid_argument(
                "controller",
                format!(
                    "unknown composite controller `{c}`; valid: {} or a path to a .json file",
                    COMPOSITE_CONTROLLER_TYPES.join(", ")
                ),
            ));
        }
    };
    let mut value = read_json(&path)?;
    let obj = value
        .as_object_mut()
        .ok_or_else(|| Error::model(format!("{}: not a JSON object", path.display())))?;
    if !obj.contains_key("type") || !obj.contains_key("body_parts") {
        return Err(Error::model(format!(
            "{}: a composite controller config needs `type` and `body_parts`",
            path.display()
        )));
    }
    let parts = obj.remove("body_parts").unwrap_or(Value::Null);
    let mut flat = Map::new();
    if let Value::Object(parts) = parts {
        for (name, part) in parts {
            match (name.as_str(), part) {
                ("arms", Value::Object(arms)) => flat.extend(arms),
                (_, part) => {
                    flat.insert(name, part);
                }
            }
        }
    }
    obj.insert("body_parts".to_owned(), Value::Object(flat));
    Ok(value)
}

/// robosuite's `_get_robot_name`: the name of a robot's default controller file
/// (`default_{name}.json`).
pub fn robot_config_name(robot: &str) -> String {
    for (key, name) in [
        ("GR1FloatingBody", "gr1_floating_body"),
        ("GR1FixedLowerBody", "gr1_fixed_lower_body"),
        ("GR1", "gr1"),
        ("G1", "g1"),
        ("H1", "h1"),
        ("PandaDex", "panda_dex"),
    ] {
        if robot.contains(key) {
            return name.to_owned();
        }
    }
    robot.to_lowercase()
}

/// robosuite's `load_part_controller_config(default_controller=...)`: the part config file
/// `default/parts/{type}.json`.
///
/// # Errors
/// [`Error::InvalidArgument`] for an unknown controller type; [`Error::Model`] when the
/// file is missing or not JSON.
pub fn load_part_controller_config(assets: &Assets, default_controller: &str) -> Result<Value> {
    if !ARM_CONTROLLER_TYPES.contains(&default_controller) {
        return Err(Error::invalid_argument(
            "default_controller",
            format!(
                "unknown controller `{default_controller}`; valid: {}",
                ARM_CONTROLLER_TYPES.join(", ")
            ),
        ));
    }
    read_json(&assets.controller_config_dir().join(format!(
        "default/parts/{}.json",
        default_controller.to_lowercase()
    )))
}

/// A controller config JSON file (robosuite's `load_part_controller_config(custom_fpath)`).
///
/// # Errors
/// [`Error::Model`] when the file is missing or not JSON.
pub fn read_json(path: &std::path::Path) -> Result<Value> {
    let text = read_file(path)?;
    serde_json::from_str(&text)
        .map_err(|e| Error::model(format!("{}: not valid JSON: {e}", path.display())))
}
