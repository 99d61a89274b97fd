//! ToolHang: observation layout, placement, the frame and tool checks on hand-set states,
//! reward, task state, a scripted grasp of the tool, and scenes supplied as XML.

use crate::common::fixtures::robosuite_observations;
use crate::common::{action, get, wrap_half, zero};
use gym_core::{Env, Error, Space, Value};
use robosuite_env::sim::{body_id, geom_id, site_id};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_from_scene_xml, make_with, scene_xml};
use std::f64::consts::{FRAC_1_SQRT_2, PI};

/// Offsets into `[time, qpos, qvel]` of the objects' free joints (after 7 arm and 2 finger
/// joints).
const STAND_Q: usize = 1 + 9;
const FRAME_Q: usize = 1 + 16;
const TOOL_Q: usize = 1 + 23;

fn tool_hang(config: EnvConfig) -> RobosuiteEnv {
    make_with("ToolHang", config).expect("ToolHang builds")
}

#[test]
fn model_matches_robosuite() {
    let env = tool_hang(EnvConfig::default());
    let m = env.sim().model();
    let f = m.ffi();
    assert_eq!((f.nq, f.nv, f.nu, f.nbody, f.ngeom), (30, 27, 9, 32, 247));
    for b in [
        "stand_root",
        "frame_root",
        "tool_root",
        "tool_hole1_root",
        "tool_grip_main",
    ] {
        assert!(body_id(m, b).is_ok(), "{b}");
    }
    for s in [
        "stand_mount_site",
        "frame_hang_site",
        "frame_mount_site",
        "frame_intersection_site",
        "frame_tip_site",
        "tool_hole1_center",
    ] {
        assert!(site_id(m, s).is_ok(), "{s}");
    }
    for g in [
        "stand_base",
        "stand_wall3",
        "stand_hole_vis_vis",
        "frame_tip_cone_50",
        "tool_hole1_hc_7",
    ] {
        assert!(geom_id(m, g).is_ok(), "{g}");
    }
    // robosuite's cameras for this task.
    let sideview = [0.4837275266036987, 0.2505579098815722, 1.2139379055124524];
    let cam = m.cam_pos().contains(&sideview);
    assert!(cam, "sideview camera");
}

#[test]
fn observation_keys_shapes_and_dtypes_match_robosuite() {
    let mut env = tool_hang(EnvConfig::default());
    let tool_hang_obs = robosuite_observations("ToolHang");
    let expected: Vec<&str> = tool_hang_obs.iter().map(|(k, _, _)| k.as_str()).collect();
    assert_eq!(env.observation_space().keys().collect::<Vec<_>>(), expected);
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert_eq!(obs.keys().map(String::as_str).collect::<Vec<_>>(), expected);
    for (key, shape, dtype) in &tool_hang_obs {
        let Value::Array(a) = &obs[key.as_str()] else {
            panic!("{key} is not an array")
        };
        assert_eq!(a.shape(), shape.as_slice(), "{key}");
        assert_eq!(a.dtype(), *dtype, "{key}");
    }
    assert!(env.observation_space().contains(&obs));
    let parts: Vec<f64> = tool_hang_obs[10..24]
        .iter()
        .flat_map(|(k, _, _)| get(&obs, k))
        .collect();
    assert_eq!(get(&obs, "object-state"), parts);
    // robosuite reads the relative poses from the previous observation's object poses: none
    // right after a reset.
    for n in ["base", "frame", "tool"] {
        assert_eq!(get(&obs, &format!("{n}_to_robot0_eef_pos")), [0.0; 3]);
        assert_eq!(get(&obs, &format!("{n}_to_robot0_eef_quat")), [0.0; 4]);
    }
    let step = env.step(&zero()).unwrap();
    assert_ne!(get(&step.observation, "tool_to_robot0_eef_pos"), [0.0; 3]);
    // The stand's base geom, the frame's corner site, the tool's body.
    let m = env.sim().model();
    let d = env.sim().data();
    assert_eq!(
        get(&step.observation, "base_pos"),
        d.geom_xpos()[geom_id(m, "stand_base").unwrap()]
    );
    assert_eq!(
        get(&step.observation, "frame_pos"),
        d.site_xpos()[site_id(m, "frame_intersection_site").unwrap()]
    );
    assert_eq!(
        get(&step.observation, "tool_pos"),
        d.xpos()[body_id(m, "tool_root").unwrap()]
    );
    assert_eq!(get(&step.observation, "frame_is_assembled"), [0.0]);
    assert_eq!(get(&step.observation, "tool_on_frame"), [0.0]);
}

/// Whether `v` is a float32 value.
fn is_f32(v: f64) -> bool {
    f64::from(v as f32) == v
}

