//! The hot paths do not touch the heap: the substep loop (`mj_step1` → controllers →
//! `mj_step2`), a robosuite env's `step_into`, and `step_into` through the flat GymWrapper
//! (alone and under FrameStackObservation).
//! Allocations are counted per thread, so tests running in parallel do not disturb each
//! other.

use adapters::WrapperExt;
use gym_core::{DictValue, Env, Info, Space, rng_from_seed};
use ndarray::ArrayD;
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, make_with};
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

fn count() {
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

/// How many allocations `f` makes on this thread.
fn allocations(f: impl FnOnce()) -> usize {
    let before = ALLOCATIONS.with(Cell::get);
    f();
    ALLOCATIONS.with(Cell::get) - before
}

// SAFETY: forwards to the system allocator, only counting calls.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn substeps_do_not_allocate() {
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(0), None).unwrap();
    let mut sim = Sim::new(env.sim().model().clone()).unwrap();
    sim.set_state(&env.get_state()).unwrap();
    let mut robot = env.robots()[0].clone();
    let action = [0.4, -0.2, 0.3, 0.1, -0.1, 0.2, 1.0];
    // Warm up once (first calls may initialise lazily).
    sim.step1().unwrap();
    robot.set_goal(&sim, &action);
    robot.apply_control(&mut sim);
    sim.step2().unwrap();
    let n = allocations(|| {
        for _ in 0..10 {
            for sub in 0..25 {
                sim.step1().unwrap();
                if sub == 0 {
                    robot.set_goal(&sim, &action);
                }
                robot.apply_control(&mut sim);
                if sub == 24 {
                    sim.step2().unwrap();
                } else {
                    sim.step2_without_sensors().unwrap();
                }
            }
        }
    });
    assert_eq!(n, 0, "the substep loop allocated {n} times");
    // The arm moved, so the loop did real work.
    assert!(env.get_state() != sim.state());
}

#[test]
fn env_step_into_does_not_allocate_and_equals_step_for_every_task() {
    step_into_does_not_allocate(&EnvConfig::default());
}

#[test]
fn shaped_rewards_do_not_allocate_for_every_task() {
    step_into_does_not_allocate(&EnvConfig::default().with_reward_shaping(true));
}

/// Every task's `step_into` with `config` allocates nothing and equals `step`.
fn step_into_does_not_allocate(config: &EnvConfig) {
    for task in robosuite_env::ENV_NAMES {
        let mut a = make_with(task, config.clone()).unwrap();
        let mut b = make_with(task, config.clone()).unwrap();
        let (mut obs, mut info) = a.reset(Some(5), None).unwrap();
        b.reset(Some(5), None).unwrap();
        let mut rng = rng_from_seed(9);
        let actions: Vec<ArrayD<f64>> =
            (0..30).map(|_| a.action_space().sample(&mut rng)).collect();
        for (i, action) in actions.iter().enumerate() {
            let mut t = None;
            let n = allocations(|| t = Some(a.step_into(action, &mut obs, &mut info).unwrap()));
            let t = t.unwrap();
            let step = b.step(action).unwrap();
            assert_eq!(obs, step.observation, "{task}: step {i}");
            assert_eq!(info, step.info, "{task}: step {i}");
            assert_eq!(
                (t.reward.to_bits(), t.terminated, t.truncated),
                (step.reward.to_bits(), step.terminated, step.truncated),
                "{task}: step {i}"
            );
            assert_eq!(n, 0, "{task}: step_into {i} allocated {n} times");
            if t.done() {
                break;
            }
        }
    }
}

