//! robosuite's controller configurations as robosuite users write them: robosuite's own
//! JSON files parse verbatim, every controller is selectable on every robot with
//! robosuite's action layout, and bad configs are typed errors naming the key, raised when
//! the env is made.

use crate::common::get;
use gym_core::{Env, Error, Space};
use ndarray::{Array1, ArrayD};
use robosuite_env::assets::Assets;
use robosuite_env::controllers::config::{
    ARM_CONTROLLER_TYPES, CompositeControllerConfig, GripperConfig, JointPositionConfig, OscConfig,
    PerAxis, load_composite_controller_config, load_part_controller_config, robot_default,
};
use robosuite_env::controllers::{ArmControllerConfig, ArmPartConfig, ControllerConfig};
use robosuite_env::models::robots::single_arm_robot_names;
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};
use serde_json::{Value, json};

fn assets() -> Assets {
    Assets::locate().unwrap()
}

fn parse(value: Value) -> gym_core::Result<ControllerConfig> {
    ControllerConfig::from_value(&value, "controller_configs")
}

fn lift(robot: &str, config: ControllerConfig) -> gym_core::Result<RobosuiteEnv> {
    make_with(
        "Lift",
        EnvConfig::default()
            .with_robots([robot])
            .with_controller(config),
    )
}

fn invalid_key(result: gym_core::Result<impl std::fmt::Debug>) -> (String, String) {
    match result {
        Err(Error::InvalidArgument { name, reason }) => (name, reason),
        other => panic!("expected InvalidArgument, got {other:?}"),
    }
}

#[test]
fn robosuites_own_files_parse_verbatim() {
    let a = assets();
    // Every robot default robosuite ships for a fixed-base arm, and basic.json.
    for robot in ["Panda", "Sawyer", "IIWA", "Kinova3", "UR5e"] {
        let value = load_composite_controller_config(&a, None, Some(robot)).unwrap();
        let config = parse(value).unwrap();
        let ControllerConfig::Composite(c) = config else {
            panic!("{robot}: a composite config")
        };
        assert_eq!(c.arms.len(), 1, "{robot}");
        assert_eq!(c.arms[0].0, "right");
        assert_eq!(c.arms[0].1.controller.controller_type(), "OSC_POSE");
    }
    // Jaco and XArm7 have no file of their own: robosuite falls back to basic.json, which
    // names both arms and the parts of mobile robots.
    for robot in ["Jaco", "XArm7"] {
        let value = load_composite_controller_config(&a, None, Some(robot)).unwrap();
        let ControllerConfig::Composite(c) = parse(value).unwrap() else {
            panic!()
        };
        let sides: Vec<&str> = c.arms.iter().map(|(s, _)| s.as_str()).collect();
        assert_eq!(sides, ["right", "left"]);
        let parts: Vec<&str> = c.parts.iter().map(|(s, _)| s.as_str()).collect();
        assert_eq!(parts, ["torso", "head", "base", "legs"]);
        assert_eq!(c.order, ["right", "left", "torso", "head", "base", "legs"]);
        let fitted = c
            .fit_to(robot, &["right"], &[], "controller_configs")
            .unwrap();
        assert_eq!(fitted.arms.len(), 1);
        assert!(fitted.parts.is_empty());
        assert_eq!(fitted.order, ["right"]);
        assert_eq!(
            c.dropped_parts(&["right"], &[]),
            ["left", "torso", "head", "base", "legs"]
        );
    }
    let basic = load_composite_controller_config(&a, Some("BASIC"), None).unwrap();
    assert!(parse(basic).is_ok());
    // Every part file, as load_part_controller_config returns it.
    for kind in ARM_CONTROLLER_TYPES {
        let value = load_part_controller_config(&a, kind).unwrap();
        let ControllerConfig::Part(part) = parse(value).unwrap() else {
            panic!("{kind}: a part config")
        };
        assert_eq!(part.controller_type(), *kind);
    }
    // HYBRID_MOBILE_BASE parses; WHOLE_BODY_MINK_IK (robosuite's example on the `mink`
    // library) is refused as not served.
    let hybrid = load_composite_controller_config(&a, Some("HYBRID_MOBILE_BASE"), None).unwrap();
    let ControllerConfig::Composite(c) = parse(hybrid).unwrap() else {
        panic!("a composite config")
    };
    assert_eq!(c.kind, "HYBRID_MOBILE_BASE");
    let mink = load_composite_controller_config(&a, Some("WHOLE_BODY_MINK_IK"), None).unwrap();
    match parse(mink) {
        Err(e @ Error::Unsupported(_)) => assert!(e.to_string().contains("mink"), "{e}"),
        other => panic!("{other:?}"),
    }
    // A file robosuite does not have, and a controller it does not know.
    assert!(matches!(
        load_composite_controller_config(&a, Some("FANCY"), None),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        load_part_controller_config(&a, "OSC_POS"),
        Err(Error::InvalidArgument { .. })
    ));
}

