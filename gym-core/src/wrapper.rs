//! Wrappers: environments that own another and change part of its behaviour, in the shape
//! of Gymnasium's `Wrapper`, `ObservationWrapper`, `ActionWrapper` and `RewardWrapper`.
//!
//! A wrapper implements [`Wrapper`] (where its inner environment is, and which kind of
//! wrapper it is) and the trait of its kind:
//!
//! | [`Wrapper::Kind`] | trait to implement | what it writes |
//! |---|---|---|
//! | [`Observations`] | [`ObservationWrapper`] | the new observation space and `observation(obs)` |
//! | [`Actions`] | [`ActionWrapper`] | the new action space and `action(act)` |
//! | [`Rewards`] | [`RewardWrapper`] | `reward(r)` |
//! | [`Steps`] | [`StepWrapper`] | any of `reset`, `step`, `step_into`, `render` (the rest forwards) |
//! | [`Custom`] | [`CustomWrapper`] | new spaces, `reset` and `step` |
//!
//! [`Env`] then comes from one generic implementation, which also forwards what wrappers
//! leave alone (metadata, render mode, `close`, the RNG, `unwrapped`) to the inner
//! environment. No wrapper writes an `Env` implementation of its own.
//!
//! ```
//! use gym_core::{Env, Rewards, RewardWrapper, Wrapper};
//!
//! /// Doubles every reward.
//! struct Double<E>(E);
//!
//! impl<E: Env> Wrapper for Double<E> {
//!     type Inner = E;
//!     type Kind = Rewards;
//!     fn inner(&self) -> &E { &self.0 }
//!     fn inner_mut(&mut self) -> &mut E { &mut self.0 }
//!     fn into_inner(self) -> E { self.0 }
//! }
//!
//! impl<E: Env> RewardWrapper for Double<E> {
//!     fn reward(&mut self, reward: f64) -> f64 { 2.0 * reward }
//! }
//! ```
//!
//! The hooks of [`StepWrapper`] and [`CustomWrapper`] take `this` rather than `self` (as
//! `Rc::get_mut` does), so that `wrapper.step(..)` always means [`Env::step`].

use crate::env::{Env, Frame, Metadata, RenderMode, Step, Transition};
use crate::error::Result;
use crate::info::{Info, ResetOptions};
use crate::rng::EnvRng;
use crate::row::{ObsRow, Pick, RowLeaves};
use crate::space::{DynSpace, Flatten, Space};
use std::any::Any;

/// An environment layered over an inner one it owns (Gymnasium's `gymnasium.Wrapper`). A
/// stack of wrappers is a plain owned value (`TimeLimit<FlattenObservation<Lift>>`), `Send`
/// when the innermost env is.
///
/// Implement it together with the trait of [`Wrapper::Kind`] (see the [module
/// documentation](self)); the wrapper is then an [`Env`].
pub trait Wrapper: Send + 'static {
    /// The wrapped environment's type.
    type Inner: Env;

    /// What the wrapper changes: [`Observations`], [`Actions`], [`Rewards`], [`Steps`] or
    /// [`Custom`].
    type Kind;

    /// The wrapped environment.
    fn inner(&self) -> &Self::Inner;

    /// The wrapped environment, mutably.
    fn inner_mut(&mut self) -> &mut Self::Inner;

    /// Takes the wrapper apart, returning the wrapped environment.
    fn into_inner(self) -> Self::Inner
    where
        Self: Sized;

    /// The innermost environment, if it has type `T` (Gymnasium's `env.unwrapped`).
    fn unwrapped<T: 'static>(&self) -> Option<&T>
    where
        Self: Sized,
    {
        self.inner().unwrapped_any().downcast_ref()
    }
}

