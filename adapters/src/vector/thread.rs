//! [`ThreadVectorEnv`]: sub-environments stepped in parallel on persistent worker threads.

use super::core::{OwnerProcess, VectorCore};
use super::delegate_to_core;
use super::slot::Member;
use super::team::{Job, Team};
use super::{AutoresetMode, Seeds, ThreadOptions, VectorEnv, VectorInfo, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Metadata, ResetOptions, Result};

/// A sub-environment with its buffers is one job of the team.
impl<E: Env> Job for Member<E> {
    fn run(&mut self) {
        Member::run(self);
    }
}

/// Gymnasium's `AsyncVectorEnv` with threads: the sub-environments are stepped in parallel
/// by `num_threads` threads, the calling thread included, that persist between calls. Each
/// thread owns a contiguous block of sub-environments and steps it first, then takes the
/// sub-environments of other blocks that are still waiting (dynamic assignment), so a step
/// waits for the slowest *environment* rather than the slowest *block*; several envs per
/// thread (`num_envs` = 2–4 × threads) therefore keep every core busy. Threads that wait
/// spin briefly before they sleep, so a loop of steps needs no system call to hand off
/// work. The semantics are those of [`SyncVectorEnv`](super::SyncVectorEnv) (same code): a
/// sub-environment's trajectory depends only on its seed and actions, never on the thread
/// that steps it, so both give identical trajectories. Steps go through [`Env::step_into`]
/// into per-environment buffers; with environments whose `step_into` reuses them (the
/// robosuite tasks and `FlatGymWrapper`) a step does not allocate.
///
/// The default thread count is `min(num_envs, available_parallelism)`; [`ThreadOptions`]
/// sets another and can pin the worker threads to CPUs. A panic inside a
/// sub-environment is caught on its thread and returned as [`Error::Simulation`] (that
/// sub-environment then refuses further calls); no call can hang on a lost thread.
/// [`VectorEnv::close`] (and `Drop`) closes the sub-environments and joins the threads.
pub struct ThreadVectorEnv<E: Env>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    core: VectorCore<E::ObsSpace, E::ActSpace>,
    team: Team<Member<E>>,
    /// The process whose threads these are (checked against `fork()`).
    owner: OwnerProcess,
}

impl<E: Env> ThreadVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    /// A vector of `envs` on `min(n, available_parallelism)` threads, with
    /// [`AutoresetMode::NextStep`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for no environments or differing spaces; an OS error
    /// spawning a thread as [`Error::Unsupported`].
    pub fn new(envs: Vec<E>) -> Result<Self> {
        Self::with_options(envs, ThreadOptions::default())
    }

    /// A vector of `envs` on `num_threads` threads (clamped to `1..=n`).
    ///
    /// # Errors
    /// As [`ThreadVectorEnv::new`].
    pub fn with_threads(envs: Vec<E>, num_threads: usize) -> Result<Self> {
        Self::with_options(envs, ThreadOptions::default().num_threads(num_threads))
    }

    /// A vector of `envs` on the threads `options` asks for (their number, and pinning).
    ///
    /// # Errors
    /// As [`ThreadVectorEnv::new`].
    pub fn with_options(envs: Vec<E>, options: ThreadOptions) -> Result<Self> {
        let mut core = VectorCore::new(&envs)?;
        let num_threads = options.threads_for(envs.len());
        let members = envs
            .into_iter()
            .enumerate()
            .map(|(i, env)| {
                let mut member = Member::new(i, env);
                core.attach_row(&mut member.slot, &member.env);
                member
            })
            .collect();
        let team = Team::new(members, num_threads, "vector-env", options.cpus())
            .map_err(|e| Error::unsupported(format!("cannot spawn a worker thread: {e}")))?;
        Ok(Self {
            core,
            team,
            owner: OwnerProcess::current(),
        })
    }

    /// `n` environments made by `make(i)` (on the calling thread), on the default threads.
    ///
    /// # Errors
    /// The first error of `make`; as [`ThreadVectorEnv::new`].
    pub fn from_fn(n: usize, make: impl FnMut(usize) -> Result<E>) -> Result<Self> {
        Self::new((0..n).map(make).collect::<Result<Vec<_>>>()?)
    }

    /// The same vector with another autoreset mode (set it before the first step).
    #[must_use]
    pub fn with_autoreset_mode(mut self, mode: AutoresetMode) -> Self {
        self.core.mode = mode;
        self
    }

    /// The number of threads stepping sub-environments, the calling thread included.
    pub fn num_threads(&self) -> usize {
        self.team.threads()
    }

    fn run_reset(
        &mut self,
        seeds: Seeds,
        options: Option<&ResetOptions>,
        mask: Option<&[bool]>,
    ) -> Result<()> {
        self.owner.check("ThreadVectorEnv")?;
        let tasks = self.core.plan_reset(seeds, options, mask)?;
        for (i, task) in tasks.into_iter().enumerate() {
            self.team.job(i).slot.task = task;
        }
        self.team.run();
        self.core.begin();
        let mut result = Ok(());
        for i in 0..self.team.len() {
            let r = self.core.finish_reset(&mut self.team.job(i).slot);
            result = result.and(r);
        }
        result
    }

    fn shutdown(&mut self) {
        if self.owner.forked() {
            // A forked child: the workers are not running here, and the jobs' locks may
            // have been held at the fork. Leak them; never lock, join or wait.
            self.team.abandon();
            return;
        }
        self.team.stop();
        for i in 0..self.team.len() {
            self.team.job(i).close();
        }
    }
}

impl<E: Env> VectorEnv for ThreadVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;

    delegate_to_core!(E::ObsSpace, E::ActSpace);

    fn step(
        &mut self,
        actions: &BatchOf<E::ActSpace>,
    ) -> Result<VectorStep<'_, BatchOf<E::ObsSpace>>> {
        self.owner.check("ThreadVectorEnv")?;
        self.core.check_step(actions)?;
        for i in 0..self.team.len() {
            self.core.plan_step(&mut self.team.job(i).slot, actions)?;
        }
        self.team.run();
        self.core.begin();
        let mut result = Ok(());
        for i in 0..self.team.len() {
            let r = self.core.finish_step(&mut self.team.job(i).slot);
            result = result.and(r);
        }
        result?;
        Ok(self.core.view())
    }

    fn close(&mut self) {
        if !self.core.closed {
            self.core.closed = true;
            self.shutdown();
        }
    }
}

impl<E: Env> Drop for ThreadVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    fn drop(&mut self) {
        self.close();
    }
}

impl<E: Env> std::fmt::Debug for ThreadVectorEnv<E>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ThreadVectorEnv")
            .field("num_envs", &self.core.n)
            .field("num_threads", &self.num_threads())
            .field("autoreset_mode", &self.core.mode)
            .field("closed", &self.core.closed)
            .finish_non_exhaustive()
    }
}