#[test]
fn reset_places_the_objects_as_robosuites_samplers() {
    let mut env = tool_hang(EnvConfig::default());
    let tol = 1e-12;
    for seed in 0..20 {
        env.reset(Some(seed), None).unwrap();
        let s = env.get_state();
        // The stand: fixed, upright, 1 mm above the table.
        assert_eq!(
            &s[STAND_Q..STAND_Q + 3],
            &[-0.8 * 0.1, 0.0, 0.8 + 0.001 + 0.08]
        );
        assert_eq!(&s[STAND_Q + 3..STAND_Q + 7], &[1.0, 0.0, 0.0, 0.0]);
        // The frame: (−0.04, −0.24) ± 0.02, lying on its side; its quaternion is robosuite's
        // float32 `quat_multiply(sampled, init_quat)`, which for a turn `a` about y is
        // (c + s, −(c + s), s − c, c − s) / 2 with c, s = cos, sin(a / 2).
        let f = &s[FRAME_Q..FRAME_Q + 7];
        assert!(
            (f[0] + 0.04).abs() <= 0.02 + tol && (f[1] + 0.24).abs() <= 0.02 + tol,
            "{f:?}"
        );
        assert!(f[3..].iter().all(|v| is_f32(*v)), "{f:?}");
        assert!(
            (f[3] + f[4]).abs() < 1e-7 && (f[5] + f[6]).abs() < 1e-7,
            "{f:?}"
        );
        let half = (f[3] - f[6]).atan2(f[3] + f[6]);
        let a = 2.0 * half;
        let centre = -PI / 2.0 + PI / 6.0;
        assert!((a - centre).abs() <= PI / 18.0 + 1e-6, "frame angle {a}");
        // The tool: (0.04, −0.2) ± 0.02, yawed −11π/18 ± π/18.
        let t = &s[TOOL_Q..TOOL_Q + 7];
        assert!(
            (t[0] - 0.04).abs() <= 0.02 + tol && (t[1] + 0.2).abs() <= 0.02 + tol,
            "{t:?}"
        );
        assert!((t[2] - (0.8 + 0.001 + 0.04)).abs() < tol);
        let yaw = 2.0 * t[6].atan2(t[3]);
        assert!(
            (yaw - (-PI / 2.0 - PI / 9.0)).abs() <= PI / 18.0 + 1e-9,
            "tool yaw {yaw}"
        );
        assert_eq!((t[4], t[5]), (0.0, 0.0));
    }
}

#[test]
fn objects_settle_on_the_table() {
    let mut env = tool_hang(EnvConfig::default());
    env.reset(Some(3), None).unwrap();
    for _ in 0..20 {
        let step = env.step(&zero()).unwrap();
        assert!(!step.terminated && step.reward == 0.0);
    }
    let obs = env.observation();
    // The base plate (1 cm thick) on the table top at 0.8.
    assert!(
        (get(&obs, "base_pos")[2] - 0.805).abs() < 1e-3,
        "{:?}",
        get(&obs, "base_pos")
    );
    // The tool lies on its 3 cm grip, the frame on its 2.54 cm grip.
    assert!(
        (get(&obs, "tool_pos")[2] - 0.815).abs() < 2e-3,
        "{:?}",
        get(&obs, "tool_pos")
    );
    let frame = get(&obs, "frame_pos");
    assert!(frame[2] > 0.8 && frame[2] < 0.83, "{frame:?}");
    assert!(!env.check_success());
}

/// The assembled state: the stand upright at (−0.08, 0) on the table, the frame upright with
/// its rod in the mount and its tip on the base plate, and the wrench hanging from the bar
/// by hole 1, 30 % along the bar from the hook, its top ring box resting 0.2 mm into the bar.
fn assembled(env: &RobosuiteEnv) -> Vec<f64> {
    let mut s = env.get_state();
    let (sx, sy, sz) = (-0.08, 0.0, 0.88);
    s[STAND_Q..STAND_Q + 7].copy_from_slice(&[sx, sy, sz, 1.0, 0.0, 0.0, 0.0]);
    // Frame figures (robosuite's HookFrame for ToolHang): rod at x = (L − t) / 2 from the
    // frame's centre, tip 0.13445 below it, bar 0.08625 above it.
    let (length, thickness) = (0.095, 0.0075);
    let rod_x = (length - thickness) / 2.0;
    let plate_top = sz - 0.08 + 0.01;
    let (fx, fy, fz) = (sx - rod_x, sy + 0.045, plate_top + 0.13445);
    s[FRAME_Q..FRAME_Q + 7].copy_from_slice(&[fx, fy, fz, 1.0, 0.0, 0.0, 0.0]);
    let bar_z = fz + 0.08625;
    let hang_x = fx - length / 2.0;
    let hole_x = hang_x + 0.3 * (rod_x + length / 2.0);
    // Hole 1: inner radius 0.0105 (to the boxes' inner faces: × cos(π/8)), 9.353 cm from the
    // tool's centre along its x axis, which a quarter turn about y points down.
    let inner = 0.0105 * (PI / 8.0).cos();
    let hole_z = bar_z + thickness / 2.0 - inner - 0.0002;
    let hole1_x = 0.09353284327242099;
    let h = FRAC_1_SQRT_2;
    s[TOOL_Q..TOOL_Q + 7].copy_from_slice(&[hole_x, fy, hole_z - hole1_x, h, 0.0, h, 0.0]);
    s
}