/// [`Wrapper::Kind`] of an [`ObservationWrapper`].
#[derive(Debug)]
pub enum Observations {}
/// [`Wrapper::Kind`] of an [`ActionWrapper`].
#[derive(Debug)]
pub enum Actions {}
/// [`Wrapper::Kind`] of a [`RewardWrapper`].
#[derive(Debug)]
pub enum Rewards {}
/// [`Wrapper::Kind`] of a [`StepWrapper`].
#[derive(Debug)]
pub enum Steps {}
/// [`Wrapper::Kind`] of a [`CustomWrapper`].
#[derive(Debug)]
pub enum Custom {}

/// Gymnasium's `ObservationWrapper`: every observation, from `reset` and `step`, is mapped
/// by [`ObservationWrapper::observation`] into [`ObservationWrapper::space`].
pub trait ObservationWrapper: Wrapper<Kind = Observations> {
    /// The new observation space.
    type Space: Flatten + DynSpace;

    /// The new observation space.
    fn space(&self) -> &Self::Space;

    /// Maps an observation of the inner environment.
    ///
    /// # Errors
    /// When the observation cannot be mapped (the step or reset then fails with it).
    fn observation(
        &mut self,
        observation: <Self::Inner as Env>::Obs,
    ) -> Result<<Self::Space as Space>::Element>;

    /// Maps the observation of a `reset` of the inner environment. The default is
    /// [`ObservationWrapper::observation`]; a wrapper whose mapping carries state from step
    /// to step (`FrameStackObservation`'s stack) starts it again here.
    ///
    /// # Errors
    /// As [`ObservationWrapper::observation`].
    fn reset_observation(
        &mut self,
        observation: <Self::Inner as Env>::Obs,
    ) -> Result<<Self::Space as Space>::Element> {
        self.observation(observation)
    }

    /// Maps a borrowed observation of the inner environment into `out`, the previous
    /// observation, reusing its storage: what [`Env::step_into`] calls. The default clones
    /// the observation and calls [`ObservationWrapper::observation`]; override it (and opt
    /// into [`ObservationWrapper::inner_buffer`]) for a step that allocates nothing.
    ///
    /// # Errors
    /// As [`ObservationWrapper::observation`].
    fn observation_into(
        &mut self,
        observation: &<Self::Inner as Env>::Obs,
        out: &mut <Self::Space as Space>::Element,
    ) -> Result<()> {
        *out = self.observation(observation.clone())?;
        Ok(())
    }

    /// Where the kind keeps the inner environment's observation between steps (a field of
    /// the wrapper, `None` until the first step), or `None` (the default) to step the inner
    /// environment with [`Env::step`]. With a buffer, [`Env::step_into`] steps the inner
    /// environment into it and maps it with [`ObservationWrapper::observation_into`].
    fn inner_buffer(&mut self) -> Option<&mut Option<<Self::Inner as Env>::Obs>> {
        None
    }

    /// For a wrapper whose observation is the inner observation's arrays rearranged
    /// (filtered, reordered, concatenated) with no other change than a dtype conversion:
    /// where each inner array goes in a row of this wrapper's observations, one [`Pick`]
    /// per inner array. With a plan (and an inner environment that
    /// [writes rows](Env::writes_rows)) the wrapper writes rows too. `None` by default.
    fn row_plan(&self) -> Option<&[Pick]> {
        None
    }
}

/// Gymnasium's `ActionWrapper`: the wrapper accepts actions of [`ActionWrapper::space`] and
/// steps the inner environment with [`ActionWrapper::action`] of them.
pub trait ActionWrapper: Wrapper<Kind = Actions> {
    /// The new action space.
    type Space: Flatten + DynSpace;

    /// The new action space.
    fn space(&self) -> &Self::Space;

    /// Maps an action to one of the inner environment.
    ///
    /// # Errors
    /// [`Error::InvalidAction`](crate::Error::InvalidAction) when the action cannot be
    /// mapped; the inner environment is not stepped.
    fn action(
        &mut self,
        action: &<Self::Space as Space>::Element,
    ) -> Result<<Self::Inner as Env>::Act>;

