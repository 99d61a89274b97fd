//! robosuite's `VisualizationWrapper`, `env.visualize` and `DomainRandomizationWrapper` in
//! Rust, against what robosuite 1.5.2 does (the fixture the Python tests use,
//! `python/tests/fixtures/robosuite_utils/visualization.json`, recorded by
//! `scripts/record_visualization.py`).
#![cfg(feature = "render")]

use crate::common::zero;
use gym_core::{Env, Error, Wrapper};
use mujoco_rs::prelude::MjtObjBase;
use robosuite_env::modders::{CameraArgs, DynamicsArgs, LightingArgs};
use robosuite_env::sim::{body_id, site_id};
use robosuite_env::wrappers::{
    DomainRandomizationArgs, DomainRandomizationWrapper, IndicatorConfig, VisualizationSettings,
    VisualizationWrapper,
};
use robosuite_env::{EnvConfig, RobosuiteEnv, make_with};
use serde_json::Value;
use std::io::Read;

fn fixture() -> Value {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../python/tests/fixtures/robosuite_utils/visualization.json"
    );
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn make(task: &str) -> RobosuiteEnv {
    let mut config = EnvConfig {
        seed: Some(0),
        ..EnvConfig::default()
    };
    if task.starts_with("TwoArm") {
        config.robots = vec!["Panda".into(), "Panda".into()];
    }
    make_with(task, config).unwrap()
}

fn indicators() -> Vec<IndicatorConfig> {
    let mut marker = IndicatorConfig::new("marker");
    marker.site_type = Some("box".into());
    marker.size = vec![0.02, 0.02, 0.02];
    marker.rgba = [0.0, 0.0, 1.0, 1.0];
    marker.pos = [0.1, -0.1, 1.0];
    vec![IndicatorConfig::default_indicator(0), marker]
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn site_rgba(env: &RobosuiteEnv, name: &str) -> [f32; 4] {
    let m = env.sim().model();
    m.site_rgba()[site_id(m, name).unwrap()]
}

fn settings(env: bool, robots: bool, grippers: bool) -> VisualizationSettings {
    VisualizationSettings {
        env,
        robots,
        grippers,
    }
}

/// The model's whole buffer.
fn model_bytes(env: &RobosuiteEnv) -> Vec<u8> {
    let m = env.sim().model().ffi();
    // SAFETY: the buffer holds `nbuffer` bytes, alive and unwritten while borrowed.
    unsafe { std::slice::from_raw_parts(m.buffer.cast::<u8>(), m.nbuffer as usize) }.to_vec()
}

const SIZE: usize = 64;

fn frame(env: &mut RobosuiteEnv, camera: &str) -> Vec<u8> {
    let id = env
        .sim()
        .model()
        .name_to_id(MjtObjBase::mjOBJ_CAMERA, camera)
        .unwrap();
    env.render_camera(id, SIZE, SIZE, false, false).unwrap().rgb
}

fn base64(text: &str) -> Vec<u8> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let digits: Vec<u8> = text.bytes().filter(|&c| c != b'=').map(value).collect();
    digits
        .chunks(4)
        .flat_map(|c| {
            let n = c
                .iter()
                .enumerate()
                .fold(0u32, |n, (i, &d)| n | (u32::from(d) << (18 - 6 * i)));
            let bytes = [(n >> 16) as u8, (n >> 8) as u8, n as u8];
            bytes[..c.len() - 1].to_vec()
        })
        .collect()
}

fn decode_frame(text: &str) -> Vec<u8> {
    let mut out = Vec::new();
    flate2::read::ZlibDecoder::new(&base64(text)[..])
        .read_to_end(&mut out)
        .unwrap();
    assert_eq!(out.len(), SIZE * SIZE * 3);
    out
}

/// Pixels where two frames differ by more than 40 in a channel: count and centroid.
fn mask(a: &[u8], b: &[u8]) -> (Vec<bool>, f64, [f64; 2]) {
    let m: Vec<bool> = a
        .chunks(3)
        .zip(b.chunks(3))
        .map(|(p, q)| (0..3).any(|k| (i32::from(p[k]) - i32::from(q[k])).abs() > 40))
        .collect();
    let (mut n, mut r, mut c) = (0.0, 0.0, 0.0);
    for (i, _) in m.iter().enumerate().filter(|(_, on)| **on) {
        n += 1.0;
        r += (i / SIZE) as f64;
        c += (i % SIZE) as f64;
    }
    (m, n, [r / n.max(1.0), c / n.max(1.0)])
}

