//! A rollout in MuJoCo's viewer window: the Rust counterpart of robosuite's
//! `has_renderer=True` quick start.
//!
//! ```text
//! cargo run --release -p examples --features viewer --example view -- Lift --robot Sawyer --policy scripted
//! ```
//!
//! Arguments: the task (default `Lift`), `--robot NAME` (default: the task's Pandas),
//! `--policy scripted | random | zero` (default `scripted` on Lift, else `random`; the
//! scripted grasp is [`examples::LiftScript`]), `--seed N`, `--frames N` (stop after N steps;
//! default: until the window is closed). Episodes restart at their end; the rollout runs at
//! the control frequency (real time). The window is mujoco-rs's viewer (`F1`: its keys;
//! `[` / `]` cycle the cameras; the mouse moves the free camera). It shows a copy of the
//! env's state taken after every step, so dragging bodies in the window does not reach the
//! env. Without a display the program says so (`DISPLAY` / `WAYLAND_DISPLAY`) and exits
//! with status 2.

use examples::LiftScript;
use gym_core::{Env, Space, rng_from_seed};
use mujoco_rs::prelude::MjData;
use mujoco_rs::viewer::MjViewer;
use mujoco_rs::wrappers::mj_model::MjModel;
use ndarray::{ArrayD, IxDyn};
use robosuite_env::EnvConfig;
use std::process::ExitCode;
use std::time::{Duration, Instant};

/// MuJoCo's full physics state (`mjSTATE_FULLPHYSICS`): what the window copies each step.
const FULL_PHYSICS: u32 = mujoco_rs::mujoco_c::mjtState::mjSTATE_FULLPHYSICS as u32;

#[derive(Debug)]
struct Args {
    task: String,
    robot: Option<String>,
    policy: String,
    seed: u64,
    frames: Option<u64>,
}

const USAGE: &str =
    "usage: view [TASK] [--robot NAME] [--policy scripted|random|zero] [--seed N] [--frames N]";

fn parse_args(mut it: impl Iterator<Item = String>) -> Result<Args, String> {
    let (mut task, mut robot, mut policy, mut seed, mut frames) = (None, None, None, 0, None);
    while let Some(arg) = it.next() {
        let mut value = |name: &str| it.next().ok_or(format!("{name} needs a value"));
        match arg.as_str() {
            "--robot" => robot = Some(value("--robot")?),
            "--policy" => policy = Some(value("--policy")?),
            "--seed" => {
                seed = value("--seed")?
                    .parse()
                    .map_err(|e| format!("--seed: {e}"))?
            }
            "--frames" => {
                frames = Some(
                    value("--frames")?
                        .parse()
                        .map_err(|e| format!("--frames: {e}"))?,
                )
            }
            "-h" | "--help" => return Err(USAGE.to_owned()),
            flag if flag.starts_with('-') => return Err(format!("unknown option {flag}")),
            name if task.is_none() => task = Some(name.to_owned()),
            extra => return Err(format!("unexpected argument {extra}")),
        }
    }
    let task = task.unwrap_or_else(|| "Lift".to_owned());
    let policy =
        policy.unwrap_or_else(|| if task == "Lift" { "scripted" } else { "random" }.into());
    if !["scripted", "random", "zero"].contains(&policy.as_str()) {
        return Err(format!("--policy {policy}: valid: scripted, random, zero"));
    }
    if policy == "scripted" && task != "Lift" {
        return Err(format!(
            "--policy scripted grasps Lift's cube; use random or zero on {task}"
        ));
    }
    Ok(Args {
        task,
        robot,
        policy,
        seed,
        frames,
    })
}

/// `Err` with what to do when no window can open here (`var`: the environment).
fn check_display(var: impl Fn(&str) -> Option<std::ffi::OsString>) -> Result<(), String> {
    let set = |v: &str| var(v).is_some_and(|s| !s.is_empty());
    if set("DISPLAY") || set("WAYLAND_DISPLAY") {
        return Ok(());
    }
    Err(
        "no display: neither DISPLAY nor WAYLAND_DISPLAY is set. Run it in a desktop session, \
         over `ssh -X`, or under a virtual display (`xvfb-run -a cargo run ...`); headless \
         machines draw frames offscreen instead (render_mode RgbArray, MUJOCO_GL=egl)"
            .to_owned(),
    )
}