    /// Maps an action into `out`, the previous inner action, reusing its storage. The
    /// default calls [`ActionWrapper::action`].
    ///
    /// # Errors
    /// As [`ActionWrapper::action`].
    fn action_into(
        &mut self,
        action: &<Self::Space as Space>::Element,
        out: &mut <Self::Inner as Env>::Act,
    ) -> Result<()> {
        *out = self.action(action)?;
        Ok(())
    }

    /// Where the kind keeps the inner action between steps (a field of the wrapper, `None`
    /// until the first step), or `None` (the default) to map each action with
    /// [`ActionWrapper::action`]. With a buffer, every step maps the action with
    /// [`ActionWrapper::action_into`].
    fn action_buffer(&mut self) -> Option<&mut Option<<Self::Inner as Env>::Act>> {
        None
    }
}

/// Gymnasium's `RewardWrapper`: every reward is mapped by [`RewardWrapper::reward`].
pub trait RewardWrapper: Wrapper<Kind = Rewards> {
    /// Maps the reward of one step.
    fn reward(&mut self, reward: f64) -> f64;
}

/// Gymnasium's plain `Wrapper` subclass: the spaces are the inner environment's, and each
/// hook forwards to the inner environment unless the wrapper overrides it (a wrapper that
/// overrides [`StepWrapper::step`] but not [`StepWrapper::step_into`] gets `step_into`
/// through its `step`).
pub trait StepWrapper: Wrapper<Kind = Steps> {
    /// [`Env::reset`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::reset`].
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(<Self::Inner as Env>::Obs, Info)> {
        this.inner_mut().reset(seed, options)
    }

    /// [`Env::step`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step(
        this: &mut Self,
        action: &<Self::Inner as Env>::Act,
    ) -> Result<Step<<Self::Inner as Env>::Obs>> {
        this.inner_mut().step(action)
    }

    /// [`Env::step_into`] of the wrapper: through [`StepWrapper::step`] unless overridden.
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step_into(
        this: &mut Self,
        action: &<Self::Inner as Env>::Act,
        observation: &mut <Self::Inner as Env>::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        Ok(move_step(Self::step(this, action)?, observation, info))
    }

    /// [`Env::writes_rows`] of the wrapper: `false` unless overridden (a wrapper that
    /// changes steps must say how [`StepWrapper::step_for_row`] does).
    fn writes_rows(this: &Self) -> bool {
        let _ = this;
        false
    }

    /// [`Env::step_for_row`] of the wrapper (see [`StepWrapper::writes_rows`]).
    ///
    /// # Errors
    /// As [`Env::step_for_row`].
    fn step_for_row(
        this: &mut Self,
        action: &<Self::Inner as Env>::Act,
        info: &mut Info,
    ) -> Result<Transition> {
        let _ = (this, action, info);
        Err(crate::Error::unsupported(
            "this wrapper does not write observations into batch rows",
        ))
    }

    /// [`Env::render`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::render`].
    fn render(this: &mut Self) -> Result<Option<Frame>> {
        this.inner_mut().render()
    }
}

/// A wrapper with spaces of its own and its own `reset` and `step` (Gymnasium's `Wrapper`
/// subclass that sets both spaces), for what is not a plain observation or action map.
pub trait CustomWrapper: Wrapper<Kind = Custom> {
    /// The wrapper's observation type.
    type Observation: Clone + std::fmt::Debug + Send + 'static;
    /// The wrapper's action type.
    type Action: Clone + std::fmt::Debug + Send + 'static;
    /// The wrapper's observation space.
    type ObservationSpace: Flatten<Element = Self::Observation> + DynSpace;
    /// The wrapper's action space.
    type ActionSpace: Flatten<Element = Self::Action> + DynSpace;

    /// [`Env::observation_space`] of the wrapper.
    fn observation_space(this: &Self) -> &Self::ObservationSpace;

    /// [`Env::action_space`] of the wrapper.
    fn action_space(this: &Self) -> &Self::ActionSpace;

