//! The suite over wrapper stacks from `adapters` on robosuite's Lift (horizon 10): each stack
//! is checked with `check_env`, typed and boxed, and run through a cheap property suite;
//! `TimeLimit` stacks must truncate at exactly their limit.

use adapters::{Padding, WrapperExt};
use conformance_tests::prop::{EpisodeEndSpec, PropConfig, prop_check_env, prop_time_limit};
use conformance_tests::{Check, CheckOptions, Report, WarningKind, check_env};
use gym_core::{BoxedEnv, Env, IntoBoxedEnv};
use robosuite_env::{EnvConfig, RobosuiteEnv};

/// Lift's horizon in these stacks.
const HORIZON: u64 = 10;
/// The `TimeLimit` of the stacks that have one (shorter than the horizon, so the truncation
/// comes from the wrapper).
const LIMIT: u64 = 5;

fn lift() -> RobosuiteEnv {
    robosuite_env::make_with("Lift", EnvConfig::default().with_horizon(HORIZON))
        .expect("Lift builds")
}

fn cheap() -> PropConfig {
    PropConfig {
        cases: 8,
        max_actions: 8,
        max_shrink_iters: 32,
        ..PropConfig::default()
    }
}

/// `check_env` on the typed stack and on its boxed form; the stack is a wrapper, so the
/// "not the unwrapped environment" warning is expected.
fn check_both<E: Env>(name: &str, make: impl Fn() -> E, options: &CheckOptions) -> Report {
    let options = options.clone().name(name);
    let report = check_env(&mut make(), &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(report.has_warning(WarningKind::NotUnwrapped), "{report}");
    let boxed = check_env(&mut make().boxed(), &options).unwrap_or_else(|e| panic!("boxed: {e}"));
    assert_eq!(
        boxed.passed, report.passed,
        "{name}: typed and boxed differ"
    );
    for check in [
        Check::ResetSeedDeterminism,
        Check::StepPassive,
        Check::InvalidAction,
        Check::StepAfterEnd,
        Check::CloseTwice,
    ] {
        assert!(
            report.passed(check),
            "{name}: {check} did not pass\n{report}"
        );
    }
    report
}

#[test]
fn gym_wrapper_flat() {
    let make = || lift().gym_wrapper(None, true).unwrap();
    let report = check_both("GymWrapper(flat)", make, &CheckOptions::default());
    assert!(report.passed(Check::StepDeterminism));
    assert!(
        report.passed(Check::ObservationDtype),
        "flat observations are float32 in a float32 Box"
    );
    // What SB3 users train on: no SB3 warning at all.
    let sb3 = check_env(&mut make(), &CheckOptions::default().sb3(true)).unwrap();
    assert!(
        !sb3.warnings
            .iter()
            .any(|w| format!("{:?}", w.kind).starts_with("Sb3")),
        "{sb3}"
    );
    let config = cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(HORIZON),
        can_terminate: false,
    });
    prop_check_env(make, &config).unwrap();
}

#[test]
fn gym_wrapper_dict() {
    let make = || lift().gym_wrapper(None, false).unwrap();
    check_both("GymWrapper(dict)", make, &CheckOptions::default());
    prop_check_env(make, &cheap()).unwrap();
}

#[test]
fn time_limit_truncates_at_exactly_n() {
    let make = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .time_limit(LIMIT)
            .unwrap()
    };
    // Past its limit, TimeLimit (as Gymnasium's) passes the step on and keeps forcing
    // `truncated`: accepted unless the check is strict.
    check_both("FlatGymWrapper+TimeLimit", make, &CheckOptions::default());
    let strict = check_env(
        &mut make(),
        &CheckOptions::default().strict_step_after_end(true),
    )
    .unwrap_err();
    assert_eq!(strict.check(), Check::StepAfterEnd);
    let config = cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(LIMIT),
        can_terminate: false,
    });
    prop_check_env(make, &config).unwrap();
    prop_time_limit(make, LIMIT, &cheap()).unwrap();
    // The limit of a TimeLimit over a boxed environment from the registry.
    robosuite_env::register_envs();
    let boxed = || {
        let kwargs = serde_json::json!({ "horizon": HORIZON });
        gym_core::registry::make("Lift", &kwargs)
            .unwrap()
            .time_limit(3)
            .unwrap()
    };
    check_both("TimeLimit<BoxedEnv>", boxed, &CheckOptions::default());
    prop_time_limit(boxed, 3, &cheap()).unwrap();
}

