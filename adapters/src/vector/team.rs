//! [`Team`]: persistent worker threads that run rounds of jobs together with the calling
//! thread, for [`ThreadVectorEnv`](super::ThreadVectorEnv).
//!
//! * Every job runs exactly once per round, on whichever thread claims it. Jobs are split
//!   into one contiguous block per thread; a thread first claims the jobs of its own block
//!   (so an environment usually stays on the same core and in its cache), then those of the
//!   other blocks still unclaimed: a fast thread takes work from a slow one, so the round
//!   does not wait for the slowest block (dynamic assignment with one atomic cursor per
//!   block).
//! * The calling thread is thread 0: it starts a round, works through block 0 and the
//!   leftovers, then waits for the jobs still running.
//! * Waiting threads spin briefly, then yield, then sleep (`park`); the next round (or the
//!   last job of a round, for the calling thread) wakes them. A round that follows quickly
//!   finds the workers awake, without a system call.
//! * The cursors, counters and jobs each sit on their own cache lines (`CachePadded`), so
//!   threads claiming and finishing jobs do not invalidate each other's lines.

use super::threads::pin_current;
use core_affinity::CoreId;
use crossbeam_utils::{Backoff, CachePadded};
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::thread::{JoinHandle, Thread};
use std::time::{Duration, Instant};

/// How long a waiting thread yields before it sleeps: long enough to bridge the calling
/// thread's work between two steps, short enough not to hold a core when stepping stops.
const SPIN: Duration = Duration::from_micros(100);

/// Work that a team runs once per round; `run` must not panic (catch inside).
pub(crate) trait Job: Send + 'static {
    /// Runs the job.
    fn run(&mut self);
}

/// One thread's block of jobs, `start..end`, and the next job not yet claimed.
struct Block {
    cursor: CachePadded<AtomicUsize>,
    start: usize,
    end: usize,
}

struct Shared<J> {
    jobs: Box<[CachePadded<Mutex<J>>]>,
    blocks: Box<[Block]>,
    /// Jobs of the current round not yet finished.
    remaining: CachePadded<AtomicUsize>,
    /// Bumped to start a round.
    round: CachePadded<AtomicU64>,
    stop: AtomicBool,
    /// The thread waiting for the round's last job.
    waiter: Mutex<Option<Thread>>,
}

impl<J: Job> Shared<J> {
    fn lock(&self, i: usize) -> MutexGuard<'_, J> {
        self.jobs[i].lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Claims and runs jobs, own block first, until none is left to claim.
    fn work(&self, thread: usize) {
        let blocks = self.blocks.len();
        for k in 0..blocks {
            let block = &self.blocks[(thread + k) % blocks];
            loop {
                let i = block.cursor.fetch_add(1, Ordering::AcqRel);
                if i >= block.end {
                    break;
                }
                self.lock(i).run();
                if self.remaining.fetch_sub(1, Ordering::AcqRel) == 1 {
                    let waiter = self.waiter.lock().unwrap_or_else(PoisonError::into_inner);
                    if let Some(t) = waiter.as_ref() {
                        t.unpark();
                    }
                }
            }
        }
    }
}

/// Spins (crossbeam's [`Backoff`]), then yields for [`SPIN`], until `ready()`; whether it
/// became ready (`false`: the caller should sleep until woken).
pub(crate) fn spin_until(mut ready: impl FnMut() -> bool) -> bool {
    let backoff = Backoff::new();
    while !backoff.is_completed() {
        if ready() {
            return true;
        }
        backoff.snooze();
    }
    let deadline = Instant::now() + SPIN;
    while Instant::now() < deadline {
        if ready() {
            return true;
        }
        std::thread::yield_now();
    }
    ready()
}

/// Waits until `ready()`: [`spin_until`], then parks (the thread that makes `ready()` true
/// must unpark this one).
fn wait_until(ready: impl Fn() -> bool) {
    if spin_until(&ready) {
        return;
    }
    while !ready() {
        std::thread::park();
    }
}

/// A worker thread: runs its share of every round until the team stops.
fn worker<J: Job>(shared: Arc<Shared<J>>, thread: usize) {
    let mut seen = 0;
    loop {
        wait_until(|| {
            shared.stop.load(Ordering::Acquire) || shared.round.load(Ordering::Acquire) != seen
        });
        if shared.stop.load(Ordering::Acquire) {
            return;
        }
        seen = shared.round.load(Ordering::Acquire);
        shared.work(thread);
    }
}