    /// [`Env::reset`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::reset`].
    fn reset(
        this: &mut Self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Observation, Info)>;

    /// [`Env::step`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step(this: &mut Self, action: &Self::Action) -> Result<Step<Self::Observation>>;

    /// [`Env::step_into`] of the wrapper: through [`CustomWrapper::step`] unless overridden.
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step_into(
        this: &mut Self,
        action: &Self::Action,
        observation: &mut Self::Observation,
        info: &mut Info,
    ) -> Result<Transition> {
        Ok(move_step(Self::step(this, action)?, observation, info))
    }

    /// [`Env::writes_rows`] of the wrapper: `false` unless overridden.
    fn writes_rows(this: &Self) -> bool {
        let _ = this;
        false
    }

    /// [`Env::step_for_row`] of the wrapper (see [`CustomWrapper::writes_rows`]).
    ///
    /// # Errors
    /// As [`Env::step_for_row`].
    fn step_for_row(this: &mut Self, action: &Self::Action, info: &mut Info) -> Result<Transition> {
        let _ = (this, action, info);
        Err(crate::Error::unsupported(
            "this wrapper does not write observations into batch rows",
        ))
    }

    /// [`Env::write_observation_row`] of the wrapper (see [`CustomWrapper::writes_rows`]).
    ///
    /// # Errors
    /// As [`Env::write_observation_row`].
    fn write_observation_row(this: &Self, row: &mut ObsRow<'_>) -> Result<()> {
        let _ = (this, row);
        Err(crate::Error::unsupported(
            "this wrapper does not write observations into batch rows",
        ))
    }

    /// [`Env::render`] of the wrapper.
    ///
    /// # Errors
    /// As [`Env::render`].
    fn render(this: &mut Self) -> Result<Option<Frame>> {
        this.inner_mut().render()
    }
}

/// Moves a step's observation and info into the caller's buffers.
fn move_step<O>(step: Step<O>, observation: &mut O, info: &mut Info) -> Transition {
    *observation = step.observation;
    *info = step.info;
    Transition {
        reward: step.reward,
        terminated: step.terminated,
        truncated: step.truncated,
    }
}

mod sealed {
    /// Keeps [`WrapperKind`](super::WrapperKind) to the kinds of this module.
    pub trait Sealed {}
    impl Sealed for super::Observations {}
    impl Sealed for super::Actions {}
    impl Sealed for super::Rewards {}
    impl Sealed for super::Steps {}
    impl Sealed for super::Custom {}
}

/// How a kind of wrapper makes its wrapper `W` an [`Env`]: implemented by the kind markers
/// ([`Observations`], ...) for the wrappers of their trait, and sealed (a new kind of wrapper
/// is a change to gym-core, not to a user's crate).
pub trait WrapperKind<W>: sealed::Sealed + 'static {
    /// [`Env::Obs`] of the wrapper.
    type Obs: Clone + std::fmt::Debug + Send + 'static;
    /// [`Env::Act`] of the wrapper.
    type Act: Clone + std::fmt::Debug + Send + 'static;
    /// [`Env::ObsSpace`] of the wrapper.
    type ObsSpace: Flatten<Element = Self::Obs> + DynSpace;
    /// [`Env::ActSpace`] of the wrapper.
    type ActSpace: Flatten<Element = Self::Act> + DynSpace;

    /// [`Env::observation_space`].
    fn observation_space(w: &W) -> &Self::ObsSpace;
    /// [`Env::action_space`].
    fn action_space(w: &W) -> &Self::ActSpace;
    /// [`Env::reset`].
    ///
    /// # Errors
    /// As [`Env::reset`].
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)>;
    /// [`Env::step`].
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>>;
    /// [`Env::step_into`].
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition>;
    /// [`Env::render`].
    ///
    /// # Errors
    /// As [`Env::render`].
    fn render(w: &mut W) -> Result<Option<Frame>>;
    /// [`Env::writes_rows`].
    fn writes_rows(w: &W) -> bool;
    /// [`Env::step_for_row`].
    ///
    /// # Errors
    /// As [`Env::step_for_row`].
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition>;
    /// [`Env::write_observation_row`].
    ///
    /// # Errors
    /// As [`Env::write_observation_row`].
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()>;
}

