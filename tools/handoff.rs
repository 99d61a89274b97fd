//! The hand-off cost of `ThreadVectorEnv` and `ThreadEnvPool`, measured with envs whose
//! step is a fixed amount of CPU work (no MuJoCo): env steps per second for 2 and 4 envs on
//! the default threads and per-env step costs of 0, 20, 100 and 400 µs, beside the same envs
//! stepped in turn on one thread (`SyncVectorEnv`); the pool returns batches of half its
//! envs. With little work per step the figure is dominated by the
//! hand-off (waking the workers, collecting the results); the ratio to the sync figure
//! shows what the threads gain. Figures are medians over `--rounds` interleaved rounds.
//!
//! ```text
//! cargo run --release -p tools --bin handoff -- [--seconds 4] [--rounds 4] [--json handoff.json]
//! ```

use adapters::{SyncVectorEnv, ThreadEnvPool, ThreadVectorEnv, VectorEnv};
use gym_core::spaces::BoxSpace;
use gym_core::{Env, Info, ResetOptions, Result, Step};
use ndarray::{ArrayD, IxDyn};
use serde_json::json;
use std::time::{Duration, Instant};

/// An env whose step spins for `iters` iterations of an LCG (the observation is its state).
#[derive(Debug, Clone)]
struct Work {
    iters: u64,
    state: u64,
    space: BoxSpace<f32>,
}

impl Env for Work {
    type Obs = ArrayD<f32>;
    type Act = ArrayD<f32>;
    type ObsSpace = BoxSpace<f32>;
    type ActSpace = BoxSpace<f32>;
    fn observation_space(&self) -> &BoxSpace<f32> {
        &self.space
    }
    fn action_space(&self) -> &BoxSpace<f32> {
        &self.space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        self.state = seed.unwrap_or(1);
        Ok((ArrayD::zeros(IxDyn(&[2])), Info::new()))
    }
    fn step(&mut self, _: &ArrayD<f32>) -> Result<Step<ArrayD<f32>>> {
        for i in 0..self.iters {
            self.state =
                std::hint::black_box(self.state.wrapping_mul(6364136223846793005).wrapping_add(i));
        }
        Ok(Step {
            observation: ArrayD::from_elem(IxDyn(&[2]), (self.state >> 40) as f32),
            reward: 0.0,
            terminated: false,
            truncated: false,
            info: Info::new(),
        })
    }
}

/// LCG iterations per µs on this machine.
fn iters_per_us() -> f64 {
    let mut env = Work {
        iters: 20_000_000,
        state: 1,
        space: BoxSpace::uniform(-1.0, 1.0, &[2]).expect("a valid box"),
    };
    let t = Instant::now();
    let _ = env.step(&ArrayD::zeros(IxDyn(&[2])));
    20_000_000.0 / (t.elapsed().as_secs_f64() * 1e6)
}

fn rate<V: VectorEnv<ActSpace = BoxSpace<f32>>>(v: &mut V, budget: Duration) -> f64
where
    V::ActSpace: adapters::BatchSpace<Batched = BoxSpace<f32>>,
{
    let actions = ArrayD::zeros(IxDyn(&[v.num_envs(), 2]));
    let start = Instant::now();
    let mut n = 0u64;
    while start.elapsed() < budget {
        let _ = v.step(&actions).expect("a step");
        n += 1;
    }
    n as f64 * v.num_envs() as f64 / start.elapsed().as_secs_f64()
}

/// Env steps per second of `pool` (reset, `ids` its last batch) sending zero actions.
fn pool_rate(pool: &mut ThreadEnvPool<Work>, ids: &mut [usize], budget: Duration) -> f64 {
    let actions = ArrayD::zeros(IxDyn(&[ids.len(), 2]));
    let start = Instant::now();
    let mut n = 0u64;
    while start.elapsed() < budget {
        let batch = pool.step(&actions, ids).expect("a pool step");
        ids.copy_from_slice(batch.env_ids);
        n += 1;
    }
    n as f64 * ids.len() as f64 / start.elapsed().as_secs_f64()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let (mut seconds, mut rounds, mut json_path) = (4.0, 4usize, None);
    while let Some(flag) = args.next() {
        let value = args.next().unwrap_or_default();
        match flag.as_str() {
            "--seconds" => seconds = value.parse().unwrap_or(seconds),
            "--rounds" => rounds = value.parse().unwrap_or(rounds),
            "--json" => json_path = Some(value),
            other => eprintln!("handoff: ignoring {other}"),
        }
    }
    let per_us = iters_per_us();
    let window = Duration::from_secs_f64(seconds / rounds as f64);
    let mut rows = Vec::new();
    for envs in [2usize, 4] {
        for work_us in [0.0, 20.0, 100.0, 400.0] {
            let make = || Work {
                iters: (work_us * per_us) as u64,
                state: 1,
                space: BoxSpace::uniform(-1.0, 1.0, &[2]).expect("a valid box"),
            };
            let mut threaded = ThreadVectorEnv::new((0..envs).map(|_| make()).collect())?;
            let mut sync = SyncVectorEnv::new((0..envs).map(|_| make()).collect())?;
            let mut pool = ThreadEnvPool::new((0..envs).map(|_| make()).collect(), envs / 2)?;
            threaded.reset(0u64, None)?;
            sync.reset(0u64, None)?;
            pool.reset(0u64)?;
            let mut ids = pool.recv()?.env_ids.to_vec();
            let (mut t, mut s, mut p) = (Vec::new(), Vec::new(), Vec::new());
            for _ in 0..rounds {
                t.push(rate(&mut threaded, window));
                s.push(rate(&mut sync, window));
                p.push(pool_rate(&mut pool, &mut ids, window));
            }
            let ratio = median(t.iter().zip(&s).map(|(a, b)| a / b).collect());
            let pool_ratio = median(p.iter().zip(&s).map(|(a, b)| a / b).collect());
            println!(
                "{envs} envs, {work_us:>5.0} us/step: ThreadVectorEnv {:>9.0} env steps/s, \
                 ThreadEnvPool {:>9.0}, SyncVectorEnv {:>9.0}, ratios {ratio:.2} / {pool_ratio:.2}",
                median(t.clone()),
                median(p.clone()),
                median(s.clone())
            );
            rows.push(
                json!({"envs": envs, "work_us": work_us, "threads": threaded.num_threads(),
                "thread_steps_per_s": median(t), "sync_steps_per_s": median(s), "ratio": ratio,
                "pool_steps_per_s": median(p), "pool_ratio": pool_ratio}),
            );
        }
    }
    if let Some(p) = json_path {
        std::fs::write(
            &p,
            serde_json::to_string_pretty(&json!(rows)).unwrap_or_default(),
        )
        .map_err(|e| gym_core::Error::invalid_argument("--json", e.to_string()))?;
    }
    Ok(())
}
