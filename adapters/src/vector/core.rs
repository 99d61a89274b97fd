//! The bookkeeping both vector environments share: what each sub-environment must do for a
//! `step` or `reset`, and how the results are written into the batch buffers and infos.
//! [`SyncVectorEnv`](super::SyncVectorEnv) runs the operations in turn,
//! [`ThreadVectorEnv`](super::ThreadVectorEnv) on its worker threads; the semantics are
//! identical.

use super::info::VectorInfo;
use super::{AutoresetMode, Seeds, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Info, InfoValue, Metadata, ResetOptions, Result, Step};
use std::any::Any;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// What one sub-environment does.
#[derive(Debug)]
pub(crate) enum Op<A> {
    /// An explicit reset.
    Reset {
        seed: Option<u64>,
        options: Option<ResetOptions>,
    },
    /// `NEXT_STEP`'s autoreset: `reset()` without seed or options, action ignored.
    AutoReset,
    /// A step.
    Step(A),
    /// `SAME_STEP`: a step, then `reset()` if it ended the episode.
    StepThenReset(A),
}

/// What one sub-environment returned.
#[derive(Debug)]
pub(crate) enum Outcome<O> {
    /// From `Reset` or `AutoReset`.
    Reset(O, Info),
    /// From `Step`, or `StepThenReset` when the episode went on.
    Step(Step<O>),
    /// From `StepThenReset` when the step ended the episode.
    StepReset {
        step: Step<O>,
        observation: O,
        info: Info,
    },
}

/// Runs one operation on one environment.
pub(crate) fn run_op<E: Env>(env: &mut E, op: Op<E::Act>) -> Result<Outcome<E::Obs>> {
    match op {
        Op::Reset { seed, options } => {
            let (o, i) = env.reset(seed, options.as_ref())?;
            Ok(Outcome::Reset(o, i))
        }
        Op::AutoReset => {
            let (o, i) = env.reset(None, None)?;
            Ok(Outcome::Reset(o, i))
        }
        Op::Step(a) => Ok(Outcome::Step(env.step(&a)?)),
        Op::StepThenReset(a) => {
            let step = env.step(&a)?;
            if step.terminated || step.truncated {
                let (observation, info) = env.reset(None, None)?;
                Ok(Outcome::StepReset {
                    step,
                    observation,
                    info,
                })
            } else {
                Ok(Outcome::Step(step))
            }
        }
    }
}

/// [`run_op`] for sub-environment `id`, refusing it when `poisoned` (it panicked before);
/// a panic sets `poisoned` and becomes an [`Error::Simulation`].
pub(crate) fn run_op_guarded<E: Env>(
    env: &mut E,
    op: Op<E::Act>,
    id: usize,
    poisoned: &mut bool,
) -> Result<Outcome<E::Obs>> {
    if *poisoned {
        return Err(Error::simulation(format!(
            "sub-environment {id} panicked earlier and is unusable"
        )));
    }
    catch_unwind(AssertUnwindSafe(|| run_op(env, op))).unwrap_or_else(|payload| {
        *poisoned = true;
        Err(Error::simulation(format!(
            "panicked: {}",
            panic_message(payload.as_ref())
        )))
    })
}

fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".to_owned())
}

/// Prefixes the message of a sub-environment's error with its index, where the variant
/// carries one.
/// Checks a whole batch of actions before any sub-environment steps, so that a rejected
/// call changes nothing: `actions` must hold exactly the items `batched` (the batched space
/// of those items) has, each of `single`'s shape, and no NaN or ±inf value (which every
/// environment of this workspace rejects).
///
/// # Errors
/// [`Error::InvalidAction`] naming the first problem.
pub(crate) fn check_batch<S: BatchSpace>(
    single: &S,
    batched: &S::Batched,
    actions: &BatchOf<S>,
    rows: usize,
) -> Result<()> {
    use gym_core::Flatten;
    for k in 0..rows {
        single
            .read_item(actions, k)
            .map_err(|e| Error::invalid_action(format!("actions[{k}]: {e}")))?;
    }
    // Every item exists and has the item's shape; the flat length then pins the number of
    // items to exactly `rows`.
    let flat = batched.flatten(actions).map_err(|e| {
        Error::invalid_action(format!("expected a batch of exactly {rows} actions: {e}"))
    })?;
    if !flat.all_finite() {
        let values = flat.to_f64_vec();
        let at = values.iter().position(|v| !v.is_finite()).unwrap_or(0);
        let per_row = (values.len() / rows.max(1)).max(1);
        return Err(Error::invalid_action(format!(
            "actions[{}] holds a value that is not finite ({}); nothing was stepped",
            at / per_row,
            values[at]
        )));
    }
    Ok(())
}

