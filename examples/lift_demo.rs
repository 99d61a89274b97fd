//! `make demo`: one Lift episode driven by a scripted policy, printed as it happens.
//!
//! The policy reads robosuite's observation keys (`cube_pos`, `robot0_eef_pos`), moves
//! the gripper above the cube, descends, closes and lifts, with OSC_POSE delta actions
//! `[dx, dy, dz, ax, ay, az, grip]` in [-1, 1] (±1 = ±5 cm per step). Afterwards it runs
//! random actions for a second and prints the measured steps per second.
//!
//! Run with `cargo run --release -p examples --example lift_demo [seed]`.

use examples::{LiftScript, format_info, vec3};
use gym_core::{Env, Space, rng_from_seed};
use robosuite_env::EnvConfig;
use std::time::Instant;

fn main() -> gym_core::Result<()> {
    let seed = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0u64);
    let mut env = robosuite_env::make_with("Lift", EnvConfig::default().with_horizon(200))?;
    println!("Lift with a Panda arm, OSC_POSE controller, 20 Hz control, horizon 200, seed {seed}");
    println!(
        "action space:      {}",
        gym_core::AnySpace::from(env.action_space().clone())
    );
    let keys: Vec<&str> = env.observation_space().keys().collect();
    println!("observation keys:  {}", keys.join(", "));

    let (mut obs, _) = env.reset(Some(seed), None)?;
    let cube0 = vec3(&obs, "cube_pos");
    println!(
        "cube starts at     ({:.3}, {:.3}, {:.3})",
        cube0[0], cube0[1], cube0[2]
    );
    let mut script = LiftScript::new(&obs);
    let mut total = 0.0;
    let mut first_success = None;
    for t in 1.. {
        let (eef, phase) = (vec3(&obs, "robot0_eef_pos"), script.phase);
        let action = script.act(&obs);
        let step = env.step(&action)?;
        total += step.reward;
        if step.info.get_bool("success") == Some(true) && first_success.is_none() {
            first_success = Some(t);
            println!(
                "step {t:3}: success: cube lifted above the table by > 4 cm ({})",
                format_info(&step.info)
            );
        }
        let next = script.phase;
        if std::mem::discriminant(&next) != std::mem::discriminant(&phase) {
            println!(
                "step {t:3}: {phase:?} done, eef ({:.3}, {:.3}, {:.3}) -> {next:?}",
                eef[0], eef[1], eef[2]
            );
        }
        obs = step.observation;
        if step.terminated || step.truncated {
            let cube = vec3(&obs, "cube_pos");
            println!(
                "step {t:3}: episode ends (terminated {}, truncated {}): cube at z {:.3}, return {total:.2}",
                step.terminated, step.truncated, cube[2]
            );
            break;
        }
    }
    match first_success {
        Some(t) => {
            println!("result: the scripted policy lifted the cube (first success at step {t})")
        }
        None => println!("result: no success this episode"),
    }

    // Throughput with random actions, one thread.
    let mut rng = rng_from_seed(seed);
    env.reset(Some(seed), None)?;
    let start = Instant::now();
    let mut steps = 0u64;
    while start.elapsed().as_secs_f64() < 1.0 {
        let action = env.action_space().sample(&mut rng);
        if env.step(&action)?.done() {
            env.reset(None, None)?;
        }
        steps += 1;
    }
    println!(
        "random actions:    {:.0} env steps/s on one thread",
        steps as f64 / start.elapsed().as_secs_f64()
    );
    Ok(())
}