#[test]
fn every_controller_steps_without_allocating() {
    use robosuite_env::controllers::ControllerConfig;
    let configs = [
        r#"{"type": "OSC_POSE", "impedance_mode": "variable", "interpolation": "linear", "input_ref_frame": "world"}"#,
        r#"{"type": "OSC_POSITION", "impedance_mode": "variable_kp"}"#,
        r#"{"type": "OSC_POSE", "input_type": "absolute", "position_limits": [[-1, -1, 0], [1, 1, 2]], "orientation_limits": [[-3, -3, -3], [3, 3, 3]]}"#,
        r#"{"type": "IK_POSE", "interpolation": "linear"}"#,
        r#"{"type": "JOINT_POSITION", "impedance_mode": "variable", "interpolation": "linear"}"#,
        r#"{"type": "JOINT_VELOCITY", "interpolation": "linear"}"#,
        r#"{"type": "JOINT_TORQUE", "interpolation": "linear"}"#,
    ];
    for (robot, text) in ["Panda", "UR5e"]
        .iter()
        .flat_map(|r| configs.iter().map(move |c| (r, c)))
    {
        let value: serde_json::Value = serde_json::from_str(text).unwrap();
        let config = ControllerConfig::from_value(&value, "controller_configs").unwrap();
        let mut env = make_with(
            "Lift",
            EnvConfig::default()
                .with_robots([*robot])
                .with_controller(config),
        )
        .unwrap();
        random_steps_do_not_allocate(&mut env, &format!("{robot} {text}"));
    }
}

/// Ten random actions from a reset: `step_into` allocates nothing.
fn random_steps_do_not_allocate(env: &mut robosuite_env::RobosuiteEnv, what: &str) {
    let (mut obs, mut info) = env.reset(Some(2), None).unwrap();
    let mut rng = rng_from_seed(4);
    let actions: Vec<ArrayD<f64>> = (0..10)
        .map(|_| env.action_space().sample(&mut rng))
        .collect();
    for (i, action) in actions.iter().enumerate() {
        let n = allocations(|| {
            let _ = env.step_into(action, &mut obs, &mut info).unwrap();
        });
        assert_eq!(n, 0, "{what}: step {i} allocated {n} times");
    }
}

#[test]
fn whole_body_robots_step_without_allocating() {
    // Each with its default composite controller and shaped rewards. PandaOmron:
    // HYBRID_MOBILE_BASE (arm OSC, torso, base); Tiago: BASIC with two arms, torso, head and
    // base; SpotWithArm: BASIC with its legs (a legged robot, controls divided by gear);
    // SpotWithArmFloating: its floating base; PandaDexRH: the hand's indexed grip actions;
    // GR1: WHOLE_BODY_IK over arms, torso, head and legs; GR1FloatingBody:
    // HYBRID_MOBILE_BASE on a floating legged base. Bimanual robots on single-arm tasks:
    // the per-arm observables, the nearest-arm reward terms and Wipe's tool per arm.
    for (task, robot) in [
        ("Lift", "PandaOmron"),
        ("TwoArmLift", "Tiago"),
        ("Lift", "SpotWithArm"),
        ("Lift", "SpotWithArmFloating"),
        ("Lift", "PandaDexRH"),
        ("Lift", "GR1"),
        ("TwoArmLift", "GR1FloatingBody"),
        ("Lift", "Baxter"),
        ("PickPlaceCan", "Tiago"),
        ("Door", "GR1ArmsOnly"),
        ("Wipe", "Baxter"),
    ] {
        let config = EnvConfig::default()
            .with_robots([robot])
            .with_reward_shaping(true);
        let mut env = make_with(task, config).unwrap();
        random_steps_do_not_allocate(&mut env, &format!("{task} {robot}"));
    }
}

#[test]
fn step_into_replaces_buffers_of_another_layout() {
    let mut env = make_with("Lift", EnvConfig::default()).unwrap();
    env.reset(Some(1), None).unwrap();
    let mut obs = DictValue::new();
    let mut info = Info::new().with("stale", 3i64);
    let action = ArrayD::zeros(ndarray::IxDyn(&[7]));
    let _ = env.step_into(&action, &mut obs, &mut info).unwrap();
    assert!(env.observation_space().contains(&obs));
    assert_eq!(info, Info::new().with("success", false));
}

