//! The Env, Wrapper, dynamic and registry layers over a small deterministic environment.

use gym_core::registry::{self, EnvSpec};
use gym_core::{
    BoxSpace, BoxedEnv, Discrete, Env, EnvExt, EnvRng, Error, Info, IntoBoxedEnv, ResetOptions,
    Result, RewardWrapper, Rewards, Space, Step, Value, Wrapper, rng_from_seed,
};
use ndarray::{ArrayD, IxDyn, arr1};
use rand::RngExt;
use std::sync::Arc;

/// A walker on a line: action 0 steps left, 1 right; the episode ends at ±3.
struct Walk {
    obs_space: BoxSpace<f32>,
    act_space: Discrete,
    pos: i64,
    rng: Option<EnvRng>,
    closed: u32,
}

impl Walk {
    fn new() -> Self {
        Self {
            obs_space: BoxSpace::uniform(-3.0, 3.0, &[1]).unwrap(),
            act_space: Discrete::new(2).unwrap(),
            pos: 0,
            rng: None,
            closed: 0,
        }
    }
    fn obs(&self) -> ArrayD<f32> {
        arr1(&[self.pos as f32]).into_dyn()
    }
}

impl Env for Walk {
    type Obs = ArrayD<f32>;
    type Act = i64;
    type ObsSpace = BoxSpace<f32>;
    type ActSpace = Discrete;
    fn observation_space(&self) -> &BoxSpace<f32> {
        &self.obs_space
    }
    fn action_space(&self) -> &Discrete {
        &self.act_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(gym_core::entropy_seed()));
        self.pos = rng.random_range(-1..=1);
        Ok((self.obs(), Info::new()))
    }
    fn step(&mut self, action: &i64) -> Result<Step<ArrayD<f32>>> {
        if !self.act_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} is not in Discrete(2)"
            )));
        }
        self.pos += if *action == 1 { 1 } else { -1 };
        let terminated = self.pos.abs() >= 3;
        Ok(Step {
            observation: self.obs(),
            reward: 1.0,
            terminated,
            truncated: false,
            info: Info::new().with("pos", self.pos),
        })
    }
    fn close(&mut self) {
        self.closed += 1;
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

/// Doubles rewards; forwards the rest.
struct Double<E>(E);

impl<E: Env> Wrapper for Double<E> {
    type Inner = E;
    type Kind = Rewards;
    fn inner(&self) -> &E {
        &self.0
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.0
    }
    fn into_inner(self) -> E {
        self.0
    }
}

impl<E: Env> RewardWrapper for Double<E> {
    fn reward(&mut self, reward: f64) -> f64 {
        reward * 2.0
    }
}

#[test]
fn seeded_reset_is_reproducible_and_rng_state_follows_the_seed() {
    let (mut a, mut b) = (Walk::new(), Walk::new());
    let pairs: Vec<_> = (0..20)
        .map(|s| {
            (
                a.reset(Some(s), None).unwrap().0,
                b.reset(Some(s), None).unwrap().0,
            )
        })
        .collect();
    assert!(pairs.iter().all(|(x, y)| x == y));
    assert!(
        pairs.iter().any(|(x, _)| x[[0]] != pairs[0].0[[0]]),
        "different seeds give different starts"
    );
    a.reset(Some(123), None).unwrap();
    let state = a.rng().cloned();
    a.reset(None, None).unwrap();
    a.reset(Some(123), None).unwrap();
    assert_eq!(a.rng().cloned(), state);
    a.reset(Some(456), None).unwrap();
    assert_ne!(a.rng().cloned(), state);
}

#[test]
fn wrappers_forward_and_unwrap() {
    let mut env = Double(Double(Walk::new()));
    env.reset(Some(0), None).unwrap();
    let s = env.step(&1).unwrap();
    assert_eq!(s.reward, 4.0);
    assert!(env.rng().is_some(), "rng is forwarded through wrappers");
    assert_eq!(
        env.unwrapped::<Walk>().map(|w| w.pos),
        Some(s.observation[[0]] as i64)
    );
    assert!(env.unwrapped::<Double<Walk>>().is_none());
    env.close();
    env.close();
    assert_eq!(env.into_inner().into_inner().closed, 2);
}

#[test]
fn boxed_env_converts_values_and_rejects_bad_actions() {
    let mut env: BoxedEnv = Double(Walk::new()).boxed();
    assert_eq!(env.action_space().to_string(), "Discrete(2)");
    assert_eq!(
        env.observation_space().to_string(),
        "Box(-3, 3, [1], float32)"
    );
    let (obs, _) = env.reset(Some(5), None).unwrap();
    assert!(env.observation_space().contains(&obs));
    let err = env
        .step(&Value::Array(arr1(&[0.5f64]).into_dyn().into()))
        .unwrap_err();
    assert!(matches!(err, Error::InvalidAction(_)), "{err}");
    let err = env.step(&Value::Discrete(7)).unwrap_err();
    assert!(matches!(err, Error::InvalidAction(_)), "{err}");
    // The env is still usable after rejected actions.
    let step = env.step(&Value::Discrete(1)).unwrap();
    assert_eq!(step.reward, 2.0);
    assert_eq!(
        step.info.get_i64("pos"),
        Some(obs.as_array().unwrap().to_f64_vec()[0] as i64 + 1)
    );
    assert!(env.unwrapped_as::<Walk>().is_some());
    // A boxed env is an Env too, so typed wrappers stack on it.
    let mut wrapped = Double(env);
    wrapped.reset(Some(5), None).unwrap();
    assert_eq!(wrapped.step(&Value::Discrete(0)).unwrap().reward, 4.0);
}

#[test]
fn registry_makes_by_id_and_lists_ids_on_unknown() {
    registry::register(EnvSpec {
        id: "Walk-v0".into(),
        factory: Arc::new(|kwargs: &registry::Kwargs| {
            if kwargs.contains_key("bad") {
                return Err(Error::invalid_argument("bad", "not accepted"));
            }
            Ok(Walk::new().boxed())
        }),
        max_episode_steps: None,
        nondeterministic: false,
        description: "a walk on a line".into(),
    });
    let mut env = registry::make("Walk-v0", &serde_json::Value::Null).unwrap();
    assert!(env.reset(Some(1), None).is_ok());
    assert!(registry::registered_ids().contains(&"Walk-v0".to_owned()));
    match registry::make("Nope-v0", &serde_json::json!({})) {
        Err(Error::UnknownEnv { id, available }) => {
            assert_eq!(id, "Nope-v0");
            assert!(available.contains(&"Walk-v0".to_owned()));
        }
        other => panic!("expected UnknownEnv, got {:?}", other.map(|_| ())),
    }
    let err = registry::make("Walk-v0", &serde_json::json!({"bad": true}))
        .map(|_| ())
        .unwrap_err();
    assert_eq!(err.to_string(), "invalid argument `bad`: not accepted");
    let err = registry::make("Walk-v0", &serde_json::json!([1]))
        .map(|_| ())
        .unwrap_err();
    assert!(
        matches!(err, Error::InvalidArgument { ref name, .. } if name == "kwargs"),
        "{err}"
    );
}

#[test]
fn step_result_helpers() {
    let s = Step {
        observation: 1,
        reward: 0.5,
        terminated: false,
        truncated: true,
        info: Info::new(),
    };
    assert!(s.done());
    let t = s.map_observation(|o| o * 10);
    assert_eq!(t.observation, 10);
    assert!(
        BoxSpace::<f64>::uniform(0.0, 1.0, &[2])
            .unwrap()
            .contains(&ArrayD::zeros(IxDyn(&[2])))
    );
}

#[test]
fn default_step_into_writes_what_step_returns() {
    let (mut a, mut b) = (Walk::new(), Walk::new());
    let (mut obs, mut info) = a.reset(Some(3), None).unwrap();
    b.reset(Some(3), None).unwrap();
    for action in [1, 1, 0, 1, 1, 1, 1] {
        let t = a.step_into(&action, &mut obs, &mut info).unwrap();
        let s = b.step(&action).unwrap();
        assert_eq!((&obs, &info), (&s.observation, &s.info));
        assert_eq!(
            (t.reward, t.terminated, t.truncated),
            (s.reward, s.terminated, s.truncated)
        );
        assert_eq!(t.done(), s.done());
        if t.done() {
            break;
        }
    }
    assert!(a.pos.abs() >= 3, "the walk ended");
    // Errors are step's.
    assert!(matches!(
        a.step_into(&7, &mut obs, &mut info),
        Err(Error::InvalidAction(_))
    ));
}
