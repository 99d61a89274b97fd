//! Stack: observation layout, placement, reward and success on hand-set states, a scripted
//! policy, state round trips.

use crate::common::fixtures::robosuite_observations;
use crate::common::{
    action, assert_observation_layout, assert_snapshot_replays, dist3, finger_yaw, get, move_to,
    wrap_to_quarter, yaw_of,
};
use gym_core::{Env, Error, Space, rng_from_seed};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn stack(config: EnvConfig) -> RobosuiteEnv {
    make_with("Stack", config).expect("Stack builds")
}

#[test]
fn sizes_and_observations_match_robosuite() {
    let mut env = stack(EnvConfig::default());
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu, m.nbody, m.ngeom), (23, 21, 9, 27, 92));
    assert_eq!(env.action_dim(), 7);
    let (obs, info) = env.reset(Some(0), None).unwrap();
    assert_eq!(info.get_bool("success"), Some(false));
    let stack_obs = robosuite_observations("Stack");
    assert_observation_layout(&env, &obs, &stack_obs);
    let object: Vec<f64> = stack_obs[10..17]
        .iter()
        .flat_map(|(k, _, _)| get(&obs, k))
        .collect();
    assert_eq!(get(&obs, "object-state"), object);
    let (a, b, eef) = (
        get(&obs, "cubeA_pos"),
        get(&obs, "cubeB_pos"),
        get(&obs, "robot0_eef_pos"),
    );
    for i in 0..3 {
        assert_eq!(get(&obs, "cubeA_to_cubeB")[i], b[i] - a[i]);
        assert_eq!(get(&obs, "gripper_to_cubeA")[i], a[i] - eef[i]);
        assert_eq!(get(&obs, "gripper_to_cubeB")[i], b[i] - eef[i]);
    }
    // Without object observations only the robot's remain.
    let mut bare = stack(EnvConfig::default().with_object_obs(false));
    let (obs, _) = bare.reset(Some(0), None).unwrap();
    let keys: Vec<&str> = obs.keys().map(String::as_str).collect();
    let robot: Vec<&str> = stack_obs[..10]
        .iter()
        .map(|(k, _, _)| k.as_str())
        .chain(["robot0_proprio-state"])
        .collect();
    assert_eq!(keys, robot);
}

#[test]
fn reset_places_the_cubes_in_range_without_overlap() {
    let mut env = stack(EnvConfig::default());
    let (mut ax, mut bx) = (Vec::new(), Vec::new());
    for seed in 0..30 {
        let (obs, _) = env.reset(Some(seed), None).unwrap();
        let (a, b) = (get(&obs, "cubeA_pos"), get(&obs, "cubeB_pos"));
        for p in [&a, &b] {
            assert!(p[0].abs() <= 0.08 && p[1].abs() <= 0.08, "{p:?}");
        }
        // Resting 1 cm above the table (top at 0.8), upright, apart.
        assert!((a[2] - 0.83).abs() < 1e-12 && (b[2] - 0.835).abs() < 1e-12);
        for q in [get(&obs, "cubeA_quat"), get(&obs, "cubeB_quat")] {
            assert!(q[0].abs() < 1e-12 && q[1].abs() < 1e-12, "{q:?}");
        }
        let r = 0.02f64.hypot(0.02) + 0.025f64.hypot(0.025);
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) > r);
        ax.push(a[0]);
        bx.push(b[0]);
    }
    // Spread over the range.
    let spread = |v: &[f64]| {
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - v.iter().copied().fold(f64::INFINITY, f64::min)
    };
    assert!(spread(&ax) > 0.1 && spread(&bx) > 0.1);
    // Stack draws no model parameters: its task state is empty.
    assert!(env.task().save_state().is_empty());
}

