//! robosuite's `WHOLE_BODY_IK` composite controller and its IK solver against robosuite 1.5.2
//! itself: `tests/fixtures/whole_body_ik/whole_body_ik.json`, recorded by
//! `scripts/record_whole_body_ik.py` with robosuite's own `WholeBodyIK` and `IKSolver` on
//! this crate's synthetic torso with two 7-joint arms (`torso_two_arms.xml`).
//!
//! Per case: the action layout, the limits, the IK joints and gains, and per step the joint
//! targets and every part's action. Tolerance: `1e-9·max(1, |x|)` for world-frame absolute
//! targets (float64 throughout in robosuite); `2e-6` where robosuite passes the target's
//! rotation through its float32 `mat2quat` (a base or body frame, the relative modes), whose
//! eigen-solver result this crate matches within float32 rounding (about 1e-7 in the
//! quaternion; the largest difference measured is 3.5e-7).

use gym_core::Error;
use mujoco_rs::wrappers::mj_model::MjModel;
use robosuite_env::controllers::whole_body_ik::{
    IkActionRepr, IkSettings, IkSolver, PartKind, WholeBodyIk, WholeBodyIkConfig, WholeBodyPart,
};
use robosuite_env::sim::Sim;
use serde::Deserialize;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::PathBuf;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/whole_body_ik")
}

#[derive(Deserialize)]
struct Fixture {
    cases: Vec<Case>,
    env_cases: Vec<EnvCase>,
}

/// A recorded Lift rollout under WHOLE_BODY_IK.
#[derive(Deserialize)]
struct EnvCase {
    name: String,
    robot: String,
    task: String,
    config: Value,
    eef_keys: Vec<String>,
    gripper_keys: Vec<String>,
    action_low: Vec<Option<f64>>,
    action_high: Vec<Option<f64>>,
    task_state: Vec<f64>,
    init_state: Vec<f64>,
    actions: Vec<Vec<f64>>,
    steps: Vec<EnvStep>,
}

#[derive(Deserialize)]
struct EnvStep {
    joint_pos: Vec<f64>,
    eef_pos: Vec<f64>,
    gripper_qpos: Vec<f64>,
}

#[derive(Deserialize)]
struct Case {
    name: String,
    config: Value,
    input_action_repr: Option<String>,
    parts: Vec<Part>,
    expected: Expected,
    steps: Vec<Step>,
}

#[derive(Deserialize)]
struct Part {
    name: String,
    joints: Vec<String>,
    action_dim: usize,
    gripper: bool,
    arm: bool,
    low: Vec<f64>,
    high: Vec<f64>,
}

#[derive(Deserialize)]
struct Expected {
    joint_names: Vec<String>,
    nullspace_gains: Vec<f64>,
    ref_names: Vec<String>,
    actuation_part_names: Vec<String>,
    ik_split: Vec<(String, usize, usize)>,
    action_split: Vec<(String, usize, usize)>,
    part_split: Vec<(String, usize, usize)>,
    action_low: Vec<Option<f64>>,
    action_high: Vec<Option<f64>>,
}

#[derive(Deserialize)]
struct Step {
    qpos: Vec<f64>,
    action: Vec<f64>,
    parts: BTreeMap<String, Vec<f64>>,
    q_des: Option<Vec<f64>>,
}

fn fixture() -> Fixture {
    let text = std::fs::read_to_string(dir().join("whole_body_ik.json")).unwrap();
    serde_json::from_str(&text).unwrap()
}

fn sim() -> Sim {
    Sim::new(MjModel::from_xml(dir().join("torso_two_arms.xml")).unwrap()).unwrap()
}

fn parts(case: &Case) -> Vec<WholeBodyPart> {
    case.parts
        .iter()
        .map(|p| WholeBodyPart {
            name: p.name.clone(),
            joints: p.joints.clone(),
            action_dim: p.action_dim,
            kind: if p.gripper {
                PartKind::Gripper
            } else if p.arm {
                PartKind::Arm
            } else {
                PartKind::Other
            },
            limits: (p.low.clone(), p.high.clone()),
        })
        .collect()
}

