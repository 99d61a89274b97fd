//! [`ThreadVectorEnv`]: sub-environments stepped in parallel on persistent worker threads.

use super::core::{Op, Outcome, OwnerProcess, VectorCore, run_op_guarded};
use super::delegate_to_core;
use super::{AutoresetMode, Seeds, VectorEnv, VectorInfo, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Metadata, ResetOptions, Result};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::thread::JoinHandle;

/// Work for one worker: operations on some of its environments (by local index).
enum Command<A> {
    Run(Vec<(usize, Op<A>)>),
    Close,
}

type Reply<O> = Vec<(usize, Result<Outcome<O>>)>;

/// The operations for one worker (by local index) and the global indices they belong to.
type WorkerBatch<A> = (Vec<(usize, Op<A>)>, Vec<usize>);

struct Worker<E: Env> {
    tx: Option<Sender<Command<E::Act>>>,
    rx: Receiver<Reply<E::Obs>>,
    handle: Option<JoinHandle<()>>,
}

/// Sub-environments (with their global indices) stepped by one thread, and which of them
/// panicked: a panicking environment is reported and then refused.
struct Block<E> {
    envs: Vec<(usize, E)>,
    poisoned: Vec<bool>,
}

impl<E: Env> Block<E> {
    fn new(envs: Vec<(usize, E)>) -> Self {
        let poisoned = vec![false; envs.len()];
        Self { envs, poisoned }
    }

    /// Runs `ops` (by local index) and returns the outcomes by global index.
    fn run(&mut self, ops: Vec<(usize, Op<E::Act>)>) -> Reply<E::Obs> {
        ops.into_iter()
            .map(|(local, op)| {
                let (global, env) = &mut self.envs[local];
                let r = run_op_guarded(env, op, *global, &mut self.poisoned[local]);
                (*global, r)
            })
            .collect()
    }

    /// Closes every environment that has not panicked.
    fn close(&mut self) {
        for ((_, env), bad) in self.envs.iter_mut().zip(&self.poisoned) {
            if !bad {
                let _ = catch_unwind(AssertUnwindSafe(|| env.close()));
            }
        }
    }
}

/// A worker thread: runs commands on its block until `Close` or until the vector
/// environment is dropped.
fn worker_loop<E: Env>(
    mut block: Block<E>,
    rx: Receiver<Command<E::Act>>,
    tx: Sender<Reply<E::Obs>>,
) {
    while let Ok(Command::Run(ops)) = rx.recv() {
        if tx.send(block.run(ops)).is_err() {
            break;
        }
    }
    block.close();
}

