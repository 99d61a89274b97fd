//! The Rust half of the fuzz suite (issue #17): proptest over actions, states, configs,
//! scene edits, vector batches and call sequences. Every call must return `Ok` or a typed
//! error, never panic or abort; a rejected call must change nothing; a diverged or failed
//! simulation must never be reported as a success. `FUZZ_CASES` sets the cases per property
//! (16 by default, so that `make test` stays fast; `make fuzz` runs 256).

mod common;

use adapters::{SyncVectorEnv, VectorEnv};
use gym_core::{Env, Error};
use ndarray::{ArrayD, IxDyn};
use proptest::prelude::*;
use proptest::test_runner::Config;
use robosuite_env::{
    EnvConfig, InitNoise, NoiseKind, RobosuiteEnv, make, make_from_scene_xml, make_with,
};

fn config() -> Config {
    let cases = std::env::var("FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(16);
    Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    }
}

/// Any f64, weighted towards the values that break things.
fn nasty_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => -2.0..2.0f64,
        1 => Just(f64::NAN),
        1 => Just(f64::INFINITY),
        1 => Just(f64::NEG_INFINITY),
        1 => prop::num::f64::ANY,
        1 => Just(1e10),
        1 => Just(-1e300),
    ]
}

/// An error that a user may get: anything but a panic. (Every `Error` is typed; this
/// names the variants the calls below are documented to return.)
fn typed(e: &Error) -> bool {
    matches!(
        e,
        Error::InvalidAction(_)
            | Error::InvalidArgument { .. }
            | Error::Simulation(_)
            | Error::ResetNeeded
            | Error::EpisodeEnded
            | Error::Closed
            | Error::Model(_)
            | Error::Space(_)
            | Error::UnknownKey { .. }
    )
}

fn lift() -> RobosuiteEnv {
    let mut env = make("Lift").unwrap();
    env.reset(Some(0), None).unwrap();
    env
}

#[derive(Debug, Clone)]
enum Call {
    Reset(Option<u64>),
    Step(Vec<f64>),
    SetState(Vec<f64>),
    SetStateNear(usize, f64),
    Snapshot,
    Restore,
    Close,
}

