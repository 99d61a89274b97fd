//! Lift: observation layout, seeding, episode mechanics, reward / success, state, errors.

use crate::common::fixtures::robosuite_observations;
use crate::common::{action, get, zero};
use gym_core::{Env, Error, Info, Space, Value};
use robosuite_env::sim::{Sim, check_mujoco_version};
use robosuite_env::{
    EnvConfig, InitNoise, RobosuiteEnv, make, make_from_scene_xml, make_with, scene_xml,
};
use serde_json::json;

fn lift(config: EnvConfig) -> RobosuiteEnv {
    make_with("Lift", config).expect("Lift builds")
}

#[test]
fn model_sizes_and_names_match_robosuite() {
    let env = make("Lift").unwrap();
    let m = env.sim().model().ffi();
    assert_eq!((m.nq, m.nv, m.nu), (16, 15, 9));
    assert_eq!(env.get_state().len(), 1 + 16 + 15);
    assert_eq!(env.substeps(), 25);
    assert_eq!(env.sim().model().opt().timestep, 0.002);
    for name in [
        "robot0_joint1",
        "robot0_joint7",
        "gripper0_right_finger_joint1",
        "gripper0_right_finger_joint2",
        "cube_joint0",
    ] {
        assert!(
            robosuite_env::sim::joint_id(env.sim().model(), name).is_ok(),
            "{name}"
        );
    }
    for name in [
        "robot0_right_center",
        "gripper0_right_grip_site",
        "gripper0_right_ft_frame",
        "table_top",
    ] {
        assert!(
            robosuite_env::sim::site_id(env.sim().model(), name).is_ok(),
            "{name}"
        );
    }
    for name in [
        "gripper0_right_finger1_pad_collision",
        "gripper0_right_finger2_pad_collision",
        "cube_g0",
        "table_collision",
    ] {
        assert!(
            robosuite_env::sim::geom_id(env.sim().model(), name).is_ok(),
            "{name}"
        );
    }
    // Joint order: arm, gripper, object.
    let qadr = env.sim().model().jnt_qposadr().to_vec();
    assert_eq!(qadr, vec![0, 1, 2, 3, 4, 5, 6, 7, 8, 9]);
    assert!(check_mujoco_version().is_ok());
    // The arena stays small (robosuite reserves 1.2 GiB).
    assert!(env.sim().arena_bytes() <= 2 << 20);
}

#[test]
fn observation_keys_shapes_and_dtypes_match_robosuite() {
    let mut env = lift(EnvConfig::default());
    let space = env.observation_space().clone();
    let keys: Vec<&str> = space.keys().collect();
    let lift_obs = robosuite_observations("Lift");
    let expected: Vec<&str> = lift_obs.iter().map(|(k, _, _)| k.as_str()).collect();
    assert_eq!(keys, expected);
    let (obs, info) = env.reset(Some(0), None).unwrap();
    assert_eq!(info.get_bool("success"), Some(false));
    assert_eq!(obs.keys().map(String::as_str).collect::<Vec<_>>(), expected);
    for (key, shape, dtype) in &lift_obs {
        let Value::Array(a) = &obs[key.as_str()] else {
            panic!("{key} is not an array")
        };
        assert_eq!(a.shape(), shape.as_slice(), "{key}");
        assert_eq!(a.dtype(), *dtype, "{key}");
    }
    assert!(space.contains(&obs));
    // The concatenations hold the sensor values in order.
    let proprio = get(&obs, "robot0_proprio-state");
    let parts: Vec<f64> = lift_obs[..10]
        .iter()
        .flat_map(|(k, _, _)| get(&obs, k))
        .collect();
    assert_eq!(proprio, parts);
    let object = get(&obs, "object-state");
    let parts: Vec<f64> = lift_obs[10..13]
        .iter()
        .flat_map(|(k, _, _)| get(&obs, k))
        .collect();
    assert_eq!(object, parts);
    // gripper_to_cube_pos = cube_pos - eef_pos; cos/sin of the joints.
    let (cube, eef, g2c) = (
        get(&obs, "cube_pos"),
        get(&obs, "robot0_eef_pos"),
        get(&obs, "gripper_to_cube_pos"),
    );
    for i in 0..3 {
        assert_eq!(g2c[i], cube[i] - eef[i]);
    }
    let q = get(&obs, "robot0_joint_pos");
    assert_eq!(
        get(&obs, "robot0_joint_pos_cos"),
        q.iter().map(|v| v.cos()).collect::<Vec<_>>()
    );
    // Action space [-1, 1]^7.
    let act = env.action_space();
    assert_eq!(act.shape(), Some(&[7][..]));
    assert!(act.low().iter().all(|v| *v == -1.0) && act.high().iter().all(|v| *v == 1.0));
}

