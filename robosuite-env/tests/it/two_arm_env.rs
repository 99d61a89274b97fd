//! The two-arm tasks (TwoArmLift, TwoArmPegInHole, TwoArmHandover): observation layouts
//! against robosuite's probes, robot set-ups (`env_configuration`, mixed pairs, per-arm
//! controllers), hand-set states, per-reset sizes, scripted success and bad input.

use crate::common::fixtures::{config_for, load};
use crate::common::get;
use gym_core::{Env, Error, Space};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::sim::{body_id, geom_id, joint_id};
use robosuite_env::{EnvConfig, EnvConfiguration, RobosuiteEnv, make, make_with};

fn pandas(task: &str, configuration: EnvConfiguration) -> RobosuiteEnv {
    make_with(
        task,
        EnvConfig::default()
            .with_robots(["Panda", "Panda"])
            .with_env_configuration(configuration),
    )
    .unwrap_or_else(|e| panic!("{task}: {e}"))
}

fn zeros(n: usize) -> ArrayD<f64> {
    ArrayD::zeros(IxDyn(&[n]))
}

fn invalid_argument(result: Result<RobosuiteEnv, Error>) -> (String, String) {
    match result {
        Err(Error::InvalidArgument { name, reason }) => (name, reason),
        Err(other) => panic!("expected InvalidArgument, got {other}"),
        Ok(_) => panic!("expected InvalidArgument, got an environment"),
    }
}

#[test]
fn observation_layouts_and_action_spaces_equal_robosuites() {
    // The keys, shapes and dtypes: `observation_layouts.rs`, for both set-ups.
    for (task, dim) in [
        ("TwoArmLift", 14),
        ("TwoArmPegInHole", 12),
        ("TwoArmHandover", 14),
        ("TwoArmTransport", 14),
    ] {
        for configuration in [EnvConfiguration::Opposed, EnvConfiguration::Parallel] {
            let mut env = pandas(task, configuration);
            let (obs, info) = env.reset(Some(1), None).unwrap();
            assert_eq!(info.get_bool("success"), Some(false), "{task}");
            assert!(env.observation_space().contains(&obs), "{task}");
            assert_eq!(env.action_dim(), dim, "{task}");
            assert!(env.action_space().low().iter().all(|v| *v == -1.0));
            assert!(env.action_space().high().iter().all(|v| *v == 1.0));
            assert_eq!(env.config().env_configuration, configuration, "{task}");
        }
    }
}

#[test]
fn default_robots_are_two_pandas_opposed() {
    for task in [
        "TwoArmLift",
        "TwoArmPegInHole",
        "TwoArmHandover",
        "TwoArmTransport",
    ] {
        let env = make(task).unwrap();
        assert_eq!(env.config().robots, ["Panda", "Panda"], "{task}");
        assert_eq!(env.config().env_configuration, EnvConfiguration::Opposed);
    }
}

#[test]
fn opposed_bases_face_each_other_and_parallel_ones_stand_side_by_side() {
    let base = |env: &RobosuiteEnv, i: usize| {
        let m = env.sim().model();
        let b = body_id(m, &format!("robot{i}_base")).unwrap();
        (m.body_pos()[b], m.body_quat()[b])
    };
    let opposed = pandas("TwoArmLift", EnvConfiguration::Opposed);
    let ((p0, q0), (p1, q1)) = (base(&opposed, 0), base(&opposed, 1));
    // robosuite: (0, ∓0.56) at the table, turned ±90° about z.
    assert!(p0[0].abs() < 1e-12 && (p0[1] + 0.56).abs() < 1e-9, "{p0:?}");
    assert!(p1[0].abs() < 1e-12 && (p1[1] - 0.56).abs() < 1e-9, "{p1:?}");
    assert!((q0[0] - q0[3]).abs() < 1e-6 && (q1[0] + q1[3]).abs() < 1e-6);
    let parallel = pandas("TwoArmLift", EnvConfiguration::Parallel);
    let ((p0, _), (p1, _)) = (base(&parallel, 0), base(&parallel, 1));
    assert!((p0[0] + 0.56).abs() < 1e-9 && (p0[1] + 0.25).abs() < 1e-12);
    assert!((p1[0] + 0.56).abs() < 1e-9 && (p1[1] - 0.25).abs() < 1e-12);
    // Handover and Transport stand 25 cm further apart.
    let handover = pandas("TwoArmHandover", EnvConfiguration::Opposed);
    assert!((base(&handover, 0).0[1] + 0.81).abs() < 1e-9);
    assert!((base(&handover, 1).0[1] - 0.81).abs() < 1e-9);
}

