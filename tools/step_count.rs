//! A fixed number of env steps of one task through one layer, for instruction-count
//! profiling: wall-clock rates on a shared 2-vCPU VM drift by ±30 % between minutes, while
//! `valgrind --tool=callgrind` counts the same instructions for the same binary and input.
//!
//! ```text
//! cargo build --release -p tools --bin step_count
//! valgrind --tool=callgrind target/release/step_count Lift gym 200 [ROBOT] [CONTROLLER]
//! ```
//!
//! `ROBOT` puts the task on another robot (`-` or nothing: the Panda), `CONTROLLER` uses
//! robosuite's part config file of that arm controller (nothing: the robot's default).
//!
//! Layers: `raw` (the robosuite env, dict observations), `gym` (the flat f32 GymWrapper),
//! `physics` (the same model, `mj_step` × substeps, arm held by gravity compensation).
//! Actions are drawn from a seeded generator before the loop, so runs are identical. The
//! per-step cost is the difference of two runs with different step counts divided by the
//! difference of the counts (`scripts/instructions_per_step.sh` does this).

use adapters::WrapperExt;
use gym_core::{Env, Error, Result, Space, rng_from_seed};
use std::hint::black_box;
use tools::case::Case;
use tools::physics_only::PhysicsOnly;

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let task = args.first().map_or("Lift", String::as_str);
    let layer = args.get(1).map_or("gym", String::as_str);
    let steps: usize = match args.get(2) {
        None => 200,
        Some(s) => s
            .parse()
            .map_err(|_| Error::invalid_argument("steps", format!("not a count: {s}")))?,
    };
    let case = Case {
        task: task.to_owned(),
        robot: args.get(3).filter(|r| *r != "-").cloned(),
        controller: args.get(4).cloned(),
    };
    let mut rng = rng_from_seed(7);
    let mut env = case.make()?;
    let actions: Vec<_> = (0..steps)
        .map(|_| env.action_space().sample(&mut rng))
        .collect();
    match layer {
        "raw" => {
            env.reset(Some(0), None)?;
            for a in &actions {
                let step = env.step(a)?;
                if step.done() {
                    env.reset(None, None)?;
                }
                let _ = black_box(step);
            }
        }
        "gym" => {
            let mut gym = env.flat_gym_wrapper(None)?;
            gym.reset(Some(0), None)?;
            for a in &actions {
                let step = gym.step(&a.mapv(|v| v as f32))?;
                if step.done() {
                    gym.reset(None, None)?;
                }
                let _ = black_box(step);
            }
        }
        "physics" => {
            env.reset(Some(0), None)?;
            let mut physics = PhysicsOnly::new(&env)?;
            for _ in &actions {
                physics.step()?;
            }
            let _ = black_box(physics.state());
        }
        other => {
            return Err(Error::invalid_argument(
                "layer",
                format!("expected raw, gym or physics, got {other}"),
            ));
        }
    }
    println!("{} {layer}: {steps} steps", case.label());
    Ok(())
}
