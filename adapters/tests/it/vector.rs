//! Vector environments: Gymnasium's autoreset traces, masks, seeds, infos, equivalence with
//! single environments, and failure handling (toy environments only).

use crate::common::{CountEnv, DictEnv, DiscreteEnv, WalkEnv, a32};
use adapters::vector::VectorInfoValue;
use adapters::{AutoresetMode, BatchSpace, Seeds, SyncVectorEnv, ThreadVectorEnv, VectorEnv};
use gym_core::{ArrayValue, Env, Error, Info, InfoValue, Space, Value};
use ndarray::{ArrayD, Axis, IxDyn, arr1, arr2};

fn counts() -> Vec<CountEnv> {
    vec![CountEnv::new(Some(2), None), CountEnv::new(Some(3), None)]
}

fn col(obs: &ArrayD<f64>) -> Vec<f64> {
    obs.iter().copied().collect()
}

/// (obs, rewards, terminations) of `steps` steps.
fn trace<V: VectorEnv>(
    v: &mut V,
    steps: usize,
    actions: &adapters::BatchOf<V::ActSpace>,
) -> Vec<(Vec<f64>, Vec<f64>, Vec<bool>)>
where
    adapters::BatchOf<V::ObsSpace>: AsF64,
{
    (0..steps)
        .map(|_| {
            let s = v.step(actions).unwrap();
            (
                s.observations.f64s(),
                s.rewards.to_vec(),
                s.terminations.to_vec(),
            )
        })
        .collect()
}

trait AsF64 {
    fn f64s(&self) -> Vec<f64>;
}

impl AsF64 for ArrayD<f64> {
    fn f64s(&self) -> Vec<f64> {
        col(self)
    }
}

fn zeros2() -> ArrayD<i64> {
    ArrayD::zeros(IxDyn(&[2]))
}

fn next_step_trace<V: VectorEnv<ActSpace = gym_core::spaces::Discrete>>(mut v: V)
where
    adapters::BatchOf<V::ObsSpace>: AsF64,
{
    assert_eq!(v.autoreset_mode(), AutoresetMode::NextStep);
    v.reset(Seeds::None, None).unwrap();
    let t = trace(&mut v, 4, &zeros2());
    assert_eq!(
        t,
        vec![
            (vec![1.0, 1.0], vec![1.0, 1.0], vec![false, false]),
            (vec![2.0, 2.0], vec![2.0, 2.0], vec![true, false]),
            (vec![0.0, 3.0], vec![0.0, 3.0], vec![false, true]),
            (vec![1.0, 0.0], vec![1.0, 0.0], vec![false, false]),
        ]
    );
}

#[test]
fn next_step_trace_matches_gymnasium() {
    next_step_trace(SyncVectorEnv::new(counts()).unwrap());
    next_step_trace(ThreadVectorEnv::new(counts()).unwrap());
}

fn next_step_infos<V: VectorEnv<ActSpace = gym_core::spaces::Discrete>>(mut v: V) {
    v.reset(None, None).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let s = v.step(&zeros2()).unwrap();
    // {'step': [0, 3], '_step': [F, T], 'reset': [T, F], '_reset': [T, F]}
    let infos = s.infos;
    assert_eq!(infos.get("step").unwrap().as_ints(), Some(&[0i64, 3][..]));
    assert_eq!(infos.mask("step"), Some(&[false, true][..]));
    assert_eq!(
        infos.get("reset").unwrap().as_bools(),
        Some(&[true, false][..])
    );
    assert_eq!(infos.mask("reset"), Some(&[true, false][..]));
    assert_eq!(infos.len(), 4);
    assert_eq!(infos.env_info(0), Info::new().with("reset", true));
}

#[test]
fn next_step_infos_have_masks() {
    next_step_infos(SyncVectorEnv::new(counts()).unwrap());
    next_step_infos(ThreadVectorEnv::with_threads(counts(), 2).unwrap());
}

