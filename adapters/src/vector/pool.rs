//! [`ThreadEnvPool`]: EnvPool's asynchronous mode on threads. `recv` returns the first
//! `batch_size` environments to finish, `send` gives exactly those their next actions, so
//! no thread waits for the slowest environment of a batch.

use super::core::{Op, Outcome, OwnerProcess, VectorCore, in_env, run_op_guarded};
use super::{Seeds, VectorInfo};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Result};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::JoinHandle;

/// One environment and whether it panicked (it then refuses every operation).
struct Slot<E> {
    env: Mutex<E>,
    poisoned: AtomicBool,
}

type Job<A> = (usize, Op<A>);
type Done<O> = (usize, Result<Outcome<O>>);

/// Where an environment is between `send` and `recv`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Turn {
    /// Queued or running on a worker.
    Pending,
    /// Returned by `recv` (or not yet reset), waiting for `send`; `ended` when its last
    /// step ended the episode, so the next `send` resets it.
    Held { ended: bool },
}

/// What [`ThreadEnvPool::recv`] returns: `batch_size` environments, in the order they
/// finished. The arrays borrow the pool's buffers (no copy).
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct PoolStep<'a, O> {
    /// Which environment each row belongs to.
    pub env_ids: &'a [usize],
    /// The batched observations (the reset observation for environments that were reset).
    pub observations: &'a O,
    /// One reward per row.
    pub rewards: &'a [f64],
    /// One `terminated` flag per row.
    pub terminations: &'a [bool],
    /// One `truncated` flag per row.
    pub truncations: &'a [bool],
    /// The batched infos, one row per returned environment.
    pub infos: VectorInfo,
}

/// EnvPool's asynchronous mode with threads: `num_envs` environments stepped by
/// `min(num_envs, available_parallelism)` worker threads that take the next queued
/// operation whichever environment it belongs to.
///
/// * [`reset`](Self::reset) queues a reset of every environment (environment `i` gets
///   `seed + i`, as in the vector envs); [`recv`](Self::recv) then returns the first
///   `batch_size` to finish, with their ids.
/// * [`send`](Self::send) gives the environments of the last `recv` (any subset of the
///   held ones, by id) their next actions. An environment whose episode ended is reset
///   instead, its action ignored, and comes back with the reset observation, reward 0 and
///   no flags (Gymnasium's `NextStep` autoreset, as EnvPool does).
/// * With `batch_size == num_envs` every call waits for all environments, like a
///   synchronous vector env; with `num_envs` ≈ 2–3 × `batch_size` the threads never wait
///   for the slowest environment of a batch.
///
/// Each environment's trajectory depends only on its seed and the actions sent to it, so
/// it is reproducible; which environments share a batch depends on timing. A panic in an
/// environment is returned as [`Error::Simulation`] and that environment refuses further
/// operations; a sent id that is unknown, repeated or still pending is an
/// [`Error::InvalidArgument`], and nothing is queued.
///
/// ```
/// use adapters::{BatchSpace, ThreadEnvPool, WrapperExt};
/// use gym_core::{Space, rng_from_seed};
///
/// let envs = (0..4)
///     .map(|_| robosuite_env::make("Lift")?.flat_gym_wrapper(None))
///     .collect::<gym_core::Result<Vec<_>>>()?;
/// let mut pool = ThreadEnvPool::new(envs, 2)?;
/// let actions = pool.single_action_space().batch_space(2)?;
/// let mut rng = rng_from_seed(0);
/// pool.reset(7u64)?;
/// let mut ids = pool.recv()?.env_ids.to_vec();
/// for _ in 0..10 {
///     // A policy would map the batch's observations to actions here.
///     let batch = pool.step(&actions.sample(&mut rng), &ids)?;
///     assert_eq!(batch.observations.shape(), [2, 60]);
///     ids = batch.env_ids.to_vec();
/// }
/// # Ok::<(), gym_core::Error>(())
/// ```
pub struct ThreadEnvPool<E: Env>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    single_obs: E::ObsSpace,
    single_act: E::ActSpace,
    batch_size: usize,
    slots: Arc<Vec<Slot<E>>>,
    jobs: Option<Sender<Job<E::Act>>>,
    done: Receiver<Done<E::Obs>>,
    workers: Vec<JoinHandle<()>>,
    turns: Vec<Turn>,
    was_reset: bool,
    observations: BatchOf<E::ObsSpace>,
    env_ids: Vec<usize>,
    rewards: Vec<f64>,
    terminations: Vec<bool>,
    truncations: Vec<bool>,
    closed: bool,
    owner: OwnerProcess,
}

