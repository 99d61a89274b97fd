//! The PickPlace family: observation layouts, placement, single-object modes, hand-set
//! reward / success, a scripted policy, task states and the MuJoCo arena.

use crate::common::object_tasks::{
    PlacePolicy, arena_use, assert_spread, assert_task_states_rejected, assert_variant_layouts,
    body_pos, probe_actions, random_episodes, set_free_joint,
};
use crate::common::{action, assert_scripted_successes, assert_snapshot_replays, get};
use gym_core::{Env, Error};
use robosuite_env::tasks::common::ObjectMode;
use robosuite_env::tasks::{PICK_PLACE_OBJECTS, PickPlaceSpec};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

fn env(name: &str, config: EnvConfig) -> RobosuiteEnv {
    make_with(name, config).unwrap_or_else(|e| panic!("{name} builds: {e}"))
}

/// The objects' extents from robosuite's files: horizontal radius and bottom offset.
const EXTENTS: [(f64, f64); 4] = [
    (0.025, -0.085),
    (0.03, -0.045),
    (0.04, -0.10),
    (0.025, -0.06),
];

/// Puts object `name` upright at `pos`.
fn put(env: &mut RobosuiteEnv, name: &str, pos: [f64; 3]) {
    set_free_joint(env, &format!("{name}_joint0"), pos, [1.0, 0.0, 0.0, 0.0]);
}

#[test]
fn variants_have_robosuites_observation_layouts() {
    // Mode 1: robosuite names the keys after each reset's object; here they are `obj_*`,
    // followed by robosuite's `obj_id`.
    assert_variant_layouts(
        &[
            ("PickPlace", &PICK_PLACE_OBJECTS[..]),
            ("PickPlaceMilk", &["Milk"][..]),
            ("PickPlaceBread", &["Bread"][..]),
            ("PickPlaceCereal", &["Cereal"][..]),
            ("PickPlaceCan", &["Can"][..]),
        ],
        [37, 33, 9, 34, 126],
        "PickPlaceSingle",
        "obj",
    );
}

#[test]
fn placement_stays_in_bin_one_without_overlap() {
    let mut e = env("PickPlace", EnvConfig::default());
    let spec = PickPlaceSpec::default();
    let mut yaws = Vec::new();
    for seed in 0..20 {
        let (obs, _) = e.reset(Some(seed), None).unwrap();
        let p: Vec<Vec<f64>> = PICK_PLACE_OBJECTS
            .iter()
            .map(|n| get(&obs, &format!("{n}_pos")))
            .collect();
        for (i, a) in p.iter().enumerate() {
            let (r, bottom) = EXTENTS[i];
            assert!((a[0] - 0.1).abs() <= 0.145 - r + 1e-12, "{a:?}");
            assert!((a[1] + 0.25).abs() <= 0.195 - r + 1e-12, "{a:?}");
            assert!((a[2] - (0.8 - bottom)).abs() < 1e-12, "{a:?}");
            for (j, b) in p.iter().enumerate().skip(i + 1) {
                assert!((a[0] - b[0]).hypot(a[1] - b[1]) > r + EXTENTS[j].0);
            }
        }
        let q = get(&obs, "Milk_quat");
        assert!(q[0].abs() < 1e-12 && q[1].abs() < 1e-12, "yaw only: {q:?}");
        yaws.push(q[2].atan2(q[3]));
        // The visual targets sit at the centres of their quadrants of bin 2, every reset.
        for (i, name) in PICK_PLACE_OBJECTS.iter().enumerate() {
            let v = body_pos(&e, &format!("Visual{name}_main"));
            let t = spec.target_bin_placement(i);
            assert!(
                (v[0] - t[0]).abs() < 1e-12 && (v[1] - t[1]).abs() < 1e-12,
                "{name}: {v:?}"
            );
            assert!((v[2] - (0.8 - EXTENTS[i].1)).abs() < 1e-12, "{name}: {v:?}");
        }
    }
    assert_spread(&yaws);
}

