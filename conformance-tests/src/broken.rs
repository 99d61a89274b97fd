//! Deliberately broken environments, one [`Defect`] each, and the check or property that
//! catches it ([`Defect::caught_by`]). They document what each check guards against and
//! test that every check catches its defect.
//!
//! [`BrokenEnv`] is a dynamic version of [`PointMass`] (observations
//! and actions are [`Value`]s, so it can return a wrong dtype) with one defect switched
//! on; [`SharedBufferEnv`] returns observations that share a buffer the environment keeps
//! writing into.
//!
//! ```
//! use conformance_tests::broken::{BrokenEnv, Caught, Defect};
//! use conformance_tests::{check_env, Check};
//!
//! let mut env = BrokenEnv::new(Defect::NanReward);
//! let err = check_env(&mut env, &BrokenEnv::check_options()).unwrap_err();
//! assert_eq!(err.check(), Check::RewardFinite);
//! assert_eq!(Defect::NanReward.caught_by(), Some(Caught::Check(Check::RewardFinite)));
//! ```

use crate::options::CheckOptions;
use crate::prop::{EpisodeEndSpec, PropConfig, Property, StateHook};
use crate::report::Check;
use crate::toy::{PointMass, PointMassState, position_probe};
use gym_core::{
    AnyBox, AnySpace, ArrayValue, BoxSpace, DType, DictSpace, DictValue, DynSpace, Env, EnvRng,
    Error, Flatten, Frame, Info, Metadata, RenderMode, ResetOptions, Result, Space, SpaceError,
    Step, TupleSpace, Value, rng_from_seed,
};
use ndarray::{ArrayD, IxDyn, arr1};
use rand::RngExt;
use std::sync::{Arc, Mutex, PoisonError};

/// Where a defect is caught.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Caught {
    /// By [`check_env`](crate::check_env), failing this check first.
    Check(Check),
    /// By the property suite ([`prop`](crate::prop)), failing this property.
    Property(Property),
}

/// One defect of a [`BrokenEnv`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Defect {
    /// No defect: a correct environment.
    None,
    /// Observations are `float64` arrays for a `float32` Box.
    WrongObsDtype,
    /// `reset(seed)` adds an offset that depends on how many resets came before.
    NonDeterministicReset,
    /// The position in the observation is 20, outside `[-10, 10]`.
    ObsOutsideSpace,
    /// The reward is NaN.
    NanReward,
    /// `reset(seed)` ignores the seed: the RNG is seeded once at construction.
    IgnoredSeed,
    /// `rng()` returns `None`.
    NoRng,
    /// A step after the end of the episode is accepted (and starts counting again).
    StepAfterEndAccepted,
    /// The info holds a count of calls, so two replays differ.
    InfoChangesBetweenReplays,
    /// `truncated` is reported after one step.
    TruncatesAfterOneStep,
    /// `close()` panics the second time.
    ClosePanicsTwice,
    /// `reset` with options returns an error, even for empty options.
    ResetRejectsOptions,
    /// `reset` ignores its documented `"position"` option.
    ResetIgnoresOptions,
    /// The observation space is an empty Dict.
    EmptyDictObservationSpace,
    /// The action space is an empty Tuple.
    EmptyTupleActionSpace,
    /// `step` adds noise that depends on how many calls came before, not on the seed.
    NonDeterministicStep,
    /// `step` panics on an action with NaN.
    InvalidActionPanics,
    /// `step` accepts an action with NaN (treating it as 0).
    InvalidActionAccepted,
    /// `step` rejects an action with NaN, but only after drawing from the RNG.
    InvalidActionCorruptsState,
    /// The observation space is unbounded and the velocity is `+inf`.
    ObsNotFinite,
    /// `render_mode` is `rgb_array`, which the metadata does not declare.
    UndeclaredRenderMode,
    /// From the third step of an episode on, the position is 20 (outside the space): only
    /// sequences of three steps or more show it.
    ObsEscapesLate,
    /// From the fourth step of an episode on, the velocity depends on a call count: one-step
    /// determinism holds, replays of four steps or more diverge.
    ReplayDiverges,
    /// At the horizon, `terminated` is reported along with `truncated` (robosuite's
    /// Gymnasium wrapper reports the time limit as termination).
    HorizonReportedAsTerminated,
    /// The declared horizon is 8 but `truncated` comes at step 9.
    TruncatesLate,
    /// `set_state` forgets the velocity.
    StateRoundTripLosesVelocity,
}

