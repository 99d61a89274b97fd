//! `ThreadVectorEnv`'s dynamic assignment: whichever thread steps a sub-environment, its
//! trajectory is bit-identical to the same environment stepped alone, for many env and
//! thread counts and uneven step costs (so that threads take each other's envs), through
//! typed and boxed (`DynEnv::step_into`) environments alike.

use crate::common::WalkEnv;
use adapters::{
    AutoresetMode, BatchSpace, SyncVectorEnv, ThreadOptions, ThreadVectorEnv, VectorEnv, WrapperExt,
};
use gym_core::{Env, EnvRng, IntoBoxedEnv, Space, Value, rng_from_seed};
use ndarray::{ArrayD, Axis};

/// One step of one environment: observation bits, reward bits and the two flags.
type Record = (Vec<u32>, u64, bool, bool);

fn bits(obs: &ArrayD<f32>) -> Vec<u32> {
    obs.iter().map(|x| x.to_bits()).collect()
}

/// Walks whose step costs differ a lot between neighbours (busy-work 0 to 60 000
/// iterations) and whose horizons differ, so episodes end at different steps.
fn uneven_walks(n: usize) -> Vec<WalkEnv> {
    (0..n)
        .map(|i| {
            let mut w = WalkEnv::new(5 + (i as u64 % 4));
            w.work_iters = [0, 20_000, 2_000, 60_000][i % 4];
            w
        })
        .collect()
}

/// `steps` batches of actions for `n` environments.
fn action_batches<S: BatchSpace>(single: &S, n: usize, steps: usize, seed: u64) -> Vec<ArrayD<f32>>
where
    S::Batched: Space<Element = ArrayD<f32>>,
{
    let batched = single.batch_space(n).unwrap();
    let mut rng: EnvRng = rng_from_seed(seed);
    (0..steps).map(|_| batched.sample(&mut rng)).collect()
}

/// Environment `i` stepped alone with row `i` of each batch, under `NextStep` autoreset
/// (the step after an episode's end resets it, with reward 0 and no flags).
fn alone<E: Env<Obs = ArrayD<f32>, Act = ArrayD<f32>>>(
    mut env: E,
    seed: u64,
    i: usize,
    batches: &[ArrayD<f32>],
) -> Vec<Record> {
    env.reset(Some(seed), None).unwrap();
    let mut ended = false;
    batches
        .iter()
        .map(|b| {
            if ended {
                ended = false;
                let (obs, _) = env.reset(None, None).unwrap();
                (bits(&obs), 0f64.to_bits(), false, false)
            } else {
                let s = env.step(&b.index_axis(Axis(0), i).to_owned()).unwrap();
                ended = s.terminated || s.truncated;
                (
                    bits(&s.observation),
                    s.reward.to_bits(),
                    s.terminated,
                    s.truncated,
                )
            }
        })
        .collect()
}

/// Each environment's records from a vector env stepped with `batches`.
fn in_vector<V: VectorEnv>(
    v: &mut V,
    seed: u64,
    batches: &[adapters::BatchOf<V::ActSpace>],
    obs_rows: impl Fn(&adapters::BatchOf<V::ObsSpace>, usize) -> ArrayD<f32>,
) -> Vec<Vec<Record>> {
    let n = v.num_envs();
    v.reset(seed, None).unwrap();
    let mut out = vec![Vec::new(); n];
    for b in batches {
        let s = v.step(b).unwrap();
        for (i, records) in out.iter_mut().enumerate() {
            records.push((
                bits(&obs_rows(s.observations, i)),
                s.rewards[i].to_bits(),
                s.terminations[i],
                s.truncations[i],
            ));
        }
    }
    out
}

fn row(batch: &ArrayD<f32>, i: usize) -> ArrayD<f32> {
    batch.index_axis(Axis(0), i).to_owned()
}

#[test]
fn trajectories_equal_single_envs_for_any_env_and_thread_count() {
    for (n, threads, pin) in [
        (1, 1, false),
        (2, 2, false),
        (3, 2, false),
        (5, 2, false),
        (8, 3, false),
        (9, 4, false),
        (16, 4, false),
        (6, 6, false),
        (12, 5, false),
        // Pinned workers, more threads than this machine's CPUs included (they wrap).
        (4, 2, true),
        (10, 6, true),
    ] {
        let options = ThreadOptions {
            num_threads: Some(threads),
            pin,
        };
        let mut v = ThreadVectorEnv::with_options(uneven_walks(n), options).unwrap();
        assert_eq!(v.num_threads(), threads);
        let batches = action_batches(v.single_action_space(), n, 40, n as u64);
        let got = in_vector(&mut v, 100, &batches, row);
        for (i, (env, records)) in uneven_walks(n).into_iter().zip(&got).enumerate() {
            let want = alone(env, 100 + i as u64, i, &batches);
            assert_eq!(
                records, &want,
                "{n} envs on {threads} threads (pinned: {pin}): env {i}"
            );
        }
    }
}

#[test]
fn same_step_autoreset_equals_the_sync_vector_env_for_any_thread_count() {
    for (n, threads) in [(3, 2), (7, 3), (10, 4)] {
        let mut t = ThreadVectorEnv::with_threads(uneven_walks(n), threads)
            .unwrap()
            .with_autoreset_mode(AutoresetMode::SameStep);
        let mut s = SyncVectorEnv::new(uneven_walks(n))
            .unwrap()
            .with_autoreset_mode(AutoresetMode::SameStep);
        let batches = action_batches(t.single_action_space(), n, 30, 9);
        t.reset(4u64, None).unwrap();
        s.reset(4u64, None).unwrap();
        for b in &batches {
            let a = t.step(b).unwrap();
            let (a_obs, a_rew, a_info) =
                (a.observations.clone(), a.rewards.to_vec(), a.infos.clone());
            let b = s.step(b).unwrap();
            assert_eq!(
                bits(&a_obs),
                bits(b.observations),
                "{n} envs on {threads} threads"
            );
            assert_eq!(a_rew, b.rewards);
            assert_eq!(&a_info, b.infos);
        }
    }
}

#[test]
fn lift_trajectories_equal_single_envs_typed_and_boxed() {
    let make = || {
        robosuite_env::make("Lift")
            .unwrap()
            .flat_gym_wrapper(None)
            .unwrap()
    };
    let n = 3;
    let mut typed = ThreadVectorEnv::with_threads((0..n).map(|_| make()).collect(), 2).unwrap();
    let batches = action_batches(typed.single_action_space(), n, 12, 5);
    let got = in_vector(&mut typed, 21, &batches, row);
    // The same environments boxed: steps go through `DynEnv::step_into`.
    let mut boxed =
        ThreadVectorEnv::with_threads((0..n).map(|_| make().boxed()).collect(), 2).unwrap();
    let boxed_batches: Vec<Value> = batches.iter().map(|b| Value::from(b.clone())).collect();
    let got_boxed = in_vector(&mut boxed, 21, &boxed_batches, |obs, i| match obs {
        Value::Array(gym_core::ArrayValue::F32(a)) => row(a, i),
        other => panic!("a flat observation batch, got {other:?}"),
    });
    for i in 0..n {
        let want = alone(make(), 21 + i as u64, i, &batches);
        assert_eq!(got[i], want, "typed env {i}");
        assert_eq!(got_boxed[i], want, "boxed env {i}");
    }
}
