//! The object-safe layer: any typed [`Env`] boxed as a [`BoxedEnv`] whose observations and
//! actions are [`Value`]s and whose spaces are [`AnySpace`]s. Registries, heterogeneous
//! collections and the Python export work at this level.

use crate::env::{Env, Frame, Metadata, RenderMode, Step, Transition};
use crate::error::{Error, Result};
use crate::for_each_array;
use crate::info::{Info, ResetOptions};
use crate::rng::EnvRng;
use crate::row::ObsRow;
use crate::space::DynSpace;
use crate::spaces::AnySpace;
use crate::value::Value;
use std::any::Any;

/// An environment seen through dynamic values; object safe.
pub trait DynEnv: Send + 'static {
    /// The observation space.
    fn observation_space(&self) -> &AnySpace;
    /// The action space.
    fn action_space(&self) -> &AnySpace;
    /// See [`Env::reset`].
    ///
    /// # Errors
    /// As [`Env::reset`].
    fn reset(&mut self, seed: Option<u64>, options: Option<&ResetOptions>)
    -> Result<(Value, Info)>;
    /// See [`Env::step`]. An action that does not convert to the typed action is an
    /// [`Error::InvalidAction`].
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step(&mut self, action: &Value) -> Result<Step<Value>>;
    /// See [`Env::step_into`]: the observation is written into `observation` and the info
    /// into `info`, the reward and end flags are returned. The default moves the result of
    /// `step` into the buffers; a [`DynAdapter`] steps its typed environment's `step_into`
    /// straight into `observation` when that value already holds the typed observation
    /// (the value of an earlier step or reset) and borrows the typed action out of
    /// `action` when it holds one, so a loop of steps converts nothing and, over an
    /// environment whose `step_into` reuses its buffers, allocates nothing.
    ///
    /// # Errors
    /// As [`Env::step`].
    fn step_into(
        &mut self,
        action: &Value,
        observation: &mut Value,
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
    /// See [`Env::writes_rows`]. `false` by default.
    fn writes_rows(&self) -> bool {
        false
    }
    /// See [`Env::step_for_row`].
    ///
    /// # Errors
    /// As [`Env::step_for_row`].
    fn step_for_row(&mut self, action: &Value, info: &mut Info) -> Result<Transition> {
        let _ = (action, info);
        Err(Error::unsupported(
            "this environment does not write observations into batch rows",
        ))
    }
    /// See [`Env::write_observation_row`].
    ///
    /// # Errors
    /// As [`Env::write_observation_row`].
    fn write_observation_row(&self, row: &mut ObsRow<'_>) -> Result<()> {
        let _ = row;
        Err(Error::unsupported(
            "this environment does not write observations into batch rows",
        ))
    }
    /// See [`Env::metadata`].
    fn metadata(&self) -> &Metadata;
    /// See [`Env::render_mode`].
    fn render_mode(&self) -> Option<RenderMode>;
    /// See [`Env::render`].
    ///
    /// # Errors
    /// As [`Env::render`].
    fn render(&mut self) -> Result<Option<Frame>>;
    /// See [`Env::close`].
    fn close(&mut self);
    /// See [`Env::rng`].
    fn rng(&self) -> Option<&EnvRng>;
    /// See [`Env::unwrapped_any`].
    fn unwrapped_any(&self) -> &dyn Any;
    /// See [`Env::unwrapped_any_mut`].
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any;
}

/// A boxed dynamic environment.
pub type BoxedEnv = Box<dyn DynEnv>;

/// Adapts a typed [`Env`] to [`DynEnv`]; made by [`IntoBoxedEnv::boxed`].
pub struct DynAdapter<E: Env> {
    env: E,
    observation_space: AnySpace,
    action_space: AnySpace,
}

impl<E: Env> DynAdapter<E> {
    /// Wraps `env`, computing its dynamic spaces once.
    pub fn new(env: E) -> Self {
        let observation_space = env.observation_space().to_any();
        let action_space = env.action_space().to_any();
        Self {
            env,
            observation_space,
            action_space,
        }
    }

    /// The typed environment inside.
    pub fn get(&self) -> &E {
        &self.env
    }

    /// The typed environment inside, mutably.
    pub fn get_mut(&mut self) -> &mut E {
        &mut self.env
    }
}

