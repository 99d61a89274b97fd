//! ThreadEnvPool (EnvPool's asynchronous mode): every environment follows the trajectory a
//! single environment would with the same seed and actions, whatever batches it lands in;
//! NextStep autoreset; typed errors for misuse; panics are errors, not hangs.

use crate::common::{WalkEnv, a32};
use adapters::{ThreadEnvPool, ThreadOptions};
use gym_core::{Env, Error, Info};
use ndarray::{ArrayD, Axis, IxDyn};
use std::collections::HashSet;

/// What a pool row must show for one environment.
#[derive(Debug, Clone, PartialEq)]
struct Expected {
    obs: Vec<f32>,
    reward: f64,
    terminated: bool,
    truncated: bool,
    info: Info,
}

impl Expected {
    /// A reset's row: its observation, reward 0, no flags.
    fn reset((obs, info): (ArrayD<f32>, Info)) -> Self {
        Self {
            obs: obs.iter().copied().collect(),
            reward: 0.0,
            terminated: false,
            truncated: false,
            info,
        }
    }
}

fn action_for(id: usize, count: usize) -> [f32; 2] {
    let x = ((id * 7 + count * 3) % 11) as f32 / 5.0 - 1.0;
    let y = ((id * 5 + count) % 9) as f32 / 4.0 - 1.0;
    [x, y]
}

fn check_trajectories(num_envs: usize, batch_size: usize, options: ThreadOptions, rounds: usize) {
    let threads = options.num_threads.unwrap_or(1);
    let mut pool = ThreadEnvPool::with_options(
        (0..num_envs).map(|_| WalkEnv::new(6)).collect(),
        batch_size,
        options,
    )
    .unwrap();
    assert_eq!(pool.num_threads(), threads.clamp(1, num_envs));
    let mut reference: Vec<WalkEnv> = (0..num_envs).map(|_| WalkEnv::new(6)).collect();
    let mut expected: Vec<Expected> = reference
        .iter_mut()
        .enumerate()
        .map(|(i, e)| Expected::reset(e.reset(Some(40 + i as u64), None).unwrap()))
        .collect();
    let mut ended = vec![false; num_envs];
    let mut sent = vec![0usize; num_envs];
    let mut seen = HashSet::new();
    let mut autoresets = 0;
    pool.reset(40u64).unwrap();
    for _ in 0..rounds {
        let batch = pool.recv().unwrap();
        let ids = batch.env_ids.to_vec();
        assert_eq!(ids.len(), batch_size);
        assert_eq!(
            ids.iter().collect::<HashSet<_>>().len(),
            batch_size,
            "{ids:?}"
        );
        for (k, &id) in ids.iter().enumerate() {
            seen.insert(id);
            let row: Vec<f32> = batch
                .observations
                .index_axis(Axis(0), k)
                .iter()
                .copied()
                .collect();
            let got = Expected {
                obs: row,
                reward: batch.rewards[k],
                terminated: batch.terminations[k],
                truncated: batch.truncations[k],
                info: batch.infos.env_info(k),
            };
            assert_eq!(got, expected[id], "env {id}");
            ended[id] = got.terminated || got.truncated;
        }
        // Send the next actions and work out what each env must answer.
        let mut actions = ArrayD::zeros(IxDyn(&[batch_size, 2]));
        for (k, &id) in ids.iter().enumerate() {
            let a = action_for(id, sent[id]);
            sent[id] += 1;
            actions.index_axis_mut(Axis(0), k).assign(&a32(&a));
            expected[id] = if ended[id] {
                autoresets += 1;
                Expected::reset(reference[id].reset(None, None).unwrap())
            } else {
                let s = reference[id].step(&a32(&a)).unwrap();
                Expected {
                    obs: s.observation.iter().copied().collect(),
                    reward: s.reward,
                    terminated: s.terminated,
                    truncated: s.truncated,
                    info: s.info,
                }
            };
        }
        pool.send(&actions, &ids).unwrap();
    }
    assert_eq!(seen.len(), num_envs, "every environment took part");
    assert!(
        sent.iter().all(|&n| n > 0),
        "every environment got actions: {sent:?}"
    );
    assert!(autoresets > 0, "some episode ended and was reset");
    pool.close();
}