/// Writes both cubes' positions (upright, at rest) and runs a forward pass.
fn set_cubes(env: &mut RobosuiteEnv, a: [f64; 3], b: [f64; 3]) {
    let mut s = env.get_state();
    // [time, qpos]: arm 7, fingers 2, cubeA 7, cubeB 7.
    s[10..13].copy_from_slice(&a);
    s[13..17].copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
    s[17..20].copy_from_slice(&b);
    s[20..24].copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
    env.set_state(&s).unwrap();
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let mut env = stack(EnvConfig::default().with_reward_scale(None));
    env.reset(Some(0), None).unwrap();
    // Cube A resting on cube B (0.1 mm of penetration makes the contact): stacked.
    set_cubes(&mut env, [0.0, 0.0, 0.8699], [0.0, 0.0, 0.825]);
    assert!(env.check_success());
    assert_eq!(env.reward(), 2.0);
    // Lifted but touching nothing: not stacked.
    set_cubes(&mut env, [0.0, 0.0, 0.95], [0.1, 0.0, 0.825]);
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
    // Touching but not lifted (side by side on the table): not stacked.
    set_cubes(&mut env, [0.0, 0.0, 0.82], [0.0449, 0.0, 0.825]);
    assert!(!env.check_success());

    let mut shaped = stack(EnvConfig::default().with_reward_shaping(true));
    let (obs, _) = shaped.reset(Some(0), None).unwrap();
    // Reaching: 0.25 (1 − tanh(10 d)), normalised by 2.
    let d = get(&obs, "gripper_to_cubeA")
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    let reach = (1.0 - (10.0 * d).tanh()) * 0.25;
    assert!((shaped.reward() - reach / 2.0).abs() < 1e-12);
    // Lifting and aligning: 1 + 0.5 (1 − tanh(horizontal distance)), normalised by 2.
    set_cubes(&mut shaped, [0.0, 0.0, 0.95], [0.1, 0.0, 0.825]);
    let lift = 1.0 + 0.5 * (1.0 - 0.1f64.tanh());
    assert!(
        (shaped.reward() - lift / 2.0).abs() < 1e-12,
        "{}",
        shaped.reward()
    );
    // Stacking: 2, normalised to 1; reward_scale 3 scales it to 3.
    set_cubes(&mut shaped, [0.0, 0.0, 0.8699], [0.0, 0.0, 0.825]);
    assert_eq!(shaped.reward(), 1.0);
    let mut scaled = stack(EnvConfig::default().with_reward_scale(Some(3.0)));
    scaled.reset(Some(0), None).unwrap();
    set_cubes(&mut scaled, [0.0, 0.0, 0.8699], [0.0, 0.0, 0.825]);
    assert_eq!(scaled.reward(), 3.0);
}

/// Grasp cube A, lift, carry it over cube B, lower, release; returns whether `success` was
/// reported and when.
fn scripted_stack(env: &mut RobosuiteEnv, seed: u64) -> (bool, usize) {
    let (mut obs, _) = env.reset(Some(seed), None).unwrap();
    let (mut phase, mut n) = (0, 0);
    for t in 0..260 {
        let eef = get(&obs, "robot0_eef_pos");
        let (a, b) = (get(&obs, "cubeA_pos"), get(&obs, "cubeB_pos"));
        let carry = [b[0] + eef[0] - a[0], b[1] + eef[1] - a[1]];
        let (target, grip, align) = match phase {
            0 => ([a[0], a[1], a[2] + 0.08], -1.0, true),
            1 => ([a[0], a[1], a[2] - 0.005], -1.0, true),
            2 => ([eef[0], eef[1], eef[2]], 1.0, false),
            3 => ([eef[0], eef[1], 0.95], 1.0, false),
            4 => ([carry[0], carry[1], 0.95], 1.0, false),
            5 => (
                [carry[0], carry[1], eef[2] + b[2] + 0.047 - a[2]],
                1.0,
                false,
            ),
            6 => ([eef[0], eef[1], eef[2]], -1.0, false),
            _ => ([eef[0], eef[1], 1.0], -1.0, false),
        };
        let yaw_err = if align {
            wrap_to_quarter(yaw_of(&get(&obs, "cubeA_quat")) - finger_yaw(&obs))
        } else {
            0.0
        };
        let step = env
            .step(&move_to(&eef, target, 10.0, yaw_err, grip))
            .unwrap();
        obs = step.observation;
        if step.info.get_bool("success") == Some(true) {
            return (true, t + 1);
        }
        n += 1;
        let d = dist3(target, &eef);
        let next = match phase {
            0 => (d < 0.01 && yaw_err.abs() < 0.05) || n > 45,
            1 => d < 0.008 || n > 25,
            2 => n > 8,
            3 => eef[2] > 0.93 || n > 30,
            4 => (a[0] - b[0]).hypot(a[1] - b[1]) < 0.004 || n > 50,
            5 => a[2] - b[2] < 0.05 || n > 30,
            6 => n > 10,
            _ => false,
        };
        if next {
            phase += 1;
            n = 0;
        }
    }
    (false, 260)
}

#[test]
fn scripted_policy_stacks_the_cubes() {
    let mut env = stack(EnvConfig::default().with_horizon(300));
    crate::common::assert_scripted_successes("Stack", &mut env, 4, 3, scripted_stack);
}

#[test]
fn task_state_snapshots_and_bad_states() {
    let mut env = stack(EnvConfig::default());
    env.reset(Some(4), None).unwrap();
    let state = env.get_state();
    let task_state = env.task().save_state();
    let first = env.observation();
    // Starting an episode at the recorded reset repeats it.
    let _ = env
        .step(&action([0.3, 0.2, -0.4, 0.0, 0.0, 0.1, 1.0]))
        .unwrap();
    let (again, _) = env.reset_to_state(&task_state, &state).unwrap();
    assert_eq!(again, first);
    // A task state of the wrong shape is refused and changes nothing.
    let before = env.get_state();
    assert!(matches!(
        env.reset_to_state(&[0.02], &state),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(env.get_state(), before);
    // Snapshots repeat the steps after them bit for bit.
    let mut rng = rng_from_seed(3);
    let actions: Vec<_> = (0..20)
        .map(|_| env.action_space().sample(&mut rng))
        .collect();
    assert_snapshot_replays(&mut env, &actions, 8);
}