fn config(case: &Case) -> WholeBodyIkConfig {
    let mut c = WholeBodyIkConfig::from_value(&case.config, "cfg").unwrap();
    c.input_action_repr = match case.input_action_repr.as_deref() {
        None | Some("absolute") => IkActionRepr::Absolute,
        Some("relative") => IkActionRepr::Relative,
        Some("relative_pose") => IkActionRepr::RelativePose,
        Some(other) => panic!("unknown repr {other}"),
    };
    c
}

fn set_state(sim: &mut Sim, qpos: &[f64]) {
    sim.data_mut().qpos_mut().copy_from_slice(qpos);
    sim.data_mut().qvel_mut().fill(0.0);
    sim.forward().unwrap();
}

fn split(s: &[(String, std::ops::Range<usize>)]) -> Vec<(String, usize, usize)> {
    s.iter().map(|(n, r)| (n.clone(), r.start, r.end)).collect()
}

/// Whether robosuite computes this case in float64 throughout.
fn float64_case(case: &Case) -> bool {
    let frame = case
        .config
        .get("ik_input_ref_frame")
        .and_then(Value::as_str);
    matches!(frame, None | Some("world")) && case.input_action_repr.is_none()
}

#[test]
fn whole_body_ik_matches_robosuite() {
    let fx = fixture();
    assert!(fx.cases.len() >= 8);
    let mut far_steps_limited = 0;
    for case in &fx.cases {
        let mut sim = sim();
        let config = config(case);
        let mut wb = WholeBodyIk::new(sim.model(), &config, &parts(case)).unwrap();
        let e = &case.expected;
        let name = &case.name;
        assert_eq!(wb.solver().joint_names(), &e.joint_names[..], "{name}");
        assert_eq!(
            wb.solver().nullspace_gains(),
            &e.nullspace_gains[..],
            "{name}"
        );
        assert_eq!(wb.solver().site_names(), &e.ref_names[..], "{name}");
        assert_eq!(
            wb.config().actuation_part_names,
            e.actuation_part_names,
            "{name}"
        );
        assert_eq!(
            split(&wb.solver().action_split_indexes()),
            e.ik_split,
            "{name}"
        );
        // With skip_wbc_action the action is the parts' (robosuite's `get_action_info` then
        // reports `_action_split_indexes`; its whole-body dict is left unused).
        let skip = case.config.get("skip_wbc_action") == Some(&Value::Bool(true));
        let action_split = if skip { &e.part_split } else { &e.action_split };
        assert_eq!(split(wb.action_split()), *action_split, "{name}");
        assert_eq!(split(wb.part_split()), e.part_split, "{name}");
        let inf = |v: &[Option<f64>], s: f64| -> Vec<f64> {
            v.iter().map(|x| x.unwrap_or(s * f64::INFINITY)).collect()
        };
        let (low, high) = wb.action_limits();
        assert_eq!(low, &inf(&e.action_low, -1.0)[..], "{name}");
        assert_eq!(high, &inf(&e.action_high, 1.0)[..], "{name}");
        assert_eq!(wb.action_dim(), e.action_low.len());

        let tol = if float64_case(case) { 1e-9 } else { 2e-6 };
        let mut worst = 0.0f64;
        let mut out = vec![f64::NAN; wb.part_actions_dim()];
        for (t, step) in case.steps.iter().enumerate() {
            set_state(&mut sim, &step.qpos);
            let before = sim.data().qpos().to_vec();
            wb.set_goal(&sim, &step.action, &mut out).unwrap();
            assert_eq!(
                sim.data().qpos(),
                &before[..],
                "set_goal must not move the robot"
            );
            for (part, range) in wb.part_split() {
                let want = &step.parts[part];
                let got = &out[range.clone()];
                assert_eq!(got.len(), want.len(), "{name} step {t} {part}");
                for (g, w) in got.iter().zip(want) {
                    let err = (g - w).abs() / w.abs().max(1.0);
                    worst = worst.max(err);
                    assert!(
                        err <= tol,
                        "{name} step {t} part {part}: {got:?} vs robosuite {want:?} (tolerance {tol})"
                    );
                }
            }
            if let Some(q_des) = &step.q_des {
                assert_eq!(wb.solver().q_des().len(), q_des.len());
                for (g, w) in wb.solver().q_des().iter().zip(q_des) {
                    assert!((g - w).abs() / w.abs().max(1.0) <= tol, "{name} step {t}");
                }
                let peak = wb.solver().dq().iter().fold(0.0f64, |a, v| a.max(v.abs()));
                if (peak - config.max_dq).abs() < 1e-12 {
                    far_steps_limited += 1;
                }
            }
        }
        eprintln!("{name}: worst relative difference {worst:.2e} (tolerance {tol:.0e})");
    }
    // The unreachable targets were limited by ik_max_dq (robosuite's best effort).
    assert!(far_steps_limited >= 3, "{far_steps_limited}");
}

