//! Every arm controller (and the variable-impedance and absolute modes) on Lift against the
//! workspace's Gymnasium `check_env` mirror and its property suite.

use conformance_tests::prop::{FnStateHook, prop_check_env_with_state};
use conformance_tests::{Check, CheckOptions, EpisodeEndSpec, PropConfig, check_env};
use robosuite_env::controllers::ControllerConfig;
use robosuite_env::{EnvConfig, EnvSnapshot, RobosuiteEnv, make_with};

fn env(config_json: &str, horizon: u64) -> RobosuiteEnv {
    let value: serde_json::Value = serde_json::from_str(config_json).unwrap();
    let config = ControllerConfig::from_value(&value, "controller_configs").unwrap();
    make_with(
        "Lift",
        EnvConfig::default()
            .with_horizon(horizon)
            .with_controller(config),
    )
    .unwrap_or_else(|e| panic!("{config_json}: {e}"))
}

fn conforms(config_json: &str) {
    let mut e = env(config_json, 30);
    let report = check_env(&mut e, &CheckOptions::default())
        .unwrap_or_else(|err| panic!("{config_json}: {err}"));
    for check in [
        Check::ResetSeedDeterminism,
        Check::InvalidAction,
        Check::StepAfterEnd,
    ] {
        assert!(report.passed(check), "{config_json}: {check:?}");
    }
    let config = PropConfig::cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(8),
        can_terminate: false,
    });
    let hook = FnStateHook::new(
        |env: &RobosuiteEnv| -> gym_core::Result<EnvSnapshot> { Ok(env.snapshot()) },
        |env: &mut RobosuiteEnv, s: &EnvSnapshot| env.restore(s),
    );
    let report = prop_check_env_with_state(|| env(config_json, 8), &hook, &config)
        .unwrap_or_else(|err| panic!("{config_json}: {err}"));
    assert!(
        report.skipped.is_empty(),
        "{config_json}: {:?}",
        report.skipped
    );
}

#[test]
fn osc_pose_variable_conforms() {
    conforms(r#"{"type": "OSC_POSE", "impedance_mode": "variable", "interpolation": "linear"}"#);
}

#[test]
fn osc_position_conforms() {
    conforms(r#"{"type": "OSC_POSITION", "input_ref_frame": "world"}"#);
}

#[test]
fn ik_pose_conforms() {
    conforms(r#"{"type": "IK_POSE"}"#);
}

#[test]
fn joint_position_conforms() {
    conforms(r#"{"type": "JOINT_POSITION", "impedance_mode": "variable_kp"}"#);
}

#[test]
fn joint_velocity_conforms() {
    conforms(
        r#"{"type": "JOINT_VELOCITY", "kp": 3.0, "output_max": 0.5, "output_min": -0.5, "interpolation": "linear"}"#,
    );
}

#[test]
fn joint_torque_conforms() {
    conforms(r#"{"type": "JOINT_TORQUE", "output_max": 5.0, "output_min": -5.0}"#);
}