#[test]
fn object_observations_can_be_turned_off() {
    let mut env = lift(EnvConfig::default().with_object_obs(false));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let keys: Vec<&str> = obs.keys().map(String::as_str).collect();
    let lift_obs = robosuite_observations("Lift");
    let expected: Vec<&str> = lift_obs
        .iter()
        .map(|(k, _, _)| k.as_str())
        .filter(|k| !k.starts_with("cube") && !k.starts_with("gripper_to") && *k != "object-state")
        .collect();
    assert_eq!(keys, expected);
    assert!(env.observation_space().contains(&obs));
}

#[test]
fn noise_free_home_pose_matches_robosuite() {
    let mut env = lift(EnvConfig::default().with_initialization_noise(InitNoise::none()));
    let (obs, _) = env.reset(Some(0), None).unwrap();
    let eef = get(&obs, "robot0_eef_pos");
    for (a, b) in eef.iter().zip([-0.102768, 0.0, 1.011044]) {
        assert!((a - b).abs() < 1e-6, "eef {eef:?}");
    }
    assert_eq!(get(&obs, "robot0_gripper_qpos"), [0.020833, -0.020833]);
    // Zero actions hold the pose.
    for _ in 0..40 {
        let _ = env.step(&zero()).unwrap();
    }
    let obs = env.observation();
    assert!(get(&obs, "robot0_joint_vel").iter().all(|v| v.abs() < 1e-6));
    let eef2 = get(&obs, "robot0_eef_pos");
    assert!(eef.iter().zip(&eef2).all(|(a, b)| (a - b).abs() < 1e-5));
}

#[test]
fn same_seed_gives_identical_resets_and_trajectories() {
    let run = |env: &mut RobosuiteEnv, seed: u64| {
        let (first, _) = env.reset(Some(seed), None).unwrap();
        let mut rng = gym_core::rng_from_seed(11);
        let mut traj = vec![first];
        for _ in 0..15 {
            let a = env.action_space().sample(&mut rng);
            traj.push(env.step(&a).unwrap().observation);
        }
        (traj, env.get_state(), env.rng().cloned())
    };
    let mut a = lift(EnvConfig::default());
    let mut b = lift(EnvConfig::default());
    let (ta, sa, ra) = run(&mut a, 5);
    let (tb, sb, rb) = run(&mut b, 5);
    assert_eq!(ta, tb);
    assert_eq!(
        sa.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
        sb.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    );
    assert_eq!(ra, rb);
    // Re-seeding the same env reproduces it; another seed differs; `None` continues the stream.
    let (tc, _, _) = run(&mut a, 5);
    assert_eq!(ta, tc);
    let (td, _, _) = run(&mut b, 6);
    assert_ne!(ta[0], td[0]);
    let (o1, _) = a.reset(None, None).unwrap();
    let (o2, _) = b.reset(None, None).unwrap();
    assert_ne!(o1, ta[0]);
    assert_ne!(o1, o2);
    // A seed in the config seeds the first reset.
    let mut c = lift(EnvConfig::default().with_seed(5));
    let mut d = lift(EnvConfig::default().with_seed(5));
    assert_eq!(
        c.reset(None, None).unwrap().0,
        d.reset(None, None).unwrap().0
    );
    assert_eq!(c.reset(None, None).unwrap().0, a_reset_twice(5));
}

fn a_reset_twice(seed: u64) -> gym_core::DictValue {
    let mut e = lift(EnvConfig::default());
    e.reset(Some(seed), None).unwrap();
    e.reset(None, None).unwrap().0
}