fn gr1_config() -> Value {
    serde_json::json!({
        "ref_name": ["gripper0_right_grip_site", "gripper0_left_grip_site"],
        "actuation_part_names": ["torso", "head", "right", "left"],
        "nullspace_joint_weights": {"robot0_torso_waist_yaw": 100.0},
        "ik_input_ref_frame": "world",
        "a_key_robosuite_ignores": 1
    })
}

fn gr1_parts() -> Vec<WholeBodyPart> {
    let fx = fixture();
    parts(&fx.cases[0])
}

#[test]
fn whole_body_ik_refuses_non_finite_actions_and_keeps_its_state() {
    let mut sim = sim();
    let config = WholeBodyIkConfig::from_value(&gr1_config(), "cfg").unwrap();
    assert_eq!(config.ignored_keys, ["cfg.a_key_robosuite_ignores"]);
    let mut wb = WholeBodyIk::new(sim.model(), &config, &gr1_parts()).unwrap();
    sim.forward().unwrap();
    let mut action = vec![0.1; wb.action_dim()];
    let mut out = vec![0.0; wb.part_actions_dim()];
    wb.set_goal(&sim, &action, &mut out).unwrap();
    let (kept, kept_q) = (out.clone(), wb.solver().q_des().to_vec());
    for bad in [f64::NAN, f64::INFINITY] {
        for i in [0, 4, 12] {
            action[i] = bad;
            let err = wb.set_goal(&sim, &action, &mut out).unwrap_err();
            assert!(matches!(err, Error::InvalidAction(_)), "{err}");
            assert_eq!(out, kept);
            assert_eq!(wb.solver().q_des(), &kept_q[..]);
            action[i] = 0.1;
        }
    }
    let err = wb.set_goal(&sim, &action[1..], &mut out).unwrap_err();
    assert!(matches!(err, Error::InvalidAction(_)), "{err}");
    // A target far beyond reach: a finite best effort within the joint ranges.
    action[..3].copy_from_slice(&[1e12, -1e12, 1e12]);
    wb.set_goal(&sim, &action, &mut out).unwrap();
    let q = wb.solver().q_des().to_vec();
    assert!(q.iter().all(|v| v.is_finite()));
    let peak = wb.solver().dq().iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!((peak - 4.0).abs() < 1e-12, "{peak}");
    // A target so far that the step overflows: refused; `hold` keeps the IK joints where
    // they are (what the robot's composite controller then commands).
    let mut overflow = action.clone();
    overflow[0] = 1e308;
    let before = out.clone();
    let err = wb.set_goal(&sim, &overflow, &mut out).unwrap_err();
    assert!(matches!(err, Error::InvalidAction(_)), "{err}");
    assert_eq!(out, before);
    wb.hold(&sim, &overflow, &mut out);
    let qpos = sim.data().qpos();
    for (c, name) in wb.solver().joint_names().iter().enumerate() {
        let id = robosuite_env::sim::joint_id(sim.model(), name).unwrap();
        let [lo, hi] = sim.model().jnt_range()[id];
        assert_eq!(out[c], qpos[id].clamp(lo, hi), "{name}");
    }
    assert_eq!(&out[19..], &overflow[12..]);
    let model = sim.model();
    for (name, v) in wb.solver().joint_names().iter().zip(&q) {
        let id = robosuite_env::sim::joint_id(model, name).unwrap();
        let [lo, hi] = model.jnt_range()[id];
        assert!(*v >= lo && *v <= hi, "{name}: {v} outside [{lo}, {hi}]");
    }
}

