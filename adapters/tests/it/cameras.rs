//! The wrappers and vector environments over Lift with a camera (robosuite-env's `render`
//! feature, Mesa's software EGL on a CPU-only machine): uint8 images pass through the
//! GymWrapper's Dict, FlattenObservation, FrameStackObservation and the vector envs.

use adapters::{
    AutoresetMode, BatchSpace, FlattenObservation, GymWrapper, Padding, SyncVectorEnv,
    ThreadEnvPool, ThreadVectorEnv, VectorEnv, WrapperExt,
};
use gym_core::{
    AnySpace, ArrayValue, BoxedEnv, DType, Env, Error, IntoBoxedEnv, Space, Value, rng_from_seed,
};
use ndarray::{ArrayD, IxDyn};
use robosuite_env::config::CameraConfig;
use robosuite_env::{EnvConfig, RobosuiteEnv};
use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

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

/// Counts how a vector env or pool takes an environment's observations: through its own
/// buffer (`step`, `step_into`) or straight into the batch (`write_observation_row`).
struct Counted<E> {
    env: E,
    copies: Arc<AtomicUsize>,
    rows: Arc<AtomicUsize>,
}

impl<E: Env> Env for Counted<E> {
    type Obs = E::Obs;
    type Act = E::Act;
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;
    fn observation_space(&self) -> &E::ObsSpace {
        self.env.observation_space()
    }
    fn action_space(&self) -> &E::ActSpace {
        self.env.action_space()
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&gym_core::ResetOptions>,
    ) -> Result<(E::Obs, gym_core::Info), Error> {
        self.env.reset(seed, options)
    }
    fn step(&mut self, action: &E::Act) -> Result<gym_core::Step<E::Obs>, Error> {
        self.copies.fetch_add(1, Ordering::SeqCst);
        self.env.step(action)
    }
    fn step_into(
        &mut self,
        action: &E::Act,
        observation: &mut E::Obs,
        info: &mut gym_core::Info,
    ) -> Result<gym_core::Transition, Error> {
        self.copies.fetch_add(1, Ordering::SeqCst);
        self.env.step_into(action, observation, info)
    }
    fn writes_rows(&self) -> bool {
        self.env.writes_rows()
    }
    fn step_for_row(
        &mut self,
        action: &E::Act,
        info: &mut gym_core::Info,
    ) -> Result<gym_core::Transition, Error> {
        self.env.step_for_row(action, info)
    }
    fn write_observation_row(&self, row: &mut gym_core::ObsRow<'_>) -> Result<(), Error> {
        self.rows.fetch_add(1, Ordering::SeqCst);
        self.env.write_observation_row(row)
    }
}

/// Lift with `agentview` behind the GymWrapper (Dict or flat), horizon 3 (so autoresets
/// happen), counted.
fn counted(flat: bool, copies: &Arc<AtomicUsize>, rows: &Arc<AtomicUsize>) -> BoxedEnv {
    let gym = GymWrapper::new(lift(), None, flat).expect("GymWrapper");
    Counted {
        env: gym,
        copies: Arc::clone(copies),
        rows: Arc::clone(rows),
    }
    .boxed()
}

/// One lone env per sub-environment, stepped as a `NextStep` vector env steps it: a step
/// after the end of an episode is `reset()` (no seed), its action ignored.
struct Lone {
    env: GymWrapper<RobosuiteEnv>,
    ended: bool,
}

impl Lone {
    fn new(flat: bool, seed: u64) -> (Self, Value) {
        let mut env = GymWrapper::new(lift(), None, flat).expect("GymWrapper");
        let (obs, _) = env.reset(Some(seed), None).expect("reset");
        (Self { env, ended: false }, obs)
    }

    fn step(&mut self, action: &ArrayD<f32>) -> Value {
        if std::mem::take(&mut self.ended) {
            return self.env.reset(None, None).expect("reset").0;
        }
        let s = self.env.step(action).expect("step");
        self.ended = s.terminated || s.truncated;
        s.observation
    }
}

/// Item `i` of a batched observation of `space`.
fn row_of(space: &AnySpace, batch: &Value, i: usize) -> Value {
    space.read_item(batch, i).expect("row")
}

