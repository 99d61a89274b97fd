//! Wipe: the wiping tool, the marker walk, observations (and their one-step lag), reward,
//! success, early termination, configuration and state round trips.

use crate::common::fixtures::{env_for, load, robosuite_observations, values};
use crate::common::{assert_observation_layout, assert_snapshot_replays, get};
use gym_core::{DType, Env, Error};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::models::robots::GripperChoice;
use robosuite_env::sim::{body_id, geom_id};
use robosuite_env::tasks::{WipeConfig, WipeSpec};
use robosuite_env::{EnvConfig, RobosuiteEnv, make, make_with};

fn act(v: [f64; 6]) -> ArrayD<f64> {
    ArrayD::from_shape_vec(IxDyn(&[6]), v.to_vec()).unwrap()
}

fn wipe_with(task_config: WipeConfig, config: EnvConfig) -> gym_core::Result<RobosuiteEnv> {
    RobosuiteEnv::new(&WipeSpec { task_config }, config)
}

/// The markers' world positions.
fn markers(env: &RobosuiteEnv) -> Vec<[f64; 3]> {
    let m = env.sim().model();
    (0..)
        .map_while(|i| body_id(m, &format!("contact{i}_main")).ok())
        .map(|b| env.sim().data().xpos()[b])
        .collect()
}

/// The wiped flags from the task state (positions 3n, then n flags).
fn wiped(env: &RobosuiteEnv) -> Vec<bool> {
    let s = env.task().save_state();
    let n = (s.len() - 9) / 4;
    s[3 * n..4 * n].iter().map(|f| *f == 1.0).collect()
}