#[test]
fn whole_body_ik_config_errors_name_the_key() {
    let sim = sim();
    let parts = gr1_parts();
    let with = |key: &str, value: Value| {
        let mut c = gr1_config();
        c[key] = value;
        c
    };
    let invalid = |c: &Value, key: &str| match WholeBodyIkConfig::from_value(c, "cfg") {
        Err(Error::InvalidArgument { name, reason }) => {
            assert_eq!(name, format!("cfg.{key}"), "{reason}");
            reason
        }
        other => panic!("{key}: {other:?}"),
    };
    for key in [
        "ref_name",
        "actuation_part_names",
        "nullspace_joint_weights",
    ] {
        let mut c = gr1_config();
        c.as_object_mut().unwrap().remove(key);
        assert!(invalid(&c, key).contains("missing"));
    }
    let reason = invalid(&with("ik_input_type", "relative".into()), "ik_input_type");
    assert!(reason.contains("always absolute"), "{reason}");
    let reason = invalid(
        &with("ik_input_rotation_repr", "mat".into()),
        "ik_input_rotation_repr",
    );
    assert!(reason.contains("axis_angle, quat_wxyz"), "{reason}");
    invalid(
        &with("ik_pseudo_inverse_damping", 0.0.into()),
        "ik_pseudo_inverse_damping",
    );
    invalid(
        &with("ik_integration_dt", (-0.1).into()),
        "ik_integration_dt",
    );
    invalid(
        &with("ref_name", "gripper0_right_grip_site".into()),
        "ref_name",
    );

    // Every reference site missing: robosuite fails; here a typed error listing grip sites.
    let c = WholeBodyIkConfig::from_value(
        &with("ref_name", serde_json::json!(["gripper0_nowhere"])),
        "cfg",
    )
    .unwrap();
    match WholeBodyIk::new(sim.model(), &c, &parts) {
        Err(Error::InvalidArgument { name, reason }) => {
            assert!(name.ends_with("ref_name"), "{name}");
            assert!(reason.contains("gripper0_right_grip_site"), "{reason}");
        }
        other => panic!("{other:?}"),
    }
    // A frame body the model lacks.
    let c = WholeBodyIkConfig::from_value(
        &with("ik_input_ref_frame", "mobilebase0_base".into()),
        "cfg",
    )
    .unwrap();
    let err = WholeBodyIk::new(sim.model(), &c, &parts).unwrap_err();
    assert!(matches!(err, Error::Model(_)), "{err}");
    // body_part_ordering must order exactly the parts.
    let c = WholeBodyIkConfig::from_value(
        &with("body_part_ordering", serde_json::json!(["right", "left"])),
        "cfg",
    )
    .unwrap();
    let err = WholeBodyIk::new(sim.model(), &c, &parts).unwrap_err();
    assert!(err.to_string().contains("body_part_ordering"), "{err}");
}

