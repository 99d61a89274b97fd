//! The GymWrapper and the vector environments over robosuite's Lift (MuJoCo). Kept few and
//! short: small horizons, a handful of steps.

use adapters::{FlatGymWrapper, GymWrapper, SyncVectorEnv, ThreadVectorEnv, VectorEnv, WrapperExt};
use gym_core::{DType, Env, Error, Space, Value, rng_from_seed};
use ndarray::{ArrayD, Axis, IxDyn};
use robosuite_env::{EnvConfig, RobosuiteEnv};

fn lift(horizon: u64) -> RobosuiteEnv {
    robosuite_env::make_with("Lift", EnvConfig::default().with_horizon(horizon))
        .expect("Lift builds")
}

fn f32s(v: &Value) -> Vec<f32> {
    v.as_array()
        .expect("array")
        .to_f64_vec()
        .iter()
        .map(|&x| x as f32)
        .collect()
}

#[test]
fn gym_wrapper_over_lift() -> Result<(), Error> {
    let mut env = lift(3).gym_wrapper(None, true)?;
    assert_eq!(env.keys(), ["object-state", "robot0_proprio-state"]);
    assert_eq!(
        env.observation_space().to_string(),
        "Box(-inf, inf, [60], float32)"
    );
    let act = env.action_space().clone();
    assert_eq!(
        (act.dtype(), act.shape()),
        (DType::F32, Some(&[7usize][..]))
    );
    assert!(act.low().iter().all(|&v| v == -1.0) && act.high().iter().all(|&v| v == 1.0));

    let (obs, _) = env.reset(Some(0), None)?;
    let flat = obs.as_array().unwrap();
    assert_eq!((flat.dtype(), flat.len()), (DType::F32, 60));
    assert!(env.observation_space().contains(&obs));

    // object-state comes first: compare with the raw env reset with the same seed.
    let mut raw = lift(3);
    let (raw_obs, _) = raw.reset(Some(0), None)?;
    let object: Vec<f32> = f32s(&raw_obs["object-state"]);
    let proprio: Vec<f32> = f32s(&raw_obs["robot0_proprio-state"]);
    let got = f32s(&obs);
    assert_eq!(&got[..10], &object[..]);
    assert_eq!(&got[10..], &proprio[..]);

    // The seed really seeds: same seed, same observation; another seed, another one.
    let (again, _) = env.reset(Some(0), None)?;
    assert_eq!(again, obs);
    let (other, _) = env.reset(Some(1), None)?;
    assert_ne!(other, obs);

    // The horizon is reported as truncated, with info["success"].
    env.reset(Some(0), None)?;
    let zero = ArrayD::zeros(IxDyn(&[7]));
    let flags: Vec<(bool, bool, Option<bool>)> = (0..3)
        .map(|_| {
            env.step(&zero)
                .map(|s| (s.terminated, s.truncated, s.info.get_bool("success")))
        })
        .collect::<Result<_, _>>()?;
    assert_eq!(
        flags,
        [
            (false, false, Some(false)),
            (false, false, Some(false)),
            (false, true, Some(false))
        ]
    );
    Ok(())
}

#[test]
fn gym_wrapper_keys_on_lift() {
    let err =
        GymWrapper::new(lift(3), Some(vec!["cube_pos".into(), "nope".into()]), true).unwrap_err();
    match err {
        Error::UnknownKey { key, available } => {
            assert_eq!(key, "nope");
            assert!(
                available.iter().any(|k| k == "object-state"),
                "{available:?}"
            );
        }
        other => panic!("{other}"),
    }
    let env = GymWrapper::new(
        lift(3),
        Some(vec!["cube_pos".into(), "robot0_eef_quat_site".into()]),
        false,
    )
    .unwrap();
    let space = env.observation_space().as_dict().unwrap();
    assert_eq!(
        space.keys().collect::<Vec<_>>(),
        ["cube_pos", "robot0_eef_quat_site"]
    );
    assert_eq!(
        space
            .get("robot0_eef_quat_site")
            .unwrap()
            .as_box()
            .unwrap()
            .dtype(),
        DType::F32
    );
}

#[test]
fn gym_wrapper_over_a_registry_made_lift() -> Result<(), Error> {
    robosuite_env::register_envs();
    let boxed = gym_core::registry::make("Lift", &serde_json::json!({"horizon": 2}))?;
    let mut env = boxed.gym_wrapper(None, true)?.time_limit(10)?;
    assert_eq!(env.observation_space().shape(), Some(&[60usize][..]));
    let (obs, _) = env.reset(Some(0), None)?;
    let mut typed = lift(2).gym_wrapper(None, true)?;
    assert_eq!(obs, typed.reset(Some(0), None)?.0);
    let zero = ArrayD::zeros(IxDyn(&[7]));
    let _ = env.step(&zero)?;
    assert!(env.step(&zero)?.truncated);
    Ok(())
}

/// Two Lift envs: a vector env (sync and threaded) and single envs agree step for step,
/// through an autoreset (horizon 2, 4 steps).
#[test]
fn vector_lift_equals_single_envs() -> Result<(), Error> {
    let make = || FlatGymWrapper::new(lift(2), None);
    let mut sync = SyncVectorEnv::new(vec![make()?, make()?])?;
    let mut threaded = ThreadVectorEnv::new(vec![make()?, make()?])?;
    let mut singles = [make()?, make()?];
    let seed = 5;
    let reset_sync = sync.reset(seed, None)?.0.clone();
    let reset_thread = threaded.reset(seed, None)?.0.clone();
    assert_eq!(reset_sync, reset_thread);
    for (i, e) in singles.iter_mut().enumerate() {
        assert_eq!(
            reset_sync.index_axis(Axis(0), i),
            e.reset(Some(seed + i as u64), None)?.0
        );
    }
    let mut rng = rng_from_seed(1);
    let mut pending = [false; 2];
    for t in 0..4 {
        let actions = sync.action_space().sample(&mut rng);
        let s = sync.step(&actions)?;
        let (obs, rewards, truncs) = (
            s.observations.clone(),
            s.rewards.to_vec(),
            s.truncations.to_vec(),
        );
        let th = threaded.step(&actions)?;
        assert_eq!(
            (th.observations, th.rewards, th.truncations),
            (&obs, &rewards[..], &truncs[..]),
            "step {t}"
        );
        for (i, e) in singles.iter_mut().enumerate() {
            let (o, r, tr) = if pending[i] {
                (e.reset(None, None)?.0, 0.0, false)
            } else {
                let st = e.step(&actions.index_axis(Axis(0), i).to_owned())?;
                (st.observation, st.reward, st.truncated)
            };
            pending[i] = tr;
            assert_eq!(obs.index_axis(Axis(0), i), o, "step {t}, env {i}");
            assert_eq!((rewards[i], truncs[i]), (r, tr), "step {t}, env {i}");
        }
    }
    // Step 5 is the second step after the autoreset: the horizon again.
    assert_eq!(
        sync.step(&ArrayD::zeros(IxDyn(&[2, 7])))?.truncations,
        &[true, true]
    );
    threaded.close();
    Ok(())
}
