//! robosuite's task constructor arguments (`table_full_size`, `use_latch`, `task_config`,
//! `single_object_mode`, ...) as a task's options: a JSON object with robosuite's names
//! and values, read and written through each [`TaskSpec`](super::TaskSpec)'s serde form.

use gym_core::{Error, Result};
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Map, Value};

/// A task's robosuite constructor arguments by name (robosuite's names and values: lists
/// as arrays, `None` as `null`).
pub type TaskOptions = Map<String, Value>;

/// `spec`'s serde form as options.
pub(crate) fn to_options<T: Serialize>(spec: &T) -> TaskOptions {
    match serde_json::to_value(spec) {
        Ok(Value::Object(map)) => map,
        _ => TaskOptions::new(),
    }
}

/// `spec` with `options` written over its serde form: an unknown name or an ill-typed
/// value is an error naming it (and, for an unknown name, listing the task's).
pub(crate) fn merged<T: Serialize + DeserializeOwned>(
    task: &str,
    spec: &T,
    options: &TaskOptions,
) -> Result<T> {
    let mut fields = to_options(spec);
    for (key, value) in options {
        if !fields.contains_key(key) {
            return Err(unknown(task, key, fields.keys().map(String::as_str)));
        }
        fields.insert(key.clone(), value.clone());
    }
    serde_path_to_error::deserialize(Value::Object(fields)).map_err(|e| {
        let path = e.path().to_string();
        Error::invalid_argument(path, e.into_inner().to_string())
    })
}

/// The error for an argument `task` does not take.
pub(crate) fn unknown<'a>(task: &str, key: &str, valid: impl Iterator<Item = &'a str>) -> Error {
    let valid: Vec<&str> = valid.collect();
    Error::invalid_argument(
        key,
        if valid.is_empty() {
            format!("{task} takes no task arguments")
        } else {
            format!(
                "{task} takes no argument `{key}`; its arguments: {}",
                valid.join(", ")
            )
        },
    )
}

/// Removes `key` from `options` and reads it as `T` (`None` when absent).
pub(crate) fn take<T: DeserializeOwned>(options: &mut TaskOptions, key: &str) -> Result<Option<T>> {
    match options.remove(key) {
        None => Ok(None),
        Some(value) => serde_json::from_value(value)
            .map(Some)
            .map_err(|e| Error::invalid_argument(key, e.to_string())),
    }
}