#[test]
fn robosuites_default_values_reach_the_controller() {
    let a = assets();
    let ControllerConfig::Composite(c) =
        parse(load_composite_controller_config(&a, None, Some("Panda")).unwrap()).unwrap()
    else {
        panic!()
    };
    let ArmControllerConfig::OscPose(osc) = &c.arms[0].1.controller else {
        panic!()
    };
    assert_eq!(osc.kp, PerAxis::Scalar(150.0));
    assert_eq!(
        osc.output_max,
        Some(PerAxis::List(vec![0.05, 0.05, 0.05, 0.5, 0.5, 0.5]))
    );
    assert_eq!(c.arms[0].1.gripper, GripperConfig::default());
    assert_eq!(robot_default(&a, "Panda").unwrap(), c);
    // A key a config leaves out takes robosuite's constructor default.
    let ControllerConfig::Part(ArmControllerConfig::JointVelocity(jv)) =
        parse(json!({"type": "JOINT_VELOCITY"})).unwrap()
    else {
        panic!()
    };
    assert_eq!(jv.kp, PerAxis::Scalar(0.25));
    assert_eq!(jv.output_max, PerAxis::Scalar(1.0));
}

/// The arm controller's slice of the action for `kind` on an arm of `n` joints, with
/// robosuite's default part config.
fn arm_dim(kind: &str, n: usize) -> usize {
    match kind {
        "OSC_POSE" | "IK_POSE" => 6,
        "OSC_POSITION" => 3,
        _ => n,
    }
}

#[test]
fn every_controller_runs_on_every_robot_with_robosuites_layout() {
    let a = assets();
    for robot in single_arm_robot_names() {
        for kind in ARM_CONTROLLER_TYPES {
            let part = load_part_controller_config(&a, kind).unwrap();
            if robot == "SpotWithArmFloating" {
                // robosuite has no default_spotwitharmfloating.json: a part config becomes a
                // BASIC config of the arm alone, which robosuite fails to build; a typed
                // error naming the floating base here.
                let (name, reason) = invalid_key(lift(robot, parse(part).unwrap()));
                assert_eq!(name, "controller_configs.body_parts");
                assert!(reason.contains("`base`"), "{reason}");
                continue;
            }
            let mut env =
                lift(robot, parse(part).unwrap()).unwrap_or_else(|e| panic!("{robot} {kind}: {e}"));
            let arm = env.robots()[0].arm();
            let n = arm.joints().len();
            let grip = arm.gripper().action_dim();
            assert_eq!(arm.controller().name(), *kind);
            // A mobile robot's other parts keep their own controllers (and
            // HYBRID_MOBILE_BASE its base mode).
            let r = &env.robots()[0];
            let others: usize = r
                .body_parts()
                .iter()
                .map(|b| b.controller().action_dim())
                .sum::<usize>()
                + r.composite_controller().extra_limits().0.len();
            assert_eq!(
                env.action_space().shape(),
                Some(&[arm_dim(kind, n) + grip + others][..]),
                "{robot} {kind}"
            );
            // It runs: a few steps of mid-range actions keep the state finite.
            env.reset(Some(1), None).unwrap();
            let mut rng = gym_core::rng_from_seed(3);
            for _ in 0..5 {
                let action = env.action_space().sample(&mut rng);
                let step = env.step(&action).unwrap();
                assert!(
                    get(&step.observation, "robot0_joint_pos")
                        .iter()
                        .all(|v| v.is_finite())
                );
            }
        }
    }
}

