//! [`ForkAwareMutex`]: the lock around a vector env or pool that a process made by
//! `fork()` never waits on.
//!
//! Python steps vector envs with the GIL released, so another Python thread can fork while a
//! step holds the lock; in the child that lock stays held forever (the thread holding it
//! does not exist there). In the process that made it the mutex behaves as a plain one; in
//! a forked child it only *tries* the lock, and a lock held at the fork is a typed error.
//! The vector env or pool behind it then refuses every call in the child by itself (its
//! worker threads exist only in the parent) and closes without waiting.

use gym_core::{Error, Result};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Mutex, MutexGuard, PoisonError, TryLockError};

/// A mutex that remembers the process that made it and the thread holding it; see the
/// module documentation.
#[derive(Debug)]
pub struct ForkAwareMutex<T> {
    inner: Mutex<T>,
    owner: u32,
    /// [`thread_token`] of the thread holding the lock, 0 when none does.
    holder: AtomicUsize,
}

/// A held [`ForkAwareMutex`].
#[derive(Debug)]
pub struct ForkAwareGuard<'a, T> {
    guard: MutexGuard<'a, T>,
    holder: &'a AtomicUsize,
}

impl<T> std::ops::Deref for ForkAwareGuard<'_, T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.guard
    }
}

impl<T> std::ops::DerefMut for ForkAwareGuard<'_, T> {
    fn deref_mut(&mut self) -> &mut T {
        &mut self.guard
    }
}

impl<T> Drop for ForkAwareGuard<'_, T> {
    fn drop(&mut self) {
        self.holder.store(0, Ordering::Release);
    }
}

/// A number unique to the calling thread among live threads (the address of a
/// thread-local), never 0.
fn thread_token() -> usize {
    thread_local!(static TOKEN: u8 = const { 0 });
    TOKEN.with(|t| std::ptr::from_ref(t) as usize)
}

impl<T> ForkAwareMutex<T> {
    /// Wraps `value`, owned by the calling process.
    pub fn new(value: T) -> Self {
        Self {
            inner: Mutex::new(value),
            owner: std::process::id(),
            holder: AtomicUsize::new(0),
        }
    }

    /// Locks the value, ignoring the poison flag (every method of the values kept here
    /// leaves a consistent state or reports an error).
    ///
    /// # Errors
    /// [`Error::Unsupported`] in a forked child when the lock was held at the fork, or when
    /// the calling thread already holds it (a call made from inside another call on the
    /// same object, e.g. from an action's `__array__`): an error instead of a deadlock.
    pub fn lock(&self) -> Result<ForkAwareGuard<'_, T>> {
        self.check_reentry()?;
        if std::process::id() == self.owner {
            let guard = self.inner.lock().unwrap_or_else(PoisonError::into_inner);
            return Ok(self.held(guard));
        }
        match self.inner.try_lock() {
            Ok(guard) => Ok(self.held(guard)),
            Err(TryLockError::Poisoned(p)) => Ok(self.held(p.into_inner())),
            Err(TryLockError::WouldBlock) => Err(self.held_at_fork()),
        }
    }

    /// Locks the value if no other thread holds it (`None` when one does), ignoring the
    /// poison flag.
    ///
    /// # Errors
    /// As [`ForkAwareMutex::lock`].
    pub fn try_lock(&self) -> Result<Option<ForkAwareGuard<'_, T>>> {
        self.check_reentry()?;
        match self.inner.try_lock() {
            Ok(guard) => Ok(Some(self.held(guard))),
            Err(TryLockError::Poisoned(p)) => Ok(Some(self.held(p.into_inner()))),
            Err(TryLockError::WouldBlock) if std::process::id() == self.owner => Ok(None),
            Err(TryLockError::WouldBlock) => Err(self.held_at_fork()),
        }
    }

    fn held<'a>(&'a self, guard: MutexGuard<'a, T>) -> ForkAwareGuard<'a, T> {
        self.holder.store(thread_token(), Ordering::Release);
        ForkAwareGuard {
            guard,
            holder: &self.holder,
        }
    }

    fn check_reentry(&self) -> Result<()> {
        if self.holder.load(Ordering::Acquire) == thread_token() {
            return Err(Error::unsupported(
                "re-entrant call: this object is already in a call on this thread (e.g. an \
                 action's `__array__` or a callback calling it back); it would wait for itself",
            ));
        }
        Ok(())
    }

    fn held_at_fork(&self) -> Error {
        Error::unsupported(format!(
            "this object was in use by another thread when process {} forked; it cannot be \
             used in this child (process {}): make a new one here",
            self.owner,
            std::process::id()
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn in_the_owner_process_it_is_a_plain_mutex() {
        let m = ForkAwareMutex::new(1);
        *m.lock().unwrap() += 1;
        assert_eq!(*m.lock().unwrap(), 2);
        let held = m.lock().unwrap();
        std::thread::scope(|s| {
            s.spawn(|| assert!(m.try_lock().unwrap().is_none()));
        });
        drop(held);
        assert_eq!(m.try_lock().unwrap().map(|g| *g), Some(2));
    }

    #[test]
    fn the_holding_thread_locking_again_is_an_error_not_a_deadlock() {
        let m = ForkAwareMutex::new(1);
        let held = m.lock().unwrap();
        assert!(m.lock().is_err());
        assert!(m.try_lock().is_err());
        drop(held);
        assert_eq!(*m.lock().unwrap(), 1);
    }
}
