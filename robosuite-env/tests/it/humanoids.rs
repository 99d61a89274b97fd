//! robosuite 1.5's GR1 humanoids (`GR1`, `GR1ArmsOnly`, `GR1FloatingBody`,
//! `GR1FixedLowerBody`): body parts, default composite controllers and action sizes as
//! robosuite's, the Fourier hands' action, and typed errors for what cannot be served.

use crate::common::get;
use gym_core::{Env, Error};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::models::robots::RobotKind;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn act(values: Vec<f64>) -> ArrayD<f64> {
    ArrayD::from_shape_vec(IxDyn(&[values.len()]), values).unwrap()
}

fn gr1(robot: &str) -> RobosuiteEnv {
    make_with("TwoArmLift", EnvConfig::default().with_robots([robot])).unwrap()
}

/// Where `name` (`"right"`, `"right_gripper"`, ...) sits in the action: the composite
/// controller's input split (WHOLE_BODY_IK's poses), else the parts' layout.
fn slot(env: &RobosuiteEnv, name: &str) -> std::ops::Range<usize> {
    let robot = &env.robots()[0];
    let split = robot.action_split().unwrap_or_else(|| {
        robot
            .action_layout()
            .iter()
            .map(|s| (s.name.clone(), s.range.clone()))
            .collect()
    });
    split
        .into_iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no `{name}` slot"))
        .1
}

/// robosuite 1.5.2 (TwoArmLift, one robot): the composite controller, the controlled body
/// parts besides the arms, the action size and the base / per-arm observation keys.
#[test]
fn gr1_robots_have_robosuites_parts_and_action_sizes() {
    for (robot, composite, parts, dim) in [
        ("GR1", "WHOLE_BODY_IK", &["legs", "head", "torso"][..], 24),
        ("GR1ArmsOnly", "WHOLE_BODY_IK", &[][..], 24),
        (
            "GR1FloatingBody",
            "HYBRID_MOBILE_BASE",
            &["base", "head", "torso"][..],
            34,
        ),
    ] {
        let mut env = gr1(robot);
        let r = &env.robots()[0];
        assert_eq!(r.kind(), RobotKind::Legged, "{robot}");
        assert_eq!(r.composite_controller().name(), composite, "{robot}");
        let got: Vec<&str> = r.body_parts().iter().map(|b| b.name()).collect();
        assert_eq!(got, parts, "{robot}");
        assert_eq!(env.action_dim(), dim, "{robot}");
        let (obs, _) = env.reset(Some(0), None).unwrap();
        for key in [
            "robot0_base_pos",
            "robot0_base_to_right_eef_pos",
            "robot0_left_eef_pos",
            "robot0_right_gripper_qpos",
        ] {
            assert!(obs.get(key).is_some(), "{robot}: {key}");
        }
        // Each Fourier hand has 11 finger joints.
        assert_eq!(get(&obs, "robot0_right_gripper_qpos").len(), 11, "{robot}");
    }
}

/// robosuite's `FourierRightHand.format_action` copies 6 actions onto 11 actuators, and
/// GR1's configs turn action scaling off: each target is its action, clipped to the
/// actuator's ctrlrange.
#[test]
fn a_fourier_hand_drives_its_fingers_with_robosuites_indices() {
    let mut env = gr1("GR1ArmsOnly");
    env.reset(Some(1), None).unwrap();
    let hand = slot(&env, "right_gripper");
    assert_eq!(hand.len(), 6);
    let mut a = vec![0.0; env.action_dim()];
    let hand_action = [0.1, 0.2, 0.3, 0.4, 0.5, 2.5];
    a[hand.clone()].copy_from_slice(&hand_action);
    let _ = env.step(&act(a)).unwrap();
    let g = env.robots()[0].arms()[0].gripper();
    let indices = [0, 0, 1, 1, 2, 2, 3, 3, 4, 4, 5];
    let m = env.sim().model();
    for (&id, &i) in g.actuators().iter().zip(&indices) {
        let [lo, hi] = m.actuator_ctrlrange()[id];
        let want = hand_action[i].clamp(lo, hi);
        assert_eq!(env.sim().data().ctrl()[id], want, "actuator {id}");
    }
}

/// GR1FixedLowerBody's default composite controller is robosuite's `WHOLE_BODY_MINK_IK`
/// (robosuite itself fails without `mink`): a typed error naming it; robosuite's BASIC and
/// WHOLE_BODY_IK configs serve the robot with robosuite's action sizes.
#[test]
fn gr1_fixed_lower_body_serves_basic_and_whole_body_ik_and_refuses_mink() {
    match make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["GR1FixedLowerBody"]),
    ) {
        Err(Error::Unsupported(reason)) => {
            let reason = reason.to_string();
            assert!(reason.contains("mink"), "{reason}");
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    for (controller, dim) in [("BASIC", 30), ("WHOLE_BODY_IK", 24)] {
        let config = crate::common::with_composite_controller(
            EnvConfig::default().with_robots(["GR1FixedLowerBody"]),
            controller,
            "GR1FixedLowerBody",
        );
        let mut env = make_with("TwoArmLift", config).unwrap();
        assert_eq!(env.action_dim(), dim, "{controller}");
        env.reset(Some(2), None).unwrap();
        let _ = env.step(&act(vec![0.1; dim])).unwrap();
    }
}

/// An IK target far out of reach moves the arms as far as the IK's step limits let them,
/// every joint stays finite; a non-finite action is refused with nothing simulated.
#[test]
fn unreachable_ik_targets_stay_finite_and_non_finite_actions_are_refused() {
    let mut env = gr1("GR1");
    env.reset(Some(3), None).unwrap();
    let right = slot(&env, "right");
    let mut a = vec![0.0; env.action_dim()];
    a[right.start] = 50.0;
    a[right.start + 2] = -30.0;
    for _ in 0..5 {
        let _ = env.step(&act(a.clone())).unwrap();
    }
    assert!(env.get_state().iter().all(|x| x.is_finite()));
    let before = env.get_state();
    a[right.start + 1] = f64::NAN;
    assert!(matches!(
        env.step(&act(a)),
        Err(Error::InvalidAction { .. })
    ));
    assert_eq!(env.get_state(), before);
}