#[test]
fn ik_solver_refuses_joints_robosuite_would_index_wrongly() {
    let sim = sim();
    let settings = IkSettings::from(&WholeBodyIkConfig::default());
    let site = ["gripper0_right_grip_site"];
    // A free joint: robosuite indexes qpos and the Jacobian by joint id.
    let err = IkSolver::new(
        sim.model(),
        &site,
        &["cube_joint"],
        &[1.0],
        settings.clone(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("joint id"), "{err}");
    // A torso joint whose model id (2) is past the step's one entry.
    let err = IkSolver::new(
        sim.model(),
        &site,
        &["robot0_torso_waist_roll"],
        &[1.0],
        settings.clone(),
    )
    .unwrap_err();
    assert!(err.to_string().contains("IndexError"), "{err}");
    let err = IkSolver::new(
        sim.model(),
        &site,
        &["robot0_no_joint"],
        &[1.0],
        settings.clone(),
    )
    .unwrap_err();
    assert!(matches!(err, Error::Model(_)), "{err}");
    let err = IkSolver::new(
        sim.model(),
        &site,
        &["robot0_r_elbow_pitch"],
        &[f64::NAN],
        settings,
    )
    .unwrap_err();
    assert!(matches!(err, Error::InvalidArgument { .. }), "{err}");
}

#[test]
fn joints_that_do_not_move_the_sites_follow_the_nullspace_only() {
    // Only the head actuated: J = 0 (JJᵀ singular, the pseudo-inverse's SVD path), so the
    // step is the nullspace pull Kn∘(0 − q) toward the zero posture, as with robosuite's
    // pinv(0) = 0.
    let mut sim = sim();
    let mut c = gr1_config();
    c["actuation_part_names"] = serde_json::json!(["head"]);
    c["nullspace_joint_weights"] = serde_json::json!({"robot0_head_pitch": 2.0});
    let config = WholeBodyIkConfig::from_value(&c, "cfg").unwrap();
    let mut wb = WholeBodyIk::new(sim.model(), &config, &gr1_parts()).unwrap();
    let head_pitch = robosuite_env::sim::joint_id(sim.model(), "robot0_head_pitch").unwrap();
    let mut qpos = sim.data().qpos().to_vec();
    qpos[head_pitch] = 0.3;
    qpos[head_pitch - 1] = 0.7; // the head's yaw, unlimited: robosuite clips it to [0, 0]
    set_state(&mut sim, &qpos);
    let action = vec![0.5; wb.action_dim()];
    let mut out = vec![0.0; wb.part_actions_dim()];
    wb.set_goal(&sim, &action, &mut out).unwrap();
    let dq = wb.solver().dq();
    assert!(
        (dq[0] + 0.7).abs() < 1e-12 && (dq[1] + 0.6).abs() < 1e-12,
        "{dq:?}"
    );
    assert_eq!(out[0], 0.0);
    assert!((out[1] - 0.24).abs() < 1e-12, "{out:?}");
    // The rest of the action goes to the other parts unchanged.
    assert_eq!(&out[2..], &action[12..]);
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// WHOLE_BODY_IK as a robot's composite controller: robosuite's recorded rollouts (its
/// `whole_body_ik.json` on a Panda on Lift, world and base frame; its Tiago config on
/// TwoArmLift and its PandaOmron config on Lift), replayed from the recorded reset state; the joints, grip sites
/// and fingers within 1e-5 at each of the 60 steps (free motion, as the arm controllers'
/// replays), the action bounds equal robosuite's.
#[test]
fn whole_body_ik_env_rollouts_replay_robosuite() {
    use crate::common::fixtures::values;
    use gym_core::Env;
    use ndarray::{Array1, ArrayD};
    use robosuite_env::controllers::ControllerConfig;
    use robosuite_env::{EnvConfig, make_with};

    let fx = fixture();
    assert_eq!(fx.env_cases.len(), 4);
    for case in &fx.env_cases {
        let name = &case.name;
        let config = ControllerConfig::from_value(&case.config, "controller_configs").unwrap();
        let mut env = make_with(
            &case.task,
            EnvConfig::default()
                .with_robots([case.robot.as_str()])
                .with_controller(config),
        )
        .unwrap();
        let space = env.action_space();
        let inf = |v: &[Option<f64>], s: f64| -> Vec<f64> {
            v.iter().map(|x| x.unwrap_or(s * f64::INFINITY)).collect()
        };
        assert_eq!(
            space.low().iter().copied().collect::<Vec<_>>(),
            inf(&case.action_low, -1.0),
            "{name}"
        );
        assert_eq!(
            space.high().iter().copied().collect::<Vec<_>>(),
            inf(&case.action_high, 1.0),
            "{name}"
        );
        env.reset_to_state(&case.task_state, &case.init_state)
            .unwrap();
        let (mut joints, mut eef, mut grip) = (0.0f64, 0.0f64, 0.0f64);
        for (a, want) in case.actions.iter().zip(&case.steps) {
            let action: ArrayD<f64> = Array1::from(a.clone()).into_dyn();
            let step = env.step(&action).unwrap();
            let obs = &step.observation;
            let concat = |keys: &[String]| -> Vec<f64> {
                keys.iter().flat_map(|k| values(obs, k)).collect()
            };
            joints = joints.max(max_diff(&values(obs, "robot0_joint_pos"), &want.joint_pos));
            eef = eef.max(max_diff(&concat(&case.eef_keys), &want.eef_pos));
            grip = grip.max(max_diff(&concat(&case.gripper_keys), &want.gripper_qpos));
        }
        eprintln!("{name}: joints {joints:.2e} rad, grip site {eef:.2e} m, fingers {grip:.2e}");
        assert!(
            joints <= 1e-5 && eef <= 1e-5 && grip <= 1e-5,
            "{name}: joints {joints:e}, grip site {eef:e}, fingers {grip:e}"
        );
    }
}
