//! One-thread env steps per second (random actions, resets at the horizon included) for
//! every registered task, or for the tasks named on the command line.
//!
//! `cargo run --release -p robosuite-env --example task_speed [seconds] [Task ...]`

use gym_core::{Env, Space, rng_from_seed};
use std::time::{Duration, Instant};

fn main() -> Result<(), gym_core::Error> {
    let mut args = std::env::args().skip(1);
    let seconds: f64 = args.next().and_then(|s| s.parse().ok()).unwrap_or(3.0);
    let names: Vec<String> = args.collect();
    let names: Vec<String> = if names.is_empty() {
        robosuite_env::ENV_NAMES
            .iter()
            .map(|s| (*s).to_owned())
            .collect()
    } else {
        names
    };
    for name in names {
        let mut env = robosuite_env::make(&name)?;
        let mut rng = rng_from_seed(1);
        env.reset(Some(0), None)?;
        let (mut steps, t0) = (0u64, Instant::now());
        while t0.elapsed() < Duration::from_secs_f64(seconds) {
            let a = env.action_space().sample(&mut rng);
            steps += 1;
            if env.step(&a)?.done() {
                env.reset(None, None)?;
            }
        }
        let rate = steps as f64 / t0.elapsed().as_secs_f64();
        let r0 = Instant::now();
        for _ in 0..50 {
            env.reset(None, None)?;
        }
        let reset_us = r0.elapsed().as_secs_f64() / 50.0 * 1e6;
        println!("{name:<20} {rate:>8.0} env steps/s   reset {reset_us:>6.0} µs");
    }
    Ok(())
}
