//! Lift against the workspace's Gymnasium `check_env` mirror and its property suite.

use conformance_tests::prop::{FnStateHook, prop_check_env_with_state};
use conformance_tests::{CheckOptions, EpisodeEndSpec, PropConfig, check_env};
use robosuite_env::{EnvConfig, EnvSnapshot, RobosuiteEnv, make_with};

fn lift(horizon: u64) -> RobosuiteEnv {
    make_with("Lift", EnvConfig::default().with_horizon(horizon)).expect("Lift builds")
}

#[test]
fn lift_passes_check_env() {
    let mut env = lift(30);
    let report = check_env(&mut env, &CheckOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.passed(conformance_tests::Check::ResetSeedDeterminism));
    assert!(report.passed(conformance_tests::Check::InvalidAction));
    assert!(report.passed(conformance_tests::Check::StepAfterEnd));
}

#[test]
fn lift_passes_the_property_suite() {
    let config = PropConfig::cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(8),
        can_terminate: false,
    });
    let hook = FnStateHook::new(
        |env: &RobosuiteEnv| -> gym_core::Result<EnvSnapshot> { Ok(env.snapshot()) },
        |env: &mut RobosuiteEnv, s: &EnvSnapshot| env.restore(s),
    );
    let report =
        prop_check_env_with_state(|| lift(8), &hook, &config).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.skipped.is_empty(), "{:?}", report.skipped);
}
