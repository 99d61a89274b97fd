//! Every check catches its defect: each deliberately broken environment fails with the
//! exact check (or property) meant for it, typed and boxed, and the same environment
//! without the defect passes everything.

use conformance_tests::broken::{BrokenEnv, BrokenStateHook, Caught, Defect, SharedBufferEnv};
use conformance_tests::prop::{
    prop_check_env_with_state, prop_observations_in_space, prop_replay_identical,
};
use conformance_tests::{Check, CheckOptions, Property, WarningKind, check_env};
use gym_core::{BoxedEnv, IntoBoxedEnv};

fn check_defect(defect: Defect) -> Result<(), String> {
    let expected = defect
        .caught_by()
        .ok_or("Defect::None has no expected check")?;
    match expected {
        Caught::Check(check) => {
            for boxed in [false, true] {
                let options = BrokenEnv::check_options();
                let result = if boxed {
                    check_env(&mut BrokenEnv::new(defect).boxed(), &options)
                } else {
                    check_env(&mut BrokenEnv::new(defect), &options)
                };
                let err = result
                    .err()
                    .ok_or_else(|| format!("{defect:?} passed check_env (boxed: {boxed})"))?;
                if err.check() != check {
                    return Err(format!(
                        "{defect:?} (boxed: {boxed}) failed {:?}, expected {check:?}: {err}",
                        err.check()
                    ));
                }
                assert!(!err.first().message.is_empty());
                println!("{defect:?} (boxed: {boxed}) -> {}", err.first());
            }
        }
        Caught::Property(property) => {
            let failure = prop_check_env_with_state(
                || BrokenEnv::new(defect),
                &BrokenStateHook,
                &BrokenEnv::prop_config(),
            )
            .err()
            .ok_or_else(|| format!("{defect:?} passed the property suite"))?;
            if failure.property != property {
                return Err(format!(
                    "{defect:?} failed {:?}, expected {property:?}: {failure}",
                    failure.property
                ));
            }
            let boxed = prop_check_env_with_state(
                || -> BoxedEnv { BrokenEnv::new(defect).boxed() },
                &BrokenStateHook,
                &BrokenEnv::prop_config(),
            )
            .err()
            .ok_or_else(|| format!("{defect:?} (boxed) passed the property suite"))?;
            if boxed.property != property {
                return Err(format!(
                    "{defect:?} (boxed) failed {:?}, expected {property:?}",
                    boxed.property
                ));
            }
            println!("{defect:?} -> {failure}");
        }
    }
    Ok(())
}

