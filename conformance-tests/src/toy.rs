//! Small environments that pass every check: references for the broken environments in
//! [`broken`](crate::broken), for the documentation, and for testing the checker itself.
//!
//! * [`PointMass`]: a 1-D point mass pushed by a force in `[-1, 1]`, Box observations and
//!   actions, noise from the seeded RNG, no terminal states and a horizon reported as
//!   truncation (like a robosuite task), a `"position"` reset option, `ansi` rendering,
//!   and state get/set.
//! * [`GridWorld`]: Gymnasium's tutorial grid world, a Dict observation of two `int64`
//!   Boxes, a Discrete action, termination on reaching the target and a horizon.

use crate::options::ResetOptionsProbe;
use crate::prop::StateHook;
use gym_core::{
    BoxSpace, DictSpace, DictValue, Discrete, Env, EnvRng, Error, Frame, Info, InfoValue, Metadata,
    RenderMode, ResetOptions, Result, Space, Step, Value, entropy_seed, rng_from_seed,
};
use ndarray::{ArrayD, arr1};
use rand::RngExt;

/// The complete state of a [`PointMass`], for [`PointMass::get_state`] and
/// [`PointMass::set_state`].
#[derive(Debug, Clone, PartialEq)]
pub struct PointMassState {
    /// Position, in `[-10, 10]`.
    pub position: f32,
    /// Velocity, in `[-10, 10]`.
    pub velocity: f32,
    /// Steps since the last reset.
    pub t: u64,
    /// Whether the episode has ended.
    pub ended: bool,
    /// The RNG, so a restored state replays the same noise.
    pub rng: EnvRng,
}

/// A point mass on a line: observation `[position, velocity]` in `[-10, 10]²` (`float32`),
/// action a force in `[-1, 1]` (`float32`, shape `[1]`).
///
/// Each step: `velocity += 0.5·force + noise` with noise uniform in `±0.05` from the
/// seeded RNG, `position += 0.1·velocity`, both clipped to `[-10, 10]`; reward
/// `-0.01·position²`. No terminal states; `truncated` at the horizon (default 50).
/// Finite out-of-bounds forces are clipped; NaN, ±inf and wrong shapes are
/// [`Error::InvalidAction`]. `reset` takes an optional `"position"` in `[-5, 5]`.
#[derive(Debug, Clone)]
pub struct PointMass {
    pub(crate) observation_space: BoxSpace<f32>,
    pub(crate) action_space: BoxSpace<f32>,
    pub(crate) horizon: u64,
    pub(crate) rng: Option<EnvRng>,
    pub(crate) position: f32,
    pub(crate) velocity: f32,
    pub(crate) t: u64,
    pub(crate) started: bool,
    pub(crate) ended: bool,
    pub(crate) closed: bool,
    pub(crate) render_mode: Option<RenderMode>,
    pub(crate) metadata: Metadata,
}

impl Default for PointMass {
    fn default() -> Self {
        Self::new()
    }
}

impl PointMass {
    /// A point mass with horizon 50 and no render mode.
    pub fn new() -> Self {
        Self {
            observation_space: BoxSpace::uniform(-10.0, 10.0, &[2]).expect("valid bounds"),
            action_space: BoxSpace::uniform(-1.0, 1.0, &[1]).expect("valid bounds"),
            horizon: 50,
            rng: None,
            position: 0.0,
            velocity: 0.0,
            t: 0,
            started: false,
            ended: false,
            closed: false,
            render_mode: None,
            metadata: Metadata {
                render_modes: vec![RenderMode::Ansi],
                render_fps: Some(10.0),
            },
        }
    }

    /// The same with another horizon (at least 1).
    #[must_use]
    pub fn with_horizon(mut self, horizon: u64) -> Self {
        self.horizon = horizon.max(1);
        self
    }