#[test]
fn reset_randomises_the_cube_in_place_like_a_recompile() {
    let mut env = lift(EnvConfig::default());
    let cube = robosuite_env::sim::body_id(env.sim().model(), "cube_main").unwrap();
    let geom = robosuite_env::sim::geom_id(env.sim().model(), "cube_g0").unwrap();
    let mut sizes = Vec::new();
    for seed in 0..4 {
        let (obs, _) = env.reset(Some(seed), None).unwrap();
        let m = env.sim().model();
        let h = m.geom_size()[geom];
        assert!(h.iter().all(|v| (0.020..=0.022).contains(v)), "{h:?}");
        sizes.push(h);
        // Mass and inertia of a solid box of density 1000.
        let mass = 1000.0 * 8.0 * h[0] * h[1] * h[2];
        assert!((m.body_mass()[cube] - mass).abs() < 1e-12);
        // Placement: within ±0.03 of the table centre, 1 cm above the table, upright.
        let p = get(&obs, "cube_pos");
        assert!(p[0].abs() <= 0.03 && p[1].abs() <= 0.03);
        assert!((p[2] - (0.8 + 0.01 + h[2])).abs() < 1e-12);
        let q = get(&obs, "cube_quat");
        assert!(q[0].abs() < 1e-12 && q[1].abs() < 1e-12);

        // The same model compiled from scratch with this cube size has the same constants.
        let spec = robosuite_env::tasks::LiftSpec {
            cube_size_min: h,
            cube_size_max: h,
            ..Default::default()
        };
        let assets = robosuite_env::assets::Assets::locate().unwrap();
        let scene =
            robosuite_env::env::compose_scene(&spec, &EnvConfig::default(), &assets).unwrap();
        let memory = robosuite_env::tasks::TaskSpec::memory(&spec);
        let fresh = Sim::new(scene.compile(memory).unwrap()).unwrap();
        let f = fresh.model();
        assert!((f.body_mass()[cube] - m.body_mass()[cube]).abs() < 1e-12);
        for i in 0..3 {
            assert!((f.body_inertia()[cube][i] - m.body_inertia()[cube][i]).abs() < 1e-12);
        }
        assert!((f.geom_rbound()[geom] - m.geom_rbound()[geom]).abs() < 1e-12);
        assert!((f.body_subtreemass()[0] - m.body_subtreemass()[0]).abs() < 1e-9);
        assert_eq!(f.geom_aabb()[geom], m.geom_aabb()[geom]);
        let (fs, ms) = (f.stat(), m.stat());
        assert!(
            (fs.meaninertia - ms.meaninertia).abs() < 1e-12 * fs.meaninertia,
            "{} {}",
            fs.meaninertia,
            ms.meaninertia
        );
        assert!(
            (fs.meanmass - ms.meanmass).abs() < 1e-12 * fs.meanmass,
            "{} {}",
            fs.meanmass,
            ms.meanmass
        );
        assert!(
            (fs.meansize - ms.meansize).abs() < 1e-12,
            "{} {}",
            fs.meansize,
            ms.meansize
        );
        for (x, y) in f.dof_length().iter().zip(m.dof_length()) {
            assert!((x - y).abs() < 1e-12, "dof_length {x} {y}");
        }
        for (x, y) in f.body_invweight0().iter().zip(m.body_invweight0()) {
            assert!(
                (x[0] - y[0]).abs() <= 1e-12 * x[0].abs().max(1.0)
                    && (x[1] - y[1]).abs() <= 1e-12 * x[1].abs().max(1.0)
            );
        }
        for (x, y) in f.dof_invweight0().iter().zip(m.dof_invweight0()) {
            assert!((x - y).abs() <= 1e-12 * x.abs().max(1.0));
        }
    }
    assert_ne!(sizes[0], sizes[1]);
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let mut env = lift(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let cube_z = 1 + 9 + 2; // [time, qpos...]: cube free joint starts at qpos 9.
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
    let mut state = env.get_state();
    state[cube_z] = 0.85;
    env.set_state(&state).unwrap();
    assert!(env.check_success());
    assert!((env.reward() - 1.0).abs() < 1e-12);
    let obs = env.observation();
    assert!((get(&obs, "cube_pos")[2] - 0.85).abs() < 1e-12);
    // 4 cm above the table is the threshold.
    state[cube_z] = 0.8 + 0.04 - 1e-9;
    env.set_state(&state).unwrap();
    assert!(!env.check_success());

    // Unnormalised: 2.25 on success.
    let mut raw = lift(EnvConfig::default().with_reward_scale(None));
    raw.reset(Some(0), None).unwrap();
    let mut s = raw.get_state();
    s[cube_z] = 0.85;
    raw.set_state(&s).unwrap();
    assert_eq!(raw.reward(), 2.25);
    // Scale 3: 3 on success.
    let mut scaled = lift(EnvConfig::default().with_reward_scale(Some(3.0)));
    scaled.reset(Some(0), None).unwrap();
    scaled.set_state(&s).unwrap();
    assert!((scaled.reward() - 3.0).abs() < 1e-12);

    // Shaped reaching reward: (1 - tanh(10 d)) / 2.25 without a grasp.
    let mut shaped = lift(EnvConfig::default().with_reward_shaping(true));
    let (obs, _) = shaped.reset(Some(0), None).unwrap();
    let g2c = get(&obs, "gripper_to_cube_pos");
    let d = g2c.iter().map(|v| v * v).sum::<f64>().sqrt();
    assert!((shaped.reward() - (1.0 - (10.0 * d).tanh()) / 2.25).abs() < 1e-12);
    let mut s = shaped.get_state();
    s[cube_z] = 0.85;
    shaped.set_state(&s).unwrap();
    assert!((shaped.reward() - 1.0).abs() < 1e-12);
    // Dropped from 0.9 the cube is still 4 cm up after one step (0.05 s).
    s[cube_z] = 0.9;
    shaped.set_state(&s).unwrap();
    let step = shaped.step(&zero()).unwrap();
    assert!((step.reward - 1.0).abs() < 1e-12);
    assert_eq!(step.info.get_bool("success"), Some(true));
}

#[test]
fn horizon_truncates_and_ends_the_episode() {
    let mut env = lift(EnvConfig::default().with_horizon(3));
    assert_eq!(env.step(&zero()), Err(Error::ResetNeeded));
    env.reset(Some(0), None).unwrap();
    for t in 1..=3 {
        let s = env.step(&zero()).unwrap();
        assert!(!s.terminated);
        assert_eq!(s.truncated, t == 3);
        assert_eq!(s.info.get_bool("success"), Some(false));
    }
    assert_eq!(env.step(&zero()), Err(Error::EpisodeEnded));
    env.reset(None, None).unwrap();
    assert!(env.step(&zero()).is_ok());

    let mut forever = lift(EnvConfig::default().with_horizon(2).with_ignore_done(true));
    forever.reset(Some(0), None).unwrap();
    for _ in 0..5 {
        let s = forever.step(&zero()).unwrap();
        assert!(!s.truncated && !s.terminated);
    }
    assert_eq!(forever.timestep(), 5);
}

#[test]
fn bad_actions_are_typed_errors_and_leave_the_env_usable() {
    let mut env = lift(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let before = env.get_state();
    let bad = [
        ndarray::ArrayD::zeros(ndarray::IxDyn(&[6])),
        ndarray::ArrayD::zeros(ndarray::IxDyn(&[8])),
        ndarray::ArrayD::zeros(ndarray::IxDyn(&[7, 1])),
        action([0.0, f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0]),
        action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, f64::INFINITY]),
        action([f64::NEG_INFINITY, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]),
    ];
    for a in &bad {
        assert!(matches!(env.step(a), Err(Error::InvalidAction(_))), "{a:?}");
    }
    assert_eq!(env.get_state(), before);
    assert_eq!(env.timestep(), 0);
    // Out-of-range values are clipped by the controllers, as in robosuite.
    let big = env
        .step(&action([5.0, 0.0, 0.0, 0.0, 0.0, 0.0, -3.0]))
        .unwrap();
    let mut twin = lift(EnvConfig::default());
    twin.reset(Some(0), None).unwrap();
    let clipped = twin
        .step(&action([1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0]))
        .unwrap();
    assert_eq!(big.observation, clipped.observation);
    // Unknown reset options are rejected; closing is final and idempotent.
    let opts = Info::new().with("foo", 1i64);
    assert!(matches!(
        env.reset(None, Some(&opts)),
        Err(Error::UnknownKey { .. })
    ));
    env.close();
    env.close();
    assert_eq!(env.step(&zero()), Err(Error::Closed));
    assert!(matches!(env.reset(None, None), Err(Error::Closed)));
}