fn same_step_trace<V: VectorEnv<ActSpace = gym_core::spaces::Discrete>>(mut v: V)
where
    adapters::BatchOf<V::ObsSpace>: AsF64,
{
    assert_eq!(v.autoreset_mode(), AutoresetMode::SameStep);
    v.reset(None, None).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(s.observations.f64s(), vec![0.0, 2.0]);
    assert_eq!(s.rewards, &[2.0, 2.0]);
    assert_eq!(s.terminations, &[true, false]);
    let infos = s.infos;
    assert_eq!(
        infos.final_observation(0),
        Some(&Value::from(arr1(&[2.0]).into_dyn()))
    );
    assert_eq!(infos.final_observation(1), None);
    assert_eq!(infos.mask("final_obs"), Some(&[true, false][..]));
    assert_eq!(infos.mask("final_info"), Some(&[true, false][..]));
    let fi = infos.get("final_info").unwrap().as_map().unwrap();
    assert_eq!(fi.get("step").unwrap().as_ints(), Some(&[2i64, 0][..]));
    assert_eq!(fi.mask("step"), Some(&[true, false][..]));
    assert_eq!(infos.final_info(0), Some(Info::new().with("step", 2i64)));
    // The reset's info is merged at the top level for env 0, the step's for env 1.
    assert_eq!(infos.mask("reset"), Some(&[true, false][..]));
    assert_eq!(infos.get("step").unwrap().as_ints(), Some(&[0i64, 2][..]));
    let keys: Vec<&str> = infos.keys().collect();
    // Gymnasium 1.4.0's key order for this step.
    assert_eq!(
        keys,
        [
            "final_obs",
            "_final_obs",
            "final_info",
            "_final_info",
            "reset",
            "_reset",
            "step",
            "_step"
        ]
    );
    // Next step: env 0 steps from its reset (1), env 1 terminates at 3 and resets.
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(s.observations.f64s(), vec![1.0, 0.0]);
    assert_eq!(s.rewards, &[1.0, 3.0]);
    assert_eq!(s.terminations, &[false, true]);
}

#[test]
fn same_step_trace_matches_gymnasium() {
    same_step_trace(
        SyncVectorEnv::new(counts())
            .unwrap()
            .with_autoreset_mode(AutoresetMode::SameStep),
    );
    same_step_trace(
        ThreadVectorEnv::new(counts())
            .unwrap()
            .with_autoreset_mode(AutoresetMode::SameStep),
    );
}

fn disabled<V: VectorEnv<ActSpace = gym_core::spaces::Discrete>>(mut v: V)
where
    adapters::BatchOf<V::ObsSpace>: AsF64,
{
    v.reset(None, None).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(s.terminations, &[true, false]);
    assert_eq!(v.step(&zeros2()).unwrap_err(), Error::EpisodeEnded);
    // Nothing was stepped by the refused call.
    assert_eq!(v.observations().f64s(), vec![2.0, 2.0]);
    let (obs, infos) = v.reset_masked(&[true, false], None, None).unwrap();
    assert_eq!(obs.f64s(), vec![0.0, 2.0]);
    assert_eq!(infos.mask("reset"), Some(&[true, false][..]));
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(
        (s.observations.f64s(), s.terminations.to_vec()),
        (vec![1.0, 3.0], vec![false, true])
    );
}

#[test]
fn disabled_mode_needs_masked_resets() {
    disabled(
        SyncVectorEnv::new(counts())
            .unwrap()
            .with_autoreset_mode(AutoresetMode::Disabled),
    );
    disabled(
        ThreadVectorEnv::new(counts())
            .unwrap()
            .with_autoreset_mode(AutoresetMode::Disabled),
    );
}

fn manual_reset_clears_autoreset<V: VectorEnv<ActSpace = gym_core::spaces::Discrete>>(mut v: V)
where
    adapters::BatchOf<V::ObsSpace>: AsF64,
{
    v.reset(None, None).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(s.terminations, &[true, false]);
    // A full manual reset: the next step is a real step for both (Gymnasium's
    // AsyncVectorEnv(shared_memory=False) would reset env 0 a second time here).
    v.reset(None, None).unwrap();
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(
        (s.observations.f64s(), s.rewards.to_vec()),
        (vec![1.0, 1.0], vec![1.0, 1.0])
    );
    // A masked manual reset clears the pending autoreset of the reset env only.
    let _ = v.step(&zeros2()).unwrap(); // env 0 terminates
    let _ = v.step(&zeros2()).unwrap(); // env 0 autoresets, env 1 terminates
    let _ = v.step(&zeros2()).unwrap(); // env 0 steps, env 1 autoresets
    let _ = v.step(&zeros2()).unwrap(); // env 0 terminates at 2
    v.reset_masked(&[true, false], None, None).unwrap();
    let s = v.step(&zeros2()).unwrap();
    assert_eq!(s.observations.f64s(), vec![1.0, 2.0]);
}