#[test]
fn every_environment_follows_its_own_trajectory() {
    let threads = |n| ThreadOptions::default().num_threads(n);
    check_trajectories(5, 2, threads(3), 60);
    check_trajectories(4, 4, threads(2), 30);
    check_trajectories(3, 1, threads(1), 40);
    // Pinned workers, more than this machine's CPUs (they wrap around).
    check_trajectories(8, 3, threads(5).pinned(), 80);
}

#[test]
fn a_full_batch_returns_every_environment() {
    let mut pool = ThreadEnvPool::new((0..3).map(|_| WalkEnv::new(5)).collect(), 3).unwrap();
    pool.reset(1u64).unwrap();
    let mut ids = pool.recv().unwrap().env_ids.to_vec();
    ids.sort_unstable();
    assert_eq!(ids, [0, 1, 2]);
}

#[test]
fn misuse_is_a_typed_error_and_queues_nothing() {
    let invalid = |r: Result<ThreadEnvPool<WalkEnv>, Error>| {
        assert!(matches!(r, Err(Error::InvalidArgument { .. })), "{r:?}");
    };
    invalid(ThreadEnvPool::new(vec![WalkEnv::new(5)], 0));
    invalid(ThreadEnvPool::new(vec![WalkEnv::new(5)], 2));
    invalid(ThreadEnvPool::new(Vec::new(), 1));

    let mut pool = ThreadEnvPool::new((0..3).map(|_| WalkEnv::new(5)).collect(), 2).unwrap();
    let one = ArrayD::zeros(IxDyn(&[1, 2]));
    assert_eq!(pool.send(&one, &[0]).unwrap_err(), Error::ResetNeeded);
    pool.reset(0u64).unwrap();
    let ids = pool.recv().unwrap().env_ids.to_vec();
    let pending = (0..3).find(|i| !ids.contains(i)).unwrap();
    let two = ArrayD::zeros(IxDyn(&[2, 2]));
    for bad in [vec![pending], vec![ids[0], ids[0]], vec![7]] {
        let e = pool.send(&two, &bad).unwrap_err();
        assert!(matches!(e, Error::InvalidArgument { .. }), "{bad:?}: {e:?}");
    }
    // Fewer action rows than ids.
    assert!(pool.send(&one, &ids).is_err());
    // One env pending (the third); a batch needs two.
    assert!(matches!(pool.recv(), Err(Error::InvalidArgument { .. })));
    // Nothing was queued by the failed sends: this works.
    pool.send(&two, &ids).unwrap();
    assert_eq!(pool.recv().unwrap().env_ids.len(), 2);
    pool.close();
    pool.close();
    assert!(pool.is_closed());
    assert_eq!(pool.reset(0u64).unwrap_err(), Error::Closed);
    assert_eq!(pool.send(&two, &ids).unwrap_err(), Error::Closed);
}

#[test]
fn an_invalid_action_is_that_environments_error_and_it_stays_usable() {
    let mut pool = ThreadEnvPool::new(vec![WalkEnv::new(5)], 1).unwrap();
    pool.reset(3u64).unwrap();
    let _ = pool.recv().unwrap();
    let bad = ArrayD::from_elem(IxDyn(&[1, 2]), 5.0f32);
    pool.send(&bad, &[0]).unwrap();
    match pool.recv() {
        Err(Error::InvalidAction(m)) => assert!(m.to_string().contains("sub-environment 0"), "{m}"),
        other => panic!("{other:?}"),
    }
    pool.send(&ArrayD::zeros(IxDyn(&[1, 2])), &[0]).unwrap();
    assert!(pool.recv().is_ok());
}

#[test]
fn a_panicking_environment_is_an_error_not_a_hang() {
    let mut bad = WalkEnv::new(10);
    bad.panic_at = Some(1);
    let mut pool = ThreadEnvPool::new(vec![bad, WalkEnv::new(10)], 2).unwrap();
    pool.reset(0u64).unwrap();
    let _ = pool.recv().unwrap();
    let a = ArrayD::zeros(IxDyn(&[2, 2]));
    match pool.step(&a, &[0, 1]) {
        Err(Error::Simulation(m)) => assert!(
            m.to_string().contains("sub-environment 0") && m.to_string().contains("panicked"),
            "{m}"
        ),
        other => panic!("{other:?}"),
    }
    match pool.step(&a, &[0, 1]) {
        Err(Error::Simulation(m)) => assert!(m.to_string().contains("earlier"), "{m}"),
        other => panic!("{other:?}"),
    }
    drop(pool);
}
