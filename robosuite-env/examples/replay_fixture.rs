//! Replays one recorded robosuite rollout (`tests/fixtures/robosuite/TASK.json`) from its
//! recorded reset and prints, as JSON, the observations the fixture records, the reward and
//! success after every step — for `scripts/replay_robosuite.py --compare`, which sets them
//! beside robosuite's own replay on another MuJoCo.
//!
//! `cargo run -p robosuite-env --example replay_fixture -- Door 0 > ours.json`

use gym_core::Env;
use ndarray::{ArrayD, IxDyn};
use serde_json::{Map, Value, json};

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .map(|a| a.iter().filter_map(Value::as_f64).collect())
        .unwrap_or_default()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let task = args.next().unwrap_or_else(|| "Lift".to_owned());
    let index: usize = args.next().map_or(Ok(0), |s| s.parse())?;
    let path = format!(
        "{}/tests/fixtures/robosuite/{task}.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let fixture: Value = serde_json::from_str(&std::fs::read_to_string(&path)?)?;
    let rollout = &fixture["rollouts"][index];
    let robots: Vec<String> = match fixture["robots"].as_array() {
        Some(list) => list
            .iter()
            .filter_map(|r| r.as_str().map(str::to_owned))
            .collect(),
        None => vec![fixture["robot"].as_str().unwrap_or("Panda").to_owned()],
    };
    let name = fixture["task"].as_str().unwrap_or(&task).to_owned();
    let mut config = robosuite_env::EnvConfig::default().with_robots(robots);
    if let Some(c) = fixture["kwargs"]["env_configuration"].as_str() {
        config = config.with_env_configuration(robosuite_env::EnvConfiguration::parse(c)?);
    }
    let mut env = robosuite_env::make_with(&name, config)?;
    env.reset_to_state(
        &numbers(&rollout["task_state"]),
        &numbers(&rollout["init_state"]),
    )?;
    let keys: Vec<String> = rollout["steps"][0]["obs"]
        .as_object()
        .map(|o| o.keys().cloned().collect())
        .unwrap_or_default();
    let mut steps = Vec::new();
    for action in rollout["actions"].as_array().into_iter().flatten() {
        let a = numbers(action);
        let step = env.step(&ArrayD::from_shape_vec(IxDyn(&[a.len()]), a)?)?;
        let mut obs = Map::new();
        for key in &keys {
            let values = step
                .observation
                .get(key)
                .and_then(|v| v.as_array())
                .map(|a| a.to_f64_vec())
                .unwrap_or_default();
            obs.insert(key.clone(), json!(values));
        }
        steps.push(json!({
            "obs": obs,
            "reward": step.reward,
            "success": step.info.get_bool("success"),
        }));
        if step.done() {
            break;
        }
    }
    println!("{}", serde_json::to_string(&steps)?);
    Ok(())
}
