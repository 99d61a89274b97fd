//! [`SharedEnv`]: one environment reachable from two places, such as robosuite's Python env
//! object and the `GymWrapper` built over it (robosuite's wrappers share the env they wrap).

use crate::fork::{ForkAwareGuard, ForkAwareMutex};
use gym_core::{
    Env, EnvRng, Frame, Info, Metadata, RenderMode, ResetOptions, Result, Step, Transition,
};
use std::any::Any;
use std::sync::Arc;

/// An environment behind an `Arc<ForkAwareMutex<_>>`, itself an [`Env`]: every call locks
/// the environment for its duration. Clones share the same environment. A call made from
/// inside another call on the same thread, or in a forked child while another thread of
/// the parent held the lock, is an error instead of a deadlock.
///
/// The spaces and metadata are copied once at construction (they never change for the
/// environments of this workspace). [`Env::rng`] is `None` because the RNG cannot be
/// borrowed through the lock; [`Env::unwrapped_any`] is the `SharedEnv` itself, so
/// `unwrapped_as::<SharedEnv<E>>()` reaches the shared environment.
pub struct SharedEnv<E: Env> {
    inner: Arc<ForkAwareMutex<E>>,
    observation_space: E::ObsSpace,
    action_space: E::ActSpace,
    metadata: Metadata,
    render_mode: Option<RenderMode>,
}

impl<E: Env> SharedEnv<E> {
    /// Shares `env`.
    pub fn new(env: E) -> Self {
        Self {
            observation_space: env.observation_space().clone(),
            action_space: env.action_space().clone(),
            metadata: env.metadata().clone(),
            render_mode: env.render_mode(),
            inner: Arc::new(ForkAwareMutex::new(env)),
        }
    }

    /// Shares an environment that is already behind an `Arc<ForkAwareMutex<_>>`.
    ///
    /// # Errors
    /// As [`ForkAwareMutex::lock`].
    pub fn from_arc(inner: Arc<ForkAwareMutex<E>>) -> Result<Self> {
        let (observation_space, action_space, metadata, render_mode) = {
            let env = inner.lock()?;
            (
                env.observation_space().clone(),
                env.action_space().clone(),
                env.metadata().clone(),
                env.render_mode(),
            )
        };
        Ok(Self {
            inner,
            observation_space,
            action_space,
            metadata,
            render_mode,
        })
    }

    /// The shared handle.
    pub fn handle(&self) -> &Arc<ForkAwareMutex<E>> {
        &self.inner
    }

    /// Locks the environment. A panic in an earlier call does not make it unusable (the
    /// poison flag is ignored: every environment method leaves a consistent state or
    /// reports an error).
    ///
    /// # Errors
    /// As [`ForkAwareMutex::lock`].
    pub fn lock(&self) -> Result<ForkAwareGuard<'_, E>> {
        self.inner.lock()
    }
}

impl<E: Env> Clone for SharedEnv<E> {
    fn clone(&self) -> Self {
        Self {
            inner: Arc::clone(&self.inner),
            observation_space: self.observation_space.clone(),
            action_space: self.action_space.clone(),
            metadata: self.metadata.clone(),
            render_mode: self.render_mode,
        }
    }
}

impl<E: Env> std::fmt::Debug for SharedEnv<E> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SharedEnv")
            .field("env", &std::any::type_name::<E>())
            .finish_non_exhaustive()
    }
}

impl<E: Env> Env for SharedEnv<E> {
    type Obs = E::Obs;
    type Act = E::Act;
    type ObsSpace = E::ObsSpace;
    type ActSpace = E::ActSpace;

    fn observation_space(&self) -> &E::ObsSpace {
        &self.observation_space
    }
    fn action_space(&self) -> &E::ActSpace {
        &self.action_space
    }
    fn reset(
        &mut self,
        seed: Option<u64>,
        options: Option<&ResetOptions>,
    ) -> Result<(E::Obs, Info)> {
        self.lock()?.reset(seed, options)
    }
    fn step(&mut self, action: &E::Act) -> Result<Step<E::Obs>> {
        self.lock()?.step(action)
    }
    fn step_into(
        &mut self,
        action: &E::Act,
        observation: &mut E::Obs,
        info: &mut Info,
    ) -> Result<Transition> {
        self.lock()?.step_into(action, observation, info)
    }
    fn metadata(&self) -> &Metadata {
        &self.metadata
    }
    fn render_mode(&self) -> Option<RenderMode> {
        self.render_mode
    }
    fn render(&mut self) -> Result<Option<Frame>> {
        self.lock()?.render()
    }
    fn close(&mut self) {
        if let Ok(mut env) = self.lock() {
            env.close();
        }
    }
    fn rng(&self) -> Option<&EnvRng> {
        None
    }
    fn unwrapped_any(&self) -> &dyn Any {
        self
    }
    fn unwrapped_any_mut(&mut self) -> &mut dyn Any {
        self
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gym_core::spaces::Discrete;

    /// Counts steps; the action is added to the count.
    struct Counter {
        space: Discrete,
        count: i64,
        closed: bool,
    }

    impl Env for Counter {
        type Obs = i64;
        type Act = i64;
        type ObsSpace = Discrete;
        type ActSpace = Discrete;
        fn observation_space(&self) -> &Discrete {
            &self.space
        }
        fn action_space(&self) -> &Discrete {
            &self.space
        }
        fn reset(&mut self, _seed: Option<u64>, _o: Option<&ResetOptions>) -> Result<(i64, Info)> {
            self.count = 0;
            Ok((0, Info::new()))
        }
        fn step(&mut self, a: &i64) -> Result<Step<i64>> {
            self.count += a;
            Ok(Step {
                observation: self.count,
                reward: 1.0,
                terminated: false,
                truncated: false,
                info: Info::new(),
            })
        }
        fn close(&mut self) {
            self.closed = true;
        }
    }

    #[test]
    fn clones_share_one_environment() {
        let mut a = SharedEnv::new(Counter {
            space: Discrete::new(100).unwrap(),
            count: 0,
            closed: false,
        });
        let mut b = a.clone();
        a.reset(None, None).unwrap();
        assert_eq!(a.step(&3).unwrap().observation, 3);
        assert_eq!(b.step(&4).unwrap().observation, 7);
        assert_eq!(a.lock().unwrap().count, 7);
        assert_eq!(a.observation_space(), &Discrete::new(100).unwrap());
        b.close();
        assert!(a.handle().lock().unwrap().closed);
        assert!(gym_core::EnvExt::unwrapped_as::<SharedEnv<Counter>>(&a).is_some());
    }
}