impl Defect {
    /// Every defect but [`Defect::None`].
    pub const ALL: [Defect; 25] = [
        Defect::WrongObsDtype,
        Defect::NonDeterministicReset,
        Defect::ObsOutsideSpace,
        Defect::NanReward,
        Defect::IgnoredSeed,
        Defect::NoRng,
        Defect::StepAfterEndAccepted,
        Defect::InfoChangesBetweenReplays,
        Defect::TruncatesAfterOneStep,
        Defect::ClosePanicsTwice,
        Defect::ResetRejectsOptions,
        Defect::ResetIgnoresOptions,
        Defect::EmptyDictObservationSpace,
        Defect::EmptyTupleActionSpace,
        Defect::NonDeterministicStep,
        Defect::InvalidActionPanics,
        Defect::InvalidActionAccepted,
        Defect::InvalidActionCorruptsState,
        Defect::ObsNotFinite,
        Defect::UndeclaredRenderMode,
        Defect::ObsEscapesLate,
        Defect::ReplayDiverges,
        Defect::HorizonReportedAsTerminated,
        Defect::TruncatesLate,
        Defect::StateRoundTripLosesVelocity,
    ];

    /// The check ([`check_env`](crate::check_env) with [`BrokenEnv::check_options`]) or the
    /// property ([`BrokenEnv::prop_config`], with [`BrokenStateHook`] for the state round
    /// trip) that catches this defect first; `None` for [`Defect::None`].
    pub fn caught_by(self) -> Option<Caught> {
        use Caught::{Check as C, Property as P};
        Some(match self {
            Defect::None => return None,
            Defect::WrongObsDtype => C(Check::ObservationDtype),
            Defect::NonDeterministicReset | Defect::IgnoredSeed | Defect::NoRng => {
                C(Check::ResetSeedDeterminism)
            }
            Defect::ObsOutsideSpace => C(Check::ObservationContained),
            Defect::NanReward => C(Check::RewardFinite),
            Defect::StepAfterEndAccepted => C(Check::StepAfterEnd),
            Defect::InfoChangesBetweenReplays | Defect::NonDeterministicStep => {
                C(Check::StepDeterminism)
            }
            Defect::TruncatesAfterOneStep => C(Check::TruncatedAfterOneStep),
            Defect::ClosePanicsTwice => C(Check::CloseTwice),
            Defect::ResetRejectsOptions | Defect::ResetIgnoresOptions => C(Check::ResetOptions),
            Defect::EmptyDictObservationSpace => C(Check::ObservationSpace),
            Defect::EmptyTupleActionSpace => C(Check::ActionSpace),
            Defect::InvalidActionPanics
            | Defect::InvalidActionAccepted
            | Defect::InvalidActionCorruptsState => C(Check::InvalidAction),
            Defect::ObsNotFinite => C(Check::ObservationFinite),
            Defect::UndeclaredRenderMode => C(Check::Render),
            Defect::ObsEscapesLate => P(Property::ObservationsInSpace),
            Defect::ReplayDiverges => P(Property::ReplayIdentical),
            Defect::HorizonReportedAsTerminated => P(Property::TerminationCause),
            Defect::TruncatesLate => P(Property::TruncationAtLimit),
            Defect::StateRoundTripLosesVelocity => P(Property::StateRoundTrip),
        })
    }
}

/// The horizon every [`BrokenEnv`] declares.
pub const HORIZON: u64 = 8;

/// A [`PointMass`] over dynamic values with one [`Defect`].
#[derive(Debug, Clone)]
pub struct BrokenEnv {
    defect: Defect,
    inner: PointMass,
    observation_space: AnySpace,
    action_space: AnySpace,
    calls: u64,
    closed_once: bool,
    metadata: Metadata,
}

