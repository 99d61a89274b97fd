//! [`SavedEnv`]: an environment's whole run-time state (episode snapshot and RNG) as text,
//! for pickling and deep copies: an env made with the same configuration and given it
//! continues bit-identically.

use crate::env::{EnvSnapshot, RobosuiteEnv};
use gym_core::{EnvRng, Error, Result};
use serde::{Deserialize, Serialize};

/// Everything [`RobosuiteEnv::snapshot`] holds plus the RNG.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SavedEnv {
    /// The episode state.
    pub snapshot: EnvSnapshot,
    /// The environment RNG (PCG64's state and increment).
    pub rng: EnvRng,
    /// Whether the RNG was seeded.
    pub rng_seeded: bool,
}

impl SavedEnv {
    /// The state of `env`.
    pub fn of(env: &RobosuiteEnv) -> Self {
        let (rng, rng_seeded) = env.rng_state();
        Self {
            snapshot: env.snapshot(),
            rng,
            rng_seeded,
        }
    }

    /// Restores this state into `env`, which must be made with the same configuration (and
    /// scene) as the env it was taken from.
    ///
    /// # Errors
    /// As [`RobosuiteEnv::restore`]; nothing is changed then.
    pub fn apply(&self, env: &mut RobosuiteEnv) -> Result<()> {
        env.restore(&self.snapshot)?;
        env.set_rng(self.rng.clone(), self.rng_seeded);
        Ok(())
    }

    /// As JSON (floats written exactly: shortest round-trip form).
    ///
    /// # Errors
    /// [`Error::Simulation`] for a state holding a NaN or ±inf, which JSON cannot hold.
    pub fn to_json(&self) -> Result<String> {
        serde_json::to_string(self)
            .map_err(|e| Error::simulation(format!("cannot serialise the env state: {e}")))
    }

    /// From [`SavedEnv::to_json`]'s text.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for text that is not such a state.
    pub fn from_json(text: &str) -> Result<Self> {
        serde_json::from_str(text)
            .map_err(|e| Error::invalid_argument("state", format!("not a saved env state: {e}")))
    }
}