// --- VisualizationWrapper and visualize ------------------------------------------------

#[test]
fn sites_indicators_and_visualize_as_robosuites() {
    let data = fixture();
    for task in [
        "Lift",
        "TwoArmLift",
        "Stack",
        "Door",
        "NutAssemblySquare",
        "PickPlaceCan",
    ] {
        let reference = &data["tasks"][task];
        let mut env = VisualizationWrapper::new(make(task), indicators()).unwrap();
        assert_eq!(
            env.get_visualization_settings().to_vec(),
            reference["settings"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_str().unwrap())
                .collect::<Vec<_>>()
        );
        assert_eq!(env.get_indicator_names(), ["indicator0", "marker"]);
        for (name, want) in reference["indicators"].as_object().unwrap() {
            let m = env.inner().sim().model();
            let body = body_id(m, &format!("{name}_body")).unwrap();
            assert_eq!(
                m.body_pos()[body].to_vec(),
                floats(&want["body_pos"]),
                "{task} {name}"
            );
            let site = site_id(m, name).unwrap();
            assert_eq!(
                m.site_type()[site] as i64,
                want["site_type"].as_i64().unwrap()
            );
            for (ours, theirs) in m.site_size()[site].iter().zip(floats(&want["site_size"])) {
                assert!((ours - theirs).abs() < 1e-7, "{task} {name} size");
            }
        }
        env.reset(Some(0), None).unwrap();
        for (name, rgba) in reference["after_reset"].as_object().unwrap() {
            let theirs = floats(rgba)[3];
            let ours = f64::from(site_rgba(env.inner(), name)[3]);
            let sign = |v: f64| if v == 0.0 { 0.0 } else { v.signum() };
            assert_eq!(sign(ours), sign(theirs), "{task} after reset: {name}");
        }
        let inner = env.inner_mut();
        inner.set_state(&floats(&reference["state"])).unwrap();
        inner.sim_mut().forward().unwrap();
        for (vis, want) in [
            settings(true, true, true),
            settings(true, false, true),
            settings(false, false, false),
            settings(false, true, true),
        ]
        .into_iter()
        .zip(reference["sequence"].as_array().unwrap())
        {
            inner.visualize(vis);
            for (name, rgba) in want.as_object().unwrap() {
                let ours = site_rgba(inner, name);
                for (o, t) in ours.iter().zip(floats(rgba)) {
                    assert!(
                        (f64::from(*o) - t).abs() < 2e-6,
                        "{task} {vis:?} {name}: ours {ours:?}, robosuite {rgba}"
                    );
                }
            }
        }
    }
}

#[test]
fn frames_show_indicators_and_sites_where_robosuites_do() {
    let data = fixture();
    let reference = &data["tasks"]["Lift"];
    let far: [f64; 3] = floats(&reference["far"]).try_into().unwrap();
    let at: [f64; 3] = floats(&reference["indicator_pos"]).try_into().unwrap();
    let mut env = VisualizationWrapper::new(make("Lift"), indicators()).unwrap();
    env.inner_mut()
        .set_state(&floats(&reference["state"]))
        .unwrap();
    env.set_indicator_pos("marker", far).unwrap();
    let cameras: Vec<String> = data["cameras"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap().to_owned())
        .collect();
    let mut ours = std::collections::HashMap::new();
    for (label, vis, pos) in [
        ("hidden", VisualizationSettings::all(false), far),
        ("indicator", VisualizationSettings::all(false), at),
        ("shown", VisualizationSettings::all(true), far),
    ] {
        env.inner_mut().visualize(vis);
        env.set_indicator_pos("indicator0", pos).unwrap();
        env.inner_mut().sim_mut().forward().unwrap();
        for c in &cameras {
            ours.insert((label, c.clone()), frame(env.inner_mut(), c));
        }
    }
    for c in &cameras {
        let theirs = |label: &str| decode_frame(reference["frames"][label][c].as_str().unwrap());
        for label in ["indicator", "shown"] {
            let (m_ours, n_ours, c_ours) =
                mask(&ours[&(label, c.clone())], &ours[&("hidden", c.clone())]);
            let (m_theirs, n_theirs, c_theirs) = mask(&theirs(label), &theirs("hidden"));
            let at = format!(
                "{c} {label}: ours {n_ours} px at {c_ours:?}, robosuite {n_theirs} px at {c_theirs:?}"
            );
            assert!(n_ours >= 3.0 && n_theirs >= 3.0, "{at}");
            assert!((0.6..=1.6).contains(&(n_ours / n_theirs)), "{at}");
            let d = ((c_ours[0] - c_theirs[0]).powi(2) + (c_ours[1] - c_theirs[1]).powi(2)).sqrt();
            assert!(d <= 1.5, "{at}");
            let inter = m_ours
                .iter()
                .zip(&m_theirs)
                .filter(|(a, b)| **a && **b)
                .count();
            let union = m_ours
                .iter()
                .zip(&m_theirs)
                .filter(|(a, b)| **a || **b)
                .count();
            assert!(
                inter as f64 / union as f64 >= 0.5,
                "{at}: IoU {inter}/{union}"
            );
        }
    }
}

