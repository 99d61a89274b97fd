//! Door: observations, hand-set states and a scripted policy.

mod common;

use common::{finger_yaw, get, move_to, wrap_half};
use gym_core::Env;
use robosuite_env::sim::body_id;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn door(config: EnvConfig) -> RobosuiteEnv {
    make_with("Door", config).expect("Door builds")
}

#[test]
fn door_sizes_and_observations_match_robosuite() {
    let mut env = door(EnvConfig::default());
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu), (11, 11, 9));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let keys = env.observation_keys();
    assert_eq!(
        &keys[10..],
        &[
            "door_pos",
            "handle_pos",
            "hinge_qpos",
            "door_to_eef_pos",
            "handle_to_eef_pos",
            "handle_qpos",
            "robot0_proprio-state",
            "object-state"
        ]
    );
    assert_eq!(get(&obs, "object-state").len(), 14);
    assert_eq!(
        obs.get("hinge_qpos").unwrap().as_array().unwrap().shape(),
        &[] as &[usize]
    );
    // The door's root is placed through the model (x 0.07..0.09, y ±0.01 around the table top).
    for seed in 0..4 {
        env.reset(Some(seed), None).unwrap();
        let root = body_id(env.sim().model(), "Door_main").unwrap();
        let p = env.sim().data().xpos()[root];
        assert!(
            (-0.13..=-0.11).contains(&p[0]) && (-0.36..=-0.34).contains(&p[1]),
            "{p:?}"
        );
        let q = env.sim().data().xquat()[root];
        let yaw = 2.0 * q[3].atan2(q[0]);
        assert!(
            (-std::f64::consts::FRAC_PI_2 - 0.25 - 1e-9..=-std::f64::consts::FRAC_PI_2 + 1e-9)
                .contains(&yaw),
            "{yaw}"
        );
    }
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let mut env = door(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let mut s = env.get_state();
    // [time, qpos]: arm 7, fingers 2, hinge, latch.
    s[10] = 0.31;
    env.set_state(&s).unwrap();
    assert!(env.check_success());
    assert_eq!(env.reward(), 1.0);
    s[10] = 0.29;
    env.set_state(&s).unwrap();
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);

    let mut shaped = door(EnvConfig::default().with_reward_shaping(true));
    let (obs, _) = shaped.reset(Some(0), None).unwrap();
    let d: f64 = get(&obs, "handle_to_eef_pos")
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    assert!((shaped.reward() - 0.25 * (1.0 - (10.0 * d).tanh())).abs() < 1e-9);
    let mut s = shaped.get_state();
    s[11] = -0.785;
    shaped.set_state(&s).unwrap();
    let obs = shaped.observation();
    assert_eq!(get(&obs, "handle_qpos"), [-0.785]);
    let d: f64 = get(&obs, "handle_to_eef_pos")
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    let expected = 0.25 * (1.0 - (10.0 * d).tanh()) + 0.25 * 0.785 / std::f64::consts::FRAC_PI_2;
    assert!((shaped.reward() - expected).abs() < 1e-9);
}

#[test]
fn the_latch_holds_the_door_until_the_handle_turns() {
    let mut env = door(EnvConfig::default().with_horizon(100));
    env.reset(Some(0), None).unwrap();
    // Force the door open without turning the handle: the tongue stops it.
    let mut s = env.get_state();
    s[10] = 0.0;
    env.set_state(&s).unwrap();
    let mut s2 = env.get_state();
    // qvel of the hinge (index 1 + nq + 9).
    s2[1 + 11 + 9] = 2.0;
    env.set_state(&s2).unwrap();
    for _ in 0..10 {
        let _ = env.step(&common::zero()).unwrap();
    }
    let hinge = env.get_state()[10];
    assert!(hinge < 0.08, "latched door opened to {hinge}");
}

/// Grasp the lever, press it down, pull the door open.
fn scripted_door(env: &mut RobosuiteEnv, seed: u64, verbose: bool) -> (bool, usize) {
    let (mut obs, _) = env.reset(Some(seed), None).unwrap();
    let door = body_id(env.sim().model(), "Door_door").unwrap();
    let mut phase = 0;
    let mut n = 0;
    let mut anchor = [0.0; 3];
    for t in 0..300 {
        let eef = get(&obs, "robot0_eef_pos");
        let h = get(&obs, "handle_pos");
        let q = env.sim().data().xquat()[door];
        let yaw = 2.0 * q[3].atan2(q[0]);
        // The door's outward normal (its local −y) in the world.
        let normal = [yaw.sin(), -yaw.cos()];
        let latch = get(&obs, "handle_qpos")[0];
        let (target, grip, align) = match phase {
            0 => ([h[0], h[1], h[2] + 0.08], -1.0, true),
            1 => ([h[0], h[1], h[2] - 0.005], -1.0, true),
            2 => ([eef[0], eef[1], eef[2]], 1.0, true),
            3 => ([anchor[0], anchor[1], anchor[2] - 0.08], 1.0, false),
            _ => (
                [
                    eef[0] + 0.1 * normal[0],
                    eef[1] + 0.1 * normal[1],
                    anchor[2] - 0.08,
                ],
                1.0,
                false,
            ),
        };
        let yaw_err = if align {
            // Fingers close along the door normal.
            wrap_half(normal[1].atan2(normal[0]) - finger_yaw(&obs))
        } else {
            0.0
        };
        let step = env
            .step(&move_to(&eef, target, 10.0, yaw_err, grip))
            .unwrap();
        obs = step.observation;
        if verbose {
            eprintln!(
                "t {t} ph {phase} eef {eef:.3?} h {h:.3?} latch {latch:.3} hinge {:.3} yaw_err {yaw_err:.3}",
                get(&obs, "hinge_qpos")[0]
            );
        }
        if step.info.get_bool("success") == Some(true) {
            return (true, t + 1);
        }
        n += 1;
        let d = common::dist3(target, &eef);
        let next = match phase {
            0 => (d < 0.01 && yaw_err.abs() < 0.05) || n > 60,
            1 => d < 0.006 || n > 40,
            2 => n >= 12,
            3 => latch > 0.5 || n > 40,
            _ => false,
        };
        if next {
            phase += 1;
            n = 0;
            anchor = [eef[0], eef[1], eef[2]];
        }
    }
    (false, 300)
}

#[test]
fn scripted_policy_opens_the_door() {
    let mut env = door(EnvConfig::default().with_horizon(300));
    let verbose = std::env::var_os("DOOR_VERBOSE").is_some();
    let mut ok = 0;
    let mut report = Vec::new();
    for seed in 0..3 {
        let r = scripted_door(&mut env, seed, verbose);
        ok += usize::from(r.0);
        report.push(r);
    }
    assert!(
        ok >= 2,
        "scripted Door succeeded on {ok}/3 seeds: {report:?}"
    );
}
