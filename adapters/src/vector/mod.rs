//! Vector environments (Gymnasium's `gymnasium.vector`): `n` copies of an environment
//! stepped as one, with batched spaces, batched observations in one preallocated buffer,
//! and infos batched with `_key` masks.
//!
//! * [`SyncVectorEnv`] steps the sub-environments in turn on the calling thread.
//! * [`ThreadVectorEnv`] steps them on persistent worker threads (Gymnasium's
//!   `AsyncVectorEnv`, with threads instead of processes since Rust environments are `Send`).
//!
//! * [`ThreadEnvPool`] is EnvPool's asynchronous mode: `recv` returns the first
//!   `batch_size` environments to finish and `send` steps exactly those, so threads do not
//!   wait for the slowest environment (not a [`VectorEnv`]: batches hold changing ids).
//! * [`ThreadOptions`] sets the thread count of either and can pin the worker threads to
//!   CPUs.
//!
//! The two vector envs implement [`VectorEnv`] with the same semantics:
//!
//! * `reset(seed)`: an integer seed gives sub-environment `i` the seed `seed + i`
//!   ([`Seeds`]); a reset mask (typed, or `options["reset_mask"]`) resets only some of them;
//!   a reset clears the reset sub-environments' flags **and pending autoresets** (Gymnasium's
//!   `AsyncVectorEnv(shared_memory=False)` forgets the latter; this port does not).
//! * [`AutoresetMode`]: `NextStep` (default; the step after an episode ended resets that
//!   sub-environment, ignoring its action, and returns its reset observation with reward 0
//!   and no flags), `SameStep` (the ending step resets at once, returns the reset
//!   observation with the ending step's reward and flags, and puts `final_obs` /
//!   `final_info` in the infos) and `Disabled` (the caller resets with a mask; stepping a
//!   sub-environment whose episode ended is [`Error::EpisodeEnded`](gym_core::Error)).
//! * Rewards are `f64`, terminations and truncations `bool`, one per sub-environment.
//! * A batch of actions must hold exactly one row per sub-environment (per id for the
//!   pool), each of the single action space's shape, with no NaN or ±inf: the whole batch
//!   is checked before any sub-environment steps, so a rejected call changes nothing.
//! * A sub-environment's error is returned as its typed error (messages prefixed with its
//!   index); the other sub-environments' results of that call are still recorded. A panic
//!   in a sub-environment (on any thread) becomes [`Error::Simulation`](gym_core::Error),
//!   never a hang, and that sub-environment refuses further calls.
//! * An environment that [writes rows](gym_core::Env::writes_rows) (the robosuite tasks,
//!   behind `GymWrapper` / `FlatGymWrapper` / `TimeLimit` / `BoxedEnv` too) writes each
//!   step's observation straight into its row of the batch
//!   ([`Env::write_observation_row`](gym_core::Env::write_observation_row); a pool, into
//!   the row `recv` returns it in): camera images are copied once per step. Other
//!   environments, resets and `SameStep` steps go through
//!   [`Env::step_into`](gym_core::Env::step_into) into per-environment buffers, then into
//!   the batch. The infos are refilled in place, so over environments whose `step_into`
//!   reuses its buffers a vector step (and a pool's `send` / `recv`) does not allocate.
//! * After `fork()`, a [`ThreadVectorEnv`] or [`ThreadEnvPool`] used in the child returns
//!   [`Error::Unsupported`](gym_core::Error) (its threads exist only in the parent); closing
//!   or dropping it there neither joins nor waits.

mod core;
pub mod info;
mod pool;
mod queue;
mod slot;
mod sync;
mod team;
mod thread;
mod threads;

pub use info::{VectorInfo, VectorInfoValue};
pub use pool::{PoolStep, ThreadEnvPool};
pub use sync::SyncVectorEnv;
pub use thread::ThreadVectorEnv;
pub use threads::ThreadOptions;