impl<E: Env> DynEnv for DynAdapter<E> {
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
        let (obs, info) = self.env.reset(seed, options)?;
        Ok((self.env.observation_space().to_value(&obs), info))
    }
    fn step(&mut self, action: &Value) -> Result<Step<Value>> {
        let action = self
            .env
            .action_space()
            .from_value(action)
            .map_err(|e| Error::InvalidAction(e.into()))?;
        let step = self.env.step(&action)?;
        let space = self.env.observation_space();
        Ok(step.map_observation(|o| space.to_value(&o)))
    }
    fn step_into(
        &mut self,
        action: &Value,
        observation: &mut Value,
        info: &mut Info,
    ) -> Result<Transition> {
        let converted;
        let action = match typed_ref::<E::Act>(action) {
            Some(a) => a,
            None => {
                converted = self
                    .env
                    .action_space()
                    .from_value(action)
                    .map_err(|e| Error::InvalidAction(e.into()))?;
                &converted
            }
        };
        if let Some(typed) = typed_mut::<E::Obs>(observation) {
            return self.env.step_into(action, typed, info);
        }
        let step = self.env.step(action)?;
        *observation = self.env.observation_space().to_value(&step.observation);
        *info = step.info;
        Ok(Transition {
            reward: step.reward,
            terminated: step.terminated,
            truncated: step.truncated,
        })
    }
    fn writes_rows(&self) -> bool {
        self.env.writes_rows()
    }
    fn step_for_row(&mut self, action: &Value, info: &mut Info) -> Result<Transition> {
        match typed_ref::<E::Act>(action) {
            Some(a) => self.env.step_for_row(a, info),
            None => {
                let converted = self
                    .env
                    .action_space()
                    .from_value(action)
                    .map_err(|e| Error::InvalidAction(e.into()))?;
                self.env.step_for_row(&converted, info)
            }
        }
    }
    fn write_observation_row(&self, row: &mut ObsRow<'_>) -> Result<()> {
        self.env.write_observation_row(row)
    }
    fn metadata(&self) -> &Metadata {
        self.env.metadata()
    }
    fn render_mode(&self) -> Option<RenderMode> {
        self.env.render_mode()
    }
    fn render(&mut self) -> Result<Option<Frame>> {
        self.env.render()
    }
    fn close(&mut self) {
        self.env.close();
    }
    fn rng(&self) -> Option<&EnvRng> {
        self.env.rng()
    }
    fn unwrapped_any(&self) -> &dyn Any {
        self.env.unwrapped_any()
    }
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any {
        self.env.unwrapped_any_mut()
    }
}

/// The element of type `T` inside `v`: `v` itself, or the array, integer, dict or tuple it
/// holds, when that has type `T` (no conversion, no copy).
fn typed_ref<T: 'static>(v: &Value) -> Option<&T> {
    if let Some(t) = (v as &dyn Any).downcast_ref::<T>() {
        return Some(t);
    }
    match v {
        Value::Array(a) => for_each_array!(a, x => (x as &dyn Any).downcast_ref::<T>()),
        Value::Discrete(i) => (i as &dyn Any).downcast_ref::<T>(),
        Value::Dict(d) => (d as &dyn Any).downcast_ref::<T>(),
        Value::Tuple(t) => (t as &dyn Any).downcast_ref::<T>(),
    }
}

/// Mutable form of [`typed_ref`].
fn typed_mut<T: 'static>(v: &mut Value) -> Option<&mut T> {
    if (&*v as &dyn Any).is::<T>() {
        return (v as &mut dyn Any).downcast_mut::<T>();
    }
    match v {
        Value::Array(a) => for_each_array!(a, x => (x as &mut dyn Any).downcast_mut::<T>()),
        Value::Discrete(i) => (i as &mut dyn Any).downcast_mut::<T>(),
        Value::Dict(d) => (d as &mut dyn Any).downcast_mut::<T>(),
        Value::Tuple(t) => (t as &mut dyn Any).downcast_mut::<T>(),
    }
}

/// Boxes any typed environment or wrapper stack into a [`BoxedEnv`].
pub trait IntoBoxedEnv {
    /// The boxed, dynamic form.
    fn boxed(self) -> BoxedEnv;
}

impl<E: Env> IntoBoxedEnv for E {
    fn boxed(self) -> BoxedEnv {
        Box::new(DynAdapter::new(self))
    }
}

/// A boxed environment is itself an [`Env`] over [`Value`]s, so typed wrappers stack on it.
impl Env for BoxedEnv {
    type Obs = Value;
    type Act = Value;
    type ObsSpace = AnySpace;
    type ActSpace = AnySpace;

    fn observation_space(&self) -> &AnySpace {
        (**self).observation_space()
    }
    fn action_space(&self) -> &AnySpace {
        (**self).action_space()
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(Value, Info)> {
        (**self).reset(seed, options)
    }
    fn step(&mut self, action: &Value) -> Result<Step<Value>> {
        (**self).step(action)
    }
    fn step_into(
        &mut self,
        action: &Value,
        observation: &mut Value,
        info: &mut Info,
    ) -> Result<Transition> {
        (**self).step_into(action, observation, info)
    }
    fn writes_rows(&self) -> bool {
        (**self).writes_rows()
    }
    fn step_for_row(&mut self, action: &Value, info: &mut Info) -> Result<Transition> {
        (**self).step_for_row(action, info)
    }
    fn write_observation_row(&self, row: &mut ObsRow<'_>) -> Result<()> {
        (**self).write_observation_row(row)
    }
    fn metadata(&self) -> &Metadata {
        (**self).metadata()
    }
    fn render_mode(&self) -> Option<RenderMode> {
        (**self).render_mode()
    }
    fn render(&mut self) -> Result<Option<Frame>> {
        (**self).render()
    }
    fn close(&mut self) {
        (**self).close();
    }
    fn rng(&self) -> Option<&EnvRng> {
        (**self).rng()
    }
    fn unwrapped_any(&self) -> &dyn Any {
        (**self).unwrapped_any()
    }
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any {
        (**self).unwrapped_any_mut()
    }
}