#[test]
fn single_modes_keep_one_object_and_park_the_others() {
    let mut single = env("PickPlaceSingle", EnvConfig::default());
    let mut seen = [false; 4];
    for seed in 0..16 {
        let (obs, _) = single.reset(Some(seed), None).unwrap();
        let id = get(&obs, "obj_id")[0] as usize;
        seen[id] = true;
        for (i, name) in PICK_PLACE_OBJECTS.iter().enumerate() {
            let p = body_pos(&single, &format!("{name}_main"));
            if i == id {
                assert_eq!(get(&obs, "obj_pos"), p.to_vec());
                assert!(p[2] < 1.0, "the object in play is in bin 1: {p:?}");
            } else {
                assert_eq!(p, [10.0; 3], "{name} is parked");
            }
        }
        assert_eq!(single.task().save_state()[0], id as f64);
    }
    assert!(seen.iter().all(|s| *s), "every object is drawn: {seen:?}");
    let mut milk = env("PickPlaceMilk", EnvConfig::default());
    for seed in 0..3 {
        milk.reset(Some(seed), None).unwrap();
        assert!(body_pos(&milk, "Milk_main")[2] < 1.0);
        for name in ["Bread", "Cereal", "Can"] {
            assert_eq!(body_pos(&milk, &format!("{name}_main")), [10.0; 3]);
        }
    }
}

#[test]
fn reward_and_success_on_hand_set_states() {
    let spec = PickPlaceSpec::default();
    let t = spec.target_bin_placement(3);
    let mut can = env("PickPlaceCan", EnvConfig::default());
    can.reset(Some(0), None).unwrap();
    put(&mut can, "Can", [t[0], t[1], 0.87]);
    assert!(can.check_success());
    assert_eq!(can.reward(), 1.0);
    // The milk's quadrant is not the can's; 10 cm above the bin's centre height is not in it.
    let t0 = spec.target_bin_placement(0);
    put(&mut can, "Can", [t0[0], t0[1], 0.87]);
    assert!(!can.check_success());
    assert_eq!(can.reward(), 0.0);
    put(&mut can, "Can", [t[0], t[1], 0.9]);
    assert!(!can.check_success());

    // Mode 0: one object in place is a quarter, all four a success.
    let mut all = env("PickPlace", EnvConfig::default());
    all.reset(Some(0), None).unwrap();
    put(&mut all, "Can", [t[0], t[1], 0.87]);
    assert!(!all.check_success());
    assert_eq!(all.reward(), 0.25);
    for (i, name) in PICK_PLACE_OBJECTS.iter().enumerate() {
        let p = spec.target_bin_placement(i);
        put(&mut all, name, [p[0], p[1], 0.85]);
    }
    assert!(all.check_success());
    assert_eq!(all.reward(), 1.0);
    // Unnormalised: one per object.
    let mut raw = env("PickPlace", EnvConfig::default().with_reward_scale(None));
    raw.reset(Some(0), None).unwrap();
    put(&mut raw, "Can", [t[0], t[1], 0.87]);
    assert_eq!(raw.reward(), 1.0);

    // Shaped: the can 1 cm from its target, above the bin but too high to count: the hover
    // term (the parked objects, 14 m away, give only their zero lift term).
    let mut shaped = env(
        "PickPlaceCan",
        EnvConfig::default()
            .with_reward_shaping(true)
            .with_reward_scale(None),
    );
    shaped.reset(Some(0), None).unwrap();
    put(&mut shaped, "Can", [t[0] + 0.01, t[1], 1.0]);
    let expected = 0.5 + (1.0 - 0.1f64.tanh()) * (0.7 - 0.5);
    assert!(
        (shaped.reward() - expected).abs() < 1e-12,
        "{}",
        shaped.reward()
    );
    // Not above its quadrant: the reaching term wins (no grasp, no lift).
    put(&mut shaped, "Can", [0.1, -0.25, 0.86]);
    let eef = get(&shaped.observation(), "robot0_eef_pos");
    let d = ((eef[0] - 0.1).powi(2) + (eef[1] + 0.25).powi(2) + (eef[2] - 0.86).powi(2)).sqrt();
    let t_d = ((t[0] - 0.1).powi(2) + (t[1] + 0.25).powi(2)).sqrt();
    let reach = (1.0 - (10.0 * d).tanh()) * 0.1;
    let hover = (1.0 - (10.0 * t_d).tanh()) * (0.7 - 0.5);
    assert!(
        (shaped.reward() - reach.max(hover)).abs() < 1e-12,
        "{}",
        shaped.reward()
    );
}