/// Gymnasium's `AsyncVectorEnv` with threads: the sub-environments are split into
/// `num_threads` contiguous blocks; the calling thread steps the first block itself while
/// persistent worker threads step the others in parallel (so one env needs no thread
/// hand-off at all, and with one block per core no core sits idle waiting). The semantics
/// are those of [`SyncVectorEnv`](super::SyncVectorEnv) (same code), so both give identical
/// trajectories.
///
/// The default thread count is `min(num_envs, available_parallelism)`. A panic inside a
/// sub-environment is caught on its thread and returned as [`Error::Simulation`] (that
/// sub-environment then refuses further calls); a worker that disappears is an error, never
/// a hang. [`VectorEnv::close`] (and `Drop`) closes the sub-environments and joins the
/// threads.
pub struct ThreadVectorEnv<E: Env>
where
    E::ObsSpace: BatchSpace,
    E::ActSpace: BatchSpace,
{
    core: VectorCore<E::ObsSpace, E::ActSpace>,
    /// The block the calling thread steps.
    local: Block<E>,
    /// The other blocks' threads; block `b` (from 1) is `workers[b - 1]`.
    workers: Vec<Worker<E>>,
    /// For each sub-environment: its block and its index there.
    placement: Vec<(usize, usize)>,
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
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        let threads = envs.len().min(cores).max(1);
        Self::with_threads(envs, threads)
    }

    /// A vector of `envs` on `num_threads` threads (clamped to `1..=n`).
    ///
    /// # Errors
    /// As [`ThreadVectorEnv::new`].
    pub fn with_threads(envs: Vec<E>, num_threads: usize) -> Result<Self> {
        let core = VectorCore::new(&envs)?;
        let n = envs.len();
        let threads = num_threads.clamp(1, n);
        let mut placement = Vec::with_capacity(n);
        let mut blocks: Vec<Vec<(usize, E)>> = (0..threads).map(|_| Vec::new()).collect();
        for (i, env) in envs.into_iter().enumerate() {
            let w = i * threads / n;
            placement.push((w, blocks[w].len()));
            blocks[w].push((i, env));
        }
        let mut blocks = blocks.into_iter();
        let local = Block::new(blocks.next().unwrap_or_default());
        let mut workers = Vec::with_capacity(threads - 1);
        for (w, block) in blocks.enumerate() {
            let (cmd_tx, cmd_rx) = channel();
            let (rep_tx, rep_rx) = channel();
            let block = Block::new(block);
            let handle = std::thread::Builder::new()
                .name(format!("vector-env-{}", w + 1))
                .spawn(move || worker_loop(block, cmd_rx, rep_tx))
                .map_err(|e| Error::unsupported(format!("cannot spawn a worker thread: {e}")))?;
            workers.push(Worker {
                tx: Some(cmd_tx),
                rx: rep_rx,
                handle: Some(handle),
            });
        }
        Ok(Self {
            core,
            local,
            workers,
            placement,
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
        self.workers.len() + 1
    }

    /// Sends each operation to its block's worker, runs the calling thread's block, and
    /// gathers the outcomes in sub-environment order.
    fn dispatch(&mut self, ops: Vec<Option<Op<E::Act>>>) -> Vec<Option<Result<Outcome<E::Obs>>>> {
        let mut per_block: Vec<WorkerBatch<E::Act>> = (0..self.num_threads())
            .map(|_| (Vec::new(), Vec::new()))
            .collect();
        for (i, op) in ops.into_iter().enumerate() {
            if let Some(op) = op {
                let (b, local) = self.placement[i];
                per_block[b].0.push((local, op));
                per_block[b].1.push(i);
            }
        }
        let mut results: Vec<Option<Result<Outcome<E::Obs>>>> =
            (0..self.core.n).map(|_| None).collect();
        let mut per_block = per_block.into_iter();
        let (own, _) = per_block.next().unwrap_or_default();
        let mut waiting = Vec::new();
        for (w, (batch, globals)) in per_block.enumerate() {
            if batch.is_empty() {
                continue;
            }
            let sent = self.workers[w]
                .tx
                .as_ref()
                .is_some_and(|tx| tx.send(Command::Run(batch)).is_ok());
            if sent {
                waiting.push((w, globals));
            } else {
                for g in globals {
                    results[g] = Some(Err(Error::simulation(format!(
                        "the worker thread of sub-environment {g} has exited"
                    ))));
                }
            }
        }
        if !own.is_empty() {
            for (g, r) in self.local.run(own) {
                results[g] = Some(r);
            }
        }
        for (w, globals) in waiting {
            match self.workers[w].rx.recv() {
                Ok(reply) => {
                    for (g, r) in reply {
                        results[g] = Some(r);
                    }
                }
                Err(_) => {
                    for g in globals {
                        results[g] = Some(Err(Error::simulation(format!(
                            "the worker thread of sub-environment {g} has exited"
                        ))));
                    }
                }
            }
        }
        results
    }

    fn run_reset(
        &mut self,
        seeds: Seeds,
        options: Option<&ResetOptions>,
        mask: Option<&[bool]>,
    ) -> Result<VectorInfo> {
        self.owner.check("ThreadVectorEnv")?;
        let ops = self.core.plan_reset(seeds, options, mask)?;
        let outcomes = self.dispatch(ops);
        self.core.finish_reset(outcomes)
    }

    fn shutdown(&mut self) {
        if self.owner.forked() {
            // A forked child: the workers are not running here, and their channels' locks
            // may have been held at the fork. Leak them; never send, join or wait.
            std::mem::forget(std::mem::take(&mut self.workers));
            return;
        }
        self.local.close();
        for w in &mut self.workers {
            if let Some(tx) = w.tx.take() {
                let _ = tx.send(Command::Close);
            }
        }
        for w in &mut self.workers {
            if let Some(h) = w.handle.take() {
                let _ = h.join();
            }
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
        let ops = self.core.plan_step(actions)?;
        let outcomes = self.dispatch(ops.into_iter().map(Some).collect());
        let outcomes = outcomes
            .into_iter()
            .map(|o| o.unwrap_or_else(|| Err(Error::simulation("a worker did not answer"))))
            .collect();
        let infos = self.core.finish_step(outcomes)?;
        Ok(self.core.view(infos))
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
