//! Door: observation layout, the door placed through the model, reward and success on
//! hand-set states, the latch, a scripted policy that opens the door, state round trips.

use crate::common::fixtures::robosuite_observations;
use crate::common::{
    action, assert_observation_layout, assert_snapshot_replays, finger_yaw, get, wrap_half,
};
use gym_core::{Env, Error, Space, rng_from_seed};
use robosuite_env::sim::{body_id, joint_id};
use robosuite_env::tasks::DoorSpec;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};
use std::f64::consts::FRAC_PI_2;

/// `[time, qpos, qvel]` indices: arm 7, fingers 2, hinge, latch.
const HINGE: usize = 1 + 9;
const LATCH: usize = 1 + 10;

fn door(config: EnvConfig) -> RobosuiteEnv {
    make_with("Door", config).expect("Door builds")
}

#[test]
fn sizes_and_observations_match_robosuite() {
    let mut env = door(EnvConfig::default());
    let m = env.sim().model();
    assert_eq!(
        (
            m.ffi().nq,
            m.ffi().nv,
            m.ffi().nu,
            m.ffi().nbody,
            m.ffi().ngeom
        ),
        (11, 11, 9, 29, 102)
    );
    // robosuite's overrides of the hinge, written into the door's XML.
    let hinge = joint_id(m, "Door_hinge").unwrap();
    let dof = m.jnt_dofadr()[hinge] as usize;
    assert_eq!(
        (m.dof_damping()[dof], m.dof_frictionloss()[dof]),
        (0.1, 0.0)
    );
    assert_eq!(m.jnt_range()[hinge], [0.0, 0.4]);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert_observation_layout(&env, &obs, &robosuite_observations("Door"));
    let (door_pos, handle, eef) = (
        get(&obs, "door_pos"),
        get(&obs, "handle_pos"),
        get(&obs, "robot0_eef_pos"),
    );
    for i in 0..3 {
        assert_eq!(get(&obs, "door_to_eef_pos")[i], door_pos[i] - eef[i]);
        assert_eq!(get(&obs, "handle_to_eef_pos")[i], handle[i] - eef[i]);
    }
    assert_eq!(get(&obs, "hinge_qpos"), [env.get_state()[HINGE]]);
    assert_eq!(get(&obs, "handle_qpos"), [env.get_state()[LATCH]]);

    // Without the latch: robosuite's door.xml, no handle_qpos.
    let spec = DoorSpec {
        use_latch: false,
        ..DoorSpec::default()
    };
    let mut plain = RobosuiteEnv::new(&spec, EnvConfig::default()).unwrap();
    let (obs, _) = plain.reset(Some(0), None).unwrap();
    assert!(obs.get("handle_qpos").is_none());
    assert_eq!(get(&obs, "object-state").len(), 13);
}

