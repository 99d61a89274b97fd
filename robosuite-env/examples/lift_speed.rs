//! One-thread throughput of Lift (Panda, OSC_POSE) against the physics-only cost of the
//! same model, and the cost of a reset.
//!
//! `cargo run --release -p robosuite-env --example lift_speed [seconds per phase]`
//!
//! Rates are given per wall-clock second and per second of this thread's CPU time (the
//! latter is steadier on a shared machine).

use gym_core::{Env, Space, rng_from_seed};
use robosuite_env::sim::Sim;
use std::time::{Duration, Instant};

/// Wall-clock and thread-CPU time of a closure.
fn timed(f: impl FnOnce()) -> (f64, f64) {
    let cpu = || {
        let mut ts = libc::timespec {
            tv_sec: 0,
            tv_nsec: 0,
        };
        // SAFETY: clock_gettime writes into the timespec we pass.
        unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut ts) };
        ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
    };
    let (w, c) = (Instant::now(), cpu());
    f();
    (w.elapsed().as_secs_f64(), cpu() - c)
}

fn main() -> Result<(), gym_core::Error> {
    let seconds: f64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(5.0);
    let budget = Duration::from_secs_f64(seconds);
    let mut env = robosuite_env::make("Lift")?;
    let mut rng = rng_from_seed(1);
    env.reset(Some(0), None)?;
    for _ in 0..200 {
        let a = env.action_space().sample(&mut rng);
        if env.step(&a)?.done() {
            env.reset(None, None)?;
        }
    }

    // 1. Env steps with uniformly random actions; resets at the horizon are included.
    let (mut steps, mut resets) = (0u64, 0u64);
    let mut result = Ok(());
    let (wall, cpu) = timed(|| {
        let t0 = Instant::now();
        while t0.elapsed() < budget {
            let a = env.action_space().sample(&mut rng);
            match env.step(&a) {
                Ok(s) if s.done() => {
                    resets += 1;
                    if let Err(e) = env.reset(None, None) {
                        result = Err(e);
                        return;
                    }
                }
                Ok(_) => {}
                Err(e) => {
                    result = Err(e);
                    return;
                }
            }
            steps += 1;
        }
    });
    result?;
    let env_rate = (steps as f64 / wall, steps as f64 / cpu);

    // 2. Physics only: the same model, mj_step × substeps per env step, from states the
    //    env visited, with the arm held by gravity compensation (ctrl = qfrc_bias) or with
    //    zero control.
    let substeps = env.substeps();
    let start = env.get_state();
    let arm: Vec<usize> = env.robots()[0].controller().binding().dofs.to_vec();
    let physics = |hold: bool| -> Result<(f64, f64), gym_core::Error> {
        let mut sim = Sim::new(env.sim().model().clone())?;
        sim.set_state(&start)?;
        let mut n = 0u64;
        let mut bias = [0.0; 7];
        let (wall, cpu) = timed(|| {
            let t0 = Instant::now();
            while t0.elapsed() < budget {
                for _ in 0..substeps {
                    if hold {
                        for (b, &d) in bias.iter_mut().zip(&arm) {
                            *b = sim.data().qfrc_bias()[d];
                        }
                        sim.data_mut().ctrl_mut()[..7].copy_from_slice(&bias);
                    }
                    sim.step();
                }
                n += 1;
                if n.is_multiple_of(200) {
                    // Stay in the states the env sees (the arm sags with zero control).
                    let _ = sim.set_state(&start);
                }
            }
        });
        Ok((n as f64 / wall, n as f64 / cpu))
    };
    let phys_hold = physics(true)?;
    let phys_zero = physics(false)?;

    // 3. Reset cost.
    let n_resets = 2000;
    let mut reset_result = Ok(());
    let (rw, rc) = timed(|| {
        for _ in 0..n_resets {
            if let Err(e) = env.reset(None, None) {
                reset_result = Err(e);
                return;
            }
        }
    });
    reset_result?;

    // 4. Resident memory per instance (after a reset and a few steps each).
    let rss = || -> f64 {
        std::fs::read_to_string("/proc/self/statm")
            .ok()
            .and_then(|s| {
                s.split_whitespace()
                    .nth(1)
                    .and_then(|v| v.parse::<f64>().ok())
            })
            .map_or(f64::NAN, |pages| pages * 4096.0 / 1048576.0)
    };
    let before = rss();
    let mut many = Vec::new();
    for i in 0..20 {
        let mut e = robosuite_env::make("Lift")?;
        e.reset(Some(i), None)?;
        for _ in 0..10 {
            let a = e.action_space().sample(&mut rng);
            let _ = e.step(&a)?;
        }
        many.push(e);
    }
    let per_instance = (rss() - before) / many.len() as f64;

    println!("Lift (Panda, OSC_POSE), one thread, {substeps} substeps per env step");
    println!("                                             per wall s   per CPU s");
    println!(
        "  env steps/s (random actions, {resets:>3} resets) {:>12.0} {:>11.0}",
        env_rate.0, env_rate.1
    );
    println!(
        "  physics only, gravity-comp ctrl (steps/s)  {:>12.0} {:>11.0}",
        phys_hold.0, phys_hold.1
    );
    println!(
        "  physics only, zero ctrl (steps/s)          {:>12.0} {:>11.0}",
        phys_zero.0, phys_zero.1
    );
    println!(
        "  env cost / physics cost (gravity-comp)     {:>12.3} {:>11.3}",
        phys_hold.0 / env_rate.0,
        phys_hold.1 / env_rate.1
    );
    println!(
        "  reset (us)                                 {:>12.1} {:>11.1}",
        rw / f64::from(n_resets) * 1e6,
        rc / f64::from(n_resets) * 1e6
    );
    println!("  resident memory per instance (MiB)         {per_instance:>12.2}");
    let d = env.sim().data().ffi();
    println!(
        "  mjData arena {:.2} MiB (max used {:.1} KiB arena, {:.1} KiB stack)",
        env.sim().arena_bytes() as f64 / 1048576.0,
        d.maxuse_arena as f64 / 1024.0,
        d.maxuse_stack as f64 / 1024.0
    );
    Ok(())
}