#[test]
fn settings_follow_steps_and_resets() {
    let mut env = VisualizationWrapper::new(make("Lift"), Vec::new()).unwrap();
    assert!(env.get_indicator_names().is_empty());
    env.reset(Some(0), None).unwrap();
    let (robot, grip, cube) = (
        "robot0_right_center",
        "gripper0_right_grip_site",
        "cube_default_site",
    );
    assert!(site_rgba(env.inner(), robot)[3] > 0.0);
    env.set_visualization_setting("robots", false).unwrap();
    let _ = env.step(&zero()).unwrap();
    assert!(site_rgba(env.inner(), robot)[3] < 0.0);
    assert!(site_rgba(env.inner(), grip)[3] > 0.0);
    // A plain reset of the env hides every site again, as robosuite's reset does.
    env.inner_mut().reset(None, None).unwrap();
    for name in [robot, grip, cube] {
        assert!(site_rgba(env.inner(), name)[3] < 0.0, "{name}");
    }
    env.reset(None, None).unwrap();
    assert!(site_rgba(env.inner(), grip)[3] > 0.0);
    assert!(site_rgba(env.inner(), robot)[3] < 0.0);
    let err = env.set_visualization_setting("walls", true).unwrap_err();
    assert!(matches!(err, Error::InvalidArgument { .. }), "{err}");
    // The grip site is coloured by its distance to the cube: red far away.
    let rgba = site_rgba(env.inner(), grip);
    assert!(rgba[0] > 0.9 && rgba[1] < 0.1, "{rgba:?}");
}

#[test]
fn bad_indicator_configs_leave_the_env_unchanged() {
    let named = |name: &str| IndicatorConfig::new(name);
    let cases: Vec<(Vec<IndicatorConfig>, &str)> = vec![
        (vec![named("")], "Name must be specified"),
        (
            vec![IndicatorConfig {
                site_type: Some("cone".into()),
                ..named("a")
            }],
            "type must be one of",
        ),
        (
            vec![IndicatorConfig {
                size: vec![f64::NAN],
                ..named("a")
            }],
            "finite",
        ),
        (
            vec![IndicatorConfig {
                size: vec![-0.1],
                ..named("a")
            }],
            "negative",
        ),
        (
            vec![IndicatorConfig {
                pos: [0.0, f64::INFINITY, 1.0],
                ..named("a")
            }],
            "finite",
        ),
        (
            vec![IndicatorConfig {
                attributes: vec![("colour".into(), "1 0 0 1".into())],
                ..named("a")
            }],
            "unknown site attribute",
        ),
        (
            vec![IndicatorConfig::default_indicator(0), named("indicator0")],
            "distinct",
        ),
        (vec![named("table_top")], "site of that name"),
    ];
    let mut env = make("Lift");
    env.reset(Some(0), None).unwrap();
    for (configs, want) in cases {
        let before = model_bytes(&env);
        let refused = VisualizationWrapper::new(env, configs).unwrap_err();
        assert!(
            matches!(refused.error, Error::InvalidArgument { .. })
                && refused.to_string().contains(want),
            "{want}: {}",
            refused.error
        );
        env = *refused.env;
        assert_eq!(model_bytes(&env), before, "{want}");
    }
    let _ = env.step(&zero()).unwrap();
    let mut wrapped =
        VisualizationWrapper::new(env, vec![IndicatorConfig::default_indicator(0)]).unwrap();
    wrapped.reset(Some(0), None).unwrap();
    wrapped
        .set_indicator_pos("indicator0", [0.1, 0.2, 1.3])
        .unwrap();
    let _ = wrapped.step(&zero()).unwrap();
    let m = wrapped.inner().sim().model();
    let site = site_id(m, "indicator0").unwrap();
    let xpos = wrapped.inner().sim().data().site_xpos()[site];
    assert!(
        xpos.iter()
            .zip([0.1, 0.2, 1.3])
            .all(|(a, b)| (a - b).abs() < 1e-12),
        "{xpos:?}"
    );
    wrapped.reset(None, None).unwrap();
    let m = wrapped.inner().sim().model();
    assert_eq!(
        m.body_pos()[body_id(m, "indicator0_body").unwrap()],
        [0.0; 3]
    );
    for (name, pos) in [
        ("nope", [0.0, 0.0, 1.0]),
        ("indicator0", [0.0, f64::INFINITY, 1.0]),
    ] {
        let err = wrapped.set_indicator_pos(name, pos).unwrap_err();
        assert!(matches!(err, Error::InvalidArgument { .. }), "{err}");
    }
}

