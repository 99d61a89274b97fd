//! Env steps per second of Lift with camera observations (one 84×84 camera; two 256×256
//! cameras) and MuJoCo's bare renderer frames per second, on whatever EGL device opens
//! (Mesa's software device on a CPU-only machine), and writes PNGs of every default camera.
//!
//! ```text
//! cargo run --release -p tools --features render --bin camera_benchmark -- [--png DIR]
//! ```

use gym_core::{Env, Frame, RenderMode};
use ndarray::ArrayD;
use robosuite_env::cameras::CameraConfig;
use robosuite_env::{EnvConfig, make_with};
use std::time::Instant;

fn steps_per_second(cameras: CameraConfig, steps: usize) -> gym_core::Result<f64> {
    let mut env = make_with(
        "Lift",
        EnvConfig::default().with_seed(0).with_cameras(cameras),
    )?;
    env.reset(Some(0), None)?;
    let mut obs = env.observation();
    let mut info = gym_core::Info::new();
    let action = ArrayD::zeros(ndarray::IxDyn(&[env.action_dim()]));
    let start = Instant::now();
    for _ in 0..steps {
        if env.step_into(&action, &mut obs, &mut info)?.truncated {
            env.reset(None, None)?;
        }
    }
    Ok(steps as f64 / start.elapsed().as_secs_f64())
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let png_dir = args
        .iter()
        .position(|a| a == "--png")
        .and_then(|i| args.get(i + 1));
    let steps = 300;
    let none = steps_per_second(CameraConfig::default(), steps)?;
    let one = steps_per_second(CameraConfig::observe(["agentview"], 84, 84), steps)?;
    let two = steps_per_second(
        CameraConfig::observe(["agentview", "robot0_eye_in_hand"], 256, 256),
        steps,
    )?;
    println!("Lift env steps/s (zero actions, {steps} steps, one thread):");
    println!("  no cameras:                      {none:8.0}");
    println!("  agentview 84x84:                 {one:8.0}");
    println!("  agentview + eye_in_hand 256x256: {two:8.0}");
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
