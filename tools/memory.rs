//! Memory per environment: resident memory (RSS) and proportional set size (PSS) of the
//! process after one environment of a task and after `N`, each made, reset and stepped
//! once; the figure is the growth per further environment.
//!
//! ```text
//! cargo run --release -p tools --bin memory -- [N] [TASK ...] [--private] [--textures]
//! ```
//!
//! Defaults: `N` = 128, tasks Lift, Stack, Door, TwoArmPegInHole. Every env shares its
//! scene's compiled model copy-on-write; `--private` gives each env a model of its own
//! (`Data::make_model_private`, a full `mj_copyModel`), the cost without sharing. The
//! envs never render, so their scene is compiled without texture images; `--textures`
//! makes them with an offscreen renderer (robosuite's `has_offscreen_renderer=True`),
//! which keeps the images. Also prints the time to make the first env of each task (its
//! scene compiled) and the model's texture bytes (`ntexdata`).
//! Linux only (reads `/proc/self`).

use gym_core::{Env, Result, Space};
use ndarray::ArrayD;

/// A field of `/proc/self/<file>` in KiB (`VmRSS:` of `status`, `Pss:` of `smaps_rollup`).
fn kib(file: &str, key: &str) -> f64 {
    let text = std::fs::read_to_string(format!("/proc/self/{file}")).unwrap_or_default();
    text.lines()
        .find_map(|l| l.strip_prefix(key))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|v| v.parse().ok())
        .unwrap_or(f64::NAN)
}

/// (RSS, PSS) in MiB.
fn memory() -> (f64, f64) {
    (
        kib("status", "VmRSS:") / 1024.0,
        kib("smaps_rollup", "Pss:") / 1024.0,
    )
}

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let private = args.iter().any(|a| a == "--private");
    let textures = args.iter().any(|a| a == "--textures");
    args.retain(|a| a != "--private" && a != "--textures");
    let n: usize = match args.first().and_then(|a| a.parse().ok()) {
        Some(n) => {
            args.remove(0);
            n
        }
        None => 128,
    };
    let tasks = if args.is_empty() {
        ["Lift", "Stack", "Door", "TwoArmPegInHole"]
            .map(String::from)
            .to_vec()
    } else {
        args
    };
    println!(
        "{n} envs per task, models {}, {}",
        if private { "private" } else { "shared" },
        if textures {
            "with texture images"
        } else {
            "without texture images"
        }
    );
    println!(
        "task              first env RSS   per further env: RSS    PSS   first make  tex_data"
    );
    for task in &tasks {
        let start = memory();
        let mut envs = Vec::with_capacity(n);
        let mut first = (0.0, 0.0);
        let mut first_make = std::time::Duration::ZERO;
        let mut texture_bytes = 0;
        for i in 0..n {
            let mut config = robosuite_env::EnvConfig::default();
            config.cameras.has_offscreen_renderer = textures;
            let made = std::time::Instant::now();
            let mut env = robosuite_env::make_with(task, config)?;
            if i == 0 {
                first_make = made.elapsed();
                texture_bytes = env.sim().model().ffi().ntexdata;
            }
            if private {
                env.sim_mut().data_mut().make_model_private();
            }
            env.reset(Some(i as u64), None)?;
            let zero: ArrayD<f64> =
                ArrayD::zeros(env.action_space().shape().unwrap_or(&[]).to_vec());
            let _ = env.step(&zero)?;
            envs.push(env);
            if i == 0 {
                first = memory();
            }
        }
        let last = memory();
        let per = |a: f64, b: f64| (b - a) / (n.max(2) - 1) as f64;
        println!(
            "{task:<17} {:>9.1} MiB   {:>14.2} MiB {:>6.2} MiB {:>8.0} ms {:>9.2} MiB",
            first.0 - start.0,
            per(first.0, last.0),
            per(first.1, last.1),
            first_make.as_secs_f64() * 1e3,
            texture_bytes as f64 / 1048576.0
        );
        drop(envs);
    }
    Ok(())
}
