//! [`Slot`]: the buffers one sub-environment of a vector environment steps into — the task
//! to run, its action, its observation and info (reused by [`Env::step_into`], so a step
//! allocates nothing) and what happened. Both vector environments run the same
//! [`Slot::run`]: `SyncVectorEnv` in turn, `ThreadVectorEnv` on whichever thread claims the
//! sub-environment, and [`ThreadEnvPool`](super::ThreadEnvPool) on whichever worker takes
//! it from its queue.

use super::core::panic_message;
use crate::batch::BatchSpace;
use gym_core::{Env, Error, Info, ObsRow, ResetOptions, Result, RowLeaves, Transition};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// What one sub-environment does in a call.
#[derive(Debug, Default)]
pub(crate) enum Task {
    /// Nothing (a masked reset that leaves it alone).
    #[default]
    Idle,
    /// An explicit reset.
    Reset {
        seed: Option<u64>,
        options: Option<ResetOptions>,
    },
    /// `NextStep`'s autoreset: `reset()` without seed or options, action ignored.
    AutoReset,
    /// A step with the slot's action.
    Step,
    /// `SameStep`: a step, then `reset()` if it ended the episode.
    StepThenReset,
}

/// What one sub-environment did (its observation and info are in the slot).
#[derive(Debug)]
pub(crate) enum Done<O> {
    /// Nothing was asked.
    Idle,
    /// It was reset.
    Reset,
    /// It stepped.
    Stepped(Transition),
    /// It stepped, ended its episode and was reset (`SameStep`); the ending step's
    /// observation and info.
    SteppedAndReset {
        transition: Transition,
        final_observation: O,
        final_info: Info,
    },
}

/// Where the observation of a slot's last call is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum ObsAt {
    /// In [`Slot::observation`] (to be copied into the batch).
    #[default]
    Slot,
    /// Already in the slot's row of the batch ([`Slot::row`]).
    Row,
    /// Still in the environment ([`Env::write_observation_row`] writes it; the pool's
    /// `recv`).
    Env,
}

/// A sub-environment with its buffers: what a worker thread locks and runs.
#[derive(Debug)]
pub(crate) struct Member<E: Env> {
    pub(crate) env: E,
    pub(crate) slot: Slot<E>,
}

impl<E: Env> Member<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    /// Sub-environment `id`, `env`, with zeroed buffers.
    pub(crate) fn new(id: usize, env: E) -> Self {
        Self {
            slot: Slot::new(id, &env),
            env,
        }
    }
}

impl<E: Env> Member<E> {
    /// Runs the slot's task on the environment ([`Slot::run`]).
    pub(crate) fn run(&mut self) {
        self.slot.run(&mut self.env);
    }

    /// Closes the environment unless it panicked.
    pub(crate) fn close(&mut self) {
        self.slot.close(&mut self.env);
    }
}

/// The buffers of one sub-environment.
#[derive(Debug)]
pub(crate) struct Slot<E: Env> {
    /// The sub-environment's index.
    pub(crate) id: usize,
    /// What to do in this call.
    pub(crate) task: Task,
    /// The action of a step.
    pub(crate) action: E::Act,
    /// The last observation (written in place by `step_into`).
    pub(crate) observation: E::Obs,
    /// The last info (written in place by `step_into`).
    pub(crate) info: Info,
    /// What the last call did.
    pub(crate) done: Result<Done<E::Obs>>,
    /// Whether the environment panicked (it then refuses every operation).
    pub(crate) poisoned: bool,
    /// The slot's row of its vector environment's batch, when the environment writes
    /// rows ([`Env::writes_rows`]): a step writes its observation there, on the thread
    /// that runs it, and nowhere else.
    pub(crate) row: Option<RowLeaves>,
    /// Steps keep the observation in the environment for the pool's `recv` to write into
    /// the row it gives it.
    pub(crate) deferred: bool,
    /// Where the last call's observation is.
    pub(crate) obs_at: ObsAt,
}

impl<E: Env> Slot<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    /// Zeroed buffers for sub-environment `id`, `env`.
    pub(crate) fn new(id: usize, env: &E) -> Self {
        Self {
            id,
            action: env.action_space().zero_element(),
            observation: env.observation_space().zero_element(),
            task: Task::Idle,
            info: Info::new(),
            done: Ok(Done::Idle),
            poisoned: false,
            row: None,
            deferred: false,
            obs_at: ObsAt::Slot,
        }
    }
}

impl<E: Env> Slot<E> {
    /// Runs the slot's task on `env` (leaving [`Task::Idle`]) and records what happened; a
    /// panic poisons the slot and becomes an [`Error::Simulation`], and a poisoned slot
    /// refuses.
    pub(crate) fn run(&mut self, env: &mut E) {
        let task = std::mem::take(&mut self.task);
        self.obs_at = ObsAt::Slot;
        if matches!(task, Task::Idle) {
            self.done = Ok(Done::Idle);
            return;
        }
        if self.poisoned {
            self.done = Err(Error::simulation(format!(
                "sub-environment {} panicked earlier and is unusable",
                self.id
            )));
            return;
        }
        let done = catch_unwind(AssertUnwindSafe(|| self.run_task(env, task)));
        self.done = done.unwrap_or_else(|payload| {
            self.poisoned = true;
            Err(Error::simulation(format!(
                "panicked: {}",
                panic_message(payload.as_ref())
            )))
        });
    }

    fn run_task(&mut self, env: &mut E, task: Task) -> Result<Done<E::Obs>> {
        match task {
            Task::Idle => Ok(Done::Idle),
            Task::Reset { seed, options } => self.reset(env, seed, options.as_ref()),
            Task::AutoReset => self.reset(env, None, None),
            Task::Step if self.deferred => {
                let t = env.step_for_row(&self.action, &mut self.info)?;
                self.obs_at = ObsAt::Env;
                Ok(Done::Stepped(t))
            }
            Task::Step => match &self.row {
                Some(leaves) => {
                    let t = env.step_for_row(&self.action, &mut self.info)?;
                    // SAFETY: `leaves` is this slot's row of its vector environment's batch
                    // (`VectorCore::attach_row`): the batch's arrays are allocated once and
                    // never replaced, the vector environment does not touch the batch while
                    // slots run, and the rows of different slots do not overlap.
                    let mut row = unsafe { ObsRow::from_raw(leaves.as_slice()) };
                    env.write_observation_row(&mut row)?;
                    self.obs_at = ObsAt::Row;
                    Ok(Done::Stepped(t))
                }
                None => {
                    let t = env.step_into(&self.action, &mut self.observation, &mut self.info)?;
                    Ok(Done::Stepped(t))
                }
            },
            Task::StepThenReset => {
                let transition =
                    env.step_into(&self.action, &mut self.observation, &mut self.info)?;
                if !transition.done() {
                    return Ok(Done::Stepped(transition));
                }
                let final_observation = self.observation.clone();
                let final_info = self.info.clone();
                self.reset(env, None, None)?;
                Ok(Done::SteppedAndReset {
                    transition,
                    final_observation,
                    final_info,
                })
            }
        }
    }

    fn reset(
        &mut self,
        env: &mut E,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<Done<E::Obs>> {
        let (observation, info) = env.reset(seed, options)?;
        self.observation = observation;
        self.info = info;
        Ok(Done::Reset)
    }

    /// Closes `env` unless it panicked.
    pub(crate) fn close(&self, env: &mut E) {
        if !self.poisoned {
            let _ = catch_unwind(AssertUnwindSafe(|| env.close()));
        }
    }
}
