//! robosuite 1.5's legged robots (`SpotWithArm`, `SpotWithArmFloating`) on the robot core:
//! the leg bases' composition, their body parts and controllers, the leg rest posture, the
//! base observables and typed errors.

use crate::common::{act, assert_action_refused};
use gym_core::{Env, Error};
use robosuite_env::controllers::ControllerConfig;
use robosuite_env::models::bases::SPOT_LEGS_INIT_QPOS;
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

const BASE_KEYS: [&str; 5] = [
    "robot0_base_pos",
    "robot0_base_quat",
    "robot0_base_to_eef_pos",
    "robot0_base_to_eef_quat",
    "robot0_base_to_eef_quat_site",
];

#[test]
fn spot_with_arm_stands_on_its_legs_with_robosuites_layout() {
    let mut env = make_with("Lift", EnvConfig::default().with_robots(["SpotWithArm"])).unwrap();
    let robot = &env.robots()[0];
    assert_eq!(robot.kind(), RobotKind::Legged);
    assert_eq!(robot.composite_controller().name(), "BASIC");
    let parts: Vec<&str> = robot.body_parts().iter().map(|b| b.name()).collect();
    assert_eq!(parts, ["legs"]);
    assert_eq!(
        slots(&env),
        [
            ("right".into(), 6),
            ("legs".into(), 12),
            ("right_gripper".into(), 1)
        ]
    );
    assert_eq!(env.action_dim(), 19);
    let f = env.sim().model().ffi();
    assert_eq!((f.nq, f.nbody, f.ngeom, f.nu), (33, 37, 80, 19));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    for key in BASE_KEYS {
        assert!(obs.get(key).is_some(), "{key}");
    }
    // robosuite's `LeggedRobot.reset`: the legs start at Spot's rest posture.
    let legs = env.robots()[0].body_part("legs").unwrap();
    let qpos: Vec<f64> = legs
        .qpos()
        .iter()
        .map(|&a| env.sim().data().qpos()[a])
        .collect();
    assert_eq!(qpos, SPOT_LEGS_INIT_QPOS);
    // A leg action moves the legs' joints away from where zero actions hold them.
    let run = |a: Vec<f64>| {
        let mut env = make_with("Lift", EnvConfig::default().with_robots(["SpotWithArm"])).unwrap();
        env.reset(Some(0), None).unwrap();
        for _ in 0..5 {
            let _ = env.step(&act(a.clone())).unwrap();
        }
        let legs = env.robots()[0].body_part("legs").unwrap().qpos().to_vec();
        legs.iter()
            .map(|&a| env.sim().data().qpos()[a])
            .collect::<Vec<_>>()
    };
    let still = run(vec![0.0; 19]);
    let mut bend = vec![0.0; 19];
    bend[6 + 2] = 1.0; // the front right knee
    let bent = run(bend);
    assert!(bent[2] - still[2] > 0.05, "{still:?} -> {bent:?}");
}

#[test]
fn spot_with_arm_floating_drives_its_base() {
    let mut env = make_with(
        "Lift",
        EnvConfig::default().with_robots(["SpotWithArmFloating"]),
    )
    .unwrap();
    let robot = &env.robots()[0];
    assert_eq!(robot.kind(), RobotKind::Legged);
    let parts: Vec<&str> = robot.body_parts().iter().map(|b| b.name()).collect();
    assert_eq!(parts, ["base"]);
    assert_eq!(
        slots(&env),
        [
            ("right".into(), 6),
            ("base".into(), 3),
            ("right_gripper".into(), 1)
        ]
    );
    // basic.json's left arm, torso, head and legs are dropped, as robosuite drops them.
    assert_eq!(env.action_dim(), 10);
    let f = env.sim().model().ffi();
    assert_eq!((f.nq, f.nbody, f.ngeom, f.nu), (17, 37, 80, 10));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    for key in BASE_KEYS {
        assert!(obs.get(key).is_some(), "{key}");
    }
    let site = env.robots()[0].base_site().unwrap();
    let start = env.sim().data().site_xpos()[site];
    let mut a = vec![0.0; 10];
    a[6] = 1.0; // forward
    for _ in 0..10 {
        let _ = env.step(&act(a.clone())).unwrap();
    }
    let end = env.sim().data().site_xpos()[site];
    let moved = (end[0] - start[0]).hypot(end[1] - start[1]);
    assert!(moved > 0.05, "{start:?} -> {end:?}");
}

#[test]
fn bad_leg_configs_and_actions_give_typed_errors() {
    let config = |value: serde_json::Value| {
        EnvConfig::default()
            .with_robots(["SpotWithArm"])
            .with_controller_configs([
                ControllerConfig::from_value(&value, "controller_configs").unwrap()
            ])
    };
    let osc = json!({"type": "OSC_POSE", "gripper": {"type": "GRIP"}});
    // The legs without a config: robosuite asserts; a typed error naming them here.
    match make_with(
        "Lift",
        config(json!({"type": "BASIC", "body_parts": {"right": osc}})),
    ) {
        Err(Error::InvalidArgument { name, reason }) => {
            assert_eq!(name, "controller_configs.body_parts");
            assert!(reason.contains("`legs`"), "{reason}");
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    // A part Spot lacks (a base): dropped, as robosuite drops it with a warning.
    let mut env = make_with(
        "Lift",
        config(json!({"type": "BASIC", "body_parts": {
            "right": osc, "legs": {"type": "JOINT_POSITION"},
            "base": {"type": "JOINT_VELOCITY"}}})),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 19);
    // A non-finite leg action: refused, nothing simulated.
    env.reset(Some(1), None).unwrap();
    for bad in [f64::NAN, f64::INFINITY] {
        let mut a = vec![0.0; 19];
        a[10] = bad;
        assert_action_refused(&mut env, a);
    }
    // A non-finite floating-base action likewise.
    let mut env = make_with(
        "Lift",
        EnvConfig::default().with_robots(["SpotWithArmFloating"]),
    )
    .unwrap();
    env.reset(Some(1), None).unwrap();
    let mut a = vec![0.0; 10];
    a[7] = f64::NEG_INFINITY;
    assert_action_refused(&mut env, a);
}

#[test]
fn two_spots_share_a_two_arm_task_as_robosuite_allows() {
    // Leg bases are prefixed per robot (`leg0_`, `leg1_`): two compile, in robosuite too.
    let env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["SpotWithArm", "SpotWithArmFloating"]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 19 + 10);
    let env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["PandaOmron", "SpotWithArm"]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 12 + 19);
}