use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Error, Metadata, ResetOptions, Result};

/// When sub-environments are reset after their episodes end (Gymnasium's
/// `AutoresetMode`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum AutoresetMode {
    /// Reset on the step after the episode ended (Gymnasium 1.x's default).
    #[default]
    NextStep,
    /// Reset within the step that ended the episode; `final_obs` / `final_info` in infos.
    SameStep,
    /// Never reset automatically.
    Disabled,
}

impl AutoresetMode {
    /// Gymnasium's value of the mode (`"NextStep"`, `"SameStep"`, `"Disabled"`).
    pub fn as_str(self) -> &'static str {
        match self {
            AutoresetMode::NextStep => "NextStep",
            AutoresetMode::SameStep => "SameStep",
            AutoresetMode::Disabled => "Disabled",
        }
    }
}

/// Seeds for a vector reset.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub enum Seeds {
    /// No seeds (each sub-environment continues its RNG stream).
    #[default]
    None,
    /// Sub-environment `i` gets `seed + i` (wrapping).
    Base(u64),
    /// One optional seed per sub-environment.
    PerEnv(Vec<Option<u64>>),
}

impl Seeds {
    /// One seed per sub-environment.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] when a per-environment list does not have `n` entries.
    pub fn resolve(&self, n: usize) -> Result<Vec<Option<u64>>> {
        match self {
            Seeds::None => Ok(vec![None; n]),
            Seeds::Base(s) => Ok((0..n as u64).map(|i| Some(s.wrapping_add(i))).collect()),
            Seeds::PerEnv(v) if v.len() == n => Ok(v.clone()),
            Seeds::PerEnv(v) => Err(Error::invalid_argument(
                "seed",
                format!("expected {n} seeds, got {}", v.len()),
            )),
        }
    }
}

impl From<Option<u64>> for Seeds {
    fn from(s: Option<u64>) -> Self {
        s.map_or(Seeds::None, Seeds::Base)
    }
}

impl From<u64> for Seeds {
    fn from(s: u64) -> Self {
        Seeds::Base(s)
    }
}

impl From<Vec<Option<u64>>> for Seeds {
    fn from(v: Vec<Option<u64>>) -> Self {
        Seeds::PerEnv(v)
    }
}

impl From<Vec<u64>> for Seeds {
    fn from(v: Vec<u64>) -> Self {
        Seeds::PerEnv(v.into_iter().map(Some).collect())
    }
}

/// What a vector `step` returns. The observations, rewards and flags borrow the vector
/// environment's buffers (no copy); clone what must outlive the next call.
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct VectorStep<'a, O> {
    /// The batched observations (the reset observation for sub-environments that were
    /// reset in this step).
    pub observations: &'a O,
    /// One reward per sub-environment.
    pub rewards: &'a [f64],
    /// One `terminated` flag per sub-environment.
    pub terminations: &'a [bool],
    /// One `truncated` flag per sub-environment.
    pub truncations: &'a [bool],
    /// The batched infos (refilled by the next call).
    pub infos: &'a VectorInfo,
}

/// A batch of environments stepped together (Gymnasium's `VectorEnv`; not an `Env`).
pub trait VectorEnv {
    /// One sub-environment's observation space.
    type ObsSpace: BatchSpace;
    /// One sub-environment's action space.
    type ActSpace: BatchSpace;

    /// The number of sub-environments.
    fn num_envs(&self) -> usize;

    /// One sub-environment's observation space.
    fn single_observation_space(&self) -> &Self::ObsSpace;

    /// One sub-environment's action space.
    fn single_action_space(&self) -> &Self::ActSpace;

    /// The batched observation space (`batch_space(single, n)`).
    fn observation_space(&self) -> &<Self::ObsSpace as BatchSpace>::Batched;

    /// The batched action space (`batch_space(single, n)`).
    fn action_space(&self) -> &<Self::ActSpace as BatchSpace>::Batched;

