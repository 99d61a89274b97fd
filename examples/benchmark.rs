//! Performance figures for every registered task: one-thread env steps/s with random
//! actions (raw env and through the flat GymWrapper), the physics-only cost of the same
//! model (`mj_step` × substeps per env step, arm held by gravity compensation) and the ratio,
//! reset time, resident memory per additional instance, and thread-vector-env throughput
//! for 1, 2, 4, ... environments. Prints a table; `--json PATH` also writes JSON.
//!
//! ```text
//! cargo run --release -p examples --example benchmark -- [--task Lift] [--seconds 3]
//!     [--max-envs 4] [--json bench.json]
//! ```
//!
//! Figures are wall-clock rates: run it on an otherwise idle machine.

use adapters::{ThreadVectorEnv, VectorEnv, WrapperExt};
use gym_core::{Env, Result, Space, rng_from_seed};
use robosuite_env::{EnvConfig, RobosuiteEnv, sim::Sim};
use serde_json::json;
use std::time::{Duration, Instant};

struct Args {
    tasks: Vec<String>,
    seconds: f64,
    max_envs: usize,
    json: Option<String>,
}

fn parse_args() -> Args {
    let mut args = Args {
        tasks: robosuite_env::ENV_NAMES
            .iter()
            .map(|s| (*s).to_owned())
            .collect(),
        seconds: 3.0,
        max_envs: std::thread::available_parallelism()
            .map_or(2, |n| n.get())
            .max(2)
            * 2,
        json: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let value = it.next().unwrap_or_default();
        match flag.as_str() {
            "--task" => args.tasks = vec![value],
            "--seconds" => args.seconds = value.parse().unwrap_or(args.seconds),
            "--max-envs" => args.max_envs = value.parse().unwrap_or(args.max_envs),
            "--json" => args.json = Some(value),
            other => eprintln!("benchmark: ignoring unknown argument {other}"),
        }
    }
    args
}

/// Runs `step` until `budget` has passed; returns calls per second.
fn rate(budget: Duration, mut step: impl FnMut() -> Result<()>) -> Result<f64> {
    let start = Instant::now();
    let mut n = 0u64;
    while start.elapsed() < budget {
        step()?;
        n += 1;
    }
    Ok(n as f64 / start.elapsed().as_secs_f64())
}

