//! robosuite 1.5.2's recorded behaviour (`tests/fixtures/robosuite/*.json`, written by
//! `scripts/record_robosuite.py` from robosuite itself) and the comparison of this crate's
//! environments with it.
#![allow(dead_code)]

use gym_core::{DictValue, Env};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};
use serde::Deserialize;
use std::collections::BTreeMap as IndexMap;
use std::path::PathBuf;

/// One task's fixture.
#[derive(Debug, Deserialize)]
pub struct Fixture {
    /// The task.
    pub task: String,
    /// The robot (the first one, where the task has several).
    pub robot: String,
    /// Every robot, where the task has several.
    #[serde(default)]
    pub robots: Option<Vec<String>>,
    /// robosuite's other `make` arguments of the recording (`env_configuration`;
    /// `composite_controller`: the name of robosuite's composite controller config for the
    /// robot, loaded as `load_composite_controller_config(controller=..., robot=...)`).
    #[serde(default)]
    pub kwargs: IndexMap<String, String>,
    /// robosuite's counts (`nq`, `nv`, `nu`, `nbody`, ...).
    pub counts: IndexMap<String, i64>,
    /// Every element's name by kind, in model order.
    pub names: IndexMap<String, Vec<String>>,
    /// Recorded rollouts.
    pub rollouts: Vec<Rollout>,
    /// Initial object positions over many resets.
    pub placement: Placement,
}

/// A recorded rollout from a reset.
#[derive(Debug, Deserialize)]
pub struct Rollout {
    /// `"scripted"` or `"random"`.
    pub kind: String,
    /// robosuite's drawn task parameters, in `Task::save_state`'s layout.
    pub task_state: Vec<f64>,
    /// `[time, qpos, qvel]` after reset.
    pub init_state: Vec<f64>,
    /// The actions.
    pub actions: Vec<Vec<f64>>,
    /// After each action.
    pub steps: Vec<RecordedStep>,
    /// What robosuite itself differs by from this recording when it runs on MuJoCo 3.17.0
    /// (`scripts/mujoco_floor.py`): the part of any difference MuJoCo's version causes.
    #[serde(default)]
    pub floor: Option<Floor>,
}

/// The MuJoCo-version floor of a rollout's differences, as [`ReplayErrors`] measures them.
#[derive(Debug, Clone, Copy, Default, Deserialize)]
pub struct Floor {
    /// Robot joints and grip site before the first touch.
    pub free_arm: f64,
    /// Robot joints and grip site after it.
    pub contact_arm: f64,
    /// Object positions.
    pub objects: f64,
    /// Rewards.
    pub reward: f64,
    /// Steps whose success differs.
    pub success_mismatches: usize,
}

/// What robosuite reported after one step.
#[derive(Debug, Deserialize)]
pub struct RecordedStep {
    /// Chosen observations, flattened.
    pub obs: IndexMap<String, Vec<f64>>,
    /// The reward.
    pub reward: f64,
    /// `_check_success()`.
    pub success: bool,
    /// Whether a robot or gripper geom touched something outside the robot.
    pub robot_contact: bool,
}

/// Initial positions over resets.
#[derive(Debug, Deserialize)]
pub struct Placement {
    /// The number of resets.
    pub resets: usize,
    /// Per object root body: smallest and largest position.
    pub bodies: IndexMap<String, Bounds>,
}

/// Smallest and largest position.
#[derive(Debug, Deserialize)]
pub struct Bounds {
    /// Smallest x, y, z.
    pub min: [f64; 3],
    /// Largest x, y, z.
    pub max: [f64; 3],
}

/// The folder of the fixtures.
pub fn fixture_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/robosuite")
}

