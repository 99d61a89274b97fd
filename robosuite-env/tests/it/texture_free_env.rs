//! An env whose configuration never renders on its own is built on its scene without texture
//! images: it simulates bit for bit as the textured env, loads the images when asked
//! (texture randomisation), and draws the textured env's frames.

use crate::common::action;
use gym_core::{DictValue, Env, Error, Wrapper};
use ndarray::ArrayD;
use robosuite_env::wrappers::{DomainRandomizationArgs, DomainRandomizationWrapper};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};

/// `task` with a seed; with `offscreen`, robosuite's `has_offscreen_renderer=True`.
fn make(task: &str, offscreen: bool) -> RobosuiteEnv {
    let mut config = EnvConfig {
        seed: Some(3),
        ..EnvConfig::default()
    };
    config.cameras.has_offscreen_renderer = offscreen;
    if task.starts_with("TwoArm") {
        config.robots = vec!["Panda".into(), "Panda".into()];
    }
    make_with(task, config).unwrap()
}

/// An observation's values as bits, per key.
type ObsBits = Vec<(String, Vec<u64>)>;

fn bits(obs: &DictValue) -> ObsBits {
    obs.iter()
        .map(|(k, v)| {
            let values = v.as_array().map(|a| a.to_f64_vec()).unwrap_or_default();
            (k.clone(), values.iter().map(|x| x.to_bits()).collect())
        })
        .collect()
}

fn state_bits(env: &RobosuiteEnv) -> Vec<u64> {
    let d = env.sim().data();
    d.qpos()
        .iter()
        .chain(d.qvel())
        .map(|x| x.to_bits())
        .collect()
}

fn model_bytes(env: &RobosuiteEnv) -> Vec<u8> {
    let m = env.sim().model().ffi();
    // SAFETY: the buffer holds `nbuffer` bytes, alive and unwritten while borrowed.
    unsafe { std::slice::from_raw_parts(m.buffer.cast::<u8>(), m.nbuffer as usize) }.to_vec()
}

fn act(env: &RobosuiteEnv, t: usize) -> ArrayD<f64> {
    let n = env.action_space().low().len();
    let values: Vec<f64> = (0..n)
        .map(|i| (0.37 * (t + 1) as f64 + 1.3 * i as f64).sin())
        .collect();
    ArrayD::from_shape_vec(vec![n], values).unwrap()
}

/// Observations, qpos and qvel bits over a reset and 12 steps.
fn rollout(env: &mut RobosuiteEnv) -> Vec<(ObsBits, Vec<u64>)> {
    let (obs, _) = env.reset(Some(7), None).unwrap();
    let mut out = vec![(bits(&obs), state_bits(env))];
    for t in 0..12 {
        let a = act(env, t);
        let step = env.step(&a).unwrap();
        out.push((bits(&step.observation), state_bits(env)));
    }
    out
}

#[test]
fn never_rendering_envs_simulate_bit_for_bit_without_texture_images() {
    for task in ["Lift", "PickPlaceCan", "Wipe", "TwoArmLift"] {
        let mut bare = make(task, false);
        let mut full = make(task, true);
        assert!(!bare.textures_loaded(), "{task}");
        assert!(full.textures_loaded(), "{task}");
        let (b, f) = (bare.sim().model().ffi(), full.sim().model().ffi());
        assert_eq!(
            (b.ntex, b.nmat, b.ngeom),
            (f.ntex, f.nmat, f.ngeom),
            "{task}"
        );
        assert!(
            b.ntexdata * 100 < f.ntexdata,
            "{task}: {} vs {} texture bytes",
            b.ntexdata,
            f.ntexdata
        );
        // The scene text (robosuite's `get_xml`) is the textured one.
        assert_eq!(bare.source_xml(), full.source_xml(), "{task}");
        assert_eq!(rollout(&mut bare), rollout(&mut full), "{task}");
    }
}