#[test]
fn scripted_policy_solves_pick_place_can() {
    let mut e = env("PickPlaceCan", EnvConfig::default().with_horizon(300));
    let spec = PickPlaceSpec::default();
    let centre = spec.target_bin_placement(3);
    // The corner of the can's quadrant nearest the robot, 6 cm inside.
    let goal = [centre[0] - 0.39 / 4.0 + 0.06, centre[1] - 0.49 / 4.0 + 0.06];
    let policy = PlacePolicy {
        grab: |obs: &gym_core::DictValue| {
            let c = get(obs, "Can_pos");
            ([c[0], c[1], c[2]], 0.0)
        },
        object_key: "Can_pos",
        goal,
        carry_z: 1.1,
        release_z: 0.82 + 0.04 + 0.005,
    };
    assert_scripted_successes("PickPlaceCan", &mut e, 3, 2, |env, seed| {
        policy
            .run(env, seed, 300)
            .map_or((false, 300), |t| (true, t))
    });
}

#[test]
fn task_state_round_trips_and_bad_states_are_rejected() {
    let mut e = env("PickPlaceSingle", EnvConfig::default());
    e.reset(Some(4), None).unwrap();
    let state = e.get_state();
    let task = e.task().save_state();
    // The object in play, then the cached pose of the observed object.
    assert_eq!(task.len(), 1 + 7);
    let id = task[0];
    for _ in 0..3 {
        let _ = e
            .step(&action([0.3, 0.1, -0.2, 0.0, 0.0, 0.1, 1.0]))
            .unwrap();
    }
    assert_snapshot_replays(&mut e, &probe_actions(), 1);

    // A recorded start: the object id alone, as the fixtures give it.
    let (obs, _) = e.reset_to_state(&[id], &state).unwrap();
    assert_eq!(get(&obs, "obj_id"), vec![id]);
    assert_eq!(get(&obs, "obj_to_robot0_eef_pos"), vec![0.0; 3]);
    let bad = [
        vec![],
        vec![4.0],
        vec![1.5],
        vec![-1.0],
        vec![f64::NAN],
        vec![id, 0.0, 0.0],
    ];
    assert_task_states_rejected(&mut e, &bad, &state);
    let mut nan_cache = task.clone();
    nan_cache[3] = f64::NAN;
    assert!(e.reset_to_state(&nan_cache, &state).is_err());

    // Mode 2 takes only its object; mode 0 has no id.
    let mut can = env("PickPlaceCan", EnvConfig::default());
    can.reset(Some(0), None).unwrap();
    let s = can.get_state();
    assert!(can.reset_to_state(&[3.0], &s).is_ok());
    assert!(can.reset_to_state(&[0.0], &s).is_err());
    let mut all = env("PickPlace", EnvConfig::default());
    all.reset(Some(0), None).unwrap();
    assert_eq!(all.task().save_state().len(), 4 * 7);
    let s = all.get_state();
    assert!(all.reset_to_state(&[], &s).is_ok());
    assert!(all.reset_to_state(&[0.0], &s).is_err());
}