#[test]
fn mixed_pairs_and_per_arm_controllers_work() {
    let mut env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["Panda", "UR5e"]),
    )
    .unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert_eq!(get(&obs, "robot1_joint_pos").len(), 6);
    assert_eq!(env.action_dim(), 7 + 7);
    assert!(!env.step(&zeros(14)).unwrap().done());
    let kwargs = serde_json::json!({"robots": ["Sawyer", "Panda"], "controller": "JOINT_VELOCITY"});
    let config = EnvConfig::from_kwargs("TwoArmHandover", kwargs.as_object().unwrap()).unwrap();
    let mut env = make_with("TwoArmHandover", config).unwrap();
    assert_eq!(env.action_dim(), 2 * (7 + 1));
    env.reset(Some(0), None).unwrap();
    assert!(!env.step(&zeros(16)).unwrap().done());
}

#[test]
fn pot_lifted_level_succeeds_and_tilted_past_30_degrees_earns_nothing() {
    let mut env = make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["Panda", "Panda"]),
    )
    .unwrap();
    env.reset(Some(3), None).unwrap();
    assert!(!env.check_success());
    let m = env.sim().model();
    let q = m.jnt_qposadr()[joint_id(m, "pot_joint0").unwrap()] as usize;
    let mut state = env.get_state();
    // Level, 12 cm above the table (bottom at 0.8 + 0.12).
    state[1 + q + 2] = 0.8 + 0.07 + 0.12;
    state[1 + q + 3..1 + q + 7].copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
    env.set_state(&state).unwrap();
    assert!(env.check_success());
    assert_eq!(env.reward(), 1.0);
    // Tilted by 40° about x: still high, but robosuite's direction coefficient is 0.
    let half = 40f64.to_radians() / 2.0;
    state[1 + q + 3..1 + q + 7].copy_from_slice(&[half.cos(), half.sin(), 0.0, 0.0]);
    env.set_state(&state).unwrap();
    assert!(env.check_success());
    assert_eq!(env.reward(), 0.0);
    // 20° is within the 30° cone.
    let half = 20f64.to_radians() / 2.0;
    state[1 + q + 3..1 + q + 7].copy_from_slice(&[half.cos(), half.sin(), 0.0, 0.0]);
    env.set_state(&state).unwrap();
    assert_eq!(env.reward(), 1.0);
    // Resting on the table: no success.
    state[1 + q + 2] = 0.8 + 0.07;
    state[1 + q + 3..1 + q + 7].copy_from_slice(&[1.0, 0.0, 0.0, 0.0]);
    env.set_state(&state).unwrap();
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
}

#[test]
fn pot_observations_follow_the_handles_and_grippers() {
    let mut env = make("TwoArmLift").unwrap();
    let (obs, _) = env.reset(Some(5), None).unwrap();
    for i in 0..2 {
        let (h, e, d) = (
            get(&obs, &format!("handle{i}_xpos")),
            get(&obs, &format!("robot{i}_eef_pos")),
            get(&obs, &format!("gripper{i}_to_handle{i}")),
        );
        for k in 0..3 {
            assert_eq!(d[k], h[k] - e[k]);
        }
    }
    // Handle 0 (+y of the pot, yawed by 120°-240°) is on robot 0's side (y < 0).
    assert!(get(&obs, "handle0_xpos")[1] < 0.0 && get(&obs, "handle1_xpos")[1] > 0.0);
}

