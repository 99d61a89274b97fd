//! Every registered task against the workspace's Gymnasium `check_env` mirror and its
//! property suite.

use conformance_tests::prop::{FnStateHook, prop_check_env_with_state};
use conformance_tests::{CheckOptions, EpisodeEndSpec, PropConfig, check_env};
use robosuite_env::{ENV_NAMES, EnvConfig, EnvSnapshot, RobosuiteEnv, make_with};

fn env(name: &str, horizon: u64) -> RobosuiteEnv {
    make_with(name, EnvConfig::default().with_horizon(horizon))
        .unwrap_or_else(|e| panic!("{name} builds: {e}"))
}

fn passes_check_env(name: &str) {
    let mut env = env(name, 30);
    let report =
        check_env(&mut env, &CheckOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(
        report.passed(conformance_tests::Check::ResetSeedDeterminism),
        "{name}"
    );
    assert!(
        report.passed(conformance_tests::Check::InvalidAction),
        "{name}"
    );
    assert!(
        report.passed(conformance_tests::Check::StepAfterEnd),
        "{name}"
    );
}

fn passes_the_property_suite(name: &str) {
    let config = PropConfig::cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(8),
        // Only Wipe ends early (arm contact, joint limit, everything wiped).
        can_terminate: name == "Wipe",
    });
    let hook = FnStateHook::new(
        |env: &RobosuiteEnv| -> gym_core::Result<EnvSnapshot> { Ok(env.snapshot()) },
        |env: &mut RobosuiteEnv, s: &EnvSnapshot| env.restore(s),
    );
    let report = prop_check_env_with_state(|| env(name, 8), &hook, &config)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert!(report.skipped.is_empty(), "{name}: {:?}", report.skipped);
}

#[test]
fn lift_passes_check_env() {
    passes_check_env("Lift");
}

#[test]
fn lift_passes_the_property_suite() {
    passes_the_property_suite("Lift");
}

/// One `check_env` test and one property-suite test per task, so the test harness runs
/// them in parallel.
macro_rules! task_tests {
    ($($check:ident, $prop:ident => $name:literal;)*) => {
        $(
            #[test]
            fn $check() {
                passes_check_env($name);
            }

            #[test]
            fn $prop() {
                passes_the_property_suite($name);
            }
        )*

        #[test]
        fn every_registered_task_is_covered() {
            let covered = ["Lift", $($name),*];
            for name in ENV_NAMES {
                assert!(covered.contains(name), "{name} has no conformance test");
            }
        }
    };
}

task_tests! {
    stack_passes_check_env, stack_passes_the_property_suite => "Stack";
    door_passes_check_env, door_passes_the_property_suite => "Door";
    wipe_passes_check_env, wipe_passes_the_property_suite => "Wipe";
    tool_hang_passes_check_env, tool_hang_passes_the_property_suite => "ToolHang";
    pick_place_passes_check_env, pick_place_passes_the_property_suite => "PickPlace";
    pick_place_single_passes_check_env, pick_place_single_passes_the_property_suite => "PickPlaceSingle";
    pick_place_milk_passes_check_env, pick_place_milk_passes_the_property_suite => "PickPlaceMilk";
    pick_place_bread_passes_check_env, pick_place_bread_passes_the_property_suite => "PickPlaceBread";
    pick_place_cereal_passes_check_env, pick_place_cereal_passes_the_property_suite => "PickPlaceCereal";
    pick_place_can_passes_check_env, pick_place_can_passes_the_property_suite => "PickPlaceCan";
    nut_assembly_passes_check_env, nut_assembly_passes_the_property_suite => "NutAssembly";
    nut_assembly_single_passes_check_env, nut_assembly_single_passes_the_property_suite => "NutAssemblySingle";
    nut_assembly_square_passes_check_env, nut_assembly_square_passes_the_property_suite => "NutAssemblySquare";
    nut_assembly_round_passes_check_env, nut_assembly_round_passes_the_property_suite => "NutAssemblyRound";
    two_arm_lift_passes_check_env, two_arm_lift_passes_the_property_suite => "TwoArmLift";
    two_arm_peg_in_hole_passes_check_env, two_arm_peg_in_hole_passes_the_property_suite => "TwoArmPegInHole";
    two_arm_handover_passes_check_env, two_arm_handover_passes_the_property_suite => "TwoArmHandover";
    two_arm_transport_passes_check_env, two_arm_transport_passes_the_property_suite => "TwoArmTransport";
}

#[test]
fn every_task_reports_success_in_info() {
    use gym_core::Env;
    for name in ENV_NAMES {
        let mut e = env(name, 5);
        let (_, info) = e.reset(Some(0), None).unwrap();
        assert_eq!(info.get_bool("success"), Some(false), "{name}");
        let a = ndarray::ArrayD::zeros(ndarray::IxDyn(&[e.action_dim()]));
        let step = e.step(&a).unwrap();
        assert_eq!(step.info.get_bool("success"), Some(false), "{name}");
    }
}

