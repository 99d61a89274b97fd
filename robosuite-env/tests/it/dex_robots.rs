//! robosuite 1.5's Panda with an Inspire hand (`PandaDexRH`, `PandaDexLH`): the hand's
//! composition and mount, its six-action grip, robosuite's scene sizes, snapshots and typed
//! errors.

use crate::common::{act, assert_action_refused, assert_snapshot_replays, get};
use gym_core::{Env, Error};
use robosuite_env::models::robots::{GripperChoice, RobotKind};
use robosuite_env::sim::body_id;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn lift(robot: &str) -> RobosuiteEnv {
    make_with("Lift", EnvConfig::default().with_robots([robot])).unwrap()
}

/// (nq, nbody, ngeom, nu) of the compiled scene.
fn sizes(env: &RobosuiteEnv) -> (i64, i64, i64, i64) {
    let f = env.sim().model().ffi();
    (f.nq, f.nbody, f.ngeom, f.nu)
}

#[test]
fn panda_dex_robots_have_robosuites_hand_layout_and_sizes() {
    for (robot, hand, quat) in [
        ("PandaDexRH", "right_hand", [-0.5, 0.5, 0.5, -0.5]),
        ("PandaDexLH", "left_hand", [0.5, -0.5, 0.5, -0.5]),
    ] {
        let mut env = lift(robot);
        let r = &env.robots()[0];
        assert_eq!(r.kind(), RobotKind::FixedBase, "{robot}");
        assert_eq!(r.composite_controller().name(), "BASIC", "{robot}");
        let slots: Vec<(String, usize)> = r
            .action_layout()
            .iter()
            .map(|s| (s.name.clone(), s.range.len()))
            .collect();
        assert_eq!(
            slots,
            [("right".into(), 6), ("right_gripper".into(), 6)],
            "{robot}"
        );
        // robosuite 1.5.2: action_dim 12, nq 26, nbody 40, ngeom 108, nu 19.
        assert_eq!(env.action_dim(), 12, "{robot}");
        assert_eq!(sizes(&env), (26, 40, 108, 19), "{robot}");
        let gripper = r.arms()[0].gripper();
        assert_eq!((gripper.qpos().len(), gripper.actuators().len()), (12, 12));
        // The hand sits on the flange with the robot's gripper mount quaternion.
        let m = env.sim().model();
        let b = body_id(m, &format!("gripper0_right_{hand}")).unwrap();
        assert_eq!(m.body_quat()[b], quat, "{robot}");
        assert_eq!(m.body_pos()[b], [0.0; 3], "{robot}");
        let (obs, _) = env.reset(Some(0), None).unwrap();
        for key in ["robot0_gripper_qpos", "robot0_gripper_qvel"] {
            assert_eq!(get(&obs, key).len(), 12, "{robot}: {key}");
        }
    }
}

#[test]
fn the_hands_actions_drive_its_twelve_actuators_directly() {
    let mut env = lift("PandaDexRH");
    env.reset(Some(1), None).unwrap();
    let mut a = vec![0.0; 12];
    // pinky, ring, middle, index, thumb bend, thumb rotation.
    a[6..].copy_from_slice(&[0.5, -0.3, 1.2, 0.9, 2.0, 0.4]);
    let _ = env.step(&act(a.clone())).unwrap();
    let acts = env.robots()[0].arms()[0].gripper().actuators().to_vec();
    let ctrl: Vec<f64> = acts.iter().map(|&i| env.sim().data().ctrl()[i]).collect();
    // robosuite's format_action copies the actions to the actuators (pinky distal and
    // proximal, ring, middle, index, thumb distal / middle / proximal 2, thumb proximal 1);
    // GRIP without action scaling clips each to its ctrlrange.
    assert_eq!(
        ctrl,
        [
            0.5, 0.5, 0.0, 0.0, 1.2, 1.2, 0.9, 0.9, 0.77, 0.68, 0.68, 0.4
        ]
    );
    // No integration: the same action gives the same targets again.
    let _ = env.step(&act(a)).unwrap();
    let again: Vec<f64> = acts.iter().map(|&i| env.sim().data().ctrl()[i]).collect();
    assert_eq!(again, ctrl);
    // Closing the fingers bends them.
    let before = env.get_state();
    let q = env.robots()[0].arms()[0].gripper().qpos().to_vec();
    let mut close = vec![0.0; 12];
    close[6..].fill(1.0);
    for _ in 0..10 {
        let _ = env.step(&act(close.clone())).unwrap();
    }
    let index_proximal = q[4];
    let qpos = env.sim().data().qpos();
    assert!(qpos[index_proximal] > 0.3, "{}", qpos[index_proximal]);
    assert_ne!(env.get_state(), before);
}