#[test]
fn variable_impedance_adds_the_gains_to_the_action() {
    let osc = |mode: &str| json!({"type": "OSC_POSE", "impedance_mode": mode, "kp_limits": [10, 200], "damping_ratio_limits": [0, 4]});
    let env = lift("Panda", parse(osc("variable")).unwrap()).unwrap();
    let space = env.action_space();
    assert_eq!(space.shape(), Some(&[19][..]));
    assert_eq!(
        space.low().as_slice().unwrap()[..12],
        [[0.0; 6], [10.0; 6]].concat()[..]
    );
    assert_eq!(
        space.high().as_slice().unwrap()[..12],
        [[4.0; 6], [200.0; 6]].concat()[..]
    );
    let env = lift("Panda", parse(osc("variable_kp")).unwrap()).unwrap();
    assert_eq!(env.action_space().shape(), Some(&[13][..]));
    let jp = json!({"type": "JOINT_POSITION", "impedance_mode": "variable"});
    let env = lift("UR5e", parse(jp).unwrap()).unwrap();
    assert_eq!(env.action_space().shape(), Some(&[3 * 6 + 1][..]));
    let ik = lift("Panda", parse(json!({"type": "IK_POSE"})).unwrap()).unwrap();
    assert_eq!(
        ik.action_space().high().as_slice().unwrap()[..6],
        [0.02, 0.02, 0.02, 0.05, 0.05, 0.05]
    );
}

#[test]
fn the_issue_example_basic_config_works_on_a_single_arm_robot() {
    // robosuite.load_composite_controller_config(controller="BASIC", robot="Panda").
    let value = load_composite_controller_config(&assets(), Some("BASIC"), Some("Panda")).unwrap();
    let mut env = lift("Panda", parse(value.clone()).unwrap()).unwrap();
    assert_eq!(env.action_space().shape(), Some(&[7][..]));
    env.reset(Some(0), None).unwrap();
    // The same through the keyword path (robosuite's dict, as the Python package passes it).
    let kwargs = serde_json::json!({ "controller_configs": value });
    let config = EnvConfig::from_kwargs("Lift", kwargs.as_object().unwrap()).unwrap();
    assert!(make_with("Lift", config).is_ok());
    // And by controller name.
    let kwargs = serde_json::json!({"controller": "JOINT_VELOCITY"});
    let config = EnvConfig::from_kwargs("Lift", kwargs.as_object().unwrap()).unwrap();
    let env = make_with("Lift", config).unwrap();
    assert_eq!(env.robots()[0].arm().controller().name(), "JOINT_VELOCITY");
}