#[test]
fn flat_gym_wrapper_step_into_does_not_allocate_and_equals_step() {
    let make = || {
        make_with("Lift", EnvConfig::default())
            .unwrap()
            .flat_gym_wrapper(None)
            .unwrap()
    };
    let (mut a, mut b) = (make(), make());
    let (mut obs, mut info) = a.reset(Some(2), None).unwrap();
    b.reset(Some(2), None).unwrap();
    let mut rng = rng_from_seed(4);
    let actions: Vec<ArrayD<f32>> = (0..30).map(|_| a.action_space().sample(&mut rng)).collect();
    // The first step fills the wrapper's inner buffers.
    let _ = a.step_into(&actions[0], &mut obs, &mut info).unwrap();
    let _ = b.step(&actions[0]).unwrap();
    for (i, action) in actions.iter().enumerate().skip(1) {
        let mut t = None;
        let n = allocations(|| t = Some(a.step_into(action, &mut obs, &mut info).unwrap()));
        let t = t.unwrap();
        let step = b.step(action).unwrap();
        assert_eq!(obs, step.observation, "step {i}");
        assert_eq!(info, step.info, "step {i}");
        assert_eq!(t.reward.to_bits(), step.reward.to_bits(), "step {i}");
        assert_eq!(n, 0, "step_into {i} allocated {n} times");
    }
    // A wrong-length action is still refused, and the env stays usable.
    let bad = ArrayD::zeros(ndarray::IxDyn(&[3]));
    assert!(a.step_into(&bad, &mut obs, &mut info).is_err());
    assert!(a.step_into(&actions[1], &mut obs, &mut info).is_ok());
}

#[test]
fn frame_stack_step_into_does_not_allocate_and_equals_step() {
    let make = || {
        make_with("Lift", EnvConfig::default())
            .unwrap()
            .flat_gym_wrapper(None)
            .unwrap()
            .frame_stack_observation(3, adapters::Padding::Reset)
            .unwrap()
    };
    let (mut a, mut b) = (make(), make());
    let (mut obs, mut info) = a.reset(Some(2), None).unwrap();
    assert_eq!(obs, b.reset(Some(2), None).unwrap().0);
    let mut rng = rng_from_seed(5);
    let actions: Vec<ArrayD<f32>> = (0..12).map(|_| a.action_space().sample(&mut rng)).collect();
    // The first step fills the wrappers' inner buffers.
    let _ = a.step_into(&actions[0], &mut obs, &mut info).unwrap();
    let _ = b.step(&actions[0]).unwrap();
    for (i, action) in actions.iter().enumerate().skip(1) {
        let mut t = None;
        let n = allocations(|| t = Some(a.step_into(action, &mut obs, &mut info).unwrap()));
        let t = t.unwrap();
        let step = b.step(action).unwrap();
        assert_eq!(obs, step.observation, "step {i}");
        assert_eq!(t.reward.to_bits(), step.reward.to_bits(), "step {i}");
        assert_eq!(n, 0, "step_into {i} allocated {n} times");
    }
}

#[test]
fn wipe_steps_that_wipe_markers_do_not_allocate() {
    // Press the tool along the markers' path: steps with contact, wiped markers and their
    // model edits, all without the heap.
    let mut env = make_with("Wipe", EnvConfig::default()).unwrap();
    let (mut obs, mut info) = env.reset(Some(0), None).unwrap();
    let m = env.sim().model();
    let path: Vec<[f64; 3]> = (0..100)
        .map(|i| {
            let b = robosuite_env::sim::body_id(m, &format!("contact{i}_main")).unwrap();
            env.sim().data().xpos()[b]
        })
        .collect();
    let mut action = ArrayD::zeros(ndarray::IxDyn(&[6]));
    let (mut k, mut down, mut wiping_steps) = (0usize, false, 0);
    let mut last = 0.0;
    for t in 0..120 {
        let eef = &obs["robot0_eef_pos"].as_array().unwrap().to_f64_vec();
        let p = path[k.min(99)];
        down |= (eef[0] - p[0]).hypot(eef[1] - p[1]) < 0.01 || t >= 60;
        k += usize::from(down);
        let z = if down { p[2] - 0.02 } else { p[2] + 0.05 };
        for (i, target) in [p[0], p[1], z].into_iter().enumerate() {
            action[i] = ((target - eef[i]) * 10.0).clamp(-1.0, 1.0);
        }
        let mut tr = None;
        let n = allocations(|| tr = Some(env.step_into(&action, &mut obs, &mut info).unwrap()));
        assert_eq!(n, 0, "Wipe step {t} allocated {n} times");
        let wiped = obs["proportion_wiped"].as_array().unwrap().to_f64_vec()[0];
        wiping_steps += usize::from(wiped > last);
        last = wiped;
        if tr.unwrap().done() {
            break;
        }
    }
    assert!(wiping_steps >= 3, "only {wiping_steps} steps wiped markers");
}

