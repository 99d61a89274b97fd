//! Performance figures for every registered task: one-thread env steps/s with random
//! actions (raw env and through the flat GymWrapper), the physics-only cost of the same
//! model (`mj_step` × substeps per env step, arm held by gravity compensation) and the ratio,
//! reset time, resident memory per additional instance, and thread-vector-env throughput
//! for 1, 2, 4, ... environments beside the machine's parallel ceiling (the same number of
//! envs stepped by independent threads, no vector env) and EnvPool's asynchronous mode
//! (`ThreadEnvPool`, two envs per thread). Prints a table; `--json PATH` also writes JSON.
//!
//! ```text
//! cargo run --release -p examples --example benchmark -- [--task Lift] [--robot Sawyer]
//!     [--controller OSC_POSITION] [--robots] [--controllers] [--cpu-time] [--seconds 3]
//!     [--max-envs 4] [--rounds 5] [--only steps|cost|vector] [--json bench.json]
//! ```
//!
//! `--robot` and `--controller` put every task on that robot (default: the Panda) and that
//! arm controller (robosuite's part config file for it; default: the robot's own config).
//! `--robots` measures the step figures of Lift on each of the seven single-arm robots,
//! `--controllers` those of Lift on the Panda with each arm controller. `--cpu-time` counts
//! one env's steps (raw, GymWrapper, physics only) per CPU-second of its thread instead of
//! per wall-clock second: on a machine that other work shares, that is what one core gives.
//!
//! Figures are wall-clock rates: run it on an otherwise idle machine. The step rates
//! (env, GymWrapper, physics only) and the vector figures are each interleaved over
//! `--rounds` rounds (medians; ratios are medians of per-round ratios), because a shared VM's
//! speed drifts between minutes. `--seconds` is the time per figure, split over the rounds.

use adapters::{BatchSpace, ThreadEnvPool, ThreadVectorEnv, VectorEnv, WrapperExt};
use examples::case::Case;
use examples::physics_only::PhysicsOnly;
use gym_core::{Env, Result, Space, rng_from_seed};
use robosuite_env::controllers::config::ARM_CONTROLLER_TYPES;
use serde_json::json;
use std::time::{Duration, Instant};

/// A part of the figures to measure alone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Only {
    /// One env's steps/s, raw and through the GymWrapper.
    Steps,
    /// Vector-env scaling.
    Vector,
    /// One env's steps/s beside the physics-only rate of its model, reset time and
    /// memory, without the vector figures (`--only cost`, `--robots`, `--controllers`).
    Cost,
}

struct Args {
    cases: Vec<Case>,
    /// One env's rates per CPU-second of its thread rather than per second.
    cpu_time: bool,
    seconds: f64,
    max_envs: usize,
    rounds: usize,
    only: Option<Only>,
    json: Option<String>,
}

fn parse_args() -> Args {
    let mut tasks: Vec<String> = robosuite_env::ENV_NAMES
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
    let (mut robot, mut controller) = (None, None);
    let (mut robots, mut controllers) = (false, false);
    let mut args = Args {
        cases: Vec::new(),
        cpu_time: false,
        seconds: 3.0,
        max_envs: std::thread::available_parallelism()
            .map_or(2, |n| n.get())
            .max(2)
            * 2,
        rounds: 5,
        only: None,
        json: None,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        match flag.as_str() {
            "--robots" => {
                robots = true;
                continue;
            }
            "--controllers" => {
                controllers = true;
                continue;
            }
            "--cpu-time" => {
                args.cpu_time = true;
                continue;
            }
            _ => {}
        }
        let value = it.next().unwrap_or_default();
        match flag.as_str() {
            "--task" => tasks = vec![value],
            "--robot" => robot = Some(value),
            "--controller" => controller = Some(value),
            "--seconds" => args.seconds = value.parse().unwrap_or(args.seconds),
            "--max-envs" => args.max_envs = value.parse().unwrap_or(args.max_envs),
            "--rounds" => args.rounds = value.parse().unwrap_or(args.rounds).max(1),
            "--json" => args.json = Some(value),
            "--only" => match value.as_str() {
                "steps" => args.only = Some(Only::Steps),
                "vector" => args.only = Some(Only::Vector),
                "cost" => args.only = Some(Only::Cost),
                other => eprintln!("benchmark: --only takes steps, cost or vector, not {other}"),
            },
            other => eprintln!("benchmark: ignoring unknown argument {other}"),
        }
    }
    let lift = |robot: Option<&str>, controller: Option<&str>| Case {
        task: "Lift".to_owned(),
        robot: robot.map(str::to_owned),
        controller: controller.map(str::to_owned),
    };
    if robots {
        args.only = Some(Only::Cost);
        args.cases.extend(
            robosuite_env::models::robots::ROBOTS
                .iter()
                .map(|r| lift(Some(r.name), None)),
        );
    }
    if controllers {
        args.only = Some(Only::Cost);
        args.cases
            .extend(ARM_CONTROLLER_TYPES.iter().map(|c| lift(None, Some(c))));
    }
    if !robots && !controllers {
        args.cases = tasks
            .into_iter()
            .map(|task| Case {
                task,
                robot: robot.clone(),
                controller: controller.clone(),
            })
            .collect();
    }
    args
}

