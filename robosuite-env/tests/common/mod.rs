//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod fixtures;
pub mod object_tasks;

use gym_core::{DictValue, Env, Result};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::RobosuiteEnv;

/// The values of an observation key as `f64`.
pub fn get(obs: &DictValue, key: &str) -> Vec<f64> {
    obs.get(key)
        .and_then(|v| v.as_array())
        .map(|a| a.to_f64_vec())
        .unwrap_or_default()
}

/// An action array.
pub fn action(values: [f64; 7]) -> ArrayD<f64> {
    ArrayD::from_shape_vec(IxDyn(&[7]), values.to_vec()).expect("7 values")
}

/// The zero action.
pub fn zero() -> ArrayD<f64> {
    action([0.0; 7])
}

/// `config` with robosuite's `load_composite_controller_config(controller, robot)` as its
/// controller configuration.
pub fn with_composite_controller(
    config: robosuite_env::EnvConfig,
    controller: &str,
    robot: &str,
) -> robosuite_env::EnvConfig {
    let assets = robosuite_env::assets::Assets::locate().expect("the model files");
    let value = robosuite_env::controllers::config::load_composite_controller_config(
        &assets,
        Some(controller),
        Some(robot),
    )
    .expect("robosuite's composite controller config loads");
    config.with_controller_configs([robosuite_env::controllers::ControllerConfig::from_value(
        &value,
        "controller_configs",
    )
    .expect("a valid controller config")])
}

/// A GR1 humanoid `robot` alone with its default composite controller; GR1FixedLowerBody,
/// whose default `WHOLE_BODY_MINK_IK` is not served, with robosuite's WHOLE_BODY_IK config.
pub fn gr1_config(robot: &str) -> robosuite_env::EnvConfig {
    let config = robosuite_env::EnvConfig::default().with_robots([robot]);
    if robot == "GR1FixedLowerBody" {
        with_composite_controller(config, "WHOLE_BODY_IK", robot)
    } else {
        config
    }
}

/// An action array of any size.
pub fn act(values: Vec<f64>) -> ArrayD<f64> {
    ArrayD::from_shape_vec(IxDyn(&[values.len()]), values).expect("a flat action")
}

/// `bad` is refused with [`gym_core::Error::InvalidAction`] and the simulation state stays
/// as it was, bit for bit.
pub fn assert_action_refused(env: &mut RobosuiteEnv, bad: Vec<f64>) {
    let before = env.get_state();
    match env.step(&act(bad)) {
        Err(gym_core::Error::InvalidAction(_)) => {}
        other => panic!("expected InvalidAction, got {:?}", other.map(|_| ())),
    }
    assert_eq!(
        env.get_state(),
        before,
        "a refused action changed the state"
    );
}

fn wrap_quarter(a: f64) -> f64 {
    let q = std::f64::consts::FRAC_PI_2;
    (a + q / 2.0).rem_euclid(q) - q / 2.0
}

/// A scripted Lift policy: align the fingers with the cube's faces, move above the cube,
/// descend, close, lift. Returns whether `info["success"]` was reported, the step it
/// happened, and the largest "grasp bonus" seen with shaped unnormalised rewards.
pub fn scripted_lift(env: &mut RobosuiteEnv, seed: u64, max_steps: usize) -> Result<(bool, usize)> {
    let (mut obs, _) = env.reset(Some(seed), None)?;
    let start_cube = get(&obs, "cube_pos");
    let mut phase = 0;
    let mut in_phase = 0;
    for t in 0..max_steps {
        let eef = get(&obs, "robot0_eef_pos");
        let cube = get(&obs, "cube_pos");
        let (target, grip) = match phase {
            0 => ([cube[0], cube[1], cube[2] + 0.08], -1.0),
            1 => ([cube[0], cube[1], cube[2] - 0.005], -1.0),
            2 => ([eef[0], eef[1], eef[2]], 1.0),
            _ => ([start_cube[0], start_cube[1], start_cube[2] + 0.2], 1.0),
        };
        let err: Vec<f64> = (0..3).map(|i| target[i] - eef[i]).collect();
        let dist = err.iter().map(|e| e * e).sum::<f64>().sqrt();
        // Finger axis (hand y axis) yaw vs the cube's yaw, modulo a quarter turn.
        let hq = get(&obs, "robot0_eef_quat");
        let (x, y, z, w) = (hq[0], hq[1], hq[2], hq[3]);
        let hand_y = [2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z)];
        let finger_yaw = hand_y[1].atan2(hand_y[0]);
        let cq = get(&obs, "cube_quat");
        let (cx, cy, cz, cw) = (cq[0], cq[1], cq[2], cq[3]);
        let cube_yaw = (2.0 * (cw * cz + cx * cy)).atan2(1.0 - 2.0 * (cy * cy + cz * cz));
        let yaw_err = if phase < 2 {
            wrap_quarter(cube_yaw - finger_yaw)
        } else {
            0.0
        };
        let a = action([
            (err[0] * 10.0).clamp(-1.0, 1.0),
            (err[1] * 10.0).clamp(-1.0, 1.0),
            (err[2] * 10.0).clamp(-1.0, 1.0),
            0.0,
            0.0,
            (yaw_err / 0.5).clamp(-1.0, 1.0),
            grip,
        ]);
        let step = env.step(&a)?;
        let done = step.done();
        obs = step.observation;
        if step.info.get_bool("success") == Some(true) {
            return Ok((true, t + 1));
        }
        if done {
            break;
        }
        in_phase += 1;
        let next = match phase {
            0 => dist < 0.01 && yaw_err.abs() < 0.05 || in_phase > 60,
            1 => dist < 0.006 || in_phase > 40,
            2 => in_phase >= 15,
            _ => false,
        };
        if next {
            phase += 1;
            in_phase = 0;
        }
    }
    Ok((false, max_steps))
}

