//! Environments of one configuration share one compiled model, copy-on-write: each reads
//! the same memory, and whatever one writes (resets' resizes, direct edits, divergence) is
//! seen by no other.

use crate::common::{action, get, zero};
use gym_core::{DictValue, Env};
use robosuite_env::sim::{MAX_STATE_MAGNITUDE, body_id};
use robosuite_env::{RobosuiteEnv, make};
use std::sync::Arc;

/// The bytes of a model's buffer (every array).
fn model_bytes(model: &mujoco_rs::wrappers::mj_model::MjModel) -> Vec<u8> {
    let m = model.ffi();
    // SAFETY: the buffer holds `nbuffer` bytes, alive and unwritten while borrowed.
    unsafe { std::slice::from_raw_parts(m.buffer.cast::<u8>(), m.nbuffer as usize) }.to_vec()
}

fn shared(env: &RobosuiteEnv) -> &Arc<robosuite_env::sim::SharedModel> {
    env.sim()
        .shared_model()
        .expect("a made env views the cached model")
}

#[test]
fn envs_of_one_configuration_share_one_model() {
    let a = make("Lift").unwrap();
    let b = make("Lift").unwrap();
    assert!(Arc::ptr_eq(shared(&a), shared(&b)));
    assert!(
        Arc::strong_count(shared(&a)) >= 3,
        "the cache and both envs"
    );
    #[cfg(target_os = "linux")]
    assert!(shared(&a).is_mapped());
    // Each env's model equals the shared one, through memory of its own address.
    assert_eq!(
        model_bytes(a.sim().model()),
        model_bytes(shared(&a).model())
    );
    assert_ne!(a.sim().model().ffi().buffer, b.sim().model().ffi().buffer);
    // Another configuration, another model.
    let c = make("Stack").unwrap();
    assert!(!Arc::ptr_eq(shared(&a), shared(&c)));
}

#[test]
fn what_one_env_writes_no_other_env_sees() {
    let mut a = make("Lift").unwrap();
    let mut b = make("Lift").unwrap();
    let base = model_bytes(shared(&a).model());
    a.reset(Some(1), None).unwrap();
    b.reset(Some(2), None).unwrap();
    let cube = body_id(a.sim().model(), "cube_main").unwrap();
    let (cube_a, cube_b) = (
        a.sim().model().body_mass()[cube],
        b.sim().model().body_mass()[cube],
    );
    assert_ne!(cube_a, cube_b, "the resets drew different cubes");
    let b_before = model_bytes(b.sim().model());
    // A direct edit of every geom colour of `a`'s model.
    // SAFETY: values only, no size or address.
    for rgba in unsafe { a.sim_mut().data_mut().model_mut() }.geom_rgba_mut() {
        *rgba = [0.25; 4];
    }
    assert!(a.sim().model().geom_rgba().iter().all(|c| *c == [0.25; 4]));
    assert_eq!(model_bytes(b.sim().model()), b_before);
    assert_eq!(
        model_bytes(shared(&a).model()),
        base,
        "the shared model never changes"
    );
    // A new env starts from the compiled model, not from anything written since.
    let c = make("Lift").unwrap();
    assert_eq!(model_bytes(c.sim().model()), base);
}

#[test]
fn a_model_made_private_keeps_its_values_and_leaves_the_shared_one() {
    let mut a = make("Lift").unwrap();
    a.reset(Some(3), None).unwrap();
    let before = model_bytes(a.sim().model());
    a.sim_mut().data_mut().make_model_private();
    assert!(a.sim().shared_model().is_none());
    assert_eq!(model_bytes(a.sim().model()), before);
    // It steps on as it did.
    let _ = a.step(&zero()).unwrap();
}

/// Lone envs (models of their own) and envs sharing one model, stepped on threads with
/// env 0 driven to divergence: every other env is bit-identical to its lone twin.
#[test]
fn a_diverged_env_leaves_its_neighbours_bit_identical_to_lone_envs() {
    const N: usize = 4;
    let lone_obs = (0..N)
        .map(|i| {
            let mut env = make("Lift").unwrap();
            env.sim_mut().data_mut().make_model_private();
            run(&mut env, i, false)
        })
        .collect::<Vec<_>>();
    let mut envs: Vec<RobosuiteEnv> = (0..N).map(|_| make("Lift").unwrap()).collect();
    let shared_obs: Vec<_> = std::thread::scope(|s| {
        let handles: Vec<_> = envs
            .iter_mut()
            .enumerate()
            .map(|(i, env)| s.spawn(move || run(env, i, i == 0)))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for i in 1..N {
        assert_eq!(shared_obs[i], lone_obs[i], "env {i}");
    }
    assert!(shared_obs[0].is_empty(), "env 0 diverged");
}

/// Resets with seed `i`, steps 15 times (diverging first when `diverge`), and returns the
/// flattened observations (empty once a step fails).
fn run(env: &mut RobosuiteEnv, i: usize, diverge: bool) -> Vec<Vec<f64>> {
    let _ = env.reset(Some(i as u64), None).unwrap();
    if diverge {
        let mut state = env.get_state();
        let nq = env.sim().model().ffi().nq as usize;
        for v in &mut state[1 + nq..] {
            *v = MAX_STATE_MAGNITUDE;
        }
        env.set_state(&state).unwrap();
    }
    let a = action([0.3, -0.2 * i as f64, 0.1, 0.0, 0.05, -0.1, 1.0]);
    let mut out = Vec::new();
    for _ in 0..15 {
        match env.step(&a) {
            Ok(step) => out.push(flat(&step.observation)),
            Err(_) => return Vec::new(),
        }
    }
    out
}

fn flat(obs: &DictValue) -> Vec<f64> {
    [
        "robot0_joint_pos",
        "robot0_eef_pos",
        "cube_pos",
        "cube_quat",
    ]
    .iter()
    .flat_map(|k| get(obs, k))
    .collect()
}

/// The 8-byte words of a model header.
fn header_words(model: &mujoco_rs::wrappers::mj_model::MjModel) -> Vec<u64> {
    let n = std::mem::size_of::<mujoco_rs::mujoco_c::mjModel>() / 8;
    let p = std::ptr::from_ref(model.ffi()).cast::<u64>();
    // SAFETY: whole words of the struct, read unaligned.
    (0..n)
        .map(|k| unsafe { p.add(k).read_unaligned() })
        .collect()
}

#[test]
fn a_view_header_is_the_shared_header_with_its_pointers_moved_to_its_own_memory() {
    let env = make("Lift").unwrap();
    let (view, base) = (env.sim().model(), shared(&env).model());
    let (vb, bb) = (view.ffi().buffer as u64, base.ffi().buffer as u64);
    let mut moved = 0;
    for (v, b) in header_words(view).into_iter().zip(header_words(base)) {
        if v != b {
            assert_eq!(
                v.wrapping_sub(vb),
                b.wrapping_sub(bb),
                "a word that is no buffer pointer"
            );
            moved += 1;
        }
    }
    assert!(moved > 100, "every array pointer moves ({moved})");
    // MuJoCo keeps nothing of a model outside its buffer: two copies differ only in
    // pointers into their own buffers.
    let (c1, c2) = (base.clone(), base.clone());
    let (b1, b2) = (c1.ffi().buffer as u64, c2.ffi().buffer as u64);
    for (x, y) in header_words(&c1).into_iter().zip(header_words(&c2)) {
        assert!(x == y || x.wrapping_sub(b1) == y.wrapping_sub(b2));
    }
}