/// Every task on `robot` against `check_env` (its own default gripper and controller; the
/// two-arm tasks with two of it, `opposed`, or a bimanual robot alone).
fn every_task_on(robot: &str) {
    let info = robosuite_env::models::robots::robot_info(robot).unwrap();
    for name in ENV_NAMES {
        let count = if info.arms.len() == 2 {
            1
        } else {
            robosuite_env::make_task(name)
                .unwrap()
                .robots()
                .num_robots()
        };
        // Two wheeled robots cannot share a scene (robosuite fails on it): a wheeled robot
        // takes a Panda as its partner. Two legged robots share one, as in robosuite.
        let mobile = info.kind == robosuite_env::models::robots::RobotKind::Wheeled;
        let mut robots = vec![robot; count];
        if mobile && count > 1 {
            robots[1..].fill("Panda");
        }
        let mut env = make_with(
            name,
            EnvConfig::default().with_horizon(30).with_robots(robots),
        )
        .unwrap_or_else(|e| panic!("{name} on {robot} builds: {e}"));
        assert_passes_check_env(&mut env, &format!("{name} on {robot}"));
    }
}

/// `check_env` with its default options passes on `env`, its seeding, action and
/// episode-end checks included.
fn assert_passes_check_env(env: &mut RobosuiteEnv, what: &str) {
    let report = check_env(env, &CheckOptions::default()).unwrap_or_else(|e| panic!("{what}: {e}"));
    for check in [
        conformance_tests::Check::ResetSeedDeterminism,
        conformance_tests::Check::InvalidAction,
        conformance_tests::Check::StepAfterEnd,
    ] {
        assert!(report.passed(check), "{what}: {check:?}");
    }
}

/// One test per robot other than the Panda (which the tests above cover), so they run in
/// parallel; the bimanual Baxter and Tiago alone on every task.
macro_rules! robot_tests {
    ($($test:ident => $robot:literal;)*) => {
        $(
            #[test]
            fn $test() {
                every_task_on($robot);
            }
        )*

        #[test]
        fn every_robot_is_covered() {
            let covered = ["Panda", $($robot),*];
            let covered: Vec<&str> = covered.iter().chain(GR1_ROBOTS).copied().collect();
            for robot in robosuite_env::models::robots::robot_names() {
                assert!(covered.contains(&robot), "{robot} has no conformance test");
            }
        }
    };
}

robot_tests! {
    every_task_on_sawyer_passes_check_env => "Sawyer";
    every_task_on_iiwa_passes_check_env => "IIWA";
    every_task_on_jaco_passes_check_env => "Jaco";
    every_task_on_kinova3_passes_check_env => "Kinova3";
    every_task_on_ur5e_passes_check_env => "UR5e";
    every_task_on_xarm7_passes_check_env => "XArm7";
    every_task_on_panda_omron_passes_check_env => "PandaOmron";
    every_task_on_spot_with_arm_passes_check_env => "SpotWithArm";
    every_task_on_spot_with_arm_floating_passes_check_env => "SpotWithArmFloating";
    every_task_on_panda_dex_rh_passes_check_env => "PandaDexRH";
    every_task_on_panda_dex_lh_passes_check_env => "PandaDexLH";
    every_task_on_baxter_passes_check_env => "Baxter";
    every_task_on_tiago_passes_check_env => "Tiago";
}

/// A GR1 humanoid alone on every task, with its default composite controller
/// (GR1FixedLowerBody, whose default `WHOLE_BODY_MINK_IK` is not served, with robosuite's
/// WHOLE_BODY_IK config). robosuite 1.5.2 makes, resets and steps every one of the 19 tasks
/// with each GR1 robot alone (the two-arm tasks with its two arms; Wipe and TwoArmPegInHole
/// without its hands), as recorded in observations.json's `TASK-GR1...` entries
/// (`scripts/record_robosuite.py --layouts --every-task --robot ROBOT`).
fn every_task_on_gr1(robot: &str) {
    let config = crate::common::gr1_config(robot).with_horizon(30);
    for task in ENV_NAMES {
        let what = format!("{task} on {robot}");
        let mut env = make_with(task, config.clone()).unwrap_or_else(|e| panic!("{what}: {e}"));
        assert_passes_check_env(&mut env, &what);
    }
}

#[test]
fn every_task_on_gr1_passes_check_env() {
    every_task_on_gr1("GR1");
}

#[test]
fn every_task_on_gr1_arms_only_passes_check_env() {
    every_task_on_gr1("GR1ArmsOnly");
}

#[test]
fn every_task_on_gr1_floating_body_passes_check_env() {
    every_task_on_gr1("GR1FloatingBody");
}

#[test]
fn every_task_on_gr1_fixed_lower_body_passes_check_env() {
    every_task_on_gr1("GR1FixedLowerBody");
}

/// A right-hand and a left-hand Panda with Inspire hands on a two-arm task (robosuite's
/// opposed set-up): check_env with the hands' six actions each.
#[test]
fn panda_dex_pair_on_two_arm_lift_passes_check_env() {
    let mut env = make_with(
        "TwoArmLift",
        EnvConfig::default()
            .with_horizon(30)
            .with_robots(["PandaDexRH", "PandaDexLH"]),
    )
    .unwrap();
    assert_eq!(env.action_dim(), 24);
    assert_passes_check_env(&mut env, "TwoArmLift on PandaDexRH and PandaDexLH");
}

/// The GR1 humanoids (`every_task_on_gr1_*`).
const GR1_ROBOTS: &[&str] = &["GR1", "GR1ArmsOnly", "GR1FloatingBody", "GR1FixedLowerBody"];