#[test]
fn state_round_trip() {
    let mut env = lift(EnvConfig::default());
    env.reset(Some(2), None).unwrap();
    for _ in 0..5 {
        let _ = env
            .step(&action([0.5, -0.3, 0.2, 0.1, 0.0, -0.2, 1.0]))
            .unwrap();
    }
    let saved = env.get_state();
    env.set_state(&saved).unwrap();
    let obs_saved = env.observation();
    for _ in 0..5 {
        let _ = env
            .step(&action([-0.5, 0.3, 0.2, 0.0, 0.0, 0.0, -1.0]))
            .unwrap();
    }
    assert_ne!(env.get_state(), saved);
    env.set_state(&saved).unwrap();
    assert_eq!(env.get_state(), saved);
    // Everything but the accelerations (which also depend on the controls, not part of the
    // state, as in robosuite) is restored exactly.
    let obs = env.observation();
    for (key, value) in &obs_saved {
        if key != "robot0_joint_acc" && key != "robot0_proprio-state" {
            assert_eq!(&obs[key], value, "{key}");
        }
    }
    assert!(matches!(
        env.set_state(&saved[1..]),
        Err(Error::InvalidArgument { .. })
    ));
    let mut nan = saved.clone();
    nan[3] = f64::NAN;
    assert!(matches!(
        env.set_state(&nan),
        Err(Error::InvalidArgument { .. })
    ));
    assert_eq!(env.get_state(), saved);
}

