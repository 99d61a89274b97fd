//! The bookkeeping both vector environments share: what each sub-environment's
//! [`Slot`] must do for a `step` or `reset`, and how the results are written into the batch
//! buffers and infos. [`SyncVectorEnv`](super::SyncVectorEnv) runs the slots in turn,
//! [`ThreadVectorEnv`](super::ThreadVectorEnv) on its threads; the semantics are
//! identical.

use super::info::VectorInfo;
use super::slot::{Done, ObsAt, Slot, Task};
use super::{AutoresetMode, Seeds, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, InfoValue, Metadata, ResetOptions, Result, RowLeaves, Transition};
use std::any::Any;

pub(crate) fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".to_owned())
}

/// The process that made a threaded vector env or pool. Its worker threads exist only in
/// that process: after `fork()` (Stable-Baselines3's `SubprocVecEnv` forks on Linux) the
/// child has the queues and slots but no threads, so a step would wait forever and a join
/// would fail. Every call compares the process id (one `getpid`, no allocation) and
/// refuses in a child.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct OwnerProcess(u32);

impl OwnerProcess {
    /// The calling process.
    pub(crate) fn current() -> Self {
        Self(std::process::id())
    }

    /// Whether the calling process is another one (a child made by `fork()`).
    pub(crate) fn forked(self) -> bool {
        std::process::id() != self.0
    }

    /// # Errors
    /// [`Error::Unsupported`] in a forked child.
    pub(crate) fn check(self, what: &str) -> Result<()> {
        if self.forked() {
            return Err(Error::unsupported(format!(
                "this {what} was made in process {} and its worker threads do not exist in \
                 this forked child (process {}); make a new one in the child",
                self.0,
                std::process::id()
            )));
        }
        Ok(())
    }
}

/// Sub-environment `i`'s error, wrapped (not rewritten) so that it names the
/// sub-environment and keeps the original as its source (see [`Error::in_env`]).
pub(crate) fn in_env(e: Error, i: usize) -> Error {
    e.in_env(i)
}

/// Spaces, buffers and autoreset flags of a vector environment.
#[derive(Debug)]
pub(crate) struct VectorCore<OS: BatchSpace, AS: BatchSpace> {
    pub(crate) n: usize,
    pub(crate) mode: AutoresetMode,
    pub(crate) single_obs: OS,
    pub(crate) single_act: AS,
    pub(crate) batched_obs: OS::Batched,
    pub(crate) batched_act: AS::Batched,
    pub(crate) metadata: Metadata,
    pub(crate) observations: BatchOf<OS>,
    pub(crate) rewards: Vec<f64>,
    pub(crate) terminations: Vec<bool>,
    pub(crate) truncations: Vec<bool>,
    pub(crate) autoreset: Vec<bool>,
    /// The infos of the last call, refilled by every call.
    pub(crate) infos: VectorInfo,
    pub(crate) closed: bool,
}

impl<OS: BatchSpace, AS: BatchSpace> VectorCore<OS, AS> {
    /// Checks that every sub-environment has the same spaces (Gymnasium's
    /// `observation_mode="same"`) and allocates the buffers.
    pub(crate) fn new<E: Env<ObsSpace = OS, ActSpace = AS>>(envs: &[E]) -> Result<Self> {
        let first = envs.first().ok_or_else(|| {
            Error::invalid_argument(
                "envs",
                "a vector environment needs at least one environment",
            )
        })?;
        let (single_obs, single_act) = (
            first.observation_space().clone(),
            first.action_space().clone(),
        );
        for (i, e) in envs.iter().enumerate().skip(1) {
            if e.observation_space() != &single_obs {
                return Err(Error::invalid_argument(
                    "envs",
                    format!(
                        "sub-environment {i}'s observation space differs from sub-environment 0's"
                    ),
                ));
            }
            if e.action_space() != &single_act {
                return Err(Error::invalid_argument(
                    "envs",
                    format!("sub-environment {i}'s action space differs from sub-environment 0's"),
                ));
            }
        }
        let n = envs.len();
        Ok(Self {
            n,
            mode: AutoresetMode::NextStep,
            batched_obs: single_obs.batch_space(n)?,
            batched_act: single_act.batch_space(n)?,
            observations: single_obs.create_empty_batch(n),
            metadata: first.metadata().clone(),
            single_obs,
            single_act,
            rewards: vec![0.0; n],
            terminations: vec![false; n],
            truncations: vec![false; n],
            autoreset: vec![false; n],
            infos: VectorInfo::new(n),
            closed: false,
        })
    }