#[test]
fn every_defect_is_caught_by_its_check() {
    let problems: Vec<String> = Defect::ALL
        .iter()
        .filter_map(|&d| check_defect(d).err())
        .collect();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn the_same_env_without_defect_passes_everything() {
    let report = check_env(
        &mut BrokenEnv::new(Defect::None),
        &BrokenEnv::check_options(),
    )
    .unwrap();
    for check in [
        Check::ActionSpace,
        Check::ObservationSpace,
        Check::ResetReturnType,
        Check::ResetSeedDeterminism,
        Check::ResetOptions,
        Check::ResetPassive,
        Check::StepPassive,
        Check::StepDeterminism,
        Check::ReturnedDataNotReused,
        Check::InvalidAction,
        Check::StepAfterEnd,
        Check::Render,
        Check::CloseTwice,
        Check::ObservationDtype,
        Check::RewardFinite,
    ] {
        assert!(report.passed(check), "{check} did not pass:\n{report}");
    }
    check_env(
        &mut BrokenEnv::new(Defect::None).boxed(),
        &BrokenEnv::check_options(),
    )
    .unwrap();
    let props = prop_check_env_with_state(
        || BrokenEnv::new(Defect::None),
        &BrokenStateHook,
        &BrokenEnv::prop_config(),
    )
    .unwrap();
    assert_eq!(props.passed.len(), 8, "{props:?}");
    assert!(props.skipped.is_empty());
}

#[test]
fn messages_say_what_was_observed() {
    let msg = |d| {
        check_env(&mut BrokenEnv::new(d), &BrokenEnv::check_options())
            .unwrap_err()
            .first()
            .message
            .clone()
    };
    let m = msg(Defect::WrongObsDtype);
    assert!(
        m.starts_with(
            "The obs returned by the `reset()` method was expecting numpy array dtype to be float32, actual type: float64"
        ),
        "{m}"
    );
    assert!(m.contains("check_reset_return_type"), "{m}");
    assert!(msg(Defect::ObsOutsideSpace).contains("element [0] = 20 is outside [-10, 10]"));
    assert!(msg(Defect::NanReward).starts_with("The reward is a NaN value"));
    assert!(
        msg(Defect::IgnoredSeed).starts_with("Using `env.reset(seed=123)` is non-deterministic")
    );
    assert!(
        msg(Defect::NoRng)
            .starts_with("Expects the random number generator to have been generated")
    );
    assert!(msg(Defect::InfoChangesBetweenReplays).contains("Deterministic step info are not equivalent for the same seed and action. First difference: [\"calls\"] differs"));
    assert!(msg(Defect::TruncatesAfterOneStep).starts_with("Environment truncates after 1 step"));
    assert!(
        msg(Defect::ClosePanicsTwice)
            .starts_with("Calling `env.close()` on the closed environment should be allowed")
    );
    assert_eq!(
        msg(Defect::EmptyDictObservationSpace),
        "An empty Dict observation space is not allowed."
    );
    assert!(
        msg(Defect::InvalidActionAccepted)
            .contains("accepted an action outside the action space (NaN at [0])")
    );
    assert!(
        msg(Defect::InvalidActionPanics).contains("panicked on an action outside the action space")
    );
    assert!(msg(Defect::InvalidActionCorruptsState).contains("differs from a replay without it"));
    assert!(msg(Defect::StepAfterEndAccepted).contains("the episode ended at step 8"));
    assert!(
        msg(Defect::ResetIgnoresOptions).contains("The reset option `position` was not honoured")
    );
    assert!(
        msg(Defect::UndeclaredRenderMode)
            .contains("unsupported render mode. Render mode: rgb_array")
    );
}

#[test]
fn ignored_seed_is_caught_by_the_rng_checks_too() {
    // With the observation comparisons off (a nondeterministic env), the RNG state still
    // shows that the seed was ignored.
    let options = BrokenEnv::check_options().nondeterministic(true);
    let err = check_env(&mut BrokenEnv::new(Defect::IgnoredSeed), &options).unwrap_err();
    assert_eq!(err.check(), Check::ResetSeedDeterminism);
    assert!(
        err.first()
            .message
            .contains("the random generates are not same"),
        "{err}"
    );
}

#[test]
fn no_rng_is_a_warning_when_not_required() {
    let options = BrokenEnv::check_options().require_rng(false);
    let report = check_env(&mut BrokenEnv::new(Defect::NoRng), &options).unwrap();
    assert!(report.has_warning(WarningKind::NoRng));
}

#[test]
fn keep_going_reports_every_failure() {
    let options = BrokenEnv::check_options().keep_going(true);
    let err = check_env(&mut BrokenEnv::new(Defect::NanReward), &options).unwrap_err();
    assert_eq!(err.check(), Check::RewardFinite);
    assert!(
        err.failures().all(|f| f.check == Check::RewardFinite),
        "{err}"
    );
    assert!(err.failures().count() > 1);
    assert!(err.report().passed(Check::ResetSeedDeterminism));
    assert!(err.report().passed(Check::CloseTwice));
}

#[test]
fn reused_buffers_are_caught() {
    let err = check_env(&mut SharedBufferEnv::new(), &CheckOptions::default()).unwrap_err();
    assert_eq!(err.check(), Check::ReturnedDataNotReused, "{err}");
    assert!(
        err.first()
            .message
            .contains("The observation returned by step 1 changed after later calls"),
        "{err}"
    );
}

#[test]
fn shrinking_finds_the_minimal_sequence() {
    let config = BrokenEnv::prop_config();
    let f =
        prop_observations_in_space(|| BrokenEnv::new(Defect::ObsEscapesLate), &config).unwrap_err();
    assert_eq!(f.property, Property::ObservationsInSpace);
    assert_eq!(f.minimal_actions, Some(3), "{f}");
    assert!(f.message.contains("episode step 3"), "{f}");
    let f = prop_replay_identical(|| BrokenEnv::new(Defect::ReplayDiverges), &config).unwrap_err();
    assert_eq!(f.property, Property::ReplayIdentical);
    assert_eq!(f.minimal_actions, Some(4), "{f}");
}

#[test]
fn property_defects_pass_check_env_where_expected() {
    // These defects only show over several steps or through a declared contract, which is
    // why the property suite exists.
    for d in [
        Defect::ReplayDiverges,
        Defect::HorizonReportedAsTerminated,
        Defect::TruncatesLate,
        Defect::StateRoundTripLosesVelocity,
    ] {
        check_env(&mut BrokenEnv::new(d), &BrokenEnv::check_options())
            .unwrap_or_else(|e| panic!("{d:?}: {e}"));
    }
}

#[test]
fn single_checks_can_run_alone() {
    use conformance_tests::{
        check_close, check_reset_seed_determinism, check_step_after_end, check_step_determinism,
    };
    let options = BrokenEnv::check_options();
    assert!(check_reset_seed_determinism(&mut BrokenEnv::new(Defect::None), &options).is_ok());
    assert_eq!(
        check_reset_seed_determinism(&mut BrokenEnv::new(Defect::NoRng), &options)
            .unwrap_err()
            .check,
        Check::ResetSeedDeterminism
    );
    assert_eq!(
        check_step_determinism(&mut BrokenEnv::new(Defect::NonDeterministicStep), &options)
            .unwrap_err()
            .check,
        Check::StepDeterminism
    );
    assert_eq!(
        check_step_after_end(&mut BrokenEnv::new(Defect::StepAfterEndAccepted), &options)
            .unwrap_err()
            .check,
        Check::StepAfterEnd
    );
    let mut env = BrokenEnv::new(Defect::ClosePanicsTwice);
    assert_eq!(
        check_close(&mut env, &options).unwrap_err().check,
        Check::CloseTwice
    );
}