type InnerObs<W> = <<W as Wrapper>::Inner as Env>::Obs;
type InnerAct<W> = <<W as Wrapper>::Inner as Env>::Act;

impl<W: ObservationWrapper> WrapperKind<W> for Observations {
    type Obs = <W::Space as Space>::Element;
    type Act = InnerAct<W>;
    type ObsSpace = W::Space;
    type ActSpace = <W::Inner as Env>::ActSpace;

    fn observation_space(w: &W) -> &W::Space {
        w.space()
    }
    fn action_space(w: &W) -> &Self::ActSpace {
        w.inner().action_space()
    }
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        let (observation, info) = w.inner_mut().reset(seed, options)?;
        Ok((w.reset_observation(observation)?, info))
    }
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>> {
        if w.inner_buffer().is_none() {
            let step = w.inner_mut().step(action)?;
            return step.try_map_observation(|o| w.observation(o));
        }
        let mut info = Info::new();
        let (t, kept) = step_kept(w, action, &mut info)?;
        let observation = w.observation(kept.clone());
        put_back(w, kept);
        Ok(Step {
            observation: observation?,
            reward: t.reward,
            terminated: t.terminated,
            truncated: t.truncated,
            info,
        })
    }
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        if w.inner_buffer().is_none() {
            return Ok(move_step(Self::step(w, action)?, observation, info));
        }
        let (t, kept) = step_kept(w, action, info)?;
        let mapped = w.observation_into(&kept, observation);
        put_back(w, kept);
        mapped.map(|()| t)
    }
    fn render(w: &mut W) -> Result<Option<Frame>> {
        w.inner_mut().render()
    }
    fn writes_rows(w: &W) -> bool {
        w.row_plan().is_some() && w.inner().writes_rows()
    }
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        if w.row_plan().is_none() {
            return Err(crate::Error::unsupported(
                "this observation wrapper does not write observations into batch rows",
            ));
        }
        w.inner_mut().step_for_row(action, info)
    }
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()> {
        let plan = w.row_plan().ok_or_else(|| {
            crate::Error::unsupported(
                "this observation wrapper does not write observations into batch rows",
            )
        })?;
        let mut leaves = RowLeaves::new();
        let mut inner = row.rearranged(plan, &mut leaves)?;
        w.inner().write_observation_row(&mut inner)
    }
}

/// Steps the inner environment of an observation wrapper with a buffer into the kept
/// observation (taken out of the wrapper, which the caller puts back with [`put_back`]);
/// the first step, with nothing kept yet, goes through [`Env::step`].
fn step_kept<W: ObservationWrapper>(
    w: &mut W,
    action: &InnerAct<W>,
    info: &mut Info,
) -> Result<(Transition, InnerObs<W>)> {
    match w.inner_buffer().and_then(Option::take) {
        Some(mut kept) => {
            let t = w.inner_mut().step_into(action, &mut kept, info);
            match t {
                Ok(t) => Ok((t, kept)),
                Err(e) => {
                    put_back(w, kept);
                    Err(e)
                }
            }
        }
        None => {
            let step = w.inner_mut().step(action)?;
            *info = step.info;
            let t = Transition {
                reward: step.reward,
                terminated: step.terminated,
                truncated: step.truncated,
            };
            Ok((t, step.observation))
        }
    }
}

/// Returns the kept inner observation to the wrapper's buffer.
fn put_back<W: ObservationWrapper>(w: &mut W, kept: InnerObs<W>) {
    if let Some(slot) = w.inner_buffer() {
        *slot = Some(kept);
    }
}