/// The process that made a threaded vector env or pool. Its worker threads exist only in
/// that process: after `fork()` (Stable-Baselines3's `SubprocVecEnv` forks on Linux) the
/// child has the channels but no threads, so a step would wait forever and a join would
/// fail. Every call compares the process id (one `getpid`, no allocation) and refuses in a
/// child.
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
            closed: false,
        })
    }

    pub(crate) fn check_open(&self) -> Result<()> {
        if self.closed {
            Err(Error::Closed)
        } else {
            Ok(())
        }
    }

    /// One operation per sub-environment for `step(actions)`.
    pub(crate) fn plan_step(&self, actions: &BatchOf<AS>) -> Result<Vec<Op<AS::Element>>> {
        self.check_open()?;
        if self.mode == AutoresetMode::Disabled && self.autoreset.iter().any(|&a| a) {
            // Gymnasium asserts; the caller must reset the ended sub-environments first.
            return Err(Error::EpisodeEnded);
        }
        check_batch(&self.single_act, &self.batched_act, actions, self.n)?;
        (0..self.n)
            .map(|i| {
                let a = self
                    .single_act
                    .read_item(actions, i)
                    .map_err(|e| Error::invalid_action(format!("actions[{i}]: {e}")))?;
                Ok(match self.mode {
                    AutoresetMode::NextStep if self.autoreset[i] => Op::AutoReset,
                    AutoresetMode::NextStep | AutoresetMode::Disabled => Op::Step(a),
                    AutoresetMode::SameStep => Op::StepThenReset(a),
                })
            })
            .collect()
    }

    /// Records the outcomes of a step (in sub-environment order) and builds the infos. The
    /// successful sub-environments are recorded even when another failed; the first error
    /// is then returned.
    pub(crate) fn finish_step(
        &mut self,
        outcomes: Vec<Result<Outcome<OS::Element>>>,
    ) -> Result<VectorInfo> {
        let mut infos = VectorInfo::new(self.n);
        let mut first_err = None;
        for (i, outcome) in outcomes.into_iter().enumerate() {
            let written = match outcome {
                Ok(Outcome::Reset(obs, info)) => {
                    self.rewards[i] = 0.0;
                    self.terminations[i] = false;
                    self.truncations[i] = false;
                    let w = self.single_obs.write_item(&mut self.observations, i, &obs);
                    infos.add(&info, i);
                    w
                }
                Ok(Outcome::Step(step)) => {
                    self.set_step(i, &step);
                    let w =
                        self.single_obs
                            .write_item(&mut self.observations, i, &step.observation);
                    infos.add(&step.info, i);
                    w
                }
                Ok(Outcome::StepReset {
                    step,
                    observation,
                    info,
                }) => {
                    self.set_step(i, &step);
                    infos.add_final(i, self.single_obs.to_value(&step.observation), &step.info);
                    let w = self
                        .single_obs
                        .write_item(&mut self.observations, i, &observation);
                    infos.add(&info, i);
                    w
                }
                Err(e) => Err(in_env(e, i)),
            };
            match written {
                Ok(()) => self.autoreset[i] = self.terminations[i] || self.truncations[i],
                Err(e) => {
                    first_err.get_or_insert(e);
                }
            }
        }
        match first_err {
            Some(e) => Err(e),
            None => Ok(infos),
        }
    }

    /// The step's view of the buffers, with `infos`.
    pub(crate) fn view(&self, infos: VectorInfo) -> VectorStep<'_, BatchOf<OS>> {
        VectorStep {
            observations: &self.observations,
            rewards: &self.rewards,
            terminations: &self.terminations,
            truncations: &self.truncations,
            infos,
        }
    }

    fn set_step(&mut self, i: usize, step: &Step<OS::Element>) {
        self.rewards[i] = step.reward;
        self.terminations[i] = step.terminated;
        self.truncations[i] = step.truncated;
    }

    /// One optional reset per sub-environment (`None` where the mask is off). A
    /// `"reset_mask"` entry of `options` (an integer array of 0/1 of shape `(n,)`, the form
    /// a NumPy bool array takes in an [`Info`]) is the mask, removed from the options the
    /// sub-environments see; `mask` is the typed form. Both at once are an error.
    pub(crate) fn plan_reset(
        &self,
        seeds: Seeds,
        options: Option<&ResetOptions>,
        mask: Option<&[bool]>,
    ) -> Result<Vec<Option<Op<AS::Element>>>> {
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
                mask.as_ref().is_none_or(|m| m[i]).then(|| Op::Reset {
                    seed,
                    options: options.clone(),
                })
            })
            .collect())
    }

    /// Records the outcomes of a (masked) reset: the reset sub-environments' observations,
    /// cleared flags (including pending autoresets) and infos.
    pub(crate) fn finish_reset(
        &mut self,
        outcomes: Vec<Option<Result<Outcome<OS::Element>>>>,
    ) -> Result<VectorInfo> {
        let mut infos = VectorInfo::new(self.n);
        let mut first_err = None;
        for (i, outcome) in outcomes.into_iter().enumerate() {
            let result = match outcome {
                None => continue,
                Some(Ok(Outcome::Reset(obs, info))) => {
                    infos.add(&info, i);
                    self.single_obs.write_item(&mut self.observations, i, &obs)
                }
                Some(Ok(_)) => Err(Error::Contract {
                    check: "vector reset".into(),
                    message: "a reset returned a step".into(),
                }),
                Some(Err(e)) => Err(in_env(e, i)),
            };
            match result {
                Ok(()) => {
                    self.terminations[i] = false;
                    self.truncations[i] = false;
                    self.autoreset[i] = false;
                }
                Err(e) => {
                    first_err.get_or_insert(e);
                }
            }
        }
        match first_err {
            Some(e) => Err(e),
            None => Ok(infos),
        }
    }
}