#[test]
fn frame_in_the_stand_with_the_tool_on_the_hook_is_a_success() {
    let mut env = tool_hang(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let s = assembled(&env);
    env.set_state(&s).unwrap();
    let obs = env.observation();
    let m = env.sim().model();
    let hole = env.sim().data().site_xpos()[site_id(m, "tool_hole1_center").unwrap()];
    assert!(
        (hole[2] - (s[FRAME_Q + 2] + 0.08625 + 0.00375 - 0.0105 * (PI / 8.0).cos() - 0.0002)).abs()
            < 1e-9
    );
    assert_eq!(get(&obs, "frame_is_assembled"), [1.0]);
    assert_eq!(get(&obs, "tool_on_frame"), [1.0]);
    assert!(env.check_success());
    assert_eq!(env.reward(), 1.0);

    // The tool 1 cm lower: hole 1 no longer touches the bar.
    let mut low = s.clone();
    low[TOOL_Q + 2] -= 0.01;
    env.set_state(&low).unwrap();
    assert_eq!(get(&env.observation(), "frame_is_assembled"), [1.0]);
    assert_eq!(get(&env.observation(), "tool_on_frame"), [0.0]);
    assert!(!env.check_success());
    assert_eq!(env.reward(), 0.0);
    // Hole 1 slid past the hook end of the bar (less than 5 % along it).
    let mut off = s.clone();
    off[TOOL_Q] -= 0.3 * 0.09125;
    env.set_state(&off).unwrap();
    assert_eq!(get(&env.observation(), "tool_on_frame"), [0.0]);
    // The frame lifted 10 cm out of the stand: not assembled (the tool still hangs).
    let mut out = s.clone();
    out[FRAME_Q + 2] += 0.1;
    out[TOOL_Q + 2] += 0.1;
    env.set_state(&out).unwrap();
    assert_eq!(get(&env.observation(), "frame_is_assembled"), [0.0]);
    assert_eq!(get(&env.observation(), "tool_on_frame"), [1.0]);
    assert!(!env.check_success());
    // The frame 1 cm beside the mount: its rod is no longer between the walls.
    let mut beside = s.clone();
    beside[FRAME_Q + 1] += 0.01;
    beside[TOOL_Q + 1] += 0.01;
    env.set_state(&beside).unwrap();
    assert_eq!(get(&env.observation(), "frame_is_assembled"), [0.0]);
    // The stand tipped over by 20° about x: not upright.
    let mut tipped = s.clone();
    let (c, sn) = ((10f64).to_radians().cos(), (10f64).to_radians().sin());
    tipped[STAND_Q + 3..STAND_Q + 7].copy_from_slice(&[c, sn, 0.0, 0.0]);
    env.set_state(&tipped).unwrap();
    assert_eq!(get(&env.observation(), "frame_is_assembled"), [0.0]);

    // reward_scale multiplies the success reward; None leaves it 1; shaping changes nothing.
    for (config, want) in [
        (EnvConfig::default().with_reward_scale(Some(2.5)), 2.5),
        (EnvConfig::default().with_reward_scale(None), 1.0),
        (EnvConfig::default().with_reward_shaping(true), 1.0),
    ] {
        let mut e = tool_hang(config);
        e.reset(Some(0), None).unwrap();
        assert_eq!(e.reward(), 0.0);
        e.set_state(&s).unwrap();
        assert_eq!(e.reward(), want);
    }
}

#[test]
fn a_hanging_tool_stays_hung() {
    let mut env = tool_hang(EnvConfig::default());
    env.reset(Some(0), None).unwrap();
    let s = assembled(&env);
    env.reset_to_state(&[], &s).unwrap();
    let mut successes = 0;
    for _ in 0..10 {
        let step = env.step(&zero()).unwrap();
        successes += usize::from(step.info.get_bool("success") == Some(true));
        assert_eq!(
            step.reward,
            f64::from(u8::from(step.info.get_bool("success") == Some(true)))
        );
    }
    assert_eq!(successes, 10);
}

#[test]
fn task_state_snapshots_and_errors() {
    let mut env = tool_hang(EnvConfig::default());
    env.reset(Some(1), None).unwrap();
    // The task state is the observation cache: the three cached poses after a pass.
    assert_eq!(env.task().save_state().len(), 21);
    for _ in 0..3 {
        let _ = env
            .step(&action([0.3, -0.2, 0.1, 0.0, 0.0, 0.2, 1.0]))
            .unwrap();
    }
    let snap = env.snapshot();
    let a = action([-0.4, 0.3, -0.2, 0.1, 0.0, -0.1, -1.0]);
    let first: Vec<_> = (0..4).map(|_| env.step(&a).unwrap().observation).collect();
    env.restore(&snap).unwrap();
    let again: Vec<_> = (0..4).map(|_| env.step(&a).unwrap().observation).collect();
    assert_eq!(first, again);

    // A task state of the wrong length is rejected and changes nothing.
    let state = env.get_state();
    let before = env.task().save_state();
    for bad in [vec![0.0; 5], vec![0.0; 22]] {
        assert!(matches!(
            env.reset_to_state(&bad, &state),
            Err(Error::InvalidArgument { .. })
        ));
        assert_eq!(env.task().save_state(), before);
        assert_eq!(env.get_state(), state);
    }
    // The empty state starts from a cleared cache.
    let (obs, _) = env.reset_to_state(&[], &state).unwrap();
    assert_eq!(get(&obs, "tool_to_robot0_eef_pos"), [0.0; 3]);
}

/// Grasps the tool's grip as `scripts/record_robosuite.py`'s scripted rollout does: above
/// the tool with the fingers turned across its grip, down, close, lift 10 cm.
#[test]
fn scripted_grasp_lifts_the_tool() {
    let mut env = tool_hang(EnvConfig::default());
    let (mut obs, _) = env.reset(Some(100), None).unwrap();
    let start = get(&obs, "tool_pos");
    let (mut phase, mut t) = (0, 0);
    for _ in 0..130 {
        let eef = get(&obs, "robot0_eef_pos");
        let tool = get(&obs, "tool_pos");
        let q = get(&obs, "tool_quat");
        // The tool's x axis (its grip) and the hand's y axis (the fingers' closing axis).
        let bar_yaw =
            (2.0 * (q[0] * q[1] + q[3] * q[2])).atan2(1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]));
        let err = wrap_half(bar_yaw + PI / 2.0 - crate::common::finger_yaw(&obs));
        t += 1;
        let (target, grip) = match phase {
            0 => ([tool[0], tool[1], tool[2] + 0.2], -1.0),
            1 => ([tool[0], tool[1], tool[2]], -1.0),
            2 => ([eef[0], eef[1], eef[2]], 1.0),
            _ => ([start[0], start[1], start[2] + 0.1], 1.0),
        };
        let d = crate::common::dist3(target, &eef);
        let turn = if phase < 2 {
            (err * 4.0).clamp(-1.0, 1.0)
        } else {
            0.0
        };
        let toward = |i: usize| ((target[i] - eef[i]) * 10.0).clamp(-1.0, 1.0);
        let a = action([toward(0), toward(1), toward(2), 0.0, 0.0, turn, grip]);
        obs = env.step(&a).unwrap().observation;
        let next = match phase {
            0 => d < 0.01 && err.abs() < 0.03 || t > 40,
            1 => d < 0.006 || t > 30,
            2 => t > 10,
            _ => false,
        };
        if next {
            phase += 1;
            t = 0;
        }
    }
    let lifted = get(&obs, "tool_pos")[2] - start[2];
    assert!(lifted > 0.07, "the tool rose {lifted} m");
    assert!(!env.check_success());
}

#[test]
fn supplied_scene_xml_builds_the_task() {
    let xml = scene_xml("ToolHang", &EnvConfig::default()).unwrap();
    let mut env = make_from_scene_xml("ToolHang", &xml, EnvConfig::default()).unwrap();
    assert_eq!(env.model_source(), robosuite_env::ModelSource::Supplied);
    let composed = tool_hang(EnvConfig::default());
    assert_eq!(
        env.sim().model().ffi().ngeom,
        composed.sim().model().ffi().ngeom
    );
    let (obs, _) = env.reset(Some(0), None).unwrap();
    assert!(env.observation_space().contains(&obs));
    let _ = env.step(&zero()).unwrap();
    // Hand-set success works on the supplied scene too.
    let s = assembled(&env);
    env.set_state(&s).unwrap();
    assert!(env.check_success());
    // A scene without the tool's hole sites is a typed error.
    let broken = xml.replace("tool_hole1_center", "tool_hole1_middle");
    assert!(matches!(
        make_from_scene_xml("ToolHang", &broken, EnvConfig::default()),
        Err(Error::Model(_))
    ));
}
