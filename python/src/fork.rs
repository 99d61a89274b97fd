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
use std::sync::{Mutex, MutexGuard, PoisonError, TryLockError};

/// A mutex that remembers the process that made it; see the module documentation.
#[derive(Debug)]
pub struct ForkAwareMutex<T> {
    inner: Mutex<T>,
    owner: u32,
}

impl<T> ForkAwareMutex<T> {
    /// Wraps `value`, owned by the calling process.
    pub fn new(value: T) -> Self {
        Self {
            inner: Mutex::new(value),
            owner: std::process::id(),
        }
    }

    /// Locks the value, ignoring the poison flag (every method of the values kept here
    /// leaves a consistent state or reports an error).
    ///
    /// # Errors
    /// [`Error::Unsupported`] in a forked child when the lock was held at the fork.
    pub fn lock(&self) -> Result<MutexGuard<'_, T>> {
        if std::process::id() == self.owner {
            return Ok(self.inner.lock().unwrap_or_else(PoisonError::into_inner));
        }
        match self.inner.try_lock() {
            Ok(guard) => Ok(guard),
            Err(TryLockError::Poisoned(p)) => Ok(p.into_inner()),
            Err(TryLockError::WouldBlock) => Err(self.held_at_fork()),
        }
    }

    /// Locks the value if no other thread holds it (`None` when one does), ignoring the
    /// poison flag.
    ///
    /// # Errors
    /// [`Error::Unsupported`] in a forked child when the lock was held at the fork.
    pub fn try_lock(&self) -> Result<Option<MutexGuard<'_, T>>> {
        match self.inner.try_lock() {
            Ok(guard) => Ok(Some(guard)),
            Err(TryLockError::Poisoned(p)) => Ok(Some(p.into_inner())),
            Err(TryLockError::WouldBlock) if std::process::id() == self.owner => Ok(None),
            Err(TryLockError::WouldBlock) => Err(self.held_at_fork()),
        }
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
        assert!(m.try_lock().unwrap().is_none());
        drop(held);
        assert_eq!(m.try_lock().unwrap().map(|g| *g), Some(2));
    }
}
