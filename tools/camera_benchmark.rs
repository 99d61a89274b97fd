//! Env steps per second and process CPU time per step of Lift with camera observations
//! (one and two cameras, 84×84 and 256×256, `--depth`: with depth) at each render quality,
//! with each quality's mean absolute difference to robosuite's frames (the camera tests'
//! 64×64 fixture, or each `--fixture` file written by
//! `scripts/record_robosuite_cameras.py --size N`), on whatever EGL device opens (Mesa's
//! software device on a CPU-only machine); `--only TEXT` keeps the setups whose name
//! contains it; writes PNGs of every default camera.
//!
//! ```text
//! cargo run --release -p tools --features render --bin camera_benchmark -- \
//!     [--steps N] [--depth] [--only TEXT] [--fixture FILE]... [--png DIR]
//! cargo run --release -p tools --features render --bin camera_benchmark -- --contexts N
//! cargo run --release -p tools --features render --bin camera_benchmark -- --vector N[,N] [--steps N]
//! ```
//!
//! `--contexts N` prints instead the process CPU time per Lift env made with and without a
//! camera (the render context's cost), over `N` envs made one after another.
//!
//! `--vector`: a `ThreadVectorEnv` of N Lift envs (GymWrapper, Dict observations, one
//! thread per env) with agentview at 84×84 and 256×256, each env writing its observation
//! straight into the batch, and the same envs behind a wrapper that hides
//! `Env::writes_rows` (each image copied into the env's observation dict, the slot, then
//! the batch); env steps per second and process CPU ms per vector step, interleaved.

use gym_core::{Env, Frame, RenderMode};
use ndarray::ArrayD;
use robosuite_env::cameras::{CameraConfig, RenderQuality, Segmentation};
use robosuite_env::{EnvConfig, make_with};
use std::time::Instant;

/// CPU time of the whole process (Mesa's rasteriser threads included), seconds.
fn process_cpu() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// Env steps per second (wall clock) and process CPU milliseconds per step.
fn steps_per_second(cameras: CameraConfig, steps: usize) -> gym_core::Result<(f64, f64)> {
    let mut env = make_with(
        "Lift",
        EnvConfig::default().with_seed(0).with_cameras(cameras),
    )?;
    env.reset(Some(0), None)?;
    let mut obs = env.observation();
    let mut info = gym_core::Info::new();
    let action = ArrayD::zeros(ndarray::IxDyn(&[env.action_dim()]));
    // Two uncounted steps (shader compilation).
    for _ in 0..2 {
        let _ = env.step_into(&action, &mut obs, &mut info)?;
    }
    let start = Instant::now();
    let cpu = process_cpu();
    for _ in 0..steps {
        if env.step_into(&action, &mut obs, &mut info)?.truncated {
            env.reset(None, None)?;
        }
    }
    let cpu_ms = (process_cpu() - cpu) * 1e3 / steps as f64;
    Ok((steps as f64 / start.elapsed().as_secs_f64(), cpu_ms))
}

/// Process CPU milliseconds per Lift env made (and reset) with `cameras`, over `n` envs made
/// one after another after a first one (which also starts the driver), each dropped before
/// the next is made.
fn make_cost(cameras: &CameraConfig, n: usize) -> gym_core::Result<f64> {
    let mut split = [0.0; 3];
    let make = |split: &mut [f64; 3]| -> gym_core::Result<()> {
        let t0 = process_cpu();
        let mut env = make_with(
            "Lift",
            EnvConfig::default()
                .with_seed(0)
                .with_cameras(cameras.clone()),
        )?;
        let t1 = process_cpu();
        env.reset(Some(0), None)?;
        let t2 = process_cpu();
        env.reset(Some(0), None)?;
        let t3 = process_cpu();
        split[0] += t1 - t0;
        split[1] += t2 - t1;
        split[2] += t3 - t2;
        Ok(())
    };
    make(&mut split)?;
    split = [0.0; 3];
    let cpu = process_cpu();
    for _ in 0..n {
        make(&mut split)?;
    }
    let n = n.max(1) as f64;
    println!(
        "    make {:.1} ms, first reset {:.1} ms, second reset {:.1} ms",
        split[0] * 1e3 / n,
        split[1] * 1e3 / n,
        split[2] * 1e3 / n
    );
    Ok((process_cpu() - cpu) * 1e3 / n)
}