/// With camera observations (two cameras, depth, element and instance segmentations), `step_into`
/// draws every frame into the env's own buffers and copies them into the caller's: no
/// allocation on the Rust side (the OpenGL driver's own memory is not counted), and the same
/// observations as `step`.
#[cfg(feature = "render")]
#[test]
fn step_into_with_cameras_does_not_allocate() {
    use robosuite_env::config::{CameraConfig, Segmentation};
    let config = EnvConfig::default().with_cameras(CameraConfig {
        camera_depths: vec![true],
        camera_segmentations: vec![vec![Segmentation::Element, Segmentation::Instance]],
        ..CameraConfig::observe(["agentview", "robot0_eye_in_hand"], 32, 24)
    });
    let mut a = make_with("Lift", config.clone()).unwrap();
    let mut b = make_with("Lift", config).unwrap();
    let (mut obs, mut info) = a.reset(Some(3), None).unwrap();
    b.reset(Some(3), None).unwrap();
    assert!(obs.contains_key("robot0_eye_in_hand_segmentation_instance"));
    let mut rng = rng_from_seed(6);
    let actions: Vec<ArrayD<f64>> = (0..5).map(|_| a.action_space().sample(&mut rng)).collect();
    for (i, action) in actions.iter().enumerate() {
        let n = allocations(|| {
            let _ = a.step_into(action, &mut obs, &mut info).unwrap();
        });
        assert_eq!(obs, b.step(action).unwrap().observation, "step {i}");
        assert_eq!(n, 0, "step_into {i} with cameras allocated {n} times");
    }
}

/// `OSC_POSE` and `OSC_POSITION`, coupled and not, on the fixed-size matrices of a 7-joint
/// and a 6-joint arm and on heap-sized ones: no allocation in `set_goal` and `compute`.
#[test]
fn osc_on_fixed_and_heap_sized_matrices_does_not_allocate() {
    use robosuite_env::controllers::config::OscConfig;
    use robosuite_env::controllers::{ArmBinding, ArmController, Osc, Timing};
    let timing = Timing {
        timestep: 0.002,
        control_freq: 20.0,
    };
    for robot in ["Panda", "UR5e"] {
        let mut env = make_with("Lift", EnvConfig::default().with_robots([robot])).unwrap();
        env.reset(Some(3), None).unwrap();
        let r = &env.robots()[0];
        let arm = r.arm();
        let model = env.sim().model();
        let bind = ArmBinding {
            site: arm.eef_site(),
            base_site: robosuite_env::sim::site_id(model, "robot0_right_center").unwrap(),
            qpos: r.joint_qpos()[arm.joints()].to_vec(),
            dofs: r.joint_dofs()[arm.joints()].to_vec(),
            nv: model.ffi().nv as usize,
            ctrlrange: arm.ctrlrange().to_vec(),
            stale_goal_origin: false,
        };
        let actuators = arm.actuators().to_vec();
        for (use_ori, uncouple, dynamic) in (0..8).map(|i| (i & 1 == 0, i & 2 == 0, i & 4 == 0)) {
            let config = OscConfig {
                uncouple_pos_ori: uncouple,
                ..OscConfig::default()
            };
            let mut osc = Osc::new(&config, use_ori, bind.clone(), timing, "c").unwrap();
            if dynamic {
                osc = osc.with_dynamic_matrices();
            }
            assert_eq!(osc.uses_fixed_size(), !dynamic);
            let mut sim = Sim::new(model.clone()).unwrap();
            sim.set_state(&env.get_state()).unwrap();
            osc.reset(&sim);
            let mut tau = vec![0.0; bind.dofs.len()];
            let action = [0.4, -0.2, 0.3, 0.1, -0.1, 0.2];
            let action = &action[..osc.action_dim()];
            let mut n = 0;
            for sub in 0..50 {
                sim.step1().unwrap();
                n += allocations(|| {
                    if sub % 25 == 0 {
                        osc.set_goal(&sim, action);
                    }
                    osc.compute(&sim, &mut tau);
                });
                for (&a, &t) in actuators.iter().zip(&tau) {
                    sim.data_mut().ctrl_mut()[a] = t;
                }
                sim.step2().unwrap();
            }
            let what = format!("{robot} use_ori {use_ori} uncouple {uncouple} dynamic {dynamic}");
            assert_eq!(n, 0, "{what}: allocated {n} times");
            assert!(tau.iter().any(|t| t.abs() > 1e-3), "{what}: no torque");
        }
    }
}

