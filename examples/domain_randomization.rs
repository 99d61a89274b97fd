//! robosuite's `DomainRandomizationWrapper` on Lift: two resets, two randomized looks
//! (textures and colours, cameras, lights, dynamics), each saved as a PNG of the
//! `agentview` camera.
//!
//! Run with `cargo run --release -p examples --example domain_randomization -- [OUT_DIR]`
//! (default `target/domain_randomization`).

use gym_core::{Env, Wrapper};
use mujoco_rs::prelude::MjtObjBase;
use robosuite_env::wrappers::{
    DomainRandomizationArgs, DomainRandomizationWrapper, VisualizationSettings,
};
use std::path::{Path, PathBuf};

const SIZE: usize = 256;

/// Saves a frame (RGB, bottom row first, as MuJoCo draws it) as a PNG, top row first.
fn save_png(path: &Path, rgb: &[u8]) -> Result<(), Box<dyn std::error::Error>> {
    let rows: Vec<u8> = rgb.chunks(3 * SIZE).rev().flatten().copied().collect();
    let mut encoder = png::Encoder::new(std::fs::File::create(path)?, SIZE as u32, SIZE as u32);
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.write_header()?.write_image_data(&rows)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out: PathBuf = std::env::args()
        .nth(1)
        .map_or_else(|| "target/domain_randomization".into(), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let env = robosuite_env::make("Lift")?;
    let args = DomainRandomizationArgs {
        seed: Some(0),
        ..DomainRandomizationArgs::default()
    };
    // A refused argument gives the env back unchanged (`Refused::env`).
    let mut env = DomainRandomizationWrapper::new(env, args)?;
    let camera = env
        .inner()
        .sim()
        .model()
        .name_to_id(MjtObjBase::mjOBJ_CAMERA, "agentview")
        .ok_or("Lift has an agentview camera")?;
    for episode in 0..2 {
        let start = std::time::Instant::now();
        env.reset(Some(episode), None)?;
        let reset = start.elapsed();
        // Frames without the robots', grippers' and cube's sites (robosuite's look).
        env.inner_mut().visualize(VisualizationSettings::all(false));
        let frame = env
            .inner_mut()
            .render_camera(camera, SIZE, SIZE, false, false)?;
        let path = out.join(format!("lift_randomized_{episode}.png"));
        save_png(&path, &frame.rgb)?;
        let cube = robosuite_env::sim::body_id(env.inner().sim().model(), "cube_main")?;
        println!(
            "{}: cube mass {:.4} kg (reset and randomization {:.0} ms)",
            path.display(),
            env.inner().sim().model().body_mass()[cube],
            reset.as_secs_f64() * 1e3
        );
    }
    Ok(())
}
