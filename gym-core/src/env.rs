//! The [`Env`] trait (Gymnasium's `gymnasium.Env`) and what `step` returns.

use crate::error::Result;
use crate::info::{Info, ResetOptions};
use crate::rng::EnvRng;
use crate::row::ObsRow;
use crate::space::{DynSpace, Flatten};
use ndarray::{Array2, Array3};
use std::any::Any;

/// What one `step` returns (Gymnasium's 5-tuple).
#[derive(Debug, Clone, PartialEq)]
#[must_use]
pub struct Step<O> {
    /// The observation after the action.
    pub observation: O,
    /// The reward for the transition.
    pub reward: f64,
    /// The episode reached a terminal state of the MDP (do not bootstrap).
    pub terminated: bool,
    /// The episode was cut short outside the MDP, usually by a time limit (bootstrap).
    pub truncated: bool,
    /// Diagnostics, such as `success`.
    pub info: Info,
}

impl<O> Step<O> {
    /// Whether the episode is over (`terminated || truncated`).
    pub fn done(&self) -> bool {
        self.terminated || self.truncated
    }

    /// The same step with the observation mapped.
    pub fn map_observation<P>(self, f: impl FnOnce(O) -> P) -> Step<P> {
        Step {
            observation: f(self.observation),
            reward: self.reward,
            terminated: self.terminated,
            truncated: self.truncated,
            info: self.info,
        }
    }

    /// The same step with the observation mapped by a fallible function.
    ///
    /// # Errors
    /// Whatever `f` returns.
    pub fn try_map_observation<P, E>(
        self,
        f: impl FnOnce(O) -> Result<P, E>,
    ) -> Result<Step<P>, E> {
        Ok(Step {
            observation: f(self.observation)?,
            reward: self.reward,
            terminated: self.terminated,
            truncated: self.truncated,
            info: self.info,
        })
    }
}

/// The reward and end flags of one step: what [`Env::step_into`] returns besides the
/// observation and info it writes into the caller's buffers.
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use]
pub struct Transition {
    /// The reward for the transition.
    pub reward: f64,
    /// The episode reached a terminal state of the MDP (do not bootstrap).
    pub terminated: bool,
    /// The episode was cut short outside the MDP, usually by a time limit (bootstrap).
    pub truncated: bool,
}

impl Transition {
    /// Whether the episode is over (`terminated || truncated`).
    pub fn done(&self) -> bool {
        self.terminated || self.truncated
    }
}

/// How an environment can be rendered (Gymnasium's `render_mode` strings).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RenderMode {
    /// Shown to a person; `render` returns nothing.
    Human,
    /// An RGB image, `u8` of shape `(height, width, 3)`.
    RgbArray,
    /// A depth image, `f32` of shape `(height, width)`.
    DepthArray,
    /// Text.
    Ansi,
}

impl RenderMode {
    /// Gymnasium's name of the mode (`"rgb_array"`, ...).
    pub fn as_str(self) -> &'static str {
        match self {
            RenderMode::Human => "human",
            RenderMode::RgbArray => "rgb_array",
            RenderMode::DepthArray => "depth_array",
            RenderMode::Ansi => "ansi",
        }
    }
}

/// One rendered frame.
#[derive(Debug, Clone, PartialEq)]
pub enum Frame {
    /// An RGB image, `(height, width, 3)`.
    Rgb(Array3<u8>),
    /// A depth image, `(height, width)`.
    Depth(Array2<f32>),
    /// Text.
    Ansi(String),
}

/// Gymnasium's `metadata`: render modes and frame rate.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Metadata {
    /// The render modes the environment supports.
    pub render_modes: Vec<RenderMode>,
    /// Frames per second of rendering (for robosuite tasks, the control frequency).
    pub render_fps: Option<f64>,
}

impl Metadata {
    /// No render modes, no frame rate.
    pub const fn empty() -> Self {
        Self {
            render_modes: Vec::new(),
            render_fps: None,
        }
    }
}

static NO_METADATA: Metadata = Metadata::empty();