    /// The same, rendering in `mode` (only [`RenderMode::Ansi`] is declared).
    #[must_use]
    pub fn with_render_mode(mut self, mode: RenderMode) -> Self {
        self.render_mode = Some(mode);
        self
    }

    /// The horizon: `truncated` is reported at this step.
    pub fn horizon(&self) -> u64 {
        self.horizon
    }

    pub(crate) fn observation(&self) -> ArrayD<f32> {
        arr1(&[self.position, self.velocity]).into_dyn()
    }

    pub(crate) fn info(&self) -> Info {
        Info::new()
            .with("t", self.t)
            .with("distance", f64::from(self.position.abs()))
    }

    /// The complete state.
    ///
    /// # Errors
    /// [`Error::ResetNeeded`] before the first reset.
    pub fn get_state(&self) -> Result<PointMassState> {
        let rng = self.rng.clone().ok_or(Error::ResetNeeded)?;
        Ok(PointMassState {
            position: self.position,
            velocity: self.velocity,
            t: self.t,
            ended: self.ended,
            rng,
        })
    }

    /// Restores a state from [`PointMass::get_state`].
    ///
    /// # Errors
    /// [`Error::InvalidArgument`] for a position or velocity outside `[-10, 10]`.
    pub fn set_state(&mut self, state: &PointMassState) -> Result<()> {
        for (name, v) in [("position", state.position), ("velocity", state.velocity)] {
            if !(-10.0..=10.0).contains(&v) {
                return Err(Error::invalid_argument(
                    name,
                    format!("{v} is outside [-10, 10]"),
                ));
            }
        }
        self.position = state.position;
        self.velocity = state.velocity;
        self.t = state.t;
        self.ended = state.ended;
        self.rng = Some(state.rng.clone());
        self.started = true;
        Ok(())
    }

    /// Reads the `"position"` option, refusing unknown keys.
    pub(crate) fn start_position(options: Option<&ResetOptions>) -> Result<Option<f32>> {
        let Some(options) = options else {
            return Ok(None);
        };
        let mut position = None;
        for (k, v) in options.iter() {
            match (k, v) {
                ("position", InfoValue::Float(x)) => position = Some(*x),
                ("position", InfoValue::Int(x)) => position = Some(*x as f64),
                ("position", other) => {
                    return Err(Error::invalid_argument(
                        "position",
                        format!("expected a number, got a {}", other.kind()),
                    ));
                }
                (other, _) => {
                    return Err(Error::UnknownKey {
                        key: other.to_owned(),
                        available: vec!["position".into()],
                    });
                }
            }
        }
        match position {
            Some(p) if !(-5.0..=5.0).contains(&p) => Err(Error::invalid_argument(
                "position",
                format!("{p} is outside [-5, 5]"),
            )),
            p => Ok(p.map(|p| p as f32)),
        }
    }

    pub(crate) fn check_usable(&self) -> Result<()> {
        if self.closed {
            Err(Error::Closed)
        } else if !self.started {
            Err(Error::ResetNeeded)
        } else if self.ended {
            Err(Error::EpisodeEnded)
        } else {
            Ok(())
        }
    }

    /// Validates a force: shape `[1]` and finite; clipped into `[-1, 1]`.
    pub(crate) fn force(action: &ArrayD<f32>) -> Result<f32> {
        if action.shape() != [1] {
            return Err(Error::invalid_action(format!(
                "expected an action of shape [1], got shape {:?}",
                action.shape()
            )));
        }
        let f = action.iter().next().copied().unwrap_or(f32::NAN);
        if !f.is_finite() {
            return Err(Error::invalid_action(format!(
                "the force is {f}; actions must be finite"
            )));
        }
        Ok(f.clamp(-1.0, 1.0))
    }