#[test]
fn invalid_object_ids_are_rejected() {
    assert!(matches!(
        PickPlaceSpec::new(ObjectMode::Single(4)),
        Err(Error::InvalidArgument { .. })
    ));
    let spec = PickPlaceSpec::new(ObjectMode::Single(2)).unwrap();
    assert_eq!(
        robosuite_env::tasks::TaskSpec::name(&spec),
        "PickPlaceCereal"
    );
    assert!(PickPlaceSpec::variant("PickPlaceSoda").is_none());
}

#[test]
fn the_mujoco_arena_suffices_for_long_random_rollouts() {
    for name in ["PickPlace", "PickPlaceSingle"] {
        let mut e = env(name, EnvConfig::default().with_horizon(500));
        random_episodes(&mut e, 2);
        let (used, reserved) = arena_use(&e);
        // Measured: about 85 KB of the default 2 MiB.
        assert!(used < reserved / 4, "{name}: {used} of {reserved} bytes");
    }
}

/// robosuite's `world_pose_in_gripper` (PickPlace, NutAssembly, ToolHang): the first task
/// observable, a 4x4 float64 `object` observable, enabled and inactive; its value (in every
/// observation pass) is the inverse of the gripper pose `(eef_pos, eef_quat)`.
#[test]
fn world_pose_in_gripper_is_enabled_inactive_and_the_inverse_gripper_pose() {
    use robosuite_env::ObservableFlag;
    for task in ["PickPlaceCan", "NutAssemblyRound", "ToolHang"] {
        let mut e = env(task, EnvConfig::default());
        let infos = e.observables();
        let first_task = infos
            .iter()
            .position(|o| !o.spec.key.starts_with("robot0_"))
            .unwrap();
        let o = &infos[first_task];
        assert_eq!(o.spec.key, "world_pose_in_gripper", "{task}");
        assert_eq!(
            (o.spec.shape.as_slice(), o.spec.modality.name()),
            (&[4, 4][..], "object".to_owned())
        );
        assert!(o.enabled && !o.active, "{task}");
        let (obs, _) = e.reset(Some(1), None).unwrap();
        assert!(
            !e.observation_keys()
                .iter()
                .any(|k| k.starts_with("world_pose"))
        );
        let step = e
            .step(&action([0.3, -0.2, 0.1, 0.0, 0.0, 0.1, -1.0]))
            .unwrap();
        assert!(obs.get("world_pose_in_gripper").is_none());
        assert!(step.observation.get("world_pose_in_gripper").is_none());
        let all = e.all_observations();
        let (p, q) = (get(&all, "robot0_eef_pos"), get(&all, "robot0_eef_quat"));
        let pose = get(&all, "world_pose_in_gripper");
        // R from the xyzw quaternion; the pose is [Rᵀ, -Rᵀp; 0 1] (float32-rounded as robosuite)
        let (x, y, z, w) = (q[0], q[1], q[2], q[3]);
        let r = [
            [
                1.0 - 2.0 * (y * y + z * z),
                2.0 * (x * y - z * w),
                2.0 * (x * z + y * w),
            ],
            [
                2.0 * (x * y + z * w),
                1.0 - 2.0 * (x * x + z * z),
                2.0 * (y * z - x * w),
            ],
            [
                2.0 * (x * z - y * w),
                2.0 * (y * z + x * w),
                1.0 - 2.0 * (x * x + y * y),
            ],
        ];
        for i in 0..3 {
            let t = -(0..3).map(|k| r[k][i] * p[k]).sum::<f64>();
            for j in 0..3 {
                assert!(
                    (pose[4 * i + j] - r[j][i]).abs() < 1e-6,
                    "{task} R[{i}][{j}]"
                );
            }
            assert!((pose[4 * i + 3] - t).abs() < 1e-6, "{task} t[{i}]");
        }
        assert_eq!(pose[12..], [0.0, 0.0, 0.0, 1.0]);
        e.modify_observable("world_pose_in_gripper", ObservableFlag::Active, true)
            .unwrap();
        assert_eq!(get(&e.observation(), "world_pose_in_gripper"), pose);
    }
}