fn hex(s: &str) -> Vec<u8> {
    (0..s.len())
        .step_by(2)
        .filter_map(|i| u8::from_str_radix(s.get(i..i + 2)?, 16).ok())
        .collect()
}

/// Mean absolute difference (of 255) of agentview's and robot0_eye_in_hand's 64×64 frames
/// to robosuite's from the same state (the fixture of the camera tests).
fn difference_to_robosuite(
    quality: RenderQuality,
    path: &str,
    depth: bool,
) -> Result<(usize, Vec<f64>), Box<dyn std::error::Error>> {
    let fx: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let size = fx["size"].as_u64().unwrap_or(64) as usize;
    let floats = |key: &str| -> Vec<f64> {
        fx[key]
            .as_array()
            .map(|a| a.iter().filter_map(serde_json::Value::as_f64).collect())
            .unwrap_or_default()
    };
    let cameras = CameraConfig {
        camera_depths: vec![depth],
        camera_segmentations: if depth {
            vec![vec![Segmentation::Element]]
        } else {
            Vec::new()
        },
        render_quality: quality,
        ..CameraConfig::observe(["agentview", "robot0_eye_in_hand"], size, size)
    };
    let mut env = make_with(
        "Lift",
        EnvConfig::default().with_seed(0).with_cameras(cameras),
    )?;
    let (obs, _) = env.reset_to_state(&floats("cube_size"), &floats("state"))?;
    let mut out = Vec::new();
    for cam in ["agentview", "robot0_eye_in_hand"] {
        let theirs = hex(fx["frames"][cam]["image"].as_str().unwrap_or(""));
        let Some(gym_core::Value::Array(gym_core::ArrayValue::U8(ours))) =
            obs.get(&format!("{cam}_image"))
        else {
            return Err(format!("no {cam}_image").into());
        };
        let sum: f64 = ours
            .iter()
            .zip(&theirs)
            .map(|(a, b)| (f64::from(*a) - f64::from(*b)).abs())
            .sum();
        out.push(sum / theirs.len().max(1) as f64);
        if !depth {
            out.push(f64::NAN);
            continue;
        }
        let theirs: Vec<f32> = hex(fx["frames"][cam]["depth"].as_str().unwrap_or(""))
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        let Some(gym_core::Value::Array(gym_core::ArrayValue::F32(ours))) =
            obs.get(&format!("{cam}_depth"))
        else {
            return Err(format!("no {cam}_depth").into());
        };
        let sum: f64 = ours
            .iter()
            .zip(&theirs)
            .map(|(a, b)| f64::from((a - b).abs()))
            .sum();
        out.push(sum / theirs.len().max(1) as f64);
    }
    Ok((size, out))
}