/// Vector envs and the pool write each step's observation (images included) once,
/// straight from the env into the batch, and the batch equals lone envs' observations bit
/// for bit, autoreset steps included; `SameStep` (which needs the final observation) and
/// resets go through the env's own buffer.
#[test]
fn batches_are_written_once_per_step_and_equal_lone_envs_bit_for_bit() -> Result<(), Error> {
    let n = 2;
    let steps = 7; // horizon 3: two autoresets per env
    for flat in [false, true] {
        let (copies, rows) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
        let envs = (0..n).map(|_| counted(flat, &copies, &rows)).collect();
        let mut vec = ThreadVectorEnv::with_threads(envs, 2)?;
        let mut lone: Vec<Lone> = Vec::new();
        let space = vec.single_observation_space().clone();
        let reset = vec.reset(10, None)?.0.clone();
        for i in 0..n {
            let (l, obs) = Lone::new(flat, 10 + i as u64);
            assert_eq!(row_of(&space, &reset, i), obs, "flat {flat}: reset row {i}");
            lone.push(l);
        }
        let mut rng = rng_from_seed(7);
        let mut stepped = 0;
        for t in 0..steps {
            let actions = vec.action_space().sample(&mut rng);
            let Value::Array(ArrayValue::F32(a)) = &actions else {
                panic!("f32 actions");
            };
            let stepping = lone.iter().filter(|l| !l.ended).count();
            let obs = vec.step(&actions)?.observations.clone();
            for (i, l) in lone.iter_mut().enumerate() {
                let expected = l.step(&a.index_axis(ndarray::Axis(0), i).to_owned());
                assert_eq!(
                    row_of(&space, &obs, i),
                    expected,
                    "flat {flat}: step {t}, env {i}"
                );
            }
            stepped += stepping;
        }
        assert!(stepped < n * steps, "autoresets happened");
        assert_eq!(
            rows.load(Ordering::SeqCst),
            stepped,
            "one row write per step"
        );
        assert_eq!(copies.load(Ordering::SeqCst), 0, "no step through a buffer");

        if flat {
            // The flat GymWrapper is checked for the vector env only (the pool and the
            // autoreset modes are the same code for both).
            continue;
        }
        // SameStep keeps the env's buffer (for final_obs).
        let (copies, rows) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
        let mut same = ThreadVectorEnv::new(vec![counted(flat, &copies, &rows)])?
            .with_autoreset_mode(AutoresetMode::SameStep);
        same.reset(1, None)?;
        let _ = same.step(&same.action_space().sample(&mut rng))?;
        assert_eq!(
            (copies.load(Ordering::SeqCst), rows.load(Ordering::SeqCst)),
            (1, 0)
        );

        // The pool: row k is env_ids[k]'s lone observation.
        let (copies, rows) = (Arc::new(AtomicUsize::new(0)), Arc::new(AtomicUsize::new(0)));
        let envs = (0..3).map(|_| counted(flat, &copies, &rows)).collect();
        let mut pool = ThreadEnvPool::with_threads(envs, 2, 2)?;
        pool.reset(20u64)?;
        let (mut lone, mut expected): (Vec<Lone>, Vec<Value>) =
            (0..3).map(|i| Lone::new(flat, 20 + i)).unzip();
        let space = pool.single_observation_space().clone();
        let batch_space = pool.single_action_space().batch_space(2)?;
        let s = pool.recv()?;
        for (k, &id) in s.env_ids.iter().enumerate() {
            assert_eq!(row_of(&space, s.observations, k), expected[id]);
        }
        let mut ids = s.env_ids.to_vec();
        let mut stepped = 0;
        for t in 0..8 {
            let batch = batch_space.sample(&mut rng);
            let Value::Array(ArrayValue::F32(a)) = &batch else {
                panic!("f32 actions");
            };
            for (k, &id) in ids.iter().enumerate() {
                stepped += usize::from(!lone[id].ended);
                expected[id] = lone[id].step(&a.index_axis(ndarray::Axis(0), k).to_owned());
            }
            pool.send(&batch, &ids)?;
            let s = pool.recv()?;
            for (k, &id) in s.env_ids.iter().enumerate() {
                assert_eq!(
                    row_of(&space, s.observations, k),
                    expected[id],
                    "flat {flat}: pool round {t}, env {id}"
                );
            }
            ids = s.env_ids.to_vec();
        }
        // Steps still pending when the loop ends have not been written yet.
        let written = rows.load(Ordering::SeqCst);
        assert!(
            written > 0 && written <= stepped,
            "{written} rows for {stepped} steps"
        );
        assert!(stepped - written <= 1, "at most one env is pending");
        assert!(rows.load(Ordering::SeqCst) > 0, "the pool writes rows");
        assert_eq!(
            copies.load(Ordering::SeqCst),
            0,
            "no pool step through a buffer"
        );
    }
    Ok(())
}