#[test]
fn manual_reset_clears_pending_autoresets() {
    manual_reset_clears_autoreset(SyncVectorEnv::new(counts()).unwrap());
    manual_reset_clears_autoreset(ThreadVectorEnv::new(counts()).unwrap());
}

#[test]
fn reset_mask_in_options_and_its_validation() {
    let mut v = SyncVectorEnv::new(counts()).unwrap();
    v.reset(None, None).unwrap();
    let _ = v.step(&zeros2()).unwrap();
    let mask = |a: ArrayValue| Info::new().with("reset_mask", a).with("other", 1i64);
    let ok = mask(ArrayValue::from(arr1(&[0u8, 1]).into_dyn()));
    let (obs, infos) = v.reset(None, Some(&ok)).unwrap();
    assert_eq!(col(obs), vec![1.0, 0.0]);
    assert_eq!(infos.mask("reset"), Some(&[false, true][..]));
    for bad in [
        mask(ArrayValue::from(arr1(&[0u8, 0]).into_dyn())),
        mask(ArrayValue::from(arr1(&[1u8, 0, 1]).into_dyn())),
        mask(ArrayValue::from(arr1(&[1.0f32, 0.0]).into_dyn())),
        mask(ArrayValue::from(arr1(&[2i8, 0]).into_dyn())),
        Info::new().with("reset_mask", true),
    ] {
        assert!(
            matches!(
                v.reset(None, Some(&bad)),
                Err(Error::InvalidArgument { .. })
            ),
            "{bad:?}"
        );
    }
    assert!(v.reset_masked(&[true], None, None).is_err());
    assert!(
        v.reset_masked(&[true, true], Seeds::PerEnv(vec![Some(1)]), None)
            .is_err()
    );
    assert!(v.reset_masked(&[true, false], None, Some(&ok)).is_err());
}

#[test]
fn spaces_are_batched() {
    let v = SyncVectorEnv::new(counts()).unwrap();
    assert_eq!(v.observation_space().shape(), Some(&[2usize, 1][..]));
    assert_eq!(v.action_space().nvec(), &arr1(&[2i64, 2]).into_dyn());
    assert_eq!(v.num_envs(), 2);
    assert_eq!(
        v.single_observation_space(),
        &CountEnv::new(None, None).observation_space
    );
    // Differing spaces are rejected.
    let mut other = CountEnv::new(None, None);
    other.observation_space = gym_core::spaces::BoxSpace::uniform(0.0, 1.0, &[1]).unwrap();
    assert!(SyncVectorEnv::new(vec![CountEnv::new(None, None), other]).is_err());
    assert!(SyncVectorEnv::<CountEnv>::new(vec![]).is_err());
}

#[test]
fn discrete_and_dict_observations_batch() {
    let mut v = SyncVectorEnv::new(vec![
        DiscreteEnv::new(),
        DiscreteEnv::new(),
        DiscreteEnv::new(),
    ])
    .unwrap();
    let (obs, _) = v.reset(None, None).unwrap();
    assert_eq!(obs, &arr1(&[2i64, 2, 2]).into_dyn());
    let s = v.step(&arr1(&[0i64, 1, 1]).into_dyn()).unwrap();
    assert_eq!(s.observations, &arr1(&[1i64, 3, 3]).into_dyn());
    assert!(v.observation_space().contains(v.observations()));

    let mut d = ThreadVectorEnv::new(vec![DictEnv::new(5, true), DictEnv::new(5, true)]).unwrap();
    d.reset(7u64, None).unwrap();
    let obs = d.observations();
    let img = obs["frontview_image"].as_array().unwrap();
    assert_eq!(img.shape(), &[2, 2, 2, 1]);
    assert!(d.observation_space().contains(obs));
    let actions = arr2(&[[0.5, 0.0, 0.0], [0.0, 0.05, 0.0]]).into_dyn();
    let s = d.step(&actions).unwrap();
    assert_eq!(
        s.infos
            .get("success")
            .unwrap()
            .as_bools()
            .map(<[bool]>::len),
        Some(2)
    );
    // The batched dict equals the single envs' dicts stacked.
    let mut single = DictEnv::new(5, true);
    single.reset(Some(8), None).unwrap();
    let one = single
        .step(&actions.index_axis(Axis(0), 1).to_owned())
        .unwrap()
        .observation;
    let row = d
        .single_observation_space()
        .read_item(d.observations(), 1)
        .unwrap();
    assert_eq!(row, one);
}