#[test]
fn normalize_observation() {
    // The running statistics make each observation depend on the history, not only on the
    // seed and the actions: the stack is nondeterministic in Gymnasium's sense, so the
    // observation comparisons are skipped (the RNG-state checks still run).
    let make = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .time_limit(LIMIT)
            .unwrap()
            .normalize_observation()
            .unwrap()
    };
    let report = check_both(
        "FlatGymWrapper+TimeLimit+NormalizeObservation",
        make,
        &CheckOptions::default().nondeterministic(true),
    );
    assert!(
        report
            .skipped
            .iter()
            .any(|s| s.check == Check::StepDeterminism)
    );
    assert!(
        check_env(&mut make(), &CheckOptions::default()).is_err(),
        "the history dependence is visible"
    );
    let config = PropConfig {
        nondeterministic: true,
        ..cheap()
    }
    .episode_end(EpisodeEndSpec {
        truncate_at: Some(LIMIT),
        can_terminate: false,
    });
    prop_check_env(make, &config).unwrap();
    // With the statistics frozen, the stack is deterministic again.
    let frozen = || {
        let mut env = make();
        env.set_update_running_mean(false);
        env
    };
    check_both(
        "NormalizeObservation(frozen)",
        frozen,
        &CheckOptions::default(),
    );
}

#[test]
fn rescale_and_clip_action() {
    let make = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .rescale_action(0.0, 1.0)
            .unwrap()
            .clip_action()
            .unwrap()
    };
    let report = check_both(
        "FlatGymWrapper+RescaleAction(0,1)+ClipAction",
        make,
        &CheckOptions::default(),
    );
    // ClipAction's action space is Box(-inf, inf): Gymnasium warns, SB3 refuses it.
    assert!(
        report.has_warning(WarningKind::BoxUnboundedBelow),
        "{report}"
    );
    let sb3 = check_env(&mut make(), &CheckOptions::default().sb3(true)).unwrap_err();
    assert_eq!(sb3.check(), Check::Sb3ActionBounds);
    prop_check_env(make, &cheap()).unwrap();
    let rescaled = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .rescale_action(0.0, 1.0)
            .unwrap()
    };
    let report = check_both(
        "FlatGymWrapper+RescaleAction(0,1)",
        rescaled,
        &CheckOptions::default().sb3(true),
    );
    assert!(
        !report.has_warning(WarningKind::ActionSpaceNotNormalized),
        "[0, 1] is normalised for Gymnasium"
    );
    assert!(
        report.has_warning(WarningKind::Sb3ActionNotNormalized),
        "but not for SB3"
    );
}

#[test]
fn record_episode_statistics() {
    let make = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .time_limit(LIMIT)
            .unwrap()
            .record_episode_statistics()
    };
    check_both(
        "FlatGymWrapper+TimeLimit+RecordEpisodeStatistics",
        make,
        &CheckOptions::default(),
    );
    // `episode.t` is wall-clock time: left out of replay comparisons.
    let config = cheap()
        .ignore_info_key("episode.t")
        .episode_end(EpisodeEndSpec {
            truncate_at: Some(LIMIT),
            can_terminate: false,
        });
    prop_check_env(make, &config).unwrap();
    let err = prop_check_env(
        make,
        &PropConfig {
            max_actions: 8,
            ..cheap()
        },
    )
    .unwrap_err();
    assert_eq!(
        err.property,
        conformance_tests::Property::ReplayIdentical,
        "{err}"
    );
    assert!(err.message.contains("[\"episode\"][\"t\"]"), "{err}");
}

#[test]
fn frame_stack_observation() {
    let make = || {
        lift()
            .flat_gym_wrapper(None)
            .unwrap()
            .frame_stack_observation(3, Padding::Reset)
            .unwrap()
    };
    let report = check_both(
        "FlatGymWrapper+FrameStackObservation(3)",
        make,
        &CheckOptions::default().sb3(true),
    );
    assert!(
        report.has_warning(WarningKind::Sb3UnconventionalShape),
        "a (3, n) stack is neither 1-D nor an image"
    );
    let config = cheap().episode_end(EpisodeEndSpec {
        truncate_at: Some(HORIZON),
        can_terminate: false,
    });
    prop_check_env(make, &config).unwrap();
}

#[test]
fn order_enforcing_and_passive_checker_over_boxed() {
    let make = || -> BoxedEnv {
        lift()
            .gym_wrapper(None, true)
            .unwrap()
            .passive_env_checker()
            .unwrap()
            .order_enforcing()
            .boxed()
    };
    let report = check_env(
        &mut make(),
        &CheckOptions::default().name("OrderEnforcing+PassiveEnvChecker"),
    )
    .unwrap();
    assert!(report.passed(Check::StepAfterEnd), "{report}");
    prop_check_env(make, &cheap()).unwrap();
}