    /// One step of the dynamics with a validated force.
    pub(crate) fn advance(&mut self, force: f32) -> Step<ArrayD<f32>> {
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        let noise = (rng.random::<f32>() - 0.5) * 0.1;
        self.velocity = (self.velocity + 0.5 * force + noise).clamp(-10.0, 10.0);
        self.position = (self.position + 0.1 * self.velocity).clamp(-10.0, 10.0);
        self.t += 1;
        let truncated = self.t >= self.horizon;
        self.ended = truncated;
        Step {
            observation: self.observation(),
            reward: -0.01 * f64::from(self.position).powi(2),
            terminated: false,
            truncated,
            info: self.info(),
        }
    }
}

impl Env for PointMass {
    type Obs = ArrayD<f32>;
    type Act = ArrayD<f32>;
    type ObsSpace = BoxSpace<f32>;
    type ActSpace = BoxSpace<f32>;

    fn observation_space(&self) -> &BoxSpace<f32> {
        &self.observation_space
    }

    fn action_space(&self) -> &BoxSpace<f32> {
        &self.action_space
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(ArrayD<f32>, Info)> {
        if self.closed {
            return Err(Error::Closed);
        }
        let start = Self::start_position(options)?;
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        self.position = start.unwrap_or_else(|| rng.random_range(-1.0f32..1.0));
        self.velocity = 0.0;
        self.t = 0;
        self.started = true;
        self.ended = false;
        Ok((self.observation(), self.info()))
    }

    fn step(&mut self, action: &ArrayD<f32>) -> Result<Step<ArrayD<f32>>> {
        self.check_usable()?;
        let force = Self::force(action)?;
        Ok(self.advance(force))
    }

    fn metadata(&self) -> &Metadata {
        &self.metadata
    }

    fn render_mode(&self) -> Option<RenderMode> {
        self.render_mode
    }

    fn render(&mut self) -> Result<Option<Frame>> {
        match self.render_mode {
            None => Ok(None),
            Some(RenderMode::Ansi) => Ok(Some(Frame::Ansi(format!(
                "t={} position={:.3} velocity={:.3}",
                self.t, self.position, self.velocity
            )))),
            Some(m) => Err(Error::unsupported(format!("render mode {}", m.as_str()))),
        }
    }

    fn close(&mut self) {
        self.closed = true;
    }

    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}

/// [`StateHook`] for [`PointMass`] (and a [`gym_core::BoxedEnv`] or wrapper stack over one,
/// through [`PointMassState`] on the unwrapped environment).
#[derive(Debug, Clone, Copy, Default)]
pub struct PointMassStateHook;

impl<E: Env> StateHook<E> for PointMassStateHook {
    type State = PointMassState;

    fn get_state(&self, env: &E) -> Result<PointMassState> {
        env.unwrapped_any()
            .downcast_ref::<PointMass>()
            .ok_or_else(|| Error::unsupported("the unwrapped environment is not a PointMass"))?
            .get_state()
    }

