//! [`ThreadVectorEnv`]: sub-environments stepped in parallel on persistent worker threads.

use super::core::{Op, Outcome, VectorCore, run_op};
use super::delegate_to_core;
use super::{AutoresetMode, Seeds, VectorEnv, VectorInfo, VectorStep};
use crate::batch::{BatchOf, BatchSpace};
use gym_core::{Env, Error, Metadata, ResetOptions, Result};
use std::any::Any;
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

fn panic_message(payload: &(dyn Any + Send)) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| (*s).to_owned())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic payload".to_owned())
}

/// The worker thread: runs commands on its environments until `Close` or until the vector
/// environment is dropped. A panicking environment is reported and then refused.
fn worker_loop<E: Env>(
    mut envs: Vec<(usize, E)>,
    rx: Receiver<Command<E::Act>>,
    tx: Sender<Reply<E::Obs>>,
) {
    let mut poisoned = vec![false; envs.len()];
    while let Ok(Command::Run(ops)) = rx.recv() {
        let reply: Reply<E::Obs> = ops
            .into_iter()
            .map(|(local, op)| {
                let (global, env) = &mut envs[local];
                let global = *global;
                if poisoned[local] {
                    return (
                        global,
                        Err(Error::Simulation(format!(
                            "sub-environment {global} panicked earlier and is unusable"
                        ))),
                    );
                }
                match catch_unwind(AssertUnwindSafe(|| run_op(env, op))) {
                    Ok(r) => (global, r),
                    Err(payload) => {
                        poisoned[local] = true;
                        (
                            global,
                            Err(Error::Simulation(format!(
                                "panicked: {}",
                                panic_message(payload.as_ref())
                            ))),
                        )
                    }
                }
            })
            .collect();
        if tx.send(reply).is_err() {
            break;
        }
    }
    for ((_, env), bad) in envs.iter_mut().zip(poisoned) {
        if !bad {
            let _ = catch_unwind(AssertUnwindSafe(|| env.close()));
        }
    }
}

/// Gymnasium's `AsyncVectorEnv` with threads: each sub-environment lives on one of
/// `num_threads` persistent worker threads (contiguous blocks of sub-environments per
/// thread), which run the `step` / `reset` of their sub-environments in parallel. The
/// semantics are those of [`SyncVectorEnv`](super::SyncVectorEnv) (same code), so both give
/// identical trajectories.
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
    workers: Vec<Worker<E>>,
    /// For each sub-environment: its worker and its index there.
    placement: Vec<(usize, usize)>,
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
        let mut workers = Vec::with_capacity(threads);
        for (w, block) in blocks.into_iter().enumerate() {
            let (cmd_tx, cmd_rx) = channel();
            let (rep_tx, rep_rx) = channel();
            let handle = std::thread::Builder::new()
                .name(format!("vector-env-{w}"))
                .spawn(move || worker_loop(block, cmd_rx, rep_tx))
                .map_err(|e| Error::Unsupported(format!("cannot spawn a worker thread: {e}")))?;
            workers.push(Worker {
                tx: Some(cmd_tx),
                rx: rep_rx,
                handle: Some(handle),
            });
        }
        Ok(Self {
            core,
            workers,
            placement,
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

    /// The number of worker threads.
    pub fn num_threads(&self) -> usize {
        self.workers.len()
    }

    /// Sends each operation to its worker and gathers the outcomes in sub-environment order.
    fn dispatch(&mut self, ops: Vec<Option<Op<E::Act>>>) -> Vec<Option<Result<Outcome<E::Obs>>>> {
        let mut per_worker: Vec<WorkerBatch<E::Act>> = (0..self.workers.len())
            .map(|_| (Vec::new(), Vec::new()))
            .collect();
        for (i, op) in ops.into_iter().enumerate() {
            if let Some(op) = op {
                let (w, local) = self.placement[i];
                per_worker[w].0.push((local, op));
                per_worker[w].1.push(i);
            }
        }
        let mut results: Vec<Option<Result<Outcome<E::Obs>>>> =
            (0..self.core.n).map(|_| None).collect();
        let mut waiting = Vec::new();
        for (w, (batch, globals)) in per_worker.into_iter().enumerate() {
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
                    results[g] = Some(Err(Error::Simulation(format!(
                        "the worker thread of sub-environment {g} has exited"
                    ))));
                }
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
                        results[g] = Some(Err(Error::Simulation(format!(
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
        let ops = self.core.plan_reset(seeds, options, mask)?;
        let outcomes = self.dispatch(ops);
        self.core.finish_reset(outcomes)
    }

    fn shutdown(&mut self) {
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
        let ops = self.core.plan_step(actions)?;
        let outcomes = self.dispatch(ops.into_iter().map(Some).collect());
        let outcomes = outcomes
            .into_iter()
            .map(|o| o.unwrap_or_else(|| Err(Error::Simulation("a worker did not answer".into()))))
            .collect();
        let infos = self.core.finish_step(outcomes)?;
        let c = &self.core;
        Ok(VectorStep {
            observations: &c.observations,
            rewards: &c.rewards,
            terminations: &c.terminations,
            truncations: &c.truncations,
            infos,
        })
    }

    fn observations(&self) -> &BatchOf<E::ObsSpace> {
        &self.core.observations
    }

    fn close(&mut self) {
        if !self.core.closed {
            self.core.closed = true;
            self.shutdown();
        }
    }

    fn is_closed(&self) -> bool {
        self.core.closed
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
            .field("num_threads", &self.workers.len())
            .field("autoreset_mode", &self.core.mode)
            .field("closed", &self.core.closed)
            .finish_non_exhaustive()
    }
}
