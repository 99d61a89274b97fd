//! Wrapper stacks: composition through `WrapperExt`, typed stacks as plain values, boxing
//! into `BoxedEnv`, and wrappers over boxed environments (toy environments only).

use crate::common::{CountEnv, DictEnv, WalkEnv, a32, a64};
use adapters::{
    FrameStackObservation, GymWrapper, NormalizeObservation, Padding, RecordEpisodeStatistics,
    TimeLimit, WrapperExt,
};
use gym_core::spaces::{AnySpace, BoxSpace};
use gym_core::{
    BoxedEnv, DType, DynSpace, Env, EnvExt, Error, Flatten, IntoBoxedEnv, Space, Value, Wrapper,
};
use ndarray::ArrayD;

fn assert_send<T: Send + 'static>(_: &T) {}

#[test]
fn the_issue_example_stack_reads_in_order() -> Result<(), Error> {
    let env: RecordEpisodeStatistics<NormalizeObservation<TimeLimit<GymWrapper<DictEnv>>>> =
        DictEnv::new(1000, false)
            .gym_wrapper(None, true)?
            .time_limit(3)?
            .normalize_observation()?
            .record_episode_statistics();
    assert_send(&env);
    let mut env = env;
    assert_eq!(
        env.observation_space().to_string(),
        "Box(-inf, inf, [7], float32)"
    );
    let (obs, _) = env.reset(Some(0), None)?;
    assert_eq!(obs.len(), 7);
    let mut last = None;
    for _ in 0..3 {
        last = Some(env.step(&a32(&[0.1, 0.0, 0.0]))?);
    }
    let last = last.unwrap();
    assert!(last.truncated && !last.terminated);
    let ep = last.info.get_map("episode").unwrap();
    assert_eq!(ep.get_i64("l"), Some(3));
    assert!(last.info.get_bool("success").is_some());
    // Wrapper access: the layers, the innermost env, taking the stack apart.
    assert_eq!(env.inner().inner().max_episode_steps(), 3);
    assert!(env.unwrapped_as::<DictEnv>().is_some());
    let inner: NormalizeObservation<_> = env.into_inner();
    assert!(inner.update_running_mean());
    Ok(())
}

#[test]
fn any_stack_boxes_into_a_dynamic_env() -> Result<(), Error> {
    let mut boxed: BoxedEnv = DictEnv::new(5, false)
        .gym_wrapper(None, true)?
        .time_limit(2)?
        .clip_action()?
        .boxed();
    assert_eq!(boxed.observation_space().kind(), "Box");
    assert_eq!(boxed.action_space().as_box().unwrap().dtype(), DType::F32);
    let (obs, _) = boxed.reset(Some(1), None)?;
    assert!(boxed.observation_space().contains(&obs));
    // ClipAction accepts out-of-bounds actions and clips them for the inner env.
    let action = Value::from(a32(&[5.0, 5.0, -5.0]));
    let s = boxed.step(&action)?;
    assert!(!s.truncated);
    assert!(boxed.step(&action)?.truncated);
    assert!(
        boxed
            .unwrapped_as::<DictEnv>()
            .is_some_and(|e| e.state[1] < 1.0)
    );
    // A wrong-shaped action is a typed error through the dynamic layer.
    assert!(matches!(
        boxed.step(&Value::from(a32(&[0.0]))),
        Err(Error::InvalidAction(_))
    ));
    Ok(())
}

#[test]
fn wrappers_stack_on_boxed_envs() -> Result<(), Error> {
    // Dict observations through the dynamic layer: filter, flatten, normalise.
    let boxed = DictEnv::new(5, true).boxed();
    let mut env = boxed
        .filter_observation(["robot0_proprio-state", "frontview_image"])?
        .flatten_observation()
        .normalize_observation()?
        .rescale_action(0.0, 1.0)?;
    // Sorted filter keys: the image comes first (uint8 -> promoted with float64).
    assert_eq!(env.observation_space().shape(), Some(&[8usize][..]));
    env.reset(Some(3), None)?;
    let s = env.step(&Value::from(a64(&[0.5, 0.5, 0.5])))?;
    assert_eq!(s.observation.len(), 8);
    // RescaleAction mapped [0, 1] to the inner bounds: 0.5 is the middle, 0.
    let inner = env.unwrapped_as::<DictEnv>().unwrap();
    assert!(inner.state.iter().all(|v| v.abs() <= 0.5 + 1e-12));
    Ok(())
}