#[test]
fn bad_configs_are_typed_errors_naming_the_key() {
    // An unknown controller type lists the valid ones.
    let (name, reason) = invalid_key(parse(
        json!({"type": "BASIC", "body_parts": {"right": {"type": "OSC_POS"}}}),
    ));
    assert_eq!(name, "controller_configs.body_parts.right.type");
    assert!(
        reason.contains("OSC_POSE") && reason.contains("JOINT_TORQUE"),
        "{reason}"
    );
    let (name, _) = invalid_key(parse(json!({"type": "JOINT_SPEED"})));
    assert_eq!(name, "controller_configs.type");
    // Keys robosuite's controllers ignore (they take `**kwargs`) are ignored here too, and
    // listed so that a caller can warn; a misspelt key thus leaves the default.
    let odd = json!({"type": "OSC_POSE", "kpp": 100, "damping_limits": [0, 10]});
    assert_eq!(
        parse(odd.clone()).unwrap(),
        parse(json!({"type": "OSC_POSE"})).unwrap()
    );
    assert_eq!(
        robosuite_env::controllers::config::ignored_keys(&odd),
        ["kpp", "damping_limits"]
    );
    let composite = json!({"type": "BASIC", "body_parts": {
        "right": {"type": "JOINT_VELOCITY", "uncouple_pos_ori": true, "input_max": 1},
        "arms": {"left": {"type": "OSC_POSE", "qpos_limits": null}}}});
    assert_eq!(
        robosuite_env::controllers::config::ignored_keys(&composite),
        [
            "body_parts.right.uncouple_pos_ori",
            "body_parts.arms.left.qpos_limits"
        ]
    );
    match parse(json!({"type": "BASIC", "body_parts": {"arms": {"rigth": {"type": "OSC_POSE"}}}})) {
        Err(Error::UnknownKey { key, available }) => {
            assert_eq!(key, "controller_configs.body_parts.arms.rigth");
            assert!(available.iter().any(|k| k == "right"));
        }
        other => panic!("{other:?}"),
    }
    // Ill-typed values name the key.
    let (name, reason) = invalid_key(parse(json!({"type": "OSC_POSE", "kp": "high"})));
    assert_eq!(name, "controller_configs.kp");
    assert!(reason.contains("number"), "{reason}");
    let (name, reason) = invalid_key(parse(
        json!({"type": "OSC_POSE", "impedance_mode": "stiff"}),
    ));
    assert_eq!(name, "controller_configs.impedance_mode");
    assert!(reason.contains("variable_kp"), "{reason}");
    let (name, _) = invalid_key(parse(json!({"type": "OSC_POSE", "interpolation": "cubic"})));
    assert_eq!(name, "controller_configs.interpolation");
    let (name, _) = invalid_key(parse(
        json!({"type": "BASIC", "body_parts": {"right": {"type": "OSC_POSE", "gripper": {"type": "JOINT_POSITION"}}}}),
    ));
    assert_eq!(name, "controller_configs.body_parts.right.gripper.type");
    assert!(matches!(
        parse(json!({"type": "WHOLE_BODY_MINK_IK", "body_parts": {}})),
        Err(Error::Unsupported(_))
    ));
    // A part given a controller robosuite's factory refuses for it.
    let (name, reason) = invalid_key(parse(
        json!({"type": "BASIC", "body_parts": {"base": {"type": "JOINT_POSITION"}}}),
    ));
    assert_eq!(name, "controller_configs.body_parts.base.type");
    assert!(reason.contains("JOINT_VELOCITY"), "{reason}");

    // Values out of range or not fitting the robot: errors when the env is made.
    let osc = |c: OscConfig| ControllerConfig::Part(ArmControllerConfig::OscPose(c));
    for (bad, key) in [
        (OscConfig::default().with_kp(f64::NAN), "kp"),
        (OscConfig::default().with_kp(-1.0), "kp"),
        (
            OscConfig::default().with_damping_ratio(-0.5),
            "damping_ratio",
        ),
        (
            OscConfig {
                kp: PerAxis::List(vec![150.0; 7]),
                ..OscConfig::default()
            },
            "kp",
        ),
        (
            OscConfig {
                input_max: PerAxis::Scalar(-1.0),
                ..OscConfig::default()
            },
            "input_min/input_max",
        ),
        (
            OscConfig {
                ramp_ratio: 0.0,
                ..OscConfig::default()
                    .with_interpolation(robosuite_env::controllers::config::Interpolation::Linear)
            },
            "ramp_ratio",
        ),
        (
            OscConfig {
                position_limits: Some(robosuite_env::controllers::config::Bounds::uniform(
                    1.0, -1.0,
                )),
                ..OscConfig::default()
            },
            "position_limits",
        ),
    ] {
        let (name, _) = invalid_key(lift("Panda", osc(bad)));
        assert_eq!(name, format!("controller_configs.body_parts.right.{key}"));
    }
    // A joint-space list sized for 7 joints on the 6-joint UR5e.
    let jp = ControllerConfig::Part(ArmControllerConfig::JointPosition(JointPositionConfig {
        kp: PerAxis::List(vec![50.0; 7]),
        ..JointPositionConfig::default()
    }));
    assert!(lift("Panda", jp.clone()).is_ok());
    let (name, reason) = invalid_key(lift("UR5e", jp));
    assert_eq!(name, "controller_configs.body_parts.right.kp");
    assert!(reason.contains("list of 6"), "{reason}");
    // Absolute joint targets need fixed impedance, as robosuite asserts.
    let (name, _) = invalid_key(lift(
        "Panda",
        parse(json!({"type": "JOINT_POSITION", "input_type": "absolute", "impedance_mode": "variable"})).unwrap(),
    ));
    assert_eq!(name, "controller_configs.body_parts.right.input_type");
    // A config that gives no controller to the robot's arm.
    let mut left_only = CompositeControllerConfig::default();
    left_only.set_arm("left", ArmPartConfig::default());
    let left_only = ControllerConfig::Composite(left_only);
    let (name, reason) = invalid_key(lift("Panda", left_only));
    assert_eq!(name, "controller_configs.body_parts");
    assert!(reason.contains("`right` arm"), "{reason}");
    // A composite controller for mobile robots on a fixed-base arm.
    let mut hybrid = CompositeControllerConfig::single_arm(ArmPartConfig::default());
    hybrid.kind = "HYBRID_MOBILE_BASE".into();
    let (name, reason) = invalid_key(lift("Panda", ControllerConfig::Composite(hybrid)));
    assert_eq!(name, "controller_configs.type");
    assert!(
        reason.contains("FixedBaseRobot") && reason.contains("BASIC"),
        "{reason}"
    );
    // One config per robot, or one for all.
    let two = EnvConfig::default().with_controller_configs([
        ControllerConfig::Part(ArmControllerConfig::default()),
        ControllerConfig::Part(ArmControllerConfig::default()),
    ]);
    assert!(matches!(
        make_with("Lift", two),
        Err(Error::InvalidArgument { .. })
    ));
    // Keyword errors: not a dict, an unknown controller name.
    let kwargs = |v: serde_json::Value| EnvConfig::from_kwargs("Lift", v.as_object().unwrap());
    assert!(matches!(
        kwargs(serde_json::json!({"controller_configs": "{type: OSC"})),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        kwargs(serde_json::json!({"controller": "OSC"})),
        Err(Error::InvalidArgument { .. })
    ));
}