/// The inner action of `action` for an action wrapper: mapped into the wrapper's kept
/// action when it keeps one (taken out; the caller returns it with [`put_back_action`]).
fn inner_action<W: ActionWrapper>(
    w: &mut W,
    action: &<W::Space as Space>::Element,
) -> Result<InnerAct<W>> {
    match w.action_buffer().and_then(Option::take) {
        Some(mut kept) => match w.action_into(action, &mut kept) {
            Ok(()) => Ok(kept),
            Err(e) => {
                put_back_action(w, kept);
                Err(e)
            }
        },
        None => w.action(action),
    }
}

/// Returns the inner action to the wrapper's buffer, if it keeps one.
fn put_back_action<W: ActionWrapper>(w: &mut W, kept: InnerAct<W>) {
    if let Some(slot) = w.action_buffer() {
        *slot = Some(kept);
    }
}

impl<W: ActionWrapper> WrapperKind<W> for Actions {
    type Obs = InnerObs<W>;
    type Act = <W::Space as Space>::Element;
    type ObsSpace = <W::Inner as Env>::ObsSpace;
    type ActSpace = W::Space;

    fn observation_space(w: &W) -> &Self::ObsSpace {
        w.inner().observation_space()
    }
    fn action_space(w: &W) -> &W::Space {
        w.space()
    }
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        w.inner_mut().reset(seed, options)
    }
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>> {
        let action = inner_action(w, action)?;
        let step = w.inner_mut().step(&action);
        put_back_action(w, action);
        step
    }
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        let action = inner_action(w, action)?;
        let t = w.inner_mut().step_into(&action, observation, info);
        put_back_action(w, action);
        t
    }
    fn render(w: &mut W) -> Result<Option<Frame>> {
        w.inner_mut().render()
    }
    fn writes_rows(w: &W) -> bool {
        w.inner().writes_rows()
    }
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        let action = inner_action(w, action)?;
        let t = w.inner_mut().step_for_row(&action, info);
        put_back_action(w, action);
        t
    }
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()> {
        w.inner().write_observation_row(row)
    }
}

impl<W: RewardWrapper> WrapperKind<W> for Rewards {
    type Obs = InnerObs<W>;
    type Act = InnerAct<W>;
    type ObsSpace = <W::Inner as Env>::ObsSpace;
    type ActSpace = <W::Inner as Env>::ActSpace;

    fn observation_space(w: &W) -> &Self::ObsSpace {
        w.inner().observation_space()
    }
    fn action_space(w: &W) -> &Self::ActSpace {
        w.inner().action_space()
    }
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        w.inner_mut().reset(seed, options)
    }
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>> {
        let mut step = w.inner_mut().step(action)?;
        step.reward = w.reward(step.reward);
        Ok(step)
    }
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        let mut t = w.inner_mut().step_into(action, observation, info)?;
        t.reward = w.reward(t.reward);
        Ok(t)
    }
    fn render(w: &mut W) -> Result<Option<Frame>> {
        w.inner_mut().render()
    }
    fn writes_rows(w: &W) -> bool {
        w.inner().writes_rows()
    }
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        let mut t = w.inner_mut().step_for_row(action, info)?;
        t.reward = w.reward(t.reward);
        Ok(t)
    }
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()> {
        w.inner().write_observation_row(row)
    }
}

impl<W: StepWrapper> WrapperKind<W> for Steps {
    type Obs = InnerObs<W>;
    type Act = InnerAct<W>;
    type ObsSpace = <W::Inner as Env>::ObsSpace;
    type ActSpace = <W::Inner as Env>::ActSpace;