#[test]
fn peg_radius_is_drawn_per_reset_without_recompiling() {
    let mut env = make("TwoArmPegInHole").unwrap();
    let m = env.sim().model();
    let (peg, g) = (
        body_id(m, "peg_main").unwrap(),
        geom_id(m, "peg_g0").unwrap(),
    );
    let mut radii = Vec::new();
    for seed in 0..6 {
        env.reset(Some(seed), None).unwrap();
        let r = env.task().save_state()[0];
        assert!((0.015..=0.03).contains(&r), "{r}");
        let m = env.sim().model();
        assert_eq!(m.geom_size()[g][..2], [r, 0.13]);
        let mass = 1000.0 * std::f64::consts::PI * r * r * 0.26;
        assert!((m.body_mass()[peg] - mass).abs() < 1e-12 * mass);
        radii.push(r);
    }
    radii.dedup();
    assert!(radii.len() > 1, "the radius changes between resets");
}

#[test]
fn peg_geometry_observables_follow_robosuites_formulae() {
    let mut env = make("TwoArmPegInHole").unwrap();
    let (obs, _) = env.reset(Some(2), None).unwrap();
    let d = env.sim().data();
    let m = env.sim().model();
    let (peg, hole) = (
        body_id(m, "peg_main").unwrap(),
        body_id(m, "hole_main").unwrap(),
    );
    let (pp, hp, pm, hm) = (d.xpos()[peg], d.xpos()[hole], d.xmat()[peg], d.xmat()[hole]);
    let v = [pm[2], pm[5], pm[8]];
    let c = [
        hp[0] + 0.1 * hm[0],
        hp[1] + 0.1 * hm[3],
        hp[2] + 0.1 * hm[6],
    ];
    let t: f64 = (0..3).map(|i| (c[i] - pp[i]) * v[i]).sum();
    let n = [hm[2], hm[5], hm[8]];
    let cos = (0..3).map(|i| n[i] * v[i]).sum::<f64>().abs();
    assert!((get(&obs, "t")[0] - t).abs() < 1e-12);
    assert!((get(&obs, "angle")[0] - cos).abs() < 1e-12);
    let to = get(&obs, "peg_to_hole");
    for i in 0..3 {
        assert_eq!(to[i], hp[i] - pp[i]);
    }
    // At rest the arms hold the peg far beside the hole: no success, sparse reward 0;
    // the shaped reward is the sum of the four terms.
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
}

#[test]
fn hammer_figures_are_drawn_per_reset_and_lifted_hammer_is_rewarded() {
    let mut env = make_with(
        "TwoArmHandover",
        EnvConfig::default().with_reward_shaping(true),
    )
    .unwrap();
    let m = env.sim().model();
    let handle = geom_id(m, "hammer_handle").unwrap();
    let mut lengths = Vec::new();
    for seed in 0..4 {
        env.reset(Some(seed), None).unwrap();
        let f = env.task().save_state();
        let (r, len, head) = (f[0], f[1], f[4]);
        assert!((0.015..=0.02).contains(&r) && (0.1..=0.25).contains(&len));
        assert!((r..=1.2 * r).contains(&head));
        assert_eq!(env.sim().model().geom_size()[handle], [r, r, len / 2.0]);
        lengths.push(len);
    }
    lengths.dedup();
    assert!(lengths.len() > 1);
    // On the table, untouched: 0.25 (1 − tanh d(gripper 0, handle)), scaled by 1/2.
    let (obs, _) = env.reset(Some(9), None).unwrap();
    let d0 = get(&obs, "gripper0_to_handle")
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    assert!((env.reward() - 0.25 * (1.0 - d0.tanh()) / 2.0).abs() < 1e-12);
    // Held up in the air by nobody: lifted, gripper 1 not grasping.
    let m = env.sim().model();
    let q = m.jnt_qposadr()[joint_id(m, "hammer_joint0").unwrap()] as usize;
    let mut state = env.get_state();
    state[1 + q + 2] += 0.3;
    env.set_state(&state).unwrap();
    let obs = env.observation();
    let d1 = get(&obs, "gripper1_to_handle")
        .iter()
        .map(|v| v * v)
        .sum::<f64>()
        .sqrt();
    assert!((env.reward() - (1.0 + 0.25 * (1.0 - d1.tanh())) / 2.0).abs() < 1e-12);
    assert!(!env.check_success());
}

