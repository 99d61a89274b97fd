//! The suite over every environment in `gym_core::registry`: robosuite's tasks (registered
//! by `robosuite_env::register_envs`) and this crate's reference environments, each made
//! by id, checked with `check_env` and run through the property suite.
//!
//! MuJoCo environments are kept cheap: a horizon of 10 steps, 8 property cases of at most
//! 8 actions.

use conformance_tests::prop::{
    EpisodeEndSpec, FnStateHook, PropConfig, prop_check_env, prop_state_round_trip,
};
use conformance_tests::toy::{GridWorld, PointMass};
use conformance_tests::{Check, CheckOptions, check_env};
use gym_core::registry::{self, EnvSpec, register, registered_ids};
use gym_core::{BoxedEnv, Env, EnvExt, Error, IntoBoxedEnv, Result};
use robosuite_env::{EnvSnapshot, RobosuiteEnv};
use std::sync::{Arc, Once};

/// The horizon the robosuite environments are made with.
const HORIZON: u64 = 10;

fn register_all() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        robosuite_env::register_envs();
        register(EnvSpec {
            id: "PointMass-v0".into(),
            factory: Arc::new(|_| Ok(PointMass::new().with_horizon(HORIZON).boxed())),
            max_episode_steps: Some(HORIZON),
            nondeterministic: false,
            description: "conformance-tests' reference point mass".into(),
        });
        register(EnvSpec {
            id: "GridWorld-v0".into(),
            factory: Arc::new(|_| Ok(GridWorld::default().with_horizon(HORIZON).boxed())),
            max_episode_steps: Some(HORIZON),
            nondeterministic: false,
            description: "Gymnasium's tutorial grid world".into(),
        });
    });
}

fn is_robosuite(id: &str) -> bool {
    robosuite_env::ENV_NAMES.contains(&id)
}

/// Keyword arguments that keep an environment cheap.
fn kwargs(id: &str) -> serde_json::Value {
    if is_robosuite(id) {
        serde_json::json!({ "horizon": HORIZON })
    } else {
        serde_json::Value::Null
    }
}

fn make(id: &str) -> BoxedEnv {
    registry::make(id, &kwargs(id)).unwrap_or_else(|e| panic!("make({id}): {e}"))
}

/// robosuite tasks other than Wipe have no terminal states; our grid world has.
fn episode_end(id: &str) -> EpisodeEndSpec {
    EpisodeEndSpec {
        truncate_at: Some(HORIZON),
        can_terminate: id == "GridWorld-v0",
    }
}

#[test]
fn every_registered_env_passes_check_env() {
    register_all();
    let ids = registered_ids();
    assert!(
        ids.iter().any(|id| id == "Lift"),
        "robosuite's Lift is registered: {ids:?}"
    );
    for id in &ids {
        let spec = registry::spec(id).unwrap();
        let options = CheckOptions::default()
            .name(id.clone())
            .nondeterministic(spec.nondeterministic)
            .max_episode_steps(100);
        let report = check_env(&mut make(id), &options).unwrap_or_else(|e| panic!("{id}: {e}"));
        for check in [
            Check::ResetSeedDeterminism,
            Check::StepDeterminism,
            Check::InvalidAction,
            Check::StepAfterEnd,
        ] {
            assert!(report.passed(check), "{id}: {check} did not pass\n{report}");
        }
        println!("{report}");
    }
}

#[test]
fn every_registered_env_passes_the_property_suite() {
    register_all();
    for id in registered_ids() {
        let config = if is_robosuite(&id) {
            PropConfig {
                cases: 8,
                max_actions: 8,
                max_shrink_iters: 32,
                ..PropConfig::default()
            }
        } else {
            PropConfig {
                cases: 16,
                max_actions: 12,
                ..PropConfig::default()
            }
        }
        .episode_end(episode_end(&id));
        let report = prop_check_env(|| make(&id), &config).unwrap_or_else(|e| panic!("{id}: {e}"));
        println!("{id}: {report:?}");
    }
}

fn robosuite(env: &BoxedEnv) -> Result<&RobosuiteEnv> {
    env.unwrapped_as::<RobosuiteEnv>()
        .ok_or_else(|| Error::unsupported("not a RobosuiteEnv"))
}

fn robosuite_mut(env: &mut BoxedEnv) -> Result<&mut RobosuiteEnv> {
    env.unwrapped_as_mut::<RobosuiteEnv>()
        .ok_or_else(|| Error::unsupported("not a RobosuiteEnv"))
}

#[test]
fn robosuite_snapshots_replay_identically() {
    register_all();
    let hook = FnStateHook::new(
        |env: &BoxedEnv| -> Result<EnvSnapshot> { Ok(robosuite(env)?.snapshot()) },
        |env: &mut BoxedEnv, s: &EnvSnapshot| robosuite_mut(env)?.restore(s),
    );
    let config = PropConfig {
        cases: 8,
        max_actions: 8,
        max_shrink_iters: 32,
        ..PropConfig::default()
    };
    for id in robosuite_env::ENV_NAMES {
        prop_state_round_trip(|| make(id), &hook, &config).unwrap_or_else(|e| panic!("{id}: {e}"));
    }
}

#[test]
fn robosuite_get_state_set_state_round_trips() {
    register_all();
    for id in robosuite_env::ENV_NAMES {
        let mut env = make(id);
        env.reset(Some(3), None).unwrap();
        let state = robosuite(&env).unwrap().get_state();
        let action = env.action_space().clone();
        let a = gym_core::Space::sample(&action, &mut gym_core::rng_from_seed(1));
        let _ = env.step(&a).unwrap();
        assert_ne!(robosuite(&env).unwrap().get_state(), state);
        robosuite_mut(&mut env).unwrap().set_state(&state).unwrap();
        assert_eq!(
            robosuite(&env).unwrap().get_state(),
            state,
            "{id}: get_state after set_state"
        );
    }
}

#[test]
fn typed_lift_passes_check_env_and_properties() {
    let make = || {
        robosuite_env::make_with(
            "Lift",
            robosuite_env::EnvConfig::default().with_horizon(HORIZON),
        )
        .unwrap()
    };
    let report = check_env(&mut make(), &CheckOptions::default().sb3(true))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(!report.has_warning(conformance_tests::WarningKind::NotUnwrapped));
    let hook = FnStateHook::new(
        |env: &RobosuiteEnv| -> Result<EnvSnapshot> { Ok(env.snapshot()) },
        |env: &mut RobosuiteEnv, s: &EnvSnapshot| env.restore(s),
    );
    let config = PropConfig {
        cases: 8,
        max_actions: 8,
        max_shrink_iters: 32,
        ..PropConfig::default()
    }
    .episode_end(EpisodeEndSpec {
        truncate_at: Some(HORIZON),
        can_terminate: false,
    });
    conformance_tests::prop::prop_check_env_with_state(make, &hook, &config)
        .unwrap_or_else(|e| panic!("{e}"));
}