#[test]
fn configuration_errors_list_valid_values() {
    match make("Lfit") {
        Err(Error::UnknownEnv { id, available }) => {
            assert_eq!(id, "Lfit");
            assert!(available.contains(&"Lift".to_owned()));
        }
        other => panic!("expected UnknownEnv, got {other:?}"),
    }
    let err = make_with("Lift", EnvConfig::default().with_robots(["Sawyr"])).unwrap_err();
    assert!(
        matches!(&err, Error::InvalidArgument { name, reason } if name == "robots"
            && ["Panda", "Sawyer", "IIWA", "Jaco", "Kinova3", "UR5e", "XArm7"].iter().all(|r| reason.contains(r))),
        "{err}"
    );
    let err = make_with("Lift", EnvConfig::default().with_robots(["Panda", "Panda"])).unwrap_err();
    assert!(matches!(err, Error::InvalidArgument { .. }));
    assert!(matches!(
        make_with("Lift", EnvConfig::default().with_horizon(0)),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        make_with("Lift", EnvConfig::default().with_control_freq(0.0)),
        Err(Error::InvalidArgument { .. })
    ));
    assert!(matches!(
        make_with("Lift", EnvConfig::default().with_control_freq(1000.0)),
        Err(Error::InvalidArgument { .. })
    ));
    let noisy = InitNoise {
        magnitude: -1.0,
        ..InitNoise::default()
    };
    assert!(matches!(
        make_with(
            "Lift",
            EnvConfig::default().with_initialization_noise(noisy)
        ),
        Err(Error::InvalidArgument { .. })
    ));
    let ctrl = robosuite_env::controllers::ArmControllerConfig::OscPose(
        robosuite_env::controllers::config::OscConfig::default().with_kp(f64::NAN),
    );
    assert!(matches!(
        make_with("Lift", EnvConfig::default().with_controller(ctrl)),
        Err(Error::InvalidArgument { .. })
    ));
    // control_freq 30 gives int(0.0333 / 0.002) = 16 substeps, as robosuite.
    assert_eq!(
        lift(EnvConfig::default().with_control_freq(30.0)).substeps(),
        16
    );

    // Keyword arguments (the registry path).
    let kwargs = json!({"horizon": 7, "reward_shaping": true, "seed": 3});
    let c = EnvConfig::from_kwargs("Lift", kwargs.as_object().unwrap()).unwrap();
    assert_eq!(
        (c.horizon, c.reward_shaping, c.seed),
        (7, Some(true), Some(3))
    );
    assert!(matches!(
        EnvConfig::from_kwargs("Lift", json!({"horizn": 7}).as_object().unwrap()),
        Err(Error::UnknownKey { .. })
    ));
    assert!(matches!(
        EnvConfig::from_kwargs("Lift", json!({"horizon": "x"}).as_object().unwrap()),
        Err(Error::InvalidArgument { .. })
    ));
}