// --- DomainRandomizationWrapper ----------------------------------------------------------

fn dr(
    seed: Option<u64>,
    env_seed: u64,
    args: DomainRandomizationArgs,
) -> DomainRandomizationWrapper {
    let mut env =
        DomainRandomizationWrapper::new(make("Lift"), DomainRandomizationArgs { seed, ..args })
            .unwrap();
    env.reset(Some(env_seed), None).unwrap();
    env
}

/// What a randomized domain is made of: frames and the model's dynamics.
fn domain(env: &mut DomainRandomizationWrapper) -> (Vec<u8>, Vec<u8>, Vec<f64>) {
    let inner = env.inner_mut();
    let frame = frame(inner, "agentview");
    let bytes = model_bytes(inner);
    let m = inner.sim().model();
    let dynamics = m
        .body_mass()
        .iter()
        .chain(m.geom_friction().iter().flatten())
        .chain(m.dof_damping())
        .copied()
        .collect();
    (frame, bytes, dynamics)
}

#[test]
fn same_seed_same_domain_other_seed_other_domain() {
    let args = DomainRandomizationArgs::default;
    let mut a = dr(Some(3), 0, args());
    let mut b = dr(Some(3), 0, args());
    let mut c = dr(Some(4), 0, args());
    let (fa, ba, da) = domain(&mut a);
    let (fb, bb, db) = domain(&mut b);
    let (fc, _, dc) = domain(&mut c);
    assert!(fa == fb && ba == bb && da == db, "same seed, same domain");
    assert!(fa != fc, "other seed, same frame");
    assert_ne!(da, dc);
    // Steps randomize again, identically for the same seed; the trajectories agree.
    for _ in 0..2 {
        let sa = a.step(&zero()).unwrap();
        let sb = b.step(&zero()).unwrap();
        assert_eq!(
            format!("{:?}", sa.observation),
            format!("{:?}", sb.observation)
        );
    }
    assert!(domain(&mut a) == domain(&mut b));
    // Without a seed the env's seed decides (cameras and dynamics, the fast modders).
    let fast = || DomainRandomizationArgs {
        randomize_color: false,
        ..args()
    };
    let (f1, _, d1) = domain(&mut dr(None, 7, fast()));
    let (f2, _, d2) = domain(&mut dr(None, 7, fast()));
    let (f3, _, d3) = domain(&mut dr(None, 8, fast()));
    assert!(f1 == f2 && d1 == d2);
    assert!(f1 != f3 && d1 != d3);
}

