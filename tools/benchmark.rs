//! Performance figures for every registered task: one-thread env steps/s with random
//! actions (raw env and through the flat GymWrapper), the physics-only cost of the same
//! model (`mj_step` × substeps per env step, arm held by gravity compensation) and the ratio,
//! reset time, resident memory per additional instance, and thread-vector-env throughput
//! for 1, 2, 4, ... environments beside the machine's parallel ceiling (the same number of
//! envs stepped by independent threads, no vector env) and EnvPool's asynchronous mode
//! (`ThreadEnvPool`, two envs per thread). Prints a table; `--json PATH` also writes JSON.
//!
//! ```text
//! cargo run --release -p tools --bin benchmark -- [--task Lift] [--robot Sawyer]
//!     [--controller OSC_POSITION] [--robots] [--controllers] [--cpu-time] [--seconds 3]
//!     [--max-envs 4] [--rounds 5] [--pin] [--only steps|cost|vector|model] [--json bench.json]
//! ```
//!
//! The vector table has one row per env count (1, 2, 4, ... up to `--max-envs`, by default
//! twice the logical CPUs): `ThreadVectorEnv`'s steps/s on its default threads, the
//! independent-thread ceiling for as many envs, and the efficiency (the median of the
//! per-round ratios); the pool line has its efficiency against the ceiling of as many envs
//! as it has threads. `--only model` measures the distribution of one env's step times
//! (`step_into` with random actions, an episode's reset counted as a step, as a vector
//! env's autoreset is) and prints the barrier model's predicted efficiency (see
//! `tools::barrier_model`) for 2, 8 and 16 threads beside the vector table measured
//! here; it also splits the spread of step times into the env's own and the machine's
//! noise (each step timed again from a snapshot) and gives the model for a quiet core.
//!
//! `--pin` pins the vector envs' and the pool's worker threads to CPUs
//! ([`ThreadOptions::pin`](adapters::ThreadOptions)); the ceiling's threads stay unpinned.
//!
//! `--robot` and `--controller` put every task on that robot (default: the Panda) and that
//! arm controller (robosuite's part config file for it; default: the robot's own config).
//! `--robots` measures the step figures of Lift on each robot of robosuite's robot table,
//! `--controllers` those of Lift on the Panda with each arm controller. `--cpu-time` counts
//! one env's steps (raw, GymWrapper, physics only) per CPU-second of its thread instead of
//! per wall-clock second: on a machine that other work shares, that is what one core gives.
//!
//! Figures are wall-clock rates: run it on an otherwise idle machine. The step rates
//! (env, GymWrapper, physics only) and the vector figures are each interleaved over
//! `--rounds` rounds (medians; ratios are medians of per-round ratios), because a shared VM's
//! speed drifts between minutes. `--seconds` is the time per figure, split over the rounds.

use adapters::{BatchSpace, ThreadEnvPool, ThreadOptions, ThreadVectorEnv, VectorEnv, WrapperExt};
use gym_core::{Env, Info, Result, Space, rng_from_seed};
use robosuite_env::controllers::config::ARM_CONTROLLER_TYPES;
use serde_json::json;
use std::time::{Duration, Instant};
use tools::barrier_model::{Assignment, expected_max, predicted_efficiency, summarize};
use tools::case::Case;
use tools::physics_only::PhysicsOnly;

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
    /// The step-time distribution, the barrier model's predictions and the vector table.
    Model,
}

