//! [`IdQueue`]: a bounded queue of sub-environment ids that threads wait on, for
//! [`ThreadEnvPool`](super::ThreadEnvPool)'s hand-offs (ids to run, ids finished).
//!
//! Pushing and popping are lock-free ([`ArrayQueue`], allocated once); a thread that finds
//! the queue empty spins, then yields (see [`spin_until`]), and only then sleeps on a
//! condition variable, so a stream of work is handed over without a system call and an
//! idle pool uses no CPU.

use super::team::spin_until;
use crossbeam_queue::ArrayQueue;
use crossbeam_utils::CachePadded;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering, fence};
use std::sync::{Condvar, Mutex, PoisonError};

/// Ids waiting to be taken, and the threads sleeping until one arrives.
pub(crate) struct IdQueue {
    ids: ArrayQueue<usize>,
    /// Threads inside the sleeping part of [`IdQueue::pop`].
    sleepers: CachePadded<AtomicUsize>,
    lock: Mutex<()>,
    wake: Condvar,
}

impl IdQueue {
    /// A queue holding up to `capacity` ids (at least one).
    pub(crate) fn new(capacity: usize) -> Self {
        Self {
            ids: ArrayQueue::new(capacity.max(1)),
            sleepers: CachePadded::new(AtomicUsize::new(0)),
            lock: Mutex::new(()),
            wake: Condvar::new(),
        }
    }

    /// Adds `id` and wakes one sleeping thread; `false` (and nothing added) when the queue
    /// is full, which its owner rules out by never queuing an id twice.
    pub(crate) fn push(&self, id: usize) -> bool {
        if self.ids.push(id).is_err() {
            return false;
        }
        // Pairs with the fence in `pop`: either this load sees the sleeper, or the
        // sleeper's check after registering sees the id.
        fence(Ordering::SeqCst);
        if self.sleepers.load(Ordering::Relaxed) > 0 {
            let _guard = self.lock.lock().unwrap_or_else(PoisonError::into_inner);
            self.wake.notify_one();
        }
        true
    }

    /// Takes the next id, waiting for one; `None` once `stop` is set (and
    /// [`IdQueue::wake_all`] called) while the queue is empty.
    pub(crate) fn pop(&self, stop: &AtomicBool) -> Option<usize> {
        let mut id = None;
        let ready = spin_until(|| {
            id = self.ids.pop();
            id.is_some() || stop.load(Ordering::Acquire)
        });
        if ready {
            return id;
        }
        let mut guard = self.lock.lock().unwrap_or_else(PoisonError::into_inner);
        self.sleepers.fetch_add(1, Ordering::Relaxed);
        fence(Ordering::SeqCst);
        let id = loop {
            if let Some(id) = self.ids.pop() {
                break Some(id);
            }
            if stop.load(Ordering::Acquire) {
                break None;
            }
            guard = self
                .wake
                .wait(guard)
                .unwrap_or_else(PoisonError::into_inner);
        };
        self.sleepers.fetch_sub(1, Ordering::Relaxed);
        id
    }

    /// Wakes every sleeping thread (after setting the `stop` flag they wait with).
    pub(crate) fn wake_all(&self) {
        let _guard = self.lock.lock().unwrap_or_else(PoisonError::into_inner);
        self.wake.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use super::IdQueue;
    use std::sync::Arc;
    use std::sync::atomic::{AtomicBool, Ordering};

    #[test]
    fn every_id_pushed_is_popped_once_across_sleeping_threads() {
        let queue = Arc::new(IdQueue::new(16));
        let stop = Arc::new(AtomicBool::new(false));
        let takers: Vec<_> = (0..3)
            .map(|_| {
                let (queue, stop) = (Arc::clone(&queue), Arc::clone(&stop));
                std::thread::spawn(move || {
                    let mut got = Vec::new();
                    while let Some(id) = queue.pop(&stop) {
                        got.push(id);
                    }
                    got
                })
            })
            .collect();
        for round in 0..50 {
            // Long enough between rounds for the takers to fall asleep now and then.
            if round % 10 == 0 {
                std::thread::sleep(std::time::Duration::from_millis(2));
            }
            for k in 0..8 {
                // A full queue refuses; wait for the takers to make room.
                while !queue.push(round * 8 + k) {
                    std::thread::yield_now();
                }
            }
        }
        while !queue.ids.is_empty() {
            std::thread::yield_now();
        }
        stop.store(true, Ordering::Release);
        queue.wake_all();
        let mut all: Vec<usize> = takers.into_iter().flat_map(|t| t.join().unwrap()).collect();
        all.sort_unstable();
        assert_eq!(all, (0..400).collect::<Vec<_>>());
    }

    #[test]
    fn a_full_queue_refuses_and_keeps_its_ids() {
        let queue = IdQueue::new(2);
        assert!(queue.push(1) && queue.push(2));
        assert!(!queue.push(3));
        let popped = (queue.ids.pop(), queue.ids.pop(), queue.ids.pop());
        assert_eq!(popped, (Some(1), Some(2), None));
    }
}