    fn set_state(&self, env: &mut E, state: &PointMassState) -> Result<()> {
        env.unwrapped_any_mut()
            .downcast_mut::<PointMass>()
            .ok_or_else(|| Error::unsupported("the unwrapped environment is not a PointMass"))?
            .set_state(state)
    }
}

/// A probe for [`CheckOptions`](crate::CheckOptions): `reset(options={"position": x})`
/// must start the point mass at `x` (the first observation entry).
pub fn position_probe(x: f64) -> ResetOptionsProbe {
    ResetOptionsProbe::new(
        "position",
        Info::new().with("position", x),
        move |obs, _| {
            let first = obs.as_array().and_then(|a| a.to_f64_vec().first().copied());
            match first {
                Some(p) if (p - x).abs() < 1e-6 => Ok(()),
                Some(p) => Err(format!(
                    "the observation starts at position {p}, expected {x}"
                )),
                None => Err(format!("the observation {obs:?} has no position")),
            }
        },
    )
}

/// Gymnasium's tutorial grid world on a `size × size` grid: observation
/// `{"agent": [x, y], "target": [x, y]}` (`int64` Boxes in `[0, size - 1]`), action
/// `Discrete(4)` (right, up, left, down). Reward 1 and `terminated` on reaching the target;
/// `truncated` at the horizon (default 20).
#[derive(Debug, Clone)]
pub struct GridWorld {
    size: i64,
    horizon: u64,
    observation_space: DictSpace,
    action_space: Discrete,
    rng: Option<EnvRng>,
    agent: [i64; 2],
    target: [i64; 2],
    t: u64,
    started: bool,
    ended: bool,
}

impl Default for GridWorld {
    fn default() -> Self {
        Self::new(5)
    }
}

impl GridWorld {
    /// A grid of `size × size` cells (at least 2), horizon 20.
    pub fn new(size: i64) -> Self {
        let size = size.max(2);
        let cell = || -> gym_core::AnySpace {
            BoxSpace::<i64>::uniform(0.0, (size - 1) as f64, &[2])
                .expect("valid bounds")
                .into()
        };
        Self {
            size,
            horizon: 20,
            observation_space: DictSpace::new([("agent", cell()), ("target", cell())])
                .expect("unique keys"),
            action_space: Discrete::new(4).expect("n > 0"),
            rng: None,
            agent: [0, 0],
            target: [0, 0],
            t: 0,
            started: false,
            ended: false,
        }
    }

    /// The same with another horizon (at least 1).
    #[must_use]
    pub fn with_horizon(mut self, horizon: u64) -> Self {
        self.horizon = horizon.max(1);
        self
    }

    fn observation(&self) -> DictValue {
        let cell = |c: [i64; 2]| Value::from(arr1(&c).into_dyn());
        [
            ("agent".to_owned(), cell(self.agent)),
            ("target".to_owned(), cell(self.target)),
        ]
        .into_iter()
        .collect()
    }

    fn info(&self) -> Info {
        Info::new().with(
            "distance",
            (self.agent[0] - self.target[0]).abs() + (self.agent[1] - self.target[1]).abs(),
        )
    }
}

impl Env for GridWorld {
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
        options: Option<&ResetOptions>,
    ) -> Result<(DictValue, Info)> {
        if let Some(key) = options.and_then(|o| o.keys().next()) {
            return Err(Error::UnknownKey {
                key: key.to_owned(),
                available: Vec::new(),
            });
        }
        if let Some(s) = seed {
            self.rng = Some(rng_from_seed(s));
        }
        let rng = self
            .rng
            .get_or_insert_with(|| rng_from_seed(entropy_seed()));
        let n = self.size;
        self.agent = [rng.random_range(0..n), rng.random_range(0..n)];
        self.target = self.agent;
        while self.target == self.agent {
            self.target = [rng.random_range(0..n), rng.random_range(0..n)];
        }
        self.t = 0;
        self.started = true;
        self.ended = false;
        Ok((self.observation(), self.info()))
    }

    fn step(&mut self, action: &i64) -> Result<Step<DictValue>> {
        if !self.started {
            return Err(Error::ResetNeeded);
        }
        if self.ended {
            return Err(Error::EpisodeEnded);
        }
        if !self.action_space.contains(action) {
            return Err(Error::invalid_action(format!(
                "{action} is not in Discrete(4)"
            )));
        }
        let [dx, dy] = match action {
            0 => [1, 0],
            1 => [0, 1],
            2 => [-1, 0],
            _ => [0, -1],
        };
        self.agent = [
            (self.agent[0] + dx).clamp(0, self.size - 1),
            (self.agent[1] + dy).clamp(0, self.size - 1),
        ];
        self.t += 1;
        let terminated = self.agent == self.target;
        let truncated = self.t >= self.horizon;
        self.ended = terminated || truncated;
        Ok(Step {
            observation: self.observation(),
            reward: if terminated { 1.0 } else { 0.0 },
            terminated,
            truncated,
            info: self.info(),
        })
    }

    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}