#[test]
fn textures_reach_the_frames_and_other_envs_are_untouched() {
    let only_color = DomainRandomizationArgs {
        randomize_camera: false,
        randomize_lighting: false,
        randomize_dynamics: false,
        ..DomainRandomizationArgs::default()
    };
    let mut plain = make("Lift");
    plain.reset(Some(0), None).unwrap();
    let plain_bytes = model_bytes(&plain);
    let plain_frame = frame(&mut plain, "agentview");
    let mut env = dr(Some(1), 0, only_color);
    let first = frame(env.inner_mut(), "agentview");
    assert_ne!(
        first, plain_frame,
        "the textures and colours changed the frame"
    );
    env.randomize_domain().unwrap();
    let second = frame(env.inner_mut(), "agentview");
    assert!(first != second, "randomize_domain did not change the frame");
    // The textures went back with the defaults: the next reset starts from the plain look.
    env.restore_default_domain().unwrap();
    assert!(
        frame(env.inner_mut(), "agentview") == plain_frame,
        "the restored frame differs from the plain env's"
    );
    // A reset randomizes again and uploads what it drew: uploading every texture anew
    // changes nothing in the frame.
    env.reset(Some(0), None).unwrap();
    let after_reset = frame(env.inner_mut(), "agentview");
    assert!(
        after_reset != plain_frame,
        "the reset did not randomize the look"
    );
    let ntex = env.inner().sim().model().ffi().ntex as usize;
    for t in 0..ntex {
        env.inner_mut().upload_texture(t).unwrap();
    }
    assert!(
        frame(env.inner_mut(), "agentview") == after_reset,
        "uploading every texture changed the frame: the reset did not upload"
    );
    // Another env of the same configuration never saw any of it.
    let mut other = make("Lift");
    other.reset(Some(0), None).unwrap();
    assert_eq!(model_bytes(&other), plain_bytes);
    assert_eq!(model_bytes(&plain), plain_bytes);
    assert!(
        frame(&mut other, "agentview") == plain_frame,
        "another env's frame changed"
    );
}

#[test]
fn draws_stay_in_robosuites_ranges() {
    let mut plain = make("Lift");
    plain.reset(Some(0), None).unwrap();
    let p = plain.sim().model();
    let mut env = dr(Some(5), 0, DomainRandomizationArgs::default());
    for _ in 0..5 {
        env.randomize_domain().unwrap();
        let m = env.inner().sim().model();
        let cam = DomainRandomizationArgs::default().camera_randomization_args;
        for i in 0..m.cam_pos().len() {
            for k in 0..3 {
                assert!(
                    (m.cam_pos()[i][k] - p.cam_pos()[i][k]).abs() <= cam.position_perturbation_size
                );
            }
            assert!((m.cam_fovy()[i] - p.cam_fovy()[i]).abs() <= cam.fovy_perturbation_size);
            // The rotation is at most 0.087 rad: |<q, q0>| >= cos(0.087 / 2).
            let dot: f64 = (0..4)
                .map(|k| m.cam_quat()[i][k] * p.cam_quat()[i][k])
                .sum();
            assert!(
                dot.abs() >= (0.087f64 / 2.0).cos() - 1e-9,
                "camera {i}: {dot}"
            );
        }
        let light = LightingArgs::default();
        for i in 0..m.light_pos().len() {
            for k in 0..3 {
                assert!(
                    (m.light_pos()[i][k] - p.light_pos()[i][k]).abs()
                        <= light.position_perturbation_size
                );
                assert!(
                    f64::from((m.light_diffuse()[i][k] - p.light_diffuse()[i][k]).abs())
                        <= light.diffuse_perturbation_size + 1e-6
                );
            }
        }
        let dynamics = DynamicsArgs::default();
        for b in 0..m.body_mass().len() {
            let (ours, base) = (m.body_mass()[b], p.body_mass()[b]);
            assert!((ours - base).abs() <= base * dynamics.mass_perturbation_ratio + 1e-15);
            for k in 0..3 {
                assert!(
                    (m.body_pos()[b][k] - p.body_pos()[b][k]).abs()
                        <= dynamics.position_perturbation_size + 1e-15
                );
            }
        }
        for g in 0..m.geom_friction().len() {
            for k in 0..3 {
                let (ours, base) = (m.geom_friction()[g][k], p.geom_friction()[g][k]);
                assert!((ours - base).abs() <= base * dynamics.friction_perturbation_ratio + 1e-15);
            }
            assert!(m.geom_solref()[g].iter().all(|v| (0.0..=1.0).contains(v)));
        }
        for d in 0..m.dof_damping().len() {
            let (ours, base) = (m.dof_damping()[d], p.dof_damping()[d]);
            assert!(
                ours >= 0.0 && (ours - base).abs() <= dynamics.damping_perturbation_size + 1e-15
            );
        }
    }
}