/// Runs `steps` steps of `n` WalkEnvs in a vector and as single envs with the same seeds
/// and actions (NEXT_STEP autoreset replicated by hand); everything must agree.
fn equivalent_to_single_envs<
    V: VectorEnv<ObsSpace = gym_core::BoxSpace<f32>, ActSpace = gym_core::BoxSpace<f32>>,
>(
    mut v: V,
    n: usize,
    seed: u64,
) {
    let mut singles: Vec<WalkEnv> = (0..n).map(|_| WalkEnv::new(6)).collect();
    let (obs, _) = v.reset(seed, None).unwrap();
    for (i, e) in singles.iter_mut().enumerate() {
        let (o, _) = e.reset(Some(seed + i as u64), None).unwrap();
        assert_eq!(obs.index_axis(Axis(0), i), o);
    }
    let mut pending = vec![false; n];
    let mut rng = gym_core::rng_from_seed(99);
    for t in 0..20 {
        let actions = v.action_space().sample(&mut rng);
        let s = v.step(&actions).unwrap();
        for (i, e) in singles.iter_mut().enumerate() {
            let a = actions.index_axis(Axis(0), i).to_owned();
            let (o, r, term, trunc) = if pending[i] {
                let (o, _) = e.reset(None, None).unwrap();
                (o, 0.0, false, false)
            } else {
                let st = e.step(&a).unwrap();
                (st.observation, st.reward, st.terminated, st.truncated)
            };
            pending[i] = term || trunc;
            assert_eq!(
                s.observations.index_axis(Axis(0), i),
                o,
                "step {t}, env {i}"
            );
            assert_eq!(
                (s.rewards[i], s.terminations[i], s.truncations[i]),
                (r, term, trunc),
                "step {t}, env {i}"
            );
        }
    }
}

#[test]
fn vector_trajectories_equal_single_envs() {
    let envs = |n: usize| (0..n).map(|_| WalkEnv::new(6)).collect::<Vec<_>>();
    equivalent_to_single_envs(SyncVectorEnv::new(envs(3)).unwrap(), 3, 10);
    equivalent_to_single_envs(ThreadVectorEnv::new(envs(3)).unwrap(), 3, 10);
    equivalent_to_single_envs(ThreadVectorEnv::with_threads(envs(5), 2).unwrap(), 5, 20);
    equivalent_to_single_envs(ThreadVectorEnv::with_threads(envs(4), 4).unwrap(), 4, 30);
}

#[test]
fn seeds_per_env_and_none() {
    let mut v = SyncVectorEnv::from_fn(2, |_| Ok(WalkEnv::new(5))).unwrap();
    let (a, _) = v
        .reset(Seeds::PerEnv(vec![Some(3), Some(3)]), None)
        .unwrap();
    assert_eq!(a.index_axis(Axis(0), 0), a.index_axis(Axis(0), 1));
    let (b, _) = v.reset(3u64, None).unwrap();
    assert_ne!(b.index_axis(Axis(0), 0), b.index_axis(Axis(0), 1));
    let mut single = WalkEnv::new(5);
    assert_eq!(
        single.reset(Some(4), None).unwrap().0,
        b.index_axis(Axis(0), 1)
    );
    // None continues each env's stream.
    let (c, _) = v.reset(None, None).unwrap();
    assert_eq!(
        single.reset(None, None).unwrap().0,
        c.index_axis(Axis(0), 1)
    );
}

type Stepper = Box<dyn FnMut(&ArrayD<f32>) -> Result<Vec<f32>, Error>>;