#[test]
fn sizes_and_observations_match_robosuite() {
    let mut env = make("Wipe").unwrap();
    assert_eq!(
        env.config().reward_shaping,
        Some(true),
        "Wipe shapes by default"
    );
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu, m.nbody, m.ngeom), (7, 7, 7, 121, 216));
    assert_eq!(env.action_dim(), 6);
    let (obs, info) = env.reset(Some(0), None).unwrap();
    assert_eq!(info.get_bool("success"), Some(false));
    assert_observation_layout(&env, &obs, &robosuite_observations("Wipe"));
    // robot0_contact is part of the proprio concatenation, at its end.
    let proprio = get(&obs, "robot0_proprio-state");
    assert_eq!(proprio[46], get(&obs, "robot0_contact")[0]);
    assert_eq!(get(&obs, "proportion_wiped"), [0.0]);
    // The centroid of the markers and the largest distance to it.
    let pts = markers(&env);
    let c: Vec<f64> = (0..3)
        .map(|k| pts.iter().map(|p| p[k]).sum::<f64>() / 100.0)
        .collect();
    let centroid = get(&obs, "wipe_centroid");
    assert!((0..3).all(|k| (centroid[k] - c[k]).abs() < 1e-12));
    let r = pts
        .iter()
        .map(|p| {
            (0..3)
                .map(|k| (p[k] - centroid[k]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    assert!((get(&obs, "wipe_radius")[0] - r).abs() < 1e-12);
    let eef = get(&obs, "robot0_eef_pos");
    let g2c = get(&obs, "gripper_to_wipe_centroid");
    assert!((0..3).all(|k| g2c[k] == centroid[k] - eef[k]));
    // A 7-dim action is refused; a 6-dim one steps.
    assert!(matches!(
        env.step(&crate::common::zero()),
        Err(Error::InvalidAction(_))
    ));
    let step = env.step(&act([0.0; 6])).unwrap();
    assert!(!step.terminated && !step.truncated);
    // Shaped and normalised: mostly 5 (1 − tanh(5 d)) · 0.0328.
    assert!(
        step.reward > 0.0 && step.reward < 5.0 * 0.0328,
        "{}",
        step.reward
    );
    assert_eq!(make("Lift").unwrap().config().reward_shaping, Some(false));
}

#[test]
fn observations_equal_robosuites_before_the_tool_touches() {
    // The recorded rollouts: robot0_contact, proportion_wiped and the wipe information match
    // robosuite's at every step of the random rollout and before the first touch of the
    // scripted one (after it, MuJoCo 3.3.7 and 3.17.0 part; see robosuite_replay.rs).
    let fixture = load("Wipe");
    let mut env = env_for(&fixture);
    for rollout in &fixture.rollouts {
        env.reset_to_state(&rollout.task_state, &rollout.init_state)
            .unwrap();
        let touch = rollout
            .steps
            .iter()
            .position(|s| s.robot_contact)
            .unwrap_or(usize::MAX);
        for (i, (a, rec)) in rollout
            .actions
            .iter()
            .zip(&rollout.steps)
            .enumerate()
            .take(touch)
        {
            let step = env.step(&act(a.as_slice().try_into().unwrap())).unwrap();
            for key in [
                "robot0_contact",
                "proportion_wiped",
                "wipe_radius",
                "wipe_centroid",
                "gripper_to_wipe_centroid",
            ] {
                let (got, want) = (values(&step.observation, key), &rec.obs[key]);
                assert!(
                    got.iter().zip(want).all(|(g, w)| (g - w).abs() < 1e-6),
                    "{} step {i} {key}: {got:?} vs {want:?}",
                    rollout.kind
                );
            }
            assert!(
                (step.reward - rec.reward).abs() < 1e-6,
                "{} step {i}",
                rollout.kind
            );
            if step.done() {
                break;
            }
        }
    }
}

#[test]
fn wipe_takes_only_the_wiping_gripper() {
    for choice in [
        GripperChoice::None,
        GripperChoice::Named("PandaGripper".into()),
    ] {
        let config = EnvConfig::default().with_gripper_types([choice.clone()]);
        let err = make_with("Wipe", config).unwrap_err();
        assert!(
            matches!(&err, Error::InvalidArgument { name, reason } if name == "gripper_types" && reason.contains("WipingGripper")),
            "{choice:?}: {err}"
        );
    }
    let named =
        EnvConfig::default().with_gripper_types([GripperChoice::Named("WipingGripper".into())]);
    assert_eq!(make_with("Wipe", named).unwrap().action_dim(), 6);
}

#[test]
fn markers_follow_a_random_walk_through_the_model() {
    let mut env = make("Wipe").unwrap();
    let mut starts = Vec::new();
    for seed in 0..5 {
        env.reset(Some(seed), None).unwrap();
        let pts = markers(&env);
        assert_eq!(pts.len(), 100);
        for p in &pts {
            // On the table top (0.9), inside ±(half size · 0.6 − 0.02) around its centre.
            assert!((p[2] - 0.9).abs() < 1e-12);
            assert!(
                (p[0] - 0.15).abs() < 0.25 * 0.6 - 0.02 && p[1].abs() < 0.4 * 0.6 - 0.02,
                "{p:?}"
            );
        }
        for w in pts.windows(2) {
            let d = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            assert!((d - 0.005).abs() < 1e-9, "{d}");
        }
        // Written into the model (table frame) and part of the task state; every marker
        // visible, its site hidden.
        let m = env.sim().model();
        let state = env.task().save_state();
        for i in 0..100 {
            let b = body_id(m, &format!("contact{i}_main")).unwrap();
            assert_eq!(state[3 * i..3 * i + 3], m.body_pos()[b]);
            assert_eq!(
                m.geom_rgba()[geom_id(m, &format!("contact{i}_g0_vis")).unwrap()][3],
                1.0
            );
            let site = robosuite_env::sim::site_id(m, &format!("contact{i}_default_site")).unwrap();
            assert_eq!(m.site_rgba()[site][3], 0.0);
        }
        starts.push(pts[0]);
    }
    assert_ne!(starts[0], starts[1]);
}

#[test]
fn a_joint_at_its_limit_ends_the_episode_with_the_penalty() {
    let mut env = make("Wipe").unwrap();
    env.reset(Some(0), None).unwrap();
    let mut s = env.get_state();
    s[1] = 2.85; // joint1 within 0.1 rad of its 2.8973 limit
    env.set_state(&s).unwrap();
    let step = env.step(&act([0.0; 6])).unwrap();
    assert!(step.terminated, "a joint limit terminates");
    let norm = WipeConfig::default().reward_normalization_factor(1000);
    assert!((norm - 1000.0 / 30510.0).abs() < 1e-15);
    assert!((step.reward + 10.0 * norm).abs() < 1e-12, "{}", step.reward);
    assert_eq!(step.info.get_bool("success"), Some(false));
    assert_eq!(env.step(&act([0.0; 6])), Err(Error::EpisodeEnded));
    // With ignore_done the episode goes on after the termination, as in robosuite (its
    // step refuses only past the horizon); each step still reports it.
    let mut env = make_with("Wipe", EnvConfig::default().with_ignore_done(true)).unwrap();
    env.reset(Some(0), None).unwrap();
    env.set_state(&s).unwrap();
    assert!(env.step(&act([0.0; 6])).unwrap().terminated);
    assert!(env.step(&act([0.0; 6])).unwrap().terminated);
    // Without shaping the penalty is 0; without early terminations the episode goes on.
    let calm = WipeConfig {
        early_terminations: false,
        ..WipeConfig::default()
    };
    let mut env = wipe_with(calm, EnvConfig::default().with_reward_shaping(false)).unwrap();
    env.reset(Some(0), None).unwrap();
    env.set_state(&s).unwrap();
    let step = env.step(&act([0.0; 6])).unwrap();
    assert!(!step.terminated);
    assert_eq!(step.reward, 0.0);
}

/// Presses the tool 2 cm into the table along the markers' path, one marker per step,
/// as the recorded scripted rollout does. Returns per step (reward, terminated,
/// proportion_wiped observed, wiped count after the step).
fn press_along(
    env: &mut RobosuiteEnv,
    seed: u64,
    steps: usize,
    actions: &mut Vec<ArrayD<f64>>,
) -> Vec<(f64, bool, f64, usize)> {
    let (mut obs, _) = env.reset(Some(seed), None).unwrap();
    let pts = markers(env);
    let (mut k, mut down) = (0usize, false);
    let mut out = Vec::new();
    for t in 0..steps {
        let eef = get(&obs, "robot0_eef_pos");
        let p = pts[k.min(pts.len() - 1)];
        if !down && ((eef[0] - p[0]).hypot(eef[1] - p[1]) < 0.01 || t >= 60) {
            down = true;
        }
        if down {
            k += 1;
        }
        let z = if down { p[2] - 0.02 } else { p[2] + 0.05 };
        let a = act([
            ((p[0] - eef[0]) * 10.0).clamp(-1.0, 1.0),
            ((p[1] - eef[1]) * 10.0).clamp(-1.0, 1.0),
            ((z - eef[2]) * 10.0).clamp(-1.0, 1.0),
            0.0,
            0.0,
            0.0,
        ]);
        let step = env.step(&a).unwrap();
        actions.push(a);
        let done = step.done();
        obs = step.observation;
        let count = wiped(env).iter().filter(|w| **w).count();
        out.push((
            step.reward,
            step.terminated,
            get(&obs, "proportion_wiped")[0],
            count,
        ));
        if done {
            break;
        }
    }
    out
}

#[test]
fn pressing_the_tool_along_the_path_wipes_markers_observed_one_step_late() {
    let mut env = make_with("Wipe", EnvConfig::default().with_horizon(200)).unwrap();
    let trace = press_along(&mut env, 0, 150, &mut Vec::new());
    let wiped_now = trace.last().unwrap().3;
    assert!(wiped_now >= 10, "wiped only {wiped_now} markers");
    let norm = WipeConfig::default().reward_normalization_factor(200);
    let mut before = 0;
    for (i, &(reward, _, observed, count)) in trace.iter().enumerate() {
        // The observation is sampled before the step's reward wipes markers: it shows the
        // count of the previous step.
        assert_eq!(observed, before as f64 / 100.0, "step {i}");
        // Each newly wiped marker pays 50 (normalised); the other terms are smaller.
        if count > before {
            assert!(
                reward >= 45.0 * (count - before) as f64 * norm,
                "step {i}: {reward}"
            );
        }
        before = count;
    }
    // Wiped markers are transparent.
    let m = env.sim().model();
    for (i, w) in wiped(&env).iter().enumerate() {
        let alpha = m.geom_rgba()[geom_id(m, &format!("contact{i}_g0_vis")).unwrap()][3];
        assert_eq!(alpha, if *w { 0.0 } else { 1.0 });
    }
    // The tool presses on the table: contact beyond the bias.
    assert_eq!(get(&env.observation(), "robot0_contact"), [1.0]);
    // MuJoCo's arena holds the tool's contacts with room to spare.
    assert!(env.sim().arena_max_use() < env.sim().arena_bytes() / 2);
}

#[test]
fn wiping_every_marker_is_a_success_and_ends_the_episode() {
    let config = WipeConfig {
        num_markers: 3,
        ..WipeConfig::default()
    };
    let norm = config.reward_normalization_factor(150);
    let mut env = wipe_with(config, EnvConfig::default().with_horizon(150)).unwrap();
    let trace = press_along(&mut env, 1, 140, &mut Vec::new());
    let (reward, terminated, _, count) = *trace.last().unwrap();
    assert_eq!(count, 3);
    assert!(terminated, "success terminates");
    assert!(env.check_success());
    // The completion bonus 25.5 is in the last reward.
    assert!(reward > 25.5 * norm, "{reward}");
    assert!(trace[..trace.len() - 1].iter().all(|t| !t.1));
}

#[test]
fn robot_contact_and_object_observations_follow_the_configuration() {
    // robosuite creates robot0_contact with the object observables only.
    let mut env = make_with("Wipe", EnvConfig::default().with_object_obs(false)).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert!(obs.get("robot0_contact").is_none());
    assert_eq!(get(&obs, "robot0_proprio-state").len(), 46);
    // Per-marker observations instead of the condensed ones.
    let explicit = WipeConfig {
        use_condensed_obj_obs: false,
        num_markers: 3,
        ..WipeConfig::default()
    };
    let mut env = wipe_with(explicit, EnvConfig::default()).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let keys: Vec<&str> = obs.keys().map(String::as_str).skip(10).collect();
    assert_eq!(
        keys,
        [
            "robot0_contact",
            "marker0_pos",
            "marker0_wiped",
            "gripper_to_marker0",
            "marker1_pos",
            "marker1_wiped",
            "gripper_to_marker1",
            "marker2_pos",
            "marker2_wiped",
            "gripper_to_marker2",
            "robot0_proprio-state",
            "object-state"
        ]
    );
    assert_eq!(obs["marker0_wiped"].as_array().unwrap().dtype(), DType::I64);
    assert_eq!(get(&obs, "marker1_pos"), markers(&env)[1]);
    // No contact observation, no robot-relative ones.
    let quiet = WipeConfig {
        use_contact_obs: false,
        use_robot_obs: false,
        ..WipeConfig::default()
    };
    let mut env = wipe_with(quiet, EnvConfig::default()).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert!(obs.get("robot0_contact").is_none() && obs.get("gripper_to_wipe_centroid").is_none());
}

#[test]
fn invalid_configurations_are_typed_errors() {
    let bad = [
        WipeConfig {
            num_markers: 0,
            ..WipeConfig::default()
        },
        WipeConfig {
            line_width: -0.01,
            ..WipeConfig::default()
        },
        WipeConfig {
            distance_multiplier: 30.0,
            ..WipeConfig::default()
        },
        WipeConfig {
            ee_accel_penalty: 0.1,
            ..WipeConfig::default()
        },
        WipeConfig {
            table_height: 0.05,
            ..WipeConfig::default()
        },
        WipeConfig {
            table_full_size: [0.5, f64::NAN, 0.05],
            ..WipeConfig::default()
        },
    ];
    for config in bad {
        assert!(
            matches!(
                wipe_with(config.clone(), EnvConfig::default()),
                Err(Error::InvalidArgument { .. })
            ),
            "{config:?}"
        );
    }
    // A path area too small for a 5 mm step: the walk gives up with a typed error.
    let tight = WipeConfig {
        coverage_factor: 0.04,
        ..WipeConfig::default()
    };
    let mut env = wipe_with(tight, EnvConfig::default()).unwrap();
    assert!(matches!(
        env.reset(Some(0), None),
        Err(Error::Simulation(_))
    ));
    assert!(matches!(env.step(&act([0.0; 6])), Err(Error::ResetNeeded)));
}

#[test]
fn task_state_snapshots_and_bad_states() {
    let mut env = make_with("Wipe", EnvConfig::default().with_horizon(200)).unwrap();
    let mut actions = Vec::new();
    press_along(&mut env, 2, 60, &mut actions);
    // Starting an episode at a recorded reset repeats it.
    env.reset(Some(3), None).unwrap();
    let (state, task_state, first) = (env.get_state(), env.task().save_state(), env.observation());
    assert_eq!(task_state.len(), 4 * 100 + 9);
    env.reset(Some(4), None).unwrap();
    let (again, _) = env.reset_to_state(&task_state, &state).unwrap();
    assert_eq!(again, first);
    assert_eq!(env.task().save_state(), task_state);
    // Bad task states are refused and change nothing.
    let before = (env.get_state(), env.task().save_state());
    let mut half_wiped = task_state.clone();
    half_wiped[300] = 0.5;
    let mut nan = task_state.clone();
    nan[5] = f64::NAN;
    for bad in [&task_state[..400], &half_wiped[..], &nan[..]] {
        assert!(matches!(
            env.reset_to_state(bad, &state),
            Err(Error::InvalidArgument { .. })
        ));
        assert_eq!((env.get_state(), env.task().save_state()), before);
    }
    // Snapshots taken while wiping repeat the steps after them bit for bit: the wiped
    // markers, the force bias and the step's force come back with them.
    env.reset(Some(2), None).unwrap();
    assert_snapshot_replays(&mut env, &actions, 40);
}