#[test]
fn two_hands_on_two_arm_lift_have_robosuites_sizes() {
    let env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["PandaDexRH", "PandaDexLH"]),
    )
    .unwrap();
    // robosuite 1.5.2 (opposed): action_dim 24, nq 45, nbody 75, ngeom 217, nu 38.
    assert_eq!(env.action_dim(), 24);
    assert_eq!(sizes(&env), (45, 75, 217, 38));
}

#[test]
fn a_hand_goes_on_any_arm_and_the_mount_offset_on_any_gripper() {
    // robosuite accepts an Inspire hand on a Panda (its file's orientation) ...
    let env = make_with(
        "Lift",
        EnvConfig::default()
            .with_robots(["Panda"])
            .with_gripper_types([GripperChoice::Named("InspireRightHand".into())]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 12);
    let m = env.sim().model();
    let b = body_id(m, "gripper0_right_right_hand").unwrap();
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert!(
        m.body_quat()[b]
            .iter()
            .zip([s, s, 0.0, 0.0])
            .all(|(a, b)| (a - b).abs() < 1e-6),
        "{:?}",
        m.body_quat()[b]
    );
    // ... and a Panda gripper on PandaDexRH, turned by the robot's mount offset.
    let env = make_with(
        "Lift",
        EnvConfig::default()
            .with_robots(["PandaDexRH"])
            .with_gripper_types([GripperChoice::Named("PandaGripper".into())]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 7);
    assert_eq!(sizes(&env).3, 9);
    let m = env.sim().model();
    let b = body_id(m, "gripper0_right_right_gripper").unwrap();
    assert_eq!(m.body_quat()[b], [-0.5, 0.5, 0.5, -0.5]);
}

#[test]
fn bad_input_gives_typed_errors() {
    let mut env = lift("PandaDexRH");
    env.reset(Some(2), None).unwrap();
    let before = env.get_state();
    // A Panda-gripper-sized action (7) for the hand's 12.
    match env.step(&act(vec![0.0; 7])) {
        Err(e @ Error::InvalidAction(_)) => assert!(e.to_string().contains("[12]"), "{e}"),
        other => panic!("{:?}", other.map(|_| ())),
    }
    assert_eq!(env.get_state(), before);
    let mut a = vec![0.0; 12];
    a[9] = f64::INFINITY;
    assert_action_refused(&mut env, a);
    // An unknown hand lists the Inspire hands among the valid grippers.
    let bad = EnvConfig::default()
        .with_robots(["PandaDexRH"])
        .with_gripper_types([GripperChoice::Named("InspireHand".into())]);
    match make_with("Lift", bad) {
        Err(Error::InvalidArgument { name, reason }) => {
            assert_eq!(name, "gripper_types");
            assert!(
                reason.contains("InspireRightHand") && reason.contains("InspireLeftHand"),
                "{reason}"
            );
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
}

#[test]
fn a_snapshot_continues_a_hand_episode_bit_identically() {
    let mut env = lift("PandaDexLH");
    env.reset(Some(3), None).unwrap();
    // Hand actions beyond [-1, 1] included (robosuite passes them on, clipped to the
    // actuators' ctrlranges).
    let action = |t: usize| {
        act((0..12)
            .map(|i| 1.6 * ((t * 5 + i) as f64 * 0.41).sin())
            .collect())
    };
    let actions: Vec<_> = (0..8).map(action).collect();
    assert_snapshot_replays(&mut env, &actions, 4);
}