/// Yaw of the Panda's finger axis (hand y axis) from `robot0_eef_quat` (xyzw).
pub fn finger_yaw(obs: &DictValue) -> f64 {
    let hq = get(obs, "robot0_eef_quat");
    let (x, y, z, w) = (hq[0], hq[1], hq[2], hq[3]);
    let hand_y = [2.0 * (x * y - w * z), 1.0 - 2.0 * (x * x + z * z)];
    hand_y[1].atan2(hand_y[0])
}

/// Yaw of an xyzw quaternion.
pub fn yaw_of(q: &[f64]) -> f64 {
    let (x, y, z, w) = (q[0], q[1], q[2], q[3]);
    (2.0 * (w * z + x * y)).atan2(1.0 - 2.0 * (y * y + z * z))
}

/// Wraps an angle to (−π/4, π/4] (a box's yaw modulo a quarter turn).
pub fn wrap_to_quarter(a: f64) -> f64 {
    wrap_quarter(a)
}

/// Wraps an angle to (−π/2, π/2] (the gripper is symmetric under a half turn).
pub fn wrap_half(a: f64) -> f64 {
    let h = std::f64::consts::PI;
    (a + h / 2.0).rem_euclid(h) - h / 2.0
}

/// A proportional OSC action toward `target` with a yaw correction and a gripper command.
pub fn move_to(eef: &[f64], target: [f64; 3], gain: f64, yaw_err: f64, grip: f64) -> ArrayD<f64> {
    action([
        ((target[0] - eef[0]) * gain).clamp(-1.0, 1.0),
        ((target[1] - eef[1]) * gain).clamp(-1.0, 1.0),
        ((target[2] - eef[2]) * gain).clamp(-1.0, 1.0),
        0.0,
        0.0,
        (yaw_err / 0.5).clamp(-1.0, 1.0),
        grip,
    ])
}

/// Euclidean distance between a target and a point.
pub fn dist3(a: [f64; 3], b: &[f64]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt()
}

/// A waypoint of a scripted pick-and-place: a target for the grip site, the gripper
/// command, whether to align the fingers, and how long to stay at most / at least.
pub struct Waypoint {
    /// The target.
    pub target: [f64; 3],
    /// Gripper command (−1 open, +1 close).
    pub grip: f64,
    /// Tolerance that ends the waypoint.
    pub tol: f64,
    /// Minimum steps.
    pub min_steps: usize,
    /// Maximum steps.
    pub max_steps: usize,
}

/// Checks an observation (and the env's observation space) against robosuite's keys, shapes
/// and dtypes, in order.
pub fn assert_observation_layout(
    env: &RobosuiteEnv,
    obs: &DictValue,
    expected: &[fixtures::ObsEntry],
) {
    use gym_core::Space;
    let keys: Vec<&str> = obs.keys().map(String::as_str).collect();
    let want: Vec<&str> = expected.iter().map(|(k, _, _)| k.as_str()).collect();
    assert_eq!(keys, want);
    assert_eq!(env.observation_keys(), want);
    for (key, shape, dtype) in expected {
        let a = obs[key.as_str()]
            .as_array()
            .unwrap_or_else(|| panic!("{key} is not an array"));
        assert_eq!(a.shape(), shape.as_slice(), "{key}");
        assert_eq!(a.dtype(), *dtype, "{key}");
    }
    assert!(env.observation_space().contains(obs));
}

/// Steps `actions` from the current state, taking a snapshot after the first `at`; then
/// restores it and steps the rest again: observations, rewards, end flags and the whole
/// simulation state repeat bit for bit, and the task state comes back with the snapshot.
pub fn assert_snapshot_replays(env: &mut RobosuiteEnv, actions: &[ArrayD<f64>], at: usize) {
    for a in &actions[..at] {
        let _ = env.step(a).expect("the action steps");
    }
    let snapshot = env.snapshot();
    let task_state = env.task().save_state();
    let run = |env: &mut RobosuiteEnv| -> Vec<(DictValue, u64, bool, bool, Vec<u64>)> {
        actions[at..]
            .iter()
            .map_while(|a| {
                let s = env.step(a).ok()?;
                let state = env.get_state().iter().map(|x| x.to_bits()).collect();
                Some((
                    s.observation,
                    s.reward.to_bits(),
                    s.terminated,
                    s.truncated,
                    state,
                ))
            })
            .collect()
    };
    let first = run(env);
    assert!(!first.is_empty());
    env.restore(&snapshot).expect("the snapshot restores");
    assert_eq!(env.task().save_state(), task_state);
    let second = run(env);
    assert_eq!(first, second);
}

/// Runs a scripted `policy` (returning whether it reported success, and when) from resets
/// with the seeds `0..seeds` and checks that it succeeds on at least `min` of them.
pub fn assert_scripted_successes(
    task: &str,
    env: &mut RobosuiteEnv,
    seeds: u64,
    min: usize,
    mut policy: impl FnMut(&mut RobosuiteEnv, u64) -> (bool, usize),
) {
    let report: Vec<(bool, usize)> = (0..seeds).map(|seed| policy(env, seed)).collect();
    let ok = report.iter().filter(|r| r.0).count();
    assert!(
        ok >= min,
        "scripted {task} succeeded on {ok}/{seeds} seeds: {report:?}"
    );
}
