//! The wrappers and vector environments over Lift with a camera (robosuite-env's `render`
//! feature, Mesa's software EGL on a CPU-only machine): uint8 images pass through the
//! GymWrapper's Dict, FlattenObservation, FrameStackObservation and the vector envs.

use adapters::{
    FlattenObservation, GymWrapper, Padding, SyncVectorEnv, ThreadVectorEnv, VectorEnv, WrapperExt,
};
use gym_core::{AnySpace, ArrayValue, DType, Env, Error, Space, Value, rng_from_seed};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::config::CameraConfig;
use robosuite_env::{EnvConfig, RobosuiteEnv};

const SIZE: usize = 24;

fn lift() -> RobosuiteEnv {
    let config = EnvConfig::default()
        .with_horizon(3)
        .with_cameras(CameraConfig::observe(["agentview"], SIZE, SIZE));
    robosuite_env::make_with("Lift", config).expect("Lift with a camera builds")
}

/// The GymWrapper over Lift with `agentview`, unflattened.
fn dict_env() -> Result<GymWrapper<RobosuiteEnv>, Error> {
    GymWrapper::new(lift(), None, false)
}

fn image(v: &Value) -> &ArrayD<u8> {
    match v {
        Value::Array(ArrayValue::U8(a)) => a,
        other => panic!("expected a uint8 image, got {other:?}"),
    }
}

fn dict(v: &Value) -> &gym_core::DictValue {
    match v {
        Value::Dict(d) => d,
        other => panic!("expected a Dict, got {other:?}"),
    }
}

#[test]
fn gym_wrapper_dict_holds_uint8_images_in_robosuites_key_order() -> Result<(), Error> {
    let mut env = dict_env()?;
    assert_eq!(
        env.keys(),
        ["object-state", "agentview_image", "robot0_proprio-state"]
    );
    let AnySpace::Dict(space) = env.observation_space().clone() else {
        panic!("a Dict space");
    };
    let AnySpace::Box(b) = space.get("agentview_image").expect("image key") else {
        panic!("a Box");
    };
    assert_eq!(
        (b.dtype(), b.shape()),
        (DType::U8, Some(&[SIZE, SIZE, 3][..]))
    );
    let (obs, _) = env.reset(Some(0), None)?;
    assert!(env.observation_space().contains(&obs));
    let img = image(&dict(&obs)["agentview_image"]);
    assert_eq!(img.shape(), [SIZE, SIZE, 3]);
    assert!(img.iter().any(|&p| p != img[[0, 0, 0]]), "a drawn frame");
    Ok(())
}

#[test]
fn flatten_observation_promotes_pixels_in_key_order() -> Result<(), Error> {
    let mut env = FlattenObservation::new(dict_env()?);
    let pixels = SIZE * SIZE * 3;
    let space = env.observation_space().clone();
    // Gymnasium's promotion: uint8 with float64 parts gives float64.
    assert_eq!(space.dtype(), DType::F64);
    assert_eq!(space.shape(), Some(&[10 + pixels + 50][..]));
    let (flat, _) = env.reset(Some(2), None)?;
    let mut raw = dict_env()?;
    let (obs, _) = raw.reset(Some(2), None)?;
    let img = image(&dict(&obs)["agentview_image"]);
    let flat = flat.to_f64_vec();
    let expected: Vec<f64> = img.iter().map(|&p| f64::from(p)).collect();
    assert_eq!(&flat[10..10 + pixels], &expected[..]);
    let step = env.step(&ArrayD::zeros(IxDyn(&[7])))?;
    assert!(space.contains(&step.observation));
    Ok(())
}

#[test]
fn frame_stack_keeps_the_last_frames() -> Result<(), Error> {
    let inner = GymWrapper::new(lift(), Some(vec!["agentview_image".into()]), false)?;
    let mut env = inner.frame_stack_observation(2, Padding::Zero)?;
    let (first, _) = env.reset(Some(0), None)?;
    let stacked = image(&dict(&first)["agentview_image"]).clone();
    assert_eq!(stacked.shape(), [2, SIZE, SIZE, 3]);
    // Zero padding, then the reset frame.
    assert!(
        stacked
            .index_axis(ndarray::Axis(0), 0)
            .iter()
            .all(|&p| p == 0)
    );
    let reset_frame = stacked.index_axis(ndarray::Axis(0), 1).to_owned();
    assert!(reset_frame.iter().any(|&p| p != 0));
    let action = ArrayD::from_elem(IxDyn(&[7]), 0.5f32);
    let step = env.step(&action)?;
    let next = image(&dict(&step.observation)["agentview_image"]);
    assert_eq!(next.index_axis(ndarray::Axis(0), 0), reset_frame);
    assert!(env.observation_space().contains(&step.observation));
    Ok(())
}

/// Sync and threaded vector envs batch uint8 images and agree with single envs.
#[test]
fn vector_envs_batch_uint8_images() -> Result<(), Error> {
    let mut sync = SyncVectorEnv::new(vec![dict_env()?, dict_env()?])?;
    let mut threaded = ThreadVectorEnv::new(vec![dict_env()?, dict_env()?])?;
    let mut single = dict_env()?;
    let reset = sync.reset(4, None)?.0.clone();
    assert_eq!(&reset, threaded.reset(4, None)?.0);
    let batch = image(&dict(&reset)["agentview_image"]);
    assert_eq!(batch.shape(), [2, SIZE, SIZE, 3]);
    let (one, _) = single.reset(Some(5), None)?;
    assert_eq!(
        batch.index_axis(ndarray::Axis(0), 1),
        image(&dict(&one)["agentview_image"])
    );
    let mut rng = rng_from_seed(3);
    for t in 0..4 {
        let actions = sync.action_space().sample(&mut rng);
        let s = sync.step(&actions)?.observations.clone();
        let th = threaded.step(&actions)?.observations;
        assert_eq!(&s, th, "step {t}");
        assert!(sync.observation_space().contains(&s));
        assert_eq!(
            image(&dict(&s)["agentview_image"]).shape(),
            [2, SIZE, SIZE, 3]
        );
    }
    Ok(())
}
