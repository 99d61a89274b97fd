//! Vector envs and pools under bad batches and `fork()` (issue #17): a batch must match
//! exactly and is checked as a whole before any environment steps, so a rejected call
//! changes nothing; a forked child gets a clear error, never a hang.

use crate::common::WalkEnv;
use adapters::{SyncVectorEnv, ThreadEnvPool, ThreadVectorEnv, VectorEnv};
use gym_core::Error;
use ndarray::{Array2, ArrayD};
use std::time::{Duration, Instant};

fn batch(rows: &[[f32; 2]]) -> ArrayD<f32> {
    Array2::from_shape_vec((rows.len(), 2), rows.concat())
        .unwrap()
        .into_dyn()
}

fn walks(n: usize) -> Vec<WalkEnv> {
    (0..n).map(|_| WalkEnv::new(50)).collect()
}

/// The batches every vector env of two must reject, each with the reason.
fn bad_batches() -> Vec<(&'static str, ArrayD<f32>)> {
    vec![
        ("three rows", batch(&[[0.1, 0.1], [0.2, 0.2], [0.3, 0.3]])),
        ("one row", batch(&[[0.1, 0.1]])),
        ("NaN in the last row", batch(&[[0.1, 0.1], [f32::NAN, 0.0]])),
        (
            "inf in the first row",
            batch(&[[f32::INFINITY, 0.1], [0.1, 0.1]]),
        ),
        (
            "transposed",
            ArrayD::from_shape_vec(vec![2, 1, 2], vec![0.0; 4]).unwrap(),
        ),
    ]
}

fn rejected_batches_change_nothing<V: VectorEnv<ActSpace = gym_core::BoxSpace<f32>>>(
    mut v: V,
    mut reference: V,
) where
    V::ObsSpace: adapters::BatchSpace<Element = ArrayD<f32>>,
    adapters::BatchOf<V::ObsSpace>: PartialEq + Clone + std::fmt::Debug,
{
    let _ = v.reset(7u64, None).unwrap();
    let _ = reference.reset(7u64, None).unwrap();
    let good = batch(&[[0.5, -0.5], [-0.25, 0.75]]);
    for (why, bad) in bad_batches() {
        let before = v.observations().clone();
        assert!(
            matches!(v.step(&bad), Err(Error::InvalidAction(_))),
            "{why}"
        );
        assert_eq!(v.observations(), &before, "{why}");
        // Nothing stepped: the next good step matches a vector env that never saw it.
        let got = v.step(&good).unwrap().observations.clone();
        let want = reference.step(&good).unwrap().observations.clone();
        assert_eq!(got, want, "{why}");
    }
}

#[test]
fn vector_envs_take_exact_finite_batches_only() {
    rejected_batches_change_nothing(
        SyncVectorEnv::new(walks(2)).unwrap(),
        SyncVectorEnv::new(walks(2)).unwrap(),
    );
    rejected_batches_change_nothing(
        ThreadVectorEnv::with_threads(walks(2), 2).unwrap(),
        ThreadVectorEnv::with_threads(walks(2), 2).unwrap(),
    );
}

#[test]
fn pool_send_takes_one_finite_row_per_id() {
    let mut pool = ThreadEnvPool::with_threads(walks(2), 2, 2).unwrap();
    pool.reset(3u64).unwrap();
    let ids = pool.recv().unwrap().env_ids.to_vec();
    for (why, bad) in bad_batches() {
        assert!(
            matches!(pool.send(&bad, &ids), Err(Error::InvalidAction(_))),
            "{why}"
        );
        // Nothing was queued.
        assert!(pool.recv().is_err(), "{why}");
    }
    let step = pool.step(&batch(&[[0.1, 0.1], [0.2, 0.2]]), &ids).unwrap();
    assert_eq!(step.env_ids.len(), 2);
}

/// Runs `child` in a forked child process and returns its exit code; a child that has not
/// exited within `limit` is killed and reported as `None` (a hang).
fn in_forked_child(limit: Duration, child: impl FnOnce() -> i32) -> Option<i32> {
    // SAFETY: the child runs `child` and leaves with `_exit`, never returning into the test
    // harness; the parent only waits for it.
    let pid = unsafe { libc::fork() };
    assert!(pid >= 0, "fork failed");
    if pid == 0 {
        let code = std::panic::catch_unwind(std::panic::AssertUnwindSafe(child)).unwrap_or(99);
        // SAFETY: ends the child at once, without running the parent's destructors.
        unsafe { libc::_exit(code) };
    }
    let start = Instant::now();
    let mut status = 0;
    loop {
        // SAFETY: waits for our own child without blocking.
        let done = unsafe { libc::waitpid(pid, &mut status, libc::WNOHANG) };
        if done == pid {
            return libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status));
        }
        if start.elapsed() > limit {
            // SAFETY: kills and reaps our own child.
            unsafe {
                libc::kill(pid, libc::SIGKILL);
                libc::waitpid(pid, &mut status, 0);
            }
            return None;
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

#[test]
fn a_forked_child_gets_an_error_not_a_hang() {
    let mut v = ThreadVectorEnv::with_threads(walks(4), 4).unwrap();
    let _ = v.reset(1u64, None).unwrap();
    let mut pool = ThreadEnvPool::with_threads(walks(4), 2, 4).unwrap();
    pool.reset(1u64).unwrap();
    let a = batch(&[[0.1, 0.1]; 4]);
    let code = in_forked_child(Duration::from_secs(20), move || {
        let step =
            matches!(v.step(&a), Err(Error::Unsupported(m)) if m.to_string().contains("fork"));
        let reset = matches!(v.reset(2u64, None), Err(Error::Unsupported(_)));
        let recv = matches!(pool.recv(), Err(Error::Unsupported(_)));
        v.close();
        pool.close();
        drop(v);
        drop(pool);
        if step && reset && recv { 0 } else { 1 }
    });
    assert_eq!(
        code,
        Some(0),
        "the child failed (1), panicked (99) or hung (None)"
    );
}

#[test]
fn the_parent_keeps_working_after_a_fork() {
    let mut v = ThreadVectorEnv::with_threads(walks(2), 2).unwrap();
    let _ = v.reset(1u64, None).unwrap();
    assert_eq!(in_forked_child(Duration::from_secs(20), || 0), Some(0));
    let a = batch(&[[0.1, 0.1]; 2]);
    let _ = v.step(&a).unwrap();
}