impl BrokenEnv {
    /// A point mass with horizon [`HORIZON`] and `defect`.
    pub fn new(defect: Defect) -> Self {
        let mut inner = PointMass::new().with_horizon(if defect == Defect::TruncatesLate {
            HORIZON + 1
        } else {
            HORIZON
        });
        if defect == Defect::IgnoredSeed {
            inner.rng = Some(rng_from_seed(999));
        }
        if defect == Defect::UndeclaredRenderMode {
            inner.render_mode = Some(RenderMode::RgbArray);
        }
        let observation_space = match defect {
            Defect::EmptyDictObservationSpace => AnySpace::Dict(
                DictSpace::new(Vec::<(String, AnySpace)>::new()).expect("no duplicate keys"),
            ),
            Defect::ObsNotFinite => BoxSpace::<f32>::unbounded(&[2]).into(),
            _ => inner.observation_space.to_any(),
        };
        let action_space = match defect {
            Defect::EmptyTupleActionSpace => AnySpace::Tuple(TupleSpace::new(Vec::new())),
            _ => inner.action_space.to_any(),
        };
        let metadata = inner.metadata.clone();
        Self {
            defect,
            inner,
            observation_space,
            action_space,
            calls: 0,
            closed_once: false,
            metadata,
        }
    }

    /// The defect.
    pub fn defect(&self) -> Defect {
        self.defect
    }

    /// The options to check a `BrokenEnv` with: the defaults, plus the `"position"` reset
    /// option probe ([`position_probe`]).
    pub fn check_options() -> CheckOptions {
        CheckOptions::default().reset_options_probe(position_probe(2.5))
    }

    /// The property configuration for a `BrokenEnv`: horizon [`HORIZON`], no terminal
    /// states, short sequences.
    pub fn prop_config() -> PropConfig {
        PropConfig {
            cases: 24,
            max_actions: 12,
            ..PropConfig::default()
        }
        .episode_end(EpisodeEndSpec {
            truncate_at: Some(HORIZON),
            can_terminate: false,
        })
    }

    fn observation(&self, obs: &ArrayD<f32>) -> Value {
        let mut obs = obs.clone();
        let t = self.inner.t;
        match self.defect {
            Defect::EmptyDictObservationSpace => return Value::Dict(DictValue::new()),
            Defect::WrongObsDtype => return Value::from(obs.mapv(f64::from)),
            Defect::NonDeterministicReset if t == 0 => obs[[0]] += 0.001 * (self.calls % 7) as f32,
            Defect::ObsOutsideSpace => obs[[0]] = 20.0,
            Defect::ObsNotFinite => obs[[1]] = f32::INFINITY,
            Defect::ObsEscapesLate if t >= 3 => obs[[0]] = 20.0,
            Defect::NonDeterministicStep if t > 0 => {
                obs[[1]] = (obs[[1]] - 0.01 * (self.calls % 5) as f32).max(-10.0)
            }
            Defect::ReplayDiverges if t >= 4 => {
                obs[[1]] = (obs[[1]] - 0.01 * (self.calls % 5) as f32).max(-10.0)
            }
            _ => {}
        }
        Value::from(obs)
    }

    fn force(&mut self, action: &Value) -> Result<f32> {
        if self.defect == Defect::EmptyTupleActionSpace {
            return match action {
                Value::Tuple(items) if items.is_empty() => Ok(0.0),
                other => Err(Error::invalid_action(format!(
                    "expected an empty tuple, got {}",
                    other.kind()
                ))),
            };
        }
        let typed = self
            .inner
            .action_space
            .from_value(action)
            .map_err(|e| Error::invalid_action(e.to_string()))?;
        let finite = typed.iter().all(|x| x.is_finite());
        match self.defect {
            Defect::InvalidActionPanics if !finite => panic!("non-finite action {typed:?}"),
            Defect::InvalidActionAccepted if !finite => return Ok(0.0),
            Defect::InvalidActionCorruptsState if !finite => {
                if let Some(rng) = self.inner.rng.as_mut() {
                    let _: f32 = rng.random();
                }
            }
            _ => {}
        }
        PointMass::force(&typed)
    }
}

impl Env for BrokenEnv {
    type Obs = Value;
    type Act = Value;
    type ObsSpace = AnySpace;
    type ActSpace = AnySpace;

