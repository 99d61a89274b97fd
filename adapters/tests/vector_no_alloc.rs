//! A vector step does not touch the heap once its buffers exist: `SyncVectorEnv`,
//! `ThreadVectorEnv` (worker threads included) and `ThreadEnvPool`'s `send` / `recv` over
//! robosuite's Lift behind the flat GymWrapper, typed and boxed (`DynEnv::step_into`),
//! and a single GymWrapper's
//! `step_into` in both modes (flat, and Dict). Allocations are counted on every thread, so
//! this file holds one test.

use adapters::{BatchSpace, SyncVectorEnv, ThreadEnvPool, ThreadVectorEnv, VectorEnv, WrapperExt};
use gym_core::{Env, IntoBoxedEnv, Space, Value, rng_from_seed};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

struct Counting;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

fn count() {
    if COUNTING.load(Ordering::Relaxed) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: forwards to the system allocator, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// How many allocations (on any thread) `f` makes.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    f();
    COUNTING.store(false, Ordering::SeqCst);
    ALLOCATIONS.load(Ordering::SeqCst) - before
}

/// Steps `v` with `batches` (after a reset and two warm-up steps that size the buffers) and
/// returns the allocations of the remaining steps; no episode ends within them.
fn step_allocations<V: VectorEnv>(mut v: V, batches: &[adapters::BatchOf<V::ActSpace>]) -> usize {
    v.reset(3u64, None).unwrap();
    for b in &batches[..2] {
        let _ = v.step(b).unwrap();
    }
    allocations(|| {
        for b in &batches[2..] {
            let s = v.step(b).unwrap();
            assert!(!s.terminations.iter().chain(s.truncations).any(|&d| d));
        }
    })
}

#[test]
fn vector_steps_do_not_allocate() {
    let make = || {
        robosuite_env::make("Lift")
            .unwrap()
            .flat_gym_wrapper(None)
            .unwrap()
    };
    let n = 4;
    let single = make().action_space().clone();
    let batched = single.batch_space(n).unwrap();
    let mut rng = rng_from_seed(2);
    let batches: Vec<_> = (0..12).map(|_| batched.sample(&mut rng)).collect();
    let sync = SyncVectorEnv::new((0..n).map(|_| make()).collect()).unwrap();
    assert_eq!(step_allocations(sync, &batches), 0, "SyncVectorEnv");
    for threads in [1, 2, 3, 4] {
        let v = ThreadVectorEnv::with_threads((0..n).map(|_| make()).collect(), threads).unwrap();
        assert_eq!(
            step_allocations(v, &batches),
            0,
            "ThreadVectorEnv, {threads} threads"
        );
    }
    let boxed_batches: Vec<Value> = batches.iter().map(|b| Value::from(b.clone())).collect();
    let boxed = ThreadVectorEnv::with_threads((0..n).map(|_| make().boxed()).collect(), 2).unwrap();
    assert_eq!(
        step_allocations(boxed, &boxed_batches),
        0,
        "boxed ThreadVectorEnv"
    );

    // The pool: 4 envs, batches of 2, on 1 and 2 worker threads; the ids of each batch are
    // copied into a kept buffer, as a caller that sends them back would.
    let pool_batches: Vec<_> = {
        let batched = single.batch_space(2).unwrap();
        (0..10).map(|_| batched.sample(&mut rng)).collect()
    };
    for threads in [1, 2] {
        let mut pool =
            ThreadEnvPool::with_threads((0..n).map(|_| make()).collect(), 2, threads).unwrap();
        pool.reset(3u64).unwrap();
        let mut ids = pool.recv().unwrap().env_ids.to_vec();
        // One send/recv round; counts how often each environment came back.
        let round =
            |pool: &mut ThreadEnvPool<_>, ids: &mut Vec<usize>, b, returned: &mut [usize]| {
                let s = pool.step(b, ids).unwrap();
                assert!(!s.terminations.iter().chain(s.truncations).any(|&d| d));
                ids.copy_from_slice(s.env_ids);
                for &id in s.env_ids {
                    returned[id] += 1;
                }
            };
        // Warm-up until every environment has stepped twice (recording its info keys).
        let mut returned = [0usize; 4];
        for b in pool_batches.iter().cycle().take(40) {
            round(&mut pool, &mut ids, b, &mut returned);
        }
        assert!(returned.iter().all(|&r| r >= 2), "warm-up: {returned:?}");
        let count = allocations(|| {
            for b in &pool_batches {
                round(&mut pool, &mut ids, b, &mut returned);
            }
        });
        assert_eq!(count, 0, "ThreadEnvPool, {threads} threads");
    }

    // Camera observations, Dict GymWrapper, boxed: images written straight into the batch.
    let camera = || {
        let config = robosuite_env::EnvConfig::default().with_cameras(
            robosuite_env::config::CameraConfig::observe(["agentview"], 24, 24),
        );
        robosuite_env::make_with("Lift", config)
            .unwrap()
            .gym_wrapper(None, false)
            .unwrap()
            .boxed()
    };
    let camera_batches: Vec<Value> = batches[..6]
        .iter()
        .map(|b| {
            let rows = b.slice(ndarray::s![..2, ..]).to_owned().into_dyn();
            Value::from(rows)
        })
        .collect();
    let cameras = ThreadVectorEnv::with_threads(vec![camera(), camera()], 2).unwrap();
    assert_eq!(
        step_allocations(cameras, &camera_batches),
        0,
        "boxed ThreadVectorEnv with a camera"
    );

    for flatten_obs in [true, false] {
        let mut env = robosuite_env::make("Lift")
            .unwrap()
            .gym_wrapper(None, flatten_obs)
            .unwrap();
        let actions: Vec<_> = (0..12)
            .map(|_| env.action_space().sample(&mut rng))
            .collect();
        let (mut obs, mut info) = env.reset(Some(3), None).unwrap();
        for a in &actions[..2] {
            let _ = env.step_into(a, &mut obs, &mut info).unwrap();
        }
        let n = allocations(|| {
            for a in &actions[2..] {
                let t = env.step_into(a, &mut obs, &mut info).unwrap();
                assert!(!t.done());
            }
        });
        assert_eq!(n, 0, "GymWrapper::step_into, flatten_obs = {flatten_obs}");
    }
}
