//! How to check your own environment: `check_env` (Gymnasium's checks, plus the Rust
//! ones) and the property suite (random seeds and action sequences, shrunk to a minimal
//! failure).
//!
//! ```text
//! cargo run -p conformance-tests --example check_my_env
//! ```

use conformance_tests::prop::{EpisodeEndSpec, FnStateHook, PropConfig, prop_check_env_with_state};
use conformance_tests::{CheckOptions, check_env};
use gym_core::{
    BoxSpace, Discrete, Env, EnvRng, Error, Info, IntoBoxedEnv, ResetOptions, Result, Space, Step,
    entropy_seed, rng_from_seed,
};
use ndarray::{ArrayD, arr1};
use rand::RngExt;

/// A room to keep at 21 °C: observation `[temperature]` in `[0, 40]`, action `Discrete(3)`
/// (cool, off, heat), reward `-|temperature - 21|`, 48 steps per episode.
#[derive(Debug)]
struct Thermostat {
    observation_space: BoxSpace<f32>,
    action_space: Discrete,
    rng: Option<EnvRng>,
    temperature: f32,
    t: u64,
    running: bool,
}

/// Everything that determines what the room does next.
#[derive(Debug, Clone, PartialEq)]
struct ThermostatState {
    temperature: f32,
    t: u64,
    running: bool,
    rng: Option<EnvRng>,
}

impl Thermostat {
    fn new() -> Self {
        Self {
            observation_space: BoxSpace::uniform(0.0, 40.0, &[1]).expect("valid bounds"),
            action_space: Discrete::new(3).expect("n > 0"),
            rng: None,
            temperature: 21.0,
            t: 0,
            running: false,
        }
    }

    fn obs(&self) -> ArrayD<f32> {
        arr1(&[self.temperature]).into_dyn()
    }

    fn state(&self) -> ThermostatState {
        ThermostatState {
            temperature: self.temperature,
            t: self.t,
            running: self.running,
            rng: self.rng.clone(),
        }
    }

    fn set_state(&mut self, s: &ThermostatState) {
        self.temperature = s.temperature;
        self.t = s.t;
        self.running = s.running;
        self.rng = s.rng.clone();
    }
}

impl Env for Thermostat {
    type Obs = ArrayD<f32>;
    type Act = i64;
    type ObsSpace = BoxSpace<f32>;
    type ActSpace = Discrete;

    fn observation_space(&self) -> &BoxSpace<f32> {
        &self.observation_space
    }

    fn action_space(&self) -> &Discrete {
        &self.action_space
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        // Seed the RNG on `Some(seed)`, continue its stream on `None` (Gymnasium's rule).
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        self.temperature = rng.random_range(15.0f32..27.0);
        self.t = 0;
        self.running = true;
        Ok((self.obs(), Info::new()))
    }

    fn step(&mut self, action: &i64) -> Result<Step<ArrayD<f32>>> {
        if !self.running {
            return Err(Error::EpisodeEnded);
        }
        // Actions outside the space are a typed error, and change nothing.
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} is not in Discrete(3)"
            )));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        let drift: f32 = rng.random_range(-0.2..0.2);
        self.temperature =
            (self.temperature + (*action as f32 - 1.0) * 0.5 + drift).clamp(0.0, 40.0);
        self.t += 1;
        let truncated = self.t >= 48;
        self.running = !truncated;
        Ok(Step {
            observation: self.obs(),
            reward: -f64::from((self.temperature - 21.0).abs()),
            terminated: false,
            truncated,
            info: Info::new().with("heating", *action == 2),
        })
    }

    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

fn main() {
    // 1. Gymnasium's check_env, check by check. Warnings are kept apart from failures.
    let options = CheckOptions::default().name("Thermostat");
    match check_env(&mut Thermostat::new(), &options) {
        Ok(report) => println!("{report}"),
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(1);
        }
    }

    // The same checks on the dynamic form (what a registry or Python sees).
    if let Err(e) = check_env(&mut Thermostat::new().boxed(), &options) {
        eprintln!("boxed: {e}");
        std::process::exit(1);
    }

    // 2. The property suite: random seeds and action sequences; a failure is shrunk to a
    // minimal seed and action sequence. The episode-end rules and a state hook are optional.
    let config = PropConfig {
        cases: 64,
        ..PropConfig::default()
    }
    .episode_end(EpisodeEndSpec {
        truncate_at: Some(48),
        can_terminate: false,
    });
    let hook = FnStateHook::new(
        |env: &Thermostat| Ok(env.state()),
        |env: &mut Thermostat, s: &ThermostatState| {
            env.set_state(s);
            Ok(())
        },
    );
    match prop_check_env_with_state(Thermostat::new, &hook, &config) {
        Ok(report) => println!("properties passed: {:?}", report.passed),
        Err(failure) => {
            eprintln!("{failure}");
            std::process::exit(1);
        }
    }
}
