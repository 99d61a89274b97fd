//! [`ThreadEnvPool`]: EnvPool's asynchronous mode on threads. `recv` returns the first
//! `batch_size` environments to finish, `send` gives exactly those their next actions, so
//! no thread waits for the slowest environment of a batch.
//!
//! Each environment has a [`Member`] (its buffers, as in the vector envs): `send` writes
//! the action into it and queues its id; a worker takes the id, runs the step in place
//! ([`Env::step_into`]) and queues the id as finished; `recv` copies the finished rows into
//! the batch. The two queues ([`IdQueue`]) are lock-free and allocated once, and waiting
//! threads spin before they sleep, so over environments whose `step_into` reuses its
//! buffers a `send` / `recv` round allocates nothing.

use super::core::{OwnerProcess, VectorCore, in_env};
use super::queue::IdQueue;
use super::slot::{Done, Member, ObsAt, Task};
use super::threads::pin_current;
use super::{Seeds, ThreadOptions, VectorInfo};
use crate::batch::{BatchOf, BatchSpace};
use crossbeam_utils::CachePadded;
use gym_core::{Env, Error, ObsRow, Result, RowLeaves};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::thread::JoinHandle;

/// What the pool's threads share: the environments and the two queues of ids.
struct Shared<E: Env> {
    members: Box<[CachePadded<Mutex<Member<E>>>]>,
    /// Ids whose task is set, waiting for a worker.
    todo: IdQueue,
    /// Ids whose task has run, waiting for `recv`.
    finished: IdQueue,
    /// Set by `close`: the workers exit once `todo` is empty.
    stop: AtomicBool,
}

impl<E: Env> Shared<E> {
    /// Environment `id` with its buffers (a worker holds it only while running its task).
    fn member(&self, id: usize) -> MutexGuard<'_, Member<E>> {
        self.members[id]
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
    }
}

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
    pub infos: &'a VectorInfo,
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
/// [`Error::InvalidArgument`], and nothing is queued. Steps go through [`Env::step_into`]
/// into per-environment buffers and the batch buffers and infos are reused, so over
/// environments whose `step_into` reuses its buffers (the robosuite tasks,
/// `FlatGymWrapper`) `send` and `recv` allocate nothing.
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
    shared: Arc<Shared<E>>,
    workers: Vec<JoinHandle<()>>,
    turns: Vec<Turn>,
    /// `send`'s record of the ids it was given (kept, so `send` does not allocate).
    seen: Vec<bool>,
    was_reset: bool,
    observations: BatchOf<E::ObsSpace>,
    env_ids: Vec<usize>,
    rewards: Vec<f64>,
    terminations: Vec<bool>,
    truncations: Vec<bool>,
    infos: VectorInfo,
    closed: bool,
    owner: OwnerProcess,
}