#[test]
fn no_bad_config_reaches_a_step() {
    // Configs robosuite accepts and that stress the controllers still step finitely.
    let wild = json!({"type": "OSC_POSE", "impedance_mode": "variable", "kp_limits": [0, 300], "damping_ratio_limits": [0, 100]});
    let mut env = lift("Panda", parse(wild).unwrap()).unwrap();
    env.reset(Some(0), None).unwrap();
    let mut extreme = vec![100.0; 6];
    extreme.extend([300.0; 6]);
    extreme.extend([1.0, -1.0, 1.0, 1.0, -1.0, 1.0, 1.0]);
    let action: ArrayD<f64> = Array1::from(extreme).into_dyn();
    for _ in 0..20 {
        let step = env.step(&action).unwrap();
        assert!(
            get(&step.observation, "robot0_eef_pos")
                .iter()
                .all(|v| v.is_finite())
        );
    }
}

#[test]
fn gripper_without_action_scaling_writes_the_command() {
    let config =
        ControllerConfig::Composite(CompositeControllerConfig::single_arm(ArmPartConfig {
            controller: ArmControllerConfig::default(),
            gripper: GripperConfig {
                use_action_scaling: false,
            },
        }));
    let mut env = lift("Panda", config).unwrap();
    env.reset(Some(0), None).unwrap();
    let mut a = vec![0.0; 7];
    a[6] = -1.0; // open: the Panda's command moves toward [1, -1]
    let action: ArrayD<f64> = Array1::from(a).into_dyn();
    let _ = env.step(&action).unwrap();
    let ctrl = env.sim().data().ctrl();
    let acts = env.robots()[0]
        .arm()
        .gripper()
        .controller()
        .command()
        .to_vec();
    // Unscaled, the commands ±0.2 are the targets, clipped to the ctrlrange [0, 0.04] /
    // [-0.04, 0].
    assert_eq!(acts, [0.2, -0.2]);
    assert_eq!(&ctrl[7..9], &[0.04, -0.04]);
}

#[test]
fn robosuites_broken_setups_work_here() {
    // robosuite's recorded drift under zero actions (20 steps) against ours.
    let fixture: Value = serde_json::from_str(
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("tests/fixtures/robosuite/controllers/Panda.json"),
        )
        .unwrap(),
    )
    .unwrap();
    let drift = &fixture["robosuite_zero_action_drift"];
    for (name, config) in [
        ("IK_POSE", json!({"type": "IK_POSE"})),
        (
            "OSC_POSE linear base",
            json!({"type": "OSC_POSE", "interpolation": "linear"}),
        ),
    ] {
        let theirs = drift[name].as_f64().unwrap();
        let mut env = lift("Panda", parse(config).unwrap()).unwrap();
        let (obs, _) = env.reset(Some(5), None).unwrap();
        let p0 = get(&obs, "robot0_eef_pos");
        let zero: ArrayD<f64> = Array1::zeros(7).into_dyn();
        let mut p = p0.clone();
        for _ in 0..20 {
            p = get(&env.step(&zero).unwrap().observation, "robot0_eef_pos");
        }
        let ours = p
            .iter()
            .zip(&p0)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        assert!(theirs > 0.3, "{name}: robosuite moves {theirs} m");
        assert!(ours < 2e-3, "{name}: ours moves {ours} m");
    }
    // JOINT_TORQUE with robosuite's defaults (±0.1 N·m) does not move the arm, as in
    // robosuite: the torques stay below the joints' friction loss.
    let frictionloss = {
        let env = lift("Panda", parse(json!({"type": "JOINT_TORQUE"})).unwrap()).unwrap();
        let dofs = env.robots()[0].joint_dofs()[..7].to_vec();
        dofs.iter()
            .map(|&d| env.sim().model().dof_frictionloss()[d])
            .fold(f64::INFINITY, f64::min)
    };
    assert!(frictionloss >= 0.1, "{frictionloss}");
}