#[test]
fn randomize_every_n_steps() {
    let only_camera = DomainRandomizationArgs {
        randomize_color: false,
        randomize_lighting: false,
        randomize_dynamics: false,
        randomize_on_reset: false,
        randomize_every_n_steps: 2,
        ..DomainRandomizationArgs::default()
    };
    let mut env = dr(Some(0), 0, only_camera);
    let pos = |env: &DomainRandomizationWrapper| env.inner().sim().model().cam_pos().to_vec();
    let start = pos(&env);
    let mut changed = Vec::new();
    let mut last = start.clone();
    for _ in 0..5 {
        let _ = env.step(&zero()).unwrap();
        changed.push(pos(&env) != last);
        last = pos(&env);
    }
    assert_eq!(changed, [true, false, true, false, true]);
    assert_eq!(env.step_counter(), 5);
    // The next reset restores the defaults first.
    env.reset(None, None).unwrap();
    assert_eq!(pos(&env), start);
}

#[test]
fn bad_randomization_arguments_leave_the_env_unchanged() {
    let d = DomainRandomizationArgs::default;
    let cases: Vec<(DomainRandomizationArgs, &str)> = vec![
        (
            DomainRandomizationArgs {
                camera_randomization_args: CameraArgs {
                    position_perturbation_size: -0.1,
                    ..CameraArgs::default()
                },
                ..d()
            },
            "position_perturbation_size",
        ),
        (
            DomainRandomizationArgs {
                camera_randomization_args: CameraArgs {
                    camera_names: Some(vec!["nope".into()]),
                    ..CameraArgs::default()
                },
                ..d()
            },
            "unknown camera",
        ),
        (
            DomainRandomizationArgs {
                camera_randomization_args: CameraArgs {
                    fovy_perturbation_size: 90.0,
                    ..CameraArgs::default()
                },
                ..d()
            },
            "fovy_perturbation_size",
        ),
        (
            DomainRandomizationArgs {
                lighting_randomization_args: LightingArgs {
                    diffuse_perturbation_size: f64::NAN,
                    ..LightingArgs::default()
                },
                ..d()
            },
            "diffuse_perturbation_size",
        ),
        (
            DomainRandomizationArgs {
                lighting_randomization_args: LightingArgs {
                    light_names: Some(vec!["sun".into()]),
                    ..LightingArgs::default()
                },
                ..d()
            },
            "unknown light",
        ),
        (
            DomainRandomizationArgs {
                dynamics_randomization_args: DynamicsArgs {
                    body_names: Some(vec!["cube_main".into(), "moon".into()]),
                    ..DynamicsArgs::default()
                },
                ..d()
            },
            "unknown body",
        ),
        (
            DomainRandomizationArgs {
                dynamics_randomization_args: DynamicsArgs {
                    mass_perturbation_ratio: f64::INFINITY,
                    ..DynamicsArgs::default()
                },
                ..d()
            },
            "mass_perturbation_ratio",
        ),
        (
            DomainRandomizationArgs {
                color_randomization_args: robosuite_env::modders::ColorArgs {
                    local_rgb_interpolation: 1.5,
                    ..Default::default()
                },
                ..d()
            },
            "local_rgb_interpolation",
        ),
        (
            DomainRandomizationArgs {
                color_randomization_args: robosuite_env::modders::ColorArgs {
                    texture_variations: Vec::new(),
                    ..Default::default()
                },
                ..d()
            },
            "texture_variations",
        ),
    ];
    let mut env = make("Lift");
    env.reset(Some(0), None).unwrap();
    for (args, want) in cases {
        let before = model_bytes(&env);
        let refused = DomainRandomizationWrapper::new(env, args).unwrap_err();
        assert!(
            matches!(refused.error, Error::InvalidArgument { .. })
                && refused.to_string().contains(want),
            "{want}: {}",
            refused.error
        );
        env = *refused.env;
        assert_eq!(model_bytes(&env), before, "{want}");
    }
    assert!(
        "swirl"
            .parse::<robosuite_env::modders::TextureVariation>()
            .is_err()
    );
    let _ = env.step(&zero()).unwrap();
}