    /// Gives `slot` its row of the batch when its environment writes rows
    /// ([`Env::writes_rows`]) and the observation space has row leaves
    /// ([`BatchSpace::row_leaves`]): its steps then write their observations straight
    /// into the batch (see [`Slot::row`]).
    pub(crate) fn attach_row<E: Env<ObsSpace = OS, ActSpace = AS>>(
        &mut self,
        slot: &mut Slot<E>,
        env: &E,
    ) {
        let mut leaves = RowLeaves::new();
        if env.writes_rows()
            && self
                .single_obs
                .row_leaves(&mut self.observations, slot.id, &mut leaves)
        {
            slot.row = Some(leaves);
        }
    }

    pub(crate) fn check_open(&self) -> Result<()> {
        if self.closed {
            Err(Error::Closed)
        } else {
            Ok(())
        }
    }

    /// Checks a `step(actions)` call before any sub-environment steps: open, no ended
    /// episode under `Disabled`, and exactly one finite action per sub-environment.
    ///
    /// # Errors
    /// [`Error::Closed`], [`Error::EpisodeEnded`], [`Error::InvalidAction`].
    pub(crate) fn check_step(&self, actions: &BatchOf<AS>) -> Result<()> {
        self.check_open()?;
        if self.mode == AutoresetMode::Disabled && self.autoreset.iter().any(|&a| a) {
            // Gymnasium asserts; the caller must reset the ended sub-environments first.
            return Err(Error::EpisodeEnded);
        }
        self.single_act.check_batch(actions, self.n)
    }

    /// Sets `slot`'s task for `step(actions)` and copies its action row into it (call
    /// [`check_step`](Self::check_step) first).
    ///
    /// # Errors
    /// [`Error::InvalidAction`] when the row cannot be read.
    pub(crate) fn plan_step<E: Env<ObsSpace = OS, ActSpace = AS>>(
        &self,
        slot: &mut Slot<E>,
        actions: &BatchOf<AS>,
    ) -> Result<()>
    where
        AS: gym_core::Space<Element = E::Act>,
    {
        let i = slot.id;
        slot.task = match self.mode {
            AutoresetMode::NextStep if self.autoreset[i] => Task::AutoReset,
            AutoresetMode::NextStep | AutoresetMode::Disabled => Task::Step,
            AutoresetMode::SameStep => Task::StepThenReset,
        };
        if !matches!(slot.task, Task::AutoReset) {
            self.single_act
                .read_item_into(actions, i, &mut slot.action)
                .map_err(|e| Error::invalid_action(format!("actions[{i}]: {e}")))?;
        }
        Ok(())
    }

    /// Starts recording the results of a call (empties the infos).
    pub(crate) fn begin(&mut self) {
        self.infos.clear();
    }

    /// Records what `slot` did in a step (call in sub-environment order, after
    /// [`begin`](Self::begin)). A failed sub-environment keeps its row.
    ///
    /// # Errors
    /// The sub-environment's error, its message prefixed with its index.
    pub(crate) fn finish_step<E: Env<ObsSpace = OS, ActSpace = AS>>(
        &mut self,
        slot: &mut Slot<E>,
    ) -> Result<()>
    where
        OS: gym_core::Space<Element = E::Obs>,
    {
        let i = slot.id;
        let done = std::mem::replace(&mut slot.done, Ok(Done::Idle));
        let written = match done {
            Ok(Done::Idle) => Ok(()),
            Ok(Done::Reset) => {
                self.rewards[i] = 0.0;
                self.terminations[i] = false;
                self.truncations[i] = false;
                self.infos.add(&slot.info, i);
                self.single_obs
                    .write_item(&mut self.observations, i, &slot.observation)
            }
            Ok(Done::Stepped(t)) => {
                self.set_step(i, t);
                self.infos.add(&slot.info, i);
                if slot.obs_at == ObsAt::Row {
                    Ok(())
                } else {
                    self.single_obs
                        .write_item(&mut self.observations, i, &slot.observation)
                }
            }
            Ok(Done::SteppedAndReset {
                transition,
                final_observation,
                final_info,
            }) => {
                self.set_step(i, transition);
                self.infos
                    .add_final(i, self.single_obs.to_value(&final_observation), &final_info);
                self.infos.add(&slot.info, i);
                self.single_obs
                    .write_item(&mut self.observations, i, &slot.observation)
            }
            Err(e) => Err(in_env(e, i)),
        };
        written?;
        self.autoreset[i] = self.terminations[i] || self.truncations[i];
        Ok(())
    }