/// CPU time this thread has run, from `/proc/thread-self/schedstat` (Linux), in seconds.
fn thread_cpu_seconds() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: u64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns as f64 * 1e-9)
}

/// Runs `step` until `budget` of wall-clock time has passed; returns calls per CPU-second
/// of this thread (what one core gives, whatever else shares the machine), or per second
/// where the CPU time cannot be read.
fn cpu_rate(budget: Duration, mut step: impl FnMut() -> Result<()>) -> Result<f64> {
    let Some(cpu0) = thread_cpu_seconds() else {
        return rate(budget, step);
    };
    let start = Instant::now();
    let mut n = 0u64;
    while start.elapsed() < budget {
        step()?;
        n += 1;
    }
    let cpu = thread_cpu_seconds().map_or(0.0, |c| c - cpu0);
    Ok(if cpu > 0.0 { n as f64 / cpu } else { f64::NAN })
}

/// [`cpu_rate`] with `cpu_time`, else [`rate`].
fn one_env_rate(cpu_time: bool, budget: Duration, step: impl FnMut() -> Result<()>) -> Result<f64> {
    if cpu_time {
        cpu_rate(budget, step)
    } else {
        rate(budget, step)
    }
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

/// Steps/s of `n` flat-GymWrapper envs stepped by `n` independent threads (no vector env,
/// no synchronisation): what the machine itself allows for `n` parallel envs.
fn parallel_ceiling(task: &Case, n: usize, budget: Duration) -> Result<f64> {
    let envs = (0..n)
        .map(|_| task.make()?.flat_gym_wrapper(None))
        .collect::<Result<Vec<_>>>()?;
    std::thread::scope(|scope| {
        let handles: Vec<_> = envs
            .into_iter()
            .enumerate()
            .map(|(i, mut env)| {
                scope.spawn(move || {
                    let mut rng = rng_from_seed(100 + i as u64);
                    env.reset(Some(i as u64), None)?;
                    rate(budget, || {
                        let a = env.action_space().sample(&mut rng);
                        if env.step(&a)?.done() {
                            env.reset(None, None)?;
                        }
                        Ok(())
                    })
                })
            })
            .collect();
        handles.into_iter().try_fold(0.0, |sum, h| {
            let r = h
                .join()
                .map_err(|_| gym_core::Error::simulation("a benchmark thread panicked"))??;
            Ok(sum + r)
        })
    })
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        (v[m - 1] + v[m]) / 2.0
    }
}