/// Loads the fixture of `task`.
pub fn load(task: &str) -> Fixture {
    let path = fixture_dir().join(format!("{task}.json"));
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The tasks that have a fixture: files named after a task (`Lift.json`,
/// `Lift-Sawyer.json`, ...); the camera fixtures beside them have their own tests.
pub fn recorded_tasks() -> Vec<String> {
    // A comma-separated list of fixture stems narrows a local run (not set in CI).
    let only = std::env::var("ROBOSUITE_FIXTURES").ok();
    let mut out: Vec<String> = std::fs::read_dir(fixture_dir())
        .expect("the fixture folder exists")
        .filter_map(|e| {
            let name = e.ok()?.file_name().into_string().ok()?;
            let stem = name.strip_suffix(".json")?;
            let task = stem.split('-').next()?;
            let wanted = only
                .as_deref()
                .is_none_or(|list| list.split(',').any(|s| s == stem));
            (wanted && robosuite_env::ENV_NAMES.contains(&task)).then(|| stem.to_owned())
        })
        .collect();
    out.sort();
    out
}

/// The largest differences seen replaying one rollout.
#[derive(Debug, Default, Clone)]
pub struct ReplayErrors {
    /// Robot joint positions and grip-site position before the robot first touches
    /// anything (rad / m).
    pub free_arm: f64,
    /// Every recorded position (joints, grip site, objects) over the whole rollout.
    pub all_positions: f64,
    /// Robot joint positions and grip-site position after the first touch.
    pub contact_arm: f64,
    /// Object positions over the whole rollout (objects rest and slide on tables).
    pub objects: f64,
    /// Rewards.
    pub reward: f64,
    /// Steps whose success differs, apart from the shifts below.
    pub success_mismatches: usize,
    /// Steps next to a change of the recorded success (the step before or the step of the
    /// change) whose success differs: a crossing of the success boundary displaced by one
    /// step, which a sub-millimetre difference in a moving object causes. Their rewards are
    /// left out of `reward`.
    pub success_shifts: usize,
    /// Changes of the recorded success over the rollout.
    pub success_changes: usize,
    /// The step of the first touch, if any.
    pub first_contact: Option<usize>,
    /// Steps compared.
    pub steps: usize,
}

/// The values of an observation key as `f64`.
pub fn values(obs: &DictValue, key: &str) -> Vec<f64> {
    obs.get(key)
        .and_then(|v| v.as_array())
        .map(|a| a.to_f64_vec())
        .unwrap_or_else(|| panic!("no observation `{key}`"))
}

fn max_abs_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Position keys of a robot (compared at the arm tolerance).
fn is_arm_key(key: &str) -> bool {
    key.starts_with("robot") && (key.ends_with("joint_pos") || key.ends_with("eef_pos"))
}

/// Object position keys (world positions of objects).
fn is_object_pos_key(key: &str) -> bool {
    !key.starts_with("robot")
        && key.ends_with("_pos")
        && !key.contains("_to_")
        && !key.starts_with("gripper")
}

/// The configuration `fixture` was recorded with: its robots and `env_configuration`,
/// robosuite's defaults otherwise.
pub fn config_for(fixture: &Fixture) -> EnvConfig {
    let robots = fixture
        .robots
        .clone()
        .unwrap_or_else(|| vec![fixture.robot.clone()]);
    let mut config = EnvConfig::default().with_robots(robots);
    for (key, value) in &fixture.kwargs {
        match key.as_str() {
            "env_configuration" => {
                config = config.with_env_configuration(
                    robosuite_env::EnvConfiguration::parse(value).expect("a known configuration"),
                );
            }
            "composite_controller" => {
                config = super::with_composite_controller(config, value, &fixture.robot);
            }
            other => panic!("{}: unknown recorded argument `{other}`", fixture.task),
        }
    }
    config
}

/// An environment for `fixture` with its recorded configuration.
pub fn env_for(fixture: &Fixture) -> RobosuiteEnv {
    make_with(&fixture.task, config_for(fixture))
        .unwrap_or_else(|e| panic!("{}: {e}", fixture.task))
}

/// Replays `rollout` from its recorded reset in `env` and measures the differences.
pub fn replay(env: &mut RobosuiteEnv, rollout: &Rollout) -> ReplayErrors {
    env.reset_to_state(&rollout.task_state, &rollout.init_state)
        .expect("the recorded reset state loads");
    let mut e = ReplayErrors {
        first_contact: rollout.steps.iter().position(|s| s.robot_contact),
        ..Default::default()
    };
    for (i, (action, rec)) in rollout.actions.iter().zip(&rollout.steps).enumerate() {
        let a = ArrayD::from_shape_vec(IxDyn(&[action.len()]), action.clone()).unwrap();
        let step = env.step(&a).expect("the recorded action steps");
        let touched = e.first_contact.is_some_and(|c| i >= c);
        for (key, want) in &rec.obs {
            let got = values(&step.observation, key);
            let d = max_abs_diff(&got, want);
            if is_arm_key(key) {
                if touched {
                    e.contact_arm = e.contact_arm.max(d);
                } else {
                    e.free_arm = e.free_arm.max(d);
                }
                e.all_positions = e.all_positions.max(d);
            } else if is_object_pos_key(key) {
                e.objects = e.objects.max(d);
                e.all_positions = e.all_positions.max(d);
            }
        }
        let changes_here = |j: usize| {
            j > 0
                && j < rollout.steps.len()
                && rollout.steps[j].success != rollout.steps[j - 1].success
        };
        if changes_here(i) {
            e.success_changes += 1;
        }
        if step.info.get_bool("success") == Some(rec.success) {
            e.reward = e.reward.max((step.reward - rec.reward).abs());
        } else if changes_here(i) || changes_here(i + 1) {
            e.success_shifts += 1;
        } else {
            e.reward = e.reward.max((step.reward - rec.reward).abs());
            e.success_mismatches += 1;
        }
        e.steps += 1;
        if step.done() {
            break;
        }
    }
    e
}

/// One observation key of robosuite: its name, shape and dtype.
pub type ObsEntry = (String, Vec<usize>, gym_core::DType);

/// One task's entry of `observations.json`.
#[derive(Debug, Deserialize)]
struct RecordedObservations {
    action_dim: usize,
    obs: Vec<(String, Vec<usize>, String)>,
}

fn recorded_observations(task: &str) -> RecordedObservations {
    let path = fixture_dir().join("observations.json");
    let text = std::fs::read_to_string(&path).expect("observations.json is readable");
    let mut all: IndexMap<String, RecordedObservations> =
        serde_json::from_str(&text).expect("observations.json parses");
    all.remove(task)
        .unwrap_or_else(|| panic!("observations.json has no entry {task}"))
}

/// robosuite 1.5.2's observation keys of `task` made with its defaults, in order, with
/// their shapes and dtypes (`observations.json`).
pub fn robosuite_observations(task: &str) -> Vec<ObsEntry> {
    recorded_observations(task)
        .obs
        .into_iter()
        .map(|(key, shape, dtype)| {
            let dtype = match dtype.as_str() {
                "float64" => gym_core::DType::F64,
                "float32" => gym_core::DType::F32,
                "int64" => gym_core::DType::I64,
                "bool" => gym_core::DType::Bool,
                other => panic!("{task} {key}: unexpected dtype {other}"),
            };
            (key, shape, dtype)
        })
        .collect()
}

/// robosuite 1.5.2's action dimension of `task` made with its defaults.
pub fn robosuite_action_dim(task: &str) -> usize {
    recorded_observations(task).action_dim
}
