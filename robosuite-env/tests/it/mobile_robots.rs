//! robosuite 1.5's mobile robots on the robot core: body parts and their controllers, the
//! composite controllers' action layouts, the base observables, typed errors and
//! snapshots.

use crate::common::{act, assert_action_refused, assert_snapshot_replays};
use gym_core::{Env, Error};
use robosuite_env::controllers::ControllerConfig;
use robosuite_env::models::robots::RobotKind;
use robosuite_env::{EnvConfig, make_with};
use serde_json::json;

fn slots(env: &robosuite_env::RobosuiteEnv) -> Vec<(String, usize)> {
    env.robots()[0]
        .action_layout()
        .iter()
        .map(|s| (s.name.clone(), s.range.len()))
        .collect()
}

#[test]
fn panda_omron_has_robosuites_parts_layout_and_keys() {
    let mut env = make_with("Lift", EnvConfig::default().with_robots(["PandaOmron"])).unwrap();
    let robot = &env.robots()[0];
    assert_eq!(robot.kind(), RobotKind::Wheeled);
    assert_eq!(robot.composite_controller().name(), "HYBRID_MOBILE_BASE");
    let parts: Vec<&str> = robot.body_parts().iter().map(|b| b.name()).collect();
    assert_eq!(parts, ["base", "torso"]);
    // robosuite: right 6, torso 1, base 3, right_gripper 1, then the base mode.
    assert_eq!(
        slots(&env),
        [
            ("right".into(), 6),
            ("torso".into(), 1),
            ("base".into(), 3),
            ("right_gripper".into(), 1)
        ]
    );
    assert_eq!(env.action_dim(), 12);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    for key in [
        "robot0_base_pos",
        "robot0_base_quat",
        "robot0_base_to_eef_pos",
        "robot0_base_to_eef_quat",
        "robot0_base_to_eef_quat_site",
    ] {
        assert!(obs.get(key).is_some(), "{key}");
    }
    // The torso starts at robosuite's init_torso_qpos.
    let torso = env.robots()[0].body_part("torso").unwrap().qpos()[0];
    assert_eq!(env.sim().data().qpos()[torso], 0.2);
    // Driving the base forward in base mode moves it, the arm's goal held.
    let mut a = vec![0.0; 12];
    a[7] = 1.0;
    a[11] = 1.0;
    let start = env.sim().data().site_xpos()[env.robots()[0].base_site().unwrap()];
    for _ in 0..10 {
        let _ = env.step(&act(a.clone())).unwrap();
    }
    let end = env.sim().data().site_xpos()[env.robots()[0].base_site().unwrap()];
    assert!(end[0] - start[0] > 0.05, "{start:?} -> {end:?}");
}

#[test]
fn tiago_has_robosuites_parts_and_layout() {
    let env = make_with("TwoArmLift", EnvConfig::default().with_robots(["Tiago"])).unwrap();
    let parts: Vec<&str> = env.robots()[0]
        .body_parts()
        .iter()
        .map(|b| b.name())
        .collect();
    assert_eq!(parts, ["base", "head", "torso"]);
    let names: Vec<String> = slots(&env).into_iter().map(|(n, _)| n).collect();
    assert_eq!(
        names,
        [
            "right",
            "left",
            "torso",
            "head",
            "base",
            "right_gripper",
            "left_gripper"
        ]
    );
    assert_eq!(env.action_dim(), 20);
}

#[test]
fn bad_configs_and_actions_give_typed_errors() {
    let config = |value: serde_json::Value| {
        EnvConfig::default()
            .with_robots(["PandaOmron"])
            .with_controller_configs([
                ControllerConfig::from_value(&value, "controller_configs").unwrap()
            ])
    };
    let osc = json!({"type": "OSC_POSE", "gripper": {"type": "GRIP"}});
    // A part the robot has without a config: robosuite fails; a typed error here.
    let no_base = config(json!({"type": "HYBRID_MOBILE_BASE", "body_parts": {
        "right": osc, "torso": {"type": "JOINT_POSITION"}}}));
    match make_with("Lift", no_base) {
        Err(Error::InvalidArgument { name, reason }) => {
            assert_eq!(name, "controller_configs.body_parts");
            assert!(reason.contains("`base`"), "{reason}");
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    // A part the robot lacks: dropped, as robosuite drops it (with a warning).
    let legs = config(json!({"type": "HYBRID_MOBILE_BASE", "body_parts": {
        "right": osc, "torso": {"type": "JOINT_POSITION"}, "base": {"type": "JOINT_VELOCITY"},
        "legs": {"type": "JOINT_POSITION"}}}));
    let mut env = make_with("Lift", legs).unwrap();
    assert_eq!(env.action_dim(), 12);
    // A non-finite base action: refused, nothing simulated.
    env.reset(Some(1), None).unwrap();
    let mut a = vec![0.0; 12];
    a[7] = f64::NAN;
    assert_action_refused(&mut env, a);
}

#[test]
fn a_snapshot_continues_a_mobile_episode_bit_identically() {
    let mut env = make_with("Lift", EnvConfig::default().with_robots(["PandaOmron"])).unwrap();
    env.reset(Some(3), None).unwrap();
    let action = |t: usize| {
        let mut a: Vec<f64> = (0..12).map(|i| ((t * 7 + i) as f64 * 0.37).sin()).collect();
        a[11] = if t.is_multiple_of(2) { 1.0 } else { -1.0 };
        act(a)
    };
    let actions: Vec<_> = (0..10).map(action).collect();
    assert_snapshot_replays(&mut env, &actions, 5);
}

#[test]
fn two_mobile_robots_are_refused_as_robosuite_cannot_compile_them() {
    match make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["PandaOmron", "PandaOmron"]),
    ) {
        Err(Error::InvalidArgument { name, reason }) => {
            assert_eq!(name, "robots");
            assert!(reason.contains("manipulator_mount"), "{reason}");
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    // One mobile robot beside a fixed-base one works.
    let env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["PandaOmron", "Panda"]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 12 + 7);
}