#[test]
fn gymnasium_make_order_with_checker() -> Result<(), Error> {
    // gym.make: env -> PassiveEnvChecker -> OrderEnforcing -> TimeLimit.
    let mut env = WalkEnv::new(1000)
        .passive_env_checker()?
        .order_enforcing()
        .time_limit(4)?;
    assert_eq!(env.step(&a32(&[0.0, 0.0])).unwrap_err(), Error::ResetNeeded);
    env.reset(Some(0), None)?;
    let flags: Vec<bool> = (0..4)
        .map(|_| env.step(&a32(&[0.0, 0.0])).map(|s| s.truncated))
        .collect::<Result<_, _>>()?;
    assert_eq!(flags, [false, false, false, true]);
    assert!(env.inner().inner().warnings().is_empty());
    Ok(())
}

#[test]
fn autoreset_with_statistics_and_frame_stack() -> Result<(), Error> {
    let mut env = CountEnv::new(Some(2), None)
        .record_episode_statistics()
        .autoreset()
        .frame_stack_observation(2, Padding::Zero)?;
    env.reset(None, None)?;
    let a: Vec<_> = (0..4).map(|_| env.step(&0)).collect::<Result<_, _>>()?;
    let obs: Vec<Vec<f64>> = a
        .iter()
        .map(|s| s.observation.iter().copied().collect())
        .collect();
    assert_eq!(
        obs,
        vec![
            vec![0.0, 1.0],
            vec![1.0, 2.0],
            vec![2.0, 0.0],
            vec![0.0, 1.0]
        ]
    );
    assert_eq!(
        a[1].info.get_map("episode").and_then(|m| m.get_i64("l")),
        Some(2)
    );
    assert_eq!((a[2].reward, a[2].terminated), (0.0, false));
    Ok(())
}

#[test]
fn frame_stack_over_dynamic_observations_uses_batch_space() -> Result<(), Error> {
    let mut env: FrameStackObservation<GymWrapper<DictEnv>> = DictEnv::new(5, false)
        .gym_wrapper(None, false)?
        .frame_stack_observation(3, Padding::Reset)?;
    let space = env.observation_space().clone();
    let AnySpace::Dict(d) = &space else {
        panic!("{space}")
    };
    assert_eq!(
        d.get("object-state").unwrap().shape(),
        Some(&[3usize, 3][..])
    );
    let (obs, _) = env.reset(Some(2), None)?;
    assert!(space.contains(&obs));
    let s = env.step(&a32(&[0.0, 0.0, 0.0]))?;
    assert!(space.contains(&s.observation));
    Ok(())
}

#[test]
fn transforms_compose() -> Result<(), Error> {
    let mut env = CountEnv::new(None, None)
        .transform_reward(|r| -r)
        .transform_observation(
            |o: ArrayD<f64>| o.mapv(|v| v as f32),
            BoxSpace::<f32>::unbounded(&[1]),
        )
        .transform_action(|a: &bool| i64::from(*a), BoolSpace);
    env.reset(None, None)?;
    let s = env.step(&true)?;
    assert_eq!((s.observation[[0]], s.reward), (1.0f32, -1.0));
    Ok(())
}

/// A two-element space of `bool`s, to show that `TransformAction` can change the action
/// type entirely.
#[derive(Debug, Clone, PartialEq)]
struct BoolSpace;

impl Space for BoolSpace {
    type Element = bool;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> bool {
        rng.next_u32() & 1 == 1
    }

    fn contains(&self, _x: &bool) -> bool {
        true
    }

    fn shape(&self) -> Option<&[usize]> {
        Some(&[])
    }
}

impl Flatten for BoolSpace {
    fn flatdim(&self) -> usize {
        1
    }

    fn flat_dtype(&self) -> DType {
        DType::I8
    }

    fn flatten(&self, x: &bool) -> Result<gym_core::ArrayValue, gym_core::SpaceError> {
        Ok(gym_core::ArrayValue::from(
            ndarray::arr1(&[i8::from(*x)]).into_dyn(),
        ))
    }

    fn unflatten(&self, flat: &gym_core::ArrayValue) -> Result<bool, gym_core::SpaceError> {
        Ok(flat.to_f64_vec().first().is_some_and(|v| *v != 0.0))
    }

    fn flatten_space(&self) -> gym_core::AnyBox {
        BoxSpace::<i8>::uniform(0.0, 1.0, &[1]).unwrap().into()
    }
}

impl DynSpace for BoolSpace {
    fn to_any(&self) -> AnySpace {
        gym_core::spaces::MultiBinary::new(&[1]).unwrap().into()
    }

    fn to_value(&self, x: &bool) -> Value {
        self.flatten(x).unwrap().into()
    }

    fn from_value(&self, v: &Value) -> Result<bool, gym_core::SpaceError> {
        self.unflatten(v.as_array().ok_or(gym_core::SpaceError::WrongKind {
            expected: "array",
            got: v.kind(),
        })?)
    }
}