/// A worker: takes the next queued id, runs that environment's task, queues the id as
/// finished; exits when the pool stops.
fn worker_loop<E: Env>(shared: Arc<Shared<E>>) {
    while let Some(id) = shared.todo.pop(&shared.stop) {
        shared.member(id).run();
        // Cannot fail: an id is in at most one queue, and each holds every id.
        let _ = shared.finished.push(id);
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
        Self::with_options(envs, batch_size, ThreadOptions::default())
    }

    /// [`ThreadEnvPool::new`] with `num_threads` worker threads (clamped to `1..=n`).
    ///
    /// # Errors
    /// As [`ThreadEnvPool::new`].
    pub fn with_threads(envs: Vec<E>, batch_size: usize, num_threads: usize) -> Result<Self> {
        Self::with_options(
            envs,
            batch_size,
            ThreadOptions::default().num_threads(num_threads),
        )
    }

    /// [`ThreadEnvPool::new`] on the worker threads `options` asks for (their number, and
    /// pinning: worker `k` on the `k`-th CPU).
    ///
    /// # Errors
    /// As [`ThreadEnvPool::new`].
    pub fn with_options(envs: Vec<E>, batch_size: usize, options: ThreadOptions) -> Result<Self> {
        let core = VectorCore::new(&envs)?;
        let num_threads = options.threads_for(envs.len());
        let cpus = options.cpus();
        let n = envs.len();
        if batch_size == 0 || batch_size > n {
            return Err(Error::invalid_argument(
                "batch_size",
                format!("must be in 1..={n} (the number of environments), got {batch_size}"),
            ));
        }
        let mut observations = core.single_obs.create_empty_batch(batch_size);
        // Environments that write rows keep a step's observation until `recv` writes it
        // into the row it returns it in (one copy, environment to batch).
        let rows = core
            .single_obs
            .row_leaves(&mut observations, 0, &mut RowLeaves::new());
        let shared = Arc::new(Shared {
            members: envs
                .into_iter()
                .enumerate()
                .map(|(i, env)| {
                    let mut member = Member::new(i, env);
                    member.slot.deferred = rows && member.env.writes_rows();
                    CachePadded::new(Mutex::new(member))
                })
                .collect(),
            todo: IdQueue::new(n),
            finished: IdQueue::new(n),
            stop: AtomicBool::new(false),
        });
        let mut pool = Self {
            observations,
            single_obs: core.single_obs,
            single_act: core.single_act,
            batch_size,
            shared,
            workers: Vec::new(),
            turns: vec![Turn::Held { ended: false }; n],
            seen: vec![false; n],
            was_reset: false,
            env_ids: vec![0; batch_size],
            rewards: vec![0.0; batch_size],
            terminations: vec![false; batch_size],
            truncations: vec![false; batch_size],
            infos: VectorInfo::new(batch_size),
            closed: false,
            owner: OwnerProcess::current(),
        };
        for w in 0..num_threads {
            let shared = Arc::clone(&pool.shared);
            let cpus = cpus.clone();
            let handle = std::thread::Builder::new()
                .name(format!("env-pool-{w}"))
                .spawn(move || {
                    pin_current(cpus.as_deref(), w);
                    worker_loop(shared);
                })
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
        self.drain_pending();
        for (id, seed) in seeds.into_iter().enumerate() {
            self.shared.member(id).slot.task = Task::Reset {
                seed,
                options: None,
            };
            self.queue(id);
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
        self.seen.fill(false);
        for &id in env_ids {
            let held = self.turns.get(id).is_some_and(|t| *t != Turn::Pending);
            if !held || std::mem::replace(&mut self.seen[id], true) {
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
        // Write every task first, so that a row that cannot be read queues nothing.
        for (k, &id) in env_ids.iter().enumerate() {
            let mut member = self.shared.member(id);
            let slot = &mut member.slot;
            slot.task = match self.turns[id] {
                Turn::Held { ended: true } => Task::AutoReset,
                _ => Task::Step,
            };
            if matches!(slot.task, Task::Step)
                && let Err(e) = self.single_act.read_item_into(actions, k, &mut slot.action)
            {
                drop(member);
                for &earlier in &env_ids[..=k] {
                    self.shared.member(earlier).slot.task = Task::Idle;
                }
                return Err(Error::invalid_action(format!("actions[{k}]: {e}")));
            }
        }
        for &id in env_ids {
            self.queue(id);
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
        self.infos.clear();
        let mut first_err = None;
        for k in 0..self.batch_size {
            let id = self.next_finished();
            self.env_ids[k] = id;
            let mut member = self.shared.member(id);
            let Member { env, slot } = &mut *member;
            let outcome = match std::mem::replace(&mut slot.done, Ok(Done::Idle)) {
                Ok(Done::Reset) => Ok((0.0, false, false)),
                Ok(Done::Stepped(t)) => Ok((t.reward, t.terminated, t.truncated)),
                Ok(_) => Err(Error::Contract {
                    check: "ThreadEnvPool".into(),
                    message: "an environment finished without a step or reset".into(),
                }),
                Err(e) => Err(e),
            };
            let written = outcome.and_then(|(reward, terminated, truncated)| {
                self.rewards[k] = reward;
                self.terminations[k] = terminated;
                self.truncations[k] = truncated;
                self.infos.add(&slot.info, k);
                if slot.obs_at == ObsAt::Env {
                    let mut leaves = RowLeaves::new();
                    if !self
                        .single_obs
                        .row_leaves(&mut self.observations, k, &mut leaves)
                    {
                        return Err(Error::Contract {
                            check: "ThreadEnvPool".into(),
                            message: "the batch has no row leaves".into(),
                        });
                    }
                    // SAFETY: row `k` of the pool's own batch, which nothing else reads or
                    // writes while `row` lives (`recv` holds `&mut self`).
                    let mut row = unsafe { ObsRow::from_raw(leaves.as_slice()) };
                    env.write_observation_row(&mut row)?;
                } else {
                    self.single_obs
                        .write_item(&mut self.observations, k, &slot.observation)?;
                }
                Ok(terminated || truncated)
            });
            drop(member);
            self.turns[id] = Turn::Held {
                ended: *written.as_ref().unwrap_or(&false),
            };
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
            infos: &self.infos,
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
            // A forked child: no worker runs here and the environments' locks may have
            // been held at the fork. Leak the threads' handles; never join, wait or lock.
            std::mem::forget(std::mem::take(&mut self.workers));
            return;
        }
        self.drain_pending();
        self.shared.stop.store(true, Ordering::Release);
        self.shared.todo.wake_all();
        for handle in self.workers.drain(..) {
            let _ = handle.join();
        }
        for id in 0..self.num_envs() {
            self.shared.member(id).close();
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

    /// Queues `id`, whose task is set.
    fn queue(&mut self, id: usize) {
        // Cannot fail: `id` is held (in no queue), and the queue holds every id.
        let _ = self.shared.todo.push(id);
        self.turns[id] = Turn::Pending;
    }

    /// The next finished id (one is pending: every queued id finishes, panics included).
    fn next_finished(&self) -> usize {
        loop {
            if let Some(id) = self.shared.finished.pop(&self.shared.stop) {
                return id;
            }
        }
    }

    /// Waits for every pending environment and drops its result.
    fn drain_pending(&mut self) {
        while self.turns.contains(&Turn::Pending) {
            let id = self.next_finished();
            self.shared.member(id).slot.done = Ok(Done::Idle);
            self.turns[id] = Turn::Held { ended: false };
        }
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