#[test]
fn transport_places_the_group_and_rewards_only_success() {
    let mut env = make_with(
        "TwoArmTransport",
        EnvConfig::default().with_reward_shaping(true),
    )
    .unwrap();
    let (obs, _) = env.reset(Some(4), None).unwrap();
    // The lid on the start bin, the payload in it, the trash in the target bin.
    let (payload, trash, lid) = (
        get(&obs, "payload_pos"),
        get(&obs, "trash_pos"),
        get(&obs, "lid_handle_pos"),
    );
    let m = env.sim().model();
    let start = env.sim().data().xpos()[body_id(m, "transport_start_bin_root").unwrap()];
    let target = get(&obs, "target_bin_pos");
    assert!((payload[0] - start[0]).abs() < 1e-12 && (payload[1] - start[1]).abs() < 1e-12);
    assert!((lid[0] - start[0]).abs() < 1e-9 && lid[2] > start[2] + 0.075);
    assert!((trash[0] - target[0]).abs() < 1e-12 && (trash[1] - target[1]).abs() < 1e-12);
    assert!(
        start[1] < 0.0 && target[1] > 0.0,
        "table 0 at y < 0, table 1 at y > 0"
    );
    // The payload's head is drawn per reset; its other figures are fixed.
    let f = env.task().save_state();
    assert_eq!(f[..4], [0.015, 0.2, 150.0, 4.0]);
    assert!((0.015..=0.018).contains(&f[4]));
    // Shaping: robosuite warns, turns it off and returns 0; then sparse.
    let step = env.step(&zeros(14)).unwrap();
    assert_eq!(step.reward, 0.0);
    assert!(!env.check_success());
    // Let things settle: the trash rests on the target bin's base, not the trash bin's.
    for _ in 0..10 {
        assert!(!env.step(&zeros(14)).unwrap().done());
    }
    let obs = env.observation();
    assert_eq!(get(&obs, "payload_in_target_bin"), [0.0]);
    assert_eq!(get(&obs, "trash_in_trash_bin"), [0.0]);
    // Payload dropped into the target bin, trash into the trash bin: success, reward 1.
    let m = env.sim().model();
    let qpos = |j: &str| m.jnt_qposadr()[joint_id(m, j).unwrap()] as usize;
    let (p, t) = (qpos("payload_joint0"), qpos("trash_joint0"));
    let trash_bin = get(&obs, "trash_bin_pos");
    let mut state = env.get_state();
    state[1 + p..1 + p + 3].copy_from_slice(&[target[0], target[1], target[2] + 0.04]);
    state[1 + t..1 + t + 3].copy_from_slice(&[trash_bin[0], trash_bin[1], trash_bin[2] + 0.03]);
    env.set_state(&state).unwrap();
    let mut rewards = Vec::new();
    for _ in 0..10 {
        let step = env.step(&zeros(14)).unwrap();
        rewards.push(step.reward);
    }
    let obs = env.observation();
    assert_eq!(get(&obs, "payload_in_target_bin"), [1.0]);
    assert_eq!(get(&obs, "trash_in_trash_bin"), [1.0]);
    assert!(env.check_success());
    assert_eq!(rewards.last(), Some(&1.0));
}

#[test]
fn recorded_scripted_policies_reach_success() {
    for (fixture, at_least) in [
        ("TwoArmLift", 40),
        ("TwoArmLift-parallel", 40),
        ("TwoArmHandover", 10),
    ] {
        let f = load(fixture);
        let mut env = make_with(&f.task, config_for(&f)).unwrap();
        let rollout = &f.rollouts[0];
        assert_eq!(rollout.kind, "scripted");
        env.reset_to_state(&rollout.task_state, &rollout.init_state)
            .unwrap();
        let mut successes = 0;
        for a in &rollout.actions {
            let step = env
                .step(&ArrayD::from_shape_vec(IxDyn(&[a.len()]), a.clone()).unwrap())
                .unwrap();
            successes += usize::from(step.info.get_bool("success") == Some(true));
        }
        assert!(
            successes >= at_least,
            "{fixture}: {successes} successful steps"
        );
    }
}