    fn observation_space(&self) -> &AnySpace {
        &self.observation_space
    }

    fn action_space(&self) -> &AnySpace {
        &self.action_space
    }

    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Value, Info)> {
        self.calls += 1;
        let seed = if self.defect == Defect::IgnoredSeed {
            None
        } else {
            seed
        };
        let options = match self.defect {
            Defect::ResetRejectsOptions if options.is_some() => {
                return Err(Error::invalid_argument(
                    "options",
                    "this environment takes no options",
                ));
            }
            Defect::ResetIgnoresOptions => None,
            _ => options,
        };
        let (obs, info) = self.inner.reset(seed, options)?;
        Ok((self.observation(&obs), info))
    }

    fn step(&mut self, action: &Value) -> Result<Step<Value>> {
        self.calls += 1;
        if self.defect == Defect::StepAfterEndAccepted && self.inner.ended {
            self.inner.ended = false;
            self.inner.t = 0;
        }
        self.inner.check_usable()?;
        let force = self.force(action)?;
        let mut step = self.inner.advance(force);
        let observation = self.observation(&step.observation);
        match self.defect {
            Defect::NanReward => step.reward = f64::NAN,
            Defect::InfoChangesBetweenReplays => {
                step.info.insert("calls", self.calls);
            }
            Defect::TruncatesAfterOneStep if self.inner.t == 1 => {
                step.truncated = true;
                self.inner.ended = true;
            }
            Defect::HorizonReportedAsTerminated if step.truncated => step.terminated = true,
            _ => {}
        }
        Ok(Step {
            observation,
            reward: step.reward,
            terminated: step.terminated,
            truncated: step.truncated,
            info: step.info,
        })
    }

    fn metadata(&self) -> &Metadata {
        &self.metadata
    }

    fn render_mode(&self) -> Option<RenderMode> {
        self.inner.render_mode
    }

    fn render(&mut self) -> Result<Option<Frame>> {
        self.inner.render()
    }

    fn close(&mut self) {
        if self.defect == Defect::ClosePanicsTwice && self.closed_once {
            panic!("the simulator was already freed");
        }
        self.closed_once = true;
        self.inner.close();
    }

    fn rng(&self) -> Option<&EnvRng> {
        if self.defect == Defect::NoRng {
            None
        } else {
            self.inner.rng.as_ref()
        }
    }
}

/// [`StateHook`] for [`BrokenEnv`] (and a `BoxedEnv` over one). With
/// [`Defect::StateRoundTripLosesVelocity`], `set_state` forgets the velocity.
#[derive(Debug, Clone, Copy, Default)]
pub struct BrokenStateHook;

impl<E: Env> StateHook<E> for BrokenStateHook {
    type State = PointMassState;

    fn get_state(&self, env: &E) -> Result<PointMassState> {
        env.unwrapped_any()
            .downcast_ref::<BrokenEnv>()
            .ok_or_else(|| Error::unsupported("the unwrapped environment is not a BrokenEnv"))?
            .inner
            .get_state()
    }

    fn set_state(&self, env: &mut E, state: &PointMassState) -> Result<()> {
        let env = env
            .unwrapped_any_mut()
            .downcast_mut::<BrokenEnv>()
            .ok_or_else(|| Error::unsupported("the unwrapped environment is not a BrokenEnv"))?;
        let mut state = state.clone();
        if env.defect == Defect::StateRoundTripLosesVelocity {
            state.velocity = 0.0;
        }
        env.inner.set_state(&state)
    }
}

/// An observation that shares its buffer: cloning it clones the `Arc`, not the data.
#[derive(Debug, Clone)]
pub struct SharedObs(pub Arc<Mutex<ArrayD<f32>>>);

impl SharedObs {
    /// A copy of the data.
    pub fn get(&self) -> ArrayD<f32> {
        self.0
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .clone()
    }

    fn new(a: ArrayD<f32>) -> Self {
        Self(Arc::new(Mutex::new(a)))
    }
}

impl PartialEq for SharedObs {
    fn eq(&self, other: &Self) -> bool {
        self.get() == other.get()
    }
}