#[test]
fn sub_environment_errors_are_typed_and_recoverable() {
    for threaded in [false, true] {
        let envs = vec![WalkEnv::new(10), WalkEnv::new(10)];
        let mut v: Stepper = if threaded {
            let mut v = ThreadVectorEnv::new(envs).unwrap();
            v.reset(0u64, None).unwrap();
            Box::new(move |a| v.step(a).map(|s| s.observations.iter().copied().collect()))
        } else {
            let mut v = SyncVectorEnv::new(envs).unwrap();
            v.reset(0u64, None).unwrap();
            Box::new(move |a| v.step(a).map(|s| s.observations.iter().copied().collect()))
        };
        let bad = arr2(&[[0.0f32, 0.0], [5.0, 0.0]]).into_dyn();
        match v(&bad) {
            Err(Error::InvalidAction(m)) => {
                assert!(m.to_string().contains("sub-environment 1"), "{m}")
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(v(&a32(&[0.0, 0.0])), Err(Error::InvalidAction(_))));
        assert!(v(&arr2(&[[0.1f32, 0.0], [0.0, 0.1]]).into_dyn()).is_ok());
    }
}

#[test]
fn a_panicking_worker_env_is_an_error_not_a_hang() {
    let mut bad = WalkEnv::new(10);
    bad.panic_at = Some(2);
    let mut v = ThreadVectorEnv::with_threads(vec![WalkEnv::new(10), bad], 2).unwrap();
    v.reset(0u64, None).unwrap();
    let a = ArrayD::zeros(IxDyn(&[2, 2]));
    assert!(v.step(&a).is_ok());
    match v.step(&a) {
        Err(Error::Simulation(m)) => assert!(
            m.to_string().contains("sub-environment 1") && m.to_string().contains("panicked"),
            "{m}"
        ),
        other => panic!("{other:?}"),
    }
    assert!(matches!(v.step(&a), Err(Error::Simulation(m)) if m.to_string().contains("earlier")));
    v.close();
    v.close();
    assert!(v.is_closed());
    assert_eq!(v.step(&a).unwrap_err(), Error::Closed);
    assert_eq!(v.reset(None, None).unwrap_err(), Error::Closed);
}

#[test]
fn a_panicking_env_on_the_calling_thread_is_an_error() {
    let mut bad = WalkEnv::new(10);
    bad.panic_at = Some(1);
    // Sub-environment 0 is in the calling thread's block.
    let mut v = ThreadVectorEnv::with_threads(vec![bad, WalkEnv::new(10)], 2).unwrap();
    assert_eq!(v.num_threads(), 2);
    v.reset(0u64, None).unwrap();
    let a = ArrayD::zeros(IxDyn(&[2, 2]));
    match v.step(&a) {
        Err(Error::Simulation(m)) => assert!(
            m.to_string().contains("sub-environment 0") && m.to_string().contains("panicked"),
            "{m}"
        ),
        other => panic!("{other:?}"),
    }
    assert!(matches!(v.step(&a), Err(Error::Simulation(m)) if m.to_string().contains("earlier")));
    v.close();
    assert!(v.is_closed());
}

#[test]
fn close_closes_sub_environments_and_drop_joins() {
    let mut v = SyncVectorEnv::new(vec![
        crate::common::script_f32(&[&[0.0]], &[0.0]),
        crate::common::script_f32(&[&[0.0]], &[0.0]),
    ])
    .unwrap();
    v.close();
    v.close();
    assert!(v.envs().iter().all(|e| e.closed == 1));
    // Dropping a threaded vector env that was never closed joins its workers.
    let t = ThreadVectorEnv::new(vec![WalkEnv::new(3), WalkEnv::new(3), WalkEnv::new(3)]).unwrap();
    assert!(t.num_threads() >= 1);
    drop(t);
}

#[test]
fn infos_of_record_episode_statistics_are_nested() {
    use adapters::WrapperExt;
    let envs = vec![
        CountEnv::new(Some(1), None).record_episode_statistics(),
        CountEnv::new(Some(2), None).record_episode_statistics(),
    ];
    let mut v = SyncVectorEnv::new(envs).unwrap();
    v.reset(None, None).unwrap();
    let s = v.step(&zeros2()).unwrap();
    let ep = s.infos.get("episode").unwrap().as_map().unwrap();
    assert_eq!(s.infos.mask("episode"), Some(&[true, false][..]));
    assert_eq!(ep.get("r").unwrap().as_floats(), Some(&[1.0, 0.0][..]));
    assert_eq!(ep.get("l").unwrap().as_ints(), Some(&[1i64, 0][..]));
    assert!(matches!(ep.get("t"), Some(VectorInfoValue::Float(_))));
    assert_eq!(
        s.infos.env_info(0).get_map("episode").unwrap().get("l"),
        Some(&InfoValue::Int(1))
    );
}