fn write_png(path: &std::path::Path, frame: &ndarray::Array3<u8>) -> std::io::Result<()> {
    let (h, w, _) = frame.dim();
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = mujoco_rs::renderer::png::Encoder::new(file, w as u32, h as u32);
    enc.set_color(mujoco_rs::renderer::png::ColorType::Rgb);
    enc.set_depth(mujoco_rs::renderer::png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(frame.as_slice().unwrap_or(&[]))
        .map_err(std::io::Error::other)
}

/// An env whose observations reach a vector env through its own buffer (`step_into`):
/// it does not forward [`Env::writes_rows`].
struct ThroughBuffer<E>(E);

impl<E: Env> Env for ThroughBuffer<E> {
    type Obs = E::Obs;
    type Act = E::Act;
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;
    fn observation_space(&self) -> &E::ObsSpace {
        self.0.observation_space()
    }
    fn action_space(&self) -> &E::ActSpace {
        self.0.action_space()
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&gym_core::ResetOptions>,
    ) -> gym_core::Result<(E::Obs, gym_core::Info)> {
        self.0.reset(seed, options)
    }
    fn step(&mut self, action: &E::Act) -> gym_core::Result<gym_core::Step<E::Obs>> {
        self.0.step(action)
    }
    fn step_into(
        &mut self,
        action: &E::Act,
        observation: &mut E::Obs,
        info: &mut gym_core::Info,
    ) -> gym_core::Result<gym_core::Transition> {
        self.0.step_into(action, observation, info)
    }
}

/// Env steps per second and process CPU ms per vector step of `vec` with zero actions.
fn vector_rate<V: adapters::VectorEnv>(
    vec: &mut V,
    actions: &adapters::BatchOf<V::ActSpace>,
    steps: usize,
) -> gym_core::Result<(f64, f64)> {
    vec.reset(0u64, None)?;
    for _ in 0..2 {
        let _ = vec.step(actions)?;
    }
    let start = Instant::now();
    let cpu = process_cpu();
    for _ in 0..steps {
        let _ = vec.step(actions)?;
    }
    let cpu_ms = (process_cpu() - cpu) * 1e3 / steps as f64;
    let rate = (steps * vec.num_envs()) as f64 / start.elapsed().as_secs_f64();
    Ok((rate, cpu_ms))
}

/// `--vector`: rows against the env's own buffer, interleaved (see the module docs).
fn vector_benchmark(counts: &[usize], steps: usize) -> Result<(), Box<dyn std::error::Error>> {
    use adapters::{BatchSpace, GymWrapper, ThreadVectorEnv, VectorEnv};
    println!("ThreadVectorEnv of Lift (agentview), zero actions, {steps} vector steps:");
    println!("  env steps/s (wall) and process CPU ms per vector step");
    for &size in &[84, 256] {
        for &n in counts {
            let make = || -> gym_core::Result<_> {
                let config = EnvConfig::default()
                    .with_seed(0)
                    .with_cameras(CameraConfig::observe(["agentview"], size, size));
                GymWrapper::new(make_with("Lift", config)?, None, false)
            };
            let mut rows = ThreadVectorEnv::new((0..n).map(|_| make()).collect::<Result<_, _>>()?)?;
            let mut buffer = ThreadVectorEnv::new(
                (0..n)
                    .map(|_| make().map(ThroughBuffer))
                    .collect::<Result<_, _>>()?,
            )?;
            let actions = rows.single_action_space().create_empty_batch(n);
            let (mut r_rate, mut r_cpu, mut b_rate, mut b_cpu) = (0.0, 0.0, 0.0, 0.0);
            for _ in 0..2 {
                let (rate, cpu) = vector_rate(&mut buffer, &actions, steps / 2)?;
                b_rate += rate / 2.0;
                b_cpu += cpu / 2.0;
                let (rate, cpu) = vector_rate(&mut rows, &actions, steps / 2)?;
                r_rate += rate / 2.0;
                r_cpu += cpu / 2.0;
            }
            println!(
                "  {n} envs {size}x{size}: rows {r_rate:6.1} steps/s {r_cpu:7.2} ms | \
                 through the env's buffer {b_rate:6.1} steps/s {b_cpu:7.2} ms"
            );
        }
    }
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let vector = args
        .iter()
        .position(|a| a == "--vector")
        .and_then(|i| args.get(i + 1));
    if let Some(counts) = vector {
        let counts: Vec<usize> = counts.split(',').filter_map(|c| c.parse().ok()).collect();
        let steps = args
            .iter()
            .position(|a| a == "--steps")
            .and_then(|i| args.get(i + 1))
            .and_then(|s| s.parse().ok())
            .unwrap_or(40);
        return vector_benchmark(&counts, steps);
    }
    let png_dir = args
        .iter()
        .position(|a| a == "--png")
        .and_then(|i| args.get(i + 1));
    let steps = args
        .iter()
        .position(|a| a == "--steps")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let default_fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../robosuite-env/tests/fixtures/robosuite/lift_cameras.json"
    );
    let mut fixtures: Vec<&str> = args
        .iter()
        .enumerate()
        .filter(|(_, a)| *a == "--fixture")
        .filter_map(|(i, _)| args.get(i + 1).map(String::as_str))
        .collect();
    if fixtures.is_empty() {
        fixtures.push(default_fixture);
    }
    let only: Option<&String> = args
        .iter()
        .position(|a| a == "--only")
        .and_then(|i| args.get(i + 1));
    let depth = args.iter().any(|a| a == "--depth");
    if let Some(n) = args
        .iter()
        .position(|a| a == "--contexts")
        .and_then(|i| args.get(i + 1))
        .and_then(|s| s.parse::<usize>().ok())
    {
        let plain = make_cost(&CameraConfig::default(), n)?;
        println!("Lift envs made one after another, process CPU ms per env ({n} envs):");
        println!("  no cameras:                {plain:8.1} ms");
        for quality in [RenderQuality::Robosuite, RenderQuality::Fast] {
            let cameras = CameraConfig {
                render_quality: quality,
                ..CameraConfig::observe(["agentview"], 84, 84)
            };
            let with = make_cost(&cameras, n)?;
            println!(
                "  agentview 84x84, {:9}: {with:8.1} ms (render context {:.1} ms)",
                quality.as_str(),
                with - plain
            );
        }
        return Ok(());
    }
    let (none, none_cpu) = steps_per_second(CameraConfig::default(), steps)?;
    println!(
        "Lift, zero actions, {steps} steps, one thread: env steps/s (wall) and process CPU ms per step"
    );
    println!("  no cameras: {none:8.0} steps/s {none_cpu:8.2} ms");
    let setups: [(&str, &[&str], usize); 4] = [
        ("agentview 84x84", &["agentview"], 84),
        ("agentview 256x256", &["agentview"], 256),
        (
            "agentview + eye_in_hand 84x84",
            &["agentview", "robot0_eye_in_hand"],
            84,
        ),
        (
            "agentview + eye_in_hand 256x256",
            &["agentview", "robot0_eye_in_hand"],
            256,
        ),
    ];
    for quality in [RenderQuality::Robosuite, RenderQuality::Fast] {
        for path in &fixtures {
            let (size, rgb) = difference_to_robosuite(quality, path, false)?;
            let (_, diff) = difference_to_robosuite(quality, path, true)?;
            println!(
                "render_quality={} {size}x{size}: mean |diff| to robosuite's frames (of 255): RGB agentview {:.2}, robot0_eye_in_hand {:.2}; with depth {:.2}, {:.2}, depth {:.1e}, {:.1e}",
                quality.as_str(),
                rgb[0],
                rgb[2],
                diff[0],
                diff[2],
                diff[1],
                diff[3]
            );
        }
        for (name, cams, size) in setups {
            if only.is_some_and(|o| !name.contains(o.as_str())) {
                continue;
            }
            let cameras = CameraConfig {
                render_quality: quality,
                camera_depths: vec![depth],
                ..CameraConfig::observe(cams.iter().copied(), size, size)
            };
            let (rate, cpu) = steps_per_second(cameras, steps)?;
            println!("  {name:32} {rate:8.1} steps/s {cpu:8.2} ms");
        }
    }
    if let Some(dir) = png_dir {
        std::fs::create_dir_all(dir)?;
        for cam in [
            "frontview",
            "agentview",
            "birdview",
            "sideview",
            "robot0_robotview",
            "robot0_eye_in_hand",
        ] {
            let mut env = make_with(
                "Lift",
                EnvConfig::default()
                    .with_seed(0)
                    .with_cameras(CameraConfig {
                        render_mode: Some(RenderMode::RgbArray),
                        render_quality: RenderQuality::Robosuite,
                        render_camera: cam.into(),
                        ..CameraConfig::default()
                    }),
            )?;
            env.reset(Some(0), None)?;
            if let Some(Frame::Rgb(frame)) = env.render()? {
                let path = std::path::Path::new(dir).join(format!("lift_{cam}.png"));
                write_png(&path, &frame)?;
                println!("wrote {}", path.display());
            }
        }
    }
    Ok(())
}
