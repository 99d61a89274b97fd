//! Every task's observation layout against robosuite's (`fixtures/robosuite/observations.json`):
//! keys in order, shapes, dtypes and the action dimension.

use crate::common::fixtures::{ObsEntry, robosuite_action_dim, robosuite_observations};
use crate::common::{assert_observation_layout, gr1_config};
use gym_core::Env;
use robosuite_env::{ENV_NAMES, EnvConfig, EnvConfiguration, make_with};

/// The keys of the single-object mode 1 variants: robosuite names them after the object
/// drawn at each reset (recorded: one of them), this crate's fixed observation space after
/// the task's single-object prefix (`nut_*`, `obj_*`); shapes and dtypes are the same.
fn with_single_object_prefix(task: &str, mut expected: Vec<ObsEntry>) -> Vec<ObsEntry> {
    let prefix = match task {
        "NutAssemblySingle" => "nut",
        "PickPlaceSingle" => "obj",
        _ => return expected,
    };
    let drawn = expected
        .iter()
        .find_map(|(k, _, _)| {
            k.strip_suffix("_to_robot0_eef_pos")
                .or_else(|| k.strip_suffix("_to_robot0_right_eef_pos"))
        })
        .expect("an object's relative position")
        .to_owned();
    for (key, _, _) in &mut expected {
        if let Some(rest) = key.strip_prefix(&format!("{drawn}_")) {
            *key = format!("{prefix}_{rest}");
        }
    }
    expected
}

#[test]
fn every_task_lays_out_its_observations_as_robosuite() {
    for &task in ENV_NAMES {
        let expected = with_single_object_prefix(task, robosuite_observations(task));
        // The two-arm tasks were recorded `opposed`; `parallel` lays out the same keys.
        let configs = if task.starts_with("TwoArm") {
            [EnvConfiguration::Opposed, EnvConfiguration::Parallel]
                .map(|c| {
                    EnvConfig::default()
                        .with_robots(["Panda", "Panda"])
                        .with_env_configuration(c)
                })
                .to_vec()
        } else {
            vec![EnvConfig::default()]
        };
        for config in configs {
            let what = format!("{task} {}", config.env_configuration.as_str());
            let mut env = make_with(task, config).unwrap_or_else(|e| panic!("{what}: {e}"));
            let (obs, _) = env.reset(Some(1), None).unwrap();
            assert_observation_layout(&env, &obs, &expected);
            assert_eq!(env.action_dim(), robosuite_action_dim(task), "{what}");
        }
    }
}

/// robosuite's single-arm tasks, whose layouts with each bimanual robot were recorded
/// (`TASK-ROBOT` entries of `observations.json`).
const BIMANUAL_TASKS: &[&str] = &[
    "Lift",
    "Stack",
    "Door",
    "Wipe",
    "ToolHang",
    "PickPlace",
    "PickPlaceSingle",
    "PickPlaceMilk",
    "PickPlaceBread",
    "PickPlaceCereal",
    "PickPlaceCan",
    "NutAssembly",
    "NutAssemblySingle",
    "NutAssemblySquare",
    "NutAssemblyRound",
];

#[test]
fn bimanual_robots_lay_out_single_arm_tasks_as_robosuite() {
    for &task in BIMANUAL_TASKS {
        for robot in ["Baxter", "Tiago"] {
            let entry = format!("{task}-{robot}");
            let expected = with_single_object_prefix(task, robosuite_observations(&entry));
            let config = EnvConfig::default().with_robots([robot]);
            let mut env = make_with(task, config).unwrap_or_else(|e| panic!("{entry}: {e}"));
            let (obs, _) = env.reset(Some(1), None).unwrap();
            assert_observation_layout(&env, &obs, &expected);
            assert_eq!(env.action_dim(), robosuite_action_dim(&entry), "{entry}");
        }
    }
}

/// Every task with a GR1 humanoid alone against robosuite's layout (`TASK-ROBOT` entries
/// of `observations.json`, recorded with `record_robosuite.py --layouts --every-task`):
/// GR1FixedLowerBody with robosuite's WHOLE_BODY_IK config, the others with their defaults.
fn lays_out_every_task_as_robosuite(robot: &str) {
    let config = gr1_config(robot);
    for &task in ENV_NAMES {
        let entry = format!("{task}-{robot}");
        let expected = with_single_object_prefix(task, robosuite_observations(&entry));
        let mut env = make_with(task, config.clone()).unwrap_or_else(|e| panic!("{entry}: {e}"));
        let (obs, _) = env.reset(Some(1), None).unwrap();
        assert_observation_layout(&env, &obs, &expected);
        assert_eq!(env.action_dim(), robosuite_action_dim(&entry), "{entry}");
    }
}

#[test]
fn gr1_lays_out_every_task_as_robosuite() {
    lays_out_every_task_as_robosuite("GR1");
}

#[test]
fn gr1_arms_only_lays_out_every_task_as_robosuite() {
    lays_out_every_task_as_robosuite("GR1ArmsOnly");
}

#[test]
fn gr1_floating_body_lays_out_every_task_as_robosuite() {
    lays_out_every_task_as_robosuite("GR1FloatingBody");
}

#[test]
fn gr1_fixed_lower_body_lays_out_every_task_as_robosuite() {
    lays_out_every_task_as_robosuite("GR1FixedLowerBody");
}