/// Resident set size of this process in MiB.
fn rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/statm")
        .ok()
        .and_then(|s| {
            s.split_whitespace()
                .nth(1)
                .and_then(|v| v.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |pages| pages * 4096.0 / 1048576.0)
}

fn make(task: &str) -> Result<RobosuiteEnv> {
    robosuite_env::make_with(task, EnvConfig::default())
}

fn bench_task(task: &str, args: &Args) -> Result<serde_json::Value> {
    let budget = Duration::from_secs_f64(args.seconds);
    let mut rng = rng_from_seed(1);

    // Raw env, random actions, resets at the horizon included.
    let mut env = make(task)?;
    env.reset(Some(0), None)?;
    let env_rate = rate(budget, || {
        let a = env.action_space().sample(&mut rng);
        if env.step(&a)?.done() {
            env.reset(None, None)?;
        }
        Ok(())
    })?;

    // The same through robosuite's (corrected) GymWrapper: f32 flat observations.
    let mut gym = make(task)?.flat_gym_wrapper(None)?;
    gym.reset(Some(0), None)?;
    let gym_rate = rate(budget, || {
        let a = gym.action_space().sample(&mut rng);
        if gym.step(&a)?.done() {
            gym.reset(None, None)?;
        }
        Ok(())
    })?;

    // Physics only: the env's model, mj_step × substeps, gravity-compensated arm.
    let substeps = env.substeps();
    env.reset(Some(0), None)?;
    let start = env.get_state();
    let mut sim = Sim::new(env.sim().model().clone())?;
    sim.set_state(&start)?;
    let dofs: Vec<Vec<usize>> = env
        .robots()
        .iter()
        .map(|r| r.controller().binding().dofs.to_vec())
        .collect();
    let mut n = 0u64;
    let physics_rate = rate(budget, || {
        for _ in 0..substeps {
            let mut col = 0;
            for arm in &dofs {
                for &d in arm {
                    let bias = sim.data().qfrc_bias()[d];
                    sim.data_mut().ctrl_mut()[col] = bias;
                    col += 1;
                }
            }
            sim.step();
        }
        n += 1;
        if n.is_multiple_of(200) {
            sim.set_state(&start)?;
        }
        Ok(())
    })?;

    // Reset cost.
    let resets = 500;
    let t = Instant::now();
    for _ in 0..resets {
        env.reset(None, None)?;
    }
    let reset_us = t.elapsed().as_secs_f64() / f64::from(resets) * 1e6;

    // Resident memory per additional instance.
    let before = rss_mib();
    let mut many = Vec::new();
    for i in 0..16 {
        let mut e = make(task)?;
        e.reset(Some(i), None)?;
        for _ in 0..5 {
            let a = e.action_space().sample(&mut rng);
            let _ = e.step(&a)?;
        }
        many.push(e);
    }
    let mib_per_env = (rss_mib() - before) / many.len() as f64;
    drop(many);

    // Thread vector env scaling.
    let mut vector = Vec::new();
    let mut n_envs = 1;
    let mut base = None;
    while n_envs <= args.max_envs {
        let envs = (0..n_envs)
            .map(|_| make(task)?.flat_gym_wrapper(None))
            .collect::<Result<Vec<_>>>()?;
        let mut venv = ThreadVectorEnv::new(envs)?;
        venv.reset(0u64, None)?;
        let steps_rate = rate(budget, || {
            let actions = venv.action_space().sample(&mut rng);
            venv.step(&actions).map(|_| ())
        })? * n_envs as f64;
        let threads = venv.num_threads();
        venv.close();
        let base_rate = *base.get_or_insert(steps_rate);
        vector.push(
            json!({"envs": n_envs, "threads": threads, "steps_per_s": steps_rate,
                           "speedup": steps_rate / base_rate}),
        );
        n_envs *= 2;
    }

    Ok(json!({
        "task": task,
        "substeps": substeps,
        "steps_per_s": env_rate,
        "gym_wrapper_steps_per_s": gym_rate,
        "physics_only_steps_per_s": physics_rate,
        "cost_ratio": physics_rate / env_rate,
        "reset_us": reset_us,
        "mib_per_env": mib_per_env,
        "arena_mib": env.sim().arena_bytes() as f64 / 1048576.0,
        "vector": vector,
    }))
}

fn main() -> Result<()> {
    let args = parse_args();
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "robosuite-rs benchmark: {cpus} logical CPUs, {:.0} s per measurement, random actions",
        args.seconds
    );
    let mut results = Vec::new();
    for task in &args.tasks {
        let r = bench_task(task, &args)?;
        println!("\n{task} ({} substeps per env step)", r["substeps"]);
        println!(
            "  env steps/s, one thread             {:>10.0}",
            r["steps_per_s"].as_f64().unwrap_or(0.0)
        );
        println!(
            "  through GymWrapper (flat f32)        {:>10.0}",
            r["gym_wrapper_steps_per_s"].as_f64().unwrap_or(0.0)
        );
        println!(
            "  physics only (mj_step x substeps)    {:>10.0}",
            r["physics_only_steps_per_s"].as_f64().unwrap_or(0.0)
        );
        println!(
            "  env cost / physics-only cost         {:>10.2}x",
            r["cost_ratio"].as_f64().unwrap_or(0.0)
        );
        println!(
            "  reset                                {:>10.1} us",
            r["reset_us"].as_f64().unwrap_or(0.0)
        );
        println!(
            "  resident memory per extra instance   {:>10.2} MiB",
            r["mib_per_env"].as_f64().unwrap_or(0.0)
        );
        for v in r["vector"].as_array().into_iter().flatten() {
            println!(
                "  ThreadVectorEnv {:>2} envs / {} threads {:>10.0} steps/s ({:.2}x one env)",
                v["envs"],
                v["threads"],
                v["steps_per_s"].as_f64().unwrap_or(0.0),
                v["speedup"].as_f64().unwrap_or(0.0)
            );
        }
        results.push(r);
    }
    if let Some(path) = &args.json {
        let doc = json!({"cpus": cpus, "seconds": args.seconds, "tasks": results});
        std::fs::write(path, serde_json::to_string_pretty(&doc).unwrap_or_default())
            .map_err(|e| gym_core::Error::invalid_argument("--json", e.to_string()))?;
        println!("\nwrote {path}");
    }
    Ok(())
}