    fn observation_space(w: &W) -> &Self::ObsSpace {
        w.inner().observation_space()
    }
    fn action_space(w: &W) -> &Self::ActSpace {
        w.inner().action_space()
    }
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        <W as StepWrapper>::reset(w, seed, options)
    }
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>> {
        <W as StepWrapper>::step(w, action)
    }
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        <W as StepWrapper>::step_into(w, action, observation, info)
    }
    fn render(w: &mut W) -> Result<Option<Frame>> {
        <W as StepWrapper>::render(w)
    }
    fn writes_rows(w: &W) -> bool {
        <W as StepWrapper>::writes_rows(w) && w.inner().writes_rows()
    }
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        <W as StepWrapper>::step_for_row(w, action, info)
    }
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()> {
        w.inner().write_observation_row(row)
    }
}

impl<W: CustomWrapper> WrapperKind<W> for Custom {
    type Obs = W::Observation;
    type Act = W::Action;
    type ObsSpace = W::ObservationSpace;
    type ActSpace = W::ActionSpace;

    fn observation_space(w: &W) -> &Self::ObsSpace {
        <W as CustomWrapper>::observation_space(w)
    }
    fn action_space(w: &W) -> &Self::ActSpace {
        <W as CustomWrapper>::action_space(w)
    }
    fn reset(
        w: &mut W,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        <W as CustomWrapper>::reset(w, seed, options)
    }
    fn step(w: &mut W, action: &Self::Act) -> Result<Step<Self::Obs>> {
        <W as CustomWrapper>::step(w, action)
    }
    fn step_into(
        w: &mut W,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        <W as CustomWrapper>::step_into(w, action, observation, info)
    }
    fn render(w: &mut W) -> Result<Option<Frame>> {
        <W as CustomWrapper>::render(w)
    }
    fn writes_rows(w: &W) -> bool {
        <W as CustomWrapper>::writes_rows(w)
    }
    fn step_for_row(w: &mut W, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        <W as CustomWrapper>::step_for_row(w, action, info)
    }
    fn write_observation_row(w: &W, row: &mut ObsRow<'_>) -> Result<()> {
        <W as CustomWrapper>::write_observation_row(w, row)
    }
}

/// Every wrapper is an environment: its kind says how it observes, acts and rewards, and
/// the rest (metadata, render mode, `close`, RNG, `unwrapped`) is the inner environment's.
impl<W> Env for W
where
    W: Wrapper,
    W::Kind: WrapperKind<W>,
{
    type Obs = <W::Kind as WrapperKind<W>>::Obs;
    type Act = <W::Kind as WrapperKind<W>>::Act;
    type ObsSpace = <W::Kind as WrapperKind<W>>::ObsSpace;
    type ActSpace = <W::Kind as WrapperKind<W>>::ActSpace;

    fn observation_space(&self) -> &Self::ObsSpace {
        W::Kind::observation_space(self)
    }
    fn action_space(&self) -> &Self::ActSpace {
        W::Kind::action_space(self)
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Self::Obs, Info)> {
        W::Kind::reset(self, seed, options)
    }
    fn step(&mut self, action: &Self::Act) -> Result<Step<Self::Obs>> {
        W::Kind::step(self, action)
    }
    fn step_into(
        &mut self,
        action: &Self::Act,
        observation: &mut Self::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        W::Kind::step_into(self, action, observation, info)
    }
    fn writes_rows(&self) -> bool {
        W::Kind::writes_rows(self)
    }
    fn step_for_row(&mut self, action: &Self::Act, info: &mut Info) -> Result<Transition> {
        W::Kind::step_for_row(self, action, info)
    }
    fn write_observation_row(&self, row: &mut ObsRow<'_>) -> Result<()> {
        W::Kind::write_observation_row(self, row)
    }
    fn metadata(&self) -> &Metadata {
        self.inner().metadata()
    }
    fn render_mode(&self) -> Option<RenderMode> {
        self.inner().render_mode()
    }
    fn render(&mut self) -> Result<Option<Frame>> {
        W::Kind::render(self)
    }
    fn close(&mut self) {
        self.inner_mut().close();
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.inner().rng()
    }
    fn unwrapped_any(&self) -> &dyn Any {
        self.inner().unwrapped_any()
    }
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any {
        self.inner_mut().unwrapped_any_mut()
    }
}