/// A `float32` Box whose elements are [`SharedObs`].
#[derive(Debug, Clone, PartialEq)]
pub struct SharedBoxSpace(pub BoxSpace<f32>);

impl Space for SharedBoxSpace {
    type Element = SharedObs;

    fn sample<R: rand::Rng + ?Sized>(&self, rng: &mut R) -> SharedObs {
        SharedObs::new(self.0.sample(rng))
    }

    fn contains(&self, x: &SharedObs) -> bool {
        self.0.contains(&x.get())
    }

    fn shape(&self) -> Option<&[usize]> {
        self.0.shape()
    }
}

impl Flatten for SharedBoxSpace {
    fn flatdim(&self) -> usize {
        self.0.flatdim()
    }

    fn flat_dtype(&self) -> DType {
        DType::F32
    }

    fn flatten(&self, x: &SharedObs) -> std::result::Result<ArrayValue, SpaceError> {
        self.0.flatten(&x.get())
    }

    fn unflatten(&self, flat: &ArrayValue) -> std::result::Result<SharedObs, SpaceError> {
        self.0.unflatten(flat).map(SharedObs::new)
    }

    fn flatten_space(&self) -> AnyBox {
        self.0.flatten_space()
    }
}

impl DynSpace for SharedBoxSpace {
    fn to_any(&self) -> AnySpace {
        self.0.to_any()
    }

    fn to_value(&self, x: &SharedObs) -> Value {
        Value::from(x.get())
    }

    fn from_value(&self, v: &Value) -> std::result::Result<SharedObs, SpaceError> {
        self.0.from_value(v).map(SharedObs::new)
    }
}

/// A counter whose observation is a [`SharedObs`] over one buffer the environment keeps
/// writing into: every returned observation changes when the environment steps again
/// (Gymnasium's reused-buffer bug, caught by
/// [`Check::ReturnedDataNotReused`]).
#[derive(Debug)]
pub struct SharedBufferEnv {
    observation_space: SharedBoxSpace,
    action_space: BoxSpace<f32>,
    buffer: Arc<Mutex<ArrayD<f32>>>,
    rng: Option<EnvRng>,
    t: u64,
}

impl Default for SharedBufferEnv {
    fn default() -> Self {
        Self::new()
    }
}

impl SharedBufferEnv {
    /// A new environment.
    pub fn new() -> Self {
        Self {
            observation_space: SharedBoxSpace(
                BoxSpace::uniform(0.0, 1000.0, &[1]).expect("valid bounds"),
            ),
            action_space: BoxSpace::uniform(-1.0, 1.0, &[1]).expect("valid bounds"),
            buffer: Arc::new(Mutex::new(ArrayD::zeros(IxDyn(&[1])))),
            rng: None,
            t: 0,
        }
    }

    fn write(&mut self) -> SharedObs {
        *self.buffer.lock().unwrap_or_else(PoisonError::into_inner) =
            arr1(&[self.t as f32]).into_dyn();
        SharedObs(Arc::clone(&self.buffer))
    }
}

impl Env for SharedBufferEnv {
    type Obs = SharedObs;
    type Act = ArrayD<f32>;
    type ObsSpace = SharedBoxSpace;
    type ActSpace = BoxSpace<f32>;

    fn observation_space(&self) -> &SharedBoxSpace {
        &self.observation_space
    }

    fn action_space(&self) -> &BoxSpace<f32> {
        &self.action_space
    }

    fn reset(&mut self, seed: Option<u64>, _: Option<&ResetOptions>) -> Result<(SharedObs, Info)> {
        self.rng = Some(rng_from_seed(seed.unwrap_or(0)));
        self.t = 0;
        Ok((self.write(), Info::new()))
    }

    fn step(&mut self, action: &ArrayD<f32>) -> Result<Step<SharedObs>> {
        PointMass::force(action)?;
        self.t += 1;
        Ok(Step {
            observation: self.write(),
            reward: 0.0,
            terminated: false,
            truncated: self.t >= 100,
            info: Info::new(),
        })
    }

    fn rng(&self) -> Option<&EnvRng> {
        self.rng.as_ref()
    }
}