    /// Sub-environment 0's metadata.
    fn metadata(&self) -> &Metadata;

    /// The autoreset mode.
    fn autoreset_mode(&self) -> AutoresetMode;

    /// Resets every sub-environment (or those selected by `options["reset_mask"]`).
    ///
    /// # Errors
    /// [`Error::Closed`] after `close`; [`Error::InvalidArgument`] for a bad seed list or
    /// mask; a sub-environment's error.
    fn reset(
        &mut self,
        seed: impl Into<Seeds>,
        options: Option<&ResetOptions>,
    ) -> Result<(&BatchOf<Self::ObsSpace>, &VectorInfo)>;

    /// Resets the sub-environments whose `mask` entry is true (Gymnasium's
    /// `options={"reset_mask": mask}`); the others keep their observation and state.
    ///
    /// # Errors
    /// As [`VectorEnv::reset`]; a mask that is not `num_envs` long or selects nothing.
    fn reset_masked(
        &mut self,
        mask: &[bool],
        seed: impl Into<Seeds>,
        options: Option<&ResetOptions>,
    ) -> Result<(&BatchOf<Self::ObsSpace>, &VectorInfo)>;

    /// Steps every sub-environment with its row of `actions`.
    ///
    /// # Errors
    /// [`Error::Closed`] after `close`; [`Error::InvalidAction`] for a malformed batch;
    /// [`Error::EpisodeEnded`] under [`AutoresetMode::Disabled`] when a sub-environment's
    /// episode ended; a sub-environment's error.
    fn step(
        &mut self,
        actions: &BatchOf<Self::ActSpace>,
    ) -> Result<VectorStep<'_, BatchOf<Self::ObsSpace>>>;

    /// The current batched observations.
    fn observations(&self) -> &BatchOf<Self::ObsSpace>;

    /// Closes every sub-environment (and joins worker threads); idempotent.
    fn close(&mut self);

    /// Whether `close` has been called.
    fn is_closed(&self) -> bool;
}

/// The parts of [`VectorEnv`] that [`SyncVectorEnv`] and [`ThreadVectorEnv`] share: space
/// and metadata accessors read from `self.core` (a `VectorCore`), and the resets that go
/// through `self.run_reset`. Used inside both `impl VectorEnv` blocks.
macro_rules! delegate_to_core {
    ($obs:ty, $act:ty) => {
        fn num_envs(&self) -> usize {
            self.core.n
        }

        fn single_observation_space(&self) -> &$obs {
            &self.core.single_obs
        }

        fn single_action_space(&self) -> &$act {
            &self.core.single_act
        }

        fn observation_space(&self) -> &<$obs as BatchSpace>::Batched {
            &self.core.batched_obs
        }

        fn action_space(&self) -> &<$act as BatchSpace>::Batched {
            &self.core.batched_act
        }

        fn metadata(&self) -> &Metadata {
            &self.core.metadata
        }

        fn autoreset_mode(&self) -> AutoresetMode {
            self.core.mode
        }

        fn reset(
            &mut self,
            seed: impl Into<Seeds>,
            options: Option<&ResetOptions>,
        ) -> Result<(&BatchOf<$obs>, &VectorInfo)> {
            self.run_reset(seed.into(), options, None)?;
            Ok((&self.core.observations, &self.core.infos))
        }

        fn reset_masked(
            &mut self,
            mask: &[bool],
            seed: impl Into<Seeds>,
            options: Option<&ResetOptions>,
        ) -> Result<(&BatchOf<$obs>, &VectorInfo)> {
            self.run_reset(seed.into(), options, Some(mask))?;
            Ok((&self.core.observations, &self.core.infos))
        }

        fn observations(&self) -> &BatchOf<$obs> {
            &self.core.observations
        }

        fn is_closed(&self) -> bool {
            self.core.closed
        }
    };
}
pub(crate) use delegate_to_core;