/// A worker: takes the next job, runs it on its environment, reports the outcome; exits
/// when the pool drops its job sender.
fn worker_loop<E: Env>(
    slots: Arc<Vec<Slot<E>>>,
    jobs: Arc<Mutex<Receiver<Job<E::Act>>>>,
    done: Sender<Done<E::Obs>>,
) {
    loop {
        let job = jobs.lock().unwrap_or_else(PoisonError::into_inner).recv();
        let Ok((id, op)) = job else { break };
        let slot = &slots[id];
        let mut poisoned = slot.poisoned.load(Ordering::Acquire);
        let result = {
            let mut env = slot.env.lock().unwrap_or_else(PoisonError::into_inner);
            run_op_guarded(&mut *env, op, id, &mut poisoned)
        };
        slot.poisoned.store(poisoned, Ordering::Release);
        if done.send((id, result)).is_err() {
            break;
        }
    }
}

impl<E: Env> ThreadEnvPool<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    /// A pool of `envs` whose `recv` returns `batch_size` of them, on
    /// `min(num_envs, available_parallelism)` threads.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no environments, differing spaces, or a batch size
    /// outside `1..=num_envs`; an OS error spawning a thread as [`Error::Unsupported`].
    pub fn new(envs: Vec<E>, batch_size: usize) -> Result<Self> {
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        let threads = envs.len().min(cores).max(1);
        Self::with_threads(envs, batch_size, threads)
    }

    /// [`ThreadEnvPool::new`] with `num_threads` worker threads (clamped to `1..=n`).
    ///
    /// # Errors
    /// As [`ThreadEnvPool::new`].
    pub fn with_threads(envs: Vec<E>, batch_size: usize, num_threads: usize) -> Result<Self> {
        let core = VectorCore::new(&envs)?;
        let n = envs.len();
        if batch_size == 0 || batch_size > n {
            return Err(Error::invalid_argument(
                "batch_size",
                format!("must be in 1..={n} (the number of environments), got {batch_size}"),
            ));
        }
        let slots: Arc<Vec<Slot<E>>> = Arc::new(
            envs.into_iter()
                .map(|env| Slot {
                    env: Mutex::new(env),
                    poisoned: AtomicBool::new(false),
                })
                .collect(),
        );
        let (job_tx, job_rx) = channel();
        let job_rx = Arc::new(Mutex::new(job_rx));
        let (done_tx, done_rx) = channel();
        let mut pool = Self {
            observations: core.single_obs.create_empty_batch(batch_size),
            single_obs: core.single_obs,
            single_act: core.single_act,
            batch_size,
            slots,
            jobs: Some(job_tx),
            done: done_rx,
            workers: Vec::new(),
            turns: vec![Turn::Held { ended: false }; n],
            was_reset: false,
            env_ids: vec![0; batch_size],
            rewards: vec![0.0; batch_size],
            terminations: vec![false; batch_size],
            truncations: vec![false; batch_size],
            closed: false,
            owner: OwnerProcess::current(),
        };
        for w in 0..num_threads.clamp(1, n) {
            let (slots, jobs, done) = (pool.slots.clone(), job_rx.clone(), done_tx.clone());
            let handle = std::thread::Builder::new()
                .name(format!("env-pool-{w}"))
                .spawn(move || worker_loop(slots, jobs, done))
                .map_err(|e| Error::unsupported(format!("cannot spawn a worker thread: {e}")))?;
            pool.workers.push(handle);
        }
        Ok(pool)
    }

    /// The number of environments.
    pub fn num_envs(&self) -> usize {
        self.turns.len()
    }

    /// How many environments each `recv` returns.
    pub fn batch_size(&self) -> usize {
        self.batch_size
    }

    /// The number of worker threads.
    pub fn num_threads(&self) -> usize {
        self.workers.len()
    }

    /// One environment's observation space.
    pub fn single_observation_space(&self) -> &E::ObsSpace {
        &self.single_obs
    }

    /// One environment's action space.
    pub fn single_action_space(&self) -> &E::ActSpace {
        &self.single_act
    }

    /// Queues a reset of every environment; [`recv`](Self::recv) returns them. Steps still
    /// pending are waited for and their results dropped.
    ///
    /// # Errors
    /// [`Error::Closed`]; [`Error::InvalidArgument`] for a per-environment seed list of the
    /// wrong length.
    pub fn reset(&mut self, seeds: impl Into<Seeds>) -> Result<()> {
        self.check_open()?;
        let seeds = seeds.into().resolve(self.num_envs())?;
        while self.turns.contains(&Turn::Pending) {
            let (id, _) = self.next_done()?;
            self.turns[id] = Turn::Held { ended: false };
        }
        for (id, seed) in seeds.into_iter().enumerate() {
            self.queue(
                id,
                Op::Reset {
                    seed,
                    options: None,
                },
            )?;
        }
        self.was_reset = true;
        Ok(())
    }

    /// Gives the environments `env_ids` their next actions: row `k` of `actions` goes to
    /// `env_ids[k]` (an environment whose episode ended is reset instead).
    ///
    /// # Errors
    /// [`Error::Closed`]; [`Error::ResetNeeded`] before the first reset;
    /// [`Error::InvalidArgument`] for an unknown, repeated or pending id;
    /// [`Error::InvalidAction`] unless `actions` holds exactly one finite row per id. Nothing
    /// is queued then.
    pub fn send(&mut self, actions: &BatchOf<E::ActSpace>, env_ids: &[usize]) -> Result<()> {
        self.check_open()?;
        if !self.was_reset {
            return Err(Error::ResetNeeded);
        }
        let mut seen = vec![false; self.num_envs()];
        for &id in env_ids {
            let held = self.turns.get(id).is_some_and(|t| *t != Turn::Pending);
            if !held || std::mem::replace(&mut seen[id], true) {
                return Err(Error::invalid_argument(
                    "env_ids",
                    format!(
                        "{id} is not an environment returned by the last recv (unknown, \
                         repeated or still pending; {} environments)",
                        self.num_envs()
                    ),
                ));
            }
        }
        if !env_ids.is_empty() {
            self.single_act.check_batch(actions, env_ids.len())?;
        }
        let rows = env_ids
            .iter()
            .enumerate()
            .map(|(k, _)| self.single_act.read_item(actions, k))
            .collect::<Result<Vec<_>>>()?;
        for (&id, action) in env_ids.iter().zip(rows) {
            let op = match self.turns[id] {
                Turn::Held { ended: true } => Op::AutoReset,
                _ => Op::Step(action),
            };
            self.queue(id, op)?;
        }
        Ok(())
    }

    /// Waits for the first `batch_size` environments to finish and returns them.
    ///
    /// # Errors
    /// [`Error::Closed`]; [`Error::InvalidArgument`] when fewer than `batch_size`
    /// environments are pending; an environment's error (message prefixed with its id;
    /// the batch's other results are still recorded, and that environment can be sent to
    /// again).
    pub fn recv(&mut self) -> Result<PoolStep<'_, BatchOf<E::ObsSpace>>> {
        self.check_open()?;
        let pending = self.turns.iter().filter(|t| **t == Turn::Pending).count();
        if pending < self.batch_size {
            return Err(Error::invalid_argument(
                "recv",
                format!(
                    "{pending} environments are pending, a batch needs {}; send first",
                    self.batch_size
                ),
            ));
        }
        let mut infos = VectorInfo::new(self.batch_size);
        let mut first_err = None;
        for k in 0..self.batch_size {
            let (id, result) = self.next_done()?;
            self.env_ids[k] = id;
            let written = result.and_then(|outcome| match outcome {
                Outcome::Reset(obs, info) => {
                    self.rewards[k] = 0.0;
                    self.terminations[k] = false;
                    self.truncations[k] = false;
                    infos.add(&info, k);
                    self.single_obs.write_item(&mut self.observations, k, &obs)
                }
                Outcome::Step(step) => {
                    self.rewards[k] = step.reward;
                    self.terminations[k] = step.terminated;
                    self.truncations[k] = step.truncated;
                    infos.add(&step.info, k);
                    self.single_obs
                        .write_item(&mut self.observations, k, &step.observation)
                }
            });
            let ended = written.is_ok() && (self.terminations[k] || self.truncations[k]);
            self.turns[id] = Turn::Held { ended };
            if let Err(e) = written {
                first_err.get_or_insert(in_env(e, id));
            }
        }
        if let Some(e) = first_err {
            return Err(e);
        }
        Ok(PoolStep {
            env_ids: &self.env_ids,
            observations: &self.observations,
            rewards: &self.rewards,
            terminations: &self.terminations,
            truncations: &self.truncations,
            infos,
        })
    }

    /// [`send`](Self::send) then [`recv`](Self::recv).
    ///
    /// # Errors
    /// As those two.
    pub fn step(
        &mut self,
        actions: &BatchOf<E::ActSpace>,
        env_ids: &[usize],
    ) -> Result<PoolStep<'_, BatchOf<E::ObsSpace>>> {
        self.send(actions, env_ids)?;
        self.recv()
    }

    /// Closes the pool: waits for pending work, stops the threads and closes the
    /// environments. Calling it again does nothing.
    pub fn close(&mut self) {
        if self.closed {
            return;
        }
        self.closed = true;
        if self.owner.forked() {
            // A forked child: no worker runs here and the channels' and environments' locks
            // may have been held at the fork. Leak them; never send, join or lock.
            std::mem::forget(self.jobs.take());
            std::mem::forget(std::mem::take(&mut self.workers));
            let (_, done) = channel();
            std::mem::forget(std::mem::replace(&mut self.done, done));
            return;
        }
        self.jobs = None;
        for handle in self.workers.drain(..) {
            let _ = handle.join();
        }
        for slot in self.slots.iter() {
            if !slot.poisoned.load(Ordering::Acquire) {
                let mut env = slot.env.lock().unwrap_or_else(PoisonError::into_inner);
                let _ = catch_unwind(AssertUnwindSafe(|| env.close()));
            }
        }
    }

    /// Whether [`close`](Self::close) was called.
    pub fn is_closed(&self) -> bool {
        self.closed
    }

    fn check_open(&self) -> Result<()> {
        if self.closed {
            return Err(Error::Closed);
        }
        self.owner.check("ThreadEnvPool")
    }

    fn queue(&mut self, id: usize, op: Op<E::Act>) -> Result<()> {
        let sent = self
            .jobs
            .as_ref()
            .is_some_and(|tx| tx.send((id, op)).is_ok());
        if !sent {
            return Err(Error::simulation("the pool's worker threads have exited"));
        }
        self.turns[id] = Turn::Pending;
        Ok(())
    }

    fn next_done(&mut self) -> Result<Done<E::Obs>> {
        self.done
            .recv()
            .map_err(|_| Error::simulation("the pool's worker threads have exited"))
    }
}

impl<E: Env> Drop for ThreadEnvPool<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    fn drop(&mut self) {
        self.close();
    }
}

impl<E: Env> std::fmt::Debug for ThreadEnvPool<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ThreadEnvPool")
            .field("num_envs", &self.num_envs())
            .field("batch_size", &self.batch_size)
            .field("num_threads", &self.workers.len())
            .field("closed", &self.closed)
            .finish_non_exhaustive()
    }
}
