//! [`ThreadOptions`]: how many threads a [`ThreadVectorEnv`](super::ThreadVectorEnv) or
//! [`ThreadEnvPool`](super::ThreadEnvPool) runs, and whether they are pinned to CPUs.

use core_affinity::CoreId;

/// How a threaded vector env or pool places its threads.
///
/// ```
/// use adapters::ThreadOptions;
///
/// let options = ThreadOptions::default().num_threads(8).pinned();
/// assert_eq!(options.threads_for(16), 8);
/// assert_eq!(ThreadOptions::default().num_threads(32).threads_for(4), 4);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct ThreadOptions {
    /// The number of threads (clamped to `1..=num_envs`); `None`:
    /// `min(num_envs, available_parallelism)`.
    pub num_threads: Option<usize>,
    /// Pin each worker thread to its own CPU: worker `k` runs only on the `k`-th CPU this
    /// process may use (wrapping around when there are more threads than CPUs). A
    /// [`ThreadVectorEnv`](super::ThreadVectorEnv)'s calling thread, which steps a share
    /// too, is left as it is (its placement is the caller's); its workers take CPUs 1, 2,
    /// …, leaving the first to it. Pinning keeps each environment's memory in one core's
    /// caches on a machine with many cores; it is best effort (where the OS refuses, the
    /// thread runs unpinned).
    pub pin: bool,
}

impl ThreadOptions {
    /// These options with `n` threads.
    #[must_use]
    pub fn num_threads(mut self, n: usize) -> Self {
        self.num_threads = Some(n);
        self
    }

    /// These options with pinned worker threads.
    #[must_use]
    pub fn pinned(mut self) -> Self {
        self.pin = true;
        self
    }

    /// How many threads these options give `num_envs` environments.
    pub fn threads_for(&self, num_envs: usize) -> usize {
        let n = num_envs.max(1);
        self.num_threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from))
            .clamp(1, n)
    }

    /// The CPUs threads `0, 1, …` are pinned to (thread `k` to `cpus[k % len]`), or none.
    pub(crate) fn cpus(&self) -> Option<Vec<CoreId>> {
        if self.pin {
            core_affinity::get_core_ids().filter(|ids| !ids.is_empty())
        } else {
            None
        }
    }
}

/// Pins the calling thread to the CPU of thread `k` in `cpus` (nothing when `cpus` is none
/// or the OS refuses).
pub(crate) fn pin_current(cpus: Option<&[CoreId]>, k: usize) {
    if let Some(cpus) = cpus.filter(|c| !c.is_empty()) {
        let _ = core_affinity::set_for_current(cpus[k % cpus.len()]);
    }
}

#[cfg(test)]
mod tests {
    use super::ThreadOptions;

    #[test]
    fn thread_counts_are_clamped_to_the_environments() {
        let cores = std::thread::available_parallelism().map_or(1, usize::from);
        assert_eq!(ThreadOptions::default().threads_for(1000), cores);
        assert_eq!(ThreadOptions::default().threads_for(1), 1);
        assert_eq!(ThreadOptions::default().num_threads(0).threads_for(5), 1);
        assert_eq!(ThreadOptions::default().num_threads(3).threads_for(5), 3);
        assert_eq!(ThreadOptions::default().num_threads(9).threads_for(5), 5);
    }

    #[test]
    fn pinned_options_name_the_cpus_the_process_may_use() {
        assert!(ThreadOptions::default().cpus().is_none());
        let cpus = ThreadOptions::default().pinned().cpus();
        // Linux always reports the affinity mask; it holds at least one CPU.
        #[cfg(target_os = "linux")]
        assert!(cpus.is_some_and(|c| !c.is_empty()));
        #[cfg(not(target_os = "linux"))]
        let _ = cpus;
    }

    /// How many CPUs the calling thread may run on.
    #[cfg(target_os = "linux")]
    fn allowed_cpus() -> usize {
        // SAFETY: `set` is a valid, zeroed cpu_set_t of the size passed.
        unsafe {
            let mut set: libc::cpu_set_t = std::mem::zeroed();
            assert_eq!(
                libc::sched_getaffinity(0, std::mem::size_of::<libc::cpu_set_t>(), &mut set),
                0
            );
            libc::CPU_COUNT(&set) as usize
        }
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_pinned_thread_runs_on_one_cpu_and_an_unpinned_one_is_left_alone() {
        let cpus = ThreadOptions::default().pinned().cpus().unwrap();
        let before = allowed_cpus();
        for k in [0, 1, cpus.len() + 1] {
            let cpus = cpus.clone();
            let pinned = std::thread::spawn(move || {
                super::pin_current(Some(&cpus), k);
                allowed_cpus()
            });
            assert_eq!(pinned.join().unwrap(), 1, "thread {k}");
        }
        let unpinned = std::thread::spawn(|| {
            super::pin_current(None, 1);
            allowed_cpus()
        });
        assert_eq!(unpinned.join().unwrap(), before);
    }
}