#[test]
fn registry_makes_boxed_envs() {
    robosuite_env::register_envs();
    let mut env = gym_core::registry::make("Lift", &json!({"horizon": 2})).unwrap();
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert!(env.observation_space().contains(&obs));
    let a = env.action_space().sample(&mut gym_core::rng_from_seed(0));
    assert!(!env.step(&a).unwrap().truncated);
    assert!(env.step(&a).unwrap().truncated);
    assert!(matches!(
        gym_core::registry::make("Nope", &json!({})),
        Err(Error::UnknownEnv { .. })
    ));
}

#[test]
fn supplied_scene_xml_builds_the_task() {
    let xml = scene_xml("Lift", &EnvConfig::default()).unwrap();
    let mut env = make_from_scene_xml("Lift", &xml, EnvConfig::default()).unwrap();
    assert_eq!(env.model_source(), robosuite_env::ModelSource::Supplied);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert!(env.observation_space().contains(&obs));
    // Sizes are kept as the file gives them (the composed cube: the middle of its range).
    let geom = robosuite_env::sim::geom_id(env.sim().model(), "cube_g0").unwrap();
    let mid = 0.5 * (0.020 + 0.022);
    assert_eq!(env.sim().model().geom_size()[geom], [mid; 3]);
    assert!((get(&obs, "cube_pos")[2] - (0.81 + mid)).abs() < 1e-12);
    let _ = env.step(&zero()).unwrap();

    // Errors are typed and never abort.
    assert!(matches!(
        make_from_scene_xml("Lift", "<mujoco><worldbody>", EnvConfig::default()),
        Err(Error::Model(_))
    ));
    assert!(matches!(
        make_from_scene_xml("Lift", "not xml \0 at all", EnvConfig::default()),
        Err(Error::Model(_))
    ));
    let no_cube = xml.replace("cube_joint0", "other_joint");
    assert!(matches!(
        make_from_scene_xml("Lift", &no_cube, EnvConfig::default()),
        Err(Error::Model(_))
    ));
    let empty = "<mujoco><worldbody><geom type='plane' size='1 1 1'/></worldbody></mujoco>";
    assert!(matches!(
        make_from_scene_xml("Lift", empty, EnvConfig::default()),
        Err(Error::Model(_))
    ));
    let missing = RobosuiteEnv::from_scene_file(
        robosuite_env::make_task("Lift").unwrap().as_ref(),
        "/nonexistent/scene.xml",
        EnvConfig::default(),
    );
    assert!(matches!(missing, Err(Error::Model(_))));
}

#[test]
fn gripper_integrator_follows_the_sign_of_the_action() {
    let mut env = lift(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let command = |e: &RobosuiteEnv| {
        e.robots()[0]
            .arm()
            .gripper()
            .controller()
            .command()
            .to_vec()
    };
    let ctrl = |e: &RobosuiteEnv| e.sim().data().ctrl()[7..9].to_vec();
    assert_eq!(command(&env), [0.0, 0.0]);
    let _ = env
        .step(&action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.3]))
        .unwrap();
    assert_eq!(command(&env), [-0.2, 0.2]);
    assert!((ctrl(&env)[0] - 0.016).abs() < 1e-15 && (ctrl(&env)[1] + 0.016).abs() < 1e-15);
    for _ in 0..9 {
        let _ = env
            .step(&action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]))
            .unwrap();
    }
    assert_eq!(command(&env), [-1.0, 1.0]);
    assert_eq!(ctrl(&env), [0.0, 0.0]);
    let closed = get(&env.observation(), "robot0_gripper_qpos");
    // robosuite: 10 closing steps take the fingers from 0.0208 to 0.0013.
    assert!(
        (closed[0] - 0.0013).abs() < 0.001 && (closed[1] + 0.0013).abs() < 0.001,
        "{closed:?}"
    );
    let _ = env.step(&zero()).unwrap();
    assert_eq!(command(&env), [-1.0, 1.0]);
    for _ in 0..10 {
        let _ = env
            .step(&action([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.01]))
            .unwrap();
    }
    assert_eq!(command(&env), [1.0, -1.0]);
    assert_eq!(ctrl(&env), [0.04, -0.04]);
    let open = get(&env.observation(), "robot0_gripper_qpos");
    // ... and 10 opening steps to 0.033.
    assert!(
        (open[0] - 0.033).abs() < 0.001 && (open[1] + 0.033).abs() < 0.001,
        "{open:?}"
    );
    env.reset(None, None).unwrap();
    assert_eq!(command(&env), [0.0, 0.0]);
}

