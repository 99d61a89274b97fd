//! Every arm controller against robosuite 1.5.2 itself: the recorded free-motion rollouts of
//! `tests/fixtures/robosuite/controllers/ROBOT.json` (see `scripts/record_controllers.py`;
//! every controller and mode on the Panda, every controller on the Sawyer and the 6-joint
//! UR5e), replayed from the recorded reset state with the recorded actions.
//!
//! Tolerance: the arm's joints within 1e-5 rad, the grip site within 1e-5 m and the finger
//! joints within 1e-5 at every one of the 60 steps, or, where robosuite itself run on MuJoCo
//! 3.17.0 already differs from its 3.3.7 recording by more (the case's `floor`, measured by
//! `record_controllers.py --floor`: the UR5e's Robotiq gripper, a closed linkage, differs
//! by up to 0.12 rad, which moves the arm by a few 1e-5), that floor plus 10 %. The action
//! bounds equal robosuite's `action_spec`.

use crate::common::fixtures::values;
use gym_core::Env;
use ndarray::{Array1, ArrayD};
use robosuite_env::controllers::ControllerConfig;
use robosuite_env::{EnvConfig, make_with};
use serde::Deserialize;
use serde_json::Value;

const TOL: f64 = 1e-5;

#[derive(Deserialize)]
struct Fixture {
    robot: String,
    joints: usize,
    cases: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    name: String,
    config: Value,
    action_low: Vec<f64>,
    action_high: Vec<f64>,
    task_state: Vec<f64>,
    init_state: Vec<f64>,
    actions: Vec<Vec<f64>>,
    steps: Vec<Step>,
    floor: Floor,
}

/// How far robosuite on MuJoCo 3.17.0 is from its own 3.3.7 recording.
#[derive(Deserialize)]
struct Floor {
    joint_pos: f64,
    eef_pos: f64,
    gripper_qpos: f64,
}

fn tolerance(floor: f64) -> f64 {
    TOL.max(1.1 * floor)
}

#[derive(Deserialize)]
struct Step {
    joint_pos: Vec<f64>,
    eef_pos: Vec<f64>,
    gripper_qpos: Vec<f64>,
}

fn load(robot: &str) -> Fixture {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join(format!("tests/fixtures/robosuite/controllers/{robot}.json"));
    let text = std::fs::read_to_string(&path).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The largest joint and grip-site errors over a case's rollout.
fn replay(robot: &str, case: &Case) -> (f64, f64, f64) {
    let config = ControllerConfig::from_value(&case.config, "controller_configs").unwrap();
    let mut env = make_with(
        "Lift",
        EnvConfig::default()
            .with_robots([robot])
            .with_controller(config),
    )
    .unwrap();
    let space = env.action_space();
    assert_eq!(
        space.low().iter().copied().collect::<Vec<_>>(),
        case.action_low,
        "{robot} {}: action low",
        case.name
    );
    assert_eq!(
        space.high().iter().copied().collect::<Vec<_>>(),
        case.action_high,
        "{robot} {}: action high",
        case.name
    );
    env.reset_to_state(&case.task_state, &case.init_state)
        .unwrap();
    let (mut joints, mut eef, mut grip) = (0.0f64, 0.0f64, 0.0f64);
    for (a, want) in case.actions.iter().zip(&case.steps) {
        let action: ArrayD<f64> = Array1::from(a.clone()).into_dyn();
        let step = env.step(&action).unwrap();
        let obs = &step.observation;
        joints = joints.max(max_diff(&values(obs, "robot0_joint_pos"), &want.joint_pos));
        eef = eef.max(max_diff(&values(obs, "robot0_eef_pos"), &want.eef_pos));
        grip = grip.max(max_diff(
            &values(obs, "robot0_gripper_qpos"),
            &want.gripper_qpos,
        ));
    }
    (joints, eef, grip)
}

fn check_robot(robot: &str) {
    let fixture = load(robot);
    assert_eq!(fixture.robot, robot);
    let mut names = Vec::new();
    for case in &fixture.cases {
        let (joints, eef, grip) = replay(robot, case);
        let f = &case.floor;
        if std::env::var_os("REPLAY_REPORT").is_some() {
            println!(
                "{robot} {:<26} joints {joints:.2e} rad (floor {:.2e}), grip site {eef:.2e} m ({:.2e}), fingers {grip:.2e} ({:.2e})",
                case.name, f.joint_pos, f.eef_pos, f.gripper_qpos
            );
        }
        assert!(
            joints <= tolerance(f.joint_pos)
                && eef <= tolerance(f.eef_pos)
                && grip <= tolerance(f.gripper_qpos),
            "{robot} {}: joints {joints:e}, grip site {eef:e}, fingers {grip:e}",
            case.name
        );
        names.push(case.name.split(' ').next().unwrap_or_default().to_owned());
    }
    // Every controller is covered on every recorded robot.
    for kind in robosuite_env::controllers::config::ARM_CONTROLLER_TYPES {
        assert!(names.iter().any(|n| n == kind), "{robot}: no {kind} case");
    }
    assert!(fixture.joints >= 6);
}

#[test]
fn panda_controllers_replay_robosuite() {
    check_robot("Panda");
}

#[test]
fn sawyer_controllers_replay_robosuite() {
    check_robot("Sawyer");
}

#[test]
fn ur5e_controllers_replay_robosuite() {
    check_robot("UR5e");
}