fn call() -> impl Strategy<Value = Call> {
    prop_oneof![
        1 => prop::option::of(0..4u64).prop_map(Call::Reset),
        6 => prop::collection::vec(nasty_f64(), 5..9).prop_map(Call::Step),
        1 => prop::collection::vec(nasty_f64(), 0..40).prop_map(Call::SetState),
        2 => (0..32usize, nasty_f64()).prop_map(|(i, v)| Call::SetStateNear(i, v)),
        1 => Just(Call::Snapshot),
        1 => Just(Call::Restore),
        1 => Just(Call::Close),
    ]
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn actions_are_stepped_or_rejected_without_effect(values in prop::collection::vec(nasty_f64(), 0..12)) {
        let mut env = lift();
        let before = env.get_state();
        let action = ArrayD::from_shape_vec(IxDyn(&[values.len()]), values.clone()).unwrap();
        match env.step(&action) {
            Ok(step) => {
                prop_assert!(values.len() == 7 && values.iter().all(|v| v.is_finite()));
                prop_assert!(step.reward.is_finite());
            }
            Err(e) => {
                prop_assert!(matches!(e, Error::InvalidAction(_)), "{e}");
                prop_assert_eq!(env.get_state(), before);
            }
        }
    }

    #[test]
    fn states_are_set_or_rejected_and_steps_never_diverge_silently(
        edits in prop::collection::vec((0..32usize, nasty_f64()), 0..4),
        scale in prop_oneof![Just(1.0), Just(1e3), Just(1e6)],
    ) {
        let mut env = lift();
        let mut state = env.get_state();
        for &(i, v) in &edits {
            state[i] = v * scale;
        }
        let before = env.get_state();
        match env.set_state(&state) {
            Ok(()) => {
                for _ in 0..2 {
                    match env.step(&ArrayD::zeros(IxDyn(&[7]))) {
                        Ok(step) => prop_assert!(step.reward.is_finite()),
                        Err(e) => {
                            prop_assert!(matches!(e, Error::Simulation(_) | Error::ResetNeeded), "{e}");
                            break;
                        }
                    }
                }
            }
            Err(e) => {
                prop_assert!(matches!(e, Error::InvalidArgument { .. }), "{e}");
                prop_assert_eq!(env.get_state(), before);
            }
        }
    }

    #[test]
    fn configs_make_an_env_or_a_typed_error(
        hz in nasty_f64().prop_map(|v| v * 50.0),
        horizon in 0..2000u64,
        noise in nasty_f64(),
    ) {
        let config = EnvConfig {
            horizon,
            ..EnvConfig::default()
        }
        .with_control_freq(hz)
        .with_initialization_noise(InitNoise { magnitude: noise, kind: NoiseKind::Uniform });
        match make_with("Lift", config) {
            Ok(mut env) => {
                prop_assert!(env.substeps() >= 1 && env.substeps() <= robosuite_env::config::MAX_SUBSTEPS);
                env.reset(Some(1), None).unwrap();
            }
            Err(e) => prop_assert!(matches!(e, Error::InvalidArgument { .. }), "{e}"),
        }
    }

    #[test]
    fn scene_edits_make_an_env_or_a_typed_error(
        memory_kib in prop_oneof![Just(1u64), Just(16), Just(64), Just(512), Just(4096)],
        timestep in prop_oneof![Just(1e-9), Just(1e-5), Just(0.002), Just(0.05), Just(1.0)],
    ) {
        let xml = robosuite_env::scene_xml("Lift", &EnvConfig::default()).unwrap();
        let end = xml.rfind("</mujoco>").unwrap();
        let extra = format!(r#"<size memory="{memory_kib}K"/><option timestep="{timestep}"/>"#);
        let xml = format!("{}{extra}{}", &xml[..end], &xml[end..]);
        match make_from_scene_xml("Lift", &xml, EnvConfig::default()) {
            Ok(mut env) => {
                env.reset(Some(0), None).unwrap();
                for _ in 0..2 {
                    if let Err(e) = env.step(&ArrayD::zeros(IxDyn(&[7]))) {
                        prop_assert!(matches!(e, Error::Simulation(_) | Error::ResetNeeded | Error::EpisodeEnded), "{e}");
                        break;
                    }
                }
            }
            Err(e) => prop_assert!(matches!(e, Error::Model(_) | Error::InvalidArgument { .. }), "{e}"),
        }
    }

    #[test]
    fn vector_batches_are_exact_or_change_nothing(
        rows in 0..4usize,
        cols in 5..9usize,
        values in prop::collection::vec(nasty_f64(), 32),
    ) {
        let mut v = SyncVectorEnv::new(vec![make("Lift").unwrap(), make("Lift").unwrap()]).unwrap();
        let _ = v.reset(3u64, None).unwrap();
        let before = v.observations().clone();
        let batch = ArrayD::from_shape_vec(IxDyn(&[rows, cols]), values[..rows * cols].to_vec()).unwrap();
        match v.step(&batch) {
            Ok(_) => prop_assert!(rows == 2 && cols == 7 && values[..14].iter().all(|x| x.is_finite())),
            Err(e) => {
                prop_assert!(matches!(e, Error::InvalidAction(_)), "{e}");
                prop_assert_eq!(v.observations(), &before);
            }
        }
    }

    #[test]
    fn call_sequences_never_panic(calls in prop::collection::vec(call(), 1..12)) {
        let mut env = lift();
        let mut saved = None;
        for c in calls {
            let result = match c {
                Call::Reset(seed) => env.reset(seed, None).map(|_| ()),
                Call::Step(values) => {
                    let a = ArrayD::from_shape_vec(IxDyn(&[values.len()]), values).unwrap();
                    env.step(&a).map(|s| assert!(s.reward.is_finite()))
                }
                Call::SetState(s) => env.set_state(&s),
                Call::SetStateNear(i, v) => {
                    let mut s = env.get_state();
                    s[i] = v;
                    env.set_state(&s)
                }
                Call::Snapshot => {
                    saved = Some(env.snapshot());
                    Ok(())
                }
                Call::Restore => saved.as_ref().map_or(Ok(()), |s| env.restore(s)),
                Call::Close => {
                    env.close();
                    Ok(())
                }
            };
            if let Err(e) = result {
                prop_assert!(typed(&e), "{e:?}");
            }
        }
    }
}
