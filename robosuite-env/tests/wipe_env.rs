//! Wipe: the wiping tool, the marker walk, observations, reward, success and early
//! termination.

mod common;

use common::get;
use gym_core::{DType, Env};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::tasks::{Wipe, WipeConfig};
use robosuite_env::{EnvConfig, RobosuiteEnv, default_config, make, make_with};

fn act(v: [f64; 6]) -> ArrayD<f64> {
    ArrayD::from_shape_vec(IxDyn(&[6]), v.to_vec()).unwrap()
}

#[test]
fn wipe_sizes_and_observations_match_robosuite() {
    let mut env = make("Wipe").unwrap();
    assert!(env.config().reward_shaping, "Wipe shapes by default");
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu), (7, 7, 7));
    assert_eq!(env.action_dim(), 6);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let keys = env.observation_keys();
    assert_eq!(
        &keys[8..],
        &[
            "robot0_gripper_qpos",
            "robot0_gripper_qvel",
            "robot0_contact",
            "proportion_wiped",
            "wipe_radius",
            "wipe_centroid",
            "gripper_to_wipe_centroid",
            "robot0_proprio-state",
            "object-state"
        ]
    );
    assert_eq!(get(&obs, "robot0_proprio-state").len(), 47);
    assert_eq!(get(&obs, "object-state").len(), 8);
    assert_eq!(get(&obs, "robot0_gripper_qpos").len(), 0);
    assert_eq!(
        obs.get("robot0_contact")
            .unwrap()
            .as_array()
            .unwrap()
            .dtype(),
        DType::I8
    );
    assert_eq!(get(&obs, "proportion_wiped"), [0.0]);
    // A 7-dim action is rejected.
    assert!(env.step(&common::zero()).is_err());
    let step = env.step(&act([0.0; 6])).unwrap();
    assert!(!step.terminated && !step.truncated);
    // Shaped, normalised: 5 (1 − tanh(5 d)) (+ small contact terms) × 0.032776.
    assert!(step.reward > 0.0 && step.reward < 0.2, "{}", step.reward);
    assert!(default_config("Wipe").reward_shaping && !default_config("Lift").reward_shaping);
}

#[test]
fn markers_follow_a_random_walk_on_the_table() {
    let mut env = make("Wipe").unwrap();
    let mut first = Vec::new();
    for seed in 0..3 {
        env.reset(Some(seed), None).unwrap();
        let task = env.task();
        let _ = task;
        let sim = env.sim();
        let pts: Vec<[f64; 3]> = (0..100)
            .map(|i| {
                let b =
                    robosuite_env::sim::body_id(sim.model(), &format!("contact{i}_main")).unwrap();
                sim.data().xpos()[b]
            })
            .collect();
        for p in &pts {
            assert!((p[2] - 0.9).abs() < 1e-12);
            assert!((p[0] - 0.15).abs() < 0.25 * 0.6 - 0.02 + 1e-12, "{p:?}");
            assert!(p[1].abs() < 0.4 * 0.6 - 0.02 + 1e-12, "{p:?}");
        }
        for w in pts.windows(2) {
            let d = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            assert!((d - 0.005).abs() < 1e-9, "{d}");
        }
        first.push(pts[0]);
    }
    assert_ne!(first[0], first[1]);
}

#[test]
fn a_joint_at_its_limit_ends_the_episode_with_the_penalty() {
    let mut env = make("Wipe").unwrap();
    env.reset(Some(0), None).unwrap();
    let mut s = env.get_state();
    s[1] = 2.85; // joint1 within 0.1 rad of its 2.8973 limit
    env.set_state(&s).unwrap();
    let step = env.step(&act([0.0; 6])).unwrap();
    assert!(step.terminated, "joint limit terminates");
    let norm = WipeConfig::default().normalization(1000);
    assert!((norm - 0.032776).abs() < 1e-6);
    assert!((step.reward + 10.0 * norm).abs() < 1e-9, "{}", step.reward);
    assert_eq!(step.info.get_bool("success"), Some(false));
    assert!(env.step(&act([0.0; 6])).is_err());
}

/// Presses the tool down onto the first marker and follows the walk; returns the env.
fn press_along(env: &mut RobosuiteEnv, seed: u64, steps: usize) -> Vec<(f64, bool, usize)> {
    env.reset(Some(seed), None).unwrap();
    let sim = env.sim();
    let n = (0..)
        .take_while(|i| {
            robosuite_env::sim::body_id(sim.model(), &format!("contact{i}_main")).is_ok()
        })
        .count();
    let pts: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let b = robosuite_env::sim::body_id(sim.model(), &format!("contact{i}_main")).unwrap();
            sim.data().xpos()[b]
        })
        .collect();
    let mut out = Vec::new();
    let mut obs = env.observation();
    let mut k = 0usize;
    for t in 0..steps {
        let eef = get(&obs, "robot0_eef_pos");
        let p = pts[k.min(n - 1)];
        let above = (eef[0] - p[0]).hypot(eef[1] - p[1]) > 0.01 && t < 60;
        let z = if above { p[2] + 0.05 } else { p[2] - 0.02 };
        let a = act([
            ((p[0] - eef[0]) * 10.0).clamp(-1.0, 1.0),
            ((p[1] - eef[1]) * 10.0).clamp(-1.0, 1.0),
            ((z - eef[2]) * 10.0).clamp(-1.0, 1.0),
            0.0,
            0.0,
            0.0,
        ]);
        let step = env.step(&a).unwrap();
        obs = step.observation;
        out.push((
            step.reward,
            step.terminated,
            (get(&obs, "proportion_wiped")[0] * n as f64).round() as usize,
        ));
        if step.terminated || step.truncated {
            break;
        }
        if !above {
            k += 2;
        }
    }
    out
}

#[test]
fn pressing_the_tool_on_the_path_wipes_markers() {
    let mut env = make_with("Wipe", default_config("Wipe").with_horizon(200)).unwrap();
    let trace = press_along(&mut env, 0, 150);
    let wiped = trace.last().unwrap().2;
    assert!(wiped >= 10, "wiped only {wiped} markers: {trace:?}");
    // A step that wipes markers pays 50 each (normalised); the other terms (distance,
    // contact, pressure, force penalty) are small next to it.
    let norm = WipeConfig::default().normalization(200);
    let mut prev = 0;
    let mut saw = false;
    for (r, _, w) in &trace {
        if *w > prev {
            assert!(
                *r >= 40.0 * (*w - prev) as f64 * norm,
                "{r} for {} new",
                w - prev
            );
            saw = true;
        }
        prev = *w;
    }
    assert!(saw);
    eprintln!("wiped {wiped} of 100 in {} steps", trace.len());
}

#[test]
fn wiping_every_marker_is_a_success_and_ends_the_episode() {
    // Three markers: the tool covers them at once.
    let config = WipeConfig {
        num_markers: 3,
        ..WipeConfig::default()
    };
    let mut env = RobosuiteEnv::new(
        Box::new(Wipe::new(config).unwrap()),
        EnvConfig::default()
            .with_reward_shaping(true)
            .with_horizon(150),
    )
    .unwrap();
    let trace = press_along(&mut env, 1, 140);
    let (r, terminated, wiped) = *trace.last().unwrap();
    assert_eq!(wiped, 3, "{trace:?}");
    assert!(terminated, "success terminates");
    assert!(env.check_success());
    // The completion bonus 25.5 is in the last reward.
    let norm = WipeConfig {
        num_markers: 3,
        ..WipeConfig::default()
    }
    .normalization(150);
    assert!(r > 25.5 * norm, "{r}");
}