struct Args {
    cases: Vec<Case>,
    /// One env's rates per CPU-second of its thread rather than per second.
    cpu_time: bool,
    /// The vector envs' and the pool's threads.
    threads: ThreadOptions,
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
        threads: ThreadOptions::default(),
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
            "--pin" => {
                args.threads = args.threads.pinned();
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
                "model" => args.only = Some(Only::Model),
                other => {
                    eprintln!("benchmark: --only takes steps, cost, vector or model, not {other}")
                }
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

/// Steps/s of `n` flat-GymWrapper envs stepped (`step_into`, as the vector envs do) by `n`
/// independent threads (no vector env, no synchronisation): what the machine itself allows
/// for `n` parallel envs.
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
                    let (mut obs, mut info) = env.reset(Some(i as u64), None)?;
                    rate(budget, || {
                        let a = env.action_space().sample(&mut rng);
                        if env.step_into(&a, &mut obs, &mut info)?.done() {
                            (obs, info) = env.reset(None, None)?;
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
            let mut venv = ThreadVectorEnv::with_options(envs, args.threads)?;
            venv.reset(0u64, None)?;
            Ok(venv)
        })
        .collect::<Result<Vec<_>>>()?;
    // EnvPool's asynchronous mode: 2 envs per thread, recv returns one per thread.
    let threads = std::thread::available_parallelism().map_or(2, usize::from);
    let pool_envs = (0..2 * threads)
        .map(|_| task.make()?.flat_gym_wrapper(None))
        .collect::<Result<Vec<_>>>()?;
    let mut pool = ThreadEnvPool::with_options(pool_envs, threads, args.threads)?;
    let pool_actions = pool.single_action_space().batch_space(threads)?;
    pool.reset(0u64)?;
    let mut ids = pool.recv()?.env_ids.to_vec();
    // rates[i][round] for the vector env and the ceiling of counts[i].
    let mut vector_rates = vec![Vec::new(); counts.len()];
    let mut ceiling_rates = vec![Vec::new(); counts.len()];
    let mut pool_rates = Vec::new();
    // The ceiling of as many envs as the pool has threads, where no row measures it.
    let pool_row = counts.iter().position(|&n| n == pool.num_threads());
    let mut pool_ceiling_rates = Vec::new();
    for _ in 0..args.rounds {
        if pool_row.is_none() {
            pool_ceiling_rates.push(parallel_ceiling(task, pool.num_threads(), window)?);
        }
        pool_rates.push(
            rate(window, || {
                let actions = pool_actions.sample(rng);
                let batch = pool.step(&actions, &ids)?;
                ids.copy_from_slice(batch.env_ids);
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
    let pool_ceiling = pool_row.map_or(&pool_ceiling_rates, |i| &ceiling_rates[i]);
    let pool = json!({
        "envs": pool.num_envs(),
        "batch_size": pool.batch_size(),
        "threads": pool.num_threads(),
        "steps_per_s": median(pool_rates.clone()),
        "speedup": ratio(&pool_rates, &vector_rates[0]),
        "ceiling_steps_per_s": median(pool_ceiling.clone()),
        "efficiency": ratio(&pool_rates, pool_ceiling),
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
    if matches!(args.only, None | Some(Only::Model)) {
        step_time_model(task, args, &mut rng, &mut figures)?;
        step_time_split(task, args, &mut rng, &mut figures)?;
    }
    if matches!(args.only, None | Some(Only::Vector) | Some(Only::Model)) {
        let (vector, pool) = vector_scaling(task, args, &mut rng)?;
        figures["vector"] = json!(vector);
        figures["pool"] = pool;
    }
    Ok(figures)
}

/// CPU time this thread has run, in seconds (`CLOCK_THREAD_CPUTIME_ID`: exact, unlike
/// [`thread_cpu_seconds`], which is updated at scheduler ticks).
fn thread_cpu_now() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to fill.
    unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

fn summary_json(times: &[f64]) -> serde_json::Value {
    let s = summarize(times);
    json!({
        "count": s.count, "mean": s.mean, "sd": s.sd, "min": s.min, "p50": s.p50,
        "p90": s.p90, "p99": s.p99, "max": s.max,
    })
}

/// The barrier model's predictions for 2, 8 and 16 threads from a sample of step times.
fn model_rows(times: &[f64], rng: &mut gym_core::EnvRng) -> Vec<serde_json::Value> {
    let rounds = 20_000;
    let mean = summarize(times).mean;
    let mut rows = Vec::new();
    for threads in [2usize, 8, 16] {
        let e_max = expected_max(times, threads, rounds, rng);
        for (envs, assignment) in [
            (threads, Assignment::Static),
            (threads, Assignment::Dynamic),
            (2 * threads, Assignment::Static),
            (2 * threads, Assignment::Dynamic),
            (4 * threads, Assignment::Static),
            (4 * threads, Assignment::Dynamic),
        ] {
            rows.push(json!({
                "threads": threads,
                "envs": envs,
                "assignment": format!("{assignment:?}").to_lowercase(),
                "predicted_efficiency":
                    predicted_efficiency(times, envs, threads, assignment, rounds, rng),
                "expected_max_over_mean": e_max / mean,
            }));
        }
    }
    rows
}

/// One env's single-step times (`step_into`, random actions; the reset after an episode's
/// end counted as a step, as a vector env's autoreset is), in wall-clock and in CPU time of
/// the stepping thread (what a dedicated core sees: without preemption by other work), their
/// summaries in µs, and the barrier model's predicted efficiency for 2, 8 and 16 threads
/// from each sample (see `tools::barrier_model`).
fn step_time_model(
    task: &Case,
    args: &Args,
    rng: &mut gym_core::EnvRng,
    figures: &mut serde_json::Value,
) -> Result<()> {
    let mut env = task.make()?.flat_gym_wrapper(None)?;
    let (mut obs, _) = env.reset(Some(0), None)?;
    let mut info = Info::new();
    let (mut wall, mut cpu) = (Vec::new(), Vec::new());
    let budget = Duration::from_secs_f64(args.seconds);
    let start = Instant::now();
    let mut ended = false;
    while start.elapsed() < budget || wall.len() < 200 {
        let a = env.action_space().sample(rng);
        let (t, c) = (Instant::now(), thread_cpu_now());
        if ended {
            (obs, info) = env.reset(None, None)?;
            ended = false;
        } else {
            ended = env.step_into(&a, &mut obs, &mut info)?.done();
        }
        cpu.push((thread_cpu_now() - c) * 1e6);
        wall.push(t.elapsed().as_secs_f64() * 1e6);
    }
    figures["step_times_us"] = summary_json(&wall);
    figures["step_cpu_times_us"] = summary_json(&cpu);
    figures["barrier_model"] = json!(model_rows(&cpu, rng));
    figures["barrier_model_wall"] = json!(model_rows(&wall, rng));
    Ok(())
}

/// How many times [`step_time_split`] steps each state.
const REPEATS: usize = 5;

/// Splits the spread of one env's step CPU times into the env's own (different states and
/// actions take different times: contacts, solver iterations) and the machine's (the same
/// step timed again). Random actions as in [`step_time_model`]; before each step a
/// snapshot is taken and the same step, from the same state with the same action, is
/// stepped [`REPEATS`] times (restored in between, untimed; bit-identical by
/// [`RobosuiteEnv::snapshot`](robosuite_env::RobosuiteEnv::snapshot)). The first run is
/// timed as a normal step; the repeats after it find warm caches, so their spread (pooled
/// within each state) is the machine's noise, and their median per state is the step's
/// time on a quiet core. The barrier model from those medians is what a machine without
/// noise would see.
fn step_time_split(
    task: &Case,
    args: &Args,
    rng: &mut gym_core::EnvRng,
    figures: &mut serde_json::Value,
) -> Result<()> {
    let mut env = task.make()?;
    let (mut obs, mut info) = env.reset(Some(1), None)?;
    let (mut first, mut quiet) = (Vec::new(), Vec::new());
    let (mut within_ss, mut within_df) = (0.0, 0usize);
    let budget = Duration::from_secs_f64(args.seconds);
    let start = Instant::now();
    while start.elapsed() < budget || first.len() < 100 {
        let a = env.action_space().sample(rng);
        let snapshot = env.snapshot();
        let mut times = [0.0; REPEATS];
        let mut done = false;
        for (r, time) in times.iter_mut().enumerate() {
            if r > 0 {
                env.restore(&snapshot)?;
            }
            let c = thread_cpu_now();
            done = env.step_into(&a, &mut obs, &mut info)?.done();
            *time = (thread_cpu_now() - c) * 1e6;
        }
        if done {
            (obs, info) = env.reset(None, None)?;
        }
        first.push(times[0]);
        let repeats = &mut times[1..];
        let mean = repeats.iter().sum::<f64>() / repeats.len() as f64;
        within_ss += repeats.iter().map(|t| (t - mean).powi(2)).sum::<f64>();
        within_df += repeats.len() - 1;
        repeats.sort_by(f64::total_cmp);
        quiet.push(repeats[repeats.len() / 2]);
    }
    let noise_sd = (within_ss / within_df.max(1) as f64).sqrt();
    figures["step_time_split"] = json!({
        "states": first.len(),
        "repeats": REPEATS - 1,
        "first_run_cpu_us": summary_json(&first),
        "quiet_cpu_us": summary_json(&quiet),
        "noise_sd_us": noise_sd,
    });
    figures["barrier_model_quiet"] = json!(model_rows(&quiet, rng));
    Ok(())
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
    let mut failed = Vec::new();
    for case in &args.cases {
        let r = match bench_task(case, &args) {
            Ok(r) => r,
            Err(e) => {
                // One case that cannot be made (a robot a task refuses) does not stop the
                // others; the run still fails at the end.
                eprintln!("\n{}: not measured: {e}", case.label());
                failed.push(case.label());
                continue;
            }
        };
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
        for (key, label) in [
            ("step_times_us", "step time, wall-clock"),
            ("step_cpu_times_us", "step time, thread CPU"),
        ] {
            if let Some(t) = r.get(key) {
                println!(
                    "  {label} (us, {} steps): mean {:.1}, sd {:.1}, min {:.1}, p50 {:.1}, \
                     p90 {:.1}, p99 {:.1}, max {:.1}",
                    t["count"],
                    t["mean"].as_f64().unwrap_or(0.0),
                    t["sd"].as_f64().unwrap_or(0.0),
                    t["min"].as_f64().unwrap_or(0.0),
                    t["p50"].as_f64().unwrap_or(0.0),
                    t["p90"].as_f64().unwrap_or(0.0),
                    t["p99"].as_f64().unwrap_or(0.0),
                    t["max"].as_f64().unwrap_or(0.0)
                );
            }
        }
        let wall_model = r["barrier_model_wall"].as_array();
        for (k, m) in r["barrier_model"]
            .as_array()
            .into_iter()
            .flatten()
            .enumerate()
        {
            let measured = (m["threads"].as_u64() == Some(cpus as u64)
                && m["assignment"] == "dynamic")
                .then(|| {
                    r["vector"]
                        .as_array()
                        .into_iter()
                        .flatten()
                        .find(|v| v["envs"] == m["envs"] && v["threads"] == m["threads"])
                })
                .flatten()
                .and_then(|v| v["efficiency"].as_f64());
            let wall = wall_model
                .and_then(|w| w.get(k))
                .and_then(|w| w["predicted_efficiency"].as_f64())
                .unwrap_or(f64::NAN);
            println!(
                "  model: {:>2} threads, {:>2} envs, {:<7} predicted efficiency {:.3} \
                 (E[max of {}] / mean {:.2}; from wall-clock times {:.3}){}",
                m["threads"],
                m["envs"],
                m["assignment"].as_str().unwrap_or(""),
                m["predicted_efficiency"].as_f64().unwrap_or(0.0),
                m["threads"],
                m["expected_max_over_mean"].as_f64().unwrap_or(0.0),
                wall,
                measured.map_or(String::new(), |e| format!("; measured here {e:.3}"))
            );
        }
        if let Some(split) = r.get("step_time_split") {
            let sd = |k: &str| split[k]["sd"].as_f64().unwrap_or(0.0);
            let mean = |k: &str| split[k]["mean"].as_f64().unwrap_or(0.0);
            println!(
                "  step time split ({} states, each stepped again {} times from a snapshot): \
                 first run mean {:.1} sd {:.1}; repeated (quiet core) median per state: mean \
                 {:.1} sd {:.1}; machine noise sd {:.1} (us)",
                split["states"],
                split["repeats"],
                mean("first_run_cpu_us"),
                sd("first_run_cpu_us"),
                mean("quiet_cpu_us"),
                sd("quiet_cpu_us"),
                split["noise_sd_us"].as_f64().unwrap_or(0.0)
            );
        }
        for m in r["barrier_model_quiet"]
            .as_array()
            .into_iter()
            .flatten()
            .filter(|m| m["assignment"] == "dynamic")
        {
            println!(
                "  model from the quiet-core times: {:>2} threads, {:>2} envs, predicted \
                 efficiency {:.3} (E[max of {}] / mean {:.2})",
                m["threads"],
                m["envs"],
                m["predicted_efficiency"].as_f64().unwrap_or(0.0),
                m["threads"],
                m["expected_max_over_mean"].as_f64().unwrap_or(0.0),
            );
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
                "  ThreadEnvPool {} envs, batches of {} {:>10.0} steps/s ({:.2}x one env; \
                 efficiency {:.2} against {} independent threads)",
                p["envs"],
                p["batch_size"],
                p["steps_per_s"].as_f64().unwrap_or(0.0),
                p["speedup"].as_f64().unwrap_or(0.0),
                p["efficiency"].as_f64().unwrap_or(0.0),
                p["threads"]
            );
        }
        results.push(r);
    }
    if let Some(path) = &args.json {
        let doc = json!({"cpus": cpus, "seconds": args.seconds, "pinned": args.threads.pin, "tasks": results});
        std::fs::write(path, serde_json::to_string_pretty(&doc).unwrap_or_default())
            .map_err(|e| gym_core::Error::invalid_argument("--json", e.to_string()))?;
        println!("\nwrote {path}");
    }
    if failed.is_empty() {
        Ok(())
    } else {
        Err(gym_core::Error::simulation(format!(
            "not measured: {}",
            failed.join(", ")
        )))
    }
}