fn run(args: &Args) -> Result<(), String> {
    let mut config = EnvConfig::default().with_seed(args.seed);
    if let Some(robot) = &args.robot {
        config = config.with_robots([robot.clone()]);
    }
    let mut env = robosuite_env::make_with(&args.task, config).map_err(|e| e.to_string())?;
    check_display(|v| std::env::var_os(v))?;
    // The window draws its own copy of the model and state (the env keeps its own).
    let model: MjModel = env.sim().model().clone();
    let mut shown = MjData::new(&model);
    let mut viewer = MjViewer::builder()
        .window_name(format!("robosuite-rs: {} ({})", args.task, args.policy))
        .build_passive(&model)
        .map_err(|e| {
            format!(
                "the viewer window did not open: {e} (DISPLAY={:?})",
                std::env::var("DISPLAY").ok()
            )
        })?;
    let period = Duration::from_secs_f64(1.0 / env.config().control_freq);
    let mut rng = rng_from_seed(args.seed);
    let dim = env
        .action_space()
        .shape()
        .unwrap_or(&[])
        .iter()
        .product::<usize>();
    let (mut obs, _) = env
        .reset(Some(args.seed), None)
        .map_err(|e| e.to_string())?;
    let mut script = LiftScript::new(&obs);
    let (mut steps, mut episodes, mut next) = (0u64, 1u64, Instant::now());
    while viewer.running() && args.frames.is_none_or(|n| steps < n) {
        let action = match args.policy.as_str() {
            "scripted" => script.act(&obs),
            "random" => env.action_space().sample(&mut rng),
            _ => ArrayD::zeros(IxDyn(&[dim])),
        };
        let step = env.step(&action).map_err(|e| e.to_string())?;
        steps += 1;
        obs = step.observation;
        if step.terminated || step.truncated {
            println!(
                "episode {episodes}: {steps} steps so far, success {:?}",
                step.info.get_bool("success")
            );
            episodes += 1;
            obs = env.reset(None, None).map_err(|e| e.to_string())?.0;
            script = LiftScript::new(&obs);
        }
        shown
            .set_state(&env.sim().data().state(FULL_PHYSICS), FULL_PHYSICS)
            .map_err(|e| e.to_string())?;
        shown.forward();
        viewer.sync_data(&mut shown);
        viewer
            .render()
            .map_err(|e| format!("the viewer failed: {e}"))?;
        next += period;
        if let Some(wait) = next.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        } else {
            next = Instant::now();
        }
    }
    println!("{steps} steps in {episodes} episode(s) shown");
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse_args(std::env::args().skip(1)) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("view: {e}\n{USAGE}");
            return ExitCode::from(2);
        }
    };
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("view: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(line: &str) -> Result<Args, String> {
        parse_args(line.split_whitespace().map(str::to_owned))
    }

    #[test]
    fn arguments() {
        let a = args("Lift --robot Sawyer --policy scripted --frames 5 --seed 3").unwrap();
        assert_eq!(
            (a.task.as_str(), a.robot.as_deref()),
            ("Lift", Some("Sawyer"))
        );
        assert_eq!(
            (a.policy.as_str(), a.frames, a.seed),
            ("scripted", Some(5), 3)
        );
        let d = args("").unwrap();
        assert_eq!(
            (d.task.as_str(), d.policy.as_str(), d.frames),
            ("Lift", "scripted", None)
        );
        assert_eq!(args("Door").unwrap().policy, "random");
        assert!(args("Door --policy scripted").unwrap_err().contains("Lift"));
        assert!(args("--policy greedy").unwrap_err().contains("valid"));
        assert!(args("--frames x").unwrap_err().contains("--frames"));
        assert!(args("--robot").unwrap_err().contains("needs a value"));
        assert!(args("--fast").unwrap_err().contains("unknown option"));
    }

    #[test]
    fn no_display_is_a_clear_error() {
        let none = check_display(|_| None).unwrap_err();
        assert!(
            none.contains("DISPLAY") && none.contains("WAYLAND_DISPLAY"),
            "{none}"
        );
        assert!(none.contains("xvfb-run"), "{none}");
        assert!(check_display(|v| (v == "DISPLAY").then(|| ":0".into())).is_ok());
        assert!(check_display(|v| (v == "WAYLAND_DISPLAY").then(|| "wayland-0".into())).is_ok());
        assert!(check_display(|v| (v == "DISPLAY").then(|| "".into())).is_err());
    }
}
