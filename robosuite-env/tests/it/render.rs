//! MuJoCo's offscreen renderer on a headless EGL context (Mesa's software device on a
//! CPU-only machine): frames of Lift's cameras.
#![cfg(feature = "render")]

use mujoco_rs::prelude::MjtObjBase;
use robosuite_env::models::scene::compile_cached;
use robosuite_env::render::{OffscreenRenderer, Outputs, Request, real_depth};
use robosuite_env::sim::Sim;
use robosuite_env::{EnvConfig, scene_xml};

fn lift_sim() -> Sim {
    let xml = scene_xml("Lift", &EnvConfig::default()).unwrap();
    let mut sim = Sim::new(compile_cached(&xml).unwrap()).unwrap();
    sim.forward().unwrap();
    sim
}

struct Frame {
    rgb: Vec<u8>,
    depth: Vec<f32>,
    seg: Vec<i32>,
}

fn draw(
    renderer: &mut OffscreenRenderer,
    sim: &mut Sim,
    camera: &str,
    w: usize,
    h: usize,
) -> Frame {
    let id = sim
        .model()
        .name_to_id(MjtObjBase::mjOBJ_CAMERA, camera)
        .expect("camera exists");
    let mut f = Frame {
        rgb: vec![0; w * h * 3],
        depth: vec![0.0; w * h],
        seg: vec![0; w * h],
    };
    let mut requests = [Request {
        camera: id.into(),
        width: w,
        height: h,
        out: Outputs {
            rgb: Some(&mut f.rgb),
            depth: Some(&mut f.depth),
            segmentation: Some(&mut f.seg),
            segmentation_type: None,
        },
    }];
    renderer.render(sim.data_mut(), &mut requests).unwrap();
    f
}

#[test]
fn renders_lift_cameras_headless_deterministically_and_on_other_threads() {
    let mut sim = lift_sim();
    let mut renderer = OffscreenRenderer::new(sim.model(), 128, 128).unwrap();
    let f = draw(&mut renderer, &mut sim, "agentview", 96, 64);
    if let Ok(path) = std::env::var("RENDER_TEST_DUMP") {
        std::fs::write(path, &f.rgb).unwrap();
    }
    // A real picture: many distinct colours, depth strictly inside the clip range.
    let mut colours: Vec<&[u8]> = f.rgb.chunks(3).collect();
    colours.sort();
    colours.dedup();
    assert!(colours.len() > 100, "only {} colours", colours.len());
    assert!(f.depth.iter().all(|d| *d > 0.0 && *d < 1.0));
    let metres: Vec<f64> = f
        .depth
        .iter()
        .map(|d| real_depth(sim.model(), *d))
        .collect();
    let nearest = metres.iter().cloned().fold(f64::INFINITY, f64::min);
    // agentview sits about 0.5 m in front of the table's edge and 1.35 m high.
    assert!(nearest > 0.3 && nearest < 3.0, "nearest {nearest} m");
    // Segmentation names geoms: the table top and the cube are in view.
    let table = sim
        .model()
        .name_to_id(MjtObjBase::mjOBJ_GEOM, "table_visual")
        .unwrap() as i32;
    assert!(f.seg.contains(&table));
    let names: Vec<String> = f
        .seg
        .iter()
        .filter(|id| **id >= 0)
        .map(|id| {
            sim.model()
                .id_to_name(MjtObjBase::mjOBJ_GEOM, *id as usize)
                .unwrap_or("")
                .to_owned()
        })
        .collect();
    // robosuite's defaults: visual geoms (group 1) drawn, collision geoms (group 0) hidden.
    assert!(names.iter().any(|n| n == "fixed_mount0_pedestal_vis"));
    assert!(!names.iter().any(|n| n.ends_with("_col")), "{names:?}");

    // The same state gives the same pixels, also from another thread.
    let again = draw(&mut renderer, &mut sim, "agentview", 96, 64);
    assert_eq!(again.rgb, f.rgb);
    assert_eq!(again.depth, f.depth);
    let (rgb, sim, renderer) = std::thread::spawn(move || {
        let f = draw(&mut renderer, &mut sim, "agentview", 96, 64);
        (f.rgb, sim, renderer)
    })
    .join()
    .unwrap();
    assert_eq!(rgb, f.rgb);
    drop((sim, renderer));
}

#[test]
fn refuses_bad_requests_without_drawing() {
    let mut sim = lift_sim();
    let mut renderer = OffscreenRenderer::new(sim.model(), 32, 32).unwrap();
    let mut rgb = vec![7u8; 64 * 64 * 3];
    let mut too_big = [Request {
        camera: 0.into(),
        width: 64,
        height: 64,
        out: Outputs {
            rgb: Some(&mut rgb),
            ..Outputs::default()
        },
    }];
    assert!(renderer.render(sim.data_mut(), &mut too_big).is_err());
    assert!(rgb.iter().all(|v| *v == 7));
    let mut bad_camera = [Request {
        camera: 10_000.into(),
        width: 8,
        height: 8,
        out: Outputs::default(),
    }];
    assert!(renderer.render(sim.data_mut(), &mut bad_camera).is_err());
    assert!(OffscreenRenderer::new(sim.model(), 0, 10).is_err());
    assert!(OffscreenRenderer::new(sim.model(), 10, 100_000).is_err());
}

#[test]
fn a_changed_texture_is_drawn_once_uploaded() {
    let mut sim = lift_sim();
    let mut renderer = OffscreenRenderer::new(sim.model(), 64, 64).unwrap();
    let before = draw(&mut renderer, &mut sim, "agentview", 64, 64).rgb;
    // The same scene with every texture black, drawn by the renderer made for the first.
    let xml = scene_xml("Lift", &EnvConfig::default()).unwrap();
    let mut model = compile_cached(&xml).unwrap();
    model.tex_data_mut().fill(0);
    let ntex = model.ffi().ntex as usize;
    assert!(ntex > 0);
    let mut dark = Sim::new(model).unwrap();
    dark.forward().unwrap();
    let stale = draw(&mut renderer, &mut dark, "agentview", 64, 64).rgb;
    assert_eq!(stale, before, "the renderer keeps the textures it uploaded");
    for t in 0..ntex {
        renderer.upload_texture(dark.model(), t).unwrap();
    }
    let after = draw(&mut renderer, &mut dark, "agentview", 64, 64).rgb;
    let mean = |v: &[u8]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
    assert!(
        mean(&after) < mean(&before) - 10.0,
        "black textures darken the frame: {} -> {}",
        mean(&before),
        mean(&after)
    );
    let err = renderer.upload_texture(dark.model(), ntex).unwrap_err();
    assert!(
        matches!(err, gym_core::Error::InvalidArgument { .. }),
        "{err}"
    );
}