#[test]
fn loading_textures_gives_the_textured_envs_model_and_keeps_the_state() {
    let mut bare = make("Lift", false);
    let mut full = make("Lift", true);
    let a = action([0.2, -0.1, 0.3, 0.0, 0.0, 0.1, -1.0]);
    for env in [&mut bare, &mut full] {
        env.reset(Some(11), None).unwrap();
        // an edit of the env's own model survives the load
        // SAFETY: values only, no size or address.
        unsafe { env.sim_mut().data_mut().model_mut() }.geom_rgba_mut()[0] = [0.1, 0.2, 0.3, 0.4];
        for _ in 0..4 {
            let _ = env.step(&a).unwrap();
        }
    }
    let before = state_bits(&bare);
    bare.load_textures().unwrap();
    assert!(bare.textures_loaded());
    assert!(bare.sim().shared_model().is_none(), "the env's own model");
    assert_eq!(state_bits(&bare), before);
    assert_eq!(model_bytes(&bare), model_bytes(&full));
    assert_eq!(bare.scene_xml().unwrap(), full.scene_xml().unwrap());
    bare.load_textures().unwrap();
    for _ in 0..4 {
        let (x, y) = (bare.step(&a).unwrap(), full.step(&a).unwrap());
        assert_eq!(bits(&x.observation), bits(&y.observation));
    }
    assert_eq!(state_bits(&bare), state_bits(&full));
    let mut closed = make("Lift", false);
    closed.close();
    assert!(matches!(closed.load_textures(), Err(Error::Closed)));
    assert!(!closed.textures_loaded());
}

#[test]
fn the_scene_xml_of_a_never_rendering_env_is_the_textured_envs() {
    let mut bare = make("Lift", false);
    let mut full = make("Lift", true);
    bare.reset(Some(5), None).unwrap();
    full.reset(Some(5), None).unwrap();
    assert_eq!(bare.scene_xml().unwrap(), full.scene_xml().unwrap());
    assert!(!bare.textures_loaded(), "reading the scene loads nothing");
}

#[test]
fn texture_randomisation_loads_the_images_first() {
    let args = DomainRandomizationArgs {
        seed: Some(4),
        randomize_camera: false,
        randomize_lighting: false,
        randomize_dynamics: false,
        ..DomainRandomizationArgs::default()
    };
    let mut wrapped = [false, true].map(|offscreen| {
        DomainRandomizationWrapper::new(make("Lift", offscreen), args.clone()).unwrap()
    });
    assert!(wrapped[0].inner().textures_loaded());
    for w in &mut wrapped {
        w.reset(Some(2), None).unwrap();
    }
    let tex = |w: &DomainRandomizationWrapper| w.inner().sim().model().tex_data().to_vec();
    assert_eq!(tex(&wrapped[0]), tex(&wrapped[1]));
    assert_ne!(
        tex(&wrapped[1]),
        make("Lift", true).sim().model().tex_data(),
        "the reset randomised the textures"
    );
}

#[cfg(feature = "render")]
#[test]
fn uploading_a_texture_needs_the_images() {
    let mut bare = make("Lift", false);
    assert!(matches!(bare.upload_texture(0), Err(Error::Unsupported(_))));
    bare.load_textures().unwrap();
    bare.upload_texture(0).unwrap();
}

#[cfg(feature = "render")]
#[test]
fn frames_of_a_never_rendering_env_equal_the_textured_envs() {
    use mujoco_rs::wrappers::mj_model::MjtObjBase;
    use robosuite_env::render::OffscreenRenderer;
    let mut bare = make("Lift", false);
    let mut full = make("Lift", true);
    bare.reset(Some(9), None).unwrap();
    full.reset(Some(9), None).unwrap();
    let cam = bare
        .sim()
        .model()
        .name_to_id(MjtObjBase::mjOBJ_CAMERA, "agentview")
        .unwrap();
    let b = bare.render_camera(cam, 64, 64, true, false).unwrap();
    let f = full.render_camera(cam, 64, 64, true, false).unwrap();
    assert_eq!(b.rgb, f.rgb);
    assert_eq!(b.depth, f.depth);
    assert!(!bare.textures_loaded(), "rendering keeps the env's model");
    // The images matter: the env's own model draws another frame.
    let mut own = OffscreenRenderer::new(bare.sim().model(), 64, 64).unwrap();
    let mut rgb = vec![0u8; 64 * 64 * 3];
    let mut request = [robosuite_env::render::Request {
        camera: cam.into(),
        width: 64,
        height: 64,
        out: robosuite_env::render::Outputs {
            rgb: Some(&mut rgb),
            ..Default::default()
        },
    }];
    own.render(bare.sim_mut().data_mut(), &mut request).unwrap();
    assert_ne!(rgb, f.rgb);
}