#[test]
fn a_deterministic_reset_is_robosuites_posture_without_noise_fingers_left_as_the_scene_has_them() {
    let mut env = lift(EnvConfig::default().with_seed(3));
    env.reset(None, None).unwrap();
    for _ in 0..5 {
        let _ = env
            .step(&action([0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]))
            .unwrap();
    }
    let rng_before = env.rng_state();
    env.reset_deterministic().unwrap();
    let robot = &env.robots()[0];
    let qpos = env.sim().data().qpos();
    let arm: Vec<f64> = robot.joint_qpos().iter().map(|&a| qpos[a]).collect();
    assert_eq!(arm, robot.init_qpos());
    // robosuite's `robot.reset(deterministic=True)` does not touch the fingers: after the
    // data reset they are at the model's qpos0, not at the gripper's init_qpos.
    let qpos0 = env.sim().model().qpos0();
    for &a in robot.arm().gripper().qpos() {
        assert_eq!(qpos[a], qpos0[a]);
    }
    assert_ne!(
        robot.arm().gripper().info().init_qpos.map(|q| q[0]),
        Some(qpos0[robot.arm().gripper().qpos()[0]])
    );
    // Nothing drawn from the RNG.
    assert_eq!(env.rng_state(), rng_before);
}

#[test]
fn an_inactive_observable_leaves_the_observation_but_keeps_its_value() {
    use robosuite_env::ObservableFlag;
    let mut env = lift(EnvConfig::default().with_seed(1));
    let (obs, _) = env.reset(None, None).unwrap();
    env.modify_observable("cube_pos", ObservableFlag::Active, false)
        .unwrap();
    let after = env.observation();
    assert!(after.get("cube_pos").is_none());
    assert_eq!(
        get(&env.all_observations(), "cube_pos"),
        get(&obs, "cube_pos")
    );
    // The object-state concatenation shrinks by the three values.
    assert_eq!(
        get(&after, "object-state").len() + 3,
        get(&obs, "object-state").len()
    );
    assert!(matches!(
        env.modify_observable("nope", ObservableFlag::Active, false),
        Err(Error::UnknownKey { .. })
    ));
}

/// The model fields a box resize changes (sizes, masses, inertias and what MuJoCo derives
/// from them).
fn resize_fields(env: &RobosuiteEnv) -> Vec<f64> {
    let m = env.sim().model();
    let mut out: Vec<f64> = Vec::new();
    out.extend(m.geom_size().iter().flatten());
    out.extend(m.geom_rbound());
    out.extend(m.body_mass());
    out.extend(m.body_inertia().iter().flatten());
    out.extend(m.body_subtreemass());
    out.extend(m.dof_invweight0());
    out.extend(m.body_invweight0().iter().flatten());
    let stat = &m.ffi().stat;
    out.extend([stat.meanmass, stat.meaninertia, stat.meansize]);
    out
}

fn assert_close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: lengths");
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!(
            (x - y).abs() <= tol * x.abs().max(y.abs()).max(1.0),
            "{what}[{i}]: {x} vs {y}"
        );
    }
}