#[test]
fn bad_robot_set_ups_are_typed_errors_listing_what_is_valid() {
    let (name, reason) = invalid_argument(make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["Panda"]),
    ));
    assert_eq!(name, "robots");
    assert!(
        reason.contains("bimanual") && reason.contains("Sawyer"),
        "{reason}"
    );
    let (name, reason) = invalid_argument(make_with(
        "TwoArmHandover",
        EnvConfig::default().with_robots(["Panda", "Panda", "Panda"]),
    ));
    assert_eq!(name, "robots");
    assert!(reason.contains("got 3 robots"), "{reason}");
    let (name, _) = invalid_argument(make_with(
        "TwoArmLift",
        EnvConfig::default()
            .with_robots(["Panda", "Panda"])
            .with_env_configuration(EnvConfiguration::SingleRobot),
    ));
    assert_eq!(name, "env_configuration");
    let (name, reason) = invalid_argument(make_with(
        "Lift",
        EnvConfig::default().with_env_configuration(EnvConfiguration::Opposed),
    ));
    assert_eq!(name, "env_configuration");
    assert!(reason.contains("default"), "{reason}");
    let (name, reason) = invalid_argument(make_with(
        "Lift",
        EnvConfig::default().with_robots(["Panda", "Panda"]),
    ));
    assert_eq!(name, "robots");
    assert!(reason.contains("needs 1"), "{reason}");
    let Err(Error::InvalidArgument { name, reason }) = EnvConfiguration::parse("diagonal") else {
        panic!("an unknown configuration is an error")
    };
    assert_eq!(name, "env_configuration");
    assert!(
        reason.contains("opposed") && reason.contains("parallel"),
        "{reason}"
    );
    let kwargs = serde_json::json!({"env_configuration": "diagonal"});
    assert!(matches!(
        EnvConfig::from_kwargs("TwoArmLift", kwargs.as_object().unwrap()),
        Err(Error::InvalidArgument { .. })
    ));
    // robosuite's older names still work.
    let kwargs = serde_json::json!({"env_configuration": "single-arm-parallel"});
    assert_eq!(
        EnvConfig::from_kwargs("TwoArmLift", kwargs.as_object().unwrap())
            .unwrap()
            .env_configuration,
        EnvConfiguration::Parallel
    );
    // TwoArmPegInHole's arms carry the peg and the plate: robosuite asserts no gripper.
    let (name, _) = invalid_argument(make_with(
        "TwoArmPegInHole",
        EnvConfig::default().with_gripper_types([
            robosuite_env::models::robots::GripperChoice::Named("PandaGripper".into()),
            robosuite_env::models::robots::GripperChoice::Default,
        ]),
    ));
    assert_eq!(name, "gripper_types");
}