/// Jobs and the threads that run them (see the module documentation).
pub(crate) struct Team<J: Job> {
    shared: Arc<Shared<J>>,
    /// Threads 1.. (thread 0 is the caller of [`Team::run`]).
    workers: Vec<JoinHandle<()>>,
}

impl<J: Job> Team<J> {
    /// `jobs` on `threads` threads (clamped to `1..=jobs.len()`), the calling thread
    /// included; threads are named `name-1`, `name-2`, ... and, with `cpus`, worker `k`
    /// is pinned to `cpus[k % len]` (the calling thread is not pinned).
    ///
    /// # Errors
    /// The OS error of a thread that cannot be spawned.
    pub(crate) fn new(
        jobs: Vec<J>,
        threads: usize,
        name: &str,
        cpus: Option<Vec<CoreId>>,
    ) -> std::io::Result<Self> {
        let n = jobs.len();
        let threads = threads.clamp(1, n.max(1));
        let blocks = (0..threads)
            .map(|t| {
                // Job i belongs to block i * threads / n: contiguous, sizes differ by one.
                let start = (t * n).div_ceil(threads);
                let end = ((t + 1) * n).div_ceil(threads);
                Block {
                    cursor: CachePadded::new(AtomicUsize::new(end)),
                    start,
                    end,
                }
            })
            .collect();
        let shared = Arc::new(Shared {
            jobs: jobs
                .into_iter()
                .map(|j| CachePadded::new(Mutex::new(j)))
                .collect(),
            blocks,
            remaining: CachePadded::new(AtomicUsize::new(0)),
            round: CachePadded::new(AtomicU64::new(0)),
            stop: AtomicBool::new(false),
            waiter: Mutex::new(None),
        });
        let mut team = Self {
            shared,
            workers: Vec::with_capacity(threads - 1),
        };
        for t in 1..threads {
            let shared = Arc::clone(&team.shared);
            let cpus = cpus.clone();
            let handle = std::thread::Builder::new()
                .name(format!("{name}-{t}"))
                .spawn(move || {
                    pin_current(cpus.as_deref(), t);
                    worker(shared, t);
                })?;
            team.workers.push(handle);
        }
        Ok(team)
    }

    /// The number of threads, the calling thread included.
    pub(crate) fn threads(&self) -> usize {
        self.workers.len() + 1
    }

    /// The number of jobs.
    pub(crate) fn len(&self) -> usize {
        self.shared.jobs.len()
    }

    /// Job `i`, locked (between rounds no other thread holds it).
    pub(crate) fn job(&self, i: usize) -> MutexGuard<'_, J> {
        self.shared.lock(i)
    }

    /// Runs every job once, on all threads; returns when all have finished.
    pub(crate) fn run(&self) {
        let s = &*self.shared;
        s.remaining.store(s.jobs.len(), Ordering::Release);
        for b in s.blocks.iter() {
            b.cursor.store(b.start, Ordering::Release);
        }
        s.round.fetch_add(1, Ordering::AcqRel);
        for w in &self.workers {
            w.thread().unpark();
        }
        s.work(0);
        if s.remaining.load(Ordering::Acquire) == 0 {
            return;
        }
        let done = || s.remaining.load(Ordering::Acquire) == 0;
        if spin_until(done) {
            return;
        }
        // Register as the waiter (the thread finishing the last job unparks it), then wait.
        *s.waiter.lock().unwrap_or_else(PoisonError::into_inner) = Some(std::thread::current());
        while !done() {
            std::thread::park();
        }
        *s.waiter.lock().unwrap_or_else(PoisonError::into_inner) = None;
    }

    /// Stops and joins the worker threads (the jobs stay, reachable with [`Team::job`]).
    pub(crate) fn stop(&mut self) {
        self.shared.stop.store(true, Ordering::Release);
        for w in &self.workers {
            w.thread().unpark();
        }
        for w in self.workers.drain(..) {
            let _ = w.join();
        }
    }

    /// Forgets the worker threads without stopping or joining them: in a process made by
    /// `fork()` they do not exist, and a lock may have been held at the fork.
    pub(crate) fn abandon(&mut self) {
        std::mem::forget(std::mem::take(&mut self.workers));
    }
}

impl<J: Job> Drop for Team<J> {
    /// Stops the workers that are still running (none after [`Team::stop`] or
    /// [`Team::abandon`]).
    fn drop(&mut self) {
        if !self.workers.is_empty() {
            self.stop();
        }
    }
}
