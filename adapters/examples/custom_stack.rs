//! A custom wrapper stack over robosuite's Lift, one scripted episode, then the same stack
//! in a thread-parallel vector environment.
//!
//! ```text
//! cargo run -p adapters --release --example custom_stack
//! ```

use adapters::{AutoresetMode, ThreadVectorEnv, VectorEnv, WrapperExt};
use gym_core::{Env, IntoBoxedEnv, Space, Wrapper};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::EnvConfig;

/// Flat-observation layout of Lift (object-state first): cube position, and the
/// end-effector position inside robot0_proprio-state (which starts at 10).
const CUBE_POS: std::ops::Range<usize> = 0..3;
const EEF_POS: std::ops::Range<usize> = 45..48;

/// A scripted grasp: hover above the cube, descend, close the gripper, lift.
/// OSC_POSE maps an action of 1 to a 5 cm position delta per step; outputs are not clipped
/// here on purpose (ClipAction does it).
fn policy(obs: &ArrayD<f32>, t: u64) -> ArrayD<f32> {
    let cube: Vec<f32> = obs.as_slice().unwrap()[CUBE_POS].to_vec();
    let eef: Vec<f32> = obs.as_slice().unwrap()[EEF_POS].to_vec();
    let d: Vec<f32> = cube.iter().zip(&eef).map(|(c, e)| c - e).collect();
    let xy_err = (d[0] * d[0] + d[1] * d[1]).sqrt();
    let (target_dz, grip) = match t {
        _ if xy_err > 0.01 && t < 40 => (d[2] + 0.05, -1.0), // above the cube, open
        0..=59 => (d[2], -1.0),                              // descend, open
        60..=74 => (0.0, 1.0),                               // close
        _ => (0.15, 1.0),                                    // lift
    };
    let gain = 1.0 / 0.05;
    let mut a = vec![
        gain * d[0],
        gain * d[1],
        gain * target_dz,
        0.0,
        0.0,
        0.0,
        grip,
    ];
    if t >= 60 {
        a[0] = 0.0;
        a[1] = 0.0;
    }
    ArrayD::from_shape_vec(IxDyn(&[7]), a).expect("7 values")
}

fn main() -> Result<(), gym_core::Error> {
    let make = || -> Result<_, gym_core::Error> {
        Ok(
            robosuite_env::make_with("Lift", EnvConfig::default().with_horizon(1000))?
                .flat_gym_wrapper(None)? // 60-dim float32 observations, f32 actions
                .passive_env_checker()? // every reset/step validated against the spaces
                .clip_action()? // the scripted policy may leave [-1, 1]
                .time_limit(120)? // shorter episodes than the env's horizon
                .record_episode_statistics() // info["episode"] = {r, l, t}
                .transform_reward(|r| 10.0 * r),
        ) // any closure
    };

    let mut env = make()?;
    println!(
        "stack: TransformReward<RecordEpisodeStatistics<TimeLimit<ClipAction<PassiveEnvChecker<FlatGymWrapper<Lift>>>>>>"
    );
    println!("observation space: {}", env.observation_space());
    println!("action space:      {}", env.action_space());

    let (mut obs, _) = env.reset(Some(7), None)?;
    let (mut total, mut t, mut success_steps) = (0.0, 0u64, 0);
    loop {
        let step = env.step(&policy(&obs, t))?;
        total += step.reward;
        t += 1;
        if step.info.get_bool("success") == Some(true) {
            success_steps += 1;
        }
        if t % 20 == 0 || step.terminated || step.truncated {
            let cube_z = step.observation[[2]];
            println!(
                "t={t:3}  reward={:6.3}  cube z={cube_z:.4}  success={:?}",
                step.reward,
                step.info.get_bool("success")
            );
        }
        obs = step.observation;
        if step.terminated || step.truncated {
            let ep = step
                .info
                .get_map("episode")
                .expect("RecordEpisodeStatistics adds it");
            println!(
                "episode: r={:.3} (inner, before the reward transform) l={} t={:.3}s; {} steps with success; \
                 total transformed reward {total:.3}; terminated={} truncated={}",
                ep.get_f64("r").unwrap_or(0.0),
                ep.get_i64("l").unwrap_or(0),
                ep.get_f64("t").unwrap_or(0.0),
                success_steps,
                step.terminated,
                step.truncated
            );
            break;
        }
    }
    println!(
        "checker warnings: {:?}",
        env.inner().inner().inner().inner().warnings()
    );

    // The same stack, boxed into the dynamic layer (what registries and Python see).
    let mut boxed = make()?.boxed();
    let (o, _) = boxed.reset(Some(7), None)?;
    println!(
        "boxed: {} observation of {} values",
        boxed.observation_space(),
        o.as_array().map_or(0, |a| a.len())
    );

    // Four copies stepped in parallel with Gymnasium's SAME_STEP autoreset.
    let envs = (0..4).map(|_| make()).collect::<Result<Vec<_>, _>>()?;
    let mut venv = ThreadVectorEnv::new(envs)?.with_autoreset_mode(AutoresetMode::SameStep);
    println!(
        "vector: {} envs on {} threads, observations {}",
        venv.num_envs(),
        venv.num_threads(),
        venv.observation_space()
    );
    venv.reset(100u64, None)?;
    let mut rng = gym_core::rng_from_seed(0);
    let start = std::time::Instant::now();
    let steps = 50;
    for _ in 0..steps {
        let actions = venv.action_space().sample(&mut rng);
        let s = venv.step(&actions)?;
        if s.truncations.iter().any(|&x| x) {
            println!(
                "some episode ended; final_obs present: {}",
                s.infos.mask("final_obs").is_some()
            );
        }
    }
    let secs = start.elapsed().as_secs_f64();
    println!(
        "{} env steps in {secs:.3}s ({:.0} steps/s)",
        steps * venv.num_envs(),
        (steps * venv.num_envs()) as f64 / secs
    );
    venv.close();
    Ok(())
}