/// The Lift scene robosuite 1.5.2 saved (its `env.sim.model.get_xml()`, as in every
/// demonstration it records) with the cube's half-extents scaled by `scale`.
fn saved_lift_scene(scale: f64) -> String {
    use std::io::Read;
    let path = crate::common::fixtures::fixture_dir()
        .parent()
        .unwrap()
        .join("scenes/Lift-Panda.xml.gz");
    let mut xml = String::new();
    flate2::read::GzDecoder::new(std::fs::File::open(&path).unwrap())
        .read_to_string(&mut xml)
        .unwrap();
    let mut out = String::new();
    let mut rest = xml.as_str();
    for name in ["name=\"cube_g0\" size=\"", "name=\"cube_g0_vis\" size=\""] {
        let at = rest.find(name).expect("the cube geom") + name.len();
        let end = at + rest[at..].find('"').unwrap();
        let sizes: Vec<String> = rest[at..end]
            .split_whitespace()
            .map(|v| format!("{}", v.parse::<f64>().unwrap() * scale))
            .collect();
        out.push_str(&rest[..at]);
        out.push_str(&sizes.join(" "));
        rest = &rest[end..];
    }
    out.push_str(rest);
    out
}

#[test]
fn reset_from_xml_string_loads_a_resized_scene_in_place() {
    // Two scenes as robosuite saves them per episode: equal but for the cube's size.
    let (xml_a, xml_b) = (saved_lift_scene(0.99), saved_lift_scene(1.0317));
    let mut env = make("Lift").unwrap();
    // observable flags are kept by both kinds of load
    let flag = robosuite_env::ObservableFlag::Active;
    env.modify_observable("robot0_joint_pos", flag, true)
        .unwrap();
    let flags = env.observables();
    let (first, _, load) = env.reset_from_xml_string(&xml_a).unwrap();
    assert_eq!(load, robosuite_env::SceneLoad::Compiled);
    assert_eq!(env.observables(), flags);
    assert!(first.contains_key("robot0_joint_pos"));
    let model_ptr = env.sim().model().ffi() as *const _;
    env.reset(Some(3), None).unwrap(); // a reset draws another cube size: overwritten below
    let (obs, _, load) = env.reset_from_xml_string(&xml_b).unwrap();
    assert_eq!(env.observables(), flags);
    assert_eq!(load, robosuite_env::SceneLoad::InPlace);
    assert_eq!(
        env.sim().model().ffi() as *const _,
        model_ptr,
        "the same model, overwritten"
    );

    // The same env as one built on scene B: model, objects, observations and a trajectory.
    let mut fresh = make_from_scene_xml("Lift", &xml_b, EnvConfig::default()).unwrap();
    let (fresh_obs, _) = fresh.reset_deterministic().unwrap();
    assert_close(&resize_fields(&env), &resize_fields(&fresh), 1e-12, "model");
    assert_eq!(env.mujoco_objects(), fresh.mujoco_objects());
    let cube = robosuite_env::sim::geom_id(env.sim().model(), "cube_g0").unwrap();
    let half = env.sim().model().geom_size()[cube];
    let a_env = make_from_scene_xml("Lift", &xml_a, EnvConfig::default()).unwrap();
    assert!((half[0] / a_env.sim().model().geom_size()[cube][0] - 1.0317 / 0.99).abs() < 1e-6);
    for key in ["cube_pos", "robot0_eef_pos", "robot0_joint_pos_cos"] {
        assert_close(&get(&obs, key), &get(&fresh_obs, key), 1e-12, key);
    }
    for t in 0..20 {
        let a = action([
            0.3,
            -0.2,
            -0.4,
            0.0,
            0.0,
            0.1,
            if t < 10 { -1.0 } else { 1.0 },
        ]);
        let (x, y) = (env.step(&a).unwrap(), fresh.step(&a).unwrap());
        let key = "cube_pos";
        assert_close(
            &get(&x.observation, key),
            &get(&y.observation, key),
            1e-9,
            key,
        );
        assert_close(&env.get_state(), &fresh.get_state(), 1e-9, "state");
    }

    // Bad scenes are refused and change nothing.
    let before = env.get_state();
    for bad in ["<mujoco><worldbody>", "no xml \0 here"] {
        assert!(matches!(
            env.reset_from_xml_string(bad),
            Err(Error::Model(_))
        ));
        assert_eq!(env.get_state(), before);
    }
    let _ = env.step(&zero()).unwrap();
}
