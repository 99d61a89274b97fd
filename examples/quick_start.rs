//! The README's Rust quick start, kept compiling: a wrapper stack over Lift, one step.
//!
//! Run with `cargo run --release -p examples --example quick_start`.

use adapters::WrapperExt;
use gym_core::{Env, Space, rng_from_seed};

fn main() -> gym_core::Result<()> {
    let mut env = robosuite_env::make("Lift")? // robosuite's dict observations
        .gym_wrapper(None, true)? // 60-dim float32 vector, object-state first
        .time_limit(500)?
        .normalize_observation()?;
    let (_obs, _info) = env.reset(Some(42), None)?;
    let mut rng = rng_from_seed(0);
    let action = env.action_space().sample(&mut rng);
    let step = env.step(&action)?;
    println!(
        "reward {} success {:?}",
        step.reward,
        step.info.get_bool("success")
    );
    Ok(())
}