#[test]
fn reset_places_the_door_through_the_model() {
    let mut env = door(EnvConfig::default());
    let root = body_id(env.sim().model(), "Door_main").unwrap();
    let mut poses = Vec::new();
    for seed in 0..20 {
        env.reset(Some(seed), None).unwrap();
        let m = env.sim().model();
        let (pos, quat) = (m.body_pos()[root], m.body_quat()[root]);
        // x ∈ U(0.07, 0.09), y ∈ U(−0.01, 0.01) around the table top (−0.2, −0.35, 0.8),
        // the door's bottom (0.3 below its origin) on the table.
        assert!(
            (-0.13..=-0.11).contains(&pos[0]) && (-0.36..=-0.34).contains(&pos[1]),
            "{pos:?}"
        );
        assert!((pos[2] - 1.1).abs() < 1e-12);
        // Yaw ∈ U(−π/2 − 0.25, −π/2) about z.
        assert!(quat[1].abs() < 1e-12 && quat[2].abs() < 1e-12);
        let yaw = 2.0 * quat[3].atan2(quat[0]);
        assert!((-FRAC_PI_2 - 0.25..=-FRAC_PI_2).contains(&yaw), "{yaw}");
        // The world pose follows, and the task state is that pose.
        assert_eq!(env.sim().data().xpos()[root], pos);
        let state = env.task().save_state();
        assert_eq!(state[..3], pos);
        assert_eq!(state[3..], quat);
        poses.push(pos);
    }
    assert_ne!(poses[0], poses[1]);
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let mut env = door(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let mut s = env.get_state();
    s[HINGE] = 0.31;
    env.set_state(&s).unwrap();
    assert!(env.check_success());
    assert_eq!(env.reward(), 1.0);
    s[HINGE] = 0.29;
    env.set_state(&s).unwrap();
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);

    let mut shaped = door(EnvConfig::default().with_reward_shaping(true));
    let (obs, _) = shaped.reset(Some(0), None).unwrap();
    let reach = |obs: &gym_core::DictValue| {
        let d = get(obs, "handle_to_eef_pos")
            .iter()
            .map(|v| v * v)
            .sum::<f64>()
            .sqrt();
        0.25 * (1.0 - (10.0 * d).tanh())
    };
    assert!((shaped.reward() - reach(&obs)).abs() < 1e-12);
    // The handle turned by −π/4 adds 0.25 · |−π/4| / (π/2) = 0.125.
    let mut s = shaped.get_state();
    s[LATCH] = -std::f64::consts::FRAC_PI_4;
    shaped.set_state(&s).unwrap();
    let obs = shaped.observation();
    assert_eq!(get(&obs, "handle_qpos"), [-std::f64::consts::FRAC_PI_4]);
    assert!((shaped.reward() - (reach(&obs) + 0.125)).abs() < 1e-12);
    // The latch term is clipped at 0.25 (the joint allows ±1.57 < π/2, so it never is) and
    // success overrides everything.
    s[HINGE] = 0.35;
    shaped.set_state(&s).unwrap();
    assert_eq!(shaped.reward(), 1.0);
}