/// ThreadVectorEnv throughput for 1, 2, 4, ... envs and the parallel ceiling of the same
/// count. The machine's speed drifts between minutes, so the measurements are interleaved
/// in `args.rounds` rounds and each ratio is the median of its per-round ratios.
fn vector_scaling(
    task: &Case,
    args: &Args,
    rng: &mut gym_core::EnvRng,
) -> Result<(Vec<serde_json::Value>, serde_json::Value)> {
    let window = Duration::from_secs_f64(args.seconds / args.rounds as f64);
    let counts: Vec<usize> = std::iter::successors(Some(1usize), |n| Some(n * 2))
        .take_while(|n| *n <= args.max_envs)
        .collect();
    let mut venvs = counts
        .iter()
        .map(|&n| {
            let envs = (0..n)
                .map(|_| task.make()?.flat_gym_wrapper(None))
                .collect::<Result<Vec<_>>>()?;
            let mut venv = ThreadVectorEnv::new(envs)?;
            venv.reset(0u64, None)?;
            Ok(venv)
        })
        .collect::<Result<Vec<_>>>()?;
    // EnvPool's asynchronous mode: 2 envs per thread, recv returns one per thread.
    let threads = std::thread::available_parallelism().map_or(2, usize::from);
    let pool_envs = (0..2 * threads)
        .map(|_| task.make()?.flat_gym_wrapper(None))
        .collect::<Result<Vec<_>>>()?;
    let mut pool = ThreadEnvPool::new(pool_envs, threads)?;
    let pool_actions = pool.single_action_space().batch_space(threads)?;
    pool.reset(0u64)?;
    let mut ids = pool.recv()?.env_ids.to_vec();
    // rates[i][round] for the vector env and the ceiling of counts[i].
    let mut vector_rates = vec![Vec::new(); counts.len()];
    let mut ceiling_rates = vec![Vec::new(); counts.len()];
    let mut pool_rates = Vec::new();
    for _ in 0..args.rounds {
        pool_rates.push(
            rate(window, || {
                let actions = pool_actions.sample(rng);
                let next = pool.step(&actions, &ids)?.env_ids.to_vec();
                ids = next;
                Ok(())
            })? * threads as f64,
        );
        for (i, (venv, &n)) in venvs.iter_mut().zip(&counts).enumerate() {
            let r = rate(window, || {
                let actions = venv.action_space().sample(rng);
                venv.step(&actions).map(|_| ())
            })? * n as f64;
            vector_rates[i].push(r);
            ceiling_rates[i].push(if n == 1 {
                r
            } else {
                parallel_ceiling(task, n, window)?
            });
        }
    }
    let ratio = |a: &[f64], b: &[f64]| median(a.iter().zip(b).map(|(x, y)| x / y).collect());
    let pool = json!({
        "envs": pool.num_envs(),
        "batch_size": pool.batch_size(),
        "threads": pool.num_threads(),
        "steps_per_s": median(pool_rates.clone()),
        "speedup": ratio(&pool_rates, &vector_rates[0]),
    });
    let vector = counts
        .iter()
        .zip(&venvs)
        .enumerate()
        .map(|(i, (&n, venv))| {
            json!({
                "envs": n,
                "threads": venv.num_threads(),
                "steps_per_s": median(vector_rates[i].clone()),
                "speedup": ratio(&vector_rates[i], &vector_rates[0]),
                "ceiling_steps_per_s": median(ceiling_rates[i].clone()),
                "ceiling_speedup": ratio(&ceiling_rates[i], &vector_rates[0]),
                "efficiency": ratio(&vector_rates[i], &ceiling_rates[i]),
            })
        })
        .collect::<Vec<_>>();
    Ok((vector, pool))
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

fn bench_task(task: &Case, args: &Args) -> Result<serde_json::Value> {
    let mut rng = rng_from_seed(1);
    let mut figures =
        json!({"task": task.task, "robot": task.robot, "controller": task.controller});
    if args.only != Some(Only::Vector) {
        step_rates(task, args, &mut rng, &mut figures)?;
    }
    if matches!(args.only, None | Some(Only::Cost)) {
        reset_and_memory(task, &mut rng, &mut figures)?;
    }
    if args.only.is_none() || args.only == Some(Only::Vector) {
        let (vector, pool) = vector_scaling(task, args, &mut rng)?;
        figures["vector"] = json!(vector);
        figures["pool"] = pool;
    }
    Ok(figures)
}

/// One env's steps/s with random actions (resets at the horizon included), raw and through
/// the flat GymWrapper, and (without `--only`) the physics-only rate of the same model.
/// The three are interleaved in `args.rounds` rounds: rates are medians, the cost ratio is
/// the median of the per-round ratios.
fn step_rates(
    task: &Case,
    args: &Args,
    rng: &mut gym_core::EnvRng,
    figures: &mut serde_json::Value,
) -> Result<()> {
    let window = Duration::from_secs_f64(args.seconds / args.rounds as f64);
    let mut env = task.make()?;
    env.reset(Some(0), None)?;
    let mut physics = match args.only {
        None | Some(Only::Cost) => Some(PhysicsOnly::new(&env)?),
        Some(_) => None,
    };
    let mut gym = task.make()?.flat_gym_wrapper(None)?;
    gym.reset(Some(0), None)?;
    let (mut env_rates, mut gym_rates, mut physics_rates) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..args.rounds {
        env_rates.push(one_env_rate(args.cpu_time, window, || {
            let a = env.action_space().sample(rng);
            if env.step(&a)?.done() {
                env.reset(None, None)?;
            }
            Ok(())
        })?);
        gym_rates.push(one_env_rate(args.cpu_time, window, || {
            let a = gym.action_space().sample(rng);
            if gym.step(&a)?.done() {
                gym.reset(None, None)?;
            }
            Ok(())
        })?);
        if let Some(p) = &mut physics {
            physics_rates.push(one_env_rate(args.cpu_time, window, || p.step())?);
        }
    }
    figures["substeps"] = json!(env.substeps());
    figures["steps_per_s"] = json!(median(env_rates.clone()));
    figures["gym_wrapper_steps_per_s"] = json!(median(gym_rates));
    if !physics_rates.is_empty() {
        let ratios = physics_rates.iter().zip(&env_rates).map(|(p, e)| p / e);
        figures["cost_ratio"] = json!(median(ratios.collect()));
        figures["physics_only_steps_per_s"] = json!(median(physics_rates));
    }
    Ok(())
}

/// Reset time and resident memory per additional instance.
fn reset_and_memory(
    task: &Case,
    rng: &mut gym_core::EnvRng,
    figures: &mut serde_json::Value,
) -> Result<()> {
    let mut env = task.make()?;
    env.reset(Some(0), None)?;
    let resets = 500;
    let t = Instant::now();
    for _ in 0..resets {
        env.reset(None, None)?;
    }
    let reset_us = t.elapsed().as_secs_f64() / f64::from(resets) * 1e6;

    let before = rss_mib();
    let mut many = Vec::new();
    for i in 0..16 {
        let mut e = task.make()?;
        e.reset(Some(i), None)?;
        for _ in 0..5 {
            let a = e.action_space().sample(rng);
            let _ = e.step(&a)?;
        }
        many.push(e);
    }
    let mib_per_env = (rss_mib() - before) / many.len() as f64;
    drop(many);

    figures["reset_us"] = json!(reset_us);
    figures["mib_per_env"] = json!(mib_per_env);
    figures["arena_mib"] = json!(env.sim().arena_bytes() as f64 / 1048576.0);
    Ok(())
}

fn main() -> Result<()> {
    let args = parse_args();
    let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
    println!(
        "robosuite-rs benchmark: {cpus} logical CPUs, {:.0} s per measurement, random actions",
        args.seconds
    );
    let mut results = Vec::new();
    for case in &args.cases {
        let r = bench_task(case, &args)?;
        println!("\n{}", case.label());
        let rows = [
            ("substeps", "substeps per env step", ""),
            ("steps_per_s", "env steps/s, one thread", ""),
            (
                "gym_wrapper_steps_per_s",
                "through GymWrapper (flat f32)",
                "",
            ),
            (
                "physics_only_steps_per_s",
                "physics only (mj_step x substeps)",
                "",
            ),
            ("cost_ratio", "physics-only / env speed", "x"),
            ("reset_us", "reset", " us"),
            ("mib_per_env", "resident memory per extra instance", " MiB"),
        ];
        for (key, label, unit) in rows {
            if let Some(v) = r[key].as_f64() {
                let digits = if unit.is_empty() { 0 } else { 2 };
                println!("  {label:<36} {v:>10.digits$}{unit}");
            }
        }
        for v in r["vector"].as_array().into_iter().flatten() {
            println!(
                "  ThreadVectorEnv {:>2} envs / {} threads {:>10.0} steps/s ({:.2}x one env; \
                 {} independent threads: {:.2}x; efficiency {:.2})",
                v["envs"],
                v["threads"],
                v["steps_per_s"].as_f64().unwrap_or(0.0),
                v["speedup"].as_f64().unwrap_or(0.0),
                v["envs"],
                v["ceiling_speedup"].as_f64().unwrap_or(0.0),
                v["efficiency"].as_f64().unwrap_or(0.0)
            );
        }
        if let Some(p) = r.get("pool") {
            println!(
                "  ThreadEnvPool {} envs, batches of {} {:>10.0} steps/s ({:.2}x one env)",
                p["envs"],
                p["batch_size"],
                p["steps_per_s"].as_f64().unwrap_or(0.0),
                p["speedup"].as_f64().unwrap_or(0.0)
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
