//! The substep loop (`mj_step1` → controllers → `mj_step2`) does not touch the heap.

use gym_core::Env;
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, make_with};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn substeps_do_not_allocate() {
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(0), None).unwrap();
    let mut sim = Sim::new(env.sim().model().clone()).unwrap();
    sim.set_state(&env.get_state()).unwrap();
    let mut robot = env.robots()[0].clone();
    let action = [0.4, -0.2, 0.3, 0.1, -0.1, 0.2, 1.0];
    // Warm up once (first calls may initialise lazily).
    sim.step1();
    robot.set_goal(&sim, &action);
    robot.apply_control(&mut sim);
    sim.step2();
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..10 {
        for sub in 0..25 {
            sim.step1();
            if sub == 0 {
                robot.set_goal(&sim, &action);
            }
            robot.apply_control(&mut sim);
            sim.step2();
        }
    }
    let after = ALLOCATIONS.load(Ordering::Relaxed);
    assert_eq!(
        after - before,
        0,
        "the substep loop allocated {} times",
        after - before
    );
    // The arm moved, so the loop did real work.
    assert!(env.get_state() != sim.state());
}