#[test]
fn whole_body_ik_set_goal_does_not_allocate() {
    use robosuite_env::controllers::whole_body_ik::{
        PartKind, WholeBodyIk, WholeBodyIkConfig, WholeBodyPart,
    };
    let dir =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/whole_body_ik");
    let model =
        mujoco_rs::wrappers::mj_model::MjModel::from_xml(dir.join("torso_two_arms.xml")).unwrap();
    let mut sim = Sim::new(model).unwrap();
    sim.forward().unwrap();
    let arm = |side: &str, s: &str| WholeBodyPart {
        name: side.to_owned(),
        joints: [
            "shoulder_pitch",
            "shoulder_roll",
            "shoulder_yaw",
            "elbow_pitch",
            "wrist_yaw",
            "wrist_roll",
            "wrist_pitch",
        ]
        .iter()
        .map(|j| format!("robot0_{s}_{j}"))
        .collect(),
        action_dim: 7,
        kind: PartKind::Arm,
        limits: (vec![-1.0; 7], vec![1.0; 7]),
    };
    let parts = vec![
        arm("right", "r"),
        arm("left", "l"),
        WholeBodyPart {
            name: "head".to_owned(),
            joints: vec!["robot0_head_yaw".to_owned(), "robot0_head_pitch".to_owned()],
            action_dim: 2,
            kind: PartKind::Other,
            limits: (vec![-1.0; 2], vec![1.0; 2]),
        },
    ];
    // The arms (a well-conditioned JJᵀ) and the head alone (JJᵀ = 0: the SVD path).
    for actuated in [vec!["right", "left"], vec!["head"]] {
        let config = WholeBodyIkConfig::from_value(
            &serde_json::json!({
                "ref_name": ["gripper0_right_grip_site", "gripper0_left_grip_site"],
                "actuation_part_names": actuated,
                "nullspace_joint_weights": {},
                "ik_input_ref_frame": "base",
            }),
            "cfg",
        )
        .unwrap();
        let mut wb = WholeBodyIk::new(sim.model(), &config, &parts).unwrap();
        let mut action = vec![0.2; wb.action_dim()];
        let mut out = vec![0.0; wb.part_actions_dim()];
        wb.set_goal(&sim, &action, &mut out).unwrap();
        let n = allocations(|| {
            for i in 0..20 {
                action[i % 12] += 0.01;
                wb.set_goal(&sim, &action, &mut out).unwrap();
            }
        });
        assert_eq!(n, 0, "{actuated:?}: {n} allocations in 20 IK steps");
    }
}
