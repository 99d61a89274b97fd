//! Stack: observations, hand-set states and a scripted policy.

mod common;

use common::{dist3, finger_yaw, get, move_to, wrap_to_quarter, yaw_of};
use gym_core::{DType, Env};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn stack(config: EnvConfig) -> RobosuiteEnv {
    make_with("Stack", config).expect("Stack builds")
}

#[test]
fn stack_sizes_and_observations_match_robosuite() {
    let mut env = stack(EnvConfig::default());
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu), (23, 21, 9));
    let (obs, info) = env.reset(Some(0), None).unwrap();
    assert_eq!(info.get_bool("success"), Some(false));
    let keys = env.observation_keys();
    let expected_obj = [
        "cubeA_pos",
        "cubeA_quat",
        "cubeB_pos",
        "cubeB_quat",
        "cubeA_to_cubeB",
        "gripper_to_cubeA",
        "gripper_to_cubeB",
    ];
    assert_eq!(&keys[10..17], &expected_obj);
    assert_eq!(&keys[17..], &["robot0_proprio-state", "object-state"]);
    assert_eq!(get(&obs, "object-state").len(), 23);
    assert_eq!(
        obs.get("cubeA_pos").unwrap().as_array().unwrap().dtype(),
        DType::F64
    );
    // Placement: in range, resting 1 cm above the table, without overlap.
    for seed in 0..5 {
        let (obs, _) = env.reset(Some(seed), None).unwrap();
        let a = get(&obs, "cubeA_pos");
        let b = get(&obs, "cubeB_pos");
        assert!(a[0].abs() <= 0.08 && a[1].abs() <= 0.08 && b[0].abs() <= 0.08);
        assert!((a[2] - 0.83).abs() < 1e-9 && (b[2] - 0.835).abs() < 1e-9);
        assert!((a[0] - b[0]).hypot(a[1] - b[1]) > 0.0636);
        let ab = get(&obs, "cubeA_to_cubeB");
        for i in 0..3 {
            assert!((ab[i] - (b[i] - a[i])).abs() < 1e-12);
        }
    }
}

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
    // Released on top of cube B (1e-4 m of penetration gives the contact): success.
    set_cubes(&mut env, [0.0, 0.0, 0.8699], [0.0, 0.0, 0.825]);
    assert!(env.check_success());
    assert_eq!(env.reward(), 2.0);
    // Lifted but not touching: no success, no sparse reward.
    set_cubes(&mut env, [0.0, 0.0, 0.95], [0.1, 0.0, 0.825]);
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
    // Both on the table: nothing.
    set_cubes(&mut env, [0.0, 0.1, 0.82], [0.0, -0.1, 0.825]);
    assert!(!env.check_success());

    let mut shaped = stack(EnvConfig::default().with_reward_shaping(true));
    shaped.reset(Some(0), None).unwrap();
    set_cubes(&mut shaped, [0.0, 0.0, 0.95], [0.1, 0.0, 0.825]);
    // Lift stage: (1 + 0.5 (1 − tanh 0.1)) / 2.
    let expected = (1.0 + 0.5 * (1.0 - 0.1f64.tanh())) / 2.0;
    assert!(
        (shaped.reward() - expected).abs() < 1e-9,
        "{}",
        shaped.reward()
    );
    set_cubes(&mut shaped, [0.0, 0.0, 0.8699], [0.0, 0.0, 0.825]);
    assert_eq!(shaped.reward(), 1.0);
}

/// Grasp cube A, lift, move above cube B, lower, release.
fn scripted_stack(env: &mut RobosuiteEnv, seed: u64) -> (bool, usize) {
    let (mut obs, _) = env.reset(Some(seed), None).unwrap();
    let mut phase = 0;
    let mut n = 0;
    for t in 0..260 {
        let eef = get(&obs, "robot0_eef_pos");
        let a = get(&obs, "cubeA_pos");
        let b = get(&obs, "cubeB_pos");
        let (target, grip, align) = match phase {
            0 => ([a[0], a[1], a[2] + 0.08], -1.0, true),
            1 => ([a[0], a[1], a[2] - 0.005], -1.0, true),
            2 => ([eef[0], eef[1], eef[2]], 1.0, false),
            3 => ([eef[0], eef[1], 0.98], 1.0, false),
            // Carry: keep the grip site's offset to cube A while bringing A over B.
            4 => (
                [b[0] + eef[0] - a[0], b[1] + eef[1] - a[1], 0.98],
                1.0,
                false,
            ),
            5 => (
                [
                    b[0] + eef[0] - a[0],
                    b[1] + eef[1] - a[1],
                    eef[2] + b[2] + 0.05 - a[2],
                ],
                1.0,
                false,
            ),
            _ => ([eef[0], eef[1], eef[2] + 0.01], -1.0, false),
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
            0 => (d < 0.01 && yaw_err.abs() < 0.05) || n > 60,
            1 => d < 0.006 || n > 40,
            2 => n >= 12,
            3 => d < 0.01 || n > 40,
            4 => d < 0.005 || n > 60,
            5 => d < 0.005 || n > 40,
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
    let mut report = Vec::new();
    let mut ok = 0;
    for seed in 0..3 {
        let r = scripted_stack(&mut env, seed);
        ok += usize::from(r.0);
        report.push(r);
    }
    assert!(
        ok >= 2,
        "scripted Stack succeeded on {ok}/3 seeds: {report:?}"
    );
}