#[test]
fn the_latch_holds_the_door_until_the_handle_turns() {
    let mut env = door(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    // Swing the door open without turning the handle: the latch stops it.
    let mut s = env.get_state();
    s[1 + 11 + 9] = 2.0; // hinge velocity
    env.set_state(&s).unwrap();
    for _ in 0..10 {
        let _ = env.step(&crate::common::zero()).unwrap();
    }
    let latched = env.get_state()[HINGE];
    assert!(latched < 0.05, "the latched door opened to {latched}");
    // With the handle turned down by 1.2 rad the latch clears the frame and the door swings.
    env.reset(Some(0), None).unwrap();
    let mut s = env.get_state();
    s[LATCH] = 1.2;
    s[1 + 11 + 9] = 2.0;
    env.set_state(&s).unwrap();
    let _ = env.step(&crate::common::zero()).unwrap();
    let free = env.get_state()[HINGE];
    assert!(free > latched + 0.02, "the unlatched door stayed at {free}");
}

/// Lever geometry of robosuite's door_lock.xml in the latch body's frame: the lever runs
/// along +x, 0.1 m in front of the door (−y).
fn lever_point(
    latch: ([f64; 3], [f64; 9]),
    theta: f64,
    along: f64,
    height: f64,
    behind: f64,
) -> [f64; 3] {
    let (p, r) = latch;
    let col = |j: usize| [r[j], r[3 + j], r[6 + j]];
    let (x, y, z) = (col(0), col(1), col(2));
    let (c, s) = (theta.cos(), theta.sin());
    std::array::from_fn(|i| {
        p[i] + along * (c * x[i] - s * z[i]) + height * (s * x[i] + c * z[i])
            - (0.1 - behind) * y[i]
    })
}

/// Fingers along the lever, above its far half; press it down along its arc by 1.3 rad
/// (the latch clears the frame), then pull along the door's outward normal.
fn scripted_door(env: &mut RobosuiteEnv, seed: u64) -> (bool, usize) {
    let (mut obs, _) = env.reset(Some(seed), None).unwrap();
    let latch_body = body_id(env.sim().model(), "Door_latch").unwrap();
    let (mut phase, mut n, mut theta) = (0, 0, 0.0);
    let mut frame = ([0.0; 3], [0.0; 9]);
    let mut pull = [0.0; 3];
    for t in 0..260 {
        if phase < 2 {
            let d = env.sim().data();
            frame = (d.xpos()[latch_body], d.xmat()[latch_body]);
        }
        let eef = get(&obs, "robot0_eef_pos");
        let outward = [-frame.1[1], -frame.1[4], -frame.1[7]];
        let target = match phase {
            0 => lever_point(frame, 0.0, 0.11, 0.08, 0.012),
            1 => lever_point(frame, 0.0, 0.11, 0.025, 0.012),
            2 => {
                theta = f64::min(theta + 0.05, 1.3);
                lever_point(frame, theta, 0.11, 0.0, 0.012)
            }
            _ => std::array::from_fn(|i| pull[i] + 0.25 * outward[i]),
        };
        let lever_yaw = frame.1[3].atan2(frame.1[0]);
        let yaw_err = if phase < 2 {
            wrap_half(lever_yaw - finger_yaw(&obs))
        } else {
            0.0
        };
        let step = env
            .step(&crate::common::move_to(&eef, target, 10.0, yaw_err, 1.0))
            .unwrap();
        obs = step.observation;
        if step.info.get_bool("success") == Some(true) {
            return (true, t + 1);
        }
        n += 1;
        let d = crate::common::dist3(target, &eef);
        let next = match phase {
            0 => d < 0.006 || n > 90,
            1 => d < 0.006 || n > 30,
            2 => theta >= 1.3 && n > 40,
            _ => false,
        };
        if next {
            phase += 1;
            n = 0;
            pull = [eef[0], eef[1], eef[2]];
        }
    }
    (false, 260)
}

#[test]
fn scripted_policy_opens_the_door() {
    let mut env = door(EnvConfig::default().with_horizon(300));
    crate::common::assert_scripted_successes("Door", &mut env, 3, 2, scripted_door);
}

#[test]
fn task_state_snapshots_and_bad_states() {
    let mut env = door(EnvConfig::default());
    env.reset(Some(6), None).unwrap();
    let state = env.get_state();
    let task_state = env.task().save_state();
    let first = env.observation();
    // Another reset moves the door; starting at the recorded reset puts it back.
    env.reset(Some(7), None).unwrap();
    assert_ne!(env.task().save_state(), task_state);
    let (again, _) = env.reset_to_state(&task_state, &state).unwrap();
    assert_eq!(again, first);
    assert_eq!(env.task().save_state(), task_state);
    // Bad task states are refused and change nothing.
    let before = (env.get_state(), env.task().save_state());
    let mut nan = task_state.clone();
    nan[0] = f64::NAN;
    let mut zero_quat = task_state.clone();
    zero_quat[3..].fill(0.0);
    for bad in [&task_state[..6], &[][..], &nan[..], &zero_quat[..]] {
        assert!(
            matches!(
                env.reset_to_state(bad, &state),
                Err(Error::InvalidArgument { .. })
            ),
            "{bad:?}"
        );
        assert_eq!((env.get_state(), env.task().save_state()), before);
    }
    // Snapshots repeat the steps after them bit for bit (the door pose is restored too).
    let mut rng = rng_from_seed(5);
    let actions: Vec<_> = (0..20)
        .map(|_| env.action_space().sample(&mut rng))
        .collect();
    assert_snapshot_replays(&mut env, &actions, 8);
    let snapshot = env.snapshot();
    env.reset(Some(8), None).unwrap();
    env.restore(&snapshot).unwrap();
    assert_eq!(env.task().save_state(), task_state);
    let _ = env.step(&action([0.0; 7])).unwrap();
}