    /// The step's view of the buffers and infos.
    pub(crate) fn view(&self) -> VectorStep<'_, BatchOf<OS>> {
        VectorStep {
            observations: &self.observations,
            rewards: &self.rewards,
            terminations: &self.terminations,
            truncations: &self.truncations,
            infos: &self.infos,
        }
    }

    fn set_step(&mut self, i: usize, t: Transition) {
        self.rewards[i] = t.reward;
        self.terminations[i] = t.terminated;
        self.truncations[i] = t.truncated;
    }

    /// One task per sub-environment for a reset ([`Task::Idle`] where the mask is off). A
    /// `"reset_mask"` entry of `options` (an integer array of 0/1 of shape `(n,)`, the form
    /// a NumPy bool array takes in an [`Info`]) is the mask, removed from the options the
    /// sub-environments see; `mask` is the typed form. Both at once are an error.
    pub(crate) fn plan_reset(
        &self,
        seeds: Seeds,
        options: Option<&ResetOptions>,
        mask: Option<&[bool]>,
    ) -> Result<Vec<Task>> {
        self.check_open()?;
        let seeds = seeds.resolve(self.n)?;
        let mut options = options.cloned();
        let option_mask = match options.as_mut().and_then(|o| o.remove("reset_mask")) {
            None => None,
            Some(InfoValue::Array(a)) => {
                if a.dtype().is_float()
                    || a.shape() != [self.n]
                    || a.to_f64_vec().iter().any(|&v| v != 0.0 && v != 1.0)
                {
                    return Err(Error::invalid_argument(
                        "reset_mask",
                        format!(
                            "expected a 0/1 (bool) array of shape ({},), got {} of shape {:?}",
                            self.n,
                            a.dtype(),
                            a.shape()
                        ),
                    ));
                }
                Some(
                    a.to_f64_vec()
                        .iter()
                        .map(|&v| v == 1.0)
                        .collect::<Vec<bool>>(),
                )
            }
            Some(other) => {
                return Err(Error::invalid_argument(
                    "reset_mask",
                    format!("expected a bool array, got a {}", other.kind()),
                ));
            }
        };
        let mask: Option<Vec<bool>> = match (mask, option_mask) {
            (Some(_), Some(_)) => {
                return Err(Error::invalid_argument(
                    "reset_mask",
                    "given both as an argument and in options",
                ));
            }
            (Some(m), None) => Some(m.to_vec()),
            (None, m) => m,
        };
        if let Some(m) = &mask {
            if m.len() != self.n {
                return Err(Error::invalid_argument(
                    "reset_mask",
                    format!("expected {} entries, got {}", self.n, m.len()),
                ));
            }
            if !m.iter().any(|&b| b) {
                return Err(Error::invalid_argument(
                    "reset_mask",
                    "at least one sub-environment must be reset",
                ));
            }
        }
        Ok(seeds
            .into_iter()
            .enumerate()
            .map(|(i, seed)| {
                if mask.as_ref().is_none_or(|m| m[i]) {
                    Task::Reset {
                        seed,
                        options: options.clone(),
                    }
                } else {
                    Task::Idle
                }
            })
            .collect())
    }

    /// Records what `slot` did in a (masked) reset (call in sub-environment order, after
    /// [`begin`](Self::begin)): a reset sub-environment's observation, cleared flags
    /// (including a pending autoreset) and info.
    ///
    /// # Errors
    /// The sub-environment's error, its message prefixed with its index.
    pub(crate) fn finish_reset<E: Env<ObsSpace = OS, ActSpace = AS>>(
        &mut self,
        slot: &mut Slot<E>,
    ) -> Result<()>
    where
        OS: gym_core::Space<Element = E::Obs>,
    {
        let i = slot.id;
        match std::mem::replace(&mut slot.done, Ok(Done::Idle)) {
            Ok(Done::Idle) => return Ok(()),
            Ok(Done::Reset) => {
                self.infos.add(&slot.info, i);
                self.single_obs
                    .write_item(&mut self.observations, i, &slot.observation)?;
            }
            Ok(_) => {
                return Err(Error::Contract {
                    check: "vector reset".into(),
                    message: "a reset returned a step".into(),
                });
            }
            Err(e) => return Err(in_env(e, i)),
        }
        self.terminations[i] = false;
        self.truncations[i] = false;
        self.autoreset[i] = false;
        Ok(())
    }
}
