//! A user's own pyo3 module: two Rust envs exported as `gymnasium.Env`, one call each.
//!
//! * `make_corridor(length)`: a small env that has nothing to do with robosuite (Dict
//!   observation with a Discrete and a Box, Discrete actions).
//! * `make_lift_stack(horizon, repeat)`: a custom wrapper stack over robosuite's Lift
//!   (a user-written action-repeat wrapper, then adapters' GymWrapper flattening).

use gym_core::spaces::{BoxSpace, DictSpace, Discrete};
use gym_core::{
    AnySpace, DictValue, Env, EnvRng, Error, Info, IntoBoxedEnv, ResetOptions, Result, Step,
    StepWrapper, Steps, Value, Wrapper, entropy_seed, rng_from_seed,
};
use ndarray::{ArrayD, IxDyn};
use pyo3::prelude::*;
use rand::RngExt;
use robosuite_env::EnvConfig;

/// Walk left (0) or right (1) along a corridor to its end; the start is random.
pub struct Corridor {
    length: i64,
    position: i64,
    steps: u64,
    rng: EnvRng,
    seeded: bool,
    observation_space: DictSpace,
    action_space: Discrete,
}

impl Corridor {
    /// A corridor of `length` cells.
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a length below 2.
    pub fn new(length: i64) -> Result<Self> {
        if length < 2 {
            return Err(Error::invalid_argument(
                "length",
                format!("must be at least 2, got {length}"),
            ));
        }
        let observation_space = DictSpace::new([
            ("position", AnySpace::Discrete(Discrete::new(length)?)),
            ("distance", BoxSpace::<f32>::uniform(0.0, 1.0, &[1])?.into()),
        ])?;
        Ok(Self {
            length,
            position: 0,
            steps: 0,
            rng: rng_from_seed(0),
            seeded: false,
            observation_space,
            action_space: Discrete::new(2)?,
        })
    }

    fn observation(&self) -> DictValue {
        let distance = (self.length - 1 - self.position) as f32 / (self.length - 1) as f32;
        let mut obs = DictValue::new();
        obs.insert("position".into(), Value::Discrete(self.position));
        obs.insert(
            "distance".into(),
            ArrayD::from_shape_vec(IxDyn(&[1]), vec![distance])
                .expect("shape")
                .into(),
        );
        obs
    }
}

impl Env for Corridor {
    type Obs = DictValue;
    type Act = i64;
    type ObsSpace = DictSpace;
    type ActSpace = Discrete;

    fn observation_space(&self) -> &DictSpace {
        &self.observation_space
    }
    fn action_space(&self) -> &Discrete {
        &self.action_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        _options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        if let Some(s) = seed {
            self.rng = rng_from_seed(s);
        } else if !self.seeded {
            self.rng = rng_from_seed(entropy_seed());
        }
        self.seeded = true;
        self.position = self.rng.random_range(0..self.length - 1);
        self.steps = 0;
        Ok((self.observation(), Info::new()))
    }
    fn step(&mut self, action: &i64) -> Result<Step<DictValue>> {
        let delta = match action {
            0 => -1,
            1 => 1,
            other => {
                return Err(Error::invalid_action(format!(
                    "expected 0 (left) or 1 (right), got {other}"
                )));
            }
        };
        self.position = (self.position + delta).clamp(0, self.length - 1);
        self.steps += 1;
        let terminated = self.position == self.length - 1;
        let truncated = !terminated && self.steps >= 4 * self.length as u64;
        let reward = if terminated { 1.0 } else { -0.01 };
        Ok(Step {
            observation: self.observation(),
            reward,
            terminated,
            truncated,
            info: Info::new().with("steps", self.steps),
        })
    }
    fn rng(&self) -> Option<&EnvRng> {
        Some(&self.rng)
    }
}

/// A user-written wrapper: repeats each action `repeat` times and sums the rewards.
pub struct ActionRepeat<E: Env> {
    env: E,
    repeat: usize,
}

impl<E: Env> Wrapper for ActionRepeat<E> {
    type Inner = E;
    type Kind = Steps;
    fn inner(&self) -> &E {
        &self.env
    }
    fn inner_mut(&mut self) -> &mut E {
        &mut self.env
    }
    fn into_inner(self) -> E {
        self.env
    }
}

/// Only `step` changes; everything else forwards to the inner environment.
impl<E: Env> StepWrapper for ActionRepeat<E> {
    fn step(this: &mut Self, action: &E::Act) -> Result<Step<E::Obs>> {
        let mut total = 0.0;
        let mut step = this.env.step(action)?;
        total += step.reward;
        for _ in 1..this.repeat {
            if step.terminated || step.truncated {
                break;
            }
            step = this.env.step(action)?;
            total += step.reward;
        }
        step.reward = total;
        Ok(step)
    }
}

/// The corridor as a `gymnasium.Env`.
#[pyfunction]
#[pyo3(signature = (length=8))]
fn make_corridor(py: Python<'_>, length: i64) -> PyResult<Py<PyAny>> {
    let env = Corridor::new(length).map_err(robosuite_py::to_pyerr)?;
    robosuite_py::export_env(py, env.boxed())
}

/// Lift → ActionRepeat → GymWrapper (flat `float32` observations), as a `gymnasium.Env`.
#[pyfunction]
#[pyo3(signature = (horizon=100, repeat=2))]
fn make_lift_stack(py: Python<'_>, horizon: u64, repeat: usize) -> PyResult<Py<PyAny>> {
    let build = || -> Result<gym_core::BoxedEnv> {
        let lift = robosuite_env::make_with("Lift", EnvConfig::default().with_horizon(horizon))?;
        let stack = ActionRepeat {
            env: lift,
            repeat: repeat.max(1),
        };
        Ok(adapters::GymWrapper::new(stack, None, true)?.boxed())
    };
    robosuite_py::export_env(py, build().map_err(robosuite_py::to_pyerr)?)
}

/// The module.
#[pymodule(name = "_native")]
fn my_envs(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(make_corridor, m)?)?;
    m.add_function(wrap_pyfunction!(make_lift_stack, m)?)?;
    Ok(())
}
