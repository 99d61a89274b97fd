//! A process-wide registry of environments by id (Gymnasium's `gymnasium.make`).
//!
//! Crates that provide environments register them (robosuite-env: `register_envs()`);
//! [`make`] builds one by id with keyword arguments given as JSON values (Gymnasium's
//! `**kwargs`: numbers, strings, lists, dicts, `None`).

use crate::dynamic::BoxedEnv;
use crate::error::{Error, Result};
use indexmap::IndexMap;
use std::sync::{Arc, LazyLock, RwLock};

/// Keyword arguments by name (Gymnasium's `**kwargs`).
pub type Kwargs = serde_json::Map<String, serde_json::Value>;

/// Builds an environment from keyword arguments.
pub type EnvFactory = Arc<dyn Fn(&Kwargs) -> Result<BoxedEnv> + Send + Sync>;

/// How to make a registered environment (Gymnasium's `EnvSpec`).
#[derive(Clone)]
pub struct EnvSpec {
    /// The id, such as `"Lift"`.
    pub id: String,
    /// Builds the environment.
    pub factory: EnvFactory,
    /// The episode length the environment enforces itself, if any (robosuite's horizon).
    pub max_episode_steps: Option<u64>,
    /// Whether the same seed and actions may give different trajectories.
    pub nondeterministic: bool,
    /// One line saying what the environment is.
    pub description: String,
}

impl std::fmt::Debug for EnvSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("EnvSpec")
            .field("id", &self.id)
            .field("max_episode_steps", &self.max_episode_steps)
            .field("nondeterministic", &self.nondeterministic)
            .field("description", &self.description)
            .finish_non_exhaustive()
    }
}

static REGISTRY: LazyLock<RwLock<IndexMap<String, EnvSpec>>> = LazyLock::new(Default::default);

/// Registers (or replaces) an environment; returns the spec it replaced.
pub fn register(spec: EnvSpec) -> Option<EnvSpec> {
    let mut map = REGISTRY
        .write()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    map.insert(spec.id.clone(), spec)
}

/// The spec registered under `id`.
///
/// # Errors
/// [`Error::UnknownEnv`] listing every registered id.
pub fn spec(id: &str) -> Result<EnvSpec> {
    let map = REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    map.get(id).cloned().ok_or_else(|| Error::UnknownEnv {
        id: id.to_owned(),
        available: map.keys().cloned().collect(),
    })
}

/// Makes the environment registered under `id` with keyword arguments `kwargs`: a JSON
/// object of them, or `null` for none.
///
/// ```no_run
/// let env = gym_core::registry::make("Lift", &serde_json::json!({"horizon": 200}))?;
/// # Ok::<(), gym_core::Error>(())
/// ```
///
/// # Errors
/// [`Error::UnknownEnv`] for an unregistered id; [`Error::InvalidArgument`] when `kwargs`
/// is neither an object nor `null`; whatever the factory returns for bad arguments.
pub fn make(id: &str, kwargs: &serde_json::Value) -> Result<BoxedEnv> {
    let spec = spec(id)?;
    match kwargs {
        serde_json::Value::Object(map) => (spec.factory)(map),
        serde_json::Value::Null => (spec.factory)(&Kwargs::new()),
        other => Err(Error::invalid_argument(
            "kwargs",
            format!("must be an object of keyword arguments or null, got {other}"),
        )),
    }
}

/// Every registered id, in registration order.
pub fn registered_ids() -> Vec<String> {
    REGISTRY
        .read()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
        .keys()
        .cloned()
        .collect()
}