#[test]
fn one_baxter_is_robosuites_single_robot_set_up() {
    for (task, dim) in [
        ("TwoArmLift", 14),
        ("TwoArmPegInHole", 12),
        ("TwoArmHandover", 14),
        ("TwoArmTransport", 14),
    ] {
        let mut env = make_with(task, EnvConfig::default().with_robots(["Baxter"])).unwrap();
        assert_eq!(
            env.config().env_configuration,
            EnvConfiguration::SingleRobot
        );
        assert_eq!(env.action_dim(), dim, "{task}");
        let (obs, _) = env.reset(Some(0), None).unwrap();
        let keys = env.observation_keys();
        for side in ["right", "left"] {
            assert!(keys.contains(&format!("robot0_{side}_eef_pos")), "{task}");
        }
        assert!(!keys.iter().any(|k| k.starts_with("robot1_")), "{task}");
        assert_eq!(get(&obs, "robot0_joint_pos").len(), 14);
        assert!(!env.step(&zeros(dim)).unwrap().done());
    }
    // Gripper 0 is the right arm, gripper 1 the left one.
    let mut env = make_with("TwoArmLift", EnvConfig::default().with_robots(["Baxter"])).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    for (i, side) in [(0, "right"), (1, "left")] {
        let (h, e, d) = (
            get(&obs, &format!("handle{i}_xpos")),
            get(&obs, &format!("robot0_{side}_eef_pos")),
            get(&obs, &format!("gripper{i}_to_handle{i}")),
        );
        for k in 0..3 {
            assert_eq!(d[k], h[k] - e[k]);
        }
    }
    // robosuite's demos name the one-bimanual-robot set-up "bimanual"; robosuite runs it as
    // `single-robot` (and refuses it for two robots).
    let parsed = robosuite_env::EnvConfiguration::parse("bimanual").unwrap();
    let config = EnvConfig::default()
        .with_robots(["Baxter"])
        .with_env_configuration(parsed);
    assert_eq!(
        make_with("TwoArmLift", config).unwrap().observation_keys(),
        env.observation_keys()
    );
    let two = EnvConfig::default()
        .with_robots(["Panda", "Panda"])
        .with_env_configuration(parsed);
    assert_eq!(
        invalid_argument(make_with("TwoArmLift", two)).0,
        "env_configuration"
    );
    // A single-arm task takes one robot (bimanual included); a bimanual robot does not
    // pair up.
    let (name, reason) = invalid_argument(make_with(
        "Lift",
        EnvConfig::default().with_robots(["Baxter", "Panda"]),
    ));
    assert_eq!(name, "robots");
    assert!(
        reason.contains("needs 1 robot") && reason.contains("Panda") && reason.contains("Tiago"),
        "{reason}"
    );
    let (name, reason) = invalid_argument(make_with(
        "TwoArmLift",
        EnvConfig::default().with_robots(["Baxter", "Panda"]),
    ));
    assert_eq!(name, "robots");
    assert!(reason.contains("Baxter"), "{reason}");
}

#[test]
fn every_controller_runs_on_both_of_baxters_arms() {
    let assets = robosuite_env::assets::Assets::locate().unwrap();
    for kind in robosuite_env::controllers::config::ARM_CONTROLLER_TYPES {
        let part =
            robosuite_env::controllers::config::load_part_controller_config(&assets, kind).unwrap();
        let config = robosuite_env::controllers::ControllerConfig::from_value(&part, "c").unwrap();
        let mut env = make_with(
            "TwoArmLift",
            EnvConfig::default()
                .with_robots(["Baxter"])
                .with_controller(config),
        )
        .unwrap_or_else(|e| panic!("{kind}: {e}"));
        let arm_dim = match *kind {
            "OSC_POSE" | "IK_POSE" => 6,
            "OSC_POSITION" => 3,
            _ => 7,
        };
        assert_eq!(env.action_dim(), 2 * arm_dim + 2, "{kind}");
        for arm in env.robots()[0].arms() {
            assert_eq!(arm.controller().name(), *kind);
        }
        env.reset(Some(0), None).unwrap();
        assert!(
            !env.step(&zeros(env.action_dim())).unwrap().done(),
            "{kind}"
        );
    }
}

#[test]
fn two_arm_episodes_are_deterministic() {
    for task in [
        "TwoArmLift",
        "TwoArmPegInHole",
        "TwoArmHandover",
        "TwoArmTransport",
    ] {
        let run = || {
            let mut env = make(task).unwrap();
            env.reset(Some(11), None).unwrap();
            let n = env.action_dim();
            let a = ArrayD::from_shape_fn(IxDyn(&[n]), |i| ((i[0] as f64) * 0.37).sin());
            for _ in 0..5 {
                assert!(!env.step(&a).unwrap().done());
            }
            env.get_state()
        };
        assert_eq!(run(), run(), "{task}");
    }
}