/// A reinforcement-learning environment with Gymnasium 1.x semantics.
///
/// * `reset(seed, options)`: `Some(seed)` re-seeds the environment's RNG; `None` continues
///   its stream (and seeds it from entropy on the very first reset), as in Gymnasium.
/// * `step(action)` returns a [`Step`]; after `terminated || truncated` the caller must
///   `reset`. A step after the end should be refused with
///   [`Error::EpisodeEnded`](crate::Error::EpisodeEnded) (robosuite-env's tasks do, as
///   robosuite raises); an environment that accepts it must keep reporting the episode as
///   ended (Gymnasium's `TimeLimit` keeps answering `truncated`). Before the first `reset`,
///   `step` answers [`Error::ResetNeeded`](crate::Error::ResetNeeded).
/// * Invalid actions are a typed error ([`Error::InvalidAction`](crate::Error::InvalidAction)),
///   never a panic, and leave the environment usable.
/// * `close` is idempotent.
///
/// An environment is `Send + 'static`, so a whole wrapper stack can move to another thread.
///
/// Only the spaces, `reset` and `step` are required; everything else has a default (a plain
/// environment is its own [`Env::unwrapped_any`]).
pub trait Env: AsAny + Send + 'static {
    /// The observation type.
    type Obs: Clone + std::fmt::Debug + Send + 'static;
    /// The action type.
    type Act: Clone + std::fmt::Debug + Send + 'static;
    /// The observation space (flattenable and convertible to the dynamic layer, as every
    /// Gymnasium space is).
    type ObsSpace: Flatten<Element = Self::Obs> + DynSpace;
    /// The action space.
    type ActSpace: Flatten<Element = Self::Act> + DynSpace;

    /// The space observations lie in.
    fn observation_space(&self) -> &Self::ObsSpace;

    /// The space actions must lie in.
    fn action_space(&self) -> &Self::ActSpace;

    /// Starts a new episode.
    ///
    /// # Errors
    /// Environment-specific: invalid options, a failed placement, a closed environment.
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)>;

    /// Applies one action.
    ///
    /// # Errors
    /// [`Error::InvalidAction`](crate::Error::InvalidAction) for an action outside the
    /// space; [`Error::ResetNeeded`](crate::Error::ResetNeeded) /
    /// [`Error::EpisodeEnded`](crate::Error::EpisodeEnded) when called out of order.
    fn step(&mut self, action: &Self::Act) -> Result<Step<Self::Obs>>;

    /// [`Env::step`] into buffers the caller keeps: the observation is written into
    /// `observation` and the diagnostics into `info` (both replaced), the reward and end
    /// flags are returned. The semantics are `step`'s; after an error the buffers hold
    /// unspecified values.
    ///
    /// The default moves the result of `step` into the buffers. Environments that can reuse
    /// the buffers' storage override it so that stepping in a loop does not allocate
    /// (robosuite-env's tasks, and adapters' `FlatGymWrapper` over them).
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step_into(
        &mut self,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        let step = self.step(action)?;
        *observation = step.observation;
        *info = step.info;
        Ok(Transition {
            reward: step.reward,
            terminated: step.terminated,
            truncated: step.truncated,
        })
    }

    /// Whether [`Env::step_for_row`] and [`Env::write_observation_row`] are supported:
    /// the environment can write its observation straight into a row of a vector
    /// environment's batch (no copy into a buffer of its own first). `false` by default.
    fn writes_rows(&self) -> bool {
        false
    }

    /// [`Env::step`] that keeps the observation in the environment, for
    /// [`Env::write_observation_row`] to write into a row of a batch; the info is written
    /// into `info`, the reward and end flags are returned.
    ///
    /// # Errors
    /// As [`Env::step`]; [`Error::Unsupported`](crate::Error::Unsupported) when [`Env::writes_rows`] is `false`.
    fn step_for_row(&mut self, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        let _ = (action, info);
        Err(crate::Error::unsupported(
            "this environment does not write observations into batch rows",
        ))
    }

    /// Writes the observation of the last [`Env::step_for_row`] into `row`, one leaf per
    /// array of the observation in the space's order (see [`ObsRow`]), converting to the
    /// leaves' dtypes.
    ///
    /// # Errors
    /// [`Error::Contract`](crate::Error::Contract) when the row does not have the observation's leaves;
    /// [`Error::Unsupported`](crate::Error::Unsupported) when [`Env::writes_rows`] is `false`.
    fn write_observation_row(&self, row: &mut ObsRow<'_>) -> Result<()> {
        let _ = row;
        Err(crate::Error::unsupported(
            "this environment does not write observations into batch rows",
        ))
    }

    /// Render modes and frame rate.
    fn metadata(&self) -> &Metadata {
        &NO_METADATA
    }

    /// The render mode chosen at construction, if any.
    fn render_mode(&self) -> Option<RenderMode> {
        None
    }

    /// Renders a frame in the chosen render mode (`None` without one).
    ///
    /// # Errors
    /// Environment-specific rendering failures.
    fn render(&mut self) -> Result<Option<Frame>> {
        Ok(None)
    }

    /// Releases resources; calling it twice is allowed and does nothing the second time.
    fn close(&mut self) {}

    /// The environment's RNG (Gymnasium's `np_random`), for checking that seeding works.
    fn rng(&self) -> Option<&EnvRng> {
        None
    }

    /// The innermost environment as `Any` (Gymnasium's `env.unwrapped`): the environment
    /// itself by default; wrappers forward it to their inner environment. See
    /// [`EnvExt::unwrapped_as`].
    fn unwrapped_any(&self) -> &dyn Any {
        self.as_any()
    }

    /// Mutable form of [`Env::unwrapped_any`].
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any {
        self.as_any_mut()
    }
}

/// A value as `Any`, for every sized `'static` type: what [`Env::unwrapped_any`] returns by
/// default (a provided method cannot turn `self` into a trait object by itself).
pub trait AsAny: Any {
    /// `self` as `&dyn Any`.
    fn as_any(&self) -> &dyn Any;
    /// `self` as `&mut dyn Any`.
    fn as_any_mut(&mut self) -> &mut dyn Any;
}

impl<T: Any> AsAny for T {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

/// Conveniences on every [`Env`].
pub trait EnvExt: Env {
    /// The innermost environment, if it has type `T` (Gymnasium's `env.unwrapped`).
    fn unwrapped_as<T: 'static>(&self) -> Option<&T> {
        self.unwrapped_any().downcast_ref()
    }

    /// Mutable form of [`EnvExt::unwrapped_as`].
    fn unwrapped_as_mut<T: 'static>(&mut self) -> Option<&mut T> {
        self.unwrapped_any_mut().downcast_mut()
    }
}

impl<E: Env + ?Sized> EnvExt for E {}
